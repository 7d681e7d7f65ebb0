//! Base-4 digit machinery for the Basu-Owen construction, on whole integer lanes at once
//! (SWAR: all 16 digits of a `u32` index are processed by the same few word operations, so
//! there is no loop over digits and no branch).
//!
//! Digit `j` of an index `i` is the bit pair `(i >> 2j) & 3`, least significant first: the
//! order in which the construction consumes them.

use crate::lanes::UintLane;

/// The low bit of every digit.
const EVEN_BITS: u32 = 0x5555_5555;

/// Exchanges the bits selected by `mask` with the bits `shift` places above them (a "delta
/// swap"; `mask` and `mask << shift` must not overlap).
#[inline(always)]
fn delta_swap<U: UintLane>(x: U, mask: u32, shift: u32) -> U {
    let t = (x ^ x.shr(shift)) & U::splat(mask);
    x ^ t ^ t.shl(shift)
}

/// Reverses the order of the 16 digits: digit `j` moves to digit `15 - j`, its two bits kept
/// in order (the reference for [`fields`]).
#[cfg(test)]
fn reverse_digits<U: UintLane>(x: U) -> U {
    let x = x.shr(16) | x.shl(16);
    let x = delta_swap(x, 0x00ff_00ff, 8);
    let x = delta_swap(x, 0x0f0f_0f0f, 4);
    delta_swap(x, 0x3333_3333, 2)
}

/// Separates even and odd bits: bit `2k` moves to bit `k` and bit `2k + 1` to bit `16 + k`
/// (the inverse perfect shuffle; Warren, "Hacker's Delight", section 7-2).
#[inline(always)]
fn unzip<U: UintLane>(x: U) -> U {
    let x = delta_swap(x, 0x2222_2222, 1);
    let x = delta_swap(x, 0x0c0c_0c0c, 2);
    let x = delta_swap(x, 0x00f0_00f0, 4);
    delta_swap(x, 0x0000_ff00, 8)
}

/// A 32-bit avalanche hash (xorshift-multiply; constants from C. Wellons' "hash prospector"
/// search). A bijection, so distinct seeds never collide.
#[inline(always)]
fn mix<U: UintLane>(x: U) -> U {
    let x = (x ^ x.shr(16)) * U::splat(0x21f0_aaad);
    let x = (x ^ x.shr(15)) * U::splat(0xd35a_2d97);
    x ^ x.shr(15)
}

/// Multiplies every digit by `omega^m` in GF(4) (`m` in `0..3`), with the digit `lo + 2 hi`
/// read as `lo + hi omega`: `omega` maps `(lo, hi)` to `(hi, lo ^ hi)`, the 3-cycle
/// `1 -> 2 -> 3 -> 1` that fixes 0.
#[inline(always)]
fn rotate_digits<U: UintLane>(x: U, m: U) -> U {
    let lo = x & U::splat(EVEN_BITS);
    let hi = x.shr(1) & U::splat(EVEN_BITS);
    let once = hi | (lo ^ hi).shl(1);
    let twice = (lo ^ hi) | lo.shl(1);
    U::select(
        m.simd_eq(U::splat(1)),
        once,
        U::select(m.simd_eq(U::splat(2)), twice, x),
    )
}

