//! The lane abstraction: every warp in this crate is written once, generically over [`Lane`],
//! and instantiated for `f32` (one sample), [`f32x8`] (eight samples in SIMD lanes) and
//! [`f32x16`] (sixteen: one AVX-512 register, or two 8-lane halves where `wide` emulates it).
//!
//! The trait holds only operations whose result is fully specified by IEEE 754 (add, sub,
//! mul, div, sqrt, compare, bit operations), so the scalar and the SIMD instantiations of one
//! body produce the same bits by construction:
//!
//! * no fused multiply-add (`mul_add` fuses on some builds only);
//! * no approximate reciprocal or reciprocal square root;
//! * no `min`/`max`: their treatment of NaN and of `-0.0` vs `+0.0` differs between instruction
//!   sets. Warps clamp with compare + select on inputs already free of NaN, see
//!   [`unit_interval`] and [`signed_unit`].
//!
//! One thing IEEE 754 leaves open is the sign and payload of a NaN *produced* by an invalid
//! operation (x86 gives a negative "default NaN", ARM and wasm a positive canonical one, and
//! wasm may differ between its scalar and SIMD instructions). Warp bodies therefore never let a
//! NaN reach an output: inputs are sanitized first, and the few `0/0` intermediates are
//! replaced with a select before they are used.
//!
//! The square root is correctly rounded on every path: the hardware instruction for scalars
//! on x86 (through `wide`, see [`Lane::sqrt`] for `f32`), `libm::sqrtf` elsewhere, and for
//! `f32x8` and `f32x16` the hardware instruction where `wide` has one (SSE/AVX/AVX-512, wasm
//! `simd128`, aarch64 NEON; `f32x16` without AVX-512 is two `f32x8` square roots) and
//! `libm::sqrtf` per lane elsewhere (never `wide`'s no-std software fallback).
//!
//! The integer operations of `u32x16` match `u32x8` lane for lane: wrapping arithmetic,
//! shifts by a count taken modulo 32 (`wide` masks it on both), unsigned compares (AVX-512 has
//! an unsigned compare instruction; elsewhere `wide` biases by `2^31`), and selects on masks
//! whose lanes are all ones or all zeros (`wide` blends by the top bit or by bytes, which
//! agree on such masks). The tests below check each against the scalar `Wrapping<u32>`.

#[cfg(feature = "envmap")]
mod interleaved;
#[cfg(feature = "envmap")]
pub(crate) use interleaved::Interleaved;

use core::num::Wrapping;
use core::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};
use wide::{f32x4, f32x8, f32x16, u32x4, u32x8, u32x16};

/// `1 - 2^-24`, the largest `f32` below one: the top of every warp's input range.
pub(crate) const ONE_MINUS_EPSILON: f32 = 1.0 - 1.0 / 16_777_216.0;

/// A per-lane boolean: `bool` for scalars, all-ones/all-zeros `u32` lanes for `f32x8`.
pub(crate) trait Mask:
    Copy + BitAnd<Output = Self> + BitOr<Output = Self> + Not<Output = Self>
{
}

/// A lane-generic integer kernel of a word and a key, for [`UintLane::map4`] (a closure
/// cannot be generic over the lane type).
#[cfg(feature = "sampler")]
pub(crate) trait Kernel4: Copy {
    fn run<U: UintLane>(self, word: U, key: U) -> U;
}

/// What both lane kinds share: a `Copy` value with `+`, `-` and `*`.
pub(crate) trait Ring:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self>
{
}
impl<T: Copy + Add<Output = T> + Sub<Output = T> + Mul<Output = T>> Ring for T {}

