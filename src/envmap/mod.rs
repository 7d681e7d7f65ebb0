//! Environment-map importance sampling: draw texels of an image in proportion to their weight
//! (usually luminance), heap-free, with caller-owned storage.
//!
//! | distribution | build | sample | keeps | source |
//! |---|---|---|---|---|
//! | [`MarginalConditional`] | row CDF + one CDF per row, 0.31 fixed point, from `f64` sums; 4 bytes per texel | two branch-free binary searches | strata along each axis | pbrt-v4 `PiecewiseConstant2D`, Mitsuba 3 `DiscreteDistribution2D` |
//! | [`Hierarchical`] | a centred MIP pyramid of 0.31 split fractions, from pairwise sums, in 64-byte two-level blocks; about 4.3 bytes per padded texel | one 2x2 split per level, exact integer interval arithmetic on the sample | compact 2D strata | Mitsuba 3 `Hierarchical2D`; McCool and Harwood 1997, "Probability Trees"; Clarberg et al. 2005, "Wavelet Importance Sampling" |
//!
//! Both take a row-major `width x height` array of weights — a piecewise-constant density on
//! the unit square, texel `(column, row)` covering `[column/width, (column+1)/width) x
//! [row/height, (row+1)/height)`, so row 0 is `v` in `[0, 1/height)` — and a caller-owned
//! `&mut [Word]` of at least `storage_len(width, height)` words. They never allocate; building
//! writes the tables into the storage, sampling only reads it.
//!
//! ```
//! use warpcore::envmap::{Hierarchical, MarginalConditional, Word};
//!
//! let (width, height) = (4, 2);
//! let weights = [1.0, 2.0, 0.0, 1.0, 4.0, 0.0, 0.5, 0.5];
//! let mut storage = vec![0 as Word; Hierarchical::storage_len(width, height)];
//! let map = Hierarchical::new(&weights, width, height, &mut storage)?;
//! let s = map.sample([0.3, 0.8]);
//! assert_eq!(s.pdf, map.pdf(s.uv)); // the pdf of the texel actually chosen
//! assert_ne!(s.texel, [2, 0]); // a zero-weight texel is never returned
//!
//! let mut storage = vec![0 as Word; MarginalConditional::storage_len(width, height)];
//! let map = MarginalConditional::new(&weights, width, height, &mut storage)?;
//! let s = map.sample([0.3, 0.8]);
//! assert!((s.pdf - 8.0 * weights[(s.texel[1] * 4 + s.texel[0]) as usize] / 9.0).abs() < 1e-5);
//! # Ok::<(), warpcore::envmap::Error>(())
//! ```
//!
//! Both implement the sealed trait [`Distribution`] (`sample`, `pdf` and their `_x8`, `_x16`
//! and `_slice` forms), so a renderer can be generic over them; the same methods are inherent.
//! [`Compensation`] builds either from MIS-compensated weights (`new_compensated`).
//!
//! # What every distribution here promises
//!
//! * **The pdf is that of the texel actually chosen**, computed from the same quantized tables
//!   that drive the choice, so it matches the empirical frequency of the texel (the tests
//!   compare both), and `pdf(sample(u).uv) == sample(u).pdf` bit for bit. It is a density
//!   with respect to area on `[0, 1]^2`: `P(texel) * width * height`. See [`image`]'s
//!   conversions to solid angle.
//! * **Never a zero-weight texel**, for any input `u`. Conversely, quantization never rounds a
//!   positive texel away in marginal-conditional (it gets at least one fixed-point unit, so it
//!   is oversampled instead); hierarchical keeps each positive child's split fraction strictly
//!   inside `(0, 1)`, but a texel fainter than its 30-bit intervals resolve (probability below
//!   about `2^-30` per axis) can be unreachable — its pdf then says 0, consistently.
//! * **`u` near 1 never rounds onto the next texel**: the texel is found by exact integer
//!   arithmetic on fixed-point keys (`floor(u * 2^31)` or `2^30`, exact), never by
//!   `floor(u * n)` in floating point.
//! * **Every `uv` lies inside its texel exactly**: `column <= uv[0] * width < column + 1` in
//!   exact arithmetic (likewise for rows), and `uv` is in `[0, 1)^2`. The position inside the
//!   texel is uniform (it reuses the sample's remaining bits) and clamped, by one `f32` ulp
//!   at most, to the texel's exact bounds.
//! * **Bit-identical widths**: `sample`, `sample_x8` and `sample_slice` (and the `pdf` forms)
//!   run one generic body.
//! * **Total**: `u` goes through the crate's forward rule (NaN, negatives -> 0; `>= 1`, `+inf`
//!   -> `1 - 2^-24`); `pdf(uv)` clamps `uv` the same way. Nothing panics, no pdf is NaN.
//!
//! # Bad and stiff input
//!
//! Real HDR maps contain zeros, small negative texels (lossy-compression artifacts), NaN and
//! infinities, and dynamic ranges beyond `10^9 : 1`.
//!
//! * NaN, `-0.0`, negative values and `-inf` weigh **0** (they are never sampled).
//! * `+inf` is an error, [`Error::InfiniteWeight`] with the texel's index: an infinite weight
//!   cannot be normalized, and sampling only that texel would silently drop the rest.
//! * An all-zero map (after the rule above) samples **uniformly**: every texel gets an equal
//!   share of the tables' fixed-point intervals up to their rounding, so its pdf is exactly 1
//!   when `width` and `height` are powers of two, and otherwise within
//!   `2^-22 + (width + height) 2^-29` of 1 (measured over every size up to 128 x 128 and 300
//!   sizes up to 5000 x 3000; for example 0.99999994 on the first row of a 1 x 13 hierarchical map).
//! * Any finite weights work, subnormals and `f32::MAX` included: sums are taken in `f64`
//!   (marginal-conditional) or in a rescaled `f32` pyramid (hierarchical), never overflow.
//! * Maps of any size from `1 x 1` to `MAX_SIDE x MAX_SIDE` (that fit the 32-bit table
//!   indices, see [`Error::TooLarge`]), square or not, powers of two or not.
//!
//! # Storage format: build once, load later
//!
//! A built storage is self-describing, so an asset pipeline can build the tables once, write
//! the words to a file, and a renderer can read them back and sample without the weights:
//!
//! ```
//! use warpcore::envmap::{Hierarchical, Word};
//!
//! let weights = [1.0, 2.0, 0.0, 1.0, 4.0, 0.0, 0.5, 0.5];
//! let mut storage = vec![0 as Word; Hierarchical::storage_len(4, 2)];
//! let map = Hierarchical::new(&weights, 4, 2, &mut storage)?;
//! let built = map.sample([0.3, 0.8]);
//!
//! // The bytes to write (while the map is in use): its storage's in-memory bytes,
//! // little-endian on every target.
//! let file: Vec<u8> = bytemuck::cast_slice(map.storage()).to_vec();
//! // ... later, on any machine: read the bytes back into words and validate them.
//! let words: Vec<Word> = file.chunks_exact(4).map(|b| Word::from_ne_bytes(b.try_into().unwrap())).collect();
//! let map = Hierarchical::from_storage(&words)?; // O(1): the header only
//! assert_eq!(map.sample([0.3, 0.8]), built);
//! let map = Hierarchical::from_storage_verified(&words)?; // O(n): every word, checksum
//! assert_eq!(map.sample([0.3, 0.8]), built);
//! # Ok::<(), warpcore::envmap::Error>(())
//! ```
//!
//! Layout, in 32-bit words:
//!
//! | words | contents |
//! |---|---|
//! | 0 | format tag: the bytes `wcMC` ([`MarginalConditional`]) or `wcHI` ([`Hierarchical`]) |
//! | 1 | format version, [`FORMAT_VERSION`] |
//! | 2, 3 | width, height |
//! | 4..8 | the lengths in words of the four regions that follow, in order: marginal-conditional: row CDF (`height + 1`), row CDFs (`(width + 1) height`), column edges (`width + 1`), row edges (`height + 1`); hierarchical: padding (always 0 since version 3), blocks (`16 * blocks`), column edges, row edges |
//! | 8 | the content checksum ([`CHECKSUM_WORD`]) of every other word of the storage |
//! | 9..16 | reserved, 0 |
//! | 16.. | the tables |
//!
//! **Byte order.** The storage's bytes in memory are little-endian on every target (big-endian
//! targets byte-swap the words once after building and on every read), so the memory image
//! — `bytemuck::cast_slice::<Word, u8>` in Rust, `fwrite` of the `uint32_t` array in C — is
//! the file format, and a file written on one machine loads on any other. Words `new` does not
//! need (reserved and unused slots) are written as 0, so **the bytes are a function of the
//! weights alone**: the same map built from Rust, C or JavaScript, into buffers at any
//! address, gives the same bytes (a cache can key them by hash). The tables start at byte 64,
//! so [`Hierarchical`]'s 64-byte blocks sit on cache lines exactly when the storage is 64-byte
//! aligned (C: `aligned_alloc(64, ...)`); at any other alignment sampling gives the same bits,
//! with blocks that may straddle two lines (format version 2 aligned them itself, recording
//! the buffer's address in the bytes).
//!
//! **Validation.** `from_storage` is O(1): it checks the tag, the version, the sizes and that
//! the lengths agree with them and with `storage.len()`, and reports [`Error::WrongFormat`],
//! [`Error::UnsupportedVersion`], [`Error::Corrupt`] or [`Error::StorageTooSmall`]. It does not
//! read the tables, and it does not need to: **sampling a storage that passed it never panics
//! and never leaves the map, whatever its table words hold** — texels are in `0..width` x
//! `0..height`, `uv` in `[0, 1)^2`, pdfs finite and nonnegative (garbage tables give garbage
//! but valid samples). `from_storage_verified` adds one pass over every table word and
//! rejects tables that break the format's invariants (CDFs that are not monotone from 0 to
//! `2^31`, split fractions above 1, reachable padding, nonzero unused words, wrong texel
//! edges), then compares the **content checksum** in header word [`CHECKSUM_WORD`] with one
//! computed over every other word. The checksum (eight interleaved chains of a bijective
//! 32-bit mixer, see `from_storage_verified`) changes whenever any single word changes, so
//! **every single-bit flip is caught, by construction** (tested exhaustively on small maps);
//! other corruptions slip through with probability about `2^-32`. Use it for files; the
//! O(1) `from_storage` is for tables already in memory.

