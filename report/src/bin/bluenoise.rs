//! Screen-space blue noise, measured (`warpcore_report::bluenoise`): prints the table per base
//! pattern and writes `target/bluenoise.png`.
//!
//! ```text
//! cargo run --release -p warpcore-report --bin bluenoise
//! ```

use openqmc::{PmjBnSampler, SobolBnSampler};
use std::path::Path;
use warpcore::sampler::{Blue, Pmj02bn, Sobol};
use warpcore_report::bluenoise::{
    FRAMES, FrameDraw, SIGMA, SIZE, SPP, continued, frame_errors, fresh, openqmc_continued,
    patterns, picture, rms_after_blur, white, zsobol_frames, zsobol_rms_after_blur,
};

fn main() {
    println!(
        "RMS of the error after a Gaussian blur (sigma {SIGMA} px), half-plane edges varying \
         across a {SIZE}x{SIZE} image, {FRAMES} frames"
    );
    for (name, base, blue, oq_base, oq_bn) in patterns() {
        let [b, bl, ob, obn] = [base, blue, oq_base, oq_bn].map(|d| rms_after_blur(d, 0..FRAMES));
        println!();
        println!(
            "{:>4} | {:>10} | {:>16} | {:>6} | {:>12} | {:>12} | {:>8}",
            "spp",
            name,
            format!("Blue<{name}>"),
            "ratio",
            "openqmc base",
            "openqmc BN",
            "BN ratio"
        );
        println!(
            "{:-<5}|{:-<12}|{:-<18}|{:-<8}|{:-<14}|{:-<14}|{:-<9}",
            "", "", "", "", "", "", ""
        );
        for (k, spp) in SPP.iter().enumerate() {
            println!(
                "{spp:>4} | {:>10.5} | {:>16.5} | {:>6.3} | {:>12.5} | {:>12.5} | {:>8.3}",
                b[k],
                bl[k],
                bl[k] / b[k],
                ob[k],
                obn[k],
                obn[k] / ob[k]
            );
        }
    }
    zsobol_table();
    frames_table();
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/bluenoise.png");
    match picture(&path) {
        Ok(()) => println!("\nwrote {}", path.display()),
        Err(e) => eprintln!("bluenoise: {}: {e}", path.display()),
    }
}

/// Issue 34: 1 spp per frame, accumulated over 32 and 64 frames.
fn frames_table() {
    let rows: [(&str, FrameDraw); 13] = [
        ("white noise", white),
        ("Sobol, frames continued", continued::<Sobol>),
        ("Sobol, fresh per frame", fresh::<Sobol>),
        ("Blue<Sobol>, frames continued", continued::<Blue<Sobol>>),
        ("Blue<Sobol>, fresh per frame", fresh::<Blue<Sobol>>),
        ("Pmj02bn, frames continued", continued::<Pmj02bn>),
        ("Pmj02bn, fresh per frame", fresh::<Pmj02bn>),
        (
            "Blue<Pmj02bn>, frames continued",
            continued::<Blue<Pmj02bn>>,
        ),
        ("Blue<Pmj02bn>, fresh per frame", fresh::<Blue<Pmj02bn>>),
        (
            "openqmc SobolBn, index continued",
            openqmc_continued::<SobolBnSampler>,
        ),
        (
            "openqmc PmjBn, index continued",
            openqmc_continued::<PmjBnSampler>,
        ),
        ("ZSobol, 32-sample pixels over the frames", zsobol_frames),
        ("white noise (again, other seed)", |x, y, t| {
            white(x, y, t ^ 0x8000_0000)
        }),
    ];
    for frames in [32u32, 64] {
        println!();
        println!(
            "1 spp per frame, {frames} frames, {SIZE}x{SIZE} edges: per-frame RMS after the \
             sigma {SIGMA} blur (mean, worst), running mean (blurred, per-pixel), EMA alpha 0.1 \
             after a sigma 1 blur; ratios to white noise"
        );
        let w = frame_errors(white, frames);
        println!(
            "{:<34} | {:>15} | {:>15} | {:>15} | {:>15} | {:>15}",
            "sampler",
            "frame, mean",
            "frame, worst",
            "mean, blurred",
            "mean, per pixel",
            "EMA, blur 1"
        );
        for (name, draw) in rows {
            let e = frame_errors(draw, frames);
            let cell = |k: usize| format!("{:.5} {:.2}x", e[k], e[k] / w[k]);
            println!(
                "{name:<34} | {:>15} | {:>15} | {:>15} | {:>15} | {:>15}",
                cell(0),
                cell(1),
                cell(2),
                cell(3),
                cell(4)
            );
        }
    }
}

/// The Morton-ordered Sobol' peer (`zsobol`) at each sample count, against `Sobol` and
/// `Blue<Sobol>` (same table as above).
fn zsobol_table() {
    println!();
    println!("Morton-ordered Sobol' (ZSobol, sample count known in advance), same measure");
    let (sobol, blue) = (
        rms_after_blur(patterns()[0].1, 0..FRAMES),
        rms_after_blur(patterns()[0].2, 0..FRAMES),
    );
    println!(
        "{:>4} | {:>10} | {:>12} | {:>14}",
        "spp", "ZSobol", "/ Sobol", "/ Blue<Sobol>"
    );
    for (k, spp) in SPP.iter().enumerate() {
        let z = zsobol_rms_after_blur(*spp, FRAMES);
        println!(
            "{spp:>4} | {z:>10.5} | {:>12.3} | {:>14.3}",
            z / sobol[k],
            z / blue[k]
        );
    }
}
