"""Shared helpers of the Python module's tests: the brute-force reference, a numpy BP, problems."""
import itertools
import os
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[2]


def brute_force_marginals(psi):
    """p(a_i = j) of eqs (9)-(11) of bp-marginal-association by enumerating every consistent event."""
    n, m = psi.shape
    marginals = np.zeros((n, m + 1))
    total = 0.0
    for event in itertools.product(range(m + 1), repeat=n):  # event[i] = 0 (missed) or 1..m
        used = [j for j in event if j > 0]
        if len(used) != len(set(used)):
            continue
        weight = np.prod([psi[i, j - 1] if j > 0 else 1.0 for i, j in enumerate(event)])
        total += weight
        for i, j in enumerate(event):
            marginals[i, j] += weight
    return marginals / total


def numpy_bp(psi, tolerance=1e-14, max_iterations=100000):
    """Loopy BP for data association (Williams & Lau 2014, eqs (26)-(27)), written independently of
    dabench: messages target→measurement μ and measurement→target ν, updated in parallel."""
    n, m = psi.shape
    nu = np.ones((n, m))
    for _ in range(max_iterations):
        weighted = psi * nu
        mu = psi / (1.0 + weighted.sum(axis=1, keepdims=True) - weighted)
        new_nu = 1.0 / (1.0 + mu.sum(axis=0, keepdims=True) - mu)
        change = np.max(np.abs(new_nu - nu)) if nu.size else 0.0
        nu = new_nu
        if change < tolerance:
            break
    beliefs = np.hstack([np.ones((n, 1)), psi * nu])
    return beliefs / beliefs.sum(axis=1, keepdims=True)


def random_psi(rng, n, m, gated_share=0.3):
    psi = rng.exponential(2.0, size=(n, m))
    psi[rng.random((n, m)) < gated_share] = 0.0
    return psi


@pytest.fixture
def rng():
    return np.random.default_rng(20141)


@pytest.fixture(scope="session")
def dabench_program():
    program = Path(os.environ.get("DABENCH_PROGRAM", ROOT / "build" / "dabench"))
    if not program.is_file():
        pytest.skip(f"no {program} (build it, or set DABENCH_PROGRAM)")
    return program


# The [scenario] block of the BP paper's baseline panel (Fig. 6 top left, spacing swept).
BASELINE_SCENARIO = """\
[scenario]
rows = 2
cols = 3
pd = 0.6
lambda_fa = 0.01
"""


def write_experiment(folder, text):
    path = Path(folder) / "experiment.ini"
    path.write_text(text)
    return path
