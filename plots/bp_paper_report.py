#!/usr/bin/python3
"""Section V-B of Williams & Lau 2014 (bp-marginal-association): every quantitative claim next to
the measured numbers, as a Markdown table with a verdict per claim.

Usage:
  /usr/bin/python3 plots/bp_paper_report.py [--exp1 RUN1/summary.csv] [--exp2 RUN2/summary.csv]
                   [--exp3 RUN3/summary.csv] [--out report.md] [--no-trials]

Inputs are the summary.csv files of the paper's three experiments (as for fig6_paper.py, whose
data model this script uses: panels are identified the same way). When a run folder also holds
trials.csv, it is streamed (never loaded whole) for the maximum BP iteration count and the
reasons of skipped trials; --no-trials skips that.

Verdicts: "agrees" / "differs" by the rule stated with each claim (in the comment above its
function, and printed under "Rules and details"); "not run" when the algorithms or experiments
a claim is about are absent from the inputs; "inconclusive" when the inputs cannot decide (only
for the iteration maximum without trials.csv). Words of the paper are turned into numbers by
fixed conventions, used throughout:
  - "k orders of magnitude": log10 of the ratio rounds to k, i.e. lies in [k - 0.5, k + 0.5);
    "a-b orders" is [a - 0.5, b + 0.5).
  - "similar"/"comparable": within a factor of 2 either way; "much better/worse": a factor of 3.
  - "most"/"generally": at least two thirds of the cases; "often"/"many": at least a quarter or
    a third as stated; values the paper gives are compared at its precision (0.015 -> < 0.0155).
  - A ratio "per panel" is the median over the panel's x values (spacings or target counts) at
    which both algorithms have a value; an "overall" ratio is the median of the per-panel ones.
  - A sweep point "could not be completed" when the algorithm has no row there, or more than
    half of its trials were skipped or failed.
Rows whose trials were all skipped or failed carry no values (as in the figure).

Needs only the standard library (and fig6_paper.py / fig6.py, which import numpy/matplotlib).
"""

import argparse
import csv
import math
import os
import statistics
import sys
from collections import Counter

sys.dont_write_bytecode = True
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fig6_paper as fp  # noqa: E402
from fig6 import fail, fnum, note  # noqa: E402

SHORT = {"baseline": "baseline", "lambda_fa=0.0316": "λfa 0.0316", "lambda_fa=0.1": "λfa 0.1",
         "pd=0.3": "Pd 0.3", "pd=0.9": "Pd 0.9", "r=0.1": "r 0.1", "r=10": "r 10",
         "3xn": "n×3", "nxn": "n×n"}
EXP1 = fp.EXP1_KEYS
LARGE = ["3xn", "nxn"]
ALL = EXP1[:3] + EXP1[3:5] + ["3xn"] + EXP1[5:] + ["nxn"]

AGREES, DIFFERS, NOT_RUN, INCONCLUSIVE = "agrees", "differs", "not run", "inconclusive"


def g3(v):
    if v is None or (isinstance(v, float) and math.isnan(v)):
        return "–"
    if v == 0:
        return "0"
    a = abs(v)
    if 1e-3 <= a < 1e4:
        return f"{v:.3g}"
    return f"{v:.2e}"


def frac(k, n):
    return f"{k}/{n}"


def median(vals):
    vals = [v for v in vals if v is not None and not math.isnan(v)]
    return statistics.median(vals) if vals else math.nan


def spearman(xs, ys):
    """Spearman rank correlation (average ranks for ties); NaN for fewer than 3 points."""
    n = len(xs)
    if n < 3:
        return math.nan

    def ranks(v):
        order = sorted(range(n), key=lambda i: v[i])
        r = [0.0] * n
        i = 0
        while i < n:
            j = i
            while j + 1 < n and v[order[j + 1]] == v[order[i]]:
                j += 1
            for k in range(i, j + 1):
                r[order[k]] = (i + j) / 2.0
            i = j + 1
        return r

    rx, ry = ranks(xs), ranks(ys)
    mx, my = sum(rx) / n, sum(ry) / n
    cov = sum((a - mx) * (b - my) for a, b in zip(rx, ry))
    vx = math.sqrt(sum((a - mx) ** 2 for a in rx))
    vy = math.sqrt(sum((b - my) ** 2 for b in ry))
    return cov / (vx * vy) if vx > 0 and vy > 0 else math.nan


class Result:
    def __init__(self, verdict, measured, details=()):
        self.verdict, self.measured, self.details = verdict, measured, list(details)


def not_run(what):
    return Result(NOT_RUN, f"not run ({what})")


# ----------------------------------------------------------------------------- data access


class Report:
    def __init__(self, data, trials_info):
        self.data = data
        self.trials = trials_info  # {exp: TrialsScan}
        self._spec_cache = {}

    def panels(self, keys):
        return [self.data.by_key[k] for k in keys if k in self.data.by_key]

    def spec(self, panel, fam, value=None):
        """The SPEC of family fam (and ordering value) in a panel, or None.

        Several candidates (e.g. a reference MCMCDA 1e7 and a second instance with seed=1):
        prefer one with a positive error somewhere in the panel, then one that is not the run's
        reference, then the one with fewest other parameters, then file order."""
        key = (panel.key, fam, value)
        if key in self._spec_cache:
            return self._spec_cache[key]
        cands = []
        for i, s in enumerate(panel.algorithms):
            if fp.family_key(s) != fam:
                continue
            if fam not in fp.REFERENCE_FAMILIES and fp.is_reference_family(s):
                continue
            if value is not None:
                v = fp.order_value(s)
                if math.isnan(v) or not fp.close(v, value, 1e-9):
                    continue
            has_err = any(fnum(r.get("max_error_mean")) > 0 for r in panel.rows
                          if (r.get("algorithm") or "").strip() == s)
            cands.append((not has_err, self.data.is_reference(s, panel.exp),
                          len(fp.other_params(s)), i, s))
        best = min(cands)[-1] if cands else None
        self._spec_cache[key] = best
        return best

    def present(self, keys, fam, value=None):
        """Panels (of keys) that hold the algorithm."""
        return [p for p in self.panels(keys) if self.spec(p, fam, value)]

    def col(self, panel, spec, col):
        """{x: value} of a column (finite values only)."""
        out = {}
        for x, r in panel.points(spec).items():
            v = fnum(r.get(col))
            if not math.isnan(v):
                out[x] = v
        return out

    def pairs(self, panel, a, b, col="max_error_mean"):
        """[(x, value of a, value of b)] at the x where both have a finite value."""
        va, vb = self.col(panel, a, col), self.col(panel, b, col)
        return [(x, va[x], vb[x]) for x in sorted(va) if x in vb]

    def ratio_med(self, panel, num, den, col="max_error_mean", log=False):
        """Median over x of num/den (den > 0, num > 0 for log) or its log10."""
        vals = []
        for _, a, b in self.pairs(panel, num, den, col):
            if b > 0 and (a > 0 or not log):
                vals.append(math.log10(a / b) if log else a / b)
        return median(vals)

    def incomplete(self, panel, spec):
        """Sorted x values of the panel's points that the algorithm could not complete."""
        xs = sorted({panel.x_of(r) for r in panel.all_rows if not math.isnan(panel.x_of(r))})
        pts = panel.points(spec, include_skipped=True) if spec else {}
        bad = []
        for x in xs:
            r = pts.get(x)
            if r is None:
                bad.append(x)
                continue
            n = fnum(r.get("trials"))
            lost = fnum(r.get("skipped")) + fnum(r.get("failed"))
            ok = fnum(r.get("ok"))
            if ok == 0 or (not math.isnan(n) and n > 0 and not math.isnan(lost) and lost > n / 2):
                bad.append(x)
        return xs, bad

    def grid_name(self, panel, x):
        for r in panel.all_rows:
            if panel.x_of(r) == x:
                return f"{fp.fig6.fmt_value(r.get('rows'))}×{fp.fig6.fmt_value(r.get('cols'))}"
        return g3(x)

    def skip_reasons(self, spec):
        c = Counter()
        for scan in self.trials.values():
            c.update(scan.reasons.get(spec, {}))
        return c