/// The unsigned-integer lane paired with a [`Lane`]: `Wrapping<u32>` or [`u32x8`].
/// Arithmetic wraps (it never panics); shifts take the count modulo 32.
pub(crate) trait UintLane:
    Ring + BitAnd<Output = Self> + BitOr<Output = Self> + BitXor<Output = Self> + Not<Output = Self>
{
    type Mask: Mask;
    fn splat(x: u32) -> Self;
    fn shl(self, n: u32) -> Self;
    fn shr(self, n: u32) -> Self;
    fn simd_eq(self, rhs: Self) -> Self::Mask;
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    /// Unsigned `self < rhs`, lane by lane.
    fn simd_lt(self, rhs: Self) -> Self::Mask;
    /// The high 32 bits of the 64-bit product `self * rhs`, lane by lane.
    fn mul_high(self, rhs: Self) -> Self;
    /// Lane-wise table lookup of `N`-word records: lane `j` gets `table[idx_j]`. An index past
    /// the end reads zeros, so the lookup can never panic (callers index in range; SIMD lanes
    /// are loaded one by one, there is no gather instruction on the baseline targets).
    fn gather<const N: usize>(table: &[[u32; N]], idx: Self) -> [Self; N];
    /// Lane-wise read of four consecutive words: lane `j` gets `table[start_j..start_j + 4]`
    /// (zeros where that range is out of bounds, never a panic). For `u32x8` each lane is one
    /// 16-byte load and two 4x4 transposes make the four vectors.
    fn gather4(table: &[u32], start: Self) -> [Self; 4];
    /// Lane-wise read of two consecutive words: lane `j` gets `table[start_j..start_j + 2]`
    /// (zeros where that range is out of bounds, never a panic): one 8-byte load per lane.
    #[allow(dead_code)] // for the environment maps
    fn gather2(table: &[u32], start: Self) -> [Self; 2];

    /// Per lane, `f(lane)` split into two lanes: the table lookups of the sequences.
    #[allow(dead_code)] // for the table-driven families (pmj02bn)
    fn gather_pairs(self, f: impl Fn(u32) -> [u32; 2]) -> [Self; 2];

    /// `kernel` applied to four (word, key) pairs of this lane type: one call per pair, except
    /// that a scalar runs the four as one 4-lane vector (the same integer operations, so the
    /// same bits): one vector hash and vector bit reversals instead of four hashes and up to
    /// eight scalar reversals (no bit-reverse instruction on x86). The sampling core's Owen
    /// scrambles of a 4D point go through it (`crate::hash::owen_scramble4`).
    #[cfg(feature = "sampler")]
    #[inline(always)]
    fn map4<K: Kernel4>(words: [Self; 4], keys: [Self; 4], kernel: K) -> [Self; 4] {
        core::array::from_fn(|d| kernel.run(words[d], keys[d]))
    }

    /// Each lane rotated right by `n` bits (`n` in `1..32`): the cheap derived keys of the
    /// sampling core.
    #[allow(dead_code)] // for the sampling core
    #[inline(always)]
    fn rotr(self, n: u32) -> Self {
        self.shr(n) | self.shl(32 - n)
    }

    /// The bits of each lane in reverse order (bit 0 <-> bit 31): the swap network of
    /// Warren's *Hacker's Delight*, 7-1. Integer results, so every lane type agrees.
    #[allow(dead_code)] // for the scrambled sequences (pmj02bn)
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        let swap =
            |x: Self, n: u32, m: u32| (x.shr(n) & Self::splat(m)) | (x & Self::splat(m)).shl(n);
        let x = swap(self, 1, 0x5555_5555);
        let x = swap(x, 2, 0x3333_3333);
        let x = swap(x, 4, 0x0f0f_0f0f);
        let x = swap(x, 8, 0x00ff_00ff);
        x.shr(16) | x.shl(16)
    }
}

/// The float lane: `f32` or [`f32x8`]. See the module docs for what it may and may not hold.
pub(crate) trait Lane: Ring + Div<Output = Self> + Neg<Output = Self> {
    type Mask: Mask;
    type U: UintLane<Mask = Self::Mask>;

    fn splat(x: f32) -> Self;
    /// Correctly rounded square root.
    fn sqrt(self) -> Self;
    fn simd_lt(self, rhs: Self) -> Self::Mask;
    fn simd_le(self, rhs: Self) -> Self::Mask;
    fn simd_eq(self, rhs: Self) -> Self::Mask;
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self;
    fn to_bits(self) -> Self::U;
    fn from_bits(bits: Self::U) -> Self;
    /// Truncating conversion; only used for `0 <= self < 2^31` (where both instantiations
    /// agree exactly).
    fn to_uint(self) -> Self::U;
    /// Conversion of an integer below `2^24` (exact there).
    fn from_uint(u: Self::U) -> Self;

    /// `|self|`, by clearing the sign bit (so `abs(-0.0) = +0.0` and NaN stays NaN).
    #[inline(always)]
    fn abs(self) -> Self {
        Self::from_bits(self.to_bits() & Self::U::splat(0x7fff_ffff))
    }
    /// The sign bit of `self` (`0x8000_0000` or `0`) as an integer lane.
    #[inline(always)]
    fn sign_bit(self) -> Self::U {
        self.to_bits() & Self::U::splat(0x8000_0000)
    }
    /// `self` with its sign bit xor-ed with `sign` (a lane holding `0x8000_0000` or `0`).
    #[inline(always)]
    fn flip_sign(self, sign: Self::U) -> Self {
        Self::from_bits(self.to_bits() ^ sign)
    }
    /// `t` where the lane is one value and `mask` holds, else `all()`; `all()` must equal `t`
    /// in every lane where `mask` holds (it selects per lane). A rare path (a fallback) is then
    /// computed by the scalar form only when it is taken, with the same bits; the wide forms
    /// always call `all()`.
    #[inline(always)]
    fn unless<T>(mask: Self::Mask, t: T, all: impl FnOnce() -> T) -> T {
        let _ = (mask, t);
        all()
    }
}

impl Mask for bool {}

