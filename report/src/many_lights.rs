//! The many-light scene: which light a next-event estimate picks, among thousands.
//!
//! **Scene.** A procedural city at night: a grid of buildings whose four facades carry a
//! grid of windows, some lit (one-sided emissive quads, two triangles each, radiance spread
//! over two decades, shop fronts on the ground floor brighter), plus street lamps (small
//! downward triangles, bright). The shading points are the street surface (`y = 0`, normal
//! `+y`, diffuse albedo 0.5) seen from above, one per pixel of a small image; pixels inside
//! a building's footprint are left out. Every emitter lies strictly above the street, so each
//! pixel's exact value is a closed form: `rho / pi * sum_j L_j * E_j`, with `E_j` the
//! irradiance of triangle `j` by Lambert's polygon formula (in `f64`, 0 where `p` is behind
//! the emitter). Unoccluded (no shadow rays): visibility multiplies every row's integrand by
//! the same function, and the rows differ only in which light they choose.
//!
//! **Estimator.** One sample: choose light `j` with probability `P(j)` from one `u`, a point
//! on it uniform in solid angle (`spherical::triangle`, density `1 / omega`) from a 2D
//! point, then `rho / pi * L_j * max(0, n . w) * [p in front of j] / (P(j) / omega)`. The 1D
//! light choice is the first coordinate of one 2D stream of the sampler, the triangle point
//! a second, independently seeded stream of the same pattern.
//!
//! **Rows** ([`LightChooser`]): uniform choice (`P = 1/n`), the alias table by power
//! (`lights::AliasTable`, power `= pi * L * area`), and the light tree by importance at the
//! shading point (`lights::LightTree` over each triangle's [`Emitter::bounds`]). MSE over the pixels at equal sample counts, for every sampler
//! pattern of [`SAMPLERS`]; time per sample (choice, triangle sampling and shading,
//! single-threaded, best of a few runs); MSE at equal time as `MSE x time per sample`
//! relative to the alias table's.

use crate::path::scene::{cross, dot, sub};
use crate::samplers::{SAMPLERS, Sampler};
use std::fmt::Write as _;
use std::hint::black_box;
use std::time::Instant;
use warpcore::lights::{AliasTable, LightBounds, LightTree};
use warpcore::spherical;

type V = [f32; 3];

/// A light-selection strategy: the light for a shading point `p` with normal `n` and one
/// uniform number `u`, with the probability of that choice (`None`: no light contributes).
pub trait LightChooser: Sync {
    /// The row's label (the API it calls).
    fn name(&self) -> String;
    fn sample(&self, p: V, n: V, u: f32) -> Option<(u32, f32)>;
}

/// Every light with probability `1 / n`.
pub struct Uniform(pub u32);

impl LightChooser for Uniform {
    fn name(&self) -> String {
        "uniform (1/n)".into()
    }
    fn sample(&self, _p: V, _n: V, u: f32) -> Option<(u32, f32)> {
        let i = ((u * self.0 as f32) as u32).min(self.0 - 1);
        Some((i, 1.0 / self.0 as f32))
    }
}

impl LightChooser for AliasTable<'_> {
    fn name(&self) -> String {
        "lights::AliasTable by power".into()
    }
    fn sample(&self, _p: V, _n: V, u: f32) -> Option<(u32, f32)> {
        Some(AliasTable::sample(self, u))
    }
}

impl LightChooser for LightTree<'_> {
    fn name(&self) -> String {
        "lights::LightTree by importance".into()
    }
    fn sample(&self, p: V, n: V, u: f32) -> Option<(u32, f32)> {
        LightTree::sample(self, p, n, u)
    }
}

/// One emissive triangle: vertices (counter-clockwise seen from the lit side), radiance.
#[derive(Clone, Copy, Debug)]
pub struct Emitter {
    pub v: [V; 3],
    pub radiance: f32,
}

