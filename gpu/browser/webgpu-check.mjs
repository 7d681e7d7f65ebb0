// Runs in a page (served from the repository root): evaluates functions of
// shaders/warpcore.wgsl with WebGPU and compares every output word with the JavaScript module
// (js/warpcore.mjs, the crate compiled to wasm). Inputs stay away from subnormals, which
// SwiftShader (Chromium's software adapter) flushes to zero. See webgpu.test.mjs.
import { load } from '../../js/warpcore.mjs';
import { callBody, computeShader, createPipeline, library, openGpu, runCompute } from '../../js/demo/gpu.mjs';

// [WGSL function, JS method, input kind, output floats per point]
const FUNCTIONS = [
  ['wc_disk_polar', 'diskPolar', 'square', 2],
  ['wc_disk_polar_inverse', 'diskPolarInverse', 'disk', 2],
  ['wc_disk_concentric', 'diskConcentric', 'square', 2],
  ['wc_disk_concentric_inverse', 'diskConcentricInverse', 'disk', 2],
  ['wc_disk_polar4', 'diskPolar4', 'quadrant', 2],
  ['wc_disk_polar4_inverse', 'diskPolar4Inverse', 'quadrant-inverse', 3],
  ['wc_disk_concentric4', 'diskConcentric4', 'quadrant', 2],
  ['wc_disk_concentric4_inverse', 'diskConcentric4Inverse', 'quadrant-inverse', 3],
  ['wc_triangle_uniform', 'triangleUniform', 'square', 3],
  ['wc_triangle_uniform_inverse', 'triangleUniformInverse', 'barycentric', 2],
  ['wc_triangle_sqrt_map', 'triangleSqrtMap', 'square', 3],
  ['wc_triangle_sqrt_map_inverse', 'triangleSqrtMapInverse', 'barycentric', 2],
  ['wc_triangle_basu_owen', 'triangleBasuOwen', 'index', 3],
  ['wc_triangle_basu_owen_permuted', 'triangleBasuOwenPermuted', 'index', 3],
  ['wc_sphere_equal_area', 'sphereEqualArea', 'square', 3],
  ['wc_sphere_equal_area_inverse', 'sphereEqualAreaInverse', 'direction', 2],
  ['wc_sphere_equal_area_pdf_to_solid_angle', 'sphereEqualAreaPdfToSolidAngle', 'density', 1],
  ['wc_sphere_equal_area_wrap', 'sphereEqualAreaWrap', 'extended', 2],
  ['wc_sphere_uniform', 'sphereUniform', 'square', 3],
  ['wc_sphere_uniform_inverse', 'sphereUniformInverse', 'direction', 2],
  ['wc_sphere_uniform_hemisphere', 'sphereUniformHemisphere', 'square', 3],
  ['wc_sphere_uniform_hemisphere_inverse', 'sphereUniformHemisphereInverse', 'direction', 2],
  ['wc_sphere_cosine_hemisphere', 'sphereCosineHemisphere', 'square', 3],
  ['wc_sphere_cosine_hemisphere_inverse', 'sphereCosineHemisphereInverse', 'direction', 2],
  ['wc_sphere_cosine_hemisphere_pdf', 'sphereCosineHemispherePdf', 'density', 1],
  ['wc_sphere_equirect', 'sphereEquirect', 'square', 3],
  ['wc_sphere_equirect_inverse', 'sphereEquirectInverse', 'direction', 2],
  ['wc_sphere_equirect_pdf_to_solid_angle', 'sphereEquirectPdfToSolidAngle', 'density-direction', 1],
];

const SEED = 0x2545f491;

/** xorshift32: the test points need no more. */
function rng(seed) {
  let s = seed >>> 0 || 1;
  return () => {
    s ^= s << 13;
    s >>>= 0;
    s ^= s >>> 17;
    s ^= s << 5;
    return (s >>>= 0);
  };
}

/** `n` points of the square on the 2^-24 grid, every coordinate at least 2^-12 from 0. */
function square(n, next) {
  const u = new Float32Array(2 * n);
  for (let i = 0; i < u.length; i++) u[i] = ((next() >>> 8) | 0x1000) / 16777216;
  return u;
}

