//! Helpers around the distributions: weights from an RGB image, the solid-angle factor of an
//! equirect (lat-long) map, the conversions of an area pdf on `[0, 1]^2` to a pdf over directions, and
//! the resampling of a lat-long image into an equal-area (octahedral) square image.
//!
//! Conventions (as [`sphere::equirect`]): an **equirect** (equirectangular, lat-long) map puts
//! `phi = 2 pi u`, `theta = pi v`, direction `(sin theta cos phi, sin theta sin phi, cos theta)`,
//! so row 0 is around `+z` (the top of the image: a PFM file, which stores its rows bottom to
//! top, must be flipped on loading); its Jacobian is `d(omega) = 2 pi^2 sin(theta) du dv`. An
//! **equal-area** map
//! (Clarberg's octahedral square, `sphere::equal_area`) has the constant Jacobian
//! `d(omega) = 4 pi du dv`.
//!
//! Recipes:
//!
//! * **equirect**: [`luminance_slice`] -> [`equirect_solid_angle_weights`] ->
//!   [`Hierarchical::new`](super::Hierarchical::new) -> `sample` -> direction
//!   [`sphere::equirect`]`(uv)` -> density [`equirect_pdf_to_solid_angle`]`(pdf, uv[1])` (or
//!   both at once: `sample_direction(Layout::Equirect, u)`);
//! * **equal-area** (the better parameterization: no pole distortion, every texel the same
//!   solid angle, so no row factor): [`equirect_to_equal_area`] (once, from your lat-long
//!   image) -> [`luminance_slice`] -> `Hierarchical::new` -> `sample` -> direction
//!   [`sphere::equal_area`]`(uv)` -> density [`equal_area_pdf_to_solid_angle`]`(pdf)` (or both
//!   at once: `sample_direction(Layout::EqualArea, u)`).

use super::{Error, MAX_SIDE, check_len};
use crate::lanes::{Lane, unit_interval};
use crate::sphere::{self, finite_density};
use crate::trig::sin_cos_turns;
use core::f64::consts::PI;
use wide::f32x8;

pub use crate::sphere::{equal_area_pdf_to_solid_angle, equal_area_pdf_to_solid_angle_x8};

/// Rec. 709 / sRGB luminance coefficients of linear `[R, G, B]`.
pub const LUMINANCE: [f32; 3] = [0.2126, 0.7152, 0.0722];

/// `1 / (2 pi^2)`, rounded once from `f64`.
const INV_2_PI_SQ: f32 = (1.0 / (2.0 * PI * PI)) as f32;

#[inline(always)]
fn luminance_body<L: Lane>(rgb: [L; 3]) -> [L; 1] {
    let l = L::splat(LUMINANCE[0]) * rgb[0]
        + L::splat(LUMINANCE[1]) * rgb[1]
        + L::splat(LUMINANCE[2]) * rgb[2];
    // The weight rule, by compare + select: NaN (a NaN channel, or `inf - inf`), `-0.0` and
    // negatives become `+0.0`; `+inf` stays.
    let zero = L::splat(0.0);
    [L::select(zero.simd_lt(l), l, zero)]
}

/// Luminance of a linear RGB texel as a weight: `0.2126 R + 0.7152 G + 0.0722 B` (evaluated
/// in that order, without FMA) where that is positive, `+0.0` otherwise — NaN (a NaN channel,
/// or infinite channels of opposite signs), `-0.0`, negative values and `-inf` give `+0.0`,
/// the weight the distributions give them anyway. `+inf` stays `+inf`, so a build reports
/// [`Error::InfiniteWeight`] with the texel's index rather than dropping it. Never NaN, never
/// negative: the result's bits are the same on every target and in every form (a NaN's bits
/// would not be).
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
    crate::slices::map(rgb, out, luminance_body)
}

/// `sin(pi v)` for `v` in `[0, 1]`, from the crate's polynomial kernels: `pi v` is the half
/// turn `v / 2` (exact scaling), and near both poles the reduced argument is exact, so small
/// values keep their relative precision (error at most 2.1 ulp).
#[inline(always)]
fn sin_pi<L: Lane>(v: L) -> L {
    sin_cos_turns(v * L::splat(0.5)).0.abs()
}

