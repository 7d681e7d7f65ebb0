//! Area lights sampled by area and by solid angle (`warpcore::spherical`), at light size /
//! distance 4, 1 and 0.25: the triangle, the square and the 16:1 rectangle of `area.rs`
//! (unit area, in the plane `z = 0`), the shading point at height `h = 1 / ratio` over a
//! foot `q` uniform in `[-1/2, 1/2]^2`, the same pixel classes (`lit`, `penumbra`) and the
//! same exact references ([`area::irradiance`] at height `h`).
//!
//! **Estimators.** By area: `E_N = (A / N) sum h^2 / r^4 V` (as in `area.rs`; the triangle
//! through `triangle::uniform` or index-driven `basu_owen_permuted`, the rectangles through
//! the identity). By solid angle: `E_N = (1 / N) sum cos(theta) V / pdf` with `pdf = 1 /
//! omega` from `spherical::triangle` / `spherical::rectangle` and `cos(theta) = h / r`: the
//! `cos' / r^2` factor is gone, only the receiver's cosine and the visibility remain.
//!
//! **Cosine-aware variant** (`solid_angle_cos`): `u` is first warped by the
//! bilinear density whose corner values are the receiver's clamped cosine `max(0, n . w)`
//! towards the light's corners (the idea of Hart, Pharr, Mueller, Lopes, McGuire and Shirley
//! 2020, "Practical Product Sampling by Fitting and Composing Warps", EGSR, which pbrt-v4's
//! triangle light uses), then mapped by the spherical map; the density is the solid-angle
//! density times the bilinear one. The square's corners `(u0, u1) = (0, 0), (1, 0), (0, 1),
//! (1, 1)` map to the triangle's `v1, v1, v0, v2` (Arvo's apex `v1` is the whole side `u1 =
//! 0`) and to the rectangle's `corner`, `+ ex`, `+ ey`, `+ ex + ey`. The receiver's normal
//! faces the light plane (`n = -z`). Exactly unbiased: the bilinear warp is a bijection of
//! the open square with a density positive inside it; weights that are all 0 (or not
//! finite) leave `u` unchanged with density factor 1. Measured first here, then kept in the
//! library (`spherical::triangle_cosine`, `rectangle_cosine`), which the scenes now call.
//!
//! **Timings.** `draw` (what the report times) runs the sampler and the warp for the shading
//! point over the light's centre, through the slice forms; `evaluate` re-runs the solid-angle
//! map for the pixel's own shading point (the map depends on it), untimed.

use crate::area::{self, AreaPixel, AreaScene, PixelClass, Shape};
use crate::run::{Scene, Scratch};
use crate::samplers::Sampler;
use warpcore::{spherical, triangle};

/// How the samples reach the light.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Uniform by area: identity (rectangles) or `triangle::uniform`.
    Area,
    /// Uniform by area, index-driven `triangle::basu_owen_permuted` (triangle only).
    AreaBasuOwen,
    /// Uniform by solid angle.
    SolidAngle,
    /// By solid angle after the bilinear cosine warp (see the module docs).
    SolidAngleCos,
}

impl Domain {
    fn name(self) -> &'static str {
        match self {
            Domain::Area => "area",
            Domain::AreaBasuOwen => "area_basu_owen_permuted",
            Domain::SolidAngle => "solid_angle",
            Domain::SolidAngleCos => "solid_angle_cos",
        }
    }
}

/// One light at one size / distance ratio, one class of pixels.
pub struct SolidAngleScene {
    pub base: AreaScene,
    pub ratio: f64,
    pub domains: Vec<Domain>,
}

/// The ratios of the report.
pub const RATIOS: [f64; 3] = [4.0, 1.0, 0.25];

impl SolidAngleScene {
    /// `[triangle, square, skinny] x RATIOS x [lit, penumbra]`, in pairs (lit, penumbra).
    pub fn all() -> Vec<SolidAngleScene> {
        let mut out = Vec::new();
        for base in AreaScene::all() {
            let domains = match base.light {
                "triangle" => vec![
                    Domain::Area,
                    Domain::AreaBasuOwen,
                    Domain::SolidAngle,
                    Domain::SolidAngleCos,
                ],
                "square" | "skinny" => {
                    vec![Domain::Area, Domain::SolidAngle, Domain::SolidAngleCos]
                }
                _ => continue,
            };
            for ratio in RATIOS {
                out.push(SolidAngleScene {
                    base: AreaScene {
                        light: base.light,
                        class: base.class,
                        shape: base.shape.clone(),
                        warps: base.warps.clone(),
                        id: base.id,
                    },
                    ratio,
                    domains: domains.clone(),
                });
            }
        }
        // Group each (light, ratio) as (lit, penumbra).
        out.sort_by(|a, b| {
            (a.base.id, (a.ratio * 100.0) as u64, a.base.class as u8).cmp(&(
                b.base.id,
                (b.ratio * 100.0) as u64,
                b.base.class as u8,
            ))
        });
        out
    }

