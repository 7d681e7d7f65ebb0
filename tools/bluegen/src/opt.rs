//! The optimiser: per-pixel keys whose Monte Carlo errors cancel between neighbours.
//!
//! # What is optimised
//!
//! A pixel of `Blue<P>` draws `P`'s points keyed by one 32-bit word of a `TILE x TILE` tile
//! (see `src/sampler/blue.rs`). Following Heitz, Belcour, Ostromoukhov, Coeurjolly and Iehl,
//! "A Low-Discrepancy Sampler that Distributes Monte Carlo Errors as a Blue Noise in Screen
//! Space" (SIGGRAPH Talks 2019), and Belcour and Heitz, "Lessons learned and improvements
//! when building screen-space samplers with blue-noise error distribution" (SIGGRAPH Talks
//! 2021), the keys are chosen offline so that, for a family of test integrands, the errors of
//! neighbouring pixels differ — here: cancel. Every key of a pool gets an *error vector*: its
//! signed error on each test integrand after 1, 2, 4, ... `2^(levels-1)` samples (the first
//! two dimensions, `draw::<2>()`, through the library's own code), every level normalised to
//! unit RMS over the pool and then weighted, so that every power-of-two count counts and the
//! tile is blue noise progressively, without knowing the count in advance.
//!
//! The test integrands are half-planes of the pixel square (the discontinuity that dominates
//! rendering error), a rank-1 lattice over the lines that cross the square ([`Edge::lattice`]):
//! with random lines the optimiser fits their accidents (128 random lines: blurred error
//! 0.59 x white noise at 4 spp on the training lines, 0.75 x on fresh ones), a stratified
//! family generalises better (256 lattice lines: 0.60 x -> 0.67 x). With the line energy
//! below, a grid of 32 angles x 8 offsets ([`Edge::grid`]), whose offsets the pairing
//! across pixels needs.
//!
//! # The energy
//!
//! Heitz et al. minimise a sum over pixel pairs of `exp(-|p-q|^2/s_i^2 - |e_p-e_q|^2/s_s^2)`,
//! which pushes neighbouring error vectors apart. We minimise what a denoiser (or the eye)
//! sees instead: the energy of the error image after a Gaussian low-pass filter `g` (sigma
//! [`SIGMA`] pixels), summed over the test integrands and levels,
//!
//! ```text
//! E = sum_t |g * e_t|^2 = sum_{p,q} G(p - q) e_p . e_q,   G = g * g (a Gaussian of sigma * sqrt 2),
//! ```
//!
//! on the torus (the tile repeats and is shifted per domain), a quadratic form in the error
//! vectors with the same effect (neighbours' errors negatively correlated, the pair term
//! growing as they approach) and the same blue spectrum, measured the way the acceptance
//! figure measures it. Keeping the filtered field `F_p = sum_q G(p - q) e_q` makes every move
//! `O(dim)` to evaluate:
//!
//! * replacing the key of `a` by an unused pool key (`d = e_new - e_a`):
//!   `dE = 2 d . F_a + G(0) |d|^2 = |e_new + F_a - G(0) e_a|^2 - const`;
//! * swapping the keys of pixels `a` and `b` (`d = e_b - e_a`):
//!   `dE = 2 d . (F_a - F_b) + 2 |d|^2 (G(0) - G(a - b))`;
//!
//! and `O(taps x dim)` to apply (the field is updated over the kernel's support).
//!
//! The energy may filter groups of levels with different kernels ([`Span`]: the slot tiles
//! measure their EMA channel at sigma 1 and their frames at sigma 1.5): `E` is then a sum of
//! such quadratic forms, one per span, each level's field is filtered with its span's kernel,
//! and `G(0)` (1 for every kernel) and `G(a - b)` in the moves are taken per span.
//!
//! # Lines (a light's silhouette)
//!
//! On a rendered image the error of the pixel-position draw is not spread over the plane:
//! it lives on the one-pixel outlines of emitters seen directly, and a pixel's error can
//! only cancel against neighbours that carry error too — along the line. Tiles optimised
//! for the full plane alone leave 0.77-0.85x of white noise's blurred error there instead
//! of 0.27x. So the energy can also be measured on lines ([`Kernel::lines`]): with test
//! edges on a grid of angles and offsets, a pixel crossed by the line of edge `(n, c)` pairs
//! with its neighbour `q = p + d` through the edge `(n, c - d . n)` of `q`'s square (the
//! same line), and with nothing when that edge misses `q`; averaged over the tile's eight
//! symmetries. Per level (sample count) a weight mixes the two energies: 0.8 on lines at 1
//! and 2 spp, 0.4 from 4 spp up (lines at every count cost the path scenes at 4 spp, where
//! the indirect light, a full-plane integrand, weighs more, and the edge test's 4-spp
//! margin) — see docs/sampler.md for the measurements. The line pairs do not see the tile's
//! mean error, which fresh frames converge to (every frame reads the same 4096 keys at
//! another shift); without a constant kernel to hold it at zero the running mean of 32
//! fresh `Blue<P>` frames measured 1.1-1.3x white noise after the blur (0.6-0.7x with it).
//!
//! # The search
//!
//! The best replacement for a pixel is the pool key nearest to `-(F_a - G(0) e_a)`, the error
//! that cancels what its neighbours leave. *Guided sweeps* visit every pixel in a random order
//! and take that key: a random projection of all error vectors to [`SKETCH`] dimensions
//! (Johnson-Lindenstrauss) shortlists [`SHORTLIST`] candidates among the whole pool in
//! `O(pool x SKETCH)`, their exact `dE` decides. Eight sweeps reach what 16 million random
//! proposals reach (0.60 x white noise at 4 spp on the training lines, equal weights) in a
//! third of the time. Optional random proposals follow (half swaps, half replacements from the pool),
//! accepted by *threshold accepting* (Dueck and Scheuer 1990): a move is taken when `dE` is
//! below a threshold that falls linearly to zero — simulated annealing's schedule without
//! its `exp`.
//!
//! The level weights trade counts against each other (a key is one choice among the pool for
//! all levels at once): `1, 1, 1, 0.85, 0.7` for 1, 2, 4, 8, 16 spp buys 1-4 spp a few
//! percent at 16 spp's expense (the full-plane tiles); the committed tiles use
//! `1, 0.8, 1, 0.6, 0.4` with line weights `0.8, 0.8, 0.4` (1 and 4 spp are the counts the
//! path scenes are measured at).
//!
//! # Determinism
//!
//! One SplitMix64 stream per tile, single-threaded, integer hit counts, f32/f64 adds and
//! multiplies in a fixed order (eight explicit lanes; Rust never contracts them into fused
//! multiply-adds), no libm: the kernel's weights and the lattice's directions come from our
//! own series. The same bytes on every machine.

