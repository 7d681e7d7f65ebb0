//! GGX microfacet reflection: chi-square tests of visible normals and reflected directions
//! against their densities integrated in `f64` over cells of the sphere; the returned density
//! against the density functions; the reflection densities' integrals over the sphere; the
//! fraction below the horizon (caps vs bounded); error against `f64` transcriptions of the
//! textbook formulas; totality on hostile input; bit identity across widths.
//!
//! Significance: every chi-square test runs at the suite's Sidak-corrected level
//! (`testkit::chi2`, 1% for the whole suite), 2^20 samples each, fixed seeds.
#![cfg(feature = "microfacet")]

use std::f64::consts::PI;
use warpcore::microfacet as mf;
use warpcore_testkit as common;

use common::{chi2, rng, specials, unit2};

type V3 = [f64; 3];

fn d3(v: [f32; 3]) -> V3 {
    v.map(|x| x as f64)
}
fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
fn normalize(a: V3) -> V3 {
    let l = dot(a, a).sqrt();
    a.map(|x| x / l)
}

/// The textbook GGX in `f64` (Walter et al. 2007; Heitz 2014, 2018), on unit vectors.
#[derive(Clone, Copy)]
struct Ggx {
    ax: f64,
    ay: f64,
}

impl Ggx {
    fn new(a: [f32; 2]) -> Self {
        Ggx {
            ax: a[0] as f64,
            ay: a[1] as f64,
        }
    }
    /// `D(m) = 1 / (pi ax ay cos^4 (1 + tan^2 (cos^2 phi / ax^2 + sin^2 phi / ay^2))^2)`.
    fn d(self, m: V3) -> f64 {
        let m = normalize(m);
        if m[2] <= 0.0 {
            return 0.0;
        }
        let c2 = m[2] * m[2];
        let s2 = 1.0 - c2;
        let e = if s2 > 0.0 {
            (m[0] * m[0] / (self.ax * self.ax) + m[1] * m[1] / (self.ay * self.ay)) / c2
        } else {
            0.0
        };
        1.0 / (PI * self.ax * self.ay * c2 * c2 * (1.0 + e) * (1.0 + e))
    }
    /// `Lambda(w) = (-1 + sqrt(1 + alpha(phi)^2 tan^2 theta)) / 2`.
    fn lambda(self, w: V3) -> f64 {
        let w = normalize(w);
        let c2 = w[2] * w[2];
        let a2t2 = (self.ax * self.ax * w[0] * w[0] + self.ay * self.ay * w[1] * w[1]) / c2;
        (-1.0 + (1.0 + a2t2).sqrt()) / 2.0
    }
    fn g1(self, w: V3) -> f64 {
        1.0 / (1.0 + self.lambda(w))
    }
    fn g2(self, wo: V3, wi: V3) -> f64 {
        1.0 / (1.0 + self.lambda(wo) + self.lambda(wi))
    }
    /// `D_wo(m) = G1(wo) max(0, wo.m) D(m) / wo.z`.
    fn vndf(self, wo: V3, m: V3) -> f64 {
        let (wo, m) = (normalize(wo), normalize(m));
        let wm = dot(wo, m);
        if wm <= 0.0 {
            return 0.0;
        }
        self.g1(wo) * wm * self.d(m) / wo[2]
    }
    /// `D_wo(h) / (4 wo.h)` with `h = normalize(wo + wi)`.
    fn reflect_pdf(self, wo: V3, wi: V3) -> f64 {
        let Some((wo, h)) = half(wo, wi) else {
            return 0.0;
        };
        let wh = dot(wo, h);
        if wh <= 0.0 {
            return 0.0;
        }
        self.vndf(wo, h) / (4.0 * wh)
    }
    /// Eto and Tokuyoshi 2023: the standard-space cap `z >= -k i.z`; the reflection density
    /// is the caps one times the ratio of the caps' areas inside the cap's image, 0 outside.
    fn bounded_pdf(self, wo: V3, wi: V3) -> f64 {
        let Some((wo, h)) = half(wo, wi) else {
            return 0.0;
        };
        let i = normalize([self.ax * wo[0], self.ay * wo[1], wo[2]]);
        let n = normalize([h[0] / self.ax, h[1] / self.ay, h[2]]);
        let k = self.k(wo);
        let o_z = 2.0 * dot(i, n) * n[2] - i[2];
        if o_z < -k * i[2] {
            return 0.0;
        }
        self.reflect_pdf(wo, wi) * (1.0 + i[2]) / (1.0 + k * i[2])
    }
    fn k(self, wo: V3) -> f64 {
        let a = self.ax.min(self.ay);
        let s = 1.0 + (wo[0] * wo[0] + wo[1] * wo[1]).sqrt();
        (1.0 - a * a) * s * s / (s * s + a * a * wo[2] * wo[2])
    }
    /// The standard-space normal of `m` and back, and `d omega_m / d omega_n`.
    fn to_standard(self, m: V3) -> V3 {
        normalize([m[0] / self.ax, m[1] / self.ay, m[2]])
    }
    fn standard_to_normal(self, n: V3) -> (V3, f64) {
        let a = [self.ax * n[0], self.ay * n[1], n[2]];
        let l = dot(a, a).sqrt();
        (a.map(|x| x / l), self.ax * self.ay / (l * l * l))
    }
}