impl UintLane for Wrapping<u32> {
    type Mask = bool;
    #[inline(always)]
    fn splat(x: u32) -> Self {
        Wrapping(x)
    }
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        Wrapping(self.0.wrapping_shl(n))
    }
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        Wrapping(self.0.wrapping_shr(n))
    }
    #[inline(always)]
    fn simd_eq(self, rhs: Self) -> bool {
        self == rhs
    }
    #[inline(always)]
    fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
        if mask { if_true } else { if_false }
    }
    #[inline(always)]
    fn gather_pairs(self, f: impl Fn(u32) -> [u32; 2]) -> [Self; 2] {
        f(self.0).map(Wrapping)
    }
    #[inline(always)]
    fn reverse_bits(self) -> Self {
        // One instruction on aarch64 and thumbv7em; the same bits as the swap network.
        Wrapping(self.0.reverse_bits())
    }

    #[cfg(feature = "sampler")]
    #[inline(always)]
    fn map4<K: Kernel4>(words: [Self; 4], keys: [Self; 4], kernel: K) -> [Self; 4] {
        let w = u32x4::new(words.map(|w| w.0));
        let k = u32x4::new(keys.map(|k| k.0));
        kernel.run(w, k).to_array().map(Wrapping)
    }

    #[inline(always)]
    fn simd_lt(self, rhs: Self) -> bool {
        self < rhs
    }
    #[inline(always)]
    fn mul_high(self, rhs: Self) -> Self {
        Wrapping(((u64::from(self.0) * u64::from(rhs.0)) >> 32) as u32)
    }
    #[inline(always)]
    fn gather<const N: usize>(table: &[[u32; N]], idx: Self) -> [Self; N] {
        table
            .get(idx.0 as usize)
            .copied()
            .unwrap_or([0; N])
            .map(Wrapping)
    }
    #[inline(always)]
    fn gather4(table: &[u32], start: Self) -> [Self; 4] {
        words(table, start.0).map(Wrapping)
    }
    #[inline(always)]
    fn gather2(table: &[u32], start: Self) -> [Self; 2] {
        words(table, start.0).map(Wrapping)
    }
}

/// `table[start..start + N]` as an array, zeros when out of bounds.
#[inline(always)]
fn words<const N: usize>(table: &[u32], start: u32) -> [u32; N] {
    let start = start as usize;
    table
        .get(start..start.wrapping_add(N))
        .and_then(|s| <[u32; N]>::try_from(s).ok())
        .unwrap_or([0; N])
}

impl Lane for f32 {
    type Mask = bool;
    type U = Wrapping<u32>;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        // x86: the hardware square root through `wide` (an intrinsic LLVM sees, encoded like
        // the code around it), not `libm::sqrtf`, whose x86 version is an inline-asm legacy
        // `sqrtss`: opaque to the optimiser, and in VEX/EVEX code (`target-cpu` with AVX or
        // AVX-512) a legacy-SSE instruction, which pays SSE/AVX transition or merge penalties
        // on CPUs that have them. Both are IEEE 754 correctly rounded: the same bits.
        #[cfg(all(
            any(target_arch = "x86", target_arch = "x86_64"),
            target_feature = "sse"
        ))]
        {
            f32x4::splat(self).sqrt().to_array()[0]
        }
        #[cfg(not(all(
            any(target_arch = "x86", target_arch = "x86_64"),
            target_feature = "sse"
        )))]
        {
            libm::sqrtf(self)
        }
    }
    #[inline(always)]
    fn simd_lt(self, rhs: Self) -> bool {
        self < rhs
    }
    #[inline(always)]
    fn simd_le(self, rhs: Self) -> bool {
        self <= rhs
    }
    #[inline(always)]
    fn simd_eq(self, rhs: Self) -> bool {
        self == rhs
    }
    #[inline(always)]
    fn select(mask: bool, if_true: Self, if_false: Self) -> Self {
        if mask { if_true } else { if_false }
    }
    #[inline(always)]
    fn unless<T>(mask: bool, t: T, all: impl FnOnce() -> T) -> T {
        if mask { t } else { all() }
    }
    #[inline(always)]
    fn to_bits(self) -> Wrapping<u32> {
        Wrapping(f32::to_bits(self))
    }
    #[inline(always)]
    fn from_bits(bits: Wrapping<u32>) -> Self {
        f32::from_bits(bits.0)
    }
    #[inline(always)]
    fn to_uint(self) -> Wrapping<u32> {
        Wrapping(self as i32 as u32)
    }
    #[inline(always)]
    fn from_uint(u: Wrapping<u32>) -> Self {
        // Through i32 like the SIMD conversion, so both agree on every input.
        u.0 as i32 as f32
    }
}

/// Lane mask of SIMD comparisons ([`u32x8`] or [`u32x16`] lanes): each lane all ones (true)
/// or all zeros.
#[derive(Clone, Copy)]
pub(crate) struct SimdMask<U>(U);

impl<U: BitAnd<Output = U>> BitAnd for SimdMask<U> {
    type Output = Self;
    #[inline(always)]
    fn bitand(self, rhs: Self) -> Self {
        SimdMask(self.0 & rhs.0)
    }
}
impl<U: BitOr<Output = U>> BitOr for SimdMask<U> {
    type Output = Self;
    #[inline(always)]
    fn bitor(self, rhs: Self) -> Self {
        SimdMask(self.0 | rhs.0)
    }
}
impl<U: Not<Output = U>> Not for SimdMask<U> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        SimdMask(!self.0)
    }
}
impl<U: Copy + BitAnd<Output = U> + BitOr<Output = U> + Not<Output = U>> Mask for SimdMask<U> {}

