//! The harness that runs `shaders/warpcore.wgsl` on a GPU and compares it with the crate.
//!
//! [`functions`] lists every public WGSL function from the registry (each bound by a
//! registry entry, whose scalar body is the crate reference); [`inputs`] builds the test
//! points of a function (edge values, grids, random points of the domain, random bit patterns
//! of every `f32` class); [`Gpu::run`] evaluates the WGSL function on every point in a compute
//! shader and returns the output words; [`Func::eval`] gives the crate's words for the same
//! point. `tests/lavapipe.rs` requires them to be equal on Mesa's lavapipe, and the
//! `gpu-check` binary reports the differences on any adapter. See `docs/gpu.md`.
//!
//! [`tables`] does the same for `shaders/warpcore_tables.wgsl` (pmj02bn and the sampling core,
//! with the buffer of tables it builds; `tests/lavapipe_tables.rs`), and [`envmaps`] for
//! `shaders/warpcore_envmap.wgsl` (environment maps from their storage words;
//! `tests/lavapipe_envmap.rs`). The solid-angle lights of `warpcore.wgsl` are listed apart
//! ([`lights`]; the rest are the [`warps`]), with their lights and samples in [`spherical`]
//! (`tests/lavapipe_spherical.rs`).

pub mod envmaps;
pub mod functions;
pub mod model;
pub mod spherical;
pub mod tables;
pub mod testing;

pub use functions::{Func, all_functions, all_functions_shader, lights, warps};

use std::fmt::Write as _;
use warpcore::{disk, sphere, triangle};

/// The WGSL library, as shipped.
pub const WGSL: &str = include_str!("../../shaders/warpcore.wgsl");

/// What a function's test points look like.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Points of the unit square (and beyond: every f32 class).
    Square,
    /// Points of the unit square with a quadrant word.
    SquareQuadrant,
    /// Points of the plane around the unit disk.
    Plane,
    /// Directions (and any 3-vector).
    Direction,
    /// Barycentrics (and any 3-vector).
    Barycentric,
    /// The square extended far beyond its edges.
    Extended,
    /// (index, seed) pairs.
    IndexSeed,
    /// Densities.
    Density,
    /// A density and a direction.
    DensityDirection,
    /// Microfacet arguments: a direction (and any 3-vector), then a second one where `.0` is
    /// 8 words, a roughness pair, and a sample where `.0` is 7 (`[w, alpha]`, `[wo, alpha, u]`,
    /// `[wo, wi, alpha]`).
    Microfacet(usize),
    /// Solid-angle lights ([`spherical::inputs`]): a light (12 words), then what the
    /// function takes after it.
    Light(spherical::Layout),
}

// ---------------------------------------------------------------------------------------
// Test points

/// The test points' generator: pmjgen's SplitMix64 (a small, well-mixed generator; the test
/// points need no more), with the draws of floats the points are made of.
pub struct Rng(pmjgen::Rng);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(pmjgen::Rng::new(seed))
    }
    pub fn next_u32(&mut self) -> u32 {
        self.0.next_u32()
    }
    /// Uniform on the 2^-24 grid of [0, 1) (what fixed-point samplers produce).
    pub fn grid24(&mut self) -> f32 {
        (self.next_u32() >> 8) as f32 * (1.0 / 16_777_216.0)
    }
    /// Any f32 in [0, 1), with full precision near 0 (random mantissa and exponent).
    pub fn unit_any(&mut self) -> f32 {
        let x = self.next_u32();
        let exp = 126 - (x.leading_zeros().min(125)); // geometric exponent, down to 2^-125
        f32::from_bits((exp << 23) | (self.next_u32() >> 9))
    }
    /// A random bit pattern: every f32 class (NaN, infinities, subnormals, negatives, huge).
    pub fn bits(&mut self) -> f32 {
        f32::from_bits(self.next_u32())
    }
    /// Uniform in [lo, hi).
    pub fn range(&mut self, lo: f32, hi: f32) -> f32 {
        lo + (hi - lo) * self.grid24()
    }
}

