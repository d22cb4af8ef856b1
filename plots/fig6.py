#!/usr/bin/python3
"""Fig. 6 of Williams & Lau 2014 (bp-marginal-association): marginal error and time vs. a sweep.

Usage:
  /usr/bin/python3 -m plots.fig6 RUN_DIR/summary.csv [--x spacing] [--out RUN_DIR/fig6.png]
                   [--metric max_error] [--title TEXT] [--where KEY=VALUE ...] [--independent-y]
                   [--time-stat median|mean]

Reads the `summary.csv` written by `dabench run` (one row per (point, algorithm): `point`, the
scenario parameters, `algorithm`, `trials,ok,skipped,failed`, then M_count, M_mean, M_se,
M_median, M_p5, M_p95 for each metric M) and draws, per panel, the average of --metric (log y)
with the time per problem (log y) underneath, one line per algorithm, in the paper's styles.
Writes a PNG and an SVG with the same stem.

- Time rows (--time-stat): by default the median time per problem with its 5-95 % band
  (time_us_median, time_us_p5, time_us_p95): on a busy machine the mean is dominated by the
  rare calls another job preempts. `--time-stat mean` draws the paper's average time per
  problem with its +-2 standard error band instead. The axis label says which.

- x: --x, else the scenario parameter with the most distinct values. If x is `rows` or `cols`
  the x value is the number of targets (n_targets_mean, else rows*cols).
- Panels: one per combination of the other scenario parameters that vary in the file (a
  parameter in one-to-one correspondence with x, e.g. cols when rows = cols, follows x and does
  not split panels). Panels keep the file's order, three per figure row.
- Shaded band of the error rows: mean +- 2 standard errors (Monte Carlo noise). Points whose value is zero or
  missing are not drawn on the log axes; an algorithm whose error is zero or missing everywhere
  (the reference itself) is left out of the error row but kept in the time row.

Needs only the standard library, numpy and matplotlib (Debian's python3-matplotlib).
Exit status 2 with a one-line message on stderr when the input cannot be plotted.
"""

import argparse
import csv
import math
import os
import re
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

PROG = os.path.basename(sys.argv[0]) if sys.argv and sys.argv[0] else "fig6.py"

# ----------------------------------------------------------------------------- input helpers


def fail(msg):
    """One-line error on stderr, exit status 2."""
    print(f"{PROG}: error: {msg}", file=sys.stderr)
    sys.exit(2)


def note(msg):
    print(f"{PROG}: note: {msg}", file=sys.stderr)


def fnum(s):
    """CSV field -> float; empty, missing or unparsable -> NaN."""
    if s is None:
        return math.nan
    s = s.strip()
    if not s:
        return math.nan
    try:
        return float(s)
    except ValueError:
        return math.nan


def norm_key(s):
    """Grouping key of a parameter value: numbers compare as numbers ('0.10' == '0.1')."""
    s = (s or "").strip()
    try:
        v = float(s)
        return ("n", v)
    except ValueError:
        return ("s", s)


class Summary:
    """summary.csv as a list of dict rows plus the column roles."""

    def __init__(self, path):
        self.path = path
        try:
            with open(path, newline="", encoding="utf-8-sig") as f:
                reader = csv.DictReader(f)
                header = reader.fieldnames
                rows = [r for r in reader if any((v or "").strip() for v in r.values() if isinstance(v, str))]
        except OSError as e:
            fail(f"cannot read {path}: {e.strerror}")
        except csv.Error as e:
            fail(f"{path}: malformed CSV: {e}")
        if not header:
            fail(f"{path}: empty file (no header line)")
        header = [h.strip() for h in header]
        # DictReader keys are the raw header; re-key on stripped names
        rows = [{(k or "").strip(): v for k, v in r.items() if k is not None} for r in rows]
        if "algorithm" not in header:
            fail(f"{path}: no 'algorithm' column (header: {','.join(header[:12])}...)")
        if not rows:
            fail(f"{path}: no data rows")
        self.header = header
        self.columns = set(header)
        ai = header.index("algorithm")
        self.params = [c for c in header[:ai] if c and c != "point"]
        self.rows = rows

    def has(self, col):
        return col in self.columns

    def distinct(self, col, rows=None):
        """Distinct normalised values of col, in order of first appearance."""
        seen = {}
        for r in self.rows if rows is None else rows:
            k = norm_key(r.get(col))
            if k not in seen:
                seen[k] = r.get(col)
        return seen


