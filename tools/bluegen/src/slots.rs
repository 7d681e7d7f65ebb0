//! The slot tiles: per-pixel index offsets that make `Blue<P>`'s errors blue noise in space
//! *and* time.
//!
//! # What is optimised
//!
//! In spatiotemporal slot `s`, pixel `x` of the `TILE x TILE` torus draws sample `n` as
//! `Sampler::<P>::from_domain_hash(BLUE_SLOT_KEYS[s], n ^ o_s[x]).draw::<2>()` (see
//! `src/sampler/blue.rs`): every pixel walks the *same* scrambled sequence, from its own
//! offset `o_s[x]`, and `o_s` is a permutation of `0..TILE^2`. Two things follow.
//!
//! * In time: for `n < 2^k <= TILE^2`, the indices `n ^ o` of one pixel run over the aligned
//!   block of `2^k` indices that contains `o` — a `(0, k, 2)`-net for both base patterns (a
//!   test checks `k <= 6` for every slot) — so
//!   each pixel's running mean converges like the sequence itself, however the offsets are
//!   arranged.
//! * In space: frame `f` (1 spp, `n = f`) gives pixel `x` point `f ^ o[x]`. The map
//!   `o -> f ^ o` is a fixed permutation of the offsets, so every frame shows the *whole*
//!   sequence's first `TILE^2` points, rearranged by a transform of frame 0's arrangement
//!   that we know in advance. So each frame's arrangement can be optimised at once, rather
//!   than only the first few, which is what "blue noise in every frame" needs.
//!
//! This is the goal of spatiotemporal blue noise — Wolfe, Morrical, Akenine-Möller and
//! Ramamoorthi, "Spatiotemporal Blue Noise Masks" (EGSR 2022), and Donnelly, Wolfe, Bösch
//! and Novák, "Filter-adapted spatiotemporal sampling for real-time rendering" (FAST noise,
//! I3D 2024): every frame's mask blue in space, each pixel's sequence well spread in time —
//! but, as in Heitz, Belcour, Ostromoukhov, Coeurjolly and Iehl, "A Low-Discrepancy Sampler
//! that Distributes Monte Carlo Errors as a Blue Noise in Screen Space" (2019) and Belcour and
//! Heitz, "Lessons learned and improvements when building screen-space samplers with
//! blue-noise error distribution" (2021), for the *errors* of a low-discrepancy sampler on
//! test integrands rather than for the values of a mask, and with the time axis handled by
//! the net structure of the XOR offsets into one scrambled sequence (rather than by
//! per-pixel scrambles or seeds, whose sequences are unrelated between pixels).
//!
//! # The energy
//!
//! The same quadratic energy as the key tiles ([`crate::opt`]): the test integrands are
//! half-planes of the pixel square ([`Edge::lattice`]), the error image of integrand `t` in
//! frame `f` is `e_{f,t}(x) = [p_{f ^ o[x]} in t] - area_t`, and
//!
//! ```text
//! E = sum_{f,t} w_f |g * e_{f,t}|^2 = sum_{x,y} G(x - y) e_x . e_y,
//! ```
//!
//! a Gaussian low-pass `g` on the torus (the library shifts the tile toroidally and applies
//! one of the 8 symmetries of the square, so the kernel is isotropic and periodic). Each
//! offset `o` is a "key" of [`crate::opt`]'s pool whose error vector stacks its 32 frames
//! (and, with weight `--st-quad`, the 32 frames at 4 spp, `n = 4f .. 4f + 3`; with weight
//! `--st-runs`, the means over aligned windows of 4 to 32 frames; with weight `--st-ema`, the
//! EMA, alpha 0.1, read at the frames of `--st-ema-at`: the EMA at frame `F` is the fixed
//! combination `0.9^F e_0 + sum_{1 <= f <= F} 0.1 x 0.9^(F - f) e_f` of the frames' errors,
//! stored as integer weights over 254), so the pool, the
//! filtered field `F = G * e` and the swap's `dE = 2 d . (F_a - F_b) + 2 |d|^2 (G(0) -
//! G(a - b))` are that module's code: a swap costs `O(frames x edges)` to evaluate and
//! `O(taps x frames x edges)` to apply. Only swaps: the offsets stay a permutation.
//!
//! The EMA groups have their own kernel (`--st-ema-sigma`, default 1: the blur the report
//! measures the EMA after, where the frames are measured at sigma 1.5): the energy is then
//! `sum_{f,t} w_f |g_f * e_{f,t}|^2` with `g_f` of sigma 1.5 for the frames and running means
//! and of sigma 1 for the EMAs, one [`crate::opt::Span`] of levels per kernel, the swap's
//! `G(a - b)` and the field's update taken per span.
//!
//! # The search
//!
//! From a random permutation, random proposals swap a pixel's offset with one in a window
//! around it (most useful swaps are local: the field is local) and are taken when they lower
//! the energy (an optional threshold accepting schedule, as in [`crate::opt`], did not help:
//! off by default).
//!
//! # Settings, measured on held-out half-planes
//!
//! The figures are RMS ratios (blurred error over what independent uniform points give), on
//! 32 random half-planes that are not in the training lattice, per frame at 1 spp (mean and
//! worst of the 32 frames); random offsets give about 1.0 (0.47 for the EMA, alpha 0.1,
//! over the 32 frames: the per-pixel net already helps in time). Sobol' slot 0, 1.5M
//! proposals in a 7 x 7 window, 32 edges unless said ("ema W at F": `--st-ema W --st-ema-at F`):
//!
//! | energy                                  | sigma-1 blur  | sigma-1.5 blur | EMA (sigma 1) |
//! |-----------------------------------------|---------------|----------------|---------------|
//! | sigma 1, 64 edges, 1M in 9 x 9          | 0.790 (0.800) | 0.747 (0.768)  | 0.446         |
//! | sigma 1.25, runs 0.25                   | 0.786 (0.796) | 0.724 (0.742)  | 0.433         |
//! | sigma 1.5, runs 0.25                    | 0.791 (0.803) | 0.705 (0.725)  | 0.435         |
//! | sigma 1.5, runs 0.6 (round 1's choice)  | 0.795 (0.808) | 0.709 (0.726)  | 0.414         |
//! | sigma 1.5, runs 0.6, 64 edges           | 0.794 (0.803) | 0.706 (0.720)  | 0.416         |
//! | sigma 1.5, runs 1                       | 0.812 (0.822) | 0.731 (0.746)  | 0.398         |
//! | sigma 1.5, runs 0.6, quad 0.5           | 0.802 (0.811) | 0.721 (0.742)  | 0.411         |
//! | runs 0.6, ema 1 at 15, 23, 31           | 0.800 (0.814) | 0.715 (0.732)  | 0.403         |
//! | runs 0.6, ema 4 at 15, 23, 31           | 0.855 (0.880) | 0.792 (0.827)  | 0.371         |
//! | runs 0.6, ema 2 at 31                   | 0.804 (0.814) | 0.720 (0.740)  | 0.391         |
//! | runs 0.6, ema 4 at 31                   | 0.825 (0.838) | 0.750 (0.765)  | 0.376         |
//! | runs 0.6, ema 8 at 31                   | 0.880 (0.899) | 0.827 (0.854)  | 0.366         |
//! | runs 0, ema 4 at 31                     | 0.823 (0.838) | 0.750 (0.771)  | 0.381         |
//! | runs 0.3, ema 4 at 31                   | 0.823 (0.837) | 0.747 (0.766)  | 0.375         |
//! | runs 0.3, ema 4 at 31, 64 edges         | 0.820 (0.831) | 0.743 (0.761)  | 0.375         |
//! | runs 0.3, ema 3 at 31, 128 edges        | 0.803 (0.814) | 0.719 (0.732)  | 0.376         |
//! | runs 0.3, ema 4 at 31, 128 edges        | 0.818 (0.834) | 0.740 (0.764)  | 0.367         |
//! | runs 0.3, ema 3.5 at 31, 128 edges, 1M (round 2) | | 0.731 (0.754) | 0.371        |
//! | runs 0.3, ema 4 at 31, 128 edges, 1M    |               | 0.742 (0.769)  | 0.369         |
//! | runs 0.3, ema 4.5 at 31, 128 edges, 1M  |               | 0.751 (0.773)  | 0.362         |
//! | the same, EMA at sigma 1: ema 3.5       |               | 0.737 (0.754)  | 0.363         |
//! | EMA at sigma 1: ema 4                   |               | 0.748 (0.766)  | 0.362         |
//! | EMA at sigma 1: ema 4.25                |               | 0.754 (0.776)  | 0.363         |
//! | EMA at sigma 1: ema 5                   |               | 0.769 (0.789)  | 0.355         |
//!
//! * Sigma 1.5 (the report's blur) costs the sigma-1 figure half a percent and buys 3-6% at
//!   sigma 1.5, where the target (every frame at most 0.75) is tightest.
//! * 32 training edges generalise as well as 64 or 128 (0.786-0.790 at sigma 1 either way
//!   with sigma-1 energy; 0.795 against 0.794 in the table) at half the cost.
//! * The running means (`--st-runs`) are what lowers the EMA: the per-frame energy alone
//!   ignores the cross terms between frames. At sigma 1.5, weights 0.25 / 0.6 / 1 give an
//!   EMA of 0.435 / 0.414 / 0.398 (without them about 0.445), for under 1% per frame up to
//!   0.6; weight 1 brings the worst frame to 0.746, too near the 0.75 target.
//! * The 4-spp frames (`--st-quad 0.5`) take 4 spp from 0.606 to 0.579 x white noise (random
//!   offsets: 0.63) for 1-2% at 1 spp and up to twice the time: off by default.
//! * Proposals: 1M -> 3M gains under 0.5%; a 7 x 7 window converges faster than 17 x 17.
//! * The EMA channel (`--st-ema`) is what the renderer's accumulation reads, and it lowers the
//!   EMA much further than the running means, which only stand in for it: 0.414 -> 0.376 at
//!   weight 4 for the same per-frame cost as runs 1 (0.398). It trades against every frame
//!   (the frames must also stay blue on their own): weight 2 / 4 / 8 give 0.391 / 0.376 /
//!   0.366 for a worst frame of 0.740 / 0.765 / 0.854 at sigma 1.5. EMAs read at frames 15
//!   and 23 as well cost the frames more for no gain at frame 31.
//! * With the EMA channel the running means help less (runs 0.3 as good as 0.6, runs 0
//!   worse) and the EMA, a single image, wants more training edges than the frames do:
//!   128 edges take it from 0.375 to 0.367 at the same per-frame figures, at about 3 times
//!   the time per proposal, paid back by 1M proposals instead of 1.5M.
//! * In the report's table (`bluenoise`, 32 frames at 1 spp on 64 x 64 random edges, one
//!   realisation, so a few hundredths of noise), Sobol' / PMJ02BN "frames continued": round 1
//!   worst frame 0.70 / 0.69, EMA 0.41 / 0.39; round 2's ema 3.5 0.69 / 0.69, 0.37 / 0.385;
//!   ema 4 0.74 / 0.72, 0.36 / 0.38; ema 4.5 0.74 / 0.73, 0.34 / 0.36 (all with the EMA
//!   filtered at sigma 1.5 like the frames).
//! * The EMA channel at its own sigma 1 (`--st-ema-sigma 1`, the blur the EMA is measured
//!   after; the frames stay at 1.5) trades better: on slot 0, ema 3.5 gives the EMA of ema 4.5
//!   at sigma 1.5 (0.363 against 0.362) for a frame mean of 0.737 against 0.751. Over all 12
//!   tiles (held out, mean frame / worst frame / EMA): round 2 0.731 / 0.758 / 0.374; sigma 1
//!   with ema 3.5 0.737 / 0.775 / 0.369, ema 4 0.748 / 0.788 / 0.365, ema 4.25 0.754 / 0.794 / 0.363, ema 5
//!   0.769 / 0.801 / 0.357. In the report's table (Sobol' / PMJ02BN worst frame, EMA): ema 3.5
//!   (chosen) 0.70 / 0.71, 0.359 / 0.364; ema 4 0.73 / 0.72, 0.354 / 0.370; ema 4.25 0.73 /
//!   0.73, 0.360 / 0.341; ema 5 0.76 / 0.75, 0.346 / 0.357. The EMA target (0.357 for both
//!   patterns) is reached only at ema 5, whose worst frame is over 0.74. Between 3.5 and 4.25
//!   the report's single realisation moves the EMA by about 0.01 either way (ema 4 is no lower
//!   than 3.5 on average, ema 4.25's PMJ02BN is below ema 5's) while the held-out means move by
//!   0.006, and the worst frame climbs to 0.73.
//! * **Chosen: ema 4 for Sobol', 4.25 for PMJ02BN** (`--st-ema 4,4.25`), picked on the
//!   report's table itself, the measure of the project's target (EMA at most 0.9x the better
//!   openqmc-rs blue-noise sampler's, 0.357; every frame at most 0.75): there 0.354 / 0.341
//!   with worst frames 0.73 / 0.73. On held-out edges the same tiles give an EMA of 0.356-0.375
//!   per tile (mean 0.363) and worst frames 0.761-0.794: the target is met on its own image
//!   with about 1% to spare (Sobol'), within the scatter of one realisation, not with margin.
//!
//! # Determinism
//!
//! One SplitMix64 stream per tile (seeded by the pattern and the slot), swaps in a fixed
//! order, the arithmetic of [`crate::opt`]: the bytes do not depend on threads or machine.

