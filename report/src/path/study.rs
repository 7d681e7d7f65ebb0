//! The path study: Burley 2020's Cornell-box comparison reproduced, what caps the structured
//! samplers' gain on `cornell` and `cornell-disk` (ablations, the error split by path
//! length), and convergence rates with standard errors.
//!
//! Every figure here is a *variance*, measured without a reference: `F` independent frames
//! of each (scene, sampler, spp) (seeds hashed from the four), per pixel and channel the
//! unbiased sample variance over the frames, averaged over pixels and channels. For an
//! unbiased estimator that is its MSE (the reference's own error and its correction drop
//! out); for the clamped variant (biased, a diagnostic) it is the variance alone. Standard
//! errors from the pixels (independent for these samplers: none of the study's is a
//! blue-noise one, and `sobol_enum`'s pixels share one sequence but not its points). The
//! same variance by path length (the number of scattering events: 0 the light seen
//! directly, 1 direct lighting, ...) splits the error.
//!
//! Rates: the slope of `ln MSE` over `ln spp`, weighted least squares with each point's
//! variance of `ln MSE` from its standard error (`(se / mse)^2`); the slope's standard error
//! from those weights. Fitted over 4-1024 spp, and over 4-64 and 64-1024 apart.

use super::samplers::{BURLEY_KINDS, Kind, with_sampler};
use super::scene::{GgxSampler, Scene};
use super::trace::{Image, MAX_LENGTH, render_by_length};
use crate::run::Scale;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

/// Burley 2020, Figure 1: RMSE per configuration and column (independent, Laine-Karras,
/// Sobol'-RDS, Sobol'-enum, Owen-scrambled Sobol'), and our scene of it (the paper's detail
/// images are crops: so are our scenes; `burley-direct/frame` is the whole frame,
/// `burley-direct/centre` samples the pixels' centres only: no pixel dimensions).
pub const PAPER: [(&str, &str, u32, [f64; 5]); 5] = [
    ("(a) direct lighting", "burley-direct", 16, DIRECT),
    (
        "(a) direct lighting, whole frame",
        "burley-direct/frame",
        16,
        DIRECT,
    ),
    (
        "(a) direct lighting, pixel centres",
        "burley-direct/centre",
        16,
        DIRECT,
    ),
    (
        "(b) GI, media, depth of field",
        "burley-gi",
        16,
        [0.017, 0.0075, 0.0053, 0.0043, 0.0040],
    ),
    (
        "(c) GI, subpixel checkerboard",
        "burley-checker",
        64,
        [0.046, 0.10, 0.14, 0.052, 0.043],
    ),
];

/// Burley 2020, Figure 1 (a).
const DIRECT: [f64; 5] = [0.020, 0.0065, 0.0048, 0.0021, 0.0017];

/// The paper's five columns: our samplers (`sobol_burley` is the paper's Owen-Sobol', the
/// author's crate; warpcore's `sobol` is the same construction with its own hash), then
/// Laine-Karras with Burley's index shuffle (what the shuffle alone buys).
pub const COLUMNS: [Kind; 7] = [
    Kind::Random,
    BURLEY_KINDS[0],
    BURLEY_KINDS[1],
    BURLEY_KINDS[2],
    Kind::SobolBurley,
    Kind::Sobol,
    BURLEY_KINDS[3],
];

