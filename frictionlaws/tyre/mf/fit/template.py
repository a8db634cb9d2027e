"""The template of a Magic Formula fit: the property file that gives what the data do not.

The template gives FNOMIN, the nominal pressure, the other sections and the value of every
coefficient the data cannot determine (:func:`template_file`: the packaged example of the
version by default); :func:`model_from_template` builds the model the stages fit from it,
after the data are checked against it; :func:`build_file` writes the fitted values, FITTYP,
the pressures and the data's ranges into a copy of it.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from ....base.errors import InputError
from ...data.table import TyreData
from ..coefficients import section_of
from ..property_file import FITTYP_VERSIONS, PropertyFile, file_structure, version_of
from ..tir import EXAMPLES, open_property_file, read_packaged
from .checks import check_plausible
from .peak import FittingModel

__all__ = ["template_file", "build_file", "model_from_template", "FAR_FROM_DATA",
           "near_data", "nominal_pressure"]


def template_file(template: str | Path | PropertyFile | None, version: str) -> PropertyFile:
    """The template: a property file, a path or packaged example name, or (None) the
    packaged example of ``version``; refused when it cannot serve (:func:`_check_template`)."""
    if template is None:
        packaged = read_packaged(EXAMPLES["magicformula" + version.replace(".", "")])
        if packaged is None:
            raise InputError("the packaged template property files are missing")
        pf = packaged
    else:
        pf = open_property_file(template)
    _check_template(pf, version)
    return pf


def _check_template(pf: PropertyFile, version: str) -> None:
    """Refuse a template of the other family (MF 5.2 against MF 6.x: it lacks the
    coefficients and sections of the version written, which would be written without
    them or as zeros claimed to be the template's values) or with an unloaded radius
    that is not positive (the moments would be zero and M_z data look wrong)."""
    have, how = version_of(pf)
    if (have == "5.2") != (version == "5.2"):
        raise InputError(
            f"the template is Magic Formula {have} ({how}) and the file to write is MF "
            f"{version}: the template lacks coefficients and sections of MF {version}, so "
            f"they would have no template value; give an MF {version} template, or none "
            "for the packaged example", file=pf.path)
    if pf.has("DIMENSION", "UNLOADED_RADIUS") and not pf.si("DIMENSION",
                                                            "UNLOADED_RADIUS") > 0:
        raise InputError("the template's [DIMENSION] UNLOADED_RADIUS must be positive",
                         file=pf.path, row=pf.lines.get(("DIMENSION", "UNLOADED_RADIUS")))


#: A template's FNOMIN or nominal pressure this factor or more outside the measured
#: range is replaced by the median measured value (:func:`near_data`).
FAR_FROM_DATA = 2.0


def near_data(name: str, value: float, measured: np.ndarray, unit: str,
               notes: list[str]) -> float:
    """``value``, or the median of ``measured`` (3 significant digits) when ``value`` lies
    more than :data:`FAR_FROM_DATA` times outside the measured range: a reference that far
    from the data (a car template for a truck tyre) makes every load or pressure
    polynomial extrapolate and the stage starts fail."""
    lo, hi = float(np.min(measured)), float(np.max(measured))
    if lo / FAR_FROM_DATA <= value <= FAR_FROM_DATA * hi:
        return value
    new = float(f"{float(np.median(measured)):.3g}")
    notes.append(f"the template's {name} {value:g} {unit} lies far outside the measured "
                 f"{lo:g}..{hi:g} {unit}: {name} is set to the median measured {new:g} {unit} "
                 "(the coefficients refer to it)")
    return new


def nominal_pressure(pf: PropertyFile, data: TyreData, notes: list[str]) -> float | None:
    measured = data.pressure[np.isfinite(data.pressure)]
    for sec, key in (("OPERATING_CONDITIONS", "NOMPRES"), ("TIRE_CONDITIONS", "IP_NOM")):
        if pf.has(sec, key):
            p = pf.si(sec, key)
            return near_data("NOMPRES", p, measured, "Pa", notes) if measured.size else p
    if measured.size:
        p = float(np.median(measured))
        notes.append(f"no nominal pressure in the template: the median measured pressure "
                     f"{p:g} Pa is taken as NOMPRES")
        return p
    return None



def build_file(t: PropertyFile, fittyp: int, values: dict[str, float],
                p_nom: float | None, data: TyreData, notes: list[str],
                fnomin: float | None = None) -> PropertyFile:
    """The template with FITTYP, the fitted coefficients, the pressure and the data ranges.

    A nominal pressure outside the measured ones stays NOMPRES (the coefficients refer to
    it); INFLPRES, where the file is evaluated by default, is the nearest measured one."""
    pf = PropertyFile({s: dict(e) for s, e in t.sections.items()}, dict(t.tables),
                      dict(t.metadata), path="<fitted>", format="tir",
                      comments=dict(t.comments))
    pf.sections.setdefault("MODEL", {})["FITTYP"] = float(fittyp)
    for k, v in values.items():
        pf.sections.setdefault(section_of(k), {})[k] = v
    f_force, f_p = pf.si_factor("force"), pf.si_factor("pressure")
    if fnomin is not None:
        pf.sections.setdefault("VERTICAL", {})["FNOMIN"] = fnomin / f_force
    if p_nom is not None and FITTYP_VERSIONS[fittyp] != "5.2":
        oc = pf.sections.setdefault("OPERATING_CONDITIONS", {})
        oc["NOMPRES"] = oc["INFLPRES"] = p_nom / f_p
    ranges = [("VERTICAL_FORCE_RANGE", "FZMIN", "FZMAX", data.fz / f_force),
              ("LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", data.kappa),
              ("SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", data.alpha),
              ("INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", data.gamma)]
    measured = data.pressure[np.isfinite(data.pressure)]
    if measured.size and FITTYP_VERSIONS[fittyp] != "5.2":
        ranges.append(("INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX", measured / f_p))
    elif p_nom is not None and FITTYP_VERSIONS[fittyp] != "5.2":
        # no pressure measured: the data are taken at NOMPRES, the only pressure they cover
        ranges.append(("INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX",
                       np.array([p_nom / f_p])))
        notes.append(f"no pressure measured: the data are taken at NOMPRES {p_nom:g} Pa, "
                     "so PRESMIN = PRESMAX = NOMPRES and another pressure is warned of as "
                     "extrapolation (the pressure terms are the template's)")
    for sec, lo, hi, observed in ranges:
        entry = pf.sections.setdefault(sec, {})
        entry[lo], entry[hi] = float(np.min(observed)), float(np.max(observed))
    if p_nom is not None and measured.size and FITTYP_VERSIONS[fittyp] != "5.2":
        inside = float(np.clip(p_nom, measured.min(), measured.max()))
        if inside != p_nom:
            pf.sections["OPERATING_CONDITIONS"]["INFLPRES"] = inside / f_p
            notes.append(f"the nominal pressure {p_nom:g} Pa lies outside the measured "
                         f"{measured.min():g}..{measured.max():g} Pa: INFLPRES is set to "
                         f"{inside:g} Pa, NOMPRES stays")
    return pf


def model_from_template(tpl: PropertyFile, data: TyreData, version: str, notes: list[str]
                         ) -> tuple[dict[str, float], float | None, float | None, FittingModel]:
    """The template's coefficients, the nominal pressure (of the file; of the fit: None for
    MF 5.2) and the model the stages fit,
    after the data's plausibility against the template (FNOMIN, pressure, radius)."""
    tpl_coeffs = tpl.coefficients("SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS",
                                  "LATERAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS")
    fnomin = tpl.si("VERTICAL", "FNOMIN")
    first = len(notes)
    # MF 5.2 is written without a nominal pressure (it has no pressure terms here)
    p_nom = nominal_pressure(tpl, data, notes) if version != "5.2" else None
    radius = (tpl.si("DIMENSION", "UNLOADED_RADIUS") if tpl.has("DIMENSION", "UNLOADED_RADIUS")
              else None)
    p_tpl = (tpl.si("OPERATING_CONDITIONS", "NOMPRES")
             if tpl.has("OPERATING_CONDITIONS", "NOMPRES") else None)
    check_plausible(data, fnomin, p_tpl, radius)
    kept = near_data("FNOMIN", fnomin, data.fz, "N", notes)
    notes.insert(first, f"template {tpl.path}: "
                 + ("FNOMIN, " if kept == fnomin else "")
                 + "the other sections and the undetermined coefficients come from it")
    fnomin = kept
    p_fit = p_nom
    mf = FittingModel(dict(tpl_coeffs), fnomin=fnomin, version=version, source=tpl.path,
                      pressure=p_fit, nominal_pressure=p_fit, structure=file_structure(tpl))
    if version == "5.2" and np.isfinite(data.pressure).any():
        notes.append("MF 5.2 has no pressure coefficients here: the pressure column is "
                     "not used")
    return dict(tpl_coeffs), p_nom, p_fit, mf
