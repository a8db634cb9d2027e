"""Outlier rules for the record means of a campaign: pooled robust scatter, and its power.

The pooled rule
    Repeats of one condition are few (3..7 on the thesis' rig), too few for a
    test that estimates the scatter from the condition alone (Grubbs flags a
    +30 % record among 4 repeats with 2 % scatter only about a third of the
    time, and never among 3).  The record-to-record scatter of a rig is much
    the same from condition to condition *relative to the level* (pin
    alignment, temperature, wear act multiplicatively: a campaign spans mu
    from 0.3 to above 2, and an absolute scatter pooled over it would be set by
    the high-mu conditions and blind the low ones).  So the rule pools a
    *relative* scatter over the whole campaign:

    1. per condition (3 or more usable records), the relative deviations
       ``d_i = mu_i / median - 1`` from the condition's median;
    2. the *inner* deviations of each condition -- the sorted ``|d|`` without
       the largest (a single bad record per condition cannot inflate the
       scale) and without the exact zero of the median record when ``n`` is
       odd -- each divided by its consistency constant ``q_n`` (the median of
       the inner ``|d|`` of ``n`` standard normal values), pooled over the
       campaign; their median is the pooled relative scatter ``sigma``;
    3. a record's score is ``z = |d| / sigma``, its departure from its
       condition's median in pooled-scatter units; the records of a condition
       whose ``z`` exceeds the threshold ``t_n`` are flagged (at most
       ``(n - 1) // 2``, largest ``z`` first, so that the majority stays).

    The threshold ``t_n`` is calibrated for the campaign's own layout (how
    many conditions have how many records): it is the ``1 - 0.8 alpha``
    quantile of a condition's largest ``z`` in seeded simulations of the same
    layout with normal scatter and no outlier (0.8: a margin for the
    simulation's own noise), so a condition without an outlier is flagged with
    probability at most ``alpha`` whatever the number of repeats.  Conditions
    with 2 records are not tested and do not enter the scale.  With fewer than
    :data:`MIN_POOL` inner deviations in the campaign (or a pooled scatter of
    zero) the scatter cannot be pooled; the caller then falls back to Grubbs.

:func:`outlier_power` measures the power and the false-alarm rate of both
rules by a seeded Monte-Carlo simulation (the table in the user guide).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ..base.errors import InputError

__all__ = ["MIN_POOL", "PooledResult", "pooled_outliers", "pooled_thresholds",
           "inner_count", "outlier_power", "grubbs_critical"]

#: Fewest inner deviations (over the campaign) from which a scatter is pooled.
MIN_POOL = 6
#: Seed of the calibration simulations (results are reproducible).
CALIBRATION_SEED = 20261125
#: Simulated conditions per record count in a calibration.
CALIBRATION_CONDITIONS = 60000
#: The calibration quantile is ``1 - MARGIN * alpha``.
MARGIN = 0.8
#: Relative scatter of the calibration simulations (the rule is scale-free).
_SIM_SCATTER = 0.01


def _inner(sorted_abs: np.ndarray, n: int) -> np.ndarray:
    """The inner deviations of sorted ``|d|`` along the last axis (size ``n``)."""
    lo = 1 if n % 2 else 0
    return sorted_abs[..., lo:n - 1]


def inner_count(n: int) -> int:
    """Inner deviations a condition of ``n`` records contributes to the pooled scatter."""
    return 0 if n < 3 else n - 1 - (n % 2)


@lru_cache(maxsize=64)
def _consistency(n: int) -> float:
    """Median of the inner ``|x - median|`` of ``n`` standard normal values (seeded)."""
    rng = np.random.default_rng(CALIBRATION_SEED + n)
    x = rng.standard_normal((400000 // n + 1, n))
    a = np.sort(np.abs(x - np.median(x, axis=1, keepdims=True)), axis=1)
    return float(np.median(_inner(a, n)))


def _scores(groups: Mapping[int, np.ndarray]) -> tuple[dict[int, np.ndarray], np.ndarray]:
    """Scores ``z`` of every record and the pooled scatter, vectorised over replicates.

    ``groups[n]`` has shape ``(R, m, n)``: ``R`` replicates of ``m`` conditions
    with ``n`` records each (positive values).  Returns ``z`` in the same
    shapes and ``sigma`` of shape ``(R,)``.
    """
    absdev: dict[int, np.ndarray] = {}
    pooled = []
    for n, x in groups.items():
        med = np.median(x, axis=-1, keepdims=True)
        a = np.abs(x / med - 1.0)
        absdev[n] = a
        inner = _inner(np.sort(a, axis=-1), n) / _consistency(n)
        pooled.append(inner.reshape(inner.shape[0], -1))
    sigma = np.median(np.concatenate(pooled, axis=1), axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = {n: a / sigma[:, None, None] for n, a in absdev.items()}
    return z, sigma


@lru_cache(maxsize=256)
def pooled_thresholds(layout: tuple[tuple[int, int], ...], alpha: float) -> dict[int, float]:
    """Thresholds ``t_n`` of the pooled rule for a campaign layout.

    Parameters
    ----------
    layout : tuple of (n, m)
        ``m`` conditions with ``n`` usable records each (``n >= 3``).
    alpha : float
        Largest probability that a condition without an outlier is flagged.

    Returns
    -------
    dict
        ``n -> t_n``, the ``1 - MARGIN * alpha`` quantile of a condition's
        largest score in seeded null simulations of the layout.
    """
    total = sum(m for _, m in layout)
    reps = max(200, CALIBRATION_CONDITIONS // max(total, 1))
    rng = np.random.default_rng(CALIBRATION_SEED)
    groups = {n: 1.0 + _SIM_SCATTER * rng.standard_normal((reps, m, n)) for n, m in layout}
    z, _ = _scores(groups)
    return {n: float(np.quantile(zn.max(axis=-1), 1.0 - MARGIN * alpha))
            for n, zn in z.items()}


@dataclass
class PooledResult:
    """The outcome of the pooled rule on one campaign.

    Attributes
    ----------
    sigma : float
        Pooled relative record-to-record scatter (NaN when it cannot be pooled).
    pool : int
        Inner deviations it was pooled from.
    z : list of numpy.ndarray
        Per condition, each record's departure from the condition's median in
        units of ``sigma`` (NaN for conditions of fewer than 3 records).
    threshold : list of float
        Per condition, ``t_n`` (NaN when not tested).
    flagged : list of list of int
        Per condition, the positions of the flagged records.
    """

    sigma: float
    pool: int
    z: list[np.ndarray]
    threshold: list[float]
    flagged: list[list[int]]

    @property
    def pooled(self) -> bool:
        """Whether the scatter could be pooled (else nothing is flagged)."""
        return math.isfinite(self.sigma)


def pooled_outliers(conditions: Sequence[Sequence[float] | np.ndarray],
                    alpha: float = 0.01) -> PooledResult:
    """Apply the pooled rule (module docstring) to the record means of a campaign.

    Parameters
    ----------
    conditions : sequence of array-like
        Per condition, the usable record means (positive).
    alpha : float
        Per-condition false-alarm probability (0 < alpha < 0.5).

    Returns
    -------
    PooledResult
    """
    if not 0.0 < alpha < 0.5:
        raise InputError(f"the outlier alpha must be in (0, 0.5), got {alpha!r}")
    values = [np.asarray(c, dtype=float) for c in conditions]
    for v in values:
        if v.size and not np.all(np.isfinite(v) & (v > 0)):
            raise InputError("the pooled outlier rule needs positive, finite record means")
    nan_z = [np.full(v.size, math.nan) for v in values]
    nothing: list[list[int]] = [[] for _ in values]
    tested = [i for i, v in enumerate(values) if v.size >= 3]
    pool = sum(inner_count(values[i].size) for i in tested)
    if pool < MIN_POOL:
        return PooledResult(math.nan, pool, nan_z, [math.nan] * len(values), nothing)
    sizes = sorted({values[i].size for i in tested})
    groups = {n: np.stack([values[i] for i in tested if values[i].size == n])[None]
              for n in sizes}
    z, sigma = _scores(groups)
    if not sigma[0] > 0:  # identical repeats: no scatter to measure departures against
        return PooledResult(math.nan, pool, nan_z, [math.nan] * len(values), nothing)
    layout = tuple((n, groups[n].shape[1]) for n in sizes)
    t = pooled_thresholds(layout, float(alpha))
    seen = dict.fromkeys(sizes, 0)
    thresholds = [math.nan] * len(values)
    flagged: list[list[int]] = [[] for _ in values]
    for i in tested:
        n = values[i].size
        zi = z[n][0, seen[n]]
        seen[n] += 1
        nan_z[i] = zi
        thresholds[i] = t[n]
        over = [int(j) for j in np.argsort(-zi, kind="stable") if zi[j] > t[n]]
        flagged[i] = sorted(over[:(n - 1) // 2])
    return PooledResult(float(sigma[0]), pool, nan_z, thresholds, flagged)


def grubbs_critical(n: int, alpha: float) -> float:
    """Two-sided Grubbs critical value for ``n`` values at significance ``alpha``."""
    from scipy import stats

    t = float(stats.t.ppf(1.0 - alpha / (2.0 * n), n - 2))
    return (n - 1) / math.sqrt(n) * math.sqrt(t * t / (n - 2 + t * t))


def _grubbs_flags(x: np.ndarray, alpha: float) -> np.ndarray:
    """Grubbs decisions for the last axis of ``x`` (vectorised): the flagged position or -1."""
    n = x.shape[-1]
    if n < 4:  # the campaign applies Grubbs from 4 records
        return np.full(x.shape[:-1], -1)
    sd = x.std(axis=-1, ddof=1, keepdims=True)
    g = np.abs(x - x.mean(axis=-1, keepdims=True)) / sd
    i = g.argmax(axis=-1)
    return np.where(np.take_along_axis(g, i[..., None], -1)[..., 0]
                    > grubbs_critical(n, alpha), i, -1)


def outlier_power(n: int, shifts: Sequence[float] = (0.2, 0.3, 0.5), *,
                  scatter: float = 0.02, conditions: int = 8, trials: int = 1000,
                  alpha: float = 0.01, seed: int = 0, every_condition: bool = False
                  ) -> dict[str, float]:
    """Seeded Monte-Carlo power and false-alarm rate of the pooled rule and of Grubbs.

    A simulated campaign has ``conditions`` conditions of ``n`` records with
    relative normal scatter ``scatter`` about levels spread over 0.3..2.0.
    For the power, one record of one condition is multiplied by ``1 + shift``
    (a single outlier in the campaign), or one record of every condition with
    ``every_condition`` (a bad pin in each condition: the hardest case for the
    pooled scale); the power is the fraction of outliers dropped.  The
    false-alarm rate is the fraction of conditions without an outlier in which
    some record is flagged.

    Parameters
    ----------
    n : int
        Records per condition (3 or more).
    shifts : sequence of float
        Relative outlier sizes (0.3: +30 %).
    scatter, conditions, trials, alpha, seed
        Simulation settings; ``alpha`` is passed to both rules.
    every_condition : bool
        Put an outlier in every condition instead of one.

    Returns
    -------
    dict
        ``"pooled +30%"``, ``"grubbs +30%"``... (fraction of trials in which the
        outlier is flagged), ``"pooled false alarms"``, ``"grubbs false alarms"``.
    """
    if n < 3 or conditions < 1 or trials < 1:
        raise InputError(f"outlier_power needs n >= 3, conditions >= 1, trials >= 1; got "
                         f"n = {n}, conditions = {conditions}, trials = {trials}")
    rng = np.random.default_rng(seed)
    level = np.linspace(0.3, 2.0, conditions)[None, :, None]
    x = level * (1.0 + scatter * rng.standard_normal((trials, conditions, n)))
    t = pooled_thresholds(((n, conditions),), float(alpha))[n]
    out: dict[str, float] = {}
    z, _ = _scores({n: x})
    out["pooled false alarms"] = float(np.mean(z[n].max(axis=-1) > t))
    out["grubbs false alarms"] = float(np.mean(_grubbs_flags(x, alpha) >= 0))
    if every_condition:
        rows, which = np.indices((trials, conditions)).reshape(2, -1)
    else:
        rows, which = np.arange(trials), rng.integers(0, conditions, trials)
    for shift in shifts:
        bad = x.copy()
        bad[rows, which, 0] *= 1.0 + shift
        zb, _ = _scores({n: bad})
        hit = zb[n][rows, which, 0]
        top = zb[n][rows, which].max(axis=-1)
        out[f"pooled +{shift:.0%}"] = float(np.mean((hit > t) & (hit >= top)))
        out[f"grubbs +{shift:.0%}"] = float(np.mean(_grubbs_flags(bad, alpha)[rows, which] == 0))
    return out
