//! Progressive multi-jittered (0,2) sequences, with and without the blue-noise step, in
//! 0.32 fixed point.
//!
//! This library is the whole algorithm, with no dependencies: warpcore's tests use it (to
//! regenerate tables and to build the plain pmj02 reference of the blue-noise comparison)
//! and `main.rs` wraps it in a command-line tool.
//!
//! # The sequence
//!
//! Christensen, Kensler and Kilpatrick, "Progressive Multi-Jittered Sample Sequences" (EGSR
//! 2018). Points are added in powers of two; after `2^m` points every *elementary grid* of
//! `2^m` cells (`2^k` columns by `2^(m-k)` rows, `k = 0..=m`) holds exactly one point per cell,
//! i.e. every power-of-two prefix is a (0,m,2)-net. Growing `N = 4^j` points:
//!
//! * `N -> 2N`: the new point `N + s` goes into the sub-quadrant diagonally opposite point
//!   `s`'s, inside `s`'s cell of the `sqrt(N) x sqrt(N)` grid;
//! * `2N -> 4N`: the new point `2N + s` goes into the sub-quadrant next to point `s`'s, across
//!   x (x-flip) or across y (y-flip) — one random choice for the whole step, so the two new
//!   points of each cell fill its two empty sub-quadrants.
//!
//! Inside the sub-quadrant the point must lie in a free cell of *every* elementary grid of the
//! `2N` (or `4N`) cells. Those are found without dart throwing, following the observation of
//! Pharr ("Efficient Generation of Points that Satisfy Two-Dimensional Elementary Intervals",
//! JCGT 2019) that the valid positions form a product set: once the sub-quadrant fixes the top
//! bits of x and y, the grids with more columns constrain only further x bits (given the fixed
//! y bits) and the grids with more rows only further y bits. Two small depth-first searches
//! give the valid x strata and the valid y strata; any pair of them is a valid cell.
//!
//! **bn** (blue noise): draw `candidates` cells from that product (all of them when there are
//! fewer), each with random bits below the stratum, and keep the one farthest — toroidally —
//! from the points placed so far (Mitchell's best candidate). A uniform grid with at most two
//! points per cell (by the (0,2) property) makes each nearest-neighbour query O(1). With
//! `candidates = 1` the step is skipped: that is plain pmj02.
//!
//! Everything is integer arithmetic on `u32` fixed point (`x / 2^32`) driven by one seeded
//! SplitMix64 stream, so the output is a pure function of `(count, seed, candidates)` on every
//! machine.

pub mod tool;

/// SplitMix64 (Steele, Lea and Flood 2014): small, fast, and fully specified (bluegen's
/// optimiser draws from it too).
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Self {
        Rng(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    pub fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }

    /// A value in `0..n` (`n >= 1`), by multiply-shift (bias below 2^-32, irrelevant here).
    pub fn below(&mut self, n: usize) -> usize {
        ((self.next_u32() as u64 * n as u64) >> 32) as usize
    }
}

/// Toroidal squared distance of two fixed-point points, in units of `2^-64`.
pub fn toroidal_dist2(a: [u32; 2], b: [u32; 2]) -> u64 {
    let d = |p: u32, q: u32| (p.wrapping_sub(q) as i32).unsigned_abs() as u64;
    let (dx, dy) = (d(a[0], b[0]), d(a[1], b[1]));
    dx * dx + dy * dy
}

/// The top `bits` bits of a fixed-point coordinate (its stratum among `2^bits`).
fn top(v: u32, bits: u32) -> u32 {
    if bits == 0 { 0 } else { v >> (32 - bits) }
}

/// Occupancy of the `t + 1` elementary grids of `2^t` cells.
struct Grids {
    t: u32,
    /// `cells[k]`: grid with `2^k` columns and `2^(t-k)` rows, row-major by column index.
    cells: Vec<Vec<bool>>,
}

impl Grids {
    fn new(t: u32, points: &[[u32; 2]]) -> Self {
        let mut g = Grids {
            t,
            cells: (0..=t).map(|_| vec![false; 1 << t]).collect(),
        };
        for &p in points {
            g.mark(p);
        }
        g
    }

    fn index(&self, k: u32, x: u32, y: u32) -> usize {
        ((x as usize) << (self.t - k)) | y as usize
    }

    /// Is the cell with x stratum `x` (k bits) and y stratum `y` (t - k bits) taken?
    fn taken(&self, k: u32, x: u32, y: u32) -> bool {
        self.cells[k as usize][self.index(k, x, y)]
    }

