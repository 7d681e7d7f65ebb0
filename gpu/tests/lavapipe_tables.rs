//! `shaders/warpcore_tables.wgsl` (pmj02bn and the sampling core) against the crate, word for
//! word, on Mesa's software Vulkan driver (lavapipe), and naga's translations of it to SPIR-V,
//! GLSL, HLSL and MSL. The same environment variables as `tests/lavapipe.rs`
//! (`WARPCORE_GPU_SKIP`, `WARPCORE_GPU_REQUIRE_TOOLS`, `WARPCORE_GPU_RANDOM`).

use warpcore_gpu::tables::{
    TABLE_FUNCTIONS, TABLES_WGSL, TableFunc, cpu_outputs, run, run_source, shader_source,
    shader_source_with, table_inputs, table_words,
};
use warpcore_gpu::testing::{lavapipe, library, library_text, random_points, translate};
use warpcore_gpu::{Gpu, all_shader, compare_words};

/// Every output word (states, fixed-point draws, float draws, roulette values) equals the
/// crate's, for every pattern, over whole table blocks, edge values of every argument
/// (index 0 and 2^32 - 1, seed 0, split sizes 0 to 2^32 - 1, pixels past 2^16) and random
/// words.
#[test]
fn every_table_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    println!(
        "adapter: {} ({:?}, {} {})",
        gpu.info.name, gpu.info.device_type, gpu.info.driver, gpu.info.driver_info
    );
    let tables = table_words();
    let mut failed = Vec::new();
    let mut total = 0;
    for (k, func) in TABLE_FUNCTIONS.iter().enumerate() {
        let input = table_inputs(func.domain, random_points(), 0x7ab1_0000 + k as u64);
        let want = cpu_outputs(func, &input);
        let got = run(&gpu, func, &input, &tables).unwrap_or_else(|e| panic!("{e}"));
        let d = compare_words(func.out_words, |_| true, &got, &want);
        total += d.points;
        println!(
            "{:<32} {:>9} points {:>8} mismatches",
            func.name, d.points, d.mismatches
        );
        if let Some(p) = d.first {
            println!(
                "    first mismatch: in {:08x?}\n      gpu {:08x?}\n    crate {:08x?}",
                &input[p * func.in_words..(p + 1) * func.in_words],
                &got[p * func.out_words..(p + 1) * func.out_words],
                &want[p * func.out_words..(p + 1) * func.out_words]
            );
            failed.push(func.name);
        }
    }
    println!("{} checks, {total} points", TABLE_FUNCTIONS.len());
    assert!(failed.is_empty(), "mismatches in {failed:?}");
}

fn mismatches(gpu: &Gpu, func: &TableFunc, source: &str, tables: &[u32], n: usize) -> usize {
    let input = table_inputs(func.domain, n, 11);
    let want = cpu_outputs(func, &input);
    let got = run_source(gpu, func, source, &input, tables).unwrap_or_else(|e| panic!("{e}"));
    compare_words(func.out_words, |_| true, &got, &want).mismatches
}

/// The comparison is sharp: a table of another build (one set instead of four), one flipped
/// word of the Sobol' rows, and a wrong blue-noise tile size are each caught.
#[test]
fn a_wrong_table_or_layout_is_detected() {
    let Some(gpu) = lavapipe() else { return };
    let tables = table_words();
    let find = |name: &str| *TABLE_FUNCTIONS.iter().find(|f| f.name == name).unwrap();
    let pmj = find("wc_pmj02bn_sample");
    let sobol = find("wc_sampler_* Sobol");
    let blue = find("wc_sampler_* Blue<Pmj02bn>");
    assert_eq!(
        mismatches(&gpu, &pmj, &shader_source(&pmj), &tables, 1 << 12),
        0
    );

    for (what, func, from, to) in [
        (
            "one set",
            &pmj,
            "const WC_PMJ02BN_SETS: u32 = 4u;",
            "const WC_PMJ02BN_SETS: u32 = 1u;",
        ),
        (
            "32 x 32 tile",
            &blue,
            "const WC_BLUE_TILE: u32 = 64u;",
            "const WC_BLUE_TILE: u32 = 32u;",
        ),
    ] {
        let wrong = TABLES_WGSL.replace(from, to);
        assert_ne!(wrong, TABLES_WGSL, "{what}: the text to change is there");
        let source = shader_source_with(func, &wrong);
        let n = mismatches(&gpu, func, &source, &tables, 1 << 12);
        println!("{what}: {n} mismatches");
        assert!(n > 1000, "{what}: {n}");
    }

    let mut flipped = tables.clone();
    let row = warpcore_gpu::tables::PMJ02BN_WORDS + 4 * (256 * 3 + 0x80) + 2;
    flipped[row] ^= 1;
    let n = mismatches(&gpu, &sobol, &shader_source(&sobol), &flipped, 1 << 12);
    println!("one Sobol' bit flipped: {n} mismatches");
    assert!(n > 10, "{n}");
}

