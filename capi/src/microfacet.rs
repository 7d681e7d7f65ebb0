//! GGX microfacet reflection: records of interleaved floats in, records out (the slice forms of
//! `warpcore::microfacet`, whose docs give the formulas, precision and out-of-domain rules).

use crate::ffi::map;
use warpcore::microfacet as mf;

/// GGX distribution of normals `D(m)` per steradian: `n` records `[mx, my, mz, ax, ay]` (`5n` floats) to `n` values. 0 for `mz <= 0` or an invalid `m`; `alpha` clamped to `[1e-4, 1]`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `5n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_d(input: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 5, 1>(input, out, n, mf::ggx_d_slice) }
}

/// Smith masking `G1(w)` of GGX: `n` records `[wx, wy, wz, ax, ay]` (`5n` floats) to `n` values (`|wz|` is used; an invalid `w` reads as +z). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `5n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_g1(input: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 5, 1>(input, out, n, mf::ggx_g1_slice) }
}

/// Height-correlated Smith masking-shadowing `G2(wo, wi)` of GGX: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` values. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_g2(input: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 8, 1>(input, out, n, mf::ggx_g2_slice) }
}

/// GGX visible normals by spherical caps (Dupuy and Benyoub 2023): `n` records `[wo, ax, ay, u0, u1]` (`7n` floats) to `n` unit normals `m` (`3n` floats), distributed as `G1(wo) max(0, wo.m) D(m) / wo.z`. `wo` below the horizon is mirrored, an invalid `wo` reads as +z. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `7n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_visible_normal(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 7, 3>(input, out, n, mf::ggx_visible_normal_slice) }
}

/// Density of `wc_microfacet_ggx_visible_normal` per steradian of `m`: `n` records `[wo, m, ax, ay]` (`8n` floats) to `n` densities (0 for an invalid `m`). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_visible_normal_pdf(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 8, 1>(input, out, n, mf::ggx_visible_normal_pdf_slice) }
}

/// GGX reflection by visible normals: `n` records `[wo, ax, ay, u0, u1]` (`7n` floats) to `n` records `[wi, pdf]` (`4n` floats), `wi = 2 (wo.m) m - wo` (it may lie below the horizon) and its density per steradian, equal to `wc_microfacet_ggx_reflect_pdf` at `wi`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `7n` floats and `out` writable for `4n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_reflect(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 7, 4>(input, out, n, mf::ggx_reflect_slice) }
}

/// Density of `wc_microfacet_ggx_reflect` per steradian of `wi`: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` densities. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_reflect_pdf(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 8, 1>(input, out, n, mf::ggx_reflect_pdf_slice) }
}

/// Bounded GGX reflection (Eto and Tokuyoshi 2023): as `wc_microfacet_ggx_reflect`, with fewer directions below the horizon and its own exact density. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `7n` floats and `out` writable for `4n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_reflect_bounded(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 7, 4>(input, out, n, mf::ggx_reflect_bounded_slice) }
}

/// Density of `wc_microfacet_ggx_reflect_bounded` per steradian of `wi`: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` densities (0 outside the image of the shrunk cap). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
/// arrays other than `input == out` (in place: the output is smaller).
///
/// # Safety
/// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_microfacet_ggx_reflect_bounded_pdf(
    input: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { map::<f32, f32, 8, 1>(input, out, n, mf::ggx_reflect_bounded_pdf_slice) }
}