/// The unit `wo` and the half vector `normalize(wo/|wo| + wi/|wi|)`, unless that is zero.
fn half(wo: V3, wi: V3) -> Option<(V3, V3)> {
    let (wo, wi) = (normalize(wo), normalize(wi));
    let h = [wo[0] + wi[0], wo[1] + wi[1], wo[2] + wi[2]];
    (dot(h, h) > 0.0).then(|| (wo, normalize(h)))
}

fn reflect(wo: V3, m: V3) -> V3 {
    let t = 2.0 * dot(wo, m);
    [t * m[0] - wo[0], t * m[1] - wo[1], t * m[2] - wo[2]]
}

/// Equal-area parameters of a unit direction, `((1 - z) / 2, phi / 2 pi)`, and back.
fn param(d: V3) -> [f64; 2] {
    let phi = d[1].atan2(d[0]).rem_euclid(2.0 * PI);
    [(1.0 - d[2]) / 2.0, phi / (2.0 * PI)]
}
fn unparam(s: [f64; 2]) -> V3 {
    let z = 1.0 - 2.0 * s[0];
    let r = (1.0 - z * z).max(0.0).sqrt();
    let phi = 2.0 * PI * s[1];
    [r * phi.cos(), r * phi.sin(), z]
}

/// The outgoing direction of polar cosine `z` at azimuth 0.7 rad, in `f32`.
fn outgoing(z: f64) -> [f32; 3] {
    let s = (1.0 - z * z).sqrt();
    [
        (s * 0.7f64.cos()) as f32,
        (s * 0.7f64.sin()) as f32,
        z as f32,
    ]
}

const ALPHAS: [[f32; 2]; 6] = [
    [1e-3, 1e-3],
    [0.05, 0.05],
    [0.3, 0.3],
    [1.0, 1.0],
    [0.02, 0.4],
    [0.8, 0.1],
];
const WO_Z: [f64; 4] = [1.0, 0.5, 0.05, 1e-4];

const N: usize = 1 << 20;
const GRID: usize = 32;

/// [`chi2::expected_from_density`] on a 4x finer grid, summed back to `GRID x GRID` cells:
/// 8 x 8 Gauss-Legendre nodes per sub-cell, so that the bounded density's step at the rim of
/// its cap costs the quadrature little.
fn expected_fine(density: impl Fn([f64; 2]) -> f64) -> Vec<f64> {
    let fine = chi2::expected_from_density(4 * GRID, 4 * GRID, density);
    let mut p = vec![0.0; GRID * GRID];
    for j in 0..4 * GRID {
        for i in 0..4 * GRID {
            p[(j / 4) * GRID + i / 4] += fine[j * 4 * GRID + i];
        }
    }
    p
}

/// Which sampler a chi-square test runs.
#[derive(Clone, Copy, Debug)]
enum Which {
    Normal,
    Reflect,
    Bounded,
}