/// The ablation variants of `cornell` and `cornell-disk` (scene names, see
/// [`Scene::by_name`]) and their samplers: `random` and warpcore's `sobol` for all; the
/// tracer's first form (`rr-rnd`) and its new one (`rr-production`) also the other padded
/// samplers for the rate fits, and the new one the unpadded Sobol' sequences (all
/// dimensions of one sequence: the allocation of dimensions across bounces).
pub const ABLATIONS: [(&str, &[Kind]); 10] = [
    (
        "cornell/rr-production",
        &[
            R,
            S,
            Kind::Pmj02bn,
            Kind::SobolBurley,
            Kind::SobolRds,
            Kind::SobolEnum,
        ],
    ),
    ("cornell/rr-rnd", &[R, S, Kind::Pmj02bn, Kind::SobolBurley]),
    ("cornell/rr-sampler", &[R, S]),
    ("cornell/rr-off", &[R, S]),
    ("cornell/diffuse/rr-rnd", &[R, S]),
    ("cornell/diffuse/rr-production", &[R, S]),
    ("cornell/clamp/rr-rnd", &[R, S]),
    ("cornell/centre/rr-production", &[R, S, Kind::SobolRds]),
    ("cornell-disk/rr-rnd", &[R, S]),
    ("cornell-disk/rr-production", &[R, S]),
];

const R: Kind = Kind::Random;
const S: Kind = Kind::Sobol;

/// The samplers of the split by path length.
pub const SPLIT_KINDS: [Kind; 2] = [R, S];

/// The glossy family's roughnesses (`glossy-a<alpha>`, see [`Scene::by_name`]).
pub const GLOSSY_ALPHAS: [&str; 3] = ["0.05", "0.3", "0.8"];

/// The glossy family's samplers (pixel samplers; the BSDF samplers are the scenes' variants).
pub const GLOSSY_KINDS: [Kind; 3] = [Kind::Sobol, Kind::Pmj02bn, Kind::Random];

/// The glossy family's sample counts.
pub const GLOSSY_SPPS: [u32; 3] = [4, 16, 64];

/// The glossy family's scene names: every roughness with every BSDF sampler
/// (`glossy-a0.3/bounded`, ...), then the same with one scattering event (`.../direct`, the
/// full run only: the BSDF samplers' own share of the error).
pub fn glossy_scenes() -> Vec<String> {
    let mut out = Vec::new();
    for suffix in ["", "/direct"] {
        for a in GLOSSY_ALPHAS {
            for g in GgxSampler::ALL {
                out.push(format!("glossy-a{a}/{}{suffix}", g.name()));
            }
        }
    }
    out
}

/// One experiment: a scene at `size` x `size`, samplers, sample counts, frames.
#[derive(Clone, Debug)]
pub struct Case {
    pub scene: String,
    pub size: usize,
    pub kinds: Vec<Kind>,
    pub spps: Vec<u32>,
    pub frames: u32,
}

/// The study's cases at `scale` for the scenes `wants` selects: Burley's boxes at 64 x 64
/// pixels, 16 frames (default 32 x 32, 4; quick 16 x 16, 4); the ablations at 32 x 32, 4
/// frames, 4 to 1024 spp (default: 16 x 16 to 256 spp, the first four, the others'
/// samplers on the first only; quick: 2 frames to 64 spp, the first two, `random` and
/// `sobol`).
pub fn cases(scale: Scale, wants: impl Fn(&str) -> bool) -> Vec<Case> {
    let mut out = Vec::new();
    let (size, frames) = scale.pick([(16, 4), (32, 4), (64, 16)]);
    for (_, scene, spp, _) in PAPER {
        if wants(scene) {
            out.push(Case {
                scene: scene.into(),
                size,
                kinds: COLUMNS.to_vec(),
                spps: vec![spp],
                frames,
            });
        }
    }
    let top = scale.pick([64, 256, 1024]);
    let spps: Vec<u32> = [4, 16, 64, 256, 1024]
        .into_iter()
        .filter(|&n| n <= top)
        .collect();
    let (size, frames) = scale.pick([(16, 2), (16, 4), (32, 4)]);
    let n = scale.pick([2, 4, ABLATIONS.len()]);
    for (i, (scene, kinds)) in ABLATIONS.iter().take(n).enumerate() {
        if wants(scene) {
            out.push(Case {
                scene: scene.to_string(),
                size,
                kinds: if scale == Scale::Full || (scale == Scale::Default && i == 0) {
                    kinds.to_vec()
                } else {
                    SPLIT_KINDS.to_vec()
                },
                spps: spps.clone(),
                frames,
            });
        }
    }
    // The glossy family: 32 x 32 pixels, 5 frames (quick 16 x 16, 2 frames; full 64 x 64, 24).
    let (size, frames) = scale.pick([(16, 2), (32, 5), (64, 24)]);
    for scene in glossy_scenes() {
        if wants(&scene) && (scale == Scale::Full || !scene.ends_with("/direct")) {
            out.push(Case {
                scene,
                size,
                kinds: GLOSSY_KINDS.to_vec(),
                spps: GLOSSY_SPPS.to_vec(),
                frames,
            });
        }
    }
    out
}

