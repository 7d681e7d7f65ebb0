//! Screen-space blue noise, measured: the RMS of the error image after a Gaussian blur.
//!
//! ```text
//! cargo run --release -p warpcore-report --bin bluenoise
//! ```
//!
//! The image is 64 x 64 pixels; pixel `(x, y)` integrates its own half-plane edge over the
//! pixel square `[0,1)^2` (the edge's angle and offset vary slowly across the image, see
//! [`edge`]) with the points `draw::<2>()` of domain 0 of `Sampler::new([x, y], frame, i,
//! 0)`, `i < spp`. The exact value of every pixel is the area of its half-plane in the square
//! (f64). The error image of a frame is blurred with a Gaussian of sigma 1.5 pixels (weights
//! renormalised at the image border), a stand-in for a denoiser or the eye; the figure is the
//! RMS of the blurred error over all pixels and [`FRAMES`] frames. White-noise error (every
//! pixel scrambled independently, as `Sampler<P>` does) keeps a flat spectrum that the blur
//! only scales down; blue-noise error (`Blue<P>`: neighbouring pixels' errors cancel) loses
//! most of its energy in the blur.
//!
//! Prints one table per base pattern (spp 1-16; `Sampler<P>`, `Sampler<Blue<P>>`, their
//! ratio, and OpenQMC's base and blue-noise samplers through `openqmc-rs` for reference) and
//! writes `target/bluenoise.png`: for each pattern (rows Sobol', pmj02bn) the 1-spp error
//! image of frame 0 under `P` and `Blue<P>`, then both after the blur (4x contrast).
//! `report/tests/blue_noise.rs` asserts the ratios with this code.

use crate::path::samplers::{OpenQmc, PathSampler};
use openqmc::{PmjBnSampler, PmjSampler, SobolBnSampler, SobolSampler};
use std::marker::PhantomData;
use std::path::Path;
use warpcore::sampler::{Blue, Pattern, Pmj02bn, Sampler, Sobol};

/// Image side in pixels.
pub const SIZE: usize = 64;
/// Standard deviation of the Gaussian blur, in pixels.
pub const SIGMA: f64 = 1.5;
/// Frames averaged (frame `f` of seed 0, `f < FRAMES`).
pub const FRAMES: u32 = 32;
/// Samples per pixel reported: every power of two up to 16 (one progressive run per frame).
pub const SPP: [u32; 5] = [1, 2, 4, 8, 16];

/// A sampler under test: the 2D point of sample `index` of pixel `(x, y)` in `frame`.
pub type Draw = fn(u32, u32, u32, u32) -> [f32; 2];

/// `Sampler<P>`: domain 0, seed 0.
pub fn ours<P: Pattern>(x: u32, y: u32, frame: u32, index: u32) -> [f32; 2] {
    Sampler::<P>::new([x, y], frame, index, 0)
        .domain(0)
        .draw::<2>()
}

/// An OpenQMC sampler (`openqmc-rs`) through the path tracer's interface: domain 0, the
/// frame as its seed.
pub fn openqmc<T>(x: u32, y: u32, frame: u32, index: u32) -> [f32; 2]
where
    OpenQmc<T>: PathSampler,
{
    let s = OpenQmc::<T>(PhantomData);
    s.draw2(&s.sample([x, y], index, 0, frame), 0)
}

/// The half-plane of pixel `(x, y)`: `{u in [0,1)^2 : (u - 1/2) . n < c}` as `[n_x, n_y,
/// c]`, with the normal's angle turning by about 0.07 radians per pixel along x (0.03 along
/// y) and the offset `|c| <= 0.3` (so every pixel's edge crosses its square) drifting more
/// slowly still.
pub fn edge(x: usize, y: usize) -> [f64; 3] {
    let tau = std::f64::consts::TAU;
    let (x, y) = (x as f64, y as f64);
    let angle = tau * (x + 0.5 * y) / 96.0 + 0.3;
    let c = 0.3 * (tau * (y - 0.5 * x) / 80.0 + 0.5).sin();
    [angle.cos(), angle.sin(), c]
}

/// Is `p` inside the half-plane `e`?
pub fn inside(e: &[f64; 3], p: [f32; 2]) -> bool {
    (p[0] as f64 - 0.5) * e[0] + (p[1] as f64 - 0.5) * e[1] < e[2]
}

/// The area of the half-plane `e` inside the unit square.
pub fn area(e: &[f64; 3]) -> f64 {
    pmjgen::tool::square_area_below(|p| (p[0] - 0.5) * e[0] + (p[1] - 0.5) * e[1] - e[2])
}

