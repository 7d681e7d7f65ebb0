//! Disk warps: the unit square onto the unit disk, uniformly (all four are area-preserving,
//! so the density of the result is [`PDF`] `= 1/pi` with respect to area).
//!
//! | warp | maps | keeps | source |
//! |---|---|---|---|
//! | [`polar`] | `r = sqrt(u0)`, `theta = 2 pi u1` | nothing compact: strata become thin rings near the rim | textbook; pbrt-v4 `SampleUniformDiskPolar` |
//! | [`concentric`] | squares to rings, wedge by wedge | 4x4 strata stay compact | Shirley and Chiu 1997, "A Low Distortion Map Between Disk and Square" |
//! | [`polar4`] | one 2D point to four quadrants: `r = sqrt(u0)`, `theta = (pi/2)(u1 + quadrant)` | the point's strata, four times | Christensen 2018, "Progressive Sampling Strategies for Disk Light Sources" (Pixar TM 18-02) |
//! | [`concentric4`] | one 2D point to four quadrants: Shirley-Chiu on the quarter disk, turned | compact strata, four times | the same memo |
//!
//! The two quadrant warps use sample `i` with point `i / 4` of a 2D sequence and quadrant
//! `i % 4`; their `_indexed` and `_slice` forms do that bookkeeping.
//!
//! `u[0]` drives the radius and `u[1]` the angle (counter-clockwise from `+x`).
//!
//! **Out-of-range input** (every function here is total): each forward coordinate is first
//! mapped onto `[0, 1 - 2^-24]` — NaN, `-0.0`, negatives and `-inf` become `0`, values
//! `>= 1` and `+inf` become `1 - 2^-24`. Inverses clamp each coordinate of `p` to `[-1, 1]`
//! (NaN becomes `0`); a point outside the disk then maps like the rim point in its direction.
//!
//! **Domain guarantee**: every output lies in the closed unit disk in exact arithmetic
//! (`x^2 + y^2 <= 1` holds for the returned `f32` values, however the caller evaluates it). To
//! make that provable despite rounding in sin/cos, radii are clamped to `1 - 2^-23`
//! (only the outermost 1.2e-7 of the radius is affected; see `trig::MAX_RADIUS`).
//!
//! **Precision** (tests in `tests/disk.rs`, against the same formulas in `f64` over 2^22
//! random points and dense edge sweeps): forward maps are within 1.5e-7 of the `f64` result
//! per coordinate (measured 1.35e-7; 2.5e-7 at the clamped rim, measured 1.8e-7);
//! `inverse(warp(u))` is within 5e-7 of `u`, the rim included, except on the singular sets
//! named on each inverse.

use crate::lanes::{Lane, UintLane, signed_unit, unit_interval};
use crate::slices::{self, Vector};
use crate::trig::{
    MAX_RADIUS, atan_ratio_pi4, atan2_turns, sin_cos_pi4, sin_cos_quarter_turns, sin_cos_turns,
};
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// Density of every disk warp's output with respect to area on the unit disk: `1 / pi`.
pub const PDF: f32 = core::f32::consts::FRAC_1_PI;

/// `min(r, MAX_RADIUS)` for `r >= 0` (compare and select, see `lanes`).
#[inline(always)]
fn clamp_radius<L: Lane>(r: L) -> L {
    let max = L::splat(MAX_RADIUS);
    L::select(max.simd_lt(r), max, r)
}

// ---------------------------------------------------------------------------------------
// Polar

#[inline(always)]
fn polar_body<L: Lane>(u: [L; 2]) -> [L; 2] {
    let r = clamp_radius(unit_interval(u[0]).sqrt());
    let (s, c) = sin_cos_turns(unit_interval(u[1]));
    [r * c, r * s]
}

#[inline(always)]
fn polar_inverse_body<L: Lane>(p: [L; 2]) -> [L; 2] {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    [unit_interval(x * x + y * y), atan2_turns(y, x)]
}

/// Polar map: `r = sqrt(u0)`, `theta = 2 pi u1`, returns `(r cos theta, r sin theta)`.
///
/// Exact range reduction: `4 u1` splits into a quarter-turn count and a fraction, so the
/// angle never passes through a rounded `2 pi u1`. Density [`PDF`]. Error against `f64`: at
/// most 1.5e-7 per coordinate. See the [module docs](self) for out-of-range input.
#[inline]
pub fn polar(u: [f32; 2]) -> [f32; 2] {
    polar_body(u)
}