/// Chi-square of one sampler at one configuration. Samples are histogrammed over the sphere
/// of standard-space normals `n` (the half vector of `wo` and `wi` for the reflections,
/// unstretched and normalised: a bijection computed in `f64`), where even `alpha = 1e-3`
/// spreads over the whole sphere; the expected cell probabilities integrate the `f64`
/// density times the Jacobians (`4 wo.h` from `wi` to `h`, `ax ay / |A n|^3` from `h` to
/// `n`). Also checks each returned density against the density function (bit for bit) and
/// against `f64` at every 16th sample (the worst relative error is returned, over densities
/// above 1e-30).
fn chi2_config(which: Which, wo: [f32; 3], alpha: [f32; 2], seed: u64) -> f64 {
    let g = Ggx::new(alpha);
    let wo64 = normalize(d3(wo));
    let mut hist = chi2::Histogram::new(GRID, GRID);
    let mut r = rng(seed);
    let mut worst = 0.0f64;
    for i in 0..N {
        let u = unit2(&mut r);
        let h = match which {
            Which::Normal => d3(mf::ggx_visible_normal(wo, alpha, u)),
            Which::Reflect | Which::Bounded => {
                let (wi, p) = if let Which::Reflect = which {
                    mf::ggx_reflect(wo, alpha, u)
                } else {
                    mf::ggx_reflect_bounded(wo, alpha, u)
                };
                let pf = if let Which::Reflect = which {
                    mf::ggx_reflect_pdf(wo, wi, alpha)
                } else {
                    mf::ggx_reflect_bounded_pdf(wo, wi, alpha)
                };
                assert_eq!(
                    p.to_bits(),
                    pf.to_bits(),
                    "{which:?} {wo:?} {alpha:?} {u:?}"
                );
                // The `f64` density (a diagnostic: `error_against_f64` asserts the bounds)
                // at every 16th sample.
                if i % 16 == 0 {
                    let p64 = if let Which::Reflect = which {
                        g.reflect_pdf(wo64, d3(wi))
                    } else {
                        g.bounded_pdf(wo64, d3(wi))
                    };
                    if p64 > 1e-30 {
                        worst = worst.max((p as f64 - p64).abs() / p64);
                    }
                }
                let wi = normalize(d3(wi));
                normalize([wo64[0] + wi[0], wo64[1] + wi[1], wo64[2] + wi[2]])
            }
        };
        hist.add(param(g.to_standard(h)));
    }
    let expected = expected_fine(|s| {
        let (h, jac) = g.standard_to_normal(unparam(s));
        let p = match which {
            Which::Normal => g.vndf(wo64, h),
            Which::Reflect | Which::Bounded => {
                let wh = dot(wo64, h);
                if wh <= 0.0 {
                    return 0.0;
                }
                let wi = reflect(wo64, h);
                let p = if let Which::Reflect = which {
                    g.reflect_pdf(wo64, wi)
                } else {
                    g.bounded_pdf(wo64, wi)
                };
                p * 4.0 * wh
            }
        };
        p * jac
    });
    chi2::check(
        &format!("{which:?} wo.z {} alpha {alpha:?}", wo[2]),
        &hist,
        &expected,
    );
    worst
}

fn chi2_all(which: Which) {
    let mut seed = 1000 * which as u64;
    for alpha in ALPHAS {
        for z in WO_Z {
            seed += 1;
            // An f32 `wi` cannot resolve a lobe narrower than a few ulps: at `alpha = 1e-3`
            // and `wo.z = 1e-4` the reflected lobe is about 2e-7 rad wide (3 ulps of the
            // direction), so its half vector (what the cells are made of) is lost; the
            // reflections are tested there by their density's error instead.
            if !matches!(which, Which::Normal) && alpha[0].min(alpha[1]) as f64 * z < 1e-6 {
                eprintln!("skipped: {which:?} wo.z {z} alpha {alpha:?}");
                continue;
            }
            let worst = chi2_config(which, outgoing(z), alpha, seed);
            eprintln!("  density vs f64 at returned directions: {worst:.2e} relative");
        }
    }
}

