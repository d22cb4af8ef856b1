"""TBD's digests: the small committed files that the checks read in place of the runs' per-step
files (steps.csv, beliefs.csv), which are not committed. digest(root) (python3 -m reports.digest tbd)
writes runs.csv (per run), steps-mean.csv (per step), steps-paired*.csv (per-step paired differences
between trackers on the same runs) and the toys' beliefs-summary.csv (toy.py)."""

import csv
import math
import os
import sys

import numpy as np

from reports.core import data
from experiments.tbd import toy as tbd_toy
from experiments.tbd.runs import (BP1, BP2, CALIBRATION, D1_WIDE, D2, D3, GOSPA, IEMB, JOINT, MATCHED_RUNS, MB,
                                      MB_READINGS, MERGE, PARTICLES, RUNTIME, SENSITIVITY, TOY)
from experiments.tbd.toy import fmt

RUN_COLUMNS = ["gospa", "gospa_p2", "localisation", "missed", "false", "n_objects", "n_estimates"]
# Which digests each run folder gets: per-step means (steps-mean.csv) and per-step paired
# differences (steps-paired.csv) between its trackers and/or against a partner run's trackers on
# the same trials (merge against gospa's first MERGE_TRIALS runs); and the toys' beliefs
# (beliefs-summary.csv; with the KDE mode where asked).
DIGESTS = [
    (GOSPA, {"steps": True, "pairs": "within", "first": MATCHED_RUNS}),
    (JOINT, {"steps": True, "pairs": "within", "partner": (GOSPA, [MB, IEMB, BP1, BP2]), "first": MATCHED_RUNS}),
    (D2, {"pairs": "within"}),
    (D3, {"pairs": "within"}),
    (D1_WIDE, {"pairs": "within"}),
    (SENSITIVITY, {"pairs": "within"}),
    (PARTICLES, {}),
    (MERGE, {"partner": (GOSPA, [IEMB])}),
    (MB_READINGS, {"partner": (GOSPA, [MB, IEMB, BP1])}),
    (RUNTIME, {}),
]
BELIEF_DIGESTS = [(TOY, True), (CALIBRATION, False)]



def read_steps(root, folder):
    """steps.csv of a run as {(point, algorithm): {metric: array [trials x K]}, 'trials': [...]},
    NaN where a step is missing, keys in file order."""
    full = data.path(root, folder, "steps.csv")
    rows = {}
    try:
        with open(full, newline="", encoding="utf-8") as f:
            reader = csv.reader(f)
            header = next(reader)
            col = {c: i for i, c in enumerate(header)}
            metrics = RUN_COLUMNS + ["time_us"]
            for r in reader:
                key = (r[col["point"]], r[col["algorithm"]])
                values = [float(r[col[m]]) if r[col[m]] != "" else math.nan for m in metrics]
                rows.setdefault(key, []).append((int(r[col["trial"]]), int(r[col["k"]]), values))
    except OSError as error:
        raise data.DataError(f"{folder}/steps.csv: {error.strerror}") from None
    except (KeyError, StopIteration, ValueError):
        raise data.DataError(f"{folder}/steps.csv: not the track-before-detect steps format") from None
    tables = {}
    for key, entries in rows.items():
        trials = sorted({t for t, _, _ in entries})
        where = {t: i for i, t in enumerate(trials)}
        steps = max(k for _, k, _ in entries)
        cube = np.full((len(metrics), len(trials), steps), np.nan)
        for t, k, values in entries:
            cube[:, where[t], k - 1] = values
        table = {m: cube[i] for i, m in enumerate(metrics)}
        table["excess"] = table["n_estimates"] - table["n_objects"]
        table["trials"] = trials
        tables[key] = table
    return tables