def parse_where(items, summary):
    """['pd=0.9', 'r=1,lambda_fa=0.01'] -> [(col, key)]; unknown columns are errors."""
    out = []
    for item in items or []:
        for part in item.split(","):
            part = part.strip()
            if not part:
                continue
            if "=" not in part:
                fail(f"--where '{part}': expected KEY=VALUE")
            k, v = (s.strip() for s in part.split("=", 1))
            if not summary.has(k):
                fail(f"--where '{part}': no column '{k}' in {summary.path}")
            out.append((k, norm_key(v)))
    return out


def apply_where(rows, where):
    def keep(r):
        for k, key in where:
            rk = norm_key(r.get(k))
            if key[0] == "n" and rk[0] == "n":
                if not math.isclose(key[1], rk[1], rel_tol=1e-9, abs_tol=1e-12):
                    return False
            elif rk != key:
                return False
        return True

    return [r for r in rows if keep(r)]


# ----------------------------------------------------------------------------- sweep structure

SYMBOLS = {
    "pd": r"$P_d$",
    "lambda_fa": r"$\lambda_{fa}$",
    "r": r"$r$",
    "q": r"$q$",
    "T": r"$T$",
    "spacing": "spacing",
    "steps": "steps",
    "gate_miss": "gate miss",
}

X_LABELS = {"spacing": "target spacing", "rows": "number of targets", "cols": "number of targets"}


def fmt_value(s):
    """'0.0316' -> '0.0316', '1e-05' -> '$10^{-5}$', '100000' -> '$10^{5}$' (exact powers only)."""
    v = fnum(s)
    if math.isnan(v):
        return (s or "").strip() or "?"
    if v != 0 and abs(v) >= 1e5 or 0 < abs(v) < 1e-3:
        e = math.log10(abs(v))
        if abs(e - round(e)) < 1e-9:
            return ("-" if v < 0 else "") + r"$10^{%d}$" % round(e)
        m, e = f"{v:.3g}".split("e")
        return r"$%s{\times}10^{%d}$" % (m, int(e))
    return f"{v:g}"


def choose_x(summary, rows, requested):
    params = summary.params
    if requested:
        if requested not in params:
            if summary.has(requested):
                fail(f"--x '{requested}' is not a scenario parameter (the columns before "
                     f"'algorithm': {','.join(params) or 'none'})")
            fail(f"{summary.path}: no column '{requested}' for the x axis "
                 f"(scenario parameters: {','.join(params) or 'none'})")
        return requested
    if not params:
        fail(f"{summary.path}: no scenario parameter columns before 'algorithm'; nothing to use as x")
    counts = {p: len(summary.distinct(p, rows)) for p in params}
    best = max(counts.values())
    cands = [p for p in params if counts[p] == best]
    for pref in ("spacing", "rows", "cols"):
        if pref in cands:
            return pref
    return cands[0]


def linked_to(x, p, rows):
    """True if p and x are in one-to-one correspondence over rows (p just follows x)."""
    fwd, back = {}, {}
    for r in rows:
        a, b = norm_key(r.get(x)), norm_key(r.get(p))
        if fwd.setdefault(a, b) != b or back.setdefault(b, a) != a:
            return False
    return True


