#!/usr/bin/env bash
# tools/fuzz.sh [seconds per target] [target ...]: a fuzz campaign — every target in
# fuzz/fuzz_targets (or the ones named) runs as a libFuzzer *search* (cargo-fuzz), starting
# from its committed corpus fuzz/corpus/<target>, for the given time (default 60 s), one
# after the other on one core (WARPCORE_FUZZ_JOBS=N: N targets at a time, each on its own
# core). Then:
#
# * what the search found that adds coverage is merged into fuzz/corpus/<target>
#   (libFuzzer's -merge=1 -use_counters=0: only inputs that reach an edge the corpus does
#   not, so the corpus grows by a few files, not by everything the search kept — merging by
#   hit counts as well kept over a thousand files after ten minutes of capi_envmap); the replay
#   tests (registry/tests/fuzz_corpus.rs, capi/tests/fuzz_corpus.rs) then run them in every
#   `cargo test`. WARPCORE_FUZZ_MERGE=0 skips the merge (CI: the checkout is not changed);
# * a table gives executions, executions per second, corpus files added and the finding
#   (the artifact path) per target;
# * the exit status is 1 when any target found something (a failed check, a panic, a
#   timeout, an out-of-memory), 2 on a bad command line or a failed build, 0 otherwise. The
#   artifact stays in fuzz/artifacts/<target>/; reproduce it with
#   `cargo +nightly fuzz run <target> <artifact>` and minimise it with `cargo fuzz tmin`.
#
# Sanitizers. The library is #![forbid(unsafe_code)], and every target but one calls only
# safe Rust, whose memory errors the compiler already rules out: AddressSanitizer would only
# slow those searches (about 2x) and cost a second build, so they run with `-s none`
# (coverage instrumentation only; debug assertions and overflow checks stay on). The
# exception is `capi_envmap`: it drives the C ABI (capi/src/envmap.rs, capi/src/ffi.rs) through
# raw pointers in `unsafe` blocks, with arrays the fuzzer places next to guard words — exactly
# what ASan checks — so it is built with `-s address` (nightly), in its own target directory
# (fuzz/target/asan) so that switching sanitizers never rebuilds the other. Without a nightly
# toolchain everything runs with `-s none` on stable, and the script says so.
#
# Environment: WARPCORE_FUZZ_MERGE (default 1), WARPCORE_FUZZ_ASAN (default 1; 0: no sanitizer
# anywhere), WARPCORE_FUZZ_JOBS (default 1: targets searched at once; libFuzzer runs one
# process per target, so up to the number of cores gives each target the same executions in
# less wall time), WARPCORE_FUZZ_ARGS (extra libFuzzer flags).
set -uo pipefail
cd "$(dirname "$0")/../fuzz" || exit 2

secs=${1:-60}
[ "$#" -gt 0 ] && shift
case $secs in '' | *[!0-9]*) echo "usage: tools/fuzz.sh [seconds per target] [target ...]" >&2; exit 2 ;; esac
parallel=${WARPCORE_FUZZ_JOBS:-1}
case $parallel in '' | *[!0-9]* | 0) echo "WARPCORE_FUZZ_JOBS must be a positive integer" >&2; exit 2 ;; esac
if [ "$#" -gt 0 ]; then
  targets=("$@")
