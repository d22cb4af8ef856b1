"""Calibration of the track-before-detect measurement readings against the supplement's own
evidence (scenarios/tbd/tbd.hpp; harness/tbd/problem.hpp):

- Fig. 1(a), digitised (experiments/data/tbd-fig1a-frame.csv): the toy's frame, drawn with the
  two objects at (4, 4) and (5, 5). Given the objects, each readable cell's magnitude |z_j| is
  Rice distributed: z_j ~ N(m_j, s_j I2) with m_j = sum of the objects' means mu_j (along e1) and
  s_j = sigma^2 + sum of their c_j. The log-likelihood of the readable cells is a function of
  the reading's parameters.
- Fig. 2: the excess energy sum_j (|z_j|^2 - 2 sigma^2) of the isolated object, read in three
  panels [F] (../shared/tbd-bp-model.md section 1.2): its mean, with the standard error of the
  three readings, against each reading's expected energy sum_j (|mu_j|^2 + 2 c_j).

D3 (mu_j = (sqrt(rho gamma) g_j, 0), c_j = (1 - rho) sigma_S^2 gamma / 2 g_j) is fitted by
maximising the Fig. 1 log-likelihood plus the Gaussian log-likelihood of the Fig. 2 energy over a
grid of rho (step 0.01) and sigma_h^2 (step 0.01 m^2); the profile over rho shows how well the
evidence pins it. D1 is D3 at rho = 0; D2 is evaluated at its own sigma_h^2 (1.5) and at its
best one."""

import math
import os
import re

import numpy as np

FRAME = "experiments/data/tbd-fig1a-frame.csv"
SCENARIO_HEADER = "scenarios/tbd/tbd.hpp"
GAMMA = 60.0           # [S] toy
NOISE = 1.0            # sigma^2 [F]
TOY_OBJECTS = ((4.0, 4.0), (5.0, 5.0))
FIG2_ENERGY = (187.0, 127.0, 222.0)  # [F] excess energy of the isolated object, k = 14, 21, 27
RHO_GRID = np.round(np.arange(0.0, 1.0 + 1e-9, 0.01), 2)
SPREAD_GRID = np.round(np.arange(0.20, 2.0 + 1e-9, 0.01), 2)
D1_SPREAD, D2_SPREAD = 0.5, 1.5
LR_95 = 1.92  # half the 95 % quantile of chi-square(1): a profile likelihood interval


def read_frame(root):
    rows = []
    with open(os.path.join(root, FRAME)) as f:
        for line in f:
            line = line.strip()
            if line and not line.startswith("#"):
                rows.append([float(v) for v in line.split(",")])
    return np.array(rows)  # [row (y, bottom first)][column (x)]


def _spreads(shape, spread):
    rows, columns = shape
    y, x = np.mgrid[0:rows, 0:columns]
    return [np.exp(-((x + 0.5 - px) ** 2 + (y + 0.5 - py) ** 2) / (2.0 * spread)) for px, py in TOY_OBJECTS]


def _log_i0(x):
    x = np.asarray(x, dtype=float)
    small = x < 500.0
    out = np.empty_like(x)
    out[small] = np.log(np.i0(x[small]))
    big = x[~small]
    out[~small] = big - 0.5 * np.log(2.0 * math.pi * big)
    return out


def _rice_log_likelihood(a, nu, s):
    """sum of log Rice(a; nu, s) for per-component variance s."""
    return float(np.sum(np.log(a / s) - (a * a + nu * nu) / (2.0 * s) + _log_i0(a * nu / s)))


def fig1_log_likelihood(frame, rho, spread):
    """D3 (D1 at rho = 0)."""
    g = sum(_spreads(frame.shape, spread))
    readable = ~np.isnan(frame)
    nu = math.sqrt(rho * GAMMA) * g
    s = NOISE + (1.0 - rho) * GAMMA / 2.0 * g
    return _rice_log_likelihood(frame[readable], nu[readable], s[readable])


def fig1_log_likelihood_d2(frame, spread):
    gs = _spreads(frame.shape, spread)
    readable = ~np.isnan(frame)
    nu = GAMMA / (2.0 * math.pi * spread) * sum(gs)
    s = NOISE + sum(g * g for g in gs)
    return _rice_log_likelihood(frame[readable], nu[readable], s[readable])


