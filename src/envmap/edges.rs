//! Exact texel boundaries in `f32`: where a texel's `uv` interval starts and ends.
//!
//! Texel `k` of `n` covers `[k/n, (k+1)/n)`. Those bounds are rarely `f32` values, and
//! `(k + frac) / n` rounds, so a point computed that way can land one ulp outside its texel
//! (and `floor(uv * n)` then names the neighbour). Each distribution therefore stores, per
//! axis, `edge[k]` = the smallest `f32` `x` with `x * n >= k` exactly, for `k = 0..=n`
//! (`edge[0] = 0`, `edge[n] = 1`). Texel `k` holds exactly the `f32`s in
//! `[edge[k], edge[k+1])`; the sampler clamps its point into that range and the `pdf`
//! lookup inverts it with one multiply and a one-step correction.

use super::from_storage_order;
use crate::lanes::{Lane, UintLane, unit_interval};

/// The smallest `f32` `x` with `x * n >= k` in exact arithmetic, for `0 <= k <= n <= 2^24`.
///
/// `f32 * n` with `n < 2^25` has at most 49 significant bits, so the products below are exact
/// in `f64`.
fn edge(k: u32, n: u32) -> f32 {
    let exact_ge = |x: f32| f64::from(x) * f64::from(n) >= f64::from(k);
    let mut x = (f64::from(k) / f64::from(n)) as f32;
    // The rounded quotient is within one ulp of the answer; step onto it.
    while !exact_ge(x) {
        x = f32::from_bits(x.to_bits() + 1);
    }
    while x > 0.0 && exact_ge(f32::from_bits(x.to_bits() - 1)) {
        x = f32::from_bits(x.to_bits() - 1);
    }
    x
}

/// Fills `out` (`n + 1` words) with the edges of `n` texels, as `f32` bits.
pub(super) fn fill(out: &mut [u32], n: u32) {
    for (k, o) in (0u32..).zip(out.iter_mut()) {
        *o = edge(k, n).to_bits();
    }
}

/// Index of the first of the `n + 1` words of `table` that is not `edge(k, n)` (in storage
/// byte order), if any: the one-pass check of a loaded storage.
pub(super) fn first_wrong(table: &[[u32; 1]], n: u32) -> Option<usize> {
    (0u32..=n).position(|k| {
        let got = table
            .get(k as usize)
            .map(|&[w]| from_storage_order(core::num::Wrapping(w)).0);
        got != Some(edge(k, n).to_bits())
    })
}

/// `[edge[k], edge[k + 1]]` per lane (one 8-byte read each), from storage byte order.
#[inline(always)]
fn load2<U: UintLane>(edges: &[[u32; 1]], k: U) -> [U; 2] {
    U::gather2(edges.as_flattened(), k).map(from_storage_order)
}

/// The point `(k + frac) / n` of texel `k` (`frac` in `[0, 1)`), clamped into
/// `[edge[k], edge[k+1])` so it lies inside the texel exactly.
///
/// The final forward rule is a no-op for real edges (the point is already in `[0, 1)`); it
/// keeps the point in `[0, 1)` whatever a corrupt table holds.
#[inline(always)]
pub(super) fn point<L: Lane>(edges: &[[u32; 1]], k: L::U, frac: L, n: f32) -> L {
    let x = (L::from_uint(k) + frac) / L::splat(n);
    let [lo, next] = load2(edges, k);
    // `edge[k+1] > 0`, so its predecessor is one less in the bit pattern.
    let (lo, hi) = (L::from_bits(lo), L::from_bits(next - L::U::splat(1)));
    let x = L::select(x.simd_lt(lo), lo, x);
    unit_interval(L::select(hi.simd_lt(x), hi, x))
}

/// The texel (`0..n`) holding coordinate `x`, after the forward rule (NaN, negatives -> 0,
/// `>= 1` -> `1 - 2^-24`). `x * n` rounds by less than one texel (`n <= 2^24`), so one
/// correction step against the edges makes the answer exact. (The last clamp is a no-op for
/// real edges; with a corrupt table it keeps the texel in `0..n`.)
#[inline(always)]
pub(super) fn texel<L: Lane>(edges: &[[u32; 1]], x: L, n: u32) -> L::U {
    let x = unit_interval(x);
    let k = (x * L::splat(n as f32)).to_uint();
    let last = L::U::splat(n.wrapping_sub(1));
    let k = L::U::select(last.simd_lt(k), last, k);
    let one = L::U::splat(1);
    let [lo, next] = load2(edges, k);
    let below = x.simd_lt(L::from_bits(lo));
    let above = L::from_bits(next).simd_le(x);
    let k = L::U::select(below, k - one, L::U::select(above, k + one, k));
    L::U::select(last.simd_lt(k), last, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Edges against exact rational comparisons, for many sizes.
    #[test]
    fn edges_are_the_exact_texel_bounds() {
        for n in [
            1u32,
            2,
            3,
            5,
            7,
            10,
            255,
            256,
            257,
            1000,
            4097,
            8191,
            1 << 24,
        ] {
            let ks: [u32; 6] = [0, 1, n / 3, n / 2, n - 1, n];
            for &k in &ks {
                let e = edge(k, n);
                assert!(f64::from(e) * f64::from(n) >= f64::from(k));
                if k > 0 {
                    let below = f32::from_bits(e.to_bits() - 1);
                    assert!(f64::from(below) * f64::from(n) < f64::from(k), "{k}/{n}");
                }
            }
            assert_eq!(edge(0, n), 0.0);
            assert_eq!(edge(n, n), 1.0);
        }
    }

    #[test]
    fn point_and_texel_agree_at_the_bounds() {
        for n in [1u32, 3, 7, 1000, 4097] {
            let mut e = [[0u32; 1]; 4098];
            let (e, _) = e.split_at_mut(n as usize + 1);
            for (k, o) in e.iter_mut().enumerate() {
                o[0] = edge(k as u32, n).to_bits();
            }
            for k in [0, n / 2, n - 1] {
                for frac in [0.0f32, 1e-30, 0.5, 1.0 - 1.0 / 16_777_216.0] {
                    let x: f32 = point(e, core::num::Wrapping(k), frac, n as f32);
                    assert!((0.0..1.0).contains(&x));
                    let t = f64::from(x) * f64::from(n);
                    assert!(t >= f64::from(k) && t < f64::from(k + 1), "{k}/{n} {frac}");
                    assert_eq!(texel(e, x, n).0, k);
                }
            }
            assert_eq!(texel(e, f32::NAN, n).0, 0);
            assert_eq!(texel(e, 2.0f32, n).0, n - 1);
        }
    }
}
