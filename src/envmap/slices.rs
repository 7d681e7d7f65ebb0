//! The slice forms of both distributions: batches of any length through the same generic
//! bodies as `sample` and `sample_x8`, with several lane groups interleaved.
//!
//! A walk is a chain of dependent table reads (one per pyramid block or CDF probe) with a
//! little integer work between them, so one group of lanes leaves the core waiting: on a
//! 4096 x 2048 map most reads miss the caches, and even on a map that fits in L2 each read's
//! latency is on the chain. A slice step therefore runs [`HIER`] (or [`MC`]) groups of eight
//! lanes as one [`Interleaved`] lane type: every operation, table reads included, is issued
//! for all groups before the next one, so that many independent chains overlap. Eight-lane
//! groups beat sixteen-lane ones even with AVX-512 (measured on Zen 4: 6 x 8 lanes 53 M/s,
//! 1 x 16 lanes 37 M/s, 2 x 16 lanes 18 M/s on the 4096 x 2048 `park` map): the 4 x 4
//! transposes of `gather4` are cheap at 256 bits, and 16-lane groups run out of registers
//! when interleaved. Group counts were measured per instruction set (`tools/slicebench`):
//! past six hierarchical groups the code spills (seven ran at 9 M/s).
//!
//! The rest of a batch (fewer than a whole step) runs group by group, and the last partial
//! group is padded with zeros (a valid input). Lanes never interact, so every element gets
//! exactly the bits of the scalar form.

use super::{Sample, samples_of};
use crate::lanes::{Interleaved, Lane, UintLane};
use crate::slices::{self, Vector};

/// The sealed [`Body`] (and [`Distribution`](super::Distribution)) impls of a distribution
/// type with lane-generic `sample_body` and `pdf_body` methods and `width`, `height` fields,
/// whose slices interleave `$groups` groups of eight lanes.
macro_rules! body {
    ($t:ident, $groups:ident) => {
        // Sealed supertrait of `Distribution`, generic over the crate's private lane traits.
        #[allow(private_bounds, private_interfaces)]
        impl slices::Body for $t<'_> {
            #[inline(always)]
            fn sample_lanes<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]) {
                self.sample_body(u)
            }
            #[inline(always)]
            fn pdf_lanes<L: Lane>(&self, uv: [L; 2]) -> L {
                self.pdf_body(uv)
            }
            #[inline(always)]
            fn size(&self) -> [u32; 2] {
                [self.width, self.height]
            }
            fn slice_sample(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize {
                slices::sample::<Self, f32x8, 8, { slices::$groups }>(self, u, out)
            }
            fn slice_pdf(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
                slices::pdf::<Self, f32x8, 8, { slices::$groups }>(self, uv, out)
            }
        }

        impl super::Distribution for $t<'_> {}
    };
}
pub(super) use body;

/// Groups of eight lanes a hierarchical slice step interleaves: six (48 walks in flight)
/// with AVX2 or AVX-512, two elsewhere (SSE2 and wasm `simd128`, where an eight-lane vector
/// takes two of the 16 registers and more groups spill). Measured: see the module docs.
#[cfg(target_feature = "avx2")]
pub(super) const HIER: usize = 6;
/// Groups of eight lanes a hierarchical slice step interleaves (see the AVX2 variant).
#[cfg(not(target_feature = "avx2"))]
pub(super) const HIER: usize = 2;

/// Groups of eight lanes a marginal-conditional slice step interleaves: four with AVX2 or
/// AVX-512, two elsewhere. Measured: see the module docs.
#[cfg(target_feature = "avx2")]
pub(super) const MC: usize = 4;
/// Groups of eight lanes a marginal-conditional slice step interleaves (see the AVX2 variant).
#[cfg(not(target_feature = "avx2"))]
pub(super) const MC: usize = 2;

/// What a body's `sample` returns over lane type `L`: `(uv, pdf, texel)`.
type Results<L> = ([L; 2], L, [<L as Lane>::U; 2]);

