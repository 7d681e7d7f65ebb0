//! `shaders/warpcore_tables.wgsl` (pmj02bn and the sampling core on the GPU): the contents of
//! its one storage buffer, and the checks that compare its functions with the crate.
//!
//! [`table_words`] / [`table_bytes`] build the buffer a renderer uploads (the layout is
//! documented at the top of the WGSL file and in docs/gpu.md); [`TABLE_FUNCTIONS`] lists the
//! checks, each a WGSL body over input words with the crate function that defines its output
//! words; [`table_inputs`] builds their test points (edge values, whole table blocks, random
//! words); [`run`] evaluates one on a GPU.

use crate::{Gpu, check_shader};
use std::fmt::Write as _;
use warpcore::pmj02bn;
use warpcore::sampler::{Blue, Pattern, Pmj02bn, Sampler, Sobol};

/// The table library, as shipped.
pub const TABLES_WGSL: &str = include_str!("../../shaders/warpcore_tables.wgsl");

/// Side of the blue-noise key tiles (`warpcore::sampler::BLUE_TILE`).
pub const BLUE_TILE: usize = warpcore::sampler::BLUE_TILE as usize;

/// The blue-noise key tiles of the crate (`src/tables/blue_*_64.bin`), Sobol' then pmj02bn.
const BLUE_SOBOL: &[u8] = include_bytes!("../../src/tables/blue_sobol_64.bin");
const BLUE_PMJ02BN: &[u8] = include_bytes!("../../src/tables/blue_pmj02bn_64.bin");
/// The blue-noise slot tiles (16-bit index offsets), Sobol' then pmj02bn.
const SLOTS_SOBOL: &[u8] = include_bytes!("../../src/tables/blue_slots_sobol_64.bin");
const SLOTS_PMJ02BN: &[u8] = include_bytes!("../../src/tables/blue_slots_pmj02bn_64.bin");

/// Word offsets of the buffer's parts, for this build of the crate (`WC_TABLES_*` in the
/// WGSL file, which assumes the default build: 4096 points, 4 sets).
pub const PMJ02BN_WORDS: usize = 2 * pmj02bn::POINTS * pmj02bn::SETS;
pub const SOBOL_WORDS: usize = 4 * 1024;
pub const BLUE_WORDS: usize = BLUE_TILE * BLUE_TILE;
/// Words of one pattern's slot tiles (two 16-bit offsets per word).
pub const SLOT_WORDS: usize = warpcore::sampler::BLUE_SLOTS * BLUE_WORDS / 2;

/// Sobol' direction numbers of dimension `d` (1..=3) as 0.32 fixed point: the primitive
/// polynomials `x + 1`, `x^2 + x + 1`, `x^3 + x + 1` with Joe and Kuo's initial `m` values
/// `(1)`, `(1, 3)`, `(1, 3, 1)`, continued by the Bratley-Fox recurrence (the construction of
/// `src/sampler/sobol.rs`).
fn sobol_directions(d: usize) -> [u32; 32] {
    let (s, a, init): (usize, u64, [u64; 3]) =
        [(1, 0, [1, 0, 0]), (2, 1, [1, 3, 0]), (3, 1, [1, 3, 1])][d - 1];
    let mut m = [0u64; 33];
    for k in 1..=32 {
        m[k] = if k <= s {
            init[k - 1]
        } else {
            let mut x = m[k - s] ^ (m[k - s] << s);
            for j in 1..s {
                if (a >> (s - 1 - j)) & 1 == 1 {
                    x ^= m[k - j] << j;
                }
            }
            x
        };
    }
    core::array::from_fn(|k| (m[k + 1] << (31 - k)) as u32)
}

/// The Sobol' part: row `256 b + byte` holds, for dimensions 0..3, the XOR of the bit-reversed
/// direction numbers of the index bits that the set bits of `byte` stand for in byte `b` of
/// the bit-reversed index (bit `8 b + j` of `reverse(i)` is bit `31 - (8 b + j)` of `i`).
pub fn sobol_rows() -> Vec<u32> {
    let dirs = [1, 2, 3].map(sobol_directions);
    let mut t = vec![0u32; SOBOL_WORDS];
    for e in 0..1024 {
        let (b, byte) = (e / 256, e % 256);
        for j in 0..8 {
            if (byte >> j) & 1 == 1 {
                let k = 31 - (8 * b + j);
                t[4 * e] ^= 1 << k;
                for d in 1..4 {
                    t[4 * e + d] ^= dirs[d - 1][k].reverse_bits();
                }
            }
        }
    }
    t
}

