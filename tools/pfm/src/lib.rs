//! A small PFM (portable float map) reader for the tests, benchmarks, the report and the
//! tools — not part of the `no_std` library. Reads colour (`PF`) and grey (`Pf`) files of either byte order and
//! returns the rows top to bottom (PFM stores them bottom to top), so row 0 of the result is
//! `v` in `[0, 1/height)` of a lat-long map (around `+z`).
use std::path::{Path, PathBuf};

/// An RGB float image, rows top to bottom.
pub struct Image {
    pub width: usize,
    pub height: usize,
    pub rgb: Vec<[f32; 3]>,
}

/// Parses a PFM file's bytes.
pub fn parse(bytes: &[u8]) -> Result<Image, String> {
    // Header: three whitespace-separated tokens lines: "PF"/"Pf", "W H", "scale", each ended by
    // one whitespace byte; the raster starts right after the scale's terminator.
    let mut pos = 0;
    let mut token = || -> Result<String, String> {
        while pos < bytes.len() && bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        let start = pos;
        while pos < bytes.len() && !bytes[pos].is_ascii_whitespace() {
            pos += 1;
        }
        if start == pos {
            return Err("truncated PFM header".into());
        }
        let t = String::from_utf8_lossy(&bytes[start..pos]).into_owned();
        pos += 1; // the single whitespace byte after the token
        Ok(t)
    };
    let channels = match token()?.as_str() {
        "PF" => 3,
        "Pf" => 1,
        m => return Err(format!("not a PFM file (magic {m:?})")),
    };
    let width: usize = token()?.parse().map_err(|e| format!("width: {e}"))?;
    let height: usize = token()?.parse().map_err(|e| format!("height: {e}"))?;
    let scale: f32 = token()?.parse().map_err(|e| format!("scale: {e}"))?;
    let little = scale < 0.0;
    let data = &bytes[pos.min(bytes.len())..];
    let n = width * height * channels;
    if data.len() < 4 * n {
        return Err(format!(
            "raster holds {} bytes, {} needed",
            data.len(),
            4 * n
        ));
    }
    let floats: Vec<f32> = data[..4 * n]
        .chunks_exact(4)
        .map(|b| {
            let b = [b[0], b[1], b[2], b[3]];
            if little {
                f32::from_le_bytes(b)
            } else {
                f32::from_be_bytes(b)
            }
        })
        .collect();
    let mut rgb = vec![[0.0f32; 3]; width * height];
    for row in 0..height {
        let src = (height - 1 - row) * width; // bottom-to-top in the file
        for x in 0..width {
            let k = (src + x) * channels;
            rgb[row * width + x] = if channels == 3 {
                [floats[k], floats[k + 1], floats[k + 2]]
            } else {
                [floats[k]; 3]
            };
        }
    }
    Ok(Image { width, height, rgb })
}

/// Reads a PFM file.
pub fn read(path: &Path) -> Result<Image, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    parse(&bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// The real CC0 lat-long maps shipped in `tests/data/envmaps/` (see its README).
pub const ENVMAPS: [&str; 6] = ["apartment", "forest", "night", "park", "sunset", "venice"];

/// Path of one of [`ENVMAPS`].
pub fn envmap_path(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/envmaps")
        .join(format!("{name}.pfm"))
}

/// Loads one of [`ENVMAPS`] (panics with a clear message if the data folder is missing).
pub fn envmap(name: &str) -> Image {
    read(&envmap_path(name)).unwrap_or_else(|e| panic!("test map: {e}"))
}

/// Bilinear upsampling of a `w x h` lat-long float map by an integer factor `k` (texel centres
/// aligned, wrapping around in longitude, clamped in latitude, negative values read as 0): a
/// larger map with the same content, for timing the distributions at other sizes.
pub fn upsample(src: &[f32], w: usize, h: usize, k: usize) -> Vec<f32> {
    let (nw, nh) = (w * k, h * k);
    let at = |x: isize, y: isize| {
        let x = x.rem_euclid(w as isize) as usize;
        let y = y.clamp(0, h as isize - 1) as usize;
        src[y * w + x].max(0.0)
    };
    let mut out = vec![0.0f32; nw * nh];
    for y in 0..nh {
        let fy = (y as f32 + 0.5) / k as f32 - 0.5;
        let (y0, ty) = (fy.floor() as isize, fy - fy.floor());
        for x in 0..nw {
            let fx = (x as f32 + 0.5) / k as f32 - 0.5;
            let (x0, tx) = (fx.floor() as isize, fx - fx.floor());
            let top = at(x0, y0) * (1.0 - tx) + at(x0 + 1, y0) * tx;
            let bottom = at(x0, y0 + 1) * (1.0 - tx) + at(x0 + 1, y0 + 1) * tx;
            out[y * nw + x] = top * (1.0 - ty) + bottom * ty;
        }
    }
    out
}