function inputs(kind, n, wc, next) {
  switch (kind) {
    case 'square':
      return square(n, next);
    case 'disk':
      return wc.diskConcentric(square(n, next));
    case 'barycentric':
      return wc.triangleUniform(square(n, next));
    case 'direction':
      return wc.sphereEqualArea(square(n, next));
    case 'extended': {
      const u = new Float32Array(2 * n);
      for (let i = 0; i < u.length; i++) u[i] = ((next() >>> 12) - 2 ** 19) / 2 ** 18 + 0.5;
      return u;
    }
    default:
      throw new Error(kind);
  }
}

function shader(lib, name, kind, outFloats) {
  const f = (k) => `bitcast<f32>(wc_in[b + ${k}u])`;
  const v2 = `vec2<f32>(${f(0)}, ${f(1)})`;
  const [inw, call] = {
    index: [2, `${name}(wc_in[b], wc_in[b + 1u])`],
    direction: [3, `${name}(vec3<f32>(${f(0)}, ${f(1)}, ${f(2)}))`],
    barycentric: [3, `${name}(vec3<f32>(${f(0)}, ${f(1)}, ${f(2)}))`],
    quadrant: [3, `${name}(${v2}, wc_in[b + 2u])`],
    density: [1, `${name}(${f(0)})`],
    'density-direction': [4, `${name}(${f(0)}, vec3<f32>(${f(1)}, ${f(2)}, ${f(3)}))`],
  }[kind] ?? [2, `${name}(${v2})`];
  const writes =
    kind === 'quadrant-inverse'
      ? ['bitcast<u32>(r.u.x)', 'bitcast<u32>(r.u.y)', 'r.quadrant']
      : outFloats === 1
        ? ['bitcast<u32>(r)']
        : ['x', 'y', 'z'].slice(0, outFloats).map((c) => `bitcast<u32>(r.${c})`);
  return computeShader(lib, 'wc_check_main', [0, 1], inw, outFloats, callBody(call, writes));
}

/** The library `shaders/${file}` (`edit` = [from, to] replaces a string of it first), the
 * JavaScript module and a WebGPU device: `{ wc, lib, device, adapter }`. */
async function setup(file, edit = null) {
  const gpu = await openGpu();
  if (gpu.reason) throw new Error(gpu.reason);
  const lib = await library(file, edit);
  return { wc: await load(), lib, device: gpu.device, adapter: `${gpu.adapter} (fallback ${gpu.fallback})` };
}

/** Runs `code`'s entry point `wc_check_main` over the `n` points of `input` (`wc_in` at
 * binding `inBinding`, `wc_out` after it) into `outWords` words, with the buffers `bound`
 * (`[binding, GPUBuffer]`). */
async function run(device, code, input, n, outWords, bound = [], inBinding = 0) {
  const pipeline = await createPipeline(device, code, 'wc_check_main');
  return runCompute(device, pipeline, bound, inBinding, input, n, outWords);
}

/** A row of the results: `[name, points, mismatches, first]`, the first mismatching point with
 * its words (and its input words, `inw` per point, when `input` is given). */
function row(name, got, want, outw, input = null, inw = 0) {
  const points = want.length / outw;
  const words = (a, p, w) => Array.from(a.subarray(p * w, (p + 1) * w));
  let mismatches = 0;
  let first = null;
  for (let p = 0; p < points; p++) {
    const g = got.subarray(p * outw, (p + 1) * outw);
    if (g.some((x, k) => x !== want[p * outw + k])) {
      mismatches++;
      first ??= { point: p, got: Array.from(g), want: words(want, p, outw), ...(input ? { input: words(input, p, inw) } : {}) };
    }
  }
  return [name, points, mismatches, first];
}

/**
 * Checks every function on `n` points; returns `{ adapter, rows: [[name, points, mismatches,
 * first]] }`. `edit = [from, to]` replaces a string of the library first (the test's check that
 * a one-ulp change is seen).
 */
