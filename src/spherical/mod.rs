//! Lights by solid angle: points on a triangle or a rectangle distributed uniformly in the
//! solid angle they subtend at a shading point `p`, their inverses, and the solid angles.
//!
//! | function | maps | source |
//! |---|---|---|
//! | [`triangle`] | `u` to the barycentrics of a point of triangle `v`, uniform in solid angle at `p` | Arvo 1995, "Stratified Sampling of Spherical Triangles" (SIGGRAPH) |
//! | [`rectangle`] | `u` to `(s, t)` of the point `corner + s ex + t ey`, uniform in solid angle | Urena, Fajardo and King 2013, "An Area-Preserving Parametrization for Spherical Rectangles" (EGSR) |
//! | [`triangle_cosine`], [`rectangle_cosine`] | `u` warped by [`bilinear`] (a bilinear fit of the receiver's clamped cosine at the light's corners), then the map above; density `bilinear_pdf(u') / omega` | Hart, Pharr, Mueller, Lopes, McGuire and Shirley 2020, "Practical Product Sampling by Fitting and Composing Warps" (EGSR) |
//! | [`cone`] | `u` to a direction uniform in the cone a sphere light (centre, radius) subtends at `p`, through the concentric disk | Shirley and Chiu 1997 (the disk), the cap's area-preserving lift; pbrt-v4's `SampleUniformCone` is the polar peer |
//! | [`triangle_solid_angle`], [`rectangle_solid_angle`] | the solid angle `omega` in `[0, 2 pi]` | Van Oosterom and Strackee 1983, "The Solid Angle of a Plane Triangle" (IEEE TBME) |
//!
//! Near a light, sampling the solid angle removes the `cos' / r^2` factor from the estimator
//! that area sampling ([`crate::triangle`], `s, t = u`) leaves in it; far away both agree and
//! area sampling is cheaper. `docs/REPORT.md` measures where the switch pays.
//!
//! **Density.** The second result is the density with respect to solid angle at `p`:
//! `1 / omega`. Below [`AREA_FALLBACK_SR`] (`1e-8` sr), where `f32` cannot place points
//! faithfully by angle, both maps sample by area instead ([`crate::triangle::uniform`], or
//! `(s, t) = u`) and return the matching solid-angle density `|q - p|^2 / (cos' area)`; the
//! inverses follow the same switch, so round trips hold there too.
//!
//! **How the maps stay exact.** A straight `f32` transcription of the papers loses the
//! density and the round trip below about `1e-3` sr (`acos` of nearly 1, `1 - cos`,
//! `k + u0 omega` with `k` near `2 pi`). Here: the light is translated to `p` and scaled by
//! an exact power of two (no overflow or underflow for any finite input); edges come from
//! the caller's vertices, not from differences of nearly equal vectors; the solid angle is
//! Van Oosterom-Strackee's `atan2` of the triple product (computed from edges) through the
//! crate's own `atan` kernel; chords between directions come from edges (`|x| - |y| =
//! -(y - x).(x + y) / (|x| + |y|)`); Arvo's first step is solved in closed form for the
//! point on the chord (a quadratic with no `acos`), his second by chord lengths; the
//! rectangle's `x` comes from a closed form written with the half-infinite strips beside
//! the light (each accurate on either side of it), which is the point for lights of
//! `1e-2 .. 2` sr seen within `kappa <= 16` (below) with sides within a factor 16; other
//! lights take one Newton step on the strip's solid angle computed by Van Oosterom-Strackee
//! (relative, not absolute, accuracy); its `y` uses `1 -+ y/r` forms. A long rectangle seen
//! from beside its middle (both ends along a side far beyond `p`'s distance from it, where
//! two corners are seen nearly opposite and one pair of Van Oosterom-Strackee triangles
//! cancels) is cut at `p`'s foot into pieces on one side of it, whose solid angles add
//! without cancellation; this serves the solid angle, the Newton step and the inverse.
//! Every square root and inverse sine/cosine argument is clamped, every `0/0` selected away.
//!
//! **Precision** (`tests/spherical.rs`, 20 000 random lights per shape from `1e-8` sr to
//! nearly `2 pi`, distances `1e-6 .. 1e6`, against `f64` on the same `f32` input). The
//! conditioning of any light computation is `kappa = |v - p| |n| / |(v - p) . n|` (one over
//! the cosine at which `p` sees the light's plane; the farthest vertex for rectangles): the
//! input's own rounding moves the solid angle by about `ulp * kappa`. Measured: solid angle
//! and density `1 / omega` within `7.7e-7 kappa` relative (triangle) and `9.8e-7 kappa`
//! (rectangle), so within 1e-4 for every light seen at more than 0.6 degrees from grazing
//! (`kappa <= 100`); round trip `inverse(sample(u))` for solid angles `1e-4 .. 2` sr within
//! 2.3e-5 of `u` (triangle, `kappa <= 100`, `u1 >= 0.01`: at the apex `v1` the map
//! collapses `u0` and its error grows like `1 / sqrt(u1)`) and 6.5e-6 (rectangle,
//! `kappa <= 100`), and within `3.1e-6 kappa` for every light. Two more conditions: a thin
//! triangle is only as accurate as its shape (its edges are rounded from the caller's
//! vertices), so its error also grows with `s = l_max^2 / |e1 x e2|` (1.15 for an
//! equilateral triangle): slivers measure within `8.2e-8 kappa s` where `kappa s <= 1e5`;
//! and `f32` barycentrics place a direction no finer than about `3e-7 kappa s / q` when `p`
//! is near a vertex (`q`, the distance to it over the longest edge, below 1), which bounds the
//! round trip there. Long rectangles seen from beside them (sides to `10^6 : 1`, ends 3 to
//! 3000 times `p`'s distance): `3.0e-7 kappa`, their map's `u0` within `1.9e-4`. Samples are
//! uniform in solid angle (chi-square over sub-regions whose solid angles are computed in
//! `f64`, 2^21 samples per light).
//!
//! **Totality.** Every function accepts any `f32`. `u` is first mapped onto `[0, 1 - 2^-24]`
//! (NaN, negatives to 0; `>= 1`, `+inf` to `1 - 2^-24`); barycentrics are in the closed
//! simplex (each in `[0, 1]`, summing to 1 within 3e-7), `(s, t)` in `[0, 1]^2`, the density
//! finite and `>= 0`. The density is 0 exactly where the solid angle is 0: a degenerate
//! light (zero area, collinear vertices, `ex` or `ey` zero), `p` on the light's plane or at
//! a vertex, or non-finite input (NaN or inf anywhere, or coordinate differences of
//! `2^127` or more; every difference `v_i - p`, edge, `corner - p`, `ex`, `ey` component
//! below `2^-126` in magnitude is made 0 before the power-of-two scaling, so a point
//! `2^-149 .. 2^-127` above the light is on its plane), and lights below
//! [`AREA_FALLBACK_SR`] seen edge-on: triple product `a0 . (e1 x e2)` below `2^-120`
//! (triangle) or `z w h` below `2^-116` (rectangle) in the scaled frame, whose largest
//! coordinate is in `[1, 2)` (at most about `1e-36` sr for far lights; these thresholds keep
//! the area density below `2^127`). The point is then the area-sampling one. Solid angles of
//! such lights are 0, except that `p` on the plane inside the light may report `2 pi` (the
//! `atan2` of `+0` over a negative number). The density is never NaN, infinite or
//! `FLT_MAX`. Above [`AREA_FALLBACK_SR`] the triple product may be as small as it likes
//! (a point `2^-126` above the light, a `1e18` dynamic range): the density is `1 / omega`
//! and the barycentrics, whose numerators are lifted by an exact `2^64` when their sum is
//! below `2^-64`, stay in the simplex (their accuracy is then the input's). Rectangles keep
//! their accuracy while the shortest of `z`, `w`, `h` exceeds `2^-63` times the largest
//! coordinate (a `1 x 2^63` rectangle at distance 1 gets `pi / 4`). `docs/warps.md` gives
//! the reasons. Inverses clamp
//! barycentrics to `[0, 1]` and renormalise (all zero: the centroid), `(s, t)` to
//! `[0, 1]^2`, NaN to 0; their results are in `[0, 1 - 2^-24]`. `ey` is made orthogonal to
//! `ex` (its component along `ex` is dropped), a no-op for the rectangles of the contract.
//!
//! ```
//! use warpcore::spherical;
//!
//! // A unit square light one unit above the shading point.
//! let (corner, ex, ey, p) = ([-0.5f32, -0.5, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0; 3]);
//! let ([s, t], pdf) = spherical::rectangle(corner, ex, ey, p, [0.3, 0.8]);
//! let omega = spherical::rectangle_solid_angle(corner, ex, ey, p);
//! assert!((pdf * omega - 1.0).abs() < 1e-5);
//! let u = spherical::rectangle_inverse(corner, ex, ey, p, [s, t]);
//! assert!((u[0] - 0.3).abs() < 1e-5 && (u[1] - 0.8).abs() < 1e-5);
//!
//! // A triangle: barycentrics weight the vertices.
//! let v = [[0.0f32, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
//! let (b, pdf) = spherical::triangle(v, p, [0.5, 0.5]);
//! assert!(b.iter().all(|&x| (0.0..=1.0).contains(&x)) && pdf > 0.0);
//!
//! // Cosine-aware: the receiver's normal `n` tilts the samples towards where it faces; the
//! // density is the bilinear factor over the solid angle.
//! let n = [0.5f32, 0.0, 1.0];
//! let (b, pdf) = spherical::triangle_cosine(v, p, n, [0.5, 0.5]);
//! let u = spherical::triangle_inverse(v, p, b); // the warped sample
//! let c = |x: [f32; 3]| (n[0] * x[0] + n[1] * x[1] + n[2] * x[2])
//!     / (x.iter().map(|a| a * a).sum::<f32>().sqrt() * 1.25f32.sqrt());
//! let w = [c(v[1]), c(v[1]), c(v[0]), c(v[2])];
//! let omega = spherical::triangle_solid_angle(v, p);
//! assert!((pdf * omega - spherical::bilinear_pdf(u, w)).abs() < 1e-3);
//! ```

