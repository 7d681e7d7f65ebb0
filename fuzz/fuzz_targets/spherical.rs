//! Fuzz the solid-angle light maps: any bytes -> any light, point and samples; see
//! `fuzz/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::spherical(data));
