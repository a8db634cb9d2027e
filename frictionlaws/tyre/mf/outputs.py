"""The steady-state outputs of the Magic Formula: one table, and the evaluation that fills it.

:data:`OUTPUTS` is the one table of outputs (name -> unit, meaning, function):
:func:`steady_state`, the CLI (``tyre mf FILE --kappa ...``, its text and ``--json``) and
the xarray results (:func:`labelled_steady_state`) all loop over it.  A new output is one
row and one function of an :class:`Evaluation` (the checked conditions, the tyre and what
several outputs share, computed once when first needed).

:func:`steady_state` evaluates, for one :class:`~frictionlaws.tyre.mf.model.MagicFormula`
and per row of load, slips, camber, pressure, speed, turn slip and wheel speed, the
outputs MFeval's ``fullSteadyState`` gives (turn slip:
:mod:`frictionlaws.tyre.mf.turn_slip`; low speed, running backwards and the limit checks:
:mod:`frictionlaws.tyre.mf.conditions`): the combined-slip
forces, the aligning moment M_z with its pneumatic trail t and residual torque
M_zr, the pure-slip aligning moment M_z0, the overturning moment M_x, the rolling
resistance moment M_y, the effective rolling radius R_e, the loaded radius R_l and
deflection rho, the vertical stiffness, the contact patch length 2a and width 2b,
the longitudinal and lateral stiffnesses C_x, C_y and relaxation lengths sigma_x,
sigma_y, the slip stiffnesses K_xk and K_ya, the peak friction coefficients and instKya,
the slope of F_y against the slip angle between neighbours along the last axis.

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
:class:`~frictionlaws.tyre.mf.model.MagicFormula` chooses; its default ``mfeval``
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
beyond the limits (``tests/tyre/data/mfeval``): the moments within 4e-12 of the peak moment,
the forces within 3e-12 of the peak force; R_e and Omega within 3e-8 and 3e-6 (MFeval ends
its R_e iteration when the first row of a batch converges); R_l and rho within 1e-6 m
where MFeval's fminsearch for the MF 6.2 radius converged.  Past steady rolling (turn slip
with phit -2..2 1/m, speeds -20..2 m/s through VXLOW, a given wheel speed, without limit
checks: ``tests/tyre/data/mfeval/MF*_beyond_steady.csv.gz``, packaged files and turn-slip
variants, useModes 111-222): every output within 5e-11 of its peak at MFeval's wheel
speed; estimating the wheel speed, MFeval's omega lies up to 5e-5 of the peak from the
fixed point (its early end of the iteration), which the turn slip's camber spin carries
into F_y, t and M_z by up to 1.5e-6.  The MF 6.2 loaded radius here
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
``vx`` [m/s] defaults to the file's LONGVL; at and below VXLOW MF-Tyre's low-speed
reductions apply, with a warning, and a negative speed runs the tyre backwards
(:mod:`~frictionlaws.tyre.mf.conditions`).  ``limit_checks=False`` evaluates as MFeval's
useModes 2xx (no E capped at 1, no low-speed reductions).
"""


from __future__ import annotations

import copy
import warnings
from collections.abc import Callable, Mapping
from dataclasses import dataclass, replace
from functools import cached_property
from typing import Any, NamedTuple

import numpy as np

from ...base.errors import ExtrapolationWarning, InputError
from .coefficients import RecordingValues
from .conditions import Conditions
from .equations import (
    LateralSpin,
    MFCoefficients,
    lateral,
    longitudinal,
    slip_variable,
    weight_x,
    weight_y,
)
from .inputs import INPUTS
from .labelled import is_labelled, refuse_plain
from .moments import (
    Aligning,
    AligningSpin,
    Forces,
    ZeroCamber,
    aligning,
    overturning,
    rolling,
)
from .notices import collected
from .parameters import MFParameters
from .plausibility import check_wheel_speed
from .turn_slip import (
    Spin,
    check_turn_slip,
    residual_zetas,
    spin,
    zeta_trail,
    zeta_x,
    zeta_y,
)
from .vertical import carcass_stiffness, loaded_radius, patch, relaxation, rolling_radius