/// Nested (Owen) scramble of the base-4 digits of `index`, keyed by `seed`; `seed = 0`
/// returns `index` unchanged.
///
/// Digit `j` of the result is `pi(d_j)`, where the permutation `pi` of `{0, 1, 2, 3}` is
/// drawn afresh for every prefix `d_0 .. d_(j-1)` (every node of the 4-ary tree of
/// sub-triangles), as in Owen's nested uniform scrambling (Owen 1995, "Randomly permuted
/// (t,m,s)-nets and (t,s)-sequences") and its hash-based form for base 2 (Burley 2020,
/// "Practical Hash-based Owen Scrambling"). Here `pi = D o R^m`:
///
/// * `D`, from a hash in which output bit `k` depends only on input bits `<= k` (a bijection:
///   seed addition, multiplication by a seed-dependent odd number, and `x ^= x * even`, the
///   structure of Vegdahl 2021, "Building a Better LK Hash", with our own constants). On a digit
///   such a hash flips the low bit by a function of the prefix and the high bit by a function
///   of the prefix and the low bit: an element of the 8-element dihedral group `D4` (the
///   permutations that keep the pairs `{0, 2}`, `{1, 3}` together), a different one per node.
///   A base-2 hash can reach no more than that.
/// * `R^m`: multiplication by `omega^m` in GF(4) with `m` in `{0, 1, 2}` drawn once per seed.
///   `D4` and the powers of `R` (a 3-cycle) together give every permutation of four digits
///   exactly once (`S4 = D4 . C3`), so with `D` uniform on `D4` and `m` uniform, every node's
///   permutation is uniform on all 24. Sharing `m` between nodes does not change the joint
///   law of any *pair* of points (the deeper digits of each stay uniform through their own
///   `D`), so the variance of any estimator is that of Owen's fully independent scramble.
///
/// Since each node's map is a bijection, the first `4^k` indices still occupy all `4^k`
/// prefixes: the stratification of the construction is kept, for every seed.
#[inline(always)]
pub(super) fn nested_scramble<U: UintLane>(index: U, seed: U) -> U {
    let k1 = mix(seed);
    let k2 = mix(seed ^ U::splat(0x5bd1_e995));
    let k3 = mix(seed ^ U::splat(0x2545_f491));
    // m = floor(3 t / 2^24) for the top 24 bits t of k3: uniform on {0, 1, 2} up to 2^-24.
    let m = (k3.shr(8) * U::splat(3)).shr(24);
    let x = rotate_digits(index, m);
    // Constants: fractional parts of the golden ratio, sqrt(2), sqrt(3), made even.
    let x = x ^ (x * U::splat(0x9e37_79b8));
    let x = x + k1;
    let x = x * (k2 | U::splat(1));
    let x = x ^ (x * U::splat(0x6a09_e666));
    let x = x ^ (x * U::splat(0xbb67_ae84));
    U::select(seed.simd_eq(U::splat(0)), index, x)
}

/// The low 16 bits: one bit per digit in the "fields" layout of [`fields`].
const LOW16: u32 = 0x0000_ffff;

/// The index's digits as two 16-bit fields, most significant digit first: bit `15 - j` holds
/// the low bit of digit `j` and bit `31 - j` its high bit. The walk consumes this layout, and
/// [`LevelKeys`] permute digits in it.
///
/// That is `unzip(reverse_digits(index))`, computed as `rotate16(unzip(reverse_bits(index)))`:
/// reversing all 32 bits also reverses the digit order but swaps the two bits of each digit,
/// so after the unzip the high bits land in the low half; a rotation by 16 swaps the halves
/// back. `reverse_bits` is one or two instructions on most targets (`rbit`; GFNI or PSHUFB
/// nibble tables on x86), where `reverse_digits` costs four delta swaps.
#[inline(always)]
pub(super) fn fields<U: UintLane>(index: U) -> U {
    let x = unzip(index.reverse_bits());
    x.shr(16) | x.shl(16)
}

/// One permutation of `{0, 1, 2, 3}` per level of the subdivision, shared by every node of
/// that level, as masks over the [`fields`] layout: digit `d` at level `j` becomes
/// `sigma_j(d) = L_j d + k_j` over GF(2)^2 (`d` read as the bit vector `(low, high)`).
///
/// Every permutation of four points is such an affine map (`AGL(2, 2)` has 24 elements and
/// acts faithfully), so a per-level `(L_j, k_j)` is exactly a per-level `sigma_j`. Applied to
/// the fields `f` (low bits in the low half, high bits in the high half):
/// `f' = (f & a) ^ (swap_halves(f) & b) ^ k`, six word operations for all 16 digits.
#[derive(Clone, Copy)]
pub(super) struct LevelKeys<U> {
    /// `L_j[0][0]` at bit `15 - j`, `L_j[1][1]` at bit `31 - j`.
    a: U,
    /// `L_j[0][1]` at bit `15 - j`, `L_j[1][0]` at bit `31 - j`.
    b: U,
    /// `k_j`, its low bit at `15 - j`, its high bit at `31 - j`.
    k: U,
}

