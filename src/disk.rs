//! Disk warps: the unit square onto the unit disk, uniformly (all four are area-preserving,
//! so the density of the result is [`PDF`] `= 1/pi` with respect to area).
//!
//! | warp | maps | keeps | source |
//! |---|---|---|---|
//! | [`polar`] | `r = sqrt(u0)`, `theta = 2 pi u1` | nothing compact: strata become thin rings near the rim | textbook; pbrt-v4 `SampleUniformDiskPolar` |
//! | [`concentric`] | squares to rings, wedge by wedge | 4x4 strata stay compact | Shirley and Chiu 1997, "A Low Distortion Map Between Disk and Square" |
//! | [`polar4`] | one 2D point to four quadrants: `r = sqrt(u0)`, `theta = (pi/2)(u1 + quadrant)` | the point's strata, four times | Christensen 2018, "Progressive Sampling Strategies for Disk Light Sources" (Pixar TM 18-02) |
//! | [`concentric4`] | one 2D point to four quadrants: Shirley-Chiu on the quarter disk, turned | compact strata, four times | the same memo |
//!
//! The two quadrant warps use sample `i` with point `i / 4` of a 2D sequence and quadrant
//! `i % 4`; their `_indexed` and `_slice` forms do that bookkeeping.
//!
//! `u[0]` drives the radius and `u[1]` the angle (counter-clockwise from `+x`).
//!
//! **Out-of-range input** (every function here is total): each forward coordinate is first
//! mapped onto `[0, 1 - 2^-24]` — NaN, `-0.0`, negatives and `-inf` become `0`, values
//! `>= 1` and `+inf` become `1 - 2^-24`. Inverses clamp each coordinate of `p` to `[-1, 1]`
//! (NaN becomes `0`); a point outside the disk then maps like the rim point in its direction.
//!
//! **Domain guarantee**: every output lies in the closed unit disk in exact arithmetic
//! (`x^2 + y^2 <= 1` holds for the returned `f32` values, however the caller evaluates it). To
//! make that provable despite rounding in sin/cos, radii are clamped to `1 - 2^-23`
//! (only the outermost 1.2e-7 of the radius is affected; see `kernels::MAX_RADIUS`).
//!
//! **Precision** (tests in `tests/disk.rs`, against the same formulas in `f64` over 2^22
//! random points and dense edge sweeps): forward maps are within 1.5e-7 of the `f64` result
//! per coordinate (measured 1.35e-7; 2.5e-7 at the clamped rim, measured 1.8e-7);
//! `inverse(warp(u))` is within 5e-7 of `u`, the rim included, except on the singular sets
//! named on each inverse.

use crate::batch;
use crate::kernels::{
    MAX_RADIUS, atan_ratio_pi4, atan2_turns, sin_cos_pi4, sin_cos_quarter_turns, sin_cos_turns,
};
use crate::lanes::{Lane, UintLane, signed_unit, unit_interval};
use core::num::Wrapping;
use wide::{f32x8, u32x8};

/// Density of every disk warp's output with respect to area on the unit disk: `1 / pi`.
pub const PDF: f32 = core::f32::consts::FRAC_1_PI;

/// `min(r, MAX_RADIUS)` for `r >= 0` (compare and select, see `lanes`).
#[inline(always)]
fn clamp_radius<L: Lane>(r: L) -> L {
    let max = L::splat(MAX_RADIUS);
    L::select(max.simd_lt(r), max, r)
}

// ---------------------------------------------------------------------------------------
// Polar

#[inline(always)]
fn polar_body<L: Lane>(u: [L; 2]) -> [L; 2] {
    let r = clamp_radius(unit_interval(u[0]).sqrt());
    let (s, c) = sin_cos_turns(unit_interval(u[1]));
    [r * c, r * s]
}

#[inline(always)]
fn polar_inverse_body<L: Lane>(p: [L; 2]) -> [L; 2] {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    [unit_interval(x * x + y * y), atan2_turns(y, x)]
}

