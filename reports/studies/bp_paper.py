"""bp-paper: Williams & Lau 2014 (bp-marginal-association), Section V, reproduced with dabench.

The 29 statements of Sec. V-B are the rules of plots/bp_paper_report.py, on the data model of
plots/fig6_paper.py. Each rule is evaluated on the committed summaries and on RESAMPLES parametric
resamples of their means (each mean drawn from N(mean, se²)); its verdict is
verdicts.from_resamples: "agrees" / "differs" only when at least 95 % of the resamples say what the
data say. Besides those: the wall-time target of experiment 1 (issue 3), the BP-vs-exact run, the
JT threshold readings, the references of experiments 2 and 3, the BP iteration maximum (from the
trials digests this module writes) and the kernel benchmarks (results/bp-paper/bench.json).

Everything is read from summary.csv, meta.json, trials-digest.csv and bench.json under the root."""

import contextlib
import csv
import json
import math
import os
import statistics
import sys
from collections import Counter

import numpy as np

from reports.core import data, markdown, stats, verdicts
from reports.core.study import Claim, Run, Step, Study

PLOTS = os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))), "plots")
if PLOTS not in sys.path:
    sys.path.insert(0, PLOTS)
import bp_paper_report as bpr  # noqa: E402  (the 29 rules of Sec. V-B)
import fig6_paper as fp  # noqa: E402  (their data model: the nine panels of Fig. 6)
import jt_threshold_table as jtt  # noqa: E402  (the JT threshold readings table)

FOLDER = "results/bp-paper"
EXP1 = f"{FOLDER}/exp1"
EXP1_1E7 = f"{FOLDER}/exp1-with-mcmcda-1e7"
EXP2 = f"{FOLDER}/exp2"
EXP3 = f"{FOLDER}/exp3"
BP_VS_EXACT = f"{FOLDER}/fig6-exp1-bp-vs-exact"
JT_READING = f"{FOLDER}/jt-threshold-reading"
DIGEST = "trials-digest.csv"  # per (point, algorithm) of a run's trials.csv, which is not committed
DIGESTED = (EXP1, EXP2, EXP3, BP_VS_EXACT)  # the runs whose digests the checks read
BENCH = f"{FOLDER}/bench.json"  # Google Benchmark JSON of the kernels below

# The kernels of the Timing table (bench/single_scan/*.cpp); `taskset -c 0` pins them to one core.
BENCH_FILTER = ("^(fig3_naive/|solve_grid/bp_|solve_grid_ehm/ehm_(2x3_s[03]|3x(5|10|20|30)_s3)(/|$)"
                "|chain_grid/|solve_grid_jt/jt_1e-3_(2x3|3x3)_s[03]$)")

RUNS = [
    Run(EXP1, "./build/dabench run experiments/bp-paper-exp1-timed.ini --force",
        "exp. 1 without MCMCDA 1e7, 1000 trials: the one-hour target"),
    Run(EXP1_1E7, "./build/dabench run experiments/bp-paper-exp1.ini --trials 20 --force",
        "exp. 1 with MCMCDA 1e7, 20 trials"),
    Run(EXP2, "./build/dabench run experiments/bp-paper-exp2.ini --trials 50 --force", "exp. 2: n×3, n = 2…30"),
    Run(EXP3, "./build/dabench run experiments/bp-paper-exp3.ini --trials 20 --force", "exp. 3: n×n, n = 2…10"),
    Run(BP_VS_EXACT, "./build/dabench run experiments/bp-paper-fig6-exp1.ini --force", "BP vs exact, 1000 trials"),
    Run(JT_READING, "./build/dabench run experiments/jt-threshold-reading.ini --force",
        "which JT threshold? 200 trials"),
    Run(BENCH, f"taskset -c 0 ./build/dabench_bench --benchmark_filter='{BENCH_FILTER}' "
               f"--benchmark_out={BENCH} --benchmark_out_format=json", "the Timing table's kernels, one core",
        optional=True),
]

FIG6_INPUTS = (f"--exp1 {EXP1}/summary.csv --exp1-extra {EXP1_1E7}/summary.csv "
               f"--exp2 {EXP2}/summary.csv --exp3 {EXP3}/summary.csv")
STEPS = [
    Step("/usr/bin/python3 reports/digest.py bp-paper", f"{DIGEST} of exp1, exp2, exp3, fig6-exp1-bp-vs-exact"),
    Step(f"/usr/bin/python3 plots/fig6_paper.py {FIG6_INPUTS} --time-stat mean --out {FOLDER}/fig6.png"),
    Step(f"/usr/bin/python3 plots/fig6_paper.py {FIG6_INPUTS} --time-stat median --out {FOLDER}/fig6_median_time.png"),
    Step(f"/usr/bin/python3 plots/fig7.py {EXP1}/summary.csv --where pd=0.9 --out {FOLDER}/fig7.png"),
]

RESAMPLES = 200  # parametric resamples of the summary means per rule
RESAMPLED = ("max_error_mean", "time_us_mean", "w_star_mean")  # the means the rules read
COUNTED = ("4c", "4f", "8")  # rules on counts only (trials completed, the digests' iteration maximum)

