//! The GGX distribution of normals `D` and Smith's masking `G1` and height-correlated
//! masking-shadowing `G2`, on alpha-scaled vectors (no `alpha^4` underflow).

use super::{Rough, rough, scaled, slice_form, split32, split332};
use crate::lanes::Lane;
use crate::vec3::{V, norm};

#[inline(always)]
fn d_body<L: Lane>(m: V<L>, alpha: [L; 2]) -> L {
    let (m, ok) = scaled(m);
    L::select(ok, rough(alpha).d(m).0, L::splat(0.0))
}

/// `|stretch(w)| / |w.z|` of `w` made scale-free (`+inf` at `w.z = 0`; 1 for an invalid `w`,
/// read as `+z`): `2 / G1(w) - 1`, i.e. `1 + 2 Lambda(w)`.
#[inline(always)]
fn lambda_term<L: Lane>(r: &Rough<L>, w: V<L>) -> L {
    let (s, ok) = scaled([w[0], w[1], w[2].abs()]);
    L::select(ok, norm(r.stretch(s)) / s[2], L::splat(1.0))
}

#[inline(always)]
fn g1_body<L: Lane>(w: V<L>, alpha: [L; 2]) -> L {
    let two = L::splat(2.0);
    two / (L::splat(1.0) + lambda_term(&rough(alpha), w))
}

#[inline(always)]
fn g2_body<L: Lane>(wo: V<L>, wi: V<L>, alpha: [L; 2]) -> L {
    let r = rough(alpha);
    L::splat(2.0) / (lambda_term(&r, wo) + lambda_term(&r, wi))
}

lane_forms! {
    /// The GGX (Trowbridge-Reitz) distribution of normals per steradian of `m`:
    /// `D(m) = 1 / (pi ax ay ((mx/ax)^2 + (my/ay)^2 + mz^2)^2)` for unit `m` with `mz > 0`,
    /// 0 for `mz <= 0` (Trowbridge and Reitz 1975; Walter, Marschner, Li and Torrance 2007).
    /// Normalised: `integral D(m) mz dm = 1`.
    ///
    /// Evaluated on `m` of any length as `(|m|^2 / |(mx/ax, my/ay, mz)|^2)^2 / (pi ax ay)`
    /// (only the direction of `m` counts), so nothing below `1e-8` is formed at `alpha = 1e-4`
    /// and nothing overflows. `alpha` clamped to `[1e-4, 1]`; a zero or non-finite `m` gives 0
    /// (see the [module docs](super)). Error against `f64`: see `docs/warps.md`
    /// (within 1e-6 relative, measured 7.0e-7, over `alpha` in `[1e-4, 1]` and every direction).
    pub fn ggx_d, ggx_d_x8, ggx_d_x16 ["(normal, roughness) pairs"]
        (m: [L; 3], alpha: [L; 2]) -> L = d_body;
}

lane_forms! {
    /// Smith's masking function for GGX: `G1(w) = 1 / (1 + Lambda(w))
    /// = 2 |wz| / (|wz| + |(ax wx, ay wy, wz)|)` (Smith 1967; Heitz 2014, "Understanding the
    /// Masking-Shadowing Function in Microfacet-Based BRDFs", JCGT 3(2)), for `w` of any length
    /// (only its direction counts).
    ///
    /// `w` below the horizon is read as its mirror image (`|wz|`, pbrt-v4's convention); at
    /// `wz = 0` it is 0; a zero or non-finite `w` is read as `+z` (1). `alpha` clamped to
    /// `[1e-4, 1]`. Error against `f64`: within 1e-6 relative (measured 2.1e-7).
    pub fn ggx_g1, ggx_g1_x8, ggx_g1_x16 ["(direction, roughness) pairs"]
        (w: [L; 3], alpha: [L; 2]) -> L = g1_body;
}

lane_forms! {
    /// The height-correlated Smith masking-shadowing function for GGX:
    /// `G2(wo, wi) = 1 / (1 + Lambda(wo) + Lambda(wi))` (Heitz 2014), evaluated as
    /// `2 / (|stretch(wo)| / |wo.z| + |stretch(wi)| / |wi.z|)` with `stretch(w) = (ax wx,
    /// ay wy, wz)` of the scale-free vectors.
    ///
    /// Both directions are read as [`ggx_g1`](super::ggx_g1) reads them (mirrored; 0 where either is
    /// grazing; invalid ones as `+z`). It does not test that `wi` is on `wo`'s side of the
    /// surface: a reflection BSDF is 0 there anyway. Error against `f64`: within 1e-6
    /// relative (measured 2.4e-7).
    pub fn ggx_g2, ggx_g2_x8, ggx_g2_x16 ["(direction, direction, roughness) triples"]
        (wo: [L; 3], wi: [L; 3], alpha: [L; 2]) -> L = g2_body;
}

slice_form! {
    /// [`ggx_d`](super::ggx_d) over a batch of packed `[mx, my, mz, ax, ay]`: `out[i] = [ggx_d(..)]`.
    /// Bit-identical to the scalar form.
    pub fn ggx_d_slice [5 -> 1] = |x| {
        let (m, a) = split32(x);
        [d_body(m, a)]
    };
}

slice_form! {
    /// [`ggx_g1`](super::ggx_g1) over a batch of packed `[wx, wy, wz, ax, ay]`. Bit-identical to the scalar
    /// form.
    pub fn ggx_g1_slice [5 -> 1] = |x| {
        let (w, a) = split32(x);
        [g1_body(w, a)]
    };
}

slice_form! {
    /// [`ggx_g2`](super::ggx_g2) over a batch of packed `[wo, wi, alpha]` (8 floats). Bit-identical to the
    /// scalar form.
    pub fn ggx_g2_slice [8 -> 1] = |x| {
        let (wo, wi, a) = split332(x);
        [g2_body(wo, wi, a)]
    };
}
