//! The three samplers of the report, each a per-pixel stream of 2D points from warpcore:
//!
//! | name | points for `n` samples | from |
//! |---|---|---|
//! | `random` | `n` independent uniform points | `sequence::random_slice` |
//! | `stratified` | one jittered point per cell of an `m x m` grid, `m = sqrt(n)` (all sample counts here are squares) | `sequence::stratified_slice` |
//! | `pmj02bn` | the first `n` points of an Owen-scrambled pmj02bn sequence | `pmj02bn::sample_slice` |
//!
//! Each pixel (and sample count) gets its own seed, so pixels are independent. The samplers
//! are filled through their slice forms: what a renderer drawing a pixel's samples at once
//! would call.

use warpcore::{pmj02bn, sequence, u32x8};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sampler {
    Random,
    Stratified,
    Pmj02bn,
}

pub const SAMPLERS: [Sampler; 3] = [Sampler::Random, Sampler::Stratified, Sampler::Pmj02bn];

impl Sampler {
    pub fn name(self) -> &'static str {
        match self {
            Sampler::Random => "random",
            Sampler::Stratified => "stratified",
            Sampler::Pmj02bn => "pmj02bn",
        }
    }

    pub fn index(self) -> usize {
        self as usize
    }

    /// Fills `out` with this sampler's `out.len()` points for `seed` (for `stratified`, the
    /// jittered grid of exactly `out.len()` points).
    #[inline]
    pub fn fill(self, seed: u32, out: &mut [[f32; 2]]) {
        match self {
            Sampler::Random => {
                sequence::random_slice(0, seed, out);
            }
            Sampler::Stratified => {
                sequence::stratified_slice(0, out.len() as u32, seed, out);
            }
            Sampler::Pmj02bn => {
                pmj02bn::sample_slice(0, seed, out);
            }
        }
    }
}

/// Wellons' `lowbias32` on eight lanes: independent random 32-bit indices for the
/// `random` sampler of index-driven constructions (Basu-Owen).
#[inline]
pub fn hash_x8(x: u32x8) -> u32x8 {
    let mut x = x;
    x ^= x >> 16;
    x *= u32x8::splat(0x7feb_352d);
    x ^= x >> 15;
    x *= u32x8::splat(0x846c_a68b);
    x ^ (x >> 16)
}
