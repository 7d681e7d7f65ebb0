// The sampler through the JavaScript API: the Rust crate's bits (the hashes of
// capi/examples/sampler_hashes.rs, computed now by cargo, over every pattern, six roots and the
// domain paths JavaScript expresses), the promises (draw == (drawU32 >>> 8) * 2^-24, values in
// [0, 1 - 2^-24], slices == scalar draws, wrapping), the argument errors (TypeError or
// RangeError, never a wasm trap, no user code run and no user value in a message), memory
// released, and the path tracer's loop of docs/javascript.md.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { load } from '../warpcore.mjs';
import { Fnv } from './fnv.mjs';

const root = fileURLToPath(new URL('../../', import.meta.url));
const wasmUrl = process.env.WARPCORE_WASM ? pathToFileURL(process.env.WARPCORE_WASM) : new URL('../warpcore.wasm', import.meta.url);
const wc = await load(wasmUrl);

// ---- the cases and the hash of sampler_hashes.rs ----


const ROOTS = [
  [0, 0, 0, 0, 0],
  [5, 7, 1, 3, 0],
  [63, 64, 2, 1023, 42],
  [65535, 1, 7, 4096, 0x9e3779b9],
  [70000, 123456, 0xffffffff, 0xfffffff0, 0xffffffff],
  [0xffffffff, 0xfffffffe, 12345, 65536, 1],
];
const KEY_PATHS = [[], [0], [7, 0xffffffff]].map((k) => Uint32Array.from(k));
const SLICE = 37;
const SPLIT_PATHS = [
  wc.samplerPath().split(3, 4, 1),
  wc.samplerPath().split(9, 0, 5).domain(2),
  wc.samplerPath().domain(1).split(0xffffffff, 0xffffffff, 0xfffffffe),
];
// The new_frame roots' samples per frame and the paths below them (sampler_hashes.rs).
const FRAME_SPP = [1, 4, 1, 3, 0, 4];
const FRAME_PATHS = (spp) => [
  wc.samplerFramePath(spp).domain(0),
  wc.samplerFramePath(spp).domain(5).split(3, 4, 1),
  wc.samplerFramePath(spp).domain(6).domain(0),
];
const PATTERNS = { pmj02bn: 'pmj02bn', sobol: 'sobol', blue_pmj02bn: 'bluePmj02bn', blue_sobol: 'blueSobol' };

function jsHashes() {
  const out = {};
  for (const [name, pattern] of Object.entries(PATTERNS)) {
    const parts = {
      draw: (h, args) => {
        for (let n = 1; n <= 4; n++) h.floats(wc.samplerDraw(pattern, ...args, n));
      },
      draw_u32: (h, args) => {
        for (let n = 1; n <= 4; n++) h.words(wc.samplerDrawU32(pattern, ...args, n));
      },
      rnd: (h, args) => {
        for (let n = 1; n <= 4; n++) h.floats(wc.samplerRnd(pattern, ...args, n));
      },
      slice: (h, [pixel, frame, index, seed, path]) => {
        for (let n = 1; n <= 4; n++) h.floats(wc.samplerDrawSlice(pattern, pixel, frame, index, SLICE, seed, path, n));
      },
    };
    for (const [what, f] of Object.entries(parts)) {
      const h = new Fnv();
      for (const [x, y, frame, index, seed] of ROOTS) {
        for (const path of KEY_PATHS) f(h, [Uint32Array.of(x, y), frame, index, seed, path]);
      }
      out[`sampler_${name}_${what}`] = h.hex();
    }
    // The split paths: everything but the state words (JavaScript has no sampler value).
    const h = new Fnv();
    for (const [x, y, frame, index, seed] of ROOTS) {
      for (const path of SPLIT_PATHS) {
        for (const f of Object.values(parts)) f(h, [Uint32Array.of(x, y), frame, index, seed, path]);
      }
    }
    out[`sampler_${name}_split`] = h.hex();
    const frames = new Fnv();
    ROOTS.forEach(([x, y, frame, index, seed], r) => {
      for (const path of FRAME_PATHS(FRAME_SPP[r])) {
        for (const f of Object.values(parts)) f(frames, [Uint32Array.of(x, y), frame, index, seed, path]);
      }
    });
    out[`sampler_${name}_frames`] = frames.hex();
  }
  return out;
}

