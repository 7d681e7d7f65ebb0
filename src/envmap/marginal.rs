//! Marginal-conditional sampling: pick a row by its total, then a column within the row.
//!
//! The CDFs are 0.31 fixed point: every row's conditional CDF and the row (marginal) CDF
//! partition `[0, 2^31)` exactly into one interval per texel, of length proportional to its
//! weight. The sample's coordinates become 31-bit keys `floor(u * 2^31)` (exact), a
//! branch-free binary search finds the interval holding each key, and the key's offset inside
//! it gives the position inside the texel. Integer intervals make the three classic traps
//! impossible by construction: a zero-weight texel has an empty interval, so no key finds it;
//! the last interval ends at exactly `2^31`, above every key, so `u` near 1 cannot run past
//! the row; and the pdf is the product of the two interval lengths the search returned.
//!
//! Quantization: interval ends are `round(prefix / total * 2^31)`, with the prefix sums in
//! `f64`, so each interval is within one unit (`2^-31 = 4.7e-10`) of its exact share: the
//! conditional probability `p` of a texel (and of a row) has relative error at most
//! `4.7e-10 / p` (`1e-6` for `p >= 4.7e-4`). The ends are clamped so that every positive
//! texel keeps at least one unit: a positive weight never rounds to probability 0, it is
//! oversampled instead (this moves the other ends by at most one unit per such texel). The
//! pdf is computed from the quantized intervals, so it always reports what is sampled.
//!
//! Learned from pbrt-v4's `PiecewiseConstant1D/2D` and Mitsuba 3's `DiscreteDistribution2D`
//! (which use `f32` CDFs, binary searches and a continuous offset); the fixed-point
//! construction is ours, because `f32` CDFs misreport pdfs by more than 1% at a dynamic range
//! of `50,000 : 1` (the sum of the small texels is lost in the rounding of the large).

use super::{
    Compensation, Compensator, Error, HEADER_WORDS, Word, carve, carve_ref, check_lens, check_size,
    check_sum, checked_len, clean, edges, fixed_key, from_storage_order, load, read_header, seal,
    tag, take, to_storage_order, u32_to_f32, write_header,
};
use super::{Sample, slices};
use crate::lanes::{Lane, UintLane, unit_interval};
use wide::f32x8;

/// Fixed-point scale of the CDFs: `2^31` (so `2^31` itself, the end of every CDF, fits a `u32`).
const ONE: u64 = 1 << 31;

/// Format tag of a marginal-conditional storage (header word 0).
const TAG: u32 = tag(*b"wcMC");

/// Lengths of the four regions after the header: row CDF, row CDFs, column and row edges.
fn regions(w: usize, h: usize) -> [usize; 4] {
    [h + 1, (w + 1) * h, w + 1, h + 1]
}

/// Marginal-conditional 2D distribution over a `width x height` weight map (see the
/// [module docs](super) for the guarantees and the bad-input rules).
///
/// Storage: `16 + (width + 1) * height + (height + 1) + (width + 1) + (height + 1)` words —
/// the header, the per-row CDFs, the row CDF and the exact texel edges of both axes (4 bytes
/// per texel plus a little: 32.0 MiB for 4096 x 2048). See the [module docs](super) for the
/// format, which [`from_storage`](Self::from_storage) loads back.
///
/// Sampling ([`Distribution`](super::Distribution), or the same methods inherent): `u[1]`
/// picks the row, `u[0]` the column, by two binary searches of `log2(height)` and
/// `log2(width)` steps; `sample_slice` interleaves four groups of eight lanes with AVX2 or
/// AVX-512, two elsewhere.
#[derive(Clone, Copy, Debug)]
pub struct MarginalConditional<'a> {
    /// The whole storage (`storage_len` words, header included), for [`Self::storage`].
    storage: &'a [Word],
    /// Row CDF: `height + 1` starts, `0` first and `2^31` last.
    rows: &'a [[u32; 1]],
    /// Row `r`'s CDF at `r * (width + 1)`: `width + 1` starts, `0` first and `2^31` last.
    columns: &'a [[u32; 1]],
    edges_x: &'a [[u32; 1]],
    edges_y: &'a [[u32; 1]],
    width: u32,
    height: u32,
    /// `width * height * 2^-62`: turns the product of two interval lengths into a density.
    pdf_scale: f32,
}

slices::body!(MarginalConditional, MC);