/// Edge values of the unit interval and of every f32 class.
pub fn square_edges() -> Vec<f32> {
    let ulp_below = |x: f32| f32::from_bits(x.to_bits() - 1);
    let ulp_above = |x: f32| f32::from_bits(x.to_bits() + 1);
    vec![
        0.0,
        -0.0,
        f32::from_bits(1),
        -f32::from_bits(1),
        f32::from_bits(0x007f_ffff),
        f32::MIN_POSITIVE,
        1e-30,
        -1e-30,
        1.0 / 16_777_216.0,
        1.0 / 8_388_608.0,
        0.25,
        ulp_below(0.25),
        ulp_above(0.25),
        0.5,
        ulp_below(0.5),
        ulp_above(0.5),
        0.75,
        ulp_below(0.75),
        ulp_above(0.75),
        1.0 / 3.0,
        2.0 / 3.0,
        0.1,
        0.9,
        1.0 - 1.0 / 8_388_608.0,
        1.0 - 1.0 / 16_777_216.0,
        1.0,
        ulp_above(1.0),
        1.5,
        2.0,
        -1.0,
        -0.5,
        -2.0,
        f32::MAX,
        -f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        -f32::NAN,
        f32::from_bits(0x7f80_0001),
        f32::from_bits(0xffc1_2345),
    ]
}

/// Edge values of the signed unit interval (coordinates of disk points and directions).
pub fn signed_edges() -> Vec<f32> {
    let mut e = square_edges();
    for x in [
        0.5f32,
        0.25,
        0.75,
        1.0 - 1.0 / 16_777_216.0,
        1e-20,
        0.707_106_77,
        0.577_350_26,
    ] {
        e.push(-x);
    }
    e.push(0.707_106_77);
    e.push(0.577_350_26);
    e
}

