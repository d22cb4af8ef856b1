"""Section V-B of Williams & Lau 2014, bullets 1-3, as rules: BP's error levels and how they scale
with the number of targets (1a-1c), BP against LMIPDA and BAA in error and time (2a-2c), LMIPDA
against BAA (3a-3d). The comment above each rule function states its rule. differences.py also
reads the ratios of comparator_ratios and pair_ratio."""

import math
import statistics

from plots import fig6_paper as fp
from experiments.bp_paper.panels import (AGREES, ALL, DIFFERS, EXP1, LARGE, SHORT, Result, bp_of, claim_list, frac, g3,
                             median, not_run, span)

CLAIMS = []  # (id, statement, rule, function) of rules 1a-3d, in the paper's order
claim = claim_list(CLAIMS)


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
