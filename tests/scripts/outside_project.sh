#!/usr/bin/env bash
# dabench as an installed library: installs BUILD (default ./build, already built) into a
# temporary prefix, configures and builds examples/outside-project against it, and checks that
#   - outside-solve solves by SPEC and by typed options with identical results (its own checks);
#   - `outside list` shows damped-bp and, unchanged, everything the installed dabench lists
#     (the built-in registrations survive static linking);
#   - `outside run quickstart-damped.ini` writes every damped-bp row with status ok.
# Fails loudly (message on stderr, exit status 1) on the first problem; removes its files.
set -euo pipefail
cd "$(dirname "$0")/../.."
build=$(realpath "${1:-build}")
work=$(mktemp -d "${TMPDIR:-/tmp}/dabench-outside-XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "test_outside_project: FAILED: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/prefix" >/dev/null || fail "cmake --install $build"
cmake -S examples/outside-project -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" \
  -DCMAKE_BUILD_TYPE=Release >/dev/null || fail "configuring examples/outside-project"
cmake --build "$work/build" -j"$(nproc)" >/dev/null || fail "building examples/outside-project"
cd "$work/build"

./outside-solve >solve.txt || fail "outside-solve (exit $?): $(cat solve.txt)"

"$work/prefix/bin/dabench" list >dabench-list.txt
./outside list >outside-list.txt || fail "outside list (exit $?)"
for name in bp exact ehm grid bearings othr jdt-vb mptf; do
  grep -q "^  $name " dabench-list.txt || fail "the installed dabench does not list '$name'"
done
removed=$(diff dabench-list.txt outside-list.txt | grep -c '^<' || true)
added=$(diff dabench-list.txt outside-list.txt | grep '^>' || true)
[ "$removed" -eq 0 ] || fail "outside list lacks $removed line(s) of dabench list"
grep -q '^>   damped-bp ' <<<"$added" || fail "outside list does not show damped-bp"
[ "$(wc -l <<<"$added")" -eq 4 ] || fail "outside list adds other lines than damped-bp and its 3 parameters: $added"

./outside run quickstart-damped.ini --threads 2 2>run.txt || fail "outside run (exit $?): $(cat run.txt)"
trials=results/quickstart-damped/trials.csv
rows=$(grep -c ',damped-bp:damping=0.5,ok,' "$trials" || true)
[ "$rows" -eq 8200 ] || fail "$trials has $rows damped-bp rows with status ok, not 41 spacings x 200 trials"
[ -s results/quickstart-damped/summary.csv ] || fail "no summary.csv"
echo "test_outside_project: ok (installed, built examples/outside-project, solved, listed, ran $rows damped-bp trials)"
