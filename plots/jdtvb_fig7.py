#!/usr/bin/python3
"""Fig. 7 of JDT-VB (jdt-vb-multipath-othr, Sec. IV-B3): tracking metrics versus VB iteration.

Usage:
  /usr/bin/python3 -m plots.jdtvb_fig7 RUN_DIR/iterations.csv [--algorithm jdt-vb]
                   [--metrics nvt,tpd,...] [--bands] [--out RUN_DIR/jdtvb_fig7.png] [--title TEXT]

Reads iterations.csv, written by `dabench run` for a tracking experiment with
`iterations = true` (e.g. experiments/jdtvb/fig7.ini): one row per (sweep point, run,
tracker, iteration r), r = 0 being the tracks before the first iteration. Draws one panel per
metric (default NVT, TPD, NFT, TTL, AEE-R, AEE-B, MOSPA) against r = 0..R, R the largest
iteration any run reached, with one line per setting (sweep point: pd and N_c, and any other
parameter that varies) and tracker, the mean over that setting's runs; a last panel shows the
share of runs that reached r (ran at least r iterations).

Carry-forward rule: a run that stopped at r_c < R (its free energy converged) contributes its
final metrics, those of r_c, at every r > r_c: its tracks no longer change. A metric left
empty in a run (TTL and AEE need a followed target) is skipped in the mean at that r, as
summary.csv does. --bands shades +-1 standard error. Prints the mean metrics at r = 0 and r = R
per line to stdout; writes a PNG (200 dpi) and an SVG with the same stem and prints their paths
on stderr; exit status 2 with a one-line message when the input cannot be plotted.
"""

import argparse
import csv
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCRIPT = "jdtvb_fig7.py"
# (iterations.csv column, panel title); TTL in scans, AEE-R and MOSPA in km, AEE-B in mrad.
METRICS = {"nvt": "NVT", "tpd": "TPD", "nft": "NFT", "false_tracks": "false tracks", "ghost_tracks": "ghost tracks",
           "broken_targets": "broken targets", "ttl_scans": "TTL (scans)", "aee_range_km": "AEE-R (km)",
           "aee_bearing_mrad": "AEE-B (mrad)", "mospa_km": "MOSPA (km)"}
DEFAULT_METRICS = ["nvt", "tpd", "nft", "ttl_scans", "aee_range_km", "aee_bearing_mrad", "mospa_km"]
NAMES = {"pd": "$p_d$", "clutter": "$N_c$"}


class PlotError(Exception):
    """Input that cannot be plotted: printed on one line, exit status 2."""


def fail(message):
    print(f"{SCRIPT}: {message}", file=sys.stderr)
    sys.exit(2)


def number(text):
    return float(text) if text not in ("", None) else math.nan


def read_runs(path, algorithm, metrics):
    """{(point, algorithm): {"params": {...}, "runs": {trial: [row metrics by r]}}} in file order,
    and the names of the parameters that vary between points."""
    if not os.path.exists(path):
        raise PlotError(f"{path}: missing (run an experiment with 'iterations = true', e.g. "
                        "experiments/jdtvb/fig7.ini)")
    lines = {}
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            for column in ["point", "trial", "algorithm", "iteration"] + metrics:
                if column not in header:
                    raise PlotError(f"{path}: no column '{column}' (is it an iterations.csv of `dabench run`?)")
            param_names = header[1:header.index("trial")]
            for line_number, r in enumerate(reader, start=2):
                if algorithm is not None and r["algorithm"] != algorithm:
                    continue
                line = lines.setdefault((r["point"], r["algorithm"]),
                                        {"params": {k: r[k] for k in param_names}, "runs": {}})
                history = line["runs"].setdefault(r["trial"], [])
                try:
                    iteration = int(r["iteration"])
                    values = [number(r[m]) for m in metrics]
                except ValueError:
                    raise PlotError(f"{path}:{line_number}: not a number")
                if iteration != len(history):
                    raise PlotError(f"{path}:{line_number}: iteration {iteration} of point {r['point']}, "
                                    f"trial {r['trial']}, {r['algorithm']} follows {len(history) - 1} "
                                    "(expected 0, 1, ... in order)")
                history.append(values)
    except OSError as error:
        raise PlotError(f"{path}: {error.strerror}")
    except csv.Error as error:
        raise PlotError(f"{path}: {error}")
    if not lines:
        raise PlotError(f"{path}: no rows" + (f" for algorithm '{algorithm}'" if algorithm else ""))
    varying = [k for k in param_names if len({line["params"][k] for line in lines.values()}) > 1]
    return lines, varying


