//! Hierarchical sampling: walk a MIP pyramid from the whole map down to one texel, splitting
//! the sample square at each level in proportion to the four children.
//!
//! The map is padded with zero weight to `2^a x 2^b` texels (`2^a >= width`, `2^b >= height`).
//! Level `L - 1` groups texels 2x2, each level above groups the one below 2x2, and on a
//! non-square map the top `|a - b|` levels split the longer axis only (2x1 or 1x2), exactly
//! the MIP chain of a non-square image read from the top. Every internal node stores three
//! split fractions, computed at build time from its children's sums:
//!
//! * `px`: the left column's share of the node, `(s00 + s01) / (s00 + s01 + s10 + s11)`;
//! * `py0`, `py1`: the lower row's share within the left and the right column.
//!
//! Sampling is the warp of McCool and Harwood (1997) and Clarberg et al. (2005) as in
//! Mitsuba 3's `Hierarchical2D`: the current sample rectangle splits vertically at `px`, then
//! the chosen half splits horizontally at its `py`. Instead of rescaling `u` at every level
//! (one division per axis per level, and a rounded copy of `u` each time), we keep the
//! sample fixed and narrow an interval `[lo, hi)` around it on each axis: the split point is
//! `lo + (hi - lo) p`, a comparison picks the child, and after the last level
//! `(u - lo) / (hi - lo)` is the position inside the texel. The warp is piecewise affine and
//! local — compact strata of the square land on compact sets of texels, the point of the
//! method. Exactness rules: `p = 0` puts the split at `lo` and `p = 1` at `hi` (so a
//! zero-weight child gets an empty interval and is never chosen), and a positive child's
//! fraction is kept strictly inside `(0, 1)`.
//!
//! The pdf is the product of the fractions along the texel's path (times `width * height`),
//! so it reports the quantized distribution that is actually sampled; against the weights
//! it is exact to `f32` rounding: every fraction is a ratio of two sums taken pairwise up the
//! pyramid, relative error at most about `2 log2(texels) * 2^-24` whatever the dynamic range.
//! Sums are `f32`, rescaled by a power of two when the total would overflow (weights below
//! `2^-149` of that scale then count as 0).
//!
//! Cost: one 16-byte node read per level (`max(a, b)` levels), a handful of `f32` operations
//! and no division until the last step.

use super::{
    Error, Sample, SampleX8, Word, carve, check_size, checked_len, clean, edges, pdf_batch,
    sample_batch, scalar_sample, simd_sample, take,
};
use crate::lanes::{Lane, UintLane, unit_interval};
use wide::f32x8;

/// Hierarchical (MIP-pyramid) 2D distribution over a `width x height` weight map (see the
/// [module docs](super) for the guarantees and the bad-input rules).
///
/// Storage: 4 words per internal node of the padded pyramid (about `4/3` of the padded texel
/// count) plus the texel edges: `(4/3) * 4` bytes per padded texel, 42.7 MiB for
/// 4096 x 2048, and for non-power-of-two maps up to 4 times that of the unpadded map.
#[derive(Clone, Copy, Debug)]
pub struct Hierarchical<'a> {
    /// `[px, py0, py1, sum]` as `f32` bits, level by level from the root; the children of node
    /// `i` of a level are nodes `i * branching + (bx | by << split_x)` of the next.
    nodes: &'a [[u32; 4]],
    edges_x: &'a [[u32; 1]],
    edges_y: &'a [[u32; 1]],
    width: u32,
    height: u32,
    /// The padded map is `2^xbits x 2^ybits` texels.
    xbits: u32,
    ybits: u32,
    /// `width * height`: the density of the whole map before any split.
    area_scale: f32,
}

/// `ceil(log2 n)` for `n >= 1` (saturating at 64 for huge `n`, which `checked_len` rejects).
fn bits(n: u64) -> u32 {
    n.checked_next_power_of_two()
        .map_or(u64::BITS, |p| p.trailing_zeros())
}

/// Which axes level `level` (0 = root) splits, for a `2^xbits x 2^ybits` pyramid: the finest
/// `xbits` levels split x, the finest `ybits` split y.
#[inline(always)]
fn splits(level: u32, xbits: u32, ybits: u32) -> (bool, bool) {
    let levels = xbits.max(ybits);
    (level + xbits >= levels, level + ybits >= levels)
}

/// Internal nodes of the pyramid.
fn node_count(xbits: u32, ybits: u32) -> u64 {
    let (mut total, mut count) = (0u64, 1u64);
    for level in 0..xbits.max(ybits) {
        let (sx, sy) = splits(level, xbits, ybits);
        total += count;
        count <<= u32::from(sx) + u32::from(sy);
    }
    total
}

