//! The sampling cores the path tracer is driven by, behind one trait: the scene code is the
//! same for all, only the source of the path's dimensions changes.
//!
//! A path asks for its dimensions by *domain*: domain 0 the position in the pixel (2D),
//! domain 1 the lens (2D), domain `2 + d` the light point and the BSDF direction of vertex
//! `d` (4D), domain [`ROULETTE_DOMAIN`]` + d` the roulette's decision at vertex `d` (its first
//! dimension), and [`PathSampler::rnd`] an unstratified number (the `/rr-rnd` variant's
//! roulette). Each core maps that onto its own interface:
//!
//! * warpcore `Sampler<P>`: `root.domain(k).draw::<N>()`, `rnd` for `rnd`; `Blue<P>` the
//!   same but a 4D request as two 2D draws of sub-domains ([`WarpcorePairs`]: the draw the
//!   blue-noise tiles are optimised for, docs/sampler.md "Over a whole path");
//! * openqmc-rs (`X::new(x, y, frame, index).new_domain(k).draw_sample_f32::<N>()`), the frame
//!   carrying the seed, `draw_rnd_f32` for `rnd`;
//! * `sobol_burley::sample_4d(index, k, seed)`: domain `k` is the 4D dimension set `k`,
//!   padded (a 2D request uses its first two dimensions); the seed hashes the pixel;
//! * a pbrt-v4-style PMJ02BN: the 2D pair `j` of the path reads table set `j mod SETS` at a
//!   per-pixel, per-pair random permutation of the `spp` sample indices, shifted by a
//!   per-pixel, per-pair Cranley-Patterson rotation (as pbrt-v4's `PMJ02BNSampler` does; our
//!   own code over warpcore's tables);
//! * independent uniform random numbers (a counter hash);
//! * the path study's Laine-Karras, Sobol'-RDS and Sobol'-enum ([`super::qmc`]).

use openqmc::SamplerImpl;
use warpcore::pmj02bn;
use warpcore::sampler::{Pattern, Sampler};

/// The source of one path sample's dimensions.
pub trait PathSampler: Sync {
    /// Everything one sample needs (a root state).
    type Sample: Copy;
    /// Sample `index` of `spp` of `pixel` in the render keyed by `seed`.
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> Self::Sample;
    /// Two stratified dimensions of `domain`.
    fn draw2(&self, s: &Self::Sample, domain: u32) -> [f32; 2];
    /// Four stratified dimensions of `domain`.
    fn draw4(&self, s: &Self::Sample, domain: u32) -> [f32; 4];
    /// One unstratified number for `domain` (Russian roulette).
    fn rnd(&self, s: &Self::Sample, domain: u32) -> f32;
}

/// The roulette's own domain key, away from the stratified domains.
const RND_DOMAIN: u32 = 0x100;

/// The first domain of the roulette's stratified decisions (domain `ROULETTE_DOMAIN + d` at
/// vertex `d`), away from the path's domains `0..=6` and below `sobol_burley`'s 64 sets.
pub const ROULETTE_DOMAIN: u32 = 32;

/// lowbias32 (Wellons): a well-mixed bijective 32-bit hash.
pub fn hash32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

fn unit(x: u32) -> f32 {
    (x >> 8) as f32 * (1.0 / (1u32 << 24) as f32)
}

/// warpcore's sampling core with pattern `P`.
#[derive(Clone, Copy)]
pub struct Warpcore<P>(pub std::marker::PhantomData<fn() -> P>);

impl<P: Pattern> PathSampler for Warpcore<P> {
    type Sample = Sampler<P>;
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> Sampler<P> {
        Sampler::<P>::new(pixel, 0, index, seed)
    }
    fn draw2(&self, s: &Sampler<P>, domain: u32) -> [f32; 2] {
        s.domain(domain).draw::<2>()
    }
    fn draw4(&self, s: &Sampler<P>, domain: u32) -> [f32; 4] {
        s.domain(domain).draw::<4>()
    }
    fn rnd(&self, s: &Sampler<P>, domain: u32) -> f32 {
        s.domain(RND_DOMAIN + domain).rnd::<1>()[0]
    }
}

