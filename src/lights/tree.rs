//! The light tree: a bounding-volume hierarchy over [`LightBounds`] that picks a light with
//! probability proportional to a conservative estimate of its contribution at the shading
//! point (pbrt-v4's BVH light sampler; Conty Estevez and Kulla 2018, "Importance Sampling of
//! Many Lights with Adaptive Tree Splitting"), in caller-owned `[u32]` storage.
//!
//! See [`LightTree`] for the promises, the importance function and the storage layout.

mod build;

use super::Error;
use crate::lanes::{Lane, ONE_MINUS_EPSILON, UintLane, unit_interval};
use crate::storage::{from_storage_order, header, sealed};
use core::num::Wrapping;
use wide::{f32x4, f32x8, f32x16, u32x4, u32x8, u32x16};

/// A light's bounds for the tree's importance: where it is, how much it emits and in which
/// directions (pbrt-v4's `LightBounds`).
///
/// A one-sided area light: its triangle's box, `axis` its normal, `cos_theta_o = 1`,
/// `cos_theta_e = 0` (cosine falloff to 90 degrees). A point light: a degenerate box,
/// `cos_theta_o = -1` (every direction), `cos_theta_e = 0`. A spot light: `cos_theta_o` the
/// cosine of the full-intensity angle, `cos_theta_e` the cosine of the falloff angle beyond it
/// (1 for a hard edge). Beyond 90 degrees from the cone nothing is chosen: a `cos_theta_e`
/// below 0 acts as 0.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LightBounds {
    /// Lower corner of the box around the emitter.
    pub min: [f32; 3],
    /// Upper corner of the box around the emitter.
    pub max: [f32; 3],
    /// Emitted power (>= 0). A light of power 0 is never chosen (its `pmf` is 0).
    pub power: f32,
    /// Principal emission direction. Need not be unit: [`LightTree::new`] normalises it
    /// (a zero, NaN or infinite axis is [`Error::InvalidBounds`]).
    pub axis: [f32; 3],
    /// Cosine of the spread of normals around the axis (`theta_o`), in `[-1, 1]`.
    pub cos_theta_o: f32,
    /// Cosine of the emission falloff beyond `theta_o` (`theta_e`), in `[-1, 1]`.
    pub cos_theta_e: f32,
    /// Whether the emitter emits on both sides (the cone and its mirror image).
    pub two_sided: bool,
}

/// Format tag of a light tree's storage: the bytes `wcLT`.
const TAG: u32 = u32::from_le_bytes(*b"wcLT");
/// The storage format version this build writes and reads (1: 8-word nodes with an
/// octahedral axis and 16-bit cosines, no longer read).
const VERSION: u32 = 2;
/// Header words (64 bytes), as the environment maps.
const HEADER_WORDS: usize = 16;
/// The header word holding the content checksum.
const CHECKSUM_WORD: usize = 8;
/// Words of one node record.
const NODE_WORDS: usize = 12;
/// Flag of a node's last word: the node is a leaf, the low bits are the light's index.
const LEAF: u32 = 1 << 31;
/// Flag of a node's last word: some light below emits on both sides.
const TWO_SIDED: u32 = 1 << 30;
/// The index bits of a node's last word (a child pair or a light).
const INDEX_MASK: u32 = (1 << 30) - 1;
/// Most levels a walk takes (the root pair's level included); a balanced tree of
/// `MAX_LIGHTS` lights needs 12; a trail holds 2 bits per level.
const MAX_LEVELS: u32 = 16;
/// Importances are clamped to this (`2^125`), so a quad's sum of four stays finite.
const BIG: f32 = 4.253_529_6e37;

