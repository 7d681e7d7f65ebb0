//! `bluegen`: writes (or checks) warpcore's screen-space blue-noise key tiles.
//!
//! ```text
//! cargo run --release -p bluegen -- [--check] [--out DIR]
//!     [--only sobol|pmj02bn] [--seed S] [--pool N] [--edges T] [--levels L] [--sweeps S] [--rounds R]
//!     [--threshold X] [--weights W1,W2,..]
//! ```
//!
//! For each base pattern (`Sobol`, `Pmj02bn`) it optimises a 64 x 64 tile of 32-bit keys (see
//! [`opt`] for the method) and writes `DIR/blue_{pattern}_64.bin`: little-endian `u32`,
//! row-major, the layout `src/sampler/blue.rs` embeds. `DIR/blue_MANIFEST` records the command
//! and each file's size and FNV-1a 64 hash.
//!
//! `--check` regenerates everything in memory and compares it byte for byte with `DIR`
//! (exit status 1 on any difference): CI runs this, so the committed tiles are exactly what
//! the command in the manifest produces from the library's current points. Defaults:
//! `--out src/tables` (run from the repository root) and the settings of [`Params`] below.

mod opt;

use opt::{Base, Params};
use pmjgen::tool::{fnv1a64, write_or_check};
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

struct Args {
    out: PathBuf,
    only: Option<Base>,
    params: Params,
    check: bool,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        out: PathBuf::from("src/tables"),
        only: None,
        params: Params {
            seed: 20190728,
            pool: 16384,
            edges: 256,
            levels: 5,
            sweeps: 12,
            rounds: 0,
            threshold: 0.0,
            weights: vec![1.0, 1.0, 1.0, 0.85, 0.7],
        },
        check: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        let p = &mut a.params;
        fn num<T: std::str::FromStr>(flag: &str, v: String) -> Result<T, String>
        where
            T::Err: std::fmt::Display,
        {
            v.parse().map_err(|e| format!("{flag}: {e}"))
        }
        match flag.as_str() {
            "--out" => a.out = PathBuf::from(value()?),
            "--only" => {
                a.only = Some(match value()?.as_str() {
                    "sobol" => Base::Sobol,
                    "pmj02bn" => Base::Pmj02bn,
                    other => return Err(format!("--only: unknown pattern {other}")),
                })
            }
            "--seed" => p.seed = num(&flag, value()?)?,
            "--pool" => p.pool = num(&flag, value()?)?,
            "--edges" => p.edges = num(&flag, value()?)?,
            "--levels" => p.levels = num(&flag, value()?)?,
            "--sweeps" => p.sweeps = num(&flag, value()?)?,
            "--rounds" => p.rounds = num(&flag, value()?)?,
            "--threshold" => p.threshold = num(&flag, value()?)?,
            "--weights" => {
                p.weights = value()?
                    .split(',')
                    .map(|w| num(&flag, w.to_string()))
                    .collect::<Result<_, _>>()?
            }
            "--check" => a.check = true,
            _ => return Err(format!("unknown argument {flag}")),
        }
    }
    let p = &a.params;
    if p.edges == 0 || !p.edges.is_multiple_of(8) {
        return Err("--edges must be a positive multiple of 8".into());
    }
    if p.pool < opt::TILE * opt::TILE || p.levels == 0 || p.levels > 8 {
        return Err("--pool must be at least 4096, --levels in 1..=8".into());
    }
    Ok(a)
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("bluegen: {e}");
            return ExitCode::from(2);
        }
    };
    let p = &args.params;
    let settings = format!(
        "--seed {} --pool {} --edges {} --levels {} --sweeps {} --rounds {} --threshold {} \
         --weights {}",
        p.seed,
        p.pool,
        p.edges,
        p.levels,
        p.sweeps,
        p.rounds,
        p.threshold,
        p.weights
            .iter()
            .map(|w| w.to_string())
            .collect::<Vec<_>>()
            .join(",")
    );
    let mut manifest = format!(
        "# warpcore blue-noise key tiles: 64 x 64 little-endian u32 keys, row-major.\n\
         # Written by `cargo run --release -p bluegen -- {settings}`.\n\
         # file bytes fnv1a64\n"
    );
    let mut files = Vec::new();
    let start = Instant::now();
    for base in [Base::Sobol, Base::Pmj02bn] {
        if args.only.is_some_and(|o| o != base) {
            continue;
        }
        let t = Instant::now();
        let (tile, report) = opt::optimise(base, p);
        let show = |r: &[f64]| {
            r.iter()
                .map(|x| format!("{x:.3}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        eprintln!(
            "{}: {:.1} s, {} moves accepted ({} from the pool); blurred error / white noise \
             per level (1, 2, 4.. spp): {} -> {}",
            base.name(),
            t.elapsed().as_secs_f64(),
            report.accepted,
            report.replaced,
            show(&report.before),
            show(&report.after)
        );
        let bytes: Vec<u8> = tile.iter().flat_map(|k| k.to_le_bytes()).collect();
        let name = format!("blue_{}_64.bin", base.name());
        manifest += &format!("{name} {} {:016x}\n", bytes.len(), fnv1a64(&bytes));
        files.push((name, bytes));
    }
    if args.only.is_none() {
        files.push(("blue_MANIFEST".to_string(), manifest.into_bytes()));
    }
    eprintln!(
        "bluegen {settings}: generated in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    write_or_check("bluegen", &args.out, &files, args.check)
}