mod cone;
mod cosine;
mod rectangle;
mod triangle;

use crate::lanes::Lane;
use crate::slices;

/// Below this solid angle (steradians) [`triangle`] and [`rectangle`] sample by area (with
/// the matching solid-angle density), and their inverses invert that.
pub const AREA_FALLBACK_SR: f32 = 1e-8;

#[inline(always)]
fn splat3<L: Lane>(v: [f32; 3]) -> [L; 3] {
    [L::splat(v[0]), L::splat(v[1]), L::splat(v[2])]
}

#[inline(always)]
fn splat33<L: Lane>(v: [[f32; 3]; 3]) -> [[L; 3]; 3] {
    [splat3(v[0]), splat3(v[1]), splat3(v[2])]
}

lane_forms! {
    /// Uniform in solid angle over the spherical triangle that triangle `v` subtends at `p`
    /// (Arvo 1995): returns the barycentrics `b` of the point `b0 v0 + b1 v1 + b2 v2` and the
    /// density with respect to solid angle at `p`, `1 / omega`.
    ///
    /// `u0` picks the sub-triangle `(v0, v1, x)`, `x` on the edge `v0 v2`, whose solid angle is
    /// `u0 omega`; `u1` a point on the arc from `v1` to `x` with `1 - cos(angle from v1) = u1
    /// (1 - cos(angle(v1, x)))`. Strata of the square become wedges at `v1` (like
    /// [`crate::triangle::sqrt_map`]'s at `v0`). See the [module docs](self) for the exact
    /// forms, the precision (density 1e-4 relative and round trip 1e-4 for `1e-4 .. 2` sr where
    /// the light is seen at more than 0.6 degrees from grazing) and
    /// the out-of-domain rule (degenerate lights: area sampling, density 0).
    pub fn triangle, triangle_x8, triangle_x16 ["(light, point, sample) triples"]
        (v: [[L; 3]; 3], p: [L; 3], u: [L; 2]) -> ([L; 3], L) = triangle::sample_body;
}

