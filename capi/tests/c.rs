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
//! * `sampler.c` (with the `blue-noise` feature) prints one `name hash` line per case of
//!   `capi/examples/sampler_hashes.rs`, which must equal the Rust crate's (bit-identity for
//!   every pattern, domain path, split, draw, `draw_u32`, `rnd` and slice), and checks the
//!   sampler's promises and error returns.
//! * `hostile.c` makes randomized hostile calls against arrays flush with guard pages and
//!   reports which (function, documented outcome) rows it reached; [`TABLE`] lists every
//!   function's documented outcomes, and the test fails on a function or outcome without its
//!   row.
//! * The header also compiles as C++ (`c++ -std=c++11 -pedantic`), warnings as errors.
//! * Every ```c block of README.md and docs/*.md compiles with exactly the build line its page
//!   prints (named by a `<!-- docs-test: cc ... -->` marker before the block), warnings as
//!   errors, and runs.
//!
//! Environment: `WARPCORE_CFLAGS` adds compiler flags to every C and C++ compile and link
//! (CI: `-fsanitize=address,undefined -fno-sanitize-recover=all`, and `-m32`);
//! `WARPCORE_CAPI_LIB` links that static library instead of building one (CI: a nightly
//! `-Zsanitizer=address` build, or the `i686-unknown-linux-gnu` one for `-m32`);
//! `WARPCORE_HOSTILE_ROUNDS` sets `hostile.c`'s rounds (about 50 calls each).
//!
//! Every family is needed: `Cargo.toml` names the features this target requires.

#[cfg(feature = "blue-noise")]
#[path = "../examples/sampler_hashes.rs"]
mod sampler_hashes;

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::process::Command;
use warpcore_registry::fingerprint::{self, Hasher};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The static library of this build: `target/<profile>/libwarpcore_capi.a`, next to the
/// `deps/` directory holding this test executable. Cargo does not build a library that is
/// only a `staticlib`/`cdylib` for integration tests, so this runs `cargo build` for it (once
/// per test process; a no-op when it is up to date) with the same profile.
fn staticlib() -> PathBuf {
    static LIB: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();
    LIB.get_or_init(|| match std::env::var_os("WARPCORE_CAPI_LIB") {
        // Relative to the workspace root (tests run in `capi/`).
        Some(lib) => root().join(lib),
        None => build_staticlib(),
    })
    .clone()
}

/// `WARPCORE_CFLAGS`, split at whitespace.
fn extra_flags() -> Vec<String> {
    std::env::var("WARPCORE_CFLAGS")
        .unwrap_or_default()
        .split_whitespace()
        .map(str::to_string)
        .collect()
}

