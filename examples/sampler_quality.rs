//! Integration error of the sampling core on path-tracer-like integrands, against OpenQMC's
//! samplers (openqmc-rs 0.2.4), `sobol_burley` and plain random numbers.
//!
//! Every sampler hands out the dimensions of one "path" the way a renderer asks for them:
//! `domain(0).draw::<2>()` (pixel position), `domain(1).draw::<2>()` (lens), then one
//! `domain(2 + b).draw::<4>()` per bounce `b < 3` (a light point and a BSDF direction): 16
//! dimensions per sample, from five domains. Four integrands with exact (analytic)
//! integrals, each normalised to an integral of 1:
//!
//! * **pairs x**: the product, over the eight 2D pairs, of `0.5 + gaussian + 0.5 step`
//!   (a Gaussian bump and a half-plane step at a random angle, one per pair);
//! * **pairs +**: the sum of the same eight factors;
//! * **4D**: one 4D function of the first bounce's 4D draw: a 4D Gaussian, the step
//!   `x0 + x1 + x2 + x3 < t` and a product of two 1D steps;
//! * **cross**: a product of couplings between dimensions of *different* domains (Gaussians
//!   of differences, steps `u + v < t` and `u < v`): a shared index order or correlated
//!   domains shows here.
//!
//! The error is measured per pixel: each pixel is an independent randomisation (its own
//! scrambles), the estimate of a pixel at `n` samples per pixel is the mean over the sample
//! indices `0..n` (one progressive sequence: 16, 64 and 256 are prefixes of one run), and the
//! table gives the mean squared error over all pixels.
//!
//! Run: `cargo run --release --example sampler_quality [-- --pixels N]` (default 16384
//! pixels of a 256-pixel-wide image: about 13 s of CPU time, spread over the threads).

use std::f64::consts::PI;
use std::time::Instant;
use warpcore::sampler::{Pmj02bn, Sampler, Sobol};

/// Samples per pixel at which the error is reported (prefixes of one run of `SPP[2]`).
const SPP: [usize; 3] = [16, 64, 256];
/// Dimensions of one path: 2 + 2 + 3 x 4.
const DIMS: usize = 16;

/// A sampler as the table sees it: the 16 dimensions of sample `index` of `pixel`.
type Path = fn([u32; 2], u32) -> [f64; DIMS];

/// One path from a sampler's domains: domains 0 and 1 draw two dimensions, 2..5 draw four.
fn path_of(draw2: impl Fn(u32) -> [f32; 2], draw4: impl Fn(u32) -> [f32; 4]) -> [f64; DIMS] {
    let mut d = [0.0; DIMS];
    d[..2].copy_from_slice(&draw2(0).map(f64::from));
    d[2..4].copy_from_slice(&draw2(1).map(f64::from));
    for bounce in 0..3 {
        let c = draw4(2 + bounce as u32);
        d[4 + 4 * bounce..8 + 4 * bounce].copy_from_slice(&c.map(f64::from));
    }
    d
}

/// One path from a warpcore sampler (`root.domain(k).draw::<N>()`).
fn warpcore_path<P: warpcore::sampler::Pattern>(pixel: [u32; 2], index: u32) -> [f64; DIMS] {
    let root = Sampler::<P>::new(pixel, 0, index, 0);
    path_of(
        |k| root.domain(k).draw::<2>(),
        |k| root.domain(k).draw::<4>(),
    )
}

/// The same path from an openqmc-rs sampler (`X::new(x, y, frame, index).new_domain(k)`).
fn openqmc_path<T: openqmc::SamplerImpl>(pixel: [u32; 2], index: u32) -> [f64; DIMS] {
    let root = openqmc::Sampler::<T>::new(pixel[0] as i32, pixel[1] as i32, 0, index as i32);
    path_of(
        |k| root.new_domain(k as i32).draw_sample_f32::<2>(),
        |k| root.new_domain(k as i32).draw_sample_f32::<4>(),
    )
}

