"""Section V-B of Williams & Lau 2014, bullets 4-6, as rules: the methods that buy accuracy with
computation, against BP: the junction tree at each threshold, including which n×3 and n×n points it
could not complete (4a-4f), MCMCDA at 10^5-10^7 samples (5a-5d) and correlation decay at depths 3,
5 and 7 (6a-6f). The comment above each rule function states its rule."""

import math
import statistics
from collections import Counter

from experiments.bp_paper.panels import (AGREES, ALL, DIFFERS, EXP1, LARGE, NOT_RUN, SHORT, Result, bp_of, claim_list, frac,
                             g3, median, not_run, spearman, span)

CLAIMS = []  # (id, statement, rule, function) of rules 4a-6f, in the paper's order
claim = claim_list(CLAIMS)


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