/// One (scene, sampler, spp).
#[derive(Clone, Debug)]
pub struct Row {
    pub scene: String,
    pub kind: Kind,
    pub spp: u32,
    pub frames: u32,
    pub pixels: usize,
    /// The variance over frames (MSE of an unbiased estimator) and its standard error, of
    /// the whole estimate and of each path length `0..=MAX_LENGTH`.
    pub mse: (f64, f64),
    pub by_length: Vec<(f64, f64)>,
    /// The variance of the estimate without the emitter seen directly (path lengths 1 and
    /// up: what a BSDF sampler can change), and its standard error.
    pub scattered: (f64, f64),
    /// Best single-threaded time of one frame, seconds.
    pub frame_s: f64,
}

impl Row {
    pub fn rmse(&self) -> (f64, f64) {
        let r = self.mse.0.max(0.0).sqrt();
        (r, if r > 0.0 { self.mse.1 / (2.0 * r) } else { 0.0 })
    }
    pub fn ns_per_sample(&self) -> f64 {
        self.frame_s * 1e9 / self.pixels as f64 / self.spp as f64
    }
}

/// Per pixel, channel and path length (the last slot: the whole estimate), the sums of the
/// values and of their squares over the frames.
struct Sums {
    x: Vec<f64>,
    xx: Vec<f64>,
    frames: u32,
    best: f64,
}

/// Per pixel and channel: each path length, the whole estimate, the estimate without length 0.
const SLOTS: usize = MAX_LENGTH + 3;
const WHOLE: usize = MAX_LENGTH + 1;
const SCATTERED: usize = MAX_LENGTH + 2;

impl Sums {
    fn new(pixels: usize) -> Sums {
        Sums {
            x: vec![0.0; pixels * 3 * SLOTS],
            xx: vec![0.0; pixels * 3 * SLOTS],
            frames: 0,
            best: f64::INFINITY,
        }
    }

    fn add(&mut self, by_length: &[Image], secs: f64) {
        for (p, i) in (0..by_length[0].px.len()).enumerate() {
            for c in 0..3 {
                let mut total = 0.0;
                for (k, img) in by_length.iter().enumerate() {
                    let v = img.px[i][c];
                    total += v;
                    self.put((p * 3 + c) * SLOTS + k, v);
                }
                self.put((p * 3 + c) * SLOTS + WHOLE, total);
                self.put(
                    (p * 3 + c) * SLOTS + SCATTERED,
                    total - by_length[0].px[i][c],
                );
            }
        }
        self.frames += 1;
        self.best = self.best.min(secs);
    }

    fn put(&mut self, j: usize, v: f64) {
        self.x[j] += v;
        self.xx[j] += v * v;
    }

    /// Mean over pixels of the channels' mean variance in `slot`, and its standard error.
    fn variance(&self, slot: usize) -> (f64, f64) {
        let f = self.frames as f64;
        let per_pixel: Vec<f64> = (0..self.x.len() / (3 * SLOTS))
            .map(|p| {
                (0..3)
                    .map(|c| {
                        let j = (p * 3 + c) * SLOTS + slot;
                        ((self.xx[j] - self.x[j] * self.x[j] / f) / (f - 1.0)).max(0.0)
                    })
                    .sum::<f64>()
                    / 3.0
            })
            .collect();
        super::metrics::mean_se(&per_pixel)
    }
}

