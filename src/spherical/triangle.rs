//! Arvo's spherical-triangle map (1995) in cancellation-free form, its inverse and the
//! Van Oosterom-Strackee solid angle.

use crate::lanes::{Lane, unit_interval};
use crate::triangle::{uniform_body, uniform_inverse_body};
use crate::trig::{atan2_turns, sin_cos_turns};
use crate::vec3::*;

/// The triangle seen from `p`: vertex vectors `a[i] = 2^k (v_i - p)`, edges `e1 = v1 - v0`,
/// `e2 = v2 - v0`, `f2 = v2 - v1` (from the caller's vertices, so they carry no cancellation
/// against `p`), all scaled by the same exact power of two.
pub(super) struct Tri<L: Lane> {
    pub a: [V<L>; 3],
    pub e1: V<L>,
    pub e2: V<L>,
    pub f2: V<L>,
    pub len: [L; 3],
    /// `a0 . (e1 x e2)`: six times the signed volume of the tetrahedron `(p, v0, v1, v2)`.
    pub det: L,
    /// The solid angle in turns of `4 pi`, `[0, 1/2]`; 0 where `ok` is false.
    pub turns: L,
    /// Finite input, no vertex at `p`.
    pub ok: L::Mask,
}

#[inline(always)]
pub(super) fn setup<L: Lane>(v: [V<L>; 3], p: V<L>) -> Tri<L> {
    let a = [sub(v[0], p), sub(v[1], p), sub(v[2], p)];
    let a = a.map(flush_subnormal);
    let e1 = flush_subnormal(sub(v[1], v[0]));
    let e2 = flush_subnormal(sub(v[2], v[0]));
    let f2 = flush_subnormal(sub(v[2], v[1]));
    let (k, scaled) = pow2_scale(a);
    let a = [scale(a[0], k), scale(a[1], k), scale(a[2], k)];
    let (e1, e2, f2) = (scale(e1, k), scale(e2, k), scale(f2, k));
    let len = [norm(a[0]), norm(a[1]), norm(a[2])];
    let zero = L::splat(0.0);
    // Finite input without a finiteness test: an infinite `v_i - p` fails `scaled`, a NaN one
    // gives a NaN length, and the edges are finite where the `v_i - p` are below `2^127` (an
    // edge is then below `2^128 - 2^103`, which rounds to at most `f32::MAX`), NaN only where
    // some `v_i - p` is NaN or infinite.
    let ok = scaled & zero.simd_lt(len[0]) & zero.simd_lt(len[1]) & zero.simd_lt(len[2]);
    let det = dot(a[0], cross(e1, e2));
    let turns = half_angle_turns(a, len, det.abs());
    // Below the area-sampling threshold, a triple product below FLAT_DET counts as zero (the
    // light as seen edge-on, solid angle 0): it bounds the area density 2 |q|^3 / |det|
    // (|q| < 2 sqrt 3 in this frame) below 2^127.
    let flat = turns.simd_lt(L::splat(FALLBACK_TURNS)) & det.abs().simd_lt(L::splat(FLAT_DET));
    let det = L::select(flat, zero, det);
    let ok_turns = ok & !flat;
    Tri {
        a,
        e1,
        e2,
        f2,
        len,
        det,
        turns: L::select(ok_turns, turns, zero),
        ok,
    }
}

/// Below [`FALLBACK_TURNS`], lights whose triple product `a0 . (e1 x e2)` (in the scaled
/// frame, largest coordinate in `[1, 2)`) is below this count as seen edge-on: solid angle
/// and density 0.
pub(super) const FLAT_DET: f32 = 1.0 / (1u128 << 120) as f32;

/// Van Oosterom and Strackee (1983): `tan(omega / 2) = |det| / (|a||b||c| + (a.b)|c| +
/// (a.c)|b| + (b.c)|a|)`, returned as `omega / (4 pi)` through `atan2_turns`.
#[inline(always)]
pub(super) fn half_angle_turns<L: Lane>(a: [V<L>; 3], len: [L; 3], abs_det: L) -> L {
    let den = len[0] * len[1] * len[2]
        + dot(a[0], a[1]) * len[2]
        + dot(a[0], a[2]) * len[1]
        + dot(a[1], a[2]) * len[0];
    atan2_turns(abs_det, den)
}