/// warpcore's sampling core as `Blue<P>` wants it (docs/sampler.md, "Over a whole path"):
/// each 2D decision from its own domain with `draw::<2>()`, the draw the blue-noise tiles are
/// optimised for, and the first decisions from the root's spatiotemporal slots (domains
/// `0..BLUE_SLOTS`): the pixel position (domain 0), the lens (1), and the light point and the
/// BSDF direction of vertex `d` from `root.domain(2 + 2 d)` and `root.domain(3 + 2 d)` —
/// slots for vertices 0 and 1, other domains of the root after them — instead of one
/// `draw::<4>()`, whose dimensions 2-3 are not blue across pixels. Otherwise [`Warpcore`]'s.
#[derive(Clone, Copy)]
pub struct WarpcorePairs<P>(pub std::marker::PhantomData<fn() -> P>);

impl<P: Pattern> PathSampler for WarpcorePairs<P> {
    type Sample = Sampler<P>;
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> Sampler<P> {
        Warpcore::<P>(std::marker::PhantomData).sample(pixel, index, spp, seed)
    }
    fn draw2(&self, s: &Sampler<P>, domain: u32) -> [f32; 2] {
        s.domain(domain).draw::<2>()
    }
    fn draw4(&self, s: &Sampler<P>, domain: u32) -> [f32; 4] {
        // Vertex d = domain - 2 (the path's 4D draws start at domain 2): root domains
        // 2 + 2 d and 3 + 2 d, below ROULETTE_DOMAIN for every depth the tracer reaches.
        let light = domain.wrapping_sub(1).wrapping_mul(2);
        let bsdf = light.wrapping_add(1);
        let ([a, b], [c, d]) = (s.domain(light).draw::<2>(), s.domain(bsdf).draw::<2>());
        [a, b, c, d]
    }
    fn rnd(&self, s: &Sampler<P>, domain: u32) -> f32 {
        Warpcore::<P>(std::marker::PhantomData).rnd(s, domain)
    }
}

/// An openqmc-rs sampler; the render's seed goes in as the frame number.
pub struct OpenQmc<T>(pub std::marker::PhantomData<fn() -> T>);

impl<T: SamplerImpl> PathSampler for OpenQmc<openqmc::Sampler<T>> {
    type Sample = openqmc::Sampler<T>;
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> Self::Sample {
        Self::Sample::new(
            pixel[0] as i32,
            pixel[1] as i32,
            (seed & 0x7fff_ffff) as i32,
            index as i32,
        )
    }
    fn draw2(&self, s: &Self::Sample, domain: u32) -> [f32; 2] {
        s.new_domain(domain as i32).draw_sample_f32::<2>()
    }
    fn draw4(&self, s: &Self::Sample, domain: u32) -> [f32; 4] {
        s.new_domain(domain as i32).draw_sample_f32::<4>()
    }
    fn rnd(&self, s: &Self::Sample, domain: u32) -> f32 {
        s.new_domain((RND_DOMAIN + domain) as i32)
            .draw_rnd_f32::<1>()[0]
    }
}

/// `sobol_burley::sample_4d`, padded: domain `k` is dimension set `k`.
pub struct SobolBurley;

