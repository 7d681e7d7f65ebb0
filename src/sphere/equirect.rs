//! The lat-long (equirectangular) layout: `phi = 2 pi u0`, `theta = pi u1`, so row `v = 0` is
//! `+z` and `v -> 1` is `-z`.
//!
//! Not area-preserving: a texel's solid angle shrinks with `sin theta` towards the poles, which
//! is why [`equirect_pdf_to_solid_angle`] divides by `2 pi^2 sin theta` and why the octahedral
//! [`equal_area`](super::equal_area) layout is the better one for importance sampling. Both
//! angles go through the exact quarter-turn reduction of the sin/cos kernel, and the inverse
//! takes `theta` from `atan2(sqrt(x^2 + y^2), z)` rather than `acos(z)`, which loses its
//! precision at the poles.

use crate::lanes::{Lane, unit_interval};
use crate::slices;
use crate::trig::{atan2_turns, sin_cos_turns};
use wide::{f32x8, f32x16};

use super::{clamped_direction, finite_density};

/// `2 pi^2`, the area of the `(phi, theta)` rectangle `[0, 2 pi] x [0, pi]`, rounded once.
const TWO_PI_SQUARED: f32 = (2.0 * core::f64::consts::PI * core::f64::consts::PI) as f32;

#[inline(always)]
fn equirect_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let (sin_phi, cos_phi) = sin_cos_turns(unit_interval(u[0]));
    // theta = pi u1 is half a turn times u1; sin theta >= 0 on [0, pi].
    let (sin_theta, cos_theta) = sin_cos_turns(unit_interval(u[1]) * L::splat(0.5));
    [sin_theta * cos_phi, sin_theta * sin_phi, cos_theta]
}

#[inline(always)]
fn equirect_inverse_body<L: Lane>(d: [L; 3]) -> [L; 2] {
    let ([x, y, z], rho2, _) = clamped_direction(d);
    let phi = atan2_turns(y, x);
    // sin theta >= 0, so the angle is in [0, 1/2] turn: theta / pi = 2 * turns.
    let theta = atan2_turns(rho2.sqrt(), z);
    [phi, unit_interval(theta + theta)]
}

/// Lat-long map: `phi = 2 pi u0`, `theta = pi u1`,
/// `d = (sin theta cos phi, sin theta sin phi, cos theta)`; `u1 = 0` is `+z`.
///
/// Both angles are reduced exactly (quarter turns split off in the input's units, never a
/// rounded multiple of `pi`). Not area-preserving: uniform `u` gives directions of density
/// `1 / (2 pi^2 sin theta)`; see [`equirect_pdf_to_solid_angle`].
///
/// Precision against `f64`: `| |d| - 1 | <= 2e-7` (measured 1.8e-7), each coordinate within
/// 2e-7 of the `f64` map (measured 1.4e-7). See the module docs of [`sphere`](super) for
/// out-of-range input.
#[inline]
pub fn equirect(u: [f32; 2]) -> [f32; 3] {
    equirect_body(u)
}

/// [`equirect`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn equirect_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    equirect_body(u)
}

/// [`equirect`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn equirect_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    equirect_body(u)
}

/// [`equirect`] over a batch: writes `out[i] = equirect(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count. Bit-identical to the scalar form.
#[inline]
pub fn equirect_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, equirect_body::<slices::Widest>)
}

/// Inverse of [`equirect`]: `u0 = atan2(y, x) / (2 pi)` in `[0, 1)`,
/// `u1 = atan2(sqrt(x^2 + y^2), z) / pi` in `[0, 1)`.
///
/// `y = -0.0` counts as the `u0 = 0` side of the seam (a tiny negative `y` gives a value just
/// below 1); on the axis (`x = y = 0`, the poles) `u0 = 0`; `-z` gives `u1 = 1 - 2^-24`.
/// Round trip `|u - equirect_inverse(equirect(u))| <= 5e-7` for `u` in `[0, 1)^2` (measured
/// 6.0e-8), except for `u0` at the pole `u1 = 0` (the azimuth is lost; also for `u1 < 1e-30`,
/// where `sin theta` underflows), and across the `u0` seam (compare modulo 1).
/// `equirect(equirect_inverse(d))` is within 1e-6 rad of `d` (measured 2.4e-7). Only the direction of `d` matters; see the module docs of
/// [`sphere`](super) for out-of-range input.
#[inline]
pub fn equirect_inverse(d: [f32; 3]) -> [f32; 2] {
    equirect_inverse_body(d)
}

