#!/usr/bin/python3
"""Section V-B of Williams & Lau 2014 (bp-marginal-association): every quantitative claim next to
the measured numbers, as a Markdown table with a verdict per claim.

Usage:
  /usr/bin/python3 -m experiments.bp_paper.rules [--exp1 RUN1/summary.csv] [--exp2 RUN2/summary.csv]
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

The rules live in rules_bp.py (Sec. V-B bullets 1-3), rules_comparators.py
(bullets 4-6) and rules_convergence.py (Fig. 7, the iteration maximum), on the panels and
helpers of panels.py.

Needs only the standard library (and fig6_paper.py / fig6.py, which import numpy/matplotlib).
"""

import argparse
import csv
import os
import sys
from collections import Counter

sys.dont_write_bytecode = True
from plots import fig6_paper as fp
from plots.fig6 import note
from experiments.bp_paper import rules_bp as bp_paper_rules_bp
from experiments.bp_paper import rules_comparators as bp_paper_rules_comparators
from experiments.bp_paper import rules_convergence as bp_paper_rules_convergence
from experiments.bp_paper.panels import AGREES, DIFFERS, INCONCLUSIVE, NOT_RUN, SHORT, Report, Result, TrialsScan

# Every rule, (id, statement, rule, function), in the paper's order.
CLAIMS = bp_paper_rules_bp.CLAIMS + bp_paper_rules_comparators.CLAIMS + bp_paper_rules_convergence.CLAIMS


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
    fp.add_input_arguments(ap)  # --exp1, --exp1-extra, --exp2, --exp3, as for fig6_paper.py
    ap.add_argument("--out", metavar="FILE", help="write the Markdown here instead of stdout")
    ap.add_argument("--no-trials", action="store_true", help="do not read trials.csv next to the summaries")
    args = ap.parse_args(argv)
    data = fp.read_inputs(args)
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
