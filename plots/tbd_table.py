#!/usr/bin/python3
"""The track-before-detect comparison as Markdown tables (results/tbd/REPORT.md).

Usage:
  /usr/bin/python3 -m plots.tbd_table RUN_DIR [--point P]

RUN_DIR is the output folder of `dabench run` on a track-before-detect experiment (e.g.
experiments/tbd/gospa.ini). Prints, for sweep point P (default 0):
  1. per tracker: runs, the averaged GOSPA (p = 1) over k as its mean over k with +-2 standard
     errors (over runs, of each run's mean over k), the same for GOSPA with p = 2, its
     localisation / missed / false parts (mean per step), mean estimates per step and the mean
     runtime per step;
  2. per pair of trackers (A, B), in the experiment's order: at how many steps k A's averaged
     GOSPA is below B's, and the paired difference of the runs' mean GOSPA (A - B) with +-2
     standard errors (the trackers ran on identical frames).
Exit status 2 with a one-line message when the input cannot be read.
"""

import argparse
import csv
import math
import os
import sys
from collections import defaultdict

SCRIPT = "tbd_table.py"


def fail(message):
    print(f"{SCRIPT}: {message}", file=sys.stderr)
    sys.exit(2)


def rows(path):
    if not os.path.exists(path):
        fail(f"no {path}")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def mean_se(values):
    n = len(values)
    m = sum(values) / n
    se = math.sqrt(sum((v - m) ** 2 for v in values) / max(1, n - 1) / n) if n > 1 else float("nan")
    return m, se


def label(spec):
    name, _, options = spec.partition(":")
    return name.upper() + (f" [{options}]" if options else "")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("run_dir")
    parser.add_argument("--point", default="0")
    args = parser.parse_args()
    steps = [r for r in rows(os.path.join(args.run_dir, "steps.csv")) if r["point"] == args.point]
    trials = [r for r in rows(os.path.join(args.run_dir, "trials.csv"))
              if r["point"] == args.point and r["status"] == "ok"]
    if not steps or not trials:
        fail(f"no rows of point {args.point} in {args.run_dir}")
    columns = ["gospa", "gospa_p2", "localisation", "missed", "false", "n_estimates"]
    # per tracker: per trial: per column: values over k; and per k: gospa values over trials
    per_trial = defaultdict(lambda: defaultdict(lambda: defaultdict(list)))
    per_k = defaultdict(lambda: defaultdict(list))
    for r in steps:
        if r["gospa"] == "":
            continue
        for c in columns:
            per_trial[r["algorithm"]][r["trial"]][c].append(float(r[c]))
        per_k[r["algorithm"]][int(r["k"])].append(float(r["gospa"]))
    step_time = defaultdict(list)
    for r in trials:
        step_time[r["algorithm"]].append(float(r["step_time_us"]))
    trackers = list(per_trial)

    print("| tracker | runs | GOSPA p = 1 (mean over k) | GOSPA p = 2 | localisation | missed | false "
          "| estimates per step | runtime per step |")
    print("|---|---|---|---|---|---|---|---|---|")
    run_means = {}
    for spec in trackers:
        by_trial = per_trial[spec]
        summary = {}
        for c in columns:
            summary[c] = mean_se([sum(v[c]) / len(v[c]) for v in by_trial.values()])
        run_means[spec] = {t: sum(v["gospa"]) / len(v["gospa"]) for t, v in by_trial.items()}
        time_ms = sum(step_time[spec]) / len(step_time[spec]) / 1e3 if step_time[spec] else float("nan")
        cells = [f"{summary[c][0]:.3f} ± {2 * summary[c][1]:.3f}" for c in ("gospa", "gospa_p2")]
        cells += [f"{summary[c][0]:.3f}" for c in ("localisation", "missed", "false", "n_estimates")]
        print(f"| {label(spec)} | {len(by_trial)} | " + " | ".join(cells) + f" | {time_ms:.1f} ms |")
    print()
    print("| A | B | steps k with A's averaged GOSPA below B's | mean over runs of A − B (±2 SE) |")
    print("|---|---|---|---|")
    for i, a in enumerate(trackers):
        for b in trackers[i + 1:]:
            ks = sorted(set(per_k[a]) & set(per_k[b]))
            below = sum(1 for k in ks if sum(per_k[a][k]) / len(per_k[a][k]) < sum(per_k[b][k]) / len(per_k[b][k]))
            common = sorted(set(run_means[a]) & set(run_means[b]))
            diff = mean_se([run_means[a][t] - run_means[b][t] for t in common])
            print(f"| {label(a)} | {label(b)} | {below} of {len(ks)} | {diff[0]:+.3f} ± {2 * diff[1]:.3f} |")


if __name__ == "__main__":
    main()
