//! Clarberg's equal-area octahedral map between the unit square and the unit sphere, its
//! inverse, and the edge wrapping an octahedral environment map needs for filtering.
//!
//! With `a = 2 u0 - 1`, `b = 2 u1 - 1`, the rotated square `|a| + |b| <= 1` is the upper
//! hemisphere and the four corner triangles are the lower one, folded underneath. Per
//! quadrant (signs of `a`, `b` become the signs of `x`, `y`) the point has "radius"
//! `r = |a| + |b|` on the upper side and `r = (1 - |a|) + (1 - |b|)` on the lower side, and
//! in both cases `z = +-(1 - r^2)`, `sqrt(x^2 + y^2) = r sqrt(2 - r^2)`, and the azimuth is
//! `phi = (pi/2) q / r` with `q` the `|b|`-side share of `r` (`|b|` above, `1 - |a|` below).
//! Lambert's azimuthal projection behind it (`z = 1 - r^2`) is what makes it equal-area.
//!
//! Precision choices, each measured in `tests/sphere.rs`:
//!
//! * The lower side's coordinates `1 - |a|`, `1 - |b|` are exact for `|a|, |b| >= 1/2`
//!   (Sterbenz), so `r` keeps its relative precision at the `-z` pole (the corners) — the
//!   textbook `r = 1 - |1 - (|a| + |b|)|` loses it there.
//! * The azimuth is evaluated like the concentric disk map: `t = 2 min(p, q) / r` in `[0, 1]`,
//!   sin and cos of `(pi/4) t`, and a swap — never `cos(pi/4 + x)`, which cancels.
//! * `z = 1 - r^2` and `sqrt(x^2 + y^2) = sqrt(r^2 (2 - r^2))` use the same rounded `r^2`, so
//!   `z^2 + x^2 + y^2 = 1` up to the last roundings and the kernel's `sin^2 + cos^2`
//!   (`r sqrt(2 - r^2)` measured 2.4e-7 off unit length, this form 1.83e-7).
//! * The inverse computes `r^2 = 1 - |z|` as `(x^2 + y^2) / (1 + |z|)` (in its scale-free
//!   form, see [`equal_area_inverse`]): near the poles `1 - |z|` is a difference of nearly
//!   equal numbers and loses up to all of its digits.
//! * The azimuth of the inverse is `atan(min / max)` on `[0, 1]` (the kernel's best range),
//!   and the square point's in-quadrant coordinates are `r w / 2` and `r - r w / 2` (no
//!   cancellation).
//! * Sign bits, not comparisons, carry `a` and `b` into `x` and `y` and back, so `-0.0` on a
//!   seam maps to its own side (see [`equal_area_inverse`]).

use crate::lanes::{Lane, UintLane, unit_interval};
use crate::slices;
use crate::trig::{atan_ratio_pi4, sin_cos_pi4};
use wide::{f32x8, f32x16};

use super::{clamped_direction, finite_density};

// ---------------------------------------------------------------------------------------
// Forward

