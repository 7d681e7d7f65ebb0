//! The environment-map family, one test target: this file (invariants on any input, bit
//! identity across widths, agreement with the weights against an `f64` reference, chi-square
//! and per-texel frequency tests on the real CC0 maps, stiff and bad input, errors, the
//! solid-angle helpers) and its modules: [`centred`] (non-power-of-two maps centred in their
//! pyramid), [`compensation`] (MIS-compensated builds), [`direction`] (directions and
//! densities per steradian), [`storage`] (caller-owned storage, its format and checksum).
#![cfg(feature = "envmap")]
#![allow(clippy::needless_range_loop)]

mod centred;
mod compensation;
mod direction;
mod storage;

use warpcore_testkit as common;

use common::{chi2, lane, rng, same_bits, soa, special_pairs, unit2};
use proptest::prelude::*;
use rand::RngExt;
use std::f64::consts::PI;
use warpcore::envmap::{
    Error, Hierarchical, MAX_SIDE, MarginalConditional, Sample, SampleX8, SampleX16, Word, image,
};
use warpcore::{f32x8, f32x16};

// ----------------------------------------------------------------------------------------
// Both distributions behind one interface.

trait Dist {
    fn name(&self) -> &'static str;
    fn sample(&self, u: [f32; 2]) -> Sample;
    fn sample_x8(&self, u: [f32x8; 2]) -> SampleX8;
    fn sample_x16(&self, u: [f32x16; 2]) -> SampleX16;
    fn sample_slice(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize;
    fn pdf(&self, uv: [f32; 2]) -> f32;
    fn pdf_x8(&self, uv: [f32x8; 2]) -> f32x8;
    fn pdf_x16(&self, uv: [f32x16; 2]) -> f32x16;
    fn pdf_slice(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize;
}

macro_rules! impl_dist {
    ($t:ident, $name:literal) => {
        impl Dist for $t<'_> {
            fn name(&self) -> &'static str {
                $name
            }
            fn sample(&self, u: [f32; 2]) -> Sample {
                $t::sample(self, u)
            }
            fn sample_x8(&self, u: [f32x8; 2]) -> SampleX8 {
                $t::sample_x8(self, u)
            }
            fn sample_x16(&self, u: [f32x16; 2]) -> SampleX16 {
                $t::sample_x16(self, u)
            }
            fn sample_slice(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize {
                $t::sample_slice(self, u, out)
            }
            fn pdf(&self, uv: [f32; 2]) -> f32 {
                $t::pdf(self, uv)
            }
            fn pdf_x8(&self, uv: [f32x8; 2]) -> f32x8 {
                $t::pdf_x8(self, uv)
            }
            fn pdf_x16(&self, uv: [f32x16; 2]) -> f32x16 {
                $t::pdf_x16(self, uv)
            }
            fn pdf_slice(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
                $t::pdf_slice(self, uv, out)
            }
        }
    };
}
impl_dist!(MarginalConditional, "marginal-conditional");
impl_dist!(Hierarchical, "hierarchical");

/// Builds both distributions of a map and hands each to `f`.
fn with_both(weights: &[f32], w: usize, h: usize, mut f: impl FnMut(&dyn Dist)) {
    let mut s = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    f(&MarginalConditional::new(weights, w, h, &mut s).expect("marginal-conditional"));
    let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
    f(&Hierarchical::new(weights, w, h, &mut s).expect("hierarchical"));
}

/// Random weights, about a quarter of them 0 and the rest `nonzero(x)` of a uniform `x` in
/// `[0, 1)`, from a fixed seed.
fn random_weights(w: usize, h: usize, seed: u64, nonzero: impl Fn(f32) -> f32) -> Vec<f32> {
    let mut r = rng(seed);
    (0..w * h)
        .map(|_| {
            if r.random::<u32>() % 4 == 0 {
                0.0
            } else {
                nonzero(r.random::<f32>())
            }
        })
        .collect()
}

/// The weight rule, as an independent reference: positive finite values count, all else is 0.
fn clean(x: f32) -> f64 {
    if x > 0.0 && x.is_finite() {
        x as f64
    } else {
        0.0
    }
}

/// Texel probabilities the weights ask for (uniform for an all-zero map), in f64.
fn reference_probabilities(weights: &[f32]) -> Vec<f64> {
    let total: f64 = weights.iter().map(|&x| clean(x)).sum();
    if total == 0.0 {
        return vec![1.0 / weights.len() as f64; weights.len()];
    }
    weights.iter().map(|&x| clean(x) / total).collect()
}

/// Texel centres, row-major.
fn centres(w: usize, h: usize) -> Vec<[f32; 2]> {
    let mut c = Vec::with_capacity(w * h);
    for r in 0..h {
        for k in 0..w {
            c.push([
                ((k as f64 + 0.5) / w as f64) as f32,
                ((r as f64 + 0.5) / h as f64) as f32,
            ]);
        }
    }
    c
}

/// Texel probabilities a distribution reports: `pdf(centre) / (w h)`.
fn reported_probabilities(d: &dyn Dist, w: usize, h: usize) -> Vec<f64> {
    let c = centres(w, h);
    let mut pdf = vec![0.0f32; c.len()];
    assert_eq!(d.pdf_slice(&c, &mut pdf), c.len());
    pdf.iter().map(|&p| p as f64 / (w * h) as f64).collect()
}

/// Everything a sample must satisfy: `uv` in `[0, 1)^2` and inside its texel exactly, a
/// positive-weight texel (any texel for an all-zero map), a finite positive pdf that
/// `pdf(uv)` reproduces bit for bit.
fn check_sample(d: &dyn Dist, weights: &[f32], w: usize, h: usize, u: [f32; 2], s: Sample) {
    let ctx = || format!("{} {w}x{h} u {u:?} -> {s:?}", d.name());
    assert!(
        s.uv.iter().all(|x| (0.0..1.0).contains(x)),
        "uv out of range: {}",
        ctx()
    );
    let [c, r] = s.texel;
    assert!((c as usize) < w && (r as usize) < h, "texel: {}", ctx());
    let (tx, ty) = (s.uv[0] as f64 * w as f64, s.uv[1] as f64 * h as f64);
    assert!(
        tx >= c as f64 && tx < c as f64 + 1.0 && ty >= r as f64 && ty < r as f64 + 1.0,
        "uv outside its texel: {}",
        ctx()
    );
    let all_zero = weights.iter().all(|&x| clean(x) == 0.0);
    assert!(
        all_zero || clean(weights[r as usize * w + c as usize]) > 0.0,
        "zero-weight texel: {}",
        ctx()
    );
    assert!(s.pdf.is_finite() && s.pdf > 0.0, "pdf: {}", ctx());
    assert_eq!(
        d.pdf(s.uv).to_bits(),
        s.pdf.to_bits(),
        "pdf(uv) differs: {}",
        ctx()
    );
}

/// Scalar, x8, x16 and slice forms of `sample` and `pdf` agree bit for bit on eight inputs
/// (the x16 form gets them twice, the second time reversed, so every lane is checked).
fn check_widths(d: &dyn Dist, pts: &[[f32; 2]; 8]) {
    let v = d.sample_x8(soa(pts)).to_array();
    let pv = d.pdf_x8(soa(pts));
    let twice: [[f32; 2]; 16] = core::array::from_fn(|j| pts[if j < 8 { j } else { 15 - j }]);
    let soa16: [f32x16; 2] =
        core::array::from_fn(|k| f32x16::new(core::array::from_fn(|j| twice[j][k])));
    let v16 = d.sample_x16(soa16).to_array();
    let pv16 = d.pdf_x16(soa16).to_array();
    for (j, p) in twice.iter().enumerate() {
        let (s, o) = (d.sample(*p), v16[j]);
        assert!(
            same_bits([s.uv[0], s.uv[1], s.pdf], [o.uv[0], o.uv[1], o.pdf]) && s.texel == o.texel,
            "{} x16 lane {j}: {p:?}: {s:?} vs {o:?}",
            d.name()
        );
        assert_eq!(d.pdf(*p).to_bits(), pv16[j].to_bits(), "pdf_x16 {j}");
    }
    let mut out = [Sample {
        uv: [9.0; 2],
        pdf: 9.0,
        texel: [9; 2],
    }; 8];
    let mut pout = [9.0f32; 8];
    for n in [8usize, 5, 1] {
        assert_eq!(d.sample_slice(&pts[..n], &mut out), n);
        assert_eq!(d.pdf_slice(&pts[..n], &mut pout), n);
        for j in 0..n {
            let s = d.sample(pts[j]);
            for (what, o) in [("x8", v[j]), ("slice", out[j])] {
                assert!(
                    same_bits([s.uv[0], s.uv[1], s.pdf], [o.uv[0], o.uv[1], o.pdf])
                        && s.texel == o.texel,
                    "{} {what} lane {j}: {:?}: {s:?} vs {o:?}",
                    d.name(),
                    pts[j]
                );
            }
            let p = d.pdf(pts[j]);
            assert_eq!(p.to_bits(), lane([pv], j)[0].to_bits(), "pdf_x8 {j}");
            assert_eq!(p.to_bits(), pout[j].to_bits(), "pdf_slice {j}");
        }
    }
}

/// A small irregular map with every kind of bad value: zeros, negatives, NaN, -inf, -0.0,
/// subnormals, a zero row and a zero column, and a wide dynamic range.
fn irregular_map() -> (Vec<f32>, usize, usize) {
    let (w, h) = (13, 7);
    let mut r = rng(99);
    let mut m: Vec<f32> = (0..w * h)
        .map(|_| {
            let x = common::unit(&mut r);
            (x * 20.0).exp() * 1e-4
        })
        .collect();
    for k in 0..w {
        m[2 * w + k] = 0.0; // a zero row
    }
    for r in 0..h {
        m[r * w + 5] = if r % 2 == 0 { -1.0 } else { f32::NAN }; // a bad column
    }
    m[0] = f32::NEG_INFINITY;
    m[1] = -0.0;
    m[w + 3] = f32::from_bits(1);
    m[w * h - 1] = 1e30;
    (m, w, h)
}

// ----------------------------------------------------------------------------------------
// Any input: invariants and bit identity.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    /// Arbitrary bit patterns as `u` (and as `uv` for the pdf), on a map full of bad values.
    #[test]
    fn widths_agree_on_any_bits(bits in prop::array::uniform16(any::<u32>())) {
        let pts: [[f32; 2]; 8] =
            std::array::from_fn(|j| [f32::from_bits(bits[2 * j]), f32::from_bits(bits[2 * j + 1])]);
        let (m, w, h) = irregular_map();
        with_both(&m, w, h, |d| {
            check_widths(d, &pts);
            for &u in &pts {
                check_sample(d, &m, w, h, u, d.sample(u));
                let p = d.pdf(u);
                assert!(p.is_finite() && p >= 0.0);
            }
        });
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Any map of any size (weights from arbitrary bits) either builds or reports the first
    /// `+inf`; built, it never returns a zero-weight texel, an out-of-texel uv or a bad pdf.
    #[test]
    fn any_map_any_input(
        w in 1usize..40,
        h in 1usize..40,
        seed: u64,
        density in 0u32..4,
        us in prop::collection::vec((any::<u32>(), any::<u32>()), 32),
    ) {
        let mut r = rng(seed);
        // Mostly sparse maps of arbitrary bit patterns (density 0: all bits random).
        let weights: Vec<f32> = (0..w * h)
            .map(|_| {
                let bits = rand::RngExt::random::<u32>(&mut r);
                if density > 0 && !bits.is_multiple_of(1 << density) { 0.0 } else { f32::from_bits(bits) }
            })
            .collect();
        let first_inf = weights.iter().position(|&x| x == f32::INFINITY);
        let mut s1 = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        let mut s2 = vec![0 as Word; Hierarchical::storage_len(w, h)];
        let m = MarginalConditional::new(&weights, w, h, &mut s1);
        let hd = Hierarchical::new(&weights, w, h, &mut s2);
        if let Some(index) = first_inf {
            prop_assert_eq!(m.err(), Some(Error::InfiniteWeight { index }));
            prop_assert_eq!(hd.err(), Some(Error::InfiniteWeight { index }));
            return Ok(());
        }
        let (m, hd) = (m.unwrap(), hd.unwrap());
        let mut pts = us.iter().map(|&(a, b)| [f32::from_bits(a), f32::from_bits(b)]).collect::<Vec<_>>();
        pts.extend([[0.0, 0.0], [common::ONE_MINUS_EPS; 2], [0.0, common::ONE_MINUS_EPS]]);
        for d in [&m as &dyn Dist, &hd] {
            for &u in &pts {
                check_sample(d, &weights, w, h, u, d.sample(u));
            }
            check_widths(d, pts[..8].try_into().unwrap());
            // The reported distribution sums to 1 and is 0 exactly on zero-weight texels.
            let p = reported_probabilities(d, w, h);
            let sum: f64 = p.iter().sum();
            prop_assert!((sum - 1.0).abs() < 1e-5, "{} sums to {sum}", d.name());
            // Zero weight <=> probability 0, except that the hierarchical distribution may
            // leave a texel unreachable when it is fainter than its 31-bit intervals resolve.
            let all_zero = weights.iter().all(|&x| clean(x) == 0.0);
            let want = reference_probabilities(&weights);
            for (k, (&pk, &x)) in p.iter().zip(&weights).enumerate() {
                if all_zero {
                    prop_assert!(pk > 0.0);
                } else if clean(x) == 0.0 {
                    prop_assert_eq!(pk, 0.0, "{} texel {}: weight {}", d.name(), k, x);
                } else if pk == 0.0 {
                    prop_assert!(d.name() == "hierarchical" && want[k] < 2f64.powi(-20),
                        "{} texel {} unreachable: weight {} p {}", d.name(), k, x, want[k]);
                }
            }
        }
    }
}

#[test]
fn widths_agree_on_special_values() {
    let pts = special_pairs();
    let (m, w, h) = irregular_map();
    let park = luminance_latlong(&pfm::envmap("park"));
    for (weights, w, h) in [(&m[..], w, h), (&park.0[..], park.1, park.2)] {
        with_both(weights, w, h, |d| {
            for group in pts.chunks_exact(8) {
                check_widths(d, group.try_into().unwrap());
            }
            for &u in &pts {
                check_sample(d, weights, w, h, u, d.sample(u));
            }
        });
    }
}

/// Slices of every length 0..=40, the lengths around whole interleaved steps (up to six
/// groups of eight lanes: 48, 96, ...), and mismatched output lengths, against the scalar form.
#[test]
fn slices_of_any_length() {
    let (m, w, h) = irregular_map();
    let mut r = rng(8);
    let input: Vec<[f32; 2]> = (0..400).map(|_| unit2(&mut r)).collect();
    let lengths = (0..=40usize).chain([47, 48, 49, 63, 64, 65, 95, 96, 97, 103, 143, 144, 400]);
    with_both(&m, w, h, |d| {
        for n in lengths.clone() {
            for len in [n, n + 3, n.saturating_sub(5)] {
                let marker = Sample {
                    uv: [7.0; 2],
                    pdf: 7.0,
                    texel: [7; 2],
                };
                let mut out = vec![marker; len];
                let written = d.sample_slice(&input[..n], &mut out);
                assert_eq!(written, n.min(len));
                for j in 0..len {
                    if j < written {
                        assert_eq!(out[j], d.sample(input[j]));
                    } else {
                        assert_eq!(out[j], marker);
                    }
                }
                let mut p = vec![7.0f32; len];
                assert_eq!(d.pdf_slice(&input[..n], &mut p), n.min(len));
                for (j, q) in p.iter().enumerate().take(written) {
                    assert_eq!(q.to_bits(), d.pdf(input[j]).to_bits(), "pdf_slice {j}");
                }
                assert!(p[n.min(len)..].iter().all(|&x| x == 7.0));
            }
        }
    });
}

// ----------------------------------------------------------------------------------------
// Real maps.

/// An independent f64 model of the hierarchical warp: the padded pyramid of exact sums, and
/// for each texel the lengths `d_x`, `d_y` (fractions of the unit square) of the interval
/// each axis narrows to, as products of exact shares.
struct Pyramid {
    a: u32,
    b: u32,
    /// Sums per level (0 = root), row-major over that level's grid.
    sums: Vec<Vec<f64>>,
    width: usize,
    /// The map is centred in the padded square: texel `(c, r)` is padded `(c + ox, r + oy)`.
    off: (usize, usize),
}

impl Pyramid {
    fn new(weights: &[f32], w: usize, h: usize) -> Self {
        let (a, b) = (
            w.next_power_of_two().trailing_zeros(),
            h.next_power_of_two().trailing_zeros(),
        );
        let levels = a.max(b);
        let all_zero = weights.iter().all(|&x| clean(x) == 0.0);
        let (pw, ph) = (1usize << a, 1usize << b);
        let (ox, oy) = ((pw - w) / 2, (ph - h) / 2);
        let mut finest = vec![0.0f64; pw * ph];
        for r in 0..h {
            for k in 0..w {
                finest[(r + oy) * pw + k + ox] = if all_zero {
                    1.0
                } else {
                    clean(weights[r * w + k])
                };
            }
        }
        let mut sums = vec![finest];
        for level in (0..levels).rev() {
            let (sx, sy) = (level + a >= levels, level + b >= levels);
            let (cw, ch) = Self::dims(a, b, level + 1);
            let (nw, nh) = Self::dims(a, b, level);
            let child = sums.last().unwrap();
            let mut s = vec![0.0f64; nw * nh];
            for y in 0..ch {
                for x in 0..cw {
                    let (px, py) = (if sx { x / 2 } else { x }, if sy { y / 2 } else { y });
                    s[py * nw + px] += child[y * cw + x];
                }
            }
            sums.push(s);
        }
        sums.reverse();
        Pyramid {
            a,
            b,
            sums,
            width: w,
            off: (ox, oy),
        }
    }

