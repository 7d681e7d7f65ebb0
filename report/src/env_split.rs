//! The variance split of the environment-map integrands: why the equal-area
//! octahedral layout loses to lat-long with Owen-scrambled (0,2) points.
//!
//! For one pixel and one warp, the integrand seen in the sample square is
//! `g(u0, u1) = L_t max(0, n . w) [m . w >= 0] / p(w)` with `w` the direction the warp puts
//! `u` at (the estimator's term, [`EnvView::value`]). Its ANOVA decomposition (Hoeffding;
//! Owen 2013, "Monte Carlo theory, methods and examples", appendix A) splits the variance
//!
//! ```text
//! Var g = Var_0 + Var_1 + Var_01,  Var_0 = Var E[g | u0],  Var_1 = Var E[g | u1],
//! ```
//!
//! into the parts that vary along one sample axis at a time and the remainder `Var_01`
//! that depends on both. Random points see all of `Var g`; a (0,2)-net integrates the
//! one-axis parts of a smooth-enough integrand almost exactly (each 1D projection is
//! stratified into `N` intervals), so its error comes mostly from `Var_01`. The share
//! `Var_01 / Var g` of a layout, and the ratio of `Var_01` between layouts, predict how the
//! layouts rank under pmj02bn and Sobol'.
//!
//! **Method.** `grid x grid` midpoints of the sample square through the scene's own
//! hierarchical distributions (`warp_points`, the report's code path), per pixel; the sums
//! of the per-pixel variances over `pixels` pixels of each class (MSE is a mean over pixels,
//! so the variances add). The midpoint rule resolves the texel and occluder edges to
//! `1 / grid` of the square: the shares are estimates, stated to two digits.

use crate::envscene::{EnvScene, EnvView};
use crate::run::{Scene, SceneResult, Scratch};
use crate::samplers::Sampler;

/// The hierarchical warps, lat-long then equal-area (indices into `envscene::WARPS`).
const WARPS: [(usize, &str); 2] = [(1, "hierarchical_equirect"), (3, "hierarchical_equal_area")];

/// The split of one scene class and warp, summed over pixels.
#[derive(Clone, Debug, Default)]
pub struct Split {
    pub scene: String,
    pub warp: &'static str,
    pub pixels: usize,
    pub var: f64,
    pub var_u0: f64,
    pub var_u1: f64,
    pub var_both: f64,
    /// `N Var` of a jittered `k x k` grid (`N = k^2` points, one per cell): the mean over the
    /// cells of the variance of `g` within the cell, for `k = 4` (16 spp) and `k = 16` (256
    /// spp). Random points have `N Var = var`; the ratio is the grid's gain.
    pub var_strat16: f64,
    pub var_strat256: f64,
}

impl Split {
    /// The CSV columns `warp,pixels,var,var_u0,var_u1,var_both`.
    pub fn csv_columns(&self) -> String {
        format!(
            "{},{},{:.6e},{:.6e},{:.6e},{:.6e}",
            self.warp, self.pixels, self.var, self.var_u0, self.var_u1, self.var_both
        )
    }

    pub fn share_both(&self) -> f64 {
        if self.var > 0.0 {
            self.var_both / self.var
        } else {
            0.0
        }
    }
}

/// The ANOVA of one `n x n` table of values `g[b * n + a]` (`a` along `u0`): `(Var, Var_0,
/// Var_1, Var_01)`.
pub fn anova(g: &[f64], n: usize) -> (f64, f64, f64, f64) {
    let nn = (n * n) as f64;
    let mean = g.iter().sum::<f64>() / nn;
    let var = g.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / nn;
    let mut var0 = 0.0;
    let mut var1 = 0.0;
    for i in 0..n {
        let m0 = (0..n).map(|b| g[b * n + i]).sum::<f64>() / n as f64; // E[g | u0 = a_i]
        let m1 = g[i * n..(i + 1) * n].iter().sum::<f64>() / n as f64; // E[g | u1 = b_i]
        var0 += (m0 - mean) * (m0 - mean);
        var1 += (m1 - mean) * (m1 - mean);
    }
    let (var0, var1) = (var0 / n as f64, var1 / n as f64);
    (var, var0, var1, (var - var0 - var1).max(0.0))
}

/// The mean over the `k x k` cells of an `n x n` table `g` (`n` a multiple of `k`) of the
/// variance of `g` within the cell: `N Var` of a jittered grid of `N = k^2` points (the
/// stratified estimator's variance is `(1 / N^2) sum_c Var_c`).
pub fn within_cells(g: &[f64], n: usize, k: usize) -> f64 {
    let c = n / k;
    if c == 0 {
        return 0.0;
    }
    let mut acc = 0.0;
    for cy in 0..k {
        for cx in 0..k {
            let vals = (0..c).flat_map(|b| (0..c).map(move |a| (cy * c + b) * n + cx * c + a));
            let mean = vals.clone().map(|i| g[i]).sum::<f64>() / (c * c) as f64;
            acc += vals.map(|i| (g[i] - mean) * (g[i] - mean)).sum::<f64>() / (c * c) as f64;
        }
    }
    acc / (k * k) as f64
}

