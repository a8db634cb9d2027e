"""Display units of results: what tables, HTML and figures show, SI one argument away.

frictionlaws computes in SI (p in Pa, so Thirion's ``b`` is in 1/Pa and ``tau_sat`` in
Pa), but a friction engineer reads pressures in MPa.  The result views
(:meth:`FitResult.to_frame <frictionlaws.fitting.FitResult.to_frame>`,
:meth:`FitResult.plot <frictionlaws.fitting.FitResult.plot>`, the HTML Jupyter shows)
take ``units="display"`` (the default) or ``units="si"``:

* a variable is shown in its display unit of :data:`frictionlaws.base.units.QUANTITIES`
  (p in MPa, v in m/s, T in degC, F_N in N);
* a parameter or derived quantity whose unit contains pascals is shown with the
  pascals in the pressure display unit (``1/Pa`` -> ``1/MPa``, ``Pa`` -> ``MPa``), its
  value, error and interval scaled by the same factor; every other unit is kept;
* dimensionless is written ``-`` everywhere (:data:`DIMENSIONLESS`).

Group labels (``T=20 degC``) and the per-group tables of ``fit --by`` and of a shared fit
(:func:`parameter_table`) use the same display units.  JSON files, the CSV outputs of the
command line and the single fit's text report stay in SI, their units written beside them.
"""

from __future__ import annotations

import functools
import math
import re
from collections.abc import Mapping, Sequence
from typing import Any

from .errors import InputError
from .units import QUANTITIES, display_unit, to_display

__all__ = ["DIMENSIONLESS", "UNITS_CHOICES", "check_units", "unit_text", "display_param_unit",
           "group_label", "parameter_table"]

#: How every result view writes "no unit".
DIMENSIONLESS = "-"
#: The accepted values of a view's ``units=`` argument.
UNITS_CHOICES = ("display", "si")

_PASCAL = re.compile(r"(?<![A-Za-z])Pa(?![A-Za-z])")


def check_units(units: str) -> str:
    """``units`` when it is ``"display"`` or ``"si"``; otherwise an :class:`InputError`."""
    if units not in UNITS_CHOICES:
        raise InputError(f"units must be 'display' or 'si', got {units!r}", option="units")
    return units


def unit_text(unit: str | None) -> str:
    """A unit as views write it: ``""`` and ``None`` become :data:`DIMENSIONLESS`."""
    return unit if unit else DIMENSIONLESS


_TOKEN = re.compile(r"\s*(\*\*|[A-Za-z_]+|[0-9]+(?:\.[0-9]+)?|[-+*/^()])")


def _pascal_power(unit: str) -> float:
    """The power of ``Pa`` in a law's unit string (``"1/Pa^2"`` -> -2), without pint.

    A small parser of ``*``, ``/``, ``^`` or ``**`` with a number, and parentheses,
    which is all a declared parameter unit uses; anything else is an ``InputError``.
    """
    tokens = [t for t in _TOKEN.findall(unit)]
    if "".join(tokens) != unit.replace(" ", ""):
        raise InputError(f"cannot read the unit '{unit}'")
    pos = 0

    def peek() -> str:
        return tokens[pos] if pos < len(tokens) else ""

    def take() -> str:
        nonlocal pos
        if pos >= len(tokens):
            raise InputError(f"cannot read the unit '{unit}'")
        pos += 1
        return tokens[pos - 1]

    def factor() -> float:
        tok = take()
        if tok == "(":
            inner = product()
            if take() != ")":
                raise InputError(f"cannot read the unit '{unit}'")
            value = inner
        elif tok.replace(".", "").isdigit() or re.fullmatch(r"[A-Za-z_]+", tok):
            value = 1.0 if tok == "Pa" else 0.0
        else:
            raise InputError(f"cannot read the unit '{unit}'")
        if peek() in ("^", "**"):
            take()
            sign = -1.0 if peek() == "-" else 1.0
            if peek() in ("-", "+"):
                take()
            number = take()
            if not number.replace(".", "").isdigit():
                raise InputError(f"cannot read the unit '{unit}'")
            value *= sign * float(number)
        return value

    def product() -> float:
        value = factor()
        while peek() in ("*", "/"):
            value += factor() if take() == "*" else -factor()
        return value

    power = product()
    if pos != len(tokens):
        raise InputError(f"cannot read the unit '{unit}'")
    return power


