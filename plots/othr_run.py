"""Shared reading for the OTHR tracking plots (othr_scenario.py, othr_tracks.py): the files of
a tracking run (`dabench run` on scenario othr) and the choice of one sweep point and trial.

tracks.csv and measurements.csv start with `point`, the scenario parameters and `trial`; the
parameters are the columns between `point` and `trial`. Rows are streamed and only those of
the chosen point and trial are kept.
"""

import csv
import os
import sys

PATH_NAMES = {1: "EE", 2: "EF", 3: "FE", 4: "FF"}  # Table II, tau = 1..4 (origin_path)


class PlotError(Exception):
    """Input that cannot be plotted; the script prints it on one line and exits with status 2."""


def fail(script, message):
    print(f"{script}: {message}", file=sys.stderr)
    sys.exit(2)


def parse_where(text):
    """'pd=0.75,clutter=125' -> {'pd': '0.75', 'clutter': '125'}."""
    where = {}
    for part in (text or "").split(","):
        if not part.strip():
            continue
        if "=" not in part:
            raise PlotError(f"--where '{text}': expected KEY=VALUE[,KEY=VALUE...]")
        key, value = part.split("=", 1)
        where[key.strip()] = value.strip()
    return where


def _same_value(a, b):
    try:
        return abs(float(a) - float(b)) <= 1e-9 * max(1.0, abs(float(b)))
    except ValueError:
        return a == b


def run_file(run_dir, name):
    path = os.path.join(run_dir, name)
    if not os.path.exists(path):
        raise PlotError(f"{path}: missing (is {run_dir} a tracking run of `dabench run`?)")
    return path


def read_point_rows(path, where, point, trial, required):
    """Rows of `path` at the chosen point and trial, and a description of the point.

    The point is `point` if given, else the first whose parameters match `where` (numbers
    compared as numbers), else point 0. Returns (rows, {parameter: value}).
    """
    chosen, params, rows = (None if point is None else str(point)), None, []
    try:
        with open(path, newline="") as f:
            reader = csv.DictReader(f)
            header = reader.fieldnames or []
            for column in ["point", "trial"] + required:
                if column not in header:
                    raise PlotError(f"{path}: no column '{column}'")
            for key in where:
                if key not in header[1:header.index("trial")]:
                    raise PlotError(f"{path}: --where names '{key}', not a scenario parameter "
                                    f"({', '.join(header[1:header.index('trial')])})")
            param_names = header[1:header.index("trial")]
            for r in reader:
                if chosen is None and all(_same_value(r[k], v) for k, v in where.items()):
                    chosen = r["point"]
                if r["point"] != chosen:
                    continue
                params = params or {k: r[k] for k in param_names}
                if r["trial"] == str(trial):
                    rows.append(r)
    except OSError as error:
        raise PlotError(f"{path}: {error.strerror}")
    if chosen is None:
        raise PlotError(f"{path}: no sweep point matches --where {where}")
    if not rows:
        raise PlotError(f"{path}: no rows for point {chosen}, trial {trial}")
    return rows, params


def point_title(params, keys=("pd", "clutter")):
    """'pd = 0.75, N_c = 125' from a point's parameters."""
    names = {"pd": "$p_d$", "clutter": "$N_c$"}
    return ", ".join(f"{names.get(k, k)} = {params[k]}" for k in keys if k in params)


def save_figure(fig, out, script):
    """Writes OUT (PNG, 200 dpi) and the SVG beside it, and names both on stderr."""
    svg = os.path.splitext(out)[0] + ".svg"
    try:
        fig.savefig(out, dpi=200)
        fig.savefig(svg)
    except OSError as error:
        fail(script, f"{out}: {error.strerror}")
    print(out, file=sys.stderr)
    print(svg, file=sys.stderr)
