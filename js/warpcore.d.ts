// Types of warpcore.mjs. Arrays are interleaved as in the C API: `n` points of the unit
// square are `2n` floats `u0 v0 u1 v1 ...`; disk points `2n`; directions and barycentrics `3n`.
// Every function checks its arguments: a wrong type throws a TypeError, a count that is not
// an integer in [0, MAX_COUNT], an array length that is not a multiple of the element size or
// does not match, or a call whose arrays do not fit in wasm32 memory throws a RangeError.
// Functions that return an array accept an optional `out` of exactly the returned type and
// length, write into it and return it.

/** Largest element count any function accepts (`size_t` on wasm32). */
export declare const MAX_COUNT: number;

/** What `load()` accepts: a URL (a path in Node), a Response, bytes or a compiled module. */
export type WasmSource =
  | URL
  | string
  | Response
  | PromiseLike<Response>
  | ArrayBuffer
  | ArrayBufferView
  | WebAssembly.Module;

/**
 * Loads the module: by default `warpcore.wasm` next to `warpcore.mjs` (fetched in browsers,
 * read from disk in Node).
 */
export declare function load(source?: WasmSource): Promise<Warpcore>;

/** One batch of environment-map samples. */
export interface EnvSamples {
  /** `2n` floats: the points, in [0, 1)^2, inside their texels. */
  uv: Float32Array;
  /** `n` densities with respect to area on [0, 1]^2 (`P(texel) * width * height`). */
  pdf: Float32Array;
  /** `2n` values: `[column, row]` of each sample's texel. */
  texel: Uint32Array;
}

/** Error codes an environment-map function may attach to its RangeError (`error.code`). */
export type EnvMapErrorCode =
  | 'WC_ERR_ZERO_SIZE'
  | 'WC_ERR_TOO_LARGE'
  | 'WC_ERR_LENGTH_MISMATCH'
  | 'WC_ERR_STORAGE_TOO_SMALL'
  | 'WC_ERR_INFINITE_WEIGHT'
  | 'WC_ERR_WRONG_FORMAT'
  | 'WC_ERR_UNSUPPORTED_VERSION'
  | 'WC_ERR_CORRUPT'
  | 'WC_ERR_INVALID_ARGUMENT'
  | 'WC_ERR_OTHER';

/** How an env map's unit square lies on the sphere of directions. */
export type EnvLayout = 'equirect' | 'equal-area';

/** `n` env-map samples as directions (EnvMap.sampleDirection). */
export interface EnvDirections {
  /** `3n` floats: unit directions. */
  dir: Float32Array;
  /** `n` densities with respect to solid angle (per steradian). */
  pdf: Float32Array;
  /** `2n` floats: the points on the unit square. */
  uv: Float32Array;
  /** `2n` values: `[column, row]` of each texel. */
  texel: Uint32Array;
}

/**
 * An environment-map distribution whose tables live in the module's memory. Create with
 * `envmapHierarchical`, `envmapMarginalConditional` or `envmapFromStorage`; release with
 * `free()` (or `using`; garbage collection frees it too).
 */
export interface EnvMap extends Stored {
  readonly kind: 'hierarchical' | 'marginal-conditional';
  /** Texels per row. */
  readonly width: number;
  /** Rows. */
  readonly height: number;
  /** One sample per point of `u` (`2n` floats; any values, clamped to [0, 1)). */
  sample(u: Float32Array): EnvSamples;
  /** Densities at `n` points (`2n` floats), bit-equal to the `pdf` of a sample there. */
  pdf(uv: Float32Array, out?: Float32Array): Float32Array;
  /**
   * Samples as directions with their density per steradian, in one call: `layout`
   * 'equirect' (sphereEquirect; pdf / (2 pi^2 sin(pi v)), 0 exactly at the pole) or
   * 'equal-area' (sphereEqualArea; pdf / (4 pi)).
   */
  sampleDirection(layout: EnvLayout, u: Float32Array): EnvDirections;
  /** Densities per steradian of `n` directions (`3n` floats, any length) under `layout`. */
  pdfDirection(layout: EnvLayout, dir: Float32Array, out?: Float32Array): Float32Array;
}

