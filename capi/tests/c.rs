//! The C API tested from C: `capi/tests/c/*.c` are compiled with the system C compiler (`cc`,
//! or `$CC`) as strict C99 against `include/warpcore.h`, linked with the static library
//! cargo built for this test run, and run.
//!
//! * `fingerprint.c` computes the determinism fingerprint through the C API; it must equal
//!   `tests/golden/fingerprint.txt` and the Rust crate's own fingerprint. Its extra lines
//!   hash the functions the fingerprint does not cover; this file recomputes each with the
//!   Rust crate.
//! * `rules.c` checks the pointer and count rules, the env-map errors and a storage written
//!   to a file and read back.
//! * The header also compiles as C++ (`c++ -std=c++11 -pedantic`), warnings as errors.
#![cfg(all(
    feature = "disk",
    feature = "triangle",
    feature = "sphere",
    feature = "pmj02bn",
    feature = "sequence",
    feature = "envmap"
))]

#[path = "../../examples/wasm-demo/src/fingerprint.rs"]
mod fingerprint;

use fingerprint::{Hasher, N, input, unit};
use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The static library of this build: `target/<profile>/libwarpcore_capi.a`, next to the
/// `deps/` directory holding this test executable. Cargo does not build a library that is
/// only a `staticlib`/`cdylib` for integration tests, so this runs `cargo build` for it (once
/// per test process; a no-op when it is up to date) with the same profile.
fn staticlib() -> PathBuf {
    static LIB: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    LIB.get_or_init(build_staticlib).clone()
}

fn build_staticlib() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
    let lib = profile_dir.join("libwarpcore_capi.a");
    {
        let release = profile_dir.file_name().is_some_and(|n| n == "release");
        let mut cargo = Command::new(env!("CARGO"));
        cargo.args(["build", "-p", "warpcore-capi", "--lib"]);
        if release {
            cargo.arg("--release");
        }
        let status = cargo.current_dir(root()).status().expect("cargo");
        assert!(status.success(), "building the static library failed");
    }
    assert!(lib.exists(), "no static library at {}", lib.display());
    lib
}

fn compiler(var: &str, default: &str) -> String {
    std::env::var(var).unwrap_or_else(|_| default.to_string())
}

