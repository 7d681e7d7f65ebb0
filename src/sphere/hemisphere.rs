//! Hemisphere warps on the concentric disk: a uniform (equal-area) lift and a cosine-weighted
//! one, both starting from the disk crate's Shirley-Chiu map so that compact strata of the
//! square stay compact on the hemisphere.
//!
//! The disk point comes in polar form, signed radius `r` and unit direction, so the lifts can
//! use `1 - r^2 = (1 - |r|)(1 + |r|)`, where `1 - |r|` is exact for `|r| >= 1/2`: the height
//! keeps its relative precision at the horizon, which matters most for the cosine lift
//! (`z = sqrt(1 - r^2)` would turn an absolute error of 1e-7 in `r^2` into a visible error in
//! `z` there).

use crate::disk::{concentric_inverse_body, concentric_parts};
use crate::lanes::Lane;
use crate::slices;
use wide::{f32x8, f32x16};

use super::{clamped_direction, finite_density};

/// Density of uniformly distributed directions on the hemisphere (and of
/// [`uniform_hemisphere`]) with respect to solid angle: `1 / (2 pi)`.
pub const HEMISPHERE_PDF: f32 = (0.5 * core::f64::consts::FRAC_1_PI) as f32;

#[inline(always)]
fn uniform_hemisphere_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let one = L::splat(1.0);
    let (r, c, s) = concentric_parts(u);
    // Lambert's azimuthal projection: z = 1 - r^2, |(x, y)| = r sqrt(2 - r^2), both from the
    // same rounded r^2 (as in the equal-area map) so that z^2 + rho^2 = 1 up to the last
    // roundings; the sign of the concentric radius goes along. z is linear in r^2, so its
    // absolute error stays at the rounding of 1 - r^2 even at the horizon.
    let r2 = r * r;
    let z = one - r2;
    let rho = (r2 * (one + z)).sqrt().flip_sign(r.sign_bit());
    [rho * c, rho * s, z]
}

#[inline(always)]
fn cosine_hemisphere_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let one = L::splat(1.0);
    let (r, c, s) = concentric_parts(u);
    // Malley: project the disk point up; (x, y) is exactly `disk::concentric(u)`, and
    // 1 - r^2 = (1 - |r|)(1 + |r|) keeps its relative precision at the horizon, where the
    // square root would magnify an absolute error.
    let ar = r.abs();
    [r * c, r * s, ((one - ar) * (one + ar)).sqrt()]
}

/// The disk point `(x, y) * scale`, or the disk centre where `den` is 0 (the zero vector).
#[inline(always)]
fn to_disk<L: Lane>(x: L, y: L, den: L) -> [L; 2] {
    let zero = L::splat(0.0);
    let degenerate = den.simd_eq(zero);
    let scale = L::splat(1.0) / L::select(degenerate, L::splat(1.0), den.sqrt());
    let scale = L::select(degenerate, zero, scale);
    concentric_inverse_body([x * scale, y * scale])
}

#[inline(always)]
fn uniform_hemisphere_inverse_body<L: Lane>(d: [L; 3]) -> [L; 2] {
    let ([x, y, z], _, n) = clamped_direction(d);
    // Disk point (x, y) / sqrt(1 + z) for a unit d; for any length, (x, y) / sqrt(|d| (|d| + z)).
    // Below the horizon: the mirror image, |z|.
    let den = n + n.sqrt() * z.abs();
    to_disk(x, y, den)
}

#[inline(always)]
fn cosine_hemisphere_inverse_body<L: Lane>(d: [L; 3]) -> [L; 2] {
    let ([x, y, _], _, n) = clamped_direction(d);
    // Disk point (x, y) / |d|.
    to_disk(x, y, n)
}

#[inline(always)]
fn cosine_hemisphere_pdf_body<L: Lane>(cos_theta: L) -> L {
    // A cosine above 1 (`+inf` included) is 1; NaN stays NaN and gives 0.
    let one = L::splat(1.0);
    let c = L::select(one.simd_lt(cos_theta), one, cos_theta);
    finite_density(c * L::splat(core::f32::consts::FRAC_1_PI))
}

