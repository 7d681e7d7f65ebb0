//! Triangle warps: domain and barycentric sums on any input, bit identity across widths,
//! accuracy against f64, round trips, edge inputs, chi-square uniformity, and the Basu-Owen
//! structure (construction, stratification, nesting, Owen pair law, seed independence).
#![cfg(feature = "triangle")]
// Lane-by-lane comparisons index several arrays with one counter.
#![allow(clippy::needless_range_loop)]

use warpcore_testkit as common;

use common::textbook;

use common::{
    ONE_MINUS_EPS, chi2, in_unit_square, lane, rng, same_bits, special_pairs, special_triples,
    unit, unit2,
};
use proptest::prelude::*;
use rand::RngExt;
use warpcore::triangle;
use warpcore::{f32x8, u32x8};

const ULP1: f64 = 1.0 / 16_777_216.0; // 2^-24, one ulp of 1 from below

// ----------------------------------------------------------------------------------------
// f64 references: the published formulas, branches and all.

/// Heitz 2019 as published.
fn uniform_ref(u: [f32; 2]) -> [f64; 3] {
    let (u0, u1) = (u[0] as f64, u[1] as f64);
    let (b0, b1) = if u0 < u1 {
        (u0 / 2.0, u1 - u0 / 2.0)
    } else {
        (u0 - u1 / 2.0, u1 / 2.0)
    };
    [b0, b1, 1.0 - b0 - b1]
}

fn sqrt_ref(u: [f32; 2]) -> [f64; 3] {
    let s = (u[0] as f64).sqrt();
    [1.0 - s, u[1] as f64 * s, (1.0 - u[1] as f64) * s]
}

/// The Basu-Owen walk of DESIGN.md section 4 in f64 (exact).
fn basu_owen_ref(index: u32) -> [f64; 3] {
    textbook::basu_owen(index)
}

fn err3(b: [f32; 3], r: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (b[k] as f64 - r[k]).abs())
        .fold(0.0, f64::max)
}

/// Exact in f64 for the values tested here (all three within 2^-29 .. 1 of each other, or
/// tiny enough not to matter at the 2^-48 scale).
fn sum(b: [f32; 3]) -> f64 {
    b[0] as f64 + b[1] as f64 + b[2] as f64
}

/// Valid barycentrics: finite, each in [0, 1], and summing to 1 within one ulp of 1.
fn valid(b: [f32; 3]) -> bool {
    b.iter()
        .all(|&x| x.is_finite() && (0.0..=1.0).contains(&x) && x.to_bits() >> 31 == 0)
        && (sum(b) - 1.0).abs() <= ULP1
}

/// A uniform f32 in [2^-20, 1) with a full random mantissa (not on the 2^-24 grid), so
/// that f64 sums of the warps' outputs are exact.
fn fine(r: &mut impl RngExt) -> f32 {
    let e = r.random_range(0..20);
    f32::from_bits(((126 - e) << 23) | (r.random::<u32>() >> 9))
}

// ----------------------------------------------------------------------------------------
// Domain: any bit pattern gives valid barycentrics; inverses give points of [0, 1)^2.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn forward_warps_give_valid_barycentrics(a: u32, b: u32, index: u32, seed: u32) {
        let u = [f32::from_bits(a), f32::from_bits(b)];
        let (p, q) = (triangle::uniform(u), triangle::sqrt_map(u));
        prop_assert!(valid(p), "uniform {u:?} -> {p:?}");
        prop_assert!(valid(q), "sqrt_map {u:?} -> {q:?}");
        let o = triangle::basu_owen(index, seed);
        prop_assert!(valid(o) && sum(o) == 1.0, "basu_owen {index} {seed} -> {o:?}");
        let o = triangle::basu_owen_permuted(index, seed);
        prop_assert!(valid(o) && sum(o) == 1.0, "basu_owen_permuted {index} {seed} -> {o:?}");
        prop_assert!(o.iter().all(|&c| c >= 85.0 / 16_777_216.0 && (c * 16_777_216.0).fract() == 0.0));
    }

    #[test]
    fn inverses_stay_in_the_square(a: u32, b: u32, c: u32) {
        let p = [f32::from_bits(a), f32::from_bits(b), f32::from_bits(c)];
        prop_assert!(in_unit_square(triangle::uniform_inverse(p)));
        prop_assert!(in_unit_square(triangle::sqrt_map_inverse(p)));
    }

    /// Scalar, x8 and slice forms agree bit for bit on arbitrary bit patterns.
    #[test]
    fn widths_agree_on_any_bits(bits in prop::array::uniform24(any::<u32>()), index: [u32; 8], seed: [u32; 8]) {
        let pts: [[f32; 2]; 8] = std::array::from_fn(|j| [f32::from_bits(bits[2 * j]), f32::from_bits(bits[2 * j + 1])]);
        let bary: [[f32; 3]; 8] = std::array::from_fn(|j| [f32::from_bits(bits[3 * j]), f32::from_bits(bits[3 * j + 1]), f32::from_bits(bits[3 * j + 2])]);
        check_widths(&pts, &bary);
        check_basu_owen_widths(index, seed);
    }

    #[test]
    fn uniform_round_trip(u0 in 0f32..1.0, u1 in 0f32..1.0) {
        let back = triangle::uniform_inverse(triangle::uniform([u0, u1]));
        prop_assert!((back[0] - u0).abs() as f64 <= ULP1 && (back[1] - u1).abs() as f64 <= ULP1, "{u0} {u1} -> {back:?}");
    }

    #[test]
    fn sqrt_map_round_trip(u0 in 1e-14f32..1.0, u1 in 0f32..1.0) {
        let back = triangle::sqrt_map_inverse(triangle::sqrt_map([u0, u1]));
        prop_assert!((back[0] - u0).abs() <= 1.2e-7 && (back[1] - u1).abs() <= 1.2e-7, "{u0} {u1} -> {back:?}");
    }
}

