"""The least-squares machinery behind :func:`frictionlaws.fitting.fit`.

A :class:`Problem` holds one fit's data with the floors applied once, the parameters
held and those varied, their bounds, and the law's analytic Jacobian when its generated
form exists (:mod:`frictionlaws.derivatives`).  :func:`solve` runs one local
minimisation from one start and returns a :class:`Solution` with the statistics the
fit reports (chi^2, AIC, BIC and the covariance scaled by the reduced chi^2, as lmfit
computes them).

The solver is chosen for the problem: MINPACK's Levenberg-Marquardt
(:func:`scipy.optimize.leastsq`, lean in memory and call overhead) whenever it reaches a
minimum with no bound active; when a bound is active (or MINPACK keeps trying points
beyond the bounds) the bounded trust-region reflective method of
:func:`scipy.optimize.least_squares` takes over (``x_scale=1``: scaling by the Jacobian's
columns was tried and sent several huemer starts to worse minima).  Other lmfit method
names go through :func:`lmfit.minimize` with the same residual (lmfit is imported only then).

:func:`score_starts` evaluates chi^2 at many candidate starts in one pass, so a
multi-start search refines only the promising ones.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from .law import NUMPY, Law

__all__ = ["Problem", "Solution", "solve", "score_starts", "numeric_jacobian",
           "analytic_jacobian", "prepare_variables"]

#: Evaluations of the model per start and varied parameter (as the fit always allowed).
NFEV_PER_PARAM = 300
#: Rows x starts evaluated at once by :func:`score_starts` (beyond: one start at a time).
_SCORE_CELLS = 500_000


@dataclass
class Problem:
    """One fit: prepared variables, data, weights, held and varied parameters.

    Parameters
    ----------
    law : Law
        The law (with its settings as the fit uses them).
    x : mapping
        Variable name -> SI array, the law's variables only.
    y : numpy.ndarray
        Measured mu.
    w : numpy.ndarray or None
        Weights multiplying the residuals (None: unweighted).
    held : dict
        Values of everything not varied (settings and fixed parameters).
    names : list of str
        The varied parameters, in order.
    lower, upper : numpy.ndarray
        Their bounds.
    """

    law: Law
    x: Mapping[str, np.ndarray]
    y: np.ndarray
    w: np.ndarray | None
    held: dict[str, float]
    names: list[str]
    lower: np.ndarray
    upper: np.ndarray
    prepared: dict[str, np.ndarray] = field(init=False)
    jac_func: Callable[..., Any] | None = field(init=False)

    def __post_init__(self) -> None:
        from .derivatives import jacobian_function

        self.prepared = prepare_variables(self.law, self.x, self.y.size)
        self.jac_func = jacobian_function(self.law)

    def values(self, theta: ArrayLike) -> dict[str, float]:
        """All parameter and setting values for the varied values ``theta``."""
        out = dict(self.held)
        out.update(zip(self.names, (float(t) for t in np.asarray(theta, dtype=float))))
        return out

    def model(self, theta: ArrayLike) -> np.ndarray:
        """The law at ``theta`` on every row (floors applied, no checks)."""
        with np.errstate(all="ignore"):
            out = self.law.formula(NUMPY, **self.prepared, **self.values(theta))
        out = np.asarray(out, float)
        if out.shape != self.y.shape:
            out = np.broadcast_to(out, self.y.shape)
        return out

    def residual(self, theta: ArrayLike) -> np.ndarray:
        """``(model - y) * w``, the vector whose squares are summed."""
        r = self.model(theta) - self.y
        if self.w is not None:
            r *= self.w
        return r

    def jacobian(self, theta: ArrayLike) -> np.ndarray | None:
        """d residual / d theta, analytic, as an (n, k) array (None without a form)."""
        if self.jac_func is None:
            return None
        jac = analytic_jacobian(self.jac_func, self.prepared, self.values(theta), self.names,
                                self.y.size, self.w)
        bad = np.flatnonzero(~np.all(np.isfinite(jac), axis=0))
        if bad.size:  # e.g. d(0**c)/dc = 0**c log 0 at v = 0: differences there
            self._difference_columns(jac, np.asarray(theta, float), bad)
        return jac

    def _difference_columns(self, jac: np.ndarray, theta: np.ndarray, cols: np.ndarray
                            ) -> None:
        """Replace columns ``cols`` of ``jac`` by forward differences of the residual."""
        r0 = self.residual(theta)
        for j in cols:
            h = 1.5e-8 * max(abs(theta[j]), 1e-8)
            step = theta.copy()
            step[j] = step[j] + h if step[j] + h <= self.upper[j] else step[j] - h
            jac[:, j] = (self.residual(step) - r0) / (step[j] - theta[j])

    @property
    def bounded(self) -> bool:
        """True when a varied parameter has a finite bound."""
        return bool(np.any(np.isfinite(self.lower)) or np.any(np.isfinite(self.upper)))


def prepare_variables(law: Law, x: Mapping[str, np.ndarray], n: int) -> dict[str, np.ndarray]:
    """The law's variables as the formula takes them: ``|v|``, floors, float arrays."""
    out = {}
    for k in law.variables:
        v = np.asarray(x[k], float) if k in x else np.zeros(n)
        if k == "v":
            v = np.abs(v)
        floor = law.floors.get(k)
        if floor is not None:
            v = np.maximum(v, floor)
        out[k] = v
    return out


