//! Replays the `capi_envmap` fuzz corpus (or any files or directories given as arguments)
//! through `capi/fuzz_checks.rs`, as `tests/fuzz_corpus.rs` does, in a plain binary: CI builds
//! it with nightly `-Zsanitizer=address` (`--features fuzz-replay`), which a test target
//! cannot do cheaply (it would build the dev-dependencies under the sanitizer too).
#![cfg(feature = "fuzz-replay")]

#[allow(dead_code)]
#[path = "src/ffi.rs"]
mod ffi;

#[path = "src/envmap.rs"]
mod envmap;

#[path = "fuzz_checks.rs"]
mod capi_checks;

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering;

fn main() {
    let mut args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    if args.is_empty() {
        args.push(Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/capi_envmap"));
    }
    let mut files = Vec::new();
    for a in &args {
        if a.is_dir() {
            for e in std::fs::read_dir(a).expect("read the corpus directory") {
                files.push(e.expect("a directory entry").path());
            }
        } else {
            files.push(a.clone());
        }
    }
    files.sort();
    assert!(!files.is_empty(), "no inputs");
    for f in &files {
        capi_checks::capi_envmap(&std::fs::read(f).expect("read an input"));
    }
    println!(
        "capi_envmap: replayed {} inputs, {} C calls",
        files.len(),
        capi_checks::CALLS.load(Ordering::Relaxed)
    );
}