/// The splits of both hierarchical layouts of `view` over its first `pixels` pixels, each
/// pixel seeing its own rotation of the map (`index % rotation_count`, the report's pixels).
pub fn split(view: &EnvView, pixels: usize, grid: usize, threads: usize) -> [Split; 2] {
    split_at(view, pixels, grid, threads, None)
}

/// [`split`] with every pixel seeing rotation `rotation` (`Some(0)`: the map as authored),
/// or its own (`None`).
pub fn split_at(
    view: &EnvView,
    pixels: usize,
    grid: usize,
    threads: usize,
    rotation: Option<usize>,
) -> [Split; 2] {
    let sums = std::sync::Mutex::new([[0.0f64; 6]; 2]);
    let next = std::sync::atomic::AtomicUsize::new(0);
    std::thread::scope(|sc| {
        for _ in 0..threads.max(1) {
            sc.spawn(|| {
                let mut s = Scratch::default();
                let mut local = [[0.0f64; 6]; 2];
                let mut g = vec![0.0; grid * grid];
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    if i >= pixels {
                        break;
                    }
                    let own = i % view.rotation_count();
                    let px = view.pixel_at(i as u64, rotation.unwrap_or(own), false);
                    for (l, &(warp, _)) in WARPS.iter().enumerate() {
                        s.reserve(grid * grid);
                        for b in 0..grid {
                            for a in 0..grid {
                                s.points[b * grid + a] = [
                                    ((a as f64 + 0.5) / grid as f64) as f32,
                                    ((b as f64 + 0.5) / grid as f64) as f32,
                                ];
                            }
                        }
                        view.warp_points(px.rotation, warp, grid * grid, &mut s);
                        for (k, v) in g.iter_mut().enumerate() {
                            *v = view.value(&px, warp, k, &s);
                        }
                        let (v, v0, v1, v01) = anova(&g, grid);
                        let (s16, s256) = (within_cells(&g, grid, 4), within_cells(&g, grid, 16));
                        for (acc, x) in local[l].iter_mut().zip([v, v0, v1, v01, s16, s256]) {
                            *acc += x;
                        }
                    }
                }
                let mut t = sums.lock().unwrap();
                for (a, b) in t.iter_mut().flatten().zip(local.iter().flatten()) {
                    *a += b;
                }
            });
        }
    });
    let sums = sums.into_inner().unwrap();
    [0, 1].map(|l| Split {
        scene: view.name(),
        warp: WARPS[l].1,
        pixels,
        var: sums[l][0],
        var_u0: sums[l][1],
        var_u1: sums[l][2],
        var_both: sums[l][3],
        var_strat16: sums[l][4],
        var_strat256: sums[l][5],
    })
}

/// Measured MSE of `sampler` + `warp` at the largest sample count of `scene`'s result.
fn measured(results: &[SceneResult], scene: &str, sampler: Sampler, warp: &str) -> Option<f64> {
    let r = results.iter().find(|r| r.scene == scene)?;
    let row = r.row(sampler, warp)?;
    row.stats.last().map(|s| s.mse)
}

/// `variance_split.csv` rows.
pub fn csv(splits: &[Split]) -> String {
    let mut out = String::from("scene,warp,pixels,var,var_u0,var_u1,var_both,share_both\n");
    for s in splits {
        out += &format!("{},{},{:.4}\n", s.scene, s.csv_columns(), s.share_both());
    }
    out
}

/// `variance_split.md`: the shares per layout, and the equal-area / lat-long ratios they
/// predict next to the measured MSE ratios (largest sample count).
pub fn markdown(splits: &[Split], results: &[SceneResult], grid: usize) -> String {
    let spp = results
        .iter()
        .find(|r| r.scene.starts_with("envmap:"))
        .and_then(|r| r.spps.last().copied())
        .unwrap_or(0);
    let mut out = format!(
        "Share of each hierarchical layout's integrand variance that depends on both sample \
         axes (`Var_01 / Var`, {grid} x {grid} midpoints per pixel, summed over pixels; see \
         `report/src/env_split.rs`), and the equal-area / lat-long ratios it predicts: \
         `Var` for random points, `Var_01` for (0,2) points. Measured: MSE ratios at {spp} spp.\n\n\
         | scene | pixels | both-axes share, lat-long | both-axes share, equal-area | \
         predicted EA/LL, random (`Var`) | measured, random | predicted EA/LL, (0,2) (`Var_01`) | \
         measured, pmj02bn | measured, Sobol' (`sobol_owen`) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|\n"
    );
    for pair in splits.chunks_exact(2) {
        let (ll, ea) = (&pair[0], &pair[1]);
        let ratio = |sampler| match (
            measured(results, &ll.scene, sampler, ll.warp),
            measured(results, &ea.scene, sampler, ea.warp),
        ) {
            (Some(a), Some(b)) if a > 0.0 => format!("{:.2}", b / a),
            _ => "—".into(),
        };
        out += &format!(
            "| {} | {} | {:.2} | {:.2} | {:.2} | {} | {:.2} | {} | {} |\n",
            ll.scene,
            ll.pixels,
            ll.share_both(),
            ea.share_both(),
            ea.var / ll.var,
            ratio(Sampler::Random),
            ea.var_both / ll.var_both,
            ratio(Sampler::Pmj02bn),
            ratio(Sampler::SobolOwen),
        );
    }
    out
}