#[inline(always)]
fn equal_area_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let two = L::splat(2.0);
    let a = two * unit_interval(u[0]) - one;
    let b = two * unit_interval(u[1]) - one;
    let (ua, ub) = (a.abs(), b.abs());
    // Fold the lower hemisphere (the corner triangles) onto the upper one: p and q are the
    // in-quadrant coordinates measured from the nearer pole, each exact or rounded once.
    let lower = one.simd_lt(ua + ub);
    let p = L::select(lower, one - ub, ua);
    let q = L::select(lower, one - ua, ub);
    let r = p + q;
    // phi = (pi/2) q / r, evaluated on [0, pi/4] and mirrored: the smaller share over r.
    let q_major = p.simd_lt(q);
    let m = L::select(q_major, p, q);
    // r == 0 only at the poles (p = q = 0): t = 0 instead of 0/0.
    let t = L::select(r.simd_eq(zero), zero, (m + m) / r);
    let (s, c) = sin_cos_pi4(t);
    let cos_phi = L::select(q_major, s, c);
    let sin_phi = L::select(q_major, c, s);
    // z = 1 - r^2 and sqrt(x^2 + y^2) = sqrt(r^2 (2 - r^2)) from the same rounded r^2, so
    // that z^2 + rho^2 = 1 holds up to the last roundings (r sqrt(2 - r^2) mixes r^2 and its
    // rounded value and measured 2.4e-7 off unit length instead of 1.9e-7).
    let r2 = r * r;
    let z_sign = L::U::select(lower, L::U::splat(0x8000_0000), L::U::splat(0));
    let z = (one - r2).flip_sign(z_sign);
    let rho = (r2 * (two - r2)).sqrt();
    [
        (rho * cos_phi).flip_sign(a.sign_bit()),
        (rho * sin_phi).flip_sign(b.sign_bit()),
        z,
    ]
}

/// Clarberg's equal-area octahedral map (2008): the unit square onto the unit sphere, with
/// the square's centre at `+z` and its four corners at `-z`.
///
/// `a = 2 u0 - 1`, `b = 2 u1 - 1`; `d = 1 - (|a| + |b|)`, `r = 1 - |d|`,
/// `phi = (pi/4) ((|b| - |a|) / r + 1)` (`r = 0`: a pole), `z = sign(d) (1 - r^2)`,
/// `(x, y) = r sqrt(2 - r^2) (cos phi, sin phi)` with the signs of `a`, `b`.
///
/// Branch-free: one division, one square root, sin and cos on `[-pi/4, pi/4]`. `r` keeps its
/// relative precision at both poles (on the lower side it is `(1 - |a|) + (1 - |b|)`, exact
/// terms, instead of `1 - |1 - (|a| + |b|)|`), the azimuth is evaluated as `(pi/4) t` with
/// `t = 2 min / r` in `[0, 1]` plus a swap (never `cos(pi/4 + x)`, which cancels), and `z` and
/// `sqrt(x^2 + y^2) = sqrt(r^2 (2 - r^2))` come from the same rounded `r^2`. Area-preserving: uniform `u` gives uniform directions, density
/// [`UNIFORM_PDF`](super::UNIFORM_PDF) `= 1/(4 pi)`; a density over the square converts with
/// [`equal_area_pdf_to_solid_angle`].
///
/// Precision against `f64` (2^22 random points plus dense sweeps of both poles, the equator
/// fold and the seams): `| |d| - 1 | <= 2e-7` (measured 1.83e-7; the kernels' `sin^2 + cos^2`
/// alone spans `1 - 2.5e-7 .. 1 + 1.0e-7`), each coordinate within 2e-7 of the `f64` map
/// (measured 1.65e-7). Signs of `x`, `y` are those of `a`, `b` even when the coordinate is
/// zero (`-0.0` where `a < 0`, e.g. on the edge `u1 = 0` left of its midpoint, where the lower
/// hemisphere's `x = 0` meridian runs), which is what lets [`equal_area_inverse`] return the
/// right side. See the module docs of
/// [`sphere`](super) for out-of-range input.
#[inline]
pub fn equal_area(u: [f32; 2]) -> [f32; 3] {
    equal_area_body(u)
}

/// [`equal_area`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn equal_area_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    equal_area_body(u)
}

/// [`equal_area`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn equal_area_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    equal_area_body(u)
}

/// [`equal_area`] over a batch: writes `out[i] = equal_area(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count (a length mismatch never panics; the
/// rest of the longer slice is untouched). Bit-identical to the scalar form.
#[inline]
pub fn equal_area_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, equal_area_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Inverse