    fn mark(&mut self, p: [u32; 2]) {
        for k in 0..=self.t {
            let i = self.index(k, top(p[0], k), top(p[1], self.t - k));
            debug_assert!(
                !self.cells[k as usize][i],
                "two points in one elementary interval"
            );
            self.cells[k as usize][i] = true;
        }
    }

    /// All x strata (t bits) that extend the prefix `xp` (`px` bits) and are free in the grids
    /// `k = px + 1 ..= t`, whose row is a prefix of `yp` (`py` bits, `px + py >= t`).
    fn valid_x(&self, xp: u32, px: u32, yp: u32, py: u32, out: &mut Vec<u32>) {
        if px == self.t {
            out.push(xp);
            return;
        }
        let k = px + 1;
        let y = yp >> (py - (self.t - k));
        for bit in 0..2 {
            let x = (xp << 1) | bit;
            if !self.taken(k, x, y) {
                self.valid_x(x, k, yp, py, out);
            }
        }
    }

    /// The mirror image of [`Grids::valid_x`]: y strata extending `yp` (`py` bits), free in
    /// the grids `k = t - py - 1 ..= 0`, whose column is a prefix of `xp`.
    fn valid_y(&self, xp: u32, px: u32, yp: u32, py: u32, out: &mut Vec<u32>) {
        if py == self.t {
            out.push(yp);
            return;
        }
        let k = self.t - (py + 1);
        let x = xp >> (px - k);
        for bit in 0..2 {
            let y = (yp << 1) | bit;
            if !self.taken(k, x, y) {
                self.valid_y(xp, px, y, py + 1, out);
            }
        }
    }

    /// Are the grids fully determined by both prefixes (`t - py <= k <= px`) free there?
    fn prefixes_free(&self, xp: u32, px: u32, yp: u32, py: u32) -> bool {
        (self.t - py..=px).all(|k| !self.taken(k, xp >> (px - k), yp >> (py - (self.t - k))))
    }
}

/// Nearest-neighbour search on the torus: a `2^g x 2^g` grid of buckets. A bucket is an
/// elementary interval of area `2^-2g`, so it holds at most `2^(t - 2g) <= 2` points of a
/// (0,t,2)-net.
struct Neighbours {
    g: u32,
    buckets: Vec<[u32; 2]>,
}

const EMPTY: u32 = u32::MAX;

impl Neighbours {
    fn new(t: u32, points: &[[u32; 2]]) -> Self {
        let g = t / 2;
        let mut n = Neighbours {
            g,
            buckets: vec![[EMPTY; 2]; 1 << (2 * g)],
        };
        for (i, &p) in points.iter().enumerate() {
            n.insert(i as u32, p);
        }
        n
    }

    fn bucket(&self, bx: u32, by: u32) -> usize {
        ((bx as usize) << self.g) | by as usize
    }

    fn insert(&mut self, index: u32, p: [u32; 2]) {
        let b = self.bucket(top(p[0], self.g), top(p[1], self.g));
        let slot = if self.buckets[b][0] == EMPTY { 0 } else { 1 };
        debug_assert_eq!(self.buckets[b][slot], EMPTY, "bucket overflow");
        self.buckets[b][slot] = index;
    }

    /// Squared toroidal distance from `c` to the nearest of `points` (`u64::MAX` if none).
    fn nearest(&self, c: [u32; 2], points: &[[u32; 2]]) -> u64 {
        let side = 1u32 << self.g;
        let mut best = u64::MAX;
        if side < 8 {
            for &p in points {
                best = best.min(toroidal_dist2(c, p));
            }
            return best;
        }
        let (cx, cy) = (top(c[0], self.g) as i64, top(c[1], self.g) as i64);
        let cell = 1u64 << (32 - self.g);
        // Rings of buckets at Chebyshev distance r; a point in ring r is at least (r - 1)
        // bucket widths away, so stop once that exceeds the best distance so far. Rings stay
        // below half the grid so that no bucket is visited twice across the wrap.
        for r in 0..(side as i64 / 2) {
            if r >= 1 {
                let reach = (r as u64 - 1) * cell;
                if best <= reach * reach {
                    return best;
                }
            }
            for dx in -r..=r {
                for dy in -r..=r {
                    if dx.abs() != r && dy.abs() != r {
                        continue;
                    }
                    let bx = (cx + dx).rem_euclid(side as i64) as u32;
                    let by = (cy + dy).rem_euclid(side as i64) as u32;
                    for &i in &self.buckets[self.bucket(bx, by)] {
                        if i != EMPTY {
                            best = best.min(toroidal_dist2(c, points[i as usize]));
                        }
                    }
                }
            }
        }
        // Not reached for the densities of a growing net; stay exact regardless.
        for &p in points {
            best = best.min(toroidal_dist2(c, p));
        }
        best
    }
}

