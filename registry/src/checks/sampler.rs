//! The sampling core's promises on any input, shared by the fuzz target
//! (`fuzz/fuzz_targets/sampler.rs`) and the stable corpus replay (`registry/tests/fuzz_corpus.rs`).
//!
//! The fuzzer's bytes, as little-endian words: a pattern selector, the root's pixel, frame,
//! index and seed, then a domain path of any length: each step a word whose low bit picks
//! `domain(key)` (one more word) or `split(key, size, sub)` (three more words). For the
//! sampler at every step of the path, and for 8 and 16 lanes that each vary the pixel, frame,
//! index, seed and sub-sample: every `draw`, `draw_u32` and `rnd` of 1 to 4 dimensions lies in
//! `[0, 1 - 2^-24]`, `draw == (draw_u32 >> 8) * 2^-24`, the lanes equal the scalar sampler (and
//! `lane(j)` the scalar state), slices equal scalar draws at consecutive (wrapping) indices, and
//! nothing panics.
#[allow(unused_imports)]
use std::prelude::rust_2024::*;
#[allow(unused_imports)]
use std::{format, vec};

use super::words;
use warpcore::sampler::{Pattern, Pmj02bn, Sampler, SamplerX8, SamplerX16, Sobol};
use warpcore::{u32x8, u32x16};

/// A step of a domain path.
#[derive(Clone, Copy, Debug)]
enum Step {
    Domain(u32),
    Split(u32, u32, u32),
}

/// Steps checked per input (a longer path is cut; every prefix is checked).
const MAX_STEPS: usize = 16;
/// Points per slice.
const SLICE: usize = 21;
const ULP: f32 = 1.0 / 16_777_216.0;

fn in_range(v: &[f32]) -> bool {
    v.iter().all(|x| (0.0..=1.0 - ULP).contains(x))
}

fn bits<const N: usize>(v: [f32; N]) -> [u32; N] {
    v.map(f32::to_bits)
}

/// One sampler's draws of `N` dimensions: ranges and the draw/draw_u32 identity.
fn scalar<P: Pattern, const N: usize>(s: Sampler<P>) -> ([f32; N], [u32; N], [f32; N]) {
    let (f, w, r) = (s.draw::<N>(), s.draw_u32::<N>(), s.rnd::<N>());
    assert!(in_range(&f), "draw::<{N}>() = {f:?} out of range for {s:?}");
    assert!(in_range(&r), "rnd::<{N}>() = {r:?} out of range for {s:?}");
    for d in 0..N {
        let want = (w[d] >> 8) as f32 * ULP;
        assert_eq!(f[d].to_bits(), want.to_bits(), "draw != draw_u32 for {s:?}");
    }
    (f, w, r)
}

/// The slice of `SLICE` points from `s` equals the scalar draws at `index + k` (wrapping).
fn slice<P: Pattern, const N: usize>(s: Sampler<P>) {
    let mut out = [[0.0f32; N]; SLICE];
    assert_eq!(s.draw_slice(&mut out), SLICE);
    for (k, o) in out.iter().enumerate() {
        let t = s.with_index(s.index().wrapping_add(k as u32));
        assert_eq!(bits(*o), bits(t.draw::<N>()), "slice point {k} of {s:?}");
    }
}

/// Every check for `N` dimensions on the scalar sampler and the lanes.
fn dims<P: Pattern, const N: usize>(
    s: Sampler<P>,
    lanes8: &[Sampler<P>; 8],
    x8: SamplerX8<P>,
    lanes16: &[Sampler<P>; 16],
    x16: SamplerX16<P>,
) {
    scalar::<P, N>(s);
    slice::<P, N>(s);
    let (f, w, r) = (x8.draw::<N>(), x8.draw_u32::<N>(), x8.rnd::<N>());
    for (j, lane) in lanes8.iter().enumerate() {
        let (sf, sw, sr) = scalar::<P, N>(*lane);
        for d in 0..N {
            assert_eq!(
                f[d].to_array()[j].to_bits(),
                sf[d].to_bits(),
                "x8 draw lane {j}"
            );
            assert_eq!(w[d].to_array()[j], sw[d], "x8 draw_u32 lane {j}");
            assert_eq!(
                r[d].to_array()[j].to_bits(),
                sr[d].to_bits(),
                "x8 rnd lane {j}"
            );
        }
    }
    let (f, w, r) = (x16.draw::<N>(), x16.draw_u32::<N>(), x16.rnd::<N>());
    for (j, lane) in lanes16.iter().enumerate() {
        let (sf, sw, sr) = (lane.draw::<N>(), lane.draw_u32::<N>(), lane.rnd::<N>());
        for d in 0..N {
            assert_eq!(
                f[d].to_array()[j].to_bits(),
                sf[d].to_bits(),
                "x16 draw lane {j}"
            );
            assert_eq!(w[d].to_array()[j], sw[d], "x16 draw_u32 lane {j}");
            assert_eq!(
                r[d].to_array()[j].to_bits(),
                sr[d].to_bits(),
                "x16 rnd lane {j}"
            );
        }
    }
}

/// Lane `j`'s root arguments `[x, y, frame, index, seed]`: each varies across the lanes (and
/// a split's sub-sample is `sub + j`).
fn lane_args(root: [u32; 5], j: u32) -> [u32; 5] {
    let [x, y, frame, index, seed] = root;
    let m = j.wrapping_mul(0x9e37_79b9);
    [
        x ^ (j << 13),
        y.wrapping_add(j),
        frame ^ (m & 3),
        index.wrapping_add(j.wrapping_mul(7)),
        seed ^ (m >> 29),
    ]
}