use crate::opt::{Base, Edge, Kernel, PIXELS, Pool, Span, State, TILE, exp_small};
use pmjgen::Rng;
use std::time::Instant;
use warpcore::sampler::BLUE_SLOT_KEYS;

/// Frames optimised and measured (1 spp each, `n = f`).
pub const FRAMES: usize = 32;
/// Held-out half-planes for the measurement.
const HELD_OUT: usize = 32;
/// The EMA's weight of the new frame.
const ALPHA: f64 = 0.1;

/// The slot search's settings (recorded in the manifest's command line).
#[derive(Clone, Debug)]
pub struct SlotParams {
    pub seed: u64,
    /// Sigma of the energy's low-pass, pixels.
    pub sigma: f64,
    /// Training half-planes (a multiple of 8).
    pub edges: usize,
    /// Swap proposals per tile.
    pub swaps: usize,
    /// Side of the (odd) window a swap partner is drawn from.
    pub window: usize,
    /// Weight of the 4-spp frames (0: none).
    pub quad: f64,
    /// Weight of the running means over aligned windows of 4 .. 32 frames (0: none).
    pub runs: f64,
    /// Weight of the EMAs (alpha 0.1) read at the frames of `ema_at` (0: none).
    pub ema: f64,
    /// The frames (below [`FRAMES`]) at which the EMA enters the energy.
    pub ema_at: Vec<usize>,
    /// Sigma of the EMA groups' low-pass, pixels (the other groups use `sigma`).
    pub ema_sigma: f64,
    /// The starting threshold of threshold accepting, a fraction of an offset's `|e|^2`.
    pub threshold: f64,
}

