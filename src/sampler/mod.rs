//! The sampling core: every dimension a path draws, from one small value per sample.
//!
//! A path tracer draws 10 to 100 dimensions per path — pixel, lens and time, then a light
//! point, a BSDF direction and a roulette decision at every bounce. A [`Sampler`] hands them
//! out through a **domain tree** (the interface of OpenQMC, Academy Software Foundation): a
//! root per (pixel, frame, sample index, seed), an independent child pattern per
//! [`domain`](Sampler::domain) key, and up to four stratified dimensions per
//! [`draw`](Sampler::draw).
//!
//! ```
//! use warpcore::sampler::{Pmj02bn, Sampler};
//!
//! let root = Sampler::<Pmj02bn>::new([12, 34], 0, 7, 0); // pixel, frame, sample index, seed
//! let [px, py] = root.domain(0).draw::<2>();              // position in the pixel
//! let [lens_u, lens_v] = root.domain(1).draw::<2>();      // thin lens
//! for bounce in 0..3u32 {
//!     let b = root.domain(2 + bounce);
//!     let [lu, lv, bu, bv] = b.domain(0).draw::<4>();   // light point and BSDF direction
//!     let [roulette] = b.domain(1).rnd::<1>();           // unstratified: cheap
//!     assert!([lu, lv, bu, bv, roulette].iter().all(|x| (0.0..1.0).contains(x)));
//! }
//! assert!([px, py, lens_u, lens_v].iter().all(|x| (0.0..1.0).contains(x)));
//! ```
//!
//! ## Patterns
//!
//! | pattern | a draw of up to four dimensions | stratified |
//! |---|---|---|
//! | [`Pmj02bn`] | two independent 2D pmj02bn pairs (dimensions 0-1, 2-3) | each pair a (0,2)-sequence |
//! | [`Sobol`] | Owen-scrambled Sobol' dimensions 0..3 | 0-1 a (0,2)-sequence; each dimension a (0,1)-sequence; 2-3 not a (0,2) pair |
//! | [`Blue<P>`](Blue) | `P`, with per-pixel keys from an optimised tile | as `P`, plus screen-space blue-noise error |
//!
//! So `draw::<4>()` means two things: for [`Sobol`] one 4D point (its four dimensions, and
//! every 3D projection, stratified together); for [`Pmj02bn`] two independent (0,2) pairs
//! (each pair stratified, nothing between them). Prefer [`Pmj02bn`] when a 4D draw is two 2D
//! decisions (a light point and a BSDF direction); [`Sobol`] when the four dimensions drive
//! one 3D or 4D integrand, such as a one-sample MIS estimator (the technique and the sample's
//! place from one draw): measured, one driven by one `draw::<4>()` had 4x lower MSE at 256
//! spp with [`Sobol`] (6.2e-5) than with [`Pmj02bn`] (2.6e-4).
//!
//! ## The promises (tested)
//!
//! * **Every argument is valid**: no `u32` panics; see [`split`](Sampler::split) for
//!   `size = 0` and the indices past `2^32`.
//! * **Nets.** For a fixed (pixel, frame, seed, domain path), the points of `draw::<2>()` over
//!   the indices of any aligned power-of-two block `[q 2^m, (q + 1) 2^m)` form a (0,m,2)-net
//!   (every `2^k x 2^(m-k)` grid holds one point per cell) — both pairs of [`Pmj02bn`] (up to
//!   [`pmj02bn::POINTS`](crate::pmj02bn::POINTS) points, see that module for longer runs),
//!   dimensions 0-1 of [`Sobol`] (all `2^32` indices), and the same for [`Blue<P>`](Blue).
//!   Every single dimension is stratified (one point per `2^-m` interval).
//! * **Domains are independent.** `domain(a)` and `domain(b)`, `a != b`, get independent
//!   scrambles *and* independent index shuffles (Burley 2020's nested uniform shuffle), so
//!   their joint projections show no structure. (Two scrambles over one shared index order
//!   would put 1024 points into 16 of the 256 cells of their joint 16 x 16 grid: the
//!   shared-index-order bug.) Sibling keys never collide: `key -> child` is a bijection.
//! * **Splitting is global.** `split(key, size, sub)` gives the child index `index * size +
//!   sub` in a child domain that does not depend on `sub` or the index, so the `size * n`
//!   points of all sub-samples of parent indices `0..n` are one prefix of one sequence: a
//!   (0,m,2)-net when `size * n = 2^m` (OpenQMC's `newDomainSplit`).
//! * **Values.** [`draw`](Sampler::draw) returns `(w >> 8) * 2^-24` of the words
//!   [`draw_u32`](Sampler::draw_u32) returns, so it lies in `[0, 1 - 2^-24]`;
//!   [`rnd`](Sampler::rnd) lies in `[0, 1 - 2^-24]` too. Integer arithmetic only: exact, the
//!   same bits on every target.
//! * **One body.** [`Sampler`], [`SamplerX8`], [`SamplerX16`] and
//!   [`draw_slice`](Sampler::draw_slice) run the same generic body: bit-identical.
//!
//! ## How the state works
//!
//! A [`Sampler`] is three words (12 bytes): the pixel (`x` and `y`, 16 bits each), a 32-bit
//! domain hash and the sample index. [`new`](Sampler::new) hashes the seed and the frame into
//! a root (two mixes a renderer's loop hoists), then — except for [`Blue`], whose pixels must
//! share one key tile — folds in the pixel `x ^ rotl(y, 16)` with one round of a bijective
//! mixer (the first half of Wellons' `lowbias32`): the pixel enters one-to-one below `2^16`
//! per coordinate, so every pixel of any real image gets its own domain hash (larger
//! coordinates are folded in too, their high halves onto the low ones);
//! [`domain`](Sampler::domain) re-hashes it with the same one-round mixer and
//! [`split`](Sampler::split) with the full `lowbias32` (the draw's Laine-Karras keys mix
//! again, so the tree's hashes need not be outputs-grade). A draw derives its shuffle and scramble keys from the domain
//! hash by **rotations**, not by more hashing (the low bits of a Laine-Karras key drive the
//! top levels of its scramble, so rotations give each key its own bits there; OpenQMC
//! rotates bytes the same way): a draw is one shuffle, a table product and the scrambles,
//! which is what makes the scalar form as fast as OpenQMC's (`docs/sampler-performance.md`).
//! Nothing is stored, nothing is shared between threads.

