//! Size arithmetic under hostile sizes: every env-map entry point that computes a size from
//! caller-supplied sides, counts or header words, given sizes from 0 to `usize::MAX` (around
//! `MAX_SIDE`, around `2^16` where `width * height` overflows a 32-bit `usize`, and any value)
//! with short slices, returns exactly the documented result — computed here by a model in
//! `u128`, which cannot overflow — and never panics. Tests build with overflow checks, so an
//! unchecked multiplication fails here; CI runs this file natively and as wasm32-wasip1
//! (32-bit `usize`: the target where the products overflow).
#![cfg(feature = "envmap")]

use proptest::prelude::*;
use warpcore::envmap::{Error, HEADER_WORDS, Hierarchical, MAX_SIDE, MarginalConditional, image};

/// One library call (every call of a property goes through here, to count them: 8 per case).
fn call<T>(f: impl FnOnce() -> T) -> T {
    f()
}

/// A size: 0, small, around the limits and the 32-bit overflow points, or anything.
fn size() -> impl Strategy<Value = usize> {
    let m = MAX_SIDE;
    prop_oneof![
        3 => 1usize..9,
        1 => Just(0usize),
        2 => prop::sample::select(vec![
            m - 1,
            m,
            m + 1,
            1 << 16,
            (1 << 16) + 1,
            65_535,
            46_341,
            1 << 20,
            (1 << 31) - 1,
            usize::MAX,
            usize::MAX / 2,
            usize::MAX / 3,
            usize::MAX / 4 + 1,
        ]),
        1 => any::<usize>(),
    ]
}

/// `a * b` as the crate reports an expected length: saturating at `usize::MAX`.
fn product(a: usize, b: usize) -> usize {
    usize::try_from(a as u128 * b as u128).unwrap_or(usize::MAX)
}

/// Marginal-conditional storage words, or `usize::MAX` (the documented rule).
/// (A 16-word header since storage format version 3.)
fn mc_len(w: usize, h: usize) -> usize {
    if w == 0 || h == 0 {
        return 0;
    }
    if w > MAX_SIDE || h > MAX_SIDE {
        return usize::MAX;
    }
    let (w, h) = (w as u128, h as u128);
    let n = 16 + (h + 1) + (w + 1) * h + (w + 1) + (h + 1);
    if n > u32::MAX as u128 {
        usize::MAX
    } else {
        usize::try_from(n).unwrap_or(usize::MAX)
    }
}

