//! Shared benchmark scaffolding: every warp group measures warpcore's scalar loop, `_x8` on
//! structure-of-arrays data and the slice form over the same batch, plus the peers in the
//! same group, all with `Throughput::Elements` so criterion reports samples per second.
#![allow(dead_code)]

use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion, Throughput};
use std::hint::black_box;
use std::time::Duration;
use warpcore::{f32x8, f32x16};

/// Points per iteration: 4096 (32 KiB of 2D input), resident in L1/L2 like a renderer's batch.
pub const BATCH: usize = 4096;

pub fn criterion() -> Criterion {
    Criterion::default()
        .sample_size(30)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .configure_from_args()
}

/// Uniform points in [0, 1)^N from a fixed seed (24 random bits per coordinate).
pub fn uniform_points<const N: usize>(n: usize, seed: u64) -> Vec<[f32; N]> {
    let mut s = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    (0..n)
        .map(|_| {
            std::array::from_fn(|_| {
                // splitmix64
                s = s.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut z = s;
                z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                ((z ^ (z >> 31)) >> 40) as f32 * (1.0 / 16_777_216.0)
            })
        })
        .collect()
}

/// Array-of-structs points as structure-of-arrays SIMD groups (length rounded down to 8).
pub fn to_soa<const N: usize>(points: &[[f32; N]]) -> Vec<[f32x8; N]> {
    points
        .chunks_exact(8)
        .map(|g| std::array::from_fn(|k| f32x8::new(std::array::from_fn(|j| g[j][k]))))
        .collect()
}

/// Array-of-structs points as 16-lane structure-of-arrays groups (length rounded down to 16).
pub fn to_soa16<const N: usize>(points: &[[f32; N]]) -> Vec<[f32x16; N]> {
    points
        .chunks_exact(16)
        .map(|g| std::array::from_fn(|k| f32x16::new(std::array::from_fn(|j| g[j][k]))))
        .collect()
}

/// Times `f` writing the whole of `out` (then `black_box`es `out`, so nothing is elided).
pub fn bench_out<O>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    out: &mut [O],
    mut f: impl FnMut(&mut [O]),
) {
    g.bench_function(label, |b| {
        b.iter(|| {
            f(out);
            black_box(&mut *out);
        })
    });
}

/// Times `out[i] = f(input[i])`, the input behind `black_box` (a plain loop: the compiler may
/// batch or vectorize the calls; wrap the element in `black_box` inside `f` to stop it).
pub fn bench_map<I: Copy, O>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    input: &[I],
    out: &mut [O],
    f: impl Fn(I) -> O,
) {
    bench_out(g, label, out, |out| {
        for (o, u) in out.iter_mut().zip(black_box(input)) {
            *o = f(*u);
        }
    });
}

/// Times `out[i] = f(i)` over the whole output.
pub fn bench_indexed<O>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    out: &mut [O],
    f: impl Fn(usize) -> O,
) {
    bench_out(g, label, out, |out| {
        for (i, o) in out.iter_mut().enumerate() {
            *o = f(i);
        }
    });
}

/// Times `out[k] = f(k, v)` over the whole output, with `v = once()` made once per iteration
/// (a seed or pixel behind `black_box`, whose per-value work the compiler may hoist out of the
/// loop, as in a renderer's loop over one pixel's samples).
pub fn bench_hoisted<V: Copy, O>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    out: &mut [O],
    once: impl Fn() -> V,
    f: impl Fn(usize, V) -> O,
) {
    bench_out(g, label, out, |out| {
        let v = once();
        for (k, o) in out.iter_mut().enumerate() {
            *o = f(k, v);
        }
    });
}

/// Output buffers for the forms of one map: `BATCH` scalar outputs, `BATCH / 8` and
/// `BATCH / 16` lane groups.
pub struct Outputs<O, O8, O16> {
    pub out: Vec<O>,
    pub out8: Vec<O8>,
    pub out16: Vec<O16>,
}

impl<O: Clone, O8: Clone, O16: Clone> Outputs<O, O8, O16> {
    pub fn new(zero: O, zero8: O8, zero16: O16) -> Self {
        Outputs {
            out: vec![zero; BATCH],
            out8: vec![zero8; BATCH / 8],
            out16: vec![zero16; BATCH / 16],
        }
    }
}

