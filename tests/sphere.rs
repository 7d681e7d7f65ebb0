//! Sphere warps: domain on any input bits, bit identity across widths, accuracy against f64
//! references (unit length, per-coordinate error, round trips both ways) over random points
//! and dense sweeps of the poles, the equator fold and the octant seams, signed zeros, the
//! octahedral edge wrap, density conversions, and chi-square tests on the sphere.
#![cfg(feature = "sphere")]
// Lane-by-lane comparisons index several arrays with one counter.
#![allow(clippy::needless_range_loop)]

use warpcore_testkit as common;

use common::textbook;

use common::{
    ONE_MINUS_EPS, chi2, in_unit_square, lane, rng, same_bits, soa, special_pairs, special_triples,
    unit, unit2,
};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use warpcore::f32x8;
use warpcore::sphere;

// ----------------------------------------------------------------------------------------
// f64 references: the published formulas, branches and all, evaluated in f64 on the f32
// input. (|a| + |b| of two f32 values is exact in f64, so the fold is exact here.)

fn ab(u: [f32; 2]) -> (f64, f64) {
    (2.0 * u[0] as f64 - 1.0, 2.0 * u[1] as f64 - 1.0)
}

/// Clarberg's equal-area map as written in the paper / DESIGN.md.
fn equal_area_ref(u: [f32; 2]) -> [f64; 3] {
    let (a, b) = ab(u);
    let (r, phi, sd) = textbook::equal_area_fold(a, b);
    let z = if sd >= 0.0 {
        1.0 - r * r
    } else {
        -(1.0 - r * r)
    };
    let s = r * (2.0 - r * r).sqrt();
    let sign = |v: f64| if v < 0.0 { -1.0 } else { 1.0 };
    [s * phi.cos() * sign(a), s * phi.sin() * sign(b), z]
}

/// The inverse as published: r = sqrt(1 - |z|) of the normalized direction.
fn equal_area_inverse_ref(d: [f32; 3]) -> [f64; 2] {
    let n = norm(d);
    let (x, y, z) = (d[0] as f64 / n, d[1] as f64 / n, d[2] as f64 / n);
    let r = (1.0 - z.abs()).max(0.0).sqrt();
    let phi = y.abs().atan2(x.abs()); // [0, pi/2]
    textbook::equal_area_unfold(r, r * phi / FRAC_PI_2, [x, y, z])
}

fn equirect_ref(u: [f32; 2]) -> [f64; 3] {
    let (phi, theta) = (TAU * u[0] as f64, PI * u[1] as f64);
    [
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    ]
}

fn uniform_ref(u: [f32; 2]) -> [f64; 3] {
    let z = 1.0 - 2.0 * u[0] as f64;
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * u[1] as f64;
    [r * phi.cos(), r * phi.sin(), z]
}

/// Shirley and Chiu's concentric map exactly as published, with the disk warps' radius clamp.
fn concentric_ref(u: [f32; 2]) -> [f64; 2] {
    let (a, b) = ab(u);
    let (r, phi) = textbook::concentric_polar(a, b);
    let max = 1.0 - 2f64.powi(-23);
    let r = r.clamp(-max, max);
    [r * phi.cos(), r * phi.sin()]
}

fn uniform_hemisphere_ref(u: [f32; 2]) -> [f64; 3] {
    let [x, y] = concentric_ref(u);
    let r2 = x * x + y * y;
    let s = (2.0 - r2).sqrt();
    [x * s, y * s, 1.0 - r2]
}

fn cosine_hemisphere_ref(u: [f32; 2]) -> [f64; 3] {
    let [x, y] = concentric_ref(u);
    [x, y, (1.0 - x * x - y * y).max(0.0).sqrt()]
}

fn norm(d: [f32; 3]) -> f64 {
    d.iter().map(|&c| (c as f64).powi(2)).sum::<f64>().sqrt()
}

fn norm64(d: [f64; 3]) -> f64 {
    d.iter().map(|c| c * c).sum::<f64>().sqrt()
}

fn to64(d: [f32; 3]) -> [f64; 3] {
    d.map(|c| c as f64)
}

/// Max per-coordinate distance.
fn dist3(p: [f32; 3], q: [f64; 3]) -> f64 {
    (0..3)
        .map(|k| (p[k] as f64 - q[k]).abs())
        .fold(0.0, f64::max)
}

fn dist2(p: [f32; 2], q: [f64; 2]) -> f64 {
    (0..2)
        .map(|k| (p[k] as f64 - q[k]).abs())
        .fold(0.0, f64::max)
}

/// Angle between two directions (any lengths), accurate for tiny angles.
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let cross = [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ];
    let dot: f64 = (0..3).map(|k| a[k] * b[k]).sum();
    norm64(cross).atan2(dot)
}

/// Round-trip distance in the square with the first coordinate compared modulo 1 (seams of
/// the azimuth).
fn dist_mod1(u: [f32; 2], b: [f32; 2], periodic: [bool; 2]) -> f64 {
    (0..2)
        .map(|k| {
            let d = (u[k] as f64 - b[k] as f64).abs();
            if periodic[k] { d.min(1.0 - d) } else { d }
        })
        .fold(0.0, f64::max)
}

