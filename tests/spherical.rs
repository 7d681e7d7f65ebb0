//! Lights by solid angle: accuracy of the solid angle and of the density against f64,
//! round trips, chi-square uniformity in solid angle, compact strata, totality on stiff and
//! non-finite input, and bit identity across widths.
#![cfg(feature = "spherical")]
#![allow(clippy::needless_range_loop)]

mod common;

use common::{chi2, rng, specials, unit2};
use rand::RngExt;
use rand_xoshiro::Xoshiro256PlusPlus;
use warpcore::spherical;
use warpcore::{f32x8, f32x16};

type V3 = [f64; 3];

fn d3(v: [f32; 3]) -> V3 {
    [v[0] as f64, v[1] as f64, v[2] as f64]
}
fn sub(a: V3, b: V3) -> V3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn add(a: V3, b: V3) -> V3 {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
fn mul(a: V3, k: f64) -> V3 {
    [a[0] * k, a[1] * k, a[2] * k]
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn norm(a: V3) -> f64 {
    dot(a, a).sqrt()
}

/// f64 Van Oosterom-Strackee for the triangle with vertices `a`, `a + e1`, `a + e2`
/// (relative to the shading point; edges given separately so no cancellation enters).
fn vos(a: V3, e1: V3, e2: V3) -> f64 {
    let b = add(a, e1);
    let c = add(a, e2);
    let det = dot(a, cross(e1, e2)).abs();
    let (la, lb, lc) = (norm(a), norm(b), norm(c));
    let den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
    2.0 * det.atan2(den)
}

/// The solid angle's condition number for perturbations of the vertices relative to `p`:
/// `|v0 - p| |n| / |(v0 - p) . n|`, one over the cosine at which `p` sees the light's plane.
fn tri_kappa(v: [[f32; 3]; 3], p: [f32; 3]) -> f64 {
    let (v0, v1, v2, p) = (d3(v[0]), d3(v[1]), d3(v[2]), d3(p));
    let (a, n) = (sub(v0, p), cross(sub(v1, v0), sub(v2, v0)));
    norm(a) * norm(n) / dot(a, n).abs()
}

fn rect_kappa(c: [f32; 3], ex: [f32; 3], ey: [f32; 3], p: [f32; 3]) -> f64 {
    let (a, n) = (sub(d3(c), d3(p)), cross(d3(ex), d3(ey)));
    let far = [
        a,
        add(a, d3(ex)),
        add(a, d3(ey)),
        add(add(a, d3(ex)), d3(ey)),
    ]
    .iter()
    .map(|&q| norm(q))
    .fold(0.0, f64::max);
    far * norm(n) / dot(a, n).abs()
}

fn tri_omega(v: [[f32; 3]; 3], p: [f32; 3]) -> f64 {
    let (v0, v1, v2, p) = (d3(v[0]), d3(v[1]), d3(v[2]), d3(p));
    vos(sub(v0, p), sub(v1, v0), sub(v2, v0))
}

fn rect_omega(c: [f32; 3], ex: [f32; 3], ey: [f32; 3], p: [f32; 3]) -> f64 {
    let (c, ex, ey, p) = (d3(c), d3(ex), d3(ey), d3(p));
    let a = sub(c, p);
    vos(a, ex, add(ex, ey)) + vos(a, add(ex, ey), ey)
}

/// A random unit vector.
fn dir(r: &mut Xoshiro256PlusPlus) -> V3 {
    loop {
        let v = [
            2.0 * r.random::<f64>() - 1.0,
            2.0 * r.random::<f64>() - 1.0,
            2.0 * r.random::<f64>() - 1.0,
        ];
        let n = norm(v);
        if n > 0.1 && n <= 1.0 {
            return mul(v, 1.0 / n);
        }
    }
}

fn f3(v: V3) -> [f32; 3] {
    [v[0] as f32, v[1] as f32, v[2] as f32]
}

/// A random triangle of size ~`size` at distance `dist` from a random shading point whose
/// coordinates are of order `offset`; shapes from equilateral-ish to thin.
fn random_triangle(
    r: &mut Xoshiro256PlusPlus,
    size: f64,
    dist: f64,
    offset: f64,
) -> ([[f32; 3]; 3], [f32; 3]) {
    let p = mul(dir(r), offset * r.random::<f64>());
    let centre = add(p, mul(dir(r), dist));
    let v: [[f32; 3]; 3] =
        std::array::from_fn(|_| f3(add(centre, mul(dir(r), size * (0.2 + r.random::<f64>())))));
    (v, f3(p))
}

/// A random rectangle (orthogonal sides, aspect up to 16) of size ~`size` at distance
/// `dist`; the sides are exactly orthogonal in f32 (axis-aligned frame rotated by one of a
/// few exact permutations and sign flips).
fn random_rect(
    r: &mut Xoshiro256PlusPlus,
    size: f64,
    dist: f64,
    offset: f64,
) -> ([f32; 3], [f32; 3], [f32; 3], [f32; 3]) {
    let p = mul(dir(r), offset * r.random::<f64>());
    let centre = add(p, mul(dir(r), dist));
    let w = size * (0.25 + r.random::<f64>());
    let h = w / (1.0 + 15.0 * r.random::<f64>());
    let axis = r.random_range(0..3usize);
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut ex = [0.0; 3];
    let mut ey = [0.0; 3];
    ex[i] = if r.random::<bool>() { w } else { -w };
    ey[j] = if r.random::<bool>() { h } else { -h };
    if r.random::<bool>() {
        std::mem::swap(&mut ex, &mut ey);
    }
    let corner = sub(centre, mul(add(ex, ey), 0.5));
    (f3(corner), f3(ex), f3(ey), f3(p))
}

fn assert_total_tri(v: [[f32; 3]; 3], p: [f32; 3], u: [f32; 2]) {
    let (b, pdf) = spherical::triangle(v, p, u);
    assert!(
        b.iter().all(|x| (0.0..=1.0).contains(x)),
        "{v:?} {p:?} {u:?}: {b:?}"
    );
    let s = b[0] as f64 + b[1] as f64 + b[2] as f64;
    assert!((s - 1.0).abs() <= 3e-7, "{v:?} {p:?} {u:?}: sum {s}");
    assert!(
        pdf.is_finite() && pdf >= 0.0,
        "{v:?} {p:?} {u:?}: pdf {pdf}"
    );
    let w = spherical::triangle_inverse(v, p, b);
    assert!(w.iter().all(|x| (0.0..1.0).contains(x)), "inverse {w:?}");
    let o = spherical::triangle_solid_angle(v, p);
    assert!((0.0..=std::f32::consts::TAU).contains(&o), "omega {o}");
}

fn assert_total_rect(c: [f32; 3], ex: [f32; 3], ey: [f32; 3], p: [f32; 3], u: [f32; 2]) {
    let (st, pdf) = spherical::rectangle(c, ex, ey, p, u);
    assert!(
        st.iter().all(|x| (0.0..=1.0).contains(x)),
        "{c:?} {ex:?} {ey:?} {p:?} {u:?}: {st:?}"
    );
    assert!(
        pdf.is_finite() && pdf >= 0.0,
        "{c:?} {ex:?} {ey:?} {p:?} {u:?}: pdf {pdf}"
    );
    let w = spherical::rectangle_inverse(c, ex, ey, p, st);
    assert!(w.iter().all(|x| (0.0..1.0).contains(x)), "inverse {w:?}");
    let o = spherical::rectangle_solid_angle(c, ex, ey, p);
    assert!((0.0..=std::f32::consts::TAU).contains(&o), "omega {o}");
}

/// Solid angle and density against f64 over lights from ~1e-9 sr to nearly 2 pi, and the
/// round trip for 1e-4..2 sr. Prints the measured maxima (the figures in the docs).
#[test]
fn accuracy_against_f64() {
    let mut r = rng(22);
    let mut worst = [0.0f64; 6];
    // Round-trip maxima over well-conditioned lights (kappa <= 100), and error / kappa over all.
    let mut rt = [0.0f64; 4];
    let mut count = [0usize; 2];
    for k in 0..20_000 {
        // size / distance from 1e-5 to 1e2, distances 1e-6 .. 1e6.
        let ratio = 10f64.powf(-5.0 + 7.0 * r.random::<f64>());
        let dist = 10f64.powf(-6.0 + 12.0 * r.random::<f64>());
        let offset = if k % 2 == 0 { 0.0 } else { dist };
        let u = unit2(&mut r);
        // Triangle.
        let (v, p) = random_triangle(&mut r, ratio * dist, dist, offset);
        let om = tri_omega(v, p);
        if om > 1e-8 && om < 6.2 {
            let kappa = tri_kappa(v, p);
            let o = spherical::triangle_solid_angle(v, p) as f64;
            worst[0] = worst[0].max((o / om - 1.0).abs() / kappa);
            let (b, pdf) = spherical::triangle(v, p, u);
            worst[1] = worst[1].max((pdf as f64 * om - 1.0).abs() / kappa);
            if (1e-4..=2.0).contains(&om) && u[1] >= 0.01 {
                count[0] += 1;
                let w = spherical::triangle_inverse(v, p, b);
                let e = (w[0] - u[0]).abs().max((w[1] - u[1]).abs()) as f64;
                if kappa <= 100.0 {
                    rt[0] = rt[0].max(e);
                }
                rt[1] = rt[1].max(e / kappa);
            }
        }
        // Rectangle.
        let (c, ex, ey, p) = random_rect(&mut r, ratio * dist, dist, offset);
        let om = rect_omega(c, ex, ey, p);
        if om > 1e-8 && om < 6.2 {
            let kappa = rect_kappa(c, ex, ey, p);
            let o = spherical::rectangle_solid_angle(c, ex, ey, p) as f64;
            worst[3] = worst[3].max((o / om - 1.0).abs() / kappa);
            let (st, pdf) = spherical::rectangle(c, ex, ey, p, u);
            let e = (pdf as f64 * om - 1.0).abs() / kappa;
            worst[4] = worst[4].max(e);
            if (1e-4..=2.0).contains(&om) {
                count[1] += 1;
                let w = spherical::rectangle_inverse(c, ex, ey, p, st);
                let e = (w[0] - u[0]).abs().max((w[1] - u[1]).abs()) as f64;
                if kappa <= 100.0 {
                    rt[2] = rt[2].max(e);
                }
                rt[3] = rt[3].max(e / kappa);
            }
        }
    }
    eprintln!(
        "relative error / kappa: triangle omega {:.2e}, density {:.2e}; rectangle omega {:.2e}, density {:.2e}",
        worst[0], worst[1], worst[3], worst[4]
    );
    eprintln!(
        "round trip (1e-4..2 sr): triangle {:.2e} at kappa <= 100, {:.2e} kappa overall ({} cases); rectangle {:.2e} at kappa <= 100, {:.2e} kappa overall ({} cases)",
        rt[0], rt[1], count[0], rt[2], rt[3], count[1]
    );
    // The density: 1e-4 relative for kappa <= 100 (the contract's well-conditioned cases).
    assert!(worst[0] < 1e-6 && worst[1] < 1e-6 && worst[3] < 1e-6 && worst[4] < 1e-6);
    assert!(rt[0] < 1e-4 && rt[2] < 1e-4 && rt[1] < 1e-5 && rt[3] < 1e-5);
    assert!(count[0] > 2000 && count[1] > 2000);
}

/// A few lights with every kind of trouble: slivers, collinear and repeated vertices, `p` at
/// a vertex, on an edge, on the plane inside and outside, at 1e-6 and 1e6, tiny and huge
/// coordinates.
fn stiff_triangles() -> Vec<([[f32; 3]; 3], [f32; 3])> {
    let t = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let mut out = vec![
        (t, [0.0, 0.0, 0.0]),
        (t, [0.2, 0.2, 1.0]),        // on the plane, inside
        (t, [3.0, 3.0, 1.0]),        // on the plane, outside
        (t, [0.5, 0.0, 1.0]),        // on an edge
        (t, t[1]),                   // at a vertex
        (t, [0.2, 0.2, 1.0 - 1e-6]), // just below the plane
        (t, [0.2, 0.2, 1.0 + 1e-6]), // just above
        (t, [0.2, 0.2, 1e6]),        // far
        (t, [1e6, -1e6, 1e6]),       // far and oblique
        (t, [0.2, 0.2, -1e30]),
        (
            [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [2.0, 0.0, 1.0]],
            [0.0; 3],
        ), // collinear
        (
            [[0.0, 0.0, 1.0], [0.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            [0.0; 3],
        ), // repeated vertex
        ([[0.0, 0.0, 1.0]; 3], [0.0; 3]), // a point
        (
            [[0.0, 0.0, 1.0], [1.0, 1e-7, 1.0], [2.0, 0.0, 1.0]],
            [0.0; 3],
        ), // sliver
        (
            [[0.0, 0.0, 1e-6], [1e-6, 0.0, 1e-6], [0.0, 1e-6, 1e-6]],
            [0.0; 3],
        ), // 1e-6 away
        (
            [[0.0, 0.0, 1e6], [1.0, 0.0, 1e6], [0.0, 1.0, 1e6]],
            [0.0; 3],
        ), // 1e-12 sr
        (
            [[0.0, 0.0, 1e-30], [1e-30, 0.0, 1e-30], [0.0, 1e-30, 1e-30]],
            [0.0; 3],
        ),
        (
            [[-1e30, -1e30, 1.0], [1e30, -1e30, 1.0], [0.0, 1e30, 1.0]],
            [0.0; 3],
        ), // nearly 2 pi
        (
            [[-3e38, 0.0, 1.0], [3e38, 0.0, 1.0], [0.0, 3e38, 1.0]],
            [0.0; 3],
        ), // edges overflow
        (
            [
                [0.0, 0.0, f32::MIN_POSITIVE],
                [f32::from_bits(1), 0.0, 1.0],
                [0.0, 1.0, 1.0],
            ],
            [0.0; 3],
        ),
    ];
    // Every special value in every one of the 12 coordinates of the plain case.
    for x in specials() {
        for k in 0..12 {
            let (mut v, mut p) = (t, [0.25f32, 0.25, 0.0]);
            if k < 9 {
                v[k / 3][k % 3] = x;
            } else {
                p[k - 9] = x;
            }
            out.push((v, p));
        }
    }
    out
}

/// A rectangle light and a shading point: `(corner, ex, ey, p)`.
type RectCase = ([f32; 3], [f32; 3], [f32; 3], [f32; 3]);

fn stiff_rects() -> Vec<RectCase> {
    let (c, ex, ey) = ([-0.5f32, -0.5, 1.0], [1.0f32, 0.0, 0.0], [0.0f32, 1.0, 0.0]);
    let mut out = vec![
        (c, ex, ey, [0.0, 0.0, 0.0]),
        (c, ex, ey, [0.1, 0.1, 1.0]), // on the plane, inside
        (c, ex, ey, [3.0, 0.1, 1.0]), // on the plane, outside
        (c, ex, ey, c),               // at the corner
        (c, ex, ey, [0.1, 0.1, 1.0 - 1e-6]),
        (c, ex, ey, [0.0, 0.0, -1e6]),
        (c, ex, ey, [1e6, 1e6, 1.0 - 1e-3]), // far and grazing
        (c, [0.0; 3], ey, [0.0; 3]),         // zero-area
        (c, ex, [0.0; 3], [0.0; 3]),
        (c, ex, ex, [0.0; 3]),               // parallel sides
        (c, [1e-7, 0.0, 0.0], ey, [0.0; 3]), // sliver
        (
            [-1e30, -1e30, 1.0],
            [2e30, 0.0, 0.0],
            [0.0, 2e30, 0.0],
            [0.0; 3],
        ), // nearly 2 pi
        (
            [0.0, 0.0, 1e-6],
            [1e-6, 0.0, 0.0],
            [0.0, 1e-6, 0.0],
            [0.0; 3],
        ),
        ([0.0, 0.0, 1e6], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]), // 1e-12 sr
        (
            [-3e38, 0.0, 1.0],
            [f32::MAX, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0; 3],
        ),
    ];
    for x in specials() {
        for k in 0..12 {
            let mut a = [c, ex, ey, [0.1f32, 0.2, 0.0]];
            a[k / 3][k % 3] = x;
            out.push((a[0], a[1], a[2], a[3]));
        }
    }
    out
}

fn stiff_us() -> Vec<[f32; 2]> {
    let sp = specials();
    let mut us = vec![];
    for &a in &sp {
        for &b in &[0.0f32, 0.5, 1.0, f32::NAN] {
            us.push([a, b]);
            us.push([b, a]);
        }
    }
    us
}

#[test]
fn total_on_stiff_input() {
    let us = stiff_us();
    for (v, p) in stiff_triangles() {
        for &u in &us {
            assert_total_tri(v, p, u);
        }
        for b in [
            [f32::NAN, 0.5, 0.5],
            [-1.0, 2.0, f32::INFINITY],
            [0.0; 3],
            [1.0, 0.0, 0.0],
        ] {
            let w = spherical::triangle_inverse(v, p, b);
            assert!(
                w.iter().all(|x| (0.0..1.0).contains(x)),
                "{v:?} {p:?} {b:?}: {w:?}"
            );
        }
    }
    for (c, ex, ey, p) in stiff_rects() {
        for &u in &us {
            assert_total_rect(c, ex, ey, p, u);
        }
        let w = spherical::rectangle_inverse(c, ex, ey, p, [f32::NAN, f32::INFINITY]);
        assert!(w.iter().all(|x| (0.0..1.0).contains(x)));
    }
    // Random lights over 24 decades of scale and distance, every u.
    let mut r = rng(7);
    for _ in 0..20_000 {
        let ratio = 10f64.powf(-8.0 + 10.0 * r.random::<f64>());
        let dist = 10f64.powf(-12.0 + 24.0 * r.random::<f64>());
        let (v, p) = random_triangle(&mut r, ratio * dist, dist, dist);
        assert_total_tri(v, p, unit2(&mut r));
        let (c, ex, ey, p) = random_rect(&mut r, ratio * dist, dist, dist);
        assert_total_rect(c, ex, ey, p, unit2(&mut r));
    }
}

/// The documented zero-density cases, and the area fallback's density below 1e-8 sr.
#[test]
fn degenerate_and_fallback_densities() {
    let t = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    for p in [
        [0.2f32, 0.2, 1.0],
        [3.0, 3.0, 1.0],
        t[0],
        [f32::NAN, 0.0, 0.0],
    ] {
        assert_eq!(spherical::triangle(t, p, [0.3, 0.6]).1, 0.0, "{p:?}");
    }
    let (c, ex, ey) = ([-0.5f32, -0.5, 1.0], [1.0f32, 0.0, 0.0], [0.0f32, 1.0, 0.0]);
    assert_eq!(
        spherical::rectangle(c, [0.0; 3], ey, [0.0; 3], [0.3, 0.6]).1,
        0.0
    );
    assert_eq!(
        spherical::rectangle(c, ex, ey, [0.1, 0.1, 1.0], [0.3, 0.6]).1,
        0.0
    );
    // 1e-12 sr: area sampling; the density is |q - p|^2 / (cos area) at the returned point.
    let far = [[0.0f32, 0.0, 1e6], [1.0, 0.0, 1e6], [0.0, 1.0, 1e6]];
    let (b, pdf) = spherical::triangle(far, [0.0; 3], [0.3, 0.6]);
    let q: V3 = std::array::from_fn(|k| {
        b[0] as f64 * far[0][k] as f64
            + b[1] as f64 * far[1][k] as f64
            + b[2] as f64 * far[2][k] as f64
    });
    let want = dot(q, q) / ((q[2] / norm(q)) * 0.5);
    assert!((pdf as f64 / want - 1.0).abs() < 1e-5, "{pdf} {want}");
    assert_eq!(b, warpcore::triangle::uniform([0.3, 0.6]));
    let (st, pdf) = spherical::rectangle([0.0, 0.0, 1e6], ex, ey, [0.0; 3], [0.3, 0.6]);
    assert_eq!(st, [0.3, 0.6]);
    let q = [0.3f64, 0.6, 1e6];
    let want = dot(q, q) / (q[2] / norm(q));
    assert!((pdf as f64 / want - 1.0).abs() < 1e-5, "{pdf} {want}");
    // Just above the threshold the exact map runs and its density is 1 / omega.
    let om = spherical::rectangle_solid_angle([0.0, 0.0, 5e3], ex, ey, [0.0; 3]);
    assert!(om > spherical::AREA_FALLBACK_SR && om < 1e-7);
    let (_, pdf) = spherical::rectangle([0.0, 0.0, 5e3], ex, ey, [0.0; 3], [0.3, 0.6]);
    assert!((pdf * om - 1.0).abs() < 1e-5);
}

/// Triangle: the 16 sub-triangles of the 4x4 barycentric grid, expected probabilities their
/// f64 solid angles over the whole. Three lights (near, oblique at kappa ~ 10, large), 2^21
/// samples each from a seeded generator; Sidak-corrected level of `common::chi2`.
#[test]
fn chi2_triangle_uniform_in_solid_angle() {
    let lights: [([[f32; 3]; 3], [f32; 3]); 3] = [
        (
            [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            [0.1, 0.1, 0.0],
        ),
        (
            [[0.0, 0.0, 0.2], [4.0, 0.0, 0.2], [0.5, 3.0, 0.2]],
            [-0.5, 0.3, 0.0],
        ),
        (
            [[-3.0, -2.0, 0.5], [3.0, -2.0, 0.5], [0.0, 4.0, 0.5]],
            [0.0, 0.0, 0.0],
        ),
    ];
    let n = 4usize;
    for (li, (v, p)) in lights.into_iter().enumerate() {
        // Sub-triangle k of the grid: up triangles (i, j) with i + j < n and down ones.
        let (v0, v1, v2, pp) = (d3(v[0]), d3(v[1]), d3(v[2]), d3(p));
        let at = |b1: f64, b2: f64| add(v0, add(mul(sub(v1, v0), b1), mul(sub(v2, v0), b2)));
        let mut expected = vec![];
        let h = 1.0 / n as f64;
        for i in 0..n {
            for j in 0..n - i {
                let (a, b, c) = (
                    at(i as f64 * h, j as f64 * h),
                    at((i + 1) as f64 * h, j as f64 * h),
                    at(i as f64 * h, (j + 1) as f64 * h),
                );
                expected.push(vos(sub(a, pp), sub(b, a), sub(c, a)));
                if i + j + 1 < n {
                    let d = at((i + 1) as f64 * h, (j + 1) as f64 * h);
                    expected.push(vos(sub(b, pp), sub(d, b), sub(c, b)));
                }
            }
        }
        let total: f64 = expected.iter().sum();
        assert!((total / tri_omega(v, p) - 1.0).abs() < 1e-9);
        let expected: Vec<f64> = expected.iter().map(|e| e / total).collect();
        let cells = expected.len();
        let mut hist = chi2::Histogram::new(cells, 1);
        let mut r = rng(100 + li as u64);
        for _ in 0..chi2::SAMPLES {
            let (b, _) = spherical::triangle(v, p, unit2(&mut r));
            let (x, y) = (b[1] as f64 * n as f64, b[2] as f64 * n as f64);
            let (i, j) = ((x as usize).min(n - 1), (y as usize).min(n - 1));
            let (i, j) = if i + j >= n { (n - 1 - j, j) } else { (i, j) };
            let up = x - i as f64 + y - j as f64 <= 1.0 || i + j + 1 >= n;
            // Index in the order pushed above.
            let mut k = 0;
            for ii in 0..i {
                k += 2 * (n - ii) - 1;
            }
            k += 2 * j + if up { 0 } else { 1 };
            hist.add([(k as f64 + 0.5) / cells as f64, 0.5]);
        }
        chi2::check(&format!("spherical triangle {li}"), &hist, &expected);
    }
}

/// Rectangle: an 8x8 grid of sub-rectangles, expected probabilities their f64 solid angles.
/// A square overhead, a 16:1 strip seen obliquely, a grazing one; 2^21 samples each.
#[test]
fn chi2_rectangle_uniform_in_solid_angle() {
    let lights = [
        (
            [-0.5f32, -0.5, 1.0],
            [1.0f32, 0.0, 0.0],
            [0.0f32, 1.0, 0.0],
            [0.0f32; 3],
        ),
        (
            [0.0, -0.125, 0.5],
            [4.0, 0.0, 0.0],
            [0.0, 0.25, 0.0],
            [-1.0, 0.3, 0.0],
        ),
        (
            [1.0, -2.0, 0.1],
            [0.0, 4.0, 0.0],
            [3.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
        ),
    ];
    let n = 8usize;
    for (li, (c, ex, ey, p)) in lights.into_iter().enumerate() {
        let (cc, ex64, ey64) = (d3(c), d3(ex), d3(ey));
        let mut expected = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                let corner = add(
                    cc,
                    add(
                        mul(ex64, i as f64 / n as f64),
                        mul(ey64, j as f64 / n as f64),
                    ),
                );
                let (a, ux, uy) = (
                    sub(corner, d3(p)),
                    mul(ex64, 1.0 / n as f64),
                    mul(ey64, 1.0 / n as f64),
                );
                expected[j * n + i] = vos(a, ux, add(ux, uy)) + vos(a, add(ux, uy), uy);
            }
        }
        let total: f64 = expected.iter().sum();
        assert!((total / rect_omega(c, ex, ey, p) - 1.0).abs() < 1e-9);
        let expected: Vec<f64> = expected.iter().map(|e| e / total).collect();
        let mut hist = chi2::Histogram::new(n, n);
        let mut r = rng(200 + li as u64);
        for _ in 0..chi2::SAMPLES {
            let (st, _) = spherical::rectangle(c, ex, ey, p, unit2(&mut r));
            hist.add([st[0] as f64, st[1] as f64]);
        }
        chi2::check(&format!("spherical rectangle {li}"), &hist, &expected);
    }
}

/// Compact strata: the image of each cell of an 8x8 grid of the square (sampled on a 5x5
/// sub-grid) has a diameter at most the stated fraction of the light's. Urena's map keeps
/// cells near-rectangular (bound 0.3, a cell's own diagonal is 0.18); Arvo's makes wedges
/// at v1 like the sqrt map (bound 0.5). A map that tears or folds the square breaks these.
#[test]
fn compact_strata_stay_compact() {
    let n = 8;
    let m = 5;
    let v = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let p = [0.2f32, 0.3, 0.0];
    let pos = |b: [f32; 3]| -> V3 {
        std::array::from_fn(|k| (0..3).map(|i| b[i] as f64 * v[i][k] as f64).sum())
    };
    let mut worst = [0.0f64; 2];
    for ci in 0..n {
        for cj in 0..n {
            let mut tri = vec![];
            let mut rect = vec![];
            for a in 0..m {
                for b in 0..m {
                    let u = [
                        (ci as f32 + a as f32 / (m - 1) as f32 * 0.999) / n as f32,
                        (cj as f32 + b as f32 / (m - 1) as f32 * 0.999) / n as f32,
                    ];
                    tri.push(pos(spherical::triangle(v, p, u).0));
                    let (st, _) = spherical::rectangle(
                        [-0.5, -0.5, 1.0],
                        [1.0, 0.0, 0.0],
                        [0.0, 1.0, 0.0],
                        [0.2, 0.1, 0.0],
                        u,
                    );
                    rect.push([st[0] as f64, st[1] as f64, 0.0]);
                }
            }
            let diam = |pts: &[V3]| {
                pts.iter()
                    .flat_map(|a| pts.iter().map(move |b| norm(sub(*a, *b))))
                    .fold(0.0, f64::max)
            };
            worst[0] = worst[0].max(diam(&tri) / 2f64.sqrt());
            worst[1] = worst[1].max(diam(&rect) / 2f64.sqrt());
        }
    }
    eprintln!(
        "largest stratum diameter / light diameter: triangle {:.3}, rectangle {:.3}",
        worst[0], worst[1]
    );
    assert!(worst[0] < 0.5 && worst[1] < 0.3, "{worst:?}");
}

fn lane8<const N: usize>(v: [f32x8; N], j: usize) -> [f32; N] {
    std::array::from_fn(|k| v[k].to_array()[j])
}
fn lane16<const N: usize>(v: [f32x16; N], j: usize) -> [f32; N] {
    std::array::from_fn(|k| v[k].to_array()[j])
}
fn bits<const N: usize>(a: [f32; N]) -> [u32; N] {
    a.map(f32::to_bits)
}

/// scalar == x8 == x16 == slice, bit for bit, over random lights (every lane its own light)
/// mixed with the stiff cases, and the slice form (one light, many u) at several lengths.
#[test]
fn widths_agree_bit_for_bit() {
    let mut r = rng(9);
    let tris = stiff_triangles();
    let rects = stiff_rects();
    let us = stiff_us();
    for round in 0..400 {
        let mut tv = vec![];
        let mut rv = vec![];
        for j in 0..16 {
            let u = if j % 3 == 0 {
                us[(round * 16 + j) % us.len()]
            } else {
                unit2(&mut r)
            };
            let dist = 10f64.powf(-3.0 + 6.0 * r.random::<f64>());
            let size = dist * r.random::<f64>();
            let (v, p) = if j % 4 == 1 {
                tris[(round * 7 + j) % tris.len()]
            } else {
                random_triangle(&mut r, size, dist, dist)
            };
            let rc = if j % 4 == 1 {
                rects[(round * 7 + j) % rects.len()]
            } else {
                random_rect(&mut r, size, dist, dist)
            };
            tv.push((v, p, u));
            rv.push((rc, u));
        }
        let t8 = |g: &dyn Fn(usize) -> f32| f32x8::new(std::array::from_fn(g));
        let t16 = |g: &dyn Fn(usize) -> f32| f32x16::new(std::array::from_fn(g));
        macro_rules! soa {
            ($mk:ident, $f:expr) => {
                $mk(&$f)
            };
        }
        // Triangles.
        let v8: [[f32x8; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|k| soa!(t8, |j| tv[j].0[i][k])));
        let p8: [f32x8; 3] = std::array::from_fn(|k| soa!(t8, |j| tv[j].1[k]));
        let u8_: [f32x8; 2] = std::array::from_fn(|k| soa!(t8, |j| tv[j].2[k]));
        let v16: [[f32x16; 3]; 3] =
            std::array::from_fn(|i| std::array::from_fn(|k| soa!(t16, |j| tv[j].0[i][k])));
        let p16: [f32x16; 3] = std::array::from_fn(|k| soa!(t16, |j| tv[j].1[k]));
        let u16_: [f32x16; 2] = std::array::from_fn(|k| soa!(t16, |j| tv[j].2[k]));
        let (b8, d8) = spherical::triangle_x8(v8, p8, u8_);
        let (b16, d16) = spherical::triangle_x16(v16, p16, u16_);
        let i8 = spherical::triangle_inverse_x8(v8, p8, b8);
        let i16 = spherical::triangle_inverse_x16(v16, p16, b16);
        let o8 = spherical::triangle_solid_angle_x8(v8, p8).to_array();
        let o16 = spherical::triangle_solid_angle_x16(v16, p16).to_array();
        for j in 0..16 {
            let (v, p, u) = tv[j];
            let (b, d) = spherical::triangle(v, p, u);
            let w = spherical::triangle_inverse(v, p, b);
            let o = spherical::triangle_solid_angle(v, p);
            assert_eq!(bits(b), bits(lane16(b16, j)));
            assert_eq!(d.to_bits(), d16.to_array()[j].to_bits());
            assert_eq!(bits(w), bits(lane16(i16, j)));
            assert_eq!(o.to_bits(), o16[j].to_bits());
            if j < 8 {
                assert_eq!(bits(b), bits(lane8(b8, j)));
                assert_eq!(d.to_bits(), d8.to_array()[j].to_bits());
                assert_eq!(bits(w), bits(lane8(i8, j)));
                assert_eq!(o.to_bits(), o8[j].to_bits());
            }
        }
        // Rectangles.
        let g = |k: usize, i: usize| -> [f32; 3] {
            let ((c, ex, ey, p), _) = rv[k];
            [c, ex, ey, p][i]
        };
        let a8: [[f32x8; 3]; 4] =
            std::array::from_fn(|i| std::array::from_fn(|k| soa!(t8, |j| g(j, i)[k])));
        let a16: [[f32x16; 3]; 4] =
            std::array::from_fn(|i| std::array::from_fn(|k| soa!(t16, |j| g(j, i)[k])));
        let ru8: [f32x8; 2] = std::array::from_fn(|k| soa!(t8, |j| rv[j].1[k]));
        let ru16: [f32x16; 2] = std::array::from_fn(|k| soa!(t16, |j| rv[j].1[k]));
        let (s8, e8) = spherical::rectangle_x8(a8[0], a8[1], a8[2], a8[3], ru8);
        let (s16, e16) = spherical::rectangle_x16(a16[0], a16[1], a16[2], a16[3], ru16);
        let j8 = spherical::rectangle_inverse_x8(a8[0], a8[1], a8[2], a8[3], s8);
        let j16 = spherical::rectangle_inverse_x16(a16[0], a16[1], a16[2], a16[3], s16);
        let q8 = spherical::rectangle_solid_angle_x8(a8[0], a8[1], a8[2], a8[3]).to_array();
        let q16 = spherical::rectangle_solid_angle_x16(a16[0], a16[1], a16[2], a16[3]).to_array();
        for j in 0..16 {
            let ((c, ex, ey, p), u) = rv[j];
            let (st, d) = spherical::rectangle(c, ex, ey, p, u);
            let w = spherical::rectangle_inverse(c, ex, ey, p, st);
            let o = spherical::rectangle_solid_angle(c, ex, ey, p);
            assert_eq!(bits(st), bits(lane16(s16, j)));
            assert_eq!(d.to_bits(), e16.to_array()[j].to_bits());
            assert_eq!(bits(w), bits(lane16(j16, j)));
            assert_eq!(o.to_bits(), q16[j].to_bits());
            if j < 8 {
                assert_eq!(bits(st), bits(lane8(s8, j)));
                assert_eq!(d.to_bits(), e8.to_array()[j].to_bits());
                assert_eq!(bits(w), bits(lane8(j8, j)));
                assert_eq!(o.to_bits(), q8[j].to_bits());
            }
        }
        // Slices: one light, many u (lengths around the lane widths).
        let (v, p, _) = tv[round % 16];
        let ((c, ex, ey, rp), _) = rv[round % 16];
        let n = [0usize, 1, 7, 8, 9, 15, 16, 17, 33][round % 9];
        let uu: Vec<[f32; 2]> = (0..n)
            .map(|k| {
                if k % 5 == 0 {
                    us[(round + k) % us.len()]
                } else {
                    unit2(&mut r)
                }
            })
            .collect();
        let mut out4 = vec![[0.0f32; 4]; n + 2];
        assert_eq!(spherical::triangle_slice(v, p, &uu, &mut out4), n);
        let mut out3 = vec![[0.0f32; 3]; n];
        assert_eq!(spherical::rectangle_slice(c, ex, ey, rp, &uu, &mut out3), n);
        let bb: Vec<[f32; 3]> = out4.iter().take(n).map(|o| [o[0], o[1], o[2]]).collect();
        let ss: Vec<[f32; 2]> = out3.iter().map(|o| [o[0], o[1]]).collect();
        let mut inv_t = vec![[0.0f32; 2]; n];
        let mut inv_r = vec![[0.0f32; 2]; n];
        assert_eq!(spherical::triangle_inverse_slice(v, p, &bb, &mut inv_t), n);
        assert_eq!(
            spherical::rectangle_inverse_slice(c, ex, ey, rp, &ss, &mut inv_r),
            n
        );
        for k in 0..n {
            let (b, d) = spherical::triangle(v, p, uu[k]);
            assert_eq!(bits([b[0], b[1], b[2], d]), bits(out4[k]));
            assert_eq!(
                bits(spherical::triangle_inverse(v, p, bb[k])),
                bits(inv_t[k])
            );
            let (st, d) = spherical::rectangle(c, ex, ey, rp, uu[k]);
            assert_eq!(bits([st[0], st[1], d]), bits(out3[k]));
            assert_eq!(
                bits(spherical::rectangle_inverse(c, ex, ey, rp, ss[k])),
                bits(inv_r[k])
            );
        }
        assert_eq!(out4[n], [0.0; 4], "untouched beyond the common length");
    }
}