#[inline(always)]
fn equal_area_inverse_body<L: Lane>(d: [L; 3]) -> [L; 2] {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let half = L::splat(0.5);
    let ([x, y, z], rho2, n) = clamped_direction(d);
    let (ax, ay, az) = (x.abs(), y.abs(), z.abs());
    // r^2 = 1 - |z| / |d| = (x^2 + y^2) / (|d| (|d| + |z|)): no cancellation at the poles and
    // no normalization needed. n = 0 only for the zero vector (or underflow): r = 0 there.
    let len = n.sqrt();
    let den = n + len * az;
    let r2 = rho2 / L::select(den.simd_eq(zero), one, den);
    let r = L::select(one.simd_lt(r2), one, r2).sqrt();
    // The azimuth in units of pi/4 within the octant, then the in-quadrant coordinates p (along
    // |x|) and q (along |y|) with p + q = r and q / r = phi / (pi/2).
    let x_major = ay.simd_le(ax);
    let w = atan_ratio_pi4(L::select(x_major, ay, ax), L::select(x_major, ax, ay));
    let minor = r * w * half;
    let major = r - minor;
    let p = L::select(x_major, major, minor);
    let q = L::select(x_major, minor, major);
    // Unfold the lower hemisphere (z < 0, and z = -0.0) into the corner triangles.
    let lower = z.sign_bit().simd_eq(L::U::splat(0x8000_0000));
    let ua = L::select(lower, one - q, p);
    let ub = L::select(lower, one - p, q);
    let a = ua.flip_sign(x.sign_bit());
    let b = ub.flip_sign(y.sign_bit());
    [
        unit_interval(a * half + half),
        unit_interval(b * half + half),
    ]
}

/// Inverse of [`equal_area`]: the point of the unit square whose image is the direction `d`.
///
/// `r = sqrt(1 - |z|)`, evaluated as `sqrt((x^2 + y^2) / (1 + |z|))` so that it keeps its
/// relative precision at the poles (the direct form turns the rounding of `z`, up to 3e-8,
/// into a relative error `3e-8 / (1 - |z|)` of `r^2`), and in fact as
/// `(x^2 + y^2) / (|d| (|d| + |z|))` so that only the direction of `d` matters (this costs
/// one square root, about 4% of the throughput). The azimuth comes from `atan(min(|x|, |y|) / max(|x|, |y|))`;
/// lower-hemisphere directions unfold into the corner triangles.
///
/// **Seams.** The sign bits of `x`, `y` and `z` pick the side: on the square's edges (where
/// the lower hemisphere's `x = 0` or `y = 0` meridians fold onto themselves) `x = -0.0` gives
/// `u0 < 1/2` and `x = +0.0` gives `u0 > 1/2`, and likewise for `y`; `z = -0.0` counts as the
/// lower hemisphere (the equator is the fold, both sides give the same point).
///
/// Round trip `|u - equal_area_inverse(equal_area(u))| <= 5e-7` for every `u` in `[0, 1)^2`
/// (measured 6.0e-8 over 2^22 random points and dense sweeps of the poles, seams and fold;
/// the textbook formulas in `f32` with `1 - |z|` measure 6.1e-5 on the same points, worst at
/// the poles); against the published inverse in `f64`, within 2e-7 (measured 7.7e-8);
/// `equal_area(equal_area_inverse(d))` is within 1e-6 rad of `d` (measured 5.5e-7). See the module docs of [`sphere`](super) for non-unit and
/// out-of-range `d`.
#[inline]
pub fn equal_area_inverse(d: [f32; 3]) -> [f32; 2] {
    equal_area_inverse_body(d)
}

/// [`equal_area_inverse`] on eight directions at once; bit-identical to eight scalar calls.
#[inline]
pub fn equal_area_inverse_x8(d: [f32x8; 3]) -> [f32x8; 2] {
    equal_area_inverse_body(d)
}

/// [`equal_area_inverse`] on sixteen directions at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn equal_area_inverse_x16(d: [f32x16; 3]) -> [f32x16; 2] {
    equal_area_inverse_body(d)
}

