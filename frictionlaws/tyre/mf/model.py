"""The Magic Formula (PAC2002 / MF 5.2 and MF 6.1/6.2), pure and combined slip, from property files.

:class:`MagicFormula` evaluates the steady-state pure-slip forces of a tyre
described by a property file (ADAMS ``.tir`` or its JSON variant, read by
:mod:`frictionlaws.tyre.mf.tir`):

* ``fx0(kappa, fz)``: longitudinal force at slip ratio ``kappa`` (positive when
  driving) and vertical load ``fz`` [N];
* ``fy0(alpha, fz)``: lateral force at slip angle ``alpha`` [rad];
* ``mu_x_peak(fz)``, ``mu_y_peak(fz)``: the peak friction coefficients
  D/F_z;
* ``longitudinal(fz)``, ``lateral(fz)``: the B, C, D, E, K, S_H, S_V factors;
* ``fx(kappa, alpha, fz)``, ``fy(kappa, alpha, fz)``: combined-slip forces.

All inputs and outputs are SI and vectorised (numpy broadcasting).  Forces
follow the sign convention of the property file (for TYDEX/ISO files a
positive slip angle gives a negative lateral force: ``PKY1 < 0``).

Equations
---------
The equations themselves are plain functions of the checked parameters in
:mod:`frictionlaws.tyre.mf.equations` (forces), :mod:`~frictionlaws.tyre.mf.moments` and
:mod:`~frictionlaws.tyre.mf.vertical`; :class:`MagicFormula` checks its inputs once
(:class:`~frictionlaws.tyre.mf.parameters.MFParameters`) and hands on to them.

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
  camber g_x = gamma LGAX, g_y = gamma LGAY (``equations="published"``; see below);
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
  the friction scaling of the vertical shifts LMU' (``friction_scaling`` below).

Combined slip (``fx(kappa, alpha, fz)``, ``fy(...)``) multiplies the pure-slip
forces by the cosine weighting functions of eqs. (4.E50)-(4.E67):
``F_x = G_xa F_x0`` and ``F_y = G_yk F_y0 + S_Vyk`` (see :meth:`MagicFormula.weight_x`
and :meth:`MagicFormula.weight_y`); MF 5.2 uses the same equations with
``g = gamma LGAY`` and without RBX3/RBY4.

Conventions, each an option named after what it means (defaults first):

* ``slip_angle``: ``"tan_alpha"`` (the book's alpha* = tan(alpha); MFeval
  useMode +20) or ``"alpha"`` (the angle itself; MFeval useMode +10 and
  several PAC2002 codes; the two differ by < 0.3 % below 5 degrees, by up to
  ~5 % of F_y0 at 25-30 degrees);
* ``friction_scaling``: ``"linear"`` (LMU' = LMU, i.e. A = 1 in eq. 4.E8: MFeval 4.0,
  whose authors set A = 1 to match TNO's evaluator) or ``"degressive"`` (MF 6.x
  ``LMU' = A LMU / (1 + (A-1) LMU)`` with A = 10, the value Pacejka 2012 suggests);
  identical when LMUX = LMUY = 1, and MF 5.2 is always linear;
* ``loads_above_fzmax``: ``"extrapolate"`` (the equations at the given load,
  with an :class:`~frictionlaws.base.errors.ExtrapolationWarning`) or ``"clamp"``
  (evaluated at FZMAX, as MFeval's limit checks do);
* ``equations``: ``"mfeval"`` (MFeval 4.0's forms where they depart from the
  published ones; its authors matched them to TNO's evaluator) or ``"published"``.
  In the forces: PDX3's camber term in gamma (MFeval) or gamma* (eq. 4.E13); for
  MF 5.2 the lateral and combined-slip camber g_y = gamma* LGAY with LKYC on PHY3,
  PVY3 and PVY4 and the 6.x PKY4, PKY5, PEY5 (MFeval, which evaluates MF 5.2 with
  the 6.x forms; gamma* = sin(gamma) with ``slip_angle="tan_alpha"``) or
  g_y = gamma LGAY (MF-Tyre 5.2).  The moments' differences are listed in
  :mod:`frictionlaws.tyre.mf.outputs`.

Turn slip (``turn_slip=True`` with the path curvature ``phit``), low speed, running
backwards, a given wheel speed and MFeval's useModes 2xx are options of
:meth:`MagicFormula.steady_state` (and ``phit``, ``turn_slip`` of the force and moment
methods, at LONGVL): :mod:`~frictionlaws.tyre.mf.turn_slip`,
:mod:`~frictionlaws.tyre.mf.conditions`.  Simplifications, stated: no speed dependence of
friction (LMUV ignored: the steady-state curves are for the file's measurement speed
``LONGVL``).  Absent coefficients are 0, absent scaling factors 1.  E is limited to <= 1
as the textbook requires (unless ``limit_checks=False``).  Pressure terms are used whenever
the file has them (PAC2002 files may carry PPX/PPY too) with the pressure
from ``[OPERATING_CONDITIONS] INFLPRES`` (MF 6.x) or ``[TIRE_CONDITIONS] IP``
(PAC2002), or the ``pressure=`` argument; a file with a nominal pressure but no
INFLPRES is evaluated at the nominal pressure (dpi = 0), with a note.  A file without
a nominal pressure has no pressure terms: a ``pressure=`` given then warns (it cannot
change the outputs), and the pressure terms it holds are noted as not used.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from ...base.errors import InputError
from .coefficients import listing
from .equations import (
    MFCoefficients,
    gamma_star,
    lateral,
    longitudinal,
    mf_curve,
    pure_fx,
    slip_variable,
    weight_x,
    weight_y,
)
from .labelled import is_labelled, labelled
from .outputs import (
    aligning_moment,
    coefficient_users,
    labelled_steady_state,
    steady_state,
    tyre_summary,
)
from .parameters import (
    EQUATIONS,
    FRICTION_SCALINGS,
    LOADS_ABOVE_FZMAX,
    MF_VERSIONS,
    SLIP_ANGLE_INPUTS,
    MFParameters,
)
from .property_file import PropertyFile, model_inputs
from .tir import EXAMPLES, open_property_file, packaged_example

__all__ = ["MagicFormula", "MFCoefficients", "mf_curve", "MF_VERSIONS", "SLIP_ANGLE_INPUTS",
           "FRICTION_SCALINGS", "LOADS_ABOVE_FZMAX", "EQUATIONS", "EXAMPLES", "packaged_example"]


class MagicFormula(MFParameters):
    """Pure-slip Magic Formula of one tyre (PAC2002 / MF 5.2 or MF 6.1/6.2).

    Parameters
    ----------
    coefficients : mapping
        Coefficient name (``PCX1``, ``PDY2``, ``LMUX``...) -> value.  Absent ones take
        their declared default (:mod:`~frictionlaws.tyre.mf.declarations`: 0, scaling
        factors 1); values outside their declared bounds are refused.
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
        (:class:`~frictionlaws.base.errors.ExtrapolationWarning`).
    name, source : str
        Labels for reports.
    notes : list of str
        How the version was decided, conversions made.
    slip_angle : {"tan_alpha", "alpha"}
        How the slip angle enters the lateral curve (default ``tan_alpha``, the
        book's alpha* = tan(alpha); ``alpha`` uses the angle itself).
    friction_scaling : {"linear", "degressive"}
        MF 6.x friction scaling of the vertical shifts: ``linear`` (default,
        LMU' = LMU, A = 1, as MFeval 4.0) or ``degressive`` (LMU' = A LMU /
        (1 + (A - 1) LMU) with A = 10, as Pacejka 2012 suggests).  MF 5.2 always
        uses LMU' = LMU.
    loads_above_fzmax : {"extrapolate", "clamp"}
        Loads above the file's ``FZMAX``: evaluated as given with an
        :class:`~frictionlaws.base.errors.ExtrapolationWarning` (default) or clamped
        to FZMAX (as MFeval's limit checks do).
    equations : {"mfeval", "published"}
        Where MFeval 4.0 departs from the published equations (the camber in PDX3's
        term, MF 5.2's camber variable, LFZO in the trail, the side-force shift in MF
        5.2's M_z; see the module notes): MFeval's forms (default) or the published ones.
    structure : mapping, optional
        The file's dimensions, vertical and structural stiffnesses, contact-patch
        coefficients and reference speeds (``UNLOADED_RADIUS``, ``VERTICAL_STIFFNESS``,
        ``LONGVL``...), SI, used by :meth:`steady_state`.
    """

    @classmethod
    def from_file(cls, path: str | Path, *, version: str | None = None,
                  pressure: float | None = None, **options: str) -> MagicFormula:
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
        **options : str
            ``slip_angle``, ``friction_scaling``, ``loads_above_fzmax``, ``equations``
            (see the class documentation).
        """
        return cls.from_property_file(open_property_file(path), version=version,
                                      pressure=pressure, **options)

    @classmethod
    def from_property_file(cls, pf: PropertyFile, *, version: str | None = None,
                           pressure: float | None = None, **options: str) -> MagicFormula:
        """Build from an already read :class:`~frictionlaws.tyre.mf.property_file.PropertyFile`.

        Parameters
        ----------
        pf : PropertyFile
            The property file.
        version : {"5.2", "6.1", "6.2"}, optional
            Override the equation set detected from ``FITTYP``.
        pressure : float, optional
            Inflation pressure [Pa] (default: the file's INFLPRES / IP).
        **options : str
            ``slip_angle``, ``friction_scaling``, ``loads_above_fzmax``, ``equations``
            (see the class documentation).

        Returns
        -------
        MagicFormula
            The tyre, with notes of how the version and the pressures were decided.

        Raises
        ------
        InputError
            For a missing FNOMIN or pure-slip coefficient, an unknown version, an
            angle unit other than radians, or a range whose MIN is above its MAX.
        """
        if version is not None and version not in MF_VERSIONS:
            raise InputError(f"unknown Magic Formula version {version!r}; expected one of "
                             f"{', '.join(MF_VERSIONS)}", file=pf.path)
        kw = model_inputs(pf, version)
        if pressure is not None:
            kw["pressure"] = pressure
        kw.update(options)
        return cls(**kw)

    # ------------------------------------------------------------- inputs
    def _inputs(self, fz: Any, gamma: Any, pressure: Any) -> tuple[Any, Any, Any]:
        """Checked load, camber and pressure increment (warned outside the file's ranges;
        the load clamped at FZMAX with ``loads_above_fzmax="clamp"``)."""
        fz, _ = self.limit_loads(self.check("fz", fz, positive=True))
        gamma = np.asarray(gamma, dtype=float)
        if gamma.ndim or gamma != 0.0:
            self.check("gamma", gamma)
            self.warn_range("gamma", gamma)
        dpi = self.dpi(pressure)  # refuses a pressure no tyre runs at, before any warning
        used = self.pressure if pressure is None else pressure  # the file's INFLPRES too
        if used is not None:
            self.warn_range("pressure", np.asarray(used, dtype=float))
        return fz, gamma, dpi

    def _kappa(self, kappa: Any) -> Any:
        """The checked slip ratio (warned outside the file's range)."""
        kappa = self.check("kappa", kappa)
        self.warn_range("kappa", kappa)
        return kappa

    def _alpha_star(self, alpha: Any) -> Any:
        """The slip variable of the lateral curve from a checked slip angle."""
        alpha = self.check("alpha", alpha)
        self.warn_range("alpha", alpha)
        if np.any(np.abs(alpha) >= np.pi / 2):
            raise InputError("slip angles must lie strictly between -90 and 90 degrees")
        return slip_variable(self, alpha)

    # -------------------------------------------------------------- public
    def longitudinal(self, fz: Any, gamma: Any = 0.0,
                     pressure: Any = None) -> MFCoefficients:
        """Return the longitudinal factors B_x, C_x, D_x, E_x, K_x, S_Hx, S_Vx at a load.

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        MFCoefficients
            The factors (arrays shaped like the broadcast inputs): ``K`` is the
            slip stiffness [N], ``D`` the peak [N], ``S_H`` a slip-ratio shift [-],
            ``S_V`` a force shift [N], ``mu`` the peak coefficient [-].
        """
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        return longitudinal(self, fz, gamma, dpi)

    def lateral(self, fz: Any, gamma: Any = 0.0, pressure: Any = None
                ) -> MFCoefficients:
        """Return the lateral factors B_y, C_y, D_y, E_y, K_y, S_Hy, S_Vy at a load.

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        MFCoefficients
            The factors (arrays shaped like the broadcast inputs): ``K`` is the
            cornering stiffness [N/rad], ``D`` the peak [N], ``S_H`` a shift of
            tan(alpha), ``S_V`` a force shift [N], ``mu`` the peak coefficient [-].
        """
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        return lateral(self, fz, gamma, dpi)

    def _turning(self, name: str, kappa: Any, alpha: Any, fz: Any, gamma: Any, pressure: Any,
                 phit: Any, turn_slip: bool) -> Any | None:
        """Output ``name`` of the steady state with turn slip (None without it: the caller's
        own path); a turn slip without the model is refused there."""
        if not turn_slip and not np.any(np.asarray(phit, dtype=float) != 0):
            return None
        out = self.steady_state(kappa, alpha, fz, gamma, pressure, phit=phit,
                                turn_slip=turn_slip)[name]
        return float(out) if np.ndim(out) == 0 else out

    @labelled(("kappa", "fz", "gamma", "phit"), ("F_x0", "N", "pure longitudinal force"))
    def fx0(self, kappa: Any, fz: Any, gamma: Any = 0.0, pressure: Any = None, *,
            phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Pure longitudinal force F_x0 [N].

        Parameters
        ----------
        kappa : array-like
            Longitudinal slip ratio (positive when driving, -1 = locked wheel).
        fz : array-like
            Vertical load [N] (> 0); broadcast against ``kappa``.
        gamma : array-like
            Inclination (camber) angle [rad].
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).
        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            F_x0 [N], broadcast over the inputs; a DataArray (named ``F_x0``, with
            the inputs' dimensions and coordinates) when an input is one.
        """
        turned = self._turning("Fx", kappa, 0.0, fz, gamma, pressure, phit, turn_slip)
        if turned is not None:
            return turned
        kappa = self._kappa(kappa)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        k = longitudinal(self, fz, gamma, dpi)
        out = mf_curve(kappa + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
        return float(out) if np.ndim(out) == 0 else out

    @labelled(("alpha", "fz", "gamma", "phit"), ("F_y0", "N", "pure lateral force"))
    def fy0(self, alpha: Any, fz: Any, gamma: Any = 0.0, pressure: Any = None, *,
            phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Pure lateral force F_y0 [N].

        The slip enters as tan(alpha) or alpha (the ``slip_angle`` convention, see
        the module notes).

        Parameters
        ----------
        alpha : array-like
            Slip angle [rad], strictly between -pi/2 and pi/2.
        fz : array-like
            Vertical load [N] (> 0); broadcast against ``alpha``.
        gamma : array-like
            Inclination (camber) angle [rad].
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).
        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            F_y0 [N], broadcast over the inputs; a DataArray (named ``F_y0``, with
            the inputs' dimensions and coordinates) when an input is one.
        """
        turned = self._turning("Fy", 0.0, alpha, fz, gamma, pressure, phit, turn_slip)
        if turned is not None:
            return turned
        alpha_s = self._alpha_star(alpha)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        k = lateral(self, fz, gamma, dpi)
        out = mf_curve(alpha_s + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
        return float(out) if np.ndim(out) == 0 else out

    def gamma_star(self, gamma: Any) -> Any:
        """Return the camber variable gamma* of the equations.

        It is sin(gamma) with ``slip_angle = "tan_alpha"`` (the book's starred
        quantities, eq. 4.E4) and gamma itself with ``"alpha"`` (both unstarred, as
        MFeval's "revoke alpha_star" modes).

        Parameters
        ----------
        gamma : float or array
            Camber angle [rad].

        Returns
        -------
        float or numpy.ndarray
            The value of gamma* (sin(gamma) or gamma).
        """
        return gamma_star(self, gamma)

    @labelled(("kappa", "alpha", "fz", "gamma"), ("G_xa", "1", "combined-slip weight of F_x"))
    def weight_x(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0) -> Any:
        """Combined-slip weighting G_xa of F_x (= 1 at alpha = 0), eqs. (4.E50)-(4.E57).

        ``B_xa = (RBX1 + RBX3 g^2) cos(arctan(RBX2 kappa)) LXAL``, ``C_xa = RCX1``,
        ``E_xa = REX1 + REX2 dfz`` (<= 1), ``S_Hxa = RHX1``, ``a_s = alpha* + S_Hxa``
        and ``G_xa = cos(C_xa arctan(B_xa a_s - E_xa (B_xa a_s - arctan(B_xa a_s))))``
        divided by the same expression at ``a_s = S_Hxa``.

        Parameters
        ----------
        kappa, alpha : array-like
            Slip ratio [-] and slip angle [rad], broadcast together with ``fz``.
        fz : array-like
            Vertical load [N].
        gamma : array-like
            Inclination angle [rad].

        Returns
        -------
        float or numpy.ndarray
            G_xa [-], 1 where ``alpha = 0``.
        """
        kappa = self._kappa(kappa)
        alpha_s = self._alpha_star(alpha)
        fz, gamma, _ = self._inputs(fz, gamma, None)
        out = weight_x(self, kappa, alpha_s, fz, gamma)
        return float(out) if np.ndim(out) == 0 else out

    @labelled(("kappa", "alpha", "fz", "gamma"), ("G_yk", "1", "combined-slip weight of F_y"),
               ("S_Vyk", "N", "slip-induced lateral force shift"))
    def weight_y(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                 pressure: Any = None) -> tuple[Any, Any]:
        """Combined-slip weighting G_yk of F_y and the shift S_Vyk [N], eqs. (4.E58)-(4.E67).

        ``B_yk = (RBY1 + RBY4 g^2) cos(arctan(RBY2 (alpha* - RBY3))) LYKA``,
        ``C_yk = RCY1``, ``E_yk = REY1 + REY2 dfz`` (<= 1), ``S_Hyk = RHY1 + RHY2 dfz``,
        ``k_s = kappa + S_Hyk``; ``G_yk`` as for x; ``S_Vyk = D_Vyk sin(RVY5
        arctan(RVY6 kappa)) LVYKA`` with ``D_Vyk = mu_y F_z (RVY1 + RVY2 dfz + RVY3 g)
        cos(arctan(RVY4 alpha*))``.  G_yk = 1 and S_Vyk = 0 at kappa = 0.

        Parameters
        ----------
        kappa, alpha : array-like
            Slip ratio [-] and slip angle [rad], broadcast together with ``fz``.
        fz : array-like
            Vertical load [N].
        gamma : array-like
            Inclination angle [rad].
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row.

        Returns
        -------
        G_yk : float or numpy.ndarray
            The weighting [-].
        S_Vyk : float or numpy.ndarray
            The slip-induced lateral force shift [N].
        """
        kappa = self._kappa(kappa)
        alpha_s = self._alpha_star(alpha)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        return weight_y(self, kappa, alpha_s, fz, gamma, lateral(self, fz, gamma, dpi).mu)

    @labelled(("kappa", "alpha", "fz", "gamma", "phit"), ("F_x", "N", "longitudinal force"))
    def fx(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
           pressure: Any = None, *, phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Longitudinal force F_x = G_xa F_x0 [N] under combined slip.

        Parameters
        ----------
        kappa, alpha : array-like
            Slip ratio [-] and slip angle [rad], broadcast together with ``fz``.
        fz : array-like
            Vertical load [N].
        gamma : array-like
            Inclination angle [rad].
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row.

        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            F_x [N]; equal to :meth:`fx0` where ``alpha = 0``; a DataArray when an
            input is one.
        """
        turned = self._turning("Fx", kappa, alpha, fz, gamma, pressure, phit, turn_slip)
        if turned is not None:
            return turned
        kappa = self._kappa(kappa)
        alpha_s = self._alpha_star(alpha)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        out = (np.asarray(weight_x(self, kappa, alpha_s, fz, gamma))
               * np.asarray(pure_fx(self, kappa, fz, gamma, dpi)))
        return float(out) if np.ndim(out) == 0 else out

    @labelled(("kappa", "alpha", "fz", "gamma", "phit"), ("F_y", "N", "lateral force"))
    def fy(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
           pressure: Any = None, *, phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Lateral force F_y = G_yk F_y0 + S_Vyk [N] under combined slip.

        Equal to :meth:`fy0` where ``kappa = 0``.

        Parameters
        ----------
        kappa, alpha : array-like
            Slip ratio [-] and slip angle [rad], broadcast together with ``fz``.
        fz : array-like
            Vertical load [N].
        gamma : array-like
            Inclination angle [rad].
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row.

        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            F_y [N]; a DataArray when an input is one.
        """
        turned = self._turning("Fy", kappa, alpha, fz, gamma, pressure, phit, turn_slip)
        if turned is not None:
            return turned
        kappa = self._kappa(kappa)
        alpha_s = self._alpha_star(alpha)
        fz, gamma, dpi = self._inputs(fz, gamma, pressure)
        lat = lateral(self, fz, gamma, dpi)
        G, S_V = weight_y(self, kappa, alpha_s, fz, gamma, lat.mu)
        fy0 = mf_curve(alpha_s + lat.S_H, lat.B, lat.C, lat.D, lat.E_a, lat.E_b, lat.S_V)
        out = np.asarray(G) * np.asarray(fy0) + S_V
        return float(out) if np.ndim(out) == 0 else out

    @labelled(("fz", "gamma"), ("mu_x_peak", "1", "peak longitudinal friction coefficient"))
    def mu_x_peak(self, fz: Any, gamma: Any = 0.0, pressure: Any = None) -> Any:
        """Peak longitudinal friction coefficient mu_x = D_x / F_z [-].

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            The peak coefficient mu_x [-] per load; a DataArray when an input is one.
        """
        mu = self.longitudinal(fz, gamma, pressure).mu
        return float(mu) if np.ndim(mu) == 0 else mu

    @labelled(("fz", "gamma"), ("mu_y_peak", "1", "peak lateral friction coefficient"))
    def mu_y_peak(self, fz: Any, gamma: Any = 0.0, pressure: Any = None) -> Any:
        """Peak lateral friction coefficient mu_y = D_y / F_z [-].

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            The peak coefficient mu_y [-] per load; a DataArray when an input is one.
        """
        mu = self.lateral(fz, gamma, pressure).mu
        return float(mu) if np.ndim(mu) == 0 else mu

    @labelled(("fz", "gamma"), ("K_x", "N", "longitudinal slip stiffness"))
    def slip_stiffness(self, fz: Any, gamma: Any = 0.0, pressure: Any = None) -> Any:
        """Longitudinal slip stiffness K_x = dF_x0/dkappa at the shifted origin [N].

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            K_x [N per unit slip] per load; a DataArray when an input is one.
        """
        K = self.longitudinal(fz, gamma, pressure).K
        return float(K) if np.ndim(K) == 0 else K

    @labelled(("fz", "gamma"), ("K_y", "N/rad", "cornering stiffness"))
    def cornering_stiffness(self, fz: Any, gamma: Any = 0.0,
                            pressure: Any = None) -> Any:
        """Cornering stiffness K_y = dF_y0/d(tan alpha) at the shifted origin [N/rad].

        Parameters
        ----------
        fz : array-like
            Vertical load [N] (> 0).
        gamma : array-like
            Inclination (camber) angle [rad], broadcast with ``fz``.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).

        Returns
        -------
        float, numpy.ndarray or xarray.DataArray
            K_y [N/rad] per load; a DataArray when an input is one.
        """
        K = self.lateral(fz, gamma, pressure).K
        return float(K) if np.ndim(K) == 0 else K

    def steady_state(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                     pressure: Any = None, vx: Any = None, saturate: bool = False, *,
                     phit: Any = 0.0, omega: Any = None, turn_slip: bool = False,
                     limit_checks: bool = True) -> dict[str, Any]:
        """Every steady-state output per row: forces, moments, radii, stiffnesses.

        See :func:`frictionlaws.tyre.mf.outputs.steady_state` (the outputs, their units
        and equations, the camber convention of the moments) and
        :mod:`frictionlaws.tyre.mf.turn_slip` (turn slip).

        Parameters
        ----------
        kappa, alpha, fz, gamma : array-like
            Slip ratio [-], slip angle [rad], vertical load [N], camber [rad]; broadcast.
        pressure : float or array-like, optional
            Inflation pressure [Pa], one or one per row (default: the file's).
        vx : float or array-like, optional
            Forward speed [m/s] (default: the file's LONGVL; negative: backwards).
        saturate : bool
            Clamp the inputs at the file's limits as MFeval does (default False).
        phit : float or array-like
            Turn slip, the path curvature [1/m] (default 0; with ``turn_slip``).
        omega : float or array-like, optional
            Wheel angular speed [rad/s] (default: from the slip ratio).
        turn_slip : bool
            MF-Tyre's turn-slip model (MFeval's useModes x2; default False).
        limit_checks : bool
            MFeval's limit checks (default True); False: its useModes 2xx.

        Returns
        -------
        dict of str to numpy.ndarray
            ``Fx``, ``Fy``, ``Mx``, ``My``, ``Mz``, ``Mz0``, ``t``, ``Mzr``, ``Re``, ``Rl``...
        """
        inputs = {"kappa": kappa, "alpha": alpha, "fz": fz, "gamma": gamma,
                  "pressure": pressure, "vx": vx, "phit": phit, "omega": omega}
        if any(map(is_labelled, inputs.values())):
            return labelled_steady_state(self, inputs, saturate, turn_slip, limit_checks)
        return steady_state(self, kappa, alpha, fz, gamma, pressure, vx, saturate, phit=phit,
                            omega=omega, turn_slip=turn_slip, limit_checks=limit_checks)

    def mz(self, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
           pressure: Any = None, *, phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Aligning moment M_z [N m] under combined slip at the file's speed LONGVL.

        Parameters
        ----------
        kappa, alpha, fz, gamma : array-like
            Slip ratio [-], slip angle [rad], vertical load [N], camber [rad]; broadcast.
        pressure : float or array-like, optional
            Inflation pressure [Pa] (default: the file's).
        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float or numpy.ndarray
            M_z [N m]; equal to :meth:`mz0` plus ``s F_x`` where ``kappa = 0``.
        """
        out = aligning_moment(self, kappa, alpha, fz, gamma, pressure, phit=phit,
                              turn_slip=turn_slip)["Mz"]
        return float(out) if np.ndim(out) == 0 else out

    def mz0(self, alpha: Any, fz: Any, gamma: Any = 0.0, pressure: Any = None, *,
            phit: Any = 0.0, turn_slip: bool = False) -> Any:
        """Pure-slip aligning moment M_z0 [N m] (eq. 4.E31) at the file's speed LONGVL.

        Parameters
        ----------
        alpha, fz, gamma : array-like
            Slip angle [rad], vertical load [N], camber [rad]; broadcast.
        pressure : float or array-like, optional
            Inflation pressure [Pa] (default: the file's).
        phit, turn_slip : array-like, bool
            Turn slip [1/m] and its model, at the file's speed LONGVL (default 0, False).

        Returns
        -------
        float or numpy.ndarray
            M_z0 [N m].
        """
        out = aligning_moment(self, 0.0, alpha, fz, gamma, pressure, phit=phit,
                              turn_slip=turn_slip)["Mz0"]
        return float(out) if np.ndim(out) == 0 else out

    def summary(self, loads: Any = None) -> dict[str, Any]:
        """Summarise the tyre as JSON-able data.

        Parameters
        ----------
        loads : array-like, optional
            Vertical loads [N] at which the peaks and stiffnesses are given
            (default: 0.5, 1 and 1.5 times FNOMIN).

        Returns
        -------
        dict
            Name, source, version, FNOMIN [N], pressures [Pa], the conventions as applied,
            the file's limits (SI), and at each load the peak coefficients mu_x, mu_y
            [-], the stiffnesses K_x [N], K_y [N/rad] and (when the file gives the
            radius and LONGVL) the pneumatic trail at zero slip and the peak pure-slip
            aligning moment with its slip angle; the keys name the units.  ``loads_N`` are
            the loads asked for, ``loads_evaluated_N`` those evaluated and ``clamped`` says
            which were clamped (at FZMAX); ``warnings`` are the warnings of those loads and
            the pressure (also issued), ``notes`` the model's notes.
        """
        return tyre_summary(self, loads)

    def coefficient_listing(self) -> list[dict[str, Any]]:
        """The model's values beside their declarations (``tyre mf --coefficients``).

        Returns
        -------
        list of dict
            :func:`~frictionlaws.tyre.mf.coefficients.listing` with ``used_by``: the
            steady-state outputs that read each coefficient (found by evaluating them,
            :func:`~frictionlaws.tyre.mf.outputs.coefficient_users`).
        """
        rows = listing(self.version, self.coefficients, {**self.structure, "FNOMIN": self.fnomin})
        users = coefficient_users(self)
        return [{**row, "used_by": list(users.get(str(row["name"]), ()))} for row in rows]

    def __repr__(self) -> str:
        return (f"<MagicFormula {self.name!r} MF {self.version}, FNOMIN {self.fnomin:g} N>")
