"""TBD's runtime: the supplement's Fig. 4 (mean runtime per step against the number of objects)
against the recorded run (R1: linear in the objects; R2: L = 2 against L = 1) and the one-core
benchmark of results/tbd/bench.json (R2-bench, and R3: the issue's target for TBD-BP)."""

import math

import numpy as np

from reports.core import data, markdown, stats, verdicts
from reports.core.study import Claim
from reports.core import bench_json
from experiments.tbd.data import ms
from experiments.tbd.runs import BENCH, BP, RUNTIME

# Supplement Fig. 4: mean runtime per step (s) over 400 runs at 1, 3, ..., 11 objects, read off the
# bars (docs/models/track-before-detect.md §5.3, 600 dpi).
FIG4_OBJECTS = (1, 3, 5, 7, 9, 11)
FIG4_SECONDS = {1: ("0.069", "0.226", "0.442", "0.675", "0.919", "1.199"),
                2: ("0.097", "0.336", "0.650", "1.010", "1.390", "1.801")}
FIG4_READING_SE = 0.005  # s: about three pixels of a bar's top at 600 dpi
FIG4_RUNS = 400  # supplement Sec. 3: "averaged over all 50 time steps and 400 simulation runs"
# The runtime target for TBD-BP, L = 2, on one core (bench/tbd/bench_tbd.cpp).
TARGET_PER_OBJECT_S = 0.005
TARGET_NEW_POS_S = 0.005


def leading_coefficient(n, degree):
    """The row vector c with c @ y = the leading coefficient of the least-squares polynomial of
    this degree through (n, y): the fits are linear in y, so resampled y fit in one product."""
    return np.linalg.pinv(np.vander(np.asarray(n, dtype=float), degree + 1))[0]


def runtime_statistics(n, y1, y2):
    """Per-object slope of each L, its bend (the quadratic coefficient of a least-squares parabola
    over the line's slope, 1/object: how much the curve bends, independent of its scale) and the
    slope ratio L = 2 / L = 1; y1, y2: [..., points] arrays (a row per resample)."""
    line, parabola = leading_coefficient(n, 1), leading_coefficient(n, 2)
    slope1, slope2 = np.asarray(y1) @ line, np.asarray(y2) @ line
    return {"slope1": slope1, "slope2": slope2, "bend1": (np.asarray(y1) @ parabola) / slope1,
            "bend2": (np.asarray(y2) @ parabola) / slope2, "ratio": slope2 / slope1}


def recorded_runtime(d):
    """The runtime statistics of the recorded run's mean step times (s) per point, with SEs from
    a paired bootstrap over the runs of each point (the same runs resampled for L = 1 and 2;
    stats.SEED): (values, SEs, runs per point), or None without runs.csv."""
    objects = {int(r["point"]): int(r["objects"]) for r in d.summary(RUNTIME)}
    if sorted(objects.values()) != list(FIG4_OBJECTS):
        raise data.DataError(f"{RUNTIME}/summary.csv: not the points {FIG4_OBJECTS} of tbd/runtime.ini")
    per_point = []
    for point in sorted(objects, key=objects.get):
        t1, t2 = (d.runs(RUNTIME, BP[L], "step_time_us", point) for L in (1, 2))
        if t1 is None or t2 is None:
            return None
        trials = sorted(set(t1) & set(t2))
        per_point.append((1e-6 * np.array([t1[t] for t in trials]), 1e-6 * np.array([t2[t] for t in trials])))
    n = np.array(FIG4_OBJECTS, dtype=float)
    value = {k: float(v) for k, v in runtime_statistics(
        n, np.array([a.mean() for a, _ in per_point]), np.array([b.mean() for _, b in per_point])).items()}
    rng = np.random.Generator(np.random.PCG64(stats.SEED))
    y1, y2 = np.empty((stats.RESAMPLES, len(n))), np.empty((stats.RESAMPLES, len(n)))
    for r in range(stats.RESAMPLES):
        for i, (a, b) in enumerate(per_point):
            pick = rng.integers(0, len(a), len(a))
            y1[r, i], y2[r, i] = a[pick].mean(), b[pick].mean()
    se = {k: float(np.std(v, ddof=1)) for k, v in runtime_statistics(n, y1, y2).items()}
    return value, se, min(len(a) for a, _ in per_point)


