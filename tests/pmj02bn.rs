//! pmj02bn and the baseline samplers: (0,m,2)-nets for every power-of-two prefix and aligned
//! block (raw tables and scrambled samples, checked on the f32 outputs), the continuation past
//! the table, the embedded bytes against the generator's manifest, domain, bit identity of
//! scalar / x8 / slice, and measured blue noise.
#![cfg(all(feature = "pmj02bn", feature = "sequence"))]

use warpcore_testkit as common;

// The generator's algorithm, for the plain pmj02 reference of the blue-noise comparison.
use pmjgen as pmj;

use common::{in_unit_square, lane, same_bits};
use proptest::prelude::*;
use warpcore::pmj02bn::{self, POINTS, SETS};
use warpcore::sequence;
use warpcore::u32x8;

const LOG2_POINTS: u32 = POINTS.trailing_zeros();

/// An output coordinate back to 0.32 fixed point: outputs are multiples of 2^-24 below 1,
/// so this is exact; anything else fails the test.
fn fixed(u: f32) -> u32 {
    assert!((0.0..1.0).contains(&u), "{u} outside [0, 1)");
    let v = u as f64 * 16_777_216.0;
    assert_eq!(v, v.floor(), "{u} is not a multiple of 2^-24");
    (v as u32) << 8
}

fn fixed2(p: [f32; 2]) -> [u32; 2] {
    [fixed(p[0]), fixed(p[1])]
}

/// Is every elementary interval of area `2^-m` hit by exactly `len / 2^m` points? (For
/// `len = 2^m` this is the (0,m,2)-net property: all `m + 1` grids, one point per cell.)
fn stratified_at(points: &[[u32; 2]], m: u32) -> bool {
    let cells = 1usize << m;
    if !points.len().is_multiple_of(cells) {
        return false;
    }
    let per = (points.len() / cells) as u32;
    let top = |v: u32, b: u32| if b == 0 { 0 } else { (v >> (32 - b)) as usize };
    (0..=m).all(|k| {
        let mut count = vec![0u32; cells];
        for p in points {
            count[(top(p[0], k) << (m - k)) | top(p[1], m - k)] += 1;
        }
        count.iter().all(|&c| c == per)
    })
}

fn is_net(points: &[[u32; 2]]) -> bool {
    points.len().is_power_of_two() && stratified_at(points, points.len().trailing_zeros())
}

/// Every power-of-two prefix, and every aligned power-of-two block, is a net.
fn assert_progressive_nets(points: &[[u32; 2]], what: &str) {
    for m in 0..=points.len().trailing_zeros() {
        for (b, block) in points.chunks_exact(1 << m).enumerate() {
            assert!(
                is_net(block),
                "{what}: block {b} of 2^{m} is not a (0,{m},2)-net"
            );
        }
    }
}

#[test]
fn constants_describe_the_build() {
    const { assert!(POINTS.is_power_of_two() && POINTS >= 1024 && POINTS <= 65536) };
    const { assert!(SETS == 1 || SETS == 4) };
    assert_eq!(pmj02bn::TABLE_BYTES, 8 * POINTS * SETS);
    if cfg!(feature = "pmj02bn-65536") {
        assert_eq!(POINTS, 65536);
    } else if cfg!(feature = "pmj02bn-16384") {
        assert_eq!(POINTS, 16384);
    } else if cfg!(feature = "pmj02bn-4096") {
        assert_eq!(POINTS, 4096);
    }
}

#[test]
fn raw_sets_are_progressive_nets() {
    for set in 0..SETS {
        let points: Vec<_> = (0..POINTS).map(|i| pmj02bn::raw(set, i)).collect();
        assert_progressive_nets(&points, &format!("raw set {set}"));
    }
}

#[test]
fn raw_is_total() {
    for (set, index) in [
        (SETS, 0),
        (usize::MAX, POINTS),
        (7, usize::MAX),
        (0, 3 * POINTS + 5),
    ] {
        assert_eq!(
            pmj02bn::raw(set, index),
            pmj02bn::raw(set % SETS, index % POINTS)
        );
    }
}

