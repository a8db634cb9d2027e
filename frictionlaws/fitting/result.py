"""The fit's outcome: :class:`FitResult`, :class:`ParamEstimate`, the versioned JSON schema
(:data:`RESULT_FORMAT`, :data:`RESULT_VERSION`) and :func:`load_result`.
"""

from __future__ import annotations

import functools
import json
import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..base.errors import ExtrapolationWarning, InputError
from ..law import VARIABLES, Law
from ..law.registry import get_law

if TYPE_CHECKING:
    from ..law.bound import BoundLaw

import sys
from importlib.metadata import PackageNotFoundError, version

from .. import __version__
from ..base import jsonio
from ..base.display import display_param_unit
from ..base.jsonio import dumps
from ..base.limits import read_input
from ..base.outputs import check_input_file, check_outputs, write_text_atomic
from ..law import NUMPY
from ..law.bound import bound_from_result, outside_ranges
from .data import FitData, _fmt_range
from .robust import UNCERTAINTY_METHODS
from .views import model_result, params_frame, plot_result, result_html

__all__ = ["RESULT_FORMAT", "RESULT_VERSION", "ParamEstimate", "FitResult", "load_result"]


RESULT_FORMAT = "frictionlaws-fit-result"


RESULT_VERSION = 1


@dataclass(frozen=True)
class ParamEstimate:
    """One fitted (or fixed) parameter.

    ``stderr`` and ``ci95`` are None when the parameter was fixed or the data
    cannot determine it.
    """

    name: str
    value: float
    stderr: float | None
    ci95: tuple[float, float] | None
    unit: str
    fixed: bool = False
    identifiable: bool = True

    def to_dict(self) -> dict[str, Any]:
        return {"value": self.value, "stderr": self.stderr,
                "ci95": list(self.ci95) if self.ci95 is not None else None,
                "unit": self.unit, "fixed": self.fixed, "identifiable": self.identifiable}


