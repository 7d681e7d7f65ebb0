//! GGX (Trowbridge-Reitz) microfacet reflection: the distribution of normals, Smith masking,
//! and the sampling of visible normals and reflected directions with their exact densities.
//!
//! | function | value | source |
//! |---|---|---|
//! | [`ggx_d`] | `D(m) = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2)` per steradian of `m` | Trowbridge and Reitz 1975; Walter, Marschner, Li and Torrance 2007 |
//! | [`ggx_g1`] | Smith masking `G1(w) = 2 wz / (wz + \|(ax wx, ay wy, wz)\|)` | Smith 1967; Heitz 2014, "Understanding the Masking-Shadowing Function" (JCGT 3(2)) |
//! | [`ggx_g2`] | height-correlated `G2 = 1 / (1 + Lambda(wo) + Lambda(wi))` | Heitz 2014 |
//! | [`ggx_visible_normal`] | `m` with density `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z` | Dupuy and Benyoub 2023, "Sampling Visible GGX Normals with Spherical Caps" (CGF 42(8)); the distribution of Heitz 2018 (JCGT 7(4)) |
//! | [`ggx_reflect`] | `wi = 2 (wo.m) m - wo`, density `D_wo(m) / (4 wo.m) = D(m) / (2 (wo.z + \|(ax wox, ay woy, woz)\|))` | as above |
//! | [`ggx_reflect_bounded`] | the caps sampler on a smaller cap: fewer `wi` below the horizon, density `D(m) / (2 (k wo.z + \|(ax wox, ay woy, woz)\|))` inside the cap's image, 0 outside | Eto and Tokuyoshi 2023, "Bounded VNDF Sampling for Smith-GGX Reflections" (SIGGRAPH Asia TC) |
//!
//! **Conventions.** Shading frame: `z` is the normal; `wo`, `wi` and `m` point away from the
//! surface. `alpha = [ax, ay]` is the roughness as pbrt-v4 and Mitsuba take it: `alpha = r^2`
//! of a perceptual ("artist") roughness `r`. Every function has `_x8`, `_x16` and `_slice`
//! forms, bit-identical to the scalar one; a slice packs each call's arguments in order
//! (`[wo, alpha, u]` = 7 floats for the samplers, `[wo, wi or m, alpha]` = 8 for the
//! densities and [`ggx_g2`], `[w, alpha]` = 5 for [`ggx_d`] and [`ggx_g1`]).
//!
//! **Without underflow.** No `alpha^2` products that can underflow: the distribution is
//! evaluated on alpha-scaled vectors (`(mx / ax, my / ay, mz)` and `(ax wx, ay wy, wz)`), so at
//! `alpha = 1e-4` nothing smaller than `1e-8` is formed (where `alpha^4 = 1e-16` would be
//! squared again, or `2^-149` reached, by the textbook forms). Every input vector is first
//! scaled by a power of two (exact) so that its largest component lies in `[1, 2)`; lengths
//! never overflow or underflow. `1 - z` of the standard-space incident direction is computed
//! as `(x^2 + y^2) / (l (l + z))`, without cancellation, so the caps keep their precision at
//! normal incidence, and the cap's `sin^2` is formed as a product of two non-cancelling
//! factors.
//!
//! **Totality** (any `f32` in every argument; tested with the hostile cross products of
//! `tests/hostile.rs`):
//! * `alpha`: each component clamped to `[1e-4, 1]` (NaN becomes `1e-4`).
//! * `u`: each coordinate mapped onto `[0, 1 - 2^-24]` (NaN and negatives to 0).
//! * `wo` below the horizon (`wo.z < 0`) is mirrored to `(x, y, -z)`: the surface reflects into
//!   the hemisphere `wo` lies in, as a two-sided BSDF does; `wo.z = 0` (grazing) is handled
//!   exactly (every sampler and density has a finite limit there). [`ggx_g1`] and
//!   [`ggx_g2`] use `|w.z|` likewise (pbrt-v4's convention).
//! * A zero or non-finite `wo` (or a vector whose largest component is below `2^-126` or at
//!   least `2^127`) is read as `+z`. In the density functions a zero or non-finite `m`/`wi`
//!   (same rule) has density 0, and [`ggx_d`] of such an `m` is 0.
//! * Directions returned are unit within `1e-6` and finite; visible normals have `m.z > 0`;
//!   densities are finite and `>= 0` (at most `1.6e11` per steradian: `D <= 1 / (pi 1e-8)`
//!   over `2 |(ax wox, ay woy, woz)| >= 2e-4`).
//! * `wi` may lie below the horizon (the integrand is 0 there); its density is what the
//!   sampler gives it. A density of 0 for a returned direction (the bounded sampler's cap rim,
//!   at the horizon) means the sample carries no weight.
//!
//! **Precision** against `f64` transcriptions of the textbook formulas on the same `f32`
//! inputs (`tests/microfacet.rs`; the table is in `docs/warps.md`): every density within
//! 1.3e-6 relative over `alpha` in `[1e-4, 1]` and `wo.z` in `[1e-6, 1]`. Where a sum of
//! products cancels (the reflections' half vector at small `alpha`, `wo.m` of the visible
//! density) it is formed in double `f32` by error-free transformations (Dekker 1971; Knuth's
//! two-sum), without FMA; see each function.
//!
//! That figure is measured on the test's sweep (random `wo`, `wi`, `m`), not a bound for
//! every input: a search over 15 million cases against `f64` (60-digit checks of the worst)
//! found the densities ill-conditioned in their own arithmetic in four places.
//! * Grazing `wo` (`wo.z` from 1e-6 to 1e-2) with `alpha` below 1e-2: the reflection
//!   densities at the samplers' own directions within 6.1e-6 (the half vector is short,
//!   about `2 wo.z`, and `D` magnifies its residual error by `1 / alpha`).
//! * The visible-normal density for `m` nearly perpendicular to `wo` (`wo.m` below about
//!   `1e-8` of `sum |wo_i m_i|`, densities of 1e-14 and less): up to 1.4e-3.
//! * `wi` within about `2^-45 |wo|` of `-wo` (the half vector vanishes; below the horizon,
//!   where the integrand is 0): off by factors; at the support's edge (`h.z` near 0, the
//!   bounded cap's rim within 4e-4) 0 where `f64` is positive or the reverse. For `wo.z`
//!   below `2^-40 |wo|` a reflection sampler can return density 0 for its own direction (11
//!   of 8 million hostile cases): that sample carries no weight.
//! * At `alpha = 1e-4` with `wo.z <= 1e-4` the reflected lobe is tens of `f32` ulps wide: the
//!   visible normals are distributed exactly, but their reflections rounded to `f32` are not
//!   (a 3-4% bias of the estimated integral), as for any `f32` sampler; the contract's range
//!   starts at `alpha = 1e-3`, where no bias is measurable.
//!
//! ```
//! use warpcore::microfacet;
//!
//! let (wo, alpha) = ([0.6f32, 0.0, 0.8], [0.3f32, 0.3]);
//! let (wi, pdf) = microfacet::ggx_reflect(wo, alpha, [0.25, 0.5]);
//! assert!((wi.iter().map(|x| x * x).sum::<f32>() - 1.0).abs() < 1e-6);
//! // The returned density is the density function at the returned direction (MIS).
//! assert_eq!(pdf, microfacet::ggx_reflect_pdf(wo, wi, alpha));
//! // The bounded sampler: its own density.
//! let (wb, pb) = microfacet::ggx_reflect_bounded(wo, alpha, [0.25, 0.5]);
//! assert_eq!(pb, microfacet::ggx_reflect_bounded_pdf(wo, wb, alpha));
//! ```

