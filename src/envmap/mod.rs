//! Environment-map importance sampling: draw texels of an image in proportion to their weight
//! (usually luminance), heap-free, with caller-owned storage.
//!
//! | distribution | build | sample | keeps | source |
//! |---|---|---|---|---|
//! | [`MarginalConditional`] | row CDF + one CDF per row, 0.31 fixed point, from `f64` sums; 4 bytes per texel | two branch-free binary searches | strata along each axis | pbrt-v4 `PiecewiseConstant2D`, Mitsuba 3 `DiscreteDistribution2D` |
//! | [`Hierarchical`] | a MIP pyramid of 0.31 split fractions, from pairwise sums, in 64-byte two-level blocks; about 4.3 bytes per padded texel | one 2x2 split per level, exact integer interval arithmetic on the sample | compact 2D strata | Mitsuba 3 `Hierarchical2D`; McCool and Harwood 1997, "Probability Trees"; Clarberg et al. 2005, "Wavelet Importance Sampling" |
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
//! * An all-zero map (after the rule above) samples **uniformly**, with pdf 1.
//! * Any finite weights work, subnormals and `f32::MAX` included: sums are taken in `f64`
//!   (marginal-conditional) or in a rescaled `f32` pyramid (hierarchical), never overflow.
//! * Maps of any size from `1 x 1` to `MAX_SIDE x MAX_SIDE` (that fit the 32-bit table
//!   indices, see [`Error::TooLarge`]), square or not, powers of two or not.

mod edges;
mod hierarchical;
pub mod image;
mod marginal;

pub use hierarchical::Hierarchical;
pub use marginal::MarginalConditional;

use crate::lanes::{Lane, UintLane, unit_interval};
use core::fmt;
use wide::{f32x8, u32x8};

/// The storage element: the caller allocates `storage_len(width, height)` of them (any
/// alignment, any initial contents) and lends them to `new`.
pub type Word = u32;

/// Largest accepted width or height: `2^24`, so texel indices and edges are exact in `f32`.
pub const MAX_SIDE: usize = 1 << 24;

/// One sample of an environment-map distribution.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sample {
    /// The point, in `[0, 1)^2`, inside `texel`.
    pub uv: [f32; 2],
    /// Density with respect to area on `[0, 1]^2` at `uv` (constant over the texel).
    pub pdf: f32,
    /// `[column, row]` of the texel the point lies in.
    pub texel: [u32; 2],
}

/// Eight samples in SIMD lanes (what `sample_x8` returns). Lane `j` equals the scalar
/// `sample` of lane `j` of the input, bit for bit.
#[derive(Clone, Copy, Debug)]
pub struct SampleX8 {
    /// `[u, v]` of the eight points.
    pub uv: [f32x8; 2],
    /// The eight densities.
    pub pdf: f32x8,
    /// `[column, row]` of the eight texels.
    pub texel: [u32x8; 2],
}

impl SampleX8 {
    /// The eight samples as an array of [`Sample`]s.
    #[inline]
    pub fn to_array(&self) -> [Sample; 8] {
        let (u, v, p) = (
            self.uv[0].to_array(),
            self.uv[1].to_array(),
            self.pdf.to_array(),
        );
        let (c, r) = (self.texel[0].to_array(), self.texel[1].to_array());
        core::array::from_fn(|j| Sample {
            uv: [u[j], v[j]],
            pdf: p[j],
            texel: [c[j], r[j]],
        })
    }
}

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
        }
    }
}

impl core::error::Error for Error {}

// ---------------------------------------------------------------------------------------
// Shared by both distributions.

/// The weight rule: `+inf` is reported by the caller before this; positive finite values pass,
/// everything else (NaN, zeros, negatives, `-inf`) weighs 0.
#[inline(always)]
fn clean(w: f32) -> f32 {
    if w > 0.0 { w } else { 0.0 }
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
    let expected = width.saturating_mul(height);
    if weights.len() != expected {
        return Err(Error::LengthMismatch {
            expected,
            got: weights.len(),
        });
    }
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

/// The batch loop shared by the `sample_slice` forms.
#[inline(always)]
fn sample_batch(u: &[[f32; 2]], out: &mut [Sample], f: impl Fn([f32x8; 2]) -> SampleX8) -> usize {
    let n = u.len().min(out.len());
    let (u, out) = (
        u.get(..n).unwrap_or(&[]),
        out.get_mut(..n).unwrap_or(&mut []),
    );
    let (in_groups, in_rest) = u.as_chunks::<8>();
    let (out_groups, out_rest) = out.as_chunks_mut::<8>();
    for (src, dst) in in_groups.iter().zip(out_groups) {
        *dst = f(crate::batch::load(src)).to_array();
    }
    if !in_rest.is_empty() {
        let mut pad = [[0.0f32; 2]; 8];
        for (p, s) in pad.iter_mut().zip(in_rest) {
            *p = *s;
        }
        let res = f(crate::batch::load(&pad)).to_array();
        for (d, r) in out_rest.iter_mut().zip(res.iter()) {
            *d = *r;
        }
    }
    n
}

/// The batch loop shared by the `pdf_slice` forms.
#[inline(always)]
fn pdf_batch(uv: &[[f32; 2]], out: &mut [f32], f: impl Fn([f32x8; 2]) -> f32x8) -> usize {
    let (out, _) = out.as_chunks_mut::<1>();
    crate::batch::map(uv, out, |v| [f(v)])
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
