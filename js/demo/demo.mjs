// The live demo: points of the unit square from a sampler, warped to a domain (disk, triangle,
// sphere, environment map) by warpcore, drawn over the images of one elementary grid's strata.
//
// Strata are drawn by inverting the warp at every pixel (the library's inverse warps, one batch
// per picture): a pixel takes the colour of the stratum its preimage falls in. Basu-Owen has no
// square preimage: its strata are the level-2 (or level-4) sub-triangles, coloured by the index
// of the first point landing in each, as in the report. Environment maps are sampled forward:
// each cell of a fine grid of the square maps to the rectangle between its corners' images when
// both land in one texel (both distributions are affine inside a texel), else it is split.
//
// "Computed on the GPU" (the checkbox, enabled where WebGPU gives an adapter): the same
// points of the square go through the warp's WGSL function (./gpu.mjs, shaders/warpcore.wgsl
// or shaders/warpcore_envmap.wgsl) in a WebGPU compute shader; the page draws the GPU's points
// and says how many have the same bits, every output word, as the wasm module's.
//
// State for tests: `window.demo` ({ frame, drawn, expected, positions, error, ready, gpu }),
// `gpu` = { available, reason, adapter, on, identical, points, failed }; `demo.gpuEdit = [from, to]`
// edits the WGSL library before the next GPU frame (the browser test's sharpness check).
import { load } from '../warpcore.mjs';
import { identicalPoints, openGpu, runWarp, unsupported, WGSL } from './gpu.mjs';

const $ = (id) => document.getElementById(id);
const canvas = $('canvas');
const ctx = canvas.getContext('2d', { willReadFrequently: true });
const demo = (window.demo = {
  frame: 0,
  drawn: 0,
  expected: 0,
  positions: new Float32Array(0),
  error: null,
  ready: null,
  gpu: { available: false, reason: 'checking WebGPU', adapter: null, on: false, identical: null, points: null, failed: null },
  gpuEdit: null,
});
let gpu = null; // { device, adapter } once WebGPU is open

// ---- the report's palette (report/src/strata.rs): golden-angle hues ----

function hsv(h, s, v) {
  const i = Math.floor(h * 6);
  const f = h * 6 - i;
  const [p, q, t] = [v * (1 - s), v * (1 - f * s), v * (1 - (1 - f) * s)];
  const rgb = [[v, t, p], [q, v, p], [p, v, t], [p, q, v], [t, p, v], [v, p, q]][((i % 6) + 6) % 6];
  return rgb.map((x) => Math.min(255, Math.max(0, Math.round(x * 255))));
}
const palette = (i) => {
  const h = (i * 0.61803398875 + 0.05) % 1;
  return i % 2 === 0 ? hsv(h, 0.65, 0.95) : hsv(h, 0.8, 0.75);
};

// ---- state from the controls (and the query string) ----

const controls = ['sampler', 'warp', 'map', 'count', 'grid', 'seed'];
function readState() {
  const [k, l] = $('grid').value.split('x').map(Number);
  let n = Math.round(Number($('count').value));
  if (!Number.isFinite(n)) n = 256;
  n = Math.min(4096, Math.max(4, n));
  let seed = Math.round(Number($('seed').value));
  if (!Number.isFinite(seed) || seed < 0 || seed > 0xffffffff) seed = 7;
  const warp = $('warp').value;
  const onGpu = $('gpu').checked && gpu !== null && !unsupported(warp);
  return { sampler: $('sampler').value, warp, map: $('map').value, n, k, l, seed, gpu: onGpu };
}
function applyQuery() {
  const q = new URLSearchParams(location.search);
  for (const id of controls) if (q.has(id)) $(id).value = q.get(id);
  $('gpu').checked = q.get('gpu') === '1';
  $('count-range').value = Math.log2(Number($('count').value) || 256);
}
function writeQuery(s) {
  const q = new URLSearchParams({ sampler: s.sampler, warp: s.warp, count: s.n, grid: `${s.k}x${s.l}`, seed: s.seed });
  if (s.warp.startsWith('envmap')) q.set('map', s.map);
  if ($('gpu').checked) q.set('gpu', '1');
  history.replaceState(null, '', `?${q}`);
}

// ---- views: a domain drawn on the canvas ----