# The paper's side of each Sec. V-B rule: (its words as printed, where). Bullets of Sec. V-B:
# 1 BP, 2 BP vs LMIPDA/BAA, 3 LMIPDA vs BAA, 4 junction tree, 5 MCMCDA, 6 correlation decay.
PAPER = {
    "1a": ("≤ 0.015 in most cases", "Sec. V-B, bullet 1"),
    "1b": ("0.02 – 0.04", "Sec. V-B, bullet 1"),
    "1c": ("little or no deterioration", "Sec. V-B, bullet 1"),
    "2a": ("reduced by a factor of ten in most cases", "Sec. V-B, bullet 2"),
    "2b": ("only a few times", "Sec. V-B, bullet 2"),
    "2c": ("fractions of a millisecond; a little over a millisecond", "Sec. V-B, bullet 2"),
    "3a": ("similar", "Sec. V-B, bullet 3"),
    "3b": ("BAA significantly better", "Sec. V-B, bullet 3"),
    "3c": ("LMIPDA better", "Sec. V-B, bullet 3"),
    "3d": ("comparable", "Sec. V-B, bullet 3"),
    "4a": ("globally worse, often much worse", "Sec. V-B, bullet 4"),
    "4b": ("1-2 orders of magnitude", "Sec. V-B, bullet 4"),
    "4c": ("9 × 9 and 10 × 10 not completed", "Sec. V-B, bullet 4"),
    "4d": ("generally much better", "Sec. V-B, bullet 4"),
    "4e": ("2-4 orders of magnitude", "Sec. V-B, bullet 4"),
    "4f": ("most not completed", "Sec. V-B, bullet 4"),
    "5a": ("generally comparable", "Sec. V-B, bullet 5"),
    "5b": ("progressively worse", "Sec. V-B, bullet 5"),
    "5c": ("similar to or better", "Sec. V-B, bullet 5"),
    "5d": ("2-4 orders of magnitude", "Sec. V-B, bullet 5"),
    "6a": ("BP generally outperforms", "Sec. V-B, bullet 6"),
    "6b": ("BP tighter, CD larger spacings", "Sec. V-B, bullet 6"),
    "6c": ("particularly poorly at Pd = 0.9", "Sec. V-B, bullet 6"),
    "6d": ("slightly faster", "Sec. V-B, bullet 6"),
    "6e": ("2-3 orders of magnitude", "Sec. V-B, bullet 6"),
    "6f": ("4-5 orders of magnitude", "Sec. V-B, bullet 6"),
    "7a": ("around 300", "Sec. V-B, on Fig. 7"),
    "7b": ("minimal well-spaced, maximal close", "Sec. V-B, on Fig. 7"),
    "8": ("87", "Sec. V-B, after Fig. 7"),
}

# Targets of the issues that asked for this study (not the paper's). libDAI's junction tree (the
# paper's tool) is not run here: its times are issue 3's, measured on "this kind of machine".
WALL_TARGET_S = 3600  # issue 3: experiment 1 at 1000 trials (no MCMCDA 1e7) within an hour on 2 cores
WALL_THREADS = 2
BP_2X3_TARGET_US = 1.0  # issue 2: BP median ≤ 1 µs on the 2×3 baseline at spacing 2-3
BP_90_TARGET_US = 100.0  # issue 2: ≤ 100 µs at 90 targets
EHM_2X3_TARGET_US = 20.0  # issue 3: ehm ≤ 20 µs median on the 2×3 baseline
EHM_3XN_TARGET_US = 1e6  # issue 3: ehm ≤ 1 s median on each 3×n grid
MCMCDA_STEP_TARGET_NS = 50.0  # issue 3: ≤ 50 ns per chain step
EHM_OVER_LIBDAI = 100.0  # issue 3: ehm ≥ 100× faster than libDAI's junction tree where both finish
LIBDAI_2X3_MS = "8.7"  # issue 3: libDAI, τ = 1e-3, 2×3 baseline, spacing 0 (median)
LIBDAI_2X3_PD09_MS = "19"  # issue 3: the same at Pd 0.9
LIBDAI_3X3_S = "0.74"  # issue 3: libDAI, τ = 1e-3, 3×3

SHORT = bpr.SHORT


# ----------------------------------------------------------------------------- trials digests


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
    """A run's trials digest with the interface of bp_paper_report.TrialsScan: max_iter and
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


# ----------------------------------------------------------------------------- the Sec. V-B rules


def summary_path(root, folder):
    """The path of a run's summary.csv (DataError if it is missing: fig6_paper would exit)."""
    full = data.path(root, folder, "summary.csv")
    if not os.path.exists(full):
        raise data.DataError(f"{folder}/summary.csv: missing")
    return full


def paper_report(root):
    """bp_paper_report's Report on the committed runs of experiments 1-3 and their digests."""
    paper_data = fp.PaperData(summary_path(root, EXP1), summary_path(root, EXP2), summary_path(root, EXP3),
                              [summary_path(root, EXP1_1E7)])
    return bpr.Report(paper_data, digest_scans(root, paper_data, {1: EXP1, 2: EXP2, 3: EXP3}))


@contextlib.contextmanager
def resampled_means(rows, columns, count, seed=stats.SEED):
    """Gives an iterator of `count` steps; at each step the rows' `columns` hold one parametric
    resample of their means (mean + se·N(0, 1), se from the matching *_se column; a draw below zero
    counts as zero, as these are means of non-negative values). The rows' text is restored after."""
    cells = [(r, c) for c in columns for r in rows if math.isfinite(fp.fnum(r.get(c)))]
    original = [r[c] for r, c in cells]
    ses = [fp.fnum(r.get(c[:-len("mean")] + "se")) for r, c in cells]
    draws = np.maximum(stats.parametric_resamples([fp.fnum(t) for t in original], ses, count, seed), 0.0)

    def steps():
        for draw in draws.tolist():
            for (r, c), v in zip(cells, draw):
                r[c] = repr(v)
            yield

    try:
        yield steps()
    finally:
        for (r, c), text in zip(cells, original):
            r[c] = text


