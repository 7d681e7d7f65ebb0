//! Disk warps: `u[0]` drives the radius, `u[1]` the angle; outputs are points of the unit
//! disk, inputs of the inverses any points (clamped to `[-1, 1]`).

use crate::ffi::{CHUNK, overlap, span};
use warpcore::disk;

/// A `*4_slice` form: four disk samples per point.
type FourSlice = fn(&[[f32; 2]], &mut [[f32; 2]]) -> usize;

/// Polar map, `r = sqrt(u0)`, `theta = 2 pi u1`: `n` points `u` (`2n` floats) to `n` disk
/// points (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
/// or overlapping arrays other than `u == out`.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_polar(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 2>(u, out, n, disk::polar_slice) }
}

/// Inverse of the polar map: `n` points `p` (`2n` floats) to `n` points of the unit square.
/// Returns `n` (0 as for `wc_disk_polar`).
///
/// # Safety
/// `p` must be readable for `2n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_polar_inverse(p: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 2>(p, out, n, disk::polar_inverse_slice) }
}

/// Concentric (Shirley-Chiu) map: `n` points `u` (`2n` floats) to `n` disk points (`2n`
/// floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
/// overlapping arrays other than `u == out`.
///
/// # Safety
/// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_concentric(u: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 2>(u, out, n, disk::concentric_slice) }
}

/// Inverse of the concentric map: `n` points `p` (`2n` floats) to `n` points of the unit
/// square. Returns `n` (0 as for `wc_disk_concentric`).
///
/// # Safety
/// `p` must be readable for `2n` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_concentric_inverse(
    p: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, 2, 2>(p, out, n, disk::concentric_inverse_slice) }
}

/// polar4 (Christensen 2018): `n` disk samples (`2n` floats) from `n_points` points of the
/// square (`2 n_points` floats), four per point: sample `i` uses point `i / 4` in quadrant
/// `i % 4` (`r = sqrt(u0)`, `theta = (pi/2) u1 + (pi/2) (i % 4)`). Returns
/// `min(n, 4 n_points)`, or 0 (writing nothing) when that is 0, for a null or misaligned
/// pointer, a count whose byte size overflows, or overlapping arrays (the
/// `ceil(min(n, 4 n_points) / 4)` points the call reads and the outputs it writes).
///
/// # Safety
/// `points` must be readable for `2 n_points` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_polar4(
    points: *const f32,
    n_points: usize,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `four_per_point` checks null, alignment, size and
    // overlap.
    unsafe { four_per_point(points, n_points, out, n, disk::polar4_slice) }
}

/// Inverse of polar4: `n` disk points `p` (`2n` floats) to their points of the square (`2n`
/// floats, `out`) and quadrants (`n` values in 0..=3, `quadrant`). Returns `n`, or 0 (writing
/// nothing) for a null or misaligned pointer or overlapping arrays other than `p == out`.
///
/// # Safety
/// `p` must be readable for `2n` floats, `out` writable for `2n` floats and `quadrant`
/// writable for `n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_polar4_inverse(
    p: *const f32,
    out: *mut f32,
    quadrant: *mut u32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; the helper checks null, alignment, size and
    // overlap.
    unsafe { inverse_with_quadrant(p, out, quadrant, n, disk::polar4_inverse) }
}

/// concentric4: `n` disk samples (`2n` floats) from `n_points` points of the square (`2
/// n_points` floats), four per point: sample `i` is the quarter-disk Shirley-Chiu map of point
/// `i / 4`, turned into quadrant `i % 4`. Returns `min(n, 4 n_points)`, or 0 (writing nothing)
/// when that is 0, for a null or misaligned pointer, a count whose byte size overflows, or
/// overlapping arrays (as for `wc_disk_polar4`).
///
/// # Safety
/// `points` must be readable for `2 n_points` floats and `out` writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_concentric4(
    points: *const f32,
    n_points: usize,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `four_per_point` checks null, alignment, size and
    // overlap.
    unsafe { four_per_point(points, n_points, out, n, disk::concentric4_slice) }
}

