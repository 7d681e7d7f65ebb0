//! Blue noise over a whole path, and frames of 1 sample per pixel on the path scenes.
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
//! The samplers are [`PathSampler`]s; the frame drivers ([`WarpcoreFrame`], [`PeerFrame`],
//! [`ZSobolPath`]) say how each library is asked for frame `t` (warpcore's
//! `Sampler::new_frame`, openqmc-rs's index counting on across frames, ZSobol's `F`-sample
//! pixel, white noise).

use super::metrics::{blur, diff, squares};
use super::reference::Reference;
use super::samplers::{PathSampler, ROULETTE_DOMAIN, Random, Warpcore, WarpcorePairs, hash32};
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
    (
        q,
        q.abs() * ((a.1 / a.0).powi(2) + (b.1 / b.0).powi(2)).sqrt(),
    )
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
                [
                    mean(&squares(&d)) / 2.0,
                    mean(&squares(&blur(&d, sigma))) / 2.0,
                ]
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

/// warpcore's sampler as a real-time renderer calls it frame after frame:
/// `Sampler::new_frame(pixel, frame, spp, index, seed)` (the frames continue one sequence per
/// pixel), or with `fresh`, `Sampler::new(pixel, frame, index, seed)` (a fresh randomisation
/// per frame). The draws are `draws`'s ([`Warpcore`] or [`WarpcorePairs`]).
pub struct WarpcoreFrame<S> {
    pub frame: u32,
    pub fresh: bool,
    pub draws: S,
}

impl<P: Pattern, S: PathSampler<Sample = Sampler<P>>> PathSampler for WarpcoreFrame<S> {
    type Sample = Sampler<P>;
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> Sampler<P> {
        if self.fresh {
            Sampler::<P>::new(pixel, self.frame, index, seed)
        } else {
            Sampler::<P>::new_frame(pixel, self.frame, spp, index, seed)
        }
    }
    fn draw2(&self, s: &Sampler<P>, domain: u32) -> [f32; 2] {
        self.draws.draw2(s, domain)
    }
    fn draw4(&self, s: &Sampler<P>, domain: u32) -> [f32; 4] {
        self.draws.draw4(s, domain)
    }
    fn rnd(&self, s: &Sampler<P>, domain: u32) -> f32 {
        self.draws.rnd(s, domain)
    }
}

/// A peer at frame `frame`: with `continued`, its sample index counts on across frames
/// (`frame * spp + index`, the render's seed fixed: openqmc-rs's progressive use, ZSobol's
/// pixel of `F` samples); otherwise the frame is hashed into the seed (a fresh randomisation
/// per frame: white noise, openqmc-rs with the frame in its `frame` argument).
pub struct PeerFrame<S> {
    pub inner: S,
    pub frame: u32,
    pub continued: bool,
}

impl<S: PathSampler> PathSampler for PeerFrame<S> {
    type Sample = S::Sample;
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> S::Sample {
        if self.continued {
            let i = self.frame.wrapping_mul(spp.max(1)).wrapping_add(index);
            self.inner.sample(pixel, i, spp, seed)
        } else {
            self.inner
                .sample(pixel, index, spp, seed ^ hash32(self.frame ^ 0xf4a3_e001))
        }
    }
    fn draw2(&self, s: &S::Sample, domain: u32) -> [f32; 2] {
        self.inner.draw2(s, domain)
    }
    fn draw4(&self, s: &S::Sample, domain: u32) -> [f32; 4] {
        self.inner.draw4(s, domain)
    }
    fn rnd(&self, s: &S::Sample, domain: u32) -> f32 {
        self.inner.rnd(s, domain)
    }
}

/// The Morton-ordered Sobol' peer ([`crate::bluenoise::zsobol`]) over a whole path: pixels of
/// `2^log2_spp` samples; a path's 2D domain `k` is the pair of dimension key `2k` (keyed by
/// the render's seed), a 4D domain the pairs `2k` and `2k + 1`.
#[cfg(feature = "blue-noise")]
pub struct ZSobolPath {
    pub log2_spp: u32,
}