def all_rows(paper_data):
    return [r for s in paper_data.summaries.values() for r in s.rows]


def evaluate_rules(rep):
    """[(id, statement, rule, Result on the data, share of resamples in which the rule agrees)].
    The rules that read no mean (COUNTED) give the same outcome in every resample."""
    point = [(cid, text, rule, fn(rep)) for cid, text, rule, fn in bpr.CLAIMS]
    agree = Counter({cid: RESAMPLES * (res.verdict == bpr.AGREES) for cid, _, _, res in point if cid in COUNTED})
    with resampled_means(all_rows(rep.data), RESAMPLED, RESAMPLES) as steps:
        for _ in steps:
            for cid, _, _, fn in bpr.CLAIMS:
                if cid not in COUNTED:
                    agree[cid] += fn(rep).verdict == bpr.AGREES
    return [(cid, text, rule, res, agree[cid] / RESAMPLES) for cid, text, rule, res in point]


def rule_verdict(result, share):
    """from_resamples on a rule's outcome; a rule the data cannot evaluate is "not run"."""
    if result.verdict not in (bpr.AGREES, bpr.DIFFERS):
        return verdicts.NOT_RUN
    return verdicts.from_resamples(result.verdict == bpr.AGREES, share)


def share_text(share):
    return f"the rule holds in {markdown.percent(share, 0)} of {RESAMPLES} resamples of the means"


def section_vb_claims(report, rep):
    """The 29 rules of Sec. V-B as claims (rule functions in plots/bp_paper_report.py); returns
    their evaluations for the details list."""
    evaluated = evaluate_rules(rep)
    for cid, text, rule, res, share in evaluated:
        verdict = rule_verdict(res, share)
        report.claim(Claim(cid, text, PAPER[cid][1], PAPER[cid][0], res.measured, verdict,
                           f"{rule}; {share_text(share)}" if verdict != verdicts.NOT_RUN else f"{rule}; not run"))
    return evaluated


def rules_and_details(evaluated):
    """Each rule with its resample share, and the per-panel numbers behind it."""
    lines = []
    for cid, text, rule, res, share in evaluated:
        done = share_text(share) if rule_verdict(res, share) != verdicts.NOT_RUN else "not run"
        lines.append(f"- **{cid}** {text}. *Rule:* {rule}; {done}.")
        lines += [f"  - {d}" for d in res.details]
    return "\n".join(lines)


# ----------------------------------------------------------------------------- runs and wall time


def run_sizes(root):
    """Trials per point, points and references of each run, from meta.json."""
    rows = []
    for run in RUNS:
        if run.folder == BENCH:
            continue
        m = data.read_meta(root, run.folder)
        refs = m.get("references") or ([m["reference"]] if m.get("reference") else [])
        rows.append([f"`{run.folder.split('/')[-1]}`", m.get("trials_per_point", "?"), m.get("points", "?"),
                     len(m.get("algorithms", [])), ", ".join(f"`{r}`" for r in refs)])
    return markdown.table(["run", "trials per point", "points", "algorithms", "reference"], rows, "lrrrl")


def wall_time_claim(report, root):
    """Issue 3's target: experiment 1 at 1000 trials without MCMCDA 1e7 within an hour on 2 cores.
    Rule: compare_bound of meta.json's wall_seconds below 3600 s (no sampling error); "not run" if
    the run is not complete, or had fewer trials or more threads than the target's."""
    m = data.read_meta(root, EXP1)
    wall, threads, trials = m.get("wall_seconds"), m.get("threads"), m.get("trials_per_point")
    if m.get("status") != "complete" or wall is None or threads is None or threads > WALL_THREADS or trials != 1000:
        verdict = verdicts.NOT_RUN
    else:
        verdict = verdicts.compare_bound(wall, None, WALL_TARGET_S, holds_below=True)
    report.claim(Claim("T1", "Experiment 1 at 1000 trials (all algorithms but MCMCDA 1e7) finishes within an hour "
                             "on 2 cores", "issue 3", f"≤ {WALL_TARGET_S / 3600:g} h",
                       f"{markdown.duration(wall) if wall is not None else '–'} wall, {threads} threads, "
                       f"{trials} trials per point", verdict,
                       "meta.json's wall_seconds below the target (threads ≤ 2, 1000 trials per point)"))
    fraction = m.get("work_fraction")
    report.value("exp1_work_fraction", markdown.percent(fraction if fraction is not None else math.nan, 1))


def cost_shares(root, top=3):
    """The algorithms with the largest share of experiment 1's solver time: Σ time_us_mean ×
    time_us_count over its points, as a share of all algorithms' (references included)."""
    total = Counter()
    for r in data.read_rows(root, f"{EXP1}/summary.csv"):
        mean, count = data.num(r, "time_us_mean"), data.num(r, "time_us_count")
        if mean is not None and count:
            total[r["algorithm"]] += mean * count
    whole = sum(total.values())
    return ", ".join(f"`{a}` {markdown.percent(t / whole, 0)}" for a, t in total.most_common(top))


