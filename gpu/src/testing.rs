//! What the lavapipe test files share: the adapter (or a clear failure), the random point
//! count, and whether an external validator is on PATH.

use crate::Gpu;
use std::process::Command;

/// Mesa's lavapipe, or `None` with a note when `WARPCORE_GPU_SKIP=1`; otherwise a missing
/// adapter fails the test with the install hint.
pub fn lavapipe() -> Option<Gpu> {
    match Gpu::lavapipe() {
        Ok(gpu) => Some(gpu),
        Err(e) if std::env::var("WARPCORE_GPU_SKIP").is_ok_and(|v| v == "1") => {
            eprintln!("SKIPPED (WARPCORE_GPU_SKIP=1): {e}");
            None
        }
        Err(e) => panic!("{e} (set WARPCORE_GPU_SKIP=1 to skip this test)"),
    }
}

/// Random points per function: `WARPCORE_GPU_RANDOM`, default `2^16`.
pub fn random_points() -> usize {
    std::env::var("WARPCORE_GPU_RANDOM")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1 << 16)
}

/// Whether `name` runs; when it does not and `WARPCORE_GPU_REQUIRE_TOOLS=1` (CI), panics.
pub fn tool(name: &str) -> bool {
    let found = Command::new(name).arg("--version").output().is_ok();
    if !found {
        assert!(
            !std::env::var("WARPCORE_GPU_REQUIRE_TOOLS").is_ok_and(|v| v == "1"),
            "{name} not found on PATH (WARPCORE_GPU_REQUIRE_TOOLS=1)"
        );
        println!("SKIPPED the {name} validation: not on PATH");
    }
    found
}

/// `func` on `gpu` with `wrong` (a changed copy of `shaders/warpcore.wgsl`) as its library,
/// compared with the crate on `input`.
pub fn compare_changed(gpu: &Gpu, func: &crate::Func, wrong: &str, input: &[u32]) -> crate::Diff {
    assert_ne!(
        wrong,
        crate::WGSL,
        "the text to change is where the test expects it"
    );
    let source = Gpu::shader_source(func).replacen(crate::WGSL, wrong, 1);
    let got = gpu
        .run_source(func, &source, input)
        .unwrap_or_else(|e| panic!("{e}"));
    crate::compare(func, &got, &crate::cpu_outputs(func, input))
}

/// The names of the public (`wc_`) functions of a WGSL library file, parsed by naga
/// (panicking with naga's message) and checked for the rules every library keeps: no entry
/// point, `bindings` module-scope variables (its bindings).
pub fn library(source: &str, bindings: usize) -> Vec<String> {
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    assert!(module.entry_points.is_empty(), "an entry point");
    assert_eq!(module.global_variables.len(), bindings, "bindings");
    module
        .functions
        .iter()
        .filter_map(|(_, f)| f.name.clone())
        .filter(|n| n.starts_with("wc_"))
        .collect()
}

/// What no WGSL library file uses: entry points, `enable`, and `fma` and `pow` (whose results
/// differ between devices).
pub const NOT_IN_A_LIBRARY: &[&str] = &[
    "@compute",
    "@vertex",
    "@fragment",
    "enable ",
    "fma(",
    "pow(",
];

/// The text rules of a WGSL library file `file`: its code (`source` without its `//`
/// comments, which it returns) uses none of [`NOT_IN_A_LIBRARY`] and `banned`, and has each of
/// `signatures` exactly.
pub fn library_text(source: &str, file: &str, banned: &[&str], signatures: &[&str]) -> String {
    let code = source
        .lines()
        .map(|l| l.split("//").next().unwrap_or(""))
        .collect::<Vec<_>>()
        .join("\n");
    for b in NOT_IN_A_LIBRARY.iter().chain(banned) {
        assert!(!code.contains(b), "{file} uses {b:?}");
    }
    for sig in signatures {
        assert!(code.contains(sig), "{file} lacks the signature {sig}");
    }
    code
}

/// naga's translations of one compute shader, as written to disk and validated.
pub struct Translations {
    /// SPIR-V words.
    pub spv_words: usize,
    pub glsl: String,
    pub hlsl: String,
    pub msl: String,
}

