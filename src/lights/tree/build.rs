//! Building a [`LightTree`](super::LightTree): validation, a balanced median-split hierarchy
//! built with the storage as its only scratch, node encoding, bit trails, the header.

use super::{
    CHECKSUM_WORD, HEADER_WORDS, INDEX_MASK, LEAF, LightBounds, MAX_LIGHTS, NODE_WORDS, QUAD_WORDS,
    TAG, TWO_SIDED, VERSION, levels_for, quads_bound,
};
use crate::lanes::Lane;
use crate::lights::Error;
use crate::storage::{seal, to_storage_order};
use core::f64::consts::PI;

/// The bounds of a subtree during the build, in `f64` where unions need it.
#[derive(Clone, Copy)]
struct Bounds {
    min: [f32; 3],
    max: [f32; 3],
    phi: f64,
    /// Unit axis of the normal cone.
    w: [f64; 3],
    /// `theta_o`, radians.
    theta_o: f64,
    /// `cos(theta_o)`.
    cos_o: f64,
    cos_e: f64,
    two_sided: bool,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// The angle between two unit vectors, accurate near 0 and pi (the `atan2` of the cross and
/// dot products).
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = cross(a, b);
    libm::atan2(libm::sqrt(dot(c, c)), dot(a, b))
}

/// The smallest cone (of this construction) holding both normal cones: pbrt-v4's
/// `DirectionCone` union, our transcription.
fn cone_union(a: ([f64; 3], f64, f64), b: ([f64; 3], f64, f64)) -> ([f64; 3], f64, f64) {
    let ((wa, ta, _), (wb, tb, _)) = (a, b);
    let td = angle(wa, wb);
    if (td + tb).min(PI) <= ta {
        return a;
    }
    if (td + ta).min(PI) <= tb {
        return b;
    }
    let to = (ta + td + tb) / 2.0;
    if to >= PI {
        return (wa, PI, -1.0);
    }
    // Rotate wa towards wb by to - ta about their common normal (Rodrigues).
    let axis = cross(wa, wb);
    let len = libm::sqrt(dot(axis, axis));
    if len == 0.0 {
        return (wa, PI, -1.0);
    }
    let k = axis.map(|x| x / len);
    let (s, c) = (libm::sin(to - ta), libm::cos(to - ta));
    let kxw = cross(k, wa);
    let kw = dot(k, wa);
    let w: [f64; 3] = core::array::from_fn(|i| wa[i] * c + kxw[i] * s + k[i] * kw * (1.0 - c));
    let l = libm::sqrt(dot(w, w));
    // A margin for the rounding of the rotation.
    let to = (to + 1e-9).min(PI);
    ((w.map(|x| x / l)), to, libm::cos(to))
}

impl Bounds {
    fn of(l: &LightBounds) -> Self {
        let a = l.axis.map(f64::from);
        let len = libm::sqrt(dot(a, a));
        Bounds {
            min: l.min,
            max: l.max,
            phi: f64::from(l.power),
            w: a.map(|x| x / len),
            theta_o: libm::acos(f64::from(l.cos_theta_o)),
            cos_o: f64::from(l.cos_theta_o),
            cos_e: f64::from(l.cos_theta_e),
            two_sided: l.two_sided,
        }
    }

    fn union(&self, o: &Self) -> Self {
        let (w, theta_o, cos_o) = cone_union(
            (self.w, self.theta_o, self.cos_o),
            (o.w, o.theta_o, o.cos_o),
        );
        Bounds {
            min: core::array::from_fn(|i| self.min[i].min(o.min[i])),
            max: core::array::from_fn(|i| self.max[i].max(o.max[i])),
            phi: self.phi + o.phi,
            w,
            theta_o,
            cos_o,
            cos_e: self.cos_e.min(o.cos_e),
            two_sided: self.two_sided || o.two_sided,
        }
    }

