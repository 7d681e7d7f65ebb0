//! Area-light scenes: a shading point under a planar light of unit area, with an occluder
//! edge crossing the light, and their exact references.
//!
//! **Geometry.** The light lies in the plane `z = 0`, centred at the origin, facing up; the
//! shading point is `(q, h)` at height `h = 1`, its normal facing down, parallel to the light.
//! With unit radiance the irradiance is
//!
//! ```text
//! E = int_visible cos(theta) cos(theta') / r^2 dA = int_visible h^2 / (h^2 + |x - q|^2)^2 dA(x)
//! ```
//!
//! An occluding half-plane between the point and the light hides every light point behind
//! the line where its edge projects onto the light plane (the line through the point and the
//! occluder's edge meets the plane in a line), so visibility is a half-plane cut of the
//! light: `x` is visible when `e . x >= k` (unit normal `e`, offset `k`).
//!
//! **Pixels.** A pixel draws `q` uniform in `[-1/2, 1/2]^2` and, in the original mix, an
//! occluder edge: a point `c` uniform in the light's bounding box scaled by 1.5 about its
//! centre and a line through `c` with a uniform direction, visible side `e . (x - c) >= 0`.
//! That line either cuts the light's interior (a **penumbra** pixel), or leaves the whole
//! light visible (**lit**) or hidden (**hidden**, irradiance and error exactly 0). The report
//! measures the two classes apart, each with its own pixels drawn from the mix conditioned on
//! the class (`lit`: no occluder; `penumbra`: edges drawn until one cuts the light), and the
//! mix as their weighted sum with the class probabilities of the mix ([`mix_weights`]):
//! `MSE_mix = p_lit MSE_lit + p_penumbra MSE_penumbra` (post-stratification: the same
//! quantity as averaging over mix pixels, with less variance).
//!
//! **Estimator.** `E_N = (A / N) sum f(x_i) V(x_i)` with `x_i` the warped samples, uniform on
//! the sampling domain of area `A`: the light (`A = 1`), or for `pad_zero` the disk's bounding
//! square (`A = 4 r^2`, samples outside the disk count 0).
//!
//! **Reference** (exact). By Green's theorem the integral of `h^2 / (h^2 + |x - q|^2)^2`
//! over a region is the contour integral `1/2 oint (X dY - Y dX) / (h^2 + X^2 + Y^2)`, with
//! `(X, Y) = x - q` (the planar form of Lambert's polygon formula). Along a straight edge
//! from `A` to `B` it has the closed form [`edge_term`]; along a circular arc its integrand
//! is analytic and periodic, integrated by 16-point Gauss-Legendre on pieces of at most
//! `pi / 8` (converged to rounding: `report/tests/report.rs` checks it against an independent 2D
//! quadrature and the closed form of the whole disk).

use crate::math::{Rng, cross2, dot2, gl16, hash, integrate, sub2};
use crate::run::{Scene, Scratch};
use crate::samplers::{Sampler, hash_x8};
use std::f64::consts::{PI, TAU};
use warpcore::{disk, triangle, u32x8};

/// Height of the shading point over the light plane.
pub const HEIGHT: f64 = 1.0;

/// A light's shape, centred at the origin of the light plane, area 1.
#[derive(Clone, Debug)]
pub enum Shape {
    /// `[-hx, hx] x [-hy, hy]`.
    Rect { hx: f64, hy: f64 },
    /// Radius `r`.
    Disk { r: f64 },
    /// Vertices `v0, v1, v2`, counter-clockwise.
    Triangle { v: [[f64; 2]; 3] },
}

impl Shape {
    pub fn area(&self) -> f64 {
        match self {
            Shape::Rect { hx, hy } => 4.0 * hx * hy,
            Shape::Disk { r } => PI * r * r,
            Shape::Triangle { v } => 0.5 * cross2(sub2(v[1], v[0]), sub2(v[2], v[0])),
        }
    }

