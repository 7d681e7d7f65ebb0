//! The light tree's promises (DESIGN.md, Contract v4, "Light selection"), tested from outside.

use rand::RngExt;
use warpcore::lights::{Error, LightBounds, LightTree};
use warpcore_testkit::{chi2, rng};
use wide::{f32x8, f32x16, u32x8, u32x16};

type R = rand_xoshiro::Xoshiro256PlusPlus;

fn unit_vec(r: &mut R) -> [f32; 3] {
    loop {
        let v: [f32; 3] = core::array::from_fn(|_| r.random::<f32>() * 2.0 - 1.0);
        let l = v.iter().map(|x| x * x).sum::<f32>();
        if l > 0.01 && l <= 1.0 {
            let l = l.sqrt();
            return v.map(|x| x / l);
        }
    }
}

/// A mixed scene: small one-sided area lights facing every way, two-sided ones, spots and
/// points, clustered, with some zero powers.
fn scene(r: &mut R, n: usize, zeros: bool) -> Vec<LightBounds> {
    (0..n)
        .map(|k| {
            let cluster = (k % 4) as f32 * 3.0;
            let c: [f32; 3] = core::array::from_fn(|i| {
                r.random::<f32>() * 4.0 - 2.0 + if i == 0 { cluster } else { 0.0 }
            });
            let h: [f32; 3] = core::array::from_fn(|_| r.random::<f32>() * 0.1);
            let kind = r.random_range(0..4);
            let (cos_o, cos_e, two_sided) = match kind {
                0 => (1.0, 0.0, false),
                1 => (1.0, 0.0, true),
                2 => (0.9, 0.5, false),
                _ => (-1.0, 0.0, false),
            };
            let power = if zeros && k % 7 == 3 {
                0.0
            } else {
                r.random::<f32>() * 10.0 + 0.01
            };
            LightBounds {
                min: core::array::from_fn(|i| c[i] - h[i]),
                max: core::array::from_fn(|i| c[i] + h[i]),
                power,
                axis: unit_vec(r),
                cos_theta_o: cos_o,
                cos_theta_e: cos_e,
                two_sided,
            }
        })
        .collect()
}

/// Omnidirectional point lights: no importance is ever 0 at a finite point, so no walk
/// meets a dead end and the probabilities sum to 1.
fn omni(r: &mut R, n: usize) -> Vec<LightBounds> {
    (0..n)
        .map(|_| {
            let c: [f32; 3] = core::array::from_fn(|_| r.random::<f32>() * 10.0 - 5.0);
            LightBounds {
                min: c,
                max: c,
                power: r.random::<f32>() * 5.0 + 0.1,
                axis: [0.0, 0.0, 1.0],
                cos_theta_o: -1.0,
                cos_theta_e: 0.0,
                two_sided: false,
            }
        })
        .collect()
}

fn build(lights: &[LightBounds]) -> Vec<u32> {
    let mut s = vec![0u32; LightTree::storage_len(lights.len())];
    LightTree::new(lights, &mut s).expect("valid lights");
    s
}

fn point(r: &mut R) -> ([f32; 3], [f32; 3]) {
    let p = core::array::from_fn(|_| r.random::<f32>() * 16.0 - 4.0);
    let n = if r.random::<f32>() < 0.3 {
        [0.0; 3]
    } else {
        unit_vec(r)
    };
    (p, n)
}

#[test]
fn pmf_sums_to_one_without_dead_ends() {
    let mut r = rng(1);
    for &n in &[1, 2, 3, 7, 64, 1000] {
        let lights = omni(&mut r, n);
        let s = build(&lights);
        let t = LightTree::from_storage(&s).unwrap();
        for _ in 0..200 {
            let (p, nn) = point(&mut r);
            let sum: f64 = (0..n as u32).map(|i| f64::from(t.pmf(p, nn, i))).sum();
            assert!((sum - 1.0).abs() < 1e-5, "n {n}: sum {sum} at {p:?} {nn:?}");
        }
    }
}

