"""leaderboard: every single-scan method of dabench on the BP paper's experiment-1 panels and
experiment-2 panel (issue 32), on identical trials.

The digest (python3 -m reports.digest leaderboard) reads each run's trials.csv, which is not committed,
and writes next to it
- panels.csv: per panel and algorithm, the trials, completions, and the mean (± SE), quartiles and
  maximum of max_error and time_us over the panel's completed trials (and the largest max_error
  over the trials a method reports as converged);
- paired.csv: `dabench compare` of BP against every other algorithm, and of the permanent against
  EHM, per sweep point and metric (mean paired difference, 95 % interval, Wilcoxon signed-rank p,
  Holm-adjusted over the points of the pair, share of trials where the first is lower).
The checks read those digests, summary.csv, meta.json and the dense-problem benchmark JSON."""

import csv
import json
import math
import os
import subprocess

import numpy as np

from reports.core import data, markdown, stats, verdicts
from reports.core.study import Claim, Run, Step, Study

FOLDER = "results/leaderboard"
EXP1 = f"{FOLDER}/exp1"
EXP2 = f"{FOLDER}/exp2"
BENCH = f"{FOLDER}/bench-exact-dense.json"
PANELS = "panels.csv"
PAIRED = "paired.csv"
DABENCH = "./build/dabench"

RUNS = [
    Run(EXP1, f"{DABENCH} run experiments/leaderboard/exp1.ini --force",
        "seven panels × 21 spacings × 200 trials, 20 algorithms"),
    Run(EXP2, f"{DABENCH} run experiments/leaderboard/exp2.ini --force", "29 grid sizes × 100 trials, 19 algorithms"),
    Run(BENCH, f"taskset -c 0 ./build/dabench_bench --benchmark_filter='^exact_dense/' "
               f"--benchmark_out={BENCH} --benchmark_out_format=json",
        "the exact methods on dense random problems, one core", optional=True),
]
STEPS = [
    Step("/usr/bin/python3 -m reports.digest leaderboard", f"{PANELS} and {PAIRED} of exp1 and exp2"),
    Step(f"/usr/bin/python3 -m plots.leaderboard {EXP1}/{PANELS} {EXP2}/{PANELS} --out {FOLDER}/leaderboard.png"),
]

BP = "bp"
SIGNIFICANT = 0.05  # Holm-adjusted Wilcoxon p below which a paired difference counts
EXACT_TOLERANCE = 1e-12  # an exact method's largest error against an exact reference


# ----------------------------------------------------------------------------- panels

def exp1_panel(row):
    """The experiment-1 panel of a row: baseline, or the one parameter changed from it."""
    pd, fa, r = float(row["pd"]), float(row["lambda_fa"]), float(row["r"])
    if pd != 0.6:
        return f"exp. 1, Pd = {row['pd']}"
    if fa != 0.01:
        return f"exp. 1, λ_fa = {row['lambda_fa']}"
    if r != 1:
        return f"exp. 1, r = {row['r']}"
    return "exp. 1, baseline"


def exp2_panel(_row):
    return "exp. 2, n×3 grids"


PANEL_OF = {EXP1: exp1_panel, EXP2: exp2_panel}
X_OF = {EXP1: "spacing", EXP2: "rows"}  # the swept parameter within a panel


# ----------------------------------------------------------------------------- digest

PANELS_HEADER = ["panel", "algorithm", "role", "trials", "ok", "converged_share",
                 "max_error_mean", "max_error_se", "max_error_p25", "max_error_median", "max_error_p75",
                 "max_error_max", "max_error_max_converged",
                 "time_us_mean", "time_us_se", "time_us_p25", "time_us_median", "time_us_p75"]
PAIRED_HEADER = ["point", "panel", "x", "metric", "a", "b", "n", "mean_diff", "ci_low", "ci_high",
                 "wilcoxon_p", "holm_p", "a_better", "ties"]


def fmt(value):
    return "" if value is None or not math.isfinite(value) else f"{value:.6g}"



