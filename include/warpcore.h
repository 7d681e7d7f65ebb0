/*
 * warpcore: sample warps, pmj02bn points and environment-map importance sampling for C and
 * C++ (C99 or later, any C++), bit-identical to the Rust crate. Link libwarpcore_capi.a (or
 * the shared library) built by `cargo build --release -p warpcore-capi`; see docs/capi.md.
 *
 * Conventions: interleaved float arrays (n points = 2n or 3n floats), size_t counts. Every
 * function returns the number of elements written, and 0 (writing nothing) for n = 0, a null
 * or misaligned pointer, a count whose byte size exceeds PTRDIFF_MAX, or overlapping arrays
 * (except exactly in place when an output element is no larger than an input element). The
 * environment-map builders and checks return WC_OK or a negative WC_ERR_* code, checking
 * every argument in the documented order before reading or writing any array (a call that
 * fails those checks may pass any pointers). Nothing unwinds into C. No global state: every
 * function is thread-safe. Functions of a family left out of the build (Cargo features) are
 * declared here but absent from the library.
 *
 * GENERATED from capi/src by capi/tests/header.rs (cbindgen); do not edit. Regenerate with
 *   WARPCORE_BLESS=1 cargo test -p warpcore-capi --test header
 */

#ifndef WARPCORE_H
#define WARPCORE_H



#include <stddef.h>
#include <stdint.h>

// Success.
#define WC_OK 0

// `width` or `height` is zero.
#define WC_ERR_ZERO_SIZE (-1)

// A side exceeds 2^24, the tables would exceed 2^32 words, or an array's byte size would
// exceed `PTRDIFF_MAX` (possible on 32-bit targets); see each function.
#define WC_ERR_TOO_LARGE (-2)

// An array length does not match the sizes (the Rust crate's error; no function of this
// header returns it, since C arrays carry no length).
#define WC_ERR_LENGTH_MISMATCH (-3)

// The storage is shorter than `storage_len` (or than its header says).
#define WC_ERR_STORAGE_TOO_SMALL (-4)

// A weight is `+inf`.
#define WC_ERR_INFINITE_WEIGHT (-5)

// Word 0 of the storage is the format tag of neither distribution.
#define WC_ERR_WRONG_FORMAT (-6)

// The storage's format version is not the one this library reads.
#define WC_ERR_UNSUPPORTED_VERSION (-7)

// A header word (or, for `from_storage_verified`, a table word, or content that
// does not match the checksum in header word 8) holds a value a build never writes.
#define WC_ERR_CORRUPT (-8)

// A null or misaligned pointer, arrays that overlap where they must not, or (see each
// function) a bad `kind`, `compensation` or `channels`, or a `storage_len` no array can
// have.
#define WC_ERR_INVALID_ARGUMENT (-9)

// An error this version of the header has no name for.
#define WC_ERR_OTHER (-10)

// No lights (`n == 0`; the light-selection builders).
#define WC_ERR_EMPTY (-11)

// A light's weight or power is NaN, infinite or negative (the light-selection builders).
#define WC_ERR_INVALID_WEIGHT (-12)

// A light's bounds are unusable (`wc_lights_tree_build`): a NaN or infinite coordinate,
// `min > max`, a zero, NaN or infinite axis, or a cosine outside `[-1, 1]`.
#define WC_ERR_INVALID_BOUNDS (-13)

// Every light's weight or power is zero: no light can be chosen.
#define WC_ERR_ALL_ZERO (-14)

// Words of the header at the start of every storage (64 bytes: the tables after it sit on
// cache lines when the storage is 64-byte aligned, e.g. from `aligned_alloc(64, ...)`).
#define WC_ENVMAP_HEADER_WORDS 16

// The storage format version this library writes and reads (header word 1). Version 3 adds
// a content checksum (header word 8) and bytes that do not depend on the buffer's address;
// older storages get `WC_ERR_UNSUPPORTED_VERSION`: rebuild them from the weights.
#define WC_ENVMAP_FORMAT_VERSION 3

// `compensation` of `wc_envmap_build_compensated`: the weights as given.
#define WC_ENVMAP_COMPENSATION_NONE 0

// `compensation`: subtract `fraction` times the mean weight (texels of equal solid angle:
// equal-area maps), clamp at 0.
#define WC_ENVMAP_COMPENSATION_UNIFORM 1

// `compensation`: equirect (lat-long) weights (radiance times the row's `sin(theta)`, as
// `wc_envmap_equirect_solid_angle_weights` makes them): subtract `fraction` times the
// radiance's solid-angle average times the row's `sin(theta)`, clamp at 0.
#define WC_ENVMAP_COMPENSATION_EQUIRECT 2

// `layout` of the direction functions: the equirect (lat-long) square of
// `wc_sphere_equirect` (`phi = 2 pi u`, `theta = pi v`, row 0 around `+z`).
#define WC_ENVMAP_LAYOUT_EQUIRECT 0

// `layout` of the direction functions: the equal-area octahedral square of
// `wc_sphere_equal_area` (its centre at `+z`).
#define WC_ENVMAP_LAYOUT_EQUAL_AREA 1

// `kind` of `wc_envmap_storage_len` and the builds: the hierarchical (MIP-pyramid)
// distribution, which walks the map's pyramid and keeps 2D strata compact (format tag
// `"wcHI"`).
#define WC_ENVMAP_KIND_HIERARCHICAL 0

// `kind`: the marginal-conditional distribution, a row by its total, then a column within
// the row (format tag `"wcMC"`).
#define WC_ENVMAP_KIND_MARGINAL_CONDITIONAL 1

// Owen-scrambled pmj02bn points: a draw of up to four dimensions is two independent (0,2)
// pairs (dimensions 0-1 and 2-3).
#define WC_PATTERN_PMJ02BN 0

// Owen-scrambled Sobol' dimensions 0..3 (0-1 a (0,2)-sequence).
#define WC_PATTERN_SOBOL 1

// pmj02bn with screen-space blue-noise error across pixels (feature `blue-noise`).
#define WC_PATTERN_BLUE_PMJ02BN 2

// Sobol' with screen-space blue-noise error across pixels (feature `blue-noise`).
#define WC_PATTERN_BLUE_SOBOL 3

// One environment-map sample.
typedef struct {
  // The point, in `[0, 1)^2`, inside `texel`.
  float uv[2];
  // Density with respect to area on `[0, 1]^2` at `uv` (`P(texel) * width * height`).
  float pdf;
  // `[column, row]` of the texel the point lies in.
  uint32_t texel[2];
} WcEnvSample;

// One environment-map sample as a direction (the direction functions' output).
typedef struct {
  // The unit direction (`wc_sphere_equirect` or `wc_sphere_equal_area` of `uv`).
  float dir[3];
  // Density with respect to solid angle at `dir` (per steradian); 0 only for an equirect
  // sample exactly at the pole.
  float pdf;
  // The point on the unit square, in `[0, 1)^2`.
  float uv[2];
  // `[column, row]` of the texel.
  uint32_t texel[2];
} WcEnvDirection;