    /// Half extents of the bounding box (centred at the origin).
    pub fn half_extents(&self) -> [f64; 2] {
        match self {
            Shape::Rect { hx, hy } => [*hx, *hy],
            Shape::Disk { r } => [*r, *r],
            Shape::Triangle { v } => {
                let m = |k: usize| v.iter().map(|p| p[k].abs()).fold(0.0, f64::max);
                [m(0), m(1)]
            }
        }
    }

    /// The boundary polygon, counter-clockwise (`None` for the disk).
    pub fn polygon(&self) -> Option<Vec<[f64; 2]>> {
        match self {
            Shape::Rect { hx, hy } => Some(vec![[-hx, -hy], [*hx, -hy], [*hx, *hy], [-hx, *hy]]),
            Shape::Disk { .. } => None,
            Shape::Triangle { v } => Some(v.to_vec()),
        }
    }

    #[allow(dead_code)]
    pub fn contains(&self, x: [f64; 2]) -> bool {
        match self {
            Shape::Rect { hx, hy } => x[0].abs() <= *hx && x[1].abs() <= *hy,
            Shape::Disk { r } => dot2(x, x) <= r * r,
            Shape::Triangle { v } => {
                (0..3).all(|i| cross2(sub2(v[(i + 1) % 3], v[i]), sub2(x, v[i])) >= 0.0)
            }
        }
    }
}

/// The unit-area lights of the report.
pub fn square() -> Shape {
    Shape::Rect { hx: 0.5, hy: 0.5 }
}

/// 16:1, long along `x` (driven by `u[0]`).
pub fn skinny() -> Shape {
    Shape::Rect { hx: 2.0, hy: 0.125 }
}

pub fn disk() -> Shape {
    Shape::Disk {
        r: (1.0 / PI).sqrt(),
    }
}

/// Equilateral, centroid at the origin, `v0` at the top.
pub fn triangle() -> Shape {
    let rc = (4.0 / (3.0 * 3f64.sqrt())).sqrt();
    let at = |deg: f64| {
        let a = deg.to_radians();
        [rc * a.cos(), rc * a.sin()]
    };
    Shape::Triangle {
        v: [at(90.0), at(210.0), at(330.0)],
    }
}

/// How samples reach the light: the six disk strategies of Christensen's memo, the four
/// triangle warps, and the identity for rectangles.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AreaWarp {
    /// Rectangles: `x = (2 u0 - 1) hx, (2 u1 - 1) hy`.
    Identity,
    Polar,
    Concentric,
    /// Point `i / 4` of the sampler, quadrant `i % 4` (`disk::polar4_slice`).
    Polar4,
    /// Point `i / 4`, quadrant `i % 4` (`disk::concentric4_slice`).
    Concentric4,
    /// The point mapped to the disk's bounding square; samples outside the disk count 0.
    PadZero,
    /// Consecutive points of the sequence mapped to the bounding square until `N` land in
    /// the disk (the draw and its time include the rejected points).
    Rejection,
    /// Heitz's low-distortion map, `triangle::uniform`.
    Uniform,
    Sqrt,
    /// `triangle::basu_owen(index, pixel seed)`: index-driven, see [`AreaScene::draw`].
    BasuOwen,
    /// `triangle::basu_owen_permuted(index, pixel seed)`: index-driven.
    BasuOwenPermuted,
}

impl AreaWarp {
    pub fn name(self) -> &'static str {
        match self {
            AreaWarp::Identity => "identity",
            AreaWarp::Polar => "polar",
            AreaWarp::Concentric => "concentric",
            AreaWarp::Polar4 => "polar4",
            AreaWarp::Concentric4 => "concentric4",
            AreaWarp::PadZero => "pad_zero",
            AreaWarp::Rejection => "rejection",
            AreaWarp::Uniform => "uniform",
            AreaWarp::Sqrt => "sqrt",
            AreaWarp::BasuOwen => "basu_owen",
            AreaWarp::BasuOwenPermuted => "basu_owen_permuted",
        }
    }

    /// Driven by sample indices rather than a sampler's points.
    pub fn index_driven(self) -> bool {
        matches!(self, AreaWarp::BasuOwen | AreaWarp::BasuOwenPermuted)
    }

    /// Output in `Scratch::out2` (disk points) rather than `out3` or the points themselves.
    fn disk_out(self) -> bool {
        matches!(
            self,
            AreaWarp::Polar
                | AreaWarp::Concentric
                | AreaWarp::Polar4
                | AreaWarp::Concentric4
                | AreaWarp::PadZero
                | AreaWarp::Rejection
        )
    }
}

