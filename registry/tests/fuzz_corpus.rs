//! Replays the checked-in fuzz corpus (`fuzz/corpus/<target>/`) through the same checks the
//! fuzz targets run (`registry/src/checks.rs`), on stable, in every `cargo test`: every input a fuzzing
//! run ever found interesting stays a regression test forever.
#![cfg(feature = "disk")]

use warpcore_registry::checks;

use std::path::Path;

fn replay(target: &str, check: fn(&[u8])) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz/corpus")
        .join(target);
    let mut entries: Vec<_> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("corpus {}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    assert!(!entries.is_empty(), "empty corpus for {target}");
    for path in &entries {
        check(&std::fs::read(path).unwrap());
    }
    eprintln!("{target}: replayed {} corpus inputs", entries.len());
}

#[test]
fn disk_corpus() {
    replay("disk", checks::disk);
}

#[cfg(all(feature = "pmj02bn", feature = "sequence"))]
#[test]
fn pmj02bn_corpus() {
    replay("pmj02bn", checks::pmj02bn);
}

#[cfg(feature = "triangle")]
#[test]
fn triangle_corpus() {
    replay("triangle", checks::triangle);
}

#[cfg(feature = "spherical")]
#[test]
fn spherical_corpus() {
    replay("spherical", checks::spherical);
}

#[cfg(feature = "sphere")]
#[test]
fn sphere_corpus() {
    replay("sphere", checks::sphere);
}

#[cfg(feature = "envmap")]
#[test]
fn envmap_corpus() {
    replay("envmap", checks::envmap);
}

#[cfg(feature = "envmap")]
#[test]
fn envmap_storage_corpus() {
    replay("envmap_storage", checks::envmap_storage);
}

#[cfg(feature = "sampler")]
#[test]
fn sampler_corpus() {
    replay("sampler", checks::sampler);
}