#[test]
fn chi2_visible_normals() {
    chi2_all(Which::Normal);
}

#[test]
fn chi2_reflect() {
    chi2_all(Which::Reflect);
}

#[test]
fn chi2_reflect_bounded() {
    chi2_all(Which::Bounded);
}

/// The power check: the bounded sampler's samples are rejected against the caps density at
/// a rough, grazing configuration (their distributions differ), and the caps sampler's
/// against a density with `alpha` 10% off.
#[test]
fn chi2_rejects_wrong_density() {
    let (wo, alpha) = (outgoing(0.05), [0.8f32, 0.8]);
    let g = Ggx::new(alpha);
    let wo64 = normalize(d3(wo));
    let mut hist = chi2::Histogram::new(GRID, GRID);
    let mut r = rng(7);
    for _ in 0..N {
        let (wi, _) = mf::ggx_reflect_bounded(wo, alpha, unit2(&mut r));
        hist.add(param(normalize(d3(wi))));
    }
    let caps = chi2::expected_from_density(GRID, GRID, |s| g.reflect_pdf(wo64, unparam(s)));
    let p = chi2::statistic(&hist, &caps).map_or(0.0, |o| o.p_value);
    assert!(
        p < chi2::per_test_alpha(),
        "bounded passed as caps: p = {p}"
    );
    let off = Ggx { ax: 0.88, ay: 0.88 };
    let mut hist = chi2::Histogram::new(GRID, GRID);
    for _ in 0..N {
        hist.add(param(d3(mf::ggx_visible_normal(wo, alpha, unit2(&mut r)))));
    }
    let wrong = chi2::expected_from_density(GRID, GRID, |s| off.vndf(wo64, unparam(s)));
    let p = chi2::statistic(&hist, &wrong).map_or(0.0, |o| o.p_value);
    assert!(
        p < chi2::per_test_alpha(),
        "alpha 0.8 passed as 0.88: p = {p}"
    );
}

/// Gauss-Legendre nodes on `[0, 1]` (4 points).
fn gauss4() -> [(f64, f64); 4] {
    let x = [0.339_981_043_584_856_3, 0.861_136_311_594_052_6];
    let w = [0.652_145_154_862_546_1, 0.347_854_845_137_453_9];
    [
        (0.5 - 0.5 * x[1], 0.5 * w[1]),
        (0.5 - 0.5 * x[0], 0.5 * w[0]),
        (0.5 + 0.5 * x[0], 0.5 * w[0]),
        (0.5 + 0.5 * x[1], 0.5 * w[1]),
    ]
}

/// Gauss-Legendre over `cells x cells` cells of the equal-area square of standard-space
/// normals (4 x 4 nodes each): calls `f(h, weight)` with the half vector (or normal) `h` of
/// each node and its weight in steradians of `h` (the Jacobian from the standard sphere
/// included), so that sums of `density(h) weight` integrate over the sphere of `h`.
fn standard_quadrature(g: Ggx, cells: usize, mut f: impl FnMut(V3, f64)) {
    for j in 0..cells {
        for i in 0..cells {
            for (a, wa) in gauss4() {
                for (b, wb) in gauss4() {
                    let s = [(i as f64 + a) / cells as f64, (j as f64 + b) / cells as f64];
                    let (h, jac) = g.standard_to_normal(unparam(s));
                    f(h, jac * 4.0 * PI * wa * wb / (cells * cells) as f64);
                }
            }
        }
    }
}

