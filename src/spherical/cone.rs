//! Sphere lights: directions uniform in the cone a sphere (centre, radius) subtends at `p`,
//! in cancellation-free form (`1 - cos theta_max = sin^2 / (1 + cos)`), through the
//! concentric disk so that compact strata of the square stay compact in the cone.

use crate::disk::{concentric_inverse_body, concentric_parts};
use crate::lanes::Lane;
use crate::vec3::*;

/// The cone seen from `p`: its axis `n` (unit, towards the centre), a tangent frame `t`, `b`
/// (Duff et al. 2017), and `1 - cos theta_max`.
pub(super) struct Cone<L: Lane> {
    pub n: V<L>,
    pub t: V<L>,
    pub b: V<L>,
    /// `1 - cos theta_max` in `(0, 2]` (2: `p` inside, the whole sphere); 0 where `ok` is
    /// false.
    pub omc: L,
    /// A light of positive solid angle (finite input, not below [`POINT_RATIO`]).
    pub ok: L::Mask,
}

/// Spheres whose radius over distance is below this (`2^-60`, solid angle below `pi 2^-120`,
/// about `2.9e-36` sr) count as points: solid angle and density 0, every sample the axis.
/// It keeps the density `1 / omega` below `2^119`.
pub(super) const POINT_RATIO: f32 = 1.0 / (1u64 << 60) as f32;

/// `1 / (2 pi)`: the density is `INV_2PI / (1 - cos theta_max)`.
const INV_2PI: f32 = (0.5 * core::f64::consts::FRAC_1_PI) as f32;
/// `2 pi`.
const TWO_PI: f32 = (2.0 * core::f64::consts::PI) as f32;

#[inline(always)]
pub(super) fn setup<L: Lane>(centre: V<L>, radius: L, p: V<L>) -> Cone<L> {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let d = flush_subnormal(sub(centre, p));
    let rv = flush_subnormal([radius.abs(), zero, zero]);
    let finite = all_finite([d, rv]);
    // The axis from d at its own scale (a radius far larger than the distance would push d
    // towards underflow in the common scale), the ratio r / d at the common one.
    let (kd, has_axis) = pow2_scale([d]);
    let dn = scale(d, kd);
    let inv = one / norm(dn);
    let (k, scaled) = pow2_scale([d, rv]);
    let (d, r) = (scale(d, k), rv[0] * k);
    let dist = norm(d);
    let has_axis = finite & has_axis;
    // p outside the sphere or on it (else it sees the whole sphere of directions).
    let outside = has_axis & r.simd_le(dist);
    let dist_s = L::select(outside, dist, one);
    // sin theta_max = r / d; cos^2 = (d - r)(d + r) / d^2 (no 1 - sin^2).
    let s = r / dist_s;
    let cos = L::select(outside, ((dist_s - r) * (dist_s + r)).sqrt() / dist_s, zero);
    let omc = L::select(outside, s * s / (one + cos), L::splat(2.0));
    let ok = finite & scaled & !(outside & s.simd_lt(L::splat(POINT_RATIO)));
    let n = [
        L::select(has_axis, dn[0] * inv, zero),
        L::select(has_axis, dn[1] * inv, zero),
        L::select(has_axis, dn[2] * inv, one),
    ];
    // Duff, Burgess, Christensen, Hery, Kensler, Liani and Villemin 2017, "Building an
    // Orthonormal Basis, Revisited" (JCGT 6(1)): branch-free, continuous but at n.z = -0.
    let sign = one.flip_sign(n[2].sign_bit());
    let a = -one / (sign + n[2]);
    let bxy = n[0] * n[1] * a;
    let t = [one + sign * n[0] * n[0] * a, sign * bxy, -(sign * n[0])];
    let b = [bxy, sign + n[1] * n[1] * a, -n[1]];
    Cone {
        n,
        t,
        b,
        omc: L::select(ok, omc, zero),
        ok,
    }
}

#[inline(always)]
pub(super) fn solid_angle_body<L: Lane>(centre: V<L>, radius: L, p: V<L>) -> L {
    setup(centre, radius, p).omc * L::splat(TWO_PI)
}

#[inline(always)]
pub(super) fn sample_body<L: Lane>(centre: V<L>, radius: L, p: V<L>, u: [L; 2]) -> ([L; 3], L) {
    sample_prepared(&setup(centre, radius, p), u)
}

/// The direction for `u` and the density, with the cone set up (once per slice call by the
/// slice form).
#[inline(always)]
pub(super) fn sample_prepared<L: Lane>(c: &Cone<L>, u: [L; 2]) -> ([L; 3], L) {
    let one = L::splat(1.0);
    let (r, cphi, sphi) = concentric_parts(u);
    // Area-preserving from the disk to the cap: 1 - cos theta = r^2 (1 - cos theta_max),
    // sin theta = sqrt(x (2 - x)) (no cancellation at small angles).
    let x = r * r * c.omc;
    let cos = one - x;
    let sin = (x * (L::splat(2.0) - x)).sqrt().flip_sign(r.sign_bit());
    let (st, sb) = (sin * cphi, sin * sphi);
    let dir = [
        c.t[0] * st + c.b[0] * sb + c.n[0] * cos,
        c.t[1] * st + c.b[1] * sb + c.n[1] * cos,
        c.t[2] * st + c.b[2] * sb + c.n[2] * cos,
    ];
    let pdf = L::select(c.ok, L::splat(INV_2PI) / c.omc, L::splat(0.0));
    (dir, pdf)
}

#[inline(always)]
pub(super) fn inverse_body<L: Lane>(centre: V<L>, radius: L, p: V<L>, dir: V<L>) -> [L; 2] {
    inverse_prepared(&setup(centre, radius, p), dir)
}

/// [`inverse_body`] with the cone set up.
#[inline(always)]
pub(super) fn inverse_prepared<L: Lane>(c: &Cone<L>, dir: V<L>) -> [L; 2] {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let half = L::splat(0.5);
    // The direction scaled by a power of two (exact), then normalised; zero, NaN or inf: the
    // axis.
    let w = flush_subnormal(dir);
    let (k, scaled) = pow2_scale([w]);
    let valid = all_finite([w]) & scaled;
    let w = scale(w, k);
    let l = norm(w);
    let inv = L::select(valid, one / l, zero);
    let w = scale(w, inv);
    let (xt, yb) = (dot(w, c.t), dot(w, c.b));
    let zc = L::select(valid, dot(w, c.n), one);
    let sin2 = xt * xt + yb * yb;
    // 1 - cos theta, without cancellation on either side.
    let x = L::select(zero.simd_lt(zc), sin2 / (one + zc), one - zc);
    // Disk radius sqrt(x / omc) in the direction (xt, yb) / sin theta: (xt, yb) /
    // sqrt(omc (2 - x)); beyond the cone, the cone's edge at the same azimuth.
    let omc = L::select(c.ok, c.omc, one);
    let within = x.simd_le(omc);
    let den = L::select(within, omc * (L::splat(2.0) - x), sin2);
    let has = zero.simd_lt(den);
    let kd = L::select(has, one / L::select(has, den, one).sqrt(), zero);
    // The antipode (sin theta = 0, x = 2) is the disk's rim.
    let rim = !has & one.simd_lt(x);
    let disk = [L::select(rim, one, xt * kd), yb * kd];
    let disk = [
        L::select(valid, disk[0], zero),
        L::select(valid, disk[1], zero),
    ];
    let uv = concentric_inverse_body(disk);
    [L::select(c.ok, uv[0], half), L::select(c.ok, uv[1], half)]
}
