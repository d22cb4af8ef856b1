"""JDT-VB on the OTHR multipath scenario (jdt-vb-multipath-othr, Sec. IV): Table IV against the
paper's, the paper's Sec. IV-B statements, and our findings on its readings, the metric settings
and MD-HMHT, all from the committed trials.csv of each run (every run uses seed 2019 and the same
four settings, so the scenario draws of a (setting, trial) are the same in every run: differences
between trackers or readings are paired).

The checks live beside this file: runs.py (the runs, their commands, trackers and readings),
table4.py (Table IV and the comparisons every claim uses), paper.py (the paper's
statements, our trackers against its Table IV), iterations.py (the VB iterations, the free
energy, Fig. 7), readings.py (the paper-literal JDT-VB), metrics.py (AEE and the
metric settings) and mdhmht.py (MD-HMHT's readings)."""

from reports.core.study import Study
from experiments.jdtvb.iterations import convergence, fig7_section, free_energy
from experiments.jdtvb.mdhmht import mdhmht_section
from experiments.jdtvb.metrics import aee_section, sensitivity_section
from experiments.jdtvb.paper import (claim_accuracy, claim_fig6, claim_jdtvb_vs_paper, claim_low_snr_overall,
                                         claim_mospa, claim_nft, claim_nvt_tpd_low_pd, claim_snr, claim_tet, claim_ttl,
                                         mpmd_vs_paper)
from experiments.jdtvb.readings import literal_section
from experiments.jdtvb.runs import FOLDER, RUNS, STEPS, TABLE4
from experiments.jdtvb.table4 import best_table, table_iv
from experiments.jdtvb.tracking_runs import TrackingRun


def checks(report):
    root = report.root
    run = TrackingRun(root, TABLE4)
    readings = TrackingRun(root, f"{FOLDER}/table4-readings")
    table_iv(report, run)
    claim_snr(report, run)
    claim_nvt_tpd_low_pd(report, run)
    claim_nft(report, run)
    claim_ttl(report, run)
    claim_accuracy(report, run)
    claim_mospa(report, run)
    claim_tet(report, run)
    claim_low_snr_overall(report, run)
    claim_fig6(report, run)
    claim_jdtvb_vs_paper(report, run)
    paper_ids = ["P1", "P2a", "P2b", "P3a", "P3b", "P4a", "P4b", "P5a", "P5b", "P5c", "P6", "P7a", "P7b", "P8",
                 "P10"]
    best_table(report, run)
    convergence(report, run)
    by_run_b = free_energy(report, root, run, readings)
    literal_section(report, run, readings)
    aee_section(report, root, run)
    sensitivity_section(report, root, run)
    mdhmht_section(report, root, run)
    fig7_section(report, by_run_b, root)
    mpmd_vs_paper(report, run)
    paper_ids.insert(-1, "P9")
    report.value("paper_claims", report.claims_table(paper_ids))
    report.value("paper_claims.counts", report.verdict_counts(paper_ids))
    report.headline("statements of the paper", paper_ids)
    ours = ["B1", "B2", "B3", "B4", "F1", "R1", "R2", "R3", "R4", "R5", "R6", "R7", "A1a", "A1b", "A1c", "S1", "S2",
            "S3", "S5", "S6", "M1", "M2", "M3", "M4", "T1", "T2"]
    report.value("our_claims", report.claims_table(ours, "statement (ours)"))
    report.value("claim_rules", report.rules_list(paper_ids + ours))


STUDY = Study(name="jdtvb", report=f"{FOLDER}/REPORT.md", template="experiments/jdtvb/template.md",
              runs=RUNS, steps=STEPS, checks=checks)
