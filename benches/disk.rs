//! Disk warps: throughput of warpcore's scalar loop, `_x8` and slice forms against the peers
//! a Rust user would reach for — `rand_distr::UnitDisc` (rejection sampling, with the fast
//! Xoshiro128++ generator) and the textbook formula in scalar code with `libm` sin/cos.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench disk`
//! (without the flag the x86-64 baseline is SSE2 and `f32x8` runs as two SSE halves).

mod common;

use common::{BATCH, bench_indexed, bench_out, peer_fill, peer_scalar, warp_group};
use rand::SeedableRng;
use rand_distr::{Distribution, UnitDisc};
use rand_xoshiro::Xoshiro128PlusPlus;
use std::f32::consts::{FRAC_PI_2, TAU};
use std::hint::black_box;
use warpcore::{disk, f32x8, f32x16, u32x8, u32x16};
use warpcore_testkit::textbook;

/// Shirley-Chiu as published, two branches, libm sin/cos.
fn concentric_libm(u: [f32; 2]) -> [f32; 2] {
    let (r, phi) = textbook::concentric_polar(2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
    [r * libm::cosf(phi), r * libm::sinf(phi)]
}

fn polar_libm(u: [f32; 2]) -> [f32; 2] {
    let (r, t) = (libm::sqrtf(u[0]), TAU * u[1]);
    [r * libm::cosf(t), r * libm::sinf(t)]
}

fn polar4_libm(u: [f32; 2], q: u32) -> [f32; 2] {
    let (r, t) = (libm::sqrtf(u[0]), FRAC_PI_2 * (u[1] + (q % 4) as f32));
    [r * libm::cosf(t), r * libm::sinf(t)]
}

/// Concentric4 as specified (Shirley-Chiu on the quarter disk, then the quarter turns), two
/// branches, libm sin/cos.
fn concentric4_libm(u: [f32; 2], q: u32) -> [f32; 2] {
    let (r, phi) = textbook::concentric_polar(u[0], u[1]);
    let (x, y) = (r * libm::cosf(phi), r * libm::sinf(phi));
    match q % 4 {
        0 => [x, y],
        1 => [-y, x],
        2 => [-x, -y],
        _ => [y, -x],
    }
}

/// `rand_distr::UnitDisc`: draws its own uniforms, so it includes generator time — which is
/// what a user of it pays per disk sample.
fn unit_disc(out: &mut [[f32; 2]]) {
    let mut rng = Xoshiro128PlusPlus::seed_from_u64(1);
    for o in out {
        *o = UnitDisc.sample(&mut rng);
    }
}

/// A quadrant warp's group: the natural batch is "N/4 points -> N disk samples" (the slice
/// form), measured in disk samples per second, against the textbook formula and `UnitDisc`.
fn quadrant_group(
    c: &mut criterion::Criterion,
    name: &str,
    scalar: impl Fn([f32; 2], u32) -> [f32; 2],
    x8: impl Fn([f32x8; 2], u32x8) -> [f32x8; 2],
    x16: impl Fn([f32x16; 2], u32x16) -> [f32x16; 2],
    slice: impl Fn(&[[f32; 2]], &mut [[f32; 2]]) -> usize,
    textbook: impl Fn([f32; 2], u32) -> [f32; 2],
) {
    let points = common::uniform_points(BATCH / 4, 3);
    let mut g = common::group(c, name);
    let mut out = vec![[0.0f32; 2]; BATCH];
    bench_indexed(&mut g, "warpcore scalar loop", &mut out, |i| {
        scalar(points[i / 4], i as u32 % 4)
    });
    // Each group of lanes takes its points once and the four quadrants in turn.
    let (soa, soa16) = (common::to_soa(&points), common::to_soa16(&points));
    let q8: [u32x8; 4] = std::array::from_fn(|j| u32x8::splat(j as u32));
    let q16: [u32x16; 4] = std::array::from_fn(|j| u32x16::splat(j as u32));
    let (mut out8, mut out16) = (
        vec![[f32x8::ZERO; 2]; BATCH / 8],
        vec![[f32x16::ZERO; 2]; BATCH / 16],
    );
    bench_indexed(&mut g, "warpcore x8", &mut out8, |k| {
        x8(soa[k / 4], q8[k % 4])
    });
    bench_indexed(&mut g, "warpcore x16", &mut out16, |k| {
        x16(soa16[k / 4], q16[k % 4])
    });
    bench_out(&mut g, "warpcore slice", &mut out, |out| {
        slice(black_box(&points), out);
    });
    bench_indexed(&mut g, "libm textbook (scalar)", &mut out, |i| {
        textbook(points[i / 4], i as u32 % 4)
    });
    bench_out(
        &mut g,
        "rand_distr::UnitDisc (Xoshiro128++)",
        &mut out,
        unit_disc,
    );
    g.finish();
}

fn main() {
    let mut c = common::criterion();
    let mut g = warp_group(
        &mut c,
        "disk/concentric",
        disk::concentric,
        disk::concentric_x8,
        disk::concentric_x16,
        disk::concentric_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", concentric_libm);
    peer_fill(&mut g, "rand_distr::UnitDisc (Xoshiro128++)", unit_disc);
    g.finish();

    let mut g = warp_group(
        &mut c,
        "disk/polar",
        disk::polar,
        disk::polar_x8,
        disk::polar_x16,
        disk::polar_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", polar_libm);
    peer_fill(&mut g, "rand_distr::UnitDisc (Xoshiro128++)", unit_disc);
    g.finish();

    quadrant_group(
        &mut c,
        "disk/polar4",
        disk::polar4,
        disk::polar4_x8,
        disk::polar4_x16,
        disk::polar4_slice,
        polar4_libm,
    );
    quadrant_group(
        &mut c,
        "disk/concentric4",
        disk::concentric4,
        disk::concentric4_x8,
        disk::concentric4_x16,
        disk::concentric4_slice,
        concentric4_libm,
    );
    c.final_summary();
}
