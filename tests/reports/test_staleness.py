"""Stale runs: a run's sources (the files of its algorithms and scenario and what they include)
changed since its commit — comments aside — unless a rerun reproduced it since."""

import json
import os
import shutil
import subprocess
import tempfile
import unittest
from unittest import mock

from reports import staleness


class Staleness(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="staleness-test-")
        self.write("algorithms/single_scan/toy.hpp", '#include "harness/core/util.hpp"\nstruct Toy { static constexpr std::string_view kName = "toy"; };\n')
        self.write("algorithms/single_scan/toy.cpp", '#include "algorithms/single_scan/toy.hpp"\nint toy() { return 1; }\n')
        self.write("harness/core/util.hpp", "int util();\n")
        self.write("harness/core/util.cpp", "int util() { return 2; }  // two\n")
        self.write("scenarios/single_scan/grid.hpp", 'struct Grid { static constexpr std::string_view kName = "grid"; };\n')
        self.write("harness/core/unrelated.cpp", "int unrelated() { return 3; }\n")
        self.git("init", "-q", "-b", "main")
        self.git("add", "-A")
        self.git("commit", "-q", "-m", "one")
        self.commit = self.git("rev-parse", "HEAD")
        meta = {"git_commit": self.commit, "algorithms": ["toy:x=1"], "references": [], "scenario": "grid"}
        self.write("results/run/meta.json", json.dumps(meta))

    def tearDown(self):
        shutil.rmtree(self.root)

    def write(self, relpath, text):
        full = os.path.join(self.root, relpath)
        os.makedirs(os.path.dirname(full), exist_ok=True)
        with open(full, "w", encoding="utf-8") as f:
            f.write(text)

    def git(self, *args):
        return subprocess.run(["git", "-C", self.root, "-c", "user.email=t@t", "-c", "user.name=t", *args],
                              capture_output=True, text=True, check=True).stdout.strip()

    def state(self):
        with mock.patch.object(staleness, "run_folders", lambda: ["results/run"]):  # the one run of this tree
            rows = staleness.record_rows(self.root)
        return rows[0][1], rows[0][3].split()

    def test_sources_are_the_names_files_and_their_includes(self):
        with open(os.path.join(self.root, "results/run/meta.json"), encoding="utf-8") as f:
            meta = json.load(f)
        self.assertEqual(staleness.Sources(self.root).of_run(meta),
                         ["algorithms/single_scan/toy.cpp", "algorithms/single_scan/toy.hpp", "harness/core/util.cpp",
                          "harness/core/util.hpp", "scenarios/single_scan/grid.hpp"])

    def test_a_code_change_in_an_included_file_makes_the_run_stale_a_comment_does_not(self):
        self.assertEqual(self.state(), ("current", []))
        self.write("harness/core/util.cpp", "int util() { return 2; }  // the number two, explained\n")
        self.write("harness/core/unrelated.cpp", "int unrelated() { return 4; }\n")
        self.assertEqual(self.state(), ("current", []))
        self.write("harness/core/util.cpp", "int util() { return 3; }\n")
        self.assertEqual(self.state(), ("stale", ["harness/core/util.cpp"]))
        self.git("commit", "-q", "-am", "two")
        self.assertEqual(self.state(), ("stale", ["harness/core/util.cpp"]))  # committing changes nothing

    def test_a_reproduced_run_is_current_until_its_sources_change_again(self):
        self.write("harness/core/util.cpp", "int util() { return 3; }\n")
        staleness.record_verified(self.root, "results/run", "2026-12-08T01:00:00Z")
        self.assertEqual(self.state(), ("reproduced", []))
        self.write("algorithms/single_scan/toy.cpp", '#include "algorithms/single_scan/toy.hpp"\nint toy() { return 5; }\n')
        self.assertEqual(self.state(), ("stale", ["algorithms/single_scan/toy.cpp", "harness/core/util.cpp"]))


if __name__ == "__main__":
    unittest.main()