/// The SIMD instantiations, `f32x8`/`u32x8` and `f32x16`/`u32x16`: one definition stamped out
/// for both widths, so the two cannot drift apart. Every operation maps to the `wide` operation
/// of the same name, which is lane-wise and IEEE-exact (or an integer operation) on every
/// target; where `wide` emulates a width (`f32x16` without AVX-512 is two `f32x8` halves,
/// `f32x8` without AVX is two SSE halves) the halves run the same instructions.
macro_rules! simd_lanes {
    ($f:ident, $u:ident, $n:literal, $from_int:ident) => {
        impl UintLane for $u {
            type Mask = SimdMask<$u>;
            #[inline(always)]
            fn splat(x: u32) -> Self {
                $u::splat(x)
            }
            #[inline(always)]
            fn shl(self, n: u32) -> Self {
                self << (n & 31)
            }
            #[inline(always)]
            fn shr(self, n: u32) -> Self {
                self >> (n & 31)
            }
            #[inline(always)]
            fn simd_eq(self, rhs: Self) -> SimdMask<$u> {
                SimdMask($u::simd_eq(self, rhs))
            }
            #[inline(always)]
            fn select(mask: SimdMask<$u>, if_true: Self, if_false: Self) -> Self {
                #[cfg(target_feature = "avx512f")]
                {
                    (mask.0 & if_true) | (!mask.0 & if_false)
                }
                #[cfg(not(target_feature = "avx512f"))]
                {
                    mask.0.select(if_true, if_false)
                }
            }
            #[inline(always)]
            fn reverse_bits(self) -> Self {
                // Lane by lane, so LLVM emits its vector bit-reverse (PSHUFB nibble tables on
                // SSSE3/AVX2, GFNI where available) instead of the 20-instruction swap network.
                $u::new(self.to_array().map(u32::reverse_bits))
            }
            #[inline(always)]
            fn gather_pairs(self, f: impl Fn(u32) -> [u32; 2]) -> [Self; 2] {
                let pairs = self.to_array().map(f);
                [$u::new(pairs.map(|p| p[0])), $u::new(pairs.map(|p| p[1]))]
            }
            #[inline(always)]
            fn simd_lt(self, rhs: Self) -> SimdMask<$u> {
                // Unsigned in `wide` (bias by 2^31 and a signed compare, or an unsigned
                // compare instruction): tested on both sides of 2^31.
                SimdMask($u::simd_lt(self, rhs))
            }
            #[inline(always)]
            fn mul_high(self, rhs: Self) -> Self {
                // On x86, lane by lane in `u64`: LLVM sees an unsigned multiply-high and emits
                // its even/odd `pmuludq` pair (`wide`'s version goes through arrays there).
                // Elsewhere `wide`'s own (wasm `simd128`: `i64x2.extmul`) is the faster one.
                #[cfg(target_arch = "x86_64")]
                {
                    let (a, b) = (self.to_array(), rhs.to_array());
                    let mut out = [0u32; $n];
                    for ((o, &x), &y) in out.iter_mut().zip(a.iter()).zip(b.iter()) {
                        *o = ((u64::from(x) * u64::from(y)) >> 32) as u32;
                    }
                    $u::new(out)
                }
                #[cfg(not(target_arch = "x86_64"))]
                {
                    self.mul_keep_high(rhs)
                }
            }
            #[inline(always)]
            fn gather<const N: usize>(table: &[[u32; N]], idx: Self) -> [Self; N] {
                let idx = idx.to_array();
                let rows: [[u32; N]; $n] =
                    core::array::from_fn(|j| table.get(idx[j] as usize).copied().unwrap_or([0; N]));
                core::array::from_fn(|k| $u::new(core::array::from_fn(|j| rows[j][k])))
            }
            #[inline(always)]
            fn gather2(table: &[u32], start: Self) -> [Self; 2] {
                let pairs = start.to_array().map(|s| words::<2>(table, s));
                [0, 1].map(|k| $u::new(core::array::from_fn(|j| pairs[j][k])))
            }
            #[inline(always)]
            fn gather4(table: &[u32], start: Self) -> [Self; 4] {
                // One 16-byte load per lane, a 4x4 transpose per four lanes.
                let start = start.to_array();
                let quads: [[u32x4; 4]; $n / 4] = core::array::from_fn(|g| {
                    u32x4::transpose(core::array::from_fn(|r| {
                        u32x4::new(words(table, start[4 * g + r]))
                    }))
                });
                core::array::from_fn(|k| {
                    bytemuck::cast(core::array::from_fn::<u32x4, { $n / 4 }, _>(|g| {
                        quads[g][k]
                    }))
                })
            }
        }

        impl Lane for $f {
            type Mask = SimdMask<$u>;
            type U = $u;
            #[inline(always)]
            fn splat(x: f32) -> Self {
                $f::splat(x)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                // `wide`'s sqrt is the hardware instruction (correctly rounded) on these
                // targets, for `f32x16` too (AVX-512, or two `f32x8` halves); elsewhere it
                // would be a software approximation, so libm's correctly rounded one per lane.
                #[cfg(any(
                    target_feature = "sse",
                    target_feature = "simd128",
                    all(target_arch = "aarch64", target_feature = "neon")
                ))]
                {
                    $f::sqrt(self)
                }
                #[cfg(not(any(
                    target_feature = "sse",
                    target_feature = "simd128",
                    all(target_arch = "aarch64", target_feature = "neon")
                )))]
                {
                    $f::new(self.to_array().map(libm::sqrtf))
                }
            }
            #[inline(always)]
            fn simd_lt(self, rhs: Self) -> SimdMask<$u> {
                SimdMask(bytemuck::cast($f::simd_lt(self, rhs)))
            }
            #[inline(always)]
            fn simd_le(self, rhs: Self) -> SimdMask<$u> {
                SimdMask(bytemuck::cast($f::simd_le(self, rhs)))
            }
            #[inline(always)]
            fn simd_eq(self, rhs: Self) -> SimdMask<$u> {
                SimdMask(bytemuck::cast($f::simd_eq(self, rhs)))
            }
            #[inline(always)]
            fn select(mask: SimdMask<$u>, if_true: Self, if_false: Self) -> Self {
                #[cfg(target_feature = "avx512f")]
                {
                    let (t, f) = (if_true.to_bits(), if_false.to_bits());
                    bytemuck::cast((mask.0 & t) | (!mask.0 & f))
                }
                #[cfg(not(target_feature = "avx512f"))]
                {
                    bytemuck::cast::<$u, $f>(mask.0).select(if_true, if_false)
                }
            }
            #[inline(always)]
            fn to_bits(self) -> $u {
                bytemuck::cast(self)
            }
            #[inline(always)]
            fn from_bits(bits: $u) -> Self {
                bytemuck::cast(bits)
            }
            #[inline(always)]
            fn to_uint(self) -> $u {
                bytemuck::cast(self.trunc_int())
            }
            #[inline(always)]
            fn from_uint(u: $u) -> Self {
                $f::$from_int(bytemuck::cast(u))
            }
        }
    };
}

