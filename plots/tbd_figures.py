#!/usr/bin/python3
"""The track-before-detect figures (tbd-bp-supplement Figs 1-4; the letter's Fig. 2).

Usage:
  /usr/bin/python3 -m plots.tbd_figures toy RUN_DIR [--point P] [--out FILE]
                                                                       supplement Fig. 1
  /usr/bin/python3 -m plots.tbd_figures run RUN_DIR [--point P] [--steps 14,21,27,43] [--out FILE]
                                                                       supplement Figs 2 and 3
  /usr/bin/python3 -m plots.tbd_figures gospa RUN_DIR [--point P] [--column gospa] [--out FILE]
                                                                       the letter's Fig. 2
  /usr/bin/python3 -m plots.tbd_figures runtime RUN_DIR [--time-stat median|mean] [--out FILE]
                                                                       supplement Fig. 4

RUN_DIR is the output folder of `dabench run` on a track-before-detect experiment:
  toy      (experiments/tbd/toy-fig1a.ini or tbd/toy.ini, `beliefs = true`): at one sweep point
           (a reading), as the supplement's Fig. 1: (a) the frame's cell magnitudes |z_j| with the
           two objects, (c) the prior alpha_1 (N(p_1, 0.3 I), drawn analytically; toy layout
           only) and, per tracker, the belief of potential object 1 (label 0) of beliefs.csv over
           p_1 +- 1 m ([3, 5]^2) as a Gaussian kernel density estimate, with the supplement's
           read-off peak of the matching panel (d), (e) or (f), our mean and our mode (the KDE's
           maximum, plots/particle_density.py, as in the tbd REPORT); prints the mean and mode per tracker.
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
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from plots.particle_density import belief_density, kde_mode  # noqa: E402  (the REPORT's mode of a belief)

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
# experiments/tbd/toy.py holds the same readings for the REPORT's verdicts.
FIG1_PEAKS = {"d": (4.47, 4.31), "e": (4.14, 4.13), "f": (4.25, 4.12)}
TOY_PRIOR_VARIANCE = 0.3  # m²: α_n = N(p_n, 0.3 I) of the toy layout (scenarios/tbd/tbd.cpp)
TOY_WINDOW = 1.0  # m: the belief panels show p_1 ± 1 m, the supplement's [3, 5]²
TOY_GRID = 200  # density samples per axis of a belief panel
# The belief panels' markers: the supplement's read-off peak, our belief's mean and its KDE mode.
TOY_MARKS = {
    "supplement's peak": dict(marker="X", markersize=10, color="white", markeredgecolor="black"),
    "our mean": dict(marker="o", markersize=5, color="white", markeredgecolor="black"),
    "our mode": dict(marker="P", markersize=10, color="magenta", markeredgecolor="black"),
}


def fig1_panel(spec):
    """The supplement's panel a toy tracker corresponds to: (d) TBD-MB and the non-interacting
    update, (e) κ̃, (f) exact κ."""
    if spec.startswith("tbd-mb") or "interaction=false" in spec:
        return "d"
    return "f" if "exact_kappa=true" in spec else "e"


def po1_particles(beliefs, spec):
    """PO 1's (label 0) particles of a tracker as (xy [n, 2], normalised weights), identical
    particles pooled as in experiments/tbd/toy.py (a resampled belief repeats them)."""
    pooled = defaultdict(float)
    for r in beliefs:
        if r["algorithm"] == spec and r["label"] == "0":
            pooled[(float(r["x"]), float(r["y"]))] += float(r["weight"])
    if not pooled:
        fail(f"toy: beliefs.csv has no particle of PO 1 (label 0) for {spec}")
    w = np.array(list(pooled.values()))
    return np.array(list(pooled)), w / np.sum(w)


def small_colorbar(fig, shown, ax, text):
    bar = fig.colorbar(shown, ax=ax, shrink=0.8)
    bar.ax.tick_params(labelsize=7)
    bar.ax.yaxis.get_offset_text().set_fontsize(7)
    bar.set_label(text, fontsize=7)


def draw_frame(fig, ax, image, columns, rows_, truth):
    """Panel (a): |z_j| with the objects, as the supplement's (red object 1, black object 2)."""
    shown = ax.imshow(image, origin="lower", extent=(0, columns, 0, rows_), cmap="viridis", vmin=0)
    for index, (x, y) in enumerate(truth):
        ax.plot([x], [y], "x", color="red" if index == 0 else "black", markersize=7, markeredgewidth=2,
                label=f"object {index + 1}")
    ax.legend(loc="upper left", fontsize=7, framealpha=0.8)
    ax.set_title("(a) |z_j| and the objects", fontsize=9)
    small_colorbar(fig, shown, ax, "|z_j|")


def draw_prior(fig, ax, p1, window):
    """Panel (c): α_1, N(p_1, 0.3 I), drawn analytically."""
    xs, ys = (np.linspace(lo, hi, TOY_GRID) for lo, hi in window)
    d2 = (xs[None, :] - p1[0]) ** 2 + (ys[:, None] - p1[1]) ** 2
    density = np.exp(-d2 / (2 * TOY_PRIOR_VARIANCE)) / (2 * math.pi * TOY_PRIOR_VARIANCE)
    shown = ax.imshow(density, origin="lower", extent=(*window[0], *window[1]), cmap="jet", vmin=0)
    ax.set_title("(c) α₁(x, 1)", fontsize=9)
    small_colorbar(fig, shown, ax, "density (m⁻²)")


