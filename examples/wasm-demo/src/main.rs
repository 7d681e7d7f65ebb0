//! Prints the determinism fingerprint of this build (native targets). The `_x16` forms must
//! give the same value; if they do not, both values are printed (and the comparison with the
//! golden value fails).
#[cfg(feature = "all")]
fn main() {
    let x8 = warpcore_demo::fingerprint::fingerprint();
    let x16 = warpcore_demo::fingerprint::fingerprint_x16();
    if x8 == x16 {
        println!("{x8:016x}");
    } else {
        println!("{x8:016x} (x8) != {x16:016x} (x16)");
    }
}
#[cfg(not(feature = "all"))]
fn main() {}