export async function check(n = 1 << 14, edit = null) {
  const { wc, lib, device, adapter } = await setup('warpcore.wgsl', edit);
  const rows = [];
  for (const [k, [name, js, kind, outFloats]] of FUNCTIONS.entries()) {
    const next = rng(0x9e3779b9 ^ (k * 0x85ebca6b));
    let input, want;
    const words = (a) => new Uint32Array(a.buffer.slice(a.byteOffset, a.byteOffset + a.byteLength));
    if (kind === 'index') {
      input = new Uint32Array(2 * n);
      for (let i = 0; i < n; i++) input.set([i, SEED], 2 * i);
      want = words(wc[js](0, SEED, n));
    } else if (kind === 'quadrant') {
      // Sample i: point i / 4 in quadrant i % 4 (the JS form expands four per point).
      const points = square(n / 4, next);
      input = new Uint32Array(3 * n);
      const pw = words(points);
      for (let i = 0; i < n; i++) input.set([pw[2 * (i >> 2)], pw[2 * (i >> 2) + 1], i & 3], 3 * i);
      want = words(wc[js](points));
    } else if (kind === 'quadrant-inverse') {
      const p = wc.diskConcentric(square(n, next));
      input = words(p);
      const { u, quadrant } = wc[js](p);
      const uw = words(u);
      want = new Uint32Array(3 * n);
      for (let i = 0; i < n; i++) want.set([uw[2 * i], uw[2 * i + 1], quadrant[i]], 3 * i);
    } else if (kind === 'density') {
      const x = new Float32Array(n);
      for (let i = 0; i < n; i++) x[i] = ((next() >>> 8) | 0x1000) / 2 ** 17 - 16;
      input = words(x);
      want = words(wc[js](x));
    } else if (kind === 'density-direction') {
      const d = wc.sphereEqualArea(square(n, next));
      const pdf = new Float32Array(n);
      for (let i = 0; i < n; i++) pdf[i] = ((next() >>> 8) | 0x1000) / 2 ** 18;
      input = new Uint32Array(4 * n);
      const dw = words(d);
      const pw = words(pdf);
      for (let i = 0; i < n; i++) input.set([pw[i], dw[3 * i], dw[3 * i + 1], dw[3 * i + 2]], 4 * i);
      want = words(wc[js](pdf, d));
    } else {
      const x = inputs(kind, n, wc, next);
      input = new Uint32Array(x.buffer.slice(0));
      want = new Uint32Array(wc[js](x).buffer.slice(0));
    }
    const got = await run(device, shader(lib, name, kind, outFloats), input, n, n * outFloats);
    rows.push(row(name, got, want, outFloats));
  }
  return { adapter, rows };
}

// The solid-angle lights: [WGSL function, JS method, shape, what follows the light, output
// floats per point]. 'solid' points are lights alone; 'nu' points carry a normal, then u.
const LIGHT_FUNCTIONS = [
  ['wc_spherical_triangle', 'sphericalTriangle', 'triangle', 'u', 4],
  ['wc_spherical_triangle_inverse', 'sphericalTriangleInverse', 'triangle', 'b', 2],
  ['wc_spherical_triangle_solid_angle', 'sphericalTriangleSolidAngle', 'triangle', 'solid', 1],
  ['wc_spherical_rectangle', 'sphericalRectangle', 'rectangle', 'u', 3],
  ['wc_spherical_rectangle_inverse', 'sphericalRectangleInverse', 'rectangle', 'st', 2],
  ['wc_spherical_rectangle_solid_angle', 'sphericalRectangleSolidAngle', 'rectangle', 'solid', 1],
  ['wc_spherical_triangle_cosine', 'sphericalTriangleCosine', 'triangle', 'nu', 4],
  ['wc_spherical_rectangle_cosine', 'sphericalRectangleCosine', 'rectangle', 'nu', 3],
];