class Sweep:
    """Panels, x values and per-(panel, algorithm) series of one summary file."""

    def __init__(self, summary, rows, x):
        self.summary, self.rows, self.x = summary, rows, x
        params = summary.params
        varying = [p for p in params if p != x and len(summary.distinct(p, rows)) > 1]
        self.linked = [p for p in varying if linked_to(x, p, rows)]
        self.panel_keys = [p for p in varying if p not in self.linked]
        self.fixed = [p for p in params if p != x and p not in varying]
        if all(fnum(r.get(x)) != fnum(r.get(x)) for r in rows):
            fail(f"{summary.path}: x column '{x}' has no numeric values")
        # panels in order of first appearance
        self.panels = []  # list of (key tuple, first row)
        self.panel_of = {}
        for r in rows:
            k = tuple(norm_key(r.get(p)) for p in self.panel_keys)
            if k not in self.panel_of:
                self.panel_of[k] = len(self.panels)
                self.panels.append((k, r))
        self.x_is_count = x in ("rows", "cols")
        self._x_of_point = self._point_x()

    def point_id(self, r):
        if self.summary.has("point") and (r.get("point") or "").strip():
            return ("p", r["point"].strip())
        return ("k", tuple(norm_key(r.get(p)) for p in self.summary.params))

    def _point_x(self):
        xs = {}
        if not self.x_is_count:
            for r in self.rows:
                xs.setdefault(self.point_id(r), fnum(r.get(self.x)))
            return xs
        for r in self.rows:  # number of targets: measured, else rows*cols, else the parameter
            pid = self.point_id(r)
            v = fnum(r.get("n_targets_mean"))
            if not math.isnan(v) and (pid not in xs or math.isnan(xs[pid][0])):
                xs[pid] = (v, 0)
            elif pid not in xs:
                rc = fnum(r.get("rows")) * fnum(r.get("cols"))
                xs[pid] = (rc if not math.isnan(rc) else fnum(r.get(self.x)), 1)
        return {k: v[0] for k, v in xs.items()}

    def x_of(self, r):
        return self._x_of_point[self.point_id(r)]

    def x_label(self):
        return X_LABELS.get(self.x, SYMBOLS.get(self.x, self.x))

    def algorithms(self):
        seen = []
        for r in self.rows:
            a = (r.get("algorithm") or "").strip()
            if a and a not in seen:
                seen.append(a)
        return seen

    def series(self, panel, algorithm, col, se_col=None):
        """Sorted (x, y, se) arrays for one panel/algorithm; NaN where missing."""
        pts = {}
        for r in self.rows:
            if (r.get("algorithm") or "").strip() != algorithm:
                continue
            if self.panel_of[tuple(norm_key(r.get(p)) for p in self.panel_keys)] != panel:
                continue
            xv = self.x_of(r)
            if math.isnan(xv):
                continue
            if xv in pts:
                note(f"{algorithm}: several rows at {self.x}={xv:g} in one panel; keeping the first "
                     f"(pass --where to select)")
                continue
            se = fnum(r.get(se_col)) if se_col else math.nan
            pts[xv] = (fnum(r.get(col)), se)
        xs = sorted(pts)
        return (np.array(xs, dtype=float), np.array([pts[k][0] for k in xs], dtype=float),
                np.array([pts[k][1] for k in xs], dtype=float))

    # --- titles
    def describe(self, row, keys, fixed=False):
        """Title parts like ['2×3 grid', '$P_d$ = 0.6'] for the parameters keys, values from row.

        rows and cols are shown together as 'rows×cols grid' ('n' for a dimension that is x or
        follows x); with fixed=True the grid is named whenever x counts targets ('n×3 grid')."""
        parts = []
        keys = list(keys)
        has_grid = "rows" in self.summary.params and "cols" in self.summary.params
        if has_grid and ("rows" in keys or "cols" in keys or (fixed and self.x_is_count)):
            def dim(k):
                return "n" if (k == self.x or k in self.linked) else fmt_value(row.get(k))
            parts.append(f"{dim('rows')}×{dim('cols')} grid")
            keys = [k for k in keys if k not in ("rows", "cols")]
        for k in keys:
            parts.append(f"{SYMBOLS.get(k, k)} = {fmt_value(row.get(k))}")
        return parts

    def panel_title(self, i):
        return ", ".join(self.describe(self.panels[i][1], self.panel_keys))

    def fixed_title(self):
        return self.describe(self.rows[0], self.fixed, fixed=True)


