//! Runs every function of `shaders/warpcore.wgsl` (the solid-angle lights included),
//! `shaders/warpcore_tables.wgsl` (with its tables buffer bound) and
//! `shaders/warpcore_envmap.wgsl` (with test maps bound) on the default GPU adapter and
//! reports, per function, how many points differ from the crate and by how much (absolute and in ulps; the table file's outputs are
//! integer-derived, so only their mismatch counts are printed).
//!
//! `cargo run -p warpcore-gpu --release --bin gpu-check [-- --random N] [-- --strict]`
//! (add `--features metal` on macOS, `--features dx12` for Direct3D 12 on Windows; Vulkan is
//! always compiled in). `WGPU_ADAPTER_NAME=...` picks another adapter by name (wgpu's
//! environment variable), `WGPU_BACKEND=vulkan` a backend. `--strict` exits with status 1 if
//! any output differs from the crate; a NaN or infinite output (counted per function) always
//! does. `--typical` sends the warps and lights the ordinary points of `--model` instead of
//! the CI's (which include hostile values), for a table to set beside the model's. See
//! docs/gpu.md for what a conforming GPU may change.
//!
//! `gpu-check --model [--random N] [--trials T]` needs no GPU: it evaluates the WGSL source on
//! the CPU under the deviations the WGSL accuracy rules allow (`warpcore_gpu::model`), over `N`
//! typical points per function (default 65536), `T` times each (default 4), and prints the
//! largest deviation from the crate per function: the bounds in docs/gpu.md (for the
//! solid-angle lights on `N / 16` points: coordinates absolute, densities relative).
//!
//! `gpu-check --scan [--random N] [--trials T]` needs no GPU either: the points a GPU run sends
//! (hostile values included; default `N` 4096) through the model with subnormal flushing as
//! well (`Deviations::WGSL_FLUSH`), listing every point whose output is NaN or infinite; exit
//! status 1 if any. `WARPCORE_SCAN_ONLY=name` keeps the functions whose name contains `name`,
//! `WARPCORE_MODEL_TRACE_NAN=1` prints the operation where each NaN first arises and
//! `WARPCORE_MODEL_WORST=1` the point of the largest move.

