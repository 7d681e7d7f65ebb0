//! Screen-space blue noise, asserted: `Blue<P>`'s error after a Gaussian blur is at most 0.75x
//! `P`'s at 1, 2 and 4 samples per pixel, for both base patterns (issue 20, item 2).
//!
//! The measurement is `warpcore_report::bluenoise` itself: a 64 x 64 image whose
//! pixels each integrate their own half-plane edge (angle and offset varying slowly across
//! the image) with `draw::<2>()` of domain 0, the error image blurred with a Gaussian of sigma
//! 1.5 px, RMS over all pixels. Here over frames 1000..1032 (32 frames, 131,072 pixel
//! estimates per figure and count; the example reports frames 0..32, so this is a fresh
//! sample of the same quantity). Deterministic: the same figures on every run.
//!
//! Margin: with the committed tiles the ratios are about 0.52, 0.59 and 0.68 at 1, 2 and 4
//! spp (both patterns), and they move by about 0.01 between disjoint sets of 32 frames, so
//! the 0.75 bound holds with some six standard deviations to spare at 4 spp. Random
//! (unoptimised) tiles give 0.98-1.02 and fail. 8 and 16 spp (about 0.75 and 0.86) are held
//! to a weaker 0.95. The comparison with OpenQMC's blue-noise samplers (ours 3-6% lower at
//! 1-4 spp) is the example's table, not asserted here.
//!
//! A pmj02bn key also picks the table set, and the pmj02bn tile is optimised for the default
//! four sets (`pmj02bn-4-sets`): with one set the same keys draw other points and the error
//! is nearly white (ratios 0.94-0.98), so that test needs the feature.

#![cfg(feature = "blue-noise")]

use warpcore::sampler::{Blue, Pmj02bn, Sobol};
use warpcore_report::bluenoise::{Draw, SPP, ours, rms_after_blur};

const FRAMES: std::ops::Range<u32> = 1000..1032;

fn check(name: &str, base: Draw, blue: Draw) {
    let (b, bl) = (rms_after_blur(base, FRAMES), rms_after_blur(blue, FRAMES));
    for (k, spp) in SPP.iter().enumerate() {
        eprintln!(
            "{name} {spp:2} spp: P {:.5}  Blue<P> {:.5}  ratio {:.3}",
            b[k],
            bl[k],
            bl[k] / b[k]
        );
    }
    for k in 0..3 {
        assert!(
            bl[k] <= 0.75 * b[k],
            "{name} at {} spp: Blue<P> {:.5} > 0.75 x P {:.5} (ratio {:.3})",
            SPP[k],
            bl[k],
            b[k],
            bl[k] / b[k]
        );
    }
    // Blue noise at every power of two, not only the asserted counts (a weaker bound).
    for k in 3..SPP.len() {
        assert!(bl[k] < 0.95 * b[k], "{name} at {} spp", SPP[k]);
    }
}

#[test]
fn blue_sobol_error_is_blue_noise() {
    check("Sobol", ours::<Sobol>, ours::<Blue<Sobol>>);
}

#[cfg(feature = "pmj02bn-4-sets")]
#[test]
fn blue_pmj02bn_error_is_blue_noise() {
    check("Pmj02bn", ours::<Pmj02bn>, ours::<Blue<Pmj02bn>>);
}
