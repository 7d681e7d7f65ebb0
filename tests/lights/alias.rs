//! The alias table and the weighted reservoir (`warpcore::lights`): the promises of DESIGN.md
//! Contract v4, "Light selection", tested from outside.
#![cfg(feature = "lights")]

use rand::RngExt;
use warpcore::lights::{AliasTable, Error, Reservoir};
use warpcore_testkit::{chi2, rng, specials, unit};
use wide::{f32x8, f32x16};

fn build(weights: &[f32]) -> Vec<u32> {
    let mut s = vec![0u32; AliasTable::storage_len(weights.len())];
    AliasTable::new(weights, &mut s).expect("valid weights");
    s
}

/// Weight sets that stress the construction: ragged, zeros mixed in, huge dynamic range,
/// subnormals, one dominant light, all equal, a single light.
fn weight_sets() -> Vec<(&'static str, Vec<f32>)> {
    let mut r = rng(33);
    let ragged: Vec<f32> = (0..1000)
        .map(|i| if i % 7 == 3 { 0.0 } else { unit(&mut r) * 10.0 })
        .collect();
    let range: Vec<f32> = (0..200)
        .map(|i| match i % 4 {
            0 => 1e-18,
            1 => 0.0,
            2 => 1.0,
            _ => 1e-9,
        })
        .collect();
    let subnormal: Vec<f32> = (1..300).map(|i| f32::from_bits(i * 37)).collect();
    let mut dominant = vec![1e-7f32; 500];
    dominant[250] = 1e7;
    let mut mixed_sub = vec![f32::from_bits(1); 64];
    mixed_sub[5] = f32::MAX;
    mixed_sub[9] = 0.0;
    vec![
        ("ragged", ragged),
        ("1e18 range", range),
        ("subnormal", subnormal),
        ("dominant", dominant),
        ("subnormal and MAX", mixed_sub),
        ("equal", vec![3.0; 37]),
        ("single", vec![0.25]),
        ("max", vec![f32::MAX; 17]),
    ]
}

/// The weight's share in f64, the reference the pmf approximates.
fn shares(weights: &[f32]) -> Vec<f64> {
    let total: f64 = weights.iter().map(|&w| f64::from(w)).sum();
    weights.iter().map(|&w| f64::from(w) / total).collect()
}

#[test]
fn pmf_sums_to_one_and_matches_the_weights() {
    for (name, weights) in weight_sets() {
        let s = build(&weights);
        let t = AliasTable::from_storage(&s).unwrap();
        assert_eq!(t.len(), weights.len());
        assert!(!t.is_empty());
        let n = weights.len() as f64;
        let sum: f64 = (0..t.len() as u32).map(|i| f64::from(t.pmf(i))).sum();
        assert!((sum - 1.0).abs() < 1e-5, "{name}: pmf sums to {sum}");
        let mut worst = 0.0f64;
        for (i, (&w, share)) in weights.iter().zip(shares(&weights)).enumerate() {
            let p = f64::from(t.pmf(i as u32));
            if w == 0.0 {
                assert_eq!(p, 0.0, "{name}: light {i}");
                continue;
            }
            assert!(p > 0.0, "{name}: positive light {i} has pmf 0");
            // Documented bound: 2^-32 (1 + 1/n) absolute plus 2^-24 relative.
            let bound = 2f64.powi(-32) * (1.0 + 1.0 / n) + share * 2f64.powi(-24);
            worst = worst.max((p - share).abs() / bound);
            assert!(
                (p - share).abs() <= bound,
                "{name}: light {i}: {p} vs {share}"
            );
        }
        eprintln!("{name}: worst |pmf - w/W| = {worst:.3} of the documented bound");
        assert_eq!(t.pmf(weights.len() as u32), 0.0);
        assert_eq!(t.pmf(u32::MAX), 0.0);
    }
}

