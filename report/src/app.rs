//! The report as a function of its options: runs every scene, prints the tables, writes the
//! CSV files, the plots and the strata pictures.

use crate::area::{self, AreaScene};
#[cfg(feature = "envmap")]
use crate::envscene::EnvScene;
use crate::output;
use crate::plots;
use crate::run::{self, Config, Scale, Scene, SceneResult};
use crate::strata;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

#[derive(Clone, Debug)]
pub struct Options {
    /// Fewer pixels and shorter timings: a smoke run (under 15 s).
    pub quick: bool,
    /// The whole study at the committed page's pixel counts (`docs/REPORT.md`); neither
    /// flag: the same scenes at a quarter of the pixels, without the photographed maps.
    pub full: bool,
    pub out: PathBuf,
    /// Pixels per class of an area-light scene (quick 1024, default 8192, full 32768).
    pub pixels: Option<usize>,
    /// Pixels per class of an environment-map scene (quick 192, default 1536, full 6144).
    pub env_pixels: Option<usize>,
    /// Extra lat-long PFM maps, scenes `envmap:<stem>`.
    pub envmaps: Vec<PathBuf>,
    /// Largest sample count: powers of 4 from 4 up to it (default 256).
    pub max_spp: usize,
    pub threads: usize,
    /// Only scenes whose name starts with one of these (all when empty).
    pub scenes: Vec<String>,
    /// Re-render the path scenes' cached references.
    pub reference: bool,
    /// Run only the environment-map orientation study (`envmap_orientation.*`).
    pub orientation_only: bool,
    /// Run only the path study (`path-study.*`, `path-rates.csv`; `path::study`).
    pub path_study_only: bool,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            quick: false,
            full: false,
            out: PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("target/report"),
            pixels: None,
            env_pixels: None,
            envmaps: Vec::new(),
            max_spp: 256,
            threads: std::thread::available_parallelism().map_or(2, |n| n.get()),
            scenes: Vec::new(),
            reference: false,
            orientation_only: false,
            path_study_only: false,
        }
    }
}

impl Options {
    pub fn spps(&self) -> Vec<usize> {
        std::iter::successors(Some(4usize), |n| n.checked_mul(4))
            .take_while(|&n| n <= self.max_spp.max(4))
            .collect()
    }

    /// Every scene name `--scene` may select (by prefix).
    pub fn scene_names(&self) -> Vec<String> {
        let mut names = Vec::new();
        for s in AreaScene::all() {
            if !names.contains(&s.light.to_string()) {
                names.push(s.light.to_string());
            }
            names.push(s.name());
        }
        #[cfg(feature = "spherical")]
        for s in crate::solid_angle::SolidAngleScene::all() {
            if !names.contains(&s.light_name()) {
                names.push(s.light_name());
            }
            names.push(s.name());
        }
        #[cfg(feature = "envmap")]
        {
            names.push("envmap:sky".into());
            names.push("envmap:interior".into());
            names.push("envmap:sky_200x100".into());
            for p in self.envmaps.iter().chain(&real_envmaps()) {
                let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
                names.push(format!("envmap:{}", stem.unwrap_or_else(|| "map".into())));
            }
        }
        #[cfg(feature = "lights")]
        names.push("many_lights".into());
        names.extend(crate::path::scene::Scene::NAMES.map(String::from));
        names.extend(crate::path::study::PAPER.map(|p| p.1.to_string()));
        names.extend(crate::path::study::ABLATIONS.map(|a| a.0.to_string()));
        names.extend(crate::path::study::glossy_scenes());
        names
    }