use crate::hash::{lk_hash, mix, mix1, nested_shuffle, owen_scramble, to_unit};
use crate::lanes::{Lane, UintLane};
use crate::pmj02bn::{LOG2_POINTS, POINTS, SETS};
use core::marker::PhantomData;
use core::num::Wrapping;

#[cfg(feature = "blue-noise")]
mod blue;
mod simd;
mod sobol;

#[cfg(feature = "blue-noise")]
#[doc(hidden)]
pub use blue::SLOT_KEYS as BLUE_SLOT_KEYS;
#[cfg(feature = "blue-noise")]
pub use blue::{SLOTS as BLUE_SLOTS, TABLE_BYTES as BLUE_TABLE_BYTES, TILE as BLUE_TILE};
pub use simd::{SamplerX8, SamplerX16};

mod sealed {
    pub trait Sealed {}
}

/// A point pattern a [`Sampler`] draws from: [`Pmj02bn`], [`Sobol`], or either as
/// [`Blue<P>`](Blue). Sealed: the sampler's promises are tested for these alone.
pub trait Pattern:
    Copy + core::fmt::Debug + Default + Eq + core::hash::Hash + sealed::Sealed
{
    /// What the generic body dispatches on (a constant: each instantiation is one path).
    #[doc(hidden)]
    const ID: u8;
}

/// A base pattern, one [`Blue`] can wrap.
pub trait Base: Pattern {}

const PMJ02BN: u8 = 0;
const SOBOL: u8 = 1;
const BLUE: u8 = 2;