#[cfg(feature = "blue-noise")]
impl PathSampler for ZSobolPath {
    /// (pixel, index, seed)
    type Sample = ([u32; 2], u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> Self::Sample {
        (pixel, index, seed)
    }
    fn draw2(&self, s: &Self::Sample, domain: u32) -> [f32; 2] {
        let dim = hash32(s.2 ^ hash32(2 * domain));
        crate::bluenoise::zsobol(s.0[0], s.0[1], self.log2_spp, s.1, dim)
    }
    fn draw4(&self, s: &Self::Sample, domain: u32) -> [f32; 4] {
        let [a, b] = self.draw2(s, domain);
        let dim = hash32(s.2 ^ hash32(2 * domain + 1));
        let [c, d] = crate::bluenoise::zsobol(s.0[0], s.0[1], self.log2_spp, s.1, dim);
        [a, b, c, d]
    }
    fn rnd(&self, s: &Self::Sample, domain: u32) -> f32 {
        Random.rnd(&(hash32(s.2 ^ s.0[0] ^ hash32(s.0[1])), s.1), domain)
    }
}

/// The blur of each frame's and the running mean's error (px), as the path scenes'
/// "denoised" figure.
pub const FRAME_SIGMA: f64 = 2.0;
/// The blur after the exponential moving average (px).
pub const EMA_SIGMA: f64 = 1.0;
/// The exponential moving average's weight of the new frame.
pub const EMA_ALPHA: f64 = 0.1;

/// What `F` frames of 1 spp leave (reference variance subtracted from each): the mean over
/// frames of the per-frame MSE after a [`FRAME_SIGMA`] blur and the worst frame's; the
/// running mean's MSE after the same blur and per pixel (unblurred); the EMA's MSE after an
/// [`EMA_SIGMA`] blur; and the per-pixel MSE of one frame at `F` spp of the same pattern.
#[derive(Clone, Copy, Debug)]
pub struct FrameErrors {
    pub frame_mean: f64,
    pub frame_worst: f64,
    pub mean_blurred: f64,
    pub mean_pixel: f64,
    pub ema: f64,
    pub one_frame_pixel: f64,
}

/// [`FrameErrors`] after each count of `counts` (ascending) of one run of frames: frame `t`
/// rendered by `frame(t)` (1 spp), the one-frame render at `F` spp by `one(F)`.
pub fn frame_errors<S: PathSampler, T: PathSampler>(
    b: &Bench,
    counts: &[u32],
    seed: u32,
    frame: impl Fn(u32) -> S + Sync,
    one: impl Fn(u32) -> T + Sync,
    threads: usize,
) -> Vec<FrameErrors> {
    let top = counts.iter().copied().max().unwrap_or(0);
    let errs: Vec<Image> = par_map(top as usize, threads, |t| {
        diff(&trace::render(&b.scene, &frame(t as u32), 1, seed), &b.mean)
    });
    let ones: Vec<f64> = par_map(counts.len(), threads, |k| {
        let f = counts[k];
        let img = trace::render(&b.scene, &one(f), f, seed);
        mean(&squares(&diff(&img, &b.mean))) - b.ref_var(0.0)
    });
    let (rv0, rvf, rve) = (b.ref_var(0.0), b.ref_var(FRAME_SIGMA), b.ref_var(EMA_SIGMA));
    let n = b.mean.px.len();
    let (mut sum, mut ema) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
    let (mut total, mut worst) = (0.0, f64::MIN);
    let mut out = Vec::new();
    for (t, e) in errs.iter().enumerate() {
        let m = mean(&squares(&blur(e, FRAME_SIGMA))) - rvf;
        total += m;
        worst = worst.max(m);
        for (k, p) in e.px.iter().enumerate() {
            for c in 0..3 {
                sum[k][c] += p[c];
                ema[k][c] = if t == 0 {
                    p[c]
                } else {
                    (1.0 - EMA_ALPHA) * ema[k][c] + EMA_ALPHA * p[c]
                };
            }
        }
        let f = t as u32 + 1;
        if let Some(k) = counts.iter().position(|&c| c == f) {
            let img = |px: Vec<[f64; 3]>| Image {
                width: b.mean.width,
                height: b.mean.height,
                px,
            };
            let running = img(sum.iter().map(|p| p.map(|v| v / f as f64)).collect());
            out.push(FrameErrors {
                frame_mean: total / f as f64,
                frame_worst: worst,
                mean_blurred: mean(&squares(&blur(&running, FRAME_SIGMA))) - rvf,
                mean_pixel: mean(&squares(&running)) - rv0,
                ema: mean(&squares(&blur(&img(ema.clone()), EMA_SIGMA))) - rve,
                one_frame_pixel: ones[k],
            });
        }
    }
    out
}

/// One row of the frames table: its name and how a run of frames is measured for a seed.
pub type FrameRow<'a> = (
    &'static str,
    Box<dyn Fn(u32) -> Vec<FrameErrors> + Sync + 'a>,
);

