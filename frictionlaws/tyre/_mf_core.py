"""The Magic Formula's shared pieces: the curves, the factors at a load, the model's interface.

Below both :mod:`frictionlaws.tyre.magic_formula` (the forces) and
:mod:`frictionlaws.tyre.mf_outputs` (the moments, radii and stiffnesses), so that
neither imports the other's module to use them: the sine curve :func:`mf_curve`, the
cosine weighting shape of combined slip, the factors :class:`MFCoefficients` and
:class:`MFModel`, the interface of a Magic Formula the outputs evaluate.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np

__all__ = ["EPS", "MFCoefficients", "MFModel", "mf_curve", "cos_weight"]

#: Small number added to C*D and K_y in the denominators (the textbook's epsilon) [N].
EPS = 1e-6


@dataclass(frozen=True)
class MFCoefficients:
    """The Magic Formula factors at one load (arrays when the load is an array).

    ``E = E_a - E_b * sgn(x)`` with ``x`` the shifted slip (``k_x`` or
    ``a_y``), limited to <= 1.  ``K = B C D`` is the slip stiffness [N per
    unit slip, or N/rad], ``D = mu F_z`` the peak factor [N], ``S_H`` the
    horizontal shift [-] or [rad, of tan(alpha)], ``S_V`` the vertical shift [N].
    """

    B: Any
    C: Any
    D: Any
    E_a: Any
    E_b: Any
    K: Any
    S_H: Any
    S_V: Any
    mu: Any

    def E(self, sign: float) -> Any:
        """E for a shifted slip of sign ``sign`` (+1 or -1), limited to <= 1."""
        return np.minimum(self.E_a - self.E_b * sign, 1.0)

    def as_dict(self) -> dict[str, Any]:
        return {"B": self.B, "C": self.C, "D": self.D, "E_plus": self.E(1.0),
                "E_minus": self.E(-1.0), "K": self.K, "S_H": self.S_H, "S_V": self.S_V,
                "mu": self.mu}


def mf_curve(x: Any, B: Any, C: Any, D: Any, E_a: Any, E_b: Any, S_V: Any) -> Any:
    """The Magic Formula sine curve at shifted slip ``x``, S_V added outside the sine."""
    E = np.minimum(E_a - E_b * np.sign(x), 1.0)
    bx = B * x
    return D * np.sin(C * np.arctan(bx - E * (bx - np.arctan(bx)))) + S_V


def cos_weight(x: Any, B: Any, C: Any, E: Any) -> Any:
    """``cos(C arctan(B x - E (B x - arctan(B x))))``, the combined-slip weighting shape."""
    bx = B * x
    return np.cos(C * np.arctan(bx - E * (bx - np.arctan(bx))))


class MFModel(Protocol):
    """What :mod:`~frictionlaws.tyre.mf_outputs` uses of a Magic Formula.

    :class:`~frictionlaws.tyre.magic_formula.MagicFormula` is one; the outputs are typed
    against this interface so that their module does not import the class's.
    """

    name: str
    fnomin: float
    fz0: float
    version: str
    equations: str
    slip_angle: str
    loads_above_fzmax: str
    pressure: float | None
    source: str
    structure: dict[str, float]
    limits: dict[str, tuple[float, float]]

    def _c(self, name: str, default: float | None = None) -> float: ...

    def _check(self, what: str, x: Any, positive: bool = False) -> Any: ...

    def _dpi(self, pressure: Any) -> Any: ...

    def _warn_range(self, name: str, x: Any) -> None: ...

    def _long(self, fz: Any, gamma: Any, dpi: Any) -> MFCoefficients: ...

    def _lat(self, fz: Any, gamma: Any, dpi: Any) -> MFCoefficients: ...

    def _gxa(self, kappa: Any, alpha_s: Any, fz: Any, gamma: Any) -> Any: ...

    def _gyk(self, kappa: Any, alpha_s: Any, fz: Any, gamma: Any, mu_y: Any
             ) -> tuple[Any, Any]: ...

    def gamma_star(self, gamma: Any) -> Any: ...