impl<'a> MarginalConditional<'a> {
    /// Words of storage `new` needs for a `width x height` map; `usize::MAX` when the map is
    /// too large ([`Error::TooLarge`]), `0` for a zero side.
    pub fn storage_len(width: usize, height: usize) -> usize {
        checked_len(width, height, |w, h| {
            HEADER_WORDS as u64 + (w + 1) * h + 2 * (h + 1) + (w + 1)
        })
    }

    /// Builds the distribution of `weights` (row-major, `width * height` values) in `storage`.
    ///
    /// Time `O(width * height)`, two passes over each row. Errors: [`Error::ZeroSize`],
    /// [`Error::TooLarge`], [`Error::LengthMismatch`], [`Error::StorageTooSmall`],
    /// [`Error::InfiniteWeight`]; see the [module docs](super) for how other bad values
    /// are treated.
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
    /// remove them all. One more pass over the weights (two for `MarginalConditional`'s
    /// check); `Compensation::None` is `new`. Errors: those of `new`.
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
        let lens = regions(w, h);
        let [header, rows, columns, edges_x, edges_y] =
            carve(storage, [HEADER_WORDS, lens[0], lens[1], lens[2], lens[3]]).ok_or(
                Error::StorageTooSmall {
                    needed,
                    got: needed,
                },
            )?;
        write_header(header, TAG, w, h, lens);
        let compensator = Compensator::new(weights, w, h, compensation)?;
        let weigh = |x: f32, r: usize| match compensator {
            Some(c) => c.apply(clean(x), r),
            None => f64::from(clean(x)),
        };