__all__ = ["Output", "OUTPUTS", "Evaluation", "steady_state", "evaluate", "SteadyState",
           "aligning_moment", "aligning_summary", "tyre_summary", "coefficient_users"]


class Evaluation:
    """One evaluation of the steady state: the tyre, the checked conditions, and what
    several outputs share, each computed once when an output first needs it.

    An output's function (:data:`OUTPUTS`) takes one of these and returns its values
    (broadcast to the conditions' shape by :func:`steady_state`), or ``None`` when the
    file cannot give that output (``Cx`` without a carcass stiffness).

    Attributes
    ----------
    p : MFParameters
        The tyre (its coefficients read as ``e.p.c.PCX1``).
    r : Conditions
        The checked, broadcast inputs (``e.r.kappa``, ``e.r.fz``, ``e.r.dpi``...).
    asked : frozenset of str
        The outputs asked for by name (:func:`evaluate`'s ``names``): instKya warns of
        its NaN only when asked for.
    """

    def __init__(self, p: MFParameters, r: Conditions, asked: Any = ()) -> None:
        self.p = p
        self.r = r
        self.asked = frozenset(asked)  # the outputs asked for by name

    @cached_property
    def dfz(self) -> Any:
        """The load increment dfz = (F_z - F'z0) / F'z0 at the evaluated loads."""
        return (self.r.fz - self.p.fz0) / self.p.fz0

    @cached_property
    def alpha_s(self) -> Any:
        """The lateral slip variable (tan(alpha) sgn(V_x), or alpha)."""
        return slip_variable(self.p, self.r.alpha, self.r.vx)

    @cached_property
    def spin(self) -> Spin | None:
        """The turn slip's spin (None without the turn-slip model)."""
        p, r = self.p, self.r
        if not r.turn_slip:
            return None
        return spin(p, r.phit, r.alpha, r.gamma, r.vx, self.rolling["omega"], self.dfz)

    @cached_property
    def turn_y(self) -> LateralSpin | None:
        """What the turn slip does to the lateral curve (None without it)."""
        s, r = self.spin, self.r
        if s is None:
            return None
        zeta2, zeta3 = zeta_y(self.p, s, r.alpha, self.dfz)
        return LateralSpin(s, r.vx, zeta2, zeta3, cap=r.limit_checks)

    def _faded(self, k: MFCoefficients) -> MFCoefficients:
        """The factors with the shifts faded at low speed (the limit checks)."""
        fade = self.r.fade
        return k if np.all(fade == 1) else replace(k, S_H=k.S_H * fade, S_V=k.S_V * fade)

    def _turned(self, f: Any, lateral_force: bool = False) -> Any:
        """A pure-slip force turned with the running direction (backwards: V_x < 0);
        the lateral one only with alpha* = tan(alpha) sgn(V_x) (MFeval's alpha_star)."""
        if lateral_force and self.p.slip_angle != "tan_alpha":
            return f
        return np.where(self.r.vx < 0, -f, f)

    @cached_property
    def longitudinal(self) -> MFCoefficients:
        """The pure-slip longitudinal factors at the evaluated loads."""
        r, s = self.r, self.spin
        zeta = 1.0 if s is None else zeta_x(self.p, s, r.kappa, self.dfz)
        return self._faded(longitudinal(self.p, r.fz, r.gamma, r.dpi, zeta))

    @cached_property
    def lateral(self) -> MFCoefficients:
        """The pure-slip lateral factors at the evaluated loads."""
        r = self.r
        return self._faded(lateral(self.p, r.fz, r.gamma, r.dpi, self.turn_y))

    def pure_fy(self, lat: MFCoefficients) -> Any:
        """F_y0 [N] of the factors ``lat`` at the evaluated slip angles."""
        return self._turned(lat.curve(self.alpha_s, self.r.limit_checks), True)

    @cached_property
    def fx(self) -> Any:
        """The combined-slip longitudinal force F_x = G_xa F_x0 [N]."""
        p, r, lon = self.p, self.r, self.longitudinal
        fx0 = self._turned(lon.curve(r.kappa, r.limit_checks))
        return weight_x(p, r.kappa, self.alpha_s, r.fz, r.gamma, r.limit_checks) * fx0

    @cached_property
    def fy(self) -> tuple[Any, Any, Any]:
        """(F_y, G_yk, S_Vyk): the combined-slip lateral force [N], its weighting and the
        slip-induced shift [N]."""
        p, r, lat, alpha_s = self.p, self.r, self.lateral, self.alpha_s
        zeta2 = 1.0 if self.turn_y is None else self.turn_y.zeta2
        G_yk, S_Vyk = weight_y(p, r.kappa, alpha_s, r.fz, r.gamma, lat.mu, r.limit_checks,
                               zeta2)
        S_Vyk = S_Vyk * r.fade
        return G_yk * self.pure_fy(lat) + S_Vyk, G_yk, S_Vyk

    @cached_property
    def forces(self) -> Forces:
        """The combined-slip forces and the factors the moments take."""
        lon, lat = self.longitudinal, self.lateral  # in this order: mu_x checked first
        fx = self.fx
        fy, G_yk, S_Vyk = self.fy
        return Forces(Fx=fx, Fy=fy, alpha_s=self.alpha_s, lon=lon, lat=lat, G_yk=G_yk,
                      S_Vyk=S_Vyk)

    @cached_property
    def zero_camber(self) -> ZeroCamber:
        """The lateral force at zero camber the aligning moment takes."""
        p, r = self.p, self.r
        plain = self._faded(lateral(p, r.fz, 0.0, r.dpi))
        turned = plain if self.turn_y is None else self._faded(
            lateral(p, r.fz, 0.0, r.dpi, self.turn_y))
        s_vyk = None
        if p.version == "5.2" and p.equations == "mfeval":  # mu_y at zero camber
            s_vyk = weight_y(p, r.kappa, self.alpha_s, r.fz, r.gamma, turned.mu,
                             r.limit_checks)[1] * r.fade
        return ZeroCamber(fy0=self.pure_fy(plain), fy0_turn=self.pure_fy(turned),
                          s_vyk=s_vyk)

    @cached_property
    def aligning(self) -> Aligning:
        """M_z0, M_z, the trail and the residual torque."""
        p, r, s = self.p, self.r, self.spin
        turn = None
        if s is not None and self.turn_y is not None:
            f = self.forces
            zeta6, zeta7, zeta8 = residual_zetas(p, s, r.fz_mz, self.dfz, r.gamma, f.lat.mu,
                                                 f.G_yk)
            turn = AligningSpin(zeta2=self.turn_y.zeta2, zeta5=zeta_trail(p, s),
                                zeta6=zeta6, zeta7=zeta7, zeta8=zeta8)
        return aligning(p, r, self.forces, self.zero_camber, turn)

    @cached_property
    def inst_kya(self) -> Any:
        """instKya [N/rad]: the slope of F_y against the evaluated slip angle between
        neighbouring points of the last axis that differ in the slip angle only (MFeval's
        output 29, a forward difference along its rows; a point without such a neighbour
        ahead takes the one behind, as MFeval's last point does); NaN for a point with
        neither, with a warning when it is asked for by name (not when every output is:
        rows of measured data, all inputs changing, give NaN by design)."""
        r = self.r
        shape = r.shape
        if not shape or shape[-1] < 2:
            slope = np.full(shape, np.nan)
            self._warn_lone(slope)
            return slope
        da = np.diff(np.broadcast_to(r.alpha, shape), axis=-1)
        dfy = np.diff(np.broadcast_to(self.fy[0], shape), axis=-1)
        sweep = da != 0
        for x in (r.kappa_in, r.fz_in, r.gamma, r.pressure, r.vx, r.phit_in, r.omega):
            if x is not None and np.ndim(x):
                sweep &= np.diff(np.broadcast_to(x, shape), axis=-1) == 0
        step = np.where(sweep, dfy / np.where(sweep, da, 1.0), np.nan)
        none = np.full((*shape[:-1], 1), np.nan)
        ahead, behind = (np.concatenate(parts, axis=-1) for parts in ((step, none),
                                                                       (none, step)))
        slope = np.where(np.isnan(ahead), behind, ahead)
        self._warn_lone(slope)
        return slope

    def _warn_lone(self, slope: np.ndarray) -> None:
        """Warn where instKya, asked for by name, is NaN (no sweep neighbour)."""
        lone = np.isnan(slope)
        if "instKya" in self.asked and np.any(lone):
            warnings.warn(f"{self.p.name or 'Magic Formula'}: instKya is NaN on "
                          f"{int(lone.sum())} of {max(lone.size, 1)} row(s): no neighbour "
                          "along the last axis differs from them in the slip angle alone "
                          "(it is the slope of F_y between such neighbours; sweep the slip "
                          "angle along the last axis, the other inputs held)", UserWarning,
                          stacklevel=5)

    @cached_property
    def rolling(self) -> dict[str, Any]:
        """R_e, omega and the free radius at that speed, R_omega (warned where implausible:
        :func:`~frictionlaws.tyre.mf.plausibility.check_wheel_speed`)."""
        p, r = self.p, self.r
        roll = rolling_radius(p, r)
        check_wheel_speed(p, r.vx, r.kappa_in, r.omega, roll["omega"], roll["Re"])
        return roll

    @cached_property
    def loaded(self) -> dict[str, Any]:
        """R_l, rho and C_z."""
        roll = self.rolling
        return loaded_radius(self.p, self.r, roll["omega"], roll["Romega"], self.fx,
                             self.fy[0])

    @cached_property
    def patch(self) -> dict[str, Any]:
        """The contact patch's length 2a and width 2b."""
        return patch(self.p, self.r)

    @cached_property
    def stiffness(self) -> dict[str, Any]:
        """C_x and C_y (when the file has them)."""
        return carcass_stiffness(self.p, self.r)

    @cached_property
    def relaxation(self) -> dict[str, Any]:
        """The relaxation lengths sigma_x, sigma_y."""
        return relaxation(self.p, self.r, self.longitudinal.K, self.lateral.K, self.stiffness)