/// Every width of every square-driven function on eight points: scalar, x8, and slices (full
/// groups and padded tails).
fn check_widths(pts: &[[f32; 2]; 8], bary: &[[f32; 3]; 8]) {
    type F = fn([f32; 2]) -> [f32; 3];
    type F8 = fn([f32x8; 2]) -> [f32x8; 3];
    type S = fn(&[[f32; 2]], &mut [[f32; 3]]) -> usize;
    let forward: [(&str, F, F8, S); 2] = [
        (
            "uniform",
            triangle::uniform,
            triangle::uniform_x8,
            triangle::uniform_slice,
        ),
        (
            "sqrt_map",
            triangle::sqrt_map,
            triangle::sqrt_map_x8,
            triangle::sqrt_map_slice,
        ),
    ];
    for (name, scalar, wide8, slice) in forward {
        common::check_widths(name, pts, scalar, wide8, slice);
    }
    type G = fn([f32; 3]) -> [f32; 2];
    type G8 = fn([f32x8; 3]) -> [f32x8; 2];
    type T = fn(&[[f32; 3]], &mut [[f32; 2]]) -> usize;
    let inverse: [(&str, G, G8, T); 2] = [
        (
            "uniform_inverse",
            triangle::uniform_inverse,
            triangle::uniform_inverse_x8,
            triangle::uniform_inverse_slice,
        ),
        (
            "sqrt_map_inverse",
            triangle::sqrt_map_inverse,
            triangle::sqrt_map_inverse_x8,
            triangle::sqrt_map_inverse_slice,
        ),
    ];
    for (name, scalar, wide8, slice) in inverse {
        common::check_widths(name, bary, scalar, wide8, slice);
    }
}

type Indexed = fn(u32, u32) -> [f32; 3];
type Indexed8 = fn(u32x8, u32x8) -> [f32x8; 3];
type IndexedSlice = fn(u32, u32, &mut [[f32; 3]]) -> usize;

/// Both Basu-Owen randomizations, with their three forms.
const BASU_OWEN: [(&str, Indexed, Indexed8, IndexedSlice); 2] = [
    (
        "basu_owen",
        triangle::basu_owen,
        triangle::basu_owen_x8,
        triangle::basu_owen_slice,
    ),
    (
        "basu_owen_permuted",
        triangle::basu_owen_permuted,
        triangle::basu_owen_permuted_x8,
        triangle::basu_owen_permuted_slice,
    ),
];

fn check_basu_owen_widths(index: [u32; 8], seed: [u32; 8]) {
    for (name, scalar, x8, slice) in BASU_OWEN {
        let v = x8(u32x8::new(index), u32x8::new(seed));
        for j in 0..8 {
            let s = scalar(index[j], seed[j]);
            assert!(
                same_bits(s, lane(v, j)),
                "{name} x8 lane {j}: {} {}",
                index[j],
                seed[j]
            );
            // The slice form from this index, for lane 0's seed (tails of every length).
            let mut out = [[9.0f32; 3]; 11];
            assert_eq!(slice(index[j], seed[0], &mut out[..11 - j]), 11 - j);
            for (k, o) in out.iter().enumerate() {
                let want = if k < 11 - j {
                    scalar(index[j].wrapping_add(k as u32), seed[0])
                } else {
                    [9.0; 3]
                };
                assert!(same_bits(*o, want), "{name} slice from {} [{k}]", index[j]);
            }
        }
    }
}

#[test]
fn widths_agree_on_special_values() {
    let pts = special_pairs();
    let bary = special_triples(&[0.0, 0.5, f32::NAN, -1.0]);
    for (group, bgroup) in pts.chunks_exact(8).zip(bary.chunks_exact(8)) {
        check_widths(group.try_into().unwrap(), bgroup.try_into().unwrap());
    }
    for &u in &pts {
        assert!(valid(triangle::uniform(u)), "{u:?}");
        assert!(valid(triangle::sqrt_map(u)), "{u:?}");
    }
    for &b in &bary {
        assert!(in_unit_square(triangle::uniform_inverse(b)), "{b:?}");
        assert!(in_unit_square(triangle::sqrt_map_inverse(b)), "{b:?}");
    }
    let edges = [
        0u32,
        1,
        2,
        3,
        4,
        15,
        16,
        255,
        256,
        0x5555_5555,
        0xaaaa_aaaa,
        u32::MAX - 1,
        u32::MAX,
    ];
    for &i in &edges {
        for &s in &edges {
            let o = triangle::basu_owen(i, s);
            assert!(valid(o) && sum(o) == 1.0, "{i} {s} -> {o:?}");
        }
    }
    check_basu_owen_widths(
        [
            0,
            1,
            u32::MAX,
            0x5555_5555,
            0xaaaa_aaaa,
            7,
            1 << 30,
            3 << 30,
        ],
        [0, 0, 1, u32::MAX, 0x8000_0000, 2, 0, 3],
    );
}

