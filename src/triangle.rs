//! Triangle warps: points of the unit square (or sample indices) to barycentric coordinates
//! `[b0, b1, b2]`, uniformly distributed over the caller's triangle.
//!
//! | warp | maps | keeps | source |
//! |---|---|---|---|
//! | [`uniform`] | `u0 < u1`: `b0 = u0/2`, `b1 = u1 - u0/2`; else `b1 = u1/2`, `b0 = u0 - u1/2` | compact strata: the square is sheared, not squeezed (no sqrt, no trig) | Heitz 2019, "A Low-Distortion Map Between Triangle and Square" |
//! | [`sqrt_map`] | `b0 = 1 - sqrt(u0)`, `b1 = u1 sqrt(u0)` | strata become slivers near the `v0` corner | textbook (Turk 1990, "Generating Random Points in Triangles", Graphics Gems); for comparison |
//! | [`basu_owen`] | base-4 digits of the sample *index* walk a 4-way subdivision; nested (Owen) digit scramble | one point per level-`k` sub-triangle in every aligned block of `4^k` indices | Basu and Owen 2015, "Low Discrepancy Constructions in the Triangle" (SIAM J. Numer. Anal. 53) |
//! | [`basu_owen_permuted`] | the same walk; one digit permutation per level | the above, and the same offset inside every sub-triangle of a block | the same, with Matoušek's (1998) positional digit scrambling |
//!
//! **Which randomization when.** Both Basu-Owen randomizations are unbiased and keep one
//! point per sub-triangle. The nested scramble ([`basu_owen`]) places each point
//! independently inside its sub-triangle, like a jittered grid of sub-triangles; the
//! per-level permutation ([`basu_owen_permuted`]) puts every point of an aligned block at the
//! same place in its sub-triangle, like systematic sampling. The report (`docs/REPORT.md`;
//! a triangle light, 32768 pixels per class) measures at 256 samples per pixel: in pixels
//! where an occluder edge crosses the light (penumbrae) the per-level permutation has 0.80x
//! the MSE of Owen-scrambled pmj02bn through [`uniform`] (0.85x through [`sqrt_map`]), the
//! best triangle strategy there and in the mixed image, and the nested scramble 1.38x; in
//! fully lit pixels (a smooth integrand) it is the best strategy at 16 samples per pixel, but
//! at 256 pmj02bn through [`uniform`] is 2.5x better and through [`sqrt_map`] 5.7x (their
//! convergence rates are `N^-2.45` and `N^-2.65` against `N^-2.0`), and the nested scramble
//! is 13x worse. So: [`basu_owen_permuted`] where shadow edges matter or sample counts are
//! low, pmj02bn + [`sqrt_map`] or [`uniform`] for unoccluded lights at high counts; the
//! nested [`basu_owen`] when statistically independent point positions per seed matter more
//! than error.
//!
//! **Barycentrics.** `b_i` weights vertex `v_i` of *your* triangle: the point is
//! `b0 v0 + b1 v1 + b2 v2` (or, to keep small coordinates precise, `v2 + b0 (v0 - v2) +
//! b1 (v1 - v2)`). Every `b_i` is `>= 0`. Each warp is uniform over the triangle, whatever its
//! shape: the density of the resulting point is `1 / area` with respect to area (these warps
//! are area-preserving maps onto the reference triangle, and the affine map to yours scales
//! every area by the same factor).
//!
//! **The sum.** `b0` and `b1` are computed and `b2` is their remainder `1 - b0 - b1`, rounded
//! once: so `b0 + b1 + b2 = 1` exactly (in exact arithmetic on the returned `f32` values)
//! whenever `1 - b0 - b1` is representable, and otherwise the sum is within half an ulp of
//! `b2` of 1: `|b0 + b1 + b2 - 1| <= 2^-25` (3.0e-8; [`uniform`] may add `2^-49`, see there).
//! [`basu_owen`] returns multiples of `2^-24` that sum to exactly 1.
//!
//! **Out-of-range input** (every function here is total): forward coordinates are first
//! mapped onto `[0, 1 - 2^-24]` — NaN, `-0.0`, negatives and `-inf` become `0`, values `>= 1`
//! and `+inf` become `1 - 2^-24`. Inverses read `b0` and `b1` only (`b2` is implied by the
//! triangle); NaN and negative values count as 0, values above 1 as 1, and the result is
//! clamped into `[0, 1 - 2^-24]`, so a point outside the triangle maps like a nearby point on
//! its boundary. Every index and seed is valid for [`basu_owen`] and [`basu_owen_permuted`].
//!
//! **Precision** (tests in `tests/triangle.rs`, against the formulas in `f64` over 2^23
//! random points plus edge sweeps): per coordinate, [`uniform`] is within 4.5e-8 of the exact
//! map (measured 3.0e-8) and [`sqrt_map`] within 8e-8 (measured 6.6e-8); the round trips
//! `inverse(warp(u))` are within `2^-24` = 6.0e-8 ([`uniform`]) and 1.2e-7 ([`sqrt_map`],
//! measured 6.0e-8) of `u`; [`basu_owen`] and [`basu_owen_permuted`] are the exact centroid
//! rounded to multiples of `2^-24` (within 4e-8, measured 3.97e-8).
//!
//! ```
//! use warpcore::triangle;
//!
//! // A uniform point on your triangle from a 2D sample...
//! let (v0, v1, v2) = ([0.0f32, 0.0, 1.0], [2.0, 0.0, 1.0], [0.0, 3.0, 1.0]);
//! let b = triangle::uniform([0.3, 0.8]);
//! let p: [f32; 3] = core::array::from_fn(|k| b[0] * v0[k] + b[1] * v1[k] + b[2] * v2[k]);
//! assert!(p[0] >= 0.0 && p[1] >= 0.0 && p[0] / 2.0 + p[1] / 3.0 <= 1.0 + 1e-6);
//! // Its density is 1 / area with respect to area on the triangle: 1/3 here.
//!
//! // Or sample i of a stratified Basu-Owen stream, one seed per pixel.
//! let (pixel_seed, i) = (0x2545_f491, 5);
//! let b = triangle::basu_owen(i, pixel_seed);
//! assert_eq!(b[0] as f64 + b[1] as f64 + b[2] as f64, 1.0);
//! ```

