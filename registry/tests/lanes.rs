//! Every lane and slice form equals the scalar form, bit for bit, for every function of the
//! registry with typed bodies: `_x8` and `_x16` lane by lane (on targets without 16-lane
//! vectors `wide` emulates `f32x16` as two halves, on AVX-512 it uses other instructions:
//! both must give the scalar bits), `_slice` element by element over lengths that leave
//! padded tails. Inputs: a cross product of special values (signed zeros, NaN with payloads,
//! infinities, subnormals, values past the ends), uniform points, and arbitrary bit
//! patterns; lights: the golden set and lights of arbitrary bits. On the same inputs, every
//! scalar output obeys the domain rule: finite and below `f32::MAX` in magnitude (never NaN,
//! never infinite, never a saturated density).
use warpcore::{f32x8, f32x16, u32x8, u32x16};
use warpcore_registry::{
    Entry, Indexed, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant, Visit, entries,
};
use warpcore_testkit::{rng, specials};

/// A source of test values: coordinate `d` of point `k`, and word `k` (indices, seeds,
/// quadrants).
struct Source {
    name: &'static str,
    count: usize,
    point: Box<dyn Fn(usize, usize) -> f32>,
    word: Box<dyn Fn(usize) -> u32>,
}

/// Functions whose output is an image weight, not a point, solid angle or density: `+inf`
/// passes through them by design (documented), so that building a distribution reports the
/// texel as `Error::InfiniteWeight` instead of dropping it.
const WEIGHTS: &[&str] = &["envmap::image::luminance"];

fn bits_eq(a: &[f32], b: &[f32]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

fn lanes8<const N: usize>(p: &[[f32; N]]) -> [f32x8; N] {
    std::array::from_fn(|d| f32x8::new(std::array::from_fn(|j| p[j][d])))
}

fn lanes16<const N: usize>(p: &[[f32; N]]) -> [f32x16; N] {
    std::array::from_fn(|d| f32x16::new(std::array::from_fn(|j| p[j][d])))
}

fn l8<const N: usize>(v: [f32x8; N], j: usize) -> [f32; N] {
    std::array::from_fn(|d| v[d].to_array()[j])
}

fn l16<const N: usize>(v: [f32x16; N], j: usize) -> [f32; N] {
    std::array::from_fn(|d| v[d].to_array()[j])
}

struct Check<'a> {
    src: &'a Source,
    checked: usize,
}

impl Check<'_> {
    fn points<const I: usize>(&self, g: usize) -> [[f32; I]; 16] {
        std::array::from_fn(|j| std::array::from_fn(|d| (self.src.point)(16 * g + j, d)))
    }
    fn words(&self, g: usize, salt: usize) -> [u32; 16] {
        std::array::from_fn(|j| (self.src.word)(16 * g + j + salt))
    }
    fn groups(&self) -> usize {
        self.src.count / 16
    }
    /// The 16 lights of group `g`: the entry's set, and every third group lights of the
    /// source's values.
    fn lights(&self, set: &[[f32; 12]], g: usize) -> [Light<f32>; 16] {
        std::array::from_fn(|j| {
            let l: [f32; 12] = if g % 3 == 2 {
                std::array::from_fn(|c| (self.src.point)(16 * g + j, c + 5))
            } else {
                set[(g + j) % set.len()]
            };
            std::array::from_fn(|k| std::array::from_fn(|c| l[3 * k + c]))
        })
    }
    /// The domain rule on the scalar outputs: every value finite and below `f32::MAX` in
    /// magnitude (no NaN, no infinity, no saturated density). [`WEIGHTS`] are only never NaN
    /// and never negative.
    fn total(&self, e: &Entry, input: &dyn std::fmt::Debug, out: &[f32]) {
        let ok = if WEIGHTS.contains(&e.name) {
            out.iter().all(|x| *x >= 0.0)
        } else {
            out.iter().all(|x| x.abs() < f32::MAX)
        };
        if !ok {
            panic!(
                "{} returns {out:?} for {input:?} ({} inputs): not finite, or saturated at f32::MAX",
                e.name, self.src.name
            );
        }
    }
    fn fail(&self, e: &Entry, form: &str, what: String) -> ! {
        panic!(
            "{} {form} differs from the scalar form on {} inputs: {what}",
            e.name, self.src.name
        )
    }
}