/// A bounding-volume tree over [`LightBounds`]: picks one of `n` lights with probability
/// proportional to each subtree's *importance* at the shading point, with the exact
/// probability of the light picked (for next-event estimation and its MIS weight).
///
/// # Sampling
///
/// A walk from the root of a 4-ary tree: at each inner node the four children's importances
/// `I_0..I_3` at `(p, n)` (sum `S`) pick child `c` with probability `I_c / S`, as two binary
/// choices (the pair `{0, 1}` or `{2, 3}`, then a child of the pair; the bit trail below
/// records both). By `u`: `t = u S` is compared with the cumulative bounds `I_0`, `I_0 +
/// I_1`, `I_0 + I_1 + I_2` (compares and selects only, no division on the way down; a child
/// of importance 0 is never taken, whatever the rounding of `t`), and `u` for the next level
/// is where `t` lies in the chosen interval (`(t - start) / I_c`, clamped below 1), so sorted
/// `u` visit the leaves in order and a stratified `u` stays stratified across the leaves as
/// far as the tree's order allows. The probability returned is the product of the levels'
/// `I_c / S`, in root-to-leaf order. [`pmf`](Self::pmf) walks the light's stored path (its
/// *bit trail*: one word per light, 2 bits per level; O(depth), no hash map) through the
/// same code, so `sample(p, n, u) == Some((i, pmf(p, n, i)))` bit for bit.
///
/// **Importance** (our transcription of the bound of pbrt-v4's `LightBounds::Importance`,
/// after Conty Estevez and Kulla 2018): for a node with bounding sphere (centre `c`, radius
/// `r`), total power `phi`, normal cone (axis `w`, `theta_o`) and falloff `theta_e`, with
/// `d = |p - c|`, `theta_w` the angle between `w` and `p - c` (its mirror for two-sided
/// nodes), `theta_b = asin(r / d)` (`pi` inside the sphere),
/// `theta' = max(0, theta_w - theta_o - theta_b)`:
/// `I = phi cos(theta') / max(d^2, r^2) * cos(max(0, theta_i - theta_b))` if
/// `cos(theta') >= cos(theta_e)`, else 0 (with a strict `>` a hard-edged spot, `cos_theta_e =
/// 1`, would never be chosen), where `theta_i` is the angle between `n` and `p - c`
/// folded onto `[0, 90]` degrees (both sides of a surface: transmission), and the last factor
/// is 1 for `n = [0, 0, 0]` (a point in a medium). Angles are never formed: the cosines and
/// sines of differences come from products and `sqrt` only (no libm transcendental), carried
/// multiplied by the distance (`d cos(theta_w) = w . (p - c)`, `d cos(theta_b) = sqrt(d^2 -
/// r^2)`, `d sin(theta_b) = r`), so the three square roots are independent and one division
/// (`1 / max(d^2, r^2)`) ends the evaluation; the node stores its unit axis and the cosine
/// and sine of `theta_o` ready as `f32`, so a visit decodes nothing. pbrt-v4 clamps `d^2`
/// below by the box's half *diagonal length*; we use the bounding radius *squared* (the same
/// units as `d^2`). `n` need not be unit: it is scaled by a power of two and normalised, so
/// every finite normal whose largest coordinate is at least `2^-126` counts (a smaller,
/// zero, NaN or infinite one means a medium). A non-finite `p` gives no light.
///
/// **Range.** A quad whose children's `phi / max(d^2, r^2)` leave `[2^-100, 2^100)` is
/// evaluated again with their lengths (`p - c`, `r`) and powers multiplied by exact powers
/// of two, chosen from the children's largest `|p - c|` coordinate or radius and largest
/// power. Importances are homogeneous (degree -2 in lengths, 1 in power) and a walk compares
/// only siblings, so the scales change no choice and no bit where the unscaled evaluation
/// stayed in range; where it did not, nothing overflows or underflows: a light at `1e20`
/// beside lights at 1, faint lights seen from far away, a shading point at `1e30`, a scene
/// far from the origin. What remains: siblings whose
/// distances differ by more than `2^63` (the nearer one's `d^2` is held at `2^-126` of the
/// farther's scale and takes all but about `2^-126` of the probability), and a light whose
/// probability falls below `f32`'s normal range may read 0. The build groups lights by
/// count, not by cost: a far outlier shares a group with its nearest neighbours, whose
/// bounding sphere then contains `p`, and the group's importance `phi / r^2` starves those
/// neighbours (probability about `(d / r)^2`: 0 once that is below `2^-126`, as for four of
/// twenty unit lights beside one at `1e20`); where two groups both contain `p`, their
/// shares follow `phi / r^2`, not their nearest lights. A cost-based split (pbrt-v4's)
/// would isolate the outlier.
///
/// **What sums to 1.** A walk can reach a node whose two children both have importance 0 at
/// `p` although the node itself had some (its bounds are looser than its lights'): the walk
/// stops there and `sample` returns `None`. So `sum_i pmf(p, n, i) = 1 - P(None)`: exactly 1
/// (within rounding, 1e-5) where no such dead end is reachable, and the missing mass is
/// exactly the probability of `None` elsewhere. An estimator `f(i) / pmf(i)` stays unbiased
/// (`None` contributes 0, and every light that contributes has `pmf > 0`). pbrt-v4 behaves
/// the same way.
///
/// **Never a light with probability 0**: a light of power 0, or whose importance at `p` is
/// 0, is never returned; `sample` returns `Some((i, q))` only with `q >= 2^-126` (so `1 /
/// q` is finite in `f32`), and `q` is `pmf(p, n, i)`. Importances and probabilities below
/// `2^-126` count as 0, so a device that flushes subnormals gives the same bits. Where
/// nothing contributes, `sample` is `None` and every `pmf` is 0.
///
/// # Build
///
/// [`new`](Self::new) validates the lights, then builds a 4-ary tree over the lights of
/// positive power: each inner node's lights are split in two along the longest axis of their
/// centroids' box and each half in two along its own (our own panic-free quickselect, O(n)
/// expected per level, a heapsort fallback bounds it by O(n log n)), into groups of
/// `4^(levels - 1)` lights filled in order. Depth `ceil(log4 m)`; O(n log n); the storage is
/// the only scratch space (no allocator). The bounds of an inner node are the union of its
/// children's: the boxes, the power sums (in `f64`), the normal cones (pbrt-v4's
/// `DirectionCone` union, in `f64`) and the widest falloff.
///
/// # Storage layout (32-bit words, little-endian on every target)
///
/// | words | contents |
/// |---|---|
/// | 0 | format tag, the bytes `wcLT` |
/// | 1 | format version (2; version 1 is refused with [`Error::UnsupportedVersion`]) |
/// | 2 | `n`, the number of lights |
/// | 3 | `m`, the lights of positive power (the tree's leaves) |
/// | 4 | levels of the walk (`ceil(log4 m)`, at least 1) |
/// | 8 | content checksum of every other word |
/// | 5..8, 9..16 | 0 |
/// | 16.. | `n / 3 + 14` quads of 48 words: the four children of an inner node (quad 0: the root's) |
/// | then | `n` bit trails (bits `2l`, `2l + 1`: the pair and the child taken at level `l`) |
///
/// A node is 12 words, all `f32` but the last: its bounding sphere's centre (3) and radius,
/// its power, its unit axis (3), `cos_theta_o` and `sin_theta_o` (the walk's own `sqrt(1 -
/// cos^2)` of the stored cosine), `cos_theta_e` (the cosines rounded down: the stored cone
/// is never narrower), and a word holding a leaf flag, a two-sided flag and a child quad's
/// or a light's index. The axis's rounding error is added to `theta_o`, and the radius is
/// rounded up, so the stored bounds contain the given ones. A quad is field-major (word `k`
/// of child `c` at `4 k + c`, 192 bytes: three cache lines): a scalar walk evaluates the
/// four children as one `f32x4`. **About 68 bytes per light**
/// (`storage_len(n) = 16 + 48 (n / 3 + 14) + n` words).
///
/// `from_storage` (O(1)) checks the header; sampling any storage that passed it never panics
/// and returns valid outputs (an index below `n`, a probability in `[0, 1]`), whatever the
/// node words hold. `from_storage_verified` also checks the content checksum, which changes
/// with every single-bit flip (see the environment maps' module docs).
#[derive(Clone, Copy, Debug)]
pub struct LightTree<'a> {
    storage: &'a [u32],
    len: usize,
    levels: u32,
}

/// The tree's largest number of lights: `2^24` (indices, trails and 32-bit word offsets fit).
const MAX_LIGHTS: usize = 1 << 24;

/// How a walk picks a child at each level: by `u` (sampling) or by a light's trail (pmf).
trait Chooser<L: Lane> {
    /// The child taken among importances `i` (`s01 = I_0 + I_1`, `s23 = I_2 + I_3`, `sum =
    /// s01 + s23`) at `level`: whether it is in the pair `{2, 3}` and whether it is the
    /// second of its pair.
    fn pick(&mut self, level: u32, i: &[L; 4], s01: L, s23: L, sum: L) -> (L::Mask, L::Mask);
}