def wrap_parts(parts, width):
    """Join title parts with ', ', breaking lines between parts at about width characters."""
    lines, cur, cur_len = [], "", 0
    for p in parts:
        visible = len(re.sub(r"[$\\{}_^]|lambda", "", p))
        if cur and cur_len + 2 + visible > width:
            lines.append(cur + ",")
            cur, cur_len = p, visible
        elif cur:
            cur, cur_len = cur + ", " + p, cur_len + 2 + visible
        else:
            cur, cur_len = p, visible
    if cur:
        lines.append(cur)
    return "\n".join(lines)


# ----------------------------------------------------------------------------- styles

ORDERED_LS = ["-.", "--", "-", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)), (0, (8, 2))]
UNORDERED_LS = ["-", "--", "-.", ":", (0, (5, 1, 1, 1, 1, 1)), (0, (1, 1)), (0, (8, 2))]
FALLBACK_COLOURS = ["tab:orange", "tab:brown", "tab:purple", "tab:olive", "tab:gray", "tab:pink",
                    "#17becf", "#bcbd22", "#8c564b", "#e377c2"]
FALLBACK_MARKERS = ["D", "v", "p", "*", "h", "<", ">", "d", "P", "X"]

# family: (names, colour, marker, ordering parameters, ascending = more accurate later)
FAMILIES = [
    ("bp", ("bp",), "b", None, None, True),
    ("lmipda", ("lmipda",), "m", "^", None, True),
    ("baa", ("baa",), "c", "s", None, True),
    ("mcmcda", ("mcmcda",), "g", "o", ("samples", "iterations", "steps", "n_samples", "n"), True),
    ("cd", ("cd", "correlation_decay", "corrdecay"), "r", "+", ("depth", "t", "iterations", "levels"), True),
    ("jt", ("jt", "junction_tree", "junctiontree"), "k", "x", ("threshold", "thresh", "eps"), False),
    ("exact", ("exact",), "k", None, None, True),
    ("ehm", ("ehm", "ehm2"), "k", None, None, True),
]


def spec_parts(spec):
    name, _, rest = spec.partition(":")
    kv = {}
    for item in rest.split(","):
        if "=" in item:
            k, v = item.split("=", 1)
            kv[k.strip()] = v.strip()
    return name.strip(), kv


def family_of(name):
    low = name.lower()
    for fam in FAMILIES:
        for alias in fam[1]:
            if low == alias or re.match(re.escape(alias) + r"[-_.0-9]", low):
                return fam
    return None


def assign_styles(algorithms):
    """spec -> dict(color, ls, marker, lw, family_rank, variant_rank) and the legend order."""
    groups = {}  # family key -> list of specs (first-appearance order)
    fam_info = {}
    unknown = 0
    for spec in algorithms:
        name, _ = spec_parts(spec)
        fam = family_of(name)
        if fam is None:
            key = "?" + name.lower()
            if key not in fam_info:
                fam_info[key] = (key, (), FALLBACK_COLOURS[unknown % len(FALLBACK_COLOURS)],
                                 FALLBACK_MARKERS[unknown % len(FALLBACK_MARKERS)], None, True)
                unknown += 1
        else:
            key = fam[0]
            fam_info[key] = fam
        groups.setdefault(key, []).append(spec)
    styles, order = {}, []
    for key, specs in groups.items():
        _, _, colour, marker, order_params, ascending = fam_info[key]
        if order_params and len(specs) > 1:
            def rank_value(spec):
                kv = spec_parts(spec)[1]
                for p in order_params:
                    if p in kv and not math.isnan(fnum(kv[p])):
                        return fnum(kv[p]) if ascending else -fnum(kv[p])
                return math.inf  # no value given: after the ranked ones
            ranked = sorted(specs, key=lambda s: (rank_value(s), specs.index(s)))
            lss = ORDERED_LS
        else:
            ranked = specs
            lss = UNORDERED_LS
        for i, spec in enumerate(ranked):
            styles[spec] = dict(color=colour, ls=lss[i % len(lss)], marker=marker,
                                lw=1.6 if key == "bp" else 1.2)
            order.append(spec)
    return styles, order


# ----------------------------------------------------------------------------- plotting


