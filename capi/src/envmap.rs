//! Environment-map importance sampling over caller-owned storage: build the tables from
//! weights (or load them from a file: the storage is self-describing and little-endian on
//! every target), then sample texels in proportion to their weight.

use crate::ffi::{fits, map, overlap, read_and_fill, slice, span, zip_map};
use core::mem::size_of;
use warpcore::envmap::{
    self, Compensation, DirectionSample, Distribution, Error, Hierarchical, Layout, MAX_SIDE,
    MarginalConditional, Sample, image,
};

/// Success.
pub const WC_OK: i32 = 0;
/// `width` or `height` is zero.
pub const WC_ERR_ZERO_SIZE: i32 = -1;
/// A side exceeds 2^24, the tables would exceed 2^32 words, or an array's byte size would
/// exceed `PTRDIFF_MAX` (possible on 32-bit targets); see each function.
pub const WC_ERR_TOO_LARGE: i32 = -2;
/// An array length does not match the sizes (the Rust crate's error; no function of this
/// header returns it, since C arrays carry no length).
pub const WC_ERR_LENGTH_MISMATCH: i32 = -3;
/// The storage is shorter than `storage_len` (or than its header says).
pub const WC_ERR_STORAGE_TOO_SMALL: i32 = -4;
/// A weight is `+inf`.
pub const WC_ERR_INFINITE_WEIGHT: i32 = -5;
/// Word 0 of the storage is the format tag of neither distribution.
pub const WC_ERR_WRONG_FORMAT: i32 = -6;
/// The storage's format version is not the one this library reads.
pub const WC_ERR_UNSUPPORTED_VERSION: i32 = -7;
/// A header word (or, for `from_storage_verified`, a table word, or content that
/// does not match the checksum in header word 8) holds a value a build never writes.
pub const WC_ERR_CORRUPT: i32 = -8;
/// A null or misaligned pointer, arrays that overlap where they must not, or (see each
/// function) a bad `kind`, `compensation` or `channels`, or a `storage_len` no array can
/// have.
pub const WC_ERR_INVALID_ARGUMENT: i32 = -9;
/// An error this version of the header has no name for.
pub const WC_ERR_OTHER: i32 = -10;
/// No lights (`n == 0`; the light-selection builders).
pub const WC_ERR_EMPTY: i32 = -11;
/// A light's weight or power is NaN, infinite or negative (the light-selection builders).
pub const WC_ERR_INVALID_WEIGHT: i32 = -12;
/// A light's bounds are unusable (`wc_lights_tree_build`): a NaN or infinite coordinate,
/// `min > max`, a zero, NaN or infinite axis, or a cosine outside `[-1, 1]`.
pub const WC_ERR_INVALID_BOUNDS: i32 = -13;
/// Every light's weight or power is zero: no light can be chosen.
pub const WC_ERR_ALL_ZERO: i32 = -14;

/// Words of the header at the start of every storage (64 bytes: the tables after it sit on
/// cache lines when the storage is 64-byte aligned, e.g. from `aligned_alloc(64, ...)`).
pub const WC_ENVMAP_HEADER_WORDS: u32 = 16;
/// The storage format version this library writes and reads (header word 1). Version 3 adds
/// a content checksum (header word 8) and bytes that do not depend on the buffer's address;
/// older storages get `WC_ERR_UNSUPPORTED_VERSION`: rebuild them from the weights.
pub const WC_ENVMAP_FORMAT_VERSION: u32 = 3;

/// `compensation` of `wc_envmap_build_compensated`: the weights as given.
pub const WC_ENVMAP_COMPENSATION_NONE: u32 = 0;
/// `compensation`: subtract `fraction` times the mean weight (texels of equal solid angle:
/// equal-area maps), clamp at 0.
pub const WC_ENVMAP_COMPENSATION_UNIFORM: u32 = 1;
/// `compensation`: equirect (lat-long) weights (radiance times the row's `sin(theta)`, as
/// `wc_envmap_equirect_solid_angle_weights` makes them): subtract `fraction` times the
/// radiance's solid-angle average times the row's `sin(theta)`, clamp at 0.
pub const WC_ENVMAP_COMPENSATION_EQUIRECT: u32 = 2;

/// `layout` of the direction functions: the equirect (lat-long) square of
/// `wc_sphere_equirect` (`phi = 2 pi u`, `theta = pi v`, row 0 around `+z`).
pub const WC_ENVMAP_LAYOUT_EQUIRECT: u32 = 0;
/// `layout` of the direction functions: the equal-area octahedral square of
/// `wc_sphere_equal_area` (its centre at `+z`).
pub const WC_ENVMAP_LAYOUT_EQUAL_AREA: u32 = 1;

