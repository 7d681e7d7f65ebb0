//! Samples per second of warpcore's slice forms (and `pmj02bn::sample_x8`), timed with
//! `std::time::Instant`: for the builds criterion cannot bench (wasm32-wasip1 under Node) and
//! for before/after comparisons of two checkouts under the same load (run the two binaries
//! alternately). Only API that every version since v1 has, so an older checkout builds it too.
//!
//!   cargo run --release -p slicebench [-- FILTER]
//!   cargo run --release -p slicebench --target wasm32-wasip1
//!   RUSTFLAGS="-C target-feature=+simd128" cargo run ... --target wasm32-wasip1
//!
//! (run from the repository root, where `.cargo/config.toml` names the Node runner). Each
//! line is the median of 15 timings of 4096-element batches repeated for about 10 ms.
//!
//! The env-map lines sample the `park` map (luminance, lat-long solid-angle weights) at
//! 512 x 256 and upsampled bilinearly to 4096 x 2048, as `benches/envmap.rs` does, with the
//! slice and `_x8` forms (filter `envmap`).

use std::hint::black_box;
use std::time::Instant;
use warpcore::envmap::{Distribution, Hierarchical, MarginalConditional, Sample, Word, image};
use warpcore::{disk, f32x8, pmj02bn, sequence, sphere, triangle, u32x8};

const BATCH: usize = 4096;

fn points<const N: usize>(seed: u32) -> Vec<[f32; N]> {
    let mut s = seed.wrapping_mul(0x9e37_79b9) | 1;
    (0..BATCH)
        .map(|_| {
            std::array::from_fn(|_| {
                s ^= s << 13;
                s ^= s >> 17;
                s ^= s << 5;
                (s >> 8) as f32 * (1.0 / 16_777_216.0)
            })
        })
        .collect()
}

/// Median samples per second (millions) of `f`, which produces `BATCH` samples per call.
fn rate(mut f: impl FnMut()) -> f64 {
    // Calibrate the repetitions to about 10 ms per timing.
    let mut reps = 1u32;
    loop {
        let t = Instant::now();
        for _ in 0..reps {
            f();
        }
        if t.elapsed().as_secs_f64() > 0.01 || reps >= 1 << 20 {
            break;
        }
        reps *= 2;
    }
    let mut rates: Vec<f64> = (0..15)
        .map(|_| {
            let t = Instant::now();
            for _ in 0..reps {
                f();
            }
            (BATCH as f64 * reps as f64) / t.elapsed().as_secs_f64() / 1e6
        })
        .collect();
    rates.sort_by(|a, b| a.total_cmp(b));
    rates[rates.len() / 2]
}

fn map<const I: usize, const O: usize>(
    name: &str,
    filter: &str,
    slice: impl Fn(&[[f32; I]], &mut [[f32; O]]) -> usize,
) {
    if !name.contains(filter) {
        return;
    }
    let input = points::<I>(7);
    let mut out = vec![[0.0f32; O]; BATCH];
    let r = rate(|| {
        slice(black_box(&input), &mut out);
        black_box(&mut out);
    });
    println!("{name:<28} {r:>9.1} M/s");
}

fn indexed<const O: usize>(
    name: &str,
    filter: &str,
    slice: impl Fn(u32, u32, &mut [[f32; O]]) -> usize,
) {
    if !name.contains(filter) {
        return;
    }
    let mut out = vec![[0.0f32; O]; BATCH];
    let r = rate(|| {
        slice(0, black_box(0x5eed), &mut out);
        black_box(&mut out);
    });
    println!("{name:<28} {r:>9.1} M/s");
}

/// Lat-long luminance weights of the `park` map: `(weights, width, height)`.
fn park() -> (Vec<f32>, usize, usize) {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/envmaps/park.pfm");
    let img = pfm::read(&path).unwrap_or_else(|e| panic!("{e}"));
    let (w, h) = (img.width, img.height);
    let mut l = vec![0.0f32; w * h];
    image::luminance_slice(&img.rgb, &mut l);
    image::equirect_solid_angle_weights(&mut l, w, h).unwrap();
    (l, w, h)
}

