"""dabench.run(), load() and register(): Python algorithms on the trials of the built-in ones."""
import numpy as np
import pytest

import dabench
from conftest import BASELINE_SCENARIO, numpy_bp, write_experiment

EXPERIMENT = """\
scenario = grid
trials = 30
seed = 5
reference = bp:delta=1e-13,max_iterations=100000
algorithm = pybp
algorithm = pybp:tolerance=0.1
algorithm = pyfails
algorithm = exact
""" + BASELINE_SCENARIO + """\
[sweep]
spacing = 0.5, 1.5
"""


@pytest.fixture
def python_algorithms():
    def fails(psi, mode="raise"):
        if mode == "raise" and psi.shape[0] > 0:
            raise ArithmeticError("no luck")
        if mode == "shape":
            return np.ones((psi.shape[0], 1))
        return np.full((psi.shape[0], psi.shape[1] + 1), np.nan)

    dabench.register("pybp", numpy_bp, params={"tolerance": 1e-14, "max_iterations": 100000},
                     description="numpy BP of the tests")
    dabench.register("pyfails", fails, params={"mode": "raise"})
    yield
    for name in ["pybp", "pyfails"]:
        dabench.unregister(name)


def test_registered_bp_equals_bp_in_a_run(tmp_path, python_algorithms):
    experiment = write_experiment(tmp_path, EXPERIMENT)
    run = dabench.run(experiment, out=tmp_path / "run", threads=2, progress=False)
    trials = run.trials
    assert len(trials) == 2 * 30 * 5 and run.meta["status"] == "complete"
    pybp = trials[trials.algorithm == "pybp"]
    assert (pybp.status == "ok").all() and pybp.max_error.max() <= 1e-9
    loose = trials[trials.algorithm == "pybp:tolerance=0.1"]
    assert (loose.status == "ok").all() and loose.max_error.max() > 1e-9  # the SPEC's value reached the function
    failed = trials[trials.algorithm == "pyfails"]
    assert (failed.status == "failed:ArithmeticError: no luck").all()
    assert (trials[trials.algorithm == "exact"].status == "ok").all()
    assert set(run.summary.algorithm) >= {"pybp", "exact"}
    again = dabench.load(tmp_path / "run")
    assert again.trials.equals(trials) and again.meta == run.meta
    # The same rows for one thread: Python calls take turns, results do not depend on it.
    single = dabench.run(experiment, out=tmp_path / "run1", threads=1, progress=False)
    columns = ["point", "trial", "algorithm", "status", "max_error", "mean_error"]
    assert single.trials[columns].equals(trials[columns])


def test_wrong_returns_are_failed_rows(tmp_path, python_algorithms):
    experiment = write_experiment(tmp_path, EXPERIMENT.replace("algorithm = pyfails", "algorithm = pyfails:mode=shape\n"
                                                               "algorithm = pyfails:mode=nan"))
    trials = dabench.run(experiment, out=tmp_path / "run", threads=2, progress=False).trials
    shape = trials[trials.algorithm == "pyfails:mode=shape"].status
    assert shape.str.match(r"failed:returned shape \(\d+, 1\), expected \(\d+, \d+\)$").all()
    assert trials[trials.algorithm == "pyfails:mode=nan"].status.str.match(r"failed:returned nan at \(0, 0\)$").all()


def test_registered_algorithm_in_marginals_and_listing(rng, python_algorithms):
    psi = rng.exponential(1.0, (3, 4))
    np.testing.assert_allclose(dabench.marginals(psi, "pybp"), dabench.marginals(psi, "bp:delta=1e-13"), atol=1e-9)
    marginals, report = dabench.marginals(psi, "pyfails", report=True)
    assert marginals is None and report["status"] == "failed:ArithmeticError: no luck"
    listed = {a["name"]: a for a in dabench.algorithms("single_scan")}
    assert listed["pybp"]["description"] == "numpy BP of the tests"
    assert {p["name"]: p["default"] for p in listed["pybp"]["params"]} == {"tolerance": 1e-14, "max_iterations": 100000}
    assert set(dabench.registered()) == {"pybp", "pyfails"}
    with pytest.raises(ValueError, match="^register: 'bp' is a built-in algorithm"):
        dabench.register("bp", numpy_bp)
    with pytest.raises(ValueError, match="pybp.*unknown.*'tol'"):
        dabench.marginals(psi, "pybp:tol=1")
    with pytest.raises(TypeError):
        dabench.register("notcallable", 3)


