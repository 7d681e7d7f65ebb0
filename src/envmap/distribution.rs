//! [`Distribution`]: what both environment-map distributions offer, so that a renderer can be
//! generic over them, and the inherent methods that forward to it.

use super::direction::{CHUNK, direction_of, solid_angle_of, uv_of};
use super::{
    DirectionSample, Layout, Sample, SampleX8, SampleX16, scalar_sample, simd_sample,
    simd16_sample, slices,
};
use wide::{f32x8, f32x16};

/// A 2D distribution over an image's texels: [`Hierarchical`](super::Hierarchical) and
/// [`MarginalConditional`](super::MarginalConditional) (see the [module docs](super) for the
/// guarantees every method keeps).
///
/// Every method is provided: each runs the distribution's one generic body at its width, so
/// `sample`, `sample_x8`, `sample_x16` and `sample_slice` (and the `pdf` forms) give the
/// same bits. The trait is sealed (its supertrait is private): a renderer can be generic
/// over it, but not implement it. Both types also have every method as an inherent method,
/// callable without importing the trait, which forwards here.
///
/// ```
/// use warpcore::envmap::{Distribution, Hierarchical, MarginalConditional, Word};
///
/// /// An estimate of the map's integral of `f` over the unit square, by importance sampling.
/// fn estimate<D: Distribution>(map: &D, f: impl Fn([f32; 2]) -> f32, u: &[[f32; 2]]) -> f32 {
///     u.iter().map(|&u| { let s = map.sample(u); f(s.uv) / s.pdf }).sum::<f32>() / u.len() as f32
/// }
///
/// let weights = [1.0, 3.0];
/// let mut a = vec![0 as Word; Hierarchical::storage_len(2, 1)];
/// let mut b = vec![0 as Word; MarginalConditional::storage_len(2, 1)];
/// let u = [[0.1, 0.5], [0.6, 0.5], [0.9, 0.5]];
/// let f = |uv: [f32; 2]| if uv[0] < 0.5 { 1.0 } else { 3.0 };
/// let x = estimate(&Hierarchical::new(&weights, 2, 1, &mut a)?, f, &u);
/// let y = estimate(&MarginalConditional::new(&weights, 2, 1, &mut b)?, f, &u);
/// assert!((x - 2.0).abs() < 1e-6 && (y - 2.0).abs() < 1e-6); // f proportional to the pdf
/// # Ok::<(), warpcore::envmap::Error>(())
/// ```
pub trait Distribution: slices::Body {
    /// Width of the map in texels.
    #[inline]
    fn width(&self) -> usize {
        self.size()[0] as usize
    }

    /// Height of the map in texels.
    #[inline]
    fn height(&self) -> usize {
        self.size()[1] as usize
    }

    /// Draws a texel with probability proportional to its weight and a uniform point in it.
    ///
    /// Each coordinate of `u` is first mapped onto `[0, 1 - 2^-24]` by the forward rule (NaN
    /// and negatives to 0, `>= 1` and `+inf` to `1 - 2^-24`). The pdf equals
    /// [`pdf`](Self::pdf)`(uv)` bit for bit; the texel is never a zero-weight one.
    #[inline]
    fn sample(&self, u: [f32; 2]) -> Sample {
        scalar_sample(self.sample_lanes(u))
    }

    /// [`sample`](Self::sample) on eight points at once; bit-identical to eight scalar calls.
    #[inline]
    fn sample_x8(&self, u: [f32x8; 2]) -> SampleX8 {
        simd_sample(self.sample_lanes(u))
    }

    /// [`sample`](Self::sample) on sixteen points at once; bit-identical to sixteen scalar
    /// calls. One AVX-512 register per coordinate where the build has AVX-512F; elsewhere
    /// `wide` runs two 8-lane halves.
    #[inline]
    fn sample_x16(&self, u: [f32x16; 2]) -> SampleX16 {
        simd16_sample(self.sample_lanes(u))
    }

