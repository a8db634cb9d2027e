"""The Magic Formula's radii, vertical stiffness, contact patch and carcass stiffnesses.

Plain functions of the checked parameters of one tyre
(:class:`~frictionlaws.tyre.mf.parameters.MFParameters`) and the checked conditions of the
evaluation (:class:`~frictionlaws.tyre.mf.conditions.Conditions`): the effective rolling
radius and wheel speed, the loaded radius, deflection and vertical stiffness (MF 6.2 by
root finding), the contact patch, the carcass stiffnesses and relaxation lengths.  The
equations and their sources are listed in :mod:`frictionlaws.tyre.mf.outputs`.
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np

from ...base.errors import ExtrapolationWarning, InputError
from .conditions import Conditions
from .parameters import MFParameters

__all__ = ["rolling_radius", "loaded_radius", "patch", "carcass_stiffness", "relaxation",
           "loaded_radius_62", "fz_62"]


def rolling_radius(p: MFParameters, r: Conditions) -> dict[str, Any]:
    """R_e and the wheel speed omega (eqs. 1, 7 and 2.5), with the free radius R_omega at
    that speed: at the wheel speed given (``r.omega``), else at the speed the slip ratio
    gives, omega = (1 + kappa) V_x / R_e (a fixed point)."""
    R0, V0, fz0 = p.need("UNLOADED_RADIUS"), p.need("LONGVL"), p.fnomin
    cz0 = p.need("VERTICAL_STIFFNESS")
    s = p.structure
    q_re0, q_v1 = s.get("Q_RE0", 1.0), s.get("Q_V1", 0.0)
    pfz1 = s.get("PFZ1", 0.0)
    cz = cz0 * (1 + pfz1 * np.asarray(r.dpi))
    fz_u = r.fz_in
    deflect = (fz0 / cz) * (s.get("DREFF", 0.0) * np.arctan(s.get("BREFF", 0.0) * fz_u / fz0)
                            + s.get("FREFF", 0.0) * fz_u / fz0)

    def free(omega: Any) -> Any:  # the free radius grown at wheel speed omega
        return R0 * (q_re0 + q_v1 * (omega * R0 / V0) ** 2)

    if r.omega is not None:
        romega = free(r.omega)
        return {"Re": romega - deflect, "omega": r.omega, "Romega": romega}
    re = np.full(r.shape, 0.965 * R0)
    for _ in range(30):  # fixed point of omega = (1 + kappa) vx / R_e; converges in < 10
        re = free((r.kappa_in + 1.0) * r.vx / re) - deflect
    omega = (r.kappa_in + 1.0) * r.vx / re
    return {"Re": re, "omega": omega, "Romega": free(omega)}


def loaded_radius(p: MFParameters, r: Conditions, omega: Any, romega: Any, fx: Any,
                  fy: Any) -> dict[str, Any]:
    """R_l, rho and C_z at the wheel speed ``omega`` and free radius ``romega`` (eqs. 4-8;
    MF 6.2 by root finding, :func:`loaded_radius_62`), and ``said``: the rows made NaN
    with a warning (no loaded radius, no deflection)."""
    R0, V0, fz0 = p.need("UNLOADED_RADIUS"), p.need("LONGVL"), p.fnomin
    cz0 = p.need("VERTICAL_STIFFNESS")
    s = p.structure
    pfz1 = s.get("PFZ1", 0.0)
    q_fz2 = s.get("Q_FZ2", 0.0)
    q_fz1 = np.sqrt(max((cz0 * R0 / fz0) ** 2 - 4 * q_fz2, 0.0))
    said = np.zeros(np.shape(romega), dtype=bool)  # the rows made NaN with a warning
    if p.version == "6.2":
        rl, rho = loaded_radius_62(p, r, omega, romega, fx, fy, q_fz1, q_fz2)
        said = np.isnan(rl)
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
        rl = romega - rho
    rl, through = _through(p, rl)
    flat = ~(rho > 0)  # no deflection left (a wheel speed far past the model's): no C_z
    said = said | through | (flat & np.isfinite(rho))
    if np.any(flat & np.isfinite(rho)):
        warnings.warn(f"{p.name or 'Magic Formula'}: {int(np.sum(flat & np.isfinite(rho)))} "
                      "row(s) have no deflection (a load too small to deflect the tyre in "
                      "floating point, or a wheel speed whose free radius has grown past the "
                      "load's): C_z is NaN there", ExtrapolationWarning,
                      stacklevel=4)
    return {"Rl": rl, "rho": rho, "Cz": fz_c / np.where(flat, np.nan, rho), "said": said}


def _through(p: MFParameters, rl: Any) -> tuple[Any, Any]:
    """The loaded radius, NaN (with a warning) where the deflection reaches the free
    radius: a radius of 0 or less is no loaded radius (the load is past the model's); and
    the mask of those rows."""
    through = ~(rl > 0) & ~np.isnan(rl)
    if not np.any(through):
        return rl, through
    warnings.warn(f"{p.name or 'Magic Formula'}: {int(np.sum(through))} row(s) deflect the "
                  "tyre to its centre (the deflection reaches the free radius: the load is "
                  "past the vertical model's): R_l is NaN there", ExtrapolationWarning,
                  stacklevel=4)
    return np.where(through, np.nan, rl), through


def fz_62(p: MFParameters, r: Conditions, rl: Any, omega: Any, romega: Any, fx: Any,
           fy: Any, q_fz1: float, q_fz2: float) -> tuple[Any, Any]:
    """(F_z, rho_z) of the MF 6.2 vertical model at loaded radius ``rl``."""
    s, R0, V0, fz0 = p.structure, p.need("UNLOADED_RADIUS"), p.need("LONGVL"), p.fnomin
    g = r.gamma
    x = rl / romega
    s_fyg = (s.get("Q_FYS1", 0.0) + s.get("Q_FYS2", 0.0) * x + s.get("Q_FYS3", 0.0) * x**2) * g
    rho_fr = np.maximum(romega - rl, 0.0)
    rtw = (1.075 - 0.5 * p.need("ASPECT_RATIO")) * p.need("WIDTH")
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


def loaded_radius_62(p: MFParameters, r: Conditions, omega: Any, romega: Any, fx: Any,
                     fy: Any, q_fz1: float, q_fz2: float) -> tuple[Any, Any]:
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
        return fz_62(p, r, rl, omega, romega, fx, fy, q_fz1, q_fz2)[0] - target

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
        warnings.warn(f"{p.name or 'MF 6.2'}: {int(np.size(found) - np.sum(found))} row(s) "
                      "have no loaded radius up to the free radius that carries the load: "
                      "R_l, rho and C_z are NaN there", ExtrapolationWarning, stacklevel=4)
    return rl, fz_62(p, r, rl, omega, romega, fx, fy, q_fz1, q_fz2)[1]


def patch(p: MFParameters, r: Conditions) -> dict[str, Any]:
    """Contact patch length 2a and width 2b (eqs. 9-10; MF 5.2: Q_A1, Q_A2, 2b = width)."""
    s, R0, fz0 = p.structure, p.need("UNLOADED_RADIUS"), p.fnomin
    w, cz0 = p.need("WIDTH"), p.need("VERTICAL_STIFFNESS")
    ncz = cz0 * (1 + s.get("PFZ1", 0.0) * np.asarray(r.dpi))
    bottom = R0 - s.get("RIM_RADIUS", 0.0) - s.get("BOTTOM_OFFST", 0.0)
    fz = np.where(R0 - r.fz_in / ncz < R0 - bottom, bottom * ncz, r.fz_in)
    if p.version == "5.2":
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


def carcass_stiffness(p: MFParameters, r: Conditions) -> dict[str, Any]:
    """C_x and C_y (eqs. 17-18), when the file has [STRUCTURAL] stiffnesses (MF 5.2 files
    usually do not: their relaxation lengths come from PTX and PTY)."""
    s = p.structure
    dfz = (r.fz - p.fz0) / p.fz0
    dpi = np.asarray(r.dpi)
    out: dict[str, Any] = {}
    if "LONGITUDINAL_STIFFNESS" in s:
        out["Cx"] = (s["LONGITUDINAL_STIFFNESS"] * (1 + s.get("PCFX1", 0.0) * dfz
                     + s.get("PCFX2", 0.0) * dfz**2) * (1 + s.get("PCFX3", 0.0) * dpi))
    if "LATERAL_STIFFNESS" in s:
        out["Cy"] = (s["LATERAL_STIFFNESS"] * (1 + s.get("PCFY1", 0.0) * dfz
                     + s.get("PCFY2", 0.0) * dfz**2) * (1 + s.get("PCFY3", 0.0) * dpi))
    return out


def relaxation(p: MFParameters, r: Conditions, kxk: Any, kya: Any,
               stiffness: dict[str, Any]) -> dict[str, Any]:
    """The relaxation lengths sigma = |K / C| (eq. 19) from the slip stiffnesses and the
    carcass stiffnesses (:func:`carcass_stiffness`); MF 5.2 from PTX, PTY."""
    c = p.c
    dfz = (r.fz - p.fz0) / p.fz0
    if p.version == "5.2":
        R0 = p.need("UNLOADED_RADIUS")
        sx = ((c.PTX1 + c.PTX2 * dfz) * np.exp(-c.PTX3 * dfz) * c.LSGKP * R0
              * r.fz / p.fnomin)
        sy = (c.PTY1 * np.sin(2 * np.arctan(r.fz / (c.PTY2 * p.fz0)))
              * (1 - c.PKY3 * np.abs(r.gamma)) * R0 * c.LFZO * c.LSGAL)
        return {"sigmax": sx, "sigmay": sy}
    if "Cx" not in stiffness or "Cy" not in stiffness:
        raise InputError("[STRUCTURAL] LONGITUDINAL_STIFFNESS and LATERAL_STIFFNESS are "
                         "needed for the relaxation lengths of MF 6.x", file=p.source)
    return {"sigmax": np.abs(kxk / stiffness["Cx"]), "sigmay": np.abs(kya / stiffness["Cy"])}
