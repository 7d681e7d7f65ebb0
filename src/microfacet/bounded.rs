//! Bounded visible normals (Eto and Tokuyoshi 2023): the caps sampler on a smaller cap, so
//! that fewer reflected directions fall below the horizon, with its own exact density.

use super::{packed4, reflect_pdf, reflect_sample, slice_form, split322, split332};
use crate::lanes::Lane;
use crate::vec3::V;

#[inline(always)]
fn sample_body<L: Lane>(wo: V<L>, alpha: [L; 2], u: [L; 2]) -> (V<L>, L) {
    reflect_sample(wo, alpha, u, true)
}

#[inline(always)]
fn pdf_body<L: Lane>(wo: V<L>, wi: V<L>, alpha: [L; 2]) -> L {
    reflect_pdf(wo, wi, alpha, true)
}

lane_forms! {
    /// A reflected direction by bounded visible normals (Eto and Tokuyoshi 2023, "Bounded
    /// VNDF Sampling for Smith-GGX Reflections", SIGGRAPH Asia technical communications):
    /// [`ggx_reflect`](super::ggx_reflect) with the standard-space cap `z >= -i.z` shrunk to `z >= -k i.z`,
    /// `k = (1 - a^2) s^2 / (s^2 + a^2 wo.z^2)`, `a = min(ax, ay)`, `s = 1 + |wo.xy|`. The
    /// removed part of the cap holds only normals whose reflections are below the horizon, so
    /// above it the density is the caps density scaled by the ratio of the caps' areas,
    /// `(1 + i.z) / (1 + k i.z)`.
    ///
    /// Returns `wi` and its density [`ggx_reflect_bounded_pdf`](super::ggx_reflect_bounded_pdf) at `wi` (bit for bit). Fewer
    /// directions below the horizon than [`ggx_reflect`](super::ggx_reflect) at every `alpha` and `wo`
    /// (`docs/warps.md` has the table); the same directions above it, with a higher density
    /// there. `1 - k` is `a^2 (s^2 + wo.z^2) / (s^2 + a^2 wo.z^2)`, free of cancellation.
    /// Out of domain: the [module docs](super).
    pub fn ggx_reflect_bounded, ggx_reflect_bounded_x8, ggx_reflect_bounded_x16
        ["(direction, roughness, sample) triples"]
        (wo: [L; 3], alpha: [L; 2], u: [L; 2]) -> ([L; 3], L) = sample_body;
}

lane_forms! {
    /// The exact density of [`ggx_reflect_bounded`](super::ggx_reflect_bounded) per steradian of `wi`:
    /// `D(h) / (2 (k wo.z + |(ax wox, ay woy, woz)|))` where `h = wo/|wo| + wi/|wi|` is the
    /// image of a point of the shrunk cap, 0 elsewhere (and where `h.z <= 0`). Derivation: the
    /// caps density is `D(h) / (2 (wo.z + t))` (`t = |(ax wox, ay woy, woz)|`, `i.z = wo.z / t`);
    /// the shrunk cap has area `2 pi (1 + k i.z)` instead of `2 pi (1 + i.z)`, so inside it the
    /// density is multiplied by `(t + wo.z) / (t + k wo.z)`. A half vector comes from the cap
    /// exactly when the standard-space reflection of `i` about `h`'s standard normal `n` has
    /// height at least `-k i.z`, i.e. `2 (wo.h) h.z >= (1 - k) wo.z |(hx/ax, hy/ay, hz)|^2`
    /// (tested with a relative slack of `2^-16`, so that rounding never puts one of the
    /// sampler's own directions outside). Integrates to 1 over the sphere (`f64` quadrature
    /// in `tests/microfacet.rs`); above the horizon it is positive wherever
    /// [`ggx_reflect_pdf`](super::ggx_reflect_pdf) is.
    ///
    /// Arguments as [`ggx_reflect_pdf`](super::ggx_reflect_pdf), with the same error against `f64`.
    pub fn ggx_reflect_bounded_pdf, ggx_reflect_bounded_pdf_x8, ggx_reflect_bounded_pdf_x16
        ["(direction, direction, roughness) triples"]
        (wo: [L; 3], wi: [L; 3], alpha: [L; 2]) -> L = pdf_body;
}

slice_form! {
    /// [`ggx_reflect_bounded`](super::ggx_reflect_bounded) over a batch of packed `[wo, alpha, u]` (7 floats):
    /// `out[i] = [wi.x, wi.y, wi.z, density]`. Bit-identical to the scalar form.
    pub fn ggx_reflect_bounded_slice [7 -> 4] = |x| {
        let (wo, a, u) = split322(x);
        packed4(sample_body(wo, a, u))
    };
}

slice_form! {
    /// [`ggx_reflect_bounded_pdf`](super::ggx_reflect_bounded_pdf) over a batch of packed `[wo, wi, alpha]` (8 floats).
    /// Bit-identical to the scalar form.
    pub fn ggx_reflect_bounded_pdf_slice [8 -> 1] = |x| {
        let (wo, wi, a) = split332(x);
        [pdf_body(wo, wi, a)]
    };
}