impl<U: UintLane> LevelKeys<U> {
    /// The same keys in every lane (the slice forms derive them once per call).
    #[inline(always)]
    pub(super) fn splat(keys: LevelKeys<core::num::Wrapping<u32>>) -> Self {
        LevelKeys {
            a: U::splat(keys.a.0),
            b: U::splat(keys.b.0),
            k: U::splat(keys.k.0),
        }
    }

    /// Draws `sigma_0 .. sigma_15` from `seed`; `seed = 0` gives the identity at every level.
    ///
    /// `sigma_j = (S^s_j R^m_j, k_j)`: the translation `k_j` is two hash bits, `s_j` one
    /// more, and `m_j` in `{0, 1, 2}` is base-3 digit `j mod 8` of a hash word `t` read as a
    /// fraction of `2^32` (levels 0-7 from one word, 8-15 from another): `m_j = floor(3 t_j /
    /// 2^32)` with `t_j = 3^j t mod 2^32`, found by two compares (`3 t_j >= 2^32` exactly when
    /// `t_j >= ceil(2^32 / 3)`). `R` is multiplication by `omega` in GF(4) (`(low, high) ->
    /// (high, low ^ high)`), `S` swaps the two bits; `{S^s R^m}` is all six invertible 2x2 bit
    /// matrices, so `sigma_j` ranges over all 24 permutations. `k_j` is exactly uniform, which
    /// alone makes every point exactly uniform at the construction's resolution (a uniform
    /// translation after any linear map is uniform); `m_j` is uniform up to a relative bias of
    /// `3^8 / 2^32 = 1.5e-6`, which only touches the joint law of two points.
    #[inline(always)]
    pub(super) fn new(seed: U) -> Self {
        let k = mix(seed ^ U::splat(0x68e3_1da4));
        let s = mix(seed ^ U::splat(0xb5b8_4f2b)) & U::splat(LOW16);
        let words = [
            mix(seed ^ U::splat(0x3c6e_f372)),
            mix(seed ^ U::splat(0xa54f_f53a)),
        ];
        // Bit 15 - j of `ge1` is [m_j >= 1], of `ge2` is [m_j = 2].
        let (mut ge1, mut ge2) = (U::splat(0), U::splat(0));
        let mut power = 1u32; // 3^step
        for step in 0..8 {
            for (half, word) in words.iter().enumerate() {
                let t = *word * U::splat(power);
                let bit = U::splat(1 << (15 - (8 * half as u32 + step)));
                let zero = U::splat(0);
                ge1 = ge1 | U::select(t.simd_lt(U::splat(0x5555_5556)), zero, bit);
                ge2 = ge2 | U::select(t.simd_lt(U::splat(0xaaaa_aaab)), zero, bit);
            }
            power = power.wrapping_mul(3);
        }
        // R^m as rows (new low, new high) over (low, high):
        //   m = 0: [1 0; 0 1],  m = 1: [0 1; 1 1],  m = 2: [1 1; 1 0].
        let l00 = !(ge1 & !ge2) & U::splat(LOW16); // m != 1
        let l01 = ge1; // m != 0
        let l10 = ge1;
        let l11 = !ge2 & U::splat(LOW16); // m != 2
        // S swaps the rows where s is set.
        let pick = |keep: U, swap: U| (keep & !s) | (swap & s);
        let (n00, n01, n10, n11) = (
            pick(l00, l10),
            pick(l01, l11),
            pick(l10, l00),
            pick(l11, l01),
        );
        let zero = seed.simd_eq(U::splat(0));
        LevelKeys {
            a: U::select(zero, U::splat(u32::MAX), n00 | n11.shl(16)),
            b: U::select(zero, U::splat(0), n01 | n10.shl(16)),
            k: U::select(zero, U::splat(0), k),
        }
    }

