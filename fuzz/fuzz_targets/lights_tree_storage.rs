//! Fuzz the light tree (lights_tree_storage); see `registry/src/checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::lights_tree_storage(data));
