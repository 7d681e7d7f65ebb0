//! The alias table: probability proportional to a weight, O(1) per sample, in caller-owned
//! storage (Walker 1977, "An Efficient Method for Generating Discrete Random Variables with
//! General Distributions"; built by Vose 1991, "A Linear Algorithm for Generating Random
//! Numbers with a Given Distribution", in exact integer arithmetic).

use super::Error;
use crate::lanes::{Lane, UintLane, unit_interval};
use crate::storage::{checksum, from_storage_order, to_storage_order};
use core::num::Wrapping;
use wide::{f32x8, f32x16, u32x8, u32x16};

/// Words of the header at the start of every alias-table storage (included in
/// [`AliasTable::storage_len`]): tag, version, light count, checksum, four reserved zeros.
const HEADER_WORDS: usize = 8;
/// Words per light: threshold, alias, the column's probability, the alias's probability.
const RECORD_WORDS: usize = 4;
/// The header word holding the content checksum.
const CHECKSUM_WORD: usize = 3;
/// Word 0: the bytes `wcAL`.
const TAG: u32 = u32::from_le_bytes(*b"wcAL");
/// Word 1: the format version this build writes and reads.
const FORMAT_VERSION: u32 = 1;
/// Bits of `1.0f32`: a stored probability above it (or NaN, or negative) reads as 0.
const ONE_BITS: u32 = 0x3f80_0000;
/// One column's mass in the integer construction: a 0.32 fixed-point unit interval.
const COLUMN: u64 = 1 << 32;

/// Probability proportional to a weight (usually a light's power), O(1) per sample: Walker's
/// alias method, the table built by Vose's method in exact integer arithmetic, in
/// caller-owned `[u32]` storage (16 bytes per light plus a 32-byte header).
///
/// ```
/// use warpcore::lights::AliasTable;
///
/// let power = [1.0, 0.0, 3.0, 4.0];
/// let mut storage = vec![0u32; AliasTable::storage_len(power.len())];
/// let table = AliasTable::new(&power, &mut storage)?;
/// let (index, p) = table.sample(0.7);
/// assert_eq!(p, table.pmf(index)); // exactly: the MIS weight needs the same number
/// assert_ne!(index, 1); // a zero weight is never chosen
/// assert_eq!(table.pmf(3), 0.5);
/// # Ok::<(), warpcore::lights::Error>(())
/// ```
///
/// # The method
///
/// Column `i` of `n` holds light `i` and an alias `a_i`; a sample picks a column uniformly and
/// then light `i` with probability `t_i` or `a_i` otherwise. Vose's construction pairs each
/// light whose mass is below one column ("small") with one above ("large"), which gives the
/// small one's remainder to the large one, in O(n) time.
///
/// **Exact construction.** Each light's mass is an integer `m_i`, in units of `2^-32` of a
/// column: `m_i = floor(w_i * n * 2^32 / W)` (in `f64`, `W` the `f64` sum of the weights), at
/// least 1 for every positive weight (a faint light keeps a positive `pmf`), the
/// rounding difference given to the heaviest light so that the masses sum to `n * 2^32`
/// exactly. Vose's pairing then runs on integers: no rounding, so both worklists empty
/// together and every remaining column is exactly full (floating-point builds need a
/// tolerance there). The probability of light `i` is then **exactly** `m_i / (n 2^32)` for a
/// uniform real `u` and the ideal test (the fraction of `u n` past the column against the
/// threshold); [`pmf`](Self::pmf) returns that number rounded once to `f32` (relative error
/// at most `2^-24`), and [`sample`](Self::sample) returns the same stored `f32`, so the two
/// are equal bit for bit. The difference from `w_i / W` is below `2^-32 / n + 2^-32` absolute
/// (the floor, the minimum of 1, the heaviest light's correction).
///
/// **Zero weights are never chosen, by construction.** A zero weight has `m_i = 0`, so its
/// column's threshold is 0 (`frac < 0` never holds) and its column always goes to its alias;
/// and only a "large" light (mass at least one column, so positive) ever becomes an alias. No
/// rounding enters the pairing, so this holds for every input; the tests check it on
/// adversarial weight sets too.
///
/// # What it does to a stratified `u`
///
/// One `u` drives both choices: `u` becomes a 0.32 fixed-point key `k`; the column is the
/// high part of `k * n` (`floor(k n / 2^32)`) and the threshold test uses the low 32 bits
/// (the fraction of `u * n` left after the column). This keeps stratification as far as an
/// alias table can: `N` stratified values of `u` put `N / n` (±1) into every column, and
/// within a column the fraction is again stratified, so the split between the column's light
/// and its alias follows the threshold to within one sample. What no alias table keeps is
/// *locality*: neighbouring `u` go to unrelated lights (a column's alias is wherever Vose's
/// worklists put it), so a low-discrepancy `u` buys an even spread of counts, not a smooth
/// map; a CDF inversion keeps order but costs O(log n). The alternative — a second random
/// number for the threshold — would leave the column stratified but make each column's split
/// random; one `u` keeps both and frees a dimension.
///
/// **Resolution.** The test runs on a key, not on a real `u`: the key is even (`2 floor(u
/// 2^31)`), so within a column the fractions it produces are `2n` apart in units of `2^-32`
/// (`2^9 n` for `f32` values of `u` in `[1/2, 1)`, which have 24 bits: about `2^24 / n`
/// distinct values per column there, 16 at a million lights). The frequency of a light over
/// all keys (or all `f32` values of `u`) matches its `pmf` to about `2^-31` (`2^-24`) absolute,
/// the granularity of any inversion of a 24-bit `u` (pbrt-v4's alias table and a CDF
/// inversion have it too). A light whose share of its column is below that spacing can be
/// unreachable: a faint light (`pmf` below about `2^-24`, in a column other than the first)
/// keeps a positive `pmf` but may never be returned, so its contribution, at most its share
/// of the total weight, is lost.
///
/// # Input outside `[0, 1)`
///
/// `u` goes through the crate's forward rule: NaN, `-0.0`, negatives and `-inf` become 0;
/// `1.0`, larger values and `+inf` become `1 - 2^-24`. Any `f32` gives a valid light.
///
/// # Storage
///
/// | words | contents |
/// |---|---|
/// | 0 | format tag, the bytes `wcAL` |
/// | 1 | format version, 1 |
/// | 2 | `n`, the number of lights |
/// | 3 | content checksum of every other word (`from_storage_verified` checks it) |
/// | 4..8 | reserved, 0 |
/// | `8 + 4 i ..` | light `i`'s column: threshold (0.32 fixed point), alias index, `pmf(i)` and `pmf(alias)` as `f32` bits |
///
/// A column of full mass has alias `i` itself and threshold `u32::MAX`. The words are
/// little-endian in memory on every target (as the environment maps'), so the bytes are the
/// file format and a function of the weights alone. `from_storage` is O(1) (header only) and
/// **sampling any storage that passed it never panics and always returns an index below
/// `len()` with a probability in `[0, 1]`**; `from_storage_verified` also checks every
/// column's invariants and the checksum, which **rejects every single-bit flip** (see
/// [`envmap`](crate::envmap)'s storage section for why the checksum catches every one).
#[derive(Clone, Copy, Debug)]
pub struct AliasTable<'a> {
    /// The `storage_len(n)` words `new` wrote.
    storage: &'a [u32],
    /// The columns, `4 n` words (the storage after its header).
    records: &'a [u32],
    n: u32,
}

