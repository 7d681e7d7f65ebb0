//! Prints the determinism fingerprint of this build (native targets). The `_x16` forms must
//! give the same value; if they do not, both values are printed (and the comparison with the
//! golden value fails).
//!
//! `fingerprint --extras [ENVMAP.pfm]` prints instead one line `name hash` per function the
//! fingerprint does not cover, computed with the crate: the JavaScript module's tests
//! (`js/test/`) compute the same hashes through the JS API and compare.
#[cfg(feature = "all")]
fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().is_some_and(|a| a == "--extras") {
        for (name, hash) in extras::all(args.get(1).map(std::path::Path::new)) {
            println!("{name} {hash:016x}");
        }
    } else {
        let x8 = warpcore_demo::fingerprint::fingerprint();
        let x16 = warpcore_demo::fingerprint::fingerprint_x16();
        if x8 == x16 {
            println!("{x8:016x}");
        } else {
            println!("{x8:016x} (x8) != {x16:016x} (x16)");
        }
    }
}
#[cfg(not(feature = "all"))]
fn main() {}

#[cfg(feature = "all")]
mod extras {
    use std::path::Path;
    use warpcore::envmap::{Hierarchical, MarginalConditional, Sample, image};
    use warpcore_demo::fingerprint::{Hasher, N, input, unit};

    fn hash(f: impl FnOnce(&mut Hasher)) -> u64 {
        let mut h = Hasher::new();
        f(&mut h);
        h.finish()
    }

    /// The 13 x 7 map of the fingerprint: zeros, a negative texel, a NaN, a 10^6 : 1 texel.
    fn weights() -> [f32; 91] {
        std::array::from_fn(|k| match k {
            3 | 40 | 41 => 0.0,
            17 => -2.0,
            60 => f32::NAN,
            77 => 1.0e6,
            _ => unit(k as u32) + 0.01,
        })
    }

    /// A PFM file (RGB, little-endian) as `(width, height, rgb)`, rows top to bottom.
    fn read_pfm(path: &Path) -> (usize, usize, Vec<[f32; 3]>) {
        let bytes = std::fs::read(path).expect("read the PFM file");
        let mut fields = Vec::new();
        let mut at = 0;
        while fields.len() < 4 {
            let start = at;
            while !bytes[at].is_ascii_whitespace() {
                at += 1;
            }
            fields.push(String::from_utf8_lossy(&bytes[start..at]).into_owned());
            at += 1;
        }
        assert!(
            fields[0] == "PF" && fields[3].starts_with('-'),
            "an RGB little-endian PFM"
        );
        let (w, h): (usize, usize) = (fields[1].parse().unwrap(), fields[2].parse().unwrap());
        let floats: Vec<f32> = bytes[at..at + 12 * w * h]
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        let mut rgb = vec![[0.0f32; 3]; w * h];
        for (r, row) in floats.chunks_exact(3 * w).enumerate() {
            for (c, px) in row.chunks_exact(3).enumerate() {
                rgb[(h - 1 - r) * w + c] = [px[0], px[1], px[2]];
            }
        }
        (w, h, rgb)
    }

    pub fn all(envmap: Option<&Path>) -> Vec<(&'static str, u64)> {
        let mut out = vec![
            (
                "disk_polar4_inverse",
                hash(|h| {
                    for i in 0..N {
                        let (u, q) = warpcore::disk::polar4_inverse(input(i));
                        h.floats(&u);
                        h.word(q);
                    }
                }),
            ),
            (
                "pmj02bn_shuffle",
                hash(|h| {
                    for i in 0..N as u32 {
                        h.word(warpcore::pmj02bn::shuffle(
                            i.wrapping_mul(2_654_435_761),
                            0xabcd,
                        ));
                    }
                    h.word(warpcore::pmj02bn::POINTS as u32);
                    h.word(warpcore::pmj02bn::SETS as u32);
                }),
            ),
            (
                "envmap_luminance",
                hash(|h| {
                    for i in 0..N {
                        h.floats(&[image::luminance(input(i))]);
                    }
                }),
            ),
            (
                "envmap_equirect_pdf_to_solid_angle",
                hash(|h| {
                    for i in 0..N {
                        let [p, v]: [f32; 2] = input(i);
                        h.floats(&[image::equirect_pdf_to_solid_angle(p, v)]);
                    }
                }),
            ),
            (
                "envmap_image",
                hash(|h| {
                    let mut w = weights();
                    image::equirect_solid_angle_weights(&mut w, 13, 7).unwrap();
                    h.floats(&w);
                    let rgb: Vec<[f32; 3]> = (0..91).map(|k| input(200 + k)).collect();
                    let mut dst = vec![[0.0f32; 3]; 64];
                    image::equirect_to_equal_area(&rgb, 13, 7, &mut dst, 8, 3).unwrap();
                    for t in &dst {
                        h.floats(t);
                    }
                }),
            ),
            (
                "envmap_storage",
                hash(|h| {
                    let mut s = vec![0u32; MarginalConditional::storage_len(13, 7)];
                    MarginalConditional::new(&weights(), 13, 7, &mut s).unwrap();
                    for w in &s {
                        h.word(*w);
                    }
                }),
            ),
        ];
        if let Some(path) = envmap {
            // A real map: luminance times the rows' solid angle, both distributions, 4096
            // pmj02bn points (seed 7), the samples and the pdf at each sample's point.
            let (w, ht, rgb) = read_pfm(path);
            let mut weights = vec![0.0f32; w * ht];
            image::luminance_slice(&rgb, &mut weights);
            image::equirect_solid_angle_weights(&mut weights, w, ht).unwrap();
            let u: Vec<[f32; 2]> = (0..4096).map(|i| warpcore::pmj02bn::sample(i, 7)).collect();
            let run = |h: &mut Hasher,
                       sample: &dyn Fn([f32; 2]) -> Sample,
                       pdf: &dyn Fn([f32; 2]) -> f32| {
                for &p in &u {
                    let s = sample(p);
                    h.floats(&[s.uv[0], s.uv[1], s.pdf, pdf(s.uv)]);
                    h.word(s.texel[0]);
                    h.word(s.texel[1]);
                }
            };
            let mut s = vec![0u32; Hierarchical::storage_len(w, ht)];
            let d = Hierarchical::new(&weights, w, ht, &mut s).unwrap();
            out.push((
                "envmap_file_hierarchical",
                hash(|h| run(h, &|p| d.sample(p), &|p| d.pdf(p))),
            ));
            let mut s = vec![0u32; MarginalConditional::storage_len(w, ht)];
            let d = MarginalConditional::new(&weights, w, ht, &mut s).unwrap();
            out.push((
                "envmap_file_marginal_conditional",
                hash(|h| run(h, &|p| d.sample(p), &|p| d.pdf(p))),
            ));
        }
        out
    }
}
