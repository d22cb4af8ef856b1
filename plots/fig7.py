#!/usr/bin/python3
"""Fig. 7 of Williams & Lau 2014 (bp-marginal-association): BP's convergence parameter W* vs. a sweep.

Usage:
  /usr/bin/python3 -m plots.fig7 RUN_DIR/summary.csv [--where pd=0.9] [--algorithm bp] [--x spacing]
                   [--out RUN_DIR/fig7.png] [--title TEXT] [--logy]

Draws the mean of W* (solid blue) and its 5th and 95th percentiles over the trials (dashed
black) from the w_star_mean, w_star_p5 and w_star_p95 columns of one algorithm's rows. The rows
left after --where must form one panel (one combination of the scenario parameters other than
x); if several remain, the script lists them and exits with status 2. Writes a PNG and an SVG.
"""

import argparse
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from plots import fig6
from plots.fig6 import fail, note

plt = fig6.plt
np = fig6.np


def pick_algorithm(rows, wanted):
    """Exact spec match, else the single spec whose name equals wanted (e.g. bp -> bp:delta=1e-6)."""
    specs = []
    for r in rows:
        a = (r.get("algorithm") or "").strip()
        if a and a not in specs:
            specs.append(a)
    if wanted in specs:
        return wanted
    same_name = [s for s in specs if fig6.spec_parts(s)[0] == wanted]
    if len(same_name) == 1:
        note(f"using algorithm '{same_name[0]}' for --algorithm {wanted}")
        return same_name[0]
    if same_name:
        fail(f"--algorithm {wanted} matches {len(same_name)} specs ({', '.join(same_name)}); give the full spec")
    fail(f"no algorithm '{wanted}' in the selected rows (have: {', '.join(specs) or 'none'})")


def main(argv=None):
    ap = argparse.ArgumentParser(prog=fig6.PROG, description="Fig. 7: W* (mean, 5th/95th percentile) versus a sweep.")
    ap.add_argument("summary", help="summary.csv written by `dabench run`")
    ap.add_argument("--algorithm", default="bp", help="algorithm spec whose W* is drawn (default bp)")
    ap.add_argument("--where", action="append", metavar="KEY=VALUE",
                    help="keep only rows with KEY=VALUE (repeatable, or comma-separated), e.g. pd=0.9")
    ap.add_argument("--x", help="scenario parameter on the x axis (default: the one with most values)")
    ap.add_argument("--out", help="output PNG (an SVG is written next to it; default: fig7.png next to the summary)")
    ap.add_argument("--title", help="axes title (default: the selected panel's parameters)")
    ap.add_argument("--logy", action="store_true", help="logarithmic y axis")
    args = ap.parse_args(argv)

    summary = fig6.Summary(args.summary)
    for col in ("w_star_mean", "w_star_p5", "w_star_p95"):
        if not summary.has(col):
            fail(f"{args.summary}: no '{col}' column")
    where = fig6.parse_where(args.where, summary)
    rows = fig6.apply_where(summary.rows, where)
    if not rows:
        fail(f"no rows of {args.summary} match --where {' '.join(args.where)}")
    spec = pick_algorithm(rows, args.algorithm)
    # panels are judged on every algorithm's rows so that the title names what --where chose
    x = fig6.choose_x(summary, rows, args.x)
    full = fig6.Sweep(summary, summary.rows, x)
    sweep = fig6.Sweep(summary, rows, x)
    if len(sweep.panels) > 1:
        shown = "; ".join(",".join(f"{k}={row.get(k, '').strip()}" for k in sweep.panel_keys)
                          for _, row in sweep.panels[:8])
        fail(f"{len(sweep.panels)} panels match ({shown}{'; ...' if len(sweep.panels) > 8 else ''}); "
             f"select one with --where, e.g. --where {sweep.panel_keys[0]}=VALUE")

    xs, mean, _ = sweep.series(0, spec, "w_star_mean")
    _, p5, _ = sweep.series(0, spec, "w_star_p5")
    _, p95, _ = sweep.series(0, spec, "w_star_p95")
    if xs.size == 0 or not np.isfinite(mean).any():
        fail(f"no W* values for '{spec}' in the selected rows (does it compute W*?)")

    fig, ax = plt.subplots(figsize=(5.6, 3.6), layout="constrained")

    def line(y, **kw):
        ok = np.isfinite(y) & ((y > 0) if args.logy else np.isfinite(y))
        if not ok.any():
            return
        marker = "o" if ok.sum() == 1 else None
        ax.plot(xs[ok], y[ok], marker=marker, ms=4, **kw)

    line(mean, color="b", ls="-", lw=1.6, label="mean")
    line(p95, color="k", ls="--", lw=1.1, label="5th / 95th percentile")
    line(p5, color="k", ls="--", lw=1.1)
    if args.logy:
        ax.set_yscale("log")
    else:
        ax.set_ylim(bottom=0)
    if xs.size == 1:
        half = abs(xs[0]) * 0.5 if xs[0] else 1.0
        ax.set_xlim(xs[0] - half, xs[0] + half)
        ax.set_xticks([xs[0]])
    else:
        ax.margins(x=0.02)
    ax.set_xlabel(sweep.x_label(), fontsize=10)
    ax.set_ylabel(r"convergence parameter $W_*$", fontsize=10)
    ax.tick_params(labelsize=9)
    ax.grid(True, color="0.88", lw=0.6)
    ax.set_axisbelow(True)
    if args.title:
        title = args.title
    else:  # name the panel by the parameters that vary over the whole file, e.g. "P_d = 0.9"
        parts = full.describe(rows[0], [k for k in full.panel_keys])
        title = fig6.wrap_parts(parts or sweep.fixed_title(), 60)
        if spec != "bp":
            title = f"{spec}: {title}" if title else spec
    if title:
        ax.set_title(title, fontsize=10.5)
    ax.legend(fontsize=9, frameon=False, loc="best")

    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.summary)), "fig7.png")
    fig6.write_figure(fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
