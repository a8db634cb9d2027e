"""The views of a fit result: lmfit, pandas, Jupyter and a figure.

* :func:`model_result`: the fit as lmfit's :class:`~lmfit.model.ModelResult`, refitted
  by lmfit from the fitted values (the same optimum).
* :func:`params_frame`: the parameters as a tidy :class:`pandas.DataFrame`, in display
  units (:mod:`frictionlaws.base.display`) or SI.
* :func:`result_html`: the HTML Jupyter shows for a fit result (``_repr_html_``).
* :func:`plot_result`: data, fitted curve, 95 % confidence band
  (:func:`confidence_band`) and residuals.

A law's own integrations (its lmfit model, its HTML, evaluation on
:class:`xarray.DataArray` inputs) are in the law room (:mod:`frictionlaws.law.interop`,
:mod:`frictionlaws.law.evaluation`); a dataset's HTML beside the dataset
(:func:`frictionlaws.io.dataset_html`).  Heavy libraries are imported inside the
functions that need them.
"""

from __future__ import annotations

import html
import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..base.display import check_units, display_param_unit, unit_text
from ..base.errors import InputError
from ..base.units import QUANTITIES, to_display
from ..law import VARIABLES
from ..law.interop import lmfit_model, table_html
from .lsq import central_jacobian as _jacobian
from .lsq import lmfit_fit

__all__ = ["model_result", "params_frame", "result_html", "plot_result", "confidence_band"]


# ------------------------------------------------------------------------ lmfit
def model_result(result: Any) -> Any:
    """The lmfit :class:`~lmfit.model.ModelResult` of a fit, for lmfit's own tools.

    The law's :func:`lmfit_model` is fitted to the same data, weights and fixed values,
    starting from the library's optimum, so lmfit ends where the library did (its
    ``fit_report()``, ``conf_interval()``, ``eval_uncertainty()`` then apply).

    Parameters
    ----------
    result : FitResult
        A fit that still holds its data (``result.fit_data``; results read back from
        a file do not).

    Returns
    -------
    lmfit.model.ModelResult
        lmfit's result for the same fit.
    """
    fd = getattr(result, "fit_data", None)
    if fd is None:
        raise InputError("this result does not hold the data it was fitted to (a result "
                         "read from a file): refit to get lmfit's ModelResult")
    law = result.law
    model = lmfit_model(law, values=result.values)
    params = model.make_params()
    for name, est in result.params.items():
        params[name].set(value=est.value, vary=not est.fixed)
    for name, value in result.settings.items():
        if name in params and name not in result.params:
            params[name].set(value=value, vary=False)

    y = fd.arrays["mu"]
    xs = {k: fd.arrays[k] for k in law.variables} or {"x": y}
    with np.errstate(all="ignore"):
        return lmfit_fit(model, y, params, weights=fd.weights, **xs)


# ----------------------------------------------------------------------- pandas
def params_frame(result: Any, units: str = "display") -> Any:
    """The fitted parameters as a DataFrame: one row per parameter.

    Columns: ``value``, ``stderr``, ``ci95_low``, ``ci95_high``, ``unit``, ``fixed``;
    the index is the parameter name.  ``units="display"`` shows pressures in MPa
    (``b`` of Thirion in 1/MPa), ``"si"`` the values as fitted (see
    :mod:`frictionlaws.base.display`); dimensionless is ``-``.
    """
    import pandas as pd

    check_units(units)
    rows = []
    for name, est in result.params.items():
        unit, factor = (display_param_unit(est.unit) if units == "display"
                        else (unit_text(est.unit), 1.0))
        ci = est.ci95 if est.ci95 is not None else (math.nan, math.nan)
        rows.append({"param": name, "value": est.value * factor,
                     "stderr": math.nan if est.stderr is None else est.stderr * factor,
                     "ci95_low": ci[0] * factor, "ci95_high": ci[1] * factor, "unit": unit,
                     "fixed": bool(est.fixed)})
    frame = pd.DataFrame(rows).set_index("param")
    frame.attrs["law"] = result.law.id
    frame.attrs["units"] = units
    return frame


# ---------------------------------------------------------------------- Jupyter
def result_html(result: Any, units: str = "display") -> str:
    """HTML for a fit result: parameters with errors and CI, metrics and warnings."""
    frame = params_frame(result, units)
    rows = [{"param": k, "value": r["value"], "stderr": r["stderr"],
             "ci95": (r["ci95_low"], r["ci95_high"]), "unit": r["unit"], "fixed": r["fixed"]}
            for k, r in frame.iterrows()]
    metrics = {k: v for k, v in result.metrics.items()
               if k in ("r2", "adj_r2", "rmse", "aic", "bic", "n", "k")}
    warn = "".join(f"<li>{html.escape(w)}</li>" for w in result.warnings)
    shown = "pressures in MPa" if units == "display" else "SI"
    return "\n".join([
        f"<h4>fit of <code>{html.escape(result.law.id)}</code>"
        f" ({'converged' if result.success else 'NOT converged'})</h4>",
        table_html(rows, caption=f"parameters ({shown})"),
        table_html([metrics], caption="metrics"),
        f"<ul>{warn}</ul>" if warn else ""])