/// Slices of every length 0..=40 (and mismatched lengths) against the scalar form.
#[test]
fn slices_of_any_length() {
    let mut r = rng(7);
    let input: Vec<[f32; 2]> = (0..40).map(|_| unit2(&mut r)).collect();
    let bary: Vec<[f32; 3]> = input.iter().map(|&u| triangle::uniform(u)).collect();
    common::check_slice_lengths(&input, triangle::uniform, triangle::uniform_slice);
    common::check_slice_lengths(
        &bary,
        triangle::sqrt_map_inverse,
        triangle::sqrt_map_inverse_slice,
    );
    // Index-driven: fills the whole output, wrapping past u32::MAX.
    for n in 0..=40usize {
        let mut pts = vec![[7.0f32; 3]; n];
        let start = u32::MAX - 20;
        assert_eq!(triangle::basu_owen_slice(start, 99, &mut pts), n);
        for j in 0..n {
            let want = triangle::basu_owen(start.wrapping_add(j as u32), 99);
            assert!(same_bits(pts[j], want), "{j}");
        }
    }
    assert_eq!(triangle::uniform_slice(&[], &mut []), 0);
    assert_eq!(triangle::basu_owen_slice(0, 0, &mut []), 0);
}

// ----------------------------------------------------------------------------------------
// Accuracy against f64 and the barycentric sum.

/// Max coordinate error against the f64 formulas over 2^22 random points on the 2^-24 grid
/// and 2^22 off it; the sums are exactly 1 on the grid, and b2 is the remainder 1 - b0 - b1
/// rounded once (exactly, when it is representable) everywhere.
#[test]
fn forward_accuracy_and_sums() {
    let mut r = rng(11);
    let (mut eu, mut es) = (0.0f64, 0.0f64);
    let (mut su, mut ss) = (0.0f64, 0.0f64);
    let mut exact_cases = 0u32;
    for k in 0..(1 << 23) {
        let on_grid = k % 2 == 0;
        let u = if on_grid {
            unit2(&mut r)
        } else {
            [fine(&mut r), fine(&mut r)]
        };
        let b = triangle::uniform(u);
        let q = triangle::sqrt_map(u);
        eu = eu.max(err3(b, uniform_ref(u)));
        es = es.max(err3(q, sqrt_ref(u)));
        if on_grid {
            assert_eq!(sum(b), 1.0, "uniform sum on the grid: {u:?} -> {b:?}");
        }
        for (name, p, slack) in [("uniform", b, 2f64.powi(-49)), ("sqrt_map", q, 0.0)] {
            // The remainder, exact in f64 for these inputs.
            let rem = (1.0 - p[0] as f64) - p[1] as f64;
            let d = (p[2] as f64 - rem).abs();
            if rem as f32 as f64 == rem {
                exact_cases += 1;
                assert_eq!(
                    p[2] as f64, rem,
                    "{name} {u:?}: remainder representable but not hit"
                );
            } else {
                let ulp = (p[2].next_up() - p[2]) as f64;
                assert!(d <= ulp / 2.0 + slack, "{name} {u:?}: {d:e} > half an ulp");
            }
        }
        su = su.max((sum(b) - 1.0).abs());
        ss = ss.max((sum(q) - 1.0).abs());
    }
    eprintln!(
        "max error vs f64: uniform {eu:.3e}, sqrt_map {es:.3e}; max |sum - 1|: uniform {su:.3e}, sqrt_map {ss:.3e}; {exact_cases} exact remainders"
    );
    assert!(eu <= 4.5e-8 && es <= 8e-8, "{eu} {es}");
    let half = ULP1 / 2.0;
    assert!(su <= half + 2f64.powi(-49) && ss <= half, "{su} {ss}");
}

/// Near the corners and edges, where one coordinate is tiny: the small coordinates keep
/// their relative precision in `uniform` (the halved one is exact).
#[test]
fn uniform_small_coordinates() {
    for e in [1e-30f32, 1e-10, 1e-5, f32::MIN_POSITIVE] {
        for t in [0.0f32, 0.25, 0.5, 0.75, ONE_MINUS_EPS] {
            for u in [[e, t], [t, e], [e, e * 2.0], [e * 2.0, e]] {
                let b = triangle::uniform(u);
                let r = uniform_ref(u);
                for k in 0..2 {
                    let rel = ((b[k] as f64 - r[k]) / r[k].max(1e-300)).abs();
                    assert!(rel <= 6e-8 || r[k] == 0.0, "{u:?} -> {b:?} vs {r:?}");
                }
                assert!(err3(b, r) <= 4.5e-8 && valid(b));
            }
        }
    }
}

// ----------------------------------------------------------------------------------------
// Round trips and edge inputs.

/// Measured round-trip maxima over 2^22 random points (the figures in the doc comments),
/// and the other direction: warp(inverse(b)) = b for points of the triangle.
#[test]
fn round_trip_maxima() {
    let mut r = rng(5);
    let (mut mu, mut ms, mut bu, mut bs) = (0.0f32, 0.0f32, 0.0f64, 0.0f64);
    for _ in 0..(1 << 22) {
        let u = unit2(&mut r);
        let b = triangle::uniform_inverse(triangle::uniform(u));
        mu = mu.max((b[0] - u[0]).abs()).max((b[1] - u[1]).abs());
        if u[0] >= 1e-14 {
            let b = triangle::sqrt_map_inverse(triangle::sqrt_map(u));
            ms = ms.max((b[0] - u[0]).abs()).max((b[1] - u[1]).abs());
        }
        // Points of the triangle (b0 + b1 <= 1) back and forth, each warp on the other's
        // points (its own reproduce themselves too easily).
        let p = triangle::sqrt_map(unit2(&mut r));
        let back = triangle::uniform(triangle::uniform_inverse(p));
        bu = bu.max(err3(back, p.map(f64::from)));
        let p = triangle::uniform(unit2(&mut r));
        let back = triangle::sqrt_map(triangle::sqrt_map_inverse(p));
        bs = bs.max(err3(back, p.map(f64::from)));
    }
    eprintln!(
        "round trip max: uniform {mu:.3e}, sqrt_map {ms:.3e}; triangle -> square -> triangle: uniform {bu:.3e}, sqrt_map {bs:.3e}"
    );
    assert!(mu as f64 <= ULP1 && ms <= 1.2e-7, "{mu} {ms}");
    assert!(bu <= 1.2e-7 && bs <= 1.2e-7, "{bu} {bs}");
}