use pmjgen::Rng;
use pmjgen::tool::square_area_below;
use warpcore::sampler::{Pmj02bn, Sampler, Sobol};

/// Tile side (must equal `warpcore::sampler::BLUE_TILE`).
pub const TILE: usize = 64;
pub(crate) const PIXELS: usize = TILE * TILE;
/// Sigma of the low-pass filter the energy measures, in pixels.
pub const SIGMA: f64 = 1.5;

/// Dimensions of the random projection that shortlists replacement candidates.
const SKETCH: usize = 64;
/// Candidates per guided replacement whose exact energy change is computed.
const SHORTLIST: usize = 8;

/// A base pattern of `Blue<P>`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    Sobol,
    Pmj02bn,
}

impl Base {
    pub fn name(self) -> &'static str {
        match self {
            Base::Sobol => "sobol",
            Base::Pmj02bn => "pmj02bn",
        }
    }

    /// Point `index` of a pixel whose tile key is `key`, through the library's own code: what
    /// `Sampler::<Blue<P>>` draws in domain 0 (dimensions 0 and 1).
    pub fn point(self, key: u32, index: u32) -> [f32; 2] {
        match self {
            Base::Sobol => Sampler::<Sobol>::from_domain_hash(key, index).draw::<2>(),
            Base::Pmj02bn => Sampler::<Pmj02bn>::from_domain_hash(key, index).draw::<2>(),
        }
    }
}

/// `exp(x)` for `|x| <= 1` by its Taylor series (to the last bit of f64 within 20 terms):
/// basic arithmetic only, so the same bits everywhere.
pub(crate) fn exp_small(x: f64) -> f64 {
    let (mut term, mut sum) = (1.0, 1.0);
    for k in 1..20 {
        term = term * x / k as f64;
        sum += term;
    }
    sum
}

/// `[cos x, sin x]` for `x` in `[0, pi]`, by Taylor series around `pi / 2` (basic arithmetic
/// only).
fn cos_sin(x: f64) -> [f64; 2] {
    let t = x - core::f64::consts::FRAC_PI_2;
    // cos x = -sin t, sin x = cos t.
    let (mut sin_t, mut cos_t) = (0.0, 0.0);
    let mut term = 1.0; // t^j / j!
    for j in 0..30 {
        match j % 4 {
            0 => cos_t += term,
            1 => sin_t += term,
            2 => cos_t -= term,
            _ => sin_t -= term,
        }
        term = term * t / (j + 1) as f64;
    }
    [-sin_t, cos_t]
}

/// A test integrand: the half-plane `{u : (u - 1/2) . n < c}` of the pixel square.
#[derive(Clone, Copy, Debug)]
pub struct Edge {
    n: [f64; 2],
    c: f64,
    area: f64,
}

impl Edge {
    /// Line `k` of `count`: a rank-1 lattice over the lines that cross the square — angle
    /// `pi (k + 1/2) / count` (half a turn: the opposite normal gives the complement, whose
    /// error is the negation), offset at the golden-ratio fraction `frac(1/2 + k phi)` of its
    /// range. A stratified family approximates "all edges" far better than random lines, so
    /// the optimiser cannot fit the accidents of a random few.
    pub(crate) fn lattice(k: usize, count: usize) -> Edge {
        let angle = core::f64::consts::PI * (k as f64 + 0.5) / count as f64;
        let golden = 0.618_033_988_749_894_9;
        Edge::new(angle, (0.5 + k as f64 * golden).fract())
    }

    /// `angles x offsets` edges, angle-major: angle `pi (a + 1/2) / angles`, offset fraction
    /// `(j + 1/2) / offsets` (the family [`Kernel::lines`] pairs across pixels).
    pub(crate) fn grid(angles: usize, offsets: usize) -> Vec<Edge> {
        (0..angles * offsets)
            .map(|k| {
                let angle = core::f64::consts::PI * ((k / offsets) as f64 + 0.5) / angles as f64;
                Edge::new(angle, ((k % offsets) as f64 + 0.5) / offsets as f64)
            })
            .collect()
    }

    /// The line of normal angle `angle` (in `[0, pi]`) at the fraction `u` of the offsets
    /// whose lines cross the square.
    pub(crate) fn new(angle: f64, u: f64) -> Edge {
        let n = cos_sin(angle);
        let half = 0.5 * (n[0].abs() + n[1].abs());
        let c = half * (2.0 * u - 1.0);
        let mut e = Edge { n, c, area: 0.0 };
        e.area = e.exact_area();
        e
    }