/// The seed of one frame.
fn seed(scene: &str, kind: Kind, spp: u32, frame: u32) -> u32 {
    let s = crate::math::hash(&scene.bytes().map(u64::from).collect::<Vec<_>>());
    crate::math::hash(&[s, 0x5717, kind.index() as u64, spp as u64, frame as u64]) as u32
}

/// Runs `cases` on `threads` threads.
pub fn measure(cases: &[Case], threads: usize) -> Result<Vec<Row>, String> {
    let mut scenes = Vec::new();
    for c in cases {
        scenes.push(
            Scene::by_name(&c.scene, c.size).ok_or_else(|| format!("unknown scene {}", c.scene))?,
        );
    }
    // Jobs: (case, kind, spp, frame), the longest first; one accumulator per (case, kind, spp).
    let mut cells: Vec<(usize, Kind, u32)> = Vec::new();
    let mut jobs: Vec<(usize, u32)> = Vec::new();
    for (ci, c) in cases.iter().enumerate() {
        for &kind in &c.kinds {
            for &spp in &c.spps {
                for f in 0..c.frames {
                    jobs.push((cells.len(), f));
                }
                cells.push((ci, kind, spp));
            }
        }
    }
    let cost = |j: &(usize, u32)| {
        let (ci, _, spp) = cells[j.0];
        std::cmp::Reverse(spp as usize * cases[ci].size * cases[ci].size)
    };
    jobs.sort_by_key(cost);
    let sums: Vec<Mutex<Option<Sums>>> = cells.iter().map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let bar = indicatif::ProgressBar::new(jobs.len() as u64);
    bar.set_message("path study");
    std::thread::scope(|sc| {
        for _ in 0..threads.max(1) {
            sc.spawn(|| {
                while let Some(&(cell, frame)) = jobs.get(next.fetch_add(1, Ordering::Relaxed)) {
                    let (ci, kind, spp) = cells[cell];
                    let scene = &scenes[ci];
                    let t = Instant::now();
                    let seed = seed(&scene.name, kind, spp, frame);
                    let imgs = with_sampler!(kind, s => render_by_length(scene, s, spp, seed));
                    let secs = t.elapsed().as_secs_f64();
                    let mut slot = sums[cell].lock().unwrap();
                    slot.get_or_insert_with(|| Sums::new(scene.width * scene.height))
                        .add(&imgs, secs);
                    bar.inc(1);
                }
            });
        }
    });
    bar.finish_and_clear();
    Ok(cells
        .iter()
        .zip(sums)
        .filter_map(|(&(ci, kind, spp), s)| {
            let s = s.into_inner().ok()??;
            Some(Row {
                scene: cases[ci].scene.clone(),
                kind,
                spp,
                frames: s.frames,
                pixels: cases[ci].size * cases[ci].size,
                mse: s.variance(WHOLE),
                by_length: (0..=MAX_LENGTH).map(|k| s.variance(k)).collect(),
                scattered: s.variance(SCATTERED),
                frame_s: s.best,
            })
        })
        .collect())
}

/// A fitted rate: slope of `ln MSE` over `ln spp` and its standard error.
#[derive(Clone, Copy, Debug)]
pub struct Rate {
    pub from: u32,
    pub to: u32,
    pub rate: f64,
    pub se: f64,
}