def mean_se_rows(matrix):
    """Per column of a [runs x K] matrix: (mean, se, n) over the finite entries."""
    n = np.sum(np.isfinite(matrix), axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nanmean(matrix, axis=0)
        se = np.nanstd(matrix, axis=0, ddof=1) / np.sqrt(n)
    return mean, se, n


def runs_rows(tables):
    """runs.csv: one row per (point, trial, algorithm) with the run's mean over k of each metric,
    the extra estimates per step (reported minus true), and the run's largest GOSPA and extra."""
    out = []
    for (point, algorithm), t in tables.items():
        with np.errstate(invalid="ignore"):
            means = {m: np.nanmean(t[m], axis=1) for m in RUN_COLUMNS + ["excess", "time_us"]}
            peaks = {m: np.nanmax(t[m], axis=1) for m in ("gospa", "excess")}
        steps = np.sum(np.isfinite(t["gospa"]), axis=1)
        for i, trial in enumerate(t["trials"]):
            out.append([point, trial, algorithm, int(steps[i])]
                       + [fmt(means[m][i]) for m in RUN_COLUMNS + ["excess"]]
                       + [fmt(peaks["gospa"][i]), fmt(peaks["excess"][i]), fmt(means["time_us"][i])])
    return out


RUNS_HEADER = (["point", "trial", "algorithm", "n_steps"] + RUN_COLUMNS
               + ["excess", "gospa_max", "excess_max", "step_time_us"])
STEP_METRICS = ["gospa", "missed", "false", "excess"]
STEPS_HEADER = (["point", "algorithm", "k", "runs"] + [f"{m}_{s}" for m in STEP_METRICS for s in ("mean", "se")]
                + ["runs_excess_ge2"])
PAIRS_HEADER = ["point", "a", "b", "k", "runs", "gospa_diff_mean", "gospa_diff_se"]


def steps_rows(tables):
    """steps-mean.csv: per (point, algorithm, k) the mean and SE over runs of GOSPA, missed, false
    and extra estimates, and how many runs reported at least two objects too many."""
    out = []
    for (point, algorithm), t in tables.items():
        stats_k = {m: mean_se_rows(t[m]) for m in STEP_METRICS}
        ge2 = np.sum(t["excess"] >= 2, axis=0)
        for k in range(t["gospa"].shape[1]):
            row = [point, algorithm, k + 1, int(stats_k["gospa"][2][k])]
            for m in STEP_METRICS:
                row += [fmt(stats_k[m][0][k]), fmt(stats_k[m][1][k])]
            out.append(row + [int(ge2[k])])
    return out


def paired_rows(point, a, table_a, b, table_b):
    """steps-paired.csv rows of one pair: per k the mean and SE over the runs both hold of
    GOSPA(a) - GOSPA(b)."""
    common = sorted(set(table_a["trials"]) & set(table_b["trials"]))
    ia = [table_a["trials"].index(t) for t in common]
    ib = [table_b["trials"].index(t) for t in common]
    mean, se, n = mean_se_rows(table_a["gospa"][ia] - table_b["gospa"][ib])
    return [[point, a, b, k + 1, int(n[k]), fmt(mean[k]), fmt(se[k])] for k in range(len(mean))]


def algorithms_of(root, folder):
    return data.read_meta(root, folder).get("algorithms", [])


def pairs_within(root, folder, tables):
    order = algorithms_of(root, folder)
    out = []
    for point in sorted({p for p, _ in tables}, key=int):
        present = [a for a in order if (point, a) in tables]
        for i, a in enumerate(present):
            for b in present[i + 1:]:
                out += paired_rows(point, a, tables[(point, a)], b, tables[(point, b)])
    return out


def first_trials(tables, first):
    """The tables restricted to trials below `first` (all when None)."""
    if first is None:
        return tables
    out = {}
    for key, t in tables.items():
        keep = [i for i, trial in enumerate(t["trials"]) if trial < first]
        out[key] = {m: (v[keep] if m != "trials" else [v[i] for i in keep]) for m, v in t.items()}
    return out


def pairs_with_partner(tables, partner_tables, partners):
    out = []
    for (point, a), table_a in tables.items():
        for b in partners:
            if (point, b) in partner_tables:
                out += paired_rows(point, a, table_a, b, partner_tables[(point, b)])
    return out


def digest(root):
    """Write the digests of every run folder (see DIGESTS) and of the toys' beliefs; return the
    paths written."""
    written, parsed = [], {}

    def tables_of(folder):
        if folder not in parsed:
            parsed[folder] = read_steps(root, folder)
        return parsed[folder]

    for folder, what in DIGESTS:
        base = data.path(root, folder)
        if not os.path.exists(os.path.join(base, "steps.csv")) and os.path.exists(os.path.join(base, "runs.csv")):
            print(f"{folder}: no steps.csv (not committed; rerun it to regenerate): its committed digests are kept",
                  file=sys.stderr)
            continue
        tables = tables_of(folder)
        written.append(data.write_csv(os.path.join(base, "runs.csv"), RUNS_HEADER, runs_rows(tables)))
        if what.get("steps"):
            written.append(data.write_csv(os.path.join(base, "steps-mean.csv"), STEPS_HEADER, steps_rows(tables)))
        for name, first in (("steps-paired.csv", None), (f"steps-paired-{MATCHED_RUNS}.csv", what.get("first"))):
            if name != "steps-paired.csv" and first is None:
                continue
            own = first_trials(tables, first)
            rows = pairs_within(root, folder, own) if what.get("pairs") == "within" else []
            if what.get("partner"):
                partner, trackers = what["partner"]
                rows += pairs_with_partner(own, first_trials(tables_of(partner), first), trackers)
            if rows:
                written.append(data.write_csv(os.path.join(base, name), PAIRS_HEADER, rows))
    for folder, modes in BELIEF_DIGESTS:
        written.append(data.write_csv(data.path(root, folder, "beliefs-summary.csv"), tbd_toy.BELIEFS_HEADER,
                                 tbd_toy.belief_rows(root, folder, modes)))
    return written
