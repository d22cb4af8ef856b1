"""The multi-scan paper's open readings on Fig. 4's setting (initialising sensor, scan order) at
10 000 / 1000 / 300 particles, the particle counts of the other methods, each against the paper's
p80, and O2: the default reading repeats Fig. 4's values exactly."""

import os

import numpy as np

from reports.core import data, markdown, verdicts
from reports.core.study import Claim
from experiments.multiscan.paper import PAPER_MSBP_TAIL, PAPER_P80, percent_text, vs_paper_percent
from experiments.multiscan.runs import FOLDER, PARTICLE_COUNTS_RUN, READINGS
from experiments.multiscan.targets import Figure, label, particles_text, read_targets

# The readings are taken for READING_METHODS; the first of READINGS is the scenario's default
# (DEFAULT_READING), the reading of Figs 3-5.
SHORT = {"random": "random/round robin", "corner": "corner/round robin", "grouped": "random/grouped",
         "corner-grouped": "corner/grouped"}  # a reading in running text
DEFAULT_READING = "corner"
READING_METHODS = ["jpda-bp", "cv", "cvs:gamma=0.95"]
READING_KEY = {"jpda-bp": "jpda_bp", "cv": "cv", "cvs:gamma=0.95": "cvs095"}  # template value names
PARTICLE_COUNT_METHODS = ["msbp", "cvs:gamma=0.75", "cvs:gamma=0.55"]


def by_particles(root, folder):
    """{particles: Figure} of a run whose sweep points differ only in the particle count."""
    return {int(data.num(t.params, "particles")): Figure(t, f"{folder} point {p}")
            for p, t in read_targets(root, folder).items()}


def reading_tables(report, readings):
    """One table per method of READING_METHODS: p80 [95 % interval] per reading and particle count,
    its difference from the default reading at the same count (independent trials: SEs combined),
    the likelihood-ranked p80 (while E3 keeps that column), and the verdict against the paper's p80."""
    default = readings.get(DEFAULT_READING, {})
    show_likelihood = report.values.get("calibration.likelihood_ok") == "yes"
    lines = []  # per method: the cells within error of the paper's p80
    for method in READING_METHODS:
        rows, agreeing = [], []
        for name, text in READINGS:
            for particles, figure in sorted(readings.get(name, {}).items(), reverse=True):
                p, se = figure.value("p80", method), figure.se("p80", method)
                verdict = vs_paper_percent(p, se, PAPER_P80[method])
                if verdict == verdicts.WITHIN_ERROR:
                    agreeing.append(f"{SHORT[name]} at {particles_text(particles)}")
                base = default.get(particles)
                if name == DEFAULT_READING or base is None:
                    delta = "–"
                else:
                    delta_se = verdicts.combined_se(se, base.se("p80", method))
                    decimals = markdown.se_decimals(delta_se) or 3
                    delta = f"{markdown.signed(p - base.value('p80', method), decimals)} ± {delta_se:.{decimals}f}"
                row = [text, particles_text(particles), figure.pm_interval("p80", method), delta]
                if show_likelihood:
                    row.append(figure.pm_interval("p80_likelihood", method))
                rows.append(row + [verdict])
        header = ["reading (initialising sensor, scan order)", "particles", "p80 [95 % interval]",
                  "p80 − default reading's (SEs combined)"] + (["p80, likelihood ranking"] if show_likelihood else []) + \
                 [f"against the paper's {float(percent_text(PAPER_P80[method])) / 100:.2f}"]
        key = READING_KEY[method]
        report.value(f"readings.{key}", markdown.table(header, rows, "lrrr" + ("r" if show_likelihood else "") + "l")
                     if rows else "Not run.")
        lines.append(f"{label(method)} (paper {float(percent_text(PAPER_P80[method])) / 100:.2f}): "
                     + ("; ".join(agreeing) if agreeing else "none"))
    report.value("readings.agreeing", markdown.bullets(lines))