/// Position of node `(x, y)` of level `level` within its level: the path from the root, one
/// or two bits per level (x bit low), most significant first.
fn node_index(level: u32, x: u32, y: u32, xbits: u32, ybits: u32) -> u32 {
    let mut index = 0u32;
    for l in 0..level {
        let (sx, sy) = splits(l, xbits, ybits);
        let shift = level - 1 - l;
        let bx = if sx { (x >> shift) & 1 } else { 0 };
        let by = if sy { (y >> shift) & 1 } else { 0 };
        index = (index << (u32::from(sx) + u32::from(sy))) | bx | (by << u32::from(sx));
    }
    index
}

/// `a / (a + b)` as an `f32` fraction, kept strictly inside `(0, 1)` when both are positive,
/// `0` when `a = 0 < b`, and `1` when `b = 0` (also for an empty node, which is never reached).
fn fraction(a: f64, b: f64) -> f32 {
    let s = a + b;
    if s <= 0.0 {
        return 1.0;
    }
    let p = (a / s) as f32;
    if a > 0.0 && p <= 0.0 {
        f32::from_bits(1)
    } else if b > 0.0 && p >= 1.0 {
        1.0 - 1.0 / 16_777_216.0
    } else {
        p
    }
}

/// The node record of children sums `s[bx][by]`.
fn record(s: [[f32; 2]; 2]) -> [u32; 4] {
    let c = s.map(|col| col.map(f64::from));
    let (left, right) = (c[0][0] + c[0][1], c[1][0] + c[1][1]);
    [
        fraction(left, right).to_bits(),
        fraction(c[0][0], c[0][1]).to_bits(),
        fraction(c[1][0], c[1][1]).to_bits(),
        ((left + right) as f32).to_bits(),
    ]
}

/// Where the split at fraction `p` falls in `[lo, hi)`: exactly `lo` for `p = 0`, exactly `hi`
/// for `p = 1`, never outside.
#[inline(always)]
fn split_point<L: Lane>(lo: L, hi: L, p: L) -> L {
    let t = lo + (hi - lo) * p;
    let t = L::select(hi.simd_lt(t), hi, t);
    L::select(p.simd_eq(L::splat(1.0)), hi, t)
}

impl<'a> Hierarchical<'a> {
    /// Words of storage `new` needs for a `width x height` map; `usize::MAX` when the map is
    /// too large ([`Error::TooLarge`]), `0` for a zero side.
    pub fn storage_len(width: usize, height: usize) -> usize {
        checked_len(width, height, |w, h| {
            4 * node_count(bits(w), bits(h)) + (w + 1) + (h + 1)
        })
    }