impl Emitter {
    fn normal(&self) -> [f64; 3] {
        let [a, b, c] = self.v.map(|x| x.map(f64::from));
        cross(sub(b, a), sub(c, a))
    }
    /// `pi * L * area`: the power of a one-sided Lambertian emitter.
    pub fn power(&self) -> f32 {
        let n = self.normal();
        (std::f64::consts::PI * f64::from(self.radiance) * 0.5 * dot(n, n).sqrt()) as f32
    }
    /// The light tree's bounds: the triangle's box, its power, its normal as the axis, no
    /// spread of normals (`cos_theta_o = 1`), cosine falloff to 90 degrees (`cos_theta_e =
    /// 0`), one-sided.
    pub fn bounds(&self) -> LightBounds {
        let axis = normalize(self.normal()).map(|x| x as f32);
        let [a, b, c] = self.v;
        LightBounds {
            min: core::array::from_fn(|k| a[k].min(b[k]).min(c[k])),
            max: core::array::from_fn(|k| a[k].max(b[k]).max(c[k])),
            power: self.power(),
            axis,
            cos_theta_o: 1.0,
            cos_theta_e: 0.0,
            two_sided: false,
        }
    }
    /// Whether `p` sees the lit side.
    fn faces(&self, p: [f64; 3]) -> bool {
        dot(self.normal(), sub(p, self.v[0].map(f64::from))) > 0.0
    }
}

fn normalize(a: [f64; 3]) -> [f64; 3] {
    let l = dot(a, a).sqrt();
    a.map(|x| x / l)
}

/// The city: `emitters` and the street's shading points (`None` inside a building).
pub struct City {
    pub emitters: Vec<Emitter>,
    pub points: Vec<Option<V>>,
    pub size: [usize; 2],
}

/// The city's layout numbers: the report's hash of a counter (the same city every run).
struct Rng(u64);
impl Rng {
    fn next(&mut self) -> f32 {
        self.0 += 1;
        (crate::math::hash(&[0x011c_17e5, self.0]) >> 40) as f32 / 16_777_216.0
    }
}

/// Blocks per side, block pitch (m).
const BLOCKS: usize = 8;
const PITCH: f32 = 24.0;