def plot_series(ax, x, y, se, style, band=True, lo=None, hi=None):
    """Line of the positive finite points with a band: lo..hi where given (percentiles), else
    +-2 SE; returns the plotted y values."""
    ok = np.isfinite(x) & np.isfinite(y) & (y > 0)
    if not ok.any():
        return np.array([])
    x, y, se = x[ok], y[ok], se[ok]
    if lo is not None and hi is not None:
        lo, hi = lo[ok], hi[ok]
    marker = style["marker"]
    if marker is None and len(x) == 1:
        marker = "o"  # a lone point of a plain line would be invisible
        style["lone"] = True  # the legend shows the marker too
    filled = marker in ("+", "x", "*", "P", "X")
    ax.plot(x, y, color=style["color"], ls=style["ls"], lw=style["lw"], marker=marker,
            ms=4.5 if marker not in ("+", "x") else 5.5, mew=1.0,
            mfc=style["color"] if filled else "none", zorder=3)
    if band and lo is not None and hi is not None:
        drawn = np.isfinite(lo) & np.isfinite(hi) & (hi > 0)
        if drawn.any():
            lo = np.where(drawn & (lo > 0), lo, np.nan)  # clipped to the axis bottom later
            ax.fill_between(x, lo, np.where(drawn, hi, np.nan), color=style["color"], alpha=0.12, lw=0,
                            zorder=2)
    elif band:
        sev = np.where(np.isfinite(se) & (se > 0), se, 0.0)
        if (sev > 0).any():
            lo = y - 2 * sev
            lo = np.where(lo > 0, lo, np.nan)  # clipped to the axis bottom later
            ax.fill_between(x, lo, y + 2 * sev, color=style["color"], alpha=0.12, lw=0, zorder=2)
    return y


# --time-stat: the time rows' statistic, its band's columns (None: +-2 SE) and axis words.
TIME_STATS = {
    "median": dict(column="median", band=("p5", "p95"), word="median", band_text="5–95\u00a0% band"),
    "mean": dict(column="mean", band=None, word="avg.", band_text="±2 SE"),
}


def add_time_stat_argument(ap):
    ap.add_argument("--time-stat", choices=tuple(TIME_STATS), default="median",
                    help="time rows: the median per problem with its 5-95 %% band (default; robust to "
                         "preemption spikes on a busy machine), or the mean with +-2 standard errors "
                         "as in the paper")


def time_series(series, stat, base="time_us"):
    """(x, y, se, lo, hi) of the time statistic `stat` of metric `base`, from a series(col, se_col)
    function returning (x, y, se); lo, hi are None for the mean (its band is +-2 SE)."""
    info = TIME_STATS[stat]
    xs, ys, ses = series(f"{base}_{info['column']}", f"{base}_se" if info["band"] is None else None)
    if info["band"] is None:
        return xs, ys, ses, None, None
    _, lo, _ = series(f"{base}_{info['band'][0]}", None)
    _, hi, _ = series(f"{base}_{info['band'][1]}", None)
    return xs, ys, ses, lo, hi


def band_values(y, lo, hi):
    """The percentile band's edges where y is drawn, for the axis limits (none for +-2 SE)."""
    if lo is None or hi is None:
        return []
    drawn = np.isfinite(y) & (y > 0)
    return [lo[drawn], hi[drawn]]


def time_axis_label(stat, unit="µs", what="time"):
    """Two lines: the statistic and unit, then the band, e.g. 'median time (µs)' / '5–95 % band'."""
    info = TIME_STATS[stat]
    return f"{info['word']} {what} ({unit})\n{info['band_text']}"


def log_limits(values, pad=1.6):
    v = np.concatenate([np.asarray(a, dtype=float) for a in values]) if values else np.array([])
    v = v[np.isfinite(v) & (v > 0)]
    if v.size == 0:
        return None
    lo, hi = v.min() / pad, v.max() * pad
    if hi / lo < 10 ** 1.5:  # 1.5 decades at least: a labelled power of ten is always inside
        mid = math.sqrt(lo * hi)
        lo, hi = mid / 10 ** 0.75, mid * 10 ** 0.75
    return lo, hi