/// The five warpcore variants of one map over `input` (`BATCH` elements), each labelled
/// `label(variant)`: the scalar function in a loop and one call at a time, `_x8` and `_x16`
/// over structure-of-arrays groups, and the slice form. Everything is passed generically (not
/// as `fn` pointers) so each variant is inlined the way it would be in a user's loop.
#[allow(clippy::too_many_arguments)]
pub fn forms<const I: usize, O, O8, O16>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: impl Fn(&str) -> String,
    input: &[[f32; I]],
    outs: &mut Outputs<O, O8, O16>,
    scalar: impl Fn([f32; I]) -> O,
    x8: impl Fn([f32x8; I]) -> O8,
    x16: impl Fn([f32x16; I]) -> O16,
    slice: impl Fn(&[[f32; I]], &mut [O]) -> usize,
) {
    let (soa, soa16) = (to_soa(input), to_soa16(input));
    // A plain loop over the scalar function: the bodies are branch-free, so LLVM may
    // auto-vectorize this loop (it does for concentric with AVX-512).
    bench_map(g, &label("scalar loop"), input, &mut outs.out, &scalar);
    // One sample per call, as in a path tracer's per-sample code: `black_box` on each input
    // keeps the compiler from batching calls, so this is the scalar code itself.
    bench_map(
        g,
        &label("scalar, one call at a time"),
        input,
        &mut outs.out,
        |u| scalar(black_box(u)),
    );
    bench_map(g, &label("x8"), &soa, &mut outs.out8, x8);
    // Without AVX-512 `wide` runs the 16 lanes as two 8-lane halves.
    bench_map(g, &label("x16"), &soa16, &mut outs.out16, x16);
    bench_out(g, &label("slice"), &mut outs.out, |out| {
        slice(black_box(input), out);
    });
}

/// A group of `BATCH` elements per iteration named `name`.
pub fn group<'c>(c: &'c mut Criterion, name: &str) -> BenchmarkGroup<'c, WallTime> {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(BATCH as u64));
    g
}

/// Starts a warp's group with the warpcore [`forms`] over `input`, labelled "warpcore
/// scalar loop" and so on. Add peers with [`peer_scalar_on`] / [`peer_fill`], then `finish()`.
pub fn warp_group_on<'c, const I: usize, const O: usize>(
    c: &'c mut Criterion,
    name: &str,
    input: &[[f32; I]],
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    x16: impl Fn([f32x16; I]) -> [f32x16; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) -> BenchmarkGroup<'c, WallTime> {
    let mut g = group(c, name);
    let mut outs = Outputs::new([0.0f32; O], [f32x8::ZERO; O], [f32x16::ZERO; O]);
    let label = |variant: &str| format!("warpcore {variant}");
    forms(&mut g, label, input, &mut outs, scalar, x8, x16, slice);
    g
}

/// [`warp_group_on`] over `BATCH` uniform points (seed 1), the input of [`peer_scalar`].
pub fn warp_group<'c, const I: usize, const O: usize>(
    c: &'c mut Criterion,
    name: &str,
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    x16: impl Fn([f32x16; I]) -> [f32x16; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) -> BenchmarkGroup<'c, WallTime> {
    let input = uniform_points::<I>(BATCH, 1);
    warp_group_on(c, name, &input, scalar, x8, x16, slice)
}

/// A scalar peer applied in a loop over `input`.
pub fn peer_scalar_on<const I: usize, const O: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    input: &[[f32; I]],
    f: impl Fn([f32; I]) -> [f32; O],
) {
    bench_map(g, label, input, &mut vec![[0.0f32; O]; input.len()], f);
}

/// A scalar peer applied in a loop over the same input batch as [`warp_group`].
pub fn peer_scalar<const I: usize, const O: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    f: impl Fn([f32; I]) -> [f32; O],
) {
    peer_scalar_on(g, label, &uniform_points::<I>(BATCH, 1), f);
}

/// A peer that produces `BATCH` outputs on its own (e.g. a `rand_distr` distribution drawing
/// its own uniforms).
pub fn peer_fill<const O: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    f: impl FnMut(&mut [[f32; O]]),
) {
    // On the heap, as every other output buffer.
    #[allow(clippy::useless_vec)]
    bench_out(g, label, &mut vec![[0.0f32; O]; BATCH], f);
}