/// A distribution's generic bodies, as [`Distribution`](super::Distribution)'s provided
/// methods and the slice loops call them.
///
/// Public in a private module: the sealed supertrait of `Distribution` (users can name and
/// call `Distribution` but not implement it). Its methods are generic over the crate's
/// private lane traits, hence the `private_bounds` allowances here and on the two impls.
#[allow(private_bounds, private_interfaces)]
pub trait Body {
    /// `sample` over any lane type: `(uv, pdf, texel)`.
    fn sample_lanes<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]);
    /// `pdf` over any lane type.
    fn pdf_lanes<L: Lane>(&self, uv: [L; 2]) -> L;
    /// `[width, height]` in texels.
    fn size(&self) -> [u32; 2];
    /// The slice form of `sample` (each distribution picks its interleaving).
    fn slice_sample(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize;
    /// The slice form of `pdf`.
    fn slice_pdf(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize;
}

/// `G` groups of `N` elements as one interleaved vector per component.
#[inline(always)]
fn load<L: Vector<N>, const N: usize, const G: usize>(
    groups: &[[[f32; 2]; N]; G],
) -> [Interleaved<L, G>; 2] {
    let mut parts = [[L::splat(0.0); 2]; G];
    for (p, g) in parts.iter_mut().zip(groups) {
        *p = slices::load(g);
    }
    [0, 1].map(|k| Interleaved(core::array::from_fn(|g| parts[g][k])))
}

/// A body's lane results as `N` [`Sample`]s.
#[inline(always)]
fn samples<L: Vector<N>, const N: usize>((uv, pdf, texel): ([L; 2], L, [L::U; 2])) -> [Sample; N] {
    let [u, v, p] = [uv[0], uv[1], pdf].map(|x| L::to_words(x.to_bits()).map(f32::from_bits));
    samples_of(u, v, p, texel.map(L::to_words))
}

/// Part `g` of interleaved body results.
#[inline(always)]
fn part<L: Lane, const G: usize>(
    (uv, pdf, texel): Results<Interleaved<L, G>>,
    g: usize,
) -> ([L; 2], L, [L::U; 2]) {
    let pick = |x: Interleaved<L, G>| x.0.get(g).copied().unwrap_or(L::splat(0.0));
    let pick_u = |x: Interleaved<L::U, G>| x.0.get(g).copied().unwrap_or(L::U::splat(0));
    (uv.map(pick), pick(pdf), texel.map(pick_u))
}

/// The batch loop of both slice forms: `out[i] = f(input[i])` for
/// `i < min(input.len(), out.len())`, `G` groups of `N` at a time through `step`, the rest
/// group by group through `one`, the last partial group padded with zeros; returns the count.
#[inline(always)]
fn run<T: Copy, const N: usize, const G: usize>(
    input: &[[f32; 2]],
    out: &mut [T],
    step: impl Fn(&[[[f32; 2]; N]; G]) -> [[T; N]; G],
    one: impl Fn(&[[f32; 2]; N]) -> [T; N],
) -> usize {
    let n = input.len().min(out.len());
    let (input, out) = (
        input.get(..n).unwrap_or(&[]),
        out.get_mut(..n).unwrap_or(&mut []),
    );
    let (in_groups, in_rest) = input.as_chunks::<N>();
    let (out_groups, out_rest) = out.as_chunks_mut::<N>();
    let (in_steps, in_single) = in_groups.as_chunks::<G>();
    let (out_steps, out_single) = out_groups.as_chunks_mut::<G>();
    for (src, dst) in in_steps.iter().zip(out_steps) {
        *dst = step(src);
    }
    for (src, dst) in in_single.iter().zip(out_single) {
        *dst = one(src);
    }
    if !in_rest.is_empty() {
        let mut pad = [[0.0f32; 2]; N];
        for (p, s) in pad.iter_mut().zip(in_rest) {
            *p = *s;
        }
        for (o, r) in out_rest.iter_mut().zip(one(&pad)) {
            *o = r;
        }
    }
    n
}

/// `out[i] = sample(u[i])` for `i < min(u.len(), out.len())`; returns that count.
#[inline(always)]
pub(super) fn sample<D: Body, L: Vector<N>, const N: usize, const G: usize>(
    d: &D,
    u: &[[f32; 2]],
    out: &mut [Sample],
) -> usize {
    run::<Sample, N, G>(
        u,
        out,
        |src| {
            let r = d.sample_lanes::<Interleaved<L, G>>(load(src));
            core::array::from_fn(|g| samples(part(r, g)))
        },
        |src| samples(d.sample_lanes::<L>(slices::load(src))),
    )
}

/// `out[i] = pdf(uv[i])` for `i < min(uv.len(), out.len())`; returns that count.
#[inline(always)]
pub(super) fn pdf<D: Body, L: Vector<N>, const N: usize, const G: usize>(
    d: &D,
    uv: &[[f32; 2]],
    out: &mut [f32],
) -> usize {
    let words = |p: L| L::to_words(p.to_bits()).map(f32::from_bits);
    run::<f32, N, G>(
        uv,
        out,
        |src| d.pdf_lanes::<Interleaved<L, G>>(load(src)).0.map(words),
        |src| words(d.pdf_lanes::<L>(slices::load(src))),
    )
}