/// The embedded tables are the committed files, byte for byte, and those match the
/// generator's manifest (CI's `pmjgen --check` regenerates them and compares the bytes).
#[test]
fn tables_match_the_manifest() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("src/tables");
    let manifest = std::fs::read_to_string(dir.join("MANIFEST")).unwrap();
    let fnv = |b: &[u8]| {
        b.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, &x| {
            (h ^ x as u64).wrapping_mul(0x0000_0100_0000_01b3)
        })
    };
    let mut files = 0;
    for line in manifest.lines().filter(|l| !l.starts_with('#')) {
        let f: Vec<&str> = line.split_whitespace().collect();
        let bytes = std::fs::read(dir.join(f[0])).unwrap();
        assert_eq!(bytes.len().to_string(), f[1], "{}", f[0]);
        assert_eq!(format!("{:016x}", fnv(&bytes)), f[2], "{} hash", f[0]);
        files += 1;
    }
    assert_eq!(files, 16);
    for set in 0..4 {
        let read = |n: usize| std::fs::read(dir.join(format!("pmj02bn_{n}_{set}.bin"))).unwrap();
        let big = read(65536);
        for n in [1024, 4096, 16384] {
            assert_eq!(read(n)[..], big[..8 * n], "table {n} is a prefix of 65536");
        }
        if set < SETS {
            let words: Vec<u32> = read(POINTS)
                .chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
                .collect();
            for (i, w) in words.chunks_exact(2).enumerate() {
                assert_eq!(pmj02bn::raw(set, i), [w[0], w[1]], "set {set} point {i}");
            }
        }
    }
}

fn samples(seed: u32, start: u32, n: usize) -> Vec<[u32; 2]> {
    (0..n as u32)
        .map(|i| fixed2(pmj02bn::sample(start.wrapping_add(i), seed)))
        .collect()
}

#[test]
fn scrambled_sequences_are_progressive_nets() {
    let mut r = common::rng(4);
    let mut seeds = vec![0u32, 1, u32::MAX, 0x8000_0000];
    seeds.extend((0..60).map(|_| rand::RngExt::random::<u32>(&mut r)));
    for seed in seeds {
        assert_progressive_nets(&samples(seed, 0, POINTS), &format!("seed {seed}"));
    }
}

/// Past the table: each further block of POINTS is a net under its own keys (not a repeat of
/// block 0), and 2^k consecutive aligned blocks hit every elementary interval of area
/// 1/POINTS exactly 2^k times.
#[test]
fn continuation_past_the_table() {
    for seed in [0u32, 17, 0xdead_beef] {
        let first = samples(seed, 0, 4 * POINTS);
        for (q, block) in first.chunks_exact(POINTS).enumerate() {
            assert_progressive_nets(block, &format!("seed {seed} block {q}"));
        }
        assert_ne!(
            first[..POINTS],
            first[POINTS..2 * POINTS],
            "block 1 repeats block 0"
        );
        assert!(stratified_at(&first[..2 * POINTS], LOG2_POINTS));
        assert!(stratified_at(&first, LOG2_POINTS));
        // Far blocks, including the last one before the index wraps.
        for q in [1000u32, (u32::MAX >> LOG2_POINTS)] {
            let block = samples(seed, q << LOG2_POINTS, POINTS);
            assert_progressive_nets(&block, &format!("seed {seed} block {q}"));
        }
    }
}

#[test]
fn shuffled_indices_keep_the_nets() {
    for (dim, seed) in [(1u32, 5u32), (2, 5), (0xdead_beef, 9)] {
        let points: Vec<_> = (0..POINTS as u32)
            .map(|i| fixed2(pmj02bn::sample(pmj02bn::shuffle(i, dim), seed)))
            .collect();
        for m in 0..=LOG2_POINTS {
            assert!(is_net(&points[..1 << m]), "shuffled prefix 2^{m}");
        }
        let mut sorted = points.clone();
        let mut plain = samples(seed, 0, POINTS);
        sorted.sort_unstable();
        plain.sort_unstable();
        assert_eq!(sorted, plain, "a shuffle only reorders the points");
        assert_ne!(
            points,
            samples(seed, 0, POINTS),
            "the shuffle reorders something"
        );
    }
    let a = pmj02bn::shuffle_x8(
        u32x8::new([0, 1, 2, 3, 99, 1 << 20, u32::MAX, 7]),
        u32x8::splat(3),
    );
    for (j, i) in [0u32, 1, 2, 3, 99, 1 << 20, u32::MAX, 7]
        .into_iter()
        .enumerate()
    {
        assert_eq!(a.to_array()[j], pmj02bn::shuffle(i, 3));
    }
}

