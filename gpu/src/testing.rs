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
