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
//! (a division per axis per level, and a rounded copy of `u` each time), we keep the sample
//! fixed and narrow an interval `[lo, hi)` around it on each axis, in the same 0.31 fixed
//! point as the marginal-conditional keys (`key = floor(u * 2^31)`, exact): the split point is
//! `lo + floor((hi - lo) p)` (one 32x32-bit multiply-high, fractions being 0.32 fixed point),
//! a comparison picks the child, and after the last level `(key - lo) / (hi - lo)` is the
//! position inside the texel. The warp is piecewise affine and local — compact strata of the
//! square land on compact sets of texels, the point of the method.
//!
//! Exactness: `p = 0` puts the split at `lo` and `p = 1` (stored as `u32::MAX`) at `hi`, so a
//! zero-weight child gets an empty interval and is never chosen; a positive child's fraction
//! is kept strictly inside `(0, 1)`. A texel's preimage in the sample square is the rectangle
//! of its two final intervals, so its probability *is* `(hi_x - lo_x)(hi_y - lo_y) 2^-62`,
//! which is what the pdf reports — `pdf(uv)` repeats the walk, following the texel's bits
//! instead of comparing keys, and gets the same integers. Against the weights: fractions are
//! ratios of `f64` sums of `f32` node sums taken pairwise up the pyramid (relative error
//! about `2^-24` per level, whatever the dynamic range), rounded to `2^-32`, and each split
//! point truncates by less than one unit, so a texel whose interval on an axis is `d` long is
//! within about `levels * 2^-31 / d` (relative) of its share on that axis: 1e-5 on the
//! real 512 x 256 maps, for texels down to a sixteenth of the average (measured). A texel so
//! faint that its interval would be shorter than one unit (probability below about `2^-31`
//! per axis) can be unreachable; its pdf then says 0, consistently. Node sums are `f32`,
//! rescaled by a power of two when the total would overflow (weights below `2^-149` of that
//! scale then count as 0).
//!
//! Cost: one 16-byte node read per level (`max(a, b)` levels), a handful of integer
//! operations per level and one division per axis at the end.

use super::{
    Error, Sample, SampleX8, Word, carve, check_size, checked_len, clean, edges, pdf_batch,
    sample_batch, scalar_sample, simd_sample, take,
};
use super::{fixed_key, u32_to_f32};
use crate::lanes::{Lane, UintLane, unit_interval};
use wide::f32x8;

/// Hierarchical (MIP-pyramid) 2D distribution over a `width x height` weight map (see the
/// [module docs](super) for the guarantees and the bad-input rules).
///
/// Storage: 4 words per internal node of the padded pyramid (a third as many nodes as padded
/// texels) plus the texel edges: `16/3` bytes per padded texel, 42.7 MiB for 4096 x 2048.
/// Padding to powers of two costs up to (just under) 4 times that on unlucky sizes.
#[derive(Clone, Copy, Debug)]
pub struct Hierarchical<'a> {
    /// `[px, py0, py1, sum]`, level by level from the root: 0.32 fixed-point fractions
    /// (`u32::MAX` meaning 1) and the node's `f32` sum (used while building). The children of
    /// node `i` of a level are nodes `i * branching + (bx | by << split_x)` of the next.
    nodes: &'a [[u32; 4]],
    edges_x: &'a [[u32; 1]],
    edges_y: &'a [[u32; 1]],
    width: u32,
    height: u32,
    /// The padded map is `2^xbits x 2^ybits` texels.
    xbits: u32,
    ybits: u32,
    /// `width * height * 2^-62`: turns the product of the two final interval lengths into a
    /// density.
    pdf_scale: f32,
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

/// `a / (a + b)` as a 0.32 fixed-point fraction: `u32::MAX` (meaning 1) when `b = 0` (also
/// for an empty node, which is never reached), `0` when `a = 0 < b`, and strictly inside
/// `[1, 2^32 - 2]` when both are positive.
fn fraction(a: f64, b: f64) -> u32 {
    if b <= 0.0 {
        return u32::MAX;
    }
    if a <= 0.0 {
        return 0;
    }
    let p = (a / (a + b) * 4_294_967_296.0 + 0.5) as u64;
    p.max(1).min(u64::from(u32::MAX) - 1) as u32
}

/// The node record of children sums `s[bx][by]`.
fn record(s: [[f32; 2]; 2]) -> [u32; 4] {
    let c = s.map(|col| col.map(f64::from));
    let (left, right) = (c[0][0] + c[0][1], c[1][0] + c[1][1]);
    [
        fraction(left, right),
        fraction(c[0][0], c[0][1]),
        fraction(c[1][0], c[1][1]),
        ((left + right) as f32).to_bits(),
    ]
}

