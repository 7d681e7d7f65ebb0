//! The 16-wide forms: every `_x16` function agrees bit for bit with the scalar form, lane by
//! lane, on special values (signed zeros, NaN with payloads, infinities, subnormals, values
//! past the ends) and on arbitrary bit patterns. On targets without 16-lane vectors `wide`
//! emulates `f32x16` as two 8-lane halves, on AVX-512 it uses other instructions: both must
//! give the scalar bits. (The fingerprint test checks the same on a fixed input set; the slice
//! forms, 16 lanes wide with AVX-512, are checked against the scalar form in each family's
//! tests and at both widths by the library's unit tests.)
#![cfg(all(
    feature = "disk",
    feature = "triangle",
    feature = "sphere",
    feature = "pmj02bn",
    feature = "sequence"
))]

use warpcore_testkit as common;

use common::{rng, specials};
use proptest::prelude::*;
use rand::RngExt;
use warpcore::{disk, f32x16, pmj02bn, sequence, sphere, triangle, u32x16};

/// Sixteen points as SIMD lanes (structure of arrays).
fn soa16<const N: usize>(points: &[[f32; N]; 16]) -> [f32x16; N] {
    std::array::from_fn(|k| f32x16::new(std::array::from_fn(|j| points[j][k])))
}

fn lane16<const N: usize>(v: [f32x16; N], j: usize) -> [f32; N] {
    std::array::from_fn(|k| v[k].to_array()[j])
}

fn same_bits<const N: usize>(a: [f32; N], b: [f32; N]) -> bool {
    a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits())
}

/// `x16` on the sixteen points equals `scalar` on each.
fn check<const I: usize, const O: usize>(
    name: &str,
    pts: &[[f32; I]; 16],
    scalar: impl Fn([f32; I]) -> [f32; O],
    x16: impl Fn([f32x16; I]) -> [f32x16; O],
) {
    let v = x16(soa16(pts));
    for (j, p) in pts.iter().enumerate() {
        let s = scalar(*p);
        assert!(
            same_bits(s, lane16(v, j)),
            "{name} lane {j}: {p:?} -> scalar {s:?}, x16 {:?}",
            lane16(v, j)
        );
    }
}

type W2 = (
    &'static str,
    fn([f32; 2]) -> [f32; 2],
    fn([f32x16; 2]) -> [f32x16; 2],
);
type W23 = (
    &'static str,
    fn([f32; 2]) -> [f32; 3],
    fn([f32x16; 2]) -> [f32x16; 3],
);
type W32 = (
    &'static str,
    fn([f32; 3]) -> [f32; 2],
    fn([f32x16; 3]) -> [f32x16; 2],
);

const SQUARE_TO_SQUARE: [W2; 5] = [
    ("disk::polar", disk::polar, disk::polar_x16),
    ("disk::concentric", disk::concentric, disk::concentric_x16),
    (
        "disk::polar_inverse",
        disk::polar_inverse,
        disk::polar_inverse_x16,
    ),
    (
        "disk::concentric_inverse",
        disk::concentric_inverse,
        disk::concentric_inverse_x16,
    ),
    (
        "sphere::equal_area_wrap",
        sphere::equal_area_wrap,
        sphere::equal_area_wrap_x16,
    ),
];

const SQUARE_TO_3: [W23; 7] = [
    (
        "triangle::uniform",
        triangle::uniform,
        triangle::uniform_x16,
    ),
    (
        "triangle::sqrt_map",
        triangle::sqrt_map,
        triangle::sqrt_map_x16,
    ),
    (
        "sphere::equal_area",
        sphere::equal_area,
        sphere::equal_area_x16,
    ),
    ("sphere::equirect", sphere::equirect, sphere::equirect_x16),
    ("sphere::uniform", sphere::uniform, sphere::uniform_x16),
    (
        "sphere::uniform_hemisphere",
        sphere::uniform_hemisphere,
        sphere::uniform_hemisphere_x16,
    ),
    (
        "sphere::cosine_hemisphere",
        sphere::cosine_hemisphere,
        sphere::cosine_hemisphere_x16,
    ),
];

