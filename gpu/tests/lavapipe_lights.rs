//! `shaders/warpcore_lights.wgsl` (light selection from the crate's storage words) against
//! the crate, word for word, on Mesa's lavapipe. The same environment variables as
//! `tests/lavapipe.rs`.

use warpcore::lights::{AliasTable, LightBounds, LightTree};
use warpcore_gpu::testing::{lavapipe, library, random_points};
use warpcore_gpu::{Rng, call_body, check_shader, compare_words, square_edges};

/// The shipped library.
const LIGHTS_WGSL: &str = include_str!("../../shaders/warpcore_lights.wgsl");

/// Test tables one after the other, with each one's word offset and light count: one light,
/// equal weights, zeros mixed in, a 10^18 dynamic range, subnormals next to `f32::MAX`, a
/// thousand ragged weights.
fn tables() -> (Vec<u32>, Vec<(u32, u32)>) {
    let mut rng = Rng::new(0x11a5);
    let ragged: Vec<f32> = (0..1000)
        .map(|k| {
            if k % 5 == 1 {
                0.0
            } else {
                rng.grid24() * 2f32.powi((k % 40) - 20)
            }
        })
        .collect();
    let sets: Vec<Vec<f32>> = vec![
        vec![2.0],
        vec![1.0; 7],
        vec![0.0, 3.0, 0.0, 0.0, 1.0, 0.5],
        (0..64)
            .map(|k| if k % 2 == 0 { 1e-18 } else { 1.0 })
            .collect(),
        vec![
            f32::from_bits(1),
            f32::MAX,
            0.0,
            f32::MIN_POSITIVE,
            f32::from_bits(77),
        ],
        ragged,
    ];
    let (mut buffer, mut bases) = (Vec::new(), Vec::new());
    for w in sets {
        let mut s = vec![0u32; AliasTable::storage_len(w.len())];
        AliasTable::new(&w, &mut s).expect("valid weights");
        bases.push((buffer.len() as u32, w.len() as u32));
        buffer.extend_from_slice(&s);
    }
    (buffer, bases)
}

/// Light-tree test sets appended to `buffer` (each at its word offset, with its light
/// count): one light; 24 of every kind (one- and two-sided areas, spots, points, two of
/// power 0); 300 clustered lights of ragged power and orientation; 40 lights far from the
/// origin (1e15) next to tiny ones; 21 with one at 1e20 and faint powers.
fn trees(buffer: &mut Vec<u32>) -> Vec<(u32, u32)> {
    let mut rng = Rng::new(0x7ee);
    let light = |k: usize, scale: f32, rng: &mut Rng| {
        let c = [
            rng.range(-4.0, 4.0),
            rng.range(-2.0, 2.0),
            rng.range(0.0, 2.0),
        ]
        .map(|x| x * scale);
        let h = rng.range(0.0, 0.5) * scale;
        let (cos_theta_o, cos_theta_e, two_sided) = match k % 4 {
            0 => (1.0, 0.0, false),
            1 => (1.0, 0.0, true),
            2 => (rng.range(-1.0, 1.0), rng.range(-1.0, 1.0), k % 8 == 2),
            _ => (-1.0, 0.0, false),
        };
        LightBounds {
            min: [c[0] - h, c[1] - h, c[2]],
            max: [c[0] + h, c[1] + h, c[2] + h],
            power: if k % 11 == 5 {
                0.0
            } else {
                rng.range(0.0, 10.0) * 2f32.powi((k % 9) as i32 - 4)
            },
            axis: [
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0),
                rng.range(-1.0, 1.0) + 0.01,
            ],
            cos_theta_o,
            cos_theta_e,
            two_sided,
        }
    };
    let sets: Vec<Vec<LightBounds>> = vec![
        vec![light(0, 1.0, &mut rng)],
        (0..24).map(|k| light(k, 1.0, &mut rng)).collect(),
        (0..300)
            .map(|k| light(k, if k < 150 { 0.2 } else { 3.0 }, &mut rng))
            .collect(),
        (0..40)
            .map(|k| light(k, if k % 2 == 0 { 1e15 } else { 1e-6 }, &mut rng))
            .collect(),
        // The range the per-quad scales serve: one light at 1e20 among unit ones, and powers
        // down to 1e-30.
        (0..21)
            .map(|k| {
                let mut l = light(k, 1.0, &mut rng);
                if k == 20 {
                    (l.min, l.max) = ([1e20, -1e20, 0.0], [1e20, -1e20, 0.0]);
                }
                if k % 3 == 1 {
                    l.power *= 1e-30;
                }
                l
            })
            .collect(),
    ];
    let mut bases = Vec::new();
    for lights in sets {
        let mut s = vec![0u32; LightTree::storage_len(lights.len())];
        LightTree::new(&lights, &mut s).expect("valid lights");
        bases.push((buffer.len() as u32, lights.len() as u32));
        buffer.extend_from_slice(&s);
    }
    bases
}