        // Pass over each row: its f64 sum and positive count, then its CDF. The row sums wait
        // in `rows[r + 1]` (low word) and `edges_y[r]` (high word) until the row CDF is built.
        let mut total = 0.0f64;
        let mut positive_rows = 0u32;
        let mut index = 0usize;
        for (r, (((row, cdf), lo), hi)) in weights
            .chunks_exact(w.max(1))
            .zip(columns.chunks_exact_mut(w.max(1) + 1))
            .zip(rows.iter_mut().skip(1))
            .zip(edges_y.iter_mut())
            .enumerate()
        {
            let (mut sum, mut positive) = (0.0f64, 0u32);
            for &x in row {
                if x == f32::INFINITY {
                    return Err(Error::InfiniteWeight { index });
                }
                index += 1;
                let x = weigh(x, r);
                sum += x;
                positive += u32::from(x > 0.0);
            }
            if positive > 0 {
                fill_cdf(cdf, row.iter().map(|&x| weigh(x, r)), sum, positive);
            } else {
                // Never chosen (its row interval is empty), but keep a valid CDF.
                fill_cdf(cdf, row.iter().map(|_| 1.0), w as f64, w as u32);
            }
            let bits = sum.to_bits();
            *lo = bits as u32;
            *hi = (bits >> 32) as u32;
            total += sum;
            positive_rows += u32::from(positive > 0);
        }
        if positive_rows == 0 {
            // All zero: uniform (every row CDF above is already uniform).
            fill_cdf(rows, (0..h).map(|_| 1.0), h as f64, h as u32);
        } else {
            // In place: step r reads row r's sum from `rows[r + 1]`, then overwrites it.
            let mut q = Quantizer::new(total, positive_rows);
            if let Some(first) = rows.first_mut() {
                *first = 0;
            }
            for (end, &hi) in rows.iter_mut().skip(1).zip(edges_y.iter()) {
                let sum = f64::from_bits(u64::from(*end) | (u64::from(hi) << 32));
                *end = q.next(sum);
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
    /// that agree with the sizes — and that `storage` holds `storage_len(width, height)` words
    /// (more are ignored). Errors: [`Error::WrongFormat`], [`Error::UnsupportedVersion`],
    /// [`Error::Corrupt`], [`Error::StorageTooSmall`]. The tables are not read: sampling is
    /// total whatever they hold (texels inside the map, `uv` in `[0, 1)^2`, finite pdfs), and
    /// bit-identical to the distribution `new` returned when they are what `new` wrote.
    pub fn from_storage(storage: &'a [Word]) -> Result<Self, Error> {
        let (w, h, needed, lens) = read_header(storage, TAG, Self::storage_len)?;
        check_lens(lens, regions(w, h), needed, storage.len())?;
        let tables = storage.get(HEADER_WORDS..).unwrap_or(&[]);
        let [rows, columns, edges_x, edges_y] =
            carve_ref(tables, regions(w, h)).ok_or(Error::StorageTooSmall {
                needed,
                got: storage.len(),
            })?;
        Ok(MarginalConditional {
            storage: storage.get(..needed).unwrap_or(storage),
            rows,
            columns,
            edges_x,
            edges_y,
            width: w as u32,
            height: h as u32,
            pdf_scale: (w as f64 * h as f64 / (ONE as f64 * ONE as f64)) as f32,
        })
    }

    /// [`from_storage`](Self::from_storage), then one pass over every table word: each CDF
    /// (the row CDF and every row's) starts at 0, never decreases and ends at `2^31`, and the
    /// texel edges are exactly the ones `new` writes ([`Error::Corrupt`] names the first word
    /// that is not); then the content checksum over every word ([`Error::Corrupt`] naming
    /// [`CHECKSUM_WORD`](super::CHECKSUM_WORD)), which catches every single-bit flip of the
    /// storage. Time `O(width * height)`: 11 ms for 4096 x 2048 (`benches/envmap.rs`, on a
    /// shared 2-core VM).
    pub fn from_storage_verified(storage: &'a [Word]) -> Result<Self, Error> {
        let map = Self::from_storage(storage)?;
        let (w, h) = (map.width as usize, map.height as usize);
        let lens = regions(w, h);
        let start = [0, 1, 2, 3].map(|k| HEADER_WORDS + lens.iter().take(k).sum::<usize>());
        let corrupt = |word: usize| Err(Error::Corrupt { word });
        if let Some(k) = first_bad_cdf(map.rows) {
            return corrupt(start[0] + k);
        }
        for (r, cdf) in map.columns.chunks_exact((w + 1).max(1)).enumerate() {
            if let Some(k) = first_bad_cdf(cdf) {
                return corrupt(start[1] + r * (w + 1) + k);
            }
        }
        if let Some(k) = edges::first_wrong(map.edges_x, w as u32) {
            return corrupt(start[2] + k);
        }
        if let Some(k) = edges::first_wrong(map.edges_y, h as u32) {
            return corrupt(start[3] + k);
        }
        check_sum(storage, map.storage.len())?;
        Ok(map)
    }

    super::inherent_methods!();

    /// The storage words this map reads: exactly `storage_len(width, height)` words, header
    /// included, little-endian in memory — the bytes to write to a file while the map is in
    /// use (`bytemuck::cast_slice::<Word, u8>(map.storage())`), which
    /// [`from_storage_verified`](Self::from_storage_verified) loads back. The same weights
    /// give the same words, whatever buffer (and address) they were built in.
    ///
    /// ```
    /// use warpcore::envmap::{MarginalConditional, Word};
    ///
    /// let mut buffer = vec![0 as Word; MarginalConditional::storage_len(2, 2) + 5];
    /// let map = MarginalConditional::new(&[1.0, 2.0, 3.0, 4.0], 2, 2, &mut buffer)?;
    /// let s = map.sample([0.25, 0.75]);
    /// let file: Vec<u8> = bytemuck::cast_slice(map.storage()).to_vec(); // save while sampling
    /// let words: Vec<Word> =
    ///     file.chunks_exact(4).map(|b| Word::from_ne_bytes(b.try_into().unwrap())).collect();
    /// assert_eq!(MarginalConditional::from_storage_verified(&words)?.sample([0.25, 0.75]), s);
    /// # Ok::<(), warpcore::envmap::Error>(())
    /// ```
    #[inline]
    pub fn storage(&self) -> &'a [Word] {
        self.storage
    }

    #[inline(always)]
    fn sample_body<L: Lane>(&self, u: [L; 2]) -> ([L; 2], L, [L::U; 2]) {
        let one = L::U::splat(1);
        let (key_x, key_y) = (fixed_key(u[0]), fixed_key(u[1]));
        let row = search(self.rows, L::U::splat(0), self.height, key_y);
        let r0 = load(self.rows, row);
        let r1 = load(self.rows, row + one);
        let base = row * L::U::splat(self.width + 1);
        let column = search(self.columns, base, self.width, key_x);
        let c0 = load(self.columns, base + column);
        let c1 = load(self.columns, base + column + one);
        let (len_y, len_x) = (r1 - r0, c1 - c0);
        // The key's offset inside its interval is the position inside the texel.
        let fy = unit_interval(u32_to_f32::<L>(key_y - r0) / u32_to_f32::<L>(len_y));
        let fx = unit_interval(u32_to_f32::<L>(key_x - c0) / u32_to_f32::<L>(len_x));
        let uv = [
            edges::point(self.edges_x, column, fx, self.width as f32),
            edges::point(self.edges_y, row, fy, self.height as f32),
        ];
        (uv, self.density(len_x, len_y), [column, row])
    }

    /// `P(texel) * width * height` from the two interval lengths.
    #[inline(always)]
    fn density<L: Lane>(&self, len_x: L::U, len_y: L::U) -> L {
        u32_to_f32::<L>(len_y) * u32_to_f32::<L>(len_x) * L::splat(self.pdf_scale)
    }

    #[inline(always)]
    fn pdf_body<L: Lane>(&self, uv: [L; 2]) -> L {
        let one = L::U::splat(1);
        let column = edges::texel(self.edges_x, uv[0], self.width);
        let row = edges::texel(self.edges_y, uv[1], self.height);
        let r0 = load(self.rows, row);
        let r1 = load(self.rows, row + one);
        let base = row * L::U::splat(self.width + 1);
        let c0 = load(self.columns, base + column);
        let c1 = load(self.columns, base + column + one);
        self.density(c1 - c0, r1 - r0)
    }
}

/// Index of the first word of a CDF (in storage byte order) that breaks "starts at 0, never
/// decreases, ends at `2^31`", if any.
fn first_bad_cdf(cdf: &[[u32; 1]]) -> Option<usize> {
    let value = |k: usize| {
        cdf.get(k)
            .map_or(0, |&[w]| from_storage_order(core::num::Wrapping(w)).0)
    };
    let last = cdf.len().checked_sub(1)?;
    if value(0) != 0 {
        return Some(0);
    }
    if let Some(k) = (1..=last).find(|&k| value(k) < value(k - 1)) {
        return Some(k);
    }
    (u64::from(value(last)) != ONE).then_some(last)
}

/// The largest `k < n` with `table[base + k] <= key`, given `table[base] = 0 <= key`:
/// a binary search with a fixed number of steps (`ceil(log2 n)`), the same for every lane.
/// (For any table contents the result is in `0..n`.)
#[inline(always)]
pub(super) fn search<U: UintLane>(table: &[[u32; 1]], base: U, n: u32, key: U) -> U {
    let mut lo = U::splat(0);
    let mut len = n;
    while len > 1 {
        let half = len / 2;
        let mid = lo + U::splat(half);
        let v = load(table, base + mid);
        lo = U::select(key.simd_lt(v), lo, mid);
        len -= half;
    }
    lo
}

/// Turns nonnegative weights into interval ends in 0.31 fixed point (see the module docs).
struct Quantizer {
    acc: f64,
    total: f64,
    prev: u64,
    /// Positive weights still to come.
    remaining: u64,
}

impl Quantizer {
    fn new(total: f64, positive: u32) -> Self {
        Quantizer {
            acc: 0.0,
            total,
            prev: 0,
            remaining: u64::from(positive),
        }
    }

    /// The end of the next interval. `round(prefix / total * 2^31)`, clamped so this texel
    /// (if positive) gets at least one unit and every positive texel after it can too. The
    /// prefix is summed in the same order as `total`, so the last positive texel ends at
    /// exactly `2^31`.
    fn next(&mut self, w: f64) -> u32 {
        if w > 0.0 {
            self.acc += w;
            self.remaining = self.remaining.saturating_sub(1);
            let ideal = (self.acc / self.total * ONE as f64 + 0.5) as u64;
            let hi = ONE.saturating_sub(self.remaining);
            self.prev = ideal.min(hi).max(self.prev + 1);
        }
        self.prev as u32
    }
}

/// Fills a CDF of `n + 1` starts (`0` first, `2^31` last) from `n` weights whose sum, taken in
/// this order, is `total`, `positive` of them positive.
fn fill_cdf(out: &mut [u32], weights: impl Iterator<Item = f64>, total: f64, positive: u32) {
    let mut q = Quantizer::new(total, positive);
    let mut out = out.iter_mut();
    if let Some(first) = out.next() {
        *first = 0;
    }
    for (o, w) in out.zip(weights) {
        *o = q.next(w);
    }
}