/// The library rules: one binding (the tables), no entry points, no `enable`, no floating-
/// point arithmetic besides the exact conversion; every public function is checked.
#[test]
fn the_tables_file_is_a_library_with_one_binding() {
    let signatures = [
        "fn wc_pmj02bn_sample(index: u32, seed: u32) -> vec2<f32>",
        "fn wc_sampler_new(pattern: u32, pixel: vec2<u32>, frame: u32, index: u32, seed: u32) -> WcSampler",
        "fn wc_sampler_new_frame(pattern: u32, pixel: vec2<u32>, frame: u32, spp: u32, index: u32, seed: u32) -> WcSampler",
        "fn wc_sampler_domain(s: WcSampler, key: u32) -> WcSampler",
        "fn wc_sampler_split(s: WcSampler, key: u32, size: u32, sub: u32) -> WcSampler",
        "fn wc_sampler_draw2(s: WcSampler) -> vec2<f32>",
        "fn wc_sampler_draw4(s: WcSampler) -> vec4<f32>",
    ];
    let code = library_text(TABLES_WGSL, "warpcore_tables.wgsl", &[], &signatures);
    assert_eq!(code.matches("@group").count(), 1);
    assert_eq!(code.matches("@binding").count(), 1);
    assert!(code.contains("@group(0) @binding(0) var<storage, read> wc_tables: array<u32>;"));
    let public = library(TABLES_WGSL, 1);
    for name in &public {
        assert!(
            TABLE_FUNCTIONS
                .iter()
                .any(|f| f.covers.contains(&name.as_str())),
            "{name} is not checked by TABLE_FUNCTIONS"
        );
    }
    assert_eq!(public.len(), 10, "{public:?}");
    // The two files together: no name is shared.
    let both = format!("{}\n{}", warpcore_gpu::WGSL, TABLES_WGSL);
    naga::front::wgsl::parse_str(&both).expect("warpcore.wgsl + warpcore_tables.wgsl parse");
}

/// naga validates the file and translates a shader that calls every check's body to SPIR-V,
/// GLSL 450, HLSL and MSL 1.2; spirv-val and glslangValidator accept the SPIR-V and the GLSL.
#[test]
fn naga_translates_the_tables_file() {
    let bodies = TABLE_FUNCTIONS.iter().take(3).map(|f| {
        format!(
            "    let b = i * {}u;\n    let o = i * {}u;\n{}",
            f.in_words,
            f.out_words,
            (f.wgsl)()
        )
    });
    let source = all_shader(TABLES_WGSL, [1, 2], bodies);
    let dir = std::path::PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("warpcore-wgsl");
    let t = translate(&source, "wc_all", &dir, "warpcore_tables");
    for (lang, text) in [("GLSL", &t.glsl), ("HLSL", &t.hlsl), ("MSL", &t.msl)] {
        for name in ["wc_pmj02bn_sample", "wc_sampler_draw4", "wc_sampler_split"] {
            assert!(text.contains(name), "{lang} lacks {name}");
        }
        println!("{lang}: {} bytes", text.len());
    }
}
