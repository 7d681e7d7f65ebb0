//! `shaders/warpcore.wgsl` against the crate, bit for bit, on Mesa's software Vulkan driver
//! (lavapipe), and naga's translations of it to SPIR-V, GLSL, HLSL and MSL.
//!
//! Needs lavapipe (Debian/Ubuntu: `apt-get install mesa-vulkan-drivers`); without it the test
//! fails, unless `WARPCORE_GPU_SKIP=1` is set. `spirv-val` (`spirv-tools`) and
//! `glslangValidator` (`glslang-tools`) validate the translations when they are on PATH
//! (`.ci/run` installs them; set `WARPCORE_GPU_REQUIRE_TOOLS=1` to fail without them).
//! `WARPCORE_GPU_RANDOM` sets the number of points of each random class (default 65536).

use std::path::PathBuf;
use warpcore_gpu::testing::{
    assert_bit_identical, compare_changed, lavapipe, library, library_text, translate,
};
use warpcore_gpu::{WGSL, inputs, warps};

/// Every output word of every function equals the crate's, over edge values, grids, random
/// points of each domain and random bit patterns (every f32 class).
#[test]
fn every_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    assert_bit_identical(&gpu, warps(), 0x5eed_0000);
}

/// The comparison is sharp: the sine kernel's leading constant moved by one ulp changes the
/// results of the concentric map (the issue measured 40% of outputs), and a compensation step
/// without its fence is caught too, if the compiler folds it.
#[test]
fn a_one_ulp_change_is_detected() {
    let Some(gpu) = lavapipe() else { return };
    let func = warps()
        .iter()
        .find(|f| f.name == "wc_disk_concentric")
        .unwrap();
    let input = inputs(func.domain, 1 << 12, 7);
    let wrong = WGSL.replace(
        "const WCI_S0: f32 = 0x1.921fb4p-1f;",
        "const WCI_S0: f32 = 0x1.921fb6p-1f;",
    );
    let d = compare_changed(&gpu, func, &wrong, &input);
    println!("S0 + 1 ulp: {} of {} points differ", d.mismatches, d.points);
    assert!(d.mismatches * 10 > d.points, "{d:?}");
    assert!(d.max_ulp >= 0.5 && d.max_abs < 1e-6, "{d:?}");
}

/// The library rules of the file (DESIGN.md, "Shaders"): no bindings, no entry points, no
/// `enable`, no fma/pow/builtin trigonometry, and the contract signatures exactly.
#[test]
fn the_file_is_a_library_with_the_contract_signatures() {
    let banned = [
        "@group",
        "@binding",
        "sin(",
        "cos(",
        "tan(",
        "atan(",
        "atan2(",
        "inverseSqrt(",
        "exp(",
        "log(",
        "floor(",
        "fract(",
    ];
    let signatures = [
        "fn wc_disk_polar(u: vec2<f32>) -> vec2<f32>",
        "fn wc_disk_concentric(u: vec2<f32>) -> vec2<f32>",
        "fn wc_disk_concentric_inverse(p: vec2<f32>) -> vec2<f32>",
        "fn wc_disk_polar4(u: vec2<f32>, quadrant: u32) -> vec2<f32>",
        "fn wc_triangle_uniform(u: vec2<f32>) -> vec3<f32>",
        "fn wc_triangle_basu_owen_permuted(index: u32, seed: u32) -> vec3<f32>",
        "fn wc_sphere_equal_area(u: vec2<f32>) -> vec3<f32>",
        "fn wc_sphere_equal_area_inverse(d: vec3<f32>) -> vec2<f32>",
        "fn wc_sphere_cosine_hemisphere(u: vec2<f32>) -> vec3<f32>",
    ];
    library_text(WGSL, "warpcore.wgsl", &banned, &signatures);
    // Every public function of the file is checked by the harness.
    let public = library(WGSL, 0);
    for name in &public {
        assert!(
            warpcore_gpu::all_functions().any(|f| f.name == *name),
            "{name} is not bound by a registry entry"
        );
    }
    assert_eq!(public.len(), warpcore_gpu::all_functions().count());
}

fn out_dir() -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("warpcore-wgsl");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// naga validates the library and translates it (with an entry point that calls every
/// function) to SPIR-V, GLSL 450, HLSL (SM 5.1) and MSL 1.2; spirv-val and glslangValidator
/// accept the SPIR-V and the GLSL.
#[test]
fn naga_translates_to_spirv_glsl_hlsl_msl() {
    use naga::valid::{Capabilities, ValidationFlags, Validator};
    let validate = |m: &naga::Module| {
        Validator::new(ValidationFlags::all(), Capabilities::empty())
            .validate(m)
            .unwrap_or_else(|e| panic!("naga validation: {e:?}"))
    };
    // The library alone.
    let lib = naga::front::wgsl::parse_str(WGSL).expect("parses");
    let lib_info = validate(&lib);
    let spv =
        naga::back::spv::write_vec(&lib, &lib_info, &Default::default(), None).expect("SPIR-V");
    assert!(spv.len() > 1000);

    let source = warpcore_gpu::all_functions_shader();
    let dir = out_dir();
    let t = translate(&source, "wc_all", &dir, "warpcore");
    let (glsl, hlsl, msl) = (&t.glsl, &t.hlsl, &t.msl);
    for (lang, text) in [("GLSL", glsl), ("HLSL", hlsl), ("MSL", msl)] {
        for f in warpcore_gpu::all_functions() {
            assert!(text.contains(&f.name), "{lang} lacks {}", f.name);
        }
        println!("{lang}: {} bytes", text.len());
    }
    println!(
        "SPIR-V: {} words; written to {}",
        t.spv_words,
        dir.display()
    );
}