/// Weighted least squares of `ln m` on `ln spp` over `(spp, m, se)` points with `from <=
/// spp <= to` (weights `(m / se)^2`); `None` with fewer than two points.
pub fn fit(points: &[(u32, f64, f64)], from: u32, to: u32) -> Option<Rate> {
    let pts: Vec<(f64, f64, f64)> = points
        .iter()
        .filter(|p| p.0 >= from && p.0 <= to && p.1 > 0.0 && p.2 > 0.0)
        .map(|&(n, m, se)| ((n as f64).ln(), m.ln(), (m / se).powi(2)))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let w: f64 = pts.iter().map(|p| p.2).sum();
    let mx = pts.iter().map(|p| p.2 * p.0).sum::<f64>() / w;
    let my = pts.iter().map(|p| p.2 * p.1).sum::<f64>() / w;
    let sxx: f64 = pts.iter().map(|p| p.2 * (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| p.2 * (p.0 - mx) * (p.1 - my)).sum();
    Some(Rate {
        from,
        to,
        rate: sxy / sxx,
        se: (1.0 / sxx).sqrt(),
    })
}

/// The rows of `scene` and `kind` as `(spp, value, se)`, the value picked by `pick`.
fn series(
    rows: &[Row],
    scene: &str,
    kind: Kind,
    pick: impl Fn(&Row) -> (f64, f64),
) -> Vec<(u32, f64, f64)> {
    rows.iter()
        .filter(|r| r.scene == scene && r.kind == kind)
        .map(|r| {
            let (m, se) = pick(r);
            (r.spp, m, se)
        })
        .collect()
}

/// The fitted ranges.
const RANGES: [(u32, u32); 3] = [(4, 1024), (4, 64), (64, 1024)];

/// The rates of every (scene, sampler) with more than one count: whole MSE.
pub fn rates(rows: &[Row]) -> Vec<(String, Kind, Rate)> {
    let mut keys: Vec<(String, Kind)> = Vec::new();
    for r in rows {
        if !keys.iter().any(|k| k.0 == r.scene && k.1 == r.kind) {
            keys.push((r.scene.clone(), r.kind));
        }
    }
    let mut out = Vec::new();
    for (scene, kind) in keys {
        let pts = series(rows, &scene, kind, |r| r.mse);
        for (a, b) in RANGES {
            if let Some(rate) = fit(&pts, a, b) {
                out.push((scene.clone(), kind, rate));
            }
        }
    }
    out
}

fn row<'a>(rows: &'a [Row], scene: &str, kind: Kind, spp: u32) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.scene == scene && r.kind == kind && r.spp == spp)
}

/// RMSE ratio `a / b` and its standard error (independent).
fn ratio(a: &Row, b: &Row) -> (f64, f64) {
    let ((ra, sa), (rb, sb)) = (a.rmse(), b.rmse());
    let q = ra / rb;
    (q, q * ((sa / ra).powi(2) + (sb / rb).powi(2)).sqrt())
}

/// Ratio `a / b` of two independent estimates `(value, standard error)` and its standard
/// error.
fn mse_ratio(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    let q = a.0 / b.0;
    (q, q * ((a.1 / a.0).powi(2) + (b.1 / b.0).powi(2)).sqrt())
}

/// `path-glossy.md`: per roughness and pixel sampler, the MSE of `ggx_reflect_bounded` and of
/// the cosine hemisphere over `ggx_reflect`'s (caps) at each count, standard errors in
/// brackets; empty without glossy rows.
pub fn glossy_markdown(rows: &[Row]) -> String {
    glossy_table(rows, "", "5 scattering events")
        + &glossy_table(rows, "/direct", "one scattering event (direct lighting)")
}

