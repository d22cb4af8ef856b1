#!/usr/bin/env bash
# The main job: install dependencies, build the dabench program (and its MPI module: nothing else;
# scripts/test.sh builds the tests, benchmarks and Python package), run the quick-start experiment
# (BP vs exact on the 2×3 grid baseline of Fig. 6) and render its figure.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh dabench
./build/dabench run experiments/quickstart.ini --force
/usr/bin/python3 plots/fig6.py results/quickstart/summary.csv --out results/quickstart/fig6.png \
  --title "2x3 grid, Pd = 0.6, lambda_fa = 0.01, r = 1"
echo
echo "Results of the quick start are in results/quickstart/:"
echo "  trials.csv   one row per (spacing, trial, algorithm)"
echo "  summary.csv  mean / SE / median / 5th / 95th percentile per (spacing, algorithm)"
echo "  meta.json    command line, seed, commit, compiler, threads, timing"
echo "  fig6.png     average max error and median time (5-95 % band) versus spacing (as Fig. 6 of the BP paper)"
