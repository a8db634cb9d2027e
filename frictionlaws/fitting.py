"""Fitting a law to data, honestly.

:func:`fit` minimises the (weighted) squared residual of a law's declaration with
scipy's bounded trust region, the way lmfit's ``least_squares`` method does
(:mod:`frictionlaws._lsq`; lmfit's other minimisers on request), starts from the
law's data-driven guess, tries several starts where the surface may have several
minima, and returns a :class:`FitResult` with values, standard errors, 95 %
confidence intervals, the correlation matrix, goodness of fit and warnings.

On :data:`ANALYTIC_FROM` rows or more the solver and the
identifiability analysis use each law's analytic Jacobian, derived once from its
symbolic form (:mod:`frictionlaws.derivatives`).  The deterministic starts are
scored by their chi^2 and refined best first; the search stops when a second start
reproduces the best chi^2.

Identifiability is checked on the Jacobian at the optimum: its columns are
scaled to unit length and decomposed (SVD).  A relative singular value below
``1e-5`` means a direction in parameter space the data cannot see at all; the
parameters that carry that direction are *named* in
:attr:`FitResult.non_identifiable` and their standard errors are withheld
instead of printing meaningless numbers.  Values between ``1e-5`` and ``1e-2``
give a "poorly determined" warning.

Standard errors are the asymptotic ones from the covariance matrix (scaled by
the reduced chi-square as lmfit does); the 95 % intervals use Student's t with
``n - k`` degrees of freedom.
"""

from __future__ import annotations

import functools
import inspect
import json
import math
import warnings
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field, replace
from datetime import datetime, timezone
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import Argument, ExtrapolationWarning, FitError, InputError
from .law import VARIABLES, Law
from .registry import get_law
from .units import si_magnitude

if TYPE_CHECKING:
    from .bound import BoundLaw

__all__ = ["fit", "FitResult", "ParamEstimate", "load_result", "FitData", "as_fit_data",
           "check_fit_options", "invalid_rows", "RESULT_FORMAT", "RESULT_VERSION"]

RESULT_FORMAT = "frictionlaws-fit-result"
RESULT_VERSION = 1

#: Relative singular value below which a parameter direction is not identifiable.
RANK_TOL = 1e-5
#: Relative singular value below which a parameter direction is poorly determined.
WEAK_TOL = 1e-2
#: Rows from which a fit uses the laws' analytic Jacobians (and MINPACK first).  Below,
#: fits have few rows per parameter and are often ill-conditioned, so that the solver's
#: path decides between near-equal optima: there the trust region with finite
#: differences keeps the path of the results pinned by tests/test_pinned_*.py (the
#: thesis data have 19 rows, the synthetic pins 80), and a fit costs little anyway.
ANALYTIC_FROM = 100
#: Rows on which the starts after the first are refined on large data (4x this or more):
#: a start in the best fit's basin is recognised there at a fraction of a full solve.
SCOUT_ROWS = 1000


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
class FitData:
    """The arrays a fit works on (SI), with where they came from."""

    arrays: dict[str, np.ndarray]
    name: str
    source: str
    weights: np.ndarray | None = None
    notes: list[str] = field(default_factory=list)
    row_labels: np.ndarray | None = None
    #: A condition label per row (the dataset's ``condition_id`` column), for the bootstrap.
    conditions: np.ndarray | None = None

    @property
    def n(self) -> int:
        return int(self.arrays["mu"].size)

    @property
    def variables(self) -> set[str]:
        return {k for k in self.arrays if k in VARIABLES}

    def subset(self, mask: np.ndarray) -> FitData:
        """The rows where ``mask`` is True."""
        mask = np.asarray(mask)
        return FitData(
            {k: v[mask] for k, v in self.arrays.items()}, self.name, self.source,
            None if self.weights is None else self.weights[mask], list(self.notes),
            None if self.row_labels is None else self.row_labels[mask],
            None if self.conditions is None else self.conditions[mask])

    def ranges(self) -> dict[str, tuple[float, float]]:
        """(min, max) of every variable present, in SI."""
        return {k: (float(np.min(v)), float(np.max(v))) for k, v in self.arrays.items()
                if k in VARIABLES and v.size}


def as_fit_data(data: Any, *, mapping: Mapping[str, str] | None = None,
                units: Mapping[str, str] | None = None, area: Any = None,
                weights: Any = "auto") -> FitData:
    """Turn a dataset name, path, Dataset, DataFrame or mapping of arrays into :class:`FitData`.

    A mapping of arrays must hold ``"mu"`` and variables by their canonical
    names in SI; everything else goes through :func:`frictionlaws.io.load_dataset`.
    """
    if isinstance(data, FitData):
        fd = data
    elif isinstance(data, Mapping) and "mu" in data:
        fd = _arrays_fit_data(data)
    else:
        from .io import load_dataset

        ds = load_dataset(data, mapping=mapping, units=units, area=area)
        refuse_pooled_groups(ds)
        fd = FitData(ds.arrays(), ds.name, ds.source, ds.weights(), list(ds.notes))
        labels = getattr(ds, "row_labels", None)
        fd.row_labels = np.asarray(labels) if labels is not None else None
        if CONDITION_COLUMN in ds.column_names:  # the columns, without building a DataFrame
            fd.conditions = np.array([str(c) for c in ds.column(CONDITION_COLUMN)], object)
    _check_magnitudes(fd)
    if isinstance(weights, str):
        if weights != "auto":
            raise InputError(f"weights must be 'auto', None or an array, not {weights!r}")
    elif weights is None:
        fd.weights = None
    else:
        w = np.asarray(weights, float)
        if w.shape != fd.arrays["mu"].shape or np.any(~np.isfinite(w)) or np.any(w < 0):
            raise InputError("weights must be finite, non-negative and one per row")
        if np.count_nonzero(w) < 2:
            raise InputError(f"only {np.count_nonzero(w)} of {w.size} rows have a "
                             "weight > 0; a fit needs at least two weighted rows",
                             option="weights")
        fd.weights = w
    return fd


#: Columns that name a group of rows (counter-surface, compound...); a pooled fit over
#: several of their values is refused.
GROUP_COLUMNS = ("surface", "compound", "rig", "condition", "material", "counter_surface")

#: A column naming each row's test condition (repeats share it): the bootstrap's unit.
CONDITION_COLUMN = "condition_id"

#: Lower limits of the arrays given to a fit: (limit, inclusive).
_ARRAY_LIMITS = {"mu": (0.0, True), "p": (0.0, True), "F_N": (0.0, True), "T": (0.0, False)}


def refuse_pooled_groups(dataset: Any) -> None:
    """Raise :class:`~frictionlaws.errors.GroupingError` when a grouping column varies."""
    from .errors import GroupingError

    names = getattr(dataset, "column_names", None)
    if names is None:
        return
    for col in GROUP_COLUMNS:
        if col in names:
            values = sorted({str(v) for v in dataset.column(col) if str(v).strip()})
            if len(values) > 1:
                shown = ", ".join(values[:6]) + (" ..." if len(values) > 6 else "")
                raise GroupingError(
                    f"the rows come from {len(values)} values of '{col}' ({shown}); one law "
                    "fitted to all of them would describe none", column=col,
                    file=str(getattr(dataset, "source", "")) or None)


