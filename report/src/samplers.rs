//! The five samplers of the report, each a per-pixel stream of 2D points: warpcore's three
//! and the randomizations two peer renderers apply to comparable points.
//!
//! | name | points for `n` samples | from |
//! |---|---|---|
//! | `random` | `n` independent uniform points | `sequence::random_slice` |
//! | `stratified` | one jittered point per cell of an `m x m` grid, `m = sqrt(n)` (all sample counts here are squares) | `sequence::stratified_slice` |
//! | `pmj02bn` | the first `n` points of an Owen-scrambled pmj02bn sequence | `pmj02bn::sample_slice` |
//! | `pmj02bn_cp` | the first `n` points of pmj02bn table set 0, unscrambled, shifted toroidally by one uniform offset per pixel (Cranley-Patterson rotation) | `pmj02bn::raw`: pbrt-v4's `PMJ02BNSampler` for its first two dimensions (the table's first set, the pixel's blue-noise offset) |
//! | `sobol_owen` | the first `n` points of Sobol' dimensions 0 and 1, Owen-scrambled, index-shuffled by the seed | `sobol_burley::sample_4d` (its first two of four dimensions; Burley 2020; what Cycles-style renderers use) |
//!
//! Each pixel (and sample count) gets its own seed, so pixels are independent. The samplers
//! are filled through their batch forms: what a renderer drawing a pixel's samples at once
//! would call. The Cranley-Patterson shift is added in 0.32 fixed point (exactly modulo 1),
//! then truncated to the `2^-24` grid like every other sampler here; pbrt-v4 adds in `f32`
//! and subtracts 1, which differs only by rounding.

use crate::math::hash;
use warpcore::{pmj02bn, sequence, u32x8};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Sampler {
    Random,
    Stratified,
    Pmj02bn,
    Pmj02bnCp,
    SobolOwen,
}

pub const SAMPLERS: [Sampler; 5] = [
    Sampler::Random,
    Sampler::Stratified,
    Sampler::Pmj02bn,
    Sampler::Pmj02bnCp,
    Sampler::SobolOwen,
];

/// `(x >> 8) * 2^-24`: 0.32 fixed point to `[0, 1)`, truncating (never rounds up to 1).
#[inline]
fn unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

impl Sampler {
    pub fn name(self) -> &'static str {
        match self {
            Sampler::Random => "random",
            Sampler::Stratified => "stratified",
            Sampler::Pmj02bn => "pmj02bn",
            Sampler::Pmj02bnCp => "pmj02bn_cp",
            Sampler::SobolOwen => "sobol_owen",
        }
    }

    pub fn index(self) -> usize {
        self as usize
    }

    /// The API a renderer calls for this sampler's points (peers marked as peers): what the
    /// generated recommendations print (the CSV keeps the short names).
    pub fn api_name(self) -> &'static str {
        match self {
            Sampler::Random => "sequence::random",
            Sampler::Stratified => "sequence::stratified",
            Sampler::Pmj02bn => "pmj02bn::sample",
            Sampler::Pmj02bnCp => "peer: pbrt-v4 PMJ02BN (table + shift)",
            Sampler::SobolOwen => "peer: sobol_burley (Owen Sobol')",
        }
    }

    /// Whether the sampler is one of the peers' randomizations (not warpcore's own).
    pub fn is_peer(self) -> bool {
        matches!(self, Sampler::Pmj02bnCp | Sampler::SobolOwen)
    }

    /// Fills `out` with this sampler's `out.len()` points for `seed` (for `stratified`, the
    /// jittered grid of exactly `out.len()` points).
    #[inline]
    pub fn fill(self, seed: u32, out: &mut [[f32; 2]]) {
        match self {
            Sampler::Stratified => {
                sequence::stratified_slice(0, out.len() as u32, seed, out);
            }
            _ => self.fill_from(seed, 0, out),
        }
    }

    /// Points `start .. start + out.len()` of the sampler's sequence for `seed` (consecutive
    /// points, as rejection sampling consumes them). `stratified` is not a sequence: each
    /// block of `block` consecutive indices is a fresh jittered grid of `block` points (its own
    /// seed), its cells visited in a random order (a random affine permutation of the cell
    /// index), so that every point, taken alone, is uniform on the square.
    #[inline]
    pub fn fill_from_blocks(self, seed: u32, start: u32, block: u32, out: &mut [[f32; 2]]) {
        if self != Sampler::Stratified {
            return self.fill_from(seed, start, out);
        }
        let block = block.max(1);
        let mut grid = u32::MAX;
        let (mut a, mut b, mut jitter) = (1u64, 0u64, 0u32);
        for (k, o) in out.iter_mut().enumerate() {
            let i = start + k as u32;
            if i / block != grid {
                // A new grid: its seed and its cell order `(a j + b) mod block`, drawn once.
                grid = i / block;
                let h = hash(&[seed as u64, grid as u64]);
                // Odd multipliers are coprime with the powers of two used here; for other
                // block sizes step until coprime.
                let mut m = (h as u32) | 1;
                while gcd(m % block, block) != 1 {
                    m = m.wrapping_add(2);
                }
                (a, b, jitter) = (m as u64, h >> 32, (h >> 16) as u32);
            }
            let cell = ((a * (i % block) as u64 + b) % block as u64) as u32;
            *o = sequence::stratified(cell, block, jitter);
        }
    }

    fn fill_from(self, seed: u32, start: u32, out: &mut [[f32; 2]]) {
        match self {
            Sampler::Random => {
                sequence::random_slice(start, seed, out);
            }
            Sampler::Stratified => self.fill_from_blocks(seed, start, out.len() as u32, out),
            Sampler::Pmj02bn => {
                pmj02bn::sample_slice(start, seed, out);
            }
            Sampler::Pmj02bnCp => {
                let h = hash(&[seed as u64, 0x6370]);
                let shift = [h as u32, (h >> 32) as u32];
                for (k, o) in out.iter_mut().enumerate() {
                    let [x, y] = pmj02bn::raw(0, start as usize + k);
                    *o = [
                        unit(x.wrapping_add(shift[0])),
                        unit(y.wrapping_add(shift[1])),
                    ];
                }
            }
            Sampler::SobolOwen => {
                // Dimensions 0-3 in one SIMD call (the same values as `sample(i, d, seed)`
                // for d = 0, 1): the crate's fastest way to a 2D point.
                for (k, o) in out.iter_mut().enumerate() {
                    let [x, y, _, _] = sobol_burley::sample_4d(start + k as u32, 0, seed);
                    *o = [x, y];
                }
            }
        }
    }
}

fn gcd(mut a: u32, mut b: u32) -> u32 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
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