    /// The checks made before any work (`main` exits with code 2 on an error): only the full
    /// study writes the committed `docs/report`, every `--scene` prefix selects some scene,
    /// every `--envmap` file reads as a usable map.
    pub fn check(&self) -> Result<(), String> {
        if !self.full_study() && writes_docs(&self.out) {
            return Err(format!(
                "--out {}: the committed report is the full study; add --full",
                self.out.display()
            ));
        }
        let names = self.scene_names();
        for s in &self.scenes {
            if !names.iter().any(|n| n.starts_with(s.as_str())) {
                return Err(format!(
                    "--scene {s:?} selects no scene; the scenes (any prefix selects): {}",
                    names.join(", ")
                ));
            }
        }
        #[cfg(feature = "envmap")]
        for path in &self.envmaps {
            load_envmap(path, 1).map_err(|e| format!("--envmap: {e}"))?;
        }
        #[cfg(not(feature = "envmap"))]
        if !self.envmaps.is_empty() {
            return Err("--envmap: this build has no envmap feature".into());
        }
        Ok(())
    }

    /// How much of the study this run computes (`--quick` wins over `--full`).
    pub fn scale(&self) -> Scale {
        match (self.quick, self.full) {
            (true, _) => Scale::Quick,
            (false, false) => Scale::Default,
            (false, true) => Scale::Full,
        }
    }

    /// Pixels per class of an environment-map scene: `--env-pixels`, or 192 / 1536 / 6144.
    #[cfg(feature = "envmap")]
    fn env_pixels(&self) -> usize {
        self.env_pixels
            .unwrap_or(self.scale().pick([192, 1536, 6144]))
    }

    /// Map rotations each environment-map scene's pixels cycle through: 8 (default 4,
    /// quick 2).
    #[cfg(feature = "envmap")]
    pub fn rotations(&self) -> usize {
        self.scale().pick([2, 4, 8])
    }

    /// Pixels per class of the orientation study (`orientation.rs`): the built-in sky and
    /// interior `env_pixels / 4` (1536), the other maps `env_pixels / 6` (1024, as their
    /// scenes); without `--full` (and `--env-pixels`): 32.
    #[cfg(feature = "envmap")]
    pub fn orientation_pixels(&self, builtin: bool) -> usize {
        if !self.full_study() && self.env_pixels.is_none() {
            return 32;
        }
        let p = self.env_pixels();
        (if builtin { p / 4 } else { p / 6 }).max(2)
    }

    /// The side studies (variance split, orientation, strata pictures) at their full sizes.
    fn full_study(&self) -> bool {
        self.scale() == Scale::Full
    }

    /// Pixels per class and grid side of the variance split (`env_split.rs`, and the
    /// orientation study's split): 256 and 128 with `--full`, else 16 and 32.
    #[cfg(feature = "envmap")]
    fn split_sizes(&self) -> (usize, usize) {
        if self.full_study() {
            (256, 128)
        } else {
            (16, 32)
        }
    }

    /// The PFM maps to run as scenes: the real maps of `tests/data/envmaps/` (without
    /// `--full` only when a `--scene` names them) and every `--envmap` file.
    #[cfg(feature = "envmap")]
    fn envmap_files(&self) -> Vec<PathBuf> {
        let named = |p: &PathBuf| {
            let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
            let name = format!("envmap:{}", stem.unwrap_or_default());
            self.scenes
                .iter()
                .any(|s| name.starts_with(s.as_str()) && s.len() > "envmap:".len())
        };
        real_envmaps()
            .into_iter()
            .filter(|p| {
                if self.full_study() {
                    self.wants_name(p)
                } else {
                    named(p)
                }
            })
            .chain(self.envmaps.iter().cloned())
            .collect()
    }

    #[cfg(feature = "envmap")]
    fn wants_name(&self, p: &std::path::Path) -> bool {
        let stem = p.file_stem().map(|s| s.to_string_lossy().into_owned());
        self.wants(&format!("envmap:{}", stem.unwrap_or_default()))
    }

    /// The path scenes to run.
    fn path_scenes(&self) -> Vec<String> {
        crate::path::scene::Scene::NAMES
            .iter()
            .filter(|n| self.wants(n))
            .map(|n| n.to_string())
            .collect()
    }

    /// The path study's cases this run selects.
    fn study_cases(&self) -> Vec<crate::path::study::Case> {
        crate::path::study::cases(self.scale(), |n| self.wants(n))
    }

