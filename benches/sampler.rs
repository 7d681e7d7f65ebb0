//! The sampling core: a 4D point per sample index, the way a renderer asks for it, for
//! warpcore's `Sampler<Sobol>`, `Sampler<Pmj02bn>` and their `Blue<..>` variants (scalar,
//! 8 and 16 lanes, slice) against openqmc-rs 0.2.4 (OpenQMC's samplers, ported bit for bit)
//! and `sobol_burley::sample_4d`.
//!
//! Every scalar and lane form builds its sampler from (pixel, frame, index, seed) for every
//! sample and draws from a child domain: `Sampler::new(pixel, frame, i, seed).domain(k)
//! .draw::<4>()` (openqmc-rs: `X::new(x, y, frame, i).new_domain(k).draw_sample_f32::<4>()`).
//! The pixel goes through `black_box` per sample, so the whole construction runs for every
//! sample (as when a progressive renderer's loop moves from pixel to pixel). The "pixel loop"
//! entries build it the same way over one pixel's samples with the pixel fixed, so the
//! compiler may hoist what does not depend on the index (as in a loop over a pixel's
//! samples). The slice form fills the same `BATCH` points of one domain in one call.
//!
//! The "sampler, per call" group is the renderer's inner loop with nothing to hoist: every
//! call gets its own pixel (from a pre-generated list of 4096 random pixels) and index, both
//! through `black_box`, one sampler built per index, `domain(1).draw::<4>()`; openqmc-rs's
//! `SobolSampler` and `PmjSampler` (`new(x, y, frame, i).new_domain(1)
//! .draw_sample_f32::<4>()`) in the same group.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench sampler`

mod common;

use common::{BATCH, bench_hoisted, bench_indexed, bench_out};
use criterion::BenchmarkGroup;
use criterion::measurement::WallTime;
use openqmc::{LatticeSampler, PmjBnSampler, PmjSampler, SobolBnSampler, SobolSampler};
use std::hint::black_box;
use warpcore::sampler::{Blue, Pattern, Pmj02bn, Sampler, SamplerX8, SamplerX16, Sobol};
use warpcore::{f32x8, f32x16, u32x8, u32x16};

const PIXEL: [u32; 2] = [123, 45];
const FRAME: u32 = 3;
const SEED: u32 = 0x5eed;
/// The child domain every form draws from (a path's "light sample at bounce 2", say).
const DOMAIN: u32 = 5;

/// The four warpcore forms of one pattern (and, with `pixel_loop`, the scalar form over one
/// pixel's samples, where the compiler may hoist what does not depend on the index).
fn ours<P: Pattern>(g: &mut BenchmarkGroup<'_, WallTime>, name: &str, pixel_loop: bool) {
    let mut out = vec![[0.0f32; 4]; BATCH];
    bench_indexed(
        g,
        &format!("warpcore Sampler<{name}> scalar"),
        &mut out,
        |i| {
            let s = Sampler::<P>::new(black_box(PIXEL), FRAME, i as u32, SEED);
            s.domain(DOMAIN).draw::<4>()
        },
    );
    if pixel_loop {
        let label = format!("warpcore Sampler<{name}> scalar, pixel loop");
        bench_hoisted(
            g,
            &label,
            &mut out,
            || black_box(PIXEL),
            |i, pixel| {
                let s = Sampler::<P>::new(pixel, FRAME, i as u32, SEED);
                s.domain(DOMAIN).draw::<4>()
            },
        );
    }
    let lane = u32x8::new(std::array::from_fn(|j| j as u32));
    let mut out8 = vec![[f32x8::ZERO; 4]; BATCH / 8];
    bench_indexed(g, &format!("warpcore Sampler<{name}> x8"), &mut out8, |k| {
        let [x, y] = black_box(PIXEL).map(u32x8::splat);
        let index = u32x8::splat(8 * k as u32) + lane;
        let s = SamplerX8::<P>::new([x, y], u32x8::splat(FRAME), index, u32x8::splat(SEED));
        s.domain(DOMAIN).draw::<4>()
    });
    let lane = u32x16::new(std::array::from_fn(|j| j as u32));
    let mut out16 = vec![[f32x16::ZERO; 4]; BATCH / 16];
    bench_indexed(
        g,
        &format!("warpcore Sampler<{name}> x16"),
        &mut out16,
        |k| {
            let [x, y] = black_box(PIXEL).map(u32x16::splat);
            let index = u32x16::splat(16 * k as u32) + lane;
            let s = SamplerX16::<P>::new([x, y], u32x16::splat(FRAME), index, u32x16::splat(SEED));
            s.domain(DOMAIN).draw::<4>()
        },
    );
    bench_out(
        g,
        &format!("warpcore Sampler<{name}> draw_slice"),
        &mut out,
        |out| {
            let s = Sampler::<P>::new(black_box(PIXEL), FRAME, 0, SEED).domain(DOMAIN);
            s.draw_slice(out);
        },
    );
}