/// The disk light's warps: the six strategies of Christensen's memo, in the tables' order.
pub const DISK_WARPS: [AreaWarp; 6] = [
    AreaWarp::Polar,
    AreaWarp::Concentric,
    AreaWarp::Polar4,
    AreaWarp::Concentric4,
    AreaWarp::PadZero,
    AreaWarp::Rejection,
];

/// The triangle light's warps, in the tables' order.
pub const TRIANGLE_WARPS: [AreaWarp; 4] = [
    AreaWarp::Uniform,
    AreaWarp::Sqrt,
    AreaWarp::BasuOwen,
    AreaWarp::BasuOwenPermuted,
];

/// Which pixels a scene holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PixelClass {
    /// No occluder: the whole light is visible (a smooth integrand).
    Lit,
    /// The occluder's edge cuts the light.
    Penumbra,
}

impl PixelClass {
    pub fn name(self) -> &'static str {
        match self {
            PixelClass::Lit => "lit",
            PixelClass::Penumbra => "penumbra",
        }
    }
}

/// The visible side of the occluder's edge: `e . x >= k`.
#[derive(Clone, Copy, Debug)]
pub struct Cut {
    pub e: [f64; 2],
    pub k: f64,
}

impl Cut {
    pub fn visible(&self, x: [f64; 2]) -> bool {
        dot2(self.e, x) >= self.k
    }
}

/// One pixel: shading point, edge and exact reference.
#[derive(Clone, Debug)]
pub struct AreaPixel {
    pub q: [f64; 2],
    pub cut: Cut,
    pub reference: f64,
    pub penumbra: bool,
}

/// `h^2 / (h^2 + |x - q|^2)^2`: the unoccluded integrand.
#[inline]
pub fn integrand(x: [f64; 2], q: [f64; 2], h: f64) -> f64 {
    let (dx, dy) = (x[0] - q[0], x[1] - q[1]);
    let h2 = h * h;
    let d = h2 + dx * dx + dy * dy;
    h2 / (d * d)
}

/// `1/2 int (X dY - Y dX) / (h^2 + X^2 + Y^2)` along the segment from `a` to `b` (relative to
/// the shading point's foot), in closed form:
/// `(a x b) / (2 s) * atan2(|d|^2 s, s^2 + (a . d)(b . d))`, `d = b - a`,
/// `s = sqrt(|d|^2 h^2 + (a x b)^2)` — the difference of the two arctangents of the
/// antiderivative, combined into one `atan2` (no cancellation).
pub fn edge_term(a: [f64; 2], b: [f64; 2], h: f64) -> f64 {
    let d = sub2(b, a);
    let dd = dot2(d, d);
    let axb = cross2(a, b);
    if dd == 0.0 || axb == 0.0 {
        return 0.0;
    }
    let s = (dd * h * h + axb * axb).sqrt();
    0.5 * axb / s * (dd * s).atan2(s * s + dot2(a, d) * dot2(b, d))
}

/// The same contour integral along the arc `x = r (cos t, sin t)`, `t` from `t0` to `t1`.
pub fn arc_term(r: f64, t0: f64, t1: f64, q: [f64; 2], h: f64) -> f64 {
    let pieces = ((t1 - t0).abs() / (PI / 8.0)).ceil().max(1.0) as usize;
    let dt = (t1 - t0) / pieces as f64;
    let k = h * h + dot2(q, q) + r * r;
    (0..pieces)
        .map(|i| {
            let a = t0 + i as f64 * dt;
            integrate(gl16(), a, a + dt, |t| {
                let (s, c) = t.sin_cos();
                let m = q[0] * c + q[1] * s;
                0.5 * (r * r - r * m) / (k - 2.0 * r * m)
            })
        })
        .sum()
}

