"""The measured numbers of the top-level README and of its manual's pages (docs/, rendered from
experiments/readme/docs/): the quick start's BP error against the BP paper's statement, the cost of
the multi-scan paper's Algorithm 2 against the column-dual Newton solver, the Open MPI
measurements (efficiency, the writer's capacity, and the core counts derived from them) and the
test command's times, each from committed runs and records."""

import math

from reports.core import data, markdown, verdicts
from experiments.readme import scheduling
from experiments.readme.runs import CLUSTER, PAIRS, QUICKSTART, RUNS, STEPS
from reports.core.study import Claim, Study

ALGORITHM2 = "results/multiscan/algorithm2-cost"
ALGORITHM2_1000 = "results/multiscan/algorithm2-cost-1000"
DERIVED_FROM = "results/multiscan/fig4"  # the study whose per-item cost the derived core count uses
BP_PAPER_BOUND = 0.015  # bp-marginal-association Sec. V-B: "average errors of 0.015 or less in most cases"
FUZZ_LONG_RUNS = "tests/fuzz/long-runs.csv"  # written by FUZZ_RECORD=tests/fuzz/long-runs.csv scripts/fuzz.sh SECONDS
FUZZ_TARGETS = ["experiment", "weights", "shard_meta", "spec"]  # tests/fuzz/CMakeLists.txt
TEST_STEPS = "tests/timings/steps.csv"  # written by scripts/record_test_timings.py after scripts/test.sh
TEST_CASES = "tests/timings/cases.csv"
TEST_RUN_ORDER = ["before", "cold", "warm", "fast"]  # the columns of docs/tests.md's table; other labels follow

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
        report.value(f"cluster.rate.{name}", markdown.thousands(rates[name]))
    capacity = min(rates["np2"], rates["np3"])  # what rank 0 sustains while it also computes
    report.value("cluster.capacity", markdown.thousands(capacity))
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
    report.value("cluster.derived.cores", markdown.thousands(cores, 1))


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
    table = [[f"`fuzz_{r['target']}`", markdown.duration(data.num(r, "seconds")), markdown.thousands(data.num(r, "inputs")),
              markdown.thousands(data.num(r, "inputs_per_second")), r["seed_inputs"], r["new_inputs"], r["edges"], r["features"],
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


# The studies the README lists, each with its headline verdict counts (the value "headline" of
# its checks: Report.headline).
HEADLINED = ("bp-paper", "multiscan", "jdtvb", "tbd", "leaderboard")


def headlines(report):
    for name in HEADLINED:
        report.value(f"headline.{name}", report.studies[name].values["headline"])


def checks(report):
    headlines(report)
    quickstart(report)
    scheduling.check(report)
    algorithm2(report)
    cluster(report)
    study_wall_times(report)
    fuzz_long_runs(report)
    test_timings(report)


# The manual's pages (docs/), rendered from the same checks as the README, the front page.
DOCS_PAGES = ("layout", "command-line", "clusters", "experiment-files", "result-files", "extending", "cpp-library",
              "python", "tests", "benchmarks", "algorithms")

STUDY = Study(name="readme", report="README.md", template="experiments/readme/template.md", runs=RUNS, steps=STEPS,
              checks=checks, digest=scheduling.digest, needs=HEADLINED,
              pages=tuple((f"experiments/readme/docs/{page}.md", f"docs/{page}.md") for page in DOCS_PAGES))
