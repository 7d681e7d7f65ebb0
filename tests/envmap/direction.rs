//! Directions and densities per steradian in one call (`sample_direction`, `pdf_direction` and
//! their slice forms) for both distributions and both layouts: the density of a sampled
//! direction equals the sample's, the solid-angle density integrates to 1 over the sphere,
//! importance sampling the constant 1 gives `4 pi`, and the slice forms are bit-identical to
//! the scalar ones.
#![cfg(feature = "envmap")]

use warpcore_testkit as common;

use common::{rng, specials, unit, unit2};
use std::f64::consts::PI;
use warpcore::envmap::{
    DirectionSample, Distribution, Hierarchical, Layout, MarginalConditional, Word, image,
};
use warpcore::sphere;

/// A map of the layout: positive weights in [0.5, 1.5) with a few bright texels; equirect
/// weights carry the rows' `sin(theta)` (sampling by radiance times solid angle).
fn weights(layout: Layout, w: usize, h: usize, seed: u64) -> Vec<f32> {
    let mut r = rng(seed);
    let mut v: Vec<f32> = (0..w * h)
        .map(|k| 0.5 + unit(&mut r) + if k % 37 == 5 { 4.0 } else { 0.0 })
        .collect();
    if layout == Layout::Equirect {
        image::equirect_solid_angle_weights(&mut v, w, h).unwrap();
    }
    v
}

fn check<D: Distribution>(d: &D, layout: Layout, name: &str) {
    let n = 1 << 16;
    let mut r = rng(5);
    let us: Vec<[f32; 2]> = (0..n).map(|_| unit2(&mut r)).collect();

    // 1. The direction and density are the layout's map and conversion of the area sample.
    // 2. pdf_direction(dir) equals the sample's pdf to a few ulp, except on the few samples
    //    whose direction the inverse puts on a neighbouring texel (within an ulp of an edge).
    let mut mismatched = 0usize;
    let mut inv_pdf_sum = 0.0f64;
    for &u in &us {
        let s = d.sample(u);
        let ds = d.sample_direction(layout, u);
        assert_eq!(ds.uv, s.uv, "{name}");
        assert_eq!(ds.texel, s.texel, "{name}");
        let expected_dir = match layout {
            Layout::Equirect => sphere::equirect(s.uv),
            Layout::EqualArea => sphere::equal_area(s.uv),
        };
        assert_eq!(ds.dir, expected_dir, "{name}");
        // The density per steradian from the f64 Jacobian of the layout.
        let jacobian = match layout {
            Layout::Equirect => 2.0 * PI * PI * (PI * f64::from(s.uv[1])).sin(),
            Layout::EqualArea => 4.0 * PI,
        };
        let exact = f64::from(s.pdf) / jacobian;
        assert!(
            (f64::from(ds.pdf) - exact).abs() <= 1e-5 * exact,
            "{name}: pdf {} vs {exact}",
            ds.pdf
        );
        let back = d.pdf_direction(layout, ds.dir);
        if (f64::from(back) - f64::from(ds.pdf)).abs() > 1e-4 * f64::from(ds.pdf) {
            mismatched += 1;
        }
        inv_pdf_sum += 1.0 / f64::from(ds.pdf);
    }
    assert!(
        mismatched * 1000 <= n,
        "{name}: pdf_direction(dir) != pdf for {mismatched} of {n} samples"
    );
    // 3. E[1 / pdf(dir)] over sampled directions is the sphere's solid angle 4 pi (every
    //    weight is positive, so the support is the whole sphere). With pdf within a factor
    //    of about 20 of its mean, the relative standard deviation of 1/pdf is below 1, so the
    //    mean of 2^16 has a standard error below 0.4%: a 2% tolerance is over 5 sigma.
    let mean = inv_pdf_sum / n as f64;
    assert!(
        (mean / (4.0 * PI) - 1.0).abs() < 0.02,
        "{name}: E[1/pdf] = {mean}, 4 pi = {}",
        4.0 * PI
    );
    // 4. The solid-angle density integrates to 1 over the sphere: Monte Carlo over 2^16
    //    uniform directions, 4 pi * mean(pdf_direction). pdf / mean(pdf) is below about 20,
    //    its relative standard deviation below 1.5: standard error below 0.6%, tolerance 3%.
    let mut r = rng(9);
    let dirs: Vec<[f32; 3]> = (0..n).map(|_| sphere::uniform(unit2(&mut r))).collect();
    let integral = 4.0
        * PI
        * dirs
            .iter()
            .map(|&w| f64::from(d.pdf_direction(layout, w)))
            .sum::<f64>()
        / n as f64;
    assert!(
        (integral - 1.0).abs() < 0.03,
        "{name}: integral of the solid-angle pdf = {integral}"
    );

    // 5. Slice forms: bit-identical to the scalar forms, any length, specials included.
    let sp = specials();
    let mut inputs: Vec<[f32; 2]> = sp
        .iter()
        .flat_map(|&a| sp.iter().map(move |&b| [a, b]))
        .collect();
    inputs.extend(us.iter().take(1000));
    let mut out = vec![DirectionSample::default(); inputs.len() + 3];
    assert_eq!(
        d.sample_direction_slice(layout, &inputs, &mut out),
        inputs.len()
    );
    for (u, o) in inputs.iter().zip(&out) {
        let s = d.sample_direction(layout, *u);
        assert_eq!(
            (
                s.dir.map(f32::to_bits),
                s.pdf.to_bits(),
                s.uv.map(f32::to_bits),
                s.texel
            ),
            (
                o.dir.map(f32::to_bits),
                o.pdf.to_bits(),
                o.uv.map(f32::to_bits),
                o.texel
            ),
            "{name} slice at {u:?}"
        );
        assert!(s.pdf.is_finite() && s.pdf >= 0.0);
    }
    assert_eq!(
        out[inputs.len()],
        DirectionSample::default(),
        "wrote past the count"
    );
    let mut hostile: Vec<[f32; 3]> = dirs.iter().take(500).copied().collect();
    for &a in &sp {
        hostile.extend([[a, 0.0, 0.0], [0.0, a, 1.0], [a, a, a], [0.0, 0.0, a]]);
    }
    hostile.push([0.0; 3]);
    let mut pdfs = vec![-1.0f32; hostile.len()];
    assert_eq!(d.pdf_direction_slice(layout, &hostile, &mut pdfs[..7]), 7);
    assert_eq!(
        d.pdf_direction_slice(layout, &hostile, &mut pdfs),
        hostile.len()
    );
    for (w, p) in hostile.iter().zip(&pdfs) {
        let q = d.pdf_direction(layout, *w);
        assert_eq!(q.to_bits(), p.to_bits(), "{name} pdf slice at {w:?}");
        assert!(
            q.is_finite() && q >= 0.0,
            "{name}: pdf_direction({w:?}) = {q}"
        );
    }
}

