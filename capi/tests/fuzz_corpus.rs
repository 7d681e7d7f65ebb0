//! Replays the `capi_envmap` fuzz corpus (`fuzz/corpus/capi_envmap/`) through the checks the
//! fuzz target runs (`capi/fuzz_checks.rs`), on stable, in every `cargo test`: the C ABI's
//! env-map entry points called through their Rust signatures with the storage, sizes, counts
//! and pointers the fuzzer chose, against a model of the documented rules and the safe
//! crate's results. CI also runs it under AddressSanitizer (nightly `-Zsanitizer=address`).
#![cfg(feature = "envmap")]

// The C functions through their Rust signatures: the library's own sources, compiled in
// (the crate has no `rlib`, see Cargo.toml).
#[allow(dead_code)]
#[path = "../src/ffi.rs"]
mod ffi;

#[path = "../src/envmap.rs"]
mod envmap;

#[path = "../fuzz_checks.rs"]
mod capi_checks;

use std::path::Path;
use std::sync::atomic::Ordering;

#[test]
fn capi_envmap_corpus() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/capi_envmap");
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("corpus {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| !p.file_name().unwrap().to_string_lossy().starts_with('.'))
        .collect();
    entries.sort();
    assert!(entries.len() >= 20, "only {} corpus inputs", entries.len());
    for path in &entries {
        capi_checks::capi_envmap(&std::fs::read(path).unwrap());
    }
    let calls = capi_checks::CALLS.load(Ordering::Relaxed);
    eprintln!(
        "capi_envmap: replayed {} corpus inputs, {calls} C calls",
        entries.len()
    );
    assert!(calls as usize >= 2 * entries.len(), "only {calls} calls");
}