// A disk of radius r at (cx, cy): disk points <-> pixels.
const diskView = (W, H, cx, cy, r) => ({ W, H, toPixel: (x, y) => [cx + r * x, cy - r * y], cx, cy, r });

// The triangle of the report's pictures: v0 top, v1 bottom left, v2 bottom right.
const TRI = [[0.5, 0.06], [0.03, 0.87], [0.97, 0.87]].map(([x, y]) => [40 + 560 * x, 40 + 560 * y]);
function triPixel(b0, b1, b2) {
  return [b0 * TRI[0][0] + b1 * TRI[1][0] + b2 * TRI[2][0], b0 * TRI[0][1] + b1 * TRI[1][1] + b2 * TRI[2][1]];
}
function pixelBary(px, py) {
  const [[x0, y0], [x1, y1], [x2, y2]] = TRI;
  const det = (y1 - y2) * (x0 - x2) + (x2 - x1) * (y0 - y2);
  const b0 = ((y1 - y2) * (px - x2) + (x2 - x1) * (py - y2)) / det;
  const b1 = ((y2 - y0) * (px - x2) + (x0 - x2) * (py - y2)) / det;
  return [b0, b1, 1 - b0 - b1];
}

// Sphere pictures: each hemisphere by Lambert's azimuthal equal-area projection (so equal
// areas on the sphere are equal areas in the picture), the upper seen from +z, the lower from -z.
const SPHERE = { W: 800, H: 420, r: 185, centres: [[205, 225], [595, 225]] };
const HEMI = { W: 640, H: 640, r: 290, centres: [[320, 320]] };
function directionToPixel(view, x, y, z) {
  const lower = z < 0 && view.centres.length > 1;
  const s = 1 / Math.sqrt(1 + Math.abs(z));
  const [cx, cy] = view.centres[lower ? 1 : 0];
  return [cx + view.r * x * s * (lower ? -1 : 1), cy - view.r * y * s];
}

// ---- the square's points ----

function squarePoints(wc, sampler, m, seed) {
  if (sampler === 'random') return wc.sequenceRandom(0, seed, m);
  if (sampler === 'stratified') return wc.sequenceStratified(0, m, seed, m);
  return wc.pmj02bnSample(0, seed, m);
}

// ---- strata pictures (cached: they depend on the warp, grid, seed and map, not the count) ----

const stratumOf = (u0, u1, k, l) => {
  const i = Math.min(k - 1, Math.max(0, Math.floor(u0 * k)));
  const j = Math.min(l - 1, Math.max(0, Math.floor(u1 * l)));
  return j * k + i;
};

function paintByInverse(image, pixels, preimage, k, l) {
  // pixels: [pixelIndex...]; preimage: Float32Array of 2 per pixel (u) or null entries
  const data = image.data;
  for (let p = 0; p < pixels.length; p++) {
    const [r, g, b] = palette(stratumOf(preimage[2 * p], preimage[2 * p + 1], k, l));
    const o = 4 * pixels[p];
    data[o] = r;
    data[o + 1] = g;
    data[o + 2] = b;
    data[o + 3] = 255;
  }
}

function diskStrata(wc, warp, view, k, l) {
  const image = new ImageData(view.W, view.H);
  const pixels = [];
  const pts = [];
  for (let py = 0; py < view.H; py++) {
    for (let px = 0; px < view.W; px++) {
      const x = (px + 0.5 - view.cx) / view.r;
      const y = -(py + 0.5 - view.cy) / view.r;
      if (x * x + y * y <= 1) {
        pixels.push(py * view.W + px);
        pts.push(x, y);
      }
    }
  }
  const p = new Float32Array(pts);
  const u = {
    polar: () => wc.diskPolarInverse(p),
    concentric: () => wc.diskConcentricInverse(p),
    polar4: () => wc.diskPolar4Inverse(p).u,
    concentric4: () => wc.diskConcentric4Inverse(p).u,
  }[warp]();
  paintByInverse(image, pixels, u, k, l);
  return image;
}

