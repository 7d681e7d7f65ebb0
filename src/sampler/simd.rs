//! The sampler for 8 and 16 lanes (a wavefront renderer's pixels or sample indices side by
//! side) and the slice form: the same generic body as [`Sampler`], so the same bits.

use super::{Pattern, Sampler, State, unit};
use crate::lanes::UintLane;
use crate::slices::{self, Rows};
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
                Self::from_state(self.state.domain(P::ID, key))
            }
            /// [`Sampler::split`] lane by lane, with a sub-sample number per lane.
            #[inline]
            pub fn split(self, key: u32, size: u32, sub: $u) -> Self {
                Self::from_state(self.state.split(P::ID, key, size, sub))
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

/// [`Sampler::draw_slice`] on `LN`-lane vectors.
///
/// The aligned groups of `LN` indices take each pattern's group form (the keys of the one
/// domain derived once, the shuffle's common high bits once per group: see
/// `sobol::fill_groups` and `super::pmj02bn_groups`); the 0 to `LN - 1` indices before the
/// first aligned group and after the last run the generic body on lanes, the state
/// broadcast and the index counting up. Both give the scalar bits (tested at every start
/// and length).
#[inline(always)]
pub(super) fn draw_slice<P: Pattern, L: Rows<LN>, const LN: usize, const N: usize>(
    s: State<Wrapping<u32>>,
    out: &mut [[f32; N]],
) -> usize {
    let n = out.len();
    let wide = State {
        pixel: L::U::splat(s.pixel.0),
        domain: L::U::splat(s.domain.0),
        index: L::U::splat(0),
    };
    let lanes = |start: u32, part: &mut [[f32; N]]| {
        slices::fill_indexed::<L, LN, N>(start, part, |index| {
            State { index, ..wide }.bits::<N>(P::ID).map(unit::<L>)
        })
    };
    let start = s.index.0;
    // The draw's key, and the pixel's index offset in a `Blue<P>` slot (0 elsewhere): an
    // offset moves every index by an XOR, not along the aligned groups below, so such a
    // slice is drawn lane by lane (the same bits either way).
    let (seed, offset) = State {
        index: Wrapping(0),
        ..s
    }
    .keyed(P::ID);
    if offset.0 != 0 {
        lanes(start, out);
        return n;
    }
    let head = (start.wrapping_neg() as usize % LN).min(n);
    let (head_out, rest) = out.split_at_mut(head);
    lanes(start, head_out);
    let first = start.wrapping_add(head as u32);
    let (groups, tail) = rest.as_chunks_mut::<LN>();
    let seed = seed.0;
    if P::ID & !super::BLUE == super::SOBOL {
        super::sobol::fill_groups::<L, LN, N>(first, seed, groups);
    } else {
        super::pmj02bn_groups::<L, LN, N>(first, seed, groups);
    }
    lanes(first.wrapping_add((groups.len() * LN) as u32), tail);
    n
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use crate::sampler::{Pmj02bn, Sobol};
    use std::vec;

    /// The slice form at both widths (whatever `slices::Widest` this build has) against the
    /// scalar form: starts on both sides of the aligned groups and the wrap, lengths up to
    /// three groups of 16 and a run across a pmj02bn table block.
    fn slices_agree<P: Pattern, L: Rows<LN>, const LN: usize, const N: usize>() {
        for (t, start) in (0..17u32).chain([4096 - 21, u32::MAX - 40]).enumerate() {
            let s = Sampler::<P>::new([t as u32, 5], 3, start, 7).domain(t as u32);
            for len in (0..50).chain([4200]) {
                let mut out = vec![[9.0f32; N]; len];
                assert_eq!(draw_slice::<P, L, LN, N>(s.state, &mut out), len);
                for (k, o) in out.iter().enumerate() {
                    let want = s.with_index(start.wrapping_add(k as u32)).draw::<N>();
                    assert_eq!(
                        o.map(f32::to_bits),
                        want.map(f32::to_bits),
                        "{start} {len} {k}"
                    );
                }
            }
        }
    }

    #[test]
    fn slices_agree_at_both_widths() {
        slices_agree::<Sobol, f32x8, 8, 4>();
        slices_agree::<Sobol, f32x16, 16, 4>();
        slices_agree::<Sobol, f32x16, 16, 1>();
        slices_agree::<Pmj02bn, f32x8, 8, 4>();
        slices_agree::<Pmj02bn, f32x16, 16, 4>();
        slices_agree::<Pmj02bn, f32x16, 16, 2>();
        #[cfg(feature = "blue-noise")]
        {
            use crate::sampler::Blue;
            slices_agree::<Blue<Sobol>, f32x16, 16, 3>();
            slices_agree::<Blue<Pmj02bn>, f32x8, 8, 4>();
        }
    }
}
