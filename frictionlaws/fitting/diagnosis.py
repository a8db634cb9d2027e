"""What the optimum says: the Jacobian's identifiability (:data:`RANK_TOL`, :data:`WEAK_TOL`),
standard errors and intervals, correlations, goodness of fit and the warnings they raise.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..law import Law
from ..law.evaluation import BLOCK_ROWS, BLOCKED_FROM
from .data import FitData, _fmt_range
from .lsq import central_jacobian as _jacobian
from .result import ParamEstimate, _numpy_ns
from .robust import ZERO_SPREAD
from .search import _Search, _Setup

__all__ = ["RANK_TOL", "WEAK_TOL", "weak_warning", "metric_table", "derived_columns"]


#: Relative singular value below which a parameter direction is not identifiable.
RANK_TOL = 1e-5


#: Relative singular value below which a parameter direction is poorly determined.
WEAK_TOL = 1e-2




def _unit_columns_r(jac: np.ndarray, cols: list[int], norms: np.ndarray) -> np.ndarray:
    """The columns ``cols`` of ``jac`` scaled to unit length, or on large data their R factor.

    ``J = Q R`` leaves the singular values and right singular vectors unchanged, and R is
    built block by block (``R = qr([R; J_block])``), so a fit on millions of rows needs no
    scaled copy of the Jacobian nor an n-row U of its SVD.
    """
    n = jac.shape[0]
    if n < BLOCKED_FROM:
        return jac[:, cols] / norms
    r = np.zeros((0, len(cols)))
    for start in range(0, n, BLOCK_ROWS):
        block = jac[start:start + BLOCK_ROWS, cols] / norms
        if not np.all(np.isfinite(block)):
            return block
        r = np.asarray(np.linalg.qr(np.vstack([r, block]), mode="r"))
    return r


def _identifiability(jac: np.ndarray, names: list[str]) -> tuple[list[str], list[str], float]:
    """Names of non-identifiable and poorly determined parameters, and the ratio s_min/s_max."""
    norms = np.linalg.norm(jac, axis=0)
    dead = [names[j] for j in range(len(names)) if not np.isfinite(norms[j]) or norms[j] == 0]
    ok = [j for j in range(len(names)) if np.isfinite(norms[j]) and norms[j] > 0]
    if not ok:
        return list(names), [], 0.0
    jn = _unit_columns_r(jac, ok, norms[ok])
    if not np.all(np.isfinite(jn)):
        return list(names), [], 0.0
    _, s, vt = np.linalg.svd(jn, full_matrices=False)
    if jn.shape[0] < jn.shape[1]:
        s = np.concatenate([s, np.zeros(jn.shape[1] - jn.shape[0])])
        vt = np.linalg.svd(np.vstack([jn, np.zeros((jn.shape[1] - jn.shape[0], jn.shape[1]))]))[2]
    rel = s / s[0] if s[0] > 0 else np.zeros_like(s)
    non_id, weak = _directions(rel, vt, [names[j] for j in ok], dead)
    order = {n: i for i, n in enumerate(names)}
    return (sorted(non_id, key=order.__getitem__), sorted(weak, key=order.__getitem__),
            float(rel[-1]) if rel.size else 0.0)


def _directions(rel: np.ndarray, vt: np.ndarray, names: list[str], dead: list[str]
                ) -> tuple[set[str], set[str]]:
    """The parameters the data cannot determine and those poorly determined.

    ``rel`` are the relative singular values of the unit-column Jacobian and ``vt`` its
    right singular vectors (rows), over the parameters ``names``; a direction below
    :data:`WEAK_TOL` (:data:`RANK_TOL`) involves every parameter whose component is
    above a tenth of its largest.  ``dead`` (columns of zeros) are undetermined too.
    """
    non_id: set[str] = set(dead)
    weak: set[str] = set()
    for i, r in enumerate(rel):
        if r < WEAK_TOL:
            comp = np.abs(vt[i])
            involved = {names[j] for j in np.flatnonzero(comp > 0.1 * comp.max())}
            (non_id if r < RANK_TOL else weak).update(involved)
    return non_id, weak - non_id


@dataclass
class _Diagnosis:
    """The best fit's values and what the data can determine of them."""

    vary: list[str]
    values: dict[str, float]
    full_values: dict[str, float]
    jac: np.ndarray
    non_id: list[str]