impl<'a> AliasTable<'a> {
    /// Largest number of lights a table holds: `2^26` (so the integer masses, at most
    /// `n * 2^32`, and their sums stay far inside `u64`, and every storage index inside `u32`).
    pub const MAX_LIGHTS: usize = 1 << 26;

    /// Words of storage for `n` lights: `8 + 4 n`; `usize::MAX` when `n > MAX_LIGHTS`.
    pub const fn storage_len(n: usize) -> usize {
        if n > Self::MAX_LIGHTS {
            usize::MAX
        } else {
            HEADER_WORDS + RECORD_WORDS * n
        }
    }

    /// Builds the table for `weights` (one per light, any finite value `>= 0`, subnormals
    /// and `f32::MAX` included) into `storage` (at least [`storage_len`](Self::storage_len)
    /// words, any contents; the rest is left untouched). O(n), no allocation: the storage is
    /// the build's scratch (integer masses and Vose's two worklists as linked lists through
    /// the columns).
    ///
    /// Errors: [`Error::Empty`] without weights, [`Error::TooLarge`] above `MAX_LIGHTS`,
    /// [`Error::StorageTooSmall`], [`Error::InvalidWeight`] for the first NaN, infinite or
    /// negative weight (`-0.0` is zero), [`Error::AllZero`] when every weight is zero.
    pub fn new(weights: &[f32], storage: &'a mut [u32]) -> Result<Self, Error> {
        let n = weights.len();
        if n == 0 {
            return Err(Error::Empty);
        }
        let needed = Self::storage_len(n);
        if needed == usize::MAX {
            return Err(Error::TooLarge);
        }
        let got = storage.len();
        let storage = storage
            .get_mut(..needed)
            .ok_or(Error::StorageTooSmall { needed, got })?;
        let mut total = 0.0f64;
        for (index, &w) in weights.iter().enumerate() {
            if !(w >= 0.0 && w.is_finite()) {
                return Err(Error::InvalidWeight { index });
            }
            total += f64::from(w);
        }
        if total == 0.0 {
            return Err(Error::AllZero);
        }
        let (header, records) = storage.split_at_mut(HEADER_WORDS);
        build(weights, total, records);
        header.fill(0);
        let words = [TAG, FORMAT_VERSION, n as u32];
        for (h, w) in header.iter_mut().zip(words) {
            *h = w;
        }
        to_storage_order(storage);
        let sum = checksum(storage, CHECKSUM_WORD);
        if let Some(w) = storage.get_mut(CHECKSUM_WORD) {
            *w = sum.to_le();
        }
        let storage: &'a [u32] = storage;
        Ok(Self::over(storage, n as u32))
    }

