//! Caller-owned storage shared by the families that build tables into `[u32]` words (the
//! environment maps, the light-selection tables): little-endian words on every target, and a
//! content checksum that catches every single-bit flip.

use crate::lanes::UintLane;
use wide::u32x8;

/// The content checksum of a storage of exactly `storage_len` words (storage byte order):
/// every word but the checksum's own (`checksum_word`), header included.
///
/// Eight interleaved chains `s = mix(s ^ word)` (word `i` of the sequence feeds chain
/// `i % 8`), folded at the end by `h = mix(h ^ s)`, where `mix` is Chris Wellons'
/// `lowbias32` (`hash::mix`), a bijection of `u32`. Because each step is a bijection of the
/// chain's state for a fixed word *and* of the word for a fixed state, a change confined to
/// one word — in particular **every single-bit flip** — always changes the result (a proof,
/// not a probability); other changes go unnoticed with probability about `2^-32`. A CRC-32
/// would give the same single-word guarantee (plus bursts), but costs a 1 KiB table or eight
/// dependent steps per byte; the eight independent chains keep the multiplier busy and need
/// no table (`benches/envmap.rs` measures the env maps' `from_storage_verified`, checksum included).
pub(crate) fn checksum(storage: &[u32], checksum_word: usize) -> u32 {
    use crate::hash::mix;
    use core::num::Wrapping as W;
    let step = |s: u32, w: u32| mix(W(s ^ u32::from_le(w))).0;
    let mut lanes: [u32; 8] = core::array::from_fn(|j| (j as u32 + 1).wrapping_mul(0x9e37_79b9));
    let (head, tail) = storage.split_at(checksum_word.min(storage.len()));
    let tail = tail.get(1..).unwrap_or(&[]);
    for (s, &w) in lanes.iter_mut().zip(head) {
        *s = step(*s, w);
    }
    // The whole groups of eight: the eight chains as the lanes of one `u32x8` (the same
    // integer operations per lane, so the same bits as eight scalar chains).
    let (chunks, rest) = tail.as_chunks::<8>();
    let mut v = u32x8::new(lanes);
    for chunk in chunks {
        v = mix(v ^ from_storage_order(u32x8::new(*chunk)));
    }
    lanes = v.to_array();
    for (s, &w) in lanes.iter_mut().zip(rest) {
        *s = step(*s, w);
    }
    lanes
        .iter()
        .fold(storage.len() as u32, |h, &s| mix(W(h ^ s)).0)
}

/// Makes a freshly built storage little-endian in memory (a no-op on little-endian targets).
pub(crate) fn to_storage_order(storage: &mut [u32]) {
    if cfg!(target_endian = "big") {
        for w in storage {
            *w = w.to_le();
        }
    }
}

/// A storage word as a number (the words are little-endian in memory on every target).
#[inline(always)]
pub(crate) fn from_storage_order<U: UintLane>(x: U) -> U {
    if cfg!(target_endian = "big") {
        let byte = U::splat(0xff);
        x.shr(24) | (x.shr(8) & byte.shl(8)) | (x.shl(8) & byte.shl(16)) | x.shl(24)
    } else {
        x
    }
}

/// Why a storage header was refused before its family-specific words were read: each family
/// maps this onto its own `Error` (`StorageTooSmall`, `WrongFormat`, `UnsupportedVersion`).
pub(crate) enum HeaderFault {
    /// Fewer words than the header (`needed`).
    TooSmall { needed: usize, got: usize },
    /// Word 0 is not the expected format tag.
    WrongFormat { found: u32 },
    /// Word 1 is not the version this build reads.
    UnsupportedVersion { found: u32 },
}

/// `impl From<HeaderFault> for $error`, for a family's `Error` with the variants
/// `StorageTooSmall { needed, got }`, `WrongFormat { found }` and
/// `UnsupportedVersion { found }`.
macro_rules! from_header_fault {
    ($error:ty) => {
        impl From<crate::storage::HeaderFault> for $error {
            fn from(f: crate::storage::HeaderFault) -> Self {
                use crate::storage::HeaderFault as F;
                match f {
                    F::TooSmall { needed, got } => Self::StorageTooSmall { needed, got },
                    F::WrongFormat { found } => Self::WrongFormat { found },
                    F::UnsupportedVersion { found } => Self::UnsupportedVersion { found },
                }
            }
        }
    };
}
pub(crate) use from_header_fault;

/// The first `N` words of a storage as numbers, once word 0 is `tag` and word 1 is `version`
/// (the O(1) checks every `from_storage` starts with).
pub(crate) fn header<const N: usize>(
    storage: &[u32],
    tag: u32,
    version: u32,
) -> Result<[u32; N], HeaderFault> {
    let got = storage.len();
    let words: &[u32; N] = storage
        .first_chunk::<N>()
        .ok_or(HeaderFault::TooSmall { needed: N, got })?;
    let words = words.map(u32::from_le);
    let [found, v] = [0, 1].map(|k| words.get(k).copied().unwrap_or(0));
    if found != tag {
        return Err(HeaderFault::WrongFormat { found });
    }
    if v != version {
        return Err(HeaderFault::UnsupportedVersion { found: v });
    }
    Ok(words)
}

/// Writes the checksum of a freshly built storage (already in storage byte order) into word
/// `checksum_word`.
pub(crate) fn seal(storage: &mut [u32], checksum_word: usize) {
    let sum = checksum(storage, checksum_word);
    if let Some(w) = storage.get_mut(checksum_word) {
        *w = sum.to_le();
    }
}

/// Whether a storage matches the checksum in its word `checksum_word`.
pub(crate) fn sealed(storage: &[u32], checksum_word: usize) -> bool {
    let stored = storage.get(checksum_word).map_or(0, |&w| u32::from_le(w));
    checksum(storage, checksum_word) == stored
}