/// One env-map line: `sample_slice` (or `sample_x8` over structure-of-arrays groups) of `d`
/// over `BATCH` points.
fn envmap_line<D: Distribution>(name: &str, filter: &str, d: &D) {
    let blank = Sample {
        uv: [0.0; 2],
        pdf: 0.0,
        texel: [0; 2],
    };
    let input = points::<2>(7);
    let mut out = vec![blank; BATCH];
    let slice_name = format!("{name} slice");
    if slice_name.contains(filter) {
        let r = rate(|| {
            d.sample_slice(black_box(&input), &mut out);
            black_box(&mut out);
        });
        println!("{slice_name:<28} {r:>9.1} M/s");
    }
    let x8_name = format!("{name} x8");
    if x8_name.contains(filter) {
        let soa: Vec<[f32x8; 2]> = input
            .chunks_exact(8)
            .map(|g| std::array::from_fn(|k| f32x8::new(std::array::from_fn(|j| g[j][k]))))
            .collect();
        let r = rate(|| {
            for (o, u) in out.chunks_exact_mut(8).zip(black_box(&soa)) {
                o.copy_from_slice(&d.sample_x8(*u).to_array());
            }
            black_box(&mut out);
        });
        println!("{x8_name:<28} {r:>9.1} M/s");
    }
}

/// Both distributions on the `park` map at 512 x 256 and 4096 x 2048.
fn envmaps(filter: &str) {
    if !"envmap::".contains(filter) && !filter.starts_with("envmap") {
        return;
    }
    let (small, w, h) = park();
    let big = pfm::upsample(&small, w, h, 8);
    for (weights, w, h) in [(&small, w, h), (&big, 8 * w, 8 * h)] {
        let mut sh = vec![0 as Word; Hierarchical::storage_len(w, h)];
        let d = Hierarchical::new(weights, w, h, &mut sh).unwrap();
        envmap_line(&format!("envmap::hier {w}x{h}"), filter, &d);
        let mut sm = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        let d = MarginalConditional::new(weights, w, h, &mut sm).unwrap();
        envmap_line(&format!("envmap::mc {w}x{h}"), filter, &d);
    }
}

fn main() {
    let filter = std::env::args().nth(1).unwrap_or_default();
    let f = filter.as_str();
    map("disk::concentric_slice", f, disk::concentric_slice);
    map("disk::polar_slice", f, disk::polar_slice);
    map(
        "disk::concentric_inverse_slice",
        f,
        disk::concentric_inverse_slice,
    );
    // The quadrant slices: BATCH / 4 points in, BATCH samples out.
    map(
        "disk::polar4_slice",
        f,
        |p: &[[f32; 2]], o: &mut [[f32; 2]]| disk::polar4_slice(&p[..BATCH / 4], o),
    );
    map(
        "disk::concentric4_slice",
        f,
        |p: &[[f32; 2]], o: &mut [[f32; 2]]| disk::concentric4_slice(&p[..BATCH / 4], o),
    );
    map("triangle::uniform_slice", f, triangle::uniform_slice);
    map("triangle::sqrt_map_slice", f, triangle::sqrt_map_slice);
    indexed("triangle::basu_owen_slice", f, triangle::basu_owen_slice);
    indexed(
        "triangle::basu_owen_permuted_slice",
        f,
        triangle::basu_owen_permuted_slice,
    );
    map("sphere::equal_area_slice", f, sphere::equal_area_slice);
    map(
        "sphere::equal_area_inverse_slice",
        f,
        sphere::equal_area_inverse_slice,
    );
    map("sphere::equirect_slice", f, sphere::equirect_slice);
    map(
        "sphere::cosine_hemisphere_slice",
        f,
        sphere::cosine_hemisphere_slice,
    );
    indexed("pmj02bn::sample_slice", f, pmj02bn::sample_slice);
    if "pmj02bn::sample_x8".contains(f) {
        let mut out = vec![[warpcore::f32x8::ZERO; 2]; BATCH / 8];
        let lane = u32x8::new([0, 1, 2, 3, 4, 5, 6, 7]);
        let r = rate(|| {
            let seed = u32x8::splat(black_box(0x5eed));
            for (k, o) in out.iter_mut().enumerate() {
                *o = pmj02bn::sample_x8(u32x8::splat(8 * k as u32) + lane, seed);
            }
            black_box(&mut out);
        });
        println!("{:<28} {r:>9.1} M/s", "pmj02bn::sample_x8");
    }
    indexed("sequence::random_slice", f, sequence::random_slice);
    indexed("sequence::stratified_slice", f, |s, seed, o| {
        sequence::stratified_slice(s, BATCH as u32, seed, o)
    });
    envmaps(f);
}