def numeric_jacobian(func: Callable[[Any], np.ndarray], x: np.ndarray,
                     scales: np.ndarray | None = None) -> np.ndarray:
    """Central-difference Jacobian of ``func`` (vector -> vector) at ``x``.

    The first step is 1e-6 of the parameter's magnitude or of its typical
    scale (``scales``, e.g. the declared default), whichever is larger, or
    1e-6 in its unit when both are zero.  When that step moves the model by
    less than 1e-7 of its size (a parameter sitting near a bound of 0, say),
    the step grows until it does, so every column stands well above round-off.
    """
    f0 = func(x)
    size = max(float(np.linalg.norm(f0)), 1e-300)
    jac = np.empty((f0.size, x.size))
    for j in range(x.size):
        mag = max(abs(x[j]), abs(scales[j]) if scales is not None else 0.0)
        h = 1e-6 * mag if mag > 0 else 1e-6
        for _ in range(8):
            xp, xm = x.copy(), x.copy()
            xp[j] += h
            xm[j] -= h
            diff = func(xp) - func(xm)
            if np.linalg.norm(diff) >= 1e-7 * size or not np.all(np.isfinite(diff)):
                break
            h *= 10.0
        jac[:, j] = diff / (2 * h)
    return jac


def analytic_jacobian(func: Callable[..., Any], prepared: Mapping[str, np.ndarray],
                      values: Mapping[str, float], names: Sequence[str], n: int,
                      w: np.ndarray | None) -> np.ndarray:
    """The (n, k) Jacobian of the (weighted) model from a generated derivative function."""
    with np.errstate(all="ignore"):
        cols = func(NUMPY, names, **prepared, **values)
    jac = np.empty((n, len(names)), order="F")
    for j, col in enumerate(cols):
        jac[:, j] = col
    if w is not None:
        jac *= w[:, None]
    return jac


@dataclass
class Solution:
    """The outcome of one local minimisation, with lmfit's statistics.

    Parameters
    ----------
    theta : numpy.ndarray
        The varied parameters at the end.
    names : list of str
        Their names.
    residual : numpy.ndarray
        ``(model - y) * w`` there.
    best_fit : numpy.ndarray
        The model there (unweighted).
    success : bool
        Whether the solver reports convergence.
    message : str
        The solver's message.
    nfev : int
        Model evaluations used.
    """

    theta: np.ndarray
    names: list[str]
    residual: np.ndarray
    best_fit: np.ndarray
    success: bool
    message: str
    nfev: int = 0
    covar: np.ndarray | None = None
    jac: np.ndarray | None = None

    @property
    def chisqr(self) -> float:
        """Sum of squared (weighted) residuals (floored at 1e-250 n, as lmfit does)."""
        n = self.residual.size
        return float(max(float(np.dot(self.residual, self.residual)), 1e-250 * n))

    @property
    def nfree(self) -> int:
        """Rows minus varied parameters."""
        return self.residual.size - len(self.names)

    @property
    def redchi(self) -> float:
        """chi^2 per degree of freedom (per row when there is none)."""
        return self.chisqr / max(1, self.nfree)

    @property
    def aic(self) -> float:
        """Akaike information criterion, lmfit's definition."""
        n = self.residual.size
        return float(n * math.log(self.chisqr / n) + 2 * len(self.names))

    @property
    def bic(self) -> float:
        """Bayesian information criterion, lmfit's definition."""
        n = self.residual.size
        return float(n * math.log(self.chisqr / n) + math.log(n) * len(self.names))

    def stderr(self) -> dict[str, float | None]:
        """Standard errors from the covariance (None where it has none)."""
        out: dict[str, float | None] = {k: None for k in self.names}
        if self.covar is None:
            return out
        for j, k in enumerate(self.names):
            d = float(self.covar[j, j])
            out[k] = math.sqrt(d) if math.isfinite(d) and d >= 0 else None
        return out


