//! The environment-map layouts under two orientations of each map.
//!
//! The report's env-map scenes average 8 rotations of every map (pixel `i` sees rotation
//! `i % 8`, rotation 0 the map as authored). The source talk's setting is the map as
//! authored: the sun in the upper half, the horizon on the equator, where photographers and
//! sky models put them, and so along a row of the lat-long image. This study runs the same
//! pixels, samples and estimators ([`EnvView::value`] through `Scene::evaluate`) twice:
//!
//! - **authored**: every pixel sees rotation 0;
//! - **rotated**: every pixel sees its own rotation (the report's scenes; its rotation-0
//!   pixels are the authored run's, sample for sample).
//!
//! For each scene class, sampler, sample count (16 and 256) and the four plain warps it keeps
//! every pixel's error, so that the equal-area / lat-long MSE ratio of each distribution comes
//! with a paired standard error (delta method on the two means of squared errors, their
//! covariance included: the warps share the sampler's points). Classes combine by the
//! geometric mean of their ratios (standard error `sqrt(sum se_k^2) / K` on the log scale,
//! classes taken as independent).
//!
//! The variance split ([`env_split`]) runs per orientation too, with the jittered grid's own
//! prediction: `N Var` of a `k x k` jittered grid is the mean within-cell variance of the
//! warped integrand (`within_cells`), against `Var` for random points and the both-axes part
//! `Var_01` for (0,2) points.
//!
//! Outputs: `envmap_orientation.csv` (one row per class, orientation, sampler, warp and
//! count), `envmap_orientation_split.csv` (the split per class, layout and orientation) and
//! `envmap_orientation.md` (the tables `docs/REPORT.md` quotes).

use crate::env_split::{self, Split};
use crate::envscene::EnvView;
use crate::run::{self, Scene, Scratch};
use crate::samplers::{SAMPLERS, Sampler};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// The sample counts of the study.
pub const SPPS: [usize; 2] = [16, 256];
/// The plain warps (indices `0..4` of `envscene::WARPS`).
pub const WARPS: [&str; 4] = [
    "marginal_equirect",
    "hierarchical_equirect",
    "marginal_equal_area",
    "hierarchical_equal_area",
];
pub const ORIENTATIONS: [&str; 2] = ["authored", "rotated"];
/// Errors kept per pixel.
const PER_PIXEL: usize = ORIENTATIONS.len() * SAMPLERS.len() * SPPS.len() * WARPS.len();

/// Where `(orientation, sampler, count, warp)` lies in a pixel's errors.
pub fn slot(o: usize, sampler: Sampler, k: usize, w: usize) -> usize {
    ((o * SAMPLERS.len() + sampler.index()) * SPPS.len() + k) * WARPS.len() + w
}

/// One scene class's errors `E_N - E`, per pixel, in pixel order.
#[derive(Clone, Debug)]
pub struct ClassErrors {
    pub scene: String,
    /// `procedural` or `PFM` (the real maps and `--envmap` files).
    pub group: &'static str,
    pub lit: bool,
    pub pixels: usize,
    pub rotations: usize,
    /// `errors[i * PER_PIXEL + slot(..)]`.
    pub errors: Vec<f64>,
}

/// A mean of squared errors with its relative standard error.
#[derive(Clone, Copy, Debug, Default)]
pub struct Mse {
    pub mse: f64,
    pub rel_se: f64,
}

/// A ratio with its relative standard error.
#[derive(Clone, Copy, Debug, Default)]
pub struct Ratio {
    pub ratio: f64,
    pub rel_se: f64,
}

impl ClassErrors {
    pub fn error(&self, pixel: usize, o: usize, sampler: Sampler, k: usize, w: usize) -> f64 {
        self.errors[pixel * PER_PIXEL + slot(o, sampler, k, w)]
    }

    fn squares(&self, o: usize, sampler: Sampler, k: usize, w: usize) -> Vec<f64> {
        (0..self.pixels)
            .map(|i| self.error(i, o, sampler, k, w).powi(2))
            .collect()
    }