const THREE_TO_SQUARE: [W32; 7] = [
    (
        "triangle::uniform_inverse",
        triangle::uniform_inverse,
        triangle::uniform_inverse_x16,
    ),
    (
        "triangle::sqrt_map_inverse",
        triangle::sqrt_map_inverse,
        triangle::sqrt_map_inverse_x16,
    ),
    (
        "sphere::equal_area_inverse",
        sphere::equal_area_inverse,
        sphere::equal_area_inverse_x16,
    ),
    (
        "sphere::equirect_inverse",
        sphere::equirect_inverse,
        sphere::equirect_inverse_x16,
    ),
    (
        "sphere::uniform_inverse",
        sphere::uniform_inverse,
        sphere::uniform_inverse_x16,
    ),
    (
        "sphere::uniform_hemisphere_inverse",
        sphere::uniform_hemisphere_inverse,
        sphere::uniform_hemisphere_inverse_x16,
    ),
    (
        "sphere::cosine_hemisphere_inverse",
        sphere::cosine_hemisphere_inverse,
        sphere::cosine_hemisphere_inverse_x16,
    ),
];

/// Every point-driven `_x16` function (warps, inverses, quadrant warps and their indexed
/// helpers, density conversions) on sixteen 2D points and sixteen 3D points, with per-lane
/// quadrants.
fn check_all(pts: &[[f32; 2]; 16], dirs: &[[f32; 3]; 16], q: [u32; 16]) {
    for (name, s, v) in SQUARE_TO_SQUARE {
        check(name, pts, s, v);
    }
    for (name, s, v) in SQUARE_TO_3 {
        check(name, pts, s, v);
    }
    for (name, s, v) in THREE_TO_SQUARE {
        check(name, dirs, s, v);
    }
    let (x, quads) = (soa16(pts), u32x16::new(q));
    let p4 = disk::polar4_x16(x, quads);
    let c4 = disk::concentric4_x16(x, quads);
    let (pi, pq) = disk::polar4_inverse_x16(x);
    let (ci, cq) = disk::concentric4_inverse_x16(x);
    // The indexed helpers pass index / 4 to the point source and use index % 4.
    let pi4 = disk::polar4_indexed_x16(quads, |k| {
        soa16(&std::array::from_fn(|j| pts[k.to_array()[j] as usize % 16]))
    });
    let ci4 = disk::concentric4_indexed_x16(quads, |k| {
        soa16(&std::array::from_fn(|j| pts[k.to_array()[j] as usize % 16]))
    });
    let d = soa16(dirs);
    let pdf = d[0];
    let ea_pdf = sphere::equal_area_pdf_to_solid_angle_x16(pdf);
    let er_pdf = sphere::equirect_pdf_to_solid_angle_x16(pdf, d);
    let cos_pdf = sphere::cosine_hemisphere_pdf_x16(pdf);
    for j in 0..16 {
        let (u, qj) = (pts[j], q[j]);
        assert!(
            same_bits(disk::polar4(u, qj), lane16(p4, j)),
            "polar4 {u:?} {qj}"
        );
        assert!(
            same_bits(disk::concentric4(u, qj), lane16(c4, j)),
            "concentric4 {u:?}"
        );
        let (su, sq) = disk::polar4_inverse(u);
        assert!(
            same_bits(su, lane16(pi, j)) && sq == pq.to_array()[j],
            "polar4_inverse"
        );
        let (su, sq) = disk::concentric4_inverse(u);
        assert!(
            same_bits(su, lane16(ci, j)) && sq == cq.to_array()[j],
            "concentric4_inverse"
        );
        let point = |k: u32| pts[k as usize % 16];
        assert!(
            same_bits(disk::polar4_indexed(qj, point), lane16(pi4, j)),
            "polar4_indexed"
        );
        assert!(
            same_bits(disk::concentric4_indexed(qj, point), lane16(ci4, j)),
            "concentric4_indexed"
        );
        let p = dirs[j][0];
        assert!(same_bits(
            [
                sphere::equal_area_pdf_to_solid_angle(p),
                sphere::equirect_pdf_to_solid_angle(p, dirs[j]),
                sphere::cosine_hemisphere_pdf(p),
            ],
            [
                ea_pdf.to_array()[j],
                er_pdf.to_array()[j],
                cos_pdf.to_array()[j]
            ]
        ));
    }
}