/// Parses and validates `source` with naga (panicking with naga's message), translates its
/// compute entry point `entry` to SPIR-V, GLSL 450, HLSL and MSL 1.2 (`reverseBits` needs
/// 1.2), writes them as `dir/stem.{spv,comp,hlsl,metal}`, and has `spirv-val` (Vulkan 1.0)
/// and `glslangValidator` accept the SPIR-V and the GLSL when they are on PATH ([`tool`]).
pub fn translate(source: &str, entry: &str, dir: &std::path::Path, stem: &str) -> Translations {
    use naga::valid::{Capabilities, ValidationFlags, Validator};
    let module = naga::front::wgsl::parse_str(source)
        .unwrap_or_else(|e| panic!("{}", e.emit_to_string(source)));
    let info = Validator::new(ValidationFlags::all(), Capabilities::empty())
        .validate(&module)
        .unwrap_or_else(|e| panic!("naga validation: {e:?}"));
    let ep = entry.to_string();
    std::fs::create_dir_all(dir).unwrap();
    let spv = naga::back::spv::write_vec(
        &module,
        &info,
        &Default::default(),
        Some(&naga::back::spv::PipelineOptions {
            shader_stage: naga::ShaderStage::Compute,
            entry_point: ep.clone(),
        }),
    )
    .expect("SPIR-V");
    let spv_path = dir.join(format!("{stem}.spv"));
    let bytes: Vec<u8> = spv.iter().flat_map(|w| w.to_le_bytes()).collect();
    std::fs::write(&spv_path, bytes).unwrap();
    let mut glsl = String::new();
    naga::back::glsl::Writer::new(
        &mut glsl,
        &module,
        &info,
        &naga::back::glsl::Options {
            version: naga::back::glsl::Version::Desktop(450),
            ..Default::default()
        },
        &naga::back::glsl::PipelineOptions {
            shader_stage: naga::ShaderStage::Compute,
            entry_point: ep.clone(),
            multiview: None,
        },
        Default::default(),
    )
    .expect("GLSL writer")
    .write()
    .expect("GLSL");
    let glsl_path = dir.join(format!("{stem}.comp"));
    std::fs::write(&glsl_path, &glsl).unwrap();
    let mut hlsl = String::new();
    naga::back::hlsl::Writer::new(
        &mut hlsl,
        &Default::default(),
        &naga::back::hlsl::PipelineOptions {
            entry_point: Some((naga::ShaderStage::Compute, ep.clone())),
        },
    )
    .write(&module, &info, None)
    .expect("HLSL");
    std::fs::write(dir.join(format!("{stem}.hlsl")), &hlsl).unwrap();
    let (msl, _) = naga::back::msl::write_string(
        &module,
        &info,
        &naga::back::msl::Options {
            lang_version: (1, 2),
            ..Default::default()
        },
        &naga::back::msl::PipelineOptions {
            entry_point: Some((naga::ShaderStage::Compute, ep)),
            ..Default::default()
        },
    )
    .expect("MSL");
    std::fs::write(dir.join(format!("{stem}.metal")), &msl).unwrap();
    for (name, args, path) in [
        ("spirv-val", &["--target-env", "vulkan1.0"][..], &spv_path),
        ("glslangValidator", &[][..], &glsl_path),
    ] {
        if tool(name) {
            let out = Command::new(name).args(args).arg(path).output().unwrap();
            assert!(
                out.status.success(),
                "{name} on {}: {}{}",
                path.display(),
                String::from_utf8_lossy(&out.stdout),
                String::from_utf8_lossy(&out.stderr)
            );
            println!("{name}: {stem} ok");
        }
    }
    Translations {
        spv_words: spv.len(),
        glsl,
        hlsl,
        msl,
    }
}

/// The bit-identity proof over `funcs`: edge values, grids, random points of each domain and
/// random bit patterns ([`crate::inputs`], [`random_points`] of them, seeds from `seed`) run
/// on `gpu` and compared word for word with the crate. Prints a table (points, mismatches,
/// largest absolute and ulp difference) and the first mismatch of each function; panics when
/// any word differs, or when the crate itself returned NaN (the domain rule).
pub fn assert_bit_identical(gpu: &Gpu, funcs: &[crate::Func], seed: u64) {
    println!(
        "adapter: {} ({:?}, {} {})",
        gpu.info.name, gpu.info.device_type, gpu.info.driver, gpu.info.driver_info
    );
    println!(
        "{:<42} {:>9} {:>10} {:>12} {:>8}",
        "function", "points", "mismatches", "max abs", "max ulp"
    );
    let show = |w: &[u32]| {
        w.iter()
            .map(|x| format!("{:#010x} ({:e})", x, f32::from_bits(*x)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut failed = Vec::new();
    let mut total = 0;
    for (k, func) in funcs.iter().enumerate() {
        let input = crate::inputs(func.domain, random_points(), seed + k as u64);
        let want = crate::cpu_outputs(func, &input);
        let got = gpu.run(func, &input).unwrap_or_else(|e| panic!("{e}"));
        let d = crate::compare(func, &got, &want);
        total += d.points;
        println!(
            "{:<42} {:>9} {:>10} {:>12.3e} {:>8.1}",
            func.name, d.points, d.mismatches, d.max_abs, d.max_ulp
        );
        let (inw, outw) = (func.in_words(), func.out_words());
        if let Some(p) = d.first {
            println!(
                "    first mismatch: in [{}]\n      gpu [{}]\n    crate [{}]",
                show(&input[p * inw..(p + 1) * inw]),
                show(&got[p * outw..(p + 1) * outw]),
                show(&want[p * outw..(p + 1) * outw])
            );
            failed.push(func.name.as_str());
        }
        // A sanity check of the comparison itself: the outputs are never NaN (the domain rule).
        assert!(
            (0..d.points).all(|p| {
                (0..outw).all(|w| {
                    func.is_integer_output(w) || !f32::from_bits(want[p * outw + w]).is_nan()
                })
            }),
            "{}: the crate returned NaN",
            func.name
        );
    }
    println!("{} functions, {total} points", funcs.len());
    assert!(failed.is_empty(), "mismatches in {failed:?}");
}
