"""JDT-VB's Table IV beside ours, and how the study's claims compare: an entry of ours against the
paper's Table IV as printed (plots/jdtvb_table.py; the paper's standard error estimated as ours),
tracker against tracker on the same draws, the direction the paper's own table takes, and a claim
made of many such comparisons (its verdict the worst part's). Also which tracker is best in each
Table IV metric at each setting."""

import math

from reports.core import markdown, verdicts
from reports.core.study import Claim
from experiments.jdtvb.runs import LITERAL, MDHMHT_LITERAL, PAPER_TRACKERS
from experiments.jdtvb.tracking_runs import HEADING, HIGHER_IS_BETTER, METRICS, SETTINGS, setting_label

from plots import jdtvb_table  # Table IV as printed: one copy, shared with the plot script

PAPER_NAME = jdtvb_table.PAPER_NAMES
TABLE_METRICS = [m for m, _ in jdtvb_table.METRICS]  # Table IV's rows, TET last
PAPER_RUNS = 100  # Sec. IV-A: "100 Monte Carlo runs are carried out"


def paper_value(setting, tracker, metric):
    """The paper's Table IV entry as printed (text) and as a number."""
    text = jdtvb_table.PAPER_TABLE_IV[setting][PAPER_NAME[tracker]][TABLE_METRICS.index(metric)]
    return text, float(text)


def vs_paper(run, setting, tracker, metric, paper_tracker=None):
    """(verdict, ours mean, ours se, paper text) of one Table IV cell against the paper's row of
    paper_tracker (default: tracker). The paper's standard error is estimated as ours: its runs
    are as many (100) and, we assume, as spread as ours."""
    m, se, n = run.mean(setting, tracker, metric)
    text, p = paper_value(setting, paper_tracker or tracker, metric)
    per_run_sd = se * math.sqrt(n) if n > 1 else math.nan
    verdict, _, _ = verdicts.compare_value(m, se, p, per_run_sd / math.sqrt(PAPER_RUNS), text)
    return verdict, m, se, text


MARK = {verdicts.WITHIN_ERROR: "≈", verdicts.DIFFERS: "≠"}


# ----------------------------------------------------------------------------- Table IV


PAPER_ROW_OF = {LITERAL: "jdt-vb", MDHMHT_LITERAL: "md-hmht"}  # the paper's row a literal row is read against


def table_iv(report, run):
    """Table IV: our rows (mean ± SE) and the paper's, each paper cell marked ≈ (within error of
    ours) or ≠ (differs beyond error); TET is not compared (MATLAB on a Core i5). The
    paper-literal rows are counted against their tracker's paper row."""
    rows, counts = [], {}
    for setting in SETTINGS:
        for tracker in ["jdt-vb", LITERAL, "mptf", "md-hmht", MDHMHT_LITERAL]:
            ok, total = run.runs(setting, tracker)
            rows.append([setting_label(setting), tracker, f"{ok}/{total}"]
                        + [run.cell(setting, tracker, m) for m in TABLE_METRICS[:-1]]
                        + [markdown.sig(run.mean(setting, tracker, "tet_s")[0], 2)])
            if tracker in PAPER_ROW_OF:
                for m in TABLE_METRICS[:-1]:
                    counts.setdefault(tracker, []).append(vs_paper(run, setting, tracker, m, PAPER_ROW_OF[tracker])[0])
                continue
            paper_cells = []
            for m in TABLE_METRICS[:-1]:
                verdict, _, _, text = vs_paper(run, setting, tracker, m)
                counts.setdefault(tracker, []).append(verdict)
                paper_cells.append(f"{text} {MARK[verdict]}")
            rows.append(["", f"{PAPER_NAME[tracker]} (paper)", f"{PAPER_RUNS}"] + paper_cells
                        + [paper_value(setting, tracker, "tet_s")[0]])
    header = ["setting", "tracker", "runs"] + [HEADING[m] for m in TABLE_METRICS]
    report.value("table_iv", markdown.table(header, rows))
    for tracker, vs in counts.items():
        within = sum(v == verdicts.WITHIN_ERROR for v in vs)
        report.value(f"table_iv.within.{tracker.replace(':literal=1', '-literal')}", f"{within} of {len(vs)}")
    return counts


