//! Lights by solid angle: throughput of warpcore's scalar loop and slice form (one light, one
//! shading point, `BATCH` samples) against straightforward scalar `f32` transcriptions of
//! Arvo 1995 and Urena et al. 2013 (libm `acosf`, `sinf`, `cosf`, as a user would write them
//! from the papers; they lose the density below about 1e-3 sr, see `src/spherical`).
//!
//! The cosine-aware slices (`triangle_cosine_slice`, `rectangle_cosine_slice`: the bilinear
//! warp plus the same map) sit beside the plain ones.
//!
//! The "a light per call" groups are what a renderer pays when the light or the shading
//! point changes from one sample to the next: every call takes the next of 4096 pre-generated
//! random lights, shading points and `u` (index through `black_box`, so no set-up can be
//! hoisted out of the loop), with the textbook transcriptions in the same group. In the
//! one-light groups the scalar rows pass the light and the point through `black_box` per
//! call too (a fixed light would let the compiler hoist the whole set-up out of the loop).
//!
//! The transcriptions are `#[inline(always)]`, as a renderer's own code is inlined into its
//! loop (the library's maps are `#[inline]`): left to LLVM they stayed calls, with spills
//! around the `libm` calls, and ran 22-29% slower than in a renderer, which flattered the
//! per-call ratios (docs/warps.md).
//!
//! Sphere lights (`spherical::cone`) against a textbook transcription of pbrt-v4's cone
//! sampling, per call and over a slice.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench spherical`

mod common;

use common::{BATCH, bench_indexed, bench_map, bench_out, group, uniform_points};
use std::hint::black_box;
use warpcore::spherical;
use warpcore_testkit::textbook::{add, cross, dot, scale, sub};

type V = [f32; 3];
fn normalize(a: V) -> V {
    scale(a, 1.0 / libm::sqrtf(dot(a, a)))
}
/// `a` without its component along unit `b`, normalised.
fn ortho(a: V, b: V) -> V {
    normalize(sub(a, scale(b, dot(a, b))))
}

/// Arvo 1995 as printed: angles by `acos` of normalised plane normals, the sub-triangle's
/// new vertex by the cosine `q`, the final point by `z = 1 - u1 (1 - cos)`; barycentrics by
/// intersecting the ray with the plane (Cramer's rule).
#[inline(always)]
fn arvo_textbook(v: [V; 3], p: V, u: [f32; 2]) -> ([f32; 3], f32) {
    let (va, vb, vc) = (sub(v[0], p), sub(v[1], p), sub(v[2], p));
    let (a, b, c) = (normalize(va), normalize(vb), normalize(vc));
    let (nab, nbc, nca) = (
        normalize(cross(a, b)),
        normalize(cross(b, c)),
        normalize(cross(c, a)),
    );
    let alpha = libm::acosf(-dot(nab, nca));
    let beta = libm::acosf(-dot(nab, nbc));
    let gamma = libm::acosf(-dot(nbc, nca));
    let area = alpha + beta + gamma - core::f32::consts::PI;
    let ah = u[0] * area;
    let (s, t) = (libm::sinf(ah - alpha), libm::cosf(ah - alpha));
    let (ca, sa) = (libm::cosf(alpha), libm::sinf(alpha));
    let uu = t - ca;
    let vv = s + sa * dot(a, b);
    let q = ((vv * t - uu * s) * ca - vv) / ((vv * s + uu * t) * sa);
    let q = q.clamp(-1.0, 1.0);
    let ch = add(scale(a, q), scale(ortho(c, a), libm::sqrtf(1.0 - q * q)));
    let z = 1.0 - u[1] * (1.0 - dot(ch, b));
    let z = z.clamp(-1.0, 1.0);
    let d = add(scale(b, z), scale(ortho(ch, b), libm::sqrtf(1.0 - z * z)));
    let l0 = dot(d, cross(vb, vc));
    let l1 = dot(d, cross(vc, va));
    let l2 = dot(d, cross(va, vb));
    let sum = l0 + l1 + l2;
    ([l0 / sum, l1 / sum, l2 / sum], 1.0 / area)
}