    /// Reads a storage `new` wrote (possibly saved and loaded since) in O(1): checks the
    /// tag ([`Error::WrongFormat`]), the version ([`Error::UnsupportedVersion`]), the light
    /// count and the reserved words ([`Error::Corrupt`]) and the length
    /// ([`Error::StorageTooSmall`]); not the columns. Sampling the result never panics and
    /// stays valid whatever the columns hold (see the type's docs).
    pub fn from_storage(storage: &'a [u32]) -> Result<Self, Error> {
        let got = storage.len();
        let word = |k: usize| storage.get(k).map_or(0, |&w| u32::from_le(w));
        if got < HEADER_WORDS {
            return Err(Error::StorageTooSmall {
                needed: HEADER_WORDS,
                got,
            });
        }
        if word(0) != TAG {
            return Err(Error::WrongFormat { found: word(0) });
        }
        if word(1) != FORMAT_VERSION {
            return Err(Error::UnsupportedVersion { found: word(1) });
        }
        let n = word(2) as usize;
        if n == 0 || n > Self::MAX_LIGHTS {
            return Err(Error::Corrupt { word: 2 });
        }
        if let Some(k) = (CHECKSUM_WORD + 1..HEADER_WORDS).find(|&k| word(k) != 0) {
            return Err(Error::Corrupt { word: k });
        }
        let needed = Self::storage_len(n);
        let storage = storage
            .get(..needed)
            .ok_or(Error::StorageTooSmall { needed, got })?;
        Ok(Self::over(storage, n as u32))
    }

    /// [`from_storage`](Self::from_storage), then one O(n) pass over every column: alias
    /// below `n`, probabilities finite in `[0, 1]`, each column's copy of its alias's
    /// probability equal to the alias's own, a positive probability for every alias and for
    /// every column with a positive threshold (so no zero-probability light is reachable), a
    /// full column aliased to itself; then the content checksum (word 3). Reports the first
    /// offending word as [`Error::Corrupt`]. Every single-bit flip of a valid storage is
    /// rejected.
    pub fn from_storage_verified(storage: &'a [u32]) -> Result<Self, Error> {
        let table = Self::from_storage(storage)?;
        let word = |k: usize| table.records.get(k).map_or(0, |&w| u32::from_le(w));
        let corrupt = |k: usize| -> Result<Self, Error> {
            Err(Error::Corrupt {
                word: HEADER_WORDS + k,
            })
        };
        let n = table.n;
        for i in 0..n as usize {
            let r = RECORD_WORDS * i;
            let [threshold, alias, own, of_alias] = [0, 1, 2, 3].map(|k| word(r + k));
            if alias >= n {
                return corrupt(r + 1);
            }
            if own > ONE_BITS || (threshold > 0 && own == 0) {
                return corrupt(r + 2);
            }
            if alias as usize == i && threshold != u32::MAX {
                return corrupt(r);
            }
            if of_alias == 0 || of_alias != word(RECORD_WORDS * alias as usize + 2) {
                return corrupt(r + 3);
            }
        }
        let needed = Self::storage_len(n as usize);
        let s = storage.get(..needed).unwrap_or(storage);
        let stored = s.get(CHECKSUM_WORD).map_or(0, |&w| u32::from_le(w));
        if checksum(s, CHECKSUM_WORD) != stored {
            return Err(Error::Corrupt {
                word: CHECKSUM_WORD,
            });
        }
        Ok(table)
    }

