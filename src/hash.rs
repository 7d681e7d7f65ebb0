//! Integer hashes over [`UintLane`]: seed mixing, nested (Owen) scrambling of 0.32 fixed-point
//! coordinates, and a prefix-preserving shuffle of sample indices. Integer arithmetic only,
//! so one body gives the same bits for `Wrapping<u32>` and `u32x8`.

#[cfg(feature = "sampler")]
use crate::lanes::Kernel4;
use crate::lanes::UintLane;

/// A bijective 32-bit mixer with low bias: Chris Wellons' `lowbias32` from *hash-prospector*
/// (xorshift-multiply, two rounds). `mix(0) = 0`.
#[inline(always)]
pub(crate) fn mix<U: UintLane>(x: U) -> U {
    let x = x ^ x.shr(16);
    let x = x * U::splat(0x7feb_352d);
    let x = x ^ x.shr(15);
    let x = x * U::splat(0x846c_a68b);
    x ^ x.shr(16)
}

/// One round of [`mix`] (xorshift, multiply, xorshift: the first half of Wellons'
/// `lowbias32`): bijective, `mix1(0) = 0`, half the cost. For the sampler's domain tree, whose
/// hashes feed the Laine-Karras keys of [`lk_hash`] (which mix again) rather than outputs.
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn mix1<U: UintLane>(x: U) -> U {
    let x = x ^ x.shr(16);
    let x = x * U::splat(0x7feb_352d);
    x ^ x.shr(15)
}

/// A hash of bit-reversed values in which output bit `j` depends only on input bits `<= j`
/// (each step is `+`, `*` by an odd number, or `^= x * even`, which carry upwards only),
/// keyed by `seed`. Laine and Karras (2011) proposed the form; these constants are Vegdahl's
/// improved ones ("Building a Better LK Hash", 2021), as used by Burley's practical hash-based
/// Owen scrambling (JCGT 2020).
#[inline(always)]
pub(crate) fn lk_hash<U: UintLane>(x: U, seed: U) -> U {
    let x = x ^ (x * U::splat(0x3d20_adea));
    let x = x + seed;
    let x = x * (seed.shr(16) | U::splat(1));
    let x = x ^ (x * U::splat(0x0552_6c56));
    x ^ (x * U::splat(0x53a2_2864))
}

/// Nested uniform (Owen) scramble of a 0.32 fixed-point coordinate, keyed by `seed`.
///
/// Reverse the bits so that the most significant digit becomes the least significant, apply
/// [`lk_hash`] (each digit is then flipped by a function of the digits above it only), and
/// reverse back: a random permutation of base-2 digits that maps every dyadic interval onto
/// a dyadic interval of the same length. Applied to both coordinates, it maps every
/// elementary interval onto one of the same shape, so a (0,m,2)-net stays one.
#[inline(always)]
pub(crate) fn owen_scramble<U: UintLane>(v: U, seed: U) -> U {
    owen_scramble_reversed(v.reverse_bits(), seed)
}

/// [`owen_scramble`] of a value given bit-reversed (`r = reverse(v)`), as the Sobol'
/// matrices produce it: [`lk_hash`] then one reversal.
#[inline(always)]
pub(crate) fn owen_scramble_reversed<U: UintLane>(r: U, seed: U) -> U {
    lk_hash(r, seed).reverse_bits()
}

/// [`owen_scramble`] as a [`Kernel4`].
#[cfg(feature = "sampler")]
#[derive(Clone, Copy)]
struct OwenScramble;

#[cfg(feature = "sampler")]
impl Kernel4 for OwenScramble {
    #[inline(always)]
    fn run<U: UintLane>(self, word: U, key: U) -> U {
        owen_scramble(word, key)
    }
}

/// The four words of one 4D point (in each lane) under four keys' [`owen_scramble`]; a
/// scalar runs the four as one 4-lane vector ([`UintLane::map4`]): its eight bit reversals
/// are cheaper as vector shifts and masks than as scalar ones (x86 has no bit-reverse
/// instruction; per call with SSE2 the vector form is 1.6x the four scalar ones).
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn owen_scramble4<U: UintLane>(words: [U; 4], keys: [U; 4]) -> [U; 4] {
    U::map4(words, keys, OwenScramble)
}