    fn wants(&self, scene: &str) -> bool {
        self.scenes.is_empty() || self.scenes.iter().any(|s| scene.starts_with(s.as_str()))
    }

    fn config(&self, pixels: usize) -> Config {
        Config {
            pixels,
            spps: self.spps(),
            threads: self.threads.max(1),
            timing_samples: self.scale().pick([1 << 14, 1 << 16, 1 << 18]),
            timing_reps: self.scale().pick([2, 3, 5]),
        }
    }
}

/// The many-light scene's tables (`many_lights.md`): a street image of 48 x 48 points
/// (quick 24 x 24, full 96 x 96): uniform choice, the alias table by power, the light tree.
#[cfg(feature = "lights")]
fn many_lights(opts: &Options) -> std::io::Result<()> {
    use crate::many_lights::{City, LightChooser, Uniform, run};
    use warpcore::lights::{AliasTable, LightTree};
    let side = opts.scale().pick([24, 48, 96]);
    let t = Instant::now();
    let city = City::new(side, side);
    let power: Vec<f32> = city.emitters.iter().map(|e| e.power()).collect();
    let mut storage = vec![0u32; AliasTable::storage_len(power.len())];
    let alias = AliasTable::new(&power, &mut storage).map_err(std::io::Error::other)?;
    let bounds: Vec<_> = city.emitters.iter().map(|e| e.bounds()).collect();
    let mut tree_storage = vec![0u32; LightTree::storage_len(bounds.len())];
    let tree = LightTree::new(&bounds, &mut tree_storage).map_err(std::io::Error::other)?;
    let uniform = Uniform(power.len() as u32);
    let choosers: [&dyn LightChooser; 3] = [&uniform, &alias, &tree];
    let results = run(&city, &choosers, opts.threads.max(1));
    let md = results.markdown();
    print!("{md}");
    println!("(many_lights: {:.1} s)", t.elapsed().as_secs_f64());
    output::write(&opts.out.join("many_lights.md"), &md)
}

fn bar(len: u64, what: &str, name: &str) -> ProgressBar {
    let b = ProgressBar::new(len);
    b.set_style(
        ProgressStyle::with_template(&format!(
            "{{msg:>22}} [{{bar:32}}] {{pos:>6}}/{{len}} {what} {{elapsed}}"
        ))
        .unwrap_or_else(|_| ProgressStyle::default_bar())
        .progress_chars("=> "),
    );
    b.set_message(name.to_string());
    b
}

/// The error runs of one scene (no timings yet).
pub fn measure<S: Scene>(scene: &S, cfg: &Config) -> SceneResult {
    let name = scene.name();
    let b = bar(cfg.pixels as u64, "pixels", &name);
    let result = run::errors(scene, cfg, &b);
    b.finish_and_clear();
    if !std::io::stderr().is_terminal() {
        eprintln!(
            "{name}: {} pixels in {:.1} s",
            result.pixels, result.seconds
        );
    }
    result
}

/// Fills in `result`'s timings by drawing `scene`'s samples, and copies them to `others`
/// (the scene's other pixel classes: the draws do not depend on the pixels).
pub fn time<S: Scene>(
    scene: &S,
    cfg: &Config,
    result: &mut SceneResult,
    others: &mut [&mut SceneResult],
) {
    let name = scene.name();
    let b = bar(result.rows.len() as u64, "timings", &name);
    let t = Instant::now();
    run::timings(scene, cfg, result, &b);
    b.finish_and_clear();
    if !std::io::stderr().is_terminal() {
        eprintln!("{name}: timings in {:.1} s", t.elapsed().as_secs_f64());
    }
    for other in others.iter_mut() {
        for row in other.rows.iter_mut() {
            if let Some(src) = result.row(row.sampler, row.warp) {
                row.ns = src.ns.clone();
            }
        }
    }
}

