//! Lights by solid angle: accuracy of the solid angle and of the density against f64,
//! round trips, chi-square uniformity in solid angle, compact strata, totality on stiff and
//! non-finite input, and bit identity across widths.
#![cfg(feature = "spherical")]
#![allow(clippy::needless_range_loop)]

use warpcore_testkit as common;

use common::textbook::{add, cross, dot, scale, sub};
use common::{chi2, rng, specials, unit2};
use rand::RngExt;
use rand_xoshiro::Xoshiro256PlusPlus;
use warpcore::spherical;
use warpcore::{f32x8, f32x16};

type V3 = [f64; 3];

fn d3(v: [f32; 3]) -> V3 {
    [v[0] as f64, v[1] as f64, v[2] as f64]
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

/// A triangle's shape condition `s = l_max^2 / |e1 x e2|` (1.15 for an equilateral
/// triangle, large for slivers) and its longest edge `l_max`.
fn tri_shape(v: [[f32; 3]; 3]) -> (f64, f64) {
    let (e1, e2) = (sub(d3(v[1]), d3(v[0])), sub(d3(v[2]), d3(v[0])));
    let l2 = dot(e1, e1)
        .max(dot(e2, e2))
        .max(dot(sub(e2, e1), sub(e2, e1)));
    (l2 / norm(cross(e1, e2)), l2.sqrt())
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
            return scale(v, 1.0 / n);
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
    let p = scale(dir(r), offset * r.random::<f64>());
    let centre = add(p, scale(dir(r), dist));
    let v: [[f32; 3]; 3] =
        std::array::from_fn(|_| f3(add(centre, scale(dir(r), size * (0.2 + r.random::<f64>())))));
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
    let p = scale(dir(r), offset * r.random::<f64>());
    let centre = add(p, scale(dir(r), dist));
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
    let corner = sub(centre, scale(add(ex, ey), 0.5));
    (f3(corner), f3(ex), f3(ey), f3(p))
}

/// Barycentrics in the closed simplex: each in `[0, 1]`, their sum within 3e-7 of 1.
fn assert_barycentric(b: [f32; 3], context: impl Fn() -> String) {
    assert!(
        b.iter().all(|x| (0.0..=1.0).contains(x)),
        "{}: {b:?}",
        context()
    );
    let s = b[0] as f64 + b[1] as f64 + b[2] as f64;
    assert!((s - 1.0).abs() <= 3e-7, "{}: sum {s}", context());
}

fn assert_total_tri(v: [[f32; 3]; 3], p: [f32; 3], u: [f32; 2]) {
    let (b, pdf) = spherical::triangle(v, p, u);
    assert_barycentric(b, || format!("{v:?} {p:?} {u:?}"));
    assert!(
        (0.0..f32::MAX).contains(&pdf),
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
        (0.0..f32::MAX).contains(&pdf),
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

/// Slivers: the edges are rounded to `f32` from the caller's vertices, so a thin triangle's
/// solid angle is only as accurate as its shape, and the error grows with the shape's
/// condition `s = l_max^2 / |e1 x e2|` (longest edge squared over twice the area; 1.15 for an
/// equilateral triangle) as it does with `kappa`. 20 000 slivers (width 1e-5 to 1e-1 of their
/// length, any orientation, 1e-3 to 1e3 away) against f64, where `kappa s <= 1e5` (beyond,
/// `ulp kappa s` nears 1 and the shape is lost to the input's rounding): solid angle and
/// density within `5e-7 kappa s` relative (measured `8.2e-8`).
#[test]
fn slivers_within_kappa_times_shape() {
    let mut r = rng(43);
    let (mut worst, mut count) = (0.0f64, 0usize);
    for _ in 0..20_000 {
        let dist = 10f64.powf(-3.0 + 6.0 * r.random::<f64>());
        let size = dist * 10f64.powf(-3.0 + 4.0 * r.random::<f64>());
        let thin = 10f64.powf(-5.0 + 4.0 * r.random::<f64>());
        let p = scale(dir(&mut r), dist * r.random::<f64>());
        let centre = add(p, scale(dir(&mut r), dist));
        let (a, b) = (dir(&mut r), dir(&mut r));
        let along = size * (2.0 * r.random::<f64>() - 1.0);
        let v = [
            f3(add(centre, scale(a, size))),
            f3(add(centre, scale(a, -size))),
            f3(add(centre, add(scale(b, size * thin), scale(a, along)))),
        ];
        let p = f3(p);
        let om = tri_omega(v, p);
        let ks = tri_kappa(v, p) * tri_shape(v).0;
        if !(om > 1e-8 && om < 6.2 && ks <= 1e5) {
            continue;
        }
        count += 1;
        let o = spherical::triangle_solid_angle(v, p) as f64;
        let (_, pdf) = spherical::triangle(v, p, unit2(&mut r));
        worst = worst.max((o / om - 1.0).abs() / ks);
        worst = worst.max((pdf as f64 * om - 1.0).abs() / ks);
    }
    eprintln!("slivers: solid angle and density within {worst:.2e} kappa s ({count} lights)");
    assert!(
        worst < 5e-7 && count > 10_000,
        "{worst:.2e} kappa s over {count}"
    );
}

/// Near a vertex the `f32` barycentrics, not the map, limit the round trip: they place the
/// point on the light to about an ulp of the light's size, which seen from `p` at a distance
/// `q` times the longest edge from a vertex is an angle `ulp / q`. 20 000 lights of `1e-4 ..
/// 2` sr with `p` at `q = 1e-6 .. 1` (relative) from `v0`, `u1 >= 0.01`: the round trip within
/// `1e-6 kappa s / q` (measured about `3e-7`).
#[test]
fn round_trip_near_a_vertex() {
    let mut r = rng(47);
    let (mut worst, mut count) = (0.0f64, 0usize);
    for _ in 0..20_000 {
        let size = 10f64.powf(-3.0 + 6.0 * r.random::<f64>());
        let q = 10f64.powf(-6.0 * r.random::<f64>());
        let v0 = scale(dir(&mut r), size * r.random::<f64>());
        let v = [
            f3(v0),
            f3(add(v0, scale(dir(&mut r), size))),
            f3(add(v0, scale(dir(&mut r), size))),
        ];
        let p = f3(add(d3(v[0]), scale(dir(&mut r), q * size)));
        let om = tri_omega(v, p);
        let (shape, longest) = tri_shape(v);
        let ks = tri_kappa(v, p) * shape;
        let qv = norm(sub(d3(p), d3(v[0]))) / longest;
        let u = unit2(&mut r);
        if !((1e-4..=2.0).contains(&om) && u[1] >= 0.01 && ks.is_finite() && qv > 0.0) {
            continue;
        }
        count += 1;
        let (b, _) = spherical::triangle(v, p, u);
        let w = spherical::triangle_inverse(v, p, b);
        let e = (w[0] - u[0]).abs().max((w[1] - u[1]).abs()) as f64;
        worst = worst.max(e * qv.min(1.0) / ks);
    }
    eprintln!("near a vertex: round trip within {worst:.2e} kappa s / q ({count} lights)");
    assert!(
        worst < 1e-6 && count > 5_000,
        "{worst:.2e} kappa s / q over {count}"
    );
}

/// The f64 solid angle of `[x0, x0 + w] x [y0, y0 + h]` at height `z` above the origin's
/// plane, cut at the origin's foot (each piece on one side of it in both directions, so no
/// denominator of Van Oosterom-Strackee cancels, even in f64).
fn strip64(x0: f64, w: f64, y0: f64, h: f64, z: f64) -> f64 {
    let cut = |a: f64, l: f64| {
        if a < 0.0 && 0.0 < a + l {
            vec![(a, -a), (0.0, a + l)]
        } else {
            vec![(a, l)]
        }
    };
    let mut total = 0.0;
    for &(xa, wa) in &cut(x0, w) {
        for &(ya, ha) in &cut(y0, h) {
            let (a, ex, ey) = ([xa, ya, z], [wa, 0.0, 0.0], [0.0, ha, 0.0]);
            total += vos(a, ex, add(ex, ey)) + vos(a, add(ex, ey), ey);
        }
    }
    total
}

/// Long lights seen from beside their middle (the shading point's foot inside the light's
/// extent, both ends 3 to 3000 times its distance away, sides up to 10^6 : 1, either side
/// the long one): two corners are seen nearly opposite, where one pair of Van
/// Oosterom-Strackee triangles cancels. Before the rectangle was cut at the foot, these
/// lights' density erred up to `8.7e-5 kappa` and the map's `s` missed its strip's solid
/// angle by up to 0.99 in `u0` (`u0` near 1 at `s = 0`); cut, `3.0e-7 kappa` and `1.9e-4`
/// (one Newton step from the closed form, the longest lights). 20 000 lights against f64.
#[test]
fn long_lights_seen_from_beside() {
    let mut r = rng(41);
    let (mut density, mut map) = (0.0f64, 0.0f64);
    for _ in 0..20_000 {
        let len = 10f64.powf(0.5 + 3.0 * r.random::<f64>());
        let y0 = 10f64.powf(-3.0 + 3.5 * r.random::<f64>())
            * if r.random::<bool>() { -1.0 } else { 1.0 };
        let h = 10f64.powf(-3.0 + 3.0 * r.random::<f64>()) * y0.abs().max(0.1);
        let x0 = -len * r.random::<f64>();
        // Half the lights along `ey` (the cut then runs across `ey`): the light's own frame.
        let (lx0, lw, ly0, lh) = if r.random::<bool>() {
            (y0, h, x0, len)
        } else {
            (x0, len, y0, h)
        };
        let (lx0, lw, ly0, lh) = (lx0 as f32, lw as f32, ly0 as f32, lh as f32);
        let (c, ex, ey, p) = (
            [lx0, ly0, 1.0f32],
            [lw, 0.0, 0.0],
            [0.0, lh, 0.0],
            [0.0f32; 3],
        );
        let (lx0, lw, ly0, lh) = (lx0 as f64, lw as f64, ly0 as f64, lh as f64);
        let om = strip64(lx0, lw, ly0, lh, 1.0);
        let kappa = rect_kappa(c, ex, ey, p);
        let o = spherical::rectangle_solid_angle(c, ex, ey, p) as f64;
        density = density.max((o / om - 1.0).abs() / kappa);
        let u = unit2(&mut r);
        let ([s, _], pdf) = spherical::rectangle(c, ex, ey, p, u);
        density = density.max((pdf as f64 * om - 1.0).abs() / kappa);
        // `u0` is the fraction of the solid angle in the strip `[0, s] x [0, 1]`.
        let frac = strip64(lx0, s as f64 * lw, ly0, lh, 1.0) / om;
        map = map.max((frac - u[0] as f64).abs());
    }
    eprintln!("long lights: density {density:.2e} kappa, map {map:.2e} in u0");
    assert!(density < 1e-6, "density {density:.2e} kappa");
    assert!(map < 1e-3, "the map misses u0 by {map:.2e}");
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
        let at = |b1: f64, b2: f64| add(v0, add(scale(sub(v1, v0), b1), scale(sub(v2, v0), b2)));
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
                        scale(ex64, i as f64 / n as f64),
                        scale(ey64, j as f64 / n as f64),
                    ),
                );
                let (a, ux, uy) = (
                    sub(corner, d3(p)),
                    scale(ex64, 1.0 / n as f64),
                    scale(ey64, 1.0 / n as f64),
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

fn bits<const N: usize>(a: [f32; N]) -> [u32; N] {
    a.map(f32::to_bits)
}

/// A result's bits: the scalar form's, or lane `j` of a wide form's.
trait Bits {
    fn lane_bits(&self, j: usize) -> Vec<u32>;
}
impl Bits for f32 {
    fn lane_bits(&self, _: usize) -> Vec<u32> {
        vec![self.to_bits()]
    }
}
impl Bits for f32x8 {
    fn lane_bits(&self, j: usize) -> Vec<u32> {
        vec![self.to_array()[j].to_bits()]
    }
}
impl Bits for f32x16 {
    fn lane_bits(&self, j: usize) -> Vec<u32> {
        vec![self.to_array()[j].to_bits()]
    }
}
impl<T: Bits, const N: usize> Bits for [T; N] {
    fn lane_bits(&self, j: usize) -> Vec<u32> {
        self.iter().flat_map(|x| x.lane_bits(j)).collect()
    }
}
impl<A: Bits, B: Bits> Bits for (A, B) {
    fn lane_bits(&self, j: usize) -> Vec<u32> {
        [self.0.lane_bits(j), self.1.lane_bits(j)].concat()
    }
}

/// `scalar(j)` equals lane `j` of `x16` for the 16 lanes, and of `x8` for the first 8.
fn assert_lanes(scalar: impl Fn(usize) -> Box<dyn Bits>, x8: &dyn Bits, x16: &dyn Bits) {
    for j in 0..16 {
        let s = scalar(j).lane_bits(0);
        assert_eq!(s, x16.lane_bits(j), "x16 lane {j}");
        if j < 8 {
            assert_eq!(s, x8.lane_bits(j), "x8 lane {j}");
        }
    }
}

/// The first 8 and all 16 of `rows` as 8- and 16-lane structure of arrays.
fn soa<const N: usize>(rows: &[[f32; N]]) -> ([f32x8; N], [f32x16; N]) {
    (
        std::array::from_fn(|k| f32x8::new(std::array::from_fn(|j| rows[j][k]))),
        std::array::from_fn(|k| f32x16::new(std::array::from_fn(|j| rows[j][k]))),
    )
}

/// [`soa`] of each of `K` vectors (a light's vertices or corner and edges).
type Wide<const K: usize> = ([[f32x8; 3]; K], [[f32x16; 3]; K]);
fn soa_k<const K: usize>(rows: &[[[f32; 3]; K]]) -> Wide<K> {
    let parts: [_; K] =
        std::array::from_fn(|i| soa(&rows.iter().map(|r| r[i]).collect::<Vec<_>>()));
    (parts.map(|p| p.0), parts.map(|p| p.1))
}

/// Lane `j`'s `u` in round `round`: every third a stiff one, else random; and a light's size
/// and distance (`1e-3 .. 1e3`).
fn lane_u_and_scale(
    r: &mut Xoshiro256PlusPlus,
    us: &[[f32; 2]],
    round: usize,
    j: usize,
) -> ([f32; 2], f64, f64) {
    let u = if j.is_multiple_of(3) {
        us[(round * 16 + j) % us.len()]
    } else {
        unit2(r)
    };
    let dist = 10f64.powf(-3.0 + 6.0 * r.random::<f64>());
    let size = dist * r.random::<f64>();
    (u, size, dist)
}

/// The `u` of round `round`'s slice check (lengths around the lane widths; every fifth a
/// stiff one).
fn slice_us(r: &mut Xoshiro256PlusPlus, us: &[[f32; 2]], round: usize) -> Vec<[f32; 2]> {
    let len = [0usize, 1, 7, 8, 9, 15, 16, 17, 33][round % 9];
    (0..len)
        .map(|k| {
            if k.is_multiple_of(5) {
                us[(round + k) % us.len()]
            } else {
                unit2(r)
            }
        })
        .collect()
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
        // Every lane its own light: every fourth a stiff one.
        let (tv, rv): (Vec<_>, Vec<_>) = (0..16)
            .map(|j| {
                let (u, size, dist) = lane_u_and_scale(&mut r, &us, round, j);
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
                ((v, p, u), (rc, u))
            })
            .unzip();
        // Triangles.
        let (v8, v16) = soa_k(&tv.iter().map(|t| t.0).collect::<Vec<_>>());
        let ([p8], [p16]) = soa_k(&tv.iter().map(|t| [t.1]).collect::<Vec<_>>());
        let (u8_, u16_) = soa(&tv.iter().map(|t| t.2).collect::<Vec<_>>());
        let s8 = spherical::triangle_x8(v8, p8, u8_);
        let s16 = spherical::triangle_x16(v16, p16, u16_);
        let scalar = |j: usize| spherical::triangle(tv[j].0, tv[j].1, tv[j].2);
        assert_lanes(|j| Box::new(scalar(j)), &s8, &s16);
        assert_lanes(
            |j| Box::new(spherical::triangle_inverse(tv[j].0, tv[j].1, scalar(j).0)),
            &spherical::triangle_inverse_x8(v8, p8, s8.0),
            &spherical::triangle_inverse_x16(v16, p16, s16.0),
        );
        assert_lanes(
            |j| Box::new(spherical::triangle_solid_angle(tv[j].0, tv[j].1)),
            &spherical::triangle_solid_angle_x8(v8, p8),
            &spherical::triangle_solid_angle_x16(v16, p16),
        );
        // Rectangles.
        let (a8, a16) = soa_k(
            &rv.iter()
                .map(|((c, ex, ey, p), _)| [*c, *ex, *ey, *p])
                .collect::<Vec<_>>(),
        );
        let (ru8, ru16) = soa(&rv.iter().map(|t| t.1).collect::<Vec<_>>());
        let s8 = spherical::rectangle_x8(a8[0], a8[1], a8[2], a8[3], ru8);
        let s16 = spherical::rectangle_x16(a16[0], a16[1], a16[2], a16[3], ru16);
        let scalar = |j: usize| {
            let ((c, ex, ey, p), u) = rv[j];
            spherical::rectangle(c, ex, ey, p, u)
        };
        assert_lanes(|j| Box::new(scalar(j)), &s8, &s16);
        assert_lanes(
            |j| {
                let ((c, ex, ey, p), _) = rv[j];
                Box::new(spherical::rectangle_inverse(c, ex, ey, p, scalar(j).0))
            },
            &spherical::rectangle_inverse_x8(a8[0], a8[1], a8[2], a8[3], s8.0),
            &spherical::rectangle_inverse_x16(a16[0], a16[1], a16[2], a16[3], s16.0),
        );
        assert_lanes(
            |j| {
                let ((c, ex, ey, p), _) = rv[j];
                Box::new(spherical::rectangle_solid_angle(c, ex, ey, p))
            },
            &spherical::rectangle_solid_angle_x8(a8[0], a8[1], a8[2], a8[3]),
            &spherical::rectangle_solid_angle_x16(a16[0], a16[1], a16[2], a16[3]),
        );
        // Slices: one light, many u (lengths around the lane widths).
        let (v, p, _) = tv[round % 16];
        let ((c, ex, ey, rp), _) = rv[round % 16];
        let uu = slice_us(&mut r, &us, round);
        let n = uu.len();
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

// ----------------------------------------------------------------------------------------
// The cosine-aware variant (issue 22 item 3): the bilinear warp by the receiver's clamped
// cosine at the light's corners, then the spherical map.

/// `max(0, n . d) / (|n| |d|)` in f64.
fn cos64(n: [f32; 3], d: V3) -> f64 {
    let n = d3(n);
    (dot(n, d) / (norm(n) * norm(d))).max(0.0)
}

/// The weights of the square's corners `(0,0), (1,0), (0,1), (1,1)`, in f64: the triangle's
/// `v1, v1, v0, v2` (Arvo's apex is the side `u1 = 0`), the rectangle's four corners.
fn tri_weights(v: [[f32; 3]; 3], p: [f32; 3], n: [f32; 3]) -> [f64; 4] {
    let c = |i: usize| cos64(n, sub(d3(v[i]), d3(p)));
    [c(1), c(1), c(0), c(2)]
}
fn rect_weights(c: [f32; 3], ex: [f32; 3], ey: [f32; 3], p: [f32; 3], n: [f32; 3]) -> [f64; 4] {
    let o = sub(d3(c), d3(p));
    let (x, y) = (d3(ex), d3(ey));
    [o, add(o, x), add(o, y), add(add(o, x), y)].map(|d| cos64(n, d))
}

/// The normalised bilinear density in f64 (written from its definition).
fn bilinear64(p: [f64; 2], w: [f64; 4]) -> f64 {
    let [x, y] = p;
    let s = w[0] + w[1] + w[2] + w[3];
    4.0 * ((1.0 - x) * (1.0 - y) * w[0]
        + x * (1.0 - y) * w[1]
        + (1.0 - x) * y * w[2]
        + x * y * w[3])
        / s
}

/// The crate's rule for `u`: NaN and negatives to 0, `>= 1` to `1 - 2^-24`.
fn unit_clamp(a: f32) -> f32 {
    if a > 0.0 {
        a.min(common::ONE_MINUS_EPS)
    } else {
        0.0
    }
}

/// `spherical::bilinear` inverts the CDFs of its marginal and conditional (checked in f64
/// against their closed forms, `F(x) = (2 a x + (b - a) x^2) / (a + b)`), and its density is
/// the bilinear one; all-zero, NaN and infinite weights leave `u` alone with density 1.
#[test]
fn bilinear_warp_inverts_its_cdfs() {
    let mut r = rng(21);
    let cdf = |x: f64, a: f64, b: f64| (2.0 * a * x + (b - a) * x * x) / (a + b);
    for k in 0..100_000 {
        let mut w: [f32; 4] = std::array::from_fn(|_| r.random::<f32>());
        if k % 4 == 0 {
            w[k / 4 % 4] = 0.0;
        }
        if k % 8 == 1 {
            w[(k / 8) % 4] = 0.0;
            w[(k / 8 + 1) % 4] = 0.0;
        }
        let u = unit2(&mut r);
        let ([x, y], pdf) = spherical::bilinear(u, w);
        assert!(
            (0.0..1.0).contains(&x) && (0.0..1.0).contains(&y),
            "{u:?} {w:?}"
        );
        let wd = w.map(|x| x as f64);
        let (x, y) = (x as f64, y as f64);
        let fy = cdf(y, wd[0] + wd[1], wd[2] + wd[3]);
        assert!((fy - u[1] as f64).abs() < 2e-6, "{u:?} {w:?}: F(y) = {fy}");
        let (a, b) = ((1.0 - y) * wd[0] + y * wd[2], (1.0 - y) * wd[1] + y * wd[3]);
        let fx = cdf(x, a, b);
        assert!((fx - u[0] as f64).abs() < 2e-6, "{u:?} {w:?}: F(x) = {fx}");
        let want = bilinear64([x, y], wd);
        assert!(
            (pdf as f64 - want).abs() < 2e-6 * want.max(1.0),
            "{pdf} {want}"
        );
        assert_eq!(
            spherical::bilinear_pdf([x as f32, y as f32], w).to_bits(),
            pdf.to_bits()
        );
    }
    for w in [
        [0.0f32; 4],
        [f32::NAN, 1.0, 1.0, 1.0],
        [f32::INFINITY, 0.0, 0.0, 0.0],
        [-1.0, -2.0, 0.0, -0.0],
        [f32::MAX, f32::MAX, 0.0, 0.0],
    ] {
        for &a in &specials() {
            let u = [a, 0.3];
            let (v, pdf) = spherical::bilinear(u, w);
            let nan_w = w.iter().any(|x| x.is_nan());
            if !nan_w {
                assert_eq!(pdf, 1.0, "{w:?}");
                assert_eq!(bits(v), bits([unit_clamp(a), 0.3]), "{w:?} {u:?}");
            }
            assert!(v.iter().all(|x| (0.0..1.0).contains(x)) && pdf.is_finite() && pdf >= 0.0);
        }
    }
}

/// Polygon clipped to the receiver's upper half-space `n . x >= 0` (relative to `p`), and
/// the cosine-weighted solid angle `int max(0, n . w) dw` of the clipped polygon by
/// Lambert's formula `1/2 |sum_i angle(a_i, a_i+1) n . unit(a_i x a_i+1)|`.
fn projected_solid_angle(poly: &[V3], n: V3) -> f64 {
    let n = scale(n, 1.0 / norm(n));
    let mut clipped = vec![];
    for i in 0..poly.len() {
        let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
        let (da, db) = (dot(n, a), dot(n, b));
        if da >= 0.0 {
            clipped.push(a);
        }
        if (da >= 0.0) != (db >= 0.0) {
            clipped.push(add(a, scale(sub(b, a), da / (da - db))));
        }
    }
    let mut s = 0.0;
    for i in 0..clipped.len() {
        let (a, b) = (clipped[i], clipped[(i + 1) % clipped.len()]);
        let c = cross(a, b);
        let cl = norm(c);
        if cl > 0.0 {
            s += cl.atan2(dot(a, b)) * dot(n, c) / cl;
        }
    }
    0.5 * s.abs()
}

/// The estimator `max(0, n . w) / pdf` of the cosine-aware maps is unbiased for the
/// cosine-weighted solid angle (Lambert's formula on the light clipped to the receiver's
/// horizon): lights facing the receiver obliquely, one straddling its horizon, 2^20 random
/// samples each; |mean - exact| below 5 standard errors (two-sided 5.7e-7 per test, far
/// below 1% over the 8 cases).
#[test]
fn cosine_estimator_is_unbiased() {
    let n_up = [0.3f32, -0.2, 1.0];
    type TriCase = ([[f32; 3]; 3], [f32; 3], [f32; 3]);
    type RectNCase = ([f32; 3], [f32; 3], [f32; 3], [f32; 3], [f32; 3]);
    let tri: [TriCase; 4] = [
        (
            [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]],
            [0.1, 0.1, 0.0],
            n_up,
        ),
        (
            [[-2.0, -1.0, 0.3], [3.0, -1.0, 0.4], [0.0, 3.0, 0.2]],
            [0.0; 3],
            [0.0, 0.0, 1.0],
        ),
        (
            [[-2.0, -1.0, 0.3], [3.0, -1.0, 0.4], [0.0, 3.0, 0.2]],
            [0.0; 3],
            [0.7, 0.1, 0.2],
        ),
        // Straddling the horizon: v0 below it.
        (
            [[-1.0, 0.0, 0.5], [1.0, 0.5, 1.0], [0.5, 1.0, 2.0]],
            [0.0; 3],
            [1.0, 0.0, 0.2],
        ),
    ];
    let rects: [RectNCase; 4] = [
        (
            [-0.5, -0.5, 1.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.2, 0.1, 0.0],
            n_up,
        ),
        (
            [-2.0, -2.0, 0.25],
            [4.0, 0.0, 0.0],
            [0.0, 4.0, 0.0],
            [0.0; 3],
            [0.0, 0.0, 1.0],
        ),
        (
            [-2.0, -0.125, 0.5],
            [4.0, 0.0, 0.0],
            [0.0, 0.25, 0.0],
            [0.3, 0.0, 0.0],
            [-0.5, 0.3, 1.0],
        ),
        (
            [-1.0, -1.0, 0.5],
            [2.0, 0.0, 0.0],
            [0.0, 2.0, 0.0],
            [0.0; 3],
            [1.0, 0.0, 0.3],
        ),
    ];
    let n_samples = 1 << 20;
    let check =
        |name: &str, exact: f64, mut f: Box<dyn FnMut([f32; 2]) -> (V3, f64)>, n: [f32; 3]| {
            let mut r = rng(33);
            let (mut s, mut s2) = (0.0, 0.0);
            for _ in 0..n_samples {
                let (d, pdf) = f(unit2(&mut r));
                let e = if pdf > 0.0 { cos64(n, d) / pdf } else { 0.0 };
                s += e;
                s2 += e * e;
            }
            let m = s / n_samples as f64;
            let se = ((s2 / n_samples as f64 - m * m) / n_samples as f64).sqrt();
            let z = (m - exact) / se;
            println!("{name}: exact {exact:.6}, estimate {m:.6}, z = {z:+.2}");
            assert!(z.abs() < 5.0, "{name}: z = {z}");
        };
    for (i, (v, p, n)) in tri.into_iter().enumerate() {
        let poly: Vec<V3> = v.iter().map(|&x| sub(d3(x), d3(p))).collect();
        let exact = projected_solid_angle(&poly, d3(n));
        check(
            &format!("triangle {i}"),
            exact,
            Box::new(move |u| {
                let (b, pdf) = spherical::triangle_cosine(v, p, n, u);
                let x = (0..3).fold([0.0; 3], |acc, k| add(acc, scale(d3(v[k]), b[k] as f64)));
                (sub(x, d3(p)), pdf as f64)
            }),
            n,
        );
    }
    for (i, (c, ex, ey, p, n)) in rects.into_iter().enumerate() {
        let o = sub(d3(c), d3(p));
        let poly = vec![
            o,
            add(o, d3(ex)),
            add(add(o, d3(ex)), d3(ey)),
            add(o, d3(ey)),
        ];
        let exact = projected_solid_angle(&poly, d3(n));
        check(
            &format!("rectangle {i}"),
            exact,
            Box::new(move |u| {
                let ([s, t], pdf) = spherical::rectangle_cosine(c, ex, ey, p, n, u);
                let x = add(o, add(scale(d3(ex), s as f64), scale(d3(ey), t as f64)));
                (x, pdf as f64)
            }),
            n,
        );
    }
}

/// The density is `bilinear_pdf(u') / omega` with `u'` the warped sample (recovered through
/// the inverse maps) and the weights the receiver's cosines computed here in f64; and the
/// warped samples follow the bilinear density (chi-square over an 8 x 8 grid of the square,
/// expected probabilities from the f64 bilinear density, 2^21 samples per light).
#[test]
fn cosine_density_and_chi2() {
    let mut r = rng(41);
    // Density identity over random lights and normals facing them.
    for _ in 0..20_000 {
        let (v, p) = random_triangle(&mut r, 1.0, 1.5, 1.0);
        let centre = scale(add(add(d3(v[0]), d3(v[1])), d3(v[2])), 1.0 / 3.0);
        let n = f3(add(
            sub(centre, d3(p)),
            scale(dir(&mut r), 0.8 * norm(sub(centre, d3(p)))),
        ));
        let u = unit2(&mut r);
        let (b, pdf) = spherical::triangle_cosine(v, p, n, u);
        let w = tri_weights(v, p, n);
        let uw = spherical::triangle_inverse(v, p, b);
        let want = bilinear64([uw[0] as f64, uw[1] as f64], w) / tri_omega(v, p);
        if tri_kappa(v, p) < 100.0 && uw[1] > 0.01 {
            assert!(
                (pdf as f64 - want).abs() <= 1e-3 * 4.0 / tri_omega(v, p),
                "{v:?} {p:?} {n:?} {u:?}: {pdf} vs {want}"
            );
        }
        let (c, ex, ey, p) = random_rect(&mut r, 1.0, 1.5, 1.0);
        let centre = add(d3(c), scale(add(d3(ex), d3(ey)), 0.5));
        let n = f3(add(
            sub(centre, d3(p)),
            scale(dir(&mut r), 0.8 * norm(sub(centre, d3(p)))),
        ));
        let (st, pdf) = spherical::rectangle_cosine(c, ex, ey, p, n, u);
        let w = rect_weights(c, ex, ey, p, n);
        let uw = spherical::rectangle_inverse(c, ex, ey, p, st);
        let want = bilinear64([uw[0] as f64, uw[1] as f64], w) / rect_omega(c, ex, ey, p);
        if rect_kappa(c, ex, ey, p) < 100.0 {
            assert!(
                (pdf as f64 - want).abs() <= 1e-3 * 4.0 / rect_omega(c, ex, ey, p),
                "{c:?} {ex:?} {ey:?} {p:?} {n:?} {u:?}: {pdf} vs {want}"
            );
        }
    }
    // Chi-square of the warped samples against the bilinear density.
    let (v, tp, tn) = (
        [[-2.0f32, -1.0, 0.3], [3.0, -1.0, 0.4], [0.0, 3.0, 0.2]],
        [0.0f32; 3],
        [0.7f32, 0.1, 0.2],
    );
    let w = tri_weights(v, tp, tn);
    let expected = chi2::expected_from_density(8, 8, |q| bilinear64(q, w));
    let mut hist = chi2::Histogram::new(8, 8);
    let mut r = rng(43);
    for _ in 0..chi2::SAMPLES {
        let (b, _) = spherical::triangle_cosine(v, tp, tn, unit2(&mut r));
        let u = spherical::triangle_inverse(v, tp, b);
        hist.add([u[0] as f64, u[1] as f64]);
    }
    chi2::check("triangle_cosine", &hist, &expected);
    let (c, ex, ey, rp, rn) = (
        [-2.0f32, -0.125, 0.5],
        [4.0f32, 0.0, 0.0],
        [0.0f32, 0.25, 0.0],
        [0.3f32, 0.0, 0.0],
        [-0.5f32, 0.3, 1.0],
    );
    let w = rect_weights(c, ex, ey, rp, rn);
    let expected = chi2::expected_from_density(8, 8, |q| bilinear64(q, w));
    let mut hist = chi2::Histogram::new(8, 8);
    for _ in 0..chi2::SAMPLES {
        let (st, _) = spherical::rectangle_cosine(c, ex, ey, rp, rn, unit2(&mut r));
        let u = spherical::rectangle_inverse(c, ex, ey, rp, st);
        hist.add([u[0] as f64, u[1] as f64]);
    }
    chi2::check("rectangle_cosine", &hist, &expected);
}

/// Total on the stiff lights with every special `u` and hostile normals (zero, NaN, inf,
/// subnormal, huge); where every weight is 0 (normal facing away, zero, NaN) the result is the
/// plain map's, bit for bit.
#[test]
fn cosine_total_and_falls_back() {
    let normals = [
        [0.0f32, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [0.0; 3],
        [f32::NAN, 0.0, 1.0],
        [f32::INFINITY, 1.0, 0.0],
        [f32::from_bits(1), 0.0, f32::from_bits(1)],
        [f32::MAX, f32::MAX, f32::MAX],
        [1.0, -1.0, 0.5],
    ];
    let us = stiff_us();
    for (v, p) in stiff_triangles() {
        for (k, &u) in us.iter().enumerate() {
            let n = normals[k % normals.len()];
            let (b, pdf) = spherical::triangle_cosine(v, p, n, u);
            assert_barycentric(b, || format!("{v:?} {p:?} {n:?} {u:?}"));
            assert!(
                pdf.is_finite() && pdf >= 0.0,
                "{v:?} {p:?} {n:?} {u:?}: {pdf}"
            );
            if n == [0.0; 3] || n[0].is_nan() {
                let (b2, pdf2) = spherical::triangle(v, p, u);
                assert_eq!(
                    bits([b[0], b[1], b[2], pdf]),
                    bits([b2[0], b2[1], b2[2], pdf2])
                );
            }
        }
    }
    for (c, ex, ey, p) in stiff_rects() {
        for (k, &u) in us.iter().enumerate() {
            let n = normals[k % normals.len()];
            let (st, pdf) = spherical::rectangle_cosine(c, ex, ey, p, n, u);
            assert!(st.iter().all(|x| (0.0..=1.0).contains(x)), "{st:?}");
            assert!(
                pdf.is_finite() && pdf >= 0.0,
                "{c:?} {ex:?} {ey:?} {p:?} {n:?} {u:?}: {pdf}"
            );
            if n == [0.0; 3] || n[0].is_nan() {
                let (st2, pdf2) = spherical::rectangle(c, ex, ey, p, u);
                assert_eq!(bits([st[0], st[1], pdf]), bits([st2[0], st2[1], pdf2]));
            }
        }
    }
    // A light wholly behind the receiver: every weight 0, the plain map.
    let v = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let mut r = rng(47);
    for _ in 0..1000 {
        let u = unit2(&mut r);
        let (b, d) = spherical::triangle_cosine(v, [0.0; 3], [0.0, 0.0, -1.0], u);
        let (b2, d2) = spherical::triangle(v, [0.0; 3], u);
        assert_eq!(bits([b[0], b[1], b[2], d]), bits([b2[0], b2[1], b2[2], d2]));
    }
}

/// scalar == x8 == x16 == slice for the cosine-aware maps, bit for bit.
#[test]
fn cosine_widths_agree_bit_for_bit() {
    let mut r = rng(53);
    let us = stiff_us();
    for round in 0..200 {
        // Every lane its own light and normal.
        let (tv, rv): (Vec<_>, Vec<_>) = (0..16)
            .map(|j| {
                let (u, size, dist) = lane_u_and_scale(&mut r, &us, round, j);
                let n = f3(dir(&mut r));
                let (v, p) = random_triangle(&mut r, size, dist, dist);
                ((v, p, n, u), (random_rect(&mut r, size, dist, dist), n, u))
            })
            .unzip();
        let (v8, v16) = soa_k(&tv.iter().map(|t| t.0).collect::<Vec<_>>());
        let ([p8, n8], [p16, n16]) = soa_k(&tv.iter().map(|t| [t.1, t.2]).collect::<Vec<_>>());
        let (u8_, u16_) = soa(&tv.iter().map(|t| t.3).collect::<Vec<_>>());
        assert_lanes(
            |j| {
                let (v, p, n, u) = tv[j];
                Box::new(spherical::triangle_cosine(v, p, n, u))
            },
            &spherical::triangle_cosine_x8(v8, p8, n8, u8_),
            &spherical::triangle_cosine_x16(v16, p16, n16, u16_),
        );
        let lights: Vec<_> = rv
            .iter()
            .map(|((c, ex, ey, p), n, _)| [*c, *ex, *ey, *p, *n])
            .collect();
        let (a8, a16) = soa_k(&lights);
        let (ru8, ru16) = soa(&rv.iter().map(|t| t.2).collect::<Vec<_>>());
        assert_lanes(
            |j| {
                let ((c, ex, ey, p), n, u) = rv[j];
                Box::new(spherical::rectangle_cosine(c, ex, ey, p, n, u))
            },
            &spherical::rectangle_cosine_x8(a8[0], a8[1], a8[2], a8[3], a8[4], ru8),
            &spherical::rectangle_cosine_x16(a16[0], a16[1], a16[2], a16[3], a16[4], ru16),
        );
        let (v, p, n, _) = tv[round % 16];
        let ((c, ex, ey, rp), rn, _) = rv[round % 16];
        let uu = slice_us(&mut r, &us, round);
        let len = uu.len();
        let mut out4 = vec![[0.0f32; 4]; len + 1];
        assert_eq!(
            spherical::triangle_cosine_slice(v, p, n, &uu, &mut out4),
            len
        );
        let mut out3 = vec![[0.0f32; 3]; len];
        assert_eq!(
            spherical::rectangle_cosine_slice(c, ex, ey, rp, rn, &uu, &mut out3),
            len
        );
        for k in 0..len {
            let (b, d) = spherical::triangle_cosine(v, p, n, uu[k]);
            assert_eq!(bits([b[0], b[1], b[2], d]), bits(out4[k]));
            let (st, d) = spherical::rectangle_cosine(c, ex, ey, rp, rn, uu[k]);
            assert_eq!(bits([st[0], st[1], d]), bits(out3[k]));
        }
        assert_eq!(out4[len], [0.0; 4]);
    }
}

// Hostile lights found from outside: a shading point a hair above the light, subnormal
// vertex components, 1e18 dynamic range inside one light, subnormal cosine weights, very long
// and very far rectangles. Each was a wrong result before the fix it names.

/// The triangle's density when `p` lies on the light's plane by the documented rule (the
/// scaled triple product below 2^-116): 0, with an area-sampled point.
fn assert_flat_tri(v: [[f32; 3]; 3], p: [f32; 3], u: [f32; 2]) {
    assert_total_tri(v, p, u);
    let (b, pdf) = spherical::triangle(v, p, u);
    assert_eq!(pdf, 0.0, "{v:?} {p:?} {u:?}: {b:?}");
    assert_eq!(b, warpcore::triangle::uniform(u));
    let o = spherical::triangle_solid_angle(v, p);
    assert!(o == 0.0 || o == std::f32::consts::TAU, "omega {o}");
}

/// `p` a hair (`2^-20 .. 2^-60` of the light's size) above a light and inside it, where the
/// rectangle is cut at `p`'s foot into four pieces of nearly a quarter hemisphere each: their
/// solid angles, added in `f32`, rounded past `2 pi` (23 of 200 000 positions, by up to
/// three ulps; found by the `spherical` fuzz search, a light 4e-8 long with `p` 1e-26 above
/// it). The solid angle stays in `[0, 2 pi]` and the map total; the test also requires that
/// it reached the top of that range (else it tests nothing).
#[test]
fn rectangle_cut_into_four_stays_below_two_pi() {
    let mut r = rng(52);
    let mut top = 0.0f32;
    for k in 0..200_000 {
        let (a, b) = (
            0.01 + 0.98 * r.random::<f32>(),
            0.01 + 0.98 * r.random::<f32>(),
        );
        let z = 2f32.powf(-20.0 - 40.0 * r.random::<f32>());
        let (w, h) = (1.0 + 3.0 * r.random::<f32>(), 1.0 + 3.0 * r.random::<f32>());
        let (c, ex, ey) = ([-a * w, -b * h, -z], [w, 0.0, 0.0], [0.0, h, 0.0]);
        let o = spherical::rectangle_solid_angle(c, ex, ey, [0.0; 3]);
        assert!(
            (0.0..=std::f32::consts::TAU).contains(&o),
            "{c:?} {ex:?} {ey:?}: omega {o}"
        );
        top = top.max(o);
        if k % 64 == 0 {
            assert_total_rect(c, ex, ey, [0.0; 3], unit2(&mut r));
        }
    }
    assert!(top >= std::f32::consts::TAU * (1.0 - 1e-6), "largest {top}");
    // The fuzz input itself (bits as the search wrote them).
    let f = f32::from_bits;
    let (c, ex, ey, p) = (
        [f(0x8795_1cd9), f(0x0001_22f0), f(0x951c_d92e)],
        [f(0x0122_f087), f(0x333f_0000), f(0x0d19_b1a7)],
        [f(0x2998_6931), f(0x0000_00d3), f(0x96eb_1000)],
        [f(0x1ed8_0b75), f(0x2286_b57f), f(0x00fd_4895)],
    );
    assert_total_rect(c, ex, ey, p, [0.5, 0.5]);
}

/// `p` 2^-149 .. 2^-100 above a unit-sized triangle (self-intersection leaves shading points
/// there): barycentrics in the closed simplex (not [1, 1, 0] or [1, 1, 1]), density 0 where
/// the height counts as zero, else 1 / omega.
#[test]
fn triangle_p_a_hair_above_the_light() {
    let v = [[0.0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.3, 0.8, 0.0]];
    let mut r = rng(30);
    for e in 100..=149 {
        let p = [0.3f32, 0.3, 2f32.powi(-e)];
        for k in 0..2000 {
            let u = if k == 0 { [1.0, 0.999] } else { unit2(&mut r) };
            assert_total_tri(v, p, u);
            let (_, pdf) = spherical::triangle(v, p, u);
            // A height below 2^-126 counts as zero: p on the plane (density 0).
            if e > 126 {
                assert_eq!(pdf, 0.0, "h = 2^-{e}");
            } else {
                assert!(
                    (pdf * std::f32::consts::TAU - 1.0).abs() < 1e-5,
                    "h = 2^-{e}: {pdf}"
                );
            }
        }
    }
    assert_flat_tri(v, [0.3, 0.3, 1e-45], [1.0, 0.999]);
}

/// A vertex with a subnormal component: `p` is on the light's plane by the rule.
#[test]
fn triangle_subnormal_vertex_component() {
    let v = [[0.0f32, -1.0, 1e-40], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    for u in [[0.3f32, 0.6], [0.0, 0.0], [0.999, 0.5], [0.5, 0.999]] {
        assert_flat_tri(v, [0.0; 3], u);
    }
}

/// About 1e18 dynamic range inside one normal-range light (`p` on an edge, the plane
/// through `p` within 1e-31): the scaled triple product is subnormal; barycentrics in the
/// closed simplex, density finite.
#[test]
fn triangle_dynamic_range_1e18() {
    let v = [
        [0.0f32, -4096.0, 1e-31],
        [262144.0, 0.0, 0.0],
        [0.0, 1.0 / 32.0, 0.0],
    ];
    let mut r = rng(31);
    for _ in 0..1000 {
        assert_total_tri(v, [0.0; 3], unit2(&mut r));
    }
}

/// Weights whose sum is subnormal: the identity with density 1 (1 / sum overflows), here and
/// on a device that flushes subnormals alike.
#[test]
fn bilinear_subnormal_weight_sum() {
    for w in [
        [0.0f32, 0.0, 1e-40, 0.0],
        [1e-45, 1e-45, 1e-45, 1e-45],
        [f32::MIN_POSITIVE / 8.0, 0.0, f32::MIN_POSITIVE / 2.0, 0.0],
    ] {
        for u in [[0.0f32, 0.0], [0.3, 0.7], [0.999, 0.5]] {
            let (x, pdf) = spherical::bilinear(u, w);
            assert_eq!((x, pdf), (u, 1.0), "{w:?} {u:?}");
            assert_eq!(spherical::bilinear_pdf(u, w), 1.0, "{w:?} {u:?}");
        }
    }
    // The smallest normal sum is used as given.
    let w = [f32::MIN_POSITIVE, 0.0, 0.0, 0.0];
    let (_, pdf) = spherical::bilinear([0.25, 0.25], w);
    assert!(pdf.is_finite() && pdf > 1.0, "{pdf}");
}

/// Through the cosine-aware maps: lights whose only corner above the receiver's horizon is
/// there by a subnormal cosine. The density is the plain map's (finite, never FLT_MAX).
#[test]
fn cosine_maps_with_subnormal_weights() {
    let n = [0.0f32, 0.0, 1.0];
    let v = [[1e8f32, 0.0, 1e-31], [0.0, 1.0, -1.0], [0.0, -1.0, -1.0]];
    let mut r = rng(32);
    for _ in 0..200 {
        let u = unit2(&mut r);
        let (b, pdf) = spherical::triangle_cosine(v, [0.0; 3], n, u);
        let (b0, pdf0) = spherical::triangle(v, [0.0; 3], u);
        assert_eq!((b, pdf), (b0, pdf0), "{u:?}");
        assert!(pdf.is_finite() && pdf > 0.0 && pdf < 1.0, "{pdf}");
        // A rectangle whose near edge is 1e-31 above the horizon at 1e8.
        let (c, ex, ey) = (
            [1e8f32, 0.0, 1e-31],
            [0.0f32, 1.0, 0.0],
            [-1e8f32, 0.0, -1.0],
        );
        let (st, pdf) = spherical::rectangle_cosine(c, ex, ey, [0.0; 3], n, u);
        let (st0, pdf0) = spherical::rectangle(c, ex, ey, [0.0; 3], u);
        assert_eq!((st, pdf), (st0, pdf0), "{u:?}");
        assert!((0.0..f32::MAX).contains(&pdf), "{pdf}");
    }
}

/// The solid angle of `[0, 1] x [0, b]` at height 1 above its corner, f64.
fn corner_rect_omega(b: f64) -> f64 {
    (b / (2.0 + b * b).sqrt()).atan()
}

/// Very long rectangles: the strip form must not lose the half-infinite part (it underflowed
/// to 0 at 2^51 and was 18% low at 2^50), and the density is 1 / omega.
#[test]
fn rectangle_very_long() {
    for e in [20, 40, 50, 51, 60, 63] {
        let b = 2f32.powi(e);
        let (c, ex, ey, p) = (
            [0.0f32, 0.0, 1.0],
            [1.0f32, 0.0, 0.0],
            [0.0, b, 0.0],
            [0.0f32; 3],
        );
        let want = corner_rect_omega(b as f64);
        let o = spherical::rectangle_solid_angle(c, ex, ey, p) as f64;
        assert!((o / want - 1.0).abs() < 1e-5, "2^{e}: {o} {want}");
        for u in [[0.3f32, 0.6], [0.0, 0.0], [0.999, 0.999]] {
            assert_total_rect(c, ex, ey, p, u);
            let (_, pdf) = spherical::rectangle(c, ex, ey, p, u);
            assert!((pdf as f64 * want - 1.0).abs() < 1e-5, "2^{e} {u:?}: {pdf}");
        }
    }
}

/// Beyond the documented aspect (squares of the shortest length underflow in the scaled
/// frame), the rule still holds: solid angle 0 exactly where the density is 0.
#[test]
fn rectangle_too_long_is_consistent() {
    for e in [80, 100, 126] {
        let (c, ex, ey, p) = (
            [0.0f32, 0.0, 1.0],
            [1.0f32, 0.0, 0.0],
            [0.0, 2f32.powi(e), 0.0],
            [0.0f32; 3],
        );
        let o = spherical::rectangle_solid_angle(c, ex, ey, p);
        let (_, pdf) = spherical::rectangle(c, ex, ey, p, [0.3, 0.6]);
        assert_total_rect(c, ex, ey, p, [0.3, 0.6]);
        assert_eq!(o == 0.0, pdf == 0.0, "2^{e}: {o} {pdf}");
    }
}

/// Lights so far that the triple product of the scaled frame is below 2^-116: solid angle 0
/// and density 0 (it was FLT_MAX); just inside the rule, both positive and finite.
#[test]
fn rectangle_and_triangle_very_far() {
    let (ex, ey) = ([1.0f32, 0.0, 0.0], [0.0f32, 1.0, 0.0]);
    for e in [40, 60, 100, 120, 126] {
        let d = 2f32.powi(e);
        let c = [0.0f32, 0.0, d];
        let o = spherical::rectangle_solid_angle(c, ex, ey, [0.0; 3]);
        let v = [c, [1.0, 0.0, d], [0.0, 1.0, d]];
        let ot = spherical::triangle_solid_angle(v, [0.0; 3]);
        for u in [[0.3f32, 0.6], [0.0, 0.0], [0.999, 0.999]] {
            assert_total_rect(c, ex, ey, [0.0; 3], u);
            assert_total_tri(v, [0.0; 3], u);
            let (_, pdf) = spherical::rectangle(c, ex, ey, [0.0; 3], u);
            let (_, pdft) = spherical::triangle(v, [0.0; 3], u);
            // z w h and the triple product relative to the largest coordinate d: 2^-2e,
            // flat below 2^-116 (rectangle) and 2^-120 (triangle).
            let want = 1.0 / (d as f64 * d as f64);
            if 2 * e > 116 {
                assert_eq!((o, pdf), (0.0, 0.0), "2^{e}");
            } else {
                assert!((o as f64 / want - 1.0).abs() < 1e-5, "2^{e}: {o}");
                assert!((pdf as f64 * want - 1.0).abs() < 1e-4, "2^{e}: {pdf}");
            }
            if 2 * e > 120 {
                assert_eq!((ot, pdft), (0.0, 0.0), "2^{e}");
            } else {
                assert!((ot as f64 / want * 2.0 - 1.0).abs() < 1e-5, "2^{e}: {ot}");
                assert!(
                    (pdft as f64 * want / 2.0 - 1.0).abs() < 1e-4,
                    "2^{e}: {pdft}"
                );
            }
        }
    }
}

/// A far sliver sampled by area next to `p`: the area density `|q|^3 / (z w h)` must not
/// underflow in `|q|^3` (it returned 0 at `u0 = 0`, where the solid angle is positive).
#[test]
fn rectangle_sliver_area_density() {
    // p at height 2^-44 above the near end of a strip 1 long and 2^-71 wide (7.5e-9 sr).
    let (c, ex, ey, p) = (
        [0.0f32, 0.0, 2f32.powi(-44)],
        [1.0f32, 0.0, 0.0],
        [0.0f32, 2f32.powi(-71), 0.0],
        [0.0f32; 3],
    );
    let o = spherical::rectangle_solid_angle(c, ex, ey, p);
    assert!(o > 0.0 && o < spherical::AREA_FALLBACK_SR, "{o}");
    for u in [[0.0f32, 0.0], [0.0, 0.5], [1e-6, 0.5], [0.5, 0.5]] {
        assert_total_rect(c, ex, ey, p, u);
        let (st, pdf) = spherical::rectangle(c, ex, ey, p, u);
        let q = [st[0] as f64, st[1] as f64 * 2f64.powi(-71), 2f64.powi(-44)];
        let want = norm(q).powi(3) / (2f64.powi(-44) * 2f64.powi(-71));
        assert!(
            (pdf as f64 / want - 1.0).abs() < 2e-6,
            "{u:?}: {pdf} {want}"
        );
    }
}

/// A hostile coordinate: a random magnitude from `1e-20 .. 1e20` (an 1e18-range light has
/// coordinates spread over 18 decades), a subnormal, or 0, with a random sign.
fn hostile_coord(r: &mut Xoshiro256PlusPlus) -> f32 {
    let m = match r.random_range(0..8u32) {
        0 => f32::from_bits(r.random_range(1..0x0080_0000u32)), // subnormal
        1 => 0.0,
        2 => 1e-40,
        _ => 10f64.powf(-20.0 + 40.0 * r.random::<f64>()) as f32,
    };
    if r.random::<bool>() { -m } else { m }
}

/// Hostile lights: `p` a hair (2^-149 .. 2^-100) above or below an axis-aligned light's
/// plane (inside or outside it), vertex components with subnormal lifts, and 1e18 dynamic
/// ranges inside one light; each map in the closed simplex / square, the sum within 3e-7,
/// the density finite, >= 0 and below FLT_MAX, also for the cosine-aware maps.
#[test]
fn total_on_hostile_lights() {
    let mut r = rng(36);
    let perm = |v: [f32; 3], k: usize| [v[k % 3], v[(k + 1) % 3], v[(k + 2) % 3]];
    for i in 0..40_000 {
        let axis = r.random_range(0..3usize);
        let (v, p, (c, ex, ey, rp)): ([[f32; 3]; 3], [f32; 3], RectCase) = match i % 3 {
            0 => {
                // A hair above the plane z = z0 (exactly representable heights).
                let z0 = [0.0f32, 1.0, -3.0][r.random_range(0..3usize)];
                let h = 2f32.powi(-r.random_range(100..=149i32));
                let h = if r.random::<bool>() { h } else { -h };
                let s = 10f32.powi(r.random_range(-3..=3i32));
                let xy = |r: &mut Xoshiro256PlusPlus| {
                    [
                        s * (2.0 * r.random::<f32>() - 1.0),
                        s * (2.0 * r.random::<f32>() - 1.0),
                    ]
                };
                let v: [[f32; 3]; 3] = std::array::from_fn(|_| {
                    let [x, y] = xy(&mut r);
                    perm([x, y, z0], axis)
                });
                let [x, y] = xy(&mut r);
                let p = perm([x, y, z0 + h], axis);
                let [cx, cy] = xy(&mut r);
                let c = perm([cx, cy, z0], axis);
                let ex = perm([s * r.random::<f32>(), 0.0, 0.0], axis);
                let ey = perm([0.0, s * r.random::<f32>(), 0.0], axis);
                (v, p, (c, ex, ey, p))
            }
            1 => {
                // Subnormal lifts: a unit light with one or two subnormal components.
                let mut v = [[0.0f32, -1.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
                let mut p = [0.0f32; 3];
                if r.random::<bool>() {
                    v = v.map(|q| [q[0], q[1], 0.0]);
                }
                for _ in 0..r.random_range(1..=2) {
                    let k = r.random_range(0..12usize);
                    let x = f32::from_bits(r.random_range(1..0x0080_0000u32));
                    if k < 9 {
                        v[k / 3][k % 3] = x
                    } else {
                        p[k - 9] = x
                    }
                }
                let mut rc = [
                    [-0.5f32, -0.5, 0.0],
                    [1.0, 0.0, 0.0],
                    [0.0, 1.0, 0.0],
                    [0.0; 3],
                ];
                let k = r.random_range(0..12usize);
                rc[k / 3][k % 3] = f32::from_bits(r.random_range(1..0x0080_0000u32));
                (v, p, (rc[0], rc[1], rc[2], rc[3]))
            }
            _ => {
                // 1e18 (and wider) dynamic range inside one light.
                let v: [[f32; 3]; 3] =
                    std::array::from_fn(|_| std::array::from_fn(|_| hostile_coord(&mut r)));
                let c: [f32; 3] = std::array::from_fn(|_| hostile_coord(&mut r));
                let (a, b) = (hostile_coord(&mut r), hostile_coord(&mut r));
                let (ex, ey) = (perm([a, 0.0, 0.0], axis), perm([0.0, b, 0.0], axis));
                (v, [0.0; 3], (c, ex, ey, [0.0; 3]))
            }
        };
        let n = [hostile_coord(&mut r), hostile_coord(&mut r), 1.0];
        for _ in 0..4 {
            let u = unit2(&mut r);
            assert_total_tri(v, p, u);
            assert_total_rect(c, ex, ey, rp, u);
            let (b, pdf) = spherical::triangle_cosine(v, p, n, u);
            let s = b[0] as f64 + b[1] as f64 + b[2] as f64;
            assert!(
                b.iter().all(|x| (0.0..=1.0).contains(x)) && (s - 1.0).abs() <= 3e-7,
                "{v:?} {p:?} {n:?} {u:?}: {b:?}"
            );
            assert!((0.0..f32::MAX).contains(&pdf), "{v:?} {p:?} {n:?}: {pdf}");
            let (st, pdf) = spherical::rectangle_cosine(c, ex, ey, rp, n, u);
            assert!(st.iter().all(|x| (0.0..=1.0).contains(x)), "{st:?}");
            assert!(
                (0.0..f32::MAX).contains(&pdf),
                "{c:?} {ex:?} {ey:?} {rp:?} {n:?}: {pdf}"
            );
        }
    }
}

// ---- Sphere lights: `spherical::cone` -------------------------------------------------------

/// The f64 solid angle of the sphere (`c`, `r`) at `p` (on the same f32 input):
/// `2 pi s^2 / (1 + sqrt(1 - s^2))`, `s = r / |c - p|`; `4 pi` inside.
fn cone_omega(c: [f32; 3], r: f32, p: [f32; 3]) -> f64 {
    let d = norm(sub(d3(c), d3(p)));
    let r = (r as f64).abs();
    if r > d {
        return 4.0 * std::f64::consts::PI;
    }
    let s2 = (r / d) * (r / d);
    2.0 * std::f64::consts::PI * s2 / (1.0 + (1.0 - s2).sqrt())
}

/// `(1 - cos theta, azimuth in turns)` of direction `w` about the f64 axis from `p` to `c`,
/// in any fixed f64 frame of that axis: an equal-area parameterisation of the sphere of
/// directions around the axis.
fn cone_coords(c: [f32; 3], p: [f32; 3], w: [f32; 3]) -> (f64, f64) {
    let n = sub(d3(c), d3(p));
    let n = scale(n, 1.0 / norm(n));
    let w = scale(d3(w), 1.0 / norm(d3(w)));
    let a = if n[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let t = cross(n, a);
    let t = scale(t, 1.0 / norm(t));
    let b = cross(n, t);
    let ch = sub(w, n);
    let x = 0.5 * dot(ch, ch); // 1 - cos theta, from the chord
    let phi = dot(w, b).atan2(dot(w, t)) / std::f64::consts::TAU;
    (x, phi.rem_euclid(1.0))
}

/// A random sphere light of solid angle about `omega` sr (`1e-8 .. 2 pi`) at distance
/// `10^(-3..3)` from a random point.
fn random_cone(r: &mut Xoshiro256PlusPlus, omega: f64) -> ([f32; 3], f32, [f32; 3]) {
    let dist = 10f64.powf(-3.0 + 6.0 * r.random::<f64>());
    let p = scale(dir(r), dist * 3.0 * r.random::<f64>());
    // omega = 2 pi (1 - cos): sin^2 = 1 - cos^2.
    let omc = (omega / std::f64::consts::TAU).min(1.0);
    let cos = 1.0 - omc;
    let s = (1.0 - cos * cos).sqrt();
    let c = add(p, scale(dir(r), dist));
    (f3(c), (s * dist) as f32, f3(p))
}

/// Solid angle, density and direction against f64 from `1e-8` sr to `2 pi`, and the round
/// trip `cone_inverse(cone(u))` from `1e-4` sr.
#[test]
fn cone_accuracy_against_f64() {
    let mut r = rng(900);
    let (mut omega_err, mut pdf_err, mut dir_err, mut trip) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let mut omega_kappa = 0.0f64;
    let mut tiny_dir_rel = 0.0f64;
    for k in 0..20_000 {
        let omega =
            10f64.powf(-8.0 + (std::f64::consts::TAU.log10() + 8.0) * (k as f64 / 19_999.0));
        let (c, rad, p) = random_cone(&mut r, omega);
        let want = cone_omega(c, rad, p);
        let got = spherical::cone_solid_angle(c, rad, p) as f64;
        // The condition number for relative perturbations of d and r: 1 / cos theta_max
        // (p near the surface).
        let omc = want / std::f64::consts::TAU;
        let kappa = 1.0 / (1.0 - omc).max(1e-30);
        let e = (got / want - 1.0).abs();
        omega_kappa = omega_kappa.max(e / kappa);
        if kappa < 2.0 {
            omega_err = omega_err.max(e);
        }
        let u = unit2(&mut r);
        let (w, pdf) = spherical::cone(c, rad, p, u);
        if kappa < 2.0 {
            pdf_err = pdf_err.max((pdf as f64 * want - 1.0).abs());
        }
        // The f64 map of the same u: 1 - cos theta = rho^2 (1 - cos theta_max), the same
        // azimuth as the f32 direction's (so this measures the polar angle), |w| = 1.
        let (x, _) = cone_coords(c, p, w);
        let (rho, _) =
            common::textbook::concentric_polar(2.0 * u[0] as f64 - 1.0, 2.0 * u[1] as f64 - 1.0);
        // The map's own error: the f64 map at the f32 solid angle (whose error is above).
        let x64 = rho * rho * got / std::f64::consts::TAU;
        let theta = |x: f64| 2.0 * (0.5 * x).sqrt().asin();
        let e = (theta(x) - theta(x64)).abs().max((norm(d3(w)) - 1.0).abs());
        dir_err = dir_err.max(e);
        if omega < 1e-7 {
            tiny_dir_rel = tiny_dir_rel.max(e / theta(want / std::f64::consts::TAU));
        }
        if omega >= 1e-4 {
            let back = spherical::cone_inverse(c, rad, p, w);
            trip = trip.max((back[0] - u[0]).abs().max((back[1] - u[1]).abs()) as f64);
        }
    }
    println!(
        "cone vs f64: solid angle {omega_err:.2e}, density {pdf_err:.2e} relative (kappa < 2), \
         solid angle {omega_kappa:.2e} kappa overall; polar angle {dir_err:.2e} rad \
         ({tiny_dir_rel:.2e} of theta_max below 1e-7 sr); round trip {trip:.2e}"
    );
    assert!(omega_err < 6e-7 && pdf_err < 6e-7, "{omega_err} {pdf_err}");
    assert!(omega_kappa < 6e-7, "{omega_kappa}");
    assert!(dir_err < 3e-7, "{dir_err}");
    assert!(trip < 1e-4, "{trip}");
}

/// Uniform in solid angle: 16 x 16 cells of `(1 - cos theta) / (1 - cos theta_max)` and the
/// azimuth (equal solid angles), 2^21 samples per sphere: 1e-6 sr, 0.01 sr, 1 sr, `p` a
/// hair outside the surface (nearly `2 pi`) and `p` inside (the whole sphere).
#[test]
fn chi2_cone_uniform_in_solid_angle() {
    let cases: [([f32; 3], f32, [f32; 3]); 5] = [
        ([0.3, -2.0, 5.0], 5.64e-4 * 5.43, [0.0; 3]),
        ([1.0, 1.0, 1.0], 0.0975, [0.0, 0.0, 1.0]),
        ([0.0, 0.0, 3.0], 1.5, [0.2, 0.1, 0.0]),
        ([0.0, 0.0, 1.0], 0.999, [0.0; 3]),
        ([0.1, 0.2, 0.3], 2.0, [0.0; 3]),
    ];
    let n = 16usize;
    for (ci, (c, rad, p)) in cases.into_iter().enumerate() {
        let omc = cone_omega(c, rad, p) / std::f64::consts::TAU;
        let mut hist = chi2::Histogram::new(n, n);
        let mut r = rng(910 + ci as u64);
        for _ in 0..chi2::SAMPLES {
            let (w, _) = spherical::cone(c, rad, p, unit2(&mut r));
            let (x, phi) = cone_coords(c, p, w);
            // f32 directions sit within 6e-8 rad of the rim: 2e-4 of x at 1e-6 sr.
            let t = x / omc;
            hist.add([if t > 1.0 && t < 1.0 + 1e-3 { 1.0 } else { t }, phi]);
        }
        chi2::check(
            &format!("spherical cone {ci}"),
            &hist,
            &chi2::expected_uniform(n, n),
        );
    }
}

/// The density is `1 / solid angle` and the special solid angles are exact: `p` on the
/// surface sees `2 pi`, inside `4 pi` (density `1 / (4 pi)`), point lights 0.
#[test]
fn cone_density_and_special_spheres() {
    let pi = std::f32::consts::PI;
    let mut r = rng(920);
    for _ in 0..10_000 {
        let omega = 10f64.powf(-8.0 + 8.8 * r.random::<f64>());
        let (c, rad, p) = random_cone(&mut r, omega);
        let (_, pdf) = spherical::cone(c, rad, p, unit2(&mut r));
        let om = spherical::cone_solid_angle(c, rad, p);
        assert!(
            (pdf * om - 1.0).abs() < 1e-6,
            "{c:?} {rad} {p:?}: {pdf} {om}"
        );
    }
    // On the surface (exactly: distance 2 = radius 2) and inside.
    assert_eq!(
        spherical::cone_solid_angle([0.0, 0.0, 2.0], 2.0, [0.0; 3]),
        2.0 * pi
    );
    let (_, pdf) = spherical::cone([0.0, 0.0, 2.0], 2.0, [0.0; 3], [0.3, 0.7]);
    assert!((pdf * 2.0 * pi - 1.0).abs() < 1e-6);
    for (c, rad, p) in [
        ([0.0f32, 0.0, 1.0], 2.0f32, [0.0f32; 3]),
        ([5.0, 5.0, 5.0], 1.0, [5.0, 5.0, 5.0]),
        ([0.0, 0.0, 0.0], 1e30, [1e29, -3e29, 0.0]),
        ([0.0, 0.0, 0.0], -3.0, [1.0, 0.0, 0.0]),
    ] {
        let om = spherical::cone_solid_angle(c, rad, p);
        assert!((om - 4.0 * pi).abs() < 1e-5, "{c:?} {rad} {p:?}: {om}");
        let mut hist = [0usize; 2];
        for _ in 0..4096 {
            let (w, pdf) = spherical::cone(c, rad, p, unit2(&mut r));
            assert!((pdf * 4.0 * pi - 1.0).abs() < 1e-6);
            hist[(w[2] > 0.0) as usize] += 1;
        }
        // Both hemispheres about equally (binomial, 4096 draws: 6 sigma is 192).
        assert!(hist[0].abs_diff(hist[1]) < 192, "{hist:?}");
    }
    // Point lights: radius 0 or below 2^-60 of the distance: the axis, density 0.
    for rad in [0.0f32, 1e-19, -1e-20, 1e-45] {
        let (w, pdf) = spherical::cone([0.0, 3.0, 4.0], rad, [0.0; 3], [0.2, 0.9]);
        assert_eq!((w, pdf), ([0.0, 0.6, 0.8], 0.0), "{rad}");
        assert_eq!(
            spherical::cone_solid_angle([0.0, 3.0, 4.0], rad, [0.0; 3]),
            0.0
        );
        assert_eq!(
            spherical::cone_inverse([0.0, 3.0, 4.0], rad, [0.0; 3], w),
            [0.5, 0.5]
        );
    }
    // 1e-17 of the distance is still a light (solid angle 3.1e-34 sr).
    let om = spherical::cone_solid_angle([0.0, 3.0, 4.0], 5e-17, [0.0; 3]);
    assert!(
        (om as f64 / (std::f64::consts::PI * 1e-34) - 1.0).abs() < 1e-5,
        "{om}"
    );
}

/// Totality: NaN, inf, subnormal and huge values anywhere give unit directions, finite
/// densities `>= 0` (never `FLT_MAX`), inverses in `[0, 1)`.
#[test]
fn cone_total_on_hostile_input() {
    let sp = specials();
    let mut r = rng(930);
    let vals: Vec<f32> = sp
        .iter()
        .copied()
        .chain([1e30, -1e30, 3e38, 1e-40, -1e-44, 2.0, 0.5, 1e-20, 1e20])
        .collect();
    let pick = |r: &mut Xoshiro256PlusPlus| {
        if r.random::<f32>() < 0.5 {
            vals[r.random_range(0..vals.len())]
        } else {
            (r.random::<f32>() - 0.5) * 10.0
        }
    };
    for _ in 0..200_000 {
        let c = [pick(&mut r), pick(&mut r), pick(&mut r)];
        let p = [pick(&mut r), pick(&mut r), pick(&mut r)];
        let rad = pick(&mut r);
        let u = [pick(&mut r), pick(&mut r)];
        let (w, pdf) = spherical::cone(c, rad, p, u);
        let l = (w[0] as f64).hypot(w[1] as f64).hypot(w[2] as f64);
        assert!((l - 1.0).abs() < 1e-6, "{c:?} {rad} {p:?} {u:?}: {w:?}");
        assert!((0.0..f32::MAX).contains(&pdf), "{pdf}");
        let om = spherical::cone_solid_angle(c, rad, p);
        assert!(
            (0.0..=4.0 * std::f32::consts::PI + 1e-6).contains(&om),
            "{om}"
        );
        let d = [pick(&mut r), pick(&mut r), pick(&mut r)];
        for dd in [d, w] {
            let back = spherical::cone_inverse(c, rad, p, dd);
            assert!(back.iter().all(|x| (0.0..1.0).contains(x)), "{back:?}");
        }
    }
}

/// scalar == x8 == x16 == slice, bit for bit, every lane its own sphere (random, inside,
/// point-like, hostile).
#[test]
fn cone_widths_agree_bit_for_bit() {
    let mut r = rng(940);
    let sp = specials();
    for round in 0..200 {
        let rows: Vec<[[f32; 3]; 4]> = (0..16)
            .map(|j| {
                let om = 10f64.powf(-9.0 + 10.0 * r.random::<f64>());
                let (c, rad, p) = random_cone(&mut r, om);
                let rad = match j % 5 {
                    0 => sp[(round + j) % sp.len()],
                    1 => rad * 50.0,
                    _ => rad,
                };
                let u = unit2(&mut r);
                let d = f3(dir(&mut r));
                [c, [rad, u[0], u[1]], p, d]
            })
            .collect();
        let (w8, w16) = soa_k(&rows);
        let (r8, r16) = (w8[1][0], w16[1][0]);
        let (u8, u16) = ([w8[1][1], w8[1][2]], [w16[1][1], w16[1][2]]);
        let row = |j: usize| {
            (
                rows[j][0],
                rows[j][1][0],
                rows[j][2],
                [rows[j][1][1], rows[j][1][2]],
                rows[j][3],
            )
        };
        assert_lanes(
            |j| {
                let (c, rad, p, u, _) = row(j);
                Box::new(spherical::cone(c, rad, p, u))
            },
            &spherical::cone_x8(w8[0], r8, w8[2], u8),
            &spherical::cone_x16(w16[0], r16, w16[2], u16),
        );
        assert_lanes(
            |j| {
                let (c, rad, p, _, d) = row(j);
                Box::new(spherical::cone_inverse(c, rad, p, d))
            },
            &spherical::cone_inverse_x8(w8[0], r8, w8[2], w8[3]),
            &spherical::cone_inverse_x16(w16[0], r16, w16[2], w16[3]),
        );
        assert_lanes(
            |j| {
                let (c, rad, p, _, _) = row(j);
                Box::new(spherical::cone_solid_angle(c, rad, p))
            },
            &spherical::cone_solid_angle_x8(w8[0], r8, w8[2]),
            &spherical::cone_solid_angle_x16(w16[0], r16, w16[2]),
        );
        let (c, rad, p, _, _) = row(round % 16);
        let us = slice_us(&mut r, &[[0.0, 1.0], [f32::NAN, 0.5]], round);
        let mut out = vec![[0.0f32; 4]; us.len()];
        assert_eq!(spherical::cone_slice(c, rad, p, &us, &mut out), us.len());
        for (u, o) in us.iter().zip(&out) {
            let (w, pdf) = spherical::cone(c, rad, p, *u);
            assert_eq!(bits(*o), bits([w[0], w[1], w[2], pdf]));
        }
        let ds: Vec<[f32; 3]> = out.iter().map(|o| [o[0], o[1], o[2]]).collect();
        let mut back = vec![[0.0f32; 2]; ds.len()];
        assert_eq!(
            spherical::cone_inverse_slice(c, rad, p, &ds, &mut back),
            ds.len()
        );
        for (d, b) in ds.iter().zip(&back) {
            assert_eq!(bits(*b), bits(spherical::cone_inverse(c, rad, p, *d)));
        }
    }
}
