//! The uniform sphere by Archimedes' hat-box theorem: the height `z` of a uniform direction is
//! uniform on `[-1, 1]`, and the azimuth is independent of it.

use crate::lanes::{Lane, unit_interval};
use crate::slices;
use crate::trig::{atan2_turns, sin_cos_turns};
use wide::{f32x8, f32x16};

use super::clamped_direction;

/// Density of uniformly distributed directions (and of [`uniform`] and
/// [`equal_area`](super::equal_area)) with respect to solid angle: `1 / (4 pi)`.
pub const UNIFORM_PDF: f32 = (0.25 * core::f64::consts::FRAC_1_PI) as f32;

#[inline(always)]
fn uniform_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let one = L::splat(1.0);
    let u0 = unit_interval(u[0]);
    let z = one - (u0 + u0);
    // sqrt(1 - z^2) = 2 sqrt(u0 (1 - u0)): no cancellation at either pole.
    let s = (u0 * (one - u0)).sqrt();
    let r = s + s;
    let (sin_phi, cos_phi) = sin_cos_turns(unit_interval(u[1]));
    [r * cos_phi, r * sin_phi, z]
}

#[inline(always)]
fn uniform_inverse_body<L: Lane>(d: [L; 3]) -> [L; 2] {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let ([x, y, z], rho2, n) = clamped_direction(d);
    // u0 = (1 - z / |d|) / 2 = (|d| - z) / (2 |d|); for z > 0 the numerator is
    // x^2 + y^2 / (|d| + z) instead, which keeps its precision near +z.
    let len = n.sqrt();
    let north = zero.simd_lt(z);
    let num = L::select(north, rho2, len - z);
    let den = L::select(north, len + z, one) * len;
    // The zero vector gives 0/0 = NaN, which `unit_interval` turns into 0 (+z).
    let u0 = num / (den + den);
    [unit_interval(u0), atan2_turns(y, x)]
}

/// Uniform sphere: `z = 1 - 2 u0`, `phi = 2 pi u1`, `(x, y) = sqrt(1 - z^2) (cos phi, sin phi)`.
///
/// `sqrt(1 - z^2)` is computed as `2 sqrt(u0 (1 - u0))`, precise at both poles. Density
/// [`UNIFORM_PDF`] `= 1 / (4 pi)`. Slices of constant `u0` are circles of latitude, so strata
/// become thin rings near the poles; [`equal_area`](super::equal_area) keeps them compact.
///
/// Precision against `f64`: `| |d| - 1 | <= 2e-7` (measured 1.8e-7), each coordinate within
/// 2e-7 of the `f64` map (measured 1.4e-7). Near `-z` the input grid is coarse: `z = 1 - 2 u0`
/// moves in steps of `2^-23` for `u0 >= 1/2`, and the top value `u0 = 1 - 2^-24` stands for
/// the whole cap within `2^-11` rad of `-z`. See the module docs of [`sphere`](super) for
/// out-of-range input.
#[inline]
pub fn uniform(u: [f32; 2]) -> [f32; 3] {
    uniform_body(u)
}

/// [`uniform`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    uniform_body(u)
}

/// [`uniform`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    uniform_body(u)
}

/// [`uniform`] over a batch: writes `out[i] = uniform(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count. Bit-identical to the scalar form.
#[inline]
pub fn uniform_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, uniform_body::<slices::Widest>)
}

/// Inverse of [`uniform`]: `u0 = (1 - z) / 2`, `u1 = atan2(y, x) / (2 pi)` in `[0, 1)`.
///
/// Near `+z`, `1 - z` is evaluated as `(x^2 + y^2) / (1 + z)` (scale-free, like every inverse
/// here). Round trip `|u - uniform_inverse(uniform(u))| <= 5e-7` for `u` in `[0, 1)^2`
/// (measured 8.9e-8), except for `u1` at the pole `u0 = 0` (the azimuth is lost; `0` is
/// returned) and across the `u1` seam (compare modulo 1; `y = -0.0` is the `u1 = 0` side).
/// `uniform(uniform_inverse(d))` is within 1e-6 rad of `d` (measured 2.1e-7) plus, in the
/// southern hemisphere, one step of the input grid, `2^-23 / sin theta` (see [`uniform`];
/// measured 0.80 step).
#[inline]
pub fn uniform_inverse(d: [f32; 3]) -> [f32; 2] {
    uniform_inverse_body(d)
}

/// [`uniform_inverse`] on eight directions at once; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_inverse_x8(d: [f32x8; 3]) -> [f32x8; 2] {
    uniform_inverse_body(d)
}

/// [`uniform_inverse`] on sixteen directions at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_inverse_x16(d: [f32x16; 3]) -> [f32x16; 2] {
    uniform_inverse_body(d)
}

/// [`uniform_inverse`] over a batch, with the length rule of [`uniform_slice`].
#[inline]
pub fn uniform_inverse_slice(d: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(d, out, uniform_inverse_body::<slices::Widest>)
}
