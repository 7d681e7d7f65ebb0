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
//! **Spatiotemporal slots.** Below a root made by `Sampler::new_frame`, the domains
//! `0..SLOTS` are slots: all pixels of slot `s` draw `P` keyed by [`SLOT_KEYS`]`[s]` (one
//! scramble for the whole screen), at the sample number XOR a 16-bit offset read from the
//! slot's tile at the pixel's (shifted, turned) position. A pixel's frames are then an
//! aligned block of one sequence (a net), and the offsets are optimised so that each of
//! frames 0..32 is blue noise across pixels. The domain hash carries a two-bit tag (low
//! bits): 2 for such a root, 1 for a slot (the slot in bits 2..4), 0 for every other
//! `Blue<P>` domain; the tile shift reads bits 6 and up.
//!
//! The tiles are the output of `tools/bluegen` (CI regenerates them and compares the bytes;
//! `src/tables/blue_MANIFEST` holds the command): keys chosen from a pool so that the errors
//! of neighbouring pixels cancel under a Gaussian blur, for half-plane integrands at 1, 2, 4,
//! 8 and 16 samples per pixel at once, through the library's own points
//! (`Sampler::<P>::from_domain_hash`). `report/src/bluenoise.rs` measures the result and
//! `report/tests/blue_noise.rs` asserts it. A pmj02bn key also picks the table set: the pmj02bn tile
//! is optimised for the default four sets (`pmj02bn-4-sets`); a build with one set draws other
//! points for the same keys, still nets, but with nearly white error across pixels.

use super::{TAG_MASK, TAG_ROOT, TAG_SLOT};
use crate::lanes::UintLane;

/// Tile side in pixels.
pub const TILE: u32 = 64;

/// Spatiotemporal domain slots: the domains `0..SLOTS` of a `Blue<P>` `new_frame` root.
pub const SLOTS: usize = 6;

