//! The WGSL source evaluated on the CPU (naga's IR, interpreted in IEEE `f32`) equals the
//! crate bit for bit: a check of the transcription that needs no GPU. See `src/model.rs`.

use warpcore_gpu::model::{Deviations, deviation};
use warpcore_gpu::{FUNCTIONS, WGSL, inputs};

#[test]
fn interpreted_wgsl_equals_the_crate() {
    let module = naga::front::wgsl::parse_str(WGSL).expect("parses");
    let mut failed = Vec::new();
    for (k, func) in FUNCTIONS.iter().enumerate() {
        let input = inputs(func.domain, 1 << 10, 0xface + k as u64);
        let d = deviation(&module, func, &input, Deviations::NONE, 1, 1);
        println!(
            "{:<42} {:>8} points, {} mismatches",
            func.name, d.points, d.mismatches
        );
        if d.mismatches > 0 {
            failed.push(func.name);
        }
    }
    assert!(failed.is_empty(), "{failed:?}");
}

/// The interpreter is not blind: a WGSL-allowed division error moves some outputs.
#[test]
fn the_model_moves_results() {
    let module = naga::front::wgsl::parse_str(WGSL).expect("parses");
    let func = FUNCTIONS
        .iter()
        .find(|f| f.name == "wc_disk_concentric")
        .unwrap();
    let input = inputs(func.domain, 1 << 8, 3);
    let d = deviation(&module, func, &input, Deviations::WGSL, 1, 9);
    println!("{d:?}");
    assert!(d.mismatches > 0 && d.max_abs < 1e-5, "{d:?}");
}
