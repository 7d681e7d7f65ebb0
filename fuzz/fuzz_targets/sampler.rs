//! Fuzz the sampling core: any pattern, root and domain path (domains and splits of any size
//! and sub-sample); see `registry/src/checks/sampler.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::sampler(data));
