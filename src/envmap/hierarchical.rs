//! Hierarchical sampling: walk a MIP pyramid from the whole map down to one texel, splitting
//! the sample square at each level in proportion to the four children.
//!
//! The map is padded with zero weight to `2^a x 2^b` texels (`2^a >= width`, `2^b >= height`),
//! **centred**: `floor((2^a - width) / 2)` columns of padding before the map and the rest after
//! it (likewise rows), so the pyramid's split lines fall symmetrically about the map's centre
//! instead of wherever the power-of-two boundaries of a corner-padded map happen to cut it
//! (storage format version 2; version 1 padded in the corner). A fraction whose lower part is
//! all padding is exactly 0 and one whose upper part is all padding or missing exactly 1, so
//! no walk can enter the padding.
//!
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
//! fixed and narrow an interval around it on each axis, in 0.30 fixed point
//! (`key = floor(u * 2^30)`, exact for `u >= 2^-6`). The walk keeps, per axis, the interval's
//! length `len` and the key's offset `r` inside it: the lower child gets
//! `m = floor(len p)` units (one 32x32-bit multiply-high, fractions `p` being 0.31 fixed
//! point), the key goes low if `r < m` (then `len = m`), else high (`len -= m`, `r -= m`),
//! and after the last level `r / len` is the position inside the texel. The warp is piecewise
//! affine and local — compact strata of the square land on compact sets of texels, the point
//! of the method.
//!
//! Exactness: `p = 0` gives the lower child no units and `p = 1` (`2^31`) all of them, so a
//! zero-weight child gets an empty interval and is never chosen; a positive child's fraction
//! is kept strictly inside `(0, 1)`. A texel's preimage in the sample square is the rectangle
//! of its two final intervals, so its probability *is* `len_x len_y 2^-60`, which is what the
//! pdf reports — `pdf(uv)` repeats the walk, following the texel's bits
//! instead of comparing keys, and gets the same integers. Against the weights: fractions are
//! ratios of `f64` sums of `f32` node sums taken pairwise up the pyramid (relative error
//! about `2^-24` per level, whatever the dynamic range), rounded to `2^-32`, and each split
//! truncates by less than one unit, so a texel whose interval on an axis is `d` long (as a
//! fraction of the square) is within `1.25 levels 2^-30 / d` (relative) of its share on that
//! axis — the tests check exactly this bound against an `f64` model of the pyramid; measured
//! at most 1.0e-4 on the real maps for texels down to a sixteenth of the average. A texel so
//! faint that its interval would be shorter than one unit (probability below about `2^-30`
//! per axis) can be unreachable; its pdf then says 0, consistently. Node sums are `f32`,
//! rescaled by a power of two when the total would overflow (weights below `2^-149` of that
//! scale then count as 0), and compensated weights (computed in `f64`) by the power of two
//! that brings the largest into `[1, 2)` when it is below `f32`'s normal range, so a map of
//! subnormal weights keeps its compensated texels instead of rounding them all to 0.
//!
//! Layout: levels are stored in pairs, as 64-byte blocks aligned to cache lines — a node's
//! three fractions, its (up to) four children's three fractions each, and its sum (used
//! while building). A walk reads one block per two levels, so on a map too large for the
//! caches it waits for half as many dependent memory loads. (When the level count is odd, the
//! root block's first level is an empty one-child level.)
//!
//! Cost: one 64-byte block per two levels (`ceil(max(a, b) / 2)` blocks), a handful of
//! integer operations per level and one division per axis at the end.

use super::{
    Compensation, Compensator, Error, HEADER_WORDS, Sample, Word, carve, carve_ref, check_lens,
    check_size, check_sum, checked_len, clean, edges, from_storage_order, load4, read_header, seal,
    slices, tag, take, to_storage_order, u32_to_f32, write_header,
};
use crate::lanes::{Lane, UintLane, unit_interval};
use wide::f32x8;

/// Words per block: own fractions (3), four children's fractions (12), the block's sum (1).
const BLOCK: usize = 16;
/// Format tag of a hierarchical storage (header word 0).
const TAG: u32 = tag(*b"wcHI");