impl PathSampler for SobolBurley {
    /// (index, seed of the pixel)
    type Sample = (u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> (u32, u32) {
        (index, hash32(pixel[0] ^ hash32(pixel[1] ^ hash32(seed))))
    }
    fn draw2(&self, s: &(u32, u32), domain: u32) -> [f32; 2] {
        let p = sobol_burley::sample_4d(s.0, domain, s.1);
        [p[0], p[1]]
    }
    fn draw4(&self, s: &(u32, u32), domain: u32) -> [f32; 4] {
        sobol_burley::sample_4d(s.0, domain, s.1)
    }
    fn rnd(&self, s: &(u32, u32), domain: u32) -> f32 {
        unit(hash32(s.1 ^ hash32(s.0 ^ hash32(RND_DOMAIN + domain))))
    }
}

/// A bijection of `[0, 2^bits)` keyed by `key` (xor, odd multiply and xorshift, each a
/// bijection modulo `2^bits`), extended to `[0, n)` by cycle walking.
pub fn permute(i: u32, n: u32, key: u32) -> u32 {
    if n <= 1 {
        return 0;
    }
    let bits = 32 - (n - 1).leading_zeros();
    let mask = if bits == 32 {
        u32::MAX
    } else {
        (1 << bits) - 1
    };
    let mult = hash32(key ^ 0x68e3_1da4) | 1;
    let mut x = i;
    loop {
        x ^= key & mask;
        x = x.wrapping_mul(mult) & mask;
        x ^= (x >> (bits / 2 + 1)) & mask;
        x = x.wrapping_mul(0x2c1b_3c6d | 1) & mask;
        x ^= (key >> 16) & mask;
        x = x.wrapping_mul(0x297a_2d39 | 1) & mask;
        x ^= x >> (bits / 3 + 1);
        if x < n {
            return x;
        }
    }
}

/// pbrt-v4-style PMJ02BN over warpcore's tables (see the module docs).
pub struct PbrtPmj;

impl PbrtPmj {
    fn pair(&self, s: &([u32; 2], u32, u32, u32), pair: u32) -> [f32; 2] {
        let (pixel, index, spp, seed) = *s;
        let key = hash32(pixel[0] ^ hash32(pixel[1] ^ hash32(pair ^ hash32(seed))));
        let i = permute(index, spp, key) as usize % pmj02bn::POINTS;
        let set = pair as usize % pmj02bn::SETS;
        let p = pmj02bn::raw(set, i);
        let shift = [hash32(key ^ 0x5bd1_e995), hash32(key ^ 0x1b87_3593)];
        [
            unit(p[0].wrapping_add(shift[0])),
            unit(p[1].wrapping_add(shift[1])),
        ]
    }
}

impl PathSampler for PbrtPmj {
    /// (pixel, index, spp, seed)
    type Sample = ([u32; 2], u32, u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, spp: u32, seed: u32) -> Self::Sample {
        (pixel, index, spp.max(1), seed)
    }
    fn draw2(&self, s: &Self::Sample, domain: u32) -> [f32; 2] {
        self.pair(s, 2 * domain)
    }
    fn draw4(&self, s: &Self::Sample, domain: u32) -> [f32; 4] {
        let [a, b] = self.pair(s, 2 * domain);
        let [c, d] = self.pair(s, 2 * domain + 1);
        [a, b, c, d]
    }
    fn rnd(&self, s: &Self::Sample, domain: u32) -> f32 {
        let key = hash32(s.0[0] ^ hash32(s.0[1] ^ hash32(s.3)));
        unit(hash32(key ^ hash32(s.1 ^ hash32(RND_DOMAIN + domain))))
    }
}

/// Independent uniform numbers: a counter hash of (seed, pixel, index, domain, dimension).
pub struct Random;

impl Random {
    fn value(s: &(u32, u32), domain: u32, dim: u32) -> f32 {
        unit(hash32(s.0 ^ hash32(s.1 ^ hash32(domain * 8 + dim))))
    }
}

impl PathSampler for Random {
    /// (hash of seed and pixel, index)
    type Sample = (u32, u32);
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> (u32, u32) {
        (
            hash32(seed ^ hash32(pixel[0] ^ hash32(pixel[1] ^ 0x2545_f491))),
            index,
        )
    }
    fn draw2(&self, s: &(u32, u32), domain: u32) -> [f32; 2] {
        [Self::value(s, domain, 0), Self::value(s, domain, 1)]
    }
    fn draw4(&self, s: &(u32, u32), domain: u32) -> [f32; 4] {
        std::array::from_fn(|k| Self::value(s, domain, k as u32))
    }
    fn rnd(&self, s: &(u32, u32), domain: u32) -> f32 {
        Self::value(s, RND_DOMAIN + domain, 0)
    }
}

/// The reference's own stream: splitmix64 of a 64-bit key (no 32-bit hash, no sampler of
/// the test list), 53 random bits per value rounded to f32.
pub struct ReferenceRandom;

impl PathSampler for ReferenceRandom {
    type Sample = u64;
    fn sample(&self, pixel: [u32; 2], index: u32, _spp: u32, seed: u32) -> u64 {
        crate::math::hash(&[
            0x7265_6665_7265_6e63,
            seed as u64,
            pixel[0] as u64,
            pixel[1] as u64,
            index as u64,
        ])
    }
    fn draw2(&self, s: &u64, domain: u32) -> [f32; 2] {
        let d = self.draw4(s, domain);
        [d[0], d[1]]
    }
    fn draw4(&self, s: &u64, domain: u32) -> [f32; 4] {
        std::array::from_fn(|k| {
            let z = crate::math::mix64(s ^ crate::math::mix64((domain as u64) << 8 | k as u64));
            ((z >> 40) as f32) * (1.0 / (1u64 << 24) as f32)
        })
    }
    fn rnd(&self, s: &u64, domain: u32) -> f32 {
        self.draw4(s, RND_DOMAIN + domain)[0]
    }
}

/// The samplers of the comparison, by their CSV names.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Kind {
    Pmj02bn,
    Sobol,
    BluePmj02bn,
    BlueSobol,
    OpenqmcSobol,
    OpenqmcSobolbn,
    OpenqmcPmj,
    OpenqmcPmjbn,
    OpenqmcLattice,
    OpenqmcLatticebn,
    SobolBurley,
    PbrtPmj02bn,
    Random,
    LaineKarras,
    LkShuffled,
    SobolRds,
    SobolEnum,
}

