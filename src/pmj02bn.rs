//! pmj02bn: progressive multi-jittered (0,2) points with blue-noise spacing, from embedded
//! tables, Owen-scrambled per seed.
//!
//! | function | returns |
//! |---|---|
//! | [`raw`] | table point `index` of set `set`, unscrambled, 0.32 fixed point |
//! | [`sample`], [`sample_x8`], [`sample_x16`], [`sample_slice`] | point `index` of the sequence for `seed`, in `[0, 1)^2` |
//! | [`shuffle`], [`shuffle_x8`], [`shuffle_x16`] | a prefix-preserving permutation of indices, required for every 2D dimension after the first |
//!
//! **The tables.** [`SETS`] sets of [`POINTS`] points each, chosen by Cargo features (see the
//! crate docs), generated offline by `tools/pmjgen` (Christensen, Kensler and Kilpatrick,
//! "Progressive Multi-Jittered Sample Sequences", EGSR 2018, plus a nested-flip blue-noise
//! optimization) and embedded with `include_bytes!`: two little-endian `u32` per point, read
//! in place (no copy, no build script) and byte-swapped on big-endian targets. Every
//! power-of-two prefix of every set — and every aligned power-of-two block — is a
//! (0,m,2)-net: each of the `m + 1` elementary grids of `2^m` cells (`2^k x 2^(m-k)`) holds
//! exactly one point per cell.
//!
//! **Sampling.** [`sample`]`(index, seed)` takes table point `index` of a set chosen by the
//! seed, applies an independent nested uniform (Owen) scramble to each coordinate (hash-based:
//! Burley, "Practical Hash-based Owen Scrambling", JCGT 2020, with Vegdahl's 2021 hash), and
//! converts by truncation, `(x >> 8) * 2^-24`, so results lie in `[0, 1 - 2^-24]`: never
//! 1.0. A nested scramble maps elementary intervals onto elementary intervals of the same
//! shape, so every power-of-two prefix of every seed's sequence is still a (0,m,2)-net. No
//! Cranley-Patterson rotation (it would break the nets).
//!
//! **Past the table** (`index >= POINTS`): index `q * POINTS + r` is table point `r`
//! scrambled with the keys of block `q` — set and scrambles are re-drawn from `(seed, q)` —
//! instead of repeating block 0's points. Every aligned block of up to `POINTS` indices is
//! still a (0,m,2)-net; an aligned block of `2^k * POINTS` indices is `2^k` independently
//! scrambled nets, so each elementary interval of area `1 / POINTS` holds exactly `2^k`
//! points (a `(k, m + k, 2)`-net) — stratified like the table, not better. Build with a larger
//! table (`pmj02bn-16384`, `pmj02bn-65536`) when more samples per pixel are common.
//!
//! **Several 2D dimensions** of one pixel: every 2D dimension after the first needs its own
//! seed **and** its own index shuffle, `sample(shuffle(index, dim_seed), seed)`. The shuffle
//! is not optional: with another seed but the same index order, the scramble relabels strata
//! identically for every index while point `index` of every table set sits in strata fixed by
//! `index`'s place in the progressive construction, so the second pair is (nearly) a function
//! of the first: in an estimator coupling the two, each pixel converges to its own wrong value
//! (the mean over pixels stays unbiased; separable estimators are unaffected). Over 1024
//! samples, the joint 16 x 16 grid of the two x coordinates gets its points in 16 to 64 of
//! its 256 cells, 16 when both seeds pick the same table set. [`shuffle`] keeps every power-of-two prefix as a set, so the nets survive, but
//! it reorders points inside each one, which costs blue noise at counts that are not powers
//! of two. Simpler: the sampling core (`warpcore::sampler`, feature `sampler`) gives every
//! `domain(key)` its own scramble and its own index order.
//!
//! **Out-of-range arguments.** Every `u32` index and seed is valid (see "past the table"); the
//! index wraps after `2^32`. [`raw`] reduces `set` modulo [`SETS`] and `index` modulo
//! [`POINTS`].