# ----------------------------------------------------------------------- figure
def plot_result(result: Any, data: Any = None, *, x: str | None = None, ax: Any = None,
                units: str = "display") -> Any:
    """Data, fitted law, 95 % confidence band and residuals of a fit.

    Parameters
    ----------
    result : FitResult
        The fit.
    data : mapping or Dataset, optional
        The data (``mu`` and the law's variables, SI); by default the data the fit
        kept (``result.fit_data``; results loaded from JSON keep only ranges).
    x : str, optional
        The variable on the horizontal axis (default: the law's first varying one).
    ax : sequence of two matplotlib Axes, optional
        Where to draw (curve, residuals); a new figure otherwise.
    units : {"display", "si"}
        The horizontal axis in the variable's display unit (p in MPa, T in degC;
        default) or in SI.

    Returns
    -------
    matplotlib.figure.Figure
    """
    check_units(units)
    arrays = _arrays_of(data if data is not None else getattr(result, "fit_data", None))
    if arrays is None or "mu" not in arrays:
        raise InputError("no data to plot: pass the data (results loaded from JSON keep "
                         "only the fitted ranges)")
    name = x or next((v for v in result.law.variables
                      if np.ptp(np.asarray(arrays[v], float)) > 0), None)
    if name is None or name not in arrays:
        raise InputError(f"law '{result.law.id}' has no varying variable '{x or ''}' to plot "
                         "against")
    return _draw(result, arrays, name, ax, units)


def _arrays_of(data: Any) -> Mapping[str, Any] | None:
    if data is None:
        return None
    arrays = getattr(data, "arrays", data)
    return arrays() if callable(arrays) else arrays


def confidence_band(result: Any, variables: Mapping[str, np.ndarray]) -> np.ndarray:
    """Half-width of the 95 % confidence band of the fitted curve at ``variables``.

    First-order propagation of the parameter covariance (standard errors and
    correlations of the fit) through a central-difference Jacobian of the law, with
    Student's t on the fit's residual degrees of freedom, as its parameter intervals
    (the normal 1.96 would be narrower than them on few rows).  Where
    the curve depends on a fitted parameter without a standard error (one the data
    cannot determine, or whose error was withheld) the band is NaN: undetermined, not
    zero nor the narrower band of the other parameters.
    """
    shape = np.broadcast_shapes(*(np.shape(v) for v in variables.values()))
    free = [k for k, e in result.params.items() if not e.fixed]
    known = [k for k in free if result.params[k].stderr is not None
             and math.isfinite(result.params[k].stderr)]
    jac = {k: _slope(result, variables, k) for k in free}
    var = np.zeros(shape)
    if known:
        se = np.array([result.params[k].stderr for k in known])
        corr = np.array([[1.0 if a == b else result.correlation.get(a, {}).get(b, 0.0)
                          for b in known] for a in known])
        cols = np.stack([np.broadcast_to(jac[k], shape) for k in known], axis=-1)
        var = np.einsum("...i,ij,...j->...", cols, corr * np.outer(se, se), cols)
    from scipy.special import stdtrit  # Student's t quantile, as the fit's intervals

    dof = int(result.metrics.get("n", 0) or 0) - int(result.metrics.get("k", 0) or 0)
    tval = float(stdtrit(dof, 0.975)) if dof > 0 else math.nan
    half = tval * np.sqrt(np.maximum(var, 0.0))
    for k in free:
        if k not in known:
            half = np.where(np.broadcast_to(jac[k], shape) != 0, np.nan, half)
    return half


def _slope(result: Any, variables: Mapping[str, np.ndarray], name: str) -> np.ndarray:
    """d mu / d ``name`` at ``variables`` (central difference).

    The step is the fit's own (:func:`frictionlaws.fitting.lsq.central_jacobian`): it
    grows until it stands above round-off, so a parameter sitting at 0 (a bound) keeps
    its true slope instead of a step of 1e-18 that leaves none.
    """
    base = result.values
    shape = np.broadcast_shapes(*(np.shape(v) for v in variables.values()))
    law = result.law
    default = (law.param(name).default if name in law.param_names
               else law.setting_values.get(name, 0.0))

    def mu_of(theta: np.ndarray) -> np.ndarray:
        mu = law.evaluate(variables, {**base, name: float(theta[0])})
        return np.broadcast_to(np.asarray(mu, float), shape).ravel()

    jac = _jacobian(mu_of, np.array([base[name]], float), np.array([default], float))
    return jac[:, 0].reshape(shape)


def _draw(result: Any, arrays: Mapping[str, Any], name: str, ax: Any, units: str) -> Any:
    import matplotlib.pyplot as plt

    if ax is None:
        _, ax = plt.subplots(2, 1, figsize=(6, 5), sharex=True,
                             gridspec_kw={"height_ratios": [3, 1]})
    fig = ax[0].figure
    xs = np.asarray(arrays[name], float)
    mu = np.asarray(arrays["mu"], float)
    variables = {v: np.asarray(arrays[v], float) for v in result.law.variables}
    pred = np.broadcast_to(np.asarray(result.law.evaluate(variables, result.values), float),
                           mu.shape)
    half = np.broadcast_to(confidence_band(result, variables), mu.shape)
    order = np.argsort(xs, kind="stable")
    unit = _unit(name)
    if units == "display" and name in QUANTITIES:
        xs, unit = to_display(xs, name), _unit(name, display=True)
    ax[0].plot(xs, mu, "o", ms=4, label="data")
    ax[0].plot(xs[order], pred[order], "-", label=f"{result.law.id} fit")
    ax[0].fill_between(xs[order], (pred - half)[order], (pred + half)[order], alpha=0.25,
                       label="95 % confidence band")
    ax[1].axhline(0.0, color="0.5", lw=0.8)
    ax[1].plot(xs, mu - pred, "o", ms=3)
    ax[1].set_xlabel(f"{name} [{unit}]")
    ax[0].set_ylabel("mu [-]")
    ax[1].set_ylabel("residual [-]")
    ax[0].legend()
    return fig


def _unit(name: str, display: bool = False) -> str:
    var = VARIABLES.get(name)
    if var is None:
        return unit_text(None)
    return unit_text(var.display_unit if display else var.unit)
