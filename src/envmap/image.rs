//! Helpers around the distributions: weights from an RGB image, the solid-angle factor of a
//! lat-long map, and the conversions of an area pdf on `[0, 1]^2` to a pdf over directions.
//!
//! Conventions (DESIGN section 3): a **lat-long** (equirectangular) map puts `phi = 2 pi u`,
//! `theta = pi v`, direction `(sin theta cos phi, sin theta sin phi, cos theta)`, so row 0 is
//! around `+z`; its Jacobian is `d(omega) = 2 pi^2 sin(theta) du dv`. An **equal-area** map
//! (Clarberg's octahedral square, `sphere::equal_area`) has the constant Jacobian
//! `d(omega) = 4 pi du dv`.
//!
//! Recipe for a lat-long map: `luminance_slice` -> `latlong_solid_angle_weights` ->
//! `Hierarchical::new` -> `sample` -> direction from `uv` -> `latlong_pdf_to_solid_angle(pdf,
//! uv[1])`. For an equal-area map no row factor is needed (every texel covers the same solid
//! angle) and the pdf converts with `equal_area_pdf_to_solid_angle`.

use super::Error;
use crate::kernels::sin_cos_turns;
use crate::lanes::{Lane, unit_interval};
use core::f64::consts::PI;
use wide::f32x8;

/// Rec. 709 / sRGB luminance coefficients of linear `[R, G, B]`.
pub const LUMINANCE: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// `1 / (2 pi^2)`, rounded once from `f64`.
const INV_2_PI_SQ: f32 = (1.0 / (2.0 * PI * PI)) as f32;
/// `1 / (4 pi)`, rounded once from `f64`.
const INV_4_PI: f32 = (1.0 / (4.0 * PI)) as f32;

#[inline(always)]
fn luminance_body<L: Lane>(rgb: [L; 3]) -> [L; 1] {
    [L::splat(LUMINANCE[0]) * rgb[0]
        + L::splat(LUMINANCE[1]) * rgb[1]
        + L::splat(LUMINANCE[2]) * rgb[2]]
}

/// Luminance of a linear RGB texel, `0.2126 R + 0.7152 G + 0.0722 B` (evaluated in that
/// order, without FMA). Bad values propagate (a NaN channel gives NaN, which a distribution
/// then weighs 0; an infinite one gives an infinite weight, which it rejects).
#[inline]
pub fn luminance(rgb: [f32; 3]) -> f32 {
    luminance_body(rgb)[0]
}

/// [`luminance`] over an image: `out[i] = luminance(rgb[i])` for
/// `i < min(rgb.len(), out.len())`; returns that count. Bit-identical to the scalar form.
/// (An interleaved `&[f32]` image is `rgb.as_chunks::<3>().0`.)
#[inline]
pub fn luminance_slice(rgb: &[[f32; 3]], out: &mut [f32]) -> usize {
    let (out, _) = out.as_chunks_mut::<1>();
    crate::batch::map(rgb, out, luminance_body)
}

/// `sin(pi v)` for `v` in `[0, 1]`, from the crate's polynomial kernels: `pi v` is the half
/// turn `v / 2` (exact scaling), and near both poles the reduced argument is exact, so small
/// values keep their relative precision (error at most 2.1 ulp).
#[inline(always)]
fn sin_pi<L: Lane>(v: L) -> L {
    sin_cos_turns(v * L::splat(0.5)).0.abs()
}

