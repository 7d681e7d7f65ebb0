//! MIS compensation (issue 25): `new_compensated` builds the tables of
//! `max(0, w - fraction * average)` (lat-long: of the radiance, over solid angle), falling
//! back to the weights as given when nothing would be left. Checked against an independent
//! `f64` reference: the reported pdf integrates to 1, is 0 exactly where compensation removed
//! the texel and proportional to the compensated weight elsewhere; no sample lands on a
//! removed texel; the fallbacks build the uncompensated tables word for word.
#![cfg(feature = "envmap")]

use warpcore_testkit as common;

use common::{ONE_MINUS_EPS, rng, unit2};
use rand::RngExt;
use std::f64::consts::PI;
use warpcore::envmap::{
    Compensation, Distribution, Error, Hierarchical, MarginalConditional, Sample, Word,
};

/// Weights `1 + 10^(3 r)` with a quarter zeros; no weight within 1e-3 relative of the
/// compensation threshold `t` (so `f32` row factors cannot move a texel across it).
fn weights(w: usize, h: usize, seed: u64) -> Vec<f32> {
    super::random_weights(w, h, seed, |x| 1.0 + 10f32.powf(3.0 * x))
}

/// Per texel, row-major: `(column, row, pdf(centre) / (w h), want / sum(want))`, the
/// reported and the wanted probability.
fn shares<'a>(
    pdf: impl Fn([f32; 2]) -> f32 + 'a,
    w: usize,
    h: usize,
    want: &'a [f64],
) -> impl Iterator<Item = (usize, usize, f64, f64)> + 'a {
    let total: f64 = want.iter().sum();
    (0..w * h).map(move |t| {
        let (c, r) = (t % w, t / w);
        let p = pdf(centre(c, r, w, h)) as f64 / (w * h) as f64;
        (c, r, p, want[t] / total)
    })
}

/// The compensated weights, in `f64`, from the definition (not the library's code).
fn reference(wts: &[f32], w: usize, h: usize, how: Compensation) -> Vec<f64> {
    signed_reference(wts, w, h, how)
        .into_iter()
        .map(|c| c.max(0.0))
        .collect()
}

fn centre(c: usize, r: usize, w: usize, h: usize) -> [f32; 2] {
    [
        ((c as f64 + 0.5) / w as f64) as f32,
        ((r as f64 + 0.5) / h as f64) as f32,
    ]
}

/// The reported pdf against the reference: sums to 1, 0 exactly on removed texels, and
/// `pdf / (w h)` within 1e-4 relative of the compensated share for texels at least a
/// sixteenth of the average (both distributions' documented precision at these sizes).
fn check_against_reference<D: Distribution>(d: &D, want: &[f64], label: &str) {
    let (w, h) = (d.width(), d.height());
    let avg = 1.0 / (w * h) as f64;
    let mut sum = 0.0;
    let mut removed = 0;
    for (c, r, p, x) in shares(|uv| d.pdf(uv), w, h, want) {
        sum += p;
        if x == 0.0 {
            assert_eq!(p, 0.0, "{label} [{c}, {r}] removed");
            removed += 1;
        } else if x >= avg / 16.0 {
            assert!((p / x - 1.0).abs() < 1e-4, "{label} [{c}, {r}]: {p} vs {x}");
        }
    }
    assert!((sum - 1.0).abs() < 1e-6, "{label}: sum {sum}");
    assert!(
        removed > w * h / 3,
        "{label}: only {removed} texels removed"
    );
    // Sampling never returns a removed texel.
    let mut g = rng(5);
    for _ in 0..20_000 {
        let s = d.sample(unit2(&mut g));
        let k = s.texel[1] as usize * w + s.texel[0] as usize;
        assert!(want[k] > 0.0, "{label}: sampled removed texel {s:?}");
        assert_eq!(s.pdf.to_bits(), d.pdf(s.uv).to_bits());
    }
}

#[test]
fn compensated_pdf_is_the_compensated_share() {
    for (i, &(w, h)) in [(64usize, 32usize), (181, 181), (33, 17), (1, 40)]
        .iter()
        .enumerate()
    {
        let wts = weights(w, h, 1 + i as u64);
        for how in [
            Compensation::Uniform(1.0),
            Compensation::Uniform(0.5),
            Compensation::Equirect(1.0),
            Compensation::Equirect(0.75),
        ] {
            let want = reference(&wts, w, h, how);
            let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
            let d = Hierarchical::new_compensated(&wts, w, h, how, &mut s).unwrap();
            check_against_reference(&d, &want, &format!("hierarchical {w}x{h} {how:?}"));
            let mut s = vec![0 as Word; MarginalConditional::storage_len(w, h)];
            let d = MarginalConditional::new_compensated(&wts, w, h, how, &mut s).unwrap();
            check_against_reference(&d, &want, &format!("marginal {w}x{h} {how:?}"));
        }
    }
}

