//! The functions of `shaders/warpcore.wgsl`, from the registry: every public WGSL function is
//! bound by a registry entry (`warpcore_registry::entries`, `names_in(Lang::Wgsl, ..)`), and
//! the crate reference the checker compares the GPU with is that entry's scalar body,
//! evaluated on a point's input words ([`Func::eval`]). What is WGSL-specific follows from
//! elsewhere: how to spell the call and read the result from the function's declaration in
//! the file (naga's parse of its parameters and return type), the test points from the
//! entry's shape and path ([`domain`]). The only references kept by hand are the two
//! cosine-aware lights' ([`BY_HAND`]).

use crate::spherical::Layout;
use crate::{Domain, WGSL, all_shader, call_body};
use std::sync::LazyLock;
use warpcore::spherical as sp;
use warpcore_registry::fingerprint::tri;
use warpcore_registry::{
    Entry, Indexed, Kind, Lang, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant, Visit, entries,
};

/// One public function of `shaders/warpcore.wgsl`.
pub struct Func {
    /// Its WGSL name (`wc_...`).
    pub name: String,
    /// The registry entry that binds it.
    pub entry: &'static Entry,
    pub domain: Domain,
    in_words: usize,
    /// The call on the input words `wc_in[b + k]`.
    call: String,
    /// The output words of the result `r`, and whether each is a `u32` (not `f32` bits).
    outs: Vec<(String, bool)>,
    /// A reference kept by hand ([`BY_HAND`]); `None`: the entry's scalar body.
    by_hand: Option<Reference>,
}

/// A crate reference: the output words `o` of one point's input words `i`.
pub type Reference = fn(&[u32], &mut [u32]);

/// The references kept by hand. The sphere lights take `centre, radius, p` (7 words) in WGSL,
/// their registry bodies the 12-float light `centre, [radius, 0, 0], -, p`. The cosine-aware
/// lights take the receiver normal `n` as a
/// parameter in WGSL (`light, n, u`: 17 words), while their registry bodies derive the normal
/// from the light (the golden hash has no normal input), so the registry body cannot take the
/// checker's points. These call the same crate functions with `n` from the point's words
/// (`tests/registry.rs` checks that they equal the registry bodies where `n` is the registry's
/// normal).
pub const BY_HAND: &[(&str, Reference)] = &[
    ("wc_spherical_cone", |w, o| {
        let (c, r, p, u) = sphere(w);
        let (d, pdf) = sp::cone(c, r, p, floats(u));
        put(o, &[d[0], d[1], d[2], pdf]);
    }),
    ("wc_spherical_cone_inverse", |w, o| {
        let (c, r, p, d) = sphere(w);
        put(o, &sp::cone_inverse(c, r, p, floats(d)));
    }),
    ("wc_spherical_cone_solid_angle", |w, o| {
        let (c, r, p, _) = sphere(w);
        put(o, &[sp::cone_solid_angle(c, r, p)]);
    }),
    ("wc_spherical_triangle_cosine", |w, o| {
        let (l, n, u) = (light(w), floats(&w[12..]), floats(&w[15..]));
        let (b, d) = sp::triangle_cosine(tri(l), l[3], n, u);
        put(o, &[b[0], b[1], b[2], d]);
    }),
    ("wc_spherical_rectangle_cosine", |w, o| {
        let (l, n, u) = (light(w), floats(&w[12..]), floats(&w[15..]));
        let (st, d) = sp::rectangle_cosine(l[0], l[1], l[2], l[3], n, u);
        put(o, &[st[0], st[1], d]);
    }),
];

impl Func {
    /// Input words per point.
    pub fn in_words(&self) -> usize {
        self.in_words
    }

    /// Output words per point.
    pub fn out_words(&self) -> usize {
        self.outs.len()
    }

    /// Whether output word `word` is a `u32` rather than an `f32` bit pattern.
    pub fn is_integer_output(&self, word: usize) -> bool {
        self.outs[word].1
    }

