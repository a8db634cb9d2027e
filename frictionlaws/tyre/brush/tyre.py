"""The brush tyre's geometry and stiffness (:class:`BrushTyre`), the model's choices and
numerical settings, and the limits of the values a tyre may have.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np

from ...base.errors import InputError

__all__ = ["DEFAULT_ANGLES_DEG", "PRESSURE_SHAPES", "CONTACT_MODELS", "SLIDING_SPEEDS",
           "ORIGIN_STEP", "BISECTION_STEPS", "NEWTON_SWEEPS", "TIP_STEPS", "SWEEP_TOL",
           "DEFAULT_C_PY", "TYRE_LIMITS", "BrushTyre", "SLIP_SCAN", "LOCAL_VARIABLES",
           "positive_load"]


#: The slip angles of the thesis' FE cornering runs [deg].
DEFAULT_ANGLES_DEG = (1.0, 2.0, 3.0)


PRESSURE_SHAPES = ("parabolic", "uniform")


CONTACT_MODELS = ("sqrt", "deflection")


SLIDING_SPEEDS = ("slip", "local")


#: Slip angle of the Richardson estimate of the slope at the origin [rad].
ORIGIN_STEP = 1e-4


#: Bisection steps per node for velocity-dependent laws (relative accuracy 2**-45).
BISECTION_STEPS = 45


#: Newton sweeps over the patch at most (sliding_speed="local"), Newton steps of the tip
#: speeds per sweep, and the step below which (relative to the largest deflection) the
#: sweeps have converged.
NEWTON_SWEEPS = 30


TIP_STEPS = 3


SWEEP_TOL = 1e-13


#: Scan grid of x = (q_a - q)/q_a for the slowest sliding solution (sliding_speed="local").
SLIP_SCAN = np.geomspace(1e-9, 1.0, 60)


#: Allowed variables of a law used as the local friction limit.
LOCAL_VARIABLES = ("p", "v")


#: Lateral tread stiffness per unit length of patch of the default tyre [N/m^2].
#: Chosen so that, with constant mu = 0.9 and the default patch, the secant
#: cornering stiffness over 1-3 deg at 4 kN equals the thesis' FE value
#: (Table 6-2: 0.890 kN/deg); see tests/tyre/test_tyre_brush.py.
DEFAULT_C_PY = 8.49e6


#: Ranges of real tyres (bicycle to mining tyre) outside which the brush tyre refuses
#: its geometry and speed: a 150 km wide patch is a typing error, not a tyre.
TYRE_LIMITS: dict[str, tuple[float, float]] = {
    "width": (0.005, 2.0),
    "half_length_ref": (0.001, 1.0),
    "radius": (0.05, 2.5),
    "speed": (1e-3, 150.0),
}


_LIMIT_UNITS = {"width": "m", "half_length_ref": "m", "radius": "m", "speed": "m/s"}


@dataclass(frozen=True)
class BrushTyre:
    """Geometry, stiffness and operating speed of a brush tyre (SI units).

    Parameters
    ----------
    width : float
        Contact patch width w [m].
    half_length_ref : float
        Half contact length a_ref [m] at ``ref_load`` (``contact="sqrt"``).
    ref_load : float
        Reference load F_ref [N].
    contact : {"sqrt", "deflection"} or callable
        Contact half-length against load (see the module documentation).
    radius, vertical_stiffness, q_ra1, q_ra2 : float
        Unloaded radius R [m], vertical stiffness K_z [N/m] and the two
        coefficients of ``a = q_ra1 sqrt(R delta) + q_ra2 delta`` (``"deflection"``).
    c_py, c_px : float
        Lateral and longitudinal tread stiffness per unit length of patch
        [N/m^2] (the line load per unit bristle deflection).
    pressure : {"parabolic", "uniform"} or callable
        Pressure distribution along the patch, or a shape ``f(xi)``.
    speed : float
        Forward (road) speed [m/s]; default 10 km/h as in the thesis.
    nodes : int
        Integration intervals along the patch.
    """

    width: float = 0.15
    half_length_ref: float = 0.055
    ref_load: float = 3000.0
    contact: str | Callable[[float], float] = "sqrt"
    radius: float = 0.31
    vertical_stiffness: float = 2.0e5
    q_ra1: float = 0.6
    q_ra2: float = 0.8
    c_py: float = DEFAULT_C_PY
    c_px: float = DEFAULT_C_PY
    pressure: str | Callable[[np.ndarray], np.ndarray] = "parabolic"
    speed: float = 10.0 / 3.6
    nodes: int = 400

    def __post_init__(self) -> None:
        for name in ("width", "half_length_ref", "ref_load", "radius", "vertical_stiffness",
                     "c_py", "c_px", "speed"):
            value = getattr(self, name)
            if not (isinstance(value, (int, float)) and math.isfinite(value) and value > 0):
                raise InputError(f"brush tyre: {name} must be a positive number (SI), "
                                 f"got {value!r}")
        for name, (lo, hi) in TYRE_LIMITS.items():
            value = getattr(self, name)
            if not lo <= value <= hi:
                raise InputError(f"brush tyre: {name} = {value:g} {_LIMIT_UNITS[name]} is "
                                 f"outside {lo:g}..{hi:g} {_LIMIT_UNITS[name]}, the range of "
                                 "real tyres this model is meant for")
        for name in ("q_ra1", "q_ra2"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0):
                raise InputError(f"brush tyre: {name} must be >= 0, got {value!r}")
        if not callable(self.contact) and self.contact not in CONTACT_MODELS:
            raise InputError(f"brush tyre: contact must be one of {', '.join(CONTACT_MODELS)} "
                             f"or a function of the load, got {self.contact!r}")
        if not callable(self.pressure) and self.pressure not in PRESSURE_SHAPES:
            raise InputError(f"brush tyre: pressure must be one of "
                             f"{', '.join(PRESSURE_SHAPES)} or a shape function f(xi), "
                             f"got {self.pressure!r}")
        if not (isinstance(self.nodes, int) and self.nodes >= 20):
            raise InputError(f"brush tyre: nodes must be an integer >= 20, got {self.nodes!r}")

    # ------------------------------------------------------------- geometry
    def half_length(self, fz: float) -> float:
        """Return the contact half-length a at a vertical load.

        Parameters
        ----------
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float
            Contact half-length a [m] given by :attr:`contact`.

        Raises
        ------
        InputError
            When ``fz`` is not a positive number, when a contact-length function
            gives a non-positive length, or when ``"sqrt"`` or ``"deflection"``
            gives a longer than the tyre radius.
        """
        fz = positive_load(fz)
        if callable(self.contact):
            a = float(self.contact(fz))
            if not (math.isfinite(a) and a > 0):
                raise InputError(f"brush tyre: the contact-length function gave a = {a!r} m "
                                 f"at F_z = {fz:g} N; expected a positive length")
            return a
        if self.contact == "sqrt":
            a = self.half_length_ref * math.sqrt(fz / self.ref_load)
        else:
            delta = fz / self.vertical_stiffness
            a = self.q_ra1 * math.sqrt(self.radius * delta) + self.q_ra2 * delta
        if a > self.radius:  # a patch longer than the wheel's diameter is not a tyre
            raise InputError(f"brush tyre: at F_z = {fz:g} N the contact half-length would "
                             f"be {a:.3g} m, more than the tyre radius {self.radius:g} m: "
                             "the load is beyond what this tyre can carry")
        return a

    def patch(self, fz: float, nodes: int | None = None) -> tuple[np.ndarray, np.ndarray]:
        """Return the patch nodes and the contact pressure along the patch at a load.

        The discrete pressure integrates (trapezoid rule, times the width) to
        exactly ``fz``.

        Parameters
        ----------
        fz : float
            Vertical load F_z [N], positive.
        nodes : int, optional
            Number of integration intervals (default :attr:`nodes`).

        Returns
        -------
        s : numpy.ndarray
            Positions of the ``nodes + 1`` nodes along the patch [m], from the
            leading edge (0) to the trailing edge (2a).
        p : numpy.ndarray
            Contact pressure at each node [Pa].

        Raises
        ------
        InputError
            For a bad load or a pressure shape function that is not usable.
        """
        fz = positive_load(fz)
        n = nodes or self.nodes
        a = self.half_length(fz)
        s = np.linspace(0.0, 2 * a, n + 1)
        xi = 1.0 - s / a
        if callable(self.pressure):
            shape = np.asarray(self.pressure(xi), dtype=float)
            if shape.shape != xi.shape or not np.all(np.isfinite(shape)) or np.any(shape < 0):
                raise InputError("brush tyre: the pressure shape function must return one "
                                 "finite value >= 0 per point xi in [-1, 1]")
        elif self.pressure == "parabolic":
            shape = np.clip(1.0 - xi**2, 0.0, None)
        else:
            shape = np.ones_like(xi)
        ds = s[1] - s[0]
        integral = float(np.sum(shape) - 0.5 * (shape[0] + shape[-1])) * ds
        if not integral > 0:
            raise InputError("brush tyre: the pressure shape integrates to zero")
        return s, fz * shape / (self.width * integral)

    def mean_pressure(self, fz: float) -> float:
        """Return the mean contact pressure F_z / (2 a w) at a load.

        Parameters
        ----------
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float
            Mean contact pressure [Pa].
        """
        return positive_load(fz) / (2 * self.half_length(fz) * self.width)

    def describe(self) -> dict[str, Any]:
        """Return the tyre's parameters as a JSON-able dict.

        Returns
        -------
        dict
            Field name -> value in SI (callables shown as ``"callable NAME"``),
            plus ``"units"``: field name -> unit of the dimensional fields.
        """
        out = asdict(self)
        for k in ("contact", "pressure"):
            v = getattr(self, k)
            if callable(v):
                out[k] = f"callable {getattr(v, '__name__', type(v).__name__)}"
        out["units"] = {"width": "m", "half_length_ref": "m", "ref_load": "N", "radius": "m",
                        "vertical_stiffness": "N/m", "c_py": "N/m^2", "c_px": "N/m^2",
                        "speed": "m/s"}
        return out


def positive_load(fz: Any) -> float:
    """The vertical load ``fz`` [N] as a float, refused unless a positive finite number."""
    try:
        value = float(fz)
    except (TypeError, ValueError):
        raise InputError(f"the vertical load must be a number in N, got {fz!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"the vertical load must be positive and finite [N], got {fz!r}")
    return value