// Literals, so that cbindgen can write them; checked against the core crate here.
const _: () = assert!(WC_ENVMAP_HEADER_WORDS as usize == envmap::HEADER_WORDS);
const _: () = assert!(WC_ENVMAP_FORMAT_VERSION == envmap::FORMAT_VERSION);

/// One environment-map sample.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WcEnvSample {
    /// The point, in `[0, 1)^2`, inside `texel`.
    pub uv: [f32; 2],
    /// Density with respect to area on `[0, 1]^2` at `uv` (`P(texel) * width * height`).
    pub pdf: f32,
    /// `[column, row]` of the texel the point lies in.
    pub texel: [u32; 2],
}

/// One environment-map sample as a direction (the direction functions' output).
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct WcEnvDirection {
    /// The unit direction (`wc_sphere_equirect` or `wc_sphere_equal_area` of `uv`).
    pub dir: [f32; 3],
    /// Density with respect to solid angle at `dir` (per steradian); 0 only for an equirect
    /// sample exactly at the pole.
    pub pdf: f32,
    /// The point on the unit square, in `[0, 1)^2`.
    pub uv: [f32; 2],
    /// `[column, row]` of the texel.
    pub texel: [u32; 2],
}

fn layout_of(layout: u32) -> Option<Layout> {
    match layout {
        WC_ENVMAP_LAYOUT_EQUIRECT => Some(Layout::Equirect),
        WC_ENVMAP_LAYOUT_EQUAL_AREA => Some(Layout::EqualArea),
        _ => None,
    }
}

/// A static, NUL-terminated English description of a `WC_OK` / `WC_ERR_*` code, for messages:
/// never null; codes this header does not name get `"unknown warpcore error code"`. Any
/// argument; reads and writes no memory (the strings live as long as the program).
#[unsafe(no_mangle)]
pub extern "C" fn wc_error_string(code: i32) -> *const core::ffi::c_char {
    let s: &'static core::ffi::CStr = match code {
        WC_OK => c"success",
        WC_ERR_ZERO_SIZE => c"environment map has zero width or height",
        WC_ERR_TOO_LARGE => {
            c"too large: a side above 2^24, tables above 2^32 words, or an array above PTRDIFF_MAX bytes"
        }
        WC_ERR_LENGTH_MISMATCH => c"an array length does not match the sizes",
        WC_ERR_STORAGE_TOO_SMALL => c"storage shorter than needed (or than its header says)",
        WC_ERR_INFINITE_WEIGHT => c"a weight is +inf",
        WC_ERR_WRONG_FORMAT => {
            c"not an environment-map storage (wrong format tag, or a byte-swapped copy)"
        }
        WC_ERR_UNSUPPORTED_VERSION => {
            c"storage format version not supported (older storages: rebuild the tables from the weights)"
        }
        WC_ERR_CORRUPT => {
            c"corrupt storage: a header or table word a build never writes, or content that does not match its checksum"
        }
        WC_ERR_INVALID_ARGUMENT => {
            c"invalid argument: a null or misaligned pointer, overlapping arrays, or a bad option"
        }
        WC_ERR_OTHER => c"an error this version of the header has no name for",
        WC_ERR_EMPTY => c"no lights",
        WC_ERR_INVALID_WEIGHT => c"a light's weight or power is NaN, infinite or negative",
        WC_ERR_INVALID_BOUNDS => {
            c"a light's bounds are invalid (NaN or infinite coordinate, min > max, zero or non-finite axis, cosine outside [-1, 1])"
        }
        WC_ERR_ALL_ZERO => c"every light's weight or power is zero",
        _ => c"unknown warpcore error code",
    };
    s.as_ptr()
}

/// The `WC_ERR_*` code of a crate error.
pub(crate) fn code(e: Error) -> i32 {
    match e {
        Error::ZeroSize => WC_ERR_ZERO_SIZE,
        Error::TooLarge => WC_ERR_TOO_LARGE,
        Error::LengthMismatch { .. } => WC_ERR_LENGTH_MISMATCH,
        Error::StorageTooSmall { .. } => WC_ERR_STORAGE_TOO_SMALL,
        Error::InfiniteWeight { .. } => WC_ERR_INFINITE_WEIGHT,
        Error::WrongFormat { .. } => WC_ERR_WRONG_FORMAT,
        Error::UnsupportedVersion { .. } => WC_ERR_UNSUPPORTED_VERSION,
        Error::Corrupt { .. } => WC_ERR_CORRUPT,
        _ => WC_ERR_OTHER,
    }
}

