"""The Magic Formula's moments as plain functions: aligning M_z, overturning M_x, rolling M_y.

Each takes the checked parameters of one tyre
(:class:`~frictionlaws.tyre.mf.parameters.MFParameters`), the checked conditions of the
evaluation (:class:`~frictionlaws.tyre.mf.conditions.Conditions`) and the forces they rest
on; the equations and their sources are listed in :mod:`frictionlaws.tyre.mf.outputs`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .conditions import Conditions
from .equations import EPS, MFCoefficients, gamma_star
from .parameters import MFParameters

__all__ = ["Forces", "Aligning", "ZeroCamber", "AligningSpin", "aligning", "overturning",
           "rolling", "sgn"]


def sgn(x: Any) -> Any:
    """sign with sgn(0) = +1 (the convention of the equations' epsilon guards)."""
    return np.where(np.asarray(x) >= 0, 1.0, -1.0)


@dataclass(frozen=True)
class Forces:
    """The combined-slip forces of one evaluation and the factors the moments take.

    Attributes
    ----------
    Fx, Fy : numpy.ndarray
        Combined-slip forces [N].
    alpha_s : numpy.ndarray
        The lateral slip variable (tan(alpha) or alpha).
    lon, lat : MFCoefficients
        The pure-slip factors at the evaluated loads.
    G_yk, S_Vyk : numpy.ndarray
        The combined-slip weighting of F_y [-] and its slip-induced shift [N].
    """

    Fx: Any
    Fy: Any
    alpha_s: Any
    lon: MFCoefficients
    lat: MFCoefficients
    G_yk: Any
    S_Vyk: Any


@dataclass(frozen=True)
class Aligning:
    """The aligning moment and its parts [N m, m]."""

    Mz0: Any
    Mz: Any
    t: Any
    Mzr: Any


@dataclass(frozen=True)
class ZeroCamber:
    """The lateral force at zero camber the aligning moment takes.

    Attributes
    ----------
    fy0 : numpy.ndarray
        F'_y0 without turn slip [N] (of M_z0).
    fy0_turn : numpy.ndarray
        F'_y0 with the turn slip, if any [N] (of M_z, as MFeval 4.0).
    s_vyk : numpy.ndarray or None
        MF 5.2 (``equations="mfeval"``): the slip-induced shift with mu_y at zero camber.
    """

    fy0: Any
    fy0_turn: Any
    s_vyk: Any = None


@dataclass(frozen=True)
class AligningSpin:
    """The turn slip's factors of the aligning moment
    (:mod:`~frictionlaws.tyre.mf.turn_slip`): zeta_2 on the residual torque's offset,
    zeta_5 on the trail, zeta_6 on B_r, C_r = zeta_7 (complex where the arccosine is),
    the spin moment zeta_8 - 1; the camber term of D_r drops (zeta_0 = 0)."""

    zeta2: Any
    zeta5: Any
    zeta6: Any
    zeta7: Any
    zeta8: Any


def _trail_factors(p: MFParameters, r: Conditions, fz: Any, dfz: Any, alpha_t: Any,
                   zeta5: Any) -> tuple[Any, Any, Any, Any]:
    """(B_t, C_t, D_t, E_t) of the pneumatic trail (eqs. A58, 4.E41, A60, 4.E44)."""
    c = p.c
    R0 = p.need("UNLOADED_RADIUS")
    g_s, g = gamma_star(p, r.gamma), r.gamma
    B_t = ((c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz**2)
           * (1 + c.QBZ4 * g + c.QBZ5 * np.abs(g)) * c.LKY / c.LMUY)
    C_t = c.QCZ1
    D_t = ((c.QDZ1 + c.QDZ2 * dfz) * (1 - c.PPZ1 * r.dpi)
           * (1 + c.QDZ3 * g + c.QDZ4 * g**2) * fz * (R0 / p.fz0) * c.LTR * zeta5)
    E_t = ((c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz**2)
           * (1 + (c.QEZ4 + c.QEZ5 * g_s) * (2 / np.pi) * np.arctan(B_t * C_t * alpha_t)))
    return B_t, C_t, D_t, (np.minimum(E_t, 1.0) if r.limit_checks else E_t)


def _residual_offset(p: MFParameters, r: Conditions, fz: Any, dfz: Any, alpha_s: Any,
                     turn: AligningSpin | None) -> Any:
    """D_r, the offset of the residual torque (eq. 4.E47; with the spin moment)."""
    c = p.c
    g_s = gamma_star(p, r.gamma)
    zeta0, zeta2, spin_moment = (1.0, 1.0, 0.0) if turn is None else (
        0.0, turn.zeta2, turn.zeta8 - 1)
    return (fz * p.need("UNLOADED_RADIUS")
            * ((c.QDZ6 + c.QDZ7 * dfz) * c.LRES * zeta2
               + ((c.QDZ8 + c.QDZ9 * dfz) * (1 + c.PPZ2 * r.dpi)
                  + (c.QDZ10 + c.QDZ11 * dfz) * np.abs(g_s)) * g_s * c.LKZC * zeta0)
            * c.LMUY * np.sign(r.vx) * np.cos(alpha_s) + spin_moment)


def aligning(p: MFParameters, r: Conditions, f: Forces, zero: ZeroCamber,
             turn: AligningSpin | None = None) -> Aligning:
    """M_z0, M_z, the pneumatic trail t and the residual torque M_zr (eqs. 4.E31-4.E49,
    4.E71-4.E78; the MF 6.x forms of the 2010 paper; the turn slip's factors ``turn``;
    at low speed the trail and residual torque faded)."""
    c = p.c
    R0 = p.need("UNLOADED_RADIUS")
    alpha_s, lat = f.alpha_s, f.lat
    fz = r.fz_mz
    dfz = (r.fz - p.fz0) / p.fz0
    g_s = gamma_star(p, r.gamma)
    K_ya = lat.K + EPS * sgn(lat.K)
    alpha_r = alpha_s + lat.S_H + lat.S_V / K_ya
    alpha_t = alpha_s + c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * g_s
    B_t, C_t, D_t, E_t = _trail_factors(p, r, fz, dfz, alpha_t,
                                        1.0 if turn is None else turn.zeta5)
    B_r = c.QBZ9 * c.LKY / c.LMUY + c.QBZ10 * lat.B * lat.C
    C_r: Any = 1.0
    if turn is not None:
        B_r, C_r = B_r * turn.zeta6, turn.zeta7
    D_r = _residual_offset(p, r, fz, dfz, alpha_s, turn)
    v_c = np.sqrt(r.vx**2 + (np.tan(r.alpha) * r.vx) ** 2)
    cos_a = r.vx / (v_c + EPS)  # cos(alpha'), eq. (4.E6)

    def trail(a: Any) -> Any:
        x = B_t * a
        return D_t * np.cos(C_t * np.arctan(x - E_t * (x - np.arctan(x)))) * cos_a

    def residual(a: Any) -> Any:
        return np.real(D_r * np.cos(C_r * np.arctan(B_r * a)))

    mz0 = (-trail(alpha_t) * zero.fy0 + residual(alpha_r) * cos_a) * r.fade
    ratio2 = (f.lon.K / K_ya) ** 2 * r.kappa**2
    a_r = np.arctan(np.sqrt(np.tan(alpha_r) ** 2 + ratio2)) * sgn(alpha_r)
    a_t = np.arctan(np.sqrt(np.tan(alpha_t) ** 2 + ratio2)) * sgn(alpha_t)
    t = trail(a_t) * (c.LFZO if p.equations == "mfeval" else 1.0) * r.fade
    M_zr = residual(a_r) * r.fade
    s = R0 * (c.SSZ1 + c.SSZ2 * f.Fy / p.fnomin + (c.SSZ3 + c.SSZ4 * dfz) * r.gamma) * c.LS
    if p.version != "5.2":
        fy_arm = f.G_yk * zero.fy0_turn
    elif zero.s_vyk is not None:  # MFeval: the shift S_Vyk with mu_y at zero camber
        fy_arm = f.Fy - zero.s_vyk
    else:
        fy_arm = f.Fy - f.S_Vyk
    return Aligning(Mz0=mz0, Mz=-t * fy_arm + M_zr + s * f.Fx, t=t, Mzr=M_zr)


def overturning(p: MFParameters, r: Conditions, fy: Any) -> Any:
    """M_x [N m], the TNO MF-Tyre form (QSX1-14, PPMX1)."""
    c = p.c
    R0, fz0, fz, g = p.need("UNLOADED_RADIUS"), p.fnomin, r.fz_mx, r.gamma
    return (R0 * fz * c.LMX * (
        c.QSX1 * c.LVMX - c.QSX2 * g * (1 + c.PPMX1 * r.dpi) + c.QSX3 * fy / fz0
        + c.QSX4 * np.cos(c.QSX5 * np.arctan((c.QSX6 * fz / fz0) ** 2))
        * np.sin(c.QSX7 * g + c.QSX8 * np.arctan(c.QSX9 * fy / fz0))
        + c.QSX10 * np.arctan(c.QSX11 * fz / fz0) * g)
        + R0 * c.LMX * (fy * (c.QSX13 + c.QSX14 * np.abs(g))
                        - fz * c.QSX12 * g * np.abs(g)))


def rolling(p: MFParameters, r: Conditions, fx: Any) -> Any:
    """M_y [N m]: eq. (A48) of the 2010 paper (MF 6.x) or the MF 5.2 manual."""
    c = p.c
    R0, fz0, V0 = p.need("UNLOADED_RADIUS"), p.fnomin, p.need("LONGVL")
    fz, v = r.fz_my, r.vx / V0
    base = c.QSY1 + c.QSY2 * fx / fz0 + c.QSY3 * np.abs(v) + c.QSY4 * v**4
    if p.version == "5.2":
        my = -R0 * fz * c.LMY * base
    else:
        p_ratio = 1.0 + np.asarray(r.dpi)
        my = (-R0 * fz0 * c.LMY * (base + (c.QSY5 + c.QSY6 * fz / fz0) * r.gamma**2)
              * (fz / fz0) ** c.QSY7 * p_ratio ** c.QSY8)
    my = np.where(r.vx < 0, -my, my)  # running backwards
    # towards the locked wheel (wheel speed below VXLOW) M_y fades as MFeval's does
    vxlow = p.structure.get("VXLOW", 0.0)
    with np.errstate(divide="ignore", invalid="ignore"):
        high = vxlow / np.abs(r.vx) - 1.0
        low = -1.0 - vxlow - high
        k = r.kappa_in
        fade = np.sin((np.pi / 2) * (k + 1.0) / (high + 1.0))
        my = np.where((k >= low) & (k <= high), my * fade, np.where(k < low, -my, my))
    return np.where(r.vx == 0, 0.0, my)  # a standing wheel