/// A direction uniform on the sphere from f64 arithmetic, rounded to f32 (like a normalized
/// vector a renderer passes in: length 1 within a few 1e-8).
fn random_direction(r: &mut rand_xoshiro::Xoshiro256PlusPlus) -> [f32; 3] {
    let (u, v) = (unit(r) as f64, unit(r) as f64);
    let z = 1.0 - 2.0 * u;
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = TAU * v;
    [(s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32]
}

fn is_unit(d: [f32; 3], tol: f64) -> bool {
    d.iter().all(|c| c.is_finite()) && (norm(d) - 1.0).abs() <= tol
}

// ----------------------------------------------------------------------------------------
// The warps as a table, so the generic checks run over all of them.

type Fwd = fn([f32; 2]) -> [f32; 3];
type Fwd8 = fn([f32x8; 2]) -> [f32x8; 3];
type FwdS = fn(&[[f32; 2]], &mut [[f32; 3]]) -> usize;
type Inv = fn([f32; 3]) -> [f32; 2];
type Inv8 = fn([f32x8; 3]) -> [f32x8; 2];
type InvS = fn(&[[f32; 3]], &mut [[f32; 2]]) -> usize;

struct Warp {
    name: &'static str,
    fwd: Fwd,
    fwd8: Fwd8,
    fwd_slice: FwdS,
    inv: Inv,
    inv8: Inv8,
    inv_slice: InvS,
    reference: fn([f32; 2]) -> [f64; 3],
    /// Only the upper hemisphere (z >= 0).
    hemisphere: bool,
    /// Which square coordinates are an azimuth (compared modulo 1 in round trips).
    periodic: [bool; 2],
}

fn warps() -> [Warp; 5] {
    [
        Warp {
            name: "equal_area",
            fwd: sphere::equal_area,
            fwd8: sphere::equal_area_x8,
            fwd_slice: sphere::equal_area_slice,
            inv: sphere::equal_area_inverse,
            inv8: sphere::equal_area_inverse_x8,
            inv_slice: sphere::equal_area_inverse_slice,
            reference: equal_area_ref,
            hemisphere: false,
            periodic: [false, false],
        },
        Warp {
            name: "equirect",
            fwd: sphere::equirect,
            fwd8: sphere::equirect_x8,
            fwd_slice: sphere::equirect_slice,
            inv: sphere::equirect_inverse,
            inv8: sphere::equirect_inverse_x8,
            inv_slice: sphere::equirect_inverse_slice,
            reference: equirect_ref,
            hemisphere: false,
            periodic: [true, false],
        },
        Warp {
            name: "uniform",
            fwd: sphere::uniform,
            fwd8: sphere::uniform_x8,
            fwd_slice: sphere::uniform_slice,
            inv: sphere::uniform_inverse,
            inv8: sphere::uniform_inverse_x8,
            inv_slice: sphere::uniform_inverse_slice,
            reference: uniform_ref,
            hemisphere: false,
            periodic: [false, true],
        },
        Warp {
            name: "uniform_hemisphere",
            fwd: sphere::uniform_hemisphere,
            fwd8: sphere::uniform_hemisphere_x8,
            fwd_slice: sphere::uniform_hemisphere_slice,
            inv: sphere::uniform_hemisphere_inverse,
            inv8: sphere::uniform_hemisphere_inverse_x8,
            inv_slice: sphere::uniform_hemisphere_inverse_slice,
            reference: uniform_hemisphere_ref,
            hemisphere: true,
            periodic: [false, false],
        },
        Warp {
            name: "cosine_hemisphere",
            fwd: sphere::cosine_hemisphere,
            fwd8: sphere::cosine_hemisphere_x8,
            fwd_slice: sphere::cosine_hemisphere_slice,
            inv: sphere::cosine_hemisphere_inverse,
            inv8: sphere::cosine_hemisphere_inverse_x8,
            inv_slice: sphere::cosine_hemisphere_inverse_slice,
            reference: cosine_hemisphere_ref,
            hemisphere: true,
            periodic: [false, false],
        },
    ]
}

/// The stated bounds (doc comments and docs/precision.md).
const UNIT_TOL: f64 = 2e-7;
const ROUND_TRIP: f64 = 5e-7;
const ANGLE_TOL: f64 = 1e-6;

// ----------------------------------------------------------------------------------------
// Domain: any bit pattern gives a unit direction (in the right hemisphere) and inverses give
// points of [0, 1)^2.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn forward_warps_give_unit_directions(a: u32, b: u32) {
        let u = [f32::from_bits(a), f32::from_bits(b)];
        for w in warps() {
            let d = (w.fwd)(u);
            prop_assert!(is_unit(d, UNIT_TOL), "{} {u:?} -> {d:?}", w.name);
            prop_assert!(!w.hemisphere || d[2] >= 0.0, "{} {u:?} -> {d:?}", w.name);
        }
        // equal_area: the hemisphere is the one of the formula (|a| + |b| <= 1 is z >= 0).
        let d = sphere::equal_area(u);
        let r = equal_area_ref(clamp_like_the_crate(u));
        prop_assert!(r[2].abs() < 1e-6 || (d[2] >= 0.0) == (r[2] >= 0.0), "{u:?} -> {d:?}");
    }

    #[test]
    fn inverses_give_points_of_the_square(x: u32, y: u32, z: u32) {
        let d = [f32::from_bits(x), f32::from_bits(y), f32::from_bits(z)];
        for w in warps() {
            let u = (w.inv)(d);
            prop_assert!(in_unit_square(u), "{} {d:?} -> {u:?}", w.name);
        }
    }

    #[test]
    fn wrap_and_densities_are_total(a: u32, b: u32, p: u32) {
        let u = [f32::from_bits(a), f32::from_bits(b)];
        let w = sphere::equal_area_wrap(u);
        prop_assert!(w.iter().all(|c| (0.0..=1.0).contains(c)), "{u:?} -> {w:?}");
        let pdf = f32::from_bits(p);
        let d = [u[0], u[1], pdf];
        for q in [
            sphere::equal_area_pdf_to_solid_angle(pdf),
            sphere::equirect_pdf_to_solid_angle(pdf, d),
            sphere::cosine_hemisphere_pdf(pdf),
        ] {
            prop_assert!(q.is_finite() && q >= 0.0, "{pdf} {d:?} -> {q}");
        }
    }

    /// Scalar, x8 and slice forms agree bit for bit on arbitrary bit patterns.
    #[test]
    fn widths_agree_on_any_bits(bits in prop::array::uniform24(any::<u32>())) {
        let f = |k: usize| f32::from_bits(bits[k]);
        let pts: [[f32; 2]; 8] = std::array::from_fn(|j| [f(2 * j), f(2 * j + 1)]);
        let dirs: [[f32; 3]; 8] = std::array::from_fn(|j| [f(3 * j), f(3 * j + 1), f(3 * j + 2)]);
        check_widths(&pts, &dirs);
    }

    #[test]
    fn equal_area_round_trip(u0 in 0f32..1.0, u1 in 0f32..1.0) {
        let u = [u0, u1];
        let back = sphere::equal_area_inverse(sphere::equal_area(u));
        prop_assert!(dist_mod1(u, back, [false; 2]) <= ROUND_TRIP, "{u:?} -> {back:?}");
    }
}

/// The crate's forward input rule, for the references.
fn clamp_like_the_crate(u: [f32; 2]) -> [f32; 2] {
    u.map(|x| {
        if x > 0.0 {
            if x < 1.0 { x } else { ONE_MINUS_EPS }
        } else {
            0.0
        }
    })
}

/// Every width of every sphere function on eight inputs: scalar, x8 and slices (a full
/// group and padded tails).
fn check_widths(pts: &[[f32; 2]; 8], dirs: &[[f32; 3]; 8]) {
    let (p8, d8) = (soa(pts), soa(dirs));
    for w in warps() {
        common::check_widths(w.name, pts, w.fwd, w.fwd8, w.fwd_slice);
        common::check_widths(
            &format!("{} inverse", w.name),
            dirs,
            w.inv,
            w.inv8,
            w.inv_slice,
        );
    }
    let wrap8 = sphere::equal_area_wrap_x8(p8);
    let mut wrapped = [[9.0f32; 2]; 8];
    assert_eq!(sphere::equal_area_wrap_slice(pts, &mut wrapped), 8);
    let pdf = f32x8::new(std::array::from_fn(|j| dirs[j][0]));
    let (e8, q8, c8) = (
        sphere::equal_area_pdf_to_solid_angle_x8(pdf),
        sphere::equirect_pdf_to_solid_angle_x8(pdf, d8),
        sphere::cosine_hemisphere_pdf_x8(pdf),
    );
    for j in 0..8 {
        let s = sphere::equal_area_wrap(pts[j]);
        assert!(
            same_bits(s, lane(wrap8, j)) && same_bits(s, wrapped[j]),
            "wrap {j}"
        );
        let p = dirs[j][0];
        let same = |a: f32, b: f32x8| a.to_bits() == b.to_array()[j].to_bits();
        assert!(same(sphere::equal_area_pdf_to_solid_angle(p), e8));
        assert!(same(sphere::equirect_pdf_to_solid_angle(p, dirs[j]), q8));
        assert!(same(sphere::cosine_hemisphere_pdf(p), c8));
    }
}

