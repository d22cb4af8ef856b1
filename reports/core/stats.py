"""Sampling statistics for the checks: means with standard errors, percentiles, and bootstrap
intervals over trials (resampling whole trials, so that targets or steps of one trial stay
together). Resamples come from numpy's PCG64 with a fixed seed, so a check gives the same numbers
on every run."""

import math

import numpy as np

RESAMPLES = 1000  # bootstrap resamples of a statistic
SEED = 20261204  # the bootstrap's fixed seed


def finite(values):
    return [float(v) for v in values if v is not None and math.isfinite(float(v))]


def mean_se(values):
    """(mean, standard error of the mean, n) of the finite values; se NaN below two values."""
    v = finite(values)
    n = len(v)
    if n == 0:
        return math.nan, math.nan, 0
    m = math.fsum(v) / n
    if n < 2:
        return m, math.nan, n
    var = math.fsum((x - m) ** 2 for x in v) / (n - 1)
    return m, math.sqrt(var / n), n


def sd(values):
    """Sample standard deviation of the finite values (NaN below two)."""
    m, se, n = mean_se(values)
    return se * math.sqrt(n) if n >= 2 else math.nan


def paired(a, b):
    """(mean, se, n) of a[k] - b[k] over the keys both dicts hold with finite values: the paired
    difference of two algorithms on identical trials."""
    keys = [k for k in a if k in b and a[k] is not None and b[k] is not None
            and math.isfinite(a[k]) and math.isfinite(b[k])]
    return mean_se([a[k] - b[k] for k in keys])


def percentile(values, q):
    """The q-th percentile (0-100) by linear interpolation between order statistics (numpy's
    default; multiscan_cdf.py's p80)."""
    v = np.asarray(finite(values))
    return float(np.percentile(v, q)) if len(v) else math.nan


def share(values, predicate):
    v = finite(values)
    return sum(1 for x in v if predicate(x)) / len(v) if v else math.nan


def cluster_bootstrap(groups, statistic, resamples=RESAMPLES, seed=SEED):
    """Bootstrap of statistic(values) where values come in groups (a trial's targets): each
    resample draws len(groups) groups with replacement and pools their values. Returns the
    resampled statistics as a numpy array."""
    groups = [np.asarray(g, dtype=float) for g in groups if len(g)]
    rng = np.random.Generator(np.random.PCG64(seed))
    out = np.empty(resamples)
    for r in range(resamples):
        pick = rng.integers(0, len(groups), len(groups))
        out[r] = statistic(np.concatenate([groups[i] for i in pick]))
    return out


def bootstrap_se(groups, statistic, resamples=RESAMPLES, seed=SEED):
    """(statistic on all values, bootstrap standard error, 95 % percentile interval)."""
    pooled = np.concatenate([np.asarray(g, dtype=float) for g in groups if len(g)])
    value = float(statistic(pooled))
    draws = cluster_bootstrap(groups, statistic, resamples, seed)
    return value, float(np.std(draws, ddof=1)), percentile_interval(draws)


def percentile_interval(draws, level=0.95):
    """The bootstrap percentile interval of a statistic from its resampled values: their
    (1 - level) / 2 and (1 + level) / 2 quantiles (numpy's linear interpolation)."""
    tail = 50.0 * (1.0 - level)
    return float(np.percentile(draws, tail)), float(np.percentile(draws, 100.0 - tail))


def parametric_resamples(means, ses, resamples, seed=SEED):
    """Draws of independent normal estimates N(mean, se²) (se NaN or missing: held fixed), one
    row per resample: the sampling error of a rule evaluated on many summary means at once."""
    m = np.asarray(means, dtype=float)
    s = np.nan_to_num(np.asarray(ses, dtype=float), nan=0.0)
    rng = np.random.Generator(np.random.PCG64(seed))
    return m + s * rng.standard_normal((resamples, len(m)))