#[test]
fn sample_returns_exactly_pmf_and_never_a_zero_weight() {
    for (name, weights) in weight_sets() {
        let s = build(&weights);
        let t = AliasTable::from_storage(&s).unwrap();
        let mut r = rng(1);
        let mut us: Vec<f32> = (0..20_000).map(|_| unit(&mut r)).collect();
        us.extend(specials());
        // Every column's boundaries: u just below and at k / n.
        for k in 0..=weights.len().min(2000) {
            let x = k as f32 / weights.len() as f32;
            us.extend([x, f32::from_bits(x.to_bits().wrapping_sub(1)), x.next_up()]);
        }
        for &u in &us {
            let (i, p) = t.sample(u);
            assert!((i as usize) < weights.len(), "{name}: u = {u}");
            assert_eq!(p.to_bits(), t.pmf(i).to_bits(), "{name}: u = {u}");
            assert!(
                weights[i as usize] > 0.0,
                "{name}: zero weight {i} at u = {u}"
            );
        }
    }
}

/// Every f32 in [0, 1) on a table with many zero weights around each positive one: the
/// exhaustive form of "never a zero weight" (2^30 values, run on 1 in 64 of them).
#[test]
fn zero_weights_are_never_chosen_for_any_u() {
    let weights: Vec<f32> = (0..1013)
        .map(|i| match i % 5 {
            0 => 1.0 + i as f32,
            3 => 1e-30,
            _ => 0.0,
        })
        .collect();
    let s = build(&weights);
    let t = AliasTable::from_storage(&s).unwrap();
    let mut bits = 0u32;
    while bits < 0x3f80_0000 {
        let (i, p) = t.sample(f32::from_bits(bits));
        assert!(weights[i as usize] > 0.0 && p > 0.0, "u bits {bits:#x}");
        bits += 63;
    }
}

fn histogram(counts: &[u64]) -> chi2::Histogram {
    let mut h = chi2::Histogram::new(counts.len(), 1);
    h.counts.copy_from_slice(counts);
    h.total = counts.iter().sum();
    h
}

#[test]
fn frequencies_match_pmf_chi_square() {
    // alpha: the suite's Sidak-corrected level (testkit::chi2); 2^21 samples each.
    for (name, weights) in weight_sets() {
        // Sets where one light holds nearly all the mass ("dominant", "subnormal and MAX")
        // leave no second bin to test.
        let bins = shares(&weights)
            .iter()
            .filter(|&&p| p * chi2::SAMPLES as f64 >= 5.0)
            .count();
        if bins < 3 {
            continue;
        }
        let s = build(&weights);
        let t = AliasTable::from_storage(&s).unwrap();
        let mut r = rng(7);
        let mut counts = vec![0u64; weights.len()];
        for _ in 0..chi2::SAMPLES {
            counts[t.sample(unit(&mut r)).0 as usize] += 1;
        }
        let p: Vec<f64> = (0..t.len() as u32).map(|i| f64::from(t.pmf(i))).collect();
        let total: f64 = p.iter().sum();
        let p: Vec<f64> = p.iter().map(|x| x / total).collect();
        chi2::check(&format!("alias {name}"), &histogram(&counts), &p);
    }
}

/// Power: the frequencies of a table are rejected against a slightly different pmf.
#[test]
fn chi_square_rejects_a_wrong_pmf() {
    let weights: Vec<f32> = (1..=64).map(|i| i as f32).collect();
    let s = build(&weights);
    let t = AliasTable::from_storage(&s).unwrap();
    let mut r = rng(8);
    let mut counts = vec![0u64; 64];
    for _ in 0..chi2::SAMPLES {
        counts[t.sample(unit(&mut r)).0 as usize] += 1;
    }
    let wrong: Vec<f64> = (1..=64).map(|i| (i as f64).powf(1.05)).collect();
    let total: f64 = wrong.iter().sum();
    let wrong: Vec<f64> = wrong.iter().map(|x| x / total).collect();
    let out = chi2::statistic(&histogram(&counts), &wrong).unwrap();
    assert!(out.p_value < chi2::per_test_alpha(), "{out:?}");
}