#[test]
fn widths_agree_on_special_values() {
    let pts = special_pairs();
    let dirs = special_triples(&[0.0, -0.0, 1.0, -1.0, f32::NAN, 0.3, f32::INFINITY, 1e-30]);
    for (k, group) in pts.chunks_exact(8).enumerate() {
        let d: Vec<[f32; 3]> = (0..8).map(|j| dirs[(8 * k + j) * 7 % dirs.len()]).collect();
        check_widths(group.try_into().unwrap(), d.as_slice().try_into().unwrap());
    }
    for group in dirs.chunks_exact(8) {
        let p: Vec<[f32; 2]> = group.iter().map(|d| [d[0], d[2]]).collect();
        check_widths(p.as_slice().try_into().unwrap(), group.try_into().unwrap());
    }
    // Domain on the whole cross products.
    for w in warps() {
        for &u in &pts {
            let d = (w.fwd)(u);
            assert!(is_unit(d, UNIT_TOL), "{} {u:?} -> {d:?}", w.name);
            assert!(!w.hemisphere || d[2] >= 0.0);
        }
        for &d in &dirs {
            assert!(in_unit_square((w.inv)(d)), "{} {d:?}", w.name);
        }
    }
}

/// Slices of every length 0..=20 (and mismatched lengths) against the scalar form.
#[test]
fn slices_of_any_length() {
    let mut r = rng(7);
    let input: Vec<[f32; 2]> = (0..20).map(|_| unit2(&mut r)).collect();
    let dirs: Vec<[f32; 3]> = (0..20).map(|_| random_direction(&mut r)).collect();
    common::check_slice_lengths(&input, sphere::equal_area, sphere::equal_area_slice);
    common::check_slice_lengths(
        &dirs,
        sphere::equal_area_inverse,
        sphere::equal_area_inverse_slice,
    );
}

// ----------------------------------------------------------------------------------------
// Accuracy against f64.

/// The input points of the accuracy tests: 2^22 random points plus the dense sweeps.
fn accuracy_inputs() -> Vec<[f32; 2]> {
    let mut r = rng(11);
    let mut v: Vec<[f32; 2]> = (0..(1 << 22)).map(|_| unit2(&mut r)).collect();
    v.extend(sweeps());
    v
}

/// Dense sweeps of the places where equal-area (and the other maps) are delicate:
/// * the `+z` pole (square centre) and the `-z` pole (corners): offsets `k 2^-24` and
///   `2^-e` in every direction;
/// * the equator fold `|a| + |b| = 1`: points on it and 1-3 ulp either side;
/// * the octant seams `u0 = 1/2`, `u1 = 1/2` (and 1 ulp either side), the square's edges
///   `u = 0` and `u = 1 - 2^-24`, and the diagonals `|a| = |b|`.
fn sweeps() -> Vec<[f32; 2]> {
    let mut v = Vec::new();
    let mut offsets: Vec<f32> = (1..=64).map(|k| k as f32 / 16_777_216.0).collect();
    offsets.extend((2..=24).map(|e| 2f32.powi(-e)));
    offsets.push(0.0);
    for &s in &offsets {
        for &t in &offsets {
            for (sa, sb) in [(1.0f32, 1.0f32), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
                v.push([0.5 + sa * s, 0.5 + sb * t]); // near +z
                let corner = |o: f32, sg: f32| if sg > 0.0 { o } else { ONE_MINUS_EPS - o };
                v.push([corner(s, sa), corner(t, sb)]); // near -z
            }
        }
    }
    let nudge = |x: f32, k: i32| f32::from_bits(x.to_bits().wrapping_add_signed(k));
    for i in 0..=4096u32 {
        let t = i as f32 / 8192.0; // a in [0, 1/2], exact
        for (sa, sb) in [(1.0f32, 1.0f32), (1.0, -1.0), (-1.0, 1.0), (-1.0, -1.0)] {
            // |a| + |b| = 1 with a = sa t, b = sb (1 - t): u = (a + 1) / 2 is exact.
            let u0 = 0.5 + 0.5 * sa * t;
            let u1 = 0.5 + 0.5 * sb * (1.0 - t);
            for k in -3..=3 {
                v.push([u0, nudge(u1, k)]);
                v.push([nudge(u1, k), u0]);
            }
            // Diagonals |a| = |b|.
            v.push([0.5 + sa * t, 0.5 + sb * t]);
        }
        let s = i as f32 / 4096.0;
        let s = if s < 1.0 { s } else { ONE_MINUS_EPS };
        for e in [0.5f32, nudge(0.5, 1), nudge(0.5, -1), 0.0, ONE_MINUS_EPS] {
            v.push([e, s]);
            v.push([s, e]);
        }
    }
    v.retain(|u| u.iter().all(|&x| (0.0..1.0).contains(&x)));
    v
}

/// Unit length and per-coordinate accuracy of every forward warp against its f64 reference,
/// over 2^22 random points and the sweeps; equal_area additionally away from... nowhere: the
/// bounds hold everywhere.
#[test]
fn forward_accuracy_against_f64() {
    let inputs = accuracy_inputs();
    let mut failures = 0;
    for w in warps() {
        let (mut unit_err, mut coord_err) = (0.0f64, 0.0f64);
        let mut worst = [0.0f32; 2];
        for &u in &inputs {
            let d = (w.fwd)(u);
            unit_err = unit_err.max((norm(d) - 1.0).abs());
            let e = dist3(d, (w.reference)(u));
            if e > coord_err {
                coord_err = e;
                worst = u;
            }
        }
        eprintln!(
            "{}: max ||d| - 1| {unit_err:.3e}, max coordinate error {coord_err:.3e} at {worst:?}",
            w.name
        );
        failures += usize::from(unit_err > UNIT_TOL) + usize::from(coord_err > 2e-7);
    }
    assert_eq!(failures, 0);
}