mod bounded;
mod distribution;
mod exact;
mod reflect;
mod visible_normal;

pub use bounded::{
    ggx_reflect_bounded, ggx_reflect_bounded_pdf, ggx_reflect_bounded_pdf_slice,
    ggx_reflect_bounded_pdf_x8, ggx_reflect_bounded_pdf_x16, ggx_reflect_bounded_slice,
    ggx_reflect_bounded_x8, ggx_reflect_bounded_x16,
};
pub use distribution::{
    ggx_d, ggx_d_slice, ggx_d_x8, ggx_d_x16, ggx_g1, ggx_g1_slice, ggx_g1_x8, ggx_g1_x16, ggx_g2,
    ggx_g2_slice, ggx_g2_x8, ggx_g2_x16,
};
pub use reflect::{
    ggx_reflect, ggx_reflect_pdf, ggx_reflect_pdf_slice, ggx_reflect_pdf_x8, ggx_reflect_pdf_x16,
    ggx_reflect_slice, ggx_reflect_x8, ggx_reflect_x16,
};
pub use visible_normal::{
    ggx_visible_normal, ggx_visible_normal_pdf, ggx_visible_normal_pdf_slice,
    ggx_visible_normal_pdf_x8, ggx_visible_normal_pdf_x16, ggx_visible_normal_slice,
    ggx_visible_normal_x8, ggx_visible_normal_x16,
};