    pub(crate) fn inside(&self, p: [f32; 2]) -> bool {
        (p[0] as f64 - 0.5) * self.n[0] + (p[1] as f64 - 0.5) * self.n[1] < self.c
    }

    /// The exact area of the half-plane in the square (computed once, by [`Edge::new`]).
    pub(crate) fn area(&self) -> f64 {
        self.area
    }

    fn exact_area(&self) -> f64 {
        square_area_below(|p| (p[0] - 0.5) * self.n[0] + (p[1] - 0.5) * self.n[1] - self.c)
    }
}

/// The optimiser's settings (recorded in the manifest's command line).
#[derive(Clone, Debug)]
pub struct Params {
    pub seed: u64,
    /// Candidate keys (the tile starts with the first `TILE^2`).
    pub pool: usize,
    /// Test half-planes (a multiple of 8).
    pub edges: usize,
    /// Sample counts 1, 2, 4, .. `2^(levels - 1)`.
    pub levels: usize,
    /// Guided sweeps (every pixel takes the best pool key the sketch finds).
    pub sweeps: usize,
    /// Random proposals per pixel, after the sweeps.
    pub rounds: usize,
    /// The starting threshold, as a fraction of the mean `|e|^2` of one pool key.
    pub threshold: f64,
    /// Weight of each level in the energy (missing entries: 1).
    pub weights: Vec<f64>,
    /// Per level, the share of the energy measured on lines (see [`Kernel::lines`]; missing
    /// entries: the last one, none: 0): 0 is the full-plane energy alone.
    pub line_weights: Vec<f64>,
    /// Offsets per angle of the test edges when a line weight is not 0 (a grid of `edges /
    /// line_offsets` angles; with 0, the rank-1 lattice of [`Edge::lattice`]).
    pub line_offsets: usize,
}

/// What one optimisation did.
pub struct Report {
    /// Per level: `sqrt(E / E_white)` of the start and the result, an estimate of the blurred
    /// RMS error relative to white noise (independent keys) on the test integrands.
    pub before: Vec<f64>,
    pub after: Vec<f64>,
    pub accepted: usize,
    pub replaced: usize,
}

/// The pool's errors: for key `j`, level `l` (`n_l` samples, `n_l = 2^l` for the key tiles) and
/// edge `t`, the error is `(hits - n_l area_t) / n_l`, scaled by `weight_l / rms_l` (the level's
/// RMS over the pool, so every level weighs the same before its weight). Only `hits` depends on the key: it is stored as one byte (levels
/// up to 128 samples), which makes a move's cost mostly a read of `dim` bytes per key; the
/// difference of two keys' errors is exactly `(hits_b - hits_a) * unit_l`.
pub(crate) struct Pool {
    hits: Vec<u8>,
    levels: usize,
    edges: usize,
    dim: usize,
    /// Per level: `1 / (n rms_l)`, the error of one hit.
    unit: Vec<f32>,
    /// Per level: `n area_t` for each edge (the hits of zero error), `dim` entries.
    zero: Vec<f64>,
}

impl Pool {
    fn new(base: Base, keys: &[u32], edges: &[Edge], levels: usize, weights: &[f64]) -> Pool {
        let t = edges.len();
        let dim = levels * t;
        let mut hits = vec![0u8; keys.len() * dim];
        let mut count = vec![0u32; t];
        for (k, &key) in keys.iter().enumerate() {
            count.iter_mut().for_each(|h| *h = 0);
            let row = &mut hits[k * dim..(k + 1) * dim];
            let mut i = 0u32;
            for level in 0..levels {
                while i < 1 << level {
                    let p = base.point(key, i);
                    for (h, e) in count.iter_mut().zip(edges) {
                        *h += e.inside(p) as u32;
                    }
                    i += 1;
                }
                for (r, &h) in row[level * t..(level + 1) * t].iter_mut().zip(&count) {
                    *r = h as u8;
                }
            }
        }
        let counts: Vec<u32> = (0..levels).map(|l| 1 << l).collect();
        Pool::from_hits(hits, &counts, edges, weights)
    }

    /// The pool of the rows of `hits`: row `j`, level `l`, edge `t` at `j dim + l T + t` is
    /// how many of the level's `counts[l]` points (at most 255) fall in edge `t`.
    pub(crate) fn from_hits(
        hits: Vec<u8>,
        counts: &[u32],
        edges: &[Edge],
        weights: &[f64],
    ) -> Pool {
        let (t, levels) = (edges.len(), counts.len());
        let dim = levels * t;
        assert!(t.is_multiple_of(8) && hits.len().is_multiple_of(dim));
        let zero: Vec<f64> = (0..dim)
            .map(|k| counts[k / t] as f64 * edges[k % t].area)
            .collect();
        // The RMS error of each level over the pool (f64, in a fixed order).
        let mut square = vec![0.0f64; levels];
        for row in hits.chunks_exact(dim) {
            for (k, &h) in row.iter().enumerate() {
                let e = h as f64 - zero[k];
                square[k / t] += e * e;
            }
        }
        let unit = (0..levels)
            .map(|l| {
                let n = counts[l] as f64;
                let rms = (square[l] / (hits.len() / dim * t) as f64).sqrt() / n;
                (weights.get(l).copied().unwrap_or(1.0) / (n * rms)) as f32
            })
            .collect();
        Pool {
            hits,
            levels,
            edges: t,
            dim,
            unit,
            zero,
        }
    }

    fn row(&self, j: usize) -> &[u8] {
        &self.hits[j * self.dim..(j + 1) * self.dim]
    }

