"""A Magic Formula property file's content, and what it says about the tyre.

:class:`PropertyFile` is the content of an ADAMS ``.tir`` file or its JSON variant (read and
written by :mod:`frictionlaws.tyre.mf.tir`): named sections of ``KEY = value`` entries.
Keys and section names are case-insensitive (stored in upper case).  The ``[UNITS]``
section is honoured: :meth:`PropertyFile.si` converts the dimensional entries (loads,
lengths, pressures, stiffnesses) to SI with pint.

What the file says about the tyre is read here, in one place, by
:meth:`PropertyFile.model_inputs`: the version of the equations (FITTYP /
PROPERTY_FILE_FORMAT / the coefficients), the coefficients, the nominal load, the
inflation and nominal pressures, the validity ranges and the structure (radii,
stiffnesses, speeds), all in SI, after the entries are checked against their
declarations (:mod:`frictionlaws.tyre.mf.declarations`).
"""

from __future__ import annotations

import difflib
import math
import re
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ...base.errors import InputError
from ...base.numbers import is_number, parse_number
from ...base.sanitize import ascii_line
from ...base.units import parse_unit_text, unit_registry
from .coefficients import outside_fit, section_keys
from .declarations import COEFFICIENT_SECTIONS, DECLARED, STRUCTURE_SECTIONS

__all__ = ["PropertyFile", "Value", "DIMENSIONAL", "MF_KEYS", "format_number", "RANGES",
           "FITTYP_VERSIONS", "version_of", "file_pressures", "file_limits",
           "file_coefficients", "file_structure", "model_inputs"]

Value = float | str


#: The SI symbols of the declarations' units and the file's ``[UNITS]`` entry each is
#: converted from (a unit per radian is per radian in every file: angles must be radians).
_UNIT_KINDS = {"N": "force", "m": "length", "s": "time", "kg": "mass", "Pa": "pressure"}


def _unit_kind(unit: str) -> str | None:
    """The kind of a declared SI unit (``"N/m"`` -> ``"force/length"``), None if none."""
    kind = re.sub(r"/rad(\*\*[0-9])?|\brad(\*\*[0-9])?\b", "", unit)
    kind = re.sub(r"\b(N|m|s|kg|Pa)\b", lambda m: _UNIT_KINDS[m.group(1)], kind)
    return kind if re.search(r"force|length|time|mass|pressure", kind) else None


#: Dimensional entries and the kind of unit they carry, for :meth:`PropertyFile.si`,
#: from the declarations' units (:mod:`frictionlaws.tyre.mf.declarations`).  Everything
#: else a Magic Formula uses is dimensionless or an angle (radians).
DIMENSIONAL = {(c.section, c.name): kind for c in DECLARED.values()
               if (kind := _unit_kind(c.unit)) is not None}


#: The coefficient names of the Magic Formula 5.2 (PAC2002), 6.1 and 6.2 property
#: files, per section (from the declarations, :mod:`frictionlaws.tyre.mf.declarations`):
#: a key of a coefficient section outside this list is unknown (listed to the user, or
#: refused when it is a near miss of an absent name).
MF_KEYS: dict[str, frozenset[str]] = section_keys()


