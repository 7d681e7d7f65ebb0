//! The report (`report/`, the `warpcore-report` crate), tested through its library: the references
//! are right (closed forms, limit cases, an independent quadrature, Monte Carlo), the
//! estimators are unbiased, and the `--quick` run works end to end.
// The report is a native desktop tool (threads, files): not run under wasm.
#![cfg(all(
    feature = "disk",
    feature = "triangle",
    feature = "pmj02bn",
    feature = "sequence",
    not(target_family = "wasm")
))]
// Component-wise loops index several arrays with one counter.
#![allow(clippy::needless_range_loop)]

use warpcore_report::app;
use warpcore_report::area;
#[cfg(feature = "envmap")]
use warpcore_report::envscene;
use warpcore_report::math;
#[cfg(feature = "envmap")]
use warpcore_report::orientation;
use warpcore_report::path;
use warpcore_report::plots;
use warpcore_report::run;
use warpcore_report::samplers;
#[cfg(feature = "spherical")]
use warpcore_report::solid_angle;
#[cfg(feature = "envmap")]
use warpcore_report::sphere_ref;

use area::{AreaScene, Cut, Shape};
use math::{Rng, dot3, gauss_legendre, integrate};
use run::{Scene, Scratch};
use samplers::{SAMPLERS, Sampler};
use statrs::distribution::{ContinuousCDF, Normal};
use std::f64::consts::PI;

// ----------------------------------------------------------------------------------------
// Statistics

/// The two-sided bound on a standard normal statistic for one of `family` tests at
/// suite-wide level 1% (Sidak): `Phi^-1(1 - alpha' / 2)`, `alpha' = 1 - 0.99^(1 / family)`.
fn sidak_bound(family: u32) -> f64 {
    let alpha = 1.0 - 0.99f64.powf(1.0 / family as f64);
    Normal::standard().inverse_cdf(1.0 - alpha / 2.0)
}

// ----------------------------------------------------------------------------------------
// Quadrature for the independent checks

fn gl32() -> &'static [(f64, f64)] {
    static RULE: std::sync::OnceLock<Vec<(f64, f64)>> = std::sync::OnceLock::new();
    RULE.get_or_init(|| gauss_legendre(32))
}

/// `int_a^b f` by tanh-sinh (double-exponential) quadrature with step `h` (Takahashi and
/// Mori): exponentially convergent for `f` analytic inside `(a, b)`, even with algebraic
/// singularities such as `sqrt(b - x)` at the ends, which the nodes never touch.
fn tanh_sinh(a: f64, b: f64, h: f64, mut f: impl FnMut(f64) -> f64) -> f64 {
    let half = 0.5 * (b - a);
    let mut sum = std::f64::consts::FRAC_PI_2 * f(0.5 * (a + b));
    for k in 1.. {
        let t = k as f64 * h;
        let s = std::f64::consts::FRAC_PI_2 * t.sinh();
        let w = std::f64::consts::FRAC_PI_2 * t.cosh() / (s.cosh() * s.cosh());
        // Distance of the nodes from the ends, without cancellation: half (1 - tanh s).
        let d = half * 2.0 / (1.0 + (2.0 * s).exp());
        if w < 1e-20 || a + d <= a || b - d >= b {
            break;
        }
        sum += w * (f(a + d) + f(b - d));
    }
    half * h * sum
}

// ----------------------------------------------------------------------------------------
// Area-light references

/// The irradiance by an independent method: Fubini over the clipped light (convex), the
/// outer integral in `x` by tanh-sinh between the `x` of its corners (square-root endpoint
/// behaviour at a disk's extreme `x` is what tanh-sinh handles), the inner one in `y` by
/// 32-point Gauss-Legendre (the integrand is analytic), the `y` range found directly from
/// the shape and the cut at each `x`.
fn irradiance_fubini(shape: &Shape, q: [f64; 2], h: f64, cut: Cut) -> f64 {
    // y-range of the shape at x.
    let shape_range = |x: f64| -> Option<(f64, f64)> {
        match shape {
            Shape::Rect { hx, hy } => (x.abs() <= *hx).then_some((-hy, *hy)),
            Shape::Disk { r } => (x.abs() <= *r).then(|| {
                let s = (r * r - x * x).max(0.0).sqrt();
                (-s, s)
            }),
            Shape::Triangle { v } => {
                let mut ys = Vec::new();
                for i in 0..3 {
                    let (a, b) = (v[i], v[(i + 1) % 3]);
                    if (a[0] - x) * (b[0] - x) <= 0.0 && a[0] != b[0] {
                        let t = (x - a[0]) / (b[0] - a[0]);
                        ys.push(a[1] + t * (b[1] - a[1]));
                    }
                }
                let lo = ys.iter().copied().fold(f64::MAX, f64::min);
                let hi = ys.iter().copied().fold(f64::MIN, f64::max);
                (lo <= hi).then_some((lo, hi))
            }
        }
    };
    // The cut e . p >= k at fixed x: e1 y >= k - e0 x.
    let range = |x: f64| -> Option<(f64, f64)> {
        let (mut lo, mut hi) = shape_range(x)?;
        let rhs = cut.k - cut.e[0] * x;
        if cut.e[1] > 0.0 {
            lo = lo.max(rhs / cut.e[1]);
        } else if cut.e[1] < 0.0 {
            hi = hi.min(rhs / cut.e[1]);
        } else if rhs > 0.0 {
            return None;
        }
        (lo < hi).then_some((lo, hi))
    };
    // Breakpoints: the shape's x-extent, its corners, and where the cut meets the boundary.
    let [hx, _] = shape.half_extents();
    let mut xs = vec![-hx, hx];
    if let Some(poly) = shape.polygon() {
        xs.extend(poly.iter().map(|p| p[0]));
        xs.extend(area::clip(&poly, cut).iter().map(|p| p[0]));
    } else if let Shape::Disk { r } = shape {
        let d = cut.k;
        if d.abs() < *r {
            let s = (r * r - d * d).sqrt();
            let t = [-cut.e[1], cut.e[0]];
            xs.push(d * cut.e[0] + s * t[0]);
            xs.push(d * cut.e[0] - s * t[0]);
        }
    }
    xs.sort_by(f64::total_cmp);
    xs.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
    let inner = |x: f64| match range(x) {
        Some((lo, hi)) => integrate(gl32(), lo, hi, |y| area::integrand([x, y], q, h)),
        None => 0.0,
    };
    xs.windows(2)
        .filter(|w| w[1] > w[0])
        .map(|w| tanh_sinh(w[0], w[1], 1.0 / 64.0, inner))
        .sum()
}

