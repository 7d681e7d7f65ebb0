//! SVG plots of each scene: MSE against samples per pixel (log-log, with the convergence
//! rates `N^-1` and `N^-1.5` as guides) and MSE against the time to draw and warp a pixel's
//! samples. Colour family per warp, shade and marker per sampler.

use crate::run::SceneResult;
use crate::samplers::Sampler;
use plotters::element::{Drawable, PointCollection};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// File name of a scene's plot: `envmap:sky` -> `envmap-sky.svg`.
pub fn file_name(scene: &str) -> String {
    format!("{}.svg", scene.replace([':', '/', '\\', ' '], "-"))
}

/// Colour of (warp number, sampler): one hue per warp (six, for the disk's strategies), darker
/// for warpcore's stratified samplers, paler for random and the peers' randomizations.
fn colour(warp: usize, sampler: Sampler) -> RGBColor {
    const HUES: [f64; 6] = [0.58, 0.08, 0.33, 0.97, 0.75, 0.14];
    let (sat, val) = match sampler {
        Sampler::Random => (0.35, 0.90),
        Sampler::Stratified => (0.75, 0.80),
        Sampler::Pmj02bn => (0.95, 0.50),
        Sampler::Pmj02bnCp => (0.55, 0.70),
        Sampler::SobolOwen => (0.85, 0.35),
    };
    let (r, g, b) = crate::strata::hsv(HUES[warp % HUES.len()], sat, val);
    RGBColor(r, g, b)
}

type Series = (String, RGBColor, Sampler, Vec<(f64, f64)>);

/// A sampler's marker: its shape, size and whether it is filled.
fn marker_style(sampler: Sampler) -> (char, i32, bool) {
    match sampler {
        Sampler::Random => ('o', 3, true),
        Sampler::Stratified => ('^', 4, true),
        Sampler::Pmj02bn => ('x', 4, false),
        Sampler::Pmj02bnCp => ('o', 4, false),
        Sampler::SobolOwen => ('^', 5, false),
    }
}

/// The marker of `sampler` at `p` (chart coordinates or pixels).
fn marker<DB: DrawingBackend, C: Clone + 'static>(
    sampler: Sampler,
    c: RGBColor,
    p: C,
) -> DynElement<'static, DB, C>
where
    Circle<C, i32>: Drawable<DB>,
    TriangleMarker<C, i32>: Drawable<DB>,
    Cross<C, i32>: Drawable<DB>,
    for<'b> &'b Circle<C, i32>: PointCollection<'b, C>,
    for<'b> &'b TriangleMarker<C, i32>: PointCollection<'b, C>,
    for<'b> &'b Cross<C, i32>: PointCollection<'b, C>,
{
    let (shape, size, filled) = marker_style(sampler);
    let style = if filled {
        c.filled()
    } else if shape == 'x' {
        c.stroke_width(2)
    } else {
        c.stroke_width(1)
    };
    match shape {
        'o' => Circle::new(p, size, style).into_dyn(),
        '^' => TriangleMarker::new(p, size, style).into_dyn(),
        _ => Cross::new(p, size, style).into_dyn(),
    }
}

/// The dash pattern of a sampler's lines (`None`: solid).
fn dashes(sampler: Sampler) -> Option<(u32, u32)> {
    match sampler {
        Sampler::Pmj02bn => None,
        Sampler::Random => Some((3, 4)),
        Sampler::Stratified => Some((8, 4)),
        Sampler::Pmj02bnCp => Some((2, 3)),
        Sampler::SobolOwen => Some((12, 3)),
    }
}

/// The legend column: one entry per warp (its colour, as pmj02bn draws it), then one per
/// sampler (its marker and dashes, in grey).
fn legend(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    warps: &[&str],
    samplers: &[Sampler],
) -> Result<(), Box<dyn std::error::Error>> {
    let font = ("sans-serif", 12).into_font();
    let mut y = 40;
    let line =
        |y: i32, c: RGBColor, sampler: Option<Sampler>| -> Result<(), Box<dyn std::error::Error>> {
            let pts = vec![(10, y), (42, y)];
            match sampler.and_then(dashes) {
                None => area.draw(&PathElement::new(pts, c.stroke_width(2)))?,
                Some((size, gap)) => {
                    for x in (10..42).step_by((size + gap) as usize) {
                        let end = (x + size as i32).min(42);
                        area.draw(&PathElement::new(vec![(x, y), (end, y)], c.stroke_width(2)))?;
                    }
                }
            }
            if let Some(s) = sampler {
                area.draw(&marker(s, c, (26, y)))?;
            }
            Ok(())
        };
    if warps.len() > 1 {
        area.draw(&Text::new("warps", (10, y - 22), font.clone()))?;
        for (w, name) in warps.iter().enumerate() {
            line(y, colour(w, Sampler::Pmj02bn), None)?;
            area.draw(&Text::new(name.to_string(), (50, y - 7), font.clone()))?;
            y += 20;
        }
        y += 26;
    }
    area.draw(&Text::new("samplers", (10, y - 22), font.clone()))?;
    let grey = RGBColor(90, 90, 90);
    for &s in samplers {
        let c = if warps.len() > 1 { grey } else { colour(0, s) };
        line(y, c, Some(s))?;
        area.draw(&Text::new(s.name().to_string(), (50, y - 7), font.clone()))?;
        y += 20;
    }
    Ok(())
}

