//! The registry: every public function of the library once, family by family, in the order
//! the golden fingerprint hashes them. Adding a function to the product means its body, its
//! bindings and one entry here; `registry/tests/coverage.rs` fails while a public function,
//! a C declaration, a JS method or a WGSL function has none.

use crate::entry::{
    Entry, Forms, Golden, Indexed, Kind, Lang, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant,
};
#[allow(unused_imports)]
use crate::fingerprint::{
    self as fp, SPHERICAL_CONES, SPHERICAL_RECTANGLES, SPHERICAL_TRIANGLES, tri,
};
use Lang::{C, Js, Wgsl};

/// Bound in C, JS and WGSL under the regular name.
const CJW: &[Lang] = &[C, Js, Wgsl];
/// Bound in C and JS under the regular name.
const CJ: &[Lang] = &[C, Js];

/// A map with every form.
macro_rules! all {
    ($f:path, $x8:path, $x16:path, $slice:path) => {
        Map {
            scalar: $f,
            x8: Some($x8),
            x16: Some($x16),
            slice: Some($slice),
        }
    };
}

/// Every entry of the families compiled in, in fingerprint order.
pub fn entries() -> impl Iterator<Item = &'static Entry> {
    [
        DISK, PMJ02BN, SAMPLER, SEQUENCE, TRIANGLE, SPHERE, ENVMAP, SPHERICAL, LIGHTS, LIGHT_TREE,
        MICROFACET,
    ]
    .into_iter()
    .flatten()
}

/// Bindings that are not a library function: each with what it is.
pub const NOT_FUNCTIONS: &[(Lang, &str, &str)] = &[
    (C, "wc_error_string", "the message of a C error code"),
    (C, "wc_pmj02bn_points", "the constant pmj02bn::POINTS"),
    (C, "wc_pmj02bn_sets", "the constant pmj02bn::SETS"),
    (Js, "pmj02bnPoints", "the constant pmj02bn::POINTS"),
    (Js, "pmj02bnSets", "the constant pmj02bn::SETS"),
    (
        C,
        "wc_sampler_pattern_supported",
        "whether a pattern id is compiled in",
    ),
    (Js, "samplerPath", "the root of a JS sampler's domain path"),
    (
        Js,
        "envmapFromStorage",
        "either distribution from storage words (header says which)",
    ),
];

/// Light selection: the alias table and the weighted reservoir (the light tree's entries
/// follow them).
#[cfg(feature = "lights")]
const LIGHTS: &[Entry] = {
    const TESTS: Golden = Golden::Tests("tests/lights/alias.rs");
    const fn alias(name: &'static str) -> Entry {
        Entry::new(name, Forms::SCALAR, Kind::Other).golden(TESTS)
    }
    &[
        Entry::new("lights::AliasTable::sample", Forms::ALL, Kind::Other)
            .golden(Golden::OwnPiece(fp::lights_alias))
            .named(&[
                (C, "wc_lights_alias_sample"),
                (Wgsl, "wc_lights_alias_sample"),
            ]),
        alias("lights::AliasTable::pmf")
            .named(&[(C, "wc_lights_alias_pmf"), (Wgsl, "wc_lights_alias_pmf")]),
        alias("lights::AliasTable::storage_len").named(&[(C, "wc_lights_alias_storage_len")]),
        alias("lights::AliasTable::new")
            .named(&[(C, "wc_lights_alias_build"), (Js, "lightsAlias")]),
        alias("lights::AliasTable::from_storage").named(&[(C, "wc_lights_alias_from_storage")]),
        alias("lights::AliasTable::from_storage_verified").named(&[
            (C, "wc_lights_alias_from_storage_verified"),
            (Js, "lightsAliasFromStorage"),
        ]),
        alias("lights::AliasTable::len"),
        alias("lights::AliasTable::is_empty"),
        alias("lights::AliasTable::storage"),
        alias("lights::Reservoir::new"),
        alias("lights::Reservoir::update"),
        alias("lights::Reservoir::merge"),
        alias("lights::Reservoir::chosen"),
        alias("lights::Reservoir::total"),
        alias("lights::Reservoir::weight"),
    ]
};
#[cfg(not(feature = "lights"))]
const LIGHTS: &[Entry] = &[];

