"""A cornering sweep's result (:class:`CorneringResult`): forces, moments, stiffness and the
shares of the patch that slide, with units.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...base.errors import InputError

__all__ = ["CorneringResult"]


@dataclass
class CorneringResult:
    """Cornering stiffness of a brush tyre against load (SI inside).

    Attributes
    ----------
    loads : numpy.ndarray
        Vertical loads [N].
    angles_deg : numpy.ndarray
        Slip angles of the secant [deg].
    fy : numpy.ndarray
        Lateral force [N], shape (loads, angles).
    cs : numpy.ndarray
        Cornering stiffness over the angles (least-squares slope through the
        origin) [N/rad].
    cs_origin : numpy.ndarray
        Slope at the origin [N/rad].
    half_length, mean_pressure, peak_pressure : numpy.ndarray
        Patch half-length [m], mean and peak contact pressure [Pa] per load.
    """

    law: str
    params: dict[str, float]
    tyre: dict[str, Any]
    loads: np.ndarray
    angles_deg: np.ndarray
    fy: np.ndarray
    cs: np.ndarray
    cs_origin: np.ndarray
    half_length: np.ndarray
    mean_pressure: np.ndarray
    peak_pressure: np.ndarray
    warnings: list[str] = field(default_factory=list)

    @property
    def cs_kN_per_deg(self) -> np.ndarray:
        """Cornering stiffness over the angles [kN/deg]."""
        return self.cs * math.pi / 180.0 / 1000.0

    @property
    def cs_origin_kN_per_deg(self) -> np.ndarray:
        """Slope at the origin [kN/deg]."""
        return self.cs_origin * math.pi / 180.0 / 1000.0

    @property
    def secants_kN_per_deg(self) -> np.ndarray:
        """F_y(alpha)/alpha at each angle [kN/deg], shape (loads, angles)."""
        return self.fy / self.angles_deg[None, :] / 1000.0

    def ratio(self, low: float | None = None, high: float | None = None) -> float:
        """CS(high)/CS(low) for loads [N] in the result (default: last over first)."""
        i = 0 if low is None else _index_of(self.loads, low)
        j = -1 if high is None else _index_of(self.loads, high)
        if not self.cs[i] > 0:  # no friction, no stiffness: the ratio is undefined
            return math.nan
        return float(self.cs[j] / self.cs[i])

    def to_dict(self) -> dict[str, Any]:
        """JSON-able result with units in the keys."""
        return {
            "law": self.law, "params": dict(self.params), "tyre": self.tyre,
            "angles_deg": self.angles_deg.tolist(),
            "method": "least-squares slope of Fy against alpha through the origin over "
                      "the angles; origin = numerical slope at alpha -> 0",
            "loads_kN": (self.loads / 1000).tolist(),
            "cornering_stiffness_kN_per_deg": self.cs_kN_per_deg.tolist(),
            "cornering_stiffness_origin_kN_per_deg": self.cs_origin_kN_per_deg.tolist(),
            "secants_kN_per_deg": self.secants_kN_per_deg.tolist(),
            "fy_kN": (self.fy / 1000).tolist(),
            "half_length_mm": (self.half_length * 1000).tolist(),
            "mean_pressure_MPa": (self.mean_pressure / 1e6).tolist(),
            "peak_pressure_MPa": (self.peak_pressure / 1e6).tolist(),
            "ratio_last_over_first": self.ratio(),
            "warnings": list(self.warnings),
        }

    def table(self) -> str:
        """A plain-text table with units."""
        angles = ", ".join(f"{a:g}" for a in self.angles_deg)
        lines = [f"brush tyre, law {self.law}: cornering stiffness over alpha = {angles} deg "
                 "(least-squares slope through the origin) and at the origin",
                 f"{'load [kN]':>9}  {'CS [kN/deg]':>11}  {'CS0 [kN/deg]':>12}  "
                 f"{'2a [mm]':>7}  {'p_mean [MPa]':>12}  {'p_max [MPa]':>11}  "
                 + "  ".join(f"{'Fy(' + format(a, 'g') + ') [kN]':>11}"
                             for a in self.angles_deg)]
        for i, fz in enumerate(self.loads):
            lines.append(
                f"{fz / 1000:>9.3g}  {self.cs_kN_per_deg[i]:>11.4f}  "
                f"{self.cs_origin_kN_per_deg[i]:>12.4f}  {2000 * self.half_length[i]:>7.1f}  "
                f"{self.mean_pressure[i] / 1e6:>12.4f}  {self.peak_pressure[i] / 1e6:>11.4f}  "
                + "  ".join(f"{f / 1000:>11.4f}" for f in self.fy[i]))
        ratio = self.ratio()
        lines.append(f"CS({self.loads[-1] / 1000:g} kN) / CS({self.loads[0] / 1000:g} kN) = "
                     + (f"{ratio:.3f}" if math.isfinite(ratio)
                        else "n/a (no cornering stiffness at the lowest load)"))
        lines.extend(f"warning: {w}" for w in self.warnings)
        return "\n".join(lines)


def _index_of(values: np.ndarray, x: float) -> int:
    idx = np.flatnonzero(np.isclose(values, x, rtol=1e-9, atol=1e-9))
    if idx.size == 0:
        raise InputError(f"load {x:g} N is not among the computed loads "
                         f"{', '.join(f'{v:g}' for v in values)}")
    return int(idx[0])

