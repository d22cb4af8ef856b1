"""The measured numbers of the top-level README and of its manual's pages (docs/, rendered from
experiments/readme/docs/): the quick start's BP error against the BP paper's statement, the cost of
the multi-scan paper's Algorithm 2 against the column-dual Newton solver, the Open MPI
measurements (efficiency, the writer's capacity, and the core counts derived from them) and the
test command's times, each from committed runs and records."""

import csv
import io
import math
import subprocess
from pathlib import Path

from reports.core import data, markdown, verdicts
from reports.core.study import Claim, Run, Step, Study

QUICKSTART = "results/quickstart"
CLUSTER = "results/cluster"
ALGORITHM2 = "results/multiscan/algorithm2-cost"
ALGORITHM2_1000 = "results/multiscan/algorithm2-cost-1000"
DERIVED_FROM = "results/multiscan/fig4"  # the study whose per-item cost the derived core count uses
BP_PAPER_BOUND = 0.015  # bp-marginal-association Sec. V-B: "average errors of 0.015 or less in most cases"
MPI = "mpirun --allow-run-as-root"
PAIRS = ["a", "b"]
FUZZ_LONG_RUNS = "tests/fuzz/long-runs.csv"  # written by FUZZ_RECORD=tests/fuzz/long-runs.csv scripts/fuzz.sh SECONDS
FUZZ_TARGETS = ["experiment", "weights", "shard_meta", "spec"]  # tests/fuzz/CMakeLists.txt
TEST_STEPS = "tests/timings/steps.csv"  # written by scripts/record_test_timings.py after scripts/test.sh
TEST_CASES = "tests/timings/cases.csv"
TEST_RUN_ORDER = ["before", "cold", "warm", "fast"]  # the columns of docs/tests.md's table; other labels follow

RUNS = [Run(QUICKSTART, "./build/dabench run experiments/quickstart.ini --out results/quickstart --force",
            "the quick start's reference run")]
RUNS += [
    Run(f"{CLUSTER}/throughput-threads2",
        "./build/dabench run experiments/readme/bp-throughput.ini --threads 2 --force --out results/cluster/throughput-threads2"),
    Run(f"{CLUSTER}/throughput-np2",
        f"{MPI} -np 2 ./build/dabench run experiments/readme/bp-throughput.ini --threads 1 --force "
        "--out results/cluster/throughput-np2"),
    Run(f"{CLUSTER}/throughput-np3",
        f"{MPI} --oversubscribe -np 3 ./build/dabench run experiments/readme/bp-throughput.ini --threads 1 --force "
        "--out results/cluster/throughput-np3"),
]
for _pair in PAIRS:
    RUNS += [
        Run(f"{CLUSTER}/efficiency-threads2-{_pair}",
            "./build/dabench run experiments/readme/cluster-efficiency.ini --threads 2 --force "
            f"--out results/cluster/efficiency-threads2-{_pair}"),
        Run(f"{CLUSTER}/efficiency-np2-{_pair}",
            f"{MPI} -np 2 ./build/dabench run experiments/readme/cluster-efficiency.ini --threads 1 --force "
            f"--out results/cluster/efficiency-np2-{_pair}"),
    ]
SCHEDULE_RUNS = {  # fig3 at 8 trials, as issue 31 measures the work queue: 1 and 2 threads, and 2 with --costs-from
    "threads1": "--threads 1",
    "threads2": "--threads 2",
    "threads2-costs-from": "--threads 2",
}
for _name, _threads in SCHEDULE_RUNS.items():
    RUNS.append(Run(f"{CLUSTER}/schedule-fig3-8-{_name}",
                    f"./build/dabench run experiments/multiscan/fig3.ini --trials 8 {_threads} --force "
                    f"--out results/cluster/schedule-fig3-8-{_name}"
                    + (f" --costs-from {CLUSTER}/schedule-fig3-8-threads1" if _name.endswith("costs-from") else "")))