#[cfg(feature = "disk")]
const DISK: &[Entry] = {
    use warpcore::disk as d;
    &[
        Entry::new(
            "disk::polar",
            Forms::ALL,
            Kind::M22(all!(d::polar, d::polar_x8, d::polar_x16, d::polar_slice)),
        )
        .bound(CJW),
        Entry::new(
            "disk::concentric",
            Forms::ALL,
            Kind::M22(all!(
                d::concentric,
                d::concentric_x8,
                d::concentric_x16,
                d::concentric_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "disk::polar_inverse",
            Forms::ALL,
            Kind::M22(all!(
                d::polar_inverse,
                d::polar_inverse_x8,
                d::polar_inverse_x16,
                d::polar_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "disk::concentric_inverse",
            Forms::ALL,
            Kind::M22(all!(
                d::concentric_inverse,
                d::concentric_inverse_x8,
                d::concentric_inverse_x16,
                d::concentric_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "disk::polar4",
            Forms::ALL,
            Kind::Quadrant(Quadrant {
                scalar: d::polar4,
                x8: d::polar4_x8,
                x16: d::polar4_x16,
            }),
        )
        .bound(CJW),
        Entry::new(
            "disk::concentric4",
            Forms::ALL,
            Kind::Quadrant(Quadrant {
                scalar: d::concentric4,
                x8: d::concentric4_x8,
                x16: d::concentric4_x16,
            }),
        )
        .bound(CJW),
        Entry::new(
            "disk::polar4_inverse",
            Forms::LANES,
            Kind::ToQuadrant(ToQuadrant {
                scalar: d::polar4_inverse,
                x8: d::polar4_inverse_x8,
                x16: d::polar4_inverse_x16,
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "disk::concentric4_inverse",
            Forms::LANES,
            Kind::ToQuadrant(ToQuadrant {
                scalar: d::concentric4_inverse,
                x8: d::concentric4_inverse_x8,
                x16: d::concentric4_inverse_x16,
            }),
        )
        .golden(Golden::Piece(fp::disk_quadrant_slices))
        .bound(CJW),
        Entry::new("disk::polar4_indexed", Forms::LANES, Kind::Other)
            .golden(Golden::Tests("tests/disk.rs")),
        Entry::new("disk::concentric4_indexed", Forms::LANES, Kind::Other)
            .golden(Golden::Tests("tests/disk.rs")),
    ]
};
#[cfg(not(feature = "disk"))]
const DISK: &[Entry] = &[];

#[cfg(feature = "pmj02bn")]
const PMJ02BN: &[Entry] = {
    use warpcore::pmj02bn as p;
    &[
        Entry::new(
            "pmj02bn::sample",
            Forms::ALL,
            Kind::I2(Indexed {
                scalar: p::sample,
                x8: p::sample_x8,
                x16: p::sample_x16,
                slice: p::sample_slice,
            }),
        )
        .bound(CJW),
        Entry::new("pmj02bn::raw", Forms::SCALAR, Kind::Other)
            .golden(Golden::Piece(fp::pmj02bn_raw))
            .bound(CJ),
        Entry::new("pmj02bn::shuffle", Forms::LANES, Kind::Other)
            .golden(Golden::OwnPiece(fp::pmj02bn_shuffle))
            .bound(CJW),
    ]
};
#[cfg(not(feature = "pmj02bn"))]
const PMJ02BN: &[Entry] = &[];

/// The sampling core: the methods of `Sampler<P>`; "forms" `_x8`, `_x16` are the methods of
/// the same name on `SamplerX8<P>`, `SamplerX16<P>`, the slice form `draw_slice`.
#[cfg(feature = "sampler")]
const SAMPLER: &[Entry] = {
    const DRAW: Golden = Golden::With("sampler::Sampler::draw");
    const TESTS: Golden = Golden::Tests("tests/sampler.rs");
    &[
        Entry::new("sampler::Sampler::draw", Forms::ALL, Kind::Other)
            .golden(Golden::Piece(fp::sampler))
            .named(&[
                (C, "wc_sampler_draw"),
                (C, "wc_sampler_draw_slice"),
                (Js, "samplerDraw"),
                (Js, "samplerDrawSlice"),
                (Wgsl, "wc_sampler_draw2"),
                (Wgsl, "wc_sampler_draw4"),
            ]),
        Entry::new("sampler::Sampler::new", Forms::LANES, Kind::Other)
            .golden(DRAW)
            .named(&[(C, "wc_sampler_new"), (Wgsl, "wc_sampler_new")]),
        Entry::new("sampler::Sampler::new_frame", Forms::SCALAR, Kind::Other)
            .golden(TESTS)
            .named(&[
                (C, "wc_sampler_new_frame"),
                (Js, "samplerFramePath"),
                (Wgsl, "wc_sampler_new_frame"),
            ]),
        Entry::new("sampler::Sampler::domain", Forms::LANES, Kind::Other)
            .golden(DRAW)
            .named(&[(C, "wc_sampler_domain"), (Wgsl, "wc_sampler_domain")]),
        Entry::new("sampler::Sampler::split", Forms::LANES, Kind::Other)
            .golden(DRAW)
            .named(&[(C, "wc_sampler_split"), (Wgsl, "wc_sampler_split")]),
        Entry::new("sampler::Sampler::draw_u32", Forms::LANES, Kind::Other)
            .golden(DRAW)
            .named(&[
                (C, "wc_sampler_draw_u32"),
                (Js, "samplerDrawU32"),
                (Wgsl, "wc_sampler_draw4_u32"),
            ]),
        Entry::new("sampler::Sampler::rnd", Forms::LANES, Kind::Other)
            .golden(DRAW)
            .named(&[
                (C, "wc_sampler_rnd"),
                (Js, "samplerRnd"),
                (Wgsl, "wc_sampler_rnd4"),
            ]),
        Entry::new("sampler::Sampler::with_index", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("sampler::Sampler::index", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("sampler::SamplerX8::from_lanes", Forms::SCALAR, Kind::Other).golden(DRAW),
        Entry::new("sampler::SamplerX8::splat", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("sampler::SamplerX8::lane", Forms::SCALAR, Kind::Other).golden(TESTS),
    ]
};
#[cfg(not(feature = "sampler"))]
const SAMPLER: &[Entry] = &[];

#[cfg(feature = "sequence")]
const SEQUENCE: &[Entry] = {
    use warpcore::sequence as s;
    &[
        Entry::new(
            "sequence::random",
            Forms::ALL,
            Kind::I2(Indexed {
                scalar: s::random,
                x8: s::random_x8,
                x16: s::random_x16,
                slice: s::random_slice,
            }),
        )
        .bound(CJ),
        Entry::new("sequence::stratified", Forms::ALL, Kind::Other)
            .golden(Golden::Piece(fp::stratified))
            .bound(CJ),
        Entry::new("sequence::stratified_side", Forms::SCALAR, Kind::Other)
            .golden(Golden::Tests("tests/pmj02bn.rs")),
    ]
};
#[cfg(not(feature = "sequence"))]
const SEQUENCE: &[Entry] = &[];

#[cfg(feature = "triangle")]
const TRIANGLE: &[Entry] = {
    use warpcore::triangle as t;
    &[
        Entry::new(
            "triangle::uniform",
            Forms::ALL,
            Kind::M23(all!(
                t::uniform,
                t::uniform_x8,
                t::uniform_x16,
                t::uniform_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "triangle::uniform_inverse",
            Forms::ALL,
            Kind::M32(all!(
                t::uniform_inverse,
                t::uniform_inverse_x8,
                t::uniform_inverse_x16,
                t::uniform_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "triangle::sqrt_map",
            Forms::ALL,
            Kind::M23(all!(
                t::sqrt_map,
                t::sqrt_map_x8,
                t::sqrt_map_x16,
                t::sqrt_map_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "triangle::sqrt_map_inverse",
            Forms::ALL,
            Kind::M32(all!(
                t::sqrt_map_inverse,
                t::sqrt_map_inverse_x8,
                t::sqrt_map_inverse_x16,
                t::sqrt_map_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "triangle::basu_owen",
            Forms::ALL,
            Kind::I3(Indexed {
                scalar: t::basu_owen,
                x8: t::basu_owen_x8,
                x16: t::basu_owen_x16,
                slice: t::basu_owen_slice,
            }),
        )
        .bound(CJW),
        Entry::new(
            "triangle::basu_owen_permuted",
            Forms::ALL,
            Kind::I3(Indexed {
                scalar: t::basu_owen_permuted,
                x8: t::basu_owen_permuted_x8,
                x16: t::basu_owen_permuted_x16,
                slice: t::basu_owen_permuted_slice,
            }),
        )
        .bound(CJW),
    ]
};
#[cfg(not(feature = "triangle"))]
const TRIANGLE: &[Entry] = &[];

#[cfg(feature = "sphere")]
const SPHERE: &[Entry] = {
    use warpcore::sphere as s;
    const DENSITIES: Golden = Golden::With("sphere::equirect_pdf_to_solid_angle");
    &[
        Entry::new(
            "sphere::equal_area",
            Forms::ALL,
            Kind::M23(all!(
                s::equal_area,
                s::equal_area_x8,
                s::equal_area_x16,
                s::equal_area_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::equal_area_inverse",
            Forms::ALL,
            Kind::M32(all!(
                s::equal_area_inverse,
                s::equal_area_inverse_x8,
                s::equal_area_inverse_x16,
                s::equal_area_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::equal_area_wrap",
            Forms::ALL,
            Kind::M22(all!(
                s::equal_area_wrap,
                s::equal_area_wrap_x8,
                s::equal_area_wrap_x16,
                s::equal_area_wrap_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::equirect",
            Forms::ALL,
            Kind::M23(all!(
                s::equirect,
                s::equirect_x8,
                s::equirect_x16,
                s::equirect_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::equirect_inverse",
            Forms::ALL,
            Kind::M32(all!(
                s::equirect_inverse,
                s::equirect_inverse_x8,
                s::equirect_inverse_x16,
                s::equirect_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::uniform",
            Forms::ALL,
            Kind::M23(all!(
                s::uniform,
                s::uniform_x8,
                s::uniform_x16,
                s::uniform_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::uniform_inverse",
            Forms::ALL,
            Kind::M32(all!(
                s::uniform_inverse,
                s::uniform_inverse_x8,
                s::uniform_inverse_x16,
                s::uniform_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::uniform_hemisphere",
            Forms::ALL,
            Kind::M23(all!(
                s::uniform_hemisphere,
                s::uniform_hemisphere_x8,
                s::uniform_hemisphere_x16,
                s::uniform_hemisphere_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::uniform_hemisphere_inverse",
            Forms::ALL,
            Kind::M32(all!(
                s::uniform_hemisphere_inverse,
                s::uniform_hemisphere_inverse_x8,
                s::uniform_hemisphere_inverse_x16,
                s::uniform_hemisphere_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::cosine_hemisphere",
            Forms::ALL,
            Kind::M23(all!(
                s::cosine_hemisphere,
                s::cosine_hemisphere_x8,
                s::cosine_hemisphere_x16,
                s::cosine_hemisphere_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::cosine_hemisphere_inverse",
            Forms::ALL,
            Kind::M32(all!(
                s::cosine_hemisphere_inverse,
                s::cosine_hemisphere_inverse_x8,
                s::cosine_hemisphere_inverse_x16,
                s::cosine_hemisphere_inverse_slice
            )),
        )
        .bound(CJW),
        Entry::new(
            "sphere::equirect_pdf_to_solid_angle",
            Forms::LANES,
            Kind::M41(Map {
                scalar: |[p, x, y, z]| [s::equirect_pdf_to_solid_angle(p, [x, y, z])],
                x8: Some(|[p, x, y, z]| [s::equirect_pdf_to_solid_angle_x8(p, [x, y, z])]),
                x16: Some(|[p, x, y, z]| [s::equirect_pdf_to_solid_angle_x16(p, [x, y, z])]),
                slice: None,
            }),
        )
        .golden(Golden::Piece(fp::sphere_densities))
        .bound(CJW),
        Entry::new(
            "sphere::equal_area_pdf_to_solid_angle",
            Forms::LANES,
            Kind::M11(Map {
                scalar: |[p]| [s::equal_area_pdf_to_solid_angle(p)],
                x8: Some(|[p]| [s::equal_area_pdf_to_solid_angle_x8(p)]),
                x16: Some(|[p]| [s::equal_area_pdf_to_solid_angle_x16(p)]),
                slice: None,
            }),
        )
        .golden(DENSITIES)
        .bound(CJW),
        Entry::new(
            "sphere::cosine_hemisphere_pdf",
            Forms::LANES,
            Kind::M11(Map {
                scalar: |[c]| [s::cosine_hemisphere_pdf(c)],
                x8: Some(|[c]| [s::cosine_hemisphere_pdf_x8(c)]),
                x16: Some(|[c]| [s::cosine_hemisphere_pdf_x16(c)]),
                slice: None,
            }),
        )
        .golden(DENSITIES)
        .bound(CJW),
        Entry::new("sphere::equal_area_wrap_texel", Forms::SCALAR, Kind::Other)
            .golden(DENSITIES)
            .bound(CJ),
    ]
};
#[cfg(not(feature = "sphere"))]
const SPHERE: &[Entry] = &[];

/// The two distributions' methods: one entry each per method name of `MarginalConditional`
/// (the same methods of `Hierarchical` are named in [`HIERARCHICAL`]).
#[cfg(feature = "envmap")]
const ENVMAP: &[Entry] = {
    use warpcore::envmap::image;
    const TESTS: Golden = Golden::Tests("tests/envmap/main.rs");
    const STORAGE: Golden = Golden::Tests("tests/envmap/storage.rs");
    const SAMPLE: Golden = Golden::With("envmap::MarginalConditional::sample");
    &[
        Entry::new(
            "envmap::MarginalConditional::sample",
            Forms::ALL,
            Kind::Other,
        )
        .golden(Golden::Piece(fp::envmap_distributions))
        .named(&[
            (C, "wc_envmap_sample"),
            (Wgsl, "wc_envmap_marginal_conditional_sample"),
        ]),
        Entry::new("envmap::MarginalConditional::pdf", Forms::ALL, Kind::Other)
            .golden(SAMPLE)
            .named(&[
                (C, "wc_envmap_pdf"),
                (Wgsl, "wc_envmap_marginal_conditional_pdf"),
            ]),
        Entry::new("envmap::Hierarchical::sample", Forms::ALL, Kind::Other)
            .golden(SAMPLE)
            .named(&[
                (C, "wc_envmap_sample"),
                (Wgsl, "wc_envmap_hierarchical_sample"),
            ]),
        Entry::new("envmap::Hierarchical::pdf", Forms::ALL, Kind::Other)
            .golden(SAMPLE)
            .named(&[(C, "wc_envmap_pdf"), (Wgsl, "wc_envmap_hierarchical_pdf")]),
        Entry::new(
            "envmap::MarginalConditional::new",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::OwnPiece(fp::envmap_storage))
        .named(&[(C, "wc_envmap_build"), (Js, "envmapMarginalConditional")]),
        Entry::new("envmap::Hierarchical::new", Forms::SCALAR, Kind::Other)
            .golden(STORAGE)
            .named(&[(C, "wc_envmap_build"), (Js, "envmapHierarchical")]),
        Entry::new(
            "envmap::MarginalConditional::storage_len",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::OwnPiece(fp::envmap_storage_lens))
        .named(&[(C, "wc_envmap_storage_len")]),
        Entry::new(
            "envmap::Hierarchical::storage_len",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::With("envmap::MarginalConditional::storage_len"))
        .named(&[(C, "wc_envmap_storage_len")]),
        Entry::new(
            "envmap::MarginalConditional::new_compensated",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/compensation.rs"))
        .named(&[
            (C, "wc_envmap_build_compensated"),
            (Js, "envmapMarginalConditionalCompensated"),
        ]),
        Entry::new(
            "envmap::Hierarchical::new_compensated",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/compensation.rs"))
        .named(&[
            (C, "wc_envmap_build_compensated"),
            (Js, "envmapHierarchicalCompensated"),
        ]),
        Entry::new(
            "envmap::MarginalConditional::from_storage",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(STORAGE)
        .named(&[(C, "wc_envmap_from_storage")]),
        Entry::new(
            "envmap::Hierarchical::from_storage",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(STORAGE)
        .named(&[(C, "wc_envmap_from_storage")]),
        Entry::new(
            "envmap::MarginalConditional::from_storage_verified",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(STORAGE)
        .named(&[(C, "wc_envmap_from_storage_verified")]),
        Entry::new(
            "envmap::Hierarchical::from_storage_verified",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(STORAGE)
        .named(&[(C, "wc_envmap_from_storage_verified")]),
        Entry::new(
            "envmap::MarginalConditional::storage",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(STORAGE),
        Entry::new(
            "envmap::MarginalConditional::width",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/centred.rs")),
        Entry::new(
            "envmap::MarginalConditional::height",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/centred.rs")),
        Entry::new(
            "envmap::MarginalConditional::sample_direction",
            Forms::SLICE,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/direction.rs"))
        .named(&[(C, "wc_envmap_sample_direction")]),
        Entry::new(
            "envmap::MarginalConditional::pdf_direction",
            Forms::SLICE,
            Kind::Other,
        )
        .golden(Golden::Tests("tests/envmap/direction.rs"))
        .named(&[(C, "wc_envmap_pdf_direction")]),
        Entry::new("envmap::SampleX8::to_array", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new(
            "envmap::image::luminance",
            Forms::SLICE,
            Kind::M31(Map {
                scalar: |rgb| [image::luminance(rgb)],
                x8: None,
                x16: None,
                slice: Some(|rgb, out| image::luminance_slice(rgb, out.as_flattened_mut())),
            }),
        )
        .golden(Golden::OwnPiece(fp::envmap_luminance))
        .named(&[(C, "wc_envmap_luminance"), (Js, "envmapLuminance")]),
        Entry::new(
            "envmap::image::equirect_pdf_to_solid_angle",
            Forms::of(true, false, false),
            Kind::M21(Map {
                scalar: |[p, v]| [image::equirect_pdf_to_solid_angle(p, v)],
                x8: Some(|[p, v]| [image::equirect_pdf_to_solid_angle_x8(p, v)]),
                x16: None,
                slice: None,
            }),
        )
        .golden(Golden::OwnPiece(fp::envmap_equirect_pdf))
        .named(&[
            (C, "wc_envmap_equirect_pdf_to_solid_angle"),
            (Js, "envmapEquirectPdfToSolidAngle"),
        ]),
        Entry::new(
            "envmap::image::equirect_solid_angle_weights",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::OwnPiece(fp::envmap_image))
        .named(&[
            (C, "wc_envmap_equirect_solid_angle_weights"),
            (Js, "envmapEquirectSolidAngleWeights"),
        ]),
        Entry::new(
            "envmap::image::equirect_to_equal_area",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(Golden::With("envmap::image::equirect_solid_angle_weights"))
        .named(&[
            (C, "wc_envmap_equirect_to_equal_area"),
            (Js, "envmapEquirectToEqualArea"),
        ]),
    ]
};
#[cfg(not(feature = "envmap"))]
const ENVMAP: &[Entry] = &[];

#[cfg(feature = "spherical")]
const SPHERICAL: &[Entry] = {
    use warpcore::spherical as sp;
    const TRI: &[[f32; 12]] = &SPHERICAL_TRIANGLES;
    const RECT: &[[f32; 12]] = &SPHERICAL_RECTANGLES;
    const CONE: &[[f32; 12]] = &SPHERICAL_CONES;
    fn b4<T: Copy>((b, d): ([T; 3], T)) -> [T; 4] {
        [b[0], b[1], b[2], d]
    }
    fn st3<T: Copy>((st, d): ([T; 2], T)) -> [T; 3] {
        [st[0], st[1], d]
    }
    &[
        Entry::new(
            "spherical::triangle",
            Forms::ALL,
            Kind::L24(LightMap {
                lights: TRI,
                scalar: |l, u| b4(sp::triangle(tri(l), l[3], u)),
                x8: |l, u| b4(sp::triangle_x8(tri(l), l[3], u)),
                x16: |l, u| b4(sp::triangle_x16(tri(l), l[3], u)),
                slice: |l, u, o| sp::triangle_slice(tri(l), l[3], u, o),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::triangle_inverse",
            Forms::ALL,
            Kind::L32(LightMap {
                lights: TRI,
                scalar: |l, b| sp::triangle_inverse(tri(l), l[3], b),
                x8: |l, b| sp::triangle_inverse_x8(tri(l), l[3], b),
                x16: |l, b| sp::triangle_inverse_x16(tri(l), l[3], b),
                slice: |l, b, o| sp::triangle_inverse_slice(tri(l), l[3], b, o),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::triangle_solid_angle",
            Forms::LANES,
            Kind::OfLight(OfLight {
                lights: TRI,
                scalar: |l| sp::triangle_solid_angle(tri(l), l[3]),
                x8: |l| sp::triangle_solid_angle_x8(tri(l), l[3]),
                x16: |l| sp::triangle_solid_angle_x16(tri(l), l[3]),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::rectangle",
            Forms::ALL,
            Kind::L23(LightMap {
                lights: RECT,
                scalar: |l, u| st3(sp::rectangle(l[0], l[1], l[2], l[3], u)),
                x8: |l, u| st3(sp::rectangle_x8(l[0], l[1], l[2], l[3], u)),
                x16: |l, u| st3(sp::rectangle_x16(l[0], l[1], l[2], l[3], u)),
                slice: |l, u, o| sp::rectangle_slice(l[0], l[1], l[2], l[3], u, o),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::rectangle_inverse",
            Forms::ALL,
            Kind::L22(LightMap {
                lights: RECT,
                scalar: |l, st| sp::rectangle_inverse(l[0], l[1], l[2], l[3], st),
                x8: |l, st| sp::rectangle_inverse_x8(l[0], l[1], l[2], l[3], st),
                x16: |l, st| sp::rectangle_inverse_x16(l[0], l[1], l[2], l[3], st),
                slice: |l, st, o| sp::rectangle_inverse_slice(l[0], l[1], l[2], l[3], st, o),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::rectangle_solid_angle",
            Forms::LANES,
            Kind::OfLight(OfLight {
                lights: RECT,
                scalar: |l| sp::rectangle_solid_angle(l[0], l[1], l[2], l[3]),
                x8: |l| sp::rectangle_solid_angle_x8(l[0], l[1], l[2], l[3]),
                x16: |l| sp::rectangle_solid_angle_x16(l[0], l[1], l[2], l[3]),
            }),
        )
        .bound(CJW),
        Entry::new(
            "spherical::triangle_cosine",
            Forms::ALL,
            Kind::L24(LightMap {
                lights: TRI,
                scalar: |l, u| b4(sp::triangle_cosine(tri(l), l[3], normal(l), u)),
                x8: |l, u| b4(sp::triangle_cosine_x8(tri(l), l[3], normal_x8(l), u)),
                x16: |l, u| b4(sp::triangle_cosine_x16(tri(l), l[3], normal_x16(l), u)),
                slice: |l, u, o| sp::triangle_cosine_slice(tri(l), l[3], normal(l), u, o),
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "spherical::rectangle_cosine",
            Forms::ALL,
            Kind::L23(LightMap {
                lights: RECT,
                scalar: |l, u| st3(sp::rectangle_cosine(l[0], l[1], l[2], l[3], normal(l), u)),
                x8: |l, u| {
                    st3(sp::rectangle_cosine_x8(
                        l[0],
                        l[1],
                        l[2],
                        l[3],
                        normal_x8(l),
                        u,
                    ))
                },
                x16: |l, u| {
                    st3(sp::rectangle_cosine_x16(
                        l[0],
                        l[1],
                        l[2],
                        l[3],
                        normal_x16(l),
                        u,
                    ))
                },
                slice: |l, u, o| {
                    sp::rectangle_cosine_slice(l[0], l[1], l[2], l[3], normal(l), u, o)
                },
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "spherical::cone",
            Forms::ALL,
            Kind::L24(LightMap {
                lights: CONE,
                scalar: |l, u| b4(sp::cone(l[0], l[1][0], l[3], u)),
                x8: |l, u| b4(sp::cone_x8(l[0], l[1][0], l[3], u)),
                x16: |l, u| b4(sp::cone_x16(l[0], l[1][0], l[3], u)),
                slice: |l, u, o| sp::cone_slice(l[0], l[1][0], l[3], u, o),
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "spherical::cone_inverse",
            Forms::ALL,
            Kind::L32(LightMap {
                lights: CONE,
                scalar: |l, d| sp::cone_inverse(l[0], l[1][0], l[3], d),
                x8: |l, d| sp::cone_inverse_x8(l[0], l[1][0], l[3], d),
                x16: |l, d| sp::cone_inverse_x16(l[0], l[1][0], l[3], d),
                slice: |l, d, o| sp::cone_inverse_slice(l[0], l[1][0], l[3], d, o),
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "spherical::cone_solid_angle",
            Forms::LANES,
            Kind::OfLight(OfLight {
                lights: CONE,
                scalar: |l| sp::cone_solid_angle(l[0], l[1][0], l[3]),
                x8: |l| sp::cone_solid_angle_x8(l[0], l[1][0], l[3]),
                x16: |l| sp::cone_solid_angle_x16(l[0], l[1][0], l[3]),
            }),
        )
        .golden(Golden::Own)
        .bound(CJW),
        Entry::new(
            "spherical::bilinear",
            Forms::SCALAR,
            Kind::M63(Map {
                scalar: |x| {
                    let (st, d) = sp::bilinear([x[0], x[1]], [x[2], x[3], x[4], x[5]]);
                    [st[0], st[1], d]
                },
                x8: None,
                x16: None,
                slice: None,
            }),
        )
        .golden(Golden::Own),
        Entry::new(
            "spherical::bilinear_pdf",
            Forms::SCALAR,
            Kind::M61(Map {
                scalar: |x| [sp::bilinear_pdf([x[0], x[1]], [x[2], x[3], x[4], x[5]])],
                x8: None,
                x16: None,
                slice: None,
            }),
        )
        .golden(Golden::Own),
    ]
};
/// The receiver normal the cosine-aware maps are hashed with: derived from the light's
/// floats (facing, grazing or behind it; NaN and inf for the non-finite lights).
#[cfg(feature = "spherical")]
fn normal(l: Light<f32>) -> [f32; 3] {
    [l[0][1] - l[3][1] + 0.3, 0.5 - l[2][0], 0.7 - l[1][2] * 0.5]
}

/// [`normal`] on 8 lanes (the same operations).
#[cfg(feature = "spherical")]
fn normal_x8(l: Light<warpcore::f32x8>) -> [warpcore::f32x8; 3] {
    let s = warpcore::f32x8::splat;
    [
        l[0][1] - l[3][1] + s(0.3),
        s(0.5) - l[2][0],
        s(0.7) - l[1][2] * s(0.5),
    ]
}

/// [`normal`] on 16 lanes (the same operations).
#[cfg(feature = "spherical")]
fn normal_x16(l: Light<warpcore::f32x16>) -> [warpcore::f32x16; 3] {
    let s = warpcore::f32x16::splat;
    [
        l[0][1] - l[3][1] + s(0.3),
        s(0.5) - l[2][0],
        s(0.7) - l[1][2] * s(0.5),
    ]
}

#[cfg(not(feature = "spherical"))]
const SPHERICAL: &[Entry] = &[];

/// The light tree (`lights::LightTree`): built objects, so `Kind::Other`; the bits are pinned
/// by [`fp::lights_tree`] (a fixed light set's storage, samples and pmfs) and proved by
/// `tests/lights/tree.rs` (lanes and slices bit-identical, hostile inputs, storage).
#[cfg(feature = "lights")]
const LIGHT_TREE: &[Entry] = {
    const TESTS: Golden = Golden::Tests("tests/lights/tree.rs");
    const SAMPLE: Golden = Golden::With("lights::LightTree::sample");
    &[
        Entry::new("lights::LightTree::sample", Forms::ALL, Kind::Other)
            .golden(Golden::OwnPiece(fp::lights_tree))
            .named(&[
                (C, "wc_lights_tree_sample"),
                (Wgsl, "wc_lights_tree_sample"),
            ]),
        Entry::new("lights::LightTree::pmf", Forms::LANES, Kind::Other)
            .golden(SAMPLE)
            .named(&[(C, "wc_lights_tree_pmf"), (Wgsl, "wc_lights_tree_pmf")]),
        Entry::new("lights::LightTree::new", Forms::SCALAR, Kind::Other)
            .golden(SAMPLE)
            .named(&[(C, "wc_lights_tree_build"), (Js, "lightsTree")]),
        Entry::new("lights::LightTree::new_from_fn", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("lights::LightTree::storage_len", Forms::SCALAR, Kind::Other)
            .golden(SAMPLE)
            .named(&[(C, "wc_lights_tree_storage_len")]),
        Entry::new(
            "lights::LightTree::from_storage",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(TESTS)
        .named(&[(C, "wc_lights_tree_from_storage")]),
        Entry::new(
            "lights::LightTree::from_storage_verified",
            Forms::SCALAR,
            Kind::Other,
        )
        .golden(TESTS)
        .named(&[
            (C, "wc_lights_tree_from_storage_verified"),
            (Js, "lightsTreeFromStorage"),
        ]),
        Entry::new("lights::LightTree::len", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("lights::LightTree::is_empty", Forms::SCALAR, Kind::Other).golden(TESTS),
        Entry::new("lights::LightTree::storage", Forms::SCALAR, Kind::Other).golden(TESTS),
    ]
};
#[cfg(not(feature = "lights"))]
const LIGHT_TREE: &[Entry] = &[];

/// The packed arguments of the microfacet samplers (`[wo, alpha, u]`), densities and `G2`
/// (`[wo, wi or m, alpha]`), `D` and `G1` (`[w, alpha]`), and their results, on any lane type.
#[cfg(feature = "microfacet")]
mod packed {
    pub fn s7<T: Copy>(x: [T; 7]) -> ([T; 3], [T; 2], [T; 2]) {
        ([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]])
    }
    pub fn s8<T: Copy>(x: [T; 8]) -> ([T; 3], [T; 3], [T; 2]) {
        ([x[0], x[1], x[2]], [x[3], x[4], x[5]], [x[6], x[7]])
    }
    pub fn s5<T: Copy>(x: [T; 5]) -> ([T; 3], [T; 2]) {
        ([x[0], x[1], x[2]], [x[3], x[4]])
    }
    pub fn dir_pdf<T: Copy>((w, p): ([T; 3], T)) -> [T; 4] {
        [w[0], w[1], w[2], p]
    }
    pub fn dir<T: Copy>(w: [T; 3]) -> [T; 3] {
        w
    }
    pub fn one<T: Copy>(p: T) -> [T; 1] {
        [p]
    }
}

/// A microfacet entry with every form: `$split` unpacks the packed input into the arguments
/// `$arg`, `$out` packs the result; the slice form takes the packed input as it is.
#[cfg(feature = "microfacet")]
macro_rules! microfacet {
    ($name:literal, $kind:ident, $split:ident($($arg:ident),+) -> $out:ident,
        $f:ident, $x8:ident, $x16:ident, $slice:ident) => {
        Entry::new(
            concat!("microfacet::", $name),
            Forms::ALL,
            Kind::$kind(Map {
                scalar: |x| {
                    let ($($arg),+) = packed::$split(x);
                    packed::$out(mf::$f($($arg),+))
                },
                x8: Some(|x| {
                    let ($($arg),+) = packed::$split(x);
                    packed::$out(mf::$x8($($arg),+))
                }),
                x16: Some(|x| {
                    let ($($arg),+) = packed::$split(x);
                    packed::$out(mf::$x16($($arg),+))
                }),
                slice: Some(mf::$slice),
            }),
        )
        .golden(Golden::Own)
        .bound(CJW)
    };
}

#[cfg(feature = "microfacet")]
const MICROFACET: &[Entry] = {
    use warpcore::microfacet as mf;
    &[
        microfacet!("ggx_d", M51, s5(m, a) -> one, ggx_d, ggx_d_x8, ggx_d_x16, ggx_d_slice),
        microfacet!("ggx_g1", M51, s5(w, a) -> one, ggx_g1, ggx_g1_x8, ggx_g1_x16, ggx_g1_slice),
        microfacet!(
            "ggx_g2", M81, s8(wo, wi, a) -> one,
            ggx_g2, ggx_g2_x8, ggx_g2_x16, ggx_g2_slice
        ),
        microfacet!(
            "ggx_visible_normal", M73, s7(wo, a, u) -> dir,
            ggx_visible_normal, ggx_visible_normal_x8, ggx_visible_normal_x16,
            ggx_visible_normal_slice
        ),
        microfacet!(
            "ggx_visible_normal_pdf", M81, s8(wo, m, a) -> one,
            ggx_visible_normal_pdf, ggx_visible_normal_pdf_x8, ggx_visible_normal_pdf_x16,
            ggx_visible_normal_pdf_slice
        ),
        microfacet!(
            "ggx_reflect", M74, s7(wo, a, u) -> dir_pdf,
            ggx_reflect, ggx_reflect_x8, ggx_reflect_x16, ggx_reflect_slice
        ),
        microfacet!(
            "ggx_reflect_pdf", M81, s8(wo, wi, a) -> one,
            ggx_reflect_pdf, ggx_reflect_pdf_x8, ggx_reflect_pdf_x16, ggx_reflect_pdf_slice
        ),
        microfacet!(
            "ggx_reflect_bounded", M74, s7(wo, a, u) -> dir_pdf,
            ggx_reflect_bounded, ggx_reflect_bounded_x8, ggx_reflect_bounded_x16,
            ggx_reflect_bounded_slice
        ),
        microfacet!(
            "ggx_reflect_bounded_pdf", M81, s8(wo, wi, a) -> one,
            ggx_reflect_bounded_pdf, ggx_reflect_bounded_pdf_x8, ggx_reflect_bounded_pdf_x16,
            ggx_reflect_bounded_pdf_slice
        ),
    ]
};

#[cfg(not(feature = "microfacet"))]
const MICROFACET: &[Entry] = &[];
