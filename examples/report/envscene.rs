//! Environment-map scenes: a shading point lit by an environment map, with a clamped cosine
//! lobe around its normal `n` and an occluder that hides the half-space `m . w < 0`:
//!
//! ```text
//! I = int_S2 L(w) max(0, n . w) [m . w >= 0] dw
//! ```
//!
//! **Pixels.** Pixel `i` draws `n` and `m` independently and uniformly on the sphere from a
//! hash of `(scene, i)`. Every pixel's cut crosses its cosine lobe (two great circles always
//! meet), so all pixels are "in penumbra"; in about a quarter of them the sun (or a lamp) is
//! both in the lobe and visible. The `/lit` class of a scene (`envmap:<name>/lit`) drops the
//! occluder: the same pixels' cosine lobes, unoccluded (a smooth integrand but for the map's
//! own edges).
//!
//! **Maps.** Each scene has one piecewise-constant radiance map per parameterization: a
//! lat-long map (`w x h`) and an equal-area octahedral map of about the same texel count
//! (`s x s`, `s = round(sqrt(w h))`). The built-in maps are procedural functions rasterized
//! into each parameterization (each texel the mean of an 8 x 8 grid of point values); a
//! `--envmap` PFM file is taken as its lat-long map (luminance, negative and NaN as 0) and
//! resampled by `warpcore::envmap::image::equirect_to_equal_area` (4 x 4 points per texel).
//!
//! **Warps** (`warp` = distribution + parameterization):
//!
//! | warp | distribution over the map's square | weights | direction | density over directions |
//! |---|---|---|---|---|
//! | `marginal_equirect` | `MarginalConditional` | luminance x `sin(theta)` of the row (`equirect_solid_angle_weights`) | `sphere::equirect` | `equirect_pdf_to_solid_angle(pdf, v)` |
//! | `hierarchical_equirect` | `Hierarchical` | the same | the same | the same |
//! | `marginal_equal_area` | `MarginalConditional` | luminance | `sphere::equal_area` | `equal_area_pdf_to_solid_angle(pdf)` |
//! | `hierarchical_equal_area` | `Hierarchical` | luminance | the same | the same |
//!
//! **Estimator.** `(1 / N) sum L_t max(0, n . w_i) [m . w_i >= 0] / p(w_i)`, with `L_t` the
//! radiance of the texel the sample came from (its `uv` lies in it exactly) and `p` the
//! solid-angle density (a sample whose density converts to 0 — only exactly at the lat-long
//! pole — contributes 0, as in pbrt and Mitsuba).
//!
//! **MIS warps** (`hierarchical_equirect_mis`, `hierarchical_equal_area_mis`; issue 25; for
//! random points, pmj02bn and Sobol' only, the report's time budget): the hierarchical
//! distribution built from MIS-compensated
//! weights (`Compensation::Equirect` / `Compensation::Uniform` with fraction 1: the map minus
//! its solid-angle average, clamped at 0; Karlik et al. 2019, pbrt-v4's
//! `compensatedDistribution`, Mitsuba 3's `mis_compensation`), combined with cosine-weighted
//! BSDF sampling by the balance heuristic: each of the `N` sample points gives one map sample
//! `w_l` and one BSDF sample `w_b` (the point shifted by (1/2, 1/2) modulo 1, warped by
//! `sphere::cosine_hemisphere` around `n`), and the estimate is
//! `(1 / N) sum [f(w_l) / (p_l(w_l) + p_b(w_l)) + f(w_b) / (p_l(w_b) + p_b(w_b))]` with
//! `p_b = max(0, n . w) / pi`. Two integrand evaluations per point: compare these rows at
//! equal cost with the plain rows at twice the sample count. The environment variable
//! `REPORT_MIS_FRACTION` changes the fraction (0: MIS without compensation), for studies.
//!
//! **Reference**: [`crate::sphere_ref`], exact for each parameterization's map.

