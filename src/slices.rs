//! Slice forms: run a SIMD warp body over an array-of-structs batch of any length.
//!
//! Full groups of `N` elements (`N` = 8 or 16, see [`Widest`]) are transposed into SIMD
//! lanes, warped and transposed back; the last `len % N` elements are padded with zeros (a
//! valid input) and run through the same body, so every element of a slice gets exactly the
//! bits the scalar form gives (the lanes of one body never interact). There is no indexing
//! that can panic: lengths are reconciled with `get`, and groups come from `as_chunks`.

use crate::lanes::{Lane, UintLane};
use wide::{ShuffleExt, f32x8, f32x16, u32x8, u32x16};
#[cfg(feature = "sampler")]
use wide::{u64x4, u64x8};

/// The lane type the slice forms run: [`f32x16`] when the build has AVX-512F (`-C
/// target-cpu=native` on such a CPU, or `-C target-feature=+avx512f`), [`f32x8`] otherwise
/// (where `wide` would emulate the 16 lanes as two 8-lane halves, which gains nothing). A
/// compile-time choice: no runtime detection, no `unsafe`. Both widths give the same bits.
#[cfg(target_feature = "avx512f")]
pub(crate) type Widest = f32x16;
/// The lane type the slice forms run (see the AVX-512F variant).
#[cfg(not(target_feature = "avx512f"))]
pub(crate) type Widest = f32x8;

/// A SIMD [`Lane`] of `N` lanes as the slice machinery sees it: its integer lanes as arrays,
/// and a lane permute.
pub(crate) trait Vector<const N: usize>: Lane {
    fn words(w: [u32; N]) -> Self::U;
    fn to_words(v: Self::U) -> [u32; N];
    /// Lane `l` of the result is lane `index[l] % N` of `v` (used where `wide`'s shuffle is an
    /// instruction, see [`permute`]).
    #[cfg_attr(
        not(any(
            target_feature = "avx2",
            target_feature = "ssse3",
            target_feature = "simd128",
            all(target_arch = "aarch64", target_feature = "neon")
        )),
        allow(dead_code)
    )]
    fn shuffle(v: Self::U, index: Self::U) -> Self::U;
    /// Lane `l` is lane `index[l]` of `a` for `index[l] < N`, else lane `index[l] - N` of `b`
    /// (`index[l] < 2 N`): one `vpermt2d` with AVX-512.
    #[cfg_attr(not(target_feature = "avx512f"), allow(dead_code))]
    fn shuffle2(a: Self::U, b: Self::U, index: Self::U) -> Self::U;
    /// `mask ? a : b` lane by lane, for masks of all-ones or all-zeros lanes.
    #[cfg_attr(
        any(
            target_feature = "avx512f",
            not(any(
                target_feature = "avx2",
                target_feature = "ssse3",
                target_feature = "simd128",
                all(target_arch = "aarch64", target_feature = "neon")
            ))
        ),
        allow(dead_code)
    )]
    fn select_words(mask: Self::U, a: Self::U, b: Self::U) -> Self::U;
}

/// [`Vector`] (and [`Rows`]) for `f32x8` and `f32x16`: each operation is `wide`'s of the same
/// name (`$w` is the integer vector of `$n / 2` 64-bit lanes).
macro_rules! vector {
    ($f:ident, $u:ident, $n:literal, $w:ident) => {
        impl Vector<$n> for $f {
            #[inline(always)]
            fn words(w: [u32; $n]) -> $u {
                $u::new(w)
            }
            #[inline(always)]
            fn to_words(v: $u) -> [u32; $n] {
                v.to_array()
            }
            #[inline(always)]
            fn shuffle(v: $u, index: $u) -> $u {
                v.shuffle(index)
            }
            #[inline(always)]
            fn shuffle2(a: $u, b: $u, index: $u) -> $u {
                [a, b].shuffle(index)
            }
            #[inline(always)]
            fn select_words(mask: $u, a: $u, b: $u) -> $u {
                mask.select(a, b)
            }
        }

        #[cfg(feature = "sampler")]
        impl Rows<$n> for $f {
            #[inline(always)]
            fn zip32(a: $u, b: $u) -> [$u; 2] {
                [a.unpack_lo(b), a.unpack_hi(b)]
            }
            #[inline(always)]
            fn zip64(a: $u, b: $u) -> [$u; 2] {
                let (a, b): ($w, $w) = (bytemuck::cast(a), bytemuck::cast(b));
                [
                    bytemuck::cast(a.unpack_lo(b)),
                    bytemuck::cast(a.unpack_hi(b)),
                ]
            }
        }
    };
}