/// Hierarchical (MIP-pyramid) 2D distribution over a `width x height` weight map (see the
/// [module docs](super) for the guarantees and the bad-input rules).
///
/// Storage: the 16-word header, one 16-word block per node of every other level of the
/// padded pyramid (a sixteenth of the padded texel count at the finest block level, plus a
/// fifteenth of that above) and the texel edges: about 4.3 bytes
/// per padded texel, 34.1 MiB for 4096 x 2048. Padding to powers of two costs up to (just
/// under) 4 times that on unlucky sizes. See the [module docs](super) for the format, which
/// [`from_storage`](Self::from_storage) loads back.
///
/// Sampling ([`Distribution`](super::Distribution), or the same methods inherent): one node
/// read per pyramid level (`ceil(log2(max(width, height)))` levels) and one division per
/// axis; `sample_slice` interleaves six groups of eight lanes with AVX2 or AVX-512, two
/// elsewhere. A side that is not a power of two is padded with zero weight on both sides,
/// the map centred in its pyramid (`docs/envmaps.md` has the measurements).
#[derive(Clone, Copy, Debug)]
pub struct Hierarchical<'a> {
    /// The whole storage (`storage_len` words, header included), for [`Self::storage`].
    storage: &'a [Word],
    /// The blocks, block level by block level from the root, 64-byte aligned. Block `i`:
    /// `[px, py0, py1]` of its node, then `[px, py0, py1]` of child `c` at `3 + 3c`, then the
    /// node's `f32` sum. Fractions are 0.31 fixed point (`2^31` meaning 1). The children
    /// of node `i` of a level are nodes `i * branching + (bx | by << split_x)` of the next.
    blocks: &'a [u32],
    edges_x: &'a [[u32; 1]],
    edges_y: &'a [[u32; 1]],
    width: u32,
    height: u32,
    /// The padded map is `2^xbits x 2^ybits` texels.
    xbits: u32,
    ybits: u32,
    /// Where the map sits in the padded square: texel `(c, r)` is padded texel
    /// `(c + off[0], r + off[1])`, `off = floor((2^bits - size) / 2)` per axis (centred).
    off: [u32; 2],
    /// `width * height * 2^-60`: turns the product of the two final interval lengths into a
    /// density.
    pdf_scale: f32,
}

/// `ceil(log2 n)` for `n >= 1` (saturating at 64 for huge `n`, which `checked_len` rejects).
fn bits(n: u64) -> u32 {
    n.checked_next_power_of_two()
        .map_or(u64::BITS, |p| p.trailing_zeros())
}

/// The level structure of a `2^xbits x 2^ybits` pyramid, in *virtual* levels: the real levels
/// (0 = root; the finest `xbits` split x, the finest `ybits` split y) preceded by one empty
/// level when their count is odd, so that virtual levels pair up into blocks.
#[derive(Clone, Copy, Debug)]
struct Shape {
    xbits: u32,
    ybits: u32,
}

impl Shape {
    #[inline(always)]
    fn levels(self) -> u32 {
        self.xbits.max(self.ybits)
    }
    /// Virtual levels: the real ones rounded up to an even count.
    #[inline(always)]
    fn virtual_levels(self) -> u32 {
        (self.levels() + 1) & !1
    }
    /// Which axes virtual level `k` splits.
    #[inline(always)]
    fn splits(self, k: u32) -> (bool, bool) {
        let pad = self.virtual_levels() - self.levels();
        if k < pad {
            return (false, false);
        }
        let (level, levels) = (k - pad, self.levels());
        (level + self.xbits >= levels, level + self.ybits >= levels)
    }
    /// `log2` of the branching of virtual level `k`.
    #[inline(always)]
    fn branch_bits(self, k: u32) -> u32 {
        let (sx, sy) = self.splits(k);
        u32::from(sx) + u32::from(sy)
    }
    /// The bit of a texel coordinate that virtual level `k` decides (when it splits that
    /// axis): the splitting levels of an axis are the finest ones, so it is the distance to
    /// the finest level.
    #[inline(always)]
    fn shift(self, k: u32) -> u32 {
        self.virtual_levels() - 1 - k
    }
    /// Splits of each axis at virtual levels `k` and finer: a node of level `k` at
    /// coordinate `c` covers padded texels `[c << below, (c + 1) << below)` on that axis.
    fn below(self, k: u32) -> [u32; 2] {
        (k..self.virtual_levels()).fold([0, 0], |[x, y], l| {
            let (sx, sy) = self.splits(l);
            [x + u32::from(sx), y + u32::from(sy)]
        })
    }
    /// Nodes at virtual level `k`.
    fn nodes(self, k: u32) -> u64 {
        (0..k).fold(1u64, |n, l| n << self.branch_bits(l))
    }
    /// Blocks in all block levels (block level `b` holds the nodes of virtual level `2b`).
    fn block_count(self) -> u64 {
        (0..self.virtual_levels() / 2)
            .map(|b| self.nodes(2 * b))
            .sum()
    }
}

/// Where a `width x height` map sits in its `2^xbits x 2^ybits` padded square: centred,
/// `off = floor((2^bits - size) / 2)` texels of padding before it on each axis (and the rest
/// after it), so that the pyramid's split lines fall symmetrically about the map's centre
/// (measured: see `docs/envmaps.md`).
#[derive(Clone, Copy, Debug)]
struct Placement {
    off: [u64; 2],
    size: [u64; 2],
}