/// Polar map: `r = sqrt(u0)`, `theta = 2 pi u1`, returns `(r cos theta, r sin theta)`.
///
/// Exact range reduction: `4 u1` splits into a quarter-turn count and a fraction, so the
/// angle never passes through a rounded `2 pi u1`. Density [`PDF`]. Error against `f64`: at
/// most 1.5e-7 per coordinate. See the [module docs](self) for out-of-range input.
#[inline]
pub fn polar(u: [f32; 2]) -> [f32; 2] {
    polar_body(u)
}

/// [`polar`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar_x8(u: [f32x8; 2]) -> [f32x8; 2] {
    polar_body(u)
}

/// [`polar`] over a batch: writes `out[i] = polar(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count (a length mismatch never panics;
/// the rest of the longer slice is untouched). Bit-identical to the scalar form.
#[inline]
pub fn polar_slice(u: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    batch::map(u, out, polar_x8)
}

/// Inverse of [`polar`]: `u0 = x^2 + y^2`, `u1 = atan2(y, x) / (2 pi)` in `[0, 1)`.
///
/// Round trip `|u - polar_inverse(polar(u))| <= 5e-7` for `u` in `[0, 1)^2` (measured
/// 3.6e-7, at the rim), except on the singular set `u0 = 0` (the centre, where the angle is lost and
/// `u1 = 0` is returned). Near the seam `u1 -> 1` the result stays below 1 (it returns
/// `1 - 2^-24`, not 0). `y = -0.0` counts as the `u1 = 0` side.
#[inline]
pub fn polar_inverse(p: [f32; 2]) -> [f32; 2] {
    polar_inverse_body(p)
}

/// [`polar_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar_inverse_x8(p: [f32x8; 2]) -> [f32x8; 2] {
    polar_inverse_body(p)
}

/// [`polar_inverse`] over a batch, with the length rule of [`polar_slice`].
#[inline]
pub fn polar_inverse_slice(p: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    batch::map(p, out, polar_inverse_x8)
}

// ---------------------------------------------------------------------------------------
// Concentric

#[inline(always)]
fn concentric_body<L: Lane>(u: [L; 2]) -> [L; 2] {
    let (r, c, s) = concentric_parts(u);
    [r * c, r * s]
}

/// The concentric map in polar form: `(r, c, s)` with `concentric(u) = [r * c, r * s]`.
///
/// `r` is the signed radius of Shirley and Chiu (`a` or `b`, clamped in magnitude to
/// `MAX_RADIUS`), and `(c, s)` the direction for that sign convention (`c^2 + s^2` is 1 up to
/// the kernels' error). The sphere warps lift the disk point to the hemisphere from `|r|`
/// directly, where `1 - r^2 = (1 - |r|)(1 + |r|)` keeps its relative precision at the rim.
#[cfg_attr(not(feature = "sphere"), allow(dead_code))]
#[inline(always)]
pub(crate) fn concentric_parts<L: Lane>(u: [L; 2]) -> (L, L, L) {
    let one = L::splat(1.0);
    let two = L::splat(2.0);
    let a = two * unit_interval(u[0]) - one;
    let b = two * unit_interval(u[1]) - one;
    // Textbook: if |a| > |b| { r = a, phi = (pi/4)(b/a) } else { r = b, phi = pi/2 - (pi/4)(a/b) }.
    let a_major = b.abs().simd_lt(a.abs());
    let r = L::select(a_major, a, b);
    let n = L::select(a_major, b, a);
    let zero = L::splat(0.0);
    // r == 0 only at the centre, where n == 0 too: t = 0 instead of 0/0.
    let t = L::select(r.simd_eq(zero), zero, n / r);
    let r = clamp_radius(r.abs()).flip_sign(r.sign_bit());
    // cos(pi/2 - x) = sin(x): the b-major wedges swap sin and cos.
    let (s, c) = sin_cos_pi4(t);
    (r, L::select(a_major, c, s), L::select(a_major, s, c))
}

