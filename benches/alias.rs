//! The alias table ("alias table" group): `AliasTable::sample` at 10^3, 10^5 and 10^6 lights,
//! scalar loop (each call its own `u`, behind `black_box`), `sample_x8` and the slice form over
//! `BATCH` values, and the build time per light; the peer is `rand_distr`'s
//! `weighted::WeightedAliasIndex` (Vose's method too, f32 weights, drawing its own column and
//! threshold from a `Xoshiro128++`, so its rows include two generator calls per sample).
//!
//! Weights: `1 + 1000 x^4` for a hash `x` of the index (a ragged, heavy-tailed power
//! distribution, as emitters are), a tenth of them 0.
//!
//! Run: `cargo bench --bench alias` (add `RUSTFLAGS="-C target-cpu=native"` for AVX2/AVX-512).

mod common;

use common::{BATCH, bench_map, bench_out, criterion, uniform_points};
use criterion::{BatchSize, Criterion, Throughput};
use rand::SeedableRng;
use rand_distr::Distribution;
use rand_distr::weighted::WeightedAliasIndex;
use rand_xoshiro::Xoshiro128PlusPlus;
use std::hint::black_box;
use warpcore::f32x8;
use warpcore::lights::AliasTable;

fn weights(n: usize) -> Vec<f32> {
    let x = uniform_points::<1>(n, 7);
    x.iter()
        .enumerate()
        .map(|(i, [x])| {
            if i % 10 == 3 {
                0.0
            } else {
                1.0 + 1000.0 * x.powi(4)
            }
        })
        .collect()
}

fn alias(c: &mut Criterion) {
    let u: Vec<f32> = uniform_points::<1>(BATCH, 1).iter().map(|[x]| *x).collect();
    let u8: Vec<f32x8> = u
        .chunks_exact(8)
        .map(|c| f32x8::new(c.try_into().unwrap()))
        .collect();
    for n in [1_000usize, 100_000, 1_000_000] {
        let w = weights(n);
        let mut storage = vec![0u32; AliasTable::storage_len(n)];
        let table = AliasTable::new(&w, &mut storage).unwrap();
        let mut g = c.benchmark_group("alias table");
        g.throughput(Throughput::Elements(BATCH as u64));
        bench_map(
            &mut g,
            &format!("warpcore sample, {n} lights"),
            &u,
            &mut vec![(0, 0.0); BATCH],
            |u| table.sample(black_box(u)),
        );
        bench_out(
            &mut g,
            &format!("warpcore sample_x8, {n} lights"),
            &mut vec![0u32; BATCH],
            |out| {
                for (o, &u) in out.chunks_exact_mut(8).zip(&u8) {
                    let (i, p) = table.sample_x8(black_box(u));
                    o.copy_from_slice(&i.to_array());
                    black_box(p);
                }
            },
        );
        let (mut idx, mut prob) = (vec![0u32; BATCH], vec![0.0f32; BATCH]);
        bench_out(
            &mut g,
            &format!("warpcore sample_slice, {n} lights"),
            &mut idx,
            |idx| {
                table.sample_slice(black_box(&u), idx, &mut prob);
            },
        );
        let peer = WeightedAliasIndex::new(w.clone()).unwrap();
        let mut rng = Xoshiro128PlusPlus::seed_from_u64(1);
        bench_out(
            &mut g,
            &format!("rand_distr WeightedAliasIndex (Xoshiro128++), {n} lights"),
            &mut vec![0usize; BATCH],
            |out| {
                for o in out.iter_mut() {
                    *o = peer.sample(&mut rng);
                }
            },
        );
        // Build: elements are lights.
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(format!("warpcore build, {n} lights"), |b| {
            b.iter(|| {
                AliasTable::new(black_box(&w), &mut storage)
                    .map(|t| t.len())
                    .unwrap()
            })
        });
        g.bench_function(
            format!("rand_distr WeightedAliasIndex build, {n} lights"),
            |b| {
                b.iter_batched(
                    || w.clone(),
                    |w| WeightedAliasIndex::new(w).unwrap(),
                    BatchSize::LargeInput,
                )
            },
        );
        g.finish();
    }
}

fn main() {
    let mut c = criterion();
    alias(&mut c);
    c.final_summary();
}