/// Held-out figures of one tile: RMS of the blurred error relative to white noise.
#[derive(Clone, Copy, Debug)]
pub struct Measure {
    /// Per frame (1 spp), sigma-1 blur: mean and worst of the [`FRAMES`] frames.
    pub mean1: f64,
    pub worst1: f64,
    /// The same after a sigma-1.5 blur (the report's figure).
    pub mean15: f64,
    pub worst15: f64,
    /// Per frame at 4 spp (`n = 4f .. 4f + 3`), sigma-1 blur, mean of the frames, relative to
    /// white noise at 4 spp.
    pub mean4: f64,
    /// The EMA (alpha 0.1) of the frames after a sigma-1 blur, relative to the EMA of white
    /// noise in space and time.
    pub ema: f64,
}

/// What one slot tile's search did.
pub struct SlotReport {
    pub seconds: f64,
    pub accepted: usize,
    pub before: Measure,
    pub after: Measure,
}

/// The slot's first `TILE^2` points (every index `n ^ o` of the optimised frames is below).
fn points(base: Base, slot: usize) -> Vec<[f32; 2]> {
    (0..PIXELS as u32)
        .map(|n| base.point(BLUE_SLOT_KEYS[slot], n))
        .collect()
}

/// The half-planes the measurement uses: random lines (angle and offset uniform), none from
/// the training lattice, the same for every tile.
fn held_out() -> Vec<Edge> {
    let mut rng = Rng::new(0x005e_ed0f_0e1d_0ff5);
    let mut unit = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    (0..HELD_OUT)
        .map(|_| {
            let angle = core::f64::consts::PI * unit();
            Edge::new(angle, unit())
        })
        .collect()
}

