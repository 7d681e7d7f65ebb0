//! Slice forms: run an 8-wide warp over an array-of-structs batch of any length.
//!
//! Full groups of 8 are transposed into SIMD lanes, warped and transposed back; the last
//! `len % 8` elements are padded with zeros (a valid input) and run through the same 8-wide
//! body, so every element of a slice gets exactly the bits the scalar form gives (the lanes of
//! one body never interact). There is no indexing that can panic: lengths are reconciled with
//! `get`, and groups come from `as_chunks`.

use wide::{f32x8, u32x8};

/// Applies `f` to `input[i]`, writing `output[i]`, for `i < min(input.len(), output.len())`;
/// returns that count. Extra elements of the longer slice are not read or written.
#[inline(always)]
pub(crate) fn map<const I: usize, const O: usize>(
    input: &[[f32; I]],
    output: &mut [[f32; O]],
    f: impl Fn([f32x8; I]) -> [f32x8; O],
) -> usize {
    let n = input.len().min(output.len());
    let input = input.get(..n).unwrap_or(&[]);
    let output = output.get_mut(..n).unwrap_or(&mut []);
    let (in_groups, in_rest) = input.as_chunks::<8>();
    let (out_groups, out_rest) = output.as_chunks_mut::<8>();
    for (src, dst) in in_groups.iter().zip(out_groups) {
        *dst = store(f(load(src)));
    }
    if !in_rest.is_empty() {
        let mut pad = [[0.0f32; I]; 8];
        for (p, s) in pad.iter_mut().zip(in_rest) {
            *p = *s;
        }
        let res = store(f(load(&pad)));
        for (d, r) in out_rest.iter_mut().zip(res.iter()) {
            *d = *r;
        }
    }
    n
}

/// Fills `output[i]` with `f` at the index `start + i` (wrapping), eight indices at a time;
/// for the index-driven sequences and constructions. Returns `output.len()`.
#[cfg_attr(
    not(any(feature = "triangle", feature = "pmj02bn", feature = "sequence")),
    allow(dead_code)
)]
#[inline(always)]
pub(crate) fn fill_indexed<const O: usize>(
    start: u32,
    output: &mut [[f32; O]],
    f: impl Fn(u32x8) -> [f32x8; O],
) -> usize {
    let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
    let mut index = u32x8::splat(start) + lane;
    let (groups, rest) = output.as_chunks_mut::<8>();
    for dst in groups {
        *dst = store(f(index));
        index += u32x8::splat(8);
    }
    if !rest.is_empty() {
        let res = store(f(index));
        for (d, r) in rest.iter_mut().zip(res.iter()) {
            *d = *r;
        }
    }
    output.len()
}

/// Eight array-of-structs elements into one SIMD vector per component.
///
/// The group is `8 I` consecutive floats: read them as `I` whole vectors and deinterleave with
/// constant lane permutes. (Gathering element by element, `group[j][k]`, compiles to `8 I`
/// scalar loads and inserts, which made the slice forms slower than a plain scalar loop.)
#[inline(always)]
pub(crate) fn load<const I: usize>(group: &[[f32; I]; 8]) -> [f32x8; I] {
    deinterleave(bytemuck::cast_ref(group)).map(bytemuck::cast)
}

/// `8 I` consecutive 32-bit words holding eight `I`-component elements, as one vector per
/// component (the integer core of [`load`]; also the pmj02bn slice's table reads).
#[inline(always)]
pub(crate) fn deinterleave<const I: usize>(rows: &[[u32; 8]; I]) -> [u32x8; I] {
    // Plain loops rather than `core::array::from_fn`: with three components LLVM left the
    // `from_fn` closure out of line, and the round trip through the stack (narrow stores read
    // back as one wide load) made 3-component slices 6-10x slower than the `_x8` form.
    let src: [u32x8; I] = rows.map(u32x8::new);
    // Component k of element j sits at flat position j I + k.
    let mut out = [u32x8::ZERO; I];
    for (k, o) in out.iter_mut().enumerate() {
        *o = permute(&src, |j| ((j * I + k) / 8, (j * I + k) % 8));
    }
    out
}

/// One SIMD vector per component back into eight array-of-structs elements.
#[inline(always)]
pub(crate) fn store<const O: usize>(v: [f32x8; O]) -> [[f32; O]; 8] {
    let src: [u32x8; O] = v.map(bytemuck::cast);
    // Flat position 8 m + l holds component (8 m + l) % O of element (8 m + l) / O.
    // Plain loops rather than `core::array::from_fn`: see `load`.
    let mut rows = [[0u32; 8]; O];
    for (m, row) in rows.iter_mut().enumerate() {
        *row = permute(&src, |l| ((8 * m + l) % O, (8 * m + l) / O)).to_array();
    }
    bytemuck::cast(rows)
}

/// A vector whose lane `l` is lane `pick(l).1` of `src[pick(l).0]`, for a `pick` that is
/// constant after inlining.
///
/// Where `wide` has a permute instruction for `u32x8::shuffle` (AVX2, SSSE3, wasm `simd128`,
/// NEON), one shuffle per source and a select; LLVM folds them (two `vpermt2d` with AVX-512).
/// Elsewhere (baseline SSE2, thumbv7em, wasm without `simd128`) that shuffle is a per-lane
/// loop with bounds checks, 20x slower for 3-component slices, so plain lane picks instead,
/// which LLVM turns into `shufps`/`pshufd` (on AVX-512 the same picks go through memory and
/// are 3-4x slower than the shuffles: hence the split). Both give the same bits.
#[inline(always)]
fn permute<const S: usize>(src: &[u32x8; S], pick: impl Fn(usize) -> (usize, usize)) -> u32x8 {
    #[cfg(any(
        target_feature = "avx2",
        target_feature = "ssse3",
        target_feature = "simd128",
        all(target_arch = "aarch64", target_feature = "neon")
    ))]
    {
        let mut acc = u32x8::ZERO;
        for (s, v) in src.iter().enumerate() {
            let index = u32x8::new(core::array::from_fn(|l| pick(l).1 as u32));
            let take = u32x8::new(core::array::from_fn(|l| {
                if pick(l).0 == s { u32::MAX } else { 0 }
            }));
            acc = take.select(v.shuffle(index), acc);
        }
        acc
    }
    #[cfg(not(any(
        target_feature = "avx2",
        target_feature = "ssse3",
        target_feature = "simd128",
        all(target_arch = "aarch64", target_feature = "neon")
    )))]
    {
        let lanes: [[u32; 8]; S] = src.map(|v| v.to_array());
        let mut out = [0u32; 8];
        for (l, o) in out.iter_mut().enumerate() {
            let (s, i) = pick(l);
            *o = lanes[s][i];
        }
        u32x8::new(out)
    }
}
