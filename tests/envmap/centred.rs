//! Centred pyramids (issue 25): a `Hierarchical` map whose sides are not powers of two sits in
//! the middle of its padded pyramid. These tests would catch an off-by-one in the centring
//! (a sample on padding or on a zero-weight texel, a pdf that is not the sampled texel's
//! share, probabilities that do not sum to 1), a placement that is not the centred one (an
//! independent `f64` model of the centred walk predicts which texel each point of the sample
//! square lands on), and an old (version 1, corner-padded) storage read as if it were new.
#![cfg(feature = "envmap")]
#![allow(clippy::needless_range_loop)]

use warpcore_testkit as common;

use common::{rng, specials, unit2};
use warpcore::envmap::{Error, FORMAT_VERSION, Hierarchical, MarginalConditional, Word};

/// Sizes with odd and power-of-two sides, both orientations, one-texel-wide maps.
const SIZES: [(usize, usize); 11] = [
    (1, 1),
    (3, 5),
    (5, 3),
    (181, 181),
    (200, 100),
    (17, 3),
    (1, 13),
    (255, 2),
    (3, 257),
    (6, 6),
    (64, 48),
];

/// Weights with about a quarter zeros and a dynamic range of `10^4`.
fn weights(w: usize, h: usize, seed: u64) -> Vec<f32> {
    super::random_weights(w, h, seed, |x| 10f32.powf(4.0 * x))
}

fn build(wts: &[f32], w: usize, h: usize) -> Vec<Word> {
    let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
    Hierarchical::new(wts, w, h, &mut s).expect("build");
    s
}

/// Every sample lands on a positive-weight texel of the map (never the padding), inside the
/// texel exactly, with `pdf == pdf(uv)` and `pdf / (w h)` equal to the texel's share of the
/// total within the documented hierarchical bound `1.25 L 2^-30 (d_x + d_y) + (2L + 6) 2^-24 P`
/// (`L` levels, `d` the texel's preimage sides, from the independent model below).
#[test]
fn samples_land_on_positive_texels_with_their_share() {
    for (i, &(w, h)) in SIZES.iter().enumerate() {
        let wts = weights(w, h, 10 + i as u64);
        let wts = if wts.iter().all(|&x| x == 0.0) {
            vec![1.0; w * h]
        } else {
            wts
        };
        let total: f64 = wts.iter().map(|&x| f64::from(x)).sum();
        let s = build(&wts, w, h);
        let map = Hierarchical::from_storage_verified(&s).expect("verified");
        let rects = model_rectangles(&wts, w, h);
        let levels = f64::from(
            w.next_power_of_two()
                .max(h.next_power_of_two())
                .trailing_zeros(),
        );
        let mut r = rng(100 + i as u64);
        let mut us: Vec<[f32; 2]> = (0..20_000).map(|_| unit2(&mut r)).collect();
        let n = 64;
        for a in 0..=n {
            for b in 0..=n {
                us.push([a as f32 / n as f32, b as f32 / n as f32]);
            }
        }
        for &x in &specials() {
            us.push([x, 0.5]);
            us.push([0.5, x]);
        }
        for u in us {
            let smp = map.sample(u);
            let [c, row] = smp.texel.map(|t| t as usize);
            let ctx = format!("{w}x{h} u {u:?} -> {smp:?}");
            assert!(c < w && row < h, "{ctx}");
            let weight = wts[row * w + c];
            assert!(weight > 0.0, "zero-weight texel: {ctx}");
            let (x, y) = (
                f64::from(smp.uv[0]) * w as f64,
                f64::from(smp.uv[1]) * h as f64,
            );
            assert!(x >= c as f64 && x < c as f64 + 1.0, "{ctx}");
            assert!(y >= row as f64 && y < row as f64 + 1.0, "{ctx}");
            assert_eq!(smp.pdf.to_bits(), map.pdf(smp.uv).to_bits(), "{ctx}");
            let share = f64::from(weight) / total;
            let got = f64::from(smp.pdf) / (w * h) as f64;
            let [_, dx, _, dy] = rects[row * w + c];
            let bound = 1.25 * levels * 2f64.powi(-30) * (dx + dy)
                + (2.0 * levels + 6.0) * 2f64.powi(-24) * share;
            assert!((got - share).abs() <= bound, "{ctx}: {got} vs {share}");
        }
    }
}