/// Storage words of a build (the header included): equal storages sample the same bits.
fn words(wts: &[f32], w: usize, h: usize, how: Compensation, hier: bool) -> Vec<Word> {
    // Aligned to 64 bytes, so that the hierarchical alignment padding is the same each time.
    let n = if hier {
        Hierarchical::storage_len(w, h)
    } else {
        MarginalConditional::storage_len(w, h)
    };
    let mut v = vec![0 as Word; n + 16];
    let skip = (64 - v.as_ptr() as usize % 64) % 64 / 4;
    let s = &mut v[skip..skip + n];
    if hier {
        Hierarchical::new_compensated(wts, w, h, how, s).unwrap();
    } else {
        MarginalConditional::new_compensated(wts, w, h, how, s).unwrap();
    }
    s.to_vec()
}

/// No compensation (`None`, NaN, zero, negative fractions) builds `new`'s tables; so does the
/// fallback when compensation would remove everything: a constant map at fraction 1 (and
/// more), an all-zero map, `+inf`.
#[test]
fn fallbacks_build_the_uncompensated_tables() {
    let (w, h) = (13usize, 7usize);
    let wts = weights(w, h, 9);
    let constant = vec![2.5f32; w * h];
    let zero = vec![0.0f32; w * h];
    for hier in [false, true] {
        for map in [&wts, &constant, &zero] {
            let plain = words(map, w, h, Compensation::None, hier);
            for how in [
                Compensation::Uniform(f32::NAN),
                Compensation::Uniform(0.0),
                Compensation::Uniform(-1.0),
                Compensation::Equirect(-0.0),
                Compensation::Uniform(f32::INFINITY),
                Compensation::Equirect(f32::INFINITY),
            ] {
                assert_eq!(words(map, w, h, how, hier), plain, "{hier} {how:?}");
            }
        }
        for how in [Compensation::Uniform(1.0), Compensation::Uniform(3.0)] {
            assert_eq!(
                words(&constant, w, h, how, hier),
                words(&constant, w, h, Compensation::None, hier)
            );
            assert_eq!(
                words(&zero, w, h, how, hier),
                words(&zero, w, h, Compensation::None, hier)
            );
        }
        // And a real compensation does change the tables.
        assert_ne!(
            words(&wts, w, h, Compensation::Uniform(1.0), hier),
            words(&wts, w, h, Compensation::None, hier)
        );
    }
    assert_eq!(Compensation::default(), Compensation::None);
}

/// A lat-long map of constant radiance (weights `sin(theta_row)`, as
/// `equirect_solid_angle_weights` makes them) is removed entirely by `LatLong(1.0)` (the
/// fallback), while `Uniform(1.0)` would wrongly keep its equator rows only.
#[test]
fn latlong_compensation_divides_out_the_row_factor() {
    let (w, h) = (16usize, 64usize);
    let mut wts = vec![1.0f32; w * h];
    warpcore::envmap::image::equirect_solid_angle_weights(&mut wts, w, h).unwrap();
    let plain = words(&wts, w, h, Compensation::None, true);
    assert_eq!(words(&wts, w, h, Compensation::Equirect(1.0), true), plain);
    let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let d = Hierarchical::new_compensated(&wts, w, h, Compensation::Uniform(1.0), &mut s).unwrap();
    assert_eq!(d.pdf([0.5, 0.5 / h as f32]), 0.0, "polar row kept");
    assert!(d.pdf([0.5, 0.5]) > 0.0, "equator removed");
}

#[test]
fn compensated_builds_report_errors() {
    let (w, h) = (5usize, 3usize);
    let mut wts = weights(w, h, 3);
    wts[7] = f32::INFINITY;
    for how in [Compensation::Uniform(1.0), Compensation::Equirect(1.0)] {
        let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
        assert_eq!(
            Hierarchical::new_compensated(&wts, w, h, how, &mut s).err(),
            Some(Error::InfiniteWeight { index: 7 })
        );
        let mut s = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        assert_eq!(
            MarginalConditional::new_compensated(&wts, w, h, how, &mut s).err(),
            Some(Error::InfiniteWeight { index: 7 })
        );
    }
    // NaN and negative weights weigh 0 before compensating.
    let mut wts = weights(w, h, 4);
    wts[0] = f32::NAN;
    wts[1] = -5.0;
    let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let d = Hierarchical::new_compensated(&wts, w, h, Compensation::Uniform(0.1), &mut s).unwrap();
    assert_eq!(d.pdf(centre(0, 0, w, h)), 0.0);
    assert_eq!(d.pdf(centre(1, 0, w, h)), 0.0);
    let _: Sample = d.sample([0.5, 0.5]);
}

