//! `shaders/warpcore_lights.wgsl` (light selection from the crate's storage words) against
//! the crate, word for word, on Mesa's lavapipe. The same environment variables as
//! `tests/lavapipe.rs`.

use warpcore::lights::AliasTable;
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

/// `(name, output words, call)` of each public function.
const FUNCTIONS: [(&str, usize, &str); 2] = [
    (
        "wc_lights_alias_sample",
        2,
        "wc_lights_alias_sample(wc_in[b], bitcast<f32>(wc_in[b + 1u]))",
    ),
    (
        "wc_lights_alias_pmf",
        1,
        "wc_lights_alias_pmf(wc_in[b], wc_in[b + 1u])",
    ),
];

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
    (name, outw, call): (&str, usize, &str),
    input: &[u32],
    buffer: &[u32],
) -> Vec<u32> {
    let body = call_body(call, outs(name).iter().copied());
    let source = check_shader(library, [2, 3], [2, outw], &body);
    gpu.run_bound(name, &source, input, 2, outw, &[(4, buffer)], [2, 3])
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn every_lights_function_is_bit_identical_on_lavapipe() {
    let Some(gpu) = lavapipe() else { return };
    let (buffer, bases) = tables();
    let mut failed = Vec::new();
    for (k, (name, outw, _)) in FUNCTIONS.into_iter().enumerate() {
        let input = inputs(name.ends_with("sample"), &bases, random_points() / 8);
        let want = cpu(name, &buffer, &input);
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

/// Changes of the library that a sharp check must see: `(what, text, replacement)`.
const MUTATIONS: [(&str, &str, &str); 2] = [
    (
        "<=",
        "let stay = frac < threshold;",
        "let stay = frac <= threshold;",
    ),
    (
        "float column",
        "let column = wcli_mul_high(key, n);",
        "let column = min(u32(x * f32(n)), n - 1u);",
    ),
];

/// The check is sharp: a threshold test with `<=` instead of `<`, or a float product for
/// the column, changes outputs.
#[test]
fn a_subtle_change_is_detected() {
    let Some(gpu) = lavapipe() else { return };
    let (buffer, bases) = tables();
    let input = inputs(true, &bases, 1 << 12);
    let want = cpu(FUNCTIONS[0].0, &buffer, &input);
    for (what, from, to) in MUTATIONS {
        let wrong = LIGHTS_WGSL.replace(from, to);
        assert_ne!(wrong, LIGHTS_WGSL, "{what}: the text to change is there");
        let got = on_gpu(&gpu, &wrong, FUNCTIONS[0], &input, &buffer);
        let differ = got
            .chunks_exact(2)
            .zip(want.chunks_exact(2))
            .filter(|(g, w)| g != w)
            .count();
        println!("{what}: {differ} of {} points differ", want.len() / 2);
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
