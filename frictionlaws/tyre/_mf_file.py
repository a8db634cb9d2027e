"""Reading a Magic Formula property file: version, pressures, validity ranges, examples.

Helpers of :class:`~frictionlaws.tyre.magic_formula.MagicFormula`: what version of
the equations a file asks for, its inflation and nominal pressures, its validity
ranges in SI, and where the packaged example files are.
"""

from __future__ import annotations

import math
from pathlib import Path

from ..base.errors import InputError
from ..base.numbers import is_number, parse_number
from .mf_coefficients import COEFFICIENT_SECTIONS, STRUCTURE_SECTIONS
from .tir import PropertyFile

__all__ = ["version_of", "file_pressures", "file_limits", "peak_cause", "EXAMPLES",
           "packaged_example", "STRUCTURE_SECTIONS", "structure", "file_coefficients"]


def version_of(pf: PropertyFile) -> tuple[str, str]:
    """(version, how it was decided) from FITTYP / PROPERTY_FILE_FORMAT / the coefficients."""
    fittyp = pf.get("MODEL", "FITTYP")
    if isinstance(fittyp, str) and is_number(fittyp):
        fittyp = parse_number(fittyp)  # quoted ('61' or "61"): the same version number
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


def peak_cause(limits: dict[str, tuple[float, float]], fz: float, gamma: float,
               pressure: float | None) -> str:
    """The likely cause of a peak friction that is none: the input outside the file's
    validity range (:func:`file_limits`: load, then camber, then pressure), else the
    coefficients."""
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


#: Validity ranges of a property file: name, section, MIN key, MAX key, and whether the
#: values carry a unit (load, pressure) or are plain numbers (slips and angles, rad).
_RANGES = (("fz", "VERTICAL_FORCE_RANGE", "FZMIN", "FZMAX", True),
           ("kappa", "LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", False),
           ("alpha", "SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", False),
           ("gamma", "INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", False),
           ("pressure", "INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX", True))


def file_limits(pf: PropertyFile) -> dict[str, tuple[float, float]]:
    """The file's validity ranges in SI; a range with MIN above MAX is refused."""
    limits = {}
    for name, sec, lo, hi, kind in _RANGES:
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



#: Packaged example property files (``datasets/mf-examples``), by short name.
EXAMPLES = {
    "magicformula52": "MagicFormula52_Parameters.json",
    "magicformula61": "MagicFormula61_Parameters.json",
    "magicformula62": "MagicFormula62_Parameters.json",
}


def packaged_example(name: str) -> Path | None:
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


def file_coefficients(pf: PropertyFile) -> dict[str, float]:
    """The numeric entries of the coefficient sections the evaluator reads (not turn slip);
    the required ones are checked with the values
    (:func:`~frictionlaws.tyre.mf_coefficients.checked_coefficients`)."""
    return pf.coefficients(*(s for s in COEFFICIENT_SECTIONS if s != "TURNSLIP_COEFFICIENTS"))


def structure(pf: PropertyFile) -> dict[str, float]:
    """The numeric entries of :data:`STRUCTURE_SECTIONS` by upper-case name, in SI."""
    out: dict[str, float] = {}
    for sec in STRUCTURE_SECTIONS:
        for key, value in pf.sections.get(sec, {}).items():
            if not isinstance(value, str):
                out[key] = pf.si(sec, key)
    return out