def particle_count_table(report, counts, fig4):
    """MSBP's and CVS(0.75 / 0.55)'s statistics at 300 and 1000 particles (particle-counts run)
    and at 10 000 (Fig. 4), each against the paper's number."""
    figures = dict(counts)
    figures[int(data.num(fig4.targets.params, "particles"))] = fig4
    rows = []
    for particles, figure in sorted(figures.items()):
        tail, tail_se = figure.value("ge_tail", "msbp"), figure.se("ge_tail", "msbp")
        row = [particles_text(particles) + (" (Fig. 4)" if figure is fig4 else ""), figure.pm_interval("p80", "msbp"),
               f"{figure.pm_percent('ge_tail', 'msbp')} ({vs_paper_percent(tail, tail_se, PAPER_MSBP_TAIL)})",
               figure.pm_percent("ge_near", "msbp")]
        for method in PARTICLE_COUNT_METHODS[1:]:
            verdict = vs_paper_percent(figure.value("p80", method), figure.se("p80", method), PAPER_P80[method])
            row.append(f"{figure.pm_interval('p80', method)} ({verdict})")
        rows.append(row)
    report.value("readings.particle_counts", markdown.table(
        ["particles", "MSBP p80", f"MSBP HPD ≥ 0.9999 (paper {PAPER_MSBP_TAIL.replace('%', ' %')})", "MSBP HPD ≥ 0.99",
         f"CVS(0.75) p80 (paper {float(percent_text(PAPER_P80['cvs:gamma=0.75'])) / 100:.2f})",
         f"CVS(0.55) p80 (paper {float(percent_text(PAPER_P80['cvs:gamma=0.55'])) / 100:.2f})"], rows, "lrrrrr"))


def claim_default_reading_repeats_fig4(report, readings, fig4):
    """O2 (ours): the default reading's 10 000-particle point has Fig. 4's seed, point and scenario,
    so its HPD values and entropies must equal Fig. 4's exactly (the same trials, a later build)."""
    figure = readings.get(DEFAULT_READING, {}).get(int(data.num(fig4.targets.params, "particles")))
    if figure is None:
        report.claim(Claim("O2", "The default reading at 10 000 particles repeats Fig. 4's values exactly", "ours",
                           "–", "not run", verdicts.NOT_RUN, "a count: identical values"))
        return
    a, b = figure.targets, fig4.targets
    aligned = len(a.trial) == len(b.trial) and np.array_equal(a.trial, b.trial)  # the same (trial, target) rows
    same = total = 0
    for method in READING_METHODS:
        i, j = a.methods.index(method), b.methods.index(method)
        total += len(b.trial)
        if aligned:
            same += int(np.sum((a.hpd[:, i] == b.hpd[:, j]) & (a.entropy[:, i] == b.entropy[:, j])))
    report.claim(Claim(
        "O2", "The default reading's 10 000-particle point (Fig. 4's seed, point and scenario, a later build) "
        "repeats Fig. 4's HPD values and entropies of JPDA-BP, CV and CVS(0.95) exactly", "ours", "–",
        f"{same} of {total} (target, method) pairs identical", verdicts.AGREES if same == total else verdicts.DIFFERS,
        "a count (no sampling error): every HPD value and entropy bit-identical"))


def readings_section(report, root, fig4):
    """The readings × particle-count tables, the particle counts of the other methods, and O2."""
    readings = {name: by_particles(root, f"{FOLDER}/reading-{name}") for name, _ in READINGS
                if os.path.exists(data.path(root, FOLDER, f"reading-{name}", "targets.csv"))}
    reading_tables(report, readings)
    counts = by_particles(root, PARTICLE_COUNTS_RUN) if os.path.exists(
        data.path(root, PARTICLE_COUNTS_RUN, "targets.csv")) else {}
    particle_count_table(report, counts, fig4)
    claim_default_reading_repeats_fig4(report, readings, fig4)
