//! [`Distribution`]: what both environment-map distributions offer, so that a renderer can be
//! generic over them, and the inherent methods that forward to it.

use super::{Sample, SampleX8, SampleX16, scalar_sample, simd_sample, simd16_sample, slices};
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
    };
}
pub(super) use inherent_methods;