/// Picks by `u`: `t = u S` falls in one of the four children's intervals `[I_0 + ... +
/// I_(c-1), I_0 + ... + I_c)` (compares against the three bounds, no division on the way
/// down; a child of importance 0 is never taken, whatever `t`'s rounding), and `u` for the
/// next level is where `t` lies in the chosen interval, `(t - start) / I_c`.
struct ByU<L>(L);

impl<L: Lane> Chooser<L> for ByU<L> {
    #[inline(always)]
    fn pick(&mut self, _level: u32, i: &[L; 4], s01: L, s23: L, sum: L) -> (L::Mask, L::Mask) {
        let zero = L::splat(0.0);
        let [i0, i1, i2, i3] = *i;
        let s012 = s01 + i2;
        let t = self.0 * sum;
        // The bound `at` past which `t` takes a side of weight `w`; never if `w` is 0.
        let bound = |w: L, at: L| L::select(zero.simd_lt(w), at, L::splat(f32::INFINITY));
        // `t` is finite (`u` in [0, 1), `S` at most 2^127), so `!(t < b)` is `b <= t`.
        let high = bound(s23, s01).simd_le(t);
        let second = L::select(high, bound(i3, s012), bound(i1, i0)).simd_le(t);
        let start = L::select(
            high,
            L::select(second, s012, s01),
            L::select(second, i0, zero),
        );
        let chosen = L::select(high, L::select(second, i3, i2), L::select(second, i1, i0));
        // `(t - start) / I_c` in [0, 1 - 2^-24]; a dead end (`I_c = 0`) gives NaN, replaced
        // by 0 (the walk stops there anyway).
        let v = (t - start) / chosen;
        let top = L::splat(ONE_MINUS_EPSILON);
        self.0 = L::select(zero.simd_lt(v), L::select(v.simd_lt(top), v, top), zero);
        (high, second)
    }
}

/// Picks by a light's bit trail.
struct ByTrail<U>(U);

impl<L: Lane> Chooser<L> for ByTrail<L::U> {
    #[inline(always)]
    fn pick(&mut self, level: u32, _i: &[L; 4], _: L, _: L, _: L) -> (L::Mask, L::Mask) {
        let one = L::U::splat(1);
        let bit = |b: u32| !(self.0.shr(b) & one).simd_eq(L::U::splat(0));
        (bit(2 * level), bit(2 * level + 1))
    }
}

/// `x` if `0 < x`, else 0 (NaN too).
#[inline(always)]
fn pos<L: Lane>(x: L) -> L {
    L::select(L::splat(0.0).simd_lt(x), x, L::splat(0.0))
}

/// The shading point as the walk sees it: `p`, the unit normal (or zeros), whether there is
/// one, whether `p` is finite, and the exact power-of-two scales of lengths and of powers
/// that a quad out of range is evaluated at ([`with_scales`]; 1 otherwise).
#[derive(Clone, Copy)]
pub(super) struct Point<L: Lane> {
    p: [L; 3],
    n: [L; 3],
    has_n: L::Mask,
    valid: L::Mask,
    /// Multiplies every `p - c` and radius: `2^k`, so that the quad's children's largest
    /// `|p - c|` coordinate or radius lies in `[1, 4)`.
    len_scale: L,
    /// Multiplies every power: `2^k`, so that the quad's children's largest power lies in
    /// `[1, 4)`.
    power_scale: L,
}

/// `2^k` with `2^k m` in `[1, 2)` for a normal `m` below `2^127`, `[2, 4)` from `2^127` to
/// `f32::MAX`; `2^126` for a smaller `m` (0 included), `2^-126` for `inf` or NaN. Always a
/// normal number (a device that flushes subnormals reads the same), and multiplying by it is
/// exact wherever the product stays normal.
#[inline(always)]
fn pow2_down<L: Lane>(m: L) -> L {
    let e = m.to_bits().shr(23) & L::U::splat(0xff);
    let e = L::U::select(e.simd_lt(L::U::splat(1)), L::U::splat(1), e);
    let e = L::U::select(e.simd_lt(L::U::splat(254)), e, L::U::splat(253));
    L::from_bits((L::U::splat(254) - e).shl(23))
}

/// `m` raised to `x` where `m < x <= f32::MAX` (NaN and infinities never win).
#[inline(always)]
fn raise<L: Lane>(m: L, x: L) -> L {
    L::select(m.simd_lt(x) & x.simd_le(L::splat(f32::MAX)), x, m)
}

#[inline(always)]
fn point<L: Lane>(p: [L; 3], n: [L; 3]) -> Point<L> {
    let big = L::splat(f32::MAX);
    let finite = |x: L| x.abs().simd_le(big);
    let valid = finite(p[0]) & finite(p[1]) & finite(p[2]);
    let zero = L::splat(0.0);
    let p = p.map(|x| L::select(valid, x, zero));
    // The normal scaled by a power of two before its length is taken (exact: the unit
    // normal's bits are those of the unscaled division wherever that did not underflow or
    // overflow), so that every finite normal whose largest coordinate is at least 2^-126 is
    // one; smaller coordinates count as zero (as everywhere in the crate).
    let m = n.iter().fold(zero, |m, &x| raise(m, x.abs()));
    let has_n = finite(n[0]) & finite(n[1]) & finite(n[2]) & L::splat(f32::MIN_POSITIVE).simd_le(m);
    let k = pow2_down(m);
    let n = n.map(|x| x * k);
    let len2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    let inv = L::select(has_n, L::splat(1.0) / len2.sqrt(), zero);
    let n = n.map(|x| L::select(has_n, x * inv, zero));
    let one = L::splat(1.0);
    Point {
        p,
        n,
        has_n,
        valid,
        len_scale: one,
        power_scale: one,
    }
}

