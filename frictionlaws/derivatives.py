"""Analytic Jacobians of the laws, derived once from their symbolic form.

Each law's formula, called with the sympy namespace, is differentiated with respect
to every parameter and setting; the derivatives share their common subexpressions
(:func:`sympy.cse`) and are written out as plain numpy code in
``frictionlaws/laws/_jacobians.py`` by :func:`write_module`
(``python -m frictionlaws.derivatives``).  Fits and the identifiability analysis then
use that code without importing sympy.

A generated entry is used only while it still describes the law: the module stores the
law's value at a probe point, and :func:`jacobian_function` compares it with the law's
formula evaluated there now.  A law changed since the module was written, a law
registered by a plugin, or a law whose formula sympy cannot differentiate (Persson's
numerical integral) gets ``None``, and the fit falls back to finite differences.
``tests/test_derivatives.py`` checks that the module is current for every built-in law
and compares every analytic Jacobian with a numerical one.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from .law import NUMPY, Law

__all__ = ["jacobian_function", "model_jacobian", "probe_point", "generate_source",
           "write_module", "MODULE_PATH"]

#: Where the generated derivative code lives.
MODULE_PATH = Path(__file__).parent / "laws" / "_jacobians.py"
#: Relative agreement the probe value must show for a generated entry to be used.
PROBE_RTOL = 1e-12


def probe_point(law: Law) -> dict[str, float]:
    """A point where the law is evaluated to recognise its generated derivative code.

    Parameters
    ----------
    law : Law
        The law.

    Returns
    -------
    dict
        Variables (inside their typical range, away from floors and zero) and every
        parameter and setting (their declared defaults, nudged off round values so
        that a changed formula shows).
    """
    out: dict[str, float] = {}
    for k in law.variables:
        lo, hi = law.typical_range(k)
        out[k] = lo + 0.37 * (hi - lo) if k != "s" else 0.0731
    for p in law.params:
        out[p.name] = _nudge(p.default, p.bounds)
    for s in law.settings:
        out[s.name] = _nudge(s.value, s.bounds)
    return out


def _nudge(value: float, bounds: tuple[float, float]) -> float:
    moved = value * 1.0137 + 0.0011 if value != 0 else 0.0123
    return moved if bounds[0] <= moved <= bounds[1] else value


def _probe_value(law: Law, point: dict[str, float]) -> float:
    with np.errstate(all="ignore"):
        try:
            return float(law.formula(NUMPY, **{k: np.float64(v) for k, v in point.items()}))
        except (TypeError, ValueError, ZeroDivisionError, OverflowError):
            return math.nan


@functools.cache
def _table() -> dict[str, tuple[dict[str, float], float, Callable[..., Any]]]:
    try:
        from .laws import _jacobians
    except ImportError:  # pragma: no cover - the module ships with the package
        return {}
    table: dict[str, tuple[dict[str, float], float, Callable[..., Any]]] = dict(
        _jacobians.JACOBIANS)  # type: ignore[arg-type]
    return table


_CHECKED: dict[int, bool] = {}


def _current(law: Law) -> bool:
    """True when the generated module's entry for ``law`` still describes its formula."""
    key = id(law.formula)
    if key not in _CHECKED:
        entry = _table().get(law.id)
        ok = False
        if entry is not None:
            point, value, _func = entry
            now = _probe_value(law, point)
            ok = set(point) == set(probe_point(law)) and math.isfinite(now) and (
                abs(now - value) <= PROBE_RTOL * max(abs(value), 1e-300))
        _CHECKED[key] = ok
    return _CHECKED[key]


def jacobian_function(law: Law) -> Callable[..., Any] | None:
    """The generated derivative function of ``law``, or None.

    Parameters
    ----------
    law : Law
        The law (its formula must be the one the code was generated from).

    Returns
    -------
    callable or None
        ``func(m, names, **variables_params_settings)`` returning one column (array or
        scalar) per name in ``names``; None when there is no current generated entry.
    """
    return _table()[law.id][2] if _current(law) else None