simd_lanes!(f32x4, u32x4, 4, from_i32x4);
simd_lanes!(f32x8, u32x8, 8, from_i32x8);
simd_lanes!(f32x16, u32x16, 16, from_i32x16);

/// Maps any `f32` onto a warp's input range `[0, 1 - 2^-24]`: values in `[0, 1)` pass
/// unchanged, values `>= 1` and `+inf` become `1 - 2^-24`, and NaN, `-0.0`, negatives and
/// `-inf` become `+0.0`. This is the documented out-of-range rule of every forward warp.
#[inline(always)]
pub(crate) fn unit_interval<L: Lane>(x: L) -> L {
    let zero = L::splat(0.0);
    let top = L::splat(ONE_MINUS_EPSILON);
    // `0 < x` is false for NaN and for -0.0, so both become +0.0.
    L::select(zero.simd_lt(x), L::select(x.simd_lt(top), x, top), zero)
}

/// Maps any `f32` onto `[-1, 1]`: NaN becomes `+0.0` (and `-0.0` stays `-0.0`), values beyond
/// the ends clamp to them. The out-of-range rule of the inverse warps' coordinates.
#[inline(always)]
pub(crate) fn signed_unit<L: Lane>(x: L) -> L {
    let one = L::splat(1.0);
    let x = L::select(x.simd_eq(x), x, L::splat(0.0));
    L::select(x.simd_lt(-one), -one, L::select(one.simd_lt(x), one, x))
}

#[cfg(test)]
#[allow(clippy::needless_range_loop)]
mod tests {
    use super::*;

    fn specials() -> [f32; 16] {
        [
            0.0,
            -0.0,
            0.5,
            ONE_MINUS_EPSILON,
            1.0,
            -1.0,
            f32::NAN,
            -f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MAX,
            1.5,
            f32::from_bits(0x007f_ffff),
            -f32::from_bits(0x7fc0_1234),
        ]
    }

    /// The scalar square root (the hardware instruction through `wide` on x86) is
    /// `libm::sqrtf` bit for bit: on every non-negative `f32` at a stride through the whole
    /// range, subnormals, powers of two and their neighbours, and the specials (negative
    /// inputs and NaN give a NaN either way).
    #[test]
    fn scalar_sqrt_is_libm_sqrtf() {
        let check = |x: f32| {
            let (a, b) = (<f32 as Lane>::sqrt(x), libm::sqrtf(x));
            if b.is_nan() {
                assert!(a.is_nan(), "sqrt({x:e}) = {a:e}, libm NaN");
            } else {
                assert_eq!(a.to_bits(), b.to_bits(), "sqrt({x:e})");
            }
        };
        for bits in (0..0x7f80_0000u32).step_by(997) {
            check(f32::from_bits(bits));
        }
        for e in 0..256u32 {
            for m in [0u32, 1, 2, 0x7f_fffe, 0x7f_ffff] {
                check(f32::from_bits((e << 23) | m));
            }
        }
        specials().into_iter().for_each(check);
    }

    #[test]
    fn unit_interval_rule() {
        for x in specials() {
            let y = unit_interval(x);
            assert!((0.0..1.0).contains(&y), "{x} -> {y}");
            assert_eq!(y.to_bits() >> 31, 0, "{x} -> {y} keeps a sign bit");
            if (0.0..1.0).contains(&x) && x.to_bits() >> 31 == 0 {
                assert_eq!(y.to_bits(), x.to_bits());
            }
        }
        assert_eq!(unit_interval(f32::NAN), 0.0);
        assert_eq!(unit_interval(2.0), ONE_MINUS_EPSILON);
        assert_eq!(unit_interval(-3.0), 0.0);
    }