mod compensation;
mod direction;
mod distribution;
mod edges;
mod hierarchical;
pub mod image;
mod marginal;
mod slices;

pub use compensation::Compensation;
use compensation::Compensator;
pub use direction::{DirectionSample, Layout};
pub use distribution::Distribution;
use distribution::inherent_methods;
pub use hierarchical::Hierarchical;
pub use marginal::MarginalConditional;

use crate::lanes::{Lane, UintLane, unit_interval};
use crate::storage::{from_storage_order, header, to_storage_order};
use core::fmt;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// The storage element: the caller allocates `storage_len(width, height)` of them (any
/// alignment, any initial contents) and lends them to `new`.
pub type Word = u32;

/// Largest accepted width or height: `2^24`, so texel indices and edges are exact in `f32`.
pub const MAX_SIDE: usize = 1 << 24;

/// Words of the header at the start of every storage (included in `storage_len`): 64 bytes,
/// so that the tables after it start on a cache line whenever the storage does.
pub const HEADER_WORDS: usize = 16;

/// The header word holding the content checksum (see the [module docs](self)):
/// [`Error::Corrupt`] names this word when the content does not match it.
pub const CHECKSUM_WORD: usize = 8;

/// The storage format version this build writes (word 1 of the header) and reads: 3 since
/// the header holds a content checksum and the layout no longer depends on the buffer's
/// address. Older storages are refused with [`Error::UnsupportedVersion`], never misread
/// (version 2 had no checksum and recorded the buffer's alignment; version 1 also padded
/// hierarchical pyramids in the corner): rebuild them from the weights.
pub const FORMAT_VERSION: u32 = 3;