// A chosen light and the probability of choosing it.
typedef struct {
  // Index of the light, below the table's light count.
  uint32_t index;
  // The probability of that choice, equal bit for bit to `wc_lights_alias_pmf` of `index`.
  float prob;
} WcLightChoice;

// One light's bounds for the tree: the fields of the crate's `LightBounds`, in its order
// (box corners, power >= 0, emission axis, then the cosines of the normal spread and of the
// falloff beyond it, each in `[-1, 1]`), with `two_sided` as a word (nonzero: true), so that
// any bytes a C caller writes are a valid value.
typedef struct {
  float min[3];
  float max[3];
  float power;
  float axis[3];
  float cos_theta_o;
  float cos_theta_e;
  uint32_t two_sided;
} WcLightBounds;

// One sample's sampler: a pattern, a pixel, a domain path and a sample index, in 16 bytes.
// A plain value: copy it, derive children from it, draw from it, from any thread.
//
// `pattern` is a `WC_PATTERN_*` constant; `index` is the sample index (after any split) and
// may be set directly (another index in the same domain: Rust's `with_index`); `pixel` and
// `domain` are hashes only this library reads. Any bits are safe: a sampler whose `pattern`
// is not a pattern of this build (garbage, or a blue-noise pattern in a build without the
// `blue-noise` feature) is carried through `wc_sampler_domain` and `wc_sampler_split`
// unchanged, and every draw from it returns 0 and writes nothing.
typedef struct {
  // A `WC_PATTERN_*` constant.
  uint32_t pattern;
  // The pixel (opaque: 16 bits of `x` and of `y`).
  uint32_t pixel;
  // The domain path's hash (opaque).
  uint32_t domain;
  // The sample index.
  uint32_t index;
} WcSampler;

