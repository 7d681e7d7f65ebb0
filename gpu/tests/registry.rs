//! The GPU checker's functions are the registry's: every WGSL function it runs
//! ([`all_functions`]) is bound by its registry entry under its name, and its crate reference
//! is that entry's scalar body, except for those kept by hand ([`BY_HAND`]: the cosine-aware
//! lights, whose normal WGSL takes as a parameter and the registry derives from the light,
//! and the sphere lights, 7 words in WGSL and 12 floats in the registry), which equal the
//! registry bodies where the normal is the registry's and the sphere the same. Needs no GPU.

use warpcore_gpu::functions::{BY_HAND, Reference, floats, light};
use warpcore_gpu::spherical::sphere7;
use warpcore_gpu::{all_functions, inputs};
use warpcore_registry::{Entry, Lang, Light, LightMap, OfLight, Visit};

#[test]
fn the_checker_runs_the_registry_functions() {
    let mut count = 0;
    for f in all_functions() {
        let mut bound = false;
        f.entry.names_in(Lang::Wgsl, |n| bound |= n == f.name);
        assert!(bound, "{}: not bound by {}", f.name, f.entry.name);
        count += 1;
    }
    assert!(count >= 36, "only {count} functions");
    let hand: Vec<&str> = BY_HAND.iter().map(|(n, _)| *n).collect();
    assert_eq!(
        hand,
        [
            "wc_spherical_cone",
            "wc_spherical_cone_inverse",
            "wc_spherical_cone_solid_angle",
            "wc_spherical_triangle_cosine",
            "wc_spherical_rectangle_cosine"
        ],
        "the references kept by hand"
    );
}

/// The receiver normal the registry hashes the cosine-aware lights with
/// (`registry/src/entries.rs`, `normal`).
fn registry_normal(l: Light<f32>) -> [f32; 3] {
    [l[0][1] - l[3][1] + 0.3, 0.5 - l[2][0], 0.7 - l[1][2] * 0.5]
}

/// A hand-kept reference on `light, registry_normal(light), u` against the registry body
/// on `light, u`, for every light of the entry and the checker's samples.
struct AgainstRegistry<'a> {
    reference: Reference,
    samples: &'a [u32],
    compared: usize,
}

impl Visit for AgainstRegistry<'_> {
    fn light_map<const I: usize, const O: usize>(&mut self, e: &Entry, l: &LightMap<I, O>) {
        if e.name.contains("cone") {
            // The sphere's 7 words, then the input (`u` or a direction).
            for lf in l.lights {
                for x in self.samples.chunks_exact(I) {
                    let want = (l.scalar)(light(&lf.map(f32::to_bits)), floats(x));
                    let mut point: Vec<u32> = sphere7(lf).map(f32::to_bits).to_vec();
                    point.extend(x);
                    let mut got = vec![0u32; O];
                    (self.reference)(&point, &mut got);
                    assert_eq!(got, want.map(f32::to_bits), "{} on {point:08x?}", e.name);
                    self.compared += 1;
                }
            }
            return;
        }
        for light_floats in l.lights {
            let words: Vec<u32> = light_floats.iter().map(|x| x.to_bits()).collect();
            let normal = registry_normal(light(&words));
            for u in self.samples.chunks_exact(2) {
                let want = (l.scalar)(light(&words), floats(u));
                let mut point = words.clone();
                point.extend(normal.map(f32::to_bits));
                point.extend(u);
                let mut got = vec![0u32; O];
                (self.reference)(&point, &mut got);
                let want: Vec<u32> = want.iter().map(|x| x.to_bits()).collect();
                assert_eq!(got, want, "{} on {point:08x?}", e.name);
                self.compared += 1;
            }
        }
    }

    fn of_light(&mut self, e: &Entry, l: &OfLight) {
        for lf in l.lights {
            let want = (l.scalar)(light(&lf.map(f32::to_bits)));
            let mut got = [0u32];
            (self.reference)(&sphere7(lf).map(f32::to_bits), &mut got);
            assert_eq!(got, [want.to_bits()], "{} on {lf:?}", e.name);
            self.compared += 1;
        }
    }
}

#[test]
fn the_references_kept_by_hand_equal_the_registry_bodies() {
    let samples = inputs(warpcore_gpu::Domain::Square, 16, 0x5eed);
    for (name, reference) in BY_HAND {
        let f = all_functions().find(|f| f.name == *name).unwrap();
        let mut v = AgainstRegistry {
            reference: *reference,
            samples: &samples[..2 * 4096],
            compared: 0,
        };
        f.entry.visit(&mut v);
        // The solid angle has one point per light (17).
        let least = if name.ends_with("solid_angle") {
            16
        } else {
            1000
        };
        assert!(v.compared > least, "{name}: {} points", v.compared);
    }
}
