//! `shaders/warpcore_envmap.wgsl` (environment-map sampling from the crate's storage words)
//! against the crate, word for word, on Mesa's lavapipe; and naga's translations. The same
//! environment variables as `tests/lavapipe.rs`.

use warpcore_gpu::compare_words;
use warpcore_gpu::envmaps::{
    ENV_FUNCTIONS, ENVMAP_WGSL, cpu_outputs, env_buffer, env_inputs, run, shader_source,
};
use warpcore_gpu::testing::{lavapipe, library, random_points, translate};

/// Every output word (uv, pdf, texel; pdf lookups) equals the crate's on every test map.
#[test]
fn every_envmap_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    println!(
        "maps: {} storages, {} words",
        env_buffer().1.len(),
        env_buffer().0.len()
    );
    let mut failed = Vec::new();
    for (k, func) in ENV_FUNCTIONS.iter().enumerate() {
        let input = env_inputs(func, random_points(), 0xe0 + k as u64);
        let want = cpu_outputs(func, &input);
        let got = run(&gpu, func, &shader_source(func), &input).unwrap_or_else(|e| panic!("{e}"));
        let d = compare_words(func.out_words(), |w| func.is_integer_output(w), &got, &want);
        println!(
            "{:<40} {:>8} points {:>7} mismatches  max abs {:.3e}  max ulp {:.1}",
            func.name, d.points, d.mismatches, d.max_abs, d.max_ulp
        );
        if let Some(p) = d.first {
            let ow = func.out_words();
            println!(
                "    first mismatch: in {:08x?}\n      gpu {:08x?}\n    crate {:08x?}",
                &input[3 * p..3 * p + 3],
                &got[p * ow..(p + 1) * ow],
                &want[p * ow..(p + 1) * ow]
            );
            failed.push(func.name);
        }
    }
    assert!(failed.is_empty(), "mismatches in {failed:?}");
}

/// The library rules: one binding, no entry point; every public function is checked; the
/// three files parse together.
#[test]
fn the_envmap_file_is_a_library_with_one_binding() {
    let public = library(ENVMAP_WGSL, 1);
    assert_eq!(public.len(), ENV_FUNCTIONS.len(), "{public:?}");
    for name in &public {
        assert!(ENV_FUNCTIONS.iter().any(|f| f.name == name), "{name}");
    }
    let all = format!(
        "{}\n{}\n{}",
        warpcore_gpu::WGSL,
        warpcore_gpu::tables::TABLES_WGSL,
        ENVMAP_WGSL
    );
    naga::front::wgsl::parse_str(&all).expect("the three files parse together");
}

/// The comparison is sharp: a reciprocal multiply instead of the division in the position
/// inside the texel (the freedom WGSL's accuracy rules give real GPUs), or the texel-edge
/// clamp left out, change outputs; and the samples are not degenerate (they reach many texels).
#[test]
fn a_subtle_change_is_detected() {
    let Some(gpu) = lavapipe() else { return };
    let func = ENV_FUNCTIONS[0];
    let input = env_inputs(&func, 1 << 10, 3);
    let want = cpu_outputs(&func, &input);
    let texels: std::collections::HashSet<(u32, u32, u32)> = want
        .chunks_exact(5)
        .zip(input.chunks_exact(3))
        .map(|(o, i)| (i[0], o[3], o[4]))
        .collect();
    println!("{} distinct (map, texel) pairs", texels.len());
    assert!(texels.len() > 500, "{}", texels.len());
    for (what, from, to) in [
        (
            "reciprocal",
            "wcei_unit_interval(wcei_u32_to_f32(w.r.x) / wcei_u32_to_f32(w.len.x))",
            "wcei_unit_interval(wcei_u32_to_f32(w.r.x) * (1.0f / wcei_u32_to_f32(w.len.x)))",
        ),
        (
            "no edge clamp",
            "return wcei_unit_interval(select(x1, hi, hi < x1));",
            "return wcei_unit_interval(x0 + 0.0 * (lo + hi + x1));",
        ),
    ] {
        let wrong = ENVMAP_WGSL.replace(from, to);
        assert_ne!(wrong, ENVMAP_WGSL, "{what}: the text to change is there");
        let source = shader_source(&func).replacen(ENVMAP_WGSL, &wrong, 1);
        let got = run(&gpu, &func, &source, &input).unwrap_or_else(|e| panic!("{e}"));
        let d = compare_words(5, |w| func.is_integer_output(w), &got, &want);
        println!("{what}: {} of {} points differ", d.mismatches, d.points);
        assert!(d.mismatches > 0, "{what}");
    }
}

/// naga validates the file and translates a shader calling every function to SPIR-V (checked
/// by spirv-val when installed), GLSL 450, HLSL and MSL 1.2.
#[test]
fn naga_translates_the_envmap_file() {
    let mut source = String::from(ENVMAP_WGSL);
    source.push_str(
        "\n@group(0) @binding(2) var<storage, read_write> wc_out: array<f32>;\n\
         @compute @workgroup_size(64)\n\
         fn wc_all(@builtin(global_invocation_id) gid: vec3<u32>) {\n\
         \x20   let u = vec2<f32>(f32(gid.x) / 64.0, 0.5);\n\
         \x20   let a = wc_envmap_hierarchical_sample(gid.y, u);\n\
         \x20   let b = wc_envmap_marginal_conditional_sample(gid.y, u);\n\
         \x20   wc_out[gid.x] = a.pdf + b.uv.x + f32(a.texel.x + b.texel.y)\n\
         \x20       + wc_envmap_hierarchical_pdf(gid.y, u) + wc_envmap_marginal_conditional_pdf(gid.y, u);\n\
         }\n",
    );
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("warpcore-wgsl");
    let t = translate(&source, "wc_all", &dir, "warpcore_envmap");
    for (lang, text) in [("GLSL", &t.glsl), ("HLSL", &t.hlsl), ("MSL", &t.msl)] {
        assert!(text.contains("wc_envmap_hierarchical_sample"), "{lang}");
        println!("{lang}: {} bytes", text.len());
    }
}

