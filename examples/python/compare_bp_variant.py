#!/usr/bin/python3
"""Your association algorithm beside dabench's on identical trials: a numpy loopy BP with a fixed
number of iterations (as Stone Soup's loopy-BP data associator runs it) is registered as
`numpy-bp`, run with dabench's bp (which stops by the Theorem-3 bound) and exact marginals on the
baseline panel of the BP paper's Fig. 6 (fig6-bp-variant.ini), and plotted as Fig. 6 is.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/compare_bp_variant.py [--trials 1000]

Writes results/python-example/ (trials.csv, summary.csv, meta.json, fig6.png) and prints the
average maximum marginal error of each algorithm at a few spacings.
"""
import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

import dabench

HERE = Path(__file__).resolve().parent
ROOT = HERE.parents[1]


def fixed_iteration_bp(psi, iterations=10):
    """Loopy BP for data association (Williams & Lau 2014, eqs (26)-(27)): messages from targets to
    measurements (mu) and back (nu), `iterations` parallel updates, then the beliefs."""
    nu = np.ones_like(psi)
    for _ in range(iterations):
        weighted = psi * nu
        mu = psi / (1.0 + weighted.sum(axis=1, keepdims=True) - weighted)
        nu = 1.0 / (1.0 + mu.sum(axis=0, keepdims=True) - mu)
    beliefs = np.hstack([np.ones((psi.shape[0], 1)), psi * nu])
    return beliefs / beliefs.sum(axis=1, keepdims=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--trials", type=int, default=None, help="trials per spacing (default: the file's 1000)")
    parser.add_argument("--out", default=str(ROOT / "results" / "python-example"))
    args = parser.parse_args()

    dabench.register("numpy-bp", fixed_iteration_bp, params={"iterations": 10},
                     description="loopy BP in numpy, a fixed number of iterations")
    # One thread: calls of a Python function take turns on the GIL, and time_us would count the waits.
    run = dabench.run(HERE / "fig6-bp-variant.ini", trials=args.trials, out=args.out, force=True, threads=1)

    summary = run.summary
    table = summary.pivot(index="spacing", columns="algorithm", values="max_error_mean")
    table = table.drop(columns=["exact"])
    print("average max marginal error against exact (rows: spacing)")
    print(table.loc[[0.0, 1.0, 1.25, 2.0, 5.0, 10.0]].to_string(float_format=lambda v: f"{v:.5f}"))
    figure = Path(args.out) / "fig6.png"
    subprocess.run([sys.executable, "-m", "plots.fig6", Path(args.out).resolve() / "summary.csv", "--out", figure.resolve(),
                    "--title", "2x3 grid, Pd = 0.6, lambda_fa = 0.01, r = 1: a numpy BP variant"], check=True, cwd=ROOT)
    print(f"figure: {figure}")


if __name__ == "__main__":
    main()
