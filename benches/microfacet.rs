//! GGX microfacet sampling: warpcore's visible normals (spherical caps), reflection and bounded
//! reflection, in every form, against a textbook `f32` transcription of Heitz 2018's sampler
//! (the orthonormal frame around the stretched view direction, a polar disk sample warped onto
//! the projected hemisphere, `std` sin/cos/sqrt) in the same group. `wo` and `alpha` vary per
//! call (pre-generated arrays of varied inputs, walked behind `black_box`), as a renderer
//! calls it: nothing is hoisted.
//!
//! Run: `cargo bench --bench microfacet` and
//! `RUSTFLAGS="-C target-cpu=native" cargo bench --bench microfacet`.

mod common;

use common::{BATCH, bench_map, uniform_points, warp_group_on};
use std::f32::consts::TAU;
use std::hint::black_box;
use warpcore::microfacet as mf;

/// Heitz 2018, "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)), written from
/// the paper's description in plain `f32` with `std`'s `sqrt` (the hardware instruction, as
/// a renderer's code gets it; `libm::sqrtf` is an opaque inline-asm `sqrtss` on x86, which
/// would handicap the peer) and `sin_cos` (the platform's `sinf`/`cosf`); always inlined into
/// the loop, as a renderer's own code is.
#[inline(always)]
fn heitz2018(wo: [f32; 3], alpha: [f32; 2], u: [f32; 2]) -> [f32; 3] {
    let norm = |v: [f32; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    // The view direction in the hemisphere configuration.
    let vh = [alpha[0] * wo[0], alpha[1] * wo[1], wo[2]];
    let l = norm(vh);
    let vh = [vh[0] / l, vh[1] / l, vh[2] / l];
    // An orthonormal basis around it.
    let lensq = vh[0] * vh[0] + vh[1] * vh[1];
    let t1 = if lensq > 0.0 {
        let inv = 1.0 / lensq.sqrt();
        [-vh[1] * inv, vh[0] * inv, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t2 = [
        vh[1] * t1[2] - vh[2] * t1[1],
        vh[2] * t1[0] - vh[0] * t1[2],
        vh[0] * t1[1] - vh[1] * t1[0],
    ];
    // A point on the disk, warped onto the visible half.
    let r = u[0].sqrt();
    let (sin, cos) = (TAU * u[1]).sin_cos();
    let p1 = r * cos;
    let p2 = r * sin;
    let s = 0.5 * (1.0 + vh[2]);
    let p2 = (1.0 - s) * (1.0 - p1 * p1).sqrt() + s * p2;
    let pz = (1.0 - p1 * p1 - p2 * p2).max(0.0).sqrt();
    let nh = [
        p1 * t1[0] + p2 * t2[0] + pz * vh[0],
        p1 * t1[1] + p2 * t2[1] + pz * vh[1],
        p1 * t1[2] + p2 * t2[2] + pz * vh[2],
    ];
    // Back to the ellipsoid configuration.
    let ne = [alpha[0] * nh[0], alpha[1] * nh[1], nh[2].max(0.0)];
    let l = norm(ne);
    [ne[0] / l, ne[1] / l, ne[2] / l]
}

/// `BATCH` packed `[wo, alpha, u]`: `wo` spread over the upper hemisphere from normal to
/// grazing, `alpha` in `[0.01, 1]` (anisotropic), `u` uniform.
fn inputs() -> Vec<[f32; 7]> {
    uniform_points::<6>(BATCH, 3)
        .into_iter()
        .map(|r| {
            let z = r[0].max(1e-4);
            let s = (1.0 - z * z).sqrt();
            let phi = TAU * r[1];
            let (ax, ay) = (0.01 + 0.99 * r[2], 0.01 + 0.99 * r[3]);
            [s * phi.cos(), s * phi.sin(), z, ax, ay, r[4], r[5]]
        })
        .collect()
}

fn split(x: [f32; 7]) -> ([f32; 3], [f32; 2], [f32; 2]) {
    ([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]])
}

/// A lane form called on packed lanes.
macro_rules! lanes {
    ($f:path) => {
        |x: [_; 7]| $f([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]])
    };
}

/// A lane form of a reflection, its result packed as `[wi, density]`.
macro_rules! reflect_lanes {
    ($f:path) => {
        |x: [_; 7]| {
            let (w, p) = $f([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]]);
            [w[0], w[1], w[2], p]
        }
    };
}

fn packed((w, p): ([f32; 3], f32)) -> [f32; 4] {
    [w[0], w[1], w[2], p]
}

/// The group of a reflection sampler: its forms on the packed inputs (generic, so each is
/// inlined as in a user's loop).
fn reflect_group(
    c: &mut criterion::Criterion,
    name: &str,
    input: &[[f32; 7]],
    scalar: impl Fn([f32; 3], [f32; 2], [f32; 2]) -> ([f32; 3], f32),
    x8: impl Fn([warpcore::f32x8; 7]) -> [warpcore::f32x8; 4],
    x16: impl Fn([warpcore::f32x16; 7]) -> [warpcore::f32x16; 4],
    slice: impl Fn(&[[f32; 7]], &mut [[f32; 4]]) -> usize,
) {
    let scalar = |x| {
        let (wo, a, u) = split(x);
        packed(scalar(wo, a, u))
    };
    warp_group_on(c, name, input, scalar, x8, x16, slice).finish();
}

fn main() {
    let mut c = common::criterion();
    let input = inputs();

    let mut g = warp_group_on(
        &mut c,
        "microfacet/ggx_visible_normal",
        &input,
        |x| {
            let (wo, a, u) = split(x);
            mf::ggx_visible_normal(wo, a, u)
        },
        lanes!(mf::ggx_visible_normal_x8),
        lanes!(mf::ggx_visible_normal_x16),
        mf::ggx_visible_normal_slice,
    );
    let peer = |x: [f32; 7]| {
        let (wo, a, u) = split(x);
        heitz2018(wo, a, u)
    };
    let mut out = vec![[0.0f32; 3]; BATCH];
    bench_map(
        &mut g,
        "Heitz 2018 textbook (scalar loop)",
        &input,
        &mut out,
        peer,
    );
    bench_map(
        &mut g,
        "Heitz 2018 textbook (scalar, one call at a time)",
        &input,
        &mut out,
        |x| peer(black_box(x)),
    );
    g.finish();

    reflect_group(
        &mut c,
        "microfacet/ggx_reflect",
        &input,
        mf::ggx_reflect,
        reflect_lanes!(mf::ggx_reflect_x8),
        reflect_lanes!(mf::ggx_reflect_x16),
        mf::ggx_reflect_slice,
    );
    reflect_group(
        &mut c,
        "microfacet/ggx_reflect_bounded",
        &input,
        mf::ggx_reflect_bounded,
        reflect_lanes!(mf::ggx_reflect_bounded_x8),
        reflect_lanes!(mf::ggx_reflect_bounded_x16),
        mf::ggx_reflect_bounded_slice,
    );

    c.final_summary();
}
