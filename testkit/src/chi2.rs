//! Chi-square goodness-of-fit test for warps, reusable by every family.
//!
//! A warp is tested by mapping its output points to an *equal-area parameterization* of the
//! target domain (see [`disk`], [`sphere`], [`triangle`]) and histogramming them over an
//! `nx x ny` grid of that unit square. Because the parameterization preserves area, each cell
//! covers the same area of the domain, and the expected probability of a cell is the integral
//! of the target density over it: `1 / cells` for a uniform target, or
//! [`expected_from_density`] for any other density.
//!
//! Cells whose expected count is below 5 are pooled (smallest first) until every bin expects
//! at least 5, as in Mitsuba 3's `chi2.py`. A sample in a cell of expected probability 0 fails
//! the test outright.
//!
//! Significance: the whole suite holds at most [`FAMILY`] chi-square tests, and each test uses
//! the Sidak-corrected level `1 - (1 - ALPHA)^(1 / FAMILY)`, so the probability that a correct
//! implementation fails *any* of them is at most [`ALPHA`] = 1%. Sample inputs come from fixed
//! seeds, so a run is reproducible: a failure is a real property of that sample, not noise.

/// Suite-wide significance level.
pub const ALPHA: f64 = 0.01;
/// Upper bound on the number of chi-square tests in the whole suite (Sidak family size).
/// Raise it when adding tests beyond it (`tests/*.rs`, `grep -c chi2::check`).
pub const FAMILY: u32 = 128;
/// Default sample count of a chi-square test (the suite's minimum is 10^6).
pub const SAMPLES: usize = 1 << 21;

/// Per-test significance after the Sidak correction over [`FAMILY`] tests.
pub fn per_test_alpha() -> f64 {
    1.0 - (1.0 - ALPHA).powf(1.0 / FAMILY as f64)
}

/// Counts over an `nx x ny` grid of the unit square of an equal-area parameterization.
pub struct Histogram {
    pub nx: usize,
    pub ny: usize,
    pub counts: Vec<u64>,
    /// Points whose parameters fell outside `[0, 1]^2` or were not finite.
    pub outside: u64,
    pub total: u64,
}

impl Histogram {
    pub fn new(nx: usize, ny: usize) -> Self {
        Histogram {
            nx,
            ny,
            counts: vec![0; nx * ny],
            outside: 0,
            total: 0,
        }
    }

    /// Adds one point given by its parameters `s` in `[0, 1]^2` (1.0 counts in the last cell).
    pub fn add(&mut self, s: [f64; 2]) {
        self.total += 1;
        let inside = |x: f64| (0.0..=1.0).contains(&x); // false for NaN
        if !(inside(s[0]) && inside(s[1])) {
            self.outside += 1;
            return;
        }
        let i = ((s[0] * self.nx as f64) as usize).min(self.nx - 1);
        let j = ((s[1] * self.ny as f64) as usize).min(self.ny - 1);
        self.counts[j * self.nx + i] += 1;
    }
}

/// Expected cell probabilities of a uniform target density.
pub fn expected_uniform(nx: usize, ny: usize) -> Vec<f64> {
    vec![1.0 / (nx * ny) as f64; nx * ny]
}

/// Expected cell probabilities of a density given over the parameter square (not necessarily
/// normalized): integrated per cell with an 8x8-point Gauss-Legendre rule, then normalized.
/// Exact for polynomials of degree 15 per axis; for smooth densities at the grid sizes used
/// here the quadrature error is many orders below the test's resolution.
pub fn expected_from_density(nx: usize, ny: usize, density: impl Fn([f64; 2]) -> f64) -> Vec<f64> {
    // Nodes and weights of 8-point Gauss-Legendre on [-1, 1].
    const X: [f64; 4] = [
        0.183_434_642_495_649_8,
        0.525_532_409_916_329,
        0.796_666_477_413_626_7,
        0.960_289_856_497_536_3,
    ];
    const W: [f64; 4] = [
        0.362_683_783_378_362,
        0.313_706_645_877_887_3,
        0.222_381_034_453_374_5,
        0.101_228_536_290_376_3,
    ];
    let nodes: Vec<(f64, f64)> = X
        .iter()
        .zip(W.iter())
        .flat_map(|(&x, &w)| [(-x, w), (x, w)])
        .collect();
    let mut p = vec![0.0; nx * ny];
    for j in 0..ny {
        for i in 0..nx {
            let (x0, y0) = (i as f64 / nx as f64, j as f64 / ny as f64);
            let (hx, hy) = (0.5 / nx as f64, 0.5 / ny as f64);
            let mut acc = 0.0;
            for &(a, wa) in &nodes {
                for &(b, wb) in &nodes {
                    acc += wa * wb * density([x0 + hx * (1.0 + a), y0 + hy * (1.0 + b)]);
                }
            }
            p[j * nx + i] = acc * hx * hy;
        }
    }
    let total: f64 = p.iter().sum();
    p.iter().map(|v| v / total).collect()
}

