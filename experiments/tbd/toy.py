"""The toy of the supplement's Fig. 1 (Sec. 1.3) on the supplement's own frame: where PO 1's
belief lies under each measurement reading and tracker, against the peaks of panels (d), (e), (f),
from the committed digest beliefs-summary.csv of results/tbd/toy-fig1a (one sweep point per
reading). Also the digest itself: per (point, algorithm, label) the belief's weighted mean, s.d.,
Monte Carlo SE, effective sample size and, where asked, its mode (the maximum of a Gaussian kernel
density estimate)."""

import csv
import math

import numpy as np

from plots.particle_density import kde_mode
from reports.core import data, markdown, verdicts
from reports.core.study import Claim

# The toy's trackers (tbd/toy-fig1a.ini) and the label of PO 1 in beliefs.csv.
MB = "tbd-mb:particles=2000"
MB_NONE = "tbd-mb:association=none,particles=2000"
FREE = "tbd-bp:iterations=1,interaction=false,particles=2000"
APPROX = "tbd-bp:iterations=1,particles=2000"
EXACT = "tbd-bp:iterations=1,exact_kappa=true,particles=2000"
NAMES = {MB: "TBD-MB (our reconstruction)", MB_NONE: "TBD-MB without exclusivity",
         FREE: "TBD-BP without interaction (the notes' stand-in for TBD-MB)",
         APPROX: "TBD-BP with κ̃ (eqs 5, 9)", EXACT: "TBD-BP with the exact message κ (letter's eq (5))"}
PANEL = {MB: "d", MB_NONE: "d", FREE: "d", APPROX: "e", EXACT: "f"}
PO1 = "0"
READINGS = {"d1": "D1", "d2": "D2", "d3": "D3"}
SUFFIX = {"d1": "", "d2": "-d2", "d3": "-d3"}  # the default reading's claims carry no suffix

# Supplement Fig. 1 (d), (e), (f): where the belief of PO 1 peaks, read off the panels (x, y) in m.
FIG1_PEAKS = {"d": ("4.47", "4.31"), "e": ("4.14", "4.13"), "f": ("4.25", "4.12")}
FIG1_READING_SE = 0.15  # m: reading a peak off a panel with 0.5 m ticks

BELIEFS_HEADER = ["point", "algorithm", "label", "particles", "existence", "ess", "mean_x", "mean_y", "sd_x", "sd_y",
                  "se_x", "se_y", "mode_x", "mode_y"]


def fmt(value):
    return "" if value is None or not math.isfinite(value) else f"{value:.7g}"


def belief_rows(root, folder, modes):
    """beliefs-summary.csv of a toy run: per (point, algorithm, label) the number of particles,
    the mean existence, the weighted mean and s.d. of x and y, and, with the weights of identical
    particles pooled (a resampled belief repeats particles), the effective sample size
    1/sum(w^2), the Monte Carlo SE of the weighted mean, sqrt(sum w^2 (x - m)^2), and (modes) the
    KDE mode."""
    groups = {}
    try:
        with open(data.path(root, folder, "beliefs.csv"), newline="", encoding="utf-8") as f:
            for r in csv.DictReader(f):
                groups.setdefault((r["point"], r["algorithm"], r["label"]), []).append(
                    (float(r["existence"]), float(r["x"]), float(r["y"]), float(r["weight"])))
    except OSError as error:
        raise data.DataError(f"{folder}/beliefs.csv: {error.strerror}") from None
    out = []
    for (point, algorithm, label), samples in groups.items():
        a = np.asarray(samples)
        pooled = {}
        for _, x, y, weight in samples:
            pooled[(x, y)] = pooled.get((x, y), 0.0) + weight
        xy = np.array(list(pooled.keys()))
        w = np.array(list(pooled.values()))
        w /= np.sum(w)
        mean = w @ xy
        sd = np.sqrt(w @ (xy - mean) ** 2)
        se = np.sqrt((w * w) @ (xy - mean) ** 2)
        mode = kde_mode(xy, w, sd) if modes else (math.nan, math.nan)
        out.append([point, algorithm, label, len(a), fmt(float(np.mean(a[:, 0]))), fmt(float(1.0 / np.sum(w * w))),
                    fmt(mean[0]), fmt(mean[1]), fmt(sd[0]), fmt(sd[1]), fmt(se[0]), fmt(se[1]),
                    fmt(mode[0]), fmt(mode[1])])
    return out