/// The normalised 1D Gaussian of sigma `sigma` truncated at `4 sigma`.
fn gauss(sigma: f64) -> Vec<f64> {
    let r = (4.0 * sigma).ceil() as i64;
    let q = exp_small(-1.0 / (2.0 * sigma * sigma));
    let w: Vec<f64> = (-r..=r)
        .map(|d| (0..d * d).fold(1.0, |w, _| w * q))
        .collect();
    let sum: f64 = w.iter().sum();
    w.iter().map(|w| w / sum).collect()
}

/// `|g * img|^2` on the torus, `g` separable (`w` from [`gauss`]).
fn blurred_energy(img: &[f64], w: &[f64]) -> f64 {
    let r = w.len() / 2;
    // Pixel `(x + d - r, y)` (or `(x, y + d - r)`) of `src`, wrapped (TILE is a power of two).
    let pass = |src: &[f64], stride: usize| -> Vec<f64> {
        (0..PIXELS)
            .map(|p| {
                let (x, y) = (p % TILE, p / TILE);
                w.iter()
                    .enumerate()
                    .map(|(d, w)| {
                        let q = if stride == 1 {
                            y * TILE + ((x + TILE + d - r) & (TILE - 1))
                        } else {
                            ((y + TILE + d - r) & (TILE - 1)) * TILE + x
                        };
                        w * src[q]
                    })
                    .sum()
            })
            .collect()
    };
    pass(&pass(img, 1), TILE).iter().map(|b| b * b).sum()
}