fn light8(ls: &[Light<f32>]) -> Light<f32x8> {
    std::array::from_fn(|k| {
        std::array::from_fn(|c| f32x8::new(std::array::from_fn(|j| ls[j][k][c])))
    })
}

fn light16(ls: &[Light<f32>]) -> Light<f32x16> {
    std::array::from_fn(|k| {
        std::array::from_fn(|c| f32x16::new(std::array::from_fn(|j| ls[j][k][c])))
    })
}

impl Visit for Check<'_> {
    fn map<const I: usize, const O: usize>(&mut self, e: &Entry, m: &Map<I, O>) {
        for g in 0..self.groups() {
            let p: [[f32; I]; 16] = self.points(g);
            let want: Vec<[f32; O]> = p.iter().map(|u| (m.scalar)(*u)).collect();
            for (u, w) in p.iter().zip(&want) {
                self.total(e, u, w);
            }
            if let Some(x8) = m.x8 {
                for half in 0..2 {
                    let v = x8(lanes8(&p[8 * half..]));
                    for j in 0..8 {
                        let got = l8(v, j);
                        if !bits_eq(&got, &want[8 * half + j]) {
                            self.fail(e, "_x8", format!("{:?} -> {got:?}", p[8 * half + j]));
                        }
                    }
                }
            }
            if let Some(x16) = m.x16 {
                let v = x16(lanes16(&p));
                for (j, w) in want.iter().enumerate() {
                    let got = l16(v, j);
                    if !bits_eq(&got, w) {
                        self.fail(e, "_x16", format!("{:?} -> {got:?}", p[j]));
                    }
                }
            }
            if let Some(slice) = m.slice {
                let n = 16 - g % 4;
                let mut out = vec![[f32::NAN; O]; n];
                assert_eq!(slice(&p[..n], &mut out), n, "{} _slice count", e.name);
                for (j, got) in out.iter().enumerate() {
                    if !bits_eq(got, &want[j]) {
                        self.fail(e, "_slice", format!("{:?} -> {got:?}", p[j]));
                    }
                }
            }
            self.checked += 16;
        }
    }

    fn indexed<const O: usize>(&mut self, e: &Entry, s: &Indexed<O>) {
        for g in 0..self.groups() {
            let (i, seed) = (self.words(g, 0), self.words(g, 7));
            let want: Vec<[f32; O]> = (0..16).map(|j| (s.scalar)(i[j], seed[j])).collect();
            for (j, w) in want.iter().enumerate() {
                self.total(e, &(i[j], seed[j]), w);
            }
            for half in 0..2 {
                let at = |a: [u32; 16]| u32x8::new(std::array::from_fn(|j| a[8 * half + j]));
                let v = (s.x8)(at(i), at(seed));
                for j in 0..8 {
                    if !bits_eq(&l8(v, j), &want[8 * half + j]) {
                        self.fail(e, "_x8", format!("index {} seed {}", i[j], seed[j]));
                    }
                }
            }
            let v = (s.x16)(u32x16::new(i), u32x16::new(seed));
            for (j, w) in want.iter().enumerate() {
                if !bits_eq(&l16(v, j), w) {
                    self.fail(e, "_x16", format!("index {} seed {}", i[j], seed[j]));
                }
            }
            let mut out = vec![[0.0f32; O]; 13];
            assert_eq!((s.slice)(i[0], seed[0], &mut out), 13);
            for (k, got) in out.iter().enumerate() {
                let want = (s.scalar)(i[0].wrapping_add(k as u32), seed[0]);
                if !bits_eq(got, &want) {
                    self.fail(
                        e,
                        "_slice",
                        format!("start {} + {k} seed {}", i[0], seed[0]),
                    );
                }
            }
            self.checked += 16;
        }
    }

    fn quadrant(&mut self, e: &Entry, m: &Quadrant) {
        for g in 0..self.groups() {
            let p: [[f32; 2]; 16] = self.points(g);
            let q = self.words(g, 3);
            let v8: Vec<[f32; 2]> = (0..2)
                .flat_map(|h| {
                    let v = (m.x8)(
                        lanes8(&p[8 * h..]),
                        u32x8::new(std::array::from_fn(|j| q[8 * h + j])),
                    );
                    (0..8).map(move |j| l8(v, j))
                })
                .collect();
            let v16 = (m.x16)(lanes16(&p), u32x16::new(q));
            for j in 0..16 {
                let want = (m.scalar)(p[j], q[j]);
                self.total(e, &(p[j], q[j]), &want);
                if !bits_eq(&v8[j], &want) || !bits_eq(&l16(v16, j), &want) {
                    self.fail(e, "_x8/_x16", format!("{:?} quadrant {}", p[j], q[j]));
                }
            }
            self.checked += 16;
        }
    }

    fn to_quadrant(&mut self, e: &Entry, m: &ToQuadrant) {
        for g in 0..self.groups() {
            let p: [[f32; 2]; 16] = self.points(g);
            let (u16, q16) = (m.x16)(lanes16(&p));
            for h in 0..2 {
                let (u8, q8) = (m.x8)(lanes8(&p[8 * h..]));
                for j in 0..8 {
                    let (want, wq) = (m.scalar)(p[8 * h + j]);
                    self.total(e, &p[8 * h + j], &want);
                    if !bits_eq(&l8(u8, j), &want) || q8.to_array()[j] != wq {
                        self.fail(e, "_x8", format!("{:?}", p[8 * h + j]));
                    }
                    let k = 8 * h + j;
                    if !bits_eq(&l16(u16, k), &want) || q16.to_array()[k] != wq {
                        self.fail(e, "_x16", format!("{:?}", p[k]));
                    }
                }
            }
            self.checked += 16;
        }
    }

    fn light_map<const I: usize, const O: usize>(&mut self, e: &Entry, m: &LightMap<I, O>) {
        for g in 0..self.groups() {
            let ls = self.lights(m.lights, g);
            let p: [[f32; I]; 16] = self.points(g);
            let want: Vec<[f32; O]> = (0..16).map(|j| (m.scalar)(ls[j], p[j])).collect();
            for j in 0..16 {
                self.total(e, &(ls[j], p[j]), &want[j]);
            }
            for h in 0..2 {
                let v = (m.x8)(light8(&ls[8 * h..8 * h + 8]), lanes8(&p[8 * h..]));
                for j in 0..8 {
                    if !bits_eq(&l8(v, j), &want[8 * h + j]) {
                        self.fail(e, "_x8", format!("{:?} {:?}", ls[8 * h + j], p[8 * h + j]));
                    }
                }
            }
            let v = (m.x16)(light16(&ls), lanes16(&p));
            for (j, w) in want.iter().enumerate() {
                if !bits_eq(&l16(v, j), w) {
                    self.fail(e, "_x16", format!("{:?} {:?}", ls[j], p[j]));
                }
            }
            let mut out = vec![[f32::NAN; O]; 13];
            assert_eq!((m.slice)(ls[0], &p[..13], &mut out), 13);
            for (j, got) in out.iter().enumerate() {
                if !bits_eq(got, &(m.scalar)(ls[0], p[j])) {
                    self.fail(e, "_slice", format!("{:?} {:?}", ls[0], p[j]));
                }
            }
            self.checked += 16;
        }
    }

    fn of_light(&mut self, e: &Entry, m: &OfLight) {
        for g in 0..self.groups() {
            let ls = self.lights(m.lights, g);
            let v16 = (m.x16)(light16(&ls)).to_array();
            for h in 0..2 {
                let v8 = (m.x8)(light8(&ls[8 * h..8 * h + 8])).to_array();
                for j in 0..8 {
                    let want = (m.scalar)(ls[8 * h + j]);
                    self.total(e, &ls[8 * h + j], &[want]);
                    if !bits_eq(&[v8[j], v16[8 * h + j]], &[want, want]) {
                        self.fail(e, "_x8/_x16", format!("{:?}", ls[8 * h + j]));
                    }
                }
            }
            self.checked += 16;
        }
    }
}