class Output(NamedTuple):
    """One steady-state output: its SI unit (``"1"``: dimensionless), what it is, and the
    function of an :class:`Evaluation` that gives its values (``None``: not given by this
    file)."""

    unit: str
    meaning: str
    value: Callable[[Evaluation], Any]


#: The outputs of :func:`steady_state`, in the order they are listed: name -> (unit,
#: meaning, function).  The CLI, JSON and xarray results loop over this table.
OUTPUTS: dict[str, Output] = {
    "Fx": Output("N", "longitudinal force (combined slip)", lambda e: e.fx),
    "Fy": Output("N", "lateral force (combined slip)", lambda e: e.fy[0]),
    "Fz": Output("N", "vertical load as evaluated", lambda e: e.r.fz),
    "Mx": Output("N m", "overturning moment", lambda e: overturning(e.p, e.r, e.fy[0])),
    "My": Output("N m", "rolling resistance moment", lambda e: rolling(e.p, e.r, e.fx)),
    "Mz": Output("N m", "aligning moment (combined slip)", lambda e: e.aligning.Mz),
    "Mz0": Output("N m", "aligning moment at pure side slip (kappa = 0)",
                  lambda e: e.aligning.Mz0),
    "t": Output("m", "pneumatic trail", lambda e: e.aligning.t),
    "Mzr": Output("N m", "residual aligning torque", lambda e: e.aligning.Mzr),
    "Re": Output("m", "effective rolling radius", lambda e: e.rolling["Re"]),
    "Rl": Output("m", "loaded radius", lambda e: e.loaded["Rl"]),
    "rho": Output("m", "vertical deflection", lambda e: e.loaded["rho"]),
    "omega": Output("rad/s", "wheel angular speed", lambda e: e.rolling["omega"]),
    "Cz": Output("N/m", "vertical stiffness at the load", lambda e: e.loaded["Cz"]),
    "2a": Output("m", "contact patch length", lambda e: e.patch["2a"]),
    "2b": Output("m", "contact patch width", lambda e: e.patch["2b"]),
    "mux": Output("1", "peak longitudinal friction coefficient", lambda e: e.longitudinal.mu),
    "muy": Output("1", "peak lateral friction coefficient", lambda e: e.lateral.mu),
    "Kxk": Output("N", "longitudinal slip stiffness", lambda e: e.longitudinal.K),
    "Kya": Output("N/rad", "cornering stiffness", lambda e: e.lateral.K),
    "Cx": Output("N/m", "longitudinal carcass stiffness", lambda e: e.stiffness.get("Cx")),
    "Cy": Output("N/m", "lateral carcass stiffness", lambda e: e.stiffness.get("Cy")),
    "sigmax": Output("m", "longitudinal relaxation length",
                     lambda e: e.relaxation["sigmax"]),
    "sigmay": Output("m", "lateral relaxation length", lambda e: e.relaxation["sigmay"]),
    "instKya": Output("N/rad", "slope of F_y against the slip angle between neighbours "
                      "along the last axis (MFeval's instKya)", lambda e: e.inst_kya),
}