/// An openqmc-rs sampler, scalar (its only form): `draw(x, y, frame, index)` builds the
/// sampler and draws from domain `DOMAIN`. The caller has warmed its cache.
fn openqmc(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    pixel_loop: bool,
    draw: impl Fn(i32, i32, i32, i32) -> [f32; 4],
) {
    let mut out = vec![[0.0f32; 4]; BATCH];
    bench_indexed(g, &format!("openqmc-rs {name}"), &mut out, |i| {
        let [x, y] = black_box(PIXEL).map(|c| c as i32);
        draw(x, y, FRAME as i32, i as i32)
    });
    if pixel_loop {
        let label = format!("openqmc-rs {name}, pixel loop");
        let pixel = || black_box(PIXEL).map(|c| c as i32);
        bench_hoisted(g, &label, &mut out, pixel, |i, [x, y]| {
            draw(x, y, FRAME as i32, i as i32)
        });
    }
}

/// `X::new(x, y, frame, index).new_domain(DOMAIN).draw_sample_f32::<4>()` for an openqmc-rs
/// sampler type, after `X::warm_cache()`.
macro_rules! openqmc {
    ($g:expr, $x:ident, $pixel_loop:expr) => {{
        $x::warm_cache();
        openqmc($g, stringify!($x), $pixel_loop, |x, y, f, i| {
            $x::new(x, y, f, i)
                .new_domain(DOMAIN as i32)
                .draw_sample_f32::<4>()
        });
    }};
}

/// 4096 random pixels of a 1920 x 1080 image (splitmix64 from a fixed seed).
fn random_pixels() -> Vec<[u32; 2]> {
    common::uniform_points::<2>(BATCH, 7)
        .into_iter()
        .map(|[x, y]| [(x * 1920.0) as u32, (y * 1080.0) as u32])
        .collect()
}

/// One 4D draw per call with the pixel and the index varied per call and black-boxed: what
/// a renderer's inner loop pays per sample when nothing can be hoisted.
fn per_call(c: &mut criterion::Criterion) {
    let pixels = random_pixels();
    let mut out = vec![[0.0f32; 4]; BATCH];
    let mut g = common::group(c, "sampler, per call");
    fn ours<P: Pattern>(
        g: &mut BenchmarkGroup<'_, WallTime>,
        name: &str,
        pixels: &[[u32; 2]],
        out: &mut [[f32; 4]],
    ) {
        bench_indexed(g, &format!("warpcore Sampler<{name}>"), out, |i| {
            let s = Sampler::<P>::new(black_box(pixels[i]), FRAME, black_box(i as u32), SEED);
            s.domain(1).draw::<4>()
        });
    }
    ours::<Sobol>(&mut g, "Sobol", &pixels, &mut out);
    ours::<Pmj02bn>(&mut g, "Pmj02bn", &pixels, &mut out);
    macro_rules! peer {
        ($x:ident) => {{
            $x::warm_cache();
            bench_indexed(
                &mut g,
                concat!("openqmc-rs ", stringify!($x)),
                &mut out,
                |i| {
                    let [x, y] = black_box(pixels[i]).map(|c| c as i32);
                    let i = black_box(i as i32);
                    $x::new(x, y, FRAME as i32, i)
                        .new_domain(1)
                        .draw_sample_f32::<4>()
                },
            );
        }};
    }
    peer!(SobolSampler);
    peer!(PmjSampler);
    g.finish();
}

fn main() {
    let mut c = common::criterion();
    per_call(&mut c);
    let mut g = common::group(&mut c, "sampler");
    ours::<Sobol>(&mut g, "Sobol", true);
    ours::<Pmj02bn>(&mut g, "Pmj02bn", true);
    ours::<Blue<Sobol>>(&mut g, "Blue<Sobol>", false);
    ours::<Blue<Pmj02bn>>(&mut g, "Blue<Pmj02bn>", false);
    openqmc!(&mut g, SobolSampler, true);
    openqmc!(&mut g, SobolBnSampler, false);
    openqmc!(&mut g, PmjSampler, true);
    openqmc!(&mut g, PmjBnSampler, false);
    openqmc!(&mut g, LatticeSampler, false);
    let mut out = vec![[0.0f32; 4]; BATCH];
    bench_indexed(&mut g, "sobol_burley::sample_4d", &mut out, |i| {
        // The seed a renderer would hash from its pixel and domain.
        let seed = black_box(SEED ^ PIXEL[0]);
        sobol_burley::sample_4d(i as u32, DOMAIN, seed)
    });
    g.finish();
    c.final_summary();
}