fn check_all(src: &Source) {
    let mut typed = 0;
    for e in entries() {
        let mut c = Check { src, checked: 0 };
        e.visit(&mut c);
        typed += usize::from(c.checked > 0);
    }
    assert!(typed >= 40, "only {typed} entries have typed bodies");
}

/// Every pair of special values in every pair of coordinates (the rest cycling), words from
/// the edges of the index ranges.
#[test]
fn lane_forms_agree_on_special_values() {
    let sp = specials();
    let s = sp.len();
    let edges = [
        0u32,
        1,
        3,
        4,
        255,
        256,
        4095,
        4096,
        0x5555_5555,
        0xaaaa_aaaa,
        0x8000_0000,
        u32::MAX - 1,
        u32::MAX,
        65535,
        65536,
        7,
    ];
    check_all(&Source {
        name: "special",
        count: s * s * 2,
        point: Box::new(move |k, d| sp[(k / s.pow((d % 2) as u32) + d / 2) % s]),
        word: Box::new(move |k| edges[k % 16].rotate_left((k / 16) as u32)),
    });
}

/// Uniform points of `[0, 1)` and signed directions, random words.
#[test]
fn lane_forms_agree_on_uniform_points() {
    let n = 4096;
    let mut r = rng(16);
    let vals: Vec<f32> = (0..n * 17)
        .map(|_| warpcore_testkit::unit(&mut r))
        .collect();
    let words: Vec<u32> = (0..n + 64).map(|_| rand::RngExt::random(&mut r)).collect();
    check_all(&Source {
        name: "uniform",
        count: n,
        point: Box::new(move |k, d| {
            if d >= 2 {
                2.0 * vals[17 * k + d] - 1.0
            } else {
                vals[17 * k + d]
            }
        }),
        word: Box::new(move |k| words[k % words.len()]),
    });
}

