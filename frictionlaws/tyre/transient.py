"""The tyre's transient response: slip relaxing over the relaxation lengths.

A tyre does not build its force the instant the slip changes: the carcass deflects first,
and the contact patch has to roll a distance of the order of the relaxation length
sigma before the force settles.  MF-Tyre's transient model (Pacejka, *Tire and Vehicle
Dynamics*, 3rd ed. 2012, chapter 8: the single-contact-point model with first-order
relaxation) lags the slips by a first-order filter in the travelled distance
and evaluates the steady-state Magic Formula at the lagged slips::

    sigma_kappa d(kappa')/dt + |V_x| kappa' = |V_x| kappa
    sigma_alpha d(alpha')/dt + |V_x| alpha' = |V_x| alpha

    F_x(t) = F_x(kappa', alpha', F_z, gamma), F_y(t) = F_y(...), M_z(t) = M_z(...)

with the relaxation lengths sigma_kappa, sigma_alpha the ones :meth:`MagicFormula.steady_state
<frictionlaws.tyre.MagicFormula.steady_state>` gives (``sigmax``, ``sigmay``: MF 6.x
K / C, MF 5.2 from PTX/PTY), evaluated at each instant's load, camber and pressure.  Per
unit of distance travelled s = integral |V_x| dt the lag is ``d(kappa')/ds = (kappa -
kappa') / sigma_kappa``: after a step in the slip angle the slip (and, in the linear range,
the side force) reaches 1 - 1/e = 63.2 % of its new steady value after one relaxation
length of travel.  At standstill (V_x = 0) the lagged slips hold their values.

**Integration.** The inputs are taken as piecewise linear in time between the samples
given (two samples at the same time make a jump).  Over a step the lag rolls
``x = ds / sigma`` relaxation lengths, ds the distance rolled (exact for the
piecewise-linear speed) and 1 / sigma the mean of its values at the step's ends; the
update is the exact solution for an input changing linearly over the step (a
first-order hold)::

    y1 = u1 + (y0 - u0) exp(-x) - (u1 - u0) (1 - exp(-x)) / x

so a step, a ramp or a sampled sine at constant speed and load are integrated without
error beyond rounding whatever the step size, and a held input at any speed.  Where the
speed or the relaxation length changes within a step while the input changes too, the
update is second-order accurate in the step (against scipy's ``solve_ivp`` at rtol
1e-11, for the speed rising from 8 to 32 m/s in 0.3 s, the load +-40 % and a 1-8 Hz
chirp of the slip angle: 1.7e-6 of the peak slip angle at 0.25 ms steps, 4.4e-7 at
0.125 ms).

A wheel speed ``omega`` may drive the slip ratio instead: then ``sigma_kappa d(kappa')/dt
+ |V_x| kappa' = R_e Omega - V_x``, the slip speed (:func:`relax_source`), which holds at
standstill too, where kappa' integrates the slip speed over sigma_kappa (a carcass winding
up).  Turn slip ``phit`` and the options of the steady state pass to it.

What is not modelled: the carcass mass and damping, the low-speed damping MF-Tyre adds
near standstill (at ``|V_x| <= VXLOW`` the forces fade with the steady state's low-speed
reductions of the lagged slips), the separate relaxation of the pneumatic trail and the
turn-slip (spin) states of the contact-mass model; the aligning moment is the steady-state
one at the lagged slips.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field, fields
from typing import Any

import numpy as np

from ..base.errors import InputError, broadcast_shape
from .mf.model import MagicFormula
from .mf.notices import collected
from .mf.outputs import evaluate
from .mf.parameters import real_array
from .mf.plausibility import SlipContradiction

__all__ = ["TransientSlip", "transient_slip", "relax", "relax_source", "travelled",
           "TRANSIENT_OUTPUTS"]

#: The fields of :class:`TransientSlip`: name -> (unit, meaning).
TRANSIENT_OUTPUTS: dict[str, tuple[str, str]] = {
    "t": ("s", "time"),
    "distance": ("m", "distance rolled, the integral of |V_x| over time"),
    "kappa": ("1", "slip ratio given (or of the wheel speed given)"),
    "alpha": ("rad", "slip angle given"),
    "kappa_t": ("1", "transient (lagged) slip ratio kappa'"),
    "alpha_t": ("rad", "transient (lagged) slip angle alpha'"),
    "sigma_x": ("m", "longitudinal relaxation length"),
    "sigma_y": ("m", "lateral relaxation length"),
    "Fx": ("N", "longitudinal force at the lagged slips"),
    "Fy": ("N", "lateral force at the lagged slips"),
    "Mz": ("N m", "aligning moment at the lagged slips"),
    "Fx_steady": ("N", "steady-state longitudinal force at the slips given"),
    "Fy_steady": ("N", "steady-state lateral force at the slips given"),
    "Mz_steady": ("N m", "steady-state aligning moment at the slips given"),
}


@dataclass(frozen=True)
class TransientSlip:
    """Time histories of the transient response (SI units, see :data:`TRANSIENT_OUTPUTS`).

    Attributes
    ----------
    t, distance, kappa, alpha, kappa_t, alpha_t, sigma_x, sigma_y : numpy.ndarray
        Time [s], distance rolled [m], the slips given, the lagged slips and the
        relaxation lengths [m], one value per sample.
    Fx, Fy, Mz : numpy.ndarray
        Forces [N] and aligning moment [N m] at the lagged slips.
    Fx_steady, Fy_steady, Mz_steady : numpy.ndarray
        The steady-state values at the slips given (what the tyre tends to).
    warnings : list of str
        The warnings of the evaluation, once each (also issued as Python warnings, once).
    """

    t: np.ndarray
    distance: np.ndarray
    kappa: np.ndarray
    alpha: np.ndarray
    kappa_t: np.ndarray
    alpha_t: np.ndarray
    sigma_x: np.ndarray
    sigma_y: np.ndarray
    Fx: np.ndarray
    Fy: np.ndarray
    Mz: np.ndarray
    Fx_steady: np.ndarray
    Fy_steady: np.ndarray
    Mz_steady: np.ndarray
    warnings: list[str] = field(default_factory=list)

    def as_dict(self) -> dict[str, np.ndarray]:
        """The histories by name (the keys of :data:`TRANSIENT_OUTPUTS`).

        Returns
        -------
        dict of str to numpy.ndarray
        """
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name != "warnings"}


def _times(t: Any) -> np.ndarray:
    """The sample times: one dimension, finite, at least two, never decreasing."""
    t = real_array("t", t)
    if t.ndim != 1 or t.size < 2:
        raise InputError(f"t must be a one-dimensional array of at least two sample times "
                         f"[s], got shape {t.shape}", option="t")
    if not np.isfinite(t).all():
        i = int(np.flatnonzero(~np.isfinite(t))[0])
        raise InputError(f"t must be finite; t[{i}] = {t[i]}", option="t")
    back = np.flatnonzero(np.diff(t) < 0)
    if back.size:
        i = int(back[0])
        raise InputError(f"t must not decrease; t[{i + 1}] = {t[i + 1]:g} s follows "
                         f"t[{i}] = {t[i]:g} s (equal times make a jump)", option="t")
    return t


def _histories(t: np.ndarray, named: dict[str, Any]) -> dict[str, np.ndarray]:
    """Every input as one value per sample: scalars spread, arrays of the length of t."""
    named = {k: real_array(k, v) for k, v in named.items() if v is not None}
    shape = broadcast_shape({"t": t, **named}, subject="transient_slip")
    if shape != t.shape:
        raise InputError(f"transient_slip: the inputs must be scalars or arrays of the "
                         f"length of t ({t.size}); they broadcast to {shape}")
    out = {}
    for name, value in named.items():
        x = np.broadcast_to(value, shape)
        if not np.isfinite(x).all():
            i = int(np.flatnonzero(~np.isfinite(x))[0])
            raise InputError(f"{name} must be finite; {name}[{i}] = {x[i]}", option=name)
        out[name] = x
    return out


def travelled(t: Any, vx: Any) -> np.ndarray:
    """Distance rolled, the integral of |V_x| over time for V_x linear between samples.

    Parameters
    ----------
    t : array-like
        Sample times [s], never decreasing.
    vx : array-like
        Forward speed [m/s] at the samples.

    Returns
    -------
    numpy.ndarray
        Distance [m] from the first sample, exact for the piecewise-linear speed
        (a step where the speed changes sign rolls (v0^2 + v1^2) h / (2 (|v0| + |v1|))).
    """
    t = np.asarray(t, dtype=float)
    v0, v1 = np.asarray(vx, dtype=float)[:-1], np.asarray(vx, dtype=float)[1:]
    h = np.diff(t)
    same = v0 * v1 >= 0
    denom = np.where(same, 1.0, np.abs(v0) + np.abs(v1))
    step = np.where(same, 0.5 * (np.abs(v0) + np.abs(v1)), 0.5 * (v0**2 + v1**2) / denom) * h
    return np.concatenate([[0.0], np.cumsum(step)])


def relax(u: Any, lag: Any, y0: float | None = None) -> np.ndarray:
    """The first-order lag ``dy/ds = (u - y) / sigma`` of an input linear between samples.

    Parameters
    ----------
    u : array-like
        The input at the samples.
    lag : array-like
        Per step between samples, the relaxation lengths rolled: the integral of
        ``|V_x| / sigma`` over the step, >= 0 (0: no travel, the state holds; one value
        fewer than ``u``).
    y0 : float, optional
        The state at the first sample (default: the input there, i.e. settled).

    Returns
    -------
    numpy.ndarray
        The lagged input y at the samples: exact for an input linear in the lag
        variable over each step (in time at constant speed and relaxation length), and
        for an input held constant over a step at any speed.
    """
    u = np.asarray(u, dtype=float)
    x = np.asarray(lag, dtype=float)
    decay = np.exp(-x)
    # (1 - exp(-x)) / x, -> 1 as x -> 0 (no travel: the state holds)
    gain = np.where(x > 1e-300, -np.expm1(-x) / np.where(x > 1e-300, x, 1.0), 1.0)
    du = np.diff(u)
    y = np.empty_like(u)
    y[0] = u[0] if y0 is None else y0
    for k in range(x.size):
        if x[k] == 0:  # no travel: the state holds exactly
            y[k + 1] = y[k]
        else:
            y[k + 1] = u[k + 1] + (y[k] - u[k]) * decay[k] - du[k] * gain[k]
    return y


def _gains(x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(1 - exp(-x)) / x and (x - 1 + exp(-x)) / x^2, -> 1 and 1/2 as x -> 0."""
    small = x < 1e-2
    safe = np.where(small, 1.0, x)
    g1 = np.where(small, 1 - x / 2 + x**2 / 6 - x**3 / 24, -np.expm1(-safe) / safe)
    g2 = np.where(small, 0.5 - x / 6 + x**2 / 24 - x**3 / 120,
                  (safe + np.expm1(-safe)) / safe**2)
    return g1, g2