# The committed studies whose wall time docs/clusters.md predicts for 16, 64 and 256 workers.
SCHEDULE_STUDIES = [
    ("quick start", QUICKSTART), ("BP paper, experiment 1", "results/bp-paper/exp1"),
    ("BP paper, experiment 2", "results/bp-paper/exp2"), ("BP paper, experiment 3", "results/bp-paper/exp3"),
    ("multi-scan Fig. 3", "results/multiscan/fig3"), ("multi-scan Fig. 4", "results/multiscan/fig4"),
    ("multi-scan Fig. 5", "results/multiscan/fig5"), ("JDT-VB Table IV", "results/jdtvb/table4"),
    ("TBD-BP GOSPA (Fig. 2)", "results/tbd/gospa"),
]
SCHEDULE_WORKERS = (16, 64, 256)
STEPS = [Step("/usr/bin/python3 -m plots.fig6 results/quickstart/summary.csv --out results/quickstart/fig6.png "
              "--title \"2x3 grid, Pd = 0.6, lambda_fa = 0.01, r = 1\"", "the README's figure"),
         Step("/usr/bin/python3 -m reports.quickstart_check --digests results/quickstart",
              "digests of the first 100, 200 and 1000 trials per spacing, which a shorter quick start is compared with")]
TIMING_COLUMNS = ("time_us",)


def quickstart(report):
    """BP's average maximum error over the spacings (its largest mean, with its SE) against the
    paper's "0.015 or less" for this panel (Sec. V-B); the run's wall time."""
    rows = [r for r in data.read_rows(report.root, f"{QUICKSTART}/summary.csv") if r["algorithm"] == "bp"]
    peak = max(rows, key=lambda r: data.num(r, "max_error_mean"))
    m, se = data.num(peak, "max_error_mean"), data.num(peak, "max_error_se")
    verdict = verdicts.compare_bound(m, se, BP_PAPER_BOUND, holds_below=True, slack=verdicts.half_unit("0.015"))
    report.claim(Claim("Q1", "BP's average maximum error is 0.015 or less on the baseline panel", "Sec. V-B",
                       "≤ 0.015", f"peak {markdown.pm(m, se)} at spacing {peak['spacing']}", verdict,
                       "largest mean over the spacings against the bound, two standard errors and the paper's rounding"))
    report.value("quickstart.peak", markdown.pm(m, se))
    report.value("quickstart.peak_spacing", peak["spacing"])
    report.value("quickstart.trials", peak["trials"])
    report.value("quickstart.rows", str(len(data.read_rows(report.root, f"{QUICKSTART}/summary.csv"))))
    meta = data.read_meta(report.root, QUICKSTART)
    report.value("quickstart.wall", markdown.duration(meta["wall_seconds"]))
    report.value("quickstart.threads", str(meta["threads"]))


