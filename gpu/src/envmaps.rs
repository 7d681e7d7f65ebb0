//! `shaders/warpcore_envmap.wgsl` (environment-map sampling from the storage words) against
//! the crate: a buffer of maps built by the crate ([`env_buffer`]), the checks
//! ([`ENV_FUNCTIONS`]), their test points ([`env_inputs`]) and the GPU run ([`run`]).

use crate::{Gpu, Rng, call_body, check_shader, square_edges};
use std::sync::OnceLock;
use warpcore::envmap::{Hierarchical, MarginalConditional, Word};

/// The environment-map library, as shipped.
pub const ENVMAP_WGSL: &str = include_str!("../../shaders/warpcore_envmap.wgsl");

/// Which distribution a check reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Hierarchical,
    MarginalConditional,
}

/// The test maps, `(name, width, height, weights)`: sizes from 1 x 1 to 300 x 7, powers of
/// two and not, zeros, negatives, NaN, subnormals, `f32::MAX`, dynamic ranges of 10^18, an
/// all-zero map (uniform), a bright spot.
pub fn env_maps() -> Vec<(String, usize, usize, Vec<f32>)> {
    let mut rng = Rng::new(0xe9f1_a9e5);
    let mut maps = vec![
        ("1x1".to_string(), 1, 1, vec![5.0]),
        (
            "4x2".to_string(),
            4,
            2,
            vec![1.0, 2.0, 0.0, 1.0, 4.0, 0.0, 0.5, 0.5],
        ),
        (
            "3x3 stiff".to_string(),
            3,
            3,
            vec![
                f32::MAX,
                f32::from_bits(1),
                0.0,
                -1.0,
                f32::NAN,
                1e-30,
                f32::MIN_POSITIVE,
                3.0,
                f32::MAX,
            ],
        ),
        ("7x5 zero".to_string(), 7, 5, vec![0.0; 35]),
    ];
    for (w, h) in [(1, 13), (13, 1), (5, 3), (64, 32), (300, 7), (17, 33)] {
        let weights = (0..w * h)
            .map(|k| {
                if k % 3 == 0 && w * h > 20 {
                    0.0
                } else {
                    let e = (rng.next_u32() % 60) as i32 - 30;
                    rng.grid24() * 2f32.powi(e)
                }
            })
            .collect();
        maps.push((format!("{w}x{h} random"), w, h, weights));
    }
    let (w, h) = (200, 100);
    let spot = (0..w * h)
        .map(|k| {
            let (x, y) = ((k % w) as f32 - 140.5, (k / w) as f32 - 30.5);
            0.05 + 1e5 * (-(x * x + y * y) / 8.0).exp()
        })
        .collect();
    maps.push(("200x100 spot".to_string(), w, h, spot));
    maps
}

/// The test maps' storages one after the other, and `(kind, name, base)` per storage.
pub type EnvBuffer = (Vec<u32>, Vec<(Kind, String, u32)>);

/// All test maps' storages, both kinds, one after the other, with each map's word offset:
/// `(buffer, [(kind, name, base)])`. Built once.
pub fn env_buffer() -> &'static EnvBuffer {
    static BUFFER: OnceLock<EnvBuffer> = OnceLock::new();
    BUFFER.get_or_init(|| {
        let mut buffer = Vec::new();
        let mut bases = Vec::new();
        for (name, w, h, weights) in env_maps() {
            let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
            let map = Hierarchical::new(&weights, w, h, &mut s).expect("hierarchical map");
            bases.push((Kind::Hierarchical, name.clone(), buffer.len() as u32));
            buffer.extend_from_slice(map.storage());
            let mut s = vec![0 as Word; MarginalConditional::storage_len(w, h)];
            let map = MarginalConditional::new(&weights, w, h, &mut s).expect("marginal map");
            bases.push((Kind::MarginalConditional, name, buffer.len() as u32));
            buffer.extend_from_slice(map.storage());
        }
        (buffer, bases)
    })
}

/// One check of the environment-map library.
#[derive(Clone, Copy)]
pub struct EnvFunc {
    pub name: &'static str,
    pub kind: Kind,
    /// `sample` (5 output words: u, v, pdf, column, row) or `pdf` (1 word).
    pub sample: bool,
}

impl EnvFunc {
    pub fn out_words(&self) -> usize {
        if self.sample { 5 } else { 1 }
    }
    /// Is output word `k` an integer (the texel) rather than `f32` bits?
    pub fn is_integer_output(&self, k: usize) -> bool {
        self.sample && k >= 3
    }
}

/// Every public function of `shaders/warpcore_envmap.wgsl`.
pub const ENV_FUNCTIONS: &[EnvFunc] = &[
    EnvFunc {
        name: "wc_envmap_hierarchical_sample",
        kind: Kind::Hierarchical,
        sample: true,
    },
    EnvFunc {
        name: "wc_envmap_hierarchical_pdf",
        kind: Kind::Hierarchical,
        sample: false,
    },
    EnvFunc {
        name: "wc_envmap_marginal_conditional_sample",
        kind: Kind::MarginalConditional,
        sample: true,
    },
    EnvFunc {
        name: "wc_envmap_marginal_conditional_pdf",
        kind: Kind::MarginalConditional,
        sample: false,
    },
];

