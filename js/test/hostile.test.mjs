// Hostile callers of the JavaScript API. Every function gets, in every argument, typed-array
// subclasses that override `set`, `subarray`, `length` and `constructor`, Proxies, DataViews,
// typed arrays from another realm or over detached buffers, objects whose `toString`,
// `valueOf` or `Symbol.toPrimitive` throw, shared and resizable buffers, and `out` arrays
// aliasing the inputs; and every call runs with the built-in prototypes the module could
// touch patched to record any use (array iterators, accessors planted on the indices of
// Array.prototype and Object.prototype, every Math/Number/Object/Reflect/%TypedArray%
// function). Every exported function and every EnvMap and SamplerPath method has cases (the
// last tests enumerate the exports and fail on one without). The test asserts:
//
// * the exact error type (TypeError or RangeError, never a user's exception, never a wasm
//   trap), or for valid arguments the same result as a plain call;
// * no user code ran during any call: no override, trap, getter, conversion method or patched
//   built-in was invoked (the one documented exception, reading `options.verify`, is tested
//   apart);
// * no view of the module's wasm memory escaped: not in a result, an error, or anything the
//   user's code could have received;
// * afterwards every EnvMap still samples what it sampled before, and no memory is reserved.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import vm from 'node:vm';
import { pathToFileURL } from 'node:url';
import { pointMaps } from './methods.mjs';

// ---- the module's memory, caught at instantiation (the module captures `instantiate` when it
// is evaluated, so the hook goes in before the import) ----
const memories = [];
const realInstantiate = WebAssembly.instantiate;
WebAssembly.instantiate = async (...args) => {
  const r = await realInstantiate(...args);
  memories.push((r instanceof WebAssembly.Instance ? r : r.instance).exports.memory);
  return r;
};
const warpcore = await import('../warpcore.mjs');
const { load } = warpcore;
/** Exported functions, classes' methods and getters that a hostile case exercised. */
const COVERED = new Set();
const wasmUrl = process.env.WARPCORE_WASM ? pathToFileURL(process.env.WARPCORE_WASM) : new URL('../warpcore.wasm', import.meta.url);
const wc = await load(wasmUrl);
WebAssembly.instantiate = realInstantiate;
assert.equal(memories.length, 1);
const memory = memories[0];

const TypedArray = Object.getPrototypeOf(Uint8Array.prototype);
const taBuffer = Object.getOwnPropertyDescriptor(TypedArray, 'buffer').get;
const dvBuffer = Object.getOwnPropertyDescriptor(DataView.prototype, 'buffer').get;
const memoryBuffer = Object.getOwnPropertyDescriptor(WebAssembly.Memory.prototype, 'buffer').get;
const { TypeError: TE, RangeError: RE } = globalThis;
// The test's own machinery runs while built-ins are patched: it uses these, captured now, and
// never an iterator or an index write on an ordinary array.
const rApply = Reflect.apply;
const rConstruct = Reflect.construct;
const rDefine = Reflect.defineProperty;
const rDelete = Reflect.deleteProperty;
const ArrayIteratorPrototype = Object.getPrototypeOf([][Symbol.iterator]());
const IteratorPrototype = Object.getPrototypeOf(ArrayIteratorPrototype);
/** Appends `v` to the array `a` by definition (no setter on Array.prototype runs). */
const append = (a, v) => rDefine(a, a.length, { value: v, writable: true, enumerable: true, configurable: true });

// Every buffer the memory ever had (it is replaced when it grows).
const wasmBuffers = new WeakSet();
const noteBuffer = () => wasmBuffers.add(memoryBuffer.call(memory));
noteBuffer();

/** Is `v`, or anything reachable from it (two levels), the module's memory or a view of it? */
function escapes(v, depth = 0) {
  if (v === null || (typeof v !== 'object' && typeof v !== 'function')) return false;
  if (v === memory || wasmBuffers.has(v)) return true;
  if (ArrayBuffer.isView(v)) {
    const b = v instanceof DataView ? dvBuffer.call(v) : taBuffer.call(v);
    return wasmBuffers.has(b);
  }
  if (depth >= 2) return false;
  for (const key of Reflect.ownKeys(v)) {
    const d = Reflect.getOwnPropertyDescriptor(v, key);
    if (d && 'value' in d && escapes(d.value, depth + 1)) return true;
  }
  return false;
}

