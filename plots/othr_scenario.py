#!/usr/bin/python3
"""Fig. 5 of JDT-VB (jdt-vb-multipath-othr, Sec. IV-B): (a) the target trajectories, (b) the
multipath detections of the targets and the clutter over all scans of one run.

Usage:
  /usr/bin/python3 -m plots.othr_scenario RUN_DIR [--where pd=0.75,clutter=125 | --point N]
                   [--out RUN_DIR/othr_scenario.png] [--title TEXT]

Reads RUN_DIR/tracks.csv (the truth rows, algorithm `truth`) and RUN_DIR/measurements.csv,
which `dabench run` writes for trial 0 of each sweep point only, so the run shown is trial 0 of
the chosen point (default: the first point matching --where, else point 0).
  (a) ground range g (km) against bearing (rad) of each target over its lifetime, a circle at
      its first scan, labelled Target 1..4 as in Table III;
  (b) every measurement in measurement space, slant range r (km) against azimuth (rad): clutter
      as small grey dots, target detections coloured by target with one marker per path
      (Table II: EE, EF, FE, FF).
Writes a PNG (200 dpi) and an SVG; exit status 2 with a one-line message when the input cannot
be plotted.
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plots.othr_run import (
    PATH_NAMES, PlotError, fail, parse_where, point_title, read_point_rows, run_file, save_figure)

SCRIPT = "othr_scenario.py"
PATH_MARKERS = {1: "o", 2: "s", 3: "^", 4: "D"}


def truth_trajectories(rows):
    """{target number: [(scan, g, theta), ...]} from the truth rows of tracks.csv."""
    targets = {}
    for r in rows:
        if r["algorithm"] == "truth":
            targets.setdefault(int(r["track"]), []).append((int(r["scan"]), float(r["g"]), float(r["theta"])))
    for points in targets.values():
        points.sort()
    return targets


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--where", help="KEY=VALUE[,KEY=VALUE...] choosing the sweep point, e.g. pd=0.75,clutter=125")
    parser.add_argument("--point", type=int, help="sweep point index (instead of --where)")
    parser.add_argument("--out")
    parser.add_argument("--title")
    args = parser.parse_args()
    try:
        where = parse_where(args.where)
        measurements, params = read_point_rows(run_file(args.run_dir, "measurements.csv"), where, args.point, 0,
                                               ["scan", "r", "azimuth", "origin_target", "origin_path"])
        tracks, _ = read_point_rows(run_file(args.run_dir, "tracks.csv"), where, args.point, 0,
                                    ["algorithm", "track", "scan", "g", "theta"])
    except PlotError as error:
        fail(SCRIPT, error)
    targets = truth_trajectories(tracks)
    if not targets:
        fail(SCRIPT, f"{args.run_dir}: no truth rows at this point")

    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 5.2))
    colours = {}
    for number, points in sorted(targets.items()):
        scans, g, theta = zip(*points)
        line, = left.plot(theta, g, "-", linewidth=1.5, label=f"Target {number}")
        colours[number] = line.get_color()
        left.plot(theta[0], g[0], "o", color=line.get_color())
        left.annotate(f"k={scans[0] + 1}", (theta[0], g[0]), textcoords="offset points", xytext=(4, 4), fontsize=7)
    left.set_xlabel("bearing $\\vartheta$ (rad)")
    left.set_ylabel("ground range $g$ (km)")
    left.set_title("(a) target trajectories")
    left.legend(fontsize=8)
    left.grid(alpha=0.3)

    clutter = [(float(r["azimuth"]), float(r["r"])) for r in measurements if int(r["origin_target"]) < 0]
    if clutter:
        az, rng = zip(*clutter)
        right.plot(az, rng, ".", color="0.7", markersize=2, label=f"clutter ({len(clutter)})")
    detections = {}
    for r in measurements:
        target = int(r["origin_target"])
        if target >= 0:
            detections.setdefault((target, int(r["origin_path"])), []).append((float(r["azimuth"]), float(r["r"])))
    for (target, path), points in sorted(detections.items()):
        az, rng = zip(*points)
        right.plot(az, rng, PATH_MARKERS.get(path, "x"), color=colours.get(target, "k"), markersize=3.5,
                   markerfacecolor="none", label=f"T{target} {PATH_NAMES.get(path, path)}")
    right.set_xlabel("azimuth $\\zeta$ (rad)")
    right.set_ylabel("slant range $r$ (km)")
    scans = len({r["scan"] for r in measurements})
    right.set_title(f"(b) multipath detections and clutter, {scans} scans")
    right.legend(fontsize=6, ncol=4, loc="lower right")
    right.grid(alpha=0.3)
    fig.suptitle(args.title or f"OTHR scenario, run 0 ({point_title(params)})")
    fig.tight_layout()
    save_figure(fig, args.out or os.path.join(os.path.abspath(args.run_dir), "othr_scenario.png"), SCRIPT)


if __name__ == "__main__":
    main()
