//! Determinism across targets: the hash of every function's output bits over a fixed input
//! set (`registry/src/fingerprint.rs`, driven by the registry's entries) must equal the
//! committed golden values. CI runs this test natively, under wasm32-wasip1 with and without
//! simd128, and the same code runs in the native `fingerprint` binary built with
//! `-C target-cpu=native` and in the wasm32-unknown-unknown cdylib (`tools/wasm-demo.mjs`).
//!
//! Two golden files: `tests/golden/fingerprint.txt`, one value over the functions that
//! existed when it was fixed (the C port and the wasm demo compute it too), and
//! `tests/golden/registry.txt`, one value per function (every entry with bits of its own).
//! When a change is *meant* to alter output bits, regenerate them with `WARPCORE_BLESS=1
//! cargo test -p warpcore-registry --test fingerprint` and say why in the commit.
#![cfg(feature = "all")]

use std::collections::BTreeMap;
use warpcore_registry::fingerprint::{self, Hasher, entry_hash};
use warpcore_registry::{Golden, entries};

fn golden_path(name: &str) -> String {
    format!("{}/../tests/golden/{name}", env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn output_bits_match_the_golden_fingerprint() {
    let golden = include_str!("../../tests/golden/fingerprint.txt").trim();
    let got = format!("{:016x}", fingerprint::fingerprint());
    assert_eq!(
        got, golden,
        "warp output bits changed on this target (or the golden file is stale)"
    );
}

/// The `_x16` forms, hashed in place of the `_x8` ones, give the same golden value: on targets
/// without 16-lane vectors `wide` emulates them, and they must still agree bit for bit.
#[test]
fn x16_forms_match_the_golden_fingerprint() {
    let golden = include_str!("../../tests/golden/fingerprint.txt").trim();
    let got = format!("{:016x}", fingerprint::fingerprint_x16());
    assert_eq!(got, golden, "the _x16 forms give other bits on this target");
}

/// Each entry's own hash, with the `_x8` forms (`x16 = false`) or the `_x16` ones.
fn per_entry(x16: bool) -> BTreeMap<&'static str, String> {
    entries()
        .filter_map(|e| {
            let mut h = if x16 {
                Hasher::new_x16()
            } else {
                Hasher::new()
            };
            entry_hash(e, &mut h).then(|| (e.name, format!("{:016x}", h.finish())))
        })
        .collect()
}

/// One golden hash per function: every entry with bits of its own (all but the accessors and
/// constructors that `Golden::Tests` names), with either lane width.
#[test]
fn every_function_matches_its_golden_hash() {
    let got = per_entry(false);
    let text: String = got.iter().map(|(n, h)| format!("{n} {h}\n")).collect();
    if std::env::var_os("WARPCORE_BLESS").is_some() {
        std::fs::write(golden_path("registry.txt"), &text).unwrap();
    }
    assert!(got.len() >= 45, "only {} entries hashed", got.len());
    let golden = include_str!("../../tests/golden/registry.txt");
    let want: BTreeMap<&str, &str> = golden.lines().filter_map(|l| l.split_once(' ')).collect();
    for (name, hash) in &got {
        assert_eq!(
            want.get(name).copied(),
            Some(hash.as_str()),
            "{name}: output bits changed on this target (or registry.txt lacks it)"
        );
    }
    assert_eq!(
        want.len(),
        got.len(),
        "registry.txt names a function that is gone"
    );
    assert_eq!(
        got,
        per_entry(true),
        "an _x16 form differs from its _x8 form"
    );
}

/// The fingerprint is sensitive: flipping one output bit of one warp changes it.
#[test]
fn fingerprint_detects_a_one_bit_change() {
    use warpcore::disk;
    fn flipped(u: [f32; 2]) -> [f32; 2] {
        let mut p = disk::polar(u);
        if u == [0.25, 0.75] {
            p[0] = f32::from_bits(p[0].to_bits() ^ 1);
        }
        p
    }
    fn flipped_x16(u: [warpcore::f32x16; 2]) -> [warpcore::f32x16; 2] {
        let mut p = disk::polar_x16(u);
        let mut x = p[1].to_array();
        x[13] = f32::from_bits(x[13].to_bits() ^ 1);
        p[1] = warpcore::f32x16::new(x);
        p
    }
    for wide in [false, true] {
        let new = if wide { Hasher::new_x16 } else { Hasher::new };
        let (mut a, mut b) = (new(), new());
        let (x8, x16, slice) = (disk::polar_x8, disk::polar_x16, disk::polar_slice);
        fingerprint::warp(&mut a, disk::polar, x8, x16, slice);
        if wide {
            fingerprint::warp(&mut b, disk::polar, x8, flipped_x16, slice);
        } else {
            fingerprint::warp(&mut b, flipped, x8, x16, slice);
        }
        assert_ne!(a.finish(), b.finish(), "x16 hasher: {wide}");
    }
}

/// The cosine-aware solid-angle maps (`spherical::triangle_cosine`, `rectangle_cosine`, added
/// after the main fingerprint was frozen for C and JS) over the same lights, inputs and lane
/// mixing, with a receiver normal derived from each light's floats (facing, grazing, behind,
/// and NaN/inf for the non-finite lights), hashed one after the other: their golden value
/// from before the registry, which the registry's entries must reproduce.
#[test]
fn cosine_maps_match_their_golden_fingerprint() {
    let mut h = Hasher::new();
    for name in ["spherical::triangle_cosine", "spherical::rectangle_cosine"] {
        let e = entries().find(|e| e.name == name).unwrap();
        assert!(entry_hash(e, &mut h), "{name} has no hash");
    }
    let golden = include_str!("../../tests/golden/fingerprint_cosine.txt").trim();
    assert_eq!(
        format!("{:016x}", h.finish()),
        golden,
        "the cosine-aware maps give other bits on this target"
    );
}

/// How each entry is pinned is consistent: a `With` names an entry that hashes a piece of its
/// own, a `Tests` names a test file that calls the function, and the typed bodies have the
/// forms the entry declares.
#[test]
fn every_entry_is_pinned_somewhere() {
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
    for e in entries() {
        assert!(
            e.kind_matches_forms(),
            "{}: forms and bodies differ",
            e.name
        );
        match e.golden {
            Golden::With(other) => {
                let o = entries()
                    .find(|o| o.name == other)
                    .unwrap_or_else(|| panic!("{}: With({other}) is no entry", e.name));
                assert!(
                    matches!(o.golden, Golden::Piece(_) | Golden::OwnPiece(_)),
                    "{}: {other} hashes no piece that could cover it",
                    e.name
                );
            }
            Golden::Tests(file) => {
                let text = std::fs::read_to_string(format!("{root}/{file}"))
                    .unwrap_or_else(|err| panic!("{}: {file}: {err}", e.name));
                let method = e.name.rsplit("::").next().unwrap();
                assert!(
                    text.contains(&format!("{method}(")) || text.contains(&format!("{method}::<")),
                    "{}: {file} never calls {method}",
                    e.name
                );
            }
            _ => {}
        }
    }
}

/// The inputs and golden hashes as data for the ports that cannot link this crate (the JS
/// tests read `js/test/registry.json` instead of copying the special values and lights):
/// the committed file must be what the registry gives now. `WARPCORE_BLESS=1` rewrites it.
#[test]
fn exported_data_is_current() {
    use warpcore_registry::Lang;
    let bits = |v: &[f32]| {
        v.iter()
            .map(|x| format!("{}", x.to_bits()))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let lights = |ls: &[[f32; 12]]| {
        ls.iter()
            .map(|l| format!("    [{}]", bits(l)))
            .collect::<Vec<_>>()
            .join(",\n")
    };
    let hashes = per_entry(false);
    let mut rows = Vec::new();
    for e in entries() {
        let mut names = Vec::new();
        for lang in [Lang::C, Lang::Js, Lang::Wgsl] {
            e.names_in(lang, |n| names.push(format!("\"{lang:?}:{n}\"")));
        }
        let hash = hashes
            .get(e.name)
            .map_or("null".to_string(), |h| format!("\"{h}\""));
        rows.push(format!(
            "    {{ \"name\": \"{}\", \"hash\": {hash}, \"bindings\": [{}] }}",
            e.name,
            names.join(", ")
        ));
    }
    let [hierarchical, marginal] = real_envmap_hashes(ENVMAP);
    let text = format!(
        "{{\n  \"comment\": \"Generated by registry/tests/fingerprint.rs (WARPCORE_BLESS=1): the fingerprint's inputs as f32 bit patterns and each registry entry's golden hash.\",\n  \"n\": {},\n  \"specials\": [{}],\n  \"triangles\": [\n{}\n  ],\n  \"rectangles\": [\n{}\n  ],\n  \"cones\": [\n{}\n  ],\n  \"envmap\": {{ \"name\": \"{ENVMAP}\", \"hierarchical\": \"{hierarchical:016x}\", \"marginalConditional\": \"{marginal:016x}\" }},\n  \"entries\": [\n{}\n  ]\n}}\n",
        fingerprint::N,
        bits(&fingerprint::SPECIALS),
        lights(&fingerprint::SPHERICAL_TRIANGLES),
        lights(&fingerprint::SPHERICAL_RECTANGLES),
        lights(&fingerprint::SPHERICAL_CONES),
        rows.join(",\n")
    );
    let path = format!("{}/../js/test/registry.json", env!("CARGO_MANIFEST_DIR"));
    if std::env::var_os("WARPCORE_BLESS").is_some() {
        std::fs::write(&path, &text).unwrap();
    }
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        committed == text,
        "js/test/registry.json is stale: run WARPCORE_BLESS=1 cargo test -p warpcore-registry --test fingerprint"
    );
}

/// The real map of the exported data (`tests/data/envmaps/`).
const ENVMAP: &str = "park";

/// Both distributions on a real map (luminance times the rows' solid angle): 4096 pmj02bn
/// points (seed 7), each sample's point, density, the density at its point and its texel.
fn real_envmap_hashes(name: &str) -> [u64; 2] {
    use warpcore::envmap::{Hierarchical, MarginalConditional, image};
    let map = pfm::envmap(name);
    let (w, ht) = (map.width, map.height);
    let mut weights = vec![0.0f32; w * ht];
    image::luminance_slice(&map.rgb, &mut weights);
    image::equirect_solid_angle_weights(&mut weights, w, ht).unwrap();
    let run = |d: &dyn Fn([f32; 2]) -> (warpcore::envmap::Sample, f32)| {
        let mut h = Hasher::new();
        for i in 0..4096 {
            let (s, pdf) = d(warpcore::pmj02bn::sample(i, 7));
            h.floats(&[s.uv[0], s.uv[1], s.pdf, pdf]);
            h.word(s.texel[0]);
            h.word(s.texel[1]);
        }
        h.finish()
    };
    let mut s = vec![0u32; Hierarchical::storage_len(w, ht)];
    let d = Hierarchical::new(&weights, w, ht, &mut s).unwrap();
    let hier = run(&|u| {
        let s = d.sample(u);
        (s, d.pdf(s.uv))
    });
    let mut s = vec![0u32; MarginalConditional::storage_len(w, ht)];
    let d = MarginalConditional::new(&weights, w, ht, &mut s).unwrap();
    let marg = run(&|u| {
        let s = d.sample(u);
        (s, d.pdf(s.uv))
    });
    [hier, marg]
}