/// `kind` of `wc_envmap_storage_len` and the builds: the hierarchical (MIP-pyramid)
/// distribution, which walks the map's pyramid and keeps 2D strata compact (format tag
/// `"wcHI"`).
pub const WC_ENVMAP_KIND_HIERARCHICAL: u32 = 0;
/// `kind`: the marginal-conditional distribution, a row by its total, then a column within
/// the row (format tag `"wcMC"`).
pub const WC_ENVMAP_KIND_MARGINAL_CONDITIONAL: u32 = 1;

/// The distribution a build makes (a caller's `kind`).
#[derive(Clone, Copy)]
enum Kind {
    Hierarchical,
    MarginalConditional,
}

impl Kind {
    /// `None` for an unknown `kind`.
    fn of(kind: u32) -> Option<Kind> {
        match kind {
            WC_ENVMAP_KIND_HIERARCHICAL => Some(Kind::Hierarchical),
            WC_ENVMAP_KIND_MARGINAL_CONDITIONAL => Some(Kind::MarginalConditional),
            _ => None,
        }
    }

    fn storage_len(self, width: usize, height: usize) -> usize {
        match self {
            Kind::Hierarchical => Hierarchical::storage_len(width, height),
            Kind::MarginalConditional => MarginalConditional::storage_len(width, height),
        }
    }

    fn build(
        self,
        weights: &[f32],
        (w, h): (usize, usize),
        compensation: Compensation,
        storage: &mut [u32],
    ) -> Result<(), Error> {
        match self {
            Kind::Hierarchical => {
                Hierarchical::new_compensated(weights, w, h, compensation, storage).map(drop)
            }
            Kind::MarginalConditional => {
                MarginalConditional::new_compensated(weights, w, h, compensation, storage).map(drop)
            }
        }
    }
}

