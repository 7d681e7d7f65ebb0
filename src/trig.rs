//! Branch-free polynomial sin, cos and atan, written once over [`Lane`].
//!
//! Angles are measured in the units the warps produce them in, so no `pi` multiplication adds
//! a rounding step: [`sin_cos_pi4`] takes `t` for the angle `(pi/4) t`, [`sin_cos_turns`] takes
//! a fraction of a full turn, and [`atan_ratio_pi4`] returns `atan(n / d) / (pi/4)`.
//!
//! The coefficients are minimax fits in `t^2` (relative error), computed by the Remez exchange
//! in `tools/fit_kernels.py` and rounded to `f32`. The fits alone are far below `f32`
//! resolution (sin 3.2e-9, cos 6.4e-11, atan 4.8e-9 relative); what remains is the rounding
//! of the Horner evaluation in `f32` without FMA. That error is measured against `f64`
//! (the `tests` module below; the `exhaustive_*` tests sweep every `f32` of the domain) and
//! stated on each kernel.
//!
//! The approach follows Cephes' `sinf`/`atanf` and pbrt-v4's and Mitsuba 3's SIMD-friendly
//! trigonometry (polynomial on a reduced range, quadrant fix-up by sign and swap), but the
//! reduction is exact here: the warps hand us the reduced argument directly.

use crate::lanes::{Lane, UintLane};

// sin((pi/4) t) = t * (S0 + S1 t^2 + S2 t^4 + S3 t^6) on [-1, 1].
//
// S0, S1, C1 and C2 are the Remez values moved by one f32 ulp (S0 to the f32 just *below*
// pi/4): a search over such nudges (best of 2450, scored on 276k arguments, then checked
// exhaustively) cut the largest excess of sin^2 + cos^2 over 1 from 2.1e-7 to 8e-8 at the
// cost of a few tenths of an ulp. That excess is what `MAX_RADIUS` has to absorb.
#[allow(clippy::approx_constant)] // deliberately the f32 just below pi/4, see above
const S0: f32 = 0.785_398_1;
const S1: f32 = -0.080_745_43;
const S2: f32 = 0.002_490_001;
const S3: f32 = -3.595_045_2e-5;
// cos((pi/4) t) = 1 + C1 t^2 + C2 t^4 + C3 t^6 + C4 t^8 on [-1, 1] (constant pinned to 1 so
// that cos(0) is exactly 1).
const C1: f32 = -0.308_425_16;
const C2: f32 = 0.015_854_325;
const C3: f32 = -3.259_400_8e-4;
const C4: f32 = 3.530_338e-6;
// atan(z) / (pi/4) = z * (A0 + A1 z^2 + ... + A5 z^10) on |z| <= 1/2; larger arguments are
// reduced first (see `atan_ratio_pi4`).
const A: [f32; 6] = [
    1.273_239_5,
    -0.424_411_4,
    0.254_562_35,
    -0.180_369_76,
    0.128_907_9,
    -0.064_685_45,
];

/// The largest radius a warp feeds into `r * (cos, sin)`: `1 - 2^-23`.
///
/// Correctly rounded (or nearly so) sine and cosine cannot keep `sin^2 + cos^2 <= 1`: near
/// `t = 0`, `cos` rounds to exactly 1 while `sin != 0`. Ours exceed 1 by at most
/// `delta = 1.04e-7` (exhaustive test). Clamping the radius to `R = 1 - 2^-23` closes the gap:
/// the products `r cos`, `r sin` round up by at most a factor `1 + 2^-24`, and
/// `R^2 (1 + 2^-24)^2 (1 + delta) < (1 - 2.38e-7)(1 + 1.19e-7)(1 + 1.04e-7) < 1`, so every disk
/// point is inside the closed unit disk in exact arithmetic (and hence also when a caller
/// checks `x * x + y * y <= 1` in `f32` or `f64`). Only the outermost `1.2e-7` of the radius
/// (the top two `f32` values of `u0` for the polar maps) is affected.
pub(crate) const MAX_RADIUS: f32 = 1.0 - 1.0 / 8_388_608.0;