#[test]
fn edge_inputs() {
    // Corners of the square.
    assert_eq!(triangle::uniform([0.0, 0.0]), [0.0, 0.0, 1.0]);
    assert_eq!(triangle::sqrt_map([0.0, 0.3]), [1.0, 0.0, 0.0]);
    let top = [ONE_MINUS_EPS, ONE_MINUS_EPS];
    for b in [triangle::uniform(top), triangle::sqrt_map(top)] {
        assert!(valid(b) && b[2] > 0.0, "{b:?}");
    }
    assert!(err3(triangle::uniform(top), uniform_ref(top)) <= 4.5e-8);
    // The diagonal u0 == u1 and its neighbours: both cases of Heitz's map meet continuously.
    let mut r = rng(3);
    for _ in 0..10_000 {
        let t = unit(&mut r);
        for u in [
            [t, t],
            [t, t.next_up()],
            [t.next_up(), t],
            [t, t.next_down()],
        ] {
            if !in_unit_square(u) {
                continue;
            }
            let b = triangle::uniform(u);
            assert!(err3(b, uniform_ref(u)) <= 4.5e-8 && valid(b), "{u:?}");
            let back = triangle::uniform_inverse(b);
            assert!((back[0] - u[0]).abs() as f64 <= ULP1 && (back[1] - u[1]).abs() as f64 <= ULP1);
        }
    }
    // The vertices map back to the square's corners and edges.
    assert_eq!(triangle::uniform_inverse([0.0, 0.0, 1.0]), [0.0, 0.0]);
    assert_eq!(
        triangle::uniform_inverse([1.0, 0.0, 0.0]),
        [ONE_MINUS_EPS, 0.0]
    );
    assert_eq!(
        triangle::uniform_inverse([0.0, 1.0, 0.0]),
        [0.0, ONE_MINUS_EPS]
    );
    assert_eq!(triangle::sqrt_map_inverse([1.0, 0.0, 0.0]), [0.0, 0.0]);
    assert_eq!(
        triangle::sqrt_map_inverse([0.0, 1.0, 0.0]),
        [ONE_MINUS_EPS, ONE_MINUS_EPS]
    );
    assert_eq!(
        triangle::sqrt_map_inverse([0.0, 0.0, 1.0]),
        [ONE_MINUS_EPS, 0.0]
    );
    // Out-of-range input follows the documented rules.
    common::assert_documented_clamp("uniform", triangle::uniform);
    common::assert_documented_clamp("sqrt_map", triangle::sqrt_map);
    assert_eq!(triangle::uniform_inverse([f32::NAN, -3.0, 7.0]), [0.0, 0.0]);
    assert_eq!(
        triangle::sqrt_map_inverse([f32::NAN, f32::NAN, f32::NAN]),
        [ONE_MINUS_EPS, 0.0]
    );
    // Outside the triangle (b0 + b1 > 1): clamped like the nearby edge point.
    assert_eq!(
        triangle::uniform_inverse([0.7, 0.8, -0.5]),
        [ONE_MINUS_EPS, ONE_MINUS_EPS]
    );
    assert_eq!(
        triangle::sqrt_map_inverse([0.5, 0.9, -0.4])[1],
        ONE_MINUS_EPS
    );
    // b2 is ignored by the inverses.
    assert!(same_bits(
        triangle::uniform_inverse([0.1, 0.2, 123.0]),
        triangle::uniform_inverse([0.1, 0.2, 0.7])
    ));
}

// ----------------------------------------------------------------------------------------
// Basu-Owen: construction, stratification and scrambling.

/// The level-`k` sub-triangle containing a point, computed from its barycentrics alone:
/// `(i, j, upright)` with `i = floor(2^k b0)`, `j = floor(2^k b1)`; the cell is upright when
/// the fractional parts sum to less than 1. (Exact in f64; Basu-Owen points are never on a
/// cell boundary.)
fn cell(b: [f32; 3], k: u32) -> (u32, u32, bool) {
    let scale = (1u64 << k) as f64;
    let (x, y) = (b[0] as f64 * scale, b[1] as f64 * scale);
    let (i, j) = (x.floor(), y.floor());
    assert!(x - i + y - j != 1.0, "{b:?} on a level-{k} boundary");
    (i as u32, j as u32, x - i + y - j < 1.0)
}

/// A dense id for level-`k` cells (for `k <= 12`).
fn cell_id(c: (u32, u32, bool), k: u32) -> usize {
    (((c.0 as usize) << k) | c.1 as usize) * 2 + c.2 as usize
}

/// Which of the four children of its level-`k` cell a point lies in, as 0..4: the three
/// corner children, then the middle one (a fixed order for each orientation of the parent).
fn child(b: [f32; 3], k: u32) -> usize {
    let (i, j, up) = cell(b, k);
    let (ci, cj, cup) = cell(b, k + 1);
    let (di, dj) = (ci - 2 * i, cj - 2 * j);
    let list = if up {
        // Upright parent: corners at (+1, 0), (0, +1), (0, 0); the middle is inverted.
        [(1, 0, true), (0, 1, true), (0, 0, true), (0, 0, false)]
    } else {
        // Inverted parent: its corners are inverted cells, its middle is upright.
        [(1, 0, false), (0, 1, false), (1, 1, false), (1, 1, true)]
    };
    list.iter()
        .position(|&c| c == (di, dj, cup))
        .unwrap_or_else(|| panic!("{b:?}: level {} cell is not a child", k + 1))
}

