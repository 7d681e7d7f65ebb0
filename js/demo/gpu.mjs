// The demo's "computed on the GPU" mode: the selected warp's points computed by a WebGPU
// compute shader built from shaders/warpcore.wgsl (or shaders/warpcore_envmap.wgsl with the
// map's storage words bound) plus a small entry point, one point per invocation. The square's
// points (or Basu-Owen's indices) come from the page as for the CPU path; every output word is
// then compared with the wasm module's, so the page can say how many points have the same bits.
//
// The entry point reads `wc_in` (u32 words, `inWords` per point) and writes `wc_out` (`outWords`
// per point); bindings 2 and 3, so that binding 1 stays warpcore_envmap.wgsl's. The shader and
// dispatch helpers (`library`, `computeShader`, `createPipeline`, `runCompute`) are
// gpu/browser/webgpu-check.mjs's too.

/**
 * The WGSL function of each demo warp: [function, input kind, output words per point].
 * Kinds: `square` (u: 2 words), `quadrant` (u and the quadrant: 3 words), `index` (index and
 * seed: 2 words), `envmap` (u: 2 words; writes uv, pdf and texel).
 */
export const WGSL = {
  'disk:polar': ['wc_disk_polar', 'square', 2],
  'disk:concentric': ['wc_disk_concentric', 'square', 2],
  'disk:polar4': ['wc_disk_polar4', 'quadrant', 2],
  'disk:concentric4': ['wc_disk_concentric4', 'quadrant', 2],
  'triangle:uniform': ['wc_triangle_uniform', 'square', 3],
  'triangle:sqrt': ['wc_triangle_sqrt_map', 'square', 3],
  'triangle:basu_owen': ['wc_triangle_basu_owen', 'index', 3],
  'triangle:basu_owen_permuted': ['wc_triangle_basu_owen_permuted', 'index', 3],
  'sphere:equal_area': ['wc_sphere_equal_area', 'square', 3],
  'sphere:equirect': ['wc_sphere_equirect', 'square', 3],
  'sphere:uniform': ['wc_sphere_uniform', 'square', 3],
  'sphere:uniform_hemisphere': ['wc_sphere_uniform_hemisphere', 'square', 3],
  'sphere:cosine_hemisphere': ['wc_sphere_cosine_hemisphere', 'square', 3],
  'envmap:hierarchical:latlong': ['wc_envmap_hierarchical_sample', 'envmap', 5],
  'envmap:marginal:latlong': ['wc_envmap_marginal_conditional_sample', 'envmap', 5],
  'envmap:hierarchical:equal_area': ['wc_envmap_hierarchical_sample', 'envmap', 5],
  'envmap:marginal:equal_area': ['wc_envmap_marginal_conditional_sample', 'envmap', 5],
};

/** Why a warp has no GPU path (null when it has one). */
export const unsupported = (warp) => (WGSL[warp] ? null : 'this warp has no WGSL version yet');

/**
 * Opens WebGPU: `{ device, adapter: "vendor architecture" }`, or `{ reason }` saying in a few
 * words why the mode is unavailable.
 */
export async function openGpu() {
  if (!globalThis.isSecureContext) return { reason: 'WebGPU needs a secure context (https or localhost)' };
  if (!navigator.gpu) return { reason: 'this browser has no WebGPU (navigator.gpu)' };
  let adapter;
  try {
    adapter = await navigator.gpu.requestAdapter();
  } catch (e) {
    return { reason: `requestAdapter failed: ${e?.message ?? e}` };
  }
  if (!adapter) return { reason: 'WebGPU found no adapter' };
  try {
    const device = await adapter.requestDevice();
    const info = adapter.info ?? {};
    const name = [info.vendor, info.architecture, info.description].filter(Boolean).join(' ') || 'unnamed adapter';
    return { device, adapter: name, fallback: Boolean(info.isFallbackAdapter) };
  } catch (e) {
    return { reason: `requestDevice failed: ${e?.message ?? e}` };
  }
}

const libraries = new Map(); // file -> Promise<string>
/**
 * The text of `shaders/${file}` (fetched once); `edit` ([from, to], or null) replaces a string
 * of it (the browser tests' check that a comparison sees a one-ulp change).
 */
export async function library(file, edit = null) {
  if (!libraries.has(file)) {
    libraries.set(
      file,
      fetch(new URL(`../../shaders/${file}`, import.meta.url)).then((r) => {
        if (!r.ok) throw new Error(`shaders/${file}: ${r.status}`);
        return r.text();
      }),
    );
  }
  const lib = await libraries.get(file);
  if (!edit) return lib;
  if (!lib.includes(edit[0])) throw new Error(`not in the library: ${edit[0]}`);
  return lib.replace(edit[0], edit[1]);
}

/**
 * A compute shader: the library `lib`, `wc_in` (u32 words, `inWords` per point) and `wc_out`
 * (`outWords` per point) at the bindings `[in, out]` of group 0, and the entry point `entry`,
 * which runs `body` for point `i`, its input words at `wc_in[b + k]`, its output words at
 * `wc_out[o + k]`.
 */
export function computeShader(lib, entry, [inBinding, outBinding], inWords, outWords, body) {
  return `${lib}
@group(0) @binding(${inBinding}) var<storage, read> wc_in: array<u32>;
@group(0) @binding(${outBinding}) var<storage, read_write> wc_out: array<u32>;
@compute @workgroup_size(64)
fn ${entry}(@builtin(global_invocation_id) gid: vec3<u32>) {
    let i = gid.x;
    if (i >= arrayLength(&wc_out) / ${outWords}u) { return; }
    let b = i * ${inWords}u;
    let o = i * ${outWords}u;
${body}
}
`;
}