/// [`equirect_inverse`] on eight directions at once; bit-identical to eight scalar calls.
#[inline]
pub fn equirect_inverse_x8(d: [f32x8; 3]) -> [f32x8; 2] {
    equirect_inverse_body(d)
}

/// [`equirect_inverse`] on sixteen directions at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn equirect_inverse_x16(d: [f32x16; 3]) -> [f32x16; 2] {
    equirect_inverse_body(d)
}

/// [`equirect_inverse`] over a batch, with the length rule of [`equirect_slice`].
#[inline]
pub fn equirect_inverse_slice(d: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(d, out, equirect_inverse_body::<slices::Widest>)
}

#[inline(always)]
fn equirect_pdf_to_solid_angle_body<L: Lane>(pdf: L, d: [L; 3]) -> L {
    let zero = L::splat(0.0);
    let (_, rho2, n) = clamped_direction(d);
    // pdf / (2 pi^2 sin theta) with sin theta = |(x, y)| / |d|; the axis (sin theta = 0) gets 0.
    let rho = rho2.sqrt();
    let on_axis = rho.simd_eq(zero);
    let den = L::select(on_axis, L::splat(1.0), rho * L::splat(TWO_PI_SQUARED));
    let q = (finite_density(pdf) * n.sqrt()) / den;
    finite_density(L::select(on_axis, zero, q))
}

/// Converts a density over the square of [`equirect`] (e.g. from importance-sampling a
/// lat-long environment map) into a density over solid angle at the direction `d`:
/// `pdf / (2 pi^2 sin theta)` — the map stretches `[0, 1]^2` (area 1) over `2 pi` of azimuth
/// and `pi` of polar angle, and a patch at polar angle `theta` covers `sin theta` times its
/// `(phi, theta)` area.
///
/// `sin theta` is taken from `d` as `sqrt(x^2 + y^2) / |d|` (any length works; coordinates are
/// clamped like the inverse's). On the axis itself (`x = y = 0`, a set of measure zero where
/// the density is unbounded; also within about `1e-19` of it, where `x^2 + y^2` underflows)
/// the result is `0`, as in pbrt and Mitsuba. NaN, `-0.0` and
/// negative densities give `0`, and so do the unbounded ones: an input of `f32::MAX` or `+inf`,
/// and a result that would reach `f32::MAX` (a huge density near the axis) — the axis's rule,
/// never a saturated value. Error: a few ulp (roundings in `sin theta`, the product and the
/// quotient).
#[inline]
pub fn equirect_pdf_to_solid_angle(pdf: f32, d: [f32; 3]) -> f32 {
    equirect_pdf_to_solid_angle_body(pdf, d)
}

/// [`equirect_pdf_to_solid_angle`] on eight densities and directions; bit-identical to eight
/// scalar calls.
#[inline]
pub fn equirect_pdf_to_solid_angle_x8(pdf: f32x8, d: [f32x8; 3]) -> f32x8 {
    equirect_pdf_to_solid_angle_body(pdf, d)
}

/// [`equirect_pdf_to_solid_angle`] on sixteen densities and directions; bit-identical to sixteen
/// scalar calls.
#[inline]
pub fn equirect_pdf_to_solid_angle_x16(pdf: f32x16, d: [f32x16; 3]) -> f32x16 {
    equirect_pdf_to_solid_angle_body(pdf, d)
}