def belief_point(row):
    """((mean_x, mean_y), (se_x, se_y), (sd_x, sd_y), ess, (mode_x, mode_y)) of a digest row."""
    f = lambda c: data.num(row, c)  # noqa: E731
    return ((f("mean_x"), f("mean_y")), (f("se_x"), f("se_y")), (f("sd_x"), f("sd_y")), f("ess"),
            (f("mode_x"), f("mode_y")))


def peak_claim(beliefs, claim_id, spec, where):
    """Supplement Fig. 1 (panel of spec): PO 1's belief peaks at the read-off point. Per
    coordinate, compare_value of our belief mean (Monte Carlo SE over the particles) with the
    reading (its error FIG1_READING_SE as the paper's SE); the worse coordinate."""
    panel = PANEL[spec]
    paper = FIG1_PEAKS[panel]
    statement = f"{where}Fig. 1({panel}): the belief of PO 1 by {NAMES[spec]} peaks at ({paper[0]}, {paper[1]})"
    rule = (f"per coordinate, our belief mean (± Monte Carlo SE over the particles) against the "
            f"read-off peak with a reading SE of {FIG1_READING_SE} m (compare_value); the worse coordinate")
    if beliefs is None or spec not in beliefs:
        return Claim(claim_id, statement, "supplement Fig. 1", f"({paper[0]}, {paper[1]})", "not run",
                     verdicts.NOT_RUN, rule)
    mean, se, _, _, mode = belief_point(beliefs[spec])
    parts = [verdicts.compare_value(mean[i], se[i], float(paper[i]), FIG1_READING_SE, paper[i]) for i in range(2)]
    ours = (f"mean ({markdown.fixed(mean[0], 2)}, {markdown.fixed(mean[1], 2)}), off by "
            f"({markdown.signed(parts[0][1], 2)}, {markdown.signed(parts[1][1], 2)}) m against a bound of "
            f"{markdown.fixed(parts[0][2], 2)} m; mode ({markdown.fixed(mode[0], 2)}, {markdown.fixed(mode[1], 2)})")
    return Claim(claim_id, statement, "supplement Fig. 1", f"({paper[0]}, {paper[1]})", ours,
                 verdicts.worst([p[0] for p in parts]), rule)


def gaussian_distance(row_a, row_b):
    """(W2, se) between the Gaussians with the two beliefs' means and (diagonal) s.d.s:
    W2^2 = |m_a - m_b|^2 + sum (s_a - s_b)^2; its SE from the Monte Carlo SEs of the means and
    of the s.d.s (s.d. / sqrt(2 ESS)), each counted in full (an upper bound)."""
    ma, sa, da, ea, _ = belief_point(row_a)
    mb, sb, db, eb, _ = belief_point(row_b)
    w2 = math.sqrt(sum((ma[i] - mb[i]) ** 2 + (da[i] - db[i]) ** 2 for i in range(2)))
    se = math.sqrt(sum(sa[i] ** 2 + sb[i] ** 2 + da[i] ** 2 / (2 * ea) + db[i] ** 2 / (2 * eb) for i in range(2)))
    return w2, se


def similarity_claim(beliefs, claim_id, where):
    """Supplement Sec. 1.3: "the beliefs provided by (ii) [κ̃] and (iii) [exact κ] are very
    similar, whereas the one provided by TBD-MB is quite different": the distance of TBD-MB's
    belief (each TBD-MB reading, and the non-interacting stand-in) from the exact-κ belief exceeds
    that of the κ̃ belief, beyond error (compare_direction on the difference)."""
    statement = where + "the beliefs with κ̃ and with the exact κ are very similar, TBD-MB's is quite different"
    rule = ("W2 distance (Gaussian, diagonal) of TBD-MB's belief from the exact-κ belief minus that of the "
            "κ̃ belief > 0 beyond 2 SE (compare_direction), for each TBD-MB reading and the non-interacting "
            "stand-in; the worst")
    if beliefs is None or any(s not in beliefs for s in (FREE, APPROX, EXACT)):
        return Claim(claim_id, statement, "supplement Sec. 1.3", "–", "not run", verdicts.NOT_RUN, rule)
    approx, approx_se = gaussian_distance(beliefs[APPROX], beliefs[EXACT])
    parts, words = [], [f"κ̃ {markdown.fixed(approx, 2)} m"]
    for spec, name in ((MB, "TBD-MB"), (MB_NONE, "TBD-MB without exclusivity"), (FREE, "no interaction")):
        if spec not in beliefs:
            continue
        far, far_se = gaussian_distance(beliefs[spec], beliefs[EXACT])
        parts.append(verdicts.compare_direction(far - approx, math.hypot(far_se, approx_se), +1))
        words.append(f"{name} {markdown.fixed(far, 2)} m")
    return Claim(claim_id, statement, "supplement Sec. 1.3", "–",
                 "distance from the exact-κ belief: " + ", ".join(words), verdicts.worst(parts), rule)


