// The JavaScript API's contract: every function checks its arguments (TypeError for a wrong
// type, RangeError for a bad count or length, never a wasm trap), `load()` accepts every kind
// of source, outputs go into `out` when given, scratch memory is released, env maps own and
// free their tables, and results agree with independent references.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { load, MAX_COUNT } from '../warpcore.mjs';
import { pointMaps } from './methods.mjs';

const wasmUrl = process.env.WARPCORE_WASM ? pathToFileURL(process.env.WARPCORE_WASM) : new URL('../warpcore.wasm', import.meta.url);
const wc = await load(wasmUrl);
const f32 = (...v) => new Float32Array(v);

// Argument kinds of every function: a valid value, and the bad values with the error each must
// throw. `vec(T, d, n)`: a T with n elements of d values.
const vec = (T, d, n = 3) => ({ T, d, good: () => new T(d * n).fill(0.25) });
const COUNT = { count: true, good: () => 5 };
const U32 = { u32: true, good: () => 7 };
// A light and shading point of the solid-angle functions (12 floats).
const LIGHT = { T: Float32Array, d: 12, good: () => Float32Array.of(0, 0, 1, 1, 0, 1, 0, 1, 1, 0.2, 0.2, 0) };
// The cosine-aware ones: the receiver's normal after the point (15 floats).
// A sphere light: centre, radius, p (7 floats).
const SPHERE7 = { T: Float32Array, d: 7, good: () => Float32Array.of(0, 0, 3, 1, 0.1, 0.2, 0) };
const LIGHT15 = { T: Float32Array, d: 15, good: () => Float32Array.of(0, 0, 1, 1, 0, 1, 0, 1, 1, 0.2, 0.2, 0, 0, 0, 1) };

const STORAGE = (() => {
  const env = wc.envmapHierarchical(new Float32Array(4).fill(1), 2, 2);
  const words = env.storage();
  env.free();
  return words;
})();

// Point lights (13 floats each: min, max, power, axis, cosThetaO, cosThetaE, twoSided) at
// pseudo-random places, powers 1 .. 4; `bound(k, i, v, ...)`: light k's field i set to v.
const POINT_LIGHTS = (() => {
  const a = new Float32Array(13 * 6);
  for (let k = 0; k < 6; k++) {
    const c = [((k * 37) % 11) - 5, ((k * 53) % 7) - 3, ((k * 29) % 5) - 2];
    a.set([...c, ...c, 1 + (k % 4), 0, 0, 1, -1, 0, 0], 13 * k);
  }
  return a;
})();
const bound = (k, ...fields) => {
  const a = POINT_LIGHTS.slice(0, 26);
  for (let j = 0; j < fields.length; j += 2) a[13 * k + fields[j]] = fields[j + 1];
  return a;
};
const ALIAS_STORAGE = (() => {
  const a = wc.lightsAlias(f32(1, 0, 2, 5));
  const words = a.storage();
  a.free();
  return words;
})();
const TREE_STORAGE = (() => {
  const t = wc.lightsTree(POINT_LIGHTS);
  const words = t.storage();
  t.free();
  return words;
})();