/// Burley's nested uniform shuffle of sample indices (Burley 2020, section 4): the
/// Laine-Karras hash of the bit-reversed index, reversed back. Nested: every aligned block of
/// `2^k` indices maps onto an aligned block of `2^k` (not necessarily the first, unlike
/// [`prefix_shuffle`]); for a (0,2)-sequence every aligned block is a net, so every prefix
/// of the shuffled sequence still is one.
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn nested_shuffle<U: UintLane>(index: U, seed: U) -> U {
    lk_hash(index.reverse_bits(), seed).reverse_bits()
}

/// A permutation of sample indices that keeps every prefix `[0, 2^k)` as a set and maps every
/// aligned block of `2^k` indices onto an aligned block of `2^k` indices: the nested scramble
/// of [`owen_scramble`] applied to the index read least significant bit first, with the image
/// of 0 pinned to 0 (xor with `lk_hash(0, seed)`, which keeps the digit structure).
#[inline(always)]
pub(crate) fn prefix_shuffle<U: UintLane>(index: U, seed: U) -> U {
    (lk_hash(index.reverse_bits(), seed) ^ lk_hash(U::splat(0), seed)).reverse_bits()
}

/// Truncating conversion of 0.32 fixed point to `f32`: `(x >> 8) * 2^-24`, exact, in
/// `[0, 1 - 2^-24]` — never `x as f32 * 2^-32`, which rounds the top values up to 1.0.
#[inline(always)]
pub(crate) fn to_unit<L: crate::lanes::Lane>(x: L::U) -> L {
    L::from_uint(x.shr(8)) * L::splat(1.0 / 16_777_216.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::num::Wrapping;
    use wide::u32x8;

    fn w(x: u32) -> Wrapping<u32> {
        Wrapping(x)
    }

    /// Bit `b` (from the top) of the scrambled value depends only on bits above and at `b`:
    /// flipping input bit `b` flips output bit `b` and leaves the bits above unchanged.
    #[test]
    fn owen_scramble_is_nested() {
        let mut x = 0x1234_5678u32;
        for seed in [0u32, 1, 0xdead_beef, 0x8000_0000] {
            for _ in 0..200 {
                x = x.wrapping_mul(0x9e37_79b9).wrapping_add(0x7f4a_7c15);
                let a = owen_scramble(w(x), w(seed)).0;
                for b in 0..32 {
                    let y = owen_scramble(w(x ^ (0x8000_0000 >> b)), w(seed)).0;
                    let above = !(u32::MAX >> b);
                    assert_eq!(a & above, y & above, "bits above {b} moved");
                    assert_ne!((a ^ y) & (0x8000_0000 >> b), 0, "bit {b} not flipped");
                }
            }
        }
    }

    #[test]
    fn prefix_shuffle_keeps_prefixes_and_blocks() {
        for seed in [0u32, 7, 0xdead_beef] {
            for k in 0..12 {
                let mut seen = [false; 4096];
                for i in 0..(1u32 << k) {
                    let j = prefix_shuffle(w(i), w(seed)).0;
                    assert!(j < 1 << k, "{i} -> {j} leaves [0, 2^{k})");
                    assert!(!core::mem::replace(&mut seen[j as usize], true));
                }
            }
            // An aligned block of 256 lands in one aligned block of 256.
            let block = |i: u32| prefix_shuffle(w(i), w(seed)).0 >> 8;
            assert!((0x5300..0x5400).all(|i| block(i) == block(0x5300)));
        }
        assert_eq!(prefix_shuffle(w(0), w(99)).0, 0);
    }

    #[test]
    fn lanes_agree() {
        let xs = [
            0u32,
            1,
            0x8000_0000,
            0x1234_5678,
            u32::MAX,
            0xdead_beef,
            42,
            1 << 20,
        ];
        let seeds = [3u32, 0, u32::MAX, 0x8000_0001, 5, 6, 7, 8];
        let (v, s) = (u32x8::new(xs), u32x8::new(seeds));
        let scr = owen_scramble(v, s).to_array();
        let shu = prefix_shuffle(v, s).to_array();
        let mx = mix(v).to_array();
        for j in 0..8 {
            assert_eq!(scr[j], owen_scramble(w(xs[j]), w(seeds[j])).0);
            assert_eq!(shu[j], prefix_shuffle(w(xs[j]), w(seeds[j])).0);
            assert_eq!(mx[j], mix(w(xs[j])).0);
        }
        assert_eq!(mix(w(0)).0, 0);
        assert_eq!(to_unit::<f32>(w(u32::MAX)), 1.0 - 1.0 / 16_777_216.0);
    }
}