/// Directions from the three files together: `wc_sphere_equal_area(s.uv)` and
/// `wc_sphere_equal_area_pdf_to_solid_angle(s.pdf)` (warpcore.wgsl) after a hierarchical sample
/// are exactly the crate's `sample_direction(Layout::EqualArea, u)`; `wc_sphere_equirect(s.uv)`
/// is exactly its `Layout::Equirect` direction, and `wc_sphere_equirect_pdf_to_solid_angle(
/// s.pdf, dir)` is exactly the crate's `sphere::equirect_pdf_to_solid_angle` (the form
/// `pdf_direction` uses, a function of the direction), within a stated bound of the density
/// `sample_direction` returns (a function of `v`).
#[test]
fn directions_compose_with_warpcore_wgsl() {
    use warpcore::envmap::{Hierarchical, Layout};
    let Some(gpu) = lavapipe() else { return };
    let func = ENV_FUNCTIONS[0];
    let input = env_inputs(&func, 1 << 10, 9);
    let (buffer, _) = env_buffer();
    let mut source = format!("{}\n{}", warpcore_gpu::WGSL, ENVMAP_WGSL);
    source.push_str(
        "\n@group(0) @binding(2) var<storage, read> wc_in: array<u32>;\n\
         @group(0) @binding(3) var<storage, read_write> wc_out: array<u32>;\n\
         @compute @workgroup_size(64)\n\
         fn wc_check_main(@builtin(global_invocation_id) gid: vec3<u32>) {\n\
         \x20   let i = gid.x;\n\
         \x20   if (i >= arrayLength(&wc_out) / 8u) { return; }\n\
         \x20   let b = i * 3u;\n\
         \x20   let s = wc_envmap_hierarchical_sample(wc_in[b], vec2<f32>(bitcast<f32>(wc_in[b + 1u]), bitcast<f32>(wc_in[b + 2u])));\n\
         \x20   let a = wc_sphere_equal_area(s.uv);\n\
         \x20   let e = wc_sphere_equirect(s.uv);\n\
         \x20   let r = array<f32, 8>(a.x, a.y, a.z, wc_sphere_equal_area_pdf_to_solid_angle(s.pdf),\n\
         \x20       e.x, e.y, e.z, wc_sphere_equirect_pdf_to_solid_angle(s.pdf, e));\n\
         \x20   for (var k = 0u; k < 8u; k++) { wc_out[i * 8u + k] = bitcast<u32>(r[k]); }\n\
         }\n",
    );
    let got = gpu
        .run_bound("directions", &source, &input, 3, 8, &[(1, buffer)], [2, 3])
        .unwrap_or_else(|e| panic!("{e}"));
    let mut want = Vec::with_capacity(got.len());
    let mut by_dir = Vec::new();
    for i in input.chunks_exact(3) {
        let m = Hierarchical::from_storage(&buffer[i[0] as usize..]).unwrap();
        let u = [f32::from_bits(i[1]), f32::from_bits(i[2])];
        for layout in [Layout::EqualArea, Layout::Equirect] {
            let d = m.sample_direction(layout, u);
            want.extend(d.dir.map(f32::to_bits));
            want.push(d.pdf.to_bits());
        }
        // The direction form of the equirect density, as the GPU composes it.
        let s = m.sample(u);
        let dir = warpcore::sphere::equirect(s.uv);
        by_dir.push(warpcore::sphere::equirect_pdf_to_solid_angle(s.pdf, dir).to_bits());
    }
    let dirs = |k: usize| k % 4 != 3;
    let (mut equal_area, mut equirect_dir, mut equirect_pdf, mut worst) = (0, 0, 0, 0f64);
    for (g, w) in got.chunks_exact(8).zip(want.chunks_exact(8)) {
        equal_area += usize::from(g[..4] != w[..4]);
        equirect_dir += usize::from((4..7).any(|k| dirs(k) && g[k] != w[k]));
        if g[7] != w[7] {
            equirect_pdf += 1;
            let (a, b) = (f32::from_bits(g[7]) as f64, f32::from_bits(w[7]) as f64);
            worst = worst.max(if b == 0.0 { a.abs() } else { (a - b).abs() / b });
        }
    }
    let n = got.len() / 8;
    println!(
        "{n} samples: equal-area {equal_area} differ; equirect directions {equirect_dir} differ, \
         densities {equirect_pdf} differ (largest relative difference {worst:.2e})"
    );
    assert_eq!(equal_area, 0);
    assert_eq!(equirect_dir, 0);
    assert!(worst < 1e-5, "{worst}");
    // The composed equirect density is the crate's direction form, bit for bit.
    let exact = got
        .chunks_exact(8)
        .zip(&by_dir)
        .filter(|(g, w)| g[7] == **w)
        .count();
    assert_eq!(
        exact, n,
        "equirect densities equal to sphere::equirect_pdf_to_solid_angle"
    );
}
