//! The pointer rules every function follows, in one place: validation of C pointers and
//! counts, and the chunked copies between C memory and the slice forms of the core crate.
//!
//! The core crate's slice forms take Rust slices; C hands us raw pointers. We never build a
//! Rust reference to C *output* memory (it may be uninitialized, and it may overlap the
//! input): each call copies a chunk of inputs into a local buffer, runs the slice form into a
//! second local buffer and copies the results out, with `core::ptr::copy_nonoverlapping`.
//! Inputs that are only read for the whole call (weights, env-map storage) become shared
//! slices, after checking that nothing we write overlaps them.
//!
//! Rules (documented in the header):
//! * `n == 0` returns 0 and touches nothing; a null pointer with `n > 0` returns 0 and writes
//!   nothing;
//! * a pointer not aligned for its element type (4 bytes for `float` and `uint32_t`) returns
//!   0 and writes nothing (such a pointer cannot come from a valid C object of that type);
//! * a count whose byte size exceeds `isize::MAX` (or wraps the address space) returns 0;
//! * input and output may be the same array (in place) when an output element is no larger
//!   than an input element; any other overlap returns 0 and writes nothing.

use core::mem::{align_of, size_of};
use core::ptr::copy_nonoverlapping;

/// Elements per chunk: a multiple of 8 (the SIMD width) and of 4 (polar4's samples per
/// point), small enough for a microcontroller's stack (at most a few KiB per buffer).
pub(crate) const CHUNK: usize = 64;

/// Can an array of `count` elements of `T` exist: is its byte size at most `isize::MAX`
/// (`PTRDIFF_MAX`)? Checked arithmetic: false when `count * size_of::<T>()` overflows.
pub fn fits<T>(count: usize) -> bool {
    count
        .checked_mul(size_of::<T>())
        .is_some_and(|bytes| bytes <= isize::MAX as usize)
}

/// Address range `[start, end)` of `count` elements of `T` at `p`, if `p` is non-null,
/// aligned for `T`, and the byte size fits `isize` without wrapping the address space.
pub fn span<T>(p: *const T, count: usize) -> Option<(usize, usize)> {
    let start = p as usize;
    if p.is_null() || !start.is_multiple_of(align_of::<T>()) || !fits::<T>(count) {
        return None;
    }
    // `fits` bounds the product.
    Some((
        start,
        start.checked_add(count.checked_mul(size_of::<T>())?)?,
    ))
}

/// Do two address ranges share a byte?
pub fn overlap(a: (usize, usize), b: (usize, usize)) -> bool {
    a.0 < b.1 && b.0 < a.1 && a.0 < a.1 && b.0 < b.1
}

/// Copies `count` elements from C memory into `dst` (a local buffer).
///
/// # Safety
/// `src` must be valid for reads of `count` elements of `T` (the caller's contract, with
/// alignment and size checked by [`span`]) and `count <= dst.len()`.
#[inline(always)]
unsafe fn read<T: Copy>(src: *const T, dst: &mut [T], count: usize) {
    debug_assert!(count <= dst.len());
    // SAFETY: `src` is valid for `count` reads (the caller's contract), `dst` holds at least
    // `count` elements, and a local buffer cannot overlap C memory the caller lent us.
    unsafe { copy_nonoverlapping(src, dst.as_mut_ptr(), count) }
}

/// Copies `count` elements of `src` (a local buffer) to C memory.
///
/// # Safety
/// `dst` must be valid for writes of `count` elements of `T`, and `count <= src.len()`.
#[inline(always)]
unsafe fn write<T: Copy>(src: &[T], dst: *mut T, count: usize) {
    debug_assert!(count <= src.len());
    // SAFETY: `dst` is valid for `count` writes (the caller's contract), `src` holds at least
    // `count` elements, and a local buffer cannot overlap C memory.
    unsafe { copy_nonoverlapping(src.as_ptr(), dst, count) }
}

