#!/usr/bin/env python3
"""Records the last `scripts/test.sh` run's step times and slowest test cases for the tables of
docs/tests.md (experiments/readme/__init__.py renders both tables from what this appends):
  tests/timings/steps.csv   run, commit, date, cores, build, step, wall_s, cpu_s (one row per step
                            of build-logs/steps.tsv, the last its `all total` row: the run's wall time)
  tests/timings/cases.csv   run, build, case, seconds (the ten slowest ctest entries of each build)
Usage: scripts/record_test_timings.py RUN_LABEL   (e.g. `cold`, after `bash scripts/test.sh` passed)
A label already recorded is replaced, so a measurement can be repeated."""

import csv
import datetime
import os
import re
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
STEPS = ROOT / "tests/timings/steps.csv"
CASES = ROOT / "tests/timings/cases.csv"
STEP_COLUMNS = ["run", "commit", "date", "cores", "build", "step", "wall_s", "cpu_s"]
CASE_COLUMNS = ["run", "build", "case", "seconds"]
CTEST_LOGS = {"release": "build-logs/release.log", "asan": "build-asan/ctest.log"}
PASSED = re.compile(r"Test +#\d+: (.*?) \.+ +Passed +([0-9.]+) sec")


def replace_rows(path, columns, label, rows):
    kept = []
    if path.is_file():
        with path.open(newline="") as f:
            kept = [r for r in csv.DictReader(f) if r["run"] != label]
    path.parent.mkdir(parents=True, exist_ok=True)
    temporary = path.with_suffix(".tmp")
    with temporary.open("w", newline="") as f:
        writer = csv.DictWriter(f, columns, lineterminator="\n")
        writer.writeheader()
        writer.writerows(kept + rows)
    temporary.replace(path)


def main(argv):
    if len(argv) != 2:
        sys.exit("usage: scripts/record_test_timings.py RUN_LABEL")
    label = argv[1]
    steps_tsv = ROOT / "build-logs/steps.tsv"
    if not steps_tsv.is_file():
        sys.exit(f"{steps_tsv}: no steps recorded (run bash scripts/test.sh first)")
    commit = subprocess.run(["git", "rev-parse", "--short=7", "HEAD"], cwd=ROOT, capture_output=True, text=True,
                            check=True).stdout.strip()
    common = {"run": label, "commit": commit, "date": datetime.date.today().isoformat(), "cores": os.cpu_count()}
    step_rows = []
    for line in steps_tsv.read_text().splitlines():
        build, step, wall, cpu, status = line.split("\t")
        if status != "0":
            sys.exit(f"{steps_tsv}: the {build} {step} step failed; only a passing run is recorded")
        step_rows.append({**common, "build": build, "step": step, "wall_s": wall, "cpu_s": cpu})
    if not step_rows or step_rows[-1]["step"] != "total":
        sys.exit(f"{steps_tsv}: the run did not finish (no total row)")
    case_rows = []
    for build, log in CTEST_LOGS.items():
        path = ROOT / log
        if not any(r["build"] == build and r["step"] == "ctest" for r in step_rows) or not path.is_file():
            continue  # this run had no such step: the log is an earlier run's
        cases = sorted(((float(s), name) for name, s in PASSED.findall(path.read_text())), reverse=True)[:10]
        case_rows += [{"run": label, "build": build, "case": name, "seconds": f"{s:.2f}"} for s, name in cases]
    replace_rows(STEPS, STEP_COLUMNS, label, step_rows)
    replace_rows(CASES, CASE_COLUMNS, label, case_rows)
    print(f"record_test_timings: {label}: {len(step_rows)} steps, {len(case_rows)} cases "
          f"in {STEPS.relative_to(ROOT)}, {CASES.relative_to(ROOT)}")


if __name__ == "__main__":
    main(sys.argv)
