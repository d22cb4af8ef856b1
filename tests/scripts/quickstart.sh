#!/usr/bin/env bash
# The README's first command at reduced size: scripts/quickstart.sh with DABENCH_QUICKSTART_TRIALS
# (the first 200 of the 10 000 trials per spacing) into a temporary folder, from the source tree
# SOURCE_DIR whose build/ ctest runs. Checks that
#   - it says its errors are the committed run's first 200 trials per spacing, bit for bit (the
#     digest results/quickstart/trials-digests.csv records), and prints the time ratios;
#   - it leaves the git tree as it found it (no tracked file changed, no untracked file added);
#   - one changed digit is found: in the run's trials.csv (against the digest), and in a
#     full-size summary (the committed run against itself is the same; with one error changed, not).
# Usage: quickstart.sh SOURCE_DIR
set -euo pipefail
cd "$1"
work=$(mktemp -d "${TMPDIR:-/tmp}/dabench-quickstart-XXXXXX")
trap 'rm -rf "$work"' EXIT
fail() { echo "quickstart test: FAILED: $*" >&2; exit 1; }
# The tree's state: what git calls changed or untracked, and the contents of each.
tree_state() {
  git status --porcelain --untracked-files=all
  git diff HEAD --binary
  git ls-files --others --exclude-standard -z | xargs -0r sha1sum
}
before=$(tree_state | sha1sum)

DABENCH_QUICKSTART_TRIALS=200 DABENCH_QUICKSTART_OUT="$work/run" DABENCH_PROGRESS=0 \
  bash scripts/quickstart.sh > "$work/log" 2>&1 || { tail -20 "$work/log"; fail "scripts/quickstart.sh exited $?"; }
expect() {  # expect FILE PATTERN WHAT: a line of FILE matches PATTERN
  grep -qE "$2" "$1" || { tail -12 "$1"; fail "no line $3"; }
}
expect "$work/log" "^quickstart: BP's peak error 0\.0[0-9]+ ± 0\.[0-9]+ at spacing [0-9.]+ \(200 trials per spacing\): the same as the committed run's first 200 trials per spacing \(its trials.csv, timings aside: 16400 rows, SHA-256 [0-9a-f]{12}…\)$" \
  "saying its trials are the committed run's first 200 per spacing"
expect "$work/log" "^quickstart: this machine: bp [0-9.]+×, exact [0-9.]+× the committed run's mean time per trial" "with the time ratios"
[ -f "$work/run/fig6.png" ] || fail "no fig6.png in the quick start's output folder"
after=$(tree_state | sha1sum)
[ "$before" = "$after" ] || { git status --short; fail "the quick start changed the git tree"; }

check() { PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -m reports.quickstart_check "$@"; }
# changed_digit FILE LINE COLUMN: FILE with the last digit of COLUMN on line LINE changed.
changed_digit() {
  awk -F, -v OFS=, -v line="$2" -v column="$3" '
    NR == 1 { for (i = 1; i <= NF; i++) if ($i == column) c = i }
    NR == line { d = substr($c, length($c)); $c = substr($c, 1, length($c) - 1) (d == "9" ? "8" : d + 1) }
    { print }' "$1"
}
expect_difference() {  # expect_difference RUN_DIR PATTERN: the check exits 1 and says PATTERN
  local status=0
  check "$1" results/quickstart > "$work/check.txt" || status=$?
  [ "$status" -eq 1 ] || fail "$1: exit $status, not 1: $(cat "$work/check.txt")"
  expect "$work/check.txt" "$2" "saying $2"
}
# A shorter run's trials.csv, one error changed: not the committed run's first 200 trials.
cp -r "$work/run" "$work/changed-trials"
changed_digit "$work/run/trials.csv" 3 max_error > "$work/changed-trials/trials.csv"
expect_difference "$work/changed-trials" "NOT the same as the committed run's first 200 trials per spacing"
# A full-size summary: the committed run is the same as itself; one changed error is not.
check results/quickstart results/quickstart > "$work/check.txt" || fail "the committed run against itself: $(cat "$work/check.txt")"
expect "$work/check.txt" "the same as the committed run \(every column of summary.csv but the timings equal bit for bit, 82 rows\)" \
  "calling the committed run the same as itself"
mkdir "$work/changed-summary"
cp results/quickstart/meta.json "$work/changed-summary/"
changed_digit results/quickstart/summary.csv 3 max_error_mean > "$work/changed-summary/summary.csv"  # point 0, bp
expect_difference "$work/changed-summary" "NOT the same as the committed run: 1 field differs, first point 0, bp, max_error_mean"
echo "quickstart test: ok (the first 200 trials per spacing bit for bit; the git tree unchanged; changed digits found)"