    /// Key `j`'s error vector.
    pub(crate) fn error(&self, j: usize) -> impl Iterator<Item = f64> + '_ {
        self.row(j)
            .iter()
            .enumerate()
            .map(|(k, &h)| (h as f64 - self.zero[k]) * self.unit[k / self.edges] as f64)
    }
}

/// The energy's kernel `G = exp(-|d|^2 / (4 sigma^2))` (the autocorrelation of a Gaussian
/// low-pass of sigma `sigma`), on the offsets with `|d|^2 <= radius2`, where `G` has fallen to
/// 1%: `radius2 = ceil(4 sigma^2 ln 100)` (42 for sigma 1.5, 19 for sigma 1).
pub(crate) struct Kernel {
    /// `(dx, dy, G(dx, dy))` over the support.
    pub(crate) taps: Vec<(i32, i32, f32)>,
    /// `G` by squared distance, `0..=radius2`.
    pub(crate) g_table: Vec<f32>,
    /// Empty (the isotropic `G` of `taps`), or per level and tap the pairs of edges it
    /// couples, see [`Kernel::lines`]: `(k, j, w)` adds `w` times the error of edge `j` of the
    /// pixel to edge `k` of its neighbour at the tap's offset.
    gather: Vec<LinePairs>,
    /// Empty, or per level the weight of a constant kernel (`|sum_p e_p|^2`, see
    /// [`Kernel::lines`]).
    dc: Vec<f32>,
}

impl Kernel {
    pub(crate) fn new(sigma: f64) -> Kernel {
        let ln100 = 4.605_170_185_988_091;
        let radius2 = (4.0 * sigma * sigma * ln100).ceil() as i32;
        let q = exp_small(-1.0 / (4.0 * sigma * sigma));
        let g_table: Vec<f32> = (0..=radius2)
            .map(|d2| (0..d2).fold(1.0f64, |w, _| w * q) as f32)
            .collect();
        let r = (radius2 as f64).sqrt() as i32;
        let mut taps = Vec::new();
        for dy in -r..=r {
            for dx in -r..=r {
                let d2 = dx * dx + dy * dy;
                if d2 <= radius2 {
                    taps.push((dx, dy, g_table[d2 as usize]));
                }
            }
        }
        Kernel {
            taps,
            g_table,
            gather: Vec::new(),
            dc: Vec::new(),
        }
    }

    /// The kernel of an energy measured partly on lines. A light's silhouette is a line of
    /// pixels, each covering a half-plane whose edge is the line: its blurred error is
    /// `sum_{p,q on the line} G(q - p) e_p e_q`, and a pixel's error can only cancel against
    /// its neighbours along the line. The neighbour `q = p + d` of a pixel crossed by the
    /// line of normal `n` and offset `c` (edge `(n, c)` in `p`'s square) sees the same line
    /// as the edge `(n, c - d . n)` of its own square, and carries error only if that edge
    /// still crosses it. So with test edges on a grid of `angles x offsets` (`edges[a
    /// offsets + j]`: angle `a`, offset fraction `(j + 1/2) / offsets`), the line energy pairs
    /// edge `j` of `p` with edge `j - offsets (d . n) / (|n_x| + |n_y|)` (rounded) of `q`, or
    /// with nothing. The tile reaches the screen under any of the eight symmetries of the
    /// square (`src/sampler/blue.rs`), which turn the tile offset `d` into the screen offset
    /// `S d` while the points stay put, so each pair is averaged over the eight. Mixed with
    /// the full-plane energy (edge `k` with edge `k`): `(1 - weight) G + weight G (line
    /// pairs)`, still the identity at `d = 0`, so moves keep their `O(dim)` evaluation. One
    /// `weight` per level (sample count).
    pub(crate) fn lines(sigma: f64, edges: &[Edge], offsets: usize, weights: &[f64]) -> Kernel {
        let mut k = Kernel::new(sigma);
        if weights.iter().all(|&w| w == 0.0) {
            return k;
        }
        k.gather = weights
            .iter()
            .map(|&w| Kernel::line_pairs(&k.taps, edges, offsets, w))
            .collect();
        // The line pairs do not see the tile's mean error (the same for every pixel), which
        // the full-plane kernel holds at zero with its whole mass `sum_d G(d)`; but the mean
        // over the tile is what fresh frames converge to (each frame reads the tile at
        // another shift), so a constant kernel gives that weight back.
        let mass: f64 = k.taps.iter().map(|t| t.2 as f64).sum();
        k.dc = weights
            .iter()
            .map(|&w| (w * mass / PIXELS as f64) as f32)
            .collect();
        k
    }

    /// [`Kernel::lines`]'s pairs of one level, per tap.
    fn line_pairs(
        taps: &[(i32, i32, f32)],
        edges: &[Edge],
        offsets: usize,
        weight: f64,
    ) -> LinePairs {
        let t = edges.len();
        assert!(t.is_multiple_of(offsets) && t <= 1 << 16);
        let mut gather = Vec::new();
        for &(dx, dy, g) in taps {
            let mut pairs = std::collections::BTreeMap::<(u16, u16), f64>::new();
            for kk in 0..t {
                *pairs.entry((kk as u16, kk as u16)).or_default() += (1.0 - weight) * g as f64;
            }
            let (dx, dy) = (dx as f64, dy as f64);
            let symmetries = [
                (dx, dy),
                (-dx, dy),
                (dx, -dy),
                (-dx, -dy),
                (dy, dx),
                (-dy, dx),
                (dy, -dx),
                (-dy, -dx),
            ];
            for (sx, sy) in symmetries {
                for (kk, e) in edges.iter().enumerate() {
                    // q = p + d is tap's neighbour: edge kk of q pairs with edge j of p,
                    // c_q = c_p - d . n, so j = j_q + offsets (d . n) / (|n_x| + |n_y|).
                    let shift = offsets as f64 * (sx * e.n[0] + sy * e.n[1])
                        / (e.n[0].abs() + e.n[1].abs());
                    let j = (kk % offsets) as i64 + shift.round() as i64;
                    if (0..offsets as i64).contains(&j) {
                        let src = (kk - kk % offsets) as i64 + j;
                        *pairs.entry((kk as u16, src as u16)).or_default() +=
                            weight * g as f64 / 8.0;
                    }
                }
            }
            gather.push(
                pairs
                    .into_iter()
                    .map(|((a, b), w)| (a, b, w as f32))
                    .collect(),
            );
        }
        gather
    }
}

