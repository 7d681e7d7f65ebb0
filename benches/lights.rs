//! The light tree: `LightTree::sample` (scalar and slice), `pmf`, and build time per light at
//! 10^3, 5 x 10^4, 10^5 and 10^6 lights, against a straightforward pbrt-v4-style binary tree
//! written here as the peer (a `Vec` of nodes in depth-first order, `f32` bounds boxes, the
//! same importance function, the same median-split topology). Inputs (`p`, `n`, `u`) vary
//! per call and go through `black_box`.
//!
//! Run: `RUSTFLAGS="-C target-cpu=native" cargo bench --bench lights`

use criterion::{Criterion, Throughput};
use rand::{RngExt, SeedableRng};
use rand_xoshiro::Xoshiro256PlusPlus as R;
use std::hint::black_box;
use warpcore::lights::{LightBounds, LightTree};

/// Clustered small area lights (one- and two-sided), spots and points, facing every way.
fn scene(r: &mut R, n: usize) -> Vec<LightBounds> {
    (0..n)
        .map(|k| {
            let side = (n as f32).cbrt();
            let cluster = (k % 16) as f32;
            let c: [f32; 3] = std::array::from_fn(|i| {
                r.random::<f32>() * side + if i == 0 { cluster * side * 0.25 } else { 0.0 }
            });
            let h: [f32; 3] = std::array::from_fn(|_| r.random::<f32>() * 0.2);
            let (cos_o, cos_e, two_sided) = match k % 4 {
                0 => (1.0, 0.0, false),
                1 => (1.0, 0.0, true),
                2 => (0.9, 0.5, false),
                _ => (-1.0, 0.0, false),
            };
            let a: [f32; 3] = std::array::from_fn(|_| r.random::<f32>() * 2.0 - 1.0);
            LightBounds {
                min: std::array::from_fn(|i| c[i] - h[i]),
                max: std::array::from_fn(|i| c[i] + h[i]),
                power: r.random::<f32>() * 10.0 + 0.01,
                axis: if a.iter().all(|&x| x == 0.0) {
                    [0.0, 0.0, 1.0]
                } else {
                    a
                },
                cos_theta_o: cos_o,
                cos_theta_e: cos_e,
                two_sided,
            }
        })
        .collect()
}

/// Shading points inside the scene's box, normals (30% media), and `u`.
fn queries(r: &mut R, n: usize, count: usize) -> Vec<([f32; 3], [f32; 3], f32)> {
    let side = (n as f32).cbrt();
    (0..count)
        .map(|_| {
            let p =
                std::array::from_fn(|i| r.random::<f32>() * side * if i == 0 { 4.75 } else { 1.0 });
            let nn = if r.random::<f32>() < 0.3 {
                [0.0; 3]
            } else {
                let v: [f32; 3] = std::array::from_fn(|_| r.random::<f32>() * 2.0 - 1.0);
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt().max(1e-3);
                v.map(|x| x / l)
            };
            (p, nn, r.random::<f32>())
        })
        .collect()
}

// ---------------------------------------------------------------------------------------
// The peer: pbrt-v4's BVH light sampler as a user would write it (nodes in a Vec, depth
// first, second child index stored, bounds boxes, the importance evaluated from the box).

#[derive(Clone, Copy)]
struct PBounds {
    min: [f32; 3],
    max: [f32; 3],
    phi: f32,
    w: [f32; 3],
    cos_o: f32,
    cos_e: f32,
    two_sided: bool,
}

#[derive(Clone, Copy)]
struct PNode {
    b: PBounds,
    /// Second child (inner node) or light index (leaf).
    child_or_light: u32,
    leaf: bool,
}

fn sub3(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn dot3(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn safe_sqrt(x: f32) -> f32 {
    x.max(0.0).sqrt()
}
fn cos_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        1.0
    } else {
        cos_a * cos_b + sin_a * sin_b
    }
}
fn sin_sub_clamped(sin_a: f32, cos_a: f32, sin_b: f32, cos_b: f32) -> f32 {
    if cos_a > cos_b {
        0.0
    } else {
        sin_a * cos_b - cos_a * sin_b
    }
}

