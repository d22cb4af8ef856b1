#!/usr/bin/python3
"""Fig. 6 of JDT-VB (jdt-vb-multipath-othr, Sec. IV-B): the tracks of one run, one panel per
tracker, over the true trajectories.

Usage:
  /usr/bin/python3 -m plots.othr_tracks RUN_DIR [--where pd=0.75,clutter=125 | --point N]
                   [--trial 0] [--all] [--min-length 1] [--plane]
                   [--out RUN_DIR/othr_tracks.png] [--title TEXT]

Reads RUN_DIR/tracks.csv (written by `dabench run` for tracking experiments): the truth rows
(algorithm `truth`) are drawn as black dashed lines labelled Target 1..4, each tracker's tracks
in colour labelled Trk-<id> at their first scan. Only confirmed tracks are drawn unless --all
(tentative ones then dotted); --min-length drops tracks shorter than that many scans (the
metrics score confirmed tracks of at least 5 scans). Axes: bearing (rad) against ground range
(km), or with --plane the ground plane x = g sin(theta), y = g cos(theta) (km; receiver at the
origin, as in scenarios/tracking/othr_geometry.hpp). The run is --trial (default 0) of the chosen sweep
point (default: the first point matching --where, else point 0). Writes a PNG (200 dpi) and an
SVG; exit status 2 with a one-line message when the input cannot be plotted.
"""

import argparse
import math
import os
import sys

sys.dont_write_bytecode = True
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from plots.othr_run import PlotError, fail, parse_where, point_title, read_point_rows, run_file, save_figure

SCRIPT = "othr_tracks.py"


def coordinates(g, theta, plane):
    if plane:
        return g * math.sin(theta), g * math.cos(theta)
    return theta, g


def collect(rows):
    """{algorithm: {track id: (confirmed, [(scan, g, theta), ...])}} in file order."""
    runs = {}
    for r in rows:
        if r["g"] == "" or r["theta"] == "":
            continue
        tracks = runs.setdefault(r["algorithm"], {})
        confirmed, points = tracks.setdefault(r["track"], (r["confirmed"] == "1", []))
        points.append((int(r["scan"]), float(r["g"]), float(r["theta"])))
    return runs


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("run_dir")
    parser.add_argument("--where", help="KEY=VALUE[,KEY=VALUE...] choosing the sweep point, e.g. pd=0.75,clutter=125")
    parser.add_argument("--point", type=int, help="sweep point index (instead of --where)")
    parser.add_argument("--trial", type=int, default=0, help="the run to draw (default 0)")
    parser.add_argument("--all", action="store_true", help="also draw tentative (unconfirmed) tracks, dotted")
    parser.add_argument("--min-length", type=int, default=1, help="draw tracks of at least this many scans (default 1)")
    parser.add_argument("--plane", action="store_true", help="ground-plane x-y axes instead of bearing-range")
    parser.add_argument("--out")
    parser.add_argument("--title")
    args = parser.parse_args()
    try:
        rows, params = read_point_rows(run_file(args.run_dir, "tracks.csv"), parse_where(args.where), args.point,
                                       args.trial, ["algorithm", "track", "confirmed", "scan", "g", "theta"])
    except PlotError as error:
        fail(SCRIPT, error)
    runs = collect(rows)
    truth = runs.pop("truth", {})
    if not truth:
        fail(SCRIPT, f"{args.run_dir}/tracks.csv: no truth rows for this point and trial")
    if not runs:
        print(f"{SCRIPT}: no tracker has tracks in this run (failed or skipped?); drawing the truth only",
              file=sys.stderr)

    panels = list(runs) or ["(no tracks)"]
    fig, axes = plt.subplots(1, len(panels), figsize=(5.5 * len(panels), 5.2), squeeze=False)
    for axis, algorithm in zip(axes[0], panels):
        for number, (_, points) in sorted(truth.items(), key=lambda item: int(item[0])):
            x, y = zip(*(coordinates(g, t, args.plane) for _, g, t in sorted(points)))
            axis.plot(x, y, "k--", linewidth=1.0)
            axis.annotate(f"Target {number}", (x[0], y[0]), textcoords="offset points", xytext=(-10, -12), fontsize=7)
        drawn = 0
        for track, (confirmed, points) in runs.get(algorithm, {}).items():
            if (not confirmed and not args.all) or len(points) < args.min_length:
                continue
            x, y = zip(*(coordinates(g, t, args.plane) for _, g, t in sorted(points)))
            line, = axis.plot(x, y, "-" if confirmed else ":", linewidth=1.6)
            axis.plot(x[0], y[0], "o", color=line.get_color(), markersize=3)
            axis.annotate(f"Trk-{track}", (x[0], y[0]), textcoords="offset points", xytext=(4, 4), fontsize=7,
                          color=line.get_color())
            drawn += 1
        axis.set_title(f"{algorithm} ({drawn} tracks)")
        axis.set_xlabel("x (km)" if args.plane else "bearing $\\vartheta$ (rad)")
        axis.set_ylabel("y (km)" if args.plane else "ground range $g$ (km)")
        axis.grid(alpha=0.3)
    fig.suptitle(args.title or f"Tracks of run {args.trial} ({point_title(params)}); truth dashed")
    fig.tight_layout()
    save_figure(fig, args.out or os.path.join(os.path.abspath(args.run_dir), "othr_tracks.png"), SCRIPT)


if __name__ == "__main__":
    main()