/// Hostile floats for the tree's points, normals and `u`.
const HOSTILE: [f32; 10] = [
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    0.0,
    -0.0,
    1e-40,
    3e38,
    -1e30,
    1.0,
    0.5,
];

/// Tree inputs, 8 words a point: base, p, n, then `u` (sample) or a light index (pmf):
/// random points around each set (normals unit, zero, non-unit or absent), a grid of `u`
/// at a few points, and every mix of hostile values.
fn tree_inputs(sample: bool, buffer: &[u32], bases: &[(u32, u32)], random: usize) -> Vec<u32> {
    let mut rng = Rng::new(0x3e3);
    let mut v = Vec::new();
    for &(base, n) in bases {
        let tree = LightTree::from_storage(&buffer[base as usize..]).expect("storage");
        let scale = if n == 40 { 1e3 } else { 6.0 };
        let mut push = |p: [f32; 3], nrm: [f32; 3], u: f32, rng: &mut Rng| {
            let last = if sample {
                u.to_bits()
            } else {
                match rng.next_u32() % 4 {
                    0 => rng.next_u32() % (n + 2),
                    1 => [u32::MAX, 1 << 30, n][rng.next_u32() as usize % 3],
                    _ => tree.sample(p, nrm, u).map_or(0, |(i, _)| i),
                }
            };
            v.push(base);
            v.extend(p.map(f32::to_bits));
            v.extend(nrm.map(f32::to_bits));
            v.push(last);
        };
        for _ in 0..random {
            let p = [0; 3].map(|_| rng.range(-scale, scale));
            let nrm = match rng.next_u32() % 4 {
                0 => [0.0; 3],
                1 => [0; 3].map(|_| rng.range(-3.0, 3.0)),
                _ => {
                    let d = [0; 3].map(|_| rng.range(-1.0, 1.0));
                    let l = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                    d.map(|x| x / l)
                }
            };
            let u = match rng.next_u32() % 3 {
                0 => rng.grid24(),
                1 => rng.unit_any(),
                _ => rng.bits(),
            };
            push(p, nrm, u, &mut rng);
        }
        for k in 0..=64 {
            push(
                [0.5, -0.25, 1.0],
                [0.0, 0.0, 1.0],
                k as f32 / 64.0,
                &mut rng,
            );
        }
        for a in HOSTILE {
            for b in HOSTILE {
                let c = HOSTILE[(a.to_bits() ^ b.to_bits()) as usize % HOSTILE.len()];
                push([a, b, 0.5], [b, c, 0.0], c, &mut rng);
                push([0.3, a, b], [0.0, a, 1.0], b, &mut rng);
            }
        }
    }
    v
}

fn tree_cpu(name: &str, buffer: &[u32], input: &[u32]) -> Vec<u32> {
    let mut out = Vec::new();
    for i in input.chunks_exact(8) {
        let t = LightTree::from_storage(&buffer[i[0] as usize..]).expect("storage");
        let f = |k: usize| f32::from_bits(i[k]);
        let (p, n) = ([f(1), f(2), f(3)], [f(4), f(5), f(6)]);
        if name.ends_with("sample") {
            let (index, q) = t.sample(p, n, f(7)).unwrap_or((u32::MAX, 0.0));
            out.extend([index, q.to_bits()]);
        } else {
            out.push(t.pmf(p, n, i[7]).to_bits());
        }
    }
    out
}