let cargo = true;
try {
  execFileSync('cargo', ['--version'], { stdio: 'ignore' });
} catch {
  cargo = false;
}

test('the Rust crate\'s bits for every pattern, root and domain path (computed now by cargo)', { skip: !cargo && 'cargo is not installed' }, () => {
  const out = execFileSync('cargo', ['run', '-q', '-p', 'warpcore-capi', '--example', 'sampler_hashes'], {
    cwd: root,
    encoding: 'utf8',
    stdio: ['ignore', 'pipe', 'inherit'],
  });
  const rust = Object.fromEntries(out.trim().split('\n').map((l) => l.split(' ')));
  assert.equal(Object.keys(rust).length, 32);
  const got = jsHashes();
  assert.equal(Object.keys(got).length, 24);
  for (const [name, hash] of Object.entries(got)) assert.equal(hash, rust[name], name);
});

// ---- promises ----

const ONE = 2 ** -24;
const px = (x, y) => Uint32Array.of(x, y);
const keys = (...k) => Uint32Array.from(k);

test('draw is (drawU32 >>> 8) * 2^-24, values in [0, 1 - 2^-24], slices equal scalar draws (wrapping)', () => {
  let checks = 0;
  for (const pattern of Object.values(PATTERNS)) {
    for (const [x, y, frame, index, seed] of ROOTS) {
      for (const path of [keys(), keys(3), keys(1, 2, 3, 4, 5, 6, 7, 8)]) {
        for (let n = 1; n <= 4; n++) {
          const f = wc.samplerDraw(pattern, px(x, y), frame, index, seed, path, n);
          const w = wc.samplerDrawU32(pattern, px(x, y), frame, index, seed, path, n);
          const r = wc.samplerRnd(pattern, px(x, y), frame, index, seed, path, n);
          assert.equal(f.length, n);
          for (let d = 0; d < n; d++) {
            assert.equal(f[d], (w[d] >>> 8) * ONE);
            assert.ok(f[d] >= 0 && f[d] <= 1 - ONE && r[d] >= 0 && r[d] <= 1 - ONE);
            checks += 2;
          }
          // Slices from an index near the wrap: 45 points, the scalar draws at index + k.
          const start = (0xffffffff - 20 + index) >>> 0;
          const slice = wc.samplerDrawSlice(pattern, px(x, y), frame, start, 45, seed, path, n);
          assert.equal(slice.length, 45 * n);
          for (let k = 0; k < 45; k += 4) {
            const one = wc.samplerDraw(pattern, px(x, y), frame, (start + k) >>> 0, seed, path, n);
            assert.deepEqual(slice.subarray(k * n, (k + 1) * n), one);
            checks++;
          }
        }
      }
    }
  }
  assert.ok(checks > 3000, `${checks} checks`);
});

test('stratified: 2^m consecutive indices of a domain put one point in each 2^-m interval per dimension', () => {
  for (const pattern of Object.values(PATTERNS)) {
    const m = 8;
    const pts = wc.samplerDrawSlice(pattern, px(17, 4), 3, 256, 2 ** m, 9, keys(2, 5), 4);
    for (let d = 0; d < 4; d++) {
      const seen = new Set();
      for (let i = 0; i < 2 ** m; i++) seen.add(Math.floor(pts[4 * i + d] * 2 ** m));
      assert.equal(seen.size, 2 ** m, `${pattern} dimension ${d}`);
    }
  }
});

