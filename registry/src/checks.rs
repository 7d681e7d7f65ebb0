//! Domain and width checks shared by the fuzz targets (`fuzz/fuzz_targets/*.rs`) and the
//! stable corpus replay (`registry/tests/fuzz_corpus.rs`): one definition of what "correct on any input"
//! means. Each check reads the fuzzer's bytes as little-endian `f32`/`u32` words, runs every
//! form of the warps and panics on a violation of the promises in DESIGN.md:
//! finite output inside the closed domain, and scalar == x8 == slice bit for bit.
#[allow(unused_imports)]
use std::prelude::rust_2024::*;
#[allow(unused_imports)]
use std::{format, vec};
use warpcore::f32x8;

#[cfg(feature = "microfacet")]
mod microfacet;
#[cfg(feature = "microfacet")]
pub use microfacet::microfacet;
#[cfg(feature = "sampler")]
mod sampler;
#[cfg(feature = "sampler")]
pub use sampler::sampler;

/// Every entry with typed bodies, the one the first word picks, through the lane proof of
/// [`crate::lanes`] on the remaining words' bits: points (coordinate `d` of point `k` is word
/// `17 k + d`, cycling), words (indices, seeds, quadrants) and, in the third group of 16,
/// lights of those bits (the first two use the entry's golden lights). Every lane and slice
/// form must give the scalar form's bits, and every scalar output must be finite and below
/// `f32::MAX`: the registry's proof, searched instead of enumerated.
pub fn registry(data: &[u8]) {
    use crate::{Kind, entries, lanes};
    let w = words(data);
    let Some((&pick, rest)) = w.split_first() else {
        return;
    };
    let typed: Vec<_> = entries()
        .filter(|e| !matches!(e.kind, Kind::Other))
        .collect();
    let e = typed[pick as usize % typed.len()];
    let bits: Vec<u32> = if rest.is_empty() {
        vec![0]
    } else {
        rest.to_vec()
    };
    let n = bits.len();
    let words = bits.clone();
    let src = lanes::Source {
        name: "fuzzed",
        count: 48,
        point: Box::new(move |k, d| f32::from_bits(bits[(17 * k + d) % n])),
        word: Box::new(move |k| words[(7 * k + 3) % n]),
    };
    lanes::check(e, &src);
}

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
        let c = disk::concentric4_x8(v, quads);
        let (ci, cq) = disk::concentric4_inverse_x8(v);
        for (j, u) in group.iter().enumerate() {
            let s = disk::concentric4(*u, q.wrapping_add(j as u32));
            assert!(
                in_disk(s) && same(s, [c[0].to_array()[j], c[1].to_array()[j]]),
                "concentric4 {u:?}"
            );
            let (back, quadrant) = disk::concentric4_inverse(*u);
            assert!(
                in_unit_square(back)
                    && quadrant < 4
                    && same(back, [ci[0].to_array()[j], ci[1].to_array()[j]])
                    && quadrant == cq.to_array()[j],
                "concentric4_inverse {u:?}"
            );
        }
        type Quad = fn([f32; 2], u32) -> [f32; 2];
        type QuadSlice = fn(&[[f32; 2]], &mut [[f32; 2]]) -> usize;
        let quad_forms: [(&str, Quad, QuadSlice); 2] = [
            ("polar4", disk::polar4, disk::polar4_slice),
            ("concentric4", disk::concentric4, disk::concentric4_slice),
        ];
        for (name, scalar, slice) in quad_forms {
            let mut out = vec![[0.0f32; 2]; (g % 5) * 7];
            let n = slice(group, &mut out);
            assert_eq!(n, out.len().min(32));
            for (i, p) in out.iter().enumerate() {
                assert!(
                    same(*p, scalar(group[i / 4], i as u32 % 4)),
                    "{name}_slice {i}"
                );
            }
        }
    }
}

/// pmj02bn and the baseline sequences on arbitrary (index, seed, count) words: outputs in
/// [0, 1) (never 1.0), scalar == x8 == slice, `raw` total.
#[cfg(feature = "pmj02bn")]
pub fn pmj02bn(data: &[u8]) {
    use warpcore::{pmj02bn, sequence, u32x8};
    let w = words(data);
    let unit = |p: [f32; 2]| p.iter().all(|c| (0.0..1.0).contains(c));
    for chunk in w.chunks(10) {
        let get = |k: usize| chunk.get(k).copied().unwrap_or(0);
        let (start, seed, count) = (get(0), get(1), get(2));
        let idx: [u32; 8] = std::array::from_fn(|j| get(2 + j));
        let _ = pmj02bn::raw(start as usize, seed as usize);
        type Scalar = fn(u32, u32) -> [f32; 2];
        let forms: [(&str, Scalar); 2] =
            [("pmj02bn", pmj02bn::sample), ("random", sequence::random)];
        for (name, f) in forms {
            let v = match name {
                "pmj02bn" => pmj02bn::sample_x8(u32x8::new(idx), u32x8::splat(seed)),
                _ => sequence::random_x8(u32x8::new(idx), u32x8::splat(seed)),
            };
            for (j, &i) in idx.iter().enumerate() {
                let s = f(i, seed);
                assert!(unit(s), "{name}({i}, {seed}) = {s:?}");
                assert!(
                    same(s, [v[0].to_array()[j], v[1].to_array()[j]]),
                    "{name} x8 {i} {seed}"
                );
            }
        }
        let mut out = [[0.0f32; 2]; 13];
        pmj02bn::sample_slice(start, seed, &mut out);
        for (k, o) in out.iter().enumerate() {
            assert!(
                same(*o, pmj02bn::sample(start.wrapping_add(k as u32), seed)),
                "pmj02bn slice"
            );
        }
        sequence::stratified_slice(start, count, seed, &mut out);
        for (k, o) in out.iter().enumerate() {
            let i = start.wrapping_add(k as u32);
            let s = sequence::stratified(i, count, seed);
            assert!(same(*o, s), "stratified slice");
            // Documented: a jittered point can round onto its cell's upper edge, never past 1.
            assert!(
                s.iter().all(|c| (0.0..=1.0).contains(c)),
                "stratified({i}, {count}, {seed}) = {s:?}"
            );
        }
    }
}

