//! The microfacet check: any bytes as packed `[wo, alpha, u]`, `[wo, wi, alpha]` and
//! `[w, alpha]` records (every `f32` class); every form of every function agrees bit for bit,
//! directions are unit and finite (visible normals with `m.z > 0`), densities and masking
//! terms finite and `>= 0`, and each sampler's density equals its density function at the
//! returned direction, bit for bit.
#[allow(unused_imports)]
use std::prelude::rust_2024::*;
use warpcore::f32x8;
use warpcore::microfacet as mf;

use super::{points, widths, words};

fn unit(d: [f32; 3]) -> bool {
    let l = d.iter().map(|&x| x as f64 * x as f64).sum::<f64>().sqrt();
    d.iter().all(|x| x.is_finite()) && (l - 1.0).abs() < 1e-6
}

fn density(p: f32) -> bool {
    (0.0..f32::MAX).contains(&p)
}

fn s7(x: [f32; 7]) -> ([f32; 3], [f32; 2], [f32; 2]) {
    ([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]])
}

fn s8(x: [f32; 8]) -> ([f32; 3], [f32; 3], [f32; 2]) {
    ([x[0], x[1], x[2]], [x[3], x[4], x[5]], [x[6], x[7]])
}

fn packed<T: Copy>((w, p): ([T; 3], T)) -> [T; 4] {
    [w[0], w[1], w[2], p]
}

fn s5(x: [f32; 5]) -> ([f32; 3], [f32; 2]) {
    ([x[0], x[1], x[2]], [x[3], x[4]])
}

/// A sampler's result and its density function at the returned direction.
type Sampler = fn([f32; 3], [f32; 2], [f32; 2]) -> ([f32; 3], f32);
type Pdf = fn([f32; 3], [f32; 3], [f32; 2]) -> f32;

pub fn microfacet(data: &[u8]) {
    let w = words(data);
    let p7 = points::<7>(&w);
    let p8 = points::<8>(&w);
    let p5 = points::<5>(&w);
    widths(
        "ggx_visible_normal",
        &p7,
        |x| {
            let (a, b, c) = s7(x);
            mf::ggx_visible_normal(a, b, c)
        },
        |x| mf::ggx_visible_normal_x8([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]]),
        mf::ggx_visible_normal_slice,
        |m| unit(m) && m[2] > 0.0,
    );
    type SamplerX8 = fn([f32x8; 3], [f32x8; 2], [f32x8; 2]) -> ([f32x8; 3], f32x8);
    type SamplerSlice = fn(&[[f32; 7]], &mut [[f32; 4]]) -> usize;
    let samplers: [(&str, Sampler, SamplerX8, SamplerSlice, Pdf); 2] = [
        (
            "ggx_reflect",
            mf::ggx_reflect,
            mf::ggx_reflect_x8,
            mf::ggx_reflect_slice,
            mf::ggx_reflect_pdf,
        ),
        (
            "ggx_reflect_bounded",
            mf::ggx_reflect_bounded,
            mf::ggx_reflect_bounded_x8,
            mf::ggx_reflect_bounded_slice,
            mf::ggx_reflect_bounded_pdf,
        ),
    ];
    for (name, sample, sample_x8, slice, pdf) in samplers {
        for &x in &p7 {
            let (wo, a, u) = s7(x);
            let (wi, p) = sample(wo, a, u);
            let q = pdf(wo, wi, a);
            assert_eq!(
                p.to_bits(),
                q.to_bits(),
                "{name}: density {p} != pdf {q} at {x:?}"
            );
        }
        widths(
            name,
            &p7,
            |x| {
                let (a, b, c) = s7(x);
                packed(sample(a, b, c))
            },
            |x| packed(sample_x8([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]])),
            slice,
            |r| unit([r[0], r[1], r[2]]) && density(r[3]),
        );
    }
    type Pair = fn(&[[f32; 8]], &mut [[f32; 1]]) -> usize;
    type PairX8 = fn([f32x8; 3], [f32x8; 3], [f32x8; 2]) -> f32x8;
    let pairs: [(&str, Pdf, PairX8, Pair); 4] = [
        (
            "ggx_visible_normal_pdf",
            mf::ggx_visible_normal_pdf,
            mf::ggx_visible_normal_pdf_x8,
            mf::ggx_visible_normal_pdf_slice,
        ),
        (
            "ggx_reflect_pdf",
            mf::ggx_reflect_pdf,
            mf::ggx_reflect_pdf_x8,
            mf::ggx_reflect_pdf_slice,
        ),
        (
            "ggx_reflect_bounded_pdf",
            mf::ggx_reflect_bounded_pdf,
            mf::ggx_reflect_bounded_pdf_x8,
            mf::ggx_reflect_bounded_pdf_slice,
        ),
        ("ggx_g2", mf::ggx_g2, mf::ggx_g2_x8, mf::ggx_g2_slice),
    ];
    for (name, f, f8, slice) in pairs {
        widths(
            name,
            &p8,
            |x| {
                let (a, b, c) = s8(x);
                [f(a, b, c)]
            },
            |x| [f8([x[0], x[1], x[2]], [x[3], x[4], x[5]], [x[6], x[7]])],
            slice,
            |[p]| density(p),
        );
    }
    type One = fn([f32; 3], [f32; 2]) -> f32;
    type OneX8 = fn([f32x8; 3], [f32x8; 2]) -> f32x8;
    type OneSlice = fn(&[[f32; 5]], &mut [[f32; 1]]) -> usize;
    let ones: [(&str, One, OneX8, OneSlice); 2] = [
        ("ggx_d", mf::ggx_d, mf::ggx_d_x8, mf::ggx_d_slice),
        ("ggx_g1", mf::ggx_g1, mf::ggx_g1_x8, mf::ggx_g1_slice),
    ];
    for (name, f, f8, slice) in ones {
        widths(
            name,
            &p5,
            |x| {
                let (a, b) = s5(x);
                [f(a, b)]
            },
            |x| [f8([x[0], x[1], x[2]], [x[3], x[4]])],
            slice,
            |[p]| density(p) && (name == "ggx_d" || p <= 1.0),
        );
    }
}
