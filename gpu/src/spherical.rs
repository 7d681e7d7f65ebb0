//! Test points of the solid-angle lights of `shaders/warpcore.wgsl` (`wc_spherical_*`): the
//! lights of the golden fingerprint (`warpcore_registry::fingerprint`, ordinary and
//! extreme) and random lights of every kind (ordinary, tiny and far, below the area fallback,
//! grazing, nearly `2 pi`, degenerate, huge and tiny coordinates, random bit patterns), times
//! grids, random points and edge values of the sample square (or of barycentrics, `(s, t)`
//! and normals).

use crate::{Rng, square_edges};
use warpcore::spherical as sp;

/// What follows the light's 12 words in a point.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Layout {
    /// A triangle light `v0, v1, v2, p` alone.
    Triangle = 0,
    /// A triangle light and `u`.
    TriangleU = 1,
    /// A triangle light and barycentrics.
    TriangleB = 2,
    /// A triangle light, a normal and `u`.
    TriangleNU = 3,
    /// A rectangle light `corner, ex, ey, p` alone.
    Rectangle = 4,
    /// A rectangle light and `u`.
    RectangleU = 5,
    /// A rectangle light and `(s, t)`.
    RectangleSt = 6,
    /// A rectangle light, a normal and `u`.
    RectangleNU = 7,
    /// A sphere light `centre, radius, p` (7 words) alone.
    Sphere = 8,
    /// A sphere light and `u`.
    SphereU = 9,
    /// A sphere light and a direction.
    SphereDir = 10,
}

impl Layout {
    fn is_rectangle(self) -> bool {
        matches!(
            self,
            Layout::Rectangle | Layout::RectangleU | Layout::RectangleSt | Layout::RectangleNU
        )
    }
}

const I: f32 = f32::INFINITY;
const NAN: f32 = f32::NAN;

/// The lights of the golden fingerprint (`warpcore_registry::fingerprint`): triangles
/// `v0, v1, v2, p` and rectangles `corner, ex, ey, p`, ordinary and extreme.
pub use warpcore_registry::fingerprint::{
    SPHERICAL_CONES as FINGERPRINT_CONES, SPHERICAL_RECTANGLES as FINGERPRINT_RECTANGLES,
    SPHERICAL_TRIANGLES as FINGERPRINT_TRIANGLES,
};

type V3 = [f32; 3];

fn pt(l: &[f32; 12], k: usize) -> V3 {
    [l[3 * k], l[3 * k + 1], l[3 * k + 2]]
}

fn unit(rng: &mut Rng) -> V3 {
    warpcore::sphere::uniform([rng.grid24(), rng.grid24()])
}