vector!(f32x8, u32x8, 8, u64x4);
vector!(f32x16, u32x16, 16, u64x8);

/// Writes the first `dst.len()` elements of a padded group's results (the tail of a slice).
#[inline(always)]
fn write_tail<const O: usize, const N: usize>(dst: &mut [[f32; O]], res: [[f32; O]; N]) {
    for (d, r) in dst.iter_mut().zip(res.iter()) {
        *d = *r;
    }
}

/// Applies `f` to `input[i]`, writing `output[i]`, for `i < min(input.len(), output.len())`;
/// returns that count. Extra elements of the longer slice are not read or written.
#[inline(always)]
pub(crate) fn map_lanes<L: Vector<N>, const N: usize, const I: usize, const O: usize>(
    input: &[[f32; I]],
    output: &mut [[f32; O]],
    f: impl Fn([L; I]) -> [L; O],
) -> usize {
    let n = input.len().min(output.len());
    let input = input.get(..n).unwrap_or(&[]);
    let output = output.get_mut(..n).unwrap_or(&mut []);
    let (in_groups, in_rest) = input.as_chunks::<N>();
    let (out_groups, out_rest) = output.as_chunks_mut::<N>();
    for (src, dst) in in_groups.iter().zip(out_groups) {
        *dst = store(f(load(src)));
    }
    if !in_rest.is_empty() {
        let mut pad = [[0.0f32; I]; N];
        for (p, s) in pad.iter_mut().zip(in_rest) {
            *p = *s;
        }
        write_tail(out_rest, store(f(load(&pad))));
    }
    n
}

/// [`map_lanes`] with an 8-wide body (the environment-map slices).
#[inline(always)]
pub(crate) fn map<const I: usize, const O: usize>(
    input: &[[f32; I]],
    output: &mut [[f32; O]],
    f: impl Fn([f32x8; I]) -> [f32x8; O],
) -> usize {
    map_lanes(input, output, f)
}

/// Fills `output[i]` with `f` at the index `start + i` (wrapping), `N` indices at a time;
/// for the index-driven sequences and constructions. Returns `output.len()`.
#[cfg_attr(
    not(any(feature = "triangle", feature = "pmj02bn", feature = "sequence")),
    allow(dead_code)
)]
#[inline(always)]
pub(crate) fn fill_indexed<L: Vector<N>, const N: usize, const O: usize>(
    start: u32,
    output: &mut [[f32; O]],
    f: impl Fn(L::U) -> [L; O],
) -> usize {
    let mut index = <L::U as UintLane>::splat(start) + lane_numbers::<L, N>();
    let (groups, rest) = output.as_chunks_mut::<N>();
    for dst in groups {
        *dst = store(f(index));
        index = index + <L::U as UintLane>::splat(N as u32);
    }
    if !rest.is_empty() {
        write_tail(rest, store(f(index)));
    }
    output.len()
}

/// `[0, 1, .., N - 1]`.
#[inline(always)]
pub(crate) fn lane_numbers<L: Vector<N>, const N: usize>() -> L::U {
    L::words(core::array::from_fn(|l| l as u32))
}

/// `N` array-of-structs elements into one SIMD vector per component.
///
/// The group is `N I` consecutive floats: read them as `I` whole vectors and deinterleave with
/// constant lane permutes. (Gathering element by element, `group[j][k]`, compiles to `N I`
/// scalar loads and inserts, which made the slice forms slower than a plain scalar loop.)
#[inline(always)]
pub(crate) fn load<L: Vector<N>, const N: usize, const I: usize>(group: &[[f32; I]; N]) -> [L; I] {
    deinterleave::<L, N, I>(bytemuck::cast_ref(group)).map(L::from_bits)
}

