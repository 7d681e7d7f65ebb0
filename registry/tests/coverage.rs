//! The registry is complete and every name in it is real: each public function of the
//! library (`pub fn` in `src/`, outside private modules, tests and `#[doc(hidden)]` items) has
//! an entry, with its `_x8`, `_x16` and `_slice` forms declared; each C function declared in
//! `include/warpcore.h`, each method of the JS module's API and each `wc_` function of the
//! WGSL libraries is bound by an entry (or is listed in `NOT_FUNCTIONS`); and each name an
//! entry gives exists in its language. Adding a public function without an entry fails here.
#![cfg(feature = "all")]

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use warpcore_registry::{Lang, NOT_FUNCTIONS, entries};

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

fn read(rel: &str) -> String {
    std::fs::read_to_string(root().join(rel)).unwrap_or_else(|e| panic!("{rel}: {e}"))
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The identifier after `key` at the start of a trimmed line (`pub fn polar(` -> `polar`).
fn ident_after<'a>(line: &'a str, key: &str) -> Option<&'a str> {
    let rest = line.trim_start().strip_prefix(key)?;
    let end = rest
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(rest.len());
    (end > 0).then(|| &rest[..end])
}

/// `(family, name)` of every public function of the library: the `pub fn` lines of the
/// public modules (and the names `lane_forms!` declares) (the families `lib.rs` declares `pub mod`), before any `#[cfg(test)]`
/// module, skipping `#[doc(hidden)]` ones.
fn public_functions() -> BTreeSet<(String, String)> {
    let src = root().join("src");
    let lib = read("src/lib.rs");
    let families: BTreeSet<&str> = lib
        .lines()
        .filter_map(|l| ident_after(l, "pub mod "))
        .collect();
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    let mut out = BTreeSet::new();
    for f in files {
        let rel = f.strip_prefix(&src).unwrap();
        let family = rel
            .iter()
            .next()
            .unwrap()
            .to_str()
            .unwrap()
            .trim_end_matches(".rs");
        if !families.contains(family) {
            continue;
        }
        let text = std::fs::read_to_string(&f).unwrap();
        let mut hidden = false;
        for line in text.lines() {
            if line.trim_start().starts_with("#[cfg(test)]") {
                break;
            }
            if line.trim_start().starts_with("#[doc(hidden)]") {
                hidden = true;
            }
            // `pub fn name(`, or inside `lane_forms!` `pub fn name, name_x8, name_x16 [`.
            let names = line
                .trim_start()
                .strip_prefix("pub fn ")
                .or_else(|| line.trim_start().strip_prefix("pub const fn "));
            if let Some(names) = names {
                let names = names.split(['(', '[', '<']).next().unwrap_or("");
                for name in names.split(',').filter_map(|n| ident_after(n, "")) {
                    if !hidden {
                        out.insert((family.to_string(), name.to_string()));
                    }
                }
                hidden = false;
            }
        }
    }
    out
}

/// A function's base name and the form its suffix names.
fn split_form(name: &str) -> (&str, &str) {
    for suffix in ["_x8", "_x16", "_slice"] {
        if let Some(base) = name.strip_suffix(suffix) {
            return (base, suffix);
        }
    }
    (name, "")
}

#[test]
fn every_public_function_has_an_entry_with_its_forms() {
    let found = public_functions();
    assert!(
        found.len() > 150,
        "the scan found only {} functions",
        found.len()
    );
    let mut missing = Vec::new();
    for (family, name) in &found {
        let (base, form) = split_form(name);
        let covered = entries().any(|e| {
            e.family() == family
                && e.name.rsplit("::").next() == Some(base)
                && e.forms.suffixes().any(|s| s == form)
        });
        if !covered {
            missing.push(format!("{family}::{name}"));
        }
    }
    assert!(
        missing.is_empty(),
        "public functions without a registry entry (registry/src/entries.rs): {missing:?}"
    );
}

#[test]
fn every_entry_names_a_public_function_and_its_forms() {
    let found = public_functions();
    for e in entries() {
        let base = e.name.rsplit("::").next().unwrap();
        for suffix in e.forms.suffixes() {
            // The sampler's lane forms are the methods of the same name of `SamplerX8` and
            // `SamplerX16`.
            let lanes_by_type =
                e.name.starts_with("sampler::Sampler::") && suffix.starts_with("_x");
            let name = format!("{base}{}", if lanes_by_type { "" } else { suffix });
            assert!(
                found.contains(&(e.family().to_string(), name.clone())),
                "{}: no public `{name}` in src/{}",
                e.name,
                e.family()
            );
        }
    }
}

