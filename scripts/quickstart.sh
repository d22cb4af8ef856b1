#!/usr/bin/env bash
# The main job: install dependencies, build the dabench program (and its MPI module: nothing else;
# scripts/test.sh builds the tests, benchmarks and Python package), run the quick-start experiment
# (BP vs exact on the 2×3 grid baseline of Fig. 6) into out/quickstart/ (ignored by git), render
# its figure, and compare its numbers with the committed reference run in results/quickstart/
# (reports/quickstart_check.py). It writes no tracked file: the committed run changes only
# through `python3 -m reports.rerun quickstart --in-place`.
# Environment: DABENCH_QUICKSTART_TRIALS=N runs the first N of the 10 000 trials per spacing
# (for N = 100, 200, 1000 compared bit for bit with the digest the committed run recorded of its
# own first N trials; other N are not compared);
# DABENCH_QUICKSTART_OUT=DIR writes there instead of out/quickstart.
set -euo pipefail
cd "$(dirname "$0")/.."
out=${DABENCH_QUICKSTART_OUT:-out/quickstart}
trials=()
[ -z "${DABENCH_QUICKSTART_TRIALS:-}" ] || trials=(--trials "$DABENCH_QUICKSTART_TRIALS")
bash scripts/setup.sh
bash scripts/build.sh dabench
./build/dabench run experiments/quickstart.ini --out "$out" --force "${trials[@]}"
/usr/bin/python3 -m plots.fig6 "$out/summary.csv" --out "$out/fig6.png" \
  --title "2x3 grid, Pd = 0.6, lambda_fa = 0.01, r = 1"
echo
echo "Results of the quick start are in $out/:"
echo "  trials.csv   one row per (spacing, trial, algorithm)"
echo "  summary.csv  mean / SE / median / 5th / 95th percentile per (spacing, algorithm)"
echo "  meta.json    command line, seed, commit, compiler, threads, timing"
echo "  fig6.png     average max error and median time (5-95 % band) versus spacing (as Fig. 6 of the BP paper)"
echo
echo "Compared with the committed reference run (results/quickstart/):"
PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 -m reports.quickstart_check "$out" results/quickstart
