"""The local least-squares solve of a fit, without lmfit's per-call bookkeeping.

With an analytic Jacobian (large data, see :data:`frictionlaws.fitting.ANALYTIC_FROM`)
MINPACK's Levenberg-Marquardt runs first and keeps its result when it converges
without trying a point outside the bounds; otherwise, and always without an analytic
Jacobian, the bounded trust region below solves the problem.

:func:`solve` runs :func:`scipy.optimize.least_squares` (bounded trust region
reflective, ``x_scale=1``, tolerances ``1e-8``) on the weighted residual
``(mu - model) * w`` and computes what a fit reports from it, exactly as lmfit's
``least_squares`` method does for the same problem: the same starting point, the
same residual (``data - model``, then times the weights), the same finite
difference Jacobian (or an analytic one when given), the same evaluation budget
(the fit is stopped after ``max_nfev`` residual evaluations, Jacobian columns
included), the covariance ``inv(J^T J)`` scaled by the reduced chi-square, and
chi-square, AIC and BIC by lmfit's formulas.  So a fit gives the numbers it gave
when lmfit ran the loop, while each residual evaluation costs one model call and
one subtraction instead of a copy of lmfit's parameter objects.

lmfit stays available for its own tools: :func:`frictionlaws.fitting.views.model_result`
refits the law with lmfit from the library's optimum.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

__all__ = ["LocalFit", "Estimate", "solve", "central_jacobian", "least_squares_solve",
           "lmfit_fit", "fit_statistics", "scaled_covariance"]

#: The message of a model that returned NaN or infinity (lmfit's wording, shortened).
NAN_MESSAGE = ("The model function generated NaN values and the fit aborted! Please check "
               "your model function and/or set boundaries on parameters where applicable.")


@dataclass
class Estimate:
    """One parameter of a local fit: its value and (for varied ones) standard error."""

    value: float
    stderr: float | None = None


@dataclass
class LocalFit:
    """The outcome of one local least-squares solve (lmfit's result attributes).

    Attributes
    ----------
    params : dict
        Every parameter (varied and held) -> :class:`Estimate`.
    var_names : list of str
        The varied parameters, in the order of ``covar``'s rows.
    covar : numpy.ndarray or None
        Covariance of the varied parameters, scaled by the reduced chi-square.
    best_fit : numpy.ndarray
        The model at the solution.
    chisqr, redchi, aic, bic : float
        Goodness of fit, as lmfit computes it.
    success : bool
        The solver's convergence flag (False when the evaluation budget ran out).
    message : str
        The solver's message.
    nfev : int
        Residual evaluations used (Jacobian columns included).
    """

    params: dict[str, Estimate]
    var_names: list[str]
    covar: np.ndarray | None
    best_fit: np.ndarray
    chisqr: float
    redchi: float
    aic: float
    bic: float
    success: bool
    message: str
    nfev: int


class _BudgetSpent(Exception):
    """Raised inside the residual when the evaluation budget is spent."""


@dataclass
class _Residual:
    """The weighted residual ``(y - model) * w`` of the varied parameters."""

    model: Callable[[dict[str, float]], Any]
    y: np.ndarray
    w: np.ndarray | None
    held: dict[str, float]
    names: list[str]
    lo: np.ndarray
    hi: np.ndarray
    max_nfev: int
    nfev: int = 0
    last: np.ndarray | None = None

    def values(self, theta: np.ndarray) -> dict[str, float]:
        """Every parameter's value at ``theta`` (varied ones kept inside their bounds)."""
        vals = dict(self.held)
        clipped = np.minimum(np.maximum(theta, self.lo), self.hi)
        vals.update(zip(self.names, clipped.tolist()))
        return vals

    def model_at(self, theta: np.ndarray) -> np.ndarray:
        """The model at ``theta``, refused (ValueError) when not finite."""
        out = np.asarray(self.model(self.values(theta)), dtype=float)
        if out.shape != self.y.shape:
            out = np.broadcast_to(out, self.y.shape)
        if not np.isfinite(out).all():
            raise ValueError(NAN_MESSAGE)
        return out

    def __call__(self, theta: np.ndarray) -> np.ndarray:
        theta = np.atleast_1d(theta)
        self.nfev += 1
        self.last = theta
        if self.nfev > self.max_nfev:
            raise _BudgetSpent
        diff = self.y - self.model_at(theta)
        if self.w is not None:
            diff *= self.w
        return diff


def solve(model: Callable[[dict[str, float]], Any], y: np.ndarray, w: np.ndarray | None,
          start: Mapping[str, float], vary: list[str],
          bounds: Mapping[str, tuple[float, float]], max_nfev: int,
          jac: Callable[[dict[str, float]], np.ndarray] | None = None,
          tol: float = 1e-8) -> LocalFit:
    """Minimise ``sum(((y - model(values)) * w)**2)`` over the ``vary`` parameters.

    Parameters
    ----------
    model : callable
        ``model(values) -> array``, values being every parameter by name.
    y, w : numpy.ndarray
        The data and the weights multiplying the residual (None: unweighted).
    start : mapping
        Every parameter's starting value; those not in ``vary`` are held there.
    vary : list of str
        The parameters varied.
    bounds : mapping
        ``(low, high)`` of each varied parameter (infinite allowed).
    max_nfev : int
        Residual evaluations allowed (finite-difference columns count).
    jac : callable, optional
        ``jac(values) -> (n, len(vary))`` Jacobian of the model; None: finite
        differences (two-point, as lmfit's default).
    tol : float
        ``ftol``, ``xtol`` and ``gtol`` of the solver (lmfit's 1e-8 by default).  A
        tighter one also scales the steps by the Jacobian's columns (``x_scale="jac"``),
        so that parameters of very different sizes converge alike (a polish).

    Returns
    -------
    LocalFit
        The solution and lmfit's statistics of it.

    Raises
    ------
    ValueError
        When the model is not finite at a point the solver tried.
    """
    lo = np.array([bounds[k][0] for k in vary], float)
    hi = np.array([bounds[k][1] for k in vary], float)
    held = {k: float(v) for k, v in start.items() if k not in vary}
    res = _Residual(model, y, w, held, list(vary), lo, hi, max_nfev)
    x0 = np.array([float(start[k]) for k in vary])
    kws: dict[str, Any] = dict(jac="2-point", method="trf", ftol=tol, xtol=tol, gtol=tol,
                               x_scale=1.0 if tol >= 1e-8 else "jac", loss="linear",
                               max_nfev=2 * max_nfev)
    if jac is not None:
        kws["jac"] = _residual_jacobian(jac, res)
    try:
        if jac is not None and y.size > len(vary):
            lm = _minpack_inside(res, x0, kws["jac"], max_nfev, tol)
            if lm is not None:
                return _finish(res, lm[0], lm[1], True, lm[2], res.nfev)
        ret = least_squares_solve(res, x0, bounds=(lo, hi), **kws)
    except _BudgetSpent:
        assert res.last is not None
        return _finish(res, res.last, None, False,
                       f"Fit aborted: number of function evaluations > {max_nfev}", max_nfev)
    return _finish(res, ret.x, ret.jac, bool(ret.success), str(ret.message), res.nfev)


class _LeftBounds(Exception):
    """Raised when MINPACK tries a point outside the bounds."""


def _minpack_inside(res: _Residual, x0: np.ndarray, jac: Callable[[np.ndarray], np.ndarray],
                    max_nfev: int, tol: float = 1e-8) -> Any:
    """Levenberg-Marquardt (MINPACK, analytic Jacobian) while it stays inside the bounds.

    Each MINPACK iteration costs one residual and one Jacobian and no decomposition
    beyond a QR in Fortran, so on large data it is the cheapest solver; it knows no
    bounds, so the solve is abandoned (None) at its first trial point outside them,
    or when it does not converge, and the bounded trust region takes over from the
    start.  A minimum it reaches inside the bounds is also the bounded problem's.  A
    start on a bound (a preset's E = 1 of the Magic Formula) is moved 1e-6 (relative)
    inside it, so MINPACK can try it too.

    MINPACK is called through :func:`scipy.optimize.leastsq`, which hands it the
    Jacobian without the copies ``least_squares(method="lm")`` keeps (four of the
    Jacobian and four of the residual on a 2e6-row fit); the arguments are those
    ``least_squares`` passes (``x_scale=1``, ``factor=100``), so the steps are the same.
    Returns ``(x, J, message)``, J the Jacobian at x, as ``least_squares`` gives it.
    """
    from scipy.optimize import leastsq

    def inside(theta: np.ndarray) -> np.ndarray:
        if (theta < res.lo).any() or (theta > res.hi).any():
            raise _LeftBounds
        return res(theta)

    gap = 1e-6 * np.maximum(np.abs(x0), 1.0)
    x0 = np.minimum(np.maximum(x0, res.lo + gap), res.hi - gap)
    if np.any(x0 <= res.lo) or np.any(x0 >= res.hi):
        return None
    try:
        x, _, _, message, ier = leastsq(inside, x0.copy(), Dfun=jac, full_output=True,
                                        ftol=tol, xtol=tol, gtol=tol, maxfev=max_nfev,
                                        factor=100.0, diag=np.ones(x0.size))
    except (_LeftBounds, ValueError, FloatingPointError, np.linalg.LinAlgError):
        return None
    if ier not in (1, 2, 3, 4):
        return None
    x = np.atleast_1d(x)
    return x, jac(x), str(message)


def _residual_jacobian(jac: Callable[[dict[str, float]], np.ndarray], res: _Residual
                       ) -> Callable[[np.ndarray], np.ndarray]:
    """The Jacobian of the weighted residual from the model's analytic one."""
    def residual_jac(theta: np.ndarray) -> np.ndarray:
        theta = np.atleast_1d(theta)
        out = np.asarray(jac(res.values(theta)), float)
        out *= -1.0
        if res.w is not None:
            out *= res.w[:, None]
        bad = np.flatnonzero(~np.isfinite(out).all(axis=0))
        if bad.size:  # e.g. d(x**c)/dc = x**c log x at x = 0: differences there
            _difference_columns(res, out, theta, bad)
        return out
    return residual_jac


def _difference_columns(res: _Residual, jac: np.ndarray, theta: np.ndarray,
                        cols: np.ndarray) -> None:
    """Replace columns ``cols`` of the residual's Jacobian by forward differences."""
    r0 = res(theta)
    for j in cols:
        h = 1.5e-8 * max(abs(float(theta[j])), 1.0)
        step = theta.copy()
        step[j] = step[j] + h if step[j] + h <= res.hi[j] else step[j] - h
        jac[:, j] = (res(step) - r0) / (step[j] - theta[j])


def _finish(res: _Residual, theta: np.ndarray, jac: np.ndarray | None, success: bool,
            message: str, nfev: int) -> LocalFit:
    """lmfit's bookkeeping of a solve: residual at the solution, statistics, covariance."""
    model = res.model_at(theta)  # the residual there, computed as the solver's was
    resid = res.y - model
    if res.w is not None:
        resid *= res.w
    theta = np.minimum(np.maximum(np.atleast_1d(theta), res.lo), res.hi)
    ndata, nvary = resid.size, len(res.names)
    chisqr, redchi, aic, bic = fit_statistics(float((resid ** 2).sum()), ndata, nvary)
    del resid
    covar = _covariance(jac, redchi)
    params = {k: Estimate(v) for k, v in res.held.items()}
    for i, k in enumerate(res.names):
        se = None if covar is None else float(np.sqrt(covar[i, i]))
        params[k] = Estimate(float(theta[i]), se)
    if covar is not None:
        for k in res.held:
            params[k].stderr = 0.0
    return LocalFit(params=params, var_names=list(res.names), covar=covar,
                    best_fit=model, chisqr=chisqr, redchi=redchi, aic=aic, bic=bic,
                    success=success, message=message, nfev=nfev)


def fit_statistics(chisqr: Any, ndata: Any, nvary: Any) -> tuple[Any, Any, Any, Any]:
    """lmfit's chi-square (floored), reduced chi-square, AIC and BIC of a solve.

    Numbers or arrays (one entry per fit), so that single fits and batches
    (:mod:`frictionlaws.fitting.batch`) report the same statistics.

    Parameters
    ----------
    chisqr : float or numpy.ndarray
        Sum of the squared weighted residuals.
    ndata, nvary : int or numpy.ndarray
        Rows and varied parameters.

    Returns
    -------
    tuple
        ``(chisqr, redchi, aic, bic)``; ``chisqr`` floored at ``1e-250 * ndata``.
    """
    redchi = chisqr / np.maximum(1, ndata - nvary)
    chisqr = np.maximum(chisqr, 1e-250 * ndata)
    neg2ll = ndata * np.log(chisqr / ndata)
    return chisqr, redchi, neg2ll + 2 * nvary, neg2ll + np.log(ndata) * nvary


def _covariance(jac: np.ndarray | None, redchi: float) -> np.ndarray | None:
    """``inv(J^T J)`` times the reduced chi-square; None when singular or not computed.

    Computed with the Jacobian's columns scaled to unit length (:func:`scaled_covariance`),
    as the batches of :mod:`frictionlaws.fitting.batch` are.
    """
    if jac is None:
        return None
    cov = scaled_covariance(np.asarray(jac, float))
    return None if cov is None else cov * redchi


def scaled_covariance(jac: np.ndarray) -> np.ndarray | None:
    """``inv(J' J)`` of Jacobians ``(..., n, k)``, computed with unit-length columns.

    Parameters
    ----------
    jac : numpy.ndarray
        The Jacobians of the weighted residuals (one, or a stack of them).

    Returns
    -------
    numpy.ndarray or None
        ``(..., k, k)``; None when some ``J' J`` is singular.
    """
    d = np.sqrt(np.einsum("...nk,...nk->...k", jac, jac))
    d = np.where(d > 0, d, 1.0)
    unit = jac / d[..., None, :]
    try:
        inv = np.linalg.inv(np.matmul(np.swapaxes(unit, -1, -2), unit))
    except np.linalg.LinAlgError:
        return None
    return np.asarray(inv / (d[..., :, None] * d[..., None, :]))


def central_jacobian(func: Callable[[np.ndarray], np.ndarray], x: np.ndarray,
                     scales: np.ndarray | None = None) -> np.ndarray:
    """Central-difference Jacobian of ``func`` (vector -> vector) at ``x``.

    The first step is 1e-6 of the parameter's magnitude or of its typical
    scale (``scales``, e.g. the declared default), whichever is larger, or
    1e-6 in its unit when both are zero.  When that step moves the model by
    less than 1e-7 of its size (a parameter sitting near a bound of 0, say),
    the step grows until it does, so every column stands well above round-off:
    eight times tenfold, and on until the step reaches 1e-6 in the parameter's unit
    (a value of 1e-20 at a bound of 0 has a slope like any other).  The fit's
    identifiability check and the confidence band of a fitted curve both use it.

    Parameters
    ----------
    func : callable
        Vector of parameters -> vector of model values.
    x : numpy.ndarray
        The point.
    scales : numpy.ndarray, optional
        Typical magnitude of each parameter.

    Returns
    -------
    numpy.ndarray
        The (len(func(x)), len(x)) Jacobian.
    """
    f0 = func(x)
    size = max(float(np.linalg.norm(f0)), 1e-300)
    jac = np.empty((f0.size, x.size))
    for j in range(x.size):
        mag = max(abs(x[j]), abs(scales[j]) if scales is not None else 0.0)
        h = 1e-6 * mag if mag > 0 else 1e-6
        for tries in range(400):
            xp, xm = x.copy(), x.copy()
            xp[j] += h
            xm[j] -= h
            diff = func(xp) - func(xm)
            if (np.linalg.norm(diff) >= 1e-7 * size or not np.all(np.isfinite(diff))
                    or (tries >= 7 and h >= 1e-6)):
                break
            h *= 10.0
        jac[:, j] = diff / (2 * h)  # the step that made diff
    return jac


def least_squares_solve(residual: Callable[[np.ndarray], np.ndarray], x0: Any,
                        **options: Any) -> Any:
    """Solve one least-squares problem with scipy's ``least_squares``.

    The package's one call of it: the fit's bounded trust region (:func:`solve`), the
    bootstrap's refits, the shared fit, the Magic Formula stages and the validation
    cases all come here with their own residuals and options, so that the solver, its
    version and its defaults are in one place.

    Parameters
    ----------
    residual : callable
        Parameter vector -> residual vector.
    x0 : array_like
        The start.
    **options
        ``bounds``, ``method``, ``x_scale``, tolerances, ``jac``, ... as scipy takes them.

    Returns
    -------
    scipy.optimize.OptimizeResult
        scipy's result (``x``, ``cost``, ``fun``, ``jac``, ``status``, ...).
    """
    from scipy.optimize import least_squares

    return least_squares(residual, x0, **options)


def lmfit_fit(model: Any, y: Any, params: Any, **kwargs: Any) -> Any:
    """Minimise with lmfit: the package's one call of ``lmfit.Model.fit``.

    Used for lmfit's other minimisers (``fit(..., method="nelder")``), the lmfit model
    of a fit result and the master curve's WLF fit.

    Parameters
    ----------
    model : lmfit.Model
        The model.
    y : array_like
        The data.
    params : lmfit.Parameters
        The start and bounds.
    **kwargs
        Independent variables, ``weights``, ``method``, ... as lmfit takes them.

    Returns
    -------
    lmfit.model.ModelResult
        lmfit's result.
    """
    return model.fit(y, params, **kwargs)