/// Compiles `capi/tests/c/<name>.c` and runs it; returns its stdout (the test fails on a
/// compiler error or a nonzero exit).
fn compile_and_run(name: &str) -> String {
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let exe = out_dir.join(name);
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/c/{name}.c"));
    let cc = compiler("CC", "cc");
    let status = Command::new(&cc)
        .args([
            "-std=c99",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .arg(&src)
        .arg(staticlib())
        // What a `std` static library needs on Linux (`--print native-static-libs`).
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lutil"])
        .arg("-o")
        .arg(&exe)
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(status.success(), "{cc} failed on {}", src.display());
    let run = Command::new(&exe)
        .current_dir(&out_dir)
        .output()
        .expect("run the C test");
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    eprintln!("{stdout}{}", String::from_utf8_lossy(&run.stderr));
    assert!(run.status.success(), "{name} failed: {:?}", run.status);
    stdout
}

/// `name hash` lines of the C program's output.
fn hashes(stdout: &str) -> HashMap<String, String> {
    stdout
        .lines()
        .filter_map(|l| l.split_once(' '))
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

#[test]
fn c_fingerprint_matches_the_golden_file_and_the_crate() {
    let out = hashes(&compile_and_run("fingerprint"));
    let golden = std::fs::read_to_string(root().join("tests/golden/fingerprint.txt")).unwrap();
    let rust = format!("{:016x}", fingerprint::fingerprint());
    assert_eq!(
        rust,
        golden.trim(),
        "the crate itself disagrees with the golden file"
    );
    assert_eq!(
        out["fingerprint"],
        golden.trim(),
        "C output bits differ from the crate's"
    );

    // The extras, recomputed with the crate.
    let hash = |f: &dyn Fn(&mut Hasher)| {
        let mut h = Hasher::new();
        f(&mut h);
        format!("{:016x}", h.finish())
    };
    let mut want: HashMap<&str, String> = HashMap::new();
    want.insert(
        "disk_polar4_inverse",
        hash(&|h| {
            for i in 0..N {
                let (u, q) = warpcore::disk::polar4_inverse(input(i));
                h.floats(&u);
                h.word(q);
            }
        }),
    );
    want.insert(
        "pmj02bn_shuffle",
        hash(&|h| {
            for i in 0..N as u32 {
                h.word(warpcore::pmj02bn::shuffle(
                    i.wrapping_mul(2_654_435_761),
                    0xabcd,
                ));
            }
            h.word(warpcore::pmj02bn::POINTS as u32);
            h.word(warpcore::pmj02bn::SETS as u32);
        }),
    );
    use warpcore::envmap::{MarginalConditional, image};
    want.insert(
        "envmap_luminance",
        hash(&|h| {
            for i in 0..N {
                h.floats(&[image::luminance(input(i))]);
            }
        }),
    );
    want.insert(
        "envmap_latlong_pdf_to_solid_angle",
        hash(&|h| {
            for i in 0..N {
                let [p, v]: [f32; 2] = input(i);
                h.floats(&[image::latlong_pdf_to_solid_angle(p, v)]);
            }
        }),
    );
    let weights: [f32; 91] = std::array::from_fn(|k| match k {
        3 | 40 | 41 => 0.0,
        17 => -2.0,
        60 => f32::NAN,
        77 => 1.0e6,
        _ => unit(k as u32) + 0.01,
    });
    want.insert(
        "envmap_image",
        hash(&|h| {
            let mut w = weights;
            image::latlong_solid_angle_weights(&mut w, 13, 7).unwrap();
            h.floats(&w);
            let rgb: Vec<[f32; 3]> = (0..91).map(|k| input(200 + k)).collect();
            let mut dst = vec![[0.0f32; 3]; 64];
            image::latlong_to_equal_area(&rgb, 13, 7, &mut dst, 8, 3).unwrap();
            for t in &dst {
                h.floats(t);
            }
        }),
    );
    want.insert(
        "envmap_storage",
        hash(&|h| {
            let n = MarginalConditional::storage_len(13, 7);
            let mut s = vec![0u32; n];
            MarginalConditional::new(&weights, 13, 7, &mut s).unwrap();
            for w in &s {
                h.word(u32::from_le(*w));
            }
            h.word(n as u32);
            h.word(warpcore::envmap::Hierarchical::storage_len(13, 7) as u32);
            h.word(warpcore::envmap::Hierarchical::storage_len(4096, 2048) as u32);
        }),
    );
    for (name, want) in &want {
        assert_eq!(out.get(*name), Some(want), "{name}: C and Rust disagree");
    }
}

#[test]
fn c_pointer_rules_errors_and_files() {
    let out = compile_and_run("rules");
    let last = out.lines().last().unwrap_or("");
    assert!(last.ends_with(" passed, 0 failed"), "{last}");
    let passed: usize = last.split(' ').next().unwrap().parse().unwrap();
    assert!(passed > 100, "only {passed} checks ran");
}

/// The header is valid C++ too (`extern "C"`, no C-only constructs), warnings as errors.
#[test]
fn header_compiles_as_cpp() {
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let src = out_dir.join("header.cpp");
    std::fs::write(
        &src,
        "#include \"warpcore.h\"\n#include <cstdio>\nint main() {\n  float u[2] = {0.25f, \
         0.75f}, p[2];\n  std::printf(\"%zu\\n\", wc_disk_concentric(u, p, 1));\n  return \
         WC_ERR_ZERO_SIZE < 0 ? 0 : 1;\n}\n",
    )
    .unwrap();
    let cxx = compiler("CXX", "c++");
    let status = Command::new(&cxx)
        .args([
            "-std=c++11",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
            "-fsyntax-only",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .arg(&src)
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C++ compiler `{cxx}`: {e}"));
    assert!(status.success(), "the header does not compile as C++");
}

/// The C++ example (`capi/examples/envlight.cpp`), small: it renders, writes a PFM, and
/// exits nonzero when its environment estimate disagrees with the exact sum over the map.
#[test]
fn cpp_example_renders_and_checks_itself() {
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let exe = out_dir.join("envlight");
    let cxx = compiler("CXX", "c++");
    let status = Command::new(&cxx)
        .args([
            "-std=c++17",
            "-O2",
            "-Wall",
            "-Wextra",
            "-Werror",
            "-pedantic",
        ])
        .arg("-I")
        .arg(root().join("include"))
        .arg(Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/envlight.cpp"))
        .arg(staticlib())
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lutil"])
        .arg("-o")
        .arg(&exe)
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C++ compiler `{cxx}`: {e}"));
    assert!(status.success(), "{cxx} failed on envlight.cpp");
    let pfm = out_dir.join("envlight.pfm");
    let run = Command::new(&exe)
        .arg(root().join("tests/data/envmaps/sunset.pfm"))
        .arg(&pfm)
        .args(["32", "16"])
        .output()
        .unwrap();
    eprintln!("{}", String::from_utf8_lossy(&run.stdout));
    assert!(run.status.success(), "envlight failed: {run:?}");
    let bytes = std::fs::read(&pfm).unwrap();
    assert!(bytes.starts_with(b"PF\n32 32\n-1.0\n"));
    assert_eq!(bytes.len(), 14 + 32 * 32 * 3 * 4);
}

/// The README's C example compiles (strict C99) and runs.
#[test]
fn readme_c_example_runs() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let code = readme
        .split("```c\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a ```c block in the README");
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let (src, exe) = (out_dir.join("readme.c"), out_dir.join("readme"));
    std::fs::write(&src, code).unwrap();
    let cc = compiler("CC", "cc");
    let status = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-pedantic"])
        .arg("-I")
        .arg(root().join("include"))
        .arg(&src)
        .arg(staticlib())
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lutil"])
        .arg("-o")
        .arg(&exe)
        .status()
        .unwrap();
    assert!(status.success(), "the README's C example does not compile");
    let run = Command::new(&exe).output().unwrap();
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success(), "{run:?}");
    assert!(stdout.starts_with("64 samples, first ("), "{stdout}");
}