/// Runs the split for both classes of every scene.
pub fn run(scenes: &[&EnvScene], pixels: usize, grid: usize, threads: usize) -> Vec<Split> {
    let mut out = Vec::new();
    for scene in scenes {
        for lit in [false, true] {
            out.extend(split(&scene.view(lit), pixels, grid, threads));
        }
    }
    out
}

/// `envmap_by_sampler.md`: per sampler, each env-map warp's MSE over `hierarchical_equirect`'s
/// (the geometric mean over every environment-map scene and class, rotations averaged
/// within each) at 16 and at the largest sample count, and the warp that is lowest.
pub fn by_sampler_markdown(results: &[SceneResult]) -> String {
    use crate::samplers::SAMPLERS;
    let env: Vec<&SceneResult> = results
        .iter()
        .filter(|r| r.scene.starts_with("envmap:"))
        .collect();
    let Some(first) = env.first() else {
        return String::new();
    };
    let spps: Vec<usize> = [16, *first.spps.last().unwrap_or(&16)]
        .into_iter()
        .filter(|s| first.spps.contains(s))
        .collect::<std::collections::BTreeSet<_>>()
        .into_iter()
        .collect();
    let warps = [
        "marginal_equirect",
        "hierarchical_equirect",
        "marginal_equal_area",
        "hierarchical_equal_area",
    ];
    let mut out = format!(
        "MSE of each warp over `hierarchical_equirect`'s, per sampler: the geometric mean over \
         the {} environment-map scene classes (built-in, real maps, both pixel classes; each \
         averaged over the map's rotations). Below 1: that warp beats lat-long + hierarchical.\n\n\
         | sampler | spp | {} | lowest |\n|---|---:|{}---|\n",
        env.len(),
        warps.join(" | "),
        "---:|".repeat(warps.len())
    );
    for sampler in SAMPLERS {
        for &spp in &spps {
            let Some(k) = first.spps.iter().position(|&s| s == spp) else {
                continue;
            };
            let ratio = |warp: &str| -> Option<f64> {
                let mut logs = Vec::new();
                for r in &env {
                    let base = r.row(sampler, "hierarchical_equirect")?.stats[k].mse;
                    let x = r.row(sampler, warp)?.stats[k].mse;
                    if base > 0.0 && x > 0.0 {
                        logs.push((x / base).ln());
                    }
                }
                (!logs.is_empty()).then(|| (logs.iter().sum::<f64>() / logs.len() as f64).exp())
            };
            let ratios: Vec<Option<f64>> = warps.iter().map(|w| ratio(w)).collect();
            let lowest = warps
                .iter()
                .zip(&ratios)
                .filter_map(|(w, r)| r.map(|r| (w, r)))
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .map(|(w, _)| format!("`{}`", crate::output::warp_api(w)))
                .unwrap_or_default();
            let cells: Vec<String> = ratios
                .iter()
                .map(|r| r.map_or("-".into(), |r| format!("{r:.2}")))
                .collect();
            out += &format!(
                "| `{}` | {spp} | {} | {lowest} |\n",
                sampler.api_name(),
                cells.join(" | ")
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::anova;

    /// An additive table has no both-axes part; a product of two centred factors is all
    /// both-axes part; the parts add up to the variance.
    #[test]
    fn anova_separates_additive_and_interaction_parts() {
        let n = 16;
        let f = |a: usize| (a as f64 + 0.5) / n as f64 - 0.5;
        let add: Vec<f64> = (0..n * n).map(|k| f(k % n) + 2.0 * f(k / n)).collect();
        let (v, v0, v1, v01) = anova(&add, n);
        assert!(v01 < 1e-12 * v, "{v01} of {v}");
        assert!((v1 / v0 - 4.0).abs() < 1e-9, "{v0} {v1}");
        let prod: Vec<f64> = (0..n * n).map(|k| f(k % n) * f(k / n)).collect();
        let (v, v0, v1, v01) = anova(&prod, n);
        assert!(
            v0 < 1e-12 && v1 < 1e-12 && (v01 - v).abs() < 1e-12 * v,
            "{v} {v0} {v1} {v01}"
        );
    }
}
