#!/usr/bin/python3
"""Figs 3-5 of Williams & Lau, "Multiple scan data association by convex variational inference":
CDFs over targets of the HPD value of the true location (top, with the x = y line of a
calibrated belief) and of the belief's entropy (bottom), one line per algorithm.

Usage:
  /usr/bin/python3 -m plots.multiscan_cdf RUN_DIR/targets.csv [--out RUN_DIR/multiscan_cdf.png]
                   [--title TEXT]

Reads targets.csv (one row per point, trial, algorithm and target, written by `dabench run` for
multi-scan experiments). Several sweep points give one column of panels each. Also prints, per
point and algorithm: targets, the Kolmogorov-Smirnov distance D of the HPD values from
Uniform(0, 1) (5 % critical value 1.358/sqrt(n)), the 80th percentile of HPD (the paper's "20 %
of targets are at a true location less likely than X of the belief"), the fraction with
HPD >= 0.9999, and the median entropy. Writes a PNG (200 dpi) and an SVG; exit status 2 with a
one-line message when the input cannot be plotted.
"""

import argparse
import csv
import math
import os
import sys

sys.dont_write_bytecode = True
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

FIXED = {"point", "trial", "seed", "algorithm", "target", "hpd", "entropy"}


def fail(message):
    print(f"multiscan_cdf.py: {message}", file=sys.stderr)
    sys.exit(2)


def ks_uniform(values):
    u = np.sort(np.clip(values, 0.0, 1.0))
    n = len(u)
    k = np.arange(1, n + 1)
    return float(max(np.max(k / n - u), np.max(u - (k - 1) / n)))


def read(path):
    try:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
    except OSError as error:
        fail(f"{path}: {error.strerror}")
    if not rows:
        fail(f"{path}: no target rows")
    for column in ("point", "algorithm", "hpd", "entropy"):
        if column not in rows[0]:
            fail(f"{path}: no column '{column}' (is this a multi-scan targets.csv?)")
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("targets")
    parser.add_argument("--out")
    parser.add_argument("--title")
    args = parser.parse_args()
    rows = read(args.targets)
    params = [c for c in rows[0] if c not in FIXED]
    points, algorithms, values = [], [], {}
    for r in rows:
        point, algorithm = r["point"], r["algorithm"]
        if point not in points:
            points.append(point)
        if algorithm not in algorithms:
            algorithms.append(algorithm)
        cell = values.setdefault((point, algorithm), ([], []))
        if r["hpd"] != "" and r["entropy"] != "":
            cell[0].append(float(r["hpd"]))
            cell[1].append(float(r["entropy"]))
    first_row = {p: next(r for r in rows if r["point"] == p) for p in points}
    varying = [c for c in params if len({first_row[p][c] for p in points}) > 1]

    print("point,algorithm,targets,ks_d,ks_critical_5pct,hpd_p80,frac_hpd_ge_0.9999,entropy_median")
    fig, axes = plt.subplots(2, len(points), figsize=(5.2 * len(points), 7.5), squeeze=False)
    for c, point in enumerate(points):
        top, bottom = axes[0][c], axes[1][c]
        for algorithm in algorithms:
            hpd, entropy = (np.array(v) for v in values.get((point, algorithm), ([], [])))
            if len(hpd) == 0:
                continue
            steps = np.arange(1, len(hpd) + 1) / len(hpd)
            top.step(np.sort(hpd), steps, where="post", label=algorithm)
            bottom.step(np.sort(entropy), steps, where="post", label=algorithm)
            print(f"{point},{algorithm},{len(hpd)},{ks_uniform(hpd):.4f},{1.358 / math.sqrt(len(hpd)):.4f},"
                  f"{np.percentile(hpd, 80):.4f},{np.mean(hpd >= 0.9999):.4f},{np.median(entropy):.4f}")
        top.plot([0, 1], [0, 1], "k:", linewidth=1, label="x = y (calibrated)")
        top.set_xlim(0, 1)
        top.set_ylim(0, 1)
        top.set_xlabel("HPD value of true location")
        top.set_ylabel("CDF")
        bottom.set_xlabel("entropy of belief (nats, differential, log area units)")
        bottom.set_ylabel("CDF")
        if varying:
            top.set_title(", ".join(f"{k}={first_row[point][k]}" for k in varying))
        top.grid(alpha=0.3)
        bottom.grid(alpha=0.3)
    axes[0][0].legend(fontsize=8, loc="upper left")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.targets)), "multiscan_cdf.png")
    fig.savefig(out, dpi=200)
    svg = os.path.splitext(out)[0] + ".svg"
    fig.savefig(svg)
    print(out, file=sys.stderr)
    print(svg, file=sys.stderr)


if __name__ == "__main__":
    main()