def _arrays_fit_data(data: Mapping[str, Any]) -> FitData:
    """Arrays given through the API, with the checks the CSV loader makes."""
    unknown = [k for k in data if k not in ("mu", "weights", *VARIABLES)]
    if unknown:
        raise InputError(f"unknown array(s) {', '.join(map(str, unknown))}; expected 'mu', "
                         f"'weights' and variables {', '.join(VARIABLES)}")
    arrays = {}
    for k, v in data.items():
        if k == "mu" or k in VARIABLES:
            unit = VARIABLES[k].unit if k in VARIABLES else ""
            arrays[k] = _float_array(k, si_magnitude(v, unit, f"array '{k}'"))
    n = arrays["mu"].size
    if n == 0:
        raise InputError("array 'mu' is empty")
    for k, v in arrays.items():
        if np.ndim(data[k]) == 0 and n > 1:
            arrays[k] = np.full(n, float(v[0]))
        elif v.size != n:
            raise InputError(f"array '{k}' has {v.size} values but 'mu' has {n}")
    for k, v in arrays.items():
        if not (k == "mu" and "s" in arrays):  # slip data: mu is signed (driving, shifts)
            _check_array(k, v)
        elif not np.all(np.isfinite(v)):
            _check_array(k, v)
    w = data.get("weights")
    return FitData(arrays, "arrays", "in-memory arrays",
                   None if w is None else np.asarray(w, float))


def _float_array(name: str, value: Any) -> np.ndarray:
    if isinstance(value, (str, bytes)):
        raise InputError(f"array '{name}' must hold numbers, got text")
    try:
        raw = np.asarray(value)
        if raw.dtype.kind in "bc":  # True -> 1.0 and 1+2j -> 1.0 would be silent guesses
            kind = "booleans" if raw.dtype.kind == "b" else "complex numbers"
            raise InputError(f"array '{name}' must hold real numbers, got {kind}")
        if raw.ndim > 1:
            raise InputError(f"array '{name}' must be one-dimensional, got shape {raw.shape}")
        return np.atleast_1d(raw.astype(float))
    except (TypeError, ValueError) as exc:
        if isinstance(exc, InputError):
            raise
        raise InputError(f"array '{name}' must hold numbers") from None


def _check_array(name: str, v: np.ndarray) -> None:
    if not np.all(np.isfinite(v)):
        bad = np.flatnonzero(~np.isfinite(v))
        raise InputError(f"array '{name}' has non-finite values at indices {bad[:5].tolist()}")
    limit = _ARRAY_LIMITS.get(name)
    if limit is not None:
        bad = np.flatnonzero(v < limit[0] if limit[1] else v <= limit[0])
        if bad.size:
            op = ">=" if limit[1] else ">"
            raise InputError(f"array '{name}' must be {op} {limit[0]:g} (SI); "
                             f"{v[bad[0]]:g} at index {int(bad[0])}"
                             f"{f' and {bad.size - 1} more' if bad.size > 1 else ''}")


#: Largest plausible friction coefficient, and largest magnitude of any other value a fit
#: can square without overflow.
MU_MAX = 1e3
_MAGNITUDE_MAX = 1e100


def _check_magnitudes(fd: FitData) -> None:
    """Refuse values a fit cannot stand behind: mu above :data:`MU_MAX`, anything whose
    square would overflow."""
    for name, v in fd.arrays.items():
        limit = MU_MAX if name == "mu" else _MAGNITUDE_MAX
        big = np.flatnonzero(np.abs(v) > limit)
        if big.size:
            i = int(big[0])
            row = (f" (row {fd.row_labels[i]})" if fd.row_labels is not None
                   else f" (index {i})")
            what = ("a friction coefficient above 1000 is not a measurement (check the "
                    "column and its unit)" if name == "mu" else
                    f"values beyond {_MAGNITUDE_MAX:g} (SI) cannot be fitted")
            raise InputError(f"'{name}' = {v[i]:g}{row}: {what}",
                             file=fd.source if fd.source != "in-memory arrays" else None,
                             column=name)


def check_fit_options(method: Any, starts: Any, seed: Any, on_invalid: Any) -> None:
    """Refuse nonsense values of :func:`fit`'s search options with a clear error.

    The one rule for these options, shared by :func:`fit` and the comparison (which fits
    with the same ``starts`` and ``seed``).

    Parameters
    ----------
    method : str
        The lmfit method; one of ``least_squares``, ``leastsq``, ``nelder``, ``lbfgsb``,
        ``powell``, ``trust-constr``.
    starts : int or None
        Number of extra starting points, a whole number 0..1000 (None: the default).
    seed : int
        Seed of the random starts, a whole number 0..2**32 - 1.
    on_invalid : str
        ``"error"`` or ``"drop"``: what to do with non-finite rows.

    Raises
    ------
    InputError
        Naming the option (``method``, ``starts``, ``seed``, ``on_invalid``) and the value
        refused.
    """
    if method not in _METHODS:
        raise InputError(f"method must be one of {', '.join(_METHODS)}, not {method!r}",
                         option="method")
    if starts is not None and (isinstance(starts, bool) or not isinstance(starts, (int, np.integer))
                               or not 0 <= starts <= 1000):
        raise InputError(f"starts must be a whole number 0..1000, not {starts!r}",
                         option="starts")
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or not (
            0 <= seed < 2**32):
        raise InputError(f"seed must be a whole number 0..{2**32 - 1}, not {seed!r}",
                         option="seed")
    if on_invalid not in ("error", "drop"):
        raise InputError(f"on_invalid must be 'error' or 'drop', not {on_invalid!r}")


#: lmfit methods a fit may use (bounded, deterministic).
_METHODS = ("least_squares", "leastsq", "nelder", "lbfgsb", "powell", "trust-constr")


def _check_fix(law: Law, fix: Mapping[str, Any], setting_names: list[str]) -> dict[str, float]:
    """Fixed values as floats, each a known name within its declared bounds."""
    out = {}
    for k, v in fix.items():
        if k not in law.param_names and k not in setting_names:
            raise InputError(f"cannot fix '{k}': law '{law.id}' has parameters "
                             f"{', '.join(law.param_names)} and settings "
                             f"{', '.join(setting_names) or 'none'}", option="fix")
        if isinstance(v, (bool, str)) or v is None:
            raise InputError(f"cannot fix '{k}' to {v!r}: a number is needed", option="fix")
        out[k] = float(si_magnitude(v, law.value_unit(k), f"fix '{k}'"))
    try:
        law.check_values(out, admissible=False)
    except InputError as exc:
        raise InputError(exc.bare_message, option="fix") from None
    return out


def _neutral_fixes(law: Law, fd: FitData, fix: Mapping[str, float], notes: list[str]
                   ) -> dict[str, float]:
    """Parameters fixed at their neutral value because their optional variable is absent.

    The law's declaration says which (``Law.optional_variables``); a note says
    so.  A parameter fixed by the caller to another value is refused: without
    the variable it cannot act.
    """
    out = law.neutral_fixes(fd.variables)
    for var, pname in ((v, law.optional_variables[v][0]) for v in law.optional_variables
                       if v not in fd.variables):
        neutral = out[pname]
        if pname in fix and fix[pname] != neutral:
            raise InputError(
                f"data '{fd.name}' have no {var} ({law.meaning(var)}), so law '{law.id}' "
                f"can only be fitted with {pname} = {neutral:g} (where {var} drops out); "
                f"{pname} was fixed to {fix[pname]:g}", option="fix")
        notes.append(f"the data have no {var} ({law.meaning(var)}): {pname} fixed at "
                     f"{neutral:g}, where {var} drops out of law '{law.id}'")
    return out


def _row_names(fd: FitData, idx: np.ndarray) -> str:
    labels = fd.row_labels if fd.row_labels is not None else np.arange(1, fd.n + 1)
    shown = ", ".join(str(labels[i]) for i in idx[:8])
    return shown + (f" and {idx.size - 8} more" if idx.size > 8 else "")


