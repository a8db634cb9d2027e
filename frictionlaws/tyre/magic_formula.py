"""The Magic Formula (PAC2002 / MF 5.2 and MF 6.1/6.2) for pure slip, from property files.

:class:`MagicFormula` evaluates the steady-state pure-slip forces of a tyre
described by a property file (ADAMS ``.tir`` or its JSON variant, read by
:mod:`frictionlaws.tyre.tir`):

* ``fx0(kappa, fz)``: longitudinal force at slip ratio ``kappa`` (positive when
  driving) and vertical load ``fz`` [N];
* ``fy0(alpha, fz)``: lateral force at slip angle ``alpha`` [rad];
* ``mu_x_peak(fz)``, ``mu_y_peak(fz)``: the peak friction coefficients
  D/F_z;
* ``longitudinal(fz)``, ``lateral(fz)``: the B, C, D, E, K, S_H, S_V factors.

All inputs and outputs are SI and vectorised (numpy broadcasting).  Forces
follow the sign convention of the property file (for TYDEX/ISO files a
positive slip angle gives a negative lateral force: ``PKY1 < 0``).

Equations
---------
Pacejka, *Tire and Vehicle Dynamics* (2nd ed. 2006, 3rd ed. 2012), section 4.3.2,
eqs. (4.E9)-(4.E30); the inflation-pressure terms of MF 6.1 (Besselink,
Schmeitz and Pacejka, Vehicle System Dynamics 48 sup. 1, 2010).  With
``dfz = (F_z - F'_z0)/F'_z0``, ``F'_z0 = FNOMIN * LFZO`` and
``dpi = (p_i - p_nom)/p_nom``::

    F_x0 = D_x sin(C_x arctan(B_x k_x - E_x (B_x k_x - arctan(B_x k_x)))) + S_Vx
    k_x  = kappa + S_Hx
    C_x  = PCX1 LCX
    mu_x = (PDX1 + PDX2 dfz)(1 + PPX3 dpi + PPX4 dpi^2)(1 - PDX3 g_x^2) LMUX
    D_x  = mu_x F_z
    E_x  = (PEX1 + PEX2 dfz + PEX3 dfz^2)(1 - PEX4 sgn(k_x)) LEX        (<= 1)
    K_x  = F_z (PKX1 + PKX2 dfz) exp(PKX3 dfz)(1 + PPX1 dpi + PPX2 dpi^2) LKX
    B_x  = K_x / (C_x D_x + eps)
    S_Hx = (PHX1 + PHX2 dfz) LHX
    S_Vx = F_z (PVX1 + PVX2 dfz) LVX LMUX'

    F_y0 = D_y sin(C_y arctan(B_y a_y - E_y (B_y a_y - arctan(B_y a_y)))) + S_Vy
    a_y  = tan(alpha) + S_Hy
    C_y  = PCY1 LCY
    mu_y = (PDY1 + PDY2 dfz)(1 + PPY3 dpi + PPY4 dpi^2)(1 - PDY3 g_y^2) LMUY
    D_y  = mu_y F_z
    B_y  = K_y / (C_y D_y + eps)

The vertical shift S_V is added **outside** the sine.  The version-specific
terms are:

* **MF 5.2 / PAC2002** (``FITTYP`` 5, 6, 21 or ``PROPERTY_FILE_FORMAT='PAC2002'``):
  camber g_x = gamma LGAX, g_y = gamma LGAY;
  ``K_y = PKY1 F'z0 (1 + PPY1 dpi) sin(2 arctan(F_z / (PKY2 F'z0 (1 + PPY2 dpi))))
  (1 - PKY3 |g_y|) LKY``;
  ``E_y = (PEY1 + PEY2 dfz)(1 - (PEY3 + PEY4 g_y) sgn(a_y)) LEY``;
  ``S_Hy = (PHY1 + PHY2 dfz) LHY + PHY3 g_y``;
  ``S_Vy = F_z ((PVY1 + PVY2 dfz) LVY + (PVY3 + PVY4 dfz) g_y) LMUY``;
  LMUX' = LMUX, LMUY' = LMUY.
* **MF 6.1 / 6.2** (``FITTYP`` 61, 62): camber g = sin(gamma);
  ``K_y = PKY1 F'z0 (1 + PPY1 dpi)(1 - PKY3 |g|) sin(PKY4 arctan(F_z /
  ((PKY2 + PKY5 g^2)(1 + PPY2 dpi) F'z0))) LKY``;
  ``E_y = (PEY1 + PEY2 dfz)(1 + PEY5 g^2 - (PEY3 + PEY4 g) sgn(a_y)) LEY``;
  ``K_yg0 = F_z (PKY6 + PKY7 dfz)(1 + PPY5 dpi) LKYC``;
  ``S_Vyg = F_z (PVY3 + PVY4 dfz) g LKYC LMUY'``;
  ``S_Vy = F_z (PVY1 + PVY2 dfz) LVY LMUY' + S_Vyg``;
  ``S_Hy = (PHY1 + PHY2 dfz) LHY + (K_yg0 g - S_Vyg) / (K_y + eps)``;
  the degressive friction scaling ``LMU' = A LMU / (1 + (A - 1) LMU)`` with
  A = 10 (equal to LMU when LMU = 1).

Simplifications, stated: pure slip only (no combined-slip weighting G), no
turn slip (all zeta = 1), no speed dependence of friction (LMUV ignored: the
steady-state curves are for the file's measurement speed ``LONGVL``), the
slip angle enters as tan(alpha) in both versions (the 2006 book's alpha*;
some PAC2002 codes use alpha itself, which differs by less than 0.3 % below
5 degrees).  Absent coefficients are 0, absent scaling factors 1.  E is
limited to <= 1 as the textbook requires.  Pressure terms are used whenever
the file has them (PAC2002 files may carry PPX/PPY too) with the pressure
from ``[OPERATING_CONDITIONS] INFLPRES`` (MF 6.x) or ``[TIRE_CONDITIONS] IP``
(PAC2002), or the ``pressure=`` argument.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import ExtrapolationWarning, InputError
from .tir import PropertyFile, read_property_file

__all__ = ["MagicFormula", "MFCoefficients", "mf_curve", "MF_VERSIONS"]

MF_VERSIONS = ("5.2", "6.1", "6.2")
#: Small number added to C*D and K_y in the denominators (the textbook's epsilon) [N].
EPS = 1e-6
#: Degressive friction-scaling constant A_mu of MF 6.1.
A_MU = 10.0

_SCALING_DEFAULT = 1.0


@dataclass(frozen=True)
class MFCoefficients:
    """The Magic Formula factors at one load (arrays when the load is an array).

    ``E = E_a - E_b * sgn(x)`` with ``x`` the shifted slip (``k_x`` or
    ``a_y``), limited to <= 1.  ``K = B C D`` is the slip stiffness [N per
    unit slip, or N/rad], ``D = mu F_z`` the peak factor [N], ``S_H`` the
    horizontal shift [-] or [rad, of tan(alpha)], ``S_V`` the vertical shift [N].
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

    def E(self, sign: float) -> Any:
        """E for a shifted slip of sign ``sign`` (+1 or -1), limited to <= 1."""
        return np.minimum(self.E_a - self.E_b * sign, 1.0)

    def as_dict(self) -> dict[str, Any]:
        return {"B": self.B, "C": self.C, "D": self.D, "E_plus": self.E(1.0),
                "E_minus": self.E(-1.0), "K": self.K, "S_H": self.S_H, "S_V": self.S_V,
                "mu": self.mu}


