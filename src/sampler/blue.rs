//! Screen-space blue noise: per-pixel keys from a tile optimised offline by `tools/bluegen`.
//!
//! Each base pattern has a tile of `TILE x TILE` 32-bit keys (little-endian, row-major). A
//! pixel's pattern for a domain is the base pattern keyed by the tile entry at the pixel's
//! position, moved by a toroidal shift and one of the eight symmetries of the square, both
//! drawn from the domain hash (which holds the seed, the frame and the domain path, never the
//! pixel): every domain and every frame sees the same optimised arrangement, shifted and
//! turned, so each is blue noise on its own, and different domains of one pixel get
//! different keys (they coincide for all pixels at once only when two domains draw the same
//! shift and symmetry: probability `1 / (8 TILE^2)` per pair of domains).
//!
//! The tiles are the output of `tools/bluegen` (CI regenerates them and compares the bytes;
//! `src/tables/blue_MANIFEST` holds the command): keys chosen from a pool so that the errors
//! of neighbouring pixels cancel under a Gaussian blur, for half-plane integrands at 1, 2, 4,
//! 8 and 16 samples per pixel at once, through the library's own points
//! (`Sampler::<P>::from_domain_hash`). `report/src/bluenoise.rs` measures the result and
//! `report/tests/blue_noise.rs` asserts it. A pmj02bn key also picks the table set: the pmj02bn tile
//! is optimised for the default four sets (`pmj02bn-4-sets`); a build with one set draws other
//! points for the same keys, still nets, but with nearly white error across pixels.

use crate::lanes::UintLane;

/// Tile side in pixels.
pub const TILE: u32 = 64;

/// Spatiotemporal domain slots: the root's domains `0..SLOTS` of a `Blue<P>` sampler.
pub const SLOTS: usize = 6;

/// The fixed scramble key of each slot: every pixel of slot `s` draws `P` keyed by
/// `SLOT_KEYS[s]` at its own index offset (the slot tile), the arrangement `tools/bluegen`
/// optimises. Arbitrary odd constants.
pub const SLOT_KEYS: [u32; SLOTS] = [
    0x8a2f_0c4b, 0x3d6e_91a7, 0xc51b_7e23, 0x6f94_d2c9, 0x1be7_4a35, 0xe403_b86d,
];

/// Bytes of blue-noise tables in this build (two base patterns): per pattern a tile of
/// 32-bit keys and [`SLOTS`] tiles of 16-bit index offsets.
pub const TABLE_BYTES: usize = 2 * (4 + 2 * SLOTS) * (TILE * TILE) as usize;

#[repr(C, align(64))]
struct Aligned<T>(T);

