//! SVG plots of each scene: MSE against samples per pixel (log-log, with the convergence
//! rates `N^-1` and `N^-1.5` as guides) and MSE against the time to draw and warp a pixel's
//! samples. Colour family per warp, shade and marker per sampler.

use crate::run::SceneResult;
use crate::samplers::Sampler;
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
    for (name, c, sampler, pts) in series {
        let style = c.stroke_width(2);
        match sampler {
            Sampler::Pmj02bn => {
                chart.draw_series(LineSeries::new(pts.clone(), style))?;
            }
            _ => {
                let (size, gap) = match sampler {
                    Sampler::Random => (3, 4),
                    Sampler::Stratified => (8, 4),
                    Sampler::Pmj02bnCp => (2, 3),
                    _ => (12, 3),
                };
                chart.draw_series(DashedLineSeries::new(pts.clone(), size, gap, style))?;
            }
        }
        let c = *c;
        let marks = pts
            .iter()
            .map(move |&p| -> DynElement<SVGBackend, (f64, f64)> {
                match sampler {
                    Sampler::Random => Circle::new(p, 3, c.filled()).into_dyn(),
                    Sampler::Stratified => TriangleMarker::new(p, 4, c.filled()).into_dyn(),
                    Sampler::Pmj02bn => Cross::new(p, 4, c.stroke_width(2)).into_dyn(),
                    Sampler::Pmj02bnCp => Circle::new(p, 4, c.stroke_width(1)).into_dyn(),
                    Sampler::SobolOwen => TriangleMarker::new(p, 5, c.stroke_width(1)).into_dyn(),
                }
            });
        chart
            .draw_series(marks)?
            .label(name.clone())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], c.stroke_width(2)));
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(200, 200, 200))
        .label_font(("sans-serif", 11))
        .position(SeriesLabelPosition::LowerLeft)
        .draw()?;
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
    {
        let root = SVGBackend::new(&path, (1100, 480)).into_drawing_area();
        root.fill(&WHITE)?;
        let (left, right) = root.split_horizontally(550);
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
                &format!(
                    "{}: error vs time to draw and warp a pixel's samples",
                    result.scene
                ),
                "ns per pixel (sampling + warp)",
                &by_t,
                false,
            )?;
        }
        root.present()?;
    }
    Ok(path)
}
