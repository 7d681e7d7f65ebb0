// Runs in a page (served from the repository root): evaluates functions of
// shaders/warpcore.wgsl with WebGPU and compares every output word with the JavaScript module
// (js/warpcore.mjs, the crate compiled to wasm). Inputs stay away from subnormals, which
// SwiftShader (Chromium's software adapter) flushes to zero. See webgpu.test.mjs.
import { load } from '../../js/warpcore.mjs';

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
  const comps =
    kind === 'quadrant-inverse'
      ? ['u.x', 'u.y', 'quadrant']
      : outFloats === 1
        ? ['']
        : ['x', 'y', 'z'].slice(0, outFloats);
  const word = (c) => (c === 'quadrant' ? 'r.quadrant' : `bitcast<u32>(r${c ? '.' + c : ''})`);
  return `${lib}
@group(0) @binding(0) var<storage, read> wc_in: array<u32>;
@group(0) @binding(1) var<storage, read_write> wc_out: array<u32>;
@compute @workgroup_size(64)
fn wc_check_main(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= arrayLength(&wc_out) / ${outFloats}u) { return; }
    let b = i * ${inw}u;
    let r = ${call};
${comps.map((c, k) => `    wc_out[i * ${outFloats}u + ${k}u] = ${word(c)};`).join('\n')}
}
`;
}

async function runOnGpu(device, code, input, outWords) {
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const pipeline = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: 'wc_check_main' } });
  const error = await device.popErrorScope();
  if (error) throw new Error(error.message);
  const inBuf = device.createBuffer({ size: input.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(inBuf, 0, input);
  const size = outWords * 4;
  const outBuf = device.createBuffer({ size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  const readBuf = device.createBuffer({ size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const bind = device.createBindGroup({
    layout: pipeline.getBindGroupLayout(0),
    entries: [
      { binding: 0, resource: { buffer: inBuf } },
      { binding: 1, resource: { buffer: outBuf } },
    ],
  });
  const enc = device.createCommandEncoder();
  const pass = enc.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(0, bind);
  pass.dispatchWorkgroups(Math.ceil(outWords / 64));
  pass.end();
  enc.copyBufferToBuffer(outBuf, 0, readBuf, 0, size);
  device.queue.submit([enc.finish()]);
  await readBuf.mapAsync(GPUMapMode.READ);
  const out = new Uint32Array(readBuf.getMappedRange().slice(0));
  readBuf.unmap();
  return out;
}

/**
 * Checks every function on `n` points; returns `{ adapter, rows: [[name, points, mismatches,
 * first]] }`. `edit = [from, to]` replaces a string of the library first (the test's check that
 * a one-ulp change is seen).
 */
export async function check(n = 1 << 14, edit = null) {
  const wc = await load();
  let lib = await (await fetch(new URL('../../shaders/warpcore.wgsl', import.meta.url))).text();
  if (edit) {
    if (!lib.includes(edit[0])) throw new Error(`not in the library: ${edit[0]}`);
    lib = lib.replace(edit[0], edit[1]);
  }
  const adapter = await navigator.gpu.requestAdapter();
  if (!adapter) throw new Error('no WebGPU adapter');
  const device = await adapter.requestDevice();
  const info = adapter.info ?? {};
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
    // The point count is the output's, which the entry point bounds by (n threads).
    const got = await runOnGpu(device, shader(lib, name, kind, outFloats), input, n * outFloats);
    let mismatches = 0;
    let first = null;
    for (let p = 0; p < n; p++) {
      for (let w = 0; w < outFloats; w++) {
        if (got[p * outFloats + w] !== want[p * outFloats + w]) {
          mismatches++;
          first ??= { point: p, got: Array.from(got.subarray(p * outFloats, (p + 1) * outFloats)), want: Array.from(want.subarray(p * outFloats, (p + 1) * outFloats)) };
          break;
        }
      }
    }
    rows.push([name, n, mismatches, first]);
  }
  return { adapter: `${info.vendor} ${info.architecture} (fallback ${info.isFallbackAdapter})`, rows };
}