#ifdef __cplusplus
extern "C" {
#endif // __cplusplus

// Polar map, `r = sqrt(u0)`, `theta = 2 pi u1`: `n` points `u` (`2n` floats) to `n` disk
// points (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `u == out`.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
size_t wc_disk_polar(const float *u, float *out, size_t n);

// Inverse of the polar map: `n` points `p` (`2n` floats) to `n` points of the unit square.
// Returns `n` (0 as for `wc_disk_polar`).
//
// # Safety
// `p` must be readable for `2n` floats and `out` writable for `2n` floats.
size_t wc_disk_polar_inverse(const float *p, float *out, size_t n);

// Concentric (Shirley-Chiu) map: `n` points `u` (`2n` floats) to `n` disk points (`2n`
// floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
// overlapping arrays other than `u == out`.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
size_t wc_disk_concentric(const float *u, float *out, size_t n);

// Inverse of the concentric map: `n` points `p` (`2n` floats) to `n` points of the unit
// square. Returns `n` (0 as for `wc_disk_concentric`).
//
// # Safety
// `p` must be readable for `2n` floats and `out` writable for `2n` floats.
size_t wc_disk_concentric_inverse(const float *p, float *out, size_t n);

// polar4 (Christensen 2018): `n` disk samples (`2n` floats) from `n_points` points of the
// square (`2 n_points` floats), four per point: sample `i` uses point `i / 4` in quadrant
// `i % 4` (`r = sqrt(u0)`, `theta = (pi/2) u1 + (pi/2) (i % 4)`). Returns
// `min(n, 4 n_points)`, or 0 (writing nothing) when that is 0, for a null or misaligned
// pointer, a count whose byte size overflows, or overlapping arrays (the
// `ceil(min(n, 4 n_points) / 4)` points the call reads and the outputs it writes).
//
// # Safety
// `points` must be readable for `2 n_points` floats and `out` writable for `2n` floats.
size_t wc_disk_polar4(const float *points, size_t n_points, float *out, size_t n);

// Inverse of polar4: `n` disk points `p` (`2n` floats) to their points of the square (`2n`
// floats, `out`) and quadrants (`n` values in 0..=3, `quadrant`). Returns `n`, or 0 (writing
// nothing) for a null or misaligned pointer or overlapping arrays other than `p == out`.
//
// # Safety
// `p` must be readable for `2n` floats, `out` writable for `2n` floats and `quadrant`
// writable for `n` values.
size_t wc_disk_polar4_inverse(const float *p, float *out, uint32_t *quadrant, size_t n);

// concentric4: `n` disk samples (`2n` floats) from `n_points` points of the square (`2
// n_points` floats), four per point: sample `i` is the quarter-disk Shirley-Chiu map of point
// `i / 4`, turned into quadrant `i % 4`. Returns `min(n, 4 n_points)`, or 0 (writing nothing)
// when that is 0, for a null or misaligned pointer, a count whose byte size overflows, or
// overlapping arrays (as for `wc_disk_polar4`).
//
// # Safety
// `points` must be readable for `2 n_points` floats and `out` writable for `2n` floats.
size_t wc_disk_concentric4(const float *points, size_t n_points, float *out, size_t n);

// Inverse of concentric4: `n` disk points `p` (`2n` floats) to their points of the square
// (`2n` floats, `out`) and quadrants (`n` values in 0..=3, `quadrant`; the origin gives 0).
// Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping arrays
// other than `p == out`.
//
// # Safety
// `p` must be readable for `2n` floats, `out` writable for `2n` floats and `quadrant`
// writable for `n` values.
size_t wc_disk_concentric4_inverse(const float *p, float *out, uint32_t *quadrant, size_t n);

// A static, NUL-terminated English description of a `WC_OK` / `WC_ERR_*` code, for messages:
// never null; codes this header does not name get `"unknown warpcore error code"`. Any
// argument; reads and writes no memory (the strings live as long as the program).
const char *wc_error_string(int32_t code);

// Words of storage `wc_envmap_build` needs for a `width x height` map of distribution
// `kind` (`WC_ENVMAP_KIND_*`), the 16-word header included: `SIZE_MAX` for an unknown
// `kind` (whatever the sides), else 0 for a zero side, `SIZE_MAX` when a side exceeds 2^24
// or the tables would exceed 2^32 words (the cases where the build returns `WC_ERR_ZERO_SIZE`, `WC_ERR_INVALID_ARGUMENT` and
// `WC_ERR_TOO_LARGE`). Any arguments; reads and writes no memory.
size_t wc_envmap_storage_len(uint32_t kind,
                             uint32_t width,
                             uint32_t height);

// Builds the distribution `kind` (`WC_ENVMAP_KIND_HIERARCHICAL` or
// `WC_ENVMAP_KIND_MARGINAL_CONDITIONAL`) of `weights` (row-major, `width * height` floats;
// NaN, negatives and `-inf` weigh 0, an all-zero map samples uniformly) into `storage`. The
// storage's header records the distribution: the other functions read it from there.
// Returns `WC_OK` (0) or the first failed check, in this order:
//
// * `WC_ERR_INVALID_ARGUMENT`: `kind` is not one of the two constants;
// * `WC_ERR_ZERO_SIZE`: `width` or `height` is 0;
// * `WC_ERR_TOO_LARGE`: a side above 2^24, tables above 2^32 words (`wc_envmap_storage_len`
//   is `SIZE_MAX`), or weights or tables larger than `PTRDIFF_MAX` bytes (32-bit targets);
// * `WC_ERR_STORAGE_TOO_SMALL`: `storage_len` is below
//   `wc_envmap_storage_len(kind, width, height)`;
// * `WC_ERR_INVALID_ARGUMENT`: a null or misaligned pointer, or weights overlapping the
//   storage's first `wc_envmap_storage_len(kind, width, height)` words;
// * `WC_ERR_INFINITE_WEIGHT`: a weight is `+inf`.
//
// Nothing is written before these checks but the last: on the other errors the storage is
// untouched; on success and on `WC_ERR_INFINITE_WEIGHT` exactly the first
// `wc_envmap_storage_len(kind, width, height)` words are written, never more. The storage's
// bytes are the file format: write them to a file and sample them later, on any machine.
//
// # Safety
// `weights` must be readable for `width * height` floats and `storage` writable for
// `storage_len` words (only when the checks above pass, so a call that returns one of the
// errors before `WC_ERR_INFINITE_WEIGHT` may pass any pointers).
int32_t wc_envmap_build(uint32_t kind,
                        const float *weights,
                        uint32_t width,
                        uint32_t height,
                        uint32_t *storage,
                        size_t storage_len);

// `wc_envmap_build` with MIS compensation (Karlik et al. 2019; pbrt-v4's
// `compensatedDistribution`, Mitsuba 3's `mis_compensation`): the tables, and every pdf
// the distribution reports, are those of `max(0, w - fraction * average)`.
// `compensation` is `WC_ENVMAP_COMPENSATION_NONE` (then this is `wc_envmap_build`),
// `WC_ENVMAP_COMPENSATION_UNIFORM` (equal-area maps: the mean weight) or
// `WC_ENVMAP_COMPENSATION_EQUIRECT` (equirect weights made by
// `wc_envmap_equirect_solid_angle_weights`: the radiance's solid-angle average, times each
// row's `sin(theta)`). `fraction` (1 is pbrt's and Mitsuba's choice) may be any float: NaN,
// zero and negative mean no compensation. When compensation would remove every weight (a
// constant map, `fraction = +inf`, an all-zero map) the build falls back to the weights as
// given, bit for bit `wc_envmap_build`.
//
// Returns `WC_OK` or the first failed check: `WC_ERR_INVALID_ARGUMENT` if `kind` or
// `compensation` is not one of its constants (checked first: nothing is read or written),
// then exactly the checks, order and writes of `wc_envmap_build`.
//
// # Safety
// As `wc_envmap_build`.
int32_t wc_envmap_build_compensated(uint32_t kind,
                                    const float *weights,
                                    uint32_t width,
                                    uint32_t height,
                                    uint32_t compensation,
                                    float fraction,
                                    uint32_t *storage,
                                    size_t storage_len);

// Checks a storage's header in O(1) and names the distribution it holds (the crate's
// `from_storage`): format tag, version, sizes and lengths. Returns `WC_OK` or the first
// failed check, in this order: `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` and `storage`
// null or misaligned, or `storage_len` words larger than `PTRDIFF_MAX` bytes),
// `WC_ERR_STORAGE_TOO_SMALL` (fewer than 16 words), `WC_ERR_WRONG_FORMAT` (word 0 is the tag
// of neither distribution), `WC_ERR_UNSUPPORTED_VERSION` (an older format: rebuild),
// `WC_ERR_CORRUPT` (a size, length or reserved word a build never writes),
// `WC_ERR_STORAGE_TOO_SMALL` (fewer words than the header says). Sampling a storage that
// passes is safe whatever its table words hold (samples stay in the map); the sampling
// functions run this check on every call. Reads only.
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_envmap_from_storage(const uint32_t *storage, size_t storage_len);

// `wc_envmap_from_storage` (the same codes, in the same order) plus one pass over every
// table word (the crate's `from_storage_verified`), rejecting (`WC_ERR_CORRUPT`) tables that
// break the format's invariants or do not match the content checksum (header word 8): every
// single-bit flip of a storage is caught. For loaders of files. Time proportional to the
// storage. Reads only.
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_envmap_from_storage_verified(const uint32_t *storage, size_t storage_len);

// Draws `n` samples from a built (or loaded) storage, of the distribution its header names:
// texels in proportion to their weight, a uniform point inside each. `u` holds `2n` floats
// (`u[2i]` picks the column, `u[2i+1]` the row; any values, clamped to `[0, 1)`). Returns
// `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte
// size overflows, an `out` that overlaps `u` (`out == u` too: a sample is larger than a
// point) or the storage, or a storage that fails `wc_envmap_from_storage`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `u` for `2n` floats, and `out`
// writable for `n` samples.
size_t wc_envmap_sample(const uint32_t *storage,
                        size_t storage_len,
                        const float *u,
                        WcEnvSample *out,
                        size_t n);

// Densities at `n` points `uv` (`2n` floats) with respect to area on `[0, 1]^2`: the pdf of
// the texel holding each point (0 on zero-weight texels), equal bit for bit to the `pdf` a
// sample at that point reports. Returns `n`, or 0 (writing nothing) for `n == 0`, a null or
// misaligned pointer, a count whose byte size overflows, an `out` that overlaps the storage
// or overlaps `uv` other than exactly in place (`out == uv`: density `i` overwrites float
// `i` after point `i / 2` was read), or a storage that fails `wc_envmap_from_storage`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `uv` for `2n` floats, and `out`
// writable for `n` floats.
size_t wc_envmap_pdf(const uint32_t *storage,
                     size_t storage_len,
                     const float *uv,
                     float *out,
                     size_t n);

// Draws `n` samples as directions with their density per steradian, in one call: the
// samples of `wc_envmap_sample`, each `uv` mapped onto the sphere by `layout`
// (`WC_ENVMAP_LAYOUT_EQUIRECT`: `wc_sphere_equirect`, density
// `pdf / (2 pi^2 sin(pi v))` with the point's own `v`, 0 exactly at the pole;
// `WC_ENVMAP_LAYOUT_EQUAL_AREA`: `wc_sphere_equal_area`, density `pdf / (4 pi)`). `u` holds
// `2n` floats (any values, clamped to `[0, 1)`); `out` receives `n` `WcEnvDirection`s.
// Returns `n`, or 0 (writing nothing) where `wc_envmap_sample` returns 0 and for an unknown
// `layout`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `u` for `2n` floats, and `out`
// writable for `n` directions.
size_t wc_envmap_sample_direction(const uint32_t *storage,
                                  size_t storage_len,
                                  uint32_t layout,
                                  const float *u,
                                  WcEnvDirection *out,
                                  size_t n);

// Densities per steradian of `n` directions `dir` (`3n` floats, any length; the MIS weight
// of a direction found by BSDF sampling): each direction mapped to the unit square by
// `layout`'s inverse (`wc_sphere_equirect_inverse` or `wc_sphere_equal_area_inverse`), the
// density of `wc_envmap_pdf` there converted to solid angle at the direction. For a
// direction of `wc_envmap_sample_direction` it equals the sample's `pdf` to a few ulp
// (except within an ulp of a texel edge). Returns `n`, or 0 (writing nothing) where
// `wc_envmap_pdf` returns 0 (`out == dir` is in place: density `i` overwrites float `i` after
// direction `i / 3` was read) and for an unknown `layout`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `dir` for `3n` floats, and `out`
// writable for `n` floats.
size_t wc_envmap_pdf_direction(const uint32_t *storage,
                               size_t storage_len,
                               uint32_t layout,
                               const float *dir,
                               float *out,
                               size_t n);

// Rec. 709 luminance of `n` linear RGB texels (`3n` floats) as `n` weights:
// `0.2126 R + 0.7152 G + 0.0722 B` (in that order, without FMA) where positive, else `+0.0`:
// NaN (a NaN channel, or infinite channels of opposite signs) and negatives weigh 0, as in
// the builds; `+inf` stays `+inf` (a build then returns `WC_ERR_INFINITE_WEIGHT`). Never NaN
// or negative; bit-identical to the Rust crate's `image::luminance`. Returns `n`, or 0
// (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte size
// overflows, or overlapping arrays other than exactly in place (`rgb == out`).
//
// # Safety
// `rgb` must be readable for `3n` floats and `out` writable for `n` floats.
size_t wc_envmap_luminance(const float *rgb, float *out, size_t n);

// Multiplies row `r` of an equirect (lat-long) weight map (in place, `width * height` floats) by
// `sin(pi (r + 1/2) / height)`, its solid-angle factor. Returns `WC_OK` or the first failed
// check, in this order: `WC_ERR_ZERO_SIZE` (`width` or `height` is 0), `WC_ERR_TOO_LARGE`
// (`width * height` floats larger than `PTRDIFF_MAX` bytes: no such array exists),
// `WC_ERR_INVALID_ARGUMENT` (a null or misaligned pointer). Writes nothing on error.
//
// # Safety
// `weights` must be readable and writable for `width * height` floats (only when the checks
// above pass).
int32_t wc_envmap_equirect_solid_angle_weights(float *weights, uint32_t width, uint32_t height);

// Equirect (lat-long) density conversion: `n` densities over the square (`pdf`) at rows `v` (`n`
// floats) to densities per steradian, `pdf / (2 pi^2 sin(pi v))` (0 at the poles). Returns
// `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte
// size overflows, an `out` overlapping `v`, or an `out` overlapping `pdf` other than
// exactly in place (`pdf == out`).
//
// # Safety
// `pdf` and `v` must be readable for `n` floats and `out` writable for `n` floats.
size_t wc_envmap_equirect_pdf_to_solid_angle(const float *pdf,
                                             const float *v,
                                             float *out,
                                             size_t n);

// Resamples an equirect (lat-long) image (`src_width x src_height` texels of `channels` floats, 1 to 4)
// onto the `size x size` equal-area octahedral square (`dst`, `size * size * channels`
// floats), each output texel the average of `supersample^2` stratified point samples of the
// source (nearest texel; NaN and negative channels count as 0). Returns `WC_OK` or the first
// failed check, in this order:
//
// * `WC_ERR_ZERO_SIZE`: `src_width`, `src_height`, `size` or `supersample` is 0;
// * `WC_ERR_INVALID_ARGUMENT`: `channels` is not 1, 2, 3 or 4;
// * `WC_ERR_TOO_LARGE`: `src_width`, `src_height` or `size` above 2^24, `supersample` above
//   64, or `src` or `dst` larger than `PTRDIFF_MAX` bytes (32-bit targets);
// * `WC_ERR_INVALID_ARGUMENT`: a null or misaligned pointer, or `src` and `dst` overlapping.
//
// Nothing is read or written before these checks pass, so on error `dst` is untouched; on
// success exactly `size * size * channels` floats are written.
//
// # Safety
// `src` must be readable for `src_width * src_height * channels` floats and `dst` writable
// for `size * size * channels` floats (only when the checks above pass).
int32_t wc_envmap_equirect_to_equal_area(const float *src,
                                         uint32_t src_width,
                                         uint32_t src_height,
                                         uint32_t channels,
                                         float *dst,
                                         uint32_t size,
                                         uint32_t supersample);

// Words of storage `wc_lights_alias_build` needs for `lights` lights: `8 + 4 lights` (16
// bytes per light and a 32-byte header); `SIZE_MAX` above 2^26 lights. Any argument; reads
// and writes no memory.
size_t wc_lights_alias_storage_len(size_t lights);

// Builds the alias table of `n` weights (usually each light's power; any finite value
// `>= 0`) into `storage` (Vose's method on exact integer masses, O(n), no allocation).
// Returns `WC_OK` (0) or the first failed check, in this order: `WC_ERR_EMPTY` (`n` is
// 0), `WC_ERR_TOO_LARGE` (more than 2^26 lights, or arrays larger than `PTRDIFF_MAX`
// bytes), `WC_ERR_STORAGE_TOO_SMALL` (`storage_len < wc_lights_alias_storage_len(n)`),
// `WC_ERR_INVALID_ARGUMENT` (a null or misaligned pointer, or weights overlapping the
// storage's first `wc_lights_alias_storage_len(n)` words), `WC_ERR_INVALID_WEIGHT` (a weight
// is NaN, infinite or negative; `-0.0` is zero), `WC_ERR_ALL_ZERO` (every weight is zero).
// On the first four errors nothing is written; otherwise exactly the first
// `wc_lights_alias_storage_len(n)` words are (zeroed on the last two errors). The storage's
// bytes are the file format, the same as the Rust crate's.
//
// # Safety
// `weights` must be readable for `n` floats and `storage` writable for `storage_len` words
// (only when the checks before `WC_ERR_INVALID_ARGUMENT` pass).
int32_t wc_lights_alias_build(const float *weights,
                              size_t n,
                              uint32_t *storage,
                              size_t storage_len);

// Checks an alias table's header in O(1) (the crate's `from_storage`): `WC_OK`, or
// `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` and `storage` null or misaligned),
// `WC_ERR_STORAGE_TOO_SMALL`, `WC_ERR_WRONG_FORMAT` (word 0 is not `"wcAL"`),
// `WC_ERR_UNSUPPORTED_VERSION`, `WC_ERR_CORRUPT` (a light count or reserved word a build
// never writes). Sampling a storage that passes never leaves it: indices below the light
// count, probabilities in `[0, 1]`. Reads only.
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_lights_alias_from_storage(const uint32_t *storage, size_t storage_len);

// `wc_lights_alias_from_storage`, then every column's invariants and the content checksum
// (the crate's `from_storage_verified`): every single-bit flip of a storage is caught
// (`WC_ERR_CORRUPT`). For loaders of files. Reads only.
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_lights_alias_from_storage_verified(const uint32_t *storage, size_t storage_len);

// Chooses `n` lights, one per float of `u` (any values; NaN and negatives act as 0, values
// `>= 1` as `1 - 2^-24`), each with probability proportional to its weight, never one of
// weight 0; `out[i]` holds the light and the exact probability of choosing it. Returns `n`,
// or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count whose byte size
// overflows, an `out` overlapping `u` or the storage, or a storage that fails
// `wc_lights_alias_from_storage`. Bit-identical to the crate's `AliasTable::sample`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `u` for `n` floats and `out` writable
// for `n` choices.
size_t wc_lights_alias_sample(const uint32_t *storage,
                              size_t storage_len,
                              const float *u,
                              WcLightChoice *out,
                              size_t n);

// The probability that `wc_lights_alias_sample` chooses each of `n` light indices (0 for
// an index at or above the light count). Returns `n`, or 0 (writing nothing) for `n == 0`,
// a null or misaligned pointer, a count whose byte size overflows, an `out` overlapping the
// storage or overlapping `index` other than exactly in place (`out == index`), or a storage
// that fails `wc_lights_alias_from_storage`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `index` for `n` values and `out`
// writable for `n` floats.
size_t wc_lights_alias_pmf(const uint32_t *storage,
                           size_t storage_len,
                           const uint32_t *index,
                           float *out,
                           size_t n);

// Words of storage `wc_lights_tree_build` needs for `lights` lights
// (`16 + 48 (lights / 3 + 14) + lights`, about 68 bytes per light), `SIZE_MAX` above 2^24
// lights. Any argument; reads and writes no memory.
size_t wc_lights_tree_storage_len(size_t lights);

// Builds the light tree of `n` lights into `storage`. Returns `WC_OK` (0) or the first
// failed check, in this order: `WC_ERR_EMPTY` (`n == 0`), `WC_ERR_TOO_LARGE` (above 2^24
// lights, or arrays above `PTRDIFF_MAX` bytes), `WC_ERR_STORAGE_TOO_SMALL` (`storage_len`
// below `wc_lights_tree_storage_len(n)`), `WC_ERR_INVALID_ARGUMENT` (a null or misaligned
// pointer, or `lights` overlapping the storage's first `wc_lights_tree_storage_len(n)`
// words), then the lights' checks (`WC_ERR_INVALID_WEIGHT`, `WC_ERR_INVALID_BOUNDS`,
// `WC_ERR_ALL_ZERO`). The storage is written only after the pointer checks pass (exactly its
// first `wc_lights_tree_storage_len(n)` words); its bytes are the file format.
//
// # Safety
// `lights` must be readable for `n` elements and `storage` writable for `storage_len`
// words (only when the checks before the lights' pass).
int32_t wc_lights_tree_build(const WcLightBounds *lights,
                             size_t n,
                             uint32_t *storage,
                             size_t storage_len);

// Checks a storage's header in O(1) (the crate's `from_storage`). Returns `WC_OK` or
// `WC_ERR_INVALID_ARGUMENT` (`storage_len > 0` with a null or misaligned `storage`),
// `WC_ERR_STORAGE_TOO_SMALL`, `WC_ERR_WRONG_FORMAT`, `WC_ERR_UNSUPPORTED_VERSION`,
// `WC_ERR_CORRUPT`. Sampling a storage that passes is safe whatever its other words hold;
// the sampling functions run this check on every call. Reads only.
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_lights_tree_from_storage(const uint32_t *storage, size_t storage_len);

// `wc_lights_tree_from_storage` plus the content checksum (the crate's
// `from_storage_verified`): every single-bit flip is rejected (`WC_ERR_CORRUPT`). O(n).
//
// # Safety
// `storage` must be readable for `storage_len` words.
int32_t wc_lights_tree_from_storage_verified(const uint32_t *storage, size_t storage_len);

// Picks a light at each of `n` shading points: `p` and `normal` hold `3n` floats (a normal
// of zeros: a point in a medium), `u` `n` floats (any values; clamped to `[0, 1)`). Writes
// `index[i]` and `prob[i]`: the light and its probability, equal bit for bit to
// `wc_lights_tree_pmf` of that light, or `UINT32_MAX` and 0 where no light contributes.
// Returns `n`, or 0 (writing nothing) for `n == 0`, a null or misaligned pointer, a count
// whose byte size overflows, outputs that overlap each other or an input, or a storage that
// fails `wc_lights_tree_from_storage`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `p` and `normal` for `3n` floats, `u`
// for `n` floats, `index` and `prob` writable for `n` elements.
size_t wc_lights_tree_sample(const uint32_t *storage,
                             size_t storage_len,
                             const float *p,
                             const float *normal,
                             const float *u,
                             uint32_t *index,
                             float *prob,
                             size_t n);

// The probability that `wc_lights_tree_sample` at shading point `i` (`p`, `normal`: `3n`
// floats) returns light `index[i]`, into `out[i]` (0 for an index past the end, a light of
// power 0 or of importance 0 there). Returns `n`, or 0 (writing nothing) for `n == 0`, a
// null or misaligned pointer, a count whose byte size overflows, an `out` overlapping an
// input, or a storage that fails `wc_lights_tree_from_storage`.
//
// # Safety
// `storage` must be readable for `storage_len` words, `p` and `normal` for `3n` floats,
// `index` for `n` words, `out` writable for `n` floats.
size_t wc_lights_tree_pmf(const uint32_t *storage,
                          size_t storage_len,
                          const float *p,
                          const float *normal,
                          const uint32_t *index,
                          float *out,
                          size_t n);

// GGX distribution of normals `D(m)` per steradian: `n` records `[mx, my, mz, ax, ay]` (`5n` floats) to `n` values. 0 for `mz <= 0` or an invalid `m`; `alpha` clamped to `[1e-4, 1]`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `5n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_d(const float *input,
                           float *out,
                           size_t n);