def model_jacobian(func: Callable[..., Any], prepared: Mapping[str, np.ndarray],
                   values: Mapping[str, float], names: list[str], n: int) -> np.ndarray:
    """The (n, k) Jacobian of a law's model from its generated derivative function.

    Parameters
    ----------
    func : callable
        The law's :func:`jacobian_function`.
    prepared : mapping
        The variables as the formula takes them (:meth:`Law.prepare_variables`).
    values : mapping
        Every parameter and setting.
    names : list of str
        The parameters (or settings) to differentiate by, one column each.
    n : int
        The number of rows.

    Returns
    -------
    numpy.ndarray
        d mu / d name, column by column (NaN or infinity where the derivative is not
        finite, e.g. d(x**c)/dc at x = 0).
    """
    from . import law as law_module

    jac = np.empty((n, len(names)), order="F")
    block = law_module._BLOCK  # the rows per block of the law's own large evaluations
    step = block if n >= law_module._BLOCKED_FROM else max(n, 1)
    for start in range(0, n, step):  # blocks keep the formula's temporaries small
        part = {k: v[start:start + step] if np.ndim(v) else v for k, v in prepared.items()}
        with np.errstate(all="ignore"):
            cols = func(NUMPY, names, **part, **values)
        for j, col in enumerate(cols):
            jac[start:start + step, j] = col
    return jac


# ----------------------------------------------------------------- generation


def _entry_source(law: Law) -> str | None:
    """The derivative function of one law as Python source, or None when not derivable."""
    import sympy
    from sympy.printing.numpy import NumPyPrinter

    try:
        expr = law.symbolic()
    except Exception:  # noqa: BLE001 - a numerical formula (an integral) is not symbolic
        return None
    syms = law.symbols()
    names = [p.name for p in law.params] + [s.name for s in law.settings]
    derivs = [sympy.diff(expr, syms[k]) for k in names]
    bad = (sympy.DiracDelta, sympy.Derivative, sympy.Subs)
    if any(d.has(*bad) for d in derivs):
        return None
    reps, reduced = sympy.cse(derivs, symbols=sympy.numbered_symbols("x"), optimizations="basic")
    printer = NumPyPrinter({"fully_qualified_modules": True, "allow_unknown_functions": False})
    args = ", ".join([*law.variables, *names])
    fname = "_d_" + law.id.replace("-", "_").replace("+", "_")
    lines = [f"def {fname}(m, names, {args}):"]
    for sym, sub in reps:
        lines.append(f"    {sym} = {printer.doprint(sub)}")
    lines.append("    d = {")
    for k, d in zip(names, reduced):
        lines.append(f"        {k!r}: {printer.doprint(d)},")
    lines.append("    }")
    lines.append("    return [d[k] for k in names]")
    text = "\n".join(lines)
    if "numpy." in text.replace("numpy.", "", 0) and "# Not supported" in text:
        return None
    return text


def generate_source(laws: list[Law]) -> str:
    """The text of ``frictionlaws/laws/_jacobians.py`` for ``laws``.

    It defines ``JACOBIANS``.

    Parameters
    ----------
    laws : list of Law
        The laws to derive (those sympy cannot differentiate are left out).

    Returns
    -------
    str
        Python source defining ``JACOBIANS``: law id -> (probe point, value there,
        derivative function).
    """
    head = ['"""Analytic Jacobians of the built-in laws: GENERATED, do not edit.',
            "",
            "Written by ``python -m frictionlaws.derivatives`` from each law's symbolic form",
            "(sympy, common subexpressions shared); see :mod:`frictionlaws.derivatives`.",
            '"""', "", "# ruff: noqa", "# mypy: ignore-errors", "",
            "import numpy", "", '__all__ = ["JACOBIANS"]', "", ""]
    body, table = [], []
    for law in laws:
        src = _entry_source(law)
        if src is None:
            continue
        point = probe_point(law)
        value = _probe_value(law, point)
        if not math.isfinite(value):
            continue
        body.append(src)
        fname = "_d_" + law.id.replace("-", "_").replace("+", "_")
        table.append(f"    {law.id!r}: ({point!r}, {value!r}, {fname}),")
    return ("\n".join(head) + "\n\n\n".join(body) + "\n\n\nJACOBIANS = {\n"
            + "\n".join(table) + "\n}\n")


def write_module(path: Path | None = None) -> Path:
    """Write the generated module for every registered built-in law.

    Parameters
    ----------
    path : Path, optional
        Where to write (default :data:`MODULE_PATH`).

    Returns
    -------
    Path
        The file written.
    """
    from .registry import list_laws

    target = MODULE_PATH if path is None else Path(path)
    target.write_text(generate_source(list(list_laws())), encoding="utf-8")
    _table.cache_clear()
    _CHECKED.clear()
    return target


if __name__ == "__main__":
    print(write_module())
