"""What is done with the declared coefficients: defaults, checks, fit stages, the checked view.

The declarations themselves (section, versions, unit, meaning, default, bounds, fit stage)
are :data:`~frictionlaws.tyre.mf.declarations.DECLARED`; this module holds what the rest
of the Magic Formula does with them:

* :class:`CoefficientView`, the checked view the equations read (``c.PCX1``: the value
  given, else the declared default; an undeclared name is an error, not a silent 0);
* the checks of a model's values (:func:`checked_coefficients`, :func:`check_values`,
  :func:`outside_fit`) and the notes of terms a version does not use
  (:func:`unused_terms`);
* the fit stages (:func:`stage_names`, :func:`needs_met`, :func:`fit_bounds`,
  :func:`direction_of`, :func:`section_of`), read by :mod:`frictionlaws.tyre.mf.fit`;
* the listing of ``tyre mf --coefficients`` (:func:`listing`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

from ...base.errors import InputError
from .declarations import (
    COEFFICIENT_SECTIONS,
    DECLARED,
    NEEDS,
    RANGE_SECTIONS,
    SECTIONS,
    Coefficient,
)

__all__ = ["CoefficientView", "RecordingValues", "default", "section_keys", "fit_bounds",
           "check_values", "checked_coefficients", "unused_terms", "outside_fit", "listing",
           "rows", "stage_names", "needs_met", "ALL_NEEDS", "direction_of", "section_of",
           "NOT_READ_BY_52", "PRESSURE_TERMS", "DEFAULTS"]

#: The declared default of every entry that has one.
DEFAULTS: dict[str, float] = {c.name: c.default for c in DECLARED.values()
                              if c.default is not None}


class CoefficientView:
    """The coefficients of one tyre, read by attribute: ``c.PCX1``.

    The value of a declared name is the one given (in the mapping the view reads, at the
    time it is read: a fit changes the mapping between evaluations), else its declared
    default (:data:`DEFAULTS`).  A name that is not declared, or has no default and is
    not given, raises :class:`AttributeError`: a misspelt coefficient in the equations
    fails the first time it is evaluated instead of reading as 0.

    Parameters
    ----------
    values : mapping
        Upper-case name -> value (checked already: see :func:`checked_coefficients`).
    """

    __slots__ = ("_values",)

    def __init__(self, values: Mapping[str, float]) -> None:
        self._values = values

    def __getattr__(self, name: str) -> float:
        value = self._values.get(name)
        if value is not None:
            return value
        try:
            return DEFAULTS[name]
        except KeyError:
            raise AttributeError(f"{name} is not a declared Magic Formula coefficient with "
                                 "a default") from None


class RecordingValues(dict):
    """A coefficient mapping that records every name read through :meth:`get`.

    The view reads with ``get``; :func:`frictionlaws.tyre.mf.outputs.coefficient_users`
    evaluates each output with one of these to find the coefficients it uses.
    """

    def __init__(self, *args: object, **kwargs: object) -> None:
        super().__init__(*args, **kwargs)
        self.read: set[str] = set()

    def get(self, key: str, default: object = None) -> object:
        self.read.add(key)
        return super().get(key, default)


def default(name: str) -> float:
    """The value the evaluator takes for ``name`` when it is absent.

    Raises
    ------
    KeyError
        ``name`` is not declared, or has no default (a programming error: the evaluator
        reads only declared names, and those without a default are checked before).
    """
    value = DECLARED[name].default
    if value is None:
        raise KeyError(f"{name} has no default")
    return value


def section_keys() -> dict[str, frozenset[str]]:
    """The declared names of each coefficient section (what a file may hold there)."""
    return {sec: frozenset(c.name for c in DECLARED.values() if c.section == sec)
            for sec in COEFFICIENT_SECTIONS}


def fit_bounds() -> dict[str, tuple[float, float]]:
    """The search range of every declared coefficient whose range is not unbounded."""
    out = {}
    for c in DECLARED.values():
        if c.section in COEFFICIENT_SECTIONS:
            lo, hi = c.fit_range()
            if math.isfinite(lo) or math.isfinite(hi):
                out[c.name] = (lo, hi)
    return out


def check_values(values: Mapping[str, float], source: str) -> None:
    """Refuse declared values outside their bounds (the first, by section and name).

    Parameters
    ----------
    values : mapping
        Name (upper case) -> value in SI; undeclared names are not checked here.
    source : str
        The file or object the values come from, for the message.

    Raises
    ------
    InputError
        Naming the section, the name, the value and the bounds.
    """
    for name, value in values.items():
        c = DECLARED.get(name)
        if c is not None and not c.allows(float(value)):
            raise InputError(c.refusal(f"{float(value):g}"), file=source)


def checked_coefficients(coefficients: Mapping[str, float], fnomin: float, source: str
                         ) -> tuple[dict[str, float], list[str]]:
    """The coefficients by upper-case name, finite and within their bounds; FNOMIN too.

    A name spelled another way (LFZ0 for LFZO) is read as its name, with a note;
    undeclared names are kept (the evaluator does not read them).

    Parameters
    ----------
    coefficients : mapping
        Name -> value.
    fnomin : float
        The nominal load [N].
    source : str
        Where they come from, for messages.

    Returns
    -------
    coefficients : dict
        Upper-case name -> value.
    notes : list of str
        What was read another way.

    Raises
    ------
    InputError
        A value that is not finite or outside its bounds, a required coefficient missing,
        or two spellings that disagree.
    """
    check_values({"FNOMIN": fnomin}, source)
    out = {k.upper(): float(v) for k, v in coefficients.items()}
    for k, v in out.items():
        if not math.isfinite(v):
            raise InputError(f"coefficient {k} is not finite", file=source)
    check_values(out, source)
    for c in DECLARED.values():
        if c.required and c.section in COEFFICIENT_SECTIONS and c.name not in out:
            raise InputError(f"[{c.section}] {c.name} is missing ({c.meaning}): not a Magic "
                             "Formula property file?", file=source)
    notes = [n for n in (outside_fit(k, v) for k, v in out.items()) if n]
    for k, c in DECLARED.items():
        if c.alias_of is None or k not in out:
            continue
        if c.alias_of in out and out[c.alias_of] != out[k]:
            raise InputError(f"{k} = {out[k]:g} and {c.alias_of} = {out[c.alias_of]:g} are "
                             "two spellings of one scaling factor: keep one", file=source)
        out[c.alias_of] = out[k]
        notes.append(f"{k} read as {c.alias_of} (another spelling of the same factor)")
    return out, notes


#: MF 6.x coefficients the MF 5.2 evaluation does not read: its camber stiffness is
#: PHY3/PVY3's and its rolling resistance has no camber, load exponent or pressure terms.
#: The other 6.x terms (pressure, M_x, the combined-slip camber terms) it reads, as
#: MFeval does.
NOT_READ_BY_52 = frozenset({"PKY6", "PKY7", "PPY5", "QSY5", "QSY6", "QSY7", "QSY8"})
#: The coefficients of the inflation pressure, read only with a nominal pressure.
PRESSURE_TERMS = frozenset(c.name for c in DECLARED.values()
                           if c.section in COEFFICIENT_SECTIONS
                           and (c.name.startswith(("PPX", "PPY", "PPZ", "PPMX"))
                                or c.name == "QSY8"))


def unused_terms(version: str, coefficients: Mapping[str, float], nominal_pressure: bool
                 ) -> list[str]:
    """Notes of the given coefficients a model of ``version`` does not use (else none).

    Parameters
    ----------
    version : str
        The MF version evaluated.
    coefficients : mapping
        Upper-case name -> value.
    nominal_pressure : bool
        Whether the model has a nominal pressure (without one the pressure terms vanish).

    Returns
    -------
    list of str
        The 6.x terms MF 5.2 does not read; the pressure terms without a nominal
        pressure (only those not 0).
    """
    notes = []
    if version == "5.2":
        not_52 = sorted(NOT_READ_BY_52 & set(coefficients))
        if not_52:
            notes.append(f"{', '.join(not_52)}: MF 6.x terms not used by the MF 5.2 "
                         "equations (kept, listed as not used)")
    pressure = sorted(k for k in PRESSURE_TERMS & set(coefficients)
                      if coefficients[k] != 0 and k not in NOT_READ_BY_52 | {"QSY8"})
    if pressure and not nominal_pressure:
        notes.append(f"{', '.join(pressure)}: pressure terms not used, the file has no "
                     "nominal pressure (NOMPRES / IP_NOM), so dpi = 0")
    return notes


def outside_fit(name: str, value: float) -> str | None:
    """A note when ``value`` lies outside the declared fit range of ``name``, or has the
    other sign than the ISO convention gives it (else None)."""
    c = DECLARED.get(name)
    if c is not None and c.sign is not None and value * c.sign[0] < 0:
        want = "< 0" if c.sign[0] < 0 else "> 0"
        return (f"[{c.section}] {name} = {value:g}: the ISO convention of property files "
                f"has {name} {want}; {c.sign[1]}")
    if c is None or c.fit is None or c.fit[0] <= value <= c.fit[1]:
        return None
    return (f"[{c.section}] {name} = {value:g} lies outside {c.fit[0]:g} .. {c.fit[1]:g}, "
            "the range fit-mf searches: unusual for a tyre")


def listing(version: str, coefficients: Mapping[str, float], structure: Mapping[str, float]
            ) -> list[dict[str, object]]:
    """A model's values beside their declarations, for ``tyre mf --coefficients``.

    Parameters
    ----------
    version : str
        The MF version evaluated: its evaluated coefficients and structure entries are
        listed, with the value given or the default taken.
    coefficients, structure : mapping
        Name -> value of the model (SI); names not declared are listed last as unknown.

    Returns
    -------
    list of dict
        ``name``, ``section``, ``value`` (None: absent without a default), ``given``
        (False: the declared default), ``unit``, ``meaning``, ``stage`` (the fit stage that
        fits it, or None).
    """
    given = {**structure, **coefficients}
    out: list[dict[str, object]] = []
    listed = rows(version)
    for c in listed:
        if c.section in RANGE_SECTIONS or c.alias_of or not c.evaluated:
            continue
        value = given.get(c.name, c.default)
        out.append({"name": c.name, "section": c.section, "value": value,
                    "given": c.name in given, "unit": c.unit, "meaning": c.meaning,
                    "stage": c.stage})
    used = {c.name for c in listed if c.evaluated}
    for c in rows():
        if c.name not in coefficients or c.name in used or c.alias_of:
            continue
        meaning = c.meaning  # a 6.x term MF 5.2 reads too, as MFeval does
        if not (version == "5.2" and c.evaluated and c.section in COEFFICIENT_SECTIONS
                and c.name not in NOT_READ_BY_52):
            why = f"not used by MF {version}" if version not in c.versions else "not used"
            meaning = f"{why}: {c.meaning}"
        out.append({"name": c.name, "section": c.section, "value": coefficients[c.name],
                    "given": True, "unit": c.unit, "meaning": meaning, "stage": c.stage})
    order = {sec: i for i, sec in enumerate(SECTIONS)}
    out.sort(key=lambda row: order[str(row["section"])])
    for name in sorted(set(coefficients) - set(DECLARED)):
        out.append({"name": name, "section": "", "value": coefficients[name], "given": True,
                    "unit": "", "meaning": "unknown: kept, not used", "stage": None})
    return out


def rows(version: str | None = None) -> list[Coefficient]:
    """The declarations in section order (only those of ``version`` when given)."""
    order = {sec: i for i, sec in enumerate(SECTIONS)}
    chosen = [c for c in DECLARED.values() if version is None or version in c.versions]
    return sorted(chosen, key=lambda c: order[c.section])


# ------------------------------------------------------------------ fit stages

#: Every need a coefficient may declare (a stage whose coefficients were screened already
#: refits them with all of these counted as met).
ALL_NEEDS = frozenset(NEEDS)


def stage_names(stage: str, version: str) -> list[str]:
    """The coefficients the fit stage ``stage`` fits for ``version``, in declaration order.

    Parameters
    ----------
    stage : str
        One of :data:`~frictionlaws.tyre.mf.declarations.STAGES` (``"Fx0"``, ``"Mz"``...).
    version : str
        The Magic Formula version fitted.

    Returns
    -------
    list of str
        The names, in the order the stage fits them.
    """
    return [c.name for c in DECLARED.values() if c.stage == stage and version in c.versions]


def needs_met(name: str, have: set[str] | frozenset[str]) -> bool:
    """True when the data span everything ``name`` needs (its declared ``needs``)."""
    c = DECLARED.get(name)
    return c is None or all(n in have for n in c.needs)


def direction_of(name: str) -> str:
    """"x", "y" or "z": the quantity a fitted coefficient is fitted to.

    Raises
    ------
    KeyError
        ``name`` is not fitted (no stage declared).
    """
    direction = DECLARED[name].direction
    if direction is None:
        raise KeyError(f"{name} is not fitted by a stage")
    return direction


def section_of(name: str) -> str:
    """The property-file section of a declared name."""
    return DECLARED[name].section
