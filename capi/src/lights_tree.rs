//! The light tree (`warpcore::lights::LightTree`) over caller-owned storage: build it from an
//! array of `WcLightBounds`, then pick lights by their importance at shading points, with the
//! exact probability for MIS.

use crate::envmap::{WC_ERR_INVALID_ARGUMENT, WC_OK};
use crate::ffi::{overlap, slice, span};
use crate::lights::{build_sizes, code};
use warpcore::lights::{LightBounds, LightTree};

/// One light's bounds for the tree: the fields of the crate's `LightBounds`, in its order
/// (box corners, power >= 0, emission axis, then the cosines of the normal spread and of the
/// falloff beyond it, each in `[-1, 1]`), with `two_sided` as a word (nonzero: true), so that
/// any bytes a C caller writes are a valid value.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[allow(missing_docs)] // the fields are documented together above
pub struct WcLightBounds {
    pub min: [f32; 3],
    pub max: [f32; 3],
    pub power: f32,
    pub axis: [f32; 3],
    pub cos_theta_o: f32,
    pub cos_theta_e: f32,
    pub two_sided: u32,
}

impl WcLightBounds {
    fn bounds(&self) -> LightBounds {
        LightBounds {
            min: self.min,
            max: self.max,
            power: self.power,
            axis: self.axis,
            cos_theta_o: self.cos_theta_o,
            cos_theta_e: self.cos_theta_e,
            two_sided: self.two_sided != 0,
        }
    }
}

/// Words of storage `wc_lights_tree_build` needs for `lights` lights
/// (`16 + 48 (lights / 3 + 14) + lights`, about 68 bytes per light), `SIZE_MAX` above 2^24
/// lights. Any argument; reads and writes no memory.
#[unsafe(no_mangle)]
pub extern "C" fn wc_lights_tree_storage_len(lights: usize) -> usize {
    LightTree::storage_len(lights)
}

/// Builds the light tree of `n` lights into `storage`. Returns `WC_OK` (0) or the first
/// failed check, in this order: `WC_ERR_EMPTY` (`n == 0`), `WC_ERR_TOO_LARGE` (above 2^24
/// lights, or arrays above `PTRDIFF_MAX` bytes), `WC_ERR_STORAGE_TOO_SMALL` (`storage_len`
/// below `wc_lights_tree_storage_len(n)`), `WC_ERR_INVALID_ARGUMENT` (a null or misaligned
/// pointer, or `lights` overlapping the storage's first `wc_lights_tree_storage_len(n)`
/// words), then the lights' checks (`WC_ERR_INVALID_WEIGHT`, `WC_ERR_INVALID_BOUNDS`,
/// `WC_ERR_ALL_ZERO`). The storage is written only after the pointer checks pass (exactly its
/// first `wc_lights_tree_storage_len(n)` words); its bytes are the file format.
///
/// # Safety
/// `lights` must be readable for `n` elements and `storage` writable for `storage_len`
/// words (only when the checks before the lights' pass).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_tree_build(
    lights: *const WcLightBounds,
    n: usize,
    storage: *mut u32,
    storage_len: usize,
) -> i32 {
    let needed = match build_sizes::<WcLightBounds>(n, LightTree::storage_len, storage_len) {
        Ok(needed) => needed,
        Err(code) => return code,
    };
    let Some(writes) = span(storage.cast_const(), needed) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    // SAFETY: the caller's contract; `slice` checks null, alignment, size and that the
    // lights do not overlap the words the build writes.
    let Some(lights) = (unsafe { slice(lights, n, Some(writes)) }) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    // SAFETY: `span` checked null, alignment and size of the first `needed` words; the
    // caller's contract makes them writable, and nothing else the call reads overlaps them.
    let words = unsafe { core::slice::from_raw_parts_mut(storage, needed) };
    let light = |i: usize| lights.get(i).map_or(LightBounds::default(), |l| l.bounds());
    match LightTree::new_from_fn(n, light, words) {
        Ok(_) => WC_OK,
        Err(e) => code(e),
    }
}

/// Checks a storage's header in O(1) (the crate's `from_storage`). Returns `WC_OK` or
/// `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` with a null or misaligned `storage`),
/// `WC_ERR_STORAGE_TOO_SMALL`, `WC_ERR_WRONG_FORMAT`, `WC_ERR_UNSUPPORTED_VERSION`,
/// `WC_ERR_CORRUPT`. Sampling a storage that passes is safe whatever its other words hold;
/// the sampling functions run this check on every call. Reads only.
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_tree_from_storage(
    storage: *const u32,
    storage_len: usize,
) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { check(storage, storage_len, false) }
}

/// `wc_lights_tree_from_storage` plus the content checksum (the crate's
/// `from_storage_verified`): every single-bit flip is rejected (`WC_ERR_CORRUPT`). O(n).
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_tree_from_storage_verified(
    storage: *const u32,
    storage_len: usize,
) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { check(storage, storage_len, true) }
}

/// # Safety
/// `storage` must be readable for `storage_len` words.
unsafe fn check(storage: *const u32, storage_len: usize, verified: bool) -> i32 {
    // SAFETY: the caller's contract; `slice` checks null (with `storage_len > 0`) and alignment.
    let Some(s) = (unsafe { slice(storage, storage_len, None) }) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    let r = if verified {
        LightTree::from_storage_verified(s)
    } else {
        LightTree::from_storage(s)
    };
    match r {
        Ok(_) => WC_OK,
        Err(e) => code(e),
    }
}