impl Placement {
    fn new(shape: Shape, width: usize, height: usize) -> Self {
        let size = [width as u64, height as u64];
        let padded = [shape.xbits, shape.ybits].map(|b| 1u64.checked_shl(b).unwrap_or(0));
        Placement {
            off: [0, 1].map(|a| padded[a].saturating_sub(size[a]) / 2),
            size,
        }
    }
    /// The offsets as `u32` (they are below `2^24`).
    fn offsets(self) -> [u32; 2] {
        self.off.map(|o| o as u32)
    }
    /// Is the node at `(x, y)` whose extent is `1 << below` padded texels per axis all
    /// padding (outside the map on some axis)?
    fn padding(self, below: [u32; 2], x: u32, y: u32) -> bool {
        [x, y].into_iter().enumerate().any(|(a, c)| {
            let start = u64::from(c) << below[a];
            let end = (u64::from(c) + 1) << below[a];
            end <= self.off[a] || start >= self.off[a] + self.size[a]
        })
    }
}

/// Fixed-point one of the fractions: `2^31`.
const FRACTION_ONE: u32 = 1 << 31;
/// Fixed-point one of the keys and intervals: `2^30`.
const KEY_ONE: u32 = 1 << 30;

/// `a / (a + b)` as a 0.31 fixed-point fraction: `2^31` (1) when the upper part is all
/// padding or missing (`b_pad`) or `b = 0` (also for an empty node, which is never reached),
/// `0` when the lower part is all padding (`a_pad`) or `a = 0 < b`, and strictly inside
/// `[1, 2^31 - 1]` when both are positive. The padding rules make the structural fractions
/// independent of the weights, which is what `from_storage_verified` checks.
fn fraction(a: f64, b: f64, a_pad: bool, b_pad: bool) -> u32 {
    if b_pad {
        return FRACTION_ONE;
    }
    if a_pad {
        return 0;
    }
    if b <= 0.0 {
        return FRACTION_ONE;
    }
    if a <= 0.0 {
        return 0;
    }
    let p = (a / (a + b) * f64::from(FRACTION_ONE) + 0.5) as u32;
    // Constant bounds: the clamp cannot panic.
    p.clamp(1, FRACTION_ONE - 1)
}

/// The fractions of a node with children sums `s[bx][by]`, and its sum; `pad[bx][by]` says
/// which children are all padding or missing.
fn node((s, pad): ([[f32; 2]; 2], [[bool; 2]; 2])) -> ([u32; 3], f32) {
    let c = s.map(|col| col.map(f64::from));
    let (left, right) = (c[0][0] + c[0][1], c[1][0] + c[1][1]);
    let column_pad = pad.map(|col| col[0] && col[1]);
    (
        [
            fraction(left, right, column_pad[0], column_pad[1]),
            fraction(c[0][0], c[0][1], pad[0][0], pad[0][1]),
            fraction(c[1][0], c[1][1], pad[1][0], pad[1][1]),
        ],
        (left + right) as f32,
    )
}

/// The lower child's share of an interval of `len <= 2^30` units at fraction `p` (0.31):
/// `floor(len p 2^-31)`, exactly `0` for `p = 0` and `len` for `p = 2^31`. (`2 len` fits 32
/// bits, so one multiply-high does it.)
#[inline(always)]
fn split<U: UintLane>(len: U, p: U) -> U {
    (len + len).mul_high(p)
}

/// Children sums `s[bx][by]` of a node and whether each is all padding, from
/// `child(bx, by)`; zero and padding where the level does not split that axis.
fn children(
    sx: bool,
    sy: bool,
    mut child: impl FnMut(u32, u32) -> (f32, bool),
) -> ([[f32; 2]; 2], [[bool; 2]; 2]) {
    let mut s = [[0.0f32; 2]; 2];
    let mut pad = [[true; 2]; 2];
    for (bx, (col, pcol)) in (0u32..).zip(s.iter_mut().zip(pad.iter_mut())) {
        for (by, (v, p)) in (0u32..).zip(col.iter_mut().zip(pcol.iter_mut())) {
            if (bx == 0 || sx) && (by == 0 || sy) {
                (*v, *p) = child(bx, by);
            }
        }
    }
    (s, pad)
}

/// Writes a node's fractions at `at` in `block`.
fn put(block: &mut [u32], at: usize, fractions: [u32; 3]) {
    if let Some(d) = block.get_mut(at..at + 3) {
        d.copy_from_slice(&fractions);
    }
}

slices::body!(Hierarchical, HIER);

impl<'a> Hierarchical<'a> {
    /// Words of storage `new` needs for a `width x height` map; `usize::MAX` when the map is
    /// too large ([`Error::TooLarge`]), `0` for a zero side.
    pub fn storage_len(width: usize, height: usize) -> usize {
        checked_len(width, height, |w, h| {
            let shape = Shape {
                xbits: bits(w),
                ybits: bits(h),
            };
            HEADER_WORDS as u64 + BLOCK as u64 * shape.block_count() + (w + 1) + (h + 1)
        })
    }