use crate::math::{Rng, dot3, hash};
use crate::run::{Scene, Scratch};
use crate::samplers::Sampler;
use crate::sphere_ref::{EqualArea, Grid, LatLong, Param};
use std::f64::consts::{PI, TAU};
use warpcore::envmap::{
    self, Compensation, Hierarchical, MarginalConditional, Sample, Word, image,
};
use warpcore::sphere;

pub const WARPS: [&str; 6] = [
    "marginal_equirect",
    "hierarchical_equirect",
    "marginal_equal_area",
    "hierarchical_equal_area",
    "hierarchical_equirect_mis",
    "hierarchical_equal_area_mis",
];

/// The plain warp (`0..4`) whose distribution and parameterization a warp uses.
fn base(warp: usize) -> usize {
    [0, 1, 2, 3, 1, 3].get(warp).copied().unwrap_or(3)
}

/// The compensation fraction of the `_mis` warps: 1, or `REPORT_MIS_FRACTION`.
fn mis_fraction() -> f32 {
    std::env::var("REPORT_MIS_FRACTION")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1.0)
}

/// Buffers of the environment-map draws.
#[derive(Default)]
pub struct EnvScratch {
    pub samples: Vec<Sample>,
    pub uv: Vec<[f32; 2]>,
    /// Densities with respect to solid angle.
    pub pdf: Vec<f32>,
}

impl EnvScratch {
    pub fn reserve(&mut self, n: usize) {
        if self.samples.len() < n {
            let zero = Sample {
                uv: [0.0; 2],
                pdf: 0.0,
                texel: [0, 0],
            };
            self.samples.resize(n, zero);
            self.uv.resize(n, [0.0; 2]);
            self.pdf.resize(n, 0.0);
        }
    }
}

fn leak(len: usize) -> &'static mut [Word] {
    Vec::leak(vec![0 as Word; len])
}

/// One parameterization of a scene: its map, reference grid and both distributions.
pub struct Side<P: Param> {
    pub grid: Grid<P>,
    /// Radiance per texel (row-major, row 0 at `v = 0`).
    pub radiance: Vec<f64>,
    pub marginal: MarginalConditional<'static>,
    pub hierarchical: Hierarchical<'static>,
    /// The hierarchical distribution of MIS-compensated weights (the `_mis` warps).
    pub hierarchical_mis: Hierarchical<'static>,
}

impl<P: Param> Side<P> {
    /// `luminance` is the map; `weights` what the distributions sample by.
    pub fn new(
        param: P,
        width: usize,
        height: usize,
        luminance: &[f32],
        weights: Vec<f32>,
        compensation: Compensation,
    ) -> Result<Self, envmap::Error> {
        let hierarchical_mis = Hierarchical::new_compensated(
            &weights,
            width,
            height,
            compensation,
            leak(Hierarchical::storage_len(width, height)),
        )?;
        let marginal = MarginalConditional::new(
            &weights,
            width,
            height,
            leak(MarginalConditional::storage_len(width, height)),
        )?;
        let hierarchical = Hierarchical::new(
            &weights,
            width,
            height,
            leak(Hierarchical::storage_len(width, height)),
        )?;
        Ok(Side {
            grid: Grid::new(param, width, height),
            radiance: luminance
                .iter()
                .map(|&l| if l > 0.0 { l as f64 } else { 0.0 })
                .collect(),
            marginal,
            hierarchical,
            hierarchical_mis,
        })
    }

    pub fn width(&self) -> usize {
        self.grid.width
    }
    pub fn height(&self) -> usize {
        self.grid.height
    }

    /// Largest over smallest positive texel radiance.
    pub fn dynamic_range(&self) -> f64 {
        let pos = self.radiance.iter().filter(|&&l| l > 0.0);
        let max = pos.clone().fold(0.0, |a: f64, &b| a.max(b));
        let min = pos.fold(f64::MAX, |a: f64, &b| a.min(b));
        max / min
    }
}

/// A procedural radiance function of the direction.
pub type Radiance = fn([f64; 3]) -> f64;

/// Angle between two unit vectors.
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = dot3(a, b).clamp(-1.0, 1.0);
    c.acos()
}

