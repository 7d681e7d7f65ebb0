//! Exact references for the environment-map scenes: the integral of a piecewise-constant
//! radiance map times a clamped cosine lobe times an occluder's half-space,
//!
//! ```text
//! I(n, m) = sum_t L_t int_{t cap H} n . w dw,   H = {w : n . w >= 0} cap {w : m . w >= 0},
//! ```
//!
//! over the texels `t` of a map in its own parameterization of the sphere (lat-long or
//! Clarberg's equal-area octahedral square), exact for the piecewise-constant map.
//!
//! **Method.** For a constant vector `n` and any region `R` of the unit sphere, Stokes'
//! theorem (with the vector potential `n x w / 2`, whose curl is `n`) gives
//!
//! ```text
//! int_R n . w dw = 1/2 n . oint_{boundary R} w x dw,
//! ```
//!
//! the boundary running counter-clockwise seen from outside. The boundary of `t cap H` is
//! made of (A) the parts of the texel's four edges inside `H` and (B) the parts of the two
//! great circles `n . w = 0`, `m . w = 0` inside the texel and inside the other half-space.
//! On a great circle with pole `h`, `w x dw = h dpsi` (`psi` the angle along it), so part B
//! is exact: `h` times the arc length inside. Part A is `int w x w' dt` along texel edges:
//! the images of grid lines, smooth between known kinks (the octahedral map's axes and its
//! equator fold; the lat-long map has none), integrated by 16-point Gauss-Legendre per
//! smooth piece — converged to rounding, because a piece is at most a texel long and the map
//! is analytic on it with its singularities (the poles of `phi = (pi/2) q / r`, the branch
//! point of `sqrt(2 - r^2)`) at least a piece's length away. Where an edge is cut by a
//! circle, the cut point is found by safeguarded Newton iteration to `1e-15` in the edge's
//! parameter, so the parts A and B close up.
//!
//! Texels that neither circle touches (no root on their edges) are wholly inside or
//! outside `H`: inside ones contribute `L_t n . V_t` with `V_t = int_t w dw` computed once
//! per map from their edges. A circle that grazes an edge twice between samples of it (a
//! near-tangency) is detected by a bound on the edge's curvature and located by a dense scan;
//! a pair of roots closer than 1/32 of an edge could still be missed, which changes the
//! result by less than `(texel size / 32)^3` relative to the texel: far below everything
//! measured. `report/tests/report.rs` checks the whole against closed forms (a uniform map gives
//! `(pi / 2)(1 + n . m)`), the lat-long texel integrals against their closed form, and
//! importance-sampled Monte Carlo with `10^7` samples.

