//! The solid-angle lights of `shaders/warpcore.wgsl` (`wc_spherical_*`) against the crate's
//! `spherical` functions, bit for bit, on Mesa's lavapipe: the lights of the golden
//! fingerprint and random lights of every kind, times grids, random points and edge values
//! (`warpcore_gpu::spherical`). Same environment variables as `tests/lavapipe.rs`.

use warpcore_gpu::testing::{assert_bit_identical, lavapipe};
use warpcore_gpu::{Func, Gpu, WGSL, compare, cpu_outputs, inputs, lights};

/// Every output word of every solid-angle function equals the crate's.
#[test]
fn every_solid_angle_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    assert_bit_identical(&gpu, lights(), 0x5fe0_0000);
}

fn find(name: &str) -> &'static Func {
    lights().iter().find(|f| f.name == name).unwrap()
}

fn mismatches(gpu: &Gpu, func: &Func, wgsl: &str, input: &[u32]) -> (usize, usize) {
    let source = Gpu::shader_source(func).replacen(WGSL, wgsl, 1);
    let got = gpu
        .run_source(func, &source, input)
        .unwrap_or_else(|e| panic!("{e}"));
    let d = compare(func, &got, &cpu_outputs(func, input));
    (d.mismatches, d.points)
}

/// The comparison is sharp on these functions too: a one-ulp change of `1 / (4 pi)` moves
/// the density of every sample that Arvo's map takes (about half of the test points: the
/// others are degenerate, non-finite or area-sampled lights), and one Newton step fewer moves
/// the rectangle's points.
#[test]
fn small_changes_are_detected() {
    let Some(gpu) = lavapipe() else { return };
    let tri = find("wc_spherical_triangle");
    let input = inputs(tri.domain, 1 << 10, 7);
    let wrong = WGSL.replace(
        "const WCI_INV_4PI: f32 = 0x1.45f306p-4f;",
        "const WCI_INV_4PI: f32 = 0x1.45f308p-4f;",
    );
    assert_ne!(wrong, WGSL, "the constant is where the test expects it");
    let (m, n) = mismatches(&gpu, tri, &wrong, &input);
    println!("1 / (4 pi) + 1 ulp: {m} of {n} triangle samples differ");
    assert!(m * 3 > n, "{m} of {n}");

    let rect = find("wc_spherical_rectangle");
    let input = inputs(rect.domain, 1 << 10, 7);
    let wrong = WGSL.replace(
        "    let dx = wci_rect_newton(r, z2, goal, dx1);",
        "    let dx = dx1;",
    );
    assert_ne!(wrong, WGSL, "the Newton step is where the test expects it");
    let (m, n) = mismatches(&gpu, rect, &wrong, &input);
    println!("one Newton step fewer: {m} of {n} rectangle samples differ");
    assert!(m * 10 > n, "{m} of {n}");
}