/// [`triangle`] for one light and one shading point over a batch of samples: writes
/// `out[i] = [b0, b1, b2, density]` of `triangle(v, p, u[i])` for
/// `i < min(u.len(), out.len())` and returns that count. Bit-identical to the scalar form.
/// The light's setup (everything that does not depend on `u`) runs once per call.
#[inline]
pub fn triangle_slice(
    v: [[f32; 3]; 3],
    p: [f32; 3],
    u: &[[f32; 2]],
    out: &mut [[f32; 4]],
) -> usize {
    // The light's setup once per call (the same operations on the same splatted values as
    // inside the scalar body, so the same bits).
    let prep = triangle::prepare::<slices::Widest>(splat33(v), splat3(p));
    slices::map_lanes(u, out, |u: [slices::Widest; 2]| {
        let (b, d) = triangle::sample_prepared(&prep, u);
        [b[0], b[1], b[2], d]
    })
}

lane_forms! {
    /// Inverse of [`triangle`]: the `u` that maps to barycentrics `b` (the solid angle of the
    /// sub-triangle `(v0, v1, x)` over `omega`, and the ratio of squared chords from `v1`).
    ///
    /// Round trip `triangle_inverse(triangle(u))` within 1e-4 of `u` for solid angles
    /// `1e-4 .. 2` sr, except `u0` where `u1 = 0` (the apex `v1`, where `u0` is lost). Below
    /// [`AREA_FALLBACK_SR`] it inverts the area map ([`crate::triangle::uniform_inverse`]).
    pub fn triangle_inverse, triangle_inverse_x8, triangle_inverse_x16
        ["(light, point, barycentrics) triples"]
        (v: [[L; 3]; 3], p: [L; 3], b: [L; 3]) -> [L; 2] = triangle::inverse_body;
}

