"""The provenance check of a committed run against a hand-written meta.json."""

import json
import os
import shutil
import subprocess
import tempfile
import unittest

from reports.core import study

EXPERIMENT = "name = toy\nscenario = grid\ntrials = 4\n"


class Provenance(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="provenance-test-")
        os.makedirs(os.path.join(self.root, "experiments"))
        os.makedirs(os.path.join(self.root, "results", "toy"))
        with open(os.path.join(self.root, "experiments", "toy.ini"), "w", encoding="utf-8") as f:
            f.write("# a comment that does not decide the run\n" + EXPERIMENT)
        self.run = study.Run("results/toy", "./build/dabench run experiments/toy.ini --force")

    def tearDown(self):
        shutil.rmtree(self.root)

    def problems(self, **meta):
        record = {"git_commit": "9dfb3047fb2a3fe617bbe39ae06a2699ccb61608", "source_modified": False,
                  "status": "complete", "experiment_path": "experiments/toy.ini", "experiment": EXPERIMENT,
                  "trials_per_point": "4", "seed": "1",
                  "command_line": "./build/dabench run experiments/toy.ini --force"}
        record.update(meta)
        with open(os.path.join(self.root, "results", "toy", "meta.json"), "w", encoding="utf-8") as f:
            json.dump(record, f)
        return study.provenance(self.root, self.run)[1]

    def test_a_clean_complete_run_has_no_problem(self):
        self.assertEqual(self.problems(), [])

    def test_a_resumed_run_is_the_same_run(self):
        self.assertEqual(self.problems(command_line="./build/dabench run experiments/toy.ini --resume"), [])

    def test_modified_or_unknown_source_is_a_problem(self):
        self.assertEqual(len(self.problems(source_modified=True)), 1)
        self.assertEqual(len(self.problems(source_modified=None)), 1)
        self.assertEqual(len(self.problems(git_commit="9dfb304-dirty")), 1)

    def test_another_command_or_an_edited_experiment_is_a_problem(self):
        self.assertIn("the study lists", self.problems(command_line="./build/dabench run experiments/toy.ini --threads 2 --force")[0])
        self.assertIn("has changed", self.problems(experiment=EXPERIMENT.replace("4", "5"))[0])

    def test_a_moved_experiment_keeps_its_runs_and_nothing_else(self):
        """A run recorded before its experiment file (and a file it reads) moved: experiments/moved.csv
        maps the recorded paths to the current ones; the content is still compared."""
        os.makedirs(os.path.join(self.root, "experiments", "study"))
        os.replace(os.path.join(self.root, "experiments", "toy.ini"),
                   os.path.join(self.root, "experiments", "study", "toy.ini"))
        with open(os.path.join(self.root, "experiments", "study", "toy.ini"), "a", encoding="utf-8") as f:
            f.write("frame = experiments/study/frame.csv\n")
        self.run = study.Run("results/toy", "./build/dabench run experiments/study/toy.ini --force")
        old = EXPERIMENT + "frame = experiments/data/frame.csv\n"
        self.assertEqual(len(self.problems(experiment=old)), 2)  # another command; its experiment not in the tree
        with open(os.path.join(self.root, "experiments", "moved.csv"), "w", encoding="utf-8") as f:
            f.write("old_path,new_path\nexperiments/toy.ini,experiments/study/toy.ini\n"
                    "experiments/data/frame.csv,experiments/study/frame.csv\n")
        self.assertEqual(self.problems(experiment=old), [])
        self.assertIn("has changed", self.problems(experiment=old.replace("4", "5"))[0])
        self.assertIn("the study lists", self.problems(experiment=old, command_line="./build/dabench run x.ini --force")[0])
        # A path that only begins like a moved one is not moved.
        self.assertEqual(study.with_moves("experiments/toy.ini2 experiments/toy.ini", study.moved_paths(self.root)),
                         "experiments/toy.ini2 experiments/study/toy.ini")

    def test_seed_and_trials_must_be_what_the_command_and_experiment_ask_for(self):
        self.assertEqual(self.problems(seed="2014"), [])  # the experiment names no seed: not checked
        self.assertEqual(self.problems(trials_per_point="4"), [])
        self.assertIn("trials_per_point is 5, its command and experiment ask for 4", self.problems(trials_per_point="5")[0])
        self.run = study.Run("results/toy", "./build/dabench run experiments/toy.ini --trials 7 --force")
        self.assertEqual(self.problems(trials_per_point="7", command_line=self.run.command), [])
        self.assertEqual(len(self.problems(trials_per_point="4", command_line=self.run.command)), 1)
        self.run = study.Run("results/toy", "./build/dabench run experiments/toy.ini --seed=9 --force")
        self.assertIn("seed is 1, its command and experiment ask for 9",
                      self.problems(seed="1", command_line=self.run.command)[0])

    def test_the_commit_must_be_in_the_repository_and_an_ancestor_of_head(self):
        def git(*args):
            return subprocess.run(["git", "-C", self.root, "-c", "user.email=t@t", "-c", "user.name=t", *args],
                                  capture_output=True, text=True, check=True).stdout.strip()
        git("init", "-q", "-b", "main")
        git("add", "-A")
        git("commit", "-q", "-m", "one")
        first = git("rev-parse", "HEAD")
        git("checkout", "-q", "-b", "side")
        git("commit", "-q", "--allow-empty", "-m", "side")
        side = git("rev-parse", "HEAD")
        git("checkout", "-q", "main")
        git("commit", "-q", "--allow-empty", "-m", "two")
        self.assertEqual(self.problems(git_commit=first), [])
        self.assertIn("is not a commit of this repository", self.problems(git_commit="0" * 40)[0])
        self.assertIn("is not an ancestor of HEAD", self.problems(git_commit=side)[0])

    def test_a_launcher_before_the_program_does_not_count(self):
        self.assertEqual(study.command_words("taskset -c 0 ./build/dabench run x.ini --force"),
                         study.command_words("./build/dabench run x.ini --resume"))


if __name__ == "__main__":
    unittest.main()