/// One area light: its `lit` and `penumbra` classes (errors each, timings once) and the mix
/// `<light>` as their weighted sum. Returns `[mix, lit, penumbra]`.
fn area_light(lit: &AreaScene, penumbra: &AreaScene, cfg: &Config) -> [SceneResult; 3] {
    let mut l = measure(lit, cfg);
    let mut p = measure(penumbra, cfg);
    time(lit, cfg, &mut l, &mut [&mut p]);
    let w = area::mix_weights(&lit.shape, lit.id, 1 << 22);
    let description = format!(
        "{}; the original mix of pixels: {:.0}% penumbra, {:.0}% fully lit, {:.0}% fully hidden (error 0), combined from the two classes",
        lit.description().split(';').next().unwrap_or_default(),
        100.0 * w[1],
        100.0 * w[0],
        100.0 * w[2]
    );
    let mix = SceneResult::mix(
        lit.light.to_string(),
        description,
        &[(w[0], &l), (w[1], &p)],
    );
    for r in [&mix, &l, &p] {
        print!("{}", output::terminal(r));
    }
    [mix, l, p]
}

/// The vector instructions this build may use, which the timings depend on.
pub fn build_features() -> String {
    let mut f: Vec<&str> = Vec::new();
    for (on, name) in [
        (cfg!(target_feature = "sse2"), "sse2"),
        (cfg!(target_feature = "sse4.1"), "sse4.1"),
        (cfg!(target_feature = "avx"), "avx"),
        (cfg!(target_feature = "avx2"), "avx2"),
        (cfg!(target_feature = "fma"), "fma"),
        (cfg!(target_feature = "avx512f"), "avx512f"),
        (cfg!(target_feature = "neon"), "neon"),
        (cfg!(target_feature = "simd128"), "simd128"),
    ] {
        if on {
            f.push(name);
        }
    }
    format!(
        "{} build, target features: {}{}",
        std::env::consts::ARCH,
        if f.is_empty() {
            "none".to_string()
        } else {
            f.join(", ")
        },
        if cfg!(debug_assertions) {
            " (debug assertions on)"
        } else {
            ""
        }
    )
}

