//! Sphere warps: the unit square to directions `[x, y, z]` and back. Inverses accept any
//! direction (clamped to `[-1, 1]` per coordinate, then normalized); hemisphere inverses map a
//! direction below the horizon like its mirror image.

use crate::ffi::{map, map_each, zip_map};
use warpcore::sphere;

/// Equal-area octahedral map (Clarberg 2008; the square's centre is +z, its corners -z): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
/// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equal_area(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 3>(u, out, n, sphere::equal_area_slice) }
}

/// Inverse of `wc_sphere_equal_area`: `n` directions `d` (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `d == out`.
///
/// # Safety
/// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equal_area_inverse(
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 3, 2>(d, out, n, sphere::equal_area_inverse_slice) }
}

/// Lat-long map, `phi = 2 pi u0`, `theta = pi u1` (row `v = 0` is +z): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
/// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equirect(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 3>(u, out, n, sphere::equirect_slice) }
}

/// Inverse of `wc_sphere_equirect`: `n` directions `d` (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `d == out`.
///
/// # Safety
/// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equirect_inverse(
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 3, 2>(d, out, n, sphere::equirect_inverse_slice) }
}

/// Uniform sphere, `z = 1 - 2 u0`, `phi = 2 pi u1`: `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
/// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_uniform(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 3>(u, out, n, sphere::uniform_slice) }
}

/// Inverse of `wc_sphere_uniform`: `n` directions `d` (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `d == out`.
///
/// # Safety
/// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_uniform_inverse(
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 3, 2>(d, out, n, sphere::uniform_inverse_slice) }
}

/// Uniform upper hemisphere (`z >= 0`; concentric disk lifted by Lambert's map): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
/// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_uniform_hemisphere(
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 3>(u, out, n, sphere::uniform_hemisphere_slice) }
}

/// Inverse of `wc_sphere_uniform_hemisphere`: `n` directions `d` (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `d == out`.
///
/// # Safety
/// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_uniform_hemisphere_inverse(
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 3, 2>(d, out, n, sphere::uniform_hemisphere_inverse_slice) }
}

/// Cosine-weighted upper hemisphere (concentric disk lifted by Malley's method): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
/// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_cosine_hemisphere(
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 3>(u, out, n, sphere::cosine_hemisphere_slice) }
}

/// Inverse of `wc_sphere_cosine_hemisphere`: `n` directions `d` (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `d == out`.
///
/// # Safety
/// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_cosine_hemisphere_inverse(
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 3, 2>(d, out, n, sphere::cosine_hemisphere_inverse_slice) }
}

/// Folds points beyond the octahedral square's edges onto their neighbours on the sphere
/// (`(1 + e, v) -> (1 - e, 1 - v)`, ...): `n` points (`2n` floats) to `n` points of
/// `[0, 1]^2`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
/// overlapping arrays other than `u == out`.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equal_area_wrap(
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 2, 2>(u, out, n, sphere::equal_area_wrap_slice) }
}

/// `wc_sphere_equal_area_wrap` for texel indices of a `size x size` equal-area image: `n`
/// texels `[column, row]` (`2n` `int32_t`, any values) to `n` texels inside the image (`2n`
/// `uint32_t`), for bilinear filtering across the edges. Returns `n`, or 0 (writing nothing)
/// for a null or misaligned pointer, overlapping arrays other than `texel == out`, or
/// `size == 0`.
///
/// # Safety
/// `texel` must be readable for `2n` values and `out` writable for `2n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equal_area_wrap_texel(
    texel: *const i32,
    size: u32,
    out: *mut u32,
    n: usize,
) -> usize {
    if size == 0 {
        return 0;
    }
    // SAFETY: the caller's contract above; `map_each` checks null, alignment, size and
    // overlap.
    unsafe { map_each(texel, out, n, |t| sphere::equal_area_wrap_texel(t, size)) }
}

/// Density conversion for the equal-area map: `n` densities over the square to densities per
/// steradian (`pdf / (4 pi)`; NaN and negative become 0). Returns `n`, or 0 (writing nothing)
/// for a null or misaligned pointer or overlapping arrays other than `pdf == out`.
///
/// # Safety
/// `pdf` must be readable and `out` writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equal_area_pdf_to_solid_angle(
    pdf: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map_each` checks null, alignment, size and
    // overlap.
    unsafe {
        map_each(pdf, out, n, |[p]| {
            [sphere::equal_area_pdf_to_solid_angle(p)]
        })
    }
}

/// Density of the cosine-weighted hemisphere per steradian, `cos_theta / pi` (0 below the
/// horizon): `n` cosines to `n` densities. Returns `n` (0 as for
/// `wc_sphere_equal_area_pdf_to_solid_angle`).
///
/// # Safety
/// `cos_theta` must be readable and `out` writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_cosine_hemisphere_pdf(
    cos_theta: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map_each` checks null, alignment, size and
    // overlap.
    unsafe { map_each(cos_theta, out, n, |[c]| [sphere::cosine_hemisphere_pdf(c)]) }
}

/// Density conversion for the lat-long map: `n` densities over the square (`pdf`) at
/// directions `d` (`3n` floats) to densities per steradian, `pdf / (2 pi^2 sin theta)` (0 on
/// the axis). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or an
/// `out` that overlaps an input other than `pdf == out`.
///
/// # Safety
/// `pdf` must be readable for `n` floats, `d` for `3n` floats, and `out` writable for `n`
/// floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sphere_equirect_pdf_to_solid_angle(
    pdf: *const f32,
    d: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `zip_map` checks null, alignment, size and
    // overlap.
    unsafe {
        zip_map(pdf, d.cast::<[f32; 3]>(), out, n, |p, dir| {
            sphere::equirect_pdf_to_solid_angle(p, dir)
        })
    }
}