/// `(integral over the sphere, integral below the horizon)` of the library's two reflection
/// densities, caps then bounded (`f32` functions at `f64`-computed directions, accumulated
/// in `f64`), by Gauss-Legendre over cells of the sphere of standard-space half vectors
/// (256 x 256 cells, 4 x 4 nodes each), both in one pass. Also asserts that the bounded
/// density is positive above the horizon wherever the caps density is (its removed cap holds
/// only reflections below it).
fn integrals(wo: [f32; 3], alpha: [f32; 2]) -> [(f64, f64); 2] {
    let g = Ggx::new(alpha);
    let wo64 = normalize(d3(wo));
    let mut sums = [(0.0, 0.0); 2];
    standard_quadrature(g, 256, |h, weight| {
        let wh = dot(wo64, h);
        if wh <= 0.0 {
            return;
        }
        let wi = reflect(wo64, h);
        let wi32 = wi.map(|x| x as f32);
        let caps = mf::ggx_reflect_pdf(wo, wi32, alpha);
        let bounded = mf::ggx_reflect_bounded_pdf(wo, wi32, alpha);
        // Where `alpha wo.h` is below 1e-3 the f32 half vector of the f32
        // `wi` is not accurate enough to decide (see the pdf's error bound).
        let amin = g.ax.min(g.ay);
        if wi[2] > 1e-6 && amin * wh > 1e-3 && caps > 0.0 {
            assert!(
                bounded > 0.0,
                "bounded 0 above the horizon: {wo:?} {wi:?} {alpha:?}"
            );
        }
        for (sum, p) in sums.iter_mut().zip([caps, bounded]) {
            let v = p as f64 * 4.0 * wh * weight;
            sum.0 += v;
            if wi[2] <= 0.0 {
                sum.1 += v;
            }
        }
    });
    sums
}

/// Both reflection densities integrate to 1 over the sphere within 2e-3 (the quadrature's
/// own error at the bounded density's rim; 1e-4 for the smooth caps density where `alpha`
/// is not tiny), and the bounded sampler puts no more of its directions below the horizon
/// than the caps sampler (the table of `docs/warps.md`, printed).
#[test]
fn densities_integrate_to_one_and_below_horizon() {
    eprintln!("| alpha | wo.z | caps below | bounded below | caps integral | bounded integral |");
    for alpha in [
        [0.01f32, 0.01],
        [0.1, 0.1],
        [0.3, 0.3],
        [0.5, 0.5],
        [0.8, 0.8],
        [1.0, 1.0],
        [0.1, 0.6],
    ] {
        for z in [1.0, 0.7, 0.3, 0.1, 0.01, 1e-4] {
            let wo = outgoing(z);
            let [(tc, bc), (tb, bb)] = integrals(wo, alpha);
            eprintln!(
                "| {alpha:?} | {z} | {:.4} | {:.4} | {tc:.6} | {tb:.6} |",
                bc / tc,
                bb / tb
            );
            assert!(
                (tc - 1.0).abs() < 1e-3,
                "caps integral {tc} at {alpha:?} {z}"
            );
            assert!(
                (tb - 1.0).abs() < 2e-3,
                "bounded integral {tb} at {alpha:?} {z}"
            );
            assert!(bb / tb <= bc / tc + 1e-4, "bounded below {bb} > caps {bc}");
        }
    }
}

/// `ggx_d` integrates to 1 against `m.z` (the normalisation of a distribution of normals),
/// and visible normals' density to 1 over the sphere (quadrature in standard space).
#[test]
fn d_and_visible_density_normalised() {
    for alpha in ALPHAS {
        let g = Ggx::new(alpha);
        for z in [1.0, 0.3, 1e-4] {
            let wo = outgoing(z);
            let (mut dz, mut vn) = (0.0, 0.0);
            standard_quadrature(g, 128, |m, w| {
                let m32 = m.map(|x| x as f32);
                dz += mf::ggx_d(m32, alpha) as f64 * m[2] * w;
                vn += mf::ggx_visible_normal_pdf(wo, m32, alpha) as f64 * w;
            });
            assert!((dz - 1.0).abs() < 1e-4, "D m.z integral {dz} at {alpha:?}");
            assert!(
                (vn - 1.0).abs() < 1e-4,
                "D_wo integral {vn} at {alpha:?} {z}"
            );
        }
    }
}

fn log_sweep(lo: f64, hi: f64, n: usize) -> impl Iterator<Item = f64> {
    (0..n).map(move |i| lo * (hi / lo).powf(i as f64 / (n - 1) as f64))
}

