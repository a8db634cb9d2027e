"""Turn slip: the spin of the contact patch and the factors zeta by which it acts.

A tyre that runs on a curved path (path curvature ``phit`` [1/m], MF-Tyre's "turn slip")
or is cambered spins about the vertical axis through its contact patch.  MF-Tyre's turn-slip
model (Pacejka, *Tire and Vehicle Dynamics*, 3rd ed. 2012, section 4.3.3, eqs. 4.75-4.106,
in the forms MFeval 4.0 evaluates, which its author matched to the MF-Tyre equation
manual) turns the spin

    phi = -phit - (1 - eps_gamma) omega sin(gamma) / V_c',
    eps_gamma = PECP1 (1 + PECP2 dfz)

into factors on the Magic Formula (all 1 without turn slip):

* zeta_1 on the longitudinal peak, ``cos(arctan(B_xp R0 phi))``,
  ``B_xp = PDXP1 (1 + PDXP2 dfz) cos(arctan(PDXP3 kappa))``;
* zeta_2 on the lateral peak, ``cos(arctan(B_yp (R0 |phi| + PDYP4 sqrt(R0 |phi|))))``,
  ``B_yp = PDYP1 (1 + PDYP2 dfz) cos(arctan(PDYP3 tan(alpha)))``;
* zeta_3 on the cornering stiffness, ``cos(arctan(PKYP1 R0^2 phi^2))``;
* zeta_0 = 0 and zeta_4 = 1 + S_Hyp - S_Vyg / K_ya': the camber's side force through the
  spin, ``S_Hyp = D_Hyp sin(C_Hyp arctan(B_Hyp R0 phi - E_Hyp (B_Hyp R0 phi -
  arctan(B_Hyp R0 phi)))) sgn(V_x)`` with ``C_Hyp = PHYP1``, ``D_Hyp = (PHYP2 + PHYP3
  dfz) sgn(V_x)``, ``E_Hyp = PHYP4`` (<= 1 with the limit checks), ``B_Hyp = K_yRp0 /
  (C_Hyp D_Hyp K_ya0)``, ``K_yRp0 = K_yg0 / (1 - eps_gamma)`` (MF 5.2 files: no S_Hyp,
  whose S_Hy has no zeta_0, zeta_4);
* zeta_5 on the pneumatic trail, ``cos(arctan(QDTP1 R0 phi))``;
* zeta_6, zeta_7, zeta_8 in the residual torque: ``B_r zeta_6``, ``C_r = zeta_7``,
  ``D_r + zeta_8 - 1`` with the spin moment (the parking moment at standstill)
  ``D_rp = D_Drp sin(C_Drp arctan(B_Drp R0 phit))``, ``zeta_8 = 1 + D_rp``,
  ``zeta_6 = cos(arctan(QBRP1 R0 phi))``,
  ``zeta_7 = (2/pi) arccos(M_zp90 / |D_rp|)``, ``M_zp90 = M_zpinf (2/pi) arctan(QCRP2 R0
  |phit|) G_yk``, ``M_zpinf = QCRP1 |mu_y| R0 F_z sqrt(F_z / F'_z0) LMP`` (> 0),
  ``C_Drp = QDRP1``, ``D_Drp = M_zpinf / sin(pi C_Drp / 2)``,
  ``B_Drp = K_zgr0 / (C_Drp D_Drp (1 - eps_gamma))``,
  ``K_zgr0 = F_z R0 (QDZ8 QDZ9 dfz + QDZ10 + QDZ11 dfz |gamma|) LKZC``.

A camber share ``eps_gamma >= 1`` is refused (the model divides by ``1 - eps_gamma``).
Where MFeval 4.0 gives no number this module gives the limit: zeta_7 at ``phit = 0``
(0/0 in MFeval: the ratio tends to ``M_zpinf (2/pi) QCRP2 G_yk (1 - eps_gamma) /
|K_zgr0|``) and S_Hyp at a standing wheel (``V_x = 0``: D_Hyp = 0 times a bounded sine).
Where ``M_zp90 / |D_rp|`` exceeds 1 the arccosine is imaginary and the residual torque
``D_r cos(zeta_7 arctan(B_r alpha_r))`` a hyperbolic cosine, as in MFeval (which takes the
real part of its complex result).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...base.errors import InputError
from .parameters import MFParameters

__all__ = ["TURN_SLIP_COEFFICIENTS", "NEEDED", "check_turn_slip", "Spin", "spin",
           "zeta_x", "zeta_y", "spin_shift", "zeta_trail", "residual_zetas"]

#: The coefficients of the turn-slip model ([TURNSLIP_COEFFICIENTS]).
TURN_SLIP_COEFFICIENTS = ("PDXP1", "PDXP2", "PDXP3", "PKYP1", "PDYP1", "PDYP2", "PDYP3",
                          "PDYP4", "PHYP1", "PHYP2", "PHYP3", "PHYP4", "PECP1", "PECP2",
                          "QDTP1", "QCRP1", "QCRP2", "QBRP1", "QDRP1")
#: Those the model divides by (the shape factors of the spin-induced shift and of the
#: spin moment): a file evaluated with turn slip must give them, not 0.
NEEDED = ("PHYP1", "QDRP1")
_PI2 = 2 / np.pi


def check_turn_slip(p: MFParameters) -> None:
    """Refuse turn slip for a file without the turn-slip coefficients it divides by."""
    missing = [n for n in NEEDED if not p.coefficients.get(n)]
    if missing:
        have = [n for n in TURN_SLIP_COEFFICIENTS if p.coefficients.get(n) is not None]
        what = ("has no [TURNSLIP_COEFFICIENTS]" if not have
                else f"gives no {' or '.join(missing)} other than 0 in [TURNSLIP_COEFFICIENTS]")
        raise InputError(f"turn slip: the property file {what}, which the turn-slip model "
                         f"needs ({', '.join(TURN_SLIP_COEFFICIENTS)}; MFeval would take its "
                         "reader's built-in values, those of another tyre)", file=p.source)


@dataclass(frozen=True)
class Spin:
    """The spin of one evaluation.

    Attributes
    ----------
    phi : numpy.ndarray
        The spin phi [1/m] the factors zeta take.
    phit : numpy.ndarray
        The path curvature [1/m] as the spin moment takes it.
    eps_gamma : numpy.ndarray
        The camber reduction eps_gamma = PECP1 (1 + PECP2 dfz) [-].
    """

    phi: Any
    phit: Any
    eps_gamma: Any


def spin(p: MFParameters, phit: Any, alpha: Any, gamma: Any, vx: Any, omega: Any,
         dfz: Any) -> Spin:
    """The spin phi = -phit - (1 - eps_gamma) omega sin(gamma) / V_c' [1/m] (eq. 4.76 with
    the sign MFeval 4.0 writes; V_c' the speed of the contact centre, VXLOW with the sign
    of V_x below VXLOW)."""
    c = p.c
    vxlow = p.structure.get("VXLOW", 0.0)
    eps_gamma = c.PECP1 * (1 + c.PECP2 * dfz)
    _check_camber_share(p, eps_gamma, dfz)
    v_c = np.hypot(vx, np.tan(alpha) * vx)
    v_c = np.where(np.abs(vx) < vxlow, np.where(vx < 0, -vxlow, vxlow), v_c)
    phi = -phit - (1 - eps_gamma) * omega * np.sin(gamma) / v_c
    return Spin(phi=phi, phit=phit, eps_gamma=eps_gamma)


def _check_camber_share(p: MFParameters, eps_gamma: Any, dfz: Any) -> None:
    """Refuse a camber share eps_gamma of 1 or more: the model divides by ``1 - eps_gamma``
    (the spin stiffness ``K_yRp0 = K_yg0 / (1 - eps_gamma)``; MFeval gives inf or NaN at
    1 and a spin shift of the other sign above), and a share of the camber not acting as
    spin above the whole camber is no tyre's.  A file's PECP2 can take it there at a load
    far above the nominal one."""
    eps = np.broadcast_to(np.asarray(eps_gamma, dtype=float), np.shape(dfz))
    if np.all(eps < 1):
        return
    i = int(np.argmax(eps))
    raise InputError(
        f"turn slip: the share of the camber not acting as spin, eps_gamma = PECP1 (1 + "
        f"PECP2 dfz) = {float(eps.flat[i]):.4g} at dfz = {float(np.ravel(dfz)[i]):.4g} "
        f"(PECP1 = {p.c.PECP1:g}, PECP2 = {p.c.PECP2:g}); the turn-slip model divides by "
        "1 - eps_gamma and holds for eps_gamma < 1 only (a lower load, or a file whose "
        "PECP1, PECP2 keep it below 1)", file=p.source)


def zeta_x(p: MFParameters, s: Spin, kappa: Any, dfz: Any) -> Any:
    """zeta_1, the spin's reduction of the longitudinal peak (eqs. 4.105-4.106)."""
    c = p.c
    b = c.PDXP1 * (1 + c.PDXP2 * dfz) * np.cos(np.arctan(c.PDXP3 * kappa))
    return np.cos(np.arctan(b * p.need("UNLOADED_RADIUS") * s.phi))


