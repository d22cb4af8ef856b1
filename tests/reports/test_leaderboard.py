"""The leaderboard study's rules on hand-made digests: the tally of significant paired differences,
the accuracy verdicts, dominance beyond error, the exactness bound, and the figure's Pareto front;
and the digest of a small trials.csv (panels and quartiles)."""

import csv
import os
import tempfile
import unittest

from experiments import leaderboard as lb
from plots import leaderboard as plot
from reports.core import verdicts


def pair(panel, mean_diff, holm_p):
    return {"panel": panel, "mean_diff": str(mean_diff), "holm_p": str(holm_p)}


def panel_row(spec, error, se, time, ok=100, trials=100, role="algorithm"):
    return {"algorithm": spec, "max_error_mean": str(error), "max_error_se": str(se), "time_us_median": str(time),
            "ok": str(ok), "trials": str(trials), "role": role}


class Rules(unittest.TestCase):
    def test_tally_counts_only_holm_significant_points_by_sign(self):
        rows = [pair("p", -0.1, 0.01), pair("p", -0.1, 0.2), pair("p", 0.05, 0.049), pair("p", 0.0, 1.0)]
        self.assertEqual(lb.tally(rows), (1, 1, 4))

    def test_accuracy_verdicts(self):
        panels = ["a", "b"]
        better = {(lb.BP, "x", "max_error"): {"a": [pair("a", -0.2, 0.001)], "b": [pair("b", 0.01, 0.5)]}}
        self.assertEqual(lb.accuracy_claim("A1", "x", better, panels).verdict, verdicts.AGREES)
        worse = {(lb.BP, "x", "max_error"): {"a": [pair("a", -0.2, 0.001)], "b": [pair("b", 0.01, 0.01)]}}
        claim = lb.accuracy_claim("A1", "x", worse, panels)
        self.assertEqual(claim.verdict, verdicts.DIFFERS)
        self.assertEqual(claim.details, ["BP higher in b (1)"])
        none = {(lb.BP, "x", "max_error"): {"a": [pair("a", -0.2, 0.3)]}}
        self.assertEqual(lb.accuracy_claim("A1", "x", none, panels).verdict, verdicts.WITHIN_ERROR)
        self.assertEqual(lb.accuracy_claim("A1", "y", none, panels).verdict, verdicts.NOT_RUN)

    def test_dominance_needs_both_axes_beyond_error_and_a_complete_competitor(self):
        bp = panel_row("bp", 0.010, 0.001, 5.0)
        others = {"bp": bp,
                  "fast_accurate": panel_row("fast_accurate", 0.001, 0.001, 4.0),   # 0.009 > 2·√2·0.001
                  "fast_close": panel_row("fast_close", 0.008, 0.001, 4.0),        # 0.002 < 2·√2·0.001
                  "slow_accurate": panel_row("slow_accurate", 0.0, 0.0, 50.0),
                  "incomplete": panel_row("incomplete", 0.0, 0.0, 1.0, ok=90),
                  "reference": panel_row("reference", 0.0, 0.0, 1.0, role="reference")}
        self.assertEqual(lb.dominated_beyond_error(bp, others), ["fast_accurate"])

    def test_exactness_bound(self):
        row = {"max_error_max": "3e-15", "ok": "12"}
        self.assertEqual(lb.exactness_claim("X", "s", row, "max_error_max", "r").verdict, verdicts.AGREES)
        row["max_error_max"] = "2e-9"
        self.assertEqual(lb.exactness_claim("X", "s", row, "max_error_max", "r").verdict, verdicts.DIFFERS)
        self.assertEqual(lb.exactness_claim("X", "s", None, "max_error_max", "r").verdict, verdicts.NOT_RUN)

    def test_figure_pareto_front(self):
        points = [(1.0, 0.5, "a"), (2.0, 0.6, "b"), (3.0, 0.1, "c"), (0.5, 0.9, "d"), (3.0, 0.2, "e")]
        self.assertEqual([p[2] for p in plot.pareto_front(points)], ["d", "a", "c"])


class Digest(unittest.TestCase):
    def test_panel_rows_from_trials(self):
        header = ["point", "pd", "lambda_fa", "r", "trial", "algorithm", "status", "max_error", "time_us", "converged"]
        rows = []
        for t, (error, time) in enumerate([(0.1, 10.0), (0.3, 30.0), (0.2, 20.0), (0.4, 40.0)]):
            rows.append(["0", "0.6", "0.01", "1", str(t), "bp", "ok", str(error), str(time), "1" if t < 2 else "0"])
        rows.append(["1", "0.3", "0.01", "1", "0", "bp", "skipped:memory", "", "", ""])
        rows.append(["0", "0.6", "0.01", "1", "0", "ref", "ok", "0", "5", "1"])
        with tempfile.TemporaryDirectory() as d:
            path = os.path.join(d, "trials.csv")
            with open(path, "w", newline="", encoding="utf-8") as f:
                w = csv.writer(f, lineterminator="\n")
                w.writerow(header)
                w.writerows(rows)
            out = {(r[0], r[1]): dict(zip(lb.PANELS_HEADER, r)) for r in lb.panel_rows(path, lb.exp1_panel, ["ref"])}
        base = out[("exp. 1, baseline", "bp")]
        self.assertEqual((base["trials"], base["ok"], base["role"]), (4, 4, "algorithm"))
        self.assertEqual(float(base["max_error_mean"]), 0.25)
        self.assertEqual(float(base["max_error_median"]), 0.25)
        self.assertEqual(float(base["max_error_max"]), 0.4)
        self.assertEqual(float(base["max_error_max_converged"]), 0.3)
        self.assertEqual(float(base["converged_share"]), 0.5)
        self.assertEqual(float(base["time_us_p25"]), 17.5)
        skipped = out[("exp. 1, Pd = 0.3", "bp")]
        self.assertEqual((skipped["trials"], skipped["ok"], skipped["max_error_mean"]), (1, 0, ""))
        self.assertEqual(out[("exp. 1, baseline", "ref")]["role"], "reference")


if __name__ == "__main__":
    unittest.main()