/// `n` interleaved inputs of `I` values of `A` to `n` interleaved outputs of `O` values of
/// `B`, through a slice form `f`. Returns `n`, or 0 when a pointer rule is broken.
///
/// # Safety
/// `input` must be valid for reads of `n * I` values and `out` for writes of `n * O` values
/// (the C caller's contract; null, misaligned and oversized pointers are rejected here).
pub unsafe fn map<A: Copy + Default, B: Copy + Default, const I: usize, const O: usize>(
    input: *const A,
    out: *mut B,
    n: usize,
    mut f: impl FnMut(&[[A; I]], &mut [[B; O]]) -> usize,
) -> usize {
    if n == 0 {
        return 0;
    }
    let (Some(src), Some(dst)) = (
        span(input, n.saturating_mul(I)),
        span(out, n.saturating_mul(O)),
    ) else {
        return 0;
    };
    let in_place = src.0 == dst.0 && O * size_of::<B>() <= I * size_of::<A>();
    if overlap(src, dst) && !in_place {
        return 0;
    }
    let mut a = [[A::default(); I]; CHUNK];
    let mut b = [[B::default(); O]; CHUNK];
    let mut done = 0;
    while done < n {
        let k = (n - done).min(CHUNK);
        // SAFETY: `done + k <= n`, so these are in the caller's ranges. In place, chunk `c`
        // writes output bytes below `(done + k) * O * size_of::<B>()`, which is at most the
        // end of the inputs already copied: nothing unread is overwritten.
        unsafe {
            read(input.add(done * I).cast::<[A; I]>(), &mut a, k);
            let written = f(&a[..k], &mut b[..k]);
            debug_assert_eq!(written, k);
            write(&b, out.add(done * O).cast::<[B; O]>(), k);
        }
        done += k;
    }
    n
}

/// [`map`] through a scalar form: `out[i] = f(input[i])`, in order (so `f` may walk a second
/// array alongside).
///
/// # Safety
/// As [`map`].
pub unsafe fn map_each<A: Copy + Default, B: Copy + Default, const I: usize, const O: usize>(
    input: *const A,
    out: *mut B,
    n: usize,
    mut f: impl FnMut([A; I]) -> [B; O],
) -> usize {
    // SAFETY: the caller's contract, passed on; `map` checks the pointers.
    unsafe {
        map::<A, B, I, O>(input, out, n, |i, o| {
            for (i, o) in i.iter().zip(o.iter_mut()) {
                *o = f(*i);
            }
            i.len().min(o.len())
        })
    }
}

/// `out[i] = f(a[i], b[i])` for `n` floats `a` and `n` values `b`. `b` is read throughout the
/// call: `out` must not overlap it; `out` may be `a` exactly (in place), no other overlap.
/// Returns `n`, or 0 (writing nothing) when a pointer rule is broken.
///
/// # Safety
/// `a` and `b` must be valid for reads of `n` values, `out` for writes of `n` floats.
pub unsafe fn zip_map<B: Copy + Default>(
    a: *const f32,
    b: *const B,
    out: *mut f32,
    n: usize,
    f: impl Fn(f32, B) -> f32,
) -> usize {
    if n == 0 {
        return 0;
    }
    // Every pointer rule first (`map` checks `a` against `out` again).
    let (Some(ra), Some(rb), Some(ro)) = (span(a, n), span(b, n), span(out.cast_const(), n)) else {
        return 0;
    };
    if overlap(rb, ro) || (overlap(ra, ro) && ra != ro) {
        return 0;
    }
    // SAFETY: the caller's contract; checked above (and again by `slice`): non-null, aligned,
    // of valid size, not written by this call.
    let Some(b) = (unsafe { slice(b, n, Some(ro)) }) else {
        return 0;
    };
    let mut b = b.iter();
    // SAFETY: the caller's contract; `map` checks null, alignment, size and overlap.
    unsafe {
        map_each::<f32, f32, 1, 1>(a, out, n, |[a]| {
            [f(a, b.next().copied().unwrap_or_default())]
        })
    }
}