// ---- spies on everything a caller could patch: installed only while a call runs (they would
// disturb the test runner otherwise), recording any use ----
const ran = []; // [what, this, args]
let active = false;
let recording = false; // re-entrancy guard: recording must not record itself
const record = (what, self, args) => {
  if (!active || recording) return;
  recording = true;
  append(ran, { __proto__: null, what, self, args });
  recording = false;
};
const SPIES = []; // [object, key, original descriptor, spy descriptor]
function spyOn(o, key, what) {
  const d = Object.getOwnPropertyDescriptor(o, key);
  if (!d || !d.configurable) return;
  let spy;
  if (typeof d.value === 'function' && key !== 'constructor') {
    const f = d.value;
    spy = {
      ...d,
      value: function (...args) {
        record(what, this, args);
        return new.target ? rConstruct(f, args, new.target) : rApply(f, this, args);
      },
    };
  } else if ('value' in d) {
    const v = d.value;
    spy = {
      configurable: true,
      enumerable: d.enumerable,
      get() {
        record(`get ${what}`, this, []);
        return v;
      },
      set(x) {
        record(`set ${what}`, this, [x]);
      },
    };
  } else {
    const g = d.get;
    spy = {
      ...d,
      get() {
        record(`get ${what}`, this, []);
        return g && rApply(g, this, []);
      },
    };
  }
  SPIES.push([o, key, d, spy]);
}
/** Accessors planted where no property was (index keys on Array.prototype and Object.prototype). */
function plant(o, key, what) {
  if (Object.getOwnPropertyDescriptor(o, key)) return;
  SPIES.push([o, key, undefined, { configurable: true, get() { record(`get ${what}`, this, []); }, set(v) { record(`set ${what}`, this, [v]); } }]); // prettier-ignore
}
for (const key of Reflect.ownKeys(TypedArray)) spyOn(TypedArray, key, `%TypedArray%.prototype.${String(key)}`);
for (const T of [Float32Array, Uint32Array, Int32Array, Uint8Array, Float64Array]) {
  spyOn(T.prototype, 'constructor', `${T.name}.prototype.constructor`);
}
spyOn(TypedArray.constructor, Symbol.species, '%TypedArray%[Symbol.species]');
for (const key of Reflect.ownKeys(Array.prototype)) if (key !== 'length') spyOn(Array.prototype, key, `Array.prototype.${String(key)}`);
for (const key of ['buffer', 'grow']) spyOn(WebAssembly.Memory.prototype, key, `Memory.prototype.${key}`);
for (const key of ['byteLength', 'slice', 'resize']) spyOn(ArrayBuffer.prototype, key, `ArrayBuffer.prototype.${key}`);
spyOn(ArrayBuffer, 'isView', 'ArrayBuffer.isView');
for (const key of ['getPrototypeOf', 'keys', 'assign', 'defineProperty', 'freeze', 'entries']) spyOn(Object, key, `Object.${key}`);
// Iterators (destructuring, for-of and spread run these), every Math, Number, Object, Reflect
// and Array function, the String and Number methods, and accessors planted on the indices of
// Array.prototype and Object.prototype (an index write or a read past an array's end runs them).
for (const key of Reflect.ownKeys(ArrayIteratorPrototype)) spyOn(ArrayIteratorPrototype, key, `%ArrayIteratorPrototype%.${String(key)}`);
for (const key of Reflect.ownKeys(IteratorPrototype)) if (key !== 'constructor') spyOn(IteratorPrototype, key, `%IteratorPrototype%.${String(key)}`);
for (const [o, name] of [[Math, 'Math'], [Number, 'Number'], [Object, 'Object'], [Reflect, 'Reflect'], [Array, 'Array'], [String.prototype, 'String.prototype'], [Number.prototype, 'Number.prototype'], [Uint8Array, 'Uint8Array'], [Float32Array, 'Float32Array'], [Uint32Array, 'Uint32Array'], [Int32Array, 'Int32Array'], [TypedArray.constructor, '%TypedArray%']]) {
  for (const key of Reflect.ownKeys(o)) {
    if (key === 'prototype' || key === 'length' || key === 'name' || key === 'constructor' || SPIES.some((s) => s[0] === o && s[1] === key)) continue;
    spyOn(o, key, `${name}.${String(key)}`);
  }
}
for (let i = 0; i < 16; i++) {
  plant(Array.prototype, String(i), `Array.prototype[${i}]`);
  plant(Object.prototype, String(i), `Object.prototype[${i}]`);
}
for (const key of ['register', 'unregister']) spyOn(FinalizationRegistry.prototype, key, `FinalizationRegistry.prototype.${key}`);
for (const key of ['toString', 'valueOf']) spyOn(Object.prototype, key, `Object.prototype.${key}`);
spyOn(Number.prototype, 'toString', 'Number.prototype.toString');
for (const key of ['call', 'apply', 'bind']) spyOn(Function.prototype, key, `Function.prototype.${key}`);
spyOn(Symbol.prototype, 'toString', 'Symbol.prototype.toString');
for (const key of ['message', 'name']) spyOn(Error.prototype, key, `Error.prototype.${key}`);
// Setters a caller could plant for the properties the module defines on its own objects.
for (const [o, key] of [[Object.prototype, 'code'], [Error.prototype, 'code'], [RangeError.prototype, 'code'], [TypeError.prototype, 'code'], [Object.prototype, 'kind'], [Object.prototype, 'width'], [Object.prototype, 'height']]) {
  SPIES.push([o, key, undefined, { configurable: true, set(v) { record(`set ${key}`, this, [v]); } }]); // prettier-ignore
}
function arm() {
  for (let i = 0; i < SPIES.length; i++) rDefine(SPIES[i][0], SPIES[i][1], SPIES[i][3]);
  active = true;
}
function disarm() {
  active = false;
  for (let i = SPIES.length - 1; i >= 0; i--) {
    const s = SPIES[i];
    if (s[2]) rDefine(s[0], s[1], s[2]);
    else rDelete(s[0], s[1]);
  }
}

let calls = 0;
/** Runs one API call with the spies armed; returns [result, error]. */
function call(f) {
  calls++;
  ran.length = 0;
  arm();
  let result;
  let error;
  try {
    result = f();
  } catch (e) {
    error = e;
  } finally {
    disarm();
  }
  noteBuffer();
  assert.deepEqual(ran.map((r) => r.what), [], 'user code ran during the call');
  assert.ok(!escapes(result), 'a wasm memory view in the result');
  assert.ok(!escapes(error), 'a wasm memory view in the error');
  if (error !== undefined) assert.ok(!(error instanceof WebAssembly.RuntimeError), `a wasm trap: ${error.message}`);
  return [result, error];
}
const expectError = (f, Want, what) => {
  const [, e] = call(f);
  assert.ok(e !== undefined, `${what}: no error`);
  assert.equal(Object.getPrototypeOf(e), Want.prototype, `${what}: ${e?.constructor?.name}: ${e?.message}`);
  return e;
};
const expectSame = (f, want, what) => {
  const [r, e] = call(f);
  assert.equal(e, undefined, `${what}: ${e?.message}`);
  assert.deepEqual(r, want, what);
  return r;
};

// ---- arguments ----
const STORAGE = (() => {
  const env = wc.envmapMarginalConditional(new Float32Array([1, 2, 0, 3, 1, 1]), 3, 2);
  const words = env.storage();
  env.free();
  return words;
})();