def best_table(report, run):
    """Which of the paper's three trackers is best in each Table IV metric at each setting:
    the best mean, "≈ X" when a runner-up X is within two paired standard errors of it."""
    rows, best_counts = [], {}
    for setting in SETTINGS:
        row = [setting_label(setting)]
        for metric, _, up in METRICS:
            means = {t: run.mean(setting, t, metric)[0] for t in PAPER_TRACKERS}
            best = max(means, key=means.get) if up else min(means, key=means.get)
            tied = []
            for other in PAPER_TRACKERS:
                if other == best:
                    continue
                v, _, _ = tracker_direction(run, setting, best, other, metric)
                if v != verdicts.AGREES:
                    tied.append(other)
            row.append(best + "".join(f" ≈ {t}" for t in tied))
            if not tied:
                best_counts.setdefault(best, []).append((setting, metric))
        rows.append(row)
    report.value("best_table", markdown.table(["setting"] + [h for _, h, _ in METRICS], rows))
    cells = len(SETTINGS) * len(METRICS)
    for tracker in PAPER_TRACKERS:
        report.value(f"best.{tracker}", f"{len(best_counts.get(tracker, []))} of {cells}")


# ----------------------------------------------------------------------------- comparisons


def better_sign(metric):
    return +1 if HIGHER_IS_BETTER[metric] else -1


def tracker_direction(run, setting, a, b, metric, a_better=True):
    """Verdict that tracker a is better (a_better) or worse than b in metric, paired on the draws."""
    d, se, _ = run.paired(setting, a, b, metric)
    sign = better_sign(metric) * (1 if a_better else -1)
    return verdicts.compare_direction(d, se, sign), d, se


SHOWN = 4  # parts of a claim named in its table row; all of them are listed under the rules


def comparisons_claim(report, cid, statement, source, items, paper_items, rule, paper_text=None):
    """A claim made of several comparisons: items [(label, verdict, difference, se)], paper_items
    [(label, holds in the paper's own table)] or None. Its verdict is the worst part's; its "ours"
    counts the parts by verdict and names the contradicted ones (then those within error when
    others are confirmed); the details list every part."""
    verdict = verdicts.worst(v for _, v, _, _ in items)
    named = {v: [f"{label} ({markdown.pm(d, se)})" for label, v2, d, se in items if v2 == v]
             for v in (verdicts.AGREES, verdicts.WITHIN_ERROR, verdicts.DIFFERS)}
    parts = [f"{len(named[v])} {name}" for v, name in ((verdicts.AGREES, "confirmed"),
                                                         (verdicts.WITHIN_ERROR, "within error"),
                                                         (verdicts.DIFFERS, "contradicted")) if named[v]]
    ours = f"{', '.join(parts)} of {len(items)}"
    shown = named[verdicts.DIFFERS] if named[verdicts.DIFFERS] else (
        named[verdicts.WITHIN_ERROR] if named[verdicts.AGREES] else [])
    if shown:
        kind = "contradicted" if named[verdicts.DIFFERS] else "within error"
        ours += f"; {kind}: " + "; ".join(shown[:SHOWN]) + (f"; … {len(shown) - SHOWN} more" if len(shown) > SHOWN else "")
    if paper_text is None and paper_items is not None:
        holds = sum(1 for _, h in paper_items if h)
        paper_text = f"{holds} of {len(paper_items)} in its Table IV"
    # Details: the parts that are not confirmed (for a claim that parts should be confirmed), or
    # the contradicted ones (for a claim that parts lie within error of each other).
    listed = {verdicts.DIFFERS} | ({verdicts.WITHIN_ERROR} if named[verdicts.AGREES] else set())
    details = [f"{label}: {markdown.pm(d, se)}, {v}" for label, v, d, se in items if v in listed]
    if paper_items is not None:
        against = [label for label, h in paper_items if not h]
        if against:
            details.append("the paper's own Table IV goes the other way in: " + "; ".join(against))
    return report.claim(Claim(cid, statement, source, paper_text or "–", ours, verdict, rule, details))


def paper_direction(setting, a, b, metric, a_better=True):
    """Whether the paper's own Table IV has tracker a better (or worse) than b."""
    pa, pb = paper_value(setting, a, metric)[1], paper_value(setting, b, metric)[1]
    better = pa > pb if HIGHER_IS_BETTER[metric] else pa < pb
    return better if a_better else (pa != pb and not better)
