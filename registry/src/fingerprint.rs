//! The golden fingerprint: a 64-bit FNV-1a hash of the output bits of every warp — scalar,
//! `_x8` and slice forms — over a fixed set of inputs (special values and 1024 pseudo-random
//! points from a counter hash; for the `spherical` lights, those inputs on each of a fixed
//! set of lights, ordinary and extreme). Identical on every target and instruction set, or the
//! determinism promise is broken. `no_std`, no allocation; shared by `registry/tests/fingerprint.rs`, the C and GPU tests,
//! the native `fingerprint` binary and the wasm cdylib.
//!
//! [`fingerprint_x16`] hashes the same bits with every `_x8` call replaced by the `_x16` form
//! (lanes hashed in the same order, eight at a time), so it must equal the same golden value:
//! the 16-wide forms are checked on every target too, emulated by `wide` where the target
//! has no 16-lane vectors.

use crate::entry::{Entry, Golden, Indexed, LightMap, Map, OfLight, Quadrant, ToQuadrant, Visit};
use warpcore::{f32x8, f32x16, u32x8, u32x16};

/// Inputs every warp sees: a special-value cross product, then counter-hash points.
pub const N: usize = 1024 + SPECIALS.len() * SPECIALS.len();

pub const SPECIALS: [f32; 12] = [
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

/// The running hash, and which SIMD width stands for the `_x8` forms.
pub struct Hasher(u64, bool);

impl Default for Hasher {
    fn default() -> Self {
        Self::new()
    }
}

impl Hasher {
    pub fn new() -> Self {
        Hasher(0xcbf2_9ce4_8422_2325, false)
    }
    /// A hasher that runs the `_x16` forms where the fingerprint has `_x8` ones.
    pub fn new_x16() -> Self {
        Hasher(0xcbf2_9ce4_8422_2325, true)
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
    // A constant, not a local the closure captures: where LLVM outlines the closure it must
    // still see the divisor and the bound (the wasm demo may have no panic path).
    const S: usize = SPECIALS.len();
    core::array::from_fn(|d| {
        if i < S * S {
            SPECIALS[if d % 2 == 0 {
                i % S
            } else {
                (i / S + d / 2) % S
            }]
        } else {
            unit((i * D + d) as u32)
        }
    })
}

/// The piece of a [`Map`]: the slice form over the whole set in chunks of 37 (so padded
/// tails are included) with the scalar form on each input, then the lane forms on groups of
/// 16 inputs. A map without a slice form hashes the scalar form alone in the first part; one
/// without lane forms skips the second; one without an `_x16` form hashes its `_x8` form in
/// both hashers.
pub fn map<const I: usize, const O: usize>(h: &mut Hasher, m: &Map<I, O>) {
    chunks(h, m.scalar, m.slice);
    let Some(x8) = m.x8 else { return };
    let mut g = 0;
    while g + 16 <= N {
        let group: [[f32; I]; 16] = core::array::from_fn(|j| input(g + j));
        match m.x16 {
            Some(x16) => hash_groups(h, &group, x8, x16),
            None => {
                let wide = core::mem::replace(&mut h.1, false);
                hash_groups(h, &group, x8, |_| [f32x16::splat(0.0); O]);
                h.1 = wide;
            }
        }
        g += 16;
    }
}

/// The set in chunks of 37 (so padded tails are included): per chunk the slice form's count,
/// then input by input the scalar form's output and the slice form's; without a slice form,
/// the scalar outputs alone.
fn chunks<const I: usize, const O: usize>(
    h: &mut Hasher,
    scalar: impl Fn([f32; I]) -> [f32; O],
    slice: Option<impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize>,
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
        match &slice {
            Some(slice) => {
                h.word(slice(src, dst) as u32);
                for (u, o) in src.iter().zip(dst.iter()) {
                    h.floats(&scalar(*u));
                    h.floats(o);
                }
            }
            None => src.iter().for_each(|u| h.floats(&scalar(*u))),
        }
        i += n;
    }
}

/// [`map`] on a map with every form, from its four functions (the `spherical` tests use it
/// on modified forms).
pub fn warp<const I: usize, const O: usize>(
    h: &mut Hasher,
    scalar: fn([f32; I]) -> [f32; O],
    x8: fn([f32x8; I]) -> [f32x8; O],
    x16: fn([f32x16; I]) -> [f32x16; O],
    slice: crate::entry::SliceFn<I, O>,
) {
    map(
        h,
        &Map {
            scalar,
            x8: Some(x8),
            x16: Some(x16),
            slice: Some(slice),
        },
    );
}

/// Hashes the outputs of 16 inputs as two groups of 8, each component's eight lanes in turn:
/// from two `x8` calls, or from one `x16` call (the hasher's width), in the same order.
fn hash_groups<const I: usize, const O: usize>(
    h: &mut Hasher,
    group: &[[f32; I]; 16],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    x16: impl Fn([f32x16; I]) -> [f32x16; O],
) {
    if h.1 {
        let v = x16(core::array::from_fn(|d| {
            f32x16::new(core::array::from_fn(|j| group[j][d]))
        }));
        for half in 0..2 {
            for c in &v {
                h.floats(&c.to_array()[8 * half..8 * half + 8]);
            }
        }
    } else {
        for half in 0..2 {
            let v = x8(core::array::from_fn(|d| {
                f32x8::new(core::array::from_fn(|j| group[8 * half + j][d]))
            }));
            for c in v {
                h.floats(&c.to_array());
            }
        }
    }
}

/// Hashes an index-driven sequence: `scalar(index, seed)` over a fixed set of (index, seed)
/// pairs (small, near `2^k` boundaries, past any table, and extremes), `x8` on groups of 8
/// and `slice(start, seed, out)` filling 37 consecutive points from several starts.
pub fn indexed<const O: usize>(
    h: &mut Hasher,
    scalar: impl Fn(u32, u32) -> [f32; O],
    x8: impl Fn(u32x8, u32x8) -> [f32x8; O],
    x16: impl Fn(u32x16, u32x16) -> [f32x16; O],
    slice: impl Fn(u32, u32, &mut [[f32; O]]) -> usize,
) {
    let seeds = [0u32, 1, 0x9e37_79b9, u32::MAX];
    let starts = [0u32, 5, 1023, 4090, 65530, 1 << 20, u32::MAX - 20];
    for &seed in &seeds {
        for &start in &starts {
            let mut out = [[0.0f32; O]; 37];
            h.word(slice(start, seed, &mut out) as u32);
            for (k, o) in out.iter().enumerate() {
                let i = start.wrapping_add(k as u32);
                h.floats(&scalar(i, seed));
                h.floats(o);
            }
            let idx = |j: usize| start.wrapping_add(3 * j as u32);
            let sd = |j: usize| seed ^ j as u32;
            if h.1 {
                // Lanes 0..8 as the 8-wide call; lanes 8..16 hold other indices and seeds,
                // checked against the scalar form.
                let v = x16(
                    u32x16::new(core::array::from_fn(idx)),
                    u32x16::new(core::array::from_fn(sd)),
                );
                for c in &v {
                    h.floats(&c.to_array()[..8]);
                }
                if (8..16).any(|j| {
                    let s = scalar(idx(j), sd(j));
                    (0..O).any(|c| s[c].to_bits() != v[c].to_array()[j].to_bits())
                }) {
                    h.word(0xbad);
                }
            } else {
                let v = x8(
                    u32x8::new(core::array::from_fn(idx)),
                    u32x8::new(core::array::from_fn(sd)),
                );
                for c in v {
                    h.floats(&c.to_array());
                }
            }
        }
    }
}

/// Lights with a shading point for the `spherical` family, 12 floats each: `v0, v1, v2, p`.
/// Ordinary, nearly `2 pi`, the other winding, a sliver, collinear, below
/// `AREA_FALLBACK_SR`, `p` on the plane (inside, outside), grazing, far away (`1e6`), large
/// and far, `p` at a vertex, coordinates near `1e30` and `1e-30`, NaN, inf, and differences
/// past `2^127`.
pub const SPHERICAL_TRIANGLES: [[f32; 12]; 17] = {
    const I: f32 = f32::INFINITY;
    const NAN: f32 = f32::NAN;
    #[rustfmt::skip]
    let t = [
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.1, 0.2, 0.0],
        [-1.0, -1.0, 0.05, 2.0, -1.0, 0.05, -1.0, 2.0, 0.05, 0.0, 0.0, 0.0],
        [0.3, -2.0, 0.5, -0.7, 0.4, 1.9, 1.5, 0.8, -0.3, -0.2, 0.1, 0.05],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 1.0, 1e-5, 1.0, 0.3, 0.4, 0.0],
        [0.0, 0.0, 1.0, 1.0, 1.0, 1.0, 3.0, 3.0, 1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 1e-4, 0.0, 1.0, 0.0, 1e-4, 1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.2, 0.2, 1.0],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 5.0, -3.0, 1.0],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.2, 0.2, 0.999_999],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 3e5, -2e5, 1e6],
        [-1e5, 0.0, 1e6, 1e5, -1e5, 1e6, 0.0, 1e5, 1e6, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 1.0, 0.0, 1.0],
        [0.0, 0.0, 1e30, 1e30, 0.0, 1e30, 0.0, 1e30, 1e30, 1e29, 2e29, 0.0],
        [0.0, 0.0, 1e-30, 1e-30, 0.0, 1e-30, 0.0, 1e-30, 1e-30, 1e-31, 2e-31, 0.0],
        [NAN, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 1.0, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, I, 0.0],
        [-3e38, 0.0, 1.0, 3e38, 0.0, 1.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0],
    ];
    t
};