const SPEC = {
  ...pointMaps((d) => vec(Float32Array, d)),
  diskPolar4: [vec(Float32Array, 2), COUNT],
  diskConcentric4: [vec(Float32Array, 2), COUNT],
  sphericalTriangle: [LIGHT, vec(Float32Array, 2)],
  sphericalTriangleInverse: [LIGHT, vec(Float32Array, 3)],
  sphericalRectangle: [LIGHT, vec(Float32Array, 2)],
  sphericalRectangleInverse: [LIGHT, vec(Float32Array, 2)],
  sphericalTriangleSolidAngle: [LIGHT],
  sphericalRectangleSolidAngle: [LIGHT],
  sphericalTriangleCosine: [LIGHT15, vec(Float32Array, 2)],
  sphericalRectangleCosine: [LIGHT15, vec(Float32Array, 2)],
  sphericalCone: [SPHERE7, vec(Float32Array, 2)],
  sphericalConeInverse: [SPHERE7, vec(Float32Array, 3)],
  sphericalConeSolidAngle: [SPHERE7],
  triangleBasuOwen: [U32, U32, COUNT],
  triangleBasuOwenPermuted: [U32, U32, COUNT],
  sphereEqualAreaWrapTexel: [vec(Int32Array, 2), U32],
  pmj02bnSample: [U32, U32, COUNT],
  pmj02bnRaw: [U32, U32, COUNT],
  pmj02bnShuffle: [vec(Uint32Array, 1), U32],
  sequenceRandom: [U32, U32, COUNT],
  sequenceStratified: [U32, U32, U32, COUNT],
  envmapEquirectSolidAngleWeights: [{ T: Float32Array, d: 6, good: () => new Float32Array(6).fill(1) }, { u32: true, good: () => 3 }, { u32: true, good: () => 2 }],
  envmapEquirectToEqualArea: [
    { T: Float32Array, d: 18, good: () => new Float32Array(18).fill(1) },
    { u32: true, good: () => 3 },
    { u32: true, good: () => 2 },
    { u32: true, good: () => 3 },
    { u32: true, good: () => 4 },
    { u32: true, good: () => 2 },
  ],
  envmapHierarchical: [{ T: Float32Array, d: 6, good: () => new Float32Array(6).fill(1) }, { u32: true, good: () => 3 }, { u32: true, good: () => 2 }],
  envmapMarginalConditional: [{ T: Float32Array, d: 6, good: () => new Float32Array(6).fill(1) }, { u32: true, good: () => 3 }, { u32: true, good: () => 2 }],
  ...Object.fromEntries(['envmapHierarchicalCompensated', 'envmapMarginalConditionalCompensated'].map((name) => [name, [
    { T: Float32Array, d: 6, good: () => new Float32Array(6).fill(1) },
    { u32: true, good: () => 3 },
    { u32: true, good: () => 2 },
    { good: () => 'uniform', bad: [['Uniform', RangeError], ['', RangeError], [1, TypeError], [null, TypeError], [undefined, TypeError]] },
    { good: () => 1, bad: [['1', TypeError], [1n, TypeError], [null, TypeError], [undefined, TypeError], [{}, TypeError]] },
  ]])),
  // Words as a Uint32Array, or the bytes of any ArrayBufferView or ArrayBuffer.
  envmapFromStorage: [{
    good: () => STORAGE.slice(),
    bad: [
      [Array.from(STORAGE), TypeError], [null, TypeError], [undefined, TypeError], ['abc', TypeError], [{}, TypeError],
      [new Uint8Array(4 * STORAGE.length + 1), RangeError], // not whole words
      [new DataView(new ArrayBuffer(4 * STORAGE.length)), RangeError], // zeros: not a storage
      [new Float32Array(STORAGE.length), RangeError],
    ],
  }],
  // Light selection: weights (one per light), bounds (13 floats per light), storage words.
  lightsAlias: [{ T: Float32Array, d: 1, good: () => f32(1, 0, 2), bad: [...badValues({ T: Float32Array, d: 1, good: () => f32(1, 0, 2) }), [f32(), RangeError], [f32(1, NaN), RangeError], [f32(1, -1), RangeError], [f32(Infinity), RangeError], [f32(0, 0), RangeError]] }],
  lightsTree: [{ T: Float32Array, d: 13, good: () => POINT_LIGHTS.slice(0, 26), bad: [...badValues({ T: Float32Array, d: 13, good: () => POINT_LIGHTS.slice(0, 26) }), [f32(), RangeError], [bound(0, 6, NaN), RangeError], [bound(0, 0, 5), RangeError], [bound(0, 11, 2), RangeError], [bound(0, 7, 0, 8, 0, 9, 0), RangeError]] }],
  ...Object.fromEntries([['lightsAliasFromStorage', () => ALIAS_STORAGE], ['lightsTreeFromStorage', () => TREE_STORAGE]].map(([name, words]) => [name, [{
    good: () => words().slice(),
    bad: [
      [Array.from(words()), TypeError], [null, TypeError], [undefined, TypeError], ['abc', TypeError], [{}, TypeError],
      [new Uint8Array(4 * words().length + 1), RangeError],
      [new DataView(new ArrayBuffer(4 * words().length)), RangeError],
      [new Float32Array(words().length), RangeError],
      [STORAGE.slice(), RangeError], // an env map's storage
      [(name === 'lightsTreeFromStorage' ? ALIAS_STORAGE : TREE_STORAGE).slice(), RangeError],
    ],
  }]])),
  memoryStats: [],
  // The sampler (js/test/sampler.test.mjs tests its arguments in depth).
  samplerPath: [],
  samplerFramePath: [U32],
  ...Object.fromEntries(['samplerDraw', 'samplerDrawU32', 'samplerRnd', 'samplerDrawSlice'].map((name) => [name, [
    { good: () => 'sobol', bad: [['Sobol', RangeError], [0, TypeError], [null, TypeError], [undefined, TypeError]] },
    { T: Uint32Array, d: 2, good: () => Uint32Array.of(3, 4) },
    U32,
    ...(name === 'samplerDrawSlice' ? [U32, COUNT] : [U32]),
    U32,
    { T: Uint32Array, d: 1, good: () => Uint32Array.of(1, 2) },
    { good: () => 2, bad: [[0, RangeError], [5, RangeError], [1.5, RangeError], ['2', TypeError], [undefined, TypeError]] },
  ]])),
};
const VALUES = ['pmj02bnPoints', 'pmj02bnSets', 'EnvMap', 'AliasTable', 'LightTree'];

/** Calls `f` and returns the error it throws (failing if it throws none or a wasm trap). */
function thrown(f, what) {
  try {
    f();
  } catch (e) {
    assert.ok(!(e instanceof WebAssembly.RuntimeError), `${what}: a wasm trap (${e.message})`);
    return e;
  }
  assert.fail(`${what}: no error`);
}

function badValues(spec) {
  if (spec.bad) return spec.bad;
  if (spec.count || spec.u32) {
    const max = spec.count ? MAX_COUNT : 0xffffffff;
    return [
      [-1, RangeError], [1.5, RangeError], [NaN, RangeError], [Infinity, RangeError], [max + 1, RangeError],
      ['4', TypeError], [4n, TypeError], [null, TypeError], [undefined, spec.count ? null : TypeError], [{}, TypeError],
    ];
  }
  const other = spec.T === Float32Array ? Float64Array : Float32Array;
  const n = spec.good().length;
  const bad = [
    [Array.from(spec.good()), TypeError], [null, TypeError], [undefined, TypeError], ['abc', TypeError],
    [new other(n), TypeError], [new DataView(new ArrayBuffer(4 * n)), TypeError], [new spec.T(n).buffer, TypeError],
  ];
  if (spec.d > 1) bad.push([new spec.T(n + 1), RangeError], [new spec.T(n - 1), RangeError]);
  return bad;
}

test('every function of the API has an argument spec, and valid calls succeed', () => {
  for (const [name, value] of Object.entries(wc)) {
    if (VALUES.includes(name)) continue;
    assert.equal(typeof value, 'function', name);
    assert.ok(SPEC[name], `no argument spec for ${name}`);
    const result = value(...SPEC[name].map((s) => s.good()));
    if (result instanceof wc.EnvMap || result instanceof wc.AliasTable || result instanceof wc.LightTree) result.free();
  }
  assert.deepEqual(Object.keys(wc).filter((k) => !(k in SPEC)).sort(), [...VALUES].sort());
  assert.ok(Object.isFrozen(wc));
});

test('bad arguments throw TypeError or RangeError, never a wasm trap, and leak nothing', (t) => {
  const before = wc.memoryStats().reserved;
  let cases = 0;
  for (const [name, specs] of Object.entries(SPEC)) {
    specs.forEach((spec, k) => {
      for (const [value, Want] of badValues(spec)) {
        if (Want === null) continue; // an optional argument
        const args = specs.map((s) => s.good());
        args[k] = value;
        const e = thrown(() => wc[name](...args), `${name} argument ${k} = ${String(value)}`);
        assert.equal(e.constructor, Want, `${name} argument ${k} = ${String(value)}: ${e.message}`);
        cases++;
      }
    });
  }
  assert.ok(cases > 400, `${cases} cases`);
  t.diagnostic(`${cases} bad-argument cases`);
  assert.equal(wc.memoryStats().reserved, before);
});