fn panel(
    area: &DrawingArea<SVGBackend, plotters::coord::Shift>,
    title: &str,
    x_desc: &str,
    series: &[Series],
    guides: bool,
) -> Result<(), Box<dyn std::error::Error>> {
    let xs = series.iter().flat_map(|s| s.3.iter().map(|p| p.0));
    let ys = series.iter().flat_map(|s| s.3.iter().map(|p| p.1));
    let (x0, x1) = xs.fold((f64::MAX, f64::MIN), |(a, b), x| (a.min(x), b.max(x)));
    let (y0, y1) = ys
        .filter(|y| *y > 0.0)
        .fold((f64::MAX, f64::MIN), |(a, b), y| (a.min(y), b.max(y)));
    let (x0, x1) = (x0 / 1.5, x1 * 1.5);
    let (y0, y1) = (y0 / 2.0, y1 * 2.0);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 17))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(62)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("MSE")
        .x_label_formatter(&|x| {
            if *x >= 1e4 {
                format!("{x:.0e}")
            } else {
                format!("{x}")
            }
        })
        .y_label_formatter(&|y| format!("{y:.0e}"))
        .light_line_style(RGBColor(235, 235, 235))
        .label_style(("sans-serif", 12))
        .draw()?;
    if guides {
        // Slopes -1 and -1.5 through the top-left corner's neighbourhood.
        let grey = RGBColor(160, 160, 160);
        let ymax = series
            .iter()
            .filter_map(|s| s.3.first().map(|p| p.1))
            .fold(f64::MIN, f64::max);
        let start = series
            .iter()
            .filter_map(|s| s.3.first().map(|p| p.0))
            .fold(f64::MAX, f64::min);
        for (slope, label) in [(-1.0, "N^-1"), (-1.5, "N^-1.5")] {
            let pts: Vec<(f64, f64)> = [start, x1 / 1.5]
                .iter()
                .map(|&x| (x, ymax * 1.4 * (x / start).powf(slope)))
                .filter(|p| p.1 >= y0)
                .collect();
            chart.draw_series(DashedLineSeries::new(
                pts.clone(),
                4,
                4,
                grey.stroke_width(1),
            ))?;
            if let Some(&last) = pts.last() {
                chart.draw_series(std::iter::once(Text::new(
                    label.to_string(),
                    last,
                    ("sans-serif", 11).into_font().color(&grey),
                )))?;
            }
        }
    }
    for (_, c, sampler, pts) in series {
        let style = c.stroke_width(2);
        match dashes(*sampler) {
            None => {
                chart.draw_series(LineSeries::new(pts.clone(), style))?;
            }
            Some((size, gap)) => {
                chart.draw_series(DashedLineSeries::new(pts.clone(), size, gap, style))?;
            }
        }
        let c = *c;
        let marks = pts.iter().map(move |&p| marker(*sampler, c, p));
        chart.draw_series(marks)?;
    }
    Ok(())
}

/// Writes `<dir>/<scene>.svg` with both panels; returns its path.
pub fn scene_plot(result: &SceneResult, dir: &Path) -> Result<PathBuf, Box<dyn std::error::Error>> {
    let path = dir.join(file_name(&result.scene));
    let mut warps: Vec<&str> = Vec::new();
    for r in &result.rows {
        if !warps.contains(&r.warp) {
            warps.push(r.warp);
        }
    }
    let mut by_n = Vec::new();
    let mut by_t = Vec::new();
    for r in &result.rows {
        if r.alias_of.is_some() {
            continue;
        }
        let w = warps.iter().position(|&x| x == r.warp).unwrap_or(0);
        let name = if warps.len() == 1 {
            r.sampler.name().to_string()
        } else {
            format!("{} + {}", r.sampler.name(), r.warp)
        };
        let c = colour(w, r.sampler);
        let n: Vec<(f64, f64)> = result
            .spps
            .iter()
            .enumerate()
            .map(|(k, &spp)| (spp as f64, r.mse(k)))
            .collect();
        let t: Vec<(f64, f64)> = result
            .spps
            .iter()
            .enumerate()
            .map(|(k, &spp)| (r.ns[k] * spp as f64, r.mse(k)))
            .filter(|p| p.0.is_finite() && p.0 > 0.0)
            .collect();
        by_n.push((name.clone(), c, r.sampler, n));
        by_t.push((name, c, r.sampler, t));
    }
    let mut samplers: Vec<Sampler> = Vec::new();
    for r in result.rows.iter().filter(|r| r.alias_of.is_none()) {
        if !samplers.contains(&r.sampler) {
            samplers.push(r.sampler);
        }
    }
    samplers.sort_by_key(|s| s.index());
    {
        let root = SVGBackend::new(&path, (1280, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let (panels, key) = root.split_horizontally(1100);
        let (left, right) = panels.split_horizontally(550);
        panel(
            &left,
            &format!("{}: error vs samples per pixel", result.scene),
            "samples per pixel N",
            &by_n,
            true,
        )?;
        if by_t.iter().all(|s| !s.3.is_empty()) {
            panel(
                &right,
                &format!("{}: error vs time to draw and warp", result.scene),
                "ns per pixel (sampling + warp)",
                &by_t,
                false,
            )?;
        }
        legend(&key, &warps, &samplers)?;
        root.present()?;
    }
    Ok(path)
}
