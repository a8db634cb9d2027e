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
opposite sign for Fy; see :mod:`frictionlaws.tyre.mf.model`.)

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

from .model import (
    BrushModel,
)
from .result import (
    CorneringResult,
)
from .tyre import (
    BISECTION_STEPS,
    CONTACT_MODELS,
    DEFAULT_ANGLES_DEG,
    DEFAULT_C_PY,
    NEWTON_SWEEPS,
    ORIGIN_STEP,
    PRESSURE_SHAPES,
    SLIDING_SPEEDS,
    SWEEP_TOL,
    TIP_STEPS,
    TYRE_LIMITS,
    BrushTyre,
)

__all__ = ["BrushTyre", "BrushModel", "CorneringResult", "DEFAULT_ANGLES_DEG", "PRESSURE_SHAPES",
           "CONTACT_MODELS", "SLIDING_SPEEDS", "ORIGIN_STEP", "BISECTION_STEPS", "NEWTON_SWEEPS",
           "TIP_STEPS", "SWEEP_TOL", "DEFAULT_C_PY", "TYRE_LIMITS"]