def relax_source(w: Any, lag: Any, gain: Any, y0: float) -> np.ndarray:
    """The lag ``sigma dy/dt + |V_x| y = w`` of a source ``w`` linear between samples.

    The form of the slip ratio driven by the wheel speed (``w = R_e Omega - V_x``, the
    slip speed), which holds at standstill too: there the state integrates ``w / sigma``.

    Parameters
    ----------
    w : array-like
        The source at the samples [m/s].
    lag : array-like
        Per step, the relaxation lengths rolled (the integral of ``|V_x| / sigma``).
    gain : array-like
        Per step, the integral of ``1 / sigma`` over time [s/m].
    y0 : float
        The state at the first sample.

    Returns
    -------
    numpy.ndarray
        The state at the samples: exact for a source linear over each step at constant
        speed and relaxation length (and the same as :func:`relax` of ``w / |V_x|``).
    """
    w = np.asarray(w, dtype=float)
    x = np.asarray(lag, dtype=float)
    c = np.asarray(gain, dtype=float)
    decay = np.exp(-x)
    g1, g2 = _gains(x)
    dw = np.diff(w)
    y = np.empty_like(w)
    y[0] = y0
    for k in range(x.size):
        y[k + 1] = y[k] * decay[k] + c[k] * (w[k] * g1[k] + dw[k] * g2[k])
    return y


