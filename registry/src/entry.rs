//! What one registry entry says about one public function: its forms, its typed bodies (the
//! shapes below), how it enters the golden hashes, and the names it has in C, JS and WGSL.
//! Every cross-cutting proof is a [`Visit`] over the typed bodies, so a proof is written once
//! per shape, never once per function.

use crate::fingerprint::Hasher;
use warpcore::{f32x8, f32x16, u32x8, u32x16};

/// Which lane and slice forms a function has besides its scalar form (`name_x8`,
/// `name_x16`, `name_slice`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Forms {
    pub x8: bool,
    pub x16: bool,
    pub slice: bool,
}

impl Forms {
    /// Scalar, `_x8`, `_x16` and `_slice`.
    pub const ALL: Forms = Forms::of(true, true, true);
    /// Scalar, `_x8` and `_x16`.
    pub const LANES: Forms = Forms::of(true, true, false);
    /// Scalar and `_slice`.
    pub const SLICE: Forms = Forms::of(false, false, true);
    /// The scalar form alone.
    pub const SCALAR: Forms = Forms::of(false, false, false);
    /// The forms with these flags.
    pub const fn of(x8: bool, x16: bool, slice: bool) -> Forms {
        Forms { x8, x16, slice }
    }
    /// The suffixes of the forms it has, `""` (scalar) first.
    pub fn suffixes(self) -> impl Iterator<Item = &'static str> {
        [
            ("", true),
            ("_x8", self.x8),
            ("_x16", self.x16),
            ("_slice", self.slice),
        ]
        .into_iter()
        .filter_map(|(s, has)| has.then_some(s))
    }
}

/// A slice form: inputs, outputs, the count written.
pub type SliceFn<const I: usize, const O: usize> = fn(&[[f32; I]], &mut [[f32; O]]) -> usize;

/// A light's slice form: the light, inputs, outputs, the count written.
pub type LightSliceFn<const I: usize, const O: usize> =
    fn(Light<f32>, &[[f32; I]], &mut [[f32; O]]) -> usize;

/// A map of points, `[f32; I] -> [f32; O]`, with its lane and slice forms where it has them.
/// Functions of other argument lists enter through non-capturing adapter closures.
#[derive(Clone, Copy)]
pub struct Map<const I: usize, const O: usize> {
    pub scalar: fn([f32; I]) -> [f32; O],
    pub x8: Option<fn([f32x8; I]) -> [f32x8; O]>,
    pub x16: Option<fn([f32x16; I]) -> [f32x16; O]>,
    pub slice: Option<SliceFn<I, O>>,
}

/// An index-driven sequence, `(index, seed) -> [f32; O]`; the slice form fills consecutive
/// indices from a start.
#[derive(Clone, Copy)]
pub struct Indexed<const O: usize> {
    pub scalar: fn(u32, u32) -> [f32; O],
    pub x8: fn(u32x8, u32x8) -> [f32x8; O],
    pub x16: fn(u32x16, u32x16) -> [f32x16; O],
    pub slice: fn(u32, u32, &mut [[f32; O]]) -> usize,
}

/// A map of points with a quadrant word, `([f32; 2], q) -> [f32; 2]` (the quadrant-split disk
/// maps).
#[derive(Clone, Copy)]
pub struct Quadrant {
    pub scalar: fn([f32; 2], u32) -> [f32; 2],
    pub x8: fn([f32x8; 2], u32x8) -> [f32x8; 2],
    pub x16: fn([f32x16; 2], u32x16) -> [f32x16; 2],
}

/// The inverse of a [`Quadrant`] map: `[f32; 2] -> ([f32; 2], q)`.
#[derive(Clone, Copy)]
pub struct ToQuadrant {
    pub scalar: fn([f32; 2]) -> ([f32; 2], u32),
    pub x8: fn([f32x8; 2]) -> ([f32x8; 2], u32x8),
    pub x16: fn([f32x16; 2]) -> ([f32x16; 2], u32x16),
}

/// A light and a shading point (four points: `v0, v1, v2, p` or `corner, ex, ey, p`).
pub type Light<T> = [[T; 3]; 4];

/// A warp of a light and shading point, `(light, [f32; I]) -> [f32; O]`, tried on every light
/// of `lights` (the golden set of ordinary and extreme lights).
#[derive(Clone, Copy)]
pub struct LightMap<const I: usize, const O: usize> {
    pub lights: &'static [[f32; 12]],
    pub scalar: fn(Light<f32>, [f32; I]) -> [f32; O],
    pub x8: fn(Light<f32x8>, [f32x8; I]) -> [f32x8; O],
    pub x16: fn(Light<f32x16>, [f32x16; I]) -> [f32x16; O],
    pub slice: LightSliceFn<I, O>,
}