def invalid_rows(law: Law, arrays: Mapping[str, np.ndarray], n: int
                 ) -> tuple[np.ndarray, list[str]]:
    """Rows where ``law`` is not defined, and why: the one rule of fits and comparisons.

    A row is invalid when a variable the law floors (it takes its log or a negative
    power) is at or below its floor (``|v|`` for the velocity), or when a variable
    lies outside a strict domain (a law that must not be extrapolated).

    Parameters
    ----------
    law : Law
        The law.
    arrays : mapping
        Variable name -> values (SI), one per row.
    n : int
        The number of rows.

    Returns
    -------
    mask : numpy.ndarray
        True for the invalid rows.
    reasons : list of str
        One sentence per rule that some row breaks.
    """
    bad = np.zeros(n, dtype=bool)
    reasons = []
    for var, floor in law.floors.items():
        if var not in arrays:
            continue
        x = arrays[var]
        b = (np.abs(x) if var == "v" else x) <= floor
        if b.any():
            bad |= b
            reasons.append(f"{var} = 0 ({law.meaning(var)}), where law '{law.id}' "
                           f"is singular (it uses log or a negative power of {var})")
    for var, (lo, hi) in law.domain.items() if law.strict_domain else ():
        if var == "s" or var not in arrays:
            continue
        x = np.abs(arrays[var]) if var == "v" else arrays[var]
        b = (x < lo * (1 - 1e-9) - 1e-300) | (x > hi * (1 + 1e-9))
        if b.any():
            bad |= b
            reasons.append(f"values outside {_fmt_range(var, lo, hi)}, the range law "
                           f"'{law.id}' is valid for (it must not be extrapolated)")
    return bad, reasons


def _check_data_for_law(law: Law, fd: FitData, on_invalid: str) -> tuple[FitData, list[str]]:
    """Family/variable checks and rows where the law is undefined (:func:`invalid_rows`)."""
    law.require_variables(fd.variables, f"data '{fd.name}'")
    notes: list[str] = []
    bad, reasons = invalid_rows(law, fd.arrays, fd.n)
    if bad.any():
        idx = np.flatnonzero(bad)
        msg = "; ".join(reasons)
        if on_invalid == "drop":
            notes.append(f"dropped {idx.size} of {fd.n} rows (rows {_row_names(fd, idx)}): {msg}")
            fd = fd.subset(~bad)
        else:
            raise InputError(
                [f"data '{fd.name}': {idx.size} rows (rows {_row_names(fd, idx)}) have {msg}; "
                 "remove them or drop them explicitly (",
                 Argument("on_invalid", "drop", switch=True), ")"])
    k = len(law.params)
    if fd.n == 0:
        raise InputError(f"data '{fd.name}' has no rows left to fit law '{law.id}'")
    if fd.n < k:
        raise InputError(f"data '{fd.name}' has {fd.n} rows; law '{law.id}' has {k} "
                         "parameters: at least as many rows as parameters are needed")
    return fd, notes


