//! # warpcore C ABI
//!
//! The functions of `include/warpcore.h`: every warp family of the `warpcore` crate as plain C
//! functions over interleaved `float` arrays, bit-identical to the Rust crate. See
//! `docs/capi.md` for the conventions; in short:
//!
//! * names `wc_<family>_<warp>`; counts are `size_t`; `n` points are `2n` or `3n` floats,
//!   interleaved (`x0 y0 x1 y1 ...`);
//! * every function returns the number of elements it wrote; `n == 0`, a null pointer with
//!   `n > 0`, a pointer not aligned for its type, and overlapping input and output (other
//!   than exactly in place with an output no larger than the input) return 0 and write
//!   nothing;
//! * the environment-map builders return 0 or a negative `WC_ERR_*` code;
//! * nothing unwinds into C: the library is built with `panic = "abort"` and the core crate
//!   has no reachable panic.
//!
//! The core crate is `#![forbid(unsafe_code)]`; the only `unsafe` is here, in the pointer
//! handling of `ffi.rs` and in each exported function's call into it, each with its safety
//! argument.
// `no_std` wherever panics abort (release builds: the library you ship links no `std`).
// Builds that unwind (the dev and test profiles) need `std`'s panic runtime; there a panic
// inside an `extern "C"` function aborts too, since Rust 1.81.
#![cfg_attr(panic = "abort", no_std)]
#![deny(unsafe_op_in_unsafe_fn)]
// Builds with only some families leave some pointer helpers unused.
#![cfg_attr(
    not(all(
        feature = "disk",
        feature = "triangle",
        feature = "sphere",
        feature = "pmj02bn",
        feature = "sequence",
        feature = "envmap"
    )),
    allow(dead_code)
)]
#![warn(missing_docs)]

mod ffi;

#[cfg(feature = "disk")]
pub mod disk;
#[cfg(feature = "envmap")]
pub mod envmap;
#[cfg(feature = "lights")]
pub mod lights;
#[cfg(all(feature = "lights", feature = "envmap"))]
pub mod lights_tree;
#[cfg(feature = "microfacet")]
pub mod microfacet;
#[cfg(feature = "pmj02bn")]
pub mod pmj02bn;
#[cfg(feature = "sampler")]
pub mod sampler;
#[cfg(feature = "sequence")]
pub mod sequence;
#[cfg(feature = "sphere")]
pub mod sphere;
#[cfg(feature = "spherical")]
pub mod spherical;
#[cfg(feature = "triangle")]
pub mod triangle;

// The library never panics (the core crate's functions are total and this crate checks every
// pointer and count first), and is built with `panic = "abort"`; should a panic happen
// anyway, abort the process (C's `abort`) rather than unwind into C.
#[cfg(panic = "abort")]
unsafe extern "C" {
    fn abort() -> !;
}

// The precompiled `core` is built to unwind, so its objects refer to the unwinding
// personality routine, which only `std` defines. Nothing unwinds in a `panic = "abort"` build:
// this definition is never called and only satisfies the linker. (Not on wasm32, where
// `core` is built with `panic = "abort"`: the JavaScript module would export it.)
#[cfg(all(panic = "abort", not(target_family = "wasm")))]
#[unsafe(no_mangle)]
extern "C" fn rust_eh_personality() {}

#[cfg(panic = "abort")]
#[panic_handler]
fn panic(_: &core::panic::PanicInfo) -> ! {
    // SAFETY: C's `abort` takes no arguments, has no preconditions and does not return.
    unsafe { abort() }
}