/// Urena, Fajardo and King 2013 as printed (their Algorithm 1), for an axis frame given by
/// `ex`, `ey`.
#[inline(always)]
fn urena_textbook(corner: V, ex: V, ey: V, p: V, u: [f32; 2]) -> ([f32; 2], f32) {
    let (w, h) = (libm::sqrtf(dot(ex, ex)), libm::sqrtf(dot(ey, ey)));
    let (x, y) = (scale(ex, 1.0 / w), scale(ey, 1.0 / h));
    let mut z = cross(x, y);
    let d = sub(corner, p);
    let mut z0 = dot(d, z);
    if z0 > 0.0 {
        z = scale(z, -1.0);
        z0 = -z0;
    }
    let _ = z;
    let (x0, y0) = (dot(d, x), dot(d, y));
    let (x1, y1) = (x0 + w, y0 + h);
    let n0 = normalize([0.0, z0, -y0]);
    let n1 = normalize([-z0, 0.0, x1]);
    let n2 = normalize([0.0, -z0, y1]);
    let n3 = normalize([z0, 0.0, -x0]);
    let g0 = libm::acosf(-n0[0] * n1[0] - n0[1] * n1[1] - n0[2] * n1[2]);
    let g1 = libm::acosf(-n1[0] * n2[0] - n1[1] * n2[1] - n1[2] * n2[2]);
    let g2 = libm::acosf(-n2[0] * n3[0] - n2[1] * n3[1] - n2[2] * n3[2]);
    let g3 = libm::acosf(-n3[0] * n0[0] - n3[1] * n0[1] - n3[2] * n0[2]);
    let k = 2.0 * core::f32::consts::PI - g2 - g3;
    let s = g0 + g1 - k;
    let (b0, b1) = (n0[2], n2[2]);
    let au = u[0] * s + k;
    let fu = (libm::cosf(au) * b0 - b1) / libm::sinf(au);
    let cu = (1.0 / libm::sqrtf(fu * fu + b0 * b0))
        .copysign(fu)
        .clamp(-1.0, 1.0);
    let xu = (-(cu * z0) / libm::sqrtf(1.0 - cu * cu)).clamp(x0, x1);
    let dd = libm::sqrtf(xu * xu + z0 * z0);
    let h0 = y0 / libm::sqrtf(dd * dd + y0 * y0);
    let h1 = y1 / libm::sqrtf(dd * dd + y1 * y1);
    let hv = h0 + u[1] * (h1 - h0);
    let hv2 = hv * hv;
    let yv = if hv2 < 1.0 - 1e-6 {
        hv * dd / libm::sqrtf(1.0 - hv2)
    } else {
        y1
    };
    ([(xu - x0) / w, (yv - y0) / h], 1.0 / s)
}

/// pbrt-v4's sphere-light sampling as a textbook transcription (Pharr, Jakob and Humphreys,
/// "Physically Based Rendering", 4th ed., `SampleUniformCone` with the sphere's
/// `sin^2 theta_max = r^2 / d^2`): `cos theta = (1 - u0) + u0 cos theta_max`, `phi = 2 pi
/// u1`, the frame from `d / |d|` (Duff et al. 2017); `1 - cos` cancels below about 1e-4 sr.
#[inline(always)]
fn cone_textbook(c: V, r: f32, p: V, u: [f32; 2]) -> ([f32; 3], f32) {
    let d = sub(c, p);
    let d2 = dot(d, d);
    let n = scale(d, 1.0 / libm::sqrtf(d2));
    let sin2 = r * r / d2;
    let cos_max = libm::sqrtf((1.0 - sin2).max(0.0));
    let cos = (1.0 - u[0]) + u[0] * cos_max;
    let sin = libm::sqrtf((1.0 - cos * cos).max(0.0));
    let phi = u[1] * core::f32::consts::TAU;
    let sign = 1.0f32.copysign(n[2]);
    let a = -1.0 / (sign + n[2]);
    let b = n[0] * n[1] * a;
    let t = [1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]];
    let bb = [b, sign + n[1] * n[1] * a, -n[1]];
    let (sp, cp) = (libm::sinf(phi), libm::cosf(phi));
    let dir = add(add(scale(t, sin * cp), scale(bb, sin * sp)), scale(n, cos));
    (dir, 1.0 / (core::f32::consts::TAU * (1.0 - cos_max)))
}