    /// Builds the distribution of `weights` (row-major, `width * height` values) in `storage`.
    ///
    /// Time `O(width * height)`: one pass to validate and total the weights, one over the
    /// finest block level, then the block levels above (a sixteenth as many). Errors:
    /// [`Error::ZeroSize`], [`Error::TooLarge`], [`Error::LengthMismatch`],
    /// [`Error::StorageTooSmall`], [`Error::InfiniteWeight`]; see the [module docs](super)
    /// for how other bad values are treated.
    pub fn new(
        weights: &[f32],
        width: usize,
        height: usize,
        storage: &'a mut [Word],
    ) -> Result<Self, Error> {
        Self::new_compensated(weights, width, height, Compensation::None, storage)
    }

    /// [`new`](Self::new) with MIS compensation: the tables (and so every pdf) are those of
    /// the compensated weights, `max(0, w - fraction * average)` (see [`Compensation`] for
    /// the lat-long form), falling back to the weights as given when compensation would
    /// remove them all. Two more passes over the weights (the average, then the largest
    /// compensated weight, which sets the pyramid's scale), and a third that stops at the
    /// first texel compensation keeps; `Compensation::None` is `new`. Errors: those of `new`.
    pub fn new_compensated(
        weights: &[f32],
        width: usize,
        height: usize,
        compensation: Compensation,
        storage: &'a mut [Word],
    ) -> Result<Self, Error> {
        let needed = Self::storage_len(width, height);
        check_size(weights, width, height, needed)?;
        let storage = take(storage, needed)?;
        let (w, h) = (width, height);
        let shape = Shape {
            xbits: bits(w as u64),
            ybits: bits(h as u64),
        };
        let blocks_len = usize::try_from(BLOCK as u64 * shape.block_count()).unwrap_or(0);
        // The blocks start right after the 64-byte header, whatever the buffer's address
        // (format version 3: the bytes are a function of the weights alone; version 2 moved
        // them to the next 64-byte boundary and recorded the shift, so the same map built at
        // two addresses gave different bytes). The padding region stays in the format, empty.
        let lens = regions(0, blocks_len, w, h);
        let [header, blocks, edges_x, edges_y] =
            carve(storage, [HEADER_WORDS, lens[1], lens[2], lens[3]]).ok_or(
                Error::StorageTooSmall {
                    needed,
                    got: needed,
                },
            )?;
        write_header(header, TAG, w, h, lens);

        let mut total = 0.0f64;
        for (index, &x) in weights.iter().enumerate() {
            if x == f32::INFINITY {
                return Err(Error::InfiniteWeight { index });
            }
            total += f64::from(clean(x));
        }
        let compensator = Compensator::new(weights, w, h, compensation)?;
        // All zero: uniform over the real texels. Otherwise scale so no f32 sum overflows
        // (compensated weights are smaller).
        let uniform = total <= 0.0;
        let exponent = ((total.to_bits() >> 52) & 0x7ff) as i32 - 1023;
        let scale = if exponent > 120 {
            f32::from_bits(((127 + 120 - exponent) as u32) << 23)
        } else {
            1.0
        };
        // Compensated weights are `f64` and go into the `f32` pyramid scaled by `cscale`:
        // `scale` as above, unless even the largest is below `f32`'s normal range (a map of
        // subnormal weights, or a fraction that leaves only a sliver above the average).
        // Rounded to `f32` as they are, such weights would lose precision or all round to 0
        // (every texel below `2^-150`), leaving an empty pyramid whose walk ends on a texel
        // of zero weight; so they are scaled by the power of two that brings the largest into
        // `[1, 2)`. Power-of-two scaling leaves every fraction as it is; maps whose largest
        // compensated weight is normal get exactly the tables they always had.
        let cscale = match compensator {
            Some(c) => {
                let top = c.max(weights, w);
                if top < f64::from(f32::MIN_POSITIVE) {
                    // `top` is a positive normal f64 in [2^-1022, 2^-126): 2^-exponent.
                    let e = ((top.to_bits() >> 52) & 0x7ff) as i64 - 1023;
                    f64::from_bits(((1023 - e) as u64) << 52)
                } else {
                    f64::from(scale)
                }
            }
            None => f64::from(scale),
        };
        let place = Placement::new(shape, w, h);
        let [ox, oy] = place.offsets();
        // Padded texel `(tx, ty)`: map texel `(tx - ox, ty - oy)`, or padding.
        let weight = |tx: u32, ty: u32| -> f32 {
            let (tx, ty) = (tx.wrapping_sub(ox), ty.wrapping_sub(oy));
            if tx as usize >= w || ty as usize >= h {
                return 0.0;
            }
            if uniform {
                return 1.0;
            }
            let x = clean(
                weights
                    .get(ty as usize * w + tx as usize)
                    .copied()
                    .unwrap_or(0.0),
            );
            match compensator {
                Some(c) => (c.apply(x, ty as usize) * cscale) as f32,
                None => x * scale,
            }
        };

        // Block offsets (in blocks) per block level.
        let block_levels = shape.virtual_levels() / 2;
        let mut offsets = [0usize; 14];
        let mut offset = 0usize;
        for (b, o) in (0..block_levels).zip(offsets.iter_mut()) {
            *o = offset;
            offset += shape.nodes(2 * b) as usize;
        }
        let (all, _) = blocks.as_chunks_mut::<BLOCK>();

        // Bottom-up. A block at virtual level k = 2b holds its node and the children at k + 1;
        // the grandchildren are texels (finest block level) or blocks of level b + 1.
        for b in (0..block_levels).rev() {
            let k = 2 * b;
            let (sx, sy) = shape.splits(k);
            let (csx, csy) = shape.splits(k + 1);
            let here = offsets.get(b as usize).copied().unwrap_or(0);
            let next = if b + 1 < block_levels {
                offsets.get(b as usize + 1).copied().unwrap_or(0)
            } else {
                all.len()
            };
            let (upper, lower) = all.split_at_mut(next.min(all.len()));
            let upper = upper.get_mut(here..).unwrap_or(&mut []);
            let finest = b + 1 == block_levels;
            let (below1, below2) = (shape.below(k + 1), shape.below(k + 2));
            for (i, block) in upper.iter_mut().enumerate() {
                // Slots of children the level does not have stay 0.
                block.fill(0);
                // Coordinates of this node: walk its index bits.
                let (x, y) = node_coords(shape, k, i as u32);
                let own = children(sx, sy, |bx, by| {
                    let c = bx | (by << u32::from(sx));
                    let cx = (x << u32::from(sx)) | bx;
                    let cy = (y << u32::from(sy)) | by;
                    let child_pad = place.padding(below1, cx, cy);
                    let grand = children(csx, csy, |lx, ly| {
                        let (gx, gy) = ((cx << u32::from(csx)) | lx, (cy << u32::from(csy)) | ly);
                        let pad = place.padding(below2, gx, gy);
                        if finest {
                            (weight(gx, gy), pad)
                        } else {
                            let j = (i << shape.branch_bits(k)) | c as usize;
                            let g = (j << shape.branch_bits(k + 1))
                                | (lx | (ly << u32::from(csx))) as usize;
                            let sum = lower
                                .get(g)
                                .map_or(0.0, |blk| f32::from_bits(blk[BLOCK - 1]));
                            (sum, pad)
                        }
                    });
                    let (fr, sum) = node(grand);
                    put(block, 3 + 3 * c as usize, fr);
                    (sum, child_pad)
                });
                let (fr, sum) = node(own);
                put(block, 0, fr);
                if let Some(last) = block.last_mut() {
                    *last = sum.to_bits();
                }
            }
        }
        edges::fill(edges_x, w as u32);
        edges::fill(edges_y, h as u32);
        to_storage_order(storage);
        seal(storage);
        Self::from_storage(storage)
    }