static SOBOL_TILE: Aligned<[u8; 4 * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_sobol_64.bin"));
static PMJ02BN_TILE: Aligned<[u8; 4 * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_pmj02bn_64.bin"));
static SOBOL_SLOTS: Aligned<[u8; 2 * SLOTS * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_slots_sobol_64.bin"));
static PMJ02BN_SLOTS: Aligned<[u8; 2 * SLOTS * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_slots_pmj02bn_64.bin"));

/// The key tile of a base pattern as words (decoded little endian on every target).
#[inline(always)]
fn tile(base: u8) -> &'static [[u8; 4]; (TILE * TILE) as usize] {
    let bytes = if base == super::SOBOL {
        &SOBOL_TILE.0
    } else {
        &PMJ02BN_TILE.0
    };
    bytemuck::cast_ref(bytes)
}

/// The tile position of `pixel` (`x | y << 16`) under the domain's shift and symmetry.
#[inline(always)]
pub(crate) fn position<U: UintLane>(pixel: U, domain: U) -> U {
    let m = U::splat(TILE - 1);
    let (x, y) = (pixel & m, pixel.shr(16) & m);
    // Symmetry: bit 29 transposes, bits 30 and 31 flip x and y (x ^ (TILE - 1) = TILE - 1 - x).
    let t = (domain.shr(29) & U::splat(1)).simd_eq(U::splat(1));
    let (x, y) = (U::select(t, y, x), U::select(t, x, y));
    let fx = U::splat(0) - (domain.shr(30) & U::splat(1));
    let fy = U::splat(0) - domain.shr(31);
    let x = (x ^ (fx & m)) + domain;
    let y = (y ^ (fy & m)) + domain.shr(12);
    (y & m) * U::splat(TILE) + (x & m)
}

/// The key of `pixel` in `domain` for base pattern `base`.
#[inline(always)]
pub(crate) fn key<U: UintLane>(base: u8, pixel: U, domain: U) -> U {
    let words = tile(base);
    let [k, _] = position(pixel, domain)
        .gather_pairs(|i| [u32::from_le_bytes(words[i as usize & (words.len() - 1)]), 0]);
    k
}

#[cfg(test)]
mod tests {
    use super::super::{Base, Blue, Pattern, Pmj02bn, Sampler, Sobol};
    use super::TILE;

    /// The key a `Blue<P>` pixel reads, worked from the documented layout alone: bit 29 of the
    /// domain hash transposes, bits 30 and 31 flip x and y, then the hash shifts x by its low
    /// bits and y by the bits from 12 up; the tile is row-major little-endian words.
    fn tile_key_at<P: Base>(pixel: [u32; 2], domain: u32) -> u32 {
        let bytes: &[u8] = if P::ID == super::super::SOBOL {
            include_bytes!("../tables/blue_sobol_64.bin")
        } else {
            include_bytes!("../tables/blue_pmj02bn_64.bin")
        };
        let (mut x, mut y) = (pixel[0] % TILE, pixel[1] % TILE);
        if domain >> 29 & 1 == 1 {
            (x, y) = (y, x);
        }
        if domain >> 30 & 1 == 1 {
            x = TILE - 1 - x;
        }
        if domain >> 31 == 1 {
            y = TILE - 1 - y;
        }
        let x = x.wrapping_add(domain) % TILE;
        let y = y.wrapping_add(domain >> 12) % TILE;
        let at = 4 * (y * TILE + x) as usize;
        u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]])
    }

    /// A `Blue<P>` pixel draws exactly `P`'s points keyed by its tile entry, i.e. what
    /// `tools/bluegen` optimises through `Sampler::<P>::from_domain_hash`: for any pixel,
    /// frame, seed, domain path and index.
    fn blue_draws_the_keyed_base_pattern<P: Base>()
    where
        Blue<P>: Pattern,
    {
        let mut r = 0x2545_f491_4f6c_dd1du64;
        let mut next = || {
            r ^= r << 13;
            r ^= r >> 7;
            r ^= r << 17;
            (r >> 32) as u32
        };
        for trial in 0..2000 {
            let pixel = if trial < 8 {
                [trial, u32::MAX - trial]
            } else {
                [next(), next()]
            };
            let (frame, seed, index) = (next(), next(), next() >> (trial % 32));
            let root = Sampler::<Blue<P>>::new(pixel, frame, index, seed);
            let (a, b) = (next(), next());
            for s in [
                root,
                root.domain(a),
                root.domain(a).domain(b),
                root.split(a, 4, 3).domain(b),
            ] {
                // The tile position uses the pixel modulo 2^16 (then modulo the tile).
                let p = [pixel[0] & 0xffff, pixel[1] & 0xffff];
                let key = tile_key_at::<P>(p, s.state.domain.0);
                let base = Sampler::<P>::from_domain_hash(key, s.index());
                assert_eq!(s.draw_u32::<4>(), base.draw_u32::<4>(), "pixel {pixel:?}");
                assert_eq!(s.draw::<2>(), base.draw::<2>());
            }
        }
    }

    #[test]
    fn blue_sobol_draws_sobol_keyed_by_the_tile() {
        blue_draws_the_keyed_base_pattern::<Sobol>();
    }

    #[test]
    fn blue_pmj02bn_draws_pmj02bn_keyed_by_the_tile() {
        blue_draws_the_keyed_base_pattern::<Pmj02bn>();
    }
}