/// The words of `shaders/warpcore_tables.wgsl`'s storage buffer for this build of the crate:
/// the pmj02bn sets (`pmj02bn::raw` over every set and index, x then y), the Sobol' rows and
/// the two blue-noise key tiles and the two patterns' slot tiles.
pub fn table_words() -> Vec<u32> {
    let mut w = Vec::with_capacity(PMJ02BN_WORDS + SOBOL_WORDS + 2 * BLUE_WORDS + 2 * SLOT_WORDS);
    for set in 0..pmj02bn::SETS {
        for i in 0..pmj02bn::POINTS {
            w.extend(pmj02bn::raw(set, i));
        }
    }
    w.extend(sobol_rows());
    for tile in [BLUE_SOBOL, BLUE_PMJ02BN, SLOTS_SOBOL, SLOTS_PMJ02BN] {
        w.extend(
            tile.chunks_exact(4)
                .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])),
        );
    }
    w
}

/// [`table_words`] as little-endian bytes: what a renderer uploads (`queue.write_buffer`).
pub fn table_bytes() -> Vec<u8> {
    table_words().iter().flat_map(|w| w.to_le_bytes()).collect()
}

/// What a check's test points look like.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TableDomain {
    /// (index, seed) pairs.
    IndexSeed,
    /// Sampler paths of one pattern (`WC_PATTERN_*`; 4 means unknown pattern values).
    Sampler(u32),
}

/// One check of the table library.
#[derive(Clone, Copy)]
pub struct TableFunc {
    /// What it checks (a WGSL function name, or the sampler functions for one pattern).
    pub name: &'static str,
    /// The public WGSL functions it calls.
    pub covers: &'static [&'static str],
    pub domain: TableDomain,
    pub in_words: usize,
    pub out_words: usize,
    /// The WGSL statements: read `wc_in[b + k]`, write `wc_out[o + k]`.
    pub wgsl: fn() -> String,
    /// The crate's output words for one point's input words.
    pub cpu: fn(&[u32], &mut [u32]),
}

const SAMPLER_FUNCTIONS: &[&str] = &[
    "wc_sampler_new",
    "wc_sampler_new_frame",
    "wc_sampler_domain",
    "wc_sampler_split",
    "wc_sampler_draw2",
    "wc_sampler_draw4",
    "wc_sampler_draw4_u32",
    "wc_sampler_rnd4",
];

/// Words per sampler path (see the `wc_sampler_*` checks of [`TABLE_FUNCTIONS`]).
pub const SAMPLER_OUT: usize = 48;

/// Every check of `shaders/warpcore_tables.wgsl`.
pub const TABLE_FUNCTIONS: &[TableFunc] = &[
    TableFunc {
        name: "wc_pmj02bn_sample",
        covers: &["wc_pmj02bn_sample"],
        domain: TableDomain::IndexSeed,
        in_words: 2,
        out_words: 2,
        wgsl: || {
            "let r = wc_pmj02bn_sample(wc_in[b], wc_in[b + 1u]);\n\
             wc_out[o] = bitcast<u32>(r.x);\n\
             wc_out[o + 1u] = bitcast<u32>(r.y);\n"
                .into()
        },
        cpu: |i, o| {
            let p = pmj02bn::sample(i[0], i[1]);
            o[0] = p[0].to_bits();
            o[1] = p[1].to_bits();
        },
    },
    TableFunc {
        name: "wc_pmj02bn_shuffle",
        covers: &["wc_pmj02bn_shuffle"],
        domain: TableDomain::IndexSeed,
        in_words: 2,
        out_words: 1,
        wgsl: || "wc_out[o] = wc_pmj02bn_shuffle(wc_in[b], wc_in[b + 1u]);\n".into(),
        cpu: |i, o| o[0] = pmj02bn::shuffle(i[0], i[1]),
    },
    TableFunc {
        name: "wc_sampler_* Pmj02bn",
        covers: SAMPLER_FUNCTIONS,
        domain: TableDomain::Sampler(0),
        in_words: 10,
        out_words: SAMPLER_OUT,
        wgsl: sampler_wgsl,
        cpu: sampler_cpu,
    },
    TableFunc {
        name: "wc_sampler_* Sobol",
        covers: SAMPLER_FUNCTIONS,
        domain: TableDomain::Sampler(1),
        in_words: 10,
        out_words: SAMPLER_OUT,
        wgsl: sampler_wgsl,
        cpu: sampler_cpu,
    },
    TableFunc {
        name: "wc_sampler_* Blue<Pmj02bn>",
        covers: SAMPLER_FUNCTIONS,
        domain: TableDomain::Sampler(2),
        in_words: 10,
        out_words: SAMPLER_OUT,
        wgsl: sampler_wgsl,
        cpu: sampler_cpu,
    },
    TableFunc {
        name: "wc_sampler_* Blue<Sobol>",
        covers: SAMPLER_FUNCTIONS,
        domain: TableDomain::Sampler(3),
        in_words: 10,
        out_words: SAMPLER_OUT,
        wgsl: sampler_wgsl,
        cpu: sampler_cpu,
    },
    TableFunc {
        name: "wc_sampler_* unknown pattern",
        covers: SAMPLER_FUNCTIONS,
        domain: TableDomain::Sampler(4),
        in_words: 10,
        out_words: SAMPLER_OUT,
        wgsl: sampler_wgsl,
        cpu: sampler_cpu,
    },
];

