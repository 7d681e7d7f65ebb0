//! The Sobol' samplers of Burley 2020's comparison ("Practical Hash-based Owen Scrambling",
//! JCGT 9(4), Figure 1) that warpcore and the peers do not provide, written here from the
//! papers' definitions (no code copied):
//!
//! * [`LaineKarras`]: Laine and Karras 2011 ("Stratified sampling for stochastic
//!   transparency") as published: every dimension of the path is the pixel's van der Corput
//!   sequence (Sobol' dimension 0) in the same sample order, its value scrambled by their
//!   hash (the "LK permutation": add the seed, then four xors with even multiples, so that
//!   each bit depends on the bits below it only) applied to the bit-reversed word, an
//!   approximation of nested uniform (Owen) scrambling; seeds per pixel and dimension.
//!   Stratified in each dimension alone, but the dimensions share one index order, so their
//!   leading digits are coupled. [`LkShuffled`] adds Burley's index shuffle per dimension
//!   (the same hash on the index): what the shuffle alone buys. Burley's own method is that
//!   hash with 4D Sobol' sets (his crate, `sobol_burley`).
//! * [`SobolRds`]: one Sobol' sequence per pixel over all the path's dimensions in order
//!   (no padding), each dimension random-digit scrambled (xor with a random word per pixel
//!   and dimension; Kollig and Keller 2002).
//! * [`SobolEnum`]: one Sobol'-RDS sequence over the whole image plane (scrambles per frame,
//!   not per pixel): dimensions 0 and 1 pick the pixel on a 64 x 64 grid, and sample `j` of
//!   a pixel is the `j`-th point of the sequence inside it, found by solving the first two
//!   dimensions' digits for the index (Grünschloß, Raab and Keller 2012, "Enumerating
//!   quasi-Monte Carlo point sequences in elementary intervals"; pbrt-v3's `SobolSampler`).
//!   Images of other sizes read the grid's pixels modulo 64 (each pixel's points, which is
//!   what its error depends on, are the same).
//!
//! Dimensions: domain 0 (pixel) is Sobol' dimensions 0-1, domain 1 (lens) 2-3, domain
//! `2 + d` dimensions `4 + 4d ..= 7 + 4d`, the roulette's domains
//! ([`ROULETTE_DOMAIN`]` + d`) dimension `24 + d`. Direction numbers: Joe and Kuo 2008
//! ("Constructing Sobol sequences with better two-dimensional projections"), the first 32
//! rows of `new-joe-kuo-6` (Copyright (c) 2008, Frances Y. Kuo and Stephen Joe; BSD
//! 3-clause licence, whose text ships with the `sobol_burley` crate as
//! `licenses/JOE_KUO.txt`).

use super::samplers::{PathSampler, ROULETTE_DOMAIN, hash32};
use std::sync::OnceLock;

/// Primitive polynomial degree `s`, its middle coefficients `a`, and `m_1 .. m_s`, for
/// Sobol' dimensions 1..=32 (dimension 0 is van der Corput's).
const JOE_KUO: [(u32, u32, &[u32]); 32] = [
    (1, 0, &[1]),
    (2, 1, &[1, 3]),
    (3, 1, &[1, 3, 1]),
    (3, 2, &[1, 1, 1]),
    (4, 1, &[1, 1, 3, 3]),
    (4, 4, &[1, 3, 5, 13]),
    (5, 2, &[1, 1, 5, 5, 17]),
    (5, 4, &[1, 1, 5, 5, 5]),
    (5, 7, &[1, 1, 7, 11, 19]),
    (5, 11, &[1, 1, 5, 1, 1]),
    (5, 13, &[1, 1, 1, 3, 11]),
    (5, 14, &[1, 3, 5, 5, 31]),
    (6, 1, &[1, 3, 3, 9, 7, 49]),
    (6, 13, &[1, 1, 1, 15, 21, 21]),
    (6, 16, &[1, 3, 1, 13, 27, 49]),
    (6, 19, &[1, 1, 1, 15, 7, 5]),
    (6, 22, &[1, 3, 1, 15, 13, 25]),
    (6, 25, &[1, 1, 5, 5, 19, 61]),
    (7, 1, &[1, 3, 7, 11, 23, 15, 103]),
    (7, 4, &[1, 3, 7, 13, 13, 15, 69]),
    (7, 7, &[1, 1, 3, 13, 7, 35, 63]),
    (7, 8, &[1, 3, 5, 9, 1, 25, 53]),
    (7, 14, &[1, 3, 1, 13, 9, 35, 107]),
    (7, 19, &[1, 3, 1, 5, 27, 61, 31]),
    (7, 21, &[1, 1, 5, 11, 19, 41, 61]),
    (7, 28, &[1, 3, 5, 3, 3, 13, 69]),
    (7, 31, &[1, 1, 7, 13, 1, 19, 1]),
    (7, 32, &[1, 3, 7, 5, 13, 19, 59]),
    (7, 37, &[1, 1, 3, 9, 25, 29, 41]),
    (7, 41, &[1, 3, 5, 13, 23, 1, 55]),
    (7, 42, &[1, 3, 7, 3, 13, 59, 17]),
    (7, 50, &[1, 3, 1, 3, 5, 53, 69]),
];

