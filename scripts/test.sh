#!/usr/bin/env bash
# The whole test suite, what CI runs on a clean checkout (docs/tests.md): three builds, each with
# the tests it exists for:
#  - release (build/, GCC, -O3): ctest (the Catch2 suite, the Python package's pytest, the
#    reports' checks, the quick start), tests/scripts/mpi.sh (Open MPI on loopback),
#    tests/scripts/faults.sh (a full disk, SIGKILL, then --resume), tests/scripts/outside_project.sh
#    (the installed library from a separate CMake project);
#  - asan (build-asan/, Clang, AddressSanitizer + UBSan): ctest, then the fuzz targets;
#  - tsan (build-tsan/, Clang, ThreadSanitizer): the runner's tests (scripts/test_sanitizers.sh).
# The two sanitizer builds compile in the background (at a lower priority) while the release
# build's tests run, which leave cores idle; each build's tests start once it is built.
# Each step's output goes to build-logs/<build>.log; a line per step says how long it took (wall
# time, and the CPU time of its processes), and a table of every step ends the run. The first step
# that fails stops the run and shows the end of its output.
# Usage: scripts/test.sh [--fast]
#   --fast  the contributor's loop: the release build and its ctest only (no sanitizers, no MPI,
#           fault or install scripts); CI runs the whole command
set -euo pipefail
cd "$(dirname "$0")/.."
logs=$(pwd)/build-logs

children_cpu() {  # sets CPU: the CPU seconds (user + system) of this shell's finished children
  local file=$logs/times.$$
  times > "$file"  # in this shell: a subshell's children are its own
  CPU=$(awk 'NR == 2 { s = 0; for (i = 1; i <= 2; i++) { split($i, t, "m"); s += t[1] * 60 + t[2] } printf "%.0f", s }' "$file")
  rm -f "$file"
}
# step BUILD NAME COMMAND...: runs COMMAND with its output appended to build-logs/BUILD.log, then
# records and prints its wall and CPU time; on failure shows the end of its output and exits 1.
step() {
  local build=$1 name=$2
  shift 2
  local start=$SECONDS cpu_start status=0
  children_cpu
  cpu_start=$CPU
  echo "===== $name: $*" >> "$logs/$build.log"
  "$@" >> "$logs/$build.log" 2>&1 || status=$?
  children_cpu
  local wall=$((SECONDS - start)) cpu=$((CPU - cpu_start))
  printf '%s\t%s\t%d\t%d\t%s\n' "$build" "$name" "$wall" "$cpu" "$status" >> "$logs/steps.tsv"
  if [ "$status" -ne 0 ]; then
    echo "test: [$build] $name FAILED (exit $status) after $((wall / 60)) min $((wall % 60)) s; the end of its output:"
    awk -v name="$name" '$0 ~ "^===== " name ":" { keep = NR } { line[NR] = $0 } END { for (i = keep; i <= NR; i++) print line[i] }' \
      "$logs/$build.log" | tail -60
    echo "test: [$build] its whole output: $logs/$build.log"
    exit 1
  fi
  echo "test: [$build] $name took $((wall / 60)) min $((wall % 60)) s (CPU $((cpu / 60)) min $((cpu % 60)) s)"
}

if [ "${1:-}" = --background-builds ]; then  # internal: the sanitizer builds, started below
  step asan build bash scripts/test_sanitizers.sh asan-build
  step tsan build bash scripts/test_sanitizers.sh tsan-build
  exit 0
fi
fast=0
case "${1:-}" in
  "") ;;
  --fast) fast=1 ;;
  *) echo "usage: scripts/test.sh [--fast]" >&2; exit 2 ;;
esac
export DABENCH_PROGRESS=0
mkdir -p "$logs"
rm -f "$logs"/*.log "$logs/steps.tsv"
start=$SECONDS
background=""
stop_background() { [ -z "$background" ] || kill -- "-$background" 2> /dev/null || true; }
trap stop_background EXIT
# wait_for BUILD: waits until the background builds have built BUILD (exits 1 if they failed).
wait_for() {
  while ! grep -q "^$1	build	" "$logs/steps.tsv" 2> /dev/null; do
    kill -0 "$background" 2> /dev/null || break
    sleep 1
  done
  grep -q "^$1	build	[0-9]*	[0-9]*	0$" "$logs/steps.tsv" || {
    echo "test: the $1 build failed; see $logs/$1.log"; exit 1; }
}

step setup setup bash scripts/setup.sh
step release build bash scripts/build.sh
if [ "$fast" = 0 ]; then
  # Started from a subshell, so that this shell never waits for it: the CPU time it reports for
  # its own steps is theirs alone.
  (setsid nice -n 10 bash "$0" --background-builds & echo $! > "$logs/background.pid")
  background=$(cat "$logs/background.pid")
fi
step release ctest ctest --test-dir build -j"$(nproc)" --output-on-failure
if [ "$fast" = 0 ]; then
  step release test_mpi bash tests/scripts/mpi.sh build
  step release test_faults bash tests/scripts/faults.sh build
  step release test_outside_project bash tests/scripts/outside_project.sh build
  wait_for asan
  step asan ctest bash scripts/test_sanitizers.sh asan-ctest
  step asan fuzz bash scripts/test_sanitizers.sh fuzz
  wait_for tsan
  step tsan runner_tests bash scripts/test_sanitizers.sh tsan-run
fi

total=$((SECONDS - start))
printf 'all\ttotal\t%d\t\t0\n' "$total" >> "$logs/steps.tsv"  # for scripts/record_test_timings.py
echo
echo "test: steps (wall time; CPU time of the step's processes; the sanitizer builds ran beside the release tests):"
awk -F'\t' '$1 != "all" { printf "  %-8s %-21s %3d min %2d s   CPU %3d min %2d s\n", $1, $2, $3 / 60, $3 % 60, $4 / 60, $4 % 60 }' "$logs/steps.tsv"
echo "test: passed in $((total / 60)) min $((total % 60)) s$([ "$fast" = 1 ] && echo " (--fast: no sanitizers, MPI, fault or install scripts)" || true)"