/// How far one stored child reaches at the point and how much it emits: the largest of `|p -
/// c|`'s coordinates and the radius, and the power (both 0 for a child of no positive
/// power; never NaN or infinite).
#[inline(always)]
fn extent<L: Lane>(pt: &Point<L>, w: &[L::U]) -> (L, L) {
    let f = |k: usize| L::from_bits(w.get(k).copied().unwrap_or(L::U::splat(0)));
    let zero = L::splat(0.0);
    let phi = raise(zero, f(4));
    let len = (0..3).fold(raise(zero, f(3)), |m, k| raise(m, (pt.p[k] - f(k)).abs()));
    let live = zero.simd_lt(phi);
    (L::select(live, len, zero), phi)
}

/// The point with a quad's scales ([`Point::len_scale`], [`Point::power_scale`]) from its
/// four children's [`extent`]s. A walk compares only the importances of siblings, and every
/// importance is homogeneous (degree -2 in lengths, 1 in power), so a factor common to the
/// four changes no choice and no probability: the bits are those of the unscaled
/// evaluation wherever that neither overflowed nor underflowed, and where it did (a light
/// at `1e20` beside lights at 1: `r^2` overflowed and the group's lights read importance 0;
/// faint lights seen from far away: `phi / d^2` underflowed) the scaled one does not, as
/// long as the four siblings' distances lie within `2^63` of each other (beyond that the
/// nearer one's `d^2` is clamped at `2^-126`: it takes all but `2^-126` of the probability).
#[inline(always)]
fn with_scales<L: Lane>(pt: &Point<L>, extents: [(L, L); 4]) -> Point<L> {
    let zero = L::splat(0.0);
    let (len, power) = extents.iter().fold((zero, zero), |(l, p), &(el, ep)| {
        (raise(l, el), raise(p, ep))
    });
    Point {
        len_scale: pow2_down(len),
        power_scale: pow2_down(power),
        ..*pt
    }
}

/// The importance of one stored node at the point (see [`LightTree`]): finite, in
/// `[0, 2^125]`, whatever the words hold.
///
/// The cosines and sines of the angles are carried multiplied by the distance `d` (by
/// `d^2` for `cos(theta')` and the incidence factor), so that the three square roots
/// (`d sin(theta_w)`, `d cos(theta_b)`, `d sin(theta_i)`) run side by side and one division
/// (`1 / d^2`) ends the chain: `d cos(theta_w) = w . (p - c)`, `d sin(theta_w) =
/// sqrt(d^2 - (w . (p - c))^2)`, `d cos(theta_b) = sqrt(d^2 - r^2)`, `d sin(theta_b) = r`.
#[inline(always)]
fn importance<L: Lane, const SCALED: bool>(pt: &Point<L>, w: &[L::U]) -> (L, L::Mask) {
    let word = |k: usize| w.get(k).copied().unwrap_or(L::U::splat(0));
    let f = |k: usize| L::from_bits(word(k));
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    // The quad's scales where it needs them (`SCALED`), else none (the same bits as a
    // multiplication by 1).
    let (ls, ps) = (pt.len_scale, pt.power_scale);
    let by = |x: L, k: L| if SCALED { x * k } else { x };
    let d = [
        by(pt.p[0] - f(0), ls),
        by(pt.p[1] - f(1), ls),
        by(pt.p[2] - f(2), ls),
    ];
    let d2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    let r = by(f(3), ls);
    let r2 = r * r;
    let phi = by(f(4), ps);
    // Inside the sphere (or on it): the cone of directions to it is the whole sphere.
    let outside = r2.simd_lt(d2);
    // The stored axis `v` is unit (to f32 rounding): `d cos(theta_w) = v . (p - c)` (folded
    // for two-sided nodes), `d sin(theta_w)`, `d`.
    let v = [f(5), f(6), f(7)];
    let a = v[0] * d[0] + v[1] * d[1] + v[2] * d[2];
    let info = word(NODE_WORDS - 1);
    let two_sided = !(info & L::U::splat(TWO_SIDED)).simd_eq(L::U::splat(0));
    // `|a|` for two-sided nodes: the sign bit cleared by a mask made off the critical path.
    let keep = L::U::select(two_sided, L::U::splat(0x7fff_ffff), L::U::splat(u32::MAX));
    let a = L::from_bits(a.to_bits() & keep);
    let sw = pos(d2 - a * a).sqrt();
    let dist = d2.sqrt();
    let (cos_o, sin_o, cos_e) = (f(8), f(9), f(10));
    // d cos(theta_x), d sin(theta_x) for theta_x = max(0, theta_w - theta_o).
    let within = (cos_o * dist).simd_lt(a);
    let cx = L::select(within, dist, a * cos_o + sw * sin_o);
    let sx = L::select(within, zero, sw * cos_o - a * sin_o);
    // d cos(theta_b); d sin(theta_b) is r.
    let cb = pos(d2 - r2).sqrt();
    // d^2 cos(theta') for theta' = max(0, theta_x - theta_b), and the incidence factor
    // d^2 cos(max(0, theta_i - theta_b)) from d cos(theta_i) = |n . (p - c)|.
    let ci = (d[0] * pt.n[0] + d[1] * pt.n[1] + d[2] * pt.n[2]).abs();
    let si = pos(d2 - ci * ci).sqrt();
    let cp = L::select(cb.simd_lt(cx), d2, cx * cb + sx * r);
    let cpi = L::select(cb.simd_lt(ci), d2, ci * cb + si * r);
    let dc = L::select(outside, d2, r2);
    let dc = L::select(
        L::splat(f32::MIN_POSITIVE).simd_lt(dc),
        dc,
        L::splat(f32::MIN_POSITIVE),
    );
    let inv = one / dc;
    let cos_p = L::select(outside, cp * inv, one);
    let cos_pi = L::select(outside & pt.has_n, cpi * inv, one);
    let q = phi * inv;
    let imp = q * cos_pi * cos_p;
    let alive = cos_e.simd_le(cos_p) & pt.valid;
    let imp = L::select(alive, imp, zero);
    // In range: `phi / max(d^2, r^2)` in `[2^-100, 2^100)` (a child of power 0 always is).
    // That covers every overflow and underflow the evaluation can meet: an infinite `d^2`
    // or `r^2` makes it 0, one held at `2^-126` large, and a finite `d^2` keeps every
    // product below it finite. A quad with a child out of range is evaluated again at its
    // scales ([`with_scales`]).
    let in_range =
        q.simd_lt(L::splat(RANGE)) & L::splat(1.0 / RANGE).simd_le(q) | !zero.simd_lt(phi);
    // Below `2^-126` an importance counts as 0 (flush-proof: a device that flushes
    // subnormals sees the same).
    let imp = L::select(
        L::splat(f32::MIN_POSITIVE).simd_le(imp),
        L::select(imp.simd_lt(L::splat(BIG)), imp, L::splat(BIG)),
        zero,
    );
    (imp, in_range)
}