/// A storage loaded as the distribution its header names (word 0, the format tag).
enum Map<'a> {
    Hierarchical(Hierarchical<'a>),
    MarginalConditional(MarginalConditional<'a>),
}

impl<'a> Map<'a> {
    /// The crate's `from_storage` (or `from_storage_verified`) of the distribution whose tag
    /// word 0 holds. A storage of neither gets the hierarchical loader's error: too small
    /// (fewer than 16 words), else the wrong format.
    fn load(storage: &'a [u32], verified: bool) -> Result<Self, Error> {
        let hierarchical = if verified {
            Hierarchical::from_storage_verified(storage)
        } else {
            Hierarchical::from_storage(storage)
        };
        match hierarchical {
            Err(Error::WrongFormat { .. }) if verified => {
                MarginalConditional::from_storage_verified(storage).map(Map::MarginalConditional)
            }
            Err(Error::WrongFormat { .. }) => {
                MarginalConditional::from_storage(storage).map(Map::MarginalConditional)
            }
            loaded => loaded.map(Map::Hierarchical),
        }
    }

    /// `op` on the loaded distribution.
    fn run<O, const I: usize>(
        &self,
        op: &impl Op<O, I>,
        input: &[[f32; I]],
        out: &mut [O],
    ) -> usize {
        match self {
            Map::Hierarchical(d) => op.call(d, input, out),
            Map::MarginalConditional(d) => op.call(d, input, out),
        }
    }
}

/// One of the sampling functions' slice forms, written once for both distributions: `n`
/// inputs of `I` floats to `n` outputs `O`.
trait Op<O, const I: usize> {
    fn call<D: Distribution>(&self, d: &D, input: &[[f32; I]], out: &mut [O]) -> usize;
}

/// `wc_envmap_sample`.
struct Samples;
/// `wc_envmap_pdf`.
struct Densities;
/// `wc_envmap_sample_direction`.
struct Directions(Layout);
/// `wc_envmap_pdf_direction`.
struct DirectionDensities(Layout);

impl Op<WcEnvSample, 2> for Samples {
    fn call<D: Distribution>(&self, d: &D, u: &[[f32; 2]], out: &mut [WcEnvSample]) -> usize {
        converted(out, |tmp: &mut [Sample]| d.sample_slice(u, tmp))
    }
}

impl Op<f32, 2> for Densities {
    fn call<D: Distribution>(&self, d: &D, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
        d.pdf_slice(uv, out)
    }
}

impl Op<WcEnvDirection, 2> for Directions {
    fn call<D: Distribution>(&self, d: &D, u: &[[f32; 2]], out: &mut [WcEnvDirection]) -> usize {
        converted(out, |tmp: &mut [DirectionSample]| {
            d.sample_direction_slice(self.0, u, tmp)
        })
    }
}

impl Op<f32, 3> for DirectionDensities {
    fn call<D: Distribution>(&self, d: &D, dir: &[[f32; 3]], out: &mut [f32]) -> usize {
        d.pdf_direction_slice(self.0, dir, out)
    }
}

/// Fills `out` (at most a chunk) with the C forms of what `fill` writes into a local buffer.
fn converted<S: Copy + Default, O: From<S>>(
    out: &mut [O],
    fill: impl FnOnce(&mut [S]) -> usize,
) -> usize {
    let mut buf = [S::default(); crate::ffi::CHUNK];
    let tmp = &mut buf[..out.len().min(crate::ffi::CHUNK)];
    let k = fill(tmp);
    for (o, s) in out.iter_mut().zip(tmp.iter().take(k)) {
        *o = O::from(*s);
    }
    k
}

impl From<Sample> for WcEnvSample {
    fn from(s: Sample) -> Self {
        WcEnvSample {
            uv: s.uv,
            pdf: s.pdf,
            texel: s.texel,
        }
    }
}

impl From<DirectionSample> for WcEnvDirection {
    fn from(s: DirectionSample) -> Self {
        WcEnvDirection {
            dir: s.dir,
            pdf: s.pdf,
            uv: s.uv,
            texel: s.texel,
        }
    }
}

/// The sampling functions' common part: `op` from `n` points of `I` floats at `input` to
/// `n` outputs at `out`, over the distribution `storage` holds. Every pointer rule first
/// (`map`'s, and `out` disjoint from the storage, which is read throughout), then the
/// storage's O(1) check; 0, writing nothing, when one fails.
///
/// # Safety
/// As the exported functions: `storage` readable for `storage_len` words, `input` for
/// `I n` floats, `out` writable for `n` outputs.
unsafe fn sampled<O: Copy + Default, const I: usize>(
    storage: *const u32,
    storage_len: usize,
    input: *const f32,
    out: *mut O,
    n: usize,
    op: &impl Op<O, I>,
) -> usize {
    if n == 0 {
        return 0;
    }
    let (Some(src), Some(writes)) = (
        n.checked_mul(I).and_then(|k| span(input, k)),
        span(out.cast_const(), n),
    ) else {
        return 0;
    };
    // In place only where an output is no larger than a point (`map` checks again).
    if overlap(src, writes) && !(src.0 == writes.0 && size_of::<O>() <= I * size_of::<f32>()) {
        return 0;
    }
    // SAFETY: the caller's contract; `slice` checks null, alignment, size and that `out`
    // (which we write) does not overlap the storage (which we read throughout).
    let Some(s) = (unsafe { slice(storage, storage_len, Some(writes)) }) else {
        return 0;
    };
    let Ok(d) = Map::load(s, false) else {
        return 0;
    };
    // SAFETY: the caller's contract; `map` checks null, alignment, size and overlap of
    // `input` and `out` again.
    unsafe {
        map::<f32, O, I, 1>(input, out, n, |input, o| {
            d.run(op, input, o.as_flattened_mut())
        })
    }
}

/// Words of storage `wc_envmap_build` needs for a `width x height` map of distribution
/// `kind` (`WC_ENVMAP_KIND_*`), the 16-word header included: `SIZE_MAX` for an unknown
/// `kind` (whatever the sides), else 0 for a zero side, `SIZE_MAX` when a side exceeds 2^24
/// or the tables would exceed 2^32 words (the cases where the build returns `WC_ERR_ZERO_SIZE`, `WC_ERR_INVALID_ARGUMENT` and
/// `WC_ERR_TOO_LARGE`). Any arguments; reads and writes no memory.
#[unsafe(no_mangle)]
pub extern "C" fn wc_envmap_storage_len(kind: u32, width: u32, height: u32) -> usize {
    Kind::of(kind).map_or(usize::MAX, |k| {
        k.storage_len(width as usize, height as usize)
    })
}

/// Builds the distribution `kind` (`WC_ENVMAP_KIND_HIERARCHICAL` or
/// `WC_ENVMAP_KIND_MARGINAL_CONDITIONAL`) of `weights` (row-major, `width * height` floats;
/// NaN, negatives and `-inf` weigh 0, an all-zero map samples uniformly) into `storage`. The
/// storage's header records the distribution: the other functions read it from there.
/// Returns `WC_OK` (0) or the first failed check, in this order:
///
/// * `WC_ERR_INVALID_ARGUMENT`: `kind` is not one of the two constants;
/// * `WC_ERR_ZERO_SIZE`: `width` or `height` is 0;
/// * `WC_ERR_TOO_LARGE`: a side above 2^24, tables above 2^32 words (`wc_envmap_storage_len`
///   is `SIZE_MAX`), or weights or tables larger than `PTRDIFF_MAX` bytes (32-bit targets);
/// * `WC_ERR_STORAGE_TOO_SMALL`: `storage_len` is below
///   `wc_envmap_storage_len(kind, width, height)`;
/// * `WC_ERR_INVALID_ARGUMENT`: a null or misaligned pointer, or weights overlapping the
///   storage's first `wc_envmap_storage_len(kind, width, height)` words;
/// * `WC_ERR_INFINITE_WEIGHT`: a weight is `+inf`.
///
/// Nothing is written before these checks but the last: on the other errors the storage is
/// untouched; on success and on `WC_ERR_INFINITE_WEIGHT` exactly the first
/// `wc_envmap_storage_len(kind, width, height)` words are written, never more. The storage's
/// bytes are the file format: write them to a file and sample them later, on any machine.
///
/// # Safety
/// `weights` must be readable for `width * height` floats and `storage` writable for
/// `storage_len` words (only when the checks above pass, so a call that returns one of the
/// errors before `WC_ERR_INFINITE_WEIGHT` may pass any pointers).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_build(
    kind: u32,
    weights: *const f32,
    width: u32,
    height: u32,
    storage: *mut u32,
    storage_len: usize,
) -> i32 {
    let Some(k) = Kind::of(kind) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    // SAFETY: the caller's contract above.
    unsafe {
        build(
            k,
            weights,
            width,
            height,
            Compensation::None,
            storage,
            storage_len,
        )
    }
}