/// A stratified u: equally spaced values give every column its share to within one, and
/// split each column between its light and its alias to within one more (the column from
/// the high bits, the threshold from the rest), so the counts deviate from `pmf * m` by at
/// most 4 per column in all; independent uniform u deviate by about 30 per light here.
#[test]
fn stratified_u_keeps_the_counts_within_rounding() {
    let weights: Vec<f32> = (0..100).map(|i| ((i * 37) % 11) as f32).collect();
    let s = build(&weights);
    let t = AliasTable::from_storage(&s).unwrap();
    let m = 1usize << 18;
    let deviation = |u: &mut dyn FnMut(usize) -> f32| {
        let mut counts = vec![0u64; weights.len()];
        for k in 0..m {
            counts[t.sample(u(k)).0 as usize] += 1;
        }
        (0..weights.len())
            .map(|i| (counts[i] as f64 - f64::from(t.pmf(i as u32)) * m as f64).abs())
            .sum::<f64>()
    };
    let stratified = deviation(&mut |k| (k as f32 + 0.5) / m as f32);
    let mut r = rng(10);
    let random = deviation(&mut |_| unit(&mut r));
    eprintln!("sum |count - expected|: stratified {stratified:.1}, random {random:.1}");
    assert!(stratified <= 4.0 * weights.len() as f64, "{stratified}");
    assert!(random > 4.0 * weights.len() as f64, "{random}");
}

#[test]
fn lane_and_slice_forms_are_bit_identical() {
    let (_, weights) = weight_sets().swap_remove(0);
    let s = build(&weights);
    let t = AliasTable::from_storage(&s).unwrap();
    let mut r = rng(9);
    let mut us: Vec<f32> = specials();
    us.extend((0..4000).map(|_| unit(&mut r)));
    us.extend((0..100).map(|_| f32::from_bits(r.random::<u32>())));
    for chunk in us.chunks_exact(16) {
        let a: [f32; 16] = chunk.try_into().unwrap();
        let (i16, p16) = t.sample_x16(f32x16::new(a));
        let (i16, p16) = (i16.to_array(), p16.to_array());
        for h in 0..2 {
            let b: [f32; 8] = a[8 * h..8 * h + 8].try_into().unwrap();
            let (i8, p8) = t.sample_x8(f32x8::new(b));
            let (i8, p8) = (i8.to_array(), p8.to_array());
            for j in 0..8 {
                let (i, p) = t.sample(b[j]);
                assert_eq!((i8[j], p8[j].to_bits()), (i, p.to_bits()));
                assert_eq!((i16[8 * h + j], p16[8 * h + j].to_bits()), (i, p.to_bits()));
            }
        }
    }
    for len in [0, 1, 7, 8, 9, 23, us.len()] {
        let mut idx = vec![u32::MAX; len + 3];
        let mut prob = vec![-1.0f32; len];
        let got = t.sample_slice(&us[..len], &mut idx, &mut prob);
        assert_eq!(got, len);
        for k in 0..len {
            let (i, p) = t.sample(us[k]);
            assert_eq!((idx[k], prob[k].to_bits()), (i, p.to_bits()));
        }
        assert!(
            idx[len..].iter().all(|&i| i == u32::MAX),
            "wrote past the count"
        );
    }
}

#[test]
fn u_outside_the_unit_interval_follows_the_forward_rule() {
    let s = build(&[1.0, 2.0, 3.0, 4.0, 0.0, 5.0]);
    let t = AliasTable::from_storage(&s).unwrap();
    let top = t.sample(1.0 - 1.0 / 16_777_216.0);
    let bottom = t.sample(0.0);
    for u in [1.0, 1.5, f32::MAX, f32::INFINITY] {
        assert_eq!(t.sample(u), top, "{u}");
    }
    for u in [-0.0, -1.0, f32::MIN, f32::NEG_INFINITY, f32::NAN, -f32::NAN] {
        assert_eq!(t.sample(u), bottom, "{u}");
    }
}

