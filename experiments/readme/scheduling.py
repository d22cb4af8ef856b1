"""The work queue's numbers in docs/clusters.md (issue 31): fig3 at 8 trials measured on 1 and 2
threads against the simulator's predictions, the predictions for 16 workers of fig3 and tbd-gospa
at 32 trials, and a table of every committed study at 16, 64 and 256 workers.

The predictions are `dabench schedule` on the committed runs. They are a digest
(SCHEDULE_DIGEST, written by `python3 -m reports.digest readme`), so that rendering needs no
build; `python3 -m experiments.readme.schedule_check` (ctest `readme_schedule_current`, after
the build) recomputes them with the build's program and fails when the digest differs."""

import csv
import io
import subprocess
from pathlib import Path

from experiments.readme.runs import CLUSTER, QUICKSTART, SCHEDULE_DIGEST, SCHEDULE_RUNS
from reports.core import data, markdown

# The committed studies whose wall time docs/clusters.md predicts for 16, 64 and 256 workers.
SCHEDULE_STUDIES = [
    ("quick start", QUICKSTART), ("BP paper, experiment 1", "results/bp-paper/exp1"),
    ("BP paper, experiment 2", "results/bp-paper/exp2"), ("BP paper, experiment 3", "results/bp-paper/exp3"),
    ("multi-scan Fig. 3", "results/multiscan/fig3"), ("multi-scan Fig. 4", "results/multiscan/fig4"),
    ("multi-scan Fig. 5", "results/multiscan/fig5"), ("JDT-VB Table IV", "results/jdtvb/table4"),
    ("TBD-BP GOSPA (Fig. 2)", "results/tbd/gospa"),
]
SCHEDULE_WORKERS = (16, 64, 256)
# Every `dabench schedule` the checks read: (folder, worker counts, --trials or None).
QUERIES = ([(f"{CLUSTER}/schedule-fig3-8-threads1", (1, 2), None),
            ("results/multiscan/fig3", (16,), 32), ("results/tbd/gospa", (16,), 32)]
           + [(folder, SCHEDULE_WORKERS, None) for _, folder in SCHEDULE_STUDIES])
SCHEDULE_COLUMNS = ["workers", "units", "total_s", "longest_unit_s", "bound_s", "wall_s", "work_fraction",
                    "blocks_wall_s", "blocks_work_fraction", "known_wall_s", "known_work_fraction"]
DIGEST_HEADER = ["folder", "trials", "unit_times"] + SCHEDULE_COLUMNS
REPO = Path(__file__).resolve().parents[2]


def unit_times(root, folder):
    """What `dabench schedule` reads a unit's time from: "trials" (trials.csv, or TBD's runs.csv
    digest), else "means" (summary.csv's per-point means: every unit of a point the same)."""
    return "trials" if any((Path(root) / folder / name).is_file() for name in ("trials.csv", "runs.csv")) else "means"


def schedule_rows(root, program):
    """The digest's rows: `program schedule FOLDER --format csv` for every query, on the data under root."""
    rows = []
    for folder, workers, trials in QUERIES:
        command = [str(program), "schedule", folder, "--format", "csv", "--workers", ",".join(map(str, workers))]
        if trials:
            command += ["--trials", str(trials)]
        try:
            done = subprocess.run(command, cwd=root, capture_output=True, text=True, check=False)
        except OSError as error:
            raise data.DataError(f"{program}: {error.strerror} (bash scripts/build.sh dabench)") from None
        if done.returncode != 0:
            raise data.DataError(f"{' '.join(command[1:])}: {done.stderr.strip()}")
        for r in csv.DictReader(io.StringIO(done.stdout)):
            rows.append([folder, str(trials or ""), unit_times(root, folder)] + [r[c] for c in SCHEDULE_COLUMNS])
    return rows


def build_program(root):
    """The dabench of the data's tree, else of this checkout."""
    candidates = [Path(root) / "build" / "dabench", REPO / "build" / "dabench"]
    program = next((c for c in candidates if c.is_file()), None)
    if program is None:
        raise data.DataError(f"{candidates[-1]}: not built (bash scripts/build.sh dabench)")
    return program