/// pmj02bn points (the crate's [`pmj02bn`](crate::pmj02bn) tables, Owen-scrambled): a draw of
/// up to four dimensions is two independent (0,2) pairs — dimensions 0-1 and 2-3 each use
/// their own index shuffle and scrambles.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Pmj02bn;

/// Owen-scrambled Sobol' dimensions 0..3 (own direction numbers from Joe and Kuo's
/// polynomials, Burley's hash-based scrambling). See the table in the [module docs](self).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Sobol;

/// `P` with screen-space blue-noise error: each pixel's keys come from a tile optimised
/// offline, so that neighbouring pixels' errors are negatively correlated at every
/// power-of-two sample count. Each pixel's own points are exactly `P`'s (nets as `P`).
/// Below a [`Sampler::new_frame`] root, domains `0..BLUE_SLOTS` are spatiotemporal slots:
/// blue noise in every frame while the frames continue one net per pixel.
/// Feature `blue-noise`; see the `blue` section of `docs/sampler.md`.
#[cfg(feature = "blue-noise")]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Blue<P>(PhantomData<P>);

impl sealed::Sealed for Pmj02bn {}
impl sealed::Sealed for Sobol {}
impl Pattern for Pmj02bn {
    const ID: u8 = PMJ02BN;
}
impl Pattern for Sobol {
    const ID: u8 = SOBOL;
}
impl Base for Pmj02bn {}
impl Base for Sobol {}
#[cfg(feature = "blue-noise")]
impl<P: Base> sealed::Sealed for Blue<P> {}
#[cfg(feature = "blue-noise")]
impl<P: Base> Pattern for Blue<P> {
    const ID: u8 = BLUE | P::ID;
}

// Hash constants (arbitrary odd values, distinct per use).
const K_SEED: u32 = 0x3c6e_f372;
const K_FRAME: u32 = 0x9e37_79b9;
const K_PIXEL: u32 = 0x85eb_ca6b;
const K_DOMAIN: u32 = 0xc2b2_ae35;
const K_SPLIT: u32 = 0x27d4_eb2f;
const K_RND: u32 = 0x1656_67b1;
const K_BLOCK: u32 = 0x5851_f42d;
const K_SET: [u32; 2] = [0x4c95_7f2d, 0xd1b5_4a35];

/// The three words of a sampler, for one lane type: `Wrapping<u32>`, `u32x8` or `u32x16`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) struct State<U> {
    /// `x | y << 16` (16 bits each: the blue-noise tile position; the full coordinates are
    /// hashed into `domain` by `new` for the other patterns).
    pixel: U,
    domain: U,
    index: U,
}

impl<U: UintLane> State<U> {
    #[inline(always)]
    fn new(id: u8, pixel: [U; 2], frame: U, index: U, seed: U) -> Self {
        let root = mix(mix(seed ^ U::splat(K_SEED)) ^ (frame * U::splat(K_FRAME)));
        // The pixel packed in one word (16 bits per coordinate), what the blue-noise tile
        // position reads. The other patterns hash `x ^ rotl(y, 16)`: the same word for pixels
        // below 2^16 (one-to-one there, so every pixel of any real image gets its own domain
        // hash), the high halves folded onto the low ones above; one round of the mixer
        // (the draw's Laine-Karras keys mix again).
        let packed = (pixel[0] & U::splat(0xffff)) | pixel[1].shl(16);
        let domain = if id & BLUE != 0 {
            blue_tagged(root, TAG_OTHER)
        } else {
            mix1(root ^ pixel[0] ^ pixel[1].rotr(16))
        };
        let pixel = packed;
        State {
            pixel,
            domain,
            index,
        }
    }

    #[inline(always)]
    fn domain(self, id: u8, key: u32) -> Self {
        let h = mix1(self.domain + U::splat(key.wrapping_mul(K_DOMAIN)));
        #[cfg(feature = "blue-noise")]
        let h = if id & BLUE != 0 {
            blue::tag_child(self.domain, key, h)
        } else {
            h
        };
        #[cfg(not(feature = "blue-noise"))]
        let _ = id;
        State { domain: h, ..self }
    }

