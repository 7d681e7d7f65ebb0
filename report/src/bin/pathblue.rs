//! Blue noise over a whole path: blurred MSE over many seeds on the path
//! scenes, ratios with standard errors, and which path length carries the blurred error.
//!
//! ```text
//! cargo run --release -p warpcore-report --bin pathblue -- [seeds] [threads] [what]
//! ```
//!
//! `what`: `ratios` (the default: `Blue<P>` / `P` at 1 and 4 spp), `pairs` (only the
//! recommended `WarpcorePairs` usage), `peers` (the same ratios for openqmc-rs's blue-noise
//! samplers against their plain ones, the state of the art the targets are measured against),
//! `lengths [spp]`, `lens`, `roulette`, `line`, `silhouette`, `frames [size] [out]`.

use std::marker::PhantomData as PD;
use warpcore::sampler::{Blue, Pmj02bn, Sobol};
use warpcore_report::path::frames::{
    Bench, Camera4, blurred_mses, by_length, mean_se, ratio, run_frames,
};
use warpcore_report::path::samplers::{OpenQmc, PathSampler, Warpcore, WarpcorePairs};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let seeds: u32 = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(32);
    let threads: usize = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(2);
    let what = args.get(3).cloned().unwrap_or_else(|| "ratios".into());
    let sigma = 2.0;
    if what == "roulette" {
        // The blurred error summed over path lengths with and without the roulette.
        use warpcore_report::path::scene::Scene;
        for name in ["cornell", "cornell/rr-off"] {
            let sc = Scene::by_name(name, 64).expect("scene");
            let total =
                |l: Vec<[f64; 2]>| l.iter().fold([0.0, 0.0], |a, v| [a[0] + v[0], a[1] + v[1]]);
            let so = total(by_length(
                &sc,
                &Warpcore::<Sobol>(PD),
                1,
                seeds,
                sigma,
                threads,
            ));
            let bl = total(by_length(
                &sc,
                &WarpcorePairs::<Blue<Sobol>>(PD),
                1,
                seeds,
                sigma,
                threads,
            ));
            show(
                &format!("{name}: 1 spp blurred variance, sobol and blue_sobol"),
                [so[1], bl[1]],
            );
        }
        return;
    }
    if what == "line" {
        // The 2D edge test's error kept on a rectangle's outline only (a light's silhouette):
        // how much of the blue-noise gain survives on a line feature.
        use warpcore_report::bluenoise::{SIZE, SPP, blur, error_images, ours};
        type Mask = fn(usize, usize) -> bool;
        let masks: [(&str, Mask); 2] = [
            ("whole image", |_, _| true),
            ("outline of a 12 x 10 rectangle", |x, y| {
                let inx = (26..38).contains(&x);
                let iny = (27..37).contains(&y);
                (inx && (y == 27 || y == 36)) || (iny && (x == 26 || x == 37))
            }),
        ];
        for (label, keep) in masks {
            let e = |d: warpcore_report::bluenoise::Draw| -> Vec<f64> {
                let mut sum = vec![0.0; SPP.len()];
                for frame in 0..seeds {
                    for (k, img) in error_images(d, frame).iter().enumerate() {
                        let m: Vec<f64> = (0..SIZE * SIZE)
                            .map(|i| {
                                if keep(i % SIZE, i / SIZE) {
                                    img[i]
                                } else {
                                    0.0
                                }
                            })
                            .collect();
                        sum[k] += blur(&m).iter().map(|v| v * v).sum::<f64>();
                    }
                }
                sum
            };
            let (a, bl) = (e(ours::<Sobol>), e(ours::<Blue<Sobol>>));
            let (c, bc) = (e(ours::<Pmj02bn>), e(ours::<Blue<Pmj02bn>>));
            for k in 0..SPP.len() {
                println!(
                    "{label}: {} spp blurred MSE ratio Blue<Sobol>/Sobol {:.3}, Blue<Pmj02bn>/Pmj02bn {:.3}",
                    SPP[k],
                    bl[k] / a[k],
                    bc[k] / c[k]
                );
            }
        }
        return;
    }
    if what == "silhouette" {
        silhouette(seeds);
        return;
    }
    if what == "frames" {
        // [seeds] [threads] frames [size] [out file]: what `cargo run-report` writes.
        let size: usize = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(32);
        let scenes = ["cornell", "cornell-disk"].map(String::from);
        let md = run_frames(&scenes, size, &[32, 64], seeds, threads).expect("references");
        print!("{md}");
        if let Some(out) = args.get(5) {
            std::fs::write(out, md).expect("write the table");
        }
        return;
    }
    for name in ["cornell", "cornell-disk"] {
        let b = Bench::new(name, 64).expect("reference");
        let r = Runs {
            b: &b,
            seeds,
            threads,
        };
        if what == "peers" {
            use openqmc::{
                LatticeBnSampler, LatticeSampler, PmjBnSampler, PmjSampler, SobolBnSampler,
                SobolSampler,
            };
            for spp in [1u32, 4] {
                let so = r.mse(&OpenQmc::<SobolSampler>(PD), "openqmc_sobol", spp, 11);
                let sb = r.mse(&OpenQmc::<SobolBnSampler>(PD), "openqmc_sobolbn", spp, 12);
                let pm = r.mse(&OpenQmc::<PmjSampler>(PD), "openqmc_pmj", spp, 13);
                let pb = r.mse(&OpenQmc::<PmjBnSampler>(PD), "openqmc_pmjbn", spp, 14);
                let la = r.mse(&OpenQmc::<LatticeSampler>(PD), "openqmc_lattice", spp, 15);
                let lb = r.mse(
                    &OpenQmc::<LatticeBnSampler>(PD),
                    "openqmc_latticebn",
                    spp,
                    16,
                );
                for (l, r) in [
                    ("openqmc_sobolbn / openqmc_sobol", ratio(sb, so)),
                    ("openqmc_pmjbn / openqmc_pmj", ratio(pb, pm)),
                    ("openqmc_latticebn / openqmc_lattice", ratio(lb, la)),
                ] {
                    show_ratio(name, spp, l, r);
                }
            }
            continue;
        }
        if what == "lens" {
            let mut pin = b.scene.clone();
            pin.camera.aperture = 0.0;
            for (sc, sl) in [(&b.scene, "lens 0.02"), (&pin, "pinhole")] {
                for (label, l) in [
                    (
                        "sobol",
                        by_length(sc, &Warpcore::<Sobol>(PD), 1, seeds, sigma, threads),
                    ),
                    (
                        "blue_sobol",
                        by_length(sc, &Warpcore::<Blue<Sobol>>(PD), 1, seeds, sigma, threads),
                    ),
                    (
                        "blue_sobol camera4",
                        by_length(
                            sc,
                            &Camera4(Warpcore::<Blue<Sobol>>(PD)),
                            1,
                            seeds,
                            sigma,
                            threads,
                        ),
                    ),
                    (
                        "blue_pmj02bn camera4",
                        by_length(
                            sc,
                            &Camera4(Warpcore::<Blue<Pmj02bn>>(PD)),
                            1,
                            seeds,
                            sigma,
                            threads,
                        ),
                    ),
                ] {
                    show(&format!("{name} {sl} {label}: len 0"), l[0]);
                }
            }
            continue;
        }
        if what == "lengths" {
            let lspp: u32 = args.get(4).and_then(|s| s.parse().ok()).unwrap_or(1);
            for (label, l) in [
                (
                    "sobol",
                    by_length(
                        &b.scene,
                        &Warpcore::<Sobol>(PD),
                        lspp,
                        seeds,
                        sigma,
                        threads,
                    ),
                ),
                (
                    "blue_sobol",
                    by_length(
                        &b.scene,
                        &Warpcore::<Blue<Sobol>>(PD),
                        lspp,
                        seeds,
                        sigma,
                        threads,
                    ),
                ),
                (
                    "blue_sobol pairs",
                    by_length(
                        &b.scene,
                        &WarpcorePairs::<Blue<Sobol>>(PD),
                        lspp,
                        seeds,
                        sigma,
                        threads,
                    ),
                ),
                (
                    "blue_pmj02bn",
                    by_length(
                        &b.scene,
                        &Warpcore::<Blue<Pmj02bn>>(PD),
                        lspp,
                        seeds,
                        sigma,
                        threads,
                    ),
                ),
            ] {
                println!("{name} {lspp} spp {label}: per length [var, blurred var, blurred/var]");
                for (k, v) in l.iter().enumerate() {
                    show(&format!("  len {k}:"), *v);
                }
            }
            continue;
        }
        // `pairs [spp]`: one count only.
        let counts: Vec<u32> = match args.get(4).and_then(|s| s.parse().ok()) {
            Some(n) if what == "pairs" => vec![n],
            _ => vec![1, 4],
        };
        for &spp in &counts {
            // Salts 1..6: the renders of each sampler are independent of the others'.
            let so = r.mse(&Warpcore::<Sobol>(PD), "sobol", spp, 1);
            // `pairs`: only the recommended usage (`WarpcorePairs`) against its base.
            let all = what != "pairs";
            let bso = all.then(|| r.mse(&Warpcore::<Blue<Sobol>>(PD), "blue_sobol", spp, 2));
            let pm = r.mse(&Warpcore::<Pmj02bn>(PD), "pmj02bn", spp, 3);
            let bpm = all.then(|| r.mse(&Warpcore::<Blue<Pmj02bn>>(PD), "blue_pmj02bn", spp, 4));
            let s = WarpcorePairs::<Blue<Sobol>>(PD);
            let bsop = r.mse(&s, "blue_sobol pairs", spp, 5);
            let s = WarpcorePairs::<Blue<Pmj02bn>>(PD);
            let bpmp = r.mse(&s, "blue_pmj02bn pairs", spp, 6);
            let show = |l: &str, q: (f64, f64)| show_ratio(name, spp, l, q);
            if let (Some(bso), Some(bpm)) = (bso, bpm) {
                show("blue_sobol / sobol", ratio(bso, so));
                show("blue_pmj02bn / pmj02bn", ratio(bpm, pm));
            }
            show("blue_sobol pairs / sobol", ratio(bsop, so));
            show("blue_pmj02bn pairs / pmj02bn", ratio(bpmp, pm));
        }
    }
}

