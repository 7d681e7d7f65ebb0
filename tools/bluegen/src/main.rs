//! `bluegen`: writes (or checks) warpcore's screen-space blue-noise key tiles.
//!
//! ```text
//! cargo run --release -p bluegen -- [--check] [--out DIR]
//!     [--only sobol|pmj02bn] [--seed S] [--pool N] [--edges T] [--levels L] [--sweeps S] [--rounds R]
//!     [--threshold X] [--weights W1,W2,..] [--line-weights X1,X2,..] [--line-offsets C] [--keys-only]
//!     [--st-seed S] [--st-sigma S] [--st-edges T] [--st-swaps N] [--st-window W]
//!     [--st-quad X] [--st-runs X] [--st-ema W or Wsobol,Wpmj02bn] [--st-ema-at F1,F2,..] [--st-ema-sigma S]
//!     [--st-threshold X]
//!     [--st-only [--st-slots K]]
//! ```
//!
//! For each base pattern (`Sobol`, `Pmj02bn`) it optimises a 64 x 64 tile of 32-bit keys (see
//! [`opt`] for the method) and writes `DIR/blue_{pattern}_64.bin`: little-endian `u32`,
//! row-major, the layout `src/sampler/blue.rs` embeds; and `BLUE_SLOTS` tiles of 16-bit index
//! offsets (see [`slots`]), `DIR/blue_slots_{pattern}_64.bin`: little-endian `u16`,
//! slot-major, row-major within a slot. `DIR/blue_MANIFEST` records the command and each
//! file's size and FNV-1a 64 hash. `--st-only` (for experiments) optimises and writes only the
//! slot tiles, without the manifest (and `--st-slots K` only the first `K` slots of each
//! pattern); `--keys-only` (for experiments) writes only the key tiles. The slot tiles are optimised on two threads, one per pattern, while the main
//! thread optimises the key tiles; each tile has its own random stream, so the bytes do not
//! depend on scheduling.
//!
//! `--check` regenerates everything in memory and compares it byte for byte with `DIR`
//! (exit status 1 on any difference): CI runs this, so the committed tiles are exactly what
//! the command in the manifest produces from the library's current points. Defaults:
//! `--out src/tables` (run from the repository root) and the settings of [`Params`] below.

mod opt;
mod slots;

use opt::{Base, Params};
use pmjgen::tool::{fnv1a64, write_or_check};
use slots::SlotParams;
use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