else
  targets=()
  for f in fuzz_targets/*.rs; do targets+=("$(basename "$f" .rs)"); done
fi
for t in "${targets[@]}"; do
  [ -f "fuzz_targets/$t.rs" ] || { echo "no fuzz target $t (fuzz/fuzz_targets/$t.rs)" >&2; exit 2; }
done
cargo fuzz --version >/dev/null 2>&1 || { echo "cargo-fuzz is missing: cargo install cargo-fuzz --locked" >&2; exit 2; }
merge=${WARPCORE_FUZZ_MERGE:-1}
if cargo +nightly --version >/dev/null 2>&1; then
  toolchain=+nightly
  asan_targets=" capi_envmap "
else
  toolchain=
  asan_targets=" "
  echo "no nightly toolchain: every target runs without a sanitizer (stable, -s none)"
fi
# WARPCORE_FUZZ_ASAN=0: no sanitizer for any target (CI's short search: a cold ASan build costs
# about five minutes, and CI replays the capi_envmap corpus under ASan in its C API step).
[ "${WARPCORE_FUZZ_ASAN:-1}" = 0 ] && asan_targets=" "

# The sanitizer and target directory of a target.
sanitizer() { case $asan_targets in *" $1 "*) echo address ;; *) echo none ;; esac; }
fuzz() { # fuzz <cargo-fuzz subcommand> <target> [args ...]
  local sub=$1 t=$2 san
  shift 2
  san=$(sanitizer "$t")
  cargo $toolchain fuzz "$sub" -s "$san" --target-dir "target/$san" "$t" "$@"
}

logs=target/fuzz-logs
mkdir -p "$logs"
# Build first (all targets of one sanitizer at once), so the timed runs time fuzzing only.
build_start=$SECONDS
for san in none address; do
  list=()
  for t in "${targets[@]}"; do [ "$(sanitizer "$t")" = "$san" ] && list+=("$t"); done
  [ "${#list[@]}" -gt 0 ] || continue
  if [ "${#list[@]}" -eq "$(ls fuzz_targets/*.rs | wc -l)" ]; then
    # Every target: one cargo invocation builds them in parallel.
    cargo $toolchain fuzz build -s "$san" --target-dir "target/$san" >"$logs/build-$san.log" 2>&1 \
      || { cat "$logs/build-$san.log"; echo "build of the fuzz targets failed" >&2; exit 2; }
    continue
  fi
  for t in "${list[@]}"; do
    fuzz build "$t" >"$logs/build-$t.log" 2>&1 \
      || { cat "$logs/build-$t.log"; echo "build of $t failed" >&2; exit 2; }
  done
done
echo "built ${#targets[@]} targets in $((SECONDS - build_start)) s"

# A target's line of the table: row <target> <executions> <exec/s> <files added> <finding>.
row() { printf '%-16s %-8s %14s %10s %6s  %s' "$1" "$(sanitizer "$1")" "$2" "$3" "$4" "$5"; }

# One target's search, its merge and its table row (in $logs/row-<target>: row, executions,
# finding flag), so that searches can run side by side.
search() {
  local t=$1 new log before rc execs rate finding added artifact
  new=$(mktemp -d)
  log=$logs/$t.log
  before=$(find "corpus/$t" -type f ! -name '.*' | wc -l)
  # New inputs go to the scratch directory (the first one); the committed corpus is read.
  # shellcheck disable=SC2086
  fuzz run "$t" "$new" "corpus/$t" -- -max_total_time="$secs" -print_final_stats=1 \
    -timeout=20 ${WARPCORE_FUZZ_ARGS:-} >"$log" 2>&1
  rc=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *\([0-9]*\).*/\1/p' "$log" | tail -1)
  [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  execs=${execs:-0}
  rate=$(sed -n 's/^stat::average_exec_per_sec: *\([0-9]*\).*/\1/p' "$log" | tail -1)
  if [ "$rc" -ne 0 ]; then
    artifact=$(sed -n 's/.*Test unit written to \(.*\)$/\1/p' "$log" | tail -1)
    finding="exit $rc: ${artifact:-no artifact} (log fuzz/$log)"
    grep -m1 -E "panicked at|ERROR: libFuzzer|ERROR: AddressSanitizer" "$log" | sed 's/^/    /'
  else
    finding=none
  fi
  added=0
  if [ "$merge" = 1 ] && [ -n "$(ls -A "$new")" ]; then
    fuzz run "$t" "corpus/$t" "$new" -- -merge=1 -use_counters=0 >"$logs/merge-$t.log" 2>&1 \
      || echo "merge for $t failed (see fuzz/$logs/merge-$t.log)"
    added=$(($(find "corpus/$t" -type f ! -name '.*' | wc -l) - before))
  fi
  rm -rf "$new"
  printf '%s\n%s\n%s\n' "$(row "$t" "$execs" "${rate:-?}" "$added" "$finding")" \
    "$execs" "$([ "$rc" -ne 0 ] && echo 1 || echo 0)" >"$logs/row-$t"
  printf '%s: %s executions in %s s, %s corpus files added, finding: %s\n' \
    "$t" "$execs" "$secs" "$added" "$finding"
}

for t in "${targets[@]}"; do
  rm -f "$logs/row-$t"
  while [ "$(jobs -rp | wc -l)" -ge "$parallel" ]; do wait -n; done
  search "$t" &
done
wait

findings=0
rows=()
total_execs=0
for t in "${targets[@]}"; do
  if [ -f "$logs/row-$t" ]; then
    mapfile -t r <"$logs/row-$t"
  else
    r=("$(row "$t" 0 '?' 0 "no result")" 0 1)
  fi
  rows+=("${r[0]}")
  total_execs=$((total_execs + r[1]))
  findings=$((findings + r[2]))
done

echo
printf '%-16s %-8s %14s %10s %6s  %s\n' target sanitizer executions 'exec/s' added finding
printf '%s\n' "${rows[@]}"
echo "total: $total_execs executions, $findings target(s) with a finding"
[ "$findings" -eq 0 ] || exit 1
