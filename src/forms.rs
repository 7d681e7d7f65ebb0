//! The public forms of a lane-generic body: every warp is written once over
//! [`Lane`](crate::lanes::Lane) and published as a scalar, an `_x8` and an `_x16` function,
//! each a one-line forward to the body. [`lane_forms!`] writes those three wrappers from one
//! signature, so the forms cannot drift apart.

// A build without the `spherical` family uses neither macro.
#![allow(unused_macros)]

/// A signature shape with `L` read as the float lane and `U` as the integer lane: `L`, `U`,
/// arrays `[shape; N]` and tuples `(shape, ...)` of them.
macro_rules! lane_ty {
    ($l:ty, $u:ty, L) => { $l };
    ($l:ty, $u:ty, U) => { $u };
    ($l:ty, $u:ty, [$t:tt; $n:literal]) => { [lane_ty!($l, $u, $t); $n] };
    ($l:ty, $u:ty, ($($t:tt),+)) => { ($(lane_ty!($l, $u, $t)),+) };
}

/// The scalar, `_x8` and `_x16` forms of one lane-generic body:
///
/// ```text
/// lane_forms! {
///     /// The scalar form's documentation.
///     pub fn name, name_x8, name_x16 ["points"] (u: [L; 2]) -> [L; 2] = name_body;
/// }
/// ```
///
/// In the argument and result shapes `L` stands for `f32`, `f32x8`, `f32x16` and `U` for
/// `u32`, `u32x8`, `u32x16`; the string names what one call of a wide form takes (its docs
/// read "[`name`] on eight points at once; bit-identical to eight scalar calls").
macro_rules! lane_forms {
    ($(
        $(#[$attr:meta])*
        pub fn $f1:ident, $f8:ident, $f16:ident [$what:literal] $sig:tt -> $r:tt = $body:path;
    )+) => {$(
        lane_forms!(@form $(#[$attr])* $f1 (f32, u32) $sig -> $r = $body);
        lane_forms!(@form
            #[doc = concat!("[`", stringify!($f1), "`] on eight ", $what,
                " at once; bit-identical to eight scalar calls.")]
            $f8 (::wide::f32x8, ::wide::u32x8) $sig -> $r = $body);
        lane_forms!(@form
            #[doc = concat!("[`", stringify!($f1), "`] on sixteen ", $what,
                " at once; bit-identical to sixteen scalar calls.")]
            $f16 (::wide::f32x16, ::wide::u32x16) $sig -> $r = $body);
    )+};
    (@form $(#[$attr:meta])* $f:ident ($l:ty, $u:ty)
        ($($arg:ident: $t:tt),+) -> $r:tt = $body:path) => {
        $(#[$attr])*
        #[inline]
        pub fn $f($($arg: lane_ty!($l, $u, $t)),+) -> lane_ty!($l, $u, $r) {
            $body($($arg),+)
        }
    };
}
