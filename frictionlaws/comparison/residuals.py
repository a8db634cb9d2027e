"""Residual analysis: is what a law leaves over structured, or just scatter?

A law that fits well leaves residuals that look like measurement noise: no
trend against any variable or against the fitted value, and no long runs of
the same sign when the rows are put in order of a variable.  This module
gives two simple tests for each ordering, plus the normal quantiles for a
Q-Q plot:

* the **Wald-Wolfowitz runs test** on the residual signs, ordered by each
  variable (ties broken by the other variables, so the order is
  reproducible) and by the fitted value.  Too *few* runs means residuals of
  one sign cluster along that variable: a systematic misfit, e.g. a law that
  is too flat.  The p-value is the exact one-sided probability of that few
  runs or fewer (normal approximation above 200 signs);
* **Kendall's tau** between the residual and the variable (a monotone
  trend), from :func:`scipy.stats.kendalltau`;
* the normal quantiles from :func:`scipy.stats.probplot` and the
  Shapiro-Wilk p-value (:func:`scipy.stats.shapiro`).

Each test is at the 5 % level on its own; several tests per law are not
corrected for multiplicity, so read an isolated p of 0.03 as a hint, and
several small p-values as a pattern.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ALPHA", "runs_test", "runs_pmf", "ResidualAnalysis", "analyse_residuals"]

#: Significance level used to call a residual pattern "structure".
ALPHA = 0.05
#: Above this many signs the runs test uses the normal approximation.
EXACT_RUNS_MAX = 200


def _comb(n: int, k: int) -> int:
    return math.comb(n, k) if 0 <= k <= n else 0


def runs_pmf(r: int, n1: int, n2: int) -> float:
    """Probability of exactly ``r`` runs in a random order of ``n1`` + and ``n2`` - signs."""
    if n1 == 0 or n2 == 0:
        return 1.0 if r == 1 else 0.0
    total = _comb(n1 + n2, n1)
    if r % 2 == 0:
        k = r // 2
        ways = 2 * _comb(n1 - 1, k - 1) * _comb(n2 - 1, k - 1)
    else:
        k = (r - 1) // 2
        ways = _comb(n1 - 1, k) * _comb(n2 - 1, k - 1) + _comb(n1 - 1, k - 1) * _comb(n2 - 1, k)
    return ways / total


def runs_test(signs: Any) -> dict[str, Any]:
    """Wald-Wolfowitz runs test on a sequence of signs (zeros are left out).

    Parameters
    ----------
    signs : array-like
        Values whose sign is taken, in the order to test.

    Returns
    -------
    dict
        ``runs`` (observed), ``expected`` (under random order), ``n_pos``,
        ``n_neg``, ``p_value`` (one-sided: probability of this few runs or
        fewer, i.e. of clustering at least this strong), ``p_two_sided``
        and ``method`` (``"exact"`` or ``"normal"``).  The p-values are None
        when all signs are equal or fewer than two are non-zero.
    """
    s = np.sign(np.asarray(signs, dtype=float))
    s = s[s != 0]
    n1, n2 = int(np.sum(s > 0)), int(np.sum(s < 0))
    n = n1 + n2
    runs = int(1 + np.count_nonzero(s[1:] != s[:-1])) if n else 0
    out: dict[str, Any] = {"runs": runs, "n_pos": n1, "n_neg": n2, "expected": None,
                           "p_value": None, "p_two_sided": None, "method": None}
    if n1 == 0 or n2 == 0:
        return out
    expected = 2.0 * n1 * n2 / n + 1.0
    out["expected"] = expected
    if n <= EXACT_RUNS_MAX:
        pmf = np.array([runs_pmf(r, n1, n2) for r in range(2, n + 1)])
        lower = float(np.sum(pmf[: runs - 1]))
        upper = float(np.sum(pmf[runs - 2:]))
        out["method"] = "exact"
    else:
        from scipy import stats

        var = 2.0 * n1 * n2 * (2.0 * n1 * n2 - n) / (n**2 * (n - 1))
        z_lo = (runs + 0.5 - expected) / math.sqrt(var)
        z_hi = (runs - 0.5 - expected) / math.sqrt(var)
        lower, upper = float(stats.norm.cdf(z_lo)), float(stats.norm.sf(z_hi))
        out["method"] = "normal"
    out["p_value"] = min(1.0, lower)
    out["p_two_sided"] = min(1.0, 2.0 * min(lower, upper))
    return out


def _order(key: np.ndarray, others: list[np.ndarray]) -> np.ndarray:
    """Row order by ``key``, ties broken by ``others`` (reproducible)."""
    return np.lexsort(tuple(reversed([key, *others])))


@dataclass
class ResidualAnalysis:
    """Residual tests of one fitted law (see the module docstring).

    ``tests`` maps an ordering (a variable name, or ``"fitted"``) to
    ``{"runs": runs_test dict, "kendall_tau": float, "kendall_p": float}``.
    """

    n: int
    tests: dict[str, dict[str, Any]]
    shapiro_p: float | None
    normal_quantiles: tuple[np.ndarray, np.ndarray]
    structure: list[str] = field(default_factory=list)

    @property
    def structured(self) -> bool:
        """True when any test found structure at the 5 % level."""
        return bool(self.structure)

    def to_dict(self) -> dict[str, Any]:
        return {"n": self.n, "alpha": ALPHA, "tests": self.tests, "shapiro_p": self.shapiro_p,
                "structure": list(self.structure)}


def analyse_residuals(residual: np.ndarray, fitted: np.ndarray,
                      variables: dict[str, np.ndarray],
                      describe: Any = None) -> ResidualAnalysis:
    """Runs and trend tests of ``residual`` along each variable and the fitted value.

    Parameters
    ----------
    residual, fitted : ndarray
        Data minus fit, and the fit, on the rows the law was fitted to.
    variables : dict
        Variable name -> values on the same rows (only variables with at least
        two distinct values are tested).
    describe : callable, optional
        ``describe(name) -> str`` naming an ordering in messages.
    """
    from scipy import stats

    describe = describe or (lambda k: k)
    residual = np.asarray(residual, float)
    fitted = np.asarray(fitted, float)
    scale = max(float(np.max(np.abs(residual))) if residual.size else 0.0, 1e-300)
    signs = np.where(np.abs(residual) <= 1e-12 * scale, 0.0, residual)
    orderings = {k: np.asarray(v, float) for k, v in variables.items()
                 if np.unique(v).size >= 2}
    orderings["fitted"] = fitted
    tests: dict[str, dict[str, Any]] = {}
    structure: list[str] = []
    for name, x in orderings.items():
        others = [v for k, v in orderings.items() if k != name]
        order = _order(x, others)
        runs = runs_test(signs[order])
        tau, p_tau = (None, None)
        if np.unique(x).size >= 2 and np.ptp(residual) > 0:
            res = stats.kendalltau(x, residual)
            tau = float(res.statistic) if np.isfinite(res.statistic) else None
            p_tau = float(res.pvalue) if np.isfinite(res.pvalue) else None
        tests[name] = {"runs": runs, "kendall_tau": tau, "kendall_p": p_tau}
        label = describe(name)
        if runs["p_value"] is not None and runs["p_value"] < ALPHA:
            structure.append(
                f"residual signs cluster along {label}: {runs['runs']} runs where "
                f"{runs['expected']:.1f} are expected at random (runs test p = "
                f"{runs['p_value']:.2g})")
        if p_tau is not None and p_tau < ALPHA:
            structure.append(f"residuals trend with {label} (Kendall tau = {tau:+.2f}, "
                             f"p = {p_tau:.2g})")
    shapiro_p = None
    if residual.size >= 3 and np.ptp(residual) > 0:
        shapiro_p = float(stats.shapiro(residual).pvalue)
        if shapiro_p < ALPHA:
            structure.append(f"residuals are not normal-looking (Shapiro-Wilk p = "
                             f"{shapiro_p:.2g}): outliers or a skewed misfit")
    (osm, osr), _ = stats.probplot(residual, dist="norm")
    return ResidualAnalysis(int(residual.size), tests, shapiro_p,
                            (np.asarray(osm), np.asarray(osr)), structure)