/// `(sin((pi/4) t), cos((pi/4) t))` for `t` in `[-1, 1]`.
///
/// Error against `f64` over every `f32` in `[-1, 1]` (measured exhaustively):
/// sin at most 2.03 ulp (absolute 1.0e-7), cos at most 1.53 ulp (absolute 9.1e-8).
/// Both are exactly odd/even in `t` and `cos(0) = 1` exactly. For every `t` the computed pair
/// satisfies `sin^2 + cos^2 <= 1 + 1.04e-7` in exact arithmetic (exhaustive test); see
/// [`MAX_RADIUS`] for how the warps turn this into an exact domain guarantee.
#[inline(always)]
pub(crate) fn sin_cos_pi4<L: Lane>(t: L) -> (L, L) {
    let s = t * t;
    let sin = t * (L::splat(S0) + s * (L::splat(S1) + s * (L::splat(S2) + s * L::splat(S3))));
    let cos = L::splat(1.0)
        + s * (L::splat(C1) + s * (L::splat(C2) + s * (L::splat(C3) + s * L::splat(C4))));
    (sin, cos)
}

/// `(sin, cos)` of the angle `(pi/2) (f + q)` for `f` in `[0, 1]` and any integer lane `q`
/// (only `q mod 4` matters). The range reduction is exact: `2f` splits at 1 into
/// `t in [-1, 1)` and a quarter-turn count, and the quarter turns are applied by swapping
/// sin and cos and flipping sign bits. Same error as [`sin_cos_pi4`].
#[inline(always)]
pub(crate) fn sin_cos_quarter_turns<L: Lane>(f: L, q: L::U) -> (L, L) {
    let h = f + f;
    let upper = L::splat(1.0).simd_le(h);
    // h - 2 is exact for h in [1, 2] (Sterbenz).
    let t = L::select(upper, h - L::splat(2.0), h);
    let q = q + L::U::select(upper, L::U::splat(1), L::U::splat(0));
    let (s, c) = sin_cos_pi4(t);
    let swap = (q & L::U::splat(1)).simd_eq(L::U::splat(1));
    let sin = L::select(swap, c, s);
    let cos = L::select(swap, s, c);
    // sin is negative in quadrants 2 and 3, cos in quadrants 1 and 2.
    let sin_sign = (q & L::U::splat(2)).shl(30);
    let cos_sign = ((q + L::U::splat(1)) & L::U::splat(2)).shl(30);
    (sin.flip_sign(sin_sign), cos.flip_sign(cos_sign))
}

/// `(sin(2 pi v), cos(2 pi v))` for `v` in `[0, 1]`: `4v` is exact, its integer part counts
/// quarter turns and its fraction goes to [`sin_cos_quarter_turns`]. Same error as
/// [`sin_cos_pi4`]; at `v = 1/4, 1/2, 3/4` the results are exact (`0` and `+-1`).
#[inline(always)]
pub(crate) fn sin_cos_turns<L: Lane>(v: L) -> (L, L) {
    let v4 = v * L::splat(4.0);
    let q = v4.to_uint();
    sin_cos_quarter_turns(v4 - L::from_uint(q), q)
}

/// `atan(num / den) / (pi/4)` for `0 <= num <= den`, so the result is in `[0, 1]`; `den = 0`
/// (the origin of an `atan2`) gives 0.
///
/// Taking the ratio as two numbers lets the reduction share the caller's one division: for
/// `num >= den / 2` it uses `atan(z) = pi/4 + atan((num - den) / (num + den))`, where
/// `num - den` is exact (Sterbenz), so the polynomial only covers `|z| <= 1/2`.
///
/// Error against `f64`: at most 2.1 ulp (absolute 1.1e-7) for every `f32` `num` in `[0, 1]`
/// with `den = 1`, and at most 2.6 ulp (absolute 1.15e-7) for `num = 0.7 z`, `den = 0.7`
/// (the division's rounding adds half an ulp); both measured exhaustively.
#[inline(always)]
pub(crate) fn atan_ratio_pi4<L: Lane>(num: L, den: L) -> L {
    let reduce = den.simd_le(num + num);
    let n = L::select(reduce, num - den, num);
    let d = L::select(reduce, num + den, den);
    let z = n / d;
    let s = z * z;
    let mut p = L::splat(A[5]);
    for &a in A[..5].iter().rev() {
        p = L::splat(a) + s * p;
    }
    let w = z * p;
    let zero = L::splat(0.0);
    // At the origin z = 0/0 is NaN: select it away (no trap, no branch).
    L::select(
        den.simd_eq(zero),
        zero,
        L::select(reduce, L::splat(1.0) + w, w),
    )
}