def _initial(initial: Any) -> tuple[float | None, float | None]:
    """The lagged slips (kappa', alpha') at the first sample, or (None, None): settled."""
    if initial is None:
        return None, None
    pair = real_array("initial", initial)
    if pair.shape != (2,) or not np.isfinite(pair).all():
        raise InputError("initial must be the two lagged slips (kappa' [-], alpha' [rad]) at "
                         f"the first sample, finite; got {str(initial)[:40]!r}",
                         option="initial")
    return float(pair[0]), float(pair[1])


def _step_mean(x: np.ndarray) -> np.ndarray:
    """The mean of the values at the two ends of each step."""
    return 0.5 * (x[:-1] + x[1:])


def _relaxation_lengths(mf: MagicFormula, rest: dict[str, Any]
                        ) -> tuple[np.ndarray, np.ndarray]:
    """sigma_x, sigma_y [m] per sample, refused where one is not positive."""
    sx, sy = rest["sigmax"], rest["sigmay"]
    for name, s in (("sigmax", sx), ("sigmay", sy)):
        if not (np.isfinite(s) & (s > 0)).all():
            i = int(np.flatnonzero(~(np.isfinite(s) & (s > 0)))[0])
            raise InputError(f"the relaxation length {name} = {s[i]:g} m at sample {i} is not "
                             "positive: the transient lag needs one", file=mf.source)
    return sx, sy


