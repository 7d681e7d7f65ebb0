//! Environment-map distributions: build time and sampling throughput of warpcore's
//! marginal-conditional and hierarchical distributions on a real 512 x 256 map (`park`, with
//! a sun) and on the same map upsampled to 4096 x 2048, scalar, x8, x16 and slice forms, against
//! the textbook `f32`-CDF marginal-conditional sampler a user would write (pbrt-v3/v4
//! `Distribution2D` style: `Vec<f32>` CDFs and `partition_point`).
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench envmap`

mod common;

use common::{BATCH, to_soa, to_soa16, uniform_points};
use criterion::{BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use std::hint::black_box;
use warpcore::envmap::{
    Hierarchical, MarginalConditional, Sample, SampleX8, SampleX16, Word, image,
};
use warpcore::{f32x8, f32x16};

/// Lat-long luminance weights of the `park` map.
fn park() -> (Vec<f32>, usize, usize) {
    let img = pfm::envmap("park");
    let (w, h) = (img.width, img.height);
    let mut l = vec![0.0f32; w * h];
    image::luminance_slice(&img.rgb, &mut l);
    image::equirect_solid_angle_weights(&mut l, w, h).unwrap();
    (l, w, h)
}

/// Bilinear upsampling by an integer factor (texel centres aligned).
fn upsample(src: &[f32], w: usize, h: usize, k: usize) -> Vec<f32> {
    let (nw, nh) = (w * k, h * k);
    let at = |x: isize, y: isize| {
        let x = x.rem_euclid(w as isize) as usize; // wraps around in longitude
        let y = y.clamp(0, h as isize - 1) as usize;
        src[y * w + x].max(0.0)
    };
    let mut out = vec![0.0f32; nw * nh];
    for y in 0..nh {
        let fy = (y as f32 + 0.5) / k as f32 - 0.5;
        let (y0, ty) = (fy.floor() as isize, fy - fy.floor());
        for x in 0..nw {
            let fx = (x as f32 + 0.5) / k as f32 - 0.5;
            let (x0, tx) = (fx.floor() as isize, fx - fx.floor());
            let top = at(x0, y0) * (1.0 - tx) + at(x0 + 1, y0) * tx;
            let bottom = at(x0, y0 + 1) * (1.0 - tx) + at(x0 + 1, y0 + 1) * tx;
            out[y * nw + x] = top * (1.0 - ty) + bottom * ty;
        }
    }
    out
}

/// The textbook peer: `f32` CDFs (normalized running sums), binary search with
/// `partition_point`, offset `(u - cdf[i]) / (cdf[i+1] - cdf[i])`, pdf `f[i] / integral`.
struct F32Cdf {
    w: usize,
    h: usize,
    marginal: Vec<f32>,
    marginal_func: Vec<f32>,
    marginal_int: f32,
    cdf: Vec<f32>,
    func: Vec<f32>,
    row_int: Vec<f32>,
}

impl F32Cdf {
    fn new(weights: &[f32], w: usize, h: usize) -> Self {
        let mut cdf = vec![0.0f32; (w + 1) * h];
        let mut row_int = vec![0.0f32; h];
        let func: Vec<f32> = weights.iter().map(|&x| x.max(0.0)).collect();
        for r in 0..h {
            let c = &mut cdf[r * (w + 1)..(r + 1) * (w + 1)];
            for k in 0..w {
                c[k + 1] = c[k] + func[r * w + k] / w as f32;
            }
            row_int[r] = c[w];
            for x in c.iter_mut() {
                *x /= row_int[r].max(f32::MIN_POSITIVE);
            }
        }
        let mut marginal = vec![0.0f32; h + 1];
        for r in 0..h {
            marginal[r + 1] = marginal[r] + row_int[r] / h as f32;
        }
        let marginal_int = marginal[h];
        for x in marginal.iter_mut() {
            *x /= marginal_int;
        }
        F32Cdf {
            w,
            h,
            marginal_func: row_int.clone(),
            marginal,
            marginal_int,
            cdf,
            func,
            row_int,
        }
    }

    fn find(cdf: &[f32], u: f32) -> usize {
        (cdf.partition_point(|&c| c <= u).saturating_sub(1)).min(cdf.len() - 2)
    }

    fn sample(&self, u: [f32; 2]) -> ([f32; 2], f32) {
        let r = Self::find(&self.marginal, u[1]);
        let dv = (u[1] - self.marginal[r]) / (self.marginal[r + 1] - self.marginal[r]);
        let row = &self.cdf[r * (self.w + 1)..(r + 1) * (self.w + 1)];
        let c = Self::find(row, u[0]);
        let du = (u[0] - row[c]) / (row[c + 1] - row[c]);
        let pdf =
            self.marginal_func[r] / self.marginal_int * self.func[r * self.w + c] / self.row_int[r];
        (
            [
                (c as f32 + du) / self.w as f32,
                (r as f32 + dv) / self.h as f32,
            ],
            pdf,
        )
    }
}

fn sample_group<'c>(
    c: &'c mut Criterion,
    name: &str,
    weights: &[f32],
    w: usize,
    h: usize,
) -> BenchmarkGroup<'c, WallTime> {
    let input = uniform_points::<2>(BATCH, 7);
    let soa = to_soa(&input);
    let soa16 = to_soa16(&input);
    let mut out = vec![
        Sample {
            uv: [0.0; 2],
            pdf: 0.0,
            texel: [0; 2]
        };
        BATCH
    ];
    let mut out8 = vec![
        SampleX8 {
            uv: [f32x8::ZERO; 2],
            pdf: f32x8::ZERO,
            texel: [warpcore::u32x8::ZERO; 2]
        };
        BATCH / 8
    ];
    let mut out16 = vec![
        SampleX16 {
            uv: [f32x16::ZERO; 2],
            pdf: f32x16::ZERO,
            texel: [warpcore::u32x16::ZERO; 2]
        };
        BATCH / 16
    ];
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements(BATCH as u64));

    let mut sm = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    let m = MarginalConditional::new(weights, w, h, &mut sm).unwrap();
    let mut sh = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let hd = Hierarchical::new(weights, w, h, &mut sh).unwrap();
    macro_rules! variants {
        ($d:expr, $label:literal) => {
            g.bench_function(concat!($label, ", scalar loop"), |b| {
                b.iter(|| {
                    for (o, u) in out.iter_mut().zip(black_box(&input)) {
                        *o = $d.sample(*u);
                    }
                    black_box(&mut out);
                })
            });
            g.bench_function(concat!($label, ", scalar, one call at a time"), |b| {
                b.iter(|| {
                    for (o, u) in out.iter_mut().zip(&input) {
                        *o = $d.sample(black_box(*u));
                    }
                    black_box(&mut out);
                })
            });
            g.bench_function(concat!($label, ", x8"), |b| {
                b.iter(|| {
                    for (o, u) in out8.iter_mut().zip(black_box(&soa)) {
                        *o = $d.sample_x8(*u);
                    }
                    black_box(&mut out8);
                })
            });
            g.bench_function(concat!($label, ", x16"), |b| {
                b.iter(|| {
                    for (o, u) in out16.iter_mut().zip(black_box(&soa16)) {
                        *o = $d.sample_x16(*u);
                    }
                    black_box(&mut out16);
                })
            });
            g.bench_function(concat!($label, ", slice"), |b| {
                b.iter(|| {
                    $d.sample_slice(black_box(&input), &mut out);
                    black_box(&mut out);
                })
            });
        };
    }
    variants!(hd, "warpcore hierarchical");
    variants!(m, "warpcore marginal-conditional");
    let peer = F32Cdf::new(weights, w, h);
    let mut pout = vec![([0.0f32; 2], 0.0f32); BATCH];
    g.bench_function("f32-CDF marginal-conditional (textbook), scalar", |b| {
        b.iter(|| {
            for (o, u) in pout.iter_mut().zip(black_box(&input)) {
                *o = peer.sample(*u);
            }
            black_box(&mut pout);
        })
    });
    g
}

fn build_group(c: &mut Criterion, name: &str, weights: &[f32], w: usize, h: usize) {
    let mut g = c.benchmark_group(name);
    g.throughput(Throughput::Elements((w * h) as u64));
    let mut sm = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    g.bench_function("warpcore marginal-conditional", |b| {
        b.iter(|| {
            black_box(MarginalConditional::new(black_box(weights), w, h, &mut sm).is_ok());
        })
    });
    let mut sh = vec![0 as Word; Hierarchical::storage_len(w, h)];
    g.bench_function("warpcore hierarchical", |b| {
        b.iter(|| {
            black_box(Hierarchical::new(black_box(weights), w, h, &mut sh).is_ok());
        })
    });
    g.bench_function("f32-CDF marginal-conditional (textbook, allocates)", |b| {
        b.iter(|| black_box(F32Cdf::new(black_box(weights), w, h).marginal_int))
    });
    // Loading a saved storage: the O(n) verifying loader (invariants and content checksum).
    MarginalConditional::new(weights, w, h, &mut sm).unwrap();
    Hierarchical::new(weights, w, h, &mut sh).unwrap();
    g.bench_function("warpcore marginal-conditional from_storage_verified", |b| {
        b.iter(|| black_box(MarginalConditional::from_storage_verified(black_box(&sm)).is_ok()))
    });
    g.bench_function("warpcore hierarchical from_storage_verified", |b| {
        b.iter(|| black_box(Hierarchical::from_storage_verified(black_box(&sh)).is_ok()))
    });
    g.finish();
}

fn main() {
    let mut c = common::criterion();
    let (small, w, h) = park();
    let big = upsample(&small, w, h, 8);
    let (bw, bh) = (w * 8, h * 8);

    sample_group(&mut c, "envmap/sample park 512x256", &small, w, h).finish();
    sample_group(
        &mut c,
        "envmap/sample park upsampled 4096x2048",
        &big,
        bw,
        bh,
    )
    .finish();
    build_group(&mut c, "envmap/build park 512x256", &small, w, h);
    build_group(
        &mut c,
        "envmap/build park upsampled 4096x2048",
        &big,
        bw,
        bh,
    );
    c.final_summary();
}