    /// Builds the distribution of `weights` (row-major, `width * height` values) in `storage`.
    ///
    /// Time `O(width * height)`: one pass to validate and total the weights, one over the
    /// finest level of the pyramid, then the levels above (a third as many nodes). Errors:
    /// [`Error::ZeroSize`], [`Error::TooLarge`], [`Error::LengthMismatch`],
    /// [`Error::StorageTooSmall`], [`Error::InfiniteWeight`]; see the [module docs](super)
    /// for how other bad values are treated.
    pub fn new(
        weights: &[f32],
        width: usize,
        height: usize,
        storage: &'a mut [Word],
    ) -> Result<Self, Error> {
        let needed = Self::storage_len(width, height);
        check_size(weights, width, height, needed)?;
        let storage = take(storage, needed)?;
        let (w, h) = (width, height);
        let (xbits, ybits) = (bits(w as u64), bits(h as u64));
        let levels = xbits.max(ybits);
        let nodes_len = usize::try_from(4 * node_count(xbits, ybits)).unwrap_or(usize::MAX);
        let [nodes, edges_x, edges_y] =
            carve(storage, [nodes_len, w + 1, h + 1]).ok_or(Error::StorageTooSmall {
                needed,
                got: needed,
            })?;
        let (nodes, _) = nodes.as_chunks_mut::<4>();

        let mut total = 0.0f64;
        for (index, &x) in weights.iter().enumerate() {
            if x == f32::INFINITY {
                return Err(Error::InfiniteWeight { index });
            }
            total += f64::from(clean(x));
        }
        // All zero: uniform over the real texels. Otherwise scale so no f32 sum overflows.
        let uniform = total <= 0.0;
        let exponent = ((total.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        let scale = if exponent > 120 {
            f32::from_bits(((127 + 120 - exponent) as u32) << 23)
        } else {
            1.0
        };
        let weight = |tx: u32, ty: u32| -> f32 {
            if tx as usize >= w || ty as usize >= h {
                return 0.0;
            }
            if uniform {
                return 1.0;
            }
            let x = weights.get(ty as usize * w + tx as usize).copied();
            clean(x.unwrap_or(0.0)) * scale
        };

        // Level offsets (in nodes) and sizes.
        let mut offsets = [0u32; 26];
        let mut count = 1u32;
        let mut offset = 0u32;
        for level in 0..levels {
            if let Some(o) = offsets.get_mut(level as usize) {
                *o = offset;
            }
            let (sx, sy) = splits(level, xbits, ybits);
            offset += count;
            count <<= u32::from(sx) + u32::from(sy);
        }

        if levels > 0 {
            // The finest level: children are texels. Walk it row by row (reads stay
            // sequential), writing each record at its path index.
            let bottom = levels - 1;
            let (sx, sy) = splits(bottom, xbits, ybits);
            let base = offsets.get(bottom as usize).copied().unwrap_or(0);
            let (cols, rows) = (
                1u32 << (xbits - u32::from(sx)),
                1u32 << (ybits - u32::from(sy)),
            );
            for y in 0..rows {
                for x in 0..cols {
                    let child = |bx: u32, by: u32| -> f32 {
                        if (bx == 1 && !sx) || (by == 1 && !sy) {
                            return 0.0;
                        }
                        let tx = (x << u32::from(sx)) | bx;
                        let ty = (y << u32::from(sy)) | by;
                        weight(tx, ty)
                    };
                    let s = [[child(0, 0), child(0, 1)], [child(1, 0), child(1, 1)]];
                    let i = base + node_index(bottom, x, y, xbits, ybits);
                    if let Some(n) = nodes.get_mut(i as usize) {
                        *n = record(s);
                    }
                }
            }
            // The levels above, from their children's sums.
            for level in (0..bottom).rev() {
                let (sx, sy) = splits(level, xbits, ybits);
                let here = offsets.get(level as usize).copied().unwrap_or(0) as usize;
                let next = offsets.get(level as usize + 1).copied().unwrap_or(0) as usize;
                let (upper, lower) = nodes.split_at_mut(next.min(nodes.len()));
                let shift = u32::from(sx) + u32::from(sy);
                let upper = upper.get_mut(here..).unwrap_or(&mut []);
                for (i, n) in upper.iter_mut().enumerate() {
                    let child = |bx: usize, by: usize| -> f32 {
                        if (bx == 1 && !sx) || (by == 1 && !sy) {
                            return 0.0;
                        }
                        let c = (i << shift) | bx | (by << usize::from(sx));
                        lower.get(c).map_or(0.0, |r| f32::from_bits(r[3]))
                    };
                    *n = record([[child(0, 0), child(0, 1)], [child(1, 0), child(1, 1)]]);
                }
            }
        }
        edges::fill(edges_x, w as u32);
        edges::fill(edges_y, h as u32);

        let nodes: &'a [[u32; 4]] = nodes;
        let (edges_x, _) = edges_x.as_chunks::<1>();
        let (edges_y, _) = edges_y.as_chunks::<1>();
        Ok(Hierarchical {
            nodes,
            edges_x,
            edges_y,
            width: w as u32,
            height: h as u32,
            xbits,
            ybits,
            area_scale: (w as f64 * h as f64) as f32,
        })
    }

    /// Width of the map in texels.
    #[inline]
    pub fn width(&self) -> usize {
        self.width as usize
    }

    /// Height of the map in texels.
    #[inline]
    pub fn height(&self) -> usize {
        self.height as usize
    }

    #[inline(always)]
    fn sample_body<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]) {
        let (zero, one) = (L::splat(0.0), L::splat(1.0));
        let (uzero, uone) = (L::U::splat(0), L::U::splat(1));
        let (ux, uy) = (unit_interval(u[0]), unit_interval(u[1]));
        let (mut lox, mut hix, mut loy, mut hiy) = (zero, one, zero, one);
        let (mut column, mut row, mut index) = (uzero, uzero, uzero);
        let mut density = L::splat(self.area_scale);
        let levels = self.xbits.max(self.ybits);
        let (mut offset, mut count) = (0u32, 1u32);
        for level in 0..levels {
            let (sx, sy) = splits(level, self.xbits, self.ybits);
            let node = L::U::gather(self.nodes, L::U::splat(offset) + index);
            let [px, py0, py1, _] = node.map(L::from_bits);
            let mut step = uzero;
            let mut py = py0;
            if sx {
                let t = split_point(lox, hix, px);
                let left = ux.simd_lt(t);
                lox = L::select(left, lox, t);
                hix = L::select(left, t, hix);
                density = density * L::select(left, px, one - px);
                let bx = L::U::select(left, uzero, uone);
                column = column.shl(1) | bx;
                step = bx;
                py = L::select(left, py0, py1);
            }
            if sy {
                let t = split_point(loy, hiy, py);
                let low = uy.simd_lt(t);
                loy = L::select(low, loy, t);
                hiy = L::select(low, t, hiy);
                density = density * L::select(low, py, one - py);
                let by = L::U::select(low, uzero, uone);
                row = row.shl(1) | by;
                step = step | by.shl(u32::from(sx));
            }
            index = index.shl(u32::from(sx) + u32::from(sy)) | step;
            offset += count;
            count <<= u32::from(sx) + u32::from(sy);
        }
        // The sample's position inside the final interval is its position inside the texel.
        let fx = unit_interval((ux - lox) / (hix - lox));
        let fy = unit_interval((uy - loy) / (hiy - loy));
        let uv = [
            edges::point(self.edges_x, column, fx, self.width as f32),
            edges::point(self.edges_y, row, fy, self.height as f32),
        ];
        (uv, floor_density(density), [column, row])
    }

