"""The pieces a law is declared from: variables, parameters, settings, derived quantities.

The variables are the library's (:data:`VARIABLES`, their units read from the one unit
table); the limits here (:data:`V_MIN`, :data:`P_MIN`, :data:`F_MIN`, :data:`MU_MAX`)
are the library's one definition of each.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.units import QUANTITIES
from .namespace import NUMPY

__all__ = ["VARIABLES", "Variable", "Param", "Setting", "Derived", "FAMILIES",
           "EVIDENCE_TAGS", "V_MIN", "P_MIN", "F_MIN", "MU_MAX"]

#: Floor applied to the sliding velocity in laws with log v or v**(-k) [m/s].
V_MIN = 1e-9
#: Floor applied to the contact pressure in laws singular at p = 0 [Pa].
P_MIN = 1.0
#: Floor applied to the normal load in laws singular at F_N = 0 [N].
F_MIN = 1e-6
#: Largest friction coefficient the library writes (FE decks) or reports as a tyre's
#: peak.  Rubber on dry rough surfaces reaches 3 to 4; more is a unit or parameter
#: error (mu_k = 9495 from an extrapolated fit, mu0 = 1e6 typed by hand).
MU_MAX = 10.0


@dataclass(frozen=True)
class Variable:
    """An independent variable a law may use (always in SI units inside).

    Its units are not declared here: :attr:`unit` and :attr:`display_unit` are read
    from the one table of units, :data:`frictionlaws.base.units.QUANTITIES`.

    Parameters
    ----------
    name : str
        The variable's name (a key of :data:`~frictionlaws.base.units.QUANTITIES`).
    meaning : str
        What the variable is, in a few words ("contact pressure").
    typical : tuple of float
        A typical range in SI (low, high).
    """

    name: str
    meaning: str
    typical: tuple[float, float]

    @property
    def unit(self) -> str:
        """The SI unit (``""`` when dimensionless)."""
        return QUANTITIES[self.name].si

    @property
    def display_unit(self) -> str:
        """The unit outputs write the variable in (p in MPa, T in degC)."""
        return QUANTITIES[self.name].display


#: The independent variables known to frictionlaws (their units are read from
#: :data:`frictionlaws.base.units.QUANTITIES`).
VARIABLES: dict[str, Variable] = {
    "p": Variable("p", "contact pressure", (1e4, 1e6)),
    "v": Variable("v", "sliding velocity (magnitude)", (1e-3, 10.0)),
    "T": Variable("T", "temperature", (253.15, 373.15)),
    "F_N": Variable("F_N", "normal load", (1.0, 1000.0)),
    "s": Variable("s", "slip ratio (braking slip, 0..1)", (0.0, 1.0)),
}


FAMILIES = ("sliding", "slip")
EVIDENCE_TAGS = {
    "C": "confirmed in a public source",
    "S": "secondary support only",
    "M": "as commonly quoted, not verified against the original",
    "I": "own derivation or numerical check",
    "NF": "original not found; documented identifiable recommendation",
}


@dataclass(frozen=True)
class Param:
    """A fitted parameter of a law.

    Parameters
    ----------
    name : str
        Python identifier used in the formula and as keyword argument.
    unit : str
        Unit in SI, parsable by pint (``""`` for dimensionless).
    default : float
        A typical value; also the fallback initial guess.
    bounds : tuple of float
        Lower and upper bound used by the fitter (may be infinite).
    meaning : str
        One line saying what the parameter is.
    optional : bool
        When True the law may be called without this parameter and the
        default is used (e.g. the Schallamach exponent n = 1/3).
    """

    name: str
    unit: str
    default: float
    bounds: tuple[float, float] = (-math.inf, math.inf)
    meaning: str = ""
    optional: bool = False


@dataclass(frozen=True)
class Setting:
    """A fixed setting of a law (a reference scale), not fitted by default.

    Parameters
    ----------
    name : str
        Python identifier used in the formula.
    value : float
        The value (SI).
    unit : str
        Unit in SI, parsable by pint (``""`` for dimensionless).
    meaning : str
        One line saying what the setting is.
    bounds : tuple of float
        Lower and upper bound when the setting is fitted (``free=``).
    """

    name: str
    value: float
    unit: str
    meaning: str = ""
    bounds: tuple[float, float] = (0.0, math.inf)


@dataclass(frozen=True)
class Derived:
    """A quantity derived from the parameters (peak, slope at origin...).

    Parameters
    ----------
    name : str
        Name of the quantity.
    unit : str
        Its SI unit.
    meaning : str
        One line saying what it is.
    func : callable
        ``func(m, **params_and_settings)`` returns the value; it is written with
        the same math namespace as the formula so uncertainties can be propagated
        numerically by the fitter.
    """

    name: str
    unit: str
    meaning: str
    func: Callable[..., Any]

    def value(self, params: Mapping[str, float], ns: Any = None) -> float:
        """Evaluate at ``params``: a division by zero gives inf or nan, never an error.

        Parameters
        ----------
        params : mapping
            Parameter and setting values (SI).
        ns : namespace, optional
            The math namespace (default: NumPy's).

        Returns
        -------
        float
            The value; ``inf``/``nan`` where the formula has a pole (e.g. 1/b at b = 0).
        """
        vals = {k: np.float64(v) for k, v in params.items()}
        with np.errstate(all="ignore"):
            try:
                return float(self.func(NUMPY if ns is None else ns, **vals))
            except (ZeroDivisionError, OverflowError):
                return math.nan