/// One sample of an environment-map distribution. `Sample::default()` (all zeros) fills the
/// output slices of the `_slice` forms: `vec![Sample::default(); n]`.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sample {
    /// The point, in `[0, 1)^2`, inside `texel`.
    pub uv: [f32; 2],
    /// Density with respect to area on `[0, 1]^2` at `uv` (constant over the texel).
    pub pdf: f32,
    /// `[column, row]` of the texel the point lies in.
    pub texel: [u32; 2],
}

/// A sample type of `$n` SIMD lanes (`$Words`, `$words` in words), what `$method` returns.
macro_rules! sample_lanes {
    ($name:ident, $f:ident, $u:ident, $n:literal, $Words:literal, $words:literal, $method:literal) => {
        #[doc = concat!($Words, " samples in SIMD lanes (what `", $method, "` returns). ")]
        #[doc = "Lane `j` equals the scalar `sample` of lane `j` of the input, bit for bit."]
        #[derive(Clone, Copy, Debug)]
        pub struct $name {
            #[doc = concat!("`[u, v]` of the ", $words, " points.")]
            pub uv: [$f; 2],
            #[doc = concat!("The ", $words, " densities.")]
            pub pdf: $f,
            #[doc = concat!("`[column, row]` of the ", $words, " texels.")]
            pub texel: [$u; 2],
        }

        impl $name {
            #[doc = concat!("The ", $words, " samples as an array of [`Sample`]s.")]
            #[inline]
            pub fn to_array(&self) -> [Sample; $n] {
                let [u, v, p] = [self.uv[0], self.uv[1], self.pdf].map(|x| x.to_array());
                samples_of(u, v, p, self.texel.map(|t| t.to_array()))
            }
        }
    };
}