/// The whole report. Returns the scene results (also written to `opts.out`).
pub fn run(opts: &Options) -> Result<Vec<SceneResult>, Box<dyn std::error::Error>> {
    let start = Instant::now();
    std::fs::create_dir_all(&opts.out)?;
    if opts.orientation_only {
        #[cfg(feature = "envmap")]
        orientation_study(opts, &env_scenes(opts)?)?;
        return only_study(opts, "the orientation study", start);
    }
    if opts.path_study_only {
        let rows = crate::path::study::run(&opts.study_cases(), opts.threads, &opts.out)?;
        let csv = opts.out.join("results.csv");
        let old = std::fs::read_to_string(&csv).unwrap_or_default();
        let scenes: Vec<&str> = rows.iter().map(|r| r.scene.as_str()).collect();
        output::write(
            &csv,
            &(replace_scenes(&old, &scenes) + &crate::path::study::results_csv_rows(&rows)),
        )?;
        return only_study(opts, "the path study", start);
    }
    println!(
        "warpcore report: MSE against exact references at {:?} samples per pixel; timings: {} (set RUSTFLAGS=\"-C target-cpu=native\" for this CPU's vector units), {} threads for the error runs",
        opts.spps(),
        build_features(),
        opts.threads
    );
    let scale = opts.scale();
    let area_pixels = opts.pixels.unwrap_or(scale.pick([1024, 8192, 32768]));
    let mut results = Vec::new();
    let scenes = AreaScene::all();
    for pair in scenes.chunks_exact(2) {
        let (lit, penumbra) = (&pair[0], &pair[1]);
        let light = lit.light;
        if opts.wants(light) || opts.wants(&lit.name()) || opts.wants(&penumbra.name()) {
            results.extend(area_light(lit, penumbra, &opts.config(area_pixels)));
        }
    }
    // Lights by solid angle against by area: lit and penumbra at three distances;
    // 8192 pixels per class (default 2048, quick 256).
    #[cfg(feature = "spherical")]
    {
        let sa = crate::solid_angle::SolidAngleScene::all();
        let cfg = opts.config(opts.pixels.unwrap_or(scale.pick([256, 2048, 8192])));
        for pair in sa.chunks_exact(2) {
            if opts.wants(&pair[0].light_name()) || opts.wants("sa_") {
                let mut l = measure(&pair[0], &cfg);
                let mut p = measure(&pair[1], &cfg);
                time(&pair[0], &cfg, &mut l, &mut [&mut p]);
                for r in [&l, &p] {
                    print!("{}", output::terminal(r));
                }
                results.push(l);
                results.push(p);
            }
        }
    }
    // Many lights: light selection for next-event estimation in a city at night.
    #[cfg(feature = "lights")]
    if opts.wants("many_lights") {
        many_lights(opts)?;
    }
    #[cfg(feature = "envmap")]
    {
        let env_pixels = opts.env_pixels();
        let envs = env_scenes(opts)?;
        for scene in &envs {
            if opts.wants(&scene.name) {
                // The real maps and the 200 x 100 sky: a sixth of the pixels each (the
                // references of 8 maps at full count would double the report's time).
                let builtin = scene.name == "envmap:sky" || scene.name == "envmap:interior";
                let mut cfg = opts.config(if builtin { env_pixels } else { env_pixels / 6 });
                if !builtin {
                    // Their sampling and warping cost is the built-in maps' (same sizes):
                    // shorter timings.
                    cfg.timing_samples /= 8;
                    cfg.timing_reps = cfg.timing_reps.min(3);
                }
                let (cut, lit) = (scene.view(false), scene.view(true));
                let mut c = measure(&cut, &cfg);
                let mut l = measure(&lit, &cfg);
                time(&cut, &cfg, &mut c, &mut [&mut l]);
                for r in [&c, &l] {
                    print!("{}", output::terminal(r));
                }
                results.push(c);
                results.push(l);
            }
        }
        // The variance split per layout: 256 pixels per class, 128 x 128 points
        // (without --full: 16 and 32).
        if !envs.is_empty() {
            let (pixels, grid) = opts.split_sizes();
            let chosen: Vec<&EnvScene> = envs.iter().filter(|s| opts.wants(&s.name)).collect();
            let splits = crate::env_split::run(&chosen, pixels, grid, opts.threads);
            output::write(
                &opts.out.join("variance_split.csv"),
                &crate::env_split::csv(&splits),
            )?;
            output::write(
                &opts.out.join("variance_split.md"),
                &crate::env_split::markdown(&splits, &results, grid),
            )?;
            output::write(
                &opts.out.join("envmap_by_sampler.md"),
                &crate::env_split::by_sampler_markdown(&results),
            )?;
            orientation_study(opts, &envs)?;
        }
        if let Some(interior) = envs.iter().find(|s| s.name == "envmap:interior") {
            let grid = if opts.full_study() { 1024 } else { 128 };
            crate::strata_env::write(interior, &opts.out, grid)?;
        }
    }
    #[cfg(not(feature = "envmap"))]
    if !opts.envmaps.is_empty() || opts.env_pixels.is_some() {
        eprintln!("report: built without the envmap feature: no environment-map scenes");
    }

    // The path-traced scenes: their own CSVs, tables and pictures; their rows
    // join results.csv.
    let path_cfg = crate::path::PathConfig::new(
        opts.path_scenes(),
        scale,
        opts.threads.max(1),
        opts.reference,
    );
    let path_results = crate::path::run(&path_cfg, &opts.out)?;
    // Frames of 1 spp on the path scenes: running mean, EMA, per-frame error.
    #[cfg(feature = "blue-noise")]
    if !path_results.is_empty() {
        let counts: &[u32] = if scale == Scale::Quick {
            &[32]
        } else {
            &[32, 64]
        };
        let md = crate::path::frames::run_frames(
            &path_cfg.scenes,
            path_cfg.size,
            counts,
            scale.pick([1, 2, 40]),
            opts.threads.max(1),
        )?;
        print!("{md}");
        output::write(&opts.out.join("path-frames.md"), &md)?;
    }
    // The path study (Burley 2020's boxes, the ablations, the rates): its rows join too.
    let study = crate::path::study::run(&opts.study_cases(), opts.threads, &opts.out)?;
    let csv = opts.out.join("results.csv");
    output::write(
        &csv,
        &(output::csv(&results)
            + &crate::path::results_csv_rows(&path_results)
            + &crate::path::study::results_csv_rows(&study)),
    )?;
    output::write(
        &opts.out.join("details.csv"),
        &output::details_csv(&results),
    )?;
    let tables: String = format!("Timings: {}.\n\n", build_features())
        + &output::summary_markdown(&results)
        + "\n"
        + &results
            .iter()
            .map(|r| output::markdown(r) + "\n")
            .collect::<String>();
    output::write(&opts.out.join("tables.md"), &tables)?;
    let recommendations = output::recommendations_markdown(&results)
        + &if path_results.is_empty() {
            String::new()
        } else {
            crate::path::recommendations_markdown(&path_results)
        };
    output::write(&opts.out.join("recommendations.md"), &recommendations)?;
    output::write(
        &opts.out.join("comparison.md"),
        &output::comparison_markdown(&results),
    )?;
    for r in &results {
        plots::scene_plot(r, &opts.out)?;
    }
    output::write(&opts.out.join("strata.svg"), &strata::disk_triangle_svg())?;
    paste_into_page(opts)?;
    println!(
        "\nWhich sampler and warp, per light and pixel class ({:?} run; recommendations.md):\n\n{recommendations}",
        opts.scale()
    );
    println!(
        "wrote {} (and details.csv, tables.md, recommendations.md, one SVG plot per scene, strata pictures) in {:.1} s",
        csv.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(results)
}

/// The end of a run of one side study (`--orientation-only`, `--path-study-only`): pastes
/// the page when the output is `docs/report`, says where `what` went.
fn only_study(
    opts: &Options,
    what: &str,
    start: Instant,
) -> Result<Vec<SceneResult>, Box<dyn std::error::Error>> {
    paste_into_page(opts)?;
    println!(
        "wrote {what} to {} in {:.1} s",
        opts.out.display(),
        start.elapsed().as_secs_f64()
    );
    Ok(Vec::new())
}

/// `csv` (a `results.csv`, header first) without the rows of `scenes`.
pub fn replace_scenes(csv: &str, scenes: &[&str]) -> String {
    let mut out = String::new();
    for (i, line) in csv.lines().enumerate() {
        let scene = line.split(',').next().unwrap_or_default();
        if i == 0 || !scenes.contains(&scene) {
            out.push_str(line);
            out.push('\n');
        }
    }
    if out.is_empty() {
        out.push_str("scene,sampler,warp,spp,mse,ns_per_sample\n");
    }
    out
}

/// The repository's `docs`.
fn docs() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("docs")
}