/// Below this solid angle (`1e-8` sr, in turns of `4 pi`) the maps sample by area.
pub(super) const FALLBACK_TURNS: f32 = (1e-8 * 0.25 * core::f64::consts::FRAC_1_PI) as f32;

#[inline(always)]
pub(super) fn solid_angle_body<L: Lane>(v: [V<L>; 3], p: V<L>) -> L {
    setup(v, p).turns * L::splat(FOUR_PI)
}

/// Everything [`sample_body`] computes from the light and the shading point alone: built once
/// per slice call by the slice forms (the same operations as in the per-sample body, so the
/// same bits).
pub(super) struct Prepared<L: Lane> {
    pub t: Tri<L>,
    /// `|v0 - p|` (scaled as `t.a`).
    la: L,
    /// Chord `c^ - a^`, its squared length and length.
    d: V<L>,
    d2: L,
    dl: L,
    /// Chord `b^ - a^`.
    dab: V<L>,
    /// `1 + a.b`, `(a + b) . (c - a)`, `|a . (b x c)|`.
    one_ab: L,
    s: L,
    tt: L,
    /// `b^`.
    b: V<L>,
    /// `e1 x e2`, `e2 x a`, `a x e1`, `det / |v0 - p|`.
    n: V<L>,
    c1: V<L>,
    c2: V<L>,
    det_la: L,
    /// Arvo's map applies (else area sampling).
    arvo: L::Mask,
    /// The area fallback's density is defined (else 0).
    area_ok: L::Mask,
}

#[inline(always)]
pub(super) fn prepare<L: Lane>(v: [V<L>; 3], p: V<L>) -> Prepared<L> {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let half = L::splat(0.5);
    let t = setup(v, p);
    let [la, lb, lc] = t.len;
    let [va, vb, vc] = t.a;
    let (ia, ib, ic) = (one / la, one / lb, one / lc);
    // Chords c^ - a^ and b^ - a^ from the edges ([`chord`] with the shared `1 / |y|`).
    let d = chord_k(va, t.e2, dot(t.e2, add(va, vc)) / ((la + lc) * la), ic);
    let dab = chord_k(va, t.e1, dot(t.e1, add(va, vb)) / ((la + lb) * la), ib);
    let d2 = dot(d, d);
    let one_ab = L::splat(2.0) - dot(dab, dab) * half; // 1 + a.b
    let s = dot(dab, d) - d2; // (a + b) . (c - a)
    // |a^ . (b^ x c^)|: each partial product is bounded (|det| / la <= |e1| |e2|, ...).
    let tt = t.det.abs() * ia * ib * ic;
    let dl = d2.sqrt();
    let b = add(scale(va, ia), dab); // b^, only in terms of second order below
    let n = cross(t.e1, t.e2);
    let c1 = cross(t.e2, va);
    let c2 = cross(va, t.e1);
    let det_la = t.det * ia;
    let area_ok = t.ok & zero.simd_lt(t.det.abs());
    let arvo = area_ok & L::splat(FALLBACK_TURNS).simd_le(t.turns);
    Prepared {
        t,
        la,
        d,
        d2,
        dl,
        dab,
        one_ab,
        s,
        tt,
        b,
        n,
        c1,
        c2,
        det_la,
        arvo,
        area_ok,
    }
}

#[inline(always)]
pub(super) fn sample_body<L: Lane>(v: [V<L>; 3], p: V<L>, u: [L; 2]) -> ([L; 3], L) {
    sample_prepared(&prepare(v, p), u)
}

