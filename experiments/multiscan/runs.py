"""The multiscan study's runs: the committed run folders under results/multiscan, the commands that
made them (their provenance) and the steps after them (the CDF figures)."""

from reports.core.study import Run, Step

FOLDER = "results/multiscan"
FIGURES = [("fig3", "Fig. 3"), ("fig4", "Fig. 4"), ("fig5", "Fig. 5")]
COST_RUN = f"{FOLDER}/algorithm2-cost"
COST_RUN_1000 = f"{FOLDER}/algorithm2-cost-1000"  # the same trial at 1000 particles: the estimate's basis
# The open readings of Sec. IV (issue 28) on Fig. 4's setting, experiments/multiscan/reading-*.ini
# (readings.py); the first is the scenario's default, the reading of Figs 3-5.
READINGS = [("corner", "corner 0, round robin (the default)"), ("random", "random corner, round robin"),
            ("corner-grouped", "corner 0, grouped by sensor"), ("grouped", "random corner, grouped by sensor")]
PARTICLE_COUNTS_RUN = f"{FOLDER}/particle-counts"  # MSBP, CVS(0.75), CVS(0.55) at 1000 and 300 particles

RUNS = [
    Run(f"{FOLDER}/particles", "./build/dabench run experiments/multiscan/particles.ini --force",
        "calibration of exact Bayes: one target, 300 to 10 000 particles"),
    Run(f"{FOLDER}/fig3", "./build/dabench run experiments/multiscan/fig3.ini --force", "Fig. 3: 4 scans"),
    Run(f"{FOLDER}/fig4", "./build/dabench run experiments/multiscan/fig4.ini --force", "Fig. 4: 12 scans"),
    Run(f"{FOLDER}/fig5", "./build/dabench run experiments/multiscan/fig5.ini --force",
        "Fig. 5: 12 scans, Fig. 4's trials"),
] + [Run(f"{FOLDER}/reading-{name}", f"./build/dabench run experiments/multiscan/reading-{name}.ini --force",
         f"reading: {text}; 10 000 / 1000 / 300 particles") for name, text in READINGS] + [
    Run(PARTICLE_COUNTS_RUN, "./build/dabench run experiments/multiscan/particle-counts.ini --force",
        "MSBP and CVS(0.75 / 0.55) at 1000 and 300 particles (Fig. 4's setting)"),
    Run(COST_RUN, "./build/dabench run experiments/multiscan/algorithm2-cost.ini --threads 1 --force",
        "Algorithm 2 vs Newton on one 10 000-particle CVS(0.95) trial, one thread: run it last",
        optional=True),
    Run(COST_RUN_1000, "./build/dabench run experiments/multiscan/algorithm2-cost-1000.ini --threads 1 --force",
        "the same trial at 1000 particles, one thread (about 20 min)", optional=True),
]

STEPS = [Step(f"/usr/bin/python3 -m plots.multiscan_cdf {FOLDER}/{name}/targets.csv --out {FOLDER}/{name}.png",
              f"{name}.png") for name in ("particles", "fig3", "fig4", "fig5")]
