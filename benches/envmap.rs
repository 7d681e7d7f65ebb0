//! Environment-map distributions: build time and sampling throughput of warpcore's
//! marginal-conditional and hierarchical distributions on a real 512 x 256 map (`park`, with
//! a sun) and on the same map upsampled to 4096 x 2048, scalar, x8, x16 and slice forms, against
//! the textbook `f32`-CDF marginal-conditional sampler a user would write (pbrt-v3/v4
//! `Distribution2D` style: `Vec<f32>` CDFs and `partition_point`).
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench envmap`

mod common;

use common::{BATCH, Outputs, bench_map, forms, uniform_points};
use criterion::{BenchmarkGroup, Criterion, Throughput, measurement::WallTime};
use std::hint::black_box;
use warpcore::envmap::{
    Distribution, Hierarchical, MarginalConditional, Sample, SampleX8, SampleX16, Word, image,
};
use warpcore::{f32x8, f32x16, u32x8, u32x16};

/// Lat-long luminance weights of the `park` map.
fn park() -> (Vec<f32>, usize, usize) {
    let img = pfm::envmap("park");
    let (w, h) = (img.width, img.height);
    let mut l = vec![0.0f32; w * h];
    image::luminance_slice(&img.rgb, &mut l);
    image::equirect_solid_angle_weights(&mut l, w, h).unwrap();
    (l, w, h)
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

/// The warpcore forms of one distribution's `sample`, labelled "`name`, scalar loop" and so on.
fn variants<D: Distribution>(
    g: &mut BenchmarkGroup<'_, WallTime>,
    name: &str,
    d: &D,
    input: &[[f32; 2]],
    outs: &mut Outputs<Sample, SampleX8, SampleX16>,
) {
    let label = |v: &str| format!("{name}, {v}");
    let (x8, x16) = (|u| d.sample_x8(u), |u| d.sample_x16(u));
    forms(
        g,
        label,
        input,
        outs,
        |u| d.sample(u),
        x8,
        x16,
        |u, o| d.sample_slice(u, o),
    );
}

fn sample_group<'c>(
    c: &'c mut Criterion,
    name: &str,
    weights: &[f32],
    w: usize,
    h: usize,
) -> BenchmarkGroup<'c, WallTime> {
    let input = uniform_points::<2>(BATCH, 7);
    let texel = [0; 2];
    let zero = Sample {
        uv: [0.0; 2],
        pdf: 0.0,
        texel,
    };
    let (z8, u8) = (f32x8::ZERO, [u32x8::ZERO; 2]);
    let (z16, u16) = (f32x16::ZERO, [u32x16::ZERO; 2]);
    let zero8 = SampleX8 {
        uv: [z8; 2],
        pdf: z8,
        texel: u8,
    };
    let zero16 = SampleX16 {
        uv: [z16; 2],
        pdf: z16,
        texel: u16,
    };
    let mut outs = Outputs::new(zero, zero8, zero16);
    let mut g = common::group(c, name);

    let mut sh = vec![0 as Word; Hierarchical::storage_len(w, h)];
    let hd = Hierarchical::new(weights, w, h, &mut sh).unwrap();
    variants(&mut g, "warpcore hierarchical", &hd, &input, &mut outs);
    let mut sm = vec![0 as Word; MarginalConditional::storage_len(w, h)];
    let m = MarginalConditional::new(weights, w, h, &mut sm).unwrap();
    variants(
        &mut g,
        "warpcore marginal-conditional",
        &m,
        &input,
        &mut outs,
    );
    let peer = F32Cdf::new(weights, w, h);
    let label = "f32-CDF marginal-conditional (textbook), scalar";
    let mut pout = vec![([0.0f32; 2], 0.0f32); BATCH];
    bench_map(&mut g, label, &input, &mut pout, |u| peer.sample(u));
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
    let big = pfm::upsample(&small, w, h, 8);
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
