#!/usr/bin/python3
"""The complete Fig. 6 of Williams & Lau 2014 (bp-marginal-association), from three runs.

Usage:
  /usr/bin/python3 -m plots.fig6_paper [--exp1 RUN1/summary.csv] [--exp2 RUN2/summary.csv]
                   [--exp3 RUN3/summary.csv] [--out results/bp-paper/fig6.png]
                   [--metric max_error] [--show-reference-error] [--independent-y]
                   [--time-unit auto|us|ms|s] [--time-stat median|mean] [--no-bands] [--title TEXT]

Layout as in the paper: three panels per figure row, each panel an error axes (average
--metric, log y) above a time axes (time per problem, log y), so 3 panel rows make 6 axes rows:

    row 1:  baseline           lambda_fa 0.0316     lambda_fa 0.1
    row 2:  Pd 0.3             Pd 0.9               n x 3 grids  (experiment 2, shaded)
    row 3:  r 0.1              r 10                 n x n grids  (experiment 3, shaded)

Experiment-1 panels (x = target spacing) are identified by their (pd, lambda_fa, r) against the
baseline pd 0.6, lambda_fa 0.01, r 1; experiments 2 and 3 (x = number of targets,
n_targets_mean, else rows*cols) are drawn on a light grey background. A missing input leaves its
panels out; figure rows or columns left entirely empty are dropped.

Lines and styles are fig6.py's (imported from it), with the paper's fixed variant mapping:
MCMCDA 1e5/1e6/1e7 samples, correlation decay depth 3/5/7 and junction tree threshold
1e-1/1e-2/1e-3 are dot-dashed/dashed/solid in every panel, whatever subset a run holds. The
exact/ehm references appear in the time rows only unless --show-reference-error. Summary rows
whose trials were all skipped or failed (ok == 0) are not drawn, and neither is any point whose
mean is zero or missing (log axes). One legend for the whole figure. Writes PNG and SVG.

The time axes show the median time per problem with its 5-95 % band by default: on a busy
machine the mean is dominated by the rare calls another job preempts. `--time-stat mean` draws
the paper's average time per problem with +-2 standard errors. Axis labels and title say which.

experiments/bp_paper/rules.py imports the data model (PaperData) and the input options (add_input_arguments,
read_inputs) from this file.
"""

import argparse
import json
import math
import os
import re
import sys
import textwrap

sys.dont_write_bytecode = True  # no __pycache__ in the source tree
from plots import fig6
from plots.fig6 import fail, fnum, note

plt = fig6.plt
np = fig6.np
Line2D = fig6.Line2D

# ----------------------------------------------------------------------------- panels

BASELINE = {"pd": 0.6, "lambda_fa": 0.01, "r": 1.0}

# key, title, experiment, overrides of the baseline (experiment 1 only), (panel row, column)
PANEL_DEFS = [
    ("baseline", "baseline", 1, {}, (0, 0)),
    ("lambda_fa=0.0316", r"$\lambda_{fa}$ = 0.0316", 1, {"lambda_fa": 0.0316}, (0, 1)),
    ("lambda_fa=0.1", r"$\lambda_{fa}$ = 0.1", 1, {"lambda_fa": 0.1}, (0, 2)),
    ("pd=0.3", r"$P_d$ = 0.3", 1, {"pd": 0.3}, (1, 0)),
    ("pd=0.9", r"$P_d$ = 0.9", 1, {"pd": 0.9}, (1, 1)),
    ("3xn", None, 2, None, (1, 2)),
    ("r=0.1", r"$r$ = 0.1", 1, {"r": 0.1}, (2, 0)),
    ("r=10", r"$r$ = 10", 1, {"r": 10.0}, (2, 1)),
    ("nxn", None, 3, None, (2, 2)),
]
EXP1_KEYS = [d[0] for d in PANEL_DEFS if d[2] == 1]