use crate::hash::{mix, owen_scramble, prefix_shuffle, to_unit};
use crate::lanes::{Lane, UintLane};
use crate::slices::{self, Vector};
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// Points per set in this build: 1024 (feature `pmj02bn` alone), 4096 (`pmj02bn-4096`, in the
/// default features), 16384 (`pmj02bn-16384`) or 65536 (`pmj02bn-65536`); the largest
/// enabled wins.
#[cfg(feature = "pmj02bn-65536")]
pub const POINTS: usize = 65536;
/// Points per set in this build (see the crate docs for the features).
#[cfg(all(feature = "pmj02bn-16384", not(feature = "pmj02bn-65536")))]
pub const POINTS: usize = 16384;
/// Points per set in this build (see the crate docs for the features).
#[cfg(all(
    feature = "pmj02bn-4096",
    not(any(feature = "pmj02bn-16384", feature = "pmj02bn-65536"))
))]
pub const POINTS: usize = 4096;
/// Points per set in this build (see the crate docs for the features).
#[cfg(not(any(
    feature = "pmj02bn-4096",
    feature = "pmj02bn-16384",
    feature = "pmj02bn-65536"
)))]
pub const POINTS: usize = 1024;

/// Independent point sets in this build: 4 with `pmj02bn-4-sets` (in the default features),
/// else 1.
#[cfg(feature = "pmj02bn-4-sets")]
pub const SETS: usize = 4;
/// Independent point sets in this build: 4 with `pmj02bn-4-sets`, else 1.
#[cfg(not(feature = "pmj02bn-4-sets"))]
pub const SETS: usize = 1;

/// Bytes of embedded table data in this build: `8 * POINTS * SETS`.
pub const TABLE_BYTES: usize = 8 * POINTS * SETS;

pub(crate) const LOG2_POINTS: u32 = POINTS.trailing_zeros();

/// The sets' bytes, one after the other, aligned to a cache line (each set's size is a
/// multiple of 64 bytes, so a point never straddles two lines).
#[repr(C, align(64))]
struct Aligned<T>(T);

/// `include_bytes!` of set `$set` of the `$points`-point tables.
macro_rules! set_bytes {
    ($points:literal, $set:literal) => {
        *include_bytes!(concat!("tables/pmj02bn_", $points, "_", $set, ".bin"))
    };
}

/// The sets of this build, for `$points` points per set.
#[cfg(feature = "pmj02bn-4-sets")]
macro_rules! sets {
    ($points:literal) => {
        Aligned([
            set_bytes!($points, "0"),
            set_bytes!($points, "1"),
            set_bytes!($points, "2"),
            set_bytes!($points, "3"),
        ])
    };
}
#[cfg(not(feature = "pmj02bn-4-sets"))]
macro_rules! sets {
    ($points:literal) => {
        Aligned([set_bytes!($points, "0")])
    };
}

#[cfg(feature = "pmj02bn-65536")]
static TABLES: Aligned<[[u8; 8 * POINTS]; SETS]> = sets!("65536");
#[cfg(all(feature = "pmj02bn-16384", not(feature = "pmj02bn-65536")))]
static TABLES: Aligned<[[u8; 8 * POINTS]; SETS]> = sets!("16384");
#[cfg(all(
    feature = "pmj02bn-4096",
    not(any(feature = "pmj02bn-16384", feature = "pmj02bn-65536"))
))]
static TABLES: Aligned<[[u8; 8 * POINTS]; SETS]> = sets!("4096");
#[cfg(not(any(
    feature = "pmj02bn-4096",
    feature = "pmj02bn-16384",
    feature = "pmj02bn-65536"
)))]
static TABLES: Aligned<[[u8; 8 * POINTS]; SETS]> = sets!("1024");

/// Set `set` (reduced modulo [`SETS`]) as a fixed-length array of 8-byte points, viewing its
/// embedded bytes in place. The cast is between arrays of bytes of the same length, so it
/// cannot fail (no alignment or size check survives compilation); the fixed length lets a
/// masked index reach the table without a bounds check.
#[inline(always)]
fn view(set: usize) -> &'static [[u8; 8]; POINTS] {
    bytemuck::cast_ref(&TABLES.0[set & (SETS - 1)])
}

/// All sets as one array of `SETS * POINTS` 8-byte points (set `s`, point `r` at
/// `s * POINTS + r`), viewed in place like [`view`]: the gathers index it with one masked
/// word per lane.
#[inline(always)]
fn all_points() -> &'static [[u8; 8]; SETS * POINTS] {
    bytemuck::cast_ref(&TABLES.0)
}