def expected_energy(rho, spread):
    """sum_j (|mu_j|^2 + 2 c_j) of a cell-centred D3 object at sigma_S^2 = 1 (lattice sums of g and
    g^2 by the integrals 2 pi sigma_h^2 and pi sigma_h^2: relative error below 1e-3 here)."""
    return rho * GAMMA * math.pi * spread + (1.0 - rho) * GAMMA * 2.0 * math.pi * spread


def expected_energy_d2(spread):
    # |mu|^2 = (gamma / (2 pi sigma_h^2))^2 g^2 summed: gamma^2 / (4 pi sigma_h^2); 2 c = 2 g^2: 2 pi sigma_h^2.
    return GAMMA ** 2 / (4.0 * math.pi * spread) + 2.0 * math.pi * spread


def energy_evidence():
    mean = float(np.mean(FIG2_ENERGY))
    se = float(np.std(FIG2_ENERGY, ddof=1) / math.sqrt(len(FIG2_ENERGY)))
    return mean, se


def energy_log_likelihood(energy):
    mean, se = energy_evidence()
    return -0.5 * ((energy - mean) / se) ** 2


def fit(root):
    """The D3 fit, its profile over rho, and the readings D1, D2 under the same evidence."""
    frame = read_frame(root)
    table = np.array([[fig1_log_likelihood(frame, rho, s) + energy_log_likelihood(expected_energy(rho, s))
                       for s in SPREAD_GRID] for rho in RHO_GRID])
    i, j = np.unravel_index(np.argmax(table), table.shape)
    best = {"rho": float(RHO_GRID[i]), "spread": float(SPREAD_GRID[j]), "joint": float(table[i, j])}
    best["fig1"] = fig1_log_likelihood(frame, best["rho"], best["spread"])
    best["energy"] = expected_energy(best["rho"], best["spread"])
    profile = []
    for k, rho in enumerate(RHO_GRID):
        jj = int(np.argmax(table[k]))
        profile.append({"rho": float(rho), "spread": float(SPREAD_GRID[jj]), "joint": float(table[k, jj]),
                        "fig1": fig1_log_likelihood(frame, rho, SPREAD_GRID[jj]),
                        "energy": expected_energy(rho, SPREAD_GRID[jj])})
    inside = [p["rho"] for p in profile if best["joint"] - p["joint"] <= LR_95]
    best["interval"] = (min(inside), max(inside))
    d1 = {"spread": D1_SPREAD, "fig1": fig1_log_likelihood(frame, 0.0, D1_SPREAD),
          "energy": expected_energy(0.0, D1_SPREAD)}
    d1["joint"] = d1["fig1"] + energy_log_likelihood(d1["energy"])
    d2 = {"spread": D2_SPREAD, "fig1": fig1_log_likelihood_d2(frame, D2_SPREAD), "energy": expected_energy_d2(D2_SPREAD)}
    d2["joint"] = d2["fig1"] + energy_log_likelihood(d2["energy"])
    d2_best = max(({"spread": float(s), "fig1": fig1_log_likelihood_d2(frame, s), "energy": expected_energy_d2(s)}
                   for s in SPREAD_GRID), key=lambda r: r["fig1"] + energy_log_likelihood(r["energy"]))
    d2_best["joint"] = d2_best["fig1"] + energy_log_likelihood(d2_best["energy"])
    return {"best": best, "profile": profile, "d1": d1, "d2": d2, "d2_best": d2_best,
            "cells": int(np.sum(~np.isnan(frame))), "unread": int(np.sum(np.isnan(frame)))}


def scenario_constants(root):
    """kMeanShareD3 and kSpreadD3 as written in scenarios/tbd/tbd.hpp."""
    with open(os.path.join(root, SCENARIO_HEADER)) as f:
        text = f.read()
    found = {}
    for name in ("kMeanShareD3", "kSpreadD3"):
        match = re.search(rf"constexpr double {name} = ([0-9.eE+-]+);", text)
        found[name] = float(match.group(1)) if match else None
    return found