def mf_curve(x: Any, B: Any, C: Any, D: Any, E_a: Any, E_b: Any, S_V: Any) -> Any:
    """The Magic Formula sine curve at shifted slip ``x``, S_V added outside the sine."""
    E = np.minimum(E_a - E_b * np.sign(x), 1.0)
    bx = B * x
    return D * np.sin(C * np.arctan(bx - E * (bx - np.arctan(bx)))) + S_V


def _version_of(pf: PropertyFile) -> tuple[str, str]:
    """(version, how it was decided) from FITTYP / PROPERTY_FILE_FORMAT / the coefficients."""
    fittyp = pf.get("MODEL", "FITTYP")
    fmt = (pf.text("MODEL", "PROPERTY_FILE_FORMAT", "") or "").upper()
    if fittyp is not None:
        known = {61: "6.1", 62: "6.2", 5: "5.2", 6: "5.2", 21: "5.2"}
        if not isinstance(fittyp, float) or fittyp not in known:
            raise InputError(
                f"[MODEL] FITTYP = {pf.text('MODEL', 'FITTYP')}: not a Magic Formula "
                "version evaluated here (5, 6 or 21: MF 5.2 / PAC2002; 61: MF 6.1; "
                "62: MF 6.2)", file=pf.path,
                row=pf.lines.get(("MODEL", "FITTYP")))
        return known[int(fittyp)], f"FITTYP = {int(fittyp)}"
    if "PAC2002" in fmt or "MF_05" in fmt:
        return "5.2", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if "MF_61" in fmt or "MF61" in fmt:
        return "6.1", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if "MF_62" in fmt or "MF62" in fmt:
        return "6.2", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if pf.has("LATERAL_COEFFICIENTS", "PKY4"):
        return "6.1", "no FITTYP; PKY4 present, so the MF 6.1 equations were assumed"
    return "5.2", "no FITTYP; the MF 5.2 / PAC2002 equations were assumed"