/// `N I` consecutive 32-bit words holding `N` `I`-component elements, as one vector per
/// component (the integer core of [`load`]; also the pmj02bn slice's table reads).
#[inline(always)]
pub(crate) fn deinterleave<L: Vector<N>, const N: usize, const I: usize>(
    rows: &[[u32; N]; I],
) -> [L::U; I] {
    // Plain loops rather than `core::array::from_fn`: with three components LLVM left the
    // `from_fn` closure out of line, and the round trip through the stack (narrow stores read
    // back as one wide load) made 3-component slices 6-10x slower than the `_x8` form.
    let mut src = [<L::U as UintLane>::splat(0); I];
    for (s, r) in src.iter_mut().zip(rows) {
        *s = L::words(*r);
    }
    let mut out = [<L::U as UintLane>::splat(0); I];
    for (k, o) in out.iter_mut().enumerate() {
        *o = permute::<L, N, I, I, TO_COMPONENTS>(&src, k);
    }
    out
}

/// One SIMD vector per component back into `N` array-of-structs elements.
#[inline(always)]
pub(crate) fn store<L: Vector<N>, const N: usize, const O: usize>(v: [L; O]) -> [[f32; O]; N] {
    let src: [L::U; O] = v.map(L::to_bits);
    // Plain loops rather than `core::array::from_fn`: see `deinterleave`.
    let mut rows = [[0u32; N]; O];
    for (m, row) in rows.iter_mut().enumerate() {
        *row = L::to_words(permute::<L, N, O, O, TO_ELEMENTS>(&src, m));
    }
    bytemuck::cast(rows)
}

/// Layout of [`deinterleave`]: `S` whole vectors of `N`-lane elements (element `j`,
/// component `k` at flat word `j S + k`) to `S` component vectors.
pub(crate) const TO_COMPONENTS: usize = 0;
/// Layout of [`store`]: `S` component vectors to `S` whole vectors of elements.
pub(crate) const TO_ELEMENTS: usize = 1;
/// Layout of the quadrant slices (`disk::four_turns`): from `[x, y]` of `N` points, eight
/// rows holding each point's four quarter turns `(x, y), (-y, x), (-x, -y), (y, -x)` (the
/// signs are applied separately). Word `f` is point `f / 8`, sample `(f % 8) / 2`, component
/// `f % 2`, and it is `y` exactly when sample + component is odd.
pub(crate) const FOUR_TURNS: usize = 2;

/// Where lane `l` of output row `r` comes from in `LAYOUT`: `(source vector, source lane)`.
#[inline(always)]
pub(crate) const fn pick<const N: usize, const S: usize, const LAYOUT: usize>(
    r: usize,
    l: usize,
) -> (usize, usize) {
    match LAYOUT {
        TO_COMPONENTS => ((l * S + r) / N, (l * S + r) % N),
        TO_ELEMENTS => ((N * r + l) % S, (N * r + l) / S),
        _ => {
            let f = N * r + l;
            (((f % 8) / 2 + f) % 2, f / 8)
        }
    }
}

/// Row `r` (of `ROWS`) of the lane permutation `LAYOUT` of `S` source vectors: lane `l` is
/// lane `pick(r, l).1` of `src[pick(r, l).0]`.
///
/// With AVX-512 a chain of two-source permutes (`vpermt2d`: `S - 1` instructions) whose index
/// vectors come from a table built at compile time, so they are constants at every width.
/// Elsewhere, where `wide` has a one-source permute instruction (AVX2, SSSE3, wasm `simd128`,
/// NEON), one shuffle per source and a select with indices computed in place (constant once
/// LLVM unrolls the 8-lane loops). Elsewhere again (baseline SSE2, thumbv7em, wasm without
/// `simd128`) that shuffle is a per-lane loop with bounds checks, 20x slower for 3-component
/// slices, so plain lane picks, which LLVM turns into `shufps`/`pshufd`. All give the same
/// bits.
#[inline(always)]
pub(crate) fn permute<
    L: Vector<N>,
    const N: usize,
    const S: usize,
    const ROWS: usize,
    const LAYOUT: usize,