/// The fuzz finding of a compensated 2 x 33 map (`fuzz/corpus/envmap/93216fcb...`,
/// decoded): its only positive weight is the smallest subnormal, `2^-149`, at texel `[0, 2]`
/// (the others 0, NaN or negative), at `Uniform(42.426)`. Compensation leaves that texel
/// `2^-149 (1 - 42.426 / 66)`, positive but below half the smallest `f32` subnormal, so it is
/// the whole distribution: every `u` must give texel `[0, 2]` at density `66` (all of the
/// probability on one texel of a 66-texel map) — never a zero-weight texel.
#[test]
fn compensated_subnormal_only_weight_is_sampled() {
    let (w, h) = (2usize, 33usize);
    let mut wts = vec![0.0f32; w * h];
    wts[0] = f32::from_bits(0xffff_ffff); // NaN
    wts[1] = f32::from_bits(0xff7e_ffff); // -3.4e38
    wts[2] = f32::from_bits(0xfffe_fffd); // NaN
    wts[3] = f32::from_bits(0xff5b_ffff); // -2.9e38
    wts[4] = f32::from_bits(1); // 1e-45, texel [0, 2]
    let how = Compensation::Uniform(f32::from_bits(0x6e84_5368u32.rotate_left(7)));
    assert_eq!(how, Compensation::Uniform(42.42599));
    let mut hs = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let hier = Hierarchical::new_compensated(&wts, w, h, how, &mut hs).unwrap();
    let mut ms = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    let marg = MarginalConditional::new_compensated(&wts, w, h, how, &mut ms).unwrap();
    let mut g = rng(36);
    let us = [[0.0, 0.0], [0.5, 0.5], [ONE_MINUS_EPS; 2]]
        .into_iter()
        .chain((0..1000).map(|_| unit2(&mut g)));
    for u in us {
        for (name, s, at) in [
            ("hierarchical", hier.sample(u), hier.pdf(hier.sample(u).uv)),
            ("marginal", marg.sample(u), marg.pdf(marg.sample(u).uv)),
        ] {
            assert_eq!(s.texel, [0, 2], "{name} {u:?}");
            assert_eq!(s.pdf, 66.0, "{name} {u:?}");
            assert_eq!(at.to_bits(), s.pdf.to_bits(), "{name} {u:?}");
        }
    }
    assert_eq!(hier.pdf(centre(0, 0, w, h)), 0.0);
    assert_eq!(marg.pdf(centre(0, 0, w, h)), 0.0);
}

