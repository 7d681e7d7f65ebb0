//! Fuzz the sphere warps: any bytes -> any inputs; see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::sphere(data));
