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
//! **MIS warps** (`hierarchical_equirect_mis`, `hierarchical_equal_area_mis`; for
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
use std::sync::{Arc, Mutex};
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
    /// The reference machinery of the parameterization (shared by a scene's rotations).
    pub grid: Arc<Grid<P>>,
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
        grid: Arc<Grid<P>>,
        luminance: &[f32],
        weights: Vec<f32>,
        compensation: Compensation,
    ) -> Result<Self, envmap::Error> {
        let (width, height) = (grid.width, grid.height);
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
            grid,
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

/// Rasterizes `f` into a `w x h` map of `param`: each texel the mean of `k x k` point values.
pub fn rasterize<P: Param>(
    param: &P,
    w: usize,
    h: usize,
    k: usize,
    f: &(dyn Fn([f64; 3]) -> f64 + Sync),
) -> Vec<f32> {
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

/// A rotation of the sphere, row-major.
pub type Rotation = [[f64; 3]; 3];

/// The map rotations the report averages over: rotation 0 is the identity, the
/// others are uniformly distributed rotations (Shoemake's unit quaternions) from a fixed
/// stream, the same for every scene. The layout a map is stored in decides where its bright
/// features fall relative to the sample square's split lines and the octahedral folds, so
/// one orientation can flatter or penalize a layout (the sun's position alone moved the
/// equal-area / lat-long MSE ratio from 1.05 to 2.00 over 12 rotations in the first layout study).
pub fn rotations(count: usize) -> Vec<Rotation> {
    let mut rng = Rng::new(0x726f_7461_7465);
    (0..count.max(1))
        .map(|k| {
            let (u1, u2, u3) = (rng.uniform(), rng.uniform(), rng.uniform());
            if k == 0 {
                return [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
            }
            let (a, b) = ((1.0 - u1).sqrt(), u1.sqrt());
            let (x, y) = (a * (TAU * u2).sin(), a * (TAU * u2).cos());
            let (z, w) = (b * (TAU * u3).sin(), b * (TAU * u3).cos());
            [
                [
                    1.0 - 2.0 * (y * y + z * z),
                    2.0 * (x * y - z * w),
                    2.0 * (x * z + y * w),
                ],
                [
                    2.0 * (x * y + z * w),
                    1.0 - 2.0 * (x * x + z * z),
                    2.0 * (y * z - x * w),
                ],
                [
                    2.0 * (x * z - y * w),
                    2.0 * (y * z + x * w),
                    1.0 - 2.0 * (x * x + y * y),
                ],
            ]
        })
        .collect()
}

/// `R^T d`: the direction of the unrotated map seen at `d` in the map turned by `R`.
fn unrotate(r: &Rotation, d: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|i| r[0][i] * d[0] + r[1][i] * d[1] + r[2][i] * d[2])
}

/// An environment-map scene: one map, turned by each of [`rotations`]; its pixels with or
/// without the occluder.
pub struct EnvScene {
    pub name: String,
    /// Rotation 0 (the map as given).
    pub latlong: Side<LatLong>,
    pub equal_area: Side<EqualArea>,
    /// Rotations 1.. of the same map (the same grids).
    pub rotated: Vec<(Side<LatLong>, Side<EqualArea>)>,
    /// Seeds the pixels' geometry: scenes with the same `id` (one map at two resolutions)
    /// have the same pixels.
    pub id: u64,
}

/// One pixel: normal, occluder plane normal, the map rotation it sees, and the two
/// references.
#[derive(Clone, Debug)]
pub struct EnvPixel {
    pub n: [f64; 3],
    pub m: [f64; 3],
    /// Index into [`rotations`]: pixel `i` sees rotation `i % count`.
    pub rotation: usize,
    /// Per parameterization: lat-long, equal-area.
    pub reference: [f64; 2],
}

/// The lat-long and equal-area maps of one rotation of a scene, scaled so that the lat-long
/// map's mean radiance over the sphere is 1 (unoccluded irradiance is then at most pi: MSE
/// figures comparable across maps), with their distributions.
fn sides(
    grids: (&Arc<Grid<LatLong>>, &Arc<Grid<EqualArea>>),
    mut ll: Vec<f32>,
    mut ea: Vec<f32>,
) -> Result<(Side<LatLong>, Side<EqualArea>), envmap::Error> {
    let (w, h) = (grids.0.width, grids.0.height);
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
    Ok((
        Side::new(
            grids.0.clone(),
            &ll,
            ll_weights,
            Compensation::Equirect(mis_fraction()),
        )?,
        Side::new(
            grids.1.clone(),
            &ea,
            ea_weights,
            Compensation::Uniform(mis_fraction()),
        )?,
    ))
}

/// The reference grids of a `w x h` lat-long map and its `s x s` equal-area partner, built
/// once per size and shared by every scene and rotation of that size.
fn grids(w: usize, h: usize) -> (Arc<Grid<LatLong>>, Arc<Grid<EqualArea>>) {
    type Grids = (Arc<Grid<LatLong>>, Arc<Grid<EqualArea>>);
    static CACHE: Mutex<Vec<((usize, usize), Grids)>> = Mutex::new(Vec::new());
    let mut cache = CACHE.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, g)) = cache.iter().find(|(k, _)| *k == (w, h)) {
        return g.clone();
    }
    let s = ((w * h) as f64).sqrt().round() as usize;
    let g = (
        Arc::new(Grid::new(LatLong, w, h)),
        Arc::new(Grid::new(EqualArea, s, s)),
    );
    cache.push(((w, h), g.clone()));
    g
}