/// Error against `f64` over dense sweeps: `wo.z` from 1e-6 to 1, `alpha` from 1e-4 to 1
/// (isotropic and anisotropic), 64 samples each: returned directions unit within 1e-6;
/// densities at the returned directions within the documented bounds; `D`, `G1`, `G2`.
#[test]
fn error_against_f64() {
    let mut r = rng(99);
    let (mut unit_err, mut e_d, mut e_g1, mut e_g2) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut e_vn, mut e_vn_cond, mut e_rf, mut e_bd) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    let (mut e_rf_cond, mut n_rf, mut n_rf_over) = (0.0f64, 0u64, 0u64);
    let (mut e_bd_cond, mut n_vn_over, mut n_bd_over) = (0.0f64, 0u64, 0u64);
    for z in log_sweep(1e-6, 1.0, 40) {
        for ax in log_sweep(1e-4, 1.0, 17) {
            for ratio in [1.0, 0.1, 7.0] {
                let alpha = [ax as f32, (ax * ratio).clamp(1e-4, 1.0) as f32];
                let g = Ggx::new(alpha);
                let wo = outgoing(z);
                let wo64 = normalize(d3(wo));
                for _ in 0..64 {
                    let u = unit2(&mut r);
                    let m = mf::ggx_visible_normal(wo, alpha, u);
                    let (wi, p) = mf::ggx_reflect(wo, alpha, u);
                    let (wb, pb) = mf::ggx_reflect_bounded(wo, alpha, u);
                    for v in [m, wi, wb] {
                        unit_err = unit_err.max((dot(d3(v), d3(v)).sqrt() - 1.0).abs());
                    }
                    assert!(m[2] > 0.0, "{m:?}");
                    let rel = |a: f32, b: f64| {
                        if b > 1e-30 {
                            (a as f64 - b).abs() / b
                        } else {
                            0.0
                        }
                    };
                    let (m64, wm) = (normalize(d3(m)), dot(wo64, normalize(d3(m))));
                    let evn = rel(mf::ggx_visible_normal_pdf(wo, m, alpha), g.vndf(wo64, m64));
                    e_vn = e_vn.max(evn);
                    n_vn_over += (evn > 1e-5) as u64;
                    e_vn_cond = e_vn_cond.max(evn * wm);
                    let h = normalize([
                        wo64[0] + d3(wi)[0],
                        wo64[1] + d3(wi)[1],
                        wo64[2] + d3(wi)[2],
                    ]);
                    let amin = g.ax.min(g.ay);
                    let erf = rel(p, g.reflect_pdf(wo64, d3(wi)));
                    e_rf = e_rf.max(erf);
                    e_rf_cond = e_rf_cond.max(erf * amin * dot(wo64, h));
                    n_rf += 1;
                    n_rf_over += (erf > 1e-5) as u64;
                    let hb = normalize([
                        wo64[0] + d3(wb)[0],
                        wo64[1] + d3(wb)[1],
                        wo64[2] + d3(wb)[2],
                    ]);
                    let ebd = rel(pb, g.bounded_pdf(wo64, d3(wb)));
                    e_bd = e_bd.max(ebd);
                    n_bd_over += (ebd > 1e-5) as u64;
                    e_bd_cond = e_bd_cond.max(ebd * amin * dot(wo64, hb));
                    e_d = e_d.max(rel(mf::ggx_d(m, alpha), g.d(m64)));
                    e_g1 = e_g1.max(rel(mf::ggx_g1(wo, alpha), g.g1(wo64)));
                    if wi[2] > 0.0 {
                        e_g2 = e_g2.max(rel(mf::ggx_g2(wo, wi, alpha), g.g2(wo64, d3(wi))));
                    }
                }
            }
        }
    }
    eprintln!("unit: {unit_err:.2e}; D {e_d:.2e}; G1 {e_g1:.2e}; G2 {e_g2:.2e}");
    eprintln!(
        "visible pdf {e_vn:.2e} (times wo.m: {e_vn_cond:.2e}); over 1e-5: {n_vn_over}; bounded over 1e-5: {n_bd_over}"
    );
    eprintln!(
        "reflect pdf {e_rf:.2e} (times alpha_min wo.h: {e_rf_cond:.2e}); over 1e-5: {n_rf_over} of {n_rf}; bounded {e_bd:.2e} (times alpha_min wo.h: {e_bd_cond:.2e})"
    );
    assert!(unit_err < 1e-6);
    // The target: every density within 1e-5 relative of f64 over the whole sweep (where it
    // exceeds 1e-30), and the documented figures (2e-6) with it.
    assert!(
        n_vn_over == 0 && n_rf_over == 0 && n_bd_over == 0,
        "over 1e-5: visible {n_vn_over}, reflect {n_rf_over}, bounded {n_bd_over}"
    );
    assert!(
        e_vn < 2e-6 && e_rf < 2e-6 && e_bd < 2e-6,
        "visible {e_vn} reflect {e_rf} bounded {e_bd}"
    );
    assert!(e_d < 1e-6 && e_g1 < 1e-6 && e_g2 < 1e-6);
}