    #[test]
    fn signed_unit_rule() {
        for x in specials() {
            let y = signed_unit(x);
            assert!((-1.0..=1.0).contains(&y), "{x} -> {y}");
        }
        assert_eq!(signed_unit(f32::NAN), 0.0);
        assert_eq!(signed_unit(f32::NEG_INFINITY), -1.0);
        assert_eq!(signed_unit(0.25), 0.25);
    }

    /// Every lane operation gives the same bits for f32 and f32x8, special values included.
    #[test]
    fn lanes_agree() {
        let xs = specials();
        for &a in &xs {
            for &b in &xs {
                let (va, vb) = (f32x8::splat(a), f32x8::splat(b));
                // NaN results of invalid operations (sqrt(-1), 0/0, inf - inf) may differ in
                // sign and payload between instruction sets: any NaN equals any NaN here.
                let same = |s: f32, v: f32x8| {
                    let v = v.to_array()[3];
                    assert!(
                        s.to_bits() == v.to_bits() || s.is_nan() && v.is_nan(),
                        "{a} {b}: {s} vs {v}"
                    );
                };
                same(a + b, va + vb);
                same16(a, b);
                same(a - b, va - vb);
                same(a * b, va * vb);
                same(a / b, va / vb);
                same(Lane::sqrt(a), Lane::sqrt(va));
                same(unit_interval(a), unit_interval(va));
                same(signed_unit(a), signed_unit(va));
                same(Lane::abs(a), Lane::abs(va));
                same(
                    f32::select(a.simd_lt(b), 1.0, 2.0),
                    f32x8::select(va.simd_lt(vb), f32x8::ONE, f32x8::splat(2.0)),
                );
                same(
                    f32::select(a.simd_le(b), 1.0, 2.0),
                    f32x8::select(va.simd_le(vb), f32x8::ONE, f32x8::splat(2.0)),
                );
            }
        }
        for u in [0u32, 1, 3, 1 << 23, (1 << 24) - 1] {
            let s = <f32 as Lane>::from_uint(Wrapping(u));
            let v = <f32x8 as Lane>::from_uint(u32x8::splat(u)).to_array()[0];
            assert_eq!(s.to_bits(), v.to_bits());
            assert_eq!(s as u32, u);
            assert_eq!(Lane::to_uint(s).0, u);
            assert_eq!(Lane::to_uint(f32x8::splat(s)).to_array()[5], u);
        }
        // Truncation agrees up to 2^31 (the envmap fixed-point keys go that high).
        for x in [16_777_217.0f32, 2_147_483_520.0, 1.5e9] {
            assert_eq!(Lane::to_uint(x).0, x as u32);
            assert_eq!(Lane::to_uint(f32x8::splat(x)).to_array()[2], x as u32);
        }
        for w in [0u32, 1, 0x8000_0000, 0x1234_5678, 0xdead_beef, u32::MAX] {
            let v = u32x8::splat(w).reverse_bits().to_array();
            assert!(v.iter().all(|&r| r == w.reverse_bits()), "{w:#x}");
            assert_eq!(Wrapping(w).reverse_bits().0, w.reverse_bits());
            let g = u32x8::splat(w).gather_pairs(|x| [x ^ 1, x.rotate_left(3)]);
            assert_eq!(
                [g[0].to_array()[2], g[1].to_array()[7]],
                [w ^ 1, w.rotate_left(3)]
            );
        }
        for k in [0, 1, 5, 31, 32, 33] {
            let w = Wrapping(0x8000_0001u32);
            assert_eq!(w.shl(k).0, u32x8::splat(w.0).shl(k).to_array()[0]);
            assert_eq!(w.shr(k).0, u32x8::splat(w.0).shr(k).to_array()[0]);
        }
    }

    /// Every float lane operation of `f32x16` against the scalar one, for `(a, b)` in lane 11
    /// and other values in the rest (without AVX-512 `wide` runs two `f32x8` halves; with it,
    /// other instructions: both must agree with the scalar bits).
    fn same16(a: f32, b: f32) {
        let fill = |x: f32| {
            let mut v = [0.75f32; 16];
            v[11] = x;
            v[3] = -x;
            f32x16::new(v)
        };
        let (va, vb) = (fill(a), fill(b));
        let same = |s: f32, v: f32x16, what: &str| {
            let v = v.to_array()[11];
            assert!(
                s.to_bits() == v.to_bits() || s.is_nan() && v.is_nan(),
                "x16 {what} {a} {b}: {s} vs {v}"
            );
        };
        same(a + b, va + vb, "add");
        same(a - b, va - vb, "sub");
        same(a * b, va * vb, "mul");
        same(a / b, va / vb, "div");
        same(-a, -va, "neg");
        same(Lane::sqrt(a), Lane::sqrt(va), "sqrt");
        same(unit_interval(a), unit_interval(va), "unit_interval");
        same(signed_unit(a), signed_unit(va), "signed_unit");
        same(Lane::abs(a), Lane::abs(va), "abs");
        let pick = |m: bool| if m { 1.0 } else { 2.0 };
        let one = f32x16::ONE;
        let two = f32x16::splat(2.0);
        same(pick(a < b), f32x16::select(va.simd_lt(vb), one, two), "lt");
        same(pick(a <= b), f32x16::select(va.simd_le(vb), one, two), "le");
        same(pick(a == b), f32x16::select(va.simd_eq(vb), one, two), "eq");
        // Masks combine lane-wise like bools.
        let (lt, eq, gt) = (a < b, a == b, b < a);
        let m = (va.simd_lt(vb) | va.simd_eq(vb)) & !vb.simd_lt(va);
        same(
            pick((lt | eq) & !gt),
            f32x16::select(m, one, two),
            "mask ops",
        );
        assert_eq!(Lane::to_bits(va).to_array()[11], a.to_bits());
        assert_eq!(
            <f32x16 as Lane>::from_bits(u32x16::splat(a.to_bits())).to_array()[11].to_bits(),
            a.to_bits()
        );
        assert_eq!(Lane::sign_bit(va).to_array()[11], a.to_bits() & 0x8000_0000);
    }