def algorithm2(report):
    """The multi-scan paper's Algorithm 2 (cvs:solver=pdca) against the column-dual Newton solver on
    the recorded trial (experiments/multiscan/algorithm2-cost.ini), or, while that run is not
    recorded, the same trial at 1000 particles and the estimate it gives (labelled as one)."""
    def solvers(folder):
        try:
            if data.read_meta(report.root, folder).get("status") != "complete":
                return None
            rows = data.read_rows(report.root, f"{folder}/trials.csv")
        except data.DataError:
            return None
        by_solver = {("pdca" if "solver=pdca" in r["algorithm"] else "newton"): r for r in rows}
        return (data.num(by_solver["newton"], "time_us") / 1e6, data.num(by_solver["pdca"], "time_us") / 1e6,
                data.num(by_solver["pdca"], "converged") == 1)
    full = solvers(ALGORITHM2)
    if full:
        newton_s, pdca_s, converged = full
        report.value("algorithm2.sentence",
                     f"on the recorded 8-target, 12-scan, 10 000-particle trial it took {markdown.sig(newton_s, 2)} s "
                     f"and Algorithm 2 {markdown.duration(pdca_s)}" + ("" if converged else ", stopping at its sweep cap")
                     + f" (`{ALGORITHM2}`)")
        return
    small = solvers(ALGORITHM2_1000)
    if not small:
        report.value("algorithm2.sentence", "Algorithm 2's cost at the study's size is not recorded yet "
                                             "(`experiments/multiscan/algorithm2-cost.ini`)")
        return
    newton_s, pdca_s, converged = small
    report.value("algorithm2.sentence",
                 f"on an 8-target, 12-scan trial at 1000 particles it took {markdown.sig(newton_s, 2)} s and "
                 f"Algorithm 2 {markdown.duration(pdca_s)}" + ("" if converged else ", stopping at its sweep cap")
                 + f" (`{ALGORITHM2_1000}`); at the study's 10 000 particles Algorithm 2 is estimated, not measured, "
                 f"at about {markdown.duration(10 * pdca_s)}, if its cost grows linearly with the particles")


def summaries_equal_but_timing(root, a, b):
    """Whether two runs' summary.csv agree in every column but the timing statistics."""
    ra, rb = data.read_rows(root, f"{a}/summary.csv"), data.read_rows(root, f"{b}/summary.csv")
    if len(ra) != len(rb):
        return False
    for x, y in zip(ra, rb):
        for k in x:
            if not k.startswith(TIMING_COLUMNS) and x[k] != y.get(k):
                return False
    return True


def thousands(value, digits=3):
    """value to `digits` significant digits with thin groups: 185626 -> "186 000"."""
    return f"{float(f'{value:.{digits}g}'):,.0f}".replace(",", " ")


def rows_per_second(meta):
    """trials.csv rows written per second of the run's wall time."""
    return meta["items_total"] * len(meta["algorithms"]) / meta["wall_seconds"]


def cluster(report):
    """Open MPI efficiency (wall time of 2 threads in one process over 2 ranks of 1 thread, pairs
    run back to back) and the writer's rows per second; the derived number of cores one writer
    keeps busy at the multi-scan study's cost per row (derived: not measured)."""
    root = report.root
    effs, same = [], True
    for pair in PAIRS:
        threads = data.read_meta(root, f"{CLUSTER}/efficiency-threads2-{pair}")
        ranks = data.read_meta(root, f"{CLUSTER}/efficiency-np2-{pair}")
        effs.append(threads["wall_seconds"] / ranks["wall_seconds"])
        report.value(f"cluster.eff.{pair}", f"{markdown.fixed(ranks['wall_seconds'], 1)} s against "
                                            f"{markdown.fixed(threads['wall_seconds'], 1)} s")
        same &= summaries_equal_but_timing(root, f"{CLUSTER}/efficiency-threads2-{pair}", f"{CLUSTER}/efficiency-np2-{pair}")
    report.value("cluster.efficiencies", " and ".join(markdown.fixed(e, 2) for e in effs))
    report.value("cluster.same", "identical" if same else "**not** identical")
    rates = {}
    for name in ("threads2", "np2", "np3"):
        meta = data.read_meta(root, f"{CLUSTER}/throughput-{name}")
        rates[name] = rows_per_second(meta)
        report.value(f"cluster.rate.{name}", thousands(rates[name]))
    capacity = min(rates["np2"], rates["np3"])  # what rank 0 sustains while it also computes
    report.value("cluster.capacity", thousands(capacity))
    meta = data.read_meta(root, "results/cluster/throughput-threads2")
    report.value("cluster.items", f"{meta['items_total']:,}".replace(",", " "))
    # Derived: a multi-scan item (one trial, every algorithm) costs its algorithms' summed time
    # and writes its trials.csv and targets.csv rows; one writer at `capacity` rows/s keeps
    # capacity / rows-per-item items per second in flight, i.e. that many times seconds-per-item cores.
    fig4 = data.read_rows(root, f"{DERIVED_FROM}/trials.csv")
    targets = data.read_rows(root, f"{DERIVED_FROM}/targets.csv")
    items = len({(r["point"], r["trial"]) for r in fig4})
    seconds_per_item = math.fsum(data.num(r, "time_us") for r in fig4) / 1e6 / items
    rows_per_item = (len(fig4) + len(targets)) / items
    cores = capacity / rows_per_item * seconds_per_item
    report.value("cluster.derived.seconds", markdown.sig(seconds_per_item, 2))
    report.value("cluster.derived.rows", markdown.sig(rows_per_item, 2))
    report.value("cluster.derived.cores", thousands(cores, 1))


