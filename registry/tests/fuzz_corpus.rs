//! Replays the checked-in fuzz corpus (`fuzz/corpus/<target>/`) through the same checks the
//! fuzz targets run (`registry/src/checks.rs`), on stable, in every `cargo test`: every input a fuzzing
//! run ever found interesting stays a regression test forever.
#![cfg(feature = "all")]

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

/// Every target's corpus through its check (each target's family is a default feature).
#[test]
fn every_corpus_replays() {
    type Check = fn(&[u8]);
    let targets: [(&str, Check); 14] = [
        ("disk", checks::disk),
        ("pmj02bn", checks::pmj02bn),
        ("triangle", checks::triangle),
        ("spherical", checks::spherical),
        ("sphere", checks::sphere),
        ("envmap", checks::envmap),
        ("envmap_storage", checks::envmap_storage),
        ("sampler", checks::sampler),
        ("lights_alias_build", checks::lights_alias_build),
        ("lights_alias_storage", checks::lights_alias_storage),
        ("lights_tree_build", checks::lights_tree_build),
        ("lights_tree_storage", checks::lights_tree_storage),
        ("microfacet", checks::microfacet),
        ("registry", checks::registry),
    ];
    for (target, check) in targets {
        replay(target, check);
    }
}