fn build_staticlib() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let profile_dir = exe.parent().unwrap().parent().unwrap().to_path_buf();
    let lib = profile_dir.join("libwarpcore_capi.a");
    {
        let release = profile_dir.file_name().is_some_and(|n| n == "release");
        let mut cargo = Command::new(env!("CARGO"));
        // `-p warpcore` as well: the core crate then resolves with its default features, as
        // in the workspace's `cargo test`, whose core library this build reuses (alone, capi
        // names the same families without `default` and the core would be compiled again).
        cargo.args(["build", "-p", "warpcore-capi", "-p", "warpcore", "--lib"]);
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

/// What a `std` static library needs on Linux (`--print native-static-libs`).
const STD_LIBS: [&str; 5] = ["-lpthread", "-ldl", "-lm", "-lrt", "-lutil"];

/// The directory the compiled programs go to.
fn out_dir() -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-c");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Compiles `src` with `$var` (or `default`) as `-std=<std>`, warnings as errors, with
/// `WARPCORE_CFLAGS` and this checkout's `include/`: optimised and linked with the static
/// library into `exe`, or (`exe` = `None`) syntax only. The test fails on a compiler error.
fn compile(var: &str, default: &str, std: &str, src: &Path, exe: Option<&Path>) {
    let cc = compiler(var, default);
    let mut cmd = Command::new(&cc);
    cmd.arg(format!("-std={std}"))
        .args(["-Wall", "-Wextra", "-Werror", "-pedantic"])
        .args(extra_flags())
        .arg("-I")
        .arg(root().join("include"))
        .arg(src);
    match exe {
        Some(exe) => cmd
            .arg("-O2")
            .arg(staticlib())
            .args(STD_LIBS)
            .arg("-o")
            .arg(exe),
        None => cmd.arg("-fsyntax-only"),
    };
    let status = cmd
        .status()
        .unwrap_or_else(|e| panic!("cannot run the compiler `{cc}`: {e}"));
    assert!(status.success(), "{cc} failed on {}", src.display());
}

/// Compiles `capi/tests/c/<name>.c` and runs it; returns its stdout (the test fails on a
/// compiler error or a nonzero exit).
fn compile_and_run(name: &str) -> String {
    compile_and_run_with(name, &[])
}

fn compile_and_run_with(name: &str, args: &[&str]) -> String {
    let exe = out_dir().join(name);
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("tests/c/{name}.c"));
    compile("CC", "cc", "c99", &src, Some(&exe));
    let run = Command::new(&exe)
        .args(args)
        .current_dir(out_dir())
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

    // The extras: each line names a registry entry, whose own piece gives the same hash.
    let mut extras = 0;
    for (name, got) in &out {
        if name == "fingerprint" || got == "failed" {
            continue;
        }
        let e = warpcore_registry::entries()
            .find(|e| e.name == name.as_str())
            .unwrap_or_else(|| panic!("fingerprint.c hashed {name}, which is no registry entry"));
        let mut h = Hasher::new();
        assert!(
            fingerprint::entry_hash(e, &mut h),
            "{name} has no hash of its own"
        );
        assert_eq!(
            *got,
            format!("{:016x}", h.finish()),
            "{name}: C and Rust disagree"
        );
        extras += 1;
    }
    assert!(
        extras >= 19,
        "fingerprint.c hashed only {extras} extra functions"
    );
    // Every microfacet function is hashed through C (none is in the golden fingerprint).
    for e in warpcore_registry::entries().filter(|e| e.name.starts_with("microfacet::")) {
        assert!(
            out.contains_key(e.name),
            "fingerprint.c does not hash {}",
            e.name
        );
    }
}

/// `sampler.c`'s hashes equal the crate's, and its checks (promises, error returns, garbage)
/// all pass.
#[cfg(feature = "blue-noise")]
#[test]
fn c_sampler_matches_the_crate_and_keeps_the_rules() {
    let out = compile_and_run("sampler");
    let got = hashes(&out);
    let want = sampler_hashes::hashes();
    assert_eq!(want.len(), 32);
    for (name, hash) in &want {
        assert_eq!(got.get(name), Some(hash), "{name}: C and Rust disagree");
    }
    let passed = passed(&out);
    assert!(passed > 5000, "only {passed} checks ran");
}

/// The count of a test program's last line, `N passed, 0 failed` (the test fails on
/// another last line).
fn passed(out: &str) -> usize {
    let last = out.lines().last().unwrap_or("");
    assert!(last.ends_with(" passed, 0 failed"), "{last}");
    last.split(' ').next().unwrap().parse().unwrap()
}

#[test]
fn c_pointer_rules_errors_and_files() {
    let passed = passed(&compile_and_run("rules"));
    assert!(passed > 100, "only {passed} checks ran");
}

/// The header is valid C++ too (`extern "C"`, no C-only constructs), warnings as errors.
#[test]
fn header_compiles_as_cpp() {
    let src = out_dir().join("header.cpp");
    std::fs::write(
        &src,
        "#include \"warpcore.h\"\n#include <cstdio>\nint main() {\n  float u[2] = {0.25f, \
         0.75f}, p[2];\n  std::printf(\"%zu\\n\", wc_disk_concentric(u, p, 1));\n  return \
         WC_ERR_ZERO_SIZE < 0 ? 0 : 1;\n}\n",
    )
    .unwrap();
    compile("CXX", "c++", "c++11", &src, None);
}

