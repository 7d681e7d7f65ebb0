//! Urena, Fajardo and King's spherical-rectangle map (2013) in cancellation-free form: a
//! closed-form start refined by Newton steps on an accurate residual, its inverse, and the
//! solid angle as two Van Oosterom-Strackee triangles joined in one `atan2`.

use super::triangle::{FALLBACK_TURNS, SMALL_Q};
use crate::lanes::{Lane, unit_interval};
use crate::trig::{atan2_turns, sin_cos_turns};
use crate::vec3::*;

/// The rectangle in its own frame seen from `p` (all lengths scaled by one exact power of
/// two): `x` along `ex` from `x0` to `x0 + w`, `y` along `ey`'s component orthogonal to `ex`
/// from `y0` to `y0 + h`, and `p` at height `z` above its plane.
pub(super) struct Rect<L: Lane> {
    pub x0: L,
    pub w: L,
    pub y0: L,
    pub h: L,
    pub z: L,
    /// Solid angle in turns of `4 pi`, `[0, 1/2]`; 0 where `ok` is false.
    pub turns: L,
    /// `1 / w`, `1 / h`.
    pub iw: L,
    pub ih: L,
    /// The distances from `p` to the corners `(x0, y0)`, `(x1, y0)`, `(x1, y1)`, `(x0, y1)`
    /// (with the height before the edge-on rule; only used where that rule does not apply).
    pub radii: [L; 4],
    /// Finite input, nonzero sides.
    pub ok: L::Mask,
    /// `corner - p`, `ex` and `ey`'s component orthogonal to `ex`, scaled as the lengths:
    /// the light's corners for the cosine-aware variant.
    pub c: V<L>,
    pub ex: V<L>,
    pub eyp: V<L>,
}

#[inline(always)]
pub(super) fn setup<L: Lane>(corner: V<L>, ex: V<L>, ey: V<L>, p: V<L>) -> Rect<L> {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let c = flush_subnormal(sub(corner, p));
    let (ex, ey) = (flush_subnormal(ex), flush_subnormal(ey));
    // Only `corner - p` needs a finiteness test: infinite `ex` or `ey` fail `scaled`, NaN ones
    // give a NaN `w` or `h`.
    let finite = all_finite([c]);
    let (k, scaled) = pow2_scale([c, ex, ey]);
    let (c, ex, ey) = (scale(c, k), scale(ex, k), scale(ey, k));
    let w = norm(ex);
    let iw = one / w;
    let xh = scale(ex, iw);
    let eyp = sub(ey, scale(xh, dot(ey, xh)));
    let h = norm(eyp);
    let ih = one / h;
    let yh = scale(eyp, ih);
    let nh = cross(xh, yh);
    let x0 = dot(c, xh);
    let y0 = dot(c, yh);
    let z = dot(c, nh).abs();
    let ok = finite & scaled & zero.simd_lt(w) & zero.simd_lt(h);
    let radii = corner_radii(x0, w, y0, h, z * z);
    let turns = quad_turns_r(x0, w, y0, h, z, radii);
    // Below the area-sampling threshold, z w h below FLAT_ZWH counts as zero (the light seen
    // edge-on, solid angle 0): it bounds the area density |q|^3 / (z w h) (|q| < 6 sqrt 3
    // in this frame) below 2^127.
    let flat = turns.simd_lt(L::splat(FALLBACK_TURNS)) & (z * w * h).simd_lt(L::splat(FLAT_ZWH));
    let z = L::select(flat, zero, z);
    Rect {
        x0,
        w,
        y0,
        h,
        z,
        turns: L::select(ok & !flat, turns, zero),
        iw,
        ih,
        radii,
        ok,
        c,
        ex,
        eyp,
    }
}

/// Below [`FALLBACK_TURNS`], rectangles whose `z w h` (in the scaled frame, largest
/// coordinate of `corner - p`, `ex`, `ey` in `[1, 2)`) is below this count as seen edge-on:
/// solid angle and density 0.
pub(super) const FLAT_ZWH: f32 = 1.0 / (1u128 << 116) as f32;

/// Solid angle (turns of `4 pi`) of `[x0, x0 + dx] x [y0, y0 + dy]` at height `z`: the
/// triangles `(00, 10, 11)` and `(00, 11, 01)` by Van Oosterom-Strackee (both have
/// `|det| = z dx dy`), their half angles added as the argument of a product of complex
/// numbers, so one `atan2`.
#[inline(always)]
pub(super) fn quad_turns<L: Lane>(x0: L, dx: L, y0: L, dy: L, z: L) -> L {
    quad_turns_r(x0, dx, y0, dy, z, corner_radii(x0, dx, y0, dy, z * z))
}