#[test]
fn direction_samples_for_both_distributions_and_layouts() {
    for layout in [Layout::Equirect, Layout::EqualArea] {
        let (w, h) = match layout {
            Layout::Equirect => (48usize, 24usize),
            Layout::EqualArea => (32, 32),
        };
        let wts = weights(layout, w, h, 3);
        let mut s = vec![0 as Word; Hierarchical::storage_len(w, h)];
        let map = Hierarchical::new(&wts, w, h, &mut s).unwrap();
        check(&map, layout, &format!("hierarchical {layout:?}"));
        // The inherent forms forward to the trait's.
        let u = [0.3, 0.7];
        assert_eq!(
            map.sample_direction(layout, u),
            Distribution::sample_direction(&map, layout, u)
        );
        let mut s = vec![0 as Word; MarginalConditional::storage_len(w, h)];
        let map = MarginalConditional::new(&wts, w, h, &mut s).unwrap();
        check(&map, layout, &format!("marginal {layout:?}"));
    }
}

/// A constant equal-area map samples the sphere uniformly: every density is exactly
/// `1 / (4 pi)` (rounded once), sampled or looked up.
#[test]
fn constant_equal_area_map_is_uniform_on_the_sphere() {
    let mut s = vec![0 as Word; Hierarchical::storage_len(8, 8)];
    let map = Hierarchical::new(&[2.0; 64], 8, 8, &mut s).unwrap();
    let uniform = (1.0 / (4.0 * PI)) as f32;
    let mut r = rng(1);
    for _ in 0..1000 {
        let d = map.sample_direction(Layout::EqualArea, unit2(&mut r));
        assert_eq!(d.pdf, uniform);
        assert_eq!(map.pdf_direction(Layout::EqualArea, d.dir), uniform);
        let n = d.dir.iter().map(|x| x * x).sum::<f32>();
        assert!((n - 1.0).abs() < 1e-5);
    }
}