/// The committed report's files, `docs/report` (what `--full` writes by default).
pub fn docs_report() -> PathBuf {
    docs().join("report")
}

/// Is `out` the committed `docs/report`?
fn writes_docs(out: &std::path::Path) -> bool {
    match (out.canonicalize(), docs_report().canonicalize()) {
        (Ok(a), Ok(b)) => a == b,
        _ => false,
    }
}

/// When the output is `docs/report`, pastes the generated files into `docs/REPORT.md`'s
/// marked blocks.
fn paste_into_page(opts: &Options) -> Result<(), Box<dyn std::error::Error>> {
    if writes_docs(&opts.out) {
        let docs = docs();
        let page = docs.join("REPORT.md");
        let text = std::fs::read_to_string(&page)?;
        std::fs::write(&page, output::paste_generated(&text, &docs)?)?;
        println!("pasted the generated tables into {}", page.display());
    }
    Ok(())
}

/// The environment-map scenes `opts` selects (built-in, real maps, `--envmap` files), each
/// over `opts.rotations()` rotations.
#[cfg(feature = "envmap")]
pub fn env_scenes(opts: &Options) -> Result<Vec<EnvScene>, Box<dyn std::error::Error>> {
    let rotations = opts.rotations();
    let mut envs = Vec::new();
    if opts.wants("envmap:sky") || opts.wants("envmap:interior") {
        envs = EnvScene::builtin(rotations);
    }
    if opts.wants("envmap:sky_200x100") {
        envs.extend(EnvScene::sky_200x100(rotations));
    }
    for path in opts.envmap_files() {
        envs.push(load_envmap(&path, rotations)?);
    }
    Ok(envs)
}