/// square -> sphere -> square over 2^22 random points and the sweeps.
#[test]
fn round_trips_square_sphere_square() {
    let inputs = accuracy_inputs();
    let mut failures = 0;
    for w in warps() {
        let mut worst = (0.0f64, [0.0f32; 2]);
        for &u in &inputs {
            let d = (w.fwd)(u);
            let back = (w.inv)(d);
            // Singular sets: the azimuth of the lat-long and uniform maps is lost at their
            // poles (one coordinate of the square is a whole point of the sphere); for
            // lat-long that includes u1 below 1e-30, where sin theta underflows.
            let e = match w.name {
                "equirect" if u[1] < 1e-30 => (back[1] - u[1]).abs() as f64,
                "uniform" if u[0] == 0.0 => (back[0] - u[0]).abs() as f64,
                _ => dist_mod1(u, back, w.periodic),
            };
            if e > worst.0 {
                worst = (e, u);
            }
        }
        eprintln!(
            "{}: round trip max {:.3e} at {:?}",
            w.name, worst.0, worst.1
        );
        failures += usize::from(worst.0 > ROUND_TRIP);
    }
    assert_eq!(failures, 0);
}

/// Directions of the sphere -> square -> sphere test: random, plus the poles, the equator
/// (z = +-0 and tiny), the seams x = +-0 and y = +-0, and points near all of them.
fn direction_inputs() -> Vec<[f32; 3]> {
    let mut r = rng(13);
    let mut v: Vec<[f32; 3]> = (0..(1 << 21)).map(|_| random_direction(&mut r)).collect();
    let tiny = [0.0f32, 1e-30, 1e-12, 1e-7, 3e-4, 1e-2];
    for i in 0..2048 {
        let phi = TAU * (i as f64 + 0.25) / 2048.0;
        for &t in &tiny {
            // Near the poles: sin theta = t.
            let (s, c) = (t as f64, (1.0 - (t as f64).powi(2)).sqrt());
            for z in [c, -c] {
                v.push([(s * phi.cos()) as f32, (s * phi.sin()) as f32, z as f32]);
            }
            // Near the equator: z = +-t.
            let c = (1.0 - (t as f64).powi(2)).sqrt();
            for z in [t, -t] {
                v.push([(c * phi.cos()) as f32, (c * phi.sin()) as f32, z]);
            }
        }
        // On the seams, with both signs of zero.
        let (s, c) = (phi.sin() as f32, phi.cos() as f32);
        for zero in [0.0f32, -0.0] {
            v.push([zero, s, c]);
            v.push([s, zero, c]);
            v.push([c, s, zero]);
        }
    }
    for d in [
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [-0.0, -0.0, -1.0],
        [1.0, 0.0, 0.0],
    ] {
        v.push(d);
    }
    v
}

/// sphere -> square -> sphere: the angle between a direction and its image.
#[test]
fn round_trips_sphere_square_sphere() {
    let dirs = direction_inputs();
    let mut failures = 0;
    for w in warps() {
        // Where the f32 input grid itself is coarse, a direction can only come back as a
        // nearby one the warp produces. Uniform: z = 1 - 2 u0 moves in steps of 2^-23 for
        // u0 >= 1/2, which are 2^-23 / sin(theta) rad apart near -z (and the top value
        // u0 = 1 - 2^-24 is the whole cap within 2^-11 rad of -z): allowed one step. Cosine:
        // the disk radius moves in steps of 2^-23 near the rim, 2^-23 / z rad apart near the
        // horizon (the top radius 1 - 2^-23 is the band z < 4.9e-4), and the inverse's own
        // rounding of the radius is magnified by the same 1 / z: allowed three steps.
        let allowed_steps = match w.name {
            "uniform" => 1.0,
            "cosine_hemisphere" => 3.0,
            _ => 0.0,
        };
        let (mut worst, mut worst_steps) = ((0.0f64, [0.0f32; 3]), 0.0f64);
        for &d in &dirs {
            if w.hemisphere && d[2] < 0.0 {
                continue;
            }
            let back = (w.fwd)((w.inv)(d));
            let e = angle(to64(d), to64(back));
            let (n, z) = (norm(d), d[2] as f64);
            // (On the axis and the horizon themselves the step is unbounded; `max` keeps it
            // positive for z = -0.0.)
            let step = match w.name {
                "uniform" if z < 0.0 => 2f64.powi(-23) / (1.0 - (z / n).powi(2)).sqrt().max(1e-300),
                "cosine_hemisphere" => 2f64.powi(-23) / (z.abs() / n).max(1e-300),
                _ => 0.0,
            };
            if e > ANGLE_TOL + allowed_steps * step {
                failures += 1;
                if failures <= 5 {
                    eprintln!("{}: {d:?} comes back {e:.3e} rad off", w.name);
                }
            }
            if step > 0.0 {
                worst_steps = worst_steps.max((e - ANGLE_TOL) / step);
            } else if e > worst.0 {
                worst = (e, d);
            }
        }
        eprintln!(
            "{}: sphere round trip max angle {:.3e} rad at {:?}; where the input grid is \
             coarse, at most 1e-6 rad + {worst_steps:.2} steps",
            w.name, worst.0, worst.1
        );
    }
    assert_eq!(failures, 0);
}

/// equal_area_inverse against the published inverse in f64.
#[test]
fn equal_area_inverse_accuracy() {
    let mut worst = 0.0f64;
    for d in direction_inputs() {
        let u = sphere::equal_area_inverse(d);
        let want = equal_area_inverse_ref(d);
        // The four corners are one point (-z): skip the exact pole, compare elsewhere.
        if d[0] == 0.0 && d[1] == 0.0 {
            continue;
        }
        worst = worst.max(dist2(u, want));
    }
    eprintln!("equal_area_inverse: max error vs f64 {worst:.3e}");
    assert!(worst <= 2e-7, "{worst}");
}

/// The inverses see only the direction: scaled vectors (inside the clamp cube) give the
/// same point as the unit vector, up to rounding.
#[test]
fn inverses_are_scale_free() {
    let mut r = rng(17);
    for _ in 0..100_000 {
        let d = random_direction(&mut r);
        let scale = [1e-18f32, 1e-9, 0.001, 0.3, 0.999][(unit(&mut r) * 5.0) as usize];
        let ds = d.map(|c| c * scale);
        for w in warps() {
            let (a, b) = ((w.inv)(d), (w.inv)(ds));
            assert!(
                dist_mod1(a, b, w.periodic) <= 3e-7,
                "{} {d:?} x {scale}",
                w.name
            );
        }
    }
}