#[test]
fn pmf_sum_plus_dead_ends_is_one_and_sample_matches_pmf() {
    let mut r = rng(2);
    for &n in &[1, 5, 33, 500] {
        let lights = scene(&mut r, n, true);
        let s = build(&lights);
        let t = LightTree::from_storage_verified(&s).unwrap();
        assert_eq!(t.len(), n);
        assert!(!t.is_empty());
        // The storage round trip: the words read back give the same tree.
        let words = t.storage().to_vec();
        assert_eq!(words, s);
        let back = LightTree::from_storage_verified(&words).unwrap();
        assert_eq!(
            back.sample([0.1, 0.2, 0.3], [0.0; 3], 0.4),
            t.sample([0.1, 0.2, 0.3], [0.0; 3], 0.4)
        );
        for _ in 0..100 {
            let (p, nn) = point(&mut r);
            let sum: f64 = (0..n as u32).map(|i| f64::from(t.pmf(p, nn, i))).sum();
            assert!(sum <= 1.0 + 1e-5, "sum {sum}");
            for _ in 0..50 {
                let u = r.random::<f32>();
                if let Some((i, q)) = t.sample(p, nn, u) {
                    assert!((i as usize) < n);
                    assert!((f32::MIN_POSITIVE..=1.0).contains(&q));
                    assert_eq!(q.to_bits(), t.pmf(p, nn, i).to_bits(), "sample != pmf");
                    assert!(lights[i as usize].power > 0.0, "zero-power light chosen");
                }
            }
            // Zero-power lights have pmf 0.
            for (i, l) in lights.iter().enumerate() {
                if l.power == 0.0 {
                    assert_eq!(t.pmf(p, nn, i as u32), 0.0);
                }
            }
            assert_eq!(t.pmf(p, nn, n as u32), 0.0);
            assert_eq!(t.pmf(p, nn, u32::MAX), 0.0);
        }
    }
}

/// Frequencies vs `pmf`, with the mass of `None` in its own cell: 2^21 samples per point,
/// four points, 64 lights (with zeros) plus the `None` cell; Sidak-corrected level of the
/// suite (testkit::chi2).
#[test]
fn chi_square_frequencies_match_pmf() {
    let mut r = rng(3);
    let lights = scene(&mut r, 64, true);
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    for case in 0..4 {
        let (p, nn) = point(&mut r);
        let cells = lights.len() + 1;
        let mut expected: Vec<f64> = (0..lights.len() as u32)
            .map(|i| f64::from(t.pmf(p, nn, i)))
            .collect();
        let sum: f64 = expected.iter().sum();
        if sum == 0.0 {
            continue;
        }
        expected.push((1.0 - sum).max(0.0));
        let mut h = chi2::Histogram::new(cells, 1);
        for _ in 0..chi2::SAMPLES {
            let cell = match t.sample(p, nn, r.random::<f32>()) {
                Some((i, _)) => i as usize,
                None => lights.len(),
            };
            h.add([(cell as f64 + 0.5) / cells as f64, 0.5]);
        }
        chi2::check(&format!("light tree, point {case}"), &h, &expected);
    }
}

/// Lights facing away from `p` (one-sided, cosine falloff ending at 90 degrees, well beyond
/// the stored bounds' rounding) are never chosen and have pmf 0.
#[test]
fn lights_facing_away_are_never_chosen() {
    let mut r = rng(4);
    let mut lights = Vec::new();
    for k in 0..200 {
        let x = k as f32 * 0.1;
        // Even: facing +z (towards p above), odd: facing -z (away).
        let axis = if k % 2 == 0 {
            [0.0, 0.0, 1.0]
        } else {
            [0.0, 0.0, -1.0]
        };
        lights.push(LightBounds {
            min: [x, 0.0, 0.0],
            max: [x + 0.05, 0.05, 0.0],
            power: 1.0,
            axis,
            cos_theta_o: 1.0,
            cos_theta_e: 0.0,
            two_sided: false,
        });
    }
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    for _ in 0..100 {
        let p = [
            r.random::<f32>() * 20.0,
            r.random::<f32>() * 4.0 - 2.0,
            1.0 + r.random::<f32>() * 5.0,
        ];
        for k in (1..200).step_by(2) {
            assert_eq!(t.pmf(p, [0.0, 0.0, -1.0], k), 0.0);
        }
        for _ in 0..100 {
            if let Some((i, _)) = t.sample(p, [0.0, 0.0, -1.0], r.random()) {
                assert_eq!(i % 2, 0, "a light facing away was chosen");
            }
        }
        let sum: f64 = (0..200)
            .map(|i| f64::from(t.pmf(p, [0.0, 0.0, -1.0], i)))
            .sum();
        assert!(sum <= 1.0 + 1e-5);
    }
    // Below every light, all face away (or are edge-on): nothing contributes.
    let p = [10.0, 0.0, -3.0];
    let sum: f32 = (0..200).map(|i| t.pmf(p, [0.0; 3], i)).sum::<f32>();
    let odd: f32 = (0..200)
        .filter(|i| i % 2 == 0)
        .map(|i| t.pmf(p, [0.0; 3], i))
        .sum::<f32>();
    assert_eq!(odd, 0.0, "lights facing up chosen from below");
    assert!(sum <= 1.0 + 1e-5);
}