    /// The crate's output words for one point's input words.
    pub fn eval(&self, i: &[u32], o: &mut [u32]) {
        match self.by_hand {
            Some(f) => f(i, o),
            None => self.entry.visit(&mut Eval { i, o }),
        }
    }

    /// The WGSL call on the input words `wc_in[b + k]`, and the output words of its result
    /// `r`.
    pub fn wgsl(&self) -> (&str, impl Iterator<Item = &str>) {
        (&self.call, self.outs.iter().map(|(e, _)| e.as_str()))
    }
}

/// The warps (everything but the solid-angle lights), then the lights: two lists, since the
/// lights' points are lights times samples and the CPU model's bounds cover only the warps.
static FUNCTIONS: LazyLock<[Vec<Func>; 2]> = LazyLock::new(|| {
    let module = naga::front::wgsl::parse_str(WGSL).expect("warpcore.wgsl parses");
    let (mut warps, mut lights) = (Vec::new(), Vec::new());
    for e in entries() {
        e.names_in(Lang::Wgsl, |name| {
            // The registry binds the table and env-map libraries' functions too.
            let Some((_, f)) = module
                .functions
                .iter()
                .find(|(_, f)| f.name.as_deref() == Some(name))
            else {
                return;
            };
            let func = Func::new(&module, f, name, e);
            match func.domain {
                Domain::Light(_) => lights.push(func),
                _ => warps.push(func),
            }
        });
    }
    [warps, lights]
});

/// The warps of `shaders/warpcore.wgsl`, in registry order: every public function but the
/// solid-angle lights.
pub fn warps() -> &'static [Func] {
    &FUNCTIONS[0]
}

/// The solid-angle lights of `shaders/warpcore.wgsl` (`wc_spherical_*`), in registry order:
/// their points are lights times samples ([`crate::spherical::inputs`]).
pub fn lights() -> &'static [Func] {
    &FUNCTIONS[1]
}

/// Every public function of `shaders/warpcore.wgsl`: [`warps`], then [`lights`].
pub fn all_functions() -> impl Iterator<Item = &'static Func> {
    warps().iter().chain(lights())
}

impl Func {
    fn new(module: &naga::Module, f: &naga::Function, name: &str, entry: &'static Entry) -> Func {
        let mut in_words = 0;
        let args: Vec<String> = f
            .arguments
            .iter()
            .map(|a| argument(module, a.ty, &mut in_words))
            .collect();
        let mut outs = Vec::new();
        let ret = f.result.as_ref().expect("a result").ty;
        result(module, ret, String::new(), &mut outs);
        let by_hand = BY_HAND.iter().find(|(n, _)| *n == name).map(|(_, f)| *f);
        let mut shape = Arity(None);
        entry.visit(&mut shape);
        let (entry_in, entry_out) = shape.0.unwrap_or_else(|| {
            panic!(
                "{name}: its registry entry {} has no typed body",
                entry.name
            )
        });
        assert!(
            by_hand.is_some() || (entry_in, entry_out) == (in_words, outs.len()),
            "{name} takes {in_words} words and returns {}, its registry entry {} {entry_in} \
             and {entry_out}: give it a reference in BY_HAND",
            outs.len(),
            entry.name
        );
        Func {
            name: name.to_string(),
            entry,
            domain: domain(entry),
            in_words,
            call: format!("{name}({})", args.join(", ")),
            outs,
            by_hand,
        }
    }
}

/// An argument of WGSL type `ty` spelled on the input words from `*k` on (advanced past it).
fn argument(module: &naga::Module, ty: naga::Handle<naga::Type>, k: &mut usize) -> String {
    let mut word = |s: naga::Scalar| {
        *k += 1;
        match s.kind {
            naga::ScalarKind::Float => format!("bitcast<f32>(wc_in[b + {}u])", *k - 1),
            naga::ScalarKind::Uint => format!("wc_in[b + {}u]", *k - 1),
            other => panic!("argument kind {other:?}"),
        }
    };
    match module.types[ty].inner {
        naga::TypeInner::Scalar(s) => word(s),
        naga::TypeInner::Vector { size, scalar } => {
            let c: Vec<String> = (0..size as usize).map(|_| word(scalar)).collect();
            format!("vec{}<f32>({})", size as usize, c.join(", "))
        }
        ref other => panic!("argument type {other:?}"),
    }
}

