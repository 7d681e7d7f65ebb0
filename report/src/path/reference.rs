//! The path scenes' references: two independent half renders `A` and `B` with the
//! reference's own random stream ([`ReferenceRandom`], keyed apart from every tested
//! sampler), cached under `docs/report/` as half floats (`path-<scene>.ref`).
//!
//! The reference is `R = (A + B) / 2`. Its own variance per pixel and channel is estimated by
//! `((A - B) / 2)^2` (unbiased: `E[(A - B)^2] = 2 var(A)`, `var(R) = var(A) / 2`), and a
//! render's MSE against `R` is corrected by subtracting its mean. After a blur `G` the same
//! holds for `G A` and `G B`.
//!
//! File: the line `warpcore-path-ref 1 <width> <height> <spp per half> <seconds>`, then `A`
//! and `B` as little-endian IEEE half floats, RGB, row-major (`2 x 3 x width x height x 2`
//! bytes: 48 KiB at 64 x 64).

use super::samplers::ReferenceRandom;
use super::scene::Scene;
use super::trace::{Image, render_parallel};
use std::path::{Path, PathBuf};

pub struct Reference {
    pub a: Image,
    pub b: Image,
    pub spp_per_half: u32,
    /// Wall-clock seconds the render took (on the machine that made it).
    pub seconds: f64,
}

/// The seeds of the halves (the reference stream hashes them with its own 64-bit key).
const SEEDS: [u32; 2] = [0x5eed_a11a, 0x5eed_b22b];

impl Reference {
    pub fn render(scene: &Scene, spp_per_half: u32, threads: usize) -> Reference {
        let t = std::time::Instant::now();
        let [a, b] =
            SEEDS.map(|seed| render_parallel(scene, &ReferenceRandom, spp_per_half, seed, threads));
        Reference {
            a,
            b,
            spp_per_half,
            seconds: t.elapsed().as_secs_f64(),
        }
    }

    /// Both halves averaged over `f x f` pixel blocks (`f = 1`: unchanged).
    pub fn downsample(self, f: usize) -> Reference {
        if f <= 1 {
            return self;
        }
        let down = |im: &Image| {
            let (w, h) = (im.width / f, im.height / f);
            let mut out = Image::new(w, h);
            for y in 0..h * f {
                for x in 0..w * f {
                    let p = im.px[y * im.width + x];
                    let o = &mut out.px[(y / f) * w + x / f];
                    for c in 0..3 {
                        o[c] += p[c] / (f * f) as f64;
                    }
                }
            }
            out
        };
        Reference {
            a: down(&self.a),
            b: down(&self.b),
            ..self
        }
    }

    /// `(A + B) / 2`.
    pub fn mean(&self) -> Image {
        self.combine(|a, b| 0.5 * (a + b))
    }

    /// `(A - B) / 2`: its square estimates the variance of [`Reference::mean`].
    pub fn half_difference(&self) -> Image {
        self.combine(|a, b| 0.5 * (a - b))
    }

    fn combine(&self, f: impl Fn(f64, f64) -> f64) -> Image {
        let mut out = self.a.clone();
        for (o, b) in out.px.iter_mut().zip(&self.b.px) {
            for c in 0..3 {
                o[c] = f(o[c], b[c]);
            }
        }
        out
    }

    pub fn path(dir: &Path, scene: &str) -> PathBuf {
        dir.join(format!("path-{scene}.ref"))
    }

    pub fn to_bytes(&self) -> Vec<u8> {
        let mut v = format!(
            "warpcore-path-ref 1 {} {} {} {:.1}\n",
            self.a.width, self.a.height, self.spp_per_half, self.seconds
        )
        .into_bytes();
        for img in [&self.a, &self.b] {
            for p in &img.px {
                for &c in p {
                    v.extend_from_slice(&f16_bits(c as f32).to_le_bytes());
                }
            }
        }
        v
    }