/// [`polar`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar_x8(u: [f32x8; 2]) -> [f32x8; 2] {
    polar_body(u)
}

/// [`polar`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn polar_x16(u: [f32x16; 2]) -> [f32x16; 2] {
    polar_body(u)
}

/// [`polar`] over a batch: writes `out[i] = polar(u[i])` for
/// `i < min(u.len(), out.len())` and returns that count (a length mismatch never panics;
/// the rest of the longer slice is untouched). Bit-identical to the scalar form.
#[inline]
pub fn polar_slice(u: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(u, out, polar_body::<slices::Widest>)
}

/// Inverse of [`polar`]: `u0 = x^2 + y^2`, `u1 = atan2(y, x) / (2 pi)` in `[0, 1)`.
///
/// Round trip `|u - polar_inverse(polar(u))| <= 5e-7` for `u` in `[0, 1)^2` (measured
/// 3.6e-7, at the rim), except on the singular set `u0 = 0` (the centre, where the angle is lost and
/// `u1 = 0` is returned). Near the seam `u1 -> 1` the result stays below 1 (it returns
/// `1 - 2^-24`, not 0). `y = -0.0` counts as the `u1 = 0` side.
#[inline]
pub fn polar_inverse(p: [f32; 2]) -> [f32; 2] {
    polar_inverse_body(p)
}

/// [`polar_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar_inverse_x8(p: [f32x8; 2]) -> [f32x8; 2] {
    polar_inverse_body(p)
}

/// [`polar_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn polar_inverse_x16(p: [f32x16; 2]) -> [f32x16; 2] {
    polar_inverse_body(p)
}

/// [`polar_inverse`] over a batch, with the length rule of [`polar_slice`].
#[inline]
pub fn polar_inverse_slice(p: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(p, out, polar_inverse_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Concentric

#[inline(always)]
fn concentric_body<L: Lane>(u: [L; 2]) -> [L; 2] {
    let (r, c, s) = concentric_parts(u);
    [r * c, r * s]
}

/// The concentric map in polar form: `(r, c, s)` with `concentric(u) = [r * c, r * s]`.
///
/// `r` is the signed radius of Shirley and Chiu (`a` or `b`, clamped in magnitude to
/// `MAX_RADIUS`), and `(c, s)` the direction for that sign convention (`c^2 + s^2` is 1 up to
/// the kernels' error). The sphere warps lift the disk point to the hemisphere from `|r|`
/// directly, where `1 - r^2 = (1 - |r|)(1 + |r|)` keeps its relative precision at the rim.
#[cfg_attr(not(feature = "sphere"), allow(dead_code))]
#[inline(always)]
pub(crate) fn concentric_parts<L: Lane>(u: [L; 2]) -> (L, L, L) {
    let one = L::splat(1.0);
    let two = L::splat(2.0);
    let a = two * unit_interval(u[0]) - one;
    let b = two * unit_interval(u[1]) - one;
    // Textbook: if |a| > |b| { r = a, phi = (pi/4)(b/a) } else { r = b, phi = pi/2 - (pi/4)(a/b) }.
    let a_major = b.abs().simd_lt(a.abs());
    let r = L::select(a_major, a, b);
    let n = L::select(a_major, b, a);
    let zero = L::splat(0.0);
    // r == 0 only at the centre, where n == 0 too: t = 0 instead of 0/0.
    let t = L::select(r.simd_eq(zero), zero, n / r);
    let r = clamp_radius(r.abs()).flip_sign(r.sign_bit());
    // cos(pi/2 - x) = sin(x): the b-major wedges swap sin and cos.
    let (s, c) = sin_cos_pi4(t);
    (r, L::select(a_major, c, s), L::select(a_major, s, c))
}

#[inline(always)]
pub(crate) fn concentric_inverse_body<L: Lane>(p: [L; 2]) -> [L; 2] {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    let (ax, ay) = (x.abs(), y.abs());
    let x_major = ay.simd_lt(ax);
    let r = (x * x + y * y).sqrt();
    let w = atan_ratio_pi4(L::select(x_major, ay, ax), L::select(x_major, ax, ay));
    // The major coordinate of the square point is +-r, the minor one +-r w, with the signs of
    // x and y (see `concentric_body`: sign(x) = sign(a), sign(y) = sign(b)).
    let rw = r * w;
    let a = L::select(x_major, r, rw).flip_sign(x.sign_bit());
    let b = L::select(x_major, rw, r).flip_sign(y.sign_bit());
    let half = L::splat(0.5);
    [
        unit_interval(a * half + half),
        unit_interval(b * half + half),
    ]
}

/// Concentric map of Shirley and Chiu (1997): `a = 2 u0 - 1`, `b = 2 u1 - 1`; if `|a| > |b|`
/// then `r = a`, `phi = (pi/4)(b / a)`, else `r = b`, `phi = pi/2 - (pi/4)(a / b)`; returns
/// `(r cos phi, r sin phi)`, and the centre `u = (1/2, 1/2)` maps to the origin.
///
/// Exactly the textbook map (ties `|a| = |b|` take the second branch, as in the paper), but
/// branch-free: one division, sin and cos on `[-pi/4, pi/4]`, and a mask that swaps them.
/// Concentric squares of the domain map to concentric circles, so compact strata stay
/// compact. Density [`PDF`]. Error against `f64`: at most 1.5e-7 per coordinate. See the
/// [module docs](self) for out-of-range input.
#[inline]
pub fn concentric(u: [f32; 2]) -> [f32; 2] {
    concentric_body(u)
}

/// [`concentric`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric_x8(u: [f32x8; 2]) -> [f32x8; 2] {
    concentric_body(u)
}

/// [`concentric`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn concentric_x16(u: [f32x16; 2]) -> [f32x16; 2] {
    concentric_body(u)
}