impl EnvScene {
    /// A scene of the radiance function `f`, rasterized (`k x k` points per texel) into a
    /// `w x h` lat-long map and an `s x s` equal-area map (`s = round(sqrt(w h))`, centred in
    /// its pyramid), once per rotation. `id_name` seeds the pixels.
    pub fn from_function(
        name: &str,
        id_name: &str,
        f: &(dyn Fn([f64; 3]) -> f64 + Sync),
        (w, h): (usize, usize),
        k: usize,
        rotation_count: usize,
    ) -> Result<Self, envmap::Error> {
        let s = ((w * h) as f64).sqrt().round() as usize;
        let (gl, ge) = grids(w, h);
        let grids = (&gl, &ge);
        let mut all = Vec::new();
        for r in rotations(rotation_count) {
            let g = |d: [f64; 3]| f(unrotate(&r, d));
            let ll = rasterize(&LatLong, w, h, k, &g);
            let ea = rasterize(&EqualArea, s, s, k, &g);
            all.push(sides(grids, ll, ea)?);
        }
        let mut all = all.into_iter();
        let (latlong, equal_area) = all.next().ok_or(envmap::Error::ZeroSize)?;
        Ok(EnvScene {
            name: format!("envmap:{name}"),
            latlong,
            equal_area,
            rotated: all.collect(),
            id: hash(&id_name.bytes().map(u64::from).collect::<Vec<_>>()),
        })
    }

    /// The number of map rotations the pixels cycle through.
    pub fn rotation_count(&self) -> usize {
        1 + self.rotated.len()
    }

    /// The maps and distributions of rotation `k`.
    pub fn side(&self, k: usize) -> (&Side<LatLong>, &Side<EqualArea>) {
        match k.checked_sub(1).and_then(|i| self.rotated.get(i)) {
            Some((ll, ea)) => (ll, ea),
            None => (&self.latlong, &self.equal_area),
        }
    }

    /// The scene's pixels with the occluder (`lit = false`, the scene's own name) or without
    /// it (`lit = true`, `<name>/lit`), sharing the maps and distributions.
    pub fn view(&self, lit: bool) -> EnvView<'_> {
        EnvView { scene: self, lit }
    }

    /// A built-in procedural map at `w x h` lat-long and the matching square (8 x 8 points
    /// per texel).
    pub fn procedural(
        name: &str,
        f: fn([f64; 3]) -> f64,
        w: usize,
        h: usize,
        rotation_count: usize,
    ) -> Result<Self, envmap::Error> {
        Self::from_function(name, name, &f, (w, h), 8, rotation_count)
    }

    /// A scene from a lat-long luminance image (`width x height`, row 0 around `+z`; its
    /// negative and NaN texels weigh 0), resampled to the report's 256 x 128 lat-long and
    /// 181 x 181 equal-area maps (4 x 4 points per texel, each the source texel it falls
    /// in: for a 512 x 256 source and the unrotated map, exactly a 2 x 2 box filter).
    pub fn from_latlong(
        name: &str,
        width: usize,
        height: usize,
        luminance: Vec<f32>,
        rotation_count: usize,
    ) -> Result<Self, envmap::Error> {
        if width == 0 || height == 0 || luminance.len() != width * height {
            return Err(envmap::Error::ZeroSize);
        }
        let lookup = move |d: [f64; 3]| -> f64 {
            let [u, v] = LatLong.inverse(d);
            let i = ((u * width as f64) as usize).min(width - 1);
            let j = ((v * height as f64) as usize).min(height - 1);
            let l = luminance[j * width + i];
            if l > 0.0 { l as f64 } else { 0.0 }
        };
        Self::from_function(name, name, &lookup, (256, 128), 4, rotation_count)
    }

    /// The built-in scenes: `envmap:sky` and `envmap:interior` (procedural), 256 x 128
    /// lat-long and 181 x 181 equal-area, and `envmap:sky_200x100`, the sky at 200 x 100 and
    /// 141 x 141 with the same pixels (a non-power-of-two lat-long map against
    /// 256 x 128); each over `rotation_count` rotations.
    pub fn builtin(rotation_count: usize) -> Vec<EnvScene> {
        let make = |name: &str, f: fn([f64; 3]) -> f64| {
            EnvScene::procedural(name, f, 256, 128, rotation_count).ok()
        };
        // Built on two threads: the reference grids take a moment each.
        let (sky, interior) = std::thread::scope(|s| {
            let a = s.spawn(|| make("sky", sky));
            let b = make("interior", interior);
            (a.join().ok().flatten(), b)
        });
        sky.into_iter().chain(interior).collect()
    }

    /// `envmap:sky_200x100` (see [`EnvScene::builtin`]).
    pub fn sky_200x100(rotation_count: usize) -> Option<EnvScene> {
        Self::from_function("sky_200x100", "sky", &sky, (200, 100), 8, rotation_count).ok()
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
        let rotation = (index % self.rotation_count() as u64) as usize;
        self.pixel_at(index, rotation, true)
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
        self.warp_points(0, warp, spp, s);
    }

    fn draw_for(
        &self,
        pixel: &EnvPixel,
        warp: usize,
        sampler: Sampler,
        spp: usize,
        seed: u32,
        s: &mut Scratch,
    ) {
        s.reserve(spp);
        sampler.fill(seed, &mut s.points[..spp]);
        self.warp_points(pixel.rotation, warp, spp, s);
    }

    fn evaluate(&self, pixel: &EnvPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        if warp >= 4 {
            return self.evaluate_mis(pixel, base(warp), spp, s);
        }
        (0..spp).map(|k| self.value(pixel, warp, k, s)).sum::<f64>() / spp as f64
    }
}