/// The bit-twiddled construction equals the digit-by-digit walk: the exact centroid rounded
/// to the 2^-24 grid (the fraction is 1/3 or 2/3 of a grid step, so the rounding is unique).
#[test]
fn basu_owen_matches_the_walk() {
    let mut r = rng(21);
    let mut worst = 0.0f64;
    let indices = (0..1u32 << 16).chain((0..1 << 18).map(|_| r.random::<u32>()));
    for i in indices.chain([u32::MAX, 0x5555_5555, 0xaaaa_aaaa]) {
        let b = triangle::basu_owen(i, 0);
        let want = basu_owen_ref(i);
        for k in 0..2 {
            assert_eq!(
                b[k] as f64,
                (want[k] * 2f64.powi(24)).round() / 2f64.powi(24),
                "{i:#x} {k}"
            );
        }
        assert_eq!(sum(b), 1.0);
        worst = worst.max(err3(b, want));
    }
    eprintln!("basu_owen max error vs the exact centroid: {worst:.3e}");
    assert!(worst <= 4e-8, "{worst}");
    // The first points: the centroid, then the corners' centroids.
    assert!(err3(triangle::basu_owen(0, 0), [1.0 / 3.0; 3]) <= 4e-8);
    assert!(err3(triangle::basu_owen(1, 0), [2.0 / 3.0, 1.0 / 6.0, 1.0 / 6.0]) <= 4e-8);
    assert!(err3(triangle::basu_owen(2, 0), [1.0 / 6.0, 2.0 / 3.0, 1.0 / 6.0]) <= 4e-8);
    assert!(err3(triangle::basu_owen(3, 0), [1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0]) <= 4e-8);
}

const SEEDS: [u32; 6] = [0, 1, 2, 12345, 0xdead_beef, u32::MAX];

/// For every k <= 8 and many seeds (0 included), under both randomizations, the first 4^k
/// points, and 4^k consecutive points starting at any multiple of 4^k, fall one per level-k
/// sub-triangle.
#[test]
fn basu_owen_stratification() {
    let mut r = rng(22);
    let seeds: Vec<u32> = SEEDS
        .into_iter()
        .chain((0..26).map(|_| r.random()))
        .collect();
    for (name, _, _, slice) in BASU_OWEN {
        for &seed in &seeds {
            for k in 0..=8u32 {
                let n = 1usize << (2 * k);
                let last = (1u32 << (2 * (16 - k.max(1)))) - 1;
                for block in [0u32, 1, 7, last, r.random_range(0..=last)] {
                    let start = block.wrapping_mul(n as u32);
                    let mut seen = vec![false; 2 << (2 * k)];
                    let mut out = vec![[0.0f32; 3]; n];
                    slice(start, seed, &mut out);
                    for (m, b) in out.iter().enumerate() {
                        let id = cell_id(cell(*b, k), k);
                        assert!(
                            !std::mem::replace(&mut seen[id], true),
                            "{name} seed {seed} k {k} start {start}: point {m} shares a cell"
                        );
                    }
                }
            }
        }
    }
}

/// All 16 digits count, and the scramble is nested: indices that agree in their first k
/// digits share their level-k cell (for every seed), and differ in it otherwise.
#[test]
fn basu_owen_nesting_and_all_digits() {
    let mut r = rng(23);
    for _ in 0..20_000 {
        let i = r.random::<u32>();
        let seed = if r.random::<bool>() {
            0
        } else {
            r.random::<u32>()
        };
        let b = triangle::basu_owen(i, seed);
        let k = r.random_range(1..16u32);
        // Change digits k.. : the level-k cell stays, the level-(k+1) cell moves (digit k
        // differs) or not.
        let high = r.random::<u32>() & (u32::MAX << (2 * k));
        let j = (i & !(u32::MAX << (2 * k))) | high;
        let c = triangle::basu_owen(j, seed);
        assert_eq!(cell(b, k), cell(c, k), "{i:#x} {j:#x} seed {seed} k {k}");
        let same_digit = (i >> (2 * k)) & 3 == (j >> (2 * k)) & 3;
        assert_eq!(
            cell(b, k + 1) == cell(c, k + 1),
            same_digit,
            "{i:#x} {j:#x} seed {seed} k {k}"
        );
    }
    // The most significant digit (bits 30, 31) still moves the point to another level-16 cell.
    for seed in SEEDS {
        for i in [0u32, 1, 12345, 0x1555_5555] {
            for d in 1..4u32 {
                let (a, b) = (
                    triangle::basu_owen(i, seed),
                    triangle::basu_owen(i ^ (d << 30), seed),
                );
                assert_eq!(cell(a, 15), cell(b, 15));
                assert_ne!(cell(a, 16), cell(b, 16));
            }
        }
    }
}

// ----------------------------------------------------------------------------------------
// Owen scrambling statistics (chi-square over seeds).

/// Counts over `cells` outcomes, tested against equiprobable `allowed` ones.
fn chi2_discrete(name: &str, counts: &[u64], allowed: impl Fn(usize) -> bool) {
    let n = counts.len();
    let mut h = chi2::Histogram::new(n, 1);
    h.counts.copy_from_slice(counts);
    h.total = counts.iter().sum();
    let expected = {
        let m = (0..n).filter(|&c| allowed(c)).count() as f64;
        (0..n)
            .map(|c| if allowed(c) { 1.0 / m } else { 0.0 })
            .collect::<Vec<_>>()
    };
    chi2::check(name, &h, &expected);
}