    /// Loads a storage that [`new`](Self::new) built (possibly in another process or on
    /// another machine: see the [module docs](super) for the format), without the weights.
    ///
    /// O(1): checks the header — format tag, version, sizes in `1..=MAX_SIDE`, region lengths
    /// that agree with the sizes (the padding region is empty), zero reserved words — and that
    /// `storage` holds `storage_len(width, height)` words (more are ignored). Errors:
    /// [`Error::WrongFormat`], [`Error::UnsupportedVersion`], [`Error::Corrupt`],
    /// [`Error::StorageTooSmall`]. The tables are not read: sampling is total whatever they
    /// hold (texels inside the map, `uv` in `[0, 1)^2`, finite pdfs), and bit-identical to the
    /// distribution `new` returned when they are what `new` wrote, at any alignment of
    /// `storage` (the blocks are on 64-byte cache lines when `storage` is 64-byte aligned).
    pub fn from_storage(storage: &'a [Word]) -> Result<Self, Error> {
        let (w, h, needed, lens) = read_header(storage, TAG, Self::storage_len)?;
        let shape = Shape {
            xbits: bits(w as u64),
            ybits: bits(h as u64),
        };
        let blocks_len = usize::try_from(BLOCK as u64 * shape.block_count()).unwrap_or(0);
        check_lens(lens, regions(0, blocks_len, w, h), needed, storage.len())?;
        let tables = storage.get(HEADER_WORDS..).unwrap_or(&[]);
        let [_, blocks, edges_x, edges_y] =
            carve_ref(tables, lens).ok_or(Error::StorageTooSmall {
                needed,
                got: storage.len(),
            })?;
        Ok(Hierarchical {
            storage: storage.get(..needed).unwrap_or(storage),
            blocks: blocks.as_flattened(),
            edges_x,
            edges_y,
            width: w as u32,
            height: h as u32,
            xbits: shape.xbits,
            ybits: shape.ybits,
            off: Placement::new(shape, w, h).offsets(),
            pdf_scale: (w as f64 * h as f64 / (1u64 << 60) as f64) as f32,
        })
    }

