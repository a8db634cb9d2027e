"""Plausible speeds, wheel speeds and turn slips: the rules of this evaluator, since a
property file states no speed or yaw-rate limit.

A Magic Formula property file gives the ranges of load, slips, camber and pressure it was
measured over, but no speed range: MFeval evaluates a forward speed of 10^6 m/s, or a wheel
speed that contradicts the slip ratio, without a word.  The model's only speed terms are
the growth of the free radius, ``R_Omega = R0 (Q_RE0 + Q_V1 (Omega R0 / LONGVL)^2)``, and
the stiffening of the vertical spring, ``1 + Q_V2 (R0 / LONGVL) |Omega|`` (MF 6.x); friction
does not depend on speed (LMUV is not used), so the forces at any speed are those measured
at LONGVL.  The rule here (warned, the rows evaluated as given; see the tyre page of the
guide):

* **speed**: ``|V_x|``, and the circumferential speed ``|Omega| R0`` of the wheel, at most
  :func:`speed_bound`: the lower of :data:`SPEED_LIMIT` (150 m/s, 540 km/h: above the
  speed rating of every road tyre, 300+ km/h for a "Y" tyre) and, for a file with a
  centrifugal growth term Q_V1 > 0, the speed at which that term grows the free radius by
  :data:`GROWTH_SHARE` (5 % of R0: radial tyres grow by about 1-3 % at their rated
  speed, so the term is extrapolated past anything measured there; 149 m/s for the
  packaged MF 6.1 example).  Beyond it the loaded radius can exceed the unloaded radius
  by centimetres and grows without bound (R_l 930 km at 10^6 m/s and FNOMIN for the MF 6.1
  example);
* **wheel speed against slip ratio**: a wheel speed given (``omega``) must be the one the
  slip ratio describes, ``Omega R_e = (1 + kappa) V_x`` (the relation this evaluator uses
  when no wheel speed is given), within :data:`SLIP_TOLERANCE` ``max(|V_x|, VXLOW)``:
  0.1 in slip ratio, the distance from free rolling to about the force peak.  The forces
  take the slip ratio and the radii, C_z and the turn slip's camber spin take the wheel
  speed, so a contradiction between them gives outputs of two operating points;
* **turn slip**: the wheel's yaw rate ``|phit V_x|`` (the path curvature ``phit`` times the
  forward speed: ``phit = -psi_dot / V_c``, Pacejka 2012 eq. 4.75, MFeval's fifth input,
  with the contact centre's speed ``V_c`` taken as ``|V_x|``, as the speed rule takes it,
  so that a warning does not change with the slip angle) at most :data:`YAW_RATE_LIMIT`
  (2 pi rad/s, a turn a second: above a car's yaw rate when it spins out, a few rad/s,
  plus the quickest steering, about 1 rad/s at the road wheel).  A bound on the curvature
  alone would be wrong: a wheel pivoting on the spot (parking) has a path radius of 0,
  and the turn-slip model is made for it (its factors saturate as ``R0 |phit|`` grows,
  the spin moment tends to ``M_zpinf``); but a path radius of 1 um at 16.6 m/s (``phit``
  1e6 1/m) is a yaw rate of 1.7e7 rad/s, outputs of no tyre.  At a standing wheel
  (``V_x = 0``) any curvature is the pivot's limit and is not warned of;
* **loaded radius**: ``R_l`` above 0 (:mod:`~frictionlaws.tyre.mf.vertical`: a deflection
  that reaches the free radius gives NaN and a warning, not a radius of 0).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from .parameters import MFParameters

__all__ = ["SPEED_LIMIT", "GROWTH_SHARE", "SLIP_TOLERANCE", "YAW_RATE_LIMIT", "speed_bound",
           "check_speed", "check_wheel_speed", "check_turn_slip_rate", "SlipContradiction"]


class SlipContradiction(UserWarning):
    """A wheel speed given that contradicts the slip ratio given (outputs of two operating
    points).  A caller that gives the wheel speed alone, with a placeholder slip ratio (the
    transient's radii and relaxation lengths), ignores it."""


#: The highest plausible speed of a tyre [m/s] (540 km/h), whatever its file.
SPEED_LIMIT = 150.0
#: The largest plausible centrifugal growth of the free radius, as a share of R0.
GROWTH_SHARE = 0.05
#: The largest plausible difference between the wheel's circumferential speed given and
#: the one the slip ratio gives, as a share of max(|V_x|, VXLOW) [-].
SLIP_TOLERANCE = 0.1
#: The highest plausible yaw rate of a wheel about its vertical axis [rad/s] (a turn a
#: second), which bounds the turn slip: ``|phit| V_c`` (see the module notes).
YAW_RATE_LIMIT = 2 * np.pi


def speed_bound(p: MFParameters) -> tuple[float, str]:
    """The plausible speed bound of a file [m/s] and what sets it (see the module notes)."""
    s = p.structure
    q_v1, v0 = s.get("Q_V1", 0.0), s.get("LONGVL", 0.0)
    bound, why = SPEED_LIMIT, "above the speed rating of every road tyre"
    if q_v1 > 0 and v0 > 0:
        growth = v0 * float(np.sqrt(GROWTH_SHARE / q_v1))
        if growth < bound:
            bound = growth
            why = (f"where the file's free-radius growth Q_V1 (Omega R0 / LONGVL)^2 reaches "
                   f"{GROWTH_SHARE:.0%} of R0")
    return bound, why


def _name(p: MFParameters) -> str:
    return p.name or "Magic Formula"


def check_speed(p: MFParameters, vx: Any) -> None:
    """Warn where the forward speed ``|vx|`` [m/s] exceeds :func:`speed_bound`."""
    bound, why = speed_bound(p)
    fast = np.abs(vx) > bound
    if np.any(fast):
        warnings.warn(
            f"{_name(p)}: an implausible speed on {int(np.sum(fast))} row(s), |vx| up to "
            f"{float(np.max(np.abs(vx))):g} m/s, above {bound:.4g} m/s ({why}); evaluated as "
            "given (friction does not depend on speed in the Magic Formula; its radius and "
            "stiffness speed terms are extrapolated)", UserWarning,
            stacklevel=5)


def check_wheel_speed(p: MFParameters, vx: Any, kappa: Any, omega_given: Any,
                      omega: Any, re: Any) -> None:
    """Warn where the wheel's circumferential speed ``|omega| R0`` exceeds
    :func:`speed_bound` (rows whose ``vx`` does not, which :func:`check_speed` warns of),
    and where a wheel speed given contradicts the slip ratio ``kappa`` as evaluated.

    Parameters
    ----------
    p : MFParameters
        The tyre (its structure: UNLOADED_RADIUS, VXLOW).
    vx, kappa : numpy.ndarray
        The forward speed [m/s] and the slip ratio the forces take [-].
    omega_given : numpy.ndarray or None
        The wheel speed given [rad/s] (None: estimated from the slip ratio).
    omega, re : numpy.ndarray
        The wheel speed [rad/s] and effective rolling radius [m] evaluated.
    """
    bound, why = speed_bound(p)
    r0 = p.need("UNLOADED_RADIUS")
    rim = np.abs(omega) * r0
    fast = (rim > bound) & ~(np.abs(vx) > bound)
    if np.any(fast):
        growth = p.structure.get("Q_V1", 0.0) * np.square(np.max(rim[fast])
                                                          / p.need("LONGVL"))
        warnings.warn(
            f"{_name(p)}: an implausible wheel speed on {int(np.sum(fast))} row(s), its "
            f"circumferential speed |omega| R0 up to {float(np.max(rim[fast])):g} m/s, above "
            f"{bound:.4g} m/s ({why}); evaluated as given (the free radius grown by up to "
            f"{growth:.3g} R0)", UserWarning, stacklevel=5)
    if omega_given is None:
        return
    vxlow = p.structure.get("VXLOW", 0.0)
    off = np.abs(omega_given * re - (1 + kappa) * vx)
    allowed = SLIP_TOLERANCE * np.maximum(np.abs(vx), vxlow)
    bad = off > allowed
    if np.any(bad):
        worst = int(np.argmax(np.where(bad, off, -1.0)))
        warnings.warn(
            f"{_name(p)}: the wheel speed given contradicts the slip ratio on "
            f"{int(np.sum(bad))} row(s): omega R_e differs from the (1 + kappa) vx the slip "
            f"ratio gives by up to {float(off.flat[worst]):.4g} m/s where "
            f"{float(allowed.flat[worst]):.3g} m/s is plausible; the forces take kappa, the "
            "radii, C_z and the turn slip's camber spin take omega: outputs of two "
            "operating points", SlipContradiction, stacklevel=5)


def check_turn_slip_rate(p: MFParameters, vx: Any, phit: Any) -> None:
    """Warn where the turn slip ``phit`` [1/m] at the speed ``vx`` [m/s] (as given) is a
    yaw rate of the wheel ``|phit vx|`` above :data:`YAW_RATE_LIMIT` (see the module
    notes)."""
    with np.errstate(over="ignore", invalid="ignore"):
        rate = np.abs(phit * vx)
    fast = rate > YAW_RATE_LIMIT
    if not np.any(fast):
        return
    worst = int(np.argmax(np.where(fast, rate, -1.0)))
    radius = 1 / float(np.abs(np.broadcast_to(phit, fast.shape).flat[worst]))
    speed = float(np.abs(np.broadcast_to(vx, fast.shape).flat[worst]))
    warnings.warn(
        f"{_name(p)}: an implausible turn slip on {int(np.sum(fast))} row(s), the wheel's "
        f"yaw rate |phit vx| up to {float(rate.flat[worst]):.4g} rad/s (a path radius of "
        f"{radius:.3g} m at {speed:.4g} m/s), above {YAW_RATE_LIMIT:.3g} rad/s (a turn a "
        "second: beyond a spinning car's yaw rate and the quickest steering); evaluated as "
        "given (the turn-slip factors saturate towards those of a wheel pivoting on the "
        "spot)", UserWarning, stacklevel=5)
