//! Blue noise over a whole path, and frames of 1 sample per pixel on the path scenes
//! (issue 34, items 3 and 5).
//!
//! * [`blurred_mses`]: the MSE after a Gaussian blur of independent renders (one per seed),
//!   minus the reference's own variance after the same blur, so ratios between samplers come
//!   with a standard error over seeds ([`ratio`]) instead of the scatter of one run.
//! * [`by_length`]: which path length carries the blurred error (two independent renders per
//!   seed, no reference needed: `E |G (a - b)|^2 = 2 E |G e|^2`).
//! * [`frame_errors`]: 1 sample per pixel per frame, accumulated over `F` frames: per-frame
//!   blurred error, running mean (blurred and per pixel), exponential moving average (alpha
//!   0.1) after a sigma-1 blur, and the per-pixel MSE of the one-frame render at `F` spp.
//!
//! The samplers are [`PathSampler`]s; the frame drivers ([`FrameSource`]) say how each
//! library is asked for frame `t` (warpcore's `Sampler::new_frame`, openqmc-rs's index
//! counting on across frames, ZSobol's `F`-sample pixel, white noise).

use super::metrics::{blur, diff, squares};
use super::reference::Reference;
use super::samplers::{PathSampler, Random, ROULETTE_DOMAIN, hash32};
use super::scene::Scene;
use super::trace::{self, Image, MAX_LENGTH};
use std::marker::PhantomData;
use warpcore::sampler::{Pattern, Sampler};

/// A path scene at `size x size` pixels with its cached reference (`docs/report`, averaged
/// down from 64 x 64).
pub struct Bench {
    pub scene: Scene,
    pub mean: Image,
    half: Image,
}

impl Bench {
    pub fn new(name: &str, size: usize) -> Result<Bench, String> {
        let dir = std::path::PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/report"));
        let path = Reference::path(&dir, name);
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let r = Reference::from_bytes(&bytes)?;
        let f = (r.a.width / size.max(1)).max(1);
        let r = r.downsample(f);
        let scene = Scene::by_name(name, r.a.width).ok_or("unknown path scene")?;
        Ok(Bench {
            scene,
            mean: r.mean(),
            half: r.half_difference(),
        })
    }

    /// The reference's own variance after a blur of `sigma` (mean over pixels and channels).
    pub fn ref_var(&self, sigma: f64) -> f64 {
        mean(&squares(&blur(&self.half, sigma)))
    }

    /// Mean over pixels of the blurred squared error of `img`, minus the reference's.
    pub fn blurred_mse(&self, img: &Image, sigma: f64) -> f64 {
        mean(&squares(&blur(&diff(img, &self.mean), sigma))) - self.ref_var(sigma)
    }
}

fn mean(v: &[f64]) -> f64 {
    v.iter().sum::<f64>() / v.len().max(1) as f64
}

/// Mean and standard error of the mean.
pub fn mean_se(v: &[f64]) -> (f64, f64) {
    super::metrics::mean_se(v)
}

/// `a / b` of two independent means `(m, se)`, with its standard error (delta method).
pub fn ratio(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let q = a.0 / b.0;
    (q, q.abs() * ((a.1 / a.0).powi(2) + (b.1 / b.0).powi(2)).sqrt())
}

/// Runs `f(k)` for `k in 0..n` on `threads` threads, results in order.
pub fn par_map<T: Send>(n: usize, threads: usize, f: impl Fn(usize) -> T + Sync) -> Vec<T> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let out: Vec<std::sync::Mutex<Option<T>>> = (0..n).map(|_| Default::default()).collect();
    std::thread::scope(|sc| {
        for _ in 0..threads.max(1) {
            sc.spawn(|| {
                loop {
                    let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    if k >= n {
                        break;
                    }
                    let v = f(k);
                    if let Ok(mut slot) = out[k].lock() {
                        *slot = Some(v);
                    }
                }
            });
        }
    });
    out.into_iter()
        .filter_map(|m| m.into_inner().ok().flatten())
        .collect()
}

/// The seed of render `k` of sampler `salt` (independent renders).
pub fn seed(salt: u32, k: u32) -> u32 {
    hash32(salt ^ hash32(k ^ 0x7a11_5eed))
}

/// The blurred MSE (sigma px, reference variance subtracted) of `seeds` independent renders
/// of `s` at `spp`.
pub fn blurred_mses<S: PathSampler>(
    b: &Bench,
    s: &S,
    spp: u32,
    seeds: u32,
    salt: u32,
    sigma: f64,
    threads: usize,
) -> Vec<f64> {
    par_map(seeds as usize, threads, |k| {
        let img = trace::render(&b.scene, s, spp, seed(salt, k as u32));
        b.blurred_mse(&img, sigma)
    })
}