/// [`equal_area_inverse`] over a batch, with the length rule of [`equal_area_slice`].
#[inline]
pub fn equal_area_inverse_slice(d: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(d, out, equal_area_inverse_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Density conversion

#[inline(always)]
fn equal_area_pdf_to_solid_angle_body<L: Lane>(pdf: L) -> L {
    finite_density(finite_density(pdf) * L::splat(super::UNIFORM_PDF))
}

/// Converts a density over the square of [`equal_area`] (e.g. from importance-sampling an
/// octahedral environment map) into a density over solid angle: `pdf / (4 pi)`, since the map
/// preserves area and the sphere has area `4 pi`.
///
/// Total: NaN, `-0.0` and negative densities give `0`, and so do `f32::MAX` and `+inf` (a
/// density `f32` cannot tell from unbounded: discard the sample); the result is always finite
/// and below `f32::MAX`.
#[inline]
pub fn equal_area_pdf_to_solid_angle(pdf: f32) -> f32 {
    equal_area_pdf_to_solid_angle_body(pdf)
}

/// [`equal_area_pdf_to_solid_angle`] on eight densities; bit-identical to eight scalar calls.
#[inline]
pub fn equal_area_pdf_to_solid_angle_x8(pdf: f32x8) -> f32x8 {
    equal_area_pdf_to_solid_angle_body(pdf)
}

/// [`equal_area_pdf_to_solid_angle`] on sixteen densities; bit-identical to sixteen scalar calls.
#[inline]
pub fn equal_area_pdf_to_solid_angle_x16(pdf: f32x16) -> f32x16 {
    equal_area_pdf_to_solid_angle_body(pdf)
}

// ---------------------------------------------------------------------------------------
// Wrapping

/// `floor(x)` for `|x| <= 2^22`, with correctly rounded adds only: adding and subtracting
/// `1.5 * 2^23` rounds `x` to the nearest integer (exactly, in this range), and one compare
/// corrects round-up to floor.
#[inline(always)]
fn floor_small<L: Lane>(x: L) -> L {
    const ROUND: f32 = 12_582_912.0; // 1.5 * 2^23
    let k = (x + L::splat(ROUND)) - L::splat(ROUND);
    L::select(x.simd_lt(k), k - L::splat(1.0), k)
}

/// `x` reduced modulo 2 into `[0, 2]` (`2` only when a tiny negative `x` rounds `x + 2` up),
/// exactly for `|x| >= 1` and `0 <= x < 2`. `|x| >= 2^23`, infinities and NaN become `0`.
#[inline(always)]
fn reduce_mod_2<L: Lane>(x: L) -> L {
    let zero = L::splat(0.0);
    let x = L::select(x.abs().simd_lt(L::splat(8_388_608.0)), x, zero);
    let k = floor_small(x * L::splat(0.5));
    let r = x - (k + k);
    // The smallest negative subnormal halves to -0.0, so `k` misses it: fold it up by hand
    // (found by the `sphere` fuzz target; -0.0 itself stays -0.0).
    L::select(r.simd_lt(zero), r + L::splat(2.0), r)
}

#[inline(always)]
fn equal_area_wrap_body<L: Lane>(u: [L; 2]) -> [L; 2] {
    let one = L::splat(1.0);
    let two = L::splat(2.0);
    // The extended map repeats under translations by (2, 0), (0, 2) and (1, 1), and is
    // symmetric under the half-turns about the edge midpoints (1, 1/2), (0, 1/2), (1/2, 1),
    // (1/2, 0): reduce both coordinates to [0, 2], then undo at most one of those.
    let f0 = reduce_mod_2(u[0]);
    let f1 = reduce_mod_2(u[1]);
    let hi0 = one.simd_lt(f0);
    let hi1 = one.simd_lt(f1);
    let both = hi0 & hi1;
    let w0 = L::select(
        both,
        f0 - one,
        L::select(hi0, two - f0, L::select(hi1, one - f0, f0)),
    );
    let w1 = L::select(
        both,
        f1 - one,
        L::select(hi1, two - f1, L::select(hi0, one - f1, f1)),
    );
    [w0, w1]
}

/// Folds a point outside the square of [`equal_area`] back onto the point that is its
/// neighbour on the sphere, for filtering an octahedral environment map across its edges.
///
/// The octahedral map continues across each edge mirrored end to end: just beyond the
/// right edge, `(1 + e, v)` lies next to `(1 - e, 1 - v)` on the sphere, and likewise
/// `(-e, v) -> (e, 1 - v)`, `(u, 1 + e) -> (1 - u, 1 - e)`, `(u, -e) -> (1 - u, e)`; beyond a
/// corner, both folds apply. Extended this way the map repeats with periods `(2, 0)`,
/// `(0, 2)` and `(1, 1)`, so any distance from the square is handled: the result is the one
/// point of `[0, 1]^2` that the extended map sends to the same direction, so
/// `equal_area(equal_area_wrap(u))` continues `equal_area` smoothly across every edge.
/// pbrt-v4 wraps octahedral images the same way (`WrapEqualAreaSquare`).
///
/// Points of `[0, 1]^2` are returned unchanged, bit for bit (`-0.0` included). Beyond it the
/// result is within 6e-8 of the exact fold for `|u| < 2^23` (exact for coordinates in
/// `[-1, 2]` that are multiples of `2^-23`, e.g. texel centres of maps up to `2^22` texels
/// wide); coordinates with `|u| >= 2^23`, infinities and NaN are treated as `0`. For integer
/// texel coordinates use [`equal_area_wrap_texel`].
#[inline]
pub fn equal_area_wrap(u: [f32; 2]) -> [f32; 2] {
    equal_area_wrap_body(u)
}

/// [`equal_area_wrap`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn equal_area_wrap_x8(u: [f32x8; 2]) -> [f32x8; 2] {
    equal_area_wrap_body(u)
}

/// [`equal_area_wrap`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn equal_area_wrap_x16(u: [f32x16; 2]) -> [f32x16; 2] {
    equal_area_wrap_body(u)
}

