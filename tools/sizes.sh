#!/usr/bin/env bash
# Code + data size of warpcore per feature set: builds examples/wasm-demo as a
# wasm32-unknown-unknown cdylib (opt-level 3, LTO, panic=abort, stripped) exporting exactly one
# warp (a "probe" feature), and prints a Markdown table of the .wasm sizes in bytes.
set -euo pipefail
cd "$(dirname "$0")/../examples/wasm-demo"
probes=("probe-concentric:only disk::concentric")
printf '| build | .wasm bytes |\n|---|---|\n'
for entry in "${probes[@]}" "all:everything (all families, fingerprint)"; do
  feature=${entry%%:*}; label=${entry#*:}
  cargo build -q --release --lib --target wasm32-unknown-unknown --no-default-features --features "$feature"
  bytes=$(stat -c %s target/wasm32-unknown-unknown/release/warpcore_demo.wasm)
  printf '| %s | %s |\n' "$label" "$bytes"
  cp target/wasm32-unknown-unknown/release/warpcore_demo.wasm "target/$feature.wasm"
done