def paper_runtime(ours_se, ours_runs):
    """The same statistics of the Fig. 4 readings, with SEs from the reading error (readings
    resampled with stats.parametric_resamples) and the paper's sampling error, estimated from ours
    (ours × sqrt(our runs / 400)), combined."""
    n = np.array(FIG4_OBJECTS, dtype=float)
    y = {L: np.array([float(v) for v in FIG4_SECONDS[L]]) for L in (1, 2)}
    value = {k: float(v) for k, v in runtime_statistics(n, y[1], y[2]).items()}
    draws = stats.parametric_resamples(np.concatenate([y[1], y[2]]), [FIG4_READING_SE] * (2 * len(n)), stats.RESAMPLES)
    resampled = runtime_statistics(n, draws[:, :len(n)], draws[:, len(n):])
    se = {}
    for k in value:
        reading = float(np.std(resampled[k], ddof=1))
        se[k] = verdicts.combined_se(reading, ours_se.get(k, math.nan) * math.sqrt(ours_runs / FIG4_RUNS))
    return value, se


def read_bench(root):
    """bench.json (Google Benchmark JSON) as ({(L, objects): [s_per_step of each repetition]},
    context), or None when not committed."""
    doc = bench_json.read(root, BENCH)
    if doc is None:
        return None
    times = {}
    for b in doc.get("benchmarks", []):
        if b.get("run_type", "iteration") != "iteration" or not b["name"].startswith("tbd_bp_l"):
            continue
        family, _, arg = b["run_name"].partition("/objects:")
        times.setdefault((int(family[-1]), int(arg)), []).append(float(b["s_per_step"]))
    return times, doc.get("context", {})


def bench_statistics(times):
    """Per L: median over repetitions of s_per_step per point (SE: s.d. over repetitions / sqrt(n));
    the new POs' cost (0 objects), the least-squares slope over 1..11 objects with its propagated SE."""
    out = {}
    for L in (1, 2):
        points = sorted(o for (l, o) in times if l == L)
        med = {o: float(np.median(times[(L, o)])) for o in points}
        se = {o: stats.sd(times[(L, o)]) / math.sqrt(len(times[(L, o)])) for o in points}
        objects = np.array([o for o in points if o > 0], dtype=float)
        weights = (objects - objects.mean()) / np.sum((objects - objects.mean()) ** 2)
        slope = float(np.sum(weights * np.array([med[int(o)] for o in objects])))
        slope_se = math.sqrt(float(np.sum(weights ** 2 * np.array([se[int(o)] ** 2 for o in objects]))))
        out[L] = {"new": (med.get(0, math.nan), se.get(0, math.nan)), "slope": (slope, slope_se),
                  "top": (med[points[-1]], se[points[-1]]), "top_objects": points[-1]}
    return out


def check_runtime(report, d):
    recorded = recorded_runtime(d)
    ours, ours_se, runs = recorded if recorded else ({}, {}, 0)
    paper, paper_se = paper_runtime(ours_se, runs)
    get = lambda k: (ours.get(k, math.nan), ours_se.get(k, math.nan))  # noqa: E731 (NaN: not run)
    # R1: linear in the number of objects.
    value_parts, direction_parts = [], []
    for L in (1, 2):
        bend, bend_se = get(f"bend{L}")
        value_parts.append(verdicts.compare_value(bend, bend_se, paper[f"bend{L}"], paper_se[f"bend{L}"])[0])
        direction_parts.append(verdicts.compare_direction(*get(f"slope{L}"), +1))
    report.claim(Claim(
        "R1", "the runtime per step increases linearly with the number of objects", "supplement Sec. 3, Fig. 4",
        "bend " + ", ".join(f"L = {L}: {markdown.fixed(paper[f'bend{L}'], 3)}" for L in (1, 2)),
        "bend " + ", ".join(f"L = {L}: {markdown.pm(*get(f'bend{L}'))}" for L in (1, 2)),
        verdicts.value_and_direction(verdicts.worst(value_parts), verdicts.worst(direction_parts)),
        "per L, the bend (quadratic coefficient of a parabola through the mean step times at 1–11 objects, "
        "over the line's slope, per object) against the same of the Fig. 4 readings (compare_value; ours: "
        "paired bootstrap SE over runs; the paper's: reading error and ours × √(runs/400)); direction: slope > 0"))
    # R2: the cost of L = 2 against L = 1.
    ratio, ratio_se = get("ratio")
    paper_ratio = markdown.fixed(paper["ratio"], 2)
    value = verdicts.compare_value(ratio, ratio_se, paper["ratio"], paper_se["ratio"], paper_ratio)[0]
    report.claim(Claim(
        "R2", "L = 2 costs about 1.5 times L = 1 per object (slope ratio)", "supplement Fig. 4 (read off)",
        paper_ratio, markdown.pm(ratio, ratio_se),
        verdicts.value_and_direction(value, verdicts.compare_bound(ratio, ratio_se, 1.0, holds_below=False)),
        "slope ratio L = 2 / L = 1 of the recorded run (paired bootstrap SE) against that of the Fig. 4 "
        "readings (compare_value); direction: ratio > 1"))
    bench = read_bench(report.root)
    b = bench_statistics(bench[0]) if bench else None
    bench_rows(report, ours, ours_se, paper, b)
    check_bench(report, b, bench[1] if bench else None, paper)
    report.value("runtime.runs", str(runs) if runs else "–")
    report.value("runtime.claims", report.claims_table(["R1", "R2", "R2-bench", "R3"]))


