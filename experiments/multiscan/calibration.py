"""How good is exact Bayes at the study's particle count: with one target JPDA-BP is exact Bayes,
so its HPD values are U(0, 1) up to the particle approximation (E1: calibrated at the most
particles, E2: not at the fewest; E3: the likelihood-ranked HPD too)."""

import math

import numpy as np

from reports.core import data, markdown, verdicts
from reports.core.study import Claim
from experiments.multiscan.runs import FOLDER
from experiments.multiscan.targets import CALIBRATED_P80, Figure, ks_uniform, particles_text, read_targets, scans

KS_COEFFICIENT = 1.358  # 5 % critical value of the KS distance from U(0, 1) is 1.358 / sqrt(n)


def calibration_section(report, root):
    """The particle-count check: with one target JPDA-BP is exact Bayes, so its HPD values are
    U(0, 1) up to the particle approximation; KS distance against its 5 % critical value (one
    target per trial: independent values) and p80 against 0.80 with its bootstrap SE."""
    points = read_targets(root, f"{FOLDER}/particles")
    rows, by_particles, likelihood = [], {}, {}
    for point in sorted(points, key=lambda p: (scans(points[p].params), data.num(points[p].params, "particles"))):
        t = points[point]
        figure = Figure(t, f"particles point {point}")
        hpd = t.hpd[:, 0]
        d, critical = ks_uniform(hpd), KS_COEFFICIENT / math.sqrt(len(hpd))
        particles = int(data.num(t.params, "particles"))
        p80, se = figure.value("p80", t.methods[0]), figure.se("p80", t.methods[0])
        atom = float(np.mean(hpd == 0.0))
        by_particles.setdefault(particles, []).append((scans(t.params), d, critical, p80, se))
        row = [particles_text(particles), scans(t.params), len(hpd), markdown.fixed(d, 3),
               markdown.fixed(critical, 3), markdown.pm(p80, se), markdown.percent(atom)]
        if t.has_likelihood():
            d_l = figure.ks(t.methods[0], "likelihood")
            likelihood.setdefault(particles, []).append((scans(t.params), d_l, critical))
            row += [markdown.fixed(d_l, 3), figure.pm("p80_likelihood", t.methods[0])]
        rows.append(row)
    header = ["particles", "scans", "targets", "KS distance", "5 % critical value", "p80", "HPD = 0"]
    if likelihood:
        header += ["KS distance, likelihood ranking", "p80, likelihood ranking"]
    report.value("calibration.table", markdown.table(header, rows, "r" * len(header)))
    most, fewest = max(by_particles), min(by_particles)
    claim_likelihood_calibrated(report, likelihood.get(most, []), particles_text(most))
    report.value("calibration.most", particles_text(most))
    report.value("calibration.fewest", particles_text(fewest))
    # The smallest count from which up every count passes the KS check at every scan count.
    passing = [n for n in sorted(by_particles) if all(d <= c for _, d, c, _, _ in by_particles[n])]
    from_up = next((n for n in passing if all(m in passing for m in by_particles if m >= n)), None)
    report.value("calibration.passing_from", particles_text(from_up) if from_up else "no count")

    parts, ours = [], []
    for n_scans, d, critical, p80, se in by_particles[most]:
        ks_ok = verdicts.WITHIN_ERROR if d <= critical else verdicts.DIFFERS
        p80_ok = verdicts.compare_direction(p80 - CALIBRATED_P80, se, +1)
        parts += [ks_ok, verdicts.WITHIN_ERROR if p80_ok == verdicts.WITHIN_ERROR else verdicts.DIFFERS]
        ours.append(f"{n_scans} scans: KS {d:.3f} (critical {critical:.3f}), p80 {markdown.pm(p80, se)}")
    report.claim(Claim(
        "E1", f"At {report.values['calibration.most']} particles exact Bayes (JPDA-BP, one target) is calibrated",
        "ours", "–", "; ".join(ours), verdicts.worst(parts),
        "each scan count: KS distance at most its 5 % critical value and p80 within two SE of 0.80 "
        "(agrees within error; calibration cannot be confirmed beyond error), else differs"))
    parts, ours = [], []
    for n_scans, d, critical, p80, se in by_particles[fewest]:
        parts.append(verdicts.AGREES if d > critical else verdicts.WITHIN_ERROR)
        ours.append(f"{n_scans} scans: KS {d:.3f} (critical {critical:.3f})")
    report.claim(Claim(
        "E2", f"At {report.values['calibration.fewest']} particles exact Bayes is not calibrated", "ours",
        "–", "; ".join(ours), verdicts.worst(parts),
        "each scan count: KS distance above its 5 % critical value (uniformity rejected) agrees, else within error"))


def claim_likelihood_calibrated(report, rows, particles):
    """E3: the likelihood-ranked HPD of exact Bayes is calibrated at the study's particle count
    (its KS distance at most the 5 % critical value at each scan count); the column is shown
    beside eq (92)'s only while this holds (report value calibration.likelihood_ok)."""
    parts = [verdicts.WITHIN_ERROR if d <= critical else verdicts.DIFFERS for _, d, critical in rows]
    verdict = verdicts.worst(parts) if parts else verdicts.NOT_RUN
    report.value("calibration.likelihood_ok", "yes" if verdict == verdicts.WITHIN_ERROR else "no")
    report.claim(Claim(
        "E3", f"At {particles} particles the HPD value with particles ranked by likelihood (`hpd_likelihood`) is "
        "calibrated for exact Bayes too", "ours", "–",
        "; ".join(f"{n} scans: KS {d:.3f} (critical {c:.3f})" for n, d, c in rows) or "not recorded", verdict,
        "each scan count: KS distance at most its 5 % critical value (agrees within error), else differs"))