// Light selection: weights, and 13-float light bounds (min, max, power, axis, cosThetaO,
// cosThetaE, twoSided): an area light facing +z, a point light, a two-sided quad.
const ALIAS_WEIGHTS = [1, 0, 3, 4, 2];
const BOUNDS = [0, 0, 0, 1, 1, 0, 10, 0, 0, 1, 1, 0, 0, 3, 0, 1, 3, 0, 1, 2, 0, 0, 1, -1, 0, 0, -2, 1, 0, -1, 2, 1, 5, 1, 0, 0, 0.9, 0.2, 1];
const { ALIAS_STORAGE, TREE_STORAGE } = (() => {
  const a = wc.lightsAlias(new Float32Array(ALIAS_WEIGHTS));
  const t = wc.lightsTree(new Float32Array(BOUNDS));
  const r = { ALIAS_STORAGE: a.storage(), TREE_STORAGE: t.storage() };
  a.free();
  t.free();
  return r;
})();
const P_PROBE = new Float32Array([0.5, 0.5, 2, 0, 0, 0, 4, -1, 1, -3, 2, -2]);
const N_PROBE = new Float32Array([0, 0, -1, 0, 0, 0, 0, 1, 0, 0.6, 0, 0.8]);
const U4 = new Float32Array([0.1, 0.5, 0.7, 0.99]);
const I4 = new Uint32Array([0, 2, 1, 7]);
const vec = (T, d, n = 3) => ({ T, d, good: () => new T(d * n).map((_, i) => (i % 7) * 0.125) });
const NUM = (v) => ({ num: true, good: () => v });
const STR = (v) => ({ str: true, good: () => v });
const FIXED = (T, values) => ({ T, d: values.length, good: () => new T(values) });
// Lights by solid angle: v0 v1 v2 p (triangle), corner ex ey p (rectangle), and n (cosine).
const TRI = [0, 0, 1, 1, 0, 1, 0, 1, 1, 0.2, 0.2, 0];
const RECT = [-0.5, -0.5, 1, 1, 0, 0, 0, 1, 0, 0.1, 0, 0];
const N = [0, 0.6, 0.8];
// A sampler's domain path: keys, or (below) the SamplerPath of the same domains.
const KEYS = [4, 2];
const PATH = { T: Uint32Array, d: 1, path: true, good: () => new Uint32Array(KEYS) };
const PIXEL = FIXED(Uint32Array, [3, 5]);
const WEIGHTS = { T: Float32Array, d: 6, good: () => new Float32Array([1, 2, 0, 3, 1, 1]) };
const SPEC = {
  ...pointMaps((d) => vec(Float32Array, d)),
  diskPolar4: [vec(Float32Array, 2), NUM(5)],
  diskConcentric4: [vec(Float32Array, 2), NUM(5)],
  triangleBasuOwen: [NUM(1), NUM(2), NUM(3)],
  triangleBasuOwenPermuted: [NUM(1), NUM(2), NUM(3)],
  sphereEqualAreaWrapTexel: [vec(Int32Array, 2), NUM(8)],
  pmj02bnSample: [NUM(0), NUM(9), NUM(4)],
  pmj02bnRaw: [NUM(0), NUM(9), NUM(4)],
  pmj02bnShuffle: [vec(Uint32Array, 1), NUM(3)],
  sequenceRandom: [NUM(0), NUM(9), NUM(4)],
  sequenceStratified: [NUM(0), NUM(16), NUM(9), NUM(4)],
  envmapEquirectSolidAngleWeights: [{ T: Float32Array, d: 6, good: () => new Float32Array(6).fill(1) }, NUM(3), NUM(2)],
  envmapEquirectToEqualArea: [{ T: Float32Array, d: 18, good: () => new Float32Array(18).fill(0.5) }, NUM(3), NUM(2), NUM(3), NUM(4), NUM(2)],
  envmapHierarchical: [WEIGHTS, NUM(3), NUM(2)],
  envmapMarginalConditional: [WEIGHTS, NUM(3), NUM(2)],
  envmapHierarchicalCompensated: [WEIGHTS, NUM(3), NUM(2), STR('uniform'), NUM(0.5)],
  envmapMarginalConditionalCompensated: [WEIGHTS, NUM(3), NUM(2), STR('equirect'), NUM(0.25)],
  sphericalTriangle: [FIXED(Float32Array, TRI), vec(Float32Array, 2)],
  sphericalTriangleInverse: [FIXED(Float32Array, TRI), FIXED(Float32Array, [0.2, 0.3, 0.5, 1, 0, 0])],
  sphericalRectangle: [FIXED(Float32Array, RECT), vec(Float32Array, 2)],
  sphericalRectangleInverse: [FIXED(Float32Array, RECT), vec(Float32Array, 2)],
  sphericalTriangleCosine: [FIXED(Float32Array, [...TRI, ...N]), vec(Float32Array, 2)],
  sphericalRectangleCosine: [FIXED(Float32Array, [...RECT, ...N]), vec(Float32Array, 2)],
  sphericalTriangleSolidAngle: [FIXED(Float32Array, TRI)],
  sphericalRectangleSolidAngle: [FIXED(Float32Array, RECT)],
  sphericalCone: [FIXED(Float32Array, [0, 0, 3, 1, 0.1, 0.2, 0]), vec(Float32Array, 2)],
  sphericalConeInverse: [FIXED(Float32Array, [0, 0, 3, 1, 0.1, 0.2, 0]), vec(Float32Array, 3)],
  sphericalConeSolidAngle: [FIXED(Float32Array, [0, 0, 3, 1, 0.1, 0.2, 0])],
  samplerPath: [],
  samplerFramePath: [NUM(4)],
  samplerDraw: [STR('sobol'), PIXEL, NUM(1), NUM(7), NUM(9), PATH, NUM(4)],
  samplerDrawU32: [STR('pmj02bn'), PIXEL, NUM(1), NUM(7), NUM(9), PATH, NUM(3)],
  samplerRnd: [STR('blueSobol'), PIXEL, NUM(1), NUM(7), NUM(9), PATH, NUM(2)],
  samplerDrawSlice: [STR('bluePmj02bn'), PIXEL, NUM(1), NUM(7), NUM(5), NUM(9), PATH, NUM(4)],
  memoryStats: [],
  // Storage words: any ArrayBufferView of bytes is accepted (a subclass or another realm's
  // Uint32Array as its bytes, read with the intrinsic getters only; a DataView of zeros is a
  // RangeError: not a storage).
  envmapFromStorage: [{ T: Uint32Array, d: 1, good: () => STORAGE.slice(), bytes: { subclass: null, 'another realm': null, DataView: RangeError } }],
  lightsAlias: [FIXED(Float32Array, ALIAS_WEIGHTS)],
  lightsTree: [FIXED(Float32Array, BOUNDS)],
  lightsAliasFromStorage: [{ T: Uint32Array, d: 1, good: () => ALIAS_STORAGE.slice(), bytes: { subclass: null, 'another realm': null, DataView: RangeError } }],
  lightsTreeFromStorage: [{ T: Uint32Array, d: 1, good: () => TREE_STORAGE.slice(), bytes: { subclass: null, 'another realm': null, DataView: RangeError } }],
};
// Functions whose last argument is an optional `out` of this type and length (for the good
// arguments).
const NO_OUT = new Set(['diskPolar4Inverse', 'diskConcentric4Inverse', 'envmapHierarchical', 'envmapMarginalConditional', 'envmapHierarchicalCompensated', 'envmapMarginalConditionalCompensated', 'envmapFromStorage', 'envmapEquirectSolidAngleWeights', 'envmapEquirectToEqualArea', 'sphericalTriangleSolidAngle', 'sphericalRectangleSolidAngle', 'sphericalConeSolidAngle', 'samplerPath', 'samplerFramePath', 'memoryStats', 'lightsAlias', 'lightsTree', 'lightsAliasFromStorage', 'lightsTreeFromStorage']);
const OUT = {};
for (const [name, specs] of Object.entries(SPEC)) {
  if (NO_OUT.has(name)) continue;
  const r = wc[name](...specs.map((s) => s.good()));
  assert.ok(ArrayBuffer.isView(r), `${name} returns a typed array (else: add it to NO_OUT)`);
  OUT[name] = { T: { Float32Array, Uint32Array, Int32Array }[r[Symbol.toStringTag]], length: r.length, at: specs.length };
}

