#!/usr/bin/env bash
# Size of the C static library per feature set: builds libwarpcore_capi.a (release:
# opt-level 3, panic = abort, no_std) with only some families, and links a C program that
# calls the family's functions (cc -O2, -Wl,--gc-sections, stripped). Prints a Markdown table:
# the shared library (libwarpcore_capi.so) and what the static library adds to the linked program's code and data (text + data + bss, from
# `size`, against the same program without the calls). Run from anywhere.
#
# The table's one home is docs/capi.md, between the `capi-sizes.sh:begin` and
# `capi-sizes.sh:end` markers:
#   bash tools/capi-sizes.sh           prints the table
#   bash tools/capi-sizes.sh --check   fails when the page's table differs from this build's (CI)
#   bash tools/capi-sizes.sh --write   writes this build's table into the page
# The `.a` is not listed: it bundles Rust's precompiled `core` whole (the linker keeps only what
# is called), and even without debug info it records the paths of the dependencies' sources
# (`$CARGO_HOME/registry/...`), so its size depends on the machine.
set -euo pipefail
mode=${1:-print}
case "$mode" in print|--check|--write) ;; *) echo "usage: $0 [--check|--write]" >&2; exit 2 ;; esac
cd "$(dirname "$0")/.."
source tools/table-block.sh
out=target/capi-sizes
mkdir -p "$out"
cat > "$out/probe.c" <<'C'
#include "warpcore.h"
#include <stdio.h>
int main(int argc, char **argv) {
    float u[64] = {0.25f, 0.75f}, o[96];
    (void)argv;
    size_t k = (size_t)argc, n = 0; /* k = 1: one point per call */
#if defined(PROBE_DISK) || defined(PROBE_ALL)
    n += wc_disk_concentric(u, o, k) + wc_disk_polar4(u, 1, o, 4 * k);
#endif
#if defined(PROBE_TRIANGLE) || defined(PROBE_ALL)
    n += wc_triangle_uniform(u, o, k) + wc_triangle_basu_owen(1, 2, o, k);
#endif
#if defined(PROBE_SPHERE) || defined(PROBE_ALL)
    n += wc_sphere_equal_area(u, o, k) + wc_sphere_equal_area_inverse(o, u, k);
#endif
#if defined(PROBE_PMJ02BN) || defined(PROBE_ALL)
    n += wc_pmj02bn_sample(0, 7, o, k);
#endif
#if defined(PROBE_ENVMAP) || defined(PROBE_ALL)
    {
        static uint32_t s[4096];
        WcEnvSample e[2];
        if (wc_envmap_build(WC_ENVMAP_KIND_HIERARCHICAL, u, 4, 4, s, 4096) == WC_OK)
            n += wc_envmap_sample(s, 4096, u, e, 2);
    }
#endif
    printf("%zu %g\n", n, (double)o[0]);
    return 0;
}
C
cc -O2 -Wl,--gc-sections -s -Iinclude -o "$out/baseline" "$out/probe.c"
footprint() { size "$1" | awk 'NR == 2 { print $4 }'; }
base=$(footprint "$out/baseline")
sets=(
  "disk:DISK:\`disk\`"
  "triangle:TRIANGLE:\`triangle\`"
  "sphere:SPHERE:\`sphere\` (includes \`disk\`)"
  "pmj02bn:PMJ02BN:\`pmj02bn\`, 1024 points x 1 set"
  "pmj02bn,pmj02bn-4096,pmj02bn-4-sets:PMJ02BN:\`pmj02bn\`, 4096 points x 4 sets"
  "envmap:ENVMAP:\`envmap\` (includes \`sphere\`, \`disk\`)"
  "default:ALL:default (every family, 4096 x 4 tables)"
)
table=$'| features | `libwarpcore_capi.so` bytes | added to a linked C program |\n|---|---:|---:|'
for entry in "${sets[@]}"; do
  features=${entry%%:*}; rest=${entry#*:}; probe=${rest%%:*}; label=${rest#*:}
  if [ "$features" = default ]; then
    cargo build -q --release -p warpcore-capi --lib
  else
    cargo build -q --release -p warpcore-capi --lib --no-default-features --features "$features"
  fi
  so_bytes=$(stat -c %s target/release/libwarpcore_capi.so)
  cc -O2 -Wl,--gc-sections -s -Iinclude "-DPROBE_$probe" -o "$out/probe" "$out/probe.c" \
    target/release/libwarpcore_capi.a
  "$out/probe" > /dev/null
  table+=$'\n'"| $label | $(commas "$so_bytes") | $(commas "$(( $(footprint "$out/probe") - base ))") |"
done
# Leave the default build in place for whatever runs next.
cargo build -q --release -p warpcore-capi --lib
printf '%s\n' "$table"
table_block capi-sizes.sh docs/capi.md "$mode" "$table"
