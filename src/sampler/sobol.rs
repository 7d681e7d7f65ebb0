//! Owen-scrambled Sobol' dimensions 0..3: the generator matrices, built at compile time from
//! primitive polynomials and initial direction numbers, and the scramble.
//!
//! **The sequence.** Point `i` of Sobol' dimension `d` is `x_d(i) = XOR over the set bits k
//! of i of v_{d,k}`, with the direction numbers `v_{d,k} = m_{d,k} / 2^(k+1)` (Sobol' 1967;
//! Bratley and Fox 1988, ACM TOMS 14, Algorithm 659). Dimension 0 is the van der Corput
//! sequence (`v_{0,k} = 2^-(k+1)`); dimensions 1..3 use the primitive polynomials `x + 1`,
//! `x^2 + x + 1` and `x^3 + x + 1` with the initial values `m = (1)`, `(1, 3)` and
//! `(1, 3, 1)` of Joe and Kuo's table ("Constructing Sobol sequences with better
//! two-dimensional projections", SIAM J. Sci. Comput. 30, 2008; their dimensions 2, 3, 4).
//! Further `m` follow the recurrence `m_k = 2 a_1 m_{k-1} ^ 4 a_2 m_{k-2} ^ .. ^ 2^s m_{k-s}
//! ^ m_{k-s}`, for all 32 bits of the index.
//!
//! **What is stratified.** Dimensions 0 and 1 form a (0,2)-sequence: every aligned block of
//! `2^m` indices is a (0,m,2)-net. Each dimension alone is a (0,1)-sequence (one point per
//! `2^-m` interval). Dimensions 2 and 3 are *not* a (0,2) pair with each other or with 0 and 1
//! (their 2D projections have `t >= 1`): when a 4D draw is two 2D decisions (a point on a
//! light and a BSDF direction), [`Pmj02bn`](super::Pmj02bn) gives two (0,2) pairs.
//!
//! **Randomisation** (Burley, "Practical Hash-based Owen Scrambling", JCGT 9(4), 2020): the
//! index is shuffled by a nested uniform permutation (every aligned block of `2^k` indices
//! onto an aligned block of `2^k`, so every prefix keeps its net), then every dimension gets
//! an independent nested uniform (Owen) scramble. Both are the Laine-Karras-style hash of
//! [`crate::hash`] with independent keys. Working on bit-reversed values saves a reversal per
//! dimension: the tables below hold `reverse(v_{d,k})`, so their XOR is `reverse(x_d(i))`,
//! which is exactly what the scramble hashes.

use crate::hash::{lk_hash, owen_scramble_reversed, to_unit};
use crate::lanes::UintLane;
use core::num::Wrapping;

/// Primitive polynomial degree `s`, its middle coefficients `a` (bit `s - 2 - j` is `a_{j+1}`)
/// and the initial `m_1 .. m_s` for dimensions 1, 2 and 3 (Joe and Kuo 2008, dimensions 2-4).
const POLYNOMIALS: [(u32, u32, [u32; 3]); 3] =
    [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])];

/// Direction numbers of dimension `d` (1..=3) as 0.32 fixed point: entry `k` is `v_{d,k}`.
const fn directions(d: usize) -> [u32; 32] {
    let (s, a, init) = POLYNOMIALS[d - 1];
    let s = s as usize;
    // m_k for k = 1..=32, held as u64 (m_k < 2^k).
    let mut m = [0u64; 33];
    let mut k = 1;
    while k <= 32 {
        if k <= s {
            m[k] = init[k - 1] as u64;
        } else {
            let mut x = m[k - s] ^ (m[k - s] << s);
            let mut j = 1;
            while j < s {
                if (a >> (s - 1 - j)) & 1 == 1 {
                    x ^= m[k - j] << j;
                }
                j += 1;
            }
            m[k] = x;
        }
        k += 1;
    }
    let mut v = [0u32; 32];
    let mut k = 0;
    while k < 32 {
        // v_k = m_{k+1} / 2^(k+1), as a 0.32 fraction.
        v[k] = (m[k + 1] << (31 - k)) as u32;
        k += 1;
    }
    v
}

/// The generator matrices of dimensions 0..3 applied to an index given *bit-reversed*, by
/// bytes: `TABLE[256 b + byte][d]` is the XOR of `reverse(v_{d,k})` over the set bits `j` of
/// `byte`, where `k = 31 - (8 b + j)` is the index bit that bit `8 b + j` of the reversed
/// index holds (for dimension 0, `reverse(v_{0,k})` is bit `k`). Four 16-byte rows and three
/// XORs give `reverse(x_d(i))` for all four dimensions from `reverse(i)`, which is what the
/// nested shuffle produces before its last reversal, and what the scrambles hash: the index
/// is never reversed back (OpenQMC's tables take the reversed index the same way). 16 KiB,
/// built at compile time.
static TABLE: [[u32; 4]; 1024] = {
    let dirs = [directions(1), directions(2), directions(3)];
    let mut t = [[0u32; 4]; 1024];
    let mut e = 0;
    while e < 1024 {
        let (b, byte) = (e / 256, e % 256);
        let mut j = 0;
        while j < 8 {
            if (byte >> j) & 1 == 1 {
                let k = 31 - (8 * b + j);
                t[e][0] ^= 1 << k;
                let mut d = 1;
                while d < 4 {
                    t[e][d] ^= dirs[d - 1][k].reverse_bits();
                    d += 1;
                }
            }
            j += 1;
        }
        e += 1;
    }
    t
};