use crate::lanes::{Lane, unit_interval};
use crate::trig::sin_cos_turns;
use crate::vec3::{V, all_finite, dot, norm, pow2_lift, pow2_scale, scale};

/// The smallest roughness: `alpha` below it (and NaN) is raised to it.
pub const ALPHA_MIN: f32 = 1e-4;

/// `1 / pi`.
const INV_PI: f32 = core::f32::consts::FRAC_1_PI;

/// The roughness clamped to `[ALPHA_MIN, 1]` (NaN to `ALPHA_MIN`), by compare and select.
#[inline(always)]
fn roughness<L: Lane>(alpha: [L; 2]) -> [L; 2] {
    let (lo, one) = (L::splat(ALPHA_MIN), L::splat(1.0));
    alpha.map(|a| L::select(lo.simd_lt(a), L::select(a.simd_lt(one), a, one), lo))
}

/// `v` scaled by the power of two that puts its largest component in `[1, 2)`, and whether
/// that exists with every component finite (else the zero vector).
#[inline(always)]
fn scaled<L: Lane>(v: V<L>) -> (V<L>, L::Mask) {
    let (k, ok) = pow2_scale([v]);
    let ok = ok & all_finite([v]);
    let zero = L::splat(0.0);
    (scale(v, k).map(|x| L::select(ok, x, zero)), ok)
}

/// The outgoing direction as every function reads it: `s`, the exact power-of-two-scaled
/// `wo` mirrored into `z >= 0` ([`outgoing_scaled`]), `inv = 1 / |s|` and the unit `w = s inv`
/// (`+z` where `wo` is not a direction).
#[derive(Clone, Copy)]
struct Outgoing<L> {
    s: V<L>,
    inv: L,
    w: V<L>,
}

#[inline(always)]
fn outgoing<L: Lane>(wo: V<L>) -> Outgoing<L> {
    let s = outgoing_scaled(wo);
    let inv = L::splat(1.0) / norm(s);
    Outgoing {
        s,
        inv,
        w: scale(s, inv),
    }
}

/// The outgoing direction for the visible-normal sampler, which needs only its direction:
/// scaled by a power of two (exact), mirrored into `z >= 0`, `+z` when not a direction.
#[inline(always)]
fn outgoing_scaled<L: Lane>(wo: V<L>) -> V<L> {
    let (s, ok) = scaled([wo[0], wo[1], wo[2].abs()]);
    [s[0], s[1], L::select(ok, s[2], L::splat(1.0))]
}

/// The roughness and its reciprocals, computed once per call.
#[derive(Clone, Copy)]
struct Rough<L> {
    ax: L,
    ay: L,
    inv_ax: L,
    inv_ay: L,
}

#[inline(always)]
fn rough<L: Lane>(alpha: [L; 2]) -> Rough<L> {
    let [ax, ay] = roughness(alpha);
    let one = L::splat(1.0);
    Rough {
        ax,
        ay,
        inv_ax: one / ax,
        inv_ay: one / ay,
    }
}