// Smith masking `G1(w)` of GGX: `n` records `[wx, wy, wz, ax, ay]` (`5n` floats) to `n` values (`|wz|` is used; an invalid `w` reads as +z). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `5n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_g1(const float *input,
                            float *out,
                            size_t n);

// Height-correlated Smith masking-shadowing `G2(wo, wi)` of GGX: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` values. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_g2(const float *input,
                            float *out,
                            size_t n);

// GGX visible normals by spherical caps (Dupuy and Benyoub 2023): `n` records `[wo, ax, ay, u0, u1]` (`7n` floats) to `n` unit normals `m` (`3n` floats), distributed as `G1(wo) max(0, wo.m) D(m) / wo.z`. `wo` below the horizon is mirrored, an invalid `wo` reads as +z. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `7n` floats and `out` writable for `3n` floats.
size_t wc_microfacet_ggx_visible_normal(const float *input,
                                        float *out,
                                        size_t n);

// Density of `wc_microfacet_ggx_visible_normal` per steradian of `m`: `n` records `[wo, m, ax, ay]` (`8n` floats) to `n` densities (0 for an invalid `m`). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_visible_normal_pdf(const float *input,
                                            float *out,
                                            size_t n);

// GGX reflection by visible normals: `n` records `[wo, ax, ay, u0, u1]` (`7n` floats) to `n` records `[wi, pdf]` (`4n` floats), `wi = 2 (wo.m) m - wo` (it may lie below the horizon) and its density per steradian, equal to `wc_microfacet_ggx_reflect_pdf` at `wi`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `7n` floats and `out` writable for `4n` floats.
size_t wc_microfacet_ggx_reflect(const float *input,
                                 float *out,
                                 size_t n);