    /// Grid of a level: 2^(x splits above it) x 2^(y splits above it).
    fn dims(a: u32, b: u32, level: u32) -> (usize, usize) {
        let levels = a.max(b);
        (
            1 << level.saturating_sub(levels - a),
            1 << level.saturating_sub(levels - b),
        )
    }

    fn sum(&self, level: u32, x: usize, y: usize) -> f64 {
        let (w, _) = Self::dims(self.a, self.b, level);
        self.sums[level as usize][y * w + x]
    }

    /// `(d_x, d_y)` of texel `k` (row-major in the real map).
    fn lengths(&self, k: usize) -> (f64, f64) {
        let (tx, ty) = (k % self.width + self.off.0, k / self.width + self.off.1);
        let levels = self.a.max(self.b);
        let (mut dx, mut dy) = (1.0f64, 1.0f64);
        for level in 0..levels {
            let (sx, sy) = (level + self.a >= levels, level + self.b >= levels);
            let (nw, nh) = Self::dims(self.a, self.b, level);
            let (cw, ch) = Self::dims(self.a, self.b, level + 1);
            let (x, y) = (
                tx >> (self.a as usize - nw.trailing_zeros() as usize),
                ty >> (self.b as usize - nh.trailing_zeros() as usize),
            );
            let (cx, cy) = (
                tx >> (self.a as usize - cw.trailing_zeros() as usize),
                ty >> (self.b as usize - ch.trailing_zeros() as usize),
            );
            let node = self.sum(level, x, y);
            let column = if sy {
                self.sum(level + 1, cx, cy & !1) + self.sum(level + 1, cx, cy | 1)
            } else {
                self.sum(level + 1, cx, cy)
            };
            let child = self.sum(level + 1, cx, cy);
            if sx {
                dx *= if node > 0.0 { column / node } else { 0.0 };
            }
            if sy {
                dy *= if column > 0.0 { child / column } else { 0.0 };
            }
        }
        (dx, dy)
    }