/// The crate's words for one point `[base, x, y]` (`x`, `y` as f32 bits).
pub fn env_eval(func: &EnvFunc, buffer: &[u32], i: &[u32], o: &mut [u32]) {
    let storage = &buffer[i[0] as usize..];
    let p = [f32::from_bits(i[1]), f32::from_bits(i[2])];
    let (s, pdf) = match func.kind {
        Kind::Hierarchical => {
            let m = Hierarchical::from_storage(storage).expect("storage");
            (m.sample(p), m.pdf(p))
        }
        Kind::MarginalConditional => {
            let m = MarginalConditional::from_storage(storage).expect("storage");
            (m.sample(p), m.pdf(p))
        }
    };
    if func.sample {
        o.copy_from_slice(&[
            s.uv[0].to_bits(),
            s.uv[1].to_bits(),
            s.pdf.to_bits(),
            s.texel[0],
            s.texel[1],
        ]);
    } else {
        o[0] = pdf.to_bits();
    }
}

/// The crate's output words for every point of `input`.
pub fn cpu_outputs(func: &EnvFunc, input: &[u32]) -> Vec<u32> {
    let buffer = &env_buffer().0;
    let outw = func.out_words();
    let mut out = vec![0u32; input.len() / 3 * outw];
    for (i, o) in input.chunks_exact(3).zip(out.chunks_exact_mut(outw)) {
        env_eval(func, buffer, i, o);
    }
    out
}

/// The test points of `func`, `[base, x, y]` each, over every test map of its kind: edge
/// values of the square (every f32 class) paired, a 64 x 64 grid, random points (on the 2^-24
/// grid, at full precision, random bit patterns) and, for `pdf`, the texel edges of the map
/// and their neighbouring floats.
pub fn env_inputs(func: &EnvFunc, random: usize, seed: u64) -> Vec<u32> {
    let (buffer, bases) = env_buffer();
    let mut rng = Rng::new(seed ^ 0xe4);
    let edges = square_edges();
    let mut v = Vec::new();
    for (_, _, base) in bases.iter().filter(|(k, _, _)| *k == func.kind) {
        let mut put = |x: f32, y: f32| v.extend([*base, x.to_bits(), y.to_bits()]);
        for &a in &edges {
            for &b in &edges {
                put(a, b);
            }
        }
        for i in 0..64 {
            for j in 0..64 {
                put(i as f32 / 64.0, (j as f32 + 0.5) / 64.0);
            }
        }
        for _ in 0..random {
            put(rng.grid24(), rng.grid24());
            put(rng.unit_any(), rng.unit_any());
            put(rng.bits(), rng.bits());
        }
        if !func.sample {
            // The texel edges of both axes (header words 2..8 locate them) and their
            // neighbours: where a pdf lookup must pick the right texel.
            let b = *base as usize;
            let (w, h) = (buffer[b + 2] as usize, buffer[b + 3] as usize);
            let lens: Vec<usize> = (4..8).map(|k| buffer[b + k] as usize).collect();
            let ex = b + 16 + lens[0] + lens[1];
            let ey = ex + lens[2];
            let near = |bits: u32| [bits.saturating_sub(1), bits, bits + 1].map(f32::from_bits);
            for k in 0..=w.min(400) {
                for x in near(buffer[ex + k]) {
                    put(x, rng.grid24());
                }
            }
            for k in 0..=h.min(400) {
                for y in near(buffer[ey + k]) {
                    put(rng.grid24(), y);
                }
            }
        }
    }
    v
}

/// The compute shader that runs `func` on every point of `wc_in` (binding 2; `wc_out` is
/// binding 3, the library's `wc_envmap` binding 1).
pub fn shader_source(func: &EnvFunc) -> String {
    shader_source_with(func, ENVMAP_WGSL)
}

/// [`shader_source`] with another library text.
pub fn shader_source_with(func: &EnvFunc, library: &str) -> String {
    let call = format!(
        "{}(wc_in[b], vec2<f32>(bitcast<f32>(wc_in[b + 1u]), bitcast<f32>(wc_in[b + 2u])))",
        func.name
    );
    let outs: &[&str] = if func.sample {
        &[
            "bitcast<u32>(r.uv.x)",
            "bitcast<u32>(r.uv.y)",
            "bitcast<u32>(r.pdf)",
            "r.texel.x",
            "r.texel.y",
        ]
    } else {
        &["bitcast<u32>(r)"]
    };
    let body = call_body(&call, outs.iter().copied());
    check_shader(library, [2, 3], [3, func.out_words()], &body)
}

/// `func` on the GPU for every point of `input`, with the test maps bound.
pub fn run(gpu: &Gpu, func: &EnvFunc, source: &str, input: &[u32]) -> Result<Vec<u32>, String> {
    let buffer = &env_buffer().0;
    gpu.run_bound(
        func.name,
        source,
        input,
        3,
        func.out_words(),
        &[(1, buffer)],
        [2, 3],
    )
}