def timing_noise(rep):
    """Per experiment, the median over points of BP's mean time / median time: how far the rare
    slow calls (preemption) lift the mean that the paper plots above the median."""
    groups = [("exp. 1", fp.EXP1_KEYS), ("n×3", ["3xn"]), ("n×n", ["nxn"])]
    parts = []
    for name, keys in groups:
        ratios = []
        for p in rep.present(keys, "bp"):
            spec = rep.spec(p, "bp")
            mean, median = rep.col(p, spec, "time_us_mean"), rep.col(p, spec, "time_us_median")
            ratios += [mean[x] / median[x] for x in mean if median.get(x, 0) > 0]
        if ratios:
            parts.append(f"{name} {markdown.sig(statistics.median(ratios), 2)}")
    return ", ".join(parts)


# ----------------------------------------------------------------------------- BP vs exact


def worst_point(rep, panel, spec):
    """(value, se) of the largest max_error_mean of `spec` in a panel."""
    errors = rep.col(panel, spec, "max_error_mean")
    x = max(errors, key=errors.get)
    return errors[x], rep.col(panel, spec, "max_error_se").get(x)


def point_gaps(rep, panel, other, other_panel):
    """|BP's error in experiment 1 − in the other run| at each spacing both hold."""
    a = rep.col(panel, rep.spec(panel, "bp"), "max_error_mean")
    b = other.col(other_panel, other.spec(other_panel, "bp"), "max_error_mean")
    return [abs(a[x] - b[x]) for x in a if x in b]


def converged_text(rep):
    """"N of M" BP runs converged over every panel (converged_mean × converged_count)."""
    done = total = 0.0
    for p in rep.present(fp.EXP1_KEYS, "bp"):
        for r in p.points(rep.spec(p, "bp")).values():
            count = fp.fnum(r.get("converged_count"))
            done += fp.fnum(r.get("converged_mean")) * count
            total += count
    return f"{round(done)} of {round(total)}"


def bp_vs_exact(report, root, rep):
    """R1 (ours): the 1000-trial BP-vs-exact run (same seed; reference exact on weights floored at
    1e-4) gives BP the same worst average max error per Fig. 6 panel as experiment 1 (reference EHM
    on weights thresholded at 1e-4). Rule: compare_value per panel with both runs' standard errors;
    the worst verdict over the panels. Returns the run's Report."""
    other = bpr.Report(fp.PaperData(summary_path(root, BP_VS_EXACT)), {})
    found, ours, theirs, gaps = [], [], [], []
    for p in rep.present(fp.EXP1_KEYS, "bp"):
        q = other.data.by_key.get(p.key)
        if q is None or not other.spec(q, "bp"):
            continue
        a, b = worst_point(rep, p, rep.spec(p, "bp")), worst_point(other, q, other.spec(q, "bp"))
        found.append(verdicts.compare_value(a[0], a[1], b[0], b[1])[0])
        ours.append(f"{SHORT[p.key]} {markdown.pm(*a)}")
        theirs.append(f"{SHORT[p.key]} {markdown.pm(*b)}")
        gaps += point_gaps(rep, p, other, q)
    report.claim(Claim("R1", "The BP-vs-exact run gives BP the same worst average max error per panel as experiment 1",
                       "ours", ", ".join(theirs) or "–", ", ".join(ours) or "–",
                       verdicts.worst(found) if found else verdicts.NOT_RUN,
                       "per panel, compare_value of the two runs' largest BP error (two combined standard errors)"))
    report.value("bp_vs_exact_max_gap", markdown.sig(max(gaps), 2) if gaps else "–")
    report.value("bp_vs_exact_converged", converged_text(other))
    return other


# ----------------------------------------------------------------------------- JT threshold readings


def reading_rules(error, specs):
    """{(threshold_on, τ): the paper's rule for that τ holds} on one error table. τ = 0.1, 4a's rule:
    JT worse than BP at ≥ 90 % of the points it completed and ≥ 3× worse at ≥ 25 %; τ = 0.01 and
    0.001, 4d's rule on the table's column: JT ≤ BP/3 at ≥ half the points where BP's error is
    ≥ 1e-3 (where a 3× gain can be seen)."""
    out = {}
    for on, tau, spec in specs:
        c = jtt.compare(error, spec)
        if tau == 0.1:
            out[(on, tau)] = c["worse"] >= 0.9 * c["done"] and c["worse3"] >= 0.25 * c["done"]
        else:
            out[(on, tau)] = c["better3"] * 2 >= c["hard"]
    return out


def reproducing(rules):
    """The readings under which every τ's rule holds (4a at τ = 0.1 and 4d at 0.01 and 0.001)."""
    readings = sorted({on for on, _ in rules})
    return [on for on in readings if all(held for (o, _), held in rules.items() if o == on)]