    /// [`from_storage`](Self::from_storage), then one pass over every table word: every split
    /// fraction is at most 1 (`2^31`), exactly 1 where a level does not split an axis or where
    /// the upper part is all padding (so the walk can never reach the padding), the block sums
    /// are finite and nonnegative, words `new` leaves unused are 0, and the texel edges are
    /// exactly the ones `new` writes ([`Error::Corrupt`] names the first word that is not);
    /// then the content checksum over every word ([`Error::Corrupt`] naming
    /// [`CHECKSUM_WORD`](super::CHECKSUM_WORD)), which catches every single-bit flip of the
    /// storage. Time `O(width * height)` (a sixteenth of a word per padded texel is read
    /// twice, every word once more for the checksum): 60 ms for 4096 x 2048
    /// (`benches/envmap.rs`, on a shared 2-core VM).
    pub fn from_storage_verified(storage: &'a [Word]) -> Result<Self, Error> {
        let map = Self::from_storage(storage)?;
        let start = HEADER_WORDS;
        if let Some(k) = map.first_bad_block_word() {
            return Err(Error::Corrupt { word: start + k });
        }
        let (w, h) = (map.width, map.height);
        let edges_at = start + map.blocks.len();
        if let Some(k) = edges::first_wrong(map.edges_x, w) {
            return Err(Error::Corrupt { word: edges_at + k });
        }
        if let Some(k) = edges::first_wrong(map.edges_y, h) {
            return Err(Error::Corrupt {
                word: edges_at + w as usize + 1 + k,
            });
        }
        check_sum(storage, map.storage.len())?;
        Ok(map)
    }

    /// The first block word (index into `blocks`) that `new` cannot have written, if any.
    fn first_bad_block_word(&self) -> Option<usize> {
        let shape = Shape {
            xbits: self.xbits,
            ybits: self.ybits,
        };
        let word = |k: usize| {
            self.blocks
                .get(k)
                .map_or(0, |&x| from_storage_order(core::num::Wrapping(x)).0)
        };
        let place = Placement::new(shape, self.width as usize, self.height as usize);
        // Checks the fractions at `at` of the node at `(x, y)` of virtual level `k`: at most 1,
        // exactly 1 where the upper part is missing (axis not split) or all padding, and
        // exactly 0 where only the lower part is all padding (what `fraction` writes).
        let node_ok = |at: usize, k: u32, x: u32, y: u32| -> Option<usize> {
            let (sx, sy) = shape.splits(k);
            let [px, py0, py1] = [0, 1, 2].map(|j| word(at + j));
            let one = FRACTION_ONE;
            let below = shape.below(k + 1);
            // Child (bx, by) all padding or missing?
            let pad = |bx: u32, by: u32| {
                (bx == 1 && !sx)
                    || (by == 1 && !sy)
                    || place.padding(below, (x << u32::from(sx)) | bx, (y << u32::from(sy)) | by)
            };
            let column = |bx: u32| pad(bx, 0) && pad(bx, 1);
            let expect = |p: u32, lower: bool, upper: bool| {
                p > one || (upper && p != one) || (!upper && lower && p != 0)
            };
            if expect(px, column(0), column(1)) {
                return Some(at);
            }
            if expect(py0, pad(0, 0), pad(0, 1)) {
                return Some(at + 1);
            }
            if expect(py1, pad(1, 0), pad(1, 1)) {
                return Some(at + 2);
            }
            None
        };
        let mut offset = 0usize;
        for b in 0..shape.virtual_levels() / 2 {
            let k = 2 * b;
            let (sx, sy) = shape.splits(k);
            let branching = 1usize << shape.branch_bits(k);
            for i in 0..shape.nodes(k) as usize {
                let at = (offset + i) * BLOCK;
                let (x, y) = node_coords(shape, k, i as u32);
                if let Some(bad) = node_ok(at, k, x, y) {
                    return Some(bad);
                }
                for c in 0..4usize {
                    let slot = at + 3 + 3 * c;
                    if c >= branching {
                        if let Some(j) = (0..3).find(|&j| word(slot + j) != 0) {
                            return Some(slot + j);
                        }
                        continue;
                    }
                    let (bx, by) = if sx {
                        (c as u32 & 1, (c as u32) >> 1)
                    } else {
                        (0, c as u32)
                    };
                    let cx = (x << u32::from(sx)) | bx;
                    let cy = (y << u32::from(sy)) | by;
                    if let Some(bad) = node_ok(slot, k + 1, cx, cy) {
                        return Some(bad);
                    }
                }
                let sum = f32::from_bits(word(at + BLOCK - 1));
                if !(sum >= 0.0 && sum.is_finite()) || sum.to_bits() >> 31 != 0 {
                    return Some(at + BLOCK - 1);
                }
            }
            offset += shape.nodes(k) as usize;
        }
        None
    }

    super::inherent_methods!();

