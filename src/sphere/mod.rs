//! Sphere and hemisphere warps: the unit square onto directions, and back.
//!
//! | warp | maps | density (solid angle) | source |
//! |---|---|---|---|
//! | [`equal_area`] | octahedral layout: the square's centre is `+z`, the rotated inner square the upper hemisphere, the four corner triangles the lower one | [`UNIFORM_PDF`] `= 1/(4 pi)` | Clarberg 2008, "Fast Equal-Area Mapping of the (Hemi)Sphere using SIMD" |
//! | [`equirect`] | lat-long: `phi = 2 pi u0`, `theta = pi u1` | `1 / (2 pi^2 sin theta)` ([`equirect_pdf_to_solid_angle`]) | textbook |
//! | [`uniform`] | `z = 1 - 2 u0`, `phi = 2 pi u1` (Archimedes' hat-box) | [`UNIFORM_PDF`] | textbook; pbrt-v4 `SampleUniformSphere` |
//! | [`uniform_hemisphere`] | concentric disk, then Lambert's equal-area lift | [`HEMISPHERE_PDF`] `= 1/(2 pi)` | Shirley and Chiu 1997 + Lambert azimuthal projection; Mitsuba 3 `square_to_uniform_hemisphere` |
//! | [`cosine_hemisphere`] | concentric disk, then `z = sqrt(1 - r^2)` (Malley's method) | [`cosine_hemisphere_pdf`] `= cos theta / pi` | Malley 1988; Shirley and Chiu 1997 |
//!
//! Every warp has an inverse, 8- and 16-wide `_x8` and `_x16` forms and a `_slice` form, all bit-identical to
//! the scalar form. Directions are `[x, y, z]`; `phi` is measured counter-clockwise from `+x`
//! and `theta` from `+z`, so the hemispheres are `z >= 0`. [`equal_area`] and [`equirect`]
//! are the two environment-map layouts: use [`equal_area_inverse`] / [`equirect_inverse`] to
//! look a direction up, [`equal_area_wrap`] / [`equal_area_wrap_texel`] to filter across the
//! octahedral map's edges, and the `*_pdf_to_solid_angle` conversions to turn a density over
//! the image square into one over directions.
//!
//! ```
//! use warpcore::sphere;
//!
//! // Sample a direction from an octahedral environment map's square, and look it up again.
//! let d = sphere::equal_area([0.3, 0.8]);
//! let u = sphere::equal_area_inverse(d);
//! assert!((u[0] - 0.3).abs() < 5e-7 && (u[1] - 0.8).abs() < 5e-7);
//! // A texel's density over the square, as a density over solid angle.
//! let pdf = sphere::equal_area_pdf_to_solid_angle(2.0); // 2 / (4 pi)
//! assert!((pdf - 0.5 / std::f32::consts::PI).abs() < 1e-7);
//! // Bilinear filtering across the map's left edge: texel (-1, 5) of a 64 x 64 map is (0, 58).
//! assert_eq!(sphere::equal_area_wrap_texel([-1, 5], 64), [0, 58]);
//! // Cosine-weighted directions for diffuse bounces, eight at a time or in a batch.
//! let mut dirs = [[0.0f32; 3]; 3];
//! sphere::cosine_hemisphere_slice(&[[0.1, 0.2], [0.5, 0.5], [0.9, 0.7]], &mut dirs);
//! assert_eq!(dirs[1], [0.0, 0.0, 1.0]);
//! assert!(dirs.iter().all(|d| d[2] > 0.0));
//! ```
//!
//! **Out-of-range input** (every function here is total). Forward warps first map each
//! coordinate onto `[0, 1 - 2^-24]`: NaN, `-0.0`, negatives and `-inf` become `0`, values
//! `>= 1` and `+inf` become `1 - 2^-24`. Inverses clamp each coordinate of `d` to `[-1, 1]`
//! (NaN becomes `0`, `-0.0` stays `-0.0`) and then use only the *direction* of `d`: any
//! non-zero vector inside the cube `[-1, 1]^3` maps like its normalization (exactly so down to
//! lengths of about `1e-19`, where squares become subnormal); the zero vector maps to `+z`.
//! Results lie in `[0, 1)^2` (a result that rounds to 1 returns `1 - 2^-24`). The hemisphere
//! inverses map a direction below the horizon like its mirror image `(x, y, -z)`.
//!
//! **Precision** (tests in `tests/sphere.rs`, against the same formulas in `f64`): see each
//! function and the table in `docs/precision.md`.

