//! Blue noise over a whole path: blurred MSE over many seeds on the path
//! scenes, ratios with standard errors, and which path length carries the blurred error.
//!
//! ```text
//! cargo run --release -p warpcore-report --bin pathblue -- [seeds] [threads] [what]
//! ```
//!
//! `what`: `ratios` (the default: `Blue<P>` / `P` at 1 and 4 spp), `peers` (the same ratios
//! for openqmc-rs's blue-noise samplers against their plain ones, the state of the art the
//! targets are measured against), `lengths`, `lens`, `roulette`, `line`, `frames`.

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
        if what == "peers" {
            use openqmc::{
                LatticeBnSampler, LatticeSampler, PmjBnSampler, PmjSampler, SobolBnSampler,
                SobolSampler,
            };
            for spp in [1u32, 4] {
                let so = peer::<SobolSampler>(&b, "openqmc_sobol", spp, 11, seeds, threads);
                let sb = peer::<SobolBnSampler>(&b, "openqmc_sobolbn", spp, 12, seeds, threads);
                let pm = peer::<PmjSampler>(&b, "openqmc_pmj", spp, 13, seeds, threads);
                let pb = peer::<PmjBnSampler>(&b, "openqmc_pmjbn", spp, 14, seeds, threads);
                let la = peer::<LatticeSampler>(&b, "openqmc_lattice", spp, 15, seeds, threads);
                let lb = peer::<LatticeBnSampler>(&b, "openqmc_latticebn", spp, 16, seeds, threads);
                for (l, r) in [
                    ("openqmc_sobolbn / openqmc_sobol", ratio(sb, so)),
                    ("openqmc_pmjbn / openqmc_pmj", ratio(pb, pm)),
                    ("openqmc_latticebn / openqmc_lattice", ratio(lb, la)),
                ] {
                    println!("{name} {spp} spp   {l:<36} {:.3} +- {:.3}", r.0, r.1);
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
        for spp in [1u32, 4] {
            let run = |label: &str, s: &dyn Fn(u32) -> Vec<f64>| {
                let v = s(spp);
                let m = mean_se(&v);
                println!("{name} {spp} spp {label:<24} {:.4e} +- {:.1e}", m.0, m.1);
                m
            };
            fn go<S: PathSampler>(
                b: &Bench,
                s: S,
                spp: u32,
                seeds: u32,
                salt: u32,
                t: usize,
            ) -> Vec<f64> {
                blurred_mses(b, &s, spp, seeds, salt, 2.0, t)
            }
            let so = run("sobol", &|spp| {
                go(&b, Warpcore::<Sobol>(PD), spp, seeds, 1, threads)
            });
            let bso = run("blue_sobol", &|spp| {
                go(&b, Warpcore::<Blue<Sobol>>(PD), spp, seeds, 2, threads)
            });
            let pm = run("pmj02bn", &|spp| {
                go(&b, Warpcore::<Pmj02bn>(PD), spp, seeds, 3, threads)
            });
            let bpm = run("blue_pmj02bn", &|spp| {
                go(&b, Warpcore::<Blue<Pmj02bn>>(PD), spp, seeds, 4, threads)
            });
            let bsop = run("blue_sobol pairs", &|spp| {
                go(&b, WarpcorePairs::<Blue<Sobol>>(PD), spp, seeds, 5, threads)
            });
            let bpmp = run("blue_pmj02bn pairs", &|spp| {
                go(
                    &b,
                    WarpcorePairs::<Blue<Pmj02bn>>(PD),
                    spp,
                    seeds,
                    6,
                    threads,
                )
            });
            let show = |l: &str, r: (f64, f64)| {
                println!("{name} {spp} spp   {l:<36} {:.3} +- {:.3}", r.0, r.1)
            };
            show("blue_sobol / sobol", ratio(bso, so));
            show("blue_pmj02bn / pmj02bn", ratio(bpm, pm));
            show("blue_sobol pairs / sobol", ratio(bsop, so));
            show("blue_pmj02bn pairs / pmj02bn", ratio(bpmp, pm));
        }
    }
}

/// The mean blurred MSE (sigma 2) of an openqmc-rs sampler over `seeds` renders at `spp`, with
/// its standard error, printed.
fn peer<S>(b: &Bench, label: &str, spp: u32, salt: u32, seeds: u32, threads: usize) -> (f64, f64)
where
    OpenQmc<S>: PathSampler,
{
    let v = blurred_mses(b, &OpenQmc::<S>(PD), spp, seeds, salt, 2.0, threads);
    let m = mean_se(&v);
    println!(
        "{} {spp} spp {label:<24} {:.4e} +- {:.1e}",
        b.scene.name, m.0, m.1
    );
    m
}

/// `label a b b/a`.
fn show(label: &str, v: [f64; 2]) {
    println!("{label} {:.3e} {:.3e} {:.4}", v[0], v[1], v[1] / v[0]);
}