/// Every name bound in `lang` by the registry (entries and `NOT_FUNCTIONS`).
fn bound(lang: Lang) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for e in entries() {
        e.names_in(lang, |n| {
            out.insert(n.to_string());
        });
    }
    for (l, name, _) in NOT_FUNCTIONS {
        if *l == lang {
            out.insert(name.to_string());
        }
    }
    out
}

/// The functions `include/warpcore.h` declares (`wc_...(` at the start of a declaration).
fn c_functions() -> BTreeSet<String> {
    let header = read("include/warpcore.h");
    header
        .lines()
        .filter(|l| !l.starts_with(' ') && !l.starts_with('#') && !l.starts_with("typedef"))
        .filter_map(|l| {
            let at = l.find("wc_")?;
            let name = ident_after(&l[at..], "")?;
            l[at + name.len()..]
                .starts_with('(')
                .then(|| name.to_string())
        })
        .collect()
}

/// The methods of the JS module's API objects: keys and methods at the objects' indentation
/// whose names start with a family (`diskPolar:`, `envmapFromStorage(`).
fn js_methods() -> BTreeSet<String> {
    let js = read("js/warpcore.mjs");
    let families = [
        "disk",
        "triangle",
        "sphere",
        "spherical",
        "pmj02bn",
        "sequence",
        "envmap",
        "microfacet",
        "sampler",
        "lights",
    ];
    js.lines()
        .filter(|l| l.starts_with("    ") && !l.starts_with("     "))
        .filter_map(|l| {
            let name = ident_after(l, "")?;
            let after = &l.trim_start()[name.len()..];
            (after.starts_with(':') || after.starts_with('(')).then_some(name)
        })
        .filter(|n| families.iter().any(|f| n.starts_with(f)) && !n.ends_with("Arg"))
        .map(str::to_string)
        .collect()
}

/// The `fn wc_...` of the WGSL libraries.
fn wgsl_functions() -> BTreeSet<String> {
    [
        "warpcore.wgsl",
        "warpcore_tables.wgsl",
        "warpcore_envmap.wgsl",
        "warpcore_lights.wgsl",
    ]
    .iter()
    .flat_map(|f| {
        read(&format!("shaders/{f}"))
            .lines()
            .filter_map(|l| ident_after(l, "fn ").filter(|n| n.starts_with("wc_")))
            .map(str::to_string)
            .collect::<Vec<_>>()
    })
    .collect()
}

fn check_language(lang: Lang, declared: BTreeSet<String>, min: usize) {
    assert!(
        declared.len() >= min,
        "{lang:?}: the scan found only {declared:?}"
    );
    let bound = bound(lang);
    let unbound: Vec<_> = declared.difference(&bound).collect();
    assert!(
        unbound.is_empty(),
        "{lang:?} functions no registry entry binds: {unbound:?}"
    );
    let stale: Vec<_> = bound.difference(&declared).collect();
    assert!(
        stale.is_empty(),
        "{lang:?} names the registry gives that do not exist: {stale:?}"
    );
}

#[test]
fn every_c_function_is_bound_by_an_entry() {
    check_language(Lang::C, c_functions(), 60);
}

#[test]
fn every_js_method_is_bound_by_an_entry() {
    check_language(Lang::Js, js_methods(), 50);
}

#[test]
fn every_wgsl_function_is_bound_by_an_entry() {
    check_language(Lang::Wgsl, wgsl_functions(), 40);
}

/// The regular names follow the rule the bindings use.
#[test]
fn regular_names() {
    let e = entries()
        .find(|e| e.name == "sphere::equal_area_pdf_to_solid_angle")
        .unwrap();
    let (mut c, mut js) = (Vec::new(), Vec::new());
    e.names_in(Lang::C, |n| c.push(n.to_string()));
    e.names_in(Lang::Js, |n| js.push(n.to_string()));
    assert_eq!(c, ["wc_sphere_equal_area_pdf_to_solid_angle"]);
    assert_eq!(js, ["sphereEqualAreaPdfToSolidAngle"]);
}
