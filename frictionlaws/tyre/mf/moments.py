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
from .equations import EPS, MFCoefficients, gamma_star, lateral, mf_curve, weight_y
from .parameters import MFParameters

__all__ = ["Forces", "Aligning", "aligning", "overturning", "rolling", "sgn"]


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


def aligning(p: MFParameters, r: Conditions, f: Forces) -> Aligning:
    """M_z0, M_z, the pneumatic trail t and the residual torque M_zr (eqs. 4.E31-4.E49,
    4.E71-4.E78; the MF 6.x forms of the 2010 paper)."""
    c = p.c
    R0 = p.need("UNLOADED_RADIUS")
    alpha_s, lat = f.alpha_s, f.lat
    fz = r.fz_mz
    dfz = (r.fz - p.fz0) / p.fz0
    g_s, g = gamma_star(p, r.gamma), r.gamma
    lmuy = c.LMUY
    K_ya = lat.K + EPS * sgn(lat.K)
    alpha_r = alpha_s + lat.S_H + lat.S_V / K_ya
    alpha_t = alpha_s + c.QHZ1 + c.QHZ2 * dfz + (c.QHZ3 + c.QHZ4 * dfz) * g_s
    B_t = ((c.QBZ1 + c.QBZ2 * dfz + c.QBZ3 * dfz**2)
           * (1 + c.QBZ4 * g + c.QBZ5 * np.abs(g)) * c.LKY / lmuy)
    C_t = c.QCZ1
    D_t = ((c.QDZ1 + c.QDZ2 * dfz) * (1 - c.PPZ1 * r.dpi)
           * (1 + c.QDZ3 * g + c.QDZ4 * g**2) * fz * (R0 / p.fz0) * c.LTR)
    E_t = np.minimum((c.QEZ1 + c.QEZ2 * dfz + c.QEZ3 * dfz**2)
                     * (1 + (c.QEZ4 + c.QEZ5 * g_s) * (2 / np.pi)
                        * np.arctan(B_t * C_t * alpha_t)), 1.0)
    B_r = c.QBZ9 * c.LKY / lmuy + c.QBZ10 * lat.B * lat.C
    D_r = (fz * R0 * ((c.QDZ6 + c.QDZ7 * dfz) * c.LRES
                      + ((c.QDZ8 + c.QDZ9 * dfz) * (1 + c.PPZ2 * r.dpi)
                         + (c.QDZ10 + c.QDZ11 * dfz) * np.abs(g_s)) * g_s * c.LKZC)
           * lmuy * np.cos(alpha_s))
    v_c = np.sqrt(r.vx**2 + (np.tan(r.alpha) * r.vx) ** 2)
    cos_a = r.vx / (v_c + EPS)  # cos(alpha'), eq. (4.E6)

    def trail(a: Any) -> Any:
        x = B_t * a
        return D_t * np.cos(C_t * np.arctan(x - E_t * (x - np.arctan(x)))) * cos_a

    g0 = lateral(p, r.fz, 0.0, r.dpi)
    fy0_g0 = mf_curve(alpha_s + g0.S_H, g0.B, g0.C, g0.D, g0.E_a, g0.E_b, g0.S_V)
    mz0 = -trail(alpha_t) * fy0_g0 + D_r * np.cos(np.arctan(B_r * alpha_r)) * cos_a
    ratio2 = (f.lon.K / K_ya) ** 2 * r.kappa**2
    a_r = np.arctan(np.sqrt(np.tan(alpha_r) ** 2 + ratio2)) * sgn(alpha_r)
    a_t = np.arctan(np.sqrt(np.tan(alpha_t) ** 2 + ratio2)) * sgn(alpha_t)
    t = trail(a_t) * (c.LFZO if p.equations == "mfeval" else 1.0)
    M_zr = D_r * np.cos(np.arctan(B_r * a_r))
    s = R0 * (c.SSZ1 + c.SSZ2 * f.Fy / p.fnomin + (c.SSZ3 + c.SSZ4 * dfz) * g) * c.LS
    if p.version != "5.2":
        fy_arm = f.G_yk * fy0_g0
    elif p.equations == "mfeval":  # MFeval: the shift S_Vyk with mu_y at zero camber
        fy_arm = f.Fy - weight_y(p, r.kappa, alpha_s, r.fz, g, g0.mu)[1]
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
    # towards the locked wheel (wheel speed below VXLOW) M_y fades as MFeval's does
    high = p.structure.get("VXLOW", 0.0) / np.abs(r.vx) - 1.0
    low = -1.0 - p.structure.get("VXLOW", 0.0) - high
    k = r.kappa_in
    fade = np.sin((np.pi / 2) * (k + 1.0) / (high + 1.0))
    return np.where((k >= low) & (k <= high), my * fade, np.where(k < low, -my, my))
