// The determinism fingerprint computed through the JavaScript API: the same FNV-1a 64 hash
// over the same inputs as registry/src/fingerprint.rs (and its C port,
// capi/tests/c/fingerprint.c), every scalar and x8 call replaced by a JS call on 1 or 8
// points and every slice call by one JS call writing into an `out` subarray at an odd offset.
// It must equal tests/golden/fingerprint.txt, which the Rust tests check against the crate.
//
// Then the functions the fingerprint does not cover (and a real environment map), hashed the
// same way as the registry's pieces and compared with the hashes it exports
// (js/test/registry.json: each entry's golden hash, and the real map's).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { load } from '../warpcore.mjs';
import { Fnv } from './fnv.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const wasm = process.env.WARPCORE_WASM; // test another build (CI: the fresh one)
const wc = await load(wasm);

// ---- hashing and inputs, as in fingerprint.rs ----


// The inputs, as the registry exports them (registry/tests/fingerprint.rs writes
// js/test/registry.json and fails when it is stale): special values and lights as f32 bits.
const data = JSON.parse(readFileSync(new URL('./registry.json', import.meta.url), 'utf8'));
const SPECIAL_BITS = data.specials;
const S = SPECIAL_BITS.length;
const N = data.n;
assert.equal(N, 1024 + S * S);

function unit(i) {
  let x = (Math.imul(i, 747796405) + 2891336453) >>> 0;
  x = Math.imul(((x >>> ((x >>> 28) + 4)) ^ x) >>> 0, 277803737) >>> 0;
  x = (x ^ (x >>> 22)) >>> 0;
  return (x >>> 8) * 2 ** -24;
}

/** Points `first .. first + n` of dimension `D`, as a Float32Array. */
function inputs(first, n, D) {
  const f = new Float32Array(n * D);
  const bits = new Uint32Array(f.buffer);
  for (let k = 0; k < n; k++) {
    const i = first + k;
    for (let d = 0; d < D; d++) {
      if (i < S * S) {
        bits[k * D + d] = SPECIAL_BITS[d % 2 === 0 ? i % S : (Math.floor(i / S) + Math.floor(d / 2)) % S];
      } else {
        f[k * D + d] = unit(i * D + d);
      }
    }
  }
  return f;
}

// An `out` array at an odd float offset of a larger buffer.
const oddOut = (length) => new Float32Array(length + 1).subarray(1);

// ---- the two drivers of fingerprint.rs ----

function warp(h, call, I, O) {
  for (let i = 0; i < N; i += 37) {
    const n = Math.min(37, N - i);
    const input = inputs(i, n, I);
    const out = oddOut(n * O);
    assert.equal(call(input, out), out);
    h.word(n);
    for (let k = 0; k < n; k++) {
      h.floats(call(input.subarray(k * I, (k + 1) * I)));
      h.floats(out.subarray(k * O, (k + 1) * O));
    }
  }
  for (let g = 0; g + 8 <= N; g += 8) {
    const out8 = call(inputs(g, 8, I));
    const bits = new Uint32Array(out8.buffer);
    for (let c = 0; c < O; c++) for (let j = 0; j < 8; j++) h.word(bits[j * O + c]);
  }
}

// Quadrant `q` of a four-per-point warp, one point at a time.
const quadrant = (f, q) => (input, out) => {
  const n = input.length / 2;
  const result = out ?? new Float32Array(2 * n);
  for (let k = 0; k < n; k++) {
    const four = f(input.subarray(2 * k, 2 * k + 2), 4);
    result.set(four.subarray(2 * q, 2 * q + 2), 2 * k);
  }
  return result;
};

function indexed(h, f, O) {
  for (const seed of [0, 1, 0x9e3779b9, 0xffffffff]) {
    for (const start of [0, 5, 1023, 4090, 65530, 1 << 20, 0xffffffff - 20]) {
      const out = oddOut(37 * O);
      assert.equal(f(start, seed, 37, out), out);
      h.word(37);
      for (let k = 0; k < 37; k++) {
        h.floats(f((start + k) >>> 0, seed, 1));
        h.floats(out.subarray(k * O, (k + 1) * O));
      }
      const lanes = [];
      for (let j = 0; j < 8; j++) lanes.push(new Uint32Array(f((start + 3 * j) >>> 0, (seed ^ j) >>> 0, 1).buffer));
      for (let c = 0; c < O; c++) for (let j = 0; j < 8; j++) h.word(lanes[j][c]);
    }
  }
}

