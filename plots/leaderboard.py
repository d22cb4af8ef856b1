#!/usr/bin/python3
"""The single-scan leaderboard figure: error against time, one panel per scenario panel.

Usage:
  /usr/bin/python3 -m plots.leaderboard PANELS.csv [PANELS.csv ...] --out FIG.png

Reads the panels.csv digests that experiments/leaderboard/__init__.py writes (per panel and
algorithm: the mean of max_error over the panel's trials and the quartiles of max_error and
time_us). Each algorithm is one marker at (median time per trial, mean max error), with bars from
the 25th to the 75th percentile of each over the same trials; the grey staircase is the Pareto
front of the algorithms that completed every trial (no other is both faster and more accurate).
An algorithm that skipped trials is drawn hollow: its mean covers only the trials it completed.
The run's reference (a star; its error is zero by definition) is not on the front.
Writes a PNG and an SVG."""

import argparse
import csv
import math
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from plots import fig6

plt = fig6.plt

# family (spec name) -> colour; variants of a family differ by marker.
COLOURS = {"bp": "tab:blue", "fbp": "tab:cyan", "lmipda": "tab:purple", "baa": "tab:olive", "cheap-jpda": "tab:orange",
           "modified-cheap-jpda": "tab:brown", "map": "tab:pink", "mcmcda": "tab:green", "cd": "tab:red",
           "jt": "black", "kbest-jpda": "tab:gray", "ehm": "gold", "permanent": "darkgoldenrod"}
MARKERS = ["o", "s", "^", "D", "v", "P"]
ERROR_FLOOR = 1e-9  # errors below (exact methods' rounding, a zero quartile) are drawn at this floor


def read_panels(paths):
    """[(panel, [rows])] in file and first-appearance order."""
    panels = {}
    for p in paths:
        try:
            with open(p, newline="", encoding="utf-8") as f:
                for r in csv.DictReader(f):
                    panels.setdefault(r["panel"], []).append(r)
        except OSError as error:
            fig6.fail(f"{p}: {error.strerror}")
        except KeyError:
            fig6.fail(f"{p}: no 'panel' column (is it a leaderboard panels.csv?)")
    return list(panels.items())


def value(row, column):
    text = row.get(column, "")
    return float(text) if text not in ("", None) else math.nan


def pareto_front(points):
    """The points (x, y, ...) no other point beats on both x and y, by increasing x."""
    front, best = [], math.inf
    for p in sorted(points, key=lambda p: (p[0], p[1])):
        if p[1] < best:
            front.append(p)
            best = p[1]
    return front


def style_of(algorithms):
    styles, seen = {}, {}
    for spec in algorithms:
        name = spec.split(":", 1)[0]
        k = seen.get(name, 0)
        seen[name] = k + 1
        styles[spec] = (COLOURS.get(name, "tab:gray"), MARKERS[k % len(MARKERS)])
    return styles


def draw_panel(ax, title, rows, styles):
    points = []
    for r in rows:
        spec = r["algorithm"]
        x, y = value(r, "time_us_median"), value(r, "max_error_mean")
        if not (math.isfinite(x) and math.isfinite(y)):
            continue
        complete = int(r["ok"]) == int(r["trials"])
        reference = r.get("role") == "reference"
        colour, marker = styles[spec]
        marker = "*" if reference else marker
        shown = max(y, ERROR_FLOOR)
        xerr = [[x - value(r, "time_us_p25")], [value(r, "time_us_p75") - x]]
        lo, hi = max(value(r, "max_error_p25"), ERROR_FLOOR), max(value(r, "max_error_p75"), ERROR_FLOOR)
        yerr = [[max(shown - lo, 0.0)], [max(hi - shown, 0.0)]]
        ax.errorbar([x], [shown], xerr=xerr, yerr=yerr, color=colour, marker=marker, ms=6, lw=0.8,
                    mfc=colour if complete else "white", mec=colour, capsize=0, ls="none", zorder=3)
        if complete and not reference:
            points.append((x, shown, spec))
    front = pareto_front(points)
    if front:
        xs = [p[0] for p in front]
        ys = [p[1] for p in front]
        ax.step(xs + [xs[-1] * 3], ys + [ys[-1]], where="post", color="0.6", lw=1.2, zorder=1)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="major", lw=0.3, alpha=0.6)
    ax.tick_params(labelsize=7)
    return [p[2] for p in front]


def main(argv=None):
    ap = argparse.ArgumentParser(prog=fig6.PROG, description=__doc__.splitlines()[0])
    ap.add_argument("panels", nargs="+", help="panels.csv digests (python3 -m reports.digest leaderboard)")
    ap.add_argument("--out", required=True, help="output PNG (an SVG is written next to it)")
    args = ap.parse_args(argv)
    panels = read_panels(args.panels)
    if not panels:
        fig6.fail("no panels in the given files")
    algorithms = []
    for _, rows in panels:
        for r in rows:
            if r["algorithm"] not in algorithms:
                algorithms.append(r["algorithm"])
    styles = style_of(algorithms)
    cols = 4
    nrows = (len(panels) + cols - 1) // cols
    fig, axes = plt.subplots(nrows, cols, figsize=(3.4 * cols, 3.0 * nrows + 1.2), squeeze=False)
    for k, (title, rows) in enumerate(panels):
        ax = axes[k // cols][k % cols]
        draw_panel(ax, title, rows, styles)
        if k % cols == 0:
            ax.set_ylabel(f"mean max error (log; floor {ERROR_FLOOR:g})", fontsize=8)
        if k // cols == nrows - 1:
            ax.set_xlabel("median time per trial, µs (log)", fontsize=8)
    for k in range(len(panels), nrows * cols):
        axes[k // cols][k % cols].axis("off")
    roles = []  # (spec, is the reference) in order of appearance: a spec can be both, in different runs
    for _, rows in panels:
        for r in rows:
            key = (r["algorithm"], r.get("role") == "reference")
            if key not in roles:
                roles.append(key)
    handles = [plt.Line2D([], [], color=styles[s][0], marker="*" if ref else styles[s][1], ls="none",
                          label=s + (" (reference)" if ref else "")) for s, ref in roles]
    handles.append(plt.Line2D([], [], color="0.6", lw=1.2, label="Pareto front (complete runs)"))
    fig.legend(handles=handles, loc="lower center", ncol=6, fontsize=7, frameon=False, bbox_to_anchor=(0.5, 0.0))
    fig.tight_layout(rect=(0, 0.1 if nrows > 1 else 0.18, 1, 1))
    for written in fig6.save_both(fig, args.out):
        print(written)
    return 0


if __name__ == "__main__":
    sys.exit(main())