/// One level's edge pairs per tap of a line kernel: `(k, j, w)` adds `w` times the error of
/// edge `j` of a pixel to edge `k` of its neighbour at the tap's offset.
type LinePairs = Vec<Vec<(u16, u16, f32)>>;

/// `G` between two pixels on the torus (0 outside the support).
pub(crate) fn g_between(a: usize, b: usize, table: &[f32]) -> f32 {
    let wrap = |d: isize| {
        let d = d.rem_euclid(TILE as isize);
        if d > TILE as isize / 2 {
            d - TILE as isize
        } else {
            d
        }
    };
    let dx = wrap((b % TILE) as isize - (a % TILE) as isize);
    let dy = wrap((b / TILE) as isize - (a / TILE) as isize);
    let d2 = (dx * dx + dy * dy) as usize;
    table.get(d2).copied().unwrap_or(0.0)
}

/// For one level: `sum_k (u_k - v_k) x_k` and `sum_k (u_k - v_k)^2` (exact, integer), eight
/// lanes in a fixed order.
#[inline(always)]
fn dots(u: &[u8], v: &[u8], x: &[f32]) -> (f32, i32) {
    let (mut s1, mut s2) = ([0.0f32; 8], [0i32; 8]);
    for ((u, v), x) in u
        .chunks_exact(8)
        .zip(v.chunks_exact(8))
        .zip(x.chunks_exact(8))
    {
        for k in 0..8 {
            let d = u[k] as i32 - v[k] as i32;
            s1[k] += d as f32 * x[k];
            s2[k] += d * d;
        }
    }
    let sum = |s: [f32; 8]| ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    (sum(s1), s2.iter().sum())
}

/// As [`dots`] with `x = y - z`.
#[inline(always)]
fn dots3(u: &[u8], v: &[u8], y: &[f32], z: &[f32]) -> (f32, i32) {
    let (mut s1, mut s2) = ([0.0f32; 8], [0i32; 8]);
    for (((u, v), y), z) in u
        .chunks_exact(8)
        .zip(v.chunks_exact(8))
        .zip(y.chunks_exact(8))
        .zip(z.chunks_exact(8))
    {
        for k in 0..8 {
            let d = u[k] as i32 - v[k] as i32;
            s1[k] += d as f32 * (y[k] - z[k]);
            s2[k] += d * d;
        }
    }
    let sum = |s: [f32; 8]| ((s[0] + s[1]) + (s[2] + s[3])) + ((s[4] + s[5]) + (s[6] + s[7]));
    (sum(s1), s2.iter().sum())
}

/// The levels `levels` of a pool filtered with one kernel: a state's energy may filter
/// different groups of levels with different kernels (each group's term is its own quadratic
/// form `sum_{p,q} G_k(p - q) e_p . e_q` over its levels).
pub(crate) struct Span {
    pub(crate) kernel: Kernel,
    pub(crate) levels: core::ops::Range<usize>,
}

/// The tile being optimised and its filtered field.
pub(crate) struct State<'a> {
    pool: &'a Pool,
    /// The kernels and the levels each filters, in order, covering `0..levels`; a kernel of
    /// edge pairs or with a constant part ([`Kernel::lines`]) only as the one span.
    spans: Vec<Span>,
    /// `sum_p e_p` in hits, for the constant kernel (or empty).
    sum: Vec<f32>,
    /// Pool index of each pixel's key.
    pub(crate) tile: Vec<usize>,
    used: Vec<bool>,
    /// `F_p = sum_q G(p - q) e_q` in hits (divided by the level's unit, so that a move adds
    /// `G` times a difference of hits and `d . F` is `unit^2 sum (hits_b - hits_a) field`):
    /// `dim` floats per pixel.
    field: Vec<f32>,
    /// The unit squared per level, and the hit differences of the move being applied.
    unit2: Vec<f32>,
    delta: Vec<f32>,
    /// A random projection of every pool key's error vector to [`SKETCH`] dimensions, their
    /// squared norms, and the projection's matrix (`dim x SKETCH`, applied to the field of
    /// the pixel being visited): the cheap approximate distances that shortlist replacement
    /// candidates (empty when the search only swaps).
    sketch: Vec<f32>,
    sketch_norm: Vec<f32>,
    signs: Vec<f32>,
}

impl<'a> State<'a> {
    /// The state of `tile` (pool rows, the rest of the pool unused) with a kernel per span of
    /// levels (`spans` in order, covering every level once), its field computed; a sketch
    /// (from [`project`]) only with one span (its field is filtered with that kernel).
    pub(crate) fn with_spans(
        pool: &'a Pool,
        spans: Vec<Span>,
        tile: Vec<usize>,
        sketch: Vec<f32>,
    ) -> Self {
        State::guided(pool, spans, tile, (sketch, Vec::new()))
    }