>(
    src: &[L::U; S],
    r: usize,
) -> L::U {
    #[cfg(target_feature = "avx512f")]
    {
        let plan: &[[[u32; N]; S]; ROWS] = &const { chain_plan::<N, S, ROWS, LAYOUT>() };
        let steps = plan.get(r).copied().unwrap_or([[0; N]; S]);
        let mut acc = src[0];
        if S == 1 {
            acc = L::shuffle(acc, L::words(steps[0]));
        }
        for (v, index) in src.iter().zip(steps).skip(1) {
            acc = L::shuffle2(acc, *v, L::words(index));
        }
        acc
    }
    #[cfg(all(
        not(target_feature = "avx512f"),
        any(
            target_feature = "avx2",
            target_feature = "ssse3",
            target_feature = "simd128",
            all(target_arch = "aarch64", target_feature = "neon")
        )
    ))]
    {
        let mut acc = <L::U as UintLane>::splat(0);
        for (s, v) in src.iter().enumerate() {
            let index = L::words(core::array::from_fn(|l| {
                pick::<N, S, LAYOUT>(r, l).1 as u32
            }));
            let take = L::words(core::array::from_fn(|l| {
                if pick::<N, S, LAYOUT>(r, l).0 == s {
                    u32::MAX
                } else {
                    0
                }
            }));
            acc = L::select_words(take, L::shuffle(*v, index), acc);
        }
        acc
    }
    #[cfg(not(any(
        target_feature = "avx512f",
        target_feature = "avx2",
        target_feature = "ssse3",
        target_feature = "simd128",
        all(target_arch = "aarch64", target_feature = "neon")
    )))]
    {
        let lanes: [[u32; N]; S] = src.map(L::to_words);
        let mut out = [0u32; N];
        for (l, o) in out.iter_mut().enumerate() {
            let (s, i) = pick::<N, S, LAYOUT>(r, l);
            *o = lanes[s][i];
        }
        L::words(out)
    }
}

/// The index vectors of [`permute`]'s AVX-512 chain for every row: step `s >= 1` permutes
/// `[acc, src[s]]` (indices `0..N` keep a lane of `acc`, `N..2N` take one of `src[s]`), with
/// `acc = src[0]` before the first step; a single source is one plain permute by step 0.
#[cfg_attr(not(target_feature = "avx512f"), allow(dead_code))]
const fn chain_plan<const N: usize, const S: usize, const ROWS: usize, const LAYOUT: usize>()
-> [[[u32; N]; S]; ROWS] {
    let mut plan = [[[0; N]; S]; ROWS];
    let mut r = 0;
    while r < ROWS {
        let mut l = 0;
        while l < N {
            let (source, lane) = pick::<N, S, LAYOUT>(r, l);
            let mut s = 0;
            while s < S {
                plan[r][s][l] = if source == s && s > 0 {
                    (N + lane) as u32
                } else if s <= 1 && source == 0 {
                    // From src[0]: picked by the first step (or by the single permute).
                    lane as u32
                } else {
                    // Already in `acc` at lane l (source < s), or written by a later step.
                    l as u32
                };
                s += 1;
            }
            l += 1;
        }
        r += 1;
    }
    plan
}

/// The slices' vectors: [`Vector`] with the full-width interleaves of `wide`, from which the
/// array-of-structs stores of 2 and 4 components are built.
#[cfg(feature = "sampler")]
pub(crate) trait Rows<const LN: usize>: Vector<LN> {
    /// `[a0, b0, a1, b1, ..]`: the low halves of `a` and `b` interleaved, then the high halves.
    fn zip32(a: Self::U, b: Self::U) -> [Self::U; 2];
    /// The same with pairs of lanes as the elements.
    fn zip64(a: Self::U, b: Self::U) -> [Self::U; 2];
}