    /// `sigma_j` applied to every digit `j` of `fields` (the [`fields`] layout in and out).
    #[inline(always)]
    pub(super) fn permute(&self, fields: U) -> U {
        let swapped = fields.shr(16) | fields.shl(16);
        (fields & self.a) ^ (swapped & self.b) ^ self.k
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::num::Wrapping;

    fn w(x: u32) -> Wrapping<u32> {
        Wrapping(x)
    }

    fn samples() -> impl Iterator<Item = u32> {
        let mut s = 0x1234_5678u32;
        (0..20_000).map(move |k| {
            s ^= s << 13;
            s ^= s >> 17;
            s ^= s << 5;
            if k < 64 { k } else { s }
        })
    }

    #[test]
    fn reverse_digits_reverses() {
        for x in samples() {
            let mut want = 0u32;
            for j in 0..16 {
                want |= ((x >> (2 * j)) & 3) << (2 * (15 - j));
            }
            assert_eq!(reverse_digits(w(x)).0, want, "{x:#x}");
        }
    }

    #[test]
    fn fields_are_the_unzipped_reversed_digits() {
        for x in samples() {
            assert_eq!(fields(w(x)).0, unzip(reverse_digits(w(x))).0, "{x:#x}");
            let v = wide::u32x8::splat(x) ^ wide::u32x8::new([0, 1, 2, 3, 4, 5, 6, 0x8000_0000]);
            let got = fields(v).to_array();
            for (j, &y) in v.to_array().iter().enumerate() {
                assert_eq!(got[j], fields(w(y)).0);
            }
        }
    }

    #[test]
    fn unzip_separates_even_and_odd_bits() {
        for x in samples() {
            let mut want = 0u32;
            for k in 0..16 {
                want |= ((x >> (2 * k)) & 1) << k;
                want |= ((x >> (2 * k + 1)) & 1) << (16 + k);
            }
            assert_eq!(unzip(w(x)).0, want, "{x:#x}");
        }
    }

    #[test]
    fn rotation_is_multiplication_by_omega() {
        // GF(4) = {0, 1, w, w + 1} with w^2 = w + 1; digit lo + 2 hi is lo + hi w.
        let mul_omega = |d: u32| [0, 2, 3, 1][d as usize];
        for x in samples() {
            for m in 0..3u32 {
                let got = rotate_digits(w(x), w(m)).0;
                for j in 0..16 {
                    let mut d = (x >> (2 * j)) & 3;
                    for _ in 0..m {
                        d = mul_omega(d);
                    }
                    assert_eq!((got >> (2 * j)) & 3, d);
                }
            }
        }
    }

    /// Nested: digit j of the scrambled index depends only on digits 0..=j of the index, and
    /// for a fixed prefix it is a permutation of the four values of digit j.
    #[test]
    fn scramble_is_nested_and_bijective_per_node() {
        for seed in [1u32, 2, 0xdead_beef, u32::MAX] {
            for x in samples().take(2000) {
                let sx = nested_scramble(w(x), w(seed)).0;
                for j in 0..16u32 {
                    let low = if j == 15 {
                        u32::MAX
                    } else {
                        (1u32 << (2 * j + 2)) - 1
                    };
                    // Changing digits above j leaves digits 0..=j alone.
                    let y = x ^ (0x9e37_79b9u32 & !low);
                    let sy = nested_scramble(w(y), w(seed)).0;
                    assert_eq!(sx & low, sy & low, "seed {seed} x {x:#x} j {j}");
                    // The four values of digit j map to four different digits.
                    let mut seen = [false; 4];
                    for d in 0..4u32 {
                        let z = (x & !(3 << (2 * j))) | (d << (2 * j));
                        let sz = nested_scramble(w(z), w(seed)).0;
                        seen[((sz >> (2 * j)) & 3) as usize] = true;
                    }
                    assert!(seen.iter().all(|&s| s), "seed {seed} x {x:#x} j {j}");
                }
            }
        }
        for x in samples() {
            assert_eq!(nested_scramble(w(x), w(0)).0, x);
        }
    }
}