def study_wall_times(report):
    """Wall time of the committed runs the experiment table of docs/experiment-files.md mentions (from meta.json)."""
    for name, folder in (("jdtvb_table4", "results/jdtvb/table4"), ("multiscan", None)):
        if folder:
            report.value(f"wall.{name}", markdown.duration(data.read_meta(report.root, folder)["wall_seconds"]))
    metas = {f: data.read_meta(report.root, f"results/multiscan/{f}") for f in ("fig3", "fig4", "fig5")}
    total = sum(m["wall_seconds"] for m in metas.values())
    resumed = [f for f, m in metas.items() if m.get("resumed")]
    report.value("wall.multiscan", markdown.duration(total) + (
        f" (more: {', '.join(resumed)} was resumed and records its last session only)" if resumed else ""))


def fuzz_long_runs(report):
    """The long libFuzzer runs recorded by `FUZZ_RECORD=tests/fuzz/long-runs.csv scripts/fuzz.sh`: per
    target the time, the inputs tried and their rate, the corpus (seeds, inputs that grew it) and
    the coverage reached, each row a run that ended without a finding."""
    try:
        rows = data.read_rows(report.root, FUZZ_LONG_RUNS)
    except data.DataError:
        rows = []
    if not rows:
        report.value("fuzz.long_runs", "No long run is recorded yet (`tests/fuzz/long-runs.csv` is empty).")
        return
    table = [[f"`fuzz_{r['target']}`", markdown.duration(data.num(r, "seconds")), thousands(data.num(r, "inputs")),
              thousands(data.num(r, "inputs_per_second")), r["seed_inputs"], r["new_inputs"], r["edges"], r["features"],
              f"{r['peak_rss_mb']} MB", f"{r['date']}, `{r['commit']}`, {r['compiler']}"] for r in rows]
    missing = [f"`fuzz_{t}`" for t in FUZZ_TARGETS if t not in {r["target"] for r in rows}]
    report.value("fuzz.long_runs", markdown.table(
        ["target", "time", "inputs tried", "per second", "seed inputs", "new inputs", "edges", "features",
         "peak memory", "when, commit, compiler"], table, "lrrrrrrrrl")
        + (f"\n\nNo long run without a finding is recorded yet for {', '.join(missing)}." if missing else ""))


def minutes(seconds):
    """"7:12" (min:s)."""
    seconds = round(seconds)
    return f"{seconds // 60}:{seconds % 60:02d}"


