"""Williams & Lau 2014 on BP's convergence, as rules: the convergence parameter W* of Fig. 7 (7a,
7b) and the largest number of BP iterations in the experiment (8), read from trials.csv where a run
has one (TrialsScan). The comment above each rule function states its rule."""

import math

from experiments.bp_paper.panels import AGREES, ALL, DIFFERS, INCONCLUSIVE, SHORT, Result, bp_of, claim_list, g3, not_run

CLAIMS = []  # (id, statement, rule, function) of rules 7a, 7b and 8
claim = claim_list(CLAIMS)


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
# the max over points of iterations_p95 is a lower bound only (so is the maximum while any
# experiment lacks its trials.csv): differs if it exceeds 174, else
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
        if missing:  # their maximum is unknown but at least their p95: the maximum is a lower bound
            lb = max((v for k, v in p95.items() if rep.data.by_key[k].exp in missing), default=math.nan)
            m += f"; no trials.csv for experiment {', '.join(map(str, missing))}"
            if not math.isnan(lb) and lb > mx:
                mx = lb
                m += f" (their max ≥ p95 {g3(lb)})"
            if mx > 174:
                return Result(DIFFERS, m + ": the maximum is at least this, above 174", details)
            return Result(INCONCLUSIVE, m + ": the maximum over all experiments is not known, only that it is at "
                          f"least {g3(mx)}", details)
        ok = 44 <= mx <= 174
        return Result(AGREES if ok else DIFFERS, m, details)
    if p95max > 174:
        return Result(DIFFERS, f"max p95 {g3(p95max)} > 174 (no trials.csv; the max is at least this)", details)
    return Result(INCONCLUSIVE, f"max p95 {g3(p95max)}; maximum unknown (no trials.csv)", details)