/// `wc_envmap_build` with MIS compensation (Karlik et al. 2019; pbrt-v4's
/// `compensatedDistribution`, Mitsuba 3's `mis_compensation`): the tables, and every pdf
/// the distribution reports, are those of `max(0, w - fraction * average)`.
/// `compensation` is `WC_ENVMAP_COMPENSATION_NONE` (then this is `wc_envmap_build`),
/// `WC_ENVMAP_COMPENSATION_UNIFORM` (equal-area maps: the mean weight) or
/// `WC_ENVMAP_COMPENSATION_EQUIRECT` (equirect weights made by
/// `wc_envmap_equirect_solid_angle_weights`: the radiance's solid-angle average, times each
/// row's `sin(theta)`). `fraction` (1 is pbrt's and Mitsuba's choice) may be any float: NaN,
/// zero and negative mean no compensation. When compensation would remove every weight (a
/// constant map, `fraction = +inf`, an all-zero map) the build falls back to the weights as
/// given, bit for bit `wc_envmap_build`.
///
/// Returns `WC_OK` or the first failed check: `WC_ERR_INVALID_ARGUMENT` if `kind` or
/// `compensation` is not one of its constants (checked first: nothing is read or written),
/// then exactly the checks, order and writes of `wc_envmap_build`.
///
/// # Safety
/// As `wc_envmap_build`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_build_compensated(
    kind: u32,
    weights: *const f32,
    width: u32,
    height: u32,
    compensation: u32,
    fraction: f32,
    storage: *mut u32,
    storage_len: usize,
) -> i32 {
    let (Some(k), Some(c)) = (Kind::of(kind), compensation_of(compensation, fraction)) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    // SAFETY: the caller's contract above.
    unsafe { build(k, weights, width, height, c, storage, storage_len) }
}

/// Checks a storage's header in O(1) and names the distribution it holds (the crate's
/// `from_storage`): format tag, version, sizes and lengths. Returns `WC_OK` or the first
/// failed check, in this order: `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` and `storage`
/// null or misaligned, or `storage_len` words larger than `PTRDIFF_MAX` bytes),
/// `WC_ERR_STORAGE_TOO_SMALL` (fewer than 16 words), `WC_ERR_WRONG_FORMAT` (word 0 is the tag
/// of neither distribution), `WC_ERR_UNSUPPORTED_VERSION` (an older format: rebuild),
/// `WC_ERR_CORRUPT` (a size, length or reserved word a build never writes),
/// `WC_ERR_STORAGE_TOO_SMALL` (fewer words than the header says). Sampling a storage that
/// passes is safe whatever its table words hold (samples stay in the map); the sampling
/// functions run this check on every call. Reads only.
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_from_storage(storage: *const u32, storage_len: usize) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { check(storage, storage_len, false) }
}

/// `wc_envmap_from_storage` (the same codes, in the same order) plus one pass over every
/// table word (the crate's `from_storage_verified`), rejecting (`WC_ERR_CORRUPT`) tables that
/// break the format's invariants or do not match the content checksum (header word 8): every
/// single-bit flip of a storage is caught. For loaders of files. Time proportional to the
/// storage. Reads only.
///
/// # Safety
/// `storage` must be readable for `storage_len` words.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_from_storage_verified(
    storage: *const u32,
    storage_len: usize,
) -> i32 {
    // SAFETY: the caller's contract above.
    unsafe { check(storage, storage_len, true) }
}

