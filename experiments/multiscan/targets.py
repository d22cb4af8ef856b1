"""The multiscan study's data: the targets of a run point (targets.csv: the HPD value of each target's
true location under its belief, and the belief's entropy) and their statistics (p80, median
entropy, tail shares), with standard errors from paired bootstrap resamples of whole trials
(Figure); the methods' names as the REPORT prints them."""

import dataclasses
import math

import numpy as np

from reports.core import data, markdown, stats
from experiments.multiscan.runs import FIGURES, FOLDER

SENSORS = 4  # Sec. IV: four sensors on the corners of the square (scans = 4 × scans per sensor)
CALIBRATED_P80 = 0.80  # a calibrated belief has HPD ~ U(0, 1) (Sec. IV, [50] Sec. 9.7.2): p80 = 0.80
TAIL = 0.9999  # Sec. IV: "the true location is less likely than 99.99 % of the belief"
NEAR_TAIL = 0.99  # reported beside TAIL

LABEL = {"jpda-bp": "JPDA-BP", "msbp": "MSBP", "cv": "CV", "cvh": "CVH",
         "cvs:gamma=0.95": "CVS(0.95)", "cvs:gamma=0.75": "CVS(0.75)", "cvs:gamma=0.55": "CVS(0.55)",
         "cvsh:gamma=0.95": "CVSH(0.95)", "cvsh1:gamma=0.95": "CVSH1(0.95)"}

STATISTICS = ("p80", "entropy", "ge_near", "ge_tail", "p80_likelihood")  # rows of target_statistics()


@dataclasses.dataclass
class Targets:
    """One sweep point of a targets.csv: the targets every method solved, one row each."""
    params: dict  # the point's scenario columns (first row)
    methods: list  # in the run's order
    trial: np.ndarray  # the trial of each row
    hpd: np.ndarray  # rows × methods
    entropy: np.ndarray  # rows × methods
    hpd_likelihood: np.ndarray  # rows × methods: HPD with particles ranked by likelihood (NaN: not recorded)

    def has_likelihood(self):
        """Whether the run recorded hpd_likelihood (runs made before that column have none)."""
        return bool(np.all(np.isfinite(self.hpd_likelihood)))


def read_targets(root, folder):
    """{point: Targets} of folder/targets.csv; a point keeps the (trial, target) pairs that every
    method solved, so that methods are compared on the same targets. hpd_likelihood is NaN where
    the run did not record it."""
    rows = data.read_rows(root, f"{folder}/targets.csv")
    if not rows:
        raise data.DataError(f"{folder}/targets.csv: no rows")
    cells, params, methods = {}, {}, {}
    for r in rows:
        point = int(r["point"])
        params.setdefault(point, r)
        order = methods.setdefault(point, [])
        if r["algorithm"] not in order:
            order.append(r["algorithm"])
        hpd, entropy = data.num(r, "hpd"), data.num(r, "entropy")
        likelihood = data.num(r, "hpd_likelihood") if r.get("hpd_likelihood") else None
        if hpd is not None and entropy is not None:
            cells.setdefault((point, r["algorithm"]), {})[(int(r["trial"]), int(r["target"]))] = (
                hpd, entropy, math.nan if likelihood is None else likelihood)
    out = {}
    for point in sorted(params):
        keys = sorted(set.intersection(*(set(cells.get((point, m), {})) for m in methods[point])))
        if not keys:
            raise data.DataError(f"{folder}/targets.csv: point {point} has no target that every method solved")
        values = np.array([[cells[(point, m)][k] for m in methods[point]] for k in keys])  # rows × methods × 3
        out[point] = Targets(params[point], methods[point], np.array([k[0] for k in keys]),
                             values[:, :, 0], values[:, :, 1], values[:, :, 2])
    return out


def resample_weights(trial, resamples=stats.RESAMPLES):
    """How often each row enters each resample of whole trials (resamples × rows): the draws of
    core.stats.cluster_bootstrap (same seed; groups = the trials in increasing order)."""
    trials, group = np.unique(trial, return_inverse=True)
    n = len(trials)
    rng = np.random.Generator(np.random.PCG64(stats.SEED))
    weights = np.empty((resamples, len(trial)), dtype=np.int64)
    for r in range(resamples):
        weights[r] = np.bincount(rng.integers(0, n, n), minlength=n)[group]
    return weights