    #[inline(always)]
    fn split(self, id: u8, key: u32, size: u32, sub: U) -> Self {
        let h = mix((self.domain ^ U::splat(K_SPLIT)) + U::splat(key.wrapping_mul(K_DOMAIN)));
        State {
            domain: if id & BLUE != 0 {
                blue_tagged(h, TAG_OTHER)
            } else {
                h
            },
            index: self.index * U::splat(size.max(1)) + sub,
            ..self
        }
    }

    /// The key and the index of the base pattern's draw: the domain hash and the index, or
    /// under [`Blue`] the pixel's tile key and the index (or in a spatiotemporal slot, the
    /// slot's key and the index moved by the pixel's offset).
    #[inline(always)]
    fn keyed(self, id: u8) -> (U, U) {
        #[cfg(feature = "blue-noise")]
        if id & BLUE != 0 {
            return blue::keyed(id & !BLUE, self.pixel, self.domain, self.index);
        }
        let _ = id;
        (self.domain, self.index)
    }

    /// The stratified point, dimensions `0..N`, 0.32 fixed point.
    #[inline(always)]
    fn bits<const N: usize>(self, id: u8) -> [U; N] {
        const { assert!(N >= 1 && N <= 4, "a draw has 1 to 4 dimensions") };
        let (seed, index) = self.keyed(id);
        if id & !BLUE == SOBOL {
            sobol::point(index, seed)
        } else {
            pmj02bn_pairs(index, seed)
        }
    }

    /// Unstratified values: a counter hash of (pixel, domain, index, dimension).
    #[inline(always)]
    fn rnd<const N: usize>(self, id: u8) -> [U; N] {
        const { assert!(N >= 1 && N <= 4, "a draw has 1 to 4 dimensions") };
        let d = if id & BLUE != 0 {
            self.domain ^ mix(self.pixel ^ U::splat(K_PIXEL))
        } else {
            self.domain
        };
        let h = mix(d ^ mix(self.index ^ U::splat(K_RND)));
        core::array::from_fn(|k| mix(h + U::splat(K_FRAME.wrapping_mul(k as u32 + 1))))
    }
}

/// Two pmj02bn pairs with independent index shuffles and scrambles (the second only when
/// `N > 2`).
#[inline(always)]
fn pmj02bn_pairs<U: UintLane, const N: usize>(index: U, seed: U) -> [U; N] {
    let shuffle = pmj02bn_shuffle_keys(seed);
    let (set, scramble) = pmj02bn_block_keys(seed, index.shr(LOG2_POINTS));
    let pair = |p: usize| {
        let i = nested_shuffle(index, shuffle[p]) & U::splat(POINTS as u32 - 1);
        crate::pmj02bn::table_bits(set[p] | i)
    };
    let a = pair(0);
    let b = if N > 2 { pair(1) } else { a };
    let [x0, y0, x1, y1] = crate::hash::owen_scramble4([a[0], a[1], b[0], b[1]], scramble);
    let (a, b) = ([x0, y0], [x1, y1]);
    core::array::from_fn(|d| [a[0], a[1], b[0], b[1]][d])
}

/// The two pairs' index-shuffle keys: the draw's key `seed` and its half-turn.
#[inline(always)]
fn pmj02bn_shuffle_keys<U: UintLane>(seed: U) -> [U; 2] {
    [seed, seed.rotr(16)]
}

/// What a block of [`POINTS`] consecutive indices (`block = index >> log2(POINTS)`) of a
/// draw keyed by `seed` uses: each pair's table set (pre-shifted, the high bits of a flat
/// table index) and the four Owen-scramble keys (x and y of pair 0, then of pair 1). One
/// mix re-keys every block (the shuffle maps each block onto a block, so every block is a
/// complete scrambled table set); the keys are rotations of it (see [`sobol::keys`]) and the
/// sets the top bits of two odd multiples.
#[inline(always)]
fn pmj02bn_block_keys<U: UintLane>(seed: U, block: U) -> ([U; 2], [U; 4]) {
    let k = mix(seed ^ (block * U::splat(K_BLOCK)));
    let set =
        |p: usize| ((k * U::splat(K_SET[p])).shr(30) & U::splat(SETS as u32 - 1)).shl(LOG2_POINTS);
    ([set(0), set(1)], [k, k.rotr(8), k.rotr(16), k.rotr(24)])
}