def jt_readings(report, root):
    """The readings table (plots/jt_threshold_table.py's counts) and J1 (ours): no reading of the
    threshold makes both 4a's and 4d's rules hold on the six-target panels. J1's verdict and each
    rule's share come from parametric resamples of the run's max_error means."""
    rows = data.read_rows(root, f"{JT_READING}/summary.csv")
    error = jtt.errors(rows)
    ses = jtt.errors([dict(r, max_error_mean=r["max_error_se"]) for r in rows])
    keys = sorted(error)
    specs = jtt.readings(error)
    point = reading_rules(error, specs)
    draws = np.maximum(stats.parametric_resamples([error[k] for k in keys], [ses.get(k, 0.0) for k in keys],
                                                  RESAMPLES), 0.0)
    held = [reading_rules(dict(zip(keys, d.tolist())), specs) for d in draws]
    table = []
    for on, tau, spec in specs:
        c = jtt.compare(error, spec)
        share = sum(h[(on, tau)] for h in held) / RESAMPLES
        table.append([jtt.READINGS[on], f"{tau:g}", f"{c['worse']}/{c['done']}", f"{c['worse3']}/{c['done']}",
                      f"{c['better3']}/{c['hard']}", markdown.sig(c["mean"], 2),
                      f"{'4a' if tau == 0.1 else '4d'}: {'holds' if point[(on, tau)] else 'fails'} "
                      f"({markdown.percent(share, 0)})"])
    report.value("jt_reading_table", markdown.table(
        ["threshold on", "τ", "JT worse than BP", "≥ 3× worse", "≤ BP/3 where BP ≥ 1e-3", "mean error",
         "paper's rule (share of resamples)"], table, "llrrrrl"))
    bp = jtt.compare(error, "bp")
    report.value("jt_reading_points", f"{bp['points']} points; BP's mean error {markdown.sig(bp['mean'], 2)}; "
                                      f"{bp['hard']} points where BP's error ≥ 1e-3")
    for name, on, tau in (("jt_psi_01", "0", 0.1), ("jt_pda_01", "2", 0.1), ("jt_pda_001", "2", 0.01)):
        c = jtt.compare(error, next(s for o, t, s in specs if o == on and t == tau))
        report.value(name, f"{c['worse']} of {c['done']}")
        report.value(name + "_3x", f"{c['worse3']} of {c['done']}")
    none_share = sum(not reproducing(h) for h in held) / RESAMPLES
    report.claim(Claim("J1", "No reading of the JT threshold makes both 4a and 4d hold on the six-target panels",
                       "ours", "–", ", ".join(jtt.READINGS[on] for on in reproducing(point)) or "no reading does",
                       verdicts.from_resamples(not reproducing(point), none_share),
                       f"4a's rule at τ = 0.1, 4d's at 0.01 and 0.001, per reading (the readings table); "
                       f"no reading passes all three in {markdown.percent(none_share, 0)} of {RESAMPLES} resamples"))


# ----------------------------------------------------------------------------- where we differ


def time_text(us):
    """A time in µs as "x µs", "x ms" or "x s" (3 significant digits)."""
    if us is None or not math.isfinite(us):
        return "–"
    if us < 1e3:
        return f"{markdown.sig(us, 2)} µs"
    return f"{markdown.sig(us / 1e3, 2)} ms" if us < 1e6 else f"{markdown.sig(us / 1e6, 2)} s"


def pm_sci(mean, se):
    """markdown.pm, with a power of ten factored out below 1e-3: "(5.0 ± 2.0)·10^-7"."""
    if not math.isfinite(mean) or mean == 0 or abs(mean) >= 1e-3:
        return markdown.pm(mean, se)
    exponent = math.floor(math.log10(abs(mean)))
    scaled = markdown.pm(mean / 10 ** exponent, se / 10 ** exponent if se is not None else None)
    return f"({scaled})·10^{exponent}"


def column_range(rep, keys, fam, column, value=None):
    """(min, max) of a column of one algorithm over the points of some panels."""
    values = [v for p in rep.present(keys, fam, value) for v in rep.col(p, rep.spec(p, fam, value), column).values()]
    return (min(values), max(values)) if values else (math.nan, math.nan)


def at_point(rep, key, fam, x, value=None):
    """(max_error_mean, max_error_se) of an algorithm at one x of a panel."""
    p = rep.data.by_key[key]
    spec = rep.spec(p, fam, value)
    return (rep.col(p, spec, "max_error_mean").get(x, math.nan),
            rep.col(p, spec, "max_error_se").get(x, math.nan)) if spec else (math.nan, math.nan)


def time_values(report, rep):
    """BP's six-target median times and JT τ = 1e-3's on the baseline at spacing 0 (summary)."""
    low, high = column_range(rep, fp.EXP1_KEYS, "bp", "time_us_median")
    report.value("bp_six_median_range", f"{time_text(low)} – {time_text(high)}")
    p = rep.data.by_key["baseline"]
    report.value("jt_1e3_baseline_s0", time_text(rep.col(p, rep.spec(p, "jt", 0.001), "time_us_median").get(0.0)))
    report.value("jt01_below_bp", jt01_below_bp(rep))
    report.value("libdai_2x3", f"{LIBDAI_2X3_MS} ms")
    report.value("libdai_2x3_pd09", f"{LIBDAI_2X3_PD09_MS} ms")
    report.value("libdai_3x3", f"{LIBDAI_3X3_S} s")


def jt01_below_bp(rep):
    """Per panel, the points where JT τ = 0.1's error is not above BP's (against 4a's rule)."""
    parts = []
    for p in rep.present(bpr.ALL, "jt", 0.1):
        below = [x for x, jt, bp in rep.pairs(p, rep.spec(p, "jt", 0.1), rep.spec(p, "bp")) if jt <= bp]
        if below:
            axis = "spacing" if p.exp == 1 else "n"
            parts.append(f"{SHORT[p.key]} {len(below)} ({axis} {min(below):g}–{max(below):g})")
    return ", ".join(parts) or "none"


def lmipda_baa_values(report, rep):
    """Median over panels of LMIPDA/BP and BAA/BP error ratios (2a's numbers) and the panels where
    BAA's error is below LMIPDA's (3a's and 3c's ratios)."""
    for fam in ("lmipda", "baa"):
        ratios = [v for v in bpr.comparator_ratios(rep, fam, bpr.ALL).values() if math.isfinite(v)]
        report.value(f"{fam}_over_bp", markdown.sig(bpr.median(ratios), 2))
    ratios = bpr.pair_ratio(rep, bpr.ALL, "baa", "lmipda")
    report.value("baa_below_lmipda", f"{sum(v < 1 for v in ratios.values())} of {len(ratios)}")
    report.value("baa_over_lmipda_r01", markdown.sig(ratios.get("r=0.1", math.nan), 2))