#[test]
fn where_nothing_contributes_sample_is_none() {
    let lights = [LightBounds {
        min: [0.0; 3],
        max: [1.0, 1.0, 0.0],
        power: 1.0,
        axis: [0.0, 0.0, 1.0],
        cos_theta_o: 1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    }; 3];
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    for u in [0.0, 0.3, 0.999] {
        assert_eq!(t.sample([0.5, 0.5, -2.0], [0.0; 3], u), None);
    }
    for i in 0..3 {
        assert_eq!(t.pmf([0.5, 0.5, -2.0], [0.0; 3], i), 0.0);
    }
    // Above: the three identical lights share the probability.
    let q: Vec<f32> = (0..3)
        .map(|i| t.pmf([0.5, 0.5, 2.0], [0.0; 3], i))
        .collect();
    let sum: f32 = q.iter().sum();
    assert!((sum - 1.0).abs() < 1e-6, "{q:?}");
}

#[test]
fn hostile_inputs_to_new() {
    let good = LightBounds {
        min: [0.0; 3],
        max: [1.0; 3],
        power: 1.0,
        axis: [0.0, 0.0, 2.0],
        cos_theta_o: 1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    };
    let mut s = vec![0u32; LightTree::storage_len(3)];
    assert_eq!(LightTree::new(&[], &mut s).unwrap_err(), Error::Empty);
    let with = |f: &dyn Fn(&mut LightBounds)| {
        let mut l = [good; 3];
        f(&mut l[1]);
        l
    };
    for bad in [
        f32::NAN,
        f32::INFINITY,
        -1.0,
        f32::NEG_INFINITY,
        -f32::MIN_POSITIVE,
    ] {
        let l = with(&|l| l.power = bad);
        let mut s = vec![0u32; LightTree::storage_len(3)];
        assert_eq!(
            LightTree::new(&l, &mut s).unwrap_err(),
            Error::InvalidWeight { index: 1 }
        );
    }
    let cases: [fn(&mut LightBounds); 9] = [
        |l| l.min[0] = f32::NAN,
        |l| l.max[2] = f32::INFINITY,
        |l| l.min[1] = 2.0,
        |l| l.axis = [0.0; 3],
        |l| l.axis = [f32::NAN, 0.0, 1.0],
        |l| l.axis = [f32::INFINITY, 0.0, 1.0],
        |l| l.cos_theta_o = 1.5,
        |l| l.cos_theta_e = -1.0001,
        |l| l.cos_theta_e = f32::NAN,
    ];
    for f in cases {
        let l = with(&f);
        let mut s = vec![0u32; LightTree::storage_len(3)];
        assert_eq!(
            LightTree::new(&l, &mut s).unwrap_err(),
            Error::InvalidBounds { index: 1 }
        );
    }
    let zero = [LightBounds { power: 0.0, ..good }; 4];
    let mut s = vec![0u32; LightTree::storage_len(4)];
    assert_eq!(LightTree::new(&zero, &mut s).unwrap_err(), Error::AllZero);
    let mut small = vec![0u32; LightTree::storage_len(3) - 1];
    assert!(matches!(
        LightTree::new(&[good; 3], &mut small).unwrap_err(),
        Error::StorageTooSmall { .. }
    ));
    assert_eq!(LightTree::storage_len((1 << 24) + 1), usize::MAX);
    // `new_from_fn` builds the same words as `new`, errors included.
    let mut r = rng(11);
    let lights = scene(&mut r, 77, true);
    let mut s2 = vec![0u32; LightTree::storage_len(77)];
    LightTree::new_from_fn(77, |i| lights[i], &mut s2).unwrap();
    assert_eq!(s2, build(&lights));
    let mut s3 = vec![0u32; LightTree::storage_len(3)];
    assert_eq!(
        LightTree::new_from_fn(3, |i| with(&|l| l.power = -1.0)[i], &mut s3).unwrap_err(),
        Error::InvalidWeight { index: 1 }
    );
    // A non-unit axis is normalised: the same tree as the unit one.
    let a = build(&[good; 3]);
    let b = build(
        &[LightBounds {
            axis: [0.0, 0.0, 1.0],
            ..good
        }; 3],
    );
    assert_eq!(a, b);
    // Huge but finite boxes build and sample validly.
    let huge = [
        LightBounds {
            min: [-f32::MAX; 3],
            max: [f32::MAX; 3],
            ..good
        },
        good,
    ];
    let s = build(&huge);
    let t = LightTree::from_storage(&s).unwrap();
    if let Some((i, q)) = t.sample([0.5; 3], [0.0; 3], 0.5) {
        assert!(i < 2 && (f32::MIN_POSITIVE..=1.0).contains(&q));
    }
}

