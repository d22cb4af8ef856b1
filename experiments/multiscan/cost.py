"""The cost of the multiple-scan methods: time, iterations, line-search steps and convergence of each
method in each figure run, the column-dual solver's convergence (O1), the runs' wall time, and
Algorithm 2 against the Newton solver on one trial (the Algorithm 2 cost run)."""

import math
import os

import numpy as np

from reports.core import data, markdown, stats, verdicts
from reports.core.study import Claim
from experiments.multiscan.runs import COST_RUN, COST_RUN_1000, FIGURES, FOLDER
from experiments.multiscan.targets import label, read_targets

RESIDUAL_TOLERANCE = 1e-12  # ColumnDualSettings::tolerance (column_dual_newton.hpp)
INNER_TOLERANCE = 1e-13  # InnerSolveSettings::tolerance (tilted_track.hpp)
NEWTON = "cvs:gamma=0.95"  # the cost run's two solvers of CVS(0.95)
ALGORITHM2 = "cvs:gamma=0.95,solver=pdca"
RUN_BY_ALGORITHM2 = {"msbp", "cvsh1:gamma=0.95"}  # every other cv* method runs the column-dual solver
SINGLE_SWEEP = {"cvsh1:gamma=0.95"}  # one sweep per step by definition: never "converged"
# The notes' prototype of the Newton solver, Newton iterations of one 8-target 12-scan CVS trial at
# P = 300 / 1000 / 10 000 (docs/models/column-dual-newton.md, "Where the design came from").
NOTES_PROTOTYPE_CVS_ITERATIONS = "163 / 150 / 156 Newton steps at 300 / 1000 / 10 000 particles"


def read_trials(root, folder):
    """{algorithm: [rows]} of folder/trials.csv, in the run's order."""
    out = {}
    for r in data.read_rows(root, f"{folder}/trials.csv"):
        out.setdefault(r["algorithm"], []).append(r)
    return out


def column(rows, name):
    return [v for v in (data.num(r, name) for r in rows if r["status"] == "ok") if v is not None]


def residual_text(values):
    """The largest residual, to enough digits to tell it from its tolerance (9.996e-13, not 1.0e-12)."""
    return f"{max(values):.3e}" if values else "–"


def cost_table(by_algorithm):
    """Per method: trials solved, median and mean time per trial, mean iterations and line-search
    steps, trials converged, largest column and inner residual (column-dual solver)."""
    rows = []
    for algorithm, group in by_algorithm.items():
        ok = [r for r in group if r["status"] == "ok"]
        seconds = [t / 1e6 for t in column(group, "time_us")]
        mean_s, se_s, _ = stats.mean_se(seconds)
        iterations, it_se, _ = stats.mean_se(column(group, "iterations"))
        searches, ls_se, n_ls = stats.mean_se(column(group, "line_search_steps"))
        residuals, inner = column(group, "residual"), column(group, "inner_residual")
        converged = sum(1 for r in ok if data.num(r, "converged") == 1)
        name = label(algorithm) + (" (Algorithm 2)" if algorithm in RUN_BY_ALGORITHM2 else "")
        rows.append([name, f"{len(ok)}/{len(group)}", markdown.sig(stats.percentile(seconds, 50)),
                     markdown.pm(mean_s, se_s), markdown.pm(iterations, it_se)
                     + (" sweeps" if algorithm in RUN_BY_ALGORITHM2 else ""),
                     markdown.pm(searches, ls_se) if n_ls else "–",
                     "one sweep per step" if algorithm in SINGLE_SWEEP else f"{converged}/{len(ok)}",
                     residual_text(residuals), residual_text(inner)])
    return markdown.table(["method", "solved", "median time (s)", "mean time (s)", "mean iterations",
                           "mean line-search steps", "converged", "largest residual", "largest inner residual"],
                          rows, "lrrrrrlrr")


def cost_section(report, root):
    """The cost table of each figure run, the solver's convergence (O1), CVS's Newton steps, the
    run times, and the Algorithm 2 cost run."""
    runs = {name: read_trials(root, f"{FOLDER}/{name}") for name, _ in FIGURES}
    for name, by_algorithm in runs.items():
        report.value(f"{name}.cost", cost_table(by_algorithm))
    claim_solver_converged(report, runs)
    for value, name in (("fig4.cvs_newton_steps", "iterations"), ("fig4.cvs_line_search", "line_search_steps")):
        m, se, _ = stats.mean_se(column(runs["fig4"].get("cvs:gamma=0.95", []), name))
        report.value(value, markdown.pm(m, se))
    report.value("notes.prototype_cvs_iterations", NOTES_PROTOTYPE_CVS_ITERATIONS)
    run_times(report, root, runs)
    algorithm2_cost(report, root)


def claim_solver_converged(report, runs):
    """O1 (ours): every solve of the column-dual solver (the cv* methods that report a residual)
    converged, its largest column and inner residuals below the solver's tolerances."""
    solves, converged, residual, inner = 0, 0, 0.0, 0.0
    for by_algorithm in runs.values():
        for algorithm, group in by_algorithm.items():
            if algorithm in RUN_BY_ALGORITHM2 or not column(group, "residual"):
                continue
            solves += len(group)
            converged += sum(1 for r in group if r["status"] == "ok" and data.num(r, "converged") == 1)
            residual = max([residual] + column(group, "residual"))
            inner = max([inner] + column(group, "inner_residual"))
    holds = solves > 0 and converged == solves and residual < RESIDUAL_TOLERANCE and inner < INNER_TOLERANCE
    report.claim(Claim(
        "O1", f"Every CV, CVS, CVH and CVSH solve of Figs 3–5 (column-dual Newton solver) met its stopping rule: "
        f"column residual below {RESIDUAL_TOLERANCE:.0e}, inner residual below {INNER_TOLERANCE:.0e}", "ours", "–",
        f"{converged}/{solves} solves (trial, method and run) converged; largest residual {residual_text([residual])}, "
        f"inner {residual_text([inner])}",
        verdicts.AGREES if holds else verdicts.DIFFERS,
        "a count (no sampling error): every solve converged and the largest residuals are below the tolerances"))