    #[inline(always)]
    fn pdf_body<L: Lane>(&self, uv: [L; 2]) -> L {
        let one = L::splat(1.0);
        let (uzero, uone) = (L::U::splat(0), L::U::splat(1));
        let column = edges::texel(self.edges_x, uv[0], self.width);
        let row = edges::texel(self.edges_y, uv[1], self.height);
        let mut index = uzero;
        let mut density = L::splat(self.area_scale);
        let mut empty = L::splat(0.0).simd_lt(L::splat(0.0));
        let levels = self.xbits.max(self.ybits);
        let (mut offset, mut count) = (0u32, 1u32);
        for level in 0..levels {
            let (sx, sy) = splits(level, self.xbits, self.ybits);
            let node = L::U::gather(self.nodes, L::U::splat(offset) + index);
            let [px, py0, py1, _] = node.map(L::from_bits);
            let shift = levels - 1 - level;
            let mut step = uzero;
            let mut py = py0;
            if sx {
                let bx = column.shr(shift) & uone;
                let left = bx.simd_eq(uzero);
                let p = L::select(left, px, one - px);
                density = density * p;
                empty = empty | p.simd_le(L::splat(0.0));
                step = bx;
                py = L::select(left, py0, py1);
            }
            if sy {
                let by = row.shr(shift) & uone;
                let low = by.simd_eq(uzero);
                let p = L::select(low, py, one - py);
                density = density * p;
                empty = empty | p.simd_le(L::splat(0.0));
                step = step | by.shl(u32::from(sx));
            }
            index = index.shl(u32::from(sx) + u32::from(sy)) | step;
            offset += count;
            count <<= u32::from(sx) + u32::from(sy);
        }
        L::select(empty, L::splat(0.0), floor_density(density))
    }

    /// Draws a texel with probability proportional to its weight and a uniform point in it.
    ///
    /// Each coordinate is first mapped onto `[0, 1 - 2^-24]` by the forward rule. Cost: one
    /// node read per pyramid level (`ceil(log2(max(width, height)))` levels) and one division
    /// per axis. The pdf equals [`pdf`](Self::pdf)`(uv)` bit for bit. A texel so unlikely that
    /// its density underflows `f32` reports `f32::MIN_POSITIVE` rather than 0.
    #[inline]
    pub fn sample(&self, u: [f32; 2]) -> Sample {
        scalar_sample(self.sample_body(u))
    }

    /// [`sample`](Self::sample) on eight points at once; bit-identical to eight scalar calls.
    #[inline]
    pub fn sample_x8(&self, u: [f32x8; 2]) -> SampleX8 {
        simd_sample(self.sample_body(u))
    }

    /// [`sample`](Self::sample) over a batch: `out[i] = sample(u[i])` for
    /// `i < min(u.len(), out.len())`; returns that count. Bit-identical to the scalar form.
    #[inline]
    pub fn sample_slice(&self, u: &[[f32; 2]], out: &mut [Sample]) -> usize {
        sample_batch(u, out, |v| self.sample_x8(v))
    }

    /// Density at `uv` with respect to area on `[0, 1]^2`: `P(texel) * width * height` for
    /// the texel holding `uv` (0 on zero-weight texels). `uv` is clamped by the forward rule.
    #[inline]
    pub fn pdf(&self, uv: [f32; 2]) -> f32 {
        self.pdf_body(uv)
    }

    /// [`pdf`](Self::pdf) on eight points at once; bit-identical to eight scalar calls.
    #[inline]
    pub fn pdf_x8(&self, uv: [f32x8; 2]) -> f32x8 {
        self.pdf_body(uv)
    }

    /// [`pdf`](Self::pdf) over a batch, with the length rule of
    /// [`sample_slice`](Self::sample_slice).
    #[inline]
    pub fn pdf_slice(&self, uv: &[[f32; 2]], out: &mut [f32]) -> usize {
        pdf_batch(uv, out, |v| self.pdf_x8(v))
    }
}

/// A reachable texel's density, never below `f32::MIN_POSITIVE` (an underflowed product).
#[inline(always)]
fn floor_density<L: Lane>(d: L) -> L {
    let min = L::splat(f32::MIN_POSITIVE);
    L::select(d.simd_lt(min), min, d)
}