/// [`concentric`] over a batch, with the length rule of [`polar_slice`]. Bit-identical to
/// the scalar form.
#[inline]
pub fn concentric_slice(u: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(u, out, concentric_body::<slices::Widest>)
}

/// Inverse of [`concentric`]: the wedge is chosen by `|x|` vs `|y|`, the radius is
/// `sqrt(x^2 + y^2)` and the in-wedge coordinate `(4/pi) atan(minor / major)`.
///
/// Round trip `|u - concentric_inverse(concentric(u))| <= 5e-7` for `u` in `[0, 1)^2`
/// (measured 1.2e-7), except on the singular set `u = (1/2, 1/2)` (the centre, returned
/// exactly) — there is no other: the map is continuous across wedge diagonals.
#[inline]
pub fn concentric_inverse(p: [f32; 2]) -> [f32; 2] {
    concentric_inverse_body(p)
}

/// [`concentric_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric_inverse_x8(p: [f32x8; 2]) -> [f32x8; 2] {
    concentric_inverse_body(p)
}

/// [`concentric_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn concentric_inverse_x16(p: [f32x16; 2]) -> [f32x16; 2] {
    concentric_inverse_body(p)
}

/// [`concentric_inverse`] over a batch, with the length rule of [`polar_slice`].
#[inline]
pub fn concentric_inverse_slice(p: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    slices::map_lanes(p, out, concentric_inverse_body::<slices::Widest>)
}

// ---------------------------------------------------------------------------------------
// Polar4

#[inline(always)]
fn polar4_body<L: Lane>(u: [L; 2], quadrant: L::U) -> [L; 2] {
    let r = clamp_radius(unit_interval(u[0]).sqrt());
    let (s, c) = sin_cos_quarter_turns(unit_interval(u[1]), quadrant);
    [r * c, r * s]
}

#[inline(always)]
fn polar4_inverse_body<L: Lane>(p: [L; 2]) -> ([L; 2], L::U) {
    let [u0, turns] = polar_inverse_body(p);
    let v = turns * L::splat(4.0);
    let q = v.to_uint();
    ([u0, v - L::from_uint(q)], q)
}

/// Polar4 (Christensen 2018): one 2D point gives four disk samples, one per quadrant.
/// `r = sqrt(u0)`, `theta = (pi/2) u1 + (pi/2) quadrant`; only `quadrant % 4` is used.
///
/// Used for sample `i` with the point `i / 4` of a 2D sequence and `quadrant = i % 4` — the
/// helpers [`polar4_indexed`] and [`polar4_slice`] do this bookkeeping. The four samples of
/// one point are rotations of each other by quarter turns, which halves the error of disk-light
/// sampling at high sample counts in Christensen's measurements. For `u1 in [0, 1)`,
/// `polar(u) == polar4([u0, frac(4 u1)], floor(4 u1))` bit for bit. Density [`PDF`] (over
/// a uniformly chosen quadrant). Error against `f64`: at most 1.5e-7 per coordinate.
#[inline]
pub fn polar4(u: [f32; 2], quadrant: u32) -> [f32; 2] {
    polar4_body(u, Wrapping(quadrant))
}

