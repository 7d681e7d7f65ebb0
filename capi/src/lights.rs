//! Light selection over caller-owned storage: the alias table (choose a light in proportion
//! to its power, O(1) per sample, with the exact probability of the choice).

use crate::envmap::{
    WC_ERR_ALL_ZERO, WC_ERR_CORRUPT, WC_ERR_EMPTY, WC_ERR_INVALID_ARGUMENT, WC_ERR_INVALID_BOUNDS,
    WC_ERR_INVALID_WEIGHT, WC_ERR_OTHER, WC_ERR_STORAGE_TOO_SMALL, WC_ERR_TOO_LARGE,
    WC_ERR_UNSUPPORTED_VERSION, WC_ERR_WRONG_FORMAT, WC_OK,
};
use crate::ffi::{fits, map, map_each, read_and_fill, slice, span};
use warpcore::lights::{AliasTable, Error};

/// A chosen light and the probability of choosing it.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WcLightChoice {
    /// Index of the light, below the table's light count.
    pub index: u32,
    /// The probability of that choice, equal bit for bit to `wc_lights_alias_pmf` of `index`.
    pub prob: f32,
}

/// The `WC_ERR_*` code of a crate error (the alias table's and the light tree's).
pub(crate) fn code(e: Error) -> i32 {
    match e {
        Error::Empty => WC_ERR_EMPTY,
        Error::TooLarge => WC_ERR_TOO_LARGE,
        Error::StorageTooSmall { .. } => WC_ERR_STORAGE_TOO_SMALL,
        Error::InvalidWeight { .. } => WC_ERR_INVALID_WEIGHT,
        Error::InvalidBounds { .. } => WC_ERR_INVALID_BOUNDS,
        Error::AllZero => WC_ERR_ALL_ZERO,
        Error::WrongFormat { .. } => WC_ERR_WRONG_FORMAT,
        Error::UnsupportedVersion { .. } => WC_ERR_UNSUPPORTED_VERSION,
        Error::Corrupt { .. } => WC_ERR_CORRUPT,
        _ => WC_ERR_OTHER,
    }
}

/// The size checks both light-table builds make before touching memory: `n` lights of `T`
/// need `storage_len(n)` words (`WC_ERR_EMPTY`, `WC_ERR_TOO_LARGE` when either array's bytes
/// pass `PTRDIFF_MAX`, `WC_ERR_STORAGE_TOO_SMALL`); the words needed otherwise.
pub(crate) fn build_sizes<T>(
    n: usize,
    storage_len_of: fn(usize) -> usize,
    storage_len: usize,
) -> Result<usize, i32> {
    if n == 0 {
        return Err(WC_ERR_EMPTY);
    }
    let needed = storage_len_of(n);
    if needed == usize::MAX || !fits::<T>(n) || !fits::<u32>(needed) {
        return Err(WC_ERR_TOO_LARGE);
    }
    if storage_len < needed {
        return Err(WC_ERR_STORAGE_TOO_SMALL);
    }
    Ok(needed)
}

/// Words of storage `wc_lights_alias_build` needs for `lights` lights: `8 + 4 lights` (16
/// bytes per light and a 32-byte header); `SIZE_MAX` above 2^26 lights. Any argument; reads
/// and writes no memory.
#[unsafe(no_mangle)]
pub extern "C" fn wc_lights_alias_storage_len(lights: usize) -> usize {
    AliasTable::storage_len(lights)
}

/// Builds the alias table of `n` weights (usually each light's power; any finite value
/// `>= 0`) into `storage` (Vose's method on exact integer masses, O(n), no allocation).
/// Returns `WC_OK` (0) or the first failed check, in this order: `WC_ERR_EMPTY` (`n` is
/// 0), `WC_ERR_TOO_LARGE` (more than 2^26 lights, or arrays larger than `PTRDIFF_MAX`
/// bytes), `WC_ERR_STORAGE_TOO_SMALL` (`storage_len < wc_lights_alias_storage_len(n)`),
/// `WC_ERR_INVALID_ARGUMENT` (a null or misaligned pointer, or weights overlapping the
/// storage's first `wc_lights_alias_storage_len(n)` words), `WC_ERR_INVALID_WEIGHT` (a weight
/// is NaN, infinite or negative; `-0.0` is zero), `WC_ERR_ALL_ZERO` (every weight is zero).
/// On the first four errors nothing is written; otherwise exactly the first
/// `wc_lights_alias_storage_len(n)` words are (zeroed on the last two errors). The storage's
/// bytes are the file format, the same as the Rust crate's.
///
/// # Safety
/// `weights` must be readable for `n` floats and `storage` writable for `storage_len` words
/// (only when the checks before `WC_ERR_INVALID_ARGUMENT` pass).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_alias_build(
    weights: *const f32,
    n: usize,
    storage: *mut u32,
    storage_len: usize,
) -> i32 {
    let needed = match build_sizes::<f32>(n, AliasTable::storage_len, storage_len) {
        Ok(needed) => needed,
        Err(code) => return code,
    };
    // SAFETY: the caller's contract: weights readable for `n` floats and unchanged during the
    // call, storage writable for `storage_len >= needed` words; a zero word is a valid `u32`.
    // `read_and_fill` checks null, alignment, size and overlap first.
    let Some((weights, storage)) = (unsafe { read_and_fill(weights, n, storage, needed) }) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    match AliasTable::new(weights, storage) {
        Ok(_) => WC_OK,
        Err(e) => code(e),
    }
}

