"""Standard errors that survive model error: sandwich, bootstrap, residual checks.

The asymptotic standard errors of :func:`frictionlaws.fitting.fit` assume the
law is right and the scatter homoskedastic.  This module supplies the two
alternatives a fit may ask for (``uncertainty=``):

``"sandwich"``
    The heteroskedasticity-robust (HC3) covariance
    ``(J'J)^-1 J' diag(e_i^2 / (1 - h_i)^2) J (J'J)^-1`` with the Jacobian ``J``
    of the (weighted) residuals at the optimum and the leverages ``h_i``.
``"bootstrap"``
    A seeded bootstrap that resamples whole *conditions* (rows with the same
    variables, or the dataset's ``condition_id`` column), refits each replicate
    from the optimum (in parallel with joblib when ``n_jobs`` > 1) and reports
    the replicates' standard deviation with BCa (or percentile) intervals, for
    the parameters and the law's derived quantities alike.

:func:`residual_structure` tests residuals ordered by each variable (a runs test
of their signs and their lag-1 autocorrelation); structure there means the law
misses a trend and the asymptotic errors are too narrow.
"""

from __future__ import annotations

import itertools
import math
import warnings
from collections.abc import Callable, Iterator, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..parallel import batches, local_workers, starmap_local
from .lsq import least_squares_solve
from .resampling import MIN_DETERMINED, ZERO_SPREAD, no_spread

__all__ = ["UNCERTAINTY_METHODS", "INTERVALS", "NARROW_RATIO", "STRUCTURE_ALPHA",
           "check_uncertainty_options", "condition_ids", "sandwich_cov",
           "residual_structure", "residual_structures", "Refit", "BootstrapResult",
           "bootstrap", "intervals", "rank", "MIN_DETERMINED", "ZERO_SPREAD"]

#: Uncertainty methods of a fit.
UNCERTAINTY_METHODS = ("asymptotic", "sandwich", "bootstrap")
#: Bootstrap interval kinds.
INTERVALS = ("bca", "percentile")
#: A robust/asymptotic standard-error ratio above which the asymptotic errors are too narrow.
NARROW_RATIO = 1.5
#: Family-wise level of the residual-structure tests (Bonferroni over the tests made).
STRUCTURE_ALPHA = 0.05
#: Largest number of bootstrap replicates.
MAX_BOOT = 100_000
# MIN_DETERMINED and ZERO_SPREAD: the one rule of every resampling
# (frictionlaws.fitting.resampling), named here too.


def check_uncertainty_options(uncertainty: Any, n_boot: Any, n_jobs: Any,
                              interval: Any) -> None:
    """Refuse unknown methods and nonsense counts with an :class:`InputError`.

    Parameters
    ----------
    uncertainty : str
        One of :data:`UNCERTAINTY_METHODS`.
    n_boot : int
        Bootstrap replicates, 20..100000.
    n_jobs : int
        joblib workers: -1 (one per core) or 1..1024.
    interval : str
        One of :data:`INTERVALS`.
    """
    if uncertainty not in UNCERTAINTY_METHODS:
        raise InputError(f"uncertainty must be one of {', '.join(UNCERTAINTY_METHODS)}, "
                         f"not {uncertainty!r}", option="uncertainty")
    if isinstance(n_boot, bool) or not isinstance(n_boot, (int, np.integer)) or not (
            20 <= n_boot <= MAX_BOOT):
        raise InputError(f"n_boot must be a whole number 20..{MAX_BOOT}, not {n_boot!r}",
                         option="n_boot")
    if isinstance(n_jobs, bool) or not isinstance(n_jobs, (int, np.integer)) or not (
            n_jobs == -1 or 1 <= n_jobs <= 1024):
        raise InputError(f"n_jobs must be -1 or a whole number 1..1024, not {n_jobs!r}",
                         option="n_jobs")
    if interval not in INTERVALS:
        raise InputError(f"interval must be one of {', '.join(INTERVALS)}, not {interval!r}",
                         option="interval")


