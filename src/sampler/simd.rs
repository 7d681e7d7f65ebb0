//! The sampler for 8 and 16 lanes (a wavefront renderer's pixels or sample indices side by
//! side) and the slice form: the same generic body as [`Sampler`], so the same bits.

use super::{Pattern, Sampler, State, unit};
use crate::batch::{self, Vector};
use crate::lanes::UintLane;
use core::marker::PhantomData;
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// [`Sampler`] for eight lanes: lane `j` of every method equals the scalar method on
/// [`lane(j)`](Self::lane), bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplerX8<P: Pattern> {
    state: State<u32x8>,
    pattern: PhantomData<P>,
}

/// [`Sampler`] for sixteen lanes: lane `j` of every method equals the scalar method on
/// [`lane(j)`](Self::lane), bit for bit.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SamplerX16<P: Pattern> {
    state: State<u32x16>,
    pattern: PhantomData<P>,
}

/// The lane-generic half of the wide samplers: everything but the public signatures.
trait Words<const W: usize>: UintLane {
    fn from_array(a: [u32; W]) -> Self;
    fn into_array(self) -> [u32; W];
}
impl Words<8> for u32x8 {
    fn from_array(a: [u32; 8]) -> Self {
        u32x8::new(a)
    }
    fn into_array(self) -> [u32; 8] {
        self.to_array()
    }
}
impl Words<16> for u32x16 {
    fn from_array(a: [u32; 16]) -> Self {
        u32x16::new(a)
    }
    fn into_array(self) -> [u32; 16] {
        self.to_array()
    }
}

fn gather_lanes<U: Words<W>, P: Pattern, const W: usize>(s: [Sampler<P>; W]) -> State<U> {
    let st = s.map(|x| x.state);
    State {
        pixel: U::from_array(st.map(|x| x.pixel.0)),
        domain: U::from_array(st.map(|x| x.domain.0)),
        index: U::from_array(st.map(|x| x.index.0)),
    }
}

fn lane_of<U: Words<W>, P: Pattern, const W: usize>(s: State<U>, j: usize) -> Sampler<P> {
    let pick = |v: U| Wrapping(v.into_array()[j % W]);
    Sampler::from_state(State {
        pixel: pick(s.pixel),
        domain: pick(s.domain),
        index: pick(s.index),
    })
}

macro_rules! doc_same {
    () => {
        "The scalar method of the same name, lane by lane."
    };
}

/// One impl block for both widths (the bodies are one-line forwards to [`State`]).
macro_rules! wide_sampler {
    ($name:ident, $f:ident, $u:ident, $w:literal) => {
        impl<P: Pattern> $name<P> {
            /// Lane `j` is `Sampler::new([x[j], y[j]], frame[j], index[j], seed[j])`.
            #[inline]
            pub fn new(pixel: [$u; 2], frame: $u, index: $u, seed: $u) -> Self {
                Self::from_state(State::new(P::ID, pixel, frame, index, seed))
            }
            #[inline(always)]
            fn from_state(state: State<$u>) -> Self {
                $name {
                    state,
                    pattern: PhantomData,
                }
            }
            /// The lanes as one wide sampler (different pixels, indices or domains per lane).
            #[inline]
            pub fn from_lanes(lanes: [Sampler<P>; $w]) -> Self {
                Self::from_state(gather_lanes(lanes))
            }
            /// Every lane `sampler`.
            #[inline]
            pub fn splat(sampler: Sampler<P>) -> Self {
                Self::from_lanes([sampler; $w])
            }
            /// Lane `j` (modulo the width) as a scalar sampler.
            #[inline]
            pub fn lane(self, j: usize) -> Sampler<P> {
                lane_of(self.state, j)
            }
            #[doc = doc_same!()]
            #[inline]
            pub fn domain(self, key: u32) -> Self {
                Self::from_state(self.state.domain(key))
            }
            /// [`Sampler::split`] lane by lane, with a sub-sample number per lane.
            #[inline]
            pub fn split(self, key: u32, size: u32, sub: $u) -> Self {
                Self::from_state(self.state.split(key, size, sub))
            }
            #[doc = doc_same!()]
            #[inline]
            pub fn draw<const N: usize>(self) -> [$f; N] {
                self.state.bits::<N>(P::ID).map(unit::<$f>)
            }
            #[doc = doc_same!()]
            #[inline]
            pub fn draw_u32<const N: usize>(self) -> [$u; N] {
                self.state.bits::<N>(P::ID)
            }
            #[doc = doc_same!()]
            #[inline]
            pub fn rnd<const N: usize>(self) -> [$f; N] {
                self.state.rnd::<N>(P::ID).map(unit::<$f>)
            }
        }
    };
}

wide_sampler!(SamplerX8, f32x8, u32x8, 8);
wide_sampler!(SamplerX16, f32x16, u32x16, 16);

/// [`Sampler::draw_slice`] on `LN`-lane vectors: the scalar state broadcast, the index
/// counting up lane by lane.
#[inline(always)]
pub(super) fn draw_slice<P: Pattern, L: Vector<LN>, const LN: usize, const N: usize>(
    s: State<Wrapping<u32>>,
    out: &mut [[f32; N]],
) -> usize {
    let wide = State {
        pixel: L::U::splat(s.pixel.0),
        domain: L::U::splat(s.domain.0),
        index: L::U::splat(0),
    };
    batch::fill_indexed::<L, LN, N>(s.index.0, out, |index| {
        State { index, ..wide }.bits::<N>(P::ID).map(unit::<L>)
    })
}