    pub fn from_bytes(bytes: &[u8]) -> Result<Reference, String> {
        let nl = bytes
            .iter()
            .position(|&b| b == b'\n')
            .ok_or("no header line")?;
        let head = std::str::from_utf8(&bytes[..nl]).map_err(|_| "header not UTF-8")?;
        let f: Vec<&str> = head.split_whitespace().collect();
        if f.len() != 6 || f[0] != "warpcore-path-ref" || f[1] != "1" {
            return Err(format!("not a path reference (header {head:?})"));
        }
        let num = |s: &str| s.parse::<usize>().map_err(|_| format!("bad number {s:?}"));
        let (w, h, spp) = (num(f[2])?, num(f[3])?, num(f[4])?);
        let seconds = f[5].parse::<f64>().map_err(|_| "bad seconds")?;
        let data = &bytes[nl + 1..];
        if w == 0 || h == 0 || w > 4096 || h > 4096 || data.len() != 2 * 3 * w * h * 2 {
            return Err(format!("size mismatch: {w} x {h} and {} bytes", data.len()));
        }
        let mut it = data
            .chunks_exact(2)
            .map(|c| f16_value(u16::from_le_bytes([c[0], c[1]])) as f64);
        let mut img = || {
            let mut im = Image::new(w, h);
            for p in im.px.iter_mut() {
                for c in p.iter_mut() {
                    *c = it.next().unwrap_or(f64::NAN);
                }
            }
            im
        };
        let (a, b) = (img(), img());
        if a.px.iter().chain(&b.px).flatten().any(|c| !c.is_finite()) {
            return Err("non-finite value".into());
        }
        Ok(Reference {
            a,
            b,
            spp_per_half: spp as u32,
            seconds,
        })
    }
}

/// IEEE binary16 bits of `x`, rounded to nearest even (overflow to infinity).
pub fn f16_bits(x: f32) -> u16 {
    let b = x.to_bits();
    let sign = ((b >> 16) & 0x8000) as u16;
    let e = ((b >> 23) & 0xff) as i32;
    let m = b & 0x7f_ffff;
    if e == 255 {
        return sign | 0x7c00 | if m != 0 { 0x200 } else { 0 };
    }
    let e16 = e - 127 + 15;
    if e16 >= 31 {
        return sign | 0x7c00;
    }
    let round = |r: u32, rem: u32, half: u32| {
        if rem > half || (rem == half && r & 1 == 1) {
            r + 1
        } else {
            r
        }
    };
    if e16 <= 0 {
        if e16 < -10 {
            return sign;
        }
        let m = m | 0x80_0000;
        let shift = (14 - e16) as u32;
        let r = round(m >> shift, m & ((1 << shift) - 1), 1 << (shift - 1));
        return sign | r as u16;
    }
    let r = round(((e16 as u32) << 10) | (m >> 13), m & 0x1fff, 0x1000);
    sign | r as u16
}

/// The value of IEEE binary16 bits `h`.
pub fn f16_value(h: u16) -> f32 {
    let sign = ((h & 0x8000) as u32) << 16;
    let e = ((h >> 10) & 0x1f) as u32;
    let m = (h & 0x3ff) as u32;
    let mag = match e {
        0 => m as f32 * (1.0 / (1u32 << 24) as f32),
        31 => {
            if m == 0 {
                f32::INFINITY
            } else {
                f32::NAN
            }
        }
        _ => f32::from_bits(((e + 112) << 23) | (m << 13)),
    };
    f32::from_bits(sign | mag.to_bits())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_floats_round_to_nearest() {
        // Exactly representable values round-trip; others land within half an ulp (2^-11
        // relative for normals, 2^-25 absolute for subnormals).
        for &x in &[
            0.0f32,
            1.0,
            0.5,
            65504.0,
            6.1035156e-5,
            5.9604645e-8,
            1.5,
            17.0,
        ] {
            assert_eq!(f16_value(f16_bits(x)), x, "{x}");
        }
        let mut x = 1e-7f32;
        while x < 6e4 {
            let y = f16_value(f16_bits(x));
            let tol = (x * 2f32.powi(-11)).max(2f32.powi(-25)) * 1.0001;
            assert!((y - x).abs() <= tol, "{x} -> {y}");
            x *= 1.013;
        }
        assert_eq!(f16_value(f16_bits(1e6)), f32::INFINITY);
        assert_eq!(f16_bits(1.0 + 2f32.powi(-11)), 0x3c00); // tie to even
        assert_eq!(f16_bits(1.0 + 3.0 * 2f32.powi(-11)), 0x3c02);
    }

    #[test]
    fn reference_files_round_trip_and_refuse_garbage() {
        let s = Scene::by_name("cornell", 4).unwrap();
        let r = Reference::render(&s, 2, 1);
        let back = Reference::from_bytes(&r.to_bytes()).unwrap();
        for (x, y) in r.a.px.iter().flatten().zip(back.a.px.iter().flatten()) {
            assert!((x - y).abs() <= x.abs() * 1e-3 + 1e-7);
        }
        assert!(Reference::from_bytes(b"nonsense").is_err());
        let mut bytes = r.to_bytes();
        bytes.pop();
        assert!(Reference::from_bytes(&bytes).is_err());
    }
}