#[test]
fn hostile_points_and_u() {
    let mut r = rng(5);
    let lights = scene(&mut r, 100, true);
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    let sp = warpcore_testkit::specials();
    for &a in &sp {
        for &b in &sp {
            let p = [a, b, 1.0];
            let n = [b, 0.0, a];
            for &u in &sp {
                if let Some((i, q)) = t.sample(p, n, u) {
                    assert!((i as usize) < lights.len() && (f32::MIN_POSITIVE..=1.0).contains(&q));
                    assert_eq!(q.to_bits(), t.pmf(p, n, i).to_bits());
                }
            }
            let q = t.pmf(p, n, 3);
            assert!((0.0..=1.0).contains(&q));
        }
    }
    // A non-finite point: no light.
    assert_eq!(t.sample([f32::NAN, 0.0, 0.0], [0.0; 3], 0.5), None);
    assert_eq!(t.sample([f32::INFINITY, 0.0, 0.0], [0.0; 3], 0.5), None);
}

#[test]
fn every_single_bit_flip_is_rejected() {
    let mut r = rng(6);
    let lights = scene(&mut r, 5, true);
    let s = build(&lights);
    assert!(LightTree::from_storage_verified(&s).is_ok());
    let mut flipped = s.clone();
    for w in 0..s.len() {
        for b in 0..32 {
            flipped[w] ^= 1 << b;
            assert!(
                LightTree::from_storage_verified(&flipped).is_err(),
                "flip of bit {b} of word {w} accepted"
            );
            flipped[w] ^= 1 << b;
        }
    }
}

#[test]
fn garbage_storage_never_panics_and_stays_valid() {
    let mut r = rng(7);
    let lights = scene(&mut r, 40, true);
    let s = build(&lights);
    for trial in 0..300 {
        let mut g = s.clone();
        // Keep the header (so from_storage passes), fill the rest with garbage of several kinds.
        for w in g.iter_mut().skip(16) {
            *w = match trial % 3 {
                0 => r.random(),
                1 => [
                    0,
                    u32::MAX,
                    0x7f80_0000,
                    0xffc0_0000,
                    0x8000_0000,
                    1,
                    0x3fff_ffff,
                ][r.random_range(0..7)],
                _ => r.random::<u32>() & 0x4000_00ff | if r.random() { 0x8000_0000 } else { 0 },
            };
        }
        let t = LightTree::from_storage(&g).unwrap();
        for _ in 0..50 {
            let (p, n) = point(&mut r);
            if let Some((i, q)) = t.sample(p, n, r.random()) {
                // Valid, though not necessarily `pmf(i)`: garbage leaves can name one light twice.
                assert!((i as usize) < lights.len() && (f32::MIN_POSITIVE..=1.0).contains(&q));
            }
            let q = t.pmf(p, n, r.random_range(0..45));
            assert!((0.0..=1.0).contains(&q));
        }
    }
    // Headers that are not a tree's.
    let mut g = s.clone();
    g[0] ^= 1;
    assert!(matches!(
        LightTree::from_storage(&g),
        Err(Error::WrongFormat { .. })
    ));
    // Version 1 (8-word nodes, octahedral axis) and later versions are refused.
    for version in [1, 3, 9] {
        let mut g = s.clone();
        g[1] = version;
        assert_eq!(
            LightTree::from_storage(&g).err(),
            Some(Error::UnsupportedVersion { found: version })
        );
    }
    for (word, value) in [(2, 0), (2, 41), (3, 0), (3, 41), (4, 9), (5, 1), (15, 1)] {
        let mut g = s.clone();
        g[word] = value;
        assert!(
            LightTree::from_storage(&g).is_err(),
            "word {word} = {value} accepted"
        );
    }
    assert!(LightTree::from_storage(&s[..s.len() - 1]).is_err());
    assert!(LightTree::from_storage(&[]).is_err());
}