/** What EnvMap, AliasTable and LightTree share: storage words in the module's memory. */
export interface Stored {
  /** Words of the storage, header included. */
  readonly storageLength: number;
  /**
   * A copy of the storage words: the file format (little-endian bytes on every target; the
   * same bytes for the same inputs from JS, C and Rust).
   */
  storage(): Uint32Array;
  /** Releases the tables; later calls throw a TypeError. */
  free(): void;
  [Symbol.dispose](): void;
}

/** Error codes a light-selection function may attach to its RangeError (`error.code`). */
export type LightsErrorCode =
  | 'WC_ERR_EMPTY'
  | 'WC_ERR_TOO_LARGE'
  | 'WC_ERR_INVALID_WEIGHT'
  | 'WC_ERR_INVALID_BOUNDS'
  | 'WC_ERR_ALL_ZERO'
  | 'WC_ERR_STORAGE_TOO_SMALL'
  | 'WC_ERR_WRONG_FORMAT'
  | 'WC_ERR_UNSUPPORTED_VERSION'
  | 'WC_ERR_CORRUPT';

/** Chosen lights: `index` (`0xffffffff` where a tree found none) and the probability of each. */
export interface LightChoices {
  index: Uint32Array;
  prob: Float32Array;
}
/** One chosen light (the scalar forms). */
export interface LightChoice {
  index: number;
  prob: number;
}

/**
 * An alias table (Walker 1977, Vose 1991) over per-light weights: O(1) per sample, the exact
 * probability of each choice. Create with `lightsAlias` or `lightsAliasFromStorage`.
 */
export interface AliasTable extends Stored {
  /** The number of lights. */
  readonly count: number;
  /** A light per value of `u` (any values: NaN, negatives as 0; `>= 1` as `1 - 2^-24`); `prob` bit-equal to `pmf(index)`. */
  sample(u: Float32Array): LightChoices;
  sample(u: number): LightChoice;
  /** The probability that `sample` returns each index (0 at or past `count`). */
  pmf(index: Uint32Array, out?: Float32Array): Float32Array;
  pmf(index: number): number;
}

/**
 * A light tree (a 4-ary BVH over light bounds with pbrt-v4's importance): a light chosen by
 * its estimated contribution at the shading point. Create with `lightsTree` or
 * `lightsTreeFromStorage`.
 */
export interface LightTree extends Stored {
  /** The number of lights. */
  readonly count: number;
  /**
   * A light at each shading point `p` with normal `n` (`3k` floats each; a zero normal: a
   * point in a medium) from `u` (`k` floats, or a number with one point); `prob` bit-equal to
   * `pmf(p, n, index)`; index `0xffffffff` and prob 0 where no light contributes.
   */
  sample(p: Float32Array, n: Float32Array, u: Float32Array): LightChoices;
  sample(p: Float32Array, n: Float32Array, u: number): LightChoice;
  /** The probability that `sample` at each point returns `index` (0 past the end, for power 0 or importance 0). */
  pmf(p: Float32Array, n: Float32Array, index: Uint32Array, out?: Float32Array): Float32Array;
  pmf(p: Float32Array, n: Float32Array, index: number): number;
}

export interface Warpcore {
  // ---- disk: u[0] drives the radius, u[1] the angle ----
  /** Polar map, r = sqrt(u0), theta = 2 pi u1: `2n` floats to `2n`. */
  diskPolar(u: Float32Array, out?: Float32Array): Float32Array;
  diskPolarInverse(p: Float32Array, out?: Float32Array): Float32Array;
  /** Concentric (Shirley-Chiu) map: `2n` floats to `2n`. */
  diskConcentric(u: Float32Array, out?: Float32Array): Float32Array;
  diskConcentricInverse(p: Float32Array, out?: Float32Array): Float32Array;
  /**
   * polar4 (Christensen 2018): `n` disk samples (`2n` floats) from the points (`2m` floats),
   * four per point: sample `i` uses point `i / 4` in quadrant `i % 4`. `n` defaults to `4m`
   * and may not exceed it.
   */
  diskPolar4(points: Float32Array, n?: number, out?: Float32Array): Float32Array;
  /** Inverse of polar4: points of the square (`2n` floats) and quadrants (`n`). */
  diskPolar4Inverse(p: Float32Array): { u: Float32Array; quadrant: Uint32Array };
  /** concentric4: the quarter-disk Shirley-Chiu map of point `i / 4`, turned into quadrant `i % 4`. */
  diskConcentric4(points: Float32Array, n?: number, out?: Float32Array): Float32Array;
  diskConcentric4Inverse(p: Float32Array): { u: Float32Array; quadrant: Uint32Array };