/// [`equal_area_wrap`] over a batch, with the length rule of [`equal_area_slice`].
#[inline]
pub fn equal_area_wrap_slice(u: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(u, out, equal_area_wrap_body::<slices::Widest>)
}

/// [`equal_area_wrap`] for the texels of a `size x size` octahedral image: texel `[i, j]`
/// (column, row; any `i32`, e.g. `-1` or `size` for a bilinear footprint that crosses an
/// edge) maps to the texel in `0..size` that covers the same part of the sphere.
///
/// Texel `i` covers `[i / size, (i + 1) / size)`, so the continuous folds become
/// `i -> 2 size - 1 - i` beyond the right edge, `i -> -1 - i` beyond the left one, each
/// mirroring the other coordinate `j -> size - 1 - j`, with periods `2 size` and
/// `(size, size)`. Exact integer arithmetic; `size = 0` returns `[0, 0]`.
#[inline]
pub fn equal_area_wrap_texel(texel: [i32; 2], size: u32) -> [u32; 2] {
    if size == 0 {
        return [0, 0];
    }
    // i64 holds every intermediate: |texel| < 2^31, 2 size < 2^33.
    let n = i64::from(size);
    let reduce = |i: i32| i64::from(i).rem_euclid(2 * n);
    let (i, j) = (reduce(texel[0]), reduce(texel[1]));
    let (i, j) = match (i >= n, j >= n) {
        (true, true) => (i - n, j - n),
        (true, false) => (2 * n - 1 - i, n - 1 - j),
        (false, true) => (n - 1 - i, 2 * n - 1 - j),
        (false, false) => (i, j),
    };
    // Both are in 0..size now.
    [u32::try_from(i).unwrap_or(0), u32::try_from(j).unwrap_or(0)]
}
