//! The published formulas, branches and all, written once over [`Real`]: in `f64` (std's
//! functions) they are the tests' references, in `f32` (the `libm` crate's functions) the
//! benchmarks' "textbook" peers, the code a user would port from the papers.
use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};
use std::ops::{Add, Div, Mul, Neg, Sub};

/// `f32` or `f64` with the few functions the formulas call.
pub trait Real:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
{
    /// The constant `x` in this type (rounded once).
    fn of(x: f64) -> Self;
    fn abs(self) -> Self;
    fn sqrt(self) -> Self;
    fn sin(self) -> Self;
    fn cos(self) -> Self;
    fn copysign(self, sign: Self) -> Self;
}

/// `Real` for a float type: `sqrt`, `sin`, `cos` and `copysign` by the given functions.
macro_rules! real {
    ($t:ty, $sqrt:path, $sin:path, $cos:path, $copysign:path) => {
        impl Real for $t {
            #[inline(always)]
            fn of(x: f64) -> Self {
                x as $t
            }
            #[inline(always)]
            fn abs(self) -> Self {
                <$t>::abs(self)
            }
            #[inline(always)]
            fn sqrt(self) -> Self {
                $sqrt(self)
            }
            #[inline(always)]
            fn sin(self) -> Self {
                $sin(self)
            }
            #[inline(always)]
            fn cos(self) -> Self {
                $cos(self)
            }
            #[inline(always)]
            fn copysign(self, sign: Self) -> Self {
                $copysign(self, sign)
            }
        }
    };
}

real!(f32, libm::sqrtf, libm::sinf, libm::cosf, libm::copysignf);
real!(f64, f64::sqrt, f64::sin, f64::cos, f64::copysign);

/// Shirley and Chiu's concentric map of `(a, b) = (2 u0 - 1, 2 u1 - 1)` as published: the
/// signed radius and the angle `(r, phi)` of the point `(r cos phi, r sin phi)`, by the two
/// branches `|a| > |b|` (`r = a`, `phi = (pi/4)(b / a)`) and otherwise (`r = b`,
/// `phi = pi/2 - (pi/4)(a / b)`); `(0, 0)` at the centre.
#[inline(always)]
pub fn concentric_polar<F: Real>(a: F, b: F) -> (F, F) {
    let zero = F::of(0.0);
    if a == zero && b == zero {
        return (zero, zero);
    }
    let quarter = F::of(FRAC_PI_4);
    if a.abs() > b.abs() {
        (a, quarter * (b / a))
    } else {
        (b, F::of(FRAC_PI_2) - quarter * (a / b))
    }
}

/// Clarberg's equal-area fold of `(a, b) = (2 u0 - 1, 2 u1 - 1)` as published: `(r, phi,
/// sd)` with `sd = 1 - (|a| + |b|)` (negative on the lower hemisphere's corner triangles),
/// `r = 1 - |sd|` and the first-quadrant azimuth `phi = ((|b| - |a|) / r + 1) pi/4`
/// (`pi/4` at `r = 0`).
#[inline(always)]
pub fn equal_area_fold<F: Real>(a: F, b: F) -> (F, F, F) {
    let (ua, ub) = (a.abs(), b.abs());
    let one = F::of(1.0);
    let sd = one - (ua + ub);
    let r = one - sd.abs();
    let phi = if r == F::of(0.0) {
        F::of(FRAC_PI_4)
    } else {
        ((ub - ua) / r + one) * F::of(FRAC_PI_4)
    };
    (r, phi, sd)
}

/// Clarberg's inverse unfolding as published: from `r = sqrt(1 - |z|)` and `q = r phi /
/// (pi/2)` (`phi` the first-quadrant azimuth of `d`), the point of the unit square, with
/// `(p, q) = (r - q, q)` folded onto the corner triangles for `d[2] < 0` and the signs of
/// `d[0]`, `d[1]` (of `-0.0` too) picking the quadrant.
#[inline(always)]
pub fn equal_area_unfold<F: Real>(r: F, q: F, d: [F; 3]) -> [F; 2] {
    let (one, half) = (F::of(1.0), F::of(0.5));
    let p = r - q;
    let (ua, ub) = if d[2] < F::of(0.0) {
        (one - q, one - p)
    } else {
        (p, q)
    };
    [
        half * (ua.copysign(d[0]) + one),
        half * (ub.copysign(d[1]) + one),
    ]
}

/// The Basu-Owen walk as usually written (DESIGN.md section 4): the 16 base-4 digits of
/// `index`, lowest first, one at a time with branches, unscrambled; `[x, y, 1 - x - y]` of the
/// centroid (exact in `f64`: every step is dyadic).
#[inline(always)]
pub fn basu_owen<F: Real>(index: u32) -> [F; 3] {
    let half = F::of(0.5);
    let (mut cx, mut cy, mut w) = (F::of(0.0), F::of(0.0), half);
    for j in 0..16 {
        let d = (index >> (2 * j)) & 3;
        if d & 1 == 0 {
            cy = cy + w;
        }
        if d & 2 == 0 {
            cx = cx + w;
        }
        w = w * if d == 0 { -half } else { half };
    }
    let two_thirds_w = F::of(2.0) * w / F::of(3.0);
    let (x, y) = (cx + two_thirds_w, cy + two_thirds_w);
    [x, y, F::of(1.0) - x - y]
}

/// `a - b` of 3-vectors.
#[inline(always)]
pub fn sub<F: Real>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// `a + b` of 3-vectors.
#[inline(always)]
pub fn add<F: Real>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// `k a`.
#[inline(always)]
pub fn scale<F: Real>(a: [F; 3], k: F) -> [F; 3] {
    [a[0] * k, a[1] * k, a[2] * k]
}

/// `a . b`.
#[inline(always)]
pub fn dot<F: Real>(a: [F; 3], b: [F; 3]) -> F {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// `a x b`.
#[inline(always)]
pub fn cross<F: Real>(a: [F; 3], b: [F; 3]) -> [F; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
