"""The flash temperature on the packaged tread compound: its own figures, and what is published.

A published comparison compares like with like: the predicted mu(v) of a
rubber on a surface beside the measured friction of the same rubber on the same
surface.  No such data is openly available in a form that could be read (the
candidate source and what was read of it: ``datasets/tread-compound/PROVENANCE.md``),
and the packaged compound is constructed, not measured.  So nothing is set beside
a published figure as a check.  What this module gives instead is the model's own
figures on the packaged compound (:func:`flash_figures`: where the maximum of
mu(v) lies with and without the flash temperature, and where the heating starts
to lower the friction), which the Persson guide states and the tests hold, and
the published figures that are *not* comparable (``published.json``: Persson's
typical case of 2006, another rubber on another road; a WLF fit to another filled
rubber, :func:`published_shift`), kept as context with their sources.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..io import datasets_dir
from ..law import NUMPY
from ..viscoelastic.temperature import wlf_formula
from .flash import TREAD_THERMAL, Flash
from .material import tread_compound
from .surface import asphalt_like
from .theory import friction

__all__ = ["FlashFigures", "flash_figures", "published_shift", "peak", "PUBLISHED_FILE",
           "V_GRID"]

#: The published figures (``datasets/tread-compound/``), none of them of the packaged compound.
PUBLISHED_FILE = "tread-compound/published.json"

#: Velocities [m/s] the figures are computed on: 20 a decade, 10 um/s to 100 m/s.
V_GRID = np.logspace(-5, 2, 141)


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


def _inner_peak(v: np.ndarray, mu: np.ndarray) -> tuple[float, float]:
    """:func:`peak`, or (nan, nan) when the largest sample is at an end of the grid."""
    k = int(np.argmax(mu))
    if k == 0 or k == mu.size - 1:
        return math.nan, math.nan
    return peak(v, mu)


def _first_below(v: np.ndarray, r: np.ndarray, level: float) -> float:
    """The first velocity at which ``r`` falls below ``level`` (linear in log v); nan if never."""
    below = r < level
    if not below.any():
        return math.nan
    k = int(np.argmax(below))
    if k == 0:
        return float(v[0])
    x0, x1 = math.log10(v[k - 1]), math.log10(v[k])
    return float(10.0 ** (x0 + (x1 - x0) * (r[k - 1] - level) / (r[k - 1] - r[k])))


@dataclass(frozen=True)
class FlashFigures:
    """mu(v) of the packaged compound with and without the flash temperature, in figures.

    Attributes
    ----------
    T, p : float
        Temperature [K] and nominal pressure [Pa].
    flash : Flash
        The flash-temperature settings.
    isothermal_peak, flash_peak : tuple of float
        (height [-], velocity [m/s]) of the maximum of mu(v) over
        :data:`V_GRID` without and with the flash temperature; (nan, nan) when
        the maximum lies beyond the grid.
    onset : float
        The lowest velocity [m/s] at which the heating has lowered mu by 10 %
        (nan if it does not on the grid).
    """

    T: float
    p: float
    flash: Flash
    isothermal_peak: tuple[float, float]
    flash_peak: tuple[float, float]
    onset: float

    def describe(self) -> str:
        """One line: the two maxima and the onset, with units."""
        (m0, v0), (m1, v1) = self.isothermal_peak, self.flash_peak
        how = (f"{self.flash.closure} closure ({self.flash.contact_temperature} contact "
               "temperature)" if self.flash.closure == "volume"
               else f"{self.flash.closure} closure")
        return (f"T = {self.T - 273.15:.4g} degC, p = {self.p / 1e6:.4g} MPa, {how}: maximum of mu "
                f"{m0:.3f} at {v0:.3g} m/s isothermal, {m1:.3f} at {v1:.3g} m/s with the flash "
                f"temperature; the heating lowers mu by 10 % from {self.onset:.3g} m/s")


def flash_figures(*, T: float = 293.15, p: float = 2e5, flash: Flash = TREAD_THERMAL,
                  v_max: float = 100.0) -> FlashFigures:
    """The packaged tread compound's mu(v) with and without the flash temperature, in figures.

    On the preset ``tread-on-asphalt`` (asphalt-like surface, q1 = 1e6 1/m),
    over :data:`V_GRID` up to ``v_max``.

    Parameters
    ----------
    T : float
        Temperature [K] of the rubber and the road, inside the compound's range.
    p : float
        Nominal pressure [Pa], 1e3 .. 1e8.
    flash : Flash
        The flash-temperature settings (default :data:`~frictionlaws.persson.TREAD_THERMAL`).
    v_max : float
        Highest velocity [m/s] of the grid, 0.001 .. 100 (the surface-flux
        closure heats the rubber beyond 300 degC above some 10 m/s).

    Raises
    ------
    InputError
        A temperature or pressure that is not a number in its range, or no Flash.
    """
    mat, surf = tread_compound(), asphalt_like(1e6)
    _check_conditions(mat, T, p, flash, v_max)
    v = V_GRID[V_GRID <= v_max * (1 + 1e-12)]
    iso = friction(mat, surf, v, T, p)
    hot = friction(mat, surf, v, T, p, flash=flash)
    return FlashFigures(float(T), float(p), flash, _inner_peak(v, iso), _inner_peak(v, hot),
                        _first_below(v, hot / iso, 0.9))


def _check_conditions(material: Any, T: Any, p: Any, flash: Any, v_max: Any) -> None:
    if not isinstance(flash, Flash):
        raise InputError(f"flash_figures: flash must be a Flash (thermal properties), got "
                         f"{type(flash).__name__}")
    lo, hi = material.temperature_range()
    for name, x, a, b, unit in (("T", T, lo, hi, "K"), ("p", p, 1e3, 1e8, "Pa"),
                                ("v_max", v_max, 1e-3, 100.0, "m/s")):
        if isinstance(x, bool) or not isinstance(x, (int, float)) or not a <= x <= b:
            hint = (f"; if it is in degC, {x:g} degC is {x + 273.15:g} K"
                    if name == "T" and isinstance(x, (int, float)) and a <= x + 273.15 <= b
                    else "")
            raise InputError(f"flash_figures: {name} = {x!r} must be a number in "
                             f"{a:.6g} .. {b:.6g} {unit}{hint}")


@functools.lru_cache(maxsize=1)
def _published() -> dict[str, Any]:
    spec: dict[str, Any] = json.loads((datasets_dir() / PUBLISHED_FILE).read_text(
        encoding="utf-8"))
    return spec


def published_shift(T: Any) -> np.ndarray:
    """log10 a_T [decades] of the published WLF fit to another filled rubber (``published.json``).

    Its magnitude convention: positive below its reference temperature (the
    rubber relaxes more slowly when colder), as :mod:`frictionlaws.viscoelastic.temperature`.
    Context for the packaged compound's chosen (universal) shift, not a check
    of it: the rubbers differ.
    """
    w = _published()["wlf_filled_rubber"]
    return np.asarray(wlf_formula(NUMPY, np.asarray(T, float), w["C1"], w["C2"]["value"],
                                  w["T_ref"]["value"]))