/// The direction of `(x, y)` as a fraction of a full turn, counter-clockwise from `+x`, in
/// `[0, 1)`: `atan2(y, x) / (2 pi)` wrapped to `[0, 1)`.
///
/// Folds to the first octant (`min(|x|, |y|) / max(|x|, |y|)`), evaluates [`atan_ratio_pi4`]
/// and unfolds with exact `2 - w`, `4 - w`, `8 - w` steps in units of `pi/4`. `y = -0.0` counts
/// as `y >= 0` (angle 0, not 1); the origin gives 0; a result that rounds up to 1 returns
/// `1 - 2^-24` (the direction just below `+x`). Absolute error at most 3e-8 turns (finite
/// input; callers clamp NaN away first).
#[inline(always)]
pub(crate) fn atan2_turns<L: Lane>(y: L, x: L) -> L {
    let (ax, ay) = (x.abs(), y.abs());
    let x_major = ay.simd_le(ax);
    let w = atan_ratio_pi4(L::select(x_major, ay, ax), L::select(x_major, ax, ay));
    let zero = L::splat(0.0);
    let a = L::select(x_major, w, L::splat(2.0) - w);
    let a = L::select(x.simd_lt(zero), L::splat(4.0) - a, a);
    let a = L::select(y.simd_lt(zero), L::splat(8.0) - a, a);
    let turns = a * L::splat(0.125);
    let top = L::splat(crate::lanes::ONE_MINUS_EPSILON);
    L::select(turns.simd_lt(L::splat(1.0)), turns, top)
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec::Vec;
    use wide::{f32x8, u32x8};

    /// Distance in units in the last place of `reference` (rounded to f32).
    fn ulps(approx: f32, reference: f64) -> f64 {
        let r = reference as f32;
        let ulp = if r == 0.0 {
            f32::from_bits(1) as f64
        } else {
            let e = (r.abs().to_bits() >> 23) as i32 - 127;
            2f64.powi(e.max(-126) - 23)
        };
        (approx as f64 - reference).abs() / ulp
    }

    /// Runs `f` over every `stride`-th f32 in `[0, 1]`, split over threads; returns the
    /// per-thread maxima merged by `max`. On wasm (no threads under WASI preview 1) it runs
    /// on one thread with the stride raised to at least 61: the exhaustive native run covers
    /// the rest, and the cross-target fingerprint test proves the bits are the same.
    fn sweep(stride: u32, f: impl Fn(f32) -> [f64; 4] + Sync) -> [f64; 4] {
        let end = 1.0f32.to_bits();
        let (threads, stride) = if cfg!(target_family = "wasm") {
            (1u32, stride.max(61))
        } else {
            (4u32, stride)
        };
        let run = |k: u32| {
            let mut m = [0.0f64; 4];
            let mut bits = k * stride;
            while bits <= end {
                let r = f(f32::from_bits(bits));
                for i in 0..4 {
                    m[i] = m[i].max(r[i]);
                }
                bits += threads * stride;
            }
            m
        };
        let merge = |mut acc: [f64; 4], m: [f64; 4]| {
            for i in 0..4 {
                acc[i] = acc[i].max(m[i]);
            }
            acc
        };
        if threads == 1 {
            return run(0);
        }
        std::thread::scope(|scope| {
            let handles: Vec<_> = (0..threads).map(|k| scope.spawn(move || run(k))).collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap())
                .fold([0.0f64; 4], merge)
        })
    }

    fn sin_cos_errors(t: f32) -> [f64; 4] {
        let (s, c) = sin_cos_pi4(t);
        let a = core::f64::consts::FRAC_PI_4 * t as f64;
        [
            ulps(s, a.sin()),
            ulps(c, a.cos()),
            (s as f64 - a.sin()).abs(),
            (c as f64 - a.cos()).abs(),
        ]
    }

    fn atan_errors(z: f32) -> [f64; 4] {
        let r = (z as f64).atan() / core::f64::consts::FRAC_PI_4;
        let a = atan_ratio_pi4(z, 1.0);
        // The same ratio with a denominator that is not a power of two.
        let (n, d) = (z * 0.7, 0.7f32);
        let r2 = (n as f64 / d as f64).atan() / core::f64::consts::FRAC_PI_4;
        let a2 = atan_ratio_pi4(n, d);
        [
            ulps(a, r),
            (a as f64 - r).abs(),
            ulps(a2, r2),
            (a2 as f64 - r2).abs(),
        ]
    }

    // The bounds the doc comments state. The regular tests sweep every 61st f32 of [0, 1]
    // (17 M inputs, a prime stride so every exponent and mantissa pattern class is hit);
    // `exhaustive_*` (run with `--ignored`) sweeps all 1.07e9 and is where the figures come from.
    const SIN_ULP: f64 = 2.03;
    const COS_ULP: f64 = 1.53;
    const SIN_ABS: f64 = 1.0e-7;
    const COS_ABS: f64 = 9.1e-8;
    const ATAN_ULP: f64 = 2.1;
    const ATAN_ABS: f64 = 1.15e-7;

    /// The maxima of a kernel's sweep at `stride`, printed as `[ulp, ulp, abs, abs]` (the
    /// order of `shown`).
    fn sweep_and_print(
        name: &str,
        stride: u32,
        errors: fn(f32) -> [f64; 4],
        shown: [usize; 4],
    ) -> [f64; 4] {
        let m = sweep(stride, errors);
        let [a, b, c, d] = shown.map(|k| m[k]);
        std::println!("{name} stride {stride}: ulp {a:.3} {b:.3}, abs {c:.3e} {d:.3e}");
        m
    }

    fn check_sin_cos(stride: u32) {
        let m = sweep_and_print("sin_cos_pi4", stride, sin_cos_errors, [0, 1, 2, 3]);
        assert!(m[0] <= SIN_ULP && m[1] <= COS_ULP, "{m:?}");
        assert!(m[2] <= SIN_ABS && m[3] <= COS_ABS, "{m:?}");
    }

    fn check_atan(stride: u32) {
        let m = sweep_and_print("atan_ratio_pi4", stride, atan_errors, [0, 2, 1, 3]);
        assert!(m[0] <= ATAN_ULP && m[1] <= ATAN_ABS, "{m:?}");
        assert!(m[2] <= ATAN_ULP + 0.5 && m[3] <= ATAN_ABS, "{m:?}");
    }

    #[test]
    fn sin_cos_error_bound() {
        check_sin_cos(61);
    }

    #[test]
    fn atan_error_bound() {
        check_atan(61);
    }

    #[test]
    #[ignore = "exhaustive sweep, ~1 min: cargo test --release -- --ignored exhaustive"]
    fn exhaustive_sin_cos() {
        check_sin_cos(1);
    }

    #[test]
    #[ignore = "exhaustive sweep, ~1 min: cargo test --release -- --ignored exhaustive"]
    fn exhaustive_atan() {
        check_atan(1);
    }

    /// The excess of sin^2 + cos^2 over 1 that MAX_RADIUS absorbs, for *every* f32 t in
    /// [0, 1] (the kernels are exactly odd/even, so [-1, 0] is the mirror image). In f64 the
    /// squares of f32 values are exact and their sum errs by < 2^-53.
    #[test]
    fn sin_cos_excess_is_absorbed_by_max_radius() {
        let m = sweep(1, |t| {
            let (s, c) = sin_cos_pi4(t);
            let n = (s as f64) * (s as f64) + (c as f64) * (c as f64);
            [n - 1.0, s.abs().max(c.abs()) as f64, 0.0, 0.0]
        });
        std::println!("max sin^2 + cos^2 - 1 = {:e}", m[0]);
        assert!(m[0] <= 1.04e-7, "{:e}", m[0]);
        assert!(m[1] <= 1.0);
        // The inequality of MAX_RADIUS's doc, with the measured excess.
        let r = MAX_RADIUS as f64;
        let grow = 1.0 + 2f64.powi(-24);
        assert!(r * r * grow * grow * (1.0 + m[0]) < 1.0);
    }

    #[test]
    fn symmetry_and_exact_points() {
        for t in [0.0f32, 1e-30, 0.1, 0.5, 0.999, 1.0] {
            let (s, c) = sin_cos_pi4(t);
            let (sn, cn) = sin_cos_pi4(-t);
            assert_eq!(sn.to_bits(), (-s).to_bits());
            assert_eq!(cn.to_bits(), c.to_bits());
        }
        assert_eq!(sin_cos_pi4(0.0f32), (0.0, 1.0));
        assert_eq!(atan_ratio_pi4(0.0f32, 0.0), 0.0);
        assert_eq!(atan_ratio_pi4(0.0f32, 1.0), 0.0);
        assert_eq!(atan_ratio_pi4(1.0f32, 1.0), 1.0);
        assert_eq!(atan_ratio_pi4(3.0f32, 3.0), 1.0);
        for (v, s, c) in [
            (0.0f32, 0.0f32, 1.0f32),
            (0.25, 1.0, 0.0),
            (0.5, 0.0, -1.0),
            (0.75, -1.0, 0.0),
        ] {
            let (ss, cc) = sin_cos_turns(v);
            assert_eq!((ss, cc), (s, c), "v = {v}");
        }
    }

    /// sin_cos_turns and atan2_turns against f64 over a dense sweep of the circle, and
    /// atan2_turns inverting sin_cos_turns.
    #[test]
    fn turns_against_f64() {
        let n = 1 << 20;
        let (mut es, mut ea, mut er) = (0.0f64, 0.0f64, 0.0f64);
        for i in 0..n {
            let v = (i as f32 + 0.5) / n as f32;
            let (s, c) = sin_cos_turns(v);
            let a = core::f64::consts::TAU * v as f64;
            es = es
                .max((s as f64 - a.sin()).abs())
                .max((c as f64 - a.cos()).abs());
            let back = atan2_turns(s, c);
            let d = (back as f64 - v as f64).abs();
            er = er.max(d.min(1.0 - d));
            let (y, x) = ((v as f64 * 7.0).sin() as f32, (v as f64 * 7.0).cos() as f32);
            let want = (y as f64)
                .atan2(x as f64)
                .rem_euclid(core::f64::consts::TAU)
                / core::f64::consts::TAU;
            let d = (atan2_turns(y, x) as f64 - want).abs();
            ea = ea.max(d.min(1.0 - d));
        }
        std::println!("sin_cos_turns abs {es:.3e}, atan2_turns abs {ea:.3e}, round trip {er:.3e}");
        assert!(es <= 1.2e-7, "{es}");
        assert!(ea <= 1.2e-7, "{ea}");
        assert!(er <= 2.4e-7, "{er}");
    }

    #[test]
    fn atan2_turns_edges() {
        assert_eq!(atan2_turns(0.0f32, 0.0), 0.0);
        assert_eq!(atan2_turns(-0.0f32, 1.0), 0.0);
        assert_eq!(atan2_turns(0.0f32, -1.0), 0.5);
        assert_eq!(atan2_turns(1.0f32, 0.0), 0.25);
        assert_eq!(atan2_turns(-1.0f32, -0.0), 0.75);
        let just_below = atan2_turns(-1e-30f32, 1.0);
        assert!(just_below < 1.0 && just_below > 0.99, "{just_below}");
    }

    #[test]
    fn lanes_bit_identical() {
        let mut xs = [0.0f32; 64];
        for (i, x) in xs.iter_mut().enumerate() {
            *x = (i as f32 * 0.618_034).fract() * 2.0 - 1.0;
        }
        xs[0] = -1.0;
        xs[1] = 1.0;
        xs[2] = -0.0;
        for chunk in xs.chunks_exact(8) {
            let v = f32x8::new(chunk.try_into().unwrap());
            let (s8, c8) = sin_cos_pi4(v);
            let a8 = atan_ratio_pi4(v.abs(), f32x8::ONE);
            let q = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
            let f8 = v.abs();
            let (qs8, qc8) = sin_cos_quarter_turns(f8, q);
            let t8 = atan2_turns(v, f32x8::splat(0.3) - v);
            for j in 0..8 {
                let x = chunk[j];
                let (s, c) = sin_cos_pi4(x);
                assert_eq!(s.to_bits(), s8.to_array()[j].to_bits());
                assert_eq!(c.to_bits(), c8.to_array()[j].to_bits());
                assert_eq!(
                    atan_ratio_pi4(x.abs(), 1.0).to_bits(),
                    a8.to_array()[j].to_bits()
                );
                let (qs, qc) = sin_cos_quarter_turns(x.abs(), core::num::Wrapping(j as u32));
                assert_eq!(qs.to_bits(), qs8.to_array()[j].to_bits());
                assert_eq!(qc.to_bits(), qc8.to_array()[j].to_bits());
                assert_eq!(
                    atan2_turns(x, 0.3 - x).to_bits(),
                    t8.to_array()[j].to_bits()
                );
            }
        }
    }
}