#[test]
fn area_references_match_an_independent_quadrature() {
    let mut worst: f64 = 0.0;
    for scene in AreaScene::all() {
        for i in 0..300 {
            let (q, cut) = scene.geometry(i);
            let exact = area::irradiance(&scene.shape, q, area::HEIGHT, cut);
            let fubini = irradiance_fubini(&scene.shape, q, area::HEIGHT, cut);
            let err = (exact - fubini).abs();
            worst = worst.max(err);
            assert!(
                err < 1e-10,
                "{} pixel {i}: contour {exact} vs quadrature {fubini}",
                scene.name()
            );
        }
    }
    println!("contour references vs Fubini quadrature: max |difference| {worst:.2e}");
}

#[test]
fn area_references_limit_cases() {
    let h = area::HEIGHT;
    for scene in AreaScene::all() {
        let mut rng = Rng::new(3);
        for _ in 0..100 {
            let q = [rng.uniform() - 0.5, rng.uniform() - 0.5];
            let a = std::f64::consts::TAU * rng.uniform();
            let e = [a.cos(), a.sin()];
            // A line beyond the light: all visible, or nothing.
            let all = area::irradiance(&scene.shape, q, h, Cut { e, k: -10.0 });
            let none = area::irradiance(&scene.shape, q, h, Cut { e, k: 10.0 });
            assert_eq!(none, 0.0);
            let full = irradiance_fubini(&scene.shape, q, h, Cut { e, k: -10.0 });
            assert!(
                (all - full).abs() < 1e-10,
                "{}: {all} vs {full}",
                scene.name()
            );
            // Both sides of any line add up to the whole light.
            let k = 0.8 * (rng.uniform() - 0.5);
            let (s0, s1) = (
                area::irradiance(&scene.shape, q, h, Cut { e, k }),
                area::irradiance(
                    &scene.shape,
                    q,
                    h,
                    Cut {
                        e: [-e[0], -e[1]],
                        k: -k,
                    },
                ),
            );
            assert!(
                (s0 + s1 - all).abs() < 1e-13,
                "{}: {s0} + {s1} vs {all}",
                scene.name()
            );
        }
    }
    // The whole disk in closed form: E = (pi/2)(1 - (h^2 + d^2 - R^2) / sqrt((h^2 + d^2 +
    // R^2)^2 - 4 d^2 R^2)) at distance d from the axis (the off-axis parallel disk).
    let r = (1.0 / PI).sqrt();
    for &d in &[0.0, 0.1, 0.3, 0.56, 0.7] {
        let e = area::irradiance(
            &area::disk(),
            [d, 0.0],
            h,
            Cut {
                e: [1.0, 0.0],
                k: -10.0,
            },
        );
        let (a, b) = (h * h + d * d - r * r, h * h + d * d + r * r);
        let closed = 0.5 * PI * (1.0 - a / (b * b - 4.0 * d * d * r * r).sqrt());
        assert!((e - closed).abs() < 1e-13, "d = {d}: {e} vs {closed}");
    }
    // A unit square straight below, small: E -> area / h^2 as the light shrinks relative to h.
    let tiny = Shape::Rect { hx: 1e-4, hy: 1e-4 };
    let e = area::irradiance(
        &tiny,
        [0.0, 0.0],
        h,
        Cut {
            e: [1.0, 0.0],
            k: -1.0,
        },
    );
    assert!((e / 4e-8 - 1.0).abs() < 1e-7, "{e}");
}

/// Every light has unit area, and every warp's samples land on it.
#[test]
fn area_scenes_samples_land_on_the_light() {
    for scene in AreaScene::all() {
        assert!((scene.shape.area() - 1.0).abs() < 1e-14, "{}", scene.name());
        // The shape grown by 1e-6, for the f32 rounding of the warps.
        let grown = |x: [f64; 2]| {
            let r = (x[0] * x[0] + x[1] * x[1]).sqrt();
            let k = if r > 0.0 {
                (r - 1e-6).max(0.0) / r
            } else {
                1.0
            };
            scene.shape.contains([x[0] * k, x[1] * k])
        };
        let [hx, hy] = scene.shape.half_extents();
        let in_box = |x: [f64; 2]| x[0].abs() <= hx && x[1].abs() <= hy;
        let mut s = Scratch::default();
        for (w, name) in scene.warps().iter().enumerate() {
            for sampler in SAMPLERS {
                if !scene.applies(w, sampler) {
                    continue;
                }
                for seed in 0..8 {
                    scene.draw(w, sampler, 1024, seed, &mut s);
                    let points = scene.points(w, 1024, &s);
                    // pad_zero's samples cover the bounding square (those off the disk count
                    // 0); every other warp's lie on the light.
                    let on: &dyn Fn([f64; 2]) -> bool =
                        if *name == "pad_zero" { &in_box } else { &grown };
                    for x in &points {
                        assert!(on(*x), "{} {name} {}: {x:?}", scene.name(), sampler.name());
                    }
                    if *name == "pad_zero" {
                        // About pi/4 of them on the disk (1024 uniform points: 4.5 sigma).
                        let inside = points.iter().filter(|x| grown(**x)).count() as f64;
                        assert!((inside / 1024.0 - PI / 4.0).abs() < 0.06, "{inside}");
                    }
                }
            }
        }
    }
}