def test_listing_and_bad_runs(tmp_path):
    listed = {(a["kind"], a["name"]): a for a in dabench.algorithms()}
    assert {("single_scan", "bp"), ("multi_scan", "cv"), ("tracking", "jdt-vb"), ("tbd", "tbd-bp")} <= set(listed)
    delta = {p["name"]: p for p in listed[("single_scan", "bp")]["params"]}["delta"]
    assert isinstance(delta["default"], float) and delta["doc"]
    assert "grid" in {s["name"] for s in dabench.scenarios("single_scan")}
    kinds = {k["kind"]: k for k in dabench.kinds()}
    assert list(kinds) == ["single_scan", "multi_scan", "tracking", "tbd"]
    assert (kinds["single_scan"]["error"], kinds["single_scan"]["time"], kinds["single_scan"]["time_count"]) == \
        ("max_error", "time_us", None)
    assert (kinds["tbd"]["time"], kinds["tbd"]["time_to_seconds"], kinds["tbd"]["time_count"]) == \
        ("step_time_us", 1e-6, "n_steps")
    assert kinds["tracking"]["error"] in kinds["tracking"]["columns"] and kinds["tracking"]["time"] == "tet_s"
    with pytest.raises(ValueError, match="^run: trials 0 must be >= 1"):
        dabench.run("experiments/quickstart.ini", trials=0)
    with pytest.raises(ValueError, match="nothing.ini"):
        dabench.run(tmp_path / "nothing.ini")
    with pytest.raises(ValueError, match="unknown algorithm 'pybp'"):
        dabench.run(write_experiment(tmp_path, EXPERIMENT), out=tmp_path / "x", progress=False)
    with pytest.raises(ValueError, match="not a dabench run folder \\(no meta.json\\)"):
        dabench.load(tmp_path)


def test_interrupted_run_resumes_to_the_same_files(tmp_path):
    from dabench import _core
    experiment = write_experiment(tmp_path, EXPERIMENT.replace("trials = 30", "trials = 4000")
                                  .replace("algorithm = pybp\nalgorithm = pybp:tolerance=0.1\nalgorithm = pyfails\n", "algorithm = bp\n"))
    whole = dabench.run(experiment, out=tmp_path / "whole", threads=2, progress=False)
    handle = _core.start_run(str(experiment), out=str(tmp_path / "cut"), threads=2)
    while handle.progress()[0] == 0 and not handle.wait(0.001):
        pass
    while not handle.wait(0.001):
        handle.interrupt()
    outcome = handle.result()
    assert outcome["interrupted"] and 0 < outcome["items_written"] < outcome["items_total"] == 8000
    with pytest.raises(ValueError, match="resume"):  # an unfinished run is not overwritten by accident
        dabench.run(experiment, out=tmp_path / "cut", progress=False)
    resumed = dabench.run(experiment, out=tmp_path / "cut", threads=1, resume=True, progress=False)
    columns = [c for c in whole.trials.columns if c != "time_us"]
    assert resumed.trials[columns].equals(whole.trials[columns])
    assert resumed.meta["status"] == "complete" and resumed.meta["resumed"]


def test_progress_reaches_the_total(tmp_path):
    from dabench import _core
    experiment = write_experiment(tmp_path, EXPERIMENT.replace("algorithm = pybp\nalgorithm = pybp:tolerance=0.1\n"
                                                               "algorithm = pyfails\n", ""))
    handle = _core.start_run(str(experiment), out=str(tmp_path / "run"))
    while not handle.wait(0.05):
        pass
    assert handle.progress() == (60, 60) and not handle.result()["interrupted"]