class MagicFormula:
    """Pure-slip Magic Formula of one tyre (PAC2002 / MF 5.2 or MF 6.1/6.2).

    Parameters
    ----------
    coefficients : mapping
        Coefficient name (``PCX1``, ``PDY2``, ``LMUX``...) -> value.  Absent
        coefficients are 0 and absent scaling factors (``L...``) are 1.
    fnomin : float
        Nominal load F_z0 [N] (``[VERTICAL] FNOMIN``).
    version : {"5.2", "6.1", "6.2"}
        Equation set (see the module documentation).
    pressure, nominal_pressure : float, optional
        Inflation pressure and nominal pressure [Pa]; when either is missing
        the pressure terms vanish (dpi = 0) unless ``pressure=`` is given at
        evaluation together with a nominal pressure.
    limits : mapping, optional
        Validity ranges from the file: ``fz``, ``kappa``, ``alpha``, ``gamma``,
        ``pressure`` -> (low, high) in SI.  Evaluating outside them warns
        (:class:`~frictionlaws.errors.ExtrapolationWarning`).
    name, source : str
        Labels for reports.
    notes : list of str
        How the version was decided, conversions made.
    """

    def __init__(self, coefficients: Mapping[str, float], *, fnomin: float,
                 version: str = "5.2", pressure: float | None = None,
                 nominal_pressure: float | None = None,
                 limits: Mapping[str, tuple[float, float]] | None = None,
                 name: str = "", source: str = "<memory>",
                 notes: list[str] | None = None) -> None:
        if version not in MF_VERSIONS:
            raise InputError(f"unknown Magic Formula version {version!r}; expected one of "
                             f"{', '.join(MF_VERSIONS)}", file=source)
        if not (math.isfinite(fnomin) and fnomin > 0):
            raise InputError(f"FNOMIN must be a positive load in N, got {fnomin}", file=source)
        self.coefficients = {k.upper(): float(v) for k, v in coefficients.items()}
        for k, v in self.coefficients.items():
            if not math.isfinite(v):
                raise InputError(f"coefficient {k} is not finite", file=source)
        self.fnomin = float(fnomin)
        self.version = version
        self.pressure = None if pressure is None else float(pressure)
        self.nominal_pressure = None if nominal_pressure is None else float(nominal_pressure)
        if self.nominal_pressure is not None and not (
                math.isfinite(self.nominal_pressure) and self.nominal_pressure > 0):
            raise InputError("the nominal inflation pressure must be positive", file=source)
        if self.pressure is not None and not (math.isfinite(self.pressure) and self.pressure > 0):
            raise InputError(f"the inflation pressure must be a positive number of Pa, got "
                             f"{self.pressure:g}", file=source)
        self.limits = dict(limits or {})
        self.name = name
        self.source = source
        self.notes = list(notes or [])
        c = self._c
        if c("LFZO", 1.0) <= 0:
            raise InputError("LFZO must be positive", file=source)
        self.fz0 = self.fnomin * c("LFZO", 1.0)  # F'z0
        six = version.startswith("6")
        self._six = six
        self.lmux = c("LMUX", 1.0)
        self.lmuy = c("LMUY", 1.0)
        self.lmux_prime = A_MU * self.lmux / (1 + (A_MU - 1) * self.lmux) if six else self.lmux
        self.lmuy_prime = A_MU * self.lmuy / (1 + (A_MU - 1) * self.lmuy) if six else self.lmuy

    # ----------------------------------------------------------- construction
    def _c(self, name: str, default: float | None = None) -> float:
        if default is None:
            default = _SCALING_DEFAULT if name.startswith("L") else 0.0
        return self.coefficients.get(name, default)

    @classmethod
    def from_file(cls, path: str | Path, *, version: str | None = None,
                  pressure: float | None = None) -> MagicFormula:
        """Read a ``.tir`` or JSON property file.

        Parameters
        ----------
        path : str or Path
            The property file.  A packaged example name (``"MagicFormula62"``,
            see ``datasets/mf-examples``) is accepted too.
        version : {"5.2", "6.1", "6.2"}, optional
            Override the equation set detected from ``FITTYP``.
        pressure : float, optional
            Inflation pressure [Pa] (default: the file's INFLPRES / IP).
        """
        p = Path(path)
        if not p.exists():
            packaged = _packaged_example(str(path))
            if packaged is not None:
                p = packaged
        pf = read_property_file(p)
        return cls.from_property_file(pf, version=version, pressure=pressure)

    @classmethod
    def from_property_file(cls, pf: PropertyFile, *, version: str | None = None,
                           pressure: float | None = None) -> MagicFormula:
        """Build from an already read :class:`~frictionlaws.tyre.tir.PropertyFile`."""
        pf.check_angle_unit()
        notes = pf.check_coefficients()
        if version is None:
            version, how = _version_of(pf)
            notes.append(f"Magic Formula {version} equations ({how})")
        elif version not in MF_VERSIONS:
            raise InputError(f"unknown Magic Formula version {version!r}; expected one of "
                             f"{', '.join(MF_VERSIONS)}", file=pf.path)
        if not pf.has("VERTICAL", "FNOMIN"):
            raise InputError("[VERTICAL] FNOMIN (nominal load) is missing", file=pf.path)
        fnomin = pf.si("VERTICAL", "FNOMIN")
        coeffs = pf.coefficients("SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS",
                                 "LATERAL_COEFFICIENTS")
        for need in ("PCX1", "PDX1", "PKX1", "PCY1", "PDY1", "PKY1"):
            if need not in coeffs:
                sec = "LONGITUDINAL" if "X" in need[2:] else "LATERAL"
                raise InputError(f"[{sec}_COEFFICIENTS] {need} is missing: not a Magic "
                                 "Formula property file?", file=pf.path)
        p_i = p_nom = None
        for sec, key, nom in (("OPERATING_CONDITIONS", "INFLPRES", "NOMPRES"),
                              ("TIRE_CONDITIONS", "IP", "IP_NOM")):
            if pf.has(sec, key) or pf.has(sec, nom):
                p_i = pf.si(sec, key) if pf.has(sec, key) else None
                p_nom = pf.si(sec, nom) if pf.has(sec, nom) else None
                break
        if p_nom is None and p_i is not None:
            p_nom = p_i
            notes.append("no nominal pressure in the file: the inflation pressure is taken "
                         "as nominal (dpi = 0)")
        limits = {}
        for name, sec, lo, hi, kind in (
                ("fz", "VERTICAL_FORCE_RANGE", "FZMIN", "FZMAX", True),
                ("kappa", "LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", False),
                ("alpha", "SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", False),
                ("gamma", "INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", False),
                ("pressure", "INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX", True)):
            if pf.has(sec, lo) and pf.has(sec, hi):
                limits[name] = ((pf.si(sec, lo), pf.si(sec, hi)) if kind
                                else (pf.number(sec, lo), pf.number(sec, hi)))
        name = str(pf.metadata.get("Name") or Path(pf.path).stem)
        return cls(coeffs, fnomin=fnomin, version=version,
                   pressure=pressure if pressure is not None else p_i,
                   nominal_pressure=p_nom, limits=limits, name=name, source=pf.path,
                   notes=notes)

    # ------------------------------------------------------------- helpers
    def _dpi(self, pressure: float | None) -> float:
        p = self.pressure if pressure is None else float(pressure)
        if p is None or self.nominal_pressure is None:
            return 0.0
        if not (math.isfinite(p) and p > 0):
            raise InputError(f"inflation pressure must be positive [Pa], got {p}")
        return (p - self.nominal_pressure) / self.nominal_pressure

    def _check(self, what: str, x: Any, positive: bool = False) -> Any:
        x = np.asarray(x, dtype=float)
        ok = (x > 0).all() if positive else np.isfinite(x).all()
        if not ok:
            bad = ~(x > 0) if positive else ~np.isfinite(x)
            idx = np.flatnonzero(bad.ravel())[:5].tolist()
            need = "positive finite loads [N]" if positive else "finite values"
            raise InputError(f"{what} must hold {need}; bad values at flat indices {idx}")
        if positive and not np.isfinite(x).all():
            raise InputError(f"{what} must be finite")
        return x

    def _warn_range(self, name: str, x: Any) -> None:
        lim = self.limits.get(name)
        if lim is None:
            return
        lo, hi = lim
        xmin, xmax = float(np.min(x)), float(np.max(x))
        if xmin < lo - 1e-12 * abs(lo) or xmax > hi + 1e-12 * abs(hi):
            warnings.warn(
                f"{self.name or 'Magic Formula'}: {name} from {xmin:g} to {xmax:g} lies "
                f"outside the property file's range {lo:g}..{hi:g} (SI): extrapolation",
                ExtrapolationWarning, stacklevel=3)

    def _inputs(self, fz: Any, gamma: Any, pressure: float | None) -> tuple[Any, Any, float]:
        fz = self._check("fz", fz, positive=True)
        self._warn_range("fz", fz)
        gamma = np.asarray(gamma, dtype=float)
        if gamma.ndim or gamma != 0.0:
            self._check("gamma", gamma)
            self._warn_range("gamma", gamma)
        if pressure is not None:
            self._warn_range("pressure", np.asarray(float(pressure)))
        return fz, gamma, self._dpi(pressure)

    # ------------------------------------------------------ factors (x, y)
    def _long(self, fz: Any, gamma: Any, dpi: float) -> MFCoefficients:
        c = self._c
        dfz = (fz - self.fz0) / self.fz0
        g = np.sin(gamma) if self._six else gamma * c("LGAX")
        mu = ((c("PDX1") + c("PDX2") * dfz) * (1 + c("PPX3") * dpi + c("PPX4") * dpi**2)
              * (1 - c("PDX3") * g**2) * self.lmux)
        D = mu * fz
        C = c("PCX1") * c("LCX")
        K = (fz * (c("PKX1") + c("PKX2") * dfz) * np.exp(c("PKX3") * dfz)
             * (1 + c("PPX1") * dpi + c("PPX2") * dpi**2) * c("LKX"))
        B = K / (C * D + EPS)
        E0 = (c("PEX1") + c("PEX2") * dfz + c("PEX3") * dfz**2) * c("LEX")
        S_H = (c("PHX1") + c("PHX2") * dfz) * c("LHX")
        S_V = fz * (c("PVX1") + c("PVX2") * dfz) * c("LVX") * self.lmux_prime
        return MFCoefficients(B, C, D, E0, E0 * c("PEX4"), K, S_H, S_V, mu)

    def _lat(self, fz: Any, gamma: Any, dpi: float) -> MFCoefficients:
        c = self._c
        fz0 = self.fz0
        dfz = (fz - fz0) / fz0
        C = c("PCY1") * c("LCY")
        if self._six:
            g = np.sin(gamma)
            mu = ((c("PDY1") + c("PDY2") * dfz) * (1 + c("PPY3") * dpi + c("PPY4") * dpi**2)
                  * (1 - c("PDY3") * g**2) * self.lmuy)
            K = (c("PKY1") * fz0 * (1 + c("PPY1") * dpi) * (1 - c("PKY3") * np.abs(g))
                 * np.sin(c("PKY4", 2.0) * np.arctan(
                     fz / ((c("PKY2") + c("PKY5") * g**2) * (1 + c("PPY2") * dpi) * fz0)))
                 * c("LKY"))
            E0 = (c("PEY1") + c("PEY2") * dfz) * c("LEY")
            E_a = E0 * (1 + c("PEY5") * g**2)
            E_b = E0 * (c("PEY3") + c("PEY4") * g)
            K_g0 = fz * (c("PKY6") + c("PKY7") * dfz) * (1 + c("PPY5") * dpi) * c("LKYC")
            S_Vg = fz * (c("PVY3") + c("PVY4") * dfz) * g * c("LKYC") * self.lmuy_prime
            S_V = fz * (c("PVY1") + c("PVY2") * dfz) * c("LVY") * self.lmuy_prime + S_Vg
            S_H = (c("PHY1") + c("PHY2") * dfz) * c("LHY") + (K_g0 * g - S_Vg) / (K + EPS)
        else:
            g = gamma * c("LGAY")
            mu = ((c("PDY1") + c("PDY2") * dfz) * (1 + c("PPY3") * dpi + c("PPY4") * dpi**2)
                  * (1 - c("PDY3") * g**2) * self.lmuy)
            K = (c("PKY1") * fz0 * (1 + c("PPY1") * dpi)
                 * np.sin(2.0 * np.arctan(fz / (c("PKY2") * (1 + c("PPY2") * dpi) * fz0)))
                 * (1 - c("PKY3") * np.abs(g)) * c("LKY"))
            E0 = (c("PEY1") + c("PEY2") * dfz) * c("LEY")
            E_a = E0
            E_b = E0 * (c("PEY3") + c("PEY4") * g)
            S_H = (c("PHY1") + c("PHY2") * dfz) * c("LHY") + c("PHY3") * g
            S_V = (fz * ((c("PVY1") + c("PVY2") * dfz) * c("LVY")
                         + (c("PVY3") + c("PVY4") * dfz) * g) * self.lmuy_prime)
        D = mu * fz
        B = K / (C * D + EPS)
        return MFCoefficients(B, C, D, E_a, E_b, K, S_H, S_V, mu)

    # -------------------------------------------------------------- public
    def longitudinal(self, fz: Any, gamma: Any = 0.0,
                     pressure: float | None = None) -> MFCoefficients:
        """The longitudinal factors B_x, C_x, D_x, E_x, K_x, S_Hx, S_Vx at load ``fz`` [N]."""
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        return self._long(fz, gamma, dpi)

    def lateral(self, fz: Any, gamma: Any = 0.0, pressure: float | None = None
                ) -> MFCoefficients:
        """The lateral factors B_y, C_y, D_y, E_y, K_y, S_Hy, S_Vy at load ``fz`` [N].

        ``K_y`` is the cornering stiffness [N/rad] and ``S_Hy`` a shift of tan(alpha).
        """
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        return self._lat(fz, gamma, dpi)

    def fx0(self, kappa: Any, fz: Any, gamma: Any = 0.0, pressure: float | None = None) -> Any:
        """Pure longitudinal force F_x0 [N].

        Parameters
        ----------
        kappa : array-like
            Longitudinal slip ratio (positive when driving, -1 = locked wheel).
        fz : array-like
            Vertical load [N] (> 0); broadcast against ``kappa``.
        gamma : array-like
            Inclination (camber) angle [rad].
        pressure : float, optional
            Inflation pressure [Pa] (default: the file's).

        Returns
        -------
        float or numpy.ndarray
        """
        kappa = self._check("kappa", kappa)
        self._warn_range("kappa", kappa)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        k = self._long(fz, gamma, dpi)
        out = mf_curve(kappa + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
        return float(out) if np.ndim(out) == 0 else out

    def fy0(self, alpha: Any, fz: Any, gamma: Any = 0.0, pressure: float | None = None) -> Any:
        """Pure lateral force F_y0 [N] at slip angle ``alpha`` [rad] and load ``fz`` [N].

        The slip enters as tan(alpha) (see the module notes); ``gamma`` is the
        inclination angle [rad].
        """
        alpha = self._check("alpha", alpha)
        self._warn_range("alpha", alpha)
        if np.any(np.abs(alpha) >= np.pi / 2):
            raise InputError("slip angles must lie strictly between -90 and 90 degrees")
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        k = self._lat(fz, gamma, dpi)
        out = mf_curve(np.tan(alpha) + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
        return float(out) if np.ndim(out) == 0 else out

    def mu_x_peak(self, fz: Any, gamma: Any = 0.0, pressure: float | None = None) -> Any:
        """Peak longitudinal friction coefficient mu_x = D_x / F_z [-]."""
        mu = self.longitudinal(fz, gamma, pressure).mu
        return float(mu) if np.ndim(mu) == 0 else mu

    def mu_y_peak(self, fz: Any, gamma: Any = 0.0, pressure: float | None = None) -> Any:
        """Peak lateral friction coefficient mu_y = D_y / F_z [-]."""
        mu = self.lateral(fz, gamma, pressure).mu
        return float(mu) if np.ndim(mu) == 0 else mu

    def slip_stiffness(self, fz: Any, gamma: Any = 0.0, pressure: float | None = None) -> Any:
        """Longitudinal slip stiffness K_x = dF_x0/dkappa at the shifted origin [N]."""
        K = self.longitudinal(fz, gamma, pressure).K
        return float(K) if np.ndim(K) == 0 else K

    def cornering_stiffness(self, fz: Any, gamma: Any = 0.0,
                            pressure: float | None = None) -> Any:
        """Cornering stiffness K_y = dF_y0/d(tan alpha) at the shifted origin [N/rad]."""
        K = self.lateral(fz, gamma, pressure).K
        return float(K) if np.ndim(K) == 0 else K

    def summary(self, loads: Any = None) -> dict[str, Any]:
        """A JSON-able summary: version, nominal load, peaks and stiffnesses at ``loads`` [N]."""
        loads = np.atleast_1d(np.asarray(
            loads if loads is not None else [0.5 * self.fnomin, self.fnomin,
                                             1.5 * self.fnomin], float))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", ExtrapolationWarning)
            lon = self.longitudinal(loads)
            lat = self.lateral(loads)
        return {
            "name": self.name, "source": self.source, "version": self.version,
            "fnomin_N": self.fnomin, "pressure_Pa": self.pressure,
            "nominal_pressure_Pa": self.nominal_pressure,
            "limits_SI": {k: list(v) for k, v in self.limits.items()},
            "loads_N": loads.tolist(),
            "mu_x_peak": np.broadcast_to(lon.mu, loads.shape).tolist(),
            "mu_y_peak": np.broadcast_to(lat.mu, loads.shape).tolist(),
            "K_x_N": np.broadcast_to(lon.K, loads.shape).tolist(),
            "K_y_N_per_rad": np.broadcast_to(lat.K, loads.shape).tolist(),
            "notes": list(self.notes),
        }

    def __repr__(self) -> str:
        return (f"<MagicFormula {self.name!r} MF {self.version}, FNOMIN {self.fnomin:g} N>")


#: Packaged example property files (``datasets/mf-examples``), by short name.
EXAMPLES = {
    "magicformula52": "MagicFormula52_Parameters.json",
    "magicformula61": "MagicFormula61_Parameters.json",
    "magicformula62": "MagicFormula62_Parameters.json",
}


def _packaged_example(name: str) -> Path | None:
    """Path of a packaged example property file named ``name`` (with or without suffix)."""
    key = Path(name).name.lower()
    for suffix in (".json", ".tir"):
        key = key.removesuffix(suffix)
    key = key.removesuffix("_parameters")
    fname = EXAMPLES.get(key)
    candidates = [fname] if fname else []
    if Path(name).name != name:
        return None
    candidates.append(Path(name).name)
    try:
        from ..io import datasets_dir

        root = datasets_dir() / "mf-examples"
        for cand in candidates:
            p = root / cand
            if p.is_file():
                return Path(str(p))
    except (ModuleNotFoundError, FileNotFoundError):
        return None
    return None
