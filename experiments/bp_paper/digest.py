"""bp-paper's trials digests: trials-digest.csv, per (point, algorithm) of a run's trials.csv (which
is not committed) its rows, statuses and BP's largest iteration count. digest() writes them
(python3 -m reports.digest bp-paper); DigestScan reads one back for the Sec. V-B rules, with the interface
of plots/bp_paper_panels.py's TrialsScan."""

import csv
import math
import os
from collections import Counter

from reports.core import data
from experiments.bp_paper.runs import DIGEST, DIGESTED

from plots import fig6_paper as fp  # the data model of the Sec. V-B rules: the nine panels of Fig. 6


def digest_counts(path):
    """{(point, algorithm): [rows, Counter(status), max iterations over ok rows, its first trial]}
    of one trials.csv, streamed; keys in order of first appearance (the file's order)."""
    out = {}
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.reader(f)
        header = next(reader, None)
        if not header:
            raise data.DataError(f"{path}: empty")
        try:
            ip, ia, it, ist, iit = (header.index(c) for c in ("point", "algorithm", "trial", "status", "iterations"))
        except ValueError as error:
            raise data.DataError(f"{path}: {error}") from None
        for row in reader:
            if len(row) != len(header):
                continue  # a cut last line of an interrupted run
            cell = out.setdefault((row[ip], row[ia]), [0, Counter(), None, ""])
            cell[0] += 1
            cell[1][row[ist]] += 1
            if row[ist] == "ok" and row[iit] and (cell[2] is None or float(row[iit]) > float(cell[2])):
                cell[2], cell[3] = row[iit], row[it]
    return out


def write_digest(source, target):
    """trials-digest.csv: point, algorithm, rows, statuses ("ok=998;skipped:memory=2"),
    iterations_max (over ok rows) and iterations_max_trial (the first trial reaching it)."""
    tmp = target + ".tmp"
    with open(tmp, "w", newline="", encoding="utf-8") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["point", "algorithm", "rows", "statuses", "iterations_max", "iterations_max_trial"])
        for (point, algorithm), (rows, status, top, trial) in digest_counts(source).items():
            w.writerow([point, algorithm, rows, ";".join(f"{s}={status[s]}" for s in sorted(status)),
                        top or "", trial])
    os.replace(tmp, target)


def digest(root):
    """Write trials-digest.csv next to the trials.csv of each run in DIGESTED (a run without one
    keeps its digest)."""
    written = []
    for folder in DIGESTED:
        source = data.path(root, folder, "trials.csv")
        if os.path.exists(source):
            write_digest(source, data.path(root, folder, DIGEST))
            written.append(data.path(root, folder, DIGEST))
    if not written:
        raise data.DataError(f"no trials.csv in {', '.join(DIGESTED)}")
    return written


class DigestScan:
    """A run's trials digest with the interface of bp_paper_panels.TrialsScan: max_iter and
    max_where (BP's iteration maximum), reasons {spec: Counter(non-ok status)}, rows, path; and
    bp_rows, the number of BP runs."""

    def __init__(self, root, folder, bp_specs, summary_rows):
        self.path = f"{folder}/trials.csv (its digest {DIGEST})"
        self.rows, self.bp_rows, self.reasons, self.max_iter, self.max_where = 0, 0, {}, math.nan, ""
        for r in data.read_rows(root, f"{folder}/{DIGEST}"):
            self.rows += int(r["rows"])
            self.bp_rows += int(r["rows"]) if r["algorithm"] in bp_specs else 0
            for part in filter(None, r["statuses"].split(";")):
                status, count = part.rsplit("=", 1)
                if status != "ok":
                    self.reasons.setdefault(r["algorithm"], Counter())[status] += int(count)
            top = data.number(r["iterations_max"])
            if r["algorithm"] in bp_specs and top is not None and not top <= self.max_iter:
                self.max_iter = top
                self.max_where = point_text(summary_rows, r["point"]) + f", trial {r['iterations_max_trial']}"


def point_text(summary_rows, point):
    """'point 84, rows=2, cols=3, spacing=0, pd=0.9, lambda_fa=0.01, r=1' from a summary."""
    row = next((r for r in summary_rows if r.get("point") == point), {})
    params = [f"{c}={row[c]}" for c in ("rows", "cols", "spacing", "pd", "lambda_fa", "r") if c in row]
    return ", ".join([f"point {point}"] + params)


def digest_scans(root, paper_data, folders):
    """{experiment: DigestScan} for the experiments whose run folder has a digest."""
    bp_specs = {a for a in paper_data.algorithms() if fp.family_key(a) == "bp"}
    out = {}
    for exp, folder in folders.items():
        if os.path.exists(data.path(root, folder, DIGEST)):
            out[exp] = DigestScan(root, folder, bp_specs, paper_data.summaries[exp].rows)
    return out