use warpcore_gpu::{
    Gpu, compare, compare_words, cpu_outputs, envmaps, inputs, lights, tables, typical_inputs,
    warps,
};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut random: Option<usize> = None;
    let mut strict = false;
    let mut model = false;
    let mut scan = false;
    let mut typical = false;
    let mut trials = 4u32;
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--random" => {
                random = Some(it.next().and_then(|v| v.parse().ok()).unwrap_or_else(|| {
                    eprintln!("--random needs a number");
                    std::process::exit(2)
                }))
            }
            "--strict" => strict = true,
            "--model" => model = true,
            "--scan" => scan = true,
            "--typical" => typical = true,
            "--trials" => {
                trials = it.next().and_then(|v| v.parse().ok()).unwrap_or_else(|| {
                    eprintln!("--trials needs a number");
                    std::process::exit(2)
                })
            }
            _ => {
                eprintln!(
                    "usage: gpu-check [--random N] [--typical] [--strict] | --model [--random N] [--trials T] | --scan [--random N] [--trials T]"
                );
                std::process::exit(2)
            }
        }
    }
    if scan {
        std::process::exit(run_scan(random.unwrap_or(1 << 12), trials));
    }
    if model {
        run_model(random.unwrap_or(1 << 16), trials);
        return;
    }
    let gpu = or_exit(Gpu::default_adapter());
    println!(
        "adapter: {} ({:?}, {:?} backend, driver {} {})",
        gpu.info.name,
        gpu.info.device_type,
        gpu.info.backend,
        gpu.info.driver,
        gpu.info.driver_info
    );
    println!(
        "{:<42} {:>9} {:>10} {:>12} {:>8} {:>10}",
        "function", "points", "mismatches", "max abs", "max ulp", "non-finite"
    );
    let mut any = false;
    let mut bad = false;
    // The warps, then the solid-angle lights: the points of tests/lavapipe.rs and
    // tests/lavapipe_spherical.rs, or with --typical those of --model (ordinary inputs only).
    for (funcs, seed) in [(warps(), 0x5eed_0000), (lights(), 0x5fe0_0000)] {
        for (k, func) in funcs.iter().enumerate() {
            let n = random.unwrap_or(1 << 16);
            let input = if typical {
                typical_inputs(func.domain, n, 0x0de1_0000 + k as u64)
            } else {
                inputs(func.domain, n, seed + k as u64)
            };
            let want = cpu_outputs(func, &input);
            let got = or_exit(gpu.run(func, &input));
            let d = compare(func, &got, &want);
            let nonfinite = warpcore_gpu::model::nonfinite(func, &got).len();
            any |= d.mismatches > 0;
            bad |= nonfinite > 0;
            println!(
                "{:<42} {:>9} {:>10} {:>12.3e} {:>8.1} {:>10}",
                func.name, d.points, d.mismatches, d.max_abs, d.max_ulp, nonfinite
            );
        }
    }
    if bad {
        println!("some outputs are NaN or infinite: a defect (the crate's never are)");
    }
    // shaders/warpcore_tables.wgsl: integer arithmetic and an exact conversion only, so any
    // conforming device should give the crate's bits; mismatches are counted per check.
    let table_words = tables::table_words();
    for (k, func) in tables::TABLE_FUNCTIONS.iter().enumerate() {
        let input = tables::table_inputs(
            func.domain,
            random.unwrap_or(1 << 16),
            0x7ab1_0000 + k as u64,
        );
        let want = tables::cpu_outputs(func, &input);
        let got = or_exit(tables::run(&gpu, func, &input, &table_words));
        let d = compare_words(func.out_words, |_| true, &got, &want);
        any |= d.mismatches > 0;
        println!(
            "{:<42} {:>9} {:>10} {:>12} {:>8}",
            func.name, d.points, d.mismatches, "-", "-"
        );
    }
    // shaders/warpcore_envmap.wgsl over the test maps.
    for (k, func) in envmaps::ENV_FUNCTIONS.iter().enumerate() {
        let input = envmaps::env_inputs(func, random.unwrap_or(1 << 16) / 16, 0xe0 + k as u64);
        let want = envmaps::cpu_outputs(func, &input);
        let got = or_exit(envmaps::run(
            &gpu,
            func,
            &envmaps::shader_source(func),
            &input,
        ));
        let d = compare_words(func.out_words(), |w| func.is_integer_output(w), &got, &want);
        any |= d.mismatches > 0;
        println!(
            "{:<42} {:>9} {:>10} {:>12.3e} {:>8.1}",
            func.name, d.points, d.mismatches, d.max_abs, d.max_ulp
        );
    }
    if bad {
        std::process::exit(1);
    }
    if any {
        println!("some outputs differ from the crate: compare with the bounds in docs/gpu.md");
        if strict {
            std::process::exit(1);
        }
    } else {
        println!("every output word equals the crate's");
    }
}

/// The value, or exits with the error.
fn or_exit<T>(r: Result<T, String>) -> T {
    r.unwrap_or_else(|e| {
        eprintln!("gpu-check: {e}");
        std::process::exit(1)
    })
}