def mcmcda_values(report, rep):
    """MCMCDA 1e5's error over spacing against BP's (5a's background)."""
    low, high = column_range(rep, ["baseline"], "mcmcda", "max_error_mean", 1e5)
    report.value("mcmc_baseline_range", f"{markdown.sig(low, 2)} – {markdown.sig(high, 2)}")
    low, high = column_range(rep, fp.EXP1_KEYS, "mcmcda", "max_error_mean", 1e5)
    report.value("mcmc_exp1_range", f"{markdown.sig(low, 2)} – {markdown.sig(high, 2)}")
    spacings = sorted(rep.col(rep.data.by_key["baseline"], rep.spec(rep.data.by_key["baseline"], "bp"),
                              "max_error_mean"))
    for name, fam, value, x in (("bp_baseline_first", "bp", None, spacings[0]),
                                ("bp_baseline_last", "bp", None, spacings[-1]),
                                ("mcmc_baseline_first", "mcmcda", 1e5, spacings[0])):
        report.value(name, pm_sci(*at_point(rep, "baseline", fam, x, value)))
    report.value("baseline_first_spacing", f"{spacings[0]:g}")
    report.value("baseline_last_spacing", f"{spacings[-1]:g}")


def ehm_coverage(rep, key):
    """[(grid name, ok, trials, median time)] of EHM (threshold 0) at each point of n×3 or n×n."""
    p = rep.data.by_key[key]
    out = []
    for x, r in p.points("ehm", include_skipped=True).items():
        out.append((rep.grid_name(p, x), int(fp.fnum(r.get("ok"))), int(fp.fnum(r.get("trials"))),
                    fp.fnum(r.get("time_us_median"))))
    return out


def statuses_text(rep, spec, experiments):
    """"`skipped:memory` ×3, …": an algorithm's non-ok statuses in some experiments' digests."""
    missing = [str(e) for e in experiments if e not in rep.trials]
    if missing:
        return f"not run (no trials digest of experiment {', '.join(missing)})"
    found = Counter()
    for e in experiments:
        found.update(rep.trials[e].reasons.get(spec, {}))
    return ", ".join(f"`{s}` ×{c}" for s, c in sorted(found.items())) or "none"


def reference_values(report, rep):
    """Experiments 2 and 3: where EHM (exact) completed, its refusals, and the error of the second
    MCMCDA 1e7 instance (the paper's estimate of its reference error) against BP's."""
    n3 = ehm_coverage(rep, "3xn")
    report.value("ehm_n3_complete", f"{sum(ok == n for _, ok, n, _ in n3)} of {len(n3)}")
    report.value("ehm_n3_slowest_median", time_text(max(t for *_, t in n3)))
    report.value("ehm_nn_coverage", ", ".join(f"{g} {ok}/{n}" for g, ok, n, _ in ehm_coverage(rep, "nxn")))
    report.value("ehm_refusals", statuses_text(rep, "ehm", (2, 3)))
    p = rep.data.by_key["3xn"]
    second, bp = rep.spec(p, "mcmcda", 1e7), rep.spec(p, "bp")
    err, se = rep.col(p, second, "max_error_mean"), rep.col(p, second, "max_error_se")
    first, last = min(err), max(err)
    report.value("mcmc_second_first", f"{markdown.pm(err[first], se[first])} at n = {first:g}")
    report.value("mcmc_second_last", f"{markdown.pm(err[last], se[last])} at n = {last:g}")
    bp_last = rep.col(p, bp, "max_error_mean").get(last, math.nan)
    report.value("bp_n3_last", markdown.pm(bp_last, rep.col(p, bp, "max_error_se").get(last)))
    report.value("mcmc_second_over_bp", markdown.sig(err[last] / bp_last, 2))
    report.value("mcmc_second_spec", f"`{second}`")
    jt = rep.data.by_key["nxn"]
    report.value("jt01_nn_completed", ", ".join(
        f"{rep.grid_name(jt, x)} {int(fp.fnum(r.get('ok')))}/{int(fp.fnum(r.get('trials')))}"
        for x, r in jt.points(rep.spec(jt, "jt", 0.1), include_skipped=True).items()))
    report.value("jt01_nn_statuses", statuses_text(rep, rep.spec(jt, "jt", 0.1), (3,)))


def threshold_effect(report, rep):
    """The reference's threshold: EHM at threshold 0 against EHM at 1e-4, max over experiment 1."""
    values = [v for p in rep.panels(fp.EXP1_KEYS) for v in rep.col(p, "ehm", "max_error_mean").values()]
    report.value("threshold_effect_max", markdown.sig(max(values), 2) if values else "–")


def iteration_values(report, root, rep, other):
    """BP's iteration maximum per run from the trials digests (claim 8's numbers)."""
    scans = {e: s for e, s in rep.trials.items() if math.isfinite(s.max_iter)}
    report.value("iter_max_exp1", f"{scans[1].max_iter:g} over {scans[1].bp_rows} BP runs ({scans[1].max_where})"
                 if 1 in scans else "not run (no trials digest)")
    report.value("iter_max_large", ", ".join(f"experiment {e} {s.max_iter:g}" for e, s in sorted(scans.items())
                                             if e != 1) or "not run (no trials digests)")
    if os.path.exists(data.path(root, BP_VS_EXACT, DIGEST)):
        scan = DigestScan(root, BP_VS_EXACT, {"bp"}, other.data.summaries[1].rows)
        report.value("iter_max_bp_vs_exact", f"{scan.max_iter:g} over {scan.bp_rows} BP runs ({scan.max_where})")
    else:
        report.value("iter_max_bp_vs_exact", "not run (no trials digest)")