/// The error images of one frame, one per entry of [`SPP`] (row-major, `SIZE * SIZE`).
pub fn error_images(draw: Draw, frame: u32) -> Vec<Vec<f64>> {
    let mut out = vec![vec![0.0; SIZE * SIZE]; SPP.len()];
    for y in 0..SIZE {
        for x in 0..SIZE {
            let e = edge(x, y);
            let exact = area(&e);
            let mut hits = 0u32;
            let mut level = 0;
            for i in 0..SPP[SPP.len() - 1] {
                hits += inside(&e, draw(x as u32, y as u32, frame, i)) as u32;
                if i + 1 == SPP[level] {
                    out[level][y * SIZE + x] = hits as f64 / SPP[level] as f64 - exact;
                    level += 1;
                }
            }
        }
    }
    out
}

/// The image blurred by a Gaussian of sigma [`SIGMA`] (separable, truncated at 4 sigma,
/// weights renormalised where the kernel leaves the image).
pub fn blur(img: &[f64]) -> Vec<f64> {
    blur_sigma(img, SIGMA)
}

/// [`blur`] with another standard deviation (pixels).
pub fn blur_sigma(img: &[f64], sigma: f64) -> Vec<f64> {
    let r = (4.0 * sigma).ceil() as isize;
    let w: Vec<f64> = (-r..=r)
        .map(|d| (-((d * d) as f64) / (2.0 * sigma * sigma)).exp())
        .collect();
    let pass = |src: &[f64], horizontal: bool| {
        let mut dst = vec![0.0; SIZE * SIZE];
        for y in 0..SIZE {
            for x in 0..SIZE {
                let (mut sum, mut norm) = (0.0, 0.0);
                for d in -r..=r {
                    let (qx, qy) = if horizontal {
                        (x as isize + d, y as isize)
                    } else {
                        (x as isize, y as isize + d)
                    };
                    if (0..SIZE as isize).contains(&qx) && (0..SIZE as isize).contains(&qy) {
                        let k = w[(d + r) as usize];
                        sum += k * src[qy as usize * SIZE + qx as usize];
                        norm += k;
                    }
                }
                dst[y * SIZE + x] = sum / norm;
            }
        }
        dst
    };
    pass(&pass(img, true), false)
}

/// RMS of the blurred error over all pixels of frames `frames`, one figure per entry of
/// [`SPP`].
pub fn rms_after_blur(draw: Draw, frames: std::ops::Range<u32>) -> Vec<f64> {
    let mut sum = vec![0.0; SPP.len()];
    let count = frames.len() * SIZE * SIZE;
    for frame in frames {
        for (level, img) in error_images(draw, frame).iter().enumerate() {
            sum[level] += blur(img).iter().map(|e| e * e).sum::<f64>();
        }
    }
    sum.iter().map(|s| (s / count as f64).sqrt()).collect()
}

/// One pattern's row set of the table: `(name, P, Blue<P>, OpenQMC base, OpenQMC BN)`.
pub fn patterns() -> [(&'static str, Draw, Draw, Draw, Draw); 2] {
    [
        (
            "Sobol",
            ours::<Sobol>,
            ours::<Blue<Sobol>>,
            openqmc::<SobolSampler>,
            openqmc::<SobolBnSampler>,
        ),
        (
            "Pmj02bn",
            ours::<Pmj02bn>,
            ours::<Blue<Pmj02bn>>,
            openqmc::<PmjSampler>,
            openqmc::<PmjBnSampler>,
        ),
    ]
}

/// Rows Sobol' and pmj02bn; columns: `P` and `Blue<P>` error at 1 spp (frame 0), then both
/// blurred (4x contrast). Grey 128 is zero error.
pub fn picture(path: &Path) -> std::io::Result<()> {
    const SCALE: usize = 3;
    const GAP: usize = 6;
    let cell = SIZE * SCALE;
    let (w, h) = (4 * cell + 5 * GAP, 2 * cell + 3 * GAP);
    let mut px = vec![255u8; w * h];
    for (row, (_, base, blue, _, _)) in patterns().into_iter().enumerate() {
        let [e_base, e_blue] = [base, blue].map(|d| error_images(d, 0).swap_remove(0));
        let images = [
            (e_base.clone(), 1.0),
            (e_blue.clone(), 1.0),
            (blur(&e_base), 4.0),
            (blur(&e_blue), 4.0),
        ];
        for (col, (img, contrast)) in images.iter().enumerate() {
            let (ox, oy) = (GAP + col * (cell + GAP), GAP + row * (cell + GAP));
            for y in 0..cell {
                for x in 0..cell {
                    let e = img[(y / SCALE) * SIZE + x / SCALE] * contrast;
                    px[(oy + y) * w + ox + x] = (128.0 + 127.0 * e.clamp(-1.0, 1.0)).round() as u8;
                }
            }
        }
    }
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir)?;
    }
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w as u32, h as u32);
    enc.set_color(png::ColorType::Grayscale);
    enc.set_depth(png::BitDepth::Eight);
    let mut writer = enc.write_header().map_err(std::io::Error::other)?;
    writer
        .write_image_data(&px)
        .map_err(std::io::Error::other)?;
    writer.finish().map_err(std::io::Error::other)
}

