//! Reflection by GGX visible normals: `wi = reflect(wo, m)` and its density per steradian of
//! `wi`.

use super::reflection_forms;

reflection_forms! {
    bounded: false;
    /// A reflected direction by GGX visible normals: `m` = [`ggx_visible_normal`](super::ggx_visible_normal)`(wo, alpha,
    /// u)`, `wi = 2 (wo.m) m - wo`; returns `wi` and its density per steradian,
    /// `D_wo(m) / (4 wo.m) = G1(wo) D(m) / (4 wo.z) = D(h) / (2 (wo.z + |(ax wox, ay woy,
    /// woz)|))` (Heitz 2018; Dupuy and Benyoub 2023).
    ///
    /// The density is [`ggx_reflect_pdf`](super::ggx_reflect_pdf) evaluated at the returned `wi` (bit for bit), so a
    /// renderer's MIS weights agree whichever way a direction was found. `wi` may lie below
    /// the horizon (the integrand is 0 there; the fraction grows with `alpha` and towards
    /// grazing: see `docs/warps.md`, and [`ggx_reflect_bounded`](super::ggx_reflect_bounded) for fewer of them). `wi` is
    /// unit within 1e-6 (measured 5.3e-7). Out of domain: the [module docs](super).
    pub fn ggx_reflect, ggx_reflect_x8, ggx_reflect_x16 [sampler];
    pub fn ggx_reflect_slice [sampler];
    /// The density of [`ggx_reflect`](super::ggx_reflect) per steradian of `wi`: with the half vector `h = wo/|wo|
    /// + wi/|wi|`, `D(h) / (2 (wo.z + |(ax wox, ay woy, woz)|))` (0 where `h.z <= 0`).
    /// Integrates to 1 over the sphere (`tests/microfacet.rs`, `f64` quadrature).
    ///
    /// `wi` may have any length (its direction counts); zero or non-finite: density 0. `wo` as
    /// the sampler reads it. Error against `f64` on the same `f32` inputs: within 1.2e-6
    /// relative (measured over the sweep of `docs/warps.md`: `alpha` from 1e-4 to 1, `wo.z`
    /// from 1e-6 to 1, 130,560 sampled directions). The half vector's components cancel
    /// where `wi` is near the mirror image of `wo` (and `D` magnifies their error by
    /// `1 / alpha`), so where `alpha_min wo.h < 1/8` it is formed in double `f32` (Dekker's
    /// products and Knuth's two-sum, no FMA), elsewhere in plain `f32` (error within
    /// `4.3e-7 / (alpha_min wo.h)`, at most 3.5e-6 there).
    pub fn ggx_reflect_pdf, ggx_reflect_pdf_x8, ggx_reflect_pdf_x16 [density];
    pub fn ggx_reflect_pdf_slice [density];
}