/// [`triangle_inverse`] for one light and point over a batch, with the length rule of
/// [`triangle_slice`].
#[inline]
pub fn triangle_inverse_slice(
    v: [[f32; 3]; 3],
    p: [f32; 3],
    b: &[[f32; 3]],
    out: &mut [[f32; 2]],
) -> usize {
    let light = triangle::setup::<slices::Widest>(splat33(v), splat3(p));
    slices::map_lanes(b, out, |b: [slices::Widest; 3]| {
        triangle::inverse_prepared(&light, b)
    })
}

lane_forms! {
    /// Uniform in solid angle over the spherical rectangle that the rectangle
    /// `corner + s ex + t ey` (`s, t` in `[0, 1]`, `ex` orthogonal to `ey`) subtends at `p`
    /// (Urena, Fajardo and King 2013): returns `(s, t)` and the density with respect to solid
    /// angle, `1 / omega`.
    ///
    /// `u0` picks `s` so that the strip `[0, s] x [0, 1]` subtends `u0 omega` (closed form;
    /// one Newton step after it below `1e-2` sr, above `2` sr, beyond `kappa = 16` or an
    /// aspect ratio of 16), `u1` picks `t` uniformly in `y / sqrt(d^2 + y^2)` along that
    /// line. Compact strata of the square stay compact. See the [module docs](self) for the
    /// precision (density 1e-4 relative, round trip 1e-4 for `1e-4 .. 2` sr, away from grazing)
    /// and the out-of-domain rule.
    pub fn rectangle, rectangle_x8, rectangle_x16 ["(light, point, sample) triples"]
        (corner: [L; 3], ex: [L; 3], ey: [L; 3], p: [L; 3], u: [L; 2]) -> ([L; 2], L)
            = rectangle::sample_body;
}

/// [`rectangle`] for one light and one shading point over a batch of samples: writes
/// `out[i] = [s, t, density]` for `i < min(u.len(), out.len())` and returns that count.
/// Bit-identical to the scalar form. The light's setup (everything that does not depend on
/// `u`: the frame, the solid angle, the strips beside the rectangle) runs once per call.
#[inline]
pub fn rectangle_slice(
    corner: [f32; 3],
    ex: [f32; 3],
    ey: [f32; 3],
    p: [f32; 3],
    u: &[[f32; 2]],
    out: &mut [[f32; 3]],
) -> usize {
    let prep =
        rectangle::prepare::<slices::Widest>(splat3(corner), splat3(ex), splat3(ey), splat3(p));
    slices::map_lanes(u, out, |u: [slices::Widest; 2]| {
        let (st, d) = rectangle::sample_prepared(&prep, u);
        [st[0], st[1], d]
    })
}

lane_forms! {
    /// Inverse of [`rectangle`]: `u0` is the solid angle of the strip `[0, s] x [0, 1]` over
    /// `omega`, `u1` the fraction of `y / sqrt(d^2 + y^2)` between the edges. Closed form (no
    /// iteration). Round trip within 1e-4 for solid angles `1e-4 .. 2` sr; below
    /// [`AREA_FALLBACK_SR`] it returns `(s, t)` clamped.
    pub fn rectangle_inverse, rectangle_inverse_x8, rectangle_inverse_x16
        ["(light, point, `(s, t)`) triples"]
        (corner: [L; 3], ex: [L; 3], ey: [L; 3], p: [L; 3], st: [L; 2]) -> [L; 2]
            = rectangle::inverse_body;
}