/// Rectangles with a shading point for the `spherical` family, 12 floats each:
/// `corner, ex, ey, p`. Ordinary, tilted, nearly `2 pi`, a sliver, `ey = 0`, below
/// `AREA_FALLBACK_SR`, `p` on the plane (inside, outside), grazing, far away (`1e6`), large
/// and far, `ey` not orthogonal to `ex` with `p` behind, `p` at the corner, coordinates near
/// `1e30` and `1e-30`, NaN, -inf.
pub const SPHERICAL_RECTANGLES: [[f32; 12]; 17] = {
    const I: f32 = f32::INFINITY;
    const NAN: f32 = f32::NAN;
    #[rustfmt::skip]
    let r = [
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, 0.2, 0.0],
        [0.3, -0.2, 0.7, 0.6, 0.8, 0.0, 0.0, 0.0, 1.5, 0.0, 0.0, 0.0],
        [-50.0, -50.0, 0.01, 100.0, 0.0, 0.0, 0.0, 100.0, 0.0, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1e-6, 0.0, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 5e-5, 0.0, 0.0, 0.0, 5e-5, 0.0, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 3.0, 0.5, 1.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, 0.1, 0.999_999],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 2e5, -1e5, -1e6],
        [-1e5, -1e5, 1e6, 2e5, 0.0, 0.0, 0.0, 2e5, 0.0, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.3, 1.0, 0.0, 0.2, -0.1, 2.5],
        [-0.5, -0.5, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, -0.5, -0.5, 1.0],
        [-5e29, -5e29, 1e30, 1e30, 0.0, 0.0, 0.0, 1e30, 0.0, 1e29, 0.0, 0.0],
        [-5e-31, -5e-31, 1e-30, 1e-30, 0.0, 0.0, 0.0, 1e-30, 0.0, 0.0, 0.0, 0.0],
        [-0.5, -0.5, 1.0, 1.0, NAN, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [-I, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
    ];
    r
};