def carried_forward(runs, last):
    """Per r = 0..last, per metric: the mean and standard error over runs, each run holding its
    final values after it stopped (NaN values skipped); and the share of runs that reached r."""
    histories = list(runs.values())
    metric_count = len(histories[0][0])
    means, ses, reached = [], [], []
    for r in range(last + 1):
        values = [h[min(r, len(h) - 1)] for h in histories]
        reached.append(sum(len(h) > r for h in histories) / len(histories))
        mean_r, se_r = [], []
        for m in range(metric_count):
            column = [v[m] for v in values if math.isfinite(v[m])]
            mean = sum(column) / len(column) if column else math.nan
            var = sum((x - mean) ** 2 for x in column) / (len(column) - 1) if len(column) > 1 else math.nan
            mean_r.append(mean)
            se_r.append(math.sqrt(var / len(column)) if len(column) > 1 else math.nan)
        means.append(mean_r)
        ses.append(se_r)
    return means, ses, reached


def label(params, varying, algorithm, several_algorithms):
    parts = [f"{NAMES.get(k, k)} = {params[k]}" for k in varying]
    if several_algorithms:
        parts.append(algorithm)
    return ", ".join(parts) or algorithm


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("iterations_csv")
    parser.add_argument("--algorithm", help="only this tracker SPEC (default: every tracker in the file)")
    parser.add_argument("--metrics", help=f"comma list of columns (default {','.join(DEFAULT_METRICS)})")
    parser.add_argument("--bands", action="store_true", help="shade +-1 standard error")
    parser.add_argument("--out")
    parser.add_argument("--title")
    args = parser.parse_args()
    metrics = [m.strip() for m in args.metrics.split(",")] if args.metrics else DEFAULT_METRICS
    for m in metrics:
        if m not in METRICS:
            fail(f"--metrics: unknown metric '{m}' (known: {', '.join(METRICS)})")
    try:
        lines, varying = read_runs(args.iterations_csv, args.algorithm, metrics)
    except PlotError as error:
        fail(error)

    meta = os.path.join(os.path.dirname(os.path.abspath(args.iterations_csv)), "meta.json")
    try:
        with open(meta) as f:
            status = json.load(f).get("status")
        if status != "complete":
            print(f"{SCRIPT}: warning: {meta} says the run is '{status}': its last run's history may be cut "
                  "(finish it with --resume)", file=sys.stderr)
    except (OSError, ValueError):
        pass
    last = max(len(h) - 1 for line in lines.values() for h in line["runs"].values())
    several = len({algorithm for _, algorithm in lines}) > 1
    panels = len(metrics) + 1
    cols = min(4, panels)
    rows = (panels + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 3.0 * rows), squeeze=False)
    flat = [a for row in axes for a in row]
    x = list(range(last + 1))
    print(f"mean over runs; runs that stopped carry their final metrics forward (R = {last})")
    print("setting | runs | mean stop r | " + " | ".join(f"{METRICS[m]} r=0 -> r={last}" for m in metrics))
    for (point, algorithm), line in lines.items():
        means, ses, reached = carried_forward(line["runs"], last)
        text = label(line["params"], varying, algorithm, several)
        stops = [len(h) - 1 for h in line["runs"].values()]
        for m, axis in enumerate(flat[:len(metrics)]):
            y = [means[r][m] for r in x]
            drawn, = axis.plot(x, y, "o-", markersize=2.5, linewidth=1.3, label=text)
            if args.bands:
                low = [means[r][m] - ses[r][m] for r in x]
                high = [means[r][m] + ses[r][m] for r in x]
                axis.fill_between(x, low, high, color=drawn.get_color(), alpha=0.15, linewidth=0)
        flat[len(metrics)].plot(x, reached, "o-", markersize=2.5, linewidth=1.3, label=text)
        cells = " | ".join(f"{means[0][m]:.4g} -> {means[last][m]:.4g}" for m in range(len(metrics)))
        print(f"point {point} {text.replace('$', '')} | {len(stops)} | {sum(stops) / len(stops):.2f} | {cells}")
    for m, axis in enumerate(flat[:len(metrics)]):
        axis.set_title(METRICS[metrics[m]], fontsize=10)
    flat[len(metrics)].set_title("share of runs that reached $r$", fontsize=10)
    flat[len(metrics)].set_ylim(-0.03, 1.03)
    for axis in flat[:panels]:
        axis.set_xlabel("iteration $r$")
        axis.grid(alpha=0.3)
        axis.set_xlim(-0.3, last + 0.3)
    for axis in flat[panels:]:
        axis.set_visible(False)
    handles, labels = flat[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=min(4, len(labels)), fontsize=8, frameon=False)
    runs = sorted({len(line["runs"]) for line in lines.values()})
    fig.suptitle(args.title or f"Metrics vs VB iteration (mean of {'/'.join(map(str, runs))} runs; "
                 "stopped runs carried forward)", fontsize=11)
    fig.tight_layout(rect=(0, 0.06 if len(labels) <= 4 else 0.1, 1, 1))
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.iterations_csv)), "jdtvb_fig7.png")
    try:
        fig.savefig(out, dpi=200)
        svg = os.path.splitext(out)[0] + ".svg"
        fig.savefig(svg)
    except OSError as error:
        fail(f"{out}: {error.strerror}")
    print(out, file=sys.stderr)
    print(svg, file=sys.stderr)


if __name__ == "__main__":
    main()
