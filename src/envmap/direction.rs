//! Directions and densities per steradian in one call: an environment map's sample mapped onto
//! the sphere by its layout ([`Layout::Equirect`] or [`Layout::EqualArea`]), with the density
//! converted by the crate's one set of conversions ([`image::equirect_pdf_to_solid_angle`],
//! [`sphere::equal_area_pdf_to_solid_angle`], [`sphere::equirect_pdf_to_solid_angle`]).

use super::{Sample, image};
use crate::sphere;

/// How an environment map's unit square is laid over the sphere of directions.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Layout {
    /// Equirectangular (lat-long): [`sphere::equirect`], `phi = 2 pi u`, `theta = pi v`, row 0
    /// around `+z`; `d(omega) = 2 pi^2 sin(theta) du dv`.
    #[default]
    Equirect,
    /// Clarberg's equal-area octahedral square: [`sphere::equal_area`], the centre at `+z`;
    /// `d(omega) = 4 pi du dv`.
    EqualArea,
}

/// One sample of an environment map as a direction (what `sample_direction` returns).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DirectionSample {
    /// The unit direction of the sampled point (`sphere::equirect(uv)` or
    /// `sphere::equal_area(uv)`).
    pub dir: [f32; 3],
    /// Density with respect to solid angle at `dir` (per steradian), from the texel's area
    /// density; 0 only where the conversion says so (an equirect sample exactly at the pole).
    pub pdf: f32,
    /// The point on the unit square, as [`Sample::uv`] (for filtered radiance lookups).
    pub uv: [f32; 2],
    /// `[column, row]` of the texel, as [`Sample::texel`].
    pub texel: [u32; 2],
}

/// The direction sample of an area sample: the layout's map and its density conversion
/// (equirect: with the point's own `v`, see [`image::equirect_pdf_to_solid_angle`]).
#[inline]
pub(super) fn direction_of(layout: Layout, s: Sample) -> DirectionSample {
    let (dir, pdf) = match layout {
        Layout::Equirect => (
            sphere::equirect(s.uv),
            image::equirect_pdf_to_solid_angle(s.pdf, s.uv[1]),
        ),
        Layout::EqualArea => (
            sphere::equal_area(s.uv),
            sphere::equal_area_pdf_to_solid_angle(s.pdf),
        ),
    };
    DirectionSample {
        dir,
        pdf,
        uv: s.uv,
        texel: s.texel,
    }
}

/// The point of the unit square a direction maps to under `layout` (the layout's inverse).
#[inline]
pub(super) fn uv_of(layout: Layout, dir: [f32; 3]) -> [f32; 2] {
    match layout {
        Layout::Equirect => sphere::equirect_inverse(dir),
        Layout::EqualArea => sphere::equal_area_inverse(dir),
    }
}

/// An area density at the point `dir` maps to, converted to solid angle at `dir`.
#[inline]
pub(super) fn solid_angle_of(layout: Layout, pdf: f32, dir: [f32; 3]) -> f32 {
    match layout {
        Layout::Equirect => sphere::equirect_pdf_to_solid_angle(pdf, dir),
        Layout::EqualArea => sphere::equal_area_pdf_to_solid_angle(pdf),
    }
}

/// Elements a slice form converts per step (stack buffers of this many samples).
pub(super) const CHUNK: usize = 64;