    pub fn mse(&self, o: usize, sampler: Sampler, k: usize, w: usize) -> Mse {
        let a = self.squares(o, sampler, k, w);
        let n = a.len() as f64;
        let m = a.iter().sum::<f64>() / n;
        let var = a.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0);
        Mse {
            mse: m,
            rel_se: (var / n).sqrt() / m,
        }
    }

    /// The MSE of warp `num` over warp `den`'s on the same pixels and points, with the
    /// paired (delta-method) relative standard error.
    pub fn ratio(&self, o: usize, sampler: Sampler, k: usize, num: usize, den: usize) -> Ratio {
        let (a, b) = (
            self.squares(o, sampler, k, num),
            self.squares(o, sampler, k, den),
        );
        let n = a.len() as f64;
        let (ma, mb) = (a.iter().sum::<f64>() / n, b.iter().sum::<f64>() / n);
        let (mut vaa, mut vbb, mut vab) = (0.0, 0.0, 0.0);
        for (x, y) in a.iter().zip(&b) {
            vaa += (x - ma) * (x - ma);
            vbb += (y - mb) * (y - mb);
            vab += (x - ma) * (y - mb);
        }
        let (vaa, vbb, vab) = (vaa / (n - 1.0), vbb / (n - 1.0), vab / (n - 1.0));
        let rel_var = (vaa / (ma * ma) + vbb / (mb * mb) - 2.0 * vab / (ma * mb)) / n;
        Ratio {
            ratio: ma / mb,
            rel_se: rel_var.max(0.0).sqrt(),
        }
    }

    /// Equal-area over lat-long for the distribution of warp `w` (0 marginal, 1
    /// hierarchical).
    pub fn ea_ll(&self, o: usize, sampler: Sampler, k: usize, dist: usize) -> Ratio {
        self.ratio(o, sampler, k, dist + 2, dist)
    }
}

/// The errors of `view`'s first `pixels` pixels under both orientations (see the module
/// docs), on `threads` threads; the figures do not depend on the thread count.
pub fn measure(view: &EnvView, group: &'static str, pixels: usize, threads: usize) -> ClassErrors {
    let name = view.name();
    let rc = view.rotation_count();
    let errors = Mutex::new(vec![0.0f64; pixels * PER_PIXEL]);
    let next = AtomicUsize::new(0);
    let chunk = 16;
    std::thread::scope(|sc| {
        for _ in 0..threads.max(1) {
            sc.spawn(|| {
                let mut s = Scratch::default();
                let mut local = vec![0.0f64; chunk * PER_PIXEL];
                loop {
                    let first = next.fetch_add(chunk, Ordering::Relaxed);
                    if first >= pixels {
                        break;
                    }
                    let last = (first + chunk).min(pixels);
                    for i in first..last {
                        let own = i % rc;
                        let authored = view.pixel_at(i as u64, 0, true);
                        let rotated = if own == 0 {
                            authored.clone()
                        } else {
                            view.pixel_at(i as u64, own, true)
                        };
                        let out = &mut local[(i - first) * PER_PIXEL..(i - first + 1) * PER_PIXEL];
                        for (o, px) in [&authored, &rotated].into_iter().enumerate() {
                            for (k, &spp) in SPPS.iter().enumerate() {
                                for sampler in SAMPLERS {
                                    let seed = run::seed(&name, i as u64, spp, sampler);
                                    for w in 0..WARPS.len() {
                                        view.draw_for(px, w, sampler, spp, seed, &mut s);
                                        let est = view.evaluate(px, w, spp, &s);
                                        out[slot(o, sampler, k, w)] = est - view.reference(px, w);
                                    }
                                }
                            }
                        }
                    }
                    let mut all = errors.lock().unwrap_or_else(|e| e.into_inner());
                    all[first * PER_PIXEL..last * PER_PIXEL]
                        .copy_from_slice(&local[..(last - first) * PER_PIXEL]);
                }
            });
        }
    });
    ClassErrors {
        scene: name,
        group,
        lit: view.lit,
        pixels,
        rotations: rc,
        errors: errors.into_inner().unwrap_or_else(|e| e.into_inner()),
    }
}

/// The variance split of one class under both orientations: `[authored, rotated]`, each
/// `[lat-long, equal-area]`.
#[derive(Clone, Debug)]
pub struct ClassSplit {
    pub scene: String,
    pub group: &'static str,
    pub lit: bool,
    pub splits: [[Split; 2]; 2],
}

pub fn split(
    view: &EnvView,
    group: &'static str,
    pixels: usize,
    grid: usize,
    threads: usize,
) -> ClassSplit {
    ClassSplit {
        scene: view.name(),
        group,
        lit: view.lit,
        splits: [
            env_split::split_at(view, pixels, grid, threads, Some(0)),
            env_split::split_at(view, pixels, grid, threads, None),
        ],
    }
}

/// `envmap_orientation.csv`: per class, orientation, sampler, warp and count, the MSE and
/// its relative standard error; on the equal-area rows also the MSE over the same
/// distribution's lat-long row (`ea_ll`) and its paired relative standard error.
pub fn csv(classes: &[ClassErrors]) -> String {
    let mut out = String::from(
        "scene,orientation,sampler,warp,spp,pixels,rotations,mse,mse_rel_se,ea_ll,ea_ll_rel_se\n",
    );
    for c in classes {
        for (o, orient) in ORIENTATIONS.iter().enumerate() {
            for sampler in SAMPLERS {
                for (w, warp) in WARPS.iter().enumerate() {
                    for (k, spp) in SPPS.iter().enumerate() {
                        let m = c.mse(o, sampler, k, w);
                        let ratio = if w >= 2 {
                            let r = c.ea_ll(o, sampler, k, w - 2);
                            format!("{:.4},{:.4}", r.ratio, r.rel_se)
                        } else {
                            ",".into()
                        };
                        out += &format!(
                            "{},{orient},{},{warp},{spp},{},{},{:.6e},{:.4},{ratio}\n",
                            c.scene,
                            sampler.name(),
                            c.pixels,
                            c.rotations,
                            m.mse,
                            m.rel_se,
                        );
                    }
                }
            }
        }
    }
    out
}