/// The slice form of [`pmj02bn_pairs`] on aligned groups of `LN` consecutive indices (`LN` =
/// 8 or 16; group `g` holds indices `first + LN g ..`, `first` a multiple of `LN`): lane by
/// lane the same bits, with what is common to a group computed once.
///
/// Per pair, the nested index shuffle maps the group onto an aligned group `high | sigma(l)`
/// of shuffled indices (`high`: the shuffle of the group's first index, one scalar hash;
/// `sigma`: a permutation of `0..LN` read off the top bits of the hashed lanes), so the
/// group's table points are `LN` consecutive points of one set under one block's keys: they
/// are read as whole vectors, scrambled and converted in table order (x and y keys
/// alternating by lane), and moved to their lanes by two permutes per coordinate. The
/// shuffle maps each aligned block of `POINTS` indices onto one block of the table's, so the
/// keys are derived once per run of groups inside such a block.
#[inline(always)]
fn pmj02bn_groups<L: crate::slices::Rows<LN>, const LN: usize, const N: usize>(
    first: u32,
    seed: u32,
    groups: &mut [[[f32; N]; LN]],
) {
    let pairs = [0, 1].map(|p| PairRun::<L, LN>::new(seed, p));
    let mut done = 0;
    while let Some(rest) = groups.get_mut(done..) {
        if rest.is_empty() {
            break;
        }
        let b = first.wrapping_add((done * LN) as u32);
        let in_block = (POINTS - (b as usize & (POINTS - 1))) / LN;
        let (run, _) = rest.split_at_mut(in_block.min(rest.len()));
        let keys = pairs.map(|p| p.block_keys(b));
        for (g, dst) in run.iter_mut().enumerate() {
            let b = b.wrapping_add((g * LN) as u32).reverse_bits();
            let [x0, y0] = pairs[0].points(b, &keys[0]);
            let [x1, y1] = if N > 2 {
                pairs[1].points(b, &keys[1])
            } else {
                [x0, y0]
            };
            let comps = [x0, y0, x1, y1];
            crate::slices::store_rows(core::array::from_fn(|d| comps[d % 4]), dst);
        }
        done += run.len();
    }
}

/// One pmj02bn pair of the slices (see [`pmj02bn_groups`]): the draw's key, the pair, its
/// shuffle key, and the lane constants.
#[derive(Clone, Copy)]
struct PairRun<L: crate::slices::Rows<LN>, const LN: usize> {
    seed: u32,
    pair: usize,
    shuffle_key: Wrapping<u32>,
    lanes: L::U,
    reverse_s: L::U,
}

/// The keys of one block of the table for one pair: the set and the x/y scramble keys
/// alternating by lane.
struct BlockKeys<L: crate::slices::Rows<LN>, const LN: usize> {
    set: &'static [[u8; 8]; POINTS],
    keys_xy: L::U,
}

impl<L: crate::slices::Rows<LN>, const LN: usize> PairRun<L, LN> {
    const S: u32 = LN.trailing_zeros();

    #[inline(always)]
    fn new(seed: u32, p: usize) -> Self {
        let pair = p % 2;
        PairRun {
            seed,
            pair,
            shuffle_key: pmj02bn_shuffle_keys(Wrapping(seed))[pair],
            lanes: L::words(core::array::from_fn(|l| (l as u32).reverse_bits())),
            reverse_s: L::words(core::array::from_fn(|v| {
                (v as u32).reverse_bits() >> (32 - Self::S)
            })),
        }
    }