/// One sampler path from the input words `[pattern, x, y, frame, index, seed, k1, k2, size,
/// sub]`: the root `s`, `s1 = domain(s, k1)`, `s2 = split(s1, k2, size, sub)`, `s3 =
/// domain(s2, k1 ^ k2)`; out: the words of `s`, `draw4_u32(s)`, `draw2(s)`, `draw4(s)`,
/// `rnd4(s)`, `draw4_u32(s1)`, the words of `s2`, `draw4(s2)`, `draw2(s2)`, `draw4_u32(s3)`,
/// `rnd4(s3)`, the words of `sf = wc_sampler_new_frame(pattern, pixel, frame, size, index,
/// seed)`, `draw4_u32(domain(sf, k1))` (under blue noise a slot when `k1 < 6`; 48 words).
fn sampler_wgsl() -> String {
    let mut s = String::from(
        "let s = wc_sampler_new(wc_in[b], vec2<u32>(wc_in[b + 1u], wc_in[b + 2u]), \
         wc_in[b + 3u], wc_in[b + 4u], wc_in[b + 5u]);\n\
         let s1 = wc_sampler_domain(s, wc_in[b + 6u]);\n\
         let s2 = wc_sampler_split(s1, wc_in[b + 7u], wc_in[b + 8u], wc_in[b + 9u]);\n\
         let s3 = wc_sampler_domain(s2, wc_in[b + 6u] ^ wc_in[b + 7u]);\n\
         let sf = wc_sampler_new_frame(wc_in[b], vec2<u32>(wc_in[b + 1u], wc_in[b + 2u]), \
         wc_in[b + 3u], wc_in[b + 8u], wc_in[b + 4u], wc_in[b + 5u]);\n",
    );
    let mut k = 0;
    let mut put = |s: &mut String, e: String| {
        let _ = writeln!(s, "wc_out[o + {k}u] = {e};");
        k += 1;
    };
    let words = |v: &str| ["pattern", "pixel", "domain", "index"].map(|f| format!("{v}.{f}"));
    let u = |call: &str, n: usize| -> Vec<String> {
        ["x", "y", "z", "w"][..n]
            .iter()
            .map(|c| format!("{call}.{c}"))
            .collect()
    };
    let f = |call: &str, n: usize| -> Vec<String> {
        ["x", "y", "z", "w"][..n]
            .iter()
            .map(|c| format!("bitcast<u32>({call}.{c})"))
            .collect()
    };
    let mut all: Vec<String> = Vec::new();
    all.extend(words("s"));
    all.extend(u("wc_sampler_draw4_u32(s)", 4));
    all.extend(f("wc_sampler_draw2(s)", 2));
    all.extend(f("wc_sampler_draw4(s)", 4));
    all.extend(f("wc_sampler_rnd4(s)", 4));
    all.extend(u("wc_sampler_draw4_u32(s1)", 4));
    all.extend(words("s2"));
    all.extend(f("wc_sampler_draw4(s2)", 4));
    all.extend(f("wc_sampler_draw2(s2)", 2));
    all.extend(u("wc_sampler_draw4_u32(s3)", 4));
    all.extend(f("wc_sampler_rnd4(s3)", 4));
    all.extend(words("sf"));
    all.extend(u(
        "wc_sampler_draw4_u32(wc_sampler_domain(sf, wc_in[b + 6u]))",
        4,
    ));
    assert_eq!(all.len(), SAMPLER_OUT);
    for e in all {
        put(&mut s, e);
    }
    s
}