class TrialsScan:
    """Streaming pass over one trials.csv: BP iteration maximum and non-ok status counts."""

    def __init__(self, path, bp_specs):
        self.path = path
        self.max_iter = math.nan
        self.max_where = ""
        self.reasons = {}  # spec -> Counter(status)
        self.rows = 0
        with open(path, newline="", encoding="utf-8-sig") as f:
            reader = csv.reader(f)
            header = next(reader, None)
            if not header:
                raise ValueError("empty file")
            header = [h.strip() for h in header]
            ia, ist = header.index("algorithm"), header.index("status")
            iit = header.index("iterations") if "iterations" in header else None
            where_cols = [header.index(c) for c in ("rows", "cols", "spacing", "pd", "lambda_fa", "r")
                          if c in header]
            ipt = header.index("point") if "point" in header else None
            itr = header.index("trial") if "trial" in header else None
            for row in reader:  # one line at a time
                if len(row) != len(header):
                    continue  # a cut last line of an interrupted run
                self.rows += 1
                spec, status = row[ia], row[ist]
                if status != "ok":
                    self.reasons.setdefault(spec, Counter())[status] += 1
                if iit is not None and spec in bp_specs and status == "ok":
                    v = fnum(row[iit])
                    if not math.isnan(v) and (math.isnan(self.max_iter) or v > self.max_iter):
                        self.max_iter = v
                        parts = [f"{header[i]}={row[i]}" for i in where_cols]
                        if ipt is not None:
                            parts.insert(0, f"point {row[ipt]}")
                        if itr is not None:
                            parts.append(f"trial {row[itr]}")
                        self.max_where = ", ".join(parts)


# ----------------------------------------------------------------------------- claims

CLAIMS = []


def claim(cid, text, rule):
    def deco(fn):
        CLAIMS.append((cid, text, rule, fn))
        return fn
    return deco


def bp_of(rep, p):
    return rep.spec(p, "bp")


# Rule 1a: panels other than Pd 0.9 and r 0.1 (baseline, λfa 0.0316, λfa 0.1, Pd 0.3, r 10, n×3,
# n×n); per panel, the max over x of BP's max_error_mean. Agrees if that max is < 0.0155 (0.015
# at the paper's precision) in at least two thirds of the available panels ("most cases").
@claim("1a", "BP: average errors of 0.015 or less in most cases",
       "per panel (all but Pd 0.9, r 0.1) max over x of BP's error; agrees if < 0.0155 in ≥ 2/3 of panels")