    fn over(storage: &'a [u32], n: u32) -> Self {
        Self {
            storage,
            records: storage.get(HEADER_WORDS..).unwrap_or(&[]),
            n,
        }
    }

    /// The number of lights.
    #[inline]
    pub fn len(&self) -> usize {
        self.n as usize
    }

    /// Always `false`: a table holds at least one light.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.n == 0
    }

    /// The storage the table reads (the `storage_len(len())` words `new` wrote): save these
    /// words (little-endian bytes on every target) and load them with
    /// [`from_storage_verified`](Self::from_storage_verified).
    #[inline]
    pub fn storage(&self) -> &'a [u32] {
        self.storage
    }

    /// Picks light `index` with probability `pmf(index)` (proportional to its weight) and
    /// returns `(index, pmf(index))`, the probability bit-identical to [`pmf`](Self::pmf).
    ///
    /// O(1): one 16-byte read. Column `floor(k n / 2^32)` of the 0.32 fixed-point key
    /// `k = 2 floor(u 2^31)`, its own light when the low 32 bits of `k n` are below the
    /// column's threshold, its alias otherwise (see the type's docs for stratification and
    /// resolution). `u` outside `[0, 1)` goes through the forward rule (NaN, negatives -> 0,
    /// `>= 1`, `+inf` -> `1 - 2^-24`). Never a light of zero weight; no floating-point
    /// arithmetic beyond `u * 2^31` (exact), so no error versus `f64`; a light of `pmf` below
    /// about `2^-24` may be unreachable ("Resolution" in the type's docs).
    #[inline]
    pub fn sample(&self, u: f32) -> (u32, f32) {
        let (i, p) = self.sample_body(u);
        (i.0, p)
    }

    /// [`sample`](Self::sample) on eight values at once; bit-identical to eight scalar calls.
    #[inline]
    pub fn sample_x8(&self, u: f32x8) -> (u32x8, f32x8) {
        self.sample_body(u)
    }

    /// [`sample`](Self::sample) on sixteen values at once; bit-identical to sixteen scalar
    /// calls.
    #[inline]
    pub fn sample_x16(&self, u: f32x16) -> (u32x16, f32x16) {
        self.sample_body(u)
    }

    /// [`sample`](Self::sample) over a batch: `(index[i], prob[i]) = sample(u[i])` for `i`
    /// below the shortest of the three lengths, which it returns. Bit-identical to the scalar
    /// form (groups of eight through [`sample_x8`](Self::sample_x8), the tail padded with 0).
    pub fn sample_slice(&self, u: &[f32], index: &mut [u32], prob: &mut [f32]) -> usize {
        let len = u.len().min(index.len()).min(prob.len());
        let (u, index, prob) = (
            u.get(..len).unwrap_or(&[]),
            index.get_mut(..len).unwrap_or(&mut []),
            prob.get_mut(..len).unwrap_or(&mut []),
        );
        let (uc, ut) = u.as_chunks::<8>();
        let (ic, it) = index.as_chunks_mut::<8>();
        let (pc, pt) = prob.as_chunks_mut::<8>();
        for ((u, i), p) in uc.iter().zip(ic).zip(pc) {
            let (si, sp) = self.sample_x8(f32x8::new(*u));
            *i = si.to_array();
            *p = sp.to_array();
        }
        let mut tail = [0.0f32; 8];
        for (t, &x) in tail.iter_mut().zip(ut) {
            *t = x;
        }
        let (si, sp) = self.sample_x8(f32x8::new(tail));
        for (o, x) in it.iter_mut().zip(si.to_array()) {
            *o = x;
        }
        for (o, x) in pt.iter_mut().zip(sp.to_array()) {
            *o = x;
        }
        len
    }

    /// The probability that [`sample`](Self::sample) returns `index`: `m_i / (n 2^32)` of the
    /// exact integer construction rounded once to `f32` (within `2^-32 (1 + 1/n)` absolute
    /// plus `2^-24` relative of `w_i / sum w`); 0 for a zero weight and for `index >= len()`.
    #[inline]
    pub fn pmf(&self, index: u32) -> f32 {
        if index >= self.n {
            return 0.0;
        }
        let at = (index as usize).wrapping_mul(RECORD_WORDS).wrapping_add(2);
        let bits = self.records.get(at).map_or(0, |&w| u32::from_le(w));
        f32::from_bits(clean(Wrapping(bits)).0)
    }

    #[inline(always)]
    fn sample_body<L: Lane>(&self, u: L) -> (L::U, L) {
        let u = unit_interval(u);
        // Exact: u <= 1 - 2^-24, so u 2^31 < 2^31 and the truncation is a floor.
        let key = (u * L::splat(2_147_483_648.0)).to_uint().shl(1);
        let n = L::U::splat(self.n);
        let column = key.mul_high(n);
        let frac = key * n;
        let [threshold, alias, own, of_alias] =
            L::U::gather4(self.records, column.shl(2)).map(from_storage_order);
        // Garbage storage (unverified) may hold any alias: keep the index in range.
        let alias = L::U::select(alias.simd_lt(n), alias, column);
        let stay = frac.simd_lt(threshold);
        let index = L::U::select(stay, column, alias);
        let bits = L::U::select(stay, clean(own), clean(of_alias));
        (index, L::from_bits(bits))
    }
}

