//! Fuzz the environment-map builders and samplers: arbitrary images, sizes, storage and
//! sample inputs; see `fuzz/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::envmap(data));