#[inline(always)]
pub(super) fn sample_prepared<L: Lane>(pr: &Prepared<L>, u: [L; 2]) -> ([L; 3], L) {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let half = L::splat(0.5);
    let (u0, u1) = (unit_interval(u[0]), unit_interval(u[1]));
    let t = &pr.t;
    let (la, va, d, d2, dl, dab) = (pr.la, t.a[0], pr.d, pr.d2, pr.dl, pr.dab);
    // Step 1: the point x = a + tau (c^ - a^) on the chord with area(a, b, x^) = u0 omega.
    // With h = u0 omega / 2, Van Oosterom-Strackee for (a, b, x^) reads
    //   tau tt cos h = sin h ((1 + a.b)(|x| + 1) + tau s),  |x|^2 = 1 - tau (1 - tau) d2,
    // whose nonzero root is tau = q (2 pp - q d2) / ((pp - q d)(pp + q d)) with
    // pp = tt cos h - s sin h and q = (1 + a.b) sin h: no acos, no 1 - cos.
    let (sh, ch) = sin_cos_turns(u0 * t.turns);
    let pp = pr.tt * ch - pr.s * sh;
    let q = pr.one_ab * sh;
    let tau = clamp0(
        q * (pp + pp - q * d2) / ((pp - q * dl) * (pp + q * dl)),
        one,
    );
    // Every direction below is an offset from a^ (the direction of v0 - p), built from the
    // chords and edges: the vertex vectors v1 - p and v2 - p are rounded independently of
    // the edges, and mixing them in would cost ulp(1) / (angular size) of precision.
    let e = scale(d, tau * la);
    let xv = add(va, e);
    let lx = norm(xv);
    let ox = chord(va, xv, e, la, lx); // x^ - a^
    // Step 2: along the arc from b^ to x^, 1 - cos(angle from b) = u1 (1 - b . x^), i.e. the
    // chord from b^ is sqrt(u1) times the chord g = x^ - b^.
    let g = sub(ox, dab);
    let g2 = dot(g, g);
    let b = pr.b;
    let wv = add(g, scale(b, g2 * half));
    let wl2 = dot(wv, wv);
    let l2 = u1 * g2;
    // The chord l = sqrt(l2) from b^ has sine sin_l = l sqrt(1 - l2 / 4) along the unit
    // w = wv / |wv|: sin_l / |wv| = sqrt(u1 (1 - l2 / 4) (g2 / |wv|^2)), one root.
    let sw = (u1 * clamp0(one - l2 * L::splat(0.25), one) * (g2 / wl2)).sqrt();
    let sw = L::select(zero.simd_lt(wl2), sw, zero);
    // op = (the point's direction) - a^.
    let op = add(dab, add(scale(b, -(l2 * half)), scale(wv, sw)));
    // Barycentrics of the ray's hit: lambda_i = det with the direction in slot i, from a^
    // and the edges only (det(a^, b, c) = det / |v0 - p| and so on).
    let l1 = dot(op, pr.c1);
    let l2b = dot(op, pr.c2);
    let sum = pr.det_la + dot(op, pr.n);
    let l0 = sum - l1 - l2b;
    let sign = sum.sign_bit();
    let pos = |x: L| {
        let x = x.flip_sign(sign);
        L::select(zero.simd_lt(x), x, zero)
    };
    let (l0, l1, l2b) = (pos(l0), pos(l1), pos(l2b));
    let tot = l0 + l1 + l2b;
    // The numerators are homogeneous in the light's triple product: for a light seen nearly
    // edge-on their sum can be subnormal (its reciprocal overflows). Lift them by an exact
    // 2^64 there (a no-op elsewhere, so no bits change where 1 / tot was finite).
    let lift = L::select(
        tot.simd_lt(L::splat(LIFT_BELOW)),
        L::splat(1.0 / LIFT_BELOW),
        one,
    );
    let (l0, l1, l2b, tot) = (l0 * lift, l1 * lift, l2b * lift, tot * lift);
    let arvo = pr.arvo & positive_finite(tot);
    let inv = one / tot;
    let bary = [
        clamp0(l0 * inv, one),
        clamp0(l1 * inv, one),
        clamp0(l2b * inv, one),
    ];
    let pdf = L::splat(INV_4PI) / t.turns;
    // The area fallback only where some lane takes it (the scalar form skips it otherwise).
    L::unless(arvo, (bary, pdf), || {
        // Area sampling: the low-distortion map, density |q|^2 / (cos area) = 2 |q|^3 / |det|.
        let fb = uniform_body([u0, u1]);
        let qv = add(va, add(scale(t.e1, fb[1]), scale(t.e2, fb[2])));
        let ql = norm(qv);
        let area_pdf = L::select(
            ql.simd_lt(L::splat(SMALL_Q)),
            // |q|^3 would lose bits to underflow: the same quotient in another order.
            ql * ((ql + ql) * (ql / t.det.abs())),
            (ql * ql * ql + ql * ql * ql) / t.det.abs(),
        );
        let area_pdf = area_density(pr.area_ok, area_pdf);
        // The density is the light's (Arvo's map or area sampling), not the sample's: where a
        // direction's numerators are all <= 0 (it left the spherical triangle by rounding),
        // the point is the area map's but the density stays 1 / omega.
        (
            [
                L::select(arvo, bary[0], fb[0]),
                L::select(arvo, bary[1], fb[1]),
                L::select(arvo, bary[2], fb[2]),
            ],
            L::select(pr.arvo, pdf, area_pdf),
        )
    })
}

