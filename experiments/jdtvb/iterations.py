"""JDT-VB's VB iterations: how many runs meet the free-energy stopping rule, the free energy B
over the iterations and at convergence (F1: the literal configuration's B is finite and of the
default's order), and Fig. 7: the metrics at r = 0 and after the last iteration (P9)."""

from reports.core import data, markdown, stats, verdicts
from reports.core.study import Claim
from experiments.jdtvb.runs import FOLDER, LITERAL, LITERAL_MEAN
from experiments.jdtvb.table4 import comparisons_claim
from experiments.jdtvb.tracking_runs import METRICS, SETTINGS, setting_label, short_label

DECIMALS = {"nvt": 2, "tpd": 3, "nft": 2, "ttl_scans": 2, "aee_range_km": 2, "aee_bearing_mrad": 2, "mospa_km": 1}


def convergence(report, run):
    """Share of JDT-VB runs that met the free-energy stopping rule (|ΔB| < 1e-5) within r_max = 20,
    and their mean iterations, per setting (trials.csv: converged, iterations)."""
    shares, iterations = [], []
    for setting in SETTINGS:
        c = run.series(setting, "jdt-vb", "converged")
        shares.append(f"{100 * sum(c.values()) / len(c):.0f}")
        iterations.append(markdown.sig(run.mean(setting, "jdt-vb", "iterations")[0], 2))
    report.value("converged_percent", " / ".join(shares) + " %")
    report.value("mean_iterations", " / ".join(iterations))


def free_energy(report, root, run, readings):
    """B over the VB iterations of every Fig. 7 run (iterations.csv): the largest relative decrease
    between successive iterations; B at convergence of the default and the literal configurations
    (trials.csv), and F1: the literal B is finite and of the default's order."""
    rows = data.read_rows(root, f"{FOLDER}/fig7/iterations.csv")
    by_run = {}
    for r in rows:
        if r["free_energy"] != "":
            by_run.setdefault((r["point"], r["trial"], r["algorithm"]), []).append(
                (int(r["iteration"]), float(r["free_energy"])))
    decreases, largest = 0, 0.0
    for history in by_run.values():
        history.sort()
        for (_, b0), (_, b1) in zip(history, history[1:]):
            if b1 < b0:
                decreases += 1
                largest = max(largest, (b0 - b1) / abs(b0))
    report.value("b_runs", f"{len(by_run)}")
    report.value("b_decreases", f"{decreases}")
    report.value("b_largest_relative_decrease", "none" if decreases == 0 else f"{largest:.1e}")
    medians, counts = {}, {}
    for tracker, source, name in (("jdt-vb", run, "default"), (LITERAL, run, "literal"),
                                  (LITERAL_MEAN, readings, "literal_mean")):
        values = [v for s in SETTINGS for v in source.series(s, tracker, "free_energy").values()]
        medians[name] = stats.percentile(values, 50)
        counts[name] = (len(values), sum(source.runs(s, tracker)[0] for s in SETTINGS))
        report.value(f"b_median.{name}", f"{medians[name]:.2e}")
    ratio = medians["literal"] / medians["default"]
    finite, total = counts["literal"]
    report.claim(Claim("F1", "the literal configuration's B (eq 32 fusion with the B-maximising coupling) is finite "
                       "and of the order of the default's", "ours", "–",
                       f"median {medians['literal']:.2e} vs {medians['default']:.2e} (ratio {ratio:.2f}); finite in "
                       f"{finite} of {total} runs",
                       verdicts.AGREES if finite == total and 0.1 <= ratio <= 10 else verdicts.DIFFERS,
                       "B finite in every completed run and the ratio of the medians within [0.1, 10]"))
    return by_run


def fig7_section(report, by_run_b, root):
    """Fig. 7: each metric at r = 0 (the sequential pass) and after the last iteration, mean over
    the runs (a run that converged keeps its final tracks), and the paper's "performance improves
    with the iterations" per metric, paired per run."""
    rows = data.read_rows(root, f"{FOLDER}/fig7/iterations.csv")
    first, last = {}, {}
    for r in rows:
        key = ((float(r["pd"]), float(r["clutter"])), int(r["trial"]))
        it = int(r["iteration"])
        if it == 0:
            first[key] = r
        if key not in last or it > int(last[key]["iteration"]):
            last[key] = r
    table_rows, items = [], []
    for setting in SETTINGS:
        keys = sorted(k for k in first if k[0] == setting)
        iterations = stats.mean_se(int(last[k]["iteration"]) for k in keys)[0]
        row = [setting_label(setting), markdown.sig(iterations, 2)]
        for metric, heading, up in METRICS:
            a = {k[1]: data.number(first[k][metric]) for k in keys}
            b = {k[1]: data.number(last[k][metric]) for k in keys}
            ma = stats.mean_se(v for v in a.values() if v is not None)[0]
            mb = stats.mean_se(v for v in b.values() if v is not None)[0]
            row.append(f"{markdown.fixed(ma, DECIMALS[metric])} → {markdown.fixed(mb, DECIMALS[metric])}")
            d, se, _ = stats.paired({k: v for k, v in b.items() if v is not None},
                                    {k: v for k, v in a.items() if v is not None})
            items.append((f"{heading}, {short_label(setting)}", verdicts.compare_direction(d, se, +1 if up else -1),
                          d, se))
        table_rows.append(row)
    report.value("fig7_table", markdown.table(["setting", "mean iterations"] + [h for _, h, _ in METRICS], table_rows))
    comparisons_claim(report, "P9", "JDT-VB's performance improves with the VB iterations", "Fig. 7", items, None,
                      "paired final minus r = 0 per run, every metric and setting; worst part", paper_text="qualitative")