/// `|(x, y, z)|` at the corners `(x0, y0)`, `(x1, y0)`, `(x1, y1)`, `(x0, y1)` of
/// `[x0, x0 + dx] x [y0, y0 + dy]`.
#[inline(always)]
fn corner_radii<L: Lane>(x0: L, dx: L, y0: L, dy: L, z2: L) -> [L; 4] {
    let (x1, y1) = (x0 + dx, y0 + dy);
    let r = |x: L, y: L| (x * x + y * y + z2).sqrt();
    [r(x0, y0), r(x1, y0), r(x1, y1), r(x0, y1)]
}

/// [`quad_turns`] given the [`corner_radii`] (shared with the map's set-up and Newton step).
///
/// Where `p`'s foot lies inside the rectangle's extent along a side and both ends along it
/// are far beyond `p`'s distance from the line of the nearer other side (`-x0 x1 >`
/// [`SPLIT_ABOVE`] `(y_near^2 + z^2)`: a long light seen from beside its middle), two
/// corners are seen nearly opposite and Van Oosterom-Strackee's denominators cancel (a
/// `1 x 10^6` light at `kappa = 84` lost 4e-4 of its solid angle). There the rectangle is
/// cut at the foot into two or four pieces, each on one side of it in both directions, whose
/// denominators are sums of positive terms, and their solid angles are added. Elsewhere (and
/// where `z^2` underflows) the one pair of triangles.
#[inline(always)]
fn quad_turns_r<L: Lane>(x0: L, dx: L, y0: L, dy: L, z: L, radii: [L; 4]) -> L {
    let whole = vos_quad_turns(x0, dx, y0, dy, z, radii);
    let zero = L::splat(0.0);
    let (x1, y1) = (x0 + dx, y0 + dy);
    let z2 = z * z;
    let (sx, sy) = (
        x0.simd_lt(zero) & zero.simd_lt(x1),
        y0.simd_lt(zero) & zero.simd_lt(y1),
    );
    // The squared distance to the nearer of two parallel sides, 0 between them.
    let near2 = |a: L, b: L, inside: L::Mask| {
        let (a, b) = (a.abs(), b.abs());
        let m = L::select(a.simd_lt(b), a, b);
        L::select(inside, zero, m * m)
    };
    let t = L::splat(SPLIT_ABOVE);
    let cut_x = sx & (t * (near2(y0, y1, sy) + z2)).simd_lt(-(x0 * x1));
    let cut_y = sy & (t * (near2(x0, x1, sx) + z2)).simd_lt(-(y0 * y1));
    // Not where z^2 is below the smallest normal f32 (`z < 2^-63` in the scaled frame, `p`
    // on the plane to f32's resolution): the pieces' corner at the foot would have radius 0.
    let cut = (cut_x | cut_y) & L::splat(f32::MIN_POSITIVE).simd_le(z2);
    L::unless(!cut, whole, || {
        L::select(cut, cut_turns(x0, dx, y0, dy, z, [cut_x, cut_y]), whole)
    })
}

/// [`quad_turns_r`]'s pieces: `[x0, 0]` and `[0, x1]` where cut in `x` (else `[x0, x1]`),
/// likewise in `y`, their solid angles added. Out of line: the rare path, one copy for the
/// set-up, the Newton step and the inverse.
#[cold]
#[inline(never)]
fn cut_turns<L: Lane>(x0: L, dx: L, y0: L, dy: L, z: L, [cut_x, cut_y]: [L::Mask; 2]) -> L {
    let zero = L::splat(0.0);
    let (x1, y1, z2) = (x0 + dx, y0 + dy, z * z);
    let wa = L::select(cut_x, -x0, dx);
    let ha = L::select(cut_y, -y0, dy);
    let piece =
        |xa: L, w: L, ya: L, h: L| vos_quad_turns(xa, w, ya, h, z, corner_radii(xa, w, ya, h, z2));
    let all = zero.simd_eq(zero);
    // A loop, not four inlined copies of the pieces (the wide forms' code size); `0 + t` is
    // `t` for the first piece's turns (never `-0.0`).
    let mut turns = zero;
    for (xa, w, ya, h, taken) in [
        (x0, wa, y0, ha, all),
        (zero, x1, y0, ha, cut_x),
        (x0, wa, zero, y1, cut_y),
        (zero, x1, zero, y1, cut_x & cut_y),
    ] {
        turns = turns + L::select(taken, piece(xa, w, ya, h), zero);
    }
    // Each piece is at most half a turn, but four pieces of nearly a quarter hemisphere
    // each (`p` a hair above the light, inside it) can round past it: the sum is held at
    // `1/2` (`2 pi`), the largest solid angle a plane light subtends.
    clamp0(turns, L::splat(0.5))
}