#[test]
fn lanes_and_slices_match_scalar() {
    let mut r = rng(8);
    let lights = scene(&mut r, 300, true);
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    let sp = warpcore_testkit::specials();
    for round in 0..200 {
        let pts: Vec<([f32; 3], [f32; 3], f32, u32)> = (0..16)
            .map(|j| {
                let (mut p, mut n) = point(&mut r);
                let mut u = r.random::<f32>();
                if round % 4 == 0 {
                    p[j % 3] = sp[(round + j) % sp.len()];
                    n[(j + 1) % 3] = sp[(round * 3 + j) % sp.len()];
                    u = sp[(round * 7 + j) % sp.len()];
                }
                (p, n, u, r.random_range(0..310))
            })
            .collect();
        let scalar: Vec<Option<(u32, f32)>> =
            pts.iter().map(|&(p, n, u, _)| t.sample(p, n, u)).collect();
        let pmfs: Vec<f32> = pts.iter().map(|&(p, n, _, i)| t.pmf(p, n, i)).collect();
        let as_pair = |o: Option<(u32, f32)>| o.map_or((u32::MAX, 0), |(i, q)| (i, q.to_bits()));
        let p8 = |k: usize, o: usize| f32x8::new(core::array::from_fn(|j| pts[o + j].0[k]));
        let n8 = |k: usize, o: usize| f32x8::new(core::array::from_fn(|j| pts[o + j].1[k]));
        for o in [0, 8] {
            let (i, q) = t.sample_x8(
                [0, 1, 2].map(|k| p8(k, o)),
                [0, 1, 2].map(|k| n8(k, o)),
                f32x8::new(core::array::from_fn(|j| pts[o + j].2)),
            );
            let pm = t.pmf_x8(
                [0, 1, 2].map(|k| p8(k, o)),
                [0, 1, 2].map(|k| n8(k, o)),
                u32x8::new(core::array::from_fn(|j| pts[o + j].3)),
            );
            for j in 0..8 {
                assert_eq!(
                    (i.to_array()[j], q.to_array()[j].to_bits()),
                    as_pair(scalar[o + j])
                );
                assert_eq!(pm.to_array()[j].to_bits(), pmfs[o + j].to_bits());
            }
        }
        let p16 = |k: usize| f32x16::new(core::array::from_fn(|j| pts[j].0[k]));
        let n16 = |k: usize| f32x16::new(core::array::from_fn(|j| pts[j].1[k]));
        let (i, q) = t.sample_x16(
            [0, 1, 2].map(p16),
            [0, 1, 2].map(n16),
            f32x16::new(core::array::from_fn(|j| pts[j].2)),
        );
        let pm = t.pmf_x16(
            [0, 1, 2].map(p16),
            [0, 1, 2].map(n16),
            u32x16::new(core::array::from_fn(|j| pts[j].3)),
        );
        for j in 0..16 {
            assert_eq!(
                (i.to_array()[j], q.to_array()[j].to_bits()),
                as_pair(scalar[j])
            );
            assert_eq!(pm.to_array()[j].to_bits(), pmfs[j].to_bits());
        }
        let len = 1 + round % 16;
        let ps: Vec<[f32; 3]> = pts.iter().map(|x| x.0).collect();
        let ns: Vec<[f32; 3]> = pts.iter().map(|x| x.1).collect();
        let us: Vec<f32> = pts.iter().map(|x| x.2).collect();
        let mut out = vec![Some((7, 7.0)); 16];
        assert_eq!(t.sample_slice(&ps[..len], &ns, &us, &mut out), len);
        for j in 0..16 {
            let want = if j < len {
                as_pair(scalar[j])
            } else {
                (7, 7.0f32.to_bits())
            };
            assert_eq!(as_pair(out[j]), want);
        }
    }
}

/// A stratified `u` stays stratified: with sorted `u`, the chosen lights' leaf order is
/// monotone (each level splits `u`'s interval in two in a fixed order).
#[test]
fn u_order_is_kept() {
    let mut r = rng(9);
    let lights = omni(&mut r, 100);
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    let (p, n) = ([0.3, 0.2, 0.1], [0.0; 3]);
    // The cumulative pmf in the tree's leaf order is what sorted u walks through: the number
    // of distinct lights among 4096 stratified u equals that of distinct runs.
    let mut last = None;
    let mut runs = 0;
    let mut seen = std::collections::HashSet::new();
    for k in 0..4096 {
        let u = (k as f32 + 0.5) / 4096.0;
        let (i, _) = t.sample(p, n, u).unwrap();
        if last != Some(i) {
            runs += 1;
            last = Some(i);
        }
        seen.insert(i);
    }
    assert_eq!(runs, seen.len(), "a light's u values are not one interval");
}