def _diagnose(setup: _Setup, search: _Search, warn_msgs: list[str]) -> _Diagnosis:
    """Identifiability from the Jacobian at the best fit, with its warnings."""
    law, best, w = setup.law, search.best, setup.w
    vary = [k for k in setup.vary_names if k not in search.best_pinned]
    values = {k: float(best.params[k].value) for k in setup.names}
    full_values = {**setup.settings, **values}

    def residual_vec(theta: np.ndarray) -> np.ndarray:
        out = search.evaluate({**values, **dict(zip(vary, (float(t) for t in theta)))})
        return out * (w if w is not None else 1.0)

    jac = search.jacobian(values, vary)
    if jac is not None and np.all(np.isfinite(jac)):
        if w is not None:
            jac *= w[:, None]
    else:
        theta0 = np.array([values[k] for k in vary])
        scales = np.array([setup.typical(k) for k in vary])
        jac = _jacobian(residual_vec, theta0, scales)
    non_id, weak, ratio = _identifiability(jac, vary)
    for var in (v for v in law.variables if v in setup.fd.arrays):
        xs = setup.fd.arrays[var]
        if xs.size and np.ptp(xs) == 0:
            warn_msgs.append(
                f"the data have a single value of {var} ({_fmt_range(var, xs[0], xs[0])}); "
                f"parameters acting through {var} cannot be determined")
    if non_id:
        warn_msgs.append(
            f"the data cannot determine {', '.join(non_id)}: they cannot be told apart "
            f"(Jacobian rank deficient, singular-value ratio {ratio:.1e}); their standard "
            "errors are withheld. Hold some of them fixed (argument fix) or use an "
            "identifiable form.")
    if weak:
        warn_msgs.append(weak_warning(weak))
    return _Diagnosis(vary, values, full_values, jac, non_id)


def weak_warning(weak: Sequence[str]) -> str:
    """The warning of parameters the data determine poorly (in the law's order)."""
    return f"{', '.join(weak)} poorly determined by the data (strongly correlated; wide intervals)"


def _estimates(setup: _Setup, search: _Search, diag: _Diagnosis, tval: float, dof: int,
               warn_msgs: list[str], cut_msgs: list[str]) -> dict[str, ParamEstimate]:
    """Value, standard error and 95 % interval of every parameter, with their warnings.

    The warnings of symmetric intervals cut at a bound go to ``cut_msgs``.
    """
    estimates: dict[str, ParamEstimate] = {}
    for name in setup.names:
        estimates[name] = _estimate(setup, search, diag, name, tval, dof, warn_msgs,
                                    cut_msgs)
        if name not in setup.fix and name not in search.best_pinned:
            _warn_at_bound(setup, name, diag.values[name], warn_msgs)
    return estimates


def _estimate(setup: _Setup, search: _Search, diag: _Diagnosis, name: str, tval: float,
              dof: int, warn_msgs: list[str], cut_msgs: list[str]) -> ParamEstimate:
    """One parameter's estimate (fixed, pinned at a bound, or fitted)."""
    law, value, unit, non_id = setup.law, diag.values[name], setup.unit(name), diag.non_id
    if name in setup.fix:
        return ParamEstimate(name, value, None, None, unit, fixed=True)
    if name in search.best_pinned:
        warn_msgs.append(f"no standard error for {name}: the global stage found the best "
                         f"fit with {name} exactly at its bound, where the law changes "
                         "form (the fit is not differentiable there)")
        return ParamEstimate(name, value, None, None, unit)
    se = search.best.params[name].stderr
    if name not in non_id and se is not None and np.isfinite(se) and dof > 0:
        limits = (law.setting(name) if name in setup.freed else law.param(name)).bounds
        ci = _clip_interval(name, (value - tval * se, value + tval * se), limits, cut_msgs)
        return ParamEstimate(name, value, float(se), ci, unit)
    if name not in non_id:
        why = (" (as many parameters as data points)" if dof <= 0 else
               " (the covariance matrix is singular because of the parameters the "
               "data cannot determine; fix those to get it)" if non_id else
               " (the covariance matrix could not be estimated)")
        warn_msgs.append(f"no standard error for {name}{why}")
    return ParamEstimate(name, value, None, None, unit, identifiable=name not in non_id)