@dataclass
class PropertyFile:
    """The content of a Magic Formula property file.

    Attributes
    ----------
    sections : dict
        Section name (upper case) -> {key (upper case) -> float or str}.
    tables : dict
        Section name -> (column names, list of rows) for table sections.
    metadata : dict
        Top-level JSON members that are not sections (``Name``, ``Mass``...).
    path : str
        Where it was read from (``"<memory>"`` when built in code).
    format : str
        ``"tir"`` or ``"json"``.
    lines : dict
        (section, key) -> line number in a ``.tir`` file, for messages.
    comments : dict
        (section, key) -> the trailing ``$comment`` of a ``.tir`` entry.
    """

    sections: dict[str, dict[str, Value]]
    tables: dict[str, tuple[list[str], list[list[float]]]] = field(default_factory=dict)
    metadata: dict[str, Any] = field(default_factory=dict)
    path: str = "<memory>"
    format: str = "tir"
    lines: dict[tuple[str, str], int] = field(default_factory=dict)
    comments: dict[tuple[str, str], str] = field(default_factory=dict)

    # ----------------------------------------------------------------- access
    def has(self, section: str, key: str) -> bool:
        """True when ``[section] key`` is present."""
        return key.upper() in self.sections.get(section.upper(), {})

    def get(self, section: str, key: str, default: Any = None) -> Any:
        """The raw value of ``[section] key`` (float or str), or ``default``."""
        return self.sections.get(section.upper(), {}).get(key.upper(), default)

    def number(self, section: str, key: str, default: float | None = None) -> float:
        """``[section] key`` as a float (file units); ``default`` when absent.

        Raises
        ------
        InputError
            When the entry is absent and no default is given, or is not a number.
        """
        section, key = section.upper(), key.upper()
        value = self.sections.get(section, {}).get(key)
        if value is None:
            if default is None:
                raise InputError(f"[{section}] {key} is missing", file=self.path)
            return float(default)
        if isinstance(value, str):
            raise InputError(f"[{section}] {key} = '{value}' is text, expected a number",
                             file=self.path, row=self.lines.get((section, key)))
        return float(value)

    def text(self, section: str, key: str, default: str | None = None) -> str | None:
        """``[section] key`` as text (numbers are formatted), or ``default``."""
        value = self.get(section, key)
        if value is None:
            return default
        return value if isinstance(value, str) else format_number(value)

    def coefficients(self, *sections: str) -> dict[str, float]:
        """All numeric entries of ``sections`` merged into one dict (upper-case keys)."""
        out: dict[str, float] = {}
        for sec in sections:
            for k, v in self.sections.get(sec.upper(), {}).items():
                if not isinstance(v, str):
                    out[k] = float(v)
        return out

    def check_coefficients(self) -> list[str]:
        """Check the coefficient sections against :data:`MF_KEYS`.

        Returns
        -------
        list of str
            A note listing unknown keys (kept, not used), when there are any.

        Raises
        ------
        InputError
            A coefficient that is text instead of a number, or an unknown key that
            is a near miss of a standard name the file lacks (a misspelling that
            would silently leave the coefficient at its default).
        """
        unknown: list[str] = []
        for sec, known in MF_KEYS.items():
            entries = self.sections.get(sec, {})
            for key, value in entries.items():
                row = self.lines.get((sec, key))
                if isinstance(value, str):
                    raise InputError(f"[{sec}] {key} = '{value}' is text, expected a number",
                                     file=self.path, row=row)
                if key in known:
                    continue
                home = next((other for other, names in MF_KEYS.items() if key in names), None)
                if home is not None:
                    raise InputError(
                        f"[{sec}] {key} belongs to [{home}]: is the [{home}] header missing "
                        "above it?", file=self.path, row=row)
                near = [k for k in difflib.get_close_matches(key, known, n=3, cutoff=0.75)
                        if k not in entries]
                if near:
                    raise InputError(
                        f"[{sec}] unknown key {key}: did you mean {' or '.join(near)}? "
                        f"({near[0]} is absent, so it would take its default)",
                        file=self.path, row=row)
                unknown.append(f"[{sec}] {key}")
        notes = self.check_bounds()
        if unknown:
            notes.append("unknown keys kept but not used by the Magic Formula: "
                         + ", ".join(unknown))
        return notes

    def check_bounds(self) -> list[str]:
        """Check every declared entry against its bounds (in SI, with ``[UNITS]``).

        Returns
        -------
        list of str
            Notes of values outside the range fit-mf searches (possible, but unusual).

        Raises
        ------
        InputError
            A value outside the physically possible ones, naming section, key, value,
            the bounds and the line.
        """
        notes: list[str] = []
        for sec, entries in self.sections.items():
            for key, value in entries.items():
                c = DECLARED.get(key)
                if c is None or isinstance(value, str) or not (
                        c.section == sec or (sec in STRUCTURE_SECTIONS
                                             and c.section in STRUCTURE_SECTIONS)):
                    continue
                si = self.si(sec, key)
                if not c.allows(si):
                    shown = f"{value:g}" + (f" ({si:g} SI)" if si != value else "")
                    raise InputError(c.refusal(shown, sec), file=self.path,
                                     row=self.lines.get((sec, key)))
                note = outside_fit(key, si)
                if note:
                    notes.append(note)
        return notes

    # ------------------------------------------------------------------ units
    def unit(self, kind: str) -> str:
        """The unit the file declares for ``kind`` (LENGTH, FORCE, ANGLE, MASS, TIME, PRESSURE).

        Missing entries mean SI (meter, newton, radian, kg, second, pascal).
        """
        defaults = {"LENGTH": "meter", "FORCE": "newton", "ANGLE": "radian", "MASS": "kg",
                    "TIME": "second", "PRESSURE": ""}
        value = self.text("UNITS", kind, defaults[kind.upper()])
        return (value or "").strip()

    def si(self, section: str, key: str, default: float | None = None) -> float:
        """``[section] key`` converted to SI with the file's ``[UNITS]`` (pint).

        Dimensionless entries are returned unchanged.  ``default`` is taken as
        already SI.
        """
        section, key = section.upper(), key.upper()
        if not self.has(section, key):
            if default is None:
                raise InputError(f"[{section}] {key} is missing", file=self.path)
            return float(default)
        value = self.number(section, key)
        kind = DIMENSIONAL.get((section, key))
        if kind is None:
            return value
        return value * self.si_factor(kind)

    def si_factor(self, kind: str) -> float:
        """Factor from the file's unit of ``kind`` (e.g. ``"force/length"``) to SI.

        The file's units are read by the one unit grammar
        (:func:`~frictionlaws.base.units.parse_unit_text`), never evaluated by pint.
        """
        ureg = unit_registry()
        pieces = {"force": self.unit("FORCE"), "length": self.unit("LENGTH"),
                  "time": self.unit("TIME"), "mass": self.unit("MASS")}
        if kind == "pressure" and self.unit("PRESSURE"):
            expr, target = _pint_name(self.unit("PRESSURE")), "pascal"
        else:
            formula = "force/length**2" if kind == "pressure" else kind
            expr = re.sub(r"\b(force|length|time|mass)\b",
                          lambda m: f"({_pint_name(pieces[m.group(1)])})", formula)
            target = re.sub(r"\b(force|length|time|mass)\b",
                            lambda m: {"force": "newton", "length": "meter", "time": "second",
                                       "mass": "kilogram"}[m.group(1)], formula)
        try:
            unit = parse_unit_text(expr).to_pint()
            return float(ureg.Quantity(1.0, unit).to(target).magnitude)
        except Exception as exc:  # noqa: BLE001 - pint raises several types
            raise InputError(f"[UNITS] cannot convert '{ascii_line(expr)[:80]}' to {target} "
                             f"({ascii_line(exc)[:120]})", file=self.path) from None

    def check_angle_unit(self) -> None:
        """Raise when the file's angles are not in radians (coefficients assume radians)."""
        unit = self.unit("ANGLE").lower()
        if unit not in ("radian", "radians", "rad"):
            ureg = unit_registry()
            try:
                angle = parse_unit_text(_pint_name(unit)).to_pint()
                factor = float(ureg.Quantity(1.0, angle).to("radian").magnitude)
            except Exception:  # noqa: BLE001
                factor = math.nan
            if factor != 1.0:
                raise InputError(
                    f"[UNITS] ANGLE = '{unit}': only property files with angles in radians "
                    "are supported (slip-angle and camber coefficients are defined per "
                    "radian); convert the file", file=self.path,
                    row=self.lines.get(("UNITS", "ANGLE")))

    def __repr__(self) -> str:
        return (f"<PropertyFile {self.path!r} ({self.format}): "
                f"{len(self.sections)} sections>")


