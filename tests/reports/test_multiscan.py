"""The multiscan study's checks: its paired trial resamples (and their intervals) are core.stats'
bootstrap, a tampered copy of the committed data changes the verdict it feeds, and the Algorithm 2
cost run is reported once it is committed ("not run" before)."""

import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

import numpy as np

from reports.core import stats
from experiments import multiscan
from tests.reports.tampering import rewrite_csv

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
REPORT = "results/multiscan/REPORT.md"


class PairedResamples(unittest.TestCase):
    def test_trial_resamples_are_the_core_bootstrap(self):
        """trial_resamples draws what core.stats.cluster_bootstrap draws: the same p80 and SE."""
        rng = np.random.Generator(np.random.PCG64(5))
        trial = np.sort(rng.integers(0, 60, 400))
        values = rng.random(400)
        point, draws = multiscan.trial_resamples(trial, values[:, None], lambda c: np.percentile(c, 80, axis=0))
        groups = [values[trial == t] for t in np.unique(trial)]
        value, se, interval = stats.bootstrap_se(groups, lambda v: np.percentile(v, 80))
        self.assertAlmostEqual(point[0], value, places=14)
        self.assertAlmostEqual(float(np.std(draws[:, 0], ddof=1)), se, places=14)
        ours = stats.percentile_interval(draws[:, 0])  # what Figure.interval shows in the tables
        self.assertAlmostEqual(ours[0], interval[0], places=14)
        self.assertAlmostEqual(ours[1], interval[1], places=14)


class CopyOfTheData(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="reports-multiscan-")
        shutil.copytree(os.path.join(REPO, "results", "multiscan"), os.path.join(self.root, "results", "multiscan"))
        shutil.copytree(os.path.join(REPO, "experiments"), os.path.join(self.root, "experiments"))
        shutil.rmtree(self.data("algorithm2-cost"), ignore_errors=True)  # the tests make their own

    def tearDown(self):
        shutil.rmtree(self.root)

    def render(self):
        done = subprocess.run([sys.executable, "-m", "reports.render", "--root", self.root, "multiscan"],
                              capture_output=True, text=True, cwd=REPO)
        self.assertEqual(done.returncode, 0, done.stderr)
        with open(os.path.join(self.root, REPORT), encoding="utf-8") as f:
            return f.read()

    def committed(self):
        """The committed REPORT (in the copy): what a render of the untouched data gives, as the
        reports_current test checks, without rendering it again here."""
        with open(os.path.join(self.root, REPORT), encoding="utf-8") as f:
            return f.read()

    def verdict(self, text, claim_id):
        match = re.search(rf"^\| {re.escape(claim_id)} \|.*\| \*\*([a-z ]+)\*\* \|$", text, re.M)
        self.assertIsNotNone(match, f"claim {claim_id} not in the REPORT")
        return match.group(1)

    def data(self, *parts):
        return os.path.join(self.root, "results", "multiscan", *parts)

    def test_one_residual_above_tolerance_changes_o1(self):
        text = self.committed()
        self.assertEqual(self.verdict(text, "O1"), "agrees")
        self.assertIn("The 10 000-particle run (`results/multiscan/algorithm2-cost`) is not recorded", text)
        first = {}

        def one_residual(row):
            if row["algorithm"] == "cvh" and not first:
                first["done"] = row["residual"] = "2e-12"
        rewrite_csv(self.data("fig5", "trials.csv"), one_residual)
        self.assertEqual(self.verdict(self.render(), "O1"), "differs")

    def test_an_msbp_without_tail_changes_p4(self):
        """MSBP's HPD values moved out of the tail: no share >= 0.9999, against the paper's 12 %."""
        def out_of_tail(row):
            if row["algorithm"] == "msbp":
                row["hpd"] = "0.5"
        rewrite_csv(self.data("fig4", "targets.csv"), out_of_tail)
        self.assertEqual(self.verdict(self.render(), "P4"), "differs")

    def test_one_changed_hpd_value_breaks_o2(self):
        """O2 compares the default (corner) reading's 10 000-particle point with Fig. 4 value by value."""
        self.assertEqual(self.verdict(self.committed(), "O2"), "agrees")
        first = {}

        def one_value(row):
            if row["point"] == "0" and row["algorithm"] == "cv" and not first:
                first["done"] = row["hpd"] = repr(float(row["hpd"]) + 1e-12)
        rewrite_csv(self.data("reading-corner", "targets.csv"), one_value)
        self.assertEqual(self.verdict(self.render(), "O2"), "differs")

    def test_algorithm2_cost_is_reported_once_committed(self):
        """Both solvers' times and their largest HPD difference (absent: "not run", tested above)."""
        folder = self.data("algorithm2-cost")
        os.makedirs(folder)
        shutil.copy(self.data("fig4", "meta.json"), folder)  # a complete run's record
        for name in ("trials.csv", "targets.csv"):
            with open(self.data("fig4", name), newline="", encoding="utf-8") as f:
                reader = csv.DictReader(f)
                header = reader.fieldnames
                rows = [r for r in reader if r["trial"] == "0" and r["algorithm"] == "cvs:gamma=0.95"]
            out = []
            for solver, time_us, iterations, shift in ((multiscan.NEWTON, "1000000", "60", 0.0),
                                                       (multiscan.ALGORITHM2, "3600000000", "50000", 1e-7)):
                for r in rows:
                    r = dict(r, algorithm=solver)
                    if name == "trials.csv":
                        r.update(time_us=time_us, iterations=iterations)
                    else:
                        r["hpd"] = repr(float(r["hpd"]) + shift)
                    out.append(r)
            with open(os.path.join(folder, name), "w", newline="", encoding="utf-8") as f:
                writer = csv.DictWriter(f, header, lineterminator="\n")
                writer.writeheader()
                writer.writerows(out)
        text = self.render()
        self.assertIn("| Algorithm 2 (`solver=pdca`) |", text)
        self.assertIn("Algorithm 2 took 3600 times as long as the Newton solver", text)
        self.assertIn("the largest difference of their HPD values over the trial's targets is 1.0e-07", text)


if __name__ == "__main__":
    unittest.main()
