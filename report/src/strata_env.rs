//! Strata pictures of the environment-map warps: the 16 x 16 grid of strata of the sample
//! square `[0, 1]^2`, coloured, and where each distribution sends them in its map's own
//! square (lat-long: `u` across, `v` down from `+z`; equal-area: the octahedral square, `+z`
//! at its centre, `-z` at its corners), for one map.
//!
//! Both distributions are affine inside a texel (the marginal-conditional inversion is linear
//! inside a row's and a texel's CDF interval; the hierarchical split rescales the sample at
//! each level), so a small cell of the sample square whose corners land in the same texel
//! maps onto the axis-aligned rectangle between their images: the pictures fill those
//! rectangles (subdividing cells that straddle texels), so dim regions are painted as fully
//! as bright ones. Written as PNG (one file per panel) with the map itself for orientation.

use crate::envscene::{EnvScene, Side};
use crate::sphere_ref::Param;
use crate::strata::palette_rgb;
use std::io;
use std::path::{Path, PathBuf};
use warpcore::envmap::Sample;

/// An RGB raster.
struct Raster {
    w: usize,
    h: usize,
    px: Vec<[u8; 3]>,
}

impl Raster {
    fn new(w: usize, h: usize, fill: [u8; 3]) -> Self {
        Raster {
            w,
            h,
            px: vec![fill; w * h],
        }
    }
    /// Fills the pixels overlapping `[x0, x1] x [y0, y1]` of the unit square.
    fn rect(&mut self, x0: f32, x1: f32, y0: f32, y1: f32, c: [u8; 3]) {
        let to = |x: f32, n: usize| ((x.max(0.0) * n as f32) as usize).min(n - 1);
        for y in to(y0, self.h)..=to(y1, self.h) {
            for x in to(x0, self.w)..=to(x1, self.w) {
                self.px[y * self.w + x] = c;
            }
        }
    }
    fn write(&self, path: &Path) -> io::Result<()> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        let mut enc = png::Encoder::new(file, self.w as u32, self.h as u32);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut writer = enc.write_header().map_err(io::Error::other)?;
        let bytes: Vec<u8> = self.px.iter().flatten().copied().collect();
        writer.write_image_data(&bytes).map_err(io::Error::other)?;
        writer.finish().map_err(io::Error::other)
    }
}

/// Paints the image of the sample-square cell `[a0, a1] x [b0, b1]` under `sample`.
fn cell(
    r: &mut Raster,
    sample: &dyn Fn([f32; 2]) -> Sample,
    (a0, a1, b0, b1): (f32, f32, f32, f32),
    colour: [u8; 3],
    depth: u32,
) {
    let e = 1e-3 * (a1 - a0);
    let s0 = sample([a0 + e, b0 + e]);
    let s1 = sample([a1 - e, b1 - e]);
    if s0.texel == s1.texel {
        let (x0, x1) = (s0.uv[0].min(s1.uv[0]), s0.uv[0].max(s1.uv[0]));
        let (y0, y1) = (s0.uv[1].min(s1.uv[1]), s0.uv[1].max(s1.uv[1]));
        r.rect(x0, x1, y0, y1, colour);
    } else if depth < 4 {
        let (am, bm) = (0.5 * (a0 + a1), 0.5 * (b0 + b1));
        for q in [
            (a0, am, b0, bm),
            (am, a1, b0, bm),
            (a0, am, bm, b1),
            (am, a1, bm, b1),
        ] {
            cell(r, sample, q, colour, depth + 1);
        }
    } else {
        for s in [s0, s1] {
            r.rect(s.uv[0], s.uv[0], s.uv[1], s.uv[1], colour);
        }
    }
}

/// The strata picture of one distribution: `grid x grid` cells of the sample square.
fn strata(w: usize, h: usize, grid: usize, sample: &dyn Fn([f32; 2]) -> Sample) -> Raster {
    let mut r = Raster::new(w, h, [128, 128, 128]);
    for j in 0..grid {
        for i in 0..grid {
            let (a0, a1) = (i as f32 / grid as f32, (i + 1) as f32 / grid as f32);
            let (b0, b1) = (j as f32 / grid as f32, (j + 1) as f32 / grid as f32);
            let stratum = (j * 16 / grid) * 16 + i * 16 / grid;
            let (cr, cg, cb) = palette_rgb(stratum);
            cell(&mut r, sample, (a0, a1, b0, b1), [cr, cg, cb], 0);
        }
    }
    r
}

/// The map itself, tone-mapped (`x / (1 + x)` of the radiance over its median), grey.
fn map_picture<P: Param>(side: &Side<P>, scale: usize) -> Raster {
    let (w, h) = (side.width(), side.height());
    let mut sorted: Vec<f64> = side.radiance.clone();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2].max(1e-30);
    let mut r = Raster::new(w * scale, h * scale, [0, 0, 0]);
    for y in 0..h * scale {
        for x in 0..w * scale {
            let l = side.radiance[(y / scale) * w + x / scale] / median;
            let g = (255.0 * (l / (1.0 + l)).powf(1.0 / 2.2)) as u8;
            r.px[y * w * scale + x] = [g, g, g];
        }
    }
    r
}

/// Writes the pictures of `scene` into `dir` (`grid` cells per side of the sample square, a
/// multiple of 16); returns the files.
pub fn write(scene: &EnvScene, dir: &Path, grid: usize) -> io::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    let stem = scene.name.replace(':', "-");
    let (ll, ea) = (&scene.latlong, &scene.equal_area);
    let mut save = |name: String, r: Raster| -> io::Result<()> {
        let path = dir.join(name);
        r.write(&path)?;
        files.push(path);
        Ok(())
    };
    save(format!("{stem}-latlong.png"), map_picture(ll, 2))?;
    save(format!("{stem}-equal_area.png"), map_picture(ea, 2))?;
    let (lw, lh) = (2 * ll.width(), 2 * ll.height());
    let (ew, eh) = (2 * ea.width(), 2 * ea.height());
    type Draw<'a> = &'a dyn Fn([f32; 2]) -> Sample;
    let warps: [(&str, (usize, usize), Draw); 4] = [
        ("marginal_equirect", (lw, lh), &|u| ll.marginal.sample(u)),
        ("hierarchical_equirect", (lw, lh), &|u| {
            ll.hierarchical.sample(u)
        }),
        ("marginal_equal_area", (ew, eh), &|u| ea.marginal.sample(u)),
        ("hierarchical_equal_area", (ew, eh), &|u| {
            ea.hierarchical.sample(u)
        }),
    ];
    for (warp, (w, h), draw) in warps {
        save(format!("strata-{warp}.png"), strata(w, h, grid, draw))?;
    }
    Ok(files)
}