/** The base class of EnvMap, AliasTable and LightTree (storage, free, dispose). */
const Stored = Object.getPrototypeOf(wc.EnvMap);
const free = (r) => {
  if (r instanceof Stored) r.free();
};
/** The plain result of a call (for comparing), with EnvMaps reduced to their samples. */
const TAG = Object.getOwnPropertyDescriptor(TypedArray, Symbol.toStringTag).get;
const TYPES = { Float32Array, Uint32Array, Int32Array };
const plain = (r) => {
  if (r instanceof Stored) return summary(r);
  if (ArrayBuffer.isView(r)) return new TYPES[TAG.call(r)](r); // a plain copy (`r` may be a caller's odd array)
  return r;
};
const U_PROBE = new Float32Array([0.1, 0.2, 0.7, 0.4, 0.95, 0.99, 0, 0]);
const envSummary = (env) => ({ kind: env.kind, width: env.width, height: env.height, sample: env.sample(U_PROBE) });
/** What a Stored object samples (an EnvMap, an AliasTable or a LightTree). */
const summary = (r) =>
  r instanceof wc.EnvMap
    ? envSummary(r)
    : r instanceof wc.AliasTable
      ? { count: r.count, sample: r.sample(U4), pmf: r.pmf(I4), storage: r.storage() }
      : { count: r.count, sample: r.sample(P_PROBE, N_PROBE, U4), pmf: r.pmf(P_PROBE, N_PROBE, I4), storage: r.storage() };

// Hostile stand-ins for a typed array of type T holding `source`; `Want` is the error each
// must throw (null: must succeed with the plain result).
const otherRealm = vm.runInNewContext('({ Float32Array, Uint32Array, Int32Array })');
function hostileArrays(T, source) {
  const log = (what) => (...args) => record(`user ${what}`, null, args);
  class Sub extends T {
    set(...a) {
      log('Sub.set')(this, a);
      return super.set(...a);
    }
    subarray(...a) {
      log('Sub.subarray')(this, a);
      return super.subarray(...a);
    }
    get length() {
      log('Sub.length')();
      return 2;
    }
    static get [Symbol.species]() {
      log('Sub[species]')();
      return T;
    }
  }
  const sub = new Sub(source.length);
  T.prototype.set.call(sub, source);
  const shadowed = new T(source);
  for (const key of ['set', 'subarray', 'slice', 'constructor', 'length', 'buffer', 'byteOffset']) {
    Object.defineProperty(shadowed, key, {
      get() {
        log(`own ${key}`)();
        throw new Error(`own ${key}`);
      },
    });
  }
  const traps = {};
  for (const trap of ['get', 'getPrototypeOf', 'has', 'ownKeys', 'getOwnPropertyDescriptor', 'set', 'apply']) {
    traps[trap] = (...a) => {
      log(`Proxy ${trap}`)(a);
      return Reflect[trap](...a);
    };
  }
  const detachedBuffer = new ArrayBuffer(source.length * T.BYTES_PER_ELEMENT);
  const detachedArray = new T(detachedBuffer);
  structuredClone(detachedBuffer, { transfer: [detachedBuffer] });
  const shared = new T(new SharedArrayBuffer(source.length * T.BYTES_PER_ELEMENT + 8), 4, source.length);
  shared.set(source);
  const resizable = new T(new ArrayBuffer(source.length * T.BYTES_PER_ELEMENT, { maxByteLength: 4096 }));
  resizable.set(source);
  const foreign = new otherRealm[T.name](source.length);
  foreign.set(source);
  const revoked = Proxy.revocable(new T(source), {});
  revoked.revoke();
  return [
    ['subclass', sub, TE],
    ['own properties shadowing the prototype', shadowed, null],
    ['Proxy', new Proxy(new T(source), traps), TE],
    ['revoked Proxy', revoked.proxy, TE],
    ['DataView', new DataView(new ArrayBuffer(4 * source.length)), TE],
    ['another realm', foreign, TE],
    ['detached', detachedArray, TE],
    ['shared buffer', shared, null],
    ['resizable buffer', resizable, null],
    ['plain object with a length', { length: source.length, 0: 1 }, TE],
  ];
}

// Hostile stand-ins for a number: conversion methods that throw (or lie) must never run.
function hostileNumbers() {
  const log = (what) => () => {
    record(`user ${what}`, null, []);
    throw new Error(what);
  };
  return [
    ['valueOf', { valueOf: log('valueOf') }, TE],
    ['toString', { toString: log('toString') }, TE],
    ['Symbol.toPrimitive', { [Symbol.toPrimitive]: log('toPrimitive') }, TE],
    ['Number object', Object(4), TE],
    ['getter-laden object', Object.defineProperty({}, 'valueOf', { get: log('valueOf getter') }), TE],
    ['Proxy', new Proxy({}, { get: log('Proxy get'), getPrototypeOf: log('Proxy getPrototypeOf') }), TE],
    ['symbol', Symbol('n'), TE],
    ['BigInt', 4n, TE],
    ['function', Object.assign(() => 4, { valueOf: log('fn valueOf') }), TE],
  ];
}

// Hostile stand-ins for a string (a pattern, a compensation): only primitives are strings.
function hostileStrings(good) {
  const log = (what) => () => {
    record(`user ${what}`, null, []);
    throw new Error(what);
  };
  return [
    ['String object', Object(good), TE],
    ['toString', { toString: log('toString') }, TE],
    ['Symbol.toPrimitive', { [Symbol.toPrimitive]: log('toPrimitive') }, TE],
    ['Proxy', new Proxy({}, { get: log('Proxy get'), has: log('Proxy has'), getPrototypeOf: log('Proxy getPrototypeOf') }), TE],
    ['symbol', Symbol(good), TE],
    ['number', 1, TE],
    ['unknown name', 'toString', RE],
    ['an inherited name', '__proto__', RE],
  ];
}