/// Uniform hemisphere (`z >= 0`) through the concentric disk: the disk point `p` of
/// [`disk::concentric`](crate::disk::concentric) with `r = |p|` is lifted by Lambert's
/// azimuthal equal-area projection, `z = 1 - r^2`, `(x, y) = p sqrt(2 - r^2)`.
///
/// Both steps preserve area, so the result is uniform: density [`HEMISPHERE_PDF`]
/// `= 1 / (2 pi)`. The square's centre is `+z`, its boundary the horizon, and compact strata
/// stay compact (unlike `z = u0`, which makes thin rings). Mitsuba 3's
/// `square_to_uniform_hemisphere` uses the same construction.
///
/// Precision against `f64`: `| |d| - 1 | <= 2e-7` (measured 1.95e-7), each coordinate within
/// 2e-7 of the `f64` map (measured 1.6e-7). `z > 0` always: the disk radius is clamped like
/// the disk warps' (`1 - 2^-23`), so `z >= 2.4e-7`. See the module docs of
/// [`sphere`](super) for out-of-range input.
#[inline]
pub fn uniform_hemisphere(u: [f32; 2]) -> [f32; 3] {
    uniform_hemisphere_body(u)
}

/// [`uniform_hemisphere`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_hemisphere_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    uniform_hemisphere_body(u)
}

/// [`uniform_hemisphere`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_hemisphere_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    uniform_hemisphere_body(u)
}

/// [`uniform_hemisphere`] over a batch: writes `out[i] = uniform_hemisphere(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count. Bit-identical to the scalar form.
#[inline]
pub fn uniform_hemisphere_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, uniform_hemisphere_body::<slices::Widest>)
}

/// Inverse of [`uniform_hemisphere`]: the disk point `(x, y) / sqrt(1 + z)` (scale-free:
/// `(x, y) / sqrt(|d| (|d| + z))`), then
/// [`disk::concentric_inverse`](crate::disk::concentric_inverse).
///
/// A direction below the horizon maps like its mirror image `(x, y, -z)`. Round trip
/// `|u - uniform_hemisphere_inverse(uniform_hemisphere(u))| <= 5e-7` on `[0, 1)^2`
/// (measured 1.5e-7; the centre `u = (1/2, 1/2)` is `+z` and comes back exactly);
/// `uniform_hemisphere(uniform_hemisphere_inverse(d))` is within 1e-6 rad of `d` (measured
/// 4.8e-7).
#[inline]
pub fn uniform_hemisphere_inverse(d: [f32; 3]) -> [f32; 2] {
    uniform_hemisphere_inverse_body(d)
}

/// [`uniform_hemisphere_inverse`] on eight directions; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_hemisphere_inverse_x8(d: [f32x8; 3]) -> [f32x8; 2] {
    uniform_hemisphere_inverse_body(d)
}

/// [`uniform_hemisphere_inverse`] on sixteen directions; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_hemisphere_inverse_x16(d: [f32x16; 3]) -> [f32x16; 2] {
    uniform_hemisphere_inverse_body(d)
}

/// [`uniform_hemisphere_inverse`] over a batch, with the length rule of
/// [`uniform_hemisphere_slice`].
#[inline]
pub fn uniform_hemisphere_inverse_slice(d: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(d, out, uniform_hemisphere_inverse_body::<slices::Widest>)
}

