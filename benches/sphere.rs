//! Sphere warps: throughput of warpcore's scalar loop, `_x8` and slice forms against the
//! textbook formulas in plain scalar code with `libm` sin/cos/atan/acos (what a port of pbrt's
//! or Mitsuba's scalar code does), and `rand_distr::UnitSphere` for the uniform sphere.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench sphere`
//! (without the flag the x86-64 baseline is SSE2 and `f32x8` runs as two SSE halves).

mod common;

use common::{
    BATCH, peer_fill, peer_scalar, peer_scalar_on, uniform_points, warp_group, warp_group_on,
};
use criterion::measurement::WallTime;
use criterion::{BenchmarkGroup, Criterion};
use rand::SeedableRng;
use rand_distr::{Distribution, UnitSphere};
use rand_xoshiro::Xoshiro128PlusPlus;
use std::f32::consts::{FRAC_PI_2, PI, TAU};
use warpcore::{f32x8, f32x16, sphere};
use warpcore_testkit::textbook;

// ----------------------------------------------------------------------------------------
// Textbook peers: the published formulas, branches and libm calls, in f32.

/// Clarberg's equal-area map as written in the paper.
fn equal_area_libm(u: [f32; 2]) -> [f32; 3] {
    let (a, b) = (2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
    let (r, phi, sd) = textbook::equal_area_fold(a, b);
    let z = libm::copysignf(1.0 - r * r, sd);
    let s = r * libm::sqrtf(2.0 - r * r);
    [
        libm::copysignf(s * libm::cosf(phi), a),
        libm::copysignf(s * libm::sinf(phi), b),
        z,
    ]
}

/// Its inverse as published: r = sqrt(1 - |z|), phi from atan.
fn equal_area_inverse_libm(d: [f32; 3]) -> [f32; 2] {
    let (x, y, z) = (d[0].abs(), d[1].abs(), d[2].abs());
    let r = libm::sqrtf(1.0 - z);
    let phi = libm::atan2f(y, x) / FRAC_PI_2;
    textbook::equal_area_unfold(r, r * phi, d)
}

fn equirect_libm(u: [f32; 2]) -> [f32; 3] {
    let (phi, theta) = (TAU * u[0], PI * u[1]);
    let s = libm::sinf(theta);
    [s * libm::cosf(phi), s * libm::sinf(phi), libm::cosf(theta)]
}

fn equirect_inverse_libm(d: [f32; 3]) -> [f32; 2] {
    let phi = libm::atan2f(d[1], d[0]);
    let phi = if phi < 0.0 { phi + TAU } else { phi };
    [phi / TAU, libm::acosf(d[2].clamp(-1.0, 1.0)) / PI]
}

fn uniform_libm(u: [f32; 2]) -> [f32; 3] {
    let z = 1.0 - 2.0 * u[0];
    let r = libm::sqrtf((1.0 - z * z).max(0.0));
    let phi = TAU * u[1];
    [r * libm::cosf(phi), r * libm::sinf(phi), z]
}

/// Shirley-Chiu concentric disk (two branches) lifted by Malley's method.
fn cosine_hemisphere_libm(u: [f32; 2]) -> [f32; 3] {
    let (r, phi) = textbook::concentric_polar(2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
    let (x, y) = (r * libm::cosf(phi), r * libm::sinf(phi));
    [x, y, libm::sqrtf((1.0 - x * x - y * y).max(0.0))]
}

/// `rand_distr::UnitSphere` (Marsaglia's rejection method): draws its own uniforms, so it
/// includes generator time, which is what a user of it pays per direction.
fn unit_sphere(out: &mut [[f32; 3]]) {
    let mut rng = Xoshiro128PlusPlus::seed_from_u64(1);
    for o in out {
        *o = UnitSphere.sample(&mut rng);
    }
}

// ----------------------------------------------------------------------------------------
// Inverse groups: the same four warpcore variants as `warp_group`, on unit directions.

/// Unit directions, uniform on the sphere (the equal-area map of uniform points, in f64).
fn unit_directions(n: usize) -> Vec<[f32; 3]> {
    uniform_points::<2>(n, 2)
        .into_iter()
        .map(|u| {
            let z = 1.0 - 2.0 * u[0] as f64;
            let s = (1.0 - z * z).max(0.0).sqrt();
            let phi = std::f64::consts::TAU * u[1] as f64;
            [(s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32]
        })
        .collect()
}

fn inverse_group<'c>(
    c: &'c mut Criterion,
    name: &str,
    scalar: impl Fn([f32; 3]) -> [f32; 2],
    x8: impl Fn([f32x8; 3]) -> [f32x8; 2],
    x16: impl Fn([f32x16; 3]) -> [f32x16; 2],
    slice: impl Fn(&[[f32; 3]], &mut [[f32; 2]]) -> usize,
    peer: impl Fn([f32; 3]) -> [f32; 2],
) -> BenchmarkGroup<'c, WallTime> {
    let input = unit_directions(BATCH);
    let mut g = warp_group_on(c, name, &input, scalar, x8, x16, slice);
    peer_scalar_on(&mut g, "libm textbook (scalar)", &input, peer);
    g
}

fn main() {
    let mut c = common::criterion();

    let mut g = warp_group(
        &mut c,
        "sphere/equal_area",
        sphere::equal_area,
        sphere::equal_area_x8,
        sphere::equal_area_x16,
        sphere::equal_area_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", equal_area_libm);
    g.finish();

    inverse_group(
        &mut c,
        "sphere/equal_area_inverse",
        sphere::equal_area_inverse,
        sphere::equal_area_inverse_x8,
        sphere::equal_area_inverse_x16,
        sphere::equal_area_inverse_slice,
        equal_area_inverse_libm,
    )
    .finish();

    let mut g = warp_group(
        &mut c,
        "sphere/equirect",
        sphere::equirect,
        sphere::equirect_x8,
        sphere::equirect_x16,
        sphere::equirect_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", equirect_libm);
    g.finish();

    inverse_group(
        &mut c,
        "sphere/equirect_inverse",
        sphere::equirect_inverse,
        sphere::equirect_inverse_x8,
        sphere::equirect_inverse_x16,
        sphere::equirect_inverse_slice,
        equirect_inverse_libm,
    )
    .finish();

    let mut g = warp_group(
        &mut c,
        "sphere/cosine_hemisphere",
        sphere::cosine_hemisphere,
        sphere::cosine_hemisphere_x8,
        sphere::cosine_hemisphere_x16,
        sphere::cosine_hemisphere_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", cosine_hemisphere_libm);
    g.finish();

    let mut g = warp_group(
        &mut c,
        "sphere/uniform",
        sphere::uniform,
        sphere::uniform_x8,
        sphere::uniform_x16,
        sphere::uniform_slice,
    );
    peer_scalar(&mut g, "libm textbook (scalar)", uniform_libm);
    peer_fill(&mut g, "rand_distr::UnitSphere (Xoshiro128++)", unit_sphere);
    g.finish();

    c.final_summary();
}
