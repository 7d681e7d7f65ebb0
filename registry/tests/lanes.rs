//! Every lane and slice form equals the scalar form, bit for bit, for every function of the
//! registry with typed bodies: `_x8` and `_x16` lane by lane (on targets without 16-lane
//! vectors `wide` emulates `f32x16` as two halves, on AVX-512 it uses other instructions:
//! both must give the scalar bits), `_slice` element by element over lengths that leave
//! padded tails. Inputs: a cross product of special values (signed zeros, NaN with payloads,
//! infinities, subnormals, values past the ends), uniform points, and arbitrary bit
//! patterns; lights: the golden set and lights of arbitrary bits. On the same inputs, every
//! scalar output obeys the domain rule: finite and below `f32::MAX` in magnitude (never NaN,
//! never infinite, never a saturated density).
use warpcore::u32x16;
use warpcore_registry::lanes::{Source, bits_eq, check, l16};
use warpcore_registry::{Entry, Map};
use warpcore_testkit::{rng, specials};

fn check_all(src: &Source) {
    let typed = warpcore_registry::lanes::check_all(src);
    assert!(typed >= 40, "only {typed} entries have typed bodies");
}

/// Every pair of special values in every pair of coordinates (the rest cycling), words from
/// the edges of the index ranges.
#[test]
fn lane_forms_agree_on_special_values() {
    let sp = specials();
    let s = sp.len();
    let edges = [
        0u32,
        1,
        3,
        4,
        255,
        256,
        4095,
        4096,
        0x5555_5555,
        0xaaaa_aaaa,
        0x8000_0000,
        u32::MAX - 1,
        u32::MAX,
        65535,
        65536,
        7,
    ];
    check_all(&Source {
        name: "special",
        count: s * s * 2,
        point: Box::new(move |k, d| sp[(k / s.pow((d % 2) as u32) + d / 2) % s]),
        word: Box::new(move |k| edges[k % 16].rotate_left((k / 16) as u32)),
    });
}

/// Uniform points of `[0, 1)` and signed directions, random words.
#[test]
fn lane_forms_agree_on_uniform_points() {
    let n = 4096;
    let mut r = rng(16);
    let vals: Vec<f32> = (0..n * 17)
        .map(|_| warpcore_testkit::unit(&mut r))
        .collect();
    let words: Vec<u32> = (0..n + 64).map(|_| rand::RngExt::random(&mut r)).collect();
    check_all(&Source {
        name: "uniform",
        count: n,
        point: Box::new(move |k, d| {
            if d >= 2 {
                2.0 * vals[17 * k + d] - 1.0
            } else {
                vals[17 * k + d]
            }
        }),
        word: Box::new(move |k| words[k % words.len()]),
    });
}

/// Arbitrary bit patterns: every NaN payload, subnormal and out-of-range value.
#[test]
fn lane_forms_agree_on_any_bits() {
    let n = 4096;
    let mut r = rng(17);
    let words: Vec<u32> = (0..n * 17 + 64)
        .map(|_| rand::RngExt::random(&mut r))
        .collect();
    let w = words.clone();
    check_all(&Source {
        name: "arbitrary-bit",
        count: n,
        point: Box::new(move |k, d| f32::from_bits(w[17 * k + d])),
        word: Box::new(move |k| words[k % words.len()]),
    });
}

/// The check can fail: an entry whose `_x16` form is another map's is caught.
#[test]
#[should_panic(expected = "disk::polar _x16 differs")]
fn a_wrong_lane_form_is_caught() {
    use warpcore::disk;
    use warpcore_registry::{Forms, Kind};
    let wrong = Entry::new(
        "disk::polar",
        Forms::ALL,
        Kind::M22(Map {
            scalar: disk::polar,
            x8: Some(disk::polar_x8),
            x16: Some(disk::concentric_x16),
            slice: Some(disk::polar_slice),
        }),
    );
    let mut r = rng(3);
    let vals: Vec<f32> = (0..64).map(|_| warpcore_testkit::unit(&mut r)).collect();
    let src = Source {
        name: "uniform",
        count: 32,
        point: Box::new(move |k, d| vals[2 * k + d]),
        word: Box::new(|k| k as u32),
    };
    check(&wrong, &src);
}

/// The domain rule can fail: a density conversion that saturates `+inf` to `f32::MAX` (what
/// `sphere::equal_area_pdf_to_solid_angle` did before unbounded densities became 0) is
/// caught on the special values.
#[test]
#[should_panic(expected = "not finite, or saturated at f32::MAX")]
fn a_saturated_density_is_caught() {
    use warpcore_registry::{Forms, Kind};
    let saturating = Entry::new(
        "sphere::equal_area_pdf_to_solid_angle",
        Forms::SCALAR,
        Kind::M11(Map {
            scalar: |[p]| [if p > f32::MAX { f32::MAX } else { p.max(0.0) }],
            x8: None,
            x16: None,
            slice: None,
        }),
    );
    let sp = specials();
    let n = sp.len();
    let src = Source {
        name: "special",
        count: n.div_ceil(16) * 16,
        point: Box::new(move |k, _| sp[k % n]),
        word: Box::new(|k| k as u32),
    };
    check(&saturating, &src);
}

/// The two lane forms whose entries have no typed body (a stratum count beside the index, an
/// integer output): `sequence::stratified_x16` over edge counts and `pmj02bn::shuffle_x16`.
#[test]
fn stratified_and_shuffle_lanes_agree() {
    use warpcore::{pmj02bn, sequence};
    let mut r = rng(18);
    for _ in 0..256 {
        let i: [u32; 16] = std::array::from_fn(|_| rand::RngExt::random(&mut r));
        let s: [u32; 16] = std::array::from_fn(|_| rand::RngExt::random(&mut r));
        for count in [0u32, 1, 16, 17, 1024, u32::MAX] {
            let v = sequence::stratified_x16(u32x16::new(i), count, u32x16::new(s));
            for j in 0..16 {
                let want = sequence::stratified(i[j], count, s[j]);
                assert!(bits_eq(&l16(v, j), &want), "stratified {count}");
            }
        }
        let sh = pmj02bn::shuffle_x16(u32x16::new(i), u32x16::new(s)).to_array();
        for j in 0..16 {
            assert_eq!(sh[j], pmj02bn::shuffle(i[j], s[j]), "shuffle");
        }
    }
}