/// The test points of `domain`, flattened (`in_words` words each). `random` sets the number
/// of points of each random class; below `2^14` the grids and the edge products are thinned
/// too (for the CPU model, which interprets the WGSL).
pub fn inputs(domain: Domain, random: usize, seed: u64) -> Vec<u32> {
    let tag = match domain {
        Domain::Square => 0,
        Domain::SquareQuadrant => 1,
        Domain::Plane => 2,
        Domain::Direction => 3,
        Domain::Barycentric => 4,
        Domain::Extended => 5,
        Domain::IndexSeed => 6,
        Domain::Density => 7,
        Domain::DensityDirection => 8,
        Domain::Microfacet(words) => 9 + 1000 * words as u64,
        Domain::Light(l) => 100 + l as u64,
    };
    let mut rng = Rng::new(seed ^ tag.wrapping_mul(0x9e37_79b9));
    let small = random < 1 << 14;
    let mut v: Vec<u32> = Vec::new();
    fn put(v: &mut Vec<u32>, w: &[f32]) {
        v.extend(w.iter().map(|x| x.to_bits()));
    }
    macro_rules! push {
        ($w:expr) => {
            put(&mut v, $w)
        };
    }
    match domain {
        Domain::Square | Domain::SquareQuadrant | Domain::Extended => {
            let e = square_edges();
            let mut pts: Vec<[f32; 2]> = Vec::new();
            for &a in &e {
                for &b in &e {
                    pts.push([a, b]);
                }
            }
            let g = if small { 64 } else { 512 };
            for i in 0..g {
                for j in 0..g {
                    pts.push([i as f32 / g as f32, j as f32 / g as f32]);
                    pts.push([(i as f32 + 0.5) / g as f32, (j as f32 + 0.37) / g as f32]);
                }
            }
            for k in 0..random {
                pts.push([rng.grid24(), rng.grid24()]);
                pts.push([rng.unit_any(), rng.unit_any()]);
                pts.push([rng.bits(), rng.bits()]);
                // One coordinate on an edge, the other random.
                let edge = e[k % e.len()];
                let r = rng.unit_any();
                pts.push(if k % 2 == 0 { [edge, r] } else { [r, edge] });
                if domain == Domain::Extended {
                    pts.push([rng.range(-4.0, 5.0), rng.range(-4.0, 5.0)]);
                    let size = 1u32 << (k % 12);
                    let texel = |r: &mut Rng| {
                        ((r.next_u32() % (3 * size)) as f32 - size as f32 + 0.5) / size as f32
                    };
                    pts.push([texel(&mut rng), texel(&mut rng)]);
                }
            }
            for p in pts {
                if domain == Domain::SquareQuadrant {
                    let q = rng.next_u32();
                    let q = if q & 1 == 0 { q >> 30 } else { q };
                    v.extend([p[0].to_bits(), p[1].to_bits(), q]);
                } else {
                    push!(&p);
                }
            }
        }
        Domain::Plane => {
            let e = signed_edges();
            for &a in &e {
                for &b in &e {
                    push!(&[a, b]);
                }
            }
            for k in 0..random {
                push!(&disk::concentric([rng.unit_any(), rng.unit_any()]));
                push!(&disk::polar([rng.grid24(), rng.grid24()]));
                push!(&[rng.range(-1.2, 1.2), rng.range(-1.2, 1.2)]);
                push!(&[rng.bits(), rng.bits()]);
                let edge = e[k % e.len()];
                let r = rng.range(-1.0, 1.0);
                push!(&if k % 2 == 0 { [edge, r] } else { [r, edge] });
            }
        }
        Domain::Direction | Domain::DensityDirection => {
            let dirs = directions(random, small, &mut rng);
            for d in dirs {
                if domain == Domain::DensityDirection {
                    let pdf = [rng.unit_any() * 8.0, rng.bits(), 0.0, -1.0, f32::INFINITY]
                        [rng.next_u32() as usize % 5];
                    push!(&[pdf, d[0], d[1], d[2]]);
                } else {
                    push!(&d);
                }
            }
        }
        Domain::Microfacet(words) => {
            let dirs = directions(random, small, &mut rng);
            let mut alphas = vec![
                0.0f32,
                -0.0,
                1e-4,
                1e-3,
                0.05,
                0.3,
                1.0,
                1.5,
                f32::NAN,
                f32::INFINITY,
                -1.0,
                f32::from_bits(1),
                1e-30,
            ];
            let e = square_edges();
            let n = dirs.len();
            for (k, d) in dirs.iter().enumerate() {
                alphas.push(rng.unit_any());
                let a = [alphas[k % alphas.len()], alphas[(k / 3 + 1) % alphas.len()]];
                let a = if k % 2 == 0 { [a[0], a[0]] } else { a };
                push!(d);
                if words == 8 {
                    push!(&dirs[(k * 7 + 3) % n]);
                }
                push!(&a);
                if words == 7 {
                    let u = if k % 3 == 0 {
                        [e[k % e.len()], e[k / e.len() % e.len()]]
                    } else {
                        [rng.grid24(), rng.unit_any()]
                    };
                    push!(&u);
                }
            }
        }
        Domain::Barycentric => {
            let e = square_edges();
            for &a in &e {
                for &b in &e {
                    for &c in &[0.0f32, -0.0, 0.5, f32::NAN] {
                        push!(&[a, b, c]);
                    }
                }
            }
            for _ in 0..random {
                push!(&triangle::uniform([rng.unit_any(), rng.unit_any()]));
                push!(&triangle::sqrt_map([rng.grid24(), rng.grid24()]));
                push!(&triangle::basu_owen(rng.next_u32(), rng.next_u32()));
                push!(&[rng.bits(), rng.bits(), rng.bits()]);
                push!(&[rng.range(-0.2, 1.2), rng.range(-0.2, 1.2), 0.0]);
            }
        }
        Domain::IndexSeed => {
            let edges = [
                0u32,
                1,
                2,
                3,
                4,
                0x5555_5555,
                0xaaaa_aaaa,
                0x8000_0000,
                0x7fff_ffff,
                u32::MAX,
                0xffff,
                0x1_0000,
            ];
            for &a in &edges {
                for &b in &edges {
                    v.extend([a, b]);
                }
            }
            for i in 0..(if small { 1u32 << 10 } else { 1u32 << 16 }) {
                v.extend([i, 0]);
                v.extend([i, 0x9e37_79b9 ^ (i >> 12)]);
            }
            for _ in 0..4 * random {
                v.extend([rng.next_u32(), rng.next_u32()]);
            }
        }
        Domain::Light(layout) => return spherical::inputs(layout, random, &mut rng),
        Domain::Density => {
            for x in square_edges().into_iter().chain(signed_edges()) {
                push!(&[x, x * 1e30, x * 3.0]);
            }
            for _ in 0..random {
                push!(&[rng.bits(), rng.unit_any() * 100.0, rng.range(-1.0, 1.0)]);
            }
        }
    }
    v
}

