//! Determinism across targets: the hash of every warp's output bits over a fixed input set
//! (`registry/src/fingerprint.rs`) must equal the committed golden value. CI runs this
//! test natively, under wasm32-wasip1 with and without simd128, and the same code runs in the
//! native `fingerprint` binary built with `-C target-cpu=native` and in the wasm32-unknown-unknown
//! cdylib (`tools/wasm-demo.mjs`) — one golden file for all of them.
//!
//! The golden value covers the default feature set; when a change is *meant* to alter output
//! bits, regenerate it with `cargo run --release -p warpcore-demo
//! --bin fingerprint > tests/golden/fingerprint.txt` and say why in the commit.
#![cfg(all(
    feature = "disk",
    feature = "triangle",
    feature = "sphere",
    feature = "pmj02bn",
    feature = "sequence",
    feature = "envmap",
    feature = "spherical"
))]

use warpcore_registry::fingerprint;

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

/// The fingerprint is sensitive: flipping one output bit of one warp changes it.
#[test]
fn fingerprint_detects_a_one_bit_change() {
    let mut a = fingerprint::Hasher::new();
    let mut b = fingerprint::Hasher::new();
    fingerprint::warp(
        &mut a,
        warpcore::disk::polar,
        warpcore::disk::polar_x8,
        warpcore::disk::polar_x16,
        warpcore::disk::polar_slice,
    );
    fingerprint::warp(
        &mut b,
        |u| {
            let mut p = warpcore::disk::polar(u);
            if u == [0.25, 0.75] {
                p[0] = f32::from_bits(p[0].to_bits() ^ 1);
            }
            p
        },
        warpcore::disk::polar_x8,
        warpcore::disk::polar_x16,
        warpcore::disk::polar_slice,
    );
    assert_ne!(a.finish(), b.finish());
    // And so is the x16 variant: a one-bit change in one lane of the 16-wide form.
    let mut a = fingerprint::Hasher::new_x16();
    let mut b = fingerprint::Hasher::new_x16();
    let polar = |h: &mut fingerprint::Hasher, flip: bool| {
        fingerprint::warp(
            h,
            warpcore::disk::polar,
            warpcore::disk::polar_x8,
            |u| {
                let mut p = warpcore::disk::polar_x16(u);
                if flip {
                    let mut x = p[1].to_array();
                    x[13] = f32::from_bits(x[13].to_bits() ^ 1);
                    p[1] = warpcore::f32x16::new(x);
                }
                p
            },
            warpcore::disk::polar_slice,
        );
    };
    polar(&mut a, false);
    polar(&mut b, true);
    assert_ne!(a.finish(), b.finish());
}

/// The cosine-aware solid-angle maps (`spherical::triangle_cosine`, `rectangle_cosine`, added
/// after the main fingerprint was frozen for C and JS) over the same lights, inputs and lane
/// mixing, with a receiver normal derived from each light's floats (facing, grazing, behind,
/// and NaN/inf for the non-finite lights), against their own golden value: the same on every
/// target this test runs on (native, `-C target-cpu=native`, wasm32 with and without
/// simd128). Regenerate with `WARPCORE_BLESS=1` when a change is meant to alter these bits.
#[cfg(feature = "spherical")]
#[test]
fn cosine_maps_match_their_golden_fingerprint() {
    use fingerprint::{Hasher, SPHERICAL_RECTANGLES, SPHERICAL_TRIANGLES, lights};
    use warpcore::spherical as sp;
    use warpcore::{f32x8, f32x16};
    let n1 = |l: [[f32; 3]; 4]| [l[0][1] - l[3][1] + 0.3, 0.5 - l[2][0], 0.7 - l[1][2] * 0.5];
    let n8 = |l: [[f32x8; 3]; 4]| {
        [
            l[0][1] - l[3][1] + f32x8::splat(0.3),
            f32x8::splat(0.5) - l[2][0],
            f32x8::splat(0.7) - l[1][2] * f32x8::splat(0.5),
        ]
    };
    let n16 = |l: [[f32x16; 3]; 4]| {
        [
            l[0][1] - l[3][1] + f32x16::splat(0.3),
            f32x16::splat(0.5) - l[2][0],
            f32x16::splat(0.7) - l[1][2] * f32x16::splat(0.5),
        ]
    };
    let mut h = Hasher::new();
    lights(
        &mut h,
        &SPHERICAL_TRIANGLES,
        |l, u| {
            let (b, d) = sp::triangle_cosine([l[0], l[1], l[2]], l[3], n1(l), u);
            [b[0], b[1], b[2], d]
        },
        |l, u| {
            let (b, d) = sp::triangle_cosine_x8([l[0], l[1], l[2]], l[3], n8(l), u);
            [b[0], b[1], b[2], d]
        },
        |l, u| {
            let (b, d) = sp::triangle_cosine_x16([l[0], l[1], l[2]], l[3], n16(l), u);
            [b[0], b[1], b[2], d]
        },
        |l, u, o| sp::triangle_cosine_slice([l[0], l[1], l[2]], l[3], n1(l), u, o),
    );
    lights(
        &mut h,
        &SPHERICAL_RECTANGLES,
        |l, u| {
            let (st, d) = sp::rectangle_cosine(l[0], l[1], l[2], l[3], n1(l), u);
            [st[0], st[1], d]
        },
        |l, u| {
            let (st, d) = sp::rectangle_cosine_x8(l[0], l[1], l[2], l[3], n8(l), u);
            [st[0], st[1], d]
        },
        |l, u| {
            let (st, d) = sp::rectangle_cosine_x16(l[0], l[1], l[2], l[3], n16(l), u);
            [st[0], st[1], d]
        },
        |l, u, o| sp::rectangle_cosine_slice(l[0], l[1], l[2], l[3], n1(l), u, o),
    );
    let got = format!("{:016x}", h.finish());
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../tests/golden/fingerprint_cosine.txt"
    );
    if std::env::var_os("WARPCORE_BLESS").is_some() {
        std::fs::write(path, format!("{got}\n")).unwrap();
    }
    let golden = include_str!("../../tests/golden/fingerprint_cosine.txt").trim();
    assert_eq!(
        got, golden,
        "the cosine-aware maps give other bits on this target"
    );
}
