"""The bp-paper study's checks on a copy of the committed data: a tampered summary number changes
the Sec. V-B verdict it feeds, the wall-time target follows meta.json, the kernel targets follow
bench.json ("not run" without it), and the trials digest counts what trials.csv holds."""

import json
import os
import shutil
import tempfile
import unittest

from reports import render
from reports.core import study, verdicts
from experiments import bp_paper
from tests.reports.tampering import rewrite_csv

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
DATA = (".csv", ".json")  # what the checks read: summaries, digests, meta.json, bench.json




def pd09_bp_far_off(row):
    """BP's error at Pd 0.9 of experiment 1 ten times the paper's 0.02-0.04 range, without error."""
    if row["algorithm"] == "bp" and row["pd"] == "0.9":
        row["max_error_mean"], row["max_error_se"] = "0.4", "0"


class CopyOfTheData(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="bp-paper-test-")
        shutil.copytree(os.path.join(REPO, "experiments"), os.path.join(self.root, "experiments"))
        shutil.copytree(os.path.join(REPO, bp_paper.FOLDER), os.path.join(self.root, bp_paper.FOLDER),
                        ignore=lambda d, names: [n for n in names if os.path.isfile(os.path.join(d, n))
                                                 and not n.endswith(DATA)])

    def tearDown(self):
        shutil.rmtree(self.root)

    def path(self, *parts):
        return os.path.join(self.root, *parts)

    def report(self):
        return study.Report(bp_paper.STUDY, self.root)

    def test_a_tampered_summary_changes_the_verdict_it_feeds(self):
        """1b (BP's errors at Pd 0.9 and r 0.1 lie in 0.02-0.04) differs once Pd 0.9's are 0.4."""
        rep = self.report()
        bp_paper.section_vb_claims(rep, bp_paper.paper_report(self.root))
        self.assertNotEqual(rep.values["claim.1b.verdict"], verdicts.DIFFERS)
        rewrite_csv(self.path(bp_paper.EXP1, "summary.csv"), pd09_bp_far_off)
        text, _ = render.build(bp_paper.STUDY, self.root)
        row = next(line for line in text.splitlines() if line.startswith("| 1b |"))
        self.assertTrue(row.endswith("| **differs** |"), row)

    def test_the_wall_time_target_follows_meta_json(self):
        meta_path = self.path(bp_paper.EXP1, "meta.json")
        with open(meta_path, encoding="utf-8") as f:
            meta = json.load(f)
        for wall, threads, expected in ((1800.0, 2, verdicts.AGREES), (5400.0, 2, verdicts.DIFFERS),
                                        (1800.0, 16, verdicts.NOT_RUN)):
            meta.update(wall_seconds=wall, threads=threads, trials_per_point=1000)
            with open(meta_path, "w", encoding="utf-8") as f:
                json.dump(meta, f)
            rep = self.report()
            bp_paper.wall_time_claim(rep, self.root)
            self.assertEqual(rep.values["claim.T1.verdict"], expected, (wall, threads))

    def bench(self, bp_median_us):
        """A bench.json holding the Timing table's benchmarks, BP's 2×3 medians set to bp_median_us."""
        names = (bp_paper.BP_2X3 + bp_paper.FIG3 + bp_paper.BP_LARGE + bp_paper.EHM_2X3 + bp_paper.CHAINS
                 + [f"{n}/iterations:1" for n in bp_paper.EHM_3XN] + list(bp_paper.JT_1E3.values()))
        marks = [{"name": n, "run_type": "iteration", "median_us": bp_median_us if "bp_2x3" in n else 5.0,
                  "max_us": 9.0, "ns_per_step": 21.0, "mean_edges": 26.0, "states": 1e4, "skipped": 0.0}
                 for n in names]
        with open(self.path(bp_paper.BENCH), "w", encoding="utf-8") as f:
            json.dump({"context": {"git_commit": "0123456789abcdef", "source_modified": "false",
                                   "date": "2026-12-04T00:00:00+00:00", "num_cpus": 2}, "benchmarks": marks}, f)

    def test_the_kernel_targets_follow_bench_json(self):
        rep = self.report()
        bp_paper.bench_values(rep, bp_paper.paper_report(self.root))
        if not os.path.exists(os.path.join(REPO, bp_paper.BENCH)):
            self.assertEqual(rep.values["claim.K1.verdict"], verdicts.NOT_RUN)
        for median, expected in ((0.8, verdicts.AGREES), (1.2, verdicts.DIFFERS)):
            self.bench(median)
            rep = self.report()
            bp_paper.bench_values(rep, bp_paper.paper_report(self.root))
            self.assertEqual(rep.values["claim.K1.verdict"], expected, median)
            self.assertIn("`bp` 2×3 baseline", rep.values["kernel_table"])


class TrialsDigest(unittest.TestCase):
    def test_the_digest_counts_rows_statuses_and_the_first_largest_iteration_count(self):
        rows = [("0", "bp", "0", "ok", "15"), ("0", "bp", "1", "ok", "40"), ("0", "bp", "2", "ok", "40"),
                ("0", "bp", "3", "failed:nan", ""), ("0", "jt:threshold=0.1", "0", "skipped:memory", ""),
                ("0", "jt:threshold=0.1", "1", "ok", "0"), ("1", "bp", "0", "ok", "90")]
        with tempfile.TemporaryDirectory() as root:
            folder = os.path.join(root, bp_paper.EXP1)
            os.makedirs(folder)
            with open(os.path.join(folder, "trials.csv"), "w", encoding="utf-8") as f:
                f.write("point,trial,algorithm,status,iterations\n")
                f.writelines(f"{p},{t},{a},{s},{i}\n" for p, a, t, s, i in rows)
                f.write("1,1,bp,ok\n")  # a cut last line is not counted
            self.assertEqual(bp_paper.digest(root), [os.path.join(folder, bp_paper.DIGEST)])
            with open(os.path.join(folder, bp_paper.DIGEST), encoding="utf-8") as f:
                self.assertEqual(f.read().splitlines(), [
                    "point,algorithm,rows,statuses,iterations_max,iterations_max_trial",
                    "0,bp,4,failed:nan=1;ok=3,40,1",
                    "0,jt:threshold=0.1,2,ok=1;skipped:memory=1,0,1",
                    "1,bp,1,ok=1,90,0"])
            scan = bp_paper.DigestScan(root, bp_paper.EXP1, {"bp"}, [{"point": "1", "spacing": "0", "pd": "0.9"}])
            self.assertEqual((scan.rows, scan.bp_rows, scan.max_iter), (7, 5, 90.0))
            self.assertEqual(scan.max_where, "point 1, spacing=0, pd=0.9, trial 0")
            self.assertEqual(scan.reasons, {"bp": {"failed:nan": 1}, "jt:threshold=0.1": {"skipped:memory": 1}})


if __name__ == "__main__":
    unittest.main()
