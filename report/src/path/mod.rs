//! The path-traced scenes: which *sampler* drives a whole path best, and at what cost.
//!
//! For each scene (`cornell`, `cornell-disk`), each sampler of [`samplers::KINDS`] and each
//! sample count, independent frames (64 x 64 with `--full`, else 32 x 32; seeds hashed from
//! scene, sampler, count and frame) are rendered single-threaded (frames run in parallel),
//! compared with the cached reference (see [`mod@reference`]), and timed:
//!
//! * **MSE** over pixels and channels, minus the reference's own variance; its standard error
//!   from the pixels (independent per pixel for every sampler but the blue-noise ones, whose
//!   pixels are negatively correlated: their standard error is an overestimate);
//! * **filtered MSE** after a Gaussian blur of sigma 0.5 to 4 px (what a denoiser leaves), at
//!   1, 4 and 16 spp, corrected the same way; its standard error from the frames;
//! * **time per frame**: the whole render (sampling, tracing, shading) of one frame,
//!   single-threaded, the best over the frames of that count.

pub mod frames;
pub mod metrics;
pub mod pictures;
pub mod qmc;
pub mod reference;
pub mod samplers;
pub mod scene;
pub mod study;
pub mod trace;

use crate::run::Scale;
use metrics::{PixelStats, blur, diff, mean_se, squares};
use reference::Reference;
use samplers::{KINDS, Kind, with_sampler};
use scene::Scene;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;
use trace::Image;

/// Gaussian blur widths of the filtered error, in pixels.
pub const SIGMAS: [f64; 5] = [0.0, 0.5, 1.0, 2.0, 4.0];
/// Sample counts of the filtered error.
pub const FILTERED_SPPS: [u32; 3] = [1, 4, 16];
/// Image side.
pub const SIZE: usize = 64;
/// The reference's samples per pixel per half: 2 x 8192 = 64 x the top count (256).
pub const REFERENCE_SPP_PER_HALF: u32 = 8192;

#[derive(Clone, Debug)]
pub struct PathConfig {
    pub scenes: Vec<String>,
    pub spps: Vec<u32>,
    pub threads: usize,
    pub scale: Scale,
    /// Re-render the references (`--reference`).
    pub rebuild_reference: bool,
    /// Where the cached references live (`docs/report`).
    pub reference_dir: PathBuf,
    pub reference_spp_per_half: u32,
    /// Image side: [`SIZE`] with `--full`, else half of it (the reference is averaged over
    /// 2 x 2 pixels: with a box pixel filter that is exactly the expected value of the coarser
    /// pixels).
    pub size: usize,
}

impl PathConfig {
    /// Sample counts 1 to 256 (default: to 64; quick: to 16), 64 x 64 pixels (else 32 x 32).
    pub fn new(scenes: Vec<String>, scale: Scale, threads: usize, rebuild: bool) -> Self {
        let top = scale.pick([16, 64, 256]);
        PathConfig {
            scenes,
            spps: [1, 2, 4, 8, 16, 64, 256]
                .into_iter()
                .filter(|&n| n <= top)
                .collect(),
            threads,
            scale,
            rebuild_reference: rebuild,
            reference_dir: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/.."))
                .join("docs/report"),
            reference_spp_per_half: REFERENCE_SPP_PER_HALF,
            size: if scale == Scale::Full { SIZE } else { SIZE / 2 },
        }
    }

    /// Independent frames rendered at `spp`: 8 up to 16 spp, 2 at 64, 1 at 256 (default: 4
    /// up to 16, 1 at 64; quick: 2 at the filtered counts, else 1).
    pub fn frames(&self, spp: u32) -> u32 {
        match (self.scale, spp) {
            (Scale::Quick, s) if FILTERED_SPPS.contains(&s) => 2,
            (Scale::Quick, _) => 1,
            (Scale::Default, 0..=16) => 4,
            (Scale::Full, 0..=16) => 8,
            (Scale::Full, 17..=64) => 2,
            _ => 1,
        }
    }
}