/// A stored probability's bits, or 0 unless they are those of a number in `[0, 1]` (so
/// garbage storage never yields NaN, a negative or an infinite probability).
#[inline(always)]
fn clean<U: UintLane>(bits: U) -> U {
    U::select(bits.simd_lt(U::splat(ONE_BITS + 1)), bits, U::splat(0))
}

/// Vose's construction into `records` (`4 n` words, native order; the caller converts).
///
/// During the build a column's words hold its integer mass (words 0 and 1, low and high
/// half), its probability (word 2, final) and the next column of its worklist (word 3); each
/// finished column gets its threshold and alias in words 0 and 1, and a last pass copies each
/// alias's probability into word 3.
fn build(weights: &[f32], total: f64, records: &mut [u32]) {
    let n = weights.len();
    let target = n as u64 * COLUMN;
    let scale = target as f64 / total;
    let (columns, _) = records.as_chunks_mut::<4>();
    let mut sum = 0u64;
    let mut heaviest = 0usize;
    let mut heaviest_mass = 0u64;
    for (i, (c, &w)) in columns.iter_mut().zip(weights).enumerate() {
        // `as` saturates; the mass of one light never exceeds the target.
        let m = if w > 0.0 {
            ((f64::from(w) * scale) as u64).clamp(1, target)
        } else {
            0
        };
        if m > heaviest_mass {
            (heaviest, heaviest_mass) = (i, m);
        }
        sum += m;
        *c = [m as u32, (m >> 32) as u32, 0, 0];
    }
    // Give the rounding difference to the heaviest light (it holds at least one column's
    // mass, which dwarfs the difference of at most about n units).
    let fixed = (heaviest_mass + target).saturating_sub(sum).max(1);
    if let Some(c) = columns.get_mut(heaviest) {
        *c = [fixed as u32, (fixed >> 32) as u32, 0, 0];
    }
    const NONE: u32 = u32::MAX;
    let (mut small, mut large) = (NONE, NONE);
    let mass = |c: &[u32; 4]| u64::from(c[0]) | (u64::from(c[1]) << 32);
    for (i, c) in columns.iter_mut().enumerate() {
        let m = mass(c);
        c[2] = ((m as f64 / target as f64) as f32).to_bits();
        let list = if m < COLUMN { &mut small } else { &mut large };
        c[3] = *list;
        *list = i as u32;
    }
    while small != NONE && large != NONE {
        let s = small;
        let Some(cs) = columns.get_mut(s as usize) else {
            break;
        };
        small = cs[3];
        let ms = mass(cs);
        cs[0] = ms as u32;
        cs[1] = large;
        let Some(cl) = columns.get_mut(large as usize) else {
            break;
        };
        let ml = mass(cl) - (COLUMN - ms);
        cl[0] = ml as u32;
        cl[1] = (ml >> 32) as u32;
        if ml < COLUMN {
            let l = large;
            large = cl[3];
            cl[3] = small;
            small = l;
        }
    }
    // Exact arithmetic: whatever remains is exactly one column's mass (in the large list;
    // the small list is empty). Both are closed defensively as full columns.
    for head in [large, small] {
        let mut i = head;
        while let Some(c) = columns.get_mut(i as usize) {
            i = c[3];
            c[0] = u32::MAX;
            c[1] = NONE; // marked: alias to itself, fixed below
        }
    }
    for i in 0..columns.len() {
        let alias = columns.get(i).map_or(0, |c| c[1]);
        let alias = if alias == NONE { i as u32 } else { alias };
        let of_alias = columns.get(alias as usize).map_or(0, |c| c[2]);
        if let Some(c) = columns.get_mut(i) {
            c[1] = alias;
            c[3] = of_alias;
        }
    }
}