fn equal_area_model(
    sw: usize,
    sh: usize,
    n: usize,
    ss: usize,
    src: usize,
    dst: usize,
) -> Result<(), Error> {
    if sw == 0 || sh == 0 || n == 0 || ss == 0 {
        return Err(Error::ZeroSize);
    }
    if sw > MAX_SIDE || sh > MAX_SIDE || n > MAX_SIDE || ss > image::MAX_SUPERSAMPLE {
        return Err(Error::TooLarge);
    }
    if src != product(sw, sh) {
        return Err(Error::LengthMismatch {
            expected: product(sw, sh),
            got: src,
        });
    }
    if dst != product(n, n) {
        return Err(Error::LengthMismatch {
            expected: product(n, n),
            got: dst,
        });
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]

    /// `equirect_to_equal_area`: the documented error, in the documented order, for any sizes;
    /// `dst` unchanged on error.
    #[test]
    fn equal_area_sizes(
        sw in size(), sh in size(), n in size(), ss in size(),
        src_len in 0usize..70, dst_len in 0usize..70, fit in any::<bool>(),
    ) {
        // Half the time, lengths that fit small sizes (so `Ok` is reached too).
        let src_len = if fit && product(sw, sh) <= 64 { product(sw, sh) } else { src_len };
        let dst_len = if fit && product(n, n) <= 64 { product(n, n) } else { dst_len };
        let ss = if fit && ss > 4 && ss <= MAX_SIDE { 1 + ss % 4 } else { ss };
        let src = vec![[0.5f32, -1.0, f32::NAN]; src_len];
        let mut dst = vec![[7.0f32; 3]; dst_len];
        let got = call(|| image::equirect_to_equal_area(&src, sw, sh, &mut dst, n, ss));
        let want = equal_area_model(sw, sh, n, ss, src_len, dst_len);
        prop_assert_eq!(got, want);
        if want.is_err() {
            prop_assert!(dst.iter().all(|t| *t == [7.0; 3]), "dst written on error");
        } else {
            prop_assert!(dst.iter().all(|t| t[0] == 0.5 && t[1] == 0.0 && t[2] == 0.0));
        }
    }

    /// `equirect_solid_angle_weights`: `ZeroSize`, else `LengthMismatch` with the saturated
    /// product, else `Ok`; weights unchanged on error.
    #[test]
    fn solid_angle_sizes(w in size(), h in size(), len in 0usize..70, fit in any::<bool>()) {
        let len = if fit && product(w, h) <= 64 { product(w, h) } else { len };
        let mut weights = vec![2.0f32; len];
        let got = call(|| image::equirect_solid_angle_weights(&mut weights, w, h));
        let want = if w == 0 || h == 0 {
            Err(Error::ZeroSize)
        } else if len != product(w, h) {
            Err(Error::LengthMismatch { expected: product(w, h), got: len })
        } else {
            Ok(())
        };
        prop_assert_eq!(got, want);
        if want.is_err() {
            prop_assert!(weights.iter().all(|&x| x == 2.0));
        } else {
            prop_assert!(weights.iter().all(|&x| x > 0.0 && x <= 2.0));
        }
    }

    /// `storage_len` of both distributions, and `new` with any sizes and short slices: the
    /// documented error in the documented order (`ZeroSize`, `TooLarge`, `LengthMismatch`,
    /// `StorageTooSmall`), or a build.
    #[test]
    fn storage_sizes(
        w in size(), h in size(), weights_len in 0usize..70, storage_len in 0usize..400,
        fit in any::<bool>(),
    ) {
        let mc = call(|| MarginalConditional::storage_len(w, h));
        prop_assert_eq!(mc, mc_len(w, h));
        let hi = call(|| Hierarchical::storage_len(w, h));
        if w == 0 || h == 0 {
            prop_assert_eq!(hi, 0);
        } else if w > MAX_SIDE || h > MAX_SIDE {
            prop_assert_eq!(hi, usize::MAX);
        } else {
            prop_assert!(hi == usize::MAX || (hi as u128 >= 8 + w as u128 * h as u128 && hi as u128 <= u32::MAX as u128));
        }
        let weights_len = if fit && product(w, h) <= 64 { product(w, h) } else { weights_len };
        let weights = vec![1.0f32; weights_len];
        for (needed, hierarchical) in [(mc, false), (hi, true)] {
            let storage_len = if fit && needed <= 400 { needed } else { storage_len };
            let mut storage = vec![0xa5a5_a5a5u32; storage_len];
            let got = if hierarchical {
                call(|| Hierarchical::new(&weights, w, h, &mut storage).map(|_| ()))
            } else {
                call(|| MarginalConditional::new(&weights, w, h, &mut storage).map(|_| ()))
            };
            let want = if w == 0 || h == 0 {
                Err(Error::ZeroSize)
            } else if needed == usize::MAX {
                Err(Error::TooLarge)
            } else if weights_len != product(w, h) {
                Err(Error::LengthMismatch { expected: product(w, h), got: weights_len })
            } else if storage_len < needed {
                Err(Error::StorageTooSmall { needed, got: storage_len })
            } else {
                Ok(())
            };
            prop_assert_eq!(got, want, "hierarchical: {}", hierarchical);
            if want.is_err() {
                prop_assert!(storage.iter().all(|&x| x == 0xa5a5_a5a5), "storage written on error");
            } else {
                prop_assert!(storage[needed..].iter().all(|&x| x == 0xa5a5_a5a5), "wrote past storage_len");
            }
        }
    }

    /// `from_storage` with header words claiming any sizes and region lengths over a short
    /// storage: an error (or a load that samples inside the map), never a panic; the header's
    /// checks come in the documented order.
    #[test]
    fn header_sizes(
        w in prop_oneof![3 => 1u32..9, 1 => any::<u32>(), 1 => Just(1u32 << 24), 1 => Just((1u32 << 24) + 1)],
        h in prop_oneof![3 => 1u32..9, 1 => any::<u32>(), 1 => Just(65_536u32)],
        lens in prop::array::uniform4(prop_oneof![3 => 0u32..20, 1 => any::<u32>()]),
        true_lens in any::<bool>(),
        extra in 0usize..200,
    ) {
        for hierarchical in [false, true] {
            let tag = if hierarchical { u32::from_le_bytes(*b"wcHI") } else { u32::from_le_bytes(*b"wcMC") };
            let (wu, hu) = (w as usize, h as usize);
            let mut header = vec![tag.to_le(), warpcore::envmap::FORMAT_VERSION.to_le(), w.to_le(), h.to_le()];
            // Optionally the lengths a real storage of these sizes has (then only the storage
            // length can be wrong).
            let real = if true_lens && wu <= 8 && hu <= 8 {
                let n = if hierarchical { Hierarchical::storage_len(wu, hu) } else { MarginalConditional::storage_len(wu, hu) };
                let mut s = vec![0u32; n];
                let weights = vec![1.0f32; wu * hu];
                if hierarchical {
                    Hierarchical::new(&weights, wu, hu, &mut s).unwrap();
                } else {
                    MarginalConditional::new(&weights, wu, hu, &mut s).unwrap();
                }
                Some(s)
            } else {
                None
            };
            let mut storage = match &real {
                Some(s) => s[..(extra + HEADER_WORDS).min(s.len())].to_vec(),
                None => {
                    header.extend(lens.map(u32::to_le));
                    header.resize(HEADER_WORDS + extra, 0);
                    header
                }
            };
            storage.truncate(HEADER_WORDS + extra);
            let got = if hierarchical {
                call(|| Hierarchical::from_storage(&storage).map(|d| d.sample([0.3, 0.7])))
            } else {
                call(|| MarginalConditional::from_storage(&storage).map(|d| d.sample([0.3, 0.7])))
            };
            let side_ok = |x: usize| (1..=MAX_SIDE).contains(&x);
            let too_large = if hierarchical { Hierarchical::storage_len(wu, hu) } else { mc_len(wu, hu) } == usize::MAX;
            match got {
                Ok(s) => {
                    prop_assert!(real.is_some(), "loaded a header no build wrote");
                    prop_assert!((s.texel[0] as usize) < wu && (s.texel[1] as usize) < hu);
                }
                Err(Error::Corrupt { word: 2 }) => prop_assert!(!side_ok(wu) || (side_ok(hu) && too_large)),
                Err(Error::Corrupt { word: 3 }) => prop_assert!(side_ok(wu) && !side_ok(hu)),
                Err(Error::Corrupt { word }) => {
                    prop_assert!((4..8).contains(&word) && side_ok(wu) && side_ok(hu) && !too_large);
                    prop_assert!(real.is_none(), "the lengths of a real storage are right");
                }
                Err(Error::StorageTooSmall { needed, got }) => {
                    prop_assert_eq!(got, storage.len());
                    prop_assert!(needed > got && side_ok(wu) && side_ok(hu) && !too_large);
                }
                Err(e) => prop_assert!(false, "unexpected {:?}", e),
            }
        }
    }
}