#[test]
fn hostile_builds_give_clear_errors() {
    let mut s = vec![0u32; AliasTable::storage_len(4)];
    assert_eq!(AliasTable::new(&[], &mut s).unwrap_err(), Error::Empty);
    assert_eq!(
        AliasTable::new(&[0.0, -0.0, 0.0], &mut s).unwrap_err(),
        Error::AllZero
    );
    for (k, bad) in [
        f32::NAN,
        -f32::NAN,
        f32::INFINITY,
        f32::NEG_INFINITY,
        -1.0,
        -1e-45,
    ]
    .into_iter()
    .enumerate()
    {
        let w = [1.0, 2.0, bad, 3.0];
        assert_eq!(
            AliasTable::new(&w, &mut s).unwrap_err(),
            Error::InvalidWeight { index: 2 },
            "case {k}"
        );
    }
    let mut short = vec![0u32; AliasTable::storage_len(4) - 1];
    assert_eq!(
        AliasTable::new(&[1.0; 4], &mut short).unwrap_err(),
        Error::StorageTooSmall {
            needed: AliasTable::storage_len(4),
            got: short.len()
        }
    );
    assert_eq!(
        AliasTable::storage_len(AliasTable::MAX_LIGHTS + 1),
        usize::MAX
    );
    // Larger storage: the rest stays untouched, and the table reads only its own words.
    let mut big = vec![0xdead_beefu32; AliasTable::storage_len(3) + 5];
    let t = AliasTable::new(&[1.0, 0.0, 1.0], &mut big).unwrap();
    assert_eq!(t.storage().len(), AliasTable::storage_len(3));
    assert!(
        big[AliasTable::storage_len(3)..]
            .iter()
            .all(|&w| w == 0xdead_beef)
    );
}

#[test]
fn every_single_bit_flip_is_rejected() {
    for weights in [
        vec![1.0f32, 0.0, 2.5, 1e-20, 7.0],
        vec![3.0],
        vec![0.0, 0.0, 1.0],
    ] {
        let s = build(&weights);
        let t0 = AliasTable::from_storage_verified(&s).unwrap();
        let reference: Vec<_> = (0..64).map(|k| t0.sample(k as f32 / 64.0)).collect();
        for w in 0..s.len() {
            for b in 0..32 {
                let mut c = s.clone();
                c[w] ^= 1 << b;
                assert!(
                    AliasTable::from_storage_verified(&c).is_err(),
                    "flip of word {w} bit {b} accepted"
                );
                // The O(1) reader may accept it, but sampling stays valid.
                if let Ok(t) = AliasTable::from_storage(&c) {
                    for k in 0..64 {
                        let (i, p) = t.sample(k as f32 / 64.0);
                        assert!((i as usize) < t.len() && (0.0..=1.0).contains(&p));
                    }
                }
            }
        }
        let t = AliasTable::from_storage_verified(&s).unwrap();
        let again: Vec<_> = (0..64).map(|k| t.sample(k as f32 / 64.0)).collect();
        assert_eq!(again, reference);
    }
}

#[test]
fn garbage_storage_never_panics_and_samples_stay_valid() {
    let mut r = rng(11);
    for case in 0..3000 {
        let n = 1 + r.random::<u32>() as usize % 40;
        let mut s: Vec<u32> = (0..AliasTable::storage_len(n) + case % 3)
            .map(|_| r.random())
            .collect();
        if case % 2 == 0 {
            s[0] = u32::from_le_bytes(*b"wcAL");
            s[1] = 1;
            s[2] = n as u32;
            s[4..8].fill(0);
        }
        if case % 4 == 0 {
            s[8..].iter_mut().for_each(|w| *w &= 0x3fff_ffff);
        }
        let _ = AliasTable::from_storage_verified(&s);
        let Ok(t) = AliasTable::from_storage(&s) else {
            assert!(case % 2 == 1, "a well-formed header was refused");
            continue;
        };
        for u in specials().into_iter().chain((0..64).map(|_| unit(&mut r))) {
            let (i, p) = t.sample(u);
            assert!((i as usize) < t.len(), "index {i} of {}", t.len());
            assert!((0.0..=1.0).contains(&p), "probability {p}");
            let q = t.pmf(i);
            assert!((0.0..=1.0).contains(&q));
        }
    }
    for len in 0..12 {
        let s = vec![0u32; len];
        assert!(AliasTable::from_storage(&s).is_err());
    }
}

