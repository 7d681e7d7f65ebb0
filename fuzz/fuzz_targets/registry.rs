//! Fuzz every registry entry with typed bodies: lane and slice forms against the scalar form,
//! and the domain rule on every output; see `registry/src/checks.rs` (`registry`).
#![no_main]
use libfuzzer_sys::fuzz_target;

use warpcore_registry::checks;

fuzz_target!(|data: &[u8]| checks::registry(data));
