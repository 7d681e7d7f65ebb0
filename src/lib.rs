//! # warpcore
//!
//! Sample warps for renderers: turn points of the unit square (or sample indices) into
//! well-distributed points on the domains a renderer integrates over — the disk, the triangle,
//! the sphere, an environment map — with scalar, 8-wide ([`f32x8`]) and 16-wide ([`f32x16`])
//! SIMD and slice entry points that give **bit-identical** results; plus the points themselves: Owen-scrambled
//! pmj02bn from embedded tables, and random and stratified baselines.
//!
//! `#![no_std]`, no allocation, `#![forbid(unsafe_code)]`; depends only on `libm`, `wide` and
//! `bytemuck`. Each warp family is a Cargo feature, so a scene links only what it samples.
//!
//! ```
//! use warpcore::disk;
//!
//! // One point, eight points, or a whole batch: the same bits either way.
//! let p = disk::concentric([0.25, 0.75]);
//! let mut batch = [[0.0f32; 2]; 3];
//! disk::concentric_slice(&[[0.25, 0.75], [0.5, 0.5], [0.9, 0.1]], &mut batch);
//! assert_eq!(p, batch[0]);
//! assert!(p[0] * p[0] + p[1] * p[1] <= 1.0);
//! ```
//!
//! ## Guarantees
//!
//! * **Determinism.** Every warp is written once, generically over a small lane trait
//!   implemented for `f32`, [`f32x8`] and [`f32x16`]; `_x8`, `_x16` and `_slice` forms are thin
//!   wrappers, so they agree with the scalar form bit for bit. The bodies use only correctly rounded IEEE
//!   operations (add, mul, div, sqrt), compares and bit operations: no fused multiply-add, no
//!   approximate reciprocals, no libm transcendentals (our own polynomials instead), no
//!   `min`/`max` (their NaN and signed-zero rules differ between instruction sets). The same
//!   input therefore gives the same bits on every target: CI checks a fingerprint of every
//!   warp's output bits on x86-64 (baseline SSE2 and `-C target-cpu=native`, AVX-512 there)
//!   and on wasm with and without `simd128`; aarch64 and thumbv7em use the same operations but
//!   are built, not run, in CI.
//! * **Totality.** Every function accepts any `f32` — NaN, infinities, negatives, values
//!   `>= 1`, subnormals — and returns finite values inside the closed target domain; nothing
//!   panics. Forward warps first map each coordinate onto `[0, 1 - 2^-24]`: NaN, `-0.0`,
//!   negatives and `-inf` become `0`; values `>= 1` and `+inf` become `1 - 2^-24`. Each
//!   module documents its inverses' rule.
//! * **Slices** accept any lengths: they process `min(input.len(), output.len())` elements
//!   and return that count. They run 16 lanes when the build has AVX-512F (`-C
//!   target-cpu=native` on such a CPU; a compile-time choice, no runtime detection) and 8
//!   otherwise, with the same bits.
//! * **Widths.** `_x8` takes [`f32x8`] / [`u32x8`] lanes, `_x16` takes [`f32x16`] /
//!   [`u32x16`]: for callers whose own data is in 8- or 16-lane structure-of-arrays form. On
//!   targets without 16-lane vectors `wide` runs an `f32x16` as two `f32x8` halves (same bits,
//!   no speed-up over two `_x8` calls).
//!
//! ## Features
//!
//! | feature | module | default |
//! |---|---|---|
//! | `disk` | [`disk`]: polar, concentric, polar4, concentric4 | yes |
//! | `triangle` | [`triangle`]: low-distortion (Heitz), sqrt map, Basu-Owen (nested or per-level scramble) | yes |
//! | `sphere` | [`sphere`]: equal-area octahedral (+ wrap), lat-long, uniform sphere, uniform and cosine hemisphere; enables `disk` | yes |
//! | `pmj02bn` | [`pmj02bn`]: Owen-scrambled pmj02bn points; alone 1024 points x 1 set (8 KiB of tables) | yes |
//! | `pmj02bn-4096`, `pmj02bn-16384`, `pmj02bn-65536` | points per set (largest enabled wins; 4096 by default) | 4096 |
//! | `pmj02bn-4-sets` | 4 sets instead of 1; tables take `8 * POINTS * SETS` bytes (128 KiB by default) | yes |
//! | `sequence` | [`sequence`]: baseline `random` and `stratified` samplers (no tables) | yes |
//! | `envmap` | [`envmap`]: marginal-conditional and hierarchical image distributions, caller-owned storage; enables `sphere` | yes |
//! | `sampler` | [`sampler`]: the sampling core (domain tree, splitting, Owen-scrambled Sobol' and pmj02bn patterns, 8/16 lanes, slices); enables `pmj02bn` | yes |
//! | `blue-noise` | [`sampler::Blue`]: screen-space blue-noise error, a 64 x 64 key tile per pattern (32 KiB); enables `sampler` | yes |
//! | `spherical` | [`spherical`]: lights by solid angle, spherical triangles (Arvo) and rectangles (Urena et al.), inverses, solid angles, sphere lights by cone; enables `triangle` and `disk` | yes |
//! | `microfacet` | [`microfacet`]: GGX (Trowbridge-Reitz) microfacet reflection: `D`, Smith `G1` and height-correlated `G2`, visible normals by spherical caps (Dupuy and Benyoub 2023), reflection and bounded reflection (Eto and Tokuyoshi 2023) with exact densities | yes |
//! | `lights` | [`lights`]: light selection, an alias table by power and a light tree by importance, caller-owned storage | yes |
//! | `std` | forwards `wide/std`; the library never needs it | no |

