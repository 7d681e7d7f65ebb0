//! Triangle warps: throughput of warpcore's scalar loop, `_x8` and slice forms against the
//! textbook formulas in plain scalar code (branches, `libm::sqrtf`), as a user would write them.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench triangle`
//! (without the flag the x86-64 baseline is SSE2 and `f32x8` runs as two SSE halves).

mod common;

use common::{BATCH, bench_hoisted, bench_indexed, bench_out, peer_scalar, warp_group};
use std::hint::black_box;
use warpcore::triangle;
use warpcore::{f32x8, f32x16, u32x8, u32x16};
use warpcore_testkit::textbook;

/// Heitz 2019 as published (one branch), `b2 = 1 - b0 - b1`.
fn uniform_textbook(u: [f32; 2]) -> [f32; 3] {
    let (b0, b1) = if u[0] < u[1] {
        (u[0] / 2.0, u[1] - u[0] / 2.0)
    } else {
        (u[0] - u[1] / 2.0, u[1] / 2.0)
    };
    [b0, b1, 1.0 - b0 - b1]
}

/// The inverse of Heitz's map as published.
fn uniform_inverse_textbook(b: [f32; 3]) -> [f32; 2] {
    if b[0] < b[1] {
        [2.0 * b[0], b[0] + b[1]]
    } else {
        [b[0] + b[1], 2.0 * b[1]]
    }
}

/// The classic square-root warp with `libm::sqrtf`.
fn sqrt_map_libm(u: [f32; 2]) -> [f32; 3] {
    let s = libm::sqrtf(u[0]);
    let (b0, b1) = (1.0 - s, u[1] * s);
    [b0, b1, 1.0 - b0 - b1]
}

/// An index-driven Basu-Owen randomization: BATCH consecutive indices from a fixed start, one
/// seed (the slice's use: one pixel's stream), and for `x8` also eight different seeds (eight
/// pixels at the same sample index), against the textbook digit loop (unscrambled).
fn basu_owen_group(
    c: &mut criterion::Criterion,
    name: &str,
    scalar: impl Fn(u32, u32) -> [f32; 3],
    x8: impl Fn(u32x8, u32x8) -> [f32x8; 3],
    x16: impl Fn(u32x16, u32x16) -> [f32x16; 3],
    slice: impl Fn(u32, u32, &mut [[f32; 3]]) -> usize,
) {
    const SEED: u32 = 0x2545_f491;
    const START: u32 = 1000;
    let mut g = common::group(c, name);
    let mut out = vec![[0.0f32; 3]; BATCH];
    let mut out8 = vec![[f32x8::ZERO; 3]; BATCH / 8];
    let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
    bench_indexed(&mut g, "warpcore scalar loop", &mut out, |k| {
        scalar(START + k as u32, black_box(SEED))
    });
    bench_indexed(
        &mut g,
        "warpcore scalar, one call at a time",
        &mut out,
        |k| scalar(black_box(START + k as u32), black_box(SEED)),
    );
    let seed = || u32x8::splat(black_box(SEED));
    bench_hoisted(&mut g, "warpcore x8", &mut out8, seed, |k, seed| {
        x8(u32x8::splat(START + 8 * k as u32) + lane, seed)
    });
    // Eight pixels per call at one sample index, new pixels every call: the seeds change
    // with every call, so the per-seed work cannot be hoisted out of the loop.
    let label = "warpcore x8, new seeds every call";
    let base = || u32x8::splat(black_box(SEED)) + lane;
    bench_hoisted(&mut g, label, &mut out8, base, |k, base| {
        x8(u32x8::splat(START), base + u32x8::splat(8 * k as u32))
    });
    let lane16 = u32x16::new(std::array::from_fn(|j| j as u32));
    let mut out16 = vec![[f32x16::ZERO; 3]; BATCH / 16];
    let seed = || u32x16::splat(black_box(SEED));
    bench_hoisted(&mut g, "warpcore x16", &mut out16, seed, |k, seed| {
        x16(u32x16::splat(START + 16 * k as u32) + lane16, seed)
    });
    for (label, seed) in [
        ("warpcore slice", SEED),
        ("warpcore slice, seed 0 (unscrambled)", 0),
    ] {
        bench_out(&mut g, label, &mut out, |out| {
            slice(black_box(START), black_box(seed), out);
        });
    }
    let label = "textbook digit loop (scalar, f32, unscrambled)";
    bench_indexed(&mut g, label, &mut out, |k| {
        textbook::basu_owen::<f32>(black_box(START + k as u32))
    });
    g.finish();
}

fn main() {
    let mut c = common::criterion();

    let mut g = warp_group(
        &mut c,
        "triangle/uniform",
        triangle::uniform,
        triangle::uniform_x8,
        triangle::uniform_x16,
        triangle::uniform_slice,
    );
    peer_scalar(&mut g, "textbook (scalar, branch)", uniform_textbook);
    peer_scalar(&mut g, "sqrt map, libm textbook (scalar)", sqrt_map_libm);
    g.finish();

    let mut g = warp_group(
        &mut c,
        "triangle/sqrt_map",
        triangle::sqrt_map,
        triangle::sqrt_map_x8,
        triangle::sqrt_map_x16,
        triangle::sqrt_map_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", sqrt_map_libm);
    g.finish();

    let mut g = warp_group(
        &mut c,
        "triangle/uniform_inverse",
        triangle::uniform_inverse,
        triangle::uniform_inverse_x8,
        triangle::uniform_inverse_x16,
        triangle::uniform_inverse_slice,
    );
    peer_scalar(
        &mut g,
        "textbook (scalar, branch)",
        uniform_inverse_textbook,
    );
    g.finish();

    basu_owen_group(
        &mut c,
        "triangle/basu_owen",
        triangle::basu_owen,
        triangle::basu_owen_x8,
        triangle::basu_owen_x16,
        triangle::basu_owen_slice,
    );
    basu_owen_group(
        &mut c,
        "triangle/basu_owen_permuted",
        triangle::basu_owen_permuted,
        triangle::basu_owen_permuted_x8,
        triangle::basu_owen_permuted_x16,
        triangle::basu_owen_permuted_slice,
    );
    c.final_summary();
}