// Rust's `f as i32`: saturating, NaN to 0.
function saturatingI32(x) {
  if (Number.isNaN(x)) return 0;
  if (x >= 2147483648) return 2147483647;
  if (x <= -2147483904) return -2147483648;
  return Math.trunc(x);
}

/** The 13 x 7 map of the fingerprint: zeros, a negative texel, a NaN, a 10^6 : 1 texel. */
function envmapWeights() {
  const w = new Float32Array(91);
  for (let k = 0; k < 91; k++) {
    w[k] = [3, 40, 41].includes(k) ? 0 : k === 17 ? -2 : k === 60 ? NaN : k === 77 ? 1e6 : unit(k) + Math.fround(0.01); // an f32 sum
  }
  return w;
}

function envmap(h, build) {
  const env = build(envmapWeights(), 13, 7);
  try {
    for (let pass = 0; pass < 2; pass++) {
      // the scalar calls, then the x8 groups: the same points
      for (let i = 0; i < N; i++) {
        const s = env.sample(inputs(i, 1, 2));
        const p = env.pdf(s.uv);
        h.floats(new Float32Array([s.uv[0], s.uv[1], s.pdf[0], p[0]]));
        h.words(s.texel);
      }
    }
  } finally {
    env.free();
  }
}

// Lights for the spherical family, the registry's SPHERICAL_TRIANGLES (v0, v1, v2, p) and
// SPHERICAL_RECTANGLES (corner, ex, ey, p).
const lightsOf = (rows) => rows.map((l) => new Float32Array(Uint32Array.from(l).buffer));
const TRIANGLES = lightsOf(data.triangles);
const RECTANGLES = lightsOf(data.rectangles);
// The sphere lights (centre, [radius, 0, 0], -, p) as the 7 floats the JS functions take.
const CONES = lightsOf(data.cones).map((l) => Float32Array.of(l[0], l[1], l[2], l[3], l[9], l[10], l[11]));

// fingerprint.rs's `lights`: for each light l, the slice over all inputs in chunks of 37 and
// one call per input; then the lane forms as single calls, input i with light (l + i) % L.
function lights(h, ls, f, I, O) {
  const L = ls.length;
  for (let l = 0; l < L; l++) {
    for (let i = 0; i < N; i += 37) {
      const n = Math.min(37, N - i);
      const input = inputs(i, n, I);
      const out = oddOut(n * O);
      assert.equal(f(ls[l], input, out), out);
      h.word(n);
      for (let k = 0; k < n; k++) {
        h.floats(f(ls[l], input.subarray(k * I, (k + 1) * I)));
        h.floats(out.subarray(k * O, (k + 1) * O));
      }
    }
    for (let g = 0; g + 8 <= N; g += 8) {
      const lanes = [];
      for (let j = 0; j < 8; j++) lanes.push(new Uint32Array(f(ls[(l + g + j) % L], inputs(g + j, 1, I)).buffer));
      for (let c = 0; c < O; c++) for (let j = 0; j < 8; j++) h.word(lanes[j][c]);
    }
  }
}

// fingerprint.rs's `solid_angles`: every light, then lane j of group g holding light
// (g + j) % L, for 16 lanes and g < L.
function solidAngles(h, ls, f) {
  const L = ls.length;
  for (const l of ls) h.floats(Float32Array.of(f(l)));
  for (let g = 0; g < L; g++) for (let j = 0; j < 16; j++) h.floats(Float32Array.of(f(ls[(g + j) % L])));
}