/// The CPU model of the WGSL accuracy rules: the largest deviation from the crate per function.
fn run_model(random: usize, trials: u32) {
    use warpcore_gpu::model::{Deviations, Interpreter, deviation};
    let module = naga::front::wgsl::parse_str(warpcore_gpu::WGSL).expect("warpcore.wgsl parses");
    println!(
        "CPU model of the WGSL accuracy rules ({:?}), {trials} trials per point",
        Deviations::WGSL
    );
    println!(
        "{:<42} {:>9} {:>10} {:>12} {:>8}",
        "function", "points", "moved", "max abs", "max ulp"
    );
    for (k, func) in warps().iter().enumerate() {
        let input = typical_inputs(func.domain, random, 0x0de1_0000 + k as u64);
        let d = deviation(
            &module,
            func,
            &input,
            Deviations::WGSL,
            trials,
            0x5151 + k as u64,
        );
        if std::env::var("WARPCORE_MODEL_WORST").is_ok()
            && let Some(p) = d.worst
        {
            let w = func.in_words();
            let mut want = vec![0; func.out_words()];
            func.eval(&input[p * w..(p + 1) * w], &mut want);
            println!(
                "    worst at {:?} -> crate {:?}",
                floats(&input[p * w..(p + 1) * w]),
                floats(&want)
            );
        }
        println!(
            "{:<42} {:>9} {:>10} {:>12.3e} {:>8.1}",
            func.name, d.points, d.mismatches, d.max_abs, d.max_ulp
        );
    }
    // The solid-angle lights (ordinary random lights, typical samples; random / 16 points, the
    // interpreter is slow on them): the largest absolute move of a coordinate (barycentric,
    // (s, t) or u) and the largest relative move of the density or solid angle (last word).
    println!(
        "{:<42} {:>9} {:>10} {:>12} {:>12}",
        "function", "points", "moved", "coord abs", "density rel"
    );
    for (k, func) in lights().iter().enumerate() {
        let input = typical_inputs(func.domain, (random / 16).max(1), 0x0de1_0000 + k as u64);
        let want = cpu_outputs(func, &input);
        let outw = func.out_words();
        // The solid angles: one word, the density.
        let scalar = outw == 1;
        let has_density = scalar || outw >= 3;
        let (mut moved, mut coord, mut rel) = (0usize, 0f64, 0f64);
        for t in 0..trials {
            let seed = 0x5151 + k as u64 + 1000 * t as u64;
            let got = Interpreter::new(&module, Deviations::WGSL, seed).outputs(func, &input);
            for (g, w) in got.chunks_exact(outw).zip(want.chunks_exact(outw)) {
                moved += usize::from(g != w);
                for j in 0..outw {
                    let (a, b) = (f32::from_bits(g[j]) as f64, f32::from_bits(w[j]) as f64);
                    let d = if a.is_nan() {
                        f64::INFINITY
                    } else {
                        (a - b).abs()
                    };
                    if has_density && j == outw - 1 {
                        if b != 0.0 {
                            rel = rel.max(d / b.abs());
                        } else if d != 0.0 {
                            rel = f64::INFINITY;
                        }
                    } else {
                        coord = coord.max(d);
                    }
                }
            }
        }
        let points = want.len() / outw;
        let show = |x: f64, has: bool| if has { format!("{x:.2e}") } else { "-".into() };
        println!(
            "{:<42} {:>9} {:>9.0}% {:>12} {:>12}",
            func.name,
            points,
            100.0 * moved as f64 / (points as f64 * trials as f64),
            show(coord, !scalar),
            show(rel, has_density)
        );
    }
}

/// `--scan`: the CI's points (hostile values included, as `gpu-check` sends them) through the
/// CPU model with the WGSL freedoms and subnormal flushing; prints, per function, how many
/// points return a NaN or infinite float, with up to three of them. Exit status 1 if any.
fn run_scan(random: usize, trials: u32) -> i32 {
    use warpcore_gpu::model::{Deviations, Interpreter, nonfinite};
    let module = naga::front::wgsl::parse_str(warpcore_gpu::WGSL).expect("warpcore.wgsl parses");
    println!(
        "CPU model ({:?}), {trials} trials per point: non-finite outputs",
        Deviations::WGSL_FLUSH
    );
    let mut bad_total = 0usize;
    for (funcs, seed) in [(warps(), 0x5eed_0000u64), (lights(), 0x5fe0_0000)] {
        for (k, func) in funcs.iter().enumerate() {
            if let Ok(only) = std::env::var("WARPCORE_SCAN_ONLY")
                && !func.name.contains(only.as_str())
            {
                continue;
            }
            let input = inputs(func.domain, random, seed + k as u64);
            let (inw, outw) = (func.in_words(), func.out_words());
            let want = cpu_outputs(func, &input);
            let mut bad = 0usize;
            for t in 0..trials {
                let trial_seed = 0x5ca9 + k as u64 + 977 * t as u64;
                let got = Interpreter::new(&module, Deviations::WGSL_FLUSH, trial_seed)
                    .outputs(func, &input);
                let found = nonfinite(func, &got);
                let shown = |what: &str, p: usize| {
                    println!(
                        "    {what} at {:?}: model {:?}, crate {:?}",
                        floats(&input[p * inw..(p + 1) * inw]),
                        floats(&got[p * outw..(p + 1) * outw]),
                        floats(&want[p * outw..(p + 1) * outw])
                    )
                };
                for &p in found.iter().take(3) {
                    shown(&func.name, p);
                }
                bad += found.len();
                if std::env::var("WARPCORE_MODEL_WORST").is_ok() {
                    let d = compare(func, &got, &want);
                    if let Some(p) = d.worst {
                        shown(&format!("worst ({:e})", d.max_abs), p);
                    }
                }
            }
            println!(
                "{:<42} {:>9} {:>10}",
                func.name,
                want.len() / outw * trials as usize,
                bad
            );
            bad_total += bad;
        }
    }
    i32::from(bad_total > 0)
}

/// Words shown as the `f32` values of their bits.
fn floats(words: &[u32]) -> Vec<String> {
    words
        .iter()
        .map(|x| format!("{:e}", f32::from_bits(*x)))
        .collect()
}
