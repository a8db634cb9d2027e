"""The packaged tread compound's predictions set beside published figures.

The figures (``datasets/tread-compound/published.json``, sources and what each
says in ``datasets/tread-compound/PROVENANCE.md``) are statements about other
rubbers: Persson's flash-temperature paper (J. Phys.: Condens. Matter 18 (2006)
7789) on where the heating starts to matter and where the friction then falls,
and a published WLF fit to a filled rubber's measured shift factors.  No
measured mu(v) of the packaged compound exists (it is constructed), so these
comparisons are of kind and order of magnitude; each is computed here, on the
preset ``tread-on-asphalt`` (asphalt-like surface, q1 = 1e6 1/m) at 0.2 MPa and
20 degC, with the thermal properties :data:`~frictionlaws.persson.TREAD_THERMAL`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..law import NUMPY
from ..viscoelastic.temperature import wlf_formula
from .flash import TREAD_THERMAL, Flash

__all__ = ["Comparison", "published_comparison", "published_shift", "peak", "PUBLISHED_FILE"]

#: The published figures (``datasets/tread-compound/``).
PUBLISHED_FILE = "tread-compound/published.json"

#: Velocities [m/s] the comparisons are computed on: 20 a decade, 10 um/s to 10 m/s.
V_GRID = np.logspace(-5, 1, 121)


@dataclass(frozen=True)
class Comparison:
    """One published figure and the library's prediction of the same quantity.

    Attributes
    ----------
    quantity : str
        What is compared.
    published, predicted : float
        The published figure and the prediction, in ``unit``.
    unit : str
        Their unit.
    difference : float
        ``log10(predicted/published)`` [decades] for velocities, the relative
        difference [%] otherwise (``difference_unit`` says which).
    difference_unit : str
        ``"decades"`` or ``"%"``.
    source : str
        Where the published figure is (paper and location).
    """

    quantity: str
    published: float
    predicted: float
    unit: str
    difference: float
    difference_unit: str
    source: str

    def describe(self) -> str:
        """One line: quantity, published, predicted, difference."""
        sign = "+" if self.difference >= 0 else ""
        return (f"{self.quantity}: published {self.published:.4g} {self.unit}, predicted "
                f"{self.predicted:.4g} {self.unit} ({sign}{self.difference:.2f} "
                f"{self.difference_unit})")


def peak(v: Any, mu: Any) -> tuple[float, float]:
    """Height and velocity of the maximum of ``mu`` over ``log10 v``.

    The parabola in ``log10 v`` through the largest sample and its two
    neighbours (the samples themselves when the largest is at an end).
    """
    x, y = np.log10(np.asarray(v, float)), np.asarray(mu, float)
    k = int(np.argmax(y))
    if k == 0 or k == y.size - 1:
        return float(y[k]), float(10.0 ** x[k])
    a, b, c = np.polyfit(x[k - 1:k + 2], y[k - 1:k + 2], 2)
    xp = -b / (2.0 * a)
    return float(c - b * b / (4.0 * a)), float(10.0 ** xp)


def _first_below(v: np.ndarray, r: np.ndarray, level: float) -> float:
    """The first velocity at which ``r`` falls below ``level`` (linear in log v)."""
    k = int(np.argmax(r < level))
    if k == 0:
        return math.nan if r[0] >= level else float(v[0])
    x0, x1 = math.log10(v[k - 1]), math.log10(v[k])
    return float(10.0 ** (x0 + (x1 - x0) * (r[k - 1] - level) / (r[k - 1] - r[k])))


def _check_conditions(material: Any, T: Any, flash: Any) -> None:
    """Refuse a temperature whose shift to T + 20 K leaves the material's range, or no Flash."""
    if not isinstance(flash, Flash):
        raise InputError(f"published_comparison: flash must be a Flash (thermal properties), "
                         f"got {type(flash).__name__}")
    lo, hi = material.temperature_range()
    if not (isinstance(T, (int, float)) and lo <= T and T + 20.0 <= hi):
        raise InputError(f"published_comparison: T = {T!r} K must lie in {lo:.2f}.."
                         f"{hi - 20.0:.2f} K (the compound's range, less the 20 K of the "
                         "shift compared)")


@functools.lru_cache(maxsize=1)
def _published() -> dict[str, Any]:
    import json

    from ..io import datasets_dir

    spec: dict[str, Any] = json.loads((datasets_dir() / PUBLISHED_FILE).read_text(
        encoding="utf-8"))
    return spec


def published_shift(T: Any) -> np.ndarray:
    """log10 a_T [decades] of the published WLF fit to a filled rubber (``published.json``).

    Its magnitude convention: positive below its reference temperature (the
    rubber relaxes more slowly when colder), as :mod:`frictionlaws.viscoelastic.temperature`.
    """
    w = _published()["wlf_filled_rubber"]
    return np.asarray(wlf_formula(NUMPY, np.asarray(T, float), w["C1"], w["C2"]["value"],
                                  w["T_ref"]["value"]))


def published_comparison(*, T: float = 293.15, p: float = 2e5,
                         flash: Flash = TREAD_THERMAL) -> list[Comparison]:
    """The packaged tread compound's predictions beside the published figures.

    Parameters
    ----------
    T : float
        Temperature [K] of the rubber (and of the road): 20 degC by default.
    p : float
        Nominal pressure [Pa].
    flash : Flash
        Thermal properties for the flash temperature.

    Returns
    -------
    list of Comparison
        The velocity of the friction maximum with the flash temperature, the
        velocity at which the heating has lowered the friction by 10 %, and
        the shift of log10 a_T from T to T + 20 K.
    """
    from .material import tread_compound
    from .surface import asphalt_like
    from .theory import friction

    pub = _published()
    mat, surf = tread_compound(), asphalt_like(1e6)
    _check_conditions(mat, T, flash)
    iso = friction(mat, surf, V_GRID, T, p)
    hot = friction(mat, surf, V_GRID, T, p, flash=flash)
    fp, onset = pub["flash_peak_velocity"], pub["heating_onset_velocity"]
    v_peak = peak(V_GRID, hot)[1]
    v_onset = _first_below(V_GRID, hot / iso, 0.9)
    shift_pub = float(published_shift(T) - published_shift(T + 20.0))
    shift_here = float(mat.shift(T) - mat.shift(T + 20.0))
    return [
        Comparison("velocity of the friction maximum with the flash temperature",
                   fp["value"], v_peak, "m/s", math.log10(v_peak / fp["value"]), "decades",
                   fp["source"]),
        Comparison("velocity at which the heating has lowered mu by 10 %", onset["value"],
                   v_onset, "m/s", math.log10(v_onset / onset["value"]), "decades",
                   onset["source"]),
        Comparison("shift of log10 a_T from T to T + 20 K", shift_pub, shift_here, "decades",
                   100.0 * (shift_here / shift_pub - 1.0), "%",
                   pub["wlf_filled_rubber"]["source"]),
    ]