/// A function of a light alone (its solid angle).
#[derive(Clone, Copy)]
pub struct OfLight {
    pub lights: &'static [[f32; 12]],
    pub scalar: fn(Light<f32>) -> f32,
    pub x8: fn(Light<f32x8>) -> f32x8,
    pub x16: fn(Light<f32x16>) -> f32x16,
}

/// The typed bodies of an entry: one variant per shape of signature.
#[derive(Clone, Copy)]
pub enum Kind {
    M11(Map<1, 1>),
    M21(Map<2, 1>),
    M22(Map<2, 2>),
    M23(Map<2, 3>),
    M31(Map<3, 1>),
    M32(Map<3, 2>),
    M41(Map<4, 1>),
    M51(Map<5, 1>),
    M61(Map<6, 1>),
    M63(Map<6, 3>),
    M73(Map<7, 3>),
    M74(Map<7, 4>),
    M81(Map<8, 1>),
    I2(Indexed<2>),
    I3(Indexed<3>),
    Quadrant(Quadrant),
    ToQuadrant(ToQuadrant),
    L22(LightMap<2, 2>),
    L23(LightMap<2, 3>),
    L24(LightMap<2, 4>),
    L32(LightMap<3, 2>),
    OfLight(OfLight),
    /// Not a function of points: a constructor, an accessor, a method of a built object, a
    /// function taking a closure. Its bits are proved where [`Golden`] says.
    Other,
}

/// How an entry's output bits are pinned.
#[derive(Clone, Copy)]
pub enum Golden {
    /// Part of the golden fingerprint (`tests/golden/fingerprint.txt`), hashed by its shape's
    /// piece ([`crate::fingerprint`]).
    Fingerprint,
    /// Part of the golden fingerprint, hashed by this piece (which may cover other entries:
    /// those say [`Golden::With`]).
    Piece(fn(&mut Hasher)),
    /// Hashed inside the named entry's piece (also, where it has a shape, on its own in the
    /// per-function golden file).
    With(&'static str),
    /// Added after the golden fingerprint was fixed: pinned by the per-function golden file
    /// (`tests/golden/registry.txt`) alone, hashed by its shape's piece.
    Own,
    /// As [`Golden::Own`], hashed by this piece (the one the C port computes too).
    OwnPiece(fn(&mut Hasher)),
    /// Not hashed: its bits are those of other entries (an accessor, a constructor) and the
    /// named test file proves it.
    Tests(&'static str),
}

/// The languages besides Rust.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lang {
    /// `include/warpcore.h`.
    C,
    /// `js/warpcore.mjs`.
    Js,
    /// `shaders/*.wgsl`.
    Wgsl,
}

/// One public function of the library, with its forms and bindings.
#[derive(Clone, Copy)]
pub struct Entry {
    /// Its Rust path below the crate (`disk::polar`, `envmap::Hierarchical::sample`).
    pub name: &'static str,
    /// The forms it has besides the scalar one.
    pub forms: Forms,
    /// Its typed bodies.
    pub kind: Kind,
    /// How its bits are pinned.
    pub golden: Golden,
    /// The languages that bind it under the regular name ([`Entry::regular_name`]).
    pub regular: &'static [Lang],
    /// Bindings under other names (a method of a JS object, one C function for two Rust
    /// types).
    pub names: &'static [(Lang, &'static str)],
}