mod base4;

use crate::lanes::{Lane, UintLane, unit_interval};
use crate::slices;
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// `x` clamped to `[0, 1]`, NaN and `-0.0` to `+0.0` (compare and select, see `lanes`).
#[inline(always)]
fn unit_closed<L: Lane>(x: L) -> L {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    L::select(zero.simd_lt(x), L::select(x.simd_lt(one), x, one), zero)
}

// ---------------------------------------------------------------------------------------
// Low-distortion map (Heitz 2019)

#[inline(always)]
pub(crate) fn uniform_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let one = L::splat(1.0);
    let (u0, u1) = (unit_interval(u[0]), unit_interval(u[1]));
    // Heitz's two cases are one computation on (big, small) = the larger and smaller input.
    let upper = u0.simd_lt(u1);
    let big = L::select(upper, u1, u0);
    let small = L::select(upper, u0, u1);
    let half = small * L::splat(0.5); // exact (but for subnormals)
    let rest = big - half; // rounded once
    // Remainder 1 - half - rest, rounded once: 1 - big = t + c and big - half - rest = e are
    // exact error-free transformations (Fast2Sum, Sterbenz), so only the last two additions
    // round. c is nonzero only when big < 1/2; then |c + e| < 2^-24 rounds by at most 2^-49.
    let e = (big - rest) - half;
    let t = one - big;
    let c = (one - t) - big;
    let b2 = t + (c + e);
    [
        L::select(upper, half, rest),
        L::select(upper, rest, half),
        b2,
    ]
}

#[inline(always)]
pub(crate) fn uniform_inverse_body<L: Lane>(b: [L; 3]) -> [L; 2] {
    let (b0, b1) = (unit_closed(b[0]), unit_closed(b[1]));
    // The forward map gives b1 > b0 exactly when u0 < u1 (ties go to the second case).
    let upper = b0.simd_lt(b1);
    let sum = b0 + b1;
    let two = L::splat(2.0);
    [
        unit_interval(L::select(upper, b0 * two, sum)),
        unit_interval(L::select(upper, sum, b1 * two)),
    ]
}