def digest(root):
    """Write SCHEDULE_DIGEST from the build's `dabench schedule`; returns [the file]."""
    rows = schedule_rows(root, build_program(root))
    return [data.write_csv(data.path(root, SCHEDULE_DIGEST), DIGEST_HEADER, rows)]


def predictions(root, folder, trials=None):
    """The committed predictions of one query: {workers: {column: number}}, and its unit_times."""
    found = {}
    kind = None
    for r in data.read_rows(root, SCHEDULE_DIGEST):
        if r["folder"] == folder and r["trials"] == str(trials or ""):
            found[int(r["workers"])] = {c: float(r[c]) for c in SCHEDULE_COLUMNS}
            kind = r["unit_times"]
    if not found:
        raise data.DataError(f"{SCHEDULE_DIGEST}: no prediction for {folder}"
                             + (f" at {trials} trials" if trials else "") + " (python3 -m reports.digest readme)")
    return found, kind


def span(seconds):
    """A duration from microseconds to hours: "85 µs", "3.1 ms", "42 s", "12.7 min", "1.6 h"."""
    if seconds < 1e-3:
        return f"{markdown.sig(seconds * 1e6, 2)} µs"
    if seconds < 1:
        return f"{markdown.sig(seconds * 1e3, 2)} ms"
    return markdown.duration(seconds)


def check(report):
    """The values of docs/clusters.md's work-queue section, from the runs' meta.json and the digest."""
    metas = {name: data.read_meta(report.root, f"{CLUSTER}/schedule-fig3-8-{name}") for name in SCHEDULE_RUNS}
    predicted, _ = predictions(report.root, f"{CLUSTER}/schedule-fig3-8-threads1")
    for name, meta in metas.items():
        report.value(f"schedule.fig3.{name}.wall", f"{markdown.fixed(meta['wall_seconds'], 1)} s")
        report.value(f"schedule.fig3.{name}.fraction", markdown.fixed(meta["work_fraction"], 2))
    two = predicted[2]
    report.value("schedule.fig3.total", f"{markdown.fixed(two['total_s'], 1)} s")
    report.value("schedule.fig3.longest", f"{markdown.fixed(two['longest_unit_s'], 1)} s")
    report.value("schedule.fig3.best_fraction", markdown.fixed(two["total_s"] / (2 * two["bound_s"]), 2))
    report.value("schedule.fig3.predicted.threads1", f"{markdown.fixed(predicted[1]['wall_s'], 1)} s")
    report.value("schedule.fig3.predicted.threads2", f"{markdown.fixed(two['wall_s'], 1)} s")
    report.value("schedule.fig3.predicted.fraction2", markdown.fixed(two["work_fraction"], 2))
    report.value("schedule.fig3.predicted.known2", f"{markdown.fixed(two['known_wall_s'], 1)} s")
    report.value("schedule.fig3.predicted.blocks2", f"{markdown.fixed(two['blocks_wall_s'], 1)} s")
    report.value("schedule.fig3.predicted.blocks_fraction2", markdown.fixed(two["blocks_work_fraction"], 2))
    for name, folder in (("fig3_32", "results/multiscan/fig3"), ("tbd_32", "results/tbd/gospa")):
        at16 = predictions(report.root, folder, trials=32)[0][16]
        report.value(f"schedule.{name}", f"{markdown.sig(at16['wall_s'], 3)} s, {markdown.fixed(at16['wall_s'] / at16['bound_s'], 2)} × "
                                         f"the bound of {markdown.sig(at16['bound_s'], 3)} s (8-item blocks: "
                                         f"{markdown.sig(at16['blocks_wall_s'], 3)} s)")
    rows = []
    for label, folder in SCHEDULE_STUDIES:
        by_workers, kind = predictions(report.root, folder)
        first = by_workers[SCHEDULE_WORKERS[0]]
        row = [f"{label} (`{folder}`)" + (" †" if kind == "means" else ""), markdown.thousands(first["units"], 6),
               span(first["total_s"]), span(first["longest_unit_s"])]
        for w in SCHEDULE_WORKERS:
            p = by_workers[w]
            row.append(f"{span(p['wall_s'])} ({span(p['blocks_wall_s'])})")
        rows.append(row)
    report.value("schedule.table", markdown.table(
        ["study", "units", "algorithm time", "longest unit"] + [f"{w} workers" for w in SCHEDULE_WORKERS], rows, "lrrrrrr"))