// Lights (`v0, v1, v2, p` or `corner, ex, ey, p`) away from subnormals: some of the golden
// fingerprint's (ordinary, nearly 2 pi, the other winding, a sliver, p on the plane inside and
// outside, grazing, p at a vertex or corner) and random ordinary ones.
const LIGHTS = {
  triangle: [
    [0, 0, 1, 1, 0, 1, 0, 1, 1, 0.1, 0.2, 0],
    [-1, -1, 0.05, 2, -1, 0.05, -1, 2, 0.05, 0, 0, 0],
    [0.3, -2, 0.5, -0.7, 0.4, 1.9, 1.5, 0.8, -0.3, -0.2, 0.1, 0.05],
    [0, 0, 1, 1, 0, 1, 1, 1e-5, 1, 0.3, 0.4, 0],
    [0, 0, 1, 1, 0, 1, 0, 1, 1, 0.2, 0.2, 1],
    [0, 0, 1, 1, 0, 1, 0, 1, 1, 5, -3, 1],
    [0, 0, 1, 1, 0, 1, 0, 1, 1, 0.2, 0.2, 0.999999],
    [0, 0, 1, 1, 0, 1, 0, 1, 1, 1, 0, 1],
  ],
  rectangle: [
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 0.1, 0.2, 0],
    [0.3, -0.2, 0.7, 0.6, 0.8, 0, 0, 0, 1.5, 0, 0, 0],
    [-50, -50, 0.01, 100, 0, 0, 0, 100, 0, 0, 0, 0],
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1e-6, 0, 0, 0, 0],
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 0, 0, 1],
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 3, 0.5, 1],
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 0.1, 0.1, 0.999999],
    [-0.5, -0.5, 1, 1, 0, 0, 0.3, 1, 0, 0.2, -0.1, 2.5],
    [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, -0.5, -0.5, 1],
  ],
};

/** A random ordinary light of `shape` (size and distance about 1). */
function randomLight(shape, next) {
  const r = (lo, hi) => lo + ((hi - lo) * (next() >>> 8)) / 16777216;
  const p = [r(-0.3, 0.3), r(-0.3, 0.3), r(-0.3, 0.3)];
  if (shape === 'triangle') {
    return [r(-1, 1), r(-1, 1), r(0.5, 1.5), r(-1, 1), r(-1, 1), r(0.5, 1.5), r(-1, 1), r(-1, 1), r(0.5, 1.5), ...p];
  }
  // ex and ey orthogonal: a rotation about z of the axes, scaled.
  const a = r(0, 6.283185307179586);
  const [c, s] = [Math.cos(a), Math.sin(a)];
  const [w, h] = [r(0.2, 2), r(0.2, 2)];
  return [r(-1, 0), r(-1, 0), r(0.3, 2), w * c, w * s, 0, -h * s, h * c, 0, ...p];
}

/**
 * The solid-angle lights of shaders/warpcore.wgsl against the module's `spherical*` methods:
 * `n` points per function (lights times samples on the 2^-24 grid away from 0, the inverses
 * on the module's own samples). Returns `{ adapter, rows }` as `check`.
 */