/// The fixed scramble key of each slot: every pixel of slot `s` draws `P` keyed by
/// `SLOT_KEYS[s]` at its own index offset (the slot tile), the arrangement `tools/bluegen`
/// optimises. Arbitrary odd constants.
pub const SLOT_KEYS: [u32; SLOTS] = [
    0x8a2f_0c4b,
    0x3d6e_91a7,
    0xc51b_7e23,
    0x6f94_d2c9,
    0x1be7_4a35,
    0xe403_b86d,
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

/// Words of one tile.
type Tile<W> = [W; (TILE * TILE) as usize];

/// The key tile (little-endian words) and the slot offset tiles (little-endian halves) of a
/// base pattern.
#[inline(always)]
fn tiles(base: u8) -> (&'static Tile<[u8; 4]>, &'static [Tile<[u8; 2]>; SLOTS]) {
    let (keys, slots) = if base == super::SOBOL {
        (&SOBOL_TILE.0, &SOBOL_SLOTS.0)
    } else {
        (&PMJ02BN_TILE.0, &PMJ02BN_SLOTS.0)
    };
    (bytemuck::cast_ref(keys), bytemuck::cast_ref(slots))
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
    // Shift: bits 6..11 move x, bits 12..17 move y (bits 0..4 hold the tag and the slot).
    let x = (x ^ (fx & m)) + domain.shr(6);
    let y = (y ^ (fy & m)) + domain.shr(12);
    (y & m) * U::splat(TILE) + (x & m)
}

/// The domain hash `h` of the child `key` of a `Blue<P>` domain hash `parent`, tagged: the
/// root's children `0..SLOTS` are its slots, every other child is an other domain.
#[inline(always)]
pub(crate) fn tag_child<U: UintLane>(parent: U, key: u32, h: U) -> U {
    let other = h & U::splat(!TAG_MASK);
    if key as usize >= SLOTS {
        return other;
    }
    let root = (parent & U::splat(TAG_MASK)).simd_eq(U::splat(TAG_ROOT));
    let slot = (h & U::splat(!0x1f)) | U::splat(TAG_SLOT | key << 2);
    U::select(root, slot, other)
}

/// The draw's key and index of `pixel` in `domain` at `index` for base pattern `base`: in a
/// slot, the slot's key at the index XOR the pixel's offset; elsewhere the pixel's tile key
/// at the index itself.
#[inline(always)]
pub(crate) fn keyed<U: UintLane>(base: u8, pixel: U, domain: U, index: U) -> (U, U) {
    let (keys, slots) = tiles(base);
    let p = position(pixel, domain);
    // The slot (0..8) in bits 12..14 and whether it is one in bit 15, next to the position.
    let is_slot = (domain & U::splat(TAG_MASK)).simd_eq(U::splat(TAG_SLOT));
    let slot = domain.shr(2) & U::splat(7);
    let code = p | slot.shl(12) | U::select(is_slot, U::splat(1 << 15), U::splat(0));
    let [key, offset] = code.gather_pairs(|c| {
        let at = (c & (TILE * TILE - 1)) as usize;
        match (
            c >> 15,
            SLOT_KEYS.get(c as usize >> 12 & 7),
            slots.get(c as usize >> 12 & 7),
        ) {
            (1, Some(&k), Some(tile)) => [k, u32::from(u16::from_le_bytes(tile[at]))],
            _ => [u32::from_le_bytes(keys[at]), 0],
        }
    });
    (key, index ^ offset)
}

#[cfg(test)]
mod tests {
    use super::super::{Base, Blue, Pattern, Pmj02bn, Sampler, Sobol};
    use super::{SLOT_KEYS, SLOTS, TILE};

    /// The tile position a `Blue<P>` pixel reads, worked from the documented layout alone:
    /// bit 29 of the domain hash transposes, bits 30 and 31 flip x and y, then bits 6..11 of
    /// the hash shift x and bits 12..17 shift y; row-major.
    fn position_of(pixel: [u32; 2], domain: u32) -> usize {
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
        let x = x.wrapping_add(domain >> 6) % TILE;
        let y = y.wrapping_add(domain >> 12) % TILE;
        (y * TILE + x) as usize
    }

    /// The (key, index offset) a `Blue<P>` pixel draws with, from the documented layout: the
    /// low two bits of the domain hash are its tag (1: slot `(hash >> 2) & 7` of the root);
    /// a slot's pixel draws the slot's key at its index XOR the slot tile's 16-bit
    /// little-endian offset, any other domain's pixel the key tile's little-endian word.
    fn keyed_at<P: Base>(pixel: [u32; 2], domain: u32) -> (u32, u32) {
        let (keys, slots): (&[u8], &[u8]) = if P::ID == super::super::SOBOL {
            (
                include_bytes!("../tables/blue_sobol_64.bin"),
                include_bytes!("../tables/blue_slots_sobol_64.bin"),
            )
        } else {
            (
                include_bytes!("../tables/blue_pmj02bn_64.bin"),
                include_bytes!("../tables/blue_slots_pmj02bn_64.bin"),
            )
        };
        let at = position_of(pixel, domain);
        let slot = (domain >> 2 & 7) as usize;
        if domain & 3 == 1 && slot < SLOTS {
            let i = 2 * (slot * (TILE * TILE) as usize + at);
            (
                SLOT_KEYS[slot],
                u32::from(slots[i]) | u32::from(slots[i + 1]) << 8,
            )
        } else {
            let w = &keys[4 * at..4 * at + 4];
            (u32::from_le_bytes([w[0], w[1], w[2], w[3]]), 0)
        }
    }

    /// A `Blue<P>` pixel draws exactly `P`'s points keyed as [`keyed_at`] says, i.e. what
    /// `tools/bluegen` optimises through `Sampler::<P>::from_domain_hash`: for any pixel,
    /// frame, seed, domain path and index; a `new_frame` root's domains `0..SLOTS` are slots
    /// and no other domain is.
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
        let mut slots_seen = [0u32; SLOTS];
        for trial in 0..2000 {
            let pixel = if trial < 8 {
                [trial, u32::MAX - trial]
            } else {
                [next(), next()]
            };
            let (frame, seed, index) = (next(), next(), next() >> (trial % 32));
            let root = Sampler::<Blue<P>>::new_frame(pixel, frame, 1, index, seed);
            let fresh = Sampler::<Blue<P>>::new(pixel, frame, index, seed);
            let (a, b) = (next(), next());
            let slot = trial % SLOTS as u32;
            let cases = [
                (root, None),
                (root.domain(a), None),
                (root.domain(slot), Some(slot)),
                (root.domain(slot).domain(slot), None),
                (root.domain(a).domain(b % 8), None),
                (root.split(slot, 4, 3), None),
                (root.split(a, 4, 3).domain(b), None),
                (fresh.domain(slot), None),
                (fresh, None),
            ];
            for (s, want_slot) in cases {
                // The tile position uses the pixel modulo 2^16 (then modulo the tile).
                let p = [pixel[0] & 0xffff, pixel[1] & 0xffff];
                let d = s.state.domain.0;
                let is_slot = d & 3 == 1 && ((d >> 2) & 7) < SLOTS as u32;
                let got_slot = is_slot.then_some(d >> 2 & 7);
                assert_eq!(got_slot, want_slot);
                if let Some(k) = got_slot {
                    slots_seen[k as usize] += 1;
                }
                let (key, offset) = keyed_at::<P>(p, d);
                let base = Sampler::<P>::from_domain_hash(key, s.index() ^ offset);
                assert_eq!(s.draw_u32::<4>(), base.draw_u32::<4>(), "pixel {pixel:?}");
                assert_eq!(s.draw::<2>(), base.draw::<2>());
            }
        }
        assert!(slots_seen.iter().all(|&n| n > 300), "{slots_seen:?}");
    }

    #[test]
    fn blue_sobol_draws_sobol_keyed_by_the_tiles() {
        blue_draws_the_keyed_base_pattern::<Sobol>();
    }

    #[test]
    fn blue_pmj02bn_draws_pmj02bn_keyed_by_the_tiles() {
        blue_draws_the_keyed_base_pattern::<Pmj02bn>();
    }
}