/// Unscaled importances are used where `phi / max(d^2, r^2)` lies below this (`2^100`) and
/// at least its inverse.
const RANGE: f32 = (1u128 << 100) as f32;

/// Words of one quad: the four children of an inner node (192 bytes, three cache lines),
/// field-major: word `k` of child `c` at `4 k + c`, so that a scalar walk loads each field
/// of the four children as one `u32x4`.
const QUAD_WORDS: usize = 4 * NODE_WORDS;

/// The lanes a walk runs in, and a quad's children at the point. One lane-generic body
/// ([`importance`], [`walk`]). A scalar walk runs in `f32x4` lanes holding four copies of
/// the sample: it loads each field of a quad's four children as one `u32x4` straight from
/// the storage, evaluates the four children as the four lanes of one `f32x4`, broadcasts
/// each importance to its own vector, and makes its choices with vector compares and blends
/// (which a compiler cannot turn into branches on `u`). Every lane runs the same IEEE
/// operations in the same order, so the bits are those of the SIMD walks, which gather
/// their lanes' quads and evaluate the children one after the other.
pub(super) trait Children: Lane {
    /// The walk's lane type: `f32x4` for the scalar, `Self` otherwise.
    type W: Lane;
    /// The walk's handle on its current quad: its index (in every lane).
    type Q: Copy;
    fn widen(x: Self) -> Self::W;
    fn widen_u(x: Self::U) -> <Self::W as Lane>::U;
    fn narrow(x: Self::W) -> Self;
    fn narrow_u(x: <Self::W as Lane>::U) -> Self::U;
    /// The root's quad.
    fn root() -> Self::Q;
    /// The importances of a quad's four children, their last words (leaf flag and index),
    /// and the handles of their quads (meaningless for leaves).
    fn open(
        pt: &Point<Self::W>,
        quads: &[[u32; QUAD_WORDS]],
        quad: &Self::Q,
    ) -> Opened<Self::W, Self::Q>;
    /// The quad of the child taken (`high`: in the pair `{2, 3}`, `second`: the second of
    /// its pair) where `step`, else `quad`.
    fn advance(
        quad: Self::Q,
        children: [Self::Q; 4],
        high: <Self::W as Lane>::Mask,
        second: <Self::W as Lane>::Mask,
        step: <Self::W as Lane>::Mask,
    ) -> Self::Q;
}

/// A quad opened at the point: its four children's importances, last words (leaf flag and
/// index) and quad handles.
pub(super) struct Opened<L: Lane, Q> {
    imp: [L; 4],
    info: [L::U; 4],
    children: [Q; 4],
}

/// The scalar walk's quad (its storage words `rec`, read again as the four children in the
/// four lanes) evaluated again at its scales, the largest of the four lanes' extents
/// ([`with_scales`]). Rare (a branch on the scene, not on `u`), so out of line: inlined, its
/// registers cost the common path of every walk; and it reads the storage rather than take
/// the walk's loaded words, which the call would make every quad store first.
#[cold]
#[inline(never)]
fn rescaled4(pt: &Point<f32x4>, rec: &[u32; QUAD_WORDS]) -> f32x4 {
    let rows = rec.as_chunks::<4>().0;
    let words: &[u32x4; NODE_WORDS] = &core::array::from_fn(|k| {
        from_storage_order(u32x4::new(rows.get(k).copied().unwrap_or([0; 4])))
    });
    let (len, power) = extent::<f32x4>(pt, words);
    let (len, power) = (len.to_array(), power.to_array());
    let extents = [0, 1, 2, 3].map(|c| (f32x4::splat(len[c]), f32x4::splat(power[c])));
    importance::<f32x4, true>(&with_scales(pt, extents), words).0
}

/// A quad of zeros: what a quad index past the end reads (never in a storage `new` wrote).
const ZERO_QUAD: [u32; QUAD_WORDS] = [0; QUAD_WORDS];

/// One of four values by the two choices.
#[inline(always)]
fn pick4<U: UintLane>(v: [U; 4], high: U::Mask, second: U::Mask) -> U {
    let [a, b, c, d] = v;
    U::select(high, U::select(second, d, c), U::select(second, b, a))
}

/// Touches one word of each of quad `index`'s three cache lines, so that the lines are on
/// their way to the first-level cache while the walk is still choosing (the loaded values
/// are not used: `black_box` only keeps the loads).
#[inline(always)]
fn touch(quads: &[[u32; QUAD_WORDS]], index: u32) {
    let rec = quads.get(index as usize).unwrap_or(&ZERO_QUAD);
    core::hint::black_box(rec[0] ^ rec[QUAD_WORDS / 3] ^ rec[2 * QUAD_WORDS / 3]);
}

