"""Analytic Jacobians of the laws, derived once from their symbolic form.

Each law's formula, called with the sympy namespace, is differentiated with respect
to every parameter and setting; the derivatives share their common subexpressions
(:func:`sympy.cse`) and are written out as plain numpy code in
``frictionlaws/fitting/_jacobians.py`` by :func:`write_module` (run by
``python -m frictionlaws.caches``, with the other caches derived from the laws).  Fits and
the identifiability analysis then use that code without importing sympy.

A generated entry is used only while it still describes the law: the module stores the
law's :func:`~frictionlaws.law.formula_check` (its symbols and mu at two points, the check
the cached formula text uses too), and :func:`jacobian_function` compares it with the
law's formula now.  A law changed since the module was written, a law
registered by a plugin, or a law whose formula sympy cannot differentiate (Persson's
numerical integral) gets ``None``, and the fit falls back to finite differences.
``tests/fitting/test_derivatives.py`` checks that the module is current for every built-in
law (:func:`module_current`) and compares every analytic Jacobian with a numerical one.
"""

from __future__ import annotations

import functools
import re
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any

import numpy as np

from ..law import NUMPY, Law, evaluation, formula_check, formula_matches

__all__ = ["jacobian_function", "model_jacobian", "generate_source", "module_current",
           "write_module", "MODULE_PATH"]

#: Where the generated derivative code lives.
MODULE_PATH = Path(__file__).parent / "_jacobians.py"


@functools.cache
def _table() -> dict[str, tuple[dict[str, Any], Callable[..., Any]]]:
    try:
        from ._jacobians import JACOBIANS
    except ImportError:  # pragma: no cover - the module ships with the package
        return {}
    table: dict[str, tuple[dict[str, Any], Callable[..., Any]]] = dict(
        JACOBIANS)  # type: ignore[arg-type]
    return table


_CHECKED: dict[int, bool] = {}


def _current(law: Law) -> bool:
    """True when the generated module's entry for ``law`` still describes its formula."""
    key = id(law.formula)
    if key not in _CHECKED:
        entry = _table().get(law.id)
        _CHECKED[key] = entry is not None and formula_matches(law, entry[0])
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
    return _table()[law.id][1] if _current(law) else None


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
    jac = np.empty((n, len(names)), order="F")
    block = evaluation.BLOCK_ROWS  # the rows per block of the law's own large evaluations
    step = block if n >= evaluation.BLOCKED_FROM else max(n, 1)
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
    lines.append("    _cols = {")  # columns as functions: only the requested ones are computed
    for k, d in zip(names, reduced):
        lines.append(f"        {k!r}: lambda: {printer.doprint(d)},")
    lines.append("    }")
    lines.append("    return [_cols[k]() for k in names]")
    text = "\n".join(lines)
    if "numpy." in text.replace("numpy.", "", 0) and "# Not supported" in text:
        return None
    return text


def generate_source(laws: list[Law]) -> str:
    """The text of ``frictionlaws/fitting/_jacobians.py`` for ``laws``.

    It defines ``JACOBIANS``.

    Parameters
    ----------
    laws : list of Law
        The laws to derive (those sympy cannot differentiate are left out).

    Returns
    -------
    str
        Python source defining ``JACOBIANS``: law id -> (the law's
        :func:`~frictionlaws.law.formula_check` when written, derivative function).
    """
    head = ['"""Analytic Jacobians of the built-in laws: GENERATED, do not edit.',
            "",
            "Written by ``python -m frictionlaws.caches`` from each law's symbolic form",
            "(sympy, common subexpressions shared); see :mod:`frictionlaws.fitting.derivatives`.",
            '"""', "", "# ruff: noqa", "# mypy: ignore-errors", "",
            "import numpy", "", '__all__ = ["JACOBIANS"]', "", ""]
    body, table = [], []
    for law in laws:
        src = _entry_source(law)
        if src is None:
            continue
        check = formula_check(law)
        if check is None:
            continue
        body.append(src)
        fname = "_d_" + law.id.replace("-", "_").replace("+", "_")
        table.append(f"    {law.id!r}: ({check!r}, {fname}),")
    return ("\n".join(head) + "\n\n\n".join(body) + "\n\n\nJACOBIANS = {\n"
            + "\n".join(table) + "\n}\n")


#: A float literal of the generated code.
_FLOAT = re.compile(r"-?[0-9]+\.[0-9]+(?:e[-+]?[0-9]+)?")


def _floats_rounded(text: str) -> str:
    """``text`` with every float literal at 9 significant digits."""
    return _FLOAT.sub(lambda m: f"{float(m.group()):.9g}", text)


def module_current(laws: list[Law], path: Path | None = None) -> bool:
    """True when the generated module holds what :func:`generate_source` gives ``laws`` now.

    The code must match to the letter; the check values the module embeds (mu at two
    points, computed by numpy) to 9 significant digits, since their last digit varies
    with numpy.

    Parameters
    ----------
    laws : list of Law
        The laws the module is for (the built-in ones).
    path : Path, optional
        The module (default :data:`MODULE_PATH`).

    Returns
    -------
    bool
        True when current.
    """
    try:
        stored = Path(path or MODULE_PATH).read_text(encoding="utf-8")
    except OSError:
        return False
    return _floats_rounded(stored) == _floats_rounded(generate_source(laws))


def write_module(laws: list[Law], path: Path | None = None) -> Path:
    """Write the generated module for ``laws``.

    Parameters
    ----------
    laws : list of Law
        The laws to derive (the built-in ones).
    path : Path, optional
        Where to write (default :data:`MODULE_PATH`, which the fits then read).

    Returns
    -------
    Path
        The file written.
    """
    target = Path(path or MODULE_PATH)
    target.write_text(generate_source(laws), encoding="utf-8")
    _table.cache_clear()
    _CHECKED.clear()
    return target