/// [`rectangle_inverse`] for one light and point over a batch, with the length rule of
/// [`rectangle_slice`].
#[inline]
pub fn rectangle_inverse_slice(
    corner: [f32; 3],
    ex: [f32; 3],
    ey: [f32; 3],
    p: [f32; 3],
    st: &[[f32; 2]],
    out: &mut [[f32; 2]],
) -> usize {
    let light =
        rectangle::setup::<slices::Widest>(splat3(corner), splat3(ex), splat3(ey), splat3(p));
    slices::map_lanes(st, out, |st: [slices::Widest; 2]| {
        rectangle::inverse_prepared(&light, st)
    })
}

lane_forms! {
    /// The solid angle of triangle `v` at `p`, in `[0, 2 pi]` (Van Oosterom and Strackee 1983:
    /// `tan(omega / 2) = |a . (b x c)| / (|a||b||c| + (a.b)|c| + (a.c)|b| + (b.c)|a|)`, with
    /// `a, b, c` the vertices relative to `p` and the triple product from edges). Relative
    /// error against `f64` at most `7.7e-7 kappa` measured (see the [module docs](self)). 0 for
    /// degenerate triangles, `p` at a vertex, non-finite input; `p` on the plane inside may give
    /// `2 pi`.
    pub fn triangle_solid_angle, triangle_solid_angle_x8, triangle_solid_angle_x16
        ["(light, point) pairs"]
        (v: [[L; 3]; 3], p: [L; 3]) -> L = triangle::solid_angle_body;
}

lane_forms! {
    /// The solid angle of the rectangle `corner + s ex + t ey` at `p`, in `[0, 2 pi]`: the two
    /// triangles of the rectangle by Van Oosterom-Strackee, added in one `atan2`. Precision and
    /// degenerate cases as [`triangle_solid_angle`].
    pub fn rectangle_solid_angle, rectangle_solid_angle_x8, rectangle_solid_angle_x16
        ["(light, point) pairs"]
        (corner: [L; 3], ex: [L; 3], ey: [L; 3], p: [L; 3]) -> L
            = rectangle::solid_angle_body;
}

lane_forms! {
    /// Uniform in solid angle over the cone that the sphere (`centre`, `radius`) subtends at
    /// `p`: returns a unit direction from `p` and its density with respect to solid angle,
    /// `1 / omega` with `omega = 2 pi (1 - cos theta_max)`.
    ///
    /// **Formula.** `sin^2 theta_max = (r / d)^2` (`d = |centre - p|`), `cos theta_max =
    /// sqrt((d - r)(d + r)) / d`, and `1 - cos theta_max = sin^2 / (1 + cos)`: no `1 - cos`
    /// cancellation, so cones of `1e-8` sr and below keep full relative precision. `u` goes
    /// through the concentric disk ([`crate::disk::concentric`]: signed radius `rho`, angle
    /// `phi`) and the disk onto the cap by area: `1 - cos theta = rho^2 (1 - cos theta_max)`,
    /// `sin theta = sqrt(x (2 - x))` with `x = 1 - cos theta`, the direction `sin theta (cos
    /// phi t + sin phi b) + cos theta n` in the frame of the axis `n` (towards the centre) by
    /// Duff et al. 2017 ("Building an Orthonormal Basis, Revisited", JCGT). The square's centre
    /// is the axis and its boundary the cone's rim, compact strata stay compact (pbrt-v4's
    /// `SampleUniformCone` maps `u0` to the angle and `u1` to the azimuth: thin rings).
    ///
    /// **Precision** (`tests/spherical.rs`, 20 000 random spheres against `f64` on the same
    /// `f32` input, cones from `1e-8` sr to the whole sphere): solid angle and density within
    /// `6e-7 kappa` relative (measured `5.0e-7 kappa`), `kappa = 1 / cos theta_max` the
    /// condition number of the solid angle for relative changes of `d` and `r` (large only for
    /// `p` within a small fraction of the radius above the surface); the polar angle of the
    /// direction within `3e-7` rad of the `f64` map's (measured `2.4e-7`: at `1e-8` sr that
    /// is `2e-3` of `theta_max`, the resolution of `f32` directions); round trip
    /// [`cone_inverse`]`(cone(u))` within `1e-4` of `u` for cones of at least `1e-4` sr
    /// (measured `2.5e-5`).
    ///
    /// **Out of domain.** `u` is clamped as everywhere. `radius` counts by magnitude (NaN is
    /// non-finite). `p` inside the sphere (`d < r`, or `p` at the centre) sees every direction:
    /// uniform sphere, density `1 / (4 pi)` (`omega = 4 pi`); `p` on the surface sees a
    /// hemisphere (`2 pi`). A zero radius, or one below `2^-60` of the distance (a point
    /// light, `omega < 2.9e-36` sr), gives every `u` the axis and density 0; NaN or inf
    /// anywhere, a radius or coordinate differences of `2^127` or more, or a zero radius at
    /// `p = centre` give `+z` and density 0. Coordinates and differences below `2^-126` count as zero (as in
    /// the other lights). The density is never NaN, infinite or `FLT_MAX`.
    pub fn cone, cone_x8, cone_x16 ["(sphere, point, sample) triples"]
        (centre: [L; 3], radius: L, p: [L; 3], u: [L; 2]) -> ([L; 3], L) = cone::sample_body;
}