// ----------------------------------------------------------------------------------------
// Unbiasedness

/// Number of unbiasedness tests in this file (the Sidak family): every applicable (scene,
/// warp, sampler) of the area scenes — per class (lit, penumbra): square and skinny 5 each,
/// disk 6 x 5, triangle 2 x 5 + 2 x 2 (Basu-Owen: random indices, and the construction) —
/// and of the two built-in environment-map scenes (2 classes x 4 warps x 5 samplers each).
const BIAS_FAMILY: u32 = 2 * (5 + 5 + 30 + 14) + 2 * 2 * (4 * 5 + 2 * 3);

/// Mean over `pixels` pixels of `estimate - reference` at `spp` samples, in units of its
/// standard error: a standard normal variable (by the central limit theorem over
/// independent pixels) when the estimator is unbiased.
fn bias_z<S: Scene>(
    scene: &S,
    pixels: &[S::Pixel],
    warp: usize,
    sampler: Sampler,
    spp: usize,
) -> f64 {
    let mut stat = run::Stat::default();
    let mut s = Scratch::default();
    let name = scene.name();
    for (i, px) in pixels.iter().enumerate() {
        // Seeds independent of the report's own.
        let seed = run::seed(&name, i as u64, spp, sampler) ^ 0x5bd1_e995;
        scene.draw_for(px, warp, sampler, spp, seed, &mut s);
        stat.add(scene.evaluate(px, warp, spp, &s) - scene.reference(px, warp));
    }
    stat.bias_z()
}

/// Asserts that the mean error of every warp and sampler of `scene` that `tested` selects,
/// over `pixels` pixels at 16 samples per pixel, is within `bound` standard errors; returns
/// how many it tested.
fn assert_unbiased<S: Scene>(
    scene: &S,
    pixels: u64,
    bound: f64,
    tested: impl Fn(usize, Sampler) -> bool,
) -> u32 {
    let pixels: Vec<_> = (0..pixels).map(|i| scene.pixel(i)).collect();
    let mut tests = 0;
    for (w, name) in scene.warps().iter().enumerate() {
        for sampler in SAMPLERS.into_iter().filter(|&s| tested(w, s)) {
            tests += 1;
            let z = bias_z(scene, &pixels, w, sampler, 16);
            println!(
                "{} {name} {}: z = {z:+.2} (bound {bound:.2})",
                scene.name(),
                sampler.name()
            );
            assert!(
                z.abs() < bound,
                "{} {name} {}: z = {z} (bound {bound:.2})",
                scene.name(),
                sampler.name()
            );
        }
    }
    tests
}

/// The rows the report runs of `scene`: not an alias of another sampler's, applicable.
fn reported<S: Scene>(scene: &S) -> impl Fn(usize, Sampler) -> bool + '_ {
    |w, sampler| scene.alias(w, sampler).is_none() && scene.applies(w, sampler)
}

/// For each area scene (both pixel classes), warp and sampler, the mean error over 4096
/// pixels at 16 samples per pixel is within the Sidak bound (4.0 standard errors for 188
/// tests at 1% overall). Rejection sampling included: its stopping rule (points until `N`
/// land in the disk) does not bias it measurably for any sampler here.
#[test]
fn area_estimators_are_unbiased() {
    let bound = sidak_bound(BIAS_FAMILY);
    for scene in AreaScene::all() {
        assert_unbiased(&scene, 4096, bound, reported(&scene));
    }
}

/// The solid-angle scenes (issue 22), every warp (by area, by solid angle, cosine-aware by
/// solid angle) and applicable sampler, both classes at the three distances: the mean error
/// over 1024 pixels at 16 samples per pixel is within the Sidak bound for this family
/// (3 ratios x 2 classes x (17 triangle + 15 square + 15 16:1 (warp, sampler) rows): 282 tests
/// at 1% overall, about 4.1 standard errors).
#[cfg(feature = "spherical")]
#[test]
fn solid_angle_estimators_are_unbiased() {
    const FAMILY: u32 = 3 * 2 * (17 + 15 + 15);
    let bound = sidak_bound(FAMILY);
    let mut tests = 0;
    for scene in solid_angle::SolidAngleScene::all() {
        tests += assert_unbiased(&scene, 1024, bound, reported(&scene));
    }
    assert_eq!(tests, FAMILY, "the family size in the bound");
}

/// The same test rejects a wrong warp (by far: z > 3 bounds): the polar map with `r = u0` instead of `sqrt(u0)`
/// (points crowd the centre, and the estimator, still weighted by the uniform density,
/// overestimates).
#[test]
fn bias_test_rejects_a_wrong_warp() {
    let scene = AreaScene::all()
        .into_iter()
        .find(|s| s.name() == "disk/penumbra")
        .unwrap();
    let r = (1.0 / PI).sqrt();
    let mut stat = run::Stat::default();
    for i in 0..4096u64 {
        let px = scene.pixel(i);
        let mut sum = 0.0;
        for k in 0..16u32 {
            let u = warpcore::sequence::random(k, i as u32);
            let t = std::f64::consts::TAU * u[1] as f64;
            let x = [r * u[0] as f64 * t.cos(), r * u[0] as f64 * t.sin()];
            if px.cut.visible(x) {
                sum += area::integrand(x, px.q, area::HEIGHT);
            }
        }
        stat.add(sum / 16.0 - px.reference);
    }
    let z = stat.bias_z();
    println!("wrong polar warp: z = {z:.1}");
    assert!(z > 3.0 * sidak_bound(BIAS_FAMILY), "{z}");
}

// ----------------------------------------------------------------------------------------
// The quick run, end to end