def _covariance(jac: np.ndarray | None, redchi: float) -> np.ndarray | None:
    """``inv(J^T J)`` scaled by the reduced chi^2.

    When ``J^T J`` is singular (parameters the data cannot tell apart) the
    pseudo-inverse is used, so the parameters outside the degenerate directions
    keep their errors; the fit withholds those of the others.  None when the
    Jacobian is not finite.
    """
    if jac is None or not np.all(np.isfinite(jac)):
        return None
    hess = jac.T @ jac
    try:
        cov = np.linalg.inv(hess)
        if np.all(np.isfinite(cov)) and np.all(np.diag(cov) > 0):
            return cov * redchi
    except np.linalg.LinAlgError:
        pass
    return np.linalg.pinv(hess, rcond=1e-13, hermitian=True) * redchi


def _finish(problem: Problem, theta: np.ndarray, success: bool, message: str, nfev: int,
            jac: np.ndarray | None = None) -> Solution:
    best_fit = np.array(problem.model(theta), dtype=float)
    resid = best_fit - problem.y
    if problem.w is not None:
        resid = resid * problem.w
    sol = Solution(np.asarray(theta, float), list(problem.names), resid, best_fit, success,
                   message, nfev)
    if jac is None:
        jac = problem.jacobian(theta)
    if jac is None:
        jac = numeric_jacobian(problem.residual, np.asarray(theta, float))
    sol.jac = jac
    sol.covar = _covariance(jac, sol.redchi)
    return sol


def solve(problem: Problem, start: ArrayLike, method: str = "least_squares"
          ) -> Solution:
    """One local least-squares minimisation from ``start``.

    Parameters
    ----------
    problem : Problem
        The fit.
    start : sequence of float
        Starting values of the varied parameters (inside their bounds).
    method : str
        ``"least_squares"`` (the solver chosen for the problem, see the module
        docstring) or another lmfit method name.

    Returns
    -------
    Solution
        The end point and its statistics.

    Raises
    ------
    ValueError
        When the residuals are not finite at the start.
    """
    x0 = np.asarray(start, float)
    max_nfev = NFEV_PER_PARAM * (len(problem.names) + 1)
    if method != "least_squares":
        return _solve_lmfit(problem, x0, method, max_nfev)
    r0 = problem.residual(x0)
    if not np.all(np.isfinite(r0)):
        raise ValueError("the residuals are not finite at the start")
    jac: Any = (lambda t: problem.jacobian(t)) if problem.jac_func is not None else "2-point"
    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        if not problem.bounded:
            return _solve_minpack(problem, x0, max_nfev)
        free = _minpack_inside(problem, x0, max_nfev) if MINPACK_FIRST else None
        if free is not None and free.success and _inside(problem, free.theta):
            return free  # no bound active at the minimum: the bounded fit ends there too
        from scipy.optimize import least_squares

        ret = least_squares(problem.residual, x0, jac=jac, bounds=(problem.lower, problem.upper),
                            method="trf", x_scale=1.0, ftol=1e-8, xtol=1e-8, gtol=1e-8,
                            max_nfev=2 * max_nfev)
    return _finish(problem, ret.x, bool(ret.success), str(ret.message), int(ret.nfev))


#: Try MINPACK first on bounded problems, keeping its minimum when no bound is active.
MINPACK_FIRST = True