function triangleStrata(wc, warp, k, l, seed) {
  const image = new ImageData(640, 640);
  const pixels = [];
  const bary = [];
  for (let py = 0; py < 640; py++) {
    for (let px = 0; px < 640; px++) {
      const b = pixelBary(px + 0.5, py + 0.5);
      if (b[0] >= 0 && b[1] >= 0 && b[2] >= 0) {
        pixels.push(py * 640 + px);
        bary.push(...b);
      }
    }
  }
  const b = new Float32Array(bary);
  if (warp === 'uniform' || warp === 'sqrt') {
    const u = warp === 'uniform' ? wc.triangleUniformInverse(b) : wc.triangleSqrtMapInverse(b);
    paintByInverse(image, pixels, u, k, l);
    return image;
  }
  // Basu-Owen: level-L sub-triangles (16 or 256), each coloured by the first index in it.
  const level = k * l > 16 ? 4 : 2;
  const cells = 4 ** level;
  const first = (warp === 'basu_owen' ? wc.triangleBasuOwen : wc.triangleBasuOwenPermuted)(0, seed, cells);
  const owner = new Int32Array(cells).fill(-1);
  for (let i = cells - 1; i >= 0; i--) owner[subTriangle(first[3 * i], first[3 * i + 1], first[3 * i + 2], level)] = i;
  const data = image.data;
  for (let p = 0; p < pixels.length; p++) {
    const o = owner[subTriangle(b[3 * p], b[3 * p + 1], b[3 * p + 2], level)];
    const [r, g, bl] = o < 0 ? [200, 200, 200] : palette(o);
    data.set([r, g, bl, 255], 4 * pixels[p]);
  }
  return image;
}

// The level-`level` sub-triangle of the 4-way subdivision holding barycentrics (b0, b1, b2).
function subTriangle(b0, b1, b2, level) {
  let id = 0;
  for (let d = 0; d < level; d++) {
    let digit;
    if (b0 >= 0.5) [digit, b0, b1, b2] = [0, 2 * b0 - 1, 2 * b1, 2 * b2];
    else if (b1 >= 0.5) [digit, b0, b1, b2] = [1, 2 * b0, 2 * b1 - 1, 2 * b2];
    else if (b2 >= 0.5) [digit, b0, b1, b2] = [2, 2 * b0, 2 * b1, 2 * b2 - 1];
    else [digit, b0, b1, b2] = [3, 1 - 2 * b0, 1 - 2 * b1, 1 - 2 * b2];
    id = 4 * id + digit;
  }
  return id;
}

function sphereStrata(wc, warp, view, k, l) {
  const image = new ImageData(view.W, view.H);
  const pixels = [];
  const dirs = [];
  view.centres.forEach(([cx, cy], h) => {
    for (let py = 0; py < view.H; py++) {
      for (let px = 0; px < view.W; px++) {
        const X = (px + 0.5 - cx) / view.r;
        const Y = -(py + 0.5 - cy) / view.r;
        const r2 = X * X + Y * Y;
        if (r2 > 1) continue;
        const s = Math.sqrt(2 - r2);
        pixels.push(py * view.W + px);
        dirs.push(h === 1 ? -X * s : X * s, Y * s, h === 1 ? -(1 - r2) : 1 - r2);
      }
    }
  });
  const d = new Float32Array(dirs);
  const inverse = {
    equal_area: wc.sphereEqualAreaInverse,
    equirect: wc.sphereEquirectInverse,
    uniform: wc.sphereUniformInverse,
    uniform_hemisphere: wc.sphereUniformHemisphereInverse,
    cosine_hemisphere: wc.sphereCosineHemisphereInverse,
  }[warp];
  paintByInverse(image, pixels, inverse(d), k, l);
  return image;
}

// ---- environment maps ----

const maps = new Map(); // name -> Promise<{ width, height, rgb }>
function fetchMap(name) {
  if (!maps.has(name)) {
    maps.set(
      name,
      fetch(new URL(`../../tests/data/envmaps/${name}.pfm`, import.meta.url)).then(async (r) => {
        if (!r.ok) throw new Error(`${name}.pfm: ${r.status}`);
        return readPfm(new Uint8Array(await r.arrayBuffer()));
      }),
    );
  }
  return maps.get(name);
}