    /// As [`State::with_spans`] with the projection's matrix (from [`project`]).
    fn guided(
        pool: &'a Pool,
        spans: Vec<Span>,
        tile: Vec<usize>,
        (sketch, signs): (Vec<f32>, Vec<f32>),
    ) -> Self {
        let mut next = 0;
        for span in &spans {
            assert!(span.levels.start == next && span.levels.end > next);
            next = span.levels.end;
        }
        let lines = spans
            .iter()
            .any(|s| !s.kernel.gather.is_empty() || !s.kernel.dc.is_empty());
        assert!(next == pool.levels && ((sketch.is_empty() && !lines) || spans.len() == 1));
        let rows = pool.hits.len() / pool.dim;
        let mut used = vec![false; rows];
        tile.iter().for_each(|&j| used[j] = true);
        let mut s = State {
            pool,
            spans,
            sum: Vec::new(),
            tile,
            used,
            field: Vec::new(),
            unit2: pool.unit.iter().map(|u| u * u).collect(),
            delta: vec![0.0; pool.dim],
            sketch_norm: sketch
                .chunks_exact(SKETCH)
                .map(|s| s.iter().map(|x| x * x).sum())
                .collect(),
            sketch,
            signs,
        };
        s.recompute_field();
        if !s.dc().is_empty() {
            let mut sum = vec![0.0f64; pool.dim];
            for &j in &s.tile {
                for (k, (x, &h)) in sum.iter_mut().zip(pool.row(j)).enumerate() {
                    *x += h as f64 - pool.zero[k];
                }
            }
            s.sum = sum.iter().map(|&x| x as f32).collect();
        }
        s
    }

    pub(crate) fn neighbour(p: usize, dx: i32, dy: i32) -> usize {
        let x = (p % TILE) as i32 + dx;
        let y = (p / TILE) as i32 + dy;
        (y.rem_euclid(TILE as i32) as usize) * TILE + x.rem_euclid(TILE as i32) as usize
    }

    /// The one kernel's edge pairs per level and tap (empty: the isotropic `G`).
    fn gather(&self) -> &[LinePairs] {
        &self.spans[0].kernel.gather
    }

    /// The one kernel's constant part per level (or empty).
    fn dc(&self) -> &[f32] {
        &self.spans[0].kernel.dc
    }

    fn field_of(&self, p: usize) -> &[f32] {
        &self.field[p * self.pool.dim..(p + 1) * self.pool.dim]
    }

    /// The filtered field from scratch (in f64, then rounded).
    pub(crate) fn recompute_field(&mut self) {
        let (dim, t) = (self.pool.dim, self.pool.edges);
        let mut f = vec![0.0f64; PIXELS * dim];
        for p in 0..PIXELS {
            let e: Vec<f64> = self.pool.error(self.tile[p]).collect();
            for span in &self.spans {
                let r = span.levels.start * t..span.levels.end * t;
                let gather = &span.kernel.gather;
                for (i, &(dx, dy, w)) in span.kernel.taps.iter().enumerate() {
                    let q = Self::neighbour(p, dx, dy);
                    let f = &mut f[q * dim + r.start..q * dim + r.end];
                    if gather.is_empty() {
                        for (f, e) in f.iter_mut().zip(&e[r.clone()]) {
                            *f += w as f64 * e;
                        }
                        continue;
                    }
                    // Only as the one span: its levels are `0..levels`.
                    for (l, (f, e)) in f.chunks_exact_mut(t).zip(e.chunks_exact(t)).enumerate() {
                        for &(k, j, w) in &gather[l][i] {
                            f[k as usize] += w as f64 * e[j as usize];
                        }
                    }
                }
            }
        }
        self.field = f
            .iter()
            .enumerate()
            .map(|(i, &x)| (x / self.pool.unit[(i % dim) / t] as f64) as f32)
            .collect();
    }

    /// The change of the energy if the key of `a` became pool key `j`:
    /// `2 d . F_a + G(0) |d|^2`.
    fn replace_delta(&self, a: usize, j: usize) -> f32 {
        let (pool, t) = (self.pool, self.pool.edges);
        let (new, old, f) = (pool.row(j), pool.row(self.tile[a]), self.field_of(a));
        let mut de = 0.0;
        for l in 0..pool.levels {
            let r = l * t..(l + 1) * t;
            let (df, d2) = dots(&new[r.clone()], &old[r.clone()], &f[r.clone()]);
            de += self.unit2[l] * (2.0 * df + d2 as f32);
            if !self.dc().is_empty() {
                let (ds, _) = dots(&new[r.clone()], &old[r.clone()], &self.sum[r]);
                de += self.unit2[l] * self.dc()[l] * (2.0 * ds + d2 as f32);
            }
        }
        de
    }

    /// The change of the energy if `a` and `b` swapped keys:
    /// `2 d . (F_a - F_b) + 2 |d|^2 (G(0) - G(a - b))`, `d = e_b - e_a`.
    pub(crate) fn swap_delta(&self, a: usize, b: usize) -> f32 {
        let (pool, t) = (self.pool, self.pool.edges);
        let (eb, ea) = (pool.row(self.tile[b]), pool.row(self.tile[a]));
        let (fa, fb) = (self.field_of(a), self.field_of(b));
        if !self.gather().is_empty() {
            return self.swap_delta_gather(a, b);
        }
        let mut de = 0.0;
        for span in &self.spans {
            let g = g_between(a, b, &span.kernel.g_table);
            for l in span.levels.clone() {
                let r = l * t..(l + 1) * t;
                let (df, d2) = dots3(&eb[r.clone()], &ea[r.clone()], &fa[r.clone()], &fb[r]);
                de += self.unit2[l] * (2.0 * df + 2.0 * d2 as f32 * (1.0 - g));
            }
        }
        de
    }

