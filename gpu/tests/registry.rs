//! The GPU checker's functions are the registry's: every WGSL function it runs
//! ([`all_functions`]) is bound by a registry entry (`warpcore_registry::entries`), and the
//! crate function the checker compares the GPU with gives the bits of that entry's scalar
//! body on the checker's own test points. (The cosine-aware lights take their normal from
//! the test point here and from the light in the registry's hash, so they compare by name
//! only.) Needs no GPU.

use warpcore_gpu::{all_functions, inputs};
use warpcore_registry::{
    Entry, Indexed, Lang, Light, LightMap, Map, OfLight, Quadrant, ToQuadrant, Visit, entries,
};

/// The entry's scalar body on one point's input words, where its shape takes that many.
struct Eval<'a> {
    words: &'a [u32],
    out: Option<Vec<u32>>,
}

fn floats<const N: usize>(w: &[u32]) -> [f32; N] {
    std::array::from_fn(|k| f32::from_bits(w[k]))
}

fn light(w: &[u32]) -> Light<f32> {
    std::array::from_fn(|k| floats(&w[3 * k..]))
}

fn bits(v: &[f32]) -> Vec<u32> {
    v.iter().map(|x| x.to_bits()).collect()
}

impl Visit for Eval<'_> {
    fn map<const I: usize, const O: usize>(&mut self, _: &Entry, m: &Map<I, O>) {
        if self.words.len() == I {
            self.out = Some(bits(&(m.scalar)(floats(self.words))));
        }
    }
    fn indexed<const O: usize>(&mut self, _: &Entry, s: &Indexed<O>) {
        if let [i, seed] = *self.words {
            self.out = Some(bits(&(s.scalar)(i, seed)));
        }
    }
    fn quadrant(&mut self, _: &Entry, q: &Quadrant) {
        if let [_, _, quadrant] = *self.words {
            self.out = Some(bits(&(q.scalar)(floats(self.words), quadrant)));
        }
    }
    fn to_quadrant(&mut self, _: &Entry, q: &ToQuadrant) {
        if self.words.len() == 2 {
            let (u, quadrant) = (q.scalar)(floats(self.words));
            self.out = Some([bits(&u), vec![quadrant]].concat());
        }
    }
    fn light_map<const I: usize, const O: usize>(&mut self, _: &Entry, l: &LightMap<I, O>) {
        if self.words.len() == 12 + I {
            self.out = Some(bits(&(l.scalar)(
                light(self.words),
                floats(&self.words[12..]),
            )));
        }
    }
    fn of_light(&mut self, _: &Entry, l: &OfLight) {
        if self.words.len() == 12 {
            self.out = Some(bits(&[(l.scalar)(light(self.words))]));
        }
    }
}

#[test]
fn the_checker_runs_the_registry_functions() {
    let (mut compared, mut by_name) = (0, Vec::new());
    for (k, f) in all_functions().enumerate() {
        let e = entries()
            .find(|e| {
                let mut bound = false;
                e.names_in(Lang::Wgsl, |n| bound |= n == f.name);
                bound
            })
            .unwrap_or_else(|| panic!("{}: no registry entry binds it", f.name));
        let (iw, ow) = (f.cpu.in_words(), f.cpu.out_words());
        let points = inputs(f.domain, 256, 0x5eed + k as u64);
        let mut matched = 0;
        for p in points.chunks_exact(iw) {
            let mut want = vec![0u32; ow];
            f.cpu.eval(p, &mut want);
            let mut ev = Eval {
                words: p,
                out: None,
            };
            e.visit(&mut ev);
            let Some(got) = ev.out else { break };
            assert_eq!(got, want, "{} ({}) on {p:08x?}", f.name, e.name);
            matched += 1;
        }
        if matched == 0 {
            by_name.push(f.name);
        } else {
            compared += 1;
        }
    }
    assert_eq!(
        by_name,
        [
            "wc_spherical_triangle_cosine",
            "wc_spherical_rectangle_cosine"
        ],
        "functions whose registry body takes other inputs than the checker's"
    );
    assert!(compared >= 30, "only {compared} functions compared");
}