/// Where the split at fraction `p` falls in `[lo, hi)`: `lo + floor((hi - lo) p 2^-32)`, which
/// is `lo` for `p = 0` and below `hi` otherwise; `p = u32::MAX` means 1 and gives `hi`.
#[inline(always)]
fn split_point<U: UintLane>(lo: U, hi: U, p: U) -> U {
    let t = lo + (hi - lo).mul_high(p);
    U::select(p.simd_eq(U::splat(u32::MAX)), hi, t)
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
            pdf_scale: (w as f64 * h as f64 / (1u64 << 62) as f64) as f32,
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

    /// Walks the pyramid from the root to a texel. At each split, `left(shift, t, axis)` says
    /// (per lane) whether to take the lower half, given the split point `t` and the bit
    /// position `shift` of this level in the texel coordinates: the sampler compares its key
    /// with `t`, the pdf lookup reads the bit of the texel it was given. Both therefore compute
    /// the same intervals.
    #[inline(always)]
    fn descend<U: UintLane>(&self, mut left: impl FnMut(u32, U, usize) -> U::Mask) -> Walk<U> {
        let (zero, one) = (U::splat(0), U::splat(1));
        let mut walk = Walk {
            lo: [zero; 2],
            hi: [U::splat(1 << 31); 2],
            texel: [zero; 2],
        };
        let mut index = zero;
        let levels = self.xbits.max(self.ybits);
        let (mut offset, mut count) = (0u32, 1u32);
        for level in 0..levels {
            let (sx, sy) = splits(level, self.xbits, self.ybits);
            let shift = levels - 1 - level;
            let [px, py0, py1, _] = U::gather(self.nodes, U::splat(offset) + index);
            let mut step = zero;
            let mut py = py0;
            if sx {
                let t = split_point(walk.lo[0], walk.hi[0], px);
                let go = left(shift, t, 0);
                walk.lo[0] = U::select(go, walk.lo[0], t);
                walk.hi[0] = U::select(go, t, walk.hi[0]);
                let bx = U::select(go, zero, one);
                walk.texel[0] = walk.texel[0].shl(1) | bx;
                step = bx;
                py = U::select(go, py0, py1);
            }
            if sy {
                let t = split_point(walk.lo[1], walk.hi[1], py);
                let go = left(shift, t, 1);
                walk.lo[1] = U::select(go, walk.lo[1], t);
                walk.hi[1] = U::select(go, t, walk.hi[1]);
                let by = U::select(go, zero, one);
                walk.texel[1] = walk.texel[1].shl(1) | by;
                step = step | by.shl(u32::from(sx));
            }
            index = index.shl(u32::from(sx) + u32::from(sy)) | step;
            offset += count;
            count <<= u32::from(sx) + u32::from(sy);
        }
        walk
    }

    /// The density of the texel a walk ended in: `(hi_x - lo_x)(hi_y - lo_y) 2^-62`, its exact
    /// probability, times `width * height`; 0 for an empty rectangle (a zero-weight texel).
    #[inline(always)]
    fn density<L: Lane>(&self, walk: &Walk<L::U>) -> L {
        let dx = u32_to_f32::<L>(walk.hi[0] - walk.lo[0]);
        let dy = u32_to_f32::<L>(walk.hi[1] - walk.lo[1]);
        dy * dx * L::splat(self.pdf_scale)
    }

    #[inline(always)]
    fn sample_body<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]) {
        let key = [fixed_key(u[0]), fixed_key(u[1])];
        let walk = self.descend(|_, t: L::U, axis| match axis {
            0 => key[0].simd_lt(t),
            _ => key[1].simd_lt(t),
        });
        // The key's offset inside its final interval is the position inside the texel.
        let f = |k: usize| {
            let (lo, hi) = (walk.lo[k], walk.hi[k]);
            unit_interval(u32_to_f32::<L>(key[k] - lo) / u32_to_f32::<L>(hi - lo))
        };
        let uv = [
            edges::point(self.edges_x, walk.texel[0], f(0), self.width as f32),
            edges::point(self.edges_y, walk.texel[1], f(1), self.height as f32),
        ];
        (uv, self.density(&walk), walk.texel)
    }

    #[inline(always)]
    fn pdf_body<L: Lane>(&self, uv: [L; 2]) -> L {
        let texel = [
            edges::texel(self.edges_x, uv[0], self.width),
            edges::texel(self.edges_y, uv[1], self.height),
        ];
        let (zero, one) = (L::U::splat(0), L::U::splat(1));
        let walk = self.descend(|shift, _: L::U, axis| {
            let t = if axis == 0 { texel[0] } else { texel[1] };
            (t.shr(shift) & one).simd_eq(zero)
        });
        self.density(&walk)
    }

    /// Draws a texel with probability proportional to its weight and a uniform point in it.
    ///
    /// Each coordinate is first mapped onto `[0, 1 - 2^-24]` by the forward rule. Cost: one
    /// node read per pyramid level (`ceil(log2(max(width, height)))` levels) and one division
    /// per axis. The pdf equals [`pdf`](Self::pdf)`(uv)` bit for bit.
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

/// Where a walk down the pyramid ended: the final interval of each axis (0.31 fixed point)
/// and the texel.
struct Walk<U> {
    lo: [U; 2],
    hi: [U; 2],
    texel: [U; 2],
}
