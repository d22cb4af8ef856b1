#!/usr/bin/python3
"""A researcher's workflow with the Python package, end to end, in cells (`# %%`: run it whole, or
cell by cell in an editor that knows them):

  1. draw one trial of the BP paper's Fig. 6 baseline panel, exactly as a run draws it;
  2. solve it with three of dabench's algorithms and compare them with exact marginals;
  3. register a numpy algorithm of your own (here: PDA per target, blind to the other targets);
  4. run a panel of the figure with it beside bp, every algorithm on identical trials;
  5. plot the panel: average maximum marginal error against target spacing.

    PYTHONPATH=build/python /usr/bin/python3 examples/python/workflow.py [--trials 200] [--out DIR]

(or with the package installed by pip: docs/python.md). Writes DIR (default
results/python-workflow/): trials.csv, summary.csv, meta.json and workflow.png.
"""
# %% 0. Imports and options
import argparse
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import dabench  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
parser.add_argument("--trials", type=int, default=200, help="trials per spacing (default 200)")
parser.add_argument("--out", default=str(ROOT / "results" / "python-workflow"))
args = parser.parse_args()

# %% 1. One trial of the study's baseline panel: the experiment file says the scenario, its
# parameters and the seed; `point` is the sweep point (spacing 0, 0.5, ..., so point 2 is spacing 1).
problem = dabench.draw(str(ROOT / "experiments" / "bp_paper/fig6-exp1.ini"), trial=7, point=2)
psi = problem["psi"]
print(f"spacing {problem['params']['spacing']}: {psi.shape[0]} targets, {psi.shape[1]} measurements")

# %% 2. Three algorithms against exact marginals on that trial (LMIPDA needs the scenario's Pd and
# clutter density, which the draw carries).
exact = dabench.marginals(psi, "exact")
for spec in ["bp", "lmipda", "ehm"]:
    marginals, report = dabench.marginals(psi, spec, report=True, pd=problem["pd"], lambda_fa=problem["lambda_fa"])
    error = np.abs(marginals - exact).max()
    print(f"  {spec:8} max |p - p_exact| = {error:.2e}  ({report['time_us']:.1f} us, {report['iterations']} iterations)")
assert np.abs(dabench.marginals(psi, "ehm") - exact).max() < 1e-12  # EHM is exact too


# %% 3. Your own algorithm: psi (n × m, ψ_i(0) = 1 implied) in, n × (m+1) marginals out.
def independent_pda(psi, clutter_scale=1.0):
    """PDA for each target alone (eq (11)'s weights, every other target ignored): β_i(j) ∝ ψ_i(j),
    β_i(0) ∝ clutter_scale. What joint association buys over it is what the panel shows."""
    weights = np.hstack([np.full((psi.shape[0], 1), clutter_scale), psi])
    return weights / weights.sum(axis=1, keepdims=True)


dabench.register("independent-pda", independent_pda, params={"clutter_scale": 1.0},
                 description="PDA per target, blind to the other targets (numpy)")
print("independent-pda on the trial:", np.abs(dabench.marginals(psi, "independent-pda") - exact).max())

# %% 4. The panel: bp and the numpy algorithm against exact on identical trials — the study's own
# (experiments/bp_paper/fig6-exp1.ini's baseline: same scenario, seed and points, so bp's rows are
# those of results/bp-paper/fig6-exp1-bp-vs-exact).
experiment = """scenario = grid
trials = 1000
seed = 2014
reference = exact
algorithm = bp
algorithm = independent-pda
[scenario]
rows = 2
cols = 3
pd = 0.6
lambda_fa = 0.01
r = 1
weight_floor = 1e-4
[sweep]
spacing = 0:0.5:10
"""
with tempfile.TemporaryDirectory() as folder:
    path = Path(folder) / "panel.ini"
    path.write_text(experiment)
    # One thread: the Python function's calls take turns on the GIL, and time_us would count the waits.
    run = dabench.run(path, trials=args.trials, out=args.out, force=True, threads=1)
summary = run.summary
table = summary.pivot(index="spacing", columns="algorithm", values="max_error_mean")
print(table.loc[[0.0, 1.0, 2.0, 5.0, 10.0]].to_string(float_format=lambda v: f"{v:.4f}"))
assert (summary.loc[summary.algorithm == "exact", "max_error_mean"] == 0).all()

# %% 5. The figure: error ± one standard error against spacing, as the paper's Fig. 6 plots it.
figure, axes = plt.subplots(figsize=(6, 4))
for algorithm, rows in summary.groupby("algorithm", sort=False):
    if algorithm == "exact":
        continue
    axes.errorbar(rows.spacing, rows.max_error_mean, yerr=rows.max_error_se, label=algorithm, capsize=2)
axes.set_xlabel("target spacing")
axes.set_ylabel("average max marginal error vs exact")
axes.set_title(f"2x3 grid, Pd 0.6, λfa 0.01, r 1 ({args.trials} trials per spacing)")
axes.legend()
figure.tight_layout()
figure.savefig(Path(args.out) / "workflow.png", dpi=120)
print(f"figure: {Path(args.out) / 'workflow.png'}")