fn barycentric(b: [f32; 3]) -> bool {
    // Each >= 0 and finite; the sum within 2^-24 of 1 (the documented bound is 2^-25 + 2^-49).
    b.iter().all(|c| c.is_finite() && *c >= 0.0)
        && ((b[0] as f64 + b[1] as f64 + b[2] as f64) - 1.0).abs() <= 2f64.powi(-24)
}

/// Triangle warps, inverses on arbitrary barycentric triples, and Basu-Owen on arbitrary
/// (index, seed).
#[cfg(feature = "triangle")]
pub fn triangle(data: &[u8]) {
    use warpcore::{triangle as t, u32x8};
    let w = words(data);
    let p2 = points::<2>(&w);
    let p3 = points::<3>(&w);
    widths(
        "uniform",
        &p2,
        t::uniform,
        t::uniform_x8,
        t::uniform_slice,
        barycentric,
    );
    widths(
        "sqrt_map",
        &p2,
        t::sqrt_map,
        t::sqrt_map_x8,
        t::sqrt_map_slice,
        barycentric,
    );
    widths(
        "uniform_inverse",
        &p3,
        t::uniform_inverse,
        t::uniform_inverse_x8,
        t::uniform_inverse_slice,
        in_unit_square,
    );
    widths(
        "sqrt_map_inverse",
        &p3,
        t::sqrt_map_inverse,
        t::sqrt_map_inverse_x8,
        t::sqrt_map_inverse_slice,
        in_unit_square,
    );
    type Indexed = fn(u32, u32) -> [f32; 3];
    type Indexed8 = fn(u32x8, u32x8) -> [warpcore::f32x8; 3];
    type IndexedSlice = fn(u32, u32, &mut [[f32; 3]]) -> usize;
    let forms: [(&str, Indexed, Indexed8, IndexedSlice); 2] = [
        (
            "basu_owen",
            t::basu_owen,
            t::basu_owen_x8,
            t::basu_owen_slice,
        ),
        (
            "basu_owen_permuted",
            t::basu_owen_permuted,
            t::basu_owen_permuted_x8,
            t::basu_owen_permuted_slice,
        ),
    ];
    for chunk in w.chunks(9) {
        let get = |k: usize| chunk.get(k).copied().unwrap_or(0);
        let seed = get(0);
        let idx: [u32; 8] = std::array::from_fn(|j| get(1 + j));
        // Lane j's seed: the chunk's seed, or (odd lanes) a neighbour index word as seed.
        let seeds: [u32; 8] = std::array::from_fn(|j| if j % 2 == 0 { seed } else { idx[j - 1] });
        for (name, scalar, x8, slice) in forms {
            let v = x8(u32x8::new(idx), u32x8::new(seeds));
            for (j, &i) in idx.iter().enumerate() {
                let b = scalar(i, seeds[j]);
                assert!(
                    barycentric(b) && b[0] + b[1] + b[2] == 1.0,
                    "{name}({i}, {}) = {b:?}",
                    seeds[j]
                );
                assert!(
                    same(b, std::array::from_fn(|k| v[k].to_array()[j])),
                    "{name} x8"
                );
            }
            let mut out = [[0.0f32; 3]; 11];
            assert_eq!(slice(idx[0], seed, &mut out), 11);
            for (k, o) in out.iter().enumerate() {
                assert!(
                    same(*o, scalar(idx[0].wrapping_add(k as u32), seed)),
                    "{name} slice"
                );
            }
        }
    }
}

fn unit_vector(d: [f32; 3]) -> bool {
    let n = d.iter().map(|c| (*c as f64).powi(2)).sum::<f64>().sqrt();
    d.iter().all(|c| c.is_finite()) && (n - 1.0).abs() <= 2e-7
}

fn upper_unit_vector(d: [f32; 3]) -> bool {
    unit_vector(d) && d[2] >= 0.0
}

/// Sphere warps on arbitrary 2D input, inverses on arbitrary 3D input, the wraps, and the
/// density conversions.
#[cfg(feature = "sphere")]
pub fn sphere(data: &[u8]) {
    use warpcore::sphere as s;
    let w = words(data);
    let p2 = points::<2>(&w);
    let p3 = points::<3>(&w);
    widths(
        "equal_area",
        &p2,
        s::equal_area,
        s::equal_area_x8,
        s::equal_area_slice,
        unit_vector,
    );
    widths(
        "equirect",
        &p2,
        s::equirect,
        s::equirect_x8,
        s::equirect_slice,
        unit_vector,
    );
    widths(
        "uniform",
        &p2,
        s::uniform,
        s::uniform_x8,
        s::uniform_slice,
        unit_vector,
    );
    widths(
        "uniform_hemisphere",
        &p2,
        s::uniform_hemisphere,
        s::uniform_hemisphere_x8,
        s::uniform_hemisphere_slice,
        upper_unit_vector,
    );
    widths(
        "cosine_hemisphere",
        &p2,
        s::cosine_hemisphere,
        s::cosine_hemisphere_x8,
        s::cosine_hemisphere_slice,
        upper_unit_vector,
    );
    widths(
        "equal_area_inverse",
        &p3,
        s::equal_area_inverse,
        s::equal_area_inverse_x8,
        s::equal_area_inverse_slice,
        in_unit_square,
    );
    widths(
        "equirect_inverse",
        &p3,
        s::equirect_inverse,
        s::equirect_inverse_x8,
        s::equirect_inverse_slice,
        in_unit_square,
    );
    widths(
        "uniform_inverse",
        &p3,
        s::uniform_inverse,
        s::uniform_inverse_x8,
        s::uniform_inverse_slice,
        in_unit_square,
    );
    widths(
        "uniform_hemisphere_inverse",
        &p3,
        s::uniform_hemisphere_inverse,
        s::uniform_hemisphere_inverse_x8,
        s::uniform_hemisphere_inverse_slice,
        in_unit_square,
    );
    widths(
        "cosine_hemisphere_inverse",
        &p3,
        s::cosine_hemisphere_inverse,
        s::cosine_hemisphere_inverse_x8,
        s::cosine_hemisphere_inverse_slice,
        in_unit_square,
    );
    let closed_square = |u: [f32; 2]| u.iter().all(|c| (0.0..=1.0).contains(c));
    widths(
        "equal_area_wrap",
        &p2,
        s::equal_area_wrap,
        s::equal_area_wrap_x8,
        s::equal_area_wrap_slice,
        closed_square,
    );
    for (k, d) in p3.iter().enumerate() {
        let pdf = d[0];
        for v in [
            s::equirect_pdf_to_solid_angle(pdf, *d),
            s::equal_area_pdf_to_solid_angle(pdf),
            s::cosine_hemisphere_pdf(pdf),
        ] {
            assert!(
                (0.0..f32::MAX).contains(&v),
                "pdf conversion of {pdf} at {d:?}: {v} (NaN, negative or saturated)"
            );
        }
        let size = w.get(k).copied().unwrap_or(1) % 4097;
        let texel = [d[1].to_bits() as i32, d[2].to_bits() as i32];
        let t = s::equal_area_wrap_texel(texel, size);
        assert!(
            size == 0 && t == [0, 0] || t[0] < size && t[1] < size,
            "wrap_texel {texel:?} {size} -> {t:?}"
        );
    }
}