mod equal_area;
mod equirect;
mod hemisphere;
mod uniform;

pub use equal_area::{
    equal_area, equal_area_inverse, equal_area_inverse_slice, equal_area_inverse_x8,
    equal_area_inverse_x16, equal_area_pdf_to_solid_angle, equal_area_pdf_to_solid_angle_x8,
    equal_area_pdf_to_solid_angle_x16, equal_area_slice, equal_area_wrap, equal_area_wrap_slice,
    equal_area_wrap_texel, equal_area_wrap_x8, equal_area_wrap_x16, equal_area_x8, equal_area_x16,
};
pub use equirect::{
    equirect, equirect_inverse, equirect_inverse_slice, equirect_inverse_x8, equirect_inverse_x16,
    equirect_pdf_to_solid_angle, equirect_pdf_to_solid_angle_x8, equirect_pdf_to_solid_angle_x16,
    equirect_slice, equirect_x8, equirect_x16,
};
pub use hemisphere::{
    HEMISPHERE_PDF, cosine_hemisphere, cosine_hemisphere_inverse, cosine_hemisphere_inverse_slice,
    cosine_hemisphere_inverse_x8, cosine_hemisphere_inverse_x16, cosine_hemisphere_pdf,
    cosine_hemisphere_pdf_x8, cosine_hemisphere_pdf_x16, cosine_hemisphere_slice,
    cosine_hemisphere_x8, cosine_hemisphere_x16, uniform_hemisphere, uniform_hemisphere_inverse,
    uniform_hemisphere_inverse_slice, uniform_hemisphere_inverse_x8,
    uniform_hemisphere_inverse_x16, uniform_hemisphere_slice, uniform_hemisphere_x8,
    uniform_hemisphere_x16,
};
pub use uniform::{
    UNIFORM_PDF, uniform, uniform_inverse, uniform_inverse_slice, uniform_inverse_x8,
    uniform_inverse_x16, uniform_slice, uniform_x8, uniform_x16,
};

use crate::lanes::{Lane, signed_unit};

/// The clamped direction of an inverse's input and the sums of squares every inverse needs:
/// `([x, y, z], x^2 + y^2, x^2 + y^2 + z^2)` after [`signed_unit`] on each coordinate.
#[inline(always)]
fn clamped_direction<L: Lane>(d: [L; 3]) -> ([L; 3], L, L) {
    let [x, y, z] = d.map(signed_unit);
    let rho2 = x * x + y * y;
    (([x, y, z]), rho2, rho2 + z * z)
}

/// A density made safe to return: positive values below `f32::MAX` pass unchanged; NaN,
/// `-0.0`, negatives, `f32::MAX` and `+inf` become `+0.0`. `f32` cannot tell a density of
/// `f32::MAX` or more from an unbounded one (an overflowing product saturates there), and a
/// saturated density breaks a renderer's MIS weights (`f32::MAX^2` is `inf`, `inf / inf` is
/// NaN): it gets the rule of the conversions' other unbounded case, the lat-long axis, `0`
/// (discard the sample, as pbrt and Mitsuba do there).
#[inline(always)]
pub(crate) fn finite_density<L: Lane>(p: L) -> L {
    let zero = L::splat(0.0);
    L::select(zero.simd_lt(p) & p.simd_lt(L::splat(f32::MAX)), p, zero)
}