function fingerprint() {
  const h = new Fnv();
  // disk
  warp(h, wc.diskPolar, 2, 2);
  warp(h, wc.diskConcentric, 2, 2);
  warp(h, wc.diskPolarInverse, 2, 2);
  warp(h, wc.diskConcentricInverse, 2, 2);
  for (let q = 0; q < 4; q++) warp(h, quadrant(wc.diskPolar4, q), 2, 2);
  for (let q = 0; q < 4; q++) warp(h, quadrant(wc.diskConcentric4, q), 2, 2);
  for (let i = 0; i < N; i++) {
    const { u, quadrant: q } = wc.diskConcentric4Inverse(inputs(i, 1, 2));
    h.floats(u);
    h.words(q);
  }
  const pts = inputs(0, 9, 2);
  for (const f of [wc.diskPolar4, wc.diskConcentric4]) {
    const out = f(pts, 35);
    h.word(out.length / 2);
    h.floats(out);
  }
  // pmj02bn
  indexed(h, wc.pmj02bnSample, 2);
  for (const [set, index] of [[0, 0], [1, 1], [3, 4095], [7, 1 << 30]]) h.words(wc.pmj02bnRaw(set, index, 1));
  // sampler (fingerprint.rs `sampler::<P>`): a slice is the points of new(...).domain(3), one
  // point (the scalar and lane forms) adds split(7, 4, index & 3); then draw_u32 and rnd of
  // 64 split states; then the same draws of domain 3 of a new_frame root without the split
  const domain3 = wc.samplerPath().domain(3);
  const frames3 = wc.samplerFramePath(1).domain(3);
  const split = [0, 1, 2, 3].map((sub) => domain3.split(7, 4, sub));
  const pixel = (seed) => Uint32Array.of(seed % 641, seed >>> 20);
  for (const pattern of ['pmj02bn', 'sobol', 'bluePmj02bn', 'blueSobol']) {
    indexed(h, (start, seed, n, out) => {
      const frame = (seed ^ 5) >>> 0;
      if (n === 1) return wc.samplerDraw(pattern, pixel(seed), frame, start, seed, split[start & 3], 4, out);
      return wc.samplerDrawSlice(pattern, pixel(seed), frame, start, n, seed, domain3, 4, out);
    }, 4);
    for (let k = 0; k < 64; k++) {
      const index = Math.imul(k, 0x9e3779b9) >>> 0;
      h.words(wc.samplerDrawU32(pattern, pixel(k), k ^ 5, index, k, split[index & 3], 4));
      h.floats(wc.samplerRnd(pattern, pixel(k), k ^ 5, index, k, split[index & 3], 4));
    }
    // domain 3 of a new_frame root (1 spp), no split: under blue noise a spatiotemporal slot
    indexed(h, (start, seed, n, out) => {
      const frame = (seed ^ 5) >>> 0;
      if (n === 1) return wc.samplerDraw(pattern, pixel(seed), frame, start, seed, frames3, 4, out);
      return wc.samplerDrawSlice(pattern, pixel(seed), frame, start, n, seed, frames3, 4, out);
    }, 4);
  }
  // sequence
  indexed(h, wc.sequenceRandom, 2);
  for (const count of [1, 16, 17, 1024]) {
    indexed(h, (start, seed, n, out) => wc.sequenceStratified(start, count, seed, n, out), 2);
  }
  // triangle
  warp(h, wc.triangleUniform, 2, 3);
  warp(h, wc.triangleUniformInverse, 3, 2);
  warp(h, wc.triangleSqrtMap, 2, 3);
  warp(h, wc.triangleSqrtMapInverse, 3, 2);
  indexed(h, wc.triangleBasuOwen, 3);
  indexed(h, wc.triangleBasuOwenPermuted, 3);
  // sphere
  warp(h, wc.sphereEqualArea, 2, 3);
  warp(h, wc.sphereEqualAreaInverse, 3, 2);
  warp(h, wc.sphereEqualAreaWrap, 2, 2);
  warp(h, wc.sphereEquirect, 2, 3);
  warp(h, wc.sphereEquirectInverse, 3, 2);
  warp(h, wc.sphereUniform, 2, 3);
  warp(h, wc.sphereUniformInverse, 3, 2);
  warp(h, wc.sphereUniformHemisphere, 2, 3);
  warp(h, wc.sphereUniformHemisphereInverse, 3, 2);
  warp(h, wc.sphereCosineHemisphere, 2, 3);
  warp(h, wc.sphereCosineHemisphereInverse, 3, 2);
  for (let i = 0; i < N; i++) {
    const d = inputs(i, 1, 3);
    const p = inputs(i, 1, 1);
    h.floats(wc.sphereEquirectPdfToSolidAngle(p, d));
    h.floats(wc.sphereEqualAreaPdfToSolidAngle(p));
    h.floats(wc.sphereCosineHemispherePdf(p));
    const t = inputs(i, 1, 2);
    const texel = Int32Array.from(t, (c) => (saturatingI32(Math.fround(c * 64)) - 16) | 0);
    h.words(wc.sphereEqualAreaWrapTexel(texel, 32));
  }
  // envmap
  envmap(h, wc.envmapMarginalConditional);
  envmap(h, wc.envmapHierarchical);
  // spherical
  lights(h, TRIANGLES, wc.sphericalTriangle, 2, 4);
  lights(h, TRIANGLES, wc.sphericalTriangleInverse, 3, 2);
  solidAngles(h, TRIANGLES, wc.sphericalTriangleSolidAngle);
  lights(h, RECTANGLES, wc.sphericalRectangle, 2, 3);
  lights(h, RECTANGLES, wc.sphericalRectangleInverse, 2, 2);
  solidAngles(h, RECTANGLES, wc.sphericalRectangleSolidAngle);
  return h.hex();
}

