"""A steady-state brush tyre model whose local friction limit is any sliding law mu(p, v).

The model
---------
The tread is a row of elastic bristles (the classical brush model, Pacejka,
*Tire and Vehicle Dynamics*, chapter 3) attached to a rigid carcass.  The
contact patch has half-length ``a`` and width ``w``; ``s`` runs from the
leading edge (s = 0) to the trailing edge (s = 2a).  A bristle enters the
patch undeformed.  While it adheres to the road its tip deflection grows
linearly with the distance travelled,

    dq/ds = sigma,   sigma = tan(alpha) (side slip) or kappa / (1 + kappa) (longitudinal),

and the elastic line load is ``c q`` [N/m] with ``c`` the tread stiffness per
unit length of patch [N/m^2] (``c_py`` or ``c_px``).  The friction limit of
the line load at ``s`` is ``mu(p(s), v_s) p(s) w``: the local contact
pressure ``p(s)`` from the pressure distribution and the local sliding speed
``v_s`` feed the friction law.  Where the elastic load would exceed the limit
the bristle slides and carries exactly the limit.  Marching from the leading
edge this is

    q(s + ds) = min(q(s) + sigma ds,  mu(p, v_s) p w / c),

which also lets a sliding bristle stick again when the limit rises faster than
the adhesion deflection (possible with a pressure-dependent mu).  The force is
``F = c * integral(q ds)`` (trapezoid rule on ``nodes`` intervals).

Sliding speed.  A law that depends on the sliding speed ``v`` gets, by
default (``sliding_speed="slip"``), the speed of a fully sliding element: the
slip speed ``V tan(alpha)`` (side slip) or ``V |kappa|`` (longitudinal slip),
``V`` the road speed; the friction limit then varies along the patch through
the pressure only and the march keeps its closed form (one law evaluation per
node and slip).  This is the usual brush-model simplification; it also uses
mu at the slip speed at the adhesion/sliding transition.  With
``sliding_speed="local"`` the tip speed of each sliding bristle,
``v_s = V_r (sigma - dq/ds)`` (``V_r`` the rolling speed, ``V (1 + kappa)``
for longitudinal slip), is used instead: each node solves
``q = mu(p, V_r (q_a - q)/ds) p w / c`` (``q_a`` the adhesion trial), and a
bristle sticks while its trial stays below the static limit
``mu(p, 0) p w / c``.  All nodes of all slips are solved together (Newton
sweeps over the patch, a few milliseconds per load); when these do not settle
on the node-by-node solution (e.g. strong velocity weakening) the node-by-node
march (a scan and regula falsi per node, about 0.1 s per load) decides.  The
solution is unique when friction does not fall with sliding speed; when
several sliding speeds satisfy the law the slowest one is taken (stick-slip is
not modelled), and when none does (a law that falls with speed, where the
bristle must shed its deflection fast) the model raises an error and
``"slip"`` should be used.
Laws that need the normal load F_N, the temperature T or a slip ratio s are
rejected: a bristle only knows its pressure and sliding speed.

Sign convention: forces have the sign of the slip (``Fy`` has the sign of
``alpha``, ``Fx`` of ``kappa``), as in Pacejka's brush-model chapter, so the
cornering stiffness is positive.  (ISO/TYDEX property files give the
opposite sign for Fy; see :mod:`frictionlaws.tyre.magic_formula`.)

Contact length and pressure
---------------------------
* ``contact="sqrt"`` (default): ``a = a_ref sqrt(F_z / F_ref)``.  The defaults
  ``a_ref = 55 mm`` at ``F_ref = 3 kN`` with ``w = 150 mm`` give the footprint
  of the thesis' sizing (3000 N on 16 500 mm^2, a mean pressure of 0.18 MPa,
  close to its 0.22 MPa inflation).  A deflected circle has ``a ~ sqrt(2 R delta)``
  and a linear vertical stiffness gives ``delta ~ F_z``, hence the square root.
* ``contact="deflection"``: ``delta = F_z / K_z`` and
  ``a = q_ra1 sqrt(R delta) + q_ra2 delta`` (the MF-Swift contact-length form,
  with R = 0.31 m, K_z = 200 kN/m, q_ra1 = 0.6, q_ra2 = 0.8 by default: 53 mm
  at 3 kN, close to the default above).
* a callable ``a(F_z)`` [N -> m].

The pressure along the patch is ``"parabolic"`` (default, ``p = 3 F_z/(4 a w)
(1 - xi^2)``), ``"uniform"`` (``F_z/(2 a w)``) or a callable shape
``f(xi) >= 0`` of ``xi = x/a`` in [-1, 1] (+1 = leading edge), scaled so the
patch carries ``F_z``.

Cornering stiffness
-------------------
The thesis' FE model (chapter 6) reports a cornering stiffness in kN/deg from
the lateral forces at slip angles of 1, 2 and 3 degrees; it does not say how
the three were combined.  Here it is the least-squares slope of F_y against
alpha through the origin over those angles (``sum(F_i alpha_i) /
sum(alpha_i^2)``), with the three secants F_i/alpha_i kept as well.  At those
angles part of the patch slides, so the secant depends on friction.  The
slope at the origin does not: it is ``2 c a^2`` whenever the law gives a
positive friction limit at zero sliding speed all along the patch (the whole
patch adheres as alpha -> 0); otherwise (a law with mu(v = 0) = 0) it is
computed numerically (Richardson extrapolation at alpha = 1e-4 rad).

Why constant mu gives a cornering stiffness proportional to load: with
``a^2 ~ F_z`` both the elastic term (``2 c a^2 tan(alpha)``) and the friction
term (``mu F_z``) scale with F_z, so F_y / F_z depends on alpha only
(the parabolic brush gives ``F_y = mu F_z (3t - 3t^2 + t^3)``,
``t = 2 c a^2 tan(alpha) / (3 mu F_z)``, for t <= 1) and every secant is
proportional to F_z.  With a pressure-dependent law the mean pressure grows
like sqrt(F_z) with load, mu falls, the sliding zone grows, and the secant
rises less than in proportion.

Default tread stiffness: ``c_py = c_px = 8.49e6 N/m^2`` is the one value
calibrated, so that with constant mu = 0.9 the secant at 4 kN equals the
thesis' FE value (0.890 kN/deg).  The origin slope is then 1.19 kN/deg
(68 kN/rad) at 4 kN, a usual passenger-tyre value, and about a third of the
patch slides at 3 degrees.  With these defaults and ``thirion`` fitted to
``thesis-steel`` the ratio CS(6.5 kN)/CS(2 kN) is 2.60 against 3.25 for
constant mu (thesis FE: 1.89 for sandpaper 120 against 2.65 for mu = 0.9);
the patch pressures then exceed the 0.25 MPa the data reach, which the
model reports as an extrapolation.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from ..errors import DomainError, ExtrapolationWarning, InputError
from ..law import VARIABLES, Law

__all__ = ["BrushTyre", "BrushModel", "CorneringResult", "DEFAULT_ANGLES_DEG",
           "PRESSURE_SHAPES", "CONTACT_MODELS"]

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
_SCAN = np.geomspace(1e-9, 1.0, 60)
#: Allowed variables of a law used as the local friction limit.
_LOCAL_VARIABLES = ("p", "v")

#: Lateral tread stiffness per unit length of patch of the default tyre [N/m^2].
#: Chosen so that, with constant mu = 0.9 and the default patch, the secant
#: cornering stiffness over 1-3 deg at 4 kN equals the thesis' FE value
#: (Table 6-2: 0.890 kN/deg); see tests/test_tyre_brush.py.
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
        fz = _positive_load(fz)
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
        fz = _positive_load(fz)
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
        return _positive_load(fz) / (2 * self.half_length(fz) * self.width)

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


def _positive_load(fz: Any) -> float:
    try:
        value = float(fz)
    except (TypeError, ValueError):
        raise InputError(f"the vertical load must be a number in N, got {fz!r}") from None
    if not (math.isfinite(value) and value > 0):
        raise InputError(f"the vertical load must be positive and finite [N], got {fz!r}")
    return value


# --------------------------------------------------------------------- results


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


# ----------------------------------------------------------------------- model


def _law_mu(bound: Callable[..., Any], names: tuple[str, ...]) -> Callable[..., Any]:
    """mu(p, v) of a bound law whatever its variables (none, p, v, or both)."""
    if names == ():
        mu0 = float(bound())

        def mu(p: Any, v: Any = 0.0) -> Any:
            return np.full(np.broadcast(p, v).shape, mu0)
    elif names == ("p",):
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(p)
    elif names == ("v",):
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(v) + 0.0 * p
    else:
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(p=p, v=v)
    return mu


def _function_mu(func: Callable[..., Any]) -> Callable[..., Any]:
    """mu(p, v) of a user's function, given the speed's magnitude, as a float array."""
    def mu(p: Any, v: Any = 0.0) -> Any:
        return np.asarray(func(p, np.abs(v)), dtype=float) + 0.0 * p
    return mu


class BrushModel:
    """A brush tyre whose bristles obey a friction law mu(p, v).

    Parameters
    ----------
    law : str, Law, BoundLaw, FitResult or callable
        A registered law (id or :class:`~frictionlaws.law.Law`) with
        ``params``/``preset``; a :class:`~frictionlaws.bound.BoundLaw` or a fit
        result (its law and values; its fitted data range is used for
        extrapolation warnings); or a plain
        function ``mu(p, v)`` of pressure [Pa] and sliding speed [m/s].
    params : mapping, optional
        Parameter values of the law (SI).
    preset : str, optional
        A named preset of the law.
    tyre : BrushTyre, optional
        The tyre (default :class:`BrushTyre()`).
    sliding_speed : {"slip", "local"}
        Sliding speed given to a law that depends on v: ``"slip"`` (default)
        the speed of a fully sliding element, ``V tan(alpha)`` or
        ``V |kappa|``; ``"local"`` the bristle tip's own speed
        ``V_r (sigma - dq/ds)``, solved per node (see the module notes).

    Raises
    ------
    DomainError
        When the law needs a variable other than p and v (F_N, T, s).
    """

    def __init__(self, law: Any, params: Mapping[str, float] | None = None, *,
                 preset: str | None = None, tyre: BrushTyre | None = None,
                 sliding_speed: str = "slip") -> None:
        if sliding_speed not in SLIDING_SPEEDS:
            raise InputError(f"sliding_speed must be one of {', '.join(SLIDING_SPEEDS)}, "
                             f"got {sliding_speed!r}")
        self.sliding_speed = sliding_speed
        self.tyre = tyre if tyre is not None else BrushTyre()
        if not isinstance(self.tyre, BrushTyre):
            raise InputError("tyre must be a BrushTyre")
        self.law: Law | None = None
        self.fitted_ranges: dict[str, tuple[float, float]] = {}
        if isinstance(getattr(law, "law", None), Law):  # a BoundLaw or a fit result
            if params is not None or preset is not None:
                raise InputError("give either a bound law (or fit result) or params/preset, "
                                 "not both")
            from ..bound import as_bound

            bound = as_bound(law)
            self.fitted_ranges = dict(bound.fitted_ranges)
            params = bound.values
            law = bound.law
        if isinstance(law, (str, Law)):
            self._use_law(law, params, preset)
        elif callable(law):
            if params is not None or preset is not None:
                raise InputError("params/preset apply to a registered law, not to a function")
            self.values: dict[str, float] = {}
            self.uses_v = True
            self.label: str = getattr(law, "__name__", "function")
            self.mu = _function_mu(law)
        else:
            raise InputError(f"law must be a law name, a Law, a fit result or a function "
                             f"mu(p, v); got {type(law).__name__}")
        self._ranges = self._reference_ranges()

    def _use_law(self, law: str | Law, params: Mapping[str, float] | None,
                 preset: str | None) -> None:
        """Take a registered law of p and/or v, with its parameter values, as the limit."""
        from ..registry import get_law

        self.law = get_law(law)
        extra = [v for v in self.law.variables if v not in _LOCAL_VARIABLES]
        if extra or self.law.family != "sliding":
            what = ", ".join(f"{v} ({VARIABLES[v].meaning})" for v in extra)
            raise DomainError(
                f"law '{self.law.id}' cannot be the local friction limit of a brush "
                f"model: it needs {what or 'a slip ratio'}, while a bristle only has its "
                "contact pressure p and sliding speed v. Use a law of p and/or v "
                "(e.g. coulomb, thirion, savkoor, exponential-decay)")
        self.values = self.law.resolve(params, preset)
        adm = self.law.check_admissible(self.values)
        if adm:
            raise DomainError(f"law '{self.law.id}': parameters not admissible: {adm}")
        self.uses_v = "v" in self.law.variables
        self.label = self.law.id
        self.mu = _law_mu(self.law.bind(self.values), self.law.variables)

    # -------------------------------------------------------------- checks
    def _reference_ranges(self) -> dict[str, tuple[float, float, str]]:
        out: dict[str, tuple[float, float, str]] = {}
        if self.law is None:
            return out
        for var in self.law.variables:
            if var in self.fitted_ranges:
                lo, hi = self.fitted_ranges[var]
                out[var] = (lo, hi, "fitted data range")
            elif var in self.law.domain:
                lo, hi = self.law.domain[var]
                out[var] = (lo, hi, "valid domain of the law")
        return out

    def _limit(self, p: Any, v: Any, c: float, check: bool = True) -> np.ndarray:
        """Deflection limit mu p w / c [m]; raises on NaN or negative mu when ``check``."""
        with np.errstate(all="ignore"):
            mu = self._at_edges(np.asarray(self.mu(p, v), dtype=float), p, v)
        if check:
            self._check_mu(mu, p, v)
        return mu * self._limit_scale(p, c)

    def _at_edges(self, mu: np.ndarray, p: Any, v: Any) -> np.ndarray:
        """mu where the pressure is 0 (the patch's edges), for the limit mu p w / c.

        A law without a limit at p = 0 (mu growing as p -> 0) has no mu there, but
        the limit needs only mu p: where that goes to 0 (mu growing slower than 1/p,
        checked at p = 1e-100 and 1e-290 Pa) the limit is 0, and mu = 0 gives it;
        elsewhere mu stays NaN and is refused.
        """
        pb = np.broadcast_to(np.asarray(p, float), mu.shape)
        edge = (pb == 0) & ~np.isfinite(mu)
        if not edge.any():
            return mu
        vb = np.broadcast_to(np.asarray(v, float), mu.shape)[edge]
        with np.errstate(all="ignore"):
            q = [np.asarray(self.mu(e + 0.0 * vb, vb), float) * e for e in (1e-100, 1e-290)]
        vanishes = (np.isfinite(q[1]) & (np.abs(q[1]) <= 1e-12)
                    & (np.abs(q[1]) <= np.abs(q[0])))
        out = mu.copy()
        out[edge] = np.where(vanishes, 0.0, np.nan)
        return out

    def _limit_scale(self, p: Any, c: float) -> Any:
        """The deflection limit per unit mu, p w / c [m]."""
        return p * (self.tyre.width / c)

    def _check_mu(self, mu: np.ndarray, p: Any, v: Any) -> None:
        bad = ~np.isfinite(mu) | (mu < 0)
        if bad.any():
            i = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), bad.shape)
            pb = np.broadcast_to(np.asarray(p, float), mu.shape)[i]
            vb = np.broadcast_to(np.asarray(v, float), mu.shape)[i]
            raise DomainError(
                f"law '{self.label}' gives mu = {float(mu[i])!r} at p = {pb / 1e6:.4g} MPa, "
                f"v = {vb:.4g} m/s inside the contact patch: not usable as a friction limit "
                "there (check its parameters and valid domain)")

    def _pressure_share(self, p: np.ndarray) -> float:
        """Share of the load carried at pressures outside the law's fitted/valid range of p."""
        if "p" not in self._ranges:
            return 0.0
        lo, hi, _ = self._ranges["p"]
        outside = (p < lo * (1 - 1e-9)) | (p > hi * (1 + 1e-9))
        return float(np.sum(p[outside]) / np.sum(p)) if outside.any() else 0.0

    def _extrapolation(self, cases: list[tuple[float, np.ndarray, Any]]) -> list[str]:
        """Messages for loads whose patch leaves the law's range; ``cases`` = (fz, p, vs_range)."""
        msgs = []
        if "p" in self._ranges:
            lo, hi, what = self._ranges["p"]
            hits = [(fz, self._pressure_share(p), float(p.max())) for fz, p, _ in cases]
            hits = [h for h in hits if h[1] > 0.005]
            if hits:
                span = (f"{100 * hits[0][1]:.0f} % of the load at {hits[0][0] / 1000:g} kN"
                        if len(hits) == 1 else
                        f"{100 * hits[0][1]:.0f} % (at {hits[0][0] / 1000:g} kN) to "
                        f"{100 * hits[-1][1]:.0f} % (at {hits[-1][0] / 1000:g} kN) of the load")
                msgs.append(
                    f"law '{self.label}' is extrapolated: contact pressures outside the "
                    f"{what} of p ({lo / 1e6:.3g}..{hi / 1e6:.3g} MPa) carry {span}; "
                    f"patch pressures reach {max(h[2] for h in hits) / 1e6:.3g} MPa")
        if "v" in self._ranges:
            lo, hi, what = self._ranges["v"]
            out = [(fz, r) for fz, _, r in cases
                   if r is not None and (r[0] < lo * (1 - 1e-9) or r[1] > hi * (1 + 1e-9))]
            if out:
                vmin = min(r[0] for _, r in out)
                vmax = max(r[1] for _, r in out)
                msgs.append(
                    f"law '{self.label}' is extrapolated: sliding speeds {vmin:.3g}..{vmax:.3g} "
                    f"m/s leave the {what} of v ({lo:.3g}..{hi:.3g} m/s) at "
                    f"{', '.join(f'{fz / 1000:g}' for fz, _ in out)} kN")
        return msgs

    # --------------------------------------------------------------- core
    @staticmethod
    def _march(L: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Deflections q_k = min(q_{k-1} + d, L_k), q_0 = 0, for every slip (closed form).

        With u_k = q_k - k d the recursion is u_k = min(u_{k-1}, L_k - k d), a
        cumulative minimum.  ``L`` is (nodes,) or (slips, nodes); ``d`` (slips,).
        """
        j = np.arange(L.shape[-1])
        M = np.broadcast_to(L, (d.size, L.shape[-1])) - j[None, :] * d[:, None]
        M[:, 0] = 0.0
        return j[None, :] * d[:, None] + np.minimum.accumulate(M, axis=1)

    def _solve(self, sigma: np.ndarray, fz: float, c: float, v_roll: Any,
               nodes: int | None = None, keep: bool = False) -> dict[str, Any]:
        """Forces for slip magnitudes ``sigma`` >= 0 (1-D) at load ``fz``."""
        s, p = self.tyre.patch(fz, nodes)
        ds = s[1] - s[0]
        n_nodes = s.size
        sigma = np.asarray(sigma, dtype=float)
        d = sigma * ds
        vr = np.broadcast_to(np.asarray(v_roll, float), sigma.shape)
        vs_range = None
        if not self.uses_v:
            q = self._march(self._limit(p, 0.0, c), d)
        elif self.sliding_speed == "slip":
            vs = vr * sigma  # sliding speed of a fully sliding element
            q = self._march(self._limit(p[None, :], vs[:, None], c), d)
            slides = np.any(q < np.arange(n_nodes)[None, :] * d[:, None] * (1 - 1e-9), axis=1)
            if slides.any():
                vs_range = (float(vs[slides].min()), float(vs[slides].max()))
        else:
            q, vs_range = self._march_local(p, d, vr, ds, c)
        force = c * (np.sum(q, axis=1) - 0.5 * (q[:, 0] + q[:, -1])) * ds
        out: dict[str, Any] = {"force": force, "p": p, "s": s, "vs_range": vs_range}
        if keep:
            out["q"] = q
        return out

    def _march_local(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float, c: float
                     ) -> tuple[np.ndarray, tuple[float, float] | None]:
        """March with the local tip sliding speed V_r (sigma - dq/ds).

        All nodes of all slips are solved together (:meth:`_march_local_sweeps`); when
        that does not settle on the march's own solution (no steady sliding state, a
        law with several, mu unusable) the node-by-node march
        (:meth:`_march_local_nodes`) decides, and raises its errors.
        """
        l_static = self._limit(p, 0.0, c)
        fast = self._march_local_sweeps(p, d, vr, ds, c, l_static)
        if fast is not None:
            return fast
        return self._march_local_nodes(p, d, vr, ds, c, l_static)

    def _march_local_sweeps(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float,
                            c: float, l_static: np.ndarray
                            ) -> tuple[np.ndarray, tuple[float, float] | None] | None:
        """The local-speed march as one Newton iteration over the whole patch, or None.

        Node k maps its adhesion trial ``a_k = q_{k-1} + d`` to ``q_k = F_k(a_k)``: ``a_k``
        where it sticks (``a_k <= L_static``), else ``a_k - v/rate`` with ``v`` the tip
        speed solving ``a_k - v/rate = limit(p_k, v)`` (``rate = V_r/ds``), and
        ``F_k' = beta/(1 + beta)``, ``beta = rate dlimit/dv`` (1 where it sticks).  Each
        sweep solves every node's equation at once (:meth:`_tip_speeds`, warm-started)
        and takes the Newton step of the chain ``q_k = F_k(q_{k-1} + d)``, a
        lower-bidiagonal system.  It starts from the march at the static limit.  Returns
        None when it does not converge or when :meth:`_local_state_ok` rejects the
        result, so that the node-by-node march decides.
        """
        from scipy.linalg.lapack import dtbtrs

        n_slips, n = d.size, p.size - 1
        pk = np.tile(p[1:], n_slips)  # flat over (slip, node)
        ls = np.tile(l_static[1:], n_slips)
        rate = np.repeat(vr / ds, n)
        q = self._march(l_static, d)
        v = np.zeros(n_slips * n)
        band = np.zeros((2, n_slips * n))  # unit lower-bidiagonal, LAPACK band storage
        sub = band[1].reshape(n_slips, n)  # sub[:, k] couples node k + 1 to node k
        with np.errstate(all="ignore"):
            for _ in range(NEWTON_SWEEPS):
                a = (q[:, :-1] + d[:, None]).ravel()
                i = np.flatnonzero(a > ls)  # the sliding nodes
                if i.size == 0:
                    break  # every bristle sticks: the static march is exact
                v[i], dlim, settled = self._tip_speeds(pk[i], a[i], rate[i], c, v[i])
                f, slope = a.copy(), np.ones(a.size)
                f[i] = a[i] - v[i] / rate[i]
                slope[i] = dlim / (1.0 / rate[i] + dlim)
                sub[:, :-1] = -slope.reshape(n_slips, n)[:, 1:]
                step = dtbtrs(band, f - q[:, 1:].ravel(), uplo="L", diag="U")[0]
                q[:, 1:] += step.reshape(n_slips, n)
                if not np.all(np.isfinite(step)):
                    return None
                if settled and np.max(np.abs(step)) <= SWEEP_TOL * np.max(np.abs(q)):
                    break
            else:
                return None
            a = (q[:, :-1] + d[:, None]).ravel()
            i = np.flatnonzero(a > ls)
            speed = rate[i] * (a[i] - q[:, 1:].ravel()[i])
            if not self._local_state_ok(pk[i], a[i], speed, rate[i], c):
                return None
        return q, ((float(speed.min()), float(speed.max())) if speed.size else None)

    def _tip_speeds(self, pk: np.ndarray, a: np.ndarray, rate: np.ndarray, c: float,
                    v: np.ndarray) -> tuple[np.ndarray, np.ndarray, bool]:
        """Tip speeds v of sliding bristles: ``h(v) = a - v/rate - limit(pk, v) = 0``.

        Newton steps from the warm start ``v`` (forward-difference slope of the limit)
        inside the bracket ``[lo, hi]`` with ``h(lo) > 0 >= h(hi)`` that starts as
        ``[0, rate a]`` and shrinks with every evaluation (a step leaving it bisects
        it instead); at most :data:`TIP_STEPS`
        steps (the sweeps of :meth:`_march_local_sweeps` continue them).  Returns the
        speeds, the slopes ``dlimit/dv`` [s] and whether every ``|h| <= 1e-14 a``.
        """
        lo, hi = np.zeros_like(a), rate * a
        v = np.clip(v, lo, hi)
        dlim, settled = np.zeros_like(a), True
        scale = self._limit_scale(pk, c)  # limit = mu scale
        inv_rate, tol = 1.0 / rate, 1e-14 * a
        both = np.empty((2, a.size))
        for _ in range(TIP_STEPS):
            dv = 1e-7 * v + 1e-13
            both[0] = v
            np.add(v, dv, out=both[1])
            mu = np.broadcast_to(np.asarray(self.mu(pk, both), dtype=float), both.shape)
            lim = mu[0] * scale
            dlim = (mu[1] * scale - lim) / dv
            h = a - v / rate - lim  # as the sweep divides (q = 0 exactly where p = 0)
            pos = h > 0
            lo, hi = np.where(pos, v, lo), np.where(pos, hi, v)
            settled = bool(np.all(np.abs(h) <= tol))
            v_new = v + h / (inv_rate + dlim)
            v = np.where((v_new >= lo) & (v_new <= hi), v_new, 0.5 * (lo + hi))
            if settled:
                break
        return v, dlim, settled

    def _local_state_ok(self, pk: np.ndarray, a: np.ndarray, speed: np.ndarray,
                        rate: np.ndarray, c: float) -> bool:
        """Whether the sweeps' sliding states are those the node-by-node march picks.

        That march takes the first point of the log grid :data:`_SCAN` of
        ``x = (a - q)/a`` where the limit holds and the root between it and the point
        before; the state at ``x = speed/(rate a)`` must lie in that interval (it always
        does when the limit does not fall with speed: the root is then unique), and mu
        there must be usable.
        """
        if a.size == 0:
            return True
        lim = self._limit(pk[:, None], (rate * a)[:, None] * _SCAN[None, :], c, check=False)
        below = (a[:, None] * (1.0 - _SCAN[None, :])) <= lim
        first = np.argmax(below, axis=1)
        upper = _SCAN[first]
        lower = np.where(first > 0, _SCAN[np.maximum(first - 1, 0)], 0.0)
        x = speed / (rate * a)
        mu = np.asarray(self.mu(pk, speed), float)
        return bool(np.all(below[np.arange(a.size), first]) and np.all(x <= upper * (1 + 1e-9))
                    and np.all(x >= lower * (1 - 1e-9)) and np.all(np.isfinite(mu))
                    and np.all(mu >= 0))

    def _march_local_nodes(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float,
                           c: float, l_static: np.ndarray
                           ) -> tuple[np.ndarray, tuple[float, float] | None]:
        """The local-speed march node by node (a scan and regula falsi per node)."""
        q = np.zeros((d.size, p.size))
        qn = np.zeros(d.size)
        vs_min, vs_max = math.inf, -math.inf
        for k in range(1, p.size):
            qa = qn + d
            stick = qa <= l_static[k]
            if not stick.all():
                slide = ~stick
                qs, vrs = qa[slide], vr[slide]
                pk = p[k]
                x = self._slowest_slide(pk, qs, vrs, ds, c, l_static[k])
                qslide = qs * (1.0 - x)
                vs = vrs * (qs - qslide) / ds
                with np.errstate(all="ignore"):
                    self._check_mu(np.asarray(self.mu(pk, vs), float), pk, vs)
                qa = qa.copy()
                qa[slide] = qslide
                vs_min = min(vs_min, float(vs.min()))
                vs_max = max(vs_max, float(vs.max()))
            qn = qa
            q[:, k] = qn
        return q, ((vs_min, vs_max) if vs_min <= vs_max else None)

    def _slowest_slide(self, pk: float, qs: np.ndarray, vrs: np.ndarray, ds: float, c: float,
                       l_static: float) -> np.ndarray:
        """x = (q_a - q)/q_a of the slowest steady sliding state of each sliding bristle.

        The bristle at pressure ``pk`` with adhesion trial ``qs`` settles where its
        deflection meets the friction limit at its own tip speed:
        ``g(x) = qs (1 - x) - limit(pk, V_r qs x / ds) = 0``.  The root with the smallest
        sliding speed is bracketed by the first sign change of ``g`` on a log grid of x,
        then found by regula falsi with the Illinois modification (superlinear, and
        never leaving the bracket) to :data:`BISECTION_STEPS` halvings of the bracket;
        the returned x is the end of the final bracket where the limit holds.
        """
        x = _SCAN[None, :]
        lim = np.broadcast_to(self._limit(pk, (vrs * qs / ds)[:, None] * x, c, check=False),
                              (qs.size, _SCAN.size))
        below = (qs[:, None] * (1.0 - x)) <= lim
        first = np.argmax(below, axis=1)
        rows = np.arange(qs.size)
        if not below[rows, first].all():
            bad = int(np.flatnonzero(~below[rows, first])[0])
            raise DomainError(
                f"law '{self.label}': no steady sliding speed (tried up to "
                f"{vrs[bad] * qs[bad] / ds:.3g} m/s) holds a sliding bristle at "
                f"p = {pk / 1e6:.4g} MPa: the law falls with sliding speed there "
                "(velocity weakening) or turns negative, so the local-speed steady "
                "state does not exist; use sliding_speed='slip'")
        hi = _SCAN[first]
        g_hi = qs * (1.0 - hi) - lim[rows, first]
        prev = np.maximum(first - 1, 0)
        lo = np.where(first > 0, _SCAN[prev], 0.0)
        g_lo = np.where(first > 0, qs * (1.0 - lo) - lim[rows, prev], qs - l_static)
        return self._illinois(pk, qs, vrs, ds, c, (lo, hi, g_lo, g_hi))

    def _illinois(self, pk: float, qs: np.ndarray, vrs: np.ndarray, ds: float, c: float,
                  bracket: tuple[np.ndarray, ...]) -> np.ndarray:
        """Shrink brackets with g(lo) > 0 >= g(hi) around the root; return the hi ends."""
        lo, hi, g_lo, g_hi = bracket
        tol = (hi - lo) * 2.0**-BISECTION_STEPS
        side = np.zeros(qs.size)
        for _ in range(4 * BISECTION_STEPS):
            active = (hi - lo > tol) & (g_hi < 0)
            if not active.any():
                break
            with np.errstate(all="ignore"):
                x = hi - g_hi * (hi - lo) / (g_hi - g_lo)
            x = np.where((x > lo) & (x < hi), x, 0.5 * (lo + hi))
            g = qs * (1.0 - x) - self._limit(pk, vrs * qs * x / ds, c, check=False)
            ok = active & (g <= 0)
            up = active & ~(g <= 0)
            g_lo = np.where(ok & (side > 0), 0.5 * g_lo, g_lo)  # Illinois: the end that
            g_hi = np.where(up & (side < 0), 0.5 * g_hi, g_hi)  # stayed twice counts half
            hi, g_hi = np.where(ok, x, hi), np.where(ok, g, g_hi)
            lo, g_lo = np.where(up, x, lo), np.where(up, g, g_lo)
            side = np.where(ok, 1.0, np.where(up, -1.0, side))
        return hi

    def _full_sliding(self, fz: float, slide_speed: np.ndarray) -> np.ndarray:
        """Force of a fully sliding patch at sliding speeds ``slide_speed`` [N]."""
        s, p = self.tyre.patch(fz)
        ds = s[1] - s[0]
        lim = self._limit(p[None, :], np.asarray(slide_speed, float)[:, None], 1.0)
        return (np.sum(lim, axis=1) - 0.5 * (lim[:, 0] + lim[:, -1])) * ds

    def _emit(self, msgs: list[str]) -> None:
        if msgs:
            warnings.warn("; ".join(msgs), ExtrapolationWarning, stacklevel=3)

    def fy(self, alpha: Any, fz: float) -> Any:
        """Compute the lateral force F_y at slip angles and a vertical load.

        F_y has the sign of alpha.  Warns (ExtrapolationWarning) when the patch
        pressures or sliding speeds leave the law's fitted or valid range.

        Parameters
        ----------
        alpha : float or array-like
            Slip angles [rad], strictly between -pi/2 and pi/2.
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float or numpy.ndarray
            Lateral force F_y [N]: a float for a scalar ``alpha``, else an array
            of the shape of ``alpha``.

        Raises
        ------
        InputError
            For a bad load or slip angles that are not finite or not within
            (-90, 90) degrees.
        DomainError
            When the law gives no usable friction limit inside the patch.
        """
        fz = _positive_load(fz)
        alpha = np.asarray(alpha, dtype=float)
        if not np.all(np.isfinite(alpha)) or np.any(np.abs(alpha) >= math.pi / 2):
            raise InputError("slip angles must be finite and strictly between -90 and 90 "
                             "degrees (given in radians)")
        flat = alpha.ravel()
        sigma = np.abs(np.tan(flat))
        res = self._solve(sigma, fz, self.tyre.c_py, self.tyre.speed)
        self._emit(self._extrapolation([(fz, res["p"], res["vs_range"])]))
        out = np.sign(flat) * res["force"]
        return float(out[0]) if alpha.ndim == 0 else out.reshape(alpha.shape)

    def fx(self, kappa: Any, fz: float) -> Any:
        """Compute the longitudinal force F_x at slip ratios and a vertical load.

        ``kappa = (Omega R_e - V)/V``: positive when driving, -1 for a locked
        wheel (full sliding at the road speed).  F_x has the sign of kappa.
        Warns (ExtrapolationWarning) when the patch pressures or sliding speeds
        leave the law's fitted or valid range.

        Parameters
        ----------
        kappa : float or array-like
            Longitudinal slip ratios [-], finite.
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float or numpy.ndarray
            Longitudinal force F_x [N]: a float for a scalar ``kappa``, else an
            array of the shape of ``kappa``.

        Raises
        ------
        InputError
            For a bad load or slip ratios that are not finite.
        DomainError
            When the law gives no usable friction limit inside the patch.
        """
        fz = _positive_load(fz)
        kappa = np.asarray(kappa, dtype=float)
        if not np.all(np.isfinite(kappa)):
            raise InputError("slip ratios must be finite")
        flat = kappa.ravel()
        out = np.zeros(flat.shape)
        rolling = flat > -1.0 + 1e-9
        cases: list[tuple[float, np.ndarray, Any]] = []
        if rolling.any():
            k = flat[rolling]
            sigma = np.abs(k / (1.0 + k))
            res = self._solve(sigma, fz, self.tyre.c_px, self.tyre.speed * (1.0 + k))
            out[rolling] = np.sign(k) * res["force"]
            cases.append((fz, res["p"], res["vs_range"]))
        if (~rolling).any():
            k = flat[~rolling]
            out[~rolling] = -self._full_sliding(fz, self.tyre.speed * np.abs(k))
            speeds = self.tyre.speed * np.abs(k)
            cases.append((fz, self.tyre.patch(fz)[1],
                          (float(speeds.min()), float(speeds.max())) if self.uses_v else None))
        msgs = self._extrapolation(cases)
        self._emit(msgs)
        return float(out[0]) if kappa.ndim == 0 else out.reshape(kappa.shape)

    def patch_state(self, slip: float, fz: float, direction: str = "y") -> dict[str, np.ndarray]:
        """Compute the profiles along the contact patch at one slip and load.

        Parameters
        ----------
        slip : float
            Slip angle alpha [rad] for ``direction="y"``, or slip ratio kappa
            [-] (> -1, a rolling wheel) for ``direction="x"``.
        fz : float
            Vertical load F_z [N], positive.
        direction : {"y", "x"}
            Lateral (side slip) or longitudinal slip.

        Returns
        -------
        dict of str to numpy.ndarray
            One value per patch node: ``"s"`` position from the leading edge [m],
            ``"p"`` contact pressure [Pa], ``"line_load"`` elastic line load
            carried by the bristles [N/m], ``"adhesion_line_load"`` the line load
            had every bristle adhered [N/m], and ``"sliding"`` (bool) the nodes
            where the bristle slides and carries its friction limit.

        Raises
        ------
        InputError
            For a bad load, ``kappa <= -1`` or an unknown ``direction``.
        """
        fz = _positive_load(fz)
        if direction == "y":
            sigma, c, vr = abs(math.tan(slip)), self.tyre.c_py, self.tyre.speed
        elif direction == "x":
            if slip <= -1.0:
                raise InputError("patch_state needs a rolling wheel (kappa > -1)")
            sigma, c = abs(slip / (1.0 + slip)), self.tyre.c_px
            vr = self.tyre.speed * (1.0 + slip)
        else:
            raise InputError("direction must be 'x' or 'y'")
        res = self._solve(np.array([sigma]), fz, c, np.array([vr]), keep=True)
        q = res["q"][0]
        adhesion = np.arange(q.size) * sigma * (res["s"][1] - res["s"][0])
        return {"s": res["s"], "p": res["p"], "line_load": c * q,
                "adhesion_line_load": c * adhesion,
                "sliding": q < adhesion * (1 - 1e-9) - 1e-15}

    def cornering(self, loads: Sequence[float] | np.ndarray,
                  angles_deg: Sequence[float] = DEFAULT_ANGLES_DEG) -> CorneringResult:
        """Compute the cornering stiffness (secant over ``angles_deg`` and at the origin) by load.

        Parameters
        ----------
        loads : sequence of float
            Vertical loads [N].
        angles_deg : sequence of float
            Slip angles [deg] of the secant (the thesis used 1, 2, 3).

        Returns
        -------
        CorneringResult
            Per load: the least-squares cornering stiffness over the angles and
            the slope at the origin [N/rad], the lateral forces [N], the patch
            half-length [m] and mean and peak pressures [Pa], and extrapolation
            warnings.

        Raises
        ------
        InputError
            When no load is given, a load is not positive, or an angle is outside
            (0, 90) degrees.
        """
        loads = np.atleast_1d(np.asarray(loads, dtype=float))
        if loads.size == 0:
            raise InputError("no loads given")
        for fz in loads:
            _positive_load(fz)
        angles = np.atleast_1d(np.asarray(angles_deg, dtype=float))
        if angles.size == 0 or np.any(~np.isfinite(angles)) or np.any(angles <= 0) or np.any(
                angles >= 90):
            raise InputError("slip angles must be in (0, 90) degrees")
        alpha = np.radians(angles)
        h = ORIGIN_STEP
        sig = np.concatenate([np.tan(alpha), [math.tan(h), math.tan(2 * h)]])
        fy = np.empty((loads.size, angles.size))
        cs0 = np.empty(loads.size)
        cases: list[tuple[float, np.ndarray, Any]] = []
        for i, fz in enumerate(loads):
            res = self._solve(sig, float(fz), self.tyre.c_py, self.tyre.speed)
            f = res["force"]
            fy[i] = f[:angles.size]
            static = self._limit(res["p"][1:-1], 0.0, self.tyre.c_py)
            if np.all(static > 0):
                # bristles adhere all along the patch as alpha -> 0: exactly 2 c a^2
                cs0[i] = 2 * self.tyre.c_py * self.tyre.half_length(float(fz)) ** 2
            else:
                # no static friction somewhere: numerical slope (Richardson)
                cs0[i] = 2 * f[-2] / h - f[-1] / (2 * h)
            cases.append((float(fz), res["p"], res["vs_range"]))
        msgs = self._extrapolation(cases)
        cs = fy @ alpha / float(alpha @ alpha)
        half = np.array([self.tyre.half_length(f) for f in loads])
        mean_p = loads / (2 * half * self.tyre.width)
        peak_p = np.array([self.tyre.patch(f)[1].max() for f in loads])
        result = CorneringResult(
            law=self.label, params=dict(self.values), tyre=self.tyre.describe(), loads=loads,
            angles_deg=angles, fy=fy, cs=cs, cs_origin=cs0, half_length=half,
            mean_pressure=mean_p, peak_pressure=peak_p, warnings=msgs)
        return result

    def __repr__(self) -> str:
        return f"<BrushModel law={self.label!r} params={self.values}>"
