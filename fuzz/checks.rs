//! Domain and width checks shared by the fuzz targets (`fuzz/fuzz_targets/*.rs`) and the
//! stable corpus replay (`tests/fuzz_corpus.rs`): one definition of what "correct on any input"
//! means. Each check reads the fuzzer's bytes as little-endian `f32`/`u32` words, runs every
//! form of the warps and panics on a violation of the promises in DESIGN.md:
//! finite output inside the closed domain, and scalar == x8 == slice bit for bit.
#![allow(dead_code)]

use warpcore::f32x8;

/// The input bytes as 32-bit words (a trailing partial word is zero-padded).
pub fn words(data: &[u8]) -> Vec<u32> {
    data.chunks(4)
        .map(|c| {
            let mut w = [0u8; 4];
            w[..c.len()].copy_from_slice(c);
            u32::from_le_bytes(w)
        })
        .collect()
}

fn same<const N: usize>(a: [f32; N], b: [f32; N]) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Points of `D` coordinates from the words, padded to a multiple of 8 points.
pub fn points<const D: usize>(w: &[u32]) -> Vec<[f32; D]> {
    let n = w.len().div_ceil(D).div_ceil(8).max(1) * 8;
    (0..n)
        .map(|i| std::array::from_fn(|d| f32::from_bits(w.get(i * D + d).copied().unwrap_or(0))))
        .collect()
}

/// Runs the scalar, x8 and slice forms of a warp over `pts`; checks they agree and that every
/// output satisfies `valid`.
pub fn widths<const I: usize, const O: usize>(
    name: &str,
    pts: &[[f32; I]],
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
    valid: impl Fn([f32; O]) -> bool,
) {
    let mut out = vec![[0.0f32; O]; pts.len()];
    assert_eq!(slice(pts, &mut out), pts.len());
    for (g, group) in pts.chunks_exact(8).enumerate() {
        let v: [f32x8; I] =
            std::array::from_fn(|d| f32x8::new(std::array::from_fn(|j| group[j][d])));
        let r = x8(v);
        for (j, u) in group.iter().enumerate() {
            let s = scalar(*u);
            let lane: [f32; O] = std::array::from_fn(|k| r[k].to_array()[j]);
            assert!(valid(s), "{name}: {u:?} -> {s:?} outside the domain");
            assert!(
                same(s, lane),
                "{name}: scalar {s:?} != x8 {lane:?} for {u:?}"
            );
            assert!(same(s, out[g * 8 + j]), "{name}: scalar != slice for {u:?}");
        }
    }
}

fn in_disk(p: [f32; 2]) -> bool {
    p.iter().all(|c| c.is_finite()) && (p[0] as f64).powi(2) + (p[1] as f64).powi(2) <= 1.0
}

fn in_unit_square(u: [f32; 2]) -> bool {
    u.iter().all(|c| (0.0..1.0).contains(c))
}

/// Every disk warp, its inverse and the polar4 helpers.
#[cfg(feature = "disk")]
pub fn disk(data: &[u8]) {
    use warpcore::disk;
    let w = words(data);
    let pts = points::<2>(&w);
    widths(
        "polar",
        &pts,
        disk::polar,
        disk::polar_x8,
        disk::polar_slice,
        in_disk,
    );
    widths(
        "concentric",
        &pts,
        disk::concentric,
        disk::concentric_x8,
        disk::concentric_slice,
        in_disk,
    );
    widths(
        "polar_inverse",
        &pts,
        disk::polar_inverse,
        disk::polar_inverse_x8,
        disk::polar_inverse_slice,
        in_unit_square,
    );
    widths(
        "concentric_inverse",
        &pts,
        disk::concentric_inverse,
        disk::concentric_inverse_x8,
        disk::concentric_inverse_slice,
        in_unit_square,
    );
    let q = w.first().copied().unwrap_or(0);
    let quads = warpcore::u32x8::new(std::array::from_fn(|j| q.wrapping_add(j as u32)));
    for (g, group) in pts.chunks_exact(8).enumerate() {
        let v: [f32x8; 2] =
            std::array::from_fn(|d| f32x8::new(std::array::from_fn(|j| group[j][d])));
        let r = disk::polar4_x8(v, quads);
        for (j, u) in group.iter().enumerate() {
            let s = disk::polar4(*u, q.wrapping_add(j as u32));
            assert!(
                in_disk(s) && same(s, [r[0].to_array()[j], r[1].to_array()[j]]),
                "polar4 {u:?}"
            );
            let (back, quadrant) = disk::polar4_inverse(*u);
            assert!(in_unit_square(back) && quadrant < 4, "polar4_inverse {u:?}");
        }
        let mut out = vec![[0.0f32; 2]; (g % 5) * 7];
        let n = disk::polar4_slice(group, &mut out);
        assert_eq!(n, out.len().min(32));
        for (i, p) in out.iter().enumerate() {
            assert!(
                same(*p, disk::polar4(group[i / 4], i as u32 % 4)),
                "polar4_slice {i}"
            );
        }
    }
}