impl PBounds {
    fn importance(&self, p: [f32; 3], n: [f32; 3]) -> f32 {
        let pc: [f32; 3] = std::array::from_fn(|i| (self.min[i] + self.max[i]) / 2.0);
        let diag = sub3(self.max, self.min);
        let mut d2 = dot3(sub3(p, pc), sub3(p, pc));
        d2 = d2.max(dot3(diag, diag).sqrt() / 2.0);
        let v = sub3(p, pc);
        let len = dot3(v, v).sqrt();
        let wi = if len > 0.0 {
            v.map(|x| x / len)
        } else {
            [0.0; 3]
        };
        let mut cos_w = dot3(self.w, wi);
        if self.two_sided {
            cos_w = cos_w.abs();
        }
        let sin_w = safe_sqrt(1.0 - cos_w * cos_w);
        // The bounding sphere's subtended cone.
        let r2 = dot3(sub3(self.max, pc), sub3(self.max, pc));
        let dist2 = dot3(v, v);
        let cos_b = if dist2 < r2 {
            -1.0
        } else {
            safe_sqrt(1.0 - r2 / dist2)
        };
        let sin_b = safe_sqrt(1.0 - cos_b * cos_b);
        let sin_o = safe_sqrt(1.0 - self.cos_o * self.cos_o);
        let cos_x = cos_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let sin_x = sin_sub_clamped(sin_w, cos_w, sin_o, self.cos_o);
        let cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if cos_p <= self.cos_e {
            return 0.0;
        }
        let mut imp = self.phi * cos_p / d2;
        if n != [0.0; 3] {
            let cos_i = dot3(wi, n).abs();
            let sin_i = safe_sqrt(1.0 - cos_i * cos_i);
            imp *= cos_sub_clamped(sin_i, cos_i, sin_b, cos_b);
        }
        imp.max(0.0)
    }

    fn of(l: &LightBounds) -> Self {
        let len = dot3(l.axis, l.axis).sqrt();
        PBounds {
            min: l.min,
            max: l.max,
            phi: l.power,
            w: l.axis.map(|x| x / len),
            cos_o: l.cos_theta_o,
            cos_e: l.cos_theta_e,
            two_sided: l.two_sided,
        }
    }

    fn union(&self, o: &Self) -> Self {
        // pbrt-v4's DirectionCone union, in f32.
        let (ta, tb) = (
            self.cos_o.clamp(-1.0, 1.0).acos(),
            o.cos_o.clamp(-1.0, 1.0).acos(),
        );
        let td = dot3(self.w, o.w).clamp(-1.0, 1.0).acos();
        let (w, cos_o) = if (td + tb).min(std::f32::consts::PI) <= ta {
            (self.w, self.cos_o)
        } else if (td + ta).min(std::f32::consts::PI) <= tb {
            (o.w, o.cos_o)
        } else {
            let to = (ta + td + tb) / 2.0;
            let c = [
                self.w[1] * o.w[2] - self.w[2] * o.w[1],
                self.w[2] * o.w[0] - self.w[0] * o.w[2],
                self.w[0] * o.w[1] - self.w[1] * o.w[0],
            ];
            let cl = dot3(c, c).sqrt();
            if to >= std::f32::consts::PI || cl == 0.0 {
                ([0.0, 0.0, 1.0], -1.0)
            } else {
                let k = c.map(|x| x / cl);
                let (s, co) = (to - ta).sin_cos();
                let kxw = [
                    k[1] * self.w[2] - k[2] * self.w[1],
                    k[2] * self.w[0] - k[0] * self.w[2],
                    k[0] * self.w[1] - k[1] * self.w[0],
                ];
                let kw = dot3(k, self.w);
                let w: [f32; 3] =
                    std::array::from_fn(|i| self.w[i] * co + kxw[i] * s + k[i] * kw * (1.0 - co));
                (w, to.cos())
            }
        };
        PBounds {
            min: std::array::from_fn(|i| self.min[i].min(o.min[i])),
            max: std::array::from_fn(|i| self.max[i].max(o.max[i])),
            phi: self.phi + o.phi,
            w,
            cos_o,
            cos_e: self.cos_e.min(o.cos_e),
            two_sided: self.two_sided || o.two_sided,
        }
    }
}

struct Peer {
    nodes: Vec<PNode>,
}

impl Peer {
    fn new(lights: &[LightBounds]) -> Self {
        let mut idx: Vec<u32> = (0..lights.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * lights.len());
        Self::build(lights, &mut idx, &mut nodes);
        Peer { nodes }
    }

    fn build(lights: &[LightBounds], idx: &mut [u32], nodes: &mut Vec<PNode>) -> PBounds {
        if idx.len() == 1 {
            let b = PBounds::of(&lights[idx[0] as usize]);
            nodes.push(PNode {
                b,
                child_or_light: idx[0],
                leaf: true,
            });
            return b;
        }
        let c = |i: u32, k: usize| (lights[i as usize].min[k] + lights[i as usize].max[k]) / 2.0;
        let (mut lo, mut hi) = ([f32::INFINITY; 3], [f32::NEG_INFINITY; 3]);
        for &i in idx.iter() {
            for k in 0..3 {
                lo[k] = lo[k].min(c(i, k));
                hi[k] = hi[k].max(c(i, k));
            }
        }
        let axis = (0..3)
            .max_by(|&a, &b| (hi[a] - lo[a]).total_cmp(&(hi[b] - lo[b])))
            .unwrap();
        let mid = idx.len() / 2;
        idx.select_nth_unstable_by(mid, |&a, &b| c(a, axis).total_cmp(&c(b, axis)));
        let me = nodes.len();
        nodes.push(PNode {
            b: PBounds::of(&lights[0]),
            child_or_light: 0,
            leaf: false,
        });
        let (l, r) = idx.split_at_mut(mid);
        let bl = Self::build(lights, l, nodes);
        let second = nodes.len() as u32;
        let br = Self::build(lights, r, nodes);
        let b = bl.union(&br);
        nodes[me] = PNode {
            b,
            child_or_light: second,
            leaf: false,
        };
        b
    }