def bench_rows(report, ours, ours_se, paper, b):
    """The runtime table: per-object slope, the new POs' cost and the L = 2 / L = 1 ratio, from the
    recorded run, the benchmark and the supplement's Fig. 4."""
    get = lambda k: (ours.get(k, math.nan), ours_se.get(k, math.nan))  # noqa: E731
    rows = []
    for L in (1, 2):
        bench_cells = ["not run"] * 3
        if b:
            bench_cells = [ms(*b[L]["new"]), f"{ms(*b[L]['top'])} ({b[L]['top_objects']} objects)", ms(*b[L]["slope"])]
        paper_top = float(FIG4_SECONDS[L][-1])
        rows.append([f"TBD-BP L = {L}", ms(*get(f"slope{L}"))] + bench_cells
                    + [f"{ms(paper[f'slope{L}'])} per object; {markdown.fixed(paper_top, 2)} s at {FIG4_OBJECTS[-1]} objects"])
    bench_ratio = "not run"
    if b:
        bench_ratio = markdown.pm(*ratio_with_se(b[2]["slope"], b[1]["slope"]))
    rows.append(["L = 2 / L = 1 (slopes)", markdown.pm(*get("ratio")), "", "", bench_ratio,
                 markdown.fixed(paper["ratio"], 2)])
    report.value("runtime.table", markdown.table(
        ["", "recorded run: slope per object", "benchmark: 0 objects (the new POs)", "benchmark: most objects",
         "benchmark: slope per object", "supplement Fig. 4 (MATLAB, 400 runs)"], rows, "lrrrrr"))


def ratio_with_se(top, bottom):
    r = top[0] / bottom[0]
    return r, abs(r) * math.hypot(top[1] / top[0], bottom[1] / bottom[0])


def check_bench(report, b, context, paper):
    """R2-bench: the slope ratio of the benchmark against Fig. 4's; R3: the issue's target for
    TBD-BP at L = 2 on one core (<= 5 ms per object and step, <= 5 ms for the new POs)."""
    if b:
        ratio, ratio_se = ratio_with_se(b[2]["slope"], b[1]["slope"])
        value = verdicts.compare_value(ratio, ratio_se, paper["ratio"], None, markdown.fixed(paper["ratio"], 2))[0]
        ratio_verdict = verdicts.value_and_direction(value, verdicts.compare_bound(ratio, ratio_se, 1.0, False))
        target = verdicts.worst([verdicts.compare_bound(*b[2]["slope"], TARGET_PER_OBJECT_S, True),
                                 verdicts.compare_bound(*b[2]["new"], TARGET_NEW_POS_S, True)])
        ours_ratio, ours_target = markdown.pm(ratio, ratio_se), f"{ms(*b[2]['slope'])} per object, {ms(*b[2]['new'])} for the new POs"
        report.value("bench.provenance",
                     f"`{BENCH}`: {bench_json.provenance(context, 'provenance unknown', '?')}, "
                     f"load average {', '.join(markdown.fixed(x, 1) for x in context.get('load_avg', []))}")
    else:
        ratio_verdict = target = verdicts.NOT_RUN
        ours_ratio = ours_target = "not run"
        report.value("bench.provenance", f"`{BENCH}` is not committed: the benchmark rows are not run")
    report.claim(Claim(
        "R2-bench", "L = 2 costs about 1.5 times L = 1 per object (slope ratio; benchmark, one core)",
        "supplement Fig. 4 (read off)", markdown.fixed(paper["ratio"], 2), ours_ratio, ratio_verdict,
        "benchmark slope ratio (SE propagated from the repetitions) against the Fig. 4 readings' "
        "(compare_value); direction: ratio > 1"))
    report.claim(Claim(
        "R3", "TBD-BP, L = 2, on one core: ≤ 5 ms per object and step plus ≤ 5 ms for the new POs",
        "the issue's target", "≤ 5 ms, ≤ 5 ms", ours_target, target,
        "benchmark slope over 1–11 objects and the 0-object point (median of the repetitions) below "
        "5 ms beyond 2 SE (compare_bound); the worse"))
