//! The sampler's outputs hashed from the Rust crate's API: what the C API
//! (`capi/tests/c/sampler.c`, run by `capi/tests/c.rs`) and the JavaScript module
//! (`js/test/sampler.test.mjs`, which runs this program) must reproduce bit for bit.
//!
//! Prints `name hash` lines (FNV-1a 64 over little-endian words, as the fingerprint). The
//! cases are the same in all three: every pattern, six roots (pixels past 2^16, every frame,
//! index and seed corner), and domain paths:
//! * `sampler_<pattern>_<what>`: the paths of domain keys `[]`, `[0]`, `[7, 0xffffffff]`
//!   (what JavaScript's `domainPath` expresses): `state` (C's `WcSampler` words), `draw`,
//!   `draw_u32` and `rnd` for 1 to 4 dimensions, `slice` (37 consecutive indices, 1 to 4
//!   dimensions);
//! * `sampler_<pattern>_split`: three paths with splits (`size` 0, `sub >= size`, wrapping
//!   child indices), the draws, `draw_u32`, `rnd` and slices above in one hash;
//!   `sampler_<pattern>_split_state` their `WcSampler` words;
//! * `sampler_<pattern>_frames`: `new_frame` roots (`spp` per root from [`FRAME_SPP`]) and
//!   three paths below them (under `Blue<P>` the root's domains 0 and 5 are spatiotemporal
//!   slots, 6 is not): the draws, `draw_u32`, `rnd` and slices in one hash
//!   (JavaScript's `samplerFramePath(spp)`).
//!
//! Run: `cargo run -p warpcore-capi --example sampler_hashes`.

use warpcore::sampler::{Blue, Pattern, Pmj02bn, Sampler, Sobol};