# The paper's variant -> line style mapping (Fig. 6 caption). Values are compared numerically.
CANONICAL_LS = {
    "mcmcda": {1e5: "-.", 1e6: "--", 1e7: "-"},
    "cd": {3.0: "-.", 5.0: "--", 7.0: "-"},
    "jt": {0.1: "-.", 0.01: "--", 0.001: "-"},
}
EXTRA_LS = [":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)), (0, (8, 2)), (0, (3, 1, 1, 1))]
# Defaults of the ordering parameter when a SPEC omits it; they mirror algorithms/single_scan/mcmcda.hpp
# (samples = 100000) and algorithms/single_scan/correlation_decay.hpp (depth = 5). jt has no default here.
SPEC_DEFAULTS = {"mcmcda": 1e5, "cd": 5.0}
REFERENCE_FAMILIES = ("exact", "ehm")
DISPLAY = {"bp": "BP", "lmipda": "LMIPDA", "baa": "BAA", "mcmcda": "MCMCDA", "cd": "CD",
           "jt": "JT", "exact": "exact", "ehm": "EHM"}


def close(a, b, rel=1e-3):
    return math.isclose(a, b, rel_tol=rel, abs_tol=1e-12)


def family_key(spec):
    """'mcmcda:samples=1e5' -> 'mcmcda'; unknown names -> None."""
    fam = fig6.family_of(fig6.spec_parts(spec)[0])
    return fam[0] if fam else None


def order_value(spec):
    """The ordering parameter of a family variant (samples, depth, threshold) as a float, or NaN."""
    name, kv = fig6.spec_parts(spec)
    fam = fig6.family_of(name)
    if fam is None or not fam[4]:
        return math.nan
    for p in fam[4]:
        if p in kv:
            return fnum(kv[p])
    return SPEC_DEFAULTS.get(fam[0], math.nan)


def other_params(spec):
    """SPEC parameters other than the family's ordering one, as 'k=v' strings."""
    name, kv = fig6.spec_parts(spec)
    fam = fig6.family_of(name)
    skip = set(fam[4] or ()) if fam else set()
    return [f"{k}={v}" for k, v in kv.items() if k not in skip]


def is_reference_family(spec):
    return family_key(spec) in REFERENCE_FAMILIES


def read_references(summary_path):
    """Reference SPECs named by meta.json next to summary.csv ('reference': str or list)."""
    path = os.path.join(os.path.dirname(os.path.abspath(summary_path)), "meta.json")
    try:
        with open(path, encoding="utf-8") as f:
            meta = json.load(f)
    except (OSError, ValueError):
        return []
    ref = meta.get("reference") or meta.get("references") or []
    if isinstance(ref, str):
        ref = [ref]
    return [str(r).strip() for r in ref if str(r).strip()]


class Panel:
    """One Fig. 6 panel: its summary rows, x per row and per-algorithm series."""

    def __init__(self, key, title, exp, pos, all_rows, path):
        self.key, self.title, self.exp, self.pos, self.path = key, title, exp, pos, path
        self.all_rows = all_rows  # every summary row of the panel (the report counts skips)
        # rows whose status counts show every trial skipped or failed are not data
        self.rows = [r for r in all_rows if not (fnum(r.get("ok")) == 0)]
        self.shaded = exp != 1
        self.x_label = "target spacing" if exp == 1 else "number of targets"
        self._x = {}
        if exp == 1:
            for r in all_rows:
                self._x[id(r)] = fnum(r.get("spacing"))
        else:  # number of targets of the point: measured mean, else rows*cols
            per_point = {}
            for r in all_rows:
                pid = point_id(r)
                v = fnum(r.get("n_targets_mean"))
                if not math.isnan(v) and math.isnan(per_point.get(pid, math.nan)):
                    per_point[pid] = v
            for r in all_rows:
                v = per_point.get(point_id(r), math.nan)
                if math.isnan(v):
                    v = fnum(r.get("rows")) * fnum(r.get("cols"))
                self._x[id(r)] = v
        self.algorithms = []
        for r in all_rows:
            a = (r.get("algorithm") or "").strip()
            if a and a not in self.algorithms:
                self.algorithms.append(a)
        self._dup_noted = set()
        self._points = {}  # (spec, include_skipped) -> {x: row}: the rows never change, their values may

    def x_of(self, r):
        return self._x[id(r)]

    def points(self, spec, include_skipped=False):
        """{x: row} of one algorithm (first row per x), sorted by x."""
        key = (spec, include_skipped)
        if key not in self._points:
            self._points[key] = self._find_points(spec, include_skipped)
        return dict(self._points[key])

    def _find_points(self, spec, include_skipped):
        pts = {}
        for r in self.all_rows if include_skipped else self.rows:
            if (r.get("algorithm") or "").strip() != spec:
                continue
            xv = self.x_of(r)
            if math.isnan(xv):
                continue
            if xv in pts:
                if (spec, xv) not in self._dup_noted:
                    self._dup_noted.add((spec, xv))
                    note(f"{self.path}: panel {self.key}: several '{spec}' rows at x={xv:g}; keeping the first")
                continue
            pts[xv] = r
        return dict(sorted(pts.items()))

    def series(self, spec, col, se_col=None):
        pts = self.points(spec)
        xs = np.array(list(pts), dtype=float)
        ys = np.array([fnum(r.get(col)) for r in pts.values()], dtype=float)
        ses = np.array([fnum(r.get(se_col)) if se_col else math.nan for r in pts.values()], dtype=float)
        return xs, ys, ses

    def value(self, spec, x, col):
        r = self.points(spec).get(x)
        return fnum(r.get(col)) if r is not None else math.nan


def point_id(r):
    p = (r.get("point") or "").strip()
    return ("p", p) if p else ("k", r.get("rows"), r.get("cols"), r.get("spacing"))


def grid_title(rows):
    """'n×3 grids' / 'n×n grids' / '3×n grids' from the shape of the rows, with the spacing."""
    rs = {fnum(r.get("rows")) for r in rows}
    cs = {fnum(r.get("cols")) for r in rows}
    if all(fnum(r.get("rows")) == fnum(r.get("cols")) for r in rows) and len(rs) > 1:
        shape = "n×n"
    elif len(cs) == 1 and len(rs) > 1:
        shape = f"n×{fig6.fmt_value(rows[0].get('cols'))}"
    elif len(rs) == 1 and len(cs) > 1:
        shape = f"{fig6.fmt_value(rows[0].get('rows'))}×n"
    else:
        shape = "grid"
    sp = {fnum(r.get("spacing")) for r in rows}
    extra = f", spacing {fig6.fmt_value(rows[0].get('spacing'))}" if len(sp) == 1 else ""
    return f"{shape} grids{extra}"


class PaperData:
    """The three runs split into the nine panels of Fig. 6."""

    def __init__(self, exp1=None, exp2=None, exp3=None, exp1_extra=()):
        self.paths = {1: exp1, 2: exp2, 3: exp3}
        self.summaries = {}
        self.references = set()
        self.references_by_exp = {}
        for exp, path in self.paths.items():
            if path:
                self.summaries[exp] = fig6.Summary(path)
                self.references_by_exp[exp] = set(read_references(path))
                self.references.update(self.references_by_exp[exp])
        for path in exp1_extra:
            if 1 not in self.summaries:
                fail("--exp1-extra needs --exp1")
            self._add_algorithms(self.summaries[1], fig6.Summary(path))
        self.panels = []
        if 1 in self.summaries:
            self._split_exp1(self.summaries[1])
        for exp, key in ((2, "3xn"), (3, "nxn")):
            if exp in self.summaries:
                self._add_large(exp, key, self.summaries[exp])
        order = [d[0] for d in PANEL_DEFS]
        self.panels.sort(key=lambda p: order.index(p.key))
        self.by_key = {p.key: p for p in self.panels}

    @staticmethod
    def _add_algorithms(main, extra):
        """Rows of algorithms that `main` lacks, from a run over the same points (e.g. a shorter
        run of the costly MCMCDA 10^7 chain); algorithms `main` has keep its rows."""
        if extra.params != main.params:
            fail(f"{extra.path}: scenario columns {extra.params} differ from {main.path}'s {main.params}")
        have = {r.get("algorithm") for r in main.rows}
        added = [r for r in extra.rows if r.get("algorithm") not in have]
        if not added:
            note(f"{extra.path}: no algorithm that {main.path} lacks")
        main.rows.extend(added)
        main.columns.update(extra.columns)

    def _split_exp1(self, s):
        for col in ("pd", "lambda_fa", "r", "spacing"):
            if not s.has(col):
                fail(f"{s.path}: no '{col}' column; cannot identify the experiment-1 panels")
        rows = s.rows
        if s.has("rows") and s.has("cols"):
            sizes = {}
            for r in rows:
                k = (fnum(r.get("rows")), fnum(r.get("cols")))
                sizes[k] = sizes.get(k, 0) + 1
            if len(sizes) > 1:
                if len({fig6.norm_key(r.get("spacing")) for r in rows}) == 1:
                    fail(f"--exp1 {s.path}: the grid size varies at one spacing; this looks like "
                         f"experiment 2 or 3 (pass it as --exp2 / --exp3)")
                keep = (2.0, 3.0) if (2.0, 3.0) in sizes else max(sizes, key=sizes.get)
                note(f"--exp1 {s.path}: several grid sizes; keeping the {keep[0]:g}×{keep[1]:g} rows")
                rows = [r for r in rows if (fnum(r.get("rows")), fnum(r.get("cols"))) == keep]
        groups = {d[0]: [] for d in PANEL_DEFS if d[2] == 1}
        unmatched = set()
        for r in rows:
            vals = {k: fnum(r.get(k)) for k in BASELINE}
            hit = None
            for key, _, exp, over, _ in PANEL_DEFS:
                if exp != 1:
                    continue
                want = dict(BASELINE, **over)
                if all(close(vals[k], want[k]) for k in BASELINE):
                    hit = key
                    break
            if hit:
                groups[hit].append(r)
            else:
                unmatched.add(tuple(r.get(k, "").strip() for k in BASELINE))
        if unmatched:
            shown = "; ".join(f"pd={a},lambda_fa={b},r={c}" for a, b, c in sorted(unmatched)[:6])
            note(f"{s.path}: rows with (pd, lambda_fa, r) of no Fig. 6 panel are ignored: {shown}")
        for key, title, exp, _, pos in PANEL_DEFS:
            if exp == 1 and groups.get(key):
                self.panels.append(Panel(key, title, 1, pos, groups[key], s.path))
        if not any(groups.values()):
            note(f"{s.path}: no row matches an experiment-1 panel")

    def _add_large(self, exp, key, s):
        rows = s.rows
        if s.has("rows") and s.has("cols"):
            if exp == 3:
                keep = [r for r in rows if fnum(r.get("rows")) == fnum(r.get("cols"))]
            else:
                keep = [r for r in rows if fnum(r.get("cols")) == 3 or fnum(r.get("rows")) == 3]
            if keep and len(keep) < len(rows):
                note(f"{s.path}: {len(rows) - len(keep)} rows are not "
                     f"{'n×n' if exp == 3 else 'n×3'} grids; ignored")
                rows = keep
        pos = next(d[4] for d in PANEL_DEFS if d[0] == key)
        title = grid_title(rows) if s.has("rows") and s.has("cols") else f"experiment {exp}"
        self.panels.append(Panel(key, title, exp, pos, rows, s.path))

    def algorithms(self):
        seen = []
        for exp in (1, 2, 3):
            if exp in self.summaries:
                for r in self.summaries[exp].rows:
                    a = (r.get("algorithm") or "").strip()
                    if a and a not in seen:
                        seen.append(a)
        return seen

    def is_reference(self, spec, exp=None):
        """exact/ehm, or a SPEC meta.json names as the reference (of run exp, or of any run)."""
        if is_reference_family(spec):
            return True
        if exp is None:
            return spec in self.references
        return spec in self.references_by_exp.get(exp, ())

    def reference_note(self, spec):
        """'' / ' (reference)' / ' (reference in n×3, n×n)' for legend labels."""
        if not self.is_reference(spec):
            return ""
        used = [p for p in self.panels if spec in p.algorithms]
        if is_reference_family(spec) or all(self.is_reference(spec, p.exp) for p in used):
            return " (reference)"
        where = []
        for p in used:
            if self.is_reference(spec, p.exp) and p.exp not in where:
                where.append(p.exp)
        names = {1: "2×3", 2: "n×3", 3: "n×n"}
        return " (ref. in " + ", ".join(names[e] for e in where) + ")"


# ----------------------------------------------------------------------------- styles


def paper_styles(algorithms):
    """fig6.assign_styles, then the paper's fixed line style per canonical variant value."""
    styles, order = fig6.assign_styles(algorithms)
    # legend order fixed as in the paper's caption, whatever order the runs list the algorithms in
    rank = {f: i for i, f in enumerate(("exact", "ehm", "bp", "lmipda", "baa", "mcmcda", "cd", "jt"))}
    order = sorted(order, key=lambda s: (rank.get(family_key(s), len(rank)), order.index(s)))
    used = {}
    for spec in order:
        fam = family_key(spec)
        if fam not in CANONICAL_LS:
            continue
        v = order_value(spec)
        ls = None
        for cv, cls in CANONICAL_LS[fam].items():
            if not math.isnan(v) and close(v, cv, 1e-9):
                ls = cls
                break
        taken = used.setdefault(fam, [])
        if ls is None or ls in taken:  # another value, or a second instance of the same one
            ls = next(s for s in EXTRA_LS + [":"] if s not in taken or s == ":")
        taken.append(ls)
        styles[spec]["ls"] = ls
    return styles, order


def pretty_label(spec):
    name, kv = fig6.spec_parts(spec)
    fam = family_key(spec)
    if fam is None:
        return spec
    parts = [DISPLAY.get(fam, name)]
    v = order_value(spec)
    if fam == "mcmcda" and not math.isnan(v):
        parts.append(f"{fig6.fmt_value(str(v)) if v >= 1e5 else f'{v:g}'} samples")
    elif fam == "cd" and not math.isnan(v):
        parts.append(f"t = {v:g}")
    elif fam == "jt" and not math.isnan(v):
        parts.append(f"threshold {fig6.fmt_value(str(v)) if v < 1e-3 else f'{v:g}'}")
    label = " ".join(parts)
    extra = other_params(spec)
    if extra:
        label += " (" + ", ".join(extra) + ")"
    return label


# ----------------------------------------------------------------------------- command line


def add_input_arguments(ap):
    """--exp1, --exp1-extra, --exp2, --exp3: the runs of the three experiments (the options of
    this script and of experiments/bp_paper/rules.py); read them with read_inputs."""
    ap.add_argument("--exp1", metavar="CSV", help="summary.csv of experiment 1 (2×3 grid, seven panels)")
    ap.add_argument("--exp1-extra", metavar="CSV", action="append", default=[],
                    help="summary.csv of another experiment-1 run over the same points; adds the "
                         "algorithms --exp1 lacks (repeatable)")
    ap.add_argument("--exp2", metavar="CSV", help="summary.csv of experiment 2 (n×3 grids)")
    ap.add_argument("--exp3", metavar="CSV", help="summary.csv of experiment 3 (n×n grids)")


def read_inputs(args):
    """PaperData of the runs add_input_arguments' options name; exit 2 when none is given."""
    if not (args.exp1 or args.exp2 or args.exp3):
        fail("no input: give at least one of --exp1, --exp2, --exp3")
    return PaperData(args.exp1, args.exp2, args.exp3, args.exp1_extra)


def parse_args(argv):
    """fig6_paper.py's command line."""
    ap = argparse.ArgumentParser(
        prog=fig6.PROG,
        description="The complete Fig. 6 of Williams & Lau 2014 from the runs of its three experiments.")
    add_input_arguments(ap)
    ap.add_argument("--out", help="output PNG (an SVG is written next to it; default: fig6_paper.png "
                                  "next to the first input)")
    ap.add_argument("--metric", default="max_error", help="error metric of the error rows (default max_error)")
    ap.add_argument("--show-reference-error", action="store_true",
                    help="draw the error of exact/ehm references too (normally time rows only)")
    ap.add_argument("--independent-y", action="store_true",
                    help="own y range per panel instead of one range for all error and one for all time axes")
    ap.add_argument("--time-unit", choices=("auto", "us", "ms", "s"), default="auto",
                    help="unit of the time rows (auto: by the median time drawn)")
    ap.add_argument("--error-floor", type=float, default=1e-5, metavar="Y",
                    help="lowest y of the error axes (default 1e-5; 0 = fit the data); smaller "
                         "errors run off the bottom")
    fig6.add_time_stat_argument(ap)
    ap.add_argument("--no-bands", action="store_true", help="no bands (±2 standard errors, time percentiles)")
    ap.add_argument("--title", help="figure title")
    return ap.parse_args(argv)


def load_data(args):
    """The panels of the inputs; exits 2 when there is none, notes inputs that lack a column drawn."""
    data = read_inputs(args)
    if not data.panels:
        fail("no Fig. 6 panel found in the inputs")
    mcol = f"{args.metric}_mean"
    for s in data.summaries.values():
        if not s.has(mcol):
            note(f"{s.path}: no column '{mcol}'; its error axes will be empty")
        if not s.has(f"time_us_{args.time_stat}"):
            note(f"{s.path}: no column 'time_us_{args.time_stat}'; its time axes will be empty")
    return data


# ----------------------------------------------------------------------------- figure

TIME_UNITS = {"us": (1.0, "µs"), "ms": (1e3, "ms"), "s": (1e6, "s")}


def choose_time_unit(data, requested, time_col):
    """The time rows' unit: --time-unit, else (auto) by the median of the times drawn."""
    if requested != "auto":
        return requested
    vals = [fnum(r.get(time_col)) for p in data.panels for r in p.rows]
    vals = [v for v in vals if v > 0]
    if not vals:
        return "us"
    med = float(np.median(vals))
    return "us" if med < 1e3 else ("ms" if med < 1e6 else "s")



class Layout:
    """The figure and its grid of the panels present: panel rows and columns left empty are dropped;
    each panel's cell holds an error axes above a time axes."""

    def __init__(self, data):
        self.prows = sorted({p.pos[0] for p in data.panels})
        self.pcols = sorted({p.pos[1] for p in data.panels})
        self.nr, self.nc = len(self.prows), len(self.pcols)
        if self.nr * self.nc == 1:
            self.figsize = (5.6, 5.2)
        else:
            self.figsize = (4.45 * self.nc + 0.6, 4.6 * self.nr + 1.2)
        self.fig = plt.figure(figsize=self.figsize, layout="constrained")
        self.fig.get_layout_engine().set(h_pad=0.05, w_pad=0.05, hspace=0.035, wspace=0.03)
        self.outer = self.fig.add_gridspec(self.nr, self.nc)

    def panel_axes(self, p):
        """The error and time axes of panel p (the time axes shares the error axes' x)."""
        cell = self.outer[self.prows.index(p.pos[0]), self.pcols.index(p.pos[1])].subgridspec(2, 1, hspace=0.0)
        ax_e = self.fig.add_subplot(cell[0])
        ax_t = self.fig.add_subplot(cell[1], sharex=ax_e)
        return ax_e, ax_t


class Drawn:
    """What the panels drew: per panel (panel, error axes, time axes, error values, time values),
    and the algorithms with an error / a time line somewhere (for the legend)."""

    def __init__(self):
        self.axes = []
        self.err, self.time = set(), set()


def draw_panel(p, ax_e, ax_t, styles, legend_order, args, scale, drawn):
    """Panel p's lines: every algorithm's --metric (not the references' unless
    --show-reference-error) above its time per problem in the time unit (scale: µs per unit)."""
    mcol, mse = f"{args.metric}_mean", f"{args.metric}_se"
    ev, tv = [], []
    for spec in legend_order:
        if spec not in p.algorithms:
            continue
        st = styles[spec]
        band = not args.no_bands
        if args.show_reference_error or not is_reference_family(spec):
            xs, ys, ses = p.series(spec, mcol, mse)
            y = fig6.plot_series(ax_e, xs, ys, ses, st, band=band)
            if y.size:
                drawn.err.add(spec)
                ev.append(y)
        xs, ys, ses, lo, hi = fig6.time_series(lambda col, se_col: p.series(spec, col, se_col), args.time_stat)
        if lo is not None:
            lo, hi = lo / scale, hi / scale
        y = fig6.plot_series(ax_t, xs, ys / scale, ses / scale, st, band=band, lo=lo, hi=hi)
        if y.size:
            drawn.time.add(spec)
            tv += [y] + (fig6.band_values(ys, lo, hi) if band else [])
    drawn.axes.append((p, ax_e, ax_t, ev, tv))


def set_x_range(p, ax_e, ax_t):
    """x range of panel p's axes: its x values with 2 % padding, or one tick at a single value."""
    xs = [p.x_of(r) for r in p.rows if not math.isnan(p.x_of(r))]
    if xs:
        lo, hi = min(xs), max(xs)
        if hi > lo:
            pad = 0.02 * (hi - lo)
            ax_e.set_xlim(lo - pad, hi + pad)
        else:
            half = abs(lo) * 0.5 if lo else 1.0
            ax_e.set_xlim(lo - half, lo + half)
            ax_t.set_xticks([lo])


def finish_panel(p, ax_e, ax_t, lim_e, lim_t, y_labels):
    """Panel p's y ranges (None: no data), x range, grid, grey background (experiments 2 and 3),
    labels (y_labels: (error, time) label, or None) and title."""
    fig6.finish_log_axis(ax_e, lim_e)
    fig6.finish_log_axis(ax_t, lim_t)
    set_x_range(p, ax_e, ax_t)
    ax_e.tick_params(labelbottom=False)
    for ax in (ax_e, ax_t):
        ax.grid(True, which="major", color="0.82" if p.shaded else "0.88", lw=0.6)
        ax.tick_params(labelsize=9)
        ax.set_axisbelow(True)
        if p.shaded:
            ax.set_facecolor("0.92")
    if y_labels is not None:
        ax_e.set_ylabel(y_labels[0], fontsize=9.5)
        ax_t.set_ylabel(y_labels[1], fontsize=9.5)
    ax_t.set_xlabel(p.x_label, fontsize=9.5, labelpad=1.5)
    ax_e.set_title(p.title, fontsize=11, pad=4)


def finish_panels(drawn, args, unit_label):
    """Every panel's axes: one y range for all error and one for all time axes unless
    --independent-y, the error axes cut at --error-floor; y labels on each figure row's leftmost
    panel (on every panel with --independent-y)."""
    all_e = [v for a in drawn.axes for v in a[3]]
    all_t = [v for a in drawn.axes for v in a[4]]
    leftmost = {}
    for p, *_ in drawn.axes:
        leftmost[p.pos[0]] = min(leftmost.get(p.pos[0], 9), p.pos[1])
    y_labels = (fig6.metric_label(args.metric), fig6.time_axis_label(args.time_stat, unit_label))
    for p, ax_e, ax_t, ev, tv in drawn.axes:
        lim_e = fig6.log_limits(ev if args.independent_y else all_e) if ev else None
        if lim_e is not None and args.error_floor > 0 and lim_e[0] < args.error_floor:
            lim_e = (args.error_floor, max(lim_e[1], args.error_floor * 10))
        lim_t = fig6.log_limits(tv if args.independent_y else all_t) if tv else None
        labelled = p.pos[1] == leftmost[p.pos[0]] or args.independent_y
        finish_panel(p, ax_e, ax_t, lim_e, lim_t, y_labels if labelled else None)


def figure_title(data, args, nc):
    """--title, else the figure's title: what the rows show, then which panels are which (one
    clause per line, wrapped, when the figure has fewer than three panel columns)."""
    if args.title is not None:
        return args.title
    title = ("Fig. 6 (Williams & Lau 2014): average max marginal error and "
             if args.metric == "max_error" else
             f"Fig. 6 (Williams & Lau 2014): {fig6.metric_label(args.metric)} and ") + \
            ("average time per problem (±2 SE)" if args.time_stat == "mean" else
             "median time per problem (5–95\u00a0% band)")
    sub = []
    if any(p.exp == 1 for p in data.panels):
        sub.append("white: six targets (2×3 grid) vs spacing, baseline $P_d$ = 0.6, "
                   "$\\lambda_{fa}$ = 0.01, $r$ = 1, one parameter changed per panel")
    if any(p.shaded for p in data.panels):
        sub.append("grey: number of targets varied at the baseline parameters")
    if sub:
        title += "\n" + "; ".join(sub)
    if nc < 3:  # narrow figure: one clause per line, wrapped
        width = 48 if nc == 1 else 80
        lines = []
        for part in title.replace("; ", "\n").split("\n"):
            lines += textwrap.wrap(part, width) or [""]
        title = "\n".join(lines)
    return title


def legend_entries(data, styles, legend_order, drawn, metric):
    """Legend handles and labels in the caption's order: the paper's names, the references marked,
    "(no data)" for algorithms drawn nowhere (noted on stderr, as are ones in the time rows only)."""
    handles, labels = [], []
    for spec in legend_order:
        st = styles[spec]
        handles.append(fig6.legend_handle(st, ms=6, lw=st["lw"] + 0.2, mew=1.1))
        label = pretty_label(spec)
        label += data.reference_note(spec)
        if spec not in drawn.err and spec not in drawn.time:
            label += " (no data)"
            note(f"{spec}: no plottable value (all skipped, missing or zero)")
        elif spec not in drawn.err and not data.is_reference(spec) and drawn.err:
            note(f"{spec}: {metric} zero or missing everywhere; time rows only")
        labels.append(label)
    if len(set(labels)) < len(labels):  # two SPECs with one pretty label: use the SPECs
        labels = [lab if labels.count(lab) == 1 else f"{lab} [{spec}]" for lab, spec in zip(labels, legend_order)]
    return handles, labels


def legend_columns(handles, labels, legend_order, width):
    """One legend column per family group (references, BP, LMIPDA, BAA | MCMCDA | CD | JT | others),
    padded with blank entries, as long as the columns fit the figure width (inches); else the
    entries fill column by column. Returns the handles, labels and number of columns."""
    group_of = {"exact": 0, "ehm": 0, "bp": 0, "lmipda": 0, "baa": 0, "mcmcda": 1, "cd": 2, "jt": 3}
    groups = {}
    for h, lab, spec in zip(handles, labels, legend_order):
        groups.setdefault(group_of.get(family_key(spec), 4), []).append((h, lab))
    groups = [groups[k] for k in sorted(groups)]
    longest = max(len(re.sub(r"[$\\{}^_]", "", s)) for s in labels) if labels else 10
    col_in = 0.75 + 0.065 * longest
    fit = max(1, int(width // col_in))
    if 1 < len(groups) <= fit:
        depth = max(len(g) for g in groups)
        blank = Line2D([], [], lw=0, marker=None)
        handles, labels = [], []
        for g in groups:
            g = g + [(blank, "")] * (depth - len(g))
            handles += [h for h, _ in g]
            labels += [lab for _, lab in g]
        return handles, labels, len(groups)
    return handles, labels, max(1, min(len(labels), fit))


def add_legend(layout, data, styles, legend_order, drawn, args):
    """One legend for the whole figure, below the panels."""
    handles, labels = legend_entries(data, styles, legend_order, drawn, args.metric)
    handles, labels, ncol_leg = legend_columns(handles, labels, legend_order, layout.figsize[0])
    if handles:
        layout.fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=ncol_leg,
                          frameon=False, fontsize=10, handlelength=3.2, columnspacing=2.0)


def output_path(args):
    """--out, else fig6_paper.png next to the first input."""
    if args.out:
        return args.out
    first = next(p for p in (args.exp1, args.exp2, args.exp3) if p)
    return os.path.join(os.path.dirname(os.path.abspath(first)), "fig6_paper.png")


def main(argv=None):
    """Read the runs, draw every panel, finish the axes, title and legend, write PNG and SVG."""
    args = parse_args(argv)
    data = load_data(args)
    styles, legend_order = paper_styles(data.algorithms())
    unit = choose_time_unit(data, args.time_unit, f"time_us_{args.time_stat}")
    scale, unit_label = TIME_UNITS[unit]
    layout = Layout(data)
    drawn = Drawn()
    for p in data.panels:
        ax_e, ax_t = layout.panel_axes(p)
        draw_panel(p, ax_e, ax_t, styles, legend_order, args, scale, drawn)
    finish_panels(drawn, args, unit_label)
    title = figure_title(data, args, layout.nc)
    if title:
        layout.fig.suptitle(title, fontsize=12)
    add_legend(layout, data, styles, legend_order, drawn, args)
    fig6.write_figure(layout.fig, output_path(args))
    return 0


if __name__ == "__main__":
    sys.exit(main())
