//! [`Interleaved`]: `G` independent lane vectors advanced operation by operation, as one lane
//! type.
//!
//! A body written over [`Lane`] runs unchanged on `Interleaved<L, G>`: every operation is
//! applied to the `G` parts in turn before the next operation starts, so a table read is
//! issued for all `G` parts before any of them uses its result. That is what a latency-bound
//! body needs: the environment-map walks wait on one dependent cache miss per level, and
//! `G` groups of `L` walks keep `G` times as many misses in flight (the out-of-order window
//! does not reach the next group's loads on its own: one walk is hundreds of instructions).
//!
//! Every operation is the part's own operation on that part, so lane `j` of part `g` gets
//! exactly the bits `L` gives it: interleaving changes the order of independent work, never
//! a result.

use super::{Lane, Mask, UintLane};
use core::ops::{Add, BitAnd, BitOr, BitXor, Div, Mul, Neg, Not, Sub};

/// `G` lane vectors (or masks) of type `T`, operated on part by part.
#[derive(Clone, Copy)]
pub(crate) struct Interleaved<T, const G: usize>(pub(crate) [T; G]);

impl<T: Copy, const G: usize> Interleaved<T, G> {
    /// `f` on each part.
    #[inline(always)]
    fn map(self, f: impl Fn(T) -> T) -> Self {
        let mut out = self.0;
        for o in out.iter_mut() {
            *o = f(*o);
        }
        Interleaved(out)
    }

    /// `f` on each pair of parts.
    #[inline(always)]
    fn zip(self, rhs: Self, f: impl Fn(T, T) -> T) -> Self {
        let mut out = self.0;
        for (o, r) in out.iter_mut().zip(rhs.0) {
            *o = f(*o, r);
        }
        Interleaved(out)
    }

    /// `f` on each part, to another part type.
    #[inline(always)]
    fn to<R>(self, f: impl Fn(T) -> R) -> Interleaved<R, G> {
        Interleaved(core::array::from_fn(|g| f(self.0[g])))
    }
}

/// Implements a binary operator part by part.
macro_rules! binary {
    ($($tr:ident $f:ident),*) => {$(
        impl<T: Copy + $tr<Output = T>, const G: usize> $tr for Interleaved<T, G> {
            type Output = Self;
            #[inline(always)]
            fn $f(self, rhs: Self) -> Self {
                self.zip(rhs, T::$f)
            }
        }
    )*};
}
binary!(Add add, Sub sub, Mul mul, Div div, BitAnd bitand, BitOr bitor, BitXor bitxor);

impl<T: Copy + Not<Output = T>, const G: usize> Not for Interleaved<T, G> {
    type Output = Self;
    #[inline(always)]
    fn not(self) -> Self {
        self.map(T::not)
    }
}

impl<T: Copy + Neg<Output = T>, const G: usize> Neg for Interleaved<T, G> {
    type Output = Self;
    #[inline(always)]
    fn neg(self) -> Self {
        self.map(T::neg)
    }
}

impl<M: Mask, const G: usize> Mask for Interleaved<M, G> {}

/// `select` part by part.
#[inline(always)]
fn select<M: Copy, T: Copy, const G: usize>(
    mask: Interleaved<M, G>,
    if_true: Interleaved<T, G>,
    if_false: Interleaved<T, G>,
    f: impl Fn(M, T, T) -> T,
) -> Interleaved<T, G> {
    let mut out = if_false.0;
    for ((o, m), t) in out.iter_mut().zip(mask.0).zip(if_true.0) {
        *o = f(m, t, *o);
    }
    Interleaved(out)
}

/// A comparison part by part.
#[inline(always)]
fn compare<T: Copy, M, const G: usize>(
    a: Interleaved<T, G>,
    b: Interleaved<T, G>,
    f: impl Fn(T, T) -> M,
) -> Interleaved<M, G> {
    Interleaved(core::array::from_fn(|g| f(a.0[g], b.0[g])))
}

impl<U: UintLane, const G: usize> UintLane for Interleaved<U, G> {
    type Mask = Interleaved<U::Mask, G>;
    #[inline(always)]
    fn splat(x: u32) -> Self {
        Interleaved([U::splat(x); G])
    }
    #[inline(always)]
    fn shl(self, n: u32) -> Self {
        self.map(|x| x.shl(n))
    }
    #[inline(always)]
    fn shr(self, n: u32) -> Self {
        self.map(|x| x.shr(n))
    }
    #[inline(always)]
    fn simd_eq(self, rhs: Self) -> Self::Mask {
        compare(self, rhs, U::simd_eq)
    }
    #[inline(always)]
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self {
        select(mask, if_true, if_false, U::select)
    }
    #[inline(always)]
    fn simd_lt(self, rhs: Self) -> Self::Mask {
        compare(self, rhs, U::simd_lt)
    }
    #[inline(always)]
    fn mul_high(self, rhs: Self) -> Self {
        self.zip(rhs, U::mul_high)
    }
    #[inline(always)]
    fn gather<const N: usize>(table: &[[u32; N]], idx: Self) -> [Self; N] {
        let parts = idx.to(|i| U::gather(table, i)).0;
        core::array::from_fn(|k| Interleaved(core::array::from_fn(|g| parts[g][k])))
    }
    #[inline(always)]
    fn gather4(table: &[u32], start: Self) -> [Self; 4] {
        let parts = start.to(|i| U::gather4(table, i)).0;
        core::array::from_fn(|k| Interleaved(core::array::from_fn(|g| parts[g][k])))
    }
    #[inline(always)]
    fn gather2(table: &[u32], start: Self) -> [Self; 2] {
        let parts = start.to(|i| U::gather2(table, i)).0;
        core::array::from_fn(|k| Interleaved(core::array::from_fn(|g| parts[g][k])))
    }
    #[inline(always)]
    fn gather_pairs(self, f: impl Fn(u32) -> [u32; 2]) -> [Self; 2] {
        let parts = self.to(|x| x.gather_pairs(&f)).0;
        core::array::from_fn(|k| Interleaved(core::array::from_fn(|g| parts[g][k])))
    }
}

impl<L: Lane, const G: usize> Lane for Interleaved<L, G> {
    type Mask = Interleaved<L::Mask, G>;
    type U = Interleaved<L::U, G>;
    #[inline(always)]
    fn splat(x: f32) -> Self {
        Interleaved([L::splat(x); G])
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        self.map(L::sqrt)
    }
    #[inline(always)]
    fn simd_lt(self, rhs: Self) -> Self::Mask {
        compare(self, rhs, L::simd_lt)
    }
    #[inline(always)]
    fn simd_le(self, rhs: Self) -> Self::Mask {
        compare(self, rhs, L::simd_le)
    }
    #[inline(always)]
    fn simd_eq(self, rhs: Self) -> Self::Mask {
        compare(self, rhs, L::simd_eq)
    }
    #[inline(always)]
    fn select(mask: Self::Mask, if_true: Self, if_false: Self) -> Self {
        select(mask, if_true, if_false, L::select)
    }
    #[inline(always)]
    fn to_bits(self) -> Self::U {
        self.to(L::to_bits)
    }
    #[inline(always)]
    fn from_bits(bits: Self::U) -> Self {
        bits.to(L::from_bits)
    }
    #[inline(always)]
    fn to_uint(self) -> Self::U {
        self.to(L::to_uint)
    }
    #[inline(always)]
    fn from_uint(u: Self::U) -> Self {
        u.to(L::from_uint)
    }
}