    pub fn light_name(&self) -> String {
        format!("sa_{}_r{}", self.base.light, self.ratio)
    }

    fn height(&self) -> f64 {
        1.0 / self.ratio
    }

    /// The shading point over `q`.
    fn point(&self, q: [f64; 2]) -> [f32; 3] {
        [q[0] as f32, q[1] as f32, self.height() as f32]
    }

    /// `(triangle vertices | rectangle corner, ex, ey)` in 3D, `z = 0`.
    fn light3(&self) -> [[f32; 3]; 3] {
        match &self.base.shape {
            Shape::Triangle { v } => v.map(|p| [p[0] as f32, p[1] as f32, 0.0]),
            Shape::Rect { hx, hy } => [
                [-*hx as f32, -*hy as f32, 0.0],
                [2.0 * *hx as f32, 0.0, 0.0],
                [0.0, 2.0 * *hy as f32, 0.0],
            ],
            Shape::Disk { .. } => [[0.0; 3]; 3],
        }
    }

    /// Solid-angle samples for shading point `p`: plane points and `1 / pdf`.
    fn solid_angle_point(
        &self,
        l: &[[f32; 3]; 3],
        p: [f32; 3],
        u: [f32; 2],
        cosine: bool,
    ) -> ([f64; 2], f64) {
        match &self.base.shape {
            Shape::Triangle { v } => {
                let (b, pdf) = if cosine {
                    spherical::triangle_cosine(*l, p, RECEIVER_NORMAL, u)
                } else {
                    spherical::triangle(*l, p, u)
                };
                let (b0, b1, b2) = (b[0] as f64, b[1] as f64, b[2] as f64);
                (
                    [
                        b0 * v[0][0] + b1 * v[1][0] + b2 * v[2][0],
                        b0 * v[0][1] + b1 * v[1][1] + b2 * v[2][1],
                    ],
                    pdf as f64,
                )
            }
            _ => {
                let ([s, t], pdf) = if cosine {
                    spherical::rectangle_cosine(l[0], l[1], l[2], p, RECEIVER_NORMAL, u)
                } else {
                    spherical::rectangle(l[0], l[1], l[2], p, u)
                };
                (
                    [
                        l[0][0] as f64 + s as f64 * l[1][0] as f64,
                        l[0][1] as f64 + t as f64 * l[2][1] as f64,
                    ],
                    pdf as f64,
                )
            }
        }
    }
}

impl Scene for SolidAngleScene {
    type Pixel = AreaPixel;

    fn name(&self) -> String {
        format!("{}/{}", self.light_name(), self.base.class.name())
    }

    fn description(&self) -> String {
        let light = match &self.base.shape {
            Shape::Rect { hx, hy } if hx == hy => "a unit square light".to_string(),
            Shape::Rect { hx, hy } => format!("a {}:1 rectangular light of unit area", hx / hy),
            _ => "an equilateral triangle light of unit area".to_string(),
        };
        let pixels = match self.base.class {
            PixelClass::Lit => "fully lit pixels",
            PixelClass::Penumbra => "penumbra pixels",
        };
        format!(
            "{light} at distance {} (size / distance {}), sampled by area and by solid angle; {pixels}",
            self.height(),
            self.ratio
        )
    }

