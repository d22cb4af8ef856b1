#!/usr/bin/env python3
"""Checks that two run folders hold the same results, timings aside.

    same_results.py [--shared] BEFORE AFTER

Compares every CSV file of BEFORE with AFTER's (--shared: only the files both hold, e.g. a
committed run folder, which keeps digests of files it does not commit, against a fresh rerun) (trials.csv, targets.csv, tracks.csv,
iterations.csv, summary.csv, ...) row by row and field by field as text, so numbers must be
bit-identical in their written (shortest round-trip) form. Columns that hold timings are left
out: their name is `time_us`, `step_time_us`, `tet_s`, ends in `_seconds`, or is a summary statistic of one of
these (`time_us_mean`, ...). Prints one line per difference (at most 20 per file) and exits 1
if there is any, 0 otherwise. Used before and after refactors that must not change numbers.
checksums.csv is left out: it checksums whole rows, timings included, block by block.
"""
import csv
import os
import re
import sys

TIMING = re.compile(r"^(time_us|step_time_us|tet_s|[a-z_]*_seconds)(_(count|mean|se|median|p5|p95))?$")


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    if not rows:
        return [], []
    header, body = rows[0], rows[1:]
    keep = [i for i, name in enumerate(header) if not TIMING.match(name)]
    return [header[i] for i in keep], [[row[i] if i < len(row) else "<missing>" for i in keep] for row in body]


def compare(before, after, name):
    header_a, rows_a = read(before)
    header_b, rows_b = read(after)
    differences = []
    if header_a != header_b:
        differences.append(f"{name}: columns differ: {header_a} vs {header_b}")
        return differences
    if len(rows_a) != len(rows_b):
        differences.append(f"{name}: {len(rows_a)} rows vs {len(rows_b)}")
    for line, (a, b) in enumerate(zip(rows_a, rows_b), start=2):
        for column, x, y in zip(header_a, a, b):
            if x != y:
                differences.append(f"{name}:{line}: {column}: {x} vs {y}")
    return differences


def main():
    args = sys.argv[1:]
    shared = "--shared" in args
    args = [a for a in args if a != "--shared"]
    if len(args) != 2:
        sys.exit("usage: same_results.py [--shared] BEFORE AFTER")
    before, after = args
    files = []
    for root, _, names in os.walk(before):
        for n in names:
            if n.endswith(".csv") and n != "checksums.csv":
                files.append(os.path.relpath(os.path.join(root, n), before))
    if not files:
        sys.exit(f"same_results.py: no CSV files under {before}")
    failed = False
    if shared:
        files = [rel for rel in files if os.path.exists(os.path.join(after, rel))]
        if not files:
            sys.exit(f"same_results.py: {before} and {after} share no CSV file")
    for rel in sorted(files):
        other = os.path.join(after, rel)
        if not os.path.exists(other):
            print(f"{rel}: missing in {after}")
            failed = True
            continue
        differences = compare(os.path.join(before, rel), other, rel)
        for d in differences[:20]:
            print(d)
        if differences:
            failed = True
    print(f"{len(files)} files compared ({', '.join(sorted(files))}): "
          f"{'DIFFERENT' if failed else 'identical (timings aside)'}")
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