// Density of `wc_microfacet_ggx_reflect` per steradian of `wi`: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` densities. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_reflect_pdf(const float *input,
                                     float *out,
                                     size_t n);

// Bounded GGX reflection (Eto and Tokuyoshi 2023): as `wc_microfacet_ggx_reflect`, with fewer directions below the horizon and its own exact density. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `7n` floats and `out` writable for `4n` floats.
size_t wc_microfacet_ggx_reflect_bounded(const float *input,
                                         float *out,
                                         size_t n);

// Density of `wc_microfacet_ggx_reflect_bounded` per steradian of `wi`: `n` records `[wo, wi, ax, ay]` (`8n` floats) to `n` densities (0 outside the image of the shrunk cap). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or overlapping
// arrays other than `input == out` (in place: the output is smaller).
//
// # Safety
// `input` must be readable for `8n` floats and `out` writable for `1n` floats.
size_t wc_microfacet_ggx_reflect_bounded_pdf(const float *input,
                                             float *out,
                                             size_t n);

// Points `start, start + 1, ..., start + n - 1` (indices wrap after `UINT32_MAX`) of
// `seed`'s Owen-scrambled pmj02bn sequence, in `[0, 1)^2`: `2n` floats. Every power-of-two
// prefix (and aligned block) is a (0,m,2)-net. Returns `n`, or 0 (writing nothing) for a
// null or misaligned `out`.
//
// # Safety
// `out` must be writable for `2n` floats.
size_t wc_pmj02bn_sample(uint32_t start, uint32_t seed, float *out, size_t n);

