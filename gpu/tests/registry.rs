//! The GPU checker's functions are the registry's: every WGSL function it runs
//! ([`all_functions`]) is bound by its registry entry under its name, and its crate reference
//! is that entry's scalar body, except for the two kept by hand ([`BY_HAND`], the cosine-aware
//! lights: WGSL takes their normal as a parameter, the registry derives it from the light),
//! which equal the registry bodies where the normal is the registry's. Needs no GPU.

use warpcore_gpu::functions::{BY_HAND, Reference, floats, light};
use warpcore_gpu::{all_functions, inputs};
use warpcore_registry::{Entry, Lang, Light, LightMap, Visit};

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
        assert!(v.compared > 1000, "{name}: {} points", v.compared);
    }
}