    /// The integer lane operations of `u32x16` against `Wrapping<u32>`, lane by lane, on values
    /// on both sides of `2^31` (unsigned compares), every shift count (taken modulo 32),
    /// wrapping multiplication, the high half of the product and the bit reversal.
    #[test]
    fn uint16_agrees_with_scalar() {
        let vals = [
            0u32,
            1,
            2,
            0x7fff_ffff,
            0x8000_0000,
            0x8000_0001,
            0xdead_beef,
            0x1234_5678,
            u32::MAX,
            u32::MAX - 1,
            3,
            0x5555_5555,
            0xaaaa_aaaa,
            1 << 24,
            (1 << 24) - 1,
            42,
        ];
        let va = u32x16::new(vals);
        for rot in 0..16 {
            let b: [u32; 16] = core::array::from_fn(|j| vals[(j + rot) % 16]);
            let vb = u32x16::new(b);
            let lanes = |v: u32x16| v.to_array();
            let bit = |m: SimdMask<u32x16>| {
                lanes(<u32x16 as UintLane>::select(
                    m,
                    u32x16::splat(1),
                    u32x16::ZERO,
                ))
            };
            let (add, sub, mul) = (lanes(va + vb), lanes(va - vb), lanes(va * vb));
            let (and, or, xor, not) = (lanes(va & vb), lanes(va | vb), lanes(va ^ vb), lanes(!va));
            let (lt, eq) = (
                bit(UintLane::simd_lt(va, vb)),
                bit(UintLane::simd_eq(va, vb)),
            );
            let high = lanes(va.mul_high(vb));
            for j in 0..16 {
                let (x, y) = (Wrapping(vals[j]), Wrapping(b[j]));
                assert_eq!(add[j], (x + y).0);
                assert_eq!(sub[j], (x - y).0);
                assert_eq!(mul[j], (x * y).0);
                assert_eq!(
                    [and[j], or[j], xor[j], not[j]],
                    [(x & y).0, (x | y).0, (x ^ y).0, (!x).0]
                );
                assert_eq!(lt[j] == 1, x < y, "{x} < {y}");
                assert_eq!(eq[j] == 1, x == y);
                assert_eq!(high[j], x.mul_high(y).0);
                let sel = <u32x16 as UintLane>::select(UintLane::simd_lt(va, vb), va, vb);
                assert_eq!(sel.to_array()[j], if x < y { x.0 } else { y.0 });
            }
        }
        for n in [0, 1, 5, 16, 31, 32, 33, 63, 64, u32::MAX] {
            let (l, r) = (va.shl(n).to_array(), va.shr(n).to_array());
            for j in 0..16 {
                assert_eq!(l[j], Wrapping(vals[j]).shl(n).0, "{:#x} << {n}", vals[j]);
                assert_eq!(r[j], Wrapping(vals[j]).shr(n).0, "{:#x} >> {n}", vals[j]);
            }
        }
        let rev = va.reverse_bits().to_array();
        let pairs = va.gather_pairs(|x| [x ^ 1, x.rotate_left(3)]);
        for j in 0..16 {
            assert_eq!(rev[j], vals[j].reverse_bits());
            assert_eq!(
                [pairs[0].to_array()[j], pairs[1].to_array()[j]],
                [vals[j] ^ 1, vals[j].rotate_left(3)]
            );
        }
        // Float <-> integer conversions on the ranges the bodies use.
        let ints = u32x16::new(core::array::from_fn(|j| {
            [0, 1, 3, 1 << 23, (1 << 24) - 1][j % 5]
        }));
        let f = <f32x16 as Lane>::from_uint(ints);
        for j in 0..16 {
            let u = ints.to_array()[j];
            assert_eq!(
                f.to_array()[j].to_bits(),
                <f32 as Lane>::from_uint(Wrapping(u)).to_bits()
            );
        }
        let big = f32x16::new(core::array::from_fn(|j| {
            [
                0.0,
                0.99,
                1.5,
                16_777_217.0,
                2_147_483_520.0,
                1.5e9,
                7.25,
                3.0,
            ][j % 8]
        }));
        let t = Lane::to_uint(big).to_array();
        for j in 0..16 {
            let x = big.to_array()[j];
            assert_eq!(t[j], Lane::to_uint(x).0, "{x}");
        }
    }