// The unscrambled table points `start, ..., start + n - 1` of table set `set` (both taken
// modulo the table size, `wc_pmj02bn_sets()` and `wc_pmj02bn_points()`), as 0.32 fixed point:
// `2n` `uint32_t`. Returns `n`, or 0 (writing nothing) for a null or misaligned `out`.
//
// # Safety
// `out` must be writable for `2n` values.
size_t wc_pmj02bn_raw(uint32_t set, uint32_t start, uint32_t *out, size_t n);

// The index permutation that decorrelates dimension pairs while keeping every power-of-two
// prefix as a set: `out[i] = shuffle(index[i], seed)`. Returns `n`, or 0 (writing nothing)
// for a null or misaligned pointer or overlapping arrays other than `index == out`.
//
// # Safety
// `index` must be readable and `out` writable for `n` values.
size_t wc_pmj02bn_shuffle(const uint32_t *index, uint32_t seed, uint32_t *out, size_t n);

// Points per table set in this build (1024, 4096, 16384 or 65536; features).
size_t wc_pmj02bn_points(void);

// Table sets in this build (1 or 4; features).
size_t wc_pmj02bn_sets(void);

// Is `pattern` a pattern of this build? 1 for `WC_PATTERN_PMJ02BN` and `WC_PATTERN_SOBOL`,
// 1 for the blue-noise patterns when the library was built with the `blue-noise` feature
// (the default), 0 otherwise.
uint32_t wc_sampler_pattern_supported(uint32_t pattern);

// The root sampler of sample `index` of pixel `(x, y)` in `frame`, for `seed` (one per
// render; 0 is fine). Every pixel gets independent scrambles, except under the blue-noise
// patterns, where pixels share a key tile (`x` and `y` modulo the tile). Every `uint32_t`
// is valid. An unknown `pattern` gives `{pattern, 0, 0, 0}`, a sampler every draw refuses.
WcSampler wc_sampler_new(uint32_t pattern,
                         uint32_t x,
                         uint32_t y,
                         uint32_t frame,
                         uint32_t index,
                         uint32_t seed);

// The root sampler of sample `index` (in `0..spp`) of pixel `(x, y)` in `frame` of a render
// that accumulates frames of `spp` samples per pixel: the frames continue one sequence per
// pixel (`Sampler::new_frame`). It is `wc_sampler_new` of the 64-bit sample number `n =
// frame * spp + index` (`spp = 0` acts as 1), with `n >> 32` as `frame` and the low word as
// `index`: frame 0 is `wc_sampler_new`'s frame 0, except that under the blue-noise patterns
// this root's domains 0 to 5 are spatiotemporal slots (blue noise in every frame while the
// frames continue one net; docs/sampler.md). Every `uint32_t` is valid. An unknown
// `pattern` gives `{pattern, 0, 0, 0}`, a sampler every draw refuses.
WcSampler wc_sampler_new_frame(uint32_t pattern,
                               uint32_t x,
                               uint32_t y,
                               uint32_t frame,
                               uint32_t spp,
                               uint32_t index,
                               uint32_t seed);

// An independent child pattern for `key` (same index): one per decision of a path (lens,
// light, BSDF, one per bounce ...). Different keys never give the same child. An unknown
// pattern is returned unchanged.
WcSampler wc_sampler_domain(WcSampler s, uint32_t key);

// Sub-sample `sub` of `size` per sample: the child index is `index * size + sub` (wrapping)
// in a child domain for `key`, so the sub-samples of all samples are one sequence, globally
// stratified. `size = 0` acts as 1; `sub >= size` is another sample's sub-sample. An unknown
// pattern is returned unchanged.
WcSampler wc_sampler_split(WcSampler s, uint32_t key, uint32_t size, uint32_t sub);

// `n` (1 to 4) stratified dimensions of the point of `s`, in `[0, 1 - 2^-24]`: `n` floats.
// Returns `n`, or 0 (writing nothing) for `n` outside 1..=4, an unknown pattern, or a null
// or misaligned `out`.
//
// # Safety
// `out` must be writable for `n` floats.
size_t wc_sampler_draw(WcSampler s, size_t n, float *out);

// The point of `wc_sampler_draw` as 0.32 fixed point (`w / 2^32`; `wc_sampler_draw` returns
// `(w >> 8) * 2^-24`): `n` (1 to 4) values. Returns `n`, or 0 (writing nothing) for `n`
// outside 1..=4, an unknown pattern, or a null or misaligned `out`.
//
// # Safety
// `out` must be writable for `n` values.
size_t wc_sampler_draw_u32(WcSampler s, size_t n, uint32_t *out);

