"""bp-paper's claims of Sec. V-B: the 29 rules of plots/bp_paper_report.py (in bp_paper_rules_*.py) on
the committed summaries and trials digests, each also on RESAMPLES parametric resamples of the
summary means (each mean drawn from N(mean, se²)); a rule's verdict is verdicts.from_resamples:
"agrees" / "differs" only when at least 95 % of the resamples say what the data say."""

import contextlib
import math
from collections import Counter

import numpy as np

from reports.core import markdown, stats, verdicts
from reports.core.study import Claim
from experiments.bp_paper.digest import digest_scans
from experiments.bp_paper.runs import EXP1, EXP1_1E7, EXP2, EXP3, summary_path

from experiments.bp_paper import rules as bpr# the 29 rules of Sec. V-B
from plots import fig6_paper as fp  # their data model: the nine panels of Fig. 6

RESAMPLES = 200  # parametric resamples of the summary means per rule
RESAMPLED = ("max_error_mean", "time_us_mean", "w_star_mean")  # the means the rules read
COUNTED = ("4c", "4f", "8")  # rules on counts only (trials completed, the digests' iteration maximum)

# The paper's side of each Sec. V-B rule: (its words as printed, where). Bullets of Sec. V-B:
# 1 BP, 2 BP vs LMIPDA/BAA, 3 LMIPDA vs BAA, 4 junction tree, 5 MCMCDA, 6 correlation decay.
PAPER = {
    "1a": ("≤ 0.015 in most cases", "Sec. V-B, bullet 1"),
    "1b": ("0.02 – 0.04", "Sec. V-B, bullet 1"),
    "1c": ("little or no deterioration", "Sec. V-B, bullet 1"),
    "2a": ("reduced by a factor of ten in most cases", "Sec. V-B, bullet 2"),
    "2b": ("only a few times", "Sec. V-B, bullet 2"),
    "2c": ("fractions of a millisecond; a little over a millisecond", "Sec. V-B, bullet 2"),
    "3a": ("similar", "Sec. V-B, bullet 3"),
    "3b": ("BAA significantly better", "Sec. V-B, bullet 3"),
    "3c": ("LMIPDA better", "Sec. V-B, bullet 3"),
    "3d": ("comparable", "Sec. V-B, bullet 3"),
    "4a": ("globally worse, often much worse", "Sec. V-B, bullet 4"),
    "4b": ("1-2 orders of magnitude", "Sec. V-B, bullet 4"),
    "4c": ("9 × 9 and 10 × 10 not completed", "Sec. V-B, bullet 4"),
    "4d": ("generally much better", "Sec. V-B, bullet 4"),
    "4e": ("2-4 orders of magnitude", "Sec. V-B, bullet 4"),
    "4f": ("most not completed", "Sec. V-B, bullet 4"),
    "5a": ("generally comparable", "Sec. V-B, bullet 5"),
    "5b": ("progressively worse", "Sec. V-B, bullet 5"),
    "5c": ("similar to or better", "Sec. V-B, bullet 5"),
    "5d": ("2-4 orders of magnitude", "Sec. V-B, bullet 5"),
    "6a": ("BP generally outperforms", "Sec. V-B, bullet 6"),
    "6b": ("BP tighter, CD larger spacings", "Sec. V-B, bullet 6"),
    "6c": ("particularly poorly at Pd = 0.9", "Sec. V-B, bullet 6"),
    "6d": ("slightly faster", "Sec. V-B, bullet 6"),
    "6e": ("2-3 orders of magnitude", "Sec. V-B, bullet 6"),
    "6f": ("4-5 orders of magnitude", "Sec. V-B, bullet 6"),
    "7a": ("around 300", "Sec. V-B, on Fig. 7"),
    "7b": ("minimal well-spaced, maximal close", "Sec. V-B, on Fig. 7"),
    "8": ("87", "Sec. V-B, after Fig. 7"),
}



