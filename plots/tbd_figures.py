#!/usr/bin/python3
"""The track-before-detect figures (tbd-bp-supplement Figs 1-4; the letter's Fig. 2).

Usage:
  /usr/bin/python3 plots/tbd_figures.py toy RUN_DIR [--point P] [--out FILE]
                                                                       supplement Fig. 1
  /usr/bin/python3 plots/tbd_figures.py run RUN_DIR [--point P] [--steps 14,21,27,43] [--out FILE]
                                                                       supplement Figs 2 and 3
  /usr/bin/python3 plots/tbd_figures.py gospa RUN_DIR [--point P] [--column gospa] [--out FILE]
                                                                       the letter's Fig. 2
  /usr/bin/python3 plots/tbd_figures.py runtime RUN_DIR [--time-stat median|mean] [--out FILE]
                                                                       supplement Fig. 4

RUN_DIR is the output folder of `dabench run` on a track-before-detect experiment:
  toy      (experiments/tbd-toy-fig1a.ini or tbd-toy.ini, `beliefs = true`): at one sweep point
           (a reading), the frame's cell magnitudes |z_j| with the two objects, the prior alpha_1
           (N(p_1, 0.3 I), drawn analytically) and, per tracker, the belief of potential object 1
           (label 0) as a 2-D histogram of beliefs.csv over [3, 5]^2 as the supplement's panels,
           with its mean and the supplement's read-off peak of the matching panel (d), (e), (f).
  run      trial 0 of a point: |z_j| of frames.csv at the given steps with the true tracks and
           positions (estimates.csv, algorithm `truth`) and each tracker's estimates at that
           step; and GOSPA over k of that trial per tracker (steps.csv).
  gospa    GOSPA (or --column gospa_p2, missed, false, ...) averaged over the trials at each k,
           one line per tracker, +-1 standard error shaded (steps.csv).
  runtime  step time against the number of objects, one line per tracker (summary.csv of a
           sweep over `objects`), with a least-squares line per tracker; prints the slope (s per
           object) and intercept. By default the median over trials of each trial's mean step
           time with its 5-95 % band (robust to preemption spikes on a busy machine);
           --time-stat mean: the supplement's mean with +-2 standard errors.
Writes a PNG (200 dpi) and an SVG with the same stem (default RUN_DIR/tbd_<figure>.png) and
prints their paths on stderr; exit status 2 with a one-line message when the input cannot be
plotted.
"""

import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCRIPT = "tbd_figures.py"


def fail(message):
    print(f"{SCRIPT}: {message}", file=sys.stderr)
    sys.exit(2)


def rows(path):
    if not os.path.exists(path):
        fail(f"{path}: no such file")
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def label(spec):
    """A legend name for a tracker SPEC: tbd-bp:iterations=2 -> TBD-BP (L = 2)."""
    name, _, options = spec.partition(":")
    settings = dict(kv.split("=", 1) for kv in options.split(",") if "=" in kv)
    text = name.upper()
    if name == "tbd-bp":
        text = f"TBD-BP (L = {settings.pop('iterations', '2')})"
        if settings.pop("exact_kappa", "false") == "true":
            text += ", exact κ"
        if settings.pop("interaction", "true") == "false":
            text += ", no interaction"
    rest = ", ".join(f"{k}={v}" for k, v in settings.items())
    return text + (f" [{rest}]" if rest else "")


def save(fig, out):
    fig.savefig(out, dpi=200)
    svg = os.path.splitext(out)[0] + ".svg"
    fig.savefig(svg)
    print(f"{SCRIPT}: wrote {out} and {svg}", file=sys.stderr)


def frame_image(frames, point, k):
    cells = [r for r in frames if r["point"] == point and r["trial"] == "0" and r["k"] == str(k)]
    if not cells:
        fail(f"frames.csv has no cells of point {point}, trial 0, step {k}")
    columns = 1 + max(int(r["column"]) for r in cells)
    rows_ = 1 + max(int(r["row"]) for r in cells)
    image = [[0.0] * columns for _ in range(rows_)]
    for r in cells:
        image[int(r["row"])][int(r["column"])] = math.hypot(float(r["z1"]), float(r["z2"]))
    return image, columns, rows_