/// One (sampler, spp) of a scene.
#[derive(Clone, Debug)]
pub struct PathRow {
    pub kind: Kind,
    pub spp: u32,
    pub frames: u32,
    /// MSE minus the reference's variance, and its standard error.
    pub mse: f64,
    pub mse_se: f64,
    pub mean_error: f64,
    pub bias_z: f64,
    /// Best single-threaded time of one whole frame, seconds.
    pub frame_s: f64,
    /// Filtered MSE per [`SIGMAS`] (corrected) and its standard error over frames, at
    /// [`FILTERED_SPPS`] only.
    pub filtered: Option<[(f64, f64); 5]>,
}

impl PathRow {
    pub fn ns_per_sample(&self, pixels: usize) -> f64 {
        self.frame_s * 1e9 / pixels as f64 / self.spp as f64
    }
}

pub struct PathResult {
    pub scene: String,
    pub rows: Vec<PathRow>,
    pub reference_spp_per_half: u32,
    pub reference_seconds: f64,
    pub reference_bytes: usize,
    /// The reference's variance (mean over pixels and channels), its standard error, and
    /// the same after each blur of [`SIGMAS`].
    pub ref_var: [(f64, f64); 5],
    pub reference: Image,
    /// Frame 0 at 4 spp, per sampler (for the pictures).
    pub at4: Vec<(Kind, Image)>,
    pub seconds: f64,
}

impl PathResult {
    pub fn row(&self, kind: Kind, spp: u32) -> Option<&PathRow> {
        self.rows.iter().find(|r| r.kind == kind && r.spp == spp)
    }
    /// Slope of log MSE over log spp from 4 spp up.
    pub fn rate(&self, kind: Kind) -> f64 {
        let pts: Vec<(f64, f64)> = self
            .rows
            .iter()
            .filter(|r| r.kind == kind && r.spp >= 4 && r.mse > 0.0)
            .map(|r| ((r.spp as f64).ln(), r.mse.ln()))
            .collect();
        crate::math::slope(&pts)
    }
}

/// The cached reference of `scene`, rendered (and cached) when missing or asked for.
pub fn reference(cfg: &PathConfig, scene: &Scene) -> Result<(Reference, usize), String> {
    let path = Reference::path(&cfg.reference_dir, &scene.name);
    if !cfg.rebuild_reference
        && let Ok(bytes) = std::fs::read(&path)
    {
        let r = Reference::from_bytes(&bytes).map_err(|e| format!("{}: {e}", path.display()))?;
        if r.a.width == scene.width && r.a.height == scene.height {
            return Ok((r, bytes.len()));
        }
    }
    eprintln!(
        "{}: rendering the reference (2 x {} spp, {} threads)...",
        scene.name, cfg.reference_spp_per_half, cfg.threads
    );
    let r = Reference::render(scene, cfg.reference_spp_per_half, cfg.threads);
    let bytes = r.to_bytes();
    std::fs::create_dir_all(&cfg.reference_dir).map_err(|e| e.to_string())?;
    std::fs::write(&path, &bytes).map_err(|e| format!("{}: {e}", path.display()))?;
    eprintln!(
        "{}: reference in {:.1} s, {} bytes",
        scene.name,
        r.seconds,
        bytes.len()
    );
    Ok((r, bytes.len()))
}

/// The seed of one frame.
fn seed(scene: &str, kind: Kind, spp: u32, frame: u32) -> u32 {
    let s = crate::math::hash(&scene.bytes().map(u64::from).collect::<Vec<_>>());
    crate::math::hash(&[s, kind.index() as u64, spp as u64, frame as u64]) as u32
}

/// One frame of `kind` at `spp`, single-threaded, and its wall-clock seconds.
pub fn render(scene: &Scene, kind: Kind, spp: u32, seed: u32) -> (Image, f64) {
    let t = Instant::now();
    let img = with_sampler!(kind, s => trace::render(scene, s, spp, seed));
    (img, t.elapsed().as_secs_f64())
}