def test_timings(report):
    """`scripts/test.sh`'s recorded runs (scripts/record_test_timings.py): one table of every step's
    wall time (and its processes' CPU time) per run, and the ten slowest ctest entries per build."""
    steps = data.read_rows(report.root, TEST_STEPS)

    def order(run):
        return TEST_RUN_ORDER.index(run) if run in TEST_RUN_ORDER else len(TEST_RUN_ORDER)
    runs = sorted(dict.fromkeys(r["run"] for r in steps), key=order)
    keys = list(dict.fromkeys((r["build"], r["step"]) for r in steps))
    keys.sort(key=lambda k: k == ("all", "total"))
    by = {(r["run"], r["build"], r["step"]): r for r in steps}
    rows = []
    for build, step in keys:
        row = ["**total**" if step == "total" else step if build == step else f"{build} {step.replace('_', ' ')}"]
        for run in runs:
            r = by.get((run, build, step))
            if r is None:
                row.append("–")
                continue
            cell = minutes(data.num(r, "wall_s"))
            cpu = data.num(r, "cpu_s")
            row.append(f"**{cell}**" if step == "total" else cell + (f" ({minutes(cpu)})" if cpu is not None else ""))
        rows.append(row)
    first = {run: next(r for r in steps if r["run"] == run) for run in runs}
    floor = ["CPU of every step ÷ cores"]  # no schedule of these steps on these cores is shorter
    for run in runs:
        cpus = [data.num(r, "cpu_s") for r in steps if r["run"] == run and r["step"] != "total"]
        floor.append("–" if None in cpus else minutes(sum(cpus) / int(first[run]["cores"])))
    rows.append(floor)
    header = ["step"] + [f"{run}<br>`{first[run]['commit']}`, {first[run]['cores']} cores" for run in runs]
    report.value("tests.steps", markdown.table(header, rows, "l" + "r" * len(runs)))
    cases = data.read_rows(report.root, TEST_CASES)
    case_runs = sorted(dict.fromkeys(r["run"] for r in cases), key=order)
    for build in ("release", "asan"):
        seconds = {(r["run"], r["case"]): data.num(r, "seconds") for r in cases if r["build"] == build}
        shown = [run for run in case_runs if any(key[0] == run for key in seconds)]
        names = sorted({c for _, c in seconds}, key=lambda c: -max(v for (_, n), v in seconds.items() if n == c))
        table = [[name] + [f"{seconds[(run, name)]:.1f}" if (run, name) in seconds else "–" for run in shown]
                 for name in names]
        report.value(f"tests.cases.{build}", markdown.table(["case"] + [f"{run} (s)" for run in shown], table,
                                                            "l" + "r" * len(shown)))
    if "warm" in runs:
        warm = {r["step"]: data.num(r, "cpu_s") for r in steps if r["run"] == "warm" and r["build"] == "asan"}
        total = sum(data.num(r, "cpu_s") for r in steps if r["run"] == "warm" and r["step"] != "total")
        report.value("tests.warm_asan_share", markdown.percent((warm["ctest"] + warm["fuzz"]) / total, 0))
    else:
        report.value("tests.warm_asan_share", "(no warm run recorded)")
    cold = next((run for run in runs if run.startswith("cold")), None)
    if cold is None:
        report.value("tests.cold_compile", f"no cold run is recorded yet (`{TEST_STEPS}`)")
        return
    builds = [r for r in steps if r["run"] == cold and r["step"] == "build"]
    cpu = sum(data.num(r, "cpu_s") for r in builds)
    cores = int(first[cold]["cores"])
    report.value("tests.cold_compile", f"its builds took {minutes(cpu)} of CPU time ("
                 + ", ".join(f"{r['build']} {minutes(data.num(r, 'cpu_s'))}" for r in builds)
                 + f"), at least {minutes(cpu / cores)} of wall time on {cores} cores, against "
                 f"{minutes(data.num(by[(cold, 'all', 'total')], 'wall_s'))} for the whole run")


def span(seconds):
    """A duration from microseconds to hours: "85 µs", "3.1 ms", "42 s", "12.7 min", "1.6 h"."""
    if seconds < 1e-3:
        return f"{markdown.sig(seconds * 1e6, 2)} µs"
    if seconds < 1:
        return f"{markdown.sig(seconds * 1e3, 2)} ms"
    return markdown.duration(seconds)


