//! Baseline samplers to compare the low-discrepancy sequences against: independent
//! [`random`] points and a jittered [`stratified`] grid. Both are index-driven and seeded like
//! [`pmj02bn::sample`](crate::pmj02bn), so they drop into the same renderer code.
//!
//! | sampler | point `index` | stratification |
//! |---|---|---|
//! | [`random`] | two counter-based hashes of `(index, seed)` | none |
//! | [`stratified`] | a uniform point in cell `index` of an `m x m` grid, `m = floor(sqrt(count))` | the `m x m` grid, for the full `count` only |
//!
//! Outputs are in `[0, 1 - 2^-24]^2` (truncating conversion of 0.32 fixed point, never 1.0).
//! Every `u32` argument is valid.

use crate::hash::{mix, to_unit};
use crate::lanes::{Lane, ONE_MINUS_EPSILON, UintLane};
use crate::slices;
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

const KEY_X: u32 = 0x2545_f491;
const KEY_Y: u32 = 0x9e37_79b9;

/// Two independent 32-bit hashes of `(index, seed)`: `mix` is a bijection, so distinct
/// indices of one seed never share their inner hash.
#[inline(always)]
fn hash2<U: UintLane>(index: U, seed: U) -> [U; 2] {
    let h = mix(index ^ mix(seed));
    [mix(h ^ U::splat(KEY_X)), mix(h + U::splat(KEY_Y))]
}

#[inline(always)]
fn random_body<L: Lane>(index: L::U, seed: L::U) -> [L; 2] {
    let [x, y] = hash2(index, seed);
    [to_unit(x), to_unit(y)]
}

/// Point `index` of an independent uniform random sequence for `seed`: counter-based (a
/// stateless hash of the index, with Wellons' `lowbias32` mixer), so any index is available
/// in O(1), in any order, on any lane width.
#[inline]
pub fn random(index: u32, seed: u32) -> [f32; 2] {
    random_body::<f32>(Wrapping(index), Wrapping(seed))
}

/// [`random`] on eight lanes; bit-identical to eight scalar calls.
#[inline]
pub fn random_x8(index: u32x8, seed: u32x8) -> [f32x8; 2] {
    random_body::<f32x8>(index, seed)
}

/// [`random`] on sixteen lanes; bit-identical to sixteen scalar calls.
#[inline]
pub fn random_x16(index: u32x16, seed: u32x16) -> [f32x16; 2] {
    random_body::<f32x16>(index, seed)
}

/// Fills `out[i] = random(start + i, seed)` (wrapping); returns `out.len()`.
#[inline]
pub fn random_slice(start: u32, seed: u32, out: &mut [[f32; 2]]) -> usize {
    let seed = UintLane::splat(seed);
    slices::fill_indexed(start, out, |i| random_body::<slices::Widest>(i, seed))
}

/// Side of the stratified grid for `count` points: `floor(sqrt(min(count, 2^24)))`, at most
/// 4096 (so cell indices stay exact in `f32`).
#[inline]
pub fn stratified_side(count: u32) -> u32 {
    count.min(1 << 24).isqrt()
}

#[inline(always)]
fn stratified_body<L: Lane>(index: L::U, side: u32, seed: L::U) -> [L; 2] {
    let [hx, hy] = hash2(index, seed);
    let (jx, jy): (L, L) = (to_unit(hx), to_unit(hy));
    // row = index / side, col = index % side, for index < side^2 <= 2^24: the f32 quotient
    // is exact or one too large (correctly rounded division of integers below 2^24), and
    // one correction step makes it exact.
    let m = L::U::splat(side);
    let q = (L::from_uint(index) / L::from_uint(m)).to_uint();
    let r = index - q * m;
    let negative = r.shr(31).simd_eq(L::U::splat(1));
    let row = L::U::select(negative, q - L::U::splat(1), q);
    let col = L::U::select(negative, r + m, r);
    // (col + jitter) / side: exact up to the two roundings, which may land on the cell's
    // upper edge (never past it) — or on 1.0, which is mapped to 1 - 2^-24.
    let inv = L::splat(1.0) / L::from_uint(m);
    let one = L::splat(1.0);
    let cell = |c: L::U, j: L| {
        let v = (L::from_uint(c) + j) * inv;
        L::select(v.simd_lt(one), v, L::splat(ONE_MINUS_EPSILON))
    };
    // Cells exist for index < side^2 (then index < 2^24 and row < side); other indices
    // (and every index when count = 0) are uniform random.
    let small = index.shr(24).simd_eq(L::U::splat(0));
    let in_grid = small & L::from_uint(row).simd_lt(L::from_uint(m));
    [
        L::select(in_grid, cell(col, jx), jx),
        L::select(in_grid, cell(row, jy), jy),
    ]
}

/// Point `index` of a jittered `m x m` grid for `count` points, `m = `[`stratified_side`]`(count)`:
/// index `i < m^2` is uniform in cell `(i % m, i / m)` (column, row), with the jitter a hash
/// of `(index, seed)`; indices `m^2 <= i` (the `count - m^2` extra points when `count` is not
/// a square, and anything past `count`) are uniform random points. Each point is uniform on
/// the square, so any subset is an unbiased estimator; the stratification holds for the
/// whole `count` (a prefix covers only the lower rows).
#[inline]
pub fn stratified(index: u32, count: u32, seed: u32) -> [f32; 2] {
    stratified_body::<f32>(Wrapping(index), stratified_side(count), Wrapping(seed))
}

/// [`stratified`] on eight indices (one `count` for all lanes); bit-identical to scalar calls.
#[inline]
pub fn stratified_x8(index: u32x8, count: u32, seed: u32x8) -> [f32x8; 2] {
    stratified_body::<f32x8>(index, stratified_side(count), seed)
}

/// [`stratified`] on sixteen indices (one `count` for all lanes); bit-identical to scalar calls.
#[inline]
pub fn stratified_x16(index: u32x16, count: u32, seed: u32x16) -> [f32x16; 2] {
    stratified_body::<f32x16>(index, stratified_side(count), seed)
}

/// Fills `out[i] = stratified(start + i, count, seed)` (wrapping); returns `out.len()`.
/// `stratified_slice(0, n, seed, &mut out[..n])` is the whole stratified set.
#[inline]
pub fn stratified_slice(start: u32, count: u32, seed: u32, out: &mut [[f32; 2]]) -> usize {
    let (side, seed) = (stratified_side(count), UintLane::splat(seed));
    slices::fill_indexed(start, out, |i| {
        stratified_body::<slices::Widest>(i, side, seed)
    })
}