def _warn_at_bound(setup: _Setup, name: str, value: float, warn_msgs: list[str]) -> None:
    """Warn when a fitted value sits at one of its declared bounds."""
    lo, hi = setup.bounds[name]
    scale = max(abs(value), abs(setup.typical(name)), 1e-300)
    if (math.isfinite(lo) and abs(value - lo) <= 1e-6 * max(scale, abs(lo))) or (
            math.isfinite(hi) and abs(value - hi) <= 1e-6 * max(scale, abs(hi))):
        warn_msgs.append(f"{name} = {value:.6g} is at its bound "
                         f"[{lo:g}, {hi:g}]: the optimum may lie beyond it")


def _correlation(best: Any) -> dict[str, dict[str, float]]:
    """The parameters' correlation matrix from lmfit's covariance (empty without one)."""
    corr: dict[str, dict[str, float]] = {}
    if best.covar is None:
        return corr
    names = list(best.var_names)
    cv = np.asarray(best.covar)
    sd = np.sqrt(np.clip(np.diag(cv), 0, None))
    with np.errstate(all="ignore"):
        cm = cv / np.outer(sd, sd)
    for i, a in enumerate(names):
        corr[a] = {b: float(cm[i, j]) for j, b in enumerate(names)}
    return corr


def _metrics(y: np.ndarray, best: Any, k: int, weighted: bool, warn_msgs: list[str]
             ) -> dict[str, Any]:
    """Goodness of fit: unweighted residuals for R^2/RMSE; lmfit's AIC/BIC."""
    table = metric_table(y[None, :], np.asarray(best.best_fit, float)[None, :], k,
                         *(np.array([float(getattr(best, a))])
                           for a in ("aic", "bic", "chisqr", "redchi")))
    if table.pop("flat")[0]:
        warn_msgs.append("mu takes one value in these data: R^2 is undefined (there is "
                         "no variation to explain); judge the fit by its RMSE")
    out: dict[str, Any] = {key: float(v[0]) for key, v in table.items()}
    out.update(n=int(y.size), k=int(k), weighted=weighted)
    return out


def metric_table(y: np.ndarray, fitted: np.ndarray, k: int, aic: np.ndarray,
                 bic: np.ndarray, chisqr: np.ndarray, redchi: np.ndarray
                 ) -> dict[str, np.ndarray]:
    """Goodness of fit of fits on equally many rows, one row of ``y`` and ``fitted`` each.

    Parameters
    ----------
    y, fitted : numpy.ndarray
        The data and the fitted law, ``(B, n)``.
    k : int
        The fitted parameters.
    aic, bic, chisqr, redchi : numpy.ndarray
        The solver's statistics, ``(B,)``.

    Returns
    -------
    dict of numpy.ndarray
        ``r2`` (NaN where mu is constant to rounding, flagged in ``flat``), ``adj_r2``,
        ``rmse``, ``mae``, ``max_abs_residual``, ``aic``, ``aicc``, ``bic``, ``chisqr``,
        ``redchi`` (NaN without degrees of freedom), each ``(B,)``.
    """
    n = y.shape[1]
    resid = y - fitted
    ss_res = np.sum(resid**2, axis=1)
    ss_tot = np.sum((y - y.mean(axis=1, keepdims=True)) ** 2, axis=1)
    flat = ss_tot <= n * (1e-12 * np.max(np.abs(y), axis=1)) ** 2  # mu constant to round-off
    with np.errstate(divide="ignore", invalid="ignore"):
        r2 = np.where(flat, math.nan, 1.0 - ss_res / ss_tot)
    adj = 1.0 - (1.0 - r2) * (n - 1) / (n - k) if n - k > 0 else np.full_like(r2, math.nan)
    aicc = aic + 2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else np.full_like(aic, math.inf)
    return {"r2": r2, "adj_r2": adj, "rmse": np.sqrt(ss_res / n),
            "mae": np.mean(np.abs(resid), axis=1),
            "max_abs_residual": np.max(np.abs(resid), axis=1),
            "aic": aic, "aicc": aicc, "bic": bic, "chisqr": chisqr,
            "redchi": redchi if n - k > 0 else np.full_like(redchi, math.nan), "flat": flat}


