//! The path scenes: closed boxes of analytic quads (and one disk), diffuse walls, one glossy
//! block, one-sided area lights.
//!
//! * `cornell`: the unit box `[0,1] x [0,1] x [-1,1]` (red left wall, green right wall, white
//!   floor, ceiling, back and front walls), a short white block and a tall glossy block
//!   (modified-Phong lobe, exponent 40), a 0.25 x 0.25 square light under the ceiling.
//! * `cornell-disk`: the same box, the square light at half power and a bluish disk light
//!   (radius 0.1) on the right wall facing into the box.
//! * `burley-direct`, `burley-gi`, `burley-checker`: Burley 2020's three configurations (the
//!   path study, [`Scene::by_name`]); any scene takes `/`-separated variants.
//! * `glossy-a0.05`, `glossy-a0.3`, `glossy-a0.8` (any `glossy-a<alpha>`): the `cornell` box with
//!   the floor and both blocks a tinted GGX reflector of roughness `alpha` (warpcore's
//!   `microfacet`), each with a variant naming the BSDF sampler: `cosine`, `caps` (the default)
//!   or `bounded` ([`GgxSampler`]).
//! * `furnace` (tests only): the empty box, every wall a diffuse emitter of radiance 1 and
//!   albedo `rho`: a path of at most `K` scattering events sees `sum_{k=0..K} rho^k`.

pub type V = [f64; 3];

pub fn add(a: V, b: V) -> V {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}
pub fn sub(a: V, b: V) -> V {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
pub fn mul(a: V, s: f64) -> V {
    [a[0] * s, a[1] * s, a[2] * s]
}
pub fn had(a: V, b: V) -> V {
    [a[0] * b[0], a[1] * b[1], a[2] * b[2]]
}
pub fn dot(a: V, b: V) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
pub fn cross(a: V, b: V) -> V {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
pub fn norm(a: V) -> V {
    mul(a, 1.0 / dot(a, a).sqrt())
}
pub fn luminance(c: V) -> f64 {
    0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]
}

/// A surface: diffuse albedo, or a glossy lobe (`gloss = Some(exponent)`, `albedo` its
/// specular reflectance), and a one-sided emission along the shape's normal. `checker =
/// Some(f)`: a checkerboard of `f` checks per unit length in the plane of the surface, the
/// dark checks reflecting a tenth of `albedo` (Burley 2020's case (c)).
#[derive(Clone, Copy, Debug)]
pub struct Material {
    pub albedo: V,
    pub emission: V,
    pub gloss: Option<f64>,
    pub checker: Option<f64>,
    /// A GGX reflector instead (Fresnel-free: `albedo D G2 / (4 |wo.z| |wi.z|)`), and how
    /// its directions are sampled.
    pub ggx: Option<Ggx>,
}

/// The BSDF sampler of a GGX surface (the densities of MIS are the matching `_pdf`
/// functions).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GgxSampler {
    /// `warpcore::sphere::cosine_hemisphere`, density `cos / pi` (the baseline).
    Cosine,
    /// `warpcore::microfacet::ggx_reflect` (visible normals by spherical caps: Heitz 2018's
    /// distribution).
    Caps,
    /// `warpcore::microfacet::ggx_reflect_bounded` (Eto and Tokuyoshi 2023).
    Bounded,
}

impl GgxSampler {
    pub const ALL: [GgxSampler; 3] = [GgxSampler::Cosine, GgxSampler::Caps, GgxSampler::Bounded];

    /// The scene variant naming it.
    pub fn name(self) -> &'static str {
        match self {
            GgxSampler::Cosine => "cosine",
            GgxSampler::Caps => "caps",
            GgxSampler::Bounded => "bounded",
        }
    }
}

/// A GGX surface: isotropic roughness `alpha` (`= r^2`) and its sampler.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ggx {
    pub alpha: f32,
    pub sampler: GgxSampler,
}