// Hostile stand-ins for a domain path: the keys' typed-array stand-ins, plus a SamplerPath of
// the same domains (same result) and things that look like one.
function hostilePaths() {
  const real = wc.samplerPath().domain(KEYS[0]).domain(KEYS[1]);
  const log = (what) => (...a) => {
    record(`user ${what}`, null, a);
    return Reflect[what](...a);
  };
  const traps = {};
  for (const trap of ['get', 'getPrototypeOf', 'has', 'ownKeys', 'getOwnPropertyDescriptor']) traps[trap] = log(trap);
  return [
    ...hostileArrays(Uint32Array, new Uint32Array(KEYS)),
    ['SamplerPath', real, null],
    ['an object on SamplerPath.prototype', Object.create(Object.getPrototypeOf(real)), TE],
    ['Proxy of a SamplerPath', new Proxy(real, traps), TE],
    ['Int32Array of keys', new Int32Array(KEYS), TE],
  ];
}

test('hostile arguments: exact errors, no user code, no wasm memory view', (t) => {
  const reserved = wc.memoryStats().reserved;
  const kept = wc.envmapHierarchical(new Float32Array([1, 2, 0, 3, 1, 1, 4, 0]), 4, 2);
  const keptBefore = envSummary(kept);
  let cases = 0;
  for (const [name, specs] of Object.entries(SPEC)) {
    const good = () => specs.map((s) => s.good());
    const goodArgs = good();
    const want = call(() => rApply(wc[name], wc, goodArgs))[0];
    const wantPlain = plain(want);
    free(want);
    const positions = specs.map((s, k) => [s, k]);
    if (OUT[name]) positions.push([{ T: OUT[name].T, d: 1, good: () => new OUT[name].T(OUT[name].length), out: true }, OUT[name].at]);
    for (const [spec, k] of positions) {
      let variants = spec.num ? hostileNumbers() : spec.str ? hostileStrings(spec.good()) : spec.path ? hostilePaths() : hostileArrays(spec.T, spec.good());
      if (spec.bytes) variants = variants.map(([what, value, Want]) => [what, value, what in spec.bytes ? spec.bytes[what] : Want]);
      for (const [what, value, Want] of variants) {
        const args = good();
        args[k] = value;
        const label = `${name} argument ${k} (${spec.out ? 'out' : ''}): ${what}`;
        if (Want) {
          expectError(() => rApply(wc[name], wc, args), Want, label);
        } else {
          const [r, e] = call(() => rApply(wc[name], wc, args));
          assert.equal(e, undefined, `${label}: ${e?.message}`);
          assert.deepEqual(plain(r), wantPlain, label);
          if (spec.out) assert.equal(r, value, `${label}: out is returned`);
          free(r);
        }
        cases++;
      }
    }
  }
  for (const name in SPEC) COVERED.add(name);
  // EnvMap, AliasTable and LightTree methods: every argument (and `out`) hostile, and `this`
  // not an object of the class (another Stored included).
  const DIRS = new Float32Array([0, 0, 1, 0.6, 0, 0.8, 0, -1, 0, 0.48, 0.6, -0.64]);
  const F32 = (a) => ({ T: Float32Array, good: () => a.slice() });
  const U32s = (a) => ({ T: Uint32Array, good: () => a.slice() });
  const OUT4 = { T: Float32Array, out: true, good: () => new Float32Array(4) };
  const alias = wc.lightsAlias(new Float32Array(ALIAS_WEIGHTS));
  const tree = wc.lightsTree(new Float32Array(BOUNDS));
  const other = wc.lightsTree(new Float32Array(BOUNDS));
  const CLASSES = [
    ['EnvMap', wc.EnvMap, kept, {
      sample: [F32(U_PROBE)],
      pdf: [F32(U_PROBE), OUT4],
      sampleDirection: [STR('equal-area'), F32(U_PROBE)],
      pdfDirection: [STR('equirect'), F32(DIRS), OUT4],
    }],
    ['AliasTable', wc.AliasTable, alias, { sample: [F32(U4)], pmf: [U32s(I4), OUT4] }],
    ['LightTree', wc.LightTree, tree, { sample: [F32(P_PROBE), F32(N_PROBE), F32(U4)], pmf: [F32(P_PROBE), F32(N_PROBE), U32s(I4), OUT4] }],
    // The base's methods, on each class's object.
    ['Stored', Stored, kept, { storage: [] }],
    ['Stored', Stored, alias, { storage: [] }],
    ['Stored', Stored, tree, { storage: [] }],
  ];
  for (const [name, C, obj, methods] of CLASSES) {
    for (const method in methods) {
      const f = C.prototype[method];
      const specs = methods[method];
      const good = () => specs.map((s) => s.good());
      const want = rApply(f, obj, good());
      const goodArgs = good();
      expectSame(() => rApply(f, obj, goodArgs), want, `${name}.${method}`);
      for (let k = 0; k < specs.length; k++) {
        const spec = specs[k];
        const variants = spec.str ? hostileStrings(spec.good()) : hostileArrays(spec.T, spec.good());
        for (const [what, value, Want] of variants) {
          const args = good();
          args[k] = value;
          const label = `${name}.${method} argument ${k}: ${what}`;
          if (Want) expectError(() => rApply(f, obj, args), Want, label);
          else if (!spec.out) expectSame(() => rApply(f, obj, args), want, label);
          cases++;
        }
      }
      const strangers = [{}, null, Object.create(C.prototype), new Proxy(obj, {})];
      if (C !== Stored) strangers.push(C === wc.LightTree ? alias : other);
      for (const self of strangers) {
        expectError(() => rApply(f, self, goodArgs), TE, `${name}.${method} on a stranger`);
        cases++;
      }
      COVERED.add(`${name}.prototype.${method}`);
    }
  }
  const storageLength = Object.getOwnPropertyDescriptor(Stored.prototype, 'storageLength').get;
  for (const obj of [kept, alias, tree]) expectSame(() => rApply(storageLength, obj, []), obj.storageLength, 'storageLength');
  expectError(() => rApply(storageLength, {}, []), TE, 'storageLength on a non-Stored');
  COVERED.add('Stored.prototype.storageLength');
  const makers = [() => wc.envmapHierarchical(new Float32Array([1, 2, 3, 4]), 2, 2), () => wc.lightsAlias(new Float32Array([1, 2])), () => wc.lightsTree(new Float32Array(BOUNDS))];
  for (const key of ['free', Symbol.dispose]) {
    for (const make of makers) {
      const r = make();
      expectSame(() => r[key](), undefined, `${r.constructor.name}.${String(key)}`);
      expectSame(() => r[key](), undefined, `${r.constructor.name}.${String(key)} twice`);
      expectError(() => r.storage(), TE, `storage after ${String(key)}`);
      if (r instanceof wc.EnvMap) expectError(() => r.sample(U_PROBE), TE, `EnvMap.sample after ${String(key)}`);
      else if (r instanceof wc.AliasTable) expectError(() => r.sample(0.5), TE, `AliasTable.sample after ${String(key)}`);
      else expectError(() => r.pmf(P_PROBE, N_PROBE, I4), TE, `LightTree.pmf after ${String(key)}`);
    }
    for (const self of [{}, null, Object.create(wc.EnvMap.prototype), Object.create(Stored.prototype)]) expectError(() => rApply(Stored.prototype[key], self, []), TE, `${String(key)} on a non-Stored`);
    COVERED.add(`Stored.prototype.${String(key)}`);
  }
  for (const [name, C] of [['EnvMap', wc.EnvMap], ['AliasTable', wc.AliasTable], ['LightTree', wc.LightTree], ['Stored', Stored]]) {
    for (const args of [[], [Symbol('Stored'), 'hierarchical', 64, 16]]) {
      expectError(() => rConstruct(C, args), TE, `new ${name}`);
      expectError(() => rApply(C, undefined, args), TE, `${name} called`);
    }
    COVERED.add(name);
  }
  const aliasBefore = summary(alias);
  const treeBefore = summary(tree);
  // SamplerPath methods: every argument hostile, `this` not a SamplerPath.
  const root = wc.samplerPath().domain(1);
  const PATH_METHODS = { domain: [NUM(3)], split: [NUM(3), NUM(4), NUM(1)] };
  for (const method in PATH_METHODS) {
    const specs = PATH_METHODS[method];
    const good = () => specs.map((s) => s.good());
    const f = Object.getPrototypeOf(root)[method];
    const want = wc.samplerDraw('sobol', new Uint32Array([1, 2]), 0, 3, 4, rApply(f, root, good()), 4);
    const goodArgs = good();
    const [r] = call(() => rApply(f, root, goodArgs));
    assert.deepEqual(wc.samplerDraw('sobol', new Uint32Array([1, 2]), 0, 3, 4, r, 4), want, `SamplerPath.${method}`);
    for (let k = 0; k < specs.length; k++) {
      for (const [what, value, Want] of hostileNumbers()) {
        const args = good();
        args[k] = value;
        expectError(() => rApply(f, root, args), Want, `SamplerPath.${method} argument ${k}: ${what}`);
        cases++;
      }
    }
    for (const self of [{}, null, Object.create(Object.getPrototypeOf(root)), new Proxy(root, {})]) {
      expectError(() => rApply(f, self, goodArgs), TE, `SamplerPath.${method} on a non-SamplerPath`);
      cases++;
    }
    COVERED.add(`SamplerPath.prototype.${method}`);
  }
  const pathLength = Object.getOwnPropertyDescriptor(Object.getPrototypeOf(root), 'length').get;
  expectSame(() => rApply(pathLength, root, []), 1, 'SamplerPath.length');
  expectError(() => rApply(pathLength, {}, []), TE, 'SamplerPath.length on a non-SamplerPath');
  COVERED.add('SamplerPath.prototype.length');
  for (const args of [[], [Symbol('SamplerPath'), new Uint32Array(4)]]) {
    expectError(() => rConstruct(root.constructor, args), TE, 'new SamplerPath');
    expectError(() => rApply(root.constructor, undefined, args), TE, 'SamplerPath called');
  }
  COVERED.add('SamplerPath');
  // The class and its prototype are frozen: no method swapped, no setter planted.
  assert.throws(() => {
    wc.EnvMap.prototype.sample = () => 0;
  }, TypeError);
  assert.throws(() => Object.defineProperty(wc.EnvMap.prototype, 'kind', { set() {} }), TypeError);
  assert.ok(Object.isFrozen(wc.EnvMap) && Object.isFrozen(wc));
  assert.deepEqual(envSummary(kept), keptBefore, 'the EnvMap still samples what it did');
  assert.deepEqual(summary(alias), aliasBefore, 'the AliasTable still samples what it did');
  assert.deepEqual(summary(tree), treeBefore, 'the LightTree still samples what it did');
  for (const C of [wc.AliasTable, wc.LightTree, Stored]) assert.ok(Object.isFrozen(C) && Object.isFrozen(C.prototype));
  kept.free();
  alias.free();
  tree.free();
  other.free();
  assert.equal(wc.memoryStats().reserved, reserved, 'no memory left reserved');
  t.diagnostic(`${cases} hostile arguments, ${calls} calls so far`);
  assert.ok(cases > 900, `${cases} cases`);
});