struct Args {
    out: PathBuf,
    only: Option<Base>,
    params: Params,
    st: SlotParams,
    /// The EMA weight per pattern (Sobol', then pmj02bn; one value for both).
    st_ema: Vec<f64>,
    st_only: bool,
    st_slots: usize,
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
            weights: vec![1.0, 0.8, 1.0, 0.6, 0.4],
            line_weights: vec![0.8, 0.8, 0.4],
            line_offsets: 8,
        },
        st: SlotParams {
            seed: 20220808,
            sigma: 1.5,
            edges: 128,
            swaps: 1_000_000,
            window: 7,
            quad: 0.0,
            runs: 0.3,
            ema: 0.0, // per pattern: `st_ema`
            ema_at: vec![31],
            ema_sigma: 1.0,
            threshold: 0.0,
        },
        st_ema: vec![4.0, 4.25],
        st_only: false,
        st_slots: warpcore::sampler::BLUE_SLOTS,
        check: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        let p = &mut a.params;
        let st = &mut a.st;
        fn num<T: std::str::FromStr>(flag: &str, v: String) -> Result<T, String>
        where
            T::Err: std::fmt::Display,
        {
            v.parse().map_err(|e| format!("{flag}: {e}"))
        }
        /// A comma-separated list of numbers.
        fn nums<T: std::str::FromStr>(flag: &str, v: String) -> Result<Vec<T>, String>
        where
            T::Err: std::fmt::Display,
        {
            v.split(',').map(|w| num(flag, w.to_string())).collect()
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
            "--weights" => p.weights = nums(&flag, value()?)?,
            "--seed" => p.seed = num(&flag, value()?)?,
            "--pool" => p.pool = num(&flag, value()?)?,
            "--edges" => p.edges = num(&flag, value()?)?,
            "--levels" => p.levels = num(&flag, value()?)?,
            "--sweeps" => p.sweeps = num(&flag, value()?)?,
            "--rounds" => p.rounds = num(&flag, value()?)?,
            "--threshold" => p.threshold = num(&flag, value()?)?,
            "--line-weights" => p.line_weights = nums(&flag, value()?)?,
            "--line-offsets" => p.line_offsets = num(&flag, value()?)?,
            "--st-seed" => st.seed = num(&flag, value()?)?,
            "--st-sigma" => st.sigma = num(&flag, value()?)?,
            "--st-edges" => st.edges = num(&flag, value()?)?,
            "--st-swaps" => st.swaps = num(&flag, value()?)?,
            "--st-window" => st.window = num(&flag, value()?)?,
            "--st-quad" => st.quad = num(&flag, value()?)?,
            "--st-runs" => st.runs = num(&flag, value()?)?,
            "--st-ema" => a.st_ema = nums(&flag, value()?)?,
            "--st-ema-at" => st.ema_at = nums(&flag, value()?)?,
            "--st-ema-sigma" => st.ema_sigma = num(&flag, value()?)?,
            "--st-threshold" => st.threshold = num(&flag, value()?)?,
            "--st-only" => a.st_only = true,
            "--keys-only" => a.st_slots = 0,
            "--st-slots" => a.st_slots = num(&flag, value()?)?,
            "--check" => a.check = true,
            _ => return Err(format!("unknown argument {flag}")),
        }
    }
    let p = &a.params;
    if p.edges == 0 || !p.edges.is_multiple_of(8) {
        return Err("--edges must be a positive multiple of 8".into());
    }
    if p.line_weights.iter().any(|w| !(0.0..=1.0).contains(w))
        || p.line_offsets == 0
        || !p.edges.is_multiple_of(p.line_offsets)
    {
        return Err("--line-weights must be in 0..=1, --line-offsets divide --edges".into());
    }
    if p.pool < opt::TILE * opt::TILE || p.levels == 0 || p.levels > 8 {
        return Err("--pool must be at least 4096, --levels in 1..=8".into());
    }
    let st = &a.st;
    if st.edges == 0 || !st.edges.is_multiple_of(8) {
        return Err("--st-edges must be a positive multiple of 8".into());
    }
    if ![st.sigma, st.ema_sigma]
        .iter()
        .all(|s| (0.25..=4.0).contains(s))
        || st.window.is_multiple_of(2)
        || st.window > 63
    {
        return Err(
            "--st-sigma and --st-ema-sigma must be in 0.25..=4, --st-window odd and below 64"
                .into(),
        );
    }
    if a.st_slots > warpcore::sampler::BLUE_SLOTS
        || (a.st_slots < warpcore::sampler::BLUE_SLOTS && !a.st_only && a.st_slots > 0)
    {
        return Err("--st-slots: at most BLUE_SLOTS, fewer only with --st-only".into());
    }
    if [st.quad, st.runs]
        .iter()
        .chain(&a.st_ema)
        .any(|w| !(0.0..=16.0).contains(w))
        || !(1..=2).contains(&a.st_ema.len())
    {
        return Err(
            "--st-quad, --st-runs and --st-ema (one weight, or Sobol's and pmj02bn's) must be \
             in 0..=16"
                .into(),
        );
    }
    if st.ema_at.iter().any(|&f| f >= slots::FRAMES) {
        return Err("--st-ema-at: frames below 32".into());
    }
    Ok(a)
}

