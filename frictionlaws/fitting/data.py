"""The data a fit takes: coercion of datasets, frames and arrays to :class:`FitData`, and the
checks made before any solve (finite, plausible, enough rows, options).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import Argument, GroupingError, InputError
from ..base.units import si_magnitude, to_display
from ..io import load_dataset
from ..law import VARIABLES, Law
from .methods import fit_method

__all__ = ["FitData", "as_fit_data", "GROUP_COLUMNS", "CONDITION_COLUMN", "refuse_pooled_groups",
           "MU_DATA_MAX", "check_fit_options", "invalid_rows"]


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
    """Raise :class:`~frictionlaws.base.errors.GroupingError` when a grouping column varies."""
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


#: Largest friction coefficient accepted as a measurement (a column of mu above it is a
#: unit or column error); the library's own plausible limit is :data:`frictionlaws.law.MU_MAX`.
#: And the largest magnitude of any other value a fit can square without overflow.
MU_DATA_MAX = 1e3


_MAGNITUDE_MAX = 1e100


def _check_magnitudes(fd: FitData) -> None:
    """Refuse values a fit cannot stand behind: mu above :data:`MU_DATA_MAX`, anything whose
    square would overflow."""
    for name, v in fd.arrays.items():
        limit = MU_DATA_MAX if name == "mu" else _MAGNITUDE_MAX
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
        One of :data:`~frictionlaws.fitting.methods.FIT_METHODS`.
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
    fit_method(method)
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


def _fmt_range(k: str, lo: float, hi: float) -> str:
    var = VARIABLES.get(k)
    if var is None:
        return f"{k} {lo:g}..{hi:g}"

    shown = to_display([lo, hi], k)
    return f"{k} {shown[0]:.4g}..{shown[1]:.4g} {var.display_unit or '-'}"


def _condition_vars(fd: FitData) -> list[str]:
    """The variables that define a test condition: every one the data hold, in order."""
    return [v for v in VARIABLES if v in fd.arrays]