impl<L: Lane> Rough<L> {
    /// `(ax wx, ay wy, wz)`: a direction in the standard (alpha = 1) configuration.
    #[inline(always)]
    fn stretch(&self, w: V<L>) -> V<L> {
        [self.ax * w[0], self.ay * w[1], w[2]]
    }
    /// `(mx / ax, my / ay, mz)`: a normal in the standard configuration.
    #[inline(always)]
    fn unstretch(&self, m: V<L>) -> V<L> {
        [m[0] * self.inv_ax, m[1] * self.inv_ay, m[2]]
    }
    /// `D(m)` of a nonzero `m` of any length in the range [`scaled`] gives:
    /// `(|m|^2 / |unstretch(m)|^2)^2 / (pi ax ay)`, 0 where `m.z <= 0` or every square underflows. Also returns
    /// `|unstretch(m)|^2` (the bounded density's cap test uses it).
    #[inline(always)]
    fn d(&self, m: V<L>) -> (L, L) {
        let q = dot(self.unstretch(m), self.unstretch(m));
        let r = dot(m, m) / q;
        let d = r * r * (self.inv_ax * self.inv_ay * L::splat(INV_PI));
        // q = 0 (an `m` whose squares all underflow: the sum of a nearly opposite `wo` and
        // `wi`) would give 0 / 0.
        let zero = L::splat(0.0);
        (L::select(zero.simd_lt(m[2]) & zero.simd_lt(q), d, zero), q)
    }
    /// `|stretch(w)|` of a unit `w`: `wo.z / G1(wo) * 2 - wo.z`.
    #[inline(always)]
    fn stretched_len(&self, w: V<L>) -> L {
        norm(self.stretch(w))
    }
}

/// The bounded sampler's shrink factor `k` of Eto and Tokuyoshi 2023 (their equation 5 with
/// `a = min(ax, ay)`, `s = 1 + |wo.xy|`): `k = (1 - a^2) s^2 / (s^2 + a^2 wo.z^2)`, and
/// `1 - k = a^2 (s^2 + wo.z^2) / (s^2 + a^2 wo.z^2)` without cancellation. `w` unit, `z >= 0`.
#[inline(always)]
fn shrink<L: Lane>(r: &Rough<L>, w: V<L>) -> (L, L) {
    let Shrink { k, d, omk } = shrink_parts(r, w);
    let inv = L::splat(1.0) / d;
    (k * inv, omk * inv)
}

/// `k` and `1 - k` over their common denominator: `k = k / d`, `1 - k = omk / d`.
struct Shrink<L> {
    k: L,
    d: L,
    omk: L,
}

#[inline(always)]
fn shrink_parts<L: Lane>(r: &Rough<L>, w: V<L>) -> Shrink<L> {
    let one = L::splat(1.0);
    let a = L::select(r.ax.simd_lt(r.ay), r.ax, r.ay);
    let a2 = a * a;
    let s = one + (w[0] * w[0] + w[1] * w[1]).sqrt();
    let s2 = s * s;
    let z2 = w[2] * w[2];
    Shrink {
        k: (one - a2) * s2,
        d: s2 + a2 * z2,
        omk: a2 * (s2 + z2),
    }
}