def finish_log_axis(ax, lim, fill_lower=True):
    if lim is None:
        ax.set_yscale("linear")
        ax.set_yticks([])
        ax.text(0.5, 0.5, "no data", transform=ax.transAxes, ha="center", va="center",
                color="0.5", fontsize=9)
        return
    ax.set_yscale("log")
    ax.set_ylim(*lim)
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    if fill_lower:  # bands whose lower edge was <= 0 reach down to the axis bottom
        for coll in ax.collections:
            for path in coll.get_paths():
                verts = path.vertices
                bad = ~np.isfinite(verts[:, 1])
                if bad.any():
                    verts[bad, 1] = lim[0]


def metric_label(metric):
    return {
        "max_error": "avg. max marginal error",
        "mean_error": "avg. mean abs. marginal error",
        "iterations": "iterations",
        "w_star": r"$W_*$",
    }.get(metric, metric.replace("_", " "))


def save_both(fig, out):
    base, ext = os.path.splitext(out)
    if ext.lower() not in (".png", ".svg"):
        base = out
    d = os.path.dirname(os.path.abspath(base))
    os.makedirs(d, exist_ok=True)
    written = []
    umask = os.umask(0)
    os.umask(umask)
    for fmt in ("png", "svg"):
        target = f"{base}.{fmt}"
        fd, tmp = tempfile.mkstemp(prefix=".fig-", suffix="." + fmt, dir=d)
        os.close(fd)
        try:
            fig.savefig(tmp, format=fmt, dpi=200, bbox_inches="tight", pad_inches=0.05)
            os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the usual permissions
            os.replace(tmp, target)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
        written.append(target)
    return written


def write_figure(fig, out):
    """Save fig as PNG and SVG (save_both), print the paths written and close the figure."""
    for w in save_both(fig, out):
        print(w)
    plt.close(fig)


def legend_handle(style, ms, lw, mew):
    """The legend's line for an algorithm's style: its marker ('o' where a lone point got one), of
    size ms (ms + 1 for '+' and 'x'), filled only for the line-drawn markers."""
    marker = style["marker"] or ("o" if style.get("lone") else None)
    filled = marker in ("+", "x", "*", "P", "X")
    return Line2D([], [], color=style["color"], ls=style["ls"], lw=lw, marker=marker,
                  ms=ms if marker not in ("+", "x") else ms + 1, mew=mew,
                  mfc=style["color"] if filled else "none")


# ----------------------------------------------------------------------------- the figure (main)


def parse_args(argv):
    """fig6.py's command line."""
    ap = argparse.ArgumentParser(
        prog=PROG, description="Fig. 6: marginal error and computation time versus a sweep.")
    ap.add_argument("summary", help="summary.csv written by `dabench run`")
    ap.add_argument("--x", help="scenario parameter on the x axis (default: the one with most values)")
    ap.add_argument("--out", help="output PNG (an SVG is written next to it; default: fig6.png "
                                  "next to the summary)")
    ap.add_argument("--metric", default="max_error", help="error metric for the upper rows (default max_error)")
    ap.add_argument("--title", help="figure title (single panel: the panel title)")
    ap.add_argument("--where", action="append", metavar="KEY=VALUE",
                    help="keep only rows with KEY=VALUE (repeatable, or comma-separated)")
    ap.add_argument("--independent-y", action="store_true",
                    help="own y range per panel instead of one range per row kind")
    ap.add_argument("--max-panels", type=int, default=24, metavar="N",
                    help="refuse to draw more than N panels (default 24)")
    add_time_stat_argument(ap)
    return ap.parse_args(argv)


