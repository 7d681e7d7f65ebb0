//! Terminal tables, the CSV files and the markdown tables.

use crate::run::{Row, SceneResult};
use crate::samplers::{SAMPLERS, Sampler};
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
        .flat_map(|r| r.stats.iter().map(|s| s.rel_se()))
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
        "{}; {} pixels, MSE relative standard error <= {:.1}%",
        result.description,
        result.pixels,
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
    let _ = write!(s, "| scene | warp |");
    for sampler in SAMPLERS {
        let _ = write!(s, " {} |", sampler.name());
    }
    let _ = writeln!(s, " rate (pmj02bn) | ns/sample (pmj02bn) |");
    let _ = writeln!(s, "|---|---|{}---:|---:|", "---:|".repeat(SAMPLERS.len()));
    for res in results {
        let k = at(res, n).unwrap_or(res.spps.len() - 1);
        for w in warps(res) {
            let get = |sampler| res.row(sampler, w);
            let _ = write!(s, "| {} | {w} |", res.scene);
            for sampler in SAMPLERS {
                let cell = get(sampler).map_or("-".to_string(), |r| fixed(1000.0 * r.mse(k)));
                let _ = write!(s, " {cell} |");
            }
            let p = get(Sampler::Pmj02bn);
            let _ = writeln!(
                s,
                " {} | {} |",
                p.map_or("-".to_string(), |r| format!("{:.2}", r.rate(&res.spps))),
                p.map_or("-".to_string(), |r| fixed(r.ns[k])),
            );
        }
    }
    let _ = writeln!(s, "\nMSE x1000 at {n} samples per pixel.");
    s
}

/// The warps of a scene in row order.
pub fn warps(res: &SceneResult) -> Vec<&'static str> {
    let mut warps: Vec<&'static str> = Vec::new();
    for r in &res.rows {
        if !warps.contains(&r.warp) {
            warps.push(r.warp);
        }
    }
    warps
}

/// Every (scene, row, sample count index) of `results`, in the CSV files' order.
fn entries(results: &[SceneResult]) -> impl Iterator<Item = (&SceneResult, &Row, usize)> {
    results.iter().flat_map(|res| {
        res.rows
            .iter()
            .flat_map(move |r| (0..res.spps.len()).map(move |k| (res, r, k)))
    })
}

/// One line of `results.csv` (the path scenes' rows too, warp `path`), without its newline:
/// the columns of [`CSV_HEADER`].
pub fn csv_line(scene: &str, sampler: &str, warp: &str, spp: usize, mse: f64, ns: f64) -> String {
    format!("{scene},{sampler},{warp},{spp},{mse:.6e},{ns:.3}")
}

fn entry_line(res: &SceneResult, r: &Row, k: usize) -> String {
    csv_line(
        &res.scene,
        r.sampler.name(),
        r.warp,
        res.spps[k],
        r.mse(k),
        r.ns[k],
    )
}

/// `results.csv`: one row per scene, combination and sample count.
pub fn csv(results: &[SceneResult]) -> String {
    let mut s = format!("{CSV_HEADER}\n");
    for (res, r, k) in entries(results) {
        let _ = writeln!(s, "{}", entry_line(res, r, k));
    }
    s
}

/// `details.csv`: the same rows with the statistics behind them.
pub fn details_csv(results: &[SceneResult]) -> String {
    let mut s = format!("{CSV_HEADER},pixels,mse_rel_se,mean_error,bias_z,same_as\n");
    for (res, r, k) in entries(results) {
        let st = &r.stats[k];
        let _ = writeln!(
            s,
            "{},{},{:.4},{:.4e},{:.3},{}",
            entry_line(res, r, k),
            st.n,
            st.rel_se(),
            st.mean,
            st.bias_z(),
            r.alias_of.map(|a| a.name()).unwrap_or("")
        );
    }
    s
}

pub fn write(path: &Path, text: &str) -> io::Result<()> {
    std::fs::write(path, text)
}