def _inside(problem: Problem, theta: np.ndarray) -> bool:
    """True when ``theta`` lies strictly inside the bounds (none is active)."""
    span = np.where(np.isfinite(problem.upper - problem.lower), problem.upper - problem.lower,
                    np.maximum(np.abs(theta), 1.0))
    margin = 1e-9 * span
    return bool(np.all(np.isfinite(theta)) and np.all(theta > problem.lower + margin)
                and np.all(theta < problem.upper - margin))


#: Trial points beyond the bounds MINPACK may evaluate before the bounded solver takes over.
OUTSIDE_TRIES = 10


class _LeftBounds(Exception):
    """MINPACK stepped outside the bounds: the bounded solver takes over."""


def _minpack_inside(problem: Problem, x0: np.ndarray, max_nfev: int) -> Solution | None:
    """MINPACK, abandoned (None) once it has tried points beyond the bounds 10 times."""
    outside = [0]

    def residual(theta: np.ndarray) -> np.ndarray:
        if not _inside(problem, theta):
            outside[0] += 1
            if outside[0] > OUTSIDE_TRIES:
                raise _LeftBounds
        return problem.residual(theta)

    try:
        return _solve_minpack(problem, x0, max_nfev, residual)
    except _LeftBounds:
        return None


def _solve_minpack(problem: Problem, x0: np.ndarray, max_nfev: int,
                   residual: Callable[[np.ndarray], np.ndarray] | None = None) -> Solution:
    """MINPACK Levenberg-Marquardt (no bounds to respect)."""
    from scipy.optimize import leastsq

    dfun = (lambda t: problem.jacobian(t)) if problem.jac_func is not None else None
    theta, _cov, info, mesg, ier = leastsq(residual or problem.residual, x0, Dfun=dfun,
                                           full_output=True, maxfev=2 * max_nfev)
    return _finish(problem, np.atleast_1d(theta), ier in (1, 2, 3, 4), str(mesg),
                   int(info["nfev"]))


def _solve_lmfit(problem: Problem, x0: np.ndarray, method: str, max_nfev: int) -> Solution:
    """Another lmfit method, on the same residual."""
    import lmfit

    params = lmfit.Parameters()
    for k, v, lo, hi in zip(problem.names, x0, problem.lower, problem.upper):
        params.add(k, value=float(v), min=float(lo), max=float(hi))
    names = list(problem.names)

    def resid(p: Any) -> np.ndarray:
        r = problem.residual([p[k].value for k in names])
        if not np.all(np.isfinite(r)):
            raise ValueError("the model gives non-finite values")
        return r

    with warnings.catch_warnings(), np.errstate(all="ignore"):
        warnings.simplefilter("ignore")
        res = lmfit.minimize(resid, params, method=method, max_nfev=max_nfev)
    theta = np.array([res.params[k].value for k in names], float)
    return _finish(problem, theta, bool(res.success), str(res.message), int(res.nfev))


def score_starts(problem: Problem, starts: Sequence[ArrayLike]) -> np.ndarray:
    """chi^2 at every start, evaluated in one broadcast pass where memory allows.

    Parameters
    ----------
    problem : Problem
        The fit.
    starts : sequence of sequences of float
        Candidate values of the varied parameters.

    Returns
    -------
    numpy.ndarray
        chi^2 per start; ``inf`` where the model is not finite.
    """
    m, n = len(starts), problem.y.size
    if m == 0:
        return np.empty(0)
    theta = np.asarray(starts, float).reshape(m, len(problem.names))
    if m * n <= _SCORE_CELLS and m > 1:
        vals: dict[str, Any] = dict(problem.held)
        vals.update({k: theta[:, j:j + 1] for j, k in enumerate(problem.names)})
        with np.errstate(all="ignore"):
            try:
                out = np.asarray(problem.law.formula(NUMPY, **{
                    k: v[None, :] for k, v in problem.prepared.items()}, **vals), float)
                out = np.broadcast_to(out, (m, n))
                r = (out - problem.y) * (problem.w if problem.w is not None else 1.0)
                chi = np.einsum("ij,ij->i", r, r)
                return np.where(np.isfinite(chi), chi, np.inf)
            except (ValueError, TypeError):
                pass  # a formula that does not broadcast over parameters: one at a time
    chi = np.empty(m)
    for i in range(m):
        r = problem.residual(theta[i])
        c = float(np.dot(r, r))
        chi[i] = c if math.isfinite(c) else math.inf
    return chi
