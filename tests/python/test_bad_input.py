"""Bad input raises ValueError with the command line's one-line message."""
import subprocess

import numpy as np
import pytest

import dabench


@pytest.mark.parametrize("weights, message", [
    (np.array([[1 + 2j]]), "weights: dtype complex128 is not real numbers"),
    (np.array([["a"]]), "weights: dtype <U1 is not real numbers"),
    (np.array([[True]]), "weights: dtype bool is not real numbers"),
    (np.ones(3), "weights: a 1-dimensional array, not a matrix"),
    (np.ones((2, 2, 2)), "weights: a 3-dimensional array, not a matrix"),
    ([[1.0, "x"]], "weights: dtype <U32 is not real numbers"),
    (np.array([[1.0, np.nan]]), "weights:1: column 2: weight nan is not finite"),
    (np.array([[1.0, 2.0], [0.5, -1.0]]), "weights:2: column 2: weight -1 is negative"),
    (np.array([[1.0, np.inf]]), "weights:1: column 2: weight inf is not finite"),
])
def test_bad_weights(weights, message):
    with pytest.raises(ValueError, match="^" + message.replace("(", r"\(").replace(")", r"\)")):
        dabench.marginals(weights, "bp")


def test_bad_layouts():
    with pytest.raises(ValueError, match=r"^unknown weights layout 'pyehm' \(psi, stonesoup, tcl or matlab\)"):
        dabench.marginals(np.ones((2, 3)), layout="pyehm")
    with pytest.raises(ValueError, match="^weights:2: column 1: the clutter weight is 0"):
        dabench.marginals(np.array([[1.0, 1.0], [0.0, 2.0]]), layout="matlab")
    with pytest.raises(ValueError, match="off-diagonal entry of the missed-detection block must be 0"):
        dabench.marginals(np.array([[1.0, 1.0, 0.5], [1.0, 0.0, 1.0]]), layout="tcl")


def test_bad_algorithms_and_parameters():
    psi = np.ones((2, 2))
    with pytest.raises(ValueError, match="^unknown algorithm 'nope' \\(known: .*bp.*\\)"):
        dabench.marginals(psi, "nope")
    with pytest.raises(ValueError, match="bp.*unknown.*'dampin'"):
        dabench.marginals(psi, "bp:dampin=0.5")
    with pytest.raises(ValueError, match="bp.*delta"):
        dabench.marginals(psi, "bp:delta=-1")
    with pytest.raises(ValueError, match=r"^marginals: pd 1.5 must be in \(0, 1\)"):
        dabench.marginals(psi, "lmipda", pd=1.5)
    with pytest.raises(ValueError, match="^unknown kind 'multi' "):
        dabench.algorithms("multi")
    with pytest.raises(ValueError, match="^marginals_batch: threads 0 must be >= 1"):
        dabench.marginals_batch([psi], "bp", threads=0)


def test_messages_match_the_command_line(tmp_path, dabench_program):
    csv = tmp_path / "weights.csv"
    csv.write_text("1,2\n0.5,-1\n")
    cli = subprocess.run([dabench_program, "solve", "--algorithm", "bp", "--weights", csv],
                         capture_output=True, text=True)
    assert cli.returncode == 2
    with pytest.raises(ValueError) as python:
        dabench.marginals(np.array([[1.0, 2.0], [0.5, -1.0]]), "bp")
    assert cli.stderr.strip() == f"dabench: {csv}:2: column 2: weight -1 is negative"
    assert str(python.value) == "weights:2: column 2: weight -1 is negative"
    for spec in ["nope", "bp:dampin=0.5", "bp:delta=-1"]:
        cli = subprocess.run([dabench_program, "solve", "--algorithm", spec, "--weights", csv],
                             capture_output=True, text=True)
        with pytest.raises(ValueError) as python:
            dabench.marginals(np.ones((2, 2)), spec)
        assert cli.stderr.strip() == f"dabench: {python.value}"


def test_zero_missed_detection_weight():
    # Pd = 1 (a zero missed-detection weight, as Stone Soup and the TCL accept): the target takes
    # a measurement in every event; exact methods answer, the others refuse with a status.
    weights = np.array([[0.0, 0.2, 0.4, 0.0], [0.5, 0.3, 0.0, 0.6]])
    marginals = dabench.marginals(weights, "exact", layout="stonesoup")
    assert marginals[0, 0] == 0.0
    assert marginals[0, 1] == pytest.approx(0.22 / 0.78, rel=1e-14)
    assert np.allclose(dabench.marginals(weights, "ehm", layout="stonesoup"), marginals, rtol=1e-14, atol=0)
    with pytest.raises(dabench.SkippedError, match="bp: skipped:zero_miss_weight"):
        dabench.marginals(weights, "bp", layout="stonesoup")
    with pytest.raises(dabench.SkippedError, match="exact: skipped:infeasible"):
        dabench.marginals(np.array([[0.0, 1.0], [0.0, 1.0]]), "exact", layout="stonesoup")