impl Children for f32 {
    type W = f32x4;
    type Q = u32x4;
    #[inline(always)]
    fn widen(x: f32) -> f32x4 {
        f32x4::splat(x)
    }
    #[inline(always)]
    fn widen_u(x: Wrapping<u32>) -> u32x4 {
        u32x4::splat(x.0)
    }
    #[inline(always)]
    fn narrow(x: f32x4) -> f32 {
        x.to_array()[0]
    }
    #[inline(always)]
    fn narrow_u(x: u32x4) -> Wrapping<u32> {
        Wrapping(x.to_array()[0])
    }
    #[inline(always)]
    fn root() -> Self::Q {
        u32x4::splat(0)
    }
    /// Reads one word from each cache line of the four children's quads before the choice
    /// is made (the next level's loads then hit the first-level cache).
    #[inline(always)]
    fn open(
        pt: &Point<f32x4>,
        quads: &[[u32; QUAD_WORDS]],
        quad: &Self::Q,
    ) -> Opened<f32x4, Self::Q> {
        let rec = quads.get(quad.to_array()[0] as usize).unwrap_or(&ZERO_QUAD);
        let rows = rec.as_chunks::<4>().0;
        let words: [u32x4; NODE_WORDS] = core::array::from_fn(|k| {
            from_storage_order(u32x4::new(rows.get(k).copied().unwrap_or([0; 4])))
        });
        let info = words[NODE_WORDS - 1].to_array();
        let children = info.map(|w| {
            touch(quads, w & INDEX_MASK);
            u32x4::splat(w & INDEX_MASK)
        });
        let (imp, in_range) = importance::<f32x4, false>(pt, &words);
        // A child out of range (rare: a branch on the scene, not on `u`): the quad again at
        // its scales.
        let bad = <u32x4 as UintLane>::select(in_range, u32x4::splat(0), u32x4::splat(u32::MAX));
        let imp = if bad.to_bitmask() == 0 {
            imp
        } else {
            rescaled4(pt, rec)
        }
        .to_array();
        Opened {
            imp: imp.map(f32x4::splat),
            info: info.map(u32x4::splat),
            children,
        }
    }
    #[inline(always)]
    fn advance(
        _quad: Self::Q,
        children: [Self::Q; 4],
        high: <f32x4 as Lane>::Mask,
        second: <f32x4 as Lane>::Mask,
        _step: <f32x4 as Lane>::Mask,
    ) -> Self::Q {
        // Once the walk has stopped, what it reads no longer matters.
        pick4(children, high, second)
    }
}

macro_rules! children_one_by_one {
    ($($l:ty),*) => {$(
        impl Children for $l {
            type W = $l;
            type Q = <$l as Lane>::U;
            #[inline(always)]
            fn widen(x: $l) -> $l {
                x
            }
            #[inline(always)]
            fn widen_u(x: <$l as Lane>::U) -> <$l as Lane>::U {
                x
            }
            #[inline(always)]
            fn narrow(x: $l) -> $l {
                x
            }
            #[inline(always)]
            fn narrow_u(x: <$l as Lane>::U) -> <$l as Lane>::U {
                x
            }
            #[inline(always)]
            fn root() -> Self::Q {
                <$l as Lane>::U::splat(0)
            }
            #[inline(always)]
            fn open(
                pt: &Point<$l>,
                quads: &[[u32; QUAD_WORDS]],
                quad: &Self::Q,
            ) -> Opened<$l, Self::Q> {
                let rec = <$l as Lane>::U::gather(quads, *quad).map(from_storage_order);
                let word = |k: usize, c: usize| {
                    rec.get(4 * k + c).copied().unwrap_or(<$l as Lane>::U::splat(0))
                };
                let w: [[_; NODE_WORDS]; 4] =
                    core::array::from_fn(|c| core::array::from_fn(|k| word(k, c)));
                let fast = [0, 1, 2, 3].map(|c| importance::<$l, false>(pt, &w[c]));
                let ok = fast[0].1 & fast[1].1 & fast[2].1 & fast[3].1;
                let imp = fast.map(|x| x.0);
                // A lane with a child out of range (rare): its quad again at its scales.
                let bad = <<$l as Lane>::U as UintLane>::select(
                    ok,
                    <$l as Lane>::U::splat(0),
                    <$l as Lane>::U::splat(u32::MAX),
                );
                let imp = if bad.to_bitmask() == 0 {
                    imp
                } else {
                    let pt = with_scales(pt, [0, 1, 2, 3].map(|c| extent::<$l>(pt, &w[c])));
                    let scaled = [0, 1, 2, 3].map(|c| importance::<$l, true>(&pt, &w[c]).0);
                    [0, 1, 2, 3].map(|c| <$l as Lane>::select(ok, imp[c], scaled[c]))
                };
                let info: [_; 4] = core::array::from_fn(|c| word(NODE_WORDS - 1, c));
                let children = info.map(|w| w & <$l as Lane>::U::splat(INDEX_MASK));
                Opened { imp, info, children }
            }
            #[inline(always)]
            fn advance(
                quad: Self::Q,
                children: [Self::Q; 4],
                high: <$l as Lane>::Mask,
                second: <$l as Lane>::Mask,
                step: <$l as Lane>::Mask,
            ) -> Self::Q {
                UintLane::select(step, pick4(children, high, second), quad)
            }
        }
    )*};
}
children_one_by_one!(f32x8, f32x16);

/// The walk: `levels` steps from quad 0, each picking one of four children `c` with
/// probability `I_c / S` (`S = I_0 + I_1 + I_2 + I_3`) by two binary choices (`choose`): the
/// pair `{0, 1}` or `{2, 3}` by the pairs' sums, then a child of the pair by its two
/// importances. Returns the light reached (`u32::MAX` if none) and its probability (0 if
/// none): the product of the levels' `I_c / S` in root-to-leaf order.
#[inline(always)]
fn walk<L: Lane, K: Children<W = L>, C: Chooser<L>>(
    quads: &[[u32; QUAD_WORDS]],
    len: u32,
    levels: u32,
    pt: &Point<L>,
    choose: &mut C,
) -> (L::U, L) {
    let zero = L::splat(0.0);
    let one = L::splat(1.0);
    let uzero = L::U::splat(0);
    let mut quad = K::root();
    let mut prob = one;
    let mut index = L::U::splat(u32::MAX);
    // `done`: reached a leaf; `dead`: stopped where the children have importance 0.
    let mut done = uzero.simd_eq(L::U::splat(1));
    let mut dead = !pt.valid;
    for level in 0..levels.min(MAX_LEVELS) {
        let Opened {
            imp,
            info,
            children,
        } = K::open(pt, quads, &quad);
        let [i0, i1, i2, i3] = imp;
        let (s01, s23) = (i0 + i1, i2 + i3);
        let sum = s01 + s23;
        let (high, second) = choose.pick(level, &imp, s01, s23, sum);
        let chosen = L::select(high, L::select(second, i3, i2), L::select(second, i1, i0));
        let live = zero.simd_lt(sum);
        let active = !(done | dead);
        dead = dead | (active & !live);
        let active = active & live;
        // `chosen / sum` in [0, 1] (0 for a trail through a child of importance 0).
        let p_child = L::select(live, chosen / sum, zero);
        prob = L::select(active, prob * p_child, prob);
        let info = pick4(info, high, second);
        let target = info & L::U::splat(INDEX_MASK);
        let leaf = !(info & L::U::splat(LEAF)).simd_eq(uzero);
        let reached = active & leaf;
        index = L::U::select(reached, target, index);
        done = done | reached;
        quad = K::advance(quad, children, high, second, active & !leaf);
    }
    // A leaf naming a light past the end (only in a corrupt storage), a walk cut short, a
    // dead end or a probability below `2^-126` (its `1 / q` would overflow a renderer's
    // `f32`, and a device that flushes subnormals sees 0): no light.
    let ok =
        done & !dead & index.simd_lt(L::U::splat(len)) & L::splat(f32::MIN_POSITIVE).simd_le(prob);
    (
        L::U::select(ok, index, L::U::splat(u32::MAX)),
        L::select(ok, prob, zero),
    )
}