def run_times(report, root, runs):
    """Wall time of the three figure runs (meta.json) and Algorithm 2's share of their trial times."""
    walls = [data.read_meta(root, f"{FOLDER}/{name}").get("wall_seconds") for name, _ in FIGURES]
    report.value("figures.wall", markdown.duration(sum(walls)) if None not in walls else "–")
    seconds = {algorithm2: 0.0 for algorithm2 in (True, False)}
    for by_algorithm in runs.values():
        for algorithm, group in by_algorithm.items():
            seconds[algorithm in RUN_BY_ALGORITHM2] += math.fsum(column(group, "time_us"))
    total = seconds[True] + seconds[False]
    report.value("figures.algorithm2_share", markdown.percent(seconds[True] / total, 0) if total else "–")


def cost_rows(root, folder):
    """{Newton, Algorithm 2: the trials.csv row} of a cost run, None when it is not committed, or
    the text saying why it did not complete."""
    if not os.path.exists(data.path(root, folder, "trials.csv")):
        return None
    if data.read_meta(root, folder).get("status") != "complete":
        return "the run is not complete"
    by_algorithm = read_trials(root, folder)
    runs = {}
    for algorithm in (NEWTON, ALGORITHM2):
        rows = by_algorithm.get(algorithm, [])
        if len(rows) != 1:
            raise data.DataError(f"{folder}/trials.csv: {len(rows)} rows of {algorithm}, expected one")
        runs[algorithm] = rows[0]
    if any(r["status"] != "ok" for r in runs.values()):
        return "the run did not complete: " + ", ".join(
            f"{label(a) if a == NEWTON else 'Algorithm 2'} {r['status']}" for a, r in runs.items())
    return runs


def solver_cost_table(root, folder, runs):
    """Times, iterations and convergence of both solvers, and the largest difference of their HPD
    values and entropies over the trial's targets."""
    points = read_targets(root, folder)
    t = next(iter(points.values()))
    n, a = t.methods.index(NEWTON), t.methods.index(ALGORITHM2)
    newton, pdca = runs[NEWTON], runs[ALGORITHM2]
    newton_s, pdca_s = data.num(newton, "time_us") / 1e6, data.num(pdca, "time_us") / 1e6
    particles = int(data.num(t.params, "particles"))
    return markdown.table(
        ["solver of CVS(0.95)", "particles", "targets", "time", "iterations", "converged"],
        [["column-dual Newton", particles, int(data.num(newton, "n_targets")), markdown.duration(newton_s),
          f"{data.num(newton, 'iterations'):.0f} Newton steps", "yes" if data.num(newton, "converged") == 1 else "no"],
         ["Algorithm 2 (`solver=pdca`)", particles, int(data.num(pdca, "n_targets")), markdown.duration(pdca_s),
          f"{data.num(pdca, 'iterations'):.0f} sweeps",
          "yes" if data.num(pdca, "converged") == 1 else "no (a solve reached the sweep cap)"]],
        "lrrrrl") + "\n\n" + (
        f"Algorithm 2 took {markdown.sig(pdca_s / newton_s)} times as long as the Newton solver; the largest "
        f"difference of their HPD values over the trial's targets is {np.max(np.abs(t.hpd[:, a] - t.hpd[:, n])):.1e}, "
        f"of their entropies {np.max(np.abs(t.entropy[:, a] - t.entropy[:, n])):.1e} nats.")


def algorithm2_cost(report, root):
    """The cost of Algorithm 2 against the Newton solver on one trial at the study's 10 000
    particles (experiments/multiscan/algorithm2-cost.ini) when recorded; otherwise the same trial
    at 1000 particles (multiscan/algorithm2-cost-1000.ini) and the estimate at 10 000 it gives."""
    full = cost_rows(root, COST_RUN)
    if isinstance(full, dict):
        report.value("algorithm2.cost", solver_cost_table(root, COST_RUN, full))
        return
    text = (f"The 10 000-particle run (`{COST_RUN}`) is not recorded: it takes hours. "
            if full is None else f"The 10 000-particle run (`{COST_RUN}`): {full}. ")
    small = cost_rows(root, COST_RUN_1000)
    if not isinstance(small, dict):
        report.value("algorithm2.cost", text + (f"`{COST_RUN_1000}`: {small}." if small else
                                                f"Nor is the 1000-particle run (`{COST_RUN_1000}`)."))
        return
    pdca_s = data.num(small[ALGORITHM2], "time_us") / 1e6
    report.value("algorithm2.cost", text + f"The same trial at 1000 particles (`{COST_RUN_1000}`):\n\n"
                 + solver_cost_table(root, COST_RUN_1000, small) + "\n\n" +
                 f"Estimate (not a measurement) at 10 000 particles: about {markdown.duration(10 * pdca_s)} for "
                 "Algorithm 2, ten times the 1000-particle time, if a sweep's cost grows linearly with the "
                 "particles and the number of sweeps stays the same.")