/** A PFM file (RGB, little-endian): width, height and RGB floats, rows top to bottom. */
export function readPfm(bytes) {
  const head = new TextDecoder('latin1').decode(bytes.subarray(0, 64));
  const m = /^PF\s+(\d+)\s+(\d+)\s+(-?[\d.]+)\s/.exec(head);
  if (!m || Number(m[3]) >= 0) throw new Error('not an RGB little-endian PFM file');
  const [w, h] = [Number(m[1]), Number(m[2])];
  const data = new Float32Array(bytes.buffer.slice(bytes.byteOffset + m[0].length, bytes.byteOffset + m[0].length + 12 * w * h));
  const rgb = new Float32Array(3 * w * h);
  for (let r = 0; r < h; r++) rgb.set(data.subarray(3 * w * r, 3 * w * (r + 1)), 3 * w * (h - 1 - r));
  return { width: w, height: h, rgb };
}

const envs = new Map(); // `${map}:${param}:${kind}` -> { env, width, height, grey }
async function envmapFor(wc, name, param, kind) {
  const key = `${name}:${param}:${kind}`;
  if (envs.has(key)) return envs.get(key);
  const { width, height, rgb } = await fetchMap(name);
  let w = width;
  let h = height;
  let weights;
  let lum;
  if (param === 'latlong') {
    lum = wc.envmapLuminance(rgb);
    weights = wc.envmapLatlongSolidAngleWeights(lum, w, h);
  } else {
    w = h = 256;
    lum = wc.envmapLuminance(wc.envmapLatlongToEqualArea(rgb, width, height, 3, w, 2));
    weights = lum; // equal-area texels all cover the same solid angle
  }
  const env = kind === 'hierarchical' ? wc.envmapHierarchical(weights, w, h) : wc.envmapMarginalConditional(weights, w, h);
  const sorted = Float32Array.from(lum).sort();
  const median = Math.max(sorted[sorted.length >> 1], 1e-30);
  const entry = { env, width: w, height: h, lum, median };
  envs.set(key, entry);
  return entry;
}

function envStrata(entry, view, k, l) {
  const { env, lum, median, width, height } = entry;
  const { W, H } = view;
  // The stratum painted at each pixel (-1: none), from cells of a 128 x 128 grid of the square,
  // each split (up to 4 times) while its corners land in different texels.
  const owner = new Int16Array(W * H).fill(-1);
  const fill = (x0, x1, y0, y1, stratum) => {
    const X1 = Math.min(W - 1, Math.floor(x1 * W));
    const Y1 = Math.min(H - 1, Math.floor(y1 * H));
    for (let y = Math.max(0, Math.floor(y0 * H)); y <= Y1; y++) {
      owner.fill(stratum, y * W + Math.max(0, Math.floor(x0 * W)), y * W + X1 + 1);
    }
  };
  const G = 128;
  let cells = new Float32Array(5 * G * G); // a0, a1, b0, b1, stratum
  for (let j = 0, c = 0; j < G; j++) {
    for (let i = 0; i < G; i++, c += 5) cells.set([i / G, (i + 1) / G, j / G, (j + 1) / G, stratumOf((i + 0.5) / G, (j + 0.5) / G, k, l)], c);
  }
  for (let depth = 0; cells.length > 0; depth++) {
    const n = cells.length / 5;
    const u = new Float32Array(4 * n);
    for (let c = 0; c < n; c++) {
      const e = 1e-3 * (cells[5 * c + 1] - cells[5 * c]);
      u[4 * c] = cells[5 * c] + e;
      u[4 * c + 1] = cells[5 * c + 2] + e;
      u[4 * c + 2] = cells[5 * c + 1] - e;
      u[4 * c + 3] = cells[5 * c + 3] - e;
    }
    const { uv, texel: t } = env.sample(u);
    const next = new Float32Array(depth < 4 ? 4 * cells.length : 0);
    let m = 0;
    for (let c = 0; c < n; c++) {
      const a0 = cells[5 * c], a1 = cells[5 * c + 1], b0 = cells[5 * c + 2], b1 = cells[5 * c + 3];
      const stratum = cells[5 * c + 4];
      const u0 = uv[4 * c], v0 = uv[4 * c + 1], u1 = uv[4 * c + 2], v1 = uv[4 * c + 3];
      const x0 = Math.min(u0, u1), x1 = Math.max(u0, u1), y0 = Math.min(v0, v1), y1 = Math.max(v0, v1);
      if (t[4 * c] === t[4 * c + 2] && t[4 * c + 1] === t[4 * c + 3]) {
        fill(x0, x1, y0, y1, stratum); // affine inside a texel: the rectangle between the corners
      } else if (depth < 4) {
        const am = (a0 + a1) / 2, bm = (b0 + b1) / 2;
        next.set([a0, am, b0, bm, stratum, am, a1, b0, bm, stratum, a0, am, bm, b1, stratum, am, a1, bm, b1, stratum], m);
        m += 20;
      } else if ((x1 - x0) * W < 4 && (y1 - y0) * H < 4) {
        fill(x0, x1, y0, y1, stratum); // neighbouring texels: a few pixels
      } else {
        fill(x0, x0, y0, y0, stratum);
        fill(x1, x1, y1, y1, stratum);
      }
    }
    cells = next.subarray(0, m);
  }
  // The map, tone-mapped (x / (1 + x) of the luminance over its median), grey, under the strata.
  const image = new ImageData(W, H);
  const data = image.data;
  const colours = Array.from({ length: k * l }, (_, i) => palette(i));
  for (let py = 0, p = 0; py < H; py++) {
    const row = Math.floor((py * height) / H) * width;
    for (let px = 0; px < W; px++, p++) {
      const x = Math.max(lum[row + Math.floor((px * width) / W)] / median, 0);
      const g = 255 * Math.pow(x / (1 + x), 1 / 2.2);
      const o = owner[p];
      const c = o < 0 ? null : colours[o];
      data[4 * p] = c ? 0.35 * g + 0.65 * c[0] : g;
      data[4 * p + 1] = c ? 0.35 * g + 0.65 * c[1] : g;
      data[4 * p + 2] = c ? 0.35 * g + 0.65 * c[2] : g;
      data[4 * p + 3] = 255;
    }
  }
  return image;
}