test('load: a bad source is a TypeError (a rejected promise)', async () => {
  for (const source of [Symbol('wasm'), 4, Object(4), {}, [], true, () => 0]) {
    await assert.rejects(load(source), (e) => Object.getPrototypeOf(e) === TypeError.prototype, String(typeof source));
  }
  COVERED.add('load');
});

test('a SamplerPath cannot be changed, nor its class patched', () => {
  const path = wc.samplerPath().domain(3).split(1, 4, 2);
  const pix = new Uint32Array([1, 2]);
  const draw = () => wc.samplerDraw('sobol', pix, 0, 5, 7, path, 4);
  const before = draw();
  // Whatever the class and its prototype expose, nothing returns the path's steps to change.
  const C = path.constructor;
  for (const o of [C, C.prototype]) {
    for (const key of Reflect.ownKeys(o)) {
      const d = Object.getOwnPropertyDescriptor(o, key);
      for (const f of [d.value, d.get]) {
        if (typeof f !== 'function' || f === C) continue;
        let r;
        try {
          r = f.call(o === C ? undefined : path, path);
        } catch {
          continue;
        }
        if (ArrayBuffer.isView(r) && !Object.isFrozen(r)) for (let i = 0; i < r.length; i++) r[i] ^= 6;
      }
    }
  }
  assert.deepEqual(draw(), before, 'the path drew other points');
  // Frozen: no static method replaced or added (the module would call it on every draw).
  assert.ok(Object.isFrozen(C) && Object.isFrozen(C.prototype) && Object.isFrozen(path));
  let ran = 0;
  for (const key of ['steps', 'from', Symbol.hasInstance]) {
    assert.throws(() => {
      C[key] = () => ran++;
    }, TypeError);
  }
  expectSame(draw, before, 'samplerDraw on the path');
  assert.equal(ran, 0);
});