/// The visible normal for the outgoing direction `w` (`z >= 0`, any length for the full
/// distribution, unit for the bounded one) by a spherical cap (Dupuy and Benyoub 2023): in
/// the standard configuration the incident direction is `i = stretch(w) / l`,
/// `l = |stretch(w)|`; a point `c` uniform on the cap `z >= -b` of the unit sphere (`b = i.z`
/// for the full visible distribution, `k i.z` for the bounded one, `k` given) gives the
/// standard normal `i + c`, which is unstretched (`(ax x, ay y, z)`) and normalised. Only the
/// direction of `i + c` counts, so the construction is carried out multiplied by `l`: no
/// division until the last normalisation. Returns `m` and `l`.
#[inline(always)]
fn cap_normal<L: Lane>(r: &Rough<L>, w: V<L>, u: [L; 2], k: Option<Shrink<L>>) -> (V<L>, L) {
    let one = L::splat(1.0);
    let ws = r.stretch(w);
    let l = norm(ws);
    // The bounded cap is built multiplied by k's denominator d as well (no division): b l d
    // = k ws.z, l d, and the rim height (i.z - b) l d = (1 - k) d ws.z without cancellation.
    let (ld, bl, wd, rim) = match &k {
        Some(k) => (l * k.d, k.k * ws[2], ws.map(|x| x * k.d), k.omk * ws[2]),
        None => (l, ws[2], ws, L::splat(0.0)),
    };
    // (1 + b) l d and (1 - b) l d. The rounding of `ld - bl` (absolute, an ulp of ld) only
    // matters where (1 - u1)(1 + b) is as small, at the top two f32 values of u1.
    let (p, q) = (ld + bl, ld - bl);
    let (u0, u1) = (unit_interval(u[0]), unit_interval(u[1]));
    // c.z = (1 - u1)(1 + b) - b; 1 - c.z^2 = u1 (1 + b) ((1 - u1)(1 + b) + 1 - b).
    let vp = (one - u1) * p;
    let sin = (u1 * p * (vp + q)).sqrt();
    let (sn, cs) = sin_cos_turns(u0);
    // (i + c) l d; its height (1 - u1)(1 + b) l d + (i.z - b) l d is positive.
    let hz = if k.is_some() { vp + rim } else { vp };
    // Unstretched as (ax (i + c).x, ay (i + c).y, (i + c).z), with ax cos and ax wd.x off the
    // path from the square roots; normalised by three divisions (no reciprocal on the path).
    let m = [
        sin * (r.ax * cs) + r.ax * wd[0],
        sin * (r.ay * sn) + r.ay * wd[1],
        hz,
    ];
    let n = norm(m);
    ([m[0] / n, m[1] / n, m[2] / n], l)
}

/// `alpha_min wo.h` from which the plain `f32` half vector is used: its density error is
/// within `6.9e-7 / (alpha_min wo.h)` (measured, `tests/microfacet.rs`), `5.5e-6` here.
const PLAIN_FROM: f32 = 0.125;

/// The reflection density at `wi` (any length; its direction counts) for the outgoing `o`
/// with `t = |stretch(o.w)|`: `D(h) / (2 (k w.z + t))` with the half vector `h` of `wo` and
/// `wi` (`k = 1` for the full visible distribution), and for the bounded one 0 where `h` lies
/// outside the image of the cap: the standard-space reflection of `i` about `h`'s standard
/// normal has height below `-b`, which is `2 (w.h) h.z < (1 - k) w.z |unstretch(h)|^2`. A
/// zero or non-finite `wi` has density 0.
///
/// The half vector: `|wi| w + wi` in plain `f32` where `alpha_min wo.h >= 1/8` (judged on
/// it: `wo.h = |h| / (2 |wi|)`), else `o.s + (|o.s| / |wi|) wi` in double-`f32`
/// ([`exact::half_direction`]): its components cancel where `wi` is near the mirror image
/// of `wo` (every lobe at small `alpha`) or near `-wo`, and `D` magnifies their error by
/// `1 / alpha` there. The scalar form computes the double-`f32` one only where it is used.
/// The samplers call this on the direction they return (with the same `t`), so their
/// density is the density function's at that direction, bit for bit.
#[inline(always)]
fn reflect_density<L: Lane>(r: &Rough<L>, o: &Outgoing<L>, t: L, wi: V<L>, bounded: bool) -> L {
    let w = o.w;
    let (wi, valid) = scaled(wi);
    // An invalid wi (scaled to zero) is read as +z for the arithmetic; its density is 0.
    let wi = [wi[0], wi[1], L::select(valid, wi[2], L::splat(1.0))];
    let (den, omk) = if bounded {
        let (k, omk) = shrink(r, w);
        (k * w[2] + t, omk)
    } else {
        (w[2] + t, L::splat(0.0))
    };
    let l = norm(wi);
    let plain = [w[0] * l + wi[0], w[1] * l + wi[1], w[2] * l + wi[2]];
    let amin = L::select(r.ax.simd_lt(r.ay), r.ax, r.ay);
    let bound = L::splat(PLAIN_FROM * PLAIN_FROM * 4.0) * l * l;
    let use_plain = bound.simd_le(amin * amin * dot(plain, plain));
    let at = |h: V<L>| density_at(r, w, h, den, omk, valid, bounded);
    let p = at(plain);
    L::unless(use_plain, p, || {
        L::select(use_plain, p, at(exact::half_direction(o.s, wi)))
    })
}