/// `envmap_orientation_split.csv`: the split of each class, orientation and hierarchical
/// layout (sums over pixels, as `variance_split.csv`), with the jittered grid's `N Var`.
pub fn split_csv(splits: &[ClassSplit]) -> String {
    let mut out = String::from(
        "scene,orientation,warp,pixels,var,var_u0,var_u1,var_both,var_jitter16,var_jitter256\n",
    );
    for c in splits {
        for (o, orient) in ORIENTATIONS.iter().enumerate() {
            for s in &c.splits[o] {
                out += &format!(
                    "{},{orient},{},{:.6e},{:.6e}\n",
                    c.scene,
                    s.csv_columns(),
                    s.var_strat16,
                    s.var_strat256
                );
            }
        }
    }
    out
}

/// The geometric mean of ratios with its relative standard error (`sqrt(sum se^2) / K` on
/// the log scale).
pub fn geo_mean(ratios: &[Ratio]) -> Option<Ratio> {
    if ratios.is_empty() || ratios.iter().any(|r| r.ratio.is_nan() || r.ratio <= 0.0) {
        return None;
    }
    let k = ratios.len() as f64;
    Some(Ratio {
        ratio: (ratios.iter().map(|r| r.ratio.ln()).sum::<f64>() / k).exp(),
        rel_se: ratios
            .iter()
            .map(|r| r.rel_se * r.rel_se)
            .sum::<f64>()
            .sqrt()
            / k,
    })
}

/// `1.13 ± 0.03` (the standard error in the ratio's units).
pub fn cell(r: Option<Ratio>) -> String {
    r.map_or("-".into(), |r| {
        format!("{:.2} ± {:.2}", r.ratio, r.ratio * r.rel_se)
    })
}

/// The groups of classes the summary combines.
fn groups(classes: &[ClassErrors]) -> Vec<&'static str> {
    let mut g: Vec<&'static str> = Vec::new();
    for c in classes {
        if !g.contains(&c.group) {
            g.push(c.group);
        }
    }
    g
}

/// The samplers of the summary table, in this order.
pub const SUMMARY_SAMPLERS: [Sampler; 4] = [
    Sampler::Stratified,
    Sampler::Random,
    Sampler::Pmj02bn,
    Sampler::SobolOwen,
];

/// The geometric mean of `ea_ll` over the classes of `group` (all when `None`).
pub fn group_ratio(
    classes: &[ClassErrors],
    group: Option<&str>,
    o: usize,
    sampler: Sampler,
    k: usize,
    dist: usize,
) -> Option<Ratio> {
    let r: Vec<Ratio> = classes
        .iter()
        .filter(|c| group.is_none_or(|g| c.group == g))
        .map(|c| c.ea_ll(o, sampler, k, dist))
        .collect();
    geo_mean(&r)
}