    /// The hierarchical error bound of texel `k` (see `hierarchical.rs`): each split
    /// truncates by less than one unit `2^-30` and the 0.31 fractions round by a quarter unit
    /// of the interval, so each axis length is within `1.25 levels` units; node sums are `f32`
    /// (one rounding per level), and the reported pdf rounds four times.
    fn bound(&self, k: usize) -> f64 {
        let (dx, dy) = self.lengths(k);
        let l = self.a.max(self.b) as f64;
        let unit = 2f64.powi(-30);
        1.25 * l * unit * (dx + dy) + (2.0 * l + 6.0) * 2f64.powi(-24) * dx * dy + unit * unit
    }
}

/// Lat-long luminance weights of an image (luminance times the row's solid-angle factor).
fn luminance_latlong(img: &pfm::Image) -> (Vec<f32>, usize, usize) {
    let mut l = vec![0.0f32; img.width * img.height];
    assert_eq!(image::luminance_slice(&img.rgb, &mut l), l.len());
    image::equirect_solid_angle_weights(&mut l, img.width, img.height).unwrap();
    (l, img.width, img.height)
}

/// Histogram of `n` samples at texel resolution, from a fixed seed.
fn texel_counts(d: &dyn Dist, w: usize, h: usize, n: usize, seed: u64) -> Vec<u64> {
    let mut r = rng(seed);
    let u: Vec<[f32; 2]> = (0..n).map(|_| unit2(&mut r)).collect();
    let mut s = vec![
        Sample {
            uv: [0.0; 2],
            pdf: 0.0,
            texel: [0; 2]
        };
        n
    ];
    assert_eq!(d.sample_slice(&u, &mut s), n);
    let mut counts = vec![0u64; w * h];
    for x in &s {
        counts[x.texel[1] as usize * w + x.texel[0] as usize] += 1;
    }
    counts
}

/// Sums texel-resolution counts and probabilities into `bx x by` blocks.
fn blocks(v: &[f64], w: usize, h: usize, bx: usize, by: usize) -> Vec<f64> {
    let (nx, ny) = (w.div_ceil(bx), h.div_ceil(by));
    let mut out = vec![0.0; nx * ny];
    for r in 0..h {
        for k in 0..w {
            out[(r / by) * nx + k / bx] += v[r * w + k];
        }
    }
    out
}

fn histogram(counts: &[f64], nx: usize, ny: usize) -> chi2::Histogram {
    let mut hist = chi2::Histogram::new(nx, ny);
    hist.counts = counts.iter().map(|&c| c as u64).collect();
    hist.total = hist.counts.iter().sum();
    hist
}

/// Chi-square of a distribution's samples against its own pdf, at texel resolution and on
/// 8x8-texel blocks, and the largest per-texel deviation in standard deviations.
fn frequency_tests(d: &dyn Dist, label: &str, w: usize, h: usize, seed: u64) {
    let n = chi2::SAMPLES;
    let counts = texel_counts(d, w, h, n, seed);
    let p = reported_probabilities(d, w, h);
    let sum: f64 = p.iter().sum();
    assert!(
        (sum - 1.0).abs() < 1e-5,
        "{label}: probabilities sum to {sum}"
    );
    let c: Vec<f64> = counts.iter().map(|&x| x as f64).collect();
    chi2::check(&format!("{label} texels"), &histogram(&c, w, h), &p);
    let (bx, by) = (8.min(w), 8.min(h));
    let (nx, ny) = (w.div_ceil(bx), h.div_ceil(by));
    chi2::check(
        &format!("{label} 8x8 blocks"),
        &histogram(&blocks(&c, w, h, bx, by), nx, ny),
        &blocks(&p, w, h, bx, by),
    );
    // Per texel: |observed - expected| in binomial standard deviations, for texels expecting
    // at least 100 samples (the Poisson tail beyond 6.5 sigma is then below 2e-9 per texel,
    // so the whole suite's false-alarm probability stays below 1e-3). This catches what the
    // pooled statistic averages away: a texel expecting 10^5 samples whose pdf is 3% off
    // sits at 9.5 sigma.
    let mut worst = (0.0f64, 0usize);
    for (k, (&o, &pk)) in c.iter().zip(&p).enumerate() {
        let e = pk * n as f64;
        if e >= 100.0 {
            let z = (o - e).abs() / (e * (1.0 - pk)).sqrt();
            if z > worst.0 {
                worst = (z, k);
            }
        }
    }
    eprintln!("{label}: worst texel {} at {:.2} sigma", worst.1, worst.0);
    assert!(
        worst.0 < 6.5,
        "{label}: texel {} off by {:.2} sigma",
        worst.1,
        worst.0
    );
}

/// Reported texel probabilities against the weights' (f64): returns the largest relative
/// error over texels of probability at least `floor`, the largest excess of the absolute
/// error over `1e-4` relative, and the largest ratio of the error to the distribution's
/// error bound (`marginal_bound`, `Pyramid::bound`).
fn against_weights(
    d: &dyn Dist,
    weights: &[f32],
    w: usize,
    h: usize,
    floor: f64,
) -> (f64, f64, f64) {
    let want = reference_probabilities(weights);
    let got = reported_probabilities(d, w, h);
    let bound: Vec<f64> = if d.name() == "hierarchical" {
        let p = Pyramid::new(weights, w, h);
        (0..w * h).map(|k| p.bound(k)).collect()
    } else {
        marginal_bound(weights, w, h)
    };
    let (mut rel, mut abs, mut worst) = (0.0f64, 0.0f64, 0.0f64);
    for ((&g, &x), &b) in got.iter().zip(&want).zip(&bound) {
        abs = abs.max((g - x).abs() - 1e-4 * x);
        worst = worst.max((g - x).abs() / b);
        if x >= floor {
            rel = rel.max((g / x - 1.0).abs());
        }
    }
    (rel, abs, worst)
}

/// The marginal-conditional error bound per texel: the row probability `r` and the texel's
/// probability `c` within its row are each within one unit `2^-31` of exact (both interval
/// ends round to nearest), so `|P' - P| <= 2^-31 (r + c) + 2^-62`, plus the `f32` rounding
/// of the reported pdf (four roundings, `4 * 2^-24` relative).
fn marginal_bound(weights: &[f32], w: usize, h: usize) -> Vec<f64> {
    let unit = 2f64.powi(-31);
    let rows: Vec<f64> = weights
        .chunks_exact(w)
        .map(|r| r.iter().map(|&x| clean(x)).sum())
        .collect();
    let total: f64 = rows.iter().sum();
    let mut out = Vec::with_capacity(w * h);
    for (row, &rs) in weights.chunks_exact(w).zip(&rows) {
        for &x in row {
            let (r, c) = if total > 0.0 && rs > 0.0 {
                (rs / total, clean(x) / rs)
            } else {
                (1.0 / h as f64, 1.0 / w as f64)
            };
            out.push(unit * (r + c) + unit * unit + 4.0 * 2f64.powi(-24) * r * c);
        }
    }
    out
}

/// Both distributions over `weights` (a real map, `label`): the samples follow the reported
/// pdf (chi-square at two resolutions, per-texel deviations), and the reported pdf follows the
/// weights (f64 reference) within the proven per-texel bound; the largest relative error
/// (`p >= avg/16`) below 5e-4 and the largest absolute error beyond `1e-4 p` below `max_abs`
/// (sanity margins over the measured maxima; the bound is the proof).
fn check_real_map(label: &str, weights: &[f32], w: usize, h: usize, seed: u64, max_abs: f64) {
    let avg = 1.0 / (w * h) as f64;
    with_both(weights, w, h, |d| {
        let label = format!("{label} {}", d.name());
        frequency_tests(d, &label, w, h, seed);
        let (rel, abs, worst) = against_weights(d, weights, w, h, avg / 16.0);
        eprintln!(
            "{label}: vs weights: max rel {rel:.2e} (p >= avg/16), \
             max |error| - 1e-4 p {abs:.2e}, error / bound {worst:.2}"
        );
        assert!(worst <= 1.0, "{label}: error / bound {worst}");
        assert!(rel < 5e-4 && abs < max_abs, "{label}: {rel} {abs}");
    });
}

/// Each real map, both distributions, lat-long weights ([`check_real_map`]; measured
/// relative maximum 1.0e-4).
#[test]
fn real_maps_latlong() {
    for (i, name) in pfm::ENVMAPS.iter().enumerate() {
        let (l, w, h) = luminance_latlong(&pfm::envmap(name));
        check_real_map(
            &format!("{name} lat-long"),
            &l,
            w,
            h,
            1000 + i as u64,
            1e-10,
        );
    }
}

/// The chi-square test can fail: samples of the park map against the park map with its rows
/// moved by one (a subtle error) are rejected, at both resolutions.
#[test]
fn chi_square_rejects_a_wrong_distribution() {
    let (l, w, h) = luminance_latlong(&pfm::envmap("park"));
    let mut shifted = l.clone();
    shifted.rotate_right(w);
    let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let d = Hierarchical::new(&l, w, h, &mut s).unwrap();
    let counts: Vec<f64> = texel_counts(&d, w, h, chi2::SAMPLES, 5)
        .iter()
        .map(|&x| x as f64)
        .collect();
    let wrong = reference_probabilities(&shifted);
    let out = chi2::statistic(&histogram(&counts, w, h), &wrong);
    // Samples landing where the wrong pdf is 0 are an outright rejection, too.
    if let Ok(o) = out {
        assert!(o.p_value < chi2::per_test_alpha(), "{o:?}");
    }
    let b = chi2::statistic(
        &histogram(&blocks(&counts, w, h, 8, 8), w / 8, h / 8),
        &blocks(&wrong, w, h, 8, 8),
    )
    .unwrap();
    assert!(b.p_value < chi2::per_test_alpha(), "{b:?}");
}

/// End to end on every map: `sum f(w_i) / pdf_sa(w_i)` estimates the map's integral over the
/// sphere; with samples drawn from the lat-long distributions and pdfs converted with the
/// point's `sin(theta)`, the estimate matches the f64 integral of the texels.
#[test]
fn latlong_solid_angle_estimates_are_unbiased() {
    for name in pfm::ENVMAPS {
        let img = pfm::envmap(name);
        let (w, h) = (img.width, img.height);
        let mut lum = vec![0.0f32; w * h];
        image::luminance_slice(&img.rgb, &mut lum);
        let mut weights = lum.clone();
        image::equirect_solid_angle_weights(&mut weights, w, h).unwrap();
        // The exact integral of the piecewise-constant luminance over the sphere.
        let mut exact = 0.0f64;
        for r in 0..h {
            let (t0, t1) = (PI * r as f64 / h as f64, PI * (r + 1) as f64 / h as f64);
            let omega = 2.0 * PI / w as f64 * (t0.cos() - t1.cos());
            for k in 0..w {
                exact += clean(lum[r * w + k]) * omega;
            }
        }
        with_both(&weights, w, h, |d| {
            let mut r = rng(77);
            let n = 1 << 20;
            let mut acc = 0.0f64;
            for _ in 0..n {
                let s = d.sample(unit2(&mut r));
                let pdf = image::equirect_pdf_to_solid_angle(s.pdf, s.uv[1]);
                let f = clean(lum[s.texel[1] as usize * w + s.texel[0] as usize]);
                acc += f / pdf as f64;
            }
            let est = acc / n as f64;
            eprintln!(
                "{name} {}: estimate / exact - 1 = {:.2e}",
                d.name(),
                est / exact - 1.0
            );
            // f / pdf varies only as sin(theta_point) / sin(theta_row) inside a texel.
            assert!((est / exact - 1.0).abs() < 2e-4, "{name} {}", d.name());
        });
    }
}

// ----------------------------------------------------------------------------------------
// Stiff and bad input.

/// Random samples of a built distribution all satisfy the invariants.
fn check_many(d: &dyn Dist, weights: &[f32], w: usize, h: usize, n: usize, seed: u64) {
    let mut r = rng(seed);
    for _ in 0..n {
        let u = unit2(&mut r);
        check_sample(d, weights, w, h, u, d.sample(u));
    }
    for u in [
        [0.0, 0.0],
        [common::ONE_MINUS_EPS; 2],
        [0.5, 0.5],
        [1.0, 1.0],
    ] {
        check_sample(d, weights, w, h, u, d.sample(u));
    }
}

/// One positive texel: every sample lands in it with pdf `w h` exactly, and the pdf is 0
/// everywhere else.
#[test]
fn a_single_nonzero_texel() {
    for (w, h, c, r) in [(37, 19, 20, 11), (64, 32, 0, 0), (5, 3, 4, 2), (1, 9, 0, 8)] {
        let mut m = vec![0.0f32; w * h];
        m[r * w + c] = 0.125;
        with_both(&m, w, h, |d| {
            let mut rr = rng(3);
            for _ in 0..10_000 {
                let s = d.sample(unit2(&mut rr));
                assert_eq!(s.texel, [c as u32, r as u32], "{}", d.name());
                assert_eq!(s.pdf, (w * h) as f32, "{}", d.name());
            }
            check_many(d, &m, w, h, 1000, 4);
            let p = reported_probabilities(d, w, h);
            for (k, &pk) in p.iter().enumerate() {
                assert_eq!(
                    pk,
                    if k == r * w + c { 1.0 } else { 0.0 },
                    "{} {k}",
                    d.name()
                );
            }
        });
    }
}

/// One texel at 10^12 : 1 over the rest: the bright texel's pdf is right to 1e-6, the dim
/// texels are still reachable with a positive pdf that matches what is sampled, and the
/// probabilities sum to 1.
#[test]
fn one_bright_texel_at_ten_to_the_twelve() {
    let (w, h) = (64, 32);
    let bright = 13 * w + 40;
    let mut m = vec![1.0f32; w * h];
    m[bright] = 1e12;
    with_both(&m, w, h, |d| {
        check_many(d, &m, w, h, 100_000, 5);
        let p = reported_probabilities(d, w, h);
        let want = reference_probabilities(&m);
        assert!(
            (p[bright] / want[bright] - 1.0).abs() < 1e-6,
            "{}",
            d.name()
        );
        let sum: f64 = p.iter().sum();
        assert!((sum - 1.0).abs() < 1e-6, "{}: {sum}", d.name());
        // 2047 dim texels: reachable for the marginal-conditional one (at least one unit per
        // texel); the hierarchical one resolves 2^-31 per axis, and these sit at 1e-12 of the
        // map, most of them fainter than that next to the bright one.
        let dim: Vec<f64> = p
            .iter()
            .enumerate()
            .filter(|&(k, _)| k != bright)
            .map(|(_, &x)| x)
            .collect();
        if d.name() == "marginal-conditional" {
            assert!(dim.iter().all(|&x| x > 0.0));
        }
        eprintln!(
            "{}: bright p {:.12}, dim p in [{:.2e}, {:.2e}], want {:.2e}",
            d.name(),
            p[bright],
            dim.iter().cloned().fold(f64::INFINITY, f64::min),
            dim.iter().cloned().fold(0.0, f64::max),
            want[0]
        );
        // Keys at the very bottom of the square reach a dim texel (the first row before the
        // bright one), and report its pdf.
        let s = d.sample([0.0, 0.0]);
        assert_ne!(s.texel, [40, 13]);
        check_sample(d, &m, w, h, [0.0, 0.0], s);
    });
}

/// 1 x 1, 1 x N and N x 1 maps: the degenerate pyramids and single-entry CDFs.
#[test]
fn degenerate_shapes() {
    // 1 x 1: the texel is the whole square, uv = u (exact for u >= 2^-7), pdf 1.
    for weight in [3.0f32, 0.0, f32::NAN, -1.0, f32::MIN_POSITIVE, f32::MAX] {
        with_both(&[weight], 1, 1, |d| {
            let mut r = rng(9);
            for _ in 0..1000 {
                let u = unit2(&mut r);
                let s = d.sample(u);
                assert_eq!((s.texel, s.pdf), ([0, 0], 1.0), "{} {weight}", d.name());
                if u[0] >= 1.0 / 128.0 && u[1] >= 1.0 / 128.0 {
                    assert_eq!(s.uv, u, "{}", d.name());
                }
            }
            check_many(d, &[weight], 1, 1, 100, 10);
        });
    }
    // 1 x N and N x 1 with random weights: the samples follow the pdf, the pdf the weights.
    let mut r = rng(12);
    let line: Vec<f32> = (0..1000)
        .map(|k| {
            if k % 7 == 0 {
                0.0
            } else {
                common::unit(&mut r) * 10.0
            }
        })
        .collect();
    for (w, h) in [(1000, 1), (1, 1000)] {
        with_both(&line, w, h, |d| {
            let label = format!("{w}x{h} {}", d.name());
            check_many(d, &line, w, h, 10_000, 13);
            let p = reported_probabilities(d, w, h);
            let counts: Vec<f64> = texel_counts(d, w, h, 1 << 20, 14)
                .iter()
                .map(|&x| x as f64)
                .collect();
            chi2::check(&label, &histogram(&counts, w, h), &p);
            let (rel, _, _) = against_weights(d, &line, w, h, 1e-4);
            assert!(rel < 1e-5, "{label}: {rel}");
        });
    }
}

/// An 8192 x 4096 map (2^25 texels, the size of a production HDRI): builds, samples within
/// the invariants, and its pdf follows the weights.
#[test]
fn an_8192_x_4096_map() {
    let (w, h) = (8192usize, 4096usize);
    // Smooth sky, a sun, dark ground with holes and bad values.
    let mut m = vec![0.0f32; w * h];
    for r in 0..h {
        for k in 0..w {
            let (x, y) = (k as f32 / w as f32, r as f32 / h as f32);
            let sky = if y < 0.5 {
                1.0 + 4.0 * (1.0 - 2.0 * y)
            } else {
                0.05
            };
            let sun = if (x - 0.3).abs() < 0.001 && (y - 0.2).abs() < 0.002 {
                1e6
            } else {
                0.0
            };
            m[r * w + k] = match (k * 31 + r * 17) % 1009 {
                0 => f32::NAN,
                1 => -0.5,
                2 => 0.0,
                _ => sky + sun,
            };
        }
    }
    let want = reference_probabilities(&m);
    let marginal = marginal_bound(&m, w, h);
    let pyramid = Pyramid::new(&m, w, h);
    with_both(&m, w, h, |d| {
        let mut r = rng(21);
        let n = 1 << 18;
        let u: Vec<[f32; 2]> = (0..n).map(|_| unit2(&mut r)).collect();
        let mut s = vec![
            Sample {
                uv: [0.0; 2],
                pdf: 0.0,
                texel: [0; 2]
            };
            n
        ];
        d.sample_slice(&u, &mut s);
        let (mut worst, mut worst_bound) = (0.0f64, 0.0f64);
        let mut in_sun = 0usize;
        for (&u, &x) in u.iter().zip(&s) {
            check_sample(d, &m, w, h, u, x);
            let k = x.texel[1] as usize * w + x.texel[0] as usize;
            let err = x.pdf as f64 / (w * h) as f64 - want[k];
            worst = worst.max((err / want[k]).abs());
            let bound = if d.name() == "hierarchical" {
                pyramid.bound(k)
            } else {
                marginal[k]
            };
            worst_bound = worst_bound.max(err.abs() / bound);
            in_sun += usize::from(clean(m[k]) > 1e5);
        }
        let sun_p: f64 = m
            .iter()
            .zip(&want)
            .filter(|(x, _)| clean(**x) > 1e5)
            .map(|(_, p)| p)
            .sum();
        eprintln!(
            "8192x4096 {}: pdf vs weights on samples: max rel {worst:.2e}, error / bound \
             {worst_bound:.2}; sun {:.4} of samples, p {:.4}",
            d.name(),
            in_sun as f64 / n as f64,
            sun_p
        );
        assert!(worst_bound <= 1.0, "{}: {worst_bound}", d.name());
        let f = in_sun as f64 / n as f64;
        assert!((f - sun_p).abs() < 6.0 * (sun_p * (1.0 - sun_p) / n as f64).sqrt());
    });
}

/// NaN, negative, -0.0 and -inf weigh exactly 0: the distributions behave exactly like
/// those of the map with zeros written in their place (same samples and pdfs, bit for bit),
/// and those texels are never sampled.
#[test]
fn bad_values_weigh_zero() {
    let (m, w, h) = irregular_map();
    let zeroed: Vec<f32> = m.iter().map(|&x| clean(x) as f32).collect();
    let mut r = rng(23);
    let mut probes: Vec<[f32; 2]> = (0..10_000).map(|_| unit2(&mut r)).collect();
    probes.extend(centres(w, h));
    let outputs = |x: &[f32]| {
        let mut out = Vec::new();
        with_both(x, w, h, |d| {
            for &u in &probes {
                let s = d.sample(u);
                out.push([
                    s.uv[0].to_bits(),
                    s.uv[1].to_bits(),
                    s.pdf.to_bits(),
                    s.texel[0],
                    s.texel[1],
                    d.pdf(u).to_bits(),
                ]);
            }
        });
        out
    };
    assert_eq!(outputs(&m), outputs(&zeroed));
    with_both(&m, w, h, |d| {
        check_many(d, &m, w, h, 100_000, 22);
        let p = reported_probabilities(d, w, h);
        for (k, &x) in m.iter().enumerate() {
            if clean(x) == 0.0 {
                assert_eq!(p[k], 0.0, "{} texel {k} ({x})", d.name());
            }
        }
    });
}

/// A map whose weights are all zero (or bad) samples uniformly, with pdf 1 (within the
/// fixed-point resolution on sizes that are not powers of two).
#[test]
fn all_zero_maps_sample_uniformly() {
    for (w, h) in [(16, 8), (13, 7)] {
        let m: Vec<f32> = (0..w * h)
            .map(|k| [0.0, -0.0, -3.0, f32::NAN, f32::NEG_INFINITY][k % 5])
            .collect();
        with_both(&m, w, h, |d| {
            check_many(d, &m, w, h, 10_000, 30);
            let p = reported_probabilities(d, w, h);
            for &pk in &p {
                let pdf = pk * (w * h) as f64;
                if w.is_power_of_two() && h.is_power_of_two() {
                    assert_eq!(pdf, 1.0, "{}", d.name());
                }
                assert!((pdf - 1.0).abs() < 1e-6, "{}: {pdf}", d.name());
            }
            let counts: Vec<f64> = texel_counts(d, w, h, 1 << 20, 31)
                .iter()
                .map(|&x| x as f64)
                .collect();
            chi2::check(
                &format!("all-zero {w}x{h} {}", d.name()),
                &histogram(&counts, w, h),
                &chi2::expected_uniform(w, h),
            );
        });
    }
}

/// The documented bound on an all-zero map's pdf, on every size up to 32 x 32 (and the
/// documented example: the first row of a 1 x 13 hierarchical map at 0.99999994).
#[test]
fn all_zero_pdf_bound() {
    let mut below_one_1x13 = false;
    for w in 1..=32usize {
        for h in 1..=32usize {
            let m = vec![0.0f32; w * h];
            let bound = 2f64.powi(-22) + (w + h) as f64 * 2f64.powi(-29);
            with_both(&m, w, h, |d| {
                for r in 0..h {
                    for c in 0..w {
                        let uv = [(c as f32 + 0.5) / w as f32, (r as f32 + 0.5) / h as f32];
                        let p = d.pdf(uv) as f64;
                        assert!(
                            (p - 1.0).abs() <= bound,
                            "{} {w}x{h} [{c}, {r}]: {p}",
                            d.name()
                        );
                        if w.is_power_of_two() && h.is_power_of_two() {
                            assert_eq!(p, 1.0, "{} {w}x{h}", d.name());
                        }
                    }
                }
            });
        }
    }
    let m = vec![0.0f32; 13];
    let mut s = vec![0u32; Hierarchical::storage_len(1, 13)];
    let d = Hierarchical::new(&m, 1, 13, &mut s).unwrap();
    below_one_1x13 |= d.pdf([0.5, 0.5 / 13.0]) == 0.999_999_94;
    assert!(below_one_1x13);
}

/// Extreme finite values: all `f32::MAX` (sums overflow f32 but not the distributions), and a
/// subnormal texel next to huge ones.
#[test]
fn extreme_finite_weights() {
    let (w, h) = (6, 5);
    let m = vec![f32::MAX; w * h];
    with_both(&m, w, h, |d| {
        let p = reported_probabilities(d, w, h);
        for &pk in &p {
            assert!(
                (pk * (w * h) as f64 - 1.0).abs() < 1e-6,
                "{}: {pk}",
                d.name()
            );
        }
        check_many(d, &m, w, h, 1000, 40);
    });
    let mut m = vec![1e38f32; w * h];
    m[7] = f32::from_bits(1);
    with_both(&m, w, h, |d| {
        check_many(d, &m, w, h, 1000, 41);
        let p = reported_probabilities(d, w, h);
        // Oversampled (one fixed-point unit) by the marginal-conditional distribution;
        // below the hierarchical one's resolution (documented: may be unreachable).
        if d.name() == "marginal-conditional" {
            assert!(p[7] > 0.0 && p[7] < 1e-9);
        }
        assert!(p[7] < 1e-9);
    });
}

#[test]
fn errors() {
    let mut s = vec![0 as Word; 4096];
    let ok = [1.0f32; 12];
    macro_rules! both {
        ($weights:expr, $w:expr, $h:expr, $storage:expr, $want:expr) => {
            assert_eq!(
                MarginalConditional::new($weights, $w, $h, $storage).err(),
                Some($want)
            );
            assert_eq!(
                Hierarchical::new($weights, $w, $h, $storage).err(),
                Some($want)
            );
        };
    }
    both!(&ok, 0, 12, &mut s, Error::ZeroSize);
    both!(&ok, 12, 0, &mut s, Error::ZeroSize);
    both!(
        &ok,
        5,
        2,
        &mut s,
        Error::LengthMismatch {
            expected: 10,
            got: 12
        }
    );
    both!(
        &ok,
        13,
        1,
        &mut s,
        Error::LengthMismatch {
            expected: 13,
            got: 12
        }
    );
    both!(&ok, MAX_SIDE + 1, 1, &mut s, Error::TooLarge);
    both!(&ok, 1, usize::MAX, &mut s, Error::TooLarge);
    // The 32-bit table indices: 2^24 x 2^24 is a valid shape but far too large.
    both!(&ok, MAX_SIDE, MAX_SIDE, &mut s, Error::TooLarge);
    let mut inf = ok;
    inf[7] = f32::INFINITY;
    inf[9] = f32::INFINITY;
    both!(&inf, 4, 3, &mut s, Error::InfiniteWeight { index: 7 });
    for (w, h) in [(4usize, 3usize), (1, 12), (12, 1)] {
        let need_m = MarginalConditional::storage_len(w, h);
        let need_h = Hierarchical::storage_len(w, h);
        let mut short = vec![0 as Word; need_m - 1];
        assert_eq!(
            MarginalConditional::new(&ok, w, h, &mut short).err(),
            Some(Error::StorageTooSmall {
                needed: need_m,
                got: need_m - 1
            })
        );
        let mut short = vec![0 as Word; need_h - 1];
        assert_eq!(
            Hierarchical::new(&ok, w, h, &mut short).err(),
            Some(Error::StorageTooSmall {
                needed: need_h,
                got: need_h - 1
            })
        );
        // Longer storage is fine, and only the first `storage_len` words are written.
        let mut long = vec![0xdead_beef as Word; need_h + 5];
        Hierarchical::new(&ok, w, h, &mut long).unwrap();
        assert!(long[need_h..].iter().all(|&x| x == 0xdead_beef));
        let mut long = vec![0xdead_beef as Word; need_m + 5];
        MarginalConditional::new(&ok, w, h, &mut long).unwrap();
        assert!(long[need_m..].iter().all(|&x| x == 0xdead_beef));
    }
    // -inf is a negative weight, not an error.
    let mut neg = ok;
    neg[3] = f32::NEG_INFINITY;
    with_both(&neg, 4, 3, |d| assert_eq!(d.pdf([0.9, 0.1]), 0.0));
    // Sizes: the formulas of the docs (16 header words first, format version 3).
    assert_eq!(
        MarginalConditional::storage_len(4096, 2048),
        16 + 4097 * 2048 + 2 * 2049 + 4097
    );
    // Hierarchical: 16-word blocks for every other level, then the edges (no slack).
    assert_eq!(Hierarchical::storage_len(1, 1), 16 + 2 + 2);
    assert_eq!(Hierarchical::storage_len(2, 2), 16 + 16 + 3 + 3);
    assert_eq!(Hierarchical::storage_len(4, 2), 16 + 16 + 5 + 3);
    assert_eq!(Hierarchical::storage_len(8, 8), 16 + 16 * (1 + 4) + 9 + 9);
    let blocks_4096 = 1 + 8 + 128 + 2048 + 32768 + 524_288;
    assert_eq!(
        Hierarchical::storage_len(4096, 2048),
        16 + 16 * blocks_4096 + 4097 + 2049
    );
    assert_eq!(MarginalConditional::storage_len(0, 5), 0);
    assert_eq!(Hierarchical::storage_len(7, 0), 0);
    assert_eq!(Hierarchical::storage_len(MAX_SIDE + 1, 1), usize::MAX);
    // Display is informative.
    let e = Error::StorageTooSmall { needed: 10, got: 3 };
    assert!(e.to_string().contains("10") && e.to_string().contains('3'));
}

// ----------------------------------------------------------------------------------------
// Helpers: luminance, the lat-long row factor, pdf conversions.

#[test]
fn luminance_helpers() {
    let mut r = rng(50);
    let rgb: Vec<[f32; 3]> = (0..37)
        .map(|_| {
            [
                common::unit(&mut r) * 5.0,
                common::unit(&mut r),
                -common::unit(&mut r),
            ]
        })
        .collect();
    let mut out = vec![0.0f32; 40];
    assert_eq!(image::luminance_slice(&rgb, &mut out), 37);
    for (c, &l) in rgb.iter().zip(&out) {
        assert_eq!(l.to_bits(), image::luminance(*c).to_bits());
        let want = 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64;
        assert!((l as f64 - want.max(0.0)).abs() <= 1e-6 * (1.0 + want.abs()));
    }
    assert_eq!(image::luminance([1.0, 1.0, 1.0]), 1.0);
    // Bad texels: the weight rule (never NaN, never negative, `+0.0`), `+inf` kept; the slice
    // form (SIMD lanes) gives the same bits, NaN payloads included (there are none).
    let inf = f32::INFINITY;
    let bad: Vec<[f32; 3]> = vec![
        [f32::NAN, 0.0, 0.0],
        [0.0, f32::from_bits(0xffff_0000), 1.0],
        [inf, -inf, 0.0],
        [-1.0, 0.0, 0.0],
        [-0.0, -0.0, -0.0],
        [0.0, 0.0, -inf],
        [1.0, -2.0, 1.0],
        [inf, 0.0, 0.0],
        [inf, 1.0, f32::NAN],
        [f32::MAX, f32::MAX, f32::MAX],
        [1e-45, 0.0, 0.0],
    ];
    let want = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, inf, 0.0, f32::MAX, 0.0];
    let mut out = vec![9.0f32; bad.len() + 9];
    let mut many = bad.clone();
    many.extend(bad.iter().take(9)); // past one 8-lane group
    assert_eq!(image::luminance_slice(&many, &mut out), many.len());
    for (k, c) in bad.iter().enumerate() {
        let l = image::luminance(*c);
        assert_eq!(l.to_bits(), want[k].to_bits(), "{c:?} -> {l}");
        assert_eq!(out[k].to_bits(), l.to_bits(), "slice form, {c:?}");
    }
    for (k, c) in bad.iter().take(9).enumerate() {
        assert_eq!(out[bad.len() + k].to_bits(), image::luminance(*c).to_bits());
    }
}

