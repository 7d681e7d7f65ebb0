// warpcore for JavaScript: sample warps (disk, triangle, sphere), pmj02bn points, baseline
// samplers and environment-map importance sampling, bit-identical to the Rust crate.
//
// An ES module over `warpcore.wasm`, the C ABI crate (capi/) built for wasm32-unknown-unknown
// (see js/build.sh): no imports, no wasm-bindgen, no bundler. Every function takes and returns
// typed arrays, interleaved as in C (`n` points of the square are `2n` floats `u0 v0 u1 v1 ...`,
// directions and barycentrics `3n` floats), and checks its arguments in JavaScript: a wrong
// type throws a TypeError, a bad count or length a RangeError, never a wasm trap.
//
// Memory: the Rust library never allocates, so the module's linear memory above `__heap_base`
// is unused by Rust. This file manages that region (`Heap`): each call reserves one block for
// its input and output arrays, copies the inputs in, calls the C function and copies the
// outputs out; environment-map tables live in blocks owned by an `EnvMap` until it is freed.
// The memory grows on demand and is never shrunk (WebAssembly cannot shrink memory).
// See docs/javascript.md.

// Intrinsics, captured when this module is evaluated. The argument checks, the copies in and
// out of wasm memory and the error messages use only these: no user code runs during a call
// (not a typed-array subclass's methods or getters, a Proxy trap, a `toString`/`valueOf`, or a
// built-in prototype patched after loading), and no view of the module's memory is ever
// handed to anything but these intrinsics. See docs/javascript.md, "Hostile callers".
const {
  ArrayBuffer: ArrayBuffer_,
  Error: Error_,
  FinalizationRegistry: FinalizationRegistry_,
  Float32Array: F32,
  Function: Function_,
  Int32Array: I32,
  Math: Math_,
  Number: Number_,
  Object: Object_,
  RangeError: RangeError_,
  Symbol: Symbol_,
  TypeError: TypeError_,
  Uint8Array: U8,
  Uint32Array: U32,
  WebAssembly: WebAssembly_,
} = globalThis;
const uncurry = Function_.prototype.bind.bind(Function_.prototype.call);
const getPrototypeOf = Object_.getPrototypeOf;
const defineProperty = Object_.defineProperty;
const freeze = Object_.freeze;
const isView = ArrayBuffer_.isView;
const isInteger = Number_.isInteger;
const ceil = Math_.ceil;
const getter = (o, key) => uncurry(Object_.getOwnPropertyDescriptor(o, key).get);
const TypedArray = getPrototypeOf(U8.prototype);
const TA_TAG = getter(TypedArray, Symbol_.toStringTag);
const TA_LENGTH = getter(TypedArray, 'length');
const TA_BUFFER = getter(TypedArray, 'buffer');
const TA_BYTE_OFFSET = getter(TypedArray, 'byteOffset');
const TA_SET = uncurry(TypedArray.set);
const TA_BYTE_LENGTH = getter(TypedArray, 'byteLength');
const DV_BUFFER = getter(globalThis.DataView.prototype, 'buffer');
const DV_BYTE_OFFSET = getter(globalThis.DataView.prototype, 'byteOffset');
const DV_BYTE_LENGTH = getter(globalThis.DataView.prototype, 'byteLength');
const MEMORY_BUFFER = getter(WebAssembly_.Memory.prototype, 'buffer');
const MEMORY_GROW = uncurry(WebAssembly_.Memory.prototype.grow);
const AB_BYTE_LENGTH = getter(ArrayBuffer_.prototype, 'byteLength');
const REGISTER = FinalizationRegistry_ ? uncurry(FinalizationRegistry_.prototype.register) : null;
const UNREGISTER = FinalizationRegistry_ ? uncurry(FinalizationRegistry_.prototype.unregister) : null;
const instantiate = WebAssembly_.instantiate;
const compileBytes = WebAssembly_.compile;
const DISPOSE = Symbol_.dispose ?? Symbol_.for('Symbol.dispose');

// The typed-array types the API takes: constructor, exact prototype, name (the intrinsic
// [Symbol.toStringTag]) and element size.
const TYPES = {
  __proto__: null,
  Float32Array: { __proto__: null, T: F32, proto: F32.prototype, name: 'Float32Array', bytes: 4 },
  Uint32Array: { __proto__: null, T: U32, proto: U32.prototype, name: 'Uint32Array', bytes: 4 },
  Int32Array: { __proto__: null, T: I32, proto: I32.prototype, name: 'Int32Array', bytes: 4 },
};
const F = TYPES.Float32Array;
const U = TYPES.Uint32Array;
const I = TYPES.Int32Array;
const BYTES = { __proto__: null, T: U8, bytes: 1 }; // views of wasm memory as bytes (storage loaders)

const isNode = typeof process === 'object' && process !== null && typeof process.versions?.node === 'string';

/** Largest element count accepted by any function (`size_t` on wasm32). */
export const MAX_COUNT = 0xffff_ffff;

// ---------------------------------------------------------------------------------------------
// Loading

/**
 * Loads and instantiates the WebAssembly module.
 *
 * `source` may be nothing (the `warpcore.wasm` next to this file), a URL or string (fetched;
 * in Node, a `file:` URL or a path is read from disk), a `Response` (or a promise of one),
 * the module's bytes (`ArrayBuffer` or a typed array), or a compiled `WebAssembly.Module`.
 */
export async function load(source) {
  const module = await compile(source === undefined || source === null ? new URL('./warpcore.wasm', import.meta.url) : source);
  // An empty import object: the module imports nothing (if a panic path were linked, the
  // module would import `env.abort` and this would throw a LinkError).
  const instance = await instantiate(module, {});
  return create(instance.exports);
}

async function compile(source) {
  if (source instanceof WebAssembly.Module) return source;
  if (source instanceof ArrayBuffer || ArrayBuffer.isView(source)) return WebAssembly.compile(source);
  if (typeof source === 'string' || source instanceof URL) {
    let url = null;
    try {
      url = new URL(source);
    } catch {
      // A relative string: a path in Node, a URL relative to the page in browsers.
    }
    if (isNode && (url === null || url.protocol === 'file:')) {
      const { readFile } = await import('node:fs/promises');
      return WebAssembly.compile(await readFile(url ?? source));
    }
    return compile(fetch(url ?? source));
  }
  if (source !== null && typeof source === 'object' && typeof source.then === 'function') {
    return compile(await source);
  }
  if (typeof Response === 'function' && source instanceof Response) {
    if (!source.ok) throw new Error(`warpcore: fetching the module failed: ${source.status} ${source.statusText} (${source.url})`);
    const type = source.headers.get('content-type') ?? '';
    if (typeof WebAssembly.compileStreaming === 'function' && type.split(';')[0].trim() === 'application/wasm') {
      return WebAssembly.compileStreaming(source);
    }
    return WebAssembly.compile(await source.arrayBuffer());
  }
  throw new TypeError(`warpcore: load() takes a URL, a path, a Response, bytes or a WebAssembly.Module, not ${describe(source)}`);
}

// ---------------------------------------------------------------------------------------------
// Argument checks: intrinsics only (see the top of this file)

const typeError = (message) => new TypeError_(`warpcore: ${message}`);
const rangeError = (message) => new RangeError_(`warpcore: ${message}`);

/** What `x` is, for an error message, without running user code. */
function describe(x) {
  if (x === null) return 'null';
  const t = typeof x;
  if (t !== 'object' && t !== 'function') return t;
  if (isView(x)) {
    const tag = TA_TAG(x);
    if (tag === undefined) return 'a DataView';
    const known = TYPES[tag];
    return known !== undefined && getPrototypeOf(x) !== known.proto ? `a ${tag} subclass (or one from another realm)` : `a ${tag}`;
  }
  return t === 'function' ? 'a function' : 'an object';
}

/** Is the typed array `a` over a detached buffer? (Its intrinsic length then reads 0.) */
function detached(a) {
  if (TA_LENGTH(a) !== 0) return false;
  try {
    new U8(TA_BUFFER(a), 0, 0);
    return false;
  } catch {
    return true;
  }
}

/**
 * Checks that `a` is exactly a `type` (a typed array of this realm whose prototype is the
 * type's own: no subclass, no Proxy, no DataView) over a live buffer, and returns its length
 * read with the intrinsic getter.
 */
function array(a, type, name) {
  // `isView` is false for a Proxy; for a real typed array the tag getter and the prototype
  // lookup run no user code.
  if (!isView(a) || TA_TAG(a) !== type.name || getPrototypeOf(a) !== type.proto) {
    throw typeError(`${name} must be a ${type.name}, not ${describe(a)}`);
  }
  if (detached(a)) throw typeError(`${name} is a ${type.name} over a detached ArrayBuffer`);
  return TA_LENGTH(a);
}