def _status(best: Any, r2: float, warn_msgs: list[str]) -> tuple[bool, str]:
    """Converged, and not worse than the mean of mu; the message to report."""
    success, message = bool(best.success), str(best.message)
    if not success:
        warn_msgs.append(f"the optimiser did not report convergence: {best.message}")
    elif r2 < -1e-9:
        success = False
        message = (f"the fit is worse than the mean of mu (R^2 = {r2:.4g}): the law does not "
                   "describe these data")
        warn_msgs.append(message)
    return success, message


def _law_checks(law: Law, full_values: Mapping[str, float], fd: FitData,
                warn_msgs: list[str]) -> None:
    """Warn about inadmissible fitted values and data outside the law's domain."""
    adm = law.check_admissible(dict(full_values))
    if adm:
        warn_msgs.append(f"fitted parameters not admissible: {adm}")
    for var, count in law.outside_domain(fd.arrays).items():
        lo, hi = law.domain[var]
        warn_msgs.append(f"{count} data rows lie outside the law's valid domain of {var} "
                         f"({_fmt_range(var, lo, hi)})")


def _derived(law: Law, values: dict[str, float], names: list[str], cov: np.ndarray | None,
             non_id: list[str]) -> dict[str, dict[str, Any]]:
    """Derived quantities with uncertainties propagated from ``cov`` (delta method).

    ``names`` are the parameters (in ``cov``'s order); without a covariance the
    values are given without standard errors.
    """
    out: dict[str, dict[str, Any]] = {}
    if not law.derived:
        return out
    errors = cov is not None and not non_id
    columns = derived_columns(law, {k: np.array([v]) for k, v in values.items()},
                              list(names) if errors else [],
                              None if cov is None or not errors else np.asarray(cov)[None])
    for d in law.derived:
        value, se = columns[d.name]
        out[d.name] = {"value": float(value[0]),
                       "stderr": float(se[0]) if math.isfinite(se[0]) else None,
                       "unit": d.unit, "meaning": d.meaning}
    return out


def derived_columns(law: Law, values: Mapping[str, np.ndarray], names: list[str],
                    cov: np.ndarray | None) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """A law's derived quantities of ``B`` fits, with their delta-method standard errors.

    Parameters
    ----------
    law : Law
        The law.
    values : mapping
        Every parameter and setting, ``(B,)`` arrays.
    names : list of str
        The parameters ``cov`` is of (empty: no errors).
    cov : numpy.ndarray or None
        ``(B, k, k)`` covariances of ``names``.

    Returns
    -------
    dict
        Derived name -> ``(value, stderr)``, ``(B,)`` arrays; the error is NaN where
        there is none (no covariance, a value that is not finite, a negative variance).
    """
    size = len(next(iter(values.values())))
    theta = np.stack([np.asarray(values[k], float) for k in names], axis=-1) if names \
        else np.zeros((size, 0))
    out = {}
    for d in law.derived:
        def f(th: np.ndarray, d: Any = d) -> np.ndarray:
            vals = dict(values)
            vals.update({k: th[:, j] for j, k in enumerate(names)})
            return _derived_value(d, vals, size)
        value = f(theta)
        se = np.full(size, math.nan)
        if cov is not None and names:
            g = np.empty_like(theta)
            for j in range(theta.shape[1]):
                h = 1e-6 * np.maximum(np.abs(theta[:, j]), 1e-10)
                tp, tm = theta.copy(), theta.copy()
                tp[:, j] += h
                tm[:, j] -= h
                g[:, j] = (f(tp) - f(tm)) / (2 * h)
            var = np.einsum("bi,bij,bj->b", g, cov, g)
            with np.errstate(invalid="ignore"):
                se = np.where((var >= 0) & np.isfinite(var) & np.isfinite(value),
                              np.sqrt(np.abs(var)), math.nan)
        out[d.name] = (value, se)
    return out


