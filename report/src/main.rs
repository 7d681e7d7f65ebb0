//! The error-versus-run-time report: for every scene, sampler and warp, the mean squared
//! error of a renderer's estimate against an exact reference at 4 to 1024 samples per pixel,
//! the fitted convergence rate, and the time to draw and warp the samples.
//!
//! `cargo run-report` (an alias of `cargo run --release -p warpcore-report --bin report --`;
//! add `--help` for the options): the study at reduced pixel counts (a few minutes on 2 cores)
//! into `target/report/`: `results.csv`, `details.csv`, `tables.md`, `recommendations.md`, one
//! SVG plot per scene and the strata pictures (and, for the environment maps, the variance
//! split and the orientation study, `envmap_orientation.*`); the recommendations table last
//! on stdout. `--full`: the whole study into `docs/report/`, pasted into `docs/REPORT.md`
//! (a reading of the results); `--quick`: a smoke run.

use clap::{Arg, ArgAction, Command, value_parser};
use std::path::PathBuf;
use warpcore_report::*;

/// A flag `--name` (no value).
fn flag(name: &'static str, help: &'static str) -> Arg {
    Arg::new(name)
        .long(name)
        .action(ArgAction::SetTrue)
        .help(help)
}

/// The command line.
fn command() -> Command {
    Command::new("report")
        .about(
            "Error versus run time for every sampler x warp of warpcore, against exact references",
        )
        .arg(flag("quick", "fewer pixels and shorter timings (a smoke run, under 15 s)"))
        .arg(flag("full", "the whole study at the committed page's pixel counts, with the photographed maps (6 to 13 minutes on 2 cores); writes docs/report and pastes it into docs/REPORT.md unless --out says otherwise").conflicts_with("quick"))
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("DIR")
                .value_parser(value_parser!(PathBuf))
                .help("output directory [default: target/report; --full: docs/report]; docs/report only with --full"),
        )
        .arg(
            Arg::new("pixels")
                .long("pixels")
                .value_name("N")
                .value_parser(value_parser!(usize))
                .help("pixels per class (lit, penumbra) of each area-light scene [default: 8192; quick: 1024; full: 32768]"),
        )
        .arg(
            Arg::new("max-spp")
                .long("max-spp")
                .value_name("N")
                .value_parser(value_parser!(usize))
                .help("largest sample count; runs the powers of 4 from 4 up to it [default: 256]"),
        )
        .arg(
            Arg::new("threads")
                .long("threads")
                .value_name("N")
                .value_parser(value_parser!(usize))
                .help(
                    "threads for the error runs (timings are single-threaded) [default: all cores]",
                ),
        )
        .arg(
            Arg::new("envmap")
                .long("envmap")
                .value_name("PATH.pfm")
                .value_parser(value_parser!(PathBuf))
                .action(ArgAction::Append)
                .help(
                    "add a lat-long PFM environment map as scene envmap:<file stem> (repeatable)",
                ),
        )
        .arg(
            Arg::new("env-pixels")
                .long("env-pixels")
                .value_name("N")
                .value_parser(value_parser!(usize))
                .help("pixels per class (with and without the occluder) of each environment-map scene [default: 1536; quick: 192; full: 6144]"),
        )
        .arg(
            Arg::new("scene")
                .long("scene")
                .value_name("PREFIX")
                .action(ArgAction::Append)
                .help("run only scenes whose name starts with PREFIX (repeatable; see the valid names in an error message)"),
        )
        .arg(flag("orientation-only", "run only the environment-map orientation study (envmap_orientation.csv/.md: each map as authored and rotated; --scene and --env-pixels apply)"))
        .arg(flag("path-study-only", "run only the path study (Burley 2020's Cornell boxes, the cornell ablations, the rate fits: path-study.csv/.md, path-rates.csv; its rows replace their scenes' in results.csv; --scene applies)"))
        .arg(flag("reference", "re-render the path scenes' cached references (docs/report/path-*.ref; about a minute each on 2 cores)"))
}

/// A command line that fails before any work: clap's own errors (help, version, a value
/// that is no number) or ours, each a message for the user and exit code 2.
pub enum CliError {
    Clap(clap::Error),
    Invalid(String),
}

/// Limits on the counts (a value outside is a mistake, not a request).
const MAX_PIXELS: usize = 1 << 22;
const MAX_ENV_PIXELS: usize = 1 << 20;
const MAX_SPP: usize = 1 << 16;
const MAX_THREADS: usize = 1024;

fn count(
    m: &clap::ArgMatches,
    name: &str,
    lo: usize,
    hi: usize,
) -> Result<Option<usize>, CliError> {
    match m.get_one::<usize>(name).copied() {
        Some(n) if n < lo || n > hi => Err(CliError::Invalid(format!(
            "--{name} {n}: must be between {lo} and {hi}"
        ))),
        v => Ok(v),
    }
}