/// The table in `storage`, checked in O(1) (`verified`: O(n), every word and the checksum).
///
/// # Safety
/// `storage` must be readable for `storage_len` words, unchanged during the borrow.
unsafe fn load<'a>(
    storage: *const u32,
    storage_len: usize,
    writes: Option<(usize, usize)>,
    verified: bool,
) -> Result<AliasTable<'a>, i32> {
    // SAFETY: the caller's contract; `slice` checks null, alignment, size and overlap.
    let s = unsafe { slice(storage, storage_len, writes) }.ok_or(WC_ERR_INVALID_ARGUMENT)?;
    let t = if verified {
        AliasTable::from_storage_verified(s)
    } else {
        AliasTable::from_storage(s)
    };
    t.map_err(code)
}

/// The table a batch of `n > 0` outputs at `out` reads: `None` for `n == 0`, an `out` that
/// breaks the pointer rules or overlaps the storage, or a storage that fails the O(1) check.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, unchanged during the borrow.
unsafe fn for_batch<'a, O>(
    storage: *const u32,
    storage_len: usize,
    out: *mut O,
    n: usize,
) -> Option<AliasTable<'a>> {
    let writes = span(out.cast_const(), n).filter(|_| n > 0)?;
    // SAFETY: the caller's contract; `load` checks that `out` does not overlap the storage.
    unsafe { load(storage, storage_len, Some(writes), false) }.ok()
}

/// Checks an alias table's header in O(1) (the crate's `from_storage`): `WC_OK`, or
/// `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` and `storage` null or misaligned),
/// `WC_ERR_STORAGE_TOO_SMALL`, `WC_ERR_WRONG_FORMAT` (word 0 is not `"wcAL"`),
/// `WC_ERR_UNSUPPORTED_VERSION`, `WC_ERR_CORRUPT` (a light count or reserved word a build
/// never writes). Sampling a storage that passes never leaves it: indices below the light
/// count, probabilities in `[0, 1]`. Reads only.
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_alias_from_storage(
    storage: *const u32,
    storage_len: usize,
) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { load(storage, storage_len, None, false) }.map_or_else(|e| e, |_| WC_OK)
}

/// `wc_lights_alias_from_storage`, then every column's invariants and the content checksum
/// (the crate's `from_storage_verified`): every single-bit flip of a storage is caught
/// (`WC_ERR_CORRUPT`). For loaders of files. Reads only.
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_alias_from_storage_verified(
    storage: *const u32,
    storage_len: usize,
) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { load(storage, storage_len, None, true) }.map_or_else(|e| e, |_| WC_OK)
}

/// Chooses `n` lights, one per float of `u` (any values; NaN and negatives act as 0, values
/// `>= 1` as `1 - 2^-24`), each with probability proportional to its weight, never one of
/// weight 0; `out[i]` holds the light and the exact probability of choosing it. Returns `n`,
/// or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte size
/// overflows, an `out` overlapping `u` or the storage, or a storage that fails
/// `wc_lights_alias_from_storage`. Bit-identical to the crate's `AliasTable::sample`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `u` for `n` floats and `out` writable
/// for `n` choices.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_alias_sample(
    storage: *const u32,
    storage_len: usize,
    u: *const f32,
    out: *mut WcLightChoice,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract.
    let Some(t) = (unsafe { for_batch(storage, storage_len, out, n) }) else {
        return 0;
    };
    // SAFETY: the caller's contract; `map` checks null, alignment, size and that `out` does
    // not overlap `u` (a choice is larger than a float: no in-place use).
    unsafe {
        map::<f32, WcLightChoice, 1, 1>(u, out, n, |u, o| {
            let (mut index, mut prob) = ([0u32; 64], [0.0f32; 64]);
            let k = t.sample_slice(u.as_flattened(), &mut index, &mut prob);
            for ((o, &i), &p) in o.iter_mut().zip(&index).zip(&prob) {
                *o = [WcLightChoice { index: i, prob: p }];
            }
            k
        })
    }
}

/// The probability that `wc_lights_alias_sample` chooses each of `n` light indices (0 for
/// an index at or above the light count). Returns `n`, or 0 (writing nothing) for `n == 0`,
/// a null or misaligned pointer, a count whose byte size overflows, an `out` overlapping the
/// storage or overlapping `index` other than exactly in place (`out == index`), or a storage
/// that fails `wc_lights_alias_from_storage`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `index` for `n` values and `out`
/// writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_alias_pmf(
    storage: *const u32,
    storage_len: usize,
    index: *const u32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract; `map_each` checks the pointers and their overlap.
    unsafe { for_batch(storage, storage_len, out, n) }.map_or(0, |t| unsafe {
        map_each::<u32, f32, 1, 1>(index, out, n, |[i]| [t.pmf(i)])
    })
}
