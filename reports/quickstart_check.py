"""Compares a quick-start run with the committed reference run, one line per comparison.

    /usr/bin/python3 -m reports.quickstart_check RUN_DIR [REFERENCE_DIR]   (from the repository
        root; default reference: results/quickstart)
    /usr/bin/python3 -m reports.quickstart_check --digests REFERENCE_DIR   (writes
        REFERENCE_DIR/trials-digests.csv from its trials.csv: a step of the reference's rerun)

- Errors, bit for bit. The same seed gives the same trials on any machine and for any thread
  count, and trial t of a spacing is the same draw in a run of any length. A run of the
  reference's length must have every column of summary.csv but the timings equal to the
  reference's, as written (shortest round-trip text). A shorter run (DABENCH_QUICKSTART_TRIALS=N)
  holds the reference's first N trials per spacing: where the reference recorded a digest of
  those (trials-digests.csv: N = 100, 200, 1000), the SHA-256 of the run's trials.csv rows, timing
  columns left out and in (spacing, trial) order, must equal it. Other lengths are not compared.
- Time: each algorithm's mean time per trial (time_us over every spacing) as a ratio to the
  reference's: how this machine compares with the one that made the committed run.

Exit status 0 when the errors are the same (or not compared), 1 when they differ, 2 when the
folders cannot be compared.
"""

import csv
import hashlib
import json
import math
import os
import re
import sys

from reports.core import markdown

PROG = "quickstart_check"
DIGEST_TRIALS = (100, 200, 1000)  # the first N trials per spacing whose digests the reference records
DIGESTS = "trials-digests.csv"
TIMING = re.compile(r"^time_us(_(count|mean|se|median|p5|p95))?$")  # timing columns and their statistics
KEYS = ("point", "algorithm")


class CannotCompare(Exception):
    pass


def read_csv(path):
    try:
        with open(path, newline="", encoding="utf-8") as f:
            table = list(csv.reader(f))
    except OSError as e:
        raise CannotCompare(f"{path}: {e.strerror}") from e
    if not table:
        raise CannotCompare(f"{path} is empty")
    header, body = table[0], table[1:]
    if any(len(row) != len(header) for row in body):
        raise CannotCompare(f"{path}: a row has not the header's {len(header)} fields")
    return header, body


def read_run(folder):
    """(meta, header, rows keyed by (point, algorithm)) of a run folder's summary."""
    try:
        with open(os.path.join(folder, "meta.json"), encoding="utf-8") as f:
            meta = json.load(f)
    except OSError as e:
        raise CannotCompare(f"{folder}/meta.json: {e.strerror}") from e
    except ValueError as e:
        raise CannotCompare(f"{folder}/meta.json: not JSON ({e})") from e
    header, body = read_csv(os.path.join(folder, "summary.csv"))
    if any(k not in header for k in KEYS):
        raise CannotCompare(f"{folder}/summary.csv is not a dabench summary")
    rows = {tuple(r[header.index(k)] for k in KEYS): dict(zip(header, r)) for r in body}
    return meta, header, rows


def num(row, column):
    try:
        return float(row[column])
    except (KeyError, ValueError):
        return math.nan


def peak_line(rows, trials):
    """BP's peak average maximum error with its SE and spacing."""
    bp = [r for (_, algorithm), r in rows.items() if algorithm == "bp"]
    if not bp:
        raise CannotCompare("no bp rows")
    peak = max(bp, key=lambda r: num(r, "max_error_mean"))
    mean, se = num(peak, "max_error_mean"), num(peak, "max_error_se")
    return f"{markdown.pm(mean, se)} at spacing {peak['spacing']} ({trials} trials per spacing)"


def summary_differences(header, run, reference):
    """The (point, algorithm, column, ours, theirs) of every non-timing field that differs."""
    differences = []
    for key in sorted(reference, key=lambda k: (int(k[0]), k[1])):
        for column in header:
            if not TIMING.match(column) and run[key][column] != reference[key][column]:
                differences.append((*key, column, run[key][column], reference[key][column]))
    return differences


def trials_digests(folder, counts):
    """{N: (rows, SHA-256)} of folder/trials.csv's rows with trial < N, timing columns left out,
    in (point, trial) order (a trial's rows as written)."""
    header, body = read_csv(os.path.join(folder, "trials.csv"))
    if "point" not in header or "trial" not in header:
        raise CannotCompare(f"{folder}/trials.csv is not a dabench trials file")
    point, trial = header.index("point"), header.index("trial")
    keep = [i for i, name in enumerate(header) if not TIMING.match(name)]
    body.sort(key=lambda r: (int(r[point]), int(r[trial])))
    out = {}
    for n in counts:
        digest, rows = hashlib.sha256(), 0
        digest.update((",".join(header[i] for i in keep) + "\n").encode())
        for r in body:
            if int(r[trial]) < n:
                digest.update((",".join(r[i] for i in keep) + "\n").encode())
                rows += 1
        out[n] = (rows, digest.hexdigest())
    return out