/// Totality on the hostile cross products, as a covering array of strength 2: every special
/// value in every coordinate of `wo` (all triples), each `wo` with every special roughness
/// pair (its `u` cycling through the special samples) and with every special sample (its
/// roughness cycling), so every pair of (`wo`, `alpha`, `u`) values meets; and the densities
/// over special `wo` x special `wi` x special roughness the same way. (The full triple
/// products, 10-13x the calls, also passed; they cost half a minute per run.)
#[test]
fn hostile_inputs() {
    let sp = specials();
    let triples = common::special_triples(&sp);
    let pairs = common::special_pairs();
    let alphas: Vec<[f32; 2]> = pairs.iter().step_by(7).copied().collect();
    let us: Vec<[f32; 2]> = pairs.iter().step_by(37).copied().collect();
    let unit_ok = |v: [f32; 3]| {
        let l = dot(d3(v), d3(v)).sqrt();
        v.iter().all(|x| x.is_finite()) && (l - 1.0).abs() < 1e-6
    };
    let dens_ok = |p: f32| (0.0..f32::MAX).contains(&p);
    let sample = |wo: [f32; 3], alpha: [f32; 2], u: [f32; 2]| {
        let m = mf::ggx_visible_normal(wo, alpha, u);
        assert!(unit_ok(m) && m[2] > 0.0, "{wo:?} {alpha:?} {u:?} -> {m:?}");
        for (wi, p) in [
            mf::ggx_reflect(wo, alpha, u),
            mf::ggx_reflect_bounded(wo, alpha, u),
        ] {
            assert!(
                unit_ok(wi) && dens_ok(p),
                "{wo:?} {alpha:?} {u:?} -> {wi:?} {p}"
            );
        }
    };
    for (k, &wo) in triples.iter().enumerate() {
        for &alpha in &alphas {
            sample(wo, alpha, us[k % us.len()]);
            for v in [mf::ggx_d(wo, alpha), mf::ggx_g1(wo, alpha)] {
                assert!(dens_ok(v), "{wo:?} {alpha:?} -> {v}");
            }
        }
        for &u in &us {
            sample(wo, alphas[k % alphas.len()], u);
        }
    }
    let some: Vec<[f32; 3]> = triples.iter().step_by(61).copied().collect();
    let some_alphas: Vec<[f32; 2]> = alphas.iter().step_by(9).copied().collect();
    let densities = |wo: [f32; 3], wi: [f32; 3], alpha: [f32; 2]| {
        for v in [
            mf::ggx_visible_normal_pdf(wo, wi, alpha),
            mf::ggx_reflect_pdf(wo, wi, alpha),
            mf::ggx_reflect_bounded_pdf(wo, wi, alpha),
            mf::ggx_g2(wo, wi, alpha),
        ] {
            assert!(dens_ok(v), "{wo:?} {wi:?} {alpha:?} -> {v}");
        }
    };
    for (k, &wo) in triples.iter().enumerate() {
        for &wi in &some {
            densities(wo, wi, some_alphas[k % some_alphas.len()]);
        }
        for &alpha in &some_alphas {
            densities(wo, some[k % some.len()], alpha);
        }
    }
}