def _wheel_speed_slip(t: np.ndarray, h: dict[str, np.ndarray], re: np.ndarray,
                      sx: np.ndarray, lag_x: np.ndarray, k0: float | None, name: str
                      ) -> tuple[np.ndarray, np.ndarray]:
    """(kappa of the wheel speed, NaN at standstill; kappa') from the slip speed."""
    speed, slip_speed = np.abs(h["vx"]), re * h["omega"] - h["vx"]
    moving = speed > 0
    slip = np.where(moving, slip_speed / np.where(moving, speed, 1.0), np.nan)
    if not moving.all():
        warnings.warn(
            f"{name}: {int(np.sum(~moving))} of {moving.size} sample(s) at a standing wheel (V_x = "
            "0): the slip ratio of the wheel speed is not defined there, so kappa and the "
            "steady-state Fx, Fy and Mz are NaN; the lagged ones are computed (the slip "
            "speed R_e omega - V_x drives them)", UserWarning, stacklevel=4)
    start = k0 if k0 is not None else (slip[0] if moving[0] else 0.0)
    return slip, relax_source(slip_speed, lag_x, np.diff(t) * _step_mean(1 / sx), start)


def transient_slip(mf: MagicFormula, t: Any, vx: Any, fz: Any, *, kappa: Any = None,
                   alpha: Any = 0.0, gamma: Any = 0.0, phit: Any = 0.0, omega: Any = None,
                   pressure: Any = None, turn_slip: bool = False, limit_checks: bool = True,
                   initial: tuple[float, float] | None = None) -> TransientSlip:
    """Forces and aligning moment of a tyre whose slips relax over the relaxation lengths.

    Parameters
    ----------
    mf : MagicFormula
        The tyre, read with the structure its steady-state outputs need.
    t : array-like
        Sample times [s], never decreasing (two equal times make a jump of the inputs).
    vx : float or array-like
        Forward speed [m/s] per sample (the lag runs on |V_x|).
    fz : float or array-like
        Vertical load [N] per sample.
    kappa : float or array-like, optional
        Slip ratio [-] per sample (default 0); or give ``omega``.
    alpha, gamma : float or array-like
        Slip angle [rad] and camber [rad] per sample.
    phit : float or array-like
        Turn slip [1/m] per sample, evaluated in the steady state (with ``turn_slip``).
    omega : float or array-like, optional
        Wheel angular speed [rad/s] per sample instead of ``kappa``: the slip ratio then
        relaxes towards the slip speed, ``sigma_kappa d(kappa')/dt + |V_x| kappa' = R_e
        Omega - V_x`` (R_e at that wheel speed), which holds at standstill too.
    pressure : float or array-like, optional
        Inflation pressure [Pa] (default: the file's).
    turn_slip, limit_checks : bool
        The options of :meth:`MagicFormula.steady_state
        <frictionlaws.tyre.MagicFormula.steady_state>` (at ``|V_x| <= VXLOW`` the limit
        checks' low-speed reductions apply to the lagged slips as to steady ones).
    initial : (float, float), optional
        The lagged slips (kappa', alpha') at the first sample; default: settled at the
        slips given there (with ``omega`` at a standing wheel: 0).

    Returns
    -------
    TransientSlip
        The histories (see :data:`TRANSIENT_OUTPUTS`); with ``omega``, ``kappa`` is the
        slip ratio of the wheel speed (NaN at a standing wheel, where the steady-state
        values are NaN too).
    """
    if kappa is not None and omega is not None:
        raise InputError("transient_slip: give the slip ratio kappa or the wheel speed "
                         "omega, not both")
    with collected(mf.not_applied) as warned:  # the three evaluations: each warning once
        return _transient(mf, t, vx, fz, kappa, alpha, gamma, phit, omega, pressure,
                          turn_slip, limit_checks, initial, warned)