fn run<P: Pattern>(root: [u32; 5], steps: &[Step], frames: bool) {
    let [x, y, frame, index, seed] = root;
    // `new_frame` is `new` of the 64-bit sample number `frame * max(spp, 1) + index` (high
    // word as `frame`), worked here in 128 bits, for an arbitrary `spp` from the input; under
    // `Blue<P>` its domain word carries the tag 2 in its low two bits (a root whose domains
    // 0..6 are slots), `new`'s the tag 0.
    let spp = seed.rotate_left(7) ^ frame;
    let n = u128::from(frame) * u128::from(spp.max(1)) + u128::from(index);
    let [pixel, domain, sample] =
        Sampler::<P>::new([x, y], (n >> 32) as u32, n as u32, seed).to_words();
    let blue = P::ID & 2 != 0;
    assert_eq!(
        Sampler::<P>::new_frame([x, y], frame, spp, index, seed).to_words(),
        [pixel, if blue { domain & !3 | 2 } else { domain }, sample],
        "new_frame numbering"
    );
    // The root: `new`, or (`frames`) `new_frame` at 1 spp, whose domains 0..6 are `Blue<P>`'s
    // spatiotemporal slots (the wide forms have no `new_frame`: their lanes are its roots).
    let make = |[x, y, f, i, sd]: [u32; 5]| {
        if frames {
            Sampler::<P>::new_frame([x, y], f, 1, i, sd)
        } else {
            Sampler::<P>::new([x, y], f, i, sd)
        }
    };
    let mut s = make(root);
    let args8: [[u32; 5]; 8] = std::array::from_fn(|j| lane_args(root, j as u32));
    let args16: [[u32; 5]; 16] = std::array::from_fn(|j| lane_args(root, j as u32));
    let mut lanes8 = args8.map(make);
    let mut lanes16 = args16.map(make);
    let col8 = |c: usize| u32x8::new(args8.map(|a| a[c]));
    let col16 = |c: usize| u32x16::new(args16.map(|a| a[c]));
    let mut x8 = if frames {
        SamplerX8::<P>::from_lanes(lanes8)
    } else {
        SamplerX8::<P>::new([col8(0), col8(1)], col8(2), col8(3), col8(4))
    };
    let mut x16 = if frames {
        SamplerX16::<P>::from_lanes(lanes16)
    } else {
        SamplerX16::<P>::new([col16(0), col16(1)], col16(2), col16(3), col16(4))
    };
    for k in 0..=steps.len() {
        for (j, lane) in lanes8.iter().enumerate() {
            assert_eq!(x8.lane(j), *lane, "x8 state, lane {j}, step {k}");
        }
        for (j, lane) in lanes16.iter().enumerate() {
            assert_eq!(x16.lane(j), *lane, "x16 state, lane {j}, step {k}");
        }
        dims::<P, 1>(s, &lanes8, x8, &lanes16, x16);
        dims::<P, 2>(s, &lanes8, x8, &lanes16, x16);
        dims::<P, 3>(s, &lanes8, x8, &lanes16, x16);
        dims::<P, 4>(s, &lanes8, x8, &lanes16, x16);
        let Some(&step) = steps.get(k) else { break };
        match step {
            Step::Domain(key) => {
                s = s.domain(key);
                lanes8 = lanes8.map(|l| l.domain(key));
                lanes16 = lanes16.map(|l| l.domain(key));
                x8 = x8.domain(key);
                x16 = x16.domain(key);
            }
            Step::Split(key, size, sub) => {
                let sub_j = |j: u32| sub.wrapping_add(j);
                s = s.split(key, size, sub);
                for (j, l) in lanes8.iter_mut().enumerate() {
                    *l = l.split(key, size, sub_j(j as u32));
                }
                for (j, l) in lanes16.iter_mut().enumerate() {
                    *l = l.split(key, size, sub_j(j as u32));
                }
                x8 = x8.split(
                    key,
                    size,
                    u32x8::new(std::array::from_fn(|j| sub_j(j as u32))),
                );
                x16 = x16.split(
                    key,
                    size,
                    u32x16::new(std::array::from_fn(|j| sub_j(j as u32))),
                );
            }
        }
    }
}

/// The check: any pattern, any root, any domain path.
pub fn sampler(data: &[u8]) {
    let w = words(data);
    let get = |k: usize| w.get(k).copied().unwrap_or(0);
    let root = [get(1), get(2), get(3), get(4), get(5)];
    let mut steps = Vec::new();
    let mut k = 6;
    while k < w.len() && steps.len() < MAX_STEPS {
        let op = w[k];
        if op & 1 == 0 {
            steps.push(Step::Domain(get(k + 1)));
            k += 2;
        } else {
            steps.push(Step::Split(get(k + 1), get(k + 2), get(k + 3)));
            k += 4;
        }
    }
    // Bit 2 of the first word: a `new_frame` root (its domains 0..6 are Blue's slots).
    let frames = get(0) & 4 != 0;
    match get(0) % 4 {
        0 => run::<Pmj02bn>(root, &steps, frames),
        1 => run::<Sobol>(root, &steps, frames),
        #[cfg(feature = "blue-noise")]
        2 => run::<warpcore::sampler::Blue<Pmj02bn>>(root, &steps, frames),
        #[cfg(feature = "blue-noise")]
        _ => run::<warpcore::sampler::Blue<Sobol>>(root, &steps, frames),
        #[cfg(not(feature = "blue-noise"))]
        p => {
            if p == 2 {
                run::<Pmj02bn>(root, &steps, frames)
            } else {
                run::<Sobol>(root, &steps, frames)
            }
        }
    }
}