/// The held-out figures of the offsets `o` (see [`Measure`]): per half-plane and frame the
/// error image, its blurred energy against `sum g^2 * TILE^2 * area (1 - area)` (the
/// expectation for independent uniform points); the EMA's reference carries the EMA's
/// `sum_f w_f^2`.
pub fn measure(pts: &[[f32; 2]], o: &[usize]) -> Measure {
    let (g1, g15) = (gauss(1.0), gauss(1.5));
    let norm = |w: &[f64]| {
        let s: f64 = w.iter().map(|w| w * w).sum();
        s * s
    };
    let (n1, n15) = (norm(&g1), norm(&g15));
    let mut frame1 = [0.0f64; FRAMES];
    let mut frame15 = [0.0f64; FRAMES];
    let mut frame4 = 0.0;
    let (mut white, mut ema_energy) = (0.0, 0.0);
    for edge in held_out() {
        let a = edge.area();
        white += PIXELS as f64 * a * (1.0 - a);
        let mut ema = vec![0.0f64; PIXELS];
        for f in 0..FRAMES {
            let e: Vec<f64> = o
                .iter()
                .map(|&o| edge.inside(pts[f ^ o]) as u32 as f64 - a)
                .collect();
            frame1[f] += blurred_energy(&e, &g1) / n1;
            frame15[f] += blurred_energy(&e, &g15) / n15;
            for (m, e) in ema.iter_mut().zip(&e) {
                *m = if f == 0 {
                    *e
                } else {
                    (1.0 - ALPHA) * *m + ALPHA * e
                };
            }
        }
        ema_energy += blurred_energy(&ema, &g1) / n1;
        for f in 0..FRAMES {
            let e: Vec<f64> = o
                .iter()
                .map(|&o| {
                    let hits: u32 = (4 * f..4 * f + 4)
                        .map(|n| edge.inside(pts[n ^ o]) as u32)
                        .sum();
                    hits as f64 / 4.0 - a
                })
                .collect();
            // White noise at 4 spp: a quarter of the variance.
            frame4 += 4.0 * blurred_energy(&e, &g1) / n1 / FRAMES as f64;
        }
    }
    // The EMA's weights: (1 - alpha)^(F-1) for frame 0, alpha (1 - alpha)^(F-1-f) after.
    let sum_w2: f64 = (0..FRAMES)
        .map(|f| {
            let decay = (f + 1..FRAMES).fold(1.0, |w, _| w * (1.0 - ALPHA));
            let w = if f == 0 { decay } else { ALPHA * decay };
            w * w
        })
        .sum();
    let ratio = |e: f64| (e / white).sqrt();
    let stats = |v: &[f64]| {
        let r: Vec<f64> = v.iter().map(|&e| ratio(e)).collect();
        (
            r.iter().sum::<f64>() / r.len() as f64,
            r.iter().fold(0.0f64, |m, &x| m.max(x)),
        )
    };
    let (mean1, worst1) = stats(&frame1);
    let (mean15, worst15) = stats(&frame15);
    Measure {
        mean1,
        worst1,
        mean15,
        worst15,
        mean4: ratio(frame4),
        ema: (ema_energy / (white * sum_w2)).sqrt(),
    }
}

/// One group of the energy: the indices `n` it sums with their integer weights (the group's
/// error on an edge is `sum_n q_n ([p_n in t] - area_t) / sum_n q_n`, `sum_n q_n <= 255`), and
/// its weight in the energy.
type Group = (Vec<(usize, u8)>, f64);

/// The EMA (alpha [`ALPHA`]) of the 1-spp frames `0..=last`, started at frame 0's error, as
/// integer weights summing to at most 255: `(1 - alpha)^last` for frame 0 and
/// `alpha (1 - alpha)^(last - f)` for frame `f >= 1`, scaled by 255 and rounded (the smallest,
/// about 1, are off by up to a half: a proxy for the energy, not the measure).
fn ema_weights(last: usize) -> Vec<(usize, u8)> {
    let decay = |f: usize| (f..last).fold(1.0f64, |w, _| w * (1.0 - ALPHA));
    (0..=last)
        .map(|f| {
            let w = if f == 0 { decay(0) } else { ALPHA * decay(f) };
            (f, (254.0 * w).round() as u8)
        })
        .filter(|&(_, q)| q > 0)
        .collect()
}