/// A textbook f32 implementation (libm-style sin/cos/atan, `1 - |z|` in the inverse) for
/// comparison: the issue quotes 6e-6 globally and 9e-5 near the poles for it.
#[test]
fn textbook_f32_round_trip_for_comparison() {
    fn fwd(u: [f32; 2]) -> [f32; 3] {
        let (a, b) = (2.0 * u[0] - 1.0, 2.0 * u[1] - 1.0);
        let (r, phi, sd) = textbook::equal_area_fold(a, b);
        let z = (1.0 - r * r).copysign(sd);
        let s = r * (2.0 - r * r).max(0.0).sqrt();
        [s * phi.cos().copysign(a), s * phi.sin().copysign(b), z]
    }
    fn inv(d: [f32; 3]) -> [f32; 2] {
        let (x, y, z) = (d[0].abs(), d[1].abs(), d[2].abs());
        let r = (1.0 - z).max(0.0).sqrt();
        let (mx, mn) = if x > y { (x, y) } else { (y, x) };
        let mut phi = if mx == 0.0 { 0.0 } else { (mn / mx).atan() } / std::f32::consts::FRAC_PI_2;
        if x < y {
            phi = 1.0 - phi;
        }
        textbook::equal_area_unfold(r, phi * r, d)
    }
    let inputs = accuracy_inputs();
    let (mut ours, mut textbook, mut textbook_pole) = (0.0f64, 0.0f64, 0.0f64);
    for &u in &inputs {
        let e = dist_mod1(u, inv(fwd(u)), [false; 2]);
        textbook = textbook.max(e);
        let (a, b) = ab(u);
        if a.abs() + b.abs() < 0.01 || a.abs() + b.abs() > 1.99 {
            textbook_pole = textbook_pole.max(e);
        }
        let back = sphere::equal_area_inverse(sphere::equal_area(u));
        ours = ours.max(dist_mod1(u, back, [false; 2]));
    }
    eprintln!(
        "equal_area round trip: warpcore {ours:.2e}; textbook f32 {textbook:.2e} ({textbook_pole:.2e} near the poles)"
    );
    assert!(ours * 10.0 < textbook, "the precision work should show");
}

// ----------------------------------------------------------------------------------------
// Poles, seams, fold and signed zeros.

#[test]
fn poles_seams_and_signed_zeros() {
    // Square centre is +z, corners are -z, edge midpoints are the equator.
    assert_eq!(sphere::equal_area([0.5, 0.5]), [0.0, 0.0, 1.0]);
    let c = sphere::equal_area([0.0, 0.0]);
    assert_eq!(c, [-0.0, -0.0, -1.0]);
    assert!(c[0].is_sign_negative() && c[1].is_sign_negative());
    assert_eq!(sphere::equal_area_inverse([0.0, 0.0, 1.0]), [0.5, 0.5]);
    assert_eq!(sphere::equal_area_inverse([-0.0, -0.0, -1.0]), [0.0, 0.0]);
    assert_eq!(
        sphere::equal_area_inverse([0.0, 0.0, -1.0]),
        [ONE_MINUS_EPS, ONE_MINUS_EPS]
    );
    assert_eq!(
        sphere::equal_area_inverse([-0.0, 0.0, -1.0]),
        [0.0, ONE_MINUS_EPS]
    );
    for (u, want) in [
        ([0.0, 0.5], [-1.0, 0.0, 0.0]),
        ([0.5, 0.0], [0.0, -1.0, 0.0]),
        ([0.75, 0.75], [0.0, 0.0, 0.0]), // on the fold: |a| + |b| = 1
    ] {
        let d = sphere::equal_area(u);
        if want != [0.0; 3] {
            assert!(
                dist3(d, want.map(|c: f32| c as f64)) <= 1e-7,
                "{u:?} -> {d:?}"
            );
        }
        assert_eq!(d[2], 0.0, "{u:?} is on the equator: {d:?}");
    }
    // On the edge u1 = 0 (b = -1) the lower hemisphere's x = 0 meridian folds onto itself:
    // a and -a give the same direction, told apart only by the sign of x's zero.
    for k in 1..512 {
        let t = k as f32 / 1024.0; // a = 2 t - 1 < 0 on the left half
        let (left, right) = ([t, 0.0], [1.0 - t, 0.0]);
        let (dl, dr) = (sphere::equal_area(left), sphere::equal_area(right));
        assert_eq!(dl[0], 0.0);
        assert!(
            dl[0].is_sign_negative() && dr[0].is_sign_positive(),
            "{dl:?} {dr:?}"
        );
        assert_eq!((dl[1], dl[2]), (dr[1], dr[2]));
        assert!(dist_mod1(sphere::equal_area_inverse(dl), left, [false; 2]) <= 1e-7);
        assert!(dist_mod1(sphere::equal_area_inverse(dr), right, [false; 2]) <= 1e-7);
        // And the same for the y zero on the edge u0 = 0.
        let (low, high) = ([0.0, t], [0.0, 1.0 - t]);
        let (dl, dh) = (sphere::equal_area(low), sphere::equal_area(high));
        assert!(dl[1] == 0.0 && dl[1].is_sign_negative() && dh[1].is_sign_positive());
        assert!(dist_mod1(sphere::equal_area_inverse(dl), low, [false; 2]) <= 1e-7);
        assert!(dist_mod1(sphere::equal_area_inverse(dh), high, [false; 2]) <= 1e-7);
    }
    // A lower-hemisphere direction on a seam: the zero's sign picks the half of the edge.
    let s = 0.6f32;
    let z = -(1.0 - s * s).sqrt();
    let (neg, pos) = (
        sphere::equal_area_inverse([-0.0, s, z]),
        sphere::equal_area_inverse([0.0, s, z]),
    );
    assert!(neg[0] < 0.5 && pos[0] > 0.5, "{neg:?} {pos:?}");
    assert!((neg[0] + pos[0] - 1.0).abs() <= 1e-7 && neg[1] == pos[1]);
    // Upper hemisphere seams: both zeros give the seam itself.
    assert_eq!(sphere::equal_area_inverse([-0.0, s, -z])[0], 0.5);
    assert_eq!(sphere::equal_area_inverse([0.0, s, -z])[0], 0.5);
    // The equator: z = +-0 give the same point of the fold.
    let (p, m) = (
        sphere::equal_area_inverse([0.6, 0.8, 0.0]),
        sphere::equal_area_inverse([0.6, 0.8, -0.0]),
    );
    assert!(dist_mod1(p, m, [false; 2]) <= 1e-7, "{p:?} {m:?}");
    // The zero vector (and NaN) is +z.
    for d in [[0.0; 3], [f32::NAN; 3]] {
        assert_eq!(sphere::equal_area_inverse(d), [0.5, 0.5]);
        assert_eq!(sphere::uniform_inverse(d), [0.0, 0.0]);
        assert_eq!(sphere::equirect_inverse(d), [0.0, 0.0]);
        assert_eq!(sphere::uniform_hemisphere_inverse(d), [0.5, 0.5]);
        assert_eq!(sphere::cosine_hemisphere_inverse(d), [0.5, 0.5]);
    }
    // Out-of-range input follows the documented clamp.
    common::assert_documented_clamp("equal_area", sphere::equal_area);
    common::assert_documented_clamp("equirect", sphere::equirect);
    // Lat-long conventions: v = 0 is +z, the seam y = -0.0 is u0 = 0.
    assert_eq!(sphere::equirect([0.0, 0.0]), [0.0, 0.0, 1.0]);
    assert_eq!(sphere::equirect([0.25, 0.5]), [0.0, 1.0, 0.0]);
    assert_eq!(sphere::equirect_inverse([1.0, -0.0, 0.0]), [0.0, 0.5]);
    let below = sphere::equirect_inverse([1.0, -1e-30, 0.0])[0];
    assert!((ONE_MINUS_EPS..1.0).contains(&below));
    assert_eq!(
        sphere::equirect_inverse([0.0, 0.0, -1.0]),
        [0.0, ONE_MINUS_EPS]
    );
    // Uniform sphere poles.
    assert_eq!(sphere::uniform([0.0, 0.3]), [0.0, 0.0, 1.0]);
    assert_eq!(sphere::uniform_inverse([0.0, 0.0, -1.0])[0], ONE_MINUS_EPS);
    // Hemispheres: the centre is +z; below the horizon is the mirror image.
    assert_eq!(sphere::uniform_hemisphere([0.5, 0.5]), [0.0, 0.0, 1.0]);
    assert_eq!(sphere::cosine_hemisphere([0.5, 0.5]), [0.0, 0.0, 1.0]);
    for d in [[0.3f32, -0.4, 0.2], [0.0, 0.6, 0.8], [0.6, 0.8, 0.0]] {
        let m = [d[0], d[1], -d[2]];
        assert_eq!(
            sphere::uniform_hemisphere_inverse(d),
            sphere::uniform_hemisphere_inverse(m)
        );
        assert_eq!(
            sphere::cosine_hemisphere_inverse(d),
            sphere::cosine_hemisphere_inverse(m)
        );
    }
}

