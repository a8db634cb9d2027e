"""Steady-state outputs of the Magic Formula beyond the forces: moments, radii, stiffnesses.

:func:`steady_state` evaluates, for one :class:`~frictionlaws.tyre.magic_formula.MagicFormula`
and per row of load, slips, camber, pressure and speed, the outputs MFeval's
``fullSteadyState`` gives for steady rolling without turn slip: the combined-slip
forces, the aligning moment M_z with its pneumatic trail t and residual torque
M_zr, the pure-slip aligning moment M_z0, the overturning moment M_x, the rolling
resistance moment M_y, the effective rolling radius R_e, the loaded radius R_l and
deflection rho, the vertical stiffness, the contact patch length 2a and width 2b,
the longitudinal and lateral stiffnesses C_x, C_y and relaxation lengths sigma_x,
sigma_y, the slip stiffnesses K_xk and K_ya and the peak friction coefficients.

Equations
---------
Pacejka, *Tire and Vehicle Dynamics* (3rd ed. 2012), section 4.3.2, eqs. (4.E31)-(4.E49)
(pure-slip M_z0) and (4.E68)-(4.E78) (combined M_z, M_x, M_y), with the MF 6.1/6.2
forms of Besselink, Schmeitz and Pacejka (Vehicle System Dynamics 48 sup. 1, 2010,
appendix) where the book and the MF 6.1 property-file coefficients differ, as MFeval
4.0 evaluates them:

* pneumatic trail: ``B_t = (QBZ1 + QBZ2 dfz + QBZ3 dfz^2)(1 + QBZ4 gamma + QBZ5 |gamma|)
  LKY / LMUY``, ``C_t = QCZ1``, ``D_t = F_z (R_0 / F'_z0)(QDZ1 + QDZ2 dfz)(1 - PPZ1 dpi)
  (1 + QDZ3 gamma + QDZ4 gamma^2) LTR``, ``E_t = (QEZ1 + QEZ2 dfz + QEZ3 dfz^2)(1 +
  (QEZ4 + QEZ5 gamma*)(2/pi) arctan(B_t C_t alpha_t))`` (<= 1), ``alpha_t = alpha* + S_Ht``,
  ``S_Ht = QHZ1 + QHZ2 dfz + (QHZ3 + QHZ4 dfz) gamma*``;
* residual torque: ``B_r = QBZ9 LKY / LMUY + QBZ10 B_y C_y``, ``C_r = 1``,
  ``D_r = F_z R_0 ((QDZ6 + QDZ7 dfz) LRES + ((QDZ8 + QDZ9 dfz)(1 + PPZ2 dpi) +
  (QDZ10 + QDZ11 dfz)|gamma*|) gamma* LKZC) LMUY cos(alpha*)``,
  ``alpha_r = alpha* + S_Hy + S_Vy / K_ya'``;
* pure slip ``M_z0 = -t_0 F'_y0 + D_r cos(arctan(B_r alpha_r)) cos(alpha')`` with
  ``F'_y0`` the lateral force at zero camber; combined slip
  ``M_z = -t F'_y + M_zr + s F_x``, ``F'_y = G_yk F'_y0``, the equivalent slip angles
  ``alpha_eq = arctan(sqrt(tan^2 alpha + (K_xk / K_ya')^2 kappa^2)) sgn(alpha)`` in t
  and M_zr, ``s = R_0 (SSZ1 + SSZ2 F_y / F_z0 + (SSZ3 + SSZ4 dfz) gamma) LS``;
  MF 5.2: ``M_z = -t (F_y - S_Vyk) + M_zr + s F_x``;
* ``M_x`` as the TNO MF-Tyre equation manual (QSX1-QSX14, PPMX1); ``M_y`` as eq. (A48)
  of the 2010 paper (MF 6.x) or the MF-Tyre 5.2 manual; radii, deflection and vertical
  stiffness as eqs. (1)-(8) of the paper (MF 6.2: the loaded radius solved from the
  load with the camber and lateral-force terms); contact patch eqs. (9)-(10) (MF 5.2:
  ``Q_A1``, ``Q_A2``); ``C_x``, ``C_y`` and ``sigma = K / C`` eqs. (17)-(19) (MF 5.2:
  PTX, PTY).

**Camber convention.** The forces and the M_z terms the book writes with gamma*
(S_Ht, E_t, D_r) use gamma* (sin(gamma), or gamma with ``slip_angle = "alpha"``);
B_t, D_t, s, M_x and M_y use the camber angle gamma itself, as the MF 6.1 property-file
coefficients (QBZ4, QBZ5, QDZ3) are defined in the 2010 paper and as MFeval evaluates
them (the book's eqs. 4.E40 and 4.E43 write |gamma*| there).  The two differ by
gamma^3/6: 4.6e-4 relative at 3 degrees.

**Where MFeval 4.0 departs from the published equations** the option ``equations`` of
:class:`~frictionlaws.tyre.magic_formula.MagicFormula` chooses; its default ``mfeval``
follows MFeval (whose authors matched these forms to TNO's evaluator), ``published`` the
book and the MF-Tyre 5.2 manual: the combined-slip trail t times LFZO (MFeval) or not;
MF 5.2's ``F'_y = F_y - S_Vyk`` with S_Vyk from mu_y at zero camber (MFeval) or at the
camber; and, in the forces, gamma (MFeval) or gamma* in PDX3's term and, for MF 5.2 with
alpha* = tan(alpha), gamma* = sin(gamma) (MFeval) or gamma in the lateral and
combined-slip camber terms.  At 3 degrees the MF 5.2 example's M_z differs between the two
by up to 5e-4 of its peak moment, everything else by less than 1e-4.

**Checked** against MFeval 4.0 on the three packaged examples in both slip-angle
conventions (useModes 111 and 121, ``saturate=True``), loads from near FZMIN to beyond
FZMAX, camber -3/0/3 degrees, three pressures per row, pure and combined slip and inputs
beyond the limits (``tests/data/mfeval``): the moments within 4e-12 of the peak moment,
the forces within 3e-12 of the peak force; R_e and Omega within 3e-8 and 3e-6 (MFeval ends
its R_e iteration when the first row of a batch converges); R_l and rho within 1e-6 m
where MFeval's fminsearch for the MF 6.2 radius converged.  The MF 6.2 loaded radius here
is the root of least deflection with R_l <= R_omega (NaN and a warning where none carries
the load); MFeval 4.0 solves it from 0.3 m by fminsearch, for MF 5.2 files too, and stalls
where the model carries no load.  MF 5.2's loaded radius here is the MF 6.1 closed form
with the file's Q_FZ2 (0 when absent).

Limits and speed
----------------
``saturate=False`` (the default) evaluates the inputs as given, with an
:class:`~frictionlaws.base.errors.ExtrapolationWarning` outside the file's ranges;
``saturate=True`` clamps slip ratio, slip angle, camber, pressure and load to the file's
ranges as MFeval's limit checks do (the load to FZMAX in the forces and to at least
FZMIN in M_z, the load below FZMIN reduced in M_x and M_y as MFeval does).  The speed
``vx`` [m/s] defaults to the file's LONGVL; speeds at or below VXLOW (and backwards)
are refused: MFeval's low-speed reductions are not reproduced.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from ..base.errors import ExtrapolationWarning, InputError, broadcast_shape
from ._mf_core import EPS, mf_curve
from ._mf_core import MFModel as MagicFormula  # the interface: no import of the class's module

__all__ = ["steady_state", "aligning_moment", "aligning_summary", "OUTPUTS"]

#: The outputs of :func:`steady_state`: name -> (unit, meaning).
OUTPUTS: dict[str, tuple[str, str]] = {
    "Fx": ("N", "longitudinal force (combined slip)"),
    "Fy": ("N", "lateral force (combined slip)"),
    "Fz": ("N", "vertical load as evaluated"),
    "Mx": ("N m", "overturning moment"),
    "My": ("N m", "rolling resistance moment"),
    "Mz": ("N m", "aligning moment (combined slip)"),
    "Mz0": ("N m", "aligning moment at pure side slip (kappa = 0)"),
    "t": ("m", "pneumatic trail"),
    "Mzr": ("N m", "residual aligning torque"),
    "Re": ("m", "effective rolling radius"),
    "Rl": ("m", "loaded radius"),
    "rho": ("m", "vertical deflection"),
    "omega": ("rad/s", "wheel angular speed"),
    "Cz": ("N/m", "vertical stiffness at the load"),
    "2a": ("m", "contact patch length"),
    "2b": ("m", "contact patch width"),
    "mux": ("1", "peak longitudinal friction coefficient"),
    "muy": ("1", "peak lateral friction coefficient"),
    "Kxk": ("N", "longitudinal slip stiffness"),
    "Kya": ("N/rad", "cornering stiffness"),
    "Cx": ("N/m", "longitudinal carcass stiffness"),
    "Cy": ("N/m", "lateral carcass stiffness"),
    "sigmax": ("m", "longitudinal relaxation length"),
    "sigmay": ("m", "lateral relaxation length"),
}


#: Structure entries that are lengths or speeds of a real tyre: positive.
_POSITIVE = frozenset({"UNLOADED_RADIUS", "LONGVL", "WIDTH"})


def _need(mf: MagicFormula, key: str, default: float | None = None) -> float:
    """A structure entry of the file, or its default; refused when absent without one,
    and a radius or speed that is not positive (a zero radius gives zero moments)."""
    if key in mf.structure:
        value = mf.structure[key]
        if key in _POSITIVE and not value > 0:
            raise InputError(f"{key} = {value:g} (SI) must be positive for the moments and "
                             "radii", file=mf.source)
        return value
    if default is None:
        raise InputError(f"the property file has no {key}, needed for the moments and "
                         "radii", file=mf.source)
    return default


def _sgn(x: Any) -> Any:
    """sign with sgn(0) = +1 (the convention of the equations' epsilon guards)."""
    return np.where(np.asarray(x) >= 0, 1.0, -1.0)


class _Rows:
    """The broadcast, checked (and optionally saturated) inputs of one evaluation."""

    def __init__(self, mf: MagicFormula, kappa: Any, alpha: Any, fz: Any, gamma: Any,
                 pressure: Any, vx: Any, saturate: bool) -> None:
        k = mf._check("kappa", kappa)
        a = mf._check("alpha", alpha)
        z = mf._check("fz", fz, positive=True)
        g = mf._check("gamma", gamma)
        p = np.asarray(mf.pressure if pressure is None else pressure, dtype=float) \
            if (pressure is not None or mf.pressure is not None) else None
        v = mf._check("vx", _need(mf, "LONGVL") if vx is None else vx)
        vxlow = mf.structure.get("VXLOW", 0.0)
        if not (v > vxlow).all():
            raise InputError(f"speeds at or below VXLOW = {vxlow:g} m/s (or backwards) are "
                             "not modelled here: the steady-state outputs need vx > VXLOW",
                             file=mf.source)
        named = {"kappa": k, "alpha": a, "fz": z, "gamma": g, "vx": v}
        shape = broadcast_shape({**named, **({"pressure": p} if p is not None else {})},
                                mf.source)
        self.kappa_in = np.broadcast_to(k, shape)
        self.fz_in = np.broadcast_to(z, shape)
        self.vx = np.broadcast_to(v, shape)
        lim = mf.limits
        names = (("kappa", k), ("alpha", a), ("gamma", g), ("pressure", p))
        clipped: dict[str, Any] = {}
        for name, x in names:
            if x is None:
                clipped[name] = None
            elif saturate and name in lim:
                clipped[name] = np.clip(x, *lim[name])
            else:
                mf._warn_range(name, x)
                clipped[name] = x
        self.kappa = np.broadcast_to(clipped["kappa"], shape)
        self.alpha = np.broadcast_to(clipped["alpha"], shape)
        if np.any(np.abs(self.alpha) >= np.pi / 2):
            raise InputError("slip angles must lie strictly between -90 and 90 degrees")
        self.gamma = np.broadcast_to(clipped["gamma"], shape)
        self.pressure = clipped["pressure"]
        fzmin, fzmax = lim.get("fz", (0.0, np.inf))
        if saturate or mf.loads_above_fzmax == "clamp":
            self.fz = np.minimum(self.fz_in, fzmax)
        else:
            mf._warn_range("fz", self.fz_in)
            self.fz = self.fz_in
        self.fz_mz = np.maximum(self.fz, fzmin) if saturate else self.fz
        # MFeval's reduction of the load below FZMIN in M_x (squared) and M_y (linear)
        low = saturate & (self.fz_in < fzmin) if fzmin > 0 else np.zeros(shape, bool)
        ratio = np.where(low, self.fz_in / max(fzmin, 1e-300), 1.0)
        self.fz_mx = np.where(low, self.fz * ratio**2, self.fz)
        self.fz_my = np.where(low, self.fz_in * ratio, self.fz_in)
        self.dpi = mf._dpi(None if self.pressure is None else self.pressure)
        self.shape = shape


def steady_state(mf: MagicFormula, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                 pressure: Any = None, vx: Any = None, saturate: bool = False
                 ) -> dict[str, np.ndarray]:
    """Every steady-state output of the tyre per row (see :data:`OUTPUTS`).

    Parameters
    ----------
    mf : MagicFormula
        The tyre (read with its structure: radii, stiffnesses, LONGVL).
    kappa, alpha, fz, gamma : array-like
        Slip ratio [-], slip angle [rad], vertical load [N], camber [rad]; broadcast.
    pressure : float or array-like, optional
        Inflation pressure [Pa], one or one per row (default: the file's).
    vx : float or array-like, optional
        Forward speed [m/s] (default: the file's LONGVL); must exceed VXLOW.
    saturate : bool
        Clamp the inputs at the file's limits as MFeval does (default False: evaluate
        as given, warning outside the ranges).

    Returns
    -------
    dict of str to numpy.ndarray
        One array per output of :data:`OUTPUTS`, shaped like the broadcast inputs
        (``Cx`` and ``Cy`` only when the file gives the carcass stiffnesses).
    """
    r = _Rows(mf, kappa, alpha, fz, gamma, pressure, vx, saturate)
    out = _forces(mf, r)
    out.update(_aligning(mf, r, out))
    out["Mx"] = _overturning(mf, r, out["Fy"])
    out["My"] = _rolling(mf, r, out["Fx"])
    out.update(_radii(mf, r, out["Fx"], out["Fy"]))
    out.update(_patch(mf, r))
    out.update(_relaxation(mf, r, out["Kxk"], out["Kya"]))
    return {k: np.broadcast_to(np.asarray(v, dtype=float), r.shape).copy()
            for k, v in out.items() if k in OUTPUTS}


def aligning_moment(mf: MagicFormula, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                    pressure: Any = None, vx: Any = None, saturate: bool = False
                    ) -> dict[str, np.ndarray]:
    """The aligning moment alone: ``Mz``, ``Mz0``, ``t``, ``Mzr`` (and the forces).

    Needs only UNLOADED_RADIUS and LONGVL of the file's structure; the parameters are
    those of :func:`steady_state`.

    Parameters
    ----------
    mf : MagicFormula
        The tyre.
    kappa, alpha, fz, gamma : array-like
        Slip ratio [-], slip angle [rad], vertical load [N], camber [rad].
    pressure : float or array-like, optional
        Inflation pressure [Pa].
    vx : float or array-like, optional
        Forward speed [m/s] (default: LONGVL).
    saturate : bool
        Clamp the inputs at the file's limits (default False).

    Returns
    -------
    dict of str to numpy.ndarray
        ``Fx``, ``Fy`` [N], ``Mz``, ``Mz0``, ``Mzr`` [N m], ``t`` [m].
    """
    r = _Rows(mf, kappa, alpha, fz, gamma, pressure, vx, saturate)
    out = _forces(mf, r)
    out.update(_aligning(mf, r, out))
    return {k: np.broadcast_to(np.asarray(out[k], dtype=float), r.shape).copy()
            for k in ("Fx", "Fy", "Mz", "Mz0", "t", "Mzr")}


def aligning_summary(mf: MagicFormula, loads: Any) -> dict[str, Any]:
    """Pneumatic trail at zero slip and the peak pure-slip aligning moment per load.

    Parameters
    ----------
    mf : MagicFormula
        The tyre.
    loads : array-like
        Vertical loads [N].

    Returns
    -------
    dict
        ``trail_m`` (t at alpha = kappa = 0 [m]), ``Mz0_peak_N_m`` (the M_z0 of largest
        magnitude for slip angles within +-20 degrees, signed [N m]) and
        ``Mz0_peak_alpha_deg`` (where it is [deg]), each a list per load; empty when the
        file lacks UNLOADED_RADIUS or LONGVL.
    """
    if "UNLOADED_RADIUS" not in mf.structure or "LONGVL" not in mf.structure:
        return {}
    alpha = np.radians(np.linspace(-20.0, 20.0, 801))
    fz = np.asarray(loads, dtype=float)[:, None]
    out = aligning_moment(mf, 0.0, np.concatenate([[0.0], alpha]), fz)
    mz0 = out["Mz0"][:, 1:]
    at = np.argmax(np.abs(mz0), axis=1)
    rows = np.arange(len(at))
    return {"trail_m": out["t"][:, 0].tolist(), "Mz0_peak_N_m": mz0[rows, at].tolist(),
            "Mz0_peak_alpha_deg": np.degrees(alpha[at]).tolist()}


def _forces(mf: MagicFormula, r: _Rows) -> dict[str, Any]:
    """Combined forces and the factors the moments need."""
    alpha_s = np.tan(r.alpha) if mf.slip_angle == "tan_alpha" else r.alpha
    lon = mf._long(r.fz, r.gamma, r.dpi)
    lat = mf._lat(r.fz, r.gamma, r.dpi)
    fx0 = mf_curve(r.kappa + lon.S_H, lon.B, lon.C, lon.D, lon.E_a, lon.E_b, lon.S_V)
    fy0 = mf_curve(alpha_s + lat.S_H, lat.B, lat.C, lat.D, lat.E_a, lat.E_b, lat.S_V)
    G_yk, S_Vyk = mf._gyk(r.kappa, alpha_s, r.fz, r.gamma, lat.mu)
    return {"Fx": mf._gxa(r.kappa, alpha_s, r.fz, r.gamma) * fx0,
            "Fy": G_yk * fy0 + S_Vyk, "Fz": r.fz, "mux": lon.mu, "muy": lat.mu,
            "Kxk": lon.K, "Kya": lat.K, "_alpha_s": alpha_s, "_lat": lat, "_G_yk": G_yk,
            "_S_Vyk": S_Vyk}


def _aligning(mf: MagicFormula, r: _Rows, f: dict[str, Any]) -> dict[str, Any]:
    """M_z0, M_z, the pneumatic trail t and the residual torque M_zr."""
    c = mf._c
    R0 = _need(mf, "UNLOADED_RADIUS")
    alpha_s, lat = f["_alpha_s"], f["_lat"]
    fz = r.fz_mz
    dfz = (r.fz - mf.fz0) / mf.fz0
    g_s, g = mf.gamma_star(r.gamma), r.gamma
    lmuy = c("LMUY")
    K_ya = lat.K + EPS * _sgn(lat.K)
    alpha_r = alpha_s + lat.S_H + lat.S_V / K_ya
    alpha_t = alpha_s + c("QHZ1") + c("QHZ2") * dfz + (c("QHZ3") + c("QHZ4") * dfz) * g_s
    B_t = ((c("QBZ1") + c("QBZ2") * dfz + c("QBZ3") * dfz**2)
           * (1 + c("QBZ4") * g + c("QBZ5") * np.abs(g)) * c("LKY") / lmuy)
    C_t = c("QCZ1")
    D_t = ((c("QDZ1") + c("QDZ2") * dfz) * (1 - c("PPZ1") * r.dpi)
           * (1 + c("QDZ3") * g + c("QDZ4") * g**2) * fz * (R0 / mf.fz0) * c("LTR"))
    E_t = np.minimum((c("QEZ1") + c("QEZ2") * dfz + c("QEZ3") * dfz**2)
                     * (1 + (c("QEZ4") + c("QEZ5") * g_s) * (2 / np.pi)
                        * np.arctan(B_t * C_t * alpha_t)), 1.0)
    B_r = c("QBZ9") * c("LKY") / lmuy + c("QBZ10") * lat.B * lat.C
    D_r = (fz * R0 * ((c("QDZ6") + c("QDZ7") * dfz) * c("LRES")
                      + ((c("QDZ8") + c("QDZ9") * dfz) * (1 + c("PPZ2") * r.dpi)
                         + (c("QDZ10") + c("QDZ11") * dfz) * np.abs(g_s)) * g_s * c("LKZC"))
           * lmuy * np.cos(alpha_s))
    v_c = np.sqrt(r.vx**2 + (np.tan(r.alpha) * r.vx) ** 2)
    cos_a = r.vx / (v_c + EPS)  # cos(alpha'), eq. (4.E6)

    def trail(a: Any) -> Any:
        x = B_t * a
        return D_t * np.cos(C_t * np.arctan(x - E_t * (x - np.arctan(x)))) * cos_a

    g0 = mf._lat(r.fz, 0.0, r.dpi)
    fy0_g0 = mf_curve(alpha_s + g0.S_H, g0.B, g0.C, g0.D, g0.E_a, g0.E_b, g0.S_V)
    mz0 = -trail(alpha_t) * fy0_g0 + D_r * np.cos(np.arctan(B_r * alpha_r)) * cos_a
    ratio2 = (f["Kxk"] / K_ya) ** 2 * r.kappa**2
    a_r = np.arctan(np.sqrt(np.tan(alpha_r) ** 2 + ratio2)) * _sgn(alpha_r)
    a_t = np.arctan(np.sqrt(np.tan(alpha_t) ** 2 + ratio2)) * _sgn(alpha_t)
    t = trail(a_t) * (c("LFZO") if mf.equations == "mfeval" else 1.0)
    M_zr = D_r * np.cos(np.arctan(B_r * a_r))
    s = R0 * (c("SSZ1") + c("SSZ2") * f["Fy"] / mf.fnomin
              + (c("SSZ3") + c("SSZ4") * dfz) * g) * c("LS")
    if mf.version != "5.2":
        fy_arm = f["_G_yk"] * fy0_g0
    elif mf.equations == "mfeval":  # MFeval: the shift S_Vyk with mu_y at zero camber
        fy_arm = f["Fy"] - mf._gyk(r.kappa, alpha_s, r.fz, g, g0.mu)[1]
    else:
        fy_arm = f["Fy"] - f["_S_Vyk"]
    return {"Mz0": mz0, "Mz": -t * fy_arm + M_zr + s * f["Fx"], "t": t, "Mzr": M_zr}


def _overturning(mf: MagicFormula, r: _Rows, fy: Any) -> Any:
    """M_x [N m], the TNO MF-Tyre form (QSX1-14, PPMX1)."""
    c = mf._c
    R0, fz0, fz, g = _need(mf, "UNLOADED_RADIUS"), mf.fnomin, r.fz_mx, r.gamma
    return (R0 * fz * c("LMX") * (
        c("QSX1") * c("LVMX") - c("QSX2") * g * (1 + c("PPMX1") * r.dpi) + c("QSX3") * fy / fz0
        + c("QSX4") * np.cos(c("QSX5") * np.arctan((c("QSX6") * fz / fz0) ** 2))
        * np.sin(c("QSX7") * g + c("QSX8") * np.arctan(c("QSX9") * fy / fz0))
        + c("QSX10") * np.arctan(c("QSX11") * fz / fz0) * g)
        + R0 * c("LMX") * (fy * (c("QSX13") + c("QSX14") * np.abs(g))
                           - fz * c("QSX12") * g * np.abs(g)))


def _rolling(mf: MagicFormula, r: _Rows, fx: Any) -> Any:
    """M_y [N m]: eq. (A48) of the 2010 paper (MF 6.x) or the MF 5.2 manual."""
    c = mf._c
    R0, fz0, V0 = _need(mf, "UNLOADED_RADIUS"), mf.fnomin, _need(mf, "LONGVL")
    fz, v = r.fz_my, r.vx / V0
    base = c("QSY1") + c("QSY2") * fx / fz0 + c("QSY3") * np.abs(v) + c("QSY4") * v**4
    if mf.version == "5.2":
        my = -R0 * fz * c("LMY") * base
    else:
        p_ratio = 1.0 + np.asarray(r.dpi)
        my = (-R0 * fz0 * c("LMY") * (base + (c("QSY5") + c("QSY6") * fz / fz0) * r.gamma**2)
              * (fz / fz0) ** c("QSY7") * p_ratio ** c("QSY8"))
    # towards the locked wheel (wheel speed below VXLOW) M_y fades as MFeval's does
    high = mf.structure.get("VXLOW", 0.0) / np.abs(r.vx) - 1.0
    low = -1.0 - mf.structure.get("VXLOW", 0.0) - high
    k = r.kappa_in
    fade = np.sin((np.pi / 2) * (k + 1.0) / (high + 1.0))
    return np.where((k >= low) & (k <= high), my * fade, np.where(k < low, -my, my))


def _radii(mf: MagicFormula, r: _Rows, fx: Any, fy: Any) -> dict[str, Any]:
    """R_e, omega (eqs. 1, 7 and 2.5), R_l, rho and C_z (eqs. 4-8; MF 6.2 by root finding)."""
    R0, V0, fz0 = _need(mf, "UNLOADED_RADIUS"), _need(mf, "LONGVL"), mf.fnomin
    cz0 = _need(mf, "VERTICAL_STIFFNESS")
    s = mf.structure
    q_re0, q_v1 = s.get("Q_RE0", 1.0), s.get("Q_V1", 0.0)
    pfz1 = s.get("PFZ1", 0.0)
    cz = cz0 * (1 + pfz1 * np.asarray(r.dpi))
    fz_u = r.fz_in
    deflect = (fz0 / cz) * (s.get("DREFF", 0.0) * np.arctan(s.get("BREFF", 0.0) * fz_u / fz0)
                            + s.get("FREFF", 0.0) * fz_u / fz0)
    re = np.full(r.shape, 0.965 * R0)
    for _ in range(30):  # fixed point of omega = (1 + kappa) vx / R_e; converges in < 10
        omega = (r.kappa_in + 1.0) * r.vx / re
        romega = R0 * (q_re0 + q_v1 * (omega * R0 / V0) ** 2)
        re = romega - deflect
    omega = (r.kappa_in + 1.0) * r.vx / re
    romega = R0 * (q_re0 + q_v1 * (omega * R0 / V0) ** 2)
    q_fz2 = s.get("Q_FZ2", 0.0)
    q_fz1 = np.sqrt(max((cz0 * R0 / fz0) ** 2 - 4 * q_fz2, 0.0))
    if mf.version == "6.2":
        rl, rho = _loaded_radius_62(mf, r, omega, romega, fx, fy, q_fz1, q_fz2)
        fz_c = r.fz
    else:
        fz_c = r.fz_mz
        ext = ((1 + s.get("Q_V2", 0.0) * (R0 / V0) * np.abs(omega)
                - (s.get("Q_FCX", 0.0) * fx / fz0) ** 2 - (s.get("Q_FCY", 0.0) * fy / fz0) ** 2)
               * (1 + pfz1 * np.asarray(r.dpi)) * fz0)
        rhs = fz_c / np.maximum(ext, 1e-15)
        x = (rhs / q_fz1 if q_fz2 == 0 else
             (-q_fz1 + np.sqrt(np.maximum(q_fz1**2 + 4 * q_fz2 * rhs, 0.0))) / (2 * q_fz2))
        rho = np.maximum(x * R0, 0.0)
        rl = np.maximum(romega - rho, 0.0)
    return {"Re": re, "omega": omega, "Rl": rl, "rho": rho, "Cz": fz_c / rho}


def _fz_62(mf: MagicFormula, r: _Rows, rl: Any, omega: Any, romega: Any, fx: Any, fy: Any,
           q_fz1: float, q_fz2: float) -> tuple[Any, Any]:
    """(F_z, rho_z) of the MF 6.2 vertical model at loaded radius ``rl``."""
    s, R0, V0, fz0 = mf.structure, _need(mf, "UNLOADED_RADIUS"), _need(mf, "LONGVL"), mf.fnomin
    g = r.gamma
    x = rl / romega
    s_fyg = (s.get("Q_FYS1", 0.0) + s.get("Q_FYS2", 0.0) * x + s.get("Q_FYS3", 0.0) * x**2) * g
    rho_fr = np.maximum(romega - rl, 0.0)
    rtw = (1.075 - 0.5 * _need(mf, "ASPECT_RATIO")) * _need(mf, "WIDTH")
    q1, q2 = s.get("Q_CAM1", 0.0), s.get("Q_CAM2", 0.0)
    den = q1 * romega + q2 * romega**2
    shape = np.where(den != 0, (q1 * rl + q2 * rl**2) / np.where(den != 0, den, 1.0), 0.0)
    rho_g = np.where((g != 0) & (den != 0), shape**2 * (rtw / 8) * np.abs(np.tan(g))
                     - s.get("Q_CAM3", 0.0) * rho_fr * np.abs(g), 0.0)
    rho = np.maximum(rho_fr + rho_g, 1e-12)
    corr = ((1 + s.get("Q_V2", 0.0) * (R0 / V0) * np.abs(omega) - (s.get("Q_FCX", 0.0) * fx / fz0)
             ** 2 - ((rho / R0) ** s.get("Q_FCY2", 0.0) * s.get("Q_FCY", 0.0) * (fy - s_fyg)
                     / fz0) ** 2) * (1 + s.get("PFZ1", 0.0) * np.asarray(r.dpi)))
    return corr * (q_fz1 * rho / R0 + q_fz2 * (rho / R0) ** 2) * fz0, rho


def _loaded_radius_62(mf: MagicFormula, r: _Rows, omega: Any, romega: Any, fx: Any, fy: Any,
                      q_fz1: float, q_fz2: float) -> tuple[Any, Any]:
    """Loaded radius of MF 6.2 where the model's load equals the given one.

    The root of smallest deflection with ``R_l <= R_omega``: the load is scanned from
    the free radius inwards (64 steps) to the first radius that carries it, then
    bisected to 1e-12 of the radius.  A row without such a radius gets NaN and a
    warning (the lateral-force term can make the model's load negative at small
    deflection; a radius above R_omega, where the camber term alone grows with the
    radius, is not a loaded radius).
    """
    target = r.fz
    def excess(rl: Any) -> Any:
        return _fz_62(mf, r, rl, omega, romega, fx, fy, q_fz1, q_fz2)[0] - target

    steps = np.linspace(1.0, 0.0, 65)
    scan = np.stack([excess(romega * f) for f in steps])  # (65, *shape)
    carried = scan >= 0
    first = np.argmax(carried, axis=0)
    found = carried.any(axis=0)
    hi = romega * steps[np.maximum(first - 1, 0)]  # not yet carrying (or the free radius)
    lo = romega * steps[first]
    for _ in range(48):
        mid = 0.5 * (lo + hi)
        up = excess(mid) >= 0
        lo, hi = np.where(up, mid, lo), np.where(up, hi, mid)
    rl = np.where(found, lo, np.nan)
    if not np.all(found):
        warnings.warn(f"{mf.name or 'MF 6.2'}: {int(np.size(found) - np.sum(found))} row(s) "
                      "have no loaded radius up to the free radius that carries the load: "
                      "R_l, rho and C_z are NaN there", ExtrapolationWarning, stacklevel=4)
    return rl, _fz_62(mf, r, rl, omega, romega, fx, fy, q_fz1, q_fz2)[1]


def _patch(mf: MagicFormula, r: _Rows) -> dict[str, Any]:
    """Contact patch length 2a and width 2b (eqs. 9-10; MF 5.2: Q_A1, Q_A2, 2b = width)."""
    s, R0, fz0 = mf.structure, _need(mf, "UNLOADED_RADIUS"), mf.fnomin
    w, cz0 = _need(mf, "WIDTH"), _need(mf, "VERTICAL_STIFFNESS")
    ncz = cz0 * (1 + s.get("PFZ1", 0.0) * np.asarray(r.dpi))
    bottom = R0 - s.get("RIM_RADIUS", 0.0) - s.get("BOTTOM_OFFST", 0.0)
    fz = np.where(R0 - r.fz_in / ncz < R0 - bottom, bottom * ncz, r.fz_in)
    if mf.version == "5.2":
        q_a1, q_a2 = s.get("Q_A1", 0.0), s.get("Q_A2", 0.0)
        if q_a1 == 0 and q_a2 == 0:  # the MF-Tyre 5.2 defaults from the vertical stiffness
            y = np.log10(R0 * cz0 / fz0)
            q_a1 = -0.0388 * y**3 + 0.2509 * y**2 - 0.6283 * y + 0.6279
            q_a2 = 1.693 * q_a1**2
        return {"2a": 2 * R0 * (q_a2 * fz / fz0 + q_a1 * np.sqrt(fz / fz0)),
                "2b": np.full(r.shape, w)}
    n = fz / (ncz * R0)
    return {"2a": 2 * R0 * (s.get("Q_RA2", 0.0) * n + s.get("Q_RA1", 0.0) * np.sqrt(n)),
            "2b": 2 * w * (s.get("Q_RB2", 0.0) * n + s.get("Q_RB1", 0.0) * np.cbrt(n))}


def _relaxation(mf: MagicFormula, r: _Rows, kxk: Any, kya: Any) -> dict[str, Any]:
    """C_x, C_y (eqs. 17-18) and sigma = |K / C| (eq. 19); MF 5.2 from PTX, PTY.

    C_x and C_y are given when the file has [STRUCTURAL] stiffnesses (MF 5.2 files
    usually do not: their relaxation lengths come from PTX and PTY).
    """
    c, s = mf._c, mf.structure
    dfz = (r.fz - mf.fz0) / mf.fz0
    dpi = np.asarray(r.dpi)
    out: dict[str, Any] = {}
    if "LONGITUDINAL_STIFFNESS" in s:
        out["Cx"] = (s["LONGITUDINAL_STIFFNESS"] * (1 + s.get("PCFX1", 0.0) * dfz
                     + s.get("PCFX2", 0.0) * dfz**2) * (1 + s.get("PCFX3", 0.0) * dpi))
    if "LATERAL_STIFFNESS" in s:
        out["Cy"] = (s["LATERAL_STIFFNESS"] * (1 + s.get("PCFY1", 0.0) * dfz
                     + s.get("PCFY2", 0.0) * dfz**2) * (1 + s.get("PCFY3", 0.0) * dpi))
    if mf.version == "5.2":
        R0 = _need(mf, "UNLOADED_RADIUS")
        sx = ((c("PTX1") + c("PTX2") * dfz) * np.exp(-c("PTX3") * dfz) * c("LSGKP") * R0
              * r.fz / mf.fnomin)
        sy = (c("PTY1") * np.sin(2 * np.arctan(r.fz / (c("PTY2") * mf.fz0)))
              * (1 - c("PKY3") * np.abs(r.gamma)) * R0 * c("LFZO") * c("LSGAL"))
        return {**out, "sigmax": sx, "sigmay": sy}
    if "Cx" not in out or "Cy" not in out:
        raise InputError("[STRUCTURAL] LONGITUDINAL_STIFFNESS and LATERAL_STIFFNESS are "
                         "needed for the relaxation lengths of MF 6.x", file=mf.source)
    return {**out, "sigmax": np.abs(kxk / out["Cx"]), "sigmay": np.abs(kya / out["Cy"])}