    /// [`State::swap_delta`] under a kernel of edge pairs: `2 d . (F_a - F_b) + 2 |d|^2 -
    /// 2 sum_{(k, j, w) of the tap b - a} w d_k d_j` (a plain loop: swaps are rare in the key
    /// tiles' search).
    fn swap_delta_gather(&self, a: usize, b: usize) -> f32 {
        let (pool, t) = (self.pool, self.pool.edges);
        let (eb, ea) = (pool.row(self.tile[b]), pool.row(self.tile[a]));
        let (fa, fb) = (self.field_of(a), self.field_of(b));
        let d = |k: usize| eb[k] as f32 - ea[k] as f32;
        let mut de = 0.0;
        for k in 0..pool.dim {
            de += self.unit2[k / t] * (2.0 * d(k) * (fa[k] - fb[k]) + 2.0 * d(k) * d(k));
        }
        let tap = self.spans[0]
            .kernel
            .taps
            .iter()
            .position(|&(dx, dy, _)| Self::neighbour(a, dx, dy) == b);
        if let Some(i) = tap {
            for l in 0..pool.levels {
                for &(k, j, w) in &self.gather()[l][i] {
                    let (k, j) = (l * t + k as usize, l * t + j as usize);
                    de -= self.unit2[l] * 2.0 * w * d(k) * d(j);
                }
            }
        }
        de
    }

    /// Puts `hits_new - hits_old` into `delta`.
    fn set_delta(&mut self, new: usize, old: usize) {
        let (n, o) = (self.pool.row(new), self.pool.row(old));
        for ((d, &n), &o) in self.delta.iter_mut().zip(n).zip(o) {
            *d = (n as i32 - o as i32) as f32;
        }
    }

    /// Adds `sign G(q - p) delta` to the field around `p`, each span with its kernel.
    fn spread(&mut self, p: usize, sign: f32) {
        let (dim, t) = (self.pool.dim, self.pool.edges);
        for span in &self.spans {
            let r = span.levels.start * t..span.levels.end * t;
            let gather = &span.kernel.gather;
            for (i, &(dx, dy, w)) in span.kernel.taps.iter().enumerate() {
                let q = Self::neighbour(p, dx, dy);
                let field = &mut self.field[q * dim + r.start..q * dim + r.end];
                if gather.is_empty() {
                    let w = w * sign;
                    for (f, d) in field.iter_mut().zip(&self.delta[r.clone()]) {
                        *f += w * d;
                    }
                } else {
                    let levels = field.chunks_exact_mut(t).zip(self.delta.chunks_exact(t));
                    for (l, (f, d)) in levels.enumerate() {
                        for &(k, j, w) in &gather[l][i] {
                            f[k as usize] += sign * w * d[j as usize];
                        }
                    }
                }
            }
        }
    }

    /// Moves pixel `a` from pool key `old` to `new` in the field.
    fn move_fields(&mut self, a: usize, new: usize, old: usize) {
        self.set_delta(new, old);
        self.spread(a, 1.0);
    }

    pub(crate) fn apply_swap(&mut self, a: usize, b: usize) {
        let (ja, jb) = (self.tile[a], self.tile[b]);
        self.move_fields(a, jb, ja);
        self.move_fields(b, ja, jb);
        self.tile.swap(a, b);
    }

    fn apply_replace(&mut self, a: usize, j: usize) {
        let old = self.tile[a];
        self.move_fields(a, j, old);
        if !self.sum.is_empty() {
            for (s, d) in self.sum.iter_mut().zip(&self.delta) {
                *s += d;
            }
        }
        self.tile[a] = j;
        self.used[old] = false;
        self.used[j] = true;
    }

    /// The best replacement for the key of `a` among the unused pool keys, if it lowers the
    /// energy by more than `-threshold`: the sketch shortlists [`SHORTLIST`] candidates
    /// (`min |s_j + s(F_a - e_a)|^2`), the exact change decides.
    fn best_replacement(&self, a: usize, threshold: f32) -> Option<usize> {
        // u = 2 R^T (F_a - e_a), in error units: the field is in hits, `e_a` is
        // `hits - zero`, both times the level's unit.
        let (pool, t) = (self.pool, self.pool.edges);
        let (f, own) = (self.field_of(a), pool.row(self.tile[a]));
        let mut u = [0.0f32; SKETCH];
        for (k, r) in self.signs.chunks_exact(SKETCH).enumerate() {
            let x = 2.0 * pool.unit[k / t] * (f[k] - (own[k] as f64 - pool.zero[k]) as f32);
            for (u, r) in u.iter_mut().zip(r) {
                *u += x * r;
            }
        }
        let mut best = [(f32::INFINITY, usize::MAX); SHORTLIST];
        for (j, s) in self.sketch.chunks_exact(SKETCH).enumerate() {
            let mut acc = [0.0f32; 8];
            for (s, u) in s.chunks_exact(8).zip(u.chunks_exact(8)) {
                for k in 0..8 {
                    acc[k] += s[k] * u[k];
                }
            }
            let score = self.sketch_norm[j]
                + (((acc[0] + acc[1]) + (acc[2] + acc[3]))
                    + ((acc[4] + acc[5]) + (acc[6] + acc[7])));
            if score < best[SHORTLIST - 1].0 && !self.used[j] {
                let mut k = SHORTLIST - 1;
                while k > 0 && best[k - 1].0 > score {
                    best[k] = best[k - 1];
                    k -= 1;
                }
                best[k] = (score, j);
            }
        }
        let mut choice = None;
        let mut lowest = threshold;
        for &(_, j) in best.iter().filter(|b| b.1 != usize::MAX) {
            let de = self.replace_delta(a, j);
            if de < lowest {
                lowest = de;
                choice = Some(j);
            }
        }
        choice
    }