@dataclass
class SteadyState:
    """What one evaluation gives besides the outputs: the inputs, the rows clamped and
    the warnings (:func:`evaluate`).

    Attributes
    ----------
    outputs : dict of str to numpy.ndarray
        Output name -> values, in the order of :data:`OUTPUTS` (those the file gives).
    inputs : dict of str to numpy.ndarray
        Input name (:data:`~frictionlaws.tyre.mf.conditions.INPUTS`) -> the values given,
        broadcast (``pressure`` and ``vx`` as taken when not given; ``pressure`` absent
        when the tyre has none).
    clamped : dict of str to numpy.ndarray
        Input name -> the rows where it was clamped (to the file's range with
        ``saturate``, or the load to FZMAX with ``loads_above_fzmax="clamp"``).
    warnings : list of str
        Every warning the evaluation raised, once each, in order (also issued as Python
        warnings).
    """

    outputs: dict[str, np.ndarray]
    inputs: dict[str, np.ndarray]
    clamped: dict[str, np.ndarray]
    warnings: list[str]

    def to_dict(self) -> dict[str, Any]:
        """JSON-able: the inputs and outputs with their units and meanings, one record per
        row (inputs as given, SI; outputs SI; ``clamped``: the inputs clamped on that row,
        whose outputs are those at the clamped value, e.g. ``Fz`` the load evaluated) and
        the warnings."""
        shape = next(iter(self.outputs.values())).shape if self.outputs else ()
        flat_in = {k: v.ravel() for k, v in self.inputs.items()}
        flat_out = {k: v.ravel() for k, v in self.outputs.items()}
        clamped = {k: np.broadcast_to(v, shape).ravel() for k, v in self.clamped.items()}
        n = int(np.prod(shape)) if shape else 1
        rows = []
        for i in range(n):
            row: dict[str, Any] = {k: float(v[i]) for k, v in flat_in.items()}
            row.update({k: float(v[i]) for k, v in flat_out.items()})
            row["clamped"] = [k for k, v in clamped.items() if v[i]]
            rows.append(row)
        return {"inputs": {k: {"unit": INPUTS[k].unit, "meaning": INPUTS[k].meaning}
                           for k in self.inputs},
                "outputs": {k: {"unit": OUTPUTS[k].unit, "meaning": OUTPUTS[k].meaning}
                            for k in self.outputs},
                "rows": rows, "clamped": sorted(self.clamped),
                "warnings": list(self.warnings)}

    def clamped_rows(self) -> np.ndarray:
        """A boolean per row: some input of the row was clamped."""
        shape = next(iter(self.outputs.values())).shape if self.outputs else ()
        out = np.zeros(shape, dtype=bool)
        for rows in self.clamped.values():
            out |= rows
        return out


