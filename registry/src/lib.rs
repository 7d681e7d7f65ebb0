//! What warpcore's cross-cutting proofs share, in one crate every checker depends on (no
//! `#[path]` includes across crates): [`fingerprint`], the golden hash of every warp's output
//! bits over a fixed input set, computed identically by the Rust tests (native, wasm32 with
//! and without simd128, `-C target-cpu=native`), the wasm cdylib, the C port and the GPU
//! checker.
#![no_std]

pub mod fingerprint;