def trial_resamples(trial, columns, statistic):
    """statistic(columns) on the data, and on stats.RESAMPLES resamples of whole trials (the rows
    of each resample, repeated as resample_weights says), made once for a vector of statistics of
    many methods, so that every method sees the same resampled trials (paired)."""
    point = np.asarray(statistic(columns), dtype=float)
    weights = resample_weights(trial)
    draws = np.empty((len(weights),) + point.shape)
    for r, w in enumerate(weights):
        draws[r] = statistic(np.repeat(columns, w, axis=0))
    return point, draws


def target_statistics(columns):
    """Rows STATISTICS × methods of [HPD | entropy | likelihood-ranked HPD] columns: p80 (numpy's
    linear percentile, as plots/multiscan_cdf.py), median entropy, shares of HPD >= NEAR_TAIL and
    >= TAIL, p80 of the likelihood-ranked HPD (NaN where not recorded)."""
    m = columns.shape[1] // 3
    hpd, entropy, likelihood = columns[:, :m], columns[:, m:2 * m], columns[:, 2 * m:]
    return np.stack([np.percentile(hpd, 80, axis=0), np.median(entropy, axis=0),
                     np.mean(hpd >= NEAR_TAIL, axis=0), np.mean(hpd >= TAIL, axis=0),
                     np.percentile(likelihood, 80, axis=0)])


def _lerp(a, b, t):
    """numpy's percentile interpolation, operation for operation (numpy.lib.function_base._lerp)."""
    diff = b - a
    return np.where(t >= 0.5, b - diff * (1 - t), a + diff * t)


def _weighted_order_statistics(column, row_weights, ranks):
    """The ranks[r, k]-th smallest (0-based) value of column in resample r, where row i appears
    row_weights[i, r] times (resamples × k); NaN where a NaN enters the resample (numpy's rule:
    a NaN makes the percentile and the median NaN)."""
    order = np.argsort(column, kind="stable")  # NaN last
    # The rows' weights gathered in sorted order (whole rows: fast), then laid out resample by
    # resample, so that each running count runs along contiguous memory.
    cumulative = np.cumsum(np.ascontiguousarray(row_weights[order].T), axis=1)  # resamples × sorted rows
    position = np.stack([(cumulative <= ranks[:, [k]]).sum(axis=1) for k in range(ranks.shape[1])], axis=1)
    values = column[order][np.minimum(position, len(column) - 1)]
    has_nan = (row_weights[np.isnan(column)] > 0).any(axis=0)
    values[has_nan] = np.nan
    return values


def _weighted_p80(column, row_weights, n):
    """np.percentile(resample, 80) of each resample, as numpy computes it: the linear
    interpolation between the order statistics around (n − 1)·0.8."""
    virtual = (n - 1) * np.true_divide(80, 100)
    previous = np.floor(virtual)
    above = virtual >= n - 1  # numpy takes the largest value (index −1) there
    previous[above] = -1
    gamma = virtual - previous
    low = np.where(above, n - 1, previous).astype(np.int64)
    high = np.where(above, n - 1, previous + 1).astype(np.int64)
    values = _weighted_order_statistics(column, row_weights, np.stack([low, high], axis=1))
    return _lerp(values[:, 0], values[:, 1], gamma)


