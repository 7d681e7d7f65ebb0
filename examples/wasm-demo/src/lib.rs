//! warpcore in a minimal `no_std` WebAssembly module: no imports, no allocator.
//!
//! Exports: `fingerprint()` (see `warpcore_registry::fingerprint`), and small per-family entry points that a
//! browser or Node can call directly, e.g. `disk_concentric(u0, u1, k)` returns coordinate
//! `k` (0 or 1) of the concentric map.
#![cfg_attr(target_arch = "wasm32", no_std)]

#[cfg(feature = "all")]
pub use warpcore_registry::fingerprint;

/// The determinism fingerprint of every family compiled in.
#[cfg(feature = "all")]
#[unsafe(no_mangle)]
pub extern "C" fn fingerprint() -> u64 {
    fingerprint::fingerprint()
}

/// The same fingerprint computed with the `_x16` forms in place of the `_x8` ones.
#[cfg(feature = "all")]
#[unsafe(no_mangle)]
pub extern "C" fn fingerprint_x16() -> u64 {
    fingerprint::fingerprint_x16()
}

#[cfg(feature = "disk")]
#[unsafe(no_mangle)]
pub extern "C" fn disk_concentric(u0: f32, u1: f32, k: u32) -> f32 {
    let p = warpcore::disk::concentric([u0, u1]);
    if k == 0 { p[0] } else { p[1] }
}

#[cfg(feature = "sphere")]
#[unsafe(no_mangle)]
pub extern "C" fn sphere_equal_area(u0: f32, u1: f32, k: u32) -> f32 {
    let d = warpcore::sphere::equal_area([u0, u1]);
    match k {
        0 => d[0],
        1 => d[1],
        _ => d[2],
    }
}

#[cfg(feature = "all")]
#[unsafe(no_mangle)]
pub extern "C" fn disk_polar4(u0: f32, u1: f32, quadrant: u32, k: u32) -> f32 {
    let p = warpcore::disk::polar4([u0, u1], quadrant);
    if k == 0 { p[0] } else { p[1] }
}

#[cfg(any(feature = "all", feature = "probe-concentric4"))]
#[unsafe(no_mangle)]
pub extern "C" fn disk_concentric4(u0: f32, u1: f32, quadrant: u32, k: u32) -> f32 {
    let p = warpcore::disk::concentric4([u0, u1], quadrant);
    if k == 0 { p[0] } else { p[1] }
}

#[cfg(any(feature = "all", feature = "probe-basu-owen"))]
#[unsafe(no_mangle)]
pub extern "C" fn triangle_basu_owen(index: u32, seed: u32, k: u32) -> f32 {
    let b = warpcore::triangle::basu_owen(index, seed);
    match k {
        0 => b[0],
        1 => b[1],
        _ => b[2],
    }
}

#[cfg(any(feature = "all", feature = "probe-basu-owen-permuted"))]
#[unsafe(no_mangle)]
pub extern "C" fn triangle_basu_owen_permuted(index: u32, seed: u32, k: u32) -> f32 {
    let b = warpcore::triangle::basu_owen_permuted(index, seed);
    match k {
        0 => b[0],
        1 => b[1],
        _ => b[2],
    }
}

#[cfg(feature = "pmj02bn")]
#[unsafe(no_mangle)]
pub extern "C" fn pmj02bn_sample(index: u32, seed: u32, k: u32) -> f32 {
    let p = warpcore::pmj02bn::sample(index, seed);
    if k == 0 { p[0] } else { p[1] }
}

/// Dimension `k` (0..3) of a 4D draw from domain `key` of `Sampler<P>` (pixel `(x, y)`,
/// frame 0, seed 0): the sampler exports below.
#[cfg(feature = "sampler")]
fn sampler_draw<P: warpcore::sampler::Pattern>(
    x: u32,
    y: u32,
    index: u32,
    key: u32,
    k: u32,
) -> f32 {
    warpcore::sampler::Sampler::<P>::new([x, y], 0, index, 0)
        .domain(key)
        .draw::<4>()[k as usize & 3]
}

/// Dimension `k` (0..3) of a 4D draw from domain `key` of `Sampler<Sobol>`.
#[cfg(any(feature = "all", feature = "probe-sampler-sobol"))]
#[unsafe(no_mangle)]
pub extern "C" fn sampler_sobol(x: u32, y: u32, index: u32, key: u32, k: u32) -> f32 {
    sampler_draw::<warpcore::sampler::Sobol>(x, y, index, key, k)
}

/// Dimension `k` (0..3) of a 4D draw from domain `key` of `Sampler<Pmj02bn>`.
#[cfg(any(feature = "all", feature = "probe-sampler-pmj02bn"))]
#[unsafe(no_mangle)]
pub extern "C" fn sampler_pmj02bn(x: u32, y: u32, index: u32, key: u32, k: u32) -> f32 {
    sampler_draw::<warpcore::sampler::Pmj02bn>(x, y, index, key, k)
}

/// Dimension `k` (0..3) of a 4D draw from domain `key` of `Sampler<Blue<Sobol>>`.
#[cfg(any(feature = "all", feature = "probe-sampler-blue"))]
#[unsafe(no_mangle)]
pub extern "C" fn sampler_blue_sobol(x: u32, y: u32, index: u32, key: u32, k: u32) -> f32 {
    use warpcore::sampler::{Blue, Sobol};
    sampler_draw::<Blue<Sobol>>(x, y, index, key, k)
}

/// Coordinate `k` (0..2 barycentrics, 3 the density) of a point sampled by solid angle on the
/// triangle `(0,0,1) (1,0,1) (0,1,1)` seen from `(x, y, 0)`.
#[cfg(any(feature = "all", feature = "probe-spherical-triangle"))]
#[unsafe(no_mangle)]
pub extern "C" fn spherical_triangle(x: f32, y: f32, u0: f32, u1: f32, k: u32) -> f32 {
    let v = [[0.0, 0.0, 1.0], [1.0, 0.0, 1.0], [0.0, 1.0, 1.0]];
    let (b, pdf) = warpcore::spherical::triangle(v, [x, y, 0.0], [u0, u1]);
    [b[0], b[1], b[2], pdf][k as usize & 3]
}

/// Coordinate `k` (0..1 the fractions, 2 the density) of a point sampled by solid angle on the
/// unit square at height 1 seen from `(x, y, 0)`.
#[cfg(any(feature = "all", feature = "probe-spherical-rectangle"))]
#[unsafe(no_mangle)]
pub extern "C" fn spherical_rectangle(x: f32, y: f32, u0: f32, u1: f32, k: u32) -> f32 {
    let (c, ex, ey) = ([0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let (st, pdf) = warpcore::spherical::rectangle(c, ex, ey, [x, y, 0.0], [u0, u1]);
    [st[0], st[1], pdf, pdf][k as usize & 3]
}

// The no-panic proof: this function is never defined. If any code path that can panic is
// linked into the module, the panic handler (and with it this symbol) is kept, and the wasm
// module gains an import `env.warpcore_panic_path_reached`. `tools/wasm-demo.mjs` loads the
// module with an empty import object, so any such path fails CI.
#[cfg(all(target_arch = "wasm32", not(test)))]
unsafe extern "C" {
    fn warpcore_panic_path_reached() -> !;
}

#[cfg(all(target_arch = "wasm32", not(test)))]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: never called at run time; see above.
    unsafe { warpcore_panic_path_reached() }
}