/// `(name, input words, output words, call)` of each public function.
const FUNCTIONS: [(&str, usize, usize, &str); 4] = [
    (
        "wc_lights_alias_sample",
        2,
        2,
        "wc_lights_alias_sample(wc_in[b], bitcast<f32>(wc_in[b + 1u]))",
    ),
    (
        "wc_lights_alias_pmf",
        2,
        1,
        "wc_lights_alias_pmf(wc_in[b], wc_in[b + 1u])",
    ),
    (
        "wc_lights_tree_sample",
        8,
        2,
        "wc_lights_tree_sample(wc_in[b], P, N, bitcast<f32>(wc_in[b + 7u]))",
    ),
    (
        "wc_lights_tree_pmf",
        8,
        1,
        "wc_lights_tree_pmf(wc_in[b], P, N, wc_in[b + 7u])",
    ),
];

/// The point and normal of a tree call (input words 1..7).
const P: &str = "bitcast<vec3<f32>>(vec3<u32>(wc_in[b + 1u], wc_in[b + 2u], wc_in[b + 3u]))";
const N: &str = "bitcast<vec3<f32>>(vec3<u32>(wc_in[b + 4u], wc_in[b + 5u], wc_in[b + 6u]))";

fn outs(name: &str) -> &'static [&'static str] {
    if name.ends_with("sample") {
        &["r.index", "bitcast<u32>(r.prob)"]
    } else {
        &["bitcast<u32>(r)"]
    }
}

fn cpu(name: &str, buffer: &[u32], input: &[u32]) -> Vec<u32> {
    let mut out = Vec::new();
    for i in input.chunks_exact(2) {
        let t = AliasTable::from_storage(&buffer[i[0] as usize..]).expect("storage");
        if name.ends_with("sample") {
            let (index, p) = t.sample(f32::from_bits(i[1]));
            out.extend([index, p.to_bits()]);
        } else {
            out.push(t.pmf(i[1]).to_bits());
        }
    }
    out
}

fn inputs(sample: bool, bases: &[(u32, u32)], random: usize) -> Vec<u32> {
    let mut rng = Rng::new(0x5a3);
    let mut v = Vec::new();
    for &(base, n) in bases {
        if sample {
            for x in square_edges() {
                v.extend([base, x.to_bits()]);
            }
            for k in 0..=4 * n {
                let x = k as f32 / (4 * n) as f32;
                for y in [
                    x,
                    x.next_up(),
                    f32::from_bits(x.to_bits().saturating_sub(1)),
                ] {
                    v.extend([base, y.to_bits()]);
                }
            }
            for _ in 0..random {
                v.extend([base, rng.grid24().to_bits(), base, rng.unit_any().to_bits()]);
                v.extend([base, rng.bits().to_bits()]);
            }
        } else {
            for k in 0..n + 3 {
                v.extend([base, k]);
            }
            v.extend([base, u32::MAX, base, 1 << 30]);
        }
    }
    v
}

/// `func` of `library` on the GPU for every point of `input`, the tables of `buffer` bound.
fn on_gpu(
    gpu: &warpcore_gpu::Gpu,
    library: &str,
    (name, inw, outw, call): (&str, usize, usize, &str),
    input: &[u32],
    buffer: &[u32],
) -> Vec<u32> {
    let call = call
        .replace("P,", &format!("{P},"))
        .replace("N,", &format!("{N},"));
    let body = call_body(&call, outs(name).iter().copied());
    let source = check_shader(library, [2, 3], [inw, outw], &body);
    gpu.run_bound(name, &source, input, inw, outw, &[(4, buffer)], [2, 3])
        .unwrap_or_else(|e| panic!("{e}"))
}

/// The alias tables and the trees in one buffer, the inputs of `name` and the crate's outputs.
fn case(name: &str, random: usize) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
    let (mut buffer, bases) = tables();
    let tree_bases = trees(&mut buffer);
    let sample = name.ends_with("sample");
    if name.contains("tree") {
        let input = tree_inputs(sample, &buffer, &tree_bases, random);
        let want = tree_cpu(name, &buffer, &input);
        (buffer, input, want)
    } else {
        let input = inputs(sample, &bases, random);
        let want = cpu(name, &buffer, &input);
        (buffer, input, want)
    }
}