#[test]
fn quick_run_writes_a_well_formed_csv() {
    let out = std::env::temp_dir().join(format!("warpcore-report-{}", std::process::id()));
    let opts = app::Options {
        quick: true,
        out: out.clone(),
        ..app::Options::default()
    };
    let t = std::time::Instant::now();
    let results = app::run(&opts).expect("the quick run");
    println!("quick run: {:.1} s", t.elapsed().as_secs_f64());
    // Frames of 1 spp on the path scenes (issue 34): one table per scene, every sampler.
    #[cfg(feature = "blue-noise")]
    {
        let frames = std::fs::read_to_string(out.join("path-frames.md")).unwrap();
        for row in [
            "| white noise |",
            "| blue_sobol |",
            "| openqmc_pmjbn |",
            "| zsobol |",
        ] {
            assert_eq!(frames.matches(row).count(), 2, "{row} in path-frames.md");
        }
    }
    let csv = std::fs::read_to_string(out.join("results.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("scene,sampler,warp,spp,mse,ns_per_sample")
    );
    let disk = area::DISK_WARPS.map(area::AreaWarp::name).to_vec();
    let triangle = area::TRIANGLE_WARPS.map(area::AreaWarp::name).to_vec();
    let mut warps_of: Vec<(String, Vec<&str>)> = Vec::new();
    for (light, warps) in [
        ("square", vec!["identity"]),
        ("skinny", vec!["identity"]),
        ("disk", disk),
        ("triangle", triangle),
    ] {
        for class in ["", "/lit", "/penumbra"] {
            warps_of.push((format!("{light}{class}"), warps.clone()));
        }
    }
    #[cfg(feature = "envmap")]
    {
        let env = envscene::WARPS.to_vec();
        for map in ["envmap:sky", "envmap:interior", "envmap:sky_200x100"] {
            warps_of.push((map.to_string(), env.clone()));
            warps_of.push((format!("{map}/lit"), env.clone()));
        }
    }
    // Lights by solid angle (issue 22): by area and by solid angle at three distances.
    if cfg!(feature = "spherical") {
        for light in ["triangle", "square", "skinny"] {
            let warps = if light == "triangle" {
                vec![
                    "area",
                    "area_basu_owen_permuted",
                    "solid_angle",
                    "solid_angle_cos",
                ]
            } else {
                vec!["area", "solid_angle", "solid_angle_cos"]
            };
            for ratio in ["4", "1", "0.25"] {
                for class in ["/lit", "/penumbra"] {
                    warps_of.push((format!("sa_{light}_r{ratio}{class}"), warps.clone()));
                }
            }
        }
    }
    let spps = ["4", "16", "64", "256"];
    let samplers = [
        "random",
        "stratified",
        "pmj02bn",
        "pmj02bn_cp",
        "sobol_owen",
    ];
    // Index-driven Basu-Owen rows: random indices, and the construction under `stratified`
    // and `pmj02bn`; the peers' point-set randomizations do not apply.
    // The env-map `_mis` rows: random, pmj02bn and Sobol' only (the report's time budget).
    let rows_of = |warp: &str| {
        if warp.contains("basu_owen") || warp.ends_with("_mis") {
            3
        } else {
            5
        }
    };
    let mut seen = std::collections::HashSet::new();
    let mut path_rows = std::collections::HashSet::new();
    let mut study_rows = std::collections::HashSet::new();
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f.len(), 6, "{line}");
        // The path study's scenes (warp `path`, Burley 2020's boxes and the ablations): their
        // samplers at 4 to 64 spp in the quick run, a variance (finite, positive).
        let study = path::study::PAPER.iter().any(|p| p.1 == f[0])
            || path::study::ABLATIONS.iter().any(|a| a.0 == f[0])
            || path::study::glossy_scenes().iter().any(|g| g == f[0]);
        if f[2] == "path" && study {
            assert!(path::samplers::Kind::by_name(f[1]).is_some(), "{line}");
            assert!(["4", "16", "64"].contains(&f[3]), "{line}");
            let mse: f64 = f[4].parse().unwrap();
            assert!(mse.is_finite() && mse > 0.0, "{line}");
            assert!(
                study_rows.insert((f[0].to_string(), f[1], f[3])),
                "duplicate row {line}"
            );
            continue;
        }
        // The path-traced scenes (warp `path`): 13 samplers at 1 to 16 spp in the quick run.
        if f[2] == "path" {
            assert!(path::scene::Scene::NAMES.contains(&f[0]), "{line}");
            assert!(
                path::samplers::KINDS.iter().any(|k| k.name() == f[1]),
                "{line}"
            );
            assert!(["1", "2", "4", "8", "16"].contains(&f[3]), "{line}");
            let (mse, ns): (f64, f64) = (f[4].parse().unwrap(), f[5].parse().unwrap());
            assert!(
                mse.is_finite() && mse > 0.0 && ns.is_finite() && ns > 0.0,
                "{line}"
            );
            assert!(
                path_rows.insert((f[0].to_string(), f[1], f[3])),
                "duplicate row {line}"
            );
            continue;
        }
        let warps = &warps_of.iter().find(|(s, _)| s == f[0]).expect(line).1;
        assert!(samplers.contains(&f[1]), "{line}");
        assert!(warps.contains(&f[2]), "{line}");
        assert!(
            !(f[2].contains("basu_owen") && ["pmj02bn_cp", "sobol_owen"].contains(&f[1])),
            "{line}"
        );
        assert!(
            !(f[2].ends_with("_mis") && ["stratified", "pmj02bn_cp"].contains(&f[1])),
            "{line}"
        );
        assert!(spps.contains(&f[3]), "{line}");
        let mse: f64 = f[4].parse().unwrap();
        let ns: f64 = f[5].parse().unwrap();
        assert!(mse.is_finite() && mse > 0.0, "{line}");
        assert!(ns.is_finite() && ns > 0.0, "{line}");
        assert!(
            seen.insert((f[0].to_string(), f[1], f[2], f[3])),
            "duplicate row {line}"
        );
    }
    let expected: usize = warps_of
        .iter()
        .map(|(_, w)| w.iter().map(|w| rows_of(w)).sum::<usize>() * spps.len())
        .sum();
    assert_eq!(seen.len(), expected);
    assert_eq!(path_rows.len(), 2 * 13 * 5);
    // Quick: Burley's 5 boxes x 7 columns at one count, 2 ablations x 2 samplers x 3 counts,
    // the glossy family's 3 roughnesses x 3 BSDF samplers x 3 pixel samplers x 3 counts.
    assert_eq!(study_rows.len(), 5 * 7 + 2 * 2 * 3 + 3 * 3 * 3 * 3);
    let filtered = std::fs::read_to_string(out.join("filtered.csv")).unwrap();
    assert_eq!(filtered.lines().next(), Some("scene,sampler,spp,sigma,mse"));
    assert_eq!(filtered.lines().count(), 1 + 2 * 13 * 3 * 5);
    assert_eq!(results.len(), warps_of.len());
    for (scene, _) in &warps_of {
        assert!(out.join(plots::file_name(scene)).exists(), "{scene} plot");
    }
    assert!(out.join("strata.svg").exists());
    if cfg!(feature = "envmap") {
        // The orientation study: both orientations of every env-map class.
        let o = std::fs::read_to_string(out.join("envmap_orientation.csv")).unwrap();
        for map in ["envmap:sky", "envmap:interior", "envmap:sky_200x100"] {
            for orient in ["authored", "rotated"] {
                let prefix = format!("{map},{orient},stratified,hierarchical_equal_area,16,");
                assert!(o.lines().any(|l| l.starts_with(&prefix)), "{prefix}");
            }
        }
        let md = std::fs::read_to_string(out.join("envmap_orientation.md")).unwrap();
        assert!(md.contains("| `stratified` | 16 |"), "{md}");
        assert!(out.join("envmap_orientation_split.csv").exists());
    }
    // The mix is the class-weighted sum: between the lit and penumbra MSE of every row.
    for light in ["square", "skinny", "disk", "triangle"] {
        let get = |name: String| results.iter().find(|r| r.scene == name).unwrap();
        let (mix, lit, pen) = (
            get(light.to_string()),
            get(format!("{light}/lit")),
            get(format!("{light}/penumbra")),
        );
        for (k, row) in mix.rows.iter().enumerate() {
            for j in 0..spps.len() {
                let (m, l, p) = (row.mse(j), lit.rows[k].mse(j), pen.rows[k].mse(j));
                assert!(
                    m < p && m > 0.0 && (m > l || l > p * 0.5),
                    "{light} {k} {j}: {m} {l} {p}"
                );
            }
        }
    }
    // The recommendations and the comparison with the source cover every light and class.
    let rec = std::fs::read_to_string(out.join("recommendations.md")).unwrap();
    for (scene, _) in &warps_of {
        let (light, class) = scene.split_once('/').unwrap_or((scene, ""));
        assert!(
            rec.lines()
                .any(|l| l.starts_with(&format!("| {light} |")) && l.contains(class)),
            "{scene} missing from the recommendations"
        );
    }
    let cmp = std::fs::read_to_string(out.join("comparison.md")).unwrap();
    assert!(
        cmp.lines().filter(|l| l.starts_with("| ")).count() >= 15,
        "{cmp}"
    );
    // Converging: every row's MSE falls by at least 10x from 4 to 256 samples (64x the
    // samples; random sampling's rate gives 64x).
    for r in &results {
        for row in &r.rows {
            let (first, last) = (row.mse(0), row.mse(r.spps.len() - 1));
            assert!(
                last < first / 10.0,
                "{} {} {}: {first} -> {last}",
                r.scene,
                row.sampler.name(),
                row.warp
            );
        }
    }
    let _ = std::fs::remove_dir_all(&out);
}