/// Draws `n` samples from a built (or loaded) storage, of the distribution its header names:
/// texels in proportion to their weight, a uniform point inside each. `u` holds `2n` floats
/// (`u[2i]` picks the column, `u[2i+1]` the row; any values, clamped to `[0, 1)`). Returns
/// `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte
/// size overflows, an `out` that overlaps `u` (`out == u` too: a sample is larger than a
/// point) or the storage, or a storage that fails `wc_envmap_from_storage`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `u` for `2n` floats, and `out`
/// writable for `n` samples.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_sample(
    storage: *const u32,
    storage_len: usize,
    u: *const f32,
    out: *mut WcEnvSample,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above.
    unsafe { sampled(storage, storage_len, u, out, n, &Samples) }
}

/// Densities at `n` points `uv` (`2n` floats) with respect to area on `[0, 1]^2`: the pdf of
/// the texel holding each point (0 on zero-weight texels), equal bit for bit to the `pdf` a
/// sample at that point reports. Returns `n`, or 0 (writing nothing) for `n == 0`, a null or
/// misaligned pointer, a count whose byte size overflows, an `out` that overlaps the storage
/// or overlaps `uv` other than exactly in place (`out == uv`: density `i` overwrites float
/// `i` after point `i / 2` was read), or a storage that fails `wc_envmap_from_storage`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `uv` for `2n` floats, and `out`
/// writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_pdf(
    storage: *const u32,
    storage_len: usize,
    uv: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above.
    unsafe { sampled(storage, storage_len, uv, out, n, &Densities) }
}

/// Draws `n` samples as directions with their density per steradian, in one call: the
/// samples of `wc_envmap_sample`, each `uv` mapped onto the sphere by `layout`
/// (`WC_ENVMAP_LAYOUT_EQUIRECT`: `wc_sphere_equirect`, density
/// `pdf / (2 pi^2 sin(pi v))` with the point's own `v`, 0 exactly at the pole;
/// `WC_ENVMAP_LAYOUT_EQUAL_AREA`: `wc_sphere_equal_area`, density `pdf / (4 pi)`). `u` holds
/// `2n` floats (any values, clamped to `[0, 1)`); `out` receives `n` `WcEnvDirection`s.
/// Returns `n`, or 0 (writing nothing) where `wc_envmap_sample` returns 0 and for an unknown
/// `layout`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `u` for `2n` floats, and `out`
/// writable for `n` directions.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_sample_direction(
    storage: *const u32,
    storage_len: usize,
    layout: u32,
    u: *const f32,
    out: *mut WcEnvDirection,
    n: usize,
) -> usize {
    let Some(layout) = layout_of(layout) else {
        return 0;
    };
    // SAFETY: the caller's contract above.
    unsafe { sampled(storage, storage_len, u, out, n, &Directions(layout)) }
}

/// Densities per steradian of `n` directions `dir` (`3n` floats, any length; the MIS weight
/// of a direction found by BSDF sampling): each direction mapped to the unit square by
/// `layout`'s inverse (`wc_sphere_equirect_inverse` or `wc_sphere_equal_area_inverse`), the
/// density of `wc_envmap_pdf` there converted to solid angle at the direction. For a
/// direction of `wc_envmap_sample_direction` it equals the sample's `pdf` to a few ulp
/// (except within an ulp of a texel edge). Returns `n`, or 0 (writing nothing) where
/// `wc_envmap_pdf` returns 0 (`out == dir` is in place: density `i` overwrites float `i` after
/// direction `i / 3` was read) and for an unknown `layout`.
///
/// # Safety
/// `storage` must be readable for `storage_len` words, `dir` for `3n` floats, and `out`
/// writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_pdf_direction(
    storage: *const u32,
    storage_len: usize,
    layout: u32,
    dir: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    let Some(layout) = layout_of(layout) else {
        return 0;
    };
    // SAFETY: the caller's contract above.
    unsafe {
        sampled(
            storage,
            storage_len,
            dir,
            out,
            n,
            &DirectionDensities(layout),
        )
    }
}

