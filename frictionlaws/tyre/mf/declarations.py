"""The Magic Formula's coefficients declared: section, versions, unit, meaning, default,
bounds and fit stage.

Every coefficient and scaling factor a property file of MF 5.2 (PAC2002), 6.1 or 6.2 may
hold, and the file-level entries the evaluator reads (nominal load, radii, stiffnesses,
pressures, validity ranges), is declared here once as a :class:`Coefficient`, the way a
law declares its parameters (:class:`~frictionlaws.law.Param`):

* **unit**: SI, as the ``.tir`` states it with ``[UNITS]`` in SI (``""`` dimensionless);
  coefficients multiplying the camber angle are per radian, the files' angle unit;
* **meaning**: what the coefficient does in the equations (Pacejka, *Tire and Vehicle
  Dynamics*, 3rd ed. 2012, section 4.3.2; Besselink, Schmeitz and Pacejka 2010 for
  MF 6.1/6.2);
* **default**: the value the evaluator takes when the file lacks it (0 for
  coefficients, 1 for scaling factors, 2 for PKY4 as MF 5.2 fixes it; ``None``: no
  default, the outputs that need it are refused without it);
* **bounds**: the physically possible values (``FNOMIN > 0``, ``PCX1 > 0``, scaling
  factors ``>= 0``, slip-angle limits within +-90 degrees): a property file outside them
  is refused, naming file, section, name and value;
* **fit**: the range :func:`~frictionlaws.tyre.mf.fit.fit_mf` searches (the bounds
  when none narrower is declared); a file value outside it is noted when the file is read;
* **stage**: the stage of the staged fit that fits it (:data:`STAGES`), with what the data
  must span for it (**needs**: a second or third load, a camber, a pressure...);
* **which outputs use each**: found from the equations themselves
  (:func:`frictionlaws.tyre.mf.outputs.coefficient_users`, which evaluates every output
  and records the coefficients it reads), shown beside these declarations in the
  documentation's table and by ``frictionlaws tyre mf --coefficients``.

Who uses them: the equations read coefficients through the checked view
(:class:`~frictionlaws.tyre.mf.coefficients.CoefficientView`: a declared name, its value
or its default), the reader checks the bounds and knows the names
(:mod:`frictionlaws.tyre.mf.property_file`), fit-mf takes its stages, needs and bounds from
here (:mod:`frictionlaws.tyre.mf.coefficients`), and the documentation's table is generated
from :data:`DECLARED`.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from ...law import MU_MAX

__all__ = ["Coefficient", "DECLARED", "SECTIONS", "COEFFICIENT_SECTIONS", "STRUCTURE_SECTIONS",
           "RANGE_SECTIONS", "STAGES", "NEEDS", "VERSIONS", "LARGEST_COEFFICIENT", "UNITS_HINT",
           "POSITIVE", "ANGLE"]

INF = math.inf
#: Sections of coefficients (the names the evaluator's equations use).
COEFFICIENT_SECTIONS = ("SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS",
                        "LATERAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS",
                        "OVERTURNING_COEFFICIENTS", "ROLLING_COEFFICIENTS",
                        "TURNSLIP_COEFFICIENTS")
#: Sections whose numeric entries describe the tyre's structure and test conditions
#: (radii, stiffnesses, contact patch, reference speed), read by key.
STRUCTURE_SECTIONS = ("MODEL", "DIMENSION", "VERTICAL", "STRUCTURAL", "CONTACT_PATCH")
#: Sections of validity ranges and operating conditions.
RANGE_SECTIONS = ("VERTICAL_FORCE_RANGE", "LONG_SLIP_RANGE", "SLIP_ANGLE_RANGE",
                  "INCLINATION_ANGLE_RANGE", "INFLATION_PRESSURE_RANGE",
                  "OPERATING_CONDITIONS", "TIRE_CONDITIONS")
SECTIONS = COEFFICIENT_SECTIONS + STRUCTURE_SECTIONS + RANGE_SECTIONS

#: The Magic Formula versions declared.
VERSIONS = ("5.2", "6.1", "6.2")
ALL = VERSIONS
V52 = ("5.2",)
V6 = ("6.1", "6.2")
V62 = ("6.2",)
#: Bounds of a value that must be positive (open at 0) or not negative.
POSITIVE = (0.0, INF)
#: A slip or camber angle a property file can state [rad]: within +-90 degrees.
ANGLE = (-math.pi / 2, math.pi / 2)
#: The largest magnitude of a coefficient or scaling factor.  The published files stay
#: below 2e3 (RBY4 = 1747 of the MF 6.x examples); 1e6 leaves room for any real fit while
#: refusing a value such as 1e12 that only overflows the equations.
LARGEST_COEFFICIENT = 1e6
#: The hint of a value beyond what a real tyre has: a unit the file does not state.
UNITS_HINT = ("; check [UNITS]: is the value in the unit the file states (not kN, mm, bar or "
              "kPa where it states N, m or Pa, nor the other way round)?")
#: Real tyres, from a bicycle or a caster wheel to a mining truck's: free radius 0.05 m ..
#: 3 m (the largest earthmover tyres are about 4 m across), section width 0.01 m .. 2 m.
RADIUS = (0.05, 3.0)
WIDTH = (0.01, 2.0)
#: Nominal loads 10 N .. 2e6 N: a toy or caster wheel to the 100 t a mining-truck tyre carries.
LOAD = (10.0, 2e6)
#: Inflation pressures 1e4 .. 5e6 Pa: 0.1 bar (a soft tractor or sand tyre) to 50 bar
#: (aircraft and track-bicycle tyres reach about 15 to 20 bar); 2.6 (bar written as Pa)
#: and 2.6e8 (kPa read as Pa) are refused.
PRESSURE = (1e4, 5e6)
#: Vertical stiffness 1e3 .. 1e8 N/m: a soft bicycle tyre to an earthmover's.
STIFFNESS = (1e3, 1e8)
#: Reference speed 0.01 .. 200 m/s: a slow rig to an aircraft tyre at take-off.
SPEED = (0.01, 200.0)

#: The stages of the staged fit (:mod:`frictionlaws.tyre.mf.fit`), in their order: the
#: pure-slip forces, the combined-slip weighting functions, the pure-slip aligning moment
#: and the combined aligning moment; the direction (x, y, z) is the stage's second letter.
STAGES = ("Fx0", "Fy0", "Fx", "Fy", "Mz0", "Mz")
#: What a coefficient may need the data to span besides one load: a second or third load
#: level, two cambers (of both signs, two magnitudes, two nonzero levels), two or three
#: pressures, both signs of slip, and rows at combined slip.
NEEDS = ("loads2", "loads3", "camber", "camber_signs", "camber2", "camber_sq", "pressure",
         "pressure3", "both_signs", "combined_x", "combined_y", "combined_mz")


@dataclass(frozen=True)
class Coefficient:
    """One declared entry of a Magic Formula property file.

    Parameters
    ----------
    name : str
        The key, upper case (``PCX1``).
    section : str
        The section it belongs in (``LONGITUDINAL_COEFFICIENTS``).
    versions : tuple of str
        The MF versions whose equations define it (``("5.2", "6.1", "6.2")``).
    unit : str
        SI unit, pint-parsable (``""`` dimensionless).
    meaning : str
        What it does in the equations.
    default : float or None
        The value used when the file lacks it; ``None``: none (outputs needing it are
        refused).
    bounds : tuple of float
        Physically possible values (closed, unless ``open_low``).
    open_low : bool
        The lower bound itself is excluded (``> 0`` instead of ``>= 0``).
    fit : tuple of float, optional
        The range fit-mf searches, inside ``bounds`` (default: ``bounds``).
    evaluated : bool
        Whether the evaluator uses it (turn slip, gyroscopic and dynamic entries are known
        but not evaluated here).
    required : bool
        A property file must give it (the pure-slip core and FNOMIN).
    alias_of : str, optional
        Another spelling of that name, read as it.
    largest : float
        The largest magnitude allowed besides the bounds (coefficients and scaling
        factors: :data:`LARGEST_COEFFICIENT`); not part of the fit range.
    hint : str
        Added to a refusal (what the likely mistake is).
    sign : tuple of (int, str), optional
        The sign the ISO convention of property files gives it (-1 or 1) and what the
        other sign does: a value of the other sign is read, with that note.
    stage : str, optional
        The stage of the staged fit that fits it (:data:`STAGES`); None: not fitted.
    needs : tuple of str
        What the data must span for the fit to determine it (:data:`NEEDS`).
    """

    name: str
    section: str
    versions: tuple[str, ...]
    unit: str
    meaning: str
    default: float | None = 0.0
    bounds: tuple[float, float] = (-INF, INF)
    open_low: bool = False
    fit: tuple[float, float] | None = None
    evaluated: bool = True
    required: bool = False
    alias_of: str | None = None
    largest: float = INF
    hint: str = ""
    sign: tuple[int, str] | None = None
    stage: str | None = None
    needs: tuple[str, ...] = ()

    def __post_init__(self) -> None:
        if self.stage is not None and self.stage not in STAGES:
            raise ValueError(f"{self.name}: unknown fit stage {self.stage!r}")
        unknown = set(self.needs) - set(NEEDS)
        if unknown:
            raise ValueError(f"{self.name}: unknown needs {sorted(unknown)}")

    @property
    def direction(self) -> str | None:
        """"x", "y" or "z": the quantity of its fit stage (None when not fitted)."""
        return None if self.stage is None else self.stage[1]

    def limits(self) -> tuple[float, float]:
        """The bounds narrowed to :attr:`largest` in magnitude."""
        lo, hi = self.bounds
        return max(lo, -self.largest), min(hi, self.largest)

    def allows(self, value: float) -> bool:
        """True when ``value`` is finite and within the bounds."""
        lo, hi = self.limits()
        return (math.isfinite(value) and value <= hi
                and (value > lo if self.open_low else value >= lo))

    def expected(self) -> str:
        """The bounds as text: ``> 0``, ``>= 0``, ``-1.571 .. 1.571``, ``any``."""
        lo, hi = self.limits()
        low = f"{'>' if self.open_low else '>='} {lo:g}"
        if math.isinf(hi):
            return "any finite value" if math.isinf(lo) else low
        if math.isinf(lo):
            return f"<= {hi:g}"
        return f"{lo:.4g} {'<' if self.open_low else '<='} value <= {hi:.4g}"

    def refusal(self, shown: str, section: str | None = None) -> str:
        """The message refusing the value ``shown`` (as text) of this entry."""
        unit = f" {self.unit}" if self.unit else ""
        hint = ("; degrees where the file's angles are radians?" if self.bounds == ANGLE
                else self.hint)
        return (f"[{section or self.section}] {self.name} = {shown} is impossible: expected "
                f"{self.expected()}{unit} ({self.meaning}){hint}")

    def fit_range(self) -> tuple[float, float]:
        """The search range of fit-mf: :attr:`fit`, else the bounds (an open lower bound
        moved inside by a relative 1e-9, so that a solution on it is still allowed)."""
        if self.fit is not None:
            return self.fit
        lo, hi = self.bounds
        if self.open_low:
            lo = lo + 1e-9 * max(abs(lo), 1.0)
        return lo, hi


def _group(section: str, versions: tuple[str, ...], unit: str, default: float | None,
           entries: Iterable[tuple], **common: object) -> list[Coefficient]:
    """Declarations of one section: ``(name, meaning[, overrides])`` per entry."""
    out = []
    for entry in entries:
        name, meaning = entry[0], entry[1]
        kw: dict = {"versions": versions, "unit": unit, "default": default, **common}
        if section in COEFFICIENT_SECTIONS:
            kw.setdefault("largest", LARGEST_COEFFICIENT)
        if len(entry) > 2:
            kw.update(entry[2])
        out.append(Coefficient(name=name, section=section, meaning=meaning, **kw))
    return out


def _fit(stage: str, *needs: str) -> dict[str, object]:
    """The overrides of a fitted coefficient: its stage and what it needs of the data.

    Within a stage the coefficients are fitted in their declaration order."""
    return {"stage": stage, "needs": needs}


_NOT_EVALUATED = {"evaluated": False}
#: MF 6.x terms MFeval also evaluates for MF 5.2 files (``equations="mfeval"``).
_ALSO_52 = " (read from MF 5.2 files too with equations='mfeval', as MFeval does)"
_POS = {"bounds": POSITIVE, "open_low": True}
_SCALING = _group("SCALING_COEFFICIENTS", ALL, "", 1.0, (
    ("LFZO", "nominal load F'z0 = FNOMIN LFZO the coefficients refer to", _POS),
    ("LFZ0", "another spelling of LFZO (read as LFZO)", {"alias_of": "LFZO"}),
    ("LCX", "shape factor C_x"),
    ("LMUX", "peak friction mu_x (and, through LMU'x, the shift S_Vx)", _POS),
    ("LEX", "curvature factor E_x"),
    ("LKX", "longitudinal slip stiffness K_x"),
    ("LHX", "horizontal shift S_Hx"),
    ("LVX", "vertical shift S_Vx"),
    ("LGAX", "camber in F_x (MF 5.2: gamma_x = gamma LGAX)", {"versions": V52}),
    ("LCY", "shape factor C_y"),
    ("LMUY", "peak friction mu_y (and, through LMU'y, S_Vy, the trail and the residual "
             "torque)", _POS),
    ("LEY", "curvature factor E_y"),
    ("LKY", "cornering stiffness K_y (and the slope factors B_t, B_r of M_z)"),
    ("LKYC", "camber stiffness K_yg0 of F_y" + _ALSO_52, {"versions": V6}),
    ("LKZC", "camber terms of the residual torque D_r", {"versions": V6}),
    ("LHY", "horizontal shift S_Hy"),
    ("LVY", "vertical shift S_Vy"),
    ("LGAY", "camber in F_y and in the combined-slip terms (MF 5.2: gamma_y = gamma "
             "LGAY)", {"versions": V52}),
    ("LTR", "peak of the pneumatic trail D_t"),
    ("LRES", "offset of the residual torque D_r"),
    ("LGAZ", "camber in M_z (MF 5.2); not applied here: the M_z camber terms use gamma",
     {"versions": V52, "evaluated": False}),
    ("LXAL", "slip-angle influence on F_x, B_xa of the combined-slip weighting"),
    ("LYKA", "slip-ratio influence on F_y, B_yk of the combined-slip weighting"),
    ("LVYKA", "slip-ratio induced lateral force S_Vyk"),
    ("LS", "moment arm s of F_x in M_z"),
    ("LSGKP", "longitudinal relaxation length (MF 5.2, from PTX)", {"versions": V52}),
    ("LSGAL", "lateral relaxation length (MF 5.2, from PTY)", {"versions": V52}),
    ("LGYR", "gyroscopic torque (MF 5.2); not evaluated", {"versions": V52, **_NOT_EVALUATED}),
    ("LMX", "overturning moment M_x"),
    ("LVMX", "vertical shift of M_x (the QSX1 term)"),
    ("LMY", "rolling resistance moment M_y"),
    ("LMP", "spin (parking) moment of turn slip M_zp,inf"),
    ("LMUV", "decay of friction with slip speed; not evaluated (no speed dependence of "
             "friction)", _NOT_EVALUATED),
    ("LIP", "inflation pressure, as some files carry it; not evaluated", _NOT_EVALUATED),
    ("LCZ", "vertical stiffness; not evaluated", _NOT_EVALUATED),
), bounds=(0.0, INF))

_REQ = {"required": True, "default": None}
_LONGITUDINAL = _group("LONGITUDINAL_COEFFICIENTS", ALL, "", 0.0, (
    ("PCX1", "shape factor C_x of the F_x0 curve",
     {**_REQ, **_POS, "fit": (0.3, 3.0), **_fit("Fx0")}),
    ("PDX1", "peak friction mu_x at the nominal load",
     {**_REQ, "bounds": (0.0, MU_MAX), "open_low": True, **_fit("Fx0")}),
    ("PDX2", "change of mu_x with load (per dfz)", _fit("Fx0", "loads2")),
    ("PDX3", "change of mu_x with camber squared", {"unit": "1/rad**2", **_fit("Fx0", "camber")}),
    ("PEX1", "curvature E_x at the nominal load (the evaluator limits E_x to <= 1)",
     {"fit": (-50.0, 1.0), **_fit("Fx0")}),
    ("PEX2", "change of E_x with load", _fit("Fx0", "loads2")),
    ("PEX3", "change of E_x with load squared", _fit("Fx0", "loads3")),
    ("PEX4", "asymmetry of E_x between driving and braking (factor of sgn(kappa))",
     _fit("Fx0", "both_signs")),
    ("PKX1", "slip stiffness K_x / F_z at the nominal load", {**_REQ, **_POS, **_fit("Fx0")}),
    ("PKX2", "change of K_x / F_z with load", _fit("Fx0", "loads2")),
    ("PKX3", "exponential change of K_x / F_z with load", _fit("Fx0", "loads3")),
    ("PHX1", "horizontal shift S_Hx at the nominal load", _fit("Fx0")),
    ("PHX2", "change of S_Hx with load", _fit("Fx0", "loads2")),
    ("PVX1", "vertical shift S_Vx / F_z at the nominal load", _fit("Fx0")),
    ("PVX2", "change of S_Vx / F_z with load", _fit("Fx0", "loads2")),
    ("PPX1", "linear change of K_x with pressure (per dpi)",
     {"versions": V6, **_fit("Fx0", "pressure")}),
    ("PPX2", "quadratic change of K_x with pressure", {"versions": V6, **_fit("Fx0", "pressure3")}),
    ("PPX3", "linear change of mu_x with pressure", {"versions": V6, **_fit("Fx0", "pressure")}),
    ("PPX4", "quadratic change of mu_x with pressure",
     {"versions": V6, **_fit("Fx0", "pressure3")}),
    ("RBX1", "slope factor B_xa of the combined-slip weighting G_xa", _fit("Fx", "combined_x")),
    ("RBX2", "change of B_xa with slip ratio", _fit("Fx", "combined_x")),
    ("RCX1", "shape factor C_xa of G_xa", _fit("Fx", "combined_x")),
    ("REX1", "curvature E_xa of G_xa at the nominal load", _fit("Fx", "combined_x")),
    ("REX2", "change of E_xa with load", _fit("Fx", "combined_x", "loads2")),
    ("RHX1", "horizontal shift S_Hxa of G_xa", _fit("Fx", "combined_x")),
    ("RBX3", "change of B_xa with camber squared",
     {"versions": V6, "unit": "1/rad**2", **_fit("Fx", "combined_x", "camber")}),
    ("PTX1", "longitudinal relaxation length / R0 at the nominal load", {"versions": V52}),
    ("PTX2", "change of that relaxation length with load", {"versions": V52}),
    ("PTX3", "exponential change of that relaxation length with load", {"versions": V52}),
))

_LATERAL = _group("LATERAL_COEFFICIENTS", ALL, "", 0.0, (
    ("PCY1", "shape factor C_y of the F_y0 curve",
     {**_REQ, **_POS, "fit": (0.3, 3.0), **_fit("Fy0")}),
    ("PDY1", "peak friction mu_y at the nominal load",
     {**_REQ, "bounds": (0.0, MU_MAX), "open_low": True, **_fit("Fy0")}),
    ("PDY2", "change of mu_y with load", _fit("Fy0", "loads2")),
    ("PDY3", "change of mu_y with camber squared", {"unit": "1/rad**2", **_fit("Fy0", "camber")}),
    ("PEY1", "curvature E_y at the nominal load (the evaluator limits E_y to <= 1)",
     {"fit": (-50.0, 1.0), **_fit("Fy0")}),
    ("PEY2", "change of E_y with load", _fit("Fy0", "loads2")),
    ("PEY3", "asymmetry of E_y between positive and negative slip angles",
     _fit("Fy0", "both_signs")),
    ("PEY4", "change of that asymmetry with camber", {"unit": "1/rad", **_fit("Fy0", "camber")}),
    ("PEY5", "change of E_y with camber squared" + _ALSO_52,
     {"versions": V6, "unit": "1/rad**2", **_fit("Fy0", "camber")}),
    ("PKY1", "largest cornering stiffness K_y / F'z0 (negative in ISO files, where a "
             "positive slip angle gives a negative force)",
     {**_REQ, "unit": "1/rad", "sign": (-1, "the lateral force will have the sign of the "
                                            "slip angle (the opposite of ISO files)"),
      **_fit("Fy0")}),
    ("PKY2", "load scale of K_y, / F'z0 (the load of largest K_y when PKY4 = 2)",
     {**_REQ, **_POS, "fit": (0.05, 50.0), **_fit("Fy0", "loads2")}),
    ("PKY3", "change of K_y with the camber's magnitude",
     {"unit": "1/rad", **_fit("Fy0", "camber")}),
    ("PKY4", "curvature of K_y against load (the published MF 5.2 fixes it at 2)" + _ALSO_52,
     {"versions": V6, "default": 2.0, **_POS, "fit": (1.0, 4.0), **_fit("Fy0", "loads3")}),
    ("PKY5", "shift of the load of largest K_y with camber squared" + _ALSO_52,
     {"versions": V6, "unit": "1/rad**2", **_fit("Fy0", "camber")}),
    ("PKY6", "camber stiffness K_yg0 / F_z at the nominal load",
     {"versions": V6, "unit": "1/rad", **_fit("Fy0", "camber")}),
    ("PKY7", "change of the camber stiffness with load",
     {"versions": V6, "unit": "1/rad", **_fit("Fy0", "camber", "loads2")}),
    ("PHY1", "horizontal shift S_Hy at the nominal load", _fit("Fy0")),
    ("PHY2", "change of S_Hy with load", _fit("Fy0", "loads2")),
    ("PHY3", "change of S_Hy with camber",
     {"versions": V52, "unit": "1/rad", **_fit("Fy0", "camber")}),
    ("PVY1", "vertical shift S_Vy / F_z at the nominal load", _fit("Fy0")),
    ("PVY2", "change of S_Vy / F_z with load", _fit("Fy0", "loads2")),
    ("PVY3", "change of S_Vy / F_z with camber", {"unit": "1/rad", **_fit("Fy0", "camber")}),
    ("PVY4", "change of S_Vy / F_z with camber and load",
     {"unit": "1/rad", **_fit("Fy0", "camber", "loads2")}),
    ("PPY1", "change of the largest K_y with pressure",
     {"versions": V6, **_fit("Fy0", "pressure")}),
    ("PPY2", "change of the load of largest K_y with pressure",
     {"versions": V6, **_fit("Fy0", "pressure")}),
    ("PPY3", "linear change of mu_y with pressure", {"versions": V6, **_fit("Fy0", "pressure")}),
    ("PPY4", "quadratic change of mu_y with pressure",
     {"versions": V6, **_fit("Fy0", "pressure3")}),
    ("PPY5", "change of the camber stiffness with pressure",
     {"versions": V6, **_fit("Fy0", "pressure", "camber")}),
    ("RBY1", "slope factor B_yk of the combined-slip weighting G_yk", _fit("Fy", "combined_y")),
    ("RBY2", "change of B_yk with slip angle", _fit("Fy", "combined_y")),
    ("RBY3", "slip-angle shift in B_yk", {"unit": "rad", **_fit("Fy", "combined_y")}),
    ("RCY1", "shape factor C_yk of G_yk", _fit("Fy", "combined_y")),
    ("REY1", "curvature E_yk of G_yk at the nominal load", _fit("Fy", "combined_y")),
    ("REY2", "change of E_yk with load", _fit("Fy", "combined_y", "loads2")),
    ("RHY1", "horizontal shift S_Hyk of G_yk at the nominal load", _fit("Fy", "combined_y")),
    ("RHY2", "change of S_Hyk with load", _fit("Fy", "combined_y", "loads2")),
    ("RVY1", "slip-ratio induced force S_Vyk: its peak / (mu_y F_z) at the nominal load",
     _fit("Fy", "combined_y")),
    ("RVY2", "change of that peak with load", _fit("Fy", "combined_y", "loads2")),
    ("RVY3", "change of that peak with camber",
     {"unit": "1/rad", **_fit("Fy", "combined_y", "camber")}),
    ("RVY4", "fading of S_Vyk with slip angle", _fit("Fy", "combined_y")),
    ("RVY5", "shape of S_Vyk against slip ratio", _fit("Fy", "combined_y")),
    ("RVY6", "slope of S_Vyk against slip ratio", _fit("Fy", "combined_y")),
    ("RBY4", "change of B_yk with camber squared",
     {"versions": V6, "unit": "1/rad**2", **_fit("Fy", "combined_y", "camber")}),
    ("PTY1", "largest lateral relaxation length / R0", {"versions": V52}),
    ("PTY2", "load at which the lateral relaxation length is largest, / F'z0",
     {"versions": V52}),
))

_ALIGNING = _group("ALIGNING_COEFFICIENTS", ALL, "", 0.0, (
    ("QBZ1", "slope factor B_t of the pneumatic trail at the nominal load", _fit("Mz0")),
    ("QBZ2", "change of B_t with load", _fit("Mz0", "loads2")),
    ("QBZ3", "change of B_t with load squared", _fit("Mz0", "loads3")),
    ("QBZ4", "change of B_t with camber", {"unit": "1/rad", **_fit("Mz0", "camber")}),
    ("QBZ5", "change of B_t with the camber's magnitude",
     {"unit": "1/rad", **_fit("Mz0", "camber", "camber_signs")}),
    ("QBZ6", "change of B_t with camber squared in some MF 5.x files; not evaluated",
     {"versions": V52, "unit": "1/rad**2", **_NOT_EVALUATED}),
    ("QBZ9", "slope factor B_r of the residual torque", _fit("Mz0")),
    ("QBZ10", "part of B_r proportional to B_y C_y of the lateral force", _fit("Mz0")),
    ("QCZ1", "shape factor C_t of the pneumatic trail", _fit("Mz0")),
    ("QDZ1", "peak trail D_t / R0 at the nominal load", _fit("Mz0")),
    ("QDZ2", "change of the peak trail with load", _fit("Mz0", "loads2")),
    ("QDZ3", "change of the peak trail with camber", {"unit": "1/rad", **_fit("Mz0", "camber")}),
    ("QDZ4", "change of the peak trail with camber squared",
     {"unit": "1/rad**2", **_fit("Mz0", "camber", "camber_sq")}),
    ("QDZ5", "a peak-trail term some MF 5.x files carry; not evaluated",
     {"versions": V52, **_NOT_EVALUATED}),
    ("QDZ6", "residual torque D_r / (F_z R0) at the nominal load", _fit("Mz0")),
    ("QDZ7", "change of D_r with load", _fit("Mz0", "loads2")),
    ("QDZ8", "change of D_r with camber", {"unit": "1/rad", **_fit("Mz0", "camber")}),
    ("QDZ9", "change of D_r with camber and load",
     {"unit": "1/rad", **_fit("Mz0", "camber", "loads2")}),
    ("QEZ1", "curvature E_t of the trail at the nominal load", _fit("Mz0")),
    ("QEZ2", "change of E_t with load", _fit("Mz0", "loads2")),
    ("QEZ3", "change of E_t with load squared", _fit("Mz0", "loads3")),
    ("QEZ4", "change of E_t with the sign of the slip angle", _fit("Mz0", "both_signs")),
    ("QEZ5", "change of E_t with camber and the sign of the slip angle",
     {"unit": "1/rad", **_fit("Mz0", "camber")}),
    ("QHZ1", "horizontal shift S_Ht of the trail at the nominal load", _fit("Mz0")),
    ("QHZ2", "change of S_Ht with load", _fit("Mz0", "loads2")),
    ("QHZ3", "change of S_Ht with camber", {"unit": "1/rad", **_fit("Mz0", "camber")}),
    ("QHZ4", "change of S_Ht with camber and load",
     {"unit": "1/rad", **_fit("Mz0", "camber", "loads2")}),
    ("QDZ10", "change of D_r with camber squared",
     {"versions": V6, "unit": "1/rad**2", **_fit("Mz0", "camber", "camber2")}),
    ("QDZ11", "change of D_r with camber squared and load",
     {"versions": V6, "unit": "1/rad**2", **_fit("Mz0", "camber", "loads2", "camber2")}),
    ("PPZ1", "change of the peak trail with pressure", {"versions": V6, **_fit("Mz0", "pressure")}),
    ("PPZ2", "change of the residual torque's camber term with pressure",
     {"versions": V6, **_fit("Mz0", "pressure", "camber")}),
    ("SSZ1", "moment arm s / R0 of F_x in M_z", _fit("Mz", "combined_mz")),
    ("SSZ2", "change of s / R0 with F_y / F_z0", _fit("Mz", "combined_mz")),
    ("SSZ3", "change of s / R0 with camber",
     {"unit": "1/rad", **_fit("Mz", "combined_mz", "camber")}),
    ("SSZ4", "change of s / R0 with camber and load",
     {"unit": "1/rad", **_fit("Mz", "combined_mz", "camber", "loads2")}),
    ("QTZ1", "gyroscopic torque constant (MF 5.2); not evaluated",
     {"versions": V52, **_NOT_EVALUATED}),
    ("MBELT", "belt mass of the gyroscopic torque (MF 5.2); not evaluated",
     {"versions": V52, "unit": "kg", **_NOT_EVALUATED}),
))

_OVERTURNING = _group("OVERTURNING_COEFFICIENTS", ALL, "", 0.0, (
    ("QSX1", "vertical shift of M_x / (R0 F_z)"),
    ("QSX2", "change of M_x / (R0 F_z) with camber", {"unit": "1/rad"}),
    ("QSX3", "change of M_x / (R0 F_z) with F_y / F_z0"),
    ("QSX4", "amplitude of the combined camber and lateral-force term of M_x",
     {"versions": V6}),
    ("QSX5", "shape of that term against load", {"versions": V6}),
    ("QSX6", "load scale of that term", {"versions": V6}),
    ("QSX7", "camber in that term", {"versions": V6, "unit": "1/rad"}),
    ("QSX8", "lateral-force shape in that term", {"versions": V6}),
    ("QSX9", "lateral-force scale in that term", {"versions": V6}),
    ("QSX10", "amplitude of the camber term growing with load", {"versions": V6,
                                                                 "unit": "1/rad"}),
    ("QSX11", "load scale of that camber term", {"versions": V6}),
    ("QSX12", "camber-times-|camber| term of M_x", {"versions": V6, "unit": "1/rad**2"}),
    ("QSX13", "lateral-force term of M_x", {"versions": V6}),
    ("QSX14", "lateral-force term of M_x growing with the camber's magnitude",
     {"versions": V6, "unit": "1/rad"}),
    ("PPMX1", "change of the camber term of M_x with pressure", {"versions": V6}),
))

_ROLLING = _group("ROLLING_COEFFICIENTS", ALL, "", 0.0, (
    ("QSY1", "rolling resistance M_y / (R0 F_z), constant part"),
    ("QSY2", "change of M_y with F_x / F_z0"),
    ("QSY3", "change of M_y with speed / LONGVL"),
    ("QSY4", "change of M_y with (speed / LONGVL)^4"),
    ("QSY5", "change of M_y with camber squared", {"versions": V6, "unit": "1/rad**2"}),
    ("QSY6", "change of M_y with camber squared and load", {"versions": V6,
                                                            "unit": "1/rad**2"}),
    ("QSY7", "exponent of the load F_z / F_z0 in M_y", {"versions": V6}),
    ("QSY8", "exponent of the pressure ratio in M_y", {"versions": V6}),
))

_TS = "turn slip: "
_TURNSLIP = _group("TURNSLIP_COEFFICIENTS", ALL, "", 0.0, (
    ("PDXP1", _TS + "reduction of the F_x peak with spin (zeta_1)"),
    ("PDXP2", _TS + "change of that reduction with load"),
    ("PDXP3", _TS + "change of that reduction with slip ratio"),
    ("PKYP1", _TS + "reduction of the cornering stiffness with spin (zeta_3)"),
    ("PDYP1", _TS + "reduction of the F_y peak with spin (zeta_2)"),
    ("PDYP2", _TS + "change of that reduction with load"),
    ("PDYP3", _TS + "change of that reduction with slip angle"),
    ("PDYP4", _TS + "shape of that reduction against spin"),
    ("PHYP1", _TS + "shape C_Hyp of the spin-induced shift of F_y (turn slip needs it "
              "not 0)"),
    ("PHYP2", _TS + "amplitude of that shift at the nominal load"),
    ("PHYP3", _TS + "change of that amplitude with load"),
    ("PHYP4", _TS + "curvature E_Hyp of that shift (<= 1 with the limit checks)"),
    ("PECP1", _TS + "share eps_gamma of the camber not acting as spin, nominal load"),
    ("PECP2", _TS + "change of that share with load"),
    ("QDTP1", _TS + "reduction of the pneumatic trail with spin (zeta_5)"),
    ("QCRP1", _TS + "spin moment at large spin M_zp,inf / (mu_y R0 F_z)"),
    ("QCRP2", _TS + "growth of the spin moment at 90 deg slip with spin"),
    ("QBRP1", _TS + "reduction of the residual torque's slope with spin (zeta_6)"),
    ("QDRP1", _TS + "shape C_Drp of the spin moment, the parking moment (turn slip "
              "needs it not 0)"),
    ("QDRP2", _TS + "change of the spin moment's peak; not evaluated (MFeval 4.0 does "
              "not read it either)", _NOT_EVALUATED),
))

_NOT_NEEDED = None  # no default: refused by the outputs that need it


def _real(bounds: tuple[float, float]) -> dict[str, object]:
    """The overrides of an entry bounded by what real tyres have (refused with a units hint)."""
    return {"bounds": bounds, "hint": UNITS_HINT}


_FILE = [
    *_group("MODEL", ALL, "m/s", _NOT_NEEDED, (
        ("LONGVL", "reference speed V0 of the measurements (the speed of the "
                   "steady-state curves)", _real(SPEED)),
        ("VXLOW", "speed below which the slips are not formed (low speeds refused here)",
         {"bounds": POSITIVE, "default": 0.0}),
    )),
    *_group("DIMENSION", ALL, "m", _NOT_NEEDED, (
        ("UNLOADED_RADIUS", "free (unloaded) tyre radius R0", _real(RADIUS)),
        ("WIDTH", "nominal section width", _real(WIDTH)),
        ("ASPECT_RATIO", "nominal aspect ratio (section height / width)",
         {**_POS, "unit": ""}),
        ("RIM_RADIUS", "rim radius (bottoming of the contact patch)",
         {"bounds": POSITIVE, "default": 0.0}),
        ("RIM_WIDTH", "rim width; not evaluated", {"bounds": POSITIVE, "default": 0.0,
                                                   "evaluated": False}),
    )),
    *_group("VERTICAL", ALL, "", 0.0, (
        ("FNOMIN", "nominal (rated) load F_z0", {**_real(LOAD), **_REQ, "unit": "N",
                                                 "default": None}),
        ("VERTICAL_STIFFNESS", "vertical stiffness C_z0 at the nominal pressure",
         {**_real(STIFFNESS), "unit": "N/m", "default": None}),
        ("BREFF", "effective rolling radius: low-load stiffness factor"),
        ("DREFF", "effective rolling radius: peak value factor"),
        ("FREFF", "effective rolling radius: high-load stiffness factor"),
        ("Q_RE0", "free radius at zero speed / UNLOADED_RADIUS", {**_POS, "default": 1.0}),
        ("Q_V1", "growth of the free radius with rotational speed"),
        ("Q_V2", "growth of the vertical stiffness with rotational speed"),
        ("Q_FZ2", "quadratic term of the load against deflection"),
        ("Q_FCX", "drop of the vertical stiffness with F_x"),
        ("Q_FCY", "drop of the vertical stiffness with F_y"),
        ("Q_FCY2", "change of the F_y drop with deflection", {"versions": V62}),
        ("Q_CAM1", "linear shape of the camber deflection against loaded radius",
         {"versions": V62, "unit": "1/m"}),
        ("Q_CAM2", "quadratic shape of the camber deflection against loaded radius",
         {"versions": V62, "unit": "1/m**2"}),
        ("Q_CAM3", "change of the camber deflection with the free deflection",
         {"versions": V62}),
        ("Q_FYS1", "lateral-force shift of the vertical model with camber",
         {"versions": V62, "unit": "N/rad"}),
        ("Q_FYS2", "change of that shift with loaded radius / free radius",
         {"versions": V62, "unit": "N/rad"}),
        ("Q_FYS3", "quadratic change of that shift with loaded radius",
         {"versions": V62, "unit": "N/rad"}),
        ("PFZ1", "change of the vertical stiffness with pressure", {"versions": V6}),
        ("BOTTOM_OFFST", "distance of the bottoming contact above the rim",
         {"unit": "m", "bounds": POSITIVE}),
        ("BOTTOM_STIFF", "vertical stiffness of the bottoming contact; not evaluated",
         {"unit": "N/m", "bounds": POSITIVE, "evaluated": False}),
        ("VERTICAL_DAMPING", "vertical damping; not evaluated (steady state)",
         {"unit": "N*s/m", "bounds": POSITIVE, "evaluated": False}),
        ("Q_A1", "contact length: square-root load term (0 with Q_A2 = 0: from the "
                 "vertical stiffness)", {"versions": V52}),
        ("Q_A2", "contact length: linear load term", {"versions": V52}),
    )),
    *_group("STRUCTURAL", ALL, "N/m", _NOT_NEEDED, (
        ("LONGITUDINAL_STIFFNESS", "longitudinal carcass stiffness C_x at the nominal "
                                   "load and pressure", _POS),
        ("LATERAL_STIFFNESS", "lateral carcass stiffness C_y at the nominal load and "
                              "pressure", _POS),
        ("PCFX1", "change of C_x with load", {"unit": "", "default": 0.0}),
        ("PCFX2", "change of C_x with load squared", {"unit": "", "default": 0.0}),
        ("PCFX3", "change of C_x with pressure", {"unit": "", "default": 0.0}),
        ("PCFY1", "change of C_y with load", {"unit": "", "default": 0.0}),
        ("PCFY2", "change of C_y with load squared", {"unit": "", "default": 0.0}),
        ("PCFY3", "change of C_y with pressure", {"unit": "", "default": 0.0}),
    )),
    *_group("CONTACT_PATCH", V6, "", 0.0, (
        ("Q_RA1", "contact length: square-root deflection term"),
        ("Q_RA2", "contact length: linear deflection term"),
        ("Q_RB1", "contact width: cube-root deflection term"),
        ("Q_RB2", "contact width: linear deflection term"),
    )),
    *_group("OPERATING_CONDITIONS", V6, "Pa", _NOT_NEEDED, (
        ("INFLPRES", "inflation pressure evaluated by default", _real(PRESSURE)),
        ("NOMPRES", "nominal pressure p_i0 the pressure terms refer to (dpi = 0)",
         _real(PRESSURE)),
    )),
    *_group("TIRE_CONDITIONS", V52, "Pa", _NOT_NEEDED, (
        ("IP", "inflation pressure (PAC2002 files)", _real(PRESSURE)),
        ("IP_NOM", "nominal pressure (PAC2002 files)", _real(PRESSURE)),
    )),
    *_group("VERTICAL_FORCE_RANGE", ALL, "N", _NOT_NEEDED, (
        ("FZMIN", "smallest load of the fitted data", {"bounds": POSITIVE}),
        ("FZMAX", "largest load of the fitted data", _POS),
    )),
    *_group("LONG_SLIP_RANGE", ALL, "", _NOT_NEEDED, (
        ("KPUMIN", "smallest slip ratio of the fitted data"),
        ("KPUMAX", "largest slip ratio of the fitted data"),
    )),
    *_group("SLIP_ANGLE_RANGE", ALL, "rad", _NOT_NEEDED, (
        ("ALPMIN", "smallest slip angle of the fitted data", {"bounds": ANGLE}),
        ("ALPMAX", "largest slip angle of the fitted data", {"bounds": ANGLE}),
    )),
    *_group("INCLINATION_ANGLE_RANGE", ALL, "rad", _NOT_NEEDED, (
        ("CAMMIN", "smallest camber of the fitted data", {"bounds": ANGLE}),
        ("CAMMAX", "largest camber of the fitted data", {"bounds": ANGLE}),
    )),
    *_group("INFLATION_PRESSURE_RANGE", V6, "Pa", _NOT_NEEDED, (
        ("PRESMIN", "smallest pressure of the fitted data", _real(PRESSURE)),
        ("PRESMAX", "largest pressure of the fitted data", _real(PRESSURE)),
    )),
]

#: Every declared entry by name.
DECLARED: dict[str, Coefficient] = {
    c.name: c for c in (_SCALING + _LONGITUDINAL + _LATERAL + _ALIGNING + _OVERTURNING
                        + _ROLLING + _TURNSLIP + _FILE)}