test('index setters that swallow writes: an EnvMap from storage keeps its memory', () => {
  const u = new Float32Array([0.1, 0.2, 0.7, 0.4]);
  const plainEnv = wc.envmapFromStorage(STORAGE.slice());
  const want = [plainEnv.sample(u), plainEnv.pdf(u), plainEnv.storage()];
  plainEnv.free();
  const keys = [];
  for (let i = 0; i < 16; i++) keys.push(String(i));
  const swallowed = { n: 0 };
  for (let i = 0; i < keys.length; i++) {
    rDefine(Array.prototype, keys[i], { configurable: true, get() {}, set() { swallowed.n++; } }); // prettier-ignore
  }
  let got;
  let error;
  try {
    const env = wc.envmapFromStorage(STORAGE.slice());
    got = { __proto__: null, sample: env.sample(u), pdf: env.pdf(u), storage: env.storage() };
    env.free();
  } catch (e) {
    error = e;
  } finally {
    for (let i = 0; i < keys.length; i++) rDelete(Array.prototype, keys[i]);
  }
  assert.equal(error, undefined, `${error?.constructor?.name}: ${error?.message}`);
  assert.deepEqual([got.sample, got.pdf, got.storage], want);
  assert.equal(swallowed.n, 0, 'the module wrote array indices');
});

test('every export has a hostile case', () => {
  const exported = [];
  for (const key of Object.keys(warpcore)) if (typeof warpcore[key] === 'function') exported.push(key);
  for (const key of Object.keys(wc)) if (typeof wc[key] === 'function') exported.push(key);
  const classes = [['EnvMap', wc.EnvMap.prototype], ['AliasTable', wc.AliasTable.prototype], ['LightTree', wc.LightTree.prototype], ['Stored', Stored.prototype], ['SamplerPath', Object.getPrototypeOf(wc.samplerPath())]];
  for (const [name, proto] of classes) {
    for (const key of Reflect.ownKeys(proto)) if (key !== 'constructor') exported.push(`${name}.prototype.${String(key)}`);
    for (const key of Reflect.ownKeys(proto.constructor)) if (typeof proto.constructor[key] === 'function') exported.push(`${name}.${String(key)}`);
  }
  const missing = exported.filter((name) => !COVERED.has(name));
  assert.deepEqual(missing, [], 'exports without a hostile case');
});

test('aliasing: out is an input, or overlaps one through another view', (t) => {
  let cases = 0;
  const u = new Float32Array(64).map((_, i) => ((i * 37) % 64) / 64);
  for (const name of ['diskPolar', 'diskConcentric', 'diskConcentricInverse', 'sphereEqualAreaWrap', 'sphereEqualAreaPdfToSolidAngle', 'envmapLuminance', 'triangleUniformInverse']) {
    const I = { envmapLuminance: 3, triangleUniformInverse: 3, sphereEqualAreaPdfToSolidAngle: 1 }[name] ?? 2;
    const O = { envmapLuminance: 1, sphereEqualAreaPdfToSolidAngle: 1 }[name] ?? 2;
    const input = u.slice(0, I * 8);
    const want = wc[name](input);
    if (I === O) {
      const same = input.slice();
      expectSame(() => wc[name](same, same), want, `${name}(x, x)`);
      cases++;
    }
    for (const shift of [-3, -1, 1, 2, 5]) {
      // One buffer; the output view starts `shift` elements from the input's.
      const buffer = new ArrayBuffer(4 * (I * 8 + O * 8 + 16));
      const a = new Float32Array(buffer, 4 * 8, I * 8);
      a.set(input);
      const out = new Float32Array(buffer, 4 * (8 + shift), O * 8);
      expectSame(() => wc[name](a, out), want, `${name} out shifted ${shift}`);
      cases++;
    }
  }
  // Two-input functions: out aliasing either input.
  const pdf = new Float32Array([1, 2, 3, 4]);
  const d = new Float32Array([1, 0, 0, 0, 1, 0, 0, 0, 1, 0.6, 0.8, 0]);
  const want = wc.sphereEquirectPdfToSolidAngle(pdf, d);
  const p2 = pdf.slice();
  const d3 = d.slice();
  expectSame(() => wc.sphereEquirectPdfToSolidAngle(p2, d3, p2), want, 'pair out = pdf');
  const d2 = d.slice();
  const d2out = d2.subarray(4, 8);
  expectSame(() => wc.sphereEquirectPdfToSolidAngle(pdf, d2, d2out), want, 'pair out inside d');
  const v = new Float32Array([0.1, 0.5, 0.9, 0.3]);
  const wantV = wc.envmapEquirectPdfToSolidAngle(pdf, v);
  const v2 = v.slice();
  expectSame(() => wc.envmapEquirectPdfToSolidAngle(pdf, v2, v2), wantV, 'equirect out = v');
  cases += 3;
  // EnvMap.pdf into its own input.
  const env = wc.envmapMarginalConditional(new Float32Array([1, 2, 3, 4]), 2, 2);
  const uv = new Float32Array([0.1, 0.2, 0.6, 0.7, 0.3, 0.9, 0.8, 0.1]);
  const wantPdf = env.pdf(uv);
  const uv2 = uv.slice();
  const uv2out = uv2.subarray(0, 4);
  expectSame(() => env.pdf(uv2, uv2out), wantPdf, 'EnvMap.pdf out inside uv');
  env.free();
  cases++;
  t.diagnostic(`${cases} aliasing cases`);
});