    /// The storage words this map reads: exactly `storage_len(width, height)` words, header
    /// included, little-endian in memory — the bytes to write to a file while the map is in
    /// use (`bytemuck::cast_slice::<Word, u8>(map.storage())`), which
    /// [`from_storage_verified`](Self::from_storage_verified) loads back. The same weights
    /// give the same words, whatever buffer (and address) they were built in.
    ///
    /// ```
    /// use warpcore::envmap::{Hierarchical, Word};
    ///
    /// let mut buffer = vec![0 as Word; Hierarchical::storage_len(2, 2) + 5];
    /// let map = Hierarchical::new(&[1.0, 2.0, 3.0, 4.0], 2, 2, &mut buffer)?;
    /// let s = map.sample([0.25, 0.75]);
    /// let file: Vec<u8> = bytemuck::cast_slice(map.storage()).to_vec(); // save while sampling
    /// let words: Vec<Word> =
    ///     file.chunks_exact(4).map(|b| Word::from_ne_bytes(b.try_into().unwrap())).collect();
    /// assert_eq!(Hierarchical::from_storage_verified(&words)?.sample([0.25, 0.75]), s);
    /// # Ok::<(), warpcore::envmap::Error>(())
    /// ```
    #[inline]
    pub fn storage(&self) -> &'a [Word] {
        self.storage
    }

    /// Walks the pyramid from the root to a texel, starting with the keys `key` (the pdf
    /// lookup passes zeros). At each split, `left(shift, r, m, axis)` says (per lane) whether
    /// to take the lower child, given the key's offset `r` in the interval, the lower child's
    /// share `m` and the bit position `shift` of this level in the texel coordinates: the
    /// sampler compares `r < m`, the pdf lookup reads the bit of the texel it was given. Both
    /// therefore compute the same intervals.
    #[inline(always)]
    fn descend<U: UintLane>(
        &self,
        key: [U; 2],
        mut left: impl FnMut(u32, U, U, usize) -> U::Mask,
    ) -> Walk<U> {
        let shape = Shape {
            xbits: self.xbits,
            ybits: self.ybits,
        };
        let zero = U::splat(0);
        let mut walk = Walk {
            r: key,
            len: [U::splat(KEY_ONE); 2],
            texel: [zero; 2],
        };
        let mut index = zero;
        // Blocks before this block level, and blocks in it.
        let (mut offset, mut count) = (0u32, 1u32);
        for b in 0..shape.virtual_levels() / 2 {
            let k = 2 * b;
            let base = (U::splat(offset) + index).shl(4);
            let (b0, b1) = (shape.branch_bits(k), shape.branch_bits(k + 1));
            let (sx0, sx1) = (
                u32::from(shape.splits(k).0),
                u32::from(shape.splits(k + 1).0),
            );
            let (sy0, sy1) = (
                u32::from(shape.splits(k).1),
                u32::from(shape.splits(k + 1).1),
            );
            let [px, py0, py1, _] = load4(self.blocks, base);
            let c = walk.level(shape.shift(k), [sx0, sy0], [px, py0, py1], &mut left);
            // The fourth word is the next child's px (or the block's sum): unused.
            let [px, py0, py1, _] = load4(self.blocks, base + U::splat(3) + c + c + c);
            let g = walk.level(shape.shift(k + 1), [sx1, sy1], [px, py0, py1], &mut left);
            index = (index.shl(b0) | c).shl(b1) | g;
            offset += count;
            count <<= b0 + b1;
        }
        walk
    }

    /// The density of the texel a walk ended in: `len_x len_y 2^-60`, its exact probability,
    /// times `width * height`; 0 for an empty rectangle (a zero-weight texel).
    #[inline(always)]
    fn density<L: Lane>(&self, walk: &Walk<L::U>) -> L {
        let dx = u32_to_f32::<L>(walk.len[0]);
        let dy = u32_to_f32::<L>(walk.len[1]);
        dy * dx * L::splat(self.pdf_scale)
    }

    /// The 0.30 fixed-point keys of a sample, after the forward rule.
    #[inline(always)]
    fn keys<L: Lane>(u: [L; 2]) -> [L::U; 2] {
        let scale = L::splat(KEY_ONE as f32);
        u.map(|x| (unit_interval(x) * scale).to_uint())
    }

    /// The sample a finished walk describes.
    #[inline(always)]
    fn finish<L: Lane>(&self, walk: &Walk<L::U>) -> ([L; 2], L, [L::U; 2]) {
        // Padded coordinates to the map's (wrapping: a corrupt table could lead into the
        // padding before the map, which then clamps to the last texel).
        let texel = [
            clamp_below(walk.texel[0] - L::U::splat(self.off[0]), self.width),
            clamp_below(walk.texel[1] - L::U::splat(self.off[1]), self.height),
        ];
        let uv = [
            edges::point(
                self.edges_x,
                texel[0],
                offset::<L>(walk.r[0], walk.len[0]),
                self.width as f32,
            ),
            edges::point(
                self.edges_y,
                texel[1],
                offset::<L>(walk.r[1], walk.len[1]),
                self.height as f32,
            ),
        ];
        (uv, self.density(walk), texel)
    }

    #[inline(always)]
    fn sample_body<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]) {
        let walk = self.descend(Self::keys(u), |_, r: L::U, m, _| r.simd_lt(m));
        self.finish::<L>(&walk)
    }

    #[inline(always)]
    fn pdf_body<L: Lane>(&self, uv: [L; 2]) -> L {
        let texel = [
            edges::texel(self.edges_x, uv[0], self.width) + L::U::splat(self.off[0]),
            edges::texel(self.edges_y, uv[1], self.height) + L::U::splat(self.off[1]),
        ];
        let (zero, one) = (L::U::splat(0), L::U::splat(1));
        let walk = self.descend([zero; 2], |shift, _, _, axis| {
            let t = if axis == 0 { texel[0] } else { texel[1] };
            (t.shr(shift) & one).simd_eq(zero)
        });
        self.density(&walk)
    }
}