/// Both environment-map builders on an arbitrary image (size up to 40 x 40, any weight bits,
/// storage too small by a random amount), then arbitrary samples: a clean `Error` or a
/// distribution whose every sample lies inside a texel of positive weight (any texel of an
/// all-zero map), with a finite positive pdf equal to `pdf(uv)`, and x8 == scalar.
#[cfg(feature = "envmap")]
pub fn envmap(data: &[u8]) {
    use warpcore::envmap::{Distribution, Error, Hierarchical, MarginalConditional, Sample};
    let w = words(data);
    let get = |k: usize| w.get(k).copied().unwrap_or(0);
    let (width, height) = ((get(0) % 40 + 1) as usize, (get(1) % 40 + 1) as usize);
    let short = (get(2) % 8) as usize; // storage words missing (0: exactly enough, often)
    // MIS compensation (issue 25), from the same word's higher bits and an arbitrary fraction:
    // the samples of a compensated build must satisfy every check below as well.
    let fraction = f32::from_bits(get(2).rotate_left(7));
    let compensation = match (get(2) >> 3) % 4 {
        1 => warpcore::envmap::Compensation::Uniform(fraction),
        2 => warpcore::envmap::Compensation::Equirect(fraction),
        _ => warpcore::envmap::Compensation::None,
    };
    let weights: Vec<f32> = (0..width * height)
        .map(|k| f32::from_bits(get(3 + k)))
        .collect();
    let clean = |x: f32| if x > 0.0 { x } else { 0.0 };
    let infinite = weights.iter().position(|x| *x == f32::INFINITY);
    let all_zero = weights.iter().all(|x| clean(*x) == 0.0);
    let us = points::<2>(w.get(3 + width * height..).unwrap_or(&[]));

    let check = |name: &str, s: Sample, pdf_at: f32| {
        let [c, r] = s.texel.map(|t| t as usize);
        assert!(
            c < width && r < height,
            "{name}: texel {:?} of {width}x{height}",
            s.texel
        );
        assert!(
            all_zero || clean(weights[r * width + c]) > 0.0,
            "{name}: zero-weight texel {:?}",
            s.texel
        );
        // Exactly: x n in [k, k + 1) (the product of an f32 and n < 2^24 is exact in f64);
        // rounded edges like `k as f32 / n as f32` can sit on either side of the true edge.
        let inside = |x: f32, k: usize, n: usize| {
            let t = x as f64 * n as f64;
            t >= k as f64 && t < (k + 1) as f64
        };
        assert!(
            inside(s.uv[0], c, width) && inside(s.uv[1], r, height),
            "{name}: {:?} outside {:?}",
            s.uv,
            s.texel
        );
        assert!(s.pdf > 0.0 && s.pdf < f32::MAX, "{name}: pdf {}", s.pdf);
        assert_eq!(
            s.pdf.to_bits(),
            pdf_at.to_bits(),
            "{name}: pdf(uv) != sample.pdf"
        );
    };

    // One body for both distributions: build (or expect the documented error), then sample.
    fn run<D: Distribution>(
        name: &str,
        built: Result<D, Error>,
        expected_error: Option<Error>,
        us: &[[f32; 2]],
        check: &dyn Fn(&str, Sample, f32),
    ) {
        match built {
            Err(e) => assert_eq!(Some(e), expected_error, "{name}: unexpected error"),
            Ok(d) => {
                assert!(expected_error.is_none(), "{name} accepted a bad input");
                for g in us.chunks_exact(8) {
                    let v = d
                        .sample_x8(std::array::from_fn(|k| {
                            f32x8::new(std::array::from_fn(|j| g[j][k]))
                        }))
                        .to_array();
                    for (j, u) in g.iter().enumerate() {
                        let s = d.sample(*u);
                        check(name, s, d.pdf(s.uv));
                        assert_eq!(s, v[j], "{name} x8");
                    }
                }
            }
        }
    }
    // A too-short storage is reported first, then the first infinite weight.
    let expected = |need: usize, got: usize| {
        if got < need {
            Some(Error::StorageTooSmall { needed: need, got })
        } else {
            infinite.map(|index| Error::InfiniteWeight { index })
        }
    };
    let need = MarginalConditional::storage_len(width, height);
    let mut storage = vec![0u32; need.saturating_sub(short)];
    let got = storage.len();
    let built =
        MarginalConditional::new_compensated(&weights, width, height, compensation, &mut storage);
    run("marginal", built, expected(need, got), &us, &check);
    let need = Hierarchical::storage_len(width, height);
    let mut storage = vec![0u32; need.saturating_sub(short)];
    let got = storage.len();
    let built = Hierarchical::new_compensated(&weights, width, height, compensation, &mut storage);
    run("hierarchical", built, expected(need, got), &us, &check);
}

