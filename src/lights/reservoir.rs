//! Weighted reservoir sampling of one item: a streaming choice with its exact probability.

/// Chooses one item of a stream with probability proportional to its weight, in O(1) memory
/// and one pass, without knowing the stream's length or total weight in advance: weighted
/// reservoir sampling of size one (Chao 1982, "A general purpose unequal probability sampling
/// plan"), the building block of resampled importance sampling and ReSTIR (Talbot et al.
/// 2005; Bitterli et al. 2020, "Spatiotemporal reservoir resampling for real-time ray tracing
/// with dynamic direct lighting").
///
/// ```
/// use warpcore::lights::Reservoir;
///
/// let weights = [0.5, 0.0, 2.0, 1.5];
/// let u = [0.9, 0.1, 0.3, 0.6]; // one independent uniform number per update
/// let mut r = Reservoir::new();
/// for (i, (&w, &u)) in weights.iter().zip(&u).enumerate() {
///     r.update(i as u32, w, u);
/// }
/// let (index, p) = r.chosen().unwrap();
/// assert_eq!(index, 2);
/// assert_eq!(p, 0.5); // 2.0 / 4.0: exactly weight / total
/// # let _ = p;
/// ```
///
/// **Method.** After items `0..k` the reservoir holds item `j` with probability `w_j / W_k`
/// (`W_k` the sum so far): item `k` replaces it with probability `w_k / W_{k+1}`, and
/// `(w_j / W_k) (1 - w_k / W_{k+1}) = w_j / W_{k+1}`. The sum is kept in `f64`, the test is
/// `u W < w` in `f64` (exact for `f32` inputs: a product of two 24-bit significands), so a
/// uniform `u` replaces with probability `w / W` up to the 24-bit resolution of `u`.
/// [`merge`](Self::merge) combines two reservoirs over disjoint streams the same way (the
/// result is as if one reservoir had seen both).
///
/// **Bad weights.** NaN, negative, `-0.0` and infinite weights count as 0: the item is never
/// chosen and the total is unchanged (an infinite weight would make every other probability
/// 0 and the total unusable). `u` goes through the crate's forward rule (NaN, negatives -> 0,
/// `>= 1`, `+inf` -> `1 - 2^-24`). Nothing panics.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reservoir {
    index: u32,
    weight: f32,
    total: f64,
}

/// A weight as the reservoir counts it: itself when finite and `> 0`, else 0.
#[inline]
fn valid(w: f32) -> f64 {
    if w > 0.0 && w.is_finite() {
        f64::from(w)
    } else {
        0.0
    }
}

/// `u` by the forward rule, in `f64`.
#[inline]
fn unit(u: f32) -> f64 {
    f64::from(crate::lanes::unit_interval(u))
}

impl Reservoir {
    /// An empty reservoir (nothing chosen, total 0).
    pub const fn new() -> Self {
        Self {
            index: 0,
            weight: 0.0,
            total: 0.0,
        }
    }

    /// Offers item `index` with weight `weight`; `u` is a fresh uniform number in `[0, 1)`.
    /// Returns whether the item replaced the current choice (always for the first positive
    /// weight; never for a weight that counts as 0).
    #[inline]
    pub fn update(&mut self, index: u32, weight: f32, u: f32) -> bool {
        let w = valid(weight);
        self.total += w;
        let take = w > 0.0 && unit(u) * self.total < w;
        if take {
            self.index = index;
            self.weight = weight;
        }
        take
    }

    /// Combines `other` (a reservoir over a disjoint stream) into `self`: the result holds
    /// `other`'s choice with probability `other.total() / (self.total() + other.total())`,
    /// so every item's probability is its weight over the combined total. `u` as in
    /// [`update`](Self::update). Returns whether `other`'s choice was taken.
    #[inline]
    pub fn merge(&mut self, other: &Reservoir, u: f32) -> bool {
        let w = other.total;
        self.total += w;
        let take = w > 0.0 && unit(u) * self.total < w;
        if take {
            self.index = other.index;
            self.weight = other.weight;
        }
        take
    }

    /// The chosen item and its probability `weight / total` (computed in `f64`, rounded once
    /// to `f32`: relative error at most `2^-24`), or `None` while no positive weight was
    /// offered.
    #[inline]
    pub fn chosen(&self) -> Option<(u32, f32)> {
        (self.total > 0.0).then(|| (self.index, (f64::from(self.weight) / self.total) as f32))
    }

    /// The sum of the valid weights offered so far (in `f64`, so streams of any length and
    /// dynamic range add up without overflow).
    #[inline]
    pub fn total(&self) -> f64 {
        self.total
    }

    /// The chosen item's weight (0 while nothing is chosen).
    #[inline]
    pub fn weight(&self) -> f32 {
        self.weight
    }
}
