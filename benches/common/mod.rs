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

/// Starts a warp's group with the warpcore forms over the same `BATCH` inputs: the scalar
/// function in a loop, `_x8` and `_x16` over structure-of-arrays groups, and the slice form.
/// Everything is passed generically (not as `fn` pointers) so each variant is inlined the way
/// it would be in a user's loop. Add peers with [`peer_scalar`] / [`peer_fill`], then `finish()`.
pub fn warp_group<'c, const I: usize, const O: usize>(
    c: &'c mut Criterion,
    name: &str,
    scalar: impl Fn([f32; I]) -> [f32; O],
    x8: impl Fn([f32x8; I]) -> [f32x8; O],
    x16: impl Fn([f32x16; I]) -> [f32x16; O],
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) -> BenchmarkGroup<'c, WallTime> {
    let input = uniform_points::<I>(BATCH, 1);
    let soa = to_soa(&input);
    let soa16 = to_soa16(&input);
    let mut out = vec![[0.0f32; O]; BATCH];
    let mut out8 = vec![[f32x8::ZERO; O]; BATCH / 8];
    let mut out16 = vec![[f32x16::ZERO; O]; BATCH / 16];
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(BATCH as u64));
    // A plain loop over the scalar function: the bodies are branch-free, so LLVM may
    // auto-vectorize this loop (it does for concentric with AVX-512).
    g.bench_function("warpcore scalar loop", |b| {
        b.iter(|| {
            for (o, u) in out.iter_mut().zip(black_box(&input)) {
                *o = scalar(*u);
            }
            black_box(&mut out);
        })
    });
    // One sample per call, as in a path tracer's per-sample code: `black_box` on each input
    // keeps the compiler from batching calls, so this is the scalar code itself.
    g.bench_function("warpcore scalar, one call at a time", |b| {
        b.iter(|| {
            for (o, u) in out.iter_mut().zip(&input) {
                *o = scalar(black_box(*u));
            }
            black_box(&mut out);
        })
    });
    g.bench_function("warpcore x8", |b| {
        b.iter(|| {
            for (o, u) in out8.iter_mut().zip(black_box(&soa)) {
                *o = x8(*u);
            }
            black_box(&mut out8);
        })
    });
    // Without AVX-512 `wide` runs the 16 lanes as two 8-lane halves.
    g.bench_function("warpcore x16", |b| {
        b.iter(|| {
            for (o, u) in out16.iter_mut().zip(black_box(&soa16)) {
                *o = x16(*u);
            }
            black_box(&mut out16);
        })
    });
    g.bench_function("warpcore slice", |b| {
        b.iter(|| {
            slice(black_box(&input), &mut out);
            black_box(&mut out);
        })
    });
    g
}

/// A scalar peer applied in a loop over the same input batch as [`warp_group`].
pub fn peer_scalar<const I: usize, const O: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    f: impl Fn([f32; I]) -> [f32; O],
) {
    let input = uniform_points::<I>(BATCH, 1);
    let mut out = vec![[0.0f32; O]; BATCH];
    g.bench_function(label, |b| {
        b.iter(|| {
            for (o, u) in out.iter_mut().zip(black_box(&input)) {
                *o = f(*u);
            }
            black_box(&mut out);
        })
    });
}

/// A peer that produces `BATCH` outputs on its own (e.g. a `rand_distr` distribution drawing
/// its own uniforms).
pub fn peer_fill<const O: usize>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    label: &str,
    mut f: impl FnMut(&mut [[f32; O]]),
) {
    let mut out = vec![[0.0f32; O]; BATCH];
    g.bench_function(label, |b| {
        b.iter(|| {
            f(&mut out);
            black_box(&mut out);
        })
    });
}