struct Acc {
    stats: PixelStats,
    filtered: Vec<[f64; 5]>,
    best: f64,
}

/// The experiment on one scene.
pub fn run_scene(cfg: &PathConfig, name: &str) -> Result<PathResult, String> {
    let start = Instant::now();
    let scene = Scene::by_name(name, SIZE).ok_or_else(|| format!("unknown path scene {name}"))?;
    let (refr, reference_bytes) = reference(cfg, &scene)?;
    let f = SIZE / cfg.size.clamp(1, SIZE);
    let refr = refr.downsample(f);
    let scene = Scene::by_name(name, SIZE / f).ok_or("unknown path scene")?;
    let rmean = refr.mean();
    let rhalf = refr.half_difference();
    let ref_var: [(f64, f64); 5] = SIGMAS.map(|s| mean_se(&squares(&blur(&rhalf, s))));
    let mut jobs: Vec<(Kind, u32, u32)> = Vec::new();
    for &spp in &cfg.spps {
        for kind in KINDS {
            for f in 0..cfg.frames(spp) {
                jobs.push((kind, spp, f));
            }
        }
    }
    jobs.sort_by_key(|j| std::cmp::Reverse(j.1));
    let accs: Vec<Mutex<Acc>> = (0..KINDS.len() * cfg.spps.len())
        .map(|_| {
            Mutex::new(Acc {
                stats: PixelStats::default(),
                filtered: Vec::new(),
                best: f64::INFINITY,
            })
        })
        .collect();
    let at4 = Mutex::new(Vec::new());
    let next = AtomicUsize::new(0);
    let bar = indicatif::ProgressBar::new(jobs.len() as u64);
    bar.set_message(name.to_string());
    std::thread::scope(|sc| {
        for _ in 0..cfg.threads.max(1) {
            sc.spawn(|| {
                loop {
                    let j = next.fetch_add(1, Ordering::Relaxed);
                    let Some(&(kind, spp, frame)) = jobs.get(j) else {
                        break;
                    };
                    let (img, secs) = render(&scene, kind, spp, seed(name, kind, spp, frame));
                    let err = diff(&img, &rmean);
                    let mut st = PixelStats::default();
                    st.add_frame(&err);
                    let filt = FILTERED_SPPS.contains(&spp).then(|| {
                        SIGMAS.map(|s| {
                            squares(&blur(&err, s)).iter().sum::<f64>() / err.px.len() as f64
                        })
                    });
                    let k = cfg.spps.iter().position(|&s| s == spp).unwrap_or(0);
                    {
                        let mut a = accs[kind.index() * cfg.spps.len() + k].lock().unwrap();
                        a.stats.merge(&st);
                        a.best = a.best.min(secs);
                        if let Some(f) = filt {
                            a.filtered.push(f);
                        }
                    }
                    if spp == 4 && frame == 0 {
                        at4.lock().unwrap().push((kind, img));
                    }
                    bar.inc(1);
                }
            });
        }
    });
    bar.finish_and_clear();
    // The reference's error is common to all frames: its variance is subtracted, and its
    // mean error adds to the standard error of each mean error.
    let ref_mean_se = {
        let d: Vec<f64> = rhalf
            .px
            .iter()
            .map(|p| (p[0] + p[1] + p[2]) / 3.0)
            .collect();
        (d.iter().map(|x| x * x).sum::<f64>()).sqrt() / d.len() as f64
    };
    let mut rows = Vec::new();
    for kind in KINDS {
        for (k, &spp) in cfg.spps.iter().enumerate() {
            let a = accs[kind.index() * cfg.spps.len() + k].lock().unwrap();
            let (raw, raw_se) = a.stats.mse();
            let (me, me_se) = a.stats.bias();
            let filtered = (!a.filtered.is_empty()).then(|| {
                std::array::from_fn(|s| {
                    let v: Vec<f64> = a.filtered.iter().map(|f| f[s]).collect();
                    let (m, se) = mean_se(&v);
                    let se = if v.len() > 1 { se } else { f64::NAN };
                    (
                        m - ref_var[s].0,
                        (se * se + ref_var[s].1 * ref_var[s].1).sqrt(),
                    )
                })
            });
            rows.push(PathRow {
                kind,
                spp,
                frames: cfg.frames(spp),
                mse: raw - ref_var[0].0,
                mse_se: (raw_se * raw_se + ref_var[0].1 * ref_var[0].1).sqrt(),
                mean_error: me,
                bias_z: me / (me_se * me_se + ref_mean_se * ref_mean_se).sqrt(),
                frame_s: a.best,
                filtered,
            });
        }
    }
    let mut at4 = at4.into_inner().unwrap();
    at4.sort_by_key(|(k, _)| k.index());
    let res = PathResult {
        scene: name.to_string(),
        rows,
        reference_spp_per_half: refr.spp_per_half,
        reference_seconds: refr.seconds,
        reference_bytes,
        ref_var,
        reference: rmean,
        at4,
        seconds: start.elapsed().as_secs_f64(),
    };
    eprintln!("{name}: {} frames in {:.1} s", jobs.len(), res.seconds);
    Ok(res)
}