@functools.lru_cache(maxsize=256)
def display_param_unit(unit: str | None) -> tuple[str, float]:
    """The display unit of a parameter declared in ``unit`` (SI) and the factor to it.

    Parameters
    ----------
    unit : str or None
        The parameter's SI unit as declared by its law (``"1/Pa"``, ``"s/m"``, ``""``).

    Returns
    -------
    (str, float)
        The unit shown and ``factor`` with ``value_shown = factor * value_si``
        (``("1/MPa", 1e6)`` for ``"1/Pa"``; ``(unit, 1.0)`` when nothing changes).
    """
    if not unit or not _PASCAL.search(unit):
        return unit_text(unit), 1.0
    scale = QUANTITIES["p"].display_si[0]  # 1 MPa = 1e6 Pa
    return _PASCAL.sub(display_unit("p"), unit), float(scale ** -_pascal_power(unit))


def group_label(key: Mapping[str, Any]) -> str:
    """A group key in display units: ``{"T": 293.15}`` -> ``"T=20 degC"``.

    Variables (p, v, T, F_N...) are converted from SI to their display unit; other
    columns (``surface``) are written as they are.
    """
    parts = []
    for col, value in key.items():
        if col in QUANTITIES and isinstance(value, int | float) and not isinstance(value, bool):
            shown = float(to_display([float(value)], col)[0])
            unit = display_unit(col)
            parts.append(f"{col}={shown:.6g}{' ' + unit if unit else ''}")
        else:
            parts.append(f"{col}={value}")
    return ", ".join(parts) or "all rows"


def _estimate(est: Mapping[str, Any], factor: float) -> str:
    value, se = est.get("value"), est.get("stderr")
    if value is None or not math.isfinite(value):
        return "n/a"
    text = f"{value * factor:.5g}"
    if est.get("fixed"):
        return text + " (fixed)"
    if se is None or not math.isfinite(se):
        return text + " +/- n/a"
    return f"{text} +/- {_two_figures(se * factor)}"


def _two_figures(x: float) -> str:
    """An error to two significant figures, in plain notation where that stays short."""
    if x == 0 or not 1e-4 <= abs(x) < 1e5:
        return format(x, "#.2g")
    return f"{x:.{max(0, 1 - math.floor(math.log10(abs(x))))}f}"


def parameter_table(rows: Sequence[Mapping[str, Any]], shared: Sequence[str] = ()) -> str:
    """The per-group parameter table of ``fit --by`` and of a shared fit (display units).

    Parameters
    ----------
    rows : sequence of mapping
        One per group: ``label``, ``n``, optional ``r2`` and ``rmse``, and ``params``
        (name -> ``value``, ``stderr``, ``unit``, optional ``fixed``); a row with an
        ``error`` instead of ``params`` is shown with its message.
    shared : sequence of str
        Parameters common to every group (marked in the header).

    Returns
    -------
    str
        A fixed-width table: group, n, R^2 and RMSE (where any row has them), then
        each parameter as ``value +/- stderr`` with its unit in the header, then a row's
        ``note`` (its doubts: undetermined parameters, warnings), if it has one.
    """
    names: list[str] = []
    units: dict[str, tuple[str, float]] = {}
    for row in rows:
        for name, est in (row.get("params") or {}).items():
            if name not in units:
                names.append(name)
                units[name] = display_param_unit(est.get("unit"))
    metrics = [m for m in ("r2", "rmse")
               if any(row.get(m) is not None for row in rows)]
    head = ["group", "n", *({"r2": "R^2", "rmse": "RMSE"}[m] for m in metrics)] + [
        f"{k} [{units[k][0]}]{' (shared)' if k in shared else ''}" for k in names]
    body = []
    for row in rows:
        cells = [str(row["label"]), str(row.get("n", "-")),
                 *(_number(row.get(m), ".4f" if m == "r2" else ".4g") for m in metrics)]
        if row.get("error"):
            body.append(cells + [f"error: {row['error']}"])
            continue
        params = row.get("params") or {}
        body.append(cells + [_estimate(params[k], units[k][1]) if k in params else "-"
                             for k in names])
    widths = [max(len(r[i]) for r in [head, *body] if i < len(r)) for i in range(len(head))]
    lines = []
    for r in [head, *body]:
        lines.append("  ".join(c.ljust(widths[i]) if i == 0 else c.rjust(widths[i])
                               for i, c in enumerate(r)).rstrip())
    notes = ["", *(str(row.get("note") or "") for row in rows)]
    return "\n".join(f"{line}  ({note})" if note else line
                     for line, note in zip(lines, notes, strict=True))


def _number(x: Any, spec: str) -> str:
    return "-" if x is None or not math.isfinite(x) else format(x, spec)