/// Barycentric numerators summing below this are lifted by its inverse (exact).
const LIFT_BELOW: f32 = 1.0 / (1u128 << 64) as f32;
/// Below this `|q|` the area density is computed as `|q| (2 |q| (|q| / det))` (no underflow).
pub(super) const SMALL_Q: f32 = 1.0 / (1u64 << 40) as f32;

#[inline(always)]
pub(super) fn inverse_body<L: Lane>(v: [V<L>; 3], p: V<L>, bary: [L; 3]) -> [L; 2] {
    inverse_prepared(&setup(v, p), bary)
}

/// [`inverse_body`] with the light's setup done (once per slice call by the slice form).
#[inline(always)]
pub(super) fn inverse_prepared<L: Lane>(t: &Tri<L>, bary: [L; 3]) -> [L; 2] {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let third = L::splat(1.0 / 3.0);
    let b = [
        clamp0(bary[0], one),
        clamp0(bary[1], one),
        clamp0(bary[2], one),
    ];
    let sb = b[0] + b[1] + b[2];
    let has = zero.simd_lt(sb);
    let inv = one / sb;
    let b = [
        L::select(has, b[0] * inv, third),
        L::select(has, b[1] * inv, third),
        L::select(has, b[2] * inv, third),
    ];
    let [la, lb, _] = t.len;
    let [va, vb, _] = t.a;
    // The great circle through b^ and the point meets the arc a^c^ where the plane's line
    // from v1 through the point meets the edge v0 v2: at a + mu (c - a), mu = b2 / (b0 + b2).
    let s02 = b[0] + b[2];
    let mu = L::select(zero.simd_lt(s02), b[2] / s02, zero);
    let cm = add(va, scale(t.e2, mu));
    let lcm = norm(cm);
    let sub_turns = half_angle_turns([va, vb, cm], [la, lb, lcm], mu * t.det.abs());
    let u0 = sub_turns / t.turns;
    // u1 = (1 - cos(b, point)) / (1 - cos(b, c')): a ratio of squared chords.
    let ep = sub(scale(t.f2, b[2]), scale(t.e1, b[0])); // point - v1
    let pv = add(vb, ep);
    let lp = norm(pv);
    let cp = chord(vb, pv, ep, lb, lp);
    let cc = chord(vb, cm, sub(scale(t.e2, mu), t.e1), lb, lcm);
    let cc2 = dot(cc, cc);
    let u1 = L::select(zero.simd_lt(cc2), dot(cp, cp) / cc2, zero);
    let arvo = t.ok & zero.simd_lt(t.det.abs()) & L::splat(FALLBACK_TURNS).simd_le(t.turns);
    let fb = uniform_inverse_body(b);
    [
        L::select(arvo, unit_interval(u0), fb[0]),
        L::select(arvo, unit_interval(u1), fb[1]),
    ]
}