def condition_ids(arrays: Mapping[str, np.ndarray], variables: Sequence[str],
                  conditions: np.ndarray | None = None) -> np.ndarray:
    """One integer per row naming its condition.

    Parameters
    ----------
    arrays : mapping of str to ndarray
        The fit's arrays (SI).
    variables : sequence of str
        The variables that define a condition (the law's, or every variable present).
    conditions : ndarray, optional
        An explicit condition label per row (a dataset's ``condition_id`` column); it wins.

    Returns
    -------
    ndarray of int
        Rows with equal ids belong to the same condition.
    """
    if conditions is not None:
        return np.unique(np.asarray(conditions).astype(str), return_inverse=True)[1]
    n = int(np.asarray(arrays["mu"]).size)
    cols = [np.asarray(arrays[v], float) for v in variables if v in arrays]
    if not cols:
        return np.arange(n)
    table = np.column_stack(cols)
    return np.unique(table, axis=0, return_inverse=True)[1].ravel()


def sandwich_cov(jac: np.ndarray, resid: np.ndarray) -> np.ndarray | None:
    """HC3 sandwich covariance from the residual Jacobian and the residuals.

    Parameters
    ----------
    jac : ndarray, shape (n, k)
        Jacobian of the (weighted) model values with respect to the parameters.
    resid : ndarray, shape (n,)
        (Weighted) residuals at the optimum.

    Returns
    -------
    ndarray or None
        The k x k covariance, or None when ``J'J`` is singular or not finite.
    """
    if not np.all(np.isfinite(jac)) or not np.all(np.isfinite(resid)):
        return None
    jtj = jac.T @ jac
    if np.linalg.matrix_rank(jtj) < jtj.shape[0]:
        return None
    bread = np.linalg.inv(jtj)
    lev = np.einsum("ij,jk,ik->i", jac, bread, jac)
    lev = np.clip(lev, 0.0, 1.0 - 1e-8)
    e2 = (resid / (1.0 - lev)) ** 2
    meat = (jac * e2[:, None]).T @ jac
    return bread @ meat @ bread


@dataclass(frozen=True)
class Structure:
    """The strongest sign of residual structure found by :func:`residual_structure`."""

    variable: str
    test: str
    statistic: float
    p_value: float
    n_tests: int

    @property
    def significant(self) -> bool:
        """Bonferroni-adjusted p below :data:`STRUCTURE_ALPHA`."""
        return self.p_value * self.n_tests < STRUCTURE_ALPHA

    def describe(self) -> str:
        """One phrase for a warning."""
        what = ("too few sign runs" if self.test == "runs" else "lag-1 autocorrelation")
        return (f"residuals ordered by {self.variable} show structure ({what} "
                f"{self.statistic:.3g}, p = {self.p_value:.2g} before, "
                f"{min(1.0, self.p_value * self.n_tests):.2g} after correction for "
                f"{self.n_tests} tests)")


def _runs_p(e: np.ndarray) -> tuple[float, float]:
    """Number of sign runs and its one-sided p (too few runs) by the normal approximation."""
    s = np.sign(e)
    runs, p = _runs_rows(s[s != 0][None, :])
    return float(runs[0]), float(p[0])