def _refuse_overflow(name: str, value: np.ndarray, e: Evaluation) -> None:
    """Refuse inputs that take an output past floating point: an infinity, or a NaN but
    where it is an answer said with a warning (instKya without a neighbour in the slip
    angle alone; R_l, rho, C_z where no loaded radius carries the load), is no result (the
    speed terms grow with the square of the speed or wheel speed, a slip ratio of 1e308
    overflows the slip speed)."""
    r = e.r
    bad = np.isinf(value) if name == "instKya" else ~np.isfinite(value)
    if name in ("Rl", "rho", "Cz"):  # a NaN said of; an infinity never (R_l past 1e308 m)
        bad &= ~(e.loaded["said"] & np.isnan(value))
    if not bad.any():
        return
    i = int(np.flatnonzero(bad.ravel())[0])
    at = {"kappa": r.kappa_in, "vx [m/s]": r.vx, "omega [rad/s]": r.omega, "fz [N]": r.fz_in}
    row = ", ".join(f"{k} = {float(np.broadcast_to(v, r.shape).ravel()[i]):g}"
                    for k, v in at.items() if v is not None)
    raise InputError(f"{name} is not finite at row {i} ({row}): the inputs there lie past "
                     "what the Magic Formula's terms hold in floating point")


def evaluate(mf: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
             pressure: Any = None, vx: Any = None, saturate: bool = False,
             names: Any = None, *, phit: Any = 0.0, omega: Any = None,
             turn_slip: bool = False, limit_checks: bool = True) -> SteadyState:
    """Every steady-state output per row, with the inputs, the clamped rows and the
    warnings (:class:`SteadyState`); the parameters are those of :func:`steady_state`.

    ``names`` chooses the outputs (default: all of :data:`OUTPUTS` the file gives); an
    instKya asked for by name warns where it is NaN though the slip angle changes.
    """
    with collected(mf.not_applied) as warned, np.errstate(over="ignore", divide="ignore",
                                                           invalid="ignore"):
        r = Conditions(mf, kappa, alpha, fz, gamma, pressure, vx, saturate, phit, omega,
                       turn_slip, limit_checks)
        e = Evaluation(mf, r, names or ())
        if r.omega is not None and "UNLOADED_RADIUS" in mf.structure:
            _ = e.rolling  # a wheel speed given is checked whatever the outputs asked for
        outputs: dict[str, np.ndarray] = {}
        for name in (OUTPUTS if names is None else names):
            value = OUTPUTS[name].value(e)
            if value is not None:
                outputs[name] = np.broadcast_to(np.asarray(value, dtype=float),
                                                r.shape).copy()
                _refuse_overflow(name, outputs[name], e)
    given = {"kappa": r.kappa_in, "alpha": alpha, "fz": r.fz_in, "gamma": gamma,
             "pressure": r.pressure, "vx": r.vx,
             "phit": r.phit_in if turn_slip else None, "omega": r.omega}
    inputs = {k: np.broadcast_to(np.asarray(v, dtype=float), r.shape).copy()
              for k, v in given.items() if v is not None and k in INPUTS}
    return SteadyState(outputs, inputs, dict(r.clamped), warned)


