//! Fuzz the C ABI's environment-map entry points (`wc_envmap_*`, called through their Rust
//! signatures: `capi/src/envmap.rs` and its pointer rules `capi/src/ffi.rs` compiled in as
//! modules) with storage, sizes, counts and pointers chosen by the fuzzer; see
//! `capi/fuzz_checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[allow(dead_code)]
#[path = "../../capi/src/ffi.rs"]
mod ffi;

#[path = "../../capi/src/envmap.rs"]
mod envmap;

#[path = "../../capi/fuzz_checks.rs"]
mod capi_checks;

fuzz_target!(|data: &[u8]| capi_checks::capi_envmap(data));
