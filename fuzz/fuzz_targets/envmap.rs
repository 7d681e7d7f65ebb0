//! Fuzz the environment-map builders and samplers: arbitrary images, sizes, storage and
//! sample inputs; see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::envmap(data));