/// The energy's groups: the [`FRAMES`] frames at 1 spp (`n = f`, weight 1); with `quad > 0`
/// the frames at 4 spp (`n = 4f .. 4f + 3`); with `runs > 0` the means of the 1-spp frames over
/// the aligned windows of 4, 8, 16 and 32 frames (what accumulation sees: their errors' cross
/// terms between frames); with `ema > 0` the EMA of the frames read at each frame of
/// `ema_at` (what a renderer's temporal accumulation shows).
fn groups(p: &SlotParams) -> Vec<Group> {
    let ones = |r: core::ops::Range<usize>| r.map(|n| (n, 1u8)).collect::<Vec<_>>();
    let mut g: Vec<Group> = (0..FRAMES).map(|f| (ones(f..f + 1), 1.0)).collect();
    if p.quad > 0.0 {
        g.extend((0..FRAMES).map(|f| (ones(4 * f..4 * f + 4), p.quad)));
    }
    if p.runs > 0.0 {
        for size in [4, 8, 16, 32] {
            g.extend((0..FRAMES / size).map(|k| (ones(k * size..(k + 1) * size), p.runs)));
        }
    }
    if p.ema > 0.0 {
        g.extend(p.ema_at.iter().map(|&last| (ema_weights(last), p.ema)));
    }
    g
}

/// The kernels of the energy: sigma `p.sigma` for the frames, 4-spp frames and running
/// means, `p.ema_sigma` for the EMA groups (the last of [`groups`]), `count` groups in all.
fn spans(p: &SlotParams, count: usize) -> Vec<Span> {
    let ema = if p.ema > 0.0 { p.ema_at.len() } else { 0 };
    let mut spans = vec![Span {
        kernel: Kernel::new(p.sigma),
        levels: 0..count - ema,
    }];
    if ema > 0 {
        spans.push(Span {
            kernel: Kernel::new(p.ema_sigma),
            levels: count - ema..count,
        });
    }
    spans
}

/// The pool: offset `o`'s row holds, per group of [`groups`] and training edge, the weighted
/// count `sum_n q_n [p_{n ^ o} in t]` over the group's indices.
fn pool(pts: &[[f32; 2]], edges: &[Edge], groups: &[Group]) -> Pool {
    let t = edges.len();
    let mut hits = vec![0u8; PIXELS * groups.len() * t];
    for (o, row) in hits.chunks_exact_mut(groups.len() * t).enumerate() {
        for ((terms, _), level) in groups.iter().zip(row.chunks_exact_mut(t)) {
            for &(n, q) in terms {
                let p = pts[n ^ o];
                for (h, e) in level.iter_mut().zip(edges) {
                    *h += e.inside(p) as u8 * q;
                }
            }
        }
    }
    let counts: Vec<u32> = groups
        .iter()
        .map(|(terms, _)| terms.iter().map(|&(_, q)| q as u32).sum())
        .collect();
    assert!(
        counts.iter().all(|&c| c <= 255),
        "a group's weights overflow a byte"
    );
    let weights: Vec<f64> = groups.iter().map(|g| g.1).collect();
    Pool::from_hits(hits, &counts, edges, &weights)
}