/// Sobol' dimensions available.
pub const DIMS: usize = 33;

/// The direction numbers `v[d][k]` (bit `k` of the index), 32 bits.
fn directions() -> &'static [[u32; 32]; DIMS] {
    static V: OnceLock<[[u32; 32]; DIMS]> = OnceLock::new();
    V.get_or_init(|| {
        let mut v = [[0u32; 32]; DIMS];
        for k in 0..32 {
            v[0][k] = 1 << (31 - k);
        }
        for (d, &(s, a, m)) in JOE_KUO.iter().enumerate() {
            let s = s as usize;
            let row = &mut v[d + 1];
            for k in 0..s {
                row[k] = m[k] << (31 - k);
            }
            for k in s..32 {
                let mut x = row[k - s] ^ (row[k - s] >> s);
                for j in 1..s {
                    if (a >> (s - 1 - j)) & 1 == 1 {
                        x ^= row[k - j];
                    }
                }
                row[k] = x;
            }
        }
        v
    })
}

/// Dimension `dim` of Sobol' point `i`, unscrambled, as a 0.32 fixed-point word.
pub fn sobol(i: u32, dim: usize) -> u32 {
    let v = &directions()[dim];
    let mut x = 0;
    let mut i = i;
    let mut k = 0;
    while i != 0 {
        if i & 1 == 1 {
            x ^= v[k];
        }
        i >>= 1;
        k += 1;
    }
    x
}

/// Laine and Karras' hash: each output bit depends on the input bits at and below it.
pub fn lk_hash(mut x: u32, seed: u32) -> u32 {
    x = x.wrapping_add(seed);
    for c in [0x6c50_b47c, 0xb82f_1e52, 0xc7af_e638, 0x8d22_f6e6u32] {
        x ^= x.wrapping_mul(c);
    }
    x
}

/// The hash on the bit-reversed word: each bit then depends on the bits above it (a nested
/// scramble of the leading digits).
pub fn lk_scramble(x: u32, seed: u32) -> u32 {
    lk_hash(x.reverse_bits(), seed).reverse_bits()
}

fn unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// The first Sobol' dimension of `domain` (see the module docs).
fn first_dim(domain: u32) -> usize {
    match domain {
        0 | 1 => 2 * domain as usize,
        d if d >= ROULETTE_DOMAIN => 24 + (d - ROULETTE_DOMAIN) as usize,
        d => 4 + 4 * (d as usize - 2),
    }
    .min(DIMS - 4)
}

/// The samplers whose every pixel has its own sequence, keyed by pixel and render, by
/// `MODE`: [`SOBOL_RDS`], [`LAINE_KARRAS`] or [`LK_SHUFFLED`].
pub struct PerPixel<const MODE: u8>;

