//! Prints the determinism fingerprint of this build (native targets).
#[cfg(feature = "all")]
fn main() {
    println!("{:016x}", warpcore_demo::fingerprint::fingerprint());
}
#[cfg(not(feature = "all"))]
fn main() {}