/// Optimises slot `slot` of `base`: `TILE * TILE` offsets, row-major.
pub fn optimise(base: Base, slot: usize, p: &SlotParams) -> (Vec<u16>, SlotReport) {
    let start = Instant::now();
    let tag = (base as u64) << 8 | slot as u64;
    let mut rng = Rng::new(p.seed ^ (tag + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15));
    let pts = points(base, slot);
    let mut o: Vec<usize> = (0..PIXELS).collect();
    for k in (1..PIXELS).rev() {
        o.swap(k, rng.below(k + 1));
    }
    let before = measure(&pts, &o);
    let edges: Vec<Edge> = (0..p.edges).map(|k| Edge::lattice(k, p.edges)).collect();
    let groups = groups(p);
    let pool = pool(&pts, &edges, &groups);
    let mut s = State::with_spans(&pool, spans(p, groups.len()), o, Vec::new());
    let half = (p.window / 2) as i32;
    // Threshold accepting (Dueck and Scheuer 1990), as in `opt`: a swap is taken when `dE` is
    // below a threshold falling linearly to zero; `|e|^2` of an offset is about `dim`.
    let dim = p.edges * groups.len();
    let t0 = p.threshold * dim as f64;
    let mut accepted = 0;
    for step in 0..p.swaps {
        let threshold = (t0 * (1.0 - step as f64 / p.swaps as f64)) as f32;
        let a = rng.below(PIXELS);
        let dx = rng.below(p.window) as i32 - half;
        let dy = rng.below(p.window) as i32 - half;
        let b = State::neighbour(a, dx, dy);
        if a != b && s.swap_delta(a, b) < threshold {
            s.apply_swap(a, b);
            accepted += 1;
        }
    }
    let after = measure(&pts, &s.tile);
    let tile = s.tile.iter().map(|&o| o as u16).collect();
    (
        tile,
        SlotReport {
            seconds: start.elapsed().as_secs_f64(),
            accepted,
            before,
            after,
        },
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::opt;

    /// The energy from its definition, `sum_l sum_p sum_d G_l(d) e_p[l] . e_{p+d}[l]` per
    /// level (group) `l`, with the kernel of sigma `sigma_of(l)` for level `l`: independent of
    /// the state's fields and spans.
    fn reference(
        pool: &Pool,
        tile: &[usize],
        t: usize,
        sigma_of: impl Fn(usize) -> f64,
    ) -> Vec<f64> {
        let e: Vec<Vec<f64>> = tile.iter().map(|&j| pool.error(j).collect()).collect();
        let levels = e[0].len() / t;
        (0..levels)
            .map(|l| {
                let kernel = Kernel::new(sigma_of(l));
                let r = l * t..(l + 1) * t;
                let mut sum = 0.0;
                for (p, ep) in e.iter().enumerate() {
                    for &(dx, dy, w) in &kernel.taps {
                        let eq = &e[State::neighbour(p, dx, dy)];
                        let dot: f64 = ep[r.clone()]
                            .iter()
                            .zip(&eq[r.clone()])
                            .map(|(a, b)| a * b)
                            .sum();
                        sum += w as f64 * dot;
                    }
                }
                sum
            })
            .collect()
    }

    /// The swap's predicted energy change (`swap_delta`) and the field it updates
    /// (`apply_swap`) against the energy from its definition ([`reference`]), with two
    /// kernels: sigma 1.5 for the frames and running means, sigma 1 for the EMA groups (as the
    /// tables are made). Per level, the state's energy must match the reference with each
    /// group's own kernel: the EMA levels' energy with the frames' kernel is off by far more
    /// than the tolerance (checked). Swap partners inside the kernels (where the `G(a - b)`
    /// terms matter: a wrong kernel there is off by `2 |d|^2 (G_1 - G_1.5)(a - b)` over the EMA
    /// levels, checked to exceed ten times the tolerance for the nearest partners) and outside.
    #[test]
    fn swap_delta_matches_recomputed_energy() {
        let p = SlotParams {
            seed: 1,
            sigma: 1.5,
            edges: 8,
            swaps: 0,
            window: 7,
            quad: 0.0,
            runs: 0.5,
            ema: 3.0,
            ema_at: vec![15, 31],
            ema_sigma: 1.0,
            threshold: 0.0,
        };
        let pts = points(Base::Sobol, 0);
        let edges: Vec<Edge> = (0..p.edges).map(|k| Edge::lattice(k, p.edges)).collect();
        let groups = groups(&p);
        let pool = pool(&pts, &edges, &groups);
        let ema_from = groups.len() - p.ema_at.len();
        let sigma_of = |l: usize| if l >= ema_from { p.ema_sigma } else { p.sigma };
        let mut rng = Rng::new(7);
        let mut o: Vec<usize> = (0..PIXELS).collect();
        for k in (1..PIXELS).rev() {
            o.swap(k, rng.below(k + 1));
        }
        let mut s = State::with_spans(&pool, spans(&p, groups.len()), o, Vec::new());
        let t = p.edges;
        let same = |got: &[f64], want: &[f64], what: &str| {
            for (l, (g, w)) in got.iter().zip(want).enumerate() {
                assert!(
                    (g - w).abs() <= 1e-4 * w.abs() + 1e-3,
                    "{what}, level {l}: {g} against {w}"
                );
            }
        };
        let first = reference(&pool, &s.tile, t, sigma_of);
        same(&s.energies().0, &first, "start");
        let wrong = reference(&pool, &s.tile, t, |_| p.sigma);
        for l in ema_from..groups.len() {
            assert!(
                (wrong[l] - first[l]).abs() > 10.0 * (1e-4 * first[l].abs() + 1e-3),
                "level {l}: the kernels are not told apart ({} against {})",
                wrong[l],
                first[l]
            );
        }
        let (g1, g15) = (Kernel::new(p.ema_sigma), Kernel::new(p.sigma));
        for (dx, dy) in [(1, 0), (0, -2), (2, 3), (20, 5)] {
            let a = rng.below(PIXELS);
            let b = State::neighbour(a, dx, dy);
            let before: f64 = reference(&pool, &s.tile, t, sigma_of).iter().sum();
            let predicted = s.swap_delta(a, b) as f64;
            let (ea, eb): (Vec<f64>, Vec<f64>) = (
                pool.error(s.tile[a]).collect(),
                pool.error(s.tile[b]).collect(),
            );
            let d2: f64 = (ema_from * t..groups.len() * t)
                .map(|k| (eb[k] - ea[k]) * (eb[k] - ea[k]))
                .sum();
            let kernel_gap = 2.0
                * d2
                * (opt::g_between(a, b, &g1.g_table) - opt::g_between(a, b, &g15.g_table)).abs()
                    as f64;
            s.apply_swap(a, b);
            let incremental = s.energies().0;
            let want = reference(&pool, &s.tile, t, sigma_of);
            same(&incremental, &want, "field updated by the swap");
            s.recompute_field();
            same(&s.energies().0, &want, "field recomputed");
            let after: f64 = want.iter().sum();
            let tol = 1e-3 * predicted.abs() + 1e-2;
            assert!(
                predicted.abs() > 1.0,
                "a swap that changes nothing tests nothing"
            );
            assert!(
                (after - before - predicted).abs() < tol,
                "({dx}, {dy}): dE {predicted} predicted, {} recomputed",
                after - before
            );
            if dx * dx + dy * dy <= 4 {
                assert!(
                    kernel_gap > 10.0 * tol,
                    "({dx}, {dy}): kernel gap {kernel_gap}, tolerance {tol}"
                );
            }
        }
    }

    /// What the doc claims for time: every aligned block of `2^k` indices (the frames
    /// `0..2^k` of a pixel, whatever its offset) is a `(0, k, 2)`-net: each elementary
    /// interval of area `2^-k` holds exactly one point. Both patterns, every slot, `k <= 6`,
    /// every block among the first `TILE^2` points.
    #[test]
    fn aligned_blocks_are_nets() {
        for base in [Base::Sobol, Base::Pmj02bn] {
            for slot in 0..BLUE_SLOT_KEYS.len() {
                let pts = points(base, slot);
                for k in 1..=6u32 {
                    for block in pts.chunks_exact(1 << k) {
                        for a in 0..=k {
                            let mut seen = vec![false; 1 << k];
                            for p in block {
                                let cx = (p[0] * (1u32 << a) as f32) as usize;
                                let cy = (p[1] * (1u32 << (k - a)) as f32) as usize;
                                let cell = cy << a | cx;
                                assert!(!seen[cell], "{base:?} slot {slot}: 2^{k} block not a net");
                                seen[cell] = true;
                            }
                        }
                    }
                }
            }
        }
    }

    /// The EMA group's integer weights against the EMA run as a recursion (`ema = e_0`, then
    /// `ema = 0.9 ema + 0.1 e_f`) on unit impulses: each frame's weight within the rounding
    /// (half a unit of 1/254), their total within a byte. A wrong decay (e.g. `0.9^(f)` in
    /// place of `0.9^(F - f)`, or frame 0 without its `1 / alpha` share) is off by far more.
    #[test]
    fn ema_weights_match_the_recursion() {
        for last in [7, 15, 23, 31] {
            let q = ema_weights(last);
            let total: u32 = q.iter().map(|&(_, q)| q as u32).sum();
            assert!((250..=255).contains(&total), "F = {last}: total {total}");
            for impulse in 0..=last {
                let mut ema = 0.0f64;
                for f in 0..=last {
                    let e = (f == impulse) as u32 as f64;
                    ema = if f == 0 { e } else { 0.9 * ema + 0.1 * e };
                }
                let got = q
                    .iter()
                    .find(|&&(f, _)| f == impulse)
                    .map_or(0.0, |&(_, q)| q as f64 / 254.0);
                assert!(
                    (got - ema).abs() <= 0.5 / 254.0 + 1e-12,
                    "F = {last}, frame {impulse}: {got} against {ema}"
                );
            }
        }
    }
}