// `n` (1 to 4) cheap unstratified values in `[0, 1 - 2^-24]` (a counter hash of the pixel,
// the domain and the index), for Russian roulette and other decisions where stratification
// does not pay. Returns `n`, or 0 (writing nothing) for `n` outside 1..=4, an unknown
// pattern, or a null or misaligned `out`.
//
// # Safety
// `out` must be writable for `n` floats.
size_t wc_sampler_rnd(WcSampler s, size_t n, float *out);

// The points of `s`'s domain for the `count` consecutive indices `s.index, s.index + 1, ...`
// (wrapping after `UINT32_MAX`), `n_dims` (1 to 4) dimensions each: `count * n_dims` floats,
// interleaved, the same bits as `count` calls of `wc_sampler_draw` (eight or sixteen points at
// a time). Returns `count`, or 0 (writing nothing) for `count = 0`, `n_dims` outside 1..=4,
// an unknown pattern, a null or misaligned `out`, or `count * n_dims` floats whose byte size
// exceeds `PTRDIFF_MAX`.
//
// # Safety
// `out` must be writable for `count * n_dims` floats.
size_t wc_sampler_draw_slice(WcSampler s, size_t n_dims, float *out, size_t count);

// Independent uniform points `start, ..., start + n - 1` of `seed` (a counter-based hash),
// in `[0, 1)^2`: `2n` floats. Returns `n`, or 0 (writing nothing) for a null or misaligned
// `out`.
//
// # Safety
// `out` must be writable for `2n` floats.
size_t wc_sequence_random(uint32_t start, uint32_t seed, float *out, size_t n);

// Jittered points `start, ..., start + n - 1` of an `m x m` grid, `m = floor(sqrt(count))`
// (at most 4096; indices past `m^2` are random), for `seed`: `2n` floats. Returns `n`, or 0
// (writing nothing) for a null or misaligned `out`.
//
// # Safety
// `out` must be writable for `2n` floats.
size_t wc_sequence_stratified(uint32_t start, uint32_t count, uint32_t seed, float *out, size_t n);

// Equal-area octahedral map (Clarberg 2008; the square's centre is +z, its corners -z): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_sphere_equal_area(const float *u,
                            float *out,
                            size_t n);

// Inverse of `wc_sphere_equal_area`: `n` directions `d` (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `d == out`.
//
// # Safety
// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_sphere_equal_area_inverse(const float *d, float *out, size_t n);

// Lat-long map, `phi = 2 pi u0`, `theta = pi u1` (row `v = 0` is +z): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_sphere_equirect(const float *u,
                          float *out,
                          size_t n);

// Inverse of `wc_sphere_equirect`: `n` directions `d` (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `d == out`.
//
// # Safety
// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_sphere_equirect_inverse(const float *d, float *out, size_t n);

// Uniform sphere, `z = 1 - 2 u0`, `phi = 2 pi u1`: `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_sphere_uniform(const float *u,
                         float *out,
                         size_t n);

// Inverse of `wc_sphere_uniform`: `n` directions `d` (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `d == out`.
//
// # Safety
// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_sphere_uniform_inverse(const float *d, float *out, size_t n);

// Uniform upper hemisphere (`z >= 0`; concentric disk lifted by Lambert's map): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_sphere_uniform_hemisphere(const float *u,
                                    float *out,
                                    size_t n);

// Inverse of `wc_sphere_uniform_hemisphere`: `n` directions `d` (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `d == out`.
//
// # Safety
// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_sphere_uniform_hemisphere_inverse(const float *d, float *out, size_t n);

// Cosine-weighted upper hemisphere (concentric disk lifted by Malley's method): `n` points `u` (`2n` floats) to `n` unit directions (`3n` floats). Returns `n`, or
// 0 (writing nothing) for a null or misaligned pointer or overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_sphere_cosine_hemisphere(const float *u,
                                   float *out,
                                   size_t n);

// Inverse of `wc_sphere_cosine_hemisphere`: `n` directions `d` (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer
// or overlapping arrays other than `d == out`.
//
// # Safety
// `d` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_sphere_cosine_hemisphere_inverse(const float *d, float *out, size_t n);

// Folds points beyond the octahedral square's edges onto their neighbours on the sphere
// (`(1 + e, v) -> (1 - e, 1 - v)`, ...): `n` points (`2n` floats) to `n` points of
// `[0, 1]^2`. Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
// overlapping arrays other than `u == out`.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `2n` floats.
size_t wc_sphere_equal_area_wrap(const float *u, float *out, size_t n);

// `wc_sphere_equal_area_wrap` for texel indices of a `size x size` equal-area image: `n`
// texels `[column, row]` (`2n` `int32_t`, any values) to `n` texels inside the image (`2n`
// `uint32_t`), for bilinear filtering across the edges. Returns `n`, or 0 (writing nothing)
// for a null or misaligned pointer, overlapping arrays other than `texel == out`, or
// `size == 0`.
//
// # Safety
// `texel` must be readable for `2n` values and `out` writable for `2n` values.
size_t wc_sphere_equal_area_wrap_texel(const int32_t *texel,
                                       uint32_t size,
                                       uint32_t *out,
                                       size_t n);

// Density conversion for the equal-area map: `n` densities over the square to densities per
// steradian (`pdf / (4 pi)`; NaN and negative become 0). Returns `n`, or 0 (writing nothing)
// for a null or misaligned pointer or overlapping arrays other than `pdf == out`.
//
// # Safety
// `pdf` must be readable and `out` writable for `n` floats.
size_t wc_sphere_equal_area_pdf_to_solid_angle(const float *pdf, float *out, size_t n);

// Density of the cosine-weighted hemisphere per steradian, `cos_theta / pi` (0 below the
// horizon): `n` cosines to `n` densities. Returns `n` (0 as for
// `wc_sphere_equal_area_pdf_to_solid_angle`).
//
// # Safety
// `cos_theta` must be readable and `out` writable for `n` floats.
size_t wc_sphere_cosine_hemisphere_pdf(const float *cos_theta, float *out, size_t n);

// Density conversion for the lat-long map: `n` densities over the square (`pdf`) at
// directions `d` (`3n` floats) to densities per steradian, `pdf / (2 pi^2 sin theta)` (0 on
// the axis). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or an
// `out` that overlaps an input other than `pdf == out`.
//
// # Safety
// `pdf` must be readable for `n` floats, `d` for `3n` floats, and `out` writable for `n`
// floats.
size_t wc_sphere_equirect_pdf_to_solid_angle(const float *pdf,
                                             const float *d,
                                             float *out,
                                             size_t n);

// Uniform in solid angle over triangle `light[0..9]` seen from `light[9..12]`: `n` points
// `u` (`2n` floats) to `n` records `b0, b1, b2, density` (`4n` floats; barycentrics
// weighting the vertices, density with respect to solid angle). Returns `n`, or 0 (writing
// nothing) for a null or misaligned pointer, a size past `PTRDIFF_MAX` or overlapping `u`
// and `out`.
//
// # Safety
// `light` must be readable for 12 floats, `u` for `2n` and `out` writable for `4n`.
size_t wc_spherical_triangle(const float *light, const float *u, float *out, size_t n);

