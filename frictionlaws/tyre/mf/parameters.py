"""One tyre's Magic Formula parameters, checked once: the view the equations read.

:class:`MFParameters` takes the coefficients, the nominal load, the version and the
conventions of one tyre (from a property file, or given in code), checks them once (a
value outside its declared bounds, an unknown version or convention, a pressure that is
not a positive number of Pa, a structure entry outside its bounds) and then holds what
the equations need: the checked coefficients read through a
:class:`~frictionlaws.tyre.mf.coefficients.CoefficientView` (``p.c.PCX1``), the nominal
load F'z0 = FNOMIN LFZO, the friction scaling LMU', the file's structure (radii,
stiffnesses, speeds: :meth:`MFParameters.need`) and validity ranges.  It also checks the
inputs of an evaluation (:meth:`MFParameters.check`, :meth:`MFParameters.warn_range`,
:meth:`MFParameters.dpi`) and the peak friction the equations compute
(:meth:`MFParameters.check_peak`).

:class:`~frictionlaws.tyre.mf.model.MagicFormula` is one; the equations
(:mod:`~frictionlaws.tyre.mf.equations`, :mod:`~frictionlaws.tyre.mf.moments`,
:mod:`~frictionlaws.tyre.mf.vertical`) are plain functions of it.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Mapping
from typing import Any

import numpy as np

from ...base.errors import ExtrapolationWarning, InputError
from ...law import MU_MAX
from .coefficients import CoefficientView, check_values, checked_coefficients, unused_terms

__all__ = ["MFParameters", "real_array", "MF_VERSIONS", "SLIP_ANGLE_INPUTS", "FRICTION_SCALINGS",
           "LOADS_ABOVE_FZMAX", "EQUATIONS", "A_MU", "CONVENTIONS", "check_conventions",
           "POSITIVE_STRUCTURE", "peak_cause", "PLAUSIBLE_PRESSURE", "check_pressure"]

MF_VERSIONS = ("5.2", "6.1", "6.2")
#: Degressive friction-scaling constant A_mu of MF 6.1.
A_MU = 10.0

#: How the slip angle enters the lateral curve: ``tan_alpha`` (the book's alpha*,
#: MFeval useMode +20 "include alpha_star") or ``alpha`` (MFeval "revoke alpha_star",
#: several PAC2002 codes).
SLIP_ANGLE_INPUTS = ("tan_alpha", "alpha")
#: Friction scaling of MF 6.x: ``linear`` (LMU' = LMU, i.e. A = 1: MFeval 4.0) or
#: ``degressive`` (LMU' = A LMU / (1 + (A - 1) LMU), A = 10: Pacejka 2012, eq. 4.E8).
FRICTION_SCALINGS = ("linear", "degressive")
#: Loads above ``FZMAX``: ``extrapolate`` (the equations at the given load, with a
#: warning) or ``clamp`` (evaluated at FZMAX, as MFeval's limit checks do).
LOADS_ABOVE_FZMAX = ("extrapolate", "clamp")
#: Where MFeval 4.0 departs from the published equations: ``mfeval`` (its forms, which
#: its authors matched to TNO's evaluator) or ``published`` (the book and the MF-Tyre
#: 5.2 manual).  See :mod:`frictionlaws.tyre.mf.model`.
EQUATIONS = ("mfeval", "published")
#: The conventions, each an option of the model: name -> its values (default first).
CONVENTIONS: dict[str, tuple[str, ...]] = {
    "slip_angle": SLIP_ANGLE_INPUTS, "friction_scaling": FRICTION_SCALINGS,
    "loads_above_fzmax": LOADS_ABOVE_FZMAX, "equations": EQUATIONS}
#: Structure entries that are lengths or speeds of a real tyre: positive.
POSITIVE_STRUCTURE = frozenset({"UNLOADED_RADIUS", "LONGVL", "WIDTH"})


#: Inflation pressures tyres run at [Pa, gauge]: a bicycle's lowest to an aircraft's.
PLAUSIBLE_PRESSURE = (2e4, 2.5e6)


def check_pressure(pressure: Any, what: str = "pressure", *, file: str | None = None,
                   column: str | None = None, rows: Any = None, unit: str | None = None
                   ) -> None:
    """Refuse an inflation pressure [Pa] no tyre runs at (:data:`PLAUSIBLE_PRESSURE`): a
    unit off by a factor (kPa or bar read as Pa, Pa as kPa), which the pressure terms
    would extrapolate to forces of any size or sign.

    Parameters
    ----------
    pressure : array-like
        Pressures [Pa].
    what : str
        What they are, for the message.
    file, column : str, optional
        Where they were read, named in the message.
    rows : array-like of int, optional
        The source row of each value (named in the message; without it, the 0-based
        index of an array's value).
    unit : str, optional
        The unit they were read in, named in the message as the one that looks off.

    Raises
    ------
    InputError
        Naming the first pressure off, its file, column and row, and the plausible range.
    """
    p = np.asarray(pressure, dtype=float)
    lo, hi = PLAUSIBLE_PRESSURE
    with np.errstate(invalid="ignore"):
        bad = ~((p >= lo) & (p <= hi))
    if not np.any(bad):
        return
    i = int(np.flatnonzero(bad.ravel())[0])
    x = float(p.ravel()[i])
    row = None if rows is None else int(np.asarray(rows).ravel()[i])
    at = f" (row {i})" if rows is None and p.size > 1 else ""
    cause = (f"the unit '{unit}' looks off by a factor (bar or psi as kPa, kPa as Pa?)"
             if unit else "a unit off by a factor?")
    raise InputError(f"{what} {x / 1e3:.4g} kPa{at} is no tyre's inflation pressure (tyres run "
                     f"at {lo / 1e3:g}-{hi / 1e3:g} kPa): {cause}", file=file, column=column,
                     row=row)


def check_conventions(version: str, source: str, **conventions: str) -> None:
    """Refuse an unknown version or convention, naming the allowed values."""
    if version not in MF_VERSIONS:
        raise InputError(f"unknown Magic Formula version {version!r}; expected one of "
                         f"{', '.join(MF_VERSIONS)}", file=source)
    for what, value in conventions.items():
        allowed = CONVENTIONS[what]
        if value not in allowed:
            raise InputError(f"{what} must be one of {', '.join(allowed)}, got {value!r}",
                             file=source)


def _positive_or_none(value: float | None, what: str, source: str) -> float | None:
    """A pressure [Pa]: None, or a positive finite number."""
    if value is None:
        return None
    x = float(value)
    if not (math.isfinite(x) and x > 0):
        raise InputError(f"{what} must be a positive number of Pa, got {x:g}", file=source)
    return x


def peak_cause(limits: Mapping[str, tuple[float, float]], fz: float, gamma: float,
               pressure: float | None) -> str:
    """The likely cause of a peak friction that is none: the input outside the file's
    validity range (load, then camber, then pressure), else the coefficients."""
    def outside(name: str, x: float) -> tuple[float, float] | None:
        lim = limits.get(name)
        return lim if lim is not None and not lim[0] <= x <= lim[1] else None

    lim = outside("fz", fz)
    if lim is not None:
        return (f"the load F_z = {fz:g} N lies outside the file's FZMIN..FZMAX "
                f"{lim[0]:g}..{lim[1]:g} N: too far an extrapolation (check the load "
                "and its unit)")
    lim = outside("gamma", gamma)
    if lim is not None or abs(gamma) > 0.5:
        shown = f" {lim[0]:g}..{lim[1]:g} rad" if lim is not None else ""
        return (f"the camber {gamma:g} rad ({math.degrees(gamma):.4g} deg) lies outside "
                f"the file's range{shown}: degrees passed as radians?")
    if pressure is not None and outside("pressure", pressure) is not None:
        return "check the inflation pressure against the file's range"
    return "check the PD*/LMU* coefficients and the inflation pressure"



def real_array(what: str, x: Any) -> np.ndarray:
    """``x`` as an array of floats, refused when it is not real numbers.

    Text (numbers spelled as text go through the one number parser at the edges, not
    here), bytes, booleans and complex numbers raise
    :class:`~frictionlaws.base.errors.InputError` naming ``what``, as does anything numpy
    cannot read as floats.
    """
    try:
        kind = "U" if isinstance(x, (str, bytes)) else np.asarray(x).dtype.kind
        if kind not in "USbcV":
            return np.asarray(x, dtype=float)
    except (TypeError, ValueError) as err:
        raise InputError(f"{what} must be real numbers: {err}") from None
    raise InputError(f"{what} must be real numbers, got {type(x).__name__} {str(x)[:40]!r}")


class MFParameters:
    """The checked parameters of one tyre's Magic Formula (see the module notes).

    The parameters are those of :class:`~frictionlaws.tyre.mf.model.MagicFormula`, which
    documents them.
    """

    def __init__(self, coefficients: Mapping[str, float], *, fnomin: float,
                 version: str = "5.2", pressure: float | None = None,
                 nominal_pressure: float | None = None,
                 limits: Mapping[str, tuple[float, float]] | None = None,
                 name: str = "", source: str = "<memory>",
                 notes: list[str] | None = None, slip_angle: str = "tan_alpha",
                 friction_scaling: str = "linear",
                 loads_above_fzmax: str = "extrapolate", equations: str = "mfeval",
                 structure: Mapping[str, float] | None = None) -> None:
        check_conventions(version, source, slip_angle=slip_angle,
                          friction_scaling=friction_scaling,
                          loads_above_fzmax=loads_above_fzmax, equations=equations)
        self.equations = equations
        self.slip_angle = slip_angle
        self.friction_scaling = friction_scaling
        self.loads_above_fzmax = loads_above_fzmax
        self.coefficients, read = checked_coefficients(coefficients, fnomin, source)
        self.fnomin = float(fnomin)
        self.version = version
        self.pressure = _positive_or_none(pressure, "the inflation pressure", source)
        self.nominal_pressure = _positive_or_none(nominal_pressure,
                                                  "the nominal inflation pressure", source)
        self.limits = dict(limits or {})
        self.structure = {k.upper(): float(v) for k, v in (structure or {}).items()}
        check_values(self.structure, source)
        self.name = name
        self.source = source
        self.notes = list(notes or [])
        self.notes += [n for n in read + unused_terms(version, self.coefficients,
                                                       self.nominal_pressure is not None)
                       if n not in self.notes]
        if self.c.LFZO <= 0:
            raise InputError("LFZO must be positive", file=source)
        self.six = version.startswith("6")
        #: The options given that this model cannot apply (:meth:`options_not_applied`):
        #: noted, warned of once here, and listed in every result's warnings.
        self.not_applied = self.options_not_applied()
        for text in self.not_applied:  # noted and warned of, once: one rule
            if text not in self.notes:
                self.notes.append(text)
            warnings.warn(text, UserWarning, stacklevel=2)

    @property
    def c(self) -> CoefficientView:
        """The coefficients by attribute (``p.c.PCX1``): given, else the declared default."""
        return CoefficientView(self.coefficients)

    @property
    def fz0(self) -> float:
        """The nominal load the coefficients refer to, F'z0 = FNOMIN LFZO [N]."""
        return self.fnomin * self.c.LFZO

    @property
    def lmux(self) -> float:
        """The friction scaling factor LMUX."""
        return self.c.LMUX

    @property
    def lmuy(self) -> float:
        """The friction scaling factor LMUY."""
        return self.c.LMUY

    @property
    def lmux_prime(self) -> float:
        """LMU'x, the friction scaling of the vertical shifts (``friction_scaling``)."""
        return self._prime(self.lmux)

    @property
    def lmuy_prime(self) -> float:
        """LMU'y, the friction scaling of the vertical shifts (``friction_scaling``)."""
        return self._prime(self.lmuy)

    def _prime(self, lmu: float) -> float:
        a_mu = A_MU if self.friction_scaling == "degressive" else 1.0
        return a_mu * lmu / (1 + (a_mu - 1) * lmu) if self.six else lmu

    def need(self, key: str, default: float | None = None) -> float:
        """A structure entry of the file (SI), or ``default``.

        Raises
        ------
        InputError
            When the file lacks it and there is no default, or a radius, width or speed
            is not positive (a zero radius gives zero moments).
        """
        if key in self.structure:
            value = self.structure[key]
            if key in POSITIVE_STRUCTURE and not value > 0:
                raise InputError(f"{key} = {value:g} (SI) must be positive for the moments "
                                 "and radii", file=self.source)
            return value
        if default is None:
            raise InputError(f"the property file has no {key}, needed for the moments and "
                             "radii", file=self.source)
        return default

    # ---------------------------------------------------- options not applied
    def options_not_applied(self) -> list[str]:
        """The options given that this model cannot apply, each with why (the one rule of
        options that do not apply to a file: noted and warned of, and reported as not
        used, on every path; see :attr:`applied_conventions`).

        ``friction_scaling="degressive"`` with MF 5.2 (LMU' = LMU always),
        ``loads_above_fzmax="clamp"`` without an FZMAX in the file, an inflation
        pressure given to a file without a nominal pressure (no pressure terms).
        """
        label = self.name or "Magic Formula"
        out = []
        if not self.six and self.friction_scaling != "linear":
            out.append(f"{label}: friction_scaling = {self.friction_scaling!r} is not "
                       "applied: MF 5.2 scales the vertical shifts by LMU itself (LMU' = LMU)")
        if self.loads_above_fzmax == "clamp" and "fz" not in self.limits:
            out.append(f"{label}: loads_above_fzmax = 'clamp' is not applied: the file "
                       "gives no FZMAX, so loads are not clamped")
        if self.pressure is not None and self.nominal_pressure is None:
            out.append(self.no_pressure_terms())
        return out

    @property
    def applied_conventions(self) -> dict[str, str]:
        """The conventions as the equations apply them (an option this model cannot apply
        is reported as what is applied instead: :meth:`options_not_applied`)."""
        return {"slip_angle": self.slip_angle,
                "friction_scaling": self.friction_scaling if self.six else "linear",
                "loads_above_fzmax": (self.loads_above_fzmax if "fz" in self.limits
                                      else "extrapolate"),
                "equations": self.equations}

    # ------------------------------------------------------ evaluation inputs
    def no_pressure_terms(self) -> str:
        """Why a pressure does not change this model's outputs (the warning's text)."""
        return (f"{self.name or 'Magic Formula'}: the property file has no nominal pressure "
                "(NOMPRES / IP_NOM), so its pressure terms are not evaluated (dpi = 0): the "
                "pressure given is not used")

    def dpi(self, pressure: Any) -> Any:
        """Relative pressure increment dpi (a float, or an array for a pressure per row).

        ``None`` takes the model's pressure; a pressure given to a model without a
        nominal pressure warns (it cannot change the outputs).
        """
        p = self.pressure if pressure is None else np.asarray(pressure, dtype=float)
        if pressure is not None and self.nominal_pressure is None:
            warnings.warn(self.no_pressure_terms(), UserWarning, stacklevel=4)
        if p is None or self.nominal_pressure is None:
            return 0.0
        if pressure is not None:
            check_pressure(p)
        if not (np.isfinite(p) & (np.asarray(p) > 0)).all():
            bad = np.flatnonzero(~(np.isfinite(p) & (np.asarray(p) > 0)).ravel())[:5].tolist()
            raise InputError("inflation pressure must be positive and finite [Pa]; bad values "
                             f"at flat indices {bad}")
        dpi = (p - self.nominal_pressure) / self.nominal_pressure
        return float(dpi) if np.ndim(dpi) == 0 else dpi

    def check(self, what: str, x: Any, positive: bool = False) -> Any:
        """``x`` as a float array, refused when not finite (or, ``positive``, not > 0)."""
        x = real_array(what, x)
        ok = (x > 0).all() if positive else np.isfinite(x).all()
        if not ok:
            bad = ~(x > 0) if positive else ~np.isfinite(x)
            idx = np.flatnonzero(bad.ravel())[:5].tolist()
            need = "positive finite loads [N]" if positive else "finite values"
            raise InputError(f"{what} must hold {need}; bad values at flat indices {idx}")
        if positive and not np.isfinite(x).all():
            raise InputError(f"{what} must be finite")
        return x

    def warn_range(self, name: str, x: Any) -> None:
        """Warn (:class:`~frictionlaws.base.errors.ExtrapolationWarning`) when ``x`` leaves the
        file's validity range of ``name`` (``fz``, ``kappa``, ``alpha``, ``gamma``,
        ``pressure``), naming how many of the values lie below and above it and how far."""
        lim = self.limits.get(name)
        if lim is None or np.size(x) == 0:  # empty: no point to check, empty results
            return
        lo, hi = lim
        x = np.asarray(x, dtype=float)
        below, above = x < lo - 1e-12 * abs(lo), x > hi + 1e-12 * abs(hi)
        n_below, n_above = int(np.sum(below)), int(np.sum(above))
        if not n_below and not n_above:
            return
        sides = ([f"{n_below} below it, down to {float(np.min(x[below])):g}"] if n_below
                 else []) + ([f"{n_above} above it, up to {float(np.max(x[above])):g}"]
                             if n_above else [])
        warnings.warn(
            f"{self.name or 'Magic Formula'}: {name} of {n_below + n_above} of {x.size} "
            f"value(s) lies outside the property file's range {lo:g}..{hi:g} (SI), "
            f"{' and '.join(sides)}: extrapolation", ExtrapolationWarning, stacklevel=3)

    def clamp(self, name: str, x: Any, why: str) -> tuple[Any, Any]:
        """``x`` clipped to the file's range of ``name``, and the mask of the values
        clipped; warns once (:class:`~frictionlaws.base.errors.ExtrapolationWarning`) naming how
        many were clamped and why (``why``: the option that asked for it)."""
        lo, hi = self.limits[name]
        x = np.asarray(x, dtype=float)
        clipped = np.clip(x, lo, hi)
        rows = clipped != x
        if np.any(rows):
            out = x[rows]
            warnings.warn(
                f"{self.name or 'Magic Formula'}: {name} of {int(np.sum(rows))} value(s), "
                f"from {float(np.min(out)):g} to {float(np.max(out)):g}, lies outside the "
                f"property file's range {lo:g}..{hi:g} (SI): evaluated at the range's end "
                f"(clamped, {why})", ExtrapolationWarning, stacklevel=3)
        return clipped, rows

    def limit(self, name: str, x: Any, saturate: bool) -> tuple[Any, Any]:
        """An input of the equations within the file's range of ``name``: clamped to it
        (``saturate``: as MFeval's limit checks do), else as given with a warning outside
        it.  Returns the values and the mask of those clamped."""
        if saturate and name in self.limits:
            return self.clamp(name, x, "saturate=True")
        self.warn_range(name, x)
        return x, np.zeros(np.shape(x), dtype=bool)

    def evaluated_load(self, fz: Any, saturate: bool = False) -> Any:
        """The load the force equations take for ``fz`` [N]: at most FZMAX when
        ``loads_above_fzmax="clamp"`` (or ``saturate``) and the file gives one, else
        ``fz`` (no warning: :meth:`limit_loads` warns)."""
        lim = self.limits.get("fz")
        fz = np.asarray(fz, dtype=float)
        if lim is None or not (saturate or self.loads_above_fzmax == "clamp"):
            return fz
        return np.minimum(fz, lim[1])

    def limit_loads(self, fz: Any, saturate: bool = False) -> tuple[Any, Any]:
        """The loads of the force equations: above FZMAX clamped to it when
        ``loads_above_fzmax="clamp"`` (or ``saturate``), with a warning naming them; the
        others as given, warned about outside the file's range.  Returns the loads and the
        mask of those clamped."""
        lim = self.limits.get("fz")
        fz = np.asarray(fz, dtype=float)
        if lim is None or not (saturate or self.loads_above_fzmax == "clamp"):
            self.warn_range("fz", fz)
            return fz, np.zeros(fz.shape, dtype=bool)
        why = "saturate=True" if saturate else "loads_above_fzmax='clamp'"
        low = fz[fz <= lim[1]]
        if low.size and not saturate:  # below FZMIN: extrapolated (saturate: see Conditions)
            self.warn_range("fz", low)
        above = fz > lim[1]
        if np.any(above):
            warnings.warn(
                f"{self.name or 'Magic Formula'}: fz of {int(np.sum(above))} value(s), from "
                f"{float(np.min(fz[above])):g} to {float(np.max(fz[above])):g}, lies above "
                f"the property file's FZMAX {lim[1]:g} (SI): evaluated at FZMAX (clamped, "
                f"{why})", ExtrapolationWarning, stacklevel=3)
        return self.evaluated_load(fz, saturate), above

    def check_peak(self, name: str, mu: Any, fz: Any, dpi: Any, gamma: Any = 0.0) -> None:
        """Refuse a peak friction that is no friction coefficient (<= 0 or > MU_MAX).

        Called by the equations with every peak friction they compute; a model being
        fitted records it instead (:class:`~frictionlaws.tyre.mf.fit.peak.FittingModel`).
        """
        bad = ~((np.asarray(mu) > 0) & (np.asarray(mu) <= MU_MAX))
        if not np.any(bad):
            return
        shape = np.shape(mu) or (1,)
        i = int(np.flatnonzero(np.broadcast_to(bad, shape).ravel())[0])
        mu_i = float(np.ravel(mu)[i] if np.ndim(mu) else mu)
        fz_i, dpi_i, g_i = (float(np.ravel(np.broadcast_to(x, shape))[i])
                            for x in (fz, dpi, gamma))
        p = self.nominal_pressure * (1 + dpi_i) if self.nominal_pressure else None
        at = (f"F_z = {fz_i:g} N" + (f", camber {g_i:g} rad" if g_i else "")
              + (f", inflation {p / 1e6:.4g} MPa" if p else ""))
        raise InputError(
            f"{self.name or 'Magic Formula'}: the peak friction {name} = {mu_i:.4g} at {at} "
            f"is not a friction coefficient (expected 0 < {name} <= {MU_MAX:g}); "
            + peak_cause(self.limits, fz_i, g_i, p), file=self.source)