/// Why a point could not be placed (never observed; reported rather than hidden).
#[derive(Debug)]
pub struct Stuck {
    pub index: usize,
}

/// The first `count` points of a pmj02 sequence (`candidates = 1`) or a pmj02bn sequence
/// (`candidates > 1` best candidates per point), from `seed`.
pub fn generate(count: usize, seed: u64, candidates: usize) -> Result<Vec<[u32; 2]>, Stuck> {
    let mut rng = Rng::new(seed);
    let mut points: Vec<[u32; 2]> = Vec::with_capacity(count);
    if count == 0 {
        return Ok(points);
    }
    points.push([rng.next_u32(), rng.next_u32()]);
    // `n = 2^j` cells per side of the square grid whose cells hold one point each.
    let mut j = 0u32;
    while points.len() < count {
        let n_old = points.len();
        // N -> 2N: diagonally opposite sub-quadrant.
        let t = 2 * j + 1;
        let mut level = Level::new(t, &points);
        for s in 0..n_old {
            if points.len() == count {
                return Ok(points);
            }
            let p = points[s];
            let (xp, yp) = (top(p[0], j + 1) ^ 1, top(p[1], j + 1) ^ 1);
            level.place(&mut points, &mut rng, candidates, [xp, yp], j + 1)?;
        }
        // 2N -> 4N: the sub-quadrant across x, or across y, for every point of this step.
        let t = 2 * j + 2;
        let mut level = Level::new(t, &points);
        let flip = if rng.next_u32() & 1 == 0 {
            [1, 0]
        } else {
            [0, 1]
        };
        for s in 0..2 * n_old {
            if points.len() == count {
                return Ok(points);
            }
            let p = points[s];
            let (xp, yp) = (top(p[0], j + 1) ^ flip[0], top(p[1], j + 1) ^ flip[1]);
            level.place(&mut points, &mut rng, candidates, [xp, yp], j + 1)?;
        }
        j += 1;
    }
    Ok(points)
}

/// The state of one doubling step towards `2^t` points.
struct Level {
    grids: Grids,
    neighbours: Neighbours,
    xs: Vec<u32>,
    ys: Vec<u32>,
}

impl Level {
    fn new(t: u32, points: &[[u32; 2]]) -> Self {
        Level {
            grids: Grids::new(t, points),
            neighbours: Neighbours::new(t, points),
            xs: Vec::new(),
            ys: Vec::new(),
        }
    }

    /// Adds one point whose x and y strata start with the `bits`-bit prefixes `prefix`.
    fn place(
        &mut self,
        points: &mut Vec<[u32; 2]>,
        rng: &mut Rng,
        candidates: usize,
        prefix: [u32; 2],
        bits: u32,
    ) -> Result<(), Stuck> {
        let t = self.grids.t;
        let stuck = Stuck {
            index: points.len(),
        };
        let [xp, yp] = prefix;
        if !self.grids.prefixes_free(xp, bits, yp, bits) {
            return Err(stuck);
        }
        self.xs.clear();
        self.ys.clear();
        self.grids.valid_x(xp, bits, yp, bits, &mut self.xs);
        self.grids.valid_y(xp, bits, yp, bits, &mut self.ys);
        if self.xs.is_empty() || self.ys.is_empty() {
            return Err(stuck);
        }
        // With fewer valid cells than candidates, every cell is tried (cyclically, each time
        // with fresh bits below the stratum); otherwise cells are drawn at random.
        let cells = self.xs.len() * self.ys.len();
        let tries = candidates.max(1);
        let jitter = |rng: &mut Rng, stratum: u32| {
            // t <= 31 here: the stratum keeps the top t bits, the rest is uniform.
            (stratum << (32 - t)) | (rng.next_u32() >> t)
        };
        let mut best = None;
        let mut best_d = 0u64;
        for c in 0..tries {
            let (xi, yi) = if cells <= tries {
                (c % cells % self.xs.len(), c % cells / self.xs.len())
            } else {
                (rng.below(self.xs.len()), rng.below(self.ys.len()))
            };
            let cand = [jitter(rng, self.xs[xi]), jitter(rng, self.ys[yi])];
            if candidates <= 1 {
                best = Some(cand);
                break;
            }
            let d = self.neighbours.nearest(cand, points);
            if best.is_none() || d > best_d {
                best = Some(cand);
                best_d = d;
            }
        }
        let p = best.ok_or(stuck)?;
        self.grids.mark(p);
        self.neighbours.insert(points.len() as u32, p);
        points.push(p);
        Ok(())
    }
}