test('wrong `out` arrays throw; a right one receives the result and is returned', () => {
  const u = wc.pmj02bnSample(0, 3, 16);
  for (const [name, O] of [['diskConcentric', 2], ['sphereEqualArea', 3], ['triangleUniform', 3]]) {
    assert.equal(thrown(() => wc[name](u, new Float32Array(16 * O + 1)), name).constructor, RangeError);
    assert.equal(thrown(() => wc[name](u, new Float64Array(16 * O)), name).constructor, TypeError);
    assert.equal(thrown(() => wc[name](u, [0]), name).constructor, TypeError);
    const out = new Float32Array(16 * O + 2).subarray(1, 1 + 16 * O);
    assert.equal(wc[name](u, out), out);
    assert.deepEqual(out, wc[name](u));
  }
  const out = new Float32Array(8);
  assert.equal(wc.pmj02bnSample(0, 3, 4, out), out);
  assert.deepEqual(out, u.subarray(0, 8));
  assert.equal(thrown(() => wc.pmj02bnSample(0, 3, 4, new Float32Array(7)), 'pmj').constructor, RangeError);
});

test('counts: zero gives empty arrays, too large throws RangeError before touching memory', () => {
  assert.deepEqual(wc.diskConcentric(new Float32Array(0)), new Float32Array(0));
  assert.deepEqual(wc.pmj02bnSample(0, 0, 0), new Float32Array(0));
  assert.deepEqual(wc.diskPolar4(new Float32Array(0)), new Float32Array(0));
  const memory = wc.memoryStats().memory;
  for (const n of [2 ** 30, 2 ** 31, MAX_COUNT]) {
    for (const f of [() => wc.pmj02bnSample(0, 0, n), () => wc.triangleBasuOwen(0, 0, n), () => wc.sequenceStratified(0, 16, 0, n)]) {
      const e = thrown(f, `n = ${n}`);
      assert.equal(e.constructor, RangeError, e.message);
    }
  }
  assert.equal(wc.memoryStats().memory, memory, 'a refused call does not grow the memory');
  // polar4: n beyond four samples per point
  assert.equal(thrown(() => wc.diskPolar4(new Float32Array(4), 9), 'polar4').constructor, RangeError);
  assert.equal(wc.diskPolar4(new Float32Array(4), 8).length, 16);
  assert.equal(wc.diskPolar4(new Float32Array(4)).length, 16);
  // paired arrays of different counts
  assert.equal(thrown(() => wc.sphereEquirectPdfToSolidAngle(f32(1, 2), f32(0, 0, 1)), 'pair').constructor, RangeError);
  assert.equal(thrown(() => wc.envmapEquirectPdfToSolidAngle(f32(1, 2), f32(0.5)), 'pair').constructor, RangeError);
  assert.equal(thrown(() => wc.sphereEqualAreaWrapTexel(new Int32Array(2), 0), 'size 0').constructor, RangeError);
  assert.equal(thrown(() => wc.envmapEquirectToEqualArea(new Float32Array(18), 3, 2, 5, 4, 2), 'channels').constructor, RangeError);
});

test('large batches grow the memory, and match the same points computed in pieces', () => {
  const n = 300_000; // 7.2 MB of output: beyond the module's initial memory
  const all = wc.triangleBasuOwen(12345, 99, n);
  const piece = wc.triangleBasuOwen(12345 + 200_000, 99, 1000);
  assert.deepEqual(piece, all.subarray(3 * 200_000, 3 * 201_000));
  const u = wc.sequenceRandom(0, 5, n);
  const d = wc.sphereEqualArea(u);
  assert.deepEqual(wc.sphereEqualArea(u.subarray(2 * 123_456, 2 * 123_460)), d.subarray(3 * 123_456, 3 * 123_460));
});

test('indices wrap after 2^32 - 1, as in C', () => {
  const a = wc.pmj02bnSample(0xffffffff - 1, 11, 4);
  assert.deepEqual(a.subarray(4, 8), wc.pmj02bnSample(0, 11, 2));
});

test('load() accepts a URL, a path, bytes, a Response, a promise and a Module', async () => {
  const bytes = readFileSync(wasmUrl);
  const module = new WebAssembly.Module(bytes);
  assert.deepEqual(WebAssembly.Module.imports(module), [], 'the module has no imports');
  const want = wc.pmj02bnSample(0, 1, 8);
  const response = () => new Response(bytes, { headers: { 'content-type': 'application/wasm' } });
  const sources = [
    wasmUrl,
    wasmUrl.href,
    fileURLToPath(wasmUrl),
    bytes,
    new Uint8Array(bytes).buffer,
    response(),
    new Response(bytes), // no wasm content type: compiled from the bytes
    Promise.resolve(response()),
    module,
  ];
  if (!process.env.WARPCORE_WASM) sources.push(undefined);
  for (const source of sources) {
    const other = await load(source);
    assert.deepEqual(other.pmj02bnSample(0, 1, 8), want);
  }
  await assert.rejects(load(42), TypeError);
  await assert.rejects(load(new Response('no', { status: 404 })), /404/);
  await assert.rejects(load(new Uint8Array([0, 97, 115, 109, 9, 9, 9, 9])), WebAssembly.CompileError);
});