/// The output words of a result of WGSL type `ty` at `path` (`r.u.x`, ...), in order.
fn result(
    module: &naga::Module,
    ty: naga::Handle<naga::Type>,
    path: String,
    out: &mut Vec<(String, bool)>,
) {
    let word = |s: naga::Scalar, path: String| match s.kind {
        naga::ScalarKind::Float => (format!("bitcast<u32>(r{path})"), false),
        naga::ScalarKind::Uint => (format!("r{path}"), true),
        other => panic!("result kind {other:?}"),
    };
    match &module.types[ty].inner {
        naga::TypeInner::Scalar(s) => out.push(word(*s, path)),
        naga::TypeInner::Vector { size, scalar } => {
            for c in ["x", "y", "z", "w"].iter().take(*size as usize) {
                out.push(word(*scalar, format!("{path}.{c}")));
            }
        }
        naga::TypeInner::Struct { members, .. } => {
            for m in members {
                let name = m.name.as_deref().expect("a member name");
                result(module, m.ty, format!("{path}.{name}"), out);
            }
        }
        other => panic!("result type {other:?}"),
    }
}

/// The test points of an entry's WGSL function, from its shape and path: maps of the square
/// take its points (the quadrant maps with a quadrant word), their inverses directions, or
/// barycentrics for the triangle's, or points of the plane for the disk's (which return the
/// quadrant too where they are quadrant-split); the densities take densities (and a
/// direction); the sequences (index, seed) pairs; the lights a light and what the function
/// takes after it. The one exception: the wrap of the equal-area square takes points far
/// beyond the square.
pub fn domain(e: &Entry) -> Domain {
    let inverse = e.name.ends_with("_inverse");
    let light = |triangle, rectangle| {
        Domain::Light(if e.name.contains("rectangle") {
            rectangle
        } else {
            triangle
        })
    };
    match e.kind {
        Kind::OfLight(_) if e.name.contains("cone") => Domain::Light(Layout::Sphere),
        Kind::L24(_) if e.name.contains("cone") => Domain::Light(Layout::SphereU),
        Kind::L32(_) if e.name.contains("cone") => Domain::Light(Layout::SphereDir),
        Kind::M22(_) if e.name == "sphere::equal_area_wrap" => Domain::Extended,
        Kind::M22(_) if inverse => Domain::Plane,
        Kind::M22(_) | Kind::M23(_) => Domain::Square,
        Kind::M32(_) if e.family() == "triangle" => Domain::Barycentric,
        Kind::M32(_) => Domain::Direction,
        Kind::M11(_) => Domain::Density,
        Kind::M41(_) => Domain::DensityDirection,
        Kind::M51(_) => Domain::Microfacet(5),
        Kind::M73(_) | Kind::M74(_) => Domain::Microfacet(7),
        Kind::M81(_) => Domain::Microfacet(8),
        Kind::Quadrant(_) => Domain::SquareQuadrant,
        Kind::ToQuadrant(_) => Domain::Plane,
        Kind::I3(_) => Domain::IndexSeed,
        Kind::OfLight(_) => light(Layout::Triangle, Layout::Rectangle),
        Kind::L32(_) => Domain::Light(Layout::TriangleB),
        Kind::L22(_) => Domain::Light(Layout::RectangleSt),
        Kind::L23(_) | Kind::L24(_) if e.name.ends_with("_cosine") => {
            light(Layout::TriangleNU, Layout::RectangleNU)
        }
        Kind::L23(_) | Kind::L24(_) => light(Layout::TriangleU, Layout::RectangleU),
        _ => panic!("{}: no test points for its shape", e.name),
    }
}