    /// The shuffled group of the group whose first index, bit-reversed, is `b`: its common
    /// high bits, and per lane the low bits `sigma`.
    #[inline(always)]
    fn shuffled(&self, b: u32) -> (u32, L::U) {
        let group_mask = Wrapping(!(LN as u32 - 1));
        let high = lk_hash(Wrapping(b), self.shuffle_key).reverse_bits() & group_mask;
        let h = lk_hash(L::U::splat(b) | self.lanes, L::U::splat(self.shuffle_key.0));
        (high.0, L::shuffle(self.reverse_s, h.shr(32 - Self::S)))
    }

    /// The keys of the block of indices that holds index `first`.
    #[inline(always)]
    fn block_keys(&self, first: u32) -> BlockKeys<L, LN> {
        let (set, keys) = pmj02bn_block_keys(Wrapping(self.seed), Wrapping(first >> LOG2_POINTS));
        let [kx, ky] = [keys[2 * self.pair].0, keys[2 * self.pair + 1].0];
        BlockKeys {
            set: crate::pmj02bn::set_view(set[self.pair].0 >> LOG2_POINTS),
            keys_xy: L::words(core::array::from_fn(|l| [kx, ky][l % 2])),
        }
    }

    /// The pair's `x` and `y` of the group whose first index, bit-reversed, is `b`.
    #[inline(always)]
    fn points(&self, b: u32, keys: &BlockKeys<L, LN>) -> [L; 2] {
        let (high, sigma) = self.shuffled(b);
        let row = high as usize & (POINTS - 1);
        let scrambled = |r: usize| {
            let words = L::words(crate::pmj02bn::table_words::<LN>(keys.set, r));
            to_unit::<L>(owen_scramble(words, keys.keys_xy)).to_bits()
        };
        let (lo, hi) = (scrambled(row), scrambled(row + LN / 2));
        // Point sigma(l) is words 2 sigma (x) and 2 sigma + 1 (y) of lo ++ hi.
        let in_lo = sigma.simd_lt(L::U::splat(LN as u32 / 2));
        let ix = (sigma + sigma) & L::U::splat(LN as u32 - 1);
        let iy = ix + L::U::splat(1);
        let pick =
            |i: L::U| L::from_bits(L::U::select(in_lo, L::shuffle(lo, i), L::shuffle(hi, i)));
        [pick(ix), pick(iy)]
    }
}

/// One sample's sampler: a pattern, a pixel, a domain path and a sample index, in 12 bytes.
///
/// `Copy`: derive children freely, draw from any of them in any order; nothing mutates.
/// See the [module docs](self) for the promises.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Sampler<P: Pattern> {
    state: State<Wrapping<u32>>,
    pattern: PhantomData<P>,
}

impl<P: Pattern> Sampler<P> {
    /// The root sampler of sample `index` of `pixel` (`[x, y]`) in `frame`, for `seed` (one
    /// per render; 0 is fine).
    ///
    /// Every pixel gets independent scrambles, except under [`Blue`], where pixels share a
    /// key tile (positions modulo the tile; `x` and `y` are read modulo 2^16). Frames and
    /// seeds decorrelate like domains: **each frame is a fresh randomisation** of the
    /// pattern (frames independent). A renderer that accumulates frames and wants their mean
    /// to converge like one longer net calls [`new_frame`](Self::new_frame), or passes its
    /// own running sample number as `index` with `frame = 0` (the same points: `new_frame`
    /// is `new` of the 64-bit sample number `frame * spp + index`, high word as `frame`).
    #[inline]
    pub fn new(pixel: [u32; 2], frame: u32, index: u32, seed: u32) -> Self {
        let w = Wrapping;
        Self::from_state(State::new(P::ID, pixel.map(w), w(frame), w(index), w(seed)))
    }

