//! Light selection: pick one of `n` lights with a known probability, for next-event estimation
//! and its multiple-importance-sampling weight.
//!
//! - [`AliasTable`]: probability proportional to a weight (usually power), O(1) per sample
//!   (Walker 1977, built by Vose's method, 1991).
//! - [`LightTree`]: probability from each light's importance at the shading point, a bounding
//!   volume hierarchy over [`LightBounds`] (pbrt-v4's BVH light sampler; Conty Estevez and
//!   Kulla 2018, "Importance Sampling of Many Lights with Adaptive Tree Splitting").
//! - [`Reservoir`]: a streaming choice of one item with probability proportional to its
//!   weight (weighted reservoir sampling, Chao 1982), the building block of resampled
//!   importance sampling (Bitterli et al. 2020).
//!
//! Both live in caller-owned `[u32]` storage with a versioned, checksummed header, as the
//! environment maps do: `storage_len`, `new`, `from_storage` (O(1)) and
//! `from_storage_verified` (O(n), rejects every single-bit flip).

mod alias;
mod reservoir;
mod tree;

pub use alias::AliasTable;
pub use reservoir::Reservoir;
pub use tree::{LightBounds, LightTree};

use core::fmt;

/// Why a light-selection table could not be built or read.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// No lights: `weights` or `lights` is empty.
    Empty,
    /// More lights than the storage format indexes (see the type's `MAX_LIGHTS`);
    /// `storage_len` returns `usize::MAX` for such counts.
    TooLarge,
    /// The storage is shorter than `storage_len(n)`.
    StorageTooSmall {
        /// `storage_len(n)`.
        needed: usize,
        /// `storage.len()`.
        got: usize,
    },
    /// Light `index` has a weight or power that is NaN, infinite or negative.
    InvalidWeight {
        /// Index of the first offending light.
        index: usize,
    },
    /// Light `index` has bounds that cannot be used: a NaN or infinite coordinate, an
    /// inverted box, a zero or non-finite axis, or a cosine outside `[-1, 1]` or NaN.
    InvalidBounds {
        /// Index of the first offending light.
        index: usize,
    },
    /// Every weight (or power) is zero: no light can be chosen.
    AllZero,
    /// `from_storage`: word 0 is not this table's format tag.
    WrongFormat {
        /// Word 0 of the storage.
        found: u32,
    },
    /// `from_storage`: the format version (word 1) is not the one this build reads.
    UnsupportedVersion {
        /// Word 1 of the storage.
        found: u32,
    },
    /// `from_storage`: storage word `word` holds a value `new` never writes there, or (only
    /// `from_storage_verified`) the content does not match its checksum.
    Corrupt {
        /// Index of the first offending word in the storage.
        word: usize,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Error::Empty => write!(f, "no lights"),
            Error::TooLarge => write!(f, "too many lights for the storage format"),
            Error::StorageTooSmall { needed, got } => {
                write!(f, "storage holds {got} words, {needed} needed")
            }
            Error::InvalidWeight { index } => {
                write!(
                    f,
                    "light {index} has a NaN, infinite or negative weight or power"
                )
            }
            Error::InvalidBounds { index } => write!(f, "light {index} has invalid bounds"),
            Error::AllZero => write!(f, "every light has zero weight"),
            Error::WrongFormat { found } => {
                write!(
                    f,
                    "storage word 0 is {found:#010x}, not this table's format tag"
                )
            }
            Error::UnsupportedVersion { found } => {
                write!(f, "storage format version {found} is not this build's")
            }
            Error::Corrupt { word } => write!(f, "storage word {word} is corrupt"),
        }
    }
}

impl core::error::Error for Error {}

crate::storage::from_header_fault!(Error);
