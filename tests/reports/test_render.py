"""render.py on a copy of the committed data: one tampered number changes the verdict it feeds,
a hand-edited REPORT fails --check, and so does a data edit no REPORT shows (the manifest)."""

import csv
import os
import re
import shutil
import subprocess
import sys
import tempfile
import unittest

from reports import manifest

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def render(root, *args):
    return subprocess.run([sys.executable, "-m", "reports.render", "--root", root, *args], capture_output=True, text=True,
                          cwd=REPO)


def replace_field(path, row_predicate, column, value):
    """Set one field of the first CSV row (after the header) that row_predicate accepts."""
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    header = lines[0].split(",")
    index = header.index(column)
    for i, line in enumerate(lines[1:], start=1):
        fields = line.split(",")
        if line and row_predicate(dict(zip(header, fields))):
            fields[index] = value
            lines[i] = ",".join(fields)
            break
    else:
        raise AssertionError(f"no row of {path} matched")
    with open(path, "w", encoding="utf-8") as f:
        f.write("\n".join(lines))


class CopyOfTheData(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="reports-test-")
        for folder in ("results", "experiments", "tests/timings"):  # what the README's checks read
            shutil.copytree(os.path.join(REPO, folder), os.path.join(self.root, folder))
        shutil.copy(os.path.join(REPO, "README.md"), self.root)

    def tearDown(self):
        shutil.rmtree(self.root)

    def report(self, relpath):
        with open(os.path.join(self.root, relpath), encoding="utf-8") as f:
            return f.read()

    def claim_verdict(self, relpath, claim_id):
        match = re.search(rf"^\| {re.escape(claim_id)} \|.*\| \*\*([a-z ]+)\*\* \|$", self.report(relpath), re.M)
        self.assertIsNotNone(match, f"claim {claim_id} not in {relpath}")
        return match.group(1)

    def test_one_tampered_run_changes_the_verdict_it_feeds(self):
        # JDT-VB's mean TET must stay under 0.37 s per run (claim T1); one run of 1000 s breaks it.
        self.assertEqual(render(self.root, "jdtvb").returncode, 0)
        self.assertEqual(self.claim_verdict("results/jdtvb/REPORT.md", "T1"), "agrees")
        replace_field(os.path.join(self.root, "results/jdtvb/table4/trials.csv"),
                      lambda r: r["algorithm"] == "jdt-vb" and r["pd"] == "0.4", "tet_s", "1000")
        self.assertEqual(render(self.root, "jdtvb").returncode, 0)
        self.assertEqual(self.claim_verdict("results/jdtvb/REPORT.md", "T1"), "differs")

    def test_one_tampered_summary_number_changes_the_readme_verdict(self):
        summary = os.path.join(self.root, "results/quickstart/summary.csv")
        if not os.path.exists(summary):
            self.skipTest("results/quickstart/summary.csv is not committed")
        done = render(self.root, "readme")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("for this panel it agrees", self.report("README.md"))
        replace_field(summary, lambda r: r["algorithm"] == "bp", "max_error_mean", "0.02")
        done = render(self.root, "readme")
        self.assertEqual(done.returncode, 0, done.stderr)
        self.assertIn("for this panel it differs", self.report("README.md"))

    def test_a_hand_edited_number_fails_the_check(self):
        self.assertEqual(render(self.root, "jdtvb").returncode, 0)
        stale = "is not what the committed data give"
        self.assertNotIn(stale, render(self.root, "--check", "jdtvb").stderr)
        path = os.path.join(self.root, "results/jdtvb/REPORT.md")
        text = self.report("results/jdtvb/REPORT.md")
        edited = re.sub(r"\| (\d\.\d\d) ± ", lambda m: f"| {float(m.group(1)) + 0.01:.2f} ± ", text, count=1)
        self.assertNotEqual(edited, text)
        with open(path, "w", encoding="utf-8") as f:
            f.write(edited)
        result = render(self.root, "--check", "jdtvb")
        self.assertEqual(result.returncode, 1)
        self.assertIn(stale, result.stderr)


    def test_data_edits_that_move_no_printed_digit_fail_the_check(self):
        """The tampers of issue 50 that no REPORT shows: an MSBP HPD value of Fig. 4 × 0.9 and a
        Table IV summary mean in its last digits. The manifest (results/SHA256SUMS) names the file;
        the REPORTs themselves stay as they were."""
        manifest = "not the file results/SHA256SUMS lists"
        self.assertNotIn(manifest, render(self.root, "--check", "jdtvb").stderr)
        targets = os.path.join(self.root, "results/multiscan/fig4/targets.csv")
        with open(targets, encoding="utf-8") as f:
            hpd = next(r["hpd"] for r in csv.DictReader(f) if r["algorithm"] == "msbp")
        replace_field(targets, lambda r: r["algorithm"] == "msbp" and r["hpd"] == hpd, "hpd", repr(float(hpd) * 0.9))
        summary = os.path.join(self.root, "results/jdtvb/table4/summary.csv")
        with open(summary, encoding="utf-8") as f:
            tet = next(csv.DictReader(f))["tet_s_mean"]
        replace_field(summary, lambda r: r["tet_s_mean"] == tet, "tet_s_mean", repr(float(tet) * (1 + 1e-12)))
        result = render(self.root, "--check", "jdtvb")
        self.assertEqual(result.returncode, 1)
        self.assertIn(f"results/multiscan/fig4/targets.csv: {manifest}", result.stderr)
        self.assertIn(f"results/jdtvb/table4/summary.csv: {manifest}", result.stderr)
        self.assertNotIn("is not what the committed data give", result.stderr)

    def test_a_deleted_data_file_fails_the_check(self):
        os.remove(os.path.join(self.root, "results/jdtvb/fig7/meta.json"))
        result = render(self.root, "--check", "leaderboard")
        self.assertEqual(result.returncode, 1)
        self.assertIn("results/jdtvb/fig7/meta.json: listed in results/SHA256SUMS but missing", result.stderr)


