//! The lane proof: every lane and slice form of an entry equals its scalar form bit for bit,
//! and every scalar output obeys the domain rule (finite and below `f32::MAX` in magnitude:
//! never NaN, never infinite, never a saturated density), on the points and words of a
//! [`Source`]. `tests/lanes.rs` runs it over special values, uniform points and arbitrary
//! bits; the `registry` fuzz target ([`crate::checks::registry`]) over whatever libFuzzer
//! searches. Panics with the entry's name, the form and the input on the first failure.

use crate::{Entry, Indexed, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant, Visit, entries};
use std::boxed::Box;
use std::format;
use std::string::String;
use std::vec;
use std::vec::Vec;
use warpcore::{f32x8, f32x16, u32x8, u32x16};

/// A source of test values: coordinate `d` of point `k`, and word `k` (indices, seeds,
/// quadrants).
pub struct Source {
    /// What the inputs are, for failure messages.
    pub name: &'static str,
    /// Points to try (a multiple of 16; groups of 16 go through the lane forms at once).
    pub count: usize,
    /// Coordinate `d` of point `k` (lights read coordinates 5 to 16).
    pub point: Box<dyn Fn(usize, usize) -> f32>,
    /// Word `k` (indices, seeds, quadrants).
    pub word: Box<dyn Fn(usize) -> u32>,
}

/// Functions whose output is an image weight, not a point, solid angle or density: `+inf`
/// passes through them by design (documented), so that building a distribution reports the
/// texel as `Error::InfiniteWeight` instead of dropping it.
const WEIGHTS: &[&str] = &["envmap::image::luminance"];

/// The same bits (NaN payloads and signed zeros included).
pub fn bits_eq(a: &[f32], b: &[f32]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// The first 8 points as lanes.
pub fn lanes8<const N: usize>(p: &[[f32; N]]) -> [f32x8; N] {
    std::array::from_fn(|d| f32x8::new(std::array::from_fn(|j| p[j][d])))
}

/// The first 16 points as lanes.
pub fn lanes16<const N: usize>(p: &[[f32; N]]) -> [f32x16; N] {
    std::array::from_fn(|d| f32x16::new(std::array::from_fn(|j| p[j][d])))
}

/// Lane `j` of an 8-lane result.
pub fn l8<const N: usize>(v: [f32x8; N], j: usize) -> [f32; N] {
    std::array::from_fn(|d| v[d].to_array()[j])
}

/// Lane `j` of a 16-lane result.
pub fn l16<const N: usize>(v: [f32x16; N], j: usize) -> [f32; N] {
    std::array::from_fn(|d| v[d].to_array()[j])
}

/// The proof over one source, as a [`Visit`].
struct Check<'a> {
    src: &'a Source,
    /// Points checked so far.
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

/// Every entry with typed bodies over `src`; returns how many entries that was.
pub fn check_all(src: &Source) -> usize {
    entries().filter(|e| check(e, src) > 0).count()
}

/// One entry over `src`; returns how many points were checked (0 for an entry without typed
/// bodies).
pub fn check(e: &Entry, src: &Source) -> usize {
    let mut c = Check { src, checked: 0 };
    e.visit(&mut c);
    c.checked
}