#[test]
fn large_tree_builds() {
    let mut r = rng(10);
    let lights = scene(&mut r, 100_000, true);
    let start = std::time::Instant::now();
    let s = build(&lights);
    eprintln!("built 100,000 lights in {:?}", start.elapsed());
    let t = LightTree::from_storage_verified(&s).unwrap();
    for _ in 0..100 {
        let (p, n) = point(&mut r);
        if let Some((i, q)) = t.sample(p, n, r.random()) {
            assert_eq!(q.to_bits(), t.pmf(p, n, i).to_bits());
        }
    }
}

/// The walk in `f64` over the same stored words (the documented layout), as a reference for
/// the `f32` probabilities: the same importance formula, the same two binary choices per
/// level, every operation in `f64`.
fn pmf_f64(s: &[u32], p: [f32; 3], n: [f32; 3], index: u32) -> f64 {
    let len = s[2] as usize;
    let levels = s[4];
    let quads = 16;
    let trails = 16 + 48 * (len / 3 + 14);
    let trail = s[trails + index as usize];
    let p = p.map(f64::from);
    let n = {
        let n = n.map(f64::from);
        let l = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        if l > 0.0 && l.is_finite() {
            n.map(|x| x / l)
        } else {
            [0.0; 3]
        }
    };
    let has_n = n != [0.0; 3];
    let importance = |w: [u32; 12]| -> f64 {
        let f = |k: usize| f64::from(f32::from_bits(w[k]));
        let d = [p[0] - f(0), p[1] - f(1), p[2] - f(2)];
        let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
        let (r, phi) = (f(3), f(4));
        let inside = d2 < r * r;
        let inv = if d2 > 0.0 { 1.0 / d2.sqrt() } else { 0.0 };
        let (x, y, z) = (f(5), f(6), f(7));
        let l = (x * x + y * y + z * z).sqrt();
        let axis = [x / l, y / l, z / l];
        let mut cos_w = (axis[0] * d[0] + axis[1] * d[1] + axis[2] * d[2]) * inv;
        if w[11] & (1 << 30) != 0 {
            cos_w = cos_w.abs();
        }
        let sin_w = (1.0 - cos_w * cos_w).max(0.0).sqrt();
        let (cos_o, cos_e) = (f(8), f(10));
        let sin_o = (1.0 - cos_o * cos_o).max(0.0).sqrt();
        let sin_b0 = (r * inv).max(0.0);
        let (cos_b, sin_b) = if inside {
            (-1.0, 0.0)
        } else {
            ((1.0 - sin_b0 * sin_b0).max(0.0).sqrt(), sin_b0)
        };
        let sub =
            |ca: f64, sa: f64, cb: f64, sb: f64| if cb < ca { 1.0 } else { ca * cb + sa * sb };
        let cos_x = sub(cos_w, sin_w, cos_o, sin_o);
        let sin_x = if cos_o < cos_w {
            0.0
        } else {
            sin_w * cos_o - cos_w * sin_o
        };
        let cos_p = sub(cos_x, sin_x, cos_b, sin_b);
        let cos_i = (d[0] * n[0] + d[1] * n[1] + d[2] * n[2]).abs() * inv;
        let sin_i = (1.0 - cos_i * cos_i).max(0.0).sqrt();
        let cos_pi = if has_n {
            sub(cos_i, sin_i, cos_b, sin_b)
        } else {
            1.0
        };
        let dc = (if inside { r * r } else { d2 }).max(f64::from(f32::MIN_POSITIVE));
        if cos_e < cos_p {
            (phi * cos_p / dc * cos_pi).max(0.0)
        } else {
            0.0
        }
    };
    let mut quad = 0usize;
    let mut prob = 1.0f64;
    for level in 0..levels {
        let rec = &s[quads + 48 * quad..quads + 48 * quad + 48];
        let i: Vec<f64> = (0..4)
            .map(|c| importance(core::array::from_fn(|k| rec[4 * k + c])))
            .collect();
        let (s01, s23) = (i[0] + i[1], i[2] + i[3]);
        if s01 + s23 == 0.0 {
            return 0.0;
        }
        let high = trail >> (2 * level) & 1 != 0;
        let second = trail >> (2 * level + 1) & 1 != 0;
        let pair = if high { s23 } else { s01 };
        if pair == 0.0 {
            return 0.0;
        }
        prob *= pair / (s01 + s23);
        let first = if high { i[2] } else { i[0] };
        prob *= if second {
            1.0 - first / pair
        } else {
            first / pair
        };
        let slot = 2 * usize::from(high) + usize::from(second);
        let info = rec[44 + slot];
        if info & (1 << 31) != 0 {
            return if info & ((1 << 30) - 1) == index {
                prob
            } else {
                0.0
            };
        }
        quad = (info & ((1 << 30) - 1)) as usize;
    }
    0.0
}