/// Owen's pair law: for two indices that agree in digits 0..k and differ in digit k, over
/// random seeds their points lie in the same level-k cell, in two *different* children of it
/// — each of the 12 ordered pairs of children equally likely (a scramble by xor or by a
/// base-2 hash reaches only 4 or 8 of them) — and in independent uniform grandchildren.
#[test]
fn basu_owen_owen_pair_law() {
    let mut r = rng(31);
    const SAMPLES: u32 = 1 << 20;
    for (name, i, j, k) in [
        ("digit 0 (0, 1)", 0u32, 1u32, 0u32),
        ("digit 0 (0, 2)", 0, 2, 0),
        ("digit 1 (5, 9)", 5, 9, 1),
        ("digit 7 random", 0x1234_5678, 0x1234_5678 ^ (2 << 14), 7),
        ("digit 14 random", 0x9e37_79b9, 0x9e37_79b9 ^ (3 << 28), 14),
    ] {
        let mut counts = vec![0u64; 256];
        for _ in 0..SAMPLES {
            let seed = r.random::<u32>() | 1;
            let (a, b) = (triangle::basu_owen(i, seed), triangle::basu_owen(j, seed));
            assert_eq!(cell(a, k), cell(b, k));
            let (ca, cb) = (child(a, k), child(b, k));
            let (ga, gb) = (child(a, k + 1), child(b, k + 1));
            counts[((ca * 4 + cb) * 4 + ga) * 4 + gb] += 1;
        }
        chi2_discrete(&format!("basu_owen pair law, {name}"), &counts, |c| {
            (c >> 6) != ((c >> 4) & 3)
        });
    }
}

/// Consecutive seeds (a renderer's pixel index) give independent points: the level-2 cells
/// of the same index under seeds s and s + 1 are jointly uniform.
#[test]
fn basu_owen_consecutive_seeds_are_independent() {
    for index in [0u32, 77] {
        let mut counts = vec![0u64; 32 * 32];
        for s in 1..=(1u32 << 20) {
            let a = cell_id(cell(triangle::basu_owen(index, s), 2), 2);
            let b = cell_id(cell(triangle::basu_owen(index, s + 1), 2), 2);
            counts[a * 32 + b] += 1;
        }
        // Valid level-2 ids: upright (i + j <= 3) and inverted (i + j <= 2) cells.
        let ok = |id: usize| {
            let (i, j, up) = (id >> 3, (id >> 1) & 3, id & 1 == 1);
            if up { i + j <= 3 } else { i + j <= 2 }
        };
        chi2_discrete(
            &format!("basu_owen seeds s, s+1, index {index}"),
            &counts,
            |c| ok(c / 32) && ok(c % 32),
        );
    }
}

// ----------------------------------------------------------------------------------------
// Basu-Owen with one digit permutation per level.

/// The digit the walk took at level `k`, read back from the point's geometry: which child of
/// its level-`k` cell it lies in, in the walk's numbering (1, 2, 3: the corner children at
/// `v0`, `v1`, `v2`; 0: the middle one). `child` lists children in a fixed order per
/// orientation; in an inverted cell the first two corners swap roles.
fn digit(b: [f32; 3], k: u32) -> u32 {
    let order = if cell(b, k).2 {
        [1, 2, 3, 0]
    } else {
        [2, 1, 3, 0]
    };
    order[child(b, k)]
}

fn digits(b: [f32; 3]) -> [u32; 16] {
    std::array::from_fn(|k| digit(b, k as u32))
}

fn index_digits(i: u32) -> [u32; 16] {
    std::array::from_fn(|k| (i >> (2 * k)) & 3)
}

/// `sigma[j][d]`: the digit the walk takes at level `j` for index digit `d`, recovered from
/// the points `d << 2j` (every other digit 0).
fn recover_levels(point: impl Fn(u32) -> [f32; 3]) -> [[u32; 4]; 16] {
    std::array::from_fn(|j| std::array::from_fn(|d| digit(point((d as u32) << (2 * j)), j as u32)))
}

/// Lexicographic rank of a permutation of 0..4 (0..24).
fn perm_rank(p: [u32; 4]) -> usize {
    let mut rank = 0;
    for i in 0..4 {
        let smaller = (i + 1..4).filter(|&j| p[j] < p[i]).count();
        rank = rank * (4 - i) + smaller;
    }
    rank
}

/// The geometry read-back is right: unscrambled, the walk's digits are the index's.
#[test]
fn digit_readback_matches_the_index() {
    let mut r = rng(50);
    for i in (0..4096u32).chain((0..20_000).map(|_| r.random())) {
        assert_eq!(digits(triangle::basu_owen(i, 0)), index_digits(i), "{i:#x}");
    }
}

/// `seed = 0` is the plain construction, bit for bit.
#[test]
fn basu_owen_permuted_seed_zero_is_plain() {
    let mut r = rng(51);
    for i in (0..1u32 << 16).chain((0..100_000).map(|_| r.random())) {
        assert!(same_bits(
            triangle::basu_owen_permuted(i, 0),
            triangle::basu_owen(i, 0)
        ));
    }
}