#[inline(always)]
pub(crate) fn concentric_inverse_body<L: Lane>(p: [L; 2]) -> [L; 2] {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    let (ax, ay) = (x.abs(), y.abs());
    let x_major = ay.simd_lt(ax);
    let r = (x * x + y * y).sqrt();
    let w = atan_ratio_pi4(L::select(x_major, ay, ax), L::select(x_major, ax, ay));
    // The major coordinate of the square point is +-r, the minor one +-r w, with the signs of
    // x and y (see `concentric_body`: sign(x) = sign(a), sign(y) = sign(b)).
    let rw = r * w;
    let a = L::select(x_major, r, rw).flip_sign(x.sign_bit());
    let b = L::select(x_major, rw, r).flip_sign(y.sign_bit());
    let half = L::splat(0.5);
    [
        unit_interval(a * half + half),
        unit_interval(b * half + half),
    ]
}

/// Concentric map of Shirley and Chiu (1997): `a = 2 u0 - 1`, `b = 2 u1 - 1`; if `|a| > |b|`
/// then `r = a`, `phi = (pi/4)(b / a)`, else `r = b`, `phi = pi/2 - (pi/4)(a / b)`; returns
/// `(r cos phi, r sin phi)`, and the centre `u = (1/2, 1/2)` maps to the origin.
///
/// Exactly the textbook map (ties `|a| = |b|` take the second branch, as in the paper), but
/// branch-free: one division, sin and cos on `[-pi/4, pi/4]`, and a mask that swaps them.
/// Concentric squares of the domain map to concentric circles, so compact strata stay
/// compact. Density [`PDF`]. Error against `f64`: at most 1.5e-7 per coordinate. See the
/// [module docs](self) for out-of-range input.
#[inline]
pub fn concentric(u: [f32; 2]) -> [f32; 2] {
    concentric_body(u)
}

/// [`concentric`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric_x8(u: [f32x8; 2]) -> [f32x8; 2] {
    concentric_body(u)
}

/// [`concentric`] over a batch, with the length rule of [`polar_slice`]. Bit-identical to
/// the scalar form.
#[inline]
pub fn concentric_slice(u: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    batch::map(u, out, concentric_x8)
}

/// Inverse of [`concentric`]: the wedge is chosen by `|x|` vs `|y|`, the radius is
/// `sqrt(x^2 + y^2)` and the in-wedge coordinate `(4/pi) atan(minor / major)`.
///
/// Round trip `|u - concentric_inverse(concentric(u))| <= 5e-7` for `u` in `[0, 1)^2`
/// (measured 1.2e-7), except on the singular set `u = (1/2, 1/2)` (the centre, returned
/// exactly) — there is no other: the map is continuous across wedge diagonals.
#[inline]
pub fn concentric_inverse(p: [f32; 2]) -> [f32; 2] {
    concentric_inverse_body(p)
}

/// [`concentric_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric_inverse_x8(p: [f32x8; 2]) -> [f32x8; 2] {
    concentric_inverse_body(p)
}

/// [`concentric_inverse`] over a batch, with the length rule of [`polar_slice`].
#[inline]
pub fn concentric_inverse_slice(p: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    batch::map(p, out, concentric_inverse_x8)
}

// ---------------------------------------------------------------------------------------
// Polar4

#[inline(always)]
fn polar4_body<L: Lane>(u: [L; 2], quadrant: L::U) -> [L; 2] {
    let r = clamp_radius(unit_interval(u[0]).sqrt());
    let (s, c) = sin_cos_quarter_turns(unit_interval(u[1]), quadrant);
    [r * c, r * s]
}

#[inline(always)]
fn polar4_inverse_body<L: Lane>(p: [L; 2]) -> ([L; 2], L::U) {
    let [u0, turns] = polar_inverse_body(p);
    let v = turns * L::splat(4.0);
    let q = v.to_uint();
    ([u0, v - L::from_uint(q)], q)
}

