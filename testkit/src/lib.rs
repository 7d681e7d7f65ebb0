//! Helpers shared by warpcore's integration tests: the chi-square module, a seeded generator,
//! the special `f32` inputs every warp must survive, bit-identity checks, and the textbook
//! formulas (the tests' `f64` references and the benchmarks' `f32` peers).
pub mod chi2;
pub mod textbook;

use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus;

/// A seeded generator: every statistical test is reproducible.
pub fn rng(seed: u64) -> Xoshiro256PlusPlus {
    Xoshiro256PlusPlus::seed_from_u64(seed)
}

/// A uniform `f32` in `[0, 1)` with all 24 bits random (the top of `[0, 1)` is reachable).
pub fn unit(r: &mut Xoshiro256PlusPlus) -> f32 {
    (r.random::<u32>() >> 8) as f32 * (1.0 / 16_777_216.0)
}

pub fn unit2(r: &mut Xoshiro256PlusPlus) -> [f32; 2] {
    [unit(r), unit(r)]
}

pub const ONE_MINUS_EPS: f32 = 1.0 - 1.0 / 16_777_216.0;

/// Inputs every total function must survive: signed zeros, the ends of [0, 1), NaNs with
/// both signs and a payload, infinities, subnormals, huge and negative values.
pub fn specials() -> Vec<f32> {
    vec![
        0.0,
        -0.0,
        0.5,
        0.25,
        0.75,
        ONE_MINUS_EPS,
        1.0,
        1.0 + f32::EPSILON,
        -1.0,
        2.0,
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0x7fc0_1234),
        f32::from_bits(0xffa0_0001),
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::MIN_POSITIVE,
        f32::from_bits(1),
        -f32::from_bits(1),
        f32::from_bits(0x007f_ffff),
        f32::MAX,
        f32::MIN,
        1e-30,
        1.0 / 16_777_216.0,
    ]
}

/// Every pair `[a, b]` of [`specials`] (`a` the outer loop).
pub fn special_pairs() -> Vec<[f32; 2]> {
    let sp = specials();
    sp.iter()
        .flat_map(|&a| sp.iter().map(move |&b| [a, b]))
        .collect()
}

/// Every `[a, b, c]` with `[a, b]` from [`special_pairs`] and `c` from `third` (innermost).
pub fn special_triples(third: &[f32]) -> Vec<[f32; 3]> {
    let pairs = special_pairs();
    pairs
        .iter()
        .flat_map(|&[a, b]| third.iter().map(move |&c| [a, b, c]))
        .collect()
}

/// In the half-open unit square `[0, 1)^2`, with `+0.0` for zero (no `-0.0`, no NaN).
pub fn in_unit_square(u: [f32; 2]) -> bool {
    u.iter()
        .all(|&x| (0.0..1.0).contains(&x) && x.to_bits() >> 31 == 0)
}

/// The documented clamp of every forward warp's input (the same function on the clamped
/// point): NaN and `-0.0` become 0, negatives and `-inf` 0, values `>= 1` and `+inf`
/// `1 - 2^-24`.
pub fn assert_documented_clamp<const N: usize>(name: &str, f: impl Fn([f32; 2]) -> [f32; N]) {
    for (u, clamped) in [
        ([f32::NAN, 2.0], [0.0, ONE_MINUS_EPS]),
        ([-1.0, f32::INFINITY], [0.0, ONE_MINUS_EPS]),
        ([-0.0, 0.25], [0.0, 0.25]),
        ([0.5, f32::NEG_INFINITY], [0.5, 0.0]),
    ] {
        assert!(same_bits(f(u), f(clamped)), "{name}{u:?}");
    }
}

/// Bit equality of float arrays (NaN-safe, sign-of-zero-sensitive).
pub fn same_bits<const N: usize>(a: [f32; N], b: [f32; N]) -> bool {
    a.iter()
        .zip(b.iter())
        .all(|(x, y)| x.to_bits() == y.to_bits())
}

/// Lane `j` of a SIMD result as a plain array.
pub fn lane<const N: usize>(v: [wide::f32x8; N], j: usize) -> [f32; N] {
    std::array::from_fn(|k| v[k].to_array()[j])
}

/// Eight points as SIMD lanes (structure of arrays).
pub fn soa<const N: usize>(points: &[[f32; N]; 8]) -> [wide::f32x8; N] {
    std::array::from_fn(|k| wide::f32x8::new(std::array::from_fn(|j| points[j][k])))
}

/// Scalar == x8 == slice, bit for bit, on eight points: the `_x8` form on all eight lanes,
/// and the slice form on the full group and on padded tails of 5 and 1 elements.
pub fn check_widths<const I: usize, const O: usize>(
    name: &str,
    pts: &[[f32; I]; 8],
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([wide::f32x8; I]) -> [wide::f32x8; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) {
    let v = x8(soa(pts));
    for n in [8usize, 5, 1] {
        let mut out = [[9.0f32; O]; 8];
        assert_eq!(slice(&pts[..n], &mut out), n, "{name}: slice count");
        for (j, (p, o)) in pts.iter().zip(&out).take(n).enumerate() {
            let s = scalar(*p);
            assert!(same_bits(s, lane(v, j)), "{name} x8 lane {j}: {p:?}");
            assert!(same_bits(s, *o), "{name} slice[{j}] of {n}: {p:?}");
        }
    }
}

/// The slice length rule on every input length `0..=input.len()` and output lengths equal,
/// longer and shorter: writes `min(n, m)` elements equal to the scalar form, returns that
/// count, and leaves the rest of the output untouched.
pub fn check_slice_lengths<const I: usize, const O: usize>(
    input: &[[f32; I]],
    scalar: impl Fn([f32; I]) -> [f32; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) {
    for n in 0..=input.len() {
        for m in [n, n + 3, n.saturating_sub(5)] {
            let mut out = vec![[7.0f32; O]; m];
            let written = slice(&input[..n], &mut out);
            assert_eq!(written, n.min(m), "count for {n} inputs, {m} outputs");
            for (j, o) in out.iter().enumerate() {
                if j < written {
                    assert!(same_bits(*o, scalar(input[j])), "element {j} of {n}/{m}");
                } else {
                    assert_eq!(*o, [7.0; O], "untouched beyond the common length");
                }
            }
        }
    }
}