    /// The 16-lane gathers read the same records as the scalar ones, zeros out of bounds.
    #[test]
    fn gathers16_agree_with_scalar() {
        let table: [[u32; 3]; 5] = core::array::from_fn(|i| [10 * i as u32, 10 * i as u32 + 1, 7]);
        let flat: [u32; 11] = core::array::from_fn(|i| 100 + i as u32);
        let idx = [
            0u32,
            1,
            2,
            3,
            4,
            5,
            u32::MAX,
            7,
            4,
            3,
            2,
            1,
            0,
            8,
            9,
            1 << 31,
        ];
        let g = u32x16::gather(&table, u32x16::new(idx));
        let g4 = u32x16::gather4(&flat, u32x16::new(idx));
        let g2 = u32x16::gather2(&flat, u32x16::new(idx));
        let g2_8 = u32x8::gather2(&flat, u32x8::new(core::array::from_fn(|j| idx[j])));
        for j in 0..16 {
            let s = <Wrapping<u32> as UintLane>::gather(&table, Wrapping(idx[j]));
            let s4 = <Wrapping<u32> as UintLane>::gather4(&flat, Wrapping(idx[j]));
            let s2 = <Wrapping<u32> as UintLane>::gather2(&flat, Wrapping(idx[j]));
            for k in 0..2 {
                assert_eq!(g2[k].to_array()[j], s2[k].0, "gather2 lane {j} word {k}");
                if j < 8 {
                    assert_eq!(g2_8[k].to_array()[j], s2[k].0, "gather2 x8 lane {j}");
                }
            }
            for k in 0..3 {
                assert_eq!(g[k].to_array()[j], s[k].0, "gather lane {j} word {k}");
            }
            for k in 0..4 {
                assert_eq!(g4[k].to_array()[j], s4[k].0, "gather4 lane {j} word {k}");
            }
        }
        // In-range reads are really read (not zeros): lane 5 of gather4 starts at word 5.
        assert_eq!(g4[3].to_array()[5], 108);
        assert_eq!(g4[0].to_array()[7], 107);
        assert_eq!(g4[0].to_array()[13], 0); // 8..12 is past the end
        // gather2: 9..11 is the last full pair, 10..12 is past the end.
        assert_eq!([g2[0].to_array()[14], g2[1].to_array()[14]], [109, 110]);
        assert_eq!(g2[0].to_array()[8], 104);
        assert_eq!(g2[1].to_array()[13], 109);
        assert_eq!(g[1].to_array()[4], 41);
    }

    /// Unsigned compares (the top bit is a value, not a sign) and panic-free gathers.
    #[test]
    fn uint_compare_and_gather() {
        let vals = [0u32, 1, 0x7fff_ffff, 0x8000_0000, 0x8000_0001, u32::MAX];
        for &a in &vals {
            for &b in &vals {
                let s = UintLane::simd_lt(Wrapping(a), Wrapping(b));
                let v = UintLane::simd_lt(u32x8::splat(a), u32x8::splat(b));
                let v = <u32x8 as UintLane>::select(v, u32x8::splat(1), u32x8::splat(0)).to_array();
                assert_eq!(s, a < b);
                assert_eq!(v, [(a < b) as u32; 8]);
            }
        }
        for &a in &vals {
            for &b in &vals {
                let s = Wrapping(a).mul_high(Wrapping(b)).0;
                assert_eq!(s, ((a as u64 * b as u64) >> 32) as u32);
                let v = u32x8::new([a, b, a, b, 1, a, 0, b])
                    .mul_high(u32x8::new([b, a, b, a, a, 1, b, 0]));
                assert_eq!(v.to_array(), [s, s, s, s, 0, 0, 0, 0]);
            }
        }
        let table = [[1u32, 2], [3, 4], [5, 6]];
        assert_eq!(
            <Wrapping<u32> as UintLane>::gather(&table, Wrapping(1)),
            [Wrapping(3), Wrapping(4)]
        );
        assert_eq!(
            <Wrapping<u32> as UintLane>::gather(&table, Wrapping(3)),
            [Wrapping(0), Wrapping(0)]
        );
        let flat = [1u32, 2, 3, 4, 5, 6];
        let w = <Wrapping<u32> as UintLane>::gather4(&flat, Wrapping(2));
        assert_eq!(w, [3, 4, 5, 6].map(Wrapping));
        let w = <Wrapping<u32> as UintLane>::gather4(&flat, Wrapping(3));
        assert_eq!(w, [Wrapping(0); 4]);
        let v = u32x8::gather4(&flat, u32x8::new([0, 2, 3, 1, u32::MAX, 1, 2, 0]));
        assert_eq!(v[0].to_array(), [1, 3, 0, 2, 0, 2, 3, 1]);
        assert_eq!(v[3].to_array(), [4, 6, 0, 5, 0, 5, 6, 4]);
        let g = u32x8::gather(&table, u32x8::new([0, 1, 2, 3, u32::MAX, 2, 1, 0]));
        assert_eq!(g[0].to_array(), [1, 3, 5, 0, 0, 5, 3, 1]);
        assert_eq!(g[1].to_array(), [2, 4, 6, 0, 0, 6, 4, 2]);
    }
}