/// What "one permutation per level" means, checked exactly: for a seed, recover `sigma_j`
/// from 64 points; every `sigma_j` is a permutation, and every index `i` walks the digits
/// `sigma_j(d_j(i))`. The nested scramble of `basu_owen` fails the same check (its
/// permutations depend on the prefix), so the test can tell the two apart.
#[test]
fn basu_owen_permuted_is_one_permutation_per_level() {
    let mut r = rng(52);
    for trial in 0..200 {
        let seed = if trial == 0 { 0 } else { r.random::<u32>() };
        let sigma = recover_levels(|i| triangle::basu_owen_permuted(i, seed));
        for (j, s) in sigma.iter().enumerate() {
            let mut sorted = *s;
            sorted.sort();
            assert_eq!(sorted, [0, 1, 2, 3], "seed {seed} level {j}: {s:?}");
        }
        if seed == 0 {
            assert!(sigma.iter().all(|s| *s == [0, 1, 2, 3]));
        }
        for _ in 0..200 {
            let i = r.random::<u32>();
            let want: [u32; 16] = std::array::from_fn(|j| sigma[j][index_digits(i)[j] as usize]);
            assert_eq!(
                digits(triangle::basu_owen_permuted(i, seed)),
                want,
                "seed {seed} index {i:#x}"
            );
        }
    }
    let mut mismatches = 0;
    for _ in 0..20 {
        let seed = r.random::<u32>() | 1;
        let sigma = recover_levels(|i| triangle::basu_owen(i, seed));
        for _ in 0..50 {
            let i = r.random::<u32>();
            let want: [u32; 16] = std::array::from_fn(|j| sigma[j][index_digits(i)[j] as usize]);
            mismatches += (digits(triangle::basu_owen(i, seed)) != want) as u32;
        }
    }
    assert!(
        mismatches > 900,
        "nested scramble looked per-level: {mismatches}"
    );
}

/// 3 x (the point's offset from the centroid of its level-`k` cell), in units of `2^-24`,
/// with the sign of the cell's orientation taken out (inverted cells are point reflections).
fn oriented_offset(b: [f32; 3], k: u32) -> (i64, i64) {
    let (x, y) = ((b[0] * 16_777_216.0) as i64, (b[1] * 16_777_216.0) as i64);
    let shift = 24 - k;
    let (i, j, upright) = cell(b, k);
    let third = if upright { 1 } else { 2 };
    let ox = 3 * x - ((3 * i as i64 + third) << shift);
    let oy = 3 * y - ((3 * j as i64 + third) << shift);
    if upright { (ox, oy) } else { (-ox, -oy) }
}

/// Within every aligned block of `4^k` indices, every point sits at the same place in its
/// level-`k` sub-triangle (mirrored in the inverted ones), exactly, for the per-level
/// permutation; the nested scramble moves each point independently (and so fails this).
#[test]
fn basu_owen_permuted_same_offset_in_every_cell() {
    let mut r = rng(53);
    for trial in 0..40 {
        let seed = if trial == 0 { 0 } else { r.random::<u32>() };
        for k in 1..=6u32 {
            let n = 1u32 << (2 * k);
            for start in [0, n.wrapping_mul(r.random::<u32>() >> (2 * k))] {
                let mut out = vec![[0.0f32; 3]; n as usize];
                triangle::basu_owen_permuted_slice(start, seed, &mut out);
                let first = oriented_offset(out[0], k);
                for (m, b) in out.iter().enumerate() {
                    assert_eq!(
                        oriented_offset(*b, k),
                        first,
                        "seed {seed} k {k} start {start} point {m}"
                    );
                }
            }
        }
    }
    let mut out = vec![[0.0f32; 3]; 16];
    triangle::basu_owen_slice(0, 0x2545_f491, &mut out);
    let offsets: std::collections::HashSet<_> =
        out.iter().map(|b| oriented_offset(*b, 2)).collect();
    assert!(
        offsets.len() > 8,
        "nested scramble: {} distinct offsets",
        offsets.len()
    );
}

/// Over random seeds, each level's permutation is uniform over all 24, and the permutations
/// of two levels are independent (levels 0 and 1; 7 and 8, which come from different hash
/// words; 14 and 15, the deepest). 2^18 seeds: 455 expected per cell of the 576-cell tests.
#[test]
fn chi2_basu_owen_permuted_levels_uniform_and_independent() {
    let mut r = rng(54);
    let pairs = [(0usize, 1usize), (7, 8), (14, 15)];
    let mut counts = vec![vec![0u64; 576]; pairs.len()];
    for _ in 0..(1 << 18) {
        let seed = r.random::<u32>();
        let sigma = recover_levels(|i| triangle::basu_owen_permuted(i, seed));
        for (c, &(a, b)) in counts.iter_mut().zip(&pairs) {
            c[perm_rank(sigma[a]) * 24 + perm_rank(sigma[b])] += 1;
        }
    }
    for (c, (a, b)) in counts.iter().zip(pairs) {
        chi2_discrete(
            &format!("basu_owen_permuted sigma_{a} x sigma_{b}"),
            c,
            |_| true,
        );
    }
}

/// The pair law over seeds: two indices that agree below digit `k` and differ at `k` share
/// their level-`k` cell and lie in different children (12 ordered pairs, equally likely);
/// at level `k + 1` their digits are equal when the index digits are (4 outcomes) and
/// different otherwise (12) — the same permutation for both — independently of level `k`.
#[test]
fn basu_owen_permuted_pair_law() {
    let mut r = rng(55);
    for (name, i, j, k) in [
        ("digit 0, then equal digits", 0u32, 1u32, 0u32),
        ("digit 0, then different digits", 0, 1 | (2 << 2), 0),
        (
            "digit 7, then equal",
            0x1234_5678,
            0x1234_5678 ^ (2 << 14),
            7,
        ),
        (
            "digit 8, then different",
            0x9e37_79b9,
            0x9e37_79b9 ^ (3 << 16) ^ (1 << 18),
            8,
        ),
    ] {
        let same_next = (i >> (2 * k + 2)) & 3 == (j >> (2 * k + 2)) & 3;
        let mut counts = vec![0u64; 256];
        for _ in 0..(1u32 << 18) {
            let seed = r.random::<u32>() | 1;
            let (a, b) = (
                triangle::basu_owen_permuted(i, seed),
                triangle::basu_owen_permuted(j, seed),
            );
            assert_eq!(cell(a, k), cell(b, k));
            let (da, db) = (digit(a, k), digit(b, k));
            let (ga, gb) = (digit(a, k + 1), digit(b, k + 1));
            counts[((da * 4 + db) * 4 + ga) as usize * 4 + gb as usize] += 1;
        }
        chi2_discrete(
            &format!("basu_owen_permuted pair law, {name}"),
            &counts,
            |c| {
                let (da, db, ga, gb) = (c >> 6, (c >> 4) & 3, (c >> 2) & 3, c & 3);
                da != db && ((ga == gb) == same_next)
            },
        );
    }
}