test('independent references: concentric map in f64, pmj02bn strata, barycentrics', () => {
  // The concentric map against the textbook formula in f64.
  const n = 64 * 64;
  const u = new Float32Array(2 * n);
  for (let i = 0; i < 64; i++) for (let j = 0; j < 64; j++) u.set([(i + 0.37) / 64, (j + 0.61) / 64], 2 * (64 * i + j));
  const p = wc.diskConcentric(u);
  let worst = 0;
  for (let k = 0; k < n; k++) {
    const a = 2 * u[2 * k] - 1;
    const b = 2 * u[2 * k + 1] - 1;
    const [r, phi] = Math.abs(a) > Math.abs(b) ? [a, (Math.PI / 4) * (b / a)] : [b, Math.PI / 2 - (Math.PI / 4) * (a / b)];
    worst = Math.max(worst, Math.abs(p[2 * k] - r * Math.cos(phi)), Math.abs(p[2 * k + 1] - r * Math.sin(phi)));
  }
  assert.ok(worst <= 2.5e-7, `max error ${worst}`);
  // Every power-of-two prefix of a pmj02bn sequence is a (0,m,2)-net.
  for (const seed of [0, 1, 0xdeadbeef]) {
    for (const m of [0, 2, 4, 7, 10]) {
      const pts = wc.pmj02bnSample(0, seed, 2 ** m);
      for (let k = 0; k <= m; k++) {
        const [nx, ny] = [2 ** k, 2 ** (m - k)];
        const seen = new Set();
        for (let i = 0; i < 2 ** m; i++) seen.add(Math.floor(pts[2 * i] * nx) + nx * Math.floor(pts[2 * i + 1] * ny));
        assert.equal(seen.size, 2 ** m, `seed ${seed}, 2^${m} points, ${nx} x ${ny} grid`);
      }
    }
  }
  // Barycentrics are non-negative and sum to 1; Basu-Owen's first 4^k points are one per
  // level-k sub-triangle (distinct centroids of a 4^k subdivision: distinct cells of size 2^-k).
  for (const b of [wc.triangleUniform(wc.sequenceRandom(0, 3, 1000)), wc.triangleBasuOwen(0, 9, 1000)]) {
    for (let i = 0; i < 1000; i++) {
      const s = b[3 * i] + b[3 * i + 1] + b[3 * i + 2];
      assert.ok(b[3 * i] >= 0 && b[3 * i + 1] >= 0 && b[3 * i + 2] >= 0 && Math.abs(s - 1) < 1e-6);
    }
  }
  // Round trips through the inverses.
  const v = wc.sequenceRandom(0, 8, 500);
  for (const [fwd, inv] of [['sphereEqualArea', 'sphereEqualAreaInverse'], ['diskPolar', 'diskPolarInverse'], ['triangleUniform', 'triangleUniformInverse']]) {
    const back = wc[inv](wc[fwd](v));
    for (let i = 0; i < v.length; i++) assert.ok(Math.abs(back[i] - v[i]) < 1e-4, `${fwd} round trip`);
  }
  const { u: back, quadrant } = wc.diskPolar4Inverse(wc.diskPolar4(v.subarray(0, 2)));
  assert.deepEqual([...quadrant], [0, 1, 2, 3]);
  for (let q = 0; q < 4; q++) for (const c of [0, 1]) assert.ok(Math.abs(back[2 * q + c] - v[c]) < 1e-5);
});

test('EnvMap: sampling, pdf, storage round trip, errors, free', () => {
  const before = wc.memoryStats().reserved;
  const w = new Float32Array(8 * 4).map((_, k) => (k === 13 ? 100 : k % 5));
  for (const build of [wc.envmapHierarchical, wc.envmapMarginalConditional]) {
    const env = build(w, 8, 4);
    assert.ok(env instanceof wc.EnvMap);
    assert.equal(env.width, 8);
    assert.equal(env.height, 4);
    const u = wc.pmj02bnSample(0, 2, 4096);
    const s = env.sample(u);
    assert.deepEqual(env.pdf(s.uv), s.pdf, 'pdf(uv) equals the sample pdf bit for bit');
    let hits13 = 0;
    for (let i = 0; i < 4096; i++) {
      const [c, r] = [s.texel[2 * i], s.texel[2 * i + 1]];
      assert.ok(w[r * 8 + c] > 0, 'never a zero-weight texel');
      assert.equal(c, Math.floor(s.uv[2 * i] * 8));
      assert.equal(r, Math.floor(s.uv[2 * i + 1] * 4));
      if (r * 8 + c === 13) hits13++;
    }
    const total = w.reduce((a, b) => a + b, 0);
    assert.ok(Math.abs(hits13 / 4096 - 100 / total) < 0.01, `texel 13: ${hits13 / 4096} vs ${100 / total}`);
    // Storage: a copy; loaded again (with and without verify), it samples the same bits.
    const words = env.storage();
    assert.equal(words.length, env.storageLength);
    for (const verify of [true, false]) {
      const again = wc.envmapFromStorage(words, { verify });
      assert.equal(again.kind, env.kind);
      assert.deepEqual(again.sample(u), s);
      again.free();
    }
    // Corrupt storage is refused with the C error's name.
    const bad = words.slice();
    bad[2] = 0; // width 0
    assert.equal(thrown(() => wc.envmapFromStorage(bad), 'corrupt').code, 'WC_ERR_CORRUPT');
    const other = words.slice();
    other[0] ^= 1;
    assert.equal(thrown(() => wc.envmapFromStorage(other), 'tag').code, 'WC_ERR_WRONG_FORMAT');
    assert.equal(thrown(() => wc.envmapFromStorage(words.subarray(0, words.length - 1)), 'short').code, 'WC_ERR_STORAGE_TOO_SMALL');
    const version = words.slice();
    version[1] = 99;
    assert.equal(thrown(() => wc.envmapFromStorage(version), 'version').code, 'WC_ERR_UNSUPPORTED_VERSION');
    // Errors from the builders.
    const inf = w.slice();
    inf[3] = Infinity;
    const e = thrown(() => build(inf, 8, 4), 'inf');
    assert.equal(e.constructor, RangeError);
    assert.equal(e.code, 'WC_ERR_INFINITE_WEIGHT');
    assert.equal(thrown(() => build(w, 0, 4), 'zero').code, 'WC_ERR_ZERO_SIZE');
    assert.equal(thrown(() => build(w, 8, 3), 'length').constructor, RangeError);
    assert.equal(thrown(() => build(new Float32Array(0), 1 << 25, 0), 'zero height').code, 'WC_ERR_ZERO_SIZE');
    assert.equal(thrown(() => env.sample(f32(0.5)), 'odd u').constructor, RangeError);
    env.free();
    env.free(); // twice is harmless
    assert.equal(thrown(() => env.sample(f32(0.5, 0.5)), 'freed').constructor, TypeError);
    assert.equal(thrown(() => env.storage(), 'freed').constructor, TypeError);
  }
  assert.equal(thrown(() => new wc.EnvMap(), 'constructor').constructor, TypeError);
  // An all-zero map samples uniformly.
  const zero = wc.envmapHierarchical(new Float32Array(4), 2, 2);
  assert.deepEqual([...zero.pdf(f32(0.1, 0.1, 0.9, 0.9))], [1, 1]);
  zero[Symbol.dispose ?? Symbol.for('Symbol.dispose')]();
  assert.equal(wc.memoryStats().reserved, before, 'every table freed');
});

