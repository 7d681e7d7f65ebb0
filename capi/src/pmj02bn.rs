//! pmj02bn points: Owen-scrambled progressive multi-jittered (0,2) sequences with blue-noise
//! spacing, from tables embedded in the library.

use crate::ffi::{indexed, map_each, span};
use warpcore::pmj02bn;

/// Points `start, start + 1, ..., start + n - 1` (indices wrap after `UINT32_MAX`) of
/// `seed`'s Owen-scrambled pmj02bn sequence, in `[0, 1)^2`: `2n` floats. Every power-of-two
/// prefix (and aligned block) is a (0,m,2)-net. Returns `n`, or 0 (writing nothing) for a
/// null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `2n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_pmj02bn_sample(
    start: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `indexed` checks null, alignment and size.
    unsafe { indexed(start, seed, out, n, pmj02bn::sample_slice) }
}

/// The unscrambled table points `start, ..., start + n - 1` of table set `set` (both taken
/// modulo the table size, `wc_pmj02bn_sets()` and `wc_pmj02bn_points()`), as 0.32 fixed point:
/// `2n` `uint32_t`. Returns `n`, or 0 (writing nothing) for a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `2n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_pmj02bn_raw(set: u32, start: u32, out: *mut u32, n: usize) -> usize {
    if n == 0 || span(out, n.saturating_mul(2)).is_none() {
        return 0;
    }
    for i in 0..n {
        let index = start.wrapping_add(i as u32) as usize;
        let p = pmj02bn::raw(set as usize, index);
        // SAFETY: `i < n`, and `out` is writable for `2n` values (the caller's contract;
        // null, alignment and size checked by `span`).
        unsafe { core::ptr::copy_nonoverlapping(p.as_ptr(), out.add(2 * i), 2) };
    }
    n
}

/// The index permutation that decorrelates dimension pairs while keeping every power-of-two
/// prefix as a set: `out[i] = shuffle(index[i], seed)`. Returns `n`, or 0 (writing nothing)
/// for a null or misaligned pointer or overlapping arrays other than `index == out`.
///
/// # Safety
/// `index` must be readable and `out` writable for `n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_pmj02bn_shuffle(
    index: *const u32,
    seed: u32,
    out: *mut u32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `map_each` checks null, alignment, size and
    // overlap.
    unsafe { map_each(index, out, n, |[i]| [pmj02bn::shuffle(i, seed)]) }
}

/// Points per table set in this build (1024, 4096, 16384 or 65536; features).
#[unsafe(no_mangle)]
pub extern "C" fn wc_pmj02bn_points() -> usize {
    pmj02bn::POINTS
}

/// Table sets in this build (1 or 4; features).
#[unsafe(no_mangle)]
pub extern "C" fn wc_pmj02bn_sets() -> usize {
    pmj02bn::SETS
}
