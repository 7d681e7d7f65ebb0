#!/usr/bin/env bash
# Code + data size of warpcore per feature set: builds examples/wasm-demo (`--profile wasm`) as a
# wasm32-unknown-unknown cdylib (opt-level 3, LTO, panic=abort, stripped) exporting exactly one
# warp (a "probe" feature), and prints a Markdown table of the .wasm sizes in bytes.
#
# The table's one home is docs/determinism.md, between the `sizes.sh:begin` and `sizes.sh:end`
# markers; every other page links there instead of repeating a figure.
#   bash tools/sizes.sh           prints the table
#   bash tools/sizes.sh --check   fails when the page's table differs from this build's (CI)
#   bash tools/sizes.sh --write   writes this build's table into the page
set -euo pipefail
mode=${1:-print}
case "$mode" in print|--check|--write) ;; *) echo "usage: $0 [--check|--write]" >&2; exit 2 ;; esac
cd "$(dirname "$0")/.."
source tools/table-block.sh
# feature:label:table data in the module
probes=(
  "probe-concentric:only \`disk::concentric\`:—"
  "probe-concentric4:only \`disk::concentric4\`:—"
  "probe-basu-owen:only \`triangle::basu_owen\`:—"
  "probe-basu-owen-permuted:only \`triangle::basu_owen_permuted\`:—"
  "probe-equal-area:only \`sphere::equal_area\`:—"
  "probe-pmj02bn-1024:only \`pmj02bn::sample\`, 1024 points x 1 set:8,192"
  "probe-pmj02bn-4096:only \`pmj02bn::sample\`, 4096 points x 1 set:32,768"
  "probe-pmj02bn-16384:only \`pmj02bn::sample\`, 16384 points x 1 set:131,072"
  "probe-pmj02bn-65536:only \`pmj02bn::sample\`, 65536 points x 1 set:524,288"
  "probe-sampler-sobol:only \`sampler::Sampler<Sobol>\` (domains, 4D draws):16,384 (Sobol' matrices)"
  "probe-sampler-pmj02bn:only \`sampler::Sampler<Pmj02bn>\`, 1024 points x 1 set:8,192"
  "probe-sampler-blue:only \`sampler::Sampler<Blue<Sobol>>\` (with its key tile; it calls \`new\` only, so the slot tiles, reached through \`new_frame\`, are not linked):32,768"
  "probe-spherical-triangle:only \`spherical::triangle\` (Arvo, by solid angle):—"
  "probe-spherical-rectangle:only \`spherical::rectangle\` (Urena et al., by solid angle):—"
  "all:everything: every family with default features (4096 x 4 pmj02bn sets, the sampler with the blue-noise key and slot tiles, the spherical lights), the fingerprint (with its \`_x16\` variant) and demo exports:278,528"
)
table=$'| build | .wasm bytes | of which table data |\n|---|---|---|'
for entry in "${probes[@]}"; do
  feature=${entry%%:*}; rest=${entry#*:}; label=${rest%:*}; data=${rest##*:}
  cargo build -q --profile wasm -p warpcore-demo --lib --target wasm32-unknown-unknown --no-default-features --features "$feature"
  bytes=$(stat -c %s target/wasm32-unknown-unknown/wasm/warpcore_demo.wasm)
  table+=$'\n'"| $label | $(commas "$bytes") | $data |"
  cp target/wasm32-unknown-unknown/wasm/warpcore_demo.wasm "target/wasm32-unknown-unknown/wasm/$feature.wasm"
done
printf '%s\n' "$table"
table_block sizes.sh docs/determinism.md "$mode" "$table"

# A scene that only samples a disk light must not link the pmj02bn tables: the first 64 bytes of
# every table file must be absent from the concentric-only module (and present, as a control,
# in the 1024-point probe).
node -e '
const fs = require("fs");
const has = (wasm, table) => fs.readFileSync(wasm).includes(fs.readFileSync(table).subarray(0, 64));
const tables = fs.readdirSync("src/tables").filter(f => f.endsWith(".bin")).map(f => "src/tables/" + f);
if (tables.some(t => has("target/wasm32-unknown-unknown/wasm/probe-concentric.wasm", t))) { console.error("concentric-only build contains pmj02bn tables"); process.exit(1); }
if (!has("target/wasm32-unknown-unknown/wasm/probe-pmj02bn-1024.wasm", "src/tables/pmj02bn_1024_0.bin")) { console.error("control failed: table not found in the pmj02bn probe"); process.exit(1); }
console.log("concentric-only build contains no pmj02bn table bytes (control: found in the pmj02bn probe)");
'