/// `reverse(x_d(i))` for dimensions 0..3 from `r = reverse(i)`.
#[inline(always)]
fn reversed_dims<U: UintLane>(r: U) -> [U; 4] {
    // Spelled out: an array `map` over the four bytes stayed out of line in the slices.
    let byte = |b: u32| (r.shr(8 * b) & U::splat(0xff)) | U::splat(256 * b);
    let a = U::gather(&TABLE, byte(0));
    let b = U::gather(&TABLE, byte(1));
    let c = U::gather(&TABLE, byte(2));
    let d = U::gather(&TABLE, byte(3));
    core::array::from_fn(|k| a[k] ^ b[k] ^ c[k] ^ d[k])
}

/// The index shuffle's key and the four dimensions' scramble keys, derived from one
/// well-mixed word `h` (the domain hash, or a blue-noise tile key) by rotations. The top
/// levels of a Laine-Karras scramble are driven by the low bits of its key (bit `j` of the
/// output depends on bits `0..=j` of the key), so rotations by 6, 13, 19 and 26 give the
/// shuffle and the four scrambles disjoint key bits for their first six levels (64 strata
/// per dimension), and the multiplier (`key >> 16`) differs for each. OpenQMC derives its
/// per-dimension keys from one hash in the same spirit (byte rotations). Five rotations cost
/// less than one hash: they keep the draw short (`docs/sampler-performance.md`).
#[inline(always)]
pub(super) fn keys<U: UintLane>(h: U) -> [U; 5] {
    [h, h.rotr(6), h.rotr(13), h.rotr(19), h.rotr(26)]
}

/// Point `index` of the Owen-scrambled Sobol' sequence keyed by `seed`, dimensions `0..N`, as
/// 0.32 fixed point. Exact integer arithmetic: no rounding at all.
#[inline(always)]
pub(super) fn point<U: UintLane, const N: usize>(index: U, seed: U) -> [U; N] {
    let keys = keys(seed);
    // Nested uniform shuffle of the index (Burley 2020, section 4), kept bit-reversed, then
    // the matrices and the scrambles, which work on reversed values.
    let r = lk_hash(index.reverse_bits(), keys[0]);
    // One scramble per dimension, each a hash and one reversal. Not through the 4-lane
    // `owen_scramble4` that pmj02bn uses: with one reversal per word the four multiplies
    // dominate, and SSE2 has no 32-bit lane multiply (per call 1.3x faster this way with SSE2,
    // and faster with AVX-512 too; docs/sampler-performance.md).
    let dims = reversed_dims(r);
    core::array::from_fn(|d| owen_scramble_reversed(dims[d], keys[d + 1]))
}