/// Clips a convex counter-clockwise polygon to `cut` (Sutherland-Hodgman, one plane).
pub fn clip(polygon: &[[f64; 2]], cut: Cut) -> Vec<[f64; 2]> {
    let mut out = Vec::with_capacity(polygon.len() + 1);
    let side = |p: [f64; 2]| dot2(cut.e, p) - cut.k;
    for (i, &p) in polygon.iter().enumerate() {
        let n = polygon[(i + 1) % polygon.len()];
        let (sp, sn) = (side(p), side(n));
        if sp >= 0.0 {
            out.push(p);
        }
        if (sp >= 0.0) != (sn >= 0.0) {
            let t = sp / (sp - sn);
            out.push([p[0] + t * (n[0] - p[0]), p[1] + t * (n[1] - p[1])]);
        }
    }
    out
}

/// Exact irradiance from the visible part of `shape` at the point over `q`.
pub fn irradiance(shape: &Shape, q: [f64; 2], h: f64, cut: Cut) -> f64 {
    match shape {
        Shape::Disk { r } => {
            let r = *r;
            // Visible arc: cos(t - alpha) >= k / r.
            let alpha = cut.e[1].atan2(cut.e[0]);
            let ratio = cut.k / r;
            if ratio >= 1.0 {
                return 0.0;
            }
            if ratio <= -1.0 {
                return arc_term(r, 0.0, TAU, q, h);
            }
            let beta = ratio.acos();
            let (t0, t1) = (alpha - beta, alpha + beta);
            let at = |t: f64| [r * t.cos() - q[0], r * t.sin() - q[1]];
            arc_term(r, t0, t1, q, h) + edge_term(at(t1), at(t0), h)
        }
        _ => {
            let poly = clip(&shape.polygon().unwrap_or_default(), cut);
            (0..poly.len())
                .map(|i| {
                    let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
                    edge_term(sub2(a, q), sub2(b, q), h)
                })
                .sum()
        }
    }
}

/// Whether the edge's line cuts the light's interior.
pub fn cuts(shape: &Shape, cut: Cut) -> bool {
    match shape {
        Shape::Disk { r } => cut.k.abs() < *r,
        _ => {
            let s: Vec<f64> = shape
                .polygon()
                .unwrap_or_default()
                .iter()
                .map(|&p| dot2(cut.e, p) - cut.k)
                .collect();
            s.iter().any(|&x| x > 0.0) && s.iter().any(|&x| x < 0.0)
        }
    }
}

/// The edge of the original mix: through a point uniform in the light's bounding box scaled
/// by 1.5, with a uniform direction and side.
fn mix_edge(shape: &Shape, rng: &mut Rng) -> Cut {
    let [hx, hy] = shape.half_extents();
    let c = [
        1.5 * hx * (2.0 * rng.uniform() - 1.0),
        1.5 * hy * (2.0 * rng.uniform() - 1.0),
    ];
    let a = TAU * rng.uniform();
    let e = [a.cos(), a.sin()];
    Cut { e, k: dot2(e, c) }
}

/// The class probabilities of the mix, `(lit, penumbra, hidden)`: Monte Carlo over `draws`
/// edges of the mix (the class does not depend on `q`), with a fixed seed. With 2^22 draws
/// the standard error of each is below 2.5e-4, small against the MSE figures' 3%.
pub fn mix_weights(shape: &Shape, id: u64, draws: u64) -> [f64; 3] {
    let mut counts = [0u64; 3];
    let mut rng = Rng::new(hash(&[id, 0x006d_6978]));
    let centre_visible = |cut: Cut| match shape {
        Shape::Disk { .. } => cut.visible([0.0, 0.0]),
        _ => shape.polygon().is_some_and(|p| cut.visible(p[0])),
    };
    for _ in 0..draws {
        let cut = mix_edge(shape, &mut rng);
        let class = if cuts(shape, cut) {
            1
        } else if centre_visible(cut) {
            0
        } else {
            2
        };
        counts[class] += 1;
    }
    counts.map(|c| c as f64 / draws as f64)
}