// ---- drawing ----

const strataCache = new Map();

async function draw(wc, s) {
  const t0 = performance.now();
  const [family, name, ...rest] = s.warp.split(':');
  let view;
  let strata;
  let positions;
  let note = '';
  const key = `${s.warp}|${s.k}x${s.l}|${family === 'triangle' ? s.seed : ''}|${family === 'envmap' ? s.map : ''}`;
  const cached = (f) => {
    if (!strataCache.has(key)) strataCache.set(key, f());
    return strataCache.get(key);
  };
  // The CPU (wasm) results, as output words in the GPU's layout (`words` per point), and the
  // input words of the warp's WGSL entry point (./gpu.mjs).
  let cpu;
  let gpuInput;
  let env = null;
  let dim;
  let toPixel;
  if (family === 'disk') {
    view = diskView(640, 640, 320, 320, 300);
    strata = cached(() => diskStrata(wc, name, view, s.k, s.l));
    const four = name === 'polar4' || name === 'concentric4';
    const u = squarePoints(wc, s.sampler, four ? Math.ceil(s.n / 4) : s.n, s.seed);
    cpu = four ? (name === 'polar4' ? wc.diskPolar4(u, s.n) : wc.diskConcentric4(u, s.n)) : name === 'polar' ? wc.diskPolar(u) : wc.diskConcentric(u);
    if (four) {
      // Sample i: point i / 4 of the square in quadrant i % 4 (the JS form's order).
      const uw = words(u);
      gpuInput = new Uint32Array(3 * s.n);
      for (let i = 0; i < s.n; i++) gpuInput.set([uw[2 * (i >> 2)], uw[2 * (i >> 2) + 1], i & 3], 3 * i);
    } else {
      gpuInput = words(u);
    }
    [dim, toPixel] = [2, (x, y) => view.toPixel(x, y)];
    if (four) note = `${Math.ceil(s.n / 4)} points of the square, four disk samples each (one per quadrant)`;
  } else if (family === 'triangle') {
    view = { W: 640, H: 640 };
    strata = cached(() => triangleStrata(wc, name, s.k, s.l, s.seed));
    if (name === 'uniform' || name === 'sqrt') {
      const u = squarePoints(wc, s.sampler, s.n, s.seed);
      cpu = name === 'uniform' ? wc.triangleUniform(u) : wc.triangleSqrtMap(u);
      gpuInput = words(u);
    } else {
      cpu = (name === 'basu_owen' ? wc.triangleBasuOwen : wc.triangleBasuOwenPermuted)(0, s.seed, s.n);
      gpuInput = new Uint32Array(2 * s.n);
      for (let i = 0; i < s.n; i++) gpuInput.set([i, s.seed], 2 * i);
      note = `index-driven (the sampler does not apply); strata: the ${s.k * s.l > 16 ? 256 : 16} level-${s.k * s.l > 16 ? 4 : 2} sub-triangles, coloured by the first index in each`;
    }
    [dim, toPixel] = [3, (b0, b1, b2) => triPixel(b0, b1, b2)];
  } else if (family === 'sphere') {
    view = name.endsWith('hemisphere') ? HEMI : SPHERE;
    strata = cached(() => sphereStrata(wc, name, view, s.k, s.l));
    const u = squarePoints(wc, s.sampler, s.n, s.seed);
    const f = {
      equal_area: wc.sphereEqualArea,
      equirect: wc.sphereEquirect,
      uniform: wc.sphereUniform,
      uniform_hemisphere: wc.sphereUniformHemisphere,
      cosine_hemisphere: wc.sphereCosineHemisphere,
    }[name];
    cpu = f(u);
    gpuInput = words(u);
    [dim, toPixel] = [3, (x, y, z) => directionToPixel(view, x, y, z)];
    note = view === SPHERE ? 'left: z >= 0 seen from +z; right: z < 0 seen from -z (Lambert equal-area projections)' : 'the upper hemisphere seen from +z (Lambert equal-area projection)';
  } else {
    const [param] = rest;
    const entry = await envmapFor(wc, s.map, param, name === 'hierarchical' ? 'hierarchical' : 'marginal-conditional');
    env = entry.env;
    view = param === 'latlong' ? { W: 800, H: 400 } : { W: 640, H: 640 };
    strata = cached(() => envStrata(entry, view, s.k, s.l));
    const u = squarePoints(wc, s.sampler, s.n, s.seed);
    const smp = entry.env.sample(u);
    // uv, pdf and texel per point (the WGSL WcEnvSample's words); the picture uses uv.
    const [uvw, pw] = [words(smp.uv), words(smp.pdf)];
    cpu = new Uint32Array(5 * s.n);
    for (let i = 0; i < s.n; i++) cpu.set([uvw[2 * i], uvw[2 * i + 1], pw[i], smp.texel[2 * i], smp.texel[2 * i + 1]], 5 * i);
    gpuInput = words(u);
    [dim, toPixel] = [5, (x, y) => [x * view.W, y * view.H]];
    note = param === 'latlong' ? `${s.map}.pfm, lat-long (u across, v down from +z), weights: luminance x solid angle` : `${s.map}.pfm resampled to the equal-area square (+z at the centre), weights: luminance`;
  }
  let values = new Float32Array(cpu.buffer, cpu.byteOffset, cpu.length);
  let gpuState = { on: false, identical: null, points: null, failed: null };
  if (s.gpu) {
    try {
      const out = await runWarp(gpu.device, s.warp, gpuInput, s.n, { env, edit: demo.gpuEdit });
      const identical = identicalPoints(out, words(cpu), WGSL[s.warp][2]);
      gpuState = { on: true, identical, points: s.n, failed: null };
      values = new Float32Array(out.buffer, out.byteOffset, out.length);
    } catch (e) {
      // The page stays usable: the CPU's points, and the reason in the readout.
      gpuState.failed = String(e?.message ?? e);
      console.error(e);
    }
  }
  positions = mapPairs(values, dim, toPixel);
  if (canvas.width !== view.W || canvas.height !== view.H) {
    canvas.width = view.W;
    canvas.height = view.H;
  }
  ctx.fillStyle = '#fff';
  ctx.fillRect(0, 0, view.W, view.H);
  ctx.putImageData(await strata, 0, 0);
  // In putImageData, transparent pixels replace the white: repaint them white underneath.
  ctx.globalCompositeOperation = 'destination-over';
  ctx.fillRect(0, 0, view.W, view.H);
  ctx.globalCompositeOperation = 'source-over';
  const radius = s.n <= 256 ? 3 : s.n <= 1024 ? 2 : 1.5;
  ctx.fillStyle = '#000';
  ctx.beginPath();
  let drawn = 0;
  for (let i = 0; i < positions.length; i += 2) {
    const [x, y] = [positions[i], positions[i + 1]];
    if (!(x >= 0 && x < view.W && y >= 0 && y < view.H)) continue;
    ctx.moveTo(x + radius, y);
    ctx.arc(x, y, radius, 0, 2 * Math.PI);
    drawn++;
  }
  ctx.fill();
  const ms = performance.now() - t0;
  const grid = `${s.k} x ${s.l}`;
  $('caption').textContent = `${s.warp.replace(/:/g, ' / ')} — ${s.n} samples (${family === 'triangle' && name.startsWith('basu') ? 'index-driven' : s.sampler}), seed ${s.seed}, strata of the ${grid} grid${note ? ` — ${note}` : ''}`;
  $('status').textContent = `drew ${drawn} points in ${ms.toFixed(1)} ms${gpuState.on ? ', computed on the GPU' : ''}`;
  const result = $('gpu-result');
  if (gpuState.on) {
    const all = gpuState.identical === gpuState.points;
    result.textContent = `${gpuState.identical} of ${gpuState.points} points identical to the wasm module's (the CPU path), bit for bit — computed on ${gpu.adapter}`;
    result.className = all ? 'same' : 'differ';
  } else if (gpuState.failed) {
    result.textContent = `the GPU run failed (${gpuState.failed}): these are the CPU's points`;
    result.className = 'differ';
  } else {
    result.textContent = '';
    result.className = '';
  }
  Object.assign(demo.gpu, gpuState);
  Object.assign(demo, { drawn, expected: s.n, positions, state: s, frame: demo.frame + 1 });
}