/// Every (scene, row) of `results`, in the CSV files' order.
fn entries(results: &[PathResult]) -> impl Iterator<Item = (&PathResult, &PathRow)> {
    results
        .iter()
        .flat_map(|r| r.rows.iter().map(move |row| (r, row)))
}

/// Rows for `results.csv` (same header as the other scenes; warp `path`).
pub fn results_csv_rows(results: &[PathResult]) -> String {
    entries(results)
        .map(|(r, row)| {
            let ns = row.ns_per_sample(r.reference.px.len());
            csv_row(&r.scene, row.kind, row.spp, row.mse, ns)
        })
        .collect()
}

/// One line of `results.csv` for a path scene (warp `path`), newline included.
pub fn csv_row(scene: &str, kind: Kind, spp: u32, mse: f64, ns_per_sample: f64) -> String {
    crate::output::csv_line(scene, kind.name(), "path", spp as usize, mse, ns_per_sample) + "\n"
}

/// `filtered.csv`.
pub fn filtered_csv(results: &[PathResult]) -> String {
    let mut s = String::from("scene,sampler,spp,sigma,mse\n");
    for (r, row) in entries(results) {
        for (sigma, (m, _)) in SIGMAS.iter().zip(row.filtered.iter().flatten()) {
            let _ = writeln!(
                s,
                "{},{},{},{sigma},{m:.6e}",
                r.scene,
                row.kind.name(),
                row.spp
            );
        }
    }
    s
}

/// `path-details.csv`: the rows with their statistics.
pub fn details_csv(results: &[PathResult]) -> String {
    let mut s = String::from(
        "scene,sampler,spp,frames,mse,mse_rel_se,mean_error,bias_z,frame_ms,ns_per_sample,reference_variance\n",
    );
    for (r, row) in entries(results) {
        let _ = writeln!(
            s,
            "{},{},{},{},{:.6e},{:.4},{:.4e},{:.3},{:.3},{:.2},{:.4e}",
            r.scene,
            row.kind.name(),
            row.spp,
            row.frames,
            row.mse,
            row.mse_se / row.mse,
            row.mean_error,
            row.bias_z,
            row.frame_s * 1e3,
            row.ns_per_sample(r.reference.px.len()),
            r.ref_var[0].0
        );
    }
    s
}

fn sci(x: f64) -> String {
    if !x.is_finite() {
        return "-".into();
    }
    format!("{x:.2e}")
}

/// The best warpcore sampler at `spp` (lowest MSE).
fn best_warpcore(r: &PathResult, spp: u32) -> Option<&PathRow> {
    r.rows
        .iter()
        .filter(|x| x.spp == spp && x.kind.is_warpcore())
        .min_by(|a, b| a.mse.total_cmp(&b.mse))
}