impl<'a> LightTree<'a> {
    /// Words of storage `new` needs for `n` lights: `16 + 48 (n / 3 + 14) + n` (about 68
    /// bytes per light, after a 64-byte header and 2,688 bytes of slack for the partial
    /// quads); `usize::MAX` above `2^24` lights (the format's limit, see
    /// [`Error::TooLarge`]).
    pub const fn storage_len(n: usize) -> usize {
        if n > MAX_LIGHTS {
            usize::MAX
        } else {
            HEADER_WORDS + QUAD_WORDS * quads_bound(n) + n
        }
    }

    /// Builds the tree over `lights` into `storage` (at least [`storage_len`](Self::storage_len)
    /// words, any contents; the storage is also the build's only scratch space).
    /// O(n log n), no allocation.
    ///
    /// Errors: [`Error::Empty`] for no lights, [`Error::TooLarge`] above `2^24`,
    /// [`Error::StorageTooSmall`], [`Error::InvalidWeight`] for a NaN, infinite or negative
    /// power, [`Error::InvalidBounds`] for a NaN or infinite coordinate, `min > max` on some
    /// axis, a zero, NaN or infinite axis, or a cosine outside `[-1, 1]` or NaN (the first
    /// offending light is named), [`Error::AllZero`] if every power is 0. Never panics.
    /// Non-unit axes are normalised. Coordinates anywhere in `f32`'s range are sampled (see
    /// "Range" in the type's docs); only a coordinate difference beyond `f32::MAX` (a light
    /// and the shading point near opposite ends of the range) gives importance 0.
    pub fn new(lights: &[LightBounds], storage: &'a mut [u32]) -> Result<Self, Error> {
        let light = |i: usize| lights.get(i).copied().unwrap_or_default();
        Self::new_from_fn(lights.len(), light, storage)
    }

    /// [`new`](Self::new) over `n` lights given by `light(i)` for `i` in `0..n`, called
    /// O(n log n) times (keep it cheap): builds from any representation without collecting
    /// the bounds in memory first (the C ABI's `WcLightBounds` array, a mesh's triangles).
    /// The same tree, words and errors as `new` over `[light(0), ..., light(n - 1)]` (with
    /// `n = 0` as the empty slice).
    pub fn new_from_fn(
        n: usize,
        light: impl Fn(usize) -> LightBounds,
        storage: &'a mut [u32],
    ) -> Result<Self, Error> {
        build::build(n, light, storage)?;
        Self::from_storage(storage)
    }

    /// Reads a storage `new` wrote (O(1): the header only). Sampling a storage that passed
    /// never panics and gives valid outputs whatever its other words hold.
    ///
    /// Errors: [`Error::StorageTooSmall`], [`Error::WrongFormat`],
    /// [`Error::UnsupportedVersion`], [`Error::Corrupt`] (a header word `new` never writes).
    pub fn from_storage(storage: &'a [u32]) -> Result<Self, Error> {
        let got = storage.len();
        let header: [u32; HEADER_WORDS] = header(storage, TAG, VERSION)?;
        let word = |k: usize| header.get(k).copied().unwrap_or(0);
        let n = word(2) as usize;
        if n == 0 || n > MAX_LIGHTS {
            return Err(Error::Corrupt { word: 2 });
        }
        let m = word(3) as usize;
        if m == 0 || m > n {
            return Err(Error::Corrupt { word: 3 });
        }
        if word(4) != levels_for(m) {
            return Err(Error::Corrupt { word: 4 });
        }
        if let Some(k) = (5..HEADER_WORDS).find(|&k| k != CHECKSUM_WORD && word(k) != 0) {
            return Err(Error::Corrupt { word: k });
        }
        let needed = Self::storage_len(n);
        if got < needed {
            return Err(Error::StorageTooSmall { needed, got });
        }
        Ok(Self {
            storage: storage.get(..needed).unwrap_or(storage),
            len: n,
            levels: word(4),
        })
    }

    /// [`from_storage`](Self::from_storage), then the content checksum over every word
    /// (O(n)): every single-bit flip is rejected ([`Error::Corrupt`] naming word 8).
    pub fn from_storage_verified(storage: &'a [u32]) -> Result<Self, Error> {
        let tree = Self::from_storage(storage)?;
        if !sealed(tree.storage, CHECKSUM_WORD) {
            return Err(Error::Corrupt {
                word: CHECKSUM_WORD,
            });
        }
        Ok(tree)
    }

