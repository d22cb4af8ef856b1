"""bp-paper's runs: the committed run folders under results/bp-paper, the commands that made them
(their provenance) and the steps after them (the trials digests, Figs 6 and 7)."""

import os

from reports.core import data
from reports.core.study import Run, Step

FOLDER = "results/bp-paper"
EXP1 = f"{FOLDER}/exp1"
EXP1_1E7 = f"{FOLDER}/exp1-with-mcmcda-1e7"
EXP2 = f"{FOLDER}/exp2"
EXP3 = f"{FOLDER}/exp3"
BP_VS_EXACT = f"{FOLDER}/fig6-exp1-bp-vs-exact"
JT_READING = f"{FOLDER}/jt-threshold-reading"
DIGEST = "trials-digest.csv"  # per (point, algorithm) of a run's trials.csv, which is not committed
DIGESTED = (EXP1, EXP2, EXP3, BP_VS_EXACT)  # the runs whose digests the checks read
BENCH = f"{FOLDER}/bench.json"  # Google Benchmark JSON of the kernels below

# The kernels of the Timing table (bench/single_scan/*.cpp); `taskset -c 0` pins them to one core.
BENCH_FILTER = ("^(fig3_naive/|solve_grid/bp_|solve_grid_ehm/ehm_(2x3_s[03]|3x(5|10|20|30)_s3)(/|$)"
                "|chain_grid/|solve_grid_jt/jt_1e-3_(2x3|3x3)_s[03]$)")

RUNS = [
    Run(EXP1, "./build/dabench run experiments/bp_paper/exp1-timed.ini --force",
        "exp. 1 without MCMCDA 1e7, 1000 trials: the one-hour target"),
    Run(EXP1_1E7, "./build/dabench run experiments/bp_paper/exp1.ini --trials 20 --force",
        "exp. 1 with MCMCDA 1e7, 20 trials"),
    Run(EXP2, "./build/dabench run experiments/bp_paper/exp2.ini --trials 50 --force", "exp. 2: n×3, n = 2…30"),
    Run(EXP3, "./build/dabench run experiments/bp_paper/exp3.ini --trials 20 --force", "exp. 3: n×n, n = 2…10"),
    Run(BP_VS_EXACT, "./build/dabench run experiments/bp_paper/fig6-exp1.ini --force", "BP vs exact, 1000 trials"),
    Run(JT_READING, "./build/dabench run experiments/bp_paper/jt-threshold-reading.ini --force",
        "which JT threshold? 200 trials"),
    Run(BENCH, f"taskset -c 0 ./build/dabench_bench --benchmark_filter='{BENCH_FILTER}' "
               f"--benchmark_out={BENCH} --benchmark_out_format=json", "the Timing table's kernels, one core",
        optional=True),
]

FIG6_INPUTS = (f"--exp1 {EXP1}/summary.csv --exp1-extra {EXP1_1E7}/summary.csv "
               f"--exp2 {EXP2}/summary.csv --exp3 {EXP3}/summary.csv")
STEPS = [
    Step("/usr/bin/python3 -m reports.digest bp-paper", f"{DIGEST} of exp1, exp2, exp3, fig6-exp1-bp-vs-exact"),
    Step(f"/usr/bin/python3 -m plots.fig6_paper {FIG6_INPUTS} --time-stat mean --out {FOLDER}/fig6.png"),
    Step(f"/usr/bin/python3 -m plots.fig6_paper {FIG6_INPUTS} --time-stat median --out {FOLDER}/fig6_median_time.png"),
    Step(f"/usr/bin/python3 -m plots.fig7 {EXP1}/summary.csv --where pd=0.9 --out {FOLDER}/fig7.png"),
]


def summary_path(root, folder):
    """The path of a run's summary.csv (DataError if it is missing: fig6_paper would exit)."""
    full = data.path(root, folder, "summary.csv")
    if not os.path.exists(full):
        raise data.DataError(f"{folder}/summary.csv: missing")
    return full
