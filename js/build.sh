#!/usr/bin/env bash
# Builds js/warpcore.wasm, the WebAssembly module behind js/warpcore.mjs: the C ABI crate
# (capi/, every family, default features) as a wasm32-unknown-unknown cdylib with simd128,
# LTO, one codegen unit, panic = "abort" and stripped symbols. The module has no imports:
# capi's panic handler calls C's `abort`, which would become an import `env.abort` if any
# panic path were linked. The binary is committed (the package and the demo need no Rust
# toolchain); CI rebuilds it and fails when the committed bytes differ.
#
#   bash js/build.sh            rebuild js/warpcore.wasm
#   bash js/build.sh --check    rebuild into target/ and compare with js/warpcore.wasm
set -euo pipefail
cd "$(dirname "$0")/.."
export CARGO_TARGET_DIR=target/js-wasm
export RUSTFLAGS="-C target-feature=+simd128"
export CARGO_PROFILE_RELEASE_LTO=true CARGO_PROFILE_RELEASE_CODEGEN_UNITS=1
export CARGO_PROFILE_RELEASE_STRIP=true CARGO_PROFILE_RELEASE_OPT_LEVEL=3
cargo build -q --release --locked -p warpcore-capi --lib --target wasm32-unknown-unknown
built=$CARGO_TARGET_DIR/wasm32-unknown-unknown/release/warpcore_capi.wasm
if [ "${1:-}" = "--check" ]; then
  if cmp -s "$built" js/warpcore.wasm; then
    echo "js/warpcore.wasm equals a fresh build ($(stat -c %s "$built") bytes, $(rustc --version))"
  else
    echo "js/warpcore.wasm differs from a fresh build with $(rustc --version):"
    echo "run 'bash js/build.sh' and commit js/warpcore.wasm"
    exit 1
  fi
else
  cp "$built" js/warpcore.wasm
  echo "js/warpcore.wasm: $(stat -c %s js/warpcore.wasm) bytes"
fi