def load_sweep(args):
    """The rows --where keeps, split into panels along the x axis; notes the columns the figure
    lacks, exits 2 when nothing is left or there are more than --max-panels panels."""
    summary = Summary(args.summary)
    rows = apply_where(summary.rows, parse_where(args.where, summary))
    if not rows:
        fail(f"no rows of {args.summary} match --where {' '.join(args.where)}")
    x = choose_x(summary, rows, args.x)
    sweep = Sweep(summary, rows, x)
    mcol = f"{args.metric}_mean"
    if not summary.has(mcol):
        note(f"no column '{mcol}' in {args.summary}; the error rows will be empty")
    elif not any(fnum(r.get(mcol)) > 0 for r in rows):
        note(f"no positive value in '{mcol}'; the error rows will be empty")
    time_col = f"time_us_{TIME_STATS[args.time_stat]['column']}"
    if not summary.has(time_col):
        note(f"no column '{time_col}' in {args.summary}; the time rows will be empty")

    if len(sweep.panels) > args.max_panels:
        fail(f"{len(sweep.panels)} panels (one per combination of "
             f"{','.join(sweep.panel_keys)}) exceed --max-panels {args.max_panels}; "
             f"select rows with --where or choose another --x")
    return sweep


class Layout:
    """The figure and its grid: three panels per figure row, each an error axes above a time axes."""

    def __init__(self, npan):
        self.npan = npan
        self.ncols = min(3, npan)
        nprow = math.ceil(npan / self.ncols)
        if npan == 1:
            self.figsize = (5.6, 5.0)
        else:
            self.figsize = (3.45 * self.ncols + 0.5, 3.9 * nprow + 0.4)
        self.fig = plt.figure(figsize=self.figsize, layout="constrained")
        self.fig.get_layout_engine().set(h_pad=0.04, w_pad=0.04, hspace=0.02, wspace=0.02)
        self.gs = self.fig.add_gridspec(2 * nprow, self.ncols)

    def panel_axes(self, i):
        """The error and time axes of panel i (the time axes shares the error axes' x)."""
        pr, c = divmod(i, self.ncols)
        ax_e = self.fig.add_subplot(self.gs[2 * pr, c])
        ax_t = self.fig.add_subplot(self.gs[2 * pr + 1, c], sharex=ax_e)
        return ax_e, ax_t


class Drawn:
    """What the panels drew: their axes, the y values per panel (for the limits) and the
    algorithms with an error / a time line somewhere (for the legend)."""

    def __init__(self):
        self.err_axes, self.time_axes, self.err_vals, self.time_vals = [], [], [], []
        self.err, self.time = set(), set()


def draw_panel(sweep, i, ax_e, ax_t, styles, legend_order, args, drawn):
    """Panel i's lines: every algorithm's --metric above its time per problem."""
    mcol, mse = f"{args.metric}_mean", f"{args.metric}_se"
    ev, tv = [], []
    for spec in legend_order:
        xs, ys, ses = sweep.series(i, spec, mcol, mse)
        if xs.size == 0:
            continue
        y = plot_series(ax_e, xs, ys, ses, styles[spec])
        if y.size:
            drawn.err.add(spec)
            ev.append(y)
        xs, ys, ses, lo, hi = time_series(lambda col, se_col: sweep.series(i, spec, col, se_col),
                                          args.time_stat)
        y = plot_series(ax_t, xs, ys, ses, styles[spec], lo=lo, hi=hi)
        if y.size:
            drawn.time.add(spec)
            tv += [y] + band_values(ys, lo, hi)
    drawn.err_axes.append(ax_e)
    drawn.time_axes.append(ax_t)
    drawn.err_vals.append(ev)
    drawn.time_vals.append(tv)