/// [`PerPixel`] mode: one random-digit-scrambled Sobol' sequence, all dimensions in order.
pub const SOBOL_RDS: u8 = 0;
/// [`PerPixel`] mode: Laine and Karras 2011 as published, every dimension the pixel's van
/// der Corput sequence in the same sample order, scrambled by its own seed (no index shuffle).
pub const LAINE_KARRAS: u8 = 1;
/// [`PerPixel`] mode: as [`LAINE_KARRAS`] with each dimension's index order shuffled by the
/// same hash (Burley 2020's shuffle applied to 1D padding).
pub const LK_SHUFFLED: u8 = 2;

/// Laine-Karras as published: scrambled van der Corput per dimension, one index order.
pub type LaineKarras = PerPixel<LAINE_KARRAS>;

/// Laine-Karras with Burley's index shuffle per dimension (1D padding).
pub type LkShuffled = PerPixel<LK_SHUFFLED>;

/// Sobol'-RDS: one random-digit-scrambled Sobol' sequence per pixel, all dimensions in order.
pub type SobolRds = PerPixel<SOBOL_RDS>;

impl<const MODE: u8> PerPixel<MODE> {
    /// The `N` dimensions of `domain` of sample `s` (index, key).
    fn dims<const N: usize>(s: &(u32, u32), domain: u32) -> [f32; N] {
        let first = first_dim(domain);
        if MODE == SOBOL_RDS {
            return rds(s.0, first, s.1);
        }
        std::array::from_fn(|k| {
            let key = hash32(s.1 ^ hash32((first + k) as u32 ^ 0x51ed_270b));
            let i = if MODE == LK_SHUFFLED {
                lk_scramble(s.0, hash32(key ^ 0xa511_e9b3))
            } else {
                s.0
            };
            unit(lk_scramble(i.reverse_bits(), hash32(key ^ 0x63d8_3595)))
        })
    }
}

impl<const MODE: u8> PathSampler for PerPixel<MODE> {
    /// (index, key of the pixel and render)
    type Sample = (u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> (u32, u32) {
        let salt = if MODE == SOBOL_RDS {
            0x0bad_5eed
        } else {
            0x1a2b_3c4d
        };
        (
            index,
            hash32(pixel[0] ^ hash32(pixel[1] ^ hash32(seed ^ salt))),
        )
    }
    fn draw2(&self, s: &(u32, u32), domain: u32) -> [f32; 2] {
        Self::dims(s, domain)
    }
    fn draw4(&self, s: &(u32, u32), domain: u32) -> [f32; 4] {
        Self::dims(s, domain)
    }
    fn rnd(&self, s: &(u32, u32), domain: u32) -> f32 {
        unit(hash32(s.1 ^ hash32(s.0 ^ hash32(0x100 + domain))))
    }
}

/// The `N` dimensions from `first` of point `i`, each xor-scrambled by `key` and its
/// dimension.
fn rds<const N: usize>(i: u32, first: usize, key: u32) -> [f32; N] {
    std::array::from_fn(|k| {
        let d = first + k;
        unit(sobol(i, d) ^ hash32(key ^ hash32(d as u32 ^ 0x2f6b_4a17)))
    })
}

/// log2 of the grid [`SobolEnum`] enumerates over.
pub const ENUM_BITS: u32 = 6;

/// Sobol'-enum: one Sobol'-RDS sequence over the image plane (see the module docs).
pub struct SobolEnum {
    /// `inv[c] = b`: the index bits `6..12` whose dimension-1 contribution has leading
    /// digits `c`.
    inv: [u32; 1 << ENUM_BITS],
}

impl Default for SobolEnum {
    fn default() -> Self {
        Self::new()
    }
}

impl SobolEnum {
    pub fn new() -> SobolEnum {
        let mut inv = [u32::MAX; 1 << ENUM_BITS];
        for b in 0..1u32 << ENUM_BITS {
            inv[Self::lead(sobol(b << ENUM_BITS, 1)) as usize] = b;
        }
        debug_assert!(inv.iter().all(|&b| b != u32::MAX));
        SobolEnum { inv }
    }

    fn lead(x: u32) -> u32 {
        x >> (32 - ENUM_BITS)
    }