/// The low-distortion square-to-triangle map of Heitz (2019): if `u0 < u1` then
/// `b0 = u0 / 2`, `b1 = u1 - u0 / 2`, else `b1 = u1 / 2`, `b0 = u0 - u1 / 2`; and
/// `b2 = 1 - b0 - b1`.
///
/// The square is cut along its diagonal and each half is sheared onto the triangle, so
/// there is no square root and no trigonometry, and compact strata of the square stay
/// compact (a `4 x 4` grid becomes sixteen similar small quadrilaterals and triangles,
/// where [`sqrt_map`] makes slivers). Area-preserving: uniform on the triangle, density
/// `1 / area`.
///
/// Precision: the halved coordinate is exact (but for subnormals) and the other is rounded
/// once, within `2^-25` of the exact map; `b2` is `1 - b0 - b1` rounded once — when it
/// exceeds 1/2 a double rounding of the correction term may add `2^-49` — within 4.5e-8 of
/// the exact `1 - max(u0, u1)` (measured 3.0e-8). So `|b0 + b1 + b2 - 1| <= 2^-25 + 2^-49`
/// (measured `2^-25`), and the sum is exactly 1 whenever `1 - b0 - b1` is representable — in
/// particular for every input on the `2^-24` grid (`(x >> 8) as f32 * 2^-24`, what
/// fixed-point samplers produce). See the [module docs](self) for out-of-range input.
#[inline]
pub fn uniform(u: [f32; 2]) -> [f32; 3] {
    uniform_body(u)
}

/// [`uniform`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    uniform_body(u)
}

/// [`uniform`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    uniform_body(u)
}

/// [`uniform`] over a batch: writes `out[i] = uniform(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count (a length mismatch never panics;
/// the rest of the longer slice is untouched). Bit-identical to the scalar form.
#[inline]
pub fn uniform_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, uniform_body::<slices::Widest>)
}

/// Inverse of [`uniform`]: if `b0 < b1` then `u = (2 b0, b0 + b1)`, else
/// `u = (b0 + b1, 2 b1)`.
///
/// Round trip: `uniform_inverse(uniform(u))` is within `2^-24` of `u` for `u` in `[0, 1)^2`
/// (the doubled coordinate is exact; the sum is rounded once). The map is continuous on
/// the diagonal `b0 = b1`, so there is no singular set.
#[inline]
pub fn uniform_inverse(b: [f32; 3]) -> [f32; 2] {
    uniform_inverse_body(b)
}

/// [`uniform_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn uniform_inverse_x8(b: [f32x8; 3]) -> [f32x8; 2] {
    uniform_inverse_body(b)
}

/// [`uniform_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn uniform_inverse_x16(b: [f32x16; 3]) -> [f32x16; 2] {
    uniform_inverse_body(b)
}

/// [`uniform_inverse`] over a batch, with the length rule of [`uniform_slice`].
#[inline]
pub fn uniform_inverse_slice(b: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(b, out, uniform_inverse_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Square-root map

#[inline(always)]
fn sqrt_map_body<L: Lane>(u: [L; 2]) -> [L; 3] {
    let one = L::splat(1.0);
    let b0 = one - unit_interval(u[0]).sqrt();
    // s = 1 - b0 exactly (Sterbenz, or b0 was exact): the square root as b0 represents it.
    // Scaling with s rather than the unrounded root keeps b1 <= s, so b2 >= 0, and makes
    // b2 = s - b1 the remainder 1 - b0 - b1 rounded once.
    let s = one - b0;
    let b1 = unit_interval(u[1]) * s;
    [b0, b1, s - b1]
}

#[inline(always)]
fn sqrt_map_inverse_body<L: Lane>(b: [L; 3]) -> [L; 2] {
    let zero = L::splat(0.0);
    let s = L::splat(1.0) - unit_closed(b[0]);
    let b1 = unit_closed(b[1]);
    // At the corner v0 (s = 0) the direction is lost: u1 = 0.
    let u1 = L::select(s.simd_eq(zero), zero, b1 / s);
    [unit_interval(s * s), unit_interval(u1)]
}

/// The classic square-root map: `b0 = 1 - sqrt(u0)`, `b1 = u1 sqrt(u0)`,
/// `b2 = (1 - u1) sqrt(u0)`.
///
/// `u0` picks a segment parallel to the edge `v1 v2`, a fraction `sqrt(u0)` of the way from
/// `v0` to that edge (the square root compensates for the segments' growing length), and `u1`
/// a point on it. Uniform on the
/// triangle, density `1 / area`, but strata near `v0` become long slivers: kept for
/// comparison with [`uniform`], which is also cheaper.
///
/// Precision: within 8e-8 of the exact map per coordinate (measured 6.6e-8). `b1` is scaled by `1 - b0`
/// (exact) rather than by the rounded root, so `b2 = (1 - b0) - b1` is the remainder
/// `1 - b0 - b1` rounded once: `|b0 + b1 + b2 - 1| <= 2^-25`, exactly 1 when representable.
/// See the [module docs](self) for out-of-range input.
#[inline]
pub fn sqrt_map(u: [f32; 2]) -> [f32; 3] {
    sqrt_map_body(u)
}

/// [`sqrt_map`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn sqrt_map_x8(u: [f32x8; 2]) -> [f32x8; 3] {
    sqrt_map_body(u)
}

/// [`sqrt_map`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn sqrt_map_x16(u: [f32x16; 2]) -> [f32x16; 3] {
    sqrt_map_body(u)
}