def _model_function(law: Law, extra: tuple[str, ...]) -> Any:
    """A function with an explicit signature for lmfit.Model."""
    settings = law.setting_values
    indep = law.variables or ("_shape",)
    names = list(indep) + list(law.param_names) + list(extra)

    def model(**kw: Any) -> Any:
        variables = {k: kw[k] for k in law.variables}
        shape = kw.get("_shape")
        values = {**settings, **{k: kw[k] for k in law.param_names}, **{k: kw[k] for k in extra}}
        out = law.evaluate(variables, values)
        if shape is not None:
            out = np.broadcast_to(out, np.shape(shape))
        return out

    model.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        [inspect.Parameter(n, inspect.Parameter.POSITIONAL_OR_KEYWORD) for n in names])
    model.__name__ = law.id.replace("-", "_").replace("+", "_")
    return model


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
        from this optimum (:func:`frictionlaws.interop.model_result`), so its tools
        (``fit_report()``, ``conf_interval()``, ``eval_uncertainty()``) apply.
        """
        if self.local_fit is not None and hasattr(self.local_fit, "model"):
            return self.local_fit
        if self.fit_data is None:
            return None
        from .interop import model_result

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
        from .bound import bound_from_result

        return bound_from_result(self)

    def predict(self, *, warn: bool = True, **variables: Any) -> Any:
        """Evaluate the fitted law; warn when outside the fitted data range.

        Parameters
        ----------
        warn : bool
            Issue an :class:`~frictionlaws.errors.ExtrapolationWarning` outside the
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
        """Say which variables lie outside the range the law was fitted on.

        Parameters
        ----------
        variables : mapping
            Variable name -> values (SI).

        Returns
        -------
        list of str
            One message per variable outside its fitted range.
        """
        from .bound import outside_ranges

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
            ``"si"``: the values as fitted (1/Pa).  See :mod:`frictionlaws.display`.

        Returns
        -------
        pandas.DataFrame
            Value, stderr, CI, unit and fixed flag per parameter.
        """
        from .interop import params_frame

        return params_frame(self, units)

    def plot(self, data: Any = None, *, units: str = "display", **kw: Any) -> Any:
        """Plot data, fit, 95 % band and residuals.

        See :func:`frictionlaws.interop.plot_result`.

        Parameters
        ----------
        data : optional
            The data to show (default: the data fitted).
        units : {"display", "si"}
            The horizontal axis in display units (p in MPa; default) or SI.
        **kw
            Passed to :func:`frictionlaws.interop.plot_result`.

        Returns
        -------
        matplotlib.figure.Figure
            The figure.
        """
        from .interop import plot_result

        return plot_result(self, data, units=units, **kw)

    def _repr_html_(self) -> str:
        from .interop import result_html

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
        from .jsonio import dumps

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
        from .outputs import check_outputs, write_text_atomic

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
        hdr = f"{'parameter':<10} {'value':>13} {'std. error':>11} {'95 % CI':>29}  unit"
        lines.append(hdr)
        for p in self.params.values():
            if p.fixed:
                se, ci = "fixed", ""
            elif not p.identifiable:
                se, ci = "n/a", "not identifiable"
            else:
                se = _g(p.stderr)
                ci = f"[{_g(p.ci95[0])}, {_g(p.ci95[1])}]" if p.ci95 else ""
            lines.append(f"{p.name:<10} {_g(p.value):>13} {se:>11} {ci:>29}  {p.unit or '-'}")
        for k, v in self.settings.items():
            unit = self.law.setting(k).unit if any(s.name == k for s in self.law.settings) else ""
            lines.append(f"{k:<10} {_g(v):>13} {'setting':>11} {'':>29}  {unit or '-'}")
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
    from .display import display_param_unit

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


def _fmt_range(k: str, lo: float, hi: float) -> str:
    var = VARIABLES.get(k)
    if var is None:
        return f"{k} {lo:g}..{hi:g}"
    from .units import to_display

    shown = to_display([lo, hi], k)
    return f"{k} {shown[0]:.4g}..{shown[1]:.4g} {var.display_unit or '-'}"


# --------------------------------------------------------------------- fitting


def _starts(law: Law, guess: dict[str, float], names: list[str]) -> list[dict[str, float]]:
    """Deterministic starts: the data-driven guess, the defaults and the presets."""
    starts = [dict(guess)]
    if law.linear:
        return starts
    starts.append({**guess, **{k: law.param(k).default for k in names if k in law.param_names}})
    for preset in law.presets.values():
        starts.append({**guess, **{k: v for k, v in preset.items() if k in names}})
    # one start once: a preset equal to the defaults (pacejka's dry road) would otherwise
    # "reproduce" it without telling anything about the surface
    unique: list[dict[str, float]] = []
    for start in starts:
        if all(any(start[k] != seen[k] for k in names) for seen in unique):
            unique.append(start)
    return unique


def _random_starts(law: Law, guess: dict[str, float], names: list[str], n_random: int,
                   rng: np.random.Generator) -> list[dict[str, float]]:
    """Random perturbations of the guess (log-normal for positive parameters)."""
    starts = []
    for _ in range(n_random):
        s = dict(guess)
        for k in names:
            if k not in law.param_names:
                continue
            p = law.param(k)
            lo, _hi = p.bounds
            x = guess[k]
            if x > 0 and lo >= 0:
                x = x * math.exp(rng.normal(0.0, 1.0))
            else:
                x = x + rng.normal(0.0, 1.0) * max(abs(x), 0.1 * (abs(p.default) or 1.0))
            s[k] = x
        starts.append(s)
    return starts


def _clip(value: float, lo: float, hi: float) -> float:
    if not math.isfinite(value):
        return value
    span = hi - lo if math.isfinite(hi - lo) else 0.0
    eps = 1e-9 * span
    if math.isfinite(lo) and value <= lo:
        value = lo + eps if span else (lo + abs(lo) * 1e-9 + 1e-300 if lo >= 0 else lo)
    if math.isfinite(hi) and value >= hi:
        value = hi - eps if span else hi
    return value


@dataclass
class _GlobalStage:
    """Bounded differential evolution on transformed parameters (the global stage of a fit).

    Each parameter is searched on a finite box: two-sided bounds linearly (in log10
    when both are positive and far apart), positive one-sided ones in log10 over eight
    decades around the guess, others linearly over +/- 10 typical sizes.  Two-sided
    boxes reach 5 % beyond each bound and are clipped back, so a bound is reachable
    exactly (laws such as Wriggers' change form there).
    """

    law: Law
    held: dict[str, float]
    names: list[str]
    bounds: dict[str, tuple[float, float]]
    guess: dict[str, float]
    evaluate: Any
    y: np.ndarray
    w: np.ndarray | None
    seed: int

    def __post_init__(self) -> None:
        self.boxes = {k: self._box(k) for k in self.names}

    def wanted(self, best: Any, finals: list[float]) -> bool:
        """True when the local starts end worse than the mean of mu or at different minima."""
        if self.law.linear or best is None:
            return not self.law.linear
        fitted = np.asarray(best.best_fit, float)
        ss_tot = float(np.sum((self.y - self.y.mean()) ** 2))
        if ss_tot > 0 and float(np.sum((self.y - fitted) ** 2)) > ss_tot:
            return True
        # chi^2 differences below 1e-9 of the data's own sum of squares are round-off
        # (a law that fits exactly, e.g. constant mu), not different minima
        yw = self.y if self.w is None else self.y * self.w
        floor = 1e-6 * float(np.sum(yw ** 2))  # x the 1e-3 below: 1e-9 of it
        rel = (np.asarray(finals) - min(finals)) / max(min(finals), floor, 1e-300)
        return bool(np.mean(rel > 1e-3) > 0.5)  # most starts miss the best basin

    def _box(self, k: str) -> tuple[float, float, str]:
        lo, hi = self.bounds[k]
        ref = abs(self.guess.get(k, 0.0)) or abs(self._default(k)) or 1.0
        if math.isfinite(lo) and math.isfinite(hi):
            if lo > 0 and hi / lo > 1e3:
                span = math.log10(hi / lo)
                return math.log10(lo) - 0.05 * span, math.log10(hi) + 0.05 * span, "log"
            return lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), "lin"
        if math.isfinite(lo) and lo >= 0:
            c = math.log10(max(ref, lo * 10, 1e-300))
            return c - 4.0, c + 4.0, "log"
        c = self.guess.get(k, 0.0)
        return c - 10 * ref, c + 10 * ref, "lin"

    def _default(self, k: str) -> float:
        return self.law.param(k).default if k in self.law.param_names else \
            self.law.setting(k).value

    def values(self, u: np.ndarray) -> dict[str, float]:
        """Parameter values for a point ``u`` of the search box."""
        out = {}
        for k, uk in zip(self.names, u):
            scale = self.boxes[k][2]
            lo, hi = self.bounds[k]
            out[k] = float(min(max(10.0 ** uk if scale == "log" else uk, lo), hi))
        return out

    def cost(self, u: np.ndarray) -> float:
        vals = {**self.held, **self.values(u)}
        with np.errstate(all="ignore"):
            model = np.broadcast_to(np.asarray(self.evaluate(vals), float), self.y.shape)
        r = (model - self.y) * (self.w if self.w is not None else 1.0)
        c = float(np.sum(r * r))
        return c if math.isfinite(c) else 1e300

    def search(self) -> tuple[dict[str, float] | None, tuple[str, ...]]:
        """The best point found and the parameters it put exactly on a bound."""
        from scipy.optimize import differential_evolution

        box = [self.boxes[k][:2] for k in self.names]
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                sol = differential_evolution(self.cost, box, seed=self.seed, maxiter=200,
                                             popsize=10, tol=1e-5, polish=False)
        except (ValueError, FloatingPointError, np.linalg.LinAlgError):
            return None, ()
        if not math.isfinite(sol.fun) or sol.fun >= 1e300:
            return None, ()
        vals = {**self.guess, **self.values(sol.x)}
        pinned = tuple(k for k in self.names if vals[k] in self.bounds[k])
        return vals, pinned


def _jacobian(func: Any, x: np.ndarray, scales: np.ndarray | None = None) -> np.ndarray:
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


def _unit_columns_r(jac: np.ndarray, cols: list[int], norms: np.ndarray) -> np.ndarray:
    """The columns ``cols`` of ``jac`` scaled to unit length, or on large data their R factor.

    ``J = Q R`` leaves the singular values and right singular vectors unchanged, and R is
    built block by block (``R = qr([R; J_block])``), so a fit on millions of rows needs no
    scaled copy of the Jacobian nor an n-row U of its SVD.
    """
    from .law import _BLOCK, _BLOCKED_FROM

    n = jac.shape[0]
    if n < _BLOCKED_FROM:
        return jac[:, cols] / norms
    r = np.zeros((0, len(cols)))
    for start in range(0, n, _BLOCK):
        block = jac[start:start + _BLOCK, cols] / norms
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
    non_id: set[str] = set(dead)
    weak: set[str] = set()
    for i, r in enumerate(rel):
        if r < WEAK_TOL:
            comp = np.abs(vt[i])
            involved = {names[ok[j]] for j in np.flatnonzero(comp > 0.1 * comp.max())}
            (non_id if r < RANK_TOL else weak).update(involved)
    weak -= non_id
    order = {n: i for i, n in enumerate(names)}
    return (sorted(non_id, key=order.__getitem__), sorted(weak, key=order.__getitem__),
            float(rel[-1]) if rel.size else 0.0)


def fit(
    law: str | Law, data: Any, *, fix: Mapping[str, float] | None = None,
    free: Iterable[str] = (), initial: Mapping[str, float] | None = None,
    weights: Any = "auto", starts: int | None = None, seed: int = 0,
    on_invalid: str = "error", mapping: Mapping[str, str] | None = None,
    units: Mapping[str, str] | None = None, area: Any = None,
    method: str = "least_squares", uncertainty: str = "asymptotic", n_boot: int = 1000,
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
        ``"least_squares"`` (default: bounded trust region) or another lmfit minimiser.
    uncertainty : {"asymptotic", "sandwich", "bootstrap"}
        Standard errors from the fit's covariance, the HC3 sandwich (uneven scatter), or
        a bootstrap over whole conditions (a law that misses a trend); see
        :mod:`frictionlaws.uncertainty`.
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
    if lean:
        _polish(search)
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
    from .uncertainty import check_uncertainty_options

    check_fit_options(method, starts, seed, on_invalid)
    check_uncertainty_options(uncertainty, n_boot, n_jobs, interval)
    if global_stage not in ("auto", "on", "off"):
        raise InputError(f"global_stage must be 'auto', 'on' or 'off', not {global_stage!r}",
                         option="global_stage")
    if not isinstance(lean, bool) or (lean and uncertainty != "asymptotic"):
        raise InputError(f"lean must be True or False, and True only with the asymptotic "
                         f"uncertainty (got lean={lean!r}, uncertainty={uncertainty!r})",
                         option="lean")


@dataclass
class _Setup:
    """Everything a fit works with, once the data and options are checked."""

    law: Law
    fd: FitData
    notes: list[str]
    fix: dict[str, float]
    freed: tuple[str, ...]
    settings: dict[str, float]
    x: dict[str, np.ndarray]
    y: np.ndarray
    guess: dict[str, float]
    model_law: Law
    vary_names: list[str]
    bounds: dict[str, tuple[float, float]]

    @property
    def names(self) -> list[str]:
        """The parameters and freed settings, in the law's order."""
        return list(self.law.param_names) + list(self.freed)

    @property
    def w(self) -> np.ndarray | None:
        return self.fd.weights

    def unit(self, name: str) -> str:
        return self.law.setting(name).unit if name in self.freed else self.law.param(name).unit

    def typical(self, name: str) -> float:
        return (self.law.param(name).default if name in self.law.param_names
                else self.law.setting(name).value)


def _setup(law: Law, data: Any, fix: Mapping[str, float] | None, free: Iterable[str],
           initial: Mapping[str, float] | None, weights: Any, on_invalid: str,
           load: Mapping[str, Any]) -> _Setup:
    """Check the data, fixes, freed settings and initial values; build the start guess."""
    fd = as_fit_data(data, weights=weights, **load)
    fd, notes = _check_data_for_law(law, fd, on_invalid)
    notes = list(fd.notes) + notes
    setting_names = [s.name for s in law.settings]
    freed = _freed_settings(law, free, setting_names)
    fixed = _check_fix(law, dict(fix or {}), setting_names)
    fixed.update(_neutral_fixes(law, fd, fixed, notes))
    settings = {k: float(fixed.get(k, v)) for k, v in law.setting_values.items()
                if k not in freed}
    y = fd.arrays["mu"]
    x = {k: fd.arrays[k] if k in fd.arrays else np.zeros_like(y) for k in law.variables}
    guess = _start_guess(law, fd, x, freed, initial)
    vary_names = [k for k in list(law.param_names) + list(freed) if k not in fixed]
    if not vary_names:
        raise InputError(f"every parameter of law '{law.id}' is fixed: nothing to fit")
    bounds = {p.name: p.bounds for p in law.params}
    bounds.update({k: law.setting(k).bounds for k in freed})
    return _Setup(law, fd, notes, fixed, freed, settings, x, y, guess,
                  _model_law(law, settings, freed), vary_names, bounds)


def _freed_settings(law: Law, free: Iterable[str], setting_names: list[str]
                    ) -> tuple[str, ...]:
    """The settings to fit as parameters; an unknown name is refused."""
    free = list(dict.fromkeys(free))
    for k in free:
        if k not in setting_names and k not in law.param_names:
            raise InputError(f"law '{law.id}' has no setting '{k}' to free "
                             f"(settings: {', '.join(setting_names) or 'none'})")
    return tuple(k for k in free if k in setting_names)


def _start_guess(law: Law, fd: FitData, x: Mapping[str, np.ndarray], freed: tuple[str, ...],
                 initial: Mapping[str, float] | None) -> dict[str, float]:
    """The law's data-driven guess, the freed settings' values, then ``initial``."""
    if initial:  # pint Quantities in SI (or refused), as everywhere in the API
        initial = {k: si_magnitude(v, law.value_unit(k), f"initial '{k}'")
                   for k, v in initial.items()}
    y = fd.arrays["mu"]
    guess_data = {**x, "mu": y, **{k: v for k, v in fd.arrays.items() if k in VARIABLES}}
    guess = law.initial_guess(guess_data)
    for k in freed:
        guess[k] = float(initial.get(k, law.setting(k).value) if initial
                         else law.setting(k).value)
    if initial:
        unknown = set(initial) - set(guess)
        if unknown:
            raise InputError(f"unknown initial value(s) {sorted(unknown)} for law '{law.id}'")
        if any(isinstance(v, (bool, str)) or v is None for v in initial.values()):
            raise InputError(f"initial values must be numbers, got {dict(initial)!r}",
                             option="initial")
        given = {k: float(v) for k, v in initial.items()}
        try:  # the one parameter-value check: finite, within the declared bounds
            law.check_values(given, admissible=False)
        except InputError as exc:
            raise InputError(exc.bare_message, option="initial") from None
        guess.update(given)
    return guess


def _model_law(law: Law, settings: Mapping[str, float], freed: tuple[str, ...]) -> Law:
    """The law with settings fixed to non-default values (they flow through its closure)."""
    if settings == {k: v for k, v in law.setting_values.items() if k not in freed}:
        return law
    from .law import Setting

    return replace(law, settings=tuple(
        Setting(s.name, settings.get(s.name, s.value), s.unit, s.meaning, s.bounds)
        for s in law.settings))


@dataclass
class _Search:
    """The multi-start search: runs local lmfit fits and keeps the best."""

    setup: _Setup
    method: str
    best: Any = None
    best_pinned: tuple[str, ...] = ()
    errors: list[str] = field(default_factory=list)
    finals: list[float] = field(default_factory=list)
    model: Any = None

    def __post_init__(self) -> None:
        s = self.setup
        self.max_nfev = 300 * (len(s.vary_names) + 1)
        if self.method != "least_squares":  # lmfit's other minimisers
            import lmfit

            indep = s.law.variables or ("_shape",)
            self.model = lmfit.Model(_model_function(s.model_law, s.freed),
                                     independent_vars=list(indep), nan_policy="raise")
        self.kwargs = {k: s.x[k] for k in s.law.variables}
        if not s.law.variables:
            self.kwargs["_shape"] = s.y
        self.prepared = s.model_law.prepare_variables(s.x)
        self.held = {k: v for k, v in s.model_law.setting_values.items() if k not in s.names}
        self.jac_func = None
        if s.y.size >= ANALYTIC_FROM:
            from .derivatives import jacobian_function

            self.jac_func = jacobian_function(s.law)

    def jacobian(self, values: Mapping[str, float], names: list[str]) -> np.ndarray | None:
        """The analytic Jacobian of the model by ``names`` at ``values`` (None: none)."""
        if self.jac_func is None:
            return None
        from .derivatives import model_jacobian

        return model_jacobian(self.jac_func, self.prepared, {**self.held, **values}, names,
                              self.setup.y.size)

    def score(self, start: Mapping[str, float]) -> float:
        """chi^2 at a start (infinite when the model is not finite there)."""
        s = self.setup
        with np.errstate(all="ignore"):
            try:
                r = s.y - np.asarray(self.evaluate(self.start_values(start)), float)
            except (ValueError, FloatingPointError, TypeError, ZeroDivisionError):
                return math.inf
        if s.w is not None:
            r = r * s.w
        c = float(np.sum(r * r))
        return c if math.isfinite(c) else math.inf

    def start_values(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()
                     ) -> dict[str, float]:
        """Every parameter's start: fixed, held at a bound (pinned), or inside its bounds."""
        s = self.setup
        out = {}
        for k in s.names:
            if k in s.fix:
                out[k] = float(s.fix[k])
            elif k in pinned:  # held exactly at the bound the global stage found
                out[k] = float(start[k])
            else:
                out[k] = _clip(float(start[k]), *s.bounds[k])
        return out

    def params(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()) -> Any:
        """lmfit parameters from ``start``: fixed, pinned at a bound, or varied."""
        import lmfit

        s = self.setup
        params = lmfit.Parameters()
        for k, value in self.start_values(start, pinned).items():
            if k in s.fix or k in pinned:
                params.add(k, value=value, vary=False)
            else:
                params.add(k, value=value, min=s.bounds[k][0], max=s.bounds[k][1])
        return params

    def _local(self, start: Mapping[str, float], pinned: tuple[str, ...], tol: float = 1e-8
               ) -> Any:
        """One local solve: the lean trust region, or lmfit's minimiser when asked."""
        s = self.setup
        if self.method != "least_squares":
            return self.model.fit(s.y, self.params(start, pinned), weights=s.w,
                                  method=self.method, max_nfev=self.max_nfev, **self.kwargs)
        from ._lsq import solve

        values = self.start_values(start, pinned)
        vary = [k for k in s.names if k not in s.fix and k not in pinned]
        jac = None
        if self.jac_func is not None:
            def jac(v: Mapping[str, float]) -> np.ndarray:
                out = self.jacobian(v, vary)
                assert out is not None
                return out
        return solve(self.evaluate, s.y, s.w, values, vary, s.bounds, self.max_nfev, jac, tol)

    def evaluate(self, values: Mapping[str, float]) -> Any:
        """The model (the law with the fit's settings) at ``values`` on the data."""
        return self.setup.model_law.evaluate_prepared(self.prepared, {**self.held, **values},
                                                      self.setup.y.size)

    def solve_from(self, start: Mapping[str, float], pinned: tuple[str, ...] = (),
                   tol: float = 1e-8) -> Any:
        """One local fit from ``start`` (None when it fails; the error is kept)."""
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                res = self._local(start, pinned, tol)
        except (ValueError, FloatingPointError, np.linalg.LinAlgError, TypeError) as exc:
            self.errors.append(str(exc))
            return None
        return res if np.isfinite(res.chisqr) else None

    def run(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()) -> None:
        """One local fit from ``start``; kept when it beats the best so far."""
        res = self.solve_from(start, pinned)
        if res is None:
            return
        self.finals.append(float(res.chisqr))
        if self.best is None or res.chisqr < self.best.chisqr * (1 - 1e-10):
            self.best, self.best_pinned = res, pinned


#: Tolerances of the polish of a lean fit (:func:`_polish`).
POLISH_TOL = 1e-13


def _polish(search: _Search) -> None:
    """Refine the best fit from its own end point with tight tolerances, steps scaled.

    The search's solves stop at lmfit's tolerances (1e-8), a few 1e-7 of chi^2 short of
    the optimum on badly scaled or flat problems (Wriggers' b ~ 1e5 with d ~ 1e-5), and
    where exactly depends on the solver's path, which differs between scipy versions.
    Continued to :data:`POLISH_TOL` with the steps scaled by the Jacobian, every path
    ends at the optimum itself (chi^2 the same to about 1e-10), so the refits of a
    comparison give the same scores under every supported numpy and scipy.
    """
    best = search.best
    if best is None or search.method != "least_squares":
        return
    start = {k: float(best.params[k].value) for k in search.setup.names}
    res = search.solve_from(start, search.best_pinned, POLISH_TOL)
    if res is not None and res.chisqr <= best.chisqr:
        search.best = res


def _multistart(search: _Search, starts: int | None, seed: int) -> None:
    """The deterministic starts, then random ones when they disagree, all fail or are asked.

    The deterministic starts are scored by their chi^2 and refined best first, and the
    search stops as soon as one ends where an earlier one did (chi^2 within 1e-6): the
    surface then shows one basin for the starts that look best, and the others would
    cost a full solve each.
    """
    s = search.setup
    candidates = _starts(s.law, s.guess, s.vary_names)
    if len(candidates) > 1:
        scores = [search.score(c) for c in candidates]
        candidates = [candidates[i] for i in sorted(range(len(scores)), key=scores.__getitem__)]
    reproduced = scouted = False
    if s.y.size >= 4 * SCOUT_ROWS:
        reproduced, scouted = _scout(search, candidates), True
    else:
        for start in candidates:
            search.run(start)
            reproduced = _reproduced(search.finals)
            if reproduced:
                break
    # Random starts when the deterministic ones disagree (several minima) or all failed:
    # the surface is then multi-modal or hard, and more starts are worth their cost.
    finals = search.finals
    spread = (max(finals) - min(finals)) / max(min(finals), 1e-300) if finals else math.inf
    disagree = (spread > 1e-6 or scouted) and not reproduced
    forced = starts is not None and int(starts) > 0
    if not s.law.linear and (disagree or search.best is None or forced):
        rng = np.random.default_rng(seed)
        n_random = 6 if starts is None else int(starts)
        for start in _random_starts(s.law, s.guess, s.vary_names, n_random, rng):
            search.run(start)


def _scout(search: _Search, candidates: list[dict[str, float]]) -> bool:
    """Refine ``candidates`` on :data:`SCOUT_ROWS` evenly spaced rows, then the best on all.

    The candidates (best scored first) are refined on the subsample until one ends
    where an earlier one did (chi^2 within 1e-6 there): the rows span the data evenly,
    so their basins are the full data's, at a fraction of the cost.  The best of them
    is then refined on every row, from next to its minimum.  Returns True when a
    candidate reproduced the best on the subsample.
    """
    s = search.setup
    rows = np.unique(np.linspace(0, s.y.size - 1, SCOUT_ROWS).round().astype(int))
    mask = np.zeros(s.y.size, bool)
    mask[rows] = True
    scout = _Search(replace(s, fd=s.fd.subset(mask), y=s.y[rows],
                            x={k: v[rows] for k, v in s.x.items()}), search.method)
    for start in candidates:
        scout.run(start)
        if _reproduced(scout.finals):
            break
    if scout.best is not None:
        search.run({k: scout.best.params[k].value for k in s.names})
    if search.best is None:  # nothing converged on the subsample: every row, first start
        search.run(candidates[0])
    return _reproduced(scout.finals)


def _reproduced(finals: list[float]) -> bool:
    """True when the latest local fit ended at the best chi^2 of the earlier ones."""
    if len(finals) < 2:
        return False
    best = min(finals[:-1])
    return abs(finals[-1] - best) <= 1e-6 * max(best, 1e-300)


def _global_stage(search: _Search, mode: str, seed: int) -> list[str]:
    """Differential evolution then a local polish, when asked or wanted; its notes."""
    s = search.setup
    held = {k: v for k, v in s.fix.items() if k in s.names}  # settings: in model_law
    stage = _GlobalStage(s.model_law, held, s.vary_names, s.bounds, s.guess,
                         search.evaluate, s.y, s.w, seed)
    if not (mode == "on" or (mode == "auto" and stage.wanted(search.best, search.finals))):
        return []
    start, pinned = stage.search()
    if start is None:
        return []
    search.run(start, pinned)
    if pinned:  # the bound may be a limit the polish should also leave
        search.run(start)
    return [f"global stage: differential evolution over {len(s.vary_names)} transformed "
            "parameters, then the local polish"
            + (f" (with {', '.join(pinned)} held at the bound it reached)"
               if pinned and search.best_pinned else "")]


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
        warn_msgs.append(f"{', '.join(weak)} poorly determined by the data (strongly "
                         "correlated; wide intervals)")
    return _Diagnosis(vary, values, full_values, jac, non_id)


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
    n, dof = y.size, y.size - k
    resid = y - np.asarray(best.best_fit, float)
    ss_res = float(np.sum(resid**2))
    ss_tot = float(np.sum((y - y.mean()) ** 2))
    flat = ss_tot <= n * (1e-12 * float(np.max(np.abs(y)))) ** 2  # mu constant to round-off
    r2 = math.nan if flat else 1.0 - ss_res / ss_tot
    if flat:
        warn_msgs.append("mu takes one value in these data: R^2 is undefined (there is "
                         "no variation to explain); judge the fit by its RMSE")
    adj = 1.0 - (1.0 - r2) * (n - 1) / (n - k) if n - k > 0 else float("nan")
    aic = float(best.aic)
    aicc = aic + 2 * k * (k + 1) / (n - k - 1) if n - k - 1 > 0 else float("inf")
    return {
        "r2": r2, "adj_r2": adj, "rmse": math.sqrt(ss_res / n),
        "mae": float(np.mean(np.abs(resid))), "max_abs_residual": float(np.max(np.abs(resid))),
        "aic": aic, "aicc": aicc, "bic": float(best.bic), "chisqr": float(best.chisqr),
        "redchi": float(best.redchi) if dof > 0 else float("nan"), "n": int(n), "k": int(k),
        "weighted": weighted,
    }


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


def _derived(law: Law, values: dict[str, float], names: list[str], cov: np.ndarray | None,
             non_id: list[str]) -> dict[str, dict[str, Any]]:
    """Derived quantities with uncertainties propagated from ``cov`` (delta method).

    ``names`` are the parameters (in ``cov``'s order); without a covariance the
    values are given without standard errors.
    """
    out: dict[str, dict[str, Any]] = {}
    if not law.derived:
        return out
    names = list(names) if cov is not None else []
    for d in law.derived:
        def f(theta: np.ndarray, d=d) -> float:
            vals = dict(values)
            vals.update(dict(zip(names, theta)))
            return d.value(vals, _numpy_ns())
        value = f(np.array([values[k] for k in names])) if names else d.value(
            values, _numpy_ns())
        se = None
        if cov is not None and not non_id and math.isfinite(value):
            theta = np.array([values[k] for k in names])
            g = np.empty(theta.size)
            for j in range(theta.size):
                h = 1e-6 * max(abs(theta[j]), 1e-10)
                tp, tm = theta.copy(), theta.copy()
                tp[j] += h
                tm[j] -= h
                g[j] = (f(tp) - f(tm)) / (2 * h)
            var = float(g @ cov @ g)
            se = math.sqrt(var) if var >= 0 and math.isfinite(var) else None
        out[d.name] = {"value": value, "stderr": se, "unit": d.unit, "meaning": d.meaning}
    return out


def _withhold_doubtful(law: Law, diag: _Diagnosis, estimates: dict[str, ParamEstimate],
                       derived: dict[str, dict[str, Any]], warn_msgs: list[str]) -> None:
    """The rules every error method ends on (asymptotic, sandwich, bootstrap alike).

    A standard error of exactly zero says nothing is known about the error (exact
    data, identical resamples), so it is withheld with a warning; a derived quantity
    has no error when a parameter it depends on has none.
    """
    from .uncertainty import ZERO_SPREAD

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


@dataclass
class _ErrorInputs:
    """What the robust error methods need from a finished fit."""

    law: Law
    fd: FitData
    x: dict[str, np.ndarray]
    y: np.ndarray
    w: np.ndarray | None
    vary: list[str]
    values: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    jac: np.ndarray
    resid: np.ndarray
    non_id: list[str]
    tval: float

    @property
    def weighted_resid(self) -> np.ndarray:
        return self.resid * (self.w if self.w is not None else 1.0)


def _robust_errors(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                   derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                   warn_msgs: list[str], opts: dict[str, Any]) -> dict[str, Any]:
    """Replace the asymptotic errors by the requested method's; warn when they are too narrow.

    ``estimates``, ``derived``, ``corr`` and ``warn_msgs`` are updated in place; the
    returned record says which method was used (kept by :meth:`FitResult.to_dict`).
    """
    from .uncertainty import residual_structure

    method = opts["method"]
    info: dict[str, Any] = {"method": method}
    asym = {k: estimates[k].stderr for k in inp.vary if k in estimates}
    structure = residual_structure(inp.weighted_resid, inp.fd.arrays, _condition_vars(inp.fd))
    if structure is not None:
        info["residual_structure"] = {"variable": structure.variable, "test": structure.test,
                                      "statistic": structure.statistic,
                                      "p_value": structure.p_value,
                                      "n_tests": structure.n_tests}
    if not math.isfinite(inp.tval):  # as many parameters as rows: no method has errors
        if method != "asymptotic":
            warn_msgs.append(f"{method} standard errors need more rows than fitted "
                             "parameters: none are given")
            info["method"] = "asymptotic"
    elif method == "asymptotic" or not inp.vary or (inp.non_id and method == "sandwich"):
        if method != "asymptotic":
            warn_msgs.append(f"{method} standard errors need every fitted parameter to be "
                             "identifiable; the asymptotic ones (where available) are shown"
                             + ("; the bootstrap gives those of the identifiable ones"
                                if method == "sandwich" else ""))
            info["method"] = "asymptotic"
    elif method == "sandwich":
        if not _apply_sandwich(inp, estimates, derived, corr, warn_msgs):
            info["method"] = "asymptotic"
    else:
        info.update(_apply_bootstrap(inp, estimates, derived, corr, warn_msgs, opts))
    if info["method"] != "bootstrap" and structure is not None and structure.significant:
        warn_msgs.append(
            f"{structure.describe()}: the law misses a trend, so the {info['method']} "
            "standard errors are likely too narrow; the bootstrap method (uncertainty "
            "'bootstrap'), which resamples whole conditions, gives honest ones")
    _warn_if_narrow(info["method"], asym, estimates, warn_msgs)
    info["asymptotic_stderr"] = asym
    return info


def _condition_vars(fd: FitData) -> list[str]:
    """The variables that define a test condition: every one the data hold, in order."""
    return [v for v in VARIABLES if v in fd.arrays]


def _warn_if_narrow(method: str, asym: Mapping[str, float | None],
                    estimates: Mapping[str, ParamEstimate], warn_msgs: list[str]) -> None:
    """Warn when a robust method's errors exceed the asymptotic ones by > NARROW_RATIO."""
    from .uncertainty import NARROW_RATIO

    if method == "asymptotic":
        return
    ratios = {k: se / a for k, a in asym.items()
              if a and a > 0 and (se := estimates[k].stderr) is not None}
    wide = {k: r for k, r in ratios.items() if r > NARROW_RATIO}
    if wide:
        shown = ", ".join(f"{k} x{r:.2g}" for k, r in wide.items())
        warn_msgs.append(f"the {method} standard errors exceed the asymptotic ones by more "
                         f"than {NARROW_RATIO}x ({shown}): the asymptotic errors are too "
                         f"narrow for these data; the {method} values are reported")


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


def _set_errors(inp: _ErrorInputs, estimates: dict[str, ParamEstimate], se: np.ndarray,
                ci: np.ndarray) -> list[str]:
    """Store the method's standard errors and intervals of the fitted parameters.

    A parameter the method cannot give an error for (not finite, or zero) has its
    error withheld rather than left at another method's; its name is returned.
    """
    withheld = []
    for j, k in enumerate(inp.vary):
        if k in inp.non_id:  # withheld whatever the method
            continue
        if math.isfinite(se[j]) and se[j] > 0 and np.all(np.isfinite(ci[j])):
            estimates[k] = replace(estimates[k], stderr=float(se[j]),
                                   ci95=(float(ci[j, 0]), float(ci[j, 1])))
        else:
            estimates[k] = replace(estimates[k], stderr=None, ci95=None)
            withheld.append(k)
    return withheld


def _set_corr(names: list[str], cov: np.ndarray, corr: dict[str, dict[str, float]]) -> None:
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    with np.errstate(all="ignore"):
        cm = cov / np.outer(sd, sd)
    corr.clear()
    for i, a in enumerate(names):
        corr[a] = {b: float(cm[i, j]) for j, b in enumerate(names)}


def _apply_sandwich(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                    derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                    warn_msgs: list[str]) -> bool:
    """HC3 sandwich errors for the parameters and (delta method) the derived quantities.

    False (the asymptotic errors stay) when the sandwich cannot be computed.
    """
    from .uncertainty import sandwich_cov

    cov = sandwich_cov(inp.jac, inp.weighted_resid)
    if cov is None:
        warn_msgs.append("the sandwich covariance could not be computed (singular Jacobian); "
                         "the asymptotic standard errors are shown")
        return False
    se = np.sqrt(np.clip(np.diag(cov), 0, None))
    theta = np.array([inp.values[k] for k in inp.vary])
    ci = np.array([_clip_interval(k, (t - inp.tval * e, t + inp.tval * e), inp.bounds[k],
                                  warn_msgs) if math.isfinite(e) and e > 0 else (math.nan,) * 2
                   for k, t, e in zip(inp.vary, theta, se)]).reshape(-1, 2)
    withheld = _set_errors(inp, estimates, se, ci)
    if withheld:
        warn_msgs.append(f"the sandwich covariance gives no standard error for "
                         f"{', '.join(withheld)} (zero or not finite: the residuals do not "
                         "tell it); it is withheld")
    _set_corr(inp.vary, cov, corr)
    derived.update(_derived(inp.law, inp.values, inp.vary, cov, inp.non_id))
    return True


def _apply_bootstrap(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                     derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                     warn_msgs: list[str], opts: dict[str, Any]) -> dict[str, Any]:
    """Condition-resampling bootstrap errors and intervals, parameters and derived alike."""
    from .uncertainty import (
        MIN_DETERMINED,
        Refit,
        bootstrap,
        condition_ids,
        derived_samples,
        intervals,
        rank,
    )

    lower = np.array([inp.bounds[k][0] for k in inp.vary], float)
    upper = np.array([inp.bounds[k][1] for k in inp.vary], float)
    full_rank = rank(inp.jac, RANK_TOL)
    refit = Refit(inp.law, dict(inp.values), list(inp.vary), lower, upper, inp.x, inp.y, inp.w,
                  RANK_TOL, full_rank)
    groups = condition_ids(inp.fd.arrays, _condition_vars(inp.fd), inp.fd.conditions)
    n_cond = int(np.unique(groups).size)
    if n_cond <= full_rank:
        return _bootstrap_refused(inp, estimates, derived, warn_msgs, opts, n_cond)
    theta = np.array([inp.values[k] for k in inp.vary])
    boot = bootstrap(refit, theta, groups, n_boot=opts["n_boot"], seed=opts["seed"],
                     n_jobs=opts["n_jobs"], jackknife=opts["interval"] == "bca")
    se, ci, used = intervals(boot.samples, theta, boot.jackknife, kind=opts["interval"])
    withheld = _set_errors(inp, estimates, se, ci)
    if withheld:
        warn_msgs.append(f"the bootstrap cannot determine the standard error of "
                         f"{', '.join(withheld)}: fewer than {MIN_DETERMINED} resamples "
                         "determine it, or they do not spread at all; it is withheld "
                         "(not zero)")
    ok = np.all(np.isfinite(boot.samples), axis=1)
    if ok.sum() > len(inp.vary) and not inp.non_id:
        _set_corr(inp.vary, np.cov(boot.samples[ok].T).reshape(len(inp.vary), -1), corr)
    if inp.law.derived and not inp.non_id:
        funcs = {d.name: (lambda vals, d=d: d.value(vals, _numpy_ns()))
                 for d in inp.law.derived}
        hat = np.array([derived[k]["value"] for k in funcs], float)
        dse, dci, _ = intervals(derived_samples(funcs, inp.values, inp.vary, boot.samples),
                                hat, derived_samples(funcs, inp.values, inp.vary,
                                                     boot.jackknife), kind=opts["interval"])
        for j, k in enumerate(funcs):
            finite = math.isfinite(dse[j]) and bool(np.all(np.isfinite(dci[j])))
            derived[k] = {**derived[k], "stderr": float(dse[j]) if finite else None,
                          "ci95": [float(dci[j, 0]), float(dci[j, 1])] if finite else None}
    if boot.failed > 0.1 * opts["n_boot"]:
        warn_msgs.append(f"{boot.failed} of {opts['n_boot']} bootstrap refits failed or "
                         "could not determine every parameter (resamples of too few "
                         "distinct conditions); the bootstrap errors rest on the others")
    if boot.n_groups < 8:
        warn_msgs.append(f"the bootstrap resamples only {boot.n_groups} conditions: its "
                         "errors and intervals are coarse")
    return {"n_boot": opts["n_boot"], "seed": opts["seed"], "interval": used,
            "conditions": boot.n_groups, "failed": boot.failed}


def _bootstrap_refused(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                       derived: dict[str, dict[str, Any]], warn_msgs: list[str],
                       opts: dict[str, Any], n_cond: int) -> dict[str, Any]:
    """No bootstrap with no more conditions than parameters: every error withheld.

    Each resample of so few conditions either cannot determine the parameters or
    repeats the full fit, so its spread would read as an error of zero.
    """
    for k in inp.vary:
        estimates[k] = replace(estimates[k], stderr=None, ci95=None)
    for k in derived:
        derived[k] = {**derived[k], "stderr": None, "ci95": None}
    warn_msgs.append(f"the bootstrap needs more test conditions than the parameters they "
                     f"determine ({n_cond} condition{'s' if n_cond != 1 else ''}, "
                     f"{len(inp.vary)} parameters): its standard "
                     "errors are undetermined and withheld (the asymptotic ones are kept "
                     "in uncertainty.asymptotic_stderr)")
    return {"n_boot": opts["n_boot"], "seed": opts["seed"], "interval": None,
            "conditions": n_cond, "failed": None}


def _numpy_ns() -> Any:
    from .law import NUMPY

    return NUMPY


@functools.lru_cache(maxsize=1)
def _versions() -> tuple[tuple[str, str], ...]:
    """Versions of the packages a result depends on (read once: metadata is slow).

    A package already imported gives its ``__version__``; only the others are looked
    up in the installed metadata (a scan of the environment).
    """
    import sys
    from importlib.metadata import PackageNotFoundError, version

    def ver(pkg: str) -> str:
        loaded = getattr(sys.modules.get(pkg), "__version__", None)
        if isinstance(loaded, str):
            return loaded
        try:
            return version(pkg)
        except PackageNotFoundError:
            return "unknown"

    from . import __version__

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
    from . import jsonio
    from .limits import read_input
    from .outputs import check_input_file

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
    from .uncertainty import UNCERTAINTY_METHODS

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