test('domains and patterns differ; the path is read, not kept; out arrays receive the result', () => {
  const a = wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, keys(1), 4);
  assert.notDeepEqual(a, wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, keys(2), 4));
  assert.notDeepEqual(a, wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, keys(1, 0), 4));
  assert.notDeepEqual(a, wc.samplerDraw('pmj02bn', px(1, 2), 0, 5, 0, keys(1), 4));
  assert.notDeepEqual(a, wc.samplerDraw('sobol', px(1, 2), 1, 5, 0, keys(1), 4));
  const path = keys(1);
  const again = wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, path, 4);
  path[0] = 2;
  assert.deepEqual(again, a);
  // Blue noise: pixels share a key tile (x, y modulo 2^16 at least), other patterns do not.
  assert.deepEqual(wc.samplerDraw('blueSobol', px(3, 4), 0, 0, 0, keys(), 2), wc.samplerDraw('blueSobol', px(3 + 65536, 4), 0, 0, 0, keys(), 2));
  assert.notDeepEqual(wc.samplerDraw('sobol', px(3, 4), 0, 0, 0, keys(), 2), wc.samplerDraw('sobol', px(3 + 65536, 4), 0, 0, 0, keys(), 2));
  // out: written and returned, at any offset; other lengths and types refused.
  const buf = new Float32Array(11);
  const out = buf.subarray(3, 7);
  assert.equal(wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, keys(1), 4, out), out);
  assert.deepEqual(out, a);
  const u = new Uint32Array(2);
  assert.equal(wc.samplerDrawU32('pmj02bn', px(1, 2), 0, 5, 0, keys(), 2, u), u);
  const s = new Float32Array(3 * 10 + 1).subarray(1);
  assert.equal(wc.samplerDrawSlice('blueSobol', px(1, 2), 0, 5, 10, 0, keys(), 3, s), s);
  assert.deepEqual(s, wc.samplerDrawSlice('blueSobol', px(1, 2), 0, 5, 10, 0, keys(), 3));
  assert.deepEqual(wc.samplerDrawSlice('sobol', px(1, 2), 0, 5, 0, 0, keys(), 3), new Float32Array(0));
});

test('SamplerPath: splits as in Rust (global stratification), immutable, checked, unforgeable', () => {
  const root = wc.samplerPath();
  assert.equal(root.length, 0);
  const a = root.domain(3);
  assert.equal(root.length, 0);
  assert.equal(a.length, 1);
  assert.equal(a.split(1, 2, 3).length, 2);
  assert.ok(Object.isFrozen(a));
  // A path of domains alone is the Uint32Array of its keys.
  for (const pattern of Object.values(PATTERNS)) {
    assert.deepEqual(wc.samplerDraw(pattern, px(1, 2), 0, 5, 0, root.domain(7).domain(9), 4), wc.samplerDraw(pattern, px(1, 2), 0, 5, 0, keys(7, 9), 4));
    assert.deepEqual(wc.samplerDraw(pattern, px(1, 2), 0, 5, 0, root, 4), wc.samplerDraw(pattern, px(1, 2), 0, 5, 0, keys(), 4));
  }
  // The size * N points of split(key, size, sub) over N samples are stratified together:
  // one per 1/(size * N) interval in each dimension.
  for (const pattern of Object.values(PATTERNS)) {
    const [size, N] = [4, 64];
    const seen = [new Set(), new Set()];
    for (let i = 0; i < N; i++) {
      for (let sub = 0; sub < size; sub++) {
        const p = wc.samplerDraw(pattern, px(9, 9), 0, i, 3, root.domain(2).split(5, size, sub), 2);
        for (const d of [0, 1]) seen[d].add(Math.floor(p[d] * size * N));
      }
    }
    assert.deepEqual(seen.map((s) => s.size), [size * N, size * N], pattern);
  }
  // split(key, size, sub) is not domain(key); size 0 acts as 1.
  const draw = (path) => wc.samplerDraw('sobol', px(1, 2), 0, 5, 0, path, 2);
  assert.notDeepEqual(draw(root.split(1, 1, 0)), draw(root.domain(1)));
  assert.deepEqual(draw(root.split(1, 0, 0)), draw(root.split(1, 1, 0)));
  // Checked arguments, constant messages.
  for (const [f, Want] of [
    [() => root.domain(-1), RangeError],
    [() => root.domain(2 ** 32), RangeError],
    [() => root.domain('1'), TypeError],
    [() => root.domain(), TypeError],
    [() => root.split(1, 2), TypeError],
    [() => root.split(1, 1.5, 0), RangeError],
    [() => root.split(1, 2, { valueOf: evil }), TypeError],
  ]) {
    const e = thrown(f, 'path argument');
    assert.equal(e.constructor, Want, e.message);
    assert.match(e.message, /^warpcore: SamplerPath\.(domain|split): /);
  }
  // Unforgeable: the constructor is not public, lookalikes and proxies are not paths.
  const C = root.constructor;
  assert.equal(thrown(() => new C(), 'new').constructor, TypeError);
  assert.equal(thrown(() => new C(Symbol('SamplerPath'), new Uint32Array(4)), 'new').constructor, TypeError);
  const fakes = [Object.create(C.prototype), new Proxy(a, { get: evil, has: evil, getPrototypeOf: evil }), { length: 0 }];
  for (const fake of fakes) {
    assert.equal(thrown(() => draw(fake), 'fake path').constructor, TypeError);
    assert.equal(thrown(() => root.domain.call(fake, 1), 'fake this').constructor, TypeError);
  }
  assert.equal(ran, 0, 'user code ran');
});

