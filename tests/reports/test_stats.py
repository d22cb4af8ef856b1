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

    def test_percentile_interval_is_the_draws_quantiles(self):
        # 1001 equally spaced draws: the 2.5 % and 97.5 % quantiles are draws 25 and 975 exactly.
        for (lo, hi), expected in ((stats.percentile_interval(np.arange(1001.0)), (25.0, 975.0)),
                                   (stats.percentile_interval(np.arange(101.0), level=0.9), (5.0, 95.0))):
            self.assertAlmostEqual(lo, expected[0], places=9)
            self.assertAlmostEqual(hi, expected[1], places=9)

    def test_interval_of_a_quantile_matches_the_order_statistic_interval(self):
        # The 80th percentile of n Uniform(0, 1): the distribution-free 95 % interval is
        # [X_(r), X_(s)] with r, s = n·0.8 ∓ 1.96·sqrt(n·0.8·0.2) (binomial count below the
        # quantile, normal approximation); the bootstrap percentile interval estimates the same.
        rng = np.random.Generator(np.random.PCG64(11))
        n = 2000
        values = rng.random(n)
        _, _, (lo, hi) = stats.bootstrap_se([[x] for x in values], lambda v: np.percentile(v, 80), resamples=4000)
        order = np.sort(values)
        half = 1.96 * math.sqrt(n * 0.8 * 0.2)
        closed = (order[int(math.floor(n * 0.8 - half)) - 1], order[int(math.ceil(n * 0.8 + half)) - 1])
        width = closed[1] - closed[0]
        self.assertLess(abs(lo - closed[0]), 0.15 * width)
        self.assertLess(abs(hi - closed[1]), 0.15 * width)

    def test_interval_matches_scipy_bootstrap(self):
        # scipy.stats.bootstrap's percentile method on the same data (its own random draws): the
        # endpoints agree within the Monte Carlo noise of 4000 resamples.
        from scipy import stats as scipy_stats
        rng = np.random.Generator(np.random.PCG64(12))
        values = rng.normal(0.0, 1.0, 600)
        _, _, (lo, hi) = stats.bootstrap_se([[x] for x in values], np.median, resamples=4000)
        theirs = scipy_stats.bootstrap((values,), np.median, n_resamples=4000, method="percentile",
                                       vectorized=False, random_state=np.random.default_rng(3)).confidence_interval
        width = theirs.high - theirs.low
        self.assertLess(abs(lo - theirs.low), 0.1 * width)
        self.assertLess(abs(hi - theirs.high), 0.1 * width)

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
