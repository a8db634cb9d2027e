"""The operating conditions of one steady-state evaluation, checked and broadcast once.

The inputs are listed in :data:`~frictionlaws.tyre.mf.inputs.INPUTS`.  :class:`Conditions`
checks them once (finite, loads positive, slip angles within +-90 deg; a turn slip only
with the turn-slip model and a file that has its coefficients), broadcasts them against
each other, warns where they leave the file's validity ranges and, with ``saturate=True``
or ``loads_above_fzmax="clamp"``, clamps them as MFeval's limit checks do, recording
which rows were clamped (:attr:`Conditions.clamped`).

**Limit checks.**  With ``limit_checks=True`` (the default; MFeval's useModes 1xx) the
curvature factors E are capped at 1 and, at speeds ``|V_x| <= VXLOW``, MF-Tyre's
low-speed reductions apply as MFeval 4.0 makes them: the slip ratio is taken times
``|V_x| / VXLOW``, the slip angle times ``(|V_x| + |V_sy|) / VXLOW`` where that sum
(``V_sy = V_x tan(alpha)``) is below VXLOW, and the curves' shifts, the slip-induced side
force, the trail and the residual torque times ``(1 - cos(pi V_x / VXLOW)) / 2``; the
turn slip is taken times ``cos(alpha)`` (MFeval's empirical factor), times ``|V_x| /
VXLOW`` below VXLOW and with the sign of V_x.  ``saturate=True`` adds the clamping (MFeval's
useModes 1xx exactly).  ``limit_checks=False`` (MFeval's useModes 2xx) does none of this
and reduces the load below FZMIN in M_x (squared) and M_y (linearly), as MFeval always
does; the default (limit checks, no clamping) keeps M_x and M_y at the load given.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from ...base.errors import ExtrapolationWarning, InputError, broadcast_shape
from .parameters import MFParameters, check_pressure, real_array
from .plausibility import check_speed, check_turn_slip_rate
from .turn_slip import check_turn_slip

__all__ = ["Conditions"]


class Conditions:
    """The broadcast, checked (and optionally saturated) inputs of one evaluation.

    Parameters
    ----------
    p : MFParameters
        The tyre.
    kappa, alpha, fz, gamma : array-like
        Slip ratio [-], slip angle [rad], vertical load [N], camber [rad].
    pressure : array-like or None
        Inflation pressure [Pa] (None: the tyre's).
    vx : array-like or None
        Forward speed [m/s] (None: the file's LONGVL; negative: backwards).
    saturate : bool
        Clamp the inputs at the file's limits as MFeval does.
    phit : array-like
        Turn slip, the path curvature [1/m]; not 0 only with ``turn_slip``.
    omega : array-like or None
        Wheel angular speed [rad/s] (None: from the slip ratio).
    turn_slip : bool
        Evaluate MF-Tyre's turn-slip model.
    limit_checks : bool
        MFeval's limit checks (see the module notes); ``saturate`` needs them.

    Attributes
    ----------
    kappa, alpha, gamma, fz, vx, phit : numpy.ndarray
        The inputs as evaluated, broadcast to :attr:`shape` (``fz`` clamped at FZMAX
        where the model clamps; the slips and turn slip after the low-speed reductions).
    kappa_in, alpha_in, fz_in, phit_in : numpy.ndarray
        The slips, load and turn slip as given.
    omega : numpy.ndarray or None
        The wheel speed given.
    fade : numpy.ndarray
        The low-speed factor of the shifts, trail and residual torque (1 above VXLOW).
    fz_mz, fz_mx, fz_my : numpy.ndarray
        The loads the aligning, overturning and rolling moments take (MFeval's
        reductions below FZMIN with ``saturate`` or without limit checks).
    dpi : float or numpy.ndarray
        The relative pressure increment.
    clamped : dict of str to numpy.ndarray
        Input name -> the rows (boolean, :attr:`shape`) where it was clamped; only the
        inputs clamped on some row.
    """

    def __init__(self, p: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any,
                 pressure: Any, vx: Any, saturate: bool, phit: Any = 0.0, omega: Any = None,
                 turn_slip: bool = False, limit_checks: bool = True) -> None:
        given = self._checked(p, kappa, alpha, fz, gamma, pressure, vx, phit, omega,
                              saturate, turn_slip, limit_checks)
        shape = broadcast_shape({k: v for k, v in given.items() if v is not None}, p.source)
        self.shape = shape
        self.turn_slip, self.limit_checks = turn_slip, limit_checks
        self.clamped: dict[str, np.ndarray] = {}
        self.kappa_in = np.broadcast_to(given["kappa"], shape)
        self.alpha_in = np.broadcast_to(given["alpha"], shape)
        self.fz_in = np.broadcast_to(given["fz"], shape)
        self.vx = np.broadcast_to(given["vx"], shape)
        self.phit_in = np.broadcast_to(given["phit"], shape)
        self.omega = None if omega is None else np.broadcast_to(given["omega"], shape)
        check_speed(p, self.vx)
        if turn_slip:
            check_turn_slip_rate(p, self.vx, self.phit_in)
        k, a = self._low_speed(p)
        clipped = self._limit(p, {"kappa": k, "alpha": a, "gamma": given["gamma"],
                                  "pressure": given["pressure"]}, saturate)
        self.kappa = np.broadcast_to(clipped["kappa"], shape)
        self.alpha = np.broadcast_to(clipped["alpha"], shape)
        if np.any(np.abs(self.alpha) >= np.pi / 2):
            raise InputError("slip angles must lie strictly between -90 and 90 degrees")
        self.gamma = np.broadcast_to(clipped["gamma"], shape)
        self.pressure = clipped["pressure"]
        self._loads(p, saturate)
        self.dpi = p.dpi(None if self.pressure is None else self.pressure)

    @staticmethod
    def _checked(p: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any,
                 pressure: Any, vx: Any, phit: Any, omega: Any, saturate: bool,
                 turn_slip: bool, limit_checks: bool) -> dict[str, Any]:
        """The inputs as float arrays, each checked; the options checked together."""
        for name, flag in (("saturate", saturate), ("turn_slip", turn_slip),
                           ("limit_checks", limit_checks)):
            if not isinstance(flag, (bool, np.bool_)):
                raise InputError(f"{name} must be True or False, not {flag!r:.40}")
        if saturate and not limit_checks:
            raise InputError("saturate=True clamps the inputs as MFeval's limit checks do: "
                             "it needs limit_checks=True")
        out = {"kappa": p.check("kappa", kappa), "alpha": p.check("alpha", alpha),
               "fz": p.check("fz", fz, positive=True), "gamma": p.check("gamma", gamma),
               "pressure": real_array("pressure", p.pressure if pressure is None else pressure)
               if (pressure is not None or p.pressure is not None) else None,
               "vx": p.check("vx", p.need("LONGVL") if vx is None else vx),
               "phit": p.check("phit", phit),
               "omega": None if omega is None else p.check("omega", omega)}
        if (pressure is not None and p.nominal_pressure is not None
                and not (saturate and "pressure" in p.limits)):
            check_pressure(out["pressure"])  # no tyre runs at it: refused before any
            # warning, where the pressure terms would take it (saturate clamps it to the
            # file's range first, as MFeval does)
        if not turn_slip and np.any(out["phit"] != 0):
            raise InputError("a turn slip phit other than 0 needs the turn-slip model "
                             "(turn_slip=True, MFeval's useMode x2)")
        if turn_slip:
            check_turn_slip(p)
        vxlow = p.structure.get("VXLOW", 0.0)
        if vxlow <= 0 and (limit_checks or turn_slip) and np.any(out["vx"] == 0):
            raise InputError(f"a standing wheel (vx = 0) needs the file's VXLOW > 0 (VXLOW = "
                             f"{vxlow:g} m/s): the low-speed reductions and the turn slip's "
                             "contact speed are taken relative to it", file=p.source)
        return out

    def _low_speed(self, p: MFParameters) -> tuple[Any, Any]:
        """The slips (and turn slip) after MFeval's low-speed reductions, and the factor
        of the shifts, trail and residual torque (see the module notes)."""
        v, a, vxlow = self.vx, self.alpha_in, p.structure.get("VXLOW", 0.0)
        low = np.abs(v) <= vxlow
        phit = self.phit_in
        if not self.limit_checks:
            self.fade, self.phit = np.ones(self.shape), phit
            _warn_standing(p, v)
            if low.any():
                warnings.warn(f"{p.name or 'Magic Formula'}: {int(low.sum())} row(s) at a speed "
                              f"|vx| <= VXLOW = {vxlow:g} m/s evaluated without the low-speed "
                              "reductions (limit_checks=False): the slips as given",
                              UserWarning, stacklevel=4)
            return self.kappa_in, a
        scale = max(vxlow, 1e-300)
        linear = np.where(low, np.abs(v) / scale, 1.0)
        self.fade = np.where(low, 0.5 * (1 - np.cos(np.pi * v / scale)), 1.0)
        contact = np.abs(v) + np.abs(np.tan(a) * v)
        alpha = np.where(contact < vxlow, a * contact / scale, a)
        phit = phit * np.cos(a) * linear
        self.phit = np.where(v < 0, -phit, phit)
        if low.any():
            warnings.warn(f"{p.name or 'Magic Formula'}: {int(low.sum())} row(s) at a speed "
                          f"|vx| <= VXLOW = {vxlow:g} m/s: MF-Tyre's low-speed reductions "
                          "applied (the slips taken towards 0 with the speed, the shifts, "
                          "trail and residual torque faded), as MFeval's limit checks do",
                          UserWarning, stacklevel=4)
        return self.kappa_in * linear, alpha

    def _limit(self, p: MFParameters, given: dict[str, Any], saturate: bool
               ) -> dict[str, Any]:
        """Each input clamped to the file's range (``saturate``) or warned about outside
        it (:meth:`~frictionlaws.tyre.mf.parameters.MFParameters.limit`)."""
        clipped: dict[str, Any] = {}
        for name, x in given.items():
            if x is None:
                clipped[name] = None
                continue
            clipped[name], rows = p.limit(name, x, saturate)
            self._record(name, rows)
        return clipped

    def _record(self, name: str, rows: Any) -> None:
        rows = np.broadcast_to(rows, self.shape)
        if rows.any():
            self.clamped[name] = rows | self.clamped.get(name, False)

    def _loads(self, p: MFParameters, saturate: bool) -> None:
        """The loads of the forces and moments: clamped at FZMAX (``saturate`` or
        ``loads_above_fzmax="clamp"``), else warned about; MFeval's reductions below
        FZMIN with ``saturate`` or without limit checks."""
        fzmin = p.limits.get("fz", (0.0, np.inf))[0]
        self.fz, above = p.limit_loads(self.fz_in, saturate)
        self._record("fz", above)
        self.fz_mz = np.maximum(self.fz, fzmin) if saturate else self.fz
        # MFeval's reduction of the load below FZMIN in M_x (squared) and M_y (linear)
        reduce = saturate or not self.limit_checks
        low = reduce & (self.fz_in < fzmin) if fzmin > 0 else np.zeros(self.shape, bool)
        if np.any(low):
            self._record("fz", low)
            why = "saturate=True" if saturate else "limit_checks=False"
            warnings.warn(
                f"{p.name or 'Magic Formula'}: fz of {int(np.sum(low))} row(s) lies below "
                f"the property file's FZMIN {fzmin:g} N: M_x and M_y reduced as MFeval does "
                f"({why})" + (", M_z evaluated at FZMIN" if saturate else "")
                + ", the forces at the load given", ExtrapolationWarning, stacklevel=4)
        ratio = np.where(low, self.fz_in / max(fzmin, 1e-300), 1.0)
        self.fz_mx = np.where(low, self.fz * ratio**2, self.fz)
        self.fz_my = np.where(low, self.fz_in * ratio, self.fz_in)


def _warn_standing(p: MFParameters, vx: Any) -> None:
    """Warn of rows at a standing wheel without the limit checks, where the outputs jump."""
    standing = vx == 0
    if np.any(standing):
        warnings.warn(f"{p.name or 'Magic Formula'}: {int(standing.sum())} row(s) at a standing "
                      "wheel (vx = 0 exactly) without the limit checks: the running direction "
                      "sgn(vx) is 0 there, so the lateral slip tan(alpha) sgn(vx) and the turn "
                      "slip's side-force shift are 0 (as in MFeval 4.0) and the outputs jump "
                      "from those at any speed however small (vx = +-1e-9 m/s); the limit "
                      "checks' low-speed reductions take the slips to 0 continuously instead",
                      UserWarning, stacklevel=5)