def c1a(rep):
    ps = rep.present([k for k in ALL if k not in ("pd=0.9", "r=0.1")], "bp")
    if not ps:
        return not_run("no BP rows in these panels")
    vals = {p.key: max(rep.col(p, bp_of(rep, p), "max_error_mean").values(), default=math.nan) for p in ps}
    good = [k for k, v in vals.items() if v < 0.0155]
    ok = len(good) * 3 >= 2 * len(vals)
    measured = f"≤ 0.015 in {frac(len(good), len(vals))} panels; worst {g3(max(vals.values()))}"
    return Result(AGREES if ok else DIFFERS, measured,
                  ["max BP error per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in vals.items())])


# Rule 1b: panels Pd 0.9 and r 0.1; per panel the max over spacing of BP's max_error_mean.
# Agrees if every available one lies in [0.015, 0.045) (0.02-0.04 at the paper's precision).
@claim("1b", "BP: errors in the 0.02–0.04 range for Pd = 0.9 and r = 0.1",
       "per panel max over spacing of BP's error; agrees if in [0.015, 0.045) in both panels")
def c1b(rep):
    ps = rep.present(["pd=0.9", "r=0.1"], "bp")
    if not ps:
        return not_run("no Pd 0.9 / r 0.1 panel with BP")
    vals = {p.key: max(rep.col(p, bp_of(rep, p), "max_error_mean").values(), default=math.nan) for p in ps}
    ok = all(0.015 <= v < 0.045 for v in vals.values())
    missing = [SHORT[k] for k in ("pd=0.9", "r=0.1") if k not in vals]
    m = ", ".join(f"{SHORT[k]}: max {g3(v)}" for k, v in vals.items())
    if missing:
        m += f" ({', '.join(missing)} not run)"
    return Result(AGREES if ok else DIFFERS, m)


# Rule 1c: panels n×3 and n×n; BP's max_error_mean against the number of targets. Sort the
# points by n, drop the middle one if their number is odd, and compare the mean error of the
# upper half with that of the lower half. Agrees if upper/lower <= 1.5 in every available panel
# ("little or no indication that the accuracy deteriorates").
@claim("1c", "BP: large-scale problems show little or no deterioration of accuracy as n grows",
       "n×3 and n×n: mean BP error over the upper half of n / over the lower half; agrees if ≤ 1.5 in each")
def c1c(rep):
    ps = rep.present(LARGE, "bp")
    if not ps:
        return not_run("no n×3 / n×n run with BP")
    parts, details, ok = [], [], True
    for p in ps:
        e = rep.col(p, bp_of(rep, p), "max_error_mean")
        xs = sorted(e)
        if len(xs) < 2:
            parts.append(f"{SHORT[p.key]}: one point")
            ok = False
            continue
        h = len(xs) // 2
        lo = statistics.fmean(e[x] for x in xs[:h])
        hi = statistics.fmean(e[x] for x in xs[-h:])
        ratio = hi / lo if lo > 0 else math.inf
        ok &= ratio <= 1.5
        parts.append(f"{SHORT[p.key]}: {g3(e[xs[0]])} at n={g3(xs[0])} → {g3(e[xs[-1]])} at n={g3(xs[-1])}, "
                     f"upper/lower half {g3(ratio)}")
        details.append(f"{SHORT[p.key]} BP error by n: " + ", ".join(f"{g3(x)}: {g3(e[x])}" for x in xs))
    return Result(AGREES if ok else DIFFERS, "; ".join(parts), details)


def comparator_ratios(rep, fam, keys, col="max_error_mean", num_bp=False, log=False):
    """{panel key: median over x of fam/bp (or bp/fam if num_bp)} for panels holding both."""
    out = {}
    for p in rep.panels(keys):
        a, b = rep.spec(p, fam), bp_of(rep, p)
        if a and b:
            out[p.key] = rep.ratio_med(p, b, a, col, log) if num_bp else rep.ratio_med(p, a, b, col, log)
    return out


# Rule 2a: every panel; per panel the median over x of LMIPDA/BP and of BAA/BP error ratios.
# Agrees if, for each of LMIPDA and BAA present, the ratio is > 1 in every panel ("significantly
# outperforms") and >= 10^0.5 (a factor that rounds to ten on a log scale) in more than half of
# the panels ("reduced by a factor of ten in most cases").
@claim("2a", "BP significantly outperforms LMIPDA and BAA: errors reduced by a factor of ten in most cases",
       "per panel median over x of error ratio LMIPDA/BP, BAA/BP; agrees if > 1 in every panel and ≥ 3.16 in > half")
def c2a(rep):
    parts, details, ok, any_run = [], [], True, False
    for fam in ("lmipda", "baa"):
        rs = comparator_ratios(rep, fam, ALL)
        rs = {k: v for k, v in rs.items() if not math.isnan(v)}
        if not rs:
            parts.append(f"{fp.DISPLAY[fam]} not run")
            continue
        any_run = True
        tenfold = sum(v >= 10 ** 0.5 for v in rs.values())
        better = sum(v > 1 for v in rs.values())
        ok &= better == len(rs) and tenfold * 2 > len(rs)
        parts.append(f"{fp.DISPLAY[fam]}/BP median {g3(median(rs.values()))}; ≥ 3.16 in {frac(tenfold, len(rs))}, "
                     f"> 1 in {frac(better, len(rs))} panels")
        details.append(f"{fp.DISPLAY[fam]}/BP error ratio per panel: "
                       + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items()))
    if not any_run:
        return not_run("LMIPDA and BAA absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts), details)


# Rule 2b: every panel; per panel the median over x of BP time / LMIPDA time and BP / BAA.
# Agrees if the overall (median over panels) ratio lies in [1, 10] for each of LMIPDA and BAA
# present ("only a few times": more than once, less than an order of magnitude).
@claim("2b", "BP's computation is only a few times that of LMIPDA and BAA",
       "overall median of per-panel time ratios BP/LMIPDA and BP/BAA; agrees if each in [1, 10]")
def c2b(rep):
    parts, details, ok, any_run = [], [], True, False
    for fam in ("lmipda", "baa"):
        rs = {k: v for k, v in comparator_ratios(rep, fam, ALL, "time_us_mean", num_bp=True).items()
              if not math.isnan(v)}
        if not rs:
            parts.append(f"{fp.DISPLAY[fam]} not run")
            continue
        any_run = True
        m = median(rs.values())
        ok &= 1 <= m <= 10
        parts.append(f"BP/{fp.DISPLAY[fam]} time {g3(m)}{span(rs.values())}")
        details.append(f"BP/{fp.DISPLAY[fam]} time ratio per panel: "
                       + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items()))
    if not any_run:
        return not_run("LMIPDA and BAA absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts), details)


# Rule 2c: BP's time_us_mean: the max over all experiment-1 points must be < 1000 µs ("fractions
# of a millisecond"), and at the largest n of n×3 (90 targets) and n×n (100) it must be <= 2000 µs
# ("a little over a millisecond", read as an upper bound: the paper's figure is 2014 Matlab on a
# Xeon E5-2670, so being faster agrees). Agrees if every available part holds.
@claim("2c", "BP averages fractions of a millisecond in the six-target problems, a little over 1 ms at 90 and 100 targets",
       "BP time: max over experiment 1 < 1000 µs; at the largest n of n×3, n×n ≤ 2000 µs (upper bounds)")
def c2c(rep):
    parts, ok, any_run = [], True, False
    e1 = [v for p in rep.present(EXP1, "bp") for v in rep.col(p, bp_of(rep, p), "time_us_mean").values()]
    if e1:
        any_run = True
        ok &= max(e1) < 1000
        parts.append(f"six targets: max {g3(max(e1))} µs, median {g3(median(e1))} µs")
    for p in rep.present(LARGE, "bp"):
        t = rep.col(p, bp_of(rep, p), "time_us_mean")
        if t:
            any_run = True
            x = max(t)
            ok &= t[x] <= 2000
            parts.append(f"{SHORT[p.key]} n={g3(x)}: {g3(t[x])} µs")
    if not any_run:
        return not_run("no BP times")
    if not e1:
        parts.append("six-target panels not run")
    if not rep.present(LARGE, "bp"):
        parts.append("n×3 / n×n not run")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


def pair_ratio(rep, keys, fam_num, fam_den, col="max_error_mean"):
    out = {}
    for p in rep.panels(keys):
        a, b = rep.spec(p, fam_num), rep.spec(p, fam_den)
        if a and b:
            v = rep.ratio_med(p, a, b, col)
            if not math.isnan(v):
                out[p.key] = v
    return out


# Rule 3a: panels other than λfa 0.1, r 10 and r 0.1 (where the paper says they differ); per panel
# the median over x of the BAA/LMIPDA error ratio. Agrees if it lies in [0.5, 2] ("similar") in
# at least two thirds of those panels.
@claim("3a", "LMIPDA and BAA perform similarly to each other across the board",
       "per panel (all but λfa 0.1, r 10, r 0.1) median BAA/LMIPDA error ratio; agrees if in [0.5, 2] in ≥ 2/3")
def c3a(rep):
    rs = pair_ratio(rep, [k for k in ALL if k not in ("lambda_fa=0.1", "r=10", "r=0.1")], "baa", "lmipda")
    if not rs:
        return not_run("LMIPDA or BAA absent")
    good = sum(0.5 <= v <= 2 for v in rs.values())
    return Result(AGREES if good * 3 >= 2 * len(rs) else DIFFERS,
                  f"BAA/LMIPDA within [0.5, 2] in {frac(good, len(rs))} panels",
                  ["BAA/LMIPDA error ratio per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items())])


# Rule 3b: panels λfa 0.1 and r 10; median over spacing of BAA/LMIPDA error ratio. Agrees if it is
# <= 0.8 (BAA's error at least 20% lower: "significantly better") in each available panel.
@claim("3b", "BAA performs significantly better than LMIPDA with high false alarm rate and high measurement noise",
       "λfa 0.1 and r 10: median BAA/LMIPDA error ratio; agrees if ≤ 0.8 in each")
def c3b(rep):
    rs = pair_ratio(rep, ["lambda_fa=0.1", "r=10"], "baa", "lmipda")
    if not rs:
        return not_run("LMIPDA/BAA in the λfa 0.1 and r 10 panels")
    ok = all(v <= 0.8 for v in rs.values())
    return Result(AGREES if ok else DIFFERS, ", ".join(f"{SHORT[k]}: BAA/LMIPDA {g3(v)}" for k, v in rs.items()))


# Rule 3c: panel r 0.1; median over spacing of the LMIPDA/BAA error ratio; agrees if <= 0.8.
@claim("3c", "LMIPDA performs better than BAA with low measurement noise (r = 0.1)",
       "r 0.1: median LMIPDA/BAA error ratio; agrees if ≤ 0.8")
def c3c(rep):
    rs = pair_ratio(rep, ["r=0.1"], "lmipda", "baa")
    if not rs:
        return not_run("LMIPDA/BAA in the r 0.1 panel")
    v = rs["r=0.1"]
    return Result(AGREES if v <= 0.8 else DIFFERS, f"LMIPDA/BAA {g3(v)}")


# Rule 3d: every panel; median over x of the BAA/LMIPDA time ratio; agrees if within [0.5, 2]
# ("comparable") in at least two thirds of the panels.
@claim("3d", "LMIPDA and BAA computation times are comparable",
       "per panel median BAA/LMIPDA time ratio; agrees if in [0.5, 2] in ≥ 2/3 of panels")
def c3d(rep):
    rs = pair_ratio(rep, ALL, "baa", "lmipda", "time_us_mean")
    if not rs:
        return not_run("LMIPDA or BAA absent")
    good = sum(0.5 <= v <= 2 for v in rs.values())
    return Result(AGREES if good * 3 >= 2 * len(rs) else DIFFERS,
                  f"BAA/LMIPDA time in [0.5, 2] in {frac(good, len(rs))} panels (median {g3(median(rs.values()))})",
                  ["BAA/LMIPDA time ratio per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items())])


def pooled_pairs(rep, keys, fam, value, col="max_error_mean"):
    """[(panel key, x, algorithm value, BP value)] over panels holding both."""
    out = []
    for p in rep.panels(keys):
        a, b = rep.spec(p, fam, value), bp_of(rep, p)
        if a and b:
            out += [(p.key, x, va, vb) for x, va, vb in rep.pairs(p, a, b, col)]
    return out


def log_time_ratios(rep, keys, fam, value):
    """{panel key: median over x of log10(time fam / time BP)}."""
    out = {}
    for p in rep.panels(keys):
        a, b = rep.spec(p, fam, value), bp_of(rep, p)
        if a and b:
            v = rep.ratio_med(p, a, b, "time_us_mean", log=True)
            if not math.isnan(v):
                out[p.key] = v
    return out


def span(vals):
    """' (panels a–b)' for several values, '' for one."""
    vals = list(vals)
    return f" (panels {g3(min(vals))}–{g3(max(vals))})" if len(vals) > 1 else ""


def orders_text(rs):
    return f"median {g3(median(rs.values()))} decades{span(rs.values())}" if rs else "no times"


def any_present(rep, fam, value=None, keys=ALL):
    return bool(rep.present(keys, fam, value))


# Rule 4a: JT threshold 0.1 against BP at every point (all panels) where both have an error.
# Agrees if JT's error is larger at >= 90% of the points ("globally worse") and at least 3 times
# larger at >= 25% of them ("often much worse").
@claim("4a", "JT threshold 0.1: error globally worse than BP, often much worse",
       "all points: JT > BP at ≥ 90% and JT ≥ 3·BP at ≥ 25%")
def c4a(rep):
    if not any_present(rep, "jt", 0.1):
        return not_run("jt:threshold=0.1 absent")
    pts = pooled_pairs(rep, ALL, "jt", 0.1)
    if not pts:
        return not_run("no point with both JT 0.1 and BP errors")
    worse = sum(a > b for _, _, a, b in pts)
    much = sum(a >= 3 * b for _, _, a, b in pts)
    ok = worse >= 0.9 * len(pts) and much >= 0.25 * len(pts)
    return Result(AGREES if ok else DIFFERS,
                  f"JT > BP at {frac(worse, len(pts))} points, ≥ 3× at {frac(much, len(pts))}; "
                  f"median JT/BP {g3(median([a / b for *_, a, b in pts if b > 0]))}")


# Rule 4b: JT threshold 0.1; per panel the median over x of log10(JT time / BP time); agrees if
# the median over panels lies in [0.5, 2.5) (1-2 orders of magnitude).
@claim("4b", "JT threshold 0.1: computation 1–2 orders of magnitude higher than BP",
       "overall median log10(JT/BP time); agrees if in [0.5, 2.5)")
def c4b(rep):
    if not any_present(rep, "jt", 0.1):
        return not_run("jt:threshold=0.1 absent")
    rs = log_time_ratios(rep, ALL, "jt", 0.1)
    m = median(rs.values())
    return Result(AGREES if 0.5 <= m < 2.5 else DIFFERS, orders_text(rs),
                  ["log10 JT 0.1/BP time per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items())])


def completion_text(rep, p, spec):
    xs, bad = rep.incomplete(p, spec)
    return xs, bad, (f"{SHORT[p.key]}: {len(bad)}/{len(xs)} not completed"
                     + (f" ({', '.join(rep.grid_name(p, x) for x in bad)})" if bad else ""))


def reasons_text(rep, specs):
    c = Counter()
    for s in specs:
        c.update(rep.skip_reasons(s))
    return ", ".join(f"{k} ×{v}" for k, v in c.most_common(4)) if c else ""


# Rule 4c: JT threshold 0.1 in n×3 and n×n; a point is "not completed" when JT has no row there
# or more than half its trials were skipped/failed. Agrees if the not-completed points are exactly
# 9×9 and 10×10 of n×n (all n×3 points complete). The reason (memory) is shown from trials.csv
# statuses when available but not judged.
@claim("4c", "JT threshold 0.1: the 9×9 and 10×10 experiments could not be completed (memory)",
       "n×3, n×n: points JT 0.1 could not complete (> half skipped/failed or absent); agrees if exactly 9×9 and 10×10")
def c4c(rep):
    if not any_present(rep, "jt", 0.1):
        return not_run("jt:threshold=0.1 absent")
    ps = rep.panels(LARGE)
    if not ps:
        return not_run("no n×3 / n×n run")
    parts, ok, specs = [], True, []
    for p in ps:
        spec = rep.spec(p, "jt", 0.1)
        specs.append(spec)
        xs, bad, text = completion_text(rep, p, spec)
        parts.append(text)
        if p.key == "3xn":
            ok &= not bad
        else:
            want = [x for x in xs if rep.grid_name(p, x) in ("9×9", "10×10")]
            ok &= sorted(bad) == sorted(want) and len(want) == 2
    why = reasons_text(rep, [s for s in specs if s])
    if "nxn" not in [p.key for p in ps]:
        return Result(NOT_RUN, "not run (no n×n run); " + "; ".join(parts))
    return Result(AGREES if ok else DIFFERS, "; ".join(parts) + (f"; statuses: {why}" if why else ""))


# Rule 4d: JT thresholds 0.01 and 0.001 against BP at every point (all panels) with both errors.
# Agrees if, for each threshold present, JT's error is at most a third of BP's ("much better") at
# >= 50% of the points ("generally"; points where JT could not run do not count).
@claim("4d", "JT threshold 0.01 / 0.001: accuracy generally much better than BP",
       "all points: JT ≤ BP/3 at ≥ 50%, for each threshold")
def c4d(rep):
    parts, ok, any_run = [], True, False
    for t in (0.01, 0.001):
        if not any_present(rep, "jt", t):
            parts.append(f"JT {g3(t)} not run")
            continue
        pts = pooled_pairs(rep, ALL, "jt", t)
        if not pts:
            parts.append(f"JT {g3(t)}: no common point")
            continue
        any_run = True
        much = sum(a <= b / 3 for _, _, a, b in pts)
        ok &= much * 2 >= len(pts)
        parts.append(f"JT {g3(t)} ≤ BP/3 at {frac(much, len(pts))} points "
                     f"(median JT/BP {g3(median([a / b for *_, a, b in pts if b > 0]))})")
    if not any_run:
        return not_run("jt:threshold=0.01/0.001 absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


# Rule 4e: JT thresholds 0.01 and 0.001; per panel the median over x of log10(JT time / BP time);
# agrees if the overall median of each threshold present lies in [1.5, 4.5) (2-4 orders).
@claim("4e", "JT threshold 0.01 / 0.001: computation 2–4 orders of magnitude higher than BP",
       "overall median log10(JT/BP time) per threshold; agrees if each in [1.5, 4.5)")
def c4e(rep):
    parts, details, ok, any_run = [], [], True, False
    for t in (0.01, 0.001):
        if not any_present(rep, "jt", t):
            parts.append(f"JT {g3(t)} not run")
            continue
        rs = log_time_ratios(rep, ALL, "jt", t)
        if not rs:
            parts.append(f"JT {g3(t)}: no times")
            continue
        any_run = True
        m = median(rs.values())
        ok &= 1.5 <= m < 4.5
        parts.append(f"JT {g3(t)}: {orders_text(rs)}")
        details.append(f"log10 JT {g3(t)}/BP time per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items()))
    if not any_run:
        return not_run("jt:threshold=0.01/0.001 absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts), details)


# Rule 4f: JT thresholds 0.01 and 0.001 over the points of n×3 and n×n together; agrees if, for
# each threshold present, more than half the points could not be completed (definition as 4c).
@claim("4f", "JT threshold 0.01 / 0.001: most n×3 and n×n experiments could not be completed",
       "n×3 + n×n points not completed (as 4c); agrees if > half, for each threshold")
def c4f(rep):
    ps = rep.panels(LARGE)
    if not ps:
        return not_run("no n×3 / n×n run")
    parts, ok, any_run = [], True, False
    for t in (0.01, 0.001):
        if not any_present(rep, "jt", t):
            parts.append(f"JT {g3(t)} not run")
            continue
        any_run = True
        tot = bad_n = 0
        texts, specs = [], []
        for p in ps:
            spec = rep.spec(p, "jt", t)
            specs.append(spec)
            xs, bad, text = completion_text(rep, p, spec)
            tot += len(xs)
            bad_n += len(bad)
            texts.append(f"{SHORT[p.key]} {frac(len(bad), len(xs))}")
        ok &= bad_n * 2 > tot
        why = reasons_text(rep, [s for s in specs if s])
        parts.append(f"JT {g3(t)}: {frac(bad_n, tot)} not completed ({', '.join(texts)})"
                     + (f" [{why}]" if why else ""))
    if not any_run:
        return not_run("jt:threshold=0.01/0.001 absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


# Rule 5a: MCMCDA 1e5 vs BP in the experiment-1 panels; per panel the median over spacing of the
# MCMCDA/BP error ratio; agrees if the median over panels lies in [0.5, 2] ("comparable").
@claim("5a", "MCMCDA 10^5: generally comparable to BP in the six-target cases",
       "experiment 1: overall median MCMCDA 1e5/BP error ratio; agrees if in [0.5, 2]")
def c5a(rep):
    if not any_present(rep, "mcmcda", 1e5, EXP1):
        return not_run("mcmcda:samples=1e5 absent from experiment 1")
    rs = {}
    for p in rep.panels(EXP1):
        a, b = rep.spec(p, "mcmcda", 1e5), bp_of(rep, p)
        if a and b:
            rs[p.key] = rep.ratio_med(p, a, b)
    rs = {k: v for k, v in rs.items() if not math.isnan(v)}
    m = median(rs.values())
    return Result(AGREES if 0.5 <= m <= 2 else DIFFERS, f"MCMCDA 1e5/BP median {g3(m)}",
                  ["MCMCDA 1e5/BP error ratio per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items())])


# Rule 5b: MCMCDA 1e5 in n×3 and n×n; agrees if in each available panel its error rises with the
# number of targets (Spearman rank correlation >= 0.5) and at the largest n it exceeds BP's.
@claim("5b", "MCMCDA 10^5: progressively worse with larger numbers of targets",
       "n×3, n×n: Spearman ρ(n, MCMCDA 1e5 error) ≥ 0.5 and MCMCDA > BP at the largest n, in each")
def c5b(rep):
    ps = rep.present(LARGE, "mcmcda", 1e5)
    if not ps:
        return not_run("mcmcda:samples=1e5 absent from n×3 / n×n")
    parts, ok = [], True
    for p in ps:
        e = rep.col(p, rep.spec(p, "mcmcda", 1e5), "max_error_mean")
        xs = sorted(e)
        rho = spearman(xs, [e[x] for x in xs])
        b = rep.col(p, bp_of(rep, p), "max_error_mean") if bp_of(rep, p) else {}
        last = xs[-1] if xs else None
        worse = last is not None and last in b and e[last] > b[last]
        ok &= (not math.isnan(rho)) and rho >= 0.5 and worse
        parts.append(f"{SHORT[p.key]}: ρ = {g3(rho)}, {g3(e[xs[0]]) if xs else '–'} → {g3(e[last]) if xs else '–'}"
                     f" (BP at n={g3(last)}: {g3(b.get(last, math.nan))})")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


# Rule 5c: MCMCDA 1e6 vs BP in n×3 and n×n at the "larger cases": points with n at or above the
# panel's median n. Agrees if BP's error is at most twice MCMCDA's ("similar to or better") at
# >= 75% of those points, pooled over the panels.
@claim("5c", "In the larger cases BP performs similar to or better than MCMCDA 10^6",
       "n×3, n×n points with n ≥ median n: BP ≤ 2·MCMCDA 1e6 at ≥ 75%")
def c5c(rep):
    ps = [p for p in rep.present(LARGE, "mcmcda", 1e6) if bp_of(rep, p)]
    if not ps:
        return not_run("mcmcda:samples=1e6 or BP absent from n×3 / n×n")
    pts = []
    for p in ps:
        pr = rep.pairs(p, bp_of(rep, p), rep.spec(p, "mcmcda", 1e6))
        if pr:
            mid = statistics.median([x for x, _, _ in pr])
            pts += [(p.key, x, a, b) for x, a, b in pr if x >= mid]
    if not pts:
        return not_run("no common points")
    good = sum(a <= 2 * b for *_, a, b in pts)
    return Result(AGREES if good >= 0.75 * len(pts) else DIFFERS,
                  f"BP ≤ 2·MCMCDA 1e6 at {frac(good, len(pts))} larger points "
                  f"(median BP/MCMCDA {g3(median([a / b for *_, a, b in pts if b > 0]))})")


# Rule 5d: MCMCDA 1e5, 1e6, 1e7; per panel the median over x of log10(MCMCDA time / BP time),
# then the median over panels per sample count. Agrees if every sample count present lies in
# [1.5, 4.5) (2-4 orders). In n×3/n×n the 1e7 instance is the second (test) one when available.
@claim("5d", "MCMCDA complexity 2–4 orders of magnitude higher than BP, depending on the samples",
       "overall median log10(MCMCDA/BP time) per sample count; agrees if each in [1.5, 4.5)")
def c5d(rep):
    parts, details, ok, any_run = [], [], True, False
    for n in (1e5, 1e6, 1e7):
        if not any_present(rep, "mcmcda", n):
            parts.append(f"{g3(n)} not run")
            continue
        rs = log_time_ratios(rep, ALL, "mcmcda", n)
        if not rs:
            continue
        any_run = True
        m = median(rs.values())
        ok &= 1.5 <= m < 4.5
        parts.append(f"{n:.0e}: {g3(m)} decades")
        details.append(f"log10 MCMCDA {n:.0e}/BP time per panel: " + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in rs.items()))
    if not any_run:
        return not_run("MCMCDA absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts), details)


# Rule 6a: CD depth 3 and 5 vs BP at every point (all panels) with both errors; agrees if BP's
# error is lower at >= two thirds of the points ("generally outperforms"), for each depth present.
@claim("6a", "BP generally outperforms correlation decay with t = 3 and t = 5",
       "all points: BP < CD at ≥ 2/3, for t = 3 and t = 5")
def c6a(rep):
    parts, ok, any_run = [], True, False
    for d in (3, 5):
        pts = pooled_pairs(rep, ALL, "cd", d)
        if not pts:
            parts.append(f"t={d} not run")
            continue
        any_run = True
        good = sum(b < a for *_, a, b in pts)
        ok &= good * 3 >= 2 * len(pts)
        parts.append(f"t={d}: BP better at {frac(good, len(pts))}")
    if not any_run:
        return not_run("cd:depth=3/5 absent")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


# Rule 6b: CD depth 7 vs BP in the experiment-1 panels, pooled; "tight" = spacing below the
# middle of the panel's spacing range, "large" = above it. Agrees if BP's error is lower at more
# than half of the tight points and CD's at more than half of the large ones.
@claim("6b", "CD t = 7: BP better at tighter spacings, CD better at larger spacings",
       "experiment 1 pooled: BP < CD at > half the points below mid-range spacing, CD < BP at > half above")
def c6b(rep):
    tight, wide = [], []
    for p in rep.panels(EXP1):
        a, b = rep.spec(p, "cd", 7), bp_of(rep, p)
        if not (a and b):
            continue
        pr = rep.pairs(p, a, b)
        if not pr:
            continue
        mid = (pr[0][0] + pr[-1][0]) / 2
        tight += [(x, va, vb) for x, va, vb in pr if x < mid]
        wide += [(x, va, vb) for x, va, vb in pr if x > mid]
    if not tight and not wide:
        return not_run("cd:depth=7 absent from experiment 1")
    bp_t = sum(vb < va for _, va, vb in tight)
    cd_w = sum(va < vb for _, va, vb in wide)
    ok = bp_t * 2 > len(tight) and cd_w * 2 > len(wide)
    return Result(AGREES if ok else DIFFERS,
                  f"BP better at {frac(bp_t, len(tight))} tight points; CD better at {frac(cd_w, len(wide))} large-spacing points")


# Rule 6c: CD in the experiment-1 panels; per panel the median over spacing of CD's error. Agrees
# if, for every depth present, the Pd 0.9 panel has the highest such value ("particularly poorly").
@claim("6c", "CD performs particularly poorly with Pd = 0.9",
       "per depth: Pd 0.9 has the highest median CD error among the experiment-1 panels")
def c6c(rep):
    parts, ok, any_run = [], True, False
    for d in (3, 5, 7):
        med = {}
        for p in rep.panels(EXP1):
            s = rep.spec(p, "cd", d)
            if s:
                med[p.key] = median(rep.col(p, s, "max_error_mean").values())
        med = {k: v for k, v in med.items() if not math.isnan(v)}
        if not med:
            continue
        if "pd=0.9" not in med:
            parts.append(f"t={d}: Pd 0.9 not run")
            ok = False
            any_run = True
            continue
        any_run = True
        rank = 1 + sum(v > med["pd=0.9"] for v in med.values())
        ok &= rank == 1 and len(med) > 1
        parts.append(f"t={d}: Pd 0.9 median {g3(med['pd=0.9'])}, rank {rank}/{len(med)}")
    if not any_run:
        return not_run("CD absent from experiment 1")
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


# Rule 6d: CD in the r 0.1 panel; median over spacing of CD time / BP time per depth. Agrees if at
# least one depth lies in [1/3, 1) ("slightly faster": faster, but by less than a factor 3).
@claim("6d", "CD computation: slightly faster than BP in some cases (e.g. r = 0.1)",
       "r 0.1: median CD/BP time ratio per depth; agrees if some depth in [1/3, 1)")
def c6d(rep):
    rs = {}
    for p in rep.panels(["r=0.1"]):
        for d in (3, 5, 7):
            a, b = rep.spec(p, "cd", d), bp_of(rep, p)
            if a and b:
                rs[d] = rep.ratio_med(p, a, b, "time_us_mean")
    rs = {k: v for k, v in rs.items() if not math.isnan(v)}
    if not rs:
        return not_run("CD or the r 0.1 panel absent")
    ok = any(1 / 3 <= v < 1 for v in rs.values())
    return Result(AGREES if ok else DIFFERS, "CD/BP time at r 0.1: " + ", ".join(f"t={d} {g3(v)}" for d, v in rs.items()))


# Rule 6e: CD in the experiment-1 panels; per (panel, depth) the median over spacing of
# log10(CD time / BP time). Agrees if at least a third of these cases lie in [1.5, 3.5)
# ("2-3 orders of magnitude slower in many other cases").
@claim("6e", "CD computation: 2–3 orders of magnitude slower than BP in many cases",
       "experiment 1, per (panel, depth) median log10(CD/BP time); agrees if ≥ 1/3 of cases in [1.5, 3.5)")
def c6e(rep):
    cases = {}
    for d in (3, 5, 7):
        for k, v in log_time_ratios(rep, EXP1, "cd", d).items():
            cases[(k, d)] = v
    if not cases:
        return not_run("CD absent from experiment 1")
    good = sum(1.5 <= v < 3.5 for v in cases.values())
    return Result(AGREES if good * 3 >= len(cases) else DIFFERS,
                  f"{frac(good, len(cases))} (panel, depth) cases 2–3 decades slower; "
                  f"range {g3(min(cases.values()))}–{g3(max(cases.values()))} decades",
                  ["log10 CD/BP time: " + ", ".join(f"{SHORT[k]} t={d} {g3(v)}" for (k, d), v in cases.items())])


# Rule 6f: CD in n×3 and n×n; per (panel, depth) log10(CD time / BP time) at the largest n where CD
# completed at least one trial; per panel the max over depths. Agrees if that lies in [3.5, 5.5)
# (4-5 orders) in each available panel. Points CD could not complete are listed.
@claim("6f", "CD computation: 4–5 orders of magnitude slower than BP in the large-scale problems",
       "n×3, n×n: max over depths of log10(CD/BP time) at the largest completed n; agrees if in [3.5, 5.5) in each")
def c6f(rep):
    ps = [p for p in rep.panels(LARGE) if any(rep.spec(p, "cd", d) for d in (3, 5, 7))]
    if not ps:
        return not_run("CD absent from n×3 / n×n")
    parts, ok = [], True
    for p in ps:
        best, texts = math.nan, []
        for d in (3, 5, 7):
            a, b = rep.spec(p, "cd", d), bp_of(rep, p)
            if not (a and b):
                continue
            pr = [(x, va, vb) for x, va, vb in rep.pairs(p, a, b, "time_us_mean") if va > 0 and vb > 0]
            if not pr:
                continue
            x, va, vb = pr[-1]
            lr = math.log10(va / vb)
            best = lr if math.isnan(best) else max(best, lr)
            _, bad = rep.incomplete(p, a)
            texts.append(f"t={d} {g3(lr)} at n={g3(x)}" + (f" ({len(bad)} points not completed)" if bad else ""))
        ok &= not math.isnan(best) and 3.5 <= best < 5.5
        parts.append(f"{SHORT[p.key]}: " + ", ".join(texts))
    return Result(AGREES if ok else DIFFERS, "; ".join(parts))


def wstar(rep):
    p = rep.data.by_key.get("pd=0.9")
    if not p or not bp_of(rep, p):
        return None, None
    spec = bp_of(rep, p)
    return p, {c: rep.col(p, spec, f"w_star_{c}") for c in ("mean", "p5", "p95")}


# Rule 7a: BP's w_star_mean in the Pd 0.9 panel; agrees if its max over spacing lies in
# [150, 600] ("around 300": within a factor 2). The p5-p95 range is reported, not judged.
@claim("7a", "Fig. 7: the convergence parameter W* is around 300 (Pd = 0.9)",
       "Pd 0.9: max over spacing of BP's mean W*; agrees if in [150, 600]")
def c7a(rep):
    p, w = wstar(rep)
    if p is None or not w["mean"]:
        return not_run("no BP W* in the Pd 0.9 panel")
    xm = max(w["mean"], key=w["mean"].get)
    m = f"mean W* max {g3(w['mean'][xm])} at spacing {g3(xm)}, min {g3(min(w['mean'].values()))}"
    if w["p5"] and w["p95"]:
        m += f"; p5–p95 over spacings {g3(min(w['p5'].values()))}–{g3(max(w['p95'].values()))}"
    return Result(AGREES if 150 <= w["mean"][xm] <= 600 else DIFFERS, m,
                  ["BP mean W* by spacing (Pd 0.9): " + ", ".join(f"{g3(x)}: {g3(v)}" for x, v in sorted(w["mean"].items()))])


# Rule 7b: BP's w_star_mean vs spacing in the Pd 0.9 panel; agrees if the spacing of its maximum
# is in the lowest third of the spacing range, that of its minimum in the highest third, and the
# value at the largest spacing is below the value at the smallest.
@claim("7b", "Fig. 7: W* minimal when targets are well spaced, maximal when closely spaced",
       "Pd 0.9: argmax of mean W* in the lowest third of spacings, argmin in the highest third")
def c7b(rep):
    p, w = wstar(rep)
    if p is None or len(w["mean"]) < 2:
        return not_run("no BP W* sweep in the Pd 0.9 panel")
    m = w["mean"]
    xs = sorted(m)
    lo, hi = xs[0], xs[-1]
    xmax, xmin = max(m, key=m.get), min(m, key=m.get)
    third = (hi - lo) / 3
    ok = xmax <= lo + third and xmin >= hi - third and m[hi] < m[lo]
    return Result(AGREES if ok else DIFFERS,
                  f"max at spacing {g3(xmax)} ({g3(m[xmax])}), min at spacing {g3(xmin)} ({g3(m[xmin])})")


# Rule 8: the largest BP iteration count over every trial of every input, read from trials.csv
# next to each summary.csv (streamed). Agrees if it lies in [44, 174] (87 within a factor 2:
# the paper's point is that it is far below the ~3000 of the offline bound). Without trials.csv
# the max over points of iterations_p95 is a lower bound only: differs if it exceeds 174, else
# inconclusive.
@claim("8", "The maximum number of BP iterations in the experiment is 87",
       "max BP iterations over all trials (trials.csv); agrees if in [44, 174]; p95 only: a lower bound")
def c8(rep):
    p95 = {}
    for p in rep.panels(ALL):
        b = bp_of(rep, p)
        if b:
            v = rep.col(p, b, "iterations_p95")
            if v:
                p95[p.key] = max(v.values())
    scans = {e: s for e, s in rep.trials.items() if not math.isnan(s.max_iter)}
    if not p95 and not scans:
        return not_run("no BP iteration counts")
    p95max = max(p95.values(), default=math.nan)
    details = ["max over points of BP's iterations_p95 per panel: "
               + ", ".join(f"{SHORT[k]} {g3(v)}" for k, v in p95.items()),
               "summary.csv holds no maximum (count, mean, se, median, p5, p95 only)"]
    if scans:
        best_e = max(scans, key=lambda e: scans[e].max_iter)
        mx = scans[best_e].max_iter
        for e, s in scans.items():
            details.append(f"experiment {e}: max {g3(s.max_iter)} ({s.max_where}) over {s.rows} rows of {s.path}")
        m = f"max {g3(mx)} (experiment {best_e}, trials.csv); max p95 {g3(p95max)}"
        missing = [e for e in rep.data.summaries if e not in scans]
        if missing:  # their maximum is unknown but at least their p95
            lb = max((v for k, v in p95.items() if rep.data.by_key[k].exp in missing), default=math.nan)
            m += f"; no trials.csv for experiment {', '.join(map(str, missing))}"
            if not math.isnan(lb) and lb > mx:
                mx = lb
                m += f" (their max ≥ p95 {g3(lb)})"
        ok = 44 <= mx <= 174
        return Result(AGREES if ok else DIFFERS, m, details)
    if p95max > 174:
        return Result(DIFFERS, f"max p95 {g3(p95max)} > 174 (no trials.csv; the max is at least this)", details)
    return Result(INCONCLUSIVE, f"max p95 {g3(p95max)}; maximum unknown (no trials.csv)", details)


# ----------------------------------------------------------------------------- output


def md_cell(s):
    return str(s).replace("|", "\\|").replace("\n", " ")


def render(rep, args):
    data = rep.data
    out = ["# Williams & Lau 2014, Section V-B: claims vs. measurements", ""]
    for e in (1, 2, 3):
        path = data.paths[e]
        label = {1: "experiment 1 (2×3 grid vs spacing)", 2: "experiment 2 (n×3 grids)", 3: "experiment 3 (n×n grids)"}[e]
        if path:
            refs = ", ".join(sorted(data.references_by_exp.get(e, ()))) or "not recorded"
            extra = f"; trials.csv streamed ({rep.trials[e].rows} rows)" if e in rep.trials else ""
            out.append(f"- {label}: `{path}` (reference: {refs}{extra})")
            if e == 1:
                for more in args.exp1_extra:
                    out.append(f"  - plus the algorithms it lacks from `{more}`")
        else:
            out.append(f"- {label}: not given")
    out.append(f"- panels found: {', '.join(SHORT[p.key] for p in data.panels) or 'none'}")
    out.append(f"- algorithms: {', '.join(f'`{a}`' for a in data.algorithms())}")
    out += ["", "| # | Claim (Sec. V-B) | Measured | Verdict |", "|---|---|---|---|"]
    results = []
    for cid, text, rule, fn in CLAIMS:
        try:
            res = fn(rep)
        except Exception as exc:  # a claim that cannot be evaluated must not hide the others
            res = Result(INCONCLUSIVE, f"error while evaluating: {type(exc).__name__}: {exc}")
        results.append((cid, text, rule, res))
        verdict = f"**{res.verdict}**" if res.verdict in (AGREES, DIFFERS) else res.verdict
        out.append(f"| {cid} | {md_cell(text)} | {md_cell(res.measured)} | {verdict} |")
    counts = Counter(r.verdict for *_, r in results)
    out += ["", "Verdicts: " + ", ".join(f"{v} {counts[v]}" for v in (AGREES, DIFFERS, NOT_RUN, INCONCLUSIVE)
                                         if counts[v]), ""]
    out += ["## Rules and details", "",
            "Ratios per panel are medians over the panel's x values; \"overall\" is the median over "
            "panels; \"decades\" are log10 ratios. Errors are `max_error_mean` (average max marginal "
            "error against the run's reference), times `time_us_mean`.", ""]
    for cid, text, rule, res in results:
        out.append(f"- **{cid}** {text}. *Rule:* {rule}.")
        for d in res.details:
            out.append(f"  - {d}")
    return "\n".join(out) + "\n"


def main(argv=None):
    ap = argparse.ArgumentParser(
        prog=fp.fig6.PROG,
        description="Section V-B claims of Williams & Lau 2014 next to measured numbers (Markdown).")
    ap.add_argument("--exp1", metavar="CSV", help="summary.csv of experiment 1 (2×3 grid, seven panels)")
    ap.add_argument("--exp1-extra", metavar="CSV", action="append", default=[],
                    help="summary.csv of another experiment-1 run over the same points; adds the "
                         "algorithms --exp1 lacks (repeatable)")
    ap.add_argument("--exp2", metavar="CSV", help="summary.csv of experiment 2 (n×3 grids)")
    ap.add_argument("--exp3", metavar="CSV", help="summary.csv of experiment 3 (n×n grids)")
    ap.add_argument("--out", metavar="FILE", help="write the Markdown here instead of stdout")
    ap.add_argument("--no-trials", action="store_true", help="do not read trials.csv next to the summaries")
    args = ap.parse_args(argv)
    if not (args.exp1 or args.exp2 or args.exp3):
        fail("no input: give at least one of --exp1, --exp2, --exp3")
    data = fp.PaperData(args.exp1, args.exp2, args.exp3, args.exp1_extra)
    bp_specs = {a for a in data.algorithms() if fp.family_key(a) == "bp"}
    trials = {}
    if not args.no_trials:
        for e, path in data.paths.items():
            if not path:
                continue
            tp = os.path.join(os.path.dirname(os.path.abspath(path)), "trials.csv")
            if os.path.exists(tp):
                try:
                    trials[e] = TrialsScan(tp, bp_specs)
                except (OSError, ValueError, csv.Error) as exc:
                    note(f"{tp}: not read ({exc})")
    text = render(Report(data, trials), args)
    if args.out:
        d = os.path.dirname(os.path.abspath(args.out))
        os.makedirs(d, exist_ok=True)
        tmp = args.out + ".tmp"
        with open(tmp, "w", encoding="utf-8") as f:
            f.write(text)
        os.replace(tmp, args.out)
        print(args.out)
    else:
        sys.stdout.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