/// The trap the docs warn about: a second 2D dimension taken with another seed but the same
/// index order is not independent of the first. Owen scrambling relabels strata, the same way
/// for every index of a seed, and point `i` of every table set sits in strata fixed by `i`'s
/// place in the progressive construction, so pair B's x is (almost) a function of pair A's x.
/// Measured on the joint 16 x 16 grid of (pair A x, pair B x) over 1024 samples, for 32
/// pixels: without the shuffle the points crowd into a few of the 256 cells; with an index
/// shuffle of their own (different seed) the pairs are independent and, as for a random
/// pairing of two stratified sets (64 points per row and per column), an empty cell has
/// probability about (15/16)^64 = 1.6%, so almost all cells are hit. The estimator's error
/// shows the same: on the smooth coupling integrand `a_x * b_x` (exact 1/4) the MSE over the
/// pixels stays flat from 16 to 256 samples without the shuffle (a per-pixel bias) and falls
/// by more than 8x with it.
#[test]
fn a_second_dimension_needs_its_own_shuffle() {
    const N: u32 = 1024;
    let pixels: Vec<(u32, u32, u32)> = (0..32u32)
        .map(|p| {
            (
                0x9e37_79b9u32.wrapping_mul(p + 1),
                0x85eb_ca6b ^ p.wrapping_mul(0xc2b2_ae35),
                p ^ 0x5bd1_e995,
            )
        })
        .collect();
    let pair_b = |i: u32, seed_b: u32, dim: u32, shuffled: bool| {
        pmj02bn::sample(
            if shuffled {
                pmj02bn::shuffle(i, dim)
            } else {
                i
            },
            seed_b,
        )
    };
    let occupancy = |seed_a: u32, seed_b: u32, dim: u32, shuffled: bool| {
        let mut cells = [false; 256];
        for i in 0..N {
            let a = pmj02bn::sample(i, seed_a);
            let b = pair_b(i, seed_b, dim, shuffled);
            cells[(a[0] * 16.0) as usize * 16 + (b[0] * 16.0) as usize] = true;
        }
        cells.iter().filter(|&&c| c).count()
    };
    let (mut worst_plain, mut best_plain, mut worst_shuffled) = (0, 256, 256);
    for &(seed_a, seed_b, dim) in &pixels {
        let plain = occupancy(seed_a, seed_b, dim, false);
        let shuffled = occupancy(seed_a, seed_b, dim, true);
        worst_plain = worst_plain.max(plain);
        best_plain = best_plain.min(plain);
        worst_shuffled = worst_shuffled.min(shuffled);
    }
    println!(
        "joint 16 x 16 cells hit by {N} points: same index order {best_plain}..{worst_plain}, \
         own shuffle at least {worst_shuffled}"
    );
    // Independent pairs: expected empty cells 256 * 0.016 = 4.2 (sd about 2); 236 is about
    // ten standard deviations below the mean. Correlated pairs (measured: 16 cells when the
    // seeds pick the same table set, at most 64 otherwise): at most three-eighths of the grid.
    assert!(
        worst_plain <= 96,
        "same index order hit {worst_plain} of 256 cells"
    );
    assert!(
        worst_shuffled >= 236,
        "own shuffle hit only {worst_shuffled} of 256 cells"
    );

    let mse = |spp: u32, shuffled: bool| {
        let mut sum = 0.0f64;
        for &(seed_a, seed_b, dim) in &pixels {
            let mut estimate = 0.0f64;
            for i in 0..spp {
                let a = pmj02bn::sample(i, seed_a);
                let b = pair_b(i, seed_b, dim, shuffled);
                estimate += a[0] as f64 * b[0] as f64;
            }
            let err = estimate / spp as f64 - 0.25;
            sum += err * err;
        }
        sum / pixels.len() as f64
    };
    let (plain16, plain256) = (mse(16, false), mse(256, false));
    let (shuffled16, shuffled256) = (mse(16, true), mse(256, true));
    println!(
        "MSE of a_x * b_x over {} pixels, 16 -> 256 spp: same index order {plain16:.3e} -> \
         {plain256:.3e}, own shuffle {shuffled16:.3e} -> {shuffled256:.3e}",
        pixels.len()
    );
    // A bias does not average out: the error stays within 2x of its 16-spp level...
    assert!(plain256 > 0.5 * plain16, "same index order converged");
    // ...while independent stratified pairs converge at least like Monte Carlo (16x more
    // samples: 16x lower; 8x leaves room for the noise of 32 pixels).
    assert!(
        shuffled256 < shuffled16 / 8.0,
        "own shuffle did not converge"
    );
    assert!(
        shuffled256 < plain256 / 8.0,
        "own shuffle no better than the trap"
    );
}