/// The orientation study (`orientation.rs`) of the selected environment-map scenes, both
/// pixel classes: `envmap_orientation.csv`, `envmap_orientation_split.csv` and
/// `envmap_orientation.md` in `opts.out`.
#[cfg(feature = "envmap")]
pub fn orientation_study(
    opts: &Options,
    envs: &[EnvScene],
) -> Result<(), Box<dyn std::error::Error>> {
    use crate::orientation;
    let (split_pixels, grid) = opts.split_sizes();
    let mut classes = Vec::new();
    let mut splits = Vec::new();
    for scene in envs.iter().filter(|s| opts.wants(&s.name)) {
        let builtin =
            ["envmap:sky", "envmap:interior", "envmap:sky_200x100"].contains(&scene.name.as_str());
        let group = if builtin { "procedural" } else { "PFM" };
        let pixels =
            opts.orientation_pixels(scene.name == "envmap:sky" || scene.name == "envmap:interior");
        for lit in [false, true] {
            let view = scene.view(lit);
            let t = Instant::now();
            classes.push(orientation::measure(&view, group, pixels, opts.threads));
            splits.push(orientation::split(
                &view,
                group,
                split_pixels,
                grid,
                opts.threads,
            ));
            eprintln!(
                "{}: orientation study, {pixels} pixels in {:.1} s",
                view.name(),
                t.elapsed().as_secs_f64()
            );
        }
    }
    if classes.is_empty() {
        return Ok(());
    }
    output::write(
        &opts.out.join("envmap_orientation.csv"),
        &orientation::csv(&classes),
    )?;
    output::write(
        &opts.out.join("envmap_orientation_split.csv"),
        &orientation::split_csv(&splits),
    )?;
    output::write(
        &opts.out.join("envmap_orientation.md"),
        &orientation::markdown(&classes, &splits, grid),
    )?;
    Ok(())
}

#[cfg(feature = "envmap")]
/// The real environment maps shipped with the tests (CC0, `tests/data/envmaps/README.md`),
/// scenes `envmap:<stem>`.
pub fn real_envmaps() -> Vec<PathBuf> {
    let dir = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/..")).join("tests/data/envmaps");
    ["apartment", "venice", "night", "forest", "park", "sunset"]
        .iter()
        .map(|n| dir.join(format!("{n}.pfm")))
        .filter(|p| p.exists())
        .collect()
}

/// A lat-long PFM map as a scene named by its file stem, over `rotations` rotations.
#[cfg(feature = "envmap")]
pub fn load_envmap(
    path: &std::path::Path,
    rotations: usize,
) -> Result<EnvScene, Box<dyn std::error::Error>> {
    let img = crate::pfm::read(path)?;
    let mut lum = vec![0.0f32; img.rgb.len()];
    warpcore::envmap::image::luminance_slice(&img.rgb, &mut lum);
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "map".into());
    EnvScene::from_latlong(&stem, img.width, img.height, lum, rotations)
        .map_err(|e| format!("{}: {e:?}", path.display()).into())
}

#[cfg(test)]
mod tests {
    /// A scene's old rows go, the others and the header stay.
    #[test]
    fn replace_scenes_keeps_the_other_scenes() {
        let csv = "scene,sampler,warp,spp,mse,ns_per_sample\na,x,path,4,1,1\nb,x,path,4,1,1\na/v,x,path,4,1,1\n";
        assert_eq!(
            super::replace_scenes(csv, &["a"]),
            "scene,sampler,warp,spp,mse,ns_per_sample\nb,x,path,4,1,1\na/v,x,path,4,1,1\n"
        );
        assert!(super::replace_scenes("", &["a"]).starts_with("scene,"));
    }
}