/// Consecutive seeds give independent points (as for the nested scramble).
#[test]
fn basu_owen_permuted_consecutive_seeds_are_independent() {
    let mut counts = vec![0u64; 32 * 32];
    for s in 1..=(1u32 << 20) {
        let a = cell_id(cell(triangle::basu_owen_permuted(77, s), 2), 2);
        let b = cell_id(cell(triangle::basu_owen_permuted(77, s + 1), 2), 2);
        counts[a * 32 + b] += 1;
    }
    let ok = |id: usize| {
        let (i, j, up) = (id >> 3, (id >> 1) & 3, id & 1 == 1);
        if up { i + j <= 3 } else { i + j <= 2 }
    };
    chi2_discrete("basu_owen_permuted seeds s, s+1", &counts, |c| {
        ok(c / 32) && ok(c % 32)
    });
}

// ----------------------------------------------------------------------------------------
// Chi-square uniformity over equal-area cells ((1 - b0)^2, b1 / (1 - b0)).

const NA: usize = 32;
const NB: usize = 64;

fn chi2_triangle(name: &str, mut next: impl FnMut() -> [f32; 3]) {
    let mut h = chi2::Histogram::new(NA, NB);
    for _ in 0..chi2::SAMPLES {
        h.add(chi2::triangle(next()));
    }
    chi2::check(name, &h, &chi2::expected_uniform(NA, NB));
}

#[test]
fn chi2_uniform() {
    let mut r = rng(101);
    chi2_triangle("triangle::uniform", || triangle::uniform(unit2(&mut r)));
}

#[test]
fn chi2_sqrt_map() {
    let mut r = rng(102);
    chi2_triangle("triangle::sqrt_map", || triangle::sqrt_map(unit2(&mut r)));
}

/// Independent samples: a fresh random seed and index for every point.
#[test]
fn chi2_basu_owen_random_seeds() {
    let mut r = rng(103);
    chi2_triangle("triangle::basu_owen (random seed, random index)", || {
        triangle::basu_owen(r.random(), r.random::<u32>() | 1)
    });
}

/// Stratified sets of an index-driven slice form: `seed` (a random odd seed per set) x the
/// first 4096 points, 512 sets. Each set is "too uniform" (one point per level-6 cell), which
/// only lowers the statistic; what this catches is a density error.
fn chi2_stratified_sets(name: &str, seed: u64, slice: impl Fn(u32, u32, &mut [[f32; 3]]) -> usize) {
    let mut r = rng(seed);
    let mut buf = vec![[0.0f32; 3]; 4096];
    let mut at = buf.len();
    chi2_triangle(&format!("{name} (512 seeds x 4096 points)"), || {
        if at == buf.len() {
            slice(0, r.random::<u32>() | 1, &mut buf);
            at = 0;
        }
        at += 1;
        buf[at - 1]
    });
}

#[test]
fn chi2_basu_owen_stratified_sets() {
    chi2_stratified_sets("triangle::basu_owen", 104, triangle::basu_owen_slice);
}

/// Independent samples of the per-level permutation: random seed and index per point.
#[test]
fn chi2_basu_owen_permuted_random_seeds() {
    let mut r = rng(105);
    chi2_triangle(
        "triangle::basu_owen_permuted (random seed, random index)",
        || triangle::basu_owen_permuted(r.random(), r.random::<u32>() | 1),
    );
}

/// The per-level permutation's stratified sets.
#[test]
fn chi2_basu_owen_permuted_stratified_sets() {
    chi2_stratified_sets(
        "triangle::basu_owen_permuted",
        106,
        triangle::basu_owen_permuted_slice,
    );
}

/// The test can fail: the naive map b0 = u0, b1 = u1 (1 - u0) (density 1 / (1 - b0): mass
/// piles up at v0), and a 1% density error in one half.
#[test]
fn chi2_rejects_wrong_warps() {
    let mut r = rng(9);
    let mut h = chi2::Histogram::new(NA, NB);
    for _ in 0..chi2::SAMPLES {
        let u = unit2(&mut r);
        let (b0, b1) = (u[0], u[1] * (1.0 - u[0]));
        h.add(chi2::triangle([b0, b1, 1.0 - b0 - b1]));
    }
    let p = chi2::statistic(&h, &chi2::expected_uniform(NA, NB))
        .unwrap()
        .p_value;
    assert!(p < 1e-12, "p = {p}");

    let mut h = chi2::Histogram::new(NA, NB);
    for _ in 0..chi2::SAMPLES {
        let mut u = unit2(&mut r);
        if u[1] >= 0.5 && unit(&mut r) < 0.02 {
            u[1] -= 0.5;
        }
        h.add(chi2::triangle(triangle::uniform(u)));
    }
    chi2::assert_rejects_uniform(&h, NA, NB);
}