/// Where [`quad_turns_r`] cuts the rectangle at `p`'s foot: `-x0 x1` above this many times
/// `y_near^2 + z^2`. Below it the one pair of triangles errs at most about `1e-6 kappa`
/// (measured over 2.4 million random rectangles with sides up to `10^6 : 1`); where `-x0 x1`
/// was `2^21` times `y_near^2 + z^2` it erred `2.8e-5 kappa`.
const SPLIT_ABOVE: f32 = 32.0;

/// The solid angle (turns of `4 pi`) of the rectangle as the two triangles `(00, 10, 11)`
/// and `(00, 11, 01)`, given the [`corner_radii`].
#[inline(always)]
fn vos_quad_turns<L: Lane>(x0: L, dx: L, y0: L, dy: L, z: L, radii: [L; 4]) -> L {
    let x1 = x0 + dx;
    let y1 = y0 + dy;
    let z2 = z * z;
    let [r00, r10, r11, r01] = radii;
    let d = |xa: L, ya: L, xb: L, yb: L| xa * xb + ya * yb + z2;
    let d00_10 = d(x0, y0, x1, y0);
    let d00_11 = d(x0, y0, x1, y1);
    let d10_11 = d(x1, y0, x1, y1);
    let d00_01 = d(x0, y0, x0, y1);
    let d11_01 = d(x1, y1, x0, y1);
    let den1 = r00 * r10 * r11 + d00_10 * r11 + d00_11 * r10 + d10_11 * r00;
    let den2 = r00 * r11 * r01 + d00_11 * r01 + d00_01 * r11 + d11_01 * r00;
    let n = z * dx * dy;
    // The product (den1 + i n)(den2 + i n) is of degree 6 in the lengths: lift both factors
    // by one exact power of two so that it cannot underflow (long or far rectangles lost
    // their half-infinite part there); elsewhere the lift changes no bits.
    let s = pow2_lift([den1, den2, n]);
    let (den1, den2, n) = (den1 * s, den2 * s, n * s);
    let y = n * (den1 + den2);
    let zero = L::splat(0.0);
    atan2_turns(L::select(zero.simd_lt(y), y, zero), den1 * den2 - n * n)
}

/// `b / sqrt(d2 + b^2) - a / sqrt(d2 + a^2)` given `ba = b - a` accurately: for `a`, `b` of
/// one sign as `d2 (b - a)(b + a) / ((b ra + a rb) ra rb)`, else directly (no cancellation).
#[inline(always)]
fn h_diff<L: Lane>(a: L, ba: L, d2: L) -> L {
    let b = a + ba;
    let ra = (d2 + a * a).sqrt();
    let rb = (d2 + b * b).sqrt();
    let zero = L::splat(0.0);
    let same = zero.simd_lt(a * b);
    let num = L::select(same, d2 * ba * (b + a) / (b * ra + a * rb), b * ra - a * rb);
    num / (ra * rb)
}

/// `(1 - y / r, 1 + y / r)` from `small = 1 - |y| / r` and `big = 1 + |y| / r`.
#[inline(always)]
fn minus_plus<L: Lane>(y: L, small: L, big: L) -> (L, L) {
    let pos = L::splat(0.0).simd_lt(y);
    (L::select(pos, small, big), L::select(pos, big, small))
}

#[inline(always)]
pub(super) fn solid_angle_body<L: Lane>(corner: V<L>, ex: V<L>, ey: V<L>, p: V<L>) -> L {
    setup(corner, ex, ey, p).turns * L::splat(FOUR_PI)
}

