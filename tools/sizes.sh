#!/usr/bin/env bash
# Code + data size of warpcore per feature set: builds examples/wasm-demo as a
# wasm32-unknown-unknown cdylib (opt-level 3, LTO, panic=abort, stripped) exporting exactly one
# warp (a "probe" feature), and prints a Markdown table of the .wasm sizes in bytes.
set -euo pipefail
cd "$(dirname "$0")/../examples/wasm-demo"
probes=(
  "probe-concentric:only disk::concentric"
  "probe-concentric4:only disk::concentric4"
  "probe-basu-owen:only triangle::basu_owen"
  "probe-basu-owen-permuted:only triangle::basu_owen_permuted"
  "probe-equal-area:only sphere::equal_area"
  "probe-pmj02bn-1024:only pmj02bn::sample, 1024 points x 1 set"
  "probe-pmj02bn-4096:only pmj02bn::sample, 4096 points x 1 set"
  "probe-pmj02bn-16384:only pmj02bn::sample, 16384 points x 1 set"
  "probe-pmj02bn-65536:only pmj02bn::sample, 65536 points x 1 set"
  "probe-sampler-sobol:only sampler::Sampler<Sobol> (domains, 4D draws; 16 KiB matrices)"
  "probe-sampler-pmj02bn:only sampler::Sampler<Pmj02bn>, 1024 points x 1 set"
  "probe-sampler-blue:only sampler::Sampler<Blue<Sobol>> (with the 64 x 64 key tile)"
  "probe-spherical-triangle:only spherical::triangle (Arvo, by solid angle)"
  "probe-spherical-rectangle:only spherical::rectangle (Urena et al., by solid angle)"
)
printf '| build | .wasm bytes |\n|---|---|\n'
for entry in "${probes[@]}" "all:everything (all families, fingerprint)"; do
  feature=${entry%%:*}; label=${entry#*:}
  cargo build -q --release --lib --target wasm32-unknown-unknown --no-default-features --features "$feature"
  bytes=$(stat -c %s target/wasm32-unknown-unknown/release/warpcore_demo.wasm)
  printf '| %s | %s |\n' "$label" "$bytes"
  cp target/wasm32-unknown-unknown/release/warpcore_demo.wasm "target/$feature.wasm"
done

# A scene that only samples a disk light must not link the pmj02bn tables: the first 64 bytes of
# every table file must be absent from the concentric-only module (and present, as a control,
# in the 1024-point probe).
node -e '
const fs = require("fs");
const has = (wasm, table) => fs.readFileSync(wasm).includes(fs.readFileSync(table).subarray(0, 64));
const tables = fs.readdirSync("../../src/tables").filter(f => f.endsWith(".bin")).map(f => "../../src/tables/" + f);
if (tables.some(t => has("target/probe-concentric.wasm", t))) { console.error("concentric-only build contains pmj02bn tables"); process.exit(1); }
if (!has("target/probe-pmj02bn-1024.wasm", "../../src/tables/pmj02bn_1024_0.bin")) { console.error("control failed: table not found in the pmj02bn probe"); process.exit(1); }
console.log("concentric-only build contains no pmj02bn table bytes (control: found in the pmj02bn probe)");
'