/// The cosine hemisphere's (x, y) is the concentric disk point, bit for bit, and the top
/// of the input range stays strictly above the horizon.
#[test]
fn cosine_hemisphere_projects_the_concentric_disk() {
    let mut r = rng(19);
    for _ in 0..100_000 {
        let u = unit2(&mut r);
        let d = sphere::cosine_hemisphere(u);
        assert!(same_bits([d[0], d[1]], warpcore::disk::concentric(u)));
    }
    for u in [[0.0, 0.0], [ONE_MINUS_EPS, 0.5], [0.5, 0.0]] {
        assert!(sphere::cosine_hemisphere(u)[2] >= 4.8e-4);
        assert!(sphere::uniform_hemisphere(u)[2] >= 2.3e-7);
    }
}

// ----------------------------------------------------------------------------------------
// Wrapping.

/// The fold in f64 by its definition: half-turns about the edge midpoints, applied one
/// edge at a time (valid within one square of [0, 1]^2).
fn wrap_ref(u: [f32; 2]) -> [f64; 2] {
    let (mut x, mut y) = (u[0] as f64, u[1] as f64);
    if x < 0.0 {
        (x, y) = (-x, 1.0 - y);
    } else if x > 1.0 {
        (x, y) = (2.0 - x, 1.0 - y);
    }
    if y < 0.0 {
        (x, y) = (1.0 - x, -y);
    } else if y > 1.0 {
        (x, y) = (1.0 - x, 2.0 - y);
    }
    [x, y]
}

#[test]
fn wrap_in_range_is_identity_and_out_of_range_folds() {
    let mut r = rng(23);
    for _ in 0..200_000 {
        let u = unit2(&mut r);
        assert!(same_bits(sphere::equal_area_wrap(u), u));
        // Within one square of the edges: matches the sequential fold. (Integer coordinates
        // are on an edge, where both sides name the same direction: skipped.)
        let v = [3.0 * unit(&mut r) - 1.0, 3.0 * unit(&mut r) - 1.0];
        if v.iter().any(|x| x.fract() == 0.0) {
            continue;
        }
        let w = sphere::equal_area_wrap(v);
        assert!(
            dist2(w, wrap_ref(v)) <= 6e-8,
            "{v:?} -> {w:?} vs {:?}",
            wrap_ref(v)
        );
        // Periods (2, 0), (0, 2), (1, 1) and sums of them, far away too: on a grid of
        // 2^-10 (+ half a cell, never an edge) the shifted points are exact.
        let q = v.map(|x| ((x * 1024.0).floor() + 0.5) / 1024.0);
        for shift in [
            [2.0, 0.0],
            [0.0, -2.0],
            [1.0, 1.0],
            [-7.0, 5.0],
            [-64.0, 4096.0],
        ] {
            let s = [q[0] + shift[0], q[1] + shift[1]];
            assert_eq!(
                sphere::equal_area_wrap(s),
                sphere::equal_area_wrap(q),
                "{s:?}"
            );
        }
    }
    for u in [[1.0, 1.0], [0.0, 1.0], [-0.0, 0.5], [1.0, 0.0]] {
        assert!(same_bits(sphere::equal_area_wrap(u), u), "{u:?}");
    }
    // Non-finite and huge coordinates are 0.
    assert_eq!(sphere::equal_area_wrap([f32::NAN, 0.25]), [0.0, 0.25]);
    assert_eq!(sphere::equal_area_wrap([f32::INFINITY, 1e30]), [0.0, 0.0]);
    // A tiny negative coordinate folds to the other half of the opposite coordinate.
    assert_eq!(sphere::equal_area_wrap([-1e-30, 0.25]), [0.0, 0.75]);
}

/// The point of the wrap: equal_area continues smoothly across every edge and corner when
/// composed with it. Walking a path that leaves the square, the direction moves by no more
/// than the local scale of the map.
#[test]
fn wrap_continues_the_map_across_edges() {
    let h = 1.0 / 4096.0f32;
    let mut worst = 0.0f64;
    for k in 0..=4096 {
        let t = k as f32 / 4096.0;
        // Steps of h across each edge, and across the corners diagonally.
        let pairs = [
            ([t, -h / 2.0], [t, h / 2.0]),
            ([t, 1.0 - h / 2.0], [t, 1.0 + h / 2.0]),
            ([-h / 2.0, t], [h / 2.0, t]),
            ([1.0 - h / 2.0, t], [1.0 + h / 2.0, t]),
            ([-h / 2.0, -h / 2.0], [h / 2.0, h / 2.0]),
            ([1.0 + h / 2.0, -h / 2.0], [1.0 - h / 2.0, h / 2.0]),
        ];
        for (a, b) in pairs {
            let da = sphere::equal_area(sphere::equal_area_wrap(a));
            let db = sphere::equal_area(sphere::equal_area_wrap(b));
            worst = worst.max(angle(to64(da), to64(db)));
        }
    }
    // The map's largest stretch is below 2 pi per unit of u (along the edges), so a step of
    // h (or h sqrt 2 across a corner) moves a direction by well under 10 h.
    eprintln!("largest jump across an edge: {worst:.3e} rad for steps of {h:.3e}");
    assert!(worst <= 10.0 * h as f64, "{worst}");
    // A wrong fold (no mirroring of the other coordinate) jumps across the sphere.
    let naive = |u: [f32; 2]| [u[0].rem_euclid(1.0), u[1].rem_euclid(1.0)];
    let (a, b) = ([0.3, -h / 2.0], [0.3, h / 2.0]);
    let jump = angle(
        to64(sphere::equal_area(naive(a))),
        to64(sphere::equal_area(naive(b))),
    );
    assert!(jump > 1.0, "{jump}");
}

