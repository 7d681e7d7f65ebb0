//! pmj02bn and the baseline samplers: 2D points per second for warpcore's scalar `sample`,
//! `sample_x8` and slice forms, the `random` and `stratified` baselines, and
//! `sobol_burley::sample` (Owen-scrambled Sobol, two dimensions per point) as the peer.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench pmj02bn`

mod common;

use common::BATCH;
use criterion::Throughput;
use std::hint::black_box;
use warpcore::{f32x8, f32x16, pmj02bn, sequence, u32x8, u32x16};

const SEED: u32 = 0x5eed;

fn main() {
    let mut c = common::criterion();
    let mut g = c.benchmark_group("pmj02bn");
    g.throughput(Throughput::Elements(BATCH as u64));
    let mut out = vec![[0.0f32; 2]; BATCH];
    let mut out8 = vec![[f32x8::ZERO; 2]; BATCH / 8];

    g.bench_function("warpcore sample, scalar loop", |b| {
        b.iter(|| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = pmj02bn::sample(i as u32, black_box(SEED));
            }
            black_box(&mut out);
        })
    });
    g.bench_function("warpcore sample, one call at a time", |b| {
        b.iter(|| {
            for (i, o) in out.iter_mut().enumerate() {
                *o = pmj02bn::sample(black_box(i as u32), black_box(SEED));
            }
            black_box(&mut out);
        })
    });
    g.bench_function("warpcore sample_x8", |b| {
        let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
        b.iter(|| {
            let seed = u32x8::splat(black_box(SEED));
            for (k, o) in out8.iter_mut().enumerate() {
                *o = pmj02bn::sample_x8(u32x8::splat(8 * k as u32) + lane, seed);
            }
            black_box(&mut out8);
        })
    });
    g.bench_function("warpcore sample_x8, a seed per lane", |b| {
        let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
        b.iter(|| {
            let seed = u32x8::splat(black_box(SEED)) + lane;
            for (k, o) in out8.iter_mut().enumerate() {
                *o = pmj02bn::sample_x8(u32x8::splat(8 * k as u32) + lane, seed);
            }
            black_box(&mut out8);
        })
    });
    let mut out16 = vec![[f32x16::ZERO; 2]; BATCH / 16];
    g.bench_function("warpcore sample_x16", |b| {
        let lane = u32x16::new(std::array::from_fn(|j| j as u32));
        b.iter(|| {
            let seed = u32x16::splat(black_box(SEED));
            for (k, o) in out16.iter_mut().enumerate() {
                *o = pmj02bn::sample_x16(u32x16::splat(16 * k as u32) + lane, seed);
            }
            black_box(&mut out16);
        })
    });
    g.bench_function("warpcore sample_slice", |b| {
        b.iter(|| {
            pmj02bn::sample_slice(0, black_box(SEED), &mut out);
            black_box(&mut out);
        })
    });
    g.bench_function("warpcore random_slice", |b| {
        b.iter(|| {
            sequence::random_slice(0, black_box(SEED), &mut out);
            black_box(&mut out);
        })
    });
    g.bench_function("warpcore stratified_slice", |b| {
        b.iter(|| {
            sequence::stratified_slice(0, BATCH as u32, black_box(SEED), &mut out);
            black_box(&mut out);
        })
    });
    // The same with every call's index and seed through `black_box` (nothing to hoist or
    // strength-reduce across calls), the peer likewise.
    g.bench_function("warpcore sample_x8, per call", |b| {
        let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
        b.iter(|| {
            for (k, o) in out8.iter_mut().enumerate() {
                let index = u32x8::splat(black_box(8 * k as u32)) + lane;
                *o = pmj02bn::sample_x8(index, u32x8::splat(black_box(SEED)));
            }
            black_box(&mut out8);
        })
    });
    g.bench_function("sobol_burley::sample (2 dims), per call", |b| {
        b.iter(|| {
            for (i, o) in out.iter_mut().enumerate() {
                let (i, seed) = (black_box(i as u32), black_box(SEED));
                *o = [
                    sobol_burley::sample(i, 0, seed),
                    sobol_burley::sample(i, 1, seed),
                ];
            }
            black_box(&mut out);
        })
    });
    g.bench_function("sobol_burley::sample (2 dims)", |b| {
        b.iter(|| {
            let seed = black_box(SEED);
            for (i, o) in out.iter_mut().enumerate() {
                *o = [
                    sobol_burley::sample(i as u32, 0, seed),
                    sobol_burley::sample(i as u32, 1, seed),
                ];
            }
            black_box(&mut out);
        })
    });
    g.bench_function("sobol_burley::sample_4d (2 of 4 dims)", |b| {
        b.iter(|| {
            let seed = black_box(SEED);
            for (i, o) in out.iter_mut().enumerate() {
                let s = sobol_burley::sample_4d(i as u32, 0, seed);
                *o = [s[0], s[1]];
            }
            black_box(&mut out);
        })
    });
    g.finish();
    c.final_summary();
}