    fn warps(&self) -> Vec<&'static str> {
        self.domains.iter().map(|d| d.name()).collect()
    }

    fn pixel(&self, index: u64) -> AreaPixel {
        let (q, cut) = self.base.geometry(index);
        AreaPixel {
            q,
            cut,
            reference: area::irradiance(&self.base.shape, q, self.height(), cut),
            penumbra: area::cuts(&self.base.shape, cut),
        }
    }

    fn reference(&self, pixel: &AreaPixel, _warp: usize) -> f64 {
        pixel.reference
    }

    fn penumbra(&self, pixel: &AreaPixel) -> bool {
        pixel.penumbra
    }

    fn alias(&self, warp: usize, sampler: Sampler) -> Option<Sampler> {
        (self.domains[warp] == Domain::AreaBasuOwen && sampler == Sampler::Pmj02bn)
            .then_some(Sampler::Stratified)
    }

    fn applies(&self, warp: usize, sampler: Sampler) -> bool {
        !(self.domains[warp] == Domain::AreaBasuOwen && sampler.is_peer())
    }

    fn draw(&self, warp: usize, sampler: Sampler, spp: usize, seed: u32, s: &mut Scratch) {
        s.reserve(spp + 16);
        let pts = &mut s.points[..spp];
        match self.domains[warp] {
            Domain::AreaBasuOwen => {
                triangle::basu_owen_permuted_slice(0, seed | 1, &mut s.out3[..spp]);
            }
            Domain::Area => {
                sampler.fill(seed, pts);
                if matches!(self.base.shape, Shape::Triangle { .. }) {
                    triangle::uniform_slice(pts, &mut s.out3[..spp]);
                }
            }
            d @ (Domain::SolidAngle | Domain::SolidAngleCos) => {
                sampler.fill(seed, pts);
                // The timed warp: the shading point over the light's centre.
                let (l, p, n) = (self.light3(), self.point([0.0, 0.0]), RECEIVER_NORMAL);
                let cos = d == Domain::SolidAngleCos;
                match &self.base.shape {
                    Shape::Triangle { .. } => {
                        let mut out = [[0.0f32; 4]; 64];
                        for chunk in pts.chunks(64) {
                            if cos {
                                spherical::triangle_cosine_slice(l, p, n, chunk, &mut out);
                            } else {
                                spherical::triangle_slice(l, p, chunk, &mut out);
                            }
                        }
                    }
                    _ => {
                        let mut out = [[0.0f32; 3]; 64];
                        for chunk in pts.chunks(64) {
                            if cos {
                                spherical::rectangle_cosine_slice(
                                    l[0], l[1], l[2], p, n, chunk, &mut out,
                                );
                            } else {
                                spherical::rectangle_slice(l[0], l[1], l[2], p, chunk, &mut out);
                            }
                        }
                    }
                }
            }
        }
    }

    fn evaluate(&self, pixel: &AreaPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        let (q, cut, h) = (pixel.q, pixel.cut, self.height());
        let visible = |x: [f64; 2]| cut.visible(x);
        match self.domains[warp] {
            d @ (Domain::SolidAngle | Domain::SolidAngleCos) => {
                let (l, p) = (self.light3(), self.point(q));
                let sum: f64 = s.points[..spp]
                    .iter()
                    .map(|&u| {
                        let (x, pdf) = self.solid_angle_point(&l, p, u, d == Domain::SolidAngleCos);
                        if !visible(x) || pdf <= 0.0 {
                            return 0.0;
                        }
                        let (dx, dy) = (x[0] - q[0], x[1] - q[1]);
                        let r = (dx * dx + dy * dy + h * h).sqrt();
                        (h / r) / pdf
                    })
                    .sum();
                sum / spp as f64
            }
            d => {
                let f = |x: [f64; 2]| {
                    if visible(x) {
                        area::integrand(x, q, h)
                    } else {
                        0.0
                    }
                };
                let sum: f64 = match (&self.base.shape, d) {
                    (Shape::Triangle { v }, _) => s.out3[..spp]
                        .iter()
                        .map(|b| {
                            let (b0, b1, b2) = (b[0] as f64, b[1] as f64, b[2] as f64);
                            f([
                                b0 * v[0][0] + b1 * v[1][0] + b2 * v[2][0],
                                b0 * v[0][1] + b1 * v[1][1] + b2 * v[2][1],
                            ])
                        })
                        .sum(),
                    (Shape::Rect { hx, hy }, _) => s.points[..spp]
                        .iter()
                        .map(|p| {
                            f([
                                (2.0 * p[0] as f64 - 1.0) * hx,
                                (2.0 * p[1] as f64 - 1.0) * hy,
                            ])
                        })
                        .sum(),
                    _ => 0.0,
                };
                self.base.shape.area() * sum / spp as f64
            }
        }
    }
}

/// The receiver's normal in the report's scenes: facing the light plane.
const RECEIVER_NORMAL: [f32; 3] = [0.0, 0.0, -1.0];