test('MIS-compensated env maps: pdf of max(0, w - average), fallback, none = plain', () => {
  const pairs = [
    [wc.envmapHierarchical, wc.envmapHierarchicalCompensated],
    [wc.envmapMarginalConditional, wc.envmapMarginalConditionalCompensated],
  ];
  for (const [plain, compensated] of pairs) {
    // Mean 4: the compensated weights are [0, 0, 0, 12], so only texel [1, 1] is left (pdf 4).
    const w = f32(1, 1, 2, 12);
    const env = compensated(w, 2, 2, 'uniform', 1);
    const pdf = env.pdf(f32(0.25, 0.25, 0.75, 0.25, 0.25, 0.75, 0.75, 0.75));
    assert.deepEqual([...pdf], [0, 0, 0, 4]);
    const s = env.sample(f32(0.1, 0.9, 0.6, 0.2));
    assert.deepEqual([...s.texel], [1, 1, 1, 1]);
    env.free();
    // Half the mean: [0, 0, 0, 10] as well; a fraction of 0.1: [0.6, 0.6, 1.6, 11.6] / 14.4.
    const tenth = compensated(w, 2, 2, 'uniform', 0.1);
    const p = tenth.pdf(f32(0.25, 0.25, 0.75, 0.75));
    assert.ok(Math.abs(p[0] - (4 * 0.6) / 14.4) < 1e-5 && Math.abs(p[1] - (4 * 11.6) / 14.4) < 1e-5, `${p}`);
    tenth.free();
    // 'none', NaN and negative fractions, and a constant map (everything removed: the fallback)
    // give the plain tables word for word.
    for (const [map, how, f] of [[w, 'none', 1], [w, 'uniform', NaN], [w, 'equirect', -1], [f32(3, 3, 3, 3), 'uniform', 1]]) {
      const a = plain(map, 2, 2);
      const b = compensated(map, 2, 2, how, f);
      const [sa, sb] = [a.storage(), b.storage()];
      // Word for word (format version 3 records nothing about the buffer's address).
      assert.deepEqual(sa, sb, `${how} ${f}`);
      a.free();
      b.free();
    }
    const inf = f32(1, Infinity, 1, 1);
    assert.equal(thrown(() => compensated(inf, 2, 2, 'equirect', 1), 'inf').code, 'WC_ERR_INFINITE_WEIGHT');
  }
});

test('EnvMap directions: one call gives the direction and its density per steradian', () => {
  const [w, h] = [24, 12];
  const wts = new Float32Array(w * h).map((_, k) => 0.5 + ((k * 37) % 11) / 10);
  const u = wc.pmj02bnSample(0, 5, 4096);
  for (const layout of ['equirect', 'equal-area']) {
    const weights = layout === 'equirect' ? wc.envmapEquirectSolidAngleWeights(wts, w, h) : wts;
    for (const build of [wc.envmapHierarchical, wc.envmapMarginalConditional]) {
      const env = build(weights, w, h);
      const s = env.sample(u);
      const d = env.sampleDirection(layout, u);
      assert.deepEqual(d.uv, s.uv);
      assert.deepEqual(d.texel, s.texel);
      // The layout's map of uv, and the density from the f64 Jacobian.
      const want = layout === 'equirect' ? wc.sphereEquirect(s.uv) : wc.sphereEqualArea(s.uv);
      assert.deepEqual(d.dir, want);
      let invSum = 0;
      let close = 0;
      const back = env.pdfDirection(layout, d.dir);
      for (let i = 0; i < 4096; i++) {
        const jac = layout === 'equirect' ? 2 * Math.PI * Math.PI * Math.sin(Math.PI * s.uv[2 * i + 1]) : 4 * Math.PI;
        assert.ok(Math.abs(d.pdf[i] - s.pdf[i] / jac) <= 1e-5 * (s.pdf[i] / jac), `${layout} pdf ${i}`);
        invSum += 1 / d.pdf[i];
        if (Math.abs(back[i] - d.pdf[i]) <= 1e-4 * d.pdf[i]) close++;
      }
      // pdfDirection(dir of a sample) is the sample's pdf (all but texel-edge roundings).
      assert.ok(close >= 4090, `${layout} ${env.kind}: ${close} of 4096 close`);
      // E[1/pdf] = 4 pi (weights all positive; pdf within a factor 6 of its mean: the
      // relative standard error over 4096 stratified samples is below 1%, tolerance 3%).
      assert.ok(Math.abs(invSum / 4096 / (4 * Math.PI) - 1) < 0.03, `${layout} ${env.kind}: E[1/pdf] ${invSum / 4096}`);
      // out, and argument errors.
      const out = new Float32Array(4096);
      assert.equal(env.pdfDirection(layout, d.dir, out), out);
      assert.deepEqual(out, back);
      assert.equal(thrown(() => env.sampleDirection('latlong', u), 'layout').constructor, RangeError);
      assert.equal(thrown(() => env.sampleDirection(0, u), 'layout type').constructor, TypeError);
      assert.equal(thrown(() => env.pdfDirection(layout, f32(1, 0)), 'dir length').constructor, RangeError);
      assert.equal(thrown(() => env.sampleDirection(layout, new Float64Array(2)), 'u type').constructor, TypeError);
      const empty = env.sampleDirection(layout, new Float32Array(0));
      assert.equal(empty.dir.length + empty.pdf.length, 0);
      env.free();
      assert.equal(thrown(() => env.sampleDirection(layout, u), 'freed').constructor, TypeError);
    }
  }
});