fn from_angles(azimuth_deg: f64, elevation_deg: f64) -> [f64; 3] {
    let (a, e) = (azimuth_deg.to_radians(), elevation_deg.to_radians());
    [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
}

/// A clear sky with a sun: sun disc of angular radius 1.5 deg at elevation 35 deg, radiance
/// 50,000; sky 2 (zenith) to 8 (horizon) plus a circumsolar glow; ground 1 to 1.4. Its
/// darkest texel is 1 and the sun's fully covered texels 50,000: dynamic range 50,000 : 1.
/// The sun carries about three quarters of the map's power.
pub fn sky(d: [f64; 3]) -> f64 {
    let sun = from_angles(60.0, 35.0);
    let gamma = angle(d, sun);
    if gamma < 1.5f64.to_radians() {
        return 50_000.0;
    }
    if d[2] >= 0.0 {
        2.0 + 6.0 * (1.0 - d[2]).powi(3) + 30.0 * (-gamma / 0.12).exp()
    } else {
        let phi = d[1].atan2(d[0]);
        1.2 + 0.2 * (6.0 * phi).cos() * (10.0 * d[2]).cos()
    }
}

/// A room: floor 1 to 1.5, walls 1.5 to 3.5, ceiling 3, a window (40) and three ceiling lamps
/// (discs of angular radius 6 deg, radiance 300): dynamic range 300 : 1.
pub fn interior(d: [f64; 3]) -> f64 {
    for (az, el) in [(30.0, 60.0), (150.0, 55.0), (270.0, 70.0)] {
        if angle(d, from_angles(az, el)) < 6f64.to_radians() {
            return 300.0;
        }
    }
    let phi = d[1].atan2(d[0]).rem_euclid(TAU).to_degrees();
    let elevation = d[2].clamp(-1.0, 1.0).asin().to_degrees();
    if (200.0..250.0).contains(&phi) && (5.0..35.0).contains(&elevation) {
        return 40.0;
    }
    if d[2] < -0.3 {
        1.25 + 0.25 * (8.0 * phi.to_radians()).cos() * (6.0 * d[2]).cos()
    } else if d[2] > 0.75 {
        3.0
    } else {
        2.5 + (4.0 * phi.to_radians()).cos()
    }
}

/// Rasterizes `f` into a `w x h` map of `param`: each texel the mean of 8 x 8 point values.
pub fn rasterize<P: Param>(param: &P, w: usize, h: usize, f: Radiance) -> Vec<f32> {
    let k = 8;
    (0..h)
        .flat_map(|j| (0..w).map(move |i| (i, j)))
        .map(|(i, j)| {
            let mut acc = 0.0;
            for b in 0..k {
                for a in 0..k {
                    let u = [
                        (i as f64 + (a as f64 + 0.5) / k as f64) / w as f64,
                        (j as f64 + (b as f64 + 0.5) / k as f64) / h as f64,
                    ];
                    acc += f(param.dir(u));
                }
            }
            (acc / (k * k) as f64) as f32
        })
        .collect()
}

/// An environment-map scene: a map, and its pixels with or without the occluder.
pub struct EnvScene {
    pub name: String,
    pub latlong: Side<LatLong>,
    pub equal_area: Side<EqualArea>,
    pub id: u64,
}

/// One pixel: normal, occluder plane normal and the two references.
#[derive(Clone, Debug)]
pub struct EnvPixel {
    pub n: [f64; 3],
    pub m: [f64; 3],
    /// Per parameterization: lat-long, equal-area.
    pub reference: [f64; 2],
}

impl EnvScene {
    /// A scene from its lat-long luminance map (`w x h`, row 0 around `+z`) and its
    /// equal-area luminance map (`s x s`).
    pub fn new(
        name: &str,
        latlong: (usize, usize, Vec<f32>),
        equal_area: (usize, Vec<f32>),
    ) -> Result<Self, envmap::Error> {
        let (w, h, mut ll) = latlong;
        let (s, mut ea) = equal_area;
        // Scale both maps so that the lat-long map's mean radiance over the sphere is 1
        // (unoccluded irradiance then is at most pi): MSE figures comparable across maps.
        let power: f64 = (0..h)
            .map(|j| {
                let (t0, t1) = (PI * j as f64 / h as f64, PI * (j + 1) as f64 / h as f64);
                let omega = TAU / w as f64 * (t0.cos() - t1.cos());
                omega
                    * ll[j * w..(j + 1) * w]
                        .iter()
                        .map(|&l| l.max(0.0) as f64)
                        .sum::<f64>()
            })
            .sum();
        let scale = if power > 0.0 {
            (4.0 * PI / power) as f32
        } else {
            1.0
        };
        for l in ll.iter_mut().chain(ea.iter_mut()) {
            *l *= scale;
        }
        let mut ll_weights: Vec<f32> = ll.iter().map(|&l| if l > 0.0 { l } else { 0.0 }).collect();
        image::equirect_solid_angle_weights(&mut ll_weights, w, h)?;
        let ea_weights: Vec<f32> = ea.iter().map(|&l| if l > 0.0 { l } else { 0.0 }).collect();
        Ok(EnvScene {
            name: format!("envmap:{name}"),
            latlong: Side::new(
                LatLong,
                w,
                h,
                &ll,
                ll_weights,
                Compensation::Equirect(mis_fraction()),
            )?,
            equal_area: Side::new(
                EqualArea,
                s,
                s,
                &ea,
                ea_weights,
                Compensation::Uniform(mis_fraction()),
            )?,
            id: hash(&name.bytes().map(u64::from).collect::<Vec<_>>()),
        })
    }

    /// The scene's pixels with the occluder (`lit = false`, the scene's own name) or without
    /// it (`lit = true`, `<name>/lit`), sharing the maps and distributions.
    pub fn view(&self, lit: bool) -> EnvView<'_> {
        EnvView { scene: self, lit }
    }

    /// A built-in procedural map, rasterized at `w x h` lat-long and the matching square.
    pub fn procedural(name: &str, f: Radiance, w: usize, h: usize) -> Result<Self, envmap::Error> {
        let s = ((w * h) as f64).sqrt().round() as usize;
        let ll = rasterize(&LatLong, w, h, f);
        let ea = rasterize(&EqualArea, s, s, f);
        Self::new(name, (w, h, ll), (s, ea))
    }

    /// A scene from a lat-long luminance image; the equal-area map is resampled from it.
    pub fn from_latlong(
        name: &str,
        w: usize,
        h: usize,
        luminance: Vec<f32>,
    ) -> Result<Self, envmap::Error> {
        let s = ((w * h) as f64).sqrt().round() as usize;
        let src: Vec<[f32; 1]> = luminance.iter().map(|&l| [l]).collect();
        let mut dst = vec![[0.0f32; 1]; s * s];
        image::equirect_to_equal_area(&src, w, h, &mut dst, s, 4)?;
        let ea = dst.iter().map(|v| v[0]).collect();
        Self::new(name, (w, h, luminance), (s, ea))
    }

    /// The built-in scenes: `envmap:sky` and `envmap:interior`, 256 x 128 lat-long and
    /// 181 x 181 equal-area.
    pub fn builtin() -> Vec<EnvScene> {
        let make = |name: &str, f: Radiance| EnvScene::procedural(name, f, 256, 128).ok();
        // Built on two threads: the reference grids take a moment each.
        let (sky, interior) = std::thread::scope(|s| {
            let a = s.spawn(|| make("sky", sky));
            let b = make("interior", interior);
            (a.join().ok().flatten(), b)
        });
        sky.into_iter().chain(interior).collect()
    }

    pub fn geometry(&self, index: u64) -> ([f64; 3], [f64; 3]) {
        let mut rng = Rng::new(hash(&[self.id, index]));
        (rng.direction(), rng.direction())
    }
}