/// The markdown tables of the path scenes (`path.md`, and the REPORT's section).
pub fn markdown(results: &[PathResult]) -> String {
    let mut s = String::new();
    for r in results {
        let spps: Vec<u32> = r
            .rows
            .iter()
            .filter(|x| x.kind == Kind::Random)
            .map(|x| x.spp)
            .collect();
        let _ = writeln!(
            s,
            "### {}\n\n{} x {} pixels; reference 2 x {} spp ({:.0} s to render, {} bytes cached); reference variance {} (+- {:.0}%), subtracted from every MSE.\n",
            r.scene,
            r.reference.width,
            r.reference.height,
            r.reference_spp_per_half,
            r.reference_seconds,
            r.reference_bytes,
            sci(r.ref_var[0].0),
            100.0 * r.ref_var[0].1 / r.ref_var[0].0
        );
        let _ = write!(s, "| sampler |");
        for spp in &spps {
            let _ = write!(s, " MSE {spp} spp |");
        }
        let _ = writeln!(
            s,
            " rate | frame ms (4 spp) | MSE x time (4 spp) | bias z (4 spp) |"
        );
        let _ = writeln!(s, "|---|{}---|---|---|---|", "---:|".repeat(spps.len()));
        for kind in KINDS {
            let _ = write!(s, "| {} |", kind.name());
            for &spp in &spps {
                if let Some(x) = r.row(kind, spp) {
                    let _ = write!(
                        s,
                        " {} ({:.0}%) |",
                        sci(x.mse),
                        100.0 * x.mse_se / x.mse.abs()
                    );
                }
            }
            let x4 = r.row(kind, 4);
            let _ = writeln!(
                s,
                " {:.2} | {:.1} | {} | {:.1} |",
                r.rate(kind),
                x4.map_or(f64::NAN, |x| x.frame_s * 1e3),
                sci(x4.map_or(f64::NAN, |x| x.mse * x.frame_s)),
                x4.map_or(f64::NAN, |x| x.bias_z)
            );
        }
        // Ratios to the best warpcore sampler.
        let _ = writeln!(
            s,
            "\nMSE of each sampler / the best warpcore sampler's at that count (below 1: the peer wins; in brackets, the ratio's standard error):\n"
        );
        let _ = write!(s, "| sampler |");
        for spp in &spps {
            let _ = write!(s, " {spp} spp |");
        }
        let _ = writeln!(s, "\n|---|{}", "---:|".repeat(spps.len()));
        for kind in KINDS {
            let _ = write!(s, "| {} |", kind.name());
            for &spp in &spps {
                if let (Some(x), Some(b)) = (r.row(kind, spp), best_warpcore(r, spp)) {
                    let q = x.mse / b.mse;
                    let se = q * ((x.mse_se / x.mse).powi(2) + (b.mse_se / b.mse).powi(2)).sqrt();
                    let mark = if q < 1.0 - 2.0 * se { "**" } else { "" };
                    let _ = write!(s, " {mark}{q:.2}{mark} ({se:.2}) |");
                }
            }
            let _ = writeln!(s);
        }
        // Filtered error.
        let _ = writeln!(
            s,
            "\nError after a Gaussian blur (what a denoiser leaves): MSE at sigma = 0 / 0.5 / 1 / 2 / 4 px, relative standard error over frames in brackets for sigma = 2:\n"
        );
        let _ = write!(s, "| sampler |");
        for spp in FILTERED_SPPS {
            if r.row(Kind::Random, spp)
                .is_some_and(|x| x.filtered.is_some())
            {
                let _ = write!(s, " {spp} spp |");
            }
        }
        let _ = writeln!(s, "\n|---|---|---|---|");
        for kind in KINDS {
            let _ = write!(s, "| {} |", kind.name());
            for spp in FILTERED_SPPS {
                if let Some(f) = r.row(kind, spp).and_then(|x| x.filtered) {
                    let v: Vec<String> = f.iter().map(|(m, _)| sci(*m)).collect();
                    let _ = write!(
                        s,
                        " {} ({:.0}%) |",
                        v.join(" / "),
                        100.0 * f[3].1 / f[3].0.abs()
                    );
                }
            }
            let _ = writeln!(s);
        }
        let _ = writeln!(s);
    }
    s
}