/// The test directions: every triple of signed edge values (thinned where `small`), then per
/// random round unit directions, scaled ones (down to `1e-20`), bit patterns, points of the
/// cube and directions near the poles and the equator with signed zeros.
fn directions(random: usize, small: bool, rng: &mut Rng) -> Vec<[f32; 3]> {
    let e = signed_edges();
    let mut dirs: Vec<[f32; 3]> = Vec::new();
    for (k, &a) in e.iter().enumerate() {
        for (j, &b) in e.iter().enumerate() {
            for (i, &c) in e.iter().enumerate() {
                if !small || (k + j + i) % 13 == 0 {
                    dirs.push([a, b, c]);
                }
            }
        }
    }
    for k in 0..random {
        dirs.push(sphere::equal_area([rng.unit_any(), rng.unit_any()]));
        dirs.push(sphere::uniform([rng.grid24(), rng.grid24()]));
        let d = sphere::equal_area([rng.grid24(), rng.grid24()]);
        let s = [0.5f32, 1e-3, 1e-20, 0.999_999_9][k % 4];
        dirs.push(d.map(|x| x * s));
        dirs.push([rng.bits(), rng.bits(), rng.bits()]);
        dirs.push([
            rng.range(-1.5, 1.5),
            rng.range(-1.5, 1.5),
            rng.range(-1.5, 1.5),
        ]);
        // Near the poles and the equator, with signed zeros.
        let t = rng.unit_any() * 1e-3;
        let z = [1.0f32, -1.0, 0.0, -0.0][k % 4];
        dirs.push([t, [0.0f32, -0.0][k / 4 % 2], z]);
    }
    dirs
}