/// One area-light scene: a light, one class of pixels, the warps.
pub struct AreaScene {
    /// The light's name (`square`, `skinny`, `disk`, `triangle`); the scene is `light/class`.
    pub light: &'static str,
    pub class: PixelClass,
    pub shape: Shape,
    pub warps: Vec<AreaWarp>,
    pub id: u64,
}

impl AreaScene {
    /// The four lights, each once per class: `[square/lit, square/penumbra, skinny/lit, ...]`.
    pub fn all() -> Vec<AreaScene> {
        use AreaWarp::*;
        let lights: [(&str, Shape, Vec<AreaWarp>, u64); 4] = [
            ("square", square(), vec![Identity], 1),
            ("skinny", skinny(), vec![Identity], 2),
            ("disk", disk(), DISK_WARPS.to_vec(), 3),
            ("triangle", triangle(), TRIANGLE_WARPS.to_vec(), 4),
        ];
        lights
            .into_iter()
            .flat_map(|(light, shape, warps, id)| {
                [PixelClass::Lit, PixelClass::Penumbra].map(|class| AreaScene {
                    light,
                    class,
                    shape: shape.clone(),
                    warps: warps.clone(),
                    id,
                })
            })
            .collect()
    }

    /// Pixel `index`'s geometry (see the module docs), without its reference: `q`, and the
    /// occluder's edge (for `lit`, a "cut" that keeps the whole plane visible).
    pub fn geometry(&self, index: u64) -> (/* q */ [f64; 2], Cut) {
        let mut rng = Rng::new(hash(&[self.id, self.class as u64, index]));
        let q = [rng.uniform() - 0.5, rng.uniform() - 0.5];
        let cut = match self.class {
            PixelClass::Lit => Cut {
                e: [1.0, 0.0],
                k: f64::NEG_INFINITY,
            },
            PixelClass::Penumbra => loop {
                let cut = mix_edge(&self.shape, &mut rng);
                if cuts(&self.shape, cut) {
                    break cut;
                }
            },
        };
        (q, cut)
    }

    /// Area of the domain the samples are uniform on: the light, or its bounding square for
    /// `pad_zero`.
    fn domain_area(&self, warp: AreaWarp) -> f64 {
        match (warp, &self.shape) {
            (AreaWarp::PadZero, Shape::Disk { r }) => 4.0 * r * r,
            _ => self.shape.area(),
        }
    }

    /// Maps a warped sample to the light plane.
    #[inline]
    fn to_plane2(&self, p: [f32; 2]) -> [f64; 2] {
        match &self.shape {
            Shape::Rect { hx, hy } => [
                (2.0 * p[0] as f64 - 1.0) * hx,
                (2.0 * p[1] as f64 - 1.0) * hy,
            ],
            Shape::Disk { r } => [p[0] as f64 * r, p[1] as f64 * r],
            Shape::Triangle { .. } => [0.0, 0.0],
        }
    }

    #[inline]
    fn to_plane3(&self, b: [f32; 3]) -> [f64; 2] {
        match &self.shape {
            Shape::Triangle { v } => {
                let (b0, b1, b2) = (b[0] as f64, b[1] as f64, b[2] as f64);
                [
                    b0 * v[0][0] + b1 * v[1][0] + b2 * v[2][0],
                    b0 * v[0][1] + b1 * v[1][1] + b2 * v[2][1],
                ]
            }
            _ => [0.0, 0.0],
        }
    }
}