/// The texel wrap sends each out-of-range texel to the texel that holds the continuous wrap
/// of its centre.
#[test]
fn texel_wrap_matches_the_continuous_wrap() {
    for n in [1u32, 2, 3, 8, 37, 256] {
        let nf = n as f64;
        for i in -(2 * n as i32) - 3..(3 * n as i32 + 3) {
            for j in [
                -(n as i32) - 1,
                -1,
                0,
                (n / 2) as i32,
                n as i32 - 1,
                n as i32,
                2 * n as i32,
            ] {
                let centre = [
                    ((i as f64 + 0.5) / nf) as f32,
                    ((j as f64 + 0.5) / nf) as f32,
                ];
                let w = sphere::equal_area_wrap(centre);
                let want = [(w[0] as f64 * nf) as u32, (w[1] as f64 * nf) as u32];
                let got = sphere::equal_area_wrap_texel([i, j], n);
                assert_eq!(got, want, "n {n} texel {i} {j}");
                assert!(got[0] < n && got[1] < n);
            }
        }
    }
    assert_eq!(sphere::equal_area_wrap_texel([5, -3], 0), [0, 0]);
    let [a, b] = sphere::equal_area_wrap_texel([i32::MIN, i32::MAX], u32::MAX);
    assert!(a < u32::MAX && b < u32::MAX);
    // In range: unchanged.
    assert_eq!(sphere::equal_area_wrap_texel([3, 4], 8), [3, 4]);
    // One texel beyond the right edge of an 8x8 map: the mirrored texel of the last column.
    assert_eq!(sphere::equal_area_wrap_texel([8, 2], 8), [7, 5]);
    assert_eq!(sphere::equal_area_wrap_texel([-1, -1], 8), [7, 7]);
}

// ----------------------------------------------------------------------------------------
// Densities.

/// Solid angle per unit of square area, by finite differences of the f32 map (in f64):
/// |dd/du0 x dd/du1|.
fn jacobian(f: Fwd, u: [f32; 2], h: f32) -> f64 {
    let d = |a: f32, b: f32| to64(f([a, b]));
    let (p0, m0) = (d(u[0] + h, u[1]), d(u[0] - h, u[1]));
    let (p1, m1) = (d(u[0], u[1] + h), d(u[0], u[1] - h));
    let s = 2.0 * h as f64;
    let du: Vec<f64> = (0..3).map(|k| (p0[k] - m0[k]) / s).collect();
    let dv: Vec<f64> = (0..3).map(|k| (p1[k] - m1[k]) / s).collect();
    norm64([
        du[1] * dv[2] - du[2] * dv[1],
        du[2] * dv[0] - du[0] * dv[2],
        du[0] * dv[1] - du[1] * dv[0],
    ])
}

/// The area-to-solid-angle conversions are the inverse Jacobians of the maps, measured by
/// finite differences; the constants are the inverse Jacobians of the uniform maps.
#[test]
fn densities_match_the_jacobians() {
    let mut r = rng(29);
    let h = 1.0 / 1024.0;
    let (mut e_eq, mut e_ll, mut e_u, mut e_h) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for _ in 0..20_000 {
        // Away from the poles, where the finite difference of sqrt-like maps is inaccurate.
        let u = [0.05 + 0.9 * unit(&mut r), 0.05 + 0.9 * unit(&mut r)];
        let rel = |a: f64, b: f64| (a / b - 1.0).abs();
        // Equal-area: solid angle 4 pi per unit area, away from the fold and seams (where the
        // finite difference straddles a kink).
        let (a, b) = ab(u);
        if (a.abs() + b.abs() - 1.0).abs() > 0.01 && a.abs() > 0.01 && b.abs() > 0.01 {
            let j = jacobian(sphere::equal_area, u, h);
            e_eq = e_eq.max(rel(
                sphere::equal_area_pdf_to_solid_angle(1.0) as f64,
                1.0 / j,
            ));
            e_u = e_u.max(rel(sphere::UNIFORM_PDF as f64, 1.0 / j));
        }
        let j = jacobian(sphere::equirect, u, h);
        let d = sphere::equirect(u);
        e_ll = e_ll.max(rel(
            sphere::equirect_pdf_to_solid_angle(1.0, d) as f64,
            1.0 / j,
        ));
        let j = jacobian(sphere::uniform, u, h);
        e_u = e_u.max(rel(sphere::UNIFORM_PDF as f64, 1.0 / j));
        let c = concentric_ref(u);
        if c[0].abs() > 0.02 && c[1].abs() > 0.02 && (c[0].abs() - c[1].abs()).abs() > 0.02 {
            let j = jacobian(sphere::uniform_hemisphere, u, h);
            e_h = e_h.max(rel(sphere::HEMISPHERE_PDF as f64, 1.0 / j));
        }
    }
    eprintln!(
        "density vs finite-difference Jacobian: equal_area {e_eq:.2e}, equirect {e_ll:.2e}, uniform {e_u:.2e}, hemisphere {e_h:.2e}"
    );
    assert!(e_eq < 1e-3 && e_ll < 1e-3 && e_u < 1e-3 && e_h < 1e-3);
    // Exact values and the documented edge rules.
    assert_eq!(sphere::UNIFORM_PDF, (1.0 / (4.0 * PI)) as f32);
    assert_eq!(sphere::HEMISPHERE_PDF, (1.0 / (2.0 * PI)) as f32);
    assert_eq!(
        sphere::cosine_hemisphere_pdf(1.0),
        std::f32::consts::FRAC_1_PI
    );
    assert_eq!(sphere::cosine_hemisphere_pdf(-0.5), 0.0);
    assert_eq!(sphere::cosine_hemisphere_pdf(f32::NAN), 0.0);
    assert_eq!(
        sphere::equirect_pdf_to_solid_angle(1.0, [0.0, 0.0, 1.0]),
        0.0
    );
    // Unbounded densities give 0, never a saturated f32::MAX: +inf or f32::MAX in, and a
    // quotient that would reach f32::MAX (a huge density next to the axis); just below,
    // the quotient itself.
    for d in [[1.0, 0.0, 0.0], [0.3, -0.4, 0.5]] {
        assert_eq!(sphere::equirect_pdf_to_solid_angle(f32::INFINITY, d), 0.0);
        assert_eq!(sphere::equirect_pdf_to_solid_angle(f32::MAX, d), 0.0);
    }
    assert_eq!(
        sphere::equirect_pdf_to_solid_angle(1e30, [1e-15, 0.0, 1.0]),
        0.0
    );
    let below = f32::from_bits(f32::MAX.to_bits() - 1);
    let q = sphere::equirect_pdf_to_solid_angle(below, [1.0, 0.0, 0.0]) as f64;
    assert!((q * 2.0 * PI * PI / below as f64 - 1.0).abs() < 1e-6, "{q}");
    assert_eq!(
        sphere::cosine_hemisphere_pdf(f32::INFINITY),
        std::f32::consts::FRAC_1_PI
    );
    assert_eq!(
        sphere::cosine_hemisphere_pdf(1.5),
        std::f32::consts::FRAC_1_PI
    );
    // Within about 1e-19 of the axis x^2 + y^2 underflows: that is the axis.
    assert_eq!(
        sphere::equirect_pdf_to_solid_angle(1.0, [1e-30, 0.0, 1.0]),
        0.0
    );
    assert_eq!(sphere::equal_area_pdf_to_solid_angle(f32::INFINITY), 0.0);
    assert_eq!(sphere::equal_area_pdf_to_solid_angle(f32::MAX), 0.0);
    assert_eq!(
        sphere::equal_area_pdf_to_solid_angle(below),
        below * sphere::UNIFORM_PDF
    );
    assert_eq!(sphere::equal_area_pdf_to_solid_angle(-1.0), 0.0);
    // The equator, any length: pdf / (2 pi^2).
    let q = sphere::equirect_pdf_to_solid_angle(2.0, [0.0, 0.5, 0.0]) as f64;
    assert!((q * PI * PI - 1.0).abs() < 3e-7, "{q}");
}