/// [`polar4`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar4_x8(u: [f32x8; 2], quadrant: u32x8) -> [f32x8; 2] {
    polar4_body(u, quadrant)
}

/// [`polar4`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn polar4_x16(u: [f32x16; 2], quadrant: u32x16) -> [f32x16; 2] {
    polar4_body(u, quadrant)
}

/// Disk sample `index` of a polar4 stream: `polar4(point(index / 4), index % 4)`.
///
/// `point` returns 2D point `k` of your sequence, e.g.
/// `polar4_indexed(i, |k| my_sampler.get(k))`; it is called once, with `index / 4`.
#[inline]
pub fn polar4_indexed(index: u32, point: impl FnOnce(u32) -> [f32; 2]) -> [f32; 2] {
    polar4(point(index >> 2), index & 3)
}

/// [`polar4_indexed`] for eight sample indices at once (any indices, not only consecutive).
#[inline]
pub fn polar4_indexed_x8(index: u32x8, points: impl FnOnce(u32x8) -> [f32x8; 2]) -> [f32x8; 2] {
    polar4_x8(points(index >> 2), index & u32x8::splat(3))
}

/// [`polar4_indexed`] for sixteen sample indices at once (any indices, not only consecutive).
#[inline]
pub fn polar4_indexed_x16(
    index: u32x16,
    points: impl FnOnce(u32x16) -> [f32x16; 2],
) -> [f32x16; 2] {
    polar4_x16(points(index >> 2), index & u32x16::splat(3))
}

/// Expands 2D points into polar4 disk samples, four per point: `out[i] =
/// polar4(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`; returns that
/// count. Bit-identical to the scalar form.
#[inline]
pub fn polar4_slice(points: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    four_per_point(points, out, |u: [slices::Widest; 2]| {
        polar4_body(u, UintLane::splat(0))
    })
}

/// `out[i] = warp(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`; returns
/// that count. The slice form of the quadrant warps.
///
/// Both quadrant warps turn their result by exact quarter turns (a swap and sign flips:
/// `warp(u, q)` is `warp(u, 0)` turned `q` times by `(x, y) -> (-y, x)`, bit for bit), so
/// `warp` here is the quadrant-0 body: it runs once per *point*, `N` points per call, and
/// [`four_turns`] writes each point's four samples.
#[inline(always)]
fn four_per_point<L: Vector<N>, const N: usize>(
    points: &[[f32; 2]],
    out: &mut [[f32; 2]],
    warp: impl Fn([L; 2]) -> [L; 2],
) -> usize {
    let n = out.len().min(points.len().saturating_mul(4));
    let out = out.get_mut(..n).unwrap_or(&mut []);
    let (groups, _) = points.as_chunks::<N>();
    // Whole groups: N points in, 4 N samples out.
    let whole = n / (4 * N);
    let (out_main, out_rest) = out.split_at_mut(whole * 4 * N);
    let (out_rows, _) = out_main.as_chunks_mut::<N>();
    for (src, dst) in groups.iter().zip(out_rows.chunks_exact_mut(4)) {
        for (d, r) in dst.iter_mut().zip(four_turns(warp(slices::load(src)))) {
            *d = r;
        }
    }
    if !out_rest.is_empty() {
        // Fewer than 4 N samples left: they come from the next (at most N) points.
        let mut pad = [[0.0f32; 2]; N];
        for (p, s) in pad.iter_mut().zip(points.get(whole * N..).unwrap_or(&[])) {
            *p = *s;
        }
        let res = four_turns(warp(slices::load(&pad)));
        for (d, r) in out_rest.iter_mut().zip(res.as_flattened()) {
            *d = *r;
        }
    }
    n
}