#[test]
fn latlong_row_factor() {
    let (w, h) = (3, 256);
    let mut m = vec![2.0f32; w * h];
    image::equirect_solid_angle_weights(&mut m, w, h).unwrap();
    let mut worst = 0.0f64;
    for r in 0..h {
        let want = 2.0 * (PI * (r as f64 + 0.5) / h as f64).sin();
        for k in 0..w {
            worst = worst.max((m[r * w + k] as f64 / want - 1.0).abs());
        }
    }
    eprintln!("row factor: max rel error {worst:.2e}");
    assert!(worst < 4e-7);
    assert_eq!(
        image::equirect_solid_angle_weights(&mut m, 5, 5),
        Err(Error::LengthMismatch {
            expected: 25,
            got: 768
        })
    );
    assert_eq!(
        image::equirect_solid_angle_weights(&mut [], 0, 5),
        Err(Error::ZeroSize)
    );
}

#[test]
fn solid_angle_conversions() {
    let mut worst = 0.0f64;
    for k in 1..100_000u32 {
        let v = k as f32 / 100_000.0;
        let pdf = 0.5 + k as f32 / 1000.0;
        let got = image::equirect_pdf_to_solid_angle(pdf, v) as f64;
        let want = pdf as f64 / (2.0 * PI * PI * (PI * v as f64).sin());
        worst = worst.max((got / want - 1.0).abs());
    }
    // Near the poles, too: relative precision holds for tiny sin(theta).
    for v in [
        1e-30f32,
        1e-7,
        1.0 / 16_777_216.0,
        common::ONE_MINUS_EPS,
        0.999_999,
    ] {
        let got = image::equirect_pdf_to_solid_angle(1.0, v) as f64;
        let want = 1.0 / (2.0 * PI * PI * (PI * v as f64).sin());
        worst = worst.max((got / want - 1.0).abs());
    }
    eprintln!("lat-long pdf conversion: max rel error {worst:.2e}");
    assert!(worst < 5e-7);
    // The same density as sphere::equirect_pdf_to_solid_angle at the sampled direction.
    let mut r = rng(51);
    let mut diff = 0.0f64;
    for _ in 0..100_000 {
        let u = unit2(&mut r);
        let a = image::equirect_pdf_to_solid_angle(3.0, u[1]) as f64;
        let b = warpcore::sphere::equirect_pdf_to_solid_angle(3.0, warpcore::sphere::equirect(u))
            as f64;
        diff = diff.max((a / b - 1.0).abs());
    }
    eprintln!("lat-long conversion vs sphere::equirect_pdf_to_solid_angle: max rel {diff:.2e}");
    assert!(diff < 2e-6);
    let ea = image::equal_area_pdf_to_solid_angle(3.0) as f64;
    assert!((ea / (3.0 / (4.0 * PI)) - 1.0).abs() < 1.2e-7);
    // Totality.
    // The pole itself: 0, the convention of sphere::equirect_pdf_to_solid_angle.
    assert_eq!(image::equirect_pdf_to_solid_angle(1.0, 0.0), 0.0);
    assert_eq!(image::equirect_pdf_to_solid_angle(0.0, 0.0), 0.0);
    // Unbounded densities give 0, never a saturated f32::MAX: a result that would reach it
    // next to the pole, and f32::MAX or +inf in.
    assert_eq!(image::equirect_pdf_to_solid_angle(1e30, 1e-30), 0.0);
    assert_eq!(image::equirect_pdf_to_solid_angle(f32::NAN, 0.5), 0.0);
    assert_eq!(image::equirect_pdf_to_solid_angle(-1.0, 0.5), 0.0);
    assert_eq!(image::equirect_pdf_to_solid_angle(f32::INFINITY, 0.5), 0.0);
    assert_eq!(image::equirect_pdf_to_solid_angle(f32::MAX, 0.5), 0.0);
    let below = f32::from_bits(f32::MAX.to_bits() - 1);
    let q = image::equirect_pdf_to_solid_angle(below, 0.5) as f64;
    assert!((q * 2.0 * PI * PI / below as f64 - 1.0).abs() < 1e-6, "{q}");
    assert_eq!(image::equal_area_pdf_to_solid_angle(f32::NAN), 0.0);

    for [a, b] in special_pairs() {
        let x = image::equirect_pdf_to_solid_angle(a, b);
        assert!((0.0..f32::MAX).contains(&x), "{a} {b} -> {x}");
        let v = image::equirect_pdf_to_solid_angle_x8(f32x8::splat(a), f32x8::splat(b));
        assert_eq!(v.to_array()[3].to_bits(), x.to_bits());
        let e = image::equal_area_pdf_to_solid_angle(a);
        assert!((0.0..f32::MAX).contains(&e), "{a} -> {e}");
        let v = image::equal_area_pdf_to_solid_angle_x8(f32x8::splat(a));
        assert_eq!(v.to_array()[6].to_bits(), e.to_bits());
    }
}