/// Property: on small maps (powers of two and centred non-powers of two) whose only positive
/// weights are subnormal — the others 0, NaN, `-0.0` or negative — both distributions, with
/// and without compensation (`Uniform` and `Equirect` at fractions that remove some, most or
/// all texels), agree on the support: no texel with zero compensated weight (the `f64`
/// reference above; the weights as given when it removes everything) has a positive pdf or
/// is ever sampled, and every texel the reference keeps has a positive pdf (hierarchical:
/// those with at least `2^-20` of the total, far above its documented `2^-30`-per-axis
/// resolution). The pdfs are consistent: they sum to 1 over the texels (within 1e-6), agree
/// with the reference share within 1e-4 for texels of at least a sixteenth of the average,
/// and `pdf(sample.uv) == sample.pdf`, finite and positive. 1,600 maps (cases too close to
/// the compensation threshold for `f32` row factors to decide are skipped and counted),
/// 64 samples each.
#[test]
fn subnormal_maps_agree_between_distributions() {
    let sizes = [
        (1usize, 1usize),
        (2, 2),
        (4, 4),
        (8, 2),
        (16, 4),
        (2, 33),
        (33, 2),
        (3, 5),
        (5, 3),
        (7, 7),
        (13, 9),
        (1, 13),
    ];
    let mut g = rng(3636);
    let (mut cases, mut skipped, mut compensated) = (0, 0, 0);
    for i in 0..1600 {
        let (w, h) = sizes[i % sizes.len()];
        // Subnormal magnitudes: single ulps, small multiples, or all 23 bits.
        let top = [1u32, 2, 16, 0x7f_ffff][(i / sizes.len()) % 4];
        let mut wts: Vec<f32> = (0..w * h)
            .map(|_| match g.random::<u32>() % 8 {
                0 | 1 => f32::from_bits(1 + g.random::<u32>() % top),
                2 => f32::NAN,
                3 => -f32::from_bits(g.random::<u32>() >> 1).abs(),
                4 => -0.0,
                _ => 0.0,
            })
            .collect();
        if !wts.iter().any(|x| *x > 0.0) {
            wts[g.random::<u32>() as usize % (w * h)] = f32::from_bits(1 + g.random::<u32>() % top);
        }
        let fraction = [
            0.5f32,
            1.0,
            42.426,
            2.0 * g.random::<f32>() * (w * h) as f32,
        ][i % 4];
        let how = [
            Compensation::None,
            Compensation::Uniform(fraction),
            Compensation::Equirect(fraction),
        ][(i / 4) % 3];
        let comp = reference(&wts, w, h, how);
        let raw: Vec<f64> = wts.iter().map(|&x| x.max(0.0) as f64).collect();
        // The fallback: nothing left after compensation.
        let want = if comp.iter().any(|&x| x > 0.0) {
            comp
        } else {
            raw.clone()
        };
        // Skip maps where a positive texel sits within 1e-6 (relative) of the threshold:
        // the library's f32 row factors and its rounding of the average may decide it
        // either way.
        let near = wts
            .iter()
            .zip(signed_reference(&wts, w, h, how))
            .any(|(&x, c)| x > 0.0 && c.abs() < 1e-6 * x as f64);
        if near {
            skipped += 1;
            continue;
        }
        cases += 1;
        compensated += usize::from(want != raw);
        let label = format!("{w}x{h} {how:?} {wts:?}");
        let mut hs = vec![0 as Word; Hierarchical::storage_len(w, h)];
        let hier = Hierarchical::new_compensated(&wts, w, h, how, &mut hs).unwrap();
        let mut ms = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        let marg = MarginalConditional::new_compensated(&wts, w, h, how, &mut ms).unwrap();
        let check = |d: &dyn super::Dist, hier: bool| {
            let name = if hier { "hierarchical" } else { "marginal" };
            let mut sum = 0.0;
            for (c, r, p, x) in shares(|uv| d.pdf(uv), w, h, &want) {
                sum += p;
                if x == 0.0 {
                    assert_eq!(p, 0.0, "{name} [{c}, {r}] zero weight, {label}");
                } else if !hier || x >= 1.0 / (1u64 << 20) as f64 {
                    assert!(p > 0.0, "{name} [{c}, {r}] unreachable, {label}");
                }
                if x >= 1.0 / (16 * w * h) as f64 {
                    assert!(
                        (p / x - 1.0).abs() < 1e-4,
                        "{name} [{c}, {r}]: {p} vs {x}, {label}"
                    );
                }
            }
            assert!((sum - 1.0).abs() < 1e-6, "{name}: sum {sum}, {label}");
            let mut u = rng(i as u64);
            for k in 0..64 {
                let u = match k {
                    0 => [0.0, 0.0],
                    1 => [ONE_MINUS_EPS; 2],
                    _ => unit2(&mut u),
                };
                let s = d.sample(u);
                let at = d.pdf(s.uv);
                let t = s.texel[1] as usize * w + s.texel[0] as usize;
                assert!(
                    want[t] > 0.0,
                    "{name} {u:?}: zero-weight texel {:?}, {label}",
                    s.texel
                );
                assert!(
                    s.pdf.is_finite() && s.pdf > 0.0,
                    "{name}: pdf {}, {label}",
                    s.pdf
                );
                assert_eq!(s.pdf.to_bits(), at.to_bits(), "{name}: pdf(uv), {label}");
            }
        };
        check(&hier, true);
        check(&marg, false);
    }
    eprintln!(
        "{cases} maps checked ({compensated} compensated, not the fallback), {skipped} skipped"
    );
    assert!(
        cases >= 1500 && compensated >= 300,
        "{cases} cases, {compensated} compensated"
    );
}

/// `w - fraction * average * factor` before the `max(0, ..)` of [`reference`].
fn signed_reference(wts: &[f32], w: usize, h: usize, how: Compensation) -> Vec<f64> {
    let row = |r: usize| (PI * (r as f64 + 0.5) / h as f64).sin();
    let (fraction, latlong) = match how {
        Compensation::Uniform(f) => (f as f64, false),
        Compensation::Equirect(f) => (f as f64, true),
        _ => (0.0, false),
    };
    let factor = |r: usize| if latlong { row(r) } else { 1.0 };
    let total: f64 = wts.iter().map(|&x| x.max(0.0) as f64).sum();
    let measure: f64 = (0..h).map(factor).sum::<f64>() * w as f64;
    let sub = fraction * total / measure;
    (0..w * h)
        .map(|k| wts[k].max(0.0) as f64 - sub * factor(k / w))
        .collect()
}