function elements(a, type, dim, name) {
  const length = array(a, type, name);
  if (length % dim !== 0) {
    throw rangeError(`${name}.length must be a multiple of ${dim}, got ${length}`);
  }
  return length / dim;
}

function integer(x, name, max) {
  if (typeof x !== 'number') throw typeError(`${name} must be a number, not ${describe(x)}`);
  if (!isInteger(x) || x < 0 || x > max) {
    throw rangeError(`${name} must be an integer in [0, ${max}], got ${x}`);
  }
  return x;
}

const count = (n, name = 'n') => integer(n, name, MAX_COUNT);
const u32 = (x, name) => integer(x, name, 0xffff_ffff);

function output(out, type, length) {
  if (out === undefined) return new type.T(length);
  const got = array(out, type, 'out');
  if (got !== length) throw rangeError(`out.length must be ${length}, got ${got}`);
  return out;
}

/** The first `length` elements of the typed array `a`, as a new view of its buffer. */
const prefix = (a, type, length) => new type.T(TA_BUFFER(a), TA_BYTE_OFFSET(a), length);

// ---------------------------------------------------------------------------------------------
// The heap above __heap_base

const BLOCK_ALIGN = 64; // env-map tables are best 64-byte aligned; every block is
const PAGE = 65536;
const ADDRESS_SPACE = 2 ** 32;
const alignUp = (x, a) => ceil(x / a) * a;

// Live blocks [start, end), sorted by start, in two null-prototype objects indexed 0 ..
// count - 1: no index read or write can reach a getter or setter a caller planted on
// Array.prototype or Object.prototype, and no Array.prototype method runs.
function makeHeap(memory, base_) {
  const base = alignUp(base_, BLOCK_ALIGN);
  const starts = { __proto__: null };
  const ends = { __proto__: null };
  let count = 0;

  /** Reserves `bytes` (first fit), growing the memory when needed; RangeError when it cannot. */
  function alloc(bytes) {
    const size = alignUp(bytes > 1 ? bytes : 1, BLOCK_ALIGN);
    let at = base;
    let i = 0;
    for (; i < count; i++) {
      if (starts[i] - at >= size) break;
      at = ends[i];
    }
    const end = at + size;
    if (end > ADDRESS_SPACE) {
      throw rangeError(`${bytes} bytes do not fit in the 4 GiB of wasm32 memory`);
    }
    const have = AB_BYTE_LENGTH(MEMORY_BUFFER(memory));
    if (end > have) {
      try {
        MEMORY_GROW(memory, ceil((end - have) / PAGE));
      } catch {
        throw rangeError(`cannot grow the wasm memory to ${end} bytes`);
      }
    }
    for (let k = count; k > i; k--) {
      starts[k] = starts[k - 1];
      ends[k] = ends[k - 1];
    }
    starts[i] = at;
    ends[i] = end;
    count++;
    return at;
  }

  function free(start) {
    for (let i = 0; i < count; i++) {
      if (starts[i] === start) {
        for (let k = i; k + 1 < count; k++) {
          starts[k] = starts[k + 1];
          ends[k] = ends[k + 1];
        }
        count--;
        delete starts[count];
        delete ends[count];
        return;
      }
    }
  }

  /** Bytes reserved by live blocks. */
  function used() {
    let sum = 0;
    for (let i = 0; i < count; i++) sum += ends[i] - starts[i];
    return sum;
  }

  return { __proto__: null, alloc, free, used };
}

// ---------------------------------------------------------------------------------------------
// The API

const CODES = {
  __proto__: null,
  '-1': ['WC_ERR_ZERO_SIZE', 'a zero width or height'],
  '-2': ['WC_ERR_TOO_LARGE', 'a side above 2^24, too many lights, or tables above 2^32 words'],
  '-3': ['WC_ERR_LENGTH_MISMATCH', 'an array length that does not match the sizes'],
  '-4': ['WC_ERR_STORAGE_TOO_SMALL', 'storage shorter than its header says'],
  '-5': ['WC_ERR_INFINITE_WEIGHT', 'a +Infinity weight'],
  '-6': ['WC_ERR_WRONG_FORMAT', 'not a storage of this kind (or a byte-swapped one)'],
  '-7': ['WC_ERR_UNSUPPORTED_VERSION', 'a storage format version this build does not read (older storages: rebuild the tables from the weights)'],
  '-8': ['WC_ERR_CORRUPT', 'a header or table word a build never writes, or content that does not match its checksum'],
  '-9': ['WC_ERR_INVALID_ARGUMENT', 'an invalid argument'],
  '-11': ['WC_ERR_EMPTY', 'no lights'],
  '-12': ['WC_ERR_INVALID_WEIGHT', "a light's weight or power is NaN, infinite or negative"],
  '-13': ['WC_ERR_INVALID_BOUNDS', "a light's bounds are unusable (NaN or infinite coordinates, min > max, a zero axis, a cosine outside [-1, 1])"],
  '-14': ['WC_ERR_ALL_ZERO', "every light's weight or power is zero"],
};

function fail(code, what) {
  const known = CODES[code];
  const name = known !== undefined ? known[0] : 'WC_ERR_OTHER';
  const meaning = known !== undefined ? known[1] : `error ${code}`;
  const e = new RangeError_(`warpcore: ${what}: ${meaning} (${name})`);
  // defineProperty, not assignment: no setter a caller put on RangeError.prototype runs.
  defineProperty(e, 'code', { value: name, writable: true, enumerable: true, configurable: true });
  return e;
}

// Environment-map storage tags (header word 0, little-endian bytes "wcHI" / "wcMC").
const tag = (s) => s.charCodeAt(0) | (s.charCodeAt(1) << 8) | (s.charCodeAt(2) << 16) | ((s.charCodeAt(3) << 24) >>> 0);
const KINDS = {
  __proto__: null,
  // `kind`: the C ABI's WC_ENVMAP_KIND_* value.
  hierarchical: { __proto__: null, kind: 0, tag: tag('wcHI') },
  'marginal-conditional': { __proto__: null, kind: 1, tag: tag('wcMC') },
};
const HEADER_WORDS = 16;
const SAMPLE_WORDS = 5; // WcEnvSample: uv[2], pdf, texel[2]
const DIRECTION_WORDS = 8; // WcEnvDirection: dir[3], pdf, uv[2], texel[2]
// `layout` of sampleDirection / pdfDirection: the C ABI's WC_ENVMAP_LAYOUT_* values.
const LAYOUTS = { __proto__: null, equirect: 0, 'equal-area': 1 };
function layoutOf(layout) {
  if (typeof layout !== 'string') throw typeError(`layout must be a string, not ${describe(layout)}`);
  const l = LAYOUTS[layout];
  if (l === undefined) throw rangeError(`layout must be 'equirect' or 'equal-area', got a string of length ${layout.length}`);
  return l;
}