    /// The frame's scrambles of dimensions 0 and 1.
    fn shifts(key: u32) -> [u32; 2] {
        [hash32(key ^ 0x3c6e_f372), hash32(key ^ 0x7f4a_7c15)]
    }

    /// The index of the `j`-th point of the sequence in grid cell `cell`.
    pub fn index(&self, cell: [u32; 2], j: u32) -> u32 {
        let a = (cell[0].reverse_bits()) >> (32 - ENUM_BITS);
        let head = (j << (2 * ENUM_BITS)) | a;
        let b = self.inv[(cell[1] ^ Self::lead(sobol(head, 1))) as usize];
        head | (b << ENUM_BITS)
    }
}

impl PathSampler for SobolEnum {
    /// (index in the image-plane sequence, key of the render)
    type Sample = (u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> (u32, u32) {
        let key = hash32(seed ^ 0x5eed_e4e4);
        let sh = Self::shifts(key);
        let mask = (1 << ENUM_BITS) - 1;
        let cell = [0, 1].map(|c| (pixel[c] & mask) ^ Self::lead(sh[c]));
        (self.index(cell, index), key)
    }
    fn draw2(&self, s: &(u32, u32), domain: u32) -> [f32; 2] {
        if domain == 0 {
            let sh = Self::shifts(s.1);
            return [0, 1].map(|c| unit((sobol(s.0, c) ^ sh[c]) << ENUM_BITS));
        }
        rds(s.0, first_dim(domain), s.1)
    }
    fn draw4(&self, s: &(u32, u32), domain: u32) -> [f32; 4] {
        rds(s.0, first_dim(domain), s.1)
    }
    fn rnd(&self, s: &(u32, u32), domain: u32) -> f32 {
        PerPixel::<SOBOL_RDS>.rnd(s, domain)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const RDS: SobolRds = PerPixel;

    /// Whether `pts` (0.32 words) put exactly one point in every elementary interval of
    /// area `1 / pts.len()` (a `(0, m, 2)`-net for `pts.len() = 2^m`).
    fn is_02_net(pts: &[[u32; 2]]) -> bool {
        let m = pts.len().trailing_zeros();
        (0..=m).all(|a| {
            let mut seen = vec![false; pts.len()];
            pts.iter().all(|p| {
                let cell = ((p[0] as u64 >> (32 - a)) << (m - a)) | (p[1] as u64 >> (32 - (m - a)));
                let cell = cell as usize;
                !std::mem::replace(&mut seen[cell], true)
            })
        })
    }

    fn word(x: f32) -> u32 {
        (x as f64 * 4294967296.0) as u32
    }

    /// Every dimension of the generated Sobol' sequence is a `(0, 1)`-sequence (the first
    /// `2^m` points one per interval of `2^-m`), and dimensions 0 and 1 form a
    /// `(0, 2)`-sequence: a wrong direction number breaks one of these.
    #[test]
    fn sobol_dimensions_are_stratified() {
        for m in 0..=10u32 {
            let n = 1u32 << m;
            for d in 0..DIMS {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let c = if m == 0 {
                        0
                    } else {
                        (sobol(i, d) >> (32 - m)) as usize
                    };
                    assert!(!std::mem::replace(&mut seen[c], true), "dim {d}, m {m}");
                }
            }
            let pts: Vec<[u32; 2]> = (0..n).map(|i| [sobol(i, 0), sobol(i, 1)]).collect();
            assert!(is_02_net(&pts), "m {m}");
        }
        // Joe and Kuo's dimension 2 (ours 1) from its polynomial: v_1 = 1/2, v_2 = 3/4.
        assert_eq!(sobol(1, 1), 1 << 31);
        assert_eq!(sobol(2, 1), 3 << 30);
    }

    /// Sobol'-RDS's pixel dimensions are `(0, m, 2)`-nets at every power of two, for any
    /// pixel and seed (xor scrambling keeps nets); both Laine-Karras variants stratify every
    /// dimension alone (shuffling and nested scrambling keep the van der Corput sequence's
    /// `(0, 1)` property), and their pixel pair is not a net in general.
    #[test]
    fn rds_and_laine_karras_keep_their_stratification() {
        fn check<const MODE: u8>(lk: PerPixel<MODE>) {
            let mut lk_nets = 0;
            for (pixel, seed) in [([0u32, 0u32], 1u32), ([5, 9], 77), ([31, 2], 0xdead)] {
                for m in 0..=8u32 {
                    let n = 1u32 << m;
                    let rds: Vec<[u32; 2]> = (0..n)
                        .map(|i| RDS.draw2(&RDS.sample(pixel, i, n, seed), 0).map(word))
                        .collect();
                    assert!(is_02_net(&rds), "rds m {m}");
                    let pts: Vec<[f32; 4]> = (0..n)
                        .map(|i| lk.draw4(&lk.sample(pixel, i, n, seed), 3))
                        .collect();
                    for d in 0..4 {
                        let mut seen = vec![false; n as usize];
                        for p in &pts {
                            let c = (p[d] * n as f32) as usize;
                            assert!(!std::mem::replace(&mut seen[c], true), "dim {d}, m {m}");
                        }
                    }
                    let pair: Vec<[u32; 2]> =
                        pts.iter().map(|p| [word(p[0]), word(p[1])]).collect();
                    lk_nets += is_02_net(&pair) as u32;
                }
            }
            assert!(lk_nets < 27, "mode {MODE}: every pair a net");
        }
        check(PerPixel::<LAINE_KARRAS>);
        check(PerPixel::<LK_SHUFFLED>);
    }

    /// Laine-Karras as published walks every dimension in the same index order: the
    /// leading digit of each dimension is the index's lowest bit xor a per-dimension
    /// constant, so two dimensions' halves agree for every sample or for none. The shuffled
    /// variant breaks that coupling.
    #[test]
    fn laine_karras_dimensions_share_one_index_order() {
        let lk = PerPixel::<LAINE_KARRAS>;
        let shuffled = PerPixel::<LK_SHUFFLED>;
        let mut shuffled_coupled = 0;
        for (pixel, seed) in [([0u32, 0u32], 1u32), ([5, 9], 77), ([31, 2], 0xdead)] {
            for domain in 2..6 {
                let agree = |p: [f32; 4]| (p[0] < 0.5) == (p[2] < 0.5);
                let a: Vec<bool> = (0..64)
                    .map(|i| agree(lk.draw4(&lk.sample(pixel, i, 64, seed), domain)))
                    .collect();
                assert!(a.iter().all(|&x| x == a[0]), "{pixel:?} {seed} {domain}");
                let b: Vec<bool> = (0..64)
                    .map(|i| agree(shuffled.draw4(&shuffled.sample(pixel, i, 64, seed), domain)))
                    .collect();
                shuffled_coupled += b.iter().all(|&x| x == b[0]) as u32;
            }
        }
        // Independent shuffles couple by chance with probability about 2^-63 per case.
        assert_eq!(shuffled_coupled, 0);
    }

    /// Sobol'-enum's sample `j` of a pixel is a distinct point of the image-plane sequence
    /// inside that pixel, and a pixel's first `2^m` points form a `(0, m, 2)`-net in it.
    #[test]
    fn enumeration_finds_the_pixels_points() {
        let e = SobolEnum::new();
        for (pixel, seed) in [([0u32, 0u32], 3u32), ([17, 40], 9), ([63, 63], 0xbeef)] {
            let mut idx = Vec::new();
            let mut pts = Vec::new();
            for j in 0..256 {
                let s = e.sample(pixel, j, 256, seed);
                let sh = SobolEnum::shifts(s.1);
                for c in 0..2 {
                    assert_eq!(
                        SobolEnum::lead(sobol(s.0, c) ^ sh[c]),
                        pixel[c],
                        "pixel {pixel:?} sample {j}"
                    );
                }
                idx.push(s.0);
                pts.push(e.draw2(&s, 0).map(word));
            }
            idx.sort_unstable();
            idx.dedup();
            assert_eq!(idx.len(), 256);
            for m in 0..=8 {
                assert!(is_02_net(&pts[..1 << m]), "pixel {pixel:?}, m {m}");
            }
        }
    }
}