def _weighted_median(column, row_weights, n):
    """np.median of each resample: the middle value, or the mean of the two middle values."""
    values = _weighted_order_statistics(column, row_weights, np.stack([(n - 1) // 2, n // 2], axis=1))
    return np.where(n % 2 == 1, values[:, 0], (values[:, 0] + values[:, 1]) / 2)


def resampled_target_statistics(columns, weights):
    """target_statistics of every resample at once (resamples × STATISTICS × methods), bit for bit
    what target_statistics gives on np.repeat(columns, weights[r], axis=0): the percentiles and
    medians from order statistics of the weighted rows, the shares from weighted counts."""
    m = columns.shape[1] // 3
    hpd, entropy, likelihood = columns[:, :m], columns[:, m:2 * m], columns[:, 2 * m:]
    n = weights.sum(axis=1)
    row_weights = np.ascontiguousarray(weights.T)  # rows × resamples
    out = np.empty((len(weights), len(STATISTICS), m))
    for j in range(m):
        out[:, 0, j] = _weighted_p80(hpd[:, j], row_weights, n)
        out[:, 1, j] = _weighted_median(entropy[:, j], row_weights, n)
        out[:, 4, j] = _weighted_p80(likelihood[:, j], row_weights, n)
    for row, threshold in ((2, NEAR_TAIL), (3, TAIL)):
        out[:, row, :] = (weights @ (hpd >= threshold).astype(np.int64)) / n[:, None]
    return out


def ks_uniform(values):
    """Kolmogorov-Smirnov distance of the values from U(0, 1) (plots/multiscan_cdf.py's)."""
    u = np.sort(np.clip(values, 0.0, 1.0))
    k = np.arange(1, len(u) + 1)
    return float(max(np.max(k / len(u) - u), np.max(u - (k - 1) / len(u))))


class Figure:
    """The targets of one run point with their statistics, on the data and on paired resamples."""

    def __init__(self, targets, label):
        self.label, self.targets, self.methods = label, targets, targets.methods
        columns = np.hstack([targets.hpd, targets.entropy, targets.hpd_likelihood])
        point = target_statistics(columns)
        draws = resampled_target_statistics(columns, resample_weights(targets.trial))
        self.point = {s: point[i][None, :] for i, s in enumerate(STATISTICS)}  # 1 × methods
        self.draws = {s: draws[:, i, :] for i, s in enumerate(STATISTICS)}  # resamples × methods

    def index(self, method):
        if method not in self.methods:
            raise data.DataError(f"{self.label}: no targets of {method}")
        return self.methods.index(method)

    def value(self, statistic, method):
        return float(self.point[statistic][0, self.index(method)])

    def se(self, statistic, method):
        return float(np.std(self.draws[statistic][:, self.index(method)], ddof=1))

    def interval(self, statistic, method):
        """The 95 % bootstrap percentile interval over trials (core.stats.percentile_interval)."""
        return stats.percentile_interval(self.draws[statistic][:, self.index(method)])

    def ks(self, method, ranking="hpd"):
        values = self.targets.hpd if ranking == "hpd" else self.targets.hpd_likelihood
        return ks_uniform(values[:, self.index(method)])

    def trials(self):
        return len(np.unique(self.targets.trial))

    def holds(self, rule):
        """(rule on the data, share of resamples where it holds); rule(figure, statistics) -> bools."""
        return bool(rule(self, self.point)[0]), float(np.mean(rule(self, self.draws)))

    def pm(self, statistic, method):
        return markdown.pm(self.value(statistic, method), self.se(statistic, method))

    def pm_interval(self, statistic, method):
        """"value ± SE [lo, hi]": the bootstrap SE and 95 % percentile interval, to the SE's decimals."""
        se = self.se(statistic, method)
        return f"{self.pm(statistic, method)} {markdown.interval(*self.interval(statistic, method), se)}"

    def pm_percent(self, statistic, method):
        return markdown.pm(100 * self.value(statistic, method), 100 * self.se(statistic, method)) + " %"


def load_figures(root):
    """{"fig3": Figure, ...}: each figure run has one sweep point."""
    out = {}
    for name, label in FIGURES:
        points = read_targets(root, f"{FOLDER}/{name}")
        if len(points) != 1:
            raise data.DataError(f"{FOLDER}/{name}/targets.csv: {len(points)} points, expected one")
        out[name] = Figure(next(iter(points.values())), label)
    return out


def label(method):
    return LABEL.get(method, method)


def particles_text(n):
    """A particle count as the REPORT prints it, thousands set off by a space (10 000)."""
    return f"{n:,}".replace(",", " ")


def scans(params):
    return SENSORS * int(data.num(params, "scans_per_sensor"))