/// Cosine-weighted hemisphere (Malley's method): the concentric disk point `p`
/// ([`disk::concentric`](crate::disk::concentric), bit for bit) projected up,
/// `d = (p, sqrt(1 - |p|^2))`.
///
/// A uniform disk point projects to a density proportional to `cos theta`:
/// [`cosine_hemisphere_pdf`] `= z / pi`. `1 - |p|^2` is evaluated as `(1 - r)(1 + r)` from the
/// disk radius, so `z` is accurate to a few ulp even at the horizon.
///
/// Precision against `f64`: `| |d| - 1 | <= 2e-7` (measured 1.5e-7), each coordinate within
/// 2e-7 (measured 1.3e-7). `z >= 4.8e-4`: the top disk radius, `1 - 2^-23` (the disk clamp,
/// and also `|2 u - 1|` for the top input `u = 1 - 2^-24`), is that high; the input step there
/// covers the band `0 <= z < 4.8e-4`. See the module docs of [`sphere`](super) for
/// out-of-range input.
#[inline]
pub fn cosine_hemisphere(u: [f32; 2]) -> [f32; 3] {
    cosine_hemisphere_body(u)
}

/// [`cosine_hemisphere`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn cosine_hemisphere_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    cosine_hemisphere_body(u)
}

/// [`cosine_hemisphere`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn cosine_hemisphere_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    cosine_hemisphere_body(u)
}

/// [`cosine_hemisphere`] over a batch: writes `out[i] = cosine_hemisphere(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count. Bit-identical to the scalar form.
#[inline]
pub fn cosine_hemisphere_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, cosine_hemisphere_body::<slices::Widest>)
}

/// Inverse of [`cosine_hemisphere`]: the disk point `(x, y) / |d|`, then
/// [`disk::concentric_inverse`](crate::disk::concentric_inverse).
///
/// A direction below the horizon maps like its mirror image `(x, y, -z)`. Round trip
/// `|u - cosine_hemisphere_inverse(cosine_hemisphere(u))| <= 5e-7` on `[0, 1)^2` (measured
/// 1.2e-7). `cosine_hemisphere(cosine_hemisphere_inverse(d))` is within 1e-6 rad of `d` away
/// from the horizon; near it the map's conditioning (`d theta / d r = 1 / z`) magnifies the
/// rounding of the disk radius (steps of `2^-23` there), and the bound is
/// `1e-6 + 3 * 2^-23 / z` rad (measured 1e-6 + 2.07 steps at most).
#[inline]
pub fn cosine_hemisphere_inverse(d: [f32; 3]) -> [f32; 2] {
    cosine_hemisphere_inverse_body(d)
}

/// [`cosine_hemisphere_inverse`] on eight directions; bit-identical to eight scalar calls.
#[inline]
pub fn cosine_hemisphere_inverse_x8(d: [f32x8; 3]) -> [f32x8; 2] {
    cosine_hemisphere_inverse_body(d)
}

/// [`cosine_hemisphere_inverse`] on sixteen directions; bit-identical to sixteen scalar calls.
#[inline]
pub fn cosine_hemisphere_inverse_x16(d: [f32x16; 3]) -> [f32x16; 2] {
    cosine_hemisphere_inverse_body(d)
}

/// [`cosine_hemisphere_inverse`] over a batch, with the length rule of
/// [`cosine_hemisphere_slice`].
#[inline]
pub fn cosine_hemisphere_inverse_slice(d: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(d, out, cosine_hemisphere_inverse_body::<slices::Widest>)
}

/// Density of [`cosine_hemisphere`] with respect to solid angle: `cos theta / pi` (pass the
/// direction's `z` for a unit direction).
///
/// Below the horizon (`cos_theta <= 0`) and for NaN the density is `0`; a `cos_theta` above 1
/// (`+inf` included) counts as 1 (density `1 / pi`).
#[inline]
pub fn cosine_hemisphere_pdf(cos_theta: f32) -> f32 {
    cosine_hemisphere_pdf_body(cos_theta)
}

/// [`cosine_hemisphere_pdf`] on eight values; bit-identical to eight scalar calls.
#[inline]
pub fn cosine_hemisphere_pdf_x8(cos_theta: f32x8) -> f32x8 {
    cosine_hemisphere_pdf_body(cos_theta)
}

/// [`cosine_hemisphere_pdf`] on sixteen values; bit-identical to sixteen scalar calls.
#[inline]
pub fn cosine_hemisphere_pdf_x16(cos_theta: f32x16) -> f32x16 {
    cosine_hemisphere_pdf_body(cos_theta)
}