/// [`reflect_density`] at the half vector `h` (any length), with `den = k w.z + t` and, for
/// the bounded cap, `omk = 1 - k`.
#[inline(always)]
fn density_at<L: Lane>(
    r: &Rough<L>,
    w: V<L>,
    h: V<L>,
    den: L,
    omk: L,
    valid: L::Mask,
    bounded: bool,
) -> L {
    let zero = L::splat(0.0);
    // h is tiny where wi is nearly -w: lift it by a power of two (D is scale-free).
    let h = scale(h, pow2_lift(h));
    let hh = dot(h, h);
    let q = dot(r.unstretch(h), r.unstretch(h));
    let inside = if bounded {
        // A relative slack of 2^-16 at the rim keeps the cap's own samples inside it.
        let lhs = L::splat(2.0) * dot(w, h) * h[2];
        let rhs = w[2] * omk * q * L::splat(1.0 - 1.0 / 65536.0);
        rhs.simd_le(lhs)
    } else {
        valid
    };
    // D(h) / (2 den) = (hh / q)^2 / (pi ax ay 2 den), with one division; q = 0 (every square
    // underflowed) and h.z <= 0 give 0.
    let c = r.inv_ax * r.inv_ay * L::splat(0.5 * INV_PI);
    let p = hh * hh * c / (q * q * den);
    let ok = valid & inside & zero.simd_lt(h[2]) & zero.simd_lt(q);
    L::select(ok, p, zero)
}

/// The reflection sampler: a visible normal `m` by [`cap_normal`], `wi = 2 (w.m) m - w`, and
/// its density by [`reflect_density`] at that `wi`.
#[inline(always)]
fn reflect_sample<L: Lane>(wo: V<L>, alpha: [L; 2], u: [L; 2], bounded: bool) -> (V<L>, L) {
    let r = rough(alpha);
    let o = outgoing(wo);
    let w = o.w;
    let k = if bounded {
        Some(shrink_parts(&r, w))
    } else {
        None
    };
    let (m, t) = cap_normal(&r, w, u, k);
    let wm = dot(w, m);
    let t2 = wm + wm;
    let wi = [t2 * m[0] - w[0], t2 * m[1] - w[1], t2 * m[2] - w[2]];
    (wi, reflect_density(&r, &o, t, wi, bounded))
}

/// The reflection density function: `wo` read as the samplers read it.
#[inline(always)]
fn reflect_pdf<L: Lane>(wo: V<L>, wi: V<L>, alpha: [L; 2], bounded: bool) -> L {
    let r = rough(alpha);
    let o = outgoing(wo);
    reflect_density(&r, &o, norm(r.stretch(o.w)), wi, bounded)
}

/// Splits a packed `[a, b, c]` of 3, 3 and 2 floats (the densities' and `G2`'s arguments).
#[inline(always)]
fn split332<L: Copy>(x: [L; 8]) -> (V<L>, V<L>, [L; 2]) {
    let [a0, a1, a2, b0, b1, b2, c0, c1] = x;
    ([a0, a1, a2], [b0, b1, b2], [c0, c1])
}