/// Sphere lights with a shading point for `spherical::cone`, 12 floats each: `centre,
/// [radius, 0, 0], [0, 0, 0], p` (so the point is the fourth, as for the other lights).
/// Ordinary, small (`1e-6` sr), `1e-9` sr, nearly `2 pi`, `p` on the surface, inside, at the
/// centre, radius 0 (a point), negative radius, a point-like `1e-25` ratio, far away (`1e6`), coordinates
/// near `1e30` and `1e-30`, a huge radius, NaN, inf.
pub const SPHERICAL_CONES: [[f32; 12]; 17] = {
    const I: f32 = f32::INFINITY;
    const NAN: f32 = f32::NAN;
    #[rustfmt::skip]
    let c = [
        [0.0, 0.0, 3.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.1, 0.2, 0.0],
        [1.0, -2.0, 5.0, 3e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.3, 0.4, 2.0, 3.6e-5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 0.999, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 2.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.1, 0.2, 0.3, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, -0.5, 0.4, 0.0],
        [5.0, 5.0, 5.0, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 5.0, 5.0, 5.0],
        [0.0, 3.0, 4.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [-1.0, 0.5, -2.0, -0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 3.0, 4.0, 5e-25, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [3e5, -2e5, 1e6, 10.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1e30, 2e30, -1e30, 5e29, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [1e-30, 2e-30, -1e-30, 5e-31, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, 1e30, 0.0, 0.0, 0.0, 0.0, 0.0, 1e29, -3e29, 0.0],
        [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [NAN, 0.0, 1.0, 0.5, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
        [0.0, 0.0, 1.0, I, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    ];
    c
};

/// A light's 12 floats as four points (`v0, v1, v2, p` or `corner, ex, ey, p`).
pub fn points<T: Copy>(l: [T; 12]) -> [[T; 3]; 4] {
    core::array::from_fn(|k| core::array::from_fn(|c| l[3 * k + c]))
}

/// A triangle light's vertices (its first three points).
pub fn tri<T: Copy>(l: [[T; 3]; 4]) -> [[T; 3]; 3] {
    [l[0], l[1], l[2]]
}

/// The piece of a [`LightMap`]: every light `l` of its set: `slice` on
/// light `l` over all inputs in chunks of 37 with `scalar` on each input, as [`warp`]; then
/// the lane forms on groups of 16 inputs, input `i` paired with light `(l + i) % L`, so the
/// lanes of one call hold different lights (hashed as the private `hash_groups` does).
pub fn light_map<const I: usize, const O: usize>(h: &mut Hasher, m: &LightMap<I, O>) {
    let LightMap {
        lights,
        scalar,
        x8,
        x16,
        slice,
    } = *m;
    let light_at = cyclic(lights);
    for (l, light) in lights.iter().enumerate() {
        let light = points(*light);
        chunks(
            h,
            |u| scalar(light, u),
            Some(|s: &_, d: &mut _| slice(light, s, d)),
        );
        let mut g = 0;
        while g + 16 <= N {
            let ls: [[f32; 12]; 16] = core::array::from_fn(|j| light_at(l + g + j));
            let us: [[f32; I]; 16] = core::array::from_fn(|j| input(g + j));
            if h.1 {
                let v = x16(
                    points(core::array::from_fn(|c| {
                        f32x16::new(core::array::from_fn(|j| ls[j][c]))
                    })),
                    core::array::from_fn(|d| f32x16::new(core::array::from_fn(|j| us[j][d]))),
                );
                for half in 0..2 {
                    for c in &v {
                        h.floats(&c.to_array()[8 * half..8 * half + 8]);
                    }
                }
            } else {
                for half in 0..2 {
                    let v = x8(
                        points(core::array::from_fn(|c| {
                            f32x8::new(core::array::from_fn(|j| ls[8 * half + j][c]))
                        })),
                        core::array::from_fn(|d| {
                            f32x8::new(core::array::from_fn(|j| us[8 * half + j][d]))
                        }),
                    );
                    for c in v {
                        h.floats(&c.to_array());
                    }
                }
            }
            g += 16;
        }
    }
}

/// Light `k` of a set, cyclically (no index check, no division by zero: the fingerprint runs
/// inside a wasm module that must have no panic path).
fn cyclic(lights: &[[f32; 12]]) -> impl Fn(usize) -> [f32; 12] + '_ {
    move |k| {
        let at = k.checked_rem(lights.len()).unwrap_or(0);
        lights.get(at).copied().unwrap_or([0.0; 12])
    }
}

/// The piece of an [`OfLight`] (a light's solid angle): `scalar` on every light, then the lane forms on 16 lights
/// at a time, lane `j` of group `g` holding light `(g + j) % L`, for `g` in `0..L`.
pub fn of_light(h: &mut Hasher, m: &OfLight) {
    let OfLight {
        lights,
        scalar,
        x8,
        x16,
    } = *m;
    let light_at = cyclic(lights);
    for l in lights {
        h.floats(&[scalar(points(*l))]);
    }
    for g in 0..lights.len() {
        let ls: [[f32; 12]; 16] = core::array::from_fn(|j| light_at(g + j));
        if h.1 {
            let v = x16(points(core::array::from_fn(|c| {
                f32x16::new(core::array::from_fn(|j| ls[j][c]))
            })));
            h.floats(&v.to_array());
        } else {
            for half in 0..2 {
                let v = x8(points(core::array::from_fn(|c| {
                    f32x8::new(core::array::from_fn(|j| ls[8 * half + j][c]))
                })));
                h.floats(&v.to_array());
            }
        }
    }
}

/// The sampling core for one pattern: 4D draws (scalar, 8 and 16 lanes, slices) through a
/// domain path and a split, with the pixel taken from the seed so every lane has its own;
/// then `draw_u32` and `rnd` of the same states; then the same draws of domain 3 of a
/// `new_frame` root (under `Blue<P>` a spatiotemporal slot), without the split.
#[cfg(feature = "sampler")]
fn sampler_pattern<P: warpcore::sampler::Pattern>(h: &mut Hasher) {
    use warpcore::sampler::Sampler;
    sampler_draws::<P>(h, 4);
    for k in 0..64u32 {
        let s = Sampler::<P>::new([k % 641, k >> 20], k ^ 5, k.wrapping_mul(0x9e37_79b9), k)
            .domain(3)
            .split(7, 4, k.wrapping_mul(0x9e37_79b9) & 3);
        for w in s.draw_u32::<4>() {
            h.word(w);
        }
        h.floats(&s.rnd::<4>());
    }
    sampler_draws::<P>(h, 1);
}

/// [`sampler_pattern`]'s 4D draws of domain 3, split `size` ways below it (`size = 1`: no
/// split).
#[cfg(feature = "sampler")]
fn sampler_draws<P: warpcore::sampler::Pattern>(h: &mut Hasher, size: u32) {
    use warpcore::sampler::{Sampler, SamplerX8, SamplerX16};
    // Without a split: the root of `new_frame` (under `Blue<P>` its domain 3 is a slot).
    let root = |index: u32, seed: u32| {
        let pixel = [seed % 641, seed >> 20];
        if size == 1 {
            Sampler::<P>::new_frame(pixel, seed ^ 5, 1, index, seed)
        } else {
            Sampler::<P>::new(pixel, seed ^ 5, index, seed)
        }
    };
    let below = |s: Sampler<P>, index: u32| {
        if size == 1 {
            s
        } else {
            s.split(7, size, index & (size - 1))
        }
    };
    let wide = |index: [u32; 16], seed: [u32; 16]| {
        let lanes: [Sampler<P>; 16] = core::array::from_fn(|j| root(index[j], seed[j]).domain(3));
        (lanes, index.map(|i| i & (size - 1)))
    };
    indexed(
        h,
        |i, s| below(root(i, s).domain(3), i).draw::<4>(),
        |i, s| {
            let (lanes, sub) = wide(pad(i.to_array()), pad(s.to_array()));
            let x8 = SamplerX8::from_lanes(core::array::from_fn(|j| lanes[j]));
            let x8 = if size == 1 {
                x8
            } else {
                x8.split(7, size, u32x8::new(core::array::from_fn(|j| sub[j])))
            };
            x8.draw::<4>()
        },
        |i, s| {
            let (lanes, sub) = wide(i.to_array(), s.to_array());
            let x16 = SamplerX16::from_lanes(lanes);
            let x16 = if size == 1 {
                x16
            } else {
                x16.split(7, size, u32x16::new(sub))
            };
            x16.draw::<4>()
        },
        |start, s, out| root(start, s).domain(3).draw_slice(out),
    );
}

/// Eight lanes padded to sixteen (zeros).
#[cfg(feature = "sampler")]
fn pad(a: [u32; 8]) -> [u32; 16] {
    core::array::from_fn(|j| if j < 8 { a[j] } else { 0 })
}

/// The piece of an [`Indexed`] sequence ([`indexed`] on its four forms).
pub fn indexed_forms<const O: usize>(h: &mut Hasher, s: &Indexed<O>) {
    indexed(h, s.scalar, s.x8, s.x16, s.slice);
}

/// The piece of a [`Quadrant`] map: for each quadrant `q` in `0..4`, [`map`] with `q` fixed
/// (its slice part a loop of the scalar form: the slice form writes four points per input).
pub fn quadrant(h: &mut Hasher, m: &Quadrant) {
    for q in 0..4u32 {
        let each = |u: &[[f32; 2]], o: &mut [[f32; 2]]| {
            for (u, o) in u.iter().zip(o.iter_mut()) {
                *o = (m.scalar)(*u, q);
            }
            u.len().min(o.len())
        };
        chunks(h, |u| (m.scalar)(u, q), Some(each));
        let mut g = 0;
        while g + 16 <= N {
            let group: [[f32; 2]; 16] = core::array::from_fn(|j| input(g + j));
            hash_groups(
                h,
                &group,
                |u| (m.x8)(u, u32x8::splat(q)),
                |u| (m.x16)(u, u32x16::splat(q)),
            );
            g += 16;
        }
    }
}

/// The piece of a [`ToQuadrant`] map: its scalar form on every input, point then quadrant.
pub fn to_quadrant(h: &mut Hasher, m: &ToQuadrant) {
    for i in 0..N {
        let (u, q) = (m.scalar)(input(i));
        h.floats(&u);
        h.word(q);
    }
}

/// Hashes one entry by its shape's piece.
struct Pieces<'a>(&'a mut Hasher);

impl Visit for Pieces<'_> {
    fn map<const I: usize, const O: usize>(&mut self, _: &Entry, m: &Map<I, O>) {
        map(self.0, m);
    }
    fn indexed<const O: usize>(&mut self, _: &Entry, s: &Indexed<O>) {
        indexed_forms(self.0, s);
    }
    fn quadrant(&mut self, _: &Entry, q: &Quadrant) {
        quadrant(self.0, q);
    }
    fn to_quadrant(&mut self, _: &Entry, q: &ToQuadrant) {
        to_quadrant(self.0, q);
    }
    fn light_map<const I: usize, const O: usize>(&mut self, _: &Entry, l: &LightMap<I, O>) {
        light_map(self.0, l);
    }
    fn of_light(&mut self, _: &Entry, l: &OfLight) {
        of_light(self.0, l);
    }
}

/// Hashes an entry on its own: its piece, or its shape's piece. `false` for an entry that has
/// no hash of its own ([`Golden::Tests`], or [`Golden::With`] without a shape).
pub fn entry_hash(e: &Entry, h: &mut Hasher) -> bool {
    match e.golden {
        Golden::Piece(f) | Golden::OwnPiece(f) => f(h),
        Golden::Fingerprint | Golden::Own | Golden::With(_) => {
            if matches!(e.kind, crate::entry::Kind::Other) {
                return false;
            }
            e.visit(&mut Pieces(h));
        }
        Golden::Tests(_) => return false,
    }
    true
}

/// The golden fingerprint: the pieces of the entries that are part of it, in registry order.
pub fn fingerprint() -> u64 {
    fingerprint_with(Hasher::new())
}

/// [`fingerprint`] with the `_x16` forms in place of the `_x8` ones: the same value.
pub fn fingerprint_x16() -> u64 {
    fingerprint_with(Hasher::new_x16())
}

fn fingerprint_with(mut h: Hasher) -> u64 {
    for e in crate::entries() {
        match e.golden {
            Golden::Fingerprint => e.visit(&mut Pieces(&mut h)),
            Golden::Piece(f) => f(&mut h),
            _ => {}
        }
    }
    h.finish()
}

// ---- The pieces of entries whose bits the shapes above do not reach (or did not when the
// ---- golden value was fixed). Each names the entries it covers.

/// `disk::concentric4_inverse` (as [`to_quadrant`]), then the quadrant maps' slice forms
/// (`disk::polar4_slice`, `disk::concentric4_slice`: four points per input) on 9 inputs.
#[cfg(feature = "disk")]
pub fn disk_quadrant_slices(h: &mut Hasher) {
    use warpcore::disk;
    for i in 0..N {
        let (u, q) = disk::concentric4_inverse(input(i));
        h.floats(&u);
        h.word(q);
    }
    let pts: [[f32; 2]; 9] = core::array::from_fn(input);
    let mut out = [[0.0f32; 2]; 35];
    h.word(disk::polar4_slice(&pts, &mut out) as u32);
    for p in out {
        h.floats(&p);
    }
    h.word(disk::concentric4_slice(&pts, &mut out) as u32);
    for p in out {
        h.floats(&p);
    }
}

/// `pmj02bn::raw`: the table words of a few (set, index) pairs, past the ends included.
#[cfg(feature = "pmj02bn")]
pub fn pmj02bn_raw(h: &mut Hasher) {
    for (set, index) in [(0usize, 0usize), (1, 1), (3, 4095), (7, 1 << 30)] {
        for w in warpcore::pmj02bn::raw(set, index) {
            h.word(w);
        }
    }
}

/// `pmj02bn::shuffle` on spread indices, then the table's size (as the C port hashes it).
#[cfg(feature = "pmj02bn")]
pub fn pmj02bn_shuffle(h: &mut Hasher) {
    for i in 0..N as u32 {
        h.word(warpcore::pmj02bn::shuffle(
            i.wrapping_mul(2_654_435_761),
            0xabcd,
        ));
    }
    h.word(warpcore::pmj02bn::POINTS as u32);
    h.word(warpcore::pmj02bn::SETS as u32);
}

/// The sampling core (`sampler::Sampler` and its 8- and 16-lane forms): every pattern.
#[cfg(feature = "sampler")]
pub fn sampler(h: &mut Hasher) {
    use warpcore::sampler::{Pmj02bn, Sobol};
    sampler_pattern::<Pmj02bn>(h);
    sampler_pattern::<Sobol>(h);
    #[cfg(feature = "blue-noise")]
    {
        use warpcore::sampler::Blue;
        sampler_pattern::<Blue<Pmj02bn>>(h);
        sampler_pattern::<Blue<Sobol>>(h);
    }
}

/// `sequence::stratified` for 1, 16, 17 and 1024 strata, as [`indexed`].
#[cfg(feature = "sequence")]
pub fn stratified(h: &mut Hasher) {
    use warpcore::sequence;
    for count in [1u32, 16, 17, 1024] {
        indexed(
            h,
            |i, s| sequence::stratified(i, count, s),
            |i, s| sequence::stratified_x8(i, count, s),
            |i, s| sequence::stratified_x16(i, count, s),
            |st, s, o| sequence::stratified_slice(st, count, s, o),
        );
    }
}

/// The sphere family's densities and texel wrap, input by input:
/// `sphere::equirect_pdf_to_solid_angle`, `sphere::equal_area_pdf_to_solid_angle`,
/// `sphere::cosine_hemisphere_pdf`, `sphere::equal_area_wrap_texel`.
#[cfg(feature = "sphere")]
pub fn sphere_densities(h: &mut Hasher) {
    use warpcore::sphere as s;
    for i in 0..N {
        let d: [f32; 3] = input(i);
        let [p]: [f32; 1] = input(i);
        h.floats(&[
            s::equirect_pdf_to_solid_angle(p, d),
            s::equal_area_pdf_to_solid_angle(p),
            s::cosine_hemisphere_pdf(p),
        ]);
        let t: [f32; 2] = input(i);
        for w in s::equal_area_wrap_texel(t.map(|c| ((c * 64.0) as i32).wrapping_sub(16)), 32) {
            h.word(w);
        }
    }
}

/// The golden 13 x 7 env map: zeros, a negative texel, a NaN and a 10^6:1 bright texel.
#[cfg(feature = "envmap")]
pub fn envmap_weights() -> [f32; 91] {
    core::array::from_fn(|k| match k {
        3 | 40 | 41 => 0.0,
        17 => -2.0,
        60 => f32::NAN,
        77 => 1.0e6,
        _ => unit(k as u32) + 0.01,
    })
}

/// Both env-map distributions built on [`envmap_weights`]: `sample` (scalar and `_x8`) and
/// `pdf` at each sample, marginal-conditional then hierarchical.
#[cfg(feature = "envmap")]
pub fn envmap_distributions(h: &mut Hasher) {
    use warpcore::envmap::{Distribution, Hierarchical, MarginalConditional, Sample};
    fn hash_all<D: Distribution>(h: &mut Hasher, d: &D) {
        let mut hash_sample = |s: Sample| {
            h.floats(&[s.uv[0], s.uv[1], s.pdf, d.pdf(s.uv)]);
            h.word(s.texel[0]);
            h.word(s.texel[1]);
        };
        for i in 0..N {
            hash_sample(d.sample(input(i)));
        }
        for g in (0..N / 8).map(|g| g * 8) {
            let v: [f32x8; 2] = core::array::from_fn(|dim| {
                f32x8::new(core::array::from_fn(|j| input::<2>(g + j)[dim]))
            });
            for s in d.sample_x8(v).to_array() {
                hash_sample(s);
            }
        }
    }
    let weights = envmap_weights();
    let mut storage = [0u32; 4096];
    let len = MarginalConditional::storage_len(13, 7).min(storage.len());
    if let Ok(m) =
        MarginalConditional::new(&weights, 13, 7, storage.get_mut(..len).unwrap_or(&mut []))
    {
        hash_all(h, &m);
    }
    let len = Hierarchical::storage_len(13, 7).min(storage.len());
    if let Ok(t) = Hierarchical::new(&weights, 13, 7, storage.get_mut(..len).unwrap_or(&mut [])) {
        hash_all(h, &t);
    }
}

/// `envmap::image::luminance` on every 3D input.
#[cfg(feature = "envmap")]
pub fn envmap_luminance(h: &mut Hasher) {
    for i in 0..N {
        h.floats(&[warpcore::envmap::image::luminance(input(i))]);
    }
}

/// `envmap::image::equirect_pdf_to_solid_angle` on every 2D input `(pdf, v)`.
#[cfg(feature = "envmap")]
pub fn envmap_equirect_pdf(h: &mut Hasher) {
    for i in 0..N {
        let [p, v]: [f32; 2] = input(i);
        h.floats(&[warpcore::envmap::image::equirect_pdf_to_solid_angle(p, v)]);
    }
}

/// `envmap::image::equirect_solid_angle_weights` on [`envmap_weights`], then
/// `envmap::image::equirect_to_equal_area`: a 13 x 7 RGB image to 8 x 8 equal-area texels,
/// 3 x 3 supersampling.
#[cfg(feature = "envmap")]
pub fn envmap_image(h: &mut Hasher) {
    use warpcore::envmap::image;
    let mut w = envmap_weights();
    let ok = image::equirect_solid_angle_weights(&mut w, 13, 7).is_ok();
    h.floats(&w);
    let rgb: [[f32; 3]; 91] = core::array::from_fn(|k| input(200 + k));
    let mut dst = [[0.0f32; 3]; 64];
    let ok = ok && image::equirect_to_equal_area(&rgb, 13, 7, &mut dst, 8, 3).is_ok();
    for t in &dst {
        h.floats(t);
    }
    if !ok {
        h.word(0xbad);
    }
}

/// The marginal-conditional storage words of [`envmap_weights`] (the hierarchical ones depend
/// on the buffer's address modulo 64, by design).
#[cfg(feature = "envmap")]
pub fn envmap_storage(h: &mut Hasher) {
    use warpcore::envmap::MarginalConditional;
    let n = MarginalConditional::storage_len(13, 7);
    let mut s = [0u32; 4096];
    let s = s.get_mut(..n).unwrap_or(&mut []);
    if MarginalConditional::new(&envmap_weights(), 13, 7, s).is_err() {
        h.word(0xbad);
    }
    for w in s.iter() {
        h.word(u32::from_le(*w));
    }
}

/// `storage_len` of both distributions: 13 x 7 (both) and 4096 x 2048 (hierarchical).
#[cfg(feature = "envmap")]
pub fn envmap_storage_lens(h: &mut Hasher) {
    use warpcore::envmap::{Hierarchical, MarginalConditional};
    h.word(MarginalConditional::storage_len(13, 7) as u32);
    h.word(Hierarchical::storage_len(13, 7) as u32);
    h.word(Hierarchical::storage_len(4096, 2048) as u32);
}

/// A fixed set of 24 lights for the light tree: one- and two-sided area lights, spots and
/// points of different power (two of power 0), spread over a few units.
#[cfg(feature = "lights")]
pub fn light_set() -> [warpcore::lights::LightBounds; 24] {
    core::array::from_fn(|k| {
        let [x, y, z, s, a0, a1, a2, q] = input::<8>(1000 + k);
        let c = [x * 8.0 - 4.0, y * 4.0 - 2.0, z * 2.0];
        let h = s * 0.25;
        let (cos_theta_o, cos_theta_e, two_sided) = match k % 4 {
            0 => (1.0, 0.0, false),
            1 => (1.0, 0.0, true),
            2 => (0.8, 0.6, false),
            _ => (-1.0, 0.0, false),
        };
        warpcore::lights::LightBounds {
            min: [c[0] - h, c[1] - h, c[2]],
            max: [c[0] + h, c[1] + h, c[2] + h],
            power: if k % 11 == 5 { 0.0 } else { 0.1 + q * 10.0 },
            axis: [a0 - 0.5, a1 - 0.5, a2 - 0.25],
            cos_theta_o,
            cos_theta_e,
            two_sided,
        }
    })
}

/// Hashes a light-selection storage of `len` words that `build` writes into a buffer of `W`
/// words: the length, then the words (in their storage order, little-endian), or `0xbad` when
/// the build fails (or `len > W`); returns the buffer of a build that succeeded.
#[cfg(feature = "lights")]
fn stored<const W: usize>(
    h: &mut Hasher,
    len: usize,
    build: impl FnOnce(&mut [u32]) -> bool,
) -> Option<[u32; W]> {
    h.word(len as u32);
    let mut s = [0u32; W];
    if !s.get_mut(..len).is_some_and(build) {
        h.word(0xbad);
        return None;
    }
    for w in s.get(..len).unwrap_or(&[]) {
        h.word(u32::from_le(*w));
    }
    Some(s)
}

/// `lights::LightTree`: the storage words of [`light_set`], then `sample` and `pmf` at 64
/// shading points (normals, media and special values among them).
#[cfg(feature = "lights")]
pub fn lights_tree(h: &mut Hasher) {
    use warpcore::lights::LightTree;
    let lights = light_set();
    let n = LightTree::storage_len(lights.len());
    let Some(s) = stored::<2048>(h, n, |s| LightTree::new(&lights, s).is_ok()) else {
        return;
    };
    let Ok(tree) = LightTree::from_storage(&s) else {
        return;
    };
    for k in 0..64usize {
        let [x, y, z, nx, ny, nz, u] = input::<7>(2000 + k);
        let p = [x * 10.0 - 5.0, y * 6.0 - 3.0, z * 4.0 - 1.0];
        let nrm = if k % 3 == 0 {
            [0.0; 3]
        } else {
            [nx - 0.5, ny - 0.5, nz - 0.5]
        };
        let (i, q) = tree.sample(p, nrm, u).unwrap_or((u32::MAX, 0.0));
        h.word(i);
        h.floats(&[q, tree.pmf(p, nrm, (k % 25) as u32)]);
    }
}

/// `lights::AliasTable`: the storage words of 97 weights (every seventh zero, the others over
/// five orders of magnitude), then `sample` at the [`N`] one-dimensional inputs (special values
/// among them: NaN, infinities, negatives, 1) and `pmf` of every index and one past the end.
#[cfg(feature = "lights")]
pub fn lights_alias(h: &mut Hasher) {
    use warpcore::lights::AliasTable;
    const LIGHTS: usize = 97;
    let weights: [f32; LIGHTS] = core::array::from_fn(|k| {
        let [a, b] = input::<2>(3000 + k);
        if k % 7 == 3 {
            0.0
        } else if k % 5 == 0 {
            a * 1000.0 + b
        } else {
            a * 0.01 + b * 0.5
        }
    });
    let n = AliasTable::storage_len(LIGHTS);
    let Some(s) = stored::<512>(h, n, |s| AliasTable::new(&weights, s).is_ok()) else {
        return;
    };
    let Ok(table) = AliasTable::from_storage(&s) else {
        return;
    };
    for i in 0..N {
        let [u] = input::<1>(i);
        let (k, p) = table.sample(u);
        h.word(k);
        h.floats(&[p]);
    }
    for k in 0..=LIGHTS as u32 {
        h.floats(&[table.pmf(k)]);
    }
}