/// The four quarter turns of `N` disk points as `4 N` array-of-structs samples: sample
/// `4 j + k` is point `j` turned `k` times by `(x, y) -> (-y, x)`, i.e. `(x, y)`, `(-y, x)`,
/// `(-x, -y)`, `(y, -x)`. Lane permutes and sign-bit flips only, so exact; the permutes are
/// the ones the slice forms' transposes need anyway.
#[inline(always)]
fn four_turns<L: Vector<N>, const N: usize>(p: [L; 2]) -> [[[f32; 2]; N]; 4] {
    // Word f = N r + l of the output is negated for sample, component (1, 0), (2, _), (3, 1).
    let signs: &[[u32; N]; 8] = &const {
        let mut signs = [[0; N]; 8];
        let mut f = 0;
        while f < 8 * N {
            if matches!(f % 8, 2 | 4 | 5 | 7) {
                signs[f / N][f % N] = 0x8000_0000;
            }
            f += 1;
        }
        signs
    };
    let src = p.map(L::to_bits);
    let mut rows = [[0u32; N]; 8];
    for (r, (row, signs)) in rows.iter_mut().zip(signs).enumerate() {
        let turned = slices::permute::<L, N, 2, 8, { slices::FOUR_TURNS }>(&src, r);
        *row = L::to_words(turned ^ L::words(*signs));
    }
    bytemuck::cast(rows)
}

/// Inverse of [`polar4`]: returns `(u, quadrant)` with `quadrant` in `0..4`.
///
/// Round trip within 5e-7 for `u` in `[0, 1)^2` (measured 3.0e-7: the angle fraction is
/// scaled by 4), except at the centre `u0 = 0`, and at the quadrant seams, where `u1 -> 1` of
/// one quadrant and `u1 = 0` of the next are the same direction (compare modulo the seam).
#[inline]
pub fn polar4_inverse(p: [f32; 2]) -> ([f32; 2], u32) {
    let (u, q) = polar4_inverse_body(p);
    (u, q.0)
}

/// [`polar4_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn polar4_inverse_x8(p: [f32x8; 2]) -> ([f32x8; 2], u32x8) {
    polar4_inverse_body(p)
}

/// [`polar4_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn polar4_inverse_x16(p: [f32x16; 2]) -> ([f32x16; 2], u32x16) {
    polar4_inverse_body(p)
}

// ---------------------------------------------------------------------------------------
// Concentric4

/// The quarter turn `quadrant % 4` applied to `(x, y)`, exactly: a swap and sign flips
/// (`(x, y) -> (-y, x)` per quarter turn).
#[inline(always)]
fn quarter_turns<L: Lane>(x: L, y: L, quadrant: L::U) -> [L; 2] {
    let one = <L::U as UintLane>::splat(1);
    let odd = (quadrant & one).simd_eq(one);
    let (x, y) = (L::select(odd, y, x), L::select(odd, x, y));
    // Quadrants 1 and 2 negate the new x, quadrants 2 and 3 the new y.
    let neg_x = ((quadrant ^ quadrant.shr(1)) & one).shl(31);
    let neg_y = (quadrant.shr(1) & one).shl(31);
    [x.flip_sign(neg_x), y.flip_sign(neg_y)]
}

#[inline(always)]
fn concentric4_body<L: Lane>(u: [L; 2], quadrant: L::U) -> [L; 2] {
    let (a, b) = (unit_interval(u[0]), unit_interval(u[1]));
    // Shirley-Chiu on the quarter disk: a > b: r = a, phi = (pi/4)(b/a); else r = b,
    // phi = pi/2 - (pi/4)(a/b). t = minor / major in [0, 1]; 0 at the origin.
    let a_major = b.simd_lt(a);
    let r = L::select(a_major, a, b);
    let zero = L::splat(0.0);
    let t = L::select(r.simd_eq(zero), zero, L::select(a_major, b, a) / r);
    let r = clamp_radius(r);
    let (s, c) = sin_cos_pi4(t);
    // cos(pi/2 - x) = sin(x): the b-major wedge swaps sin and cos.
    let x = r * L::select(a_major, c, s);
    let y = r * L::select(a_major, s, c);
    quarter_turns(x, y, quadrant)
}