def toward_object2(beliefs, spec):
    """How far (m) a belief's mean lies from the exact-κ belief's along the line from object 1
    (4, 4) to object 2 (5, 5): positive towards object 2."""
    if beliefs is None or spec not in beliefs or EXACT not in beliefs:
        return math.nan
    mean, exact = belief_point(beliefs[spec])[0], belief_point(beliefs[EXACT])[0]
    return ((mean[0] - exact[0]) + (mean[1] - exact[1])) / math.sqrt(2.0)


def beliefs_by_reading(d, folder):
    """{signal: {algorithm: digest row of PO 1}} (None without the digest)."""
    points = {r["point"]: r["signal"] for r in d.summary(folder)}
    rows = d.beliefs(folder)
    if rows is None:
        return None
    out = {}
    for r in rows:
        if r["label"] == PO1:
            out.setdefault(points[r["point"]], {})[r["algorithm"]] = r
    return out


def position_table(by_reading):
    """Per tracker: PO 1's belief mean (± MC SE) and mode under each reading, and the paper's peak."""
    rows = []
    for spec, name in NAMES.items():
        cells = []
        for signal in READINGS:
            row = (by_reading or {}).get(signal, {}).get(spec)
            if row is None:
                cells.append("not run")
                continue
            mean, se, _, _, mode = belief_point(row)
            cells.append(f"({markdown.pm(mean[0], se[0])}, {markdown.pm(mean[1], se[1])}); "
                         f"mode ({markdown.fixed(mode[0], 2)}, {markdown.fixed(mode[1], 2)})")
        peak = FIG1_PEAKS[PANEL[spec]]
        rows.append([name] + cells + [f"({peak[0]}, {peak[1]}) ({PANEL[spec]})"])
    return markdown.table(["tracker"] + [f"{label}: mean; mode (x, y) in m" for label in READINGS.values()]
                          + ["supplement's peak (panel)"], rows, "lrrrr")


def check_toy(report, d, folder):
    """Fig. 1 on the supplement's frame: the peak claims T1 (no interaction), T1-mb, T1-mbnone
    (TBD-MB readings), T2 (κ̃), T3 (exact κ) and the similarity T4, per reading (suffix -d2, -d3;
    none for D1, the default)."""
    by_reading = beliefs_by_reading(d, folder)
    report.value("toy.table", position_table(by_reading))
    ids = []
    for signal, label in READINGS.items():
        beliefs = (by_reading or {}).get(signal)
        suffix, where = SUFFIX[signal], f"[{label}] "
        claims = [peak_claim(beliefs, f"T1{suffix}", FREE, where),
                  peak_claim(beliefs, f"T1-mb{suffix}", MB, where),
                  peak_claim(beliefs, f"T1-mbnone{suffix}", MB_NONE, where),
                  peak_claim(beliefs, f"T2{suffix}", APPROX, where),
                  peak_claim(beliefs, f"T3{suffix}", EXACT, where),
                  similarity_claim(beliefs, f"T4{suffix}", where)]
        for c in claims:
            report.claim(c)
            ids.append(c.id)
        for spec, name in ((FREE, "free"), (MB, "mb"), (MB_NONE, "mbnone")):
            report.value(f"toy.{name}_pull{suffix}", markdown.signed(toward_object2(beliefs, spec), 2))
    report.value("toy.claims", report.claims_table(ids))