/// Inverse of concentric4: `n` disk points `p` (`2n` floats) to their points of the square
/// (`2n` floats, `out`) and quadrants (`n` values in 0..=3, `quadrant`; the origin gives 0).
/// Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping arrays
/// other than `p == out`.
///
/// # Safety
/// `p` must be readable for `2n` floats, `out` writable for `2n` floats and `quadrant`
/// writable for `n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_disk_concentric4_inverse(
    p: *const f32,
    out: *mut f32,
    quadrant: *mut u32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; the helper checks null, alignment, size and
    // overlap.
    unsafe { inverse_with_quadrant(p, out, quadrant, n, disk::concentric4_inverse) }
}

/// Four disk samples per point through `slice` (a `*4_slice` form).
///
/// # Safety
/// `points` readable for `2 n_points` floats, `out` writable for `2n` floats.
unsafe fn four_per_point(
    points: *const f32,
    n_points: usize,
    out: *mut f32,
    n: usize,
    slice: FourSlice,
) -> usize {
    let n = n.min(n_points.saturating_mul(4));
    if n == 0 {
        return 0;
    }
    let used = n.div_ceil(4);
    let (Some(src), Some(dst)) = (span(points, 2 * used), span(out, n.saturating_mul(2))) else {
        return 0;
    };
    if overlap(src, dst) {
        return 0;
    }
    let mut a = [[0.0f32; 2]; CHUNK / 4];
    let mut b = [[0.0f32; 2]; CHUNK];
    let mut done = 0;
    while done < n {
        let k = (n - done).min(CHUNK);
        let pts = k.div_ceil(4);
        // SAFETY: points `done / 4 .. done / 4 + pts` are below `used`, outputs
        // `done .. done + k` below `n`: inside the caller's ranges (checked by `span`, no
        // overlap). The local buffers hold `CHUNK / 4` points and `CHUNK` samples.
        unsafe {
            core::ptr::copy_nonoverlapping(
                points.add(2 * (done / 4)).cast::<[f32; 2]>(),
                a.as_mut_ptr(),
                pts,
            );
        }
        let written = slice(&a[..pts], &mut b[..k]);
        debug_assert_eq!(written, k);
        // SAFETY: as above.
        unsafe {
            core::ptr::copy_nonoverlapping(b.as_ptr(), out.add(2 * done).cast::<[f32; 2]>(), k);
        }
        done += k;
    }
    n
}

/// Inverse with quadrants through `inverse`.
///
/// # Safety
/// `p` readable for `2n` floats, `out` writable for `2n` floats, `quadrant` for `n` values.
unsafe fn inverse_with_quadrant(
    p: *const f32,
    out: *mut f32,
    quadrant: *mut u32,
    n: usize,
    inverse: fn([f32; 2]) -> ([f32; 2], u32),
) -> usize {
    if n == 0 {
        return 0;
    }
    let (Some(q), Some(src), Some(dst)) = (
        span(quadrant, n),
        span(p, n.saturating_mul(2)),
        span(out, n.saturating_mul(2)),
    ) else {
        return 0;
    };
    if overlap(q, src) || overlap(q, dst) || (overlap(src, dst) && src != dst) {
        return 0;
    }
    let mut done = 0;
    while done < n {
        let k = (n - done).min(CHUNK);
        let mut a = [[0.0f32; 2]; CHUNK];
        // SAFETY: `done + k <= n`: inside the caller's ranges (checked by `span`).
        unsafe {
            core::ptr::copy_nonoverlapping(p.add(2 * done).cast::<[f32; 2]>(), a.as_mut_ptr(), k);
        }
        let mut u = [[0.0f32; 2]; CHUNK];
        let mut qs = [0u32; CHUNK];
        for ((src, u), q) in a.iter().zip(u.iter_mut()).zip(qs.iter_mut()).take(k) {
            (*u, *q) = inverse(*src);
        }
        // SAFETY: as above; `out` may equal `p` (this chunk was copied first).
        unsafe {
            core::ptr::copy_nonoverlapping(u.as_ptr(), out.add(2 * done).cast::<[f32; 2]>(), k);
            core::ptr::copy_nonoverlapping(qs.as_ptr(), quadrant.add(done), k);
        }
        done += k;
    }
    n
}