    /// The root sampler of sample `index` (in `0..spp`) of `pixel` in `frame` of a render
    /// that draws `spp` samples per pixel per frame and accumulates frames: **the frames
    /// continue one sequence**. Frame `t` draws the pixel's points `t spp .. (t + 1) spp`,
    /// so the running mean of frames `0..F` is the estimate of the first `F spp` points of
    /// the pattern (a (0,m,2)-net when `F spp = 2^m`), each frame alone is a block of the
    /// sequence (an aligned net when `spp` is a power of two; a run of `spp` consecutive
    /// points otherwise), and consecutive frames draw different points (no static noise).
    ///
    /// The sample's number in the pixel's sequence is the 64-bit `n = frame * spp + index`
    /// (`spp = 0` acts as 1; `index >= spp` reaches a later frame's sample, documented, not
    /// an error): it is [`new`](Self::new)`(pixel, (n >> 32) as u32, n as u32, seed)`, so
    /// frame 0 is `new`'s frame 0 bit for bit (under [`Blue`], but for the root's tag:
    /// below), and after `2^32` samples per pixel (`2^32 / spp` frames) the sequence
    /// continues in a fresh randomisation (`new`'s next frame),
    /// which keeps the mean converging. A render whose `spp` changes between frames passes
    /// the pixel's running sample count as `frame` and `spp = 1`: `new_frame(pixel, count,
    /// 1, index, seed)`.
    ///
    /// Under [`Blue`] the root's domains `0..BLUE_SLOTS` (six) are **spatiotemporal slots**
    /// (the one difference from `new`'s bits): each pixel of slot `s` draws `P` under the
    /// slot's fixed scramble at the sample number XOR the pixel's offset from the slot's
    /// tile, so every frame is blue noise across the screen (the tiles are optimised for
    /// frames 0 to 31) and the frames still continue one net per pixel. Other domains keep
    /// the per-pixel key tile (the pixel's key constant across frames: converging, white per
    /// frame). See `docs/sampler.md`, "In space and time: the slots".
    ///
    /// [`new`](Self::new) with `index` in `0..spp` and a new `frame` each frame is the other
    /// choice, named in its docs: a fresh randomisation per frame (frames independent, their
    /// mean converging like independent randomised nets, not like one longer net). Why `new`
    /// cannot continue the sequence by itself: `docs/design.md`, "Frames".
    #[inline]
    pub fn new_frame(pixel: [u32; 2], frame: u32, spp: u32, index: u32, seed: u32) -> Self {
        let [epoch, index] = frame_sample(frame, spp, index);
        let root = Self::new(pixel, epoch, index, seed).state;
        Self::from_state(State {
            domain: if P::ID & BLUE != 0 {
                blue_tagged(root.domain, TAG_ROOT)
            } else {
                root.domain
            },
            ..root
        })
    }

    #[inline(always)]
    fn from_state(state: State<Wrapping<u32>>) -> Self {
        Sampler {
            state,
            pattern: PhantomData,
        }
    }

    /// An independent child pattern for `key` (same index): for a new decision of the path
    /// (lens, light, BSDF, one per bounce...). Different keys never give the same child.
    #[inline]
    pub fn domain(self, key: u32) -> Self {
        Self::from_state(self.state.domain(P::ID, key))
    }

    /// Sub-sample `sub` of `size` per sample: the child index is `index * size + sub` in a
    /// child domain for `key`, so the sub-samples of all samples are one sequence — globally
    /// stratified (the `size * n` points of `n = 2^j` samples form a net when `size` is a
    /// power of two).
    ///
    /// Every argument is valid: `size = 0` acts as `size = 1`; `sub >= size` gives the index
    /// of another sample's sub-sample (documented, not an error); the child index wraps
    /// modulo `2^32`.
    #[inline]
    pub fn split(self, key: u32, size: u32, sub: u32) -> Self {
        Self::from_state(self.state.split(P::ID, key, size, Wrapping(sub)))
    }

    /// The same domain at another sample index.
    #[inline]
    pub fn with_index(self, index: u32) -> Self {
        Self::from_state(State {
            index: Wrapping(index),
            ..self.state
        })
    }

    /// This sampler's sample index (after any [`split`](Self::split)).
    #[inline]
    pub fn index(self) -> u32 {
        self.state.index.0
    }

    /// The state as three words `[pixel, domain, index]`, for bindings that carry a sampler
    /// across an ABI (the C API's `WcSampler`). Not a stable format: the words mean something
    /// only to [`from_words`](Self::from_words) of the same pattern and crate version.
    #[doc(hidden)]
    #[inline]
    pub fn to_words(self) -> [u32; 3] {
        let s = self.state;
        [s.pixel.0, s.domain.0, s.index.0]
    }

