"""The BP paper's panels as the rules of Section V-B read them (rules_bp.py,
rules_comparators.py, rules_convergence.py; rules.py runs them): the
panel keys each rule looks at, the verdict words and a rule's Result, the number formatting of its
measured text, Report (which SPEC of an algorithm family a panel holds, and its values per x) and
TrialsScan (one streamed pass over a run's trials.csv). The conventions that turn the paper's words
into numbers are listed in rules.py's docstring."""

import csv
import math
import statistics
from collections import Counter

from plots import fig6_paper as fp
from plots.fig6 import fnum

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



def span(vals):
    """' (panels a–b)' for several values, '' for one."""
    vals = list(vals)
    return f" (panels {g3(min(vals))}–{g3(max(vals))})" if len(vals) > 1 else ""


def claim_list(claims):
    """The decorator @claim(id, statement, rule) of a rules module: appends (id, statement, rule,
    function) to that module's list `claims`, in the order of the file."""
    def claim(cid, text, rule):
        def deco(fn):
            claims.append((cid, text, rule, fn))
            return fn
        return deco
    return claim


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


def bp_of(rep, p):
    return rep.spec(p, "bp")


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
