//! The solid-angle lights of `shaders/warpcore.wgsl` (`wc_spherical_*`) against the crate's
//! `spherical` functions, bit for bit, on Mesa's lavapipe: the lights of the golden
//! fingerprint and random lights of every kind, times grids, random points and edge values
//! (`warpcore_gpu::spherical`). Same environment variables as `tests/lavapipe.rs`.

use warpcore_gpu::testing::{assert_bit_identical, compare_changed, lavapipe};
use warpcore_gpu::{WGSL, inputs, lights};

/// Every output word of every solid-angle function equals the crate's.
#[test]
fn every_solid_angle_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    assert_bit_identical(&gpu, lights(), 0x5fe0_0000);
}

/// The comparison is sharp on these functions too: a one-ulp change of `1 / (4 pi)` moves
/// the density of every sample that Arvo's map takes (about half of the test points: the
/// others are degenerate, non-finite or area-sampled lights), and leaving out the Newton step
/// moves the points of many rectangles that take it (outside the closed-form window).
#[test]
fn small_changes_are_detected() {
    let Some(gpu) = lavapipe() else { return };
    for (name, what, from, to, at_least) in [
        (
            "wc_spherical_triangle",
            "1 / (4 pi) + 1 ulp",
            "const WCI_INV_4PI: f32 = 0x1.45f306p-4f;",
            "const WCI_INV_4PI: f32 = 0x1.45f308p-4f;",
            3,
        ),
        (
            "wc_spherical_rectangle",
            "no Newton step",
            "        dx = wci_rect_newton(r, y1, z2, goal, dx0);",
            "        dx = dx0;",
            20,
        ),
    ] {
        let func = lights().iter().find(|f| f.name == name).unwrap();
        let input = inputs(func.domain, 1 << 10, 7);
        let d = compare_changed(&gpu, func, &WGSL.replace(from, to), &input);
        let (m, n) = (d.mismatches, d.points);
        println!("{what}: {m} of {n} {name} samples differ");
        // More than a third of the triangle's samples, a twentieth of the rectangle's (6.6%
        // since long lights seen from beside them are cut at the foot: their strips' solid
        // angles are exact enough that the step no longer moves most of their points).
        assert!(m * at_least > n, "{what}: {m} of {n}");
    }
}