# The supplement's Fig. 1 (d), (e), (f): where PO 1's belief peaks, read off the panels (m);
# reports/studies/tbd_toy.py holds the same readings for the REPORT's verdicts.
FIG1_PEAKS = {"d": (4.47, 4.31), "e": (4.14, 4.13), "f": (4.25, 4.12)}


def fig1_panel(spec):
    """The supplement's panel a toy tracker corresponds to: (d) TBD-MB and the non-interacting
    update, (e) κ̃, (f) exact κ."""
    if spec.startswith("tbd-mb") or "interaction=false" in spec:
        return "d"
    return "f" if "exact_kappa=true" in spec else "e"


def figure_toy(run, point, out):
    frames = rows(os.path.join(run, "frames.csv"))
    estimates = rows(os.path.join(run, "estimates.csv"))
    beliefs = [r for r in rows(os.path.join(run, "beliefs.csv")) if r["point"] == point]
    image, columns, rows_ = frame_image(frames, point, 1)
    truth = [(float(r["x"]), float(r["y"])) for r in estimates if r["algorithm"] == "truth" and r["point"] == point]
    trackers = list(dict.fromkeys(r["algorithm"] for r in beliefs))
    if len(truth) < 1 or not trackers:
        fail(f"toy: point {point} needs the truth in estimates.csv and the trackers' beliefs in beliefs.csv (beliefs = true)")
    reading = beliefs[0].get("signal", "")
    panels = 2 + len(trackers)
    fig, axes = plt.subplots(1, panels, figsize=(3.3 * panels, 3.6), constrained_layout=True)
    fig.suptitle(f"{os.path.basename(os.path.normpath(run))}, point {point}" + (f": reading {reading.upper()}" if reading else ""))
    ax = axes[0]
    shown = ax.imshow(image, origin="lower", extent=(0, columns, 0, rows_), cmap="viridis")
    ax.plot(*zip(*truth), "r.", markersize=6)
    ax.set_title("(a) |z_j| and the objects")
    fig.colorbar(shown, ax=ax, shrink=0.8)
    # alpha_1: N(p_1, 0.3 I) on a fine grid around object 1.
    p1 = truth[0]
    lo_x, hi_x, lo_y, hi_y = p1[0] - 1.0, p1[0] + 1.0, p1[1] - 1.0, p1[1] + 1.0  # the supplement's [3, 5]^2
    n = 120
    grid = [[math.exp(-((lo_x + (i + 0.5) * (hi_x - lo_x) / n - p1[0]) ** 2 +
                        (lo_y + (j + 0.5) * (hi_y - lo_y) / n - p1[1]) ** 2) / (2 * 0.3))
             for i in range(n)] for j in range(n)]
    axes[1].imshow(grid, origin="lower", extent=(lo_x, hi_x, lo_y, hi_y), cmap="jet")
    axes[1].set_title("(c) α₁(x, 1)")
    for index, spec in enumerate(trackers):
        ax = axes[2 + index]
        samples = [r for r in beliefs if r["algorithm"] == spec and r["label"] == "0"]
        xs = [float(r["x"]) for r in samples]
        ys = [float(r["y"]) for r in samples]
        ws = [float(r["weight"]) for r in samples]
        ax.hist2d(xs, ys, bins=50, range=[[lo_x, hi_x], [lo_y, hi_y]], weights=ws, cmap="jet")
        mx = sum(w * x for w, x in zip(ws, xs)) / sum(ws)
        my = sum(w * y for w, y in zip(ws, ys)) / sum(ws)
        panel = fig1_panel(spec)
        peak = FIG1_PEAKS[panel]
        ax.plot([peak[0]], [peak[1]], "wx", markersize=11, markeredgewidth=2.5, label=f"supplement's peak ({panel})")
        ax.plot([mx], [my], "o", color="white", markeredgecolor="black", markersize=6, label="our mean")
        ax.set_title(f"{label(spec)}", fontsize=8)
        ax.legend(loc="lower right", fontsize=6, framealpha=0.6)
        print(f"{label(spec)}: belief mean of PO 1 ({mx:.3f}, {my:.3f}); the supplement's peak ({panel}) {peak}")
    for ax in axes:
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)")
    axes[0].set_ylabel("y (m)")
    save(fig, out)