/// `sin(pi v)`, the row factor of [`equirect_solid_angle_weights`] (for MIS compensation).
pub(super) fn row_sine(v: f32) -> f32 {
    sin_pi(v)
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
pub fn equirect_solid_angle_weights(
    weights: &mut [f32],
    width: usize,
    height: usize,
) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::ZeroSize);
    }
    check_len(weights.len(), width, height)?;
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
fn equirect_body<L: Lane>(pdf: L, v: L) -> L {
    let zero = L::splat(0.0);
    let p = finite_density(pdf);
    let s = sin_pi(unit_interval(v));
    let pole = s.simd_eq(zero);
    let r = p * L::splat(INV_2_PI_SQ) / L::select(pole, L::splat(1.0), s);
    // At the pole itself (sin theta = 0, only v = 0 can give it) the density is unbounded:
    // 0, the pbrt / Mitsuba convention that `sphere::equirect_pdf_to_solid_angle` follows.
    finite_density(L::select(pole, zero, r))
}

/// Converts an area pdf on a lat-long map's `[0, 1]^2` to a pdf with respect to solid angle
/// at the sampled point: `pdf / (2 pi^2 sin(pi v))` — what
/// [`sphere::equirect_pdf_to_solid_angle`] computes from the direction, here from the
/// sample's `v = uv[1]` (no direction needed, and `sin` keeps full relative precision near
/// both poles).
///
/// **The `sin(theta)` is the point's, not the texel row's.** The distributions sample `uv`
/// uniformly inside the chosen texel, so the density over directions varies across the
/// texel as `1 / sin(theta)`: the point's sine gives the true density of the returned
/// direction, which is what MIS weights and `f / pdf` need. The row centre's sine would be
/// the density of a different sampler (uniform in solid angle inside the texel): in the
/// polar rows it is off by up to a factor of 2 at the row's far edge, and without bound
/// towards the pole. (The weights do use the row centre, see
/// [`equirect_solid_angle_weights`]: there it is the texel's exact solid angle.)
///
/// Total: `v` is clamped by the forward rule; a NaN or negative `pdf` gives 0; at the pole
/// itself (`v = 0`) the result is 0 (the sample should be discarded, as in pbrt and
/// Mitsuba), and so is every other unbounded case: a `pdf` of `f32::MAX` or `+inf`, and a
/// result that would reach `f32::MAX` (never a saturated density). Error: within
/// 3 ulp of the `f64` formula (the sine's 2 ulp plus two roundings).
#[inline]
pub fn equirect_pdf_to_solid_angle(pdf: f32, v: f32) -> f32 {
    equirect_body(pdf, v)
}

/// [`equirect_pdf_to_solid_angle`] on eight lanes; bit-identical to eight scalar calls.
#[inline]
pub fn equirect_pdf_to_solid_angle_x8(pdf: f32x8, v: f32x8) -> f32x8 {
    equirect_body(pdf, v)
}

/// Largest supersampling factor [`equirect_to_equal_area`] accepts (per axis).
pub const MAX_SUPERSAMPLE: usize = 64;

