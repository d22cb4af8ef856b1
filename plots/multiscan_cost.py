#!/usr/bin/python3
"""Cost and convergence of the multiple-scan methods in a run (multiscan-convex-variational):
a Markdown table with, per sweep point and algorithm, the trials solved, the median and mean
time per trial (time_us), the mean iterations (Newton or L-BFGS steps of the column-dual solver,
sweeps of Algorithm 2, BP iterations of JPDA-BP), the mean line-search steps, how many trials met
the stopping rule, and the largest final column residual and inner residual (column-dual solver).

Usage:
  /usr/bin/python3 -m plots.multiscan_cost RUN_DIR/trials.csv [--out table.md]

Exit status 2 with a one-line message when the input cannot be used.
"""

import argparse
import csv
import statistics
import sys


def fail(message):
    print(f"multiscan_cost.py: {message}", file=sys.stderr)
    sys.exit(2)


def number(text):
    return float(text) if text not in ("", None) else None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("trials")
    parser.add_argument("--out")
    args = parser.parse_args()
    try:
        with open(args.trials, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as error:
        fail(f"{args.trials}: {error.strerror}")
    if not rows:
        fail(f"{args.trials}: no rows")
    for column in ("point", "algorithm", "status", "time_us", "iterations", "converged", "residual"):
        if column not in rows[0]:
            fail(f"{args.trials}: no column '{column}' (is this a multi-scan trials.csv?)")
    groups = {}
    for r in rows:
        groups.setdefault((r["point"], r["algorithm"]), []).append(r)
    lines = ["| point | algorithm | solved | median time (s) | mean time (s) | mean iterations | mean line-search steps "
             "| converged | largest residual | largest inner residual |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for (point, algorithm), group in groups.items():
        ok = [r for r in group if r["status"] == "ok"]
        times = [number(r["time_us"]) / 1e6 for r in ok if number(r["time_us"]) is not None]
        iterations = [number(r["iterations"]) for r in ok if number(r["iterations"]) is not None]
        searches = [number(r["line_search_steps"]) for r in ok if number(r.get("line_search_steps")) is not None]
        residuals = [number(r["residual"]) for r in ok if number(r["residual"]) is not None]
        inner = [number(r["inner_residual"]) for r in ok if number(r.get("inner_residual")) is not None]
        converged = sum(1 for r in ok if r["converged"] == "1")
        cell = lambda values, form: form.format(values) if values is not None else "–"  # noqa: E731
        lines.append("| {} | {} | {}/{} | {} | {} | {} | {} | {}/{} | {} | {} |".format(
            point, algorithm, len(ok), len(group),
            cell(statistics.median(times) if times else None, "{:.3g}"),
            cell(statistics.mean(times) if times else None, "{:.3g}"),
            cell(statistics.mean(iterations) if iterations else None, "{:.1f}"),
            cell(statistics.mean(searches) if searches else None, "{:.1f}"),
            converged, len(ok),
            cell(max(residuals) if residuals else None, "{:.1e}"),
            cell(max(inner) if inner else None, "{:.1e}")))
    text = "\n".join(lines) + "\n"
    if args.out:
        with open(args.out, "w") as f:
            f.write(text)
    else:
        sys.stdout.write(text)


if __name__ == "__main__":
    main()