    fn sample(&self, p: [f32; 3], n: [f32; 3], mut u: f32) -> Option<(u32, f32)> {
        let mut k = 0usize;
        let mut pmf = 1.0f32;
        loop {
            let node = &self.nodes[k];
            if node.leaf {
                if k > 0 || node.b.importance(p, n) > 0.0 {
                    return Some((node.child_or_light, pmf));
                }
                return None;
            }
            let (c0, c1) = (k + 1, node.child_or_light as usize);
            let ci = [
                self.nodes[c0].b.importance(p, n),
                self.nodes[c1].b.importance(p, n),
            ];
            if ci[0] == 0.0 && ci[1] == 0.0 {
                return None;
            }
            let p0 = ci[0] / (ci[0] + ci[1]);
            if u < p0 {
                k = c0;
                u = (u / p0).min(1.0 - f32::EPSILON / 2.0);
                pmf *= p0;
            } else {
                k = c1;
                u = ((u - p0) / (1.0 - p0)).min(1.0 - f32::EPSILON / 2.0);
                pmf *= 1.0 - p0;
            }
        }
    }
}

// ---------------------------------------------------------------------------------------

fn light_tree(c: &mut Criterion) {
    let mut g = c.benchmark_group("light tree");
    const BATCH: usize = 1024;
    for &n in &[1_000usize, 50_000, 100_000, 1_000_000] {
        let mut r = R::seed_from_u64(n as u64);
        let lights = scene(&mut r, n);
        let q = queries(&mut r, n, 1 << 16);
        let mut storage = vec![0u32; LightTree::storage_len(n)];
        let tree = LightTree::new(&lights, &mut storage).unwrap();
        let peer = Peer::new(&lights);
        g.throughput(Throughput::Elements(BATCH as u64));
        let mut at = 0usize;
        g.bench_function(format!("LightTree::sample {n}"), |b| {
            b.iter(|| {
                let mut acc = 0u32;
                for _ in 0..BATCH {
                    let (p, nn, u) = black_box(q[at & (q.len() - 1)]);
                    at = at.wrapping_add(1);
                    acc ^= tree.sample(p, nn, u).map_or(0, |s| s.0);
                }
                black_box(acc)
            })
        });
        g.bench_function(format!("peer (pbrt-style Vec tree) sample {n}"), |b| {
            b.iter(|| {
                let mut acc = 0u32;
                for _ in 0..BATCH {
                    let (p, nn, u) = black_box(q[at & (q.len() - 1)]);
                    at = at.wrapping_add(1);
                    acc ^= peer.sample(p, nn, u).map_or(0, |s| s.0);
                }
                black_box(acc)
            })
        });
        if n == 50_000 {
            let ps: Vec<[f32; 3]> = q.iter().map(|x| x.0).collect();
            let ns: Vec<[f32; 3]> = q.iter().map(|x| x.1).collect();
            let us: Vec<f32> = q.iter().map(|x| x.2).collect();
            let mut out = vec![None; BATCH];
            g.bench_function(format!("LightTree::sample_slice {n}"), |b| {
                b.iter(|| {
                    let o = at & (q.len() - 1) & !(BATCH - 1);
                    at = at.wrapping_add(BATCH);
                    let s = o..o + BATCH;
                    tree.sample_slice(
                        black_box(&ps[s.clone()]),
                        black_box(&ns[s.clone()]),
                        black_box(&us[s]),
                        &mut out,
                    );
                    black_box(&out);
                })
            });
            g.bench_function(format!("LightTree::pmf {n}"), |b| {
                b.iter(|| {
                    let mut acc = 0.0f32;
                    for k in 0..BATCH {
                        let (p, nn, _) = black_box(q[at & (q.len() - 1)]);
                        at = at.wrapping_add(1);
                        acc += tree.pmf(p, nn, black_box((k * 48_271 % n) as u32));
                    }
                    black_box(acc)
                })
            });
        }
    }
    for &n in &[1_000usize, 50_000, 1_000_000] {
        let mut r = R::seed_from_u64(7 + n as u64);
        let lights = scene(&mut r, n);
        let mut storage = vec![0u32; LightTree::storage_len(n)];
        g.throughput(Throughput::Elements(n as u64));
        g.sample_size(10);
        g.bench_function(format!("LightTree::new {n} (per light)"), |b| {
            b.iter(|| {
                LightTree::new(black_box(&lights), &mut storage).unwrap();
            })
        });
        g.bench_function(format!("peer build {n} (per light)"), |b| {
            b.iter(|| black_box(Peer::new(black_box(&lights)).nodes.len()))
        });
    }
    g.finish();
}

criterion::criterion_group!(benches, light_tree);
criterion::criterion_main!(benches);