  // ---- triangle: barycentrics [b0, b1, b2] weighting the caller's vertices ----
  /** Low-distortion map (Heitz 2019): `2n` floats to `3n`. */
  /** Uniform in solid angle over triangle `light` (v0, v1, v2, p: 12 floats): `[b0, b1, b2, density]` per sample. */
  sphericalTriangle(light: Float32Array, u: Float32Array, out?: Float32Array): Float32Array;
  sphericalTriangleInverse(light: Float32Array, b: Float32Array, out?: Float32Array): Float32Array;
  /** Uniform in solid angle over rectangle `light` (corner, ex, ey, p: 12 floats): `[s, t, density]` per sample. */
  sphericalRectangle(light: Float32Array, u: Float32Array, out?: Float32Array): Float32Array;
  sphericalRectangleInverse(light: Float32Array, st: Float32Array, out?: Float32Array): Float32Array;
  /** Cosine-aware sphericalTriangle: `light` is 15 floats (v0, v1, v2, p, n; n the receiver's normal); `u` warped by the bilinear fit of max(0, n . w) at the corners first; `[b0, b1, b2, density]` per sample, the density including the bilinear factor. */
  sphericalTriangleCosine(light: Float32Array, u: Float32Array, out?: Float32Array): Float32Array;
  /** Cosine-aware sphericalRectangle: `light` is 15 floats (corner, ex, ey, p, n); `[s, t, density]` per sample. */
  sphericalRectangleCosine(light: Float32Array, u: Float32Array, out?: Float32Array): Float32Array;
  sphericalTriangleSolidAngle(light: Float32Array): number;
  sphericalRectangleSolidAngle(light: Float32Array): number;
  /** Uniform in the cone the sphere `light` (centre, radius, p: 7 floats) subtends at p: `[x, y, z, density]` per sample (a unit direction; density 1/(4 pi) with p inside, 0 for a point light). */
  sphericalCone(light: Float32Array, u: Float32Array, out?: Float32Array): Float32Array;
  /** Inverse of sphericalCone: `3n` direction floats (any length) to `2n`. */
  sphericalConeInverse(light: Float32Array, dir: Float32Array, out?: Float32Array): Float32Array;
  /** Solid angle of the sphere `light` (centre, radius, p: 7 floats) at p: [0, 2 pi] outside, 4 pi inside. */
  sphericalConeSolidAngle(light: Float32Array): number;
  triangleUniform(u: Float32Array, out?: Float32Array): Float32Array;
  triangleUniformInverse(b: Float32Array, out?: Float32Array): Float32Array;
  /** b0 = 1 - sqrt(u0), b1 = u1 sqrt(u0): `2n` floats to `3n`. */
  triangleSqrtMap(u: Float32Array, out?: Float32Array): Float32Array;
  triangleSqrtMapInverse(b: Float32Array, out?: Float32Array): Float32Array;
  /** Basu-Owen points `start .. start + n - 1` of `seed`'s scramble (0: unscrambled): `3n` floats. */
  triangleBasuOwen(start: number, seed: number, n: number, out?: Float32Array): Float32Array;
  /** Basu-Owen with one digit permutation per level: `3n` floats. */
  triangleBasuOwenPermuted(start: number, seed: number, n: number, out?: Float32Array): Float32Array;

