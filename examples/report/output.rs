//! Terminal tables, the CSV files and the markdown tables.

use crate::run::SceneResult;
use std::fmt::Write as _;
use std::io;
use std::path::Path;

/// The exact header of `results.csv`.
pub const CSV_HEADER: &str = "scene,sampler,warp,spp,mse,ns_per_sample";

/// Index of a sample count in the results, if it was run.
fn at(result: &SceneResult, spp: usize) -> Option<usize> {
    result.spps.iter().position(|&n| n == spp)
}

/// The two sample counts the tables show: 16 and 256 when run, else the first and last.
fn shown(result: &SceneResult) -> (usize, usize) {
    let lo = at(result, 16).unwrap_or(0);
    let hi = at(result, 256).unwrap_or(result.spps.len() - 1);
    (lo, hi)
}

/// Largest relative standard error of any MSE figure of the scene.
pub fn worst_rel_se(result: &SceneResult) -> f64 {
    result
        .rows
        .iter()
        .flat_map(|r| r.stats.iter().map(|s| s.mse_rel_se()))
        .fold(0.0, f64::max)
}

fn sci(x: f64) -> String {
    if x.is_finite() && x > 0.0 {
        format!("{x:.2e}")
    } else {
        "-".into()
    }
}

fn fixed(x: f64) -> String {
    if !x.is_finite() {
        return "-".into();
    }
    let digits = if x >= 100.0 {
        0
    } else if x >= 10.0 {
        1
    } else if x >= 1.0 {
        2
    } else {
        // Three significant digits.
        (2 - x.log10().floor() as i32).clamp(2, 9) as usize
    };
    format!("{x:.digits$}")
}

/// One table as rows of cells (header first).
fn cells(result: &SceneResult) -> Vec<Vec<String>> {
    let (lo, hi) = shown(result);
    let (nlo, nhi) = (result.spps[lo], result.spps[hi]);
    let mut t = vec![vec![
        "sampler".to_string(),
        "warp".to_string(),
        format!("MSE x1000 @{nlo}"),
        format!("MSE x1000 @{nhi}"),
        "rate".to_string(),
        format!("ns/sample @{nhi}"),
        format!("MSE x ns/pixel @{nhi}"),
    ]];
    for r in &result.rows {
        let warp = match r.alias_of {
            Some(s) => format!("{} (= {})", r.warp, s.name()),
            None => r.warp.to_string(),
        };
        t.push(vec![
            r.sampler.name().to_string(),
            warp,
            fixed(1000.0 * r.mse(lo)),
            fixed(1000.0 * r.mse(hi)),
            format!("{:.2}", r.rate(&result.spps)),
            fixed(r.ns[hi]),
            sci(r.mse(hi) * r.ns[hi] * nhi as f64),
        ]);
    }
    t
}

fn caption(result: &SceneResult) -> String {
    format!(
        "{}; {} pixels ({:.0}% in penumbra), MSE relative standard error <= {:.1}%",
        result.description,
        result.pixels,
        100.0 * result.penumbra,
        100.0 * worst_rel_se(result)
    )
}

/// The terminal table of one scene.
pub fn terminal(result: &SceneResult) -> String {
    let t = cells(result);
    let widths: Vec<usize> = (0..t[0].len())
        .map(|c| t.iter().map(|r| r[c].chars().count()).max().unwrap_or(0))
        .collect();
    let mut s = format!("\n{}: {}\n", result.scene, caption(result));
    for (i, r) in t.iter().enumerate() {
        for (c, cell) in r.iter().enumerate() {
            if c < 2 {
                let _ = write!(s, "{cell:<w$}  ", w = widths[c]);
            } else {
                let _ = write!(s, "{cell:>w$}  ", w = widths[c]);
            }
        }
        s.push('\n');
        if i == 0 {
            let _ = writeln!(s, "{}", "-".repeat(widths.iter().map(|w| w + 2).sum()));
        }
    }
    s
}