/// The blurred-MSE runs on one scene: `seeds` renders per sampler and count on `threads`.
struct Runs<'a> {
    b: &'a Bench,
    seeds: u32,
    threads: usize,
}

impl Runs<'_> {
    /// The mean blurred MSE (sigma 2) of sampler `s` at `spp` (render seeds keyed by `salt`),
    /// with its standard error, printed as `scene spp label mean +- se`.
    fn mse<S: PathSampler>(&self, s: &S, label: &str, spp: u32, salt: u32) -> (f64, f64) {
        let v = blurred_mses(self.b, s, spp, self.seeds, salt, 2.0, self.threads);
        let m = mean_se(&v);
        println!(
            "{} {spp} spp {label:<24} {:.4e} +- {:.1e}",
            self.b.scene.name, m.0, m.1
        );
        m
    }
}

/// `scene spp label ratio +- se`.
fn show_ratio(scene: &str, spp: u32, label: &str, r: (f64, f64)) {
    println!("{scene} {spp} spp   {label:<36} {:.3} +- {:.3}", r.0, r.1);
}

/// `label a b b/a`.
fn show(label: &str, v: [f64; 2]) {
    println!("{label} {:.3e} {:.3e} {:.4}", v[0], v[1], v[1] / v[0]);
}

/// The silhouette test: per frame a rotated 22 x 14 rectangle and a disk of radius 10 at
/// random positions (a light seen directly), each pixel's error the pixel-position draw's
/// coverage error of the union (zero inside and outside, so only the one-pixel outline
/// carries error, and each outline pixel's edge runs along the outline), blurred with sigma
/// 2; blurred MSE ratios `Blue<P> / P` over `frames` frames with standard errors.
fn silhouette(frames: u32) {
    use warpcore_report::bluenoise::{SIZE, SPP, blur_sigma, ours};
    let shape = |f: u32| {
        // A small hash of the frame: the shapes' positions and angle.
        let h = |k: u32| {
            let mut z = (f as u64) << 8 | k as u64;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
        };
        let (rx, ry, angle) = (
            18.0 + 6.0 * h(0),
            26.0 + 12.0 * h(1),
            std::f64::consts::PI * h(2),
        );
        let (dx, dy) = (46.0 + 6.0 * h(3), 26.0 + 12.0 * h(4));
        let (c, s) = (angle.cos(), angle.sin());
        move |x: f64, y: f64| {
            let (u, v) = (x - rx, y - ry);
            let (a, b) = (c * u + s * v, -s * u + c * v);
            (a.abs() < 11.0 && b.abs() < 7.0) || (x - dx).powi(2) + (y - dy).powi(2) < 100.0
        }
    };
    // Per frame: the outline pixels and their exact coverage (a 64 x 64 grid per pixel).
    let outlines: Vec<Vec<(usize, usize, f64)>> = (0..frames)
        .map(|f| {
            let inside = shape(f);
            let mut out = Vec::new();
            for y in 0..SIZE {
                for x in 0..SIZE {
                    let corners = [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0), (0.5, 0.5)]
                        .map(|(u, v)| inside(x as f64 + u, y as f64 + v));
                    // Shapes far larger than a pixel: a pixel without a boundary point at a
                    // corner or centre within 1.5 px holds no boundary.
                    let near = (-2..=2).any(|j| {
                        (-2..=2).any(|i| {
                            inside(
                                x as f64 + 0.5 + 0.75 * i as f64,
                                y as f64 + 0.5 + 0.75 * j as f64,
                            ) != corners[4]
                        })
                    });
                    if !near && corners.iter().all(|&c| c == corners[4]) {
                        continue;
                    }
                    let g = 64;
                    let mut cov = 0u32;
                    for j in 0..g {
                        for i in 0..g {
                            let u = x as f64 + (i as f64 + 0.5) / g as f64;
                            let v = y as f64 + (j as f64 + 0.5) / g as f64;
                            cov += inside(u, v) as u32;
                        }
                    }
                    if cov != 0 && cov != g * g {
                        out.push((x, y, cov as f64 / (g * g) as f64));
                    }
                }
            }
            out
        })
        .collect();
    type Draw = warpcore_report::bluenoise::Draw;
    let errors = |draw: Draw| -> Vec<Vec<f64>> {
        // Per frame, per count: the blurred MSE.
        (0..frames)
            .map(|f| {
                let inside = shape(f);
                let mut img = vec![vec![0.0; SIZE * SIZE]; SPP.len()];
                for &(x, y, exact) in &outlines[f as usize] {
                    let (mut hits, mut level) = (0u32, 0);
                    for i in 0..SPP[SPP.len() - 1] {
                        let p = draw(x as u32, y as u32, f, i);
                        hits += inside(x as f64 + p[0] as f64, y as f64 + p[1] as f64) as u32;
                        if i + 1 == SPP[level] {
                            img[level][y * SIZE + x] = hits as f64 / SPP[level] as f64 - exact;
                            level += 1;
                        }
                    }
                }
                img.iter()
                    .map(|m| blur_sigma(m, 2.0).iter().map(|v| v * v).sum::<f64>())
                    .collect()
            })
            .collect()
    };
    let column = |v: &[Vec<f64>], k: usize| mean_se(&v.iter().map(|r| r[k]).collect::<Vec<_>>());
    let (so, bso) = (errors(ours::<Sobol>), errors(ours::<Blue<Sobol>>));
    let (pm, bpm) = (errors(ours::<Pmj02bn>), errors(ours::<Blue<Pmj02bn>>));
    for (k, spp) in SPP.iter().enumerate() {
        let a = ratio(column(&bso, k), column(&so, k));
        let b = ratio(column(&bpm, k), column(&pm, k));
        println!(
            "silhouette {spp} spp, {frames} frames: Blue<Sobol>/Sobol {:.3} +- {:.3}, Blue<Pmj02bn>/Pmj02bn {:.3} +- {:.3}",
            a.0, a.1, b.0, b.1
        );
    }
}