/// [`cone`] for one sphere and one shading point over a batch of samples: writes `out[i] =
/// [x, y, z, density]` of `cone(centre, radius, p, u[i])` for `i < min(u.len(), out.len())`
/// and returns that count. Bit-identical to the scalar form; the cone's setup runs once.
#[inline]
pub fn cone_slice(
    centre: [f32; 3],
    radius: f32,
    p: [f32; 3],
    u: &[[f32; 2]],
    out: &mut [[f32; 4]],
) -> usize {
    let c = cone::setup::<slices::Widest>(splat3(centre), slices::Widest::splat(radius), splat3(p));
    slices::map_lanes(u, out, |u: [slices::Widest; 2]| {
        let (d, pdf) = cone::sample_prepared(&c, u);
        [d[0], d[1], d[2], pdf]
    })
}

lane_forms! {
    /// Inverse of [`cone`]: the `u` whose direction is `dir` (any length; normalised after an
    /// exact power-of-two scaling): `x = 1 - cos theta` from `sin^2 / (1 + cos)` (or `1 - cos`
    /// behind), the disk point `(dir . t, dir . b) / sqrt(omega' (2 - x))` with `omega' = 1 -
    /// cos theta_max`, then [`crate::disk::concentric_inverse`]. Round trip within 1e-4 for
    /// cones of at least `1e-4` sr (see [`cone`]). Directions outside the cone go to its rim
    /// at the same azimuth, zero or non-finite `dir` to the axis (`u = (1/2, 1/2)`); for a
    /// sphere of solid angle 0 the result is `(1/2, 1/2)`. In `[0, 1 - 2^-24]^2`.
    pub fn cone_inverse, cone_inverse_x8, cone_inverse_x16
        ["(sphere, point, direction) triples"]
        (centre: [L; 3], radius: L, p: [L; 3], dir: [L; 3]) -> [L; 2] = cone::inverse_body;
}

/// [`cone_inverse`] for one sphere and point over a batch, with the length rule of
/// [`cone_slice`].
#[inline]
pub fn cone_inverse_slice(
    centre: [f32; 3],
    radius: f32,
    p: [f32; 3],
    dir: &[[f32; 3]],
    out: &mut [[f32; 2]],
) -> usize {
    let c = cone::setup::<slices::Widest>(splat3(centre), slices::Widest::splat(radius), splat3(p));
    slices::map_lanes(dir, out, |d: [slices::Widest; 3]| {
        cone::inverse_prepared(&c, d)
    })
}

lane_forms! {
    /// The solid angle of the sphere (`centre`, `radius`) at `p`: `2 pi sin^2 theta_max /
    /// (1 + cos theta_max)` in `[0, 2 pi]` outside the sphere, `4 pi` inside; 0 where [`cone`]
    /// says (point lights, non-finite input). Relative error as [`cone`]'s density.
    pub fn cone_solid_angle, cone_solid_angle_x8, cone_solid_angle_x16
        ["(sphere, point) pairs"]
        (centre: [L; 3], radius: L, p: [L; 3]) -> L = cone::solid_angle_body;
}