def steady_state(mf: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                 pressure: Any = None, vx: Any = None, saturate: bool = False, *,
                 phit: Any = 0.0, omega: Any = None, turn_slip: bool = False,
                 limit_checks: bool = True) -> dict[str, np.ndarray]:
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
        Forward speed [m/s] (default: the file's LONGVL); negative: running backwards;
        at and below VXLOW with MF-Tyre's low-speed reductions (the limit checks).
    saturate : bool
        Clamp the inputs at the file's limits as MFeval does (default False: evaluate
        as given, warning outside the ranges); needs ``limit_checks``.
    phit : float or array-like
        Turn slip, the curvature of the wheel's path [1/m] (default 0); other than 0
        only with ``turn_slip``.
    omega : float or array-like, optional
        Wheel angular speed [rad/s] (MFeval's eighth input): sets the effective rolling
        radius, the speed term of the vertical stiffness and the camber's spin; the slip
        ratio stays the one given (default: the speed the slip ratio gives).
    turn_slip : bool
        Evaluate MF-Tyre's turn-slip model (MFeval's useModes x2; default False, which
        gives the outputs without it exactly); needs the file's turn-slip coefficients.
    limit_checks : bool
        MFeval's limit checks (default True: E capped at 1, the low-speed reductions);
        False evaluates as MFeval's useModes 2xx (see
        :mod:`~frictionlaws.tyre.mf.conditions`).

    Returns
    -------
    dict of str to numpy.ndarray
        One array per output of :data:`OUTPUTS`, shaped like the broadcast inputs
        (``Cx`` and ``Cy`` only when the file gives the carcass stiffnesses).
    """
    return evaluate(mf, kappa, alpha, fz, gamma, pressure, vx, saturate, phit=phit,
                    omega=omega, turn_slip=turn_slip, limit_checks=limit_checks).outputs


def aligning_moment(mf: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any = 0.0,
                    pressure: Any = None, vx: Any = None, saturate: bool = False, *,
                    phit: Any = 0.0, turn_slip: bool = False) -> dict[str, np.ndarray]:
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
    phit : float or array-like
        Turn slip [1/m] (with ``turn_slip``).
    turn_slip : bool
        Evaluate the turn-slip model (default False).

    Returns
    -------
    dict of str to numpy.ndarray
        ``Fx``, ``Fy`` [N], ``Mz``, ``Mz0``, ``Mzr`` [N m], ``t`` [m].
    """
    r = Conditions(mf, kappa, alpha, fz, gamma, pressure, vx, saturate, phit,
                   turn_slip=turn_slip)
    e = Evaluation(mf, r)
    f, m = e.forces, e.aligning
    out = {"Fx": f.Fx, "Fy": f.Fy, "Mz": m.Mz, "Mz0": m.Mz0, "t": m.t, "Mzr": m.Mzr}
    return {k: np.broadcast_to(np.asarray(v, dtype=float), r.shape).copy()
            for k, v in out.items()}