#[test]
fn the_bytes_are_a_function_of_the_weights() {
    let w = [0.5f32, 2.0, 0.0, 1.0];
    let mut a = vec![0u32; AliasTable::storage_len(4)];
    let mut b = vec![u32::MAX; AliasTable::storage_len(4)];
    AliasTable::new(&w, &mut a).unwrap();
    AliasTable::new(&w, &mut b).unwrap();
    assert_eq!(a, b);
    // Powers of two give exact masses: pmf = w / W exactly.
    let t = AliasTable::from_storage(&a).unwrap();
    assert_eq!(
        [0, 1, 2, 3].map(|i| t.pmf(i)),
        [0.5 / 3.5, 2.0 / 3.5, 0.0, 1.0 / 3.5].map(|x| x as f32)
    );
}

// ---- the reservoir ----

#[test]
fn reservoir_frequencies_match_weight_over_total_chi_square() {
    // alpha: the suite's Sidak-corrected level; 2^20 streams of 50 items each.
    let weights: Vec<f32> = (0..50)
        .map(|i| match i % 6 {
            0 => 0.0,
            1 => f32::NAN,
            2 => -3.0,
            _ => 1.0 + ((i * 13) % 17) as f32,
        })
        .collect();
    let valid: Vec<f64> = weights
        .iter()
        .map(|&w| if w > 0.0 { f64::from(w) } else { 0.0 })
        .collect();
    let total: f64 = valid.iter().sum();
    let expected: Vec<f64> = valid.iter().map(|w| w / total).collect();
    let mut r = rng(12);
    let mut counts = vec![0u64; weights.len()];
    let mut merged = vec![0u64; weights.len()];
    for _ in 0..1 << 20 {
        let mut a = Reservoir::new();
        for (i, &w) in weights.iter().enumerate() {
            a.update(i as u32, w, unit(&mut r));
        }
        let (i, p) = a.chosen().unwrap();
        assert_eq!(
            f64::from(p),
            ((f64::from(weights[i as usize])) / total) as f32 as f64
        );
        counts[i as usize] += 1;
        // The same stream split in two, merged: the same distribution.
        let (mut b, mut c) = (Reservoir::new(), Reservoir::new());
        for (i, &w) in weights.iter().enumerate() {
            let half = if i % 3 == 0 { &mut b } else { &mut c };
            half.update(i as u32, w, unit(&mut r));
        }
        b.merge(&c, unit(&mut r));
        let (i, p) = b.chosen().unwrap();
        assert!(expected[i as usize] > 0.0 && (f64::from(p) - expected[i as usize]).abs() < 1e-7);
        merged[i as usize] += 1;
    }
    chi2::check("reservoir", &histogram(&counts), &expected);
    chi2::check("reservoir merged", &histogram(&merged), &expected);
}

#[test]
fn reservoir_bad_weights_and_u() {
    let mut r = Reservoir::new();
    assert_eq!(r.chosen(), None);
    for (i, w) in [0.0, -0.0, -1.0, f32::NAN, f32::INFINITY, f32::NEG_INFINITY]
        .into_iter()
        .enumerate()
    {
        assert!(!r.update(i as u32, w, 0.0));
    }
    assert_eq!(r.chosen(), None);
    assert_eq!(r.total(), 0.0);
    // The first positive weight is always taken, for any u.
    for u in specials() {
        let mut r = Reservoir::new();
        assert!(r.update(7, 1e-45, u));
        assert_eq!(r.chosen(), Some((7, 1.0)));
        assert!(r.update(8, 3.0, u) || r.chosen() == Some((7, (1e-45f64 / (3.0 + 1e-45)) as f32)));
        let (_, p) = r.chosen().unwrap();
        assert!(p.is_finite() && (0.0..=1.0).contains(&p));
    }
    // Huge streams do not overflow the f64 total.
    let mut r = Reservoir::new();
    for i in 0..1000 {
        r.update(i, f32::MAX, 0.5);
    }
    let (_, p) = r.chosen().unwrap();
    assert!((p - 1e-3).abs() < 1e-9);
    assert_eq!(r.weight(), f32::MAX);
    // Merging an empty reservoir never takes it.
    let mut a = Reservoir::new();
    a.update(3, 2.0, 0.5);
    assert!(!a.merge(&Reservoir::new(), 0.0));
    assert_eq!(a.chosen(), Some((3, 1.0)));
}