/// Per path length `0..=MAX_LENGTH`: `[unblurred, blurred]` variance of the error (mean
/// over pixels and channels), from `pairs` pairs of independent renders at `spp`.
pub fn by_length<S: PathSampler>(
    scene: &Scene,
    s: &S,
    spp: u32,
    pairs: u32,
    sigma: f64,
    threads: usize,
) -> Vec<[f64; 2]> {
    let per: Vec<Vec<[f64; 2]>> = par_map(pairs as usize, threads, |k| {
        let [a, b] = [0, 1].map(|j| trace::render_by_length(scene, s, spp, seed(j, k as u32)));
        a.iter()
            .zip(&b)
            .map(|(a, b)| {
                let d = diff(a, b);
                [mean(&squares(&d)) / 2.0, mean(&squares(&blur(&d, sigma))) / 2.0]
            })
            .collect()
    });
    (0..=MAX_LENGTH)
        .map(|l| {
            let n = per.len().max(1) as f64;
            [0, 1].map(|j| per.iter().map(|p| p[l][j]).sum::<f64>() / n)
        })
        .collect()
}

/// warpcore's sampler with the path's light point and BSDF direction from two 2D domains
/// of the vertex's domain (`domain(2 + d).domain(0)` and `.domain(1)`), each a `draw::<2>()`
/// (the draw the blue-noise tiles are optimised for), instead of one `draw::<4>()`.
pub struct WarpcorePairs<P>(pub PhantomData<fn() -> P>);

impl<P: Pattern> PathSampler for WarpcorePairs<P> {
    type Sample = Sampler<P>;
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> Sampler<P> {
        Sampler::<P>::new(pixel, 0, index, seed)
    }
    fn draw2(&self, s: &Sampler<P>, domain: u32) -> [f32; 2] {
        s.domain(domain).draw::<2>()
    }
    fn draw4(&self, s: &Sampler<P>, domain: u32) -> [f32; 4] {
        let v = s.domain(domain);
        let ([a, b], [c, d]) = (v.domain(0).draw::<2>(), v.domain(1).draw::<2>());
        [a, b, c, d]
    }
    fn rnd(&self, s: &Sampler<P>, domain: u32) -> f32 {
        s.domain(0x100 + domain).rnd::<1>()[0]
    }
}

/// Any sampler with the dimensions of vertices `>= depth` (and every roulette decision)
/// taken from `rest`: what the blue noise of the first vertices is worth alone.
pub struct Prefix<A, B> {
    pub first: A,
    pub rest: B,
    /// Domains below this come from `first` (`2 + d`: vertex `d`).
    pub below: u32,
}

impl<A: PathSampler, B: PathSampler> PathSampler for Prefix<A, B> {
    type Sample = (A::Sample, B::Sample);
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> Self::Sample {
        (
            self.first.sample(pixel, index, spp, seed),
            self.rest.sample(pixel, index, spp, seed ^ 0x5151_5151),
        )
    }
    fn draw2(&self, s: &Self::Sample, domain: u32) -> [f32; 2] {
        if domain < self.below {
            self.first.draw2(&s.0, domain)
        } else {
            self.rest.draw2(&s.1, domain)
        }
    }
    fn draw4(&self, s: &Self::Sample, domain: u32) -> [f32; 4] {
        if domain < self.below {
            self.first.draw4(&s.0, domain)
        } else {
            self.rest.draw4(&s.1, domain)
        }
    }
    fn rnd(&self, s: &Self::Sample, domain: u32) -> f32 {
        self.rest.rnd(&s.1, domain)
    }
}

/// Roulette domains are `ROULETTE_DOMAIN + d`: above every vertex domain.
const _: () = assert!(ROULETTE_DOMAIN > 2 + MAX_LENGTH as u32);

/// Independent uniform numbers (the white-noise peer), re-exported for the frame drivers.
pub type White = Random;

/// Any sampler with the camera ray's pixel position and lens point from one 4D draw of
/// domain 0 (dimensions 0-1 the position, 2-3 the lens) instead of two 2D domains.
pub struct Camera4<S>(pub S);

impl<S: PathSampler> PathSampler for Camera4<S> {
    type Sample = S::Sample;
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> S::Sample {
        self.0.sample(pixel, index, spp, seed)
    }
    fn draw2(&self, s: &S::Sample, domain: u32) -> [f32; 2] {
        match domain {
            0 => {
                let [a, b, _, _] = self.0.draw4(s, 0);
                [a, b]
            }
            1 => {
                let [_, _, c, d] = self.0.draw4(s, 0);
                [c, d]
            }
            _ => self.0.draw2(s, domain),
        }
    }
    fn draw4(&self, s: &S::Sample, domain: u32) -> [f32; 4] {
        self.0.draw4(s, domain)
    }
    fn rnd(&self, s: &S::Sample, domain: u32) -> f32 {
        self.0.rnd(s, domain)
    }
}
