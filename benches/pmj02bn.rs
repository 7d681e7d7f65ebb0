//! pmj02bn and the baseline samplers: 2D points per second for warpcore's scalar `sample`,
//! `sample_x8` and slice forms, the `random` and `stratified` baselines, and
//! `sobol_burley::sample` (Owen-scrambled Sobol, two dimensions per point) as the peer.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench pmj02bn`

mod common;

use common::{BATCH, bench_hoisted, bench_indexed, bench_out};
use std::hint::black_box;
use warpcore::{f32x8, f32x16, pmj02bn, sequence, u32x8, u32x16};

const SEED: u32 = 0x5eed;

fn main() {
    let mut c = common::criterion();
    let mut g = common::group(&mut c, "pmj02bn");
    let mut out = vec![[0.0f32; 2]; BATCH];
    let mut out8 = vec![[f32x8::ZERO; 2]; BATCH / 8];
    let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);

    bench_indexed(&mut g, "warpcore sample, scalar loop", &mut out, |i| {
        pmj02bn::sample(i as u32, black_box(SEED))
    });
    bench_indexed(
        &mut g,
        "warpcore sample, one call at a time",
        &mut out,
        |i| pmj02bn::sample(black_box(i as u32), black_box(SEED)),
    );
    // One seed for all lanes, then a seed per lane.
    for (label, per_lane) in [
        ("warpcore sample_x8", u32x8::ZERO),
        ("warpcore sample_x8, a seed per lane", lane),
    ] {
        let seed = || u32x8::splat(black_box(SEED)) + per_lane;
        bench_hoisted(&mut g, label, &mut out8, seed, |k, seed| {
            pmj02bn::sample_x8(u32x8::splat(8 * k as u32) + lane, seed)
        });
    }
    let lane16 = u32x16::new(std::array::from_fn(|j| j as u32));
    let mut out16 = vec![[f32x16::ZERO; 2]; BATCH / 16];
    let seed = || u32x16::splat(black_box(SEED));
    bench_hoisted(
        &mut g,
        "warpcore sample_x16",
        &mut out16,
        seed,
        |k, seed| pmj02bn::sample_x16(u32x16::splat(16 * k as u32) + lane16, seed),
    );
    bench_out(&mut g, "warpcore sample_slice", &mut out, |out| {
        pmj02bn::sample_slice(0, black_box(SEED), out);
    });
    bench_out(&mut g, "warpcore random_slice", &mut out, |out| {
        sequence::random_slice(0, black_box(SEED), out);
    });
    bench_out(&mut g, "warpcore stratified_slice", &mut out, |out| {
        sequence::stratified_slice(0, BATCH as u32, black_box(SEED), out);
    });
    // The same with every call's index and seed through `black_box` (nothing to hoist or
    // strength-reduce across calls), the peer likewise.
    bench_indexed(&mut g, "warpcore sample_x8, per call", &mut out8, |k| {
        let index = u32x8::splat(black_box(8 * k as u32)) + lane;
        pmj02bn::sample_x8(index, u32x8::splat(black_box(SEED)))
    });
    bench_indexed(
        &mut g,
        "sobol_burley::sample (2 dims), per call",
        &mut out,
        |i| {
            let (i, seed) = (black_box(i as u32), black_box(SEED));
            [0, 1].map(|d| sobol_burley::sample(i, d, seed))
        },
    );
    let seed = || black_box(SEED);
    bench_hoisted(
        &mut g,
        "sobol_burley::sample (2 dims)",
        &mut out,
        seed,
        |i, seed| [0, 1].map(|d| sobol_burley::sample(i as u32, d, seed)),
    );
    let label = "sobol_burley::sample_4d (2 of 4 dims)";
    bench_hoisted(&mut g, label, &mut out, seed, |i, seed| {
        let s = sobol_burley::sample_4d(i as u32, 0, seed);
        [s[0], s[1]]
    });
    g.finish();
    c.final_summary();
}