/// Polar4 (Christensen 2018): one 2D point gives four disk samples, one per quadrant.
/// `r = sqrt(u0)`, `theta = (pi/2) u1 + (pi/2) quadrant`; only `quadrant % 4` is used.
///
/// Used for sample `i` with the point `i / 4` of a 2D sequence and `quadrant = i % 4` — the
/// helpers [`polar4_indexed`] and [`polar4_slice`] do this bookkeeping. The four samples of
/// one point are rotations of each other by quarter turns, which halves the error of disk-light
/// sampling at high sample counts in Christensen's measurements. For `u1 in [0, 1)`,
/// `polar(u) == polar4([u0, frac(4 u1)], floor(4 u1))` bit for bit. Density [`PDF`] (over
/// a uniformly chosen quadrant). Error against `f64`: at most 1.5e-7 per coordinate.
#[inline]
pub fn polar4(u: [f32; 2], quadrant: u32) -> [f32; 2] {
    polar4_body(u, Wrapping(quadrant))
}

/// [`polar4`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar4_x8(u: [f32x8; 2], quadrant: u32x8) -> [f32x8; 2] {
    polar4_body(u, quadrant)
}

/// Disk sample `index` of a polar4 stream: `polar4(point(index / 4), index % 4)`.
///
/// `point` returns 2D point `k` of your sequence, e.g.
/// `polar4_indexed(i, |k| my_sampler.get(k))`; it is called once, with `index / 4`.
#[inline]
pub fn polar4_indexed(index: u32, point: impl FnOnce(u32) -> [f32; 2]) -> [f32; 2] {
    polar4(point(index >> 2), index & 3)
}

/// [`polar4_indexed`] for eight sample indices at once (any indices, not only consecutive).
#[inline]
pub fn polar4_indexed_x8(index: u32x8, points: impl FnOnce(u32x8) -> [f32x8; 2]) -> [f32x8; 2] {
    polar4_x8(points(index >> 2), index & u32x8::splat(3))
}

/// Expands 2D points into polar4 disk samples, four per point: `out[i] =
/// polar4(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`; returns that
/// count. Bit-identical to the scalar form.
#[inline]
pub fn polar4_slice(points: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    four_per_point(points, out, polar4_x8)
}

/// `out[i] = warp(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`, eight
/// samples (two points) per call of the 8-wide `warp`; returns that count. The slice form of
/// the quadrant warps.
#[inline(always)]
fn four_per_point(
    points: &[[f32; 2]],
    out: &mut [[f32; 2]],
    warp: impl Fn([f32x8; 2], u32x8) -> [f32x8; 2],
) -> usize {
    let n = out.len().min(points.len().saturating_mul(4));
    let out = out.get_mut(..n).unwrap_or(&mut []);
    let quadrants = u32x8::new([0, 1, 2, 3, 0, 1, 2, 3]);
    let (pairs, _) = points.as_chunks::<2>();
    let (groups, rest) = out.as_chunks_mut::<8>();
    let spread = |p: &[[f32; 2]; 2]| {
        let [a, b] = *p;
        [
            f32x8::new([a[0], a[0], a[0], a[0], b[0], b[0], b[0], b[0]]),
            f32x8::new([a[1], a[1], a[1], a[1], b[1], b[1], b[1], b[1]]),
        ]
    };
    for (dst, pair) in groups.iter_mut().zip(pairs) {
        *dst = batch::store(warp(spread(pair), quadrants));
    }
    if !rest.is_empty() {
        // 1 to 7 samples left: they come from the next one or two points.
        let first = groups.len() * 2;
        let pick = |k: usize| points.get(first + k).copied().unwrap_or([0.0; 2]);
        let res = batch::store(warp(spread(&[pick(0), pick(1)]), quadrants));
        for (d, r) in rest.iter_mut().zip(res.iter()) {
            *d = *r;
        }
    }
    n
}

/// Inverse of [`polar4`]: returns `(u, quadrant)` with `quadrant` in `0..4`.
///
/// Round trip within 5e-7 for `u` in `[0, 1)^2` (measured 3.0e-7: the angle fraction is
/// scaled by 4), except at the centre `u0 = 0`, and at the quadrant seams, where `u1 -> 1` of
/// one quadrant and `u1 = 0` of the next are the same direction (compare modulo the seam).
#[inline]
pub fn polar4_inverse(p: [f32; 2]) -> ([f32; 2], u32) {
    let (u, q) = polar4_inverse_body(p);
    (u, q.0)
}

