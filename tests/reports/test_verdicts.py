"""The verdict rules against hand-computed cases."""

import math
import unittest

from reports.core import verdicts as v


class CompareValue(unittest.TestCase):
    def test_within_two_combined_standard_errors_plus_rounding(self):
        # |0.841 - 0.88| = 0.039; bound = 2 * sqrt(0.010^2 + 0.010^2) + 0.005 = 0.03328...
        verdict, diff, bound = v.compare_value(0.841, 0.010, 0.88, 0.010, "0.88")
        self.assertAlmostEqual(diff, -0.039)
        self.assertAlmostEqual(bound, 2 * math.sqrt(2) * 0.010 + 0.005)
        self.assertEqual(verdict, v.DIFFERS)
        verdict, _, _ = v.compare_value(0.851, 0.010, 0.88, 0.010, "0.88")  # 0.029 < 0.0333
        self.assertEqual(verdict, v.WITHIN_ERROR)

    def test_rounding_of_the_printed_number(self):
        self.assertEqual(v.half_unit("0.88"), 0.005)
        self.assertEqual(v.half_unit("12.7"), 0.05)
        self.assertEqual(v.half_unit("1279"), 0.5)
        self.assertAlmostEqual(v.half_unit("1.5e-3"), 0.05e-3)
        # no sampling error at all: only the rounding decides
        self.assertEqual(v.compare_value(0.884, None, 0.88, None, "0.88")[0], v.WITHIN_ERROR)
        self.assertEqual(v.compare_value(0.886, None, 0.88, None, "0.88")[0], v.DIFFERS)

    def test_missing_value_is_not_run(self):
        self.assertEqual(v.compare_value(math.nan, 0.1, 1.0)[0], v.NOT_RUN)


class Directions(unittest.TestCase):
    def test_sign_beyond_and_within_error(self):
        self.assertEqual(v.compare_direction(0.05, 0.02, +1), v.AGREES)  # 0.05 > 0.04
        self.assertEqual(v.compare_direction(0.03, 0.02, +1), v.WITHIN_ERROR)
        self.assertEqual(v.compare_direction(-0.03, 0.02, +1), v.WITHIN_ERROR)
        self.assertEqual(v.compare_direction(-0.05, 0.02, +1), v.DIFFERS)
        self.assertEqual(v.compare_direction(-0.05, 0.02, -1), v.AGREES)
        self.assertEqual(v.compare_direction(0.05, 0.02, +1, slack=0.02), v.WITHIN_ERROR)

    def test_bounds(self):
        self.assertEqual(v.compare_bound(0.0123, 0.0001, 0.015, holds_below=True), v.AGREES)
        self.assertEqual(v.compare_bound(0.0151, 0.0001, 0.015, holds_below=True), v.WITHIN_ERROR)
        self.assertEqual(v.compare_bound(0.0160, 0.0001, 0.015, holds_below=True), v.DIFFERS)
        self.assertEqual(v.compare_bound(3.0, 0.1, 2.0, holds_below=False), v.AGREES)

    def test_direction_only_and_worst(self):
        self.assertEqual(v.value_and_direction(v.DIFFERS, v.AGREES), v.DIRECTION_ONLY)
        self.assertEqual(v.value_and_direction(v.DIFFERS, v.DIFFERS), v.DIFFERS)
        self.assertEqual(v.value_and_direction(v.WITHIN_ERROR, v.AGREES), v.WITHIN_ERROR)
        self.assertEqual(v.worst([v.AGREES, v.WITHIN_ERROR, v.NOT_RUN]), v.WITHIN_ERROR)
        self.assertEqual(v.worst([v.AGREES, v.DIRECTION_ONLY, v.WITHIN_ERROR]), v.DIRECTION_ONLY)
        self.assertEqual(v.worst([v.AGREES, v.DIFFERS]), v.DIFFERS)
        self.assertEqual(v.worst([v.NOT_RUN]), v.NOT_RUN)

    def test_resamples(self):
        self.assertEqual(v.from_resamples(True, 0.96), v.AGREES)
        self.assertEqual(v.from_resamples(True, 0.80), v.WITHIN_ERROR)
        self.assertEqual(v.from_resamples(False, 0.03), v.DIFFERS)
        self.assertEqual(v.from_resamples(False, 0.20), v.WITHIN_ERROR)


if __name__ == "__main__":
    unittest.main()