/** A `computeShader` body: `let r = call;`, then the output words `writes` of `r`. */
export const callBody = (call, writes) =>
  [`    let r = ${call};`, ...writes.map((w, k) => `    wc_out[o + ${k}u] = ${w};`)].join('\n');

/** The compute shader of one warp: the library, then the entry point `wc_demo_main`. */
export function shaderSource(lib, fn, kind, outWords) {
  const f = (k) => `bitcast<f32>(wc_in[b + ${k}u])`;
  const u = `vec2<f32>(${f(0)}, ${f(1)})`;
  const inWords = kind === 'quadrant' ? 3 : 2;
  const call = {
    square: `${fn}(${u})`,
    quadrant: `${fn}(${u}, wc_in[b + 2u])`,
    index: `${fn}(wc_in[b], wc_in[b + 1u])`,
    envmap: `${fn}(0u, ${u})`,
  }[kind];
  const writes =
    kind === 'envmap'
      ? ['bitcast<u32>(r.uv.x)', 'bitcast<u32>(r.uv.y)', 'bitcast<u32>(r.pdf)', 'r.texel.x', 'r.texel.y']
      : ['x', 'y', 'z'].slice(0, outWords).map((c) => `bitcast<u32>(r.${c})`);
  return computeShader(lib, 'wc_demo_main', [2, 3], inWords, outWords, callBody(call, writes));
}

/** The compute pipeline of `code`'s entry point `entry`, or an error with the validation message. */
export async function createPipeline(device, code, entry) {
  device.pushErrorScope('validation');
  const module = device.createShaderModule({ code });
  const p = device.createComputePipeline({ layout: 'auto', compute: { module, entryPoint: entry } });
  const error = await device.popErrorScope();
  if (error) throw new Error(`the compute shader ${entry}: ${error.message}`);
  return p;
}

const pipelines = new WeakMap(); // device -> Map(code -> Promise<GPUComputePipeline>)
function pipeline(device, code) {
  if (!pipelines.has(device)) pipelines.set(device, new Map());
  const cache = pipelines.get(device);
  if (!cache.has(code)) {
    cache.set(code, createPipeline(device, code, 'wc_demo_main'));
    cache.get(code).catch(() => cache.delete(code));
  }
  return cache.get(code);
}

/**
 * Runs `pipeline` over `n` points (64 per workgroup): `input` at binding `inBinding`, the
 * output (`outWords` words in all) at the next binding, and the buffers `bound` (`[binding,
 * GPUBuffer]`) besides. Resolves to the output words (`Uint32Array`).
 */
export async function runCompute(device, pipeline, bound, inBinding, input, n, outWords) {
  const inBuf = device.createBuffer({ size: Math.max(4, input.byteLength), usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
  device.queue.writeBuffer(inBuf, 0, input);
  const size = 4 * outWords;
  const outBuf = device.createBuffer({ size, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
  const readBuf = device.createBuffer({ size, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
  const entries = [
    ...bound.map(([binding, buffer]) => ({ binding, resource: { buffer } })),
    { binding: inBinding, resource: { buffer: inBuf } },
    { binding: inBinding + 1, resource: { buffer: outBuf } },
  ];
  const bind = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
  const enc = device.createCommandEncoder();
  const pass = enc.beginComputePass();
  pass.setPipeline(pipeline);
  pass.setBindGroup(0, bind);
  pass.dispatchWorkgroups(Math.ceil(n / 64));
  pass.end();
  enc.copyBufferToBuffer(outBuf, 0, readBuf, 0, size);
  device.queue.submit([enc.finish()]);
  await readBuf.mapAsync(GPUMapMode.READ);
  const out = new Uint32Array(readBuf.getMappedRange().slice(0));
  readBuf.unmap();
  for (const b of [inBuf, outBuf, readBuf]) b.destroy();
  return out;
}

const envBuffers = new WeakMap(); // EnvMap -> GPUBuffer of its storage words
function envBuffer(device, env) {
  if (!envBuffers.has(env)) {
    const words = env.storage();
    const buf = device.createBuffer({ size: words.byteLength, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_DST });
    device.queue.writeBuffer(buf, 0, words);
    envBuffers.set(env, buf);
  }
  return envBuffers.get(env);
}

/**
 * Runs `warp` on the GPU: `input` holds the per-point words of its kind (see `WGSL`), `n`
 * points; `env` is the EnvMap for the environment-map warps. `edit` ([from, to], or null)
 * replaces a string of the library first (the browser test's check that the comparison sees a
 * one-ulp change). Resolves to the output words (`Uint32Array`, `outWords` per point).
 */
export async function runWarp(device, warp, input, n, { env = null, edit = null } = {}) {
  const [fn, kind, outWords] = WGSL[warp];
  const lib = await library(kind === 'envmap' ? 'warpcore_envmap.wgsl' : 'warpcore.wgsl', edit);
  const p = await pipeline(device, shaderSource(lib, fn, kind, outWords));
  const bound = kind === 'envmap' ? [[1, envBuffer(device, env)]] : [];
  return runCompute(device, p, bound, 2, input, n, outWords * n);
}

/** Points (`words` per point) whose every word is the same in `a` and `b`. */
export function identicalPoints(a, b, words) {
  let same = 0;
  for (let p = 0; p < a.length / words; p++) {
    let k = 0;
    while (k < words && a[p * words + k] === b[p * words + k]) k++;
    if (k === words) same++;
  }
  return same;
}