// ----------------------------------------------------------------------------------------
// Environment-map references

#[cfg(feature = "envmap")]
mod env {
    use super::*;
    use sphere_ref::{EqualArea, Grid, LatLong, Param};

    /// A uniform map: `int_{n . w >= 0, m . w >= 0} n . w dw = (pi / 2)(1 + n . m)` (the lune
    /// between the two hemispheres; Stokes with the two half-circles as its boundary).
    fn uniform_map_case<P: Param>(param: P, w: usize, h: usize) -> f64 {
        let grid = Grid::new(param, w, h);
        let ones = vec![1.0; w * h];
        let mut rng = Rng::new(7);
        let mut worst: f64 = 0.0;
        for _ in 0..40 {
            let (n, m) = (rng.direction(), rng.direction());
            let exact = 0.5 * PI * (1.0 + dot3(n, m));
            let got = grid.integral(&ones, n, m);
            worst = worst.max((got - exact).abs());
        }
        worst
    }

    #[test]
    fn envmap_reference_uniform_map_latlong() {
        let e = uniform_map_case(LatLong, 64, 32);
        println!("lat-long 64x32: max |error| {e:.2e}");
        assert!(e < 1e-12, "{e}");
    }

    #[test]
    fn envmap_reference_uniform_map_equal_area() {
        for s in [31, 32] {
            let e = uniform_map_case(EqualArea, s, s);
            println!("equal-area {s}x{s}: max |error| {e:.2e}");
            assert!(e < 1e-12, "{e}");
        }
    }

    #[test]
    #[ignore]
    fn envmap_reference_speed() {
        let scenes = envscene::EnvScene::builtin(1);
        let s = &scenes[0];
        let t = std::time::Instant::now();
        let mut acc = 0.0;
        for i in 0..300 {
            let (n, m) = s.geometry(i);
            acc += s.latlong.grid.integral(&s.latlong.radiance, n, m);
        }
        let ll = t.elapsed().as_secs_f64() / 300.0;
        let t = std::time::Instant::now();
        for i in 0..300 {
            let (n, m) = s.geometry(i);
            acc += s.equal_area.grid.integral(&s.equal_area.radiance, n, m);
        }
        let ea = t.elapsed().as_secs_f64() / 300.0;
        println!(
            "per pixel: lat-long {:.2} ms, equal-area {:.2} ms ({acc})",
            ll * 1e3,
            ea * 1e3
        );
    }

