//! Screen-space blue noise, measured (`warpcore_report::bluenoise`): prints the table per base
//! pattern and writes `target/bluenoise.png`.
//!
//! ```text
//! cargo run --release -p warpcore-report --bin bluenoise
//! ```

use std::path::Path;
use warpcore_report::bluenoise::{FRAMES, SIGMA, SIZE, SPP, patterns, picture, rms_after_blur};

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
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../target/bluenoise.png");
    match picture(&path) {
        Ok(()) => println!("\nwrote {}", path.display()),
        Err(e) => eprintln!("bluenoise: {}: {e}", path.display()),
    }
}
