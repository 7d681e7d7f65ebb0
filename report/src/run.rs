//! The experiment loop: for every pixel of a scene, every sample count, sampler and warp,
//! one estimate against the pixel's exact reference; then, separately, the time to draw and
//! warp the samples.
//!
//! **Error.** Per combination and sample count, the mean squared error over pixels,
//! `MSE = mean((E_N - E)^2)`, with its relative standard error
//! `sqrt(var((E_N - E)^2) / P) / MSE` over the `P` pixels (pixels are independent).
//!
//! **Time.** Single-threaded, after the error runs: for each combination and sample count,
//! `max(1, budget / N)` pixels of drawing `N` samples — the sampler's slice form filling a
//! pixel's points and the warp's slice (or `x8`) form mapping them, what a renderer drawing a
//! pixel's samples at once would call — timed as a whole, best of a few repetitions, divided
//! by the number of samples. Integrand evaluation (the light's geometry, visibility, the
//! environment map's radiance) is not included: it is the same for every sampler and warp of
//! a scene and would be a renderer's own code.

use crate::math::Moments;
use crate::math::hash;
use crate::samplers::{SAMPLERS, Sampler};
use indicatif::ProgressBar;
use std::hint::black_box;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Per-thread buffers the scenes draw into.
#[derive(Default)]
pub struct Scratch {
    pub points: Vec<[f32; 2]>,
    pub out2: Vec<[f32; 2]>,
    pub out3: Vec<[f32; 3]>,
    #[cfg(feature = "envmap")]
    pub env: crate::envscene::EnvScratch,
}

impl Scratch {
    pub fn reserve(&mut self, n: usize) {
        if self.points.len() < n {
            self.points.resize(n, [0.0; 2]);
            self.out2.resize(n, [0.0; 2]);
            self.out3.resize(n, [0.0; 3]);
            #[cfg(feature = "envmap")]
            self.env.reserve(n);
        }
    }
}

/// A scene: pixels with exact references, and estimators for each (sampler, warp).
pub trait Scene: Sync {
    type Pixel: Send;
    fn name(&self) -> String;
    /// One line on the scene (light, maps), for the tables' captions.
    fn description(&self) -> String;
    fn warps(&self) -> Vec<&'static str>;
    /// Pixel `index`: its geometry and exact reference.
    fn pixel(&self, index: u64) -> Self::Pixel;
    /// The exact value the estimates of `warp` converge to (the environment-map scenes have
    /// one map, and so one reference, per parameterization).
    fn reference(&self, pixel: &Self::Pixel, warp: usize) -> f64;
    fn penumbra(&self, pixel: &Self::Pixel) -> bool;
    /// `Some(other)` when `(sampler, warp)` is the same estimator as `(other, warp)`.
    fn alias(&self, _warp: usize, _sampler: Sampler) -> Option<Sampler> {
        None
    }
    /// Whether `sampler` means anything for `warp` (rows that do not apply are left out).
    fn applies(&self, _warp: usize, _sampler: Sampler) -> bool {
        true
    }
    /// Draws and warps `spp` samples for `seed` into `s` (what the timing measures).
    fn draw(&self, warp: usize, sampler: Sampler, spp: usize, seed: u32, s: &mut Scratch);
    /// [`Scene::draw`] for one pixel (the environment-map scenes' pixels see different
    /// rotations of the map, each with its own distributions); what the error runs call.
    fn draw_for(
        &self,
        _pixel: &Self::Pixel,
        warp: usize,
        sampler: Sampler,
        spp: usize,
        seed: u32,
        s: &mut Scratch,
    ) {
        self.draw(warp, sampler, spp, seed, s)
    }
    /// The estimate from the samples `draw` left in `s`.
    fn evaluate(&self, pixel: &Self::Pixel, warp: usize, spp: usize, s: &Scratch) -> f64;
}

/// The seed of one pixel's sample stream: shared by the warps of a sampler (common random
/// numbers make the warps' comparison sharper), distinct per scene, pixel, count, sampler.
pub fn seed(scene: &str, pixel: u64, spp: usize, sampler: Sampler) -> u32 {
    let s = hash(&scene.bytes().map(u64::from).collect::<Vec<_>>());
    hash(&[s, pixel, spp as u64, sampler.index() as u64]) as u32
}

/// Running sums of the errors `E_N - E` of one combination at one sample count.
#[derive(Clone, Copy, Default, Debug)]
pub struct Stat {
    /// Of the errors.
    pub err: Moments,
    /// Of the squared errors.
    pub sq: Moments,
}

impl Stat {
    pub fn add(&mut self, err: f64) {
        self.err.add(err);
        self.sq.add(err * err);
    }
    pub fn merge(&mut self, o: &Stat) {
        self.err.merge(&o.err);
        self.sq.merge(&o.sq);
    }
    pub fn mse(&self) -> f64 {
        self.sq.mean()
    }
    /// Relative standard error of [`Stat::mse`].
    pub fn mse_rel_se(&self) -> f64 {
        let (m, se) = self.sq.mean_se();
        se / m
    }
    /// Mean error over pixels in units of its standard error (an unbiased estimator gives
    /// a standard normal value). (The tables use [`Summary::bias_z`]; the tests use this.)
    #[allow(dead_code)]
    pub fn bias_z(&self) -> f64 {
        let (mean, se) = self.err.mean_se();
        mean / se
    }
}

