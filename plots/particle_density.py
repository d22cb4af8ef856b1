"""The density of a weighted particle belief: a Gaussian kernel density estimate with Scott's
bandwidth per axis (sd · ESS^(-1/6), ESS = 1/Σw²), its maximum (the belief's mode, as the tbd
REPORT states it) and its values on a grid (as the toy figure draws it)."""

import math

import numpy as np

MODE_GRID = 0.02  # m: spacing of the grid the kernel density estimate's maximum is sought on


def kde_mode(xy, w, sd):
    """The maximum of the Gaussian kernel density estimate of weighted points (Scott's bandwidth
    per axis, sd · ESS^(-1/6)) on a MODE_GRID lattice over mean ± 3 sd."""
    ess = 1.0 / np.sum(w * w)
    h = np.maximum(sd * ess ** (-1.0 / 6.0), 1e-9)
    mean = w @ xy
    axes = [np.arange(mean[i] - 3 * sd[i], mean[i] + 3 * sd[i] + MODE_GRID, MODE_GRID) for i in (0, 1)]
    gx = np.exp(-0.5 * ((axes[0][:, None] - xy[None, :, 0]) / h[0]) ** 2)  # [grid x, point]
    gy = np.exp(-0.5 * ((axes[1][:, None] - xy[None, :, 1]) / h[1]) ** 2)
    density = (gx * w[None, :]) @ gy.T  # [grid x, grid y]
    i, j = np.unravel_index(int(np.argmax(density)), density.shape)
    return float(axes[0][i]), float(axes[1][j])


def belief_density(xy, w, sd, xs, ys):
    """The Gaussian kernel density estimate of weighted particles on the grid xs × ys ([y, x]),
    with kde_mode's bandwidth."""
    h = np.maximum(sd * np.sum(w * w) ** (1.0 / 6.0), 1e-9)
    gx, gy = (np.exp(-0.5 * ((grid[:, None] - xy[None, :, i]) / h[i]) ** 2) / (math.sqrt(2 * math.pi) * h[i])
              for i, grid in enumerate((xs, ys)))
    return (gy * w[None, :]) @ gx.T