/// Env-map storage loading: arbitrary words as a storage (`from_storage` and
/// `from_storage_verified` must return, never panic), and real storages with arbitrary words
/// written over them. Whenever a load succeeds, sampling must stay in the map — texel inside,
/// `uv` in `[0, 1)^2`, finite nonnegative pdfs — whatever the table words hold, and the widths
/// must agree bit for bit.
///
/// Input: byte 0 bit 0 picks the distribution (hierarchical if set), bit 1 the mode. Raw mode:
/// the words after byte 4 are the storage. Edit mode: words 1, 2, 3 give width and height
/// (`% 40 + 1`) and a seed for the weights; the storage is built, then each following pair of
/// words `(position, value)` overwrites one word (positions modulo the length, so the header
/// too).
#[cfg(feature = "envmap")]
pub fn envmap_storage(data: &[u8]) {
    use warpcore::envmap::{Distribution, Error, Hierarchical, MarginalConditional, Sample};
    let flags = data.first().copied().unwrap_or(0);
    let w = words(data.get(4..).unwrap_or(&[]));
    let hierarchical = flags & 1 != 0;
    let storage: Vec<u32> = if flags & 2 == 0 {
        w.clone()
    } else {
        let get = |k: usize| w.get(k).copied().unwrap_or(0);
        let (width, height) = ((get(0) % 40 + 1) as usize, (get(1) % 40 + 1) as usize);
        let seed = get(2);
        // Weights from a counter hash, with zeros.
        let weights: Vec<f32> = (0..width * height)
            .map(|k| {
                let x = (k as u32 ^ seed).wrapping_mul(0x9e37_79b9);
                if x.is_multiple_of(5) {
                    0.0
                } else {
                    (x >> 8) as f32
                }
            })
            .collect();
        let mut s = if hierarchical {
            let mut s = vec![0u32; Hierarchical::storage_len(width, height)];
            Hierarchical::new(&weights, width, height, &mut s).expect("valid build");
            s
        } else {
            let mut s = vec![0u32; MarginalConditional::storage_len(width, height)];
            MarginalConditional::new(&weights, width, height, &mut s).expect("valid build");
            s
        };
        let n = s.len();
        for pair in w.get(3..).unwrap_or(&[]).chunks_exact(2) {
            s[pair[0] as usize % n] = pair[1];
        }
        s
    };
    // Fixed sample inputs: specials crossed, then counter-hash points.
    let specials = [
        0.0f32,
        -0.0,
        0.5,
        0.999_999_94,
        1.0,
        f32::NAN,
        f32::INFINITY,
        1e-40,
    ];
    let mut us: Vec<[f32; 2]> = specials
        .iter()
        .flat_map(|&a| specials.iter().map(move |&b| [a, b]))
        .collect();
    us.extend((0..64u32).map(|i| {
        let h = |x: u32| (x.wrapping_mul(0x2c1b_3c6d) ^ (x >> 12)).wrapping_mul(0x297a_2d39);
        [
            (h(2 * i) >> 8) as f32 / 16_777_216.0,
            (h(2 * i + 1) >> 8) as f32 / 16_777_216.0,
        ]
    }));

    fn run<D: Distribution>(name: &str, d: &D, us: &[[f32; 2]]) {
        let (width, height) = (d.width(), d.height());
        let mut out = vec![
            Sample {
                uv: [0.0; 2],
                pdf: 0.0,
                texel: [0; 2],
            };
            us.len()
        ];
        assert_eq!(d.sample_slice(us, &mut out), us.len());
        for (g, group) in us.chunks_exact(8).enumerate() {
            let v: [f32x8; 2] =
                std::array::from_fn(|k| f32x8::new(std::array::from_fn(|j| group[j][k])));
            let x8 = d.sample_x8(v).to_array();
            for (j, u) in group.iter().enumerate() {
                let s = d.sample(*u);
                assert_eq!(s, x8[j], "{name}: scalar != x8 for {u:?}");
                assert_eq!(s, out[g * 8 + j], "{name}: scalar != slice for {u:?}");
                let [c, r] = s.texel.map(|t| t as usize);
                assert!(
                    c < width && r < height,
                    "{name}: texel {:?} of {width}x{height}",
                    s.texel
                );
                assert!(in_unit_square(s.uv), "{name}: uv {:?}", s.uv);
                assert!((0.0..f32::MAX).contains(&s.pdf), "{name}: pdf {}", s.pdf);
                let p = d.pdf(s.uv);
                assert!((0.0..f32::MAX).contains(&p), "{name}: pdf(uv) {p}");
            }
        }
    }
    let check = |name: &str, loaded: Result<(), Error>, verified: Result<(), Error>| {
        // The verified load accepts a subset of what the O(1) load accepts.
        if verified.is_ok() {
            assert!(
                loaded.is_ok(),
                "{name}: verified accepted what from_storage rejected"
            );
        }
        if let (Err(a), Err(b)) = (loaded, verified) {
            assert_eq!(a, b, "{name}: the header errors differ");
        }
    };
    /// Both loads of the storage as `D`: each sampled where it succeeds, their errors checked.
    fn both_loads<'a, D: Distribution>(
        name: &str,
        storage: &'a [u32],
        us: &[[f32; 2]],
        (load, load_verified): LoadPair<'a, D>,
        check: &LoadCheck,
    ) {
        let (loaded, verified) = (load(storage), load_verified(storage));
        for (d, how) in [(&loaded, ""), (&verified, " (verified)")] {
            if let Ok(d) = d {
                run(&format!("{name}{how}"), d, us);
            }
        }
        check(name, loaded.map(|_| ()), verified.map(|_| ()));
    }
    type LoadCheck = dyn Fn(&str, Result<(), Error>, Result<(), Error>);
    type LoadPair<'a, D> = (
        fn(&'a [u32]) -> Result<D, Error>,
        fn(&'a [u32]) -> Result<D, Error>,
    );
    if hierarchical {
        let loads: LoadPair<'_, Hierarchical> = (
            Hierarchical::from_storage,
            Hierarchical::from_storage_verified,
        );
        both_loads("hierarchical", &storage, &us, loads, &check);
    } else {
        let loads: LoadPair<'_, MarginalConditional> = (
            MarginalConditional::from_storage,
            MarginalConditional::from_storage_verified,
        );
        both_loads("marginal", &storage, &us, loads, &check);
    }
}