/// The documented out-of-domain rules: `wo` below the horizon samples like its mirror
/// image; an invalid `wo` like `+z`; `alpha` clamped.
#[test]
fn documented_rules() {
    let (alpha, u) = ([0.3f32, 0.2], [0.3f32, 0.6]);
    let wo = [0.3f32, -0.4, 0.5];
    let below = [0.3f32, -0.4, -0.5];
    assert_eq!(
        mf::ggx_reflect(wo, alpha, u),
        mf::ggx_reflect(below, alpha, u)
    );
    let z = [0.0f32, 0.0, 1.0];
    for bad in [[0.0f32; 3], [f32::NAN, 0.0, 1.0], [f32::INFINITY, 0.0, 0.0]] {
        assert_eq!(
            mf::ggx_visible_normal(bad, alpha, u),
            mf::ggx_visible_normal(z, alpha, u)
        );
        assert_eq!(mf::ggx_reflect_pdf(z, bad, alpha), 0.0);
    }
    assert_eq!(
        mf::ggx_visible_normal(wo, [0.0, f32::NAN], u),
        mf::ggx_visible_normal(wo, [1e-4, 1e-4], u)
    );
    assert_eq!(
        mf::ggx_visible_normal(wo, [7.0, f32::INFINITY], u),
        mf::ggx_visible_normal(wo, [1.0, 1.0], u)
    );
    // Grazing: finite, and G1 = 0 there.
    let graze = [1.0f32, 0.0, 0.0];
    assert_eq!(mf::ggx_g1(graze, alpha), 0.0);
    let (wi, p) = mf::ggx_reflect(graze, alpha, u);
    assert!(p.is_finite() && p > 0.0 && wi[2].is_finite());
}

/// Scalar, `_x8`, `_x16` and slice forms agree bit for bit (also on special values).
#[test]
fn widths_agree() {
    let mut r = rng(5);
    let sp = specials();
    let mut pick = |i: usize| {
        if i.is_multiple_of(3) {
            sp[i % sp.len()]
        } else {
            common::unit(&mut r) * 2.0 - 0.5
        }
    };
    let pts7: Vec<[f32; 7]> = (0..8 * 64)
        .map(|i| std::array::from_fn(|k| pick(i * 7 + k)))
        .collect();
    let pts8: Vec<[f32; 8]> = (0..8 * 64)
        .map(|i| std::array::from_fn(|k| pick(i * 8 + k + 1)))
        .collect();
    let s7 = |x: [f32; 7]| ([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]]);
    for c in pts7.chunks_exact(8) {
        let c: &[[f32; 7]; 8] = c.try_into().unwrap();
        common::check_widths(
            "visible",
            c,
            |x| {
                let (a, b, u) = s7(x);
                mf::ggx_visible_normal(a, b, u)
            },
            |x| mf::ggx_visible_normal_x8([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]]),
            mf::ggx_visible_normal_slice,
        );
        common::check_widths(
            "bounded",
            c,
            |x| {
                let (a, b, u) = s7(x);
                let (w, p) = mf::ggx_reflect_bounded(a, b, u);
                [w[0], w[1], w[2], p]
            },
            |x| {
                let (w, p) =
                    mf::ggx_reflect_bounded_x8([x[0], x[1], x[2]], [x[3], x[4]], [x[5], x[6]]);
                [w[0], w[1], w[2], p]
            },
            mf::ggx_reflect_bounded_slice,
        );
    }
    for c in pts8.chunks_exact(8) {
        let c: &[[f32; 8]; 8] = c.try_into().unwrap();
        common::check_widths(
            "reflect pdf",
            c,
            |x| {
                [mf::ggx_reflect_pdf(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    [x[6], x[7]],
                )]
            },
            |x| {
                [mf::ggx_reflect_pdf_x8(
                    [x[0], x[1], x[2]],
                    [x[3], x[4], x[5]],
                    [x[6], x[7]],
                )]
            },
            mf::ggx_reflect_pdf_slice,
        );
    }
    common::check_slice_lengths(
        &pts7[..20],
        |x| {
            let (a, b, u) = s7(x);
            let (w, p) = mf::ggx_reflect(a, b, u);
            [w[0], w[1], w[2], p]
        },
        mf::ggx_reflect_slice,
    );
}