/// `N` floats from words.
pub fn floats<const N: usize>(w: &[u32]) -> [f32; N] {
    std::array::from_fn(|k| f32::from_bits(w[k]))
}

/// A sphere light `centre, radius, p` from its 7 words (and the words after them).
fn sphere(w: &[u32]) -> ([f32; 3], f32, [f32; 3], &[u32]) {
    (floats(w), f32::from_bits(w[3]), floats(&w[4..]), &w[7..])
}

/// A light (4 points of 3 floats) from its 12 words.
pub fn light(w: &[u32]) -> Light<f32> {
    std::array::from_fn(|k| floats(&w[3 * k..]))
}

fn put(o: &mut [u32], v: &[f32]) {
    for (o, v) in o.iter_mut().zip(v) {
        *o = v.to_bits();
    }
}

/// An entry's words per point, `(in, out)`, by its shape (`None` for [`Kind::Other`]).
pub struct Arity(pub Option<(usize, usize)>);

impl Visit for Arity {
    fn map<const I: usize, const O: usize>(&mut self, _: &Entry, _: &Map<I, O>) {
        self.0 = Some((I, O));
    }
    fn indexed<const O: usize>(&mut self, _: &Entry, _: &Indexed<O>) {
        self.0 = Some((2, O));
    }
    fn quadrant(&mut self, _: &Entry, _: &Quadrant) {
        self.0 = Some((3, 2));
    }
    fn to_quadrant(&mut self, _: &Entry, _: &ToQuadrant) {
        self.0 = Some((2, 3));
    }
    fn light_map<const I: usize, const O: usize>(&mut self, _: &Entry, _: &LightMap<I, O>) {
        self.0 = Some((12 + I, O));
    }
    fn of_light(&mut self, _: &Entry, _: &OfLight) {
        self.0 = Some((12, 1));
    }
}

/// An entry's scalar body on one point's input words `i` (as many as its [`Arity`]), writing
/// the output words `o`.
pub struct Eval<'a> {
    pub i: &'a [u32],
    pub o: &'a mut [u32],
}

impl Visit for Eval<'_> {
    fn map<const I: usize, const O: usize>(&mut self, _: &Entry, m: &Map<I, O>) {
        put(self.o, &(m.scalar)(floats(self.i)));
    }
    fn indexed<const O: usize>(&mut self, _: &Entry, s: &Indexed<O>) {
        put(self.o, &(s.scalar)(self.i[0], self.i[1]));
    }
    fn quadrant(&mut self, _: &Entry, q: &Quadrant) {
        put(self.o, &(q.scalar)(floats(self.i), self.i[2]));
    }
    fn to_quadrant(&mut self, _: &Entry, q: &ToQuadrant) {
        let (u, quadrant) = (q.scalar)(floats(self.i));
        put(self.o, &u);
        self.o[2] = quadrant;
    }
    fn light_map<const I: usize, const O: usize>(&mut self, _: &Entry, l: &LightMap<I, O>) {
        put(self.o, &(l.scalar)(light(self.i), floats(&self.i[12..])));
    }
    fn of_light(&mut self, _: &Entry, l: &OfLight) {
        put(self.o, &[(l.scalar)(light(self.i))]);
    }
}

/// One compute shader that calls every public function ([`crate::all_shader`]), each point's
/// outputs after the previous function's.
pub fn all_functions_shader() -> String {
    let mut base = 0usize;
    let bodies = all_functions().map(|func| {
        let (call, outs) = func.wgsl();
        let n = func.out_words();
        let body = format!(
            "    let b = i * {}u;\n    let o = i * {}u + {base}u;\n{}",
            func.in_words(),
            base + n,
            call_body(call, outs)
        );
        base += n;
        body
    });
    all_shader(WGSL, [0, 1], bodies.collect::<Vec<_>>())
}