def zeta_y(p: MFParameters, s: Spin, alpha: Any, dfz: Any) -> tuple[Any, Any]:
    """(zeta_2, zeta_3): the spin's reduction of the lateral peak and of the cornering
    stiffness (eqs. 4.77-4.79)."""
    c = p.c
    r0 = p.need("UNLOADED_RADIUS")
    b = c.PDYP1 * (1 + c.PDYP2 * dfz) * np.cos(np.arctan(c.PDYP3 * np.tan(alpha)))
    turn = r0 * np.abs(s.phi)
    zeta2 = np.cos(np.arctan(b * (turn + c.PDYP4 * np.sqrt(turn))))
    zeta3 = np.cos(np.arctan(c.PKYP1 * r0**2 * s.phi**2))
    return zeta2, zeta3


def spin_shift(p: MFParameters, s: Spin, vx: Any, dfz: Any, k_y0: Any, k_yg0: Any,
               cap: bool) -> Any:
    """S_Hyp, the spin's shift of the lateral curve (eqs. 4.80-4.89): 0 at a standing
    wheel, where its amplitude D_Hyp is 0 (MFeval 4.0: 0 times an infinite slope).

    ``k_y0`` is the cornering stiffness at zero camber (with zeta_3) [N/rad], ``k_yg0``
    the camber stiffness [N/rad]; ``cap`` limits E_Hyp to 1 (the limit checks).
    """
    c = p.c
    r0 = p.need("UNLOADED_RADIUS")
    direction = np.sign(vx)
    C = c.PHYP1
    D = (c.PHYP2 + c.PHYP3 * dfz) * direction
    E = min(c.PHYP4, 1.0) if cap else c.PHYP4
    k_y0 = k_y0 + 1e-6 * np.where(k_y0 < 0, -1.0, 1.0)
    moving = D != 0
    B = np.where(moving, k_yg0 / (1 - s.eps_gamma)
                 / (C * np.where(moving, D, 1.0) * k_y0), 0.0)
    x = B * r0 * s.phi
    return D * np.sin(C * np.arctan(x - E * (x - np.arctan(x)))) * direction