def aligning_summary(mf: MFParameters, loads: Any) -> dict[str, Any]:
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


def tyre_summary(mf: MFParameters, loads: Any = None) -> dict[str, Any]:
    """The summary of a tyre (:meth:`~frictionlaws.tyre.mf.model.MagicFormula.summary`,
    which documents its keys) at ``loads`` [N] (default 0.5, 1 and 1.5 FNOMIN)."""
    loads = np.atleast_1d(np.asarray(
        loads if loads is not None else [0.5 * mf.fnomin, mf.fnomin,
                                         1.5 * mf.fnomin], float))
    with collected(mf.not_applied) as warned:  # of the loads and pressure, once
        evaluated, clamped = mf.limit_loads(mf.check("fz", loads, positive=True))
        if mf.pressure is not None:
            mf.warn_range("pressure", np.asarray(mf.pressure))
    with warnings.catch_warnings():  # the summary's own slip grid is not the user's
        warnings.simplefilter("ignore", ExtrapolationWarning)
        lon = longitudinal(mf, evaluated, np.asarray(0.0), mf.dpi(None))
        lat = lateral(mf, evaluated, np.asarray(0.0), mf.dpi(None))
        moments = aligning_summary(mf, loads)
    return {
        "name": mf.name, "source": mf.source, "version": mf.version,
        "fnomin_N": mf.fnomin, "pressure_Pa": mf.pressure,
        "nominal_pressure_Pa": mf.nominal_pressure,
        "conventions": mf.applied_conventions,
        "limits_SI": {k: list(v) for k, v in mf.limits.items()},
        "loads_N": loads.tolist(),
        "loads_evaluated_N": np.asarray(evaluated, dtype=float).tolist(),
        "clamped": np.asarray(clamped, dtype=bool).tolist(),
        "mu_x_peak": np.broadcast_to(lon.mu, loads.shape).tolist(),
        "mu_y_peak": np.broadcast_to(lat.mu, loads.shape).tolist(),
        "K_x_N": np.broadcast_to(lon.K, loads.shape).tolist(),
        "K_y_N_per_rad": np.broadcast_to(lat.K, loads.shape).tolist(),
        **moments,
        "warnings": warned,
        "notes": list(mf.notes),
    }


