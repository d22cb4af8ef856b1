"""TBD-BP (Liang, Kropfreiter & Meyer, "Belief propagation for track-before-detect", IEEE SPL 2023)
and its supplement (tbd-bp-supplement; sources and tags in docs/models/track-before-detect.md,
section 0): the toy of Fig. 1, the single run of Figs 2-3, the letter's Fig. 2
(averaged GOSPA over k) as the supplement quotes it, the runtime of Fig. 4, and our sensitivity
runs (sigma_S^2, reading D2, particles, duplicate merging).

The per-step and per-run files of the runs (steps.csv, trials.csv, beliefs.csv) are not committed;
`digest(root)` writes small digests of them next to each run's summary.csv, and the checks read
only those digests, summary.csv, meta.json and, when present, the benchmark's bench.json. Every
tracker of a run sees identical frames (the frames of a trial depend only on the seed and
(point, trial)), so differences between trackers are paired over runs; tbd/merge.ini repeats the
seed of tbd/gospa.ini, so its runs are paired with that run's first 200.

The checks live beside this file: runs.py (the runs, their commands, the steps after them and
the trackers), digest.py (writing the digests), data.py (reading them), toy.py and
calibration.py (Fig. 1 and the readings' calibration), gospa.py (Figs 2-3, TBD-MB's readings,
the extra estimates and the readings and schedules), tuning.py (particles, merging) and
runtime.py (Fig. 4 and the benchmark)."""

from reports.core import markdown
from reports.core.study import Study
from experiments.tbd import calibration as tbd_calibration
from experiments.tbd import toy as tbd_toy
from experiments.tbd.data import TbdData, k_ranges
from experiments.tbd.digest import DIGESTS, digest
from experiments.tbd.gospa import (check_constants, check_excess, check_gospa, check_mb_readings, check_readings,
                                       check_single_run, run_range_verdict, support_energy_share)
from experiments.tbd.runs import BENCH, BP1, BP2, CALIBRATION, FOLDER, GOSPA, IEMB, MB, RUNS, RUNTIME, STEPS, TOY
from experiments.tbd.runtime import check_runtime, paper_runtime
from experiments.tbd.tuning import check_merge, check_particles

# What render.py and tests/reports/test_tbd.py read from this module.
__all__ = ["STUDY", "checks", "digest", "DIGESTS", "FOLDER", "TOY", "GOSPA", "RUNTIME", "BENCH", "MB", "IEMB", "BP1",
           "BP2", "k_ranges", "paper_runtime", "run_range_verdict", "support_energy_share"]


def checks(report):
    d = TbdData(report.root)
    check_constants(report)
    tbd_toy.check_toy(report, d, TOY)
    tbd_calibration.check_calibration(report, d, CALIBRATION)
    check_gospa(report, d)
    check_single_run(report, d)
    check_mb_readings(report, d)
    check_excess(report, d)
    check_readings(report, d)
    check_particles(report, d)
    check_merge(report, d)
    check_runtime(report, d)
    report.value("claims.all", verdict_index(report.claims))
    report.value("claims.rules", grouped_rules(report.claims))
    report.value("claims.counts", report.verdict_counts())
    report.headline("claims, the papers' and ours")


def verdict_index(claims):
    """All claims in one short table: id, statement, verdict (the numbers are in their sections)."""
    return markdown.table(["#", "statement", "verdict"],
                          [[c.id, c.statement, f"**{c.verdict}**"] for c in claims])


def grouped_rules(claims):
    """Each verdict rule once, with the ids of the claims it decides."""
    ids = {}
    for c in claims:
        ids.setdefault(c.rule, []).append(c.id)
    return markdown.bullets(f"**{', '.join(group)}**: {rule}" for rule, group in ids.items())


STUDY = Study(
    name="tbd",
    report=f"{FOLDER}/REPORT.md",
    template="experiments/tbd/template.md",
    runs=RUNS,
    steps=STEPS,
    checks=checks,
    digest=digest,
)