/// The hierarchical blocks are aligned to 64 bytes inside the caller's storage, wherever it
/// starts: the results do not depend on that placement.
#[test]
fn results_do_not_depend_on_storage_placement() {
    let (m, w, h) = irregular_map();
    let n = Hierarchical::storage_len(w, h);
    let mut big = vec![0 as Word; n + 16];
    let mut r = rng(24);
    let probes: Vec<[f32; 2]> = (0..1000).map(|_| unit2(&mut r)).collect();
    let mut reference: Option<Vec<Sample>> = None;
    for start in 0..16 {
        let d = Hierarchical::new(&m, w, h, &mut big[start..]).unwrap();
        let got: Vec<Sample> = probes.iter().map(|&u| d.sample(u)).collect();
        match &reference {
            None => reference = Some(got),
            Some(want) => assert!(
                want.iter().zip(&got).all(|(a, b)| same_bits(
                    [a.uv[0], a.uv[1], a.pdf],
                    [b.uv[0], b.uv[1], b.pdf]
                ) && a.texel == b.texel),
                "start {start}"
            ),
        }
    }
}

// ----------------------------------------------------------------------------------------
// The equal-area parameterization: lat-long maps resampled onto the octahedral square.

/// Side of the equal-area versions of the 512 x 256 test maps (384^2 = 147456 texels, a
/// little more than the source's 131072) and the supersampling per axis.
const EA_SIZE: usize = 384;
const EA_SUPERSAMPLE: usize = 3;