impl City {
    /// The city and a `width x height` grid of street points over its footprint.
    pub fn new(width: usize, height: usize) -> City {
        let mut rng = Rng(33);
        let mut emitters = Vec::new();
        let mut footprints = Vec::new();
        let quad = |emitters: &mut Vec<Emitter>, o: V, a: V, b: V, radiance: f32| {
            // o, o + a, o + a + b, o + b; lit side along a x b.
            let p = |s: f32, t: f32| [0, 1, 2].map(|k| o[k] + s * a[k] + t * b[k]);
            emitters.push(Emitter {
                v: [p(0.0, 0.0), p(1.0, 0.0), p(1.0, 1.0)],
                radiance,
            });
            emitters.push(Emitter {
                v: [p(0.0, 0.0), p(1.0, 1.0), p(0.0, 1.0)],
                radiance,
            });
        };
        for bx in 0..BLOCKS {
            for bz in 0..BLOCKS {
                let (w, d) = (8.0 + 8.0 * rng.next(), 8.0 + 8.0 * rng.next());
                let h = 8.0 + 52.0 * rng.next() * rng.next();
                let (x0, z0) = (bx as f32 * PITCH + 4.0, bz as f32 * PITCH + 4.0);
                footprints.push([x0, z0, x0 + w, z0 + d]);
                let floors = (h / 3.5) as usize;
                // Facades: (origin, along, outward normal), counter-clockwise from -z.
                let faces: [(V, V, V); 4] = [
                    ([x0 + w, 0.0, z0], [-1.0, 0.0, 0.0], [0.0, 0.0, -1.0]),
                    ([x0 + w, 0.0, z0 + d], [0.0, 0.0, -1.0], [1.0, 0.0, 0.0]),
                    ([x0, 0.0, z0 + d], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]),
                    ([x0, 0.0, z0], [0.0, 0.0, 1.0], [-1.0, 0.0, 0.0]),
                ];
                let lit_share = 0.15 + 0.4 * rng.next();
                for (origin, along, out) in faces {
                    let length = if along[0] != 0.0 { w } else { d };
                    let columns = (length / 2.5) as usize;
                    for f in 0..floors {
                        for c in 0..columns {
                            if rng.next() > lit_share {
                                continue;
                            }
                            let shop = f == 0;
                            let radiance = if shop {
                                20.0 * 10f32.powf(rng.next())
                            } else {
                                10f32.powf(2.5 * rng.next())
                            };
                            let s = (c as f32 + 0.25) * length / columns as f32;
                            let y = f as f32 * 3.5 + 1.0;
                            let up = [0.0, y, 0.0];
                            let o =
                                [0, 1, 2].map(|k| origin[k] + s * along[k] + 0.02 * out[k] + up[k]);
                            let width = 0.5 * length / columns as f32;
                            let tall = if shop { 2.2 } else { 1.5 };
                            // Lit side outward: along x up is outward for this winding.
                            quad(
                                &mut emitters,
                                o,
                                [0.0, tall, 0.0],
                                along.map(|x| x * width),
                                radiance,
                            );
                        }
                    }
                }
            }
        }
        // Street lamps at the crossings, 6 m up, facing down.
        for i in 0..=BLOCKS {
            for j in 0..=BLOCKS {
                let (x, z) = (i as f32 * PITCH + 1.5, j as f32 * PITCH + 1.5);
                quad(
                    &mut emitters,
                    [x, 6.0, z],
                    [0.3, 0.0, 0.0],
                    [0.0, 0.0, 0.3],
                    3000.0,
                );
            }
        }
        // Make every emitter face outward: flip the ones whose normal points into their
        // building (or up, for lamps).
        for e in &mut emitters {
            let n = e.normal();
            let c = e.v.iter().fold([0.0f64; 3], |s, v| {
                [0, 1, 2].map(|k| s[k] + f64::from(v[k]) / 3.0)
            });
            let inside = footprints.iter().find(|f| {
                let (x, z) = (c[0] as f32, c[2] as f32);
                x >= f[0] - 0.1 && x <= f[2] + 0.1 && z >= f[1] - 0.1 && z <= f[3] + 0.1
            });
            let outward = match inside {
                Some(f) => {
                    let centre = [(f[0] + f[2]) as f64 / 2.0, c[1], (f[1] + f[3]) as f64 / 2.0];
                    dot(n, sub(c, centre)) > 0.0
                }
                None => n[1] < 0.0,
            };
            if !outward {
                e.v.swap(1, 2);
            }
        }
        let extent = BLOCKS as f32 * PITCH;
        let points = (0..width * height)
            .map(|k| {
                let (i, j) = (k % width, k / width);
                let x = (i as f32 + 0.5) / width as f32 * extent;
                let z = (j as f32 + 0.5) / height as f32 * extent;
                let inside = footprints
                    .iter()
                    .any(|f| x >= f[0] && x <= f[2] && z >= f[1] && z <= f[3]);
                (!inside).then_some([x, 0.0, z])
            })
            .collect();
        City {
            emitters,
            points,
            size: [width, height],
        }
    }

    /// The exact reflected radiance at `p` (street, normal +y, albedo [`ALBEDO`]): Lambert's
    /// polygon formula per emitter, in `f64`.
    pub fn exact(&self, p: V) -> f64 {
        let p = p.map(f64::from);
        let n = [0.0, 1.0, 0.0];
        let mut sum = 0.0;
        for e in &self.emitters {
            if !e.faces(p) {
                continue;
            }
            let a = e.v.map(|v| normalize(sub(v.map(f64::from), p)));
            let mut phi = [0.0f64; 3];
            for k in 0..3 {
                let (x, y) = (a[k], a[(k + 1) % 3]);
                let c = cross(x, y);
                let s = dot(c, c).sqrt();
                if s == 0.0 {
                    continue;
                }
                let theta = s.atan2(dot(x, y));
                for m in 0..3 {
                    phi[m] += 0.5 * theta * c[m] / s;
                }
            }
            sum += f64::from(e.radiance) * dot(n, phi).abs();
        }
        ALBEDO / std::f64::consts::PI * sum
    }

    /// One sample's estimate at `p` with `chooser`, `u_light` and the triangle point `u`.
    #[inline]
    pub fn estimate(&self, chooser: &dyn LightChooser, p: V, u_light: f32, u: [f32; 2]) -> f64 {
        let n = [0.0, 1.0, 0.0];
        let Some((j, prob)) = chooser.sample(p, n, u_light) else {
            return 0.0;
        };
        let Some(e) = self.emitters.get(j as usize) else {
            return 0.0;
        };
        if prob <= 0.0 || !e.faces(p.map(f64::from)) {
            return 0.0;
        }
        let (b, pdf) = spherical::triangle(e.v, p, u);
        if pdf <= 0.0 {
            return 0.0;
        }
        let q: V = [0, 1, 2].map(|k| b[0] * e.v[0][k] + b[1] * e.v[1][k] + b[2] * e.v[2][k]);
        let w = [q[0] - p[0], q[1] - p[1], q[2] - p[2]];
        let cos = w[1] / (w[0] * w[0] + w[1] * w[1] + w[2] * w[2]).sqrt();
        if cos <= 0.0 {
            return 0.0;
        }
        ALBEDO / std::f64::consts::PI * f64::from(e.radiance) * f64::from(cos)
            / (f64::from(prob) * f64::from(pdf))
    }
}