/// Multiplies each row of a lat-long weight map by `sin(theta)` at the row's centre,
/// `theta = pi (row + 1/2) / height`, so that a texel's weight is proportional to radiance
/// times the solid angle it covers.
///
/// That is exact, not an approximation: the solid angle of a texel row is
/// `(2 pi / width) (cos theta0 - cos theta1) = (4 pi / width) sin(theta_centre) sin(pi / (2
/// height))`, the centre's sine times a factor common to all rows. Values are multiplied
/// as they are (bad values keep their meaning for `new`). Errors: [`Error::ZeroSize`],
/// [`Error::LengthMismatch`].
pub fn latlong_solid_angle_weights(
    weights: &mut [f32],
    width: usize,
    height: usize,
) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::ZeroSize);
    }
    let expected = width.saturating_mul(height);
    if weights.len() != expected {
        return Err(Error::LengthMismatch {
            expected,
            got: weights.len(),
        });
    }
    let h = height as f64;
    for (r, row) in weights.chunks_exact_mut(width.max(1)).enumerate() {
        let v = ((r as f64 + 0.5) / h) as f32;
        let s: f32 = sin_pi(v);
        for x in row {
            *x *= s;
        }
    }
    Ok(())
}

#[inline(always)]
fn latlong_body<L: Lane>(pdf: L, v: L) -> L {
    let zero = L::splat(0.0);
    let max = L::splat(f32::MAX);
    let p = L::select(zero.simd_lt(pdf), pdf, zero);
    let s = sin_pi(unit_interval(v));
    let r = p * L::splat(INV_2_PI_SQ) / s;
    // At the pole itself (s = 0) the density is unbounded: f32::MAX (0 for p = 0).
    let r = L::select(s.simd_eq(zero), L::select(p.simd_eq(zero), zero, max), r);
    L::select(max.simd_lt(r), max, r)
}

/// Converts an area pdf on a lat-long map's `[0, 1]^2` to a pdf with respect to solid angle
/// at the sampled point: `pdf / (2 pi^2 sin(pi v))`.
///
/// **The `sin(theta)` is the point's, not the texel row's.** The distributions sample `uv`
/// uniformly inside the chosen texel, so the density over directions varies across the
/// texel as `1 / sin(theta)`: the point's sine gives the true density of the returned
/// direction, which is what MIS weights and `f / pdf` need. The row centre's sine would be
/// the density of a different sampler (uniform in solid angle inside the texel): in the
/// polar rows it is off by up to a factor of 2 at the row's far edge, and without bound
/// towards the pole. (The weights still use the row centre, see
/// [`latlong_solid_angle_weights`]: that one is the texel's exact solid angle.)
///
/// Total: `v` is clamped by the forward rule; a NaN or negative `pdf` gives 0; at `v = 0`
/// (the pole, where the density is unbounded) and on overflow the result is `f32::MAX`
/// (0 when `pdf` is 0). Error: about 3 ulp over the polynomial sine's.
#[inline]
pub fn latlong_pdf_to_solid_angle(pdf: f32, v: f32) -> f32 {
    latlong_body(pdf, v)
}

/// [`latlong_pdf_to_solid_angle`] on eight lanes; bit-identical to eight scalar calls.
#[inline]
pub fn latlong_pdf_to_solid_angle_x8(pdf: f32x8, v: f32x8) -> f32x8 {
    latlong_body(pdf, v)
}

#[inline(always)]
fn equal_area_body<L: Lane>(pdf: L) -> L {
    let zero = L::splat(0.0);
    let max = L::splat(f32::MAX);
    let p = L::select(zero.simd_lt(pdf), pdf, zero);
    let r = p * L::splat(INV_4_PI);
    L::select(max.simd_lt(r), max, r)
}

/// Converts an area pdf on an equal-area map's `[0, 1]^2` to a pdf with respect to solid
/// angle: `pdf / (4 pi)` (the map preserves area, so this is exact everywhere). A NaN or
/// negative `pdf` gives 0, `+inf` gives `f32::MAX`.
#[inline]
pub fn equal_area_pdf_to_solid_angle(pdf: f32) -> f32 {
    equal_area_body(pdf)
}

/// [`equal_area_pdf_to_solid_angle`] on eight lanes; bit-identical to eight scalar calls.
#[inline]
pub fn equal_area_pdf_to_solid_angle_x8(pdf: f32x8) -> f32x8 {
    equal_area_body(pdf)
}