/// A sphere light (centre, radius), a shading point and `u`.
type ConeCall = (V, f32, V, [f32; 2]);

/// `BATCH` random spheres of radius 0.05 .. 0.5 at distance 1 .. 3 (about 1e-3 .. 0.8 sr).
fn random_spheres() -> Vec<ConeCall> {
    uniform_points::<8>(BATCH, 5)
        .iter()
        .map(|x| {
            let c = [x[0] * 2.0 - 1.0, x[1] * 2.0 - 1.0, 1.0 + 2.0 * x[2]];
            let p = [x[3] * 0.6 - 0.3, x[4] * 0.6 - 0.3, 0.0];
            (c, 0.05 + 0.45 * x[5], p, [x[6], x[7]])
        })
        .collect()
}

/// A triangle light, a shading point and `u`.
type TriCall = ([V; 3], V, [f32; 2]);
/// A rectangle light (corner, ex, ey), a shading point and `u`.
type RectCall = (V, V, V, V, [f32; 2]);

/// `BATCH` random triangles and rectangles of about 0.01 to 1 sr (centres in a 2 x 2 box two
/// units above the shading points' 0.6 x 0.6 box, edges up to 1 long, rectangles rotated
/// about the normal), each with its own shading point and `u`.
fn random_lights() -> (Vec<TriCall>, Vec<RectCall>) {
    let r = uniform_points::<16>(BATCH, 3);
    let at = |x: &[f32], lo: f32, hi: f32| [0, 1, 2].map(|k| lo + (hi - lo) * x[k]);
    let tris = r
        .iter()
        .map(|x| {
            let c = at(&x[0..], -1.0, 1.0);
            let c = [c[0], c[1], c[2] + 2.0];
            let v = [3, 6, 9].map(|k| add(c, at(&x[k..], -0.5, 0.5)));
            (v, at(&x[12..], -0.3, 0.3), [x[15], x[14]])
        })
        .collect();
    let rects = r
        .iter()
        .map(|x| {
            let c = at(&x[0..], -1.0, 1.0);
            let corner = [c[0], c[1], c[2] + 2.0];
            let a = x[3] * core::f32::consts::TAU;
            let (w, h) = (0.2 + 0.8 * x[4], 0.2 + 0.8 * x[5]);
            let ex = [w * libm::cosf(a), w * libm::sinf(a), 0.0];
            let ey = [-h * libm::sinf(a), h * libm::cosf(a), 0.0];
            (corner, ex, ey, at(&x[6..], -0.3, 0.3), [x[9], x[10]])
        })
        .collect();
    (tris, rects)
}

/// A new light, shading point and `u` per call.
fn per_call(c: &mut criterion::Criterion) {
    let (tris, rects) = random_lights();
    let mut g = group(c, "spherical triangle, a light per call");
    let mut out = vec![([0.0f32; 3], 0.0f32); BATCH];
    bench_indexed(&mut g, "warpcore scalar", &mut out, |i| {
        let (v, p, u) = tris[black_box(i)];
        spherical::triangle(v, p, u)
    });
    bench_indexed(&mut g, "Arvo textbook f32 scalar", &mut out, |i| {
        let (v, p, u) = tris[black_box(i)];
        arvo_textbook(v, p, u)
    });
    g.finish();
    let mut g = group(c, "spherical rectangle, a light per call");
    let mut out = vec![([0.0f32; 2], 0.0f32); BATCH];
    bench_indexed(&mut g, "warpcore scalar", &mut out, |i| {
        let (corner, ex, ey, p, u) = rects[black_box(i)];
        spherical::rectangle(corner, ex, ey, p, u)
    });
    bench_indexed(&mut g, "Urena textbook f32 scalar", &mut out, |i| {
        let (corner, ex, ey, p, u) = rects[black_box(i)];
        urena_textbook(corner, ex, ey, p, u)
    });
    g.finish();
    let spheres = random_spheres();
    let mut g = group(c, "spherical cone, a light per call");
    let mut out = vec![([0.0f32; 3], 0.0f32); BATCH];
    bench_indexed(&mut g, "warpcore scalar", &mut out, |i| {
        let (c, r, p, u) = spheres[black_box(i)];
        spherical::cone(c, r, p, u)
    });
    bench_indexed(&mut g, "pbrt-v4 textbook cone f32 scalar", &mut out, |i| {
        let (c, r, p, u) = spheres[black_box(i)];
        cone_textbook(c, r, p, u)
    });
    g.finish();
}