def _runs_rows(s: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_runs_p` of sign rows ``s`` (``(B, m)``, no zeros): runs and p, NaN where
    a row has one sign only (p also where the variance vanishes)."""
    n1, n2 = np.sum(s > 0, axis=1).astype(float), np.sum(s < 0, axis=1).astype(float)
    runs = 1.0 + np.sum(s[:, 1:] != s[:, :-1], axis=1)
    n = n1 + n2
    one_sign = (n1 == 0) | (n2 == 0)
    with np.errstate(divide="ignore", invalid="ignore"):
        mean = 2.0 * n1 * n2 / n + 1.0
        var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n**2 * (n - 1))
        z = (runs - mean) / np.sqrt(np.where(var > 0, var, 1.0))
    p = _norm_cdf(z)
    return (np.where(one_sign, math.nan, runs),
            np.where(one_sign | ~(var > 0), math.nan, p))


def _lag1_p(e: np.ndarray) -> tuple[float, float]:
    """Lag-1 autocorrelation and its one-sided p (positive correlation) under independence."""
    r1, p = _lag1_rows(np.asarray(e, float)[None, :])
    return float(r1[0]), float(p[0])


def _lag1_rows(e: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_lag1_p` of rows ``e`` (``(B, n)``): NaN where a row does not vary."""
    d = e - e.mean(axis=1, keepdims=True)
    den = np.sum(d**2, axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        r1 = np.sum(d[:, 1:] * d[:, :-1], axis=1) / den
    n = e.shape[1]
    p = _norm_cdf(-(r1 + 1.0 / n) * math.sqrt(n))
    return np.where(den > 0, r1, math.nan), np.where(den > 0, p, math.nan)


def residual_structures(resid: np.ndarray, arrays: Mapping[str, np.ndarray],
                        variables: Sequence[str]) -> list[Structure | None]:
    """:func:`residual_structure` of ``B`` fits on equally many rows at once.

    Parameters
    ----------
    resid : numpy.ndarray
        The weighted residuals, ``(B, n)``.
    arrays : mapping
        Each variable's values, ``(B, n)``.
    variables : sequence of str
        The variables to order the rows by (those that vary in a row's fit).

    Returns
    -------
    list
        One :class:`Structure` (or None) per row, as :func:`residual_structure` gives it.
    """
    out: list[Structure | None] = [None] * len(resid)
    names = [v for v in variables if v in arrays]
    if resid.shape[1] < 8 or not names:
        return out
    varies = np.array([np.ptp(arrays[v], axis=1) > 0 for v in names]).reshape(len(names), -1)
    fine = np.all(np.isfinite(resid), axis=1)
    for pattern in {tuple(col) for col in varies.T}:
        present = [v for v, on in zip(names, pattern) if on]
        rows = np.flatnonzero(fine & np.all(varies.T == pattern, axis=1))
        if not present or not rows.size:
            continue
        tests: list[tuple[str, str, np.ndarray, np.ndarray]] = []
        for var in present:
            others = [arrays[o][rows] for o in reversed(present) if o != var]
            order = np.lexsort([*others, arrays[var][rows]], axis=-1)
            tests += _tests(np.take_along_axis(resid[rows], order, axis=1), var)
        _strongest(tests, rows, out)
    return out


def _tests(e: np.ndarray, var: str) -> list[tuple[str, str, np.ndarray, np.ndarray]]:
    """The runs and lag-1 tests of ordered residual rows ``e``: (var, test, statistic, p)."""
    signs = np.sign(e)
    plain = np.all(signs != 0, axis=1)
    runs, p_runs = np.full(len(e), math.nan), np.full(len(e), math.nan)
    runs[plain], p_runs[plain] = _runs_rows(signs[plain])
    for i in np.flatnonzero(~plain):  # a residual of exactly 0: its sign is left out
        runs[i], p_runs[i] = _runs_p(e[i])
    r1, p_lag = _lag1_rows(e)
    return [(var, "runs", runs, p_runs), (var, "lag1", r1, p_lag)]


def _strongest(tests: list[tuple[str, str, np.ndarray, np.ndarray]], rows: np.ndarray,
               out: list[Structure | None]) -> None:
    """Each row's smallest p (ties by variable and test name, as :func:`min` of the
    tuples ``(p, variable, test, statistic)``), and the number of tests made."""
    p = np.column_stack([t[3] for t in tests])
    stat = np.column_stack([t[2] for t in tests])
    made = np.isfinite(p)
    rank = np.argsort(np.argsort([f"{v}\x00{t}" for v, t, _, _ in tests]))
    order = np.lexsort((np.broadcast_to(rank, p.shape), np.where(made, p, np.inf)), axis=-1)
    best = order[:, 0]
    for i, row in enumerate(rows):
        count = int(made[i].sum())
        if count:
            var, test = tests[best[i]][:2]
            out[row] = Structure(var, test, float(stat[i, best[i]]), float(p[i, best[i]]),
                                 count)


def _norm_cdf(z: Any) -> Any:
    """Standard normal distribution function (array-capable)."""
    from scipy.special import ndtr

    return ndtr(z)


def _order_by(key: np.ndarray, others: list[np.ndarray]) -> np.ndarray:
    """``np.lexsort([*others, key])``: rows by ``key``, ties by ``others`` then by row.

    Without ties in ``key`` that order is the one any sort gives, so the (several times
    faster) default sort is used; with ties, the stable lexicographic sort.
    """
    order = np.argsort(key)
    ranked = key[order]
    if np.any(ranked[1:] == ranked[:-1]):
        return np.lexsort([*others, key])
    return order


def residual_structure(resid: np.ndarray, arrays: Mapping[str, np.ndarray],
                       variables: Sequence[str]) -> Structure | None:
    """The strongest residual structure along any variable (None with too few rows).

    For each variable taking at least two values the rows are ordered by it
    (ties by the other variables) and two tests are made: a Wald-Wolfowitz runs
    test of the residual signs and the lag-1 autocorrelation.  The smallest p
    is returned with the number of tests for a Bonferroni correction.
    """
    resid = np.asarray(resid, float)
    if resid.size < 8 or not np.all(np.isfinite(resid)):
        return None
    found: list[tuple[float, str, str, float]] = []
    present = [v for v in variables if v in arrays and np.ptp(arrays[v]) > 0]
    for var in present:
        others = [np.asarray(arrays[o], float) for o in reversed(present) if o != var]
        e = resid[_order_by(np.asarray(arrays[var], float), others)]
        runs, p_runs = _runs_p(e)
        r1, p_lag = _lag1_p(e)
        if math.isfinite(p_runs):
            found.append((p_runs, var, "runs", runs))
        if math.isfinite(p_lag):
            found.append((p_lag, var, "lag1", r1))
    if not found:
        return None
    p, var, test, stat = min(found)
    return Structure(var, test, stat, p, len(found))


@dataclass
class Refit:
    """Everything a bootstrap replicate needs to refit the law (picklable for joblib).

    ``evaluate(values)`` is not stored; the law and its fixed values are, so a
    worker process rebuilds the model values itself.
    """

    law: Any
    fixed: dict[str, float]
    vary: list[str]
    lower: np.ndarray
    upper: np.ndarray
    x: dict[str, np.ndarray]
    y: np.ndarray
    w: np.ndarray | None
    #: Relative singular value of the scaled Jacobian below which a direction of the
    #: parameters is not determined (the fit's own identifiability threshold).
    rank_tol: float = 1e-5
    #: The rank the full data give the Jacobian (None: every parameter): a replicate
    #: whose rows give less cannot determine what the full data determine.
    rank: int | None = None

    def model(self, theta: np.ndarray, x: Mapping[str, np.ndarray], n: int) -> np.ndarray:
        """Model values at variables ``x`` (``n`` rows) for parameters ``theta``."""
        vals = dict(self.fixed)
        vals.update(zip(self.vary, (float(t) for t in theta)))
        with np.errstate(all="ignore"):
            out = self.law.evaluate(x, vals)
        return np.broadcast_to(np.asarray(out, float), (n,))

    def solve(self, theta0: np.ndarray, rows: np.ndarray) -> np.ndarray:
        """Least-squares parameters on ``rows`` started from ``theta0``.

        NaN when the refit fails, and when the rows cannot determine every parameter
        (a resample of too few distinct conditions: its refit would stay where it
        started and show a spread of zero).
        """
        w = 1.0 if self.w is None else self.w[rows]
        y = self.y[rows]
        x = {k: v[rows] for k, v in self.x.items()}

        def resid(theta: np.ndarray) -> np.ndarray:
            r = (self.model(theta, x, rows.size) - y) * w
            return np.where(np.isfinite(r), r, 1e100)

        span = np.where(np.isfinite(self.upper - self.lower), self.upper - self.lower, 0.0)
        start = np.clip(theta0, self.lower + 1e-9 * span, self.upper - 1e-9 * span)
        start = np.where(start <= self.lower, self.lower + np.abs(self.lower) * 1e-9 + 1e-300,
                         start)
        scale = np.maximum(np.abs(start), 1e-12)
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                sol = least_squares_solve(resid, start, bounds=(self.lower, self.upper),
                                    x_scale=scale, max_nfev=200 * (start.size + 1))
        except (ValueError, FloatingPointError, np.linalg.LinAlgError):
            return np.full(theta0.size, np.nan)
        if not (np.all(np.isfinite(sol.fun)) and np.max(np.abs(sol.fun)) < 1e99) or \
                rank(sol.jac, self.rank_tol) < (self.rank or theta0.size):
            return np.full(theta0.size, np.nan)
        return np.asarray(sol.x, float)


def rank(jac: Any, rank_tol: float) -> int:
    """The numerical rank of the Jacobian with unit columns (how many directions are determined).

    Parameters
    ----------
    jac : array-like, shape (n, k)
        Jacobian of the residuals with respect to the parameters.
    rank_tol : float
        Singular values below ``rank_tol`` times the largest do not count; a zero or
        non-finite column counts for nothing.

    Returns
    -------
    int
        0..k (0 for a Jacobian that is not finite).
    """
    jac = np.asarray(jac, float)
    if jac.ndim != 2 or not np.all(np.isfinite(jac)):
        return 0
    norms = np.linalg.norm(jac, axis=0)
    live = norms > 0
    if not live.any():
        return 0
    s = np.linalg.svd(jac[:, live] / norms[live], compute_uv=False)
    return int(np.sum(s >= rank_tol * s[0]))


def _solve_many(refit: Refit, theta0: np.ndarray, rows_list: list[np.ndarray]
                ) -> np.ndarray:
    return np.array([refit.solve(theta0, rows) for rows in rows_list])


@dataclass
class BootstrapResult:
    """Replicate parameters (B x k), leave-out-conditions ones (J x k), failures."""

    samples: np.ndarray
    jackknife: np.ndarray
    n_groups: int
    failed: int


#: Leave-out sets of the BCa jackknife at most.  With more conditions than this, the
#: conditions are left out in this many blocks of consecutive ids (a grouped, delete-d
#: jackknife, whose acceleration estimate serves BCa as well): G single leave-outs would
#: cost G refits of the whole data.
JACKKNIFE_SETS = 100
#: Row indices per task of a parallel bootstrap at most (16 MB), so the tasks in
#: flight stay small whatever the data size.
_TASK_INDICES = 2_000_000


class _Resampler:
    """The rows of bootstrap replicates and jackknife sets, made one set at a time.

    Rows are grouped by condition once (a stable sort), so a replicate's rows are a
    few vectorised operations on the drawn conditions: the same rows, in the same
    order, as concatenating each drawn condition's rows, without a Python loop over
    the conditions or any set built before it is needed.
    """

    def __init__(self, groups: np.ndarray) -> None:
        self.order = np.argsort(groups, kind="stable")
        _, self.starts, self.sizes = np.unique(groups[self.order], return_index=True,
                                               return_counts=True)
        self.n_groups = int(self.sizes.size)

    def rows(self, chosen: np.ndarray) -> np.ndarray:
        """The rows of the conditions ``chosen`` (with repeats), condition after condition."""
        lens = self.sizes[chosen]
        offsets = np.cumsum(lens) - lens
        idx = np.arange(int(lens.sum())) - np.repeat(offsets - self.starts[chosen], lens)
        return self.order[idx]

    def replicates(self, n_boot: int, seed: int) -> Iterator[np.ndarray]:
        """The rows of each of ``n_boot`` resamples of whole conditions (seeded)."""
        rng = np.random.default_rng(seed)
        for _ in range(n_boot):
            yield self.rows(rng.integers(0, self.n_groups, size=self.n_groups))

    def jackknife(self) -> Iterator[np.ndarray]:
        """The rows left when each condition, or each block of them, is left out."""
        ids = np.arange(self.n_groups)
        sets = min(self.n_groups, JACKKNIFE_SETS)
        block = ids * sets // self.n_groups
        for b in range(sets):
            yield self.rows(ids[block != b])


def bootstrap(refit: Refit, theta0: np.ndarray, groups: np.ndarray, *, n_boot: int,
              seed: int, n_jobs: int = 1, jackknife: bool = True) -> BootstrapResult:
    """Refit on ``n_boot`` resamples of whole conditions (and the jackknife sets).

    The row sets are made as the refits consume them, so memory stays near the data
    size, however many conditions and replicates.

    Parameters
    ----------
    refit : Refit
        The problem.
    theta0 : ndarray
        The optimum, each replicate's start.
    groups : ndarray of int
        Condition id per row (:func:`condition_ids`).
    n_boot, seed : int
        Replicates and the seed that makes them reproducible.
    n_jobs : int
        joblib workers (1: in this process).
    jackknife : bool
        Also refit the leave-out sets BCa needs (one per condition, or
        :data:`JACKKNIFE_SETS` blocks); percentile intervals need none.
    """
    res = _Resampler(groups)
    sets = itertools.chain(res.replicates(n_boot, seed),
                           res.jackknife() if jackknife else iter(()))
    total = n_boot + (min(res.n_groups, JACKKNIFE_SETS) if jackknife else 0)
    workers = local_workers(n_jobs, total)
    if workers == 1:
        out = np.array([refit.solve(theta0, rows) for rows in sets]).reshape(total, -1)
    else:
        per_task = max(1, min(-(-total // (4 * workers)), _TASK_INDICES // max(groups.size, 1)))
        parts = starmap_local(_solve_many, ((refit, theta0, chunk)
                                            for chunk in batches(sets, per_task)), workers)
        out = np.concatenate(list(parts)).reshape(total, -1)
    samples, jack = out[:n_boot], out[n_boot:]
    failed = int(np.sum(~np.all(np.isfinite(samples), axis=1)))
    return BootstrapResult(samples, jack, res.n_groups, failed)


def intervals(samples: np.ndarray, hat: np.ndarray, jack: np.ndarray, *,
              kind: str = "bca", level: float = 0.95) -> tuple[np.ndarray, np.ndarray, str]:
    """Standard errors and (low, high) intervals per column of ``samples``.

    Parameters
    ----------
    samples : ndarray, shape (B, m)
        Bootstrap replicates of m statistics (rows with NaN are dropped per column).
    hat : ndarray, shape (m,)
        The statistics on the full data.
    jack : ndarray, shape (G, m)
        Leave-one-condition-out values (BCa acceleration).
    kind : {"bca", "percentile"}
        BCa falls back to percentile for a column where it cannot be computed.

    Returns
    -------
    (stderr, ci, kind_used)
        ``ci`` has shape (m, 2); ``kind_used`` is ``"bca"``, ``"percentile"`` or
        ``"bca/percentile"`` when some columns fell back.  A column with fewer than
        :data:`MIN_DETERMINED` finite replicates, or whose replicates do not spread
        (all within :data:`ZERO_SPREAD` of each other, relative), gets NaN: the
        resamples cannot tell its error, which is not zero.
    """
    from scipy import stats

    m = samples.shape[1]
    se = np.full(m, np.nan)
    ci = np.full((m, 2), np.nan)
    alpha = (1.0 - level) / 2.0
    used = set()
    for j in range(m):
        s = samples[:, j]
        s = s[np.isfinite(s)]
        if no_spread(s):  # the one rule of every resampling: undetermined, not 0
            continue
        se[j] = float(np.std(s, ddof=1))
        qs = np.array([alpha, 1.0 - alpha])
        if kind == "bca":
            adj = _bca_levels(s, float(hat[j]), jack[:, j], qs, stats)
            if adj is not None:
                qs = adj
                used.add("bca")
            else:
                used.add("percentile")
        else:
            used.add("percentile")
        ci[j] = np.quantile(s, qs)
    return se, ci, "/".join(sorted(used, reverse=True)) or kind


def _bca_levels(s: np.ndarray, hat: float, jack: np.ndarray, qs: np.ndarray,
                stats: Any) -> np.ndarray | None:
    """BCa-adjusted quantile levels (None when bias or acceleration is not finite)."""
    frac = float(np.mean(s < hat)) + 0.5 * float(np.mean(s == hat))
    if not 0.0 < frac < 1.0:
        return None
    z0 = float(stats.norm.ppf(frac))
    jack = jack[np.isfinite(jack)]
    if jack.size < 3:
        return None
    d = jack.mean() - jack
    den = 6.0 * float(np.sum(d**2)) ** 1.5
    acc = float(np.sum(d**3)) / den if den > 0 else 0.0
    z = stats.norm.ppf(qs)
    adj = stats.norm.cdf(z0 + (z0 + z) / (1.0 - acc * (z0 + z)))
    return adj if np.all(np.isfinite(adj)) else None


def derived_samples(funcs: Mapping[str, Callable[[dict[str, float]], float]],
                    fixed: Mapping[str, float], vary: Sequence[str],
                    thetas: np.ndarray) -> np.ndarray:
    """Derived quantities (columns, in ``funcs`` order) for each parameter row."""
    out = np.full((thetas.shape[0], len(funcs)), np.nan)
    for i, theta in enumerate(thetas):
        if not np.all(np.isfinite(theta)):
            continue
        vals = {**fixed, **dict(zip(vary, (float(t) for t in theta)))}
        for j, f in enumerate(funcs.values()):
            with np.errstate(all="ignore"):
                try:
                    out[i, j] = float(f(vals))
                except (ValueError, ZeroDivisionError, OverflowError):
                    pass
    return out