/// [`polar4_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar4_inverse_x8(p: [f32x8; 2]) -> ([f32x8; 2], u32x8) {
    polar4_inverse_body(p)
}

// ---------------------------------------------------------------------------------------
// Concentric4

/// The quarter turn `quadrant % 4` applied to `(x, y)`, exactly: a swap and sign flips
/// (`(x, y) -> (-y, x)` per quarter turn).
#[inline(always)]
fn quarter_turns<L: Lane>(x: L, y: L, quadrant: L::U) -> [L; 2] {
    let one = <L::U as UintLane>::splat(1);
    let odd = (quadrant & one).simd_eq(one);
    let (x, y) = (L::select(odd, y, x), L::select(odd, x, y));
    // Quadrants 1 and 2 negate the new x, quadrants 2 and 3 the new y.
    let neg_x = ((quadrant ^ quadrant.shr(1)) & one).shl(31);
    let neg_y = (quadrant.shr(1) & one).shl(31);
    [x.flip_sign(neg_x), y.flip_sign(neg_y)]
}

#[inline(always)]
fn concentric4_body<L: Lane>(u: [L; 2], quadrant: L::U) -> [L; 2] {
    let (a, b) = (unit_interval(u[0]), unit_interval(u[1]));
    // Shirley-Chiu on the quarter disk: a > b: r = a, phi = (pi/4)(b/a); else r = b,
    // phi = pi/2 - (pi/4)(a/b). t = minor / major in [0, 1]; 0 at the origin.
    let a_major = b.simd_lt(a);
    let r = L::select(a_major, a, b);
    let zero = L::splat(0.0);
    let t = L::select(r.simd_eq(zero), zero, L::select(a_major, b, a) / r);
    let r = clamp_radius(r);
    let (s, c) = sin_cos_pi4(t);
    // cos(pi/2 - x) = sin(x): the b-major wedge swaps sin and cos.
    let x = r * L::select(a_major, c, s);
    let y = r * L::select(a_major, s, c);
    quarter_turns(x, y, quadrant)
}

#[inline(always)]
fn concentric4_inverse_body<L: Lane>(p: [L; 2]) -> ([L; 2], L::U) {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    let zero = L::splat(0.0);
    let splat = <L::U as UintLane>::splat;
    // Quadrant q holds the quarter turn by q of {x > 0, y >= 0} (the origin counts as 0):
    // each axis belongs to the quadrant in which it is the u1 = 0 edge.
    let q = L::U::select(
        zero.simd_lt(y) & x.simd_le(zero),
        splat(1),
        L::U::select(
            y.simd_le(zero) & x.simd_lt(zero),
            splat(2),
            L::U::select(y.simd_lt(zero) & zero.simd_le(x), splat(3), splat(0)),
        ),
    );
    // Turn back into the first quadrant (three more quarter turns); the magnitudes are all
    // that is left to read, so the signs of zeros do not matter.
    let [x, y] = quarter_turns(x, y, q * splat(3));
    let (x, y) = (x.abs(), y.abs());
    let x_major = y.simd_lt(x);
    let r = (x * x + y * y).sqrt();
    let w = atan_ratio_pi4(L::select(x_major, y, x), L::select(x_major, x, y));
    let rw = r * w;
    (
        [
            unit_interval(L::select(x_major, r, rw)),
            unit_interval(L::select(x_major, rw, r)),
        ],
        q,
    )
}

