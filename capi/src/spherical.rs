//! Lights by solid angle: spherical triangles (Arvo 1995) and rectangles (Urena, Fajardo and
//! King 2013). Each call takes one light and one shading point as 12 floats, `light`:
//! `v0, v1, v2, p` (triangle) or `corner, ex, ey, p` (rectangle, the point
//! `corner + s ex + t ey`), read before anything is written (so `light` may even overlap
//! `out`); the cosine-aware variants take 15, the receiver's normal `n` after `p`. See
//! `warpcore::spherical` for the maps, their precision and the degenerate cases (density 0
//! where the solid angle is 0). Sphere lights (`wc_spherical_cone*`) take 7 floats,
//! `centre, radius, p`.

use warpcore::spherical;

/// `n` inputs of `I` floats to `n` outputs of `O` floats through a slice form
/// `f(light, input, out)` of the `K` vectors at `light` (read first, so `light` may overlap
/// `out`). Returns `n`, or 0 (writing nothing) for a null or misaligned `light`, then as
/// `map`.
///
/// # Safety
/// `light` must be readable for `3 K` floats, `input` for `I n` and `out` writable for
/// `O n`.
unsafe fn lit<const K: usize, const I: usize, const O: usize>(
    light: *const f32,
    input: *const f32,
    out: *mut f32,
    n: usize,
    f: impl Fn([[f32; 3]; K], &[[f32; I]], &mut [[f32; O]]) -> usize,
) -> usize {
    // SAFETY: the caller's contract, passed on.
    let l = unsafe { read_vectors::<K>(light) };
    // SAFETY: the caller's contract, passed on.
    unsafe { lit_read(l, input, out, n, f) }
}

/// [`lit`] with the light already read (`None`: null or misaligned, 0 returned).
///
/// # Safety
/// `input` must be readable for `I n` floats and `out` writable for `O n`.
unsafe fn lit_read<T: Copy, const I: usize, const O: usize>(
    light: Option<T>,
    input: *const f32,
    out: *mut f32,
    n: usize,
    f: impl Fn(T, &[[f32; I]], &mut [[f32; O]]) -> usize,
) -> usize {
    let Some(l) = light else {
        return 0;
    };
    // SAFETY: the caller's contract; `map` checks null, alignment, size and overlap.
    unsafe { crate::ffi::map::<f32, f32, I, O>(input, out, n, |i, o| f(l, i, o)) }
}

/// The 12 floats at `light`, or `None` for a null or misaligned pointer.
///
/// # Safety
/// `light` must be readable for 12 floats.
unsafe fn read_light(light: *const f32) -> Option<[[f32; 3]; 4]> {
    // SAFETY: the caller's contract, passed on.
    unsafe { read_vectors::<4>(light) }
}

/// The `3 K` floats at `light` as `K` vectors, or `None` for a null or misaligned pointer.
///
/// # Safety
/// `light` must be readable for `3 K` floats.
unsafe fn read_vectors<const K: usize>(light: *const f32) -> Option<[[f32; 3]; K]> {
    // SAFETY: the caller's contract; `slice` checks null, alignment and size. The slice is
    // copied at once and dropped before anything is written.
    let s = unsafe { crate::ffi::slice(light, 3 * K, None)? };
    let mut l = [[0.0f32; 3]; K];
    for (k, x) in s.iter().enumerate() {
        l[k / 3][k % 3] = *x;
    }
    Some(l)
}

/// Uniform in solid angle over triangle `light[0..9]` seen from `light[9..12]`: `n` points
/// `u` (`2n` floats) to `n` records `b0, b1, b2, density` (`4n` floats; barycentrics
/// weighting the vertices, density with respect to solid angle). Returns `n`, or 0 (writing
/// nothing) for a null or misaligned pointer, a size past `PTRDIFF_MAX` or overlapping `u`
/// and `out`.
///
/// # Safety
/// `light` must be readable for 12 floats, `u` for `2n` and `out` writable for `4n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_triangle(
    light: *const f32,
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, u, out, n, |[v0, v1, v2, p], u, o| {
            spherical::triangle_slice([v0, v1, v2], p, u, o)
        })
    }
}