/// `page` with every `<!-- generated: report/X.md -->` ... `<!-- end: report/X.md -->` block
/// replaced by the file `dir/report/X.md` (what `report/tests/report.rs` checks): the report's
/// pages quote its generated tables, never a stale copy. Run when the report writes to
/// `docs/report`.
pub fn paste_generated(page: &str, dir: &Path) -> io::Result<String> {
    let mut out = String::new();
    let mut rest = page;
    while let Some(start) = rest.find("<!-- generated: ") {
        let after = &rest[start + "<!-- generated: ".len()..];
        let Some(len) = after.find(" -->") else { break };
        let name = &after[..len];
        let body_start = start + "<!-- generated: ".len() + len + " -->".len();
        let end_marker = format!("<!-- end: {name} -->");
        let Some(end) = rest[body_start..].find(&end_marker) else {
            break;
        };
        let file = std::fs::read_to_string(dir.join(name))?;
        out.push_str(&rest[..body_start]);
        out.push('\n');
        out.push_str(file.trim());
        out.push('\n');
        out.push_str(&end_marker);
        rest = &rest[body_start + end + end_marker.len()..];
    }
    out.push_str(rest);
    Ok(out)
}

/// The functions a renderer calls for a warp of the report (its CSV name otherwise).
pub fn warp_api(warp: &str) -> String {
    let map = [
        ("identity", ""),
        ("polar", "disk::polar"),
        ("concentric", "disk::concentric"),
        ("polar4", "disk::polar4"),
        ("concentric4", "disk::concentric4"),
        (
            "pad_zero",
            "disk::polar, 4th quadrant sample dropped (pad_zero)",
        ),
        ("rejection", "rejection from the square (rejection)"),
        ("uniform", "triangle::uniform"),
        ("sqrt", "triangle::sqrt_map"),
        ("basu_owen", "triangle::basu_owen"),
        ("basu_owen_permuted", "triangle::basu_owen_permuted"),
        (
            "marginal_equirect",
            "envmap::MarginalConditional + sphere::equirect",
        ),
        (
            "hierarchical_equirect",
            "envmap::Hierarchical + sphere::equirect",
        ),
        (
            "marginal_equal_area",
            "envmap::MarginalConditional + sphere::equal_area",
        ),
        (
            "hierarchical_equal_area",
            "envmap::Hierarchical + sphere::equal_area",
        ),
        ("area", "square / triangle::uniform (by area)"),
        (
            "area_basu_owen_permuted",
            "triangle::basu_owen_permuted (by area)",
        ),
        ("solid_angle", "spherical::triangle / spherical::rectangle"),
        (
            "solid_angle_cos",
            "spherical::triangle_cosine / spherical::rectangle_cosine",
        ),
    ];
    match map.iter().find(|(w, _)| *w == warp) {
        Some((_, api)) => api.to_string(),
        None => warp.to_string(),
    }
}

/// [`label`] in API names: `pmj02bn::sample + disk::polar4` (peers marked as peers).
fn api_label(res: &SceneResult, r: &crate::run::Row) -> String {
    let index_driven = res
        .rows
        .iter()
        .any(|o| o.warp == r.warp && o.alias_of.is_some());
    let warp = warp_api(r.warp);
    if index_driven && r.sampler != Sampler::Random {
        format!("`{warp}` (index-driven)")
    } else if warp.is_empty() {
        format!("`{}`", r.sampler.api_name())
    } else {
        format!("`{}` + `{warp}`", r.sampler.api_name())
    }
}

/// The row with the lowest MSE at count index `k`, the rows statistically tied with it (their
/// MSE within two standard errors of the difference, the errors taken as independent), and
/// the cheapest of them all (sampling + warp time per sample).
struct Best<'a> {
    top: &'a crate::run::Row,
    ties: Vec<&'a crate::run::Row>,
    cheapest: &'a crate::run::Row,
}