/// Point `index` (reduced modulo `M`, a power of two: [`POINTS`] for a set's view, `SETS *
/// POINTS` for [`all_points`]): two little-endian words, decoded explicitly, so a big-endian
/// target reads the same values.
#[inline(always)]
fn decode<const M: usize>(view: &[[u8; 8]; M], index: usize) -> [u32; 2] {
    let p = view[index & (M - 1)];
    [
        u32::from_le_bytes([p[0], p[1], p[2], p[3]]),
        u32::from_le_bytes([p[4], p[5], p[6], p[7]]),
    ]
}

/// Table point `index` of set `set` (both reduced modulo the build's sizes).
#[inline(always)]
fn lookup(set: usize, index: usize) -> [u32; 2] {
    decode(view(set), index)
}

/// Table point `index` of set `set`, unscrambled, as 0.32 fixed point (`x / 2^32`).
///
/// Total: `raw(set, index) == raw(set % SETS, index % POINTS)`.
#[inline]
pub fn raw(set: usize, index: usize) -> [u32; 2] {
    lookup(set % SETS, index % POINTS)
}

// Key derivation constants (arbitrary odd 32-bit values, distinct per use).
const KEY_X: u32 = 0x68e3_1da4;
const KEY_Y: u32 = 0xb529_7a4d;
const KEY_SET: u32 = 0x1b56_c4e9;
const KEY_BLOCK: u32 = 0x9e37_79b9;

/// What a seed and a block of [`POINTS`] indices choose: the set (pre-shifted, as the high
/// bits of a flat table index) and the two scramble keys.
#[derive(Clone, Copy)]
struct Keys<U> {
    set: U,
    x: U,
    y: U,
}

#[inline(always)]
fn keys<U: UintLane>(seed: U, block: U) -> Keys<U> {
    // Block 0 uses the seed's own keys; block q > 0 re-keys (mix(0) = 0 keeps block 0 as is).
    let key = mix(seed) ^ mix(block * U::splat(KEY_BLOCK));
    Keys {
        set: (mix(key ^ U::splat(KEY_SET)) & U::splat(SETS as u32 - 1)).shl(LOG2_POINTS),
        x: mix(key ^ U::splat(KEY_X)),
        y: mix(key ^ U::splat(KEY_Y)),
    }
}

/// Owen scrambles under `keys` and the truncating conversion of table coordinates.
#[inline(always)]
fn finish<L: Lane>(x: L::U, y: L::U, keys: Keys<L::U>) -> [L; 2] {
    [
        to_unit(owen_scramble(x, keys.x)),
        to_unit(owen_scramble(y, keys.y)),
    ]
}

/// `N` consecutive points `r .. r + N` of a set, Owen-scrambled and converted in place: the
/// `8 N` contiguous bytes are read as two vectors of words in table order (`x0, y0, x1, y1,
/// ..`), each word is scrambled with its coordinate's key (`keys_xy` alternates the x and y
/// keys lane by lane) and converted, and the result is already the array-of-structs output:
/// no gather, no transposes. `None` when the points do not fit in the set (the caller falls
/// back to the gather).
#[inline(always)]
fn consecutive_points<L: Vector<N>, const N: usize>(
    view: &[[u8; 8]; POINTS],
    r: usize,
    keys_xy: L::U,
) -> Option<[[f32; 2]; N]> {
    let group: &[[u8; 8]; N] = view.get(r..r.wrapping_add(N))?.try_into().ok()?;
    let mut rows = [[0u32; N]; 2];
    for (w, c) in rows
        .as_flattened_mut()
        .iter_mut()
        .zip(group.as_flattened().as_chunks::<4>().0)
    {
        *w = u32::from_le_bytes(*c);
    }
    let out = rows.map(|w| {
        let v: L = to_unit(owen_scramble(L::words(w), keys_xy));
        L::to_words(v.to_bits())
    });
    Some(bytemuck::cast(out))
}

/// Table point `r < POINTS` under `keys`: lane-wise lookup, Owen scrambles, conversion.
#[inline(always)]
fn point<L: Lane>(r: L::U, keys: Keys<L::U>) -> [L; 2] {
    // SETS * POINTS <= 2^18: the flat index holds set and point.
    let [x, y] = (keys.set | r).gather_pairs(|i| decode(all_points(), i as usize));
    finish(x, y, keys)
}

#[inline(always)]
fn sample_body<L: Lane>(index: L::U, seed: L::U) -> [L; 2] {
    let r = index & L::U::splat(POINTS as u32 - 1);
    point(r, keys(seed, index.shr(LOG2_POINTS)))
}