def _pint_name(unit: str) -> str:
    """Unit names as ADAMS writes them -> names pint knows."""
    u = unit.strip().strip("'").strip()
    aliases = {"METER": "meter", "MM": "millimeter", "CM": "centimeter", "KM": "kilometer",
               "NEWTON": "newton", "KN": "kilonewton", "N": "newton", "KGF": "kilogram_force",
               "POUND_FORCE": "pound_force", "LBF": "pound_force", "SECOND": "second",
               "SEC": "second", "MILLI": "millisecond", "PASCAL": "pascal", "KPA": "kilopascal",
               "MPA": "megapascal", "BAR": "bar", "PSI": "psi", "RADIAN": "radian",
               "RADIANS": "radian", "DEGREE": "degree", "DEGREES": "degree", "DEG": "degree"}
    return aliases.get(u.upper(), u)


def format_number(x: float) -> str:
    """A number as a property file writes it: integers without a point, else ``repr``."""
    if float(x).is_integer() and abs(x) < 1e15:
        return str(int(x))
    return repr(float(x))


# --------------------------------------------------- what the file says about the tyre

#: FITTYP -> Magic Formula version.
FITTYP_VERSIONS = {5: "5.2", 6: "5.2", 21: "5.2", 61: "6.1", 62: "6.2"}

#: Validity ranges of a property file: name, section, MIN key, MAX key, and whether the
#: values carry a unit (load, pressure) or are plain numbers (slips and angles, rad).
RANGES = (("fz", "VERTICAL_FORCE_RANGE", "FZMIN", "FZMAX", True),
          ("kappa", "LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", False),
          ("alpha", "SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", False),
          ("gamma", "INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", False),
          ("pressure", "INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX", True))


