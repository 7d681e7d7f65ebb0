//! Double-`f32` arithmetic by error-free transformations, without FMA (banned by the
//! determinism rule): Knuth's two-sum and Dekker's product with Veltkamp's splitting (Dekker
//! 1971, "A floating-point technique for extending the available precision", Numer. Math.
//! 18; Ogita, Rump and Oishi 2005, "Accurate sum and dot product", SIAM J. Sci. Comput. 26).
//! A value is carried as an unevaluated sum `hi + lo`. Used where a sum of products
//! cancels: the half vector of the reflection densities and `wo.m` of the visible-normal
//! density. Every operation is an `f32` operation whose rounding the algorithms rely on, in
//! the written order (Rust never reassociates; the WGSL transcription fences them).
//!
//! Range: the inputs are power-of-two-scaled vectors (largest component in `[1, 2)`), so the
//! splitter's `4097 x` never overflows, and their components below `2^-40` count as zero
//! ([`coarse`]): every remaining component has an ulp of at least `2^-63`, so every product
//! of halves, error term and partial sum is a multiple of `2^-126`, never subnormal. Devices
//! that flush subnormals (Mesa lavapipe does) then compute the same bits.

use crate::lanes::Lane;
use crate::vec3::V;

/// `x = hi + lo` exactly, each half of at most 12 significant bits (Veltkamp's split with
/// the splitter `2^12 + 1`), so products of halves are exact.
#[inline(always)]
fn split<L: Lane>(x: L) -> (L, L) {
    let c = L::splat(4097.0) * x;
    let hi = c - (c - x);
    (hi, x - hi)
}

/// `a + b = s + e` exactly (Knuth's two-sum, any order of magnitude).
#[inline(always)]
pub(super) fn two_sum<L: Lane>(a: L, b: L) -> (L, L) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

/// `a b = p + e` exactly (Dekker's product).
#[inline(always)]
fn two_prod<L: Lane>(a: L, b: L) -> (L, L) {
    let p = a * b;
    let ((ah, al), (bh, bl)) = (split(a), split(b));
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// `a^2 = p + e` exactly.
#[inline(always)]
fn two_square<L: Lane>(a: L) -> (L, L) {
    let p = a * a;
    let (ah, al) = split(a);
    let t = ah * al;
    (p, ((ah * ah - p) + (t + t)) + al * al)
}

/// `v` with its components below `2^-40` in magnitude made 0 (see the module docs). For
/// the scaled vectors this moves a direction by less than `2^-40`.
#[inline(always)]
fn coarse<L: Lane>(v: V<L>) -> V<L> {
    let small = L::splat(1.0 / (1u64 << 40) as f32);
    v.map(|x| L::select(x.abs().simd_lt(small), L::splat(0.0), x))
}

/// `a . b` (components below `2^-40` read as 0) as `hi + lo`, with an error of a few
/// `2^-48 sum |a_i b_i|` (Ogita, Rump and Oishi's `Dot2`).
#[inline(always)]
pub(super) fn dot2<L: Lane>(a: V<L>, b: V<L>) -> (L, L) {
    let (a, b) = (coarse(a), coarse(b));
    sum3([
        two_prod(a[0], b[0]),
        two_prod(a[1], b[1]),
        two_prod(a[2], b[2]),
    ])
}

/// `|a|^2` as `hi + lo` (squares need one split each).
#[inline(always)]
fn norm2<L: Lane>(a: V<L>) -> (L, L) {
    sum3(a.map(two_square))
}

/// The sum of three exact products `p_i + e_i` as `hi + lo`: the `p_i` added with two
/// error-free sums, every error term added in plain `f32` (Ogita, Rump and Oishi's `Sum2`).
#[inline(always)]
fn sum3<L: Lane>(terms: [(L, L); 3]) -> (L, L) {
    let [(p0, e0), (p1, e1), (p2, e2)] = terms;
    let (s, t0) = two_sum(p0, p1);
    let (s, t1) = two_sum(s, p2);
    (s, (t0 + t1) + ((e0 + e1) + e2))
}

/// The direction of `a / |a| + b / |b|` (nonzero `a`, `b` of the scaled range, components
/// below `2^-40` read as 0), as
/// `a + (|a| / |b|) b` rounded once per component from double-`f32`: `|a| / |b|` is the
/// square root of `|a|^2 / |b|^2` to about `2^-46` relative (a quotient and a square root
/// each corrected by its exact remainder), so each component's error is a few ulps of itself
/// plus `2^-45 |a|`, however much `a_i` and the scaled `b_i` cancel. Since `|rho b| = |a|`,
/// `a . h = |h|^2 / 2` for the result `h`: its projection needs no (cancelling) dot product.
#[inline(always)]
pub(super) fn half_direction<L: Lane>(a: V<L>, b: V<L>) -> V<L> {
    let (a, b) = (coarse(a), coarse(b));
    let (a2, a2l) = norm2(a);
    let (b2, b2l) = norm2(b);
    // r = |a|^2 / |b|^2: a2 - r b2 is exact (Sterbenz), corrected by both low parts.
    let inv = L::splat(1.0) / b2;
    let r = a2 * inv;
    let (p, e) = two_prod(r, b2);
    let rl = (((a2 - p) - e) + a2l - r * b2l) * inv;
    // rho = sqrt(r), corrected by the remainder r - rho^2 (exact, Sterbenz).
    let rho = r.sqrt();
    let (p, e) = two_square(rho);
    let rhol = (((r - p) - e) + rl) / (rho + rho);
    let c = |ai: L, bi: L| {
        let (p, e) = two_prod(bi, rho);
        let (s, t) = two_sum(ai, p);
        s + ((t + e) + bi * rhol)
    };
    [c(a[0], b[0]), c(a[1], b[1]), c(a[2], b[2])]
}
