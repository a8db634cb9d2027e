"""Many least-squares problems of one law at once: the vectorised Levenberg-Marquardt solver.

:class:`Problems` stacks ``B`` problems of one law on ``n`` rows each (``y``, weights and
variables as ``(B, n)`` arrays); :func:`solve` minimises every ``sum(((y - f) * w)**2)``
at once with the law's analytic Jacobian (:mod:`frictionlaws.fitting.derivatives`), numpy doing
the loops over the problems.  The same solver with ``B = 1`` continues every small
single fit to its optimum (:func:`polish`), so a fit made alone and one made in a batch
(:mod:`frictionlaws.fitting.stacked`) end at the same point.

The iteration: the columns of the Jacobian are scaled to unit length, the damped
Gauss-Newton step ``(A + lam * max(eig A) I) ds = -g`` (``A = Js' Js``, ``g = Js' r``)
is taken from the eigen-decomposition of ``A`` and cut back into the bounds (a
parameter that would leave them stops on its bound, the others go on); a step that
does not lower the sum of squares (beyond rounding) is refused and ``lam`` grows
tenfold, an accepted one lowers it threefold.  A problem has converged when the reduction a full
Gauss-Newton step could still bring, ``g' A^-1 g``, is at most
``(GRADIENT_TOL * |r| + FLOOR_TOL * |y w|)**2``: the point is then the optimum to far
better than its standard errors (``1e-10`` of them), whatever the path to it, so the
result does not depend on the starting point within its basin, on the solver's path
or on the numpy and scipy versions.  A problem that does not get there (its optimum
lies on or beyond a bound, its model stops being finite, ``lam`` exceeds
``MAX_DAMPING`` or :data:`MAX_ITERATIONS` pass) is reported as not converged.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..law import NUMPY, Law
from .derivatives import jacobian_function
from .diagnosis import RANK_TOL
from .lsq import Estimate, LocalFit, fit_statistics, scaled_covariance
from .methods import fit_method

__all__ = ["GRADIENT_TOL", "FLOOR_TOL", "MAX_ITERATIONS", "POLISH_ROWS", "Problems",
           "Solution", "solve", "polish"]

#: Relative size of the residual's projection on the Jacobian's columns at which a
#: problem has converged (see the module docstring).
GRADIENT_TOL = 1e-10
#: The same, relative to the size of the weighted data (for fits that are exact).
FLOOR_TOL = 1e-13
#: Iterations after which a problem that has not converged is given up.
MAX_ITERATIONS = 200
#: Largest damping (relative to the largest eigenvalue) before a problem is given up.
MAX_DAMPING = 1e10
#: Fits on fewer rows are continued to their optimum by :func:`polish` (and campaigns
#: fit datasets of fewer rows in batches); larger fits keep their solver's end point.
POLISH_ROWS = 1000
#: First damping of the iteration (relative to the largest eigenvalue).
_FIRST_DAMPING = 1e-3
#: Relative rise of the sum of squares still taken as no change (rounding).
_ROUNDING = 1e-13


@dataclass
class Problems:
    """``B`` least-squares problems of one law, stacked.

    Parameters
    ----------
    law : Law
        The law (its formula and generated derivatives act element by element).
    names : list of str
        The varied parameters (or settings), the columns of ``theta``.
    held : dict
        Every other parameter and setting: a number, or a ``(B, 1)`` array.
    prepared : dict
        The law's variables as its formula takes them (:meth:`Law.prepare_variables`),
        ``(B, n)`` arrays.
    y : numpy.ndarray
        The data, ``(B, n)``.
    w : numpy.ndarray or None
        The weights multiplying the residuals, ``(B, n)``; None: unweighted.
    lo, hi : numpy.ndarray
        The bounds of the varied parameters, ``(k,)``.
    jac_func : callable
        The law's generated derivative function (:func:`frictionlaws.fitting.derivatives.
        jacobian_function`).
    """

    law: Law
    names: list[str]
    held: dict[str, Any]
    prepared: dict[str, np.ndarray]
    y: np.ndarray
    w: np.ndarray | None
    lo: np.ndarray
    hi: np.ndarray
    jac_func: Callable[..., Any]

    def take(self, idx: np.ndarray) -> Problems:
        """The problems ``idx`` (indices or a boolean mask)."""
        held = {k: v[idx] if isinstance(v, np.ndarray) else v for k, v in self.held.items()}
        return replace(self, held=held, prepared={k: v[idx] for k, v in self.prepared.items()},
                       y=self.y[idx], w=None if self.w is None else self.w[idx])

    def values(self, theta: np.ndarray) -> dict[str, Any]:
        """Every parameter and setting at ``theta`` (``(B, k)``), as ``(B, 1)`` columns."""
        out = dict(self.held)
        out.update({k: theta[:, j:j + 1] for j, k in enumerate(self.names)})
        return out

    def model(self, theta: np.ndarray) -> np.ndarray:
        """The law on every row of every problem, ``(B, n)``."""
        with np.errstate(all="ignore"):
            out = self.law.formula(NUMPY, **self.prepared, **self.values(theta))
        return np.broadcast_to(np.asarray(out, float), self.y.shape)

    def residual(self, theta: np.ndarray) -> np.ndarray:
        """The weighted residuals ``(y - model) * w``, ``(B, n)``."""
        r = self.y - self.model(theta)
        return r if self.w is None else r * self.w

    def jacobian(self, theta: np.ndarray) -> np.ndarray:
        """The Jacobian of the weighted residuals, ``(B, n, k)`` (NaN where not finite)."""
        with np.errstate(all="ignore"):
            cols = self.jac_func(NUMPY, self.names, **self.prepared, **self.values(theta))
        jac = np.empty((*self.y.shape, len(self.names)))
        for j, col in enumerate(cols):
            jac[:, :, j] = col
        jac *= -1.0
        if self.w is not None:
            jac *= self.w[:, :, None]
        return jac

    def data_size(self) -> np.ndarray:
        """``|y w|`` of every problem (the scale of an exact fit's residuals)."""
        yw = self.y if self.w is None else self.y * self.w
        return np.sqrt(np.einsum("bn,bn->b", yw, yw))


@dataclass
class Solution:
    """The end of :func:`solve`: the points, their sums of squares, convergence."""

    theta: np.ndarray
    cost: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray


def _cost(r: np.ndarray) -> np.ndarray:
    c = np.einsum("bn,bn->b", r, r)
    return np.where(np.isfinite(c), c, np.inf)


@dataclass
class _Running:
    """The problems still iterating: their indices and state."""

    idx: np.ndarray
    prob: Problems
    theta: np.ndarray
    r: np.ndarray
    cost: np.ndarray
    lam: np.ndarray
    size: np.ndarray

    def keep(self, mask: np.ndarray) -> None:
        self.idx, self.prob = self.idx[mask], self.prob.take(mask)
        self.theta, self.r, self.cost = self.theta[mask], self.r[mask], self.cost[mask]
        self.lam, self.size = self.lam[mask], self.size[mask]


def solve(prob: Problems, theta0: np.ndarray, max_iterations: int = MAX_ITERATIONS
          ) -> Solution:
    """Minimise the weighted sum of squares of every problem from ``theta0`` (``(B, k)``).

    Parameters
    ----------
    prob : Problems
        The stacked problems.
    theta0 : numpy.ndarray
        The starting points, inside the bounds.
    max_iterations : int
        Iterations after which a problem is given up.

    Returns
    -------
    Solution
        Each problem's last point, its sum of squares and whether it converged (see
        the module docstring for the rule).
    """
    theta = np.array(theta0, float, ndmin=2)
    r = prob.residual(theta)
    cost = _cost(r)
    out = Solution(theta.copy(), cost.copy(), np.zeros(len(theta), bool),
                   np.zeros(len(theta), int))
    ok = np.isfinite(cost) & np.all((theta >= prob.lo) & (theta <= prob.hi), axis=1)
    run = _Running(np.flatnonzero(ok), prob.take(ok), theta[ok], r[ok], cost[ok],
                   np.full(int(ok.sum()), _FIRST_DAMPING), prob.take(ok).data_size())
    for it in range(max_iterations):
        if not run.idx.size:
            break
        done, failed = _iterate(run)
        out.converged[run.idx[done]] = True
        finished = done | failed
        out.theta[run.idx] = run.theta
        out.cost[run.idx] = run.cost
        out.iterations[run.idx] = it + 1
        if finished.any():
            run.keep(~finished)
    return out


def _iterate(run: _Running) -> tuple[np.ndarray, np.ndarray]:
    """One iteration of every running problem: (converged, given up) masks."""
    jac = run.prob.jacobian(run.theta)
    failed = ~np.all(np.isfinite(jac), axis=(1, 2))
    jac[failed] = 0.0
    d = np.sqrt(np.einsum("bnk,bnk->bk", jac, jac))
    d = np.where(d > 0, d, 1.0)
    jac /= d[:, None, :]
    eig, vec = np.linalg.eigh(np.matmul(jac.transpose(0, 2, 1), jac))
    eig = np.maximum(eig, 0.0)
    top = np.maximum(eig[:, -1], 1e-300)
    qg = np.einsum("bkj,bk->bj", vec, np.einsum("bnk,bn->bk", jac, run.r))
    seen = eig > 1e-14 * top[:, None]
    gain = np.sum(np.where(seen, qg * qg / np.where(seen, eig, 1.0), 0.0), axis=1)
    limit = (GRADIENT_TOL * np.sqrt(run.cost) + FLOOR_TOL * run.size) ** 2
    done = ~failed & (gain <= limit)
    trying = ~(done | failed)
    while trying.any():
        t = np.flatnonzero(trying)
        shrink = eig[t] + run.lam[t, None] * top[t, None]
        step = -np.einsum("bkj,bj->bk", vec[t], qg[t] / shrink) / d[t]
        new = np.minimum(np.maximum(run.theta[t] + step, run.prob.lo), run.prob.hi)
        moved = np.any(new != run.theta[t], axis=1)
        r_new = run.prob.take(t).residual(new)
        better = moved & (_cost(r_new) <= run.cost[t] * (1.0 + _ROUNDING))
        c_new = _cost(r_new)
        acc = t[better]
        run.theta[acc], run.r[acc], run.cost[acc] = new[better], r_new[better], c_new[better]
        run.lam[acc] = np.maximum(run.lam[acc] / 3.0, 1e-15)
        run.lam[t[~better]] *= 10.0
        trying[acc] = False
        lost = t[~better][run.lam[t[~better]] > MAX_DAMPING]
        failed[lost] = True
        trying[lost] = False
    return done, failed


def one_problem(law: Law, names: list[str], held: Mapping[str, float],
                x: Mapping[str, np.ndarray], y: np.ndarray, w: np.ndarray | None,
                bounds: Mapping[str, tuple[float, float]],
                jac_func: Callable[..., Any]) -> Problems:
    """One fit's problem (``B = 1``) from its arrays."""
    prepared = {k: np.asarray(v, float)[None, :] for k, v in law.prepare_variables(x).items()}
    return Problems(law, list(names), dict(held), prepared, np.asarray(y, float)[None, :],
                    None if w is None else np.asarray(w, float)[None, :],
                    np.array([bounds[k][0] for k in names], float),
                    np.array([bounds[k][1] for k in names], float), jac_func)


def polish(search: Any) -> None:
    """Continue the best fit of a search to its optimum with :func:`solve` (one problem).

    The search's local solves stop at lmfit's tolerances (``1e-8``) with a Jacobian of
    finite differences, some ``1e-5`` (relative) short of the optimum and, on few rows,
    where exactly depends on the solver's path.  For a polished method (the default; see
    :data:`~frictionlaws.fitting.methods.FIT_METHODS`), laws with an analytic Jacobian
    and fits of fewer than :data:`POLISH_ROWS` rows the best fit is continued from its end
    point with the analytic Jacobian until it converges (:func:`solve`); its covariance
    is then ``inv(J' J)`` of that Jacobian at the optimum.  Nothing changes when the
    solve does not converge (an optimum on a bound, a model that is not finite) or
    ends higher than the search did, or the data cannot determine some parameter (the
    optimum is a valley: any point of it is the fit, and the search's stays).

    Parameters
    ----------
    search : frictionlaws.fitting.search._Search
        The finished search (its ``best`` is replaced).
    """
    s, best = search.setup, search.best
    if (best is None or not fit_method(search.method).polished or not best.success
            or s.y.size >= POLISH_ROWS):
        return
    jac_func = jacobian_function(s.law)
    if jac_func is None:
        return
    vary = [k for k in s.vary_names if k not in search.best_pinned]
    start = {k: float(best.params[k].value) for k in s.names}
    held = {**search.held, **{k: v for k, v in start.items() if k not in vary}}
    prob = one_problem(s.model_law, vary, held, s.x, s.y, s.w, s.bounds, jac_func)
    sol = solve(prob, np.array([[start[k] for k in vary]]))
    if not sol.converged[0] or _undetermined(prob.jacobian(sol.theta)[0]):
        return
    fit = local_fit_at(prob, sol.theta, {k: start[k] for k in s.names if k not in vary},
                       best.message, best.nfev + int(sol.iterations[0]))
    if fit.chisqr <= best.chisqr * (1.0 + 1e-12):
        search.best = fit


def _undetermined(jac: np.ndarray) -> bool:
    """True when the data cannot determine some direction of the parameters (relative
    singular value of the unit-column Jacobian below :data:`~.diagnosis.RANK_TOL`): the
    optimum is then a valley, not a point, and the search's end point stays."""
    norms = np.linalg.norm(jac, axis=0)
    if not np.all(np.isfinite(jac)) or not np.all(norms > 0):
        return True
    s = np.linalg.svd(jac / norms, compute_uv=False)
    return bool(s[-1] < RANK_TOL * s[0])


def local_fit_at(prob: Problems, theta: np.ndarray, held: Mapping[str, float],
                 message: str, nfev: int) -> Any:
    """The :class:`~frictionlaws.fitting.lsq.LocalFit` of one problem (``B = 1``) at ``theta``."""
    model = prob.model(theta)[0].copy()
    r = prob.residual(theta)[0]
    ndata, nvary = r.size, len(prob.names)
    chisqr, redchi, aic, bic = fit_statistics(float(r @ r), ndata, nvary)
    unit = scaled_covariance(prob.jacobian(theta)[0])
    covar = None if unit is None else unit * redchi
    params = {k: Estimate(float(v)) for k, v in held.items()}
    for j, k in enumerate(prob.names):
        with np.errstate(invalid="ignore"):  # a negative variance: NaN, as lmfit gives
            se = None if covar is None else float(np.sqrt(covar[j, j]))
        params[k] = Estimate(float(theta[0, j]), se)
    if covar is not None:
        for k in held:
            params[k].stderr = 0.0
    return LocalFit(params=params, var_names=list(prob.names), covar=covar, best_fit=model,
                    chisqr=float(chisqr), redchi=float(redchi), aic=float(aic),
                    bic=float(bic), success=True, message=message, nfev=nfev)


def stacked(values: Sequence[np.ndarray]) -> np.ndarray:
    """Equal-length rows as one ``(B, n)`` array."""
    return np.asarray(np.stack([np.asarray(v, float) for v in values]), float)


def finite_or_none(x: float) -> float | None:
    """``x``, or None when it is not finite (the JSON records' rule)."""
    return x if math.isfinite(x) else None