#[test]
fn different_seeds_differ() {
    let a = samples(1, 0, 64);
    let b = samples(2, 0, 64);
    assert_ne!(a, b);
}

// ----------------------------------------------------------------------------------------
// Domain and bit identity on arbitrary arguments.

proptest! {
    #![proptest_config(ProptestConfig::with_cases(20_000))]

    #[test]
    fn outputs_in_the_half_open_square(index: u32, seed: u32, count: u32) {
        prop_assert!(in_unit_square(pmj02bn::sample(index, seed)));
        prop_assert!(in_unit_square(sequence::random(index, seed)));
        prop_assert!(in_unit_square(sequence::stratified(index, count, seed)));
        prop_assert!(in_unit_square(sequence::stratified(index % 4096, 4096, seed)));
    }

    #[test]
    fn scalar_x8_slice_agree(index: [u32; 8], seed: [u32; 8], count: u32, start: u32, s: u32) {
        let (iv, sv) = (u32x8::new(index), u32x8::new(seed));
        let p8 = pmj02bn::sample_x8(iv, sv);
        let r8 = sequence::random_x8(iv, sv);
        let t8 = sequence::stratified_x8(iv, count, sv);
        for j in 0..8 {
            prop_assert!(same_bits(lane(p8, j), pmj02bn::sample(index[j], seed[j])));
            prop_assert!(same_bits(lane(r8, j), sequence::random(index[j], seed[j])));
            prop_assert!(same_bits(lane(t8, j), sequence::stratified(index[j], count, seed[j])));
        }
        let mut out = [[0.0f32; 2]; 13];
        prop_assert_eq!(pmj02bn::sample_slice(start, s, &mut out), 13);
        for (i, o) in out.iter().enumerate() {
            prop_assert!(same_bits(*o, pmj02bn::sample(start.wrapping_add(i as u32), s)));
        }
        sequence::random_slice(start, s, &mut out);
        for (i, o) in out.iter().enumerate() {
            prop_assert!(same_bits(*o, sequence::random(start.wrapping_add(i as u32), s)));
        }
        sequence::stratified_slice(start, count, s, &mut out);
        for (i, o) in out.iter().enumerate() {
            let want = sequence::stratified(start.wrapping_add(i as u32), count, s);
            prop_assert!(same_bits(*o, want));
        }
    }
}

#[test]
fn extreme_arguments() {
    for index in [
        0u32,
        1,
        POINTS as u32 - 1,
        POINTS as u32,
        u32::MAX - 1,
        u32::MAX,
    ] {
        for seed in [0u32, 1, u32::MAX] {
            assert!(in_unit_square(pmj02bn::sample(index, seed)));
            for count in [0u32, 1, 2, 3, 4, 1 << 24, (1 << 24) + 1, u32::MAX] {
                assert!(in_unit_square(sequence::stratified(index, count, seed)));
            }
        }
    }
    // The slice wraps the index after u32::MAX.
    let mut out = [[0.0f32; 2]; 20];
    pmj02bn::sample_slice(u32::MAX - 9, 3, &mut out);
    assert!(same_bits(out[10], pmj02bn::sample(0, 3)));
    assert_eq!(pmj02bn::sample_slice(0, 3, &mut []), 0);
}

// ----------------------------------------------------------------------------------------
// Baselines.