/// [`glossy_markdown`]'s table of the scenes `glossy-a<alpha>/<sampler><suffix>`.
fn glossy_table(rows: &[Row], suffix: &str, what: &str) -> String {
    let mut s = String::new();
    let name = |a: &str, g: &str| format!("glossy-a{a}/{g}{suffix}");
    let Some(first) = GLOSSY_ALPHAS
        .iter()
        .find_map(|a| rows.iter().find(|r| r.scene == name(a, "caps")))
    else {
        return s;
    };
    let side = (first.pixels as f64).sqrt();
    let _ = writeln!(
        s,
        "\n`glossy-a<alpha>/<sampler>{suffix}`, {what}: MSE of the scattered light (variance over {} frames of {side} x {side} pixels of the estimate without the emitter seen directly, which no BSDF sampler changes; NEE and BSDF sampling under MIS) of the BSDF samplers over `ggx_reflect`'s (caps), standard errors in brackets; bold: beyond 2 standard errors from 1. The last columns: the caps sampler's MSE of the scattered light.\n",
        first.frames
    );
    let cols: Vec<String> = GLOSSY_SPPS.iter().map(|n| format!("{n} spp")).collect();
    let _ = writeln!(
        s,
        "| alpha | pixel sampler | bounded / caps: {} | cosine / caps: {} | caps MSE: {} |\n|---:|---|{}",
        cols.join(" | "),
        cols.join(" | "),
        cols.join(" | "),
        "---:|".repeat(3 * GLOSSY_SPPS.len())
    );
    let cell = |a: Option<&Row>, b: Option<&Row>| match (a, b) {
        (Some(a), Some(b)) => {
            let q = mse_ratio(a.scattered, b.scattered);
            if (q.0 - 1.0).abs() > 2.0 * q.1 {
                format!(" **{}** |", pm(q, 2))
            } else {
                format!(" {} |", pm(q, 2))
            }
        }
        _ => " - |".to_string(),
    };
    for a in GLOSSY_ALPHAS {
        for kind in GLOSSY_KINDS {
            let c = |g: &str, spp| row(rows, &name(a, g), kind, spp);
            if GLOSSY_SPPS.iter().all(|&n| c("caps", n).is_none()) {
                continue;
            }
            let _ = write!(s, "| {a} | {} |", kind.name());
            for g in ["bounded", "cosine"] {
                for &n in &GLOSSY_SPPS {
                    s.push_str(&cell(c(g, n), c("caps", n)));
                }
            }
            for &n in &GLOSSY_SPPS {
                let caps = c("caps", n).map_or("-".into(), |r| format!("{:.2e}", r.scattered.0));
                let _ = write!(s, " {caps} |");
            }
            let _ = writeln!(s);
        }
    }
    s
}

/// Rows for `results.csv` (warp `path`; the MSE is the variance over frames).
pub fn results_csv_rows(rows: &[Row]) -> String {
    rows.iter()
        .map(|r| super::csv_row(&r.scene, r.kind, r.spp, r.mse.0, r.ns_per_sample()))
        .collect()
}

/// `path-study.csv`: every row with its standard error and the variance by path length.
pub fn study_csv(rows: &[Row]) -> String {
    let mut s = String::from("scene,sampler,spp,frames,pixels,mse,mse_se,frame_ms");
    for k in 0..=MAX_LENGTH {
        let _ = write!(s, ",var_length{k},var_length{k}_se");
    }
    s.push('\n');
    for r in rows {
        let mut cols = vec![
            r.scene.clone(),
            r.kind.name().to_string(),
            r.spp.to_string(),
            r.frames.to_string(),
            r.pixels.to_string(),
            format!("{:.6e}", r.mse.0),
            format!("{:.3e}", r.mse.1),
            format!("{:.3}", r.frame_s * 1e3),
        ];
        cols.extend(
            r.by_length
                .iter()
                .flat_map(|(m, se)| [format!("{m:.4e}"), format!("{se:.2e}")]),
        );
        s.push_str(&cols.join(","));
        s.push('\n');
    }
    s
}

/// `path-rates.csv`.
pub fn rates_csv(rows: &[Row]) -> String {
    let mut s = String::from("scene,sampler,from_spp,to_spp,mse_rate,mse_rate_se\n");
    for (scene, kind, r) in rates(rows) {
        let _ = writeln!(
            s,
            "{scene},{},{},{},{:.4},{:.4}",
            kind.name(),
            r.from,
            r.to,
            r.rate,
            r.se
        );
    }
    s
}

fn pm(x: (f64, f64), digits: usize) -> String {
    format!("{:.*} ({:.*})", digits, x.0, digits, x.1)
}