class Manifest(unittest.TestCase):
    def test_the_committed_manifest_lists_every_committed_data_file(self):
        """results/SHA256SUMS lists exactly what git tracks under results/ but the REPORTs and
        READMEs, each with its sha256 (what sha256sum -c checks)."""
        listed = manifest.read(REPO)
        committed = manifest.committed_files(REPO)
        if committed is None:
            self.skipTest("not a git work tree")
        self.assertEqual(sorted(listed), committed)
        self.assertTrue(all(not p.endswith(("REPORT.md", "README.md")) for p in listed))
        self.assertEqual(manifest.problems(REPO), [])

    def test_a_malformed_line_is_one_problem(self):
        root = tempfile.mkdtemp(prefix="manifest-test-")
        try:
            os.makedirs(os.path.join(root, "results"))
            with open(os.path.join(root, manifest.MANIFEST), "w", encoding="utf-8") as f:
                f.write("abc results/x.csv\n")
            self.assertEqual(manifest.problems(root), ["results/SHA256SUMS:1: not `<sha256>  <path>`"])
        finally:
            shutil.rmtree(root)


class UnknownStudy(unittest.TestCase):
    """rerun.py and digest.py name the studies they know when given one they do not."""

    def run_module(self, module, *args):
        return subprocess.run([sys.executable, "-m", module, *args], capture_output=True, text=True, cwd=REPO)

    def test_rerun_lists_every_study(self):
        result = self.run_module("reports.rerun", "nosuch", "--dry-run")
        self.assertEqual(result.returncode, 2)
        self.assertIn("unknown study 'nosuch' (known: bp-paper, multiscan, jdtvb, tbd, leaderboard, readme, and quickstart)", result.stderr)

    def test_rerun_names_what_it_reproduces_and_compares_it(self):
        """A cheap committed run rerun into a scratch folder: identical to the committed one,
        timings aside; the committed data untouched."""
        if not os.path.exists(os.path.join(REPO, "build", "dabench")):
            self.skipTest("dabench is not built")
        scratch = tempfile.mkdtemp(prefix="rerun-test-")
        try:
            folder = "results/cluster/throughput-threads2"
            result = self.run_module("reports.rerun", "readme", "--only", folder, "--scratch", scratch)
            self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
            self.assertIn(f"rerun: {folder}: predicted", result.stdout)
            self.assertIn(f"rerun: {folder}: 1 files compared (summary.csv): identical (timings aside)", result.stdout)
            self.assertTrue(os.path.exists(os.path.join(scratch, folder, "trials.csv")))
            self.assertEqual(manifest.problems(REPO), [])
        finally:
            shutil.rmtree(scratch)
        result = self.run_module("reports.rerun", "readme", "--only", "results/nosuch", "--dry-run")
        self.assertEqual(result.returncode, 2)
        self.assertIn("results/nosuch: not a run of readme", result.stderr)

    def test_digest_lists_the_studies_with_digests(self):
        result = self.run_module("reports.digest", "jdtvb")
        self.assertEqual(result.returncode, 2)
        self.assertIn("(studies with digests: bp-paper, tbd, leaderboard, readme)", result.stderr)


if __name__ == "__main__":
    unittest.main()