/// FNV-1a 64 over little-endian 32-bit words.
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Fnv(0xcbf2_9ce4_8422_2325)
    }
    fn word(&mut self, w: u32) {
        for b in w.to_le_bytes() {
            self.0 = (self.0 ^ b as u64).wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    fn words(&mut self, v: &[u32]) {
        v.iter().for_each(|&w| self.word(w));
    }
    fn floats(&mut self, v: &[f32]) {
        v.iter().for_each(|x| self.word(x.to_bits()));
    }
    fn hex(&self) -> String {
        format!("{:016x}", self.0)
    }
}

/// The roots: `[x, y, frame, index, seed]`.
const ROOTS: [[u32; 5]; 6] = [
    [0, 0, 0, 0, 0],
    [5, 7, 1, 3, 0],
    [63, 64, 2, 1023, 42],
    [65535, 1, 7, 4096, 0x9e37_79b9],
    [70000, 123_456, 0xffff_ffff, 0xffff_fff0, 0xffff_ffff],
    [0xffff_ffff, 0xffff_fffe, 12345, 65536, 1],
];

/// The domain-key paths (JavaScript's `domainPath`).
const KEY_PATHS: [&[u32]; 3] = [&[], &[0], &[7, 0xffff_ffff]];

/// Points per slice.
const SLICE: usize = 37;

/// The pattern names of the hash lines, in `WC_PATTERN_*` order.
const PATTERNS: [&str; 4] = ["pmj02bn", "sobol", "blue_pmj02bn", "blue_sobol"];

/// The three paths with splits: `root.split(3, 4, 1)`, `root.split(9, 0, 5).domain(2)`,
/// `root.domain(1).split(0xffffffff, 0xffffffff, 0xfffffffe)`.
fn split_paths<P: Pattern>(root: Sampler<P>) -> [Sampler<P>; 3] {
    [
        root.split(3, 4, 1),
        root.split(9, 0, 5).domain(2),
        root.domain(1).split(0xffff_ffff, 0xffff_ffff, 0xffff_fffe),
    ]
}

/// Samples per frame of each root's `new_frame` (0 acts as 1; 3 is not a power of two).
const FRAME_SPP: [u32; 6] = [1, 4, 1, 3, 0, 4];

/// The three paths below a `new_frame` root: `domain(0)`, `domain(5).split(3, 4, 1)`,
/// `domain(6).domain(0)`.
fn frame_paths<P: Pattern>(root: Sampler<P>) -> [Sampler<P>; 3] {
    [
        root.domain(0),
        root.domain(5).split(3, 4, 1),
        root.domain(6).domain(0),
    ]
}

fn state<P: Pattern>(h: &mut Fnv, pattern: u32, s: Sampler<P>) {
    h.word(pattern);
    h.words(&s.to_words());
}

fn draws<P: Pattern>(h: &mut Fnv, s: Sampler<P>) {
    h.floats(&s.draw::<1>());
    h.floats(&s.draw::<2>());
    h.floats(&s.draw::<3>());
    h.floats(&s.draw::<4>());
}

fn draws_u32<P: Pattern>(h: &mut Fnv, s: Sampler<P>) {
    h.words(&s.draw_u32::<1>());
    h.words(&s.draw_u32::<2>());
    h.words(&s.draw_u32::<3>());
    h.words(&s.draw_u32::<4>());
}

fn rnds<P: Pattern>(h: &mut Fnv, s: Sampler<P>) {
    h.floats(&s.rnd::<1>());
    h.floats(&s.rnd::<2>());
    h.floats(&s.rnd::<3>());
    h.floats(&s.rnd::<4>());
}

fn slices<P: Pattern>(h: &mut Fnv, s: Sampler<P>) {
    fn one<P: Pattern, const N: usize>(h: &mut Fnv, s: Sampler<P>) {
        let mut out = [[0.0f32; N]; SLICE];
        assert_eq!(s.draw_slice(&mut out), SLICE);
        out.iter().for_each(|p| h.floats(p));
    }
    one::<P, 1>(h, s);
    one::<P, 2>(h, s);
    one::<P, 3>(h, s);
    one::<P, 4>(h, s);
}

/// Everything for one pattern: `(name, hash)` lines.
fn pattern<P: Pattern>(pattern: u32, out: &mut Vec<(String, String)>) {
    let name = PATTERNS[pattern as usize];
    let roots =
        ROOTS.map(|[x, y, frame, index, seed]| Sampler::<P>::new([x, y], frame, index, seed));
    for what in ["state", "draw", "draw_u32", "rnd", "slice"] {
        let mut h = Fnv::new();
        for root in roots {
            for path in KEY_PATHS {
                let s = path.iter().fold(root, |s, &k| s.domain(k));
                match what {
                    "state" => state(&mut h, pattern, s),
                    "draw" => draws(&mut h, s),
                    "draw_u32" => draws_u32(&mut h, s),
                    "rnd" => rnds(&mut h, s),
                    _ => slices(&mut h, s),
                }
            }
        }
        out.push((format!("sampler_{name}_{what}"), h.hex()));
    }
    let (mut h, mut st) = (Fnv::new(), Fnv::new());
    for root in roots {
        for s in split_paths(root) {
            state(&mut st, pattern, s);
            draws(&mut h, s);
            draws_u32(&mut h, s);
            rnds(&mut h, s);
            slices(&mut h, s);
        }
    }
    out.push((format!("sampler_{name}_split"), h.hex()));
    out.push((format!("sampler_{name}_split_state"), st.hex()));
    let mut h = Fnv::new();
    for ([x, y, frame, index, seed], spp) in ROOTS.into_iter().zip(FRAME_SPP) {
        let root = Sampler::<P>::new_frame([x, y], frame, spp, index, seed);
        for s in frame_paths(root) {
            draws(&mut h, s);
            draws_u32(&mut h, s);
            rnds(&mut h, s);
            slices(&mut h, s);
        }
    }
    out.push((format!("sampler_{name}_frames"), h.hex()));
}

/// Every line, in a fixed order.
pub fn hashes() -> Vec<(String, String)> {
    let mut out = Vec::new();
    pattern::<Pmj02bn>(0, &mut out);
    pattern::<Sobol>(1, &mut out);
    pattern::<Blue<Pmj02bn>>(2, &mut out);
    pattern::<Blue<Sobol>>(3, &mut out);
    out
}

#[allow(dead_code)]
fn main() {
    for (name, hash) in hashes() {
        println!("{name} {hash}");
    }
}
