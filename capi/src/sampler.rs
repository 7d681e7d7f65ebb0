//! The sampling core: every dimension of a path from one small value per sample. `WcSampler`
//! mirrors the Rust crate's `Sampler<P>` (its three words and the pattern): derive children
//! by value with `wc_sampler_domain` and `wc_sampler_split`, draw from any of them.

use crate::ffi::{generate, span};
use warpcore::sampler::{Pattern, Pmj02bn, Sampler, Sobol};

/// Owen-scrambled pmj02bn points: a draw of up to four dimensions is two independent (0,2)
/// pairs (dimensions 0-1 and 2-3).
pub const WC_PATTERN_PMJ02BN: u32 = 0;
/// Owen-scrambled Sobol' dimensions 0..3 (0-1 a (0,2)-sequence).
pub const WC_PATTERN_SOBOL: u32 = 1;
/// pmj02bn with screen-space blue-noise error across pixels (feature `blue-noise`).
pub const WC_PATTERN_BLUE_PMJ02BN: u32 = 2;
/// Sobol' with screen-space blue-noise error across pixels (feature `blue-noise`).
pub const WC_PATTERN_BLUE_SOBOL: u32 = 3;

/// One sample's sampler: a pattern, a pixel, a domain path and a sample index, in 16 bytes.
/// A plain value: copy it, derive children from it, draw from it, from any thread.
///
/// `pattern` is a `WC_PATTERN_*` constant; `index` is the sample index (after any split) and
/// may be set directly (another index in the same domain: Rust's `with_index`); `pixel` and
/// `domain` are hashes only this library reads. Any bits are safe: a sampler whose `pattern`
/// is not a pattern of this build (garbage, or a blue-noise pattern in a build without the
/// `blue-noise` feature) is carried through `wc_sampler_domain` and `wc_sampler_split`
/// unchanged, and every draw from it returns 0 and writes nothing.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct WcSampler {
    /// A `WC_PATTERN_*` constant.
    pub pattern: u32,
    /// The pixel (opaque: 16 bits of `x` and of `y`).
    pub pixel: u32,
    /// The domain path's hash (opaque).
    pub domain: u32,
    /// The sample index.
    pub index: u32,
}

impl WcSampler {
    fn of<P: Pattern>(pattern: u32, s: Sampler<P>) -> Self {
        let [pixel, domain, index] = s.to_words();
        WcSampler {
            pattern,
            pixel,
            domain,
            index,
        }
    }

    fn get<P: Pattern>(self) -> Sampler<P> {
        Sampler::from_words([self.pixel, self.domain, self.index])
    }
}

/// Runs `$body` with the type alias `$P` set to the pattern `$pattern` names, or evaluates
/// `$unknown` for a value that is not a pattern of this build.
macro_rules! with_pattern {
    ($pattern:expr, $P:ident => $body:expr, _ => $unknown:expr) => {
        match $pattern {
            WC_PATTERN_PMJ02BN => {
                type $P = Pmj02bn;
                $body
            }
            WC_PATTERN_SOBOL => {
                type $P = Sobol;
                $body
            }
            #[cfg(feature = "blue-noise")]
            WC_PATTERN_BLUE_PMJ02BN => {
                type $P = warpcore::sampler::Blue<Pmj02bn>;
                $body
            }
            #[cfg(feature = "blue-noise")]
            WC_PATTERN_BLUE_SOBOL => {
                type $P = warpcore::sampler::Blue<Sobol>;
                $body
            }
            _ => $unknown,
        }
    };
}

/// Is `pattern` a pattern of this build? 1 for `WC_PATTERN_PMJ02BN` and `WC_PATTERN_SOBOL`,
/// 1 for the blue-noise patterns when the library was built with the `blue-noise` feature
/// (the default), 0 otherwise.
#[unsafe(no_mangle)]
pub extern "C" fn wc_sampler_pattern_supported(pattern: u32) -> u32 {
    match pattern {
        WC_PATTERN_PMJ02BN | WC_PATTERN_SOBOL => 1,
        WC_PATTERN_BLUE_PMJ02BN | WC_PATTERN_BLUE_SOBOL => u32::from(cfg!(feature = "blue-noise")),
        _ => 0,
    }
}

