//! Reflection by GGX visible normals: `wi = reflect(wo, m)` and its density per steradian of
//! `wi`.

use super::{packed4, reflect_pdf, reflect_sample, slice_form, split322, split332};
use crate::lanes::Lane;
use crate::vec3::V;

#[inline(always)]
fn sample_body<L: Lane>(wo: V<L>, alpha: [L; 2], u: [L; 2]) -> (V<L>, L) {
    reflect_sample(wo, alpha, u, false)
}

#[inline(always)]
fn pdf_body<L: Lane>(wo: V<L>, wi: V<L>, alpha: [L; 2]) -> L {
    reflect_pdf(wo, wi, alpha, false)
}

lane_forms! {
    /// A reflected direction by GGX visible normals: `m` = [`ggx_visible_normal`](super::ggx_visible_normal)`(wo, alpha,
    /// u)`, `wi = 2 (wo.m) m - wo`; returns `wi` and its density per steradian,
    /// `D_wo(m) / (4 wo.m) = G1(wo) D(m) / (4 wo.z) = D(h) / (2 (wo.z + |(ax wox, ay woy,
    /// woz)|))` (Heitz 2018; Dupuy and Benyoub 2023).
    ///
    /// The density is [`ggx_reflect_pdf`](super::ggx_reflect_pdf) evaluated at the returned `wi` (bit for bit), so a
    /// renderer's MIS weights agree whichever way a direction was found. `wi` may lie below
    /// the horizon (the integrand is 0 there; the fraction grows with `alpha` and towards
    /// grazing: see `docs/warps.md`, and [`ggx_reflect_bounded`](super::ggx_reflect_bounded) for fewer of them). `wi` is
    /// unit within 1e-6 (measured 4.2e-7). Out of domain: the [module docs](super).
    pub fn ggx_reflect, ggx_reflect_x8, ggx_reflect_x16
        ["(direction, roughness, sample) triples"]
        (wo: [L; 3], alpha: [L; 2], u: [L; 2]) -> ([L; 3], L) = sample_body;
}

lane_forms! {
    /// The density of [`ggx_reflect`](super::ggx_reflect) per steradian of `wi`: with the half vector `h = wo/|wo|
    /// + wi/|wi|`, `D(h) / (2 (wo.z + |(ax wox, ay woy, woz)|))` (0 where `h.z <= 0`).
    /// Integrates to 1 over the sphere (`tests/microfacet.rs`, `f64` quadrature).
    ///
    /// `wi` may have any length (its direction counts); zero or non-finite: density 0. `wo` as
    /// the sampler reads it. Error against `f64` on the same `f32` inputs: the half vector
    /// inherits the rounding of `wo`'s normalisation where `wo.h` is small, so the relative
    /// error is about `1e-7 / (alpha_min wo.h)` there: within 1e-5 wherever `alpha wo.h >=
    /// 0.01`, and measured over sampled directions in `docs/warps.md`.
    pub fn ggx_reflect_pdf, ggx_reflect_pdf_x8, ggx_reflect_pdf_x16
        ["(direction, direction, roughness) triples"]
        (wo: [L; 3], wi: [L; 3], alpha: [L; 2]) -> L = pdf_body;
}

slice_form! {
    /// [`ggx_reflect`](super::ggx_reflect) over a batch of packed `[wo, alpha, u]` (7 floats):
    /// `out[i] = [wi.x, wi.y, wi.z, density]`. Bit-identical to the scalar form.
    pub fn ggx_reflect_slice [7 -> 4] = |x| {
        let (wo, a, u) = split322(x);
        packed4(sample_body(wo, a, u))
    };
}

slice_form! {
    /// [`ggx_reflect_pdf`](super::ggx_reflect_pdf) over a batch of packed `[wo, wi, alpha]` (8 floats).
    /// Bit-identical to the scalar form.
    pub fn ggx_reflect_pdf_slice [8 -> 1] = |x| {
        let (wo, wi, a) = split332(x);
        [pdf_body(wo, wi, a)]
    };
}
