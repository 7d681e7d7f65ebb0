//! Fuzz pmj02bn and the baseline sequences: any (index, seed, count) words; see `fuzz/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::pmj02bn(data));
