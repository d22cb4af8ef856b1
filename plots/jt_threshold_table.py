#!/usr/bin/python3
"""Which quantity does Williams & Lau 2014 threshold before its junction tree? A Markdown table
from the summary.csv of experiments/bp_paper/jt-threshold-reading.ini: for each reading of the threshold
(jt's threshold_on) and each τ, how JT's average max error compares with BP's over the sweep
points, next to the paper's three statements (Sec. V-B):
  τ = 0.1 "globally worse than BP, often much worse";
  τ = 0.01 and 0.001 "generally much better than BP".

Usage: /usr/bin/python3 -m plots.jt_threshold_table RUN_DIR/summary.csv

experiments/bp_paper/__init__.py computes the same table with errors(), readings() and compare().
"""

import csv
import re
import sys

READINGS = {"0": "ψ (eq 11)", "1": "g = ψ λ_fa (1−Pd)/Pd", "2": "ψ/(1+Σψ)", "3": "(1−Pd) ψ"}
SPEC = re.compile(r"^jt:threshold=([0-9.e+-]+),threshold_on=([0-3])$")
HARD = 1e-3  # "where BP's error ≥ 1e-3": the points where BP's error is large enough to be beaten by 3×


def errors(rows):
    """{(point parameters, algorithm): max_error_mean} of the summary rows that have one."""
    params = list(rows[0].keys())[1:list(rows[0].keys()).index("algorithm")]
    return {(tuple(r[p] for p in params), r["algorithm"]): float(r["max_error_mean"])
            for r in rows if r["max_error_mean"]}


def readings(error):
    """[(threshold_on, τ, SPEC)] of the jt variants present, by reading then decreasing τ."""
    found = {}
    for _, a in error:
        m = SPEC.match(a)
        if m:
            found.setdefault((m.group(2), float(m.group(1))), a)
    return [(on, tau, found[(on, tau)]) for on, tau in sorted(found, key=lambda v: (v[0], -v[1]))]


def compare(error, spec):
    """JT `spec` against BP over BP's points: a dict of counts (done, worse, worse3 over the points
    JT completed; better3 over the points where BP's error is at least HARD) and JT's mean error."""
    points = sorted({k for k, a in error if a == "bp"})
    hard = [p for p in points if error[(p, "bp")] >= HARD]
    jt = {p: error.get((p, spec)) for p in points}
    done = [p for p in points if jt[p] is not None]
    return {"points": len(points), "hard": len(hard), "done": len(done),
            "worse": sum(jt[p] > error[(p, "bp")] for p in done),
            "worse3": sum(jt[p] >= 3 * error[(p, "bp")] for p in done),
            "better3": sum(jt[p] is not None and jt[p] <= error[(p, "bp")] / 3 for p in hard),
            "mean": sum(jt[p] for p in done) / len(done) if done else float("nan")}


def main():
    if len(sys.argv) != 2:
        sys.exit(next(line for line in __doc__.splitlines() if line.startswith("Usage")))
    path = sys.argv[1]
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as e:
        sys.exit(f"jt_threshold_table.py: cannot read {path}: {e.strerror}")
    if not rows or "algorithm" not in rows[0] or "max_error_mean" not in rows[0]:
        sys.exit(f"jt_threshold_table.py: {path}: not a summary.csv with algorithm and max_error_mean")
    error = errors(rows)
    points = sorted({k for k, a in error if a == "bp"})
    if not points:
        sys.exit(f"jt_threshold_table.py: {path}: no bp rows")
    hard = [p for p in points if error[(p, "bp")] >= HARD]
    print(f"{len(points)} points; BP's mean error {sum(error[(p, 'bp')] for p in points) / len(points):.4f}; "
          f"{len(hard)} points where BP's error ≥ 1e-3\n")
    print("| threshold on | τ | JT worse than BP | ≥ 3× worse | ≤ BP/3 where BP ≥ 1e-3 | mean error |")
    print("|---|---|---|---|---|---|")
    for on, tau, spec in readings(error):
        c = compare(error, spec)
        print(f"| {READINGS[on]} | {tau:g} | {c['worse']}/{c['done']} | {c['worse3']}/{c['done']} | "
              f"{c['better3']}/{c['hard']} | {c['mean']:.4f} |")


if __name__ == "__main__":
    main()