/// A C input array as a slice, unless a pointer rule is broken or it overlaps one of
/// `writes` (the ranges the call writes).
///
/// # Safety
/// `ptr` must be readable for `count` elements (the C caller's contract).
unsafe fn input<'a, T>(ptr: *const T, count: usize, writes: &[(usize, usize)]) -> Option<&'a [T]> {
    // SAFETY: the caller's contract; `slice` checks null, alignment and size.
    let s = unsafe { slice(ptr, count, None) }?;
    let range = span(ptr, count)?;
    if writes.iter().any(|&w| overlap(range, w)) {
        return None;
    }
    Some(s)
}

/// A sampling call's tree, shading points and normals.
type Inputs<'a> = (LightTree<'a>, &'a [[f32; 3]], &'a [[f32; 3]]);

/// The tree and the shading points (`3n` floats each of `p` and `normal`) of a sampling call,
/// if every pointer passes and no input overlaps `writes`.
///
/// # Safety
/// As the callers'.
unsafe fn inputs<'a>(
    storage: *const u32,
    storage_len: usize,
    p: *const f32,
    normal: *const f32,
    n: usize,
    writes: &[(usize, usize)],
) -> Option<Inputs<'a>> {
    let count = n.checked_mul(3)?;
    // SAFETY: the caller's contract.
    let (p, normal, s) = unsafe {
        (
            input(p, count, writes)?,
            input(normal, count, writes)?,
            input(storage, storage_len, writes)?,
        )
    };
    let tree = LightTree::from_storage(s).ok()?;
    Some((tree, p.as_chunks::<3>().0, normal.as_chunks::<3>().0))
}

/// Picks a light at each of `n` shading points: `p` and `normal` hold `3n` floats (a normal
/// of zeros: a point in a medium), `u` `n` floats (any values; clamped to `[0, 1)`). Writes
/// `index[i]` and `prob[i]`: the light and its probability, equal bit for bit to
/// `wc_lights_tree_pmf` of that light, or `UINT32_MAX` and 0 where no light contributes.
/// Returns `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count
/// whose byte size overflows, outputs that overlap each other or an input, or a storage that
/// fails `wc_lights_tree_from_storage`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `p` and `normal` for `3n` floats, `u`
/// for `n` floats, `index` and `prob` writable for `n` elements.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_tree_sample(
    storage: *const u32,
    storage_len: usize,
    p: *const f32,
    normal: *const f32,
    u: *const f32,
    index: *mut u32,
    prob: *mut f32,
    n: usize,
) -> usize {
    if n == 0 {
        return 0;
    }
    let (Some(wi), Some(wp)) = (span(index.cast_const(), n), span(prob.cast_const(), n)) else {
        return 0;
    };
    if overlap(wi, wp) {
        return 0;
    }
    let writes = [wi, wp];
    // SAFETY: the caller's contract; `inputs` and `input` check every pointer.
    let (Some((tree, p, normal)), Some(u)) = (unsafe {
        (
            inputs(storage, storage_len, p, normal, n, &writes),
            input(u, n, &writes),
        )
    }) else {
        return 0;
    };
    // SAFETY: `span` checked null, alignment and size; the caller's contract makes them
    // writable; they overlap neither each other nor any input (checked above).
    let (index, prob) = unsafe {
        (
            core::slice::from_raw_parts_mut(index, n),
            core::slice::from_raw_parts_mut(prob, n),
        )
    };
    for (k, (i, q)) in index.iter_mut().zip(prob.iter_mut()).enumerate() {
        let (Some(&pp), Some(&nn), Some(&uu)) = (p.get(k), normal.get(k), u.get(k)) else {
            break;
        };
        let (a, b) = tree.sample(pp, nn, uu).unwrap_or((u32::MAX, 0.0));
        *i = a;
        *q = b;
    }
    n
}

/// The probability that `wc_lights_tree_sample` at shading point `i` (`p`, `normal`: `3n`
/// floats) returns light `index[i]`, into `out[i]` (0 for an index past the end, a light of
/// power 0 or of importance 0 there). Returns `n`, or 0 (writing nothing) for `n == 0`, a
/// null or misaligned pointer, a count whose byte size overflows, an `out` overlapping an
/// input, or a storage that fails `wc_lights_tree_from_storage`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `p` and `normal` for `3n` floats,
/// `index` for `n` words, `out` writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_lights_tree_pmf(
    storage: *const u32,
    storage_len: usize,
    p: *const f32,
    normal: *const f32,
    index: *const u32,
    out: *mut f32,
    n: usize,
) -> usize {
    if n == 0 {
        return 0;
    }
    let Some(wo) = span(out.cast_const(), n) else {
        return 0;
    };
    // SAFETY: the caller's contract; `inputs` and `input` check every pointer.
    let (Some((tree, p, normal)), Some(index)) = (unsafe {
        (
            inputs(storage, storage_len, p, normal, n, &[wo]),
            input(index, n, &[wo]),
        )
    }) else {
        return 0;
    };
    // SAFETY: `span` checked null, alignment and size; writable by the caller's contract; no
    // input overlaps it (checked above).
    let out = unsafe { core::slice::from_raw_parts_mut(out, n) };
    for (k, o) in out.iter_mut().enumerate() {
        let (Some(&pp), Some(&nn), Some(&i)) = (p.get(k), normal.get(k), index.get(k)) else {
            break;
        };
        *o = tree.pmf(pp, nn, i);
    }
    n
}