fn best(res: &SceneResult, k: usize) -> Option<Best<'_>> {
    // The `_mis` rows evaluate the integrand twice per point (a map sample and a BSDF
    // sample): not comparable at equal sample counts, so never "the lowest".
    let rows: Vec<&crate::run::Row> = res
        .rows
        .iter()
        .filter(|r| r.alias_of.is_none() && !r.warp.ends_with("_mis"))
        .collect();
    let top = rows
        .iter()
        .copied()
        .filter(|r| r.mse(k).is_finite())
        .min_by(|a, b| a.mse(k).total_cmp(&b.mse(k)))?;
    let (s0, e0) = (top.mse(k), top.stats[k].rel_se());
    let ties: Vec<&crate::run::Row> = rows
        .iter()
        .copied()
        .filter(|r| !std::ptr::eq(*r, top))
        .filter(|r| {
            let e = (e0 * e0 + r.stats[k].rel_se().powi(2)).sqrt();
            r.mse(k) <= s0 * (1.0 + 2.0 * e)
        })
        .collect();
    let cheapest = std::iter::once(top)
        .chain(ties.iter().copied())
        .filter(|r| r.ns[k].is_finite())
        .min_by(|a, b| a.ns[k].total_cmp(&b.ns[k]))
        .unwrap_or(top);
    Some(Best {
        top,
        ties,
        cheapest,
    })
}

/// `recommendations.md`: per light and pixel class, at 16 and 256 samples per pixel, the
/// sampler x warp with the lowest MSE (in API names), the rows statistically tied with it,
/// and the cheapest of those (the time to draw and warp the samples, native build; a
/// statistically worse row is never recommended for its speed).
pub fn recommendations_markdown(results: &[SceneResult]) -> String {
    let mut s = String::from(
        "| light | pixels | spp | lowest MSE | tied (2 s.e.) | cheapest of these (sampling + warp) |\n|---|---|---:|---|---|---|\n",
    );
    for res in results {
        let (light, class) = match res.scene.split_once('/') {
            Some((l, c)) => (l.to_string(), c.to_string()),
            None if res.scene.starts_with("envmap:") => {
                (res.scene.clone(), "occluded (mix)".to_string())
            }
            None => (res.scene.clone(), "mix".to_string()),
        };
        for spp in [16, 256] {
            let Some(k) = at(res, spp) else { continue };
            let Some(b) = best(res, k) else { continue };
            let ties = match b.ties.len() {
                0 => "-".to_string(),
                n => {
                    let names: Vec<String> =
                        b.ties.iter().take(3).map(|r| api_label(res, r)).collect();
                    if n > 3 {
                        format!("{} and {} more", names.join(", "), n - 3)
                    } else {
                        names.join(", ")
                    }
                }
            };
            let _ = writeln!(
                s,
                "| {light} | {class} | {spp} | **{}** ({:.2e}) | {ties} | {} ({:.2} ns) |",
                api_label(res, b.top),
                b.top.mse(k),
                api_label(res, b.cheapest),
                b.cheapest.ns[k],
            );
        }
    }
    s.push_str(
        "\nMSE in absolute units (irradiance of a unit-radiance light of unit area at distance 1; environment maps scaled to mean radiance 1). \"tied\": within two standard errors of the best. \"index-driven\": the construction draws its own points from the sample index (no sampler). Samples per pixel count warped samples: `disk::polar4` makes four disk samples from each 2D point, so its 256 spp are 64 points. The environment maps' MIS rows (`_mis`: two integrand evaluations per point) are left out here; see the MIS paragraph of REPORT.md. The CSV files name the same rows by short names (`pmj02bn`, `sobol_owen`, `polar4`, ...).\n",
    );
    s
}