/// Arbitrary bit patterns: every NaN payload, subnormal and out-of-range value.
#[test]
fn lane_forms_agree_on_any_bits() {
    let n = 4096;
    let mut r = rng(17);
    let words: Vec<u32> = (0..n * 17 + 64)
        .map(|_| rand::RngExt::random(&mut r))
        .collect();
    let w = words.clone();
    check_all(&Source {
        name: "arbitrary-bit",
        count: n,
        point: Box::new(move |k, d| f32::from_bits(w[17 * k + d])),
        word: Box::new(move |k| words[k % words.len()]),
    });
}

/// The check can fail: an entry whose `_x16` form is another map's is caught.
#[test]
#[should_panic(expected = "disk::polar _x16 differs")]
fn a_wrong_lane_form_is_caught() {
    use warpcore::disk;
    use warpcore_registry::{Forms, Kind};
    let wrong = Entry::new(
        "disk::polar",
        Forms::ALL,
        Kind::M22(Map {
            scalar: disk::polar,
            x8: Some(disk::polar_x8),
            x16: Some(disk::concentric_x16),
            slice: Some(disk::polar_slice),
        }),
    );
    let mut r = rng(3);
    let vals: Vec<f32> = (0..64).map(|_| warpcore_testkit::unit(&mut r)).collect();
    let src = Source {
        name: "uniform",
        count: 32,
        point: Box::new(move |k, d| vals[2 * k + d]),
        word: Box::new(|k| k as u32),
    };
    wrong.visit(&mut Check {
        src: &src,
        checked: 0,
    });
}

/// The two lane forms whose entries have no typed body (a stratum count beside the index, an
/// integer output): `sequence::stratified_x16` over edge counts and `pmj02bn::shuffle_x16`.
#[test]
fn stratified_and_shuffle_lanes_agree() {
    use warpcore::{pmj02bn, sequence};
    let mut r = rng(18);
    for _ in 0..256 {
        let i: [u32; 16] = std::array::from_fn(|_| rand::RngExt::random(&mut r));
        let s: [u32; 16] = std::array::from_fn(|_| rand::RngExt::random(&mut r));
        for count in [0u32, 1, 16, 17, 1024, u32::MAX] {
            let v = sequence::stratified_x16(u32x16::new(i), count, u32x16::new(s));
            for j in 0..16 {
                let want = sequence::stratified(i[j], count, s[j]);
                assert!(bits_eq(&l16(v, j), &want), "stratified {count}");
            }
        }
        let sh = pmj02bn::shuffle_x16(u32x16::new(i), u32x16::new(s)).to_array();
        for j in 0..16 {
            assert_eq!(sh[j], pmj02bn::shuffle(i[j], s[j]), "shuffle");
        }
    }
}
