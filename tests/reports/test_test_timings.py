"""The test-timing tables of docs/tests.md (experiments/readme/__init__.py, test_timings) from recorded runs:
each run's floor is its steps' CPU time over its cores, the cold run's compile time is the sum of
its build steps, and a run without CPU times (the sequential script's) has no floor."""

import os
import shutil
import tempfile
import unittest

from reports.core.study import Report
from experiments import readme

STEPS = """run,commit,date,cores,build,step,wall_s,cpu_s
before,aaaaaaa,2026-12-06,2,release,build,400,
before,aaaaaaa,2026-12-06,2,all,total,900,
cold,bbbbbbb,2026-12-07,2,release,build,300,500
cold,bbbbbbb,2026-12-07,2,asan,build,400,700
cold,bbbbbbb,2026-12-07,2,release,ctest,100,120
cold,bbbbbbb,2026-12-07,2,asan,ctest,90,180
cold,bbbbbbb,2026-12-07,2,asan,fuzz,60,120
cold,bbbbbbb,2026-12-07,2,all,total,800,
warm,bbbbbbb,2026-12-07,2,release,build,5,6
warm,bbbbbbb,2026-12-07,2,release,ctest,100,150
warm,bbbbbbb,2026-12-07,2,asan,ctest,100,200
warm,bbbbbbb,2026-12-07,2,asan,fuzz,60,44
warm,bbbbbbb,2026-12-07,2,all,total,300,
"""
CASES = """run,build,case,seconds
before,release,slow one,9.5
cold,release,slow one,12.25
cold,asan,instrumented one,30.0
"""


class TestTimings(unittest.TestCase):
    def setUp(self):
        self.root = tempfile.mkdtemp(prefix="reports-test-timings-")
        os.makedirs(os.path.join(self.root, "tests", "timings"))
        for name, text in (("steps.csv", STEPS), ("cases.csv", CASES)):
            with open(os.path.join(self.root, "tests", "timings", name), "w", encoding="utf-8") as f:
                f.write(text)
        self.report = Report(readme.STUDY, self.root)
        readme.test_timings(self.report)

    def tearDown(self):
        shutil.rmtree(self.root)

    def test_floor_is_cpu_over_cores(self):
        floor = next(line for line in self.report.values["tests.steps"].splitlines() if "÷ cores" in line)
        # cold: (500 + 700 + 120 + 180 + 120) / 2 = 810 s; warm: 400 / 2 = 200 s; before: no CPU times.
        self.assertEqual(floor, "| CPU of every step ÷ cores | – | 13:30 | 3:20 |")

    def test_columns_follow_the_runs_order_and_totals_are_last(self):
        lines = self.report.values["tests.steps"].splitlines()
        self.assertTrue(lines[0].startswith("| step | before<br>`aaaaaaa`, 2 cores | cold<br>`bbbbbbb`"))
        self.assertEqual(lines[-2], "| **total** | **15:00** | **13:20** | **5:00** |")
        self.assertIn("| release build | 6:40 | 5:00 (8:20) | 0:05 (0:06) |", lines)

    def test_cold_compile_and_warm_share(self):
        self.assertEqual(self.report.values["tests.cold_compile"],
                         "its builds took 20:00 of CPU time (release 8:20, asan 11:40), at least 10:00 of wall "
                         "time on 2 cores, against 13:20 for the whole run")
        self.assertEqual(self.report.values["tests.warm_asan_share"], "61 %")  # (200 + 44) / 400

    def test_cases_by_build(self):
        self.assertIn("| slow one | 9.5 | 12.2 |", self.report.values["tests.cases.release"])
        asan = self.report.values["tests.cases.asan"]
        self.assertTrue(asan.startswith("| case | cold (s) |"))  # only the runs with ASan cases


if __name__ == "__main__":
    unittest.main()