    /// [`sample`](Self::sample) over a batch: `out[i] = sample(u[i])` for
    /// `i < min(u.len(), out.len())`; returns that count. Bit-identical to the scalar form.
    /// Runs several groups of eight lanes interleaved, so that their table reads overlap
    /// (see the distribution's docs for how many).
    #[inline]
    fn sample_slice(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize {
        self.slice_sample(u, out)
    }

    /// Density at `uv` with respect to area on `[0, 1]^2`: `P(texel) * width * height` for
    /// the texel holding `uv` (0 on zero-weight texels). `uv` is clamped by the forward rule.
    #[inline]
    fn pdf(&self, uv: [f32; 2]) -> f32 {
        self.pdf_lanes(uv)
    }

    /// [`pdf`](Self::pdf) on eight points at once; bit-identical to eight scalar calls.
    #[inline]
    fn pdf_x8(&self, uv: [f32x8; 2]) -> f32x8 {
        self.pdf_lanes(uv)
    }

    /// [`pdf`](Self::pdf) on sixteen points at once; bit-identical to sixteen scalar calls.
    #[inline]
    fn pdf_x16(&self, uv: [f32x16; 2]) -> f32x16 {
        self.pdf_lanes(uv)
    }

    /// [`pdf`](Self::pdf) over a batch, with the length rule of
    /// [`sample_slice`](Self::sample_slice).
    #[inline]
    fn pdf_slice(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
        self.slice_pdf(uv, out)
    }

    /// [`sample`](Self::sample) as a direction and its density **per steradian**: the map's
    /// `uv` laid over the sphere by `layout` ([`sphere::equirect`](crate::sphere::equirect) or
    /// [`sphere::equal_area`](crate::sphere::equal_area)), the area pdf converted by
    /// [`image::equirect_pdf_to_solid_angle`](super::image::equirect_pdf_to_solid_angle)`(pdf,
    /// uv[1])` (the point's own `sin theta`; 0 exactly at the pole, where the sample should be
    /// discarded) or [`equal_area_pdf_to_solid_angle`](crate::sphere::equal_area_pdf_to_solid_angle)
    /// (`pdf / (4 pi)`). The weights must be of that layout (for equirect, made by
    /// [`image::equirect_solid_angle_weights`](super::image::equirect_solid_angle_weights) to
    /// sample by radiance times solid angle).
    ///
    /// ```
    /// use warpcore::envmap::{Hierarchical, Layout, Word};
    ///
    /// let mut storage = vec![0 as Word; Hierarchical::storage_len(4, 4)];
    /// let map = Hierarchical::new(&[1.0; 16], 4, 4, &mut storage)?; // equal-area, constant
    /// let s = map.sample_direction(Layout::EqualArea, [0.3, 0.8]);
    /// assert!((s.pdf - 1.0 / (4.0 * core::f32::consts::PI)).abs() < 1e-7); // uniform on the sphere
    /// assert_eq!(map.pdf_direction(Layout::EqualArea, s.dir), s.pdf);
    /// # Ok::<(), warpcore::envmap::Error>(())
    /// ```
    #[inline]
    fn sample_direction(&self, layout: Layout, u: [f32; 2]) -> DirectionSample {
        direction_of(layout, self.sample(u))
    }

    /// [`sample_direction`](Self::sample_direction) over a batch: `out[i] =
    /// sample_direction(layout, u[i])` for `i < min(u.len(), out.len())`; returns that count.
    /// Bit-identical to the scalar form (the samples come from
    /// [`sample_slice`](Self::sample_slice), 64 at a time).
    fn sample_direction_slice(
        &self,
        layout: Layout,
        u: &[[f32; 2]],
        out: &mut [DirectionSample],
    ) -> usize {
        let n = u.len().min(out.len());
        let (u, out) = (
            u.get(..n).unwrap_or(&[]),
            out.get_mut(..n).unwrap_or(&mut []),
        );
        let mut buf = [Sample::default(); CHUNK];
        for (u, out) in u.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let tmp = buf.get_mut(..u.len()).unwrap_or(&mut []);
            let k = self.sample_slice(u, tmp);
            for (o, s) in out.iter_mut().zip(tmp.iter().take(k)) {
                *o = direction_of(layout, *s);
            }
        }
        n
    }

    /// Density **per steradian** with which [`sample_direction`](Self::sample_direction)
    /// returns the direction `dir` (any length; the layout's inverse maps it to `uv`, then
    /// [`pdf`](Self::pdf)`(uv)` is converted at `dir` by
    /// [`sphere::equirect_pdf_to_solid_angle`](crate::sphere::equirect_pdf_to_solid_angle) or
    /// [`sphere::equal_area_pdf_to_solid_angle`](crate::sphere::equal_area_pdf_to_solid_angle)):
    /// the MIS weight of a direction found by BSDF sampling. For a sampled direction it
    /// equals the sample's `pdf` up to a few ulp (the conversion's `sin theta` from `dir`
    /// rather than `v`), except where rounding in the inverse puts `dir` on the neighbouring
    /// texel (directions within an ulp of a texel edge). Total: NaN directions and
    /// directions on the equirect axis give 0 or a finite value, never NaN.
    #[inline]
    fn pdf_direction(&self, layout: Layout, dir: [f32; 3]) -> f32 {
        solid_angle_of(layout, self.pdf(uv_of(layout, dir)), dir)
    }