// Inverse of `wc_spherical_triangle`: `n` barycentrics (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned
// pointer, a size past `PTRDIFF_MAX` or overlapping arrays other than `b == out`.
//
// # Safety
// `light` must be readable for 12 floats, `b` for `3n` and `out` writable for `2n`.
size_t wc_spherical_triangle_inverse(const float *light, const float *b, float *out, size_t n);

// Uniform in solid angle over the rectangle `corner + s ex + t ey` (`light[0..9]`) seen
// from `light[9..12]`: `n` points `u` (`2n` floats) to `n` records `s, t, density` (`3n`
// floats). Returns `n`, or 0 as for `wc_spherical_triangle`.
//
// # Safety
// `light` must be readable for 12 floats, `u` for `2n` and `out` writable for `3n`.
size_t wc_spherical_rectangle(const float *light, const float *u, float *out, size_t n);

// Inverse of `wc_spherical_rectangle`: `n` pairs `s, t` (`2n` floats) to `n` points of the
// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned
// pointer, a size past `PTRDIFF_MAX` or overlapping arrays other than `st == out`.
//
// # Safety
// `light` must be readable for 12 floats, `st` for `2n` and `out` writable for `2n`.
size_t wc_spherical_rectangle_inverse(const float *light, const float *st, float *out, size_t n);

// The solid angle of triangle `light[0..9]` at `light[9..12]`, in `[0, 2 pi]`; 0 for a
// null or misaligned `light` (and for degenerate triangles, see `warpcore::spherical`).
//
// # Safety
// `light` must be readable for 12 floats.
float wc_spherical_triangle_solid_angle(const float *light);

// The solid angle of the rectangle `light[0..9]` at `light[9..12]`, in `[0, 2 pi]`; 0 for a
// null or misaligned `light`.
//
// # Safety
// `light` must be readable for 12 floats.
float wc_spherical_rectangle_solid_angle(const float *light);

// Cosine-aware `wc_spherical_triangle`: `light` is 15 floats, `v0, v1, v2, p, n` (`n` the
// receiver's normal, any length); `u` is first warped by the bilinear density of the
// receiver's clamped cosine towards the vertices, then mapped as by
// `wc_spherical_triangle`; records `b0, b1, b2, density` (`4n` floats), the density
// including the bilinear factor (`warpcore::spherical::triangle_cosine`). Returns `n`, or 0
// as for `wc_spherical_triangle`.
//
// # Safety
// `light` must be readable for 15 floats, `u` for `2n` and `out` writable for `4n`.
size_t wc_spherical_triangle_cosine(const float *light, const float *u, float *out, size_t n);

// Cosine-aware `wc_spherical_rectangle`: `light` is 15 floats, `corner, ex, ey, p, n`;
// records `s, t, density` (`3n` floats), the density including the bilinear factor
// (`warpcore::spherical::rectangle_cosine`). Returns `n`, or 0 as for
// `wc_spherical_triangle`.
//
// # Safety
// `light` must be readable for 15 floats, `u` for `2n` and `out` writable for `3n`.
size_t wc_spherical_rectangle_cosine(const float *light, const float *u, float *out, size_t n);

// Uniform in solid angle over the cone that the sphere `light[0..3]` (centre), `light[3]`
// (radius) subtends at `light[4..7]`: `n` points `u` (`2n` floats) to `n` records `x, y, z,
// density` (`4n` floats; a unit direction from the shading point, density with respect to
// solid angle: `1 / (4 pi)` inside the sphere, 0 for a point light, see
// `warpcore::spherical::cone`). Returns `n`, or 0 as for `wc_spherical_triangle`.
//
// # Safety
// `light` must be readable for 7 floats, `u` for `2n` and `out` writable for `4n`.
size_t wc_spherical_cone(const float *light, const float *u, float *out, size_t n);

// Inverse of `wc_spherical_cone`: `n` directions (`3n` floats, any length) to `n` points of
// the square (`2n` floats). Returns `n`, or 0 as for `wc_spherical_triangle_inverse`.
//
// # Safety
// `light` must be readable for 7 floats, `dir` for `3n` and `out` writable for `2n`.
size_t wc_spherical_cone_inverse(const float *light, const float *dir, float *out, size_t n);

// The solid angle of the sphere `light[0..4]` (centre, radius) at `light[4..7]`: in `[0, 2
// pi]` outside, `4 pi` inside; 0 for a null or misaligned `light` (and for point lights).
//
// # Safety
// `light` must be readable for 7 floats.
float wc_spherical_cone_solid_angle(const float *light);

// Low-distortion map (Heitz 2019): `n` points `u` (`2n` floats) to `n` barycentrics (`3n`
// floats). Returns `n`, or 0 (writing nothing) for a null or misaligned pointer or
// overlapping arrays.
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_triangle_uniform(const float *u, float *out, size_t n);

// Inverse of the low-distortion map: `n` barycentrics `b` (`3n` floats; `b2` is implied) to
// `n` points of the square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or
// misaligned pointer or overlapping arrays other than `b == out`.
//
// # Safety
// `b` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_triangle_uniform_inverse(const float *b, float *out, size_t n);

// Square-root map, `b0 = 1 - sqrt(u0)`, `b1 = u1 sqrt(u0)`: `n` points `u` (`2n` floats) to
// `n` barycentrics (`3n` floats). Returns `n` (0 as for `wc_triangle_uniform`).
//
// # Safety
// `u` must be readable for `2n` floats and `out` writable for `3n` floats.
size_t wc_triangle_sqrt_map(const float *u, float *out, size_t n);

// Inverse of the square-root map: `n` barycentrics (`3n` floats) to `n` points of the
// square (`2n` floats). Returns `n` (0 as for `wc_triangle_uniform_inverse`).
//
// # Safety
// `b` must be readable for `3n` floats and `out` writable for `2n` floats.
size_t wc_triangle_sqrt_map_inverse(const float *b, float *out, size_t n);

// Basu-Owen points: barycentrics of points `start, start + 1, ..., start + n - 1` (indices
// wrap after `UINT32_MAX`) of `seed`'s scrambled sequence (`seed = 0`: unscrambled), `3n`
// floats. Returns `n`, or 0 (writing nothing) for a null or misaligned `out`.
//
// # Safety
// `out` must be writable for `3n` floats.
size_t wc_triangle_basu_owen(uint32_t start, uint32_t seed, float *out, size_t n);

// Basu-Owen points with one digit permutation per level, shared by every node of the level
// (`seed = 0`: unscrambled): barycentrics of points `start, ..., start + n - 1` (indices wrap
// after `UINT32_MAX`), `3n` floats. Returns `n`, or 0 (writing nothing) for a null or
// misaligned `out`.
//
// # Safety
// `out` must be writable for `3n` floats.
size_t wc_triangle_basu_owen_permuted(uint32_t start, uint32_t seed, float *out, size_t n);

#ifdef __cplusplus
}  // extern "C"
#endif  // __cplusplus

#endif  /* WARPCORE_H */