/// The root sampler of sample `index` of pixel `(x, y)` in `frame`, for `seed` (one per
/// render; 0 is fine). Every pixel gets independent scrambles, except under the blue-noise
/// patterns, where pixels share a key tile (`x` and `y` modulo the tile). Every `uint32_t`
/// is valid. An unknown `pattern` gives `{pattern, 0, 0, 0}`, a sampler every draw refuses.
#[unsafe(no_mangle)]
pub extern "C" fn wc_sampler_new(
    pattern: u32,
    x: u32,
    y: u32,
    frame: u32,
    index: u32,
    seed: u32,
) -> WcSampler {
    with_pattern!(
        pattern,
        P => WcSampler::of(pattern, Sampler::<P>::new([x, y], frame, index, seed)),
        _ => WcSampler { pattern, ..WcSampler::default() }
    )
}

/// The root sampler of sample `index` (in `0..spp`) of pixel `(x, y)` in `frame` of a render
/// that accumulates frames of `spp` samples per pixel: the frames continue one sequence per
/// pixel (`Sampler::new_frame`). It is `wc_sampler_new` of the 64-bit sample number `n =
/// frame * spp + index` (`spp = 0` acts as 1), with `n >> 32` as `frame` and the low word as
/// `index`: frame 0 is `wc_sampler_new`'s frame 0, except that under the blue-noise patterns
/// this root's domains 0 to 5 are spatiotemporal slots (blue noise in every frame while the
/// frames continue one net; docs/sampler.md). Every `uint32_t` is valid. An unknown
/// `pattern` gives `{pattern, 0, 0, 0}`, a sampler every draw refuses.
#[unsafe(no_mangle)]
pub extern "C" fn wc_sampler_new_frame(
    pattern: u32,
    x: u32,
    y: u32,
    frame: u32,
    spp: u32,
    index: u32,
    seed: u32,
) -> WcSampler {
    with_pattern!(
        pattern,
        P => WcSampler::of(pattern, Sampler::<P>::new_frame([x, y], frame, spp, index, seed)),
        _ => WcSampler { pattern, ..WcSampler::default() }
    )
}

/// An independent child pattern for `key` (same index): one per decision of a path (lens,
/// light, BSDF, one per bounce ...). Different keys never give the same child. An unknown
/// pattern is returned unchanged.
#[unsafe(no_mangle)]
pub extern "C" fn wc_sampler_domain(s: WcSampler, key: u32) -> WcSampler {
    with_pattern!(s.pattern, P => WcSampler::of(s.pattern, s.get::<P>().domain(key)), _ => s)
}

/// Sub-sample `sub` of `size` per sample: the child index is `index * size + sub` (wrapping)
/// in a child domain for `key`, so the sub-samples of all samples are one sequence, globally
/// stratified. `size = 0` acts as 1; `sub >= size` is another sample's sub-sample. An unknown
/// pattern is returned unchanged.
#[unsafe(no_mangle)]
pub extern "C" fn wc_sampler_split(s: WcSampler, key: u32, size: u32, sub: u32) -> WcSampler {
    with_pattern!(
        s.pattern,
        P => WcSampler::of(s.pattern, s.get::<P>().split(key, size, sub)),
        _ => s
    )
}

/// `[T; 4]` holding `f::<N>()` in its first `N` elements, for `N = n` in 1..=4.
fn dims<T: Copy + Default>(n: usize, f: impl Dims<T>) -> Option<[T; 4]> {
    let mut a = [T::default(); 4];
    match n {
        1 => a[..1].copy_from_slice(&f.get::<1>()),
        2 => a[..2].copy_from_slice(&f.get::<2>()),
        3 => a[..3].copy_from_slice(&f.get::<3>()),
        4 => a.copy_from_slice(&f.get::<4>()),
        _ => return None,
    }
    Some(a)
}

/// A draw of a compile-time dimension count (a closure cannot be generic over `N`).
trait Dims<T> {
    fn get<const N: usize>(&self) -> [T; N];
}

struct DrawU32<P: Pattern>(Sampler<P>);
struct Rnd<P: Pattern>(Sampler<P>);
impl<P: Pattern> Dims<u32> for DrawU32<P> {
    fn get<const N: usize>(&self) -> [u32; N] {
        self.0.draw_u32::<N>()
    }
}
impl<P: Pattern> Dims<f32> for Rnd<P> {
    fn get<const N: usize>(&self) -> [f32; N] {
        self.0.rnd::<N>()
    }
}

