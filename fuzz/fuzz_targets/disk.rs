//! Fuzz the disk warps: any bytes -> any f32 inputs; see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::disk(data));