/// Parses and checks the arguments (`args[0]` is the program name): unknown scenes, counts
/// out of range and unreadable or malformed `--envmap` files are refused here, before any
/// scene runs.
pub fn parse<I, T>(args: I) -> Result<app::Options, CliError>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let m = command()
        .try_get_matches_from(args)
        .map_err(CliError::Clap)?;
    let mut opts = app::Options {
        quick: m.get_flag("quick"),
        full: m.get_flag("full"),
        ..app::Options::default()
    };
    if let Some(out) = m.get_one::<PathBuf>("out") {
        opts.out = out.clone();
    } else if opts.full {
        opts.out = app::docs_report();
    }
    opts.pixels = count(&m, "pixels", 1, MAX_PIXELS)?;
    opts.env_pixels = count(&m, "env-pixels", 1, MAX_ENV_PIXELS)?;
    opts.envmaps = m
        .get_many::<PathBuf>("envmap")
        .map(|v| v.cloned().collect())
        .unwrap_or_default();
    if let Some(n) = count(&m, "max-spp", 4, MAX_SPP)? {
        opts.max_spp = n;
    }
    if let Some(n) = count(&m, "threads", 1, MAX_THREADS)? {
        opts.threads = n;
    }
    opts.reference = m.get_flag("reference");
    opts.orientation_only = m.get_flag("orientation-only");
    opts.path_study_only = m.get_flag("path-study-only");
    opts.scenes = m
        .get_many::<String>("scene")
        .map(|v| v.cloned().collect())
        .unwrap_or_default();
    opts.check().map_err(CliError::Invalid)?;
    Ok(opts)
}

fn main() {
    let opts = match parse(std::env::args_os()) {
        Ok(o) => o,
        Err(CliError::Clap(e)) => e.exit(),
        Err(CliError::Invalid(msg)) => {
            eprintln!("report: {msg}");
            std::process::exit(2);
        }
    };
    if let Err(e) = app::run(&opts) {
        eprintln!("report: {e}");
        std::process::exit(1);
    }
}

#[cfg(test)]
mod cli_tests {
    use super::*;

    fn err(args: &[&str]) -> String {
        match parse(std::iter::once("report").chain(args.iter().copied())) {
            Ok(_) => panic!("{args:?} was accepted"),
            Err(CliError::Invalid(m)) => m,
            Err(CliError::Clap(e)) => {
                assert_eq!(e.exit_code(), 2, "{args:?}");
                e.to_string()
            }
        }
    }

    #[test]
    fn valid_command_lines_parse() {
        for args in [
            &[][..],
            &["--quick"],
            &["--scene", "cornell"],
            &["--scene", "cornell-disk", "--scene", "disk/lit"],
            &["--scene", "square", "--max-spp", "64", "--pixels", "16"],
            &["--scene", "envmap:sky"],
            &["--threads", "1", "--reference", "--scene", "corn"],
            &["--orientation-only", "--scene", "envmap:park"],
            &["--path-study-only", "--scene", "burley"],
            &["--scene", "cornell/rr-off"],
            &["--full", "--scene", "square"],
            &["--full", "--out", "target/report-full"],
        ] {
            assert!(
                parse(std::iter::once("report").chain(args.iter().copied())).is_ok(),
                "{args:?}"
            );
        }
    }

    #[test]
    fn only_the_full_study_writes_the_committed_page() {
        let docs = app::docs_report();
        let docs = docs.to_str().unwrap();
        assert!(err(&["--out", docs]).contains("--full"));
        assert!(err(&["--quick", "--out", docs]).contains("--full"));
        err(&["--quick", "--full"]);
        let full = parse(["report", "--full"]).ok().unwrap();
        assert_eq!(full.out, app::docs_report());
    }

    #[test]
    fn unknown_scenes_name_the_valid_ones() {
        let m = err(&["--scene", "nonsense"]);
        assert!(
            m.contains("nonsense") && m.contains("cornell-disk") && m.contains("square"),
            "{m}"
        );
        assert!(err(&["--scene", "cornell", "--scene", "x"]).contains("\"x\""));
    }

    #[test]
    fn zero_and_absurd_counts_are_refused() {
        for (flag, v) in [
            ("--max-spp", "0"),
            ("--max-spp", "3"),
            ("--max-spp", "99999999"),
            ("--pixels", "0"),
            ("--pixels", "100000000"),
            ("--env-pixels", "0"),
            ("--threads", "0"),
            ("--max-spp", "many"),
        ] {
            let m = err(&[flag, v]);
            assert!(m.contains(flag), "{flag} {v}: {m}");
        }
        // clap reads "-1" as an unknown flag: still an error (exit code 2, checked in err).
        err(&["--pixels", "-1"]);
    }

    #[cfg(feature = "envmap")]
    #[test]
    fn unreadable_or_malformed_maps_are_refused() {
        let m = err(&["--envmap", "/nonexistent/map.pfm"]);
        assert!(m.contains("/nonexistent/map.pfm"), "{m}");
        let dir = std::env::temp_dir().join(format!("warpcore-cli-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bad = dir.join("bad.pfm");
        std::fs::write(&bad, b"P6\n2 2\n255\nxxxxxxxxxxxx").unwrap();
        let m = err(&["--envmap", bad.to_str().unwrap()]);
        assert!(m.contains("bad.pfm"), "{m}");
        // A PFM header whose pixel data is cut short.
        let short = dir.join("short.pfm");
        let mut bytes = b"PF\n4 2\n-1.0\n".to_vec();
        bytes.extend(std::iter::repeat_n(0u8, 4 * 2 * 3 * 4 - 5));
        std::fs::write(&short, &bytes).unwrap();
        let m = err(&["--envmap", short.to_str().unwrap()]);
        assert!(m.contains("short.pfm"), "{m}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