/// The markdown table of one scene, with its caption.
pub fn markdown(result: &SceneResult) -> String {
    let t = cells(result);
    let mut s = format!("**{}** — {}\n\n", result.scene, caption(result));
    for (i, r) in t.iter().enumerate() {
        let _ = writeln!(s, "| {} |", r.join(" | "));
        if i == 0 {
            let _ = writeln!(
                s,
                "|{}",
                r.iter()
                    .enumerate()
                    .map(|(c, _)| if c < 2 { "---|" } else { "---:|" })
                    .collect::<String>()
            );
        }
    }
    s
}

/// One table for all scenes: MSE x1000 at 256 samples per pixel (or the largest count run
/// below it) per warp and sampler, with pmj02bn's convergence rate and ns per sample.
pub fn summary_markdown(results: &[SceneResult]) -> String {
    let mut s = String::new();
    let Some(first) = results.first() else {
        return s;
    };
    let k = at(first, 256).unwrap_or(first.spps.len() - 1);
    let n = first.spps[k];
    let _ = writeln!(
        s,
        "| scene | warp | random | stratified | pmj02bn | rate (pmj02bn) | ns/sample (pmj02bn) |"
    );
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|---:|");
    for res in results {
        let k = at(res, n).unwrap_or(res.spps.len() - 1);
        let mut warps: Vec<&str> = Vec::new();
        for r in &res.rows {
            if !warps.contains(&r.warp) {
                warps.push(r.warp);
            }
        }
        for w in warps {
            let get = |sampler| res.row(sampler, w);
            let cell = |sampler| get(sampler).map_or("-".to_string(), |r| fixed(1000.0 * r.mse(k)));
            let p = get(crate::samplers::Sampler::Pmj02bn);
            let _ = writeln!(
                s,
                "| {} | {w} | {} | {} | {} | {} | {} |",
                res.scene,
                cell(crate::samplers::Sampler::Random),
                cell(crate::samplers::Sampler::Stratified),
                cell(crate::samplers::Sampler::Pmj02bn),
                p.map_or("-".to_string(), |r| format!("{:.2}", r.rate(&res.spps))),
                p.map_or("-".to_string(), |r| fixed(r.ns[k])),
            );
        }
    }
    let _ = writeln!(s, "\nMSE x1000 at {n} samples per pixel.");
    s
}

/// `results.csv`: one row per scene, combination and sample count.
pub fn csv(results: &[SceneResult]) -> String {
    let mut s = format!("{CSV_HEADER}\n");
    for res in results {
        for r in &res.rows {
            for (k, &spp) in res.spps.iter().enumerate() {
                let _ = writeln!(
                    s,
                    "{},{},{},{},{:.6e},{:.3}",
                    res.scene,
                    r.sampler.name(),
                    r.warp,
                    spp,
                    r.mse(k),
                    r.ns[k]
                );
            }
        }
    }
    s
}

/// `details.csv`: the same rows with the statistics behind them.
pub fn details_csv(results: &[SceneResult]) -> String {
    let mut s = String::from(
        "scene,sampler,warp,spp,mse,ns_per_sample,pixels,mse_rel_se,mean_error,bias_z,same_as\n",
    );
    for res in results {
        for r in &res.rows {
            for (k, &spp) in res.spps.iter().enumerate() {
                let st = &r.stats[k];
                let _ = writeln!(
                    s,
                    "{},{},{},{},{:.6e},{:.3},{},{:.4},{:.4e},{:.3},{}",
                    res.scene,
                    r.sampler.name(),
                    r.warp,
                    spp,
                    st.mse(),
                    r.ns[k],
                    st.n,
                    st.mse_rel_se(),
                    st.sum / st.n as f64,
                    st.bias_z(),
                    r.alias_of.map(|a| a.name()).unwrap_or("")
                );
            }
        }
    }
    s
}

pub fn write(path: &Path, text: &str) -> io::Result<()> {
    std::fs::write(path, text)
}