def schedule_csv(report, folder, workers, trials=None):
    """`dabench schedule FOLDER --format csv` (the build's program) as rows of numbers by worker count."""
    # The program of the data's tree, else of this checkout (a copy of the data has no build).
    candidates = [Path(report.root) / "build" / "dabench", Path(__file__).resolve().parents[2] / "build" / "dabench"]
    program = next((c for c in candidates if c.is_file()), None)
    if program is None:
        raise data.DataError(f"{candidates[-1]}: not built (bash scripts/build.sh): the schedule table of docs/clusters.md runs it")
    command = [str(program), "schedule", folder, "--format", "csv", "--workers", ",".join(map(str, workers))]
    if trials:
        command += ["--trials", str(trials)]
    done = subprocess.run(command, cwd=report.root, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise data.DataError(f"{' '.join(command[1:])}: {done.stderr.strip()}")
    return {int(r["workers"]): {k: float(v) for k, v in r.items()} for r in csv.DictReader(io.StringIO(done.stdout))}


def scheduling(report):
    """The work queue (issue 31): fig3 at 8 trials measured on 1 and 2 threads against the
    simulator's predictions from the 1-thread run's unit times; the predictions for 16 workers
    of fig3 and tbd-gospa at 32 trials; and a table of every committed study at 16, 64 and 256."""
    root = Path(report.root)
    metas = {name: data.read_meta(report.root, f"{CLUSTER}/schedule-fig3-8-{name}") for name in SCHEDULE_RUNS}
    predicted = schedule_csv(report, f"{CLUSTER}/schedule-fig3-8-threads1", (1, 2))
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
        at16 = schedule_csv(report, folder, (16,), trials=32)[16]
        report.value(f"schedule.{name}", f"{markdown.sig(at16['wall_s'], 3)} s, {markdown.fixed(at16['wall_s'] / at16['bound_s'], 2)} × "
                                         f"the bound of {markdown.sig(at16['bound_s'], 3)} s (8-item blocks: "
                                         f"{markdown.sig(at16['blocks_wall_s'], 3)} s)")
    rows = []
    for label, folder in SCHEDULE_STUDIES:
        by_workers = schedule_csv(report, folder, SCHEDULE_WORKERS)
        first = by_workers[SCHEDULE_WORKERS[0]]
        means = not any((root / folder / name).is_file() for name in ("trials.csv", "runs.csv"))
        row = [f"{label} (`{folder}`)" + (" †" if means else ""), thousands(first["units"], 6),
               span(first["total_s"]), span(first["longest_unit_s"])]
        for w in SCHEDULE_WORKERS:
            p = by_workers[w]
            row.append(f"{span(p['wall_s'])} ({span(p['blocks_wall_s'])})")
        rows.append(row)
    report.value("schedule.table", markdown.table(
        ["study", "units", "algorithm time", "longest unit"] + [f"{w} workers" for w in SCHEDULE_WORKERS], rows, "lrrrrrr"))


# The studies the README lists, each with its headline verdict counts (the value "headline" of
# its checks: Report.headline).
HEADLINED = ("bp-paper", "multiscan", "jdtvb", "tbd", "leaderboard")


def headlines(report):
    for name in HEADLINED:
        report.value(f"headline.{name}", report.studies[name].values["headline"])


def checks(report):
    headlines(report)
    quickstart(report)
    scheduling(report)
    algorithm2(report)
    cluster(report)
    study_wall_times(report)
    fuzz_long_runs(report)
    test_timings(report)


# The manual's pages (docs/), rendered from the same checks as the README, the front page.
DOCS_PAGES = ("layout", "command-line", "clusters", "experiment-files", "result-files", "extending", "cpp-library",
              "python", "tests", "benchmarks", "algorithms")

STUDY = Study(name="readme", report="README.md", template="experiments/readme/template.md", runs=RUNS, steps=STEPS,
              checks=checks, lint=False, needs=HEADLINED,
              pages=tuple((f"experiments/readme/docs/{page}.md", f"docs/{page}.md") for page in DOCS_PAGES))