export async function checkSpherical(n = 1 << 14, edit = null) {
  const { wc, lib, device, adapter } = await setup('warpcore.wgsl', edit);
  const rows = [];
  const words = (a) => new Uint32Array(a.buffer.slice(a.byteOffset, a.byteOffset + a.byteLength));
  for (const [k, [name, js, shape, kind, outFloats]] of LIGHT_FUNCTIONS.entries()) {
    const next = rng(0x51fe ^ (k * 0x85ebca6b));
    const lights = LIGHTS[shape].map((l) => Float32Array.from(l));
    while (lights.length < 32) lights.push(Float32Array.from(randomLight(shape, next)));
    const extra = { u: 2, b: 3, st: 2, nu: 5, solid: 0 }[kind];
    const inw = 12 + extra;
    const input = new Uint32Array(n * inw);
    const want = new Uint32Array(n * outFloats);
    if (kind === 'solid') {
      // Each point a light seen from a moved shading point.
      for (let i = 0; i < n; i++) {
        const l = Float32Array.from(lights[i % lights.length]);
        if (i >= lights.length) for (let c = 9; c < 12; c++) l[c] = Math.fround(l[c] + (((next() >>> 8) / 16777216) - 0.5) * 0.5);
        input.set(words(l), i * inw);
        want[i] = words(Float32Array.of(wc[js](l)))[0];
      }
    } else {
      const per = n / lights.length;
      for (const [j, light] of lights.entries()) {
        const u = square(per, next);
        let arg = u;
        let jsLight = light;
        if (kind === 'b' || kind === 'st') {
          // The module's own samples: barycentrics or (s, t).
          const fwd = wc[shape === 'triangle' ? 'sphericalTriangle' : 'sphericalRectangle'](light, u);
          const m = kind === 'b' ? 3 : 2;
          const step = kind === 'b' ? 4 : 3;
          arg = new Float32Array(per * m);
          for (let i = 0; i < per; i++) for (let c = 0; c < m; c++) arg[i * m + c] = fwd[i * step + c];
        }
        let normal = null;
        if (kind === 'nu') {
          const r = (lo, hi) => lo + ((hi - lo) * (next() >>> 8)) / 16777216;
          normal = Float32Array.of(r(-0.5, 0.5), r(-0.5, 0.5), r(0.2, 1));
          jsLight = Float32Array.of(...light, ...normal);
        }
        const out = wc[js](jsLight, arg);
        const m = arg.length / per;
        for (let i = 0; i < per; i++) {
          const p = j * per + i;
          input.set(words(light), p * inw);
          if (normal) input.set(words(normal), p * inw + 12);
          input.set(words(arg.subarray(i * m, (i + 1) * m)), p * inw + inw - m);
          want.set(words(out.subarray(i * outFloats, (i + 1) * outFloats)), p * outFloats);
        }
      }
    }
    const f = (k) => `bitcast<f32>(wc_in[b + ${k}u])`;
    const v3 = (k) => `vec3<f32>(${f(k)}, ${f(k + 1)}, ${f(k + 2)})`;
    const v2 = (k) => `vec2<f32>(${f(k)}, ${f(k + 1)})`;
    const light = `${v3(0)}, ${v3(3)}, ${v3(6)}, ${v3(9)}`;
    const call = {
      solid: `${name}(${light})`,
      u: `${name}(${light}, ${v2(12)})`,
      st: `${name}(${light}, ${v2(12)})`,
      b: `${name}(${light}, ${v3(12)})`,
      nu: `${name}(${light}, ${v3(12)}, ${v2(15)})`,
    }[kind];
    const writes = (outFloats === 1 ? [''] : ['.x', '.y', '.z', '.w'].slice(0, outFloats)).map((c) => `bitcast<u32>(r${c})`);
    const code = computeShader(lib, 'wc_check_main', [0, 1], inw, outFloats, callBody(call, writes));
    const got = await run(device, code, input, n, n * outFloats);
    rows.push(row(name, got, want, outFloats, input, inw));
  }
  return { adapter, rows };
}

// shaders/warpcore_tables.wgsl: the compute shader around one check's body (reads wc_in[b + k],
// writes wc_out[o + k]); the library's wc_tables is binding 0.
const tablesShader = (lib, inw, outw, body) => computeShader(lib, 'wc_check_main', [1, 2], inw, outw, body);

const SAMPLER_BODY = `    var s = wc_sampler_new(wc_in[b], vec2<u32>(wc_in[b + 1u], wc_in[b + 2u]), wc_in[b + 3u], wc_in[b + 4u], wc_in[b + 5u]);
    s = wc_sampler_domain(s, wc_in[b + 6u]);
    s = wc_sampler_split(s, wc_in[b + 7u], 4u, 3u);
    s = wc_sampler_domain(s, wc_in[b + 8u]);
    let d = wc_sampler_draw4_u32(s);
    let e = wc_sampler_draw2(s);
    let r = wc_sampler_rnd4(s);
    wc_out[o] = d.x; wc_out[o + 1u] = d.y; wc_out[o + 2u] = d.z; wc_out[o + 3u] = d.w;
    wc_out[o + 4u] = bitcast<u32>(e.x); wc_out[o + 5u] = bitcast<u32>(e.y);
    wc_out[o + 6u] = bitcast<u32>(r.x); wc_out[o + 7u] = bitcast<u32>(r.y);
    wc_out[o + 8u] = bitcast<u32>(r.z); wc_out[o + 9u] = bitcast<u32>(r.w);`;