/// What the tables report of one combination at one sample count: the MSE and the mean
/// error, each with its standard error. Summaries of disjoint pixel classes combine into the
/// summary of their mixture ([`Summary::combine`]).
#[derive(Clone, Copy, Default, Debug)]
pub struct Summary {
    /// Pixels behind the figures.
    pub n: u64,
    pub mse: f64,
    pub mse_se: f64,
    pub mean: f64,
    pub mean_se: f64,
}

impl Summary {
    pub fn of(st: &Stat) -> Summary {
        let mse = st.mse();
        let (mean, mean_se) = st.err.mean_se();
        Summary {
            n: st.err.n,
            mse,
            mse_se: st.mse_rel_se() * mse,
            mean,
            mean_se,
        }
    }

    /// The mixture of independent classes with probabilities `w`: means add with the weights,
    /// variances of the estimates with the squared weights. A class of weight `w` whose
    /// errors are all zero (hidden pixels) is simply left out.
    pub fn combine(parts: &[(f64, Summary)]) -> Summary {
        let mut out = Summary::default();
        let (mut v_mse, mut v_mean) = (0.0, 0.0);
        for &(w, p) in parts {
            out.n += p.n;
            out.mse += w * p.mse;
            out.mean += w * p.mean;
            v_mse += (w * p.mse_se).powi(2);
            v_mean += (w * p.mean_se).powi(2);
        }
        out.mse_se = v_mse.sqrt();
        out.mean_se = v_mean.sqrt();
        out
    }

    pub fn rel_se(&self) -> f64 {
        self.mse_se / self.mse
    }

    /// Mean error in units of its standard error.
    pub fn bias_z(&self) -> f64 {
        self.mean / self.mean_se
    }
}

/// One (sampler, warp) row of a scene.
#[derive(Clone, Debug)]
pub struct Row {
    pub sampler: Sampler,
    pub warp: &'static str,
    /// Per sample count.
    pub stats: Vec<Summary>,
    /// Nanoseconds per sample, per sample count.
    pub ns: Vec<f64>,
    /// Same estimator as this sampler's row (reported under both names).
    pub alias_of: Option<Sampler>,
}

impl Row {
    pub fn mse(&self, k: usize) -> f64 {
        self.stats[k].mse
    }
    /// Slope of log MSE against log N.
    pub fn rate(&self, spps: &[usize]) -> f64 {
        let pts: Vec<(f64, f64)> = spps
            .iter()
            .zip(&self.stats)
            .map(|(&n, s)| ((n as f64).ln(), s.mse.ln()))
            .collect();
        crate::math::slope(&pts)
    }
}

#[derive(Clone, Debug)]
pub struct SceneResult {
    pub scene: String,
    pub description: String,
    pub pixels: usize,
    /// Fraction of the scene's pixel population in penumbra.
    pub penumbra: f64,
    pub spps: Vec<usize>,
    pub rows: Vec<Row>,
    /// Wall-clock seconds of the error runs (references included).
    pub seconds: f64,
}

impl SceneResult {
    pub fn row(&self, sampler: Sampler, warp: &str) -> Option<&Row> {
        self.rows
            .iter()
            .find(|r| r.sampler == sampler && r.warp == warp)
    }

    /// The mixture of pixel classes `parts` (the same rows, timings and sample counts) with
    /// probabilities `w`; a class left out (hidden pixels) has error exactly 0.
    pub fn mix(scene: String, description: String, parts: &[(f64, &SceneResult)]) -> SceneResult {
        let first = parts[0].1;
        let rows = first
            .rows
            .iter()
            .map(|r| {
                let stats = (0..first.spps.len())
                    .map(|k| {
                        let p: Vec<(f64, Summary)> = parts
                            .iter()
                            .filter_map(|(w, res)| {
                                res.row(r.sampler, r.warp).map(|x| (*w, x.stats[k]))
                            })
                            .collect();
                        Summary::combine(&p)
                    })
                    .collect();
                Row { stats, ..r.clone() }
            })
            .collect();
        SceneResult {
            scene,
            description,
            pixels: parts.iter().map(|p| p.1.pixels).sum(),
            penumbra: parts.iter().map(|(w, res)| w * res.penumbra).sum::<f64>(),
            spps: first.spps.clone(),
            rows,
            seconds: parts.iter().map(|p| p.1.seconds).sum(),
        }
    }
}

/// How much of the study a run computes: `--quick` (a smoke run for CI), the default (the
/// answer at reduced pixel counts, a few minutes on 2 cores) or `--full` (the committed
/// docs/REPORT.md).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Scale {
    Quick,
    Default,
    Full,
}

impl Scale {
    /// The setting of this scale among `[quick, default, full]`.
    pub fn pick<T>(self, [quick, default, full]: [T; 3]) -> T {
        match self {
            Scale::Quick => quick,
            Scale::Default => default,
            Scale::Full => full,
        }
    }
}

