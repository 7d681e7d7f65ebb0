//! Baseline samplers without tables: independent random points and a jittered grid.

use crate::ffi::indexed;
use warpcore::sequence;

/// Independent uniform points `start, ..., start + n - 1` of `seed` (a counter-based hash),
/// in `[0, 1)^2`: `2n` floats. Returns `n`, or 0 (writing nothing) for a null or misaligned
/// `out`.
///
/// # Safety
/// `out` must be writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sequence_random(
    start: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `indexed` checks null, alignment and size.
    unsafe { indexed(start, seed, out, n, sequence::random_slice) }
}

/// Jittered points `start, ..., start + n - 1` of an `m x m` grid, `m = floor(sqrt(count))`
/// (at most 4096; indices past `m^2` are random), for `seed`: `2n` floats. Returns `n`, or 0
/// (writing nothing) for a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sequence_stratified(
    start: u32,
    count: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `indexed` checks null, alignment and size.
    unsafe {
        indexed(start, seed, out, n, |i, seed, chunk| {
            sequence::stratified_slice(i, count, seed, chunk)
        })
    }
}
