//! `pmjgen`: writes (or checks) warpcore's pmj02bn tables.
//!
//! ```text
//! cargo run --release -p pmjgen -- [--check] [--out DIR]
//!     [--seed S] [--sets N] [--candidates K]
//! ```
//!
//! For each set `s < N` it generates 65536 points of pmj02bn from a seed derived from `S` and
//! `s` (see [`set_seed`]), and writes the prefixes of 1024, 4096, 16384 and 65536 points as
//! `DIR/pmj02bn_{points}_{s}.bin`: two little-endian `u32` words (x, y) per point, 0.32 fixed
//! point. A prefix of a progressive sequence is the smaller table, so the files of one set
//! agree on their common points. `DIR/MANIFEST` records the command and each file's size and
//! FNV-1a 64 hash; warpcore's tests check the embedded bytes against it.
//!
//! `--check` regenerates everything in memory and compares it byte for byte with `DIR`
//! (exit status 1 on any difference): CI runs this, so the committed tables are exactly what
//! the command in the manifest produces. `--stats` prints nearest-neighbour statistics.
//! Defaults: `--out src/tables --seed 20180702 --sets 4 --candidates 64` (run from the
//! repository root).

use pmjgen as pmj;
use pmjgen::tool::{fnv1a64, write_or_check};

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

/// Points per set in the largest table; the smaller tables are its prefixes.
const MAX_POINTS: usize = 65536;
/// The table sizes the crate's features choose from.
pub const SIZES: [usize; 4] = [1024, 4096, 16384, 65536];

/// Seed of set `s`: the `s`-th output of a SplitMix64 stream seeded with `seed`.
fn set_seed(seed: u64, s: usize) -> u64 {
    let mut rng = pmj::Rng::new(seed);
    (0..s).for_each(|_| {
        rng.next_u64();
    });
    rng.next_u64()
}

/// Set `s` of the tables: pmj02bn points (best candidates, then the flip optimization).
pub fn table_set(seed: u64, s: usize, candidates: usize) -> Result<Vec<[u32; 2]>, pmj::Stuck> {
    let mut points = pmj::generate(MAX_POINTS, set_seed(seed, s), candidates)?;
    pmj::optimize(&mut points, 2);
    // Self-check: every power-of-two prefix is a (0,m,2)-net.
    for m in 0..=MAX_POINTS.trailing_zeros() {
        if !pmj::is_net(&points[..1 << m]) {
            return Err(pmj::Stuck { index: 1 << m });
        }
    }
    Ok(points)
}

fn to_bytes(points: &[[u32; 2]]) -> Vec<u8> {
    points
        .iter()
        .flat_map(|p| p.iter().flat_map(|w| w.to_le_bytes()))
        .collect()
}

struct Args {
    out: PathBuf,
    seed: u64,
    sets: usize,
    candidates: usize,
    check: bool,
    stats: bool,
}

fn parse() -> Result<Args, String> {
    let mut a = Args {
        out: PathBuf::from("src/tables"),
        seed: 20180702,
        sets: 4,
        candidates: 64,
        check: false,
        stats: false,
    };
    let mut it = std::env::args().skip(1);
    while let Some(flag) = it.next() {
        let mut value = || it.next().ok_or(format!("{flag} needs a value"));
        match flag.as_str() {
            "--out" => a.out = PathBuf::from(value()?),
            "--seed" => a.seed = value()?.parse().map_err(|e| format!("--seed: {e}"))?,
            "--sets" => a.sets = value()?.parse().map_err(|e| format!("--sets: {e}"))?,
            "--candidates" => {
                a.candidates = value()?.parse().map_err(|e| format!("--candidates: {e}"))?
            }
            "--check" => a.check = true,
            "--stats" => a.stats = true,
            _ => return Err(format!("unknown argument {flag}")),
        }
    }
    Ok(a)
}

fn main() -> ExitCode {
    let args = match parse() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("pmjgen: {e}");
            return ExitCode::from(2);
        }
    };
    if args.stats {
        stats(&args);
        return ExitCode::SUCCESS;
    }
    let command = format!(
        "pmjgen --seed {} --sets {} --candidates {}",
        args.seed, args.sets, args.candidates
    );
    let mut manifest = format!(
        "# warpcore pmj02bn tables: two little-endian u32 (x, y) per point, 0.32 fixed point.\n\
         # Written by `cargo run --release -p pmjgen -- --seed {} \
         --sets {} --candidates {}`.\n# file bytes fnv1a64\n",
        args.seed, args.sets, args.candidates
    );
    let mut files = Vec::new();
    let start = Instant::now();
    for s in 0..args.sets {
        let t = Instant::now();
        let points = match table_set(args.seed, s, args.candidates) {
            Ok(p) => p,
            Err(e) => {
                eprintln!("pmjgen: set {s} got stuck at point {}", e.index);
                return ExitCode::FAILURE;
            }
        };
        eprintln!(
            "set {s}: {MAX_POINTS} points in {:.2} s",
            t.elapsed().as_secs_f64()
        );
        for size in SIZES {
            let bytes = to_bytes(&points[..size]);
            let name = format!("pmj02bn_{size}_{s}.bin");
            manifest += &format!("{name} {} {:016x}\n", bytes.len(), fnv1a64(&bytes));
            files.push((name, bytes));
        }
    }
    files.push(("MANIFEST".to_string(), manifest.into_bytes()));
    eprintln!(
        "{command}: generated in {:.2} s",
        start.elapsed().as_secs_f64()
    );
    write_or_check("pmjgen", &args.out, &files, args.check)
}

/// Nearest-neighbour statistics of plain pmj02 and of the pmj02bn tables' prefixes.
fn stats(args: &Args) {
    let sets = args.sets.max(1);
    let table: Vec<Vec<[u32; 2]>> = (0..sets)
        .map(|s| table_set(args.seed, s, args.candidates).expect("stuck"))
        .collect();
    for n in [256, 1024, 4096] {
        let (mut plain, mut bn) = ([0.0; 2], [0.0; 2]);
        for (s, t) in table.iter().enumerate() {
            let p = pmj::generate(n, set_seed(args.seed, s), 1).expect("stuck");
            let (a, b) = pmj::nearest_neighbour_stats(&p);
            plain = [plain[0] + a / sets as f64, plain[1] + b / sets as f64];
            let (a, b) = pmj::nearest_neighbour_stats(&t[..n]);
            bn = [bn[0] + a / sets as f64, bn[1] + b / sets as f64];
        }
        println!(
            "n {n:5}: pmj02 mean {:.3} min {:.3}   pmj02bn mean {:.3} min {:.3}",
            plain[0], plain[1], bn[0], bn[1]
        );
    }
}