// ----------------------------------------------------------------------------------------
// Chi-square on the sphere: equal-area cells in ((1 - cos theta) / 2, phi / 2 pi).

const NZ: usize = 32;
const NPHI: usize = 64;

fn histogram(seed: u64, warp: impl Fn([f32; 2]) -> [f32; 3]) -> chi2::Histogram {
    let mut h = chi2::Histogram::new(NZ, NPHI);
    let mut r = rng(seed);
    for _ in 0..chi2::SAMPLES {
        h.add(chi2::sphere(warp(unit2(&mut r))));
    }
    h
}

/// Uniform on the upper hemisphere: cells with (1 - z) / 2 < 1/2 (NZ is even, so the
/// horizon is a cell boundary).
fn hemisphere_density(s: [f64; 2]) -> f64 {
    if s[0] < 0.5 { 1.0 } else { 0.0 }
}

/// cos theta / pi on the upper hemisphere: z = 1 - 2 s0.
fn cosine_density(s: [f64; 2]) -> f64 {
    if s[0] < 0.5 { 1.0 - 2.0 * s[0] } else { 0.0 }
}

#[test]
fn chi2_equal_area() {
    let h = histogram(301, sphere::equal_area);
    chi2::check("sphere::equal_area", &h, &chi2::expected_uniform(NZ, NPHI));
}

#[test]
fn chi2_uniform() {
    let h = histogram(302, sphere::uniform);
    chi2::check("sphere::uniform", &h, &chi2::expected_uniform(NZ, NPHI));
}

#[test]
fn chi2_uniform_hemisphere() {
    let h = histogram(303, sphere::uniform_hemisphere);
    let expected = chi2::expected_from_density(NZ, NPHI, hemisphere_density);
    chi2::check("sphere::uniform_hemisphere", &h, &expected);
}

#[test]
fn chi2_cosine_hemisphere() {
    let h = histogram(304, sphere::cosine_hemisphere);
    let expected = chi2::expected_from_density(NZ, NPHI, cosine_density);
    chi2::check("sphere::cosine_hemisphere", &h, &expected);
}

/// Lat-long is not uniform: theta = pi u1 gives s0 = sin^2(theta / 2) with CDF
/// (2 / pi) asin(sqrt(s0)), integrated exactly per cell (the density is singular at the
/// poles, so no quadrature).
#[test]
fn chi2_equirect() {
    let h = histogram(305, sphere::equirect);
    let cdf = |s: f64| 2.0 / PI * s.sqrt().asin();
    let mut expected = vec![0.0; NZ * NPHI];
    for j in 0..NPHI {
        for i in 0..NZ {
            let p = cdf((i + 1) as f64 / NZ as f64) - cdf(i as f64 / NZ as f64);
            expected[j * NZ + i] = p / NPHI as f64;
        }
    }
    chi2::check("sphere::equirect", &h, &expected);
}

/// The tests can fail: a non-equal-area octahedral map (z = 1 - r instead of 1 - r^2,
/// with matching xy), the uniform hemisphere against the cosine density, and the equirect
/// map against the uniform density are all rejected decisively.
#[test]
fn chi2_rejects_wrong_warps() {
    let linear_z = |u: [f32; 2]| {
        let d = sphere::equal_area(u);
        let z = d[2].signum() * (1.0 - (1.0 - d[2].abs()).sqrt()); // 1 - r instead of 1 - r^2
        let s = ((1.0 - z * z).max(0.0) / (d[0] * d[0] + d[1] * d[1]).max(1e-30)).sqrt();
        [d[0] * s, d[1] * s, z]
    };
    let h = histogram(306, linear_z);
    let p = chi2::statistic(&h, &chi2::expected_uniform(NZ, NPHI))
        .unwrap()
        .p_value;
    assert!(p < 1e-12, "{p}");
    let h = histogram(307, sphere::uniform_hemisphere);
    let expected = chi2::expected_from_density(NZ, NPHI, cosine_density);
    assert!(chi2::statistic(&h, &expected).unwrap().p_value < 1e-12);
    let h = histogram(308, sphere::equirect);
    assert!(
        chi2::statistic(&h, &chi2::expected_uniform(NZ, NPHI))
            .unwrap()
            .p_value
            < 1e-12
    );
    // A subtle one: 1% of the mass moved from the lower to the upper hemisphere.
    let mut r = rng(309);
    let mut h = chi2::Histogram::new(NZ, NPHI);
    for _ in 0..chi2::SAMPLES {
        let mut d = sphere::equal_area(unit2(&mut r));
        if d[2] < 0.0 && unit(&mut r) < 0.02 {
            d[2] = -d[2];
        }
        h.add(chi2::sphere(d));
    }
    chi2::assert_rejects_uniform(&h, NZ, NPHI);
}

/// Found by the `sphere` fuzz target: the smallest negative subnormal halves to -0.0 in the
/// modulo-2 reduction and used to come back unchanged (outside the square). It must fold like
/// any other tiny negative coordinate: (-e, v) -> (e, 1 - v).
#[test]
fn wrap_folds_the_smallest_negative_subnormal() {
    let tiny = -f32::from_bits(1);
    for v in [0.0f32, 2.350_989e-38, 0.25, 0.999] {
        let w = sphere::equal_area_wrap([tiny, v]);
        assert!(w.iter().all(|c| (0.0..=1.0).contains(c)), "{v}: {w:?}");
        assert_eq!(w, sphere::equal_area_wrap([-1e-30, v]), "{v}");
        let w = sphere::equal_area_wrap([v, tiny]);
        assert!(w.iter().all(|c| (0.0..=1.0).contains(c)), "{v}: {w:?}");
    }
    assert_eq!(
        sphere::equal_area_wrap([-0.0, 0.5])[0].to_bits(),
        (-0.0f32).to_bits()
    );
}
