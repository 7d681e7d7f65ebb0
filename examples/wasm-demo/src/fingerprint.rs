//! The golden fingerprint: a 64-bit FNV-1a hash of the output bits of every warp — scalar,
//! `_x8` and slice forms — over a fixed set of inputs (special values and 1024 pseudo-random
//! points from a counter hash). Identical on every target and instruction set, or the
//! determinism promise is broken. `no_std`, no allocation; shared by `tests/fingerprint.rs`,
//! the native `fingerprint` binary and the wasm cdylib.

#![allow(dead_code)]

use warpcore::f32x8;

/// Inputs every warp sees: a special-value cross product, then counter-hash points.
pub const N: usize = 1024 + SPECIALS.len() * SPECIALS.len();

const SPECIALS: [f32; 12] = [
    0.0,
    -0.0,
    0.5,
    0.999_999_94,
    1.0,
    -1.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    1.0e-40,
    0.25,
    0.75,
];

pub struct Hasher(u64);

impl Hasher {
    pub fn new() -> Self {
        Hasher(0xcbf2_9ce4_8422_2325)
    }
    pub fn word(&mut self, w: u32) {
        for b in w.to_le_bytes() {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    pub fn floats(&mut self, v: &[f32]) {
        for x in v {
            self.word(x.to_bits());
        }
    }
    pub fn finish(&self) -> u64 {
        self.0
    }
}

/// A counter-based hash to `[0, 1)` (PCG output permutation), 24 random bits.
pub fn unit(i: u32) -> f32 {
    let mut x = i.wrapping_mul(747_796_405).wrapping_add(2_891_336_453);
    x = ((x >> ((x >> 28).wrapping_add(4))) ^ x).wrapping_mul(277_803_737);
    x ^= x >> 22;
    (x >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// Input point `i` of the fixed set; dimension `d` of `D`.
pub fn input<const D: usize>(i: usize) -> [f32; D] {
    let s = SPECIALS.len();
    core::array::from_fn(|d| {
        if i < s * s {
            SPECIALS[if d % 2 == 0 {
                i % s
            } else {
                (i / s + d / 2) % s
            }]
        } else {
            unit((i * D + d) as u32)
        }
    })
}

/// Hashes `scalar` over all inputs, then `x8` over groups of 8 and `slice` over the whole set
/// in chunks of 37 (so padded tails are included).
pub fn warp<const I: usize, const O: usize>(
    h: &mut Hasher,
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) {
    let mut chunk_in = [[0.0f32; I]; 37];
    let mut chunk_out = [[0.0f32; O]; 37];
    let mut i = 0;
    while i < N {
        let n = (N - i).min(37);
        for (k, slot) in chunk_in.iter_mut().enumerate().take(n) {
            *slot = input(i + k);
        }
        let (src, dst) = (
            chunk_in.get(..n).unwrap_or(&[]),
            chunk_out.get_mut(..n).unwrap_or(&mut []),
        );
        h.word(slice(src, dst) as u32);
        for (u, o) in src.iter().zip(dst.iter()) {
            h.floats(&scalar(*u));
            h.floats(o);
        }
        i += n;
    }
    let mut g = 0;
    while g + 8 <= N {
        let v: [f32x8; I] =
            core::array::from_fn(|d| f32x8::new(core::array::from_fn(|j| input::<I>(g + j)[d])));
        for c in x8(v) {
            h.floats(&c.to_array());
        }
        g += 8;
    }
}

/// The fingerprint of every family compiled in.
pub fn fingerprint() -> u64 {
    let mut h = Hasher::new();
    #[cfg(feature = "disk")]
    {
        use warpcore::disk;
        warp(&mut h, disk::polar, disk::polar_x8, disk::polar_slice);
        warp(
            &mut h,
            disk::concentric,
            disk::concentric_x8,
            disk::concentric_slice,
        );
        warp(
            &mut h,
            disk::polar_inverse,
            disk::polar_inverse_x8,
            disk::polar_inverse_slice,
        );
        warp(
            &mut h,
            disk::concentric_inverse,
            disk::concentric_inverse_x8,
            disk::concentric_inverse_slice,
        );
        for q in 0..4u32 {
            warp(
                &mut h,
                |u| disk::polar4(u, q),
                |u| disk::polar4_x8(u, warpcore::u32x8::splat(q)),
                |u, o| {
                    for (a, b) in u.iter().zip(o.iter_mut()) {
                        *b = disk::polar4(*a, q);
                    }
                    u.len().min(o.len())
                },
            );
        }
        let pts: [[f32; 2]; 9] = core::array::from_fn(input);
        let mut out = [[0.0f32; 2]; 35];
        h.word(disk::polar4_slice(&pts, &mut out) as u32);
        for p in out {
            h.floats(&p);
        }
    }
    h.finish()
}