/// Inverse of `wc_spherical_triangle`: `n` barycentrics (`3n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned
/// pointer, a size past `PTRDIFF_MAX` or overlapping arrays other than `b == out`.
///
/// # Safety
/// `light` must be readable for 12 floats, `b` for `3n` and `out` writable for `2n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_triangle_inverse(
    light: *const f32,
    b: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, b, out, n, |[v0, v1, v2, p], b, o| {
            spherical::triangle_inverse_slice([v0, v1, v2], p, b, o)
        })
    }
}

/// Uniform in solid angle over the rectangle `corner + s ex + t ey` (`light[0..9]`) seen
/// from `light[9..12]`: `n` points `u` (`2n` floats) to `n` records `s, t, density` (`3n`
/// floats). Returns `n`, or 0 as for `wc_spherical_triangle`.
///
/// # Safety
/// `light` must be readable for 12 floats, `u` for `2n` and `out` writable for `3n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_rectangle(
    light: *const f32,
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, u, out, n, |[c, ex, ey, p], u, o| {
            spherical::rectangle_slice(c, ex, ey, p, u, o)
        })
    }
}

/// Inverse of `wc_spherical_rectangle`: `n` pairs `s, t` (`2n` floats) to `n` points of the
/// square (`2n` floats). Returns `n`, or 0 (writing nothing) for a null or misaligned
/// pointer, a size past `PTRDIFF_MAX` or overlapping arrays other than `st == out`.
///
/// # Safety
/// `light` must be readable for 12 floats, `st` for `2n` and `out` writable for `2n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_rectangle_inverse(
    light: *const f32,
    st: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, st, out, n, |[c, ex, ey, p], s, o| {
            spherical::rectangle_inverse_slice(c, ex, ey, p, s, o)
        })
    }
}

/// The solid angle of triangle `light[0..9]` at `light[9..12]`, in `[0, 2 pi]`; 0 for a
/// null or misaligned `light` (and for degenerate triangles, see `warpcore::spherical`).
///
/// # Safety
/// `light` must be readable for 12 floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_triangle_solid_angle(light: *const f32) -> f32 {
    // SAFETY: the caller's contract above.
    match unsafe { read_light(light) } {
        Some([v0, v1, v2, p]) => spherical::triangle_solid_angle([v0, v1, v2], p),
        None => 0.0,
    }
}

/// The solid angle of the rectangle `light[0..9]` at `light[9..12]`, in `[0, 2 pi]`; 0 for a
/// null or misaligned `light`.
///
/// # Safety
/// `light` must be readable for 12 floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_rectangle_solid_angle(light: *const f32) -> f32 {
    // SAFETY: the caller's contract above.
    match unsafe { read_light(light) } {
        Some([c, ex, ey, p]) => spherical::rectangle_solid_angle(c, ex, ey, p),
        None => 0.0,
    }
}

/// Cosine-aware `wc_spherical_triangle`: `light` is 15 floats, `v0, v1, v2, p, n` (`n` the
/// receiver's normal, any length); `u` is first warped by the bilinear density of the
/// receiver's clamped cosine towards the vertices, then mapped as by
/// `wc_spherical_triangle`; records `b0, b1, b2, density` (`4n` floats), the density
/// including the bilinear factor (`warpcore::spherical::triangle_cosine`). Returns `n`, or 0
/// as for `wc_spherical_triangle`.
///
/// # Safety
/// `light` must be readable for 15 floats, `u` for `2n` and `out` writable for `4n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_triangle_cosine(
    light: *const f32,
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, u, out, n, |[v0, v1, v2, p, nrm], u, o| {
            spherical::triangle_cosine_slice([v0, v1, v2], p, nrm, u, o)
        })
    }
}