    /// Per level `sqrt(E_level / E_white)`: `E = sum_p e_p . F_p`, `E_white = G(0) sum_p |e_p|^2`
    /// (its expectation for independent keys).
    fn ratios(&self) -> Vec<f64> {
        let (e, white) = self.energies();
        e.iter().zip(&white).map(|(e, w)| (e / w).sqrt()).collect()
    }

    /// Per level `E = sum_p e_p . F_p` (from the field as it stands) and `sum_p |e_p|^2`.
    pub(crate) fn energies(&self) -> (Vec<f64>, Vec<f64>) {
        let (levels, t) = (self.pool.levels, self.pool.edges);
        let (mut e, mut white) = (vec![0.0f64; levels], vec![0.0f64; levels]);
        for p in 0..PIXELS {
            let f = self.field_of(p);
            for (k, ep) in self.pool.error(self.tile[p]).enumerate() {
                let l = k / t;
                e[l] += ep * f[k] as f64 * self.pool.unit[l] as f64;
                white[l] += ep * ep;
            }
        }
        (e, white)
    }
}

/// Every pool key's error vector times a random `+-1 / sqrt(SKETCH)` matrix (a
/// Johnson-Lindenstrauss projection: distances are kept to within a few tens of percent,
/// enough to shortlist).
fn project(pool: &Pool, rng: &mut Rng) -> (Vec<f32>, Vec<f32>) {
    let scale = 1.0 / (SKETCH as f32).sqrt();
    let signs: Vec<[f32; SKETCH]> = (0..pool.dim)
        .map(|_| {
            let bits = rng.next_u64();
            core::array::from_fn(|m| if bits >> m & 1 == 1 { scale } else { -scale })
        })
        .collect();
    let rows = pool.hits.len() / pool.dim;
    let mut out = vec![0.0f32; rows * SKETCH];
    for (j, o) in out.chunks_exact_mut(SKETCH).enumerate() {
        for (e, r) in pool.error(j).zip(&signs) {
            let e = e as f32;
            for m in 0..SKETCH {
                o[m] += e * r[m];
            }
        }
    }
    (out, signs.into_iter().flatten().collect())
}

/// Optimises the tile of `base`: `TILE * TILE` keys, row-major.
pub fn optimise(base: Base, p: &Params) -> (Vec<u32>, Report) {
    assert!(p.edges.is_multiple_of(8) && p.pool >= PIXELS && (1..=8).contains(&p.levels));
    let mut rng = Rng::new(p.seed ^ (base as u64 + 1).wrapping_mul(0xd1b5_4a32_d192_ed03));
    let keys: Vec<u32> = (0..p.pool).map(|_| (rng.next_u64() >> 32) as u32).collect();
    let line_weights: Vec<f64> = (0..p.levels)
        .map(|l| {
            let last = p.line_weights.last().copied().unwrap_or(0.0);
            p.line_weights.get(l).copied().unwrap_or(last)
        })
        .collect();
    let edges: Vec<Edge> = if line_weights.iter().any(|&w| w > 0.0) {
        Edge::grid(p.edges / p.line_offsets, p.line_offsets)
    } else {
        (0..p.edges).map(|k| Edge::lattice(k, p.edges)).collect()
    };
    let pool = Pool::new(base, &keys, &edges, p.levels, &p.weights);
    let sketch = project(&pool, &mut rng);
    let kernel = Kernel::lines(SIGMA, &edges, p.line_offsets, &line_weights);
    let spans = vec![Span {
        kernel,
        levels: 0..pool.levels,
    }];
    let mut s = State::guided(&pool, spans, (0..PIXELS).collect(), sketch);
    let before = s.ratios();
    let (mut accepted, mut replaced) = (0, 0);

    // Guided sweeps: every pixel, in a random order, takes the best pool key it can find.
    let mut order: Vec<usize> = (0..PIXELS).collect();
    for _ in 0..p.sweeps {
        for k in (1..PIXELS).rev() {
            order.swap(k, rng.below(k + 1));
        }
        for &a in &order {
            if let Some(j) = s.best_replacement(a, 0.0) {
                s.apply_replace(a, j);
                accepted += 1;
                replaced += 1;
            }
        }
    }

    // Random proposals (swaps and replacements) under a falling threshold. |e|^2 of a key is
    // `dim` on average (unit RMS per level).
    let t0 = p.threshold * pool.dim as f64;
    let total = p.rounds * PIXELS;
    for step in 0..total {
        let threshold = (t0 * (1.0 - step as f64 / total as f64)) as f32;
        let a = rng.below(PIXELS);
        if rng.next_u64() >> 63 == 0 {
            let b = rng.below(PIXELS);
            if b == a || s.swap_delta(a, b) >= threshold {
                continue;
            }
            s.apply_swap(a, b);
        } else {
            let j = rng.below(p.pool);
            if s.used[j] || s.replace_delta(a, j) >= threshold {
                continue;
            }
            s.apply_replace(a, j);
            replaced += 1;
        }
        accepted += 1;
    }
    s.recompute_field();
    let after = s.ratios();
    let tile = s.tile.iter().map(|&j| keys[j]).collect();
    (
        tile,
        Report {
            before,
            after,
            accepted,
            replaced,
        },
    )
}