/// Is `points` a (0,m,2)-net, `points.len() = 2^m`: one point in every cell of every
/// elementary grid?
pub fn is_net(points: &[[u32; 2]]) -> bool {
    let n = points.len();
    if !n.is_power_of_two() {
        return false;
    }
    let m = n.trailing_zeros();
    (0..=m).all(|k| {
        let mut seen = vec![false; n];
        points.iter().all(|p| {
            let i = ((top(p[0], k) as usize) << (m - k)) | top(p[1], m - k) as usize;
            !std::mem::replace(&mut seen[i], true)
        })
    })
}

/// Mean and minimum toroidal nearest-neighbour distance of `points`, both times
/// `sqrt(len)` (so a perfect hexagonal packing scores about 1.07), by brute force.
pub fn nearest_neighbour_stats(points: &[[u32; 2]]) -> (f64, f64) {
    let n = points.len();
    let scale = (n as f64).sqrt() / 4_294_967_296.0;
    let mut sum = 0.0;
    let mut min = f64::INFINITY;
    for (i, &p) in points.iter().enumerate() {
        let mut best = u64::MAX;
        for (j, &q) in points.iter().enumerate() {
            if i != j {
                best = best.min(toroidal_dist2(p, q));
            }
        }
        let d = (best as f64).sqrt() * scale;
        sum += d;
        min = min.min(d);
    }
    (sum / n as f64, min)
}

/// Blue-noise optimization by nested flips (after Ahmed and Wonka, "Optimizing Dyadic Nets",
/// SIGGRAPH 2021), adapted to a progressive sequence.
///
/// Why it is needed: in a (0,2)-sequence the cells of a new level are *forced* by the points
/// before it (given all their bits, exactly one fine cell per new point is free in every
/// elementary grid — the generator's search confirms this), so a best-candidate choice at
/// placement time only moves a point inside a cell of side `2^-t`, far below the spacing
/// `2^(-t/2)` of that level. The freedom that shapes the spacing of a `2^T`-point prefix is
/// in bits near `T/2` of the *earlier* points.
///
/// A flip of node `(axis, depth b, prefix P)` inverts bit `b` of that coordinate for every
/// point whose first `b - 1` bits are `P`: one step of a nested (Owen) scramble. It maps each
/// elementary interval onto another of the same shape, so every subset that was a net stays
/// one — every prefix remains a (0,m,2)-net whatever flips are applied. Flips move points by
/// `2^-b`, which matters for prefixes of about `2^(2b)` points and up; for each depth we weigh
/// the prefixes of `2^T` points with `2 <= T <= 2b + 1` (larger prefixes see the move as
/// fine-scale jitter) and keep a flip when it lowers a
/// Gaussian repulsion energy (`sum exp(-d^2 / (2 sigma^2))` over toroidal pairs, `sigma =
/// 0.5 / sqrt(2^T)`, each prefix weighted by `1 / 2^T`). Depths go coarse to fine, `passes`
/// times. Deterministic: no randomness, fixed visiting order.
pub fn optimize(points: &mut [[u32; 2]], passes: usize) {
    let n = points.len();
    if n < 4 || !n.is_power_of_two() {
        return;
    }
    let t_max = n.trailing_zeros();
    for _ in 0..passes {
        for b in 1..=t_max.div_ceil(2) + 1 {
            if b >= 32 {
                break;
            }
            for axis in 0..2 {
                flip_depth(points, axis, b, t_max);
            }
        }
    }
}

/// Width of the repulsion kernel in units of the spacing `1 / sqrt(2^T)` (0.35 and 0.7 were
/// measured worse).
const SIGMA: f64 = 0.5;

/// Toroidal squared distance in units of the unit square (f64).
fn dist2_f64(a: [u32; 2], b: [u32; 2]) -> f64 {
    let d = |p: u32, q: u32| (p.wrapping_sub(q) as i32) as f64 / 4_294_967_296.0;
    let (dx, dy) = (d(a[0], b[0]), d(a[1], b[1]));
    dx * dx + dy * dy
}

/// Buckets of the prefix of `2^t` points for radius queries, updated as points move.
struct Buckets {
    t: u32,
    g: u32,
    cells: Vec<Vec<u32>>,
    inv_two_sigma2: f64,
    cutoff2: f64,
}

