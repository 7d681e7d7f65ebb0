//! Bounded visible normals (Eto and Tokuyoshi 2023): the caps sampler on a smaller cap, so
//! that fewer reflected directions fall below the horizon, with its own exact density.

use super::reflection_forms;

reflection_forms! {
    bounded: true;
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
    pub fn ggx_reflect_bounded, ggx_reflect_bounded_x8, ggx_reflect_bounded_x16 [sampler];
    pub fn ggx_reflect_bounded_slice [sampler];
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
    /// Arguments as [`ggx_reflect_pdf`](super::ggx_reflect_pdf), and its half vector (double `f32` where
    /// `alpha_min wo.h < 1/8`); error against `f64` within 1.3e-6 relative (measured over
    /// the sweep of `docs/warps.md`).
    pub fn ggx_reflect_bounded_pdf, ggx_reflect_bounded_pdf_x8, ggx_reflect_bounded_pdf_x16 [density];
    pub fn ggx_reflect_bounded_pdf_slice [density];
}