  // ---- sphere: directions [x, y, z]; the square's centre maps to +z ----
  /** Equal-area octahedral map (Clarberg 2008): `2n` floats to `3n`. */
  sphereEqualArea(u: Float32Array, out?: Float32Array): Float32Array;
  sphereEqualAreaInverse(d: Float32Array, out?: Float32Array): Float32Array;
  /** Folds points beyond the octahedral square's edges onto their neighbours: `2n` to `2n`. */
  sphereEqualAreaWrap(u: Float32Array, out?: Float32Array): Float32Array;
  /** `wrap` for texels `[column, row]` (`2n` values) of a `size x size` equal-area image. */
  sphereEqualAreaWrapTexel(texels: Int32Array, size: number, out?: Uint32Array): Uint32Array;
  /** Lat-long: phi = 2 pi u0, theta = pi u1 (v = 0 is +z): `2n` floats to `3n`. */
  sphereEquirect(u: Float32Array, out?: Float32Array): Float32Array;
  sphereEquirectInverse(d: Float32Array, out?: Float32Array): Float32Array;
  /** Uniform sphere, z = 1 - 2 u0, phi = 2 pi u1. */
  sphereUniform(u: Float32Array, out?: Float32Array): Float32Array;
  sphereUniformInverse(d: Float32Array, out?: Float32Array): Float32Array;
  /** Uniform upper hemisphere (concentric disk lifted by Lambert's map). */
  sphereUniformHemisphere(u: Float32Array, out?: Float32Array): Float32Array;
  sphereUniformHemisphereInverse(d: Float32Array, out?: Float32Array): Float32Array;
  /** Cosine-weighted upper hemisphere (Malley's method). */
  sphereCosineHemisphere(u: Float32Array, out?: Float32Array): Float32Array;
  sphereCosineHemisphereInverse(d: Float32Array, out?: Float32Array): Float32Array;
  /** Densities over the square to per steradian for the equal-area map: pdf / (4 pi). */
  sphereEqualAreaPdfToSolidAngle(pdf: Float32Array, out?: Float32Array): Float32Array;
  /** Densities over the square at directions `d` (`3n`) to per steradian for the lat-long map. */
  sphereEquirectPdfToSolidAngle(pdf: Float32Array, d: Float32Array, out?: Float32Array): Float32Array;
  /** cos(theta) / pi (0 below the horizon). */
  sphereCosineHemispherePdf(cosTheta: Float32Array, out?: Float32Array): Float32Array;

  // ---- GGX microfacet reflection (records of packed arguments; alpha = r^2 of a perceptual roughness r) ----
  /** GGX D(m): records `[mx, my, mz, ax, ay]` (`5n` floats) to `n` values. */
  microfacetGgxD(input: Float32Array, out?: Float32Array): Float32Array;
  /** Smith masking G1(w): records `[wx, wy, wz, ax, ay]` to `n` values. */
  microfacetGgxG1(input: Float32Array, out?: Float32Array): Float32Array;
  /** Height-correlated Smith G2(wo, wi): records `[wo, wi, ax, ay]` (`8n` floats) to `n` values. */
  microfacetGgxG2(input: Float32Array, out?: Float32Array): Float32Array;
  /** Visible normals by spherical caps: records `[wo, ax, ay, u0, u1]` (`7n` floats) to unit normals (`3n`). */
  microfacetGgxVisibleNormal(input: Float32Array, out?: Float32Array): Float32Array;
  /** Density of the visible normals: records `[wo, m, ax, ay]` (`8n` floats) to `n` densities. */
  microfacetGgxVisibleNormalPdf(input: Float32Array, out?: Float32Array): Float32Array;
  /** Reflection by visible normals: records `[wo, ax, ay, u0, u1]` to records `[wi, pdf]` (`4n`). */
  microfacetGgxReflect(input: Float32Array, out?: Float32Array): Float32Array;
  /** Density of the reflection: records `[wo, wi, ax, ay]` to `n` densities. */
  microfacetGgxReflectPdf(input: Float32Array, out?: Float32Array): Float32Array;
  /** Bounded reflection (Eto and Tokuyoshi 2023): records `[wo, ax, ay, u0, u1]` to records `[wi, pdf]`. */
  microfacetGgxReflectBounded(input: Float32Array, out?: Float32Array): Float32Array;
  /** Density of the bounded reflection: records `[wo, wi, ax, ay]` to `n` densities. */
  microfacetGgxReflectBoundedPdf(input: Float32Array, out?: Float32Array): Float32Array;

  // ---- points of the square ----
  /** Owen-scrambled pmj02bn points `start .. start + n - 1` of `seed`: `2n` floats in [0, 1). */
  pmj02bnSample(start: number, seed: number, n: number, out?: Float32Array): Float32Array;
  /** Unscrambled table points of table set `set` as 0.32 fixed point: `2n` values. */
  pmj02bnRaw(set: number, start: number, n: number, out?: Uint32Array): Uint32Array;
  /** The prefix-preserving index shuffle: `out[i] = shuffle(index[i], seed)`. */
  pmj02bnShuffle(index: Uint32Array, seed: number, out?: Uint32Array): Uint32Array;
  /** The prefix-preserving index shuffle of one index (an integer in [0, 2^32)). */
  pmj02bnShuffle(index: number, seed: number): number;
  /** Points per table set in this build. */
  readonly pmj02bnPoints: number;
  /** Table sets in this build. */
  readonly pmj02bnSets: number;
  /** Independent uniform points (a counter-based hash): `2n` floats. */
  sequenceRandom(start: number, seed: number, n: number, out?: Float32Array): Float32Array;
  /** Jittered points of an m x m grid, m = floor(sqrt(count)) (indices past m^2 random). */
  sequenceStratified(start: number, count: number, seed: number, n: number, out?: Float32Array): Float32Array;