test('the golden fingerprint, computed through the JS API', () => {
  const golden = readFileSync(new URL('tests/golden/fingerprint.txt', `file://${root}`), 'utf8').trim();
  assert.match(golden, /^[0-9a-f]{16}$/);
  const before = wc.memoryStats().reserved;
  assert.equal(fingerprint(), golden);
  assert.equal(wc.memoryStats().reserved, before, 'every call released its scratch memory');
});

test('the FNV-1a 64 port matches known values', () => {
  // FNV-1a 64 of the empty input and of the bytes "a" (0x61), from the FNV reference.
  assert.equal(new Fnv().hex(), 'cbf29ce484222325');
  const h = new Fnv();
  h.word(0x61);
  // "a\0\0\0": reference values computed by the definition with BigInt, independently.
  let r = 0xcbf29ce484222325n;
  for (const b of [0x61, 0, 0, 0]) r = ((r ^ BigInt(b)) * 0x100000001b3n) & 0xffffffffffffffffn;
  assert.equal(h.hex(), r.toString(16).padStart(16, '0'));
});

// ---- the functions the fingerprint does not cover, against the Rust crate ----

const ENVMAP = `tests/data/envmaps/${data.envmap.name}.pfm`;

/** A PFM file (RGB, little-endian): width, height and RGB floats, rows top to bottom. */
export function readPfm(bytes) {
  const text = new TextDecoder('latin1').decode(bytes.subarray(0, 64));
  const m = /^PF\s+(\d+)\s+(\d+)\s+(-?[\d.]+)\s/.exec(text);
  assert.ok(m && Number(m[3]) < 0, 'an RGB little-endian PFM');
  const [w, h] = [Number(m[1]), Number(m[2])];
  const data = new Float32Array(bytes.buffer.slice(bytes.byteOffset + m[0].length, bytes.byteOffset + m[0].length + 12 * w * h));
  const rgb = new Float32Array(3 * w * h);
  for (let r = 0; r < h; r++) rgb.set(data.subarray(3 * w * r, 3 * w * (r + 1)), 3 * w * (h - 1 - r));
  return { width: w, height: h, rgb };
}