/// The probabilities the pdf reports over the texels sum to 1, and are 0 exactly on the
/// zero-weight texels.
#[test]
fn pdf_integrates_to_one_and_vanishes_on_zero_texels() {
    for (i, &(w, h)) in SIZES.iter().enumerate() {
        let wts = weights(w, h, 30 + i as u64);
        let s = build(&wts, w, h);
        let map = Hierarchical::from_storage(&s).unwrap();
        let mut sum = 0.0f64;
        for row in 0..h {
            for c in 0..w {
                let uv = [
                    ((c as f64 + 0.5) / w as f64) as f32,
                    ((row as f64 + 0.5) / h as f64) as f32,
                ];
                let p = map.pdf(uv);
                let zero = wts.iter().all(|&x| x == 0.0);
                if wts[row * w + c] == 0.0 && !zero {
                    assert_eq!(p, 0.0, "{w}x{h} [{c}, {row}]");
                } else {
                    assert!(p > 0.0, "{w}x{h} [{c}, {row}]");
                }
                sum += f64::from(p);
            }
        }
        let sum = sum / (w * h) as f64;
        assert!((sum - 1.0).abs() < 1e-6, "{w}x{h}: {sum}");
    }
}

/// Empirical texel frequencies follow the pdf (2^20 random points per map; per-texel
/// z-scores over texels expecting at least 20 samples below 5.5: with at most 20,000 such
/// texels a correct sampler fails with probability below 1e-3), and no zero texel is hit.
#[test]
fn frequencies_follow_the_pdf() {
    for (i, &(w, h)) in [(3usize, 5usize), (200, 100), (17, 3)].iter().enumerate() {
        let wts = weights(w, h, 50 + i as u64);
        let s = build(&wts, w, h);
        let map = Hierarchical::from_storage(&s).unwrap();
        let n = 1usize << 20;
        let counts = super::texel_counts(&map, w, h, n, 60 + i as u64);
        let probs = super::reported_probabilities(&map, w, h);
        for (t, (&k, &p)) in counts.iter().zip(&probs).enumerate() {
            let (c, row, k) = (t % w, t / w, k as f64);
            if p == 0.0 {
                assert_eq!(k, 0.0, "{w}x{h} [{c}, {row}]");
                continue;
            }
            let mean = n as f64 * p;
            if mean >= 20.0 {
                let z = (k - mean) / (mean * (1.0 - p)).sqrt();
                assert!(z.abs() < 5.5, "{w}x{h} [{c}, {row}]: {k} vs {mean}");
            }
        }
    }
}

/// One level of the model's walk along an axis: the node `[n0, n1)` keeps the half holding
/// texel `t`, and the preimage `[p0, p0 + dp)` the matching part, split at the lower half's
/// share `lower(mid) / all` of the node's weight (all of it for an empty node).
fn halve(
    t: usize,
    n: &mut [usize; 2],
    [p0, dp]: [&mut f64; 2],
    lower: impl Fn(usize) -> f64,
    all: f64,
) {
    let mid = (n[0] + n[1]) / 2;
    let share = if all > 0.0 { lower(mid) / all } else { 1.0 };
    if t < mid {
        *dp *= share;
        n[1] = mid;
    } else {
        *p0 += *dp * share;
        *dp *= 1.0 - share;
        n[0] = mid;
    }
}