/** The words of a float array (a view, no copy). */
const words = (a) => new Uint32Array(a.buffer, a.byteOffset, a.length);

function mapPairs(values, dim, f) {
  const n = values.length / dim;
  const out = new Float32Array(2 * n);
  for (let i = 0; i < n; i++) {
    const [x, y] = f(...values.subarray(dim * i, dim * (i + 1)));
    out[2 * i] = x;
    out[2 * i + 1] = y;
  }
  return out;
}

// ---- wiring: redraw live on every change, one frame at a time ----

// The GPU checkbox: enabled where WebGPU gave a device and the warp has a WGSL version,
// otherwise disabled with the reason next to it.
function gpuControl(warp) {
  const box = $('gpu');
  const why = gpu === null ? demo.gpu.reason : unsupported(warp);
  box.disabled = why !== null;
  $('gpu-note').textContent = why === null ? `(${gpu.adapter})` : `(unavailable: ${why})`;
}

async function main() {
  applyQuery();
  const opening = openGpu().catch((e) => ({ reason: String(e?.message ?? e) }));
  const wc = await load();
  const g = await opening;
  if (g.device) {
    gpu = g;
    Object.assign(demo.gpu, { available: true, reason: null, adapter: g.adapter });
    g.device.lost.then((info) => {
      if (gpu !== g) return;
      gpu = null;
      Object.assign(demo.gpu, { available: false, reason: `the GPU device was lost: ${info.message || info.reason}` });
      gpuControl($('warp').value);
    });
  } else {
    $('gpu').checked = false;
    Object.assign(demo.gpu, { available: false, reason: g.reason });
  }
  gpuControl($('warp').value);
  let pending = false;
  let running = Promise.resolve();
  const schedule = () => {
    if (pending) return;
    pending = true;
    requestAnimationFrame(() => {
      pending = false;
      const s = readState();
      writeQuery(s);
      document.querySelectorAll('.envonly').forEach((e) => e.classList.toggle('hidden', !s.warp.startsWith('envmap')));
      gpuControl(s.warp);
      running = running.then(() => draw(wc, s)).catch(showError);
    });
  };
  $('count-range').addEventListener('input', () => {
    $('count').value = Math.round(2 ** Number($('count-range').value));
    schedule();
  });
  $('count').addEventListener('input', () => {
    const n = Number($('count').value);
    if (n >= 4 && n <= 4096) $('count-range').value = Math.log2(n);
    schedule();
  });
  for (const id of ['sampler', 'warp', 'map', 'grid', 'seed', 'gpu']) $(id).addEventListener('input', schedule);
  $('gpu').addEventListener('change', schedule);
  schedule();
}

function showError(e) {
  demo.error = String(e?.stack ?? e);
  $('error').textContent = `\n${demo.error}`;
  console.error(e);
}

demo.ready = main().catch(showError);
