//! MIS compensation (issue 25): `new_compensated` builds the tables of
//! `max(0, w - fraction * average)` (lat-long: of the radiance, over solid angle), falling
//! back to the weights as given when nothing would be left. Checked against an independent
//! `f64` reference: the reported pdf integrates to 1, is 0 exactly where compensation removed
//! the texel and proportional to the compensated weight elsewhere; no sample lands on a
//! removed texel; the fallbacks build the uncompensated tables word for word.
#![cfg(feature = "envmap")]

use warpcore_testkit as common;

use common::{rng, unit2};
use rand::RngExt;
use std::f64::consts::PI;
use warpcore::envmap::{
    Compensation, Distribution, Error, Hierarchical, MarginalConditional, Sample, Word,
};

/// Weights `1 + 10^(3 r)` with a quarter zeros; no weight within 1e-3 relative of the
/// compensation threshold `t` (so `f32` row factors cannot move a texel across it).
fn weights(w: usize, h: usize, seed: u64) -> Vec<f32> {
    let mut r = rng(seed);
    (0..w * h)
        .map(|_| {
            if r.random::<u32>() % 4 == 0 {
                0.0
            } else {
                1.0 + 10f32.powf(3.0 * r.random::<f32>())
            }
        })
        .collect()
}

/// The compensated weights, in `f64`, from the definition (not the library's code).
fn reference(wts: &[f32], w: usize, h: usize, how: Compensation) -> Vec<f64> {
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
        .map(|k| (wts[k].max(0.0) as f64 - sub * factor(k / w)).max(0.0))
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
    let total: f64 = want.iter().sum();
    let avg = 1.0 / (w * h) as f64;
    let mut sum = 0.0;
    let mut removed = 0;
    for r in 0..h {
        for c in 0..w {
            let p = d.pdf(centre(c, r, w, h)) as f64 / (w * h) as f64;
            sum += p;
            let x = want[r * w + c] / total;
            if x == 0.0 {
                assert_eq!(p, 0.0, "{label} [{c}, {r}] removed");
                removed += 1;
            } else if x >= avg / 16.0 {
                assert!((p / x - 1.0).abs() < 1e-4, "{label} [{c}, {r}]: {p} vs {x}");
            }
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
