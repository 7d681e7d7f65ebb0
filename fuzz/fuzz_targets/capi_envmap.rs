//! Fuzz the C ABI's environment-map entry points (`wc_envmap_*`, called through their Rust
//! signatures) with storage, sizes, counts and pointers chosen by the fuzzer; see
//! `fuzz/capi_checks.rs`.
#![no_main]
use libfuzzer_sys::fuzz_target;

#[path = "../capi_checks.rs"]
mod capi_checks;

fuzz_target!(|data: &[u8]| capi_checks::capi_envmap(data));