sample_lanes!(SampleX8, f32x8, u32x8, 8, "Eight", "eight", "sample_x8");
sample_lanes!(
    SampleX16,
    f32x16,
    u32x16,
    16,
    "Sixteen",
    "sixteen",
    "sample_x16"
);

/// Why a distribution could not be built.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// `width` or `height` is zero.
    ZeroSize,
    /// A side exceeds [`MAX_SIDE`], or the tables would exceed `2^32` words (their 32-bit
    /// indices); `storage_len` returns `usize::MAX` for such sizes.
    TooLarge,
    /// `weights.len()` is not `width * height`.
    LengthMismatch {
        /// `width * height`.
        expected: usize,
        /// `weights.len()`.
        got: usize,
    },
    /// The storage is shorter than `storage_len(width, height)`.
    StorageTooSmall {
        /// `storage_len(width, height)`.
        needed: usize,
        /// `storage.len()`.
        got: usize,
    },
    /// `weights[index]` is `+inf`.
    InfiniteWeight {
        /// Row-major index of the first infinite weight.
        index: usize,
    },
    /// `from_storage`: word 0 is not this distribution's format tag — the other
    /// distribution's storage, data that is not a warpcore table, or a byte-swapped copy.
    WrongFormat {
        /// Word 0 of the storage.
        found: u32,
    },
    /// `from_storage`: the format version (word 1) is not [`FORMAT_VERSION`].
    UnsupportedVersion {
        /// Word 1 of the storage.
        found: u32,
    },
    /// `from_storage`: storage word `word` holds a value `new` never writes there — a size of
    /// zero or above [`MAX_SIDE`], a length that disagrees with the sizes, a nonzero reserved
    /// header word, or (only `from_storage_verified` reads the tables) a table word that
    /// breaks the format's invariants, or content that does not match the checksum (then
    /// `word` is [`CHECKSUM_WORD`]). A storage too short for its header's sizes is
    /// [`Error::StorageTooSmall`] instead.
    Corrupt {
        /// Index of the first offending word in the storage.
        word: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::ZeroSize => write!(f, "environment map has zero width or height"),
            Error::TooLarge => write!(f, "environment map too large for 32-bit table indices"),
            Error::LengthMismatch { expected, got } => {
                write!(f, "weights hold {got} values, width * height is {expected}")
            }
            Error::StorageTooSmall { needed, got } => {
                write!(f, "storage holds {got} words, {needed} needed")
            }
            Error::InfiniteWeight { index } => write!(f, "weight {index} is +inf"),
            Error::WrongFormat { found } => {
                write!(
                    f,
                    "storage format tag {found:#010x} is not this distribution's"
                )
            }
            Error::UnsupportedVersion { found } if found < FORMAT_VERSION => write!(
                f,
                "storage format version {found} was written by an older warpcore (version 1: \
                 hierarchical pyramids padded in the corner; version 2: no content checksum); \
                 this build reads version {FORMAT_VERSION}: rebuild the tables from the weights"
            ),
            Error::UnsupportedVersion { found } => {
                write!(
                    f,
                    "storage format version {found} (this build reads {FORMAT_VERSION})"
                )
            }
            Error::Corrupt {
                word: CHECKSUM_WORD,
            } => write!(
                f,
                "storage content does not match its checksum (header word {CHECKSUM_WORD}): \
                 the file was altered after it was built"
            ),
            Error::Corrupt { word } => write!(f, "storage word {word} is corrupt"),
        }
    }
}

impl core::error::Error for Error {}

crate::storage::from_header_fault!(Error);

// ---------------------------------------------------------------------------------------
// Shared by both distributions.

/// The weight rule: `+inf` is reported by the caller before this; positive finite values pass,
/// everything else (NaN, zeros, negatives, `-inf`) weighs 0.
#[inline(always)]
fn clean(w: f32) -> f32 {
    if w > 0.0 { w } else { 0.0 }
}