def finish_panel(sweep, i, layout, drawn, lims, single_x, args):
    """Panel i's log y ranges (lims: the shared ranges' values), x range, grid, labels and title."""
    ax_e, ax_t = drawn.err_axes[i], drawn.time_axes[i]
    all_e, all_t = lims
    lim_e = log_limits(drawn.err_vals[i] if args.independent_y else all_e) if drawn.err_vals[i] else None
    lim_t = log_limits(drawn.time_vals[i] if args.independent_y else all_t) if drawn.time_vals[i] else None
    finish_log_axis(ax_e, lim_e)
    finish_log_axis(ax_t, lim_t)
    ax_e.margins(x=0.02)
    if single_x is not None:  # no sweep: one tick at the value instead of a zoomed axis
        half = abs(single_x) * 0.5 if single_x else 1.0
        ax_e.set_xlim(single_x - half, single_x + half)
        ax_t.set_xticks([single_x])
    ax_e.tick_params(labelbottom=False)
    for ax in (ax_e, ax_t):
        ax.grid(True, which="major", color="0.88", lw=0.6)
        ax.tick_params(labelsize=8.5)
        ax.set_axisbelow(True)
    c = i % layout.ncols
    if c == 0 or args.independent_y:
        ax_e.set_ylabel(metric_label(args.metric), fontsize=9)
        ax_t.set_ylabel(time_axis_label(args.time_stat), fontsize=9)
    if c != 0 and not args.independent_y:
        if lim_e is not None:
            ax_e.tick_params(labelleft=False)
        if lim_t is not None:
            ax_t.tick_params(labelleft=False)
    below = i + layout.ncols < layout.npan
    if not below:
        ax_t.set_xlabel(sweep.x_label(), fontsize=9)
    if layout.npan > 1:
        ax_e.set_title(sweep.panel_title(i), fontsize=9.5)


def finish_panels(sweep, layout, drawn, args):
    """Axis ranges, labels and titles of every panel: one y range per row kind unless
    --independent-y, one x tick when the rows hold a single x value."""
    xs_all = {xv for r in sweep.rows for xv in [sweep.x_of(r)] if not math.isnan(xv)}
    single_x = next(iter(xs_all)) if len(xs_all) == 1 else None
    all_e = [v for ev in drawn.err_vals for v in ev]
    all_t = [v for tv in drawn.time_vals for v in tv]
    for i in range(layout.npan):
        finish_panel(sweep, i, layout, drawn, (all_e, all_t), single_x, args)


def add_title(sweep, layout, drawn, args):
    """--title, else the fixed parameters: the panel's title for one panel, else the figure's."""
    if layout.npan == 1:
        title = args.title or wrap_parts(sweep.fixed_title(), 60)
        if title:
            drawn.err_axes[0].set_title(title, fontsize=10)
    else:
        title = args.title or wrap_parts(sweep.fixed_title(), int(22 * layout.ncols))
        if title:
            layout.fig.suptitle(title, fontsize=10.5)


def add_legend(layout, styles, legend_order, drawn, args):
    """One legend below the panels: every algorithm, in family order; ones with no data anywhere
    are marked (and noted on stderr, as are ones drawn in the time rows only)."""
    handles, labels = [], []
    for spec in legend_order:
        handles.append(legend_handle(styles[spec], ms=5, lw=styles[spec]["lw"], mew=1.0))
        label = spec
        if spec not in drawn.err and spec not in drawn.time:
            label += " (no data)"
            note(f"{spec}: no plottable value (all skipped, missing or zero)")
        elif spec not in drawn.err and drawn.err:
            note(f"{spec}: {args.metric} zero or missing everywhere (the reference?); time row only")
        labels.append(label)
    longest = max(len(s) for s in labels) if labels else 10
    col_in = 0.7 + 0.065 * longest
    ncol_leg = max(1, min(len(labels), int(layout.figsize[0] // col_in)))
    if handles:
        layout.fig.legend(handles, labels, loc="upper center", bbox_to_anchor=(0.5, 0.0), ncol=ncol_leg,
                          frameon=False, fontsize=8.5, handlelength=3.2, columnspacing=1.6)


def main(argv=None):
    """Read, draw every panel, finish the axes, title and legend, write PNG and SVG."""
    args = parse_args(argv)
    sweep = load_sweep(args)
    styles, legend_order = assign_styles(sweep.algorithms())
    layout = Layout(len(sweep.panels))
    drawn = Drawn()
    for i in range(layout.npan):
        ax_e, ax_t = layout.panel_axes(i)
        draw_panel(sweep, i, ax_e, ax_t, styles, legend_order, args, drawn)
    finish_panels(sweep, layout, drawn, args)
    add_title(sweep, layout, drawn, args)
    add_legend(layout, styles, legend_order, drawn, args)
    out = args.out or os.path.join(os.path.dirname(os.path.abspath(args.summary)), "fig6.png")
    write_figure(layout.fig, out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