/// The first `count` slot tiles of `base` (all [`warpcore::sampler::BLUE_SLOTS`] for the
/// file), as the file's bytes, and one line per tile for the log.
fn slot_file(base: Base, st: &SlotParams, count: usize) -> (Vec<u8>, String) {
    let (mut bytes, mut log) = (Vec::new(), String::new());
    for slot in 0..count {
        let (tile, r) = slots::optimise(base, slot, st);
        let mut sorted = tile.clone();
        sorted.sort_unstable();
        assert!(
            sorted.iter().enumerate().all(|(k, &o)| k == o as usize),
            "slot tile is not a permutation"
        );
        bytes.extend(tile.iter().flat_map(|o| o.to_le_bytes()));
        let (b, a) = (r.before, r.after);
        log += &format!(
            "{} slot {slot}: {:.1} s, {} swaps accepted; blurred error / white noise on held-out \
             half-planes, {} frames at 1 spp, mean (worst): sigma 1 {:.3} ({:.3}) -> {:.3} \
             ({:.3}), sigma 1.5 {:.3} ({:.3}) -> {:.3} ({:.3}); 4 spp mean sigma 1 {:.3} -> {:.3}; EMA sigma 1 {:.3} -> {:.3}\n",
            base.name(),
            r.seconds,
            r.accepted,
            slots::FRAMES,
            b.mean1,
            b.worst1,
            a.mean1,
            a.worst1,
            b.mean15,
            b.worst15,
            a.mean15,
            a.worst15,
            b.mean4,
            a.mean4,
            b.ema,
            a.ema
        );
    }
    (bytes, log)
}

/// `v` as the comma-separated list its flag takes.
fn comma_list<T: ToString>(v: &[T]) -> String {
    v.iter().map(T::to_string).collect::<Vec<_>>().join(",")
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("bluegen: {e}");
            return ExitCode::from(2);
        }
    };
    let (p, st) = (&args.params, &args.st);
    let settings = format!(
        "--seed {} --pool {} --edges {} --levels {} --sweeps {} --rounds {} --threshold {} \
         --weights {} --line-weights {} --line-offsets {} --st-seed {} --st-sigma {} --st-edges {} \
         --st-swaps {} --st-window {} --st-quad {} --st-runs {} --st-ema {} --st-ema-at {} \
         --st-ema-sigma {} --st-threshold {}",
        p.seed,
        p.pool,
        p.edges,
        p.levels,
        p.sweeps,
        p.rounds,
        p.threshold,
        comma_list(&p.weights),
        comma_list(&p.line_weights),
        p.line_offsets,
        st.seed,
        st.sigma,
        st.edges,
        st.swaps,
        st.window,
        st.quad,
        st.runs,
        comma_list(&args.st_ema),
        comma_list(&st.ema_at),
        st.ema_sigma,
        st.threshold
    );
    let mut manifest = format!(
        "# warpcore blue-noise tiles: blue_{{pattern}}_64.bin 64 x 64 little-endian u32 keys, \
         row-major;\n\
         # blue_slots_{{pattern}}_64.bin 6 x 64 x 64 little-endian u16 index offsets, slot-major, \
         row-major.\n\
         # Written by `cargo run --release -p bluegen -- {settings}`.\n\
         # file bytes fnv1a64\n"
    );
    let mut files = Vec::new();
    let start = Instant::now();
    let bases: Vec<Base> = [Base::Sobol, Base::Pmj02bn]
        .into_iter()
        .filter(|&b| args.only.is_none_or(|o| o == b))
        .collect();
    // The slot tiles on their own threads (one per pattern, joined in order) while this one
    // optimises the key tiles.
    let slot_files: Vec<(Vec<u8>, String)> = std::thread::scope(|scope| {
        let handles: Vec<_> = bases
            .iter()
            .map(|&base| {
                let count = args.st_slots;
                let mut st = st.clone();
                let k = usize::from(base == Base::Pmj02bn).min(args.st_ema.len() - 1);
                st.ema = args.st_ema[k];
                scope.spawn(move || slot_file(base, &st, count))
            })
            .collect();
        for &base in bases.iter().filter(|_| !args.st_only) {
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
        handles
            .into_iter()
            .map(|h| h.join().expect("a slot thread panicked"))
            .collect()
    });
    for (&base, (bytes, log)) in bases.iter().zip(slot_files) {
        if args.st_slots == 0 {
            continue;
        }
        eprint!("{log}");
        let name = format!("blue_slots_{}_64.bin", base.name());
        manifest += &format!("{name} {} {:016x}\n", bytes.len(), fnv1a64(&bytes));
        files.push((name, bytes));
    }
    if args.only.is_none() && !args.st_only {
        files.push(("blue_MANIFEST".to_string(), manifest.into_bytes()));
    }
    eprintln!(
        "bluegen {settings}: generated in {:.1} s",
        start.elapsed().as_secs_f64()
    );
    write_or_check("bluegen", &args.out, &files, args.check)
}