#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]
// Builds with only some families leave parts of the shared internals unused; the full build
// (feature `all`, every family) still reports real dead code.
#![cfg_attr(not(feature = "all"), allow(dead_code))]

pub use wide::{f32x8, f32x16, u32x8, u32x16};

// Shared internals: the forms' macro, lanes, kernels, slice machinery, hashes.
#[macro_use]
mod forms;
#[cfg(any(
    feature = "pmj02bn",
    feature = "sequence",
    feature = "envmap",
    feature = "lights"
))]
mod hash;
mod lanes;
mod slices;
#[cfg(any(feature = "envmap", feature = "lights"))]
mod storage;
mod trig;
#[cfg(any(feature = "spherical", feature = "microfacet"))]
mod vec3;

#[cfg(feature = "disk")]
pub mod disk;
#[cfg(feature = "envmap")]
pub mod envmap;
#[cfg(feature = "lights")]
pub mod lights;
#[cfg(feature = "microfacet")]
pub mod microfacet;
#[cfg(feature = "pmj02bn")]
pub mod pmj02bn;
#[cfg(feature = "sampler")]
pub mod sampler;
#[cfg(feature = "sequence")]
pub mod sequence;
#[cfg(feature = "sphere")]
pub mod sphere;
#[cfg(feature = "spherical")]
pub mod spherical;
#[cfg(feature = "triangle")]
pub mod triangle;

// The README's and the docs pages' examples compile and run as doctests (they use every
// default family).
#[cfg(all(doctest, feature = "all"))]
#[doc = include_str!("../README.md")]
#[doc = include_str!("../docs/quickstart.md")]
struct ReadmeDoctests;

#[cfg(all(doctest, feature = "pmj02bn", feature = "sequence"))]
#[doc = include_str!("../docs/pmj02bn.md")]
struct Pmj02bnDocDoctests;

#[cfg(all(doctest, feature = "envmap"))]
#[doc = include_str!("../docs/envmaps.md")]
struct EnvmapsDocDoctests;

#[cfg(all(doctest, feature = "lights"))]
#[doc = include_str!("../docs/lights.md")]
struct LightsDocDoctests;

#[cfg(all(
    doctest,
    feature = "blue-noise",
    feature = "disk",
    feature = "triangle",
    feature = "sphere"
))]
#[doc = include_str!("../docs/sampler.md")]
struct SamplerDocDoctests;