/// Result of a chi-square test.
#[derive(Debug)]
pub struct Outcome {
    pub statistic: f64,
    pub dof: usize,
    pub p_value: f64,
    pub bins: usize,
}

/// Pools cells to an expected count >= 5, computes the statistic and its p-value.
/// Returns `Err` with a description when a sample fell where the expected probability is 0.
pub fn statistic(hist: &Histogram, expected: &[f64]) -> Result<Outcome, String> {
    assert_eq!(expected.len(), hist.counts.len());
    let n = hist.total as f64;
    if hist.outside > 0 {
        return Err(format!(
            "{} of {} points outside the parameter square",
            hist.outside, hist.total
        ));
    }
    let mut cells: Vec<(f64, u64)> = Vec::with_capacity(expected.len());
    for (k, (&e, &o)) in expected.iter().zip(&hist.counts).enumerate() {
        if e <= 0.0 {
            if o > 0 {
                return Err(format!(
                    "{o} samples in cell {k}, where the expected probability is 0"
                ));
            }
            continue;
        }
        cells.push((e * n, o));
    }
    cells.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap());
    let (mut stat, mut bins) = (0.0, 0usize);
    let (mut pool_e, mut pool_o) = (0.0, 0u64);
    for (e, o) in cells {
        if e < 5.0 || pool_e > 0.0 && pool_e < 5.0 {
            pool_e += e;
            pool_o += o;
            if pool_e >= 5.0 {
                stat += (pool_o as f64 - pool_e).powi(2) / pool_e;
                bins += 1;
                pool_e = 0.0;
                pool_o = 0;
            }
            continue;
        }
        stat += (o as f64 - e).powi(2) / e;
        bins += 1;
    }
    if pool_e > 0.0 {
        // A last pool below 5 joins the statistic anyway (it is tiny).
        stat += (pool_o as f64 - pool_e).powi(2) / pool_e;
        bins += 1;
    }
    let dof = bins - 1;
    let p_value = statrs::function::gamma::gamma_ur(dof as f64 / 2.0, stat / 2.0);
    Ok(Outcome {
        statistic: stat,
        dof,
        p_value,
        bins,
    })
}

/// Runs the test and panics (failing the calling test) when the fit is rejected at the
/// Sidak-corrected level.
pub fn check(name: &str, hist: &Histogram, expected: &[f64]) -> Outcome {
    let alpha = per_test_alpha();
    match statistic(hist, expected) {
        Err(e) => panic!("chi2 {name}: {e}"),
        Ok(out) => {
            eprintln!(
                "chi2 {name}: {} samples, {} bins, statistic {:.1}, dof {}, p = {:.4} (alpha {:.2e})",
                hist.total, out.bins, out.statistic, out.dof, out.p_value, alpha
            );
            assert!(
                out.p_value >= alpha,
                "chi2 {name}: rejected, p = {:.3e} < {alpha:.3e} ({out:?})",
                out.p_value
            );
            out
        }
    }
}

/// The power check: a histogram of a deliberately wrong distribution must be rejected against
/// the uniform expectation of its `nx x ny` bins at the per-test level.
pub fn assert_rejects_uniform(hist: &Histogram, nx: usize, ny: usize) {
    let p = statistic(hist, &expected_uniform(nx, ny)).unwrap().p_value;
    assert!(p < per_test_alpha(), "p = {p}");
}

/// Equal-area parameters of a point of the unit disk: `(r^2, phi / 2 pi)`.
pub fn disk(p: [f32; 2]) -> [f64; 2] {
    let (x, y) = (p[0] as f64, p[1] as f64);
    let phi = y.atan2(x).rem_euclid(std::f64::consts::TAU);
    [x * x + y * y, phi / std::f64::consts::TAU]
}

/// Equal-area parameters of a direction on the unit sphere: `((1 - z) / 2, phi / 2 pi)`
/// (Archimedes: the height is uniform for a uniform sphere). Directions are normalized first.
pub fn sphere(d: [f32; 3]) -> [f64; 2] {
    let (x, y, z) = (d[0] as f64, d[1] as f64, d[2] as f64);
    let len = (x * x + y * y + z * z).sqrt();
    let phi = y.atan2(x).rem_euclid(std::f64::consts::TAU);
    [(1.0 - z / len) / 2.0, phi / std::f64::consts::TAU]
}

/// Equal-area parameters of a point of a triangle given by barycentrics: the inverse of the
/// area-preserving square-root map, `((1 - b0)^2, b1 / (1 - b0))`.
pub fn triangle(b: [f32; 3]) -> [f64; 2] {
    let (b0, b1) = (b[0] as f64, b[1] as f64);
    let s = 1.0 - b0;
    [s * s, if s > 0.0 { b1 / s } else { 0.0 }]
}