/// One claim of the source talk: a ratio of MSEs `num / den` (rows `(scene suffix, sampler,
/// warp)`) at `spp`, and the source's value of that ratio.
struct Claim {
    what: &'static str,
    light: &'static str,
    spp: usize,
    num: (Sampler, &'static str),
    den: (Sampler, &'static str),
    source: &'static str,
}

/// `comparison.md`: the source talk's ratios (Pharr 2019, "Warp and Effect"; Christensen
/// 2018) beside ours, per pixel class.
pub fn comparison_markdown(results: &[SceneResult]) -> String {
    use Sampler::*;
    let claims = [
        Claim {
            what: "square: random / stratified",
            light: "square",
            spp: 16,
            num: (Random, "identity"),
            den: (Stratified, "identity"),
            source: "8",
        },
        Claim {
            what: "16:1 light: random / pmj02bn",
            light: "skinny",
            spp: 16,
            num: (Random, "identity"),
            den: (Pmj02bn, "identity"),
            source: "6",
        },
        Claim {
            what: "disk, stratified: concentric / polar",
            light: "disk",
            spp: 16,
            num: (Stratified, "concentric"),
            den: (Stratified, "polar"),
            source: "0.78 (2.19 / 2.80)",
        },
        Claim {
            what: "disk, pmj02bn: concentric / polar",
            light: "disk",
            spp: 16,
            num: (Pmj02bn, "concentric"),
            den: (Pmj02bn, "polar"),
            source: "1.11 (2.15 / 1.94)",
        },
        Claim {
            what: "disk, stratified: polar4 / polar",
            light: "disk",
            spp: 256,
            num: (Stratified, "polar4"),
            den: (Stratified, "polar"),
            source: "0.53 (4.14 / 7.76)",
        },
        Claim {
            what: "disk, pmj02bn: polar4 / polar",
            light: "disk",
            spp: 256,
            num: (Pmj02bn, "polar4"),
            den: (Pmj02bn, "polar"),
            source: "0.54 (3.82 / 7.11)",
        },
        Claim {
            what: "disk, pmj02bn: concentric / polar",
            light: "disk",
            spp: 256,
            num: (Pmj02bn, "concentric"),
            den: (Pmj02bn, "polar"),
            source: "1.00 (7.14 / 7.11)",
        },
        Claim {
            what: "disk, pmj02bn: concentric4 / polar4 (the memo's two quadrant strategies)",
            light: "disk",
            spp: 256,
            num: (Pmj02bn, "concentric4"),
            den: (Pmj02bn, "polar4"),
            source: "not quoted",
        },
        Claim {
            what: "disk, pmj02bn: polar4 / pad_zero (memo: \"more than 3 times error reduction in some cases\": RMSE, so MSE < 0.11)",
            light: "disk",
            spp: 256,
            num: (Pmj02bn, "polar4"),
            den: (Pmj02bn, "pad_zero"),
            source: "< 0.11",
        },
        Claim {
            what: "triangle: basu_owen (nested) / pmj02bn + uniform",
            light: "triangle",
            spp: 256,
            num: (Stratified, "basu_owen"),
            den: (Pmj02bn, "uniform"),
            source: "< 0.5 (\"more than halved\")",
        },
        Claim {
            what: "triangle: basu_owen_permuted / pmj02bn + uniform",
            light: "triangle",
            spp: 256,
            num: (Stratified, "basu_owen_permuted"),
            den: (Pmj02bn, "uniform"),
            source: "< 0.5",
        },
        Claim {
            what: "triangle: basu_owen_permuted / pmj02bn + sqrt (the older usual map)",
            light: "triangle",
            spp: 256,
            num: (Stratified, "basu_owen_permuted"),
            den: (Pmj02bn, "sqrt"),
            source: "< 0.5",
        },
        Claim {
            what: "envmap:sky, pmj02bn + marginal: equal-area / lat-long",
            light: "envmap:sky",
            spp: 256,
            num: (Pmj02bn, "marginal_equal_area"),
            den: (Pmj02bn, "marginal_equirect"),
            source: "0.7-0.8",
        },
        Claim {
            what: "envmap:interior, pmj02bn + marginal: equal-area / lat-long",
            light: "envmap:interior",
            spp: 256,
            num: (Pmj02bn, "marginal_equal_area"),
            den: (Pmj02bn, "marginal_equirect"),
            source: "0.7-0.8",
        },
        Claim {
            what: "envmap:sky, pmj02bn + hierarchical: equal-area / lat-long",
            light: "envmap:sky",
            spp: 256,
            num: (Pmj02bn, "hierarchical_equal_area"),
            den: (Pmj02bn, "hierarchical_equirect"),
            source: "0.7-0.8",
        },
        Claim {
            what: "envmap:interior, pmj02bn + hierarchical: equal-area / lat-long",
            light: "envmap:interior",
            spp: 256,
            num: (Pmj02bn, "hierarchical_equal_area"),
            den: (Pmj02bn, "hierarchical_equirect"),
            source: "0.7-0.8",
        },
        Claim {
            what: "envmap:sky, pmj02bn, equal-area: hierarchical / marginal",
            light: "envmap:sky",
            spp: 256,
            num: (Pmj02bn, "hierarchical_equal_area"),
            den: (Pmj02bn, "marginal_equal_area"),
            source: "< 1 (\"a little better\")",
        },
        Claim {
            what: "envmap:interior, pmj02bn, equal-area: hierarchical / marginal",
            light: "envmap:interior",
            spp: 256,
            num: (Pmj02bn, "hierarchical_equal_area"),
            den: (Pmj02bn, "marginal_equal_area"),
            source: "< 1",
        },
    ];
    let classes: [(&str, &str); 3] = [("", "mix"), ("/lit", "lit"), ("/penumbra", "penumbra")];
    let find = |scene: &str| results.iter().find(|r| r.scene == scene);
    let mut s = String::from(
        "| claim | spp | source | ours: mix | ours: lit | ours: penumbra |\n|---|---:|---|---:|---:|---:|\n",
    );
    for c in &claims {
        let _ = write!(s, "| {} | {} | {} |", c.what, c.spp, c.source);
        for (suffix, _) in classes {
            let ratio = find(&format!("{}{suffix}", c.light)).and_then(|res| {
                let k = at(res, c.spp)?;
                let a = res.row(c.num.0, c.num.1)?.stats[k];
                let b = res.row(c.den.0, c.den.1)?.stats[k];
                Some((
                    a.mse / b.mse,
                    (a.rel_se().powi(2) + b.rel_se().powi(2)).sqrt(),
                ))
            });
            let cell = ratio.map_or("-".to_string(), |(r, e)| {
                if r >= 0.1 {
                    format!("{r:.2} ± {:.2}", r * e)
                } else {
                    format!("{r:.1e} ± {:.0e}", r * e)
                }
            });
            let _ = write!(s, " {cell} |");
        }
        s.push('\n');
    }
    // Christensen's convergence targets: RMSE O(N^-1) lit, O(N^-0.75) penumbra, i.e. MSE
    // slopes -2 and -1.5; ours: the fitted slopes of pmj02bn with each disk strategy.
    let _ = write!(
        s,
        "| disk, pmj02bn: MSE convergence rate (memo's targets: -2 lit, -1.5 penumbra) | 4-{} | -2 / -1.5 |",
        results.first().map_or(0, |r| *r.spps.last().unwrap_or(&0))
    );
    for (suffix, _) in classes {
        let cell = find(&format!("disk{suffix}")).map_or("-".to_string(), |res| {
            crate::area::DISK_WARPS
                .iter()
                .filter_map(|w| {
                    let w = w.name();
                    res.row(Pmj02bn, w)
                        .map(|r| format!("{w} {:.2}", r.rate(&res.spps)))
                })
                .collect::<Vec<_>>()
                .join(", ")
        });
        let _ = write!(s, " {cell} |");
    }
    s.push_str("\n\nRatios of MSE at the given spp, ± one standard error (relative standard errors of the two MSEs combined, as if independent; the warps of one sampler share points, so differences between warps are sharper than this). Basu-Owen rows are the construction (indices `0..N`, the pixel's seed).\n");
    s
}
