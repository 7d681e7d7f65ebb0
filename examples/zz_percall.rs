// scratch: best-of-N per-call timing (not committed)
use openqmc::{PmjSampler, SobolSampler};
use std::hint::black_box;
use std::time::Instant;
use warpcore::sampler::{Pattern, Pmj02bn, Sampler, Sobol};

const N: usize = 4096;
fn pixels() -> Vec<[u32; 2]> {
    let mut s = 7u64;
    (0..N)
        .map(|_| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            [((s >> 33) % 1920) as u32, ((s >> 13) % 1080) as u32]
        })
        .collect()
}
fn time(f: &mut dyn FnMut(&mut [[f32; 4]]), out: &mut [[f32; 4]]) -> f64 {
    let t = Instant::now();
    f(out);
    black_box(&out);
    t.elapsed().as_secs_f64() * 1e9 / N as f64
}
fn ours<P: Pattern>(px: &[[u32; 2]]) -> impl FnMut(&mut [[f32; 4]]) + '_ {
    move |out| {
        for (i, o) in out.iter_mut().enumerate() {
            *o = Sampler::<P>::new(black_box(px[i]), 3, black_box(i as u32), 0x5eed)
                .domain(1)
                .draw::<4>();
        }
    }
}
fn main() {
    let px = pixels();
    let mut out = vec![[0f32; 4]; N];
    SobolSampler::warm_cache();
    PmjSampler::warm_cache();
    let mut fs: Vec<(&str, Box<dyn FnMut(&mut [[f32; 4]])>)> = vec![
        ("warpcore Sobol", Box::new(ours::<Sobol>(&px))),
        ("warpcore Pmj02bn", Box::new(ours::<Pmj02bn>(&px))),
        (
            "openqmc Sobol",
            Box::new(|out: &mut [[f32; 4]]| {
                for (i, o) in out.iter_mut().enumerate() {
                    let [x, y] = black_box(px[i]).map(|c| c as i32);
                    *o = SobolSampler::new(x, y, 3, black_box(i as i32))
                        .new_domain(1)
                        .draw_sample_f32::<4>();
                }
            }),
        ),
        (
            "openqmc Pmj",
            Box::new(|out: &mut [[f32; 4]]| {
                for (i, o) in out.iter_mut().enumerate() {
                    let [x, y] = black_box(px[i]).map(|c| c as i32);
                    *o = PmjSampler::new(x, y, 3, black_box(i as i32))
                        .new_domain(1)
                        .draw_sample_f32::<4>();
                }
            }),
        ),
        (
            "pmj02bn::sample_x8 /8",
            Box::new(|out: &mut [[f32; 4]]| {
                use warpcore::u32x8;
                let lane = u32x8::new(std::array::from_fn(|j| j as u32));
                for k in 0..N / 8 {
                    let p = warpcore::pmj02bn::sample_x8(
                        u32x8::splat(8 * k as u32) + lane,
                        black_box(u32x8::splat(5)),
                    );
                    let (a, b) = (p[0].to_array(), p[1].to_array());
                    for j in 0..8 {
                        out[8 * k + j][0] = a[j];
                        out[8 * k + j][1] = b[j];
                    }
                }
            }),
        ),
        (
            "sobol_burley 2d",
            Box::new(|out: &mut [[f32; 4]]| {
                for (i, o) in out.iter_mut().enumerate() {
                    o[0] = sobol_burley::sample(black_box(i as u32), 0, 5);
                    o[1] = sobol_burley::sample(i as u32, 1, 5);
                }
            }),
        ),
    ];
    let rounds: usize = std::env::args()
        .nth(1)
        .map(|s| s.parse().unwrap())
        .unwrap_or(300);
    let mut best = vec![f64::MAX; fs.len()];
    for _ in 0..rounds {
        for (k, (_, f)) in fs.iter_mut().enumerate() {
            best[k] = best[k].min(time(&mut **f, &mut out));
        }
    }
    let only = std::env::args().nth(2);
    if let Some(o) = &only {
        for _ in 0..rounds * 20 {
            for (_, f) in fs.iter_mut().filter(|(n, _)| n.contains(o.as_str())) {
                time(&mut **f, &mut out);
            }
        }
    }
    for (k, (n, _)) in fs.iter().enumerate() {
        println!("{n:20} {:.2} ns/call  {:.1} M/s", best[k], 1e3 / best[k]);
    }
}