/// Typical points of `domain` (`n` random ones, in the domain at unit scale: no edge values,
/// no bit patterns, no tiny vectors): what a renderer passes, for the CPU model's bounds.
pub fn typical_inputs(domain: Domain, n: usize, seed: u64) -> Vec<u32> {
    let mut rng = Rng::new(seed ^ 0x7e57);
    let mut v: Vec<u32> = Vec::new();
    for k in 0..n {
        let mut words: Vec<u32> = Vec::new();
        let mut put = |w: &[f32]| words.extend(w.iter().map(|x| x.to_bits()));
        let u = if k % 2 == 0 {
            [rng.grid24(), rng.grid24()]
        } else {
            [rng.unit_any(), rng.unit_any()]
        };
        match domain {
            Domain::Square => put(&u),
            Domain::SquareQuadrant => {
                let q = f32::from_bits(rng.next_u32());
                put(&[u[0], u[1], q]);
            }
            Domain::Plane => put(&if k % 4 < 2 {
                disk::concentric(u)
            } else {
                disk::polar(u)
            }),
            Domain::Direction => put(&if k % 4 < 2 {
                sphere::equal_area(u)
            } else {
                sphere::uniform(u)
            }),
            Domain::Barycentric => put(&if k % 4 < 2 {
                triangle::uniform(u)
            } else {
                triangle::sqrt_map(u)
            }),
            Domain::Extended => put(&[rng.range(-4.0, 5.0), rng.range(-4.0, 5.0)]),
            Domain::IndexSeed => put(&[rng.bits(), rng.bits()]),
            Domain::Density => put(&[u[0] * 100.0]),
            Domain::DensityDirection => {
                let d = sphere::equal_area(u);
                put(&[rng.unit_any() * 100.0, d[0], d[1], d[2]]);
            }
            Domain::Microfacet(words) => {
                let d = sphere::cosine_hemisphere(u);
                put(&d);
                if words == 8 {
                    put(&sphere::uniform([rng.unit_any(), rng.unit_any()]));
                }
                put(&[rng.range(0.01, 1.0), rng.range(0.01, 1.0)]);
                if words == 7 {
                    put(&[rng.grid24(), rng.grid24()]);
                }
            }
            Domain::Light(layout) => put(&spherical::typical(layout, u, &mut rng)),
        }
        v.extend(words);
    }
    v
}

// ---------------------------------------------------------------------------------------
// The GPU side

/// A device and queue on one adapter.
pub struct Gpu {
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
    pub info: wgpu::AdapterInfo,
}

/// Points per dispatch (64 per workgroup, under the 65535-workgroup limit).
const CHUNK: usize = 1 << 21;

impl Gpu {
    /// Mesa's lavapipe (llvmpipe on Vulkan), or an error that says what was found instead.
    pub fn lavapipe() -> Result<Gpu, String> {
        let instance = instance();
        let adapters = pollster::block_on(instance.enumerate_adapters(wgpu::Backends::VULKAN));
        let names: Vec<String> = adapters
            .iter()
            .map(|a| {
                format!(
                    "{} ({:?}, {})",
                    a.get_info().name,
                    a.get_info().device_type,
                    a.get_info().driver
                )
            })
            .collect();
        let lvp = adapters.into_iter().find(|a| {
            let info = a.get_info();
            info.device_type == wgpu::DeviceType::Cpu && info.name.contains("llvmpipe")
        });
        match lvp {
            Some(a) => Gpu::open(a),
            None => Err(format!(
                "no lavapipe (llvmpipe) Vulkan adapter; Vulkan adapters found: {names:?}. \
                 Install Mesa's software Vulkan driver (Debian/Ubuntu: apt-get install mesa-vulkan-drivers)"
            )),
        }
    }

