//! Strata pictures: the sixteen strata of each elementary grid of `[0, 1]^2` — `16x1`, `8x2`,
//! `4x4`, `2x8`, `1x16` (`k x l`: `k` intervals of `u0` times `l` of `u1`) — coloured, and
//! their images under the disk and triangle warps, with the first 16 points of one pmj02bn
//! sequence (one per stratum of every grid) warped alongside. A warp that keeps a stratum
//! compact keeps the points' stratification useful on the light; long thin images (polar
//! rings and spokes, sqrt-map slivers) spread it along one direction only.

use std::fmt::Write as _;
use warpcore::{disk, pmj02bn, triangle};

/// The grids, as (intervals of u0, intervals of u1).
pub const GRIDS: [(usize, usize); 5] = [(16, 1), (8, 2), (4, 4), (2, 8), (1, 16)];

/// A colour per stratum: hues spread by the golden angle, so neighbours differ.
pub fn palette_rgb(i: usize) -> (u8, u8, u8) {
    let h = (i as f64 * 0.618_033_988_75 + 0.05).fract();
    let (s, v) = if i.is_multiple_of(2) {
        (0.65, 0.95)
    } else {
        (0.8, 0.75)
    };
    hsv(h, s, v)
}

/// [`palette_rgb`] as an SVG colour.
pub fn palette(i: usize) -> String {
    let (r, g, b) = palette_rgb(i);
    format!("#{r:02x}{g:02x}{b:02x}")
}

pub fn hsv(h: f64, s: f64, v: f64) -> (u8, u8, u8) {
    let i = (h * 6.0).floor();
    let f = h * 6.0 - i;
    let (p, q, t) = (v * (1.0 - s), v * (1.0 - f * s), v * (1.0 - (1.0 - f) * s));
    let (r, g, b) = match (i as i64).rem_euclid(6) {
        0 => (v, t, p),
        1 => (q, v, p),
        2 => (p, v, t),
        3 => (p, q, v),
        4 => (t, p, v),
        _ => (v, p, q),
    };
    let c = |x: f64| (x * 255.0).round().clamp(0.0, 255.0) as u8;
    (c(r), c(g), c(b))
}

/// The boundary of `[x0, x1] x [y0, y1]`, counter-clockwise, each side subdivided until
/// its image under `image` is within 0.2% of the picture of a straight chord (at least four
/// pieces, at most 256).
fn rect_boundary(
    x0: f64,
    x1: f64,
    y0: f64,
    y1: f64,
    image: &dyn Fn([f32; 2]) -> [f64; 2],
) -> Vec<[f32; 2]> {
    fn side(
        a: [f64; 2],
        b: [f64; 2],
        depth: u32,
        image: &dyn Fn([f32; 2]) -> [f64; 2],
        out: &mut Vec<[f32; 2]>,
    ) {
        let f = |p: [f64; 2]| image([p[0] as f32, p[1] as f32]);
        let m = [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
        let (pa, pb, pm) = (f(a), f(b), f(m));
        let chord = [(pa[0] + pb[0]) / 2.0, (pa[1] + pb[1]) / 2.0];
        let off = (pm[0] - chord[0]).hypot(pm[1] - chord[1]);
        if depth < 2 || (depth < 8 && off > 0.002) {
            side(a, m, depth + 1, image, out);
            side(m, b, depth + 1, image, out);
        } else {
            out.push([a[0] as f32, a[1] as f32]);
        }
    }
    let mut pts = Vec::new();
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    for i in 0..4 {
        side(corners[i], corners[(i + 1) % 4], 0, image, &mut pts);
    }
    pts
}

/// The warps drawn, as named rows.
#[derive(Clone, Copy)]
enum Row {
    Polar,
    Concentric,
    Polar4,
    Concentric4,
    Uniform,
    Sqrt,
}

impl Row {
    fn label(self) -> &'static str {
        match self {
            Row::Polar => "disk: polar",
            Row::Concentric => "disk: concentric",
            Row::Polar4 => "disk: polar4",
            Row::Concentric4 => "disk: concentric4",
            Row::Uniform => "triangle: uniform",
            Row::Sqrt => "triangle: sqrt",
        }
    }
    /// Images of a square point in the unit square of the picture (y down), one per copy.
    fn images(self, u: [f32; 2]) -> Vec<[f64; 2]> {
        let disk_px = |p: [f32; 2]| [0.5 + 0.47 * p[0] as f64, 0.5 - 0.47 * p[1] as f64];
        match self {
            Row::Polar => vec![disk_px(disk::polar(u))],
            Row::Concentric => vec![disk_px(disk::concentric(u))],
            Row::Polar4 => (0..4).map(|q| disk_px(disk::polar4(u, q))).collect(),
            Row::Concentric4 => (0..4).map(|q| disk_px(disk::concentric4(u, q))).collect(),
            Row::Uniform => vec![tri_px(triangle::uniform(u))],
            Row::Sqrt => vec![tri_px(triangle::sqrt_map(u))],
        }
    }
}

