"""dabench.draw() gives the problem a run draws: the command line's trials.csv is recomputed from it."""
import subprocess

import numpy as np
import pandas
import pytest

import dabench
from conftest import BASELINE_SCENARIO, write_experiment

EXPERIMENT = """\
scenario = grid
trials = 4
seed = 77
reference = exact
algorithm = bp
""" + BASELINE_SCENARIO + """\
[sweep]
spacing = 0.5, 1.25, 4
"""


def max_error(estimate, reference):
    return np.abs(estimate - reference).max(axis=1).mean()


def test_draw_reproduces_a_command_line_run(tmp_path, dabench_program):
    experiment = write_experiment(tmp_path, EXPERIMENT)
    subprocess.run([dabench_program, "run", experiment, "--out", tmp_path / "run", "--threads", "2"], check=True,
                   capture_output=True)
    trials = pandas.read_csv(tmp_path / "run" / "trials.csv", float_precision="round_trip")
    rows = trials[trials.algorithm == "bp"]
    assert len(rows) == 12
    for row in rows.itertuples():
        problem = dabench.draw(str(experiment), trial=row.trial, point=row.point)
        assert (problem["scenario"], problem["seed"], float(problem["params"]["spacing"])) == ("grid", 77, row.spacing)
        assert problem["psi"].shape == (row.n_targets, row.n_measurements)
        # The same draw by name, parameters and seed.
        by_name = dabench.draw("grid", seed=77, trial=row.trial, point=row.point,
                               point_params=dict(rows=2, cols=3, pd=0.6, lambda_fa=0.01, spacing=row.spacing))
        assert np.array_equal(by_name["psi"], problem["psi"])
        assert np.array_equal(by_name["true_measurement"], problem["true_measurement"])
        exact = dabench.marginals(problem["psi"], "exact", pd=problem["pd"], lambda_fa=problem["lambda_fa"])
        bp = dabench.marginals(problem["psi"], "bp", pd=problem["pd"], lambda_fa=problem["lambda_fa"])
        assert max_error(bp, exact) == row.max_error  # bit-identical to the run's row


def test_draw_truth_and_errors(tmp_path):
    problem = dabench.draw("grid", seed=1, trial=3, point_params={"rows": 1, "cols": 2, "pd": 0.9})
    n = problem["psi"].shape[0]
    assert n == 2 and problem["true_measurement"].shape == (n,)
    assert problem["detections"] == np.count_nonzero(problem["true_measurement"])
    assert problem["pd"] == 0.9
    with pytest.raises(ValueError, match="^draw: give seed="):
        dabench.draw("grid", trial=0)
    with pytest.raises(ValueError, match="^draw: unknown single-scan scenario 'bearings'"):
        dabench.draw("bearings", seed=1)
    with pytest.raises(ValueError, match="grid.*unknown.*'colz'"):
        dabench.draw("grid", seed=1, point_params={"colz": 2})
    experiment = write_experiment(tmp_path, EXPERIMENT)
    with pytest.raises(ValueError, match="^draw: point 3 of .*: it has points 0 to 2"):
        dabench.draw(str(experiment), point=3)