/// An independent `f64` model of the centred walk: the map at offset
/// `floor((2^bits - size) / 2)` in a zero-padded `2^a x 2^b` square, levels from the root
/// (the top `|a - b|` split the longer axis only); each level splits x at the left column's
/// share, then y at the lower share within the chosen column. Returns, per texel, its
/// preimage rectangle `[x0, x0 + dx) x [y0, y0 + dy)` in the sample square.
fn model_rectangles(wts: &[f32], w: usize, h: usize) -> Vec<[f64; 4]> {
    let (a, b) = (
        w.next_power_of_two().trailing_zeros(),
        h.next_power_of_two().trailing_zeros(),
    );
    let (pw, ph) = (1usize << a, 1usize << b);
    let (ox, oy) = ((pw - w) / 2, (ph - h) / 2);
    // Prefix sums of the padded grid: sum over [x0, x1) x [y0, y1).
    let mut pre = vec![0.0f64; (pw + 1) * (ph + 1)];
    for y in 0..ph {
        for x in 0..pw {
            let v = if x >= ox && x < ox + w && y >= oy && y < oy + h {
                f64::from(wts[(y - oy) * w + (x - ox)].max(0.0))
            } else {
                0.0
            };
            pre[(y + 1) * (pw + 1) + x + 1] =
                v + pre[y * (pw + 1) + x + 1] + pre[(y + 1) * (pw + 1) + x] - pre[y * (pw + 1) + x];
        }
    }
    let rect = |x0: usize, x1: usize, y0: usize, y1: usize| {
        pre[y1 * (pw + 1) + x1] - pre[y0 * (pw + 1) + x1] - pre[y1 * (pw + 1) + x0]
            + pre[y0 * (pw + 1) + x0]
    };
    let levels = a.max(b);
    let mut out = Vec::with_capacity(w * h);
    for row in 0..h {
        for c in 0..w {
            let (tx, ty) = (c + ox, row + oy);
            // The node's extent in padded texels, and the texel's preimage so far.
            let (mut nx, mut ny) = ([0usize, pw], [0usize, ph]);
            let ([mut x0, mut dx], [mut y0, mut dy]) = ([0.0f64, 1.0], [0.0f64, 1.0]);
            for l in 0..levels {
                let (sx, sy) = (l + a >= levels, l + b >= levels);
                let ([x_lo, x_hi], [y_lo, y_hi]) = (nx, ny);
                let all = rect(x_lo, x_hi, y_lo, y_hi);
                if sx {
                    let left = |mid| rect(x_lo, mid, y_lo, y_hi);
                    halve(tx, &mut nx, [&mut x0, &mut dx], left, all);
                }
                let ([x_lo, x_hi], [y_lo, y_hi]) = (nx, ny);
                let all = rect(x_lo, x_hi, y_lo, y_hi);
                if sy {
                    let low = |mid| rect(x_lo, x_hi, y_lo, mid);
                    halve(ty, &mut ny, [&mut y0, &mut dy], low, all);
                }
            }
            out.push([x0, dx, y0, dy]);
        }
    }
    out
}

/// The walk is the centred one: the centre of each positive texel's preimage rectangle in
/// the model samples that texel. (A corner placement, or an offset off by one, moves the
/// rectangles of non-separable maps and fails this for many texels.)
#[test]
fn the_pyramid_is_centred() {
    for (i, &(w, h)) in [
        (5usize, 5usize),
        (3, 5),
        (181, 181),
        (200, 100),
        (17, 3),
        (6, 6),
    ]
    .iter()
    .enumerate()
    {
        let wts = weights(w, h, 70 + i as u64);
        let s = build(&wts, w, h);
        let map = Hierarchical::from_storage(&s).unwrap();
        let rects = model_rectangles(&wts, w, h);
        let mut checked = 0;
        for (k, &[x0, dx, y0, dy]) in rects.iter().enumerate() {
            if wts[k] == 0.0 || dx < 1e-5 || dy < 1e-5 {
                continue;
            }
            let u = [(x0 + dx / 2.0) as f32, (y0 + dy / 2.0) as f32];
            let t = map.sample(u).texel;
            assert_eq!(
                [t[0] as usize, t[1] as usize],
                [k % w, k / w],
                "{w}x{h} u {u:?}"
            );
            checked += 1;
        }
        assert!(
            checked * 2 > w * h / 2,
            "{w}x{h}: only {checked} texels checked"
        );
    }
}