test('patched built-ins after loading change nothing', (t) => {
  // Break the methods and getters a careless module would call; the API must not notice.
  // Every function with its good arguments (and the EnvMap and SamplerPath methods) runs with
  // these throwing; the test's own code while they are broken uses indexed loops, captured
  // intrinsics and null-prototype objects only.
  const all = (o) => Reflect.ownKeys(o).filter((k) => k !== 'constructor' && k !== 'prototype' && k !== 'length' && k !== 'name' && k !== '__proto__');
  const indices = [];
  for (let i = 0; i < 16; i++) indices.push(String(i));
  const targets = [
    [TypedArray, all(TypedArray)],
    [TypedArray.constructor, all(TypedArray.constructor)],
    [Array.prototype, [Symbol.iterator, 'map', 'find', 'splice', 'push', 'findIndex', 'reduce', 'forEach', 'slice', 'concat', 'fill', 'indexOf', 'includes', 'join', 'keys', 'values', 'entries', ...indices]],
    [Object.prototype, indices],
    [ArrayIteratorPrototype, ['next']],
    [IteratorPrototype, [Symbol.iterator]],
    [Array, all(Array)],
    [WebAssembly.Memory.prototype, ['buffer', 'grow']],
    [ArrayBuffer, ['isView']],
    [ArrayBuffer.prototype, ['byteLength', 'slice']],
    [Object, all(Object)],
    [Math, all(Math).filter((k) => typeof Math[k] === 'function')],
    [Number, all(Number).filter((k) => typeof Number[k] === 'function')],
    [Number.prototype, all(Number.prototype)],
    [String.prototype, all(String.prototype)],
    [Function.prototype, ['call', 'apply', 'bind']],
  ];
  for (const T of [Float32Array, Uint32Array, Int32Array, Uint8Array]) targets.push([T, all(T).filter((k) => typeof T[k] === 'function')]);
  const saved = [];
  for (let i = 0; i < targets.length; i++) {
    const keys = targets[i][1];
    for (let j = 0; j < keys.length; j++) saved.push([targets[i][0], keys[j], Object.getOwnPropertyDescriptor(targets[i][0], keys[j])]);
  }
  const thrower = () => {
    throw new Error('a patched built-in ran');
  };
  // The calls: every function of SPEC, then methods, with their arguments made beforehand.
  const env = wc.envmapHierarchical(new Float32Array([1, 2, 0, 3, 1, 1, 4, 0]), 4, 2);
  const path = wc.samplerPath().domain(4);
  const u = new Float32Array([0.1, 0.2, 0.3, 0.4]);
  const DIRS = new Float32Array([0, 0, 1, 0.6, 0, 0.8]);
  const jobs = [];
  for (const name in SPEC) jobs.push([name, wc[name], wc, SPEC[name].map((s) => s.good())]);
  jobs.push(['big pmj02bnSample (grows the memory)', wc.pmj02bnSample, wc, [0, 1, 300_000]]);
  jobs.push(['diskPolar4', wc.diskPolar4, wc, [u, 6]]);
  for (const [method, args] of [['sample', [u]], ['pdf', [u]], ['sampleDirection', ['equirect', u]], ['pdfDirection', ['equal-area', DIRS]], ['storage', []]]) {
    jobs.push([`EnvMap.${method}`, wc.EnvMap.prototype[method], env, args]);
  }
  const alias = wc.lightsAlias(new Float32Array(ALIAS_WEIGHTS));
  const tree = wc.lightsTree(new Float32Array(BOUNDS));
  const P1 = P_PROBE.slice(0, 3);
  const N1 = N_PROBE.slice(0, 3);
  for (const [method, args] of [['sample', [U4]], ['sample', [0.7]], ['pmf', [I4]], ['pmf', [2]], ['storage', []]]) {
    jobs.push([`AliasTable.${method}`, wc.AliasTable.prototype[method], alias, args]);
  }
  for (const [method, args] of [['sample', [P_PROBE, N_PROBE, U4]], ['sample', [P1, N1, 0.3]], ['pmf', [P_PROBE, N_PROBE, I4]], ['pmf', [P1, N1, 0]], ['storage', []]]) {
    jobs.push([`LightTree.${method}`, wc.LightTree.prototype[method], tree, args]);
  }
  jobs.push(['SamplerPath.split', path.split, path, [1, 2, 3]]);
  jobs.push(['samplerDraw on a SamplerPath', wc.samplerDraw, wc, ['pmj02bn', new Uint32Array([1, 2]), 0, 3, 4, path.split(1, 2, 3), 4]]);
  const want = jobs.map(([, f, self, args]) => rApply(f, self, args));
  const got = { __proto__: null };
  let error;
  for (let i = 0; i < saved.length; i++) {
    const d = saved[i][2];
    rDefine(saved[i][0], saved[i][1], !d || d.get || d.set ? { configurable: true, get: thrower, set: thrower } : { configurable: true, writable: true, value: thrower });
  }
  let at = 0;
  try {
    for (; at < jobs.length; at++) got[at] = rApply(jobs[at][1], jobs[at][2], jobs[at][3]);
  } catch (e) {
    error = e;
  } finally {
    for (let i = saved.length - 1; i >= 0; i--) {
      if (saved[i][2]) rDefine(saved[i][0], saved[i][1], saved[i][2]);
      else rDelete(saved[i][0], saved[i][1]);
    }
  }
  assert.equal(error, undefined, `${jobs[at]?.[0]} used a patched built-in: ${error?.stack}`);
  for (let i = 0; i < jobs.length; i++) {
    if (want[i] instanceof Stored) {
      assert.deepEqual(summary(got[i]), summary(want[i]), jobs[i][0]);
      got[i].free();
      want[i].free();
    } else if (jobs[i][0] === 'memoryStats' || jobs[i][0].startsWith('SamplerPath')) {
      assert.equal(typeof got[i], typeof want[i], jobs[i][0]);
    } else {
      assert.deepEqual(got[i], want[i], jobs[i][0]);
    }
  }
  env.free();
  alias.free();
  tree.free();
  t.diagnostic(`${jobs.length} calls with ${saved.length} built-ins broken`);
});

test('options.verify: read once, first; a throwing getter becomes a TypeError', () => {
  let reads = 0;
  const words = STORAGE.slice();
  const env = wc.envmapFromStorage(words, {
    get verify() {
      reads++;
      return false;
    },
  });
  assert.equal(reads, 1);
  env.free();
  for (const [options, Want] of [
    [{ get verify() { throw new RangeError('mine'); } }, TypeError], // prettier-ignore
    [new Proxy({}, { get() { throw new Error('trap'); } }), TypeError], // prettier-ignore
    [{ verify: 'yes' }, TypeError],
    [{ verify: 1 }, TypeError],
    [null, TypeError],
    ['verify', TypeError],
  ]) {
    const e = assert.throws(() => wc.envmapFromStorage(words, options), (e) => Object.getPrototypeOf(e) === Want.prototype);
    void e;
  }
  for (const verify of [true, false, undefined]) wc.envmapFromStorage(words, { verify }).free();
  wc.envmapFromStorage(words).free();
});

test('summary', (t) => {
  t.diagnostic(`${calls} hostile calls made through the spies`);
});