/// The bilinear density on the unit square with corner weights `w = [w00, w10, w01, w11]`
/// (`w_xy` the weight at `(x, y)`), normalised: `4 ((1-x)(1-y) w00 + x(1-y) w10 +
/// (1-x) y w01 + x y w11) / (w00 + w10 + w01 + w11)`. The density of [`bilinear`]'s points. `p` is
/// clamped to `[0, 1]^2` (NaN to 0); negative and NaN weights count as 0; weights whose sum is
/// below `2^-126` (the smallest normal `f32`, where `1 / sum` would overflow and a GPU that
/// flushes subnormals sees 0) or not finite give 1, the uniform density [`bilinear`] falls
/// back to.
#[inline]
pub fn bilinear_pdf(p: [f32; 2], w: [f32; 4]) -> f32 {
    cosine::bilinear_pdf_body(p, w)
}

/// Warps `u` by the bilinear density of [`bilinear_pdf`] (the marginal in `y`, then the
/// conditional in `x`, both linear, inverted in closed form without cancellation: `x = u (a +
/// b) / (a + sqrt((1 - u) a^2 + u b^2))`). Returns the point, in `[0, 1 - 2^-24]^2`, and its
/// density. An exact bijection of the open square, so composing it with a map and
/// multiplying the densities stays unbiased. `u` is clamped as everywhere; weights whose sum
/// is below `2^-126` or not finite leave `u` unchanged with density 1. Hart et al. 2020,
/// "Practical Product Sampling by Fitting and Composing Warps" (EGSR).
#[inline]
pub fn bilinear(u: [f32; 2], w: [f32; 4]) -> ([f32; 2], f32) {
    cosine::bilinear_body(u, w)
}

lane_forms! {
    /// Cosine-aware [`triangle`]: `u` is first warped by [`bilinear`] with weights the
    /// receiver's clamped cosine `max(0, n . w_i)` towards the vertices, where the square's corners
    /// `(0, 0), (1, 0), (0, 1), (1, 1)` land under Arvo's map (`v1, v1, v0, v2`), then mapped by
    /// [`triangle`]. Returns the barycentrics and the density with respect to solid angle,
    /// `bilinear_pdf(u') / omega` (`u'` the warped point), so the estimator `f cos / pdf` has
    /// the receiver's cosine mostly divided out (Hart et al. 2020; pbrt-v4's triangle light).
    ///
    /// `n` need not be unit length (only the weights' ratios matter). Where all weights are 0
    /// (the light wholly below the receiver's horizon) or `n` is zero or not finite, the result
    /// is [`triangle`]'s, bit for bit. The density is 0 where [`triangle`]'s is, and on sides of
    /// the square whose two corner weights are 0 (points where the receiver's cosine is 0 too).
    /// `docs/REPORT.md` measures when it pays: lit pixels at size / distance 1 and below;
    /// structured points lose a little to it very close to a light (ratio 4).
    pub fn triangle_cosine, triangle_cosine_x8, triangle_cosine_x16
        ["(light, point, normal, sample) tuples"]
        (v: [[L; 3]; 3], p: [L; 3], n: [L; 3], u: [L; 2]) -> ([L; 3], L)
            = cosine::triangle_body;
}

/// [`triangle_cosine`] for one light, point and normal over a batch: `out[i] = [b0, b1, b2,
/// density]` for `i < min(u.len(), out.len())`, returns that count; the light's setup and
/// the weights once per call. Bit-identical to the scalar form.
#[inline]
pub fn triangle_cosine_slice(
    v: [[f32; 3]; 3],
    p: [f32; 3],
    n: [f32; 3],
    u: &[[f32; 2]],
    out: &mut [[f32; 4]],
) -> usize {
    let prep = triangle::prepare::<slices::Widest>(splat33(v), splat3(p));
    let w = cosine::triangle_weights(&prep.t, splat3(n));
    slices::map_lanes(u, out, |u: [slices::Widest; 2]| {
        let (b, d) = cosine::warped(&prep, w, u, triangle::sample_prepared);
        [b[0], b[1], b[2], d]
    })
}

lane_forms! {
    /// Cosine-aware [`rectangle`]: `u` warped by [`bilinear`] with weights `max(0, n . w_i)`
    /// towards `corner`, `corner + ex`, `corner + ey`, `corner + ex + ey` (the images of the
    /// square's corners `(0, 0), (1, 0), (0, 1), (1, 1)`), then mapped by [`rectangle`]; the
    /// density is `bilinear_pdf(u') / omega`. Rules as [`triangle_cosine`].
    pub fn rectangle_cosine, rectangle_cosine_x8, rectangle_cosine_x16
        ["(light, point, normal, sample) tuples"]
        (corner: [L; 3], ex: [L; 3], ey: [L; 3], p: [L; 3], n: [L; 3], u: [L; 2])
            -> ([L; 2], L) = cosine::rectangle_body;
}