/// Writes the first `n` values of `v` (if any) to `out`: returns `n`, or 0 (writing nothing)
/// for `v == None` or a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `n` values (`n <= 4` when `v` is `Some`).
unsafe fn put<T: Copy>(v: Option<[T; 4]>, n: usize, out: *mut T) -> usize {
    let Some(v) = v else { return 0 };
    if span(out.cast_const(), n).is_none() {
        return 0;
    }
    // SAFETY: `n <= 4 = v.len()` (`dims` returned `Some`); `out` is non-null, aligned and
    // writable for `n` values (checked by `span`, and the caller's contract); `v` is local.
    unsafe { core::ptr::copy_nonoverlapping(v.as_ptr(), out, n) };
    n
}

/// `n` (1 to 4) stratified dimensions of the point of `s`, in `[0, 1 - 2^-24]`: `n` floats.
/// Returns `n`, or 0 (writing nothing) for `n` outside 1..=4, an unknown pattern, or a null
/// or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sampler_draw(s: WcSampler, n: usize, out: *mut f32) -> usize {
    // Rust's `draw` is `(w >> 8) * 2^-24` of the words of `draw_u32` (a documented promise,
    // and the tests compare with `draw` itself): one copy of the pattern code for both.
    let w = with_pattern!(s.pattern, P => dims(n, DrawU32(s.get::<P>())), _ => None);
    let v = w.map(|w| w.map(|w| (w >> 8) as f32 * (1.0 / 16_777_216.0)));
    // SAFETY: the caller's contract above; `put` checks `v`, null and alignment.
    unsafe { put(v, n, out) }
}

/// The point of `wc_sampler_draw` as 0.32 fixed point (`w / 2^32`; `wc_sampler_draw` returns
/// `(w >> 8) * 2^-24`): `n` (1 to 4) values. Returns `n`, or 0 (writing nothing) for `n`
/// outside 1..=4, an unknown pattern, or a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `n` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sampler_draw_u32(s: WcSampler, n: usize, out: *mut u32) -> usize {
    let v = with_pattern!(s.pattern, P => dims(n, DrawU32(s.get::<P>())), _ => None);
    // SAFETY: the caller's contract above; `put` checks `v`, null and alignment.
    unsafe { put(v, n, out) }
}

/// `n` (1 to 4) cheap unstratified values in `[0, 1 - 2^-24]` (a counter hash of the pixel,
/// the domain and the index), for Russian roulette and other decisions where stratification
/// does not pay. Returns `n`, or 0 (writing nothing) for `n` outside 1..=4, an unknown
/// pattern, or a null or misaligned `out`.
///
/// # Safety
/// `out` must be writable for `n` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sampler_rnd(s: WcSampler, n: usize, out: *mut f32) -> usize {
    let v = with_pattern!(s.pattern, P => dims(n, Rnd(s.get::<P>())), _ => None);
    // SAFETY: the caller's contract above; `put` checks `v`, null and alignment.
    unsafe { put(v, n, out) }
}

/// The points of `s`'s domain for the `count` consecutive indices `s.index, s.index + 1, ...`
/// (wrapping after `UINT32_MAX`), `n_dims` (1 to 4) dimensions each: `count * n_dims` floats,
/// interleaved, the same bits as `count` calls of `wc_sampler_draw` (eight or sixteen points at
/// a time). Returns `count`, or 0 (writing nothing) for `count = 0`, `n_dims` outside 1..=4,
/// an unknown pattern, a null or misaligned `out`, or `count * n_dims` floats whose byte size
/// exceeds `PTRDIFF_MAX`.
///
/// # Safety
/// `out` must be writable for `count * n_dims` floats.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn wc_sampler_draw_slice(
    s: WcSampler,
    n_dims: usize,
    out: *mut f32,
    count: usize,
) -> usize {
    with_pattern!(
        s.pattern,
        P => {
            let root = s.get::<P>();
            let at = |offset: u32| root.with_index(root.index().wrapping_add(offset));
            // SAFETY: the caller's contract above; `generate` checks null, alignment and size.
            unsafe {
                match n_dims {
                    1 => generate::<1>(out, count, |o, chunk| at(o).draw_slice(chunk)),
                    2 => generate::<2>(out, count, |o, chunk| at(o).draw_slice(chunk)),
                    3 => generate::<3>(out, count, |o, chunk| at(o).draw_slice(chunk)),
                    4 => generate::<4>(out, count, |o, chunk| at(o).draw_slice(chunk)),
                    _ => 0,
                }
            }
        },
        _ => 0
    )
}

const _: () = assert!(core::mem::size_of::<WcSampler>() == 16);