  // ---- environment maps ----
  /** Hierarchical (MIP-pyramid) distribution of row-major weights (NaN and negatives weigh 0). */
  envmapHierarchical(weights: Float32Array, width: number, height: number): EnvMap;
  /** Marginal-conditional distribution (a row by its total, then a column). */
  envmapMarginalConditional(weights: Float32Array, width: number, height: number): EnvMap;
  /**
   * MIS-compensated hierarchical distribution: tables (and pdfs) of `max(0, w - fraction * average)`;
   * 'uniform' for equal-area maps, 'equirect' for weights made by `envmapEquirectSolidAngleWeights`.
   * Falls back to the weights as given when nothing would be left.
   */
  envmapHierarchicalCompensated(weights: Float32Array, width: number, height: number, compensation: 'none' | 'uniform' | 'equirect', fraction: number): EnvMap;
  /** MIS-compensated marginal-conditional distribution (see `envmapHierarchicalCompensated`). */
  envmapMarginalConditionalCompensated(weights: Float32Array, width: number, height: number, compensation: 'none' | 'uniform' | 'equirect', fraction: number): EnvMap;
  /**
   * An EnvMap from storage words (`EnvMap.storage()` or a file written through the C API):
   * a Uint32Array, or the little-endian bytes of any ArrayBufferView (Uint8Array at any offset,
   * Node's Buffer, DataView) or ArrayBuffer. `options.verify` (default true: every word and the
   * content checksum, which catches every single-bit flip) is read once, first; a throwing
   * getter becomes a TypeError.
   */
  envmapFromStorage(words: Uint32Array | ArrayBufferView | ArrayBuffer, options?: { verify?: boolean }): EnvMap;
  /** The EnvMap class of this instance, for `instanceof` (its constructor is not public). */
  readonly EnvMap: abstract new (...args: never[]) => EnvMap;

  // ---- light selection ----
  /** The alias table of `weights` (one finite weight >= 0 per light, usually its power). */
  lightsAlias(weights: Float32Array): AliasTable;
  /** An AliasTable from storage words; `options` as `envmapFromStorage`'s. */
  lightsAliasFromStorage(words: Uint32Array | ArrayBufferView | ArrayBuffer, options?: { verify?: boolean }): AliasTable;
  /**
   * The light tree of `lights`: 13 floats per light, `min x y z, max x y z, power, axis x y z,
   * cosThetaO, cosThetaE, twoSided` (the C ABI's WcLightBounds; twoSided: any value but 0 or
   * -0 means two-sided).
   */
  lightsTree(lights: Float32Array): LightTree;
  /** A LightTree from storage words; `options` as `envmapFromStorage`'s. */
  lightsTreeFromStorage(words: Uint32Array | ArrayBufferView | ArrayBuffer, options?: { verify?: boolean }): LightTree;
  /** The AliasTable class, for `instanceof` (its constructor is not public). */
  readonly AliasTable: abstract new (...args: never[]) => AliasTable;
  /** The LightTree class, for `instanceof` (its constructor is not public). */
  readonly LightTree: abstract new (...args: never[]) => LightTree;
  /**
   * Rec. 709 luminance of RGB texels (`3n` floats) as `n` weights: 0.2126 R + 0.7152 G +
   * 0.0722 B where positive, else +0 (NaN and negatives weigh 0; +Infinity stays).
   */
  envmapLuminance(rgb: Float32Array, out?: Float32Array): Float32Array;
  /** A copy of equirect (lat-long) weights with row r multiplied by sin(pi (r + 1/2) / height). */
  envmapEquirectSolidAngleWeights(weights: Float32Array, width: number, height: number): Float32Array;
  /** Equirect densities over the square at rows `v` to per steradian. */
  envmapEquirectPdfToSolidAngle(pdf: Float32Array, v: Float32Array, out?: Float32Array): Float32Array;
  /**
   * Resamples an equirect image (`srcWidth x srcHeight` texels of `channels` floats) onto the
   * `size x size` equal-area square, `supersample^2` stratified samples per texel.
   */
  envmapEquirectToEqualArea(
    src: Float32Array,
    srcWidth: number,
    srcHeight: number,
    channels: 1 | 2 | 3 | 4,
    size: number,
    supersample: number,
  ): Float32Array;