test('envmapFromStorage takes the file bytes: Buffer, Uint8Array at any offset, DataView, ArrayBuffer', async () => {
  const { Buffer } = await import('node:buffer');
  const env = wc.envmapHierarchical(new Float32Array(35).map((_, k) => (k % 4) + 0.5), 7, 5);
  const u = wc.pmj02bnSample(0, 1, 64);
  const want = env.sample(u);
  const words = env.storage();
  const bytes = new Uint8Array(words.buffer.slice(0));
  const shifted = new Uint8Array(bytes.length + 3);
  shifted.set(bytes, 3);
  const sources = [
    Buffer.from(bytes),
    shifted.subarray(3),
    new DataView(shifted.buffer, 3, bytes.length),
    bytes.buffer,
    new Uint16Array(bytes.buffer),
  ];
  for (const src of sources) {
    const again = wc.envmapFromStorage(src);
    assert.deepEqual(again.sample(u), want);
    assert.deepEqual(again.storage(), words);
    again.free();
  }
  // Every single-bit flip of the file is caught by the verifying load (the content checksum).
  let caught = 0;
  for (let i = 0; i < bytes.length; i++) {
    for (let b = 0; b < 8; b++) {
      const bad = Buffer.from(bytes);
      bad[i] ^= 1 << b;
      try {
        wc.envmapFromStorage(bad).free();
      } catch (e) {
        assert.equal(e.constructor, RangeError);
        caught++;
      }
    }
  }
  assert.equal(caught, 8 * bytes.length);
  // A version-2 storage is refused with a message that says to rebuild.
  const old = words.slice();
  old[1] = 2;
  const e = thrown(() => wc.envmapFromStorage(old), 'v2');
  assert.equal(e.code, 'WC_ERR_UNSUPPORTED_VERSION');
  assert.match(e.message, /rebuild/);
  env.free();
});

test('one name per thing: only the equirect names; pmj02bnShuffle takes numbers', () => {
  for (const name of ['envmapLatlongPdfToSolidAngle', 'envmapLatlongSolidAngleWeights', 'envmapLatlongToEqualArea']) {
    assert.equal(wc[name], undefined, name);
  }
  const w = f32(1, 2, 3, 4);
  assert.equal(thrown(() => wc.envmapHierarchicalCompensated(w, 2, 2, 'latlong', 1), 'old name').constructor, RangeError);
  const idx = Uint32Array.of(0, 5, 77, 0xffffffff);
  const typed = wc.pmj02bnShuffle(idx, 7);
  for (let i = 0; i < idx.length; i++) assert.equal(wc.pmj02bnShuffle(idx[i], 7), typed[i]);
  assert.equal(typeof wc.pmj02bnShuffle(5, 7), 'number');
  assert.equal(thrown(() => wc.pmj02bnShuffle(-1, 7), 'negative').constructor, RangeError);
  assert.equal(thrown(() => wc.pmj02bnShuffle(1.5, 7), 'fraction').constructor, RangeError);
  assert.equal(thrown(() => wc.pmj02bnShuffle(5, 7, new Uint32Array(1)), 'out').constructor, TypeError);
});

test('the same weights give the same storage bytes, built here or in Rust (address-free format)', () => {
  // Two builds land at different addresses in wasm memory; the words are equal.
  const w = new Float32Array(13 * 7).map((_, k) => (k * 7) % 5);
  const keep = wc.envmapMarginalConditional(w, 13, 7); // shifts where the next block starts
  const a = wc.envmapHierarchical(w, 13, 7);
  const b = wc.envmapHierarchical(w, 13, 7);
  assert.deepEqual(a.storage(), b.storage());
  for (const e of [keep, a, b]) e.free();
});

// ---- light selection ----

/** A deterministic uniform stream in [0, 1) (a 32-bit LCG's high 24 bits). */
function lcg(seed) {
  let x = seed >>> 0;
  return () => {
    x = (Math.imul(x, 1664525) + 1013904223) >>> 0;
    return (x >>> 8) * 2 ** -24;
  };
}
const bits = (x) => new Uint32Array(Float32Array.of(x).buffer)[0];
/** Pearson's chi-square of `counts` against `n * p` over the cells with p > 0. */
function chiSquare(counts, p, n) {
  let chi = 0;
  let cells = 0;
  for (let i = 0; i < p.length; i++) {
    if (p[i] === 0) {
      assert.equal(counts[i], 0, `cell ${i} has probability 0 but was drawn`);
      continue;
    }
    chi += (counts[i] - n * p[i]) ** 2 / (n * p[i]);
    cells++;
  }
  return { chi, df: cells - 1 };
}
// Upper 0.1% points of chi-square (Wilson-Hilferty, good to 1% here): a correct sampler fails
// one of these tests with probability 0.001.
const chi999 = (df) => df * (1 - 2 / (9 * df) + 3.0902 * Math.sqrt(2 / (9 * df))) ** 3;

test('AliasTable: probabilities of the weights, sample == pmf bit for bit, zeros never drawn', (t) => {
  const next = lcg(7);
  const n = 50;
  const w = new Float32Array(n);
  for (let i = 0; i < n; i++) w[i] = i % 9 === 4 ? 0 : next() * 10 ** Math.floor(next() * 4);
  const table = wc.lightsAlias(w);
  assert.equal(table.count, n);
  assert.equal(table.storageLength, 8 + 4 * n);
  let total = 0;
  for (let i = 0; i < n; i++) total += w[i];
  const pmf = table.pmf(Uint32Array.from({ length: n + 3 }, (_, i) => i));
  let sum = 0;
  for (let i = 0; i < n; i++) {
    // The documented bound: 2^-32 (1 + 1/n) absolute plus 2^-24 relative.
    const want = w[i] / total;
    assert.ok(Math.abs(pmf[i] - want) <= 2 ** -32 * (1 + 1 / n) + 2 ** -24 * want + 1e-12, `light ${i}: pmf ${pmf[i]}, weight share ${want}`);
    assert.equal(pmf[i] > 0, w[i] > 0);
    assert.equal(table.pmf(i), pmf[i], 'pmf of a number');
    sum += pmf[i];
  }
  assert.ok(Math.abs(sum - 1) < 1e-6, `pmf sums to ${sum}`);
  assert.deepEqual(Array.from(pmf.subarray(n)), [0, 0, 0], 'pmf past the end');
  // 200,000 independent u: chi-square against pmf; every prob equals pmf(index) bitwise.
  const N = 200_000;
  const u = new Float32Array(N);
  for (let i = 0; i < N; i++) u[i] = next();
  const s = table.sample(u);
  const counts = new Float64Array(n);
  const again = table.pmf(s.index);
  for (let i = 0; i < N; i++) {
    counts[s.index[i]]++;
    assert.equal(bits(s.prob[i]), bits(again[i]));
  }
  const { chi, df } = chiSquare(counts, pmf.subarray(0, n), N);
  t.diagnostic(`alias chi-square ${chi.toFixed(1)} on ${df} df (0.1% point ${chi999(df).toFixed(1)}), ${N} samples`);
  assert.ok(chi < chi999(df), `chi-square ${chi}`);
  // The scalar form and out-of-range u (NaN, negatives as 0; >= 1 as 1 - 2^-24).
  for (let i = 0; i < 64; i++) assert.deepEqual(table.sample(u[i]), { index: s.index[i], prob: s.prob[i] });
  const odd = table.sample(f32(NaN, -1, -0, 1, 2, Infinity, -Infinity, 1e-40));
  const zero = table.sample(0);
  const top = table.sample(1 - 2 ** -24);
  assert.deepEqual(Array.from(odd.index), [zero.index, zero.index, zero.index, top.index, top.index, top.index, zero.index, zero.index]);
  assert.equal(table.sample(f32()).index.length, 0);
  // Stratified u keep their strata through the columns and the thresholds: every light's
  // count within 4 of M p (independent u deviate by about sqrt(M / n) = 36 here).
  const M = 1 << 16;
  const strat = table.sample(Float32Array.from({ length: M }, (_, i) => (i + 0.5) / M));
  const c2 = new Float64Array(n);
  for (let i = 0; i < M; i++) c2[strat.index[i]]++;
  let worst = 0;
  for (let i = 0; i < n; i++) worst = Math.max(worst, Math.abs(c2[i] - M * pmf[i]));
  t.diagnostic(`stratified u: largest count deviation ${worst.toFixed(2)} of ${M} samples over ${n} lights`);
  assert.ok(worst < 4, `stratified deviation ${worst}`);
  table.free();
});

