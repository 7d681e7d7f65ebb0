//! Triangle warps: barycentric coordinates `[b0, b1, b2]` (each >= 0, summing to 1) weighting
//! the vertices of the caller's triangle.

use warpcore::triangle;

/// Low-distortion map (Heitz 2019): `n` points `u` (`2n` floats) to `n` barycentrics (`3n`
/// floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
/// overlapping arrays.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_uniform(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 3>(u, out, n, triangle::uniform_slice) }
}

/// Inverse of the low-distortion map: `n` barycentrics `b` (`3n` floats; `b2` is implied) to
/// `n` points of the square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or
/// misaligned pointer or overlapping arrays other than `b == out`.
///
/// # Safety
/// `b` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_uniform_inverse(
    b: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 3, 2>(b, out, n, triangle::uniform_inverse_slice) }
}

/// Square-root map, `b0 = 1 - sqrt(u0)`, `b1 = u1 sqrt(u0)`: `n` points `u` (`2n` floats) to
/// `n` barycentrics (`3n` floats). Returns `n` (0 as for `wc_triangle_uniform`).
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_sqrt_map(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 3>(u, out, n, triangle::sqrt_map_slice) }
}

/// Inverse of the square-root map: `n` barycentrics (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n` (0 as for `wc_triangle_uniform_inverse`).
///
/// # Safety
/// `b` must be readable for `3n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_sqrt_map_inverse(
    b: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 3, 2>(b, out, n, triangle::sqrt_map_inverse_slice) }
}

/// Basu-Owen points: barycentrics of points `start, start + 1, ..., start + n - 1` (indices
/// wrap after `UINT32_MAX`) of `seed`'s scrambled sequence (`seed = 0`: unscrambled), `3n`
/// floats. Returns `n`, or 0 (writing nothing) for a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_basu_owen(
    start: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `indexed` checks null, alignment and size.
    unsafe { crate::ffi::indexed(start, seed, out, n, triangle::basu_owen_slice) }
}

/// Basu-Owen points with one digit permutation per level, shared by every node of the level
/// (`seed = 0`: unscrambled): barycentrics of points `start, ..., start + n - 1` (indices wrap
/// after `UINT32_MAX`), `3n` floats. Returns `n`, or 0 (writing nothing) for a null or
/// misaligned `out`.
///
/// # Safety
/// `out` must be writable for `3n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_triangle_basu_owen_permuted(
    start: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `indexed` checks null, alignment and size.
    unsafe { crate::ffi::indexed(start, seed, out, n, triangle::basu_owen_permuted_slice) }
}