    /// The node record (native byte order): centre, radius (rounded up to contain the box
    /// around the rounded centre), power, the axis in `f32` (scaled so that its length is
    /// at least 1: the walk, which takes it as unit, then overestimates `cos(theta_w)`, the
    /// conservative side), `cos_theta_o` (the axis's rounding error added to `theta_o`) and
    /// `cos_theta_e` rounded down to `f32`, the sine of the stored `theta_o`, and `info` with
    /// the two-sided flag.
    fn record(&self, info: u32) -> [u32; NODE_WORDS] {
        let centre: [f32; 3] = core::array::from_fn(|i| self.min[i] / 2.0 + self.max[i] / 2.0);
        let mut r2 = 0.0f64;
        for (i, &c) in centre.iter().enumerate() {
            let far = (f64::from(c) - f64::from(self.min[i]))
                .abs()
                .max((f64::from(self.max[i]) - f64::from(c)).abs());
            r2 += far * far;
        }
        let r = libm::sqrt(r2);
        let mut r32 = r as f32;
        if f64::from(r32) < r {
            r32 = r32.next_up();
        }
        let phi = self.phi.min(f64::from(f32::MAX)) as f32;
        // Each component's rounding is below 2^-24 relative, so `|axis| > 1`.
        let axis = self.w.map(|x| (x * (1.0 + 1.0 / 4_194_304.0)) as f32);
        let decoded = {
            let v = axis.map(f64::from);
            let l = libm::sqrt(dot(v, v));
            v.map(|x| x / l)
        };
        // The axis's rounding error `err` (about 1e-7) widens the cone: a lower bound of
        // `cos(theta_o + err)` from `cos(err) >= 1 - err^2 / 2` and `sin(err) <= err`, without
        // a transcendental function (`asin(s) <= 1.0001 s` for the sine `s < 0.02` of the
        // error; `atan2` otherwise).
        let c = cross(decoded, self.w);
        let sin_err = libm::sqrt(dot(c, c));
        let err = if dot(decoded, self.w) > 0.0 && sin_err < 0.02 {
            sin_err * 1.0001
        } else {
            angle(decoded, self.w)
        } + 1e-6;
        let (co, so) = (
            self.cos_o,
            libm::sqrt((1.0 - self.cos_o * self.cos_o).max(0.0)),
        );
        let cos_o = if self.theta_o + err >= PI {
            -1.0
        } else if co >= 0.0 {
            co * (1.0 - err * err / 2.0) - so * err
        } else {
            co - so * err
        };
        // Cosines rounded down to f32 (the stored cone is never narrower); the sine is the
        // walk's own `sqrt(1 - cos^2)` of the stored cosine.
        let down = |c: f64| {
            let c32 = c as f32;
            let c32 = if f64::from(c32) > c {
                c32.next_down()
            } else {
                c32
            };
            c32.clamp(-1.0, 1.0)
        };
        let cos_o = down(cos_o);
        let sin_o = Lane::sqrt((1.0 - cos_o * cos_o).max(0.0));
        let info = info | if self.two_sided { TWO_SIDED } else { 0 };
        [
            centre[0].to_bits(),
            centre[1].to_bits(),
            centre[2].to_bits(),
            r32.to_bits(),
            phi.to_bits(),
            axis[0].to_bits(),
            axis[1].to_bits(),
            axis[2].to_bits(),
            cos_o.to_bits(),
            sin_o.to_bits(),
            down(self.cos_e).to_bits(),
            info,
        ]
    }
}

/// Checks one light (see `LightTree::new`'s errors).
fn check(index: usize, l: &LightBounds) -> Result<(), Error> {
    if !(l.power.is_finite() && l.power >= 0.0) {
        return Err(Error::InvalidWeight { index });
    }
    let bad = Err(Error::InvalidBounds { index });
    let coords_ok = l.min.iter().chain(&l.max).all(|c| c.is_finite())
        && (0..3).all(|i| l.min.get(i) <= l.max.get(i));
    let a = l.axis.map(f64::from);
    let axis_ok = l.axis.iter().all(|c| c.is_finite()) && dot(a, a) > 0.0;
    let cos_ok = [l.cos_theta_o, l.cos_theta_e]
        .iter()
        .all(|c| (-1.0..=1.0).contains(c));
    if coords_ok && axis_ok && cos_ok {
        Ok(())
    } else {
        bad
    }
}