/// A well-mixed 32-bit hash (lowbias32) for the seeds of the baselines.
fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// `sobol_burley::sample_4d`: domain `k` is dimension set `k` (dimensions `4k..4k+3` of one
/// Owen-scrambled Sobol' sequence), the seed a hash of the pixel.
fn sobol_burley_path(pixel: [u32; 2], index: u32) -> [f64; DIMS] {
    let seed = hash(pixel[0] ^ hash(pixel[1] ^ 0x5851_f42d));
    let mut d = [0.0; DIMS];
    let set = |k: u32| sobol_burley::sample_4d(index, k, seed).map(f64::from);
    d[..2].copy_from_slice(&set(0)[..2]);
    d[2..4].copy_from_slice(&set(1)[..2]);
    for bounce in 0..3 {
        d[4 + 4 * bounce..8 + 4 * bounce].copy_from_slice(&set(2 + bounce as u32));
    }
    d
}

/// Independent uniform numbers: a counter hash of (pixel, index, dimension), 53 bits each.
fn random_path(pixel: [u32; 2], index: u32) -> [f64; DIMS] {
    let base = hash(pixel[0] ^ hash(pixel[1] ^ hash(index ^ 0x2545_f491)));
    std::array::from_fn(|k| {
        let hi = hash(base ^ hash(2 * k as u32 + 1)) as u64;
        let lo = hash(base ^ hash(2 * k as u32 + 2) ^ 0x9e37_79b9) as u64;
        (((hi << 32) | lo) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    })
}

/// A deterministic source of integrand parameters (splitmix64).
struct Params(u64);

impl Params {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// `integral over [0, 1] of exp(-(x - c)^2 / (2 s^2)) dx`.
fn gauss_1d(c: f64, s: f64) -> f64 {
    let k = s * std::f64::consts::SQRT_2;
    s * (PI / 2.0).sqrt() * (libm::erf((1.0 - c) / k) + libm::erf(c / k))
}

/// `integral over [0, 1]^2 of exp(-(u - v)^2 / (2 s^2))`.
fn gauss_of_difference(s: f64) -> f64 {
    let k = s * std::f64::consts::SQRT_2;
    2.0 * (s * (PI / 2.0).sqrt() * libm::erf(1.0 / k) - s * s * (1.0 - (-1.0 / (k * k)).exp()))
}

/// Area of `{p in [0, 1]^2 : n . p < t}` (the square clipped by the half-plane).
fn half_plane_area(n: [f64; 2], t: f64) -> f64 {
    pmjgen::tool::square_area_below(|p| n[0] * p[0] + n[1] * p[1] - t).abs()
}

/// `P(u0 + u1 + u2 + u3 < t)` for independent uniforms (the Irwin-Hall distribution).
fn irwin_hall_4(t: f64) -> f64 {
    let binom = [1.0, 4.0, 6.0, 4.0, 1.0];
    (0..=4)
        .filter(|&k| t > k as f64)
        .map(|k| (-1f64).powi(k) * binom[k as usize] * (t - k as f64).powi(4))
        .sum::<f64>()
        / 24.0
}

/// One 2D factor of the pair integrands: `0.5 + gaussian + 0.5 step`, with its integral.
struct Factor {
    c: [f64; 2],
    s: f64,
    n: [f64; 2],
    t: f64,
    integral: f64,
}

impl Factor {
    fn new(r: &mut Params) -> Self {
        let c = [r.range(0.2, 0.8), r.range(0.2, 0.8)];
        let s = r.range(0.08, 0.3);
        let angle = r.range(0.0, 2.0 * PI);
        let n = [angle.cos(), angle.sin()];
        let q = [r.range(0.2, 0.8), r.range(0.2, 0.8)];
        let t = n[0] * q[0] + n[1] * q[1];
        let integral = 0.5 + gauss_1d(c[0], s) * gauss_1d(c[1], s) + 0.5 * half_plane_area(n, t);
        Factor {
            c,
            s,
            n,
            t,
            integral,
        }
    }
    fn eval(&self, x: f64, y: f64) -> f64 {
        let r2 = (x - self.c[0]).powi(2) + (y - self.c[1]).powi(2);
        let step = if self.n[0] * x + self.n[1] * y < self.t {
            0.5
        } else {
            0.0
        };
        (0.5 + (-r2 / (2.0 * self.s * self.s)).exp() + step) / self.integral
    }
}

/// A coupling of two dimensions from different domains, with its integral.
enum Coupling {
    Gauss(usize, usize, f64),
    SumBelow(usize, usize, f64),
    Below(usize, usize),
}

/// The four integrands, each normalised to integrate to 1 over `[0, 1]^16`.
struct Integrands {
    factors: Vec<Factor>,
    /// 4D: Gaussian centre and width, the simplex-like step threshold, two 1D thresholds.
    c4: [f64; 4],
    s4: f64,
    t4: f64,
    a4: [f64; 2],
    integral4: f64,
    couplings: Vec<Coupling>,
}

const NAMES: [&str; 4] = ["pairs x", "pairs +", "4D", "cross"];

impl Integrands {
    fn new() -> Self {
        let mut r = Params(0x5eed_1234);
        let factors = (0..DIMS / 2).map(|_| Factor::new(&mut r)).collect();
        let c4 = std::array::from_fn(|_| r.range(0.25, 0.75));
        let s4 = 0.25;
        let t4 = 1.7;
        let a4 = [r.range(0.3, 0.7), r.range(0.3, 0.7)];
        let gauss4: f64 = c4.iter().map(|&c| gauss_1d(c, s4)).product();
        let integral4 = gauss4 + irwin_hall_4(t4) + (1.0 - a4[0]) * a4[1];
        // Dimensions of different domains: 0-1 pixel, 2-3 lens, 4-7, 8-11, 12-15 bounces.
        let couplings = vec![
            Coupling::Gauss(0, 4, 0.2),
            Coupling::SumBelow(1, 9, 0.8),
            Coupling::Below(2, 13),
            Coupling::Gauss(3, 10, 0.15),
            Coupling::SumBelow(5, 12, 1.1),
            Coupling::Gauss(6, 14, 0.25),
            Coupling::Below(7, 11),
            Coupling::SumBelow(8, 15, 0.9),
        ];
        Integrands {
            factors,
            c4,
            s4,
            t4,
            a4,
            integral4,
            couplings,
        }
    }

    fn eval(&self, d: &[f64; DIMS]) -> [f64; 4] {
        let mut product = 1.0;
        let mut sum = 0.0;
        for (k, f) in self.factors.iter().enumerate() {
            let v = f.eval(d[2 * k], d[2 * k + 1]);
            product *= v;
            sum += v;
        }
        let x = &d[4..8];
        let r2: f64 = x.iter().zip(self.c4).map(|(v, c)| (v - c).powi(2)).sum();
        let mut four = (-r2 / (2.0 * self.s4 * self.s4)).exp();
        if x.iter().sum::<f64>() < self.t4 {
            four += 1.0;
        }
        if x[1] > self.a4[0] && x[3] < self.a4[1] {
            four += 1.0;
        }
        let mut cross = 1.0;
        for c in &self.couplings {
            cross *= match *c {
                Coupling::Gauss(a, b, s) => {
                    (-(d[a] - d[b]).powi(2) / (2.0 * s * s)).exp() / gauss_of_difference(s)
                }
                Coupling::SumBelow(a, b, t) => {
                    let area = if t <= 1.0 {
                        t * t / 2.0
                    } else {
                        1.0 - (2.0 - t).powi(2) / 2.0
                    };
                    f64::from(u8::from(d[a] + d[b] < t)) / area
                }
                Coupling::Below(a, b) => f64::from(u8::from(d[a] < d[b])) * 2.0,
            };
        }
        [
            product,
            sum / self.factors.len() as f64,
            four / self.integral4,
            cross,
        ]
    }
}

/// Squared errors of one pixel per integrand and sample count.
fn pixel_errors(path: Path, f: &Integrands, p: u32) -> [[f64; 3]; 4] {
    let pixel = [p % 256, p / 256];
    let mut sums = [0.0; 4];
    let mut errors = [[0.0; 3]; 4];
    let mut next = 0;
    for i in 0..SPP[2] {
        let v = f.eval(&path(pixel, i as u32));
        for (s, v) in sums.iter_mut().zip(v) {
            *s += v;
        }
        if i + 1 == SPP[next] {
            for (e, s) in errors.iter_mut().zip(sums) {
                e[next] = (s / SPP[next] as f64 - 1.0).powi(2);
            }
            next += 1;
        }
    }
    errors
}

/// Mean squared error per integrand and sample count over `pixels` pixels: the pixels are
/// spread over the machine's threads, the errors summed in pixel order (the same table for
/// any thread count).
fn mse(path: Path, f: &Integrands, pixels: u32) -> [[f64; 3]; 4] {
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get()) as u32;
    let chunk = pixels.div_ceil(threads).max(1);
    let per_pixel: Vec<[[f64; 3]; 4]> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..pixels)
            .step_by(chunk as usize)
            .map(|lo| {
                let hi = (lo + chunk).min(pixels);
                scope.spawn(move || {
                    (lo..hi)
                        .map(|p| pixel_errors(path, f, p))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("worker thread"))
            .collect()
    });
    let mut total = [[0.0; 3]; 4];
    for e in &per_pixel {
        for (t, e) in total.iter_mut().zip(e) {
            for (t, e) in t.iter_mut().zip(e) {
                *t += e;
            }
        }
    }
    total.map(|t| t.map(|e| e / pixels as f64))
}

fn main() {
    let mut pixels = 16384u32;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--pixels" => pixels = args.next().and_then(|v| v.parse().ok()).unwrap_or(pixels),
            _ => {
                eprintln!("usage: sampler_quality [--pixels N]");
                std::process::exit(2);
            }
        }
    }
    openqmc::SobolSampler::warm_cache();
    openqmc::PmjSampler::warm_cache();
    let samplers: [(&str, Path); 6] = [
        ("warpcore Sampler<Pmj02bn>", warpcore_path::<Pmj02bn>),
        ("warpcore Sampler<Sobol>", warpcore_path::<Sobol>),
        (
            "openqmc-rs SobolSampler",
            openqmc_path::<openqmc::sobol::SobolImpl>,
        ),
        (
            "openqmc-rs PmjSampler",
            openqmc_path::<openqmc::pmj::PmjImpl>,
        ),
        ("sobol_burley::sample_4d", sobol_burley_path),
        ("random", random_path),
    ];
    let f = Integrands::new();
    let start = Instant::now();
    let results: Vec<[[f64; 3]; 4]> = samplers.iter().map(|&(_, p)| mse(p, &f, pixels)).collect();
    println!(
        "MSE over {pixels} pixels (independent randomisations), 16 dimensions from 5 domains, \
         integrals normalised to 1"
    );
    println!();
    println!(
        "| integrand | sampler | {} spp | {} spp | {} spp |",
        SPP[0], SPP[1], SPP[2]
    );
    println!("|---|---|---:|---:|---:|");
    for (k, name) in NAMES.iter().enumerate() {
        for ((sampler, _), r) in samplers.iter().zip(&results) {
            let e = r[k];
            println!(
                "| {name} | {sampler} | {:.3e} | {:.3e} | {:.3e} |",
                e[0], e[1], e[2]
            );
        }
        // The target: the better of ours at most 1.1x the better of openqmc-rs's.
        let ratio: [f64; 3] = std::array::from_fn(|j| {
            results[0][k][j].min(results[1][k][j]) / results[2][k][j].min(results[3][k][j])
        });
        println!(
            "| {name} | **best warpcore / best openqmc-rs** | {:.2} | {:.2} | {:.2} |",
            ratio[0], ratio[1], ratio[2]
        );
    }
    eprintln!("({:.1} s)", start.elapsed().as_secs_f64());
}
