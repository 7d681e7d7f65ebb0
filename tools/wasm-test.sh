#!/usr/bin/env bash
# tools/wasm-test.sh [cargo test options]: `cargo test --target wasm32-wasip1 <options>`, with
# the test binaries run under Node (tools/wasi-run.sh) WARPCORE_WASM_JOBS at a time (default 2)
# instead of one after the other: a wasm32-wasip1 test binary runs on one thread, so on two
# cores two binaries take the time of one. Each binary runs in its package's directory, as
# Cargo runs it; its output goes to a log, printed whole when it fails and as its
# `test result` line otherwise. Exit status: Cargo's if the build fails, 1 if any binary
# fails, 0 otherwise. Options are Cargo's (`-p`, `--lib`, `--test`, features); RUSTFLAGS as
# for Cargo (CI: `-C target-feature=+simd128`).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
parallel=${WARPCORE_WASM_JOBS:-2}
case $parallel in '' | *[!0-9]* | 0) echo "WARPCORE_WASM_JOBS must be a positive integer" >&2; exit 2 ;; esac

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# Build, and list "<package directory> TAB <test binary>" in Cargo's order.
cargo test --target wasm32-wasip1 --no-run --message-format=json-render-diagnostics "$@" \
  | node -e '
    const lines = require("fs").readFileSync(0, "utf8").split("\n");
    const path = require("path");
    for (const line of lines) {
      if (!line.startsWith("{")) continue;
      const m = JSON.parse(line);
      if (m.reason === "compiler-artifact" && m.profile && m.profile.test && m.executable) {
        console.log(path.dirname(m.manifest_path) + "\t" + m.executable);
      }
    }' >"$work/list"

n=0
while IFS=$'\t' read -r dir exe; do
  n=$((n + 1))
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n || true; done
  (
    cd "$dir"
    rc=0
    "$root/tools/wasi-run.sh" "$exe" >"$work/$n.log" 2>&1 || rc=$?
    echo "$rc" >"$work/$n.rc"
  ) &
done <"$work/list"
wait

failed=0
i=0
while IFS=$'\t' read -r dir exe; do
  i=$((i + 1))
  rc=$(cat "$work/$i.rc" 2>/dev/null || echo 1)
  name=${exe#"$root"/}
  if [ "$rc" = 0 ]; then
    echo "$name: $(grep -E '^test result' "$work/$i.log" | tail -1)"
  else
    failed=$((failed + 1))
    echo "$name: FAILED (exit $rc)"
    cat "$work/$i.log"
  fi
done <"$work/list"
echo "$n test binaries, $failed failed"
[ "$failed" -eq 0 ]
