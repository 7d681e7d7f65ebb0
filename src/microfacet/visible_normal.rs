//! Visible normals of GGX by spherical caps (Dupuy and Benyoub 2023), and their density.

use super::{
    cap_normal, exact, outgoing, outgoing_scaled, rough, scaled, slice_form, split322, split332,
};
use crate::lanes::Lane;
use crate::vec3::{V, norm};

#[inline(always)]
fn sample_body<L: Lane>(wo: V<L>, alpha: [L; 2], u: [L; 2]) -> V<L> {
    cap_normal(&rough(alpha), outgoing_scaled(wo), u, None).0
}

/// `D_wo(m) = 2 max(0, w.m) D(m) / ((w.z + |stretch(w)|) |m|)` for the unit outgoing `w`
/// (`G1(w) / w.z = 2 / (w.z + |stretch(w)|)`, finite at grazing), with `w.m = (s . m) / |s|`
/// of the exact scaled `s` and `m`, the dot product in double-`f32` (it cancels where `m` is
/// nearly perpendicular to `wo`).
#[inline(always)]
fn pdf_body<L: Lane>(wo: V<L>, m: V<L>, alpha: [L; 2]) -> L {
    let zero = L::splat(0.0);
    let r = rough(alpha);
    let o = outgoing(wo);
    let w = o.w;
    let (m, ok) = scaled(m);
    let (d, _) = r.d(m);
    let (hi, lo) = exact::dot2(o.s, m);
    let wm = (hi + lo) * o.inv;
    let den = (w[2] + r.stretched_len(w)) * norm(m);
    // No subnormal operand or result (flush-to-zero devices agree): wo.m below 2^-126 and a
    // density below 2^-126 count as 0; d / den is a normal number.
    let tiny = L::splat(f32::MIN_POSITIVE);
    let p = (wm + wm) * (d / den);
    L::select(ok & tiny.simd_le(wm) & tiny.simd_le(p), p, zero)
}

lane_forms! {
    /// A GGX normal visible from `wo`, distributed as `D_wo(m) = G1(wo) max(0, wo.m) D(m) /
    /// wo.z` ([`ggx_visible_normal_pdf`](super::ggx_visible_normal_pdf)): Dupuy and Benyoub 2023, "Sampling Visible GGX
    /// Normals with Spherical Caps" (CGF 42(8)), the same distribution as Heitz 2018,
    /// "Sampling the GGX Distribution of Visible Normals" (JCGT 7(4)), without its frame.
    ///
    /// In the standard configuration (`alpha = 1`) the incident direction is `i =
    /// normalize(ax wox, ay woy, woz)`; the point `c = (sin t cos phi, sin t sin phi, z)` with
    /// `phi = 2 pi u0` and `z = (1 - u1)(1 + i.z) - i.z` is uniform on the spherical cap
    /// `z >= -i.z`, `i + c` is a visible standard normal, and `m = normalize(ax (i + c).x,
    /// ay (i + c).y, (i + c).z)`. `sin^2 t` is `u1 (1 + i.z)((1 - u1)(1 + i.z) + 1 - i.z)`
    /// with `1 - i.z` from the stretched components (no cancellation at normal incidence),
    /// `(i + c).z = (1 - u1)(1 + i.z) >= 2^-24`, so `m.z > 0`; sine and cosine are the crate's
    /// polynomials. `m` is unit within 1e-6 (measured 5.3e-7 over every returned direction). Out of domain: the
    /// [module docs](super) (`wo` mirrored into `z >= 0`, invalid `wo` read as `+z`, `alpha`
    /// clamped to `[1e-4, 1]`, `u` to `[0, 1 - 2^-24]`).
    pub fn ggx_visible_normal, ggx_visible_normal_x8, ggx_visible_normal_x16
        ["(direction, roughness, sample) triples"]
        (wo: [L; 3], alpha: [L; 2], u: [L; 2]) -> [L; 3] = sample_body;
}

lane_forms! {
    /// The density of [`ggx_visible_normal`](super::ggx_visible_normal) per steradian of `m`:
    /// `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z`, evaluated as
    /// `2 max(0, wo.m) D(m) / (wo.z + |(ax wox, ay woy, woz)|)` (finite as `wo.z -> 0`).
    ///
    /// `m` may have any length (its direction counts); a zero or non-finite `m` has density
    /// 0, and so has `m.z <= 0`. `wo` as [`ggx_visible_normal`](super::ggx_visible_normal) reads it. `wo.m` is
    /// `(s . m) / |s|` of the scaled `wo` and `m`, the dot product in double `f32` (it
    /// cancels for `m` nearly perpendicular to `wo`); `wo.m` and densities below `2^-126`
    /// count as 0. Error against `f64` (on the same `f32` inputs): within 7.3e-7 relative
    /// (measured over 130,560 sampled normals, the sweep of `docs/warps.md`).
    pub fn ggx_visible_normal_pdf, ggx_visible_normal_pdf_x8, ggx_visible_normal_pdf_x16
        ["(direction, normal, roughness) triples"]
        (wo: [L; 3], m: [L; 3], alpha: [L; 2]) -> L = pdf_body;
}

slice_form! {
    /// [`ggx_visible_normal`](super::ggx_visible_normal) over a batch of packed `[wo, alpha, u]` (7 floats):
    /// `out[i] = m`. Bit-identical to the scalar form.
    pub fn ggx_visible_normal_slice [7 -> 3] = |x| {
        let (wo, a, u) = split322(x);
        sample_body(wo, a, u)
    };
}

slice_form! {
    /// [`ggx_visible_normal_pdf`](super::ggx_visible_normal_pdf) over a batch of packed `[wo, m, alpha]` (8 floats).
    /// Bit-identical to the scalar form.
    pub fn ggx_visible_normal_pdf_slice [8 -> 1] = |x| {
        let (wo, m, a) = split332(x);
        [pdf_body(wo, m, a)]
    };
}
