"""dabench.marginals(), marginals_batch() and time_solver() against a brute-force enumeration."""
import numpy as np
import pytest

import dabench
from conftest import brute_force_marginals, random_psi


@pytest.mark.parametrize("algorithm", ["exact", "ehm", "jt"])
def test_exact_methods_equal_enumeration(rng, algorithm):
    for _ in range(60):
        n, m = rng.integers(1, 5), rng.integers(0, 5)
        psi = random_psi(rng, n, m)
        np.testing.assert_allclose(dabench.marginals(psi, algorithm), brute_force_marginals(psi), rtol=0, atol=1e-12)


def test_bp_approximates_enumeration(rng):
    # BP is exact on trees; in general its error on these small problems stays below 0.1.
    worst = 0.0
    for _ in range(60):
        psi = random_psi(rng, rng.integers(1, 5), rng.integers(1, 5))
        bp = dabench.marginals(psi, "bp:delta=1e-10")
        np.testing.assert_allclose(bp.sum(axis=1), 1.0, atol=1e-12)
        worst = max(worst, np.abs(bp - brute_force_marginals(psi)).max())
    assert 0.0 < worst < 0.1
    tree = np.array([[3.0, 0.0, 0.0], [1.0, 2.0, 0.0], [0.0, 0.5, 4.0]])  # a chain: BP is exact
    np.testing.assert_allclose(dabench.marginals(tree, "bp:delta=1e-13"), brute_force_marginals(tree), atol=1e-10)


def layouts(psi, miss, clutter):
    """The same problem in each layout: ψ scaled by a missed-detection weight per target and (MATLAB)
    a clutter weight per measurement, which leaves the posterior unchanged."""
    n, m = psi.shape
    weights = psi * miss[:, None]
    matlab = np.empty((m + 1, n + 1))
    matlab[0, 0] = 7.0  # ignored
    matlab[0, 1:] = miss
    matlab[1:, 0] = clutter
    matlab[1:, 1:] = (weights * clutter[None, :]).T
    return {"psi": psi,
            "stonesoup": np.hstack([miss[:, None], weights]),
            "tcl": np.hstack([weights, np.diag(miss)]),
            "matlab": matlab}


def test_every_layout_gives_the_psi_marginals(rng):
    for _ in range(30):
        n, m = rng.integers(1, 5), rng.integers(0, 5)
        psi = random_psi(rng, n, m)
        reference = dabench.marginals(psi, "exact")
        for layout, matrix in layouts(psi, rng.uniform(0.1, 3.0, n), rng.uniform(0.1, 3.0, m)).items():
            np.testing.assert_allclose(dabench.marginals(matrix, "exact", layout=layout), reference, atol=1e-12,
                                       err_msg=layout)
            with np.errstate(divide="ignore"):
                logs = np.log(matrix)
            np.testing.assert_allclose(dabench.marginals(logs, "exact", layout=layout, log=True), reference,
                                       atol=1e-12, err_msg=f"{layout}, log")


def test_psi_layout_is_bit_identical_to_the_command_line_reading(rng):
    psi = random_psi(rng, 4, 4)
    assert np.array_equal(dabench.marginals(psi, "bp"), dabench.marginals(psi.tolist(), "bp"))
    assert np.array_equal(dabench.marginals(np.asfortranarray(psi), "bp"), dabench.marginals(psi, "bp"))


def test_report():
    psi = np.array([[2.0, 0.5], [1.0, 3.0]])
    marginals, report = dabench.marginals(psi, "bp", report=True)
    assert marginals.shape == (2, 3)
    assert report["status"] == "ok" and report["converged"] and report["iterations"] > 0
    assert report["w_star"] > 0 and report["time_us"] > 0
    # lmipda needs Pd: without it the problem is refused, as `dabench solve` refuses it.
    marginals, report = dabench.marginals(psi, "lmipda", report=True)
    assert marginals is None and report["status"] == "skipped:needs_pd"
    with pytest.raises(dabench.SkippedError, match="lmipda: skipped:needs_pd"):
        dabench.marginals(psi, "lmipda")
    assert dabench.marginals(psi, "lmipda", pd=0.6).shape == (2, 3)


def test_batch_equals_single_calls(rng):
    problems = [random_psi(rng, rng.integers(1, 7), rng.integers(0, 7)) for _ in range(200)]
    for algorithm in ["bp", "exact"]:
        batch = dabench.marginals_batch(problems, algorithm, threads=2)
        assert len(batch) == len(problems)
        for psi, marginals in zip(problems, batch):
            assert np.array_equal(marginals, dabench.marginals(psi, algorithm))
    batch, reports = dabench.marginals_batch([np.ones((2, 3))] * 3, "lmipda", report=True)
    assert all(b is None for b in batch) and {r["status"] for r in reports} == {"skipped:needs_pd"}
    with pytest.raises(ValueError, match=r"weights\[1\]:1: column 1: weight nan is not finite"):
        dabench.marginals_batch([problems[0], np.array([[np.nan]])], "bp")


def test_time_solver():
    timing = dabench.time_solver(np.array([[2.0, 0.5, 0.1], [1.0, 3.0, 0.2]]), "bp", budget_s=0.05, min_samples=3)
    assert timing["algorithm"] == "bp" and (timing["targets"], timing["measurements"]) == (2, 3)
    assert timing["samples"] >= 3 and timing["solves"] == timing["samples"] * timing["batch"]
    assert 0 < timing["p10_us"] <= timing["median_us"] <= timing["p90_us"]