use crate::math::{add3, cross3, dot3, gl16, norm3, scale3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// A parameterization of the unit sphere by `[0, 1]^2`.
pub trait Param: Sync + Send {
    fn dir(&self, u: [f64; 2]) -> [f64; 3];
    /// The direction and its derivative along `axis` (0: `u`, 1: `v`).
    fn dir_d(&self, u: [f64; 2], axis: usize) -> ([f64; 3], [f64; 3]);
    fn inverse(&self, d: [f64; 3]) -> [f64; 2];
    /// Parameters strictly between `t0` and `t1` where the map is not smooth along the line
    /// through `u` moving along `axis` (the other coordinate fixed), sorted.
    fn kinks(&self, axis: usize, other: f64, t0: f64, t1: f64) -> Vec<f64>;
    /// `+1` when `(u, v)` turns counter-clockwise seen from outside the sphere, else `-1`.
    fn orientation(&self) -> f64;
    /// `int w x dw` along the line through `u` moving along `axis` from `u[axis] = a` to `b`,
    /// in closed form where the parameterization has one (else `None`: quadrature).
    fn edge_integral(&self, _u: [f64; 2], _axis: usize, _a: f64, _b: f64) -> Option<[f64; 3]> {
        None
    }
}

/// Lat-long: `phi = 2 pi u`, `theta = pi v`, `w = (sin theta cos phi, sin theta sin phi,
/// cos theta)` (DESIGN's convention; row 0 is around `+z`).
#[derive(Clone, Copy, Debug)]
pub struct LatLong;

impl Param for LatLong {
    fn dir(&self, u: [f64; 2]) -> [f64; 3] {
        let (sp, cp) = (TAU * u[0]).sin_cos();
        let (st, ct) = (PI * u[1]).sin_cos();
        [st * cp, st * sp, ct]
    }
    fn dir_d(&self, u: [f64; 2], axis: usize) -> ([f64; 3], [f64; 3]) {
        let (sp, cp) = (TAU * u[0]).sin_cos();
        let (st, ct) = (PI * u[1]).sin_cos();
        let d = [st * cp, st * sp, ct];
        let dd = if axis == 0 {
            [-TAU * st * sp, TAU * st * cp, 0.0]
        } else {
            [PI * ct * cp, PI * ct * sp, -PI * st]
        };
        (d, dd)
    }
    fn inverse(&self, d: [f64; 3]) -> [f64; 2] {
        let phi = d[1].atan2(d[0]);
        let u = if phi < 0.0 {
            phi / TAU + 1.0
        } else {
            phi / TAU
        };
        let theta = (d[0].hypot(d[1])).atan2(d[2]);
        [u.min(1.0), theta / PI]
    }
    fn kinks(&self, _: usize, _: f64, _: f64, _: f64) -> Vec<f64> {
        Vec::new()
    }
    fn orientation(&self) -> f64 {
        // d/du x d/dv points inwards: e_phi x e_theta = -e_r.
        -1.0
    }
    /// Along a parallel (`theta` fixed): `w x dw/dphi = -sin(theta) e_theta`; along a
    /// meridian (`phi` fixed): `w x dw/dtheta = e_phi`.
    fn edge_integral(&self, u: [f64; 2], axis: usize, a: f64, b: f64) -> Option<[f64; 3]> {
        Some(if axis == 0 {
            let (st, ct) = (PI * u[1]).sin_cos();
            let (pa, pb) = (TAU * a, TAU * b);
            let (sa, ca) = pa.sin_cos();
            let (sb, cb) = pb.sin_cos();
            [
                -st * ct * (sb - sa),
                -st * ct * (ca - cb),
                st * st * (pb - pa),
            ]
        } else {
            let (sp, cp) = (TAU * u[0]).sin_cos();
            let d = PI * (b - a);
            [-sp * d, cp * d, 0.0]
        })
    }
}

/// Clarberg's equal-area octahedral map, as `warpcore::sphere::equal_area` computes it:
/// `a = 2 u - 1`, `b = 2 v - 1`; per quadrant `(p, q) = (|a|, |b|)` above the equator fold
/// `|a| + |b| = 1` and `(1 - |b|, 1 - |a|)` below; `r = p + q`, `phi = (pi/2) q / r`,
/// `z = +-(1 - r^2)`, `(x, y) = r sqrt(2 - r^2) (cos phi, sin phi)` with the signs of `a, b`.
#[derive(Clone, Copy, Debug)]
pub struct EqualArea;

fn sgn(x: f64) -> f64 {
    if x < 0.0 { -1.0 } else { 1.0 }
}

impl Param for EqualArea {
    fn dir(&self, u: [f64; 2]) -> [f64; 3] {
        self.dir_d(u, 0).0
    }
    fn dir_d(&self, u: [f64; 2], axis: usize) -> ([f64; 3], [f64; 3]) {
        let (a, b) = (2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
        let (sa, sb) = (sgn(a), sgn(b));
        let lower = a.abs() + b.abs() > 1.0;
        // (p, q) and their derivatives along the axis (da/du = db/dv = 2).
        let (p, q, dp, dq) = match (lower, axis) {
            (false, 0) => (a.abs(), b.abs(), 2.0 * sa, 0.0),
            (false, _) => (a.abs(), b.abs(), 0.0, 2.0 * sb),
            (true, 0) => (1.0 - b.abs(), 1.0 - a.abs(), 0.0, -2.0 * sa),
            (true, _) => (1.0 - b.abs(), 1.0 - a.abs(), -2.0 * sb, 0.0),
        };
        let r = p + q;
        let dr = dp + dq;
        let zs = if lower { -1.0 } else { 1.0 };
        if r <= 0.0 {
            // A pole: the direction is exact; the derivative is not needed there (never a
            // quadrature node).
            return ([0.0, 0.0, zs], [0.0; 3]);
        }
        let phi = FRAC_PI_2 * q / r;
        let dphi = FRAC_PI_2 * (dq * r - q * dr) / (r * r);
        let s = (2.0 - r * r).sqrt();
        let rho = r * s;
        let drho = dr * (2.0 - 2.0 * r * r) / s;
        let (sp, cp) = phi.sin_cos();
        let d = [sa * rho * cp, sb * rho * sp, zs * (1.0 - r * r)];
        let dd = [
            sa * (drho * cp - rho * sp * dphi),
            sb * (drho * sp + rho * cp * dphi),
            zs * (-2.0 * r * dr),
        ];
        (d, dd)
    }
    fn inverse(&self, d: [f64; 3]) -> [f64; 2] {
        let rho2 = d[0] * d[0] + d[1] * d[1];
        // r^2 = 1 - |z| = (x^2 + y^2) / (1 + |z|), without cancellation at the poles.
        let r = (rho2 / (1.0 + d[2].abs())).sqrt();
        let phi = d[1].abs().atan2(d[0].abs());
        let q = r * phi / FRAC_PI_2;
        let p = r - q;
        let (aa, bb) = if d[2] >= 0.0 {
            (p, q)
        } else {
            (1.0 - q, 1.0 - p)
        };
        let a = if d[0] < 0.0 { -aa } else { aa };
        let b = if d[1] < 0.0 { -bb } else { bb };
        [
            (0.5 * (a + 1.0)).clamp(0.0, 1.0),
            (0.5 * (b + 1.0)).clamp(0.0, 1.0),
        ]
    }
    fn kinks(&self, _axis: usize, other: f64, t0: f64, t1: f64) -> Vec<f64> {
        // Along either axis the kinks sit where the moving coordinate crosses 0 or the fold.
        let c = (2.0 * other - 1.0).abs();
        let mut k: Vec<f64> = [0.5, 0.5 * (1.0 - (1.0 - c)), 0.5 * (1.0 + (1.0 - c))]
            .into_iter()
            .filter(|&t| t > t0 && t < t1)
            .collect();
        k.sort_by(f64::total_cmp);
        k.dedup();
        k
    }
    fn orientation(&self) -> f64 {
        1.0
    }
}

/// One grid edge: from `start`, length `len` along `axis`, parameter `t` in `[0, 1]`.
#[derive(Clone, Debug)]
struct Edge {
    start: [f64; 2],
    axis: usize,
    len: f64,
    /// Breakpoints `0 = t_0 < ... < t_k = 1` (ends and kinks) and their directions.
    t: Vec<f64>,
    d: Vec<[f64; 3]>,
    /// Bound on `|d^2 w / dt^2|` over the edge (for near-tangent circles).
    curv: f64,
    /// `int_0^1 w x dw/dt dt`.
    full: [f64; 3],
    /// Index of the start node.
    node: usize,
    /// Bound on `|w(t) - w(0)|` over the edge (its length on the sphere, with a margin): a
    /// circle `h . w = 0` with `|h . w(0)| > reach` cannot cut the edge.
    reach: f64,
}

/// What the per-pixel integral knows about an edge cut by at least one circle.
#[derive(Default)]
struct CutEdge {
    /// Roots of each circle, sorted.
    roots: [Vec<f64>; 2],
    /// Their angles `psi` along their circle (see [`frame`]).
    psi: [Vec<f64>; 2],
    /// `int w x dw/dt dt` over the parts of the edge inside both half-spaces.
    inside: [f64; 3],
}

/// A texel grid on the sphere with everything the per-pixel integral reuses.
pub struct Grid<P: Param> {
    pub param: P,
    pub width: usize,
    pub height: usize,
    /// Horizontal edges (along `u`): `(h + 1) x w`, then vertical (along `v`): `h x (w + 1)`.
    horizontal: Vec<Edge>,
    vertical: Vec<Edge>,
    /// `(w + 1) x (h + 1)` grid nodes, row-major.
    nodes: Vec<[f64; 3]>,
    /// `(start node, reach)` of each horizontal and vertical edge, packed for the per-pixel
    /// scan.
    reach: [Vec<(u32, f64)>; 2],
    centres: Vec<[f64; 3]>,
    /// `V_t = int_t w dw` per texel.
    pub moment: Vec<[f64; 3]>,
}

impl Edge {
    fn uv(&self, t: f64) -> [f64; 2] {
        let mut u = self.start;
        u[self.axis] += t * self.len;
        u
    }
    fn dir_d<P: Param>(&self, p: &P, t: f64) -> ([f64; 3], [f64; 3]) {
        let (d, dd) = p.dir_d(self.uv(t), self.axis);
        (d, scale3(dd, self.len))
    }
    /// `int_{t0}^{t1} w x dw/dt dt` within one smooth piece.
    fn integral<P: Param>(&self, p: &P, t0: f64, t1: f64) -> [f64; 3] {
        let s0 = self.start[self.axis];
        if let Some(v) = p.edge_integral(
            self.start,
            self.axis,
            s0 + t0 * self.len,
            s0 + t1 * self.len,
        ) {
            return v;
        }
        let (mid, half) = (0.5 * (t0 + t1), 0.5 * (t1 - t0));
        let mut acc = [0.0; 3];
        for &(x, w) in gl16() {
            let (d, dd) = self.dir_d(p, mid + half * x);
            acc = add3(acc, scale3(cross3(d, dd), w * half));
        }
        acc
    }
    /// The same over any `[t0, t1]`, split at the kinks.
    fn integral_split<P: Param>(&self, p: &P, t0: f64, t1: f64) -> [f64; 3] {
        let mut acc = [0.0; 3];
        let mut a = t0;
        for &k in self.t.iter().filter(|&&k| k > t0 && k < t1) {
            acc = add3(acc, self.integral(p, a, k));
            a = k;
        }
        add3(acc, self.integral(p, a, t1))
    }
    fn new<P: Param>(p: &P, start: [f64; 2], axis: usize, len: f64, node: usize) -> Edge {
        let other = start[1 - axis];
        let s0 = start[axis];
        let mut t = vec![0.0];
        t.extend(
            p.kinks(axis, other, s0, s0 + len)
                .into_iter()
                .map(|k| (k - s0) / len),
        );
        t.push(1.0);
        let mut e = Edge {
            start,
            axis,
            len,
            d: Vec::new(),
            t,
            curv: 0.0,
            full: [0.0; 3],
            node,
            reach: 0.0,
        };
        e.d = e.t.iter().map(|&t| p.dir(e.uv(t))).collect();
        // Curvature bound: second differences of w' on each piece, with a safety factor.
        let mut curv: f64 = 0.0;
        for k in 0..e.t.len() - 1 {
            let (a, b) = (e.t[k], e.t[k + 1]);
            let n = 6;
            let h = (b - a) / n as f64;
            let der: Vec<[f64; 3]> = (0..=n)
                .map(|i| {
                    e.dir_d(p, a + h * (i as f64).clamp(0.01, n as f64 - 0.01))
                        .1
                })
                .collect();
            for i in 0..n {
                let diff = [
                    der[i + 1][0] - der[i][0],
                    der[i + 1][1] - der[i][1],
                    der[i + 1][2] - der[i][2],
                ];
                curv = curv.max(dot3(diff, diff).sqrt() / h);
            }
        }
        e.curv = 2.0 * curv + 1e-12;
        e.full = e.integral_split(p, 0.0, 1.0);
        // Arc length by 8 chords per piece, with a 10% margin (on a piece at most a texel
        // long, chords underestimate it by far less).
        let mut ts = Vec::new();
        for k in 0..e.t.len() - 1 {
            ts.extend((0..8).map(|i| e.t[k] + (e.t[k + 1] - e.t[k]) * i as f64 / 8.0));
        }
        ts.push(1.0);
        let pts: Vec<[f64; 3]> = ts.iter().map(|&t| p.dir(e.uv(t))).collect();
        let length: f64 = pts
            .windows(2)
            .map(|w| {
                let d = [w[1][0] - w[0][0], w[1][1] - w[0][1], w[1][2] - w[0][2]];
                dot3(d, d).sqrt()
            })
            .sum();
        e.reach = 1.1 * length + 1e-12;
        e
    }

    /// Roots of `h . w(t)` on the edge, sorted.
    fn roots<P: Param>(&self, p: &P, h: [f64; 3], out: &mut Vec<f64>) {
        for k in 0..self.t.len() - 1 {
            let (a, b) = (self.t[k], self.t[k + 1]);
            let (ga, gb) = (dot3(h, self.d[k]), dot3(h, self.d[k + 1]));
            if (ga >= 0.0) != (gb >= 0.0) {
                out.push(self.refine(p, h, a, b, ga));
            } else if ga.abs().min(gb.abs()) <= self.curv * (b - a) * (b - a) / 8.0 {
                // Possibly two roots close together: scan.
                let n = 32;
                let mut prev = (a, ga);
                for i in 1..=n {
                    let t = a + (b - a) * i as f64 / n as f64;
                    let g = if i == n {
                        gb
                    } else {
                        dot3(h, p.dir(self.uv(t)))
                    };
                    if (prev.1 >= 0.0) != (g >= 0.0) {
                        out.push(self.refine(p, h, prev.0, t, prev.1));
                    }
                    prev = (t, g);
                }
            }
        }
    }

    /// The root of `h . w(t)` in `[a, b]`, where it changes sign; `ga = g(a)`.
    fn refine<P: Param>(&self, p: &P, h: [f64; 3], mut a: f64, mut b: f64, ga: f64) -> f64 {
        let a_positive = ga >= 0.0;
        let mut t = 0.5 * (a + b);
        for _ in 0..100 {
            let (d, dd) = self.dir_d(p, t);
            let (g, dg) = (dot3(h, d), dot3(h, dd));
            if g == 0.0 {
                return t;
            }
            if (g >= 0.0) == a_positive {
                a = t;
            } else {
                b = t;
            }
            let newton = t - g / dg;
            let next = if newton > a && newton < b && dg != 0.0 {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - t).abs() <= 1e-15 || b - a <= 1e-15 {
                return next;
            }
            t = next;
        }
        t
    }
}

/// Length of the part of the arc `[a, b]` (`b - a < 2 pi`) where `cos(psi - c) >= 0`.
fn half_circle_overlap(a: f64, b: f64, c: f64) -> f64 {
    let (x0, x1) = (a - c, b - c);
    let k0 = ((x0 + FRAC_PI_2) / TAU).floor() as i64 - 1;
    (k0..=k0 + 3)
        .map(|k| {
            let (lo, hi) = (k as f64 * TAU - FRAC_PI_2, k as f64 * TAU + FRAC_PI_2);
            (x1.min(hi) - x0.max(lo)).max(0.0)
        })
        .sum()
}

/// An orthonormal frame `(e1, e2)` of the great circle with pole `h` (`e1 x e2 = h`).
fn frame(h: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let a = if h[0].abs() < 0.6 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = norm3(cross3(a, h));
    let e2 = cross3(h, e1);
    (e1, e2)
}

impl<P: Param> Grid<P> {
    pub fn new(param: P, width: usize, height: usize) -> Self {
        let (w, h) = (width, height);
        let (du, dv) = (1.0 / w as f64, 1.0 / h as f64);
        let node = |i: usize, j: usize| j * (w + 1) + i;
        let horizontal = (0..=h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| Edge::new(&param, [i as f64 * du, j as f64 * dv], 0, du, node(i, j)))
            .collect::<Vec<_>>();
        let vertical = (0..h)
            .flat_map(|j| (0..=w).map(move |i| (i, j)))
            .map(|(i, j)| Edge::new(&param, [i as f64 * du, j as f64 * dv], 1, dv, node(i, j)))
            .collect::<Vec<_>>();
        let nodes = (0..=h)
            .flat_map(|j| (0..=w).map(move |i| (i, j)))
            .map(|(i, j)| param.dir([i as f64 * du, j as f64 * dv]))
            .collect();
        let centres = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| param.dir([(i as f64 + 0.5) * du, (j as f64 + 0.5) * dv]))
            .collect();
        let mut g = Grid {
            param,
            width: w,
            height: h,
            reach: [
                horizontal
                    .iter()
                    .map(|e| (e.node as u32, e.reach))
                    .collect(),
                vertical.iter().map(|e| (e.node as u32, e.reach)).collect(),
            ],
            horizontal,
            vertical,
            nodes,
            centres,
            moment: Vec::new(),
        };
        let o = g.param.orientation();
        g.moment = (0..h)
            .flat_map(|j| (0..w).map(move |i| (i, j)))
            .map(|(i, j)| {
                let [b, r, t, l] = g.texel_edges(i, j);
                let s = add3(add3(b.full, r.full), scale3(add3(t.full, l.full), -1.0));
                scale3(s, 0.5 * o)
            })
            .collect();
        g
    }

    fn h_index(&self, i: usize, j: usize) -> usize {
        j * self.width + i
    }
    fn v_index(&self, i: usize, j: usize) -> usize {
        j * (self.width + 1) + i
    }

    /// Bottom, right, top, left edges of texel `(i, j)`.
    fn texel_edges(&self, i: usize, j: usize) -> [&Edge; 4] {
        [
            &self.horizontal[self.h_index(i, j)],
            &self.vertical[self.v_index(i + 1, j)],
            &self.horizontal[self.h_index(i, j + 1)],
            &self.vertical[self.v_index(i, j)],
        ]
    }

    /// Keys of texel `(i, j)`'s edges in the root maps: (vertical?, index).
    fn texel_keys(&self, i: usize, j: usize) -> [(bool, usize); 4] {
        [
            (false, self.h_index(i, j)),
            (true, self.v_index(i + 1, j)),
            (false, self.h_index(i, j + 1)),
            (true, self.v_index(i, j)),
        ]
    }

    /// `sum_t L_t int_{t cap H} n . w dw` over the whole map, `H = {n . w >= 0} cap
    /// {m . w >= 0}`.
    pub fn integral(&self, radiance: &[f64], n: [f64; 3], m: [f64; 3]) -> f64 {
        let (w, h) = (self.width, self.height);
        // m = +-n (never drawn, but total): one circle, or nothing visible.
        let x = cross3(n, m);
        let circles = if dot3(x, x) > 0.0 {
            2
        } else if dot3(n, m) > 0.0 {
            1
        } else {
            return 0.0;
        };
        let poles = [n, m];
        let g: [Vec<f64>; 2] =
            poles.map(|pole| self.nodes.iter().map(|&d| dot3(pole, d)).collect());
        let node_inside = |k: usize| g[0][k] >= 0.0 && g[1][k] >= 0.0;
        // Roots of each circle on each edge, and the texels they touch (bit c for circle c).
        // Cut edges are numbered: `slot[vertical][edge]` is their index in `cut`.
        let mut slot = [
            vec![u32::MAX; self.horizontal.len()],
            vec![u32::MAX; self.vertical.len()],
        ];
        let mut cut: Vec<((bool, usize), CutEdge)> = Vec::new();
        let mut touched = vec![0u8; w * h];
        let mut buf = Vec::new();
        for (c, &pole) in poles.iter().enumerate().take(circles) {
            for (vertical, edges) in [(false, &self.horizontal), (true, &self.vertical)] {
                for (idx, &(node, reach)) in self.reach[vertical as usize].iter().enumerate() {
                    if g[c][node as usize].abs() > reach {
                        continue;
                    }
                    buf.clear();
                    edges[idx].roots(&self.param, pole, &mut buf);
                    if buf.is_empty() {
                        continue;
                    }
                    let s = &mut slot[vertical as usize][idx];
                    if *s == u32::MAX {
                        *s = cut.len() as u32;
                        cut.push(((vertical, idx), CutEdge::default()));
                    }
                    cut[*s as usize].1.roots[c] = buf.clone();
                    // The texels on both sides of the edge.
                    let (i, j) = if vertical {
                        (idx % (w + 1), idx / (w + 1))
                    } else {
                        (idx % w, idx / w)
                    };
                    let mut mark = |i: usize, j: usize| touched[j * w + i] |= 1 << c;
                    if vertical {
                        if i < w {
                            mark(i, j);
                        }
                        if i > 0 {
                            mark(i - 1, j);
                        }
                    } else {
                        if j < h {
                            mark(i, j);
                        }
                        if j > 0 {
                            mark(i, j - 1);
                        }
                    }
                }
            }
        }
        // Part A of the cut edges, once per edge (two texels share it).
        let p = &self.param;
        let inside = |d: [f64; 3]| dot3(n, d) >= 0.0 && dot3(m, d) >= 0.0;
        let frames = poles.map(frame);
        for ((vertical, idx), ce) in cut.iter_mut() {
            let (vertical, idx) = (*vertical, *idx);
            let e = if vertical {
                &self.vertical[idx]
            } else {
                &self.horizontal[idx]
            };
            for ((psi, roots), &(e1, e2)) in ce.psi.iter_mut().zip(&ce.roots).zip(&frames) {
                *psi = roots
                    .iter()
                    .map(|&t| {
                        let d = p.dir(e.uv(t));
                        dot3(d, e2).atan2(dot3(d, e1))
                    })
                    .collect();
            }
            let mut cuts: Vec<f64> = ce.roots.concat();
            cuts.push(0.0);
            cuts.push(1.0);
            cuts.sort_by(f64::total_cmp);
            for s in cuts.windows(2) {
                if s[1] > s[0] && inside(p.dir(e.uv(0.5 * (s[0] + s[1])))) {
                    ce.inside = add3(ce.inside, e.integral_split(p, s[0], s[1]));
                }
            }
        }
        let mut total = 0.0;
        for j in 0..h {
            for i in 0..w {
                let t = j * w + i;
                let l = radiance[t];
                if l == 0.0 {
                    continue;
                }
                if touched[t] == 0 {
                    let c = self.centres[t];
                    if dot3(n, c) >= 0.0 && dot3(m, c) >= 0.0 {
                        total += l * dot3(n, self.moment[t]);
                    }
                } else {
                    let lookup = |(vertical, idx): (bool, usize)| {
                        let s = slot[vertical as usize][idx];
                        (s != u32::MAX).then(|| &cut[s as usize].1)
                    };
                    total += l * self.cut_texel(
                        i,
                        j,
                        [n, m],
                        frames,
                        &lookup,
                        touched[t],
                        circles == 2,
                        &node_inside,
                    );
                }
            }
        }
        total
    }

    /// `int_{t cap H} n . w dw` for a texel touched by at least one circle.
    #[allow(clippy::too_many_arguments)]
    fn cut_texel<'a>(
        &self,
        i: usize,
        j: usize,
        poles: [[f64; 3]; 2],
        frames: [([f64; 3], [f64; 3]); 2],
        cut: &dyn Fn((bool, usize)) -> Option<&'a CutEdge>,
        touched: u8,
        two_circles: bool,
        node_inside: &dyn Fn(usize) -> bool,
    ) -> f64 {
        let p = &self.param;
        let edges = self.texel_edges(i, j);
        let keys = self.texel_keys(i, j);
        let signs = [1.0, 1.0, -1.0, -1.0];
        let cuts = keys.map(cut);
        // Part A: the edges inside H (an uncut edge is wholly inside or outside).
        let mut part_a = [0.0; 3];
        for k in 0..4 {
            let contribution = match cuts[k] {
                Some(ce) => ce.inside,
                None if node_inside(edges[k].node) => edges[k].full,
                None => [0.0; 3],
            };
            part_a = add3(part_a, scale3(contribution, signs[k]));
        }
        // Part B: the circles inside the texel and the other half-space.
        let mut part_b = [0.0; 3];
        for c in 0..2 {
            if touched & (1 << c) == 0 {
                continue;
            }
            let (pole, other) = (poles[c], poles[1 - c]);
            let (e1, e2) = frames[c];
            let mut angles: Vec<f64> = cuts
                .iter()
                .flatten()
                .flat_map(|ce| ce.psi[c].iter().copied())
                .collect();
            angles.sort_by(f64::total_cmp);
            // Arcs of the circle inside the texel, as [start, end] with start < end.
            let mut arcs: Vec<(f64, f64)> = Vec::new();
            if angles.len() == 2 {
                // A texel is far smaller than a half circle: the shorter arc is inside.
                let (a, b) = (angles[0], angles[1]);
                arcs.push(if b - a <= PI { (a, b) } else { (b, a + TAU) });
            } else if angles.len() > 2 {
                let (u0, u1) = (
                    i as f64 / self.width as f64,
                    (i + 1) as f64 / self.width as f64,
                );
                let (v0, v1) = (
                    j as f64 / self.height as f64,
                    (j + 1) as f64 / self.height as f64,
                );
                let k = angles.len();
                for a in 0..k {
                    let s0 = angles[a];
                    let s1 = if a + 1 < k {
                        angles[a + 1]
                    } else {
                        angles[0] + TAU
                    };
                    if s1 <= s0 {
                        continue;
                    }
                    let (sm, cm) = (0.5 * (s0 + s1)).sin_cos();
                    let uv = p.inverse(add3(scale3(e1, cm), scale3(e2, sm)));
                    if uv[0] >= u0 && uv[0] <= u1 && uv[1] >= v0 && uv[1] <= v1 {
                        arcs.push((s0, s1));
                    }
                }
            }
            // The other half-space is the half circle cos(psi - c0) >= 0 (with one circle,
            // m = n, there is no other).
            let c0 = dot3(other, e2).atan2(dot3(other, e1));
            let length: f64 = arcs
                .iter()
                .map(|&(a, b)| {
                    if two_circles {
                        half_circle_overlap(a, b, c0)
                    } else {
                        b - a
                    }
                })
                .sum();
            part_b = add3(part_b, scale3(pole, length));
        }
        let o = p.orientation();
        0.5 * dot3(poles[0], add3(scale3(part_a, o), part_b))
    }
}
