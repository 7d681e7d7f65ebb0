//! Fuzz the GGX microfacet functions: any bytes -> any directions, roughness and samples;
//! see `registry/src/checks/microfacet.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::microfacet(data));
