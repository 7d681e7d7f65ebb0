//! Fuzz the solid-angle light maps: any bytes -> any light, point and samples; see
//! `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::spherical(data));