fn sampler_cpu(i: &[u32], o: &mut [u32]) {
    match i[0] {
        0 => sampler_path::<Pmj02bn>(i, o),
        1 => sampler_path::<Sobol>(i, o),
        2 => sampler_path::<Blue<Pmj02bn>>(i, o),
        3 => sampler_path::<Blue<Sobol>>(i, o),
        // An unknown pattern (the C ABI's rule): a root {pattern, 0, 0, 0} that domain and
        // split return unchanged, and draws of zeros.
        p => {
            o.fill(0);
            o[0] = p;
            o[22] = p; // the words of s2
            o[40] = p; // the words of new_frame's root
        }
    }
}

fn sampler_path<P: Pattern>(i: &[u32], o: &mut [u32]) {
    let pattern = i[0];
    let s = Sampler::<P>::new([i[1], i[2]], i[3], i[4], i[5]);
    let s1 = s.domain(i[6]);
    let s2 = s1.split(i[7], i[8], i[9]);
    let s3 = s2.domain(i[6] ^ i[7]);
    let words = |s: Sampler<P>| {
        let [a, b, c] = s.to_words();
        [pattern, a, b, c]
    };
    let bits = |v: &[f32]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
    let mut w: Vec<u32> = Vec::with_capacity(SAMPLER_OUT);
    w.extend(words(s));
    w.extend(s.draw_u32::<4>());
    w.extend(bits(&s.draw::<2>()));
    w.extend(bits(&s.draw::<4>()));
    w.extend(bits(&s.rnd::<4>()));
    w.extend(s1.draw_u32::<4>());
    w.extend(words(s2));
    w.extend(bits(&s2.draw::<4>()));
    w.extend(bits(&s2.draw::<2>()));
    w.extend(s3.draw_u32::<4>());
    w.extend(bits(&s3.rnd::<4>()));
    let sf = Sampler::<P>::new_frame([i[1], i[2]], i[3], i[8], i[4], i[5]);
    w.extend(words(sf));
    w.extend(sf.domain(i[6]).draw_u32::<4>());
    o.copy_from_slice(&w);
}

/// The compute shader that runs `func` on every point of `wc_in` (binding 1; `wc_out` is
/// binding 2, the library's `wc_tables` binding 0, which every check's shader reads, so that
/// the automatic layout always has the three bindings).
pub fn shader_source(func: &TableFunc) -> String {
    shader_source_with(func, TABLES_WGSL)
}

/// [`shader_source`] with another library text (for the sharpness checks).
pub fn shader_source_with(func: &TableFunc, library: &str) -> String {
    let body = format!(
        "    if (arrayLength(&wc_tables) == 0u) {{ return; }}\n{}",
        (func.wgsl)()
    );
    check_shader(library, [1, 2], [func.in_words, func.out_words], &body)
}

/// `func` on the GPU for every point of `input`, with the tables `tables` bound.
pub fn run(gpu: &Gpu, func: &TableFunc, input: &[u32], tables: &[u32]) -> Result<Vec<u32>, String> {
    run_source(gpu, func, &shader_source(func), input, tables)
}

/// [`run`] with another shader source.
pub fn run_source(
    gpu: &Gpu,
    func: &TableFunc,
    source: &str,
    input: &[u32],
    tables: &[u32],
) -> Result<Vec<u32>, String> {
    gpu.run_words(
        func.name,
        source,
        input,
        func.in_words,
        func.out_words,
        Some(tables),
    )
}

/// The crate's output words for every point of `input`.
pub fn cpu_outputs(func: &TableFunc, input: &[u32]) -> Vec<u32> {
    let mut out = vec![0u32; input.len() / func.in_words * func.out_words];
    for (i, o) in input
        .chunks_exact(func.in_words)
        .zip(out.chunks_exact_mut(func.out_words))
    {
        (func.cpu)(i, o);
    }
    out
}