/// The `f32` probabilities against the same walk in `f64` (measured bounds, stated in the
/// docs): 2000 points x every light of a 300-light scene. Absolute error everywhere; relative
/// error where the `f64` probability is at least 1e-3 (below, `1 - P` of a side near 1 has
/// the `f32` spacing of 1 as its absolute error, so the relative error grows as `1 / P`).
#[test]
fn pmf_against_f64() {
    let mut r = rng(12);
    let lights = scene(&mut r, 300, true);
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    let (mut abs, mut rel) = (0.0f64, 0.0f64);
    for _ in 0..2000 {
        let (p, n) = point(&mut r);
        for i in 0..300 {
            let want = pmf_f64(&s, p, n, i);
            let got = f64::from(t.pmf(p, n, i));
            abs = abs.max((got - want).abs());
            if want >= 1e-3 {
                rel = rel.max((got - want).abs() / want);
            }
        }
    }
    eprintln!(
        "light tree pmf vs f64: max absolute error {abs:.3e}, max relative error {rel:.3e} (P >= 1e-3)"
    );
    assert!(abs < 1e-6 && rel < 1e-4, "absolute {abs}, relative {rel}");
}

/// Scenes and points spanning the `f32` range: a light at `1e20` beside lights at 1 (its
/// group's `r^2` overflowed and the group's lights read importance 0), faint lights seen
/// from far away (`phi / d^2` underflowed to 0: `None` for a light that contributes), a
/// shading point at `1e30`, normals scaled by `1e-25` or `1e20` (read as "no normal" when
/// `|n|^2` underflowed or overflowed). Each against the `f64` walk of the same storage;
/// every light of positive `f64` probability must have a positive `pmf`.
#[test]
fn extreme_scales_drop_no_light() {
    let omni = |c: [f32; 3], power: f32| LightBounds {
        min: c,
        max: c,
        power,
        axis: [0.0, 0.0, 1.0],
        cos_theta_o: -1.0,
        cos_theta_e: 0.0,
        two_sided: false,
    };
    let check = |name: &str, lights: &[LightBounds], p: [f32; 3], n: [f32; 3]| {
        let s = build(lights);
        let t = LightTree::from_storage(&s).unwrap();
        let mut sum = 0.0f64;
        for i in 0..lights.len() as u32 {
            let want = pmf_f64(&s, p, n, i);
            let got = t.pmf(p, n, i);
            sum += f64::from(got);
            assert!(
                (f64::from(got) - want).abs() <= 1e-5 * want.max(1e-30) + 1e-12,
                "{name}: light {i} pmf {got:e}, f64 {want:e}"
            );
            // (A probability below f32's normal range may round to 0.)
            assert!(
                want < f64::from(f32::MIN_POSITIVE) || got > 0.0,
                "{name}: light {i} dropped (f64 {want:e})"
            );
        }
        assert!((sum - 1.0).abs() < 1e-5, "{name}: pmfs sum to {sum}");
        let (i, q) = t.sample(p, n, 0.5).expect("a light contributes");
        assert_eq!(q, t.pmf(p, n, i), "{name}");
    };
    // A far light beside five at 1 (the nearest shares its group: the group's bound, not an
    // overflow, then decides its share).
    for far in [2.6e19f32, 1e20, 1e30, 3e38] {
        let mut lights: Vec<_> = (0..5).map(|i| omni([i as f32, 0.0, 0.0], 1.0)).collect();
        lights.push(omni([far, 0.0, 0.0], 1.0));
        check("far light", &lights, [4.0, 1.0, 0.0], [0.0; 3]);
        // The same scene with the shading point's normal facing the near lights.
        check(
            "far light, normal",
            &lights,
            [4.0, 1.0, 0.0],
            [0.0, -1.0, 0.0],
        );
    }
    // Twenty unit lights in a box and one at 1e20 (a quarter of them went missing).
    let mut r = rng(31);
    let mut lights: Vec<_> = (0..20)
        .map(|_| omni(core::array::from_fn(|_| r.random::<f32>() * 8.0), 1.0))
        .collect();
    lights.push(omni([1e20, -1e20, 0.0], 1.0));
    for _ in 0..20 {
        let p: [f32; 3] = core::array::from_fn(|_| r.random::<f32>() * 8.0);
        check("twenty and a far one", &lights, p, [0.0; 3]);
    }
    // A faint light seen from far away; faint lights near and far.
    check("faint", &[omni([0.0; 3], 1e-30)], [1e8, 0.0, 0.0], [0.0; 3]);
    let mut lights = vec![omni([1.0, 0.0, 0.0], 1e-10)];
    for k in 0..5 {
        let sign = if k % 2 == 0 { 1.0 } else { -1.0 };
        lights.push(omni([sign * 1e18, k as f32, 0.0], 1e-10));
    }
    check("faint, near and far", &lights, [0.0; 3], [0.0; 3]);
    // A shading point far from the scene, and the scene far from the origin.
    let pair = [omni([0.0; 3], 1.0), omni([0.0, 1.0, 0.0], 2.0)];
    check("far point", &pair, [1e30, 0.0, 0.0], [0.0; 3]);
    check("far point", &pair, [3e38, -3e38, 0.0], [1.0, 0.0, 0.0]);
    let far_scene = [omni([1e25, 0.0, 0.0], 1.0), omni([1e25, 1e9, 0.0], 2.0)];
    check("far scene", &far_scene, [1e25, 2e9, 0.0], [0.0; 3]);
    // A normal of any finite length is the unit normal: bit for bit when scaled by a power of
    // two, to rounding otherwise.
    let lights = scene(&mut r, 40, false);
    check(
        "tiny normal",
        &lights,
        [0.5, 0.5, 0.5],
        [0.0, 0.6e-25, 0.8e-25],
    );
    check(
        "huge normal",
        &lights,
        [0.5, 0.5, 0.5],
        [0.0, 0.6e20, 0.8e20],
    );
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    for _ in 0..200 {
        let (p, n) = point(&mut r);
        if n == [0.0; 3] {
            continue;
        }
        for k in [-83, -100, 66, 120].map(|e: i32| 2f32.powi(e)) {
            let nk = n.map(|x| x * k);
            for i in 0..40 {
                assert_eq!(
                    t.pmf(p, nk, i).to_bits(),
                    t.pmf(p, n, i).to_bits(),
                    "normal scaled by {k:e}"
                );
            }
        }
    }
}