/// Luminance of a lat-long image, and its equal-area resampling.
fn luminance_equal_area(img: &pfm::Image) -> (Vec<f32>, Vec<f32>) {
    let mut lum = vec![0.0f32; img.width * img.height];
    image::luminance_slice(&img.rgb, &mut lum);
    let mut ea = vec![[0.0f32; 1]; EA_SIZE * EA_SIZE];
    let (src, _) = lum.as_chunks::<1>();
    image::equirect_to_equal_area(src, img.width, img.height, &mut ea, EA_SIZE, EA_SUPERSAMPLE)
        .unwrap();
    (lum, ea.into_iter().map(|[x]| x).collect())
}

/// The exact integral over the sphere of a piecewise-constant lat-long map.
fn latlong_integral(lum: &[f32], w: usize, h: usize) -> f64 {
    let mut exact = 0.0f64;
    for r in 0..h {
        let (t0, t1) = (PI * r as f64 / h as f64, PI * (r + 1) as f64 / h as f64);
        let omega = 2.0 * PI / w as f64 * (t0.cos() - t1.cos());
        exact += lum[r * w..(r + 1) * w]
            .iter()
            .map(|&x| clean(x))
            .sum::<f64>()
            * omega;
    }
    exact
}

/// The lat-long texel value in direction `d`.
fn latlong_lookup(lum: &[f32], w: usize, h: usize, d: [f32; 3]) -> f64 {
    let [u, v] = warpcore::sphere::equirect_inverse(d);
    let (x, y) = (
        ((u as f64 * w as f64) as usize).min(w - 1),
        ((v as f64 * h as f64) as usize).min(h - 1),
    );
    clean(lum[y * w + x])
}