struct Builder<'s, 'l, F> {
    quads: &'s mut [[u32; QUAD_WORDS]],
    lights: &'l F,
    next: usize,
}

impl<F: Fn(usize) -> LightBounds> Builder<'_, '_, F> {
    fn light(&self, i: u32) -> LightBounds {
        (self.lights)(i as usize)
    }

    /// Writes the children of the subtree over `perm` (at least one light, ordered by
    /// [`order`]) into quad `q` and returns the subtree's bounds.
    fn quad(&mut self, q: usize, perm: &mut [u32]) -> Bounds {
        let mut total: Option<Bounds> = None;
        for (slot, group) in groups(perm).into_iter().enumerate() {
            let (b, rec) = match *group {
                [] => continue,
                [i] => {
                    let b = Bounds::of(&self.light(i));
                    (b, b.record(LEAF | (i & INDEX_MASK)))
                }
                _ => {
                    let child = self.next;
                    self.next += 1;
                    let b = self.quad(child, group);
                    (b, b.record(child as u32 & INDEX_MASK))
                }
            };
            if let Some(dst) = self.quads.get_mut(q) {
                for (k, &w) in rec.iter().enumerate() {
                    if let Some(d) = dst.get_mut(4 * k + slot) {
                        *d = w;
                    }
                }
            }
            total = Some(total.map_or(b, |t| t.union(&b)));
        }
        total.unwrap_or(Bounds::of(&LightBounds::default()))
    }
}

/// The sizes of the first three of a quad's four groups over `m` lights: `4^(levels - 1)`
/// lights each, filled in order (full subtrees but one).
fn group_sizes(m: usize) -> [usize; 3] {
    let cap = 1usize << (2 * (levels_for(m) - 1));
    let size = |i: usize| m.saturating_sub(i * cap).min(cap);
    [size(0), size(1), size(2)]
}

/// The four groups of a quad over `v` (see [`group_sizes`]), in order.
fn groups<T>(v: &mut [T]) -> [&mut [T]; 4] {
    let [c0, c1, c2] = group_sizes(v.len());
    let (low, high) = v
        .split_at_mut_checked(c0 + c1)
        .unwrap_or((&mut [], &mut []));
    let (g0, g1) = low.split_at_mut_checked(c0).unwrap_or((&mut [], &mut []));
    let (g2, g3) = high.split_at_mut_checked(c2).unwrap_or((&mut [], &mut []));
    [g0, g1, g2, g3]
}

/// A light while the build orders them: its centroid's coordinates (`f32` bits) and its
/// index, side by side, so that the median splits read their keys in order instead of
/// fetching the caller's lights in a random one (at 10^6 lights those fetches missed every
/// cache and were most of the build).
type Rec = [u32; 4];

/// The record of light `index`: the centroid `min / 2 + max / 2` per axis.
fn rec(l: &LightBounds, index: u32) -> Rec {
    let c = |k: usize| {
        let at = |v: &[f32; 3]| v.get(k).copied().unwrap_or(0.0);
        (at(&l.min) / 2.0 + at(&l.max) / 2.0).to_bits()
    };
    [c(0), c(1), c(2), index]
}

/// Orders the lights of one subtree as [`Builder::quad`] will cut them into its four
/// groups: the first two groups below the other two along the longest axis of the
/// centroids' box, each half split the same way along its own, and every group of two or
/// more ordered in turn. Each split keeps the `at` smallest by (centroid, index), a strict
/// total order, so the groups (and the tree) do not depend on how the selection runs.
fn order(recs: &mut [Rec]) {
    if recs.len() < 2 {
        return;
    }
    let [c0, c1, c2] = group_sizes(recs.len());
    split(recs, c0 + c1);
    if let Some((low, high)) = recs.split_at_mut_checked(c0 + c1) {
        split(low, c0);
        split(high, c2);
    }
    for group in groups(recs) {
        order(group);
    }
}