    /// The closed-form lat-long edge integrals against Gauss-Legendre of `w x dw`.
    #[test]
    fn latlong_edge_integrals_match_quadrature() {
        let mut rng = Rng::new(11);
        let mut worst: f64 = 0.0;
        for _ in 0..2000 {
            let u = [rng.uniform(), rng.uniform()];
            let axis = (rng.uniform() * 2.0) as usize;
            let (a, b) = (u[axis], u[axis] + 0.05 * rng.uniform());
            let closed = LatLong.edge_integral(u, axis, a, b).unwrap();
            let mut quad = [0.0; 3];
            for k in 0..3 {
                quad[k] = integrate(gl32(), a, b, |t| {
                    let mut p = u;
                    p[axis] = t;
                    let (d, dd) = LatLong.dir_d(p, axis);
                    math::cross3(d, dd)[k]
                });
            }
            for k in 0..3 {
                worst = worst.max((closed[k] - quad[k]).abs());
            }
        }
        println!("lat-long edge integrals: max |closed form - quadrature| {worst:.2e}");
        assert!(worst < 1e-14, "{worst}");
    }

    /// The references integrate over the texels the crate's warps map to: the `f64` maps agree
    /// with `sphere::equirect` and `sphere::equal_area` to `f32` precision, and the inverses
    /// undo them.
    #[test]
    fn reference_parameterizations_are_the_crates() {
        let mut rng = Rng::new(12);
        let (mut worst_ll, mut worst_ea, mut worst_inv): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for _ in 0..200_000 {
            let u32 = [rng.uniform() as f32, rng.uniform() as f32];
            let u = [u32[0] as f64, u32[1] as f64];
            let dist = |a: [f64; 3], b: [f32; 3]| {
                (0..3)
                    .map(|k| (a[k] - b[k] as f64).abs())
                    .fold(0.0, f64::max)
            };
            worst_ll = worst_ll.max(dist(LatLong.dir(u), warpcore::sphere::equirect(u32)));
            worst_ea = worst_ea.max(dist(EqualArea.dir(u), warpcore::sphere::equal_area(u32)));
            for (p, d) in [
                (&LatLong as &dyn Param, LatLong.dir(u)),
                (&EqualArea, EqualArea.dir(u)),
            ] {
                let back = p.inverse(d);
                // Away from the lat-long poles (where the azimuth is lost).
                if (0.001..0.999).contains(&u[1]) {
                    worst_inv = worst_inv.max((back[0] - u[0]).abs().max((back[1] - u[1]).abs()));
                }
            }
        }
        println!(
            "vs crate: lat-long {worst_ll:.2e}, equal-area {worst_ea:.2e}; inverse {worst_inv:.2e}"
        );
        assert!(worst_ll < 3e-7 && worst_ea < 3e-7, "{worst_ll} {worst_ea}");
        assert!(worst_inv < 1e-12, "{worst_inv}");
    }

    /// The two sides of any cut add up to the same uncut lobe, on real texel values; and the
    /// degenerate cuts `m = n` (the whole lobe) and `m = -n` (nothing) are handled.
    #[test]
    fn complementary_cuts_add_up() {
        let scenes = envscene::EnvScene::builtin(1);
        let mut rng = Rng::new(13);
        let mut worst: f64 = 0.0;
        let neg = |m: [f64; 3]| [-m[0], -m[1], -m[2]];
        for scene in &scenes {
            for _ in 0..10 {
                let (n, m1, m2) = (rng.direction(), rng.direction(), rng.direction());
                let ll = |a, b| scene.latlong.grid.integral(&scene.latlong.radiance, a, b);
                let ea = |a, b| {
                    scene
                        .equal_area
                        .grid
                        .integral(&scene.equal_area.radiance, a, b)
                };
                for f in [&ll as &dyn Fn([f64; 3], [f64; 3]) -> f64, &ea] {
                    let lobe1 = f(n, m1) + f(n, neg(m1));
                    let lobe2 = f(n, m2) + f(n, neg(m2));
                    worst = worst.max((lobe1 - lobe2).abs() / lobe1);
                    worst = worst.max((f(n, n) - lobe1).abs() / lobe1);
                    assert_eq!(f(n, neg(n)), 0.0);
                }
            }
        }
        println!("complementary cuts: max relative mismatch {worst:.2e}");
        assert!(worst < 1e-12, "{worst}");
    }

