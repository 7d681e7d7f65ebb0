//! Fuzz pmj02bn and the baseline sequences: any (index, seed, count) words; see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::pmj02bn(data));