/// Resamples a lat-long (equirectangular) image into an equal-area octahedral square image
/// of `size x size` texels, for importance sampling in the better parameterization.
///
/// Each output texel `(column, row)` covers `[column/size, (column+1)/size) x [row/size,
/// (row+1)/size)` of the square of [`sphere::equal_area`]. It is the average of
/// `supersample^2` stratified point samples (cell centres of a `supersample x supersample`
/// grid over the texel), each mapped to a direction with [`sphere::equal_area`], looked up
/// with [`sphere::equirect_inverse`] and read from the source texel holding that point (a
/// box filter over the output texel, nearest-texel reads of the source). Every output texel
/// covers `4 pi / size^2` of solid angle, so the averages are directly the weights of an
/// equal-area distribution (no row factor), and `4 pi / size^2 * sum(dst)` estimates the
/// source's integral over the sphere.
///
/// Choose `size` so that `size^2` is about the source's texel count or more, and
/// `supersample >= 2`: a source texel smaller than an output texel's samples can be missed.
/// **When the result feeds [`Hierarchical`](super::Hierarchical), prefer a power-of-two
/// `size`** (256, 512, 1024): the pyramid then has no padding and splits the square at its own
/// halves (the octahedral seams). Other sizes are centred in the next power of two (storage
/// format version 2), which measured as well as a power of two in the report's scenes and
/// better than the old corner placement (`docs/envmaps.md` has the measurements); they cost
/// up to about 4x the storage of the map's own texels.
/// `src` is row-major, row 0 around `+z` (`v` in `[0, 1/src_height)`). Values are taken as
/// they are, except that NaN and negative channels count as 0 (the weight rule, so a bad
/// source texel cannot spoil its neighbours' averages); `+inf` stays infinite.
///
/// Errors, checked in this order before anything is written: [`Error::ZeroSize`] (a zero
/// side, `size` or `supersample`), [`Error::TooLarge`] (a side or `size` above [`MAX_SIDE`],
/// or `supersample` above [`MAX_SUPERSAMPLE`]), [`Error::LengthMismatch`]
/// (`src.len() != src_width * src_height`, then `dst.len() != size * size`; `expected`
/// saturates at `usize::MAX` where the product overflows `usize`, as it can on 32-bit
/// targets). On error `dst` is unchanged.
pub fn equirect_to_equal_area<const C: usize>(
    src: &[[f32; C]],
    src_width: usize,
    src_height: usize,
    dst: &mut [[f32; C]],
    size: usize,
    supersample: usize,
) -> Result<(), Error> {
    if src_width == 0 || src_height == 0 || size == 0 || supersample == 0 {
        return Err(Error::ZeroSize);
    }
    if src_width > MAX_SIDE
        || src_height > MAX_SIDE
        || size > MAX_SIDE
        || supersample > MAX_SUPERSAMPLE
    {
        return Err(Error::TooLarge);
    }
    // Checked: on 32-bit targets (wasm32) two sides of at most `MAX_SIDE` can overflow
    // `usize`, and no slice can then have the length (`check_len` saturates).
    check_len(src.len(), src_width, src_height)?;
    check_len(dst.len(), size, size)?;
    // Sample positions are computed in `f64` (integers below 2^31: exact, so the same bits
    // as integer arithmetic) and the source index with checked arithmetic.
    let (sw, sh) = (src_width as f64, src_height as f64);
    let (n, ss) = (size as f64, supersample as f64);
    let inv = 1.0 / (n * ss);
    let norm = 1.0 / (ss * ss);
    let clean = |x: f32| if x > 0.0 { f64::from(x) } else { 0.0 };
    for (row, out_row) in dst.chunks_exact_mut(size.max(1)).enumerate() {
        for (column, out) in out_row.iter_mut().enumerate() {
            let mut acc = [0.0f64; C];
            for b in 0..supersample {
                let v = (row as f64 * ss + b as f64 + 0.5) * inv;
                for a in 0..supersample {
                    let u = (column as f64 * ss + a as f64 + 0.5) * inv;
                    let d = sphere::equal_area([u as f32, v as f32]);
                    let [su, sv] = sphere::equirect_inverse(d);
                    // `su, sv` are in [0, 1): the products floor into range.
                    let x = ((f64::from(su) * sw) as usize).min(src_width - 1);
                    let y = ((f64::from(sv) * sh) as usize).min(src_height - 1);
                    let at = y.checked_mul(src_width).and_then(|i| i.checked_add(x));
                    if let Some(texel) = at.and_then(|i| src.get(i)) {
                        for (s, &t) in acc.iter_mut().zip(texel) {
                            *s += clean(t);
                        }
                    }
                }
            }
            for (o, s) in out.iter_mut().zip(acc) {
                *o = (s * norm) as f32;
            }
        }
    }
    Ok(())
}