    /// Monte Carlo with 2.5 x 10^6 samples per case (relative standard errors 6e-3 for the
    /// darkest case down to 4e-4), importance-sampled by texel power in `f64` and
    /// uniform in solid angle inside the texel (an estimator independent of the Stokes
    /// machinery), agrees with the reference within the Sidak bound over the 8 cases.
    #[test]
    fn envmap_references_match_monte_carlo() {
        let scenes = envscene::EnvScene::builtin(1);
        let bound = sidak_bound(8);
        for scene in &scenes {
            for pixel in 0..2u64 {
                let (n, m) = scene.geometry(pixel);
                for side in 0..2 {
                    let (w, h, radiance, reference): (usize, usize, &[f64], f64) = if side == 0 {
                        let s = &scene.latlong;
                        (
                            s.grid.width,
                            s.grid.height,
                            &s.radiance,
                            s.grid.integral(&s.radiance, n, m),
                        )
                    } else {
                        let s = &scene.equal_area;
                        (
                            s.grid.width,
                            s.grid.height,
                            &s.radiance,
                            s.grid.integral(&s.radiance, n, m),
                        )
                    };
                    // Texel solid angles.
                    let omega = |j: usize| {
                        if side == 0 {
                            let (t0, t1) =
                                (PI * j as f64 / h as f64, PI * (j + 1) as f64 / h as f64);
                            std::f64::consts::TAU / w as f64 * (t0.cos() - t1.cos())
                        } else {
                            4.0 * PI / (w * h) as f64
                        }
                    };
                    let mut cdf = Vec::with_capacity(w * h + 1);
                    let mut acc = 0.0;
                    cdf.push(0.0);
                    for t in 0..w * h {
                        acc += radiance[t] * omega(t / w);
                        cdf.push(acc);
                    }
                    let total = acc;
                    let mut rng = Rng::new(1000 + pixel + 10 * side as u64);
                    let (mut s1, mut s2) = (0.0, 0.0);
                    let count = 2_500_000;
                    for _ in 0..count {
                        let x = rng.uniform() * total;
                        let t = cdf.partition_point(|&c| c <= x).clamp(1, w * h) - 1;
                        let (i, j) = (t % w, t / w);
                        let (a, b) = (rng.uniform(), rng.uniform());
                        let d = if side == 0 {
                            let (t0, t1) =
                                (PI * j as f64 / h as f64, PI * (j + 1) as f64 / h as f64);
                            let z = t0.cos() + b * (t1.cos() - t0.cos());
                            let phi = std::f64::consts::TAU * (i as f64 + a) / w as f64;
                            let r = (1.0 - z * z).max(0.0).sqrt();
                            [r * phi.cos(), r * phi.sin(), z]
                        } else {
                            EqualArea.dir([(i as f64 + a) / w as f64, (j as f64 + b) / h as f64])
                        };
                        let c = dot3(n, d);
                        let f = if c > 0.0 && dot3(m, d) >= 0.0 { c } else { 0.0 };
                        s1 += f;
                        s2 += f * f;
                    }
                    let mean = s1 / count as f64;
                    let sigma = ((s2 / count as f64 - mean * mean) / count as f64).sqrt() * total;
                    let mc = mean * total;
                    let z = (mc - reference) / sigma;
                    println!(
                        "{} pixel {pixel} side {side}: reference {reference:.6}, MC {mc:.6} +- {sigma:.1e} (z = {z:+.2})",
                        scene.name
                    );
                    assert!(z.abs() < bound, "z = {z}");
                }
            }
        }
    }

    /// For each built-in environment-map scene (with and without the occluder), warp and
    /// sampler, the mean error over 384 pixels at 16 samples per pixel is within the Sidak
    /// bound.
    /// Rotation `k` of a map shows the unrotated map turned by `rotations()[k]`: the sun of
    /// the sky map (its brightest texels) lies at `R_k sun` in both layouts, and each
    /// rotation keeps the map's power (mean radiance 1 after scaling). Turning the wrong
    /// way (`R^T`) or drawing every rotation from the unrotated map fails this.
    #[test]
    fn rotated_maps_turn_the_sun() {
        let scene = envscene::EnvScene::procedural("sky", envscene::sky, 256, 128, 4).unwrap();
        let rots = envscene::rotations(4);
        let sun0 = {
            let (a, e) = (60f64.to_radians(), 35f64.to_radians());
            [e.cos() * a.cos(), e.cos() * a.sin(), e.sin()]
        };
        for (k, r) in rots.iter().enumerate() {
            let want = [0, 1, 2].map(|i| dot3(r[i], sun0));
            let (ll, ea) = scene.side(k);
            let brightest =
                |rad: &[f64], w: usize, h: usize, dir: &dyn Fn([f64; 2]) -> [f64; 3]| {
                    let t = (0..rad.len())
                        .max_by(|&a, &b| rad[a].total_cmp(&rad[b]))
                        .unwrap();
                    dir([
                        ((t % w) as f64 + 0.5) / w as f64,
                        ((t / w) as f64 + 0.5) / h as f64,
                    ])
                };
            let got_ll = brightest(&ll.radiance, ll.width(), ll.height(), &|u| LatLong.dir(u));
            let got_ea = brightest(&ea.radiance, ea.width(), ea.height(), &|u| EqualArea.dir(u));
            for got in [got_ll, got_ea] {
                let angle = dot3(got, want).clamp(-1.0, 1.0).acos().to_degrees();
                assert!(
                    angle < 2.0,
                    "rotation {k}: sun at {angle:.2} deg from R sun"
                );
            }
        }
        assert!(
            rots[1..].iter().all(|r| (r[0][0] - 1.0).abs() > 1e-3),
            "rotations must differ from the identity"
        );
    }