/// Frames of 1 sample per pixel, accumulated: a frame's 2D point for pixel `(x,
/// y)` at frame `t` (sample index 0 of the frame).
pub type FrameDraw = fn(u32, u32, u32) -> [f32; 2];

/// `Sampler<P>` with the frames continuing one sequence (`new_frame(pixel, t, 1, 0, 0)`).
pub fn continued<P: Pattern>(x: u32, y: u32, t: u32) -> [f32; 2] {
    Sampler::<P>::new_frame([x, y], t, 1, 0, 0)
        .domain(0)
        .draw::<2>()
}

/// `Sampler<P>` with a fresh randomisation per frame (`new(pixel, t, 0, 0)`).
pub fn fresh<P: Pattern>(x: u32, y: u32, t: u32) -> [f32; 2] {
    ours::<P>(x, y, t, 0)
}

/// White noise: a counter hash per pixel and frame (`rnd` of `Sampler<Sobol>`).
pub fn white(x: u32, y: u32, t: u32) -> [f32; 2] {
    Sampler::<Sobol>::new([x, y], t, 0, 0).domain(0).rnd::<2>()
}

/// An OpenQMC blue-noise sampler as its docs use it for progressive rendering: the sample
/// index counts on across frames (seed 0).
pub fn openqmc_continued<T>(x: u32, y: u32, t: u32) -> [f32; 2]
where
    OpenQmc<T>: PathSampler,
{
    openqmc::<T>(x, y, 0, t)
}

/// What accumulating `frames` frames of 1 spp leaves, for one sampler: `[mean per-frame RMS
/// after the sigma-1.5 blur, the worst frame's, running mean's RMS after the blur, running
/// mean's unblurred per-pixel RMS, EMA (alpha 0.1) RMS after a sigma-1 blur]`.
pub fn frame_errors(draw: FrameDraw, frames: u32) -> [f64; 5] {
    let n = SIZE * SIZE;
    let exact: Vec<f64> = (0..n).map(|k| area(&edge(k % SIZE, k / SIZE))).collect();
    let (mut sum, mut ema) = (vec![0.0; n], vec![0.0; n]);
    let (mut per_frame, mut worst) = (0.0, 0.0f64);
    let rms = |img: &[f64]| (img.iter().map(|e| e * e).sum::<f64>() / n as f64).sqrt();
    for t in 0..frames {
        let err: Vec<f64> = (0..n)
            .map(|k| {
                let (x, y) = (k % SIZE, k / SIZE);
                let hit = inside(&edge(x, y), draw(x as u32, y as u32, t)) as u32 as f64;
                hit - exact[k]
            })
            .collect();
        let r = rms(&blur(&err));
        per_frame += r / frames as f64;
        worst = worst.max(r);
        for k in 0..n {
            sum[k] += err[k];
            ema[k] = if t == 0 {
                err[k]
            } else {
                0.9 * ema[k] + 0.1 * err[k]
            };
        }
    }
    let mean: Vec<f64> = sum.iter().map(|e| e / frames as f64).collect();
    [
        per_frame,
        worst,
        rms(&blur(&mean)),
        rms(&mean),
        rms(&blur_sigma(&ema, 1.0)),
    ]
}

