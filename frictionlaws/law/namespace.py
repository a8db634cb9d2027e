"""The math namespaces a law's formula is called with: numpy's and sympy's.

A formula ``formula(m, **names)`` is written once; called with :data:`NUMPY` it is the
vectorised numeric evaluation, called with :func:`sympy_namespace` and symbols it is the
symbolic form (the docs, the Fortran generator, the tests).
"""

from __future__ import annotations

import functools
from types import SimpleNamespace
from typing import Any

import numpy as np

__all__ = ["NUMPY", "sympy_namespace"]


def _sympy_log10(x: Any) -> Any:
    import sympy

    return sympy.log(x, 10)


#: The numpy math namespace passed to formulas for numeric evaluation.
NUMPY = SimpleNamespace(
    exp=np.exp,
    log=np.log,
    log10=np.log10,
    sqrt=np.sqrt,
    sin=np.sin,
    cos=np.cos,
    tanh=np.tanh,
    cosh=np.cosh,
    arctan=np.arctan,
    abs=np.abs,
    sign=np.sign,
    maximum=np.maximum,
    minimum=np.minimum,
    power=lambda x, a: np.exp(a * np.log(x)),  # x > 0; numpy's general power is slower
    pi=np.pi,
    is_symbolic=False,
)


@functools.lru_cache(maxsize=1)
def sympy_namespace() -> SimpleNamespace:
    """The sympy math namespace passed to formulas for the symbolic form."""
    import sympy

    return SimpleNamespace(
        exp=sympy.exp,
        log=sympy.log,
        log10=_sympy_log10,
        sqrt=sympy.sqrt,
        sin=sympy.sin,
        cos=sympy.cos,
        tanh=sympy.tanh,
        cosh=sympy.cosh,
        arctan=sympy.atan,
        abs=sympy.Abs,
        sign=sympy.sign,
        maximum=sympy.Max,
        minimum=sympy.Min,
        power=sympy.Pow,
        pi=sympy.pi,
        is_symbolic=True,
    )