test('AliasTable: storage round trip, every single-bit flip rejected, garbage stays in range', () => {
  const table = wc.lightsAlias(f32(3, 0, 1, 0.5, 7));
  const words = table.storage();
  const u = Float32Array.from({ length: 64 }, (_, i) => i / 64);
  const want = table.sample(u);
  const copy = wc.lightsAliasFromStorage(words);
  assert.deepEqual(copy.sample(u), want);
  assert.deepEqual(wc.lightsAliasFromStorage(new Uint8Array(words.buffer)).sample(u), want, 'as bytes');
  copy.free();
  for (let w = 0; w < words.length; w++) {
    for (let b = 0; b < 32; b++) {
      const flipped = words.slice();
      flipped[w] ^= 1 << b;
      const e = thrown(() => wc.lightsAliasFromStorage(flipped), `word ${w} bit ${b}`);
      assert.equal(e.constructor, RangeError);
      assert.match(e.code, /^WC_ERR_(CORRUPT|WRONG_FORMAT|UNSUPPORTED_VERSION|STORAGE_TOO_SMALL)$/);
      // Unverified: loads when the header is intact, and samples stay valid.
      let loose;
      try {
        loose = wc.lightsAliasFromStorage(flipped, { verify: false });
      } catch {
        continue;
      }
      const s = loose.sample(u);
      for (let i = 0; i < 64; i++) assert.ok(s.index[i] < loose.count && s.prob[i] >= 0 && s.prob[i] <= 1, `word ${w} bit ${b}`);
      loose.free();
    }
  }
  table.free();
  assert.equal(thrown(() => table.sample(0.5)).constructor, TypeError, 'freed');
});

test('light-selection errors carry the C code', () => {
  const code = (f) => thrown(f).code;
  assert.equal(code(() => wc.lightsAlias(f32())), 'WC_ERR_EMPTY');
  assert.equal(code(() => wc.lightsAlias(f32(1, NaN))), 'WC_ERR_INVALID_WEIGHT');
  assert.equal(code(() => wc.lightsAlias(f32(1, -2))), 'WC_ERR_INVALID_WEIGHT');
  assert.equal(code(() => wc.lightsAlias(f32(0, -0))), 'WC_ERR_ALL_ZERO');
  assert.equal(code(() => wc.lightsTree(f32())), 'WC_ERR_EMPTY');
  assert.equal(code(() => wc.lightsTree(bound(1, 6, -1))), 'WC_ERR_INVALID_WEIGHT');
  assert.equal(code(() => wc.lightsTree(bound(0, 0, 9))), 'WC_ERR_INVALID_BOUNDS', 'min > max');
  assert.equal(code(() => wc.lightsTree(bound(0, 4, NaN))), 'WC_ERR_INVALID_BOUNDS', 'a NaN corner');
  assert.equal(code(() => wc.lightsTree(bound(1, 12 - 1, 1.5))), 'WC_ERR_INVALID_BOUNDS', 'a cosine above 1');
  assert.equal(code(() => wc.lightsTree(bound(0, 6, 0, 19, 0))), 'WC_ERR_ALL_ZERO');
  assert.equal(code(() => wc.lightsAliasFromStorage(TREE_STORAGE)), 'WC_ERR_WRONG_FORMAT');
  assert.equal(code(() => wc.lightsTreeFromStorage(TREE_STORAGE.subarray(0, 5))), 'WC_ERR_STORAGE_TOO_SMALL');
});