/// Lights of `1e-2 .. 2` sr (in turns of `4 pi` here) whose farthest corner is within `16 z`
/// (`kappa <= 16`) and whose sides are within a factor 16 take the closed form as the point
/// (a fast path: the scalar form branches, the wide forms select per lane). Its round-trip
/// error grows like `1 / omega` (measured 5.8e-5 at `1e-4` sr, 7.0e-6 from `1e-2` sr up,
/// 400 000 random lights; thinner lights reached 7.5e-5, 6.9e-6 with the step); elsewhere
/// one Newton step on the strip's solid angle (accurate relative to the strip, not to the
/// light's neighbours) brings it to 4.8e-7 below `1e-2` sr. `tests/spherical.rs` measures the whole
/// round trip at `kappa <= 100`: 6.44e-6 (5.30e-6 with the step everywhere).
const NEWTON_FROM_TURNS: f32 = (1e-2 * 0.25 * core::f64::consts::FRAC_1_PI) as f32;
const NEWTON_UP_TO_TURNS: f32 = (2.0 * 0.25 * core::f64::consts::FRAC_1_PI) as f32;

/// Everything [`sample_body`] computes from the light and the shading point alone: built once
/// per slice call by the slice forms (the same operations as in the per-sample body, so the
/// same bits).
pub(super) struct Prepared<L: Lane> {
    pub r: Rect<L>,
    y1: L,
    z2: L,
    /// The half-infinite strips beyond `x0` and `x1`, in turns of `4 pi`.
    left: L,
    right: L,
    /// `cos beta0 cos beta1`.
    b01: L,
    /// Urena's map applies (else area sampling).
    exact: L::Mask,
    /// The closed-form start is the point (no Newton step).
    closed: L::Mask,
    /// The area fallback's density is defined (else 0).
    area_ok: L::Mask,
}

#[inline(always)]
pub(super) fn prepare<L: Lane>(corner: V<L>, ex: V<L>, ey: V<L>, p: V<L>) -> Prepared<L> {
    let zero = L::splat(0.0);
    let r = setup(corner, ex, ey, p);
    let (x0, w, y0, h, z) = (r.x0, r.w, r.y0, r.h, r.z);
    let y1 = y0 + h;
    let z2 = z * z;
    // Closed form (Urena et al.'s step, rewritten): with psi the angle of x seen in the
    // xz-plane, beta_j that of y_j in the yz-plane, and db = beta1 - beta0, the strip from
    // psi = -pi/2 to psi subtends G(psi) + db. Let A_l and A_r be what the solution leaves
    // on each side (A_l + A_r = 2 db, both sums of positive terms: the half-infinite strips
    // beyond x0 and x1, Van Oosterom-Strackee triangles with a vertex at -+x, plus u0 omega
    // or (1 - u0) omega). With g = (A_l - A_r) / 2, b_j = cos beta_j and
    // cos g - cos db = 2 sin(A_l / 2) sin(A_r / 2) = k:
    //   tan psi = sin g / sqrt(k (k + 2 b0 b1)),
    // with no cancellation where Urena's `1 - cu^2` and `k + u0 S` lose it (grazing views,
    // small lights). Angles are in turns of 4 pi (half angles in turns of 2 pi).
    // The corners' distances from the set-up (where the edge-on rule zeroed `z` they differ,
    // but the map's result is not used there).
    let [r00, r10, r11, r01] = r.radii;
    let x1 = x0 + w;
    let zh = z * h;
    let yy = y0 * y1 + z2;
    let (qa, qb) = (y0 * y0 + z2, y1 * y1 + z2);
    // At most one side is beyond p's foot (x0 > 0 or x1 < 0): one pair of divisions serves
    // whichever it is.
    let (far_l, far_r) = (zero.simd_lt(x0), x1.simd_lt(zero));
    let xf = L::select(far_l, x0, -x1);
    let far = [
        qa / (L::select(far_l, r00, r10) + xf),
        qb / (L::select(far_l, r01, r11) + xf),
    ];
    let left = half_strip(zh, yy, far_l, far, [r00 - x0, r01 - x0]);
    let right = half_strip(zh, yy, far_r, far, [r10 + x1, r11 + x1]);
    let b01 = z2 / (qa.sqrt() * qb.sqrt());
    let area_ok = r.ok & zero.simd_lt(z);
    let exact = area_ok & L::splat(FALLBACK_TURNS).simd_le(r.turns);
    // The farthest corner within 16 z (seen within about 86 degrees of the normal), and the
    // sides within a factor 16 (thinner lights lose a factor 10 in the round trip).
    let [ra, rb, rc, rd] = r.radii;
    let max = |a: L, b: L| L::select(a.simd_lt(b), b, a);
    let farthest = max(max(ra, rb), max(rc, rd));
    let sixteen = L::splat(16.0);
    let closed = L::splat(NEWTON_FROM_TURNS).simd_le(r.turns)
        & r.turns.simd_le(L::splat(NEWTON_UP_TO_TURNS))
        & farthest.simd_le(z * sixteen)
        & w.simd_le(h * sixteen)
        & h.simd_le(w * sixteen);
    Prepared {
        r,
        y1,
        z2,
        left,
        right,
        b01,
        exact,
        closed,
        area_ok,
    }
}

