"""The calibration of the TBD readings (experiments/tbd/calibration.py) against direct
computations: the Rice density it sums is the 2-D Gaussian integrated over the phase; log I0 is
numpy's below its switch and the exact integral above; the expected excess energy is the lattice
sum over cells; the Fig. 1(a) log-likelihood is the per-cell sum over the frame file read here;
the vectorised grid is the per-point log-likelihood; the fit is the grid's maximum and its
profile interval holds it."""

import math
import os
import unittest

import numpy as np

from experiments.tbd import calibration as cal

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PHASES = 20000  # midpoint rule over [0, 2π): exact to rounding for these smooth periodic integrands


def log_sum_exp(v):
    top = float(np.max(v))
    return top + math.log(float(np.sum(np.exp(v - top))))


def rice_by_quadrature(a, nu, s):
    """log of a ∫ N((a cos t, a sin t); (nu, 0), s I2) dt over [0, 2π)."""
    t = (np.arange(PHASES) + 0.5) * 2.0 * math.pi / PHASES
    d2 = (a * np.cos(t) - nu) ** 2 + (a * np.sin(t)) ** 2
    return math.log(a / (2.0 * math.pi * s) * 2.0 * math.pi / PHASES) + log_sum_exp(-d2 / (2.0 * s))


def log_i0_by_quadrature(x):
    """log I0(x) = log (1/2π) ∫ exp(x cos t) dt over [0, 2π)."""
    t = (np.arange(PHASES) + 0.5) * 2.0 * math.pi / PHASES
    return log_sum_exp(x * np.cos(t)) - math.log(PHASES)


def theta(variance, terms=6):
    """Σ_n exp(-n²/(2 variance)) over the integers / sqrt(2π variance), by Poisson summation."""
    return 1.0 + 2.0 * sum(math.exp(-2.0 * math.pi ** 2 * variance * k * k) for k in range(1, terms))


def read_frame_here():
    """experiments/tbd/fig1a-frame.csv: {(column, row): |z|} of the readable cells (rows bottom
    first, `nan` under the figure's legend)."""
    cells = {}
    with open(os.path.join(REPO, "experiments/tbd/fig1a-frame.csv")) as f:
        lines = [line.strip() for line in f if line.strip() and not line.startswith("#")]
    for row, line in enumerate(lines):
        for column, value in enumerate(line.split(",")):
            if value.strip() != "nan":
                cells[(column, row)] = float(value)
    return cells


def fig1_by_cells(rho, spread):
    """The Fig. 1(a) log-likelihood of D3 (D1 at rho = 0) cell by cell: objects at (4, 4) and
    (5, 5), gamma = 60, sigma^2 = 1; Rayleigh where there is no mean, Rice otherwise."""
    total = 0.0
    for (column, row), a in read_frame_here().items():
        g = sum(math.exp(-((column + 0.5 - px) ** 2 + (row + 0.5 - py) ** 2) / (2.0 * spread))
                for px, py in ((4.0, 4.0), (5.0, 5.0)))
        nu = math.sqrt(rho * 60.0) * g
        s = 1.0 + (1.0 - rho) * 30.0 * g
        total += math.log(a / s) - (a * a + nu * nu) / (2.0 * s)
        if nu > 0.0:
            total += math.log(float(np.i0(a * nu / s)))
    return total


def joint(frame, rho, spread):
    """The fit's objective at one point, from the per-point functions."""
    return cal.fig1_log_likelihood(frame, rho, spread) + cal.energy_log_likelihood(cal.expected_energy(rho, spread))


class RiceDensity(unittest.TestCase):
    def test_it_is_the_gaussian_integrated_over_the_phase(self):
        # Rayleigh (nu = 0), moderate, and a * nu / s beyond the switch of log I0 (1520, 1800)
        for a, nu, s in ((1.2, 0.0, 1.0), (0.3, 0.0, 2.0), (6.1, 4.0, 3.5), (12.3, 9.0, 1.4), (2.0, 7.0, 1.0),
                         (40.0, 38.0, 1.0), (60.0, 60.0, 2.0)):
            with self.subTest(a=a, nu=nu, s=s):
                ours = cal._rice_log_likelihood(np.array([a]), np.array([nu]), np.array([s]))
                self.assertAlmostEqual(ours, rice_by_quadrature(a, nu, s), places=8)

    def test_log_i0_is_numpys_below_its_switch(self):
        x = np.array([0.0, 1e-3, 0.5, 3.0, 20.0, 150.0, 699.0])
        np.testing.assert_allclose(cal._log_i0(x), np.log(np.i0(x)), rtol=1e-13, atol=1e-15)

    def test_log_i0_is_the_integral_above_its_switch(self):
        for x in (cal.I0_SWITCH, 800.0, 5000.0, 1e5):
            with self.subTest(x=x):
                self.assertAlmostEqual(cal._log_i0(np.array([x]))[0], log_i0_by_quadrature(x), places=8)

    def test_log_i0_is_continuous_at_its_switch(self):
        below, above = cal._log_i0(np.array([cal.I0_SWITCH - 1e-9, cal.I0_SWITCH]))
        self.assertAlmostEqual(below, above, places=8)