/// [`Error::LengthMismatch`] unless `len` is `width * height` (saturating: no slice has the
/// length of a product that overflows).
fn check_len(len: usize, width: usize, height: usize) -> Result<(), Error> {
    let expected = width.saturating_mul(height);
    if len != expected {
        return Err(Error::LengthMismatch { expected, got: len });
    }
    Ok(())
}

/// Checks the arguments common to both `new`s and returns `width * height`.
fn check_size(weights: &[f32], width: usize, height: usize, needed: usize) -> Result<(), Error> {
    if width == 0 || height == 0 {
        return Err(Error::ZeroSize);
    }
    if needed == usize::MAX {
        return Err(Error::TooLarge);
    }
    // Both sides are at most 2^24 here (checked by `storage_len`), so this cannot overflow.
    check_len(weights.len(), width, height)?;
    Ok(())
}

/// `needed` words if both sides are in `1..=MAX_SIDE` and the total fits 32-bit indices,
/// otherwise `usize::MAX` (`0` for a zero side).
fn checked_len(width: usize, height: usize, words: impl FnOnce(u64, u64) -> u64) -> usize {
    if width == 0 || height == 0 {
        return 0;
    }
    if width > MAX_SIDE || height > MAX_SIDE {
        return usize::MAX;
    }
    let n = words(width as u64, height as u64);
    if n > u64::from(u32::MAX) {
        return usize::MAX;
    }
    usize::try_from(n).unwrap_or(usize::MAX)
}

/// The first `needed` words of `storage`, or [`Error::StorageTooSmall`].
fn take(storage: &mut [Word], needed: usize) -> Result<&mut [Word], Error> {
    let got = storage.len();
    storage
        .get_mut(..needed)
        .ok_or(Error::StorageTooSmall { needed, got })
}

/// Splits `s` into consecutive pieces of the given lengths (the caller sized `s` for them).
fn carve<const K: usize>(mut s: &mut [Word], lens: [usize; K]) -> Option<[&mut [Word]; K]> {
    let mut out: [&mut [Word]; K] = core::array::from_fn(|_| Default::default());
    for (o, &n) in out.iter_mut().zip(&lens) {
        let (head, tail) = core::mem::take(&mut s).split_at_mut_checked(n)?;
        *o = head;
        s = tail;
    }
    Some(out)
}

/// [`carve`] for shared slices, as the one-word rows the lane gathers read.
fn carve_ref<const K: usize>(mut s: &[Word], lens: [usize; K]) -> Option<[&[[u32; 1]]; K]> {
    let mut out: [&[[u32; 1]]; K] = [&[]; K];
    for (o, &n) in out.iter_mut().zip(&lens) {
        let (head, tail) = s.split_at_checked(n)?;
        *o = head.as_chunks::<1>().0;
        s = tail;
    }
    Some(out)
}

// ---------------------------------------------------------------------------------------
// The storage header and byte order.

/// The format tag of a distribution: four ASCII bytes, read as a little-endian word.
const fn tag(bytes: [u8; 4]) -> u32 {
    u32::from_le_bytes(bytes)
}

/// Writes the header: tag, version, sizes and the four region lengths, then zeros (the
/// checksum's place and the reserved words). Native words: the builder's final
/// [`to_storage_order`] pass makes them little-endian, and [`seal`] writes the checksum.
fn write_header(header: &mut [Word], tag: u32, width: usize, height: usize, lens: [usize; 4]) {
    let sizes = [tag, FORMAT_VERSION, width as u32, height as u32];
    header.fill(0);
    for (h, v) in header
        .iter_mut()
        .zip(sizes.into_iter().chain(lens.map(|n| n as u32)))
    {
        *h = v;
    }
}

/// Writes the checksum of a freshly built storage (already in storage byte order).
fn seal(storage: &mut [Word]) {
    crate::storage::seal(storage, CHECKSUM_WORD);
}

/// [`Error::Corrupt`] naming [`CHECKSUM_WORD`] unless the first `needed` words match their
/// checksum (what `from_storage_verified` checks last, after the tables' invariants).
fn check_sum(storage: &[Word], needed: usize) -> Result<(), Error> {
    let s = storage.get(..needed).unwrap_or(storage);
    if crate::storage::sealed(s, CHECKSUM_WORD) {
        Ok(())
    } else {
        Err(Error::Corrupt {
            word: CHECKSUM_WORD,
        })
    }
}