/// Cosine-aware `wc_spherical_rectangle`: `light` is 15 floats, `corner, ex, ey, p, n`;
/// records `s, t, density` (`3n` floats), the density including the bilinear factor
/// (`warpcore::spherical::rectangle_cosine`). Returns `n`, or 0 as for
/// `wc_spherical_triangle`.
///
/// # Safety
/// `light` must be readable for 15 floats, `u` for `2n` and `out` writable for `3n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_rectangle_cosine(
    light: *const f32,
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above; `lit` checks `light`, `map` the arrays.
    unsafe {
        lit(light, u, out, n, |[c, ex, ey, p, nrm], u, o| {
            spherical::rectangle_cosine_slice(c, ex, ey, p, nrm, u, o)
        })
    }
}

/// The 7 floats of a sphere light at `light` (`centre, radius, p`), or `None` for a null or
/// misaligned pointer.
///
/// # Safety
/// `light` must be readable for 7 floats.
unsafe fn read_sphere(light: *const f32) -> Option<([f32; 3], f32, [f32; 3])> {
    // SAFETY: the caller's contract; `slice` checks null, alignment and size. The slice is
    // copied at once and dropped before anything is written.
    let s = unsafe { crate::ffi::slice(light, 7, None)? };
    let mut l = [0.0f32; 7];
    l.copy_from_slice(s.get(..7)?);
    Some(([l[0], l[1], l[2]], l[3], [l[4], l[5], l[6]]))
}

/// A sphere light's slice form: `(centre, radius, p, input, out) -> count`.
type SphereSlice<const I: usize, const O: usize> =
    fn([f32; 3], f32, [f32; 3], &[[f32; I]], &mut [[f32; O]]) -> usize;

/// [`lit`] for a sphere light (7 floats) and a slice form `f(centre, radius, p, input, out)`.
///
/// # Safety
/// `light` must be readable for 7 floats, `input` for `I n` and `out` writable for `O n`.
unsafe fn sphere_lit<const I: usize, const O: usize>(
    light: *const f32,
    input: *const f32,
    out: *mut f32,
    n: usize,
    f: SphereSlice<I, O>,
) -> usize {
    // SAFETY: the caller's contract; `read_sphere` checks `light`, `map` the arrays.
    unsafe {
        let l = read_sphere(light);
        lit_read(l, input, out, n, |(c, r, p), i, o| f(c, r, p, i, o))
    }
}

/// Uniform in solid angle over the cone that the sphere `light[0..3]` (centre), `light[3]`
/// (radius) subtends at `light[4..7]`: `n` points `u` (`2n` floats) to `n` records `x, y, z,
/// density` (`4n` floats; a unit direction from the shading point, density with respect to
/// solid angle: `1 / (4 pi)` inside the sphere, 0 for a point light, see
/// `warpcore::spherical::cone`). Returns `n`, or 0 as for `wc_spherical_triangle`.
///
/// # Safety
/// `light` must be readable for 7 floats, `u` for `2n` and `out` writable for `4n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_cone(
    light: *const f32,
    u: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above, passed on.
    unsafe { sphere_lit(light, u, out, n, spherical::cone_slice) }
}

/// Inverse of `wc_spherical_cone`: `n` directions (`3n` floats, any length) to `n` points of
/// the square (`2n` floats). Returns `n`, or 0 as for `wc_spherical_triangle_inverse`.
///
/// # Safety
/// `light` must be readable for 7 floats, `dir` for `3n` and `out` writable for `2n`.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_cone_inverse(
    light: *const f32,
    dir: *const f32,
    out: *mut f32,
    n: usize,
) -> usize {
    // SAFETY: the caller's contract above, passed on.
    unsafe { sphere_lit(light, dir, out, n, spherical::cone_inverse_slice) }
}

/// The solid angle of the sphere `light[0..4]` (centre, radius) at `light[4..7]`: in `[0, 2
/// pi]` outside, `4 pi` inside; 0 for a null or misaligned `light` (and for point lights).
///
/// # Safety
/// `light` must be readable for 7 floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_spherical_cone_solid_angle(light: *const f32) -> f32 {
    // SAFETY: the caller's contract above.
    match unsafe { read_sphere(light) } {
        Some((c, r, p)) => spherical::cone_solid_angle(c, r, p),
        None => 0.0,
    }
}