    /// The orientation study (`orientation.rs`) measures what it says: its authored run is
    /// the report's estimator on a scene built without rotations (the same MSE), its rotated
    /// run the report's own rotated scene (`run::errors` on the same pixels), the two runs
    /// agree sample for sample on the pixels that see rotation 0 and differ on the others,
    /// and the CSV's and the table's ratios are the ratios of the MSEs.
    #[test]
    fn orientation_study_is_consistent() {
        use orientation::{ORIENTATIONS, SPPS, WARPS};
        let (w, h, rots, pixels) = (64, 32, 4, 64);
        let rotated = envscene::EnvScene::procedural("sky", envscene::sky, w, h, rots).unwrap();
        let authored = envscene::EnvScene::procedural("sky", envscene::sky, w, h, 1).unwrap();
        let mut classes = Vec::new();
        for lit in [false, true] {
            let view = rotated.view(lit);
            let c = orientation::measure(&view, "procedural", pixels, 2);
            let (mut same, mut differ, mut others) = (0, 0, 0);
            for i in 0..pixels {
                for s in SAMPLERS {
                    for k in 0..SPPS.len() {
                        for wp in 0..WARPS.len() {
                            let (a, r) = (c.error(i, 0, s, k, wp), c.error(i, 1, s, k, wp));
                            assert!(a.is_finite() && r.is_finite());
                            if i % rots == 0 {
                                same += (a.to_bits() == r.to_bits()) as usize;
                            } else {
                                others += 1;
                                differ += (a != r) as usize;
                            }
                        }
                    }
                }
            }
            let per = SAMPLERS.len() * SPPS.len() * WARPS.len();
            assert_eq!(same, pixels / rots * per, "rotation-0 pixels must agree");
            assert!(differ * 10 > others * 9, "{differ} of {others} differ");
            let cfg = run::Config {
                pixels,
                spps: SPPS.to_vec(),
                threads: 1,
                timing_samples: 1,
                timing_reps: 1,
            };
            let bar = indicatif::ProgressBar::hidden();
            for (o, scene) in [(0, &authored), (1, &rotated)] {
                let res = run::errors(&scene.view(lit), &cfg, &bar);
                for s in SAMPLERS {
                    for (wp, warp) in WARPS.iter().enumerate() {
                        for k in 0..SPPS.len() {
                            let want = res.row(s, warp).unwrap().stats[k].mse;
                            let got = c.mse(o, s, k, wp).mse;
                            assert!(
                                (got / want - 1.0).abs() < 1e-9,
                                "{} {} {} {warp} {}: {got} vs {want}",
                                ORIENTATIONS[o],
                                view.name(),
                                s.name(),
                                SPPS[k]
                            );
                        }
                    }
                }
            }
            classes.push(c);
        }
        // The CSV's ratio column is the ratio of its MSE column.
        let csv = orientation::csv(&classes);
        let rows: Vec<Vec<&str>> = csv
            .lines()
            .skip(1)
            .map(|l| l.split(',').collect())
            .collect();
        assert_eq!(
            rows.len(),
            classes.len() * 2 * SAMPLERS.len() * WARPS.len() * SPPS.len()
        );
        let mse = |r: &[&str]| r[7].parse::<f64>().unwrap();
        let find = |scene: &str, o: &str, s: &str, warp: &str, spp: &str| {
            rows.iter()
                .find(|r| r[0] == scene && r[1] == o && r[2] == s && r[3] == warp && r[4] == spp)
                .unwrap()
                .clone()
        };
        let mut ratios = std::collections::HashMap::new();
        for r in rows.iter().filter(|r| r[3].ends_with("equal_area")) {
            let ll = find(
                r[0],
                r[1],
                r[2],
                &r[3].replace("equal_area", "equirect"),
                r[4],
            );
            let (want, got) = (mse(r) / mse(&ll), r[9].parse::<f64>().unwrap());
            assert!((got / want - 1.0).abs() < 1e-3, "{r:?}: {got} vs {want}");
            ratios
                .entry((r[1], r[2], r[3], r[4]))
                .or_insert_with(Vec::new)
                .push(want);
        }
        // The table's summary cells are the geometric means of the CSV's ratios.
        let md = orientation::markdown(&classes, &[], 32);
        let mut checked = 0;
        for line in md.lines().filter(|l| l.starts_with("| `")) {
            let f: Vec<&str> = line.split('|').map(str::trim).collect();
            let (sampler, spp) = (f[1].trim_matches('`'), f[2]);
            assert_eq!(f.len(), 2 + 2 + 4, "{line}"); // one group: 4 ratio cells
            for (j, (dist, orient)) in [
                ("hierarchical_equal_area", "authored"),
                ("hierarchical_equal_area", "rotated"),
                ("marginal_equal_area", "authored"),
                ("marginal_equal_area", "rotated"),
            ]
            .into_iter()
            .enumerate()
            {
                let v = &ratios[&(orient, sampler, dist, spp)];
                let geo = (v.iter().map(|x| x.ln()).sum::<f64>() / v.len() as f64).exp();
                let shown: f64 = f[3 + j].split(' ').next().unwrap().parse().unwrap();
                assert!(
                    (shown - geo).abs() < 0.0051,
                    "{line}: {dist} {orient} {geo}"
                );
                checked += 1;
            }
        }
        assert_eq!(
            checked,
            4 * orientation::SUMMARY_SAMPLERS.len() * SPPS.len()
        );
    }

    #[test]
    fn envmap_estimators_are_unbiased() {
        let bound = sidak_bound(BIAS_FAMILY);
        // Two rotations: odd pixels see the turned maps and their own distributions.
        let maps = envscene::EnvScene::builtin(2);
        for scene in maps.iter().flat_map(|m| [m.view(false), m.view(true)]) {
            assert_unbiased(&scene, 384, bound, |_, _| true);
        }
    }
}

// ----------------------------------------------------------------------------------------
// docs/REPORT.md quotes the generated files, never a stale copy of them

/// Every `<!-- generated: report/X.md -->` ... `<!-- end: report/X.md -->` block of
/// docs/REPORT.md is exactly the file docs/report/X.md that the report last wrote (so the
/// page's tables cannot drift from `results.csv`), and the page quotes at least the
/// recommendations, the comparison with the source and the variance split that way.
#[test]
fn report_page_quotes_the_generated_files_verbatim() {
    let root = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/.."));
    let page = std::fs::read_to_string(root.join("docs/REPORT.md")).unwrap();
    let mut quoted = Vec::new();
    let mut rest = page.as_str();
    while let Some(start) = rest.find("<!-- generated: ") {
        let after = &rest[start + "<!-- generated: ".len()..];
        let name = &after[..after.find(" -->").expect("unterminated marker")];
        let body_start = start + "<!-- generated: ".len() + name.len() + " -->".len();
        let end_marker = format!("<!-- end: {name} -->");
        let end = rest[body_start..]
            .find(&end_marker)
            .unwrap_or_else(|| panic!("{name}: no end marker"));
        let body = rest[body_start..body_start + end].trim();
        let file = std::fs::read_to_string(root.join("docs").join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(
            body,
            file.trim(),
            "docs/REPORT.md's copy of {name} differs from the file: paste the file again"
        );
        quoted.push(name.to_string());
        rest = &rest[body_start + end + end_marker.len()..];
    }
    for want in [
        "report/recommendations.md",
        "report/comparison.md",
        "report/variance_split.md",
    ] {
        assert!(
            quoted.iter().any(|q| q == want),
            "{want} is not quoted; quoted: {quoted:?}"
        );
    }
}
