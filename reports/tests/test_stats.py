"""The statistics against closed forms."""

import math
import random
import unittest

import numpy as np

from reports.core import markdown, stats


class MeansAndPairs(unittest.TestCase):
    def test_mean_and_standard_error(self):
        m, se, n = stats.mean_se([1.0, 2.0, 3.0, 4.0, None, math.nan])
        self.assertEqual((m, n), (2.5, 4))
        self.assertAlmostEqual(se, math.sqrt(5.0 / 3.0 / 4.0))  # s² = 5/3
        self.assertTrue(math.isnan(stats.mean_se([1.0])[1]))

    def test_paired_difference_uses_common_keys(self):
        a = {0: 1.0, 1: 2.0, 2: 4.0, 3: None}
        b = {0: 0.5, 1: 1.0, 2: 1.0, 4: 9.0}
        m, se, n = stats.paired(a, b)
        self.assertEqual(n, 3)
        self.assertAlmostEqual(m, (0.5 + 1.0 + 3.0) / 3)


class Bootstrap(unittest.TestCase):
    def test_standard_error_of_a_mean_matches_the_closed_form(self):
        rng = random.Random(1)
        values = [rng.gauss(0.0, 1.0) for _ in range(400)]
        _, se_closed, _ = stats.mean_se(values)
        value, se_boot, (lo, hi) = stats.bootstrap_se([[x] for x in values], np.mean, resamples=2000)
        self.assertAlmostEqual(value, sum(values) / 400)
        self.assertLess(abs(se_boot / se_closed - 1.0), 0.08)  # bootstrap noise at 2000 resamples ~3 %
        self.assertLess(lo, value)
        self.assertGreater(hi, value)

    def test_median_of_a_uniform_sample(self):
        # The sample median of n Uniform(0,1) has s.d. ~ 1 / (2 sqrt(n)) (asymptotically).
        rng = random.Random(7)
        n = 1001
        values = [rng.random() for _ in range(n)]
        _, se, _ = stats.bootstrap_se([[x] for x in values], np.median, resamples=2000)
        self.assertLess(abs(se / (0.5 / math.sqrt(n)) - 1.0), 0.2)

    def test_groups_resample_whole_trials(self):
        # Two identical values per trial: the clustered standard error is that of the trial means.
        rng = random.Random(3)
        trials = [[x, x] for x in (rng.gauss(0, 1) for _ in range(300))]
        _, se_clustered, _ = stats.bootstrap_se(trials, np.mean, resamples=2000)
        _, se_trials, _ = stats.mean_se([t[0] for t in trials])
        self.assertLess(abs(se_clustered / se_trials - 1.0), 0.1)

    def test_same_seed_same_numbers(self):
        groups = [[1.0, 2.0], [3.0], [4.0, 5.0, 6.0]]
        a = stats.cluster_bootstrap(groups, np.mean, resamples=50)
        b = stats.cluster_bootstrap(groups, np.mean, resamples=50)
        self.assertTrue(np.array_equal(a, b))

    def test_percentile_interpolates(self):
        self.assertAlmostEqual(stats.percentile([0.0, 1.0, 2.0, 3.0, 4.0], 80), 3.2)


class Formatting(unittest.TestCase):
    def test_mean_with_standard_error(self):
        self.assertEqual(markdown.pm(0.8412, 0.0103), "0.841 ± 0.010")
        self.assertEqual(markdown.pm(3.613, 0.0612), "3.61 ± 0.06")
        self.assertEqual(markdown.pm(12.46, 0.71), "12.5 ± 0.7")
        self.assertEqual(markdown.pm(4.0, 0.0), "4.00")
        self.assertEqual(markdown.sig(0.012345, 3), "0.0123")
        self.assertEqual(markdown.duration(762.9), "12.7 min")


if __name__ == "__main__":
    unittest.main()
