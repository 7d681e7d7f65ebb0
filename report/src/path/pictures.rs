//! The path scenes' pictures: the reference and every sampler at 4 spp (tonemapped PNG), their
//! error heat maps (PNG), and the convergence and filtered-error plots (SVG).
//!
//! Tile order in both PNGs (7 per row, left to right, top to bottom): the reference, then
//! `pmj02bn, sobol, blue_pmj02bn, blue_sobol, openqmc_sobol, openqmc_sobolbn, openqmc_pmj,
//! openqmc_pmjbn, openqmc_lattice, openqmc_latticebn, sobol_burley, pbrt_pmj02bn, random`.

use super::samplers::{KINDS, Kind};
use super::trace::Image;
use super::{FILTERED_SPPS, PathResult, PathRow, SIGMAS};
use plotters::prelude::*;
use std::path::Path;

const SCALE: usize = 2;
const GAP: usize = 4;
const COLS: usize = 7;

/// Reinhard `x / (1 + x)` per channel, then the sRGB-like gamma 1/2.2.
fn tonemap(c: [f64; 3]) -> [u8; 3] {
    c.map(|x| {
        let x = x.max(0.0);
        (255.0 * (x / (1.0 + x)).powf(1.0 / 2.2))
            .round()
            .clamp(0.0, 255.0) as u8
    })
}

/// Squared error `e` (mean over channels) on a log scale from 1e-5 (black) through red
/// and yellow to 1 (white).
fn heat(e: f64) -> [u8; 3] {
    let t = ((e.max(1e-12).log10() + 5.0) / 5.0).clamp(0.0, 1.0);
    let ramp = |a: f64| (255.0 * a.clamp(0.0, 1.0)).round() as u8;
    [ramp(3.0 * t), ramp(3.0 * t - 1.0), ramp(3.0 * t - 2.0)]
}

fn montage(tiles: &[Vec<[u8; 3]>], w: usize, h: usize) -> (Vec<u8>, usize, usize) {
    let rows = tiles.len().div_ceil(COLS);
    let (tw, th) = (w * SCALE + GAP, h * SCALE + GAP);
    let (iw, ih) = (COLS * tw + GAP, rows * th + GAP);
    let mut buf = vec![255u8; iw * ih * 3];
    for (t, tile) in tiles.iter().enumerate() {
        let (ox, oy) = (GAP + (t % COLS) * tw, GAP + (t / COLS) * th);
        for y in 0..h * SCALE {
            for x in 0..w * SCALE {
                let c = tile[(y / SCALE) * w + x / SCALE];
                let o = ((oy + y) * iw + ox + x) * 3;
                buf[o..o + 3].copy_from_slice(&c);
            }
        }
    }
    (buf, iw, ih)
}

fn save_png(path: &Path, rgb: &[u8], w: usize, h: usize) -> Result<(), Box<dyn std::error::Error>> {
    let file = std::io::BufWriter::new(std::fs::File::create(path)?);
    let mut enc = png::Encoder::new(file, w as u32, h as u32);
    enc.set_color(png::ColorType::Rgb);
    enc.set_depth(png::BitDepth::Eight);
    enc.write_header()?.write_image_data(rgb)?;
    Ok(())
}

/// Writes the tone-mapped `images` (all of one size) side by side as `path`.
pub fn save_images(path: &Path, images: &[Image]) -> Result<(), Box<dyn std::error::Error>> {
    let Some(first) = images.first() else {
        return Ok(());
    };
    let tiles: Vec<Vec<[u8; 3]>> = images
        .iter()
        .map(|im| im.px.iter().map(|&c| tonemap(c)).collect())
        .collect();
    let (buf, iw, ih) = montage(&tiles, first.width, first.height);
    save_png(path, &buf, iw, ih)
}

/// Writes `path-<scene>.png`, `path-<scene>-error.png`, `path-<scene>-convergence.svg` and
/// `path-<scene>-filtered.svg` into `dir`.
pub fn write(r: &PathResult, dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let (w, h) = (r.reference.width, r.reference.height);
    let mut tiles = vec![
        r.reference
            .px
            .iter()
            .map(|&c| tonemap(c))
            .collect::<Vec<_>>(),
    ];
    let mut heats = vec![r.reference.px.iter().map(|_| [0u8; 3]).collect::<Vec<_>>()];
    for (_, img) in &r.at4 {
        tiles.push(img.px.iter().map(|&c| tonemap(c)).collect());
        heats.push(err_tile(img, &r.reference));
    }
    let (buf, iw, ih) = montage(&tiles, w, h);
    save_png(&dir.join(format!("path-{}.png", r.scene)), &buf, iw, ih)?;
    let (buf, iw, ih) = montage(&heats, w, h);
    save_png(
        &dir.join(format!("path-{}-error.png", r.scene)),
        &buf,
        iw,
        ih,
    )?;
    convergence_svg(r, dir)?;
    filtered_svg(r, dir)?;
    Ok(())
}