/// A Morton-ordered Sobol' sampler in the manner of pbrt-v4's `ZSobolSampler` (Ahmed and Wonka,
/// "Screen-space blue-noise diffusion of Monte Carlo sampling error via hierarchical ordering
/// of pixels", SIGGRAPH Asia 2020), our own code: sample `index` of `2^log2_spp` of pixel
/// `(x, y)` is the global index `morton(x, y) * 2^log2_spp + index` (coordinates modulo
/// `2^10`), whose base-4 digits are each permuted, from the most significant down, by one of
/// the 24 permutations of `0..4` chosen by a hash of the digits above and of `dim` (with an
/// odd `log2_spp` the lowest digit is binary and is flipped by one hash bit); the point is
/// dimensions 0-1 of Sobol' (the report's Joe-Kuo directions, [`crate::path::qmc::sobol`],
/// all 2^32 indices) at that index, Owen-scrambled by the Laine-Karras hash keyed by `dim`.
/// So each pixel's samples are an aligned block of one sequence (a net), and the pixels of
/// every aligned Morton quad take 4 blocks that together form a net: neighbouring pixels'
/// errors cancel. Needs the sample count in advance (not progressive). A report peer, not a
/// `Pattern`: its points depend on `spp`, which `Sampler::new` does not take.
pub fn zsobol(x: u32, y: u32, log2_spp: u32, index: u32, dim: u32) -> [f32; 2] {
    const LOG2_RES: u32 = 10;
    const PERMS: [[u32; 4]; 24] = {
        let mut out = [[0u32; 4]; 24];
        let (mut n, mut a) = (0, 0);
        while a < 4 {
            let mut b = 0;
            while b < 4 {
                let mut c = 0;
                while c < 4 {
                    if a != b && b != c && a != c {
                        out[n] = [a, b, c, 6 - a - b - c];
                        n += 1;
                    }
                    c += 1;
                }
                b += 1;
            }
            a += 1;
        }
        out
    };
    let spread = |v: u32| (0..LOG2_RES).fold(0u64, |m, b| m | ((((v >> b) & 1) as u64) << (2 * b)));
    let morton = spread(x & ((1 << LOG2_RES) - 1)) | (spread(y & ((1 << LOG2_RES) - 1)) << 1);
    let g = (morton << log2_spp) | u64::from(index & ((1u32 << log2_spp) - 1));
    let bits = 2 * LOG2_RES + log2_spp;
    let key = crate::path::samplers::hash32(dim ^ 0x5a17_0b01);
    let mut out = 0u64;
    let mut done = 0;
    while done < bits {
        let width = if bits - done >= 2 { 2 } else { 1 };
        let shift = bits - done - width;
        let above = g >> (shift + width);
        let h = crate::path::samplers::hash32(
            (above as u32) ^ crate::path::samplers::hash32((above >> 32) as u32 ^ key ^ done),
        );
        let digit = ((g >> shift) & ((1 << width) - 1)) as u32;
        let permuted = if width == 2 {
            PERMS[(h % 24) as usize][digit as usize]
        } else {
            digit ^ (h & 1)
        };
        out |= u64::from(permuted) << shift;
        done += width;
    }
    // Sobol' over all 2^32 indices (`sobol_burley` takes indices below 2^16 only, and the
    // permuted index here has 2 x 10 + log2_spp bits).
    let i = out as u32;
    let owen = |d: usize| {
        let x = crate::path::qmc::lk_scramble(
            crate::path::qmc::sobol(i, d),
            key ^ (d as u32 + 1).wrapping_mul(0x9e37_79b9),
        );
        (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
    };
    [owen(0), owen(1)]
}

/// RMS of the blurred error of [`zsobol`] at `spp` samples per pixel over `frames` frames
/// (frame `t` is `dim = t`: an independent randomisation per frame).
pub fn zsobol_rms_after_blur(spp: u32, frames: u32) -> f64 {
    let k = spp.trailing_zeros();
    let mut sum = 0.0;
    for t in 0..frames {
        let err: Vec<f64> = (0..SIZE * SIZE)
            .map(|p| {
                let (x, y) = (p % SIZE, p / SIZE);
                let e = edge(x, y);
                let hits = (0..spp)
                    .filter(|&i| inside(&e, zsobol(x as u32, y as u32, k, i, t)))
                    .count();
                hits as f64 / f64::from(spp) - area(&e)
            })
            .collect();
        sum += blur(&err).iter().map(|e| e * e).sum::<f64>();
    }
    (sum / (frames as usize * SIZE * SIZE) as f64).sqrt()
}

/// [`zsobol`] as 1 spp frames: frame `t < 32` is sample `t` of a 32-sample ZSobol' pixel (the
/// frames continue it, as `new_frame` does), for [`frame_errors`].
pub fn zsobol_frames(x: u32, y: u32, t: u32) -> [f32; 2] {
    zsobol(x, y, 5, t % 32, t / 32)
}
