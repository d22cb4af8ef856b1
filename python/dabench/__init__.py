"""dabench from Python: single-scan marginals from numpy arrays, runs of experiment files as
pandas DataFrames, and Python functions compared with every built-in algorithm on identical
trials. See docs/python.md.

    import numpy as np, dabench
    psi = np.array([[2.0, 0.5, 0.0], [1.0, 3.0, 0.2]])     # ψ_i(j): targets × measurements
    dabench.marginals(psi, "exact")                         # n × (m+1), column 0 = missed detection
    run = dabench.run("experiments/quickstart.ini", trials=100)
    run.summary                                             # pandas DataFrame of summary.csv

Errors the command line reports as "dabench: MESSAGE" raise ValueError(MESSAGE) here; an
algorithm that refuses a problem raises SkippedError (or, with report=True, reports it).
"""
from ._core import (SkippedError, __version__, algorithms, draw, git_commit, kinds, marginals, marginals_batch,
                    registered, scenarios, time_solver, unregister)
from ._core import register as _register
from ._runs import Run, load, run

__all__ = ["SkippedError", "algorithms", "draw", "kinds", "load", "marginals", "marginals_batch", "register",
           "registered", "run", "Run", "scenarios", "time_solver", "unregister", "__version__", "git_commit"]


def register(name, function, params=None, description=""):
    """Makes `function(psi, **params) -> marginals` a single-scan algorithm called `name`.

    psi is the problem's ψ (n × m float64, ψ_i(0) = 1 implied); the function returns the n × (m+1)
    marginals (column 0 = missed detection), or (marginals, {"iterations": k, "converged": bool}).
    `params` maps each parameter to its default (int, float, bool or str); a SPEC such as
    "name:iterations=50" sets them in experiment files, run() and marginals(). A call that raises
    or returns a wrong shape or non-finite values is that trial's failed:<reason>; the run goes on.

    The function runs under the GIL: on T threads the built-in algorithms still run in parallel,
    but the Python calls take turns, so a run is no faster than its Python calls made one by one.
    Registering the same name again replaces the function; unregister(name) removes it.
    """
    _register(name, function, params, description)
