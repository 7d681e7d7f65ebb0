//! Prints a few warped points from each disk warp: a quick look at what the crate does.
//! `cargo run --release --example points`
use warpcore::disk;

fn main() {
    // A 4x4 grid of cell centres, warped three ways.
    println!(
        "{:>14} {:>22} {:>22} {:>22}",
        "u", "polar", "concentric", "polar4 (i % 4)"
    );
    for i in 0..16u32 {
        let u = [((i % 4) as f32 + 0.5) / 4.0, ((i / 4) as f32 + 0.5) / 4.0];
        let p = disk::polar(u);
        let c = disk::concentric(u);
        let q = disk::polar4(u, i % 4);
        println!(
            "({:.3}, {:.3})  ({:+.4}, {:+.4})  ({:+.4}, {:+.4})  ({:+.4}, {:+.4})",
            u[0], u[1], p[0], p[1], c[0], c[1], q[0], q[1]
        );
    }
}
