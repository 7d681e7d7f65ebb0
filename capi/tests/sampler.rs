//! The sampler's C API tested from C: `capi/tests/c/sampler.c` is compiled with the system C
//! compiler (`cc`, or `$CC`) as strict C99 against `include/warpcore.h`, linked with the
//! static library cargo built for this test run, and run.
//!
//! * Its `name hash` lines must equal the Rust crate's (`capi/examples/sampler_hashes.rs`, the
//!   same cases through `warpcore::sampler`): bit-identity for every pattern, domain path,
//!   split, draw, `draw_u32`, `rnd` and slice.
//! * Its checks (promises, error returns, garbage) must all pass.
//! * The path tracer's loop in `docs/capi.md` compiles (strict C99) and runs.
#![cfg(feature = "blue-noise")]

#[path = "../examples/sampler_hashes.rs"]
mod sampler_hashes;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The static library of this build, `target/<profile>/libwarpcore_capi.a` (as `c.rs`: cargo
/// builds no `staticlib` for integration tests, so this runs `cargo build` once).
fn staticlib() -> PathBuf {
    static LIB: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    LIB.get_or_init(|| {
        let exe = std::env::current_exe().unwrap();
        let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
        let mut cargo = Command::new(env!("CARGO"));
        cargo.args(["build", "-p", "warpcore-capi", "--lib"]);
        if profile_dir.file_name().is_some_and(|n| n == "release") {
            cargo.arg("--release");
        }
        let status = cargo.current_dir(root()).status().expect("cargo");
        assert!(status.success(), "building the static library failed");
        let lib = profile_dir.join("libwarpcore_capi.a");
        assert!(lib.exists(), "no static library at {}", lib.display());
        lib
    })
    .clone()
}

/// Compiles `src` (strict C99, warnings as errors) into `exe`, runs it, returns its stdout
/// (the test fails on a compiler error or a nonzero exit).
fn compile_and_run(src: &Path, exe_name: &str) -> String {
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let exe = out_dir.join(exe_name);
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".to_string());
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
        .arg(src)
        .arg(staticlib())
        // What a `std` static library needs on Linux (`--print native-static-libs`).
        .args(["-lpthread", "-ldl", "-lm", "-lrt", "-lutil"])
        .arg("-o")
        .arg(&exe)
        .status()
        .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
    assert!(status.success(), "{cc} failed on {}", src.display());
    let run = Command::new(&exe).output().expect("run the C program");
    let stdout = String::from_utf8_lossy(&run.stdout).into_owned();
    eprintln!("{stdout}{}", String::from_utf8_lossy(&run.stderr));
    assert!(run.status.success(), "{exe_name} failed: {:?}", run.status);
    stdout
}

#[test]
fn c_sampler_matches_the_crate_and_keeps_the_rules() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/c/sampler.c");
    let out = compile_and_run(&src, "sampler");
    let got: HashMap<&str, &str> = out.lines().filter_map(|l| l.split_once(' ')).collect();
    let want = sampler_hashes::hashes();
    assert_eq!(want.len(), 28);
    for (name, hash) in &want {
        assert_eq!(
            got.get(name.as_str()),
            Some(&hash.as_str()),
            "{name}: C and Rust disagree"
        );
    }
    let last = out.lines().last().unwrap_or("");
    assert!(last.ends_with(" passed, 0 failed"), "{last}");
    let passed: usize = last.split(' ').next().unwrap().parse().unwrap();
    assert!(passed > 5000, "only {passed} checks ran");
}

/// The path tracer's loop of `docs/capi.md` (the ```c block of its sampler section) compiles
/// and runs: it prints its estimate, which must be close to the integral it knows.
#[test]
fn docs_c_sampler_loop_runs() {
    let doc = std::fs::read_to_string(root().join("docs/capi.md")).unwrap();
    let section = doc
        .split("\n## Sampler")
        .nth(1)
        .expect("a \"## Sampler\" section in docs/capi.md");
    let code = section
        .split("```c\n")
        .nth(1)
        .and_then(|rest| rest.split("```").next())
        .expect("a ```c block in the sampler section of docs/capi.md");
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&out_dir).unwrap();
    let src = out_dir.join("docs_sampler.c");
    std::fs::write(&src, code).unwrap();
    let stdout = compile_and_run(&src, "docs_sampler");
    assert!(stdout.starts_with("estimate "), "{stdout}");
}