impl Buckets {
    fn new(t: u32, points: &[[u32; 2]]) -> Self {
        let g = t.div_ceil(2);
        let mut cells = vec![Vec::new(); 1 << (2 * g)];
        for (i, p) in points.iter().enumerate().take(1 << t) {
            cells[Self::cell_of(g, *p)].push(i as u32);
        }
        let sigma = SIGMA / ((1u64 << t) as f64).sqrt();
        Buckets {
            t,
            g,
            cells,
            inv_two_sigma2: 1.0 / (2.0 * sigma * sigma),
            cutoff2: 9.0 * sigma * sigma,
        }
    }

    fn cell_of(g: u32, p: [u32; 2]) -> usize {
        ((top(p[0], g) as usize) << g) | top(p[1], g) as usize
    }

    fn kernel(&self, d2: f64) -> f64 {
        if d2 >= self.cutoff2 {
            0.0
        } else {
            (-d2 * self.inv_two_sigma2).exp()
        }
    }

    /// Calls `f(q)` for the indices `q` in buckets within `reach` of `p` (toroidally).
    fn around(&self, p: [u32; 2], reach: f64, mut f: impl FnMut(u32)) {
        let side = 1i64 << self.g;
        let r = ((reach * side as f64).ceil() as i64).min(side / 2);
        let (cx, cy) = (top(p[0], self.g) as i64, top(p[1], self.g) as i64);
        let span = if 2 * r + 1 > side { 0..side } else { -r..r + 1 };
        for dx in span.clone() {
            for dy in span.clone() {
                let (bx, by) = if 2 * r + 1 > side {
                    (dx, dy)
                } else {
                    ((cx + dx).rem_euclid(side), (cy + dy).rem_euclid(side))
                };
                for &q in &self.cells[((bx as usize) << self.g) | by as usize] {
                    f(q);
                }
            }
        }
    }

    fn moved(&mut self, i: u32, from: [u32; 2], to: [u32; 2]) {
        if i as u64 >= 1u64 << self.t {
            return;
        }
        let (a, b) = (Self::cell_of(self.g, from), Self::cell_of(self.g, to));
        if a != b {
            if let Some(k) = self.cells[a].iter().position(|&q| q == i) {
                self.cells[a].swap_remove(k);
            }
            self.cells[b].push(i);
        }
    }
}

fn flip_depth(points: &mut [[u32; 2]], axis: usize, b: u32, t_max: u32) {
    let hi = (2 * b + 1).min(t_max);
    if hi < 2 {
        return;
    }
    let mut grids: Vec<Buckets> = (2..=hi).map(|t| Buckets::new(t, points)).collect();
    // Group the points by their first b - 1 bits on `axis` (flips at depth b keep them).
    let mut nodes: Vec<Vec<u32>> = vec![Vec::new(); 1 << (b - 1)];
    for (i, p) in points.iter().enumerate() {
        nodes[top(p[axis], b - 1) as usize].push(i as u32);
    }
    let bit = 1u32 << (32 - b);
    let shift = 2.0 / (1u64 << b) as f64;
    let mut moved_flag = vec![false; points.len()];
    for node in &nodes {
        for &i in node {
            moved_flag[i as usize] = true;
        }
        let flipped = |p: [u32; 2]| {
            let mut q = p;
            q[axis] ^= bit;
            q
        };
        let mut delta = 0.0;
        for grid in &grids {
            let n_t = 1u64 << grid.t;
            let reach = 3.0 * SIGMA / (n_t as f64).sqrt() + shift;
            let mut d_t = 0.0;
            for &i in node {
                if i as u64 >= n_t {
                    continue;
                }
                let p = points[i as usize];
                let p_new = flipped(p);
                grid.around(p, reach, |q| {
                    if q == i || (moved_flag[q as usize] && q < i) {
                        return;
                    }
                    let qo = points[q as usize];
                    let qn = if moved_flag[q as usize] {
                        flipped(qo)
                    } else {
                        qo
                    };
                    d_t += grid.kernel(dist2_f64(p_new, qn)) - grid.kernel(dist2_f64(p, qo));
                });
            }
            delta += d_t / n_t as f64;
        }
        if delta < 0.0 {
            for &i in node {
                let from = points[i as usize];
                let to = flipped(from);
                points[i as usize] = to;
                for grid in &mut grids {
                    grid.moved(i, from, to);
                }
            }
        }
        for &i in node {
            moved_flag[i as usize] = false;
        }
    }
}