/// Each real map resampled to the equal-area square, both distributions: the samples follow
/// the reported pdf, and the reported pdf the (resampled) weights ([`check_real_map`]).
#[test]
fn real_maps_equal_area() {
    for (i, name) in pfm::ENVMAPS.iter().enumerate() {
        let (_, ea) = luminance_equal_area(&pfm::envmap(name));
        let (n, seed) = (EA_SIZE, 2000 + i as u64);
        // The absolute margin: about a quarter of the walk's fixed-point unit 2^-30 (the
        // centred pyramid puts night's faint texels at 2.2e-10; the per-texel bound is the
        // sharp check).
        check_real_map(&format!("{name} equal-area"), &ea, n, n, seed, 2.5e-10);
    }
}

/// The resampling keeps each map's integral over the sphere (every output texel covers
/// `4 pi / size^2`), and directions sampled from the equal-area distributions, with
/// `equal_area_pdf_to_solid_angle`, estimate the *original* lat-long map's integral without
/// bias (the pdf is positive wherever the source is, and the conventions agree).
#[test]
fn equal_area_sampling_estimates_the_latlong_integral() {
    for name in pfm::ENVMAPS {
        let img = pfm::envmap(name);
        let (w, h) = (img.width, img.height);
        let (lum, ea) = luminance_equal_area(&img);
        let exact = latlong_integral(&lum, w, h);
        let n = EA_SIZE;
        let resampled: f64 = ea.iter().map(|&x| x as f64).sum::<f64>() * 4.0 * PI / (n * n) as f64;
        eprintln!(
            "{name}: resampled integral / exact - 1 = {:.2e}",
            resampled / exact - 1.0
        );
        assert!((resampled / exact - 1.0).abs() < 5e-3, "{name}");
        with_both(&ea, n, n, |d| {
            let mut r = rng(78);
            let samples = 1 << 20;
            let (mut acc, mut acc2, mut zero_pdf) = (0.0f64, 0.0f64, 0usize);
            for _ in 0..samples {
                let s = d.sample(unit2(&mut r));
                let dir = warpcore::sphere::equal_area(s.uv);
                let pdf = image::equal_area_pdf_to_solid_angle(s.pdf) as f64;
                let f = latlong_lookup(&lum, w, h, dir);
                zero_pdf += usize::from(pdf == 0.0);
                let x = f / pdf;
                acc += x;
                acc2 += x * x;
            }
            let mean = acc / samples as f64;
            let sigma = ((acc2 / samples as f64 - mean * mean) / samples as f64).sqrt();
            eprintln!(
                "{name} {}: estimate / exact - 1 = {:.2e} (sigma {:.1e})",
                d.name(),
                mean / exact - 1.0,
                sigma / exact
            );
            assert_eq!(zero_pdf, 0);
            assert!((mean - exact).abs() < 5.0 * sigma, "{name} {}", d.name());
        });
    }
}