/// One pixel class of an environment-map scene: with the occluder (the scene's own name) or
/// without it (`/lit`). The maps and distributions are the scene's.
#[derive(Clone, Copy)]
pub struct EnvView<'a> {
    pub scene: &'a EnvScene,
    pub lit: bool,
}

impl std::ops::Deref for EnvView<'_> {
    type Target = EnvScene;
    fn deref(&self) -> &EnvScene {
        self.scene
    }
}

impl Scene for EnvView<'_> {
    type Pixel = EnvPixel;

    fn name(&self) -> String {
        if self.lit {
            format!("{}/lit", self.scene.name)
        } else {
            self.scene.name.clone()
        }
    }

    fn description(&self) -> String {
        let (ll, ea) = (&self.latlong, &self.equal_area);
        format!(
            "lat-long map {}x{} (dynamic range {:.0}:1), equal-area map {}x{} ({:.0}:1), {}",
            ll.width(),
            ll.height(),
            ll.dynamic_range(),
            ea.width(),
            ea.height(),
            ea.dynamic_range(),
            if self.lit {
                "cosine lobe, no occluder"
            } else {
                "cosine lobe and occluder half-space"
            }
        )
    }

    fn warps(&self) -> Vec<&'static str> {
        WARPS.to_vec()
    }

    /// The `_mis` rows (two integrand evaluations per point) run for random points, pmj02bn
    /// and Sobol' only: the report's time budget.
    fn applies(&self, warp: usize, sampler: Sampler) -> bool {
        warp < 4
            || matches!(
                sampler,
                Sampler::Random | Sampler::Pmj02bn | Sampler::SobolOwen
            )
    }

    fn pixel(&self, index: u64) -> EnvPixel {
        let (n, m) = self.geometry(index);
        // Without the occluder: the half-space m . w >= 0 with m = n hides only directions
        // the lobe already gives weight 0, so the references and the estimator are the
        // unoccluded ones.
        let m = if self.lit { n } else { m };
        EnvPixel {
            n,
            m,
            reference: [
                self.latlong.grid.integral(&self.latlong.radiance, n, m),
                self.equal_area
                    .grid
                    .integral(&self.equal_area.radiance, n, m),
            ],
        }
    }

    fn reference(&self, pixel: &EnvPixel, warp: usize) -> f64 {
        pixel.reference[base(warp) / 2]
    }

    fn penumbra(&self, _pixel: &EnvPixel) -> bool {
        !self.lit
    }

    fn draw(&self, warp: usize, sampler: Sampler, spp: usize, seed: u32, s: &mut Scratch) {
        s.reserve(spp);
        sampler.fill(seed, &mut s.points[..spp]);
        let env = &mut s.env;
        let (points, samples) = (&s.points[..spp], &mut env.samples[..spp]);
        match warp {
            0 => self.latlong.marginal.sample_slice(points, samples),
            1 => self.latlong.hierarchical.sample_slice(points, samples),
            2 => self.equal_area.marginal.sample_slice(points, samples),
            3 => self.equal_area.hierarchical.sample_slice(points, samples),
            4 => self.latlong.hierarchical_mis.sample_slice(points, samples),
            _ => self
                .equal_area
                .hierarchical_mis
                .sample_slice(points, samples),
        };
        let warp = base(warp);
        for (uv, smp) in env.uv.iter_mut().zip(samples.iter()) {
            *uv = smp.uv;
        }
        let (uv, dirs, pdf) = (&env.uv[..spp], &mut s.out3[..spp], &mut env.pdf[..spp]);
        if warp < 2 {
            sphere::equirect_slice(uv, dirs);
            for (p, smp) in pdf.iter_mut().zip(samples.iter()) {
                *p = image::equirect_pdf_to_solid_angle(smp.pdf, smp.uv[1]);
            }
        } else {
            sphere::equal_area_slice(uv, dirs);
            for (p, smp) in pdf.iter_mut().zip(samples.iter()) {
                *p = image::equal_area_pdf_to_solid_angle(smp.pdf);
            }
        }
    }

    fn evaluate(&self, pixel: &EnvPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        if warp >= 4 {
            return self.evaluate_mis(pixel, base(warp), spp, s);
        }
        let (radiance, width) = if warp < 2 {
            (&self.latlong.radiance, self.latlong.width())
        } else {
            (&self.equal_area.radiance, self.equal_area.width())
        };
        let (n, m) = (pixel.n, pixel.m);
        let mut sum = 0.0;
        for k in 0..spp {
            let smp = &s.env.samples[k];
            let d = s.out3[k].map(f64::from);
            let c = dot3(n, d);
            let p = s.env.pdf[k] as f64;
            if c <= 0.0 || dot3(m, d) < 0.0 || p <= 0.0 {
                continue;
            }
            let t = smp.texel[1] as usize * width + smp.texel[0] as usize;
            sum += radiance[t] * c / p;
        }
        sum / spp as f64
    }
}