/// Lights by solid angle: the first 24 words are a triangle light and point (12 floats) and a
/// rectangle light and point (12 floats), any bits; the rest are samples. Every form of every
/// map stays in its domain (barycentrics in the closed simplex, `(s, t)` in `[0, 1]^2`,
/// density finite and >= 0, inverses in `[0, 1)^2`) and scalar == x8 == slice. The sphere
/// light of `cone` is the triangle's `v0` (centre), `v1[0]` (radius) and `p`: unit directions,
/// density `1 / solid angle` (or 0 with solid angle 0), solid angle in `[0, 4 pi]`.
#[cfg(feature = "spherical")]
pub fn spherical(data: &[u8]) {
    use warpcore::spherical as s;
    let mut w = words(data);
    w.resize(w.len().max(24), 0);
    let f = |k: usize| f32::from_bits(w[k]);
    let v: [[f32; 3]; 3] = std::array::from_fn(|i| std::array::from_fn(|k| f(3 * i + k)));
    let p: [f32; 3] = std::array::from_fn(|k| f(9 + k));
    let r: [[f32; 3]; 4] = std::array::from_fn(|i| std::array::from_fn(|k| f(12 + 3 * i + k)));
    let rest = &w[24..];
    let p2 = points::<2>(rest);
    let p3 = points::<3>(rest);
    let sp = |x: [f32; 3]| x.map(f32x8::splat);
    let vv = [sp(v[0]), sp(v[1]), sp(v[2])];
    let tri_ok = |o: [f32; 4]| {
        o[..3].iter().all(|c| (0.0..=1.0).contains(c))
            && ((o[0] as f64 + o[1] as f64 + o[2] as f64) - 1.0).abs() <= 3e-7
            && o[3].is_finite()
            && o[3] >= 0.0
            && o[3] < f32::MAX
    };
    widths(
        "spherical::triangle",
        &p2,
        |u| {
            let (b, d) = s::triangle(v, p, u);
            [b[0], b[1], b[2], d]
        },
        |u| {
            let (b, d) = s::triangle_x8(vv, sp(p), u);
            [b[0], b[1], b[2], d]
        },
        |u, o| s::triangle_slice(v, p, u, o),
        tri_ok,
    );
    widths(
        "spherical::triangle_inverse",
        &p3,
        |b| s::triangle_inverse(v, p, b),
        |b| s::triangle_inverse_x8(vv, sp(p), b),
        |b, o| s::triangle_inverse_slice(v, p, b, o),
        in_unit_square,
    );
    let rect_ok = |o: [f32; 3]| {
        o[..2].iter().all(|c| (0.0..=1.0).contains(c))
            && o[2].is_finite()
            && o[2] >= 0.0
            && o[2] < f32::MAX
    };
    // The bilinear warp with the rectangle's 12 words as three weight sets (any bits).
    for k in 0..3 {
        let wts = [r[k][0], r[k][1], r[k][2], r[(k + 1) % 4][0]];
        for u in &p2 {
            let (x, d) = s::bilinear(*u, wts);
            assert!(
                in_unit_square(x) && (0.0..f32::MAX).contains(&d),
                "spherical::bilinear: {wts:?} {u:?} -> {x:?} {d}"
            );
            let dp = s::bilinear_pdf(x, wts);
            assert!((0.0..f32::MAX).contains(&dp), "bilinear_pdf {dp}");
        }
    }
    widths(
        "spherical::rectangle",
        &p2,
        |u| {
            let (st, d) = s::rectangle(r[0], r[1], r[2], r[3], u);
            [st[0], st[1], d]
        },
        |u| {
            let (st, d) = s::rectangle_x8(sp(r[0]), sp(r[1]), sp(r[2]), sp(r[3]), u);
            [st[0], st[1], d]
        },
        |u, o| s::rectangle_slice(r[0], r[1], r[2], r[3], u, o),
        rect_ok,
    );
    widths(
        "spherical::rectangle_inverse",
        &p2,
        |st| s::rectangle_inverse(r[0], r[1], r[2], r[3], st),
        |st| s::rectangle_inverse_x8(sp(r[0]), sp(r[1]), sp(r[2]), sp(r[3]), st),
        |st, o| s::rectangle_inverse_slice(r[0], r[1], r[2], r[3], st, o),
        in_unit_square,
    );
    // The cosine-aware variants, with normals taken from the other light's bytes.
    let (tn, rn) = (r[0], v[0]);
    widths(
        "spherical::triangle_cosine",
        &p2,
        |u| {
            let (b, d) = s::triangle_cosine(v, p, tn, u);
            [b[0], b[1], b[2], d]
        },
        |u| {
            let (b, d) = s::triangle_cosine_x8(vv, sp(p), sp(tn), u);
            [b[0], b[1], b[2], d]
        },
        |u, o| s::triangle_cosine_slice(v, p, tn, u, o),
        tri_ok,
    );
    widths(
        "spherical::rectangle_cosine",
        &p2,
        |u| {
            let (st, d) = s::rectangle_cosine(r[0], r[1], r[2], r[3], rn, u);
            [st[0], st[1], d]
        },
        |u| {
            let (st, d) = s::rectangle_cosine_x8(sp(r[0]), sp(r[1]), sp(r[2]), sp(r[3]), sp(rn), u);
            [st[0], st[1], d]
        },
        |u, o| s::rectangle_cosine_slice(r[0], r[1], r[2], r[3], rn, u, o),
        rect_ok,
    );
    let om = s::triangle_solid_angle(v, p);
    assert!(
        (0.0..=core::f32::consts::TAU).contains(&om),
        "triangle omega {om}"
    );
    let (c, rad) = (v[0], v[1][0]);
    let om = s::cone_solid_angle(c, rad, p);
    assert!(
        (0.0..=2.0 * core::f32::consts::TAU).contains(&om),
        "cone omega {om}"
    );
    let cone_ok = |o: [f32; 4]| {
        let l = (o[0] as f64).hypot(o[1] as f64).hypot(o[2] as f64);
        let d = o[3];
        (l - 1.0).abs() < 1e-6
            && d.is_finite()
            && (0.0..f32::MAX).contains(&d)
            && if om > 0.0 {
                (d as f64 * om as f64 - 1.0).abs() < 1e-6
            } else {
                d == 0.0
            }
    };
    widths(
        "spherical::cone",
        &p2,
        |u| {
            let (d, pdf) = s::cone(c, rad, p, u);
            [d[0], d[1], d[2], pdf]
        },
        |u| {
            let (d, pdf) = s::cone_x8(sp(c), f32x8::splat(rad), sp(p), u);
            [d[0], d[1], d[2], pdf]
        },
        |u, o| s::cone_slice(c, rad, p, u, o),
        cone_ok,
    );
    widths(
        "spherical::cone_inverse",
        &p3,
        |d| s::cone_inverse(c, rad, p, d),
        |d| s::cone_inverse_x8(sp(c), f32x8::splat(rad), sp(p), d),
        |d, o| s::cone_inverse_slice(c, rad, p, d, o),
        in_unit_square,
    );
    let om = s::rectangle_solid_angle(r[0], r[1], r[2], r[3]);
    assert!(
        (0.0..=core::f32::consts::TAU).contains(&om),
        "rectangle omega {om}"
    );
}