/// Barycentrics to the picture's unit square: `v0` top, `v1` bottom left, `v2` bottom right.
fn tri_px(b: [f32; 3]) -> [f64; 2] {
    let v = [[0.5, 0.06], [0.03, 0.87], [0.97, 0.87]];
    let (b0, b1, b2) = (b[0] as f64, b[1] as f64, b[2] as f64);
    [
        b0 * v[0][0] + b1 * v[1][0] + b2 * v[2][0],
        b0 * v[0][1] + b1 * v[1][1] + b2 * v[2][1],
    ]
}

struct Svg {
    body: String,
}

impl Svg {
    fn polygon(&mut self, pts: &[[f64; 2]], x: f64, y: f64, size: f64, fill: &str) {
        let mut p = String::new();
        for q in pts {
            let _ = write!(p, "{:.1},{:.1} ", x + q[0] * size, y + q[1] * size);
        }
        let _ = writeln!(
            self.body,
            r#"<polygon points="{}" fill="{fill}" stroke="{fill}" stroke-width="0.4"/>"#,
            p.trim_end()
        );
    }
    fn dot(&mut self, q: [f64; 2], x: f64, y: f64, size: f64) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{:.1}" cy="{:.1}" r="1.8" fill="black"/>"#,
            x + q[0] * size,
            y + q[1] * size
        );
    }
    fn text(&mut self, x: f64, y: f64, size: u32, anchor: &str, s: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{x:.1}" y="{y:.1}" font-family="sans-serif" font-size="{size}" text-anchor="{anchor}">{s}</text>"#
        );
    }
    fn finish(self, w: f64, h: f64) -> String {
        format!(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n{}</svg>\n",
            self.body
        )
    }
}