def draw_belief(fig, ax, spec, xy, w, window):
    """A belief panel: PO 1's density by spec over the window with the supplement's peak of the
    matching panel and our mean and mode (a marker outside the window is not drawn; the title
    gives the numbers, the panel the share in view when under half). Returns (panel, mean, mode)."""
    mean = w @ xy
    sd = np.sqrt(w @ (xy - mean) ** 2)
    mode = kde_mode(xy, w, sd)
    xs, ys = (np.linspace(lo, hi, TOY_GRID) for lo, hi in window)
    shown = ax.imshow(belief_density(xy, w, sd, xs, ys), origin="lower", extent=(*window[0], *window[1]),
                      cmap="jet", vmin=0)
    small_colorbar(fig, shown, ax, "density (m⁻²)")
    panel = fig1_panel(spec)
    for name, (x, y) in (("supplement's peak", FIG1_PEAKS[panel]), ("our mode", mode), ("our mean", mean)):
        ax.plot([x], [y], linestyle="none", **TOY_MARKS[name])
    ax.set_xlim(*window[0])
    ax.set_ylim(*window[1])
    inside = np.all((xy >= [window[0][0], window[1][0]]) & (xy <= [window[0][1], window[1][1]]), axis=1)
    if w @ inside < 0.5:
        ax.text(0.5, 0.5, f"{100 * (w @ inside):.0f} % of the belief in view", transform=ax.transAxes,
                ha="center", color="white", fontsize=8)
    ax.set_title(f"{label(spec)}\nFig. 1({panel}) peak ({FIG1_PEAKS[panel][0]:.2f}, {FIG1_PEAKS[panel][1]:.2f}); "
                 f"ours: mean ({mean[0]:.2f}, {mean[1]:.2f}),\nmode ({mode[0]:.2f}, {mode[1]:.2f})", fontsize=7)
    return panel, mean, mode


def draw_toy_legend(ax):
    """The spare panel: the belief panels' legend."""
    handles = [Line2D([], [], linestyle="none", label=name, **marks) for name, marks in TOY_MARKS.items()]
    ax.legend(handles=handles, loc="center", fontsize=9, title="belief of PO 1 (label 0), KDE", title_fontsize=9)
    ax.axis("off")


def figure_toy(run, point, out):
    """Supplement Fig. 1 at one sweep point: (a), (c) where the run is the toy layout, then one
    belief panel per tracker and the legend, on two rows."""
    frames = rows(os.path.join(run, "frames.csv"))
    estimates = rows(os.path.join(run, "estimates.csv"))
    beliefs = [r for r in rows(os.path.join(run, "beliefs.csv")) if r["point"] == point and r["k"] == "1"]
    image, columns, rows_ = frame_image(frames, point, 1)
    truth = [(float(r["x"]), float(r["y"])) for r in estimates
             if r["algorithm"] == "truth" and r["point"] == point and r["k"] == "1"]
    trackers = list(dict.fromkeys(r["algorithm"] for r in beliefs))
    if not truth or not trackers:
        fail(f"toy: point {point} needs the truth in estimates.csv and the trackers' beliefs in beliefs.csv (beliefs = true)")
    prior = beliefs[0].get("layout") == "toy"  # α_1 is known: the toy layout's N(p_1, 0.3 I)
    panels = 1 + prior + len(trackers) + 1
    columns_ = math.ceil(panels / 2)
    fig, grid = plt.subplots(2, columns_, figsize=(3.4 * columns_, 6.8), constrained_layout=True)
    axes = list(grid.flat)
    reading = beliefs[0].get("signal", "")
    frame = beliefs[0].get("frame") or "drawn"
    fig.suptitle(f"{os.path.basename(os.path.normpath(run))}, point {point}"
                 + (f": reading {reading.upper()}" if reading else "") + f" (frame: {frame})")
    draw_frame(fig, axes[0], image, columns, rows_, truth)
    p1 = truth[0]
    window = ((p1[0] - TOY_WINDOW, p1[0] + TOY_WINDOW), (p1[1] - TOY_WINDOW, p1[1] + TOY_WINDOW))
    if prior:
        draw_prior(fig, axes[1], p1, window)
    for ax, spec in zip(axes[1 + prior:], trackers):
        xy, w = po1_particles(beliefs, spec)
        panel, mean, mode = draw_belief(fig, ax, spec, xy, w, window)
        print(f"{label(spec)}: belief of PO 1 mean ({mean[0]:.3f}, {mean[1]:.3f}), mode ({mode[0]:.3f}, "
              f"{mode[1]:.3f}); the supplement's peak ({panel}) {FIG1_PEAKS[panel]}")
    draw_toy_legend(axes[panels - 1])
    for ax in axes[panels:]:
        ax.axis("off")
    for ax in axes[:panels - 1]:
        ax.set_aspect("equal")
        ax.set_xlabel("x (m)", fontsize=8)
        ax.set_ylabel("y (m)", fontsize=8)
        ax.tick_params(labelsize=7)
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
