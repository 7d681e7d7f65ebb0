//! The cosine-aware variant: `u` warped by a bilinear density fitted to the receiver's clamped
//! cosine at the light's corners, then mapped by the spherical map (Hart, Pharr, Mueller,
//! Lopes, McGuire and Shirley 2020, "Practical Product Sampling by Fitting and Composing
//! Warps", EGSR; pbrt-v4's triangle light applies the same idea). Our own derivation: the
//! marginal in `y` and the conditional in `x` are linear densities, inverted in closed form.

use super::rectangle::{self, Rect};
use super::triangle::{self, Tri};
use crate::lanes::{Lane, ONE_MINUS_EPSILON, unit_interval};
use crate::vec3::*;

/// Inverse CDF of the density `2 ((1 - x) a + x b) / (a + b)` on `[0, 1]` (`a, b` in
/// `[0, 1]`, `a + b > 0`): the root of `(b - a) x^2 + 2 a x = u (a + b)`, written without
/// cancellation as `x = u (a + b) / (a + sqrt((1 - u) a^2 + u b^2))`. The `0 / 0` of `a = 0,
/// u = 0` becomes 0; the result is clamped to `[0, 1 - 2^-24]`.
#[inline(always)]
fn sample_linear<L: Lane>(u: L, a: L, b: L) -> L {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let x = u * (a + b) / (a + ((one - u) * (a * a) + u * (b * b)).sqrt());
    let top = L::splat(ONE_MINUS_EPSILON);
    L::select(zero.simd_lt(x), L::select(x.simd_lt(top), x, top), zero)
}

/// The weights made usable: negative and NaN to 0, then divided by their sum; and whether the
/// sum is a normal finite number (at least `2^-126`, the smallest normal `f32`; else the warp
/// is the identity with density 1). A subnormal sum counts as zero: its reciprocal
/// overflows, and a device that flushes subnormals would see zero there anyway.
#[inline(always)]
fn normalise<L: Lane>(w: [L; 4]) -> ([L; 4], L::Mask) {
    let zero = L::splat(0.0);
    let w = w.map(|x| L::select(zero.simd_lt(x), x, zero));
    let sum = w[0] + w[1] + w[2] + w[3];
    let ok = L::splat(f32::MIN_POSITIVE).simd_le(sum) & sum.simd_lt(L::splat(f32::INFINITY));
    let inv = L::select(ok, L::splat(1.0) / sum, zero);
    (w.map(|x| x * inv), ok)
}

/// `4 ((1-x)(1-y) w00 + x(1-y) w10 + (1-x) y w01 + x y w11)` for weights summing to 1.
#[inline(always)]
fn lerp_pdf<L: Lane>(x: L, y: L, w: [L; 4]) -> L {
    let one = L::splat(1.0);
    let (x1, y1) = (one - x, one - y);
    L::splat(4.0) * (x1 * y1 * w[0] + x * y1 * w[1] + x1 * y * w[2] + x * y * w[3])
}

#[inline(always)]
pub(super) fn bilinear_pdf_body<L: Lane>(p: [L; 2], w: [L; 4]) -> L {
    let one = L::splat(1.0);
    let (w, ok) = normalise(w);
    let (x, y) = (clamp0(p[0], one), clamp0(p[1], one));
    L::select(ok, lerp_pdf(x, y, w), one)
}

#[inline(always)]
pub(super) fn bilinear_body<L: Lane>(u: [L; 2], w: [L; 4]) -> ([L; 2], L) {
    let one = L::splat(1.0);
    let (u0, u1) = (unit_interval(u[0]), unit_interval(u[1]));
    let (w, ok) = normalise(w);
    let y = sample_linear(u1, w[0] + w[1], w[2] + w[3]);
    let y1 = one - y;
    let x = sample_linear(u0, y1 * w[0] + y * w[2], y1 * w[1] + y * w[3]);
    let pdf = lerp_pdf(x, y, w);
    (
        [L::select(ok, x, u0), L::select(ok, y, u1)],
        L::select(ok, pdf, one),
    )
}

/// `max(0, n . d / |d|)` for each direction, with `n` scaled by a power of two (its length
/// cancels in the normalised weights); NaN (zero or non-finite `d` or `n`) gives 0.
#[inline(always)]
fn clamped_cosines<L: Lane, const N: usize>(n: V<L>, d: [V<L>; N]) -> [L; N] {
    let zero = L::splat(0.0);
    let (k, ok) = pow2_scale([n]);
    let n = scale(n, k);
    d.map(|d| {
        let c = dot(n, d) / norm(d);
        L::select(ok & zero.simd_lt(c), c, zero)
    })
}

/// The triangle's corner weights: the square's corners `(0, 0), (1, 0), (0, 1), (1, 1)` map
/// to `v1, v1, v0, v2` under Arvo's map (the side `u1 = 0` is the apex `v1`).
#[inline(always)]
pub(super) fn triangle_weights<L: Lane>(t: &Tri<L>, n: V<L>) -> [L; 4] {
    let [c0, c1, c2] = clamped_cosines(n, t.a);
    [c1, c1, c0, c2]
}

/// The rectangle's corner weights: `corner`, `+ ex`, `+ ey`, `+ ex + ey` (with `ey` made
/// orthogonal to `ex`, as the map does).
#[inline(always)]
pub(super) fn rectangle_weights<L: Lane>(r: &Rect<L>, n: V<L>) -> [L; 4] {
    let c10 = add(r.c, r.ex);
    clamped_cosines(n, [r.c, c10, add(r.c, r.eyp), add(c10, r.eyp)])
}

/// `u` warped by the bilinear weights `w`, then mapped by `sample` (a prepared light's map):
/// the point, and the solid-angle density times the bilinear factor, kept finite.
#[inline(always)]
pub(super) fn warped<L: Lane, P, const N: usize>(
    pr: &P,
    w: [L; 4],
    u: [L; 2],
    sample: impl Fn(&P, [L; 2]) -> ([L; N], L),
) -> ([L; N], L) {
    let (u, factor) = bilinear_body(u, w);
    let (x, pdf) = sample(pr, u);
    (x, below_max(pdf * factor))
}

#[inline(always)]
pub(super) fn triangle_body<L: Lane>(v: [V<L>; 3], p: V<L>, n: V<L>, u: [L; 2]) -> ([L; 3], L) {
    let pr = triangle::prepare(v, p);
    let w = triangle_weights(&pr.t, n);
    warped(&pr, w, u, triangle::sample_prepared)
}

#[inline(always)]
pub(super) fn rectangle_body<L: Lane>(
    corner: V<L>,
    ex: V<L>,
    ey: V<L>,
    p: V<L>,
    n: V<L>,
    u: [L; 2],
) -> ([L; 2], L) {
    let pr = rectangle::prepare(corner, ex, ey, p);
    let w = rectangle_weights(&pr.r, n);
    warped(&pr, w, u, rectangle::sample_prepared)
}