impl Entry {
    /// An entry with no bindings, pinned by its shape's piece in the fingerprint.
    pub const fn new(name: &'static str, forms: Forms, kind: Kind) -> Self {
        Entry {
            name,
            forms,
            kind,
            golden: Golden::Fingerprint,
            regular: &[],
            names: &[],
        }
    }
    pub const fn golden(self, golden: Golden) -> Self {
        Entry { golden, ..self }
    }
    /// Bound under the regular name in these languages.
    pub const fn bound(self, regular: &'static [Lang]) -> Self {
        Entry { regular, ..self }
    }
    /// Bound under these other names.
    pub const fn named(self, names: &'static [(Lang, &'static str)]) -> Self {
        Entry { names, ..self }
    }

    /// Its family: the first segment of its path.
    pub fn family(&self) -> &'static str {
        self.name.split("::").next().unwrap_or(self.name)
    }

    /// The regular binding name: `wc_` and the path's segments joined by `_` in C and WGSL
    /// (`wc_disk_polar`), camel case in JS (`diskPolar`). Writes into `buf`, returns the
    /// length.
    pub fn regular_name(&self, lang: Lang, buf: &mut [u8; 96]) -> usize {
        let prefix: &[u8] = if lang == Lang::Js { b"" } else { b"wc_" };
        let (mut n, mut upper, mut last) = (0, false, 0u8);
        for &b in prefix.iter().chain(self.name.as_bytes()) {
            let out = match (lang, b) {
                (Lang::Js, b':' | b'_') => {
                    upper = n > 0;
                    continue;
                }
                (_, b':') if last == b'_' => continue,
                (_, b':') => b'_',
                _ if upper => {
                    upper = false;
                    b.to_ascii_uppercase()
                }
                _ => b,
            };
            if let Some(slot) = buf.get_mut(n) {
                *slot = out;
                n += 1;
            }
            last = out;
        }
        n
    }

    /// Every binding name in `lang`: the regular one if bound so, and the other names.
    pub fn names_in(&self, lang: Lang, mut each: impl FnMut(&str)) {
        if self.regular.contains(&lang) {
            let mut buf = [0u8; 96];
            let n = self.regular_name(lang, &mut buf);
            if let Ok(s) = core::str::from_utf8(buf.get(..n).unwrap_or(&[])) {
                each(s);
            }
        }
        for (l, name) in self.names {
            if *l == lang {
                each(name);
            }
        }
    }

    /// Calls the visitor's method for this entry's shape.
    pub fn visit<V: Visit>(&self, v: &mut V) {
        match &self.kind {
            Kind::M11(m) => v.map(self, m),
            Kind::M21(m) => v.map(self, m),
            Kind::M22(m) => v.map(self, m),
            Kind::M23(m) => v.map(self, m),
            Kind::M31(m) => v.map(self, m),
            Kind::M32(m) => v.map(self, m),
            Kind::M41(m) => v.map(self, m),
            Kind::M51(m) => v.map(self, m),
            Kind::M61(m) => v.map(self, m),
            Kind::M63(m) => v.map(self, m),
            Kind::M73(m) => v.map(self, m),
            Kind::M74(m) => v.map(self, m),
            Kind::M81(m) => v.map(self, m),
            Kind::I2(s) => v.indexed(self, s),
            Kind::I3(s) => v.indexed(self, s),
            Kind::Quadrant(q) => v.quadrant(self, q),
            Kind::ToQuadrant(q) => v.to_quadrant(self, q),
            Kind::L22(l) => v.light_map(self, l),
            Kind::L23(l) => v.light_map(self, l),
            Kind::L24(l) => v.light_map(self, l),
            Kind::L32(l) => v.light_map(self, l),
            Kind::OfLight(l) => v.of_light(self, l),
            Kind::Other => v.other(self),
        }
    }

    /// Whether its typed bodies have exactly the forms it declares.
    pub fn kind_matches_forms(&self) -> bool {
        let f = self.forms;
        let all = f == Forms::ALL;
        match &self.kind {
            Kind::M11(m) => map_forms(m) == f,
            Kind::M21(m) => map_forms(m) == f,
            Kind::M22(m) => map_forms(m) == f,
            Kind::M23(m) => map_forms(m) == f,
            Kind::M31(m) => map_forms(m) == f,
            Kind::M32(m) => map_forms(m) == f,
            Kind::M41(m) => map_forms(m) == f,
            Kind::M51(m) => map_forms(m) == f,
            Kind::M61(m) => map_forms(m) == f,
            Kind::M63(m) => map_forms(m) == f,
            Kind::M73(m) => map_forms(m) == f,
            Kind::M74(m) => map_forms(m) == f,
            Kind::M81(m) => map_forms(m) == f,
            // The quadrant maps' slice form writes four points per input (another shape).
            Kind::Quadrant(_) => f.x8 && f.x16,
            Kind::ToQuadrant(_) | Kind::OfLight(_) => f == Forms::LANES,
            Kind::Other => true,
            _ => all,
        }
    }
}

fn map_forms<const I: usize, const O: usize>(m: &Map<I, O>) -> Forms {
    Forms {
        x8: m.x8.is_some(),
        x16: m.x16.is_some(),
        slice: m.slice.is_some(),
    }
}

/// A proof over entries, one method per shape; each defaults to doing nothing.
pub trait Visit {
    fn map<const I: usize, const O: usize>(&mut self, _e: &Entry, _m: &Map<I, O>) {}
    fn indexed<const O: usize>(&mut self, _e: &Entry, _s: &Indexed<O>) {}
    fn quadrant(&mut self, _e: &Entry, _q: &Quadrant) {}
    fn to_quadrant(&mut self, _e: &Entry, _q: &ToQuadrant) {}
    fn light_map<const I: usize, const O: usize>(&mut self, _e: &Entry, _l: &LightMap<I, O>) {}
    fn of_light(&mut self, _e: &Entry, _l: &OfLight) {}
    fn other(&mut self, _e: &Entry) {}
}