/// `LN` points of `N` components, one vector per component, stored as an array of points:
/// two interleaves per pair of components (4 components: the pairs `(x, y)`, `(z, w)`, then
/// their pairs of lanes), or [`store`]'s permutes for 3.
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn store_rows<L: Rows<LN>, const LN: usize, const N: usize>(
    v: [L; N],
    dst: &mut [[f32; N]; LN],
) {
    let w = |k: usize| v[k % N].to_bits();
    let rows: &mut [[f32; LN]] = dst.as_flattened_mut().as_chunks_mut::<LN>().0;
    let mut put = |r: usize, words: L::U| {
        if let Some(row) = rows.get_mut(r) {
            *row = bytemuck::cast(L::to_words(words));
        }
    };
    match N {
        1 => put(0, w(0)),
        2 => {
            let [r0, r1] = L::zip32(w(0), w(1));
            put(0, r0);
            put(1, r1);
        }
        4 => {
            let [xy0, xy1] = L::zip32(w(0), w(1));
            let [zw0, zw1] = L::zip32(w(2), w(3));
            let [r0, r1] = L::zip64(xy0, zw0);
            let [r2, r3] = L::zip64(xy1, zw1);
            put(0, r0);
            put(1, r1);
            put(2, r2);
            put(3, r3);
        }
        _ => *dst = store(v),
    }
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use core::num::Wrapping;
    use std::vec;

    /// A body that mixes components and would expose any lane or component mix-up.
    fn body<L: Lane>(u: [L; 3]) -> [L; 2] {
        [
            u[0] * L::splat(3.0) - u[2],
            u[1] / (u[0].abs() + L::splat(2.0)),
        ]
    }

    /// `map_lanes` at width `N` against the scalar body: every input length up to 70 (full
    /// groups and every padded tail), output shorter, equal and longer.
    fn map_agrees<L: Vector<N>, const N: usize>() {
        let input: [[f32; 3]; 70] = core::array::from_fn(|i| {
            let x = i as f32;
            [x, -0.5 * x, x * x + 0.25]
        });
        for n in 0..=input.len() {
            for m in [n, n + 3, n.saturating_sub(5)] {
                let mut out = vec![[9.0f32; 2]; m];
                assert_eq!(map_lanes(&input[..n], &mut out, body::<L>), n.min(m));
                for (j, o) in out.iter().enumerate() {
                    let want = if j < n.min(m) {
                        body(input[j])
                    } else {
                        [9.0; 2]
                    };
                    assert_eq!(o.map(f32::to_bits), want.map(f32::to_bits), "{n}/{m}: {j}");
                }
            }
        }
    }

    #[test]
    fn map_agrees_at_both_widths() {
        map_agrees::<f32x8, 8>();
        map_agrees::<f32x16, 16>();
    }

    /// `fill_indexed` at width `N`: index `start + i`, wrapping past `u32::MAX`, every length.
    fn fill_agrees<L: Vector<N>, const N: usize>() {
        let f = |i: L::U| -> [L; 3] {
            let lo = L::from_uint(i & L::U::splat(0xffff));
            let hi = L::from_uint(i.shr(16));
            [lo, hi, lo * hi]
        };
        for start in [0u32, 5, u32::MAX - 20] {
            for n in 0..=50 {
                let mut out = vec![[9.0f32; 3]; n];
                assert_eq!(fill_indexed::<L, N, 3>(start, &mut out, f), n);
                for (k, o) in out.iter().enumerate() {
                    let i = start.wrapping_add(k as u32);
                    let (lo, hi) = ((i & 0xffff) as f32, (i >> 16) as f32);
                    assert_eq!(*o, [lo, hi, lo * hi], "{start} {n} {k}");
                }
            }
        }
        // The scalar lane type's conversion agrees (so the expected values above are the
        // body's scalar results).
        assert_eq!(<f32 as Lane>::from_uint(Wrapping(0xffff)), 65535.0);
    }

    #[test]
    fn fill_agrees_at_both_widths() {
        fill_agrees::<f32x8, 8>();
        fill_agrees::<f32x16, 16>();
    }

    /// The transposes for 1 to 4 components at both widths, against element-by-element
    /// copies; this exercises every step of the AVX-512 permute chains (up to three
    /// `vpermt2d`) and the other targets' shuffles or lane picks.
    fn transposes<L: Vector<N>, const N: usize, const S: usize>() {
        let elements: [[f32; S]; N] =
            core::array::from_fn(|j| core::array::from_fn(|k| (100 * j + k) as f32));
        let components: [L; S] = load::<L, N, S>(&elements);
        for (k, c) in components.iter().enumerate() {
            let lanes = L::to_words(c.to_bits());
            for j in 0..N {
                assert_eq!(
                    f32::from_bits(lanes[j]),
                    elements[j][k],
                    "load {N}x{S}: {j} {k}"
                );
            }
        }
        assert_eq!(store::<L, N, S>(components), elements, "store {N}x{S}");
    }

    #[test]
    fn transposes_at_both_widths() {
        transposes::<f32x8, 8, 1>();
        transposes::<f32x8, 8, 2>();
        transposes::<f32x8, 8, 3>();
        transposes::<f32x8, 8, 4>();
        transposes::<f32x16, 16, 1>();
        transposes::<f32x16, 16, 2>();
        transposes::<f32x16, 16, 3>();
        transposes::<f32x16, 16, 4>();
    }
}