/// Runs the path scenes named in `cfg.scenes`, writes their CSVs, tables and pictures into
/// `out`; returns the results and the rows for `results.csv`.
pub fn run(cfg: &PathConfig, out: &Path) -> Result<Vec<PathResult>, Box<dyn std::error::Error>> {
    Kind::warm_all();
    let mut results = Vec::new();
    for name in &cfg.scenes {
        results.push(run_scene(cfg, name)?);
    }
    if results.is_empty() {
        return Ok(results);
    }
    crate::output::write(&out.join("filtered.csv"), &filtered_csv(&results))?;
    crate::output::write(&out.join("path-details.csv"), &details_csv(&results))?;
    let md = markdown(&results);
    crate::output::write(&out.join("path.md"), &md)?;
    print!("{md}");
    for r in &results {
        pictures::write(r, out)?;
    }
    Ok(results)
}

#[cfg(test)]
mod tests;

/// The recommendations' rows of the path scenes: "offline, 64+ spp" (lowest MSE at each
/// count from 64 up) and "real-time, 1-4 spp, denoised" (lowest MSE after a sigma = 2 px
/// blur at 1 and 4 spp), each with the samplers tied with it (within two standard errors of
/// the difference) and the lowest MSE x frame time.
pub fn recommendations_markdown(results: &[PathResult]) -> String {
    let mut s = String::from(
        "\n## Path-traced scenes: which sampler drives the whole path\n\n| scene | use | spp | lowest error | tied (2 s.e.) | lowest error x frame time |\n|---|---|---:|---|---|---|\n",
    );
    for r in results {
        let mut cases: Vec<(&str, u32, usize)> = Vec::new();
        for spp in [64, 256] {
            if r.row(Kind::Random, spp).is_some() {
                cases.push(("offline, 64+ spp (MSE)", spp, 0));
            }
        }
        for spp in [1, 4] {
            if r.row(Kind::Random, spp)
                .is_some_and(|x| x.filtered.is_some())
            {
                cases.push((
                    "real-time, 1-4 spp, denoised (MSE after a 2 px blur)",
                    spp,
                    3,
                ));
            }
        }
        for (what, spp, sigma) in cases {
            let val = |x: &PathRow| -> (f64, f64) {
                if sigma == 0 {
                    (x.mse, x.mse_se)
                } else {
                    x.filtered.map_or((f64::NAN, f64::NAN), |f| f[sigma])
                }
            };
            let rows: Vec<&PathRow> = r.rows.iter().filter(|x| x.spp == spp).collect();
            let Some(best) = rows.iter().min_by(|a, b| val(a).0.total_cmp(&val(b).0)) else {
                continue;
            };
            let (bm, bs) = val(best);
            let tied: Vec<&str> = rows
                .iter()
                .filter(|x| x.kind != best.kind)
                .filter(|x| {
                    let (m, se) = val(x);
                    m - bm <= 2.0 * (se * se + bs * bs).sqrt()
                })
                .map(|x| x.kind.name())
                .collect();
            let cost = rows
                .iter()
                .min_by(|a, b| (val(a).0 * a.frame_s).total_cmp(&(val(b).0 * b.frame_s)))
                .map_or("-", |x| x.kind.name());
            let _ = writeln!(
                s,
                "| {} | {what} | {spp} | **{}** ({}) | {} | {cost} |",
                r.scene,
                best.kind.name(),
                sci(bm),
                if tied.is_empty() {
                    "-".to_string()
                } else {
                    tied.join(", ")
                }
            );
        }
    }
    s
}