def figure_run(run, point, steps, out):
    frames = rows(os.path.join(run, "frames.csv"))
    estimates = [r for r in rows(os.path.join(run, "estimates.csv")) if r["point"] == point and r["trial"] == "0"]
    step_rows = [r for r in rows(os.path.join(run, "steps.csv")) if r["point"] == point and r["trial"] == "0"]
    trackers = list(dict.fromkeys(r["algorithm"] for r in step_rows))
    tracks = defaultdict(list)
    for r in estimates:
        if r["algorithm"] == "truth":
            tracks[r["label"]].append((int(r["k"]), float(r["x"]), float(r["y"])))
    fig, axes = plt.subplots(1, len(steps) + 1, figsize=(3.4 * (len(steps) + 1), 3.4), constrained_layout=True)
    markers = "ox^sdv"
    for ax, k in zip(axes, steps):
        image, columns, rows_ = frame_image(frames, point, k)
        shown = ax.imshow(image, origin="lower", extent=(0, columns, 0, rows_), cmap="viridis", vmin=0, vmax=11.6)
        for path in tracks.values():
            ax.plot([x for _, x, _ in path], [y for _, _, y in path], "r-", linewidth=0.8)
            ax.plot([x for kk, x, _ in path if kk == k], [y for kk, _, y in path if kk == k], "r.", markersize=5)
        for index, spec in enumerate(trackers):
            here = [(float(r["x"]), float(r["y"])) for r in estimates if r["algorithm"] == spec and r["k"] == str(k)]
            if here:
                ax.plot(*zip(*here), markers[index % len(markers)], mfc="none", color=f"C{index + 1}", markersize=6,
                        label=label(spec))
        ax.set_title(f"k = {k}")
        ax.set_aspect("equal")
    fig.colorbar(shown, ax=axes[len(steps) - 1], shrink=0.8)
    axes[0].legend(fontsize=6, loc="upper left")
    ax = axes[-1]
    for index, spec in enumerate(trackers):
        mine = sorted((int(r["k"]), float(r["gospa"])) for r in step_rows if r["algorithm"] == spec)
        ax.plot([k for k, _ in mine], [g for _, g in mine], color=f"C{index + 1}", label=label(spec))
    ax.set_xlabel("time step k")
    ax.set_ylabel("GOSPA")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=6)
    ax.set_title("GOSPA, this run")
    save(fig, out)


def figure_gospa(run, point, column, out):
    step_rows = [r for r in rows(os.path.join(run, "steps.csv")) if r["point"] == point]
    if not step_rows:
        fail(f"steps.csv has no rows of point {point}")
    if column not in step_rows[0]:
        fail(f"steps.csv has no column '{column}'")
    values = defaultdict(lambda: defaultdict(list))
    for r in step_rows:
        if r[column] != "":
            values[r["algorithm"]][int(r["k"])].append(float(r[column]))
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    for index, (spec, by_k) in enumerate(values.items()):
        ks = sorted(by_k)
        means = [sum(by_k[k]) / len(by_k[k]) for k in ks]
        ses = [math.sqrt(sum((v - m) ** 2 for v in by_k[k]) / max(1, len(by_k[k]) - 1) / len(by_k[k]))
               for k, m in zip(ks, means)]
        ax.plot(ks, means, color=f"C{index}", label=f"{label(spec)} (mean {sum(means) / len(means):.3f})")
        ax.fill_between(ks, [m - s for m, s in zip(means, ses)], [m + s for m, s in zip(means, ses)],
                        color=f"C{index}", alpha=0.2)
        print(f"{label(spec)}: mean over k of the averaged {column} = {sum(means) / len(means):.4f} "
              f"({len(by_k[ks[0]])} runs)")
    ax.set_xlabel("time step k")
    ax.set_ylabel(f"averaged {column}")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8)
    save(fig, out)