// ---- errors ----

/** Calls `f` and returns the error it throws (failing on none, or on a wasm trap). */
function thrown(f, what) {
  try {
    f();
  } catch (e) {
    assert.ok(!(e instanceof WebAssembly.RuntimeError), `${what}: a wasm trap`);
    return e;
  }
  assert.fail(`${what}: no error`);
}

// Values that run user code if anything reads, converts or formats them.
let ran = 0;
const evil = () => {
  ran++;
  throw new Error('user code ran');
};
const hostile = () => [
  { toString: evil, valueOf: evil, [Symbol.toPrimitive]: evil },
  new Proxy({}, { get: evil, has: evil, getPrototypeOf: evil, ownKeys: evil, getOwnPropertyDescriptor: evil }),
  new Proxy(new Uint32Array(2), { get: evil, has: evil, getPrototypeOf: evil }),
  new Proxy([1, 2], { get: evil, has: evil, getPrototypeOf: evil }),
  Object.defineProperty(new Float64Array(2), Symbol.toStringTag, { get: evil }),
  Object.defineProperty(new Float64Array(2), 'constructor', { get: evil }),
];

const GOOD = {
  samplerDraw: () => ['sobol', px(3, 4), 1, 2, 3, keys(4, 5), 2],
  samplerDrawU32: () => ['blueSobol', px(3, 4), 1, 2, 3, keys(), 4],
  samplerRnd: () => ['pmj02bn', px(3, 4), 1, 2, 3, keys(9), 3],
  samplerDrawSlice: () => ['bluePmj02bn', px(3, 4), 1, 2, 7, 3, keys(4), 3],
};
const U32_BAD = [[-1, RangeError], [1.5, RangeError], [NaN, RangeError], [Infinity, RangeError], [2 ** 32, RangeError], ['4', TypeError], [4n, TypeError], [null, TypeError], [undefined, TypeError], [{}, TypeError]];
const KINDS = {
  pattern: [['Sobol', RangeError], ['', RangeError], ['__proto__', RangeError], ['toString', RangeError], ['blue_sobol', RangeError], [0, TypeError], [null, TypeError], [undefined, TypeError], [new String('sobol'), TypeError]],
  pixel: [[[3, 4], TypeError], [new Int32Array(2), TypeError], [new Float32Array(2), TypeError], [new Uint32Array(3), RangeError], [new Uint32Array(1), RangeError], [new Uint32Array(0), RangeError], [new Uint32Array(2).buffer, TypeError], [new DataView(new ArrayBuffer(8)), TypeError], [null, TypeError], [undefined, TypeError]],
  u32: U32_BAD,
  count: U32_BAD,
  path: [[[1, 2], TypeError], [new Int32Array(2), TypeError], [new Uint16Array(2), TypeError], [null, TypeError], [undefined, TypeError], [1, TypeError], [new Uint32Array(2).buffer, TypeError]],
  n: [[0, RangeError], [5, RangeError], [1.5, RangeError], [-1, RangeError], [NaN, RangeError], ['2', TypeError], [2n, TypeError], [null, TypeError], [undefined, TypeError]],
  out: (name) => [[new (name === 'samplerDrawU32' ? Uint32Array : Float32Array)(1), RangeError], [new Float64Array(4), TypeError], [[0, 0, 0, 0], TypeError], [null, TypeError]],
};
const ARGS = {
  samplerDraw: ['pattern', 'pixel', 'u32', 'u32', 'u32', 'path', 'n', 'out'],
  samplerDrawU32: ['pattern', 'pixel', 'u32', 'u32', 'u32', 'path', 'n', 'out'],
  samplerRnd: ['pattern', 'pixel', 'u32', 'u32', 'u32', 'path', 'n', 'out'],
  samplerDrawSlice: ['pattern', 'pixel', 'u32', 'u32', 'count', 'u32', 'path', 'n', 'out'],
};

