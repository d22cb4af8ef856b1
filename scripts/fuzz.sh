#!/usr/bin/env bash
# Runs the libFuzzer targets of tests/fuzz/ (built in build-asan: AddressSanitizer + UBSan) for
# SECONDS each, FUZZ_JOBS at a time (default: one per core), over their committed seed corpus,
# tests/fuzz/corpus/<target> (and experiments/ for the experiment parser), and prints per target the
# inputs tried, the coverage and the corpus grown.
# A finding (a crash, a sanitizer report, an exception other than InputError, a timeout of 10 s,
# more than 2 GiB) stops it with status 1 and keeps the input as build-asan/fuzz/<target>-crash-*;
# reproduce with build-asan/fuzz/fuzz_<target> FILE.
# FUZZ_KEEP=1 merges the inputs that found new coverage into tests/fuzz/corpus/<target> (minimised).
# FUZZ_RECORD=FILE appends one CSV row per target (the long runs the README reports:
# tests/fuzz/long-runs.csv): date, commit, compiler, target, seconds, inputs tried, their rate, the
# seed corpus and the inputs that grew it, coverage (edges, features) and peak memory of a run without a finding.
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]   (default 30 s; targets experiment weights shard_meta spec)
set -euo pipefail
cd "$(dirname "$0")/.."
root=$(pwd)
seconds=${1:-30}
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(experiment weights shard_meta spec)
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export ASAN_SYMBOLIZER_PATH=/usr/lib/llvm-14/bin/llvm-symbolizer
build=()
for target in "${targets[@]}"; do build+=(--target "fuzz_$target"); done
bash scripts/sanitizer_build.sh build-asan "address;undefined" -DDABENCH_BUILD_FUZZERS=ON "${build[@]}"

# The commit the runs test (taken now: the corpus merges below change the tree).
commit=$(git rev-parse --short=7 HEAD)$(git diff --quiet HEAD -- . ':!tests/fuzz/long-runs.csv' ':!tests/fuzz/corpus' || echo +changes)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
seeds_of() { echo "$root/tests/fuzz/corpus/$1"; [ "$1" != experiment ] || echo "$root/experiments"; }
# One target's run; its status goes to $work/<target>.status (0: no finding).
fuzz_target() {
  local target=$1
  mkdir -p "$work/$target"
  local status=0
  build-asan/fuzz/fuzz_$target -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$root/build-asan/fuzz/$target-" "$work/$target" $(seeds_of "$target") > "$work/$target.log" 2>&1 || status=$?
  echo "$status" > "$work/$target.status"
}
# FUZZ_JOBS targets at a time (default: one per core), each for SECONDS.
for target in "${targets[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "${FUZZ_JOBS:-$(nproc)}" ]; do wait -n || true; done
  fuzz_target "$target" &
done
wait

for target in "${targets[@]}"; do
  log="$work/$target.log"
  if [ "$(cat "$work/$target.status")" != 0 ]; then
    grep -v "^#" "$log" | tail -40
    echo "fuzz: fuzz_$target found an input that fails (kept as build-asan/fuzz/$target-*)"
    exit 1
  fi
  stat() { sed -n "s/^stat::$1: *//p" "$log"; }
  runs=$(stat number_of_executed_units)
  done_line=$(grep -E "^#[0-9]+.* cov: " "$log" | tail -1 || true)  # the last progress line: coverage reached
  cov=$(sed -n 's/.* cov: \([0-9]*\) .*/\1/p' <<< "$done_line") features=$(sed -n 's/.* ft: \([0-9]*\) .*/\1/p' <<< "$done_line")
  grown=$(ls "$work/$target" | wc -l)
  echo "fuzz: fuzz_$target: $runs inputs in $seconds s, no finding; $grown new inputs (cov $cov, ft $features)"
  if [ -n "${FUZZ_RECORD:-}" ]; then
    [ -s "$FUZZ_RECORD" ] || echo "date,commit,compiler,target,seconds,inputs,inputs_per_second,seed_inputs,new_inputs,edges,features,peak_rss_mb" > "$FUZZ_RECORD"
    seed_count=$(find $(seeds_of "$target") -maxdepth 1 -type f | wc -l)
    echo "$(date -u +%F),$commit,clang $(clang++-14 -dumpversion),$target,$seconds,$runs,$(stat average_exec_per_sec),$seed_count,$grown,$cov,$features,$(stat peak_rss_mb)" >> "$FUZZ_RECORD"
  fi
  if [ "${FUZZ_KEEP:-0}" = 1 ]; then
    build-asan/fuzz/fuzz_$target -merge=1 "$root/tests/fuzz/corpus/$target" "$work/$target" > "$work/merge.log" 2>&1
    echo "fuzz: tests/fuzz/corpus/$target now holds $(ls "$root/tests/fuzz/corpus/$target" | wc -l) inputs"
  fi
done