/// For the sampling core: the two words of flat table point `set_row` (the set in the bits
/// above `log2(POINTS)`, reduced modulo the build's sizes), lane by lane.
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn table_bits<U: UintLane>(set_row: U) -> [U; 2] {
    set_row.gather_pairs(|i| decode(all_points(), i as usize))
}

/// For the sampling core's slices: the points of set `set` (reduced modulo [`SETS`]).
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn set_view(set: u32) -> &'static [[u8; 8]; POINTS] {
    view(set as usize)
}

/// For the sampling core's slices: the `W` little-endian words of points `r .. r + W / 2` of a
/// set, in table order (`x_r, y_r, x_{r+1}, ..`); zeros where they would run past the set's
/// end (the callers read aligned groups, which never do).
#[cfg(feature = "sampler")]
#[inline(always)]
pub(crate) fn table_words<const W: usize>(view: &[[u8; 8]; POINTS], r: usize) -> [u32; W] {
    let mut words = [0u32; W];
    if let Some(bytes) = view.as_flattened().get(8 * r..8 * r + 4 * W) {
        for (w, c) in words.iter_mut().zip(bytes.as_chunks::<4>().0) {
            *w = u32::from_le_bytes(*c);
        }
    }
    words
}

/// Point `index` of the pmj02bn sequence for `seed`: a table point (set chosen by the seed),
/// Owen-scrambled per seed, in `[0, 1 - 2^-24]^2`.
///
/// Every power-of-two prefix (and aligned block of up to [`POINTS`] indices) is a
/// (0,m,2)-net for every seed. Different seeds give independent scrambles. For
/// `index >= POINTS` see the [module docs](self). Exact: no floating-point rounding besides
/// the documented truncation to 24 bits.
#[inline]
pub fn sample(index: u32, seed: u32) -> [f32; 2] {
    sample_body::<f32>(Wrapping(index), Wrapping(seed))
}

/// [`sample`] for eight (index, seed) pairs at once; bit-identical to eight scalar calls.
#[inline]
pub fn sample_x8(index: u32x8, seed: u32x8) -> [f32x8; 2] {
    sample_body::<f32x8>(index, seed)
}

/// [`sample`] for sixteen (index, seed) pairs at once; bit-identical to sixteen scalar calls.
#[inline]
pub fn sample_x16(index: u32x16, seed: u32x16) -> [f32x16; 2] {
    sample_body::<f32x16>(index, seed)
}

/// Fills `out[i] = sample(start + i, seed)` (index wrapping after `u32::MAX`) and returns
/// `out.len()`. Bit-identical to the scalar form.
#[inline]
pub fn sample_slice(start: u32, seed: u32, out: &mut [[f32; 2]]) -> usize {
    sample_lanes::<slices::Widest, _>(start, seed, out)
}

/// [`sample_slice`] on `N`-lane vectors.
#[inline(always)]
fn sample_lanes<L: Vector<N>, const N: usize>(
    start: u32,
    seed: u32,
    out: &mut [[f32; 2]],
) -> usize {
    // Run by run within one block of POINTS indices, so the keys are derived once per run
    // (the same integers `sample_body` derives per lane: bit-identical).
    let n = out.len();
    let mask = L::U::splat(POINTS as u32 - 1);
    let mut index = start;
    let mut rest = out;
    while !rest.is_empty() {
        let in_block = POINTS - (index as usize & (POINTS - 1));
        let (run, tail) = rest.split_at_mut(in_block.min(rest.len()));
        let one = keys(Wrapping(seed), Wrapping(index >> LOG2_POINTS));
        let k = Keys {
            set: L::U::splat(one.set.0),
            x: L::U::splat(one.x.0),
            y: L::U::splat(one.y.0),
        };
        // Groups of N consecutive points read the table as whole vectors (a run never
        // crosses the set's end, so the gather fallback is only there to avoid a panic path);
        // the last 1 to N - 1 points take the gather path.
        let set = view(one.set.0 as usize >> LOG2_POINTS);
        let keys_xy = L::words(core::array::from_fn(|l| [one.x.0, one.y.0][l % 2]));
        let r0 = index as usize & (POINTS - 1);
        let (groups, _) = run.as_chunks_mut::<N>();
        let whole = groups.len() * N;
        for (g, dst) in groups.iter_mut().enumerate() {
            let r = r0 + N * g;
            *dst = match consecutive_points::<L, N>(set, r, keys_xy) {
                Some(points) => points,
                None => slices::store(point::<L>(
                    (L::U::splat(r as u32) + slices::lane_numbers::<L, N>()) & mask,
                    k,
                )),
            };
        }
        let tail_start = index.wrapping_add(whole as u32);
        let tail_out = run.get_mut(whole..).unwrap_or(&mut []);
        slices::fill_indexed::<L, N, 2>(tail_start, tail_out, |i| point::<L>(i & mask, k));
        index = index.wrapping_add(run.len() as u32);
        rest = tail;
    }
    n
}