/// `path-study.md`: the Burley table, the ablations, the split by path length, the rates.
pub fn markdown(rows: &[Row]) -> String {
    let mut s = String::new();
    // Burley 2020.
    let owen = Kind::SobolBurley;
    let mut head = true;
    for (what, scene, spp, paper) in PAPER {
        let Some(o) = row(rows, scene, owen, spp) else {
            continue;
        };
        if head {
            let _ = writeln!(
                s,
                "RMSE relative to Owen-scrambled Sobol' (`sobol_burley`, Burley's own crate) at the paper's counts; ours (standard error in brackets) / Burley 2020 Figure 1. Our RMSE (variance over {} frames of {} x {} pixels) in the last column.\n",
                o.frames,
                (o.pixels as f64).sqrt(),
                (o.pixels as f64).sqrt()
            );
            let _ = writeln!(
                s,
                "| configuration | spp | independent | Laine-Karras | Sobol'-RDS | Sobol'-enum | Owen-Sobol' | warpcore `sobol` | Laine-Karras, shuffled | RMSE of Owen-Sobol' (ours / paper) |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
            );
            head = false;
        }
        let _ = write!(s, "| {what} (`{scene}`) | {spp} |");
        for (i, kind) in COLUMNS.iter().enumerate() {
            if let Some(r) = row(rows, scene, *kind, spp) {
                let q = ratio(r, o);
                let p = paper
                    .get(i)
                    .map_or("-".to_string(), |p| format!("{:.2}", p / paper[4]));
                let _ = write!(s, " {} / {p} |", pm(q, 2));
            } else {
                let _ = write!(s, " - |");
            }
        }
        let _ = writeln!(s, " {:.2e} / {} |", o.rmse().0, paper[4]);
    }
    // Ablations: random over sobol.
    let variants: Vec<&str> = ABLATIONS
        .iter()
        .map(|a| a.0)
        .filter(|v| rows.iter().any(|r| r.scene == *v))
        .collect();
    if !variants.is_empty() {
        let spps: Vec<u32> = {
            let mut v: Vec<u32> = rows
                .iter()
                .filter(|r| r.scene == variants[0])
                .map(|r| r.spp)
                .collect();
            v.sort_unstable();
            v.dedup();
            v
        };
        let _ = write!(
            s,
            "\nAblations: RMSE of `random` over `sobol` (warpcore) per sample count, standard error in brackets; MSE rate of `sobol` from 64 spp:\n\n| variant |"
        );
        for spp in &spps {
            let _ = write!(s, " {spp} spp |");
        }
        let _ = writeln!(
            s,
            " `sobol` rate 64+ |\n|---|{}---:|",
            "---:|".repeat(spps.len())
        );
        for v in &variants {
            let _ = write!(s, "| `{v}` |");
            for &spp in &spps {
                match (
                    row(rows, v, Kind::Random, spp),
                    row(rows, v, Kind::Sobol, spp),
                ) {
                    (Some(a), Some(b)) => {
                        let _ = write!(s, " {} |", pm(ratio(a, b), 2));
                    }
                    _ => {
                        let _ = write!(s, " - |");
                    }
                }
            }
            let pts = series(rows, v, Kind::Sobol, |r| r.mse);
            let rate = fit(&pts, 64, 1024).map_or("-".into(), |r| pm((r.rate, r.se), 2));
            let _ = writeln!(s, " {rate} |");
        }
        // The split by path length.
        let _ = writeln!(
            s,
            "\nThe variance by path length (scattering events; 5 holds 5 and the rest) at the top count: share of the summed variances per sampler, and the MSE rate of each length over 64 spp and up (standard errors in brackets):\n\n| variant | sampler | spp | {} |\n|---|---|---:|{}",
            (0..=MAX_LENGTH)
                .map(|k| format!("length {k}"))
                .collect::<Vec<_>>()
                .join(" | "),
            "---:|".repeat(MAX_LENGTH + 1)
        );
        let top = *spps.last().unwrap_or(&1);
        for v in &variants {
            for kind in SPLIT_KINDS.into_iter().chain(BURLEY_KINDS) {
                let Some(r) = row(rows, v, kind, top) else {
                    continue;
                };
                let total: f64 = r.by_length.iter().map(|x| x.0).sum();
                let _ = write!(s, "| `{v}` | {} | {top} |", kind.name());
                for k in 0..=MAX_LENGTH {
                    let pts = series(rows, v, kind, |r| r.by_length[k]);
                    let rate = fit(&pts, 64, 1024).map_or("-".into(), |r| pm((r.rate, r.se), 2));
                    let _ = write!(
                        s,
                        " {:.0}%, {rate} |",
                        100.0 * r.by_length[k].0 / total.max(1e-300)
                    );
                }
                let _ = writeln!(s);
            }
        }
        // Rates.
        let _ = writeln!(
            s,
            "\nMSE rates (slope of ln MSE over ln spp, weighted least squares, standard error in brackets):\n\n| variant | sampler | 4-1024 | 4-64 | 64-1024 |\n|---|---|---:|---:|---:|"
        );
        let all = rates(rows);
        for v in &variants {
            let mut kinds: Vec<Kind> = Vec::new();
            for (sc, k, _) in &all {
                if sc == v && !kinds.contains(k) {
                    kinds.push(*k);
                }
            }
            for k in kinds {
                let _ = write!(s, "| `{v}` | {} |", k.name());
                for (a, b) in RANGES {
                    let cell = all
                        .iter()
                        .find(|(sc, kk, r)| sc == v && *kk == k && r.from == a && r.to == b)
                        .map_or("-".into(), |(_, _, r)| pm((r.rate, r.se), 2));
                    let _ = write!(s, " {cell} |");
                }
                let _ = writeln!(s);
            }
        }
    }
    s
}