fn err_tile(img: &Image, reference: &Image) -> Vec<[u8; 3]> {
    img.px
        .iter()
        .zip(&reference.px)
        .map(|(a, b)| {
            let e = (0..3).map(|c| (a[c] - b[c]).powi(2)).sum::<f64>() / 3.0;
            heat(e)
        })
        .collect()
}

/// A colour per sampler (matplotlib's tab20 hues, as `0xRRGGBB`).
fn colour(kind: Kind) -> RGBColor {
    const C: [u32; 13] = [
        0x1f77b4, 0xd62728, 0x17becf, 0xff7f0e, 0x2ca02c, 0x98df8a, 0x9467bd, 0xc5b0d5, 0x8c564b,
        0xc49c94, 0xe377c2, 0xbcbd22, 0x7f7f7f,
    ];
    let c = C[kind.index()];
    RGBColor((c >> 16) as u8, (c >> 8) as u8, c as u8)
}

type Series = (Kind, Vec<(f64, f64)>);

fn log_panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    title: &str,
    x_desc: &str,
    series: &[Series],
    legend: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let pts = series
        .iter()
        .flat_map(|s| s.1.iter())
        .filter(|p| p.0 > 0.0 && p.1 > 0.0);
    let (x0, x1, y0, y1) = pts.fold((f64::MAX, f64::MIN, f64::MAX, f64::MIN), |a, p| {
        (a.0.min(p.0), a.1.max(p.0), a.2.min(p.1), a.3.max(p.1))
    });
    if x0 > x1 || y0 > y1 {
        return Ok(());
    }
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(36)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (x0 / 1.3..x1 * 1.3).log_scale(),
            (y0 / 1.5..y1 * 1.5).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("MSE")
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .light_line_style(RGBColor(235, 235, 235))
        .label_style(("sans-serif", 12))
        .draw()?;
    for (kind, p) in series {
        let p: Vec<(f64, f64)> = p
            .iter()
            .cloned()
            .filter(|q| q.0 > 0.0 && q.1 > 0.0)
            .collect();
        let c = colour(*kind);
        let width = if kind.is_warpcore() { 3 } else { 1 };
        let s = chart.draw_series(LineSeries::new(p.clone(), c.stroke_width(width)))?;
        if legend {
            s.label(kind.name()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(width))
            });
        }
        chart.draw_series(p.iter().map(|&q| Circle::new(q, 2, c.filled())))?;
    }
    if legend {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .position(SeriesLabelPosition::LowerLeft)
            .draw()?;
    }
    Ok(())
}

fn convergence_svg(r: &PathResult, dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let path = dir.join(format!("path-{}-convergence.svg", r.scene));
    let root = SVGBackend::new(&path, (1100, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (left, right) = root.split_horizontally(550);
    // Per sampler, (x of each row, its MSE).
    let series = |x: fn(&PathRow) -> f64| -> Vec<Series> {
        KINDS
            .iter()
            .map(|&k| {
                let rows = r.rows.iter().filter(|row| row.kind == k);
                (k, rows.map(|row| (x(row), row.mse)).collect())
            })
            .collect()
    };
    let by_n = series(|row| row.spp as f64);
    let by_t = series(|row| row.frame_s * 1e3);
    log_panel(
        &left,
        &format!("{}: MSE vs samples per pixel", r.scene),
        "samples per pixel",
        &by_n,
        true,
    )?;
    log_panel(
        &right,
        &format!("{}: MSE vs time per frame", r.scene),
        "ms per 64 x 64 frame (1 thread)",
        &by_t,
        false,
    )?;
    root.present()?;
    Ok(())
}

fn filtered_svg(r: &PathResult, dir: &Path) -> Result<(), Box<dyn std::error::Error>> {
    let path = dir.join(format!("path-{}-filtered.svg", r.scene));
    let root = SVGBackend::new(&path, (1500, 460)).into_drawing_area();
    root.fill(&WHITE)?;
    let panels = root.split_evenly((1, 3));
    for (i, (area, spp)) in panels.iter().zip(FILTERED_SPPS).enumerate() {
        let series: Vec<Series> = KINDS
            .iter()
            .filter_map(|&k| {
                let f = r.row(k, spp)?.filtered?;
                // sigma 0 drawn at 0.25 px so the log axis can show it.
                let p = SIGMAS
                    .iter()
                    .zip(f)
                    .map(|(&s, (m, _))| (s.max(0.25), m))
                    .collect();
                Some((k, p))
            })
            .collect();
        if series.is_empty() {
            continue;
        }
        log_panel(
            area,
            &format!("{}: MSE after a Gaussian blur, {spp} spp", r.scene),
            "blur sigma, px (0 at 0.25)",
            &series,
            i == 0,
        )?;
    }
    root.present()?;
    Ok(())
}