test('LightTree: sample == pmf bit for bit, pmfs sum to 1 for point lights, frequencies', (t) => {
  const next = lcg(11);
  const n = 40;
  const lights = new Float32Array(13 * n);
  for (let k = 0; k < n; k++) {
    const c = [next() * 20 - 10, next() * 20 - 10, next() * 4];
    lights.set([...c, ...c, k % 13 === 6 ? 0 : 0.5 + next() * 5, 0, 0, 1, -1, 0, 0], 13 * k);
  }
  const tree = wc.lightsTree(lights);
  assert.equal(tree.count, n);
  const P = 200;
  const p = new Float32Array(3 * P);
  const nrm = new Float32Array(3 * P);
  const u = new Float32Array(P);
  for (let i = 0; i < P; i++) {
    p.set([next() * 24 - 12, next() * 24 - 12, next() * 6 - 1], 3 * i);
    if (i % 4 !== 0) {
      const z = next() * 2 - 1;
      const phi = 2 * Math.PI * next();
      const r = Math.sqrt(1 - z * z);
      nrm.set([r * Math.cos(phi), r * Math.sin(phi), z], 3 * i);
    }
    u[i] = next();
  }
  // Points in a medium (zero normal) see every point light: the pmfs sum to 1.
  let worstSum = 0;
  for (let i = 0; i < P; i += 4) {
    const pi = p.subarray(3 * i, 3 * i + 3);
    const ni = nrm.subarray(3 * i, 3 * i + 3);
    const all = tree.pmf(new Float32Array(3 * n).map((_, j) => pi[j % 3]), new Float32Array(3 * n), Uint32Array.from({ length: n }, (_, k) => k));
    let sum = 0;
    for (let k = 0; k < n; k++) {
      sum += all[k];
      assert.equal(all[k] > 0, lights[13 * k + 6] > 0, `point ${i}, light ${k}`);
      assert.equal(tree.pmf(pi, ni, k), all[k], 'the scalar pmf');
    }
    worstSum = Math.max(worstSum, Math.abs(sum - 1));
  }
  t.diagnostic(`largest |sum of pmf - 1| at 50 points in a medium: ${worstSum.toExponential(2)}`);
  assert.ok(worstSum < 1e-5);
  const s = tree.sample(p, nrm, u);
  const q = tree.pmf(p, nrm, s.index);
  for (let i = 0; i < P; i++) {
    if (s.index[i] === 0xffffffff) {
      assert.equal(s.prob[i], 0);
      continue;
    }
    assert.ok(s.prob[i] > 0);
    assert.equal(bits(s.prob[i]), bits(q[i]), `point ${i}`);
    const one = tree.sample(p.subarray(3 * i, 3 * i + 3), nrm.subarray(3 * i, 3 * i + 3), u[i]);
    assert.deepEqual(one, { index: s.index[i], prob: s.prob[i] }, 'the scalar sample');
  }
  // Frequencies at one shading point: chi-square against pmf over 100,000 u.
  const N = 100_000;
  const pt = f32(0.5, -1, 0.5);
  const nt = f32(0, 0.6, 0.8);
  const pN = new Float32Array(3 * N).map((_, j) => pt[j % 3]);
  const nN = new Float32Array(3 * N).map((_, j) => nt[j % 3]);
  const uN = new Float32Array(N).map(() => next());
  const sN = tree.sample(pN, nN, uN);
  const cells = new Float64Array(n + 1);
  for (let i = 0; i < N; i++) cells[sN.index[i] === 0xffffffff ? n : sN.index[i]]++;
  const probs = new Float64Array(n + 1);
  const pk = tree.pmf(pN.subarray(0, 3 * n), nN.subarray(0, 3 * n), Uint32Array.from({ length: n }, (_, k) => k));
  let sum = 0;
  for (let k = 0; k < n; k++) sum += probs[k] = pk[k];
  probs[n] = Math.max(0, 1 - sum); // None: a dead end (counted as a cell of its own)
  if (probs[n] < 1e-6) probs[n] = 0;
  const { chi, df } = chiSquare(cells, probs, N);
  t.diagnostic(`tree chi-square ${chi.toFixed(1)} on ${df} df (0.1% point ${chi999(df).toFixed(1)}), ${N} samples`);
  assert.ok(chi < chi999(df), `chi-square ${chi}`);
  // Hostile p, n, u: valid results, never a throw.
  const H = [NaN, Infinity, -Infinity, 0, -0, 1e-40, 3e38, -1];
  const hp = new Float32Array(3 * 64).map((_, j) => H[(j * 7) % 8]);
  const hn = new Float32Array(3 * 64).map((_, j) => H[(j * 5 + 1) % 8]);
  const hu = new Float32Array(64).map((_, j) => H[(j * 3 + 2) % 8]);
  const hs = tree.sample(hp, hn, hu);
  const hq = tree.pmf(hp, hn, hs.index);
  for (let i = 0; i < 64; i++) {
    assert.ok((hs.index[i] < n && hs.prob[i] > 0 && hs.prob[i] <= 1) || (hs.index[i] === 0xffffffff && hs.prob[i] === 0));
    if (hs.index[i] < n) assert.equal(bits(hs.prob[i]), bits(hq[i]));
  }
  tree.free();
});

test('LightTree: twoSided encoding, argument lengths, storage round trip and bit flips', () => {
  // One area light facing +z at z = 0 and a point light; the shading point is below the area.
  const make = (twoSided) => f32(0, 0, 0, 1, 1, 0, 4, 0, 0, 1, 1, 0, twoSided, 5, 5, 5, 5, 5, 5, 1, 0, 0, 1, -1, 0, 0);
  const p = f32(0.5, 0.5, -1);
  const n = f32(0, 0, 1);
  const pmf0 = (twoSided) => {
    const tr = wc.lightsTree(make(twoSided));
    const q = tr.pmf(p, n, 0);
    tr.free();
    return q;
  };
  assert.equal(pmf0(0), 0, 'one-sided: facing away');
  assert.equal(pmf0(-0), 0, '-0 is one-sided');
  const two = pmf0(1);
  assert.ok(two > 0, 'two-sided');
  assert.equal(pmf0(0.5), two, 'any nonzero value is two-sided');
  const tree = wc.lightsTree(make(1));
  assert.equal(thrown(() => tree.sample(p, f32(0, 0), 0.5)).constructor, RangeError);
  assert.equal(thrown(() => tree.sample(p, n, f32(0.1, 0.2))).constructor, RangeError);
  assert.equal(thrown(() => tree.sample(f32(0, 0, 0, 1, 1, 1), f32(0, 0, 1, 0, 0, 1), 0.5)).constructor, RangeError, 'a number u with two points');
  assert.equal(thrown(() => tree.pmf(p, n, -1)).constructor, RangeError);
  assert.equal(thrown(() => tree.pmf(p, n, 1.5)).constructor, RangeError);
  assert.equal(thrown(() => tree.pmf(p, n, 1, new Float32Array(1))).constructor, TypeError, 'out with a number');
  assert.equal(thrown(() => tree.pmf(p, n, Uint32Array.of(0), new Float32Array(2))).constructor, RangeError);
  const out = new Float32Array(1);
  assert.equal(tree.pmf(p, n, Uint32Array.of(0), out), out);
  assert.equal(out[0], two);
  const words = tree.storage();
  const copy = wc.lightsTreeFromStorage(words);
  assert.deepEqual(copy.sample(p, n, 0.25), tree.sample(p, n, 0.25));
  copy.free();
  for (let w = 0; w < words.length; w += 3) {
    const flipped = words.slice();
    flipped[w] ^= 1 << (w % 32);
    assert.equal(thrown(() => wc.lightsTreeFromStorage(flipped), `word ${w}`).constructor, RangeError);
  }
  tree.free();
});