/// Storages written by the previous formats (version 1: the pyramid padded in the corner;
/// version 2: no content checksum, the buffer's alignment recorded) are refused with
/// `UnsupportedVersion` and a message that says to rebuild, by both loaders of both
/// distributions, rather than sampled with the wrong placement or loaded unchecked.
#[test]
fn older_version_storages_are_refused() {
    assert_eq!(FORMAT_VERSION, 3);
    let (w, h) = (181usize, 181usize);
    let wts = weights(w, h, 90);
    for version in [1u32, 2] {
        let mut hs = build(&wts, w, h);
        let mut ms = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        MarginalConditional::new(&wts, w, h, &mut ms).unwrap();
        for s in [&mut hs, &mut ms] {
            assert_eq!(u32::from_le(s[1]), 3);
            s[1] = version.to_le();
        }
        let old = Error::UnsupportedVersion { found: version };
        assert_eq!(Hierarchical::from_storage(&hs).err(), Some(old));
        assert_eq!(Hierarchical::from_storage_verified(&hs).err(), Some(old));
        assert_eq!(MarginalConditional::from_storage(&ms).err(), Some(old));
        assert_eq!(
            MarginalConditional::from_storage_verified(&ms).err(),
            Some(old)
        );
        let msg = old.to_string();
        assert!(msg.contains("older") && msg.contains("rebuild"), "{msg}");
    }
    let newer = Error::UnsupportedVersion { found: 4 }.to_string();
    assert!(!newer.contains("older"), "{newer}");
}

/// Generic over [`Distribution`]: one function serves both distributions, and the trait's
/// methods give the inherent methods' bits at every width.
#[test]
fn generic_over_the_distribution_trait() {
    use warpcore::envmap::{Distribution, Sample};
    use warpcore::{f32x8, f32x16};

    fn check<D: Distribution>(
        d: &D,
        inherent: impl Fn([f32; 2]) -> (Sample, f32),
        w: usize,
        h: usize,
    ) {
        assert_eq!((d.width(), d.height()), (w, h));
        let mut r = rng(7);
        let us: Vec<[f32; 2]> = (0..37).map(|_| unit2(&mut r)).collect();
        let mut out = vec![
            Sample {
                uv: [0.0; 2],
                pdf: 0.0,
                texel: [0; 2]
            };
            us.len()
        ];
        assert_eq!(d.sample_slice(&us, &mut out), us.len());
        let uvs: Vec<[f32; 2]> = out.iter().map(|s| s.uv).collect();
        let mut pdfs = vec![0.0f32; us.len()];
        assert_eq!(d.pdf_slice(&uvs, &mut pdfs), us.len());
        for (k, &u) in us.iter().enumerate() {
            let s = d.sample(u);
            let (si, pi) = inherent(u);
            assert_eq!(s, si);
            assert_eq!(out[k], s);
            assert_eq!(d.pdf(s.uv).to_bits(), pi.to_bits());
            assert_eq!(pdfs[k].to_bits(), s.pdf.to_bits());
        }
        let chunk: [[f32; 2]; 16] = core::array::from_fn(|j| us[j]);
        let x16 = d.sample_x16([0, 1].map(|a| f32x16::from(chunk.map(|u| u[a]))));
        let x8 = d.sample_x8(
            [0, 1].map(|a| f32x8::from(core::array::from_fn::<f32, 8, _>(|j| chunk[j][a]))),
        );
        let p16 = d.pdf_x16([0, 1].map(|a| f32x16::from(chunk.map(|u| d.sample(u).uv[a]))));
        let p8 = d.pdf_x8([0, 1].map(|a| {
            f32x8::from(core::array::from_fn::<f32, 8, _>(|j| {
                d.sample(chunk[j]).uv[a]
            }))
        }));
        for j in 0..16 {
            assert_eq!(x16.to_array()[j], d.sample(chunk[j]));
            assert_eq!(
                p16.to_array()[j].to_bits(),
                d.sample(chunk[j]).pdf.to_bits()
            );
            if j < 8 {
                assert_eq!(x8.to_array()[j], d.sample(chunk[j]));
                assert_eq!(p8.to_array()[j].to_bits(), d.sample(chunk[j]).pdf.to_bits());
            }
        }
    }
    let (w, h) = (181usize, 181usize);
    let wts = weights(w, h, 95);
    let hs = build(&wts, w, h);
    let hm = Hierarchical::from_storage(&hs).unwrap();
    check(
        &hm,
        |u| {
            let s = hm.sample(u);
            (s, hm.pdf(s.uv))
        },
        w,
        h,
    );
    let mut ms = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    let mm = MarginalConditional::new(&wts, w, h, &mut ms).unwrap();
    check(
        &mm,
        |u| {
            let s = mm.sample(u);
            (s, mm.pdf(s.uv))
        },
        w,
        h,
    );
}