/// The alias table's build: the words as weights (any `f32`, NaN and negatives included), the
/// first byte choosing a dynamic-range transform. A build either fails with the documented
/// error or gives a table whose pmf sums to 1 (within 1e-5), gives zero weights pmf 0 and
/// positive ones a positive pmf, and whose samples (scalar, x8, x16, slice; the special
/// values of `u` and every weight word reused as a `u`) are one light of positive weight with
/// exactly its pmf; the storage passes `from_storage_verified` and samples the same.
#[cfg(feature = "lights")]
pub fn lights_alias_build(data: &[u8]) {
    use warpcore::f32x16;
    use warpcore::lights::{AliasTable, Error};
    let w = words(data);
    let mode = w.first().copied().unwrap_or(0) & 3;
    let weights: Vec<f32> = w
        .iter()
        .skip(1)
        .take(4096)
        .map(|&b| match mode {
            // Raw bits; small non-negative floats; bits masked to [0, 2^24) (subnormals and
            // tiny normals); the top of the range.
            0 => f32::from_bits(b),
            1 => (b >> 8) as f32 * (1.0 / 16_777_216.0),
            2 => f32::from_bits(b & 0x00ff_ffff),
            _ => f32::from_bits(0x7e00_0000 | (b & 0x00ff_ffff)),
        })
        .collect();
    let mut storage = vec![0u32; AliasTable::storage_len(weights.len()).min(1 << 20)];
    let table = match AliasTable::new(&weights, &mut storage) {
        Ok(t) => t,
        Err(Error::Empty) => return assert!(weights.is_empty()),
        Err(Error::InvalidWeight { index }) => {
            let bad = weights[index];
            assert!(!(bad >= 0.0 && bad.is_finite()), "refused {bad}");
            assert!(weights[..index].iter().all(|&x| x >= 0.0 && x.is_finite()));
            return;
        }
        Err(Error::AllZero) => return assert!(weights.iter().all(|&x| x == 0.0)),
        Err(e) => unreachable!("unexpected {e:?}"),
    };
    assert_eq!(table.len(), weights.len());
    let mut sum = 0.0f64;
    for (i, &x) in weights.iter().enumerate() {
        let p = table.pmf(i as u32);
        assert_eq!(p > 0.0, x > 0.0, "light {i}: weight {x}, pmf {p}");
        sum += f64::from(p);
    }
    assert!((sum - 1.0).abs() < 1e-5, "pmf sums to {sum}");
    let mut us: Vec<f32> = [
        0.0,
        -0.0,
        0.5,
        1.0,
        -1.0,
        f32::NAN,
        f32::INFINITY,
        1.0 - 1.0 / 16_777_216.0,
    ]
    .to_vec();
    us.extend(w.iter().take(64).map(|&b| f32::from_bits(b)));
    us.extend(
        w.iter()
            .take(64)
            .map(|&b| (b >> 8) as f32 * (1.0 / 16_777_216.0)),
    );
    us.resize(us.len().div_ceil(16) * 16, 0.25);
    let (mut idx, mut prob) = (vec![0u32; us.len()], vec![0.0f32; us.len()]);
    assert_eq!(table.sample_slice(&us, &mut idx, &mut prob), us.len());
    for (k, g) in us.chunks_exact(16).enumerate() {
        let (i16, p16) = table.sample_x16(f32x16::new(g.try_into().unwrap()));
        let (i8, p8) = table.sample_x8(f32x8::new(g[..8].try_into().unwrap()));
        for (j, &u) in g.iter().enumerate() {
            let (i, p) = table.sample(u);
            assert!(
                weights[i as usize] > 0.0,
                "zero weight {i} chosen at u = {u}"
            );
            assert_eq!(p.to_bits(), table.pmf(i).to_bits());
            assert_eq!(
                (i16.to_array()[j], p16.to_array()[j].to_bits()),
                (i, p.to_bits())
            );
            assert_eq!(
                (idx[16 * k + j], prob[16 * k + j].to_bits()),
                (i, p.to_bits())
            );
            if j < 8 {
                assert_eq!(
                    (i8.to_array()[j], p8.to_array()[j].to_bits()),
                    (i, p.to_bits())
                );
            }
        }
    }
    let again = AliasTable::from_storage_verified(table.storage()).expect("own storage verifies");
    assert_eq!(again.sample(0.3), table.sample(0.3));
}