#[inline(always)]
fn concentric4_inverse_body<L: Lane>(p: [L; 2]) -> ([L; 2], L::U) {
    let (x, y) = (signed_unit(p[0]), signed_unit(p[1]));
    let zero = L::splat(0.0);
    let splat = <L::U as UintLane>::splat;
    // Quadrant q holds the quarter turn by q of {x > 0, y >= 0} (the origin counts as 0):
    // each axis belongs to the quadrant in which it is the u1 = 0 edge.
    let q = L::U::select(
        zero.simd_lt(y) & x.simd_le(zero),
        splat(1),
        L::U::select(
            y.simd_le(zero) & x.simd_lt(zero),
            splat(2),
            L::U::select(y.simd_lt(zero) & zero.simd_le(x), splat(3), splat(0)),
        ),
    );
    // Turn back into the first quadrant (three more quarter turns); the magnitudes are all
    // that is left to read, so the signs of zeros do not matter.
    let [x, y] = quarter_turns(x, y, q * splat(3));
    let (x, y) = (x.abs(), y.abs());
    let x_major = y.simd_lt(x);
    let r = (x * x + y * y).sqrt();
    let w = atan_ratio_pi4(L::select(x_major, y, x), L::select(x_major, x, y));
    let rw = r * w;
    (
        [
            unit_interval(L::select(x_major, r, rw)),
            unit_interval(L::select(x_major, rw, r)),
        ],
        q,
    )
}

/// Concentric4 (Christensen 2018): the Shirley-Chiu map of the unit square onto the quarter
/// disk of the first quadrant, turned by `quadrant` quarter turns; one 2D point gives four
/// disk samples, one per quadrant, like [`polar4`] but with compact strata.
///
/// `a = u0`, `b = u1`; if `a > b` then `r = a`, `phi = (pi/4)(b / a)`, else `r = b`,
/// `phi = pi/2 - (pi/4)(a / b)`; the point `(r cos phi, r sin phi)` is then turned by
/// `quadrant % 4` quarter turns counter-clockwise, exactly (a swap and sign flips:
/// `concentric4(u, q + 1)` is `concentric4(u, q)` turned by `(x, y) -> (-y, x)`, bit for bit).
/// The square's diagonal maps to the quadrant's bisector, its edges `u0 = 0` and `u1 = 0` to
/// the quadrant's two axes, and `u = (0, 0)` to the centre.
///
/// Area-preserving onto the quarter disk (`r dr dphi = (pi/4) da db`), so with `quadrant`
/// uniform over `0..4` the density is [`PDF`]. Error against `f64`: at most 1.5e-7 per
/// coordinate (the kernels of [`concentric`]); the domain guarantee and out-of-range rule of
/// the [module docs](self) apply, and every `quadrant` is valid (only `quadrant % 4` is used).
/// Used for sample `i` with point `i / 4` of a 2D sequence and `quadrant = i % 4`: see
/// [`concentric4_indexed`] and [`concentric4_slice`].
///
/// Christensen's memo ("Progressive Sampling Strategies for Disk Light Sources", Pixar TM
/// 18-02) measures it beside [`polar4`]. In the report (`docs/REPORT.md`, Owen-scrambled
/// pmj02bn, 256 samples per pixel) it ties the other warps within 10% in penumbrae but is 3x
/// worse than [`concentric`] and 11x worse than [`polar4`] in fully lit pixels: the
/// quarter-disk map has a derivative kink along the square's diagonal `u0 = u1`, which limits
/// the convergence on a smooth integrand (`N^-2.4` against polar4's `N^-3.0`). Prefer
/// [`polar4`].
#[inline]
pub fn concentric4(u: [f32; 2], quadrant: u32) -> [f32; 2] {
    concentric4_body(u, Wrapping(quadrant))
}

/// [`concentric4`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric4_x8(u: [f32x8; 2], quadrant: u32x8) -> [f32x8; 2] {
    concentric4_body(u, quadrant)
}

/// [`concentric4`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn concentric4_x16(u: [f32x16; 2], quadrant: u32x16) -> [f32x16; 2] {
    concentric4_body(u, quadrant)
}

/// Disk sample `index` of a concentric4 stream: `concentric4(point(index / 4), index % 4)`;
/// `point` is called once, with `index / 4`.
#[inline]
pub fn concentric4_indexed(index: u32, point: impl FnOnce(u32) -> [f32; 2]) -> [f32; 2] {
    concentric4(point(index >> 2), index & 3)
}

/// [`concentric4_indexed`] for eight sample indices at once (any indices, not only
/// consecutive).
#[inline]
pub fn concentric4_indexed_x8(
    index: u32x8,
    points: impl FnOnce(u32x8) -> [f32x8; 2],
) -> [f32x8; 2] {
    concentric4_x8(points(index >> 2), index & u32x8::splat(3))
}

/// [`concentric4_indexed`] for sixteen sample indices at once (any indices, not only
/// consecutive).
#[inline]
pub fn concentric4_indexed_x16(
    index: u32x16,
    points: impl FnOnce(u32x16) -> [f32x16; 2],
) -> [f32x16; 2] {
    concentric4_x16(points(index >> 2), index & u32x16::splat(3))
}