def _transient(mf: MagicFormula, t: Any, vx: Any, fz: Any, kappa: Any, alpha: Any,
               gamma: Any, phit: Any, omega: Any, pressure: Any, turn_slip: bool,
               limit_checks: bool, initial: Any, warned: list[str]) -> TransientSlip:
    """:func:`transient_slip`, its warnings filled into ``warned`` when it returns."""
    t = _times(t)
    h = _histories(t, {"vx": vx, "fz": fz, "kappa": 0.0 if kappa is None else kappa,
                       "alpha": alpha, "gamma": gamma, "phit": phit, "omega": omega,
                       "pressure": pressure})
    opts: dict[str, Any] = {"pressure": h.get("pressure"), "vx": h["vx"], "phit": h["phit"],
                            "turn_slip": turn_slip, "limit_checks": limit_checks}
    forces = ("Fx", "Fy", "Mz")
    with warnings.catch_warnings():  # the slip ratio 0 here stands for none (omega's)
        warnings.simplefilter("ignore", SlipContradiction)
        rest = evaluate(mf, 0.0, 0.0, h["fz"], h["gamma"], names=("Re", "sigmax", "sigmay"),
                        omega=h.get("omega"), **opts).outputs
    sx, sy = _relaxation_lengths(mf, rest)
    dist = travelled(t, h["vx"])
    lag_x = np.diff(dist) * _step_mean(1 / sx)
    k0, a0 = _initial(initial)
    if omega is None:
        slip = np.array(h["kappa"])
        kt = relax(slip, lag_x, k0)
    else:
        slip, kt = _wheel_speed_slip(t, h, rest["Re"], sx, lag_x, k0, mf.name)
    at = relax(h["alpha"], np.diff(dist) * _step_mean(1 / sy), a0)
    lagged = evaluate(mf, kt, at, h["fz"], h["gamma"], names=forces, **opts).outputs
    known = np.isfinite(slip)
    steady = evaluate(mf, np.where(known, slip, 0.0), h["alpha"], h["fz"], h["gamma"],
                      names=forces, **opts).outputs
    return TransientSlip(t=t, distance=dist, kappa=slip, alpha=np.array(h["alpha"]),
                         kappa_t=kt, alpha_t=at, sigma_x=sx, sigma_y=sy, Fx=lagged["Fx"],
                         Fy=lagged["Fy"], Mz=lagged["Mz"],
                         **{f"{n}_steady": np.where(known, steady[n], np.nan)
                            for n in forces}, warnings=warned)