/// Loading alias-table storage: arbitrary words (the first byte's low bit choosing whether
/// a valid header for the word count is written over them, the second whether a real table's
/// storage is corrupted in one word instead). Never a panic; a storage `from_storage` accepts
/// samples lights below `len()` with probabilities in `[0, 1]`; a single changed word of a
/// real storage is rejected by `from_storage_verified`.
#[cfg(feature = "lights")]
pub fn lights_alias_storage(data: &[u8]) {
    use warpcore::lights::AliasTable;
    let mut w = words(data);
    let mode = w.first().copied().unwrap_or(0);
    if mode & 2 != 0 && w.len() >= 3 {
        // A real table of up to 64 lights from the words, one word of it replaced.
        let weights: Vec<f32> = w
            .iter()
            .skip(3)
            .take(64)
            .map(|&b| (b >> 8) as f32 + 0.0)
            .collect();
        let weights = if weights.iter().any(|&x| x > 0.0) {
            weights
        } else {
            vec![1.0]
        };
        let mut s = vec![0u32; AliasTable::storage_len(weights.len())];
        let t = AliasTable::new(&weights, &mut s).map(|t| t.len());
        if t.is_ok() {
            let at = w[1] as usize % s.len();
            let before = s[at];
            s[at] = w[2];
            let verified = AliasTable::from_storage_verified(&s);
            assert!(
                before == w[2] || verified.is_err(),
                "word {at} changed, accepted"
            );
        }
        w = s;
    } else if mode & 1 != 0 && w.len() >= 8 {
        let n = ((w.len() - 8) / 4) as u32;
        w[0] = u32::from_le_bytes(*b"wcAL");
        w[1] = 1;
        w[2] = n;
        w[4..8].fill(0);
    }
    let _ = AliasTable::from_storage_verified(&w);
    let Ok(t) = AliasTable::from_storage(&w) else {
        return;
    };
    for k in 0..64 {
        let u = w.get(k).map_or(k as f32 / 64.0, |&b| f32::from_bits(b));
        for u in [u, k as f32 / 64.0] {
            let (i, p) = t.sample(u);
            assert!((i as usize) < t.len(), "index {i} of {}", t.len());
            assert!((0.0..=1.0).contains(&p), "probability {p}");
        }
        let q = t.pmf(w.get(k + 64).copied().unwrap_or(k as u32));
        assert!((0.0..=1.0).contains(&q));
    }
}

/// Shading points for the light-tree checks: specials crossed with ordinary points, media and
/// non-unit normals.
#[cfg(feature = "lights")]
fn light_queries() -> Vec<([f32; 3], [f32; 3], f32)> {
    let specials = [
        0.0f32,
        -0.0,
        0.5,
        -3.0,
        1e30,
        f32::NAN,
        f32::INFINITY,
        1e-40,
    ];
    let h = |x: u32| (x.wrapping_mul(0x2c1b_3c6d) ^ (x >> 12)).wrapping_mul(0x297a_2d39);
    let f = |x: u32| (h(x) >> 8) as f32 / 16_777_216.0;
    let mut q: Vec<([f32; 3], [f32; 3], f32)> = specials
        .iter()
        .flat_map(|&a| {
            specials
                .iter()
                .map(move |&b| ([a, 1.0, b], [b, 0.0, 1.0], a))
        })
        .collect();
    q.extend((0..64u32).map(|i| {
        let k = 8 * i;
        let p = [f(k) * 8.0 - 4.0, f(k + 1) * 8.0 - 4.0, f(k + 2) * 8.0 - 4.0];
        let n = if i % 3 == 0 {
            [0.0; 3]
        } else {
            [f(k + 3) - 0.5, f(k + 4) - 0.5, f(k + 5) - 0.5]
        };
        (p, n, f(k + 6))
    }));
    q
}

/// What every light tree that loaded must do at `queries`: `sample` gives an index below
/// `len` and a probability in `(0, 1]`; `pmf` is in `[0, 1]`; with `exact` (a tree `new`
/// built, unaltered) `sample` equals `pmf` bit for bit, never returns a light of power 0
/// (`zero_power`) and the pmfs sum to at most `1 + 1e-4`.
#[cfg(feature = "lights")]
fn light_tree_outputs(
    t: &warpcore::lights::LightTree,
    exact: bool,
    zero_power: &dyn Fn(u32) -> bool,
) {
    let len = t.len() as u32;
    for (p, n, u) in light_queries() {
        if let Some((i, q)) = t.sample(p, n, u) {
            assert!(
                i < len && (f32::MIN_POSITIVE..=1.0).contains(&q),
                "sample ({i}, {q}) of {len}"
            );
            if exact {
                assert_eq!(q.to_bits(), t.pmf(p, n, i).to_bits(), "sample != pmf");
                assert!(!zero_power(i), "light {i} of power 0 chosen");
            }
        }
        let mut sum = 0.0f64;
        for i in 0..len.min(80) + 2 {
            let q = t.pmf(p, n, i);
            assert!(
                q == 0.0 || (f32::MIN_POSITIVE..=1.0).contains(&q),
                "pmf {q}"
            );
            sum += f64::from(q);
        }
        if exact && len <= 80 {
            assert!(sum <= 1.0 + 1e-4, "pmfs sum to {sum}");
        }
    }
}