impl Material {
    /// The material at the point `x` of a surface with normal `n` (the checkerboard's albedo
    /// there; itself without a checkerboard).
    pub fn at(&self, x: V, n: V) -> Material {
        let Some(f) = self.checker else {
            return *self;
        };
        // The two coordinates across the surface: the axes other than the normal's largest.
        let a = (0..3)
            .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
            .unwrap_or(2);
        let parity: i64 = (0..3)
            .filter(|&i| i != a)
            .map(|i| (x[i] * f).floor() as i64)
            .sum();
        let mut m = *self;
        if parity.rem_euclid(2) == 1 {
            m.albedo = mul(m.albedo, 0.1);
        }
        m
    }
}

/// How a path is ended early (Russian roulette from the third vertex on; the continuation
/// probability `q` from the throughput `beta`, which is divided by `q` on survival).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Roulette {
    /// `q = min(0.95, max beta)`, decided by an unstratified number ([`PathSampler::rnd`]):
    /// the tracer's first form (`rr-rnd`).
    ///
    /// [`PathSampler::rnd`]: super::samplers::PathSampler::rnd
    Rnd,
    /// The same `q`, decided by a stratified sampler dimension (`rr-sampler`).
    Sampler,
    /// pbrt-v4's and Cycles' form: `q = min(1, max beta)` (no roulette while the throughput
    /// is at least 1), decided by a stratified sampler dimension (`rr-production`).
    Production,
    /// No roulette: every path runs to `max_bounces` (`rr-off`).
    Off,
}

#[derive(Clone, Copy, Debug)]
pub enum Shape {
    /// The parallelogram `p + a e1 + b e2`, `a, b` in `[0, 1]`; `n` the unit normal, `w` =
    /// `(e1 x e2) / |e1 x e2|^2` (for the coordinates of a hit).
    Quad {
        p: V,
        e1: V,
        e2: V,
        n: V,
        w: V,
        area: f64,
    },
    /// A disk of radius `r` around `c` in the plane of `t1`, `t2` (unit normal `n`).
    Disk { c: V, n: V, t1: V, t2: V, r: f64 },
}

impl Shape {
    /// The quad `p + a e1 + b e2` with its normal turned towards `toward`.
    pub fn quad(p: V, e1: V, e2: V, toward: V) -> Shape {
        let (e1, e2) = if dot(cross(e1, e2), sub(toward, p)) < 0.0 {
            (e2, e1)
        } else {
            (e1, e2)
        };
        let nn = cross(e1, e2);
        let l2 = dot(nn, nn);
        Shape::Quad {
            p,
            e1,
            e2,
            n: mul(nn, 1.0 / l2.sqrt()),
            w: mul(nn, 1.0 / l2),
            area: l2.sqrt(),
        }
    }

    pub fn disk(c: V, n: V, r: f64) -> Shape {
        let n = norm(n);
        let (t1, t2) = basis(n);
        Shape::Disk { c, n, t1, t2, r }
    }

    pub fn area(&self) -> f64 {
        match *self {
            Shape::Quad { area, .. } => area,
            Shape::Disk { r, .. } => std::f64::consts::PI * r * r,
        }
    }

    pub fn normal(&self) -> V {
        match *self {
            Shape::Quad { n, .. } | Shape::Disk { n, .. } => n,
        }
    }

    /// Distance along `d` (unit) from `o` to the shape, if in `(tmin, tmax)`.
    #[inline]
    pub fn hit(&self, o: V, d: V, tmin: f64, tmax: f64) -> Option<f64> {
        let (n, p) = match *self {
            Shape::Quad { n, p, .. } => (n, p),
            Shape::Disk { n, c, .. } => (n, c),
        };
        let den = dot(n, d);
        if den.abs() < 1e-12 {
            return None;
        }
        let t = dot(n, sub(p, o)) / den;
        if !(t > tmin && t < tmax) {
            return None;
        }
        let q = sub(add(o, mul(d, t)), p);
        match *self {
            Shape::Quad { e1, e2, w, .. } => {
                let a = dot(w, cross(q, e2));
                let b = dot(w, cross(e1, q));
                ((0.0..=1.0).contains(&a) && (0.0..=1.0).contains(&b)).then_some(t)
            }
            Shape::Disk { r, .. } => (dot(q, q) <= r * r).then_some(t),
        }
    }