    /// The adapter wgpu picks by default (high performance), on any backend compiled in.
    pub fn default_adapter() -> Result<Gpu, String> {
        let instance =
            wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let adapter = pollster::block_on(instance.request_adapter(&wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::HighPerformance,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        }))
        .map_err(|e| format!("no adapter: {e}"))?;
        Gpu::open(adapter)
    }

    fn open(adapter: wgpu::Adapter) -> Result<Gpu, String> {
        let info = adapter.get_info();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("warpcore-gpu"),
            required_features: wgpu::Features::empty(),
            required_limits: wgpu::Limits::default(),
            experimental_features: wgpu::ExperimentalFeatures::disabled(),
            memory_hints: wgpu::MemoryHints::Performance,
            trace: wgpu::Trace::Off,
        }))
        .map_err(|e| format!("request_device on {}: {e}", info.name))?;
        Ok(Gpu {
            device,
            queue,
            info,
        })
    }

    /// The compute shader that evaluates `func` on every point of `wc_in`.
    pub fn shader_source(func: &Func) -> String {
        let (call, outs) = func.wgsl();
        let words = [func.in_words(), func.out_words()];
        check_shader(WGSL, [0, 1], words, &call_body(call, outs))
    }

    /// `func` evaluated on the GPU for every point of `input` (`in_words` words each); returns
    /// the output words.
    pub fn run(&self, func: &Func, input: &[u32]) -> Result<Vec<u32>, String> {
        self.run_source(func, &Gpu::shader_source(func), input)
    }

    /// [`Gpu::run`] with another shader source (entry point `wc_check_main` and the bindings
    /// of [`Gpu::shader_source`]).
    pub fn run_source(&self, func: &Func, source: &str, input: &[u32]) -> Result<Vec<u32>, String> {
        let (inw, outw) = (func.in_words(), func.out_words());
        self.run_words(&func.name, source, input, inw, outw, None)
    }

    /// Runs the compute shader `source` (entry point `wc_check_main`) on `input` (`inw` words
    /// per point) and returns `outw` words per point. Without `tables` the shader reads
    /// `wc_in` at binding 0 and writes `wc_out` at binding 1 (group 0); with `tables`, the
    /// tables buffer is binding 0 (`shaders/warpcore_tables.wgsl`'s `wc_tables`), `wc_in`
    /// binding 1 and `wc_out` binding 2.
    pub fn run_words(
        &self,
        label: &str,
        source: &str,
        input: &[u32],
        inw: usize,
        outw: usize,
        tables: Option<&[u32]>,
    ) -> Result<Vec<u32>, String> {
        match tables {
            Some(t) => self.run_bound(label, source, input, inw, outw, &[(0, t)], [1, 2]),
            None => self.run_bound(label, source, input, inw, outw, &[], [0, 1]),
        }
    }

    /// [`Gpu::run_words`] with any read-only buffers `bound` (binding, words) and the
    /// bindings `[in, out]` of `wc_in` and `wc_out` (all in group 0).
    #[allow(clippy::too_many_arguments)]
    pub fn run_bound(
        &self,
        label: &str,
        source: &str,
        input: &[u32],
        inw: usize,
        outw: usize,
        bound: &[(u32, &[u32])],
        [in_binding, out_binding]: [u32; 2],
    ) -> Result<Vec<u32>, String> {
        let scope = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let module = self
            .device
            .create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some(label),
                source: wgpu::ShaderSource::Wgsl(source.into()),
            });
        let pipeline = self
            .device
            .create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(label),
                layout: None,
                module: &module,
                entry_point: Some("wc_check_main"),
                compilation_options: Default::default(),
                cache: None,
            });
        if let Some(e) = pollster::block_on(scope.pop()) {
            return Err(format!("{label}: {e}"));
        }
        let n = input.len() / inw;
        let mut out = Vec::with_capacity(n * outw);
        // Also within the device's largest storage binding (128 MiB on the H200's Vulkan
        // driver: 2^21 points of a light's 17 input words would exceed it).
        let max_binding = self.device.limits().max_storage_buffer_binding_size as usize;
        let chunk = CHUNK.min(max_binding / (4 * inw.max(outw))).max(1);
        for start in (0..n).step_by(chunk) {
            let m = chunk.min(n - start);
            let words = &input[start * inw..(start + m) * inw];
            let mut reads: Vec<(u32, &[u32])> = bound.to_vec();
            reads.push((in_binding, words));
            out.extend(self.dispatch(&pipeline, &reads, out_binding, m, m * outw)?);
        }
        Ok(out)
    }

    fn dispatch(
        &self,
        pipeline: &wgpu::ComputePipeline,
        reads: &[(u32, &[u32])],
        out_binding: u32,
        points: usize,
        out_words: usize,
    ) -> Result<Vec<u32>, String> {
        let bytes = |w: &[u32]| w.iter().flat_map(|x| x.to_le_bytes()).collect::<Vec<u8>>();
        let in_bufs: Vec<(u32, wgpu::Buffer)> = reads
            .iter()
            .map(|&(binding, words)| {
                let buf = self.device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("wc_in"),
                    size: (words.len().max(1) * 4) as u64,
                    usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                });
                self.queue.write_buffer(&buf, 0, &bytes(words));
                (binding, buf)
            })
            .collect();
        let size = (out_words * 4) as u64;
        let out_buf = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("wc_out"),
            size,
            usage: wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let read_buf = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("wc_read"),
            size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &pipeline.get_bind_group_layout(0),
            entries: &in_bufs
                .iter()
                .map(|(binding, buf)| wgpu::BindGroupEntry {
                    binding: *binding,
                    resource: buf.as_entire_binding(),
                })
                .chain([wgpu::BindGroupEntry {
                    binding: out_binding,
                    resource: out_buf.as_entire_binding(),
                }])
                .collect::<Vec<_>>(),
        });
        let mut enc = self.device.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups(points.div_ceil(64) as u32, 1, 1);
        }
        enc.copy_buffer_to_buffer(&out_buf, 0, &read_buf, 0, size);
        self.queue.submit([enc.finish()]);
        let slice = read_buf.slice(..);
        let (tx, rx) = std::sync::mpsc::channel();
        slice.map_async(wgpu::MapMode::Read, move |r| {
            let _ = tx.send(r);
        });
        self.device
            .poll(wgpu::PollType::Wait {
                submission_index: None,
                timeout: None,
            })
            .map_err(|e| format!("poll: {e}"))?;
        rx.recv()
            .map_err(|e| format!("map: {e}"))?
            .map_err(|e| format!("map: {e}"))?;
        let view = slice
            .get_mapped_range()
            .map_err(|e| format!("map range: {e:?}"))?;
        let out = view
            .chunks_exact(4)
            .map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        drop(view);
        read_buf.unmap();
        Ok(out)
    }
}