/// A permutation of sample indices, required for every 2D dimension after the first: pass
/// `sample(shuffle(i, dim_seed), seed)` with a `dim_seed` and a `seed` of the dimension's own
/// (another seed alone leaves the dimensions correlated; see the module docs).
///
/// It maps `[0, 2^k)` onto itself for every `k` (so every power-of-two prefix of the
/// sequence keeps the same points, and stays a net) and every aligned block of `2^k` indices
/// onto an aligned block of `2^k`; within those it is a nested random permutation keyed by
/// `seed` (Burley 2020's index shuffle, with the image of 0 pinned to 0). `shuffle(0, s) = 0`.
#[inline]
pub fn shuffle(index: u32, seed: u32) -> u32 {
    prefix_shuffle(Wrapping(index), mix(Wrapping(seed))).0
}

/// [`shuffle`] for eight lanes; identical to eight scalar calls.
#[inline]
pub fn shuffle_x8(index: u32x8, seed: u32x8) -> u32x8 {
    prefix_shuffle(index, mix(seed))
}

/// [`shuffle`] for sixteen lanes; identical to sixteen scalar calls.
#[inline]
pub fn shuffle_x16(index: u32x16, seed: u32x16) -> u32x16 {
    prefix_shuffle(index, mix(seed))
}

#[cfg(test)]
mod tests {
    extern crate std;
    use super::*;
    use std::vec;

    /// The slice machinery at both widths against the scalar form: runs that start anywhere
    /// in a block, cross block boundaries and the index wrap, every tail length.
    fn slices_agree<L: Vector<N>, const N: usize>() {
        let p = POINTS as u32;
        // Under miri (CI checks the table reads there, about 50x slower) every start, the
        // lengths around one and two vectors and one seed.
        let lens: &[usize] = if cfg!(miri) {
            &[0, 1, 17, 33]
        } else {
            &[0, 1, 7, 15, 16, 17, 33, 40]
        };
        let seeds: &[u32] = if cfg!(miri) {
            &[0x5eed]
        } else {
            &[0, 0x5eed, u32::MAX]
        };
        for start in [0u32, 3, p - 5, p - 16, 2 * p - 1, u32::MAX - 10] {
            for &len in lens {
                for &seed in seeds {
                    let mut out = vec![[9.0f32; 2]; len];
                    assert_eq!(sample_lanes::<L, N>(start, seed, &mut out), len);
                    for (k, o) in out.iter().enumerate() {
                        let want = sample(start.wrapping_add(k as u32), seed);
                        assert_eq!(o.map(f32::to_bits), want.map(f32::to_bits), "{start} {k}");
                    }
                }
            }
        }
    }

    #[test]
    fn slices_agree_at_both_widths() {
        slices_agree::<wide::f32x8, 8>();
        slices_agree::<f32x16, 16>();
    }

    #[test]
    /// The in-place view covers every byte of every set, in order, and decodes little endian.
    /// (Runs under miri in CI: the cast and the reads are checked for soundness there.)
    fn table_view_is_complete() {
        let le = |b: &[u8]| u32::from_le_bytes([b[0], b[1], b[2], b[3]]);
        for (set, bytes) in TABLES.0.iter().enumerate() {
            let v = view(set);
            assert_eq!(core::mem::size_of_val(v), bytes.len());
            for k in [0, 1, POINTS / 2 + 3, POINTS - 1] {
                let b = &bytes[8 * k..8 * k + 8];
                assert_eq!(v[k], *b);
                assert_eq!(raw(set, k), [le(&b[..4]), le(&b[4..])]);
                assert_eq!(all_points()[set * POINTS + k], *b);
            }
        }
        assert_eq!(core::mem::size_of_val(&TABLES), TABLE_BYTES);
    }
}
