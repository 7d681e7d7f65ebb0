//! Fuzz loading environment-map storage: arbitrary words, and real storages with arbitrary
//! words written over them; see `fuzz/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../checks.rs"]
mod checks;

fuzz_target!(|data: &[u8]| checks::envmap_storage(data));