def panel_rows(source, panel_of, references):
    """panels.csv rows of one trials.csv, streamed: (panel, algorithm) in order of appearance;
    role "reference" for the run's references (their error is zero by definition), a reference
    that never ran (a fallback not needed) left out."""
    cells = {}
    with open(source, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        for r in reader:
            if None in r.values():
                continue  # a cut last line of an interrupted run
            cell = cells.setdefault((panel_of(r), r["algorithm"]), [0, [], [], []])
            cell[0] += 1
            if r["status"] == "ok":
                error, time = float(r["max_error"]), float(r["time_us"])
                cell[1].append(error)
                cell[2].append(time)
                if r["converged"] == "1":
                    cell[3].append(error)
    out = []
    for (panel, algorithm), (trials, errors, times, converged) in cells.items():
        if algorithm in references and not errors:
            continue
        e, t = np.asarray(errors), np.asarray(times)
        e_mean, e_se, _ = stats.mean_se(errors)
        t_mean, t_se, _ = stats.mean_se(times)
        q = lambda a, p: float(np.percentile(a, p)) if len(a) else math.nan  # noqa: E731
        out.append([panel, algorithm, "reference" if algorithm in references else "algorithm", trials, len(errors), fmt(len(converged) / len(errors) if errors else math.nan),
                    fmt(e_mean), fmt(e_se), fmt(q(e, 25)), fmt(q(e, 50)), fmt(q(e, 75)),
                    fmt(float(e.max()) if len(e) else math.nan), fmt(max(converged) if converged else math.nan),
                    fmt(t_mean), fmt(t_se), fmt(q(t, 25)), fmt(q(t, 50)), fmt(q(t, 75))])
    return out


def pairs_of(root, folder):
    """The pairs a run is compared on: BP against every other algorithm, the permanent against EHM."""
    meta = data.read_meta(root, folder)
    algorithms = meta["algorithms"]
    pairs = [(BP, a) for a in algorithms if a != BP]
    permanent = [a for a in algorithms if a.split(":")[0] == "permanent"]
    ehm = "ehm" if "ehm" in algorithms + meta["references"] else None
    if permanent and ehm:
        pairs.append((permanent[0], ehm))
    return pairs


def paired_rows(root, folder, panel_of, x_column, dabench):
    """paired.csv rows of one run from `dabench compare RUN --algorithms A,B --format csv`."""
    out = []
    for a, b in pairs_of(root, folder):
        try:
            done = subprocess.run([dabench, "compare", data.path(root, folder), "--algorithms", f"{a},{b}",
                                   "--metric", "max_error,time_us", "--format", "csv"],
                                  capture_output=True, text=True, check=False)
        except OSError as error:
            raise data.DataError(f"{dabench}: {error.strerror} (build it: bash scripts/build.sh dabench)") from None
        if done.returncode != 0:
            raise data.DataError(f"dabench compare {folder} {a},{b}: {done.stderr.strip()}")
        for r in csv.DictReader(done.stdout.splitlines()):
            out.append([r["point"], panel_of(r), r[x_column], r["metric"], r["a"], r["b"], r["n"]]
                       + [fmt(data.number(r[c])) for c in ("mean_diff", "ci_low", "ci_high", "wilcoxon_p", "holm_p",
                                                           "a_better", "ties")])
    return out


def digest(root):
    """Write panels.csv and paired.csv next to the trials.csv of each leaderboard run."""
    written = []
    dabench = data.path(root, DABENCH)
    for folder in (EXP1, EXP2):
        source = data.path(root, folder, "trials.csv")
        if not os.path.exists(source):
            continue
        references = data.read_meta(root, folder)["references"]
        data.write_csv(data.path(root, folder, PANELS), PANELS_HEADER, panel_rows(source, PANEL_OF[folder], references))
        data.write_csv(data.path(root, folder, PAIRED), PAIRED_HEADER,
                  paired_rows(root, folder, PANEL_OF[folder], X_OF[folder], dabench))
        written += [data.path(root, folder, PANELS), data.path(root, folder, PAIRED)]
    if not written:
        raise data.DataError(f"no trials.csv in {EXP1} or {EXP2}")
    return written


# ----------------------------------------------------------------------------- reading the digests

def read_panels(root):
    """{panel: {algorithm: row}} over both runs, panels in order."""
    out = {}
    for folder in (EXP1, EXP2):
        for r in data.read_rows(root, f"{folder}/{PANELS}"):
            out.setdefault(r["panel"], {})[r["algorithm"]] = r
    return out


def read_paired(root):
    """{(a, b, metric): {panel: [rows]}} over both runs."""
    out = {}
    for folder in (EXP1, EXP2):
        for r in data.read_rows(root, f"{folder}/{PAIRED}"):
            out.setdefault((r["a"], r["b"], r["metric"]), {}).setdefault(r["panel"], []).append(r)
    return out


def tally(rows):
    """(points where a is lower beyond error, points where a is higher beyond error, points)."""
    lower = sum(1 for r in rows if data.num(r, "holm_p") is not None and data.num(r, "holm_p") < SIGNIFICANT
                and data.num(r, "mean_diff") < 0)
    higher = sum(1 for r in rows if data.num(r, "holm_p") is not None and data.num(r, "holm_p") < SIGNIFICANT
                 and data.num(r, "mean_diff") > 0)
    return lower, higher, len(rows)


def complete(row):
    return int(row["ok"]) == int(row["trials"])


def competing(row):
    """A method on the leaderboard: complete, and not the reference (error zero by definition)."""
    return complete(row) and row["role"] != "reference"


def dominated_beyond_error(row, others):
    """The algorithms that beat row beyond error on both axes: faster by median time and more
    accurate by mean max error by more than Z combined standard errors (and by more than rounding,
    EXACT_TOLERANCE, so that exact methods tie); complete runs only."""
    e, se = data.num(row, "max_error_mean"), data.num(row, "max_error_se") or 0.0
    t = data.num(row, "time_us_median")
    out = []
    for spec, o in others.items():
        if o is row or not competing(o):
            continue
        oe, ose = data.num(o, "max_error_mean"), data.num(o, "max_error_se") or 0.0
        if data.num(o, "time_us_median") < t and e - oe > max(verdicts.Z * verdicts.combined_se(se, ose),
                                                              EXACT_TOLERANCE):
            out.append(spec)
    return out


# ----------------------------------------------------------------------------- checks

def mean_pm(mean, se):
    """mean ± se, in exponent form for the tiny errors of exact methods."""
    if mean is not None and 0 < abs(mean) < 1e-4:
        return f"{markdown.sig(mean, 3)} ± {markdown.sig(se, 2)}"
    return markdown.pm(mean, se)


def leaderboard_table(panel_rows_by_algorithm):
    """One panel: algorithms by mean max error, with time quartiles and completion."""
    rows = []
    ordered = sorted(panel_rows_by_algorithm.items(),
                     key=lambda kv: (kv[1]["role"] == "reference", not complete(kv[1]),
                                     data.num(kv[1], "max_error_mean")))
    for spec, r in ordered:
        beaten = dominated_beyond_error(r, panel_rows_by_algorithm)
        if r["role"] == "reference":
            front = "(the reference)"
        elif complete(r) and not beaten:
            front = "front"
        else:
            front = ", ".join(f"`{b}`" for b in beaten[:2]) + (" …" if len(beaten) > 2 else "") or "(incomplete)"
        rows.append([f"`{spec}`", mean_pm(data.num(r, "max_error_mean"), data.num(r, "max_error_se")),
                     markdown.sig(data.num(r, "max_error_p75")),
                     f"{markdown.sig(data.num(r, 'time_us_median'))} [{markdown.sig(data.num(r, 'time_us_p25'))}, "
                     f"{markdown.sig(data.num(r, 'time_us_p75'))}]",
                     f"{r['ok']} / {r['trials']}", front])
    return markdown.table(["algorithm", "mean max error", "max error p75", "time µs: median [p25, p75]", "completed",
                           "beaten on both axes by"], rows, align="lrrrrl")


def bp_matrix(paired, panels, metric):
    """Rows: each algorithm against BP; columns: panels; cells "lower/higher" counts of points."""
    others = [b for (a, b, m) in paired if a == BP and m == metric]
    rows = []
    for b in others:
        cells = []
        for panel in panels:
            found = paired[(BP, b, metric)].get(panel)
            if not found:
                cells.append("–")
                continue
            lower, higher, n = tally(found)
            cells.append(f"{lower} / {higher} ({n})")
        rows.append([f"`{b}`"] + cells)
    return markdown.table(["BP against"] + panels, rows, align="l" + "r" * len(panels))


ACCURACY_RULE = (f"per sweep point, Wilcoxon signed-rank on the paired max errors, Holm-adjusted over the pair's "
                 f"points of a run, beyond error at p < {SIGNIFICANT}; agrees: BP lower somewhere and higher nowhere; "
                 f"direction only: BP lower at more points than higher, higher at some; differs: BP higher at as many "
                 f"points as lower or more; within error: no point beyond error")


def accuracy_claim(cid, b, paired, panels):
    """Ours: BP is more accurate than b, sweep point by sweep point, trial by trial."""
    lower = higher = points = 0
    worse_at = []
    for panel in panels:
        found = paired.get((BP, b, "max_error"), {}).get(panel, [])
        lo, hi, n = tally(found)
        lower, higher, points = lower + lo, higher + hi, points + n
        if hi:
            worse_at.append(f"{panel} ({hi})")
    if points == 0:
        verdict = verdicts.NOT_RUN
    elif lower == higher == 0:
        verdict = verdicts.WITHIN_ERROR
    elif higher == 0:
        verdict = verdicts.AGREES
    elif lower > higher:
        verdict = verdicts.DIRECTION_ONLY
    else:
        verdict = verdicts.DIFFERS
    ours = f"BP lower at {lower}, higher at {higher} of {points} points"
    claim = Claim(cid, f"BP is more accurate than `{b}`", "ours", "–", ours, verdict, ACCURACY_RULE)
    if worse_at:
        claim.details.append("BP higher in " + ", ".join(worse_at))
    return claim


def exactness_claim(cid, statement, row, column, where, trials=None):
    """An exact method's largest error against an exact reference is below EXACT_TOLERANCE, over
    `trials` trials (default: the row's completed trials)."""
    value = data.num(row, column) if row else None
    if value is None:
        return Claim(cid, statement, "issue 32", f"≤ {EXACT_TOLERANCE:g}", "not run", verdicts.NOT_RUN, where)
    verdict = verdicts.AGREES if value <= EXACT_TOLERANCE else verdicts.DIFFERS
    return Claim(cid, statement, "issue 32", f"≤ {EXACT_TOLERANCE:g}",
                 f"{value:.2g} over {row['ok'] if trials is None else trials} trials", verdict, where)


def front_claim(panels):
    """Ours: BP is on the Pareto front of every panel (no competing method beats it on both axes)."""
    beaten = {p: dominated_beyond_error(by[BP], by) if BP in by else [] for p, by in panels.items()}
    beaten = {p: b for p, b in beaten.items() if b or BP not in panels[p] or not competing(panels[p][BP])}
    fronts = len(panels) - len(beaten)
    claim = Claim("F1", "BP is on the Pareto front of every panel: no complete method is both faster (median time) "
                  "and more accurate (mean max error, beyond error)", "ours", "–",
                  f"on the front in {fronts} of {len(panels)} panels",
                  verdicts.AGREES if not beaten else verdicts.DIFFERS,
                  f"dominance beyond error: faster median time and a mean max error lower by more than "
                  f"{verdicts.Z:g} combined standard errors")
    claim.details += [f"{p}: beaten by " + ", ".join(f"`{b}`" for b in by) for p, by in beaten.items()]
    return claim


def speed_claim(cid, statement, rows, expect_lower):
    """The first of a pair is faster (expect_lower) or slower at the points of some panels."""
    lower, higher, n = tally(rows)
    favourable, against = (lower, higher) if expect_lower else (higher, lower)
    if n == 0:
        verdict = verdicts.NOT_RUN
    elif against == 0 and favourable > 0:
        verdict = verdicts.AGREES
    elif favourable > against:
        verdict = verdicts.DIRECTION_ONLY
    elif favourable == against == 0:
        verdict = verdicts.WITHIN_ERROR
    else:
        verdict = verdicts.DIFFERS
    return Claim(cid, statement, "ours", "–", f"faster at {lower}, slower at {higher} of {n} points", verdict,
                 f"paired time per trial per sweep point (Wilcoxon, Holm over the points, p < {SIGNIFICANT}): agrees "
                 f"when the expected side wins somewhere and loses nowhere, direction only when it wins more often "
                 f"than it loses")


def bench_table(root):
    """Where each exact method wins on dense random problems: Google Benchmark's real time per
    solve (µs) by size and density, and the fastest method that completes."""
    try:
        with open(data.path(root, BENCH), encoding="utf-8") as f:
            benchmarks = json.load(f)["benchmarks"]
    except OSError:
        return None
    cells = {}
    for b in benchmarks:
        _, method, size, density = b["name"].split("/")[:4]
        skipped = b.get("skipped", 0.0) > 0
        cells.setdefault((size, density.replace("density_", "")), {})[method] = (b["real_time"], skipped)
    methods = ["permanent", "ehm", "jt", "exact"]
    rows = []
    for (size, density), found in cells.items():
        row = [size.replace("x", " × "), density]
        best = min(((t, m) for m, (t, s) in found.items() if not s), default=(None, "–"))
        for m in methods:
            if m not in found:
                row.append("–")
            else:
                t, s = found[m]
                row.append(f"refused after {markdown.sig(t)}" if s else markdown.sig(t))
        row.append(f"`{best[1]}`")
        rows.append(row)
    return markdown.table(["n × m", "density"] + [f"`{m}` µs" for m in methods] + ["fastest"], rows,
                          align="lr" + "r" * len(methods) + "l")


def checks(report):
    root = report.root
    panels = read_panels(root)
    paired = read_paired(root)
    names = list(panels)
    for k, (panel, by_algorithm) in enumerate(panels.items()):
        report.value(f"table_{k}", leaderboard_table(by_algorithm))
        report.value(f"panel_{k}", panel)
    report.value("bp_error_matrix", bp_matrix(paired, names, "max_error"))
    report.value("bp_time_matrix", bp_matrix(paired, names, "time_us"))
    report.claim(front_claim(panels))
    accuracy_ids = []
    approximations = [b for (a, b, m) in paired if a == BP and m == "max_error"
                      and b.split(":")[0] not in ("ehm", "permanent")]  # exact: error is the reference threshold's
    for i, b in enumerate(approximations, start=1):
        report.claim(accuracy_claim(f"A{i}", b, paired, names))
        accuracy_ids.append(f"A{i}")
    exp2_panel_name = exp2_panel(None)
    permanent2 = next((r for s, r in panels.get(exp2_panel_name, {}).items() if s.startswith("permanent")), None)
    kbest2 = panels.get(exp2_panel_name, {}).get("kbest-jpda:k=1000")
    report.claim(exactness_claim("X1", "the permanent's marginals are exact: largest max error against EHM on the "
                                 "experiment-2 trials it completes", permanent2, "max_error_max",
                                 "largest max_error over the completed trials of exp2 (reference: EHM, exact)"))
    report.claim(exactness_claim("X2", "k-best JPDA is exact where k covers every event: largest max error of "
                                 "`kbest-jpda:k=1000` over the experiment-2 trials it reports converged",
                                 kbest2, "max_error_max_converged",
                                 "largest max_error over the trials with converged = 1 (every cluster had fewer "
                                 "than k events)",
                                 trials=round(data.num(kbest2, "converged_share") * int(kbest2["ok"])) if kbest2 else None))
    report.value("kbest_converged_share", markdown.percent(data.num(kbest2, "converged_share")) if kbest2 else "–")
    perm_pairs = [(a, b) for (a, b, m) in paired if a.startswith("permanent") and m == "time_us"]
    exp1_time = [r for (a, b) in perm_pairs for p, rows in paired[(a, b, "time_us")].items() if p != exp2_panel_name
                 for r in rows]
    exp2_time = [r for (a, b) in perm_pairs for r in paired[(a, b, "time_us")].get(exp2_panel_name, [])]
    report.value("approximations", str(len(approximations)))
    for name, rows in (("exp1_faster", exp1_time), ("exp2_faster", exp2_time)):
        lower, higher, _ = tally(rows)
        report.value(name, "the permanent" if lower > higher else "EHM" if higher > lower else "neither")
    report.claim(speed_claim("E1", "on the six-target panels of experiment 1 the permanent is faster than EHM", exp1_time, expect_lower=True))
    report.claim(speed_claim("E2", "on the long grids of experiment 2 the permanent is slower than EHM where it "
                             "completes", exp2_time, expect_lower=False))
    table = bench_table(root)
    report.value("bench_table", table if table else "*(not recorded: the benchmark run above is optional)*")
    report.value("claims_table", report.claims_table(["F1", "X1", "X2", "E1", "E2"] + accuracy_ids))
    rules = report.rules_list(["F1", "X1", "X2", "E1", "E2"])
    details = [d for c in report.claims if c.id in accuracy_ids for d in [f"{c.id}: {x}" for x in c.details]]
    if accuracy_ids:
        rules += (f"\n- **{accuracy_ids[0]}–{accuracy_ids[-1]}**: {ACCURACY_RULE}"
                  + "".join(f"\n  - {d}" for d in details))
    report.value("rules", rules)
    report.value("significance", f"{SIGNIFICANT:g}")
    report.value("verdict_counts", report.verdict_counts())
    report.headline("claims of ours")


STUDY = Study(
    name="leaderboard",
    report=f"{FOLDER}/REPORT.md",
    template="experiments/leaderboard/template.md",
    runs=RUNS,
    steps=STEPS,
    checks=checks,
    digest=digest,
)