function jsExtras() {
  const hashes = {};
  const hash = (name, f) => {
    const h = new Fnv();
    f(h);
    hashes[name] = h.hex();
  };
  hash('disk::polar4_inverse', (h) => {
    const { u, quadrant: q } = wc.diskPolar4Inverse(inputs(0, N, 2));
    for (let i = 0; i < N; i++) {
      h.floats(u.subarray(2 * i, 2 * i + 2));
      h.word(q[i]);
    }
  });
  hash('pmj02bn::shuffle', (h) => {
    const idx = Uint32Array.from({ length: N }, (_, i) => Math.imul(i, 2654435761) >>> 0);
    h.words(wc.pmj02bnShuffle(idx, 0xabcd));
    h.word(wc.pmj02bnPoints);
    h.word(wc.pmj02bnSets);
  });
  hash('envmap::image::luminance', (h) => h.floats(wc.envmapLuminance(inputs(0, N, 3))));
  hash('spherical::cone', (h) => lights(h, CONES, wc.sphericalCone, 2, 4));
  hash('spherical::cone_inverse', (h) => lights(h, CONES, wc.sphericalConeInverse, 3, 2));
  hash('spherical::cone_solid_angle', (h) => solidAngles(h, CONES, wc.sphericalConeSolidAngle));
  hash('envmap::image::equirect_pdf_to_solid_angle', (h) => {
    const pv = inputs(0, N, 2);
    const pdf = pv.filter((_, k) => k % 2 === 0);
    const v = pv.filter((_, k) => k % 2 === 1);
    h.floats(wc.envmapEquirectPdfToSolidAngle(pdf, v));
  });
  hash('envmap::image::equirect_solid_angle_weights', (h) => {
    h.floats(wc.envmapEquirectSolidAngleWeights(envmapWeights(), 13, 7));
    h.floats(wc.envmapEquirectToEqualArea(inputs(200, 91, 3), 13, 7, 3, 8, 3));
  });
  hash('envmap::MarginalConditional::new', (h) => {
    const env = wc.envmapMarginalConditional(envmapWeights(), 13, 7);
    h.words(env.storage());
    env.free();
  });
  // lights (registry/src/fingerprint.rs `lights_alias`, `light_set`, `lights_tree`): every
  // float operation of the Rust inputs rounded to f32 as it is there.
  const r = Math.fround;
  hash('lights::AliasTable::sample', (h) => {
    const ab = inputs(3000, 97, 2);
    const weights = new Float32Array(97);
    for (let k = 0; k < 97; k++) {
      const [a, b] = [ab[2 * k], ab[2 * k + 1]];
      weights[k] = k % 7 === 3 ? 0 : k % 5 === 0 ? r(r(a * 1000) + b) : r(r(a * r(0.01)) + r(b * 0.5));
    }
    const table = wc.lightsAlias(weights);
    h.word(table.storageLength);
    h.words(table.storage());
    const s = table.sample(inputs(0, N, 1));
    for (let i = 0; i < N; i++) {
      h.word(s.index[i]);
      h.floats(s.prob.subarray(i, i + 1));
    }
    h.floats(table.pmf(Uint32Array.from({ length: 98 }, (_, k) => k)));
    table.free();
  });
  hash('lights::LightTree::sample', (h) => {
    const x = inputs(1000, 24, 8);
    const lights = new Float32Array(13 * 24);
    for (let k = 0; k < 24; k++) {
      const [cx, cy, cz, s, a0, a1, a2, q] = x.subarray(8 * k, 8 * k + 8);
      const c = [r(r(cx * 8) - 4), r(r(cy * 4) - 2), r(cz * 2)];
      const hh = r(s * 0.25);
      const cone = [[1, 0, 0], [1, 0, 1], [r(0.8), r(0.6), 0], [-1, 0, 0]][k % 4];
      const power = k % 11 === 5 ? 0 : r(r(0.1) + r(q * 10));
      lights.set([r(c[0] - hh), r(c[1] - hh), c[2], r(c[0] + hh), r(c[1] + hh), r(c[2] + hh), power, r(a0 - 0.5), r(a1 - 0.5), r(a2 - 0.25), ...cone], 13 * k);
    }
    const tree = wc.lightsTree(lights);
    h.word(tree.storageLength);
    h.words(tree.storage());
    const pin = inputs(2000, 64, 7);
    const p = new Float32Array(3 * 64);
    const n = new Float32Array(3 * 64);
    const u = new Float32Array(64);
    const index = new Uint32Array(64);
    for (let k = 0; k < 64; k++) {
      const [px, py, pz, nx, ny, nz, uk] = pin.subarray(7 * k, 7 * k + 7);
      p.set([r(r(px * 10) - 5), r(r(py * 6) - 3), r(r(pz * 4) - 1)], 3 * k);
      if (k % 3 !== 0) n.set([r(nx - 0.5), r(ny - 0.5), r(nz - 0.5)], 3 * k);
      u[k] = uk;
      index[k] = k % 25;
    }
    const s = tree.sample(p, n, u);
    const q = tree.pmf(p, n, index);
    for (let k = 0; k < 64; k++) {
      h.word(s.index[k]);
      h.floats(new Float32Array([s.prob[k], q[k]]));
    }
    tree.free();
  });
  const { width, height, rgb } = readPfm(readFileSync(root + ENVMAP));
  const weights = wc.envmapEquirectSolidAngleWeights(wc.envmapLuminance(rgb), width, height);
  const u = wc.pmj02bnSample(0, 7, 4096);
  for (const [name, build] of [
    ['hierarchical', wc.envmapHierarchical],
    ['marginalConditional', wc.envmapMarginalConditional],
  ]) {
    hash(name, (h) => {
      const env = build(weights, width, height);
      const s = env.sample(u);
      const p = env.pdf(s.uv);
      for (let i = 0; i < 4096; i++) {
        h.floats(new Float32Array([s.uv[2 * i], s.uv[2 * i + 1], s.pdf[i], p[i]]));
        h.words(s.texel.subarray(2 * i, 2 * i + 2));
      }
      env.free();
    });
  }
  return hashes;
}

test('functions outside the fingerprint equal their registry hashes', () => {
  const got = jsExtras();
  const want = { hierarchical: data.envmap.hierarchical, marginalConditional: data.envmap.marginalConditional };
  for (const e of data.entries) if (e.name in got) want[e.name] = e.hash;
  assert.equal(Object.keys(want).length, 13);
  assert.deepEqual(got, want);
});