    /// A point for `u` in the unit square, uniform in area: the quad's bilinear map, the
    /// disk through warpcore's concentric map.
    pub fn point(&self, u: [f32; 2]) -> V {
        match *self {
            Shape::Quad { p, e1, e2, .. } => {
                add(p, add(mul(e1, u[0] as f64), mul(e2, u[1] as f64)))
            }
            Shape::Disk { c, t1, t2, r, .. } => {
                let [x, y] = warpcore::disk::concentric(u);
                add(c, add(mul(t1, r * x as f64), mul(t2, r * y as f64)))
            }
        }
    }
}

/// An orthonormal pair completing the unit `n` (Duff et al. 2017, "Building an
/// orthonormal basis, revisited").
pub fn basis(n: V) -> (V, V) {
    let s = if n[2] >= 0.0 { 1.0 } else { -1.0 };
    let a = -1.0 / (s + n[2]);
    let b = n[0] * n[1] * a;
    (
        [1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]],
        [b, s + n[1] * n[1] * a, -n[1]],
    )
}

#[derive(Clone, Copy, Debug)]
pub struct Object {
    pub shape: Shape,
    pub material: Material,
    /// Index into [`Scene::lights`] when the object emits.
    pub light: Option<usize>,
}

/// A pinhole-or-thin-lens camera looking down `+z`.
#[derive(Clone, Copy, Debug)]
pub struct Camera {
    pub eye: V,
    /// `tan(fov / 2)`.
    pub tan_half: f64,
    pub aperture: f64,
    pub focus: f64,
    /// The part of the frame the image shows: `[x0, y0, side]` as fractions of the frame
    /// (`y` down); `[0, 0, 1]` the whole frame.
    pub crop: [f64; 3],
    /// Every sample at the pixel's centre (no pixel filter: a diagnostic variant).
    pub centre: bool,
}

#[derive(Clone, Debug)]
pub struct Scene {
    pub name: String,
    pub objects: Vec<Object>,
    /// Emitting objects, and the cumulative probabilities of choosing each (by power).
    pub lights: Vec<usize>,
    pub light_cdf: Vec<f64>,
    pub camera: Camera,
    pub max_bounces: usize,
    /// The roulette's form.
    pub roulette: Roulette,
    /// Diagnostic only (biased): each contribution of a path with two or more scattering
    /// events is clamped to this maximum channel value (Cycles' "clamp indirect").
    pub clamp: Option<f64>,
    pub width: usize,
    pub height: usize,
    /// Groups of objects behind a bounding box (the blocks): `(lo, hi, first..end)`.
    pub groups: Vec<(V, V, std::ops::Range<usize>)>,
    /// The objects outside every group (tested on every ray).
    pub loose: Vec<usize>,
}

/// Whether the ray `o + t d`, `t` in `(tmin, tmax)`, meets the box `[lo, hi]` (slabs).
#[inline]
fn meets_box(o: V, d: V, lo: V, hi: V, tmin: f64, tmax: f64) -> bool {
    let (mut t0, mut t1) = (tmin, tmax);
    for a in 0..3 {
        let inv = 1.0 / d[a];
        let (mut n, mut f) = ((lo[a] - o[a]) * inv, (hi[a] - o[a]) * inv);
        if n > f {
            std::mem::swap(&mut n, &mut f);
        }
        // NaN (0 * inf on a slab's plane) keeps the interval: conservative.
        if n > t0 {
            t0 = n;
        }
        if f < t1 {
            t1 = f;
        }
        if t0 > t1 {
            return false;
        }
    }
    true
}

const WHITE: V = [0.725, 0.71, 0.68];
const RED: V = [0.63, 0.065, 0.05];
const GREEN: V = [0.14, 0.45, 0.09];
const BLACK: V = [0.0; 3];

fn diffuse(albedo: V) -> Material {
    Material {
        albedo,
        emission: BLACK,
        gloss: None,
        checker: None,
        ggx: None,
    }
}

fn emitter(emission: V) -> Material {
    Material {
        albedo: BLACK,
        emission,
        gloss: None,
        checker: None,
        ggx: None,
    }
}