/// # Safety
/// As `wc_envmap_build`, with `kind` and `compensation` already checked.
unsafe fn build(
    kind: Kind,
    weights: *const f32,
    width: u32,
    height: u32,
    compensation: Compensation,
    storage: *mut u32,
    storage_len: usize,
) -> i32 {
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 {
        return WC_ERR_ZERO_SIZE;
    }
    let needed = kind.storage_len(w, h);
    if needed == usize::MAX {
        return WC_ERR_TOO_LARGE;
    }
    // Both sides are at most 2^24 here, yet `w * h` overflows a 32-bit `size_t`: checked, as
    // are the byte sizes of both arrays (no C array exceeds `PTRDIFF_MAX` bytes).
    let texels = match w.checked_mul(h) {
        Some(t) if fits::<f32>(t) && fits::<u32>(needed) => t,
        _ => return WC_ERR_TOO_LARGE,
    };
    if storage_len < needed {
        return WC_ERR_STORAGE_TOO_SMALL;
    }
    // Every check but the arrays' is done: from here on the call writes the storage.
    // SAFETY: the caller's contract: the weights readable for `texels` floats and unchanged
    // during the call, the storage writable for `storage_len >= needed` words; a zero word is
    // a valid `u32`. `read_and_fill` checks null, alignment, size and overlap first.
    let Some((weights, storage)) = (unsafe { read_and_fill(weights, texels, storage, needed) })
    else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    match kind.build(weights, (w, h), compensation, storage) {
        Ok(()) => WC_OK,
        Err(e) => code(e),
    }
}

/// The compensation a C caller asked for, `None` for an unknown `compensation`.
fn compensation_of(compensation: u32, fraction: f32) -> Option<Compensation> {
    match compensation {
        WC_ENVMAP_COMPENSATION_NONE => Some(Compensation::None),
        WC_ENVMAP_COMPENSATION_UNIFORM => Some(Compensation::Uniform(fraction)),
        WC_ENVMAP_COMPENSATION_EQUIRECT => Some(Compensation::Equirect(fraction)),
        _ => None,
    }
}

/// # Safety
/// `storage` readable for `storage_len` words, unchanged during the call.
unsafe fn check(storage: *const u32, storage_len: usize, verified: bool) -> i32 {
    // SAFETY: the caller's contract; `slice` checks null (with `storage_len > 0`), alignment
    // and that `storage_len` words fit `PTRDIFF_MAX` bytes.
    let Some(s) = (unsafe { slice(storage, storage_len, None) }) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    match Map::load(s, verified) {
        Ok(_) => WC_OK,
        Err(e) => code(e),
    }
}

/// Rec. 709 luminance of `n` linear RGB texels (`3n` floats) as `n` weights:
/// `0.2126 R + 0.7152 G + 0.0722 B` (in that order, without FMA) where positive, else `+0.0`:
/// NaN (a NaN channel, or infinite channels of opposite signs) and negatives weigh 0, as in
/// the builds; `+inf` stays `+inf` (a build then returns `WC_ERR_INFINITE_WEIGHT`). Never NaN
/// or negative; bit-identical to the Rust crate's `image::luminance`. Returns `n`, or 0
/// (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte size
/// overflows, or overlapping arrays other than exactly in place (`rgb == out`).
///
/// # Safety
/// `rgb` must be readable for `3n` floats and `out` writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_luminance(rgb: *const f32, out: *mut f32, n: usize) -> usize {
    // SAFETY: the caller's contract above; `map` checks null, alignment, size and overlap.
    unsafe {
        map::<f32, f32, 3, 1>(rgb, out, n, |rgb, o| {
            image::luminance_slice(rgb, o.as_flattened_mut())
        })
    }
}

/// Multiplies row `r` of an equirect (lat-long) weight map (in place, `width * height` floats) by
/// `sin(pi (r + 1/2) / height)`, its solid-angle factor. Returns `WC_OK` or the first failed
/// check, in this order: `WC_ERR_ZERO_SIZE` (`width` or `height` is 0), `WC_ERR_TOO_LARGE`
/// (`width * height` floats larger than `PTRDIFF_MAX` bytes: no such array exists),
/// `WC_ERR_INVALID_ARGUMENT` (a null or misaligned pointer). Writes nothing on error.
///
/// # Safety
/// `weights` must be readable and writable for `width * height` floats (only when the checks
/// above pass).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_equirect_solid_angle_weights(
    weights: *mut f32,
    width: u32,
    height: u32,
) -> i32 {
    let (w, h) = (width as usize, height as usize);
    if w == 0 || h == 0 {
        return WC_ERR_ZERO_SIZE;
    }
    let count = match w.checked_mul(h) {
        Some(c) if fits::<f32>(c) => c,
        _ => return WC_ERR_TOO_LARGE,
    };
    if span(weights.cast_const(), count).is_none() {
        return WC_ERR_INVALID_ARGUMENT;
    }
    // SAFETY: readable and writable for `count` initialized floats (the caller's contract);
    // non-null, aligned and of valid size (checked by `span`).
    let weights = unsafe { core::slice::from_raw_parts_mut(weights, count) };
    match image::equirect_solid_angle_weights(weights, w, h) {
        Ok(()) => WC_OK,
        Err(e) => code(e),
    }
}