@dataclass
class FitResult:
    """The outcome of :func:`fit` (or of :func:`load_result`).

    Parameters
    ----------
    law : Law
        The law fitted.
    params : dict
        Parameter name -> :class:`ParamEstimate` (fixed ones included).
    settings : dict
        Setting name -> value used (SI).
    metrics : dict
        Goodness of fit: ``r2``, ``adj_r2``, ``rmse``, ``mae``, ``max_abs_residual``,
        ``aic``, ``aicc``, ``bic``, ``chisqr``, ``redchi``, ``n``, ``k``, ``weighted``.
    correlation : dict
        Parameter -> parameter -> correlation coefficient.
    success : bool
        Whether the fit converged and beats the mean of mu.
    message : str
        The solver's message (or why the fit is refused).
    warnings : list of str
        Everything the user must know about this fit.
    non_identifiable : list of str
        Parameters the data cannot determine.
    derived : dict
        Derived quantity -> value, stderr, ci95, unit, meaning.
    data : dict
        Name, source, row count and ranges of the data.
    notes : list of str
        What was done to the data or the fit (dropped rows, global stage...).
    provenance : dict
        Package versions and creation time.
    uncertainty : dict
        How the standard errors were obtained.
    local_fit : optional
        The local solve of the best fit (None for a result read from a file); lmfit's
        ``ModelResult`` when a method other than the default was asked for.
    residual : numpy.ndarray, optional
        ``mu - fit`` per row (unweighted).
    best_fit : numpy.ndarray, optional
        The fitted law per row.
    fit_data : FitData, optional
        The data fitted.
    """

    law: Law
    params: dict[str, ParamEstimate]
    settings: dict[str, float]
    metrics: dict[str, float]
    correlation: dict[str, dict[str, float]]
    success: bool
    message: str
    warnings: list[str]
    non_identifiable: list[str]
    derived: dict[str, dict[str, Any]]
    data: dict[str, Any]
    notes: list[str] = field(default_factory=list)
    provenance: dict[str, Any] = field(default_factory=dict)
    uncertainty: dict[str, Any] = field(default_factory=dict)
    local_fit: Any = field(default=None, repr=False, compare=False)
    residual: np.ndarray | None = None
    best_fit: np.ndarray | None = None
    fit_data: FitData | None = None

    @functools.cached_property
    def lmfit_result(self) -> Any:
        """lmfit's :class:`~lmfit.model.ModelResult` of this fit (None without its data).

        lmfit's own minimiser result when it ran the fit; otherwise lmfit refits the law
        from this optimum (:func:`frictionlaws.fitting.views.model_result`), so its tools
        (``fit_report()``, ``conf_interval()``, ``eval_uncertainty()``) apply.
        """
        if self.local_fit is not None and hasattr(self.local_fit, "model"):
            return self.local_fit
        if self.fit_data is None:
            return None

        return model_result(self)

    @property
    def values(self) -> dict[str, float]:
        """All parameter and setting values, ready for :meth:`Law.evaluate`."""
        out = dict(self.settings)
        out.update({k: p.value for k, p in self.params.items()})
        return out

    @property
    def param_values(self) -> dict[str, float]:
        """Parameter values only (no settings)."""
        return {k: p.value for k, p in self.params.items()}

    @property
    def bound(self) -> BoundLaw:
        """The law bound to the fitted values, with the fitted data's ranges."""
        return bound_from_result(self)

    def predict(self, *, warn: bool = True, **variables: Any) -> Any:
        """Evaluate the fitted law; warn when outside the fitted data range.

        Parameters
        ----------
        warn : bool
            Issue an :class:`~frictionlaws.base.errors.ExtrapolationWarning` outside the
            fitted range.
        **variables
            Variable name -> values (SI).

        Returns
        -------
        float or numpy.ndarray
            The friction coefficient mu.
        """
        variables = self.law.si_variables(variables)
        if warn:
            msgs = self.extrapolation(variables)
            if msgs:
                warnings.warn("; ".join(msgs), ExtrapolationWarning, stacklevel=2)
        return self.law.evaluate(variables, self.values)

    def extrapolation(self, variables: Mapping[str, Any]) -> list[str]:
        """Return a message for each variable outside the ranges of the data fitted.

        The one rule (:func:`frictionlaws.law.bound.outside_ranges`) that
        :meth:`BoundLaw.extrapolation <frictionlaws.law.bound.BoundLaw.extrapolation>` applies.

        Parameters
        ----------
        variables : mapping
            Variables (SI), by name; those the law does not use are ignored.

        Returns
        -------
        list of str
            One message per variable with values outside its fitted range.
        """
        return outside_ranges(self.law, self.data.get("ranges", {}), variables)

    def to_dict(self) -> dict[str, Any]:
        """Return the result as a JSON-able dict (the versioned save format).

        Returns
        -------
        dict
            Everything :func:`load_result` reads back.
        """
        return {
            "format": RESULT_FORMAT,
            "version": RESULT_VERSION,
            "law": self.law.id,
            "law_title": self.law.title,
            "params": {k: p.to_dict() for k, p in self.params.items()},
            "settings": {k: {"value": v, "unit": self.law.setting(k).unit if any(
                s.name == k for s in self.law.settings) else ""}
                for k, v in self.settings.items()},
            "metrics": dict(self.metrics),
            "derived": self.derived,
            "correlation": self.correlation,
            "success": self.success,
            "message": self.message,
            "warnings": list(self.warnings),
            "non_identifiable": list(self.non_identifiable),
            "notes": list(self.notes),
            "uncertainty": dict(self.uncertainty),
            "data": self.data,
            "provenance": self.provenance,
        }

    @property
    def var_names(self) -> list[str]:
        """The fitted (not fixed) parameters, in the order of :attr:`covar`'s rows."""
        return [k for k, e in self.params.items() if not e.fixed]

    @property
    def covar(self) -> np.ndarray:
        """The covariance matrix of the fitted parameters (SI), rows in :attr:`var_names` order.

        Built from the standard errors and correlations of the method used
        (``uncertainty``); a parameter without a standard error (not identifiable)
        has NaN in its row and column.
        """
        names = self.var_names
        se = np.array([math.nan if self.params[k].stderr is None else self.params[k].stderr
                       for k in names], dtype=float)
        corr = np.array([[1.0 if a == b else self.correlation.get(a, {}).get(b, math.nan)
                          for b in names] for a in names], dtype=float).reshape(len(names), -1)
        return np.asarray(corr * np.outer(se, se), dtype=float)

    def to_frame(self, units: str = "display") -> Any:
        """Return the parameters as a :class:`pandas.DataFrame`.

        Parameters
        ----------
        units : {"display", "si"}
            ``"display"`` (default): pressures in MPa, so Thirion's ``b`` is in 1/MPa;
            ``"si"``: the values as fitted (1/Pa).  See :mod:`frictionlaws.base.display`.

        Returns
        -------
        pandas.DataFrame
            Value, stderr, CI, unit and fixed flag per parameter.
        """
        return params_frame(self, units)

    def plot(self, data: Any = None, *, units: str = "display", **kw: Any) -> Any:
        """Plot data, fit, 95 % band and residuals.

        See :func:`frictionlaws.fitting.views.plot_result`.

        Parameters
        ----------
        data : optional
            The data to show (default: the data fitted).
        units : {"display", "si"}
            The horizontal axis in display units (p in MPa; default) or SI.
        **kw
            Passed to :func:`frictionlaws.fitting.views.plot_result`.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        return plot_result(self, data, units=units, **kw)

    def _repr_html_(self) -> str:
        return result_html(self)

    def __repr__(self) -> str:
        m = self.metrics
        r2 = m.get("r2")
        r2_text = f"{r2:.4g}" if isinstance(r2, float) and math.isfinite(r2) else "-"
        values = ", ".join(f"{k}={e.value:.4g}" for k, e in self.params.items())
        state = "converged" if self.success else "NOT converged"
        return f"<FitResult {self.law.id}: {values}; R^2 = {r2_text}, n = {m.get('n')}; {state}>"

    def to_json(self, *, indent: int | None = 2) -> str:
        """Return strict JSON text of :meth:`to_dict` (``null`` for non-finite numbers).

        Parameters
        ----------
        indent : int, optional
            Indentation (None: one line).

        Returns
        -------
        str
            The JSON text.
        """
        return dumps(self.to_dict(), indent=indent)

    def save(self, path: str | Path) -> Path:
        """Write the versioned JSON to ``path`` atomically (never over the fitted data).

        Parameters
        ----------
        path : str or Path
            The file to write.

        Returns
        -------
        Path
            The file written.
        """
        source = self.data.get("source") if isinstance(self.data, Mapping) else None
        check_outputs([path], inputs=[source] if source else [])
        return write_text_atomic(path, self.to_json() + "\n")

    def report(self) -> str:
        """Return a plain-text report with units.

        Returns
        -------
        str
            Parameters, errors, derived quantities, metrics, notes and warnings.
        """
        lines = [f"law: {self.law.id} - {self.law.title}"]
        d = self.data
        rng = ", ".join(_fmt_range(k, lo, hi) for k, (lo, hi) in d.get("ranges", {}).items())
        lines.append(f"data: {d.get('name')} ({d.get('n')} rows{'; ' + rng if rng else ''})")
        lines.append(f"formula: {self.law.pretty()}   (SI: {self._si_note()})")
        lines.append("")
        width = max([10, *(len(k) for k in (*self.params, *self.settings))])  # heat_fraction
        hdr = f"{'parameter':<{width}} {'value':>13} {'std. error':>11} {'95 % CI':>29}  unit"
        lines.append(hdr)
        for p in self.params.values():
            if p.fixed:
                se, ci = "fixed", ""
            elif not p.identifiable:
                se, ci = "n/a", "not identifiable"
            else:
                se = _g(p.stderr)
                ci = f"[{_g(p.ci95[0])}, {_g(p.ci95[1])}]" if p.ci95 else ""
            lines.append(f"{p.name:<{width}} {_g(p.value):>13} {se:>11} {ci:>29}  {p.unit or '-'}")
        for k, v in self.settings.items():
            unit = self.law.setting(k).unit if any(s.name == k for s in self.law.settings) else ""
            lines.append(f"{k:<{width}} {_g(v):>13} {'setting':>11} {'':>29}  {unit or '-'}")
        if self.uncertainty.get("method"):
            lines.append(f"standard errors: {_describe_uncertainty(self.uncertainty)}")
        shown = _display_line(self.params, self.derived)
        if shown:
            lines.append(shown)
        if self.derived:
            lines.append("")
            lines.append("derived quantities:")
            for k, dv in self.derived.items():
                se = f" +/- {_g(dv['stderr'])}" if dv.get("stderr") is not None else ""
                dci = dv.get("ci95")
                se += f" [{_g(dci[0])}, {_g(dci[1])}]" if isinstance(dci, list) and len(dci) == 2 \
                    else ""
                lines.append(f"  {k} = {_g(dv['value'])}{se} {dv.get('unit') or '-'}"
                             f"  ({dv.get('meaning', '')})")
        m = self.metrics
        lines.append("")
        lines.append(
            f"R^2 = {m['r2']:.4f}   adj. R^2 = {m['adj_r2']:.4f}   RMSE = {m['rmse']:.4g} (-)   "
            f"AIC = {m['aic']:.2f}   BIC = {m['bic']:.2f}   n = {m['n']}   k = {m['k']}")
        status = "converged" if self.success else "NOT converged"
        lines.append(f"status: {status} ({self.message})")
        for note in self.notes:
            lines.append(f"note: {note}")
        for w in self.warnings:
            lines.append(f"warning: {w}")
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.report()

    def _si_note(self) -> str:
        return ", ".join(f"{v} in {VARIABLES[v].unit or '-'}" for v in self.law.variables) or "-"


def _display_line(params: Mapping[str, ParamEstimate],
                  derived: Mapping[str, Mapping[str, Any]]) -> str:
    """The values with pressures in MPa (``b = 4.72 +/- 0.381 1/MPa``), or ``""`` if none."""
    items: list[tuple[str, Any, Any, Any]] = [
        (k, e.value, e.stderr, e.unit) for k, e in params.items() if not e.fixed]
    items += [(k, d.get("value"), d.get("stderr"), d.get("unit")) for k, d in derived.items()]
    parts = []
    for name, value, se, unit in items:
        shown, factor = display_param_unit(unit)
        if factor == 1.0 or value is None:
            continue
        err = f" +/- {_g(se * factor)}" if se is not None else ""
        parts.append(f"{name} = {_g(value * factor)}{err} {shown}")
    return "with p in MPa: " + ", ".join(parts) if parts else ""


def _describe_uncertainty(info: Mapping[str, Any]) -> str:
    """One line saying how the standard errors and intervals were obtained."""
    method = info.get("method")
    if method == "bootstrap" and info.get("interval") is None:
        return (f"bootstrap refused: too few test conditions ({info.get('conditions')}); "
                "standard errors withheld")
    if method == "bootstrap":
        return (f"bootstrap ({info.get('n_boot')} resamples of {info.get('conditions')} "
                f"conditions, seed {info.get('seed')}; 95 % {info.get('interval')} intervals)")
    if method == "sandwich":
        return "sandwich (HC3, heteroskedasticity-robust; 95 % t intervals)"
    return "asymptotic (covariance of the fit scaled by the reduced chi-square; 95 % t intervals)"


def _g(x: float | None) -> str:
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return "n/a"
    return f"{x:.6g}"


def _numpy_ns() -> Any:
    return NUMPY


@functools.lru_cache(maxsize=1)
def _versions() -> tuple[tuple[str, str], ...]:
    """Versions of the packages a result depends on (read once: metadata is slow).

    A package already imported gives its ``__version__``; only the others are looked
    up in the installed metadata (a scan of the environment).
    """
    def ver(pkg: str) -> str:
        loaded = getattr(sys.modules.get(pkg), "__version__", None)
        if isinstance(loaded, str):
            return loaded
        try:
            return version(pkg)
        except PackageNotFoundError:
            return "unknown"

    return (("frictionlaws", __version__), ("scipy", ver("scipy")),
            ("numpy", ver("numpy")))


def _provenance() -> dict[str, Any]:
    versions = dict(_versions())
    return {**versions, "created": datetime.now(timezone.utc).isoformat(timespec="seconds")}


def load_result(path: str | Path) -> FitResult:
    """Load a fit result saved by :meth:`FitResult.save` (or ``fit --save``).

    Also accepts a plain ``{"law": ID, "params": {name: value}}`` JSON file.  Every
    value is checked: numbers where numbers belong, known names, values within the
    law's bounds; anything else is an :class:`InputError` naming the file and key.

    Parameters
    ----------
    path : str or Path
        The JSON file.

    Returns
    -------
    FitResult
        The result (without residuals or data arrays).

    Raises
    ------
    InputError
        Naming the file and the offending key.
    """
    path = check_input_file(path, "params file")
    raw = read_input(path, "params file")  # bounded in size
    try:
        doc = jsonio.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"not a JSON file ({exc})", file=str(path)) from None
    except ValueError as exc:
        raise InputError(str(exc), file=str(path)) from None
    if not isinstance(doc, dict) or "law" not in doc or "params" not in doc:
        raise InputError("expected a JSON object with 'law' and 'params'", file=str(path))
    if doc.get("format", RESULT_FORMAT) != RESULT_FORMAT:
        raise InputError(f"unknown format {doc.get('format')!r}", file=str(path))
    version = doc.get("version", RESULT_VERSION)
    if isinstance(version, bool) or not isinstance(version, int):
        raise InputError(f"key 'version' must be a whole number, got {version!r}",
                         file=str(path))
    if version > RESULT_VERSION:
        raise InputError(f"saved with a newer result version {version} "
                         f"(this frictionlaws reads up to {RESULT_VERSION})", file=str(path))
    if not isinstance(doc["law"], str) or not isinstance(doc["params"], dict):
        raise InputError("'law' must be a law id and 'params' an object", file=str(path))
    try:
        law = get_law(doc["law"])
    except InputError as exc:
        raise InputError(exc.bare_message, file=str(path)) from None
    params, settings = _loaded_params(law, doc, str(path))
    try:
        law.check_values({**settings, **{k: e.value for k, e in params.items()}})
    except InputError as exc:
        raise InputError(exc.bare_message, file=str(path)) from None
    return FitResult(
        law=law, params=params, settings={k: v for k, v in settings.items() if k not in params},
        metrics=_obj(doc, "metrics"), correlation=_obj(doc, "correlation"),
        success=bool(doc.get("success", True)), message=str(doc.get("message", "loaded")),
        warnings=[str(w) for w in _list(doc, "warnings")],
        non_identifiable=[str(w) for w in _list(doc, "non_identifiable")],
        derived=_obj(doc, "derived"), data=_obj(doc, "data"),
        notes=[str(w) for w in _list(doc, "notes")], provenance=_obj(doc, "provenance"),
        uncertainty=_loaded_uncertainty(doc, str(path)))


def _loaded_uncertainty(doc: Mapping[str, Any], file: str) -> dict[str, Any]:
    """The saved ``uncertainty`` record; its method must be a known one."""
    info = _obj(doc, "uncertainty")
    method = info.get("method")
    if info and method not in UNCERTAINTY_METHODS:
        raise InputError(f"uncertainty.method must be one of {', '.join(UNCERTAINTY_METHODS)}, "
                         f"got {method!r:.40}", file=file)
    return info


def _list(doc: Mapping[str, Any], key: str) -> list[Any]:
    value = doc.get(key, [])
    return list(value) if isinstance(value, list) else []


def _obj(doc: Mapping[str, Any], key: str) -> dict[str, Any]:
    value = doc.get(key, {})
    return dict(value) if isinstance(value, dict) else {}


def _number(value: Any, where: str, file: str) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(
            float(value)):
        raise InputError(f"{where} must be a finite number, got {value!r:.40}", file=file)
    return float(value)


def _loaded_param(law: Law, k: str, v: Any, file: str) -> ParamEstimate:
    if not isinstance(v, dict):
        unit = law.param(k).unit if k in law.param_names else ""
        return ParamEstimate(k, _number(v, f"params.{k}", file), None, None, unit, fixed=True)
    if "value" not in v:
        raise InputError(f"params.{k} has no 'value'", file=file)
    value = _number(v["value"], f"params.{k}.value", file)
    se = v.get("stderr")
    se = None if se is None else _number(se, f"params.{k}.stderr", file)
    ci = v.get("ci95")
    if ci is not None:
        if not isinstance(ci, list) or len(ci) != 2:
            raise InputError(f"params.{k}.ci95 must be [low, high]", file=file)
        ci = (_number(ci[0], f"params.{k}.ci95", file), _number(ci[1], f"params.{k}.ci95", file))
    unit = v.get("unit", "")
    return ParamEstimate(k, value, se, ci, unit if isinstance(unit, str) else "",
                         bool(v.get("fixed", False)), bool(v.get("identifiable", True)))


def _loaded_params(law: Law, doc: Mapping[str, Any], file: str
                   ) -> tuple[dict[str, ParamEstimate], dict[str, float]]:
    settings = dict(law.setting_values)
    for k, v in _obj(doc, "settings").items():
        if k not in settings:
            raise InputError(f"law '{law.id}' has no setting '{k}'", file=file)
        settings[k] = _number(v.get("value") if isinstance(v, dict) else v,
                              f"settings.{k}", file)
    params: dict[str, ParamEstimate] = {}
    for k, v in doc["params"].items():
        if k in law.param_names:
            params[k] = _loaded_param(law, k, v, file)
        elif k in settings:
            settings.pop(k)
            params[k] = _loaded_param(law, k, v, file)
        else:
            raise InputError(f"law '{law.id}' has no parameter '{k}' "
                             f"(parameters: {', '.join(law.param_names)})", file=file)
    missing = [p.name for p in law.params if p.name not in params and not p.optional]
    if missing:
        raise InputError(f"missing parameter(s) {', '.join(missing)} for law '{law.id}'",
                         file=file)
    for p in law.params:
        if p.name not in params:
            params[p.name] = ParamEstimate(p.name, p.default, None, None, p.unit, fixed=True)
    return params, settings