def zeta_trail(p: MFParameters, s: Spin) -> Any:
    """zeta_5, the spin's reduction of the pneumatic trail (eq. 4.91)."""
    return np.cos(np.arctan(p.c.QDTP1 * p.need("UNLOADED_RADIUS") * s.phi))


def residual_zetas(p: MFParameters, s: Spin, fz: Any, dfz: Any, gamma: Any, mu_y: Any,
                   g_yk: Any) -> tuple[Any, Any, Any]:
    """(zeta_6, zeta_7, zeta_8) of the residual torque: B_r zeta_6, C_r = zeta_7 and the
    spin moment D_rp = zeta_8 - 1 added to D_r (eqs. 4.94-4.103, the forms of the MF-Tyre
    manual as MFeval 4.0 writes them).

    zeta_7 is complex where M_zp90 / |D_rp| exceeds 1 (its arccosine imaginary, the
    residual torque then a hyperbolic cosine); at phit = 0 it is the limit of the ratio,
    ``M_zpinf (2/pi) QCRP2 G_yk (1 - eps_gamma) / |K_zgr0|`` (MFeval 4.0: 0/0).
    """
    c = p.c
    r0 = p.need("UNLOADED_RADIUS")
    fz0 = p.fz0
    zeta6 = np.cos(np.arctan(c.QBRP1 * r0 * s.phi))
    m_inf = c.QCRP1 * np.abs(mu_y) * r0 * fz * np.sqrt(fz / fz0) * c.LMP
    m_inf = np.where(m_inf < 0, 1e-6, m_inf)
    C = c.QDRP1
    D = m_inf / np.sin(0.5 * np.pi * C)
    k_zgr0 = fz * r0 * (c.QDZ8 * c.QDZ9 * dfz + (c.QDZ10 + c.QDZ11 * dfz * np.abs(gamma))) \
        * c.LKZC
    with np.errstate(divide="ignore", invalid="ignore"):
        B = k_zgr0 / (C * D * (1 - s.eps_gamma))
        d_rp = D * np.sin(C * np.arctan(B * r0 * s.phit))
        m90 = m_inf * _PI2 * np.arctan(c.QCRP2 * r0 * np.abs(s.phit)) * g_yk
        limit = m_inf * _PI2 * c.QCRP2 * g_yk * np.abs(1 - s.eps_gamma) / np.abs(k_zgr0)
        ratio = np.where(s.phit == 0, limit, m90 / np.abs(d_rp))
    zeta7 = _PI2 * np.arccos(np.asarray(ratio, dtype=complex))
    return zeta6, zeta7, 1 + d_rp