class Energy(unittest.TestCase):
    OFFSETS = np.arange(-20, 21)  # a 41 x 41 grid of cells around the object's cell

    def lattice_sum(self, rho, spread, sx=0.0, sy=0.0):
        """sum_j |mu_j|^2 + 2 c_j of a D3 object (sigma_S^2 = 1) at (sx, sy) from its cell's centre."""
        dx, dy = np.meshgrid(self.OFFSETS - sx, self.OFFSETS - sy)
        g = np.exp(-(dx ** 2 + dy ** 2) / (2.0 * spread))
        mu = math.sqrt(rho * cal.GAMMA) * g
        c = (1.0 - rho) * cal.GAMMA / 2.0 * g
        return float(np.sum(mu * mu + 2.0 * c))

    def test_expected_energy_is_the_lattice_sum_averaged_over_the_position(self):
        shifts = (np.arange(20) + 0.5) / 20.0 - 0.5  # positions within the cell, midpoint rule
        for rho in (0.0, 0.5, 1.0):
            for spread in (0.42, 0.58):
                average = np.mean([self.lattice_sum(rho, spread, sx, sy) for sx in shifts for sy in shifts])
                with self.subTest(rho=rho, spread=spread):
                    self.assertAlmostEqual(cal.expected_energy(rho, spread) / average, 1.0, places=4)

    def test_a_cell_centred_object_differs_only_by_the_lattice_aliasing(self):
        """At the cell centre the lattice sums of g and g^2 exceed their integrals by theta(sigma_h^2)^2
        and theta(sigma_h^2 / 2)^2: up to 6 % at rho = 1, sigma_h^2 = 0.42, so expected_energy is not
        a cell-centred object's energy within 1e-3; with those factors it is within 1e-12."""
        for rho in (0.0, 0.5, 1.0):
            for spread in (0.42, 0.58):
                mean_part = rho * cal.expected_energy(1.0, spread) * theta(spread / 2.0) ** 2
                fluctuating_part = (1.0 - rho) * cal.expected_energy(0.0, spread) * theta(spread) ** 2
                with self.subTest(rho=rho, spread=spread):
                    self.assertAlmostEqual(self.lattice_sum(rho, spread) / (mean_part + fluctuating_part), 1.0, places=12)


class Fit(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.frame = cal.read_frame(REPO)
        cls.fit = cal.fit(REPO)

    def test_the_frame_is_read_as_the_file_says(self):
        cells = read_frame_here()
        self.assertEqual(self.fit["cells"], len(cells))
        self.assertEqual(self.fit["cells"] + self.fit["unread"], 100)
        for (column, row), a in cells.items():
            self.assertEqual(self.frame[row, column], a)

    def test_the_fig1_log_likelihood_is_the_sum_over_the_readable_cells(self):
        for rho, spread in ((0.0, 0.42), (0.0, 0.5), (0.0, 1.5), (0.66, 0.58), (1.0, 0.3)):
            with self.subTest(rho=rho, spread=spread):
                self.assertAlmostEqual(cal.fig1_log_likelihood(self.frame, rho, spread), fig1_by_cells(rho, spread),
                                       places=9)

    def test_the_grid_is_the_per_point_likelihood(self):
        table = cal.fig1_table(self.frame)
        for i, j in ((0, 0), (33, 38), (66, 90), (100, 180)):
            with self.subTest(rho=cal.RHO_GRID[i], spread=cal.SPREAD_GRID[j]):
                self.assertAlmostEqual(table[i, j], cal.fig1_log_likelihood(self.frame, cal.RHO_GRID[i],
                                                                            cal.SPREAD_GRID[j]), places=9)

    def test_the_fit_is_the_grid_maximum(self):
        best = self.fit["best"]
        self.assertAlmostEqual(best["joint"], joint(self.frame, best["rho"], best["spread"]), places=9)
        i = int(np.argmin(np.abs(cal.RHO_GRID - best["rho"])))
        j = int(np.argmin(np.abs(cal.SPREAD_GRID - best["spread"])))
        around = [(cal.RHO_GRID[ii], cal.SPREAD_GRID[jj]) for ii in range(max(0, i - 2), min(len(cal.RHO_GRID), i + 3))
                  for jj in range(max(0, j - 2), min(len(cal.SPREAD_GRID), j + 3))]
        for rho, spread in around + [(0.0, 0.5), (0.3, 0.5), (0.9, 0.6), (1.0, 2.0)]:
            with self.subTest(rho=rho, spread=spread):
                self.assertLessEqual(joint(self.frame, rho, spread), best["joint"] + 1e-9)

    def test_the_profile_interval_holds_the_fit_and_is_the_likelihood_ratio_set(self):
        best = self.fit["best"]
        low, high = best["interval"]
        self.assertLessEqual(low, best["rho"])
        self.assertGreaterEqual(high, best["rho"])
        profile = {rho: max(joint(self.frame, rho, s) for s in cal.SPREAD_GRID)
                   for rho in (low, high, round(low - 0.01, 2), round(high + 0.01, 2)) if 0.0 <= rho <= 1.0}
        self.assertLessEqual(best["joint"] - profile[low], cal.LR_95)
        self.assertLessEqual(best["joint"] - profile[high], cal.LR_95)
        for rho in profile.keys() - {low, high}:
            with self.subTest(rho=rho):
                self.assertGreater(best["joint"] - profile[rho], cal.LR_95)


if __name__ == "__main__":
    unittest.main()
