//! What warpcore's generators and measurements share beyond the sequence itself: the
//! manifests' checksum, writing (or checking) a generator's files, and the exact area of a
//! half-plane in the unit square, the test integrand of the blue-noise optimiser
//! (`tools/bluegen`), of the report's blue-noise measurement and of the `sampler_quality`
//! example. Dependency-free, like the rest of the crate.

use std::path::Path;
use std::process::ExitCode;

/// FNV-1a, 64 bits: a small, fully specified checksum for the manifests.
pub fn fnv1a64(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

/// Writes `files` (name, bytes) into `out`, or with `check` compares each with the file
/// there byte for byte; messages on stderr prefixed with `tool`. Failure on any difference,
/// missing file or write error.
pub fn write_or_check(
    tool: &str,
    out: &Path,
    files: &[(String, Vec<u8>)],
    check: bool,
) -> ExitCode {
    if check {
        let mut ok = true;
        for (name, bytes) in files {
            let path = out.join(name);
            match std::fs::read(&path) {
                Ok(have) if have == *bytes => {}
                Ok(_) => {
                    eprintln!(
                        "{tool}: {} differs from the generator's output",
                        path.display()
                    );
                    ok = false;
                }
                Err(e) => {
                    eprintln!("{tool}: {}: {e}", path.display());
                    ok = false;
                }
            }
        }
        if !ok {
            return ExitCode::FAILURE;
        }
        eprintln!("{} files match", files.len());
    } else {
        if let Err(e) = std::fs::create_dir_all(out) {
            eprintln!("{tool}: {}: {e}", out.display());
            return ExitCode::FAILURE;
        }
        for (name, bytes) in files {
            if let Err(e) = std::fs::write(out.join(name), bytes) {
                eprintln!("{tool}: {name}: {e}");
                return ExitCode::FAILURE;
            }
        }
        eprintln!("wrote {} files to {}", files.len(), out.display());
    }
    ExitCode::SUCCESS
}

/// The area of `{p in [0, 1]^2 : side(p) < 0}` for an affine `side` (a half-plane): the
/// square clipped by the line (Sutherland-Hodgman), then the shoelace formula. Every caller's
/// bits depend on this order of operations (bluegen's tiles among them): keep it.
pub fn square_area_below(side: impl Fn([f64; 2]) -> f64) -> f64 {
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let mut poly: Vec<[f64; 2]> = Vec::with_capacity(5);
    for k in 0..4 {
        let (a, b) = (square[k], square[(k + 1) % 4]);
        let (sa, sb) = (side(a), side(b));
        if sa < 0.0 {
            poly.push(a);
        }
        if (sa < 0.0) != (sb < 0.0) {
            let t = sa / (sa - sb);
            poly.push([a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])]);
        }
    }
    let n = poly.len();
    (0..n)
        .map(|k| {
            let (a, b) = (poly[k], poly[(k + 1) % n]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum::<f64>()
        / 2.0
}