    /// [`pdf_direction`](Self::pdf_direction) over a batch, with the length rule of
    /// [`sample_slice`](Self::sample_slice); bit-identical to the scalar form.
    fn pdf_direction_slice(&self, layout: Layout, dir: &[[f32; 3]], out: &mut [f32]) -> usize {
        let n = dir.len().min(out.len());
        let (dir, out) = (
            dir.get(..n).unwrap_or(&[]),
            out.get_mut(..n).unwrap_or(&mut []),
        );
        let mut uv = [[0.0f32; 2]; CHUNK];
        for (d, out) in dir.chunks(CHUNK).zip(out.chunks_mut(CHUNK)) {
            let uv = uv.get_mut(..d.len()).unwrap_or(&mut []);
            for (p, &d) in uv.iter_mut().zip(d) {
                *p = uv_of(layout, d);
            }
            let k = self.pdf_slice(uv, out);
            for (o, &d) in out.iter_mut().zip(d).take(k) {
                *o = solid_angle_of(layout, *o, d);
            }
        }
        n
    }
}

/// The inherent forms of [`Distribution`]'s methods (callable without importing the trait),
/// each forwarding to the trait: one definition for both distributions.
macro_rules! inherent_methods {
    () => {
        /// Width of the map in texels.
        #[inline]
        pub fn width(&self) -> usize {
            super::Distribution::width(self)
        }

        /// Height of the map in texels.
        #[inline]
        pub fn height(&self) -> usize {
            super::Distribution::height(self)
        }

        /// Draws a texel with probability proportional to its weight and a uniform point in
        /// it: [`Distribution::sample`](super::Distribution::sample).
        #[inline]
        pub fn sample(&self, u: [f32; 2]) -> super::Sample {
            super::Distribution::sample(self, u)
        }

        /// [`Distribution::sample_x8`](super::Distribution::sample_x8): eight points,
        /// bit-identical to eight scalar calls.
        #[inline]
        pub fn sample_x8(&self, u: [wide::f32x8; 2]) -> super::SampleX8 {
            super::Distribution::sample_x8(self, u)
        }

        /// [`Distribution::sample_x16`](super::Distribution::sample_x16): sixteen points,
        /// bit-identical to sixteen scalar calls.
        #[inline]
        pub fn sample_x16(&self, u: [wide::f32x16; 2]) -> super::SampleX16 {
            super::Distribution::sample_x16(self, u)
        }

        /// [`Distribution::sample_slice`](super::Distribution::sample_slice): a batch,
        /// bit-identical to the scalar form; returns the count written.
        #[inline]
        pub fn sample_slice(&self, u: &[[f32; 2]], out: &mut [super::Sample]) -> usize {
            super::Distribution::sample_slice(self, u, out)
        }

        /// Density at `uv` with respect to area on `[0, 1]^2`:
        /// [`Distribution::pdf`](super::Distribution::pdf).
        #[inline]
        pub fn pdf(&self, uv: [f32; 2]) -> f32 {
            super::Distribution::pdf(self, uv)
        }

        /// [`Distribution::pdf_x8`](super::Distribution::pdf_x8): eight points.
        #[inline]
        pub fn pdf_x8(&self, uv: [wide::f32x8; 2]) -> wide::f32x8 {
            super::Distribution::pdf_x8(self, uv)
        }

        /// [`Distribution::pdf_x16`](super::Distribution::pdf_x16): sixteen points.
        #[inline]
        pub fn pdf_x16(&self, uv: [wide::f32x16; 2]) -> wide::f32x16 {
            super::Distribution::pdf_x16(self, uv)
        }

        /// [`Distribution::pdf_slice`](super::Distribution::pdf_slice): a batch.
        #[inline]
        pub fn pdf_slice(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
            super::Distribution::pdf_slice(self, uv, out)
        }

        /// A direction and its density per steradian:
        /// [`Distribution::sample_direction`](super::Distribution::sample_direction).
        #[inline]
        pub fn sample_direction(
            &self,
            layout: super::Layout,
            u: [f32; 2],
        ) -> super::DirectionSample {
            super::Distribution::sample_direction(self, layout, u)
        }

        /// [`Distribution::sample_direction_slice`](super::Distribution::sample_direction_slice):
        /// a batch, bit-identical to the scalar form; returns the count written.
        #[inline]
        pub fn sample_direction_slice(
            &self,
            layout: super::Layout,
            u: &[[f32; 2]],
            out: &mut [super::DirectionSample],
        ) -> usize {
            super::Distribution::sample_direction_slice(self, layout, u, out)
        }

        /// The density per steradian of a direction:
        /// [`Distribution::pdf_direction`](super::Distribution::pdf_direction).
        #[inline]
        pub fn pdf_direction(&self, layout: super::Layout, dir: [f32; 3]) -> f32 {
            super::Distribution::pdf_direction(self, layout, dir)
        }

        /// [`Distribution::pdf_direction_slice`](super::Distribution::pdf_direction_slice):
        /// a batch.
        #[inline]
        pub fn pdf_direction_slice(
            &self,
            layout: super::Layout,
            dir: &[[f32; 3]],
            out: &mut [f32],
        ) -> usize {
            super::Distribution::pdf_direction_slice(self, layout, dir, out)
        }
    };
}
pub(super) use inherent_methods;