/// The rows of the frames table on `b` (`counts` ascending; ZSobol's pixels hold the top
/// count): white noise, every warpcore pattern through `new_frame` (and the blue ones with
/// a fresh randomisation per frame), the openqmc-rs samplers with the index counting on
/// (their progressive use) and the blue-noise ones with the frame in `frame` (their
/// real-time use), ZSobol.
#[cfg(feature = "blue-noise")]
pub fn frame_rows<'a>(b: &'a Bench, counts: &'a [u32], threads: usize) -> Vec<FrameRow<'a>> {
    use super::samplers::OpenQmc;
    use std::marker::PhantomData as PD;
    use warpcore::sampler::{Blue, Pmj02bn, Sobol};
    fn ours<'a, P: Pattern, S: PathSampler<Sample = Sampler<P>> + Copy + Sync + 'a>(
        name: &'static str,
        fresh: bool,
        draws: S,
        b: &'a Bench,
        counts: &'a [u32],
        t: usize,
    ) -> FrameRow<'a> {
        let at = move |frame| WarpcoreFrame {
            frame,
            fresh,
            draws,
        };
        (
            name,
            Box::new(move |seed| frame_errors(b, counts, seed, at, |_| at(0), t)),
        )
    }
    fn peer<'a, S: PathSampler + Sync + 'a>(
        name: &'static str,
        continued: bool,
        make: impl Fn(u32) -> S + Sync + Copy + 'a,
        b: &'a Bench,
        counts: &'a [u32],
        t: usize,
    ) -> FrameRow<'a> {
        let top = counts.iter().copied().max().unwrap_or(1);
        let at = move |frame| PeerFrame {
            inner: make(top),
            frame,
            continued,
        };
        let one = move |f| PeerFrame {
            inner: make(f),
            frame: 0,
            continued,
        };
        (
            name,
            Box::new(move |seed| frame_errors(b, counts, seed, at, one, t)),
        )
    }
    fn oq<T>(_: u32) -> OpenQmc<T> {
        OpenQmc(PhantomData)
    }
    let zs = |f: u32| ZSobolPath {
        log2_spp: f.max(1).ilog2(),
    };
    use openqmc::{
        LatticeBnSampler, LatticeSampler, PmjBnSampler, PmjSampler, SobolBnSampler, SobolSampler,
    };
    vec![
        peer("white noise", false, |_| Random, b, counts, threads),
        ours(
            "pmj02bn",
            false,
            Warpcore::<Pmj02bn>(PD),
            b,
            counts,
            threads,
        ),
        ours("sobol", false, Warpcore::<Sobol>(PD), b, counts, threads),
        ours(
            "blue_pmj02bn",
            false,
            WarpcorePairs::<Blue<Pmj02bn>>(PD),
            b,
            counts,
            threads,
        ),
        ours(
            "blue_sobol",
            false,
            WarpcorePairs::<Blue<Sobol>>(PD),
            b,
            counts,
            threads,
        ),
        ours(
            "blue_pmj02bn, fresh frames",
            true,
            WarpcorePairs::<Blue<Pmj02bn>>(PD),
            b,
            counts,
            threads,
        ),
        ours(
            "blue_sobol, fresh frames",
            true,
            WarpcorePairs::<Blue<Sobol>>(PD),
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_sobol",
            true,
            oq::<SobolSampler>,
            b,
            counts,
            threads,
        ),
        peer("openqmc_pmj", true, oq::<PmjSampler>, b, counts, threads),
        peer(
            "openqmc_lattice",
            true,
            oq::<LatticeSampler>,
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_sobolbn",
            true,
            oq::<SobolBnSampler>,
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_pmjbn",
            true,
            oq::<PmjBnSampler>,
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_latticebn",
            true,
            oq::<LatticeBnSampler>,
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_sobolbn, frame",
            false,
            oq::<SobolBnSampler>,
            b,
            counts,
            threads,
        ),
        peer(
            "openqmc_pmjbn, frame",
            false,
            oq::<PmjBnSampler>,
            b,
            counts,
            threads,
        ),
        peer("zsobol", true, zs, b, counts, threads),
    ]
}