/// The solid angle (turns of `4 pi`) of the half-infinite strip beyond one side of the
/// light, `y0 < y' < y1` at height `z`, given `zh = z h`, `yy = y0 y1 + z^2` and the two
/// factors `ra - x`, `rb - x` of Van Oosterom-Strackee's half angle `atan2(z h, (ra - x)(rb -
/// x) + yy)` (`x` the side's distance from `p`'s foot, outwards; `ra`, `rb` its corners'
/// distances): as they are where `x <= 0`, else from the `far` forms `(y^2 + z^2) / (r + x)`
/// (no cancellation on either side of the light).
#[inline(always)]
fn half_strip<L: Lane>(zh: L, yy: L, far: L::Mask, [fa, fb]: [L; 2], [na, nb]: [L; 2]) -> L {
    atan2_turns(zh, L::select(far, fa, na) * L::select(far, fb, nb) + yy)
}

#[inline(always)]
pub(super) fn sample_body<L: Lane>(
    corner: V<L>,
    ex: V<L>,
    ey: V<L>,
    p: V<L>,
    u: [L; 2],
) -> ([L; 2], L) {
    sample_prepared(&prepare(corner, ex, ey, p), u)
}

#[inline(always)]
pub(super) fn sample_prepared<L: Lane>(pr: &Prepared<L>, u: [L; 2]) -> ([L; 2], L) {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let (u0, u1) = (unit_interval(u[0]), unit_interval(u[1]));
    let r = &pr.r;
    let (x0, w, y0, h, z) = (r.x0, r.w, r.y0, r.h, r.z);
    let (y1, z2, b01) = (pr.y1, pr.z2, pr.b01);
    let target = u0 * r.turns;
    // Sums of positive terms (the strips are accurate on either side of the light).
    let tl = pr.left + target;
    let tr = pr.right + (r.turns - target);
    let (sa, ca) = sin_cos_turns(clamp0(tl, L::splat(0.5)));
    let (sb, cb) = sin_cos_turns(clamp0(tr, L::splat(0.5)));
    let sg = sa * cb - ca * sb;
    let k = (sa + sa) * sb;
    let xu = z * sg / (k * (k + b01 + b01)).sqrt();
    let dx0 = clamp0(xu - x0, w);
    let dx = L::unless(pr.closed, dx0, || {
        L::select(pr.closed, dx0, newton_step(r, y1, z2, target, dx0))
    });
    // The height: uniform in y / sqrt(d^2 + y^2) between its values at y0 and y1.
    let x = x0 + dx;
    let d2 = x * x + z2;
    let r0 = (d2 + y0 * y0).sqrt();
    let r1 = (d2 + y1 * y1).sqrt();
    // 1 / r0 and 1 / r1 from one division (r0 r1 >= d2 >= z^2).
    let ir = one / (r0 * r1);
    let (i0, i1) = (r1 * ir, r0 * ir);
    let (h0, h1) = (y0 * i0, y1 * i1);
    // 1 -+ h_j without cancellation: the larger is 1 + |h_j| (in [1, 2]), the smaller
    // (d / r_j)^2 over it; both smaller ones from one more division.
    let (big0, big1) = (one + h0.abs(), one + h1.abs());
    let rb = one / (big0 * big1);
    let small0 = d2 * i0 * i0 * (big1 * rb);
    let small1 = d2 * i1 * i1 * (big0 * rb);
    let (m0, p0) = minus_plus(y0, small0, big0);
    let (m1, p1) = minus_plus(y1, small1, big1);
    let v1 = one - u1;
    // h1 - h0, for y0, y1 of one sign as d2 h (y0 + y1) / ((y1 r0 + y0 r1) r0 r1).
    let same = zero.simd_lt(y0 * y1);
    let hd = L::select(
        same,
        d2 * h * (y1 + y0) * (i0 * i1) / (y1 * r0 + y0 * r1),
        h1 - h0,
    );
    let dh = u1 * hd;
    let hv = h0 + dh;
    let om = v1 * m0 + u1 * m1; // 1 - hv
    let op = v1 * p0 + u1 * p1; // 1 + hv
    // With h = sin phi, y = d tan phi: y - y0 = d sin(phi - phi0) / (cos phi cos phi0) and
    // sin(phi - phi0) = dh (1 + cos(phi - phi0)) / (cos phi0 + cos phi): no cancellation.
    let dd = d2.sqrt();
    let c0 = dd * i0;
    let cv = (om * op).sqrt();
    let dy = dd * dh * (one + c0 * cv + h0 * hv) / ((c0 + cv) * cv * c0);
    let s = clamp0(dx * r.iw, one);
    let t = clamp0(dy * r.ih, one);
    let exact = pr.exact;
    let pdf = L::splat(INV_4PI) / r.turns;
    // The area fallback only where some lane takes it (the scalar form skips it otherwise).
    L::unless(exact, ([s, t], pdf), || {
        // Area sampling: density |q|^3 / (z w h).
        let qx = x0 + u0 * w;
        let qy = y0 + u1 * h;
        let ql = (qx * qx + qy * qy + z2).sqrt();
        let zwh = z * w * h;
        let area_pdf = L::select(
            ql.simd_lt(L::splat(SMALL_Q)),
            // |q|^3 would lose bits to underflow: the same quotient in another order.
            ql * (ql * (ql / zwh)),
            ql * ql * ql / zwh,
        );
        let area_pdf = area_density(pr.area_ok, area_pdf);
        (
            [L::select(exact, s, u0), L::select(exact, t, u1)],
            L::select(exact, pdf, area_pdf),
        )
    })
}