#[test]
fn stratified_fills_its_grid() {
    for (count, side) in [
        (1u32, 1u32),
        (16, 4),
        (17, 4),
        (4095, 63),
        (4096, 64),
        (1 << 24, 4096),
    ] {
        assert_eq!(sequence::stratified_side(count), side);
        let check = ((side * side) as usize).min(1 << 16); // the first rows of the largest grid
        for i in 0..check as u32 {
            let p = sequence::stratified(i, count, 11);
            // Inside the closed cell (column i % side, row i / side), in exact arithmetic
            // up to the two f32 roundings (a point may land on the cell's upper edge).
            let within = |c: f32, k: u32| {
                let (lo, hi) = (k as f64 / side as f64, (k + 1) as f64 / side as f64);
                let c = c as f64;
                c >= lo - 1e-7 && c <= hi + 1e-7
            };
            assert!(
                within(p[0], i % side) && within(p[1], i / side),
                "count {count} index {i}: {p:?}"
            );
        }
    }
    assert_eq!(sequence::stratified_side(u32::MAX), 4096);
    assert_eq!(sequence::stratified_side(0), 0);
}

/// Mean of each coordinate and of their product over 2^20 random points (independent
/// uniform coordinates: 1/2, 1/2, 1/4), within 5 standard errors.
#[test]
fn random_is_uniform_and_independent() {
    let n = 1 << 20;
    let (mut sx, mut sy, mut sxy) = (0.0f64, 0.0f64, 0.0f64);
    for i in 0..n {
        let p = sequence::random(i, 77);
        sx += p[0] as f64;
        sy += p[1] as f64;
        sxy += (p[0] * p[1]) as f64;
    }
    let n = n as f64;
    let se = (1.0f64 / 12.0 / n).sqrt();
    assert!((sx / n - 0.5).abs() < 5.0 * se);
    assert!((sy / n - 0.5).abs() < 5.0 * se);
    assert!((sxy / n - 0.25).abs() < 5.0 * (7.0f64 / 144.0 / n).sqrt());
    // Points of different seeds differ.
    assert_ne!(sequence::random(0, 1), sequence::random(0, 2));
}

// ----------------------------------------------------------------------------------------
// Blue noise, measured. Run with `--nocapture` to see the table (it is in docs/pmj02bn.md).

fn nn_stats(points: &[[u32; 2]]) -> (f64, f64) {
    pmj::nearest_neighbour_stats(points)
}

/// Any point of `[0, 1)^2` to fixed point (rounded down; the baselines' outputs are not all
/// multiples of 2^-24).
fn to_fixed(points: impl Iterator<Item = [f32; 2]>) -> Vec<[u32; 2]> {
    points
        .map(|p| p.map(|c| (c as f64 * 4_294_967_296.0) as u32))
        .collect()
}

#[test]
fn blue_noise_is_measured() {
    let sizes: Vec<usize> = [256, 1024, 4096]
        .into_iter()
        .filter(|&n| n <= POINTS)
        .collect();
    println!("| n | pmj02bn raw | pmj02bn scrambled | plain pmj02 | stratified | random |");
    println!("|---|---|---|---|---|---|");
    for n in sizes {
        // Averages over 4 instances of each kind (sets, seeds).
        let avg = |f: &dyn Fn(u32) -> Vec<[u32; 2]>| {
            let (mut mean, mut min) = (0.0, 0.0);
            for k in 0..4 {
                let (a, b) = nn_stats(&f(k));
                mean += a / 4.0;
                min += b / 4.0;
            }
            (mean, min)
        };
        let raw = avg(&|k| (0..n).map(|i| pmj02bn::raw(k as usize, i)).collect());
        let scrambled = avg(&|k| samples(1000 + k, 0, n));
        let plain = avg(&|k| pmj::generate(n, 7 + k as u64, 1).unwrap());
        let strat = avg(&|k| to_fixed((0..n as u32).map(|i| sequence::stratified(i, n as u32, k))));
        let random = avg(&|k| to_fixed((0..n as u32).map(|i| sequence::random(i, k))));
        let cell = |s: (f64, f64)| format!("{:.3} / {:.3}", s.0, s.1);
        println!(
            "| {n} | {} | {} | {} | {} | {} |",
            cell(raw),
            cell(scrambled),
            cell(plain),
            cell(strat),
            cell(random)
        );
        assert!(
            raw.0 > plain.0,
            "n {n}: pmj02bn mean NN {raw:?} vs pmj02 {plain:?}"
        );
        assert!(
            raw.1 > plain.1,
            "n {n}: pmj02bn min NN {raw:?} vs pmj02 {plain:?}"
        );
        // Every (0,2)-set beats independent random points on both measures.
        assert!(scrambled.0 > random.0 && plain.0 > random.0);
    }
}