/// The six walls of the box, each facing its centre: left, right, floor, ceiling, back, front.
fn walls() -> [Shape; 6] {
    let c = [0.5, 0.5, 0.0];
    let x = [1.0, 0.0, 0.0];
    let y = [0.0, 1.0, 0.0];
    let z = [0.0, 0.0, 2.0];
    let o = [0.0, 0.0, -1.0];
    [
        Shape::quad(o, y, z, c),
        Shape::quad([1.0, 0.0, -1.0], y, z, c),
        Shape::quad(o, x, z, c),
        Shape::quad([0.0, 1.0, -1.0], x, z, c),
        Shape::quad([0.0, 0.0, 1.0], x, y, c),
        Shape::quad(o, x, y, c),
    ]
}

/// A block standing on the floor: centre `(cx, cz)`, half side `h`, height `height`,
/// turned by `angle` radians about `y`; its top and four sides.
fn block(cx: f64, cz: f64, h: f64, height: f64, angle: f64) -> Vec<Shape> {
    let (s, c) = angle.sin_cos();
    let corner = |i: usize| {
        let (a, b) = [(-h, -h), (h, -h), (h, h), (-h, h)][i];
        [cx + c * a - s * b, 0.0, cz + s * a + c * b]
    };
    let centre = [cx, 0.5 * height, cz];
    let up = [0.0, height, 0.0];
    let mut out = Vec::new();
    let p0 = add(corner(0), up);
    let top_toward = [cx, height + 1.0, cz];
    out.push(Shape::quad(
        p0,
        sub(corner(1), corner(0)),
        sub(corner(3), corner(0)),
        top_toward,
    ));
    for i in 0..4 {
        let (a, b) = (corner(i), corner((i + 1) % 4));
        // Faces outwards: towards a point beyond the face from the centre.
        let mid = mul(add(a, b), 0.5);
        let out_pt = add(mid, sub(mid, [centre[0], 0.0, centre[2]]));
        out.push(Shape::quad(
            a,
            sub(b, a),
            up,
            [out_pt[0], 0.5 * height, out_pt[2]],
        ));
    }
    out
}

fn camera() -> Camera {
    Camera {
        eye: [0.5, 0.5, -0.9],
        tan_half: (20.0f64).to_radians().tan(),
        aperture: 0.02,
        focus: 1.4,
        crop: [0.0, 0.0, 1.0],
        centre: false,
    }
}