impl AreaScene {
    /// The light-plane points `draw` left in `s` (for the tests): `pad_zero`'s points lie in
    /// the bounding square, the others on the light.
    #[allow(dead_code)]
    pub fn points(&self, warp: usize, spp: usize, s: &Scratch) -> Vec<[f64; 2]> {
        let w = self.warps[warp];
        if w == AreaWarp::Identity {
            s.points[..spp].iter().map(|&p| self.to_plane2(p)).collect()
        } else if w.disk_out() {
            s.out2[..spp].iter().map(|&p| self.to_plane2(p)).collect()
        } else {
            s.out3[..spp].iter().map(|&b| self.to_plane3(b)).collect()
        }
    }

    /// Rejection sampling of the disk: consecutive points of the sampler's sequence, mapped to
    /// the bounding square `[-1, 1]^2` of the unit disk, until `spp` land in it. Returns the
    /// number of points drawn.
    fn rejection(&self, sampler: Sampler, spp: usize, seed: u32, s: &mut Scratch) -> usize {
        let (mut accepted, mut drawn) = (0usize, 0usize);
        while accepted < spp {
            // Enough for the expected 4/pi draws per sample, with a margin; more if needed.
            let chunk = ((spp - accepted) * 4 / 3 + 8).min(s.points.len());
            let pts = &mut s.points[..chunk];
            sampler.fill_from_blocks(seed, drawn as u32, spp as u32, pts);
            for &u in pts.iter() {
                let p = [2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0];
                if p[0] * p[0] + p[1] * p[1] <= 1.0 && accepted < spp {
                    s.out2[accepted] = p;
                    accepted += 1;
                }
            }
            drawn += chunk;
        }
        drawn
    }
}

/// The index-driven triangle warps into `out`: `triangle::basu_owen(_permuted)` of indices
/// `0..N` scrambled by the pixel's seed, or for the `random` row of hashed indices.
fn basu_owen(permuted: bool, sampler: Sampler, seed: u32, out: &mut [[f32; 3]]) {
    match sampler {
        Sampler::Random => {
            let lanes = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
            let (key, scramble) = (u32x8::splat(seed), u32x8::splat(seed | 1));
            for (g, out) in out.chunks_mut(8).enumerate() {
                let index = hash_x8((u32x8::splat(8 * g as u32) + lanes) ^ hash_x8(key));
                let b = if permuted {
                    triangle::basu_owen_permuted_x8(index, scramble)
                } else {
                    triangle::basu_owen_x8(index, scramble)
                };
                let [b0, b1, b2] = b.map(|c| c.to_array());
                for (j, o) in out.iter_mut().enumerate() {
                    *o = [b0[j], b1[j], b2[j]];
                }
            }
        }
        _ if permuted => {
            triangle::basu_owen_permuted_slice(0, seed | 1, out);
        }
        _ => {
            triangle::basu_owen_slice(0, seed | 1, out);
        }
    }
}

impl Scene for AreaScene {
    type Pixel = AreaPixel;

    fn name(&self) -> String {
        format!("{}/{}", self.light, self.class.name())
    }

    fn description(&self) -> String {
        let light = match &self.shape {
            Shape::Rect { hx, hy } if hx == hy => "a unit square light".to_string(),
            Shape::Rect { hx, hy } => format!("a {}:1 rectangular light of unit area", hx / hy),
            Shape::Disk { .. } => "a disk light of unit area".to_string(),
            Shape::Triangle { .. } => "an equilateral triangle light of unit area".to_string(),
        };
        let pixels = match self.class {
            PixelClass::Lit => "fully lit pixels (no occluder)",
            PixelClass::Penumbra => "penumbra pixels (an occluder edge across the light)",
        };
        format!("{light} at distance {HEIGHT} below the shading point; {pixels}")
    }