/// Every index-driven `_x16` function (pmj02bn, the baselines, both Basu-Owen forms, the
/// index shuffle) on sixteen (index, seed) pairs.
fn check_indexed(index: [u32; 16], seed: [u32; 16]) {
    let (i, s) = (u32x16::new(index), u32x16::new(seed));
    type Ix = (
        &'static str,
        fn(u32, u32) -> [f32; 2],
        fn(u32x16, u32x16) -> [f32x16; 2],
    );
    let two: [Ix; 2] = [
        ("pmj02bn::sample", pmj02bn::sample, pmj02bn::sample_x16),
        ("sequence::random", sequence::random, sequence::random_x16),
    ];
    for (name, scalar, x16) in two {
        let v = x16(i, s);
        for j in 0..16 {
            assert!(
                same_bits(scalar(index[j], seed[j]), lane16(v, j)),
                "{name} {} {}",
                index[j],
                seed[j]
            );
        }
    }
    type Ix3 = (
        &'static str,
        fn(u32, u32) -> [f32; 3],
        fn(u32x16, u32x16) -> [f32x16; 3],
    );
    let three: [Ix3; 2] = [
        (
            "triangle::basu_owen",
            triangle::basu_owen,
            triangle::basu_owen_x16,
        ),
        (
            "triangle::basu_owen_permuted",
            triangle::basu_owen_permuted,
            triangle::basu_owen_permuted_x16,
        ),
    ];
    for (name, scalar, x16) in three {
        let v = x16(i, s);
        for j in 0..16 {
            assert!(same_bits(scalar(index[j], seed[j]), lane16(v, j)), "{name}");
        }
    }
    for count in [0u32, 1, 16, 17, 1024, u32::MAX] {
        let v = sequence::stratified_x16(i, count, s);
        for j in 0..16 {
            let want = sequence::stratified(index[j], count, seed[j]);
            assert!(same_bits(want, lane16(v, j)), "stratified {count}");
        }
    }
    let sh = pmj02bn::shuffle_x16(i, s).to_array();
    for j in 0..16 {
        assert_eq!(sh[j], pmj02bn::shuffle(index[j], seed[j]), "shuffle");
    }
}

#[test]
fn x16_agrees_on_special_values() {
    let sp = specials();
    let mut pts = Vec::new();
    let mut dirs = Vec::new();
    for &a in &sp {
        for &b in &sp {
            pts.push([a, b]);
            for &c in &[0.0f32, -0.0, 0.5, f32::NAN, -1.0, f32::from_bits(1)] {
                dirs.push([a, b, c]);
            }
        }
    }
    let q: [u32; 16] = std::array::from_fn(|j| (j as u32).wrapping_mul(0x9e37_79b9));
    for (k, group) in pts.chunks_exact(16).enumerate() {
        let d = &dirs[16 * k..16 * k + 16];
        check_all(group.try_into().unwrap(), d.try_into().unwrap(), q);
    }
    for group in dirs.chunks_exact(16) {
        let p: [[f32; 2]; 16] = std::array::from_fn(|j| [group[j][0], group[j][2]]);
        check_all(&p, group.try_into().unwrap(), q);
    }
    let edges = [
        0u32,
        1,
        3,
        4,
        255,
        256,
        4095,
        4096,
        0x5555_5555,
        0xaaaa_aaaa,
        0x8000_0000,
        u32::MAX - 1,
        u32::MAX,
        65535,
        65536,
        7,
    ];
    for rot in 0..16 {
        check_indexed(edges, std::array::from_fn(|j| edges[(j + rot) % 16]));
    }
}

#[test]
fn x16_agrees_on_random_points() {
    let mut r = rng(16);
    for _ in 0..2000 {
        let pts: [[f32; 2]; 16] = std::array::from_fn(|_| common::unit2(&mut r));
        let dirs: [[f32; 3]; 16] =
            std::array::from_fn(|_| std::array::from_fn(|_| 2.0 * common::unit(&mut r) - 1.0));
        check_all(&pts, &dirs, std::array::from_fn(|_| r.random()));
        check_indexed(
            std::array::from_fn(|_| r.random()),
            std::array::from_fn(|_| r.random()),
        );
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Arbitrary bit patterns: every NaN payload, subnormal and out-of-range value.
    #[test]
    fn x16_agrees_on_any_bits(
        bits in prop::array::uniform32(any::<u32>()),
        dbits in prop::array::uniform32(any::<u32>()),
        extra in prop::array::uniform16(any::<u32>()),
        q in prop::array::uniform16(any::<u32>()),
    ) {
        let pts: [[f32; 2]; 16] =
            std::array::from_fn(|j| [f32::from_bits(bits[2 * j]), f32::from_bits(bits[2 * j + 1])]);
        let dirs: [[f32; 3]; 16] = std::array::from_fn(|j| {
            [f32::from_bits(dbits[2 * j]), f32::from_bits(dbits[2 * j + 1]), f32::from_bits(extra[j])]
        });
        check_all(&pts, &dirs, q);
        check_indexed(q, extra);
    }
}