# ----------------------------------------------------------------------------- kernel benchmarks


def read_bench(root):
    """(context, {name: benchmark}) of bench.json (names without "/iterations:N"), or None."""
    full = data.path(root, BENCH)
    if not os.path.exists(full):
        return None
    try:
        with open(full, encoding="utf-8") as f:
            doc = json.load(f)
    except (OSError, json.JSONDecodeError) as error:
        raise data.DataError(f"{BENCH}: {error}") from None
    marks = {b["name"].split("/iterations:")[0]: b for b in doc.get("benchmarks", [])
             if b.get("run_type", "iteration") == "iteration" and not b.get("error_occurred")}
    return doc.get("context", {}), marks


def counters(marks, names, key="median_us"):
    """A counter (median_us, ns_per_step, ...) of each benchmark; NaN for one that did not run."""
    return [float(marks.get(name, {}).get(key, math.nan)) for name in names]


def joined(values, fmt=lambda v: markdown.sig(v, 2)):
    return " / ".join(fmt(v) for v in values)


def bound_claim(report, cid, statement, source, target_text, values, target, ours_text, rule, below=True):
    """A target on the worst of some values: compare_bound without sampling error; "not run" unless
    every value was measured."""
    if not all(math.isfinite(v) for v in values):
        report.claim(Claim(cid, statement, source, target_text, f"not run ({ours_text})", verdicts.NOT_RUN, rule))
        return
    worst_value = max(values) if below else min(values)
    report.claim(Claim(cid, statement, source, target_text, ours_text,
                       verdicts.compare_bound(worst_value, None, target, holds_below=below), rule))


# The Timing table's benchmarks (bench/single_scan/*.cpp; BENCH_FILTER selects them).
BP_2X3 = [f"solve_grid/bp_2x3_{s}" for s in ("s0", "s2", "s2_5", "s3")]  # spacing 0, 2, 2.5, 3
FIG3 = [f"fig3_naive/{s}" for s in ("s0", "s2", "s2_5", "s3")]  # Fig. 3 as a plain double loop
BP_LARGE = ["solve_grid/bp_3x10_s3", "solve_grid/bp_3x30_s3"]
EHM_2X3 = [f"solve_grid_ehm/ehm_2x3_{s}" for s in ("s0", "s3")]
EHM_3XN = [f"solve_grid_ehm/ehm_{g}_s3" for g in ("3x5", "3x10", "3x20", "3x30")]
CHAINS = [f"chain_grid/{c}" for c in ("2x3_s0", "2x3_s3", "3x10_s3")]
JT_1E3 = {"2×3 spacing 0": "solve_grid_jt/jt_1e-3_2x3_s0", "3×3 spacing 3": "solve_grid_jt/jt_1e-3_3x3_s3",
          "3×3 spacing 0": "solve_grid_jt/jt_1e-3_3x3_s0"}


def kernel_claims(report, marks, exp3_ehm_3x3_us):
    """K1-K6: issue 2's and 3's targets on the benchmark medians (bench.json), each by
    compare_bound on the worst of its values (a benchmark median has no sampling error here)."""
    bp = counters(marks, BP_2X3[1:])
    bound_claim(report, "K1", "BP's median on the 2×3 baseline at spacing 2–3 is at most 1 µs", "issue 2",
                f"≤ {BP_2X3_TARGET_US:g} µs", bp, BP_2X3_TARGET_US, f"{joined(bp)} µs",
                "compare_bound: the largest of the spacing 2, 2.5 and 3 medians ≤ 1 µs")
    big = counters(marks, BP_LARGE[1:])
    bound_claim(report, "K2", "BP's median at 90 targets (3×30) is at most 100 µs", "issue 2",
                f"≤ {BP_90_TARGET_US:g} µs", big, BP_90_TARGET_US, f"{joined(big)} µs",
                "compare_bound: the 3×30 median ≤ 100 µs")
    ehm = counters(marks, EHM_2X3)
    bound_claim(report, "K3", "EHM's median on the 2×3 baseline is at most 20 µs", "issue 3",
                f"≤ {EHM_2X3_TARGET_US:g} µs", ehm, EHM_2X3_TARGET_US, f"{joined(ehm)} µs",
                "compare_bound: the larger of the spacing 0 and 3 medians ≤ 20 µs")
    large = counters(marks, EHM_3XN)
    bound_claim(report, "K4", "EHM's median on each 3×n grid is at most 1 s", "issue 3", "≤ 1 s", large,
                EHM_3XN_TARGET_US, joined(large, time_text),
                "compare_bound: the largest of the 3×5 … 3×30 medians ≤ 1 s")
    steps = counters(marks, CHAINS, "ns_per_step")
    bound_claim(report, "K5", "An MCMCDA chain step costs at most 50 ns", "issue 3",
                f"≤ {MCMCDA_STEP_TARGET_NS:g} ns", steps, MCMCDA_STEP_TARGET_NS, f"{joined(steps)} ns",
                "compare_bound: the largest ns_per_step of the three chains ≤ 50 ns")
    ratios = [float(LIBDAI_2X3_MS) * 1e3 / counters(marks, EHM_2X3[:1])[0], float(LIBDAI_3X3_S) * 1e6 / exp3_ehm_3x3_us]
    bound_claim(report, "K6", "EHM is at least 100× faster than libDAI's junction tree where both finish", "issue 3",
                f"≥ {EHM_OVER_LIBDAI:g}× (libDAI {LIBDAI_2X3_MS} ms on 2×3, {LIBDAI_3X3_S} s on 3×3)", ratios,
                EHM_OVER_LIBDAI, f"{joined(ratios)}× (2×3: benchmark; 3×3: median of experiment 3)",
                "compare_bound: the smaller of the two ratios ≥ 100; libDAI's times are issue 3's, not run here",
                below=False)