impl Scene {
    /// The scene names `--scene` accepts (tests use a white furnace scene besides).
    pub const NAMES: [&'static str; 2] = ["cornell", "cornell-disk"];

    /// A scene by name: `cornell`, `cornell-disk`, Burley 2020's configurations
    /// (`burley-direct`, `burley-gi`, `burley-checker`), each optionally followed by
    /// `/`-separated variants: `diffuse` (the glossy block made diffuse), `rr-rnd`,
    /// `rr-sampler`, `rr-production`, `rr-off` (the [`Roulette`]), `clamp` (indirect
    /// contributions clamped to 1, diagnostic), `centre` (a pinhole and every sample at the
    /// pixel's centre: no pixel or lens dimensions, diagnostic); the glossy family
    /// `glossy-a<alpha>` with `cosine`, `caps` or `bounded` (the GGX surfaces' sampler);
    /// `direct`: one scattering event (direct lighting: NEE and BSDF sampling under MIS).
    pub fn by_name(name: &str, size: usize) -> Option<Scene> {
        let mut parts = name.split('/');
        let base = parts.next()?;
        let variants: Vec<&str> = parts.collect();
        let glossy = !base.starts_with("burley") && !variants.contains(&"diffuse");
        let mut s = Scene::cornell(base, glossy, size)?;
        for v in variants {
            if let Some(&sampler) = GgxSampler::ALL.iter().find(|g| g.name() == v) {
                let mut any = false;
                for o in &mut s.objects {
                    if let Some(g) = &mut o.material.ggx {
                        g.sampler = sampler;
                        any = true;
                    }
                }
                if !any {
                    return None;
                }
                continue;
            }
            match v {
                "diffuse" => {}
                "rr-rnd" => s.roulette = Roulette::Rnd,
                "rr-sampler" => s.roulette = Roulette::Sampler,
                "rr-production" => s.roulette = Roulette::Production,
                "rr-off" => s.roulette = Roulette::Off,
                "clamp" => s.clamp = Some(1.0),
                "direct" => s.max_bounces = 1,
                "frame" => s.camera.crop = [0.0, 0.0, 1.0],
                "centre" => {
                    s.camera.centre = true;
                    s.camera.aperture = 0.0;
                }
                _ => return None,
            }
        }
        s.name = name.to_string();
        Some(s)
    }

    /// The box of `base` (see [`Scene::by_name`]); `glossy`: the tall block glossy.
    ///
    /// Burley's configurations use the box with both blocks diffuse: `burley-direct` a
    /// pinhole camera and one scattering event (emission seen directly, and at the first
    /// vertex next-event estimation and BSDF sampling combined by MIS: direct lighting);
    /// `burley-gi` 5 scattering events and a wider lens (aperture 0.06, focus on the tall
    /// block); `burley-checker` a pinhole, 5 events, and a checkerboard of 600 checks per unit
    /// on the floor and the back wall. Like the paper's detail images, each shows a quarter
    /// of the frame's side (at 64 x 64 pixels, the pixels of a 256 x 256 frame): the back
    /// wall beside the tall block's top edge (direct, GI), the floor and back wall between
    /// the blocks (checkerboard, about 3 checks per pixel side there); none shows the light
    /// itself. The variant `frame` shows the whole frame instead.
    ///
    /// `glossy-a<alpha>` (`alpha` in `(0, 1]`): `cornell`'s box and light, the floor and both
    /// blocks GGX reflectors of roughness `alpha` (tinted: a warm floor, a bluish short block,
    /// a golden tall block), 5 scattering events, sampled by `caps` unless a variant says.
    fn cornell(base: &str, glossy: bool, size: usize) -> Option<Scene> {
        let ggx_alpha = base
            .strip_prefix("glossy-a")
            .and_then(|a| a.parse::<f32>().ok())
            .filter(|a| *a > 0.0 && *a <= 1.0);
        let ggx = |albedo: V| Material {
            albedo,
            emission: BLACK,
            gloss: None,
            checker: None,
            ggx: ggx_alpha.map(|alpha| Ggx {
                alpha,
                sampler: GgxSampler::Caps,
            }),
        };
        if ggx_alpha.is_none()
            && ![
                "cornell",
                "cornell-disk",
                "burley-direct",
                "burley-gi",
                "burley-checker",
            ]
            .contains(&base)
        {
            return None;
        }
        let disk = base == "cornell-disk";
        let checker = (base == "burley-checker").then_some(600.0);
        let w = walls();
        let mut objects: Vec<Object> = w
            .iter()
            .enumerate()
            .map(|(i, &shape)| {
                let mut material = diffuse(match i {
                    0 => RED,
                    1 => GREEN,
                    _ => WHITE,
                });
                if i == 2 || i == 4 {
                    material.checker = checker;
                }
                if i == 2 && ggx_alpha.is_some() {
                    material = ggx([0.85, 0.8, 0.7]);
                }
                Object {
                    shape,
                    material,
                    light: None,
                }
            })
            .collect();
        let mut groups = Vec::new();
        let tall = if ggx_alpha.is_some() {
            ggx([0.9, 0.75, 0.5])
        } else {
            Material {
                albedo: [0.8, 0.75, 0.6],
                emission: BLACK,
                gloss: glossy.then_some(40.0),
                checker: None,
                ggx: None,
            }
        };
        let short = if ggx_alpha.is_some() {
            ggx([0.6, 0.7, 0.85])
        } else {
            diffuse(WHITE)
        };
        for (faces, material) in [
            (block(0.68, 0.35, 0.15, 0.3, -0.3), short),
            (block(0.32, 0.68, 0.15, 0.6, 0.3), tall),
        ] {
            let first = objects.len();
            objects.extend(faces.into_iter().map(|shape| Object {
                shape,
                material,
                light: None,
            }));
            groups.push(first..objects.len());
        }
        let power = if disk { 0.5 } else { 1.0 };
        objects.push(Object {
            shape: Shape::quad(
                [0.375, 0.999, 0.275],
                [0.25, 0.0, 0.0],
                [0.0, 0.0, 0.25],
                [0.5, 0.0, 0.4],
            ),
            material: emitter(mul([17.0, 12.0, 4.0], power)),
            light: None,
        });
        if disk {
            objects.push(Object {
                shape: Shape::disk([0.95, 0.7, 0.5], [-1.0, -0.3, -0.2], 0.1),
                material: emitter([6.0, 9.0, 16.0]),
                light: None,
            });
        }
        let bounces = if base == "burley-direct" { 1 } else { 5 };
        let mut scene = Scene::finish(base, objects, groups, bounces, size);
        match base {
            "burley-direct" => {
                scene.camera.aperture = 0.0;
                scene.camera.crop = [0.45, 0.3, 0.25];
            }
            "burley-gi" => {
                scene.camera.aperture = 0.06;
                scene.camera.focus = 1.55;
                scene.camera.crop = [0.45, 0.3, 0.25];
            }
            "burley-checker" => {
                scene.camera.aperture = 0.0;
                scene.camera.crop = [0.4, 0.72, 0.25];
            }
            _ => {}
        }
        Some(scene)
    }

    /// The white furnace: every wall emits 1 and reflects `rho` (diffuse).
    #[cfg(test)]
    pub fn furnace(rho: f64, size: usize) -> Scene {
        let objects = walls()
            .iter()
            .map(|&shape| Object {
                shape,
                material: Material {
                    albedo: [rho; 3],
                    emission: [1.0; 3],
                    gloss: None,
                    checker: None,
                    ggx: None,
                },
                light: None,
            })
            .collect();
        Scene::finish("furnace", objects, Vec::new(), 5, size)
    }

    fn finish(
        name: &str,
        mut objects: Vec<Object>,
        groups: Vec<std::ops::Range<usize>>,
        max_bounces: usize,
        size: usize,
    ) -> Scene {
        let groups: Vec<(V, V, std::ops::Range<usize>)> = groups
            .into_iter()
            .map(|r| {
                let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
                for o in &objects[r.clone()] {
                    if let Shape::Quad { p, e1, e2, .. } = o.shape {
                        for q in [p, add(p, e1), add(p, e2), add(add(p, e1), e2)] {
                            for a in 0..3 {
                                lo[a] = lo[a].min(q[a] - 1e-9);
                                hi[a] = hi[a].max(q[a] + 1e-9);
                            }
                        }
                    }
                }
                (lo, hi, r)
            })
            .collect();
        let loose = (0..objects.len())
            .filter(|i| !groups.iter().any(|g| g.2.contains(i)))
            .collect();
        let mut lights = Vec::new();
        let mut power = Vec::new();
        for (i, o) in objects.iter_mut().enumerate() {
            if luminance(o.material.emission) > 0.0 {
                o.light = Some(lights.len());
                lights.push(i);
                power.push(luminance(o.material.emission) * o.shape.area());
            }
        }
        let total: f64 = power.iter().sum();
        let mut acc = 0.0;
        let light_cdf = power
            .iter()
            .map(|p| {
                acc += p / total;
                acc
            })
            .collect();
        Scene {
            name: name.to_string(),
            objects,
            lights,
            light_cdf,
            camera: camera(),
            max_bounces,
            roulette: Roulette::Production,
            clamp: None,
            width: size,
            height: size,
            groups,
            loose,
        }
    }

    /// The probability of choosing light `l`.
    pub fn light_prob(&self, l: usize) -> f64 {
        self.light_cdf[l] - if l == 0 { 0.0 } else { self.light_cdf[l - 1] }
    }

    /// The nearest hit along `d` from `o` within `(tmin, tmax)`: (object, distance).
    #[inline]
    pub fn intersect(&self, o: V, d: V, tmin: f64, tmax: f64) -> Option<(usize, f64)> {
        let mut best = None;
        let mut tmax = tmax;
        for &i in &self.loose {
            if let Some(t) = self.objects[i].shape.hit(o, d, tmin, tmax) {
                tmax = t;
                best = Some((i, t));
            }
        }
        for (lo, hi, r) in &self.groups {
            if meets_box(o, d, *lo, *hi, tmin, tmax) {
                for i in r.clone() {
                    if let Some(t) = self.objects[i].shape.hit(o, d, tmin, tmax) {
                        tmax = t;
                        best = Some((i, t));
                    }
                }
            }
        }
        best
    }

    /// Whether anything lies along `d` from `o` within `(tmin, tmax)` (any hit).
    #[inline]
    pub fn occluded(&self, o: V, d: V, tmin: f64, tmax: f64) -> bool {
        for (lo, hi, r) in &self.groups {
            if meets_box(o, d, *lo, *hi, tmin, tmax)
                && self.objects[r.clone()]
                    .iter()
                    .any(|ob| ob.shape.hit(o, d, tmin, tmax).is_some())
            {
                return true;
            }
        }
        self.loose
            .iter()
            .any(|&i| self.objects[i].shape.hit(o, d, tmin, tmax).is_some())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn walls_and_lights_face_into_the_box() {
        let s = Scene::by_name("cornell-disk", 8).unwrap();
        for o in &s.objects[..6] {
            if let Shape::Quad { p, n, e1, e2, .. } = o.shape {
                let mid = add(p, mul(add(e1, e2), 0.5));
                assert!(dot(n, sub([0.5, 0.5, 0.0], mid)) > 0.0);
            }
        }
        for &l in &s.lights {
            assert!(s.objects[l].shape.normal()[1] < 0.0 || s.objects[l].shape.normal()[0] < 0.0);
        }
        assert_eq!(s.lights.len(), 2);
        assert!((s.light_cdf[1] - 1.0).abs() < 1e-12);
    }

    /// The culled intersection finds what a test of every object finds.
    #[test]
    fn culled_intersection_matches_brute_force() {
        let s = Scene::by_name("cornell", 8).unwrap();
        let mut rng = crate::math::Rng::new(5);
        for _ in 0..20000 {
            let o = [
                rng.uniform(),
                rng.uniform() * 0.7,
                rng.uniform() * 2.0 - 1.0,
            ];
            let d = rng.direction();
            let mut brute = None;
            for (i, ob) in s.objects.iter().enumerate() {
                if let Some(t) = ob.shape.hit(o, d, 1e-7, f64::INFINITY)
                    && brute.is_none_or(|(_, bt)| t < bt)
                {
                    brute = Some((i, t));
                }
            }
            assert_eq!(s.intersect(o, d, 1e-7, f64::INFINITY), brute);
            assert_eq!(s.occluded(o, d, 1e-7, 1e9), brute.is_some());
            if let Some((_, t)) = brute {
                assert!(s.occluded(o, d, 1e-7, t * 1.01));
                assert!(!s.occluded(o, d, 1e-7, t * 0.99));
            }
        }
    }

    #[test]
    fn quad_and_disk_hits() {
        let q = Shape::quad([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]);
        assert_eq!(q.hit([0.5, 0.5, 0.0], [0.0, 0.0, 1.0], 0.0, 9.0), Some(1.0));
        assert_eq!(q.hit([1.5, 0.5, 0.0], [0.0, 0.0, 1.0], 0.0, 9.0), None);
        let d = Shape::disk([0.0, 0.0, 2.0], [0.0, 0.0, -1.0], 0.5);
        assert_eq!(d.hit([0.3, 0.3, 0.0], [0.0, 0.0, 1.0], 0.0, 9.0), Some(2.0));
        assert_eq!(d.hit([0.4, 0.4, 0.0], [0.0, 0.0, 1.0], 0.0, 9.0), None);
        // Area sampling covers the shape.
        let p = d.point([0.999, 0.5]);
        assert!((p[0] * p[0] + p[1] * p[1]).sqrt() <= 0.5 + 1e-6);
    }
}