    /// The number of lights `n` (those of power 0 included).
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always false: a tree holds at least one light.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The storage words (little-endian bytes on every target): write them to a file and
    /// read them back with [`from_storage_verified`](Self::from_storage_verified).
    pub fn storage(&self) -> &'a [u32] {
        self.storage
    }

    fn quads(&self) -> &'a [[u32; QUAD_WORDS]] {
        let end = HEADER_WORDS + QUAD_WORDS * quads_bound(self.len);
        self.storage
            .get(HEADER_WORDS..end)
            .unwrap_or(&[])
            .as_chunks::<QUAD_WORDS>()
            .0
    }

    fn trails(&self) -> &'a [[u32; 1]] {
        let start = HEADER_WORDS + QUAD_WORDS * quads_bound(self.len);
        self.storage.get(start..).unwrap_or(&[]).as_chunks::<1>().0
    }

    #[inline(always)]
    fn sample_lanes<L: Children>(&self, p: [L; 3], n: [L; 3], u: L) -> (L::U, L) {
        let pt = point(p.map(L::widen), n.map(L::widen));
        let mut by_u = ByU(unit_interval(L::widen(u)));
        let quads = self.quads();
        let (i, q) = walk::<L::W, L, _>(quads, self.len as u32, self.levels, &pt, &mut by_u);
        (L::narrow_u(i), L::narrow(q))
    }

    #[inline(always)]
    fn pmf_lanes<L: Children>(&self, p: [L; 3], n: [L; 3], index: L::U) -> L {
        let pt = point(p.map(L::widen), n.map(L::widen));
        let [trail] = L::U::gather(self.trails(), index);
        let mut by_trail = ByTrail(from_storage_order(L::widen_u(trail)));
        let quads = self.quads();
        let (reached, prob) =
            walk::<L::W, L, _>(quads, self.len as u32, self.levels, &pt, &mut by_trail);
        let (reached, prob) = (L::narrow_u(reached), L::narrow(prob));
        L::select(reached.simd_eq(index), prob, L::splat(0.0))
    }

    /// Picks a light for the shading point `p` with unit normal `n` (`[0, 0, 0]` for a point
    /// in a medium) from `u`: `Some((index, probability))`, the probability being exactly
    /// [`pmf(p, n, index)`](Self::pmf) and positive; `None` where no light contributes (or
    /// the walk meets a dead end, see the type's docs). `u` goes through the crate's forward
    /// rule (NaN and negatives -> 0, `>= 1` -> `1 - 2^-24`). O(depth).
    #[inline]
    pub fn sample(&self, p: [f32; 3], n: [f32; 3], u: f32) -> Option<(u32, f32)> {
        let (i, q) = self.sample_lanes(p, n, u);
        if q > 0.0 { Some((i.0, q)) } else { None }
    }

    /// [`sample`](Self::sample) on eight points at once, bit-identical to eight scalar calls:
    /// `(indices, probabilities)`, where lane `j` is `(u32::MAX, 0.0)` for a scalar `None`.
    #[inline]
    pub fn sample_x8(&self, p: [f32x8; 3], n: [f32x8; 3], u: f32x8) -> (u32x8, f32x8) {
        self.sample_lanes(p, n, u)
    }

    /// [`sample`](Self::sample) on sixteen points at once (see [`sample_x8`](Self::sample_x8)).
    #[inline]
    pub fn sample_x16(&self, p: [f32x16; 3], n: [f32x16; 3], u: f32x16) -> (u32x16, f32x16) {
        self.sample_lanes(p, n, u)
    }

    /// [`sample`](Self::sample) over a batch: `out[i] = sample(p[i], n[i], u[i])` for `i`
    /// below the shortest length, which it returns. Runs groups of eight lanes; bit-identical
    /// to the scalar form.
    pub fn sample_slice(
        &self,
        p: &[[f32; 3]],
        n: &[[f32; 3]],
        u: &[f32],
        out: &mut [Option<(u32, f32)>],
    ) -> usize {
        let count = p.len().min(n.len()).min(u.len()).min(out.len());
        let mut start = 0;
        while start < count {
            let get3 = |s: &[[f32; 3]], k: usize| {
                f32x8::new(core::array::from_fn(|j| {
                    s.get(start + j)
                        .filter(|_| start + j < count)
                        .map_or(0.0, |v| v[k])
                }))
            };
            let pp = [0, 1, 2].map(|k| get3(p, k));
            let nn = [0, 1, 2].map(|k| get3(n, k));
            let uu = f32x8::new(core::array::from_fn(|j| {
                u.get(start + j).copied().unwrap_or(0.0)
            }));
            let (i, q) = self.sample_x8(pp, nn, uu);
            let (i, q) = (i.to_array(), q.to_array());
            for j in 0..8 {
                if start + j < count
                    && let Some(o) = out.get_mut(start + j)
                {
                    *o = if q[j] > 0.0 { Some((i[j], q[j])) } else { None };
                }
            }
            start += 8;
        }
        count
    }

    /// The probability that [`sample`](Self::sample) at `(p, n)` returns light `index`, for
    /// MIS: the product of the sides' probabilities along the light's stored path, O(depth).
    /// 0 for an index `>= len`, a light of power 0, and a light of importance 0 at `p`.
    ///
    /// Error against the same walk in `f64` (measured, `tests/lights/tree.rs`, 600,000
    /// probabilities of a 300-light scene): at most `1.4e-7` absolute, `1.9e-5` relative where
    /// the probability is at least `1e-3`. That is typical, not a bound: `d sin(theta_w) =
    /// sqrt(d^2 - (w . (p - c))^2)` cancels for `p` near a node's axis line, and `d
    /// cos(theta_b) = sqrt(d^2 - r^2)` near its bounding sphere (where the bound itself jumps),
    /// so there the `f32` importance can differ from the `f64` one by percents (2.7% for `p`
    /// `1e-3` off a spot light's axis line at distance 100). The importance only steers the
    /// choice: the probability is exact for what `sample` does (it is the product `sample`
    /// reports), so estimates stay unbiased.
    #[inline]
    pub fn pmf(&self, p: [f32; 3], n: [f32; 3], index: u32) -> f32 {
        self.pmf_lanes(p, n, Wrapping(index))
    }

    /// [`pmf`](Self::pmf) on eight points and indices at once; bit-identical to eight scalar
    /// calls.
    #[inline]
    pub fn pmf_x8(&self, p: [f32x8; 3], n: [f32x8; 3], index: u32x8) -> f32x8 {
        self.pmf_lanes(p, n, index)
    }

    /// [`pmf`](Self::pmf) on sixteen points and indices at once; bit-identical to sixteen
    /// scalar calls.
    #[inline]
    pub fn pmf_x16(&self, p: [f32x16; 3], n: [f32x16; 3], index: u32x16) -> f32x16 {
        self.pmf_lanes(p, n, index)
    }
}

/// Levels of the walk over the tree of `m` leaves: `ceil(log4 m)`, at least 1.
const fn levels_for(m: usize) -> u32 {
    if m <= 1 {
        1
    } else {
        (usize::BITS - (m - 1).leading_zeros()).div_ceil(2)
    }
}

/// Quads the storage holds for `n` lights: at least what the build of any `m <= n` lights
/// uses (`(m - 1) / 3` in its full subtrees, plus one partial quad per level).
const fn quads_bound(n: usize) -> usize {
    n / 3 + 14
}
