"""Williams & Lau, "Multiple scan data association by convex variational inference", Sec. IV
(Figs 3-5, multiscan-convex-variational), against dabench's bearings study: the checks that fill
templates/multiscan.md.

Data: results/multiscan/<run>/targets.csv (one row per target and method: the HPD value, eq 92, of
the target's true location under its belief, and the belief's entropy), trials.csv (cost and
convergence of each method on each trial) and meta.json. A statistic of the targets (the 80th
percentile of HPD, "p80"; a median entropy; a share of HPD values) gets its standard error from a
bootstrap over trials (a trial's targets resampled together), and an ordering of methods is
decided on paired resamples (every method of a run sees the same trials). The paper ran 200
trials per figure, as we do, so its own standard error of a statistic is estimated by ours.

The checks live beside this file: runs.py (the runs, their commands, the steps after
them), targets.py (the targets and their bootstrap statistics), calibration.py
(exact Bayes at each particle count), paper.py (the paper's statements),
readings.py (the open readings and particle counts) and cost.py (time and
convergence, Algorithm 2's cost)."""

from reports.core import data, markdown, verdicts
from reports.core.study import Study
from experiments.multiscan.calibration import calibration_section
from experiments.multiscan.cost import ALGORITHM2, NEWTON, cost_section
from experiments.multiscan.paper import claims_cv_cvs, claims_fig5, claims_jpda, claims_msbp, figure_readings
from experiments.multiscan.readings import readings_section
from experiments.multiscan.runs import FIGURES, FOLDER, RUNS, STEPS
from experiments.multiscan.targets import load_figures, particles_text, trial_resamples

# What render.py and tests/reports/test_multiscan.py read from this module.
__all__ = ["STUDY", "checks", "trial_resamples", "NEWTON", "ALGORITHM2"]


def setup_values(report, root, figures):
    """Particles per track, trials per figure and the mean number of targets, from the runs."""
    params = figures["fig4"].targets.params
    report.value("setup.particles", particles_text(int(data.num(params, "particles"))))
    report.value("setup.mean_targets", f"{data.num(params, 'mean_targets'):g}")
    trials = sorted({data.read_meta(root, f"{FOLDER}/{name}").get("trials_per_point") for name, _ in FIGURES})
    report.value("setup.trials", " / ".join(str(t) for t in trials))


def differences(report, ids):
    """The claims whose verdict is differs or direction only, one line each."""
    by_id = {c.id: c for c in report.claims}
    lines = [f"**{i}** {by_id[i].statement}: paper {by_id[i].paper}, ours {by_id[i].ours} — *{by_id[i].verdict}*"
             for i in ids if by_id[i].verdict in (verdicts.DIFFERS, verdicts.DIRECTION_ONLY)]
    return markdown.bullets(lines) if lines else "None: every statement agrees or agrees within error."


def checks(report):
    root = report.root
    figures = load_figures(root)
    fig3, fig4, fig5 = figures["fig3"], figures["fig4"], figures["fig5"]
    setup_values(report, root, figures)
    calibration_section(report, root)
    figure_readings(report, figures)
    claims_msbp(report, fig3, fig4)
    claims_jpda(report, fig3, fig4)
    claims_cv_cvs(report, fig3, fig4)
    claims_fig5(report, fig5)
    readings_section(report, root, fig4)
    cost_section(report, root)
    paper_ids = [f"P{i}" for i in range(1, 17)]
    ours = ["E1", "E2", "E3", "O1", "O2"]
    report.value("paper_claims", report.claims_table(paper_ids))
    report.value("paper_claims.counts", report.verdict_counts(paper_ids))
    report.headline("statements of the paper", paper_ids)
    report.value("our_claims", report.claims_table(ours, "statement (ours)"))
    report.value("claim_rules", report.rules_list(ours + paper_ids))
    report.value("paper_differences", differences(report, paper_ids))


STUDY = Study(name="multiscan", report=f"{FOLDER}/REPORT.md", template="experiments/multiscan/template.md",
              runs=RUNS, steps=STEPS, checks=checks)