/// The street's diffuse albedo.
pub const ALBEDO: f64 = 0.5;

/// One (chooser, sampler, spp) cell.
#[derive(Clone, Debug)]
pub struct Row {
    pub chooser: String,
    pub sampler: Sampler,
    pub spp: usize,
    /// Relative MSE of the image: mean over pixels and frames of `(estimate - exact)^2`
    /// over the mean of `exact^2`.
    pub rel_mse: f64,
    /// Standard error of `rel_mse` over pixels.
    pub rel_mse_se: f64,
}

/// The scene's results: the rows, the time per sample of each chooser, the scene's size.
pub struct Results {
    pub rows: Vec<Row>,
    /// (chooser, nanoseconds per sample: choice, triangle sampling, shading).
    pub ns: Vec<(String, f64)>,
    pub lights: usize,
    pub pixels: usize,
}

/// Sample counts of the scene.
pub const SPPS: [usize; 3] = [1, 4, 16];
/// Independent frames per (chooser, sampler, count).
pub const FRAMES: u64 = 16;

fn seed(pixel: usize, spp: usize, sampler: Sampler, stream: u64) -> u32 {
    crate::math::hash(&[
        0x33,
        pixel as u64,
        spp as u64,
        sampler.index() as u64,
        stream,
    ]) as u32
}

/// Runs the scene on `width x height` street points with `choosers` (the rows), every
/// sampler of [`SAMPLERS`] and [`SPPS`], over `threads` threads.
pub fn run(city: &City, choosers: &[&dyn LightChooser], threads: usize) -> Results {
    let pixels: Vec<(usize, V, f64)> = city
        .points
        .iter()
        .enumerate()
        .filter_map(|(k, p)| p.map(|p| (k, p, city.exact(p))))
        .filter(|&(_, _, e)| e > 0.0)
        .collect();
    let mean_square = pixels.iter().map(|x| x.2 * x.2).sum::<f64>() / pixels.len().max(1) as f64;
    let mut rows = Vec::new();
    for chooser in choosers {
        for sampler in SAMPLERS {
            for spp in SPPS {
                let chunk = pixels.len().div_ceil(threads.max(1));
                let sums: Vec<(f64, f64, usize)> = std::thread::scope(|s| {
                    let handles: Vec<_> = pixels
                        .chunks(chunk.max(1))
                        .map(|part| {
                            s.spawn(move || {
                                let (mut a, mut a2) = (0.0, 0.0);
                                let mut light = vec![[0.0f32; 2]; spp];
                                let mut tri = vec![[0.0f32; 2]; spp];
                                for &(k, p, exact) in part {
                                    let mut e = 0.0;
                                    for frame in 0..FRAMES {
                                        let s = 2 * frame;
                                        sampler.fill(seed(k, spp, sampler, s), &mut light);
                                        sampler.fill(seed(k, spp, sampler, s + 1), &mut tri);
                                        let est: f64 = light
                                            .iter()
                                            .zip(&tri)
                                            .map(|(l, t)| city.estimate(*chooser, p, l[0], *t))
                                            .sum::<f64>()
                                            / spp as f64;
                                        e += (est - exact).powi(2) / FRAMES as f64;
                                    }
                                    a += e;
                                    a2 += e * e;
                                }
                                (a, a2, part.len())
                            })
                        })
                        .collect();
                    handles.into_iter().map(|h| h.join().unwrap()).collect()
                });
                let (a, a2, n) = sums
                    .iter()
                    .fold((0.0, 0.0, 0), |s, x| (s.0 + x.0, s.1 + x.1, s.2 + x.2));
                let n = n as f64;
                let mean = a / n;
                let var = (a2 / n - mean * mean).max(0.0);
                rows.push(Row {
                    chooser: chooser.name(),
                    sampler,
                    spp,
                    rel_mse: mean / mean_square,
                    rel_mse_se: (var / n).sqrt() / mean_square,
                });
            }
        }
    }
    // Time per sample: the choice, the triangle sample and the shading over every pixel,
    // 16 random samples each, single-threaded, best of 5.
    let mut ns = Vec::new();
    let mut light = vec![[0.0f32; 2]; 16];
    let mut tri = vec![[0.0f32; 2]; 16];
    type Points = Vec<[f32; 2]>;
    let inputs: Vec<(V, Points, Points)> = pixels
        .iter()
        .map(|&(k, p, _)| {
            Sampler::Random.fill(seed(k, 16, Sampler::Random, 0), &mut light);
            Sampler::Random.fill(seed(k, 16, Sampler::Random, 1), &mut tri);
            (p, light.clone(), tri.clone())
        })
        .collect();
    for chooser in choosers {
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let t = Instant::now();
            let mut acc = 0.0;
            for (p, l, tr) in &inputs {
                for (l, t) in l.iter().zip(tr) {
                    acc += city.estimate(*chooser, black_box(*p), l[0], *t);
                }
            }
            black_box(acc);
            best = best.min(t.elapsed().as_secs_f64());
        }
        ns.push((chooser.name(), best * 1e9 / (inputs.len() * 16) as f64));
    }
    Results {
        rows,
        ns,
        lights: city.emitters.len(),
        pixels: pixels.len(),
    }
}

