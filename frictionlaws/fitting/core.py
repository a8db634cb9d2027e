""":func:`fit`: the one entry that sets a fit up, searches, diagnoses and builds its result.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np

from ..base.errors import FitError, InputError
from ..law import Law
from ..law.registry import get_law
from .batch import polish
from .data import check_fit_options
from .diagnosis import (
    _correlation,
    _derived,
    _diagnose,
    _estimates,
    _law_checks,
    _metrics,
    _status,
    _withhold_doubtful,
)
from .methods import DEFAULT_METHOD
from .result import FitResult, ParamEstimate, _provenance
from .robust import check_uncertainty_options
from .search import _global_stage, _multistart, _polish, _Search, _Setup, _setup
from .uncertainty import _ErrorInputs, _robust_errors

__all__ = ["fit"]


def fit(
    law: str | Law, data: Any, *, fix: Mapping[str, float] | None = None,
    free: Iterable[str] = (), initial: Mapping[str, float] | None = None,
    weights: Any = "auto", starts: int | None = None, seed: int = 0,
    on_invalid: str = "error", mapping: Mapping[str, str] | None = None,
    units: Mapping[str, str] | None = None, area: Any = None,
    method: str = DEFAULT_METHOD, uncertainty: str = "asymptotic", n_boot: int = 1000,
    n_jobs: int = 1, interval: str = "bca", global_stage: str = "auto", lean: bool = False,
) -> FitResult:
    """Fit ``law`` to ``data`` (bounded least squares, several starts).

    Parameters
    ----------
    law : str or Law
        Law id or alias, or a :class:`~frictionlaws.law.Law`.
    data : str, path, Dataset, DataFrame or mapping
        A packaged dataset name, a CSV path, a loaded dataset, or SI arrays (``"mu"``
        and the law's variables).
    fix : mapping, optional
        Parameters (or settings) held at the given values (``{"n": 1/3}``).
    free : iterable of str, optional
        Settings fitted as parameters (e.g. ``["E_v"]`` for Denny).
    initial : mapping, optional
        Initial values overriding the law's data-driven guess.
    weights : {"auto"}, None or array
        ``"auto"``: 1/mu_std, else sqrt(n), when the dataset has them; None: unweighted.
    starts : int, optional
        Random starts forced for non-linear laws (default: 6, only when the guess, the
        defaults and the presets end at different minima).
    seed : int
        Seed of the random starts, the global stage and the bootstrap.
    on_invalid : {"error", "drop"}
        Rows where the law is singular (v = 0 in a log-v law): refuse, or drop and say so.
    mapping, units, area : optional
        Column mapping, column units and contact area for :func:`~frictionlaws.io.load_dataset`.
    method : str
        One of :data:`~frictionlaws.fitting.methods.FIT_METHODS` (default: trust region).
    uncertainty : {"asymptotic", "sandwich", "bootstrap"}
        Standard errors from the fit's covariance, the HC3 sandwich (uneven scatter), or
        a bootstrap over whole conditions (a law that misses a trend); see
        :mod:`frictionlaws.fitting.robust`.
    n_boot, n_jobs : int
        Bootstrap replicates (20..100000) and joblib workers (-1: one per core).
    interval : {"bca", "percentile"}
        Bootstrap interval kind.
    global_stage : {"auto", "on", "off"}
        Bounded differential evolution before a local polish; ``"auto"``: only when the
        local starts end worse than the mean of mu or at different minima.
    lean : bool
        Values, metrics and undetermined names only (refits), polished to tight
        tolerances (:func:`_polish`): the optimum, not the solver's path or version.

    Returns
    -------
    FitResult
        Values, errors, diagnostics and metrics of the best fit.

    Raises
    ------
    InputError
        Bad data or options, unknown names, data without the law's variables.
    FitError
        When no start gives a finite fit.
    """
    law = get_law(law)
    _check_fit_options(method, starts, seed, on_invalid, uncertainty, n_boot, n_jobs,
                       interval, global_stage, lean)
    setup = _setup(law, data, fix, free, initial, weights, on_invalid,
                   {"mapping": mapping, "units": units, "area": area})
    search = _Search(setup, method)
    _multistart(search, starts, seed)
    setup.notes.extend(_global_stage(search, global_stage, seed))
    (_polish if lean else polish)(search)  # to the optimum itself (a stack's too)
    if search.best is None:
        errors = search.errors
        raise FitError(f"law '{law.id}' could not be fitted to '{setup.fd.name}': no start "
                       f"gave a finite result{(' (' + errors[0] + ')') if errors else ''}")
    return _lean_result(setup, search) if lean else _result(setup, search, dict(
        method=uncertainty, n_boot=n_boot, n_jobs=n_jobs, interval=interval, seed=seed))


def _check_fit_options(method: Any, starts: Any, seed: Any, on_invalid: Any,
                       uncertainty: Any, n_boot: Any, n_jobs: Any, interval: Any,
                       global_stage: Any, lean: Any) -> None:
    """Every keyword option of :func:`fit`, refused with a clear InputError when wrong."""
    check_fit_options(method, starts, seed, on_invalid)
    check_uncertainty_options(uncertainty, n_boot, n_jobs, interval)
    if global_stage not in ("auto", "on", "off"):
        raise InputError(f"global_stage must be 'auto', 'on' or 'off', not {global_stage!r}",
                         option="global_stage")
    if not isinstance(lean, bool) or (lean and uncertainty != "asymptotic"):
        raise InputError(f"lean must be True or False, and True only with the asymptotic "
                         f"uncertainty (got lean={lean!r}, uncertainty={uncertainty!r})",
                         option="lean")


def _result(setup: _Setup, search: _Search, opts: dict[str, Any]) -> FitResult:
    """The diagnostics, metrics and errors of the best fit, as a :class:`FitResult`."""
    from scipy.special import stdtrit  # Student's t quantile, without scipy.stats

    law, best, fd, y = setup.law, search.best, setup.fd, setup.y
    warn_msgs: list[str] = []
    diag = _diagnose(setup, search, warn_msgs)
    n, k = y.size, len(setup.vary_names)
    dof = n - k
    tval = float(stdtrit(dof, 0.975)) if dof > 0 else math.inf
    # a robust method's intervals replace the asymptotic ones: a cut asymptotic interval
    # is worth a warning only when the asymptotic errors are the ones reported
    cut_msgs: list[str] = warn_msgs if opts["method"] == "asymptotic" else []
    estimates = _estimates(setup, search, diag, tval, dof, warn_msgs, cut_msgs)
    corr = _correlation(best)
    metrics = _metrics(y, best, k, setup.w is not None, warn_msgs)
    success, message = _status(best, metrics["r2"], warn_msgs)
    _law_checks(law, diag.full_values, fd, warn_msgs)
    cov_names = list(best.var_names) if best.covar is not None else []
    derived = _derived(law, diag.full_values, cov_names,
                       None if best.covar is None else np.asarray(best.covar), diag.non_id)
    fitted = np.asarray(best.best_fit, float)
    unc_info = _robust_errors(
        _ErrorInputs(law, fd, setup.x, y, setup.w, diag.vary, diag.full_values, setup.bounds,
                     diag.jac, y - fitted, diag.non_id, tval),
        estimates, derived, corr, warn_msgs, opts)
    if unc_info["method"] == "asymptotic" and cut_msgs is not warn_msgs:
        warn_msgs.extend(cut_msgs)
    _withhold_doubtful(law, diag, estimates, derived, warn_msgs)
    return FitResult(
        law=law, params=estimates, settings=setup.settings, metrics=metrics,
        correlation=corr, success=success, message=message, warnings=warn_msgs,
        non_identifiable=diag.non_id, derived=derived,
        data={"name": fd.name, "source": fd.source, "n": int(n),
              "ranges": {k2: list(v) for k2, v in fd.ranges().items()}},
        notes=setup.notes, provenance=_provenance(), uncertainty=unc_info,
        local_fit=best, residual=y - fitted, best_fit=fitted, fit_data=fd)


def _lean_result(setup: _Setup, search: _Search) -> FitResult:
    """The values, metrics, convergence and identifiability of the best fit, nothing else.

    The identifiability check (one Jacobian and its SVD) stays: a refit whose rows cannot
    determine a parameter predicts the rows left out from an arbitrary point of a flat
    valley, and a comparison must say so.
    """
    best, y, fd = search.best, setup.y, setup.fd
    warn_msgs: list[str] = []
    non_id = _diagnose(setup, search, []).non_id
    metrics = _metrics(y, best, len(setup.vary_names), setup.w is not None, warn_msgs)
    success, message = _status(best, metrics["r2"], warn_msgs)
    params = {}
    for name in setup.names:
        est = best.params[name]
        fixed = name in setup.fix
        held = fixed or name in search.best_pinned
        se = None if held or name in non_id or est.stderr is None or \
            not np.isfinite(est.stderr) else float(est.stderr)
        params[name] = ParamEstimate(name, float(est.value), se, None, setup.unit(name),
                                     fixed=fixed, identifiable=name not in non_id)
    fitted = np.asarray(best.best_fit, float)
    return FitResult(
        law=setup.law, params=params, settings=setup.settings, metrics=metrics,
        correlation={}, success=success, message=message, warnings=warn_msgs,
        non_identifiable=non_id, derived={},
        data={"name": fd.name, "source": fd.source, "n": int(y.size)},
        notes=setup.notes + ["lean fit: values, goodness of fit and identifiability only "
                             "(no intervals or derived quantities)"],
        uncertainty={"method": "none (lean fit)"}, local_fit=best, residual=y - fitted,
        best_fit=fitted, fit_data=fd)