    /// The sampler whose [`to_words`](Self::to_words) are `w`. Every value is valid (any
    /// three words are some sampler's state).
    #[doc(hidden)]
    #[inline]
    pub fn from_words(w: [u32; 3]) -> Self {
        let [pixel, domain, index] = w.map(Wrapping);
        Self::from_state(State {
            pixel,
            domain,
            index,
        })
    }

    /// `N` (1 to 4, checked at compile time) stratified dimensions in `[0, 1 - 2^-24]`.
    #[inline]
    pub fn draw<const N: usize>(self) -> [f32; N] {
        self.draw_u32::<N>().map(|w| to_unit::<f32>(Wrapping(w)))
    }

    /// The point of [`draw`](Self::draw) as 0.32 fixed point (`w / 2^32`): `draw` is
    /// `(w >> 8) * 2^-24` of these words.
    #[inline]
    pub fn draw_u32<const N: usize>(self) -> [u32; N] {
        self.state.bits::<N>(P::ID).map(|w| w.0)
    }

    /// `N` (1 to 4) cheap unstratified values in `[0, 1 - 2^-24]`: a counter hash of the
    /// pixel, the domain and the index, for Russian roulette and other decisions where
    /// stratification does not pay.
    #[inline]
    pub fn rnd<const N: usize>(self) -> [f32; N] {
        self.state.rnd::<N>(P::ID).map(to_unit::<f32>)
    }

    /// Fills `out[k]` with `self.with_index(self.index() + k).draw::<N>()` (index wrapping)
    /// and returns `out.len()`: the points of one domain for consecutive indices, eight or
    /// sixteen at a time. Bit-identical to the scalar form.
    #[inline]
    pub fn draw_slice<const N: usize>(self, out: &mut [[f32; N]]) -> usize {
        simd::draw_slice::<P, crate::slices::Widest, _, N>(self.state, out)
    }
}

impl<P: Base> Sampler<P> {
    /// The sampler whose domain hash is `hash` (pixel 0) at sample `index`: point `index` of
    /// `P` keyed by `hash`, which is exactly what a [`Blue<P>`](Blue) pixel draws when its
    /// tile key is `hash`. For `tools/bluegen`, which optimises the tiles from the library's
    /// own points; not part of the API.
    #[doc(hidden)]
    #[inline]
    pub fn from_domain_hash(hash: u32, index: u32) -> Self {
        let w = Wrapping;
        Self::from_state(State {
            pixel: w(0),
            domain: w(hash),
            index: w(index),
        })
    }
}

/// The `(frame, index)` of [`Sampler::new`] that [`Sampler::new_frame`] builds: the high and
/// low words of `frame * max(spp, 1) + index` (at most `2^64 - 2^32`, exact in `u64`).
#[inline(always)]
fn frame_sample(frame: u32, spp: u32, index: u32) -> [u32; 2] {
    let n = u64::from(frame) * u64::from(spp.max(1)) + u64::from(index);
    [(n >> 32) as u32, n as u32]
}

/// The tag of a `Blue<P>` domain hash (its low two bits): a root, one of the root's
/// spatiotemporal slots (the slot in bits 2..4), or any other domain.
const TAG_MASK: u32 = 3;
const TAG_OTHER: u32 = 0;
const TAG_SLOT: u32 = 1;
const TAG_ROOT: u32 = 2;

/// A `Blue<P>` domain hash with its tag (the low two bits; see `blue::TAG_MASK`).
#[inline(always)]
fn blue_tagged<U: UintLane>(h: U, tag: u32) -> U {
    (h & U::splat(!TAG_MASK)) | U::splat(tag)
}

/// `to_unit` over any lane type (the conversion of [`Sampler::draw`]).
#[inline(always)]
fn unit<L: Lane>(w: L::U) -> L {
    to_unit::<L>(w)
}

const _: () = assert!(core::mem::size_of::<Sampler<Sobol>>() <= 16);
