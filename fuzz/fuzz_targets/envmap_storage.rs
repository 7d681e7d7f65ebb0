//! Fuzz loading environment-map storage: arbitrary words, and real storages with arbitrary
//! words written over them; see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::envmap_storage(data));