/**
 * Checks shaders/warpcore_tables.wgsl with shaders/warpcore_tables.bin bound: pmj02bn points
 * (three runs of `n` consecutive indices) and, per pattern, `n` sampler paths
 * `domain(k1).split(k2, 4, 3).domain(k3)` (draw4_u32, draw2, rnd4), against the JavaScript
 * module. Returns `{ adapter, rows }` as `check` does. `corrupt` flips the top bit of every
 * pmj02bn table word before the upload (the test's check that the comparison sees the tables).
 */
export async function checkTables(n = 1 << 12, corrupt = false) {
  const { wc, lib, device, adapter } = await setup('warpcore_tables.wgsl');
  const bin = await (await fetch(new URL('../../shaders/warpcore_tables.bin', import.meta.url))).arrayBuffer();
  if (corrupt) {
    const w = new Uint32Array(bin, 0, 2 * wc.pmj02bnSets * wc.pmj02bnPoints);
    for (let i = 0; i < w.length; i++) w[i] ^= 0x80000000;
  }
  const tables = device.createBuffer({ size: bin.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(tables, 0, bin);
  const words = (a) => new Uint32Array(a.buffer.slice(a.byteOffset, a.byteOffset + a.byteLength));
  const rows = [];
  const pmjBody = '    let r = wc_pmj02bn_sample(wc_in[b], wc_in[b + 1u]);\n    wc_out[o] = bitcast<u32>(r.x);\n    wc_out[o + 1u] = bitcast<u32>(r.y);';
  for (const [start, seed] of [[0, 0], [3 * wc.pmj02bnPoints - 100, 0xdeadbeef], [2 ** 32 - n / 2, 0xffffffff]]) {
    const input = new Uint32Array(2 * n);
    for (let i = 0; i < n; i++) input.set([(start + i) >>> 0, seed], 2 * i);
    const want = words(wc.pmj02bnSample(start, seed, n));
    const got = await run(device, tablesShader(lib, 2, 2, pmjBody), input, n, 2 * n, [[0, tables]], 1);
    rows.push(row(`wc_pmj02bn_sample from ${start}`, got, want, 2));
  }
  for (const [id, pattern] of ['pmj02bn', 'sobol', 'bluePmj02bn', 'blueSobol'].entries()) {
    const next = rng(0x2545f491 ^ (id * 0x9e3779b9));
    const input = new Uint32Array(9 * n);
    const want = new Uint32Array(10 * n);
    for (let i = 0; i < n; i++) {
      const w = [id, next(), next(), next(), i % 2 ? next() : i, i % 3 ? next() : 0, next(), next(), next()];
      if (i % 4 === 0) [w[1], w[2]] = [w[1] & 63, w[2] & 63];
      input.set(w, 9 * i);
      const path = wc.samplerPath().domain(w[6]).split(w[7], 4, 3).domain(w[8]);
      const args = [pattern, new Uint32Array([w[1], w[2]]), w[3], w[4], w[5], path];
      want.set(wc.samplerDrawU32(...args, 4), 10 * i);
      want.set(words(wc.samplerDraw(...args, 2)), 10 * i + 4);
      want.set(words(wc.samplerRnd(...args, 4)), 10 * i + 6);
    }
    const got = await run(device, tablesShader(lib, 9, 10, SAMPLER_BODY), input, n, 10 * n, [[0, tables]], 1);
    rows.push(row(`wc_sampler_* ${pattern}`, got, want, 10));
  }
  return { adapter, rows };
}

/**
 * Checks shaders/warpcore_envmap.wgsl: maps built by the JavaScript module (hierarchical and
 * marginal-conditional, their `storage()` words bound at binding 1), `n` random points each,
 * `sample` (uv, pdf, texel) and `pdf`, against the module. Returns `{ adapter, rows }` as
 * `check` does, with the largest difference of a `uv` coordinate and of a pdf (relative).
 */
export async function checkEnvmap(n = 1 << 12) {
  const { wc, lib, device, adapter } = await setup('warpcore_envmap.wgsl');
  const next = rng(0x51ed);
  const maps = [];
  for (const [w, h] of [[4, 2], [13, 7], [64, 32], [300, 7]]) {
    const weights = new Float32Array(w * h);
    for (let i = 0; i < weights.length; i++) weights[i] = i % 5 === 0 ? 0 : (next() >>> 8) / 2 ** 24 * 2 ** ((next() % 20) - 10);
    maps.push(['hierarchical', wc.envmapHierarchical(weights, w, h)]);
    maps.push(['marginal_conditional', wc.envmapMarginalConditional(weights, w, h)]);
  }
  const storages = maps.map(([, m]) => m.storage());
  if (storages[0][1] !== 3) throw new Error(`the JS module writes storage version ${storages[0][1]}, the shader reads 3: rebuild js/warpcore.wasm (js/build.sh)`);
  const total = storages.reduce((s, a) => s + a.length, 0);
  const words = new Uint32Array(total);
  const bases = [];
  let at = 0;
  for (const s of storages) {
    bases.push(at);
    words.set(s, at);
    at += s.length;
  }
  const envBuf = device.createBuffer({ size: words.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(envBuf, 0, words);
  const rows = [];
  for (const [kind, sample] of [['hierarchical', true], ['hierarchical', false], ['marginal_conditional', true], ['marginal_conditional', false]]) {
    const name = `wc_envmap_${kind}_${sample ? 'sample' : 'pdf'}`;
    const outw = sample ? 5 : 1;
    const chunks = [];
    const wants = [];
    for (const [k, [mk, map]] of maps.entries()) {
      if (mk !== kind) continue;
      const u = square(n, next);
      const input = new Uint32Array(3 * n);
      const uw = new Uint32Array(u.buffer);
      for (let i = 0; i < n; i++) input.set([bases[k], uw[2 * i], uw[2 * i + 1]], 3 * i);
      chunks.push(input);
      const want = new Uint32Array(outw * n);
      if (sample) {
        const s = map.sample(u);
        const uvw = new Uint32Array(s.uv.buffer);
        const pw = new Uint32Array(s.pdf.buffer);
        for (let i = 0; i < n; i++) want.set([uvw[2 * i], uvw[2 * i + 1], pw[i], s.texel[2 * i], s.texel[2 * i + 1]], 5 * i);
      } else {
        want.set(new Uint32Array(map.pdf(u).buffer));
      }
      wants.push(want);
    }
    const input = new Uint32Array(chunks.reduce((s, c) => s + c.length, 0));
    const want = new Uint32Array(wants.reduce((s, c) => s + c.length, 0));
    chunks.reduce((o, c) => (input.set(c, o), o + c.length), 0);
    wants.reduce((o, c) => (want.set(c, o), o + c.length), 0);
    const call = `${name}(wc_in[b], vec2<f32>(bitcast<f32>(wc_in[b + 1u]), bitcast<f32>(wc_in[b + 2u])))`;
    const writes = sample ? ['bitcast<u32>(r.uv.x)', 'bitcast<u32>(r.uv.y)', 'bitcast<u32>(r.pdf)', 'r.texel.x', 'r.texel.y'] : ['bitcast<u32>(r)'];
    const code = computeShader(lib, 'wc_check_main', [2, 3], 3, outw, callBody(call, writes));
    const points = want.length / outw;
    const got = await run(device, code, input, points, want.length, [[1, envBuf]], 2);
    const f = (x) => new Float32Array(new Uint32Array([x]).buffer)[0];
    let texelMismatches = 0;
    let maxUv = 0;
    let maxPdf = 0;
    for (let p = 0; p < points; p++) {
      const g = got.subarray(p * outw, (p + 1) * outw);
      const e = want.subarray(p * outw, (p + 1) * outw);
      if (sample) {
        if (g[3] !== e[3] || g[4] !== e[4]) texelMismatches++;
        maxUv = Math.max(maxUv, Math.abs(f(g[0]) - f(e[0])), Math.abs(f(g[1]) - f(e[1])));
      }
      const pg = f(g[sample ? 2 : 0]);
      const pe = f(e[sample ? 2 : 0]);
      maxPdf = Math.max(maxPdf, pe === 0 ? (pg === 0 ? 0 : Infinity) : Math.abs(pg - pe) / pe);
    }
    rows.push([...row(name, got, want, outw), texelMismatches, maxUv, maxPdf]);
  }
  for (const [, m] of maps) m.free();
  return { adapter, rows };
}