pub const KINDS: [Kind; 13] = [
    Kind::Pmj02bn,
    Kind::Sobol,
    Kind::BluePmj02bn,
    Kind::BlueSobol,
    Kind::OpenqmcSobol,
    Kind::OpenqmcSobolbn,
    Kind::OpenqmcPmj,
    Kind::OpenqmcPmjbn,
    Kind::OpenqmcLattice,
    Kind::OpenqmcLatticebn,
    Kind::SobolBurley,
    Kind::PbrtPmj02bn,
    Kind::Random,
];

/// The samplers of Burley 2020's comparison that only the path study runs
/// ([`super::qmc`]).
pub const BURLEY_KINDS: [Kind; 4] = [
    Kind::LaineKarras,
    Kind::SobolRds,
    Kind::SobolEnum,
    Kind::LkShuffled,
];

impl Kind {
    pub fn name(self) -> &'static str {
        match self {
            Kind::Pmj02bn => "pmj02bn",
            Kind::Sobol => "sobol",
            Kind::BluePmj02bn => "blue_pmj02bn",
            Kind::BlueSobol => "blue_sobol",
            Kind::OpenqmcSobol => "openqmc_sobol",
            Kind::OpenqmcSobolbn => "openqmc_sobolbn",
            Kind::OpenqmcPmj => "openqmc_pmj",
            Kind::OpenqmcPmjbn => "openqmc_pmjbn",
            Kind::OpenqmcLattice => "openqmc_lattice",
            Kind::OpenqmcLatticebn => "openqmc_latticebn",
            Kind::SobolBurley => "sobol_burley",
            Kind::PbrtPmj02bn => "pbrt_pmj02bn",
            Kind::Random => "random",
            Kind::LaineKarras => "laine_karras",
            Kind::LkShuffled => "lk_shuffled",
            Kind::SobolRds => "sobol_rds",
            Kind::SobolEnum => "sobol_enum",
        }
    }

    /// The position in [`KINDS`], then [`BURLEY_KINDS`].
    pub fn index(self) -> usize {
        KINDS
            .iter()
            .chain(&BURLEY_KINDS)
            .position(|&k| k == self)
            .unwrap_or(0)
    }

    /// The sampler of CSV name `name`.
    pub fn by_name(name: &str) -> Option<Kind> {
        KINDS
            .into_iter()
            .chain(BURLEY_KINDS)
            .find(|k| k.name() == name)
    }

    /// warpcore's own samplers (the others are peers).
    pub fn is_warpcore(self) -> bool {
        self.index() < 4
    }

    /// Builds any tables the peers build lazily, so no timing pays for them.
    pub fn warm_all() {
        openqmc::SobolSampler::warm_cache();
        openqmc::SobolBnSampler::warm_cache();
        openqmc::PmjSampler::warm_cache();
        openqmc::PmjBnSampler::warm_cache();
        openqmc::LatticeSampler::warm_cache();
        openqmc::LatticeBnSampler::warm_cache();
    }
}