/// Reorders `recs` so that its first `at` lights lie below the rest along the longest
/// axis of their centroids' box ([`select`], O(len) expected).
fn split(recs: &mut [Rec], at: usize) {
    if at == 0 || at >= recs.len() {
        return;
    }
    let coord = |r: &Rec, k: usize| f32::from_bits(r.get(k).copied().unwrap_or(0));
    let mut lo = [f32::INFINITY; 3];
    let mut hi = [f32::NEG_INFINITY; 3];
    for r in recs.iter() {
        for (k, (lo, hi)) in lo.iter_mut().zip(hi.iter_mut()).enumerate() {
            let c = coord(r, k);
            *lo = lo.min(c);
            *hi = hi.max(c);
        }
    }
    let ext = |k: usize| f64::from(hi[k]) - f64::from(lo[k]);
    let axis = if ext(0) >= ext(1) && ext(0) >= ext(2) {
        0
    } else if ext(1) >= ext(2) {
        1
    } else {
        2
    };
    select(recs, at, |r| (coord(&r, axis), r[3]));
}

/// Swaps `v[i]` and `v[j]` (nothing out of range: no panic path).
fn swap<T: Copy>(v: &mut [T], i: usize, j: usize) {
    if let (Some(&a), Some(&b)) = (v.get(i), v.get(j)) {
        if let Some(x) = v.get_mut(i) {
            *x = b;
        }
        if let Some(y) = v.get_mut(j) {
            *y = a;
        }
    }
}

/// Reorders `v` so that `v[k]` is the element a sort by `key` (pairs compared value first,
/// then index: a strict total order) would put there, with the smaller ones before it: quickselect with a median-of-three pivot and
/// Lomuto partitions, O(len) expected; after `2 log2(len) + 8` rounds the rest is
/// heap-sorted, so O(len log len) at worst. Our own (`select_nth_unstable` keeps panic paths
/// the no-panic wasm build cannot have).
fn select<T: Copy + Default>(v: &mut [T], k: usize, key: impl Fn(T) -> (f32, u32)) {
    let at = |v: &[T], i: usize| v.get(i).copied().unwrap_or_default();
    // By key, ties by index: a strict total order, so the groups do not depend on the
    // algorithm.
    let lt = |a: (f32, u32), b: (f32, u32)| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)).is_lt();
    let less = |a: T, b: T| lt(key(a), key(b));
    let (mut lo, mut hi) = (0, v.len());
    let mut budget = 2 * (usize::BITS - v.len().leading_zeros()) + 8;
    while hi - lo > 1 && (lo..hi).contains(&k) {
        if budget == 0 {
            heapsort(v.get_mut(lo..hi).unwrap_or(&mut []), &less);
            return;
        }
        budget -= 1;
        let (mid, last) = (lo + (hi - lo) / 2, hi - 1);
        // The median of v[lo], v[mid], v[last] into v[last].
        if less(at(v, mid), at(v, lo)) {
            swap(v, mid, lo);
        }
        if less(at(v, last), at(v, lo)) {
            swap(v, last, lo);
        }
        if less(at(v, mid), at(v, last)) {
            swap(v, mid, last);
        }
        let pivot = at(v, last);
        let pk = key(pivot);
        let mut store = lo;
        for i in lo..last {
            let x = at(v, i);
            if lt(key(x), pk) {
                swap(v, i, store);
                store += 1;
            }
        }
        swap(v, store, last);
        if k == store {
            return;
        }
        if k < store {
            hi = store;
        } else {
            lo = store + 1;
        }
    }
}