fn main() {
    let mut c = common::criterion();
    per_call(&mut c);
    let input = uniform_points::<2>(BATCH, 1);
    // A triangle and a square of about 0.5 sr seen obliquely.
    let tri = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.2], [0.0, 1.0, 0.9]];
    let tp = [0.2f32, 0.1, 0.0];
    let (corner, ex, ey, rp) = (
        [-0.5f32, -0.5, 1.0],
        [1.0f32, 0.0, 0.0],
        [0.0f32, 1.0, 0.0],
        [0.3f32, 0.2, 0.0],
    );
    {
        let mut g = group(&mut c, "spherical triangle");
        let mut out = vec![([0.0f32; 3], 0.0f32); BATCH];
        let label = "warpcore scalar, light black-boxed per call";
        bench_map(&mut g, label, &input, &mut out, |u| {
            spherical::triangle(black_box(tri), black_box(tp), u)
        });
        let mut out4 = vec![[0.0f32; 4]; BATCH];
        bench_out(&mut g, "warpcore slice", &mut out4, |out| {
            spherical::triangle_slice(tri, tp, black_box(&input), out);
        });
        let n = [0.2f32, 0.1, 1.0];
        bench_out(&mut g, "warpcore cosine slice", &mut out4, |out| {
            spherical::triangle_cosine_slice(tri, tp, n, black_box(&input), out);
        });
        bench_map(&mut g, "Arvo textbook f32 scalar", &input, &mut out, |u| {
            arvo_textbook(black_box(tri), black_box(tp), u)
        });
        g.finish();
    }
    {
        let mut g = group(&mut c, "spherical rectangle");
        let mut out = vec![([0.0f32; 2], 0.0f32); BATCH];
        let label = "warpcore scalar, light black-boxed per call";
        bench_map(&mut g, label, &input, &mut out, |u| {
            let [c, x, y, p] = black_box([corner, ex, ey, rp]);
            spherical::rectangle(c, x, y, p, u)
        });
        let mut out3 = vec![[0.0f32; 3]; BATCH];
        bench_out(&mut g, "warpcore slice", &mut out3, |out| {
            spherical::rectangle_slice(corner, ex, ey, rp, black_box(&input), out);
        });
        let n = [0.1f32, -0.3, 1.0];
        bench_out(&mut g, "warpcore cosine slice", &mut out3, |out| {
            spherical::rectangle_cosine_slice(corner, ex, ey, rp, n, black_box(&input), out);
        });
        bench_map(&mut g, "Urena textbook f32 scalar", &input, &mut out, |u| {
            let [c, x, y, p] = black_box([corner, ex, ey, rp]);
            urena_textbook(c, x, y, p, u)
        });
        g.finish();
    }
    {
        let mut g = group(&mut c, "spherical cone");
        let (centre, r, p) = ([0.3f32, -0.2, 2.0], 0.5f32, [0.1f32, 0.0, 0.0]);
        let mut out = vec![([0.0f32; 3], 0.0f32); BATCH];
        let label = "warpcore scalar, light black-boxed per call";
        bench_map(&mut g, label, &input, &mut out, |u| {
            spherical::cone(black_box(centre), black_box(r), black_box(p), u)
        });
        let mut out4 = vec![[0.0f32; 4]; BATCH];
        bench_out(&mut g, "warpcore slice", &mut out4, |out| {
            spherical::cone_slice(centre, r, p, black_box(&input), out);
        });
        bench_map(
            &mut g,
            "pbrt-v4 textbook cone f32 scalar",
            &input,
            &mut out,
            |u| cone_textbook(black_box(centre), black_box(r), black_box(p), u),
        );
        g.finish();
    }
    c.final_summary();
}