def _derived_value(d: Any, values: Mapping[str, Any], size: int) -> np.ndarray:
    """One derived quantity of ``size`` fits (row by row where its formula takes numbers)."""
    with np.errstate(all="ignore"):  # 1/b at b = 0: infinite, reported without an error
        try:
            return np.broadcast_to(np.asarray(d.func(_numpy_ns(), **values), float),
                                   (size,)).copy()
        except (TypeError, ValueError, ArithmeticError):
            return np.array([float(d.value({k: v[i] if np.ndim(v) else v
                                            for k, v in values.items()}, _numpy_ns()))
                             for i in range(size)])


def _withhold_doubtful(law: Law, diag: _Diagnosis, estimates: dict[str, ParamEstimate],
                       derived: dict[str, dict[str, Any]], warn_msgs: list[str]) -> None:
    """The rules every error method ends on (asymptotic, sandwich, bootstrap alike).

    A standard error of exactly zero says nothing is known about the error (exact
    data, identical resamples), so it is withheld with a warning; a derived quantity
    has no error when a parameter it depends on has none.
    """
    def nil(se: float | None, value: float) -> bool:
        return se is not None and se <= ZERO_SPREAD * abs(value)

    zero = [k for k in diag.vary if nil(estimates[k].stderr, estimates[k].value)]
    for k in zero:
        estimates[k] = replace(estimates[k], stderr=None, ci95=None)
    if zero:
        warn_msgs.append(f"the standard error of {', '.join(zero)} comes out as 0 to "
                         "rounding (the residuals or resamples do not spread): it is "
                         "undetermined and withheld, not zero")
    orphans = [k for k in diag.vary if estimates[k].stderr is None]
    doubtful = [name for name, d in derived.items()
                if d.get("stderr") is not None and (
                    nil(d["stderr"], d["value"])
                    or _depends_on(law, diag.full_values, name, orphans))]
    for name in doubtful:
        derived[name] = {**derived[name], "stderr": None, "ci95": None}
    if doubtful:
        warn_msgs.append(f"no standard error for the derived {', '.join(doubtful)}: a "
                         f"parameter it depends on ({', '.join(orphans) or 'none'}) has none, "
                         "or it comes out as 0 to rounding")


def _depends_on(law: Law, values: Mapping[str, float], derived: str,
                params: Sequence[str]) -> bool:
    """True when the derived quantity changes with any of ``params`` (a relative nudge)."""
    d = next(x for x in law.derived if x.name == derived)
    with np.errstate(all="ignore"):
        base = d.value(dict(values), _numpy_ns())
        for k in params:
            nudged = dict(values)
            nudged[k] = values[k] * (1 + 1e-6) + 1e-12 * (values[k] == 0)
            if d.value(nudged, _numpy_ns()) != base:
                return True
    return False


def _clip_interval(name: str, ci: tuple[float, float], bounds: tuple[float, float],
                   warn_msgs: list[str]) -> tuple[float, float]:
    """A symmetric interval cut at the parameter's bounds, with a warning when cut."""
    lo, hi = max(ci[0], bounds[0]), min(ci[1], bounds[1])
    if (lo, hi) != tuple(ci):
        warn_msgs.append(
            f"the 95 % interval of {name} ({ci[0]:.4g} .. {ci[1]:.4g}) reaches past its "
            f"bounds [{bounds[0]:g}, {bounds[1]:g}] and is shown cut there: the symmetric "
            "interval describes this fit poorly; uncertainty 'bootstrap' gives a better one")
    return float(lo), float(hi)

