//! The registry of warpcore's public functions and what every cross-cutting proof shares.
//!
//! [`entries`] lists every public function of the library once ([`Entry`]): its forms
//! (scalar, `_x8`, `_x16`, `_slice`), its typed bodies, how its output bits are pinned
//! ([`Golden`]) and its names in C, JS and WGSL. The proofs iterate over it instead of
//! keeping lists of their own:
//! - [`fingerprint`]: the golden hash of every function's output bits over a fixed input set,
//!   identical on every target (the Rust tests natively and under wasm32, the wasm cdylib,
//!   the C port, the GPU checker), and a golden hash per function
//!   (`tests/golden/registry.txt`);
//! - `lanes` (with the `std` feature): every lane and slice form equals the scalar form bit
//!   for bit, and every scalar output is finite and below `f32::MAX`; run by `tests/lanes.rs`
//!   on special values, uniform points and random bit patterns, and by the `registry` fuzz
//!   target on what it searches;
//! - `tests/coverage.rs`: every public function of `src/`, every C declaration, JS method
//!   and WGSL function has an entry, and every entry's names exist;
//! - `checks` (with the `std` feature): the fuzz targets' definition of "correct on any
//!   input", also replayed over the committed corpus by `tests/fuzz_corpus.rs`; the
//!   fuzz targets (`fuzz/`, outside the workspace as cargo-fuzz expects) call them.
//!
//! `no_std` and no allocation without `std`: the fingerprint runs inside the wasm cdylib.
#![no_std]
#[cfg(feature = "std")]
extern crate std;

#[cfg(feature = "std")]
pub mod checks;
mod entries;
mod entry;
pub mod fingerprint;
#[cfg(feature = "std")]
pub mod lanes;

pub use entries::{NOT_FUNCTIONS, entries};
pub use entry::{
    Entry, Forms, Golden, Indexed, Kind, Lang, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant,
    Visit,
};