/// The key's offset `r` inside its final interval of `len` units: the position inside the
/// texel, in `[0, 1)`.
#[inline(always)]
fn offset<L: Lane>(r: L::U, len: L::U) -> L {
    unit_interval(u32_to_f32::<L>(r) / u32_to_f32::<L>(len))
}

/// `t` clamped to `n - 1`: real tables never lead into the padding, corrupt ones could, so
/// this (a no-op otherwise) keeps the texel in the map.
#[inline(always)]
fn clamp_below<U: UintLane>(t: U, n: u32) -> U {
    let last = U::splat(n.wrapping_sub(1));
    U::select(last.simd_lt(t), last, t)
}

/// Where a walk down the pyramid is, per axis: the interval length `len` and the key's
/// offset `r` in it (0.30 fixed point), and the texel coordinate decided so far.
struct Walk<U> {
    r: [U; 2],
    len: [U; 2],
    texel: [U; 2],
}

impl<U: UintLane> Walk<U> {
    /// One level: split x at `px`, then y at the chosen column's fraction. Branch-free and
    /// the same for every level: an axis the level does not split has fraction 1, so the walk
    /// goes "low" with an unchanged interval and appends a leading zero bit to the texel
    /// coordinate. Both candidate y shares are computed before the x decision, which keeps
    /// them off the dependency chain. Returns the child's local index `bx | by << sx`
    /// (`sx` = 1 if the level splits x).
    ///
    /// `[sx, sy]` (0 or 1) say whether the level splits each axis. A child bit on an axis the
    /// level does not split is forced to 0 (what real tables give anyway: fraction 1), so
    /// whatever a table holds, the walk stays on the tree — node indices in range, texel
    /// coordinates below `2^xbits` and `2^ybits`.
    #[inline(always)]
    fn level(
        &mut self,
        shift: u32,
        [sx, sy]: [u32; 2],
        [px, py0, py1]: [U; 3],
        left: &mut impl FnMut(u32, U, U, usize) -> U::Mask,
    ) -> U {
        let zero = U::splat(0);
        let (split_x, split_y) = (U::splat(sx), U::splat(sy));
        let my0 = split(self.len[1], py0);
        let my1 = split(self.len[1], py1);
        let mx = split(self.len[0], px);
        let go = left(shift, self.r[0], mx, 0);
        self.len[0] = U::select(go, mx, self.len[0] - mx);
        self.r[0] = U::select(go, self.r[0], self.r[0] - mx);
        let bx = U::select(go, zero, split_x);
        self.texel[0] = self.texel[0].shl(1) | bx;
        let my = U::select(go, my0, my1);
        let go = left(shift, self.r[1], my, 1);
        self.len[1] = U::select(go, my, self.len[1] - my);
        self.r[1] = U::select(go, self.r[1], self.r[1] - my);
        let by = U::select(go, zero, split_y);
        self.texel[1] = self.texel[1].shl(1) | by;
        bx | by.shl(sx)
    }
}

/// Lengths of the four regions after the header: padding (empty since format version 3),
/// blocks, column and row edges.
fn regions(skip: usize, blocks_len: usize, w: usize, h: usize) -> [usize; 4] {
    [skip, blocks_len, w + 1, h + 1]
}

/// Coordinates `(x, y)` of node `i` of virtual level `k`: node indices are paths from the
/// root, `bx | by << split_x` per level, most significant first.
fn node_coords(shape: Shape, k: u32, i: u32) -> (u32, u32) {
    let (mut x, mut y) = (0u32, 0u32);
    let mut rest = k;
    let mut index = i;
    // Peel the path from the finest level up.
    while rest > 0 {
        rest -= 1;
        let (sx, sy) = shape.splits(rest);
        let bits = shape.branch_bits(rest);
        let local = index & ((1 << bits) - 1);
        index >>= bits;
        let shift = k - 1 - rest;
        if sx {
            x |= (local & 1) << shift;
        }
        if sy {
            y |= ((local >> u32::from(sx)) & 1) << shift;
        }
    }
    (x, y)
}
