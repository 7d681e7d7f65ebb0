//! The C ABI's environment-map entry points under fuzzer-chosen storage, sizes, counts and
//! pointers, called through their Rust signatures (`crate::envmap`: the including crate
//! compiles `capi/src/envmap.rs` and `capi/src/ffi.rs` in as modules). Shared by the
//! `capi_envmap` fuzz target and the stable corpus replay (`capi/tests/fuzz_corpus.rs`).
//!
//! The input is a little program: each operation reads a byte (which entry point), then the
//! sizes, counts, pointer plans (valid, null, misaligned, overlapping another array, in place)
//! and data it needs; bytes past the end read as 0. Every array lives in one `Arena` of
//! words with sentinel padding on both sides. A model of the documented rules (the C header)
//! says what each call must return and whether it gets past its checks; calls that get past
//! the checks are made only with arrays of the documented sizes (the caller's contract).
//! Then:
//!
//! * the return value is the documented one;
//! * a refused call changed nothing in the arena; an accepted one changed only its outputs;
//! * the outputs are bit for bit what the safe Rust crate computes for the same input
//!   (storage words, samples, densities, codes of `from_storage`), so the C layer neither
//!   drops nor invents a check.
#![allow(dead_code)]

use crate::envmap::*;
use std::sync::atomic::{AtomicU64, Ordering};
use warpcore::envmap::{
    Error, HEADER_WORDS, Hierarchical, MAX_SIDE, MarginalConditional, Sample, image,
};

/// C calls made so far (all threads): the replay reports it.
pub static CALLS: AtomicU64 = AtomicU64::new(0);

fn counted() {
    CALLS.fetch_add(1, Ordering::Relaxed);
}

/// The fuzzer's bytes, read front to back; zeros past the end.
struct Bytes<'a> {
    data: &'a [u8],
    at: usize,
}