/// [`rectangle_cosine`] for one light, point and normal over a batch: `out[i] = [s, t,
/// density]`, with the length rule of [`triangle_cosine_slice`]. Bit-identical to the scalar
/// form.
#[inline]
pub fn rectangle_cosine_slice(
    corner: [f32; 3],
    ex: [f32; 3],
    ey: [f32; 3],
    p: [f32; 3],
    n: [f32; 3],
    u: &[[f32; 2]],
    out: &mut [[f32; 3]],
) -> usize {
    let prep =
        rectangle::prepare::<slices::Widest>(splat3(corner), splat3(ex), splat3(ey), splat3(p));
    let w = cosine::rectangle_weights(&prep.r, splat3(n));
    slices::map_lanes(u, out, |u: [slices::Widest; 2]| {
        let (st, d) = cosine::warped(&prep, w, u, rectangle::sample_prepared);
        [st[0], st[1], d]
    })
}

#[cfg(test)]
mod tests {
    use crate::vec3::sub;
    use rand_xoshiro::Xoshiro256PlusPlus;
    use warpcore_testkit::{rng, unit};

    /// Values that probe the finiteness rules: zeros, subnormals (flushed), the largest
    /// difference the scaling accepts (`2^127 - 2^103`) and the smallest it rejects (`2^127`),
    /// `f32::MAX`, infinities and NaN.
    const SPECIAL: [f32; 16] = [
        0.0,
        -0.0,
        1.0,
        -0.75,
        1e-40,
        -1e-44,
        f32::MIN_POSITIVE,
        1.7014117e38,
        -1.7014117e38,
        1.7014118e38,
        f32::MAX,
        -f32::MAX,
        f32::INFINITY,
        f32::NEG_INFINITY,
        f32::NAN,
        1e-30,
    ];

    /// Half specials, half ordinary values in `+-[1e-3, 1e3]`.
    fn value(r: &mut Xoshiro256PlusPlus) -> f32 {
        let pick = unit(r);
        if pick < 0.5 {
            SPECIAL[(pick * 2.0 * SPECIAL.len() as f32) as usize]
        } else {
            let x = 10f32.powf(unit(r) * 6.0 - 3.0);
            if pick < 0.75 { x } else { -x }
        }
    }

    fn finite(v: [f32; 3]) -> bool {
        v.iter().all(|x| x.is_finite())
    }

    /// The set-ups test finiteness only where it is not implied: a light they accept (`ok`)
    /// has finite differences `v_i - p` and edges (triangle) and finite `corner - p`, `ex`, `ey`
    /// (rectangle), including at the scaling's limit, where an edge between two differences
    /// just below `2^127` of opposite signs must not round to infinity.
    #[test]
    fn accepted_lights_have_finite_differences() {
        let mut r = rng(7);
        let mut accepted = [0u32; 2];
        for _ in 0..400_000 {
            let mut v3 = || [value(&mut r), value(&mut r), value(&mut r)];
            let (v, p) = ([v3(), v3(), v3()], v3());
            if super::triangle::setup::<f32>(v, p).ok {
                accepted[0] += 1;
                let d = [sub(v[0], p), sub(v[1], p), sub(v[2], p)];
                let e = [sub(v[1], v[0]), sub(v[2], v[0]), sub(v[2], v[1])];
                assert!(d.iter().chain(&e).all(|&x| finite(x)), "{v:?} {p:?}");
            }
            let (c, ex, ey) = (v[0], v[1], v[2]);
            if super::rectangle::setup::<f32>(c, ex, ey, p).ok {
                accepted[1] += 1;
                assert!(finite(sub(c, p)) && finite(ex) && finite(ey), "{v:?} {p:?}");
            }
        }
        // Enough accepted lights for the assertions to mean something.
        assert!(accepted.iter().all(|&n| n > 1000), "{accepted:?}");
        // At the limit: differences of `+-(2^127 - 2^103)` are accepted, and their edge is
        // `f32::MAX`, not infinity.
        let big = 1.7014117e38f32;
        let v = [[big, 0.0, 0.0], [-big, 0.0, 0.0], [0.0, big, 0.0]];
        assert!(super::triangle::setup::<f32>(v, [0.0, 0.0, 1.0]).ok);
        assert_eq!(v[0][0] - v[1][0], f32::MAX);
    }
}
