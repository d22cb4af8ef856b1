"""The calibration of the TBD readings (reports/studies/tbd_calibration.py) against direct
computations: the Rice density it sums is the 2-D Gaussian integrated over the phase; the
expected excess energy is the lattice sum over cells; the vectorised grid is the per-point
log-likelihood; the fit is the grid's maximum and its profile interval holds it."""

import math
import os
import unittest

import numpy as np

from reports.studies import tbd_calibration as cal

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))


def rice_by_quadrature(a, nu, s, points=20000):
    """log of a ∫ N((a cos t, a sin t); (nu, 0), s I2) dt over [0, 2π) (midpoint rule)."""
    t = (np.arange(points) + 0.5) * 2.0 * math.pi / points
    d2 = (a * np.cos(t) - nu) ** 2 + (a * np.sin(t)) ** 2
    density = np.exp(-d2 / (2.0 * s)) / (2.0 * math.pi * s)
    return math.log(a * np.sum(density) * 2.0 * math.pi / points)


class RiceDensity(unittest.TestCase):
    def test_it_is_the_gaussian_integrated_over_the_phase(self):
        for a, nu, s in ((1.2, 0.0, 1.0), (0.3, 0.0, 2.0), (6.1, 4.0, 3.5), (12.3, 9.0, 1.4), (2.0, 7.0, 1.0)):
            with self.subTest(a=a, nu=nu, s=s):
                ours = cal._rice_log_likelihood(np.array([a]), np.array([nu]), np.array([s]))
                self.assertAlmostEqual(ours, rice_by_quadrature(a, nu, s), places=8)

    def test_log_i0_is_continuous_at_its_switch(self):
        below, above = cal._log_i0(np.array([cal.I0_SWITCH - 1e-9, cal.I0_SWITCH]))
        self.assertAlmostEqual(below, above, places=8)
        self.assertAlmostEqual(cal._log_i0(np.array([3.0]))[0], math.log(np.i0(3.0)), places=12)


class Energy(unittest.TestCase):
    def test_expected_energy_is_the_lattice_sum_averaged_over_the_position(self):
        offsets = np.arange(-12, 13)
        shifts = (np.arange(20) + 0.5) / 20.0 - 0.5  # positions within the cell, midpoint rule
        for rho in (0.0, 0.5, 1.0):
            for spread in (0.42, 0.58):
                total = 0.0
                for sx in shifts:
                    for sy in shifts:
                        dx, dy = np.meshgrid(offsets - sx, offsets - sy)
                        g = np.exp(-(dx ** 2 + dy ** 2) / (2.0 * spread))
                        total += float(np.sum(rho * cal.GAMMA * g ** 2 + (1.0 - rho) * cal.GAMMA * g))
                with self.subTest(rho=rho, spread=spread):
                    self.assertAlmostEqual(cal.expected_energy(rho, spread) / (total / len(shifts) ** 2), 1.0, places=4)


class Fit(unittest.TestCase):
    def test_the_grid_is_the_per_point_likelihood(self):
        frame = cal.read_frame(REPO)
        table = cal.fig1_table(frame)
        for i, j in ((0, 0), (33, 38), (66, 90), (100, 180)):
            with self.subTest(rho=cal.RHO_GRID[i], spread=cal.SPREAD_GRID[j]):
                self.assertAlmostEqual(table[i, j], cal.fig1_log_likelihood(frame, cal.RHO_GRID[i], cal.SPREAD_GRID[j]),
                                       places=9)

    def test_d1_is_d3_at_zero_mean_share(self):
        frame = cal.read_frame(REPO)
        readable = ~np.isnan(frame)
        y, x = np.mgrid[0:10, 0:10]
        g = sum(np.exp(-((x + 0.5 - px) ** 2 + (y + 0.5 - py) ** 2) / (2 * 0.5)) for px, py in cal.TOY_OBJECTS)
        s = 1.0 + 30.0 * g  # Rayleigh: per-component variance sigma^2 + gamma/2 g
        a = frame[readable]
        direct = float(np.sum(np.log(a / s[readable]) - a * a / (2.0 * s[readable])))
        self.assertAlmostEqual(cal.fig1_log_likelihood(frame, 0.0, 0.5), direct, places=9)

    def test_the_fit_is_the_grid_maximum_and_inside_its_interval(self):
        fit = cal.fit(REPO)
        best = fit["best"]
        frame = cal.read_frame(REPO)
        for rho, spread in ((0.0, 0.5), (0.3, 0.5), (0.66, 0.5), (0.9, 0.6), (best["rho"], best["spread"] + 0.05)):
            joint = cal.fig1_log_likelihood(frame, rho, spread) + cal.energy_log_likelihood(cal.expected_energy(rho, spread))
            self.assertLessEqual(joint, best["joint"] + 1e-9)
        self.assertLessEqual(fit["best"]["interval"][0], best["rho"])
        self.assertGreaterEqual(fit["best"]["interval"][1], best["rho"])


if __name__ == "__main__":
    unittest.main()