/// Calls `$body` with `$s` bound to the sampler of `$kind` (a generic call per core: the
/// scene code is monomorphised for each, no dynamic dispatch inside a path). One line per
/// [`Kind`]: its sampler value.
macro_rules! with_sampler {
    ($kind:expr, $s:ident => $body:expr) => {{
        use std::marker::PhantomData as PD;
        use warpcore::sampler::{Blue, Pmj02bn, Sobol};
        use $crate::path::samplers::*;
        $crate::path::samplers::with_sampler!(@match $kind, $s, $body,
            Pmj02bn => Warpcore::<Pmj02bn>(PD),
            Sobol => Warpcore::<Sobol>(PD),
            BluePmj02bn => WarpcorePairs::<Blue<Pmj02bn>>(PD),
            BlueSobol => WarpcorePairs::<Blue<Sobol>>(PD),
            OpenqmcSobol => OpenQmc::<openqmc::SobolSampler>(PD),
            OpenqmcSobolbn => OpenQmc::<openqmc::SobolBnSampler>(PD),
            OpenqmcPmj => OpenQmc::<openqmc::PmjSampler>(PD),
            OpenqmcPmjbn => OpenQmc::<openqmc::PmjBnSampler>(PD),
            OpenqmcLattice => OpenQmc::<openqmc::LatticeSampler>(PD),
            OpenqmcLatticebn => OpenQmc::<openqmc::LatticeBnSampler>(PD),
            SobolBurley => SobolBurley,
            PbrtPmj02bn => PbrtPmj,
            Random => Random,
            LaineKarras => $crate::path::qmc::PerPixel::<{ $crate::path::qmc::LAINE_KARRAS }>,
            LkShuffled => $crate::path::qmc::PerPixel::<{ $crate::path::qmc::LK_SHUFFLED }>,
            SobolRds => $crate::path::qmc::PerPixel::<{ $crate::path::qmc::SOBOL_RDS }>,
            SobolEnum => $crate::path::qmc::SobolEnum::new(),
        )
    }};
    (@match $kind:expr, $s:ident, $body:expr, $($k:ident => $v:expr,)*) => {
        match $kind {
            $(Kind::$k => {
                let $s = &$v;
                $body
            })*
        }
    };
}

pub(crate) use with_sampler;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn permute_is_a_bijection() {
        for n in [1u32, 2, 3, 4, 7, 16, 100, 256] {
            for key in [0u32, 1, 0xdead_beef, 12345] {
                let mut seen = vec![false; n as usize];
                for i in 0..n {
                    let j = permute(i, n, key);
                    assert!(j < n && !seen[j as usize], "n={n} key={key}");
                    seen[j as usize] = true;
                }
            }
        }
    }

    #[test]
    fn every_sampler_draws_in_the_unit_interval() {
        for kind in KINDS.into_iter().chain(BURLEY_KINDS) {
            with_sampler!(kind, s => {
                for i in 0..64 {
                    let smp = s.sample([3, 5], i, 64, 7);
                    for d in 0..8 {
                        let v = s.draw4(&smp, d);
                        let w = s.draw2(&smp, d);
                        let r = s.rnd(&smp, d);
                        assert!(v.iter().chain(&w).chain([&r]).all(|x| (0.0..1.0).contains(x)), "{}", kind.name());
                    }
                }
            });
        }
    }
}