/// The 16 level-2 sub-triangles of the Basu-Owen subdivision, in picture coordinates.
fn level2() -> Vec<[[f64; 2]; 3]> {
    let mid = |a: [f64; 2], b: [f64; 2]| [(a[0] + b[0]) / 2.0, (a[1] + b[1]) / 2.0];
    let split = |t: [[f64; 2]; 3]| {
        let [a, b, c] = t;
        let (ab, bc, ca) = (mid(a, b), mid(b, c), mid(c, a));
        [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    };
    let top = [
        tri_px([1.0, 0.0, 0.0]),
        tri_px([0.0, 1.0, 0.0]),
        tri_px([0.0, 0.0, 1.0]),
    ];
    split(top).iter().flat_map(|&t| split(t)).collect()
}

fn inside(t: &[[f64; 2]; 3], p: [f64; 2]) -> bool {
    let s =
        |a: [f64; 2], b: [f64; 2]| (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
    let (d0, d1, d2) = (s(t[0], t[1]), s(t[1], t[2]), s(t[2], t[0]));
    (d0 >= 0.0 && d1 >= 0.0 && d2 >= 0.0) || (d0 <= 0.0 && d1 <= 0.0 && d2 <= 0.0)
}

/// The disk and triangle strata picture, as SVG text.
pub fn disk_triangle_svg() -> String {
    let rows = [
        Row::Polar,
        Row::Concentric,
        Row::Polar4,
        Row::Concentric4,
        Row::Uniform,
        Row::Sqrt,
    ];
    let (cell, left, top) = (150.0, 215.0, 76.0);
    let mut svg = Svg {
        body: String::new(),
    };
    svg.text(
        left,
        22.0,
        15,
        "start",
        "The 16 strata of each elementary grid of [0,1]^2 (k x l: k intervals of u0 by l of u1)",
    );
    svg.text(
        left,
        42.0,
        13,
        "start",
        "through each warp; dots: the first 16 points of one pmj02bn sequence, one per stratum of every grid",
    );
    for (c, (k, l)) in GRIDS.iter().enumerate() {
        svg.text(
            left + (c as f64 + 0.5) * cell,
            top - 8.0,
            14,
            "middle",
            &format!("{k} x {l}"),
        );
    }
    let points: Vec<[f32; 2]> = (0..16).map(|i| pmj02bn::sample(i, 7)).collect();
    for (r, row) in rows.iter().enumerate() {
        let y = top + r as f64 * cell;
        svg.text(left - 10.0, y + cell / 2.0, 13, "end", row.label());
        for (c, &(k, l)) in GRIDS.iter().enumerate() {
            let x = left + c as f64 * cell;
            for j in 0..l {
                for i in 0..k {
                    let b = rect_boundary(
                        i as f64 / k as f64,
                        (i + 1) as f64 / k as f64,
                        j as f64 / l as f64,
                        (j + 1) as f64 / l as f64,
                        &|u| row.images(u)[0],
                    );
                    let images: Vec<Vec<[f64; 2]>> = b.iter().map(|&u| row.images(u)).collect();
                    for copy in 0..images[0].len() {
                        let poly: Vec<[f64; 2]> = images.iter().map(|v| v[copy]).collect();
                        svg.polygon(&poly, x + 4.0, y + 4.0, cell - 8.0, &palette(j * k + i));
                    }
                }
            }
            for &p in &points {
                for q in row.images(p) {
                    svg.dot(q, x + 4.0, y + 4.0, cell - 8.0);
                }
            }
        }
    }
    // Basu-Owen: index-driven, its strata are the sub-triangles of the subdivision. Two rows:
    // the nested scramble (each point anywhere in its sub-triangle) and the per-level
    // permutation (every point at the same place in its sub-triangle, mirrored in the
    // inverted ones), the same seeds.
    let subs = level2();
    type Construction = fn(u32, u32) -> [f32; 3];
    let constructions: [(&str, Construction); 2] = [
        ("triangle: basu_owen", triangle::basu_owen),
        ("triangle: basu_owen_permuted", triangle::basu_owen_permuted),
    ];
    let mut y = top + rows.len() as f64 * cell;
    for (label, f) in constructions {
        svg.text(left - 10.0, y + cell / 2.0, 13, "end", label);
        for (c, seed) in [0u32, 0x2545_f491, 0x9e37_79b9].iter().enumerate() {
            let x = left + c as f64 * cell;
            let pts: Vec<[f64; 2]> = (0..16).map(|i| tri_px(f(i, *seed))).collect();
            for t in &subs {
                let owner = pts.iter().position(|&p| inside(t, p)).unwrap_or(0);
                svg.polygon(t, x + 4.0, y + 4.0, cell - 8.0, &palette(owner));
            }
            for &p in &pts {
                svg.dot(p, x + 4.0, y + 4.0, cell - 8.0);
            }
            let label = if *seed == 0 {
                "seed 0 (unscrambled)".to_string()
            } else {
                format!("seed {seed:#x}")
            };
            svg.text(x + cell / 2.0, y + cell + 12.0, 12, "middle", &label);
        }
        y += cell + 20.0;
    }
    let notes = [
        "Indices 0..16 fall one per level-2",
        "sub-triangle (each coloured like the",
        "index that lands in it).",
        "basu_owen (nested): each point anywhere",
        "in its sub-triangle.",
        "basu_owen_permuted (one permutation per",
        "level): every point at the same place",
        "(mirrored in the inverted ones).",
    ];
    for (k, line) in notes.iter().enumerate() {
        svg.text(
            left + 3.0 * cell + 10.0,
            y - 2.0 * cell - 20.0 + 18.0 * k as f64,
            12,
            "start",
            line,
        );
    }
    svg.finish(left + 5.0 * cell + 20.0, y + 20.0)
}