def version_of(pf: PropertyFile) -> tuple[str, str]:
    """(version, how it was decided) from FITTYP / PROPERTY_FILE_FORMAT / the coefficients."""
    fittyp = pf.get("MODEL", "FITTYP")
    if isinstance(fittyp, str) and is_number(fittyp):
        fittyp = parse_number(fittyp)  # quoted ('61' or "61"): the same version number
    fmt = (pf.text("MODEL", "PROPERTY_FILE_FORMAT", "") or "").upper()
    if fittyp is not None:
        if not isinstance(fittyp, float) or fittyp not in FITTYP_VERSIONS:
            raise InputError(
                f"[MODEL] FITTYP = {pf.text('MODEL', 'FITTYP')}: not a Magic Formula "
                "version evaluated here (5, 6 or 21: MF 5.2 / PAC2002; 61: MF 6.1; "
                "62: MF 6.2)", file=pf.path,
                row=pf.lines.get(("MODEL", "FITTYP")))
        return FITTYP_VERSIONS[int(fittyp)], f"FITTYP = {int(fittyp)}"
    if "PAC2002" in fmt or "MF_05" in fmt:
        return "5.2", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if "MF_61" in fmt or "MF61" in fmt:
        return "6.1", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if "MF_62" in fmt or "MF62" in fmt:
        return "6.2", f"PROPERTY_FILE_FORMAT = '{fmt}'"
    if pf.has("LATERAL_COEFFICIENTS", "PKY4"):
        return "6.1", "no FITTYP; PKY4 present, so the MF 6.1 equations were assumed"
    return "5.2", "no FITTYP; the MF 5.2 / PAC2002 equations were assumed"


def file_pressures(pf: PropertyFile, notes: list[str]) -> tuple[float | None, float | None]:
    """Inflation and nominal pressure [Pa] of the file (MF 6.x or PAC2002 keys).

    When only one of them is given it stands for both (dpi = 0), with a note.
    """
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
    if p_i is None and p_nom is not None:
        p_i = p_nom
        notes.append("no inflation pressure (INFLPRES / IP) in the file: the nominal "
                     "pressure is used (dpi = 0); pass pressure= to evaluate at another")
    return p_i, p_nom


def file_limits(pf: PropertyFile) -> dict[str, tuple[float, float]]:
    """The file's validity ranges in SI; a range with MIN above MAX is refused."""
    limits = {}
    for name, sec, lo, hi, kind in RANGES:
        if not (pf.has(sec, lo) and pf.has(sec, hi)):
            continue
        low, high = ((pf.si(sec, lo), pf.si(sec, hi)) if kind
                     else (pf.number(sec, lo), pf.number(sec, hi)))
        if not low <= high or (kind and low < 0):
            raise InputError(
                f"[{sec}] {lo} .. {hi} = {pf.text(sec, lo)} .. {pf.text(sec, hi)} is "
                "not a range" + (" of positive values" if kind else "")
                + " (MIN must not be above MAX)", file=pf.path, row=pf.lines.get((sec, hi)))
        limits[name] = (low, high)
    return limits


def file_coefficients(pf: PropertyFile) -> dict[str, float]:
    """The numeric entries of the coefficient sections the evaluator reads; the required
    ones are checked with the values
    (:func:`~frictionlaws.tyre.mf.coefficients.checked_coefficients`)."""
    return pf.coefficients(*COEFFICIENT_SECTIONS)


def file_structure(pf: PropertyFile) -> dict[str, float]:
    """The numeric entries of :data:`STRUCTURE_SECTIONS` by upper-case name, in SI."""
    out: dict[str, float] = {}
    for sec in STRUCTURE_SECTIONS:
        for key, value in pf.sections.get(sec, {}).items():
            if not isinstance(value, str):
                out[key] = pf.si(sec, key)
    return out


def model_inputs(pf: PropertyFile, version: str | None = None) -> dict[str, Any]:
    """Everything a Magic Formula takes from the file, in SI, checked (one trip).

    Parameters
    ----------
    pf : PropertyFile
        The property file.
    version : {"5.2", "6.1", "6.2"}, optional
        Override the version the file states (FITTYP).

    Returns
    -------
    dict
        The keyword arguments of :class:`~frictionlaws.tyre.mf.parameters.MFParameters`:
        ``coefficients``, ``fnomin`` [N], ``version``, ``pressure`` and
        ``nominal_pressure`` [Pa] (or None), ``limits`` (SI), ``name``, ``source``,
        ``notes`` (how the version and the pressures were decided, unknown keys, values
        outside the fit ranges) and ``structure`` (SI).

    Raises
    ------
    InputError
        For a missing FNOMIN, an unknown version, an angle unit other than radians, a
        value outside its declared bounds, or a range whose MIN is above its MAX.
    """
    pf.check_angle_unit()
    notes = pf.check_coefficients()
    if version is None:
        version, how = version_of(pf)
        notes.append(f"Magic Formula {version} equations ({how})")
    if not pf.has("VERTICAL", "FNOMIN"):
        raise InputError("[VERTICAL] FNOMIN (nominal load) is missing", file=pf.path)
    coefficients = file_coefficients(pf)
    p_i, p_nom = file_pressures(pf, notes)
    return {"coefficients": coefficients, "fnomin": pf.si("VERTICAL", "FNOMIN"),
            "version": version, "pressure": p_i, "nominal_pressure": p_nom,
            "limits": file_limits(pf), "name": str(pf.metadata.get("Name")
                                                   or Path(pf.path).stem),
            "source": pf.path, "notes": notes, "structure": file_structure(pf)}
