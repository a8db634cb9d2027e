"""The Magic Formula's force equations as plain functions of the checked parameters.

Each function takes the checked parameters of one tyre
(:class:`~frictionlaws.tyre.mf.parameters.MFParameters`, whose ``c`` reads the coefficients
by name) and checked, broadcastable inputs (SI), and returns numbers: the factors of the
pure-slip curves at a load (:func:`longitudinal`, :func:`lateral`), the curve itself
(:func:`mf_curve`), the combined-slip weighting functions (:func:`weight_x`,
:func:`weight_y`) and the camber and slip variables the equations use
(:func:`gamma_star`, :func:`camber_combined`, :func:`slip_variable`).  Checking the inputs
is the caller's: :class:`~frictionlaws.tyre.mf.model.MagicFormula` and
:mod:`~frictionlaws.tyre.mf.conditions` check them once.  The equations are listed in
:mod:`frictionlaws.tyre.mf.model`.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from .parameters import MFParameters
from .turn_slip import Spin, spin_shift

__all__ = ["EPS", "MFCoefficients", "mf_curve", "cos_weight", "longitudinal", "lateral",
           "weight_x", "weight_y", "gamma_star", "camber_combined", "slip_variable",
           "pure_fx", "pure_fy", "LateralSpin"]

#: Small number added to C*D and K_y in the denominators (the textbook's epsilon) [N].
EPS = 1e-6


@dataclass(frozen=True)
class MFCoefficients:
    """The Magic Formula factors at one load (arrays when the load is an array).

    ``E = E_a - E_b * sgn(x)`` with ``x`` the shifted slip (``k_x`` or ``a_y``), limited
    to <= 1 (unless ``cap=False``: MFeval's useModes 2xx).  ``K = B C D`` is the slip
    stiffness [N per unit slip, or N/rad], ``D = mu F_z`` the peak factor [N], ``S_H``
    the horizontal shift [-] or [rad, of tan(alpha)], ``S_V`` the vertical shift [N].
    """

    B: Any
    C: Any
    D: Any
    E_a: Any
    E_b: Any
    K: Any
    S_H: Any
    S_V: Any
    mu: Any

    def E(self, sign: float, cap: bool = True) -> Any:
        """E for a shifted slip of sign ``sign`` (+1 or -1), limited to <= 1 (``cap``)."""
        E = self.E_a - self.E_b * sign
        return np.minimum(E, 1.0) if cap else E

    def as_dict(self) -> dict[str, Any]:
        """The factors by name (E at both signs of the shifted slip)."""
        return {"B": self.B, "C": self.C, "D": self.D, "E_plus": self.E(1.0),
                "E_minus": self.E(-1.0), "K": self.K, "S_H": self.S_H, "S_V": self.S_V,
                "mu": self.mu}

    def curve(self, x: Any, cap: bool = True) -> Any:
        """The curve of these factors at slip ``x`` (shifted by S_H here)."""
        return mf_curve(x + self.S_H, self.B, self.C, self.D, self.E_a, self.E_b, self.S_V,
                        cap)


def mf_curve(x: Any, B: Any, C: Any, D: Any, E_a: Any, E_b: Any, S_V: Any,
             cap: bool = True) -> Any:
    """The Magic Formula sine curve at shifted slip ``x``, S_V added outside the sine;
    the curvature E limited to <= 1 (``cap``, the limit checks)."""
    E = E_a - E_b * np.sign(x)
    if cap:
        E = np.minimum(E, 1.0)
    bx = B * x
    return D * np.sin(C * np.arctan(bx - E * (bx - np.arctan(bx)))) + S_V


def cos_weight(x: Any, B: Any, C: Any, E: Any) -> Any:
    """``cos(C arctan(B x - E (B x - arctan(B x))))``, the combined-slip weighting shape."""
    bx = B * x
    return np.cos(C * np.arctan(bx - E * (bx - np.arctan(bx))))


def gamma_star(p: MFParameters, gamma: Any) -> Any:
    """The camber variable gamma* of the equations: sin(gamma) with ``slip_angle =
    "tan_alpha"`` (the book's starred quantities, eq. 4.E4), gamma itself with
    ``"alpha"`` (both unstarred, as MFeval's "revoke alpha_star" modes)."""
    return np.sin(gamma) if p.slip_angle == "tan_alpha" else np.asarray(gamma)


def camber_combined(p: MFParameters, gamma: Any) -> Any:
    """Camber as the combined-slip terms use it: gamma* (6.x) or gamma LGAY (5.2)."""
    return (gamma_star(p, gamma) if p.six or p.equations == "mfeval"
            else gamma) * (1.0 if p.six else p.c.LGAY)


def slip_variable(p: MFParameters, alpha: Any, vx: Any = None) -> Any:
    """The slip variable of the lateral curve: tan(alpha) or alpha (``slip_angle``);
    tan(alpha) sgn(V_x) at a speed ``vx`` (eq. 4.E3: backwards, 0 at a standing wheel)."""
    if p.slip_angle != "tan_alpha":
        return alpha
    return np.tan(alpha) if vx is None else np.tan(alpha) * np.sign(vx)


@dataclass(frozen=True)
class LateralSpin:
    """What the turn slip does to the lateral curve (:mod:`~frictionlaws.tyre.mf.turn_slip`).

    Attributes
    ----------
    spin : Spin
        The spin of the evaluation.
    vx : numpy.ndarray
        The forward speed [m/s] (the shift takes its sign).
    zeta2, zeta3 : numpy.ndarray
        The reductions of the peak and of the cornering stiffness.
    cap : bool
        Limit the shift's curvature E_Hyp to 1 (the limit checks).
    """

    spin: Spin
    vx: Any
    zeta2: Any
    zeta3: Any
    cap: bool = True


def longitudinal(p: MFParameters, fz: Any, gamma: Any, dpi: Any, zeta: Any = 1.0
                 ) -> MFCoefficients:
    """The factors of F_x0 at load ``fz`` [N], camber ``gamma`` [rad] and pressure
    increment ``dpi`` (eqs. 4.E9-4.E18), the peak and S_V times the turn slip's ``zeta``
    (zeta_1); the peak friction is checked
    (:meth:`~frictionlaws.tyre.mf.parameters.MFParameters.check_peak`)."""
    c = p.c
    dfz = (fz - p.fz0) / p.fz0
    if not p.six:
        g = gamma * c.LGAX
    else:  # MFeval writes gamma itself in PDX3's term; the book gamma* (4.E13)
        g = np.asarray(gamma) if p.equations == "mfeval" else gamma_star(p, gamma)
    mu = ((c.PDX1 + c.PDX2 * dfz) * (1 + c.PPX3 * dpi + c.PPX4 * dpi**2)
          * (1 - c.PDX3 * g**2) * p.lmux)
    p.check_peak("mu_x", mu, fz, dpi, gamma)
    D = mu * fz * zeta
    C = c.PCX1 * c.LCX
    K = (fz * (c.PKX1 + c.PKX2 * dfz) * np.exp(c.PKX3 * dfz)
         * (1 + c.PPX1 * dpi + c.PPX2 * dpi**2) * c.LKX)
    B = K / (C * D + EPS)
    E0 = (c.PEX1 + c.PEX2 * dfz + c.PEX3 * dfz**2) * c.LEX
    S_H = (c.PHX1 + c.PHX2 * dfz) * c.LHX
    S_V = fz * (c.PVX1 + c.PVX2 * dfz) * c.LVX * p.lmux_prime * zeta
    return MFCoefficients(B, C, D, E0, E0 * c.PEX4, K, S_H, S_V, mu)


def lateral(p: MFParameters, fz: Any, gamma: Any, dpi: Any,
            turn: LateralSpin | None = None) -> MFCoefficients:
    """The factors of F_y0 at load ``fz`` [N], camber ``gamma`` [rad] and pressure
    increment ``dpi`` (eqs. 4.E19-4.E30, MF 6.1/6.2 or MF 5.2); with the turn slip
    ``turn`` the peak and S_V times zeta_2, K_y times zeta_3 and, for MF 6.x, the camber's
    shift through the spin (zeta_0 = 0, zeta_4; eq. 4.84).  The peak friction is checked."""
    c = p.c
    dfz = (fz - p.fz0) / p.fz0
    zeta2, zeta3 = (1.0, 1.0) if turn is None else (turn.zeta2, turn.zeta3)
    if p.six:
        mu, K, E_a, E_b, S_H, S_V = _lateral_6x(p, fz, gamma, dpi, dfz, turn)
    else:
        mu, K, E_a, E_b, S_H, S_V = _lateral_52(p, fz, gamma, dpi, dfz)
        K, S_V = K * zeta3, S_V * zeta2
    p.check_peak("mu_y", mu, fz, dpi, gamma)
    C = c.PCY1 * c.LCY
    D = mu * fz * zeta2
    B = K / (C * D + EPS)
    return MFCoefficients(B, C, D, E_a, E_b, K, S_H, S_V, mu)


def _lateral_6x(p: MFParameters, fz: Any, gamma: Any, dpi: Any, dfz: Any,
                turn: LateralSpin | None) -> tuple[Any, ...]:
    """(mu, K, E_a, E_b, S_H, S_V) of MF 6.1/6.2 (with the turn slip's zetas)."""
    c, fz0 = p.c, p.fz0
    zeta2, zeta3 = (1.0, 1.0) if turn is None else (turn.zeta2, turn.zeta3)
    g = gamma_star(p, gamma)
    mu = ((c.PDY1 + c.PDY2 * dfz) * (1 + c.PPY3 * dpi + c.PPY4 * dpi**2)
          * (1 - c.PDY3 * g**2) * p.lmuy)
    K = (c.PKY1 * fz0 * (1 + c.PPY1 * dpi) * (1 - c.PKY3 * np.abs(g))
         * np.sin(c.PKY4 * np.arctan(
             fz / ((c.PKY2 + c.PKY5 * g**2) * (1 + c.PPY2 * dpi) * fz0)))
         * c.LKY * zeta3)
    E0 = (c.PEY1 + c.PEY2 * dfz) * c.LEY
    E_a = E0 * (1 + c.PEY5 * g**2)
    E_b = E0 * (c.PEY3 + c.PEY4 * g)
    K_g0 = fz * (c.PKY6 + c.PKY7 * dfz) * (1 + c.PPY5 * dpi) * c.LKYC
    S_Vg = fz * (c.PVY3 + c.PVY4 * dfz) * g * c.LKYC * p.lmuy_prime * zeta2
    S_V = fz * (c.PVY1 + c.PVY2 * dfz) * c.LVY * p.lmuy_prime * zeta2 + S_Vg
    S_H = (c.PHY1 + c.PHY2 * dfz) * c.LHY
    if turn is None:
        S_H = S_H + (K_g0 * g - S_Vg) / (K + EPS)
    else:  # the camber acts through the spin: zeta_0 = 0, zeta_4 = 1 + S_Hyp - S_Vg / K
        K_0 = (c.PKY1 * fz0 * (1 + c.PPY1 * dpi)
               * np.sin(c.PKY4 * np.arctan(fz / (c.PKY2 * (1 + c.PPY2 * dpi) * fz0)))
               * c.LKY * zeta3)
        S_Hyp = spin_shift(p, turn.spin, turn.vx, dfz, K_0, K_g0, turn.cap)
        S_H = S_H + S_Hyp - S_Vg / (K + EPS)
    return mu, K, E_a, E_b, S_H, S_V


def _lateral_52(p: MFParameters, fz: Any, gamma: Any, dpi: Any, dfz: Any
                ) -> tuple[Any, ...]:
    """(mu, K, E_a, E_b, S_H, S_V) of MF 5.2; MFeval evaluates it with the 6.x forms
    (gamma*, PKY4, PKY5, PEY5, LKYC)."""
    c, fz0 = p.c, p.fz0
    g = camber_combined(p, gamma)
    mfe = p.equations == "mfeval"
    lkyc = c.LKYC if mfe else 1.0
    mu = ((c.PDY1 + c.PDY2 * dfz) * (1 + c.PPY3 * dpi + c.PPY4 * dpi**2)
          * (1 - c.PDY3 * g**2) * p.lmuy)
    pky4, pky5 = (c.PKY4, c.PKY5) if mfe else (2.0, 0.0)
    K = (c.PKY1 * fz0 * (1 + c.PPY1 * dpi)
         * np.sin(pky4 * np.arctan(fz / ((c.PKY2 + pky5 * g**2)
                                         * (1 + c.PPY2 * dpi) * fz0)))
         * (1 - c.PKY3 * np.abs(g)) * c.LKY)
    E0 = (c.PEY1 + c.PEY2 * dfz) * c.LEY
    E_a = E0 * (1 + c.PEY5 * g**2) if mfe else E0
    E_b = E0 * (c.PEY3 + c.PEY4 * g)
    S_H = (c.PHY1 + c.PHY2 * dfz) * c.LHY + c.PHY3 * g * lkyc
    S_V = (fz * ((c.PVY1 + c.PVY2 * dfz) * c.LVY
                 + (c.PVY3 + c.PVY4 * dfz) * g * lkyc) * p.lmuy_prime)
    return mu, K, E_a, E_b, S_H, S_V


def pure_fx(p: MFParameters, kappa: Any, fz: Any, gamma: Any, dpi: Any) -> Any:
    """F_x0 [N] at slip ratio ``kappa`` (eq. 4.E9)."""
    k = longitudinal(p, fz, gamma, dpi)
    return mf_curve(kappa + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)


def pure_fy(p: MFParameters, alpha_s: Any, fz: Any, gamma: Any, dpi: Any) -> Any:
    """F_y0 [N] at the slip variable ``alpha_s`` (tan(alpha) or alpha; eq. 4.E19)."""
    k = lateral(p, fz, gamma, dpi)
    return mf_curve(alpha_s + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)


def weight_x(p: MFParameters, kappa: Any, alpha_s: Any, fz: Any, gamma: Any,
             cap: bool = True) -> Any:
    """G_xa, the combined-slip weighting of F_x, at the slip variable ``alpha_s``
    (eqs. 4.E50-4.E57; E_xa limited to <= 1 with ``cap``)."""
    c = p.c
    dfz = (fz - p.fz0) / p.fz0
    g = camber_combined(p, gamma)
    B = (c.RBX1 + c.RBX3 * g**2) * np.cos(np.arctan(c.RBX2 * kappa)) * c.LXAL
    C = c.RCX1
    E = c.REX1 + c.REX2 * dfz
    E = np.minimum(E, 1.0) if cap else E
    S_H = c.RHX1
    return cos_weight(alpha_s + S_H, B, C, E) / cos_weight(S_H, B, C, E)


def weight_y(p: MFParameters, kappa: Any, alpha_s: Any, fz: Any, gamma: Any, mu_y: Any,
             cap: bool = True, zeta2: Any = 1.0) -> tuple[Any, Any]:
    """(G_yk, S_Vyk): the combined-slip weighting of F_y and the slip-induced shift [N],
    from the peak coefficient ``mu_y`` (eqs. 4.E58-4.E67; E_yk limited to <= 1 with
    ``cap``; the shift's peak times the turn slip's ``zeta2``)."""
    c = p.c
    dfz = (fz - p.fz0) / p.fz0
    g = camber_combined(p, gamma)
    B = ((c.RBY1 + c.RBY4 * g**2) * np.cos(np.arctan(c.RBY2 * (alpha_s - c.RBY3)))
         * c.LYKA)
    C = c.RCY1
    E = c.REY1 + c.REY2 * dfz
    E = np.minimum(E, 1.0) if cap else E
    S_H = c.RHY1 + c.RHY2 * dfz
    G = cos_weight(kappa + S_H, B, C, E) / cos_weight(S_H, B, C, E)
    D_V = (mu_y * fz * (c.RVY1 + c.RVY2 * dfz + c.RVY3 * g)
           * np.cos(np.arctan(c.RVY4 * alpha_s)) * zeta2)
    S_V = D_V * np.sin(c.RVY5 * np.arctan(c.RVY6 * kappa)) * c.LVYKA
    return G, S_V