#[test]
fn every_lights_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    let mut failed = Vec::new();
    for (k, (name, _, outw, _)) in FUNCTIONS.into_iter().enumerate() {
        let (buffer, input, want) = case(name, random_points() / 8);
        let got = on_gpu(&gpu, LIGHTS_WGSL, FUNCTIONS[k], &input, &buffer);
        let d = compare_words(outw, |w| outw == 2 && w == 0, &got, &want);
        println!(
            "{name:<28} {:>8} points {:>7} mismatches",
            d.points, d.mismatches
        );
        if d.mismatches > 0 {
            failed.push(name);
        }
    }
    assert!(failed.is_empty(), "mismatches in {failed:?}");
}

/// Changes of the library that a sharp check must see: `(what, function, text, replacement)`.
const MUTATIONS: [(&str, usize, &str, &str); 6] = [
    (
        "<=",
        0,
        "let stay = frac < threshold;",
        "let stay = frac <= threshold;",
    ),
    (
        "float column",
        0,
        "let column = wcli_mul_high(key, n);",
        "let column = min(u32(x * f32(n)), n - 1u);",
    ),
    (
        "tree: product order",
        2,
        "let imp0 = q * cos_pi * cos_p;",
        "let imp0 = phi * cos_p * cos_pi / dc;",
    ),
    (
        "tree: the level's probability by a reciprocal",
        2,
        "let p_child = select(0.0f, chosen / sum, live);",
        "let p_child = select(0.0f, chosen * (1.0f / sum), live);",
    ),
    (
        "tree: no quad evaluated at its scales",
        2,
        "if f0.y * f1.y * f2.y * f3.y == 0.0f {",
        "if false {",
    ),
    (
        "tree pmf: trail bits swapped",
        3,
        "high = ((trail >> (2u * level)) & 1u) != 0u;",
        "high = ((trail >> (2u * level + 1u)) & 1u) != 0u;",
    ),
];

/// The check is sharp: a threshold test with `<=` instead of `<`, a float product for the
/// column, the importance's products in another order, a quad out of range not evaluated
/// again at its scales, a level's probability by a reciprocal, or a trail read wrong changes
/// outputs.
#[test]
fn a_subtle_change_is_detected() {
    let Some(gpu) = lavapipe() else { return };
    for (what, f, from, to) in MUTATIONS {
        let (buffer, input, want) = case(FUNCTIONS[f].0, 1 << 12);
        let outw = FUNCTIONS[f].2;
        let wrong = LIGHTS_WGSL.replace(from, to);
        assert_ne!(wrong, LIGHTS_WGSL, "{what}: the text to change is there");
        let got = on_gpu(&gpu, &wrong, FUNCTIONS[f], &input, &buffer);
        let differ = got
            .chunks_exact(outw)
            .zip(want.chunks_exact(outw))
            .filter(|(g, w)| g != w)
            .count();
        println!("{what}: {differ} of {} points differ", want.len() / outw);
        assert!(differ > 0, "{what}");
    }
}

/// The library rules: one binding, no entry point, every public function checked; it parses
/// together with the other three files.
#[test]
fn the_lights_file_is_a_library_with_one_binding() {
    let public = library(LIGHTS_WGSL, 1);
    assert_eq!(public.len(), FUNCTIONS.len(), "{public:?}");
    for name in &public {
        assert!(FUNCTIONS.iter().any(|f| f.0 == name), "{name}");
    }
    for bad in warpcore_gpu::testing::NOT_IN_A_LIBRARY {
        assert!(!LIGHTS_WGSL.contains(bad), "{bad}");
    }
    let all = format!(
        "{}\n{}\n{}\n{}",
        warpcore_gpu::WGSL,
        warpcore_gpu::tables::TABLES_WGSL,
        warpcore_gpu::envmaps::ENVMAP_WGSL,
        LIGHTS_WGSL
    );
    naga::front::wgsl::parse_str(&all).expect("the four files parse together");
}
