//! Errors of a render against the reference: per-pixel squared error (mean over the three
//! channels), the Gaussian-filtered error a denoiser would leave, and the reference's own
//! variance in both.

use super::trace::Image;
use crate::math::Moments;

/// A Gaussian blur of standard deviation `sigma` pixels (truncated at `3 sigma`, weights
/// renormalised where the kernel leaves the image); `sigma = 0` is the identity.
pub fn blur(img: &Image, sigma: f64) -> Image {
    if sigma <= 0.0 {
        return img.clone();
    }
    let r = (3.0 * sigma).ceil() as isize;
    let k: Vec<f64> = (-r..=r)
        .map(|i| (-(i * i) as f64 / (2.0 * sigma * sigma)).exp())
        .collect();
    let (w, h) = (img.width as isize, img.height as isize);
    let pass = |src: &Image, dx: isize, dy: isize| {
        let mut out = Image::new(src.width, src.height);
        for y in 0..h {
            for x in 0..w {
                let (mut acc, mut norm) = ([0.0; 3], 0.0);
                for (j, &kw) in k.iter().enumerate() {
                    let o = j as isize - r;
                    let (sx, sy) = (x + o * dx, y + o * dy);
                    if sx < 0 || sy < 0 || sx >= w || sy >= h {
                        continue;
                    }
                    let p = src.px[(sy * w + sx) as usize];
                    for c in 0..3 {
                        acc[c] += kw * p[c];
                    }
                    norm += kw;
                }
                out.px[(y * w + x) as usize] = acc.map(|a| a / norm);
            }
        }
        out
    };
    pass(&pass(img, 1, 0), 0, 1)
}

/// `a - b`, pixel by pixel.
pub fn diff(a: &Image, b: &Image) -> Image {
    let mut out = a.clone();
    for (o, q) in out.px.iter_mut().zip(&b.px) {
        for c in 0..3 {
            o[c] -= q[c];
        }
    }
    out
}

/// Per pixel, the mean over channels of the squared value.
pub fn squares(e: &Image) -> Vec<f64> {
    e.px.iter()
        .map(|p| (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / 3.0)
        .collect()
}

/// Mean and its standard error over the values (independent).
pub fn mean_se(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let var = v.iter().map(|x| (x - m) * (x - m)).sum::<f64>() / (n - 1.0).max(1.0);
    (m, (var / n).sqrt())
}

/// Running sums over the pixels of all frames of one (scene, sampler, spp).
#[derive(Clone, Copy, Default, Debug)]
pub struct PixelStats {
    /// Of the mean over channels of the error.
    pub e: Moments,
    /// Of the mean over channels of the squared error.
    pub sq: Moments,
}

impl PixelStats {
    pub fn add_frame(&mut self, err: &Image) {
        for p in &err.px {
            self.e.add((p[0] + p[1] + p[2]) / 3.0);
            self.sq.add((p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) / 3.0);
        }
    }
    pub fn merge(&mut self, o: &PixelStats) {
        self.e.merge(&o.e);
        self.sq.merge(&o.sq);
    }
    /// Uncorrected MSE and its standard error (pixels independent).
    pub fn mse(&self) -> (f64, f64) {
        self.sq.mean_se()
    }
    /// Mean error and its standard error.
    pub fn bias(&self) -> (f64, f64) {
        self.e.mean_se()
    }
}