/// Sorts `v` by `less` in place (heapsort; no panic path).
fn heapsort<T: Copy + Default>(v: &mut [T], less: &impl Fn(T, T) -> bool) {
    let at = |v: &[T], i: usize| v.get(i).copied().unwrap_or_default();
    let sift = |v: &mut [T], mut root: usize, end: usize| loop {
        let mut child = 2 * root + 1;
        if child >= end {
            break;
        }
        if child + 1 < end && less(at(v, child), at(v, child + 1)) {
            child += 1;
        }
        if !less(at(v, root), at(v, child)) {
            break;
        }
        swap(v, root, child);
        root = child;
    };
    let n = v.len();
    for start in (0..n / 2).rev() {
        sift(v, start, n);
    }
    for end in (1..n).rev() {
        swap(v, 0, end);
        sift(v, 0, end);
    }
}

/// Writes every light's bit trail (2 bits per level: the child's slot in its quad).
fn trails(quads: &[[u32; QUAD_WORDS]], trails: &mut [u32], quad: u32, level: u32, bits: u32) {
    let Some(rec) = quads.get(quad as usize) else {
        return;
    };
    for slot in 0..4u32 {
        let info = rec
            .get(4 * (NODE_WORDS - 1) + slot as usize)
            .copied()
            .unwrap_or(0);
        let bits = bits | ((slot >> 1) | (slot & 1) << 1) << (2 * level);
        let target = info & INDEX_MASK;
        if info & LEAF != 0 {
            if let Some(t) = trails.get_mut(target as usize) {
                *t = bits;
            }
        } else if target != 0 && level < 15 {
            self::trails(quads, trails, target, level + 1, bits);
        }
    }
}

/// `LightTree::new`'s work: validate, build, encode, seal.
pub(super) fn build(
    n: usize,
    lights: impl Fn(usize) -> LightBounds,
    storage: &mut [u32],
) -> Result<(), Error> {
    if n == 0 {
        return Err(Error::Empty);
    }
    if n > MAX_LIGHTS {
        return Err(Error::TooLarge);
    }
    let needed = super::LightTree::storage_len(n);
    let got = storage.len();
    let storage = storage
        .get_mut(..needed)
        .ok_or(Error::StorageTooSmall { needed, got })?;
    for i in 0..n {
        check(i, &lights(i))?;
    }
    let (header, rest) = storage
        .split_at_mut_checked(HEADER_WORDS)
        .ok_or(Error::StorageTooSmall { needed, got })?;
    let (quads, trail) = rest
        .split_at_mut_checked(QUAD_WORDS * quads_bound(n))
        .ok_or(Error::StorageTooSmall { needed, got })?;
    // The permutation of the lights of positive power, in the trails' place.
    let mut m = 0;
    for i in 0..n {
        if lights(i).power > 0.0
            && let Some(t) = trail.get_mut(m)
        {
            *t = i as u32;
            m += 1;
        }
    }
    if m == 0 {
        return Err(Error::AllZero);
    }
    // The order of the lights in the tree, with the quads' words as scratch (4 words per
    // light of the 16 or more the quads have per light).
    let recs = quads.as_chunks_mut::<4>().0;
    let recs = recs.get_mut(..m).unwrap_or(&mut []);
    for (r, &i) in recs.iter_mut().zip(trail.iter()) {
        *r = rec(&lights(i as usize), i);
    }
    order(recs);
    for (t, r) in trail.iter_mut().zip(recs.iter()) {
        *t = r[3];
    }
    let quads = quads.as_chunks_mut::<QUAD_WORDS>().0;
    for q in quads.iter_mut() {
        *q = [0; QUAD_WORDS];
    }
    let mut b = Builder {
        quads,
        lights: &lights,
        next: 1,
    };
    b.quad(0, trail.get_mut(..m).unwrap_or(&mut []));
    trail.fill(0);
    trails(b.quads, trail, 0, 0, 0);
    header.fill(0);
    for (h, v) in header
        .iter_mut()
        .zip([TAG, VERSION, n as u32, m as u32, levels_for(m)])
    {
        *h = v;
    }
    to_storage_order(storage);
    seal(storage, CHECKSUM_WORD);
    Ok(())
}