/// Equirect (lat-long) density conversion: `n` densities over the square (`pdf`) at rows `v` (`n`
/// floats) to densities per steradian, `pdf / (2 pi^2 sin(pi v))` (0 at the poles). Returns
/// `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte
/// size overflows, an `out` overlapping `v`, or an `out` overlapping `pdf` other than
/// exactly in place (`pdf == out`).
///
/// # Safety
/// `pdf` and `v` must be readable for `n` floats and `out` writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_equirect_pdf_to_solid_angle(
    pdf: *const f32,
    v: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `zip_map` checks null, alignment, size and
    // overlap.
    unsafe { zip_map(pdf, v, out, n, image::equirect_pdf_to_solid_angle) }
}

/// Resamples an equirect (lat-long) image (`src_width x src_height` texels of `channels` floats, 1 to 4)
/// onto the `size x size` equal-area octahedral square (`dst`, `size * size * channels`
/// floats), each output texel the average of `supersample^2` stratified point samples of the
/// source (nearest texel; NaN and negative channels count as 0). Returns `WC_OK` or the first
/// failed check, in this order:
///
/// * `WC_ERR_ZERO_SIZE`: `src_width`, `src_height`, `size` or `supersample` is 0;
/// * `WC_ERR_INVALID_ARGUMENT`: `channels` is not 1, 2, 3 or 4;
/// * `WC_ERR_TOO_LARGE`: `src_width`, `src_height` or `size` above 2^24, `supersample` above
///   64, or `src` or `dst` larger than `PTRDIFF_MAX` bytes (32-bit targets);
/// * `WC_ERR_INVALID_ARGUMENT`: a null or misaligned pointer, or `src` and `dst` overlapping.
///
/// Nothing is read or written before these checks pass, so on error `dst` is untouched; on
/// success exactly `size * size * channels` floats are written.
///
/// # Safety
/// `src` must be readable for `src_width * src_height * channels` floats and `dst` writable
/// for `size * size * channels` floats (only when the checks above pass).
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_envmap_equirect_to_equal_area(
    src: *const f32,
    src_width: u32,
    src_height: u32,
    channels: u32,
    dst: *mut f32,
    size: u32,
    supersample: u32,
) -> i32 {
    let (sw, sh, c) = (src_width as usize, src_height as usize, channels as usize);
    let (n, ss) = (size as usize, supersample as usize);
    if sw == 0 || sh == 0 || n == 0 || ss == 0 {
        return WC_ERR_ZERO_SIZE;
    }
    if !(1..=4).contains(&c) {
        return WC_ERR_INVALID_ARGUMENT;
    }
    // The core's own size checks, first: it must not fail after `dst` is zeroed below.
    if sw > MAX_SIDE || sh > MAX_SIDE || n > MAX_SIDE || ss > image::MAX_SUPERSAMPLE {
        return WC_ERR_TOO_LARGE;
    }
    let (src_len, dst_len) = match (
        sw.checked_mul(sh).and_then(|x| x.checked_mul(c)),
        n.checked_mul(n).and_then(|x| x.checked_mul(c)),
    ) {
        (Some(a), Some(b)) if fits::<f32>(a) && fits::<f32>(b) => (a, b),
        _ => return WC_ERR_TOO_LARGE,
    };
    // SAFETY: the caller's contract: `src` readable for `src_len` floats and unchanged during
    // the call, `dst` writable for `dst_len` floats; a zero float is valid. `read_and_fill`
    // checks null, alignment, size and overlap first. Every other check is done (the core
    // repeats them and cannot fail now).
    let Some((src, dst)) = (unsafe { read_and_fill(src, src_len, dst, dst_len) }) else {
        return WC_ERR_INVALID_ARGUMENT;
    };
    fn run<const C: usize>(
        s: &[f32],
        w: usize,
        h: usize,
        d: &mut [f32],
        n: usize,
        ss: usize,
    ) -> i32 {
        let (s, _) = s.as_chunks::<C>();
        let (d, _) = d.as_chunks_mut::<C>();
        match image::equirect_to_equal_area(s, w, h, d, n, ss) {
            Ok(()) => WC_OK,
            Err(e) => code(e),
        }
    }
    match c {
        1 => run::<1>(src, sw, sh, dst, n, ss),
        2 => run::<2>(src, sw, sh, dst, n, ss),
        3 => run::<3>(src, sw, sh, dst, n, ss),
        _ => run::<4>(src, sw, sh, dst, n, ss),
    }
}
