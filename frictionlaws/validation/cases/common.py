"""What the validation cases share: the sources they cite, the thesis rows, the helpers that
probe a law (its maximum, a slope, a refusal) and the law ids they run over.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import numpy as np

from ...base.errors import DomainError
from ...law import VARIABLES
from ...law.registry import list_laws
from ..reference import (
    REFERENCES,
)

__all__ = ["LAWS_MD", "THESIS", "THESIS_STEEL_ROWS", "builtin_law_ids"]


LAWS_MD = "laws.md (the frictionlaws law catalogue)"


THESIS = ("source thesis: rubber friction on a rotary pin-on-disc tribometer and its use in "
          "tyre FE analysis (thesis-data.md)")


#: Thesis Figure 5-16a, steel disc (EES look-up table): (FC [-], NL [kg], CP [MPa], DV [m/s]),
#: as printed (strings, so that the hand computation below is exact).
THESIS_STEEL_ROWS = (
    ("3.005", "1", "0.03119", "0"), ("1.946", "2", "0.06239", "0"),
    ("1.304", "3", "0.09358", "0"), ("1.354", "3.5", "0.1092", "0"),
    ("1.237", "4", "0.1248", "0"), ("1.272", "4.5", "0.1404", "0"),
    ("1.155", "5", "0.156", "0"), ("1.2", "5.5", "0.1716", "0"),
    ("3.686", "1", "0.03119", "1.38"), ("2.189", "2", "0.06239", "1.38"),
    ("1.785", "3", "0.09358", "1.38"), ("1.466", "3.5", "0.1092", "1.38"),
    ("1.493", "4", "0.1248", "1.38"), ("1.351", "4.5", "0.1404", "1.38"),
    ("1.19", "5", "0.156", "1.38"), ("1.161", "6", "0.1872", "1.38"),
    ("0.9951", "7", "0.2184", "1.38"), ("1.106", "8", "0.2496", "1.38"),
    ("3.716", "1", "0.03119", "2.77"),
)


def builtin_law_ids() -> list[str]:
    """Ids of the registered laws that belong to frictionlaws (plugins excluded).

    A law belongs to frictionlaws when its formula is defined inside the package
    or when the suite knows it (it has a reference implementation); laws added
    by plugins through the entry-point group are neither.
    """
    return [law.id for law in list_laws()
            if law.id in REFERENCES
            or getattr(law.formula, "__module__", "").startswith("frictionlaws.")]


def _plugin_law_ids() -> list[str]:
    builtin = set(builtin_law_ids())
    return [law.id for law in list_laws() if law.id not in builtin]


def _argmax(f: Callable[[np.ndarray], np.ndarray], lo: float, hi: float,
            n: int = 20001) -> tuple[float, float]:
    """Location and value of the maximum of ``f`` on [lo, hi] (grid, then bounded Brent)."""
    from scipy.optimize import minimize_scalar

    x = np.linspace(lo, hi, n)
    y = np.asarray(f(x), float)
    i = int(np.nanargmax(y))
    if i in (0, n - 1):
        return float(x[i]), float(y[i])
    res = minimize_scalar(lambda t: -float(np.asarray(f(np.array([t])), float)[0]),
                          bounds=(float(x[i - 1]), float(x[i + 1])), method="bounded",
                          options={"xatol": 1e-13})
    return float(res.x), -float(res.fun)


def _half_unit(printed: str) -> float:
    """Half a unit of the last printed digit of a decimal string."""
    decimals = len(printed.split(".")[1]) if "." in printed else 0
    return 0.5 * 10.0 ** (-decimals)


def _along(law: Any, var: str, *, log10: bool = False, **fixed: float) -> Callable[[Any], Any]:
    """``law`` as a function of one variable ``var`` (of ``log10(var)`` when ``log10``)."""

    def f(x: Any) -> Any:
        return law(**{var: 10.0 ** np.asarray(x) if log10 else x}, **fixed)

    return f


def _forward_slope(f: Callable[[float], Any], h: float) -> float:
    """Second-order one-sided derivative at 0 (slip laws are defined for s >= 0)."""
    return float((-3.0 * f(0.0) + 4.0 * f(h) - f(2.0 * h)) / (2.0 * h))


def _refuses(law: Any, **kw: Any) -> bool:
    try:
        law(**kw)
    except DomainError:
        return True
    return False


def _raw(law: Any) -> Callable[..., Any]:
    """The law's formula without the checks of ``law(...)``: these cases verify identities
    of the published forms, also where those forms give mu < 0 (which ``law(...)`` refuses)."""
    def evaluate(preset: str | None = None, **kw: Any) -> Any:
        variables = {k: v for k, v in kw.items() if k in VARIABLES}
        params = {k: v for k, v in kw.items() if k not in VARIABLES}
        return law.evaluate(variables, law.resolve(params, preset))

    return evaluate