/// Expands 2D points into concentric4 disk samples, four per point: `out[i] =
/// concentric4(points[i / 4], i % 4)` for `i < min(out.len(), 4 * points.len())`; returns that
/// count. Bit-identical to the scalar form.
#[inline]
pub fn concentric4_slice(points: &[[f32; 2]], out: &mut [[f32; 2]]) -> usize {
    four_per_point(points, out, |u: [slices::Widest; 2]| {
        concentric4_body(u, UintLane::splat(0))
    })
}

/// Inverse of [`concentric4`]: returns `(u, quadrant)` with `quadrant` in `0..4`.
///
/// The quadrant is the quarter turn of `{x > 0, y >= 0}` holding `p` (the origin gives 0);
/// `p` is turned back into the first quadrant and inverted there like [`concentric_inverse`]
/// (`r = sqrt(x^2 + y^2)`, in-wedge coordinate `(4/pi) atan(minor / major)`). Round trip
/// within 5e-7 for `u` in `[0, 1)^2`, except on the singular sets: the centre (`u = (0, 0)`),
/// and the edge `u0 = 0`, which lies on the axis shared with the next quadrant and comes back
/// as that quadrant's `u1 = 0` edge (`(u1, 0)` and `quadrant + 1`). Any input is accepted,
/// under the module's inverse rule.
#[inline]
pub fn concentric4_inverse(p: [f32; 2]) -> ([f32; 2], u32) {
    let (u, q) = concentric4_inverse_body(p);
    (u, q.0)
}

/// [`concentric4_inverse`] on eight points at once; bit-identical to eight scalar calls.
#[inline]
pub fn concentric4_inverse_x8(p: [f32x8; 2]) -> ([f32x8; 2], u32x8) {
    concentric4_inverse_body(p)
}

/// [`concentric4_inverse`] on sixteen points at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn concentric4_inverse_x16(p: [f32x16; 2]) -> ([f32x16; 2], u32x16) {
    concentric4_inverse_body(p)
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;

    /// The quadrant slices' machinery at both widths (whatever `slices::Widest` this build
    /// has): each point warped once and turned by exact quarter turns equals the scalar
    /// quadrant warp bit for bit, for every point count up to 40 (so every tail), output
    /// lengths cut anywhere, and special inputs (signed zeros, NaN, infinities, subnormals).
    fn quadrant_slices<L: Vector<N>, const N: usize>() {
        let specials = [
            0.0,
            -0.0,
            0.5,
            1.0,
            f32::NAN,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::from_bits(1),
            0.999_999_94,
            0.25,
        ];
        let points: [[f32; 2]; 40] = core::array::from_fn(|i| {
            if i < 20 {
                [specials[i % 10], specials[(i * 3 + 1) % 10]]
            } else {
                [
                    (i as f32 * 0.618_034).fract(),
                    (i as f32 * 0.414_213_5).fract(),
                ]
            }
        });
        type Scalar = fn([f32; 2], u32) -> [f32; 2];
        let polar4_0 = |u: [L; 2]| polar4_body(u, UintLane::splat(0));
        let concentric4_0 = |u: [L; 2]| concentric4_body(u, UintLane::splat(0));
        for (name, scalar) in [("polar4", polar4 as Scalar), ("concentric4", concentric4)] {
            for p in 0..=points.len() {
                for m in [4 * p, 4 * p + 5, (4 * p).saturating_sub(3), 4 * p / 2 + 1] {
                    let mut out = vec![[9.0f32; 2]; m];
                    let n = if name == "polar4" {
                        four_per_point(&points[..p], &mut out, polar4_0)
                    } else {
                        four_per_point(&points[..p], &mut out, concentric4_0)
                    };
                    assert_eq!(n, m.min(4 * p), "{name} {N}: {p} points, {m} out");
                    for (i, o) in out.iter().enumerate() {
                        let want = if i < n {
                            scalar(points[i / 4], i as u32 % 4)
                        } else {
                            [9.0; 2]
                        };
                        assert_eq!(
                            o.map(f32::to_bits),
                            want.map(f32::to_bits),
                            "{name} {N}: {p} points, {m} out, sample {i}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn quadrant_slices_at_both_widths() {
        quadrant_slices::<f32x8, 8>();
        quadrant_slices::<f32x16, 16>();
    }
}