/// A hard-edged spot (`cos_theta_e = 1`: no falloff beyond `theta_o`) is chosen where `p`
/// lies inside its cone, never outside it (a strict `cos(theta') > cos(theta_e)` test never
/// chose it at all: a scene of such spots returned `None` everywhere).
#[test]
fn hard_edged_spots_are_chosen_inside_their_cone() {
    let spot = |c: [f32; 3], axis: [f32; 3]| LightBounds {
        min: c,
        max: c,
        power: 1.0,
        axis,
        cos_theta_o: 0.9,
        cos_theta_e: 1.0,
        two_sided: false,
    };
    let lights = [
        spot([0.0; 3], [0.0, 0.0, 1.0]),
        spot([4.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
    ];
    let s = build(&lights);
    let t = LightTree::from_storage(&s).unwrap();
    // On the first spot's axis, below the second: only the first lights it.
    let (i, q) = t
        .sample([0.0, 0.0, 3.0], [0.0; 3], 0.5)
        .expect("inside the first cone");
    assert_eq!((i, q), (0, 1.0));
    assert_eq!(t.pmf([0.0, 0.0, 3.0], [0.0; 3], 1), 0.0);
    // Below the second spot, inside its cone only.
    assert_eq!(t.sample([4.0, 0.0, -2.0], [0.0; 3], 0.25), Some((1, 1.0)));
    // Beside both, outside both cones: nothing.
    assert_eq!(t.sample([2.0, 0.0, 0.0], [0.0; 3], 0.5), None);
}