/// A check's compute shader: `library`, then `wc_in` and `wc_out` (bindings `[in, out]` of
/// group 0) and the entry point `wc_check_main`, which runs `body` for point `i` with its
/// `inw` input words at `wc_in[b + k]` and its `outw` output words at `wc_out[o + k]`.
pub fn check_shader(
    library: &str,
    [in_binding, out_binding]: [u32; 2],
    [inw, outw]: [usize; 2],
    body: &str,
) -> String {
    format!(
        "{library}\n@group(0) @binding({in_binding}) var<storage, read> wc_in: array<u32>;\n\
         @group(0) @binding({out_binding}) var<storage, read_write> wc_out: array<u32>;\n\
         @compute @workgroup_size(64)\n\
         fn wc_check_main(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
         \x20   let i = gid.x;\n\
         \x20   if (i >= arrayLength(&wc_out) / {outw}u) {{ return; }}\n\
         \x20   let b = i * {inw}u;\n\
         \x20   let o = i * {outw}u;\n\
         {body}}}\n"
    )
}

/// A compute shader that runs each of `bodies` in its own block for invocation `i` (entry
/// point `wc_all`; `wc_in` and `wc_out` at bindings `[in, out]` of group 0), for the
/// translation checks: naga's GLSL, HLSL and MSL writers and `spirv-val` want an entry point.
pub fn all_shader(
    library: &str,
    [in_binding, out_binding]: [u32; 2],
    bodies: impl IntoIterator<Item = String>,
) -> String {
    let mut s = format!(
        "{library}\n@group(0) @binding({in_binding}) var<storage, read> wc_in: array<u32>;\n\
         @group(0) @binding({out_binding}) var<storage, read_write> wc_out: array<u32>;\n\
         @compute @workgroup_size(64)\n\
         fn wc_all(@builtin(global_invocation_id) gid: vec3<u32>) {{\n\
         \x20   let i = gid.x;\n"
    );
    for body in bodies {
        let _ = write!(s, "    {{\n{body}    }}\n");
    }
    s.push_str("}\n");
    s
}