def jt_row(marks, label, name, yardstick):
    median, states, skipped = (counters(marks, [name], key)[0] for key in ("median_us", "states", "skipped"))
    return [f"`jt` τ = 1e-3, {label}", f"{time_text(median)} ({markdown.sig(states, 2)} clique states; "
            f"{markdown.percent(skipped, 0)} of the pool over the memory budget)", yardstick]


def kernel_table(marks):
    """The Timing table: each benchmark's median over its fixed pool (ns_per_step for the chains)."""
    slowest = max(counters(marks, EHM_3XN, "max_us"))
    rows = [
        ["`bp` 2×3 baseline, spacing 0 / 2 / 2.5 / 3", f"{joined(counters(marks, BP_2X3))} µs",
         f"K1; Fig. 3 as a plain loop: {joined(counters(marks, FIG3))} µs"],
        ["`bp` 3×10, 3×30 at spacing 3", f"{joined(counters(marks, BP_LARGE))} µs", "K2"],
        ["`ehm` 2×3 baseline, spacing 0 / 3", f"{joined(counters(marks, EHM_2X3))} µs", "K3, K6"],
        ["`ehm` 3×5, 3×10, 3×20, 3×30 at spacing 3",
         f"{joined(counters(marks, EHM_3XN), time_text)} (slowest instance {time_text(slowest)})", "K4"],
        ["`mcmcda` chain step, 2×3 spacing 0 / 2×3 spacing 3 / 3×10",
         f"{joined(counters(marks, CHAINS, 'ns_per_step'))} ns", "K5"],
    ]
    yardsticks = [f"libDAI {LIBDAI_2X3_MS} ms (issue 3)", f"libDAI {LIBDAI_3X3_S} s on 3×3 (issue 3)", ""]
    rows += [jt_row(marks, label, name, y) for (label, name), y in zip(JT_1E3.items(), yardsticks)]
    return markdown.table(["kernel", "median", "target / yardstick"], rows)


def bench_values(report, rep):
    """The Timing section: bench.json's table, provenance and K1-K6 ("not run" without it)."""
    ehm_3x3 = next((t for g, ok, n, t in ehm_coverage(rep, "nxn") if g == "3×3"), math.nan)
    found = read_bench(report.root)
    context, marks = found if found else ({}, {})
    kernel_claims(report, marks, ehm_3x3)
    if found is None:
        report.value("kernel_table", f"not run (`{BENCH}` is not committed)")
        report.value("bench_provenance", "not run")
        report.value("chain_edges", "not measured: no `bench.json`")
        return
    report.value("kernel_table", kernel_table(marks))
    state = {"false": "clean", "true": "**modified**"}.get(str(context.get("source_modified")), "unknown")
    report.value("bench_provenance", f"commit `{str(context.get('git_commit', '?'))[:10]}` ({state}), "
                                     f"{str(context.get('date', ''))[:10]}, {context.get('num_cpus', '?')} CPUs")
    edges = counters(marks, CHAINS[:1], "mean_edges")[0]
    report.value("chain_edges", f"{markdown.sig(edges, 2)} on average in the 2×3 benchmark pool at spacing 0")


# ----------------------------------------------------------------------------- the study


def claims_table(report, ids, side):
    """Report.claims_table with the "paper" column named `side` (our own statements compare with
    a target or another run, not with the paper)."""
    header, rule, *rows = report.claims_table(ids).split("\n")
    return "\n".join([header.replace("| paper |", f"| {side} |"), rule] + rows)


def checks(report):
    root = report.root
    rep = paper_report(root)
    evaluated = section_vb_claims(report, rep)
    ids = [cid for cid, *_ in evaluated]
    report.value("resamples", str(RESAMPLES))
    report.value("vb_claims", report.claims_table(ids))
    report.value("vb_counts", report.verdict_counts(ids))
    report.value("vb_details", rules_and_details(evaluated))
    report.value("run_sizes", run_sizes(root))
    wall_time_claim(report, root)
    report.value("exp1_cost_shares", cost_shares(root))
    report.value("timing_noise", timing_noise(rep))
    other = bp_vs_exact(report, root, rep)
    jt_readings(report, root)
    time_values(report, rep)
    lmipda_baa_values(report, rep)
    mcmcda_values(report, rep)
    reference_values(report, rep)
    threshold_effect(report, rep)
    iteration_values(report, root, rep, other)
    bench_values(report, rep)
    for name, ids in (("ours_claims", ["T1", "R1", "J1"]), ("kernel_claims", ["K1", "K2", "K3", "K4", "K5", "K6"])):
        report.value(name, claims_table(report, ids, "target, or the other side"))
        report.value(f"{name}_rules", report.rules_list(ids))


STUDY = Study(
    name="bp-paper",
    report=f"{FOLDER}/REPORT.md",
    template="reports/templates/bp-paper.md",
    runs=RUNS,
    steps=STEPS,
    checks=checks,
    digest=digest,
)
