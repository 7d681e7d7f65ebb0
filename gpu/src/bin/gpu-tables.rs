//! Writes the storage buffer of `shaders/warpcore_tables.wgsl` (the default build's tables,
//! `warpcore_gpu::tables::table_bytes`) to a file: `shaders/warpcore_tables.bin` in the
//! repository, for renderers that upload it from C, JavaScript or any other language.
//!
//! `cargo run -p warpcore-gpu --bin gpu-tables [-- PATH]` (default
//! `shaders/warpcore_tables.bin`); the crate's test `the_committed_buffer_is_current` fails
//! when the committed file differs from what this writes.

fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "shaders/warpcore_tables.bin".into());
    let bytes = warpcore_gpu::tables::table_bytes();
    if let Err(e) = std::fs::write(&path, &bytes) {
        eprintln!("gpu-tables: {path}: {e}");
        std::process::exit(1);
    }
    println!("{path}: {} bytes", bytes.len());
}
