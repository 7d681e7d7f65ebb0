//! Three-vectors over a [`Lane`], shared by the spherical lights and the microfacet warps: the
//! light's frame (translated to the shading point and scaled by a power of two), and the small
//! cancellation-free helpers both families use.

use crate::lanes::{Lane, UintLane};

pub(crate) type V<L> = [L; 3];

#[inline(always)]
pub(crate) fn sub<L: Lane>(a: V<L>, b: V<L>) -> V<L> {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

#[inline(always)]
pub(crate) fn add<L: Lane>(a: V<L>, b: V<L>) -> V<L> {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

#[inline(always)]
pub(crate) fn scale<L: Lane>(a: V<L>, k: L) -> V<L> {
    [a[0] * k, a[1] * k, a[2] * k]
}

#[inline(always)]
pub(crate) fn dot<L: Lane>(a: V<L>, b: V<L>) -> L {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

#[inline(always)]
pub(crate) fn cross<L: Lane>(a: V<L>, b: V<L>) -> V<L> {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[inline(always)]
pub(crate) fn norm<L: Lane>(a: V<L>) -> L {
    dot(a, a).sqrt()
}

/// `x` clamped to `[0, hi]`; NaN and `-0.0` become `+0.0` (compare and select).
#[inline(always)]
pub(crate) fn clamp0<L: Lane>(x: L, hi: L) -> L {
    L::select(
        L::splat(0.0).simd_lt(x),
        L::select(x.simd_lt(hi), x, hi),
        L::splat(0.0),
    )
}

/// `0 < x < +inf` (false for NaN).
#[inline(always)]
pub(crate) fn positive_finite<L: Lane>(x: L) -> L::Mask {
    L::splat(0.0).simd_lt(x) & x.simd_lt(L::splat(f32::INFINITY))
}

/// The chord `y/|y| - x/|x|` between the directions of `x` and `y`, from the accurately known
/// difference `e = y - x` (an edge of the light, not a difference of nearly equal unit
/// vectors): `(e - x^ (e . (x + y)) / (|x| + |y|)) / |y|`, since
/// `|x| - |y| = -(e . (x + y)) / (|x| + |y|)`. Relative error a few ulps whatever the angle.
#[inline(always)]
pub(crate) fn chord<L: Lane>(x: V<L>, y: V<L>, e: V<L>, lx: L, ly: L) -> V<L> {
    let k = dot(e, add(x, y)) / ((lx + ly) * lx);
    chord_k(x, e, k, L::splat(1.0) / ly)
}

/// [`chord`] given `k = e . (x + y) / ((|x| + |y|) |x|)` and `1 / |y|` (a caller that shares
/// their divisions).
#[inline(always)]
pub(crate) fn chord_k<L: Lane>(x: V<L>, e: V<L>, k: L, inv_ly: L) -> V<L> {
    scale(sub(e, scale(x, k)), inv_ly)
}

/// Whether every component of every vector is finite: `x * 0 == 0` fails for NaN and inf.
#[inline(always)]
pub(crate) fn all_finite<L: Lane, const N: usize>(vs: [V<L>; N]) -> L::Mask {
    let zero = L::splat(0.0);
    let mut acc = zero;
    for v in vs {
        acc = acc + v[0] * zero + v[1] * zero + v[2] * zero;
    }
    acc.simd_eq(zero)
}

/// `v` with every component below the smallest normal `f32` (`2^-126`) in magnitude made 0:
/// the rule "coordinate differences below `2^-126` count as zero", applied to each
/// difference before the power-of-two scaling (which would otherwise lift a subnormal
/// height next to normal coordinates into the computation, where its few significant bits
/// decide the side of the plane), and flush-proof (a device that flushes subnormals sees
/// the same zeros).
#[inline(always)]
pub(crate) fn flush_subnormal<L: Lane>(v: V<L>) -> V<L> {
    let tiny = L::splat(f32::MIN_POSITIVE);
    v.map(|x| L::select(x.abs().simd_lt(tiny), L::splat(0.0), x))
}

/// The largest `|x|` of `xs` (compare and select: NaN never wins).
#[inline(always)]
fn max_abs<L: Lane>(xs: &[L]) -> L {
    let mut m = L::splat(0.0);
    for x in xs {
        let a = x.abs();
        m = L::select(m.simd_lt(a), a, m);
    }
    m
}

/// The bits of the power of two `2^(127 - e)` that scales `m` (of biased exponent `e`) into
/// `[1, 2)`, and whether `m` is a normal number of exponent below `limit`.
#[inline(always)]
fn pow2_bits<L: Lane>(m: L, limit: u32) -> (L::U, L::Mask) {
    let e = m.to_bits().shr(23);
    let ok = L::U::splat(0).simd_lt(e) & e.simd_lt(L::U::splat(limit));
    ((L::U::splat(254) - e).shl(23), ok)
}

/// A power of two `2^k` that lifts the largest magnitude of `xs` into `[1, 2)` where it is a
/// normal number below 1, else 1: multiplying every `x` by it is exact and changes no bits of
/// any later product, quotient or ratio that did not underflow, while products that did
/// underflow become exact or correctly rounded.
#[inline(always)]
pub(crate) fn pow2_lift<L: Lane, const N: usize>(xs: [L; N]) -> L {
    let (bits, ok) = pow2_bits(max_abs(&xs), 127);
    L::from_bits(L::U::select(ok, bits, L::splat(1.0).to_bits()))
}

/// A power of two `2^k` such that `2^k max|x_i|` lies in `[1, 2)`, and whether it exists: the
/// largest magnitude must be a normal `f32` below `2^127` (smaller differences count as zero,
/// larger as non-finite). Scaling by it is exact, so every length, dot and cross product of
/// the scaled vectors is free of overflow and (but for what the caller's data underflows)
/// of underflow.
#[inline(always)]
pub(crate) fn pow2_scale<L: Lane, const N: usize>(vs: [V<L>; N]) -> (L, L::Mask) {
    let (bits, ok) = pow2_bits(max_abs(vs.as_flattened()), 254);
    (L::from_bits(L::U::select(ok, bits, L::U::splat(0))), ok)
}

/// `x` below `f32::MAX`, else (`+inf`, NaN) `f32::MAX`: a density kept finite.
#[inline(always)]
pub(crate) fn below_max<L: Lane>(x: L) -> L {
    L::select(x.simd_lt(L::splat(f32::MAX)), x, L::splat(f32::MAX))
}

/// The area-sampling density where area sampling is defined (`ok`), kept below `f32::MAX`;
/// 0 elsewhere.
#[inline(always)]
pub(crate) fn area_density<L: Lane>(ok: L::Mask, pdf: L) -> L {
    L::select(ok, below_max(pdf), L::splat(0.0))
}

/// `1 / (4 pi)`: solid angles are carried in turns of `4 pi` (`atan2_turns` of the
/// Van Oosterom-Strackee half angle) and the density is `INV_4PI / turns`.
pub(crate) const INV_4PI: f32 = (0.25 * core::f64::consts::FRAC_1_PI) as f32;
/// `4 pi`.
pub(crate) const FOUR_PI: f32 = (4.0 * core::f64::consts::PI) as f32;