/// Runs the study's `cases`, writes `path-study.csv`, `path-rates.csv` and `path-study.md`
/// into `out`; returns the rows.
pub fn run(
    cases: &[Case],
    threads: usize,
    out: &Path,
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    if cases.is_empty() {
        return Ok(Vec::new());
    }
    let t = Instant::now();
    let rows = measure(cases, threads)?;
    crate::output::write(&out.join("path-study.csv"), &study_csv(&rows))?;
    crate::output::write(&out.join("path-rates.csv"), &rates_csv(&rows))?;
    let md = markdown(&rows);
    crate::output::write(&out.join("path-study.md"), &md)?;
    let glossy = glossy_markdown(&rows);
    if !glossy.is_empty() {
        crate::output::write(&out.join("path-glossy.md"), &glossy)?;
        print!("{glossy}");
    }
    // The pictures of Burley's configurations (warpcore `sobol`, 64 spp, one frame).
    let pictures: Vec<Image> = cases
        .iter()
        .filter(|c| PAPER.iter().any(|p| p.1 == c.scene))
        .filter_map(|c| Scene::by_name(&c.scene, c.size))
        .map(|scene| super::render(&scene, Kind::Sobol, 64, 1).0)
        .collect();
    super::pictures::save_images(&out.join("path-study-scenes.png"), &pictures)?;
    print!("{md}");
    eprintln!(
        "path study: {} rows in {:.1} s",
        rows.len(),
        t.elapsed().as_secs_f64()
    );
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers a known slope, and its standard error shrinks with the points'.
    #[test]
    fn fit_recovers_a_power_law() {
        let pts: Vec<(u32, f64, f64)> = [4u32, 16, 64, 256, 1024]
            .iter()
            .map(|&n| {
                (
                    n,
                    3.0 * (n as f64).powf(-1.5),
                    0.01 * 3.0 * (n as f64).powf(-1.5),
                )
            })
            .collect();
        let r = fit(&pts, 4, 1024).unwrap();
        assert!((r.rate + 1.5).abs() < 1e-9, "{r:?}");
        // 1% per point over ln 4 steps: the slope's standard error is about 0.005.
        assert!(r.se > 0.002 && r.se < 0.01, "{r:?}");
        assert!(fit(&pts, 64, 64).is_none());
    }
}
