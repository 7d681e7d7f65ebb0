//! Fuzz the sampling core: any pattern, root and domain path (domains and splits of any size
//! and sub-sample); see `fuzz/sampler_checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../sampler_checks.rs"]
mod sampler_checks;

fuzz_target!(|data: &[u8]| sampler_checks::sampler(data));