/// One Newton step on `quad_turns(x0, dx, ..) = target` from `dx`.
#[inline(always)]
fn newton_step<L: Lane>(r: &Rect<L>, y1: L, z2: L, target: L, dx: L) -> L {
    let zero = L::splat(0.0);
    let (x0, w, y0, h, z) = (r.x0, r.w, r.y0, r.h, r.z);
    let [r00, _, _, r01] = r.radii;
    let x = x0 + dx;
    let radii = [
        r00,
        (x * x + y0 * y0 + z2).sqrt(),
        (x * x + y1 * y1 + z2).sqrt(),
        r01,
    ];
    let res = quad_turns_r(x0, dx, y0, h, z, radii) - target;
    let d2 = x * x + z2;
    // d(turns)/dx = z (y1 / r1 - y0 / r0) / (4 pi d2) with d2 = x^2 + z^2, r_j the
    // distances to (x, y_j); for y0, y1 of one sign y1 / r1 - y0 / r0 = d2 h (y0 + y1) /
    // ((y1 r0 + y0 r1) r0 r1) (no cancellation), so the step res / slope is one quotient.
    let (ra, rb) = (radii[1], radii[2]);
    let same = zero.simd_lt(y0 * y1);
    let d = L::select(same, (y1 * ra + y0 * rb).abs(), d2);
    let num = res * (L::splat(FOUR_PI) * (ra * rb)) * d;
    let den = z * L::select(same, h * (y0 + y1).abs(), y1 * ra - y0 * rb);
    let step = L::select(positive_finite(den), num / den, zero);
    clamp0(dx - step, w)
}

#[inline(always)]
pub(super) fn inverse_body<L: Lane>(
    corner: V<L>,
    ex: V<L>,
    ey: V<L>,
    p: V<L>,
    st: [L; 2],
) -> [L; 2] {
    inverse_prepared(&setup(corner, ex, ey, p), st)
}

/// [`inverse_body`] with the light's setup done (once per slice call by the slice form).
#[inline(always)]
pub(super) fn inverse_prepared<L: Lane>(r: &Rect<L>, st: [L; 2]) -> [L; 2] {
    let one = L::splat(1.0);
    let zero = L::splat(0.0);
    let (s, t) = (clamp0(st[0], one), clamp0(st[1], one));
    let dx = s * r.w;
    let u0 = quad_turns(r.x0, dx, r.y0, r.h, r.z) / r.turns;
    let x = r.x0 + dx;
    let d2 = x * x + r.z * r.z;
    let full = h_diff(r.y0, r.h, d2);
    let part = h_diff(r.y0, t * r.h, d2);
    let u1 = L::select(zero.simd_lt(full), part / full, zero);
    let exact = r.ok & zero.simd_lt(r.z) & L::splat(FALLBACK_TURNS).simd_le(r.turns);
    [
        L::select(exact, unit_interval(u0), unit_interval(s)),
        L::select(exact, unit_interval(u1), unit_interval(t)),
    ]
}