/// The slice form on aligned groups of `LN` consecutive indices (`LN` = 8 or 16), group `g`
/// holding the points of indices `first + LN g ..` (`first` a multiple of `LN`), for the same
/// `seed`: lane by lane the bits of [`point`], with everything that is common to a group
/// computed once, as a scalar.
///
/// The keys depend on the seed alone. The reversed indices of an aligned group differ only in
/// their top `s = log2(LN)` bits, and bit `j` of the Laine-Karras hash depends only on bits
/// `0..=j` of its input, so the hashed (shuffled, reversed) indices share their low `32 - s`
/// bits, the hash of the group's first index, and differ in their top `s` bits `v`, a
/// permutation of `0..LN`. The generator matrices are linear over GF(2): the reversed
/// dimensions are those of the common bits (one scalar table product per group; bytes 0-2
/// change once per 256 indices) XOR those of `v` (a lane permute of a constant).
#[inline(always)]
pub(super) fn fill_groups<L: crate::slices::Rows<LN>, const LN: usize, const N: usize>(
    first: u32,
    seed: u32,
    groups: &mut [[[f32; N]; LN]],
) {
    let s = LN.trailing_zeros();
    let keys = keys(Wrapping(seed));
    // Lane l holds the bit-reversed l: the low index bits of the group, reversed in place.
    let lanes = L::words(core::array::from_fn(|l| (l as u32).reverse_bits()));
    // Indexed by the top `s` bits `v` of a hashed lane: their products with the matrices
    // (byte 3 of `TABLE`, `v` in its top bits).
    let low: [L::U; 4] = core::array::from_fn(|d| {
        L::words(core::array::from_fn(|v| TABLE[768 + (v << (8 - s))][d]))
    });
    let shuffle_key = L::U::splat(keys[0].0);
    let byte3_mask = (1u32 << (8 - s)) - 1;
    // What a group needs before its vector work: its hashed first index and the lanes' top
    // bits, computed one group ahead (software pipelining: that chain of hashes then overlaps
    // the previous group's vector work instead of preceding it).
    let ahead = |g: usize| {
        let b = first.wrapping_add((g * LN) as u32).reverse_bits();
        let r = lk_hash(Wrapping(b), keys[0]).0;
        let v = lk_hash(L::U::splat(b) | lanes, shuffle_key).shr(32 - s);
        (r, v)
    };
    let mut above = (u32::MAX, [0u32; 4]);
    let mut next = ahead(0);
    for (g, dst) in groups.iter_mut().enumerate() {
        let (r, v) = next;
        next = ahead(g + 1);
        if r & 0x00ff_ffff != above.0 {
            let rows = [0, 1, 2].map(|k| TABLE[(256 * k + ((r >> (8 * k)) & 0xff)) as usize]);
            above = (
                r & 0x00ff_ffff,
                core::array::from_fn(|d| rows[0][d] ^ rows[1][d] ^ rows[2][d]),
            );
        }
        let byte3 = TABLE[(768 + ((r >> 24) & byte3_mask)) as usize];
        let common: [u32; 4] = core::array::from_fn(|d| above.1[d] ^ byte3[d]);
        // Plain loops: `core::array::from_fn` closures can stay out of line (see `batch`).
        let mut point = [L::splat(0.0); N];
        for (d, p) in point.iter_mut().enumerate() {
            let r = L::U::splat(common[d % 4]) ^ L::shuffle(low[d % 4], v);
            *p = to_unit(lk_hash(r, L::U::splat(keys[(d + 1) % 5].0)).reverse_bits());
        }
        crate::slices::store_rows(point, dst);
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use core::num::Wrapping;

    /// Unscrambled Sobol' point `i`, dimension `d`, straight from the definition.
    fn plain(i: u32, d: usize) -> u32 {
        if d == 0 {
            return i.reverse_bits();
        }
        let v = directions(d);
        (0..32)
            .filter(|k| (i >> k) & 1 == 1)
            .fold(0, |x, k| x ^ v[k])
    }

    /// The first direction numbers, worked by hand from the polynomials and `m` values.
    #[test]
    fn direction_numbers_follow_the_recurrence() {
        let frac = |m: u64, k: u32| (m << (32 - k)) as u32;
        // x + 1 (the Pascal matrix): m = 1, 3, 5, 15, 17.
        let want1 = [1, 3, 5, 15, 17].iter().zip(1..).map(|(&m, k)| frac(m, k));
        assert!(want1.eq(directions(1)[..5].iter().copied()));
        // x^2 + x + 1, m = (1, 3): m3 = 2*3 ^ 4*1 ^ 1 = 3, m4 = 2*3 ^ 4*3 ^ 3 = 9,
        // m5 = 2*9 ^ 4*3 ^ 3 = 29.
        let want2 = [1, 3, 3, 9, 29].iter().zip(1..).map(|(&m, k)| frac(m, k));
        assert!(want2.eq(directions(2)[..5].iter().copied()));
        // x^3 + x + 1 (a_1 = 0, a_2 = 1), m = (1, 3, 1): m4 = 4*3 ^ 8*1 ^ 1 = 5,
        // m5 = 4*1 ^ 8*3 ^ 3 = 31.
        let want3 = [1, 3, 1, 5, 31].iter().zip(1..).map(|(&m, k)| frac(m, k));
        assert!(want3.eq(directions(3)[..5].iter().copied()));
        // Every v_k has bit k (from the top) set and nothing below: the matrices are
        // triangular with a unit diagonal, so each dimension is a (0,1)-sequence.
        for d in 1..4 {
            for (k, &v) in directions(d).iter().enumerate() {
                assert_eq!(v.trailing_zeros(), 31 - k as u32, "dim {d} k {k}");
            }
        }
    }

    #[test]
    fn tables_match_the_definition() {
        let mut x = 0x1234_5678u32;
        for _ in 0..20_000 {
            x = x.wrapping_mul(0x9e37_79b9).wrapping_add(0x7f4a_7c15);
            let r = reversed_dims(Wrapping(x.reverse_bits()));
            for (d, r) in r.iter().enumerate() {
                assert_eq!(r.0, plain(x, d).reverse_bits(), "index {x:#x} dim {d}");
            }
        }
    }

    /// Unscrambled dimensions 0 and 1: every aligned block of 2^m points is a (0,m,2)-net.
    #[test]
    fn dimensions_0_1_are_a_02_sequence() {
        for m in 0..=12u32 {
            for start in [0u32, 1 << 12, 0xdead_0000 & !((1 << m) - 1)] {
                for k in 0..=m {
                    let mut seen = std::vec![false; 1 << m];
                    for i in start..start + (1 << m) {
                        let (x, y) = (plain(i, 0), plain(i, 1));
                        let top = |v: u32, bits: u32| ((v as u64) << bits) >> 32;
                        let cell = (top(x, k) << (m - k)) | top(y, m - k);
                        let cell = cell as usize;
                        assert!(!core::mem::replace(&mut seen[cell], true), "m {m} k {k}");
                    }
                }
            }
        }
    }
}