def coefficient_users(mf: MFParameters) -> dict[str, tuple[str, ...]]:
    """Which outputs use each coefficient of ``mf``'s version, found by evaluating them.

    Each output of :data:`OUTPUTS` is evaluated alone (at combined slip, with camber and
    the model's pressure; without and, when the file has its coefficients, with turn
    slip) with a mapping that records the coefficients read; a coefficient read through
    the nominal load F'z0 (LFZO) or the friction scaling (LMUX, LMUY) counts for every
    output that reads those.

    Parameters
    ----------
    mf : MagicFormula
        A model of the version asked about (an output its file cannot give, for want of a
        radius or a stiffness, is left out).

    Returns
    -------
    dict of str to tuple of str
        Coefficient name -> the outputs that read it, in the order of :data:`OUTPUTS`.
    """
    users: dict[str, list[str]] = {}
    model = copy.copy(mf)
    modes: tuple[bool, ...] = (False,)
    try:
        check_turn_slip(mf)
        modes = (False, True)
    except InputError:  # no turn-slip coefficients: evaluated without turn slip only
        pass
    for name, output in OUTPUTS.items():
        read: set[str] = set()
        for turn_slip in modes:
            model.coefficients = values = RecordingValues(mf.coefficients)
            try:
                with warnings.catch_warnings():
                    warnings.simplefilter("ignore")
                    r = Conditions(model, 0.05, np.radians(3.0), mf.fnomin, np.radians(2.0),
                                   None, None, False, 0.1 if turn_slip else 0.0,
                                   turn_slip=turn_slip)
                    values.read.clear()  # the check of the turn-slip coefficients
                    output.value(Evaluation(model, r))
            except InputError:  # the file cannot give this output (no radius, stiffness)
                continue
            read |= values.read
        for coefficient in sorted(read):
            users.setdefault(coefficient, []).append(name)
    return {k: tuple(v) for k, v in users.items()}


def labelled_steady_state(mf: MFParameters, inputs: Mapping[str, Any], saturate: bool,
                          turn_slip: bool = False, limit_checks: bool = True) -> Any:
    """:func:`steady_state` of :class:`xarray.DataArray` inputs as an :class:`xarray.Dataset`.

    The inputs are aligned (inner join on shared coordinates) and broadcast by their
    dimension names; each output of :data:`OUTPUTS` is a variable with its ``units`` and
    ``long_name``; the dataset's attributes hold the ``warnings`` of the evaluation,
    ``clamped`` (the inputs clamped on some row; a variable ``clamped`` flags each row) and
    the model's ``notes`` (options not applied among them).
    Plain arrays (not scalars) beside DataArrays are refused: they have no dimension
    names to broadcast by.
    """
    import xarray as xr

    named = {k: v for k, v in inputs.items() if is_labelled(v)}
    refuse_plain(inputs, list(named))
    aligned = xr.align(*named.values(), join="inner")
    wide = xr.broadcast(*aligned)
    dims = wide[0].dims
    values = dict(inputs)
    values.update({k: a.transpose(*dims).values for k, a in zip(named, wide)})
    res = evaluate(mf, values["kappa"], values["alpha"], values["fz"], values["gamma"],
                   values["pressure"], values["vx"], saturate, phit=values.get("phit", 0.0),
                   omega=values.get("omega"), turn_slip=turn_slip,
                   limit_checks=limit_checks)
    coords = wide[0].coords
    data = {k: (dims, v, {"units": OUTPUTS[k].unit, "long_name": OUTPUTS[k].meaning})
            for k, v in res.outputs.items()}
    data["clamped"] = (dims, res.clamped_rows(), {"long_name": "some input of the row was "
                                                               "clamped to the file's range"})
    return xr.Dataset(data, coords=coords,
                      attrs={"warnings": list(res.warnings), "clamped": sorted(res.clamped),
                             "notes": list(mf.notes), "source": mf.source,
                             "version": mf.version})