fn cross(a: V3, b: V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalised(a: V3) -> V3 {
    let l = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt();
    a.map(|x| x / l)
}

/// A random light of kind `k % 8` (12 words): 0 ordinary (size and distance about 1), 1 small
/// (1e-3 .. 1e-5 of its distance: around and below the area fallback), 2 far (1e2 .. 1e6
/// away), 3 grazing (`p` within 1e-4 .. 1e-7 of the light's plane, outside), 4 nearly `2 pi`
/// (`p` just above the plane, inside), 5 degenerate (collinear, a repeated vertex, `p` at a
/// vertex, `ey` not orthogonal or zero), 6 one coordinate a random bit pattern, 7 the whole
/// light scaled by a random power of two from `2^-100` to `2^100`.
pub fn random_light(rect: bool, k: usize, rng: &mut Rng) -> [f32; 12] {
    // A frame: the light's plane normal `nz`, two in-plane axes.
    let nz = unit(rng);
    let ax = normalised(cross(
        nz,
        if nz[0].abs() < 0.6 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let ay = cross(nz, ax);
    let at = |x: f32, y: f32, z: f32| -> V3 {
        core::array::from_fn(|c| x * ax[c] + y * ay[c] + z * nz[c])
    };
    let kind = k % 8;
    let (size, dist) = match kind {
        1 => ([1e-3f32, 1e-4, 3e-5, 1e-5][k / 8 % 4], 1.0f32),
        2 => (1.0, [1e2f32, 1e4, 1e6][k / 8 % 3]),
        _ => (rng.range(0.2, 2.0), rng.range(0.3, 2.0)),
    };
    let mut l = [0.0f32; 12];
    // The light's own points, in its plane at height `dist` over `p` = origin.
    let (p0, p1, p2) = if rect {
        let w = size * rng.range(0.3, 1.5);
        let h = size * rng.range(0.3, 1.5);
        let c = at(rng.range(-1.0, 0.2) * w, rng.range(-1.0, 0.2) * h, dist);
        (c, at(w, 0.0, 0.0), at(0.0, h, 0.0))
    } else {
        let v: [V3; 3] = core::array::from_fn(|_| {
            at(
                size * rng.range(-1.0, 1.0),
                size * rng.range(-1.0, 1.0),
                dist,
            )
        });
        (v[0], v[1], v[2])
    };
    let mut p = [0.0f32; 3];
    let (q0, mut q1, mut q2) = (p0, p1, p2);
    match kind {
        3 => {
            // p just below the plane, outside the light.
            let off = [1e-4f32, 1e-5, 1e-6, 1e-7][k / 8 % 4];
            p = at(3.0 * size + 1.0, 0.5, dist - off);
        }
        4 => {
            let off = [1e-3f32, 1e-5, 1e-7][k / 8 % 3];
            let centre: V3 = if rect {
                core::array::from_fn(|c| p0[c] + 0.5 * (p1[c] + p2[c]))
            } else {
                core::array::from_fn(|c| (p0[c] + p1[c] + p2[c]) / 3.0)
            };
            p = core::array::from_fn(|c| centre[c] - off * nz[c]);
        }
        5 => match k / 8 % 4 {
            0 if !rect => q2 = core::array::from_fn(|c| 2.0 * p1[c] - p0[c]),
            0 => q2 = core::array::from_fn(|c| p2[c] + 0.4 * p1[c]),
            1 if !rect => q1 = p0,
            1 => q2 = [0.0; 3],
            2 => p = p0,
            _ => q1 = [0.0; 3],
        },
        _ => {}
    }
    for (k, v) in [q0, q1, q2, p].iter().enumerate() {
        l[3 * k..3 * k + 3].copy_from_slice(v);
    }
    if kind == 2 {
        // Move p, not the light: the light stays at unit scale, the vectors to it are long.
        for x in &mut l[9..12] {
            *x = rng.range(-0.5, 0.5) * dist;
        }
    }
    if kind == 6 {
        let i = rng.next_u32() as usize % 12;
        l[i] = rng.bits();
    }
    if kind == 7 {
        let e = (rng.next_u32() % 201) as i32 - 100;
        let s = 2f32.powi(e);
        l = l.map(|x| x * s);
    }
    l
}

/// Normals for the cosine-aware maps, for light `l`: facing the light, away from it, tilted,
/// grazing, random directions, zero, tiny (subnormal), huge, non-finite.
fn normals(l: &[f32; 12], rect: bool, rng: &mut Rng) -> Vec<V3> {
    let p = pt(l, 3);
    let target: V3 = if rect {
        core::array::from_fn(|c| l[c] + 0.5 * (l[3 + c] + l[6 + c]) - p[c])
    } else {
        core::array::from_fn(|c| (l[c] + l[3 + c] + l[6 + c]) / 3.0 - p[c])
    };
    let r = unit(rng);
    vec![
        target,
        target.map(|x| -x),
        [0.0, 0.0, 1.0],
        [0.5, 0.0, 1.0],
        [1.0, 0.0, 0.0],
        r,
        unit(rng),
        [0.0; 3],
        [1e-40, 0.0, 1e-41],
        r.map(|x| x * 1e30),
        [NAN, 0.0, 1.0],
        [0.0, I, 0.0],
        [rng.bits(), rng.bits(), rng.bits()],
    ]
}

/// A fingerprint sphere light (`centre, [radius, 0, 0], -, p`) as its 7 words' floats.
pub fn sphere7(l: &[f32; 12]) -> [f32; 7] {
    [l[0], l[1], l[2], l[3], l[9], l[10], l[11]]
}

/// A random sphere light (`centre, radius, p`) of kind `k % 8`: 0 ordinary, 1 small (radius
/// `1e-2 .. 1e-6` of the distance), 2 far (`1e2 .. 1e6`), 3 `p` just outside the surface, 4
/// `p` inside, 5 a point (radius 0 or `1e-20` of the distance) or `p` at the centre, 6 one
/// word a random bit pattern, 7 the whole light scaled by a power of two from `2^-100` to
/// `2^100`.
pub fn random_sphere(k: usize, rng: &mut Rng) -> [f32; 7] {
    let n = unit(rng);
    let kind = k % 8;
    let dist = match kind {
        2 => [1e2f32, 1e4, 1e6][k / 8 % 3],
        _ => rng.range(0.3, 3.0),
    };
    let r = match kind {
        1 => dist * [1e-2f32, 1e-3, 1e-4, 1e-6][k / 8 % 4],
        3 => dist * (1.0 - [1e-3f32, 1e-5, 1e-7][k / 8 % 3]),
        4 => dist * rng.range(1.1, 10.0),
        5 => [0.0, dist * 1e-20, 1.0][k / 8 % 3],
        _ => dist * rng.range(0.05, 0.9),
    };
    let p = [
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(-1.0, 1.0),
    ];
    let mut c: V3 = core::array::from_fn(|i| p[i] + dist * n[i]);
    if kind == 5 && k / 8 % 3 == 2 {
        c = p;
    }
    let mut l = [c[0], c[1], c[2], r, p[0], p[1], p[2]];
    if kind == 6 {
        l[rng.next_u32() as usize % 7] = rng.bits();
    }
    if kind == 7 {
        let s = 2f32.powi((rng.next_u32() % 201) as i32 - 100);
        l = l.map(|x| x * s);
    }
    l
}

/// The light `l` and 15 copies seen from moved shading points (the point at `l[at..at + 3]`
/// moved by up to `1e-6 .. 10` per coordinate).
fn moved<const N: usize>(l: &[f32; N], at: usize, rng: &mut Rng) -> Vec<[f32; N]> {
    let mut v = vec![*l];
    for _ in 0..15 {
        let mut m = *l;
        let s = [1e-6f32, 1e-3, 0.1, 1.0, 10.0][rng.next_u32() as usize % 5];
        for x in &mut m[at..at + 3] {
            *x += s * rng.range(-1.0, 1.0);
        }
        v.push(m);
    }
    v
}

/// Samples of the square per light: a grid, random points (2^-24 grid, any f32 in [0, 1),
/// bit patterns), edge pairs (all of them for the fingerprint lights, `fp`).
fn samples(fp: bool, rng: &mut Rng) -> Vec<[f32; 2]> {
    let edges = square_edges();
    let g = if fp { 32 } else { 8 };
    let mut s: Vec<[f32; 2]> = Vec::new();
    for i in 0..g {
        for j in 0..g {
            s.push([(i as f32 + 0.5) / g as f32, (j as f32 + 0.37) / g as f32]);
        }
    }
    for k in 0..(if fp { 256 } else { 32 }) {
        s.push(match k % 3 {
            0 => [rng.grid24(), rng.grid24()],
            1 => [rng.unit_any(), rng.unit_any()],
            _ => [rng.bits(), rng.bits()],
        });
    }
    if fp {
        for &a in &edges {
            for &b in &edges {
                s.push([a, b]);
            }
        }
    } else {
        for _ in 0..16 {
            let a = edges[rng.next_u32() as usize % edges.len()];
            let b = edges[rng.next_u32() as usize % edges.len()];
            s.push([a, rng.unit_any()]);
            s.push([rng.unit_any(), b]);
        }
    }
    s
}

/// The test points of the sphere layouts (`centre, radius, p` and what follows).
fn sphere_inputs(layout: Layout, random: usize, rng: &mut Rng) -> Vec<u32> {
    let mut lights: Vec<([f32; 7], bool)> = FINGERPRINT_CONES
        .iter()
        .map(|l| (sphere7(l), true))
        .collect();
    for k in 0..(random / 64).max(16) {
        lights.push((random_sphere(k, rng), false));
    }
    let mut v: Vec<u32> = Vec::new();
    let mut push = |light: &[f32; 7], extra: &[f32]| {
        v.extend(light.iter().chain(extra).map(|x| x.to_bits()));
    };
    for (l, fp) in &lights {
        let (c, r, p) = ([l[0], l[1], l[2]], l[3], [l[4], l[5], l[6]]);
        let us = samples(*fp, rng);
        match layout {
            Layout::Sphere => {
                for m in moved(l, 4, rng) {
                    push(&m, &[]);
                }
            }
            Layout::SphereU => {
                for u in us {
                    push(l, &u);
                }
            }
            _ => {
                // Round trips (the crate's own directions), random directions of any
                // length, edge and bit patterns.
                for (k, u) in us.into_iter().enumerate() {
                    let d = match k % 4 {
                        0 | 1 => sp::cone(c, r, p, u).0,
                        2 => unit(rng).map(|x| x * rng.range(1e-3, 1e3)),
                        _ => [rng.bits(), rng.bits(), rng.bits()],
                    };
                    push(l, &d);
                }
                for d in [
                    [0.0f32; 3],
                    [1e-40, 0.0, -1e-41],
                    [NAN, 0.0, 1.0],
                    [0.0, -I, 0.0],
                ] {
                    push(l, &d);
                }
            }
        }
    }
    v
}

/// The test points of `layout` (`in_words` words each, the light's 12 first; 7 for spheres).
/// `random` (default 65536) sets the number of random lights (`random / 64`, at least 16).
pub fn inputs(layout: Layout, random: usize, rng: &mut Rng) -> Vec<u32> {
    if matches!(layout, Layout::Sphere | Layout::SphereU | Layout::SphereDir) {
        return sphere_inputs(layout, random, rng);
    }
    let rect = layout.is_rectangle();
    let fingerprint: &[[f32; 12]] = if rect {
        &FINGERPRINT_RECTANGLES
    } else {
        &FINGERPRINT_TRIANGLES
    };
    let edges = square_edges();
    let mut lights: Vec<([f32; 12], bool)> = fingerprint.iter().map(|l| (*l, true)).collect();
    let n_random = (random / 64).max(16);
    for k in 0..n_random {
        lights.push((random_light(rect, k, rng), false));
    }
    let mut v: Vec<u32> = Vec::new();
    let mut push = |light: &[f32; 12], extra: &[f32]| {
        v.extend(light.iter().chain(extra).map(|x| x.to_bits()));
    };
    if matches!(layout, Layout::Triangle | Layout::Rectangle) {
        // Each light, and the light seen from moved shading points.
        for (l, _) in &lights {
            for m in moved(l, 9, rng) {
                push(&m, &[]);
            }
        }
        return v;
    }
    for (l, fp) in &lights {
        let (v0, v1, v2, p) = (pt(l, 0), pt(l, 1), pt(l, 2), pt(l, 3));
        match layout {
            Layout::TriangleU | Layout::RectangleU => {
                for u in samples(*fp, rng) {
                    push(l, &u);
                }
            }
            Layout::TriangleB => {
                // Round trips (the crate's own barycentrics of grid and random samples), edge
                // triples and random triples.
                for u in samples(*fp, rng)
                    .into_iter()
                    .take(if *fp { 1280 } else { 96 })
                {
                    let (b, _) = sp::triangle([v0, v1, v2], p, u);
                    push(l, &b);
                }
                if *fp {
                    for &a in &edges {
                        for &b in &edges {
                            for &c in &[0.0f32, -0.0, 0.5, NAN] {
                                push(l, &[a, b, c]);
                            }
                        }
                    }
                } else {
                    for _ in 0..16 {
                        let e = |r: &mut Rng| edges[r.next_u32() as usize % edges.len()];
                        push(l, &[e(rng), e(rng), e(rng)]);
                        push(l, &[rng.bits(), rng.bits(), rng.bits()]);
                    }
                }
            }
            Layout::RectangleSt => {
                for (k, u) in samples(*fp, rng).into_iter().enumerate() {
                    if k % 2 == 0 {
                        let (st, _) = sp::rectangle(v0, v1, v2, p, u);
                        push(l, &st);
                    } else {
                        push(l, &u);
                    }
                }
            }
            Layout::TriangleNU | Layout::RectangleNU => {
                let ns = normals(l, layout == Layout::RectangleNU, rng);
                if *fp {
                    for (j, n) in ns.iter().enumerate() {
                        let s = samples(j == 0, rng);
                        for u in s {
                            push(l, &[n[0], n[1], n[2], u[0], u[1]]);
                        }
                    }
                } else {
                    let n = ns[rng.next_u32() as usize % ns.len()];
                    for u in samples(false, rng) {
                        push(l, &[n[0], n[1], n[2], u[0], u[1]]);
                    }
                }
            }
            _ => unreachable!(),
        }
    }
    v
}

/// One typical point of `layout` (an ordinary light, the sample `u`, a normal facing the
/// light) for the CPU model.
pub fn typical(layout: Layout, u: [f32; 2], rng: &mut Rng) -> Vec<f32> {
    if matches!(layout, Layout::Sphere | Layout::SphereU | Layout::SphereDir) {
        let l = random_sphere(0, rng);
        let mut w = l.to_vec();
        match layout {
            Layout::SphereU => w.extend(u),
            Layout::SphereDir => {
                w.extend(sp::cone([l[0], l[1], l[2]], l[3], [l[4], l[5], l[6]], u).0)
            }
            _ => {}
        }
        return w;
    }
    let rect = layout.is_rectangle();
    let l = random_light(rect, 0, rng);
    let mut w = l.to_vec();
    let (v0, v1, v2, p) = (pt(&l, 0), pt(&l, 1), pt(&l, 2), pt(&l, 3));
    match layout {
        Layout::Triangle | Layout::Rectangle => {}
        Layout::TriangleU | Layout::RectangleU => w.extend(u),
        Layout::TriangleB => w.extend(sp::triangle([v0, v1, v2], p, u).0),
        Layout::RectangleSt => w.extend(sp::rectangle(v0, v1, v2, p, u).0),
        Layout::TriangleNU | Layout::RectangleNU => {
            w.extend(normals(&l, rect, rng)[0]);
            w.extend(u);
        }
        _ => unreachable!(),
    }
    w
}