impl Bytes<'_> {
    fn byte(&mut self) -> u8 {
        let b = self.data.get(self.at).copied().unwrap_or(0);
        self.at += 1;
        b
    }
    fn word(&mut self) -> u32 {
        u32::from_le_bytes([self.byte(), self.byte(), self.byte(), self.byte()])
    }
    fn done(&self) -> bool {
        self.at >= self.data.len()
    }
    /// A side: small (`0..64`) or any `u32`.
    fn side(&mut self) -> u32 {
        let w = self.word();
        if w & 1 == 0 { (w >> 1) % 64 } else { w }
    }
    /// A count: small (`0..=64`), or one whose byte size overflows for `elem`-byte elements.
    fn count(&mut self, elem: usize) -> usize {
        let w = self.word();
        match w % 8 {
            0 => [
                usize::MAX,
                usize::MAX / 2 + 1,
                isize::MAX as usize / elem + 1,
                usize::MAX / elem + 1,
            ][(w >> 3) as usize % 4],
            _ => ((w >> 3) % 65) as usize,
        }
    }
    /// A pointer plan.
    fn plan(&mut self) -> Plan {
        match self.byte() % 8 {
            0 => Plan::Null,
            1 => Plan::Skew(1 + (self.byte() % 3) as usize),
            2 => Plan::Overlap(self.word() as usize),
            3 => Plan::InPlace,
            _ => Plan::Ok,
        }
    }
    /// A distribution (an odd byte: hierarchical), or (one byte in 16) a `kind` that names
    /// none.
    fn kind(&mut self) -> Result<Kind, u32> {
        let b = self.byte();
        match b % 16 {
            15 => Err(2 + u32::from(b >> 4)),
            _ => Ok(Kind {
                hierarchical: b & 1 == 1,
            }),
        }
    }
    /// A float: any bits.
    fn float(&mut self) -> f32 {
        f32::from_bits(self.word())
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum Plan {
    Ok,
    Null,
    /// Misaligned by this many bytes.
    Skew(usize),
    /// Placed at this offset (modulo a range) inside another array.
    Overlap(usize),
    /// The same address as the input.
    InPlace,
}

const PAD: usize = 32;
const SENTINEL: u32 = 0xa5a5_a5a5;

/// Words with sentinel padding on both sides; arrays are placed at word offsets.
struct Arena {
    v: Vec<u32>,
}

impl Arena {
    fn new(words: usize) -> Self {
        Arena {
            v: vec![SENTINEL; words + 2 * PAD],
        }
    }
    /// A pointer to word `at` of the usable part, `skew` bytes further, or null.
    fn ptr<T>(&mut self, at: usize, plan: Plan) -> *mut T {
        let p = self.v.as_mut_ptr().wrapping_add(PAD + at).cast::<u8>();
        match plan {
            Plan::Null => core::ptr::null_mut(),
            Plan::Skew(k) => p.wrapping_add(k).cast(),
            _ => p.cast(),
        }
    }
    fn put(&mut self, at: usize, words: &[u32]) {
        self.v[PAD + at..PAD + at + words.len()].copy_from_slice(words);
    }
    fn get(&self, at: usize, len: usize) -> &[u32] {
        &self.v[PAD + at..PAD + at + len]
    }
    /// Everything but `[at, at + len)` equals `before`.
    fn unchanged_outside(&self, before: &[u32], at: usize, len: usize) -> bool {
        let (a, b) = (PAD + at, PAD + at + len);
        self.v[..a] == before[..a] && self.v[b..] == before[b..]
    }
    /// Makes the C call `call` on this arena's arrays (counted) and checks the promises: it
    /// returns `want`; a refused call (`accepted` false) changes nothing, an accepted one
    /// nothing outside its outputs `[at, at + len)`. `what` names the call in messages.
    /// Returns `accepted`.
    fn call<R: PartialEq + core::fmt::Debug>(
        &self,
        want: R,
        accepted: bool,
        (at, len): (usize, usize),
        what: &str,
        call: impl FnOnce() -> R,
    ) -> bool {
        let before = self.v.clone();
        counted();
        assert_eq!(call(), want, "{what}");
        if accepted {
            assert!(
                self.unchanged_outside(&before, at, len),
                "{what} wrote outside its outputs"
            );
        } else {
            assert!(self.v == before, "a refused {what} wrote");
        }
        accepted
    }
}

fn fits(count: usize, elem: usize) -> bool {
    count
        .checked_mul(elem)
        .is_some_and(|b| b <= isize::MAX as usize)
}

fn fits64(count: u64, elem: u64) -> bool {
    count
        .checked_mul(elem)
        .is_some_and(|b| b <= isize::MAX as u64)
}

fn overlap(a: (usize, usize), b: (usize, usize)) -> bool {
    a.1 > 0 && b.1 > 0 && a.0 < b.0.saturating_add(b.1) && b.0 < a.0.saturating_add(a.1)
}

fn bits(x: &[f32]) -> Vec<u32> {
    x.iter().map(|f| f.to_bits()).collect()
}

/// A distribution: the C `kind` and the safe crate's type.
#[derive(Clone, Copy)]
struct Kind {
    hierarchical: bool,
}

impl Kind {
    /// Its `WC_ENVMAP_KIND_*`.
    fn c(self) -> u32 {
        if self.hierarchical {
            WC_ENVMAP_KIND_HIERARCHICAL
        } else {
            WC_ENVMAP_KIND_MARGINAL_CONDITIONAL
        }
    }
    fn rust_len(self, w: usize, h: usize) -> usize {
        if self.hierarchical {
            Hierarchical::storage_len(w, h)
        } else {
            MarginalConditional::storage_len(w, h)
        }
    }
    /// The safe crate's verdict on a storage of this distribution (O(1) or verified).
    fn load(self, words: &[u32], verify: bool) -> Result<(), Error> {
        match (self.hierarchical, verify) {
            (true, false) => Hierarchical::from_storage(words).map(|_| ()),
            (true, true) => Hierarchical::from_storage_verified(words).map(|_| ()),
            (false, false) => MarginalConditional::from_storage(words).map(|_| ()),
            (false, true) => MarginalConditional::from_storage_verified(words).map(|_| ()),
        }
    }
    /// The safe crate's samples and densities from a storage that loads.
    fn reference(self, words: &[u32], u: &[[f32; 2]]) -> (Vec<Sample>, Vec<f32>) {
        let blank = Sample {
            uv: [0.0; 2],
            pdf: 0.0,
            texel: [0; 2],
        };
        let (mut s, mut p) = (vec![blank; u.len()], vec![0.0f32; u.len()]);
        if self.hierarchical {
            let d = Hierarchical::from_storage(words).expect("loads");
            d.sample_slice(u, &mut s);
            d.pdf_slice(u, &mut p);
        } else {
            let d = MarginalConditional::from_storage(words).expect("loads");
            d.sample_slice(u, &mut s);
            d.pdf_slice(u, &mut p);
        }
        (s, p)
    }
}

/// The documented reading of a storage: the distribution its format tag names (word 0 as
/// bytes, `"wcHI"` or `"wcMC"`) and the safe crate's verdict for it; a storage shorter than
/// the header is too small, any other tag the wrong format. The `WC_ERR_*` code on failure.
fn loaded(words: &[u32], verify: bool) -> Result<Kind, i32> {
    let kind = match words.first().map(|w| w.to_ne_bytes()) {
        _ if words.len() < HEADER_WORDS => return Err(WC_ERR_STORAGE_TOO_SMALL),
        Some(t) if &t == b"wcHI" => Kind { hierarchical: true },
        Some(t) if &t == b"wcMC" => Kind {
            hierarchical: false,
        },
        _ => return Err(WC_ERR_WRONG_FORMAT),
    };
    kind.load(words, verify).map_err(code).map(|()| kind)
}

/// State carried between operations: the last storage a build produced.
struct State {
    storage: [Vec<u32>; 2],
}

impl State {
    fn new() -> Self {
        let weights: Vec<f32> = (0..15).map(|k| (k % 4) as f32).collect();
        let mut h = vec![0u32; Hierarchical::storage_len(5, 3)];
        Hierarchical::new(&weights, 5, 3, &mut h).expect("builds");
        let mut m = vec![0u32; MarginalConditional::storage_len(5, 3)];
        MarginalConditional::new(&weights, 5, 3, &mut m).expect("builds");
        State { storage: [m, h] }
    }
}

/// Runs the operations the input describes; panics on a broken promise.
pub fn capi_envmap(data: &[u8]) {
    let mut b = Bytes { data, at: 0 };
    let mut state = State::new();
    for _ in 0..24 {
        if b.done() {
            break;
        }
        match b.byte() % 9 {
            0 => storage_len(&mut b),
            1 => build(&mut b, &mut state),
            2 => check(&mut b, &state),
            3 => sample(&mut b, &state, false),
            4 => sample(&mut b, &state, true),
            5 => luminance(&mut b),
            6 => solid_angle_weights(&mut b),
            7 => to_equal_area(&mut b),
            _ => latlong_pdf(&mut b),
        }
    }
}

fn storage_len(b: &mut Bytes) {
    let (w, h) = (b.side(), b.side());
    counted();
    assert_eq!(
        wc_envmap_storage_len(2 + w % 7, w, h),
        usize::MAX,
        "unknown kind"
    );
    for kind in [
        Kind { hierarchical: true },
        Kind {
            hierarchical: false,
        },
    ] {
        counted();
        let got = wc_envmap_storage_len(kind.c(), w, h);
        if w == 0 || h == 0 {
            assert_eq!(got, 0, "storage_len({w}, {h})");
        } else if w as usize > MAX_SIDE || h as usize > MAX_SIDE {
            assert_eq!(got, usize::MAX, "storage_len({w}, {h})");
        } else {
            assert_eq!(got, kind.rust_len(w as usize, h as usize));
            assert!(
                got == usize::MAX
                    || (got as u64 >= 8 + w as u64 * h as u64 && got as u64 <= u32::MAX as u64)
            );
        }
    }
}

fn build(b: &mut Bytes, state: &mut State) {
    let kind = b.kind();
    let c_kind = kind.map_or_else(|k| k, Kind::c);
    let (w, h) = (b.side(), b.side());
    counted();
    let need = wc_envmap_storage_len(c_kind, w, h);
    let len = match b.byte() % 5 {
        0 => need.wrapping_sub((b.byte() % 8) as usize),
        1 => need.wrapping_add((b.byte() % 8) as usize),
        2 => b.word() as usize,
        3 => usize::MAX,
        _ => need,
    };
    let (wp, sp) = (b.plan(), b.plan());
    let texels = w as u64 * h as u64;
    let small = w > 0 && h > 0 && texels <= 4096 && need <= 1 << 16;
    let (tw, ts) = if small {
        (
            texels as usize,
            need + if len > need && len - need <= 8 {
                len - need
            } else {
                0
            },
        )
    } else {
        (4, 4)
    };
    let weights: Vec<f32> = (0..tw).map(|_| b.float()).collect();
    // Layout: weights, then the storage; overlapping plans move the weights into it.
    let mut arena = Arena::new(2 * tw + ts + 8);
    let s_at = tw + 4;
    let w_at = match wp {
        Plan::Overlap(k) => k % (tw + ts + 1),
        _ => 0,
    };
    arena.put(w_at, &bits(&weights));
    let wptr = arena.ptr::<f32>(w_at, wp);
    let sptr = arena.ptr::<u32>(s_at, sp);
    // The model, in the documented order.
    let ok_ptr = |p: Plan| !matches!(p, Plan::Null | Plan::Skew(_));
    let want = if kind.is_err() {
        WC_ERR_INVALID_ARGUMENT
    } else if w == 0 || h == 0 {
        WC_ERR_ZERO_SIZE
    } else if need == usize::MAX || !fits64(texels, 4) || !fits(need, 4) {
        WC_ERR_TOO_LARGE
    } else if len < need {
        WC_ERR_STORAGE_TOO_SMALL
    } else if !ok_ptr(wp) || !ok_ptr(sp) || overlap((w_at, texels as usize), (s_at, need)) {
        WC_ERR_INVALID_ARGUMENT
    } else if !small {
        return; // would need arrays this check does not allocate
    } else if weights.contains(&f32::INFINITY) {
        WC_ERR_INFINITE_WEIGHT
    } else {
        WC_OK
    };
    let accepted = want == WC_OK || want == WC_ERR_INFINITE_WEIGHT;
    let what = format!("build {w}x{h} len {len} (need {need}) {wp:?} {sp:?}");
    // SAFETY: the model says the call either fails before touching memory, or gets past its
    // checks with `weights` readable for `w * h` floats and the storage writable for `need`
    // words (`len` more only if the slack words exist: they must not be written).
    arena.call(want, accepted, (s_at, need), &what, || unsafe {
        wc_envmap_build(c_kind, wptr, w, h, sptr, len)
    });
    if let (WC_OK, Ok(kind)) = (want, kind) {
        let words = arena.get(s_at, need).to_vec();
        let (w, h) = (w as usize, h as usize);
        let mut rust = vec![0u32; need];
        if kind.hierarchical {
            Hierarchical::new(&weights, w, h, &mut rust).expect("the crate builds it too");
        } else {
            MarginalConditional::new(&weights, w, h, &mut rust).expect("the crate builds it too");
            assert_eq!(words, rust, "C and Rust storages differ");
        }
        // Hierarchical storage depends on the address modulo 64: compare what it samples.
        let u: Vec<[f32; 2]> = (0..16)
            .map(|i| [i as f32 / 16.0, 1.0 - i as f32 / 17.0])
            .collect();
        assert_eq!(kind.reference(&words, &u), kind.reference(&rust, &u));
        state.storage[kind.hierarchical as usize] = words;
    }
}

/// A storage to load: the last one built, damaged as the input says, or raw input words.
fn damaged(b: &mut Bytes, state: &State, kind: Kind) -> Vec<u32> {
    let mut s = state.storage[kind.hierarchical as usize].clone();
    match b.byte() % 6 {
        0 => {
            let at = b.word() as usize % s.len();
            s[at] = b.word();
        }
        1 => {
            let at = b.byte() as usize % 16; // the 16-word header
            s[at] ^= 1 << (b.byte() % 32);
        }
        2 => s.truncate(b.word() as usize % s.len()),
        3 => {
            let n = (b.byte() % 64) as usize;
            s = (0..n).map(|_| b.word()).collect();
        }
        4 => s = state.storage[1 - kind.hierarchical as usize].clone(),
        _ => {}
    }
    s
}

fn check(b: &mut Bytes, state: &State) {
    let kind = Kind {
        hierarchical: b.byte() & 1 == 1,
    };
    let verify = b.byte() & 1 == 1;
    let words = damaged(b, state, kind);
    let plan = b.plan();
    let lie = b.byte().is_multiple_of(8); // a length no array can have
    let len = if lie {
        isize::MAX as usize / 4 + 1 + (b.byte() % 4) as usize
    } else {
        words.len()
    };
    let mut arena = Arena::new(words.len());
    arena.put(0, &words);
    let p = arena.ptr::<u32>(0, plan);
    // Pointers are checked only when there are words to read (as every count: 0 reads nothing).
    let bad_ptr = matches!(plan, Plan::Null | Plan::Skew(_));
    let want = if lie || (len > 0 && bad_ptr) {
        WC_ERR_INVALID_ARGUMENT
    } else {
        loaded(&words[..len], verify).map_or_else(|c| c, |_| WC_OK)
    };
    // Reads only: accepted or not, it writes nothing.
    // SAFETY: `len` words are readable at `p` unless the model says the call refuses first.
    arena.call(
        want,
        false,
        (0, 0),
        &format!("check {plan:?} len {len}"),
        || unsafe {
            if verify {
                wc_envmap_from_storage_verified(p, len)
            } else {
                wc_envmap_from_storage(p, len)
            }
        },
    );
}

fn sample(b: &mut Bytes, state: &State, pdf: bool) {
    let kind = Kind {
        hierarchical: b.byte() & 1 == 1,
    };
    let words = damaged(b, state, kind);
    let elem = if pdf { 4 } else { size_of::<WcEnvSample>() };
    let ow = elem / 4; // words per output
    let n = b.count(elem.max(8));
    let (up, op, sp) = (b.plan(), b.plan(), b.plan());
    let small = if n <= 64 { n } else { 0 };
    let u: Vec<f32> = (0..2 * small).map(|_| b.float()).collect();
    // Layout: storage, u, out, each with room; overlapping plans move `out`.
    let sl = words.len();
    let (s_at, u_at) = (0, sl + 2);
    let mut o_at = u_at + 2 * small + 2;
    match op {
        Plan::InPlace => o_at = u_at,
        Plan::Overlap(k) if k & 1 == 0 => o_at = u_at + (k >> 1) % (2 * small + 1),
        Plan::Overlap(k) => o_at = (k >> 1) % (sl + 1),
        _ => {}
    }
    let mut arena = Arena::new(u_at + 2 * small + 2 + small * ow + sl + 4);
    arena.put(s_at, &words);
    arena.put(u_at, &bits(&u));
    let s = arena.ptr::<u32>(s_at, sp);
    let uptr = arena.ptr::<f32>(u_at, up);
    let optr = arena.ptr::<u32>(o_at, op);
    let ok_ptr = |p: Plan| !matches!(p, Plan::Null | Plan::Skew(_));
    let loads = loaded(&words, false);
    let want = if n == 0
        || !ok_ptr(up)
        || !ok_ptr(op)
        || !ok_ptr(sp)
        || !fits(n, 8)
        || !fits(n, elem)
        || (overlap((u_at, 2 * n), (o_at, n * ow)) && !(pdf && o_at == u_at))
        || overlap((s_at, sl), (o_at, n * ow))
        || loads.is_err()
    {
        0
    } else {
        n
    };
    let what = format!("sample/pdf n {n} {up:?} {op:?} {sp:?}");
    // SAFETY: the model: either refused before touching memory, or `u` holds `2n` floats,
    // `out` room for `n` outputs and the storage `sl` words, all inside the arena.
    let accepted = arena.call(
        want,
        want != 0,
        (o_at, n.saturating_mul(ow)),
        &what,
        || unsafe {
            if pdf {
                wc_envmap_pdf(s, sl, uptr, optr.cast(), n)
            } else {
                wc_envmap_sample(s, sl, uptr, optr.cast(), n)
            }
        },
    );
    if !accepted {
        return;
    }
    let pts: Vec<[f32; 2]> = u.chunks_exact(2).map(|c| [c[0], c[1]]).collect();
    let (rs, rp) = loads.expect("loads").reference(&words, &pts);
    let out = arena.get(o_at, n * ow);
    if pdf {
        assert_eq!(out, &bits(&rp)[..], "pdf differs from the crate's");
    } else {
        let want: Vec<u32> = rs
            .iter()
            .flat_map(|s| {
                [
                    s.uv[0].to_bits(),
                    s.uv[1].to_bits(),
                    s.pdf.to_bits(),
                    s.texel[0],
                    s.texel[1],
                ]
            })
            .collect();
        assert_eq!(out, &want[..], "samples differ from the crate's");
    }
}

/// One-input maps: `n` inputs of `I` floats to `n` outputs of `O` floats.
fn map_call<const I: usize, const O: usize>(
    b: &mut Bytes,
    name: &str,
    f: unsafe extern "C" fn(*const f32, *mut f32, usize) -> usize,
    reference: impl Fn(&[[f32; I]]) -> Vec<[f32; O]>,
) {
    let n = b.count(4 * I.max(O));
    let (ip, op) = (b.plan(), b.plan());
    let small = if n <= 64 { n } else { 0 };
    let input: Vec<f32> = (0..I * small).map(|_| b.float()).collect();
    let i_at = 0;
    let o_at = match op {
        Plan::InPlace => i_at,
        Plan::Overlap(k) => k % (I * small + 1),
        _ => I * small + 2,
    };
    let mut arena = Arena::new(I * small + 2 + O * small.max(1) + 2);
    arena.put(i_at, &bits(&input));
    let iptr = arena.ptr::<f32>(i_at, ip);
    let optr = arena.ptr::<f32>(o_at, op);
    let ok_ptr = |p: Plan| !matches!(p, Plan::Null | Plan::Skew(_));
    let want = if n == 0
        || !ok_ptr(ip)
        || !ok_ptr(op)
        || !fits(n, 4 * I)
        || !fits(n, 4 * O)
        || (overlap((i_at, I * n), (o_at, O * n)) && !(i_at == o_at && O <= I))
    {
        0
    } else {
        n
    };
    let what = format!("{name} n {n} {ip:?} {op:?}");
    // SAFETY: refused before touching memory, or `I n` floats readable and `O n` writable
    // inside the arena.
    if !arena.call(
        want,
        want != 0,
        (o_at, n.saturating_mul(O)),
        &what,
        || unsafe { f(iptr, optr, n) },
    ) {
        return;
    }
    let pts: Vec<[f32; I]> = input
        .chunks_exact(I)
        .map(|c| std::array::from_fn(|k| c[k]))
        .collect();
    let want: Vec<f32> = reference(&pts).into_iter().flatten().collect();
    assert_eq!(
        arena.get(o_at, O * n),
        &bits(&want)[..],
        "{name} differs from the crate's"
    );
}

fn luminance(b: &mut Bytes) {
    map_call::<3, 1>(b, "luminance", wc_envmap_luminance, |rgb| {
        rgb.iter().map(|&c| [image::luminance(c)]).collect()
    });
}

fn latlong_pdf(b: &mut Bytes) {
    let n = b.count(4);
    let (pp, vp, op) = (b.plan(), b.plan(), b.plan());
    let small = if n <= 64 { n } else { 0 };
    let vals: Vec<f32> = (0..2 * small).map(|_| b.float()).collect();
    let (p_at, v_at) = (0, small + 2);
    let o_at = match op {
        Plan::InPlace => p_at,
        Plan::Overlap(k) => k % (2 * small + 3),
        _ => 2 * small + 4,
    };
    let mut arena = Arena::new(3 * small + 6);
    arena.put(p_at, &bits(&vals[..small]));
    arena.put(v_at, &bits(&vals[small..]));
    let (pptr, vptr, optr) = (
        arena.ptr::<f32>(p_at, pp),
        arena.ptr::<f32>(v_at, vp),
        arena.ptr::<f32>(o_at, op),
    );
    let ok_ptr = |p: Plan| !matches!(p, Plan::Null | Plan::Skew(_));
    let want = if n == 0
        || !ok_ptr(pp)
        || !ok_ptr(vp)
        || !ok_ptr(op)
        || !fits(n, 4)
        || overlap((v_at, n), (o_at, n))
        || (overlap((p_at, n), (o_at, n)) && p_at != o_at)
    {
        0
    } else {
        n
    };
    let what = format!("latlong_pdf n {n} {pp:?} {vp:?} {op:?}");
    // SAFETY: refused before touching memory, or every array holds `n` floats in the arena.
    if !arena.call(want, want != 0, (o_at, n), &what, || unsafe {
        wc_envmap_equirect_pdf_to_solid_angle(pptr, vptr, optr, n)
    }) {
        return;
    }
    let r: Vec<f32> = (0..n)
        .map(|i| image::equirect_pdf_to_solid_angle(vals[i], vals[small + i]))
        .collect();
    assert_eq!(arena.get(o_at, n), &bits(&r)[..]);
}

fn solid_angle_weights(b: &mut Bytes) {
    let (w, h) = (b.side(), b.side());
    let plan = b.plan();
    let texels = w as u64 * h as u64;
    let small = w > 0 && h > 0 && texels <= 4096;
    let count = if small { texels as usize } else { 4 };
    let vals: Vec<f32> = (0..count).map(|_| b.float()).collect();
    let mut arena = Arena::new(count);
    arena.put(0, &bits(&vals));
    let p = arena.ptr::<f32>(0, plan);
    let want = if w == 0 || h == 0 {
        WC_ERR_ZERO_SIZE
    } else if !fits64(texels, 4) {
        WC_ERR_TOO_LARGE
    } else if matches!(plan, Plan::Null | Plan::Skew(_)) {
        WC_ERR_INVALID_ARGUMENT
    } else if !small {
        return;
    } else {
        WC_OK
    };
    let what = format!("solid_angle_weights {w}x{h} {plan:?}");
    // SAFETY: refused before touching memory, or `w h` floats in the arena.
    if !arena.call(want, want == WC_OK, (0, count), &what, || unsafe {
        wc_envmap_equirect_solid_angle_weights(p, w, h)
    }) {
        return;
    }
    let mut r = vals.clone();
    image::equirect_solid_angle_weights(&mut r, w as usize, h as usize).expect("valid");
    assert_eq!(arena.get(0, count), &bits(&r)[..]);
}

fn to_equal_area(b: &mut Bytes) {
    let (sw, sh, size) = (b.side(), b.side(), b.side());
    let c = (b.byte() % 6) as u32;
    let ss = match b.byte() % 4 {
        0 => b.word(),
        _ => (b.byte() % 4) as u32,
    };
    let (srcp, dstp) = (b.plan(), b.plan());
    let (src_n, dst_n) = (
        (sw as u64 * sh as u64).saturating_mul(c as u64),
        (size as u64 * size as u64).saturating_mul(c as u64),
    );
    let small = src_n > 0 && dst_n > 0 && src_n <= 4096 && dst_n <= 4096;
    let (sl, dl) = if small {
        (src_n as usize, dst_n as usize)
    } else {
        (4, 4)
    };
    let src: Vec<f32> = (0..sl).map(|_| b.float()).collect();
    let s_at = 0;
    let d_at = match dstp {
        Plan::Overlap(k) => k % (sl + 1),
        Plan::InPlace => 0,
        _ => sl + 2,
    };
    let mut arena = Arena::new(sl + 2 + dl);
    arena.put(s_at, &bits(&src));
    let (sp, dp) = (arena.ptr::<f32>(s_at, srcp), arena.ptr::<f32>(d_at, dstp));
    let ok_ptr = |p: Plan| !matches!(p, Plan::Null | Plan::Skew(_));
    let side = |x: u32| x as usize > MAX_SIDE;
    let want = if sw == 0 || sh == 0 || size == 0 || ss == 0 {
        WC_ERR_ZERO_SIZE
    } else if !(1..=4).contains(&c) {
        WC_ERR_INVALID_ARGUMENT
    } else if side(sw)
        || side(sh)
        || side(size)
        || ss as usize > image::MAX_SUPERSAMPLE
        || !fits64(src_n, 4)
        || !fits64(dst_n, 4)
    {
        WC_ERR_TOO_LARGE
    } else if !ok_ptr(srcp)
        || !ok_ptr(dstp)
        || overlap((s_at, src_n as usize), (d_at, dst_n as usize))
    {
        WC_ERR_INVALID_ARGUMENT
    } else if !small {
        return;
    } else {
        WC_OK
    };
    let what = format!("to_equal_area {sw}x{sh}x{c} -> {size} ss {ss} {srcp:?} {dstp:?}");
    // SAFETY: refused before touching memory, or both arrays of their sizes in the arena.
    if !arena.call(want, want == WC_OK, (d_at, dl), &what, || unsafe {
        wc_envmap_equirect_to_equal_area(sp, sw, sh, c, dp, size, ss)
    }) {
        return;
    }
    let (w, h, n, s) = (sw as usize, sh as usize, size as usize, ss as usize);
    let mut d = vec![0.0f32; dl];
    fn run<const C: usize>(src: &[f32], w: usize, h: usize, d: &mut [f32], n: usize, s: usize) {
        image::equirect_to_equal_area(src.as_chunks::<C>().0, w, h, d.as_chunks_mut::<C>().0, n, s)
            .expect("valid");
    }
    match c {
        1 => run::<1>(&src, w, h, &mut d, n, s),
        2 => run::<2>(&src, w, h, &mut d, n, s),
        3 => run::<3>(&src, w, h, &mut d, n, s),
        _ => run::<4>(&src, w, h, &mut d, n, s),
    }
    assert_eq!(arena.get(d_at, dl), &bits(&d)[..]);
}