    fn warps(&self) -> Vec<&'static str> {
        self.warps.iter().map(|w| w.name()).collect()
    }

    fn pixel(&self, index: u64) -> AreaPixel {
        let (q, cut) = self.geometry(index);
        AreaPixel {
            q,
            cut,
            reference: irradiance(&self.shape, q, HEIGHT, cut),
            penumbra: cuts(&self.shape, cut),
        }
    }

    fn reference(&self, pixel: &AreaPixel, _warp: usize) -> f64 {
        pixel.reference
    }

    fn penumbra(&self, pixel: &AreaPixel) -> bool {
        pixel.penumbra
    }

    /// Basu-Owen is index-driven: `random` draws independent random indices (uniform points
    /// on the triangle, as both randomizations are uniform for any index), while `stratified`
    /// and `pmj02bn` both mean the construction itself, indices `0..n` with the pixel's
    /// scramble seed — the same estimator, reported once under each name. The peers'
    /// randomizations of point sets do not apply to it.
    fn alias(&self, warp: usize, sampler: Sampler) -> Option<Sampler> {
        (self.warps[warp].index_driven() && sampler == Sampler::Pmj02bn)
            .then_some(Sampler::Stratified)
    }

    fn applies(&self, warp: usize, sampler: Sampler) -> bool {
        !(self.warps[warp].index_driven() && sampler.is_peer())
    }

    fn draw(&self, warp: usize, sampler: Sampler, spp: usize, seed: u32, s: &mut Scratch) {
        // Rejection consumes about 4/pi points per sample; every buffer holds 2 spp + 16.
        s.reserve(2 * spp + 16);
        let w = self.warps[warp];
        // The sampler's points: one per sample, a quarter of them for the four-sample disk
        // warps; rejection draws its own, the index-driven warps none.
        let points = match w {
            AreaWarp::Rejection => {
                self.rejection(sampler, spp, seed, s);
                return;
            }
            AreaWarp::BasuOwen | AreaWarp::BasuOwenPermuted => {
                let permuted = w == AreaWarp::BasuOwenPermuted;
                return basu_owen(permuted, sampler, seed, &mut s.out3[..spp]);
            }
            AreaWarp::Polar4 | AreaWarp::Concentric4 => spp / 4,
            _ => spp,
        };
        let pts = &mut s.points[..points];
        sampler.fill(seed, pts);
        let (out2, out3) = (&mut s.out2[..spp], &mut s.out3[..spp]);
        match w {
            AreaWarp::Polar => _ = disk::polar_slice(pts, out2),
            AreaWarp::Concentric => _ = disk::concentric_slice(pts, out2),
            AreaWarp::Polar4 => _ = disk::polar4_slice(pts, out2),
            AreaWarp::Concentric4 => _ = disk::concentric4_slice(pts, out2),
            AreaWarp::PadZero => {
                for (o, u) in out2.iter_mut().zip(pts.iter()) {
                    *o = [2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0];
                }
            }
            AreaWarp::Uniform => _ = triangle::uniform_slice(pts, out3),
            AreaWarp::Sqrt => _ = triangle::sqrt_map_slice(pts, out3),
            _ => {}
        }
    }

    fn evaluate(&self, pixel: &AreaPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        // (The loops below are `points` fused with the integrand.)
        let (q, cut, h) = (pixel.q, pixel.cut, HEIGHT);
        let f = |x: [f64; 2]| {
            if cut.visible(x) {
                integrand(x, q, h)
            } else {
                0.0
            }
        };
        let w = self.warps[warp];
        let sum: f64 = if w == AreaWarp::Identity {
            s.points[..spp].iter().map(|&p| f(self.to_plane2(p))).sum()
        } else if w == AreaWarp::PadZero {
            s.out2[..spp]
                .iter()
                .filter(|p| p[0] * p[0] + p[1] * p[1] <= 1.0)
                .map(|&p| f(self.to_plane2(p)))
                .sum()
        } else if w.disk_out() {
            s.out2[..spp].iter().map(|&p| f(self.to_plane2(p))).sum()
        } else {
            s.out3[..spp].iter().map(|&b| f(self.to_plane3(b))).sum()
        };
        self.domain_area(w) * sum / spp as f64
    }
}