impl EnvView<'_> {
    /// The `_mis` estimator (see the module docs): `warp` (1 or 3) names the
    /// parameterization, whose compensated hierarchical tables `draw` sampled.
    fn evaluate_mis(&self, pixel: &EnvPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        let latlong = warp < 2;
        let (radiance, width, height) = if latlong {
            (
                &self.latlong.radiance,
                self.latlong.width(),
                self.latlong.height(),
            )
        } else {
            let ea = &self.equal_area;
            (&ea.radiance, ea.width(), ea.height())
        };
        // The light technique's density over directions at `uv`.
        let light_pdf = |uv: [f32; 2]| -> f64 {
            let p = if latlong {
                self.latlong.hierarchical_mis.pdf(uv)
            } else {
                self.equal_area.hierarchical_mis.pdf(uv)
            };
            f64::from(if latlong {
                image::equirect_pdf_to_solid_angle(p, uv[1])
            } else {
                image::equal_area_pdf_to_solid_angle(p)
            })
        };
        let (n, m) = (pixel.n, pixel.m);
        let frame = basis(n);
        let mut sum = 0.0;
        for k in 0..spp {
            // The map's sample.
            let smp = &s.env.samples[k];
            let d = s.out3[k].map(f64::from);
            let c = dot3(n, d);
            let p = s.env.pdf[k] as f64;
            if c > 0.0 && dot3(m, d) >= 0.0 && p > 0.0 {
                let t = smp.texel[1] as usize * width + smp.texel[0] as usize;
                sum += radiance[t] * c / (p + c / PI);
            }
            // The BSDF's sample: the point shifted by (1/2, 1/2), cosine-weighted around n.
            let u = s.points[k].map(|x| {
                let y = x + 0.5;
                if y >= 1.0 { y - 1.0 } else { y }
            });
            let l = sphere::cosine_hemisphere(u).map(f64::from);
            let d = [0, 1, 2].map(|i| frame[0][i] * l[0] + frame[1][i] * l[1] + n[i] * l[2]);
            let c = dot3(n, d);
            if c <= 0.0 || dot3(m, d) < 0.0 {
                continue;
            }
            let df = d.map(|x| x as f32);
            let uv = if latlong {
                sphere::equirect_inverse(df)
            } else {
                sphere::equal_area_inverse(df)
            };
            let tx = ((uv[0] as f64 * width as f64) as usize).min(width - 1);
            let ty = ((uv[1] as f64 * height as f64) as usize).min(height - 1);
            sum += radiance[ty * width + tx] * c / (light_pdf(uv) + c / PI);
        }
        sum / spp as f64
    }
}

/// Two unit vectors completing `n` to an orthonormal basis (Duff et al. 2017).
fn basis(n: [f64; 3]) -> [[f64; 3]; 2] {
    let sign = 1f64.copysign(n[2]);
    let a = -1.0 / (sign + n[2]);
    let b = n[0] * n[1] * a;
    [
        [1.0 + sign * n[0] * n[0] * a, sign * b, -sign * n[0]],
        [b, sign + n[1] * n[1] * a, -n[1]],
    ]
}

/// `4 pi`: solid angle of the sphere (for tests and docs).
#[allow(dead_code)]
pub const SPHERE: f64 = 4.0 * PI;