/// Reads and checks the header (O(1)): the tag, the version, sizes in `1..=MAX_SIDE`
/// whose `storage_len` (from `len`) fits the 32-bit indices, and zero reserved words (not the
/// checksum: that is `from_storage_verified`'s O(n) pass). Returns the sizes, the needed
/// length and the four region lengths as recorded (the caller compares them with the ones the
/// sizes imply).
fn read_header(
    storage: &[Word],
    expected_tag: u32,
    len: impl FnOnce(usize, usize) -> usize,
) -> Result<(usize, usize, usize, [usize; 4]), Error> {
    let header: [Word; HEADER_WORDS] = header(storage, expected_tag, FORMAT_VERSION)?;
    let word = |k: usize| header.get(k).copied().unwrap_or(0);
    let side = |k: usize| {
        let n = word(k) as usize;
        if (1..=MAX_SIDE).contains(&n) {
            Ok(n)
        } else {
            Err(Error::Corrupt { word: k })
        }
    };
    let (width, height) = (side(2)?, side(3)?);
    let needed = len(width, height);
    if needed == usize::MAX {
        return Err(Error::Corrupt { word: 2 });
    }
    // The reserved words after the checksum are 0 in every storage this version writes.
    if let Some(k) = (CHECKSUM_WORD + 1..HEADER_WORDS).find(|&k| word(k) != 0) {
        return Err(Error::Corrupt { word: k });
    }
    let lens = [4, 5, 6, 7].map(|k| word(k) as usize);
    Ok((width, height, needed, lens))
}

/// Checks the recorded region lengths (header words 4..8) against the ones the sizes imply,
/// then the storage length against the needed one.
fn check_lens(
    recorded: [usize; 4],
    implied: [usize; 4],
    needed: usize,
    got: usize,
) -> Result<(), Error> {
    for (k, (r, i)) in recorded.iter().zip(&implied).enumerate() {
        if r != i {
            // The lengths are header words 4..8.
            return Err(Error::Corrupt { word: 4 + k });
        }
    }
    if got < needed {
        return Err(Error::StorageTooSmall { needed, got });
    }
    Ok(())
}

/// Lane-wise table read in storage byte order (zeros out of bounds, never a panic).
#[inline(always)]
fn load<U: UintLane>(table: &[[u32; 1]], idx: U) -> U {
    let [v] = U::gather(table, idx);
    from_storage_order(v)
}

/// Four consecutive words per lane, in storage byte order.
#[inline(always)]
fn load4<U: UintLane>(table: &[u32], start: U) -> [U; 4] {
    U::gather4(table, start).map(from_storage_order)
}

/// Correctly rounded `u32 -> f32` for the whole `u32` range (`from_uint` is exact only below
/// `2^24`): the high 24 bits convert exactly, and one addition rounds once.
#[inline(always)]
fn u32_to_f32<L: Lane>(x: L::U) -> L {
    L::from_uint(x.shr(8)) * L::splat(256.0) + L::from_uint(x & L::U::splat(255))
}

/// `u` in `[0, 1)` as a 0.31 fixed-point key, after the forward rule: `floor(u * 2^31)`,
/// exact (the scaling is by a power of two) and at most `2^31 - 128`.
#[inline(always)]
fn fixed_key<L: Lane>(u: L) -> L::U {
    (unit_interval(u) * L::splat(2_147_483_648.0)).to_uint()
}

/// `N` samples from their components, one array per component.
#[inline(always)]
fn samples_of<const N: usize>(
    u: [f32; N],
    v: [f32; N],
    pdf: [f32; N],
    [c, r]: [[u32; N]; 2],
) -> [Sample; N] {
    core::array::from_fn(|j| Sample {
        uv: [u[j], v[j]],
        pdf: pdf[j],
        texel: [c[j], r[j]],
    })
}

/// Scalar lane results of a generic body as a [`Sample`].
#[inline(always)]
fn scalar_sample(r: ([f32; 2], f32, [core::num::Wrapping<u32>; 2])) -> Sample {
    Sample {
        uv: r.0,
        pdf: r.1,
        texel: [r.2[0].0, r.2[1].0],
    }
}

/// SIMD lane results of a generic body as a [`SampleX8`].
#[inline(always)]
fn simd_sample(r: ([f32x8; 2], f32x8, [u32x8; 2])) -> SampleX8 {
    SampleX8 {
        uv: r.0,
        pdf: r.1,
        texel: r.2,
    }
}

/// SIMD lane results of a generic body as a [`SampleX16`].
#[inline(always)]
fn simd16_sample(r: ([f32x16; 2], f32x16, [u32x16; 2])) -> SampleX16 {
    SampleX16 {
        uv: r.0,
        pdf: r.1,
        texel: r.2,
    }
}