/// [`sqrt_map`] over a batch, with the length rule of [`uniform_slice`].
#[inline]
pub fn sqrt_map_slice(u: &[[f32; 2]], out: &mut [[f32; 3]]) -> usize {
    slices::map_lanes(u, out, sqrt_map_body::<slices::Widest>)
}

/// Inverse of [`sqrt_map`]: `u0 = (1 - b0)^2`, `u1 = b1 / (1 - b0)`.
///
/// Round trip: `sqrt_map_inverse(sqrt_map(u))` is within 1.2e-7 of `u` for `u` in
/// `[0, 1)^2` (measured 6.0e-8), except on the singular set where `b0` rounds to 1 (`u0 < 2^-50`, the corner
/// `v0`), where `u1` is lost and 0 is returned.
#[inline]
pub fn sqrt_map_inverse(b: [f32; 3]) -> [f32; 2] {
    sqrt_map_inverse_body(b)
}

/// [`sqrt_map_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn sqrt_map_inverse_x8(b: [f32x8; 3]) -> [f32x8; 2] {
    sqrt_map_inverse_body(b)
}

/// [`sqrt_map_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn sqrt_map_inverse_x16(b: [f32x16; 3]) -> [f32x16; 2] {
    sqrt_map_inverse_body(b)
}

/// [`sqrt_map_inverse`] over a batch, with the length rule of [`uniform_slice`].
#[inline]
pub fn sqrt_map_inverse_slice(b: &[[f32; 3]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(b, out, sqrt_map_inverse_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Basu-Owen triangular van der Corput construction

/// `2^24`: barycentrics are computed as integers on the `2^-24` grid.
const GRID: u32 = 1 << 24;

#[inline(always)]
fn basu_owen_body<L: Lane>(index: L::U, seed: L::U) -> [L; 3] {
    walk(base4::fields(base4::nested_scramble(index, seed)))
}

/// The per-level permutation on the index's digits in the layout of `base4::fields`.
#[inline(always)]
fn basu_owen_permuted_body<L: Lane>(fields: L::U, keys: base4::LevelKeys<L::U>) -> [L; 3] {
    walk(keys.permute(fields))
}

/// The Basu-Owen walk for all 16 digits at once: `fields` holds the (possibly permuted)
/// digits in the layout of `base4::fields` (bit `15 - j`: low bit of digit `j`; bit
/// `31 - j`: its high bit), and the result is the centroid of the level-16 sub-triangle they
/// select, as barycentrics on the `2^-24` grid.
#[inline(always)]
fn walk<L: Lane>(fields: L::U) -> [L; 3] {
    let splat = <L::U as UintLane>::splat;
    // Work in the plane triangle (0,0), (1,0), (0,1). The walk (DESIGN.md section 4): corner
    // c = (0,0), signed half-side w = 1/2; for digit d_j (j = 0, 1, .. least significant
    // first) cy += w if d_j & 1 == 0, cx += w if d_j & 2 == 0, then w *= -1/2 if d_j == 0
    // else 1/2. So w_j = s_j 2^-(j+1) with s_j = (-1)^(number of zero digits before j), and
    //   cx = sum_j [d_j & 2 == 0] s_j 2^-(j+1),   cy = sum_j [d_j & 1 == 0] s_j 2^-(j+1);
    // the point is the centroid c + (2/3) w_16 (w_16 = s_16 2^-17, s_16 the sign after all 16
    // digits). Scaled by 2^16, cx and cy are 16-bit sums of signed powers of two, computed
    // for all digits at once below.
    //
    // In the fields layout, bit 15 - j of each half is exactly the weight 2^(15 - j) of digit
    // j in cx * 2^16 and cy * 2^16.
    let bits = !fields;
    let low16 = splat(0xffff);
    let dy = bits & low16; // [d_j & 1 == 0]: cy moves
    let dx = bits.shr(16); // [d_j & 2 == 0]: cx moves
    let zero = dx & dy; // d_j == 0: w changes sign after digit j
    // Exclusive prefix parity of the zero digits in consumption order, i.e. over the higher
    // bits here: bit 15 - j of `neg` is set when s_j = -1.
    let neg = zero.shr(1);
    let neg = neg ^ neg.shr(1);
    let neg = neg ^ neg.shr(2);
    let neg = neg ^ neg.shr(4);
    let neg = neg ^ neg.shr(8);
    // 2^16 cx = (positive terms) - (negative terms) = dx - 2 (dx & neg); same for y.
    let cx = dx - (dx & neg).shl(1);
    let cy = dy - (dy & neg).shl(1);
    // s_16 = -1 when the number of zero digits is odd: parity of all of `zero`, at bit 0.
    let odd = (neg ^ zero) & splat(1);
    // On the 2^-24 grid: 2^24 (c + (2/3) w_16) = 256 (2^16 c) + s_16 * 256/3, and
    // round(256/3) = 85. The centroid is at least 2^-16 / 3 = 85.3 * 2^-24 from each side of
    // its level-16 sub-triangle, so the rounded point stays strictly inside it.
    let centre = splat(85) - odd * splat(170);
    let qx = cx.shl(8) + centre;
    let qy = cy.shl(8) + centre;
    // All three are integers in [85, 2^24 - 170]: exact in f32, and they sum to 2^24.
    let qz = splat(GRID) - qx - qy;
    let scale = L::splat(1.0 / GRID as f32);
    [
        L::from_uint(qx) * scale,
        L::from_uint(qy) * scale,
        L::from_uint(qz) * scale,
    ]
}

/// Point `index` of the Basu-Owen triangular van der Corput sequence, Owen-scrambled by
/// `seed` (`seed = 0`: the plain construction).
///
/// The base-4 digits of `index`, least significant first, walk a 4-way subdivision of the
/// triangle (digits 1, 2, 3 pick the corner sub-triangles at `v0`, `v1`, `v2`; 0 picks the
/// inverted middle one), and the result is the centroid of the level-16 sub-triangle reached
/// by all 16 digits. Consequently the first `4^k` indices (any `k <= 16`) put exactly one
/// point in each of the `4^k` level-`k` sub-triangles, and any `4^k` consecutive indices
/// starting at a multiple of `4^k` do too: much more structure than a warped square keeps,
/// which pays off in triangle-light sampling.
///
/// The walk is branch-free and bit-twiddled on the integer index (pairs of bits are digits;
/// the signed sums of the walk are formed for all 16 digits at once with shifts and masks),
/// with no float van der Corput value, so all 16 digits count (an `f32` radical inverse would
/// hold 12). The point is the exact centroid rounded to the `2^-24` grid: within 4e-8 of it,
/// strictly inside its level-16 sub-triangle, `b_i >= 85 * 2^-24`, and `b0 + b1 + b2 = 1`
/// exactly.
///
/// `seed != 0` applies a nested base-4 digit scramble (Owen scrambling, hash-based in the
/// manner of Burley 2020): each node of the subdivision tree permutes its four children by a
/// permutation drawn from all 24, independently per seed. Every point is then uniformly
/// distributed over the triangle at the construction's resolution (equally likely to be the
/// centroid of any of the `4^16` level-16 sub-triangles: density `1 / area` at any scale above
/// `2^-16`) and the one-point-per-sub-triangle property above still holds, so different seeds give independent, equally stratified point
/// sets. Use one seed per pixel (or per light sample stream) and consecutive indices within
/// it.
#[inline]
pub fn basu_owen(index: u32, seed: u32) -> [f32; 3] {
    basu_owen_body::<f32>(Wrapping(index), Wrapping(seed))
}

/// [`basu_owen`] for eight (index, seed) pairs at once; bit-identical to eight scalar calls.
#[inline]
pub fn basu_owen_x8(index: u32x8, seed: u32x8) -> [f32x8; 3] {
    basu_owen_body::<f32x8>(index, seed)
}

/// [`basu_owen`] for sixteen (index, seed) pairs at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn basu_owen_x16(index: u32x16, seed: u32x16) -> [f32x16; 3] {
    basu_owen_body::<f32x16>(index, seed)
}

/// Fills `out[i] = basu_owen(start + i, seed)` (the index wraps past `u32::MAX`) and returns
/// `out.len()`. Bit-identical to the scalar form.
#[inline]
pub fn basu_owen_slice(start: u32, seed: u32, out: &mut [[f32; 3]]) -> usize {
    let seed = UintLane::splat(seed);
    slices::fill_indexed(start, out, |index| {
        basu_owen_body::<slices::Widest>(index, seed)
    })
}

/// Point `index` of the Basu-Owen construction with one digit permutation per level, drawn
/// from `seed` (`seed = 0`: the plain construction, bit-identical to `basu_owen(index, 0)`).
///
/// Digit `j` of `index` goes through a permutation `sigma_j` of `{0, 1, 2, 3}` before the
/// walk of [`basu_owen`]; each `sigma_j` is drawn from all 24 by `(seed, j)` and is the
/// *same* for every node of level `j`: the positional "random digit scrambling" of Matoušek
/// (1998, "On the L2-discrepancy for anchored boxes", J. Complexity 14), here in base 4 on the
/// Basu-Owen tree; Owen (2003, "Variance with alternative scramblings of digital nets", ACM
/// TOMACS 13) compares such scrambles with the nested one. What it keeps:
///
/// * every point is uniform over the triangle at the construction's resolution (density
///   `1 / area` at any scale above `2^-16`), for any fixed `index`, over random seeds;
/// * every aligned block of `4^k` indices (`start` a multiple of `4^k`, any `k <= 16`) puts
///   exactly one point in each level-`k` sub-triangle, for every seed;
/// * and, unlike the nested scramble of [`basu_owen`], within such a block every point sits
///   at the *same* relative position in its level-`k` sub-triangle (mirrored in the inverted
///   ones): the deeper digits are permuted alike everywhere. The within-cell offsets are then
///   correlated like systematic sampling instead of independent like jittering.
///
/// **Which randomization when.** The shared offset is what pays at an occluder edge: in the
/// report's triangle-light penumbrae this per-level permutation has 0.80x the MSE of
/// Owen-scrambled pmj02bn through [`uniform`] at 256 samples per pixel, where the nested
/// scramble of [`basu_owen`] behaves like a jittered grid of sub-triangles and has 1.38x. In
/// fully lit pixels it is the best at 16 samples per pixel, and pmj02bn through a square warp
/// at 256 (2.5-5.7x). See the [module docs](self) and `docs/REPORT.md`.
///
/// Same guarantees as [`basu_owen`]: the exact centroid of a level-16 sub-triangle rounded to
/// the `2^-24` grid (within 4e-8 of it), multiples of `2^-24` summing to exactly 1, every
/// `b_i >= 85 * 2^-24`, every index and seed valid.
///
/// Cost: the 16 permutations are drawn from the seed (four hash words, 32 compares) and then
/// applied to all 16 digits with six word operations, with no per-node hash. The slice form
/// draws them once per call and is about 1.4x faster than [`basu_owen_slice`]; the scalar
/// and `_x8` forms draw them on every call (per lane), which makes them slower than
/// [`basu_owen`] (about 0.6x): use the slice for a pixel's stream.
#[inline]
pub fn basu_owen_permuted(index: u32, seed: u32) -> [f32; 3] {
    let keys = base4::LevelKeys::new(Wrapping(seed));
    basu_owen_permuted_body::<f32>(base4::fields(Wrapping(index)), keys)
}

/// [`basu_owen_permuted`] for eight (index, seed) pairs at once; bit-identical to eight
/// scalar calls.
#[inline]
pub fn basu_owen_permuted_x8(index: u32x8, seed: u32x8) -> [f32x8; 3] {
    basu_owen_permuted_body::<f32x8>(base4::fields(index), base4::LevelKeys::new(seed))
}

/// [`basu_owen_permuted`] for sixteen (index, seed) pairs at once; bit-identical to sixteen
/// scalar calls.
#[inline]
pub fn basu_owen_permuted_x16(index: u32x16, seed: u32x16) -> [f32x16; 3] {
    basu_owen_permuted_body::<f32x16>(base4::fields(index), base4::LevelKeys::new(seed))
}

/// Fills `out[i] = basu_owen_permuted(start + i, seed)` (the index wraps past `u32::MAX`) and
/// returns `out.len()`. Draws the per-level permutations once per call. Bit-identical to the
/// scalar form.
#[inline]
pub fn basu_owen_permuted_slice(start: u32, seed: u32, out: &mut [[f32; 3]]) -> usize {
    let keys = base4::LevelKeys::splat(base4::LevelKeys::new(Wrapping(seed)));
    slices::fill_indexed(start, out, |index| {
        basu_owen_permuted_body::<slices::Widest>(base4::fields(index), keys)
    })
}