/// The mean over `seeds` runs of each row's [`FrameErrors`] (one per count).
pub fn frame_table(rows: &[FrameRow<'_>], seeds: u32) -> Vec<(&'static str, Vec<FrameErrors>)> {
    rows.iter()
        .map(|(name, run)| {
            let runs: Vec<Vec<FrameErrors>> = (0..seeds).map(|s| run(seed(0xf7a3, s))).collect();
            let n = runs.len().max(1) as f64;
            let avg = (0..runs.first().map_or(0, |r| r.len()))
                .map(|k| {
                    let m =
                        |f: fn(&FrameErrors) -> f64| runs.iter().map(|r| f(&r[k])).sum::<f64>() / n;
                    FrameErrors {
                        frame_mean: m(|e| e.frame_mean),
                        frame_worst: m(|e| e.frame_worst),
                        mean_blurred: m(|e| e.mean_blurred),
                        mean_pixel: m(|e| e.mean_pixel),
                        ema: m(|e| e.ema),
                        one_frame_pixel: m(|e| e.one_frame_pixel),
                    }
                })
                .collect();
            (*name, avg)
        })
        .collect()
}

/// The markdown of the frames tables of one scene: per count, each row's figures as ratios
/// to white noise's (the per-pixel column as the ratio to the same pattern's one frame at
/// `F` spp).
pub fn frames_markdown(
    scene: &str,
    size: usize,
    seeds: u32,
    counts: &[u32],
    table: &[(&'static str, Vec<FrameErrors>)],
) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    for (k, f) in counts.iter().enumerate() {
        let _ = writeln!(
            s,
            "\n`{scene}`, {size} x {size} pixels, {f} frames of 1 spp, mean over {seeds} seeds: MSE after a sigma-{FRAME_SIGMA} blur per frame (mean over frames, worst frame) and of the running mean, the running mean's per-pixel MSE, the EMA (alpha {EMA_ALPHA}) after a sigma-{EMA_SIGMA} blur; in brackets the ratio to white noise; last column the running mean's per-pixel MSE / one frame at {f} spp of the same sampler.\n"
        );
        let _ = writeln!(
            s,
            "| sampler | frame, mean | frame, worst | running mean, blurred | running mean, per pixel | EMA, blurred | mean / one frame at {f} spp |\n|---|---:|---:|---:|---:|---:|---:|"
        );
        let white = table.first().and_then(|(_, v)| v.get(k)).copied();
        for (name, v) in table {
            let (Some(e), Some(w)) = (v.get(k), white) else {
                continue;
            };
            let c = |a: f64, b: f64| format!("{a:.2e} ({:.2}x)", a / b);
            let _ = writeln!(
                s,
                "| {name} | {} | {} | {} | {} | {} | {:.2} |",
                c(e.frame_mean, w.frame_mean),
                c(e.frame_worst, w.frame_worst),
                c(e.mean_blurred, w.mean_blurred),
                c(e.mean_pixel, w.mean_pixel),
                c(e.ema, w.ema),
                e.mean_pixel / e.one_frame_pixel
            );
        }
    }
    s
}

/// The frames tables of `scenes` (`path-frames.md`): `size x size` pixels, `counts` frames,
/// the mean over `seeds` runs. `cargo run-report` writes it at 32 x 32 pixels over 2 seeds
/// (quick: 32 frames, 1 seed; `--full`: 64 x 64 over 40 seeds, into `docs/report`: 4 seeds were
/// off the 40-seed ratios by up to 0.12, as much as the samplers differ).
#[cfg(feature = "blue-noise")]
pub fn run_frames(
    scenes: &[String],
    size: usize,
    counts: &[u32],
    seeds: u32,
    threads: usize,
) -> Result<String, String> {
    let mut md = String::new();
    for name in scenes.iter().filter(|n| !n.contains('/')) {
        let b = Bench::new(name, size)?;
        let rows = frame_rows(&b, counts, threads);
        let table = frame_table(&rows, seeds);
        md += &frames_markdown(name, b.mean.width, seeds, counts, &table);
    }
    Ok(md)
}