/// The resampler's conventions and contract: constant in, constant out; the upper hemisphere
/// (lat-long rows above the equator) lands in the inner rotated square of the octahedral
/// map; bad values count as 0; errors.
#[test]
fn equirect_to_equal_area_contract() {
    let (w, h, n) = (64, 32, 32);
    let constant = vec![[2.5f32, 1.0]; w * h];
    let mut out = vec![[0.0f32; 2]; n * n];
    image::equirect_to_equal_area(&constant, w, h, &mut out, n, 3).unwrap();
    assert!(out.iter().all(|&x| x == [2.5, 1.0]));
    // Upper hemisphere only.
    let upper: Vec<[f32; 1]> = (0..w * h)
        .map(|k| [if k / w < h / 2 { 1.0 } else { 0.0 }])
        .collect();
    let mut out = vec![[0.0f32; 1]; n * n];
    image::equirect_to_equal_area(&upper, w, h, &mut out, n, 4).unwrap();
    for r in 0..n {
        for c in 0..n {
            // Texel corners' L1 distance from the centre: all < 1/2 inside, all > 1/2 outside.
            let corners = [(c, r), (c + 1, r), (c, r + 1), (c + 1, r + 1)].map(|(x, y)| {
                (x as f64 / n as f64 - 0.5).abs() + (y as f64 / n as f64 - 0.5).abs()
            });
            let v = out[r * n + c][0];
            if corners.iter().all(|&x| x < 0.5) {
                assert_eq!(v, 1.0, "texel {c} {r}");
            } else if corners.iter().all(|&x| x > 0.5) {
                assert_eq!(v, 0.0, "texel {c} {r}");
            }
        }
    }
    // NaN and negative source values count as 0, +inf stays infinite (and the distributions
    // then report it).
    let mut bad = vec![[1.0f32]; w * h];
    bad[5] = [f32::NAN];
    bad[6] = [-3.0];
    let mut zeroed = bad.clone();
    zeroed[5] = [0.0];
    zeroed[6] = [0.0];
    let (mut a, mut b) = (vec![[0.0f32]; n * n], vec![[0.0f32]; n * n]);
    image::equirect_to_equal_area(&bad, w, h, &mut a, n, 2).unwrap();
    image::equirect_to_equal_area(&zeroed, w, h, &mut b, n, 2).unwrap();
    assert_eq!(a, b);
    bad[(h / 2) * w + 7] = [f32::INFINITY]; // an equator texel: big enough to be hit
    image::equirect_to_equal_area(&bad, w, h, &mut a, n, 2).unwrap();
    let flat: Vec<f32> = a.iter().map(|&[x]| x).collect();
    assert!(flat.contains(&f32::INFINITY));
    let mut s = vec![0 as Word; Hierarchical::storage_len(n, n)];
    assert!(matches!(
        Hierarchical::new(&flat, n, n, &mut s),
        Err(Error::InfiniteWeight { .. })
    ));
    // Errors.
    let mut out = vec![[0.0f32; 1]; n * n];
    let src = vec![[1.0f32]; w * h];
    assert_eq!(
        image::equirect_to_equal_area(&src, 0, h, &mut out, n, 1),
        Err(Error::ZeroSize)
    );
    assert_eq!(
        image::equirect_to_equal_area(&src, w, h, &mut out, n, 0),
        Err(Error::ZeroSize)
    );
    assert_eq!(
        image::equirect_to_equal_area(&src, w, h, &mut out, 0, 1),
        Err(Error::ZeroSize)
    );
    assert_eq!(
        image::equirect_to_equal_area(&src, w, h - 1, &mut out, n, 1),
        Err(Error::LengthMismatch {
            expected: w * (h - 1),
            got: w * h
        })
    );
    assert_eq!(
        image::equirect_to_equal_area(&src, w, h, &mut out, n + 1, 1),
        Err(Error::LengthMismatch {
            expected: (n + 1) * (n + 1),
            got: n * n
        })
    );
    assert_eq!(
        image::equirect_to_equal_area(&src, w, h, &mut out, n, image::MAX_SUPERSAMPLE + 1),
        Err(Error::TooLarge)
    );
}