impl EnvView<'_> {
    /// Pixel `index`'s geometry seeing rotation `rotation` of the map (the report's pixels
    /// see `index % rotation_count()`; the orientation study also shows every pixel the map
    /// as authored, rotation 0), with its references when `references` (else NaN: the
    /// variance split needs none).
    pub fn pixel_at(&self, index: u64, rotation: usize, references: bool) -> EnvPixel {
        let (n, m) = self.geometry(index);
        // Without the occluder: the half-space m . w >= 0 with m = n hides only directions
        // the lobe already gives weight 0, so the references and the estimator are the
        // unoccluded ones.
        let m = if self.lit { n } else { m };
        let rotation = rotation.min(self.rotation_count() - 1);
        let (ll, ea) = self.side(rotation);
        EnvPixel {
            n,
            m,
            rotation,
            reference: if references {
                [
                    ll.grid.integral(&ll.radiance, n, m),
                    ea.grid.integral(&ea.radiance, n, m),
                ]
            } else {
                [f64::NAN; 2]
            },
        }
    }

    /// One sample's term `L_t max(0, n . w) [m . w >= 0] / p(w)` of the plain estimator
    /// (`warp < 4`), for sample `k` of those `warp_points` left in `s`.
    pub fn value(&self, pixel: &EnvPixel, warp: usize, k: usize, s: &Scratch) -> f64 {
        let side = self.side(pixel.rotation);
        let (radiance, width) = if warp < 2 {
            (&side.0.radiance, side.0.width())
        } else {
            (&side.1.radiance, side.1.width())
        };
        let smp = &s.env.samples[k];
        let d = s.out3[k].map(f64::from);
        let c = dot3(pixel.n, d);
        let p = s.env.pdf[k] as f64;
        if c <= 0.0 || dot3(pixel.m, d) < 0.0 || p <= 0.0 {
            return 0.0;
        }
        radiance[smp.texel[1] as usize * width + smp.texel[0] as usize] * c / p
    }

    /// Warps the `spp` points in `s.points` by `warp` of rotation `rotation` into
    /// `s.env.samples`, `s.out3` (directions) and `s.env.pdf` (solid-angle densities).
    pub fn warp_points(&self, rotation: usize, warp: usize, spp: usize, s: &mut Scratch) {
        let (ll, ea) = self.side(rotation);
        let env = &mut s.env;
        let (points, samples) = (&s.points[..spp], &mut env.samples[..spp]);
        match warp {
            0 => ll.marginal.sample_slice(points, samples),
            1 => ll.hierarchical.sample_slice(points, samples),
            2 => ea.marginal.sample_slice(points, samples),
            3 => ea.hierarchical.sample_slice(points, samples),
            4 => ll.hierarchical_mis.sample_slice(points, samples),
            _ => ea.hierarchical_mis.sample_slice(points, samples),
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

    /// The `_mis` estimator (see the module docs): `warp` (1 or 3) names the
    /// parameterization, whose compensated hierarchical tables `draw` sampled.
    fn evaluate_mis(&self, pixel: &EnvPixel, warp: usize, spp: usize, s: &Scratch) -> f64 {
        let latlong = warp < 2;
        let (ll, ea) = self.side(pixel.rotation);
        let (radiance, width, height) = if latlong {
            (&ll.radiance, ll.width(), ll.height())
        } else {
            (&ea.radiance, ea.width(), ea.height())
        };
        // The light technique's density over directions at `uv`.
        let light_pdf = |uv: [f32; 2]| -> f64 {
            let p = if latlong {
                ll.hierarchical_mis.pdf(uv)
            } else {
                ea.hierarchical_mis.pdf(uv)
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
