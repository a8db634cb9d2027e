"""Unit systems of FE models: the units an exported file is written in.

FE codes have no units: every number in an input deck must be in the model's
own consistent system.  A :class:`UnitSystem` names the unit of each variable
(pressure, sliding velocity, temperature, normal load) in that system; the
exporters convert from the library's SI (a law is always evaluated in SI) with
the affine maps ``x_model = (x_si - offset) / scale`` computed by pint through
:mod:`frictionlaws.base.units`.

Named systems (case and punctuation do not matter):

* ``SI`` (also ``m-kg-s``): Pa, m/s, K, N;
* ``mm-N-s`` (also ``mm-t-s``): MPa, mm/s, K, N;
* ``mm-kg-ms``: GPa, m/s (= mm/ms), K, kN.

Any unit may be overridden after the name, e.g. ``"mm-N-s,T=degC"``.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from ..base.errors import InputError
from ..base.units import QUANTITIES, canonical_unit, to_si
from ..law import VARIABLES

if TYPE_CHECKING:
    import numpy as np
    from numpy.typing import ArrayLike

__all__ = ["UnitSystem", "SYSTEMS", "unit_system"]

#: Named unit systems: variable -> unit (pint syntax; "" = dimensionless).
SYSTEMS: dict[str, dict[str, str]] = {
    "SI": {v: QUANTITIES[v].si for v in VARIABLES},
    "mm-N-s": {"p": "MPa", "v": "mm/s", "T": "K", "F_N": "N", "s": ""},
    "mm-kg-ms": {"p": "GPa", "v": "m/s", "T": "K", "F_N": "kN", "s": ""},
}
_ALIASES = {"si": "SI", "mkgs": "SI", "mmns": "mm-N-s", "mmts": "mm-N-s",
            "mmkgms": "mm-kg-ms"}


def _key(name: str) -> str:
    return re.sub(r"[^a-z0-9]", "", name.lower())


@dataclass(frozen=True)
class UnitSystem:
    """The units an exported file is written in.

    Parameters
    ----------
    name : str
        Display name (``"SI"``, ``"mm-N-s"``, ``"mm-N-s,T=degC"``).
    units : dict
        Variable -> unit string understood by pint.
    """

    name: str
    units: dict[str, str] = field(default_factory=dict)

    def unit(self, var: str) -> str:
        """The unit of variable ``var`` in this system (``""`` when dimensionless)."""
        return self.units[var]

    def label(self, var: str) -> str:
        """``"MPa"``, or ``"-"`` for a dimensionless variable."""
        return self.units[var] or "-"

    def affine(self, var: str) -> tuple[float, float]:
        """``(scale, offset)`` with ``x_si = scale * x_model + offset``."""
        unit = self.units[var]
        zero = float(to_si(0.0, unit, var))
        one = float(to_si(1.0, unit, var))
        return one - zero, zero

    def to_model(self, var: str, x_si: ArrayLike) -> np.ndarray:
        """Convert SI values of ``var`` to this system's unit."""
        scale, offset = self.affine(var)
        return (np.asarray(x_si, dtype=float) - offset) / scale

    def to_si(self, var: str, x_model: ArrayLike) -> np.ndarray:
        """Convert values of ``var`` in this system's unit to SI."""
        scale, offset = self.affine(var)
        return np.asarray(x_model, dtype=float) * scale + offset

    def describe(self, variables: tuple[str, ...] | list[str] | None = None) -> str:
        """``"mm-N-s (p MPa, v mm/s, T K, F_N N); mu dimensionless"``."""
        names = [v for v in VARIABLES if variables is None or v in variables]
        parts = [f"{v} {self.label(v)}" for v in names if v != "s"]
        if "s" in names:
            parts.append("s dimensionless")
        inner = ", ".join(parts)
        return f"{self.name} ({inner}); mu dimensionless" if inner else (
            f"{self.name}; mu dimensionless")


def unit_system(spec: str | UnitSystem | None) -> UnitSystem:
    """Parse a unit-system specification.

    Parameters
    ----------
    spec : str or UnitSystem or None
        ``"SI"`` (default), ``"mm-N-s"``, ``"mm-kg-ms"``, optionally followed by
        overrides ``",VAR=UNIT"``, e.g. ``"mm-N-s,T=degC"``; or only overrides
        (``"p=MPa,v=mm/s"``, the rest SI).

    Raises
    ------
    InputError
        For an unknown system name, variable or unit (with the accepted ones).
    """
    if isinstance(spec, UnitSystem):
        return spec
    text = "SI" if spec is None or not str(spec).strip() else str(spec).strip()
    parts = [s.strip() for s in text.split(",") if s.strip()]
    base = "SI"
    if parts and "=" not in parts[0]:
        key = _key(parts[0])
        if key not in _ALIASES:
            raise InputError(
                f"unknown unit system '{parts[0]}'; expected one of "
                f"{', '.join(SYSTEMS)} (optionally followed by overrides such as ',T=degC')"
            )
        base = _ALIASES[key]
        parts = parts[1:]
    units = dict(SYSTEMS[base])
    given: set[str] = set()
    for part in parts:
        if "=" not in part:
            raise InputError(f"unit system '{text}': expected VAR=UNIT after the name, "
                             f"got '{part}'")
        var, unit = (s.strip() for s in part.split("=", 1))
        if var not in VARIABLES:
            raise InputError(f"unit system '{text}': unknown variable '{var}' "
                             f"(variables: {', '.join(VARIABLES)})")
        if var in given:
            raise InputError(f"unit system '{text}': the unit of {var} is given twice; "
                             "give it once")
        given.add(var)
        units[var] = canonical_unit(unit, var, column=var)  # written as read, never as typed
    name = base + "".join(f",{v}={units[v]}" for v in VARIABLES if v in given)
    return UnitSystem(name, units)