impl Results {
    fn row(&self, chooser: &str, sampler: Sampler, spp: usize) -> Option<&Row> {
        self.rows
            .iter()
            .find(|r| r.chooser == chooser && r.sampler == sampler && r.spp == spp)
    }
    fn ns_of(&self, chooser: &str) -> f64 {
        self.ns
            .iter()
            .find(|x| x.0 == chooser)
            .map_or(f64::NAN, |x| x.1)
    }

    /// The tables: relative MSE per chooser, sampler and count; the ratios to uniform and
    /// to the alias table at equal samples and at equal time; the recommendation.
    pub fn markdown(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "### Many lights: a city at night ({} emissive triangles, {} street points, no \
             occlusion)\n\nRelative MSE of the image (mean over pixels and {} frames of `(estimate - exact)^2` \
             over the mean of `exact^2`, ± its standard error over pixels) of next-event estimation: light by the row's chooser, point \
             by `spherical::triangle`. Time per sample: choice, triangle sample, shading, \
             single-threaded.\n",
            self.lights, self.pixels, FRAMES
        );
        let choosers: Vec<&str> = self.ns.iter().map(|x| x.0.as_str()).collect();
        let _ = write!(s, "| chooser | ns/sample | sampler |");
        for spp in SPPS {
            let _ = write!(s, " {spp} spp |");
        }
        let _ = writeln!(s, "\n|---|---:|---|{}", "---:|".repeat(SPPS.len()));
        for c in &choosers {
            for sampler in SAMPLERS {
                let _ = write!(s, "| {c} | {:.1} | {} |", self.ns_of(c), sampler.name());
                for spp in SPPS {
                    if let Some(r) = self.row(c, sampler, spp) {
                        let _ = write!(s, " {:.3e} ± {:.1e} |", r.rel_mse, r.rel_mse_se);
                    }
                }
                s.push('\n');
            }
        }
        let _ = writeln!(
            s,
            "\nRatios of MSE (row / reference, of `MSE x spp` summed over the samplers and \
             counts); at equal time each MSE is scaled by its time per sample:\n"
        );
        let _ = writeln!(
            s,
            "| chooser | vs | equal samples | equal time |\n|---|---|---:|---:|"
        );
        for (reference, c) in choosers
            .iter()
            .flat_map(|r| choosers.iter().map(move |c| (*r, *c)))
            .filter(|(r, c)| r != c && !c.starts_with("uniform"))
        {
            // MSE x spp (flat for an unbiased Monte Carlo estimate) summed over the cells.
            let sum = |c: &str| {
                SAMPLERS
                    .iter()
                    .flat_map(|&sm| SPPS.iter().map(move |&n| (sm, n)))
                    .filter_map(|(sm, n)| Some(self.row(c, sm, n)?.rel_mse * n as f64))
                    .sum::<f64>()
            };
            let mean = sum(c) / sum(reference);
            let time = self.ns_of(c) / self.ns_of(reference);
            let _ = writeln!(s, "| {c} | {reference} | {mean:.3} | {:.3} |", mean * time);
        }
        let best = choosers.iter().min_by(|a, b| {
            let score = |c: &str| {
                SAMPLERS
                    .iter()
                    .filter_map(|&sm| self.row(c, sm, 16))
                    .map(|r| r.rel_mse)
                    .sum::<f64>()
                    * self.ns_of(c)
            };
            score(a).total_cmp(&score(b))
        });
        if let Some(best) = best {
            let _ = writeln!(
                s,
                "\nRecommendation (least MSE x time at 16 spp over the samplers): **{best}**, \
                 driven by the first coordinate of `pmj02bn::sample` or the sampler of \
                 `sampler::Sampler` (one `u` per choice: the alias table keeps its strata)."
            );
        }
        s
    }
}