/// The statements of a [`check_shader`] body that call `call` and write the output words
/// `outs` of its result `r`.
pub fn call_body<'a>(call: &str, outs: impl Iterator<Item = &'a str>) -> String {
    let mut s = format!("    let r = {call};\n");
    for (k, e) in outs.enumerate() {
        let _ = writeln!(s, "    wc_out[o + {k}u] = {e};");
    }
    s
}

fn instance() -> wgpu::Instance {
    wgpu::Instance::new(wgpu::InstanceDescriptor {
        backends: wgpu::Backends::VULKAN,
        ..wgpu::InstanceDescriptor::new_without_display_handle_from_env()
    })
}

/// The crate's output words for every point of `input`.
pub fn cpu_outputs(func: &Func, input: &[u32]) -> Vec<u32> {
    let (inw, outw) = (func.in_words(), func.out_words());
    let mut out = vec![0u32; input.len() / inw * outw];
    for (i, o) in input.chunks_exact(inw).zip(out.chunks_exact_mut(outw)) {
        func.eval(i, o);
    }
    out
}

/// Differences between GPU and crate outputs of one function.
#[derive(Default, Debug, Clone, Copy)]
pub struct Diff {
    /// Points compared.
    pub points: usize,
    /// Points with at least one differing word.
    pub mismatches: usize,
    /// Largest absolute difference of an f32 output word (NaN counts as infinite).
    pub max_abs: f64,
    /// Largest difference of an f32 output word in units in the last place of the crate's
    /// value, where values below `1/2` in magnitude count as `1/2` (so that a coordinate near
    /// 0 is measured in ulps of the unit scale, `2^-24`).
    pub max_ulp: f64,
    /// The first mismatching point's index.
    pub first: Option<usize>,
    /// The point with the largest absolute difference.
    pub worst: Option<usize>,
}

/// `|gpu - crate|` in ulps of `crate` (magnitudes below `1/2` count as `1/2`: ulps of
/// `2^-24`).
pub fn ulps(gpu: f32, want: f32) -> f64 {
    if gpu.is_nan() || want.is_nan() {
        return f64::INFINITY;
    }
    let m = want.abs().max(0.5);
    let exp = ((m.to_bits() >> 23) as i32 - 127).clamp(-126, 127);
    ((gpu as f64) - (want as f64)).abs() / 2f64.powi(exp - 23)
}

/// Compares GPU words with crate words, point by point.
pub fn compare(func: &Func, gpu: &[u32], cpu: &[u32]) -> Diff {
    compare_words(func.out_words(), |k| func.is_integer_output(k), gpu, cpu)
}

/// [`compare`] for `outw` words per point, `is_integer(k)` telling which words are `u32`.
pub fn compare_words(
    outw: usize,
    is_integer: impl Fn(usize) -> bool,
    gpu: &[u32],
    cpu: &[u32],
) -> Diff {
    let mut d = Diff {
        points: cpu.len() / outw,
        ..Default::default()
    };
    for (p, (g, c)) in gpu
        .chunks_exact(outw)
        .zip(cpu.chunks_exact(outw))
        .enumerate()
    {
        if g == c {
            continue;
        }
        d.mismatches += 1;
        d.first.get_or_insert(p);
        for k in 0..outw {
            if g[k] == c[k] {
                continue;
            }
            let (abs, ulp) = if is_integer(k) {
                let a = (g[k] as f64 - c[k] as f64).abs();
                (a, a)
            } else {
                let (gf, cf) = (f32::from_bits(g[k]), f32::from_bits(c[k]));
                let a = if gf.is_nan() || cf.is_nan() {
                    f64::INFINITY
                } else {
                    (gf as f64 - cf as f64).abs()
                };
                (a, ulps(gf, cf))
            };
            if abs > d.max_abs {
                d.max_abs = abs;
                d.worst = Some(p);
            }
            d.max_ulp = d.max_ulp.max(ulp);
        }
    }
    if gpu.len() != cpu.len() {
        d.mismatches = d.points;
    }
    d
}
