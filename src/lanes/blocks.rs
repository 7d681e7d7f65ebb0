//! Whole 64-byte records per lane: [`UintLane::gather16`] for the SIMD lane types.
//!
//! A lane reads its 16 consecutive words with plain loads (one bounds check per lane), and a
//! transpose turns the rows into one vector per word: a four-stage butterfly of two-source
//! permutes on `u32x16` (64 permutes, `vpermt2d`/`vpunpck`/`vshufi32x4` with AVX-512), two
//! 8 x 8 transposes on `u32x8`. Integer moves only, so every width reads the same bits.

use wide::{ShuffleExt, u32x8, u32x16};

/// Read in place of an out-of-bounds row.
static ZEROS: [u32; 16] = [0; 16];

/// Row `idx` of `table`, zeros when out of bounds: a choice of address, then one load (no
/// copy through the stack, no branch around the load).
#[inline(always)]
fn row(table: &[[u32; 16]], idx: u32) -> &[u32; 16] {
    table.get(idx as usize).unwrap_or(&ZEROS)
}

/// The permute indices of the 16 x 16 butterfly: `PLAN[s][p]` combines the two vectors of
/// pair `p` of stage `s` (see [`transpose16`]); entries `0..16` pick a lane of the first
/// vector, `16..32` of the second.
const PLAN: [[[u32; 16]; 2]; 4] = plan();

const fn plan() -> [[[u32; 16]; 2]; 4] {
    let mut p = [[[0u32; 16]; 2]; 4];
    let mut l = 0;
    while l < 16 {
        let (chunk, m) = ((l / 4) as u32, (l % 4) as u32);
        // Stage 0: interleave 32-bit words inside each 128-bit chunk (unpacklo/hi epi32).
        p[0][0][l] = 4 * chunk + m / 2 + 16 * (m % 2);
        p[0][1][l] = 4 * chunk + 2 + m / 2 + 16 * (m % 2);
        // Stage 1: interleave 64-bit pairs inside each chunk (unpacklo/hi epi64).
        p[1][0][l] = 4 * chunk + m % 2 + 16 * (m / 2);
        p[1][1][l] = 4 * chunk + 2 + m % 2 + 16 * (m / 2);
        // Stage 2: interleave 128-bit chunks: [a.0, b.0, a.1, b.1] and [a.2, b.2, a.3, b.3].
        p[2][0][l] = 4 * (chunk / 2) + m + 16 * (chunk % 2);
        p[2][1][l] = 4 * (2 + chunk / 2) + m + 16 * (chunk % 2);
        // Stage 3: [a.0, a.1, b.0, b.1] and [a.2, a.3, b.2, b.3].
        p[3][0][l] = 4 * (chunk % 2) + m + 16 * (chunk / 2);
        p[3][1][l] = 4 * (2 + chunk % 2) + m + 16 * (chunk / 2);
        l += 1;
    }
    p
}

/// Two-source permute by `PLAN[S][W]` (a constant index vector).
#[inline(always)]
fn mix<const S: usize, const W: usize>(a: u32x16, b: u32x16) -> u32x16 {
    [a, b].shuffle(u32x16::new(const { PLAN[S][W] }))
}

/// `out[k]` lane `j` = `rows[j]` lane `k`.
///
/// Stages 0 and 1 leave word `4c + m` of rows `4i..4i+4` in chunk `c` of vector `4i + m`;
/// stages 2 and 3 gather chunk `c` of vectors `m, 4 + m, 8 + m, 12 + m` into vector `4c + m`.
#[inline(always)]
pub(super) fn transpose16(rows: [u32x16; 16]) -> [u32x16; 16] {
    let mut a = rows;
    for i in 0..4 {
        let [r0, r1, r2, r3] = [0, 1, 2, 3].map(|k| rows[4 * i + k]);
        // Words 4c, 4c + 1 and 4c + 2, 4c + 3 of row pairs (0, 1) and (2, 3).
        let (p0, p1) = (mix::<0, 0>(r0, r1), mix::<0, 1>(r0, r1));
        let (q0, q1) = (mix::<0, 0>(r2, r3), mix::<0, 1>(r2, r3));
        a[4 * i] = mix::<1, 0>(p0, q0);
        a[4 * i + 1] = mix::<1, 1>(p0, q0);
        a[4 * i + 2] = mix::<1, 0>(p1, q1);
        a[4 * i + 3] = mix::<1, 1>(p1, q1);
    }
    let mut b = a;
    for m in 0..4 {
        for base in [0, 8] {
            let (x, y) = (a[base + m], a[base + 4 + m]);
            b[base + m] = mix::<2, 0>(x, y);
            b[base + 4 + m] = mix::<2, 1>(x, y);
        }
    }
    let mut out = b;
    for m in 0..4 {
        let (lo_x, lo_y) = (b[m], b[8 + m]);
        let (hi_x, hi_y) = (b[4 + m], b[12 + m]);
        out[m] = mix::<3, 0>(lo_x, lo_y);
        out[4 + m] = mix::<3, 1>(lo_x, lo_y);
        out[8 + m] = mix::<3, 0>(hi_x, hi_y);
        out[12 + m] = mix::<3, 1>(hi_x, hi_y);
    }
    out
}

/// [`UintLane::gather16`](super::UintLane::gather16) for `u32x16`.
#[inline(always)]
pub(super) fn gather16_x16(table: &[[u32; 16]], idx: u32x16) -> [u32x16; 16] {
    let idx = idx.to_array();
    let mut rows = [u32x16::ZERO; 16];
    for (r, &i) in rows.iter_mut().zip(idx.iter()) {
        *r = u32x16::new(*row(table, i));
    }
    transpose16(rows)
}

/// [`UintLane::gather16`](super::UintLane::gather16) for `u32x8`: each row as two halves,
/// two 8 x 8 transposes.
#[inline(always)]
pub(super) fn gather16_x8(table: &[[u32; 16]], idx: u32x8) -> [u32x8; 16] {
    let idx = idx.to_array();
    let mut lo = [u32x8::ZERO; 8];
    let mut hi = [u32x8::ZERO; 8];
    for ((l, h), &i) in lo.iter_mut().zip(hi.iter_mut()).zip(idx.iter()) {
        let [a, b]: [[u32; 8]; 2] = bytemuck::cast(*row(table, i));
        *l = u32x8::new(a);
        *h = u32x8::new(b);
    }
    let (lo, hi) = (u32x8::transpose(lo), u32x8::transpose(hi));
    let mut out = [u32x8::ZERO; 16];
    for (o, v) in out.iter_mut().zip(lo.into_iter().chain(hi)) {
        *o = v;
    }
    out
}