# --time-stat of the runtime figure: summary.csv columns of the line and its band (None: ±2 SE).
RUNTIME_STATS = {
    "median": ("step_time_us_median", ("step_time_us_p5", "step_time_us_p95"), "median over trials, 5–95\u00a0% band"),
    "mean": ("step_time_us_mean", None, "mean over trials, ±2 SE"),
}


def figure_runtime(run, out, stat):
    summary = rows(os.path.join(run, "summary.csv"))
    if not summary or "objects" not in summary[0]:
        fail("runtime: summary.csv of a sweep over `objects` expected")
    column, band, words = RUNTIME_STATS[stat]
    fig, ax = plt.subplots(figsize=(6, 4), constrained_layout=True)
    by_spec = defaultdict(list)  # spec -> [(objects, value, band low, band high)] in s
    for r in summary:
        if not r.get(column):
            continue  # no trial of this point finished
        value = float(r[column])
        if band is None:
            se = float(r["step_time_us_se"]) if r.get("step_time_us_se") else 0.0
            low, high = value - 2 * se, value + 2 * se
        else:
            low, high = float(r[band[0]]), float(r[band[1]])
        by_spec[r["algorithm"]].append((int(r["objects"]), value * 1e-6, low * 1e-6, high * 1e-6))
    if not by_spec:
        fail(f"runtime: no value in column {column} of summary.csv")
    for index, (spec, points) in enumerate(by_spec.items()):
        points.sort()
        xs = [p[0] for p in points]
        ys = [p[1] for p in points]
        n = len(xs)
        mx, my = sum(xs) / n, sum(ys) / n
        slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / max(1e-300, sum((x - mx) ** 2 for x in xs))
        intercept = my - slope * mx
        ax.plot(xs, ys, "o-", color=f"C{index}", label=f"{label(spec)}: {1e3 * slope:.2f} ms/object")
        ax.fill_between(xs, [p[2] for p in points], [p[3] for p in points], color=f"C{index}", alpha=0.15, lw=0)
        print(f"{label(spec)}: {1e3 * slope:.3f} ms per object per step, intercept {1e3 * intercept:.3f} ms ({stat})")
    ax.set_xlabel("number of objects")
    ax.set_ylabel(f"runtime per time step (s)\n{words}")
    ax.grid(True, alpha=0.4)
    ax.legend(fontsize=8)
    save(fig, out)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("figure", choices=["toy", "run", "gospa", "runtime"])
    parser.add_argument("run_dir")
    parser.add_argument("--point", default="0")
    parser.add_argument("--steps", default="14,21,27,43")
    parser.add_argument("--column", default="gospa")
    parser.add_argument("--time-stat", choices=tuple(RUNTIME_STATS), default="median",
                        help="runtime: median over trials with a 5-95 %% band (default), or the mean with "
                             "+-2 standard errors as in the supplement")
    parser.add_argument("--out")
    args = parser.parse_args()
    out = args.out or os.path.join(args.run_dir, f"tbd_{args.figure}.png")
    if args.figure == "toy":
        figure_toy(args.run_dir, str(args.point), out)
    elif args.figure == "run":
        figure_run(args.run_dir, args.point, [int(k) for k in args.steps.split(",")], out)
    elif args.figure == "gospa":
        figure_gospa(args.run_dir, args.point, args.column, out)
    else:
        figure_runtime(args.run_dir, out, args.time_stat)


if __name__ == "__main__":
    main()