/// `n` outputs of an index-driven sequence of `seed` (`O` floats each): its slice form
/// `f(first, seed, chunk)` over the indices `start, start + 1, ...`, wrapping after
/// `u32::MAX`. Returns `n`, or 0 when `out` breaks a pointer rule.
///
/// # Safety
/// `out` must be valid for writes of `n * O` floats.
pub unsafe fn indexed<const O: usize>(
    start: u32,
    seed: u32,
    out: *mut f32,
    n: usize,
    f: impl Fn(u32, u32, &mut [[f32; O]]) -> usize,
) -> usize {
    // SAFETY: the caller's contract, passed on; `generate` checks null, alignment and size.
    unsafe {
        generate::<O>(out, n, |offset, chunk| {
            f(start.wrapping_add(offset), seed, chunk)
        })
    }
}

/// `n` generated outputs of `O` floats: `f(offset, chunk)` fills `chunk` with the outputs
/// `offset..offset + chunk.len()` (the offset as the `u32` the index-driven sequences wrap
/// at). Returns `n`, or 0 when `out` breaks a pointer rule.
///
/// # Safety
/// `out` must be valid for writes of `n * O` floats.
pub unsafe fn generate<const O: usize>(
    out: *mut f32,
    n: usize,
    mut f: impl FnMut(u32, &mut [[f32; O]]) -> usize,
) -> usize {
    if n == 0 || span(out, n.saturating_mul(O)).is_none() {
        return 0;
    }
    let mut b = [[0.0f32; O]; CHUNK];
    let mut done = 0;
    while done < n {
        let k = (n - done).min(CHUNK);
        let written = f(done as u32, &mut b[..k]);
        debug_assert_eq!(written, k);
        // SAFETY: `done + k <= n`: inside the caller's output range.
        unsafe { write(&b, out.add(done * O).cast::<[f32; O]>(), k) };
        done += k;
    }
    n
}

/// The arrays of a call that reads `input` (`n_in` values) throughout and fills `out` (`n_out`
/// values): the input as a shared slice and the output, zeroed through the raw pointer first
/// (C memory may be uninitialized), as a mutable one. `None`, reading and writing nothing,
/// for a null or misaligned pointer, a size past `PTRDIFF_MAX` or overlapping arrays.
///
/// # Safety
/// `input` must be valid for reads of `n_in` values, initialized and not written by anyone
/// else during the call; `out` valid for writes of `n_out` values; all-zero bytes must be a
/// valid `B`. The returned lifetime is the call's.
pub unsafe fn read_and_fill<'a, A, B>(
    input: *const A,
    n_in: usize,
    out: *mut B,
    n_out: usize,
) -> Option<(&'a [A], &'a mut [B])> {
    let (read, write) = (span(input, n_in)?, span(out.cast_const(), n_out)?);
    if overlap(read, write) {
        return None;
    }
    // SAFETY: the caller's contract; non-null, aligned, of valid size and disjoint from `out`
    // (checked above; `slice` checks again).
    let input = unsafe { slice(input, n_in, Some(write))? };
    // SAFETY: `out` is writable for `n_out` values (the caller's contract), non-null, aligned,
    // of valid size (checked by `span`) and disjoint from `input`; zeroed first, and zero
    // bytes are a valid `B` (the caller's contract), so the slice refers to initialized values.
    let out = unsafe {
        core::ptr::write_bytes(out, 0, n_out);
        core::slice::from_raw_parts_mut(out, n_out)
    };
    Some((input, out))
}

/// A read-only C array as a slice, for inputs read throughout a call (weights, storage),
/// unless a pointer rule is broken or it overlaps `writes` (the range the call writes).
///
/// # Safety
/// `p` must be valid for reads of `count` elements of `T`, initialized, and not written by
/// anyone else during the call (the C caller's contract). The returned lifetime is the
/// call's.
pub unsafe fn slice<'a, T>(
    p: *const T,
    count: usize,
    writes: Option<(usize, usize)>,
) -> Option<&'a [T]> {
    if count == 0 {
        return Some(&[]);
    }
    let range = span(p, count)?;
    if writes.is_some_and(|w| overlap(range, w)) {
        return None;
    }
    // SAFETY: non-null, aligned, `count * size_of::<T>() <= isize::MAX` (checked by `span`);
    // valid, initialized and unaliased by writes for the call (the caller's contract and the
    // overlap check above).
    Some(unsafe { core::slice::from_raw_parts(p, count) })
}
