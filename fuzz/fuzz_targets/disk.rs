//! Fuzz the disk warps: any bytes -> any f32 inputs; see `fuzz/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::disk(data));
