//! The error-versus-run-time report: for every scene, sampler and warp, the mean squared
//! error of a renderer's estimate against an exact reference at 4 to 1024 samples per pixel,
//! the fitted convergence rate, and the time to draw and warp the samples.
//!
//! `cargo run --release --example report` (add `-- --help` for the options). Writes
//! `target/report/results.csv`, `details.csv`, `tables.md`, one SVG plot per scene and the
//! strata pictures; see `docs/REPORT.md` for a reading of the results.

mod app;
mod area;
#[cfg(feature = "envmap")]
mod envscene;
mod math;
mod output;
#[cfg(feature = "envmap")]
#[path = "../../tests/common/pfm.rs"]
mod pfm;
mod plots;
mod run;
mod samplers;
#[cfg(feature = "spherical")]
mod solid_angle;
#[cfg(feature = "envmap")]
mod sphere_ref;
mod strata;
#[cfg(feature = "envmap")]
mod strata_env;

use clap::{Arg, ArgAction, Command, value_parser};
use std::path::PathBuf;

fn main() {
    let m = Command::new("report")
        .about(
            "Error versus run time for every sampler x warp of warpcore, against exact references",
        )
        .arg(
            Arg::new("quick")
                .long("quick")
                .action(ArgAction::SetTrue)
                .help("fewer pixels and shorter timings (a smoke run, under 15 s)"),
        )
        .arg(
            Arg::new("out")
                .long("out")
                .value_name("DIR")
                .value_parser(value_parser!(PathBuf))
                .help("output directory [default: target/report]"),
        )
        .arg(
            Arg::new("pixels")
                .long("pixels")
                .value_name("N")
                .value_parser(value_parser!(usize))
                .help("pixels per class (lit, penumbra) of each area-light scene [default: 32768; quick: 1024]"),
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
                .help("pixels per class (with and without the occluder) of each environment-map scene [default: 6144; quick: 192]"),
        )
        .arg(
            Arg::new("scene")
                .long("scene")
                .value_name("PREFIX")
                .action(ArgAction::Append)
                .help("run only scenes whose name starts with PREFIX (repeatable)"),
        )
        .get_matches();
    let mut opts = app::Options {
        quick: m.get_flag("quick"),
        ..app::Options::default()
    };
    if let Some(out) = m.get_one::<PathBuf>("out") {
        opts.out = out.clone();
    }
    opts.pixels = m.get_one::<usize>("pixels").copied();
    opts.env_pixels = m.get_one::<usize>("env-pixels").copied();
    opts.envmaps = m
        .get_many::<PathBuf>("envmap")
        .map(|v| v.cloned().collect())
        .unwrap_or_default();
    if let Some(&n) = m.get_one::<usize>("max-spp") {
        opts.max_spp = n;
    }
    if let Some(&n) = m.get_one::<usize>("threads") {
        opts.threads = n;
    }
    opts.scenes = m
        .get_many::<String>("scene")
        .map(|v| v.cloned().collect())
        .unwrap_or_default();
    if let Err(e) = app::run(&opts) {
        eprintln!("report: {e}");
        std::process::exit(1);
    }
}
