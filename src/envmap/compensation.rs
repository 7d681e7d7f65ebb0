//! MIS compensation: subtract (a fraction of) the map's average before building the tables.
//!
//! A renderer that combines environment-map sampling with BSDF sampling by multiple
//! importance sampling already covers the map's dim, nearly constant part well with the BSDF
//! samples; the map's samples are better spent on what stands out. Karlik, Sik, Vevoda,
//! Skrivan and Krivanek (2019), "MIS Compensation: Optimizing Sampling Techniques in Multiple
//! Importance Sampling" (ACM TOG 38(6)), show that sampling by `max(0, L - avg(L))` instead
//! of `L` lowers the variance of the MIS combination; pbrt-v4's `ImageInfiniteLight`
//! (`compensatedDistribution`) and Mitsuba 3's `envmap` (`mis_compensation`) build exactly
//! that table. The pdf both distributions report is then the compensated one, which is what
//! the MIS weights must use (the map is still evaluated as `L`).
//!
//! Rules here: weights are cleaned first (NaN, negatives, `-inf` as 0; `+inf` is
//! [`Error::InfiniteWeight`]); the average is over solid angle ([`Compensation::Equirect`]
//! divides out the rows' `sin(theta)`); the compensated weight is `max(0, w - fraction *
//! average * factor)`, computed in `f64`. When that removes everything (a constant map with
//! `fraction >= 1`, an all-zero map), the build **falls back to the uncompensated weights**
//! (the map is then best sampled as it is; pbrt-v4 falls back to uniform instead, which loses
//! the map's shape entirely when it is not constant), so a compensated build never fails
//! where an uncompensated one succeeds.

use super::{Error, clean, image};

/// How [`Hierarchical::new_compensated`](super::Hierarchical::new_compensated) and
/// [`MarginalConditional::new_compensated`](super::MarginalConditional::new_compensated)
/// compensate the weights for multiple importance sampling.
///
/// A renderer that combines env-map sampling with BSDF sampling by MIS should sample the map by
/// `max(0, L - avg L)` (Karlik, Sik, Vevoda, Skrivan and Krivanek 2019, "MIS Compensation:
/// Optimizing Sampling Techniques in Multiple Importance Sampling", ACM TOG 38(6); pbrt-v4's
/// `compensatedDistribution`, Mitsuba 3's `mis_compensation`): the BSDF samples already cover
/// the map's dim, flat part. The pdf the distribution reports is the compensated one (use it
/// in the MIS weights; the map is still evaluated as `L`). Weights are cleaned first (NaN,
/// negatives as 0; `+inf` is [`Error::InfiniteWeight`]); the subtraction is in `f64`. When
/// compensation would remove every texel (a constant map, an all-zero map, `+inf`), the
/// build falls back to the weights as given — bit for bit `new` (pbrt-v4 falls back to
/// uniform instead).
///
/// `fraction` is how much of the average to subtract: `1.0` is pbrt-v4's and Mitsuba 3's
/// choice. NaN, zero and negative fractions mean no compensation; `+inf` removes everything,
/// so the build falls back to the uncompensated weights.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Compensation {
    /// The weights as given (what `new` builds).
    #[default]
    None,
    /// Every texel covers the same solid angle (an equal-area map, or any image sampled by
    /// area): `w' = max(0, w - fraction * mean(w))`.
    Uniform(f32),
    /// An equirect (lat-long) map whose weights are radiance times the row's `sin(theta)`, as
    /// [`image::equirect_solid_angle_weights`] makes them: the radiance's solid-angle average
    /// `a = sum(w) / sum(sin(theta_row))` (over all texels) is subtracted from the radiance,
    /// `w' = max(0, w - fraction * a * sin(theta_row))`, `theta_row = pi (row + 1/2) / height`.
    Equirect(f32),
}

/// An active compensation: what to subtract from each cleaned weight.
#[derive(Clone, Copy, Debug)]
pub(super) struct Compensator {
    /// `fraction * average`.
    sub: f64,
    latlong: bool,
    height: usize,
}

impl Compensator {
    /// The compensation of `weights` (`width x height`), or `None` when it is off or would
    /// remove every weight (the fallback). Errors: [`Error::InfiniteWeight`].
    pub(super) fn new(
        weights: &[f32],
        width: usize,
        height: usize,
        how: Compensation,
    ) -> Result<Option<Self>, Error> {
        let (fraction, latlong) = match how {
            Compensation::None => return Ok(None),
            Compensation::Uniform(f) => (f, false),
            Compensation::Equirect(f) => (f, true),
        };
        // NaN, zero and negative fractions: no compensation.
        if fraction.is_nan() || fraction <= 0.0 {
            return Ok(None);
        }
        let mut total = 0.0f64;
        for (index, &x) in weights.iter().enumerate() {
            if x == f32::INFINITY {
                return Err(Error::InfiniteWeight { index });
            }
            total += f64::from(clean(x));
        }
        // The measure the average is taken over: texels, or texels times their row's sine.
        let measure = if latlong {
            (0..height).map(|r| row_factor(r, height)).sum::<f64>() * width as f64
        } else {
            (width as f64) * (height as f64)
        };
        let c = Compensator {
            sub: f64::from(fraction) * (total / measure),
            latlong,
            height,
        };
        // Anything left? (Otherwise, and for a NaN `sub` from an all-zero map, fall back.)
        let left = weights
            .chunks_exact(width.max(1))
            .enumerate()
            .any(|(r, row)| row.iter().any(|&x| c.apply(clean(x), r) > 0.0));
        Ok(left.then_some(c))
    }

    /// The largest compensated weight of `weights` (`width` per row): one pass. Positive for
    /// an active compensation (`new` returns `None` when nothing is left).
    pub(super) fn max(&self, weights: &[f32], width: usize) -> f64 {
        weights
            .chunks_exact(width.max(1))
            .enumerate()
            .fold(0.0, |m, (r, row)| {
                row.iter().fold(m, |m, &x| {
                    let v = self.apply(clean(x), r);
                    if v > m { v } else { m }
                })
            })
    }

    /// The compensated weight of a cleaned weight `x` in row `row`: `max(0, x - sub * factor)`.
    #[inline]
    pub(super) fn apply(&self, x: f32, row: usize) -> f64 {
        let factor = if self.latlong {
            row_factor(row, self.height)
        } else {
            1.0
        };
        let v = f64::from(x) - self.sub * factor;
        if v > 0.0 { v } else { 0.0 }
    }
}

/// `sin(theta)` at row `r`'s centre, as [`image::equirect_solid_angle_weights`] computes it.
fn row_factor(r: usize, height: usize) -> f64 {
    let v = ((r as f64 + 0.5) / height as f64) as f32;
    f64::from(image::row_sine(v))
}
