"""bp-paper: Williams & Lau 2014 (bp-marginal-association), Section V, reproduced with dabench: the
study and the order of its checks, and the names render.py and the tests read.

The 29 statements of Sec. V-B are the rules of plots/bp_paper_report.py, on the data model of
plots/fig6_paper.py. Each rule is evaluated on the committed summaries and on RESAMPLES parametric
resamples of their means (each mean drawn from N(mean, se²)); its verdict is
verdicts.from_resamples: "agrees" / "differs" only when at least 95 % of the resamples say what the
data say. Besides those: the wall-time target of experiment 1 (issue 3), the BP-vs-exact run, the
JT threshold readings, the references of experiments 2 and 3, the BP iteration maximum (from the
trials digests this study writes) and the kernel benchmarks (results/bp-paper/bench.json).

The checks live beside this file: runs.py (the runs, their commands and the steps after
them), digest.py (the trials digests), section_vb.py (the Sec. V-B rules as
claims), run_checks.py (the runs' sizes and costs, T1, R1), differences.py
(where and why we differ, the JT threshold readings: J1) and kernels.py (the Timing
section: K1-K6).

Everything is read from summary.csv, meta.json, trials-digest.csv and bench.json under the root."""

from reports.core.study import Study
from experiments.bp_paper.differences import (iteration_values, jt_readings, lmipda_baa_values, mcmcda_values,
                                                  reference_values, threshold_effect, time_values)
from experiments.bp_paper.digest import DigestScan, digest
from experiments.bp_paper.kernels import (BP_2X3, BP_LARGE, CHAINS, EHM_2X3, EHM_3XN, FIG3, JT_1E3,
                                              bench_values)
from experiments.bp_paper.run_checks import bp_vs_exact, cost_shares, run_sizes, timing_noise, wall_time_claim
from experiments.bp_paper.runs import BENCH, DIGEST, EXP1, FOLDER, RUNS, STEPS
from experiments.bp_paper.section_vb import RESAMPLES, paper_report, rules_and_details, section_vb_claims

# What render.py and tests/reports/test_bp_paper.py read from this module.
__all__ = ["STUDY", "checks", "digest", "DigestScan", "paper_report", "section_vb_claims", "wall_time_claim",
           "bench_values", "FOLDER", "EXP1", "DIGEST", "BENCH", "BP_2X3", "FIG3", "BP_LARGE", "EHM_2X3", "EHM_3XN",
           "CHAINS", "JT_1E3"]


def claims_table(report, ids, side):
    """Report.claims_table with the "paper" column named `side` (our own statements compare with
    a target or another run, not with the paper)."""
    header, rule, *rows = report.claims_table(ids).split("\n")
    return "\n".join([header.replace("| paper |", f"| {side} |"), rule] + rows)


def checks(report):
    root = report.root
    rep = paper_report(root)
    evaluated = section_vb_claims(report, rep)
    ids = [cid for cid, *_ in evaluated]
    report.value("resamples", str(RESAMPLES))
    report.value("vb_claims", report.claims_table(ids))
    report.value("vb_counts", report.verdict_counts(ids))
    report.headline("statements of Sec. V-B", ids)
    report.value("vb_details", rules_and_details(evaluated))
    report.value("run_sizes", run_sizes(root))
    wall_time_claim(report, root)
    report.value("exp1_cost_shares", cost_shares(root))
    report.value("timing_noise", timing_noise(rep))
    other = bp_vs_exact(report, root, rep)
    jt_readings(report, root)
    time_values(report, rep)
    lmipda_baa_values(report, rep)
    mcmcda_values(report, rep)
    reference_values(report, rep)
    threshold_effect(report, rep)
    iteration_values(report, root, rep, other)
    bench_values(report, rep)
    for name, ids in (("ours_claims", ["T1", "R1", "J1"]), ("kernel_claims", ["K1", "K2", "K3", "K4", "K5", "K6"])):
        report.value(name, claims_table(report, ids, "target, or the other side"))
        report.value(f"{name}_rules", report.rules_list(ids))


STUDY = Study(
    name="bp-paper",
    report=f"{FOLDER}/REPORT.md",
    template="experiments/bp_paper/template.md",
    runs=RUNS,
    steps=STEPS,
    checks=checks,
    digest=digest,
)