/// What to run.
#[derive(Clone, Debug)]
pub struct Config {
    pub pixels: usize,
    pub spps: Vec<usize>,
    pub threads: usize,
    /// Samples per timing measurement (per combination and count).
    pub timing_samples: usize,
    pub timing_reps: usize,
}

/// Runs the error experiment of one scene over `cfg.pixels` pixels on `cfg.threads` threads.
pub fn errors<S: Scene>(scene: &S, cfg: &Config, bar: &ProgressBar) -> SceneResult {
    let start = Instant::now();
    let name = scene.name();
    let warps = scene.warps();
    let combos = warps.len() * SAMPLERS.len();
    let ns = cfg.spps.len();
    let chunk = 32;
    let next = AtomicUsize::new(0);
    let total = Mutex::new((vec![Stat::default(); combos * ns], 0usize));
    std::thread::scope(|sc| {
        for _ in 0..cfg.threads.max(1) {
            sc.spawn(|| {
                let mut stats = vec![Stat::default(); combos * ns];
                let mut penumbra = 0;
                let mut s = Scratch::default();
                loop {
                    let first = next.fetch_add(chunk, Ordering::Relaxed);
                    if first >= cfg.pixels {
                        break;
                    }
                    let last = (first + chunk).min(cfg.pixels);
                    for i in first..last {
                        let px = scene.pixel(i as u64);
                        penumbra += scene.penumbra(&px) as usize;
                        for (k, &spp) in cfg.spps.iter().enumerate() {
                            for sampler in SAMPLERS {
                                let seed = seed(&name, i as u64, spp, sampler);
                                for w in 0..warps.len() {
                                    if scene.alias(w, sampler).is_some()
                                        || !scene.applies(w, sampler)
                                    {
                                        continue;
                                    }
                                    scene.draw_for(&px, w, sampler, spp, seed, &mut s);
                                    let est = scene.evaluate(&px, w, spp, &s);
                                    let c = w * SAMPLERS.len() + sampler.index();
                                    stats[c * ns + k].add(est - scene.reference(&px, w));
                                }
                            }
                        }
                    }
                    bar.inc((last - first) as u64);
                }
                let mut t = total.lock().unwrap();
                for (a, b) in t.0.iter_mut().zip(&stats) {
                    a.merge(b);
                }
                t.1 += penumbra;
            });
        }
    });
    let (stats, penumbra) = total.into_inner().unwrap();
    let mut rows = Vec::new();
    for (w, &warp) in warps.iter().enumerate() {
        for sampler in SAMPLERS {
            if !scene.applies(w, sampler) {
                continue;
            }
            let alias_of = scene.alias(w, sampler);
            let from = alias_of.unwrap_or(sampler);
            let c = w * SAMPLERS.len() + from.index();
            rows.push(Row {
                sampler,
                warp,
                stats: stats[c * ns..(c + 1) * ns]
                    .iter()
                    .map(Summary::of)
                    .collect(),
                ns: vec![f64::NAN; ns],
                alias_of,
            });
        }
    }
    SceneResult {
        scene: name,
        description: scene.description(),
        pixels: cfg.pixels,
        penumbra: penumbra as f64 / cfg.pixels as f64,
        spps: cfg.spps.clone(),
        rows,
        seconds: start.elapsed().as_secs_f64(),
    }
}

/// Nanoseconds per sample to draw and warp `spp` samples per pixel (see the module docs).
pub fn time_per_sample<S: Scene>(
    scene: &S,
    warp: usize,
    sampler: Sampler,
    spp: usize,
    cfg: &Config,
) -> f64 {
    let pixels = (cfg.timing_samples / spp).max(1);
    let mut s = Scratch::default();
    s.reserve(spp);
    let mut best = f64::INFINITY;
    for rep in 0..cfg.timing_reps.max(1) {
        let t = Instant::now();
        for p in 0..pixels {
            let seed = (p as u32).wrapping_mul(0x9e37_79b9) ^ rep as u32;
            scene.draw(warp, sampler, spp, black_box(seed), &mut s);
            black_box(&s);
        }
        best = best.min(t.elapsed().as_secs_f64());
    }
    best * 1e9 / (pixels * spp) as f64
}

/// Fills in the `ns` of every row of `result` (an alias row copies its source's times).
pub fn timings<S: Scene>(scene: &S, cfg: &Config, result: &mut SceneResult, bar: &ProgressBar) {
    let warps = scene.warps();
    for row in result.rows.iter_mut().filter(|r| r.alias_of.is_none()) {
        let w = warps.iter().position(|&x| x == row.warp).unwrap_or(0);
        for (k, &spp) in cfg.spps.iter().enumerate() {
            row.ns[k] = time_per_sample(scene, w, row.sampler, spp, cfg);
        }
        bar.inc(1);
    }
    for i in 0..result.rows.len() {
        if let Some(from) = result.rows[i].alias_of {
            let warp = result.rows[i].warp;
            if let Some(src) = result.row(from, warp) {
                result.rows[i].ns = src.ns.clone();
            }
            bar.inc(1);
        }
    }
}