test('bad arguments: TypeError or RangeError, never a trap, no user code, no user value in the message, nothing leaked', (t) => {
  const before = wc.memoryStats();
  let cases = 0;
  for (const [name, kinds] of Object.entries(ARGS)) {
    kinds.forEach((kind, k) => {
      const own = typeof KINDS[kind] === 'function' ? KINDS[kind](name) : KINDS[kind];
      const bad = [...own, ...hostile().map((v) => [v, TypeError])];
      for (const [value, Want] of bad) {
        const args = GOOD[name]();
        args[k] = value;
        const e = thrown(() => wc[name](...args), `${name} argument ${k}`);
        assert.equal(e.constructor, Want, `${name} argument ${k} (${kind}): ${e.message}`);
        assert.match(e.message, /^warpcore: sampler\w+: /);
        if (typeof value === 'string' && value.length > 3) assert.ok(!e.message.includes(`'${value}'`) && !e.message.includes(` ${value}`), e.message);
        cases++;
      }
    });
  }
  assert.equal(ran, 0, 'user code ran');
  assert.ok(cases > 400, `${cases} cases`);
  t.diagnostic(`${cases} bad-argument cases`);
  // A detached domain path or output is refused, not read as empty.
  const path = keys(1, 2);
  structuredClone(path.buffer, { transfer: [path.buffer] });
  assert.equal(thrown(() => wc.samplerDraw('sobol', px(1, 1), 0, 0, 0, path, 2), 'detached').constructor, TypeError);
  // Typed arrays with a shadowed length: their real length counts.
  const sneaky = Object.defineProperty(new Uint32Array(3), 'length', { value: 2 });
  assert.equal(thrown(() => wc.samplerDraw('sobol', sneaky, 0, 0, 0, keys(), 2), 'length').constructor, RangeError);
  // Counts whose floats do not fit in wasm32 memory: refused before anything grows.
  for (const [count, n] of [[2 ** 30, 1], [2 ** 30, 4], [0xffffffff, 2]]) {
    assert.equal(thrown(() => wc.samplerDrawSlice('sobol', px(0, 0), 0, 0, count, 0, keys(), n), 'huge').constructor, RangeError);
  }
  assert.deepEqual(wc.memoryStats(), before, 'no memory reserved or grown');
});

test('the path tracer loop of docs/javascript.md runs and estimates its known value', (t) => {
  const doc = readFileSync(join(root, 'docs/javascript.md'), 'utf8');
  const section = doc.split('\n## Sampler')[1];
  assert.ok(section, 'a "## Sampler" section');
  const code = section.split('```js\n')[1]?.split('```')[0];
  assert.ok(code, 'a ```js block in it');
  const dir = mkdtempSync(join(tmpdir(), 'warpcore-doc-'));
  t.after(() => rmSync(dir, { recursive: true, force: true }));
  const file = join(dir, 'loop.mjs');
  const module = pathToFileURL(join(root, 'js/warpcore.mjs')).href;
  writeFileSync(file, code.replace("from 'warpcore'", `from '${module}'`).replace('await load()', `await load(${JSON.stringify(wasmUrl.href)})`));
  const out = execFileSync(process.execPath, [file], { encoding: 'utf8' });
  const m = /^estimate (\S+)/.exec(out);
  assert.ok(m, out);
  // 16 x 16 pixels x 64 samples: a standard deviation of about 0.017 (spread of 16 seeds).
  assert.ok(Math.abs(Number(m[1]) - 1) < 0.05, out);
});