/// The C++ example (`capi/examples/envlight.cpp`), small: it renders, writes a PFM, and
/// exits nonzero when its environment estimate disagrees with the exact sum over the map.
#[test]
fn cpp_example_renders_and_checks_itself() {
    let exe = out_dir().join("envlight");
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/envlight.cpp");
    compile("CXX", "c++", "c++17", &src, Some(&exe));
    let pfm = out_dir().join("envlight.pfm");
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

/// The marker that precedes every ```c block of the documentation: the build line the page
/// prints for it, e.g. `<!-- docs-test: cc -std=c99 -Iinclude app.c
/// target/release/libwarpcore_capi.a -o app -->`.
const DOCS_MARKER: &str = "<!-- docs-test: ";

/// A ```c block of a Markdown page: its line, its build line (from the marker) and its code.
struct CBlock {
    line: usize,
    command: Option<String>,
    code: String,
}

fn c_blocks(markdown: &str) -> Vec<CBlock> {
    let lines: Vec<&str> = markdown.lines().collect();
    let mut blocks = Vec::new();
    let mut i = 0;
    while i < lines.len() {
        if lines[i].trim_end() != "```c" {
            i += 1;
            continue;
        }
        let command = i
            .checked_sub(1)
            .and_then(|j| lines[j].trim().strip_prefix(DOCS_MARKER))
            .and_then(|rest| rest.strip_suffix("-->"))
            .map(|c| c.trim().to_string());
        let start = i;
        let mut code = String::new();
        i += 1;
        while i < lines.len() && lines[i].trim_end() != "```" {
            code.push_str(lines[i]);
            code.push('\n');
            i += 1;
        }
        assert!(
            i < lines.len(),
            "an unclosed ```c block at line {}",
            start + 1
        );
        blocks.push(CBlock {
            line: start + 1,
            command,
            code,
        });
        i += 1;
    }
    blocks
}

/// Every ```c block of README.md and docs/*.md is a whole program, compiled with exactly the
/// build line its page prints (named by the marker before the block, and printed verbatim
/// elsewhere on the page), plus `-Wall -Wextra -pedantic -Werror`, then run from the
/// repository root: it must exit with 0. In the printed line `app.c` becomes the block,
/// `-Iinclude` this checkout's `include/`, `target/release/libwarpcore_capi.a` the static
/// library of this test run (a debug one also gets the `std` libraries the page documents
/// for debug builds) and `app` the executable; `cc` is `$CC` when set. (`-std=c99` with C11's
/// `aligned_alloc` was an implicit declaration and a crash at run time: the flags the page
/// prints are the ones that must work.)
#[test]
fn docs_c_blocks_compile_with_their_printed_build_line_and_run() {
    let mut pages = vec![root().join("README.md")];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    docs.sort();
    pages.extend(docs);
    let out_dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("capi-docs");
    std::fs::create_dir_all(&out_dir).unwrap();
    let lib = staticlib();
    let release = lib
        .parent()
        .and_then(Path::file_name)
        .is_some_and(|n| n == "release");
    let mut compiled = 0;
    for page in &pages {
        let markdown = std::fs::read_to_string(page).unwrap();
        let name = page.strip_prefix(root()).unwrap().display().to_string();
        for block in c_blocks(&markdown) {
            let at = format!("{name}:{}", block.line);
            let command = block.command.unwrap_or_else(|| {
                panic!("{at}: a ```c block without its build line (`{DOCS_MARKER}cc ... -->` on the line before)")
            });
            // The page prints this line (outside the marker).
            let printed = markdown
                .lines()
                .filter(|l| !l.trim().starts_with(DOCS_MARKER))
                .any(|l| l.contains(&command));
            assert!(
                printed,
                "{at}: the build line `{command}` is not printed on the page"
            );
            let words: Vec<&str> = command.split_whitespace().collect();
            assert_eq!(words[0], "cc", "{at}: a build line that is not `cc ...`");
            for needed in [
                "app.c",
                "-Iinclude",
                "target/release/libwarpcore_capi.a",
                "app",
            ] {
                assert!(
                    words.contains(&needed),
                    "{at}: `{command}` lacks `{needed}`"
                );
            }
            let stem = format!("{}_{}", name.replace(['/', '.'], "_"), block.line);
            let (src, exe) = (out_dir.join(format!("{stem}.c")), out_dir.join(&stem));
            std::fs::write(&src, &block.code).unwrap();
            let cc = compiler("CC", "cc");
            let mut cmd = Command::new(&cc);
            for word in &words[1..] {
                match *word {
                    "app.c" => cmd.arg(&src),
                    "-Iinclude" => cmd.arg(format!("-I{}", root().join("include").display())),
                    "target/release/libwarpcore_capi.a" => cmd.arg(&lib),
                    "app" => cmd.arg(&exe),
                    other => cmd.arg(other),
                };
            }
            cmd.args(["-Wall", "-Wextra", "-pedantic", "-Werror"]);
            cmd.args(extra_flags());
            if !release {
                cmd.args(STD_LIBS);
            }
            let status = cmd
                .status()
                .unwrap_or_else(|e| panic!("cannot run the C compiler `{cc}`: {e}"));
            assert!(status.success(), "{at}: `{command}` fails on the block");
            let run = Command::new(&exe).current_dir(root()).output().unwrap();
            let stdout = String::from_utf8_lossy(&run.stdout);
            eprintln!("{at}: {stdout}{}", String::from_utf8_lossy(&run.stderr));
            assert!(run.status.success(), "{at}: the program failed: {run:?}");
            compiled += 1;
        }
    }
    // docs/quickstart.md: the quick start and the environment-map quick start (which reads
    // park.pfm and flips its rows); docs/capi.md: the storage round trip and the path tracer.
    assert!(compiled >= 4, "{compiled} C blocks");
    let quickstart = std::fs::read_to_string(root().join("docs/quickstart.md")).unwrap();
    let envmap = quickstart
        .split("## Environment maps: a quick start")
        .nth(1)
        .and_then(|section| section.split("```c\n").nth(1))
        .expect("a ```c block in docs/quickstart.md's environment-map quick start");
    assert!(envmap.contains("park.pfm") && envmap.contains("h - 1 - r"));
}

/// Every C function x every documented outcome: the rows `hostile.c` must reach. Outcomes of
/// the `WC_ERR_*` functions are the codes; of the `size_t` functions: `n` (all written),
/// `in-place`, `capped` (`min(n, 4 n_points)`), and the documented reasons for 0: `0:n=0`,
/// `0:null`, `0:misaligned`, `0:size` (a count whose byte size overflows), `0:overlap`,
/// `0:invalid-storage`, `0:size=0`; of `storage_len`: `words`, `0:zero-side`, `SIZE_MAX`.
/// The sampler: its draws return `n` (or `count`, for the slice), and 0 for `0:n-range` (`n`
/// outside 1..=4), `0:n_dims-range`, `0:count=0`, `0:null`, `0:misaligned`, `0:size` and
/// `0:unknown-pattern`; its constructors give a `sampler`, or for an `unknown-pattern` the
/// documented value; `wc_sampler_pattern_supported` returns `1` or `0`.
///
/// [`hostile_calls_reach_every_documented_outcome`] checks the table against the header
/// (every declared function has rows, and the rows are exactly the outcomes its
/// documentation names) and against what `hostile.c` reached.
const TABLE: &[(&str, &[&str])] = {
    const MAP: &[&str] = &[
        "n",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
    ];
    const MAP_IN_PLACE: &[&str] = &[
        "n",
        "in-place",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
    ];
    const GEN: &[&str] = &["n", "0:n=0", "0:null", "0:misaligned", "0:size"];
    const FOUR: &[&str] = &[
        "n",
        "capped",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
    ];
    const LEN: &[&str] = &["words", "0:zero-side", "SIZE_MAX"];
    const BUILD: &[&str] = &[
        "WC_OK",
        "WC_ERR_ZERO_SIZE",
        "WC_ERR_TOO_LARGE",
        "WC_ERR_STORAGE_TOO_SMALL",
        "WC_ERR_INVALID_ARGUMENT",
        "WC_ERR_INFINITE_WEIGHT",
    ];
    const CHECK: &[&str] = &[
        "WC_OK",
        "WC_ERR_INVALID_ARGUMENT",
        "WC_ERR_STORAGE_TOO_SMALL",
        "WC_ERR_WRONG_FORMAT",
        "WC_ERR_UNSUPPORTED_VERSION",
        "WC_ERR_CORRUPT",
    ];
    const SAMPLE: &[&str] = &[
        "n",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
        "0:invalid-storage",
    ];
    const PDF: &[&str] = &[
        "n",
        "in-place",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
        "0:invalid-storage",
    ];
    const IMAGE: &[&str] = &[
        "WC_OK",
        "WC_ERR_ZERO_SIZE",
        "WC_ERR_TOO_LARGE",
        "WC_ERR_INVALID_ARGUMENT",
    ];
    const DRAW: &[&str] = &[
        "n",
        "0:n-range",
        "0:null",
        "0:misaligned",
        "0:unknown-pattern",
    ];
    const SAMPLER: &[&str] = &["sampler", "unknown-pattern"];
    const SAMPLE_DIRECTION: &[&str] = &[
        "n",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
        "0:unknown-layout",
        "0:invalid-storage",
    ];
    const PDF_DIRECTION: &[&str] = &[
        "n",
        "in-place",
        "0:n=0",
        "0:null",
        "0:misaligned",
        "0:size",
        "0:overlap",
        "0:unknown-layout",
        "0:invalid-storage",
    ];
    &[
        ("wc_disk_polar", MAP_IN_PLACE),
        ("wc_disk_polar_inverse", MAP_IN_PLACE),
        ("wc_disk_concentric", MAP_IN_PLACE),
        ("wc_disk_concentric_inverse", MAP_IN_PLACE),
        ("wc_disk_polar4", FOUR),
        ("wc_disk_polar4_inverse", MAP_IN_PLACE),
        ("wc_disk_concentric4", FOUR),
        ("wc_disk_concentric4_inverse", MAP_IN_PLACE),
        ("wc_spherical_triangle", MAP),
        ("wc_spherical_triangle_inverse", MAP_IN_PLACE),
        ("wc_spherical_rectangle", MAP),
        ("wc_spherical_rectangle_inverse", MAP_IN_PLACE),
        ("wc_spherical_triangle_cosine", MAP),
        ("wc_spherical_rectangle_cosine", MAP),
        ("wc_spherical_cone", MAP),
        ("wc_spherical_cone_inverse", MAP_IN_PLACE),
        (
            "wc_spherical_cone_solid_angle",
            &["omega", "0:null", "0:misaligned"],
        ),
        (
            "wc_spherical_triangle_solid_angle",
            &["omega", "0:null", "0:misaligned"],
        ),
        (
            "wc_spherical_rectangle_solid_angle",
            &["omega", "0:null", "0:misaligned"],
        ),
        ("wc_triangle_uniform", MAP),
        ("wc_triangle_uniform_inverse", MAP_IN_PLACE),
        ("wc_triangle_sqrt_map", MAP),
        ("wc_triangle_sqrt_map_inverse", MAP_IN_PLACE),
        ("wc_triangle_basu_owen", GEN),
        ("wc_triangle_basu_owen_permuted", GEN),
        ("wc_sphere_equal_area", MAP),
        ("wc_sphere_equal_area_inverse", MAP_IN_PLACE),
        ("wc_sphere_equirect", MAP),
        ("wc_sphere_equirect_inverse", MAP_IN_PLACE),
        ("wc_sphere_uniform", MAP),
        ("wc_sphere_uniform_inverse", MAP_IN_PLACE),
        ("wc_sphere_uniform_hemisphere", MAP),
        ("wc_sphere_uniform_hemisphere_inverse", MAP_IN_PLACE),
        ("wc_sphere_cosine_hemisphere", MAP),
        ("wc_sphere_cosine_hemisphere_inverse", MAP_IN_PLACE),
        ("wc_sphere_equal_area_wrap", MAP_IN_PLACE),
        (
            "wc_sphere_equal_area_wrap_texel",
            &[
                "n",
                "in-place",
                "0:n=0",
                "0:null",
                "0:misaligned",
                "0:size",
                "0:overlap",
                "0:size=0",
            ],
        ),
        ("wc_microfacet_ggx_d", MAP_IN_PLACE),
        ("wc_microfacet_ggx_g1", MAP_IN_PLACE),
        ("wc_microfacet_ggx_g2", MAP_IN_PLACE),
        ("wc_microfacet_ggx_visible_normal", MAP_IN_PLACE),
        ("wc_microfacet_ggx_visible_normal_pdf", MAP_IN_PLACE),
        ("wc_microfacet_ggx_reflect", MAP_IN_PLACE),
        ("wc_microfacet_ggx_reflect_pdf", MAP_IN_PLACE),
        ("wc_microfacet_ggx_reflect_bounded", MAP_IN_PLACE),
        ("wc_microfacet_ggx_reflect_bounded_pdf", MAP_IN_PLACE),
        ("wc_sphere_equal_area_pdf_to_solid_angle", MAP_IN_PLACE),
        ("wc_sphere_cosine_hemisphere_pdf", MAP_IN_PLACE),
        ("wc_sphere_equirect_pdf_to_solid_angle", MAP_IN_PLACE),
        ("wc_pmj02bn_sample", GEN),
        ("wc_pmj02bn_raw", GEN),
        ("wc_pmj02bn_shuffle", MAP_IN_PLACE),
        ("wc_pmj02bn_points", &["value"]),
        ("wc_pmj02bn_sets", &["value"]),
        ("wc_sampler_pattern_supported", &["1", "0"]),
        ("wc_sampler_new", SAMPLER),
        ("wc_sampler_new_frame", SAMPLER),
        ("wc_sampler_domain", SAMPLER),
        ("wc_sampler_split", SAMPLER),
        ("wc_sampler_draw", DRAW),
        ("wc_sampler_draw_u32", DRAW),
        ("wc_sampler_rnd", DRAW),
        (
            "wc_sampler_draw_slice",
            &[
                "count",
                "0:count=0",
                "0:n_dims-range",
                "0:null",
                "0:misaligned",
                "0:size",
                "0:unknown-pattern",
            ],
        ),
        ("wc_sequence_random", GEN),
        ("wc_sequence_stratified", GEN),
        ("wc_envmap_storage_len", LEN),
        ("wc_envmap_build", BUILD),
        ("wc_envmap_build_compensated", BUILD),
        ("wc_envmap_from_storage", CHECK),
        ("wc_envmap_from_storage_verified", CHECK),
        ("wc_envmap_sample", SAMPLE),
        ("wc_envmap_pdf", PDF),
        ("wc_envmap_sample_direction", SAMPLE_DIRECTION),
        ("wc_envmap_pdf_direction", PDF_DIRECTION),
        ("wc_envmap_luminance", MAP_IN_PLACE),
        ("wc_envmap_equirect_solid_angle_weights", IMAGE),
        ("wc_envmap_equirect_pdf_to_solid_angle", MAP_IN_PLACE),
        ("wc_envmap_equirect_to_equal_area", IMAGE),
        ("wc_lights_alias_storage_len", &["words", "SIZE_MAX"]),
        (
            "wc_lights_alias_build",
            &[
                "WC_OK",
                "WC_ERR_EMPTY",
                "WC_ERR_TOO_LARGE",
                "WC_ERR_STORAGE_TOO_SMALL",
                "WC_ERR_INVALID_ARGUMENT",
                "WC_ERR_INVALID_WEIGHT",
                "WC_ERR_ALL_ZERO",
            ],
        ),
        ("wc_lights_alias_from_storage", CHECK),
        ("wc_lights_alias_from_storage_verified", CHECK),
        ("wc_lights_alias_sample", SAMPLE),
        ("wc_lights_alias_pmf", PDF),
        ("wc_error_string", &["string"]),
        ("wc_lights_tree_storage_len", &["words", "SIZE_MAX"]),
        (
            "wc_lights_tree_build",
            &[
                "WC_OK",
                "WC_ERR_EMPTY",
                "WC_ERR_TOO_LARGE",
                "WC_ERR_STORAGE_TOO_SMALL",
                "WC_ERR_INVALID_ARGUMENT",
                "WC_ERR_INVALID_WEIGHT",
                "WC_ERR_INVALID_BOUNDS",
                "WC_ERR_ALL_ZERO",
            ],
        ),
        ("wc_lights_tree_from_storage", CHECK),
        ("wc_lights_tree_from_storage_verified", CHECK),
        ("wc_lights_tree_sample", SAMPLE),
        ("wc_lights_tree_pmf", SAMPLE),
    ]
};

/// The functions `include/warpcore.h` declares: name, declaration (return type and
/// parameters) and doc comment.
fn declarations() -> Vec<(String, String, String)> {
    let header = std::fs::read_to_string(root().join("include/warpcore.h")).unwrap();
    let mut out = Vec::new();
    let mut doc = String::new();
    let mut lines = header.lines();
    while let Some(line) = lines.next() {
        if let Some(c) = line.trim_start().strip_prefix("//") {
            doc.push_str(c.trim());
            doc.push(' ');
            continue;
        }
        if let Some(at) = line.find("wc_").filter(|_| !line.starts_with('#')) {
            let name: String = line[at..]
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            if line[at + name.len()..].starts_with('(') {
                let mut decl = line.to_string();
                while !decl.contains(';') {
                    decl.push(' ');
                    decl.push_str(lines.next().unwrap().trim());
                }
                out.push((name, decl, std::mem::take(&mut doc)));
                continue;
            }
        }
        doc.clear();
    }
    out
}

/// The outcomes a function's documentation names (its own comment, and the comments of the
/// functions it refers to, as in "0 as for `wc_disk_polar`").
fn documented_outcomes(
    name: &str,
    decl: &str,
    docs: &HashMap<String, String>,
) -> std::collections::BTreeSet<String> {
    let own = &docs[name];
    let mut doc = own.clone();
    for (other, text) in docs {
        if other != name && own.contains(&format!("`{other}`")) {
            doc.push_str(text);
        }
    }
    let mut out = std::collections::BTreeSet::new();
    if decl.starts_with("int32_t") {
        out.insert("WC_OK".to_string());
        for piece in doc.split(|c: char| !(c.is_ascii_alphanumeric() || c == '_')) {
            if piece.starts_with("WC_ERR_") {
                out.insert(piece.to_string());
            }
        }
        return out;
    }
    let mut add = |k: &str, yes: bool| {
        if yes {
            out.insert(k.to_string());
        }
    };
    let counted = decl.contains("size_t n)");
    // The header's rules for every `n`: 0 for n = 0, null, misaligned, overflowing counts.
    for k in ["n", "0:n=0", "0:null", "0:misaligned", "0:size"] {
        add(k, counted);
    }
    add("0:overlap", counted && doc.contains("overlap"));
    add(
        "in-place",
        doc.contains("other than `") || doc.contains("other than exactly in place"),
    );
    add("capped", doc.contains("min(n, 4 n_points)"));
    add("0:invalid-storage", doc.contains("fails `wc_"));
    add("0:unknown-layout", own.contains("an unknown `layout`"));
    // A static string for any argument (`wc_error_string`).
    add("string", decl.starts_with("const char *"));
    add("0:size=0", doc.contains("size == 0"));
    let len = name.ends_with("_storage_len");
    add("words", len);
    add("0:zero-side", len && doc.contains("0 for a zero side"));
    add("SIZE_MAX", len && doc.contains("`SIZE_MAX`"));
    add("value", decl.contains("(void)"));
    // A value computed from a light (the solid angles): 0 for a null or misaligned `light`.
    let light_value = decl.starts_with("float ") && decl.contains("const float *light)");
    add("omega", light_value);
    add("0:null", light_value && own.contains("null"));
    add("0:misaligned", light_value && own.contains("misaligned"));
    // The sampler (its own comment only: the draws refer to `wc_sampler_draw`). A draw of
    // `n` (or `n_dims`, for `count` points) dimensions from a `WcSampler`.
    if decl.contains("WcSampler s, size_t n") {
        let slice = decl.ends_with("size_t count);");
        add(if slice { "count" } else { "n" }, true);
        add("0:n-range", !slice && own.contains("`n` outside 1..=4"));
        add(
            "0:n_dims-range",
            slice && own.contains("`n_dims` outside 1..=4"),
        );
        add("0:count=0", slice && own.contains("`count = 0`"));
        add("0:null", own.contains("null"));
        add("0:misaligned", own.contains("misaligned"));
        add("0:size", slice && own.contains("exceeds `PTRDIFF_MAX`"));
        add("0:unknown-pattern", own.contains("an unknown pattern"));
    }
    let sampler = decl.starts_with("WcSampler ");
    add("sampler", sampler);
    add(
        "unknown-pattern",
        sampler && (own.contains("unknown pattern") || own.contains("unknown `pattern`")),
    );
    let predicate = decl.starts_with("uint32_t ") && own.contains(", 0 otherwise.");
    add("1", predicate && own.contains("? 1 for"));
    add("0", predicate);
    out
}

/// The header preamble states the rules every counted function follows; the table relies on
/// them.
#[test]
fn header_states_the_general_rules() {
    let header = std::fs::read_to_string(root().join("include/warpcore.h")).unwrap();
    let preamble = &header[..header.find("#ifndef").unwrap()].replace("\n *", "");
    for rule in [
        "0 (writing nothing) for n = 0",
        "a null or misaligned pointer",
        "a count whose byte size exceeds PTRDIFF_MAX",
    ] {
        assert!(
            preamble.contains(rule),
            "the header preamble lacks {rule:?}"
        );
    }
}

#[test]
fn hostile_calls_reach_every_documented_outcome() {
    // The table against the header.
    let decls = declarations();
    let docs: HashMap<String, String> = decls
        .iter()
        .map(|(n, _, d)| (n.clone(), d.clone()))
        .collect();
    let table: HashMap<&str, &[&str]> = TABLE.iter().copied().collect();
    assert_eq!(table.len(), TABLE.len(), "a function twice in TABLE");
    assert!(decls.len() >= 50, "only {} declarations found", decls.len());
    for (name, decl, _) in &decls {
        let rows = table
            .get(name.as_str())
            .unwrap_or_else(|| panic!("{name} has no rows in TABLE (function x outcome)"));
        let rows: std::collections::BTreeSet<String> = rows.iter().map(|s| s.to_string()).collect();
        let documented = documented_outcomes(name, decl, &docs);
        assert_eq!(
            rows, documented,
            "{name}: TABLE's rows differ from the outcomes its documentation names"
        );
    }
    for (name, _) in TABLE {
        assert!(
            decls.iter().any(|(n, _, _)| n == name),
            "{name} is in TABLE but not in the header"
        );
    }

    // The hostile calls reached every row, and only rows of the table.
    let rounds = std::env::var("WARPCORE_HOSTILE_ROUNDS").unwrap_or_else(|_| "2000".into());
    let out = compile_and_run_with("hostile", &[&rounds]);
    let mut reached: HashMap<(String, String), u64> = HashMap::new();
    for line in out.lines() {
        let mut w = line.split(' ');
        if w.next() == Some("row") {
            let (f, o, c) = (w.next().unwrap(), w.next().unwrap(), w.next().unwrap());
            reached.insert((f.to_string(), o.to_string()), c.parse().unwrap());
        }
    }
    for (f, o) in reached.keys() {
        assert!(
            table
                .get(f.as_str())
                .is_some_and(|r| r.contains(&o.as_str())),
            "hostile.c reached ({f}, {o}), which TABLE does not list"
        );
    }
    let mut missing = Vec::new();
    for (f, outcomes) in TABLE {
        for o in *outcomes {
            if !reached.contains_key(&(f.to_string(), o.to_string())) {
                missing.push(format!("({f}, {o})"));
            }
        }
    }
    assert!(
        missing.is_empty(),
        "rows never reached: {}",
        missing.join(" ")
    );
    let last = out.lines().last().unwrap_or("");
    assert!(
        last.ends_with(" failed") && last.contains(", 0 failed"),
        "{last}"
    );
    let rows: usize = TABLE.iter().map(|(_, o)| o.len()).sum();
    eprintln!("{rows} rows (function x documented outcome), all reached; {last}");
}