/// Index edge values: the ends of the `u32` range and of the table's blocks.
pub fn index_edges() -> Vec<u32> {
    let p = pmj02bn::POINTS as u32;
    vec![
        0,
        1,
        2,
        3,
        p - 1,
        p,
        p + 1,
        2 * p - 1,
        2 * p,
        1 << 16,
        (1 << 31) - 1,
        1 << 31,
        u32::MAX - p,
        u32::MAX - 1,
        u32::MAX,
    ]
}

/// The test points of `domain`: edge values, whole table blocks and random words (`random`
/// points of the random class; the sampler paths get a quarter of it).
pub fn table_inputs(domain: TableDomain, random: usize, seed: u64) -> Vec<u32> {
    let mut rng = crate::Rng::new(seed ^ 0x7ab1_e5ee);
    let mut v = Vec::new();
    let seeds_fixed = [0u32, 1, u32::MAX, 0x8000_0000];
    let p = pmj02bn::POINTS as u32;
    match domain {
        TableDomain::IndexSeed => {
            // Two whole blocks and a bit of the third, for fixed and random seeds.
            for s in seeds_fixed
                .into_iter()
                .chain((0..4).map(|_| rng.next_u32()))
            {
                for i in 0..2 * p + 16 {
                    v.extend([i, s]);
                }
            }
            for i in index_edges() {
                for s in seeds_fixed {
                    v.extend([i, s]);
                }
                for _ in 0..64 {
                    v.extend([i, rng.next_u32()]);
                }
            }
            for k in 0..random {
                let i = rng.next_u32() >> (k % 32);
                v.extend([i, rng.next_u32()]);
            }
        }
        TableDomain::Sampler(pattern) => {
            let pat = |r: &mut crate::Rng| {
                if pattern < 4 {
                    pattern
                } else {
                    // Unknown values: 4, 5, the top, random ones.
                    [4, 5, u32::MAX, r.next_u32() | 4][(r.next_u32() % 4) as usize]
                }
            };
            let pixels = [
                [0u32, 0],
                [1, 0],
                [0, 1],
                [63, 64],
                [65535, 65535],
                [65536, 3],
                [u32::MAX, u32::MAX],
            ];
            // Whole blocks of indices at fixed pixels, seeds and domain paths.
            for (n, px) in pixels.iter().enumerate().take(3) {
                // Domain 5 and 2 of the root are blue-noise slots, a random key is not.
                let k1 = [5, rng.next_u32(), 2][n];
                let (frame, s, k2) = (n as u32, seeds_fixed[n], 7);
                for i in 0..p + 64 {
                    v.extend([pat(&mut rng), px[0], px[1], frame, i, s, k1, k2, 4, i % 4]);
                }
            }
            // Edge values of every word.
            let sizes = [
                0u32,
                1,
                2,
                3,
                4,
                64,
                1 << 16,
                1 << 31,
                u32::MAX - 1,
                u32::MAX,
            ];
            for px in pixels {
                for index in index_edges() {
                    for size in sizes {
                        let sub = [0, 1, size.wrapping_sub(1), size, u32::MAX]
                            [(rng.next_u32() % 5) as usize];
                        let key =
                            [0, 1, 5, 6, u32::MAX, rng.next_u32()][(rng.next_u32() % 6) as usize];
                        let frame = [0, u32::MAX, rng.next_u32()][(rng.next_u32() % 3) as usize];
                        let s = seeds_fixed[(rng.next_u32() % 4) as usize];
                        v.extend([
                            pat(&mut rng),
                            px[0],
                            px[1],
                            frame,
                            index,
                            s,
                            key,
                            rng.next_u32(),
                            size,
                            sub,
                        ]);
                    }
                }
            }
            // Random words (sizes and indices small or any).
            for k in 0..random / 4 {
                let mut w: [u32; 10] = core::array::from_fn(|_| rng.next_u32());
                w[0] = pat(&mut rng);
                w[4] >>= k % 32;
                if k % 2 == 0 {
                    w[8] >>= 24 + k % 8;
                    w[9] %= w[8].max(1);
                }
                if k % 4 == 1 {
                    w[6] %= 8; // a blue-noise slot (or one past the last)
                }
                v.extend(w);
            }
        }
    }
    v
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pmj02bn part of the buffer is the bytes of `src/tables/pmj02bn_<points>_<set>.bin`,
    /// set after set, and the blue key and slot tiles end it: what docs/gpu.md tells a C or JS renderer to
    /// upload from the files.
    #[test]
    fn the_buffer_is_the_table_files() {
        let bytes = table_bytes();
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../src/tables");
        let mut at = 0;
        for set in 0..pmj02bn::SETS {
            let f = std::fs::read(format!("{root}/pmj02bn_{}_{set}.bin", pmj02bn::POINTS)).unwrap();
            assert_eq!(&bytes[at..at + f.len()], &f[..], "set {set}");
            at += f.len();
        }
        assert_eq!(at, 4 * PMJ02BN_WORDS);
        at += 4 * SOBOL_WORDS;
        for name in [
            "blue_sobol_64.bin",
            "blue_pmj02bn_64.bin",
            "blue_slots_sobol_64.bin",
            "blue_slots_pmj02bn_64.bin",
        ] {
            let f = std::fs::read(format!("{root}/{name}")).unwrap();
            assert_eq!(&bytes[at..at + f.len()], &f[..], "{name}");
            at += f.len();
        }
        assert_eq!(at, bytes.len());
    }

    /// `shaders/warpcore_tables.bin`, the buffer for renderers outside Rust, is current
    /// (`cargo run -p warpcore-gpu --bin gpu-tables` rewrites it).
    #[test]
    fn the_committed_buffer_is_current() {
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../shaders/warpcore_tables.bin"
        );
        let file = std::fs::read(path).expect("shaders/warpcore_tables.bin");
        assert!(
            file == table_bytes(),
            "shaders/warpcore_tables.bin is stale: run `cargo run -p warpcore-gpu --bin gpu-tables`"
        );
        assert_eq!(
            file.len(),
            4 * (PMJ02BN_WORDS + SOBOL_WORDS + 2 * BLUE_WORDS + 2 * SLOT_WORDS)
        );
    }

    /// The Sobol' rows against the definition, worked independently: dimension 0 is the bit
    /// reversal (van der Corput); dimension 1 (polynomial x + 1) is the Pascal matrix mod 2,
    /// whose column k holds bit j (from the top, j <= k) = C(k, j) mod 2; XOR of the rows of
    /// an index's bytes gives the reversed point.
    #[test]
    fn sobol_rows_follow_the_definition() {
        let rows = sobol_rows();
        let point = |i: u32, d: usize| {
            let r = i.reverse_bits();
            (0..4).fold(0u32, |x, b| {
                x ^ rows[4 * (256 * b + ((r >> (8 * b)) & 0xff) as usize) + d]
            })
        };
        let pascal = |i: u32| {
            (0..32).filter(|k| (i >> k) & 1 == 1).fold(0u32, |x, k| {
                // Column k: bit (31 - j) set when C(k, j) is odd, i.e. j & k == j.
                x ^ (0..=k)
                    .filter(|j| j & k == *j)
                    .fold(0u32, |c, j| c | (1 << (31 - j)))
            })
        };
        let mut x = 0x1234_5678u32;
        for _ in 0..5000 {
            x = x.wrapping_mul(0x9e37_79b9).wrapping_add(0x7f4a_7c15);
            assert_eq!(point(x, 0), x, "dimension 0 of {x:#x}");
            assert_eq!(
                point(x, 1),
                pascal(x).reverse_bits(),
                "dimension 1 of {x:#x}"
            );
        }
    }

    /// The documented prefixes: `draw::<1>()` and `draw::<3>()` are the first components of
    /// `draw::<4>()`, and `rnd::<N>()` of `rnd::<4>()`, so the WGSL file's draw4/rnd4 serve
    /// every N.
    #[test]
    fn smaller_draws_are_prefixes() {
        fn check<P: Pattern>() {
            let mut rng = crate::Rng::new(5);
            for _ in 0..2000 {
                let s = Sampler::<P>::new(
                    [rng.next_u32(), rng.next_u32()],
                    rng.next_u32(),
                    rng.next_u32(),
                    rng.next_u32(),
                );
                let d4 = s.draw::<4>();
                assert_eq!(s.draw::<1>(), [d4[0]]);
                assert_eq!(s.draw::<2>(), [d4[0], d4[1]]);
                assert_eq!(s.draw::<3>(), [d4[0], d4[1], d4[2]]);
                let r4 = s.rnd::<4>();
                assert_eq!(s.rnd::<1>(), [r4[0]]);
                assert_eq!(s.rnd::<3>(), [r4[0], r4[1], r4[2]]);
            }
        }
        check::<Pmj02bn>();
        check::<Sobol>();
        check::<Blue<Pmj02bn>>();
        check::<Blue<Sobol>>();
    }
}