  /** Bytes of wasm memory, and those reserved by live env maps (and a running call). */
  memoryStats(): { memory: number; reserved: number };

  // ---- the sampler: every dimension of a path (see docs/javascript.md#sampler) ----
  /** The empty domain path (the root), to extend with `.domain(key)` and `.split(...)`. */
  samplerPath(): SamplerPath;
  /**
   * The root of Rust's `Sampler::new_frame` for a render of `spp` samples per pixel per frame
   * (0 acts as 1): with it, a draw's `frame` and `index` are the frame number and the sample
   * within the frame, and the frames continue one sequence per pixel; under the blue-noise
   * patterns its domains 0 to 5 are spatiotemporal slots (blue in every frame). Extend it with
   * `.domain(key)` and `.split(...)` like `samplerPath()`.
   */
  samplerFramePath(spp: number): SamplerPath;
  /**
   * `n` (1 to 4) stratified dimensions in [0, 1 - 2^-24] of sample `index` of `pixel`
   * (`[x, y]`) in `frame`, for `seed`, in the domain reached from the root by `domainPath`
   * (keys: one child domain per key, in order; empty: the root; or a `SamplerPath`, which
   * may split). The Rust crate's
   * `Sampler::<P>::new(pixel, frame, index, seed).domain(k0).domain(k1)...draw::<n>()`.
   */
  samplerDraw(...args: [...SamplerDimensions, out?: Float32Array]): Float32Array;
  /** The point of `samplerDraw` as 0.32 fixed point (`samplerDraw` is `(w >>> 8) * 2^-24`). */
  samplerDrawU32(...args: [...SamplerDimensions, out?: Uint32Array]): Uint32Array;
  /** `n` cheap unstratified values in [0, 1 - 2^-24] (Russian roulette and other decisions). */
  samplerRnd(...args: [...SamplerDimensions, out?: Float32Array]): Float32Array;
  /**
   * The points of samples `start .. start + count - 1` (wrapping after 2^32 - 1) of one
   * domain: `count * n` floats, interleaved, the bits of `count` calls of `samplerDraw`.
   */
  samplerDrawSlice(
    pattern: SamplerPattern,
    pixel: Uint32Array,
    frame: number,
    start: number,
    count: number,
    seed: number,
    domainPath: Uint32Array | SamplerPath,
    n: 1 | 2 | 3 | 4,
    out?: Float32Array,
  ): Float32Array;
}

/**
 * The arguments that name `n` dimensions of one sample of a sampler (`samplerDraw`,
 * `samplerDrawU32`, `samplerRnd`): its pattern, `pixel` (`[x, y]`), `frame`, `index`, `seed`,
 * the domain path and `n`.
 */
export type SamplerDimensions = [
  pattern: SamplerPattern,
  pixel: Uint32Array,
  frame: number,
  index: number,
  seed: number,
  domainPath: Uint32Array | SamplerPath,
  n: 1 | 2 | 3 | 4,
];

/**
 * The sampler's point patterns: Owen-scrambled pmj02bn pairs or Sobol' dimensions, each also
 * with screen-space blue-noise error across pixels.
 */
export type SamplerPattern = 'pmj02bn' | 'sobol' | 'bluePmj02bn' | 'blueSobol';

/**
 * A domain path with splits, from `samplerPath()`: immutable; each method returns a longer
 * path. `samplerPath().domain(a).split(key, size, sub)` is Rust's
 * `sampler.domain(a).split(key, size, sub)`.
 */
export interface SamplerPath {
  /** The path to the independent child domain for `key`. */
  domain(key: number): SamplerPath;
  /**
   * The path to sub-sample `sub` of `size` per sample (child index `index * size + sub`, in
   * the child domain for `key`): globally stratified across samples. `size = 0` acts as 1.
   */
  split(key: number, size: number, sub: number): SamplerPath;
  /** Steps (domains and splits; the root of `samplerFramePath` is not one). */
  readonly length: number;
}