def paper_report(root):
    """bp_paper_report's Report on the committed runs of experiments 1-3 and their digests."""
    paper_data = fp.PaperData(summary_path(root, EXP1), summary_path(root, EXP2), summary_path(root, EXP3),
                              [summary_path(root, EXP1_1E7)])
    return bpr.Report(paper_data, digest_scans(root, paper_data, {1: EXP1, 2: EXP2, 3: EXP3}))


@contextlib.contextmanager
def resampled_means(rows, columns, count, seed=stats.SEED):
    """Gives an iterator of `count` steps; at each step the rows' `columns` hold one parametric
    resample of their means (mean + se·N(0, 1), se from the matching *_se column; a draw below zero
    counts as zero, as these are means of non-negative values). The rows' text is restored after."""
    cells = [(r, c) for c in columns for r in rows if math.isfinite(fp.fnum(r.get(c)))]
    original = [r[c] for r, c in cells]
    ses = [fp.fnum(r.get(c[:-len("mean")] + "se")) for r, c in cells]
    draws = np.maximum(stats.parametric_resamples([fp.fnum(t) for t in original], ses, count, seed), 0.0)

    def steps():
        for draw in draws.tolist():
            for (r, c), v in zip(cells, draw):
                r[c] = repr(v)
            yield

    try:
        yield steps()
    finally:
        for (r, c), text in zip(cells, original):
            r[c] = text


def all_rows(paper_data):
    return [r for s in paper_data.summaries.values() for r in s.rows]


def evaluate_rules(rep):
    """[(id, statement, rule, Result on the data, share of resamples in which the rule agrees)].
    The rules that read no mean (COUNTED) give the same outcome in every resample."""
    point = [(cid, text, rule, fn(rep)) for cid, text, rule, fn in bpr.CLAIMS]
    agree = Counter({cid: RESAMPLES * (res.verdict == bpr.AGREES) for cid, _, _, res in point if cid in COUNTED})
    with resampled_means(all_rows(rep.data), RESAMPLED, RESAMPLES) as steps:
        for _ in steps:
            for cid, _, _, fn in bpr.CLAIMS:
                if cid not in COUNTED:
                    agree[cid] += fn(rep).verdict == bpr.AGREES
    return [(cid, text, rule, res, agree[cid] / RESAMPLES) for cid, text, rule, res in point]


def rule_verdict(result, share):
    """from_resamples on a rule's outcome; a rule whose data only bound the answer (INCONCLUSIVE:
    rule 8 while an experiment's maximum is known only as a lower bound) is "agrees within error"
    (the data neither confirm nor contradict it); a rule the data cannot evaluate is "not run"."""
    if result.verdict == bpr.INCONCLUSIVE:
        return verdicts.WITHIN_ERROR
    if result.verdict not in (bpr.AGREES, bpr.DIFFERS):
        return verdicts.NOT_RUN
    return verdicts.from_resamples(result.verdict == bpr.AGREES, share)


def outcome_text(result, share):
    """How the verdict was reached, after the rule: the resample share, or why there is none."""
    if result.verdict == bpr.INCONCLUSIVE:
        return "the data bound the answer without deciding it"
    return share_text(share) if rule_verdict(result, share) != verdicts.NOT_RUN else "not run"


def share_text(share):
    return f"the rule holds in {markdown.percent(share, 0)} of {RESAMPLES} resamples of the means"


def section_vb_claims(report, rep):
    """The 29 rules of Sec. V-B as claims (rule functions in rules.py and rules_*.py); returns
    their evaluations for the details list."""
    evaluated = evaluate_rules(rep)
    for cid, text, rule, res, share in evaluated:
        verdict = rule_verdict(res, share)
        report.claim(Claim(cid, text, PAPER[cid][1], PAPER[cid][0], res.measured, verdict,
                           f"{rule}; {outcome_text(res, share)}"))
    return evaluated


def rules_and_details(evaluated):
    """Each rule with its resample share, and the per-panel numbers behind it."""
    lines = []
    for cid, text, rule, res, share in evaluated:
        lines.append(f"- **{cid}** {text}. *Rule:* {rule}; {outcome_text(res, share)}.")
        lines += [f"  - {d}" for d in res.details]
    return "\n".join(lines)