/// Concentric4 (Christensen 2018): the Shirley-Chiu map of the unit square onto the quarter
/// disk of the first quadrant, turned by `quadrant` quarter turns; one 2D point gives four
/// disk samples, one per quadrant, like [`polar4`] but with compact strata.
///
/// `a = u0`, `b = u1`; if `a > b` then `r = a`, `phi = (pi/4)(b / a)`, else `r = b`,
/// `phi = pi/2 - (pi/4)(a / b)`; the point `(r cos phi, r sin phi)` is then turned by
/// `quadrant % 4` quarter turns counter-clockwise, exactly (a swap and sign flips:
/// `concentric4(u, q + 1)` is `concentric4(u, q)` turned by `(x, y) -> (-y, x)`, bit for bit).
/// The square's diagonal maps to the quadrant's bisector, its edges `u0 = 0` and `u1 = 0` to
/// the quadrant's two axes, and `u = (0, 0)` to the centre.
///
/// Area-preserving onto the quarter disk (`r dr dphi = (pi/4) da db`), so with `quadrant`
/// uniform over `0..4` the density is [`PDF`]. Error against `f64`: at most 1.5e-7 per
/// coordinate (the kernels of [`concentric`]); the domain guarantee and out-of-range rule of
/// the [module docs](self) apply, and every `quadrant` is valid (only `quadrant % 4` is used).
/// Used for sample `i` with point `i / 4` of a 2D sequence and `quadrant = i % 4`: see
/// [`concentric4_indexed`] and [`concentric4_slice`].
///
/// Christensen's memo ("Progressive Sampling Strategies for Disk Light Sources", Pixar TM
/// 18-02) measures it beside [`polar4`]. In the report (`docs/REPORT.md`, Owen-scrambled
/// pmj02bn, 256 samples per pixel) it ties the other warps within 10% in penumbrae but is 3x
/// worse than [`concentric`] and 11x worse than [`polar4`] in fully lit pixels: the
/// quarter-disk map has a derivative kink along the square's diagonal `u0 = u1`, which limits
/// the convergence on a smooth integrand (`N^-2.4` against polar4's `N^-3.0`). Prefer
/// [`polar4`].
#[inline]
pub fn concentric4(u: [f32; 2], quadrant: u32) -> [f32; 2] {
    concentric4_body(u, Wrapping(quadrant))
}

/// [`concentric4`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric4_x8(u: [f32x8; 2], quadrant: u32x8) -> [f32x8; 2] {
    concentric4_body(u, quadrant)
}

/// Disk sample `index` of a concentric4 stream: `concentric4(point(index / 4), index % 4)`;
/// `point` is called once, with `index / 4`.
#[inline]
pub fn concentric4_indexed(index: u32, point: impl FnOnce(u32) -> [f32; 2]) -> [f32; 2] {
    concentric4(point(index >> 2), index & 3)
}

/// [`concentric4_indexed`] for eight sample indices at once (any indices, not only
/// consecutive).
#[inline]
pub fn concentric4_indexed_x8(
    index: u32x8,
    points: impl FnOnce(u32x8) -> [f32x8; 2],
) -> [f32x8; 2] {
    concentric4_x8(points(index >> 2), index & u32x8::splat(3))
}

/// Expands 2D points into concentric4 disk samples, four per point: `out[i] =
/// concentric4(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`; returns that
/// count. Bit-identical to the scalar form.
#[inline]
pub fn concentric4_slice(points: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    four_per_point(points, out, concentric4_x8)
}

/// Inverse of [`concentric4`]: returns `(u, quadrant)` with `quadrant` in `0..4`.
///
/// The quadrant is the quarter turn of `{x > 0, y >= 0}` holding `p` (the origin gives 0);
/// `p` is turned back into the first quadrant and inverted there like [`concentric_inverse`]
/// (`r = sqrt(x^2 + y^2)`, in-wedge coordinate `(4/pi) atan(minor / major)`). Round trip
/// within 5e-7 for `u` in `[0, 1)^2`, except on the singular sets: the centre (`u = (0, 0)`),
/// and the edge `u0 = 0`, which lies on the axis shared with the next quadrant and comes back
/// as that quadrant's `u1 = 0` edge (`(u1, 0)` and `quadrant + 1`). Any input is accepted,
/// under the module's inverse rule.
#[inline]
pub fn concentric4_inverse(p: [f32; 2]) -> ([f32; 2], u32) {
    let (u, q) = concentric4_inverse_body(p);
    (u, q.0)
}

/// [`concentric4_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric4_inverse_x8(p: [f32x8; 2]) -> ([f32x8; 2], u32x8) {
    concentric4_inverse_body(p)
}