/// Fuzz the light tree's build: the words are lights of 15 words each (min, max, power, axis,
/// cos_theta_o, cos_theta_e as `f32` bits, then a two-sided word), up to 64 lights. `new`
/// must return the first error an independent reading of the rules predicts (or succeed),
/// never panic, and a built tree must keep [`light_tree_outputs`]' promises.
#[cfg(feature = "lights")]
pub fn lights_tree_build(data: &[u8]) {
    use warpcore::lights::{Error, LightBounds, LightTree};
    let w = words(data);
    let f = |k: usize| f32::from_bits(w.get(k).copied().unwrap_or(0));
    let lights: Vec<LightBounds> = (0..(w.len() / 15).min(64))
        .map(|i| {
            let b = 15 * i;
            LightBounds {
                min: [f(b), f(b + 1), f(b + 2)],
                max: [f(b + 3), f(b + 4), f(b + 5)],
                power: f(b + 6),
                axis: [f(b + 7), f(b + 8), f(b + 9)],
                cos_theta_o: f(b + 10),
                cos_theta_e: f(b + 11),
                two_sided: w.get(b + 12).is_some_and(|x| x & 1 != 0),
            }
        })
        .collect();
    let expected = if lights.is_empty() {
        Some(Error::Empty)
    } else {
        lights
            .iter()
            .enumerate()
            .find_map(|(index, l)| {
                if !(l.power >= 0.0 && l.power.is_finite()) {
                    return Some(Error::InvalidWeight { index });
                }
                let coords = l.min.iter().chain(&l.max).all(|c| c.is_finite())
                    && (0..3).all(|k| l.min[k] <= l.max[k]);
                let axis = l.axis.iter().all(|c| c.is_finite())
                    && l.axis
                        .iter()
                        .map(|&c| f64::from(c) * f64::from(c))
                        .sum::<f64>()
                        > 0.0;
                let cos = [l.cos_theta_o, l.cos_theta_e]
                    .iter()
                    .all(|c| (-1.0..=1.0).contains(c));
                (!(coords && axis && cos)).then_some(Error::InvalidBounds { index })
            })
            .or_else(|| {
                lights
                    .iter()
                    .all(|l| l.power == 0.0)
                    .then_some(Error::AllZero)
            })
    };
    let mut s = vec![0u32; LightTree::storage_len(lights.len())];
    match (LightTree::new(&lights, &mut s), expected) {
        (Ok(t), None) => {
            assert_eq!(t.len(), lights.len());
            let zero = |i: u32| lights.get(i as usize).is_none_or(|l| l.power == 0.0);
            light_tree_outputs(&t, true, &zero);
            assert!(LightTree::from_storage_verified(&s).is_ok());
        }
        (Err(e), Some(x)) => assert_eq!(e, x),
        (r, x) => core::panic!("new gave {:?}, expected {x:?}", r.map(|t| t.len())),
    }
}

/// Fuzz loading light-tree storage. Byte 0: bit 0 picks edit mode. Raw mode: the words after
/// byte 4 are the storage. Edit mode: word 1 gives the light count (`% 50 + 1`) and word 2 a
/// seed; the tree is built, then each following pair of words `(position, value)` overwrites
/// one word (positions modulo the length). Whatever loads must keep
/// [`light_tree_outputs`]' validity promises; `from_storage_verified` must accept an
/// unaltered storage and reject one in which exactly one word changed (the checksum's
/// guarantee).
#[cfg(feature = "lights")]
pub fn lights_tree_storage(data: &[u8]) {
    use warpcore::lights::{LightBounds, LightTree};
    let flags = data.first().copied().unwrap_or(0);
    let w = words(data.get(4..).unwrap_or(&[]));
    let get = |k: usize| w.get(k).copied().unwrap_or(0);
    let (storage, changed) = if flags & 1 == 0 {
        (w.clone(), None)
    } else {
        let n = (get(0) % 50 + 1) as usize;
        let seed = get(1);
        let h = |x: u32| ((x ^ seed).wrapping_mul(0x9e37_79b9) >> 8) as f32 / 16_777_216.0;
        let lights: Vec<LightBounds> = (0..n as u32)
            .map(|i| {
                let c = [h(8 * i) * 6.0, h(8 * i + 1) * 6.0, h(8 * i + 2)];
                LightBounds {
                    min: c,
                    max: [c[0] + 0.1, c[1] + 0.1, c[2]],
                    power: if i % 5 == 2 {
                        0.0
                    } else {
                        h(8 * i + 3) * 4.0 + 0.01
                    },
                    axis: [h(8 * i + 4) - 0.5, h(8 * i + 5) - 0.5, h(8 * i + 6) - 0.25],
                    cos_theta_o: if i % 2 == 0 { 1.0 } else { -1.0 },
                    cos_theta_e: 0.0,
                    two_sided: i % 3 == 0,
                }
            })
            .collect();
        let mut s = vec![0u32; LightTree::storage_len(n)];
        LightTree::new(&lights, &mut s).expect("valid build");
        let original = s.clone();
        let len = s.len();
        for pair in w.get(2..).unwrap_or(&[]).chunks_exact(2) {
            s[pair[0] as usize % len] = pair[1];
        }
        let diff = s.iter().zip(&original).filter(|(a, b)| a != b).count();
        (s, Some(diff))
    };
    match changed {
        Some(0) => assert!(LightTree::from_storage_verified(&storage).is_ok()),
        Some(1) => assert!(LightTree::from_storage_verified(&storage).is_err()),
        _ => {}
    }
    if let Ok(t) = LightTree::from_storage(&storage) {
        light_tree_outputs(&t, changed == Some(0), &|_| false);
    }
}