/// Splits a packed `[wo, alpha, u]` of 3, 2 and 2 floats (the samplers' arguments).
#[inline(always)]
fn split322<L: Copy>(x: [L; 7]) -> (V<L>, [L; 2], [L; 2]) {
    let [a0, a1, a2, b0, b1, c0, c1] = x;
    ([a0, a1, a2], [b0, b1], [c0, c1])
}

/// Splits a packed `[w, alpha]` of 3 and 2 floats.
#[inline(always)]
fn split32<L: Copy>(x: [L; 5]) -> (V<L>, [L; 2]) {
    let [a0, a1, a2, b0, b1] = x;
    ([a0, a1, a2], [b0, b1])
}

/// A direction and its density as one packed result.
#[inline(always)]
fn packed4<L: Copy>((w, p): (V<L>, L)) -> [L; 4] {
    [w[0], w[1], w[2], p]
}

/// The slice form of a microfacet function: `out[i] = f(packed[i])` with the arguments packed
/// in order (see the module docs), for `i < min(input.len(), out.len())`; returns that count.
macro_rules! slice_form {
    ($(#[$attr:meta])* pub fn $name:ident [$i:literal -> $o:literal] = |$x:ident| $e:expr;) => {
        $(#[$attr])*
        #[inline]
        pub fn $name(input: &[[f32; $i]], out: &mut [[f32; $o]]) -> usize {
            crate::slices::map_lanes(input, out, |$x: [crate::slices::Widest; $i]| $e)
        }
    };
}
use slice_form;

/// The reflection sampler and its density function (`bounded` chooses Eto and Tokuyoshi's cap)
/// with all their forms: the scalar, `_x8` and `_x16` forms by [`lane_forms!`], the slices by
/// [`slice_form!`] (`[wo, alpha, u]` to `[wi, density]`, `[wo, wi, alpha]` to the density).
macro_rules! reflection_forms {
    (
        bounded: $bounded:literal;
        $(#[$sattr:meta])*
        pub fn $f:ident, $f8:ident, $f16:ident [sampler];
        pub fn $fs:ident [sampler];
        $(#[$pattr:meta])*
        pub fn $p:ident, $p8:ident, $p16:ident [density];
        pub fn $ps:ident [density];
    ) => {
        #[inline(always)]
        fn sample_body<L: crate::lanes::Lane>(wo: [L; 3], alpha: [L; 2], u: [L; 2]) -> ([L; 3], L) {
            super::reflect_sample(wo, alpha, u, $bounded)
        }

        #[inline(always)]
        fn pdf_body<L: crate::lanes::Lane>(wo: [L; 3], wi: [L; 3], alpha: [L; 2]) -> L {
            super::reflect_pdf(wo, wi, alpha, $bounded)
        }

        lane_forms! {
            $(#[$sattr])*
            pub fn $f, $f8, $f16 ["(direction, roughness, sample) triples"]
                (wo: [L; 3], alpha: [L; 2], u: [L; 2]) -> ([L; 3], L) = sample_body;
        }

        lane_forms! {
            $(#[$pattr])*
            pub fn $p, $p8, $p16 ["(direction, direction, roughness) triples"]
                (wo: [L; 3], wi: [L; 3], alpha: [L; 2]) -> L = pdf_body;
        }

        super::slice_form! {
            #[doc = concat!("[`", stringify!($f), "`] over a batch of packed `[wo, alpha, u]` ",
                "(7 floats): `out[i] = [wi.x, wi.y, wi.z, density]`. Bit-identical to the ",
                "scalar form.")]
            pub fn $fs [7 -> 4] = |x| {
                let (wo, a, u) = super::split322(x);
                super::packed4(sample_body(wo, a, u))
            };
        }

        super::slice_form! {
            #[doc = concat!("[`", stringify!($p), "`] over a batch of packed `[wo, wi, alpha]` ",
                "(8 floats). Bit-identical to the scalar form.")]
            pub fn $ps [8 -> 1] = |x| {
                let (wo, wi, a) = super::split332(x);
                [pdf_body(wo, wi, a)]
            };
        }
    };
}
use reflection_forms;