def write_digests(folder):
    digests = trials_digests(folder, DIGEST_TRIALS)
    with open(os.path.join(folder, DIGESTS), "w", newline="", encoding="utf-8") as f:
        f.write("trials,rows,sha256\n")
        for n, (rows, sha) in digests.items():
            f.write(f"{n},{rows},{sha}\n")


def recorded_digests(folder):
    """{N: (rows, SHA-256)} the reference recorded ({} when it has no trials-digests.csv)."""
    path = os.path.join(folder, DIGESTS)
    if not os.path.exists(path):
        return {}
    header, body = read_csv(path)
    if header != ["trials", "rows", "sha256"]:
        raise CannotCompare(f"{path}: not trials,rows,sha256")
    return {int(n): (int(rows), sha) for n, rows, sha in body}


def mean_time(rows, algorithm):
    pairs = [(num(r, "time_us_count"), num(r, "time_us_mean")) for (_, a), r in rows.items() if a == algorithm]
    count = sum(c for c, _ in pairs)
    return sum(c * m for c, m in pairs) / count if count > 0 else math.nan


def compare(run_dir, reference_dir):
    """The lines to print and whether the errors are the same (None: not compared)."""
    meta, header, run = read_run(run_dir)
    ref_meta, ref_header, reference = read_run(reference_dir)
    for field in ("seed", "points", "algorithms", "references"):
        if meta.get(field) != ref_meta.get(field):
            raise CannotCompare(f"{run_dir} is not the committed run's experiment ({field}: "
                                f"{meta.get(field)} vs {ref_meta.get(field)})")
    if meta.get("status") != "complete":
        raise CannotCompare(f"{run_dir}: the run is not complete (status {meta.get('status')})")
    if header != ref_header or run.keys() != reference.keys():
        raise CannotCompare(f"{run_dir}/summary.csv has other columns or rows than {reference_dir}'s")
    n, big_n = meta["trials_per_point"], ref_meta["trials_per_point"]
    ours = f"BP's peak error {peak_line(run, n)}"
    modified = " (this build is from modified sources)" if meta.get("source_modified") else ""
    recorded = recorded_digests(reference_dir)
    if n == big_n:
        differences = summary_differences(header, run, reference)
        same = not differences
        if same:
            line = (f"{ours}: the same as the committed run (every column of summary.csv but the timings "
                    f"equal bit for bit, {len(run)} rows)")
        else:
            point, algorithm, column, a, b = differences[0]
            count = f"{len(differences)} {'field differs' if len(differences) == 1 else 'fields differ'}"
            line = (f"{ours}: NOT the same as the committed run: {count}, first point {point}, "
                    f"{algorithm}, {column}: {a} vs {b}{modified}")
    elif n in recorded:
        rows, sha = trials_digests(run_dir, [n])[n]
        same = (rows, sha) == recorded[n]
        line = (f"{ours}: {'the same as' if same else 'NOT the same as'} the committed run's first {n} "
                f"trials per spacing (its trials.csv, timings aside: {rows} rows, SHA-256 {sha[:12]}…"
                + (")" if same else f"; the committed run's: {recorded[n][0]} rows, {recorded[n][1][:12]}…){modified}"))
    else:
        same = None
        counts = sorted(recorded) + [big_n]
        counts = ", ".join(str(c) for c in counts[:-1]) + f" or {counts[-1]}"
        line = (f"{ours}; not compared with the committed run's {peak_line(reference, big_n)}: a run of "
                f"{counts} trials per spacing (DABENCH_QUICKSTART_TRIALS) is compared bit for bit")
    algorithms = sorted({a for _, a in reference}, key=lambda a: (a != "bp", a))
    ratios = ", ".join(f"{a} {mean_time(run, a) / mean_time(reference, a):.2f}×" for a in algorithms)
    time_line = (f"this machine: {ratios} the committed run's mean time per trial "
                 f"(its {ref_meta.get('threads')} threads, {meta.get('threads')} here)")
    return [line, time_line], same


def main(argv):
    try:
        if len(argv) == 2 and argv[0] == "--digests":
            write_digests(argv[1])
            return 0
        if len(argv) not in (1, 2) or argv[0].startswith("-"):
            print(f"usage: {PROG} RUN_DIR [REFERENCE_DIR] | --digests REFERENCE_DIR", file=sys.stderr)
            return 2
        lines, same = compare(argv[0], argv[1] if len(argv) == 2 else "results/quickstart")
    except CannotCompare as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return 2
    for line in lines:
        print(f"quickstart: {line}")
    return 1 if same is False else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