/// `envmap_orientation.md`: the equal-area / lat-long ratios per orientation (summary and per
/// class), and the variance split per layout and orientation.
pub fn markdown(classes: &[ClassErrors], splits: &[ClassSplit], grid: usize) -> String {
    let groups = groups(classes);
    let describe: Vec<String> = groups
        .iter()
        .map(|g| {
            let cs: Vec<&ClassErrors> = classes.iter().filter(|c| c.group == *g).collect();
            let pixels: std::collections::BTreeSet<usize> = cs.iter().map(|c| c.pixels).collect();
            format!(
                "{g}: {} classes, {} pixels each",
                cs.len(),
                pixels
                    .iter()
                    .map(|p| p.to_string())
                    .collect::<Vec<_>>()
                    .join("/")
            )
        })
        .collect();
    let rotations = classes.first().map_or(0, |c| c.rotations);
    let mut out = format!(
        "Equal-area / lat-long MSE ratio of each distribution, per orientation of the maps: \
         **authored** (every pixel sees the map as authored: sun and horizon where the \
         photographer or the sky model put them) and **rotated** (pixel `i` sees rotation \
         `i mod {rotations}`, the report's scenes). Geometric mean over the classes of each \
         group ({}), ± its standard error (paired per class, classes independent). Below 1: \
         equal-area wins. See `report/src/orientation.rs`.\n\n",
        describe.join("; ")
    );
    let mut header = String::from("| sampler | spp |");
    let mut rule = String::from("|---|---:|");
    for dist in ["hierarchical", "marginal"] {
        for g in &groups {
            for orient in ORIENTATIONS {
                header += &format!(" {dist}, {g}, {orient} |");
                rule += "---:|";
            }
        }
    }
    out += &format!("{header}\n{rule}\n");
    for sampler in SUMMARY_SAMPLERS {
        for (k, spp) in SPPS.iter().enumerate() {
            out += &format!("| `{}` | {spp} |", sampler.name());
            for dist in [1, 0] {
                for g in &groups {
                    for o in 0..ORIENTATIONS.len() {
                        out += &format!(
                            " {} |",
                            cell(group_ratio(classes, Some(g), o, sampler, k, dist))
                        );
                    }
                }
            }
            out += "\n";
        }
    }
    // Per class, hierarchical warps.
    let cols: [(Sampler, usize); 4] = [
        (Sampler::Stratified, 0),
        (Sampler::Stratified, 1),
        (Sampler::Pmj02bn, 1),
        (Sampler::Random, 0),
    ];
    out += "\nPer class, hierarchical warps (equal-area / lat-long, authored | rotated):\n\n| scene | pixels |";
    for (s, k) in cols {
        out += &format!(" `{}` {} authored | rotated |", s.name(), SPPS[k]);
    }
    out += &format!("\n|---|---:|{}\n", "---:|---:|".repeat(cols.len()));
    for c in classes {
        out += &format!("| {} | {} |", c.scene, c.pixels);
        for (s, k) in cols {
            for o in 0..ORIENTATIONS.len() {
                out += &format!(" {} |", cell(Some(c.ea_ll(o, s, k, 1))));
            }
        }
        out += "\n";
    }
    if splits.is_empty() {
        return out;
    }
    // The split per layout and orientation, per group and pixel class.
    let px = splits[0].splits[0][0].pixels;
    out += &format!(
        "\nVariance split of the hierarchical warps' integrand `g = L cos / p` over the sample \
         square, per layout and orientation ({grid} x {grid} midpoints, {px} pixels per \
         class; mean over the classes of the shares, geometric mean of the ratios): the \
         shares of `Var` along `u0` alone, `u1` alone and both axes; the equal-area / \
         lat-long ratio of `Var` (random points), of the jittered grid's `N Var` at 16 and \
         256 points (mean within-cell variance, 4 x 4 and 16 x 16 cells) and of `Var_01` \
         ((0,2) points), next to the measured MSE ratios.\n\n\
         | classes | orientation | lat-long u0 / u1 / both | equal-area u0 / u1 / both | \
         `Var` EA/LL | jittered 16 EA/LL | measured `stratified` 16 | jittered 256 EA/LL | \
         measured `stratified` 256 | `Var_01` EA/LL | measured `pmj02bn` 256 |\n\
         |---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n"
    );
    for g in &groups {
        for lit in [false, true] {
            let cs: Vec<&ClassSplit> = splits
                .iter()
                .filter(|c| c.group == *g && c.lit == lit)
                .collect();
            if cs.is_empty() {
                continue;
            }
            let ce: Vec<&ClassErrors> = classes
                .iter()
                .filter(|c| c.group == *g && c.lit == lit)
                .collect();
            for (o, orient) in ORIENTATIONS.iter().enumerate() {
                let n = cs.len() as f64;
                let shares = |l: usize| {
                    let f = |pick: fn(&Split) -> f64| {
                        cs.iter()
                            .map(|c| pick(&c.splits[o][l]) / c.splits[o][l].var)
                            .sum::<f64>()
                            / n
                    };
                    format!(
                        "{:.2} / {:.2} / {:.2}",
                        f(|s| s.var_u0),
                        f(|s| s.var_u1),
                        f(|s| s.var_both)
                    )
                };
                let pred = |pick: fn(&Split) -> f64| {
                    let logs: f64 = cs
                        .iter()
                        .map(|c| (pick(&c.splits[o][1]) / pick(&c.splits[o][0])).ln())
                        .sum();
                    format!("{:.2}", (logs / n).exp())
                };
                let meas = |sampler: Sampler, k: usize| {
                    let r: Vec<Ratio> = ce.iter().map(|c| c.ea_ll(o, sampler, k, 1)).collect();
                    cell(geo_mean(&r))
                };
                out += &format!(
                    "| {g}{} | {orient} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n",
                    if lit { ", lit" } else { ", occluded" },
                    shares(0),
                    shares(1),
                    pred(|s| s.var),
                    pred(|s| s.var_strat16),
                    meas(Sampler::Stratified, 0),
                    pred(|s| s.var_strat256),
                    meas(Sampler::Stratified, 1),
                    pred(|s| s.var_both),
                    meas(Sampler::Pmj02bn, 1),
                );
            }
        }
    }
    out
}
