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

use crate::lanes::UintLane;

/// Tile side in pixels.
pub const TILE: u32 = 64;

/// Bytes of blue-noise tables in this build (two base patterns).
pub const TABLE_BYTES: usize = 2 * 4 * (TILE * TILE) as usize;

#[repr(C, align(64))]
struct Aligned<T>(T);

static SOBOL_TILE: Aligned<[u8; 4 * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_sobol_64.bin"));
static PMJ02BN_TILE: Aligned<[u8; 4 * (TILE * TILE) as usize]> =
    Aligned(*include_bytes!("../tables/blue_pmj02bn_64.bin"));

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