function create(x) {
  const memory = x.memory;
  const heap = makeHeap(memory, x.__heap_base.value);
  /** A view of the module's memory: only ever passed to the intrinsics, never returned. */
  const view = (type, p, length) => new type.T(MEMORY_BUFFER(memory), p, length);

  // Runs `body(p0, p1, p2)` with one block holding up to three regions of `n0`, `n1`, `n2`
  // elements of the types `T0`, `T1`, `T2` (64-byte aligned; `T` null: no region; `s`, a
  // checked typed array of `n` or more elements, copied in, or undefined); the block is
  // released afterwards. Plain parameters, no array: nothing is read from or written to an
  // object whose prototype a caller can reach.
  function scratch(T0, n0, s0, T1, n1, s1, T2, n2, s2, body) {
    const b0 = T0 === null ? 0 : alignUp(n0 * T0.bytes, BLOCK_ALIGN);
    const b1 = T1 === null ? 0 : alignUp(n1 * T1.bytes, BLOCK_ALIGN);
    const b2 = T2 === null ? 0 : alignUp(n2 * T2.bytes, BLOCK_ALIGN);
    const base = heap.alloc(b0 + b1 + b2);
    try {
      copyIn(T0, base, n0, s0);
      copyIn(T1, base + b0, n1, s1);
      copyIn(T2, base + b0 + b1, n2, s2);
      return body(base, base + b0, base + b0 + b1);
    } finally {
      heap.free(base);
    }
  }
  const copyIn = (type, p, length, source) => {
    if (source === undefined) return;
    TA_SET(view(type, p, length), TA_LENGTH(source) === length ? source : prefix(source, type, length));
  };
  const scratch1 = (T0, n0, s0, body) => scratch(T0, n0, s0, null, 0, undefined, null, 0, undefined, body);
  const scratch2 = (T0, n0, s0, T1, n1, s1, body) => scratch(T0, n0, s0, T1, n1, s1, null, 0, undefined, body);
  const scratch3 = scratch;

  /** Copies `length` elements at `p` into `out` and returns it. */
  const read = (type, p, length, out) => {
    TA_SET(out, view(type, p, length));
    return out;
  };
  const expect = (got, want, what) => {
    if (got >>> 0 !== want) throw new Error_(`warpcore: internal error: ${what} returned ${got >>> 0}, expected ${want}`);
  };

  // `n` elements of `I` values of `In` to `n` elements of `O` values of `Out`: C `f(in, out, n)`.
  const map = (f, In, I, Out, O, name = 'u') => (input, out) => {
    const n = elements(input, In, I, name);
    const result = output(out, Out, n * O);
    if (n === 0) return result;
    return scratch2(In, n * I, input, Out, n * O, undefined, (pi, po) => {
      expect(f(pi, po, n), n, name);
      return read(Out, po, n * O, result);
    });
  };

  // Index-driven sequences: C `f(a, b, out, n)` (or `f(a, b, c, out, n)`) filling `n`
  // elements of `O` floats.
  const generate = (f, O, n, out, a, b, c) => {
    count(n);
    const result = output(out, F, n * O);
    if (n === 0) return result;
    return scratch1(F, n * O, undefined, (po) => {
      expect(c === undefined ? f(a, b, po, n) : f(a, b, c, po, n), n, 'generator');
      return read(F, po, n * O, result);
    });
  };

  // Four disk samples per point: C `f(points, n_points, out, n)`.
  const fourPerPoint = (f) => (points, n, out) => {
    const np = elements(points, F, 2, 'points');
    n = n === undefined ? 4 * np : count(n);
    if (n > 4 * np) throw rangeError(`n = ${n} needs ${ceil(n / 4)} points, got ${np}`);
    const result = output(out, F, 2 * n);
    if (n === 0) return result;
    const used = ceil(n / 4);
    return scratch2(F, 2 * used, points, F, 2 * n, undefined, (pp, po) => {
      expect(f(pp, used, po, n), n, 'four per point');
      return read(F, po, 2 * n, result);
    });
  };

  // Inverse with quadrants: C `f(p, out, quadrant, n)`.
  const withQuadrant = (f) => (p) => {
    const n = elements(p, F, 2, 'p');
    const u = new F32(2 * n);
    const quadrant = new U32(n);
    if (n === 0) return { u, quadrant };
    return scratch3(F, 2 * n, p, F, 2 * n, undefined, U, n, undefined, (pp, pu, pq) => {
      expect(f(pp, pu, pq, n), n, 'inverse');
      return { u: read(F, pu, 2 * n, u), quadrant: read(U, pq, n, quadrant) };
    });
  };

  // Two inputs of `n` and `n * D` floats to `n` floats: C `f(a, b, out, n)`.
  const pair = (f, D, nameA, nameB) => (a, b, out) => {
    const n = elements(a, F, 1, nameA);
    const m = elements(b, F, D, nameB);
    if (m !== n) {
      throw rangeError(`${nameB}.length must be ${D * n} (${D} per ${nameA} value), got ${D * m}`);
    }
    const result = output(out, F, n);
    if (n === 0) return result;
    return scratch3(F, n, a, F, D * n, b, F, n, undefined, (pa, pb, po) => {
      expect(f(pa, pb, po, n), n, nameA);
      return read(F, po, n, result);
    });
  };

  // Lights by solid angle: one light and shading point (`light`, 12 floats: v0, v1, v2, p or
  // corner, ex, ey, p), then C `f(light, in, out, n)`.
  const lightArg = (light, len = 12) => {
    if (elements(light, F, len, 'light') !== 1) {
      throw rangeError(`light.length must be ${len}, got ${TA_LENGTH(light)}`);
    }
  };
  const withLight = (f, I, O, name, len = 12) => (light, input, out) => {
    lightArg(light, len);
    const n = elements(input, F, I, name);
    const result = output(out, F, n * O);
    if (n === 0) return result;
    return scratch3(F, len, light, F, n * I, input, F, n * O, undefined, (pl, pi, po) => {
      expect(f(pl, pi, po, n), n, name);
      return read(F, po, n * O, result);
    });
  };
  const solidAngle = (f, len = 12) => (light) => {
    lightArg(light, len);
    return scratch1(F, len, light, (pl) => f(pl));
  };

  const api = {
    // disk
    diskPolar: map(x.wc_disk_polar, F, 2, F, 2),
    diskPolarInverse: map(x.wc_disk_polar_inverse, F, 2, F, 2, 'p'),
    diskConcentric: map(x.wc_disk_concentric, F, 2, F, 2),
    diskConcentricInverse: map(x.wc_disk_concentric_inverse, F, 2, F, 2, 'p'),
    diskPolar4: fourPerPoint(x.wc_disk_polar4),
    diskPolar4Inverse: withQuadrant(x.wc_disk_polar4_inverse),
    diskConcentric4: fourPerPoint(x.wc_disk_concentric4),
    diskConcentric4Inverse: withQuadrant(x.wc_disk_concentric4_inverse),

    // triangle
    triangleUniform: map(x.wc_triangle_uniform, F, 2, F, 3),
    triangleUniformInverse: map(x.wc_triangle_uniform_inverse, F, 3, F, 2, 'b'),
    triangleSqrtMap: map(x.wc_triangle_sqrt_map, F, 2, F, 3),
    triangleSqrtMapInverse: map(x.wc_triangle_sqrt_map_inverse, F, 3, F, 2, 'b'),
    triangleBasuOwen: (start, seed, n, out) =>
      generate(x.wc_triangle_basu_owen, 3, n, out, u32(start, 'start'), u32(seed, 'seed')),
    triangleBasuOwenPermuted: (start, seed, n, out) =>
      generate(x.wc_triangle_basu_owen_permuted, 3, n, out, u32(start, 'start'), u32(seed, 'seed')),

    // lights by solid angle
    sphericalTriangle: withLight(x.wc_spherical_triangle, 2, 4, 'u'),
    sphericalTriangleInverse: withLight(x.wc_spherical_triangle_inverse, 3, 2, 'b'),
    sphericalRectangle: withLight(x.wc_spherical_rectangle, 2, 3, 'u'),
    sphericalRectangleInverse: withLight(x.wc_spherical_rectangle_inverse, 2, 2, 'st'),
    sphericalTriangleCosine: withLight(x.wc_spherical_triangle_cosine, 2, 4, 'u', 15),
    sphericalRectangleCosine: withLight(x.wc_spherical_rectangle_cosine, 2, 3, 'u', 15),
    sphericalTriangleSolidAngle: solidAngle(x.wc_spherical_triangle_solid_angle),
    sphericalRectangleSolidAngle: solidAngle(x.wc_spherical_rectangle_solid_angle),
    sphericalCone: withLight(x.wc_spherical_cone, 2, 4, 'u', 7),
    sphericalConeInverse: withLight(x.wc_spherical_cone_inverse, 3, 2, 'dir', 7),
    sphericalConeSolidAngle: solidAngle(x.wc_spherical_cone_solid_angle, 7),

    // microfacet: records of packed arguments ([wo, alpha, u], [wo, wi or m, alpha], [w, alpha])
    microfacetGgxD: map(x.wc_microfacet_ggx_d, F, 5, F, 1, 'input'),
    microfacetGgxG1: map(x.wc_microfacet_ggx_g1, F, 5, F, 1, 'input'),
    microfacetGgxG2: map(x.wc_microfacet_ggx_g2, F, 8, F, 1, 'input'),
    microfacetGgxVisibleNormal: map(x.wc_microfacet_ggx_visible_normal, F, 7, F, 3, 'input'),
    microfacetGgxVisibleNormalPdf: map(x.wc_microfacet_ggx_visible_normal_pdf, F, 8, F, 1, 'input'),
    microfacetGgxReflect: map(x.wc_microfacet_ggx_reflect, F, 7, F, 4, 'input'),
    microfacetGgxReflectPdf: map(x.wc_microfacet_ggx_reflect_pdf, F, 8, F, 1, 'input'),
    microfacetGgxReflectBounded: map(x.wc_microfacet_ggx_reflect_bounded, F, 7, F, 4, 'input'),
    microfacetGgxReflectBoundedPdf: map(x.wc_microfacet_ggx_reflect_bounded_pdf, F, 8, F, 1, 'input'),

    // sphere
    sphereEqualArea: map(x.wc_sphere_equal_area, F, 2, F, 3),
    sphereEqualAreaInverse: map(x.wc_sphere_equal_area_inverse, F, 3, F, 2, 'd'),
    sphereEqualAreaWrap: map(x.wc_sphere_equal_area_wrap, F, 2, F, 2),
    sphereEquirect: map(x.wc_sphere_equirect, F, 2, F, 3),
    sphereEquirectInverse: map(x.wc_sphere_equirect_inverse, F, 3, F, 2, 'd'),
    sphereUniform: map(x.wc_sphere_uniform, F, 2, F, 3),
    sphereUniformInverse: map(x.wc_sphere_uniform_inverse, F, 3, F, 2, 'd'),
    sphereUniformHemisphere: map(x.wc_sphere_uniform_hemisphere, F, 2, F, 3),
    sphereUniformHemisphereInverse: map(x.wc_sphere_uniform_hemisphere_inverse, F, 3, F, 2, 'd'),
    sphereCosineHemisphere: map(x.wc_sphere_cosine_hemisphere, F, 2, F, 3),
    sphereCosineHemisphereInverse: map(x.wc_sphere_cosine_hemisphere_inverse, F, 3, F, 2, 'd'),
    sphereEqualAreaPdfToSolidAngle: map(x.wc_sphere_equal_area_pdf_to_solid_angle, F, 1, F, 1, 'pdf'),
    sphereCosineHemispherePdf: map(x.wc_sphere_cosine_hemisphere_pdf, F, 1, F, 1, 'cosTheta'),
    sphereEquirectPdfToSolidAngle: pair(x.wc_sphere_equirect_pdf_to_solid_angle, 3, 'pdf', 'd'),
    sphereEqualAreaWrapTexel(texels, size, out) {
      const n = elements(texels, I, 2, 'texels');
      if (u32(size, 'size') === 0) throw rangeError('size must be at least 1');
      const result = output(out, U, 2 * n);
      if (n === 0) return result;
      return scratch2(I, 2 * n, texels, U, 2 * n, undefined, (pt, po) => {
        expect(x.wc_sphere_equal_area_wrap_texel(pt, size, po, n), n, 'wc_sphere_equal_area_wrap_texel');
        return read(U, po, 2 * n, result);
      });
    },

    // pmj02bn and the baseline samplers
    pmj02bnSample: (start, seed, n, out) =>
      generate(x.wc_pmj02bn_sample, 2, n, out, u32(start, 'start'), u32(seed, 'seed')),
    pmj02bnRaw(set, start, n, out) {
      u32(set, 'set');
      u32(start, 'start');
      count(n);
      const result = output(out, U, 2 * n);
      if (n === 0) return result;
      return scratch1(U, 2 * n, undefined, (po) => {
        expect(x.wc_pmj02bn_raw(set, start, po, n), n, 'wc_pmj02bn_raw');
        return read(U, po, 2 * n, result);
      });
    },
    pmj02bnShuffle(index, seed, out) {
      if (typeof index === 'number') {
        // One index as a plain number: the shuffled index as a number.
        u32(index, 'index');
        u32(seed, 'seed');
        if (out !== undefined) throw typeError('out is only for a Uint32Array of indices');
        return scratch2(U, 1, undefined, U, 1, undefined, (pi, po) => {
          view(U, pi, 1)[0] = index;
          expect(x.wc_pmj02bn_shuffle(pi, seed, po, 1), 1, 'wc_pmj02bn_shuffle');
          return view(U, po, 1)[0];
        });
      }
      const n = elements(index, U, 1, 'index');
      u32(seed, 'seed');
      const result = output(out, U, n);
      if (n === 0) return result;
      return scratch2(U, n, index, U, n, undefined, (pi, po) => {
        expect(x.wc_pmj02bn_shuffle(pi, seed, po, n), n, 'wc_pmj02bn_shuffle');
        return read(U, po, n, result);
      });
    },
    pmj02bnPoints: x.wc_pmj02bn_points() >>> 0,
    pmj02bnSets: x.wc_pmj02bn_sets() >>> 0,
    sequenceRandom: (start, seed, n, out) =>
      generate(x.wc_sequence_random, 2, n, out, u32(start, 'start'), u32(seed, 'seed')),
    sequenceStratified: (start, count_, seed, n, out) =>
      generate(x.wc_sequence_stratified, 2, n, out, u32(start, 'start'), u32(count_, 'count'), u32(seed, 'seed')),

    // environment maps: helpers
    envmapLuminance: map(x.wc_envmap_luminance, F, 3, F, 1, 'rgb'),
    envmapEquirectPdfToSolidAngle: pair(x.wc_envmap_equirect_pdf_to_solid_angle, 1, 'pdf', 'v'),
    envmapEquirectSolidAngleWeights(weights, width, height) {
      const n = size(weights, width, height, 1, 'weights');
      const result = new F32(n);
      return scratch1(F, n, weights, (pw) => {
        const code = x.wc_envmap_equirect_solid_angle_weights(pw, width, height);
        if (code !== 0) throw fail(code, 'envmapEquirectSolidAngleWeights');
        return read(F, pw, n, result);
      });
    },
    envmapEquirectToEqualArea(src, srcWidth, srcHeight, channels, size_, supersample) {
      if (typeof channels !== 'number') throw typeError(`channels must be a number, not ${describe(channels)}`);
      if (!isInteger(channels) || channels < 1 || channels > 4) {
        throw rangeError(`channels must be 1, 2, 3 or 4, got ${channels}`);
      }
      const n = size(src, srcWidth, srcHeight, channels, 'src');
      u32(size_, 'size');
      u32(supersample, 'supersample');
      if (size_ === 0 || supersample === 0) throw fail(-1, 'envmapEquirectToEqualArea');
      if (size_ > 1 << 24 || supersample > 64) throw fail(-2, 'envmapEquirectToEqualArea');
      const m = size_ * size_ * channels;
      if (m > MAX_COUNT) throw fail(-2, 'envmapEquirectToEqualArea');
      const result = new F32(m);
      return scratch2(F, n, src, F, m, undefined, (ps, pd) => {
        const code = x.wc_envmap_equirect_to_equal_area(ps, srcWidth, srcHeight, channels, pd, size_, supersample);
        if (code !== 0) throw fail(code, 'envmapEquirectToEqualArea');
        return read(F, pd, m, result);
      });
    },
  };

  // The words of a storage: a Uint32Array, or the bytes of any other ArrayBufferView (a
  // Uint8Array at any offset, Node's Buffer, a DataView, ...) or of an ArrayBuffer, read as
  // little-endian words (the file format). Returns the word count, word 0 (-1 when there is
  // none) and a function copying the words to wasm memory at `p`. Intrinsics only.
  function storageWords(words) {
    if (isView(words) && TA_TAG(words) === 'Uint32Array' && getPrototypeOf(words) === U.proto) {
      const len = array(words, U, 'words');
      return { __proto__: null, len, first: len > 0 ? words[0] : -1, copy: (p) => TA_SET(view(U, p, len), words) };
    }
    let buffer;
    let offset;
    let bytes;
    if (isView(words)) {
      if (TA_TAG(words) !== undefined) {
        if (detached(words)) throw typeError('words is a typed array over a detached ArrayBuffer');
        buffer = TA_BUFFER(words);
        offset = TA_BYTE_OFFSET(words);
        bytes = TA_BYTE_LENGTH(words);
      } else {
        try {
          buffer = DV_BUFFER(words);
          offset = DV_BYTE_OFFSET(words);
          bytes = DV_BYTE_LENGTH(words);
        } catch {
          throw typeError('words is a DataView over a detached ArrayBuffer');
        }
      }
    } else {
      try {
        bytes = AB_BYTE_LENGTH(words);
      } catch {
        throw typeError(`words must be a Uint32Array, an ArrayBufferView of bytes or an ArrayBuffer, not ${describe(words)}`);
      }
      buffer = words;
      offset = 0;
    }
    if (bytes % 4 !== 0) throw rangeError(`words must hold whole 32-bit words, got ${bytes} bytes`);
    let src;
    try {
      src = new U8(buffer, offset, bytes);
    } catch {
      throw typeError('words is over a detached or shared buffer');
    }
    const len = bytes / 4;
    const first = len > 0 ? (src[0] | (src[1] << 8) | (src[2] << 16) | (src[3] << 24)) >>> 0 : -1;
    return { __proto__: null, len, first, copy: (p) => TA_SET(view(BYTES, p, bytes), src) };
  }

  // Checks `width x height` texels of `channels` floats in `a`; returns the length.
  function size(a, width, height, channels, name) {
    const length = array(a, F, name);
    u32(width, 'width');
    u32(height, 'height');
    if (width === 0 || height === 0) throw fail(-1, name);
    const n = width * height * channels;
    if (length !== n) {
      throw rangeError(`${name}.length must be ${n} (${width} x ${height}${channels > 1 ? ` x ${channels}` : ''}), got ${length}`);
    }
    return n;
  }

  // ---- tables in wasm memory, owned by an object: env maps and light selection ----

  const registry = FinalizationRegistry_ ? new FinalizationRegistry_((p) => heap.free(p)) : null;
  const secret = Symbol_('Stored');
  const own = (o, key, value) => defineProperty(o, key, { value, writable: false, enumerable: true, configurable: false });
  /** The storage address of a live `Stored` (TypeError for anything else, or once freed). */
  let liveOf;
  /** The storage words of a `Stored` (its own, not a property a caller could shadow). */
  let lenOf;

  /**
   * The common base of EnvMap, AliasTable and LightTree: one block of storage words in the
   * module's memory, its copy-out, and its release (explicit, `using`, or by the GC).
   */
  class Stored {
    #p;
    #len;
    #name;
    constructor(key, name, p, len) {
      if (key !== secret) throw typeError(`${name} has no public constructor`);
      this.#p = p;
      this.#len = len;
      this.#name = name;
      if (registry !== null) REGISTER(registry, this, p, this);
    }

    static {
      liveOf = (o) => {
        if (o.#p === 0) throw typeError(`this ${o.#name} has been freed`);
        return o.#p;
      };
      lenOf = (o) => o.#len;
    }

    /** Words of the storage (header included). */
    get storageLength() {
      return this.#len;
    }

    /** A copy of the storage words: the file format (little-endian bytes on every target). */
    storage() {
      return read(U, liveOf(this), this.#len, new U32(this.#len));
    }

    /** Releases the tables' memory (also done when the object is garbage-collected). */
    free() {
      if (this.#p !== 0) {
        if (registry !== null) UNREGISTER(registry, this);
        heap.free(this.#p);
        this.#p = 0;
      }
    }

    [DISPOSE]() {
      this.free();
    }
  }
  // Frozen: a caller cannot replace a method or add a setter the constructor would run.
  freeze(Stored.prototype);
  freeze(Stored);

  /**
   * Reserves `len` words (`len` from a C `*_storage_len`, `0xffffffff`: too large), copies
   * the `n` elements of `T` of `input` to scratch memory and runs `build(input, storage)`
   * (a C builder's code); returns `make(storage)`, or frees the words and throws.
   */
  function buildStored(len, what, T, n, input, build, make) {
    if (len === 0xffff_ffff) throw fail(-2, what);
    const p = heap.alloc(4 * len);
    try {
      scratch1(T, n, input, (pin) => {
        const code = build(pin, p);
        if (code !== 0) throw fail(code, what);
      });
    } catch (e) {
      heap.free(p);
      throw e;
    }
    return make(p);
  }

  /**
   * Storage words read back (see `storageWords`): `kindOf(first, len)` names the kind (or
   * throws), the words are copied into the module's memory and checked by `check(p, len)`, or
   * `verified(p, len)` unless `options.verify` is false; returns `make(kind, p, len)`.
   * `options.verify` (default true) is the one property of a caller's object this module
   * reads: once, first; an exception from reading it becomes a TypeError.
   */
  function loadStored(words, options, what, kindOf, check, verified, make) {
    let verify = true;
    if (options !== undefined) {
      if (options === null || typeof options !== 'object') {
        throw typeError(`options must be an object, not ${describe(options)}`);
      }
      let v;
      try {
        v = options.verify;
      } catch {
        throw typeError('options.verify could not be read');
      }
      if (v !== undefined && typeof v !== 'boolean') throw typeError(`options.verify must be a boolean, not ${describe(v)}`);
      if (v === false) verify = false;
    }
    const stored = storageWords(words);
    const len = stored.len;
    const kind = kindOf(stored.first, len);
    const p = heap.alloc(4 * len);
    try {
      stored.copy(p);
      const code = verify ? verified(p, len) : check(p, len);
      if (code !== 0) throw fail(code, what);
    } catch (e) {
      heap.free(p);
      throw e;
    }
    return make(kind, p, len);
  }

  /** An environment-map distribution whose tables live in the module's memory. */
  class EnvMap extends Stored {
    #len;
    #sample;
    #pdf;
    #sampleDirection;
    #pdfDirection;
    constructor(key, kind, p, len) {
      if (key !== secret) throw typeError('use envmapHierarchical, envmapMarginalConditional or envmapFromStorage');
      super(key, 'EnvMap', p, len);
      this.#len = len;
      // One set of C functions for both distributions (the storage header says which).
      this.#sample = x.wc_envmap_sample;
      this.#pdf = x.wc_envmap_pdf;
      this.#sampleDirection = x.wc_envmap_sample_direction;
      this.#pdfDirection = x.wc_envmap_pdf_direction;
      const header = view(U, p, HEADER_WORDS);
      /** `'hierarchical'` or `'marginal-conditional'`; texels per row; rows. */
      own(this, 'kind', kind);
      own(this, 'width', header[2]);
      own(this, 'height', header[3]);
    }

    // A private method: calling it is the brand check (TypeError for anything but an EnvMap).
    #live() {
      return liveOf(this);
    }

    /**
     * Draws one sample per point of `u` (`2n` floats, any values, clamped to [0, 1)):
     * `uv` (`2n` floats, in the texel), `pdf` (`n` densities over the unit square) and
     * `texel` (`2n` values, `[column, row]`).
     */
    sample(u) {
      const p = this.#live();
      const n = elements(u, F, 2, 'u');
      const uv = new F32(2 * n);
      const pdf = new F32(n);
      const texel = new U32(2 * n);
      if (n === 0) return { uv, pdf, texel };
      const f = this.#sample;
      return scratch2(F, 2 * n, u, U, SAMPLE_WORDS * n, undefined, (pu, po) => {
        expect(f(p, this.#len, pu, po, n), n, 'sample');
        const w = view(U, po, SAMPLE_WORDS * n);
        const uvBits = new U32(TA_BUFFER(uv));
        const pdfBits = new U32(TA_BUFFER(pdf));
        for (let i = 0, k = 0; i < n; i++, k += SAMPLE_WORDS) {
          uvBits[2 * i] = w[k];
          uvBits[2 * i + 1] = w[k + 1];
          pdfBits[i] = w[k + 2];
          texel[2 * i] = w[k + 3];
          texel[2 * i + 1] = w[k + 4];
        }
        return { uv, pdf, texel };
      });
    }

    /** Densities over the unit square at `n` points `uv` (`2n` floats), bit-equal to `sample`'s. */
    pdf(uv, out) {
      const f = this.#pdf;
      return this.#densities(uv, 2, 'uv', out, 'pdf', (p, len, pu, po, n) => f(p, len, pu, po, n));
    }

    /**
     * Densities at the `n` points `x` (`d` floats each, the argument `what`) into `out` (or a
     * new array): `call(tables, len, px, po, n)` writes them (the C function `name`).
     */
    #densities(x, d, what, out, name, call) {
      const p = this.#live();
      const n = elements(x, F, d, what);
      const result = output(out, F, n);
      if (n === 0) return result;
      const len = this.#len;
      return scratch2(F, d * n, x, F, n, undefined, (px, po) => {
        expect(call(p, len, px, po, n), n, name);
        return read(F, po, n, result);
      });
    }

    /**
     * Samples as directions with their density per steradian, in one call: `layout`
     * 'equirect' (sphereEquirect, density pdf / (2 pi^2 sin(pi v)), 0 exactly at the pole) or
     * 'equal-area' (sphereEqualArea, density pdf / (4 pi)). Returns `dir` (`3n` floats),
     * `pdf` (`n`, per steradian), `uv` (`2n`) and `texel` (`2n`).
     */
    sampleDirection(layout, u) {
      const l = layoutOf(layout);
      const p = this.#live();
      const n = elements(u, F, 2, 'u');
      const dir = new F32(3 * n);
      const pdf = new F32(n);
      const uv = new F32(2 * n);
      const texel = new U32(2 * n);
      if (n === 0) return { dir, pdf, uv, texel };
      const f = this.#sampleDirection;
      return scratch2(F, 2 * n, u, U, DIRECTION_WORDS * n, undefined, (pu, po) => {
        expect(f(p, this.#len, l, pu, po, n), n, 'sampleDirection');
        const w = view(U, po, DIRECTION_WORDS * n);
        const dirBits = new U32(TA_BUFFER(dir));
        const uvBits = new U32(TA_BUFFER(uv));
        const pdfBits = new U32(TA_BUFFER(pdf));
        for (let i = 0, k = 0; i < n; i++, k += DIRECTION_WORDS) {
          dirBits[3 * i] = w[k];
          dirBits[3 * i + 1] = w[k + 1];
          dirBits[3 * i + 2] = w[k + 2];
          pdfBits[i] = w[k + 3];
          uvBits[2 * i] = w[k + 4];
          uvBits[2 * i + 1] = w[k + 5];
          texel[2 * i] = w[k + 6];
          texel[2 * i + 1] = w[k + 7];
        }
        return { dir, pdf, uv, texel };
      });
    }

    /**
     * Densities per steradian of `n` directions `dir` (`3n` floats, any length) under `layout`
     * (see sampleDirection): the MIS weight of a direction from BSDF sampling.
     */
    pdfDirection(layout, dir, out) {
      const l = layoutOf(layout);
      const f = this.#pdfDirection;
      return this.#densities(dir, 3, 'dir', out, 'pdfDirection', (p, len, pd, po, n) => f(p, len, l, pd, po, n));
    }
  }
  freeze(EnvMap.prototype);
  freeze(EnvMap);

  /** The env-map kind that storage word 0 names (a RangeError for none). */
  function envmapKind(first, len) {
    const kind = first === KINDS.hierarchical.tag ? 'hierarchical' : first === KINDS['marginal-conditional'].tag ? 'marginal-conditional' : undefined;
    if (kind === undefined) throw fail(len < HEADER_WORDS ? -4 : -6, 'envmapFromStorage');
    return kind;
  }

  // MIS compensation of a build: the C ABI's WC_ENVMAP_COMPENSATION_* values.
  const COMPENSATIONS = { __proto__: null, none: 0, uniform: 1, equirect: 2 };

  function build(kind, weights, width, height, compensated, compensation, fraction) {
    const k = KINDS[kind];
    let c = 0;
    if (compensated) {
      if (typeof compensation !== 'string') throw typeError(`compensation must be a string, not ${describe(compensation)}`);
      c = COMPENSATIONS[compensation];
      if (c === undefined) throw rangeError(`compensation must be 'none', 'uniform' or 'equirect', got ${describe(compensation)}`);
      if (typeof fraction !== 'number') throw typeError(`fraction must be a number, not ${describe(fraction)}`);
    }
    const n = size(weights, width, height, 1, 'weights');
    const len = x.wc_envmap_storage_len(k.kind, width, height) >>> 0;
    const build = compensated
      ? (pw, p) => x.wc_envmap_build_compensated(k.kind, pw, width, height, c, fraction, p, len)
      : (pw, p) => x.wc_envmap_build(k.kind, pw, width, height, p, len);
    return buildStored(len, `envmap ${kind}`, F, n, weights, build, (p) => new EnvMap(secret, kind, p, len));
  }

  Object_.assign(api, {
    EnvMap,
    /** The hierarchical (MIP-pyramid) distribution of `width x height` row-major weights. */
    envmapHierarchical: (weights, width, height) => build('hierarchical', weights, width, height),
    /** The marginal-conditional distribution of `width x height` row-major weights. */
    envmapMarginalConditional: (weights, width, height) => build('marginal-conditional', weights, width, height),
    /**
     * The hierarchical distribution of MIS-compensated weights: `max(0, w - fraction * average)`
     * (`compensation` 'uniform': the mean weight, for equal-area maps; 'equirect': the radiance's
     * solid-angle average times each row's sin(theta), for weights made by
     * `envmapEquirectSolidAngleWeights`; 'none': the weights as given). Falls back to the weights as
     * given when nothing would be left; NaN, zero and negative fractions mean no compensation.
     */
    envmapHierarchicalCompensated: (weights, width, height, compensation, fraction) =>
      build('hierarchical', weights, width, height, true, compensation, fraction),
    /** The marginal-conditional distribution of MIS-compensated weights (see envmapHierarchicalCompensated). */
    envmapMarginalConditionalCompensated: (weights, width, height, compensation, fraction) =>
      build('marginal-conditional', weights, width, height, true, compensation, fraction),
    /**
     * An EnvMap from storage words (`EnvMap.storage()`, or a file written by the C API).
     * `options.verify` (default true) is the one property of a caller's object this module
     * reads: once, first; an exception from reading it becomes a TypeError.
     */
    /**
     * An EnvMap from storage words (`EnvMap.storage()`, or a file written by the C API);
     * `options.verify` (default true): see `loadStored`.
     */
    envmapFromStorage: (words, options) =>
      loadStored(words, options, 'envmapFromStorage', envmapKind, x.wc_envmap_from_storage, x.wc_envmap_from_storage_verified, (kind, p, len) => new EnvMap(secret, kind, p, len)),
    /** Bytes of wasm memory: total, and reserved by live env maps and calls. */
    memoryStats: () => ({ memory: AB_BYTE_LENGTH(MEMORY_BUFFER(memory)), reserved: heap.used() }),
  });
  // ---- light selection: an alias table and a light tree (wc_lights_*) ----

  // Words of one WcLightBounds record: min[3], max[3], power, axis[3], cos_theta_o,
  // cos_theta_e, two_sided (a word in C; a float here, nonzero meaning two-sided).
  const BOUNDS_WORDS = 13;

  /**
   * The `n` shading points of a light-tree call: `p` and `normal` (`3n` floats each) and the
   * per-point argument `a` (`n` elements of `T`, or a number for one point: then `p` and
   * `normal` hold 3 floats). Returns `n`; RangeError when the lengths disagree.
   */
  function points(p, normal, a, T, name) {
    const n = elements(p, F, 3, 'p');
    if (elements(normal, F, 3, 'n') !== n) throw rangeError(`n.length must be ${3 * n} (p.length), got ${TA_LENGTH(normal)}`);
    const m = typeof a === 'number' ? 1 : elements(a, T, 1, name);
    if (m !== n) throw rangeError(`${name} must hold one value per point (${n}), got ${m}`);
    return n;
  }

  /** `{ index, prob }` of `n` choices from `index` and `prob` words at `pi` and `pp`: one as numbers when `one`. */
  const choices = (pi, pp, n, one) => {
    if (one) return { index: view(U, pi, 1)[0], prob: view(F, pp, 1)[0] };
    return { index: read(U, pi, n, new U32(n)), prob: read(F, pp, n, new F32(n)) };
  };

  /** The storage address of a live AliasTable or LightTree (`kind`): TypeError for anything else. */
  let liveAs;

  /** What AliasTable and LightTree share: `count`, the number of lights (storage word 2). */
  class Lights extends Stored {
    #kind;
    constructor(key, kind, maker, p, len) {
      if (key !== secret) throw typeError(`use ${maker} or ${maker}FromStorage`);
      super(key, kind, p, len);
      this.#kind = kind;
      own(this, 'count', view(U, p, 3)[2]);
    }

    static {
      // `o.#kind` is the brand check (a TypeError for anything not made by this class).
      liveAs = (o, kind) => {
        if (o.#kind !== kind) throw typeError(`a ${kind} method called on a ${o.#kind}`);
        return liveOf(o);
      };
    }
  }
  freeze(Lights.prototype);
  freeze(Lights);

  /** An alias table (Walker/Vose) over per-light weights, in the module's memory. */
  class AliasTable extends Lights {
    constructor(key, p, len) {
      super(key, 'AliasTable', 'lightsAlias', p, len);
    }

    /**
     * Chooses a light per value of `u` (a Float32Array, or one number; any values, NaN and
     * negatives as 0, `>= 1` as `1 - 2^-24`): `{ index, prob }` (a Uint32Array and a
     * Float32Array, or two numbers), `prob` bit-equal to `pmf(index)`.
     */
    sample(u) {
      const p = liveAs(this, 'AliasTable');
      const one = typeof u === 'number';
      const n = one ? 1 : elements(u, F, 1, 'u');
      if (n === 0) return { index: new U32(0), prob: new F32(0) };
      return scratch2(F, n, one ? undefined : u, U, 2 * n, undefined, (pu, po) => {
        if (one) view(F, pu, 1)[0] = u;
        expect(x.wc_lights_alias_sample(p, lenOf(this), pu, po, n), n, 'sample');
        // WcLightChoice { index, prob } pairs: split in place into index words and prob bits.
        const w = view(U, po, 2 * n);
        if (one) return { index: w[0], prob: view(F, po + 4, 1)[0] };
        const index = new U32(n);
        const prob = new F32(n);
        const probBits = new U32(TA_BUFFER(prob));
        for (let i = 0; i < n; i++) {
          index[i] = w[2 * i];
          probBits[i] = w[2 * i + 1];
        }
        return { index, prob };
      });
    }

    /**
     * The probability that `sample` chooses each light of `index` (a Uint32Array, into `out`
     * or a new Float32Array; or one number, giving a number); 0 at or past `count`.
     */
    pmf(index, out) {
      const p = liveAs(this, 'AliasTable');
      const one = typeof index === 'number';
      if (one) {
        u32(index, 'index');
        if (out !== undefined) throw typeError('out is only for a Uint32Array of indices');
      }
      const n = one ? 1 : elements(index, U, 1, 'index');
      const result = one ? undefined : output(out, F, n);
      if (n === 0) return result;
      return scratch2(U, n, one ? undefined : index, F, n, undefined, (pi, po) => {
        if (one) view(U, pi, 1)[0] = index;
        expect(x.wc_lights_alias_pmf(p, lenOf(this), pi, po, n), n, 'pmf');
        return one ? view(F, po, 1)[0] : read(F, po, n, result);
      });
    }
  }
  freeze(AliasTable.prototype);
  freeze(AliasTable);

  /** A light tree (a 4-ary BVH over light bounds, pbrt-v4's importance), in the module's memory. */
  class LightTree extends Lights {
    constructor(key, p, len) {
      super(key, 'LightTree', 'lightsTree', p, len);
    }

    /**
     * Chooses a light at each shading point `p` with normal `n` (`3k` floats each; a zero
     * normal: a point in a medium) from `u` (`k` floats, or one number with one point):
     * `{ index, prob }`, `prob` bit-equal to `pmf(p, n, index)`; index `0xffffffff` and
     * prob 0 where no light contributes.
     */
    sample(p, n, u) {
      const s = liveAs(this, 'LightTree');
      const k = points(p, n, u, F, 'u');
      const one = typeof u === 'number';
      if (k === 0) return { index: new U32(0), prob: new F32(0) };
      return scratch3(F, 3 * k, p, F, 3 * k, n, F, k, one ? undefined : u, (pp, pn, pu) => {
        if (one) view(F, pu, 1)[0] = u;
        return scratch2(U, k, undefined, F, k, undefined, (pi, pr) => {
          expect(x.wc_lights_tree_sample(s, lenOf(this), pp, pn, pu, pi, pr, k), k, 'sample');
          return choices(pi, pr, k, one);
        });
      });
    }

    /**
     * The probability that `sample` at each point (`p`, `n`: `3k` floats) returns the light
     * `index` (`k` words into `out` or a new Float32Array; or one number, giving a number).
     */
    pmf(p, n, index, out) {
      const s = liveAs(this, 'LightTree');
      const one = typeof index === 'number';
      if (one) {
        u32(index, 'index');
        if (out !== undefined) throw typeError('out is only for a Uint32Array of indices');
      }
      const k = points(p, n, index, U, 'index');
      const result = one ? undefined : output(out, F, k);
      if (k === 0) return result;
      return scratch3(F, 3 * k, p, F, 3 * k, n, U, k, one ? undefined : index, (pp, pn, pi) => {
        if (one) view(U, pi, 1)[0] = index;
        return scratch1(F, k, undefined, (po) => {
          expect(x.wc_lights_tree_pmf(s, lenOf(this), pp, pn, pi, po, k), k, 'pmf');
          return one ? view(F, po, 1)[0] : read(F, po, k, result);
        });
      });
    }
  }
  freeze(LightTree.prototype);
  freeze(LightTree);

  /** A light-selection storage needs no kind: the C check names a wrong tag. */
  const anyKind = () => undefined;

  Object_.assign(api, {
    AliasTable,
    LightTree,
    /**
     * The alias table of `weights` (a Float32Array, one finite weight >= 0 per light, usually
     * its power); RangeError (`code` WC_ERR_EMPTY, _INVALID_WEIGHT, _ALL_ZERO, _TOO_LARGE).
     */
    lightsAlias(weights) {
      const n = array(weights, F, 'weights');
      const len = x.wc_lights_alias_storage_len(n) >>> 0;
      return buildStored(len, 'lightsAlias', F, n, weights, (pw, p) => x.wc_lights_alias_build(pw, n, p, len), (p) => new AliasTable(secret, p, len));
    },
    /** An AliasTable from storage words (`AliasTable.storage()` or a C file); options as envmapFromStorage's. */
    lightsAliasFromStorage: (words, options) =>
      loadStored(words, options, 'lightsAliasFromStorage', anyKind, x.wc_lights_alias_from_storage, x.wc_lights_alias_from_storage_verified, (kind, p, len) => new AliasTable(secret, p, len)),
    /**
     * The light tree of `lights`: a Float32Array of 13 floats per light (min x y z, max x y z,
     * power, axis x y z, cosThetaO, cosThetaE, twoSided: any value but 0 or -0 means two-sided);
     * RangeError (`code` WC_ERR_EMPTY, _INVALID_WEIGHT, _INVALID_BOUNDS, _ALL_ZERO, _TOO_LARGE).
     */
    lightsTree(lights) {
      const n = elements(lights, F, BOUNDS_WORDS, 'lights');
      const len = x.wc_lights_tree_storage_len(n) >>> 0;
      const build = (pl, p) => {
        // The C record's last field is a word: 1 for two-sided, 0 for one-sided.
        const f = view(F, pl, BOUNDS_WORDS * n);
        const w = view(U, pl, BOUNDS_WORDS * n);
        for (let i = BOUNDS_WORDS - 1; i < BOUNDS_WORDS * n; i += BOUNDS_WORDS) w[i] = f[i] !== 0 ? 1 : 0;
        return x.wc_lights_tree_build(pl, n, p, len);
      };
      return buildStored(len, 'lightsTree', F, BOUNDS_WORDS * n, lights, build, (p) => new LightTree(secret, p, len));
    },
    /** A LightTree from storage words (`LightTree.storage()` or a C file); options as envmapFromStorage's. */
    lightsTreeFromStorage: (words, options) =>
      loadStored(words, options, 'lightsTreeFromStorage', anyKind, x.wc_lights_tree_from_storage, x.wc_lights_tree_from_storage_verified, (kind, p, len) => new LightTree(secret, p, len)),
  });
  Object_.assign(api, samplerApi(x, memory, heap));
  return freeze(api);
}

// ---------------------------------------------------------------------------------------------
// The sampler (wc_sampler_*): every dimension of a path from (pattern, pixel, frame, index,
// seed) and a domain path. See docs/javascript.md#sampler.
//
// Argument checks here run no user code and put no user value into a message: typed arrays
// are recognised and measured with the intrinsic %TypedArray% getters (a Proxy, a shadowed
// `length` or `Symbol.toStringTag` cannot fool them) and read by index (integer-indexed
// elements have no getters), a SamplerPath by its private field (`#steps in x` runs no Proxy
// trap); numbers and strings are primitives. Every check happens before any wasm memory is
// reserved.


/** The pattern names and their `WC_PATTERN_*` values. */
const PATTERNS = freeze({ __proto__: null, pmj02bn: 0, sobol: 1, bluePmj02bn: 2, blueSobol: 3 });

const samplerError = (Type, what, rule) => new Type(`warpcore: ${what}: ${rule}`);

function samplerInteger(v, name, min, max, what) {
  if (typeof v !== 'number') throw samplerError(TypeError_, what, `${name} must be a number`);
  if (!isInteger(v) || v < min || v > max) throw samplerError(RangeError_, what, `${name} must be an integer in [${min}, ${max}]`);
  return v;
}
const samplerU32 = (v, name, what) => samplerInteger(v, name, 0, 0xffff_ffff, what);

// Steps of a domain path: four words each, [DOMAIN, key, 0, 0] or [SPLIT, key, size, sub];
// a path from samplerFramePath(spp) starts with [FRAMES, spp, 0, 0] (the root of new_frame).
const DOMAIN = 0;
const SPLIT = 1;
const FRAMES = 2;
const PATH_SECRET = Symbol('SamplerPath');

/** The steps of a SamplerPath (never handed out: the module only reads them), else null. */
let pathSteps;

/**
 * A domain path with splits: `samplerPath().domain(a).split(key, size, sub).domain(b)`, the
 * steps of Rust's `sampler.domain(a).split(key, size, sub).domain(b)`. Immutable: the steps
 * are private and never returned, and the class, its prototype and every path are frozen.
 */
class SamplerPath {
  #steps;
  constructor(secret, steps) {
    if (secret !== PATH_SECRET) throw new TypeError_('warpcore: use samplerPath() to make a SamplerPath');
    this.#steps = steps;
    freeze(this);
  }

  static {
    // `#steps in p` runs no Proxy trap; the function is module-private (not a static method
    // a caller could reach through `path.constructor` and replace or call).
    pathSteps = (p) => (typeof p === 'object' && p !== null && #steps in p ? p.#steps : null);
  }

  #then(what, kind, key, size, sub) {
    if (!(#steps in this)) throw samplerError(TypeError_, what, 'this must be a SamplerPath');
    const n = TA_LENGTH(this.#steps);
    const steps = new U32(n + 4);
    TA_SET(steps, this.#steps);
    steps[n] = kind;
    steps[n + 1] = key;
    steps[n + 2] = size;
    steps[n + 3] = sub;
    return new SamplerPath(PATH_SECRET, steps);
  }

  /** The path to the child domain for `key`. */
  domain(key) {
    return this.#then('SamplerPath.domain', DOMAIN, samplerU32(key, 'key', 'SamplerPath.domain'), 0, 0);
  }

  /** The path to sub-sample `sub` of `size` per sample, in the child domain for `key`. */
  split(key, size, sub) {
    const what = 'SamplerPath.split';
    return this.#then(what, SPLIT, samplerU32(key, 'key', what), samplerU32(size, 'size', what), samplerU32(sub, 'sub', what));
  }

  /** Steps (domains and splits; a frame path's root is not one). */
  get length() {
    if (!(#steps in this)) throw samplerError(TypeError_, 'SamplerPath.length', 'this must be a SamplerPath');
    const n = TA_LENGTH(this.#steps);
    return (n > 0 && this.#steps[0] === FRAMES ? n - 4 : n) / 4;
  }
}
freeze(SamplerPath.prototype);
freeze(SamplerPath);
const ROOT_PATH = new SamplerPath(PATH_SECRET, new U32(0));

function samplerApi(x, memory, heap) {
  // A build without the sampler (capi features) has no sampler functions.
  if (typeof x.wc_sampler_new !== 'function') return {};
  // The standard wasm32 C ABI (rustc 1.89 and later): a `WcSampler` argument is passed as a
  // pointer to a copy, a returned one through a pointer first argument.
  const arity = { __proto__: null, wc_sampler_new: 7, wc_sampler_new_frame: 8, wc_sampler_domain: 3, wc_sampler_split: 5, wc_sampler_draw: 3, wc_sampler_draw_u32: 3, wc_sampler_rnd: 3, wc_sampler_draw_slice: 4 };
  for (const name in arity) {
    if (x[name].length !== arity[name]) throw new Error_(`warpcore: ${name} has an unexpected signature: rebuild warpcore.wasm (js/build.sh)`);
  }
  const u32 = samplerU32;
  const integer = samplerInteger;

  function pattern(p, what) {
    if (typeof p !== 'string') throw samplerError(TypeError_, what, "pattern must be a string: 'pmj02bn', 'sobol', 'bluePmj02bn' or 'blueSobol'");
    if (!(p in PATTERNS)) throw samplerError(RangeError_, what, "pattern must be 'pmj02bn', 'sobol', 'bluePmj02bn' or 'blueSobol'");
    const id = PATTERNS[p];
    if (x.wc_sampler_pattern_supported(id) !== 1) throw samplerError(RangeError_, what, 'this build has no blue-noise patterns');
    return id;
  }

  /** The length of `a` if it is a `Type` (intrinsic checks), else a TypeError. */
  function typed(a, Type, name, what) {
    if (!isView(a) || TA_TAG(a) !== Type.name || getPrototypeOf(a) !== Type.proto) throw samplerError(TypeError_, what, `${name} must be a ${Type.name}`);
    if (detached(a)) throw samplerError(TypeError_, what, `${name} is over a detached ArrayBuffer`);
    const length = TA_LENGTH(a);
    if (length === 0) {
      // Zero elements, or a detached buffer (a view over it cannot be constructed).
      try {
        new U8(TA_BUFFER(a), 0, 0);
      } catch {
        throw samplerError(TypeError_, what, `${name} is detached`);
      }
    }
    return length;
  }

  // The steps of a domain path: a SamplerPath's, or a Uint32Array of keys (copied by index).
  function path(p, what) {
    const steps = pathSteps(p);
    if (steps !== null) return steps;
    if (!isView(p) || TA_TAG(p) !== 'Uint32Array') {
      throw samplerError(TypeError_, what, 'domainPath must be a Uint32Array of keys or a SamplerPath');
    }
    const length = typed(p, U, 'domainPath', what);
    const keys = new U32(length);
    TA_SET(keys, p);
    const out = new U32(4 * length);
    for (let k = 0; k < length; k++) out[4 * k + 1] = keys[k];
    return out;
  }

  // The pixel, checked; its two values are read by index (integer-indexed elements of an
  // exact Uint32Array: no getter).
  function pixel(p, what) {
    if (typed(p, U, 'pixel', what) !== 2) throw samplerError(RangeError_, what, 'pixel must hold 2 values [x, y]');
  }

  function output(out, Type, length, what) {
    if (out === undefined) return new Type.T(length);
    if (typed(out, Type, 'out', what) !== length) throw samplerError(RangeError_, what, 'out must have exactly the length of the result');
    return out;
  }

  // Runs `draw(sampler pointer, out pointer)` on the sampler of the arguments: one block of
  // wasm memory for two samplers (a result may not alias its argument) and `bytes` of output.
  // No destructuring, no iterator: plain parameters and a swap through a local.
  function withSampler(id, px, py, frame, index, seed, steps, bytes, draw) {
    const base = heap.alloc(32 + bytes);
    try {
      let s = base;
      let t = base + 16;
      // A frame path's root is new_frame's, with its samples per frame.
      const frames = TA_LENGTH(steps) > 0 && steps[0] === FRAMES;
      if (frames) x.wc_sampler_new_frame(s, id, px, py, frame, steps[1], index, seed);
      else x.wc_sampler_new(s, id, px, py, frame, index, seed);
      for (let k = frames ? 4 : 0; k < TA_LENGTH(steps); k += 4) {
        if (steps[k] === SPLIT) x.wc_sampler_split(t, s, steps[k + 1], steps[k + 2], steps[k + 3]);
        else x.wc_sampler_domain(t, s, steps[k + 1]);
        const next = t;
        t = s;
        s = next;
      }
      return draw(s, base + 32);
    } finally {
      heap.free(base);
    }
  }

  // One draw of `n` values of `Type` through C `f(s, n, out)`.
  const one = (f, Type, what) => (p, pix, frame, index, seed, domainPath, n, out) => {
    const id = pattern(p, what);
    pixel(pix, what);
    const px = pix[0];
    const py = pix[1];
    u32(frame, 'frame', what);
    u32(index, 'index', what);
    u32(seed, 'seed', what);
    const steps = path(domainPath, what);
    integer(n, 'n', 1, 4, what);
    const result = output(out, Type, n, what);
    return withSampler(id, px, py, frame, index, seed, steps, 16, (s, po) => {
      if (f(s, n, po) >>> 0 !== n) throw new Error_(`warpcore: internal error in ${what}`);
      TA_SET(result, new Type.T(MEMORY_BUFFER(memory), po, n));
      return result;
    });
  };

  return {
    samplerPath: () => ROOT_PATH,
    samplerFramePath(spp) {
      const steps = new U32(4);
      steps[0] = FRAMES;
      steps[1] = u32(spp, 'spp', 'samplerFramePath');
      return new SamplerPath(PATH_SECRET, steps);
    },
    samplerDraw: one(x.wc_sampler_draw, F, 'samplerDraw'),
    samplerDrawU32: one(x.wc_sampler_draw_u32, U, 'samplerDrawU32'),
    samplerRnd: one(x.wc_sampler_rnd, F, 'samplerRnd'),
    samplerDrawSlice(p, pix, frame, start, count, seed, domainPath, n, out) {
      const what = 'samplerDrawSlice';
      const id = pattern(p, what);
      pixel(pix, what);
      const px = pix[0];
      const py = pix[1];
      u32(frame, 'frame', what);
      u32(start, 'start', what);
      integer(count, 'count', 0, MAX_COUNT, what);
      u32(seed, 'seed', what);
      const steps = path(domainPath, what);
      integer(n, 'n', 1, 4, what);
      // 4 * count * n bytes, and the block's 32 more, within wasm32's 4 GiB.
      if (count * n > (ADDRESS_SPACE - 2 * PAGE) / 4) throw samplerError(RangeError_, what, 'count * n floats do not fit in the 4 GiB of wasm32 memory');
      const length = count * n;
      const result = output(out, F, length, what);
      if (count === 0) return result;
      return withSampler(id, px, py, frame, start, seed, steps, 4 * length, (s, po) => {
        if (x.wc_sampler_draw_slice(s, n, po, count) >>> 0 !== count) throw new Error_(`warpcore: internal error in ${what}`);
        TA_SET(result, new F32(MEMORY_BUFFER(memory), po, length));
        return result;
      });
    },
  };
}
