"""The Magic Formula coefficient tables (``generated/mf-coefficients.rst``), from the declarations.

One table per property-file section, one row per declared entry of
:data:`frictionlaws.tyre.mf.declarations.DECLARED`: name, versions, unit, default, the
bounds a file must respect, the range fit-mf searches and the meaning.  Called by
:mod:`fl_docgen` at every build; plain Python so the tests can call it without Sphinx.
"""

from __future__ import annotations

import math
from pathlib import Path

__all__ = ["mf_coefficients_page", "write_mf_coefficients"]

_TITLES = {
    "SCALING_COEFFICIENTS": "Scaling factors",
    "LONGITUDINAL_COEFFICIENTS": "Longitudinal force",
    "LATERAL_COEFFICIENTS": "Lateral force",
    "ALIGNING_COEFFICIENTS": "Aligning moment",
    "OVERTURNING_COEFFICIENTS": "Overturning moment",
    "ROLLING_COEFFICIENTS": "Rolling resistance moment",
    "TURNSLIP_COEFFICIENTS": "Turn slip (known, not evaluated)",
}


def _cell(text: str) -> str:
    """Free text for a table cell, reST inline markup escaped."""
    from fl_docgen import escape

    return escape(text) or "–"


def _range(lo: float, hi: float, open_low: bool = False) -> str:
    if math.isinf(lo) and math.isinf(hi):
        return "–"
    if math.isinf(hi):
        return f"{'>' if open_low else '≥'} {lo:g}"
    if math.isinf(lo):
        return f"≤ {hi:g}"
    return f"{lo:.4g} .. {hi:.4g}" + (" (not the low end)" if open_low else "")


def _users() -> dict[str, list[str]]:
    """Coefficient -> the outputs that read it (any version), from evaluating each output of
    the packaged example of every version."""
    from frictionlaws.tyre.mf.model import MagicFormula
    from frictionlaws.tyre.mf.outputs import OUTPUTS, coefficient_users

    found: dict[str, set[str]] = {}
    for example in ("MagicFormula52", "MagicFormula61", "MagicFormula62"):
        for name, outputs in coefficient_users(MagicFormula.from_file(example)).items():
            found.setdefault(name, set()).update(outputs)
    return {name: [o for o in OUTPUTS if o in outs] for name, outs in found.items()}


def _row(c: object, users: dict[str, list[str]] | None = None) -> list[str]:
    from frictionlaws.tyre.mf.declarations import Coefficient

    assert isinstance(c, Coefficient)
    if c.required:
        dflt = "required"
    elif c.alias_of:
        dflt = f"read as {c.alias_of}"
    elif c.default is None:
        dflt = "none"
    else:
        dflt = f"{c.default:g}"
    bounds = _range(*c.limits(), c.open_low)
    searched = _range(*c.bounds, c.open_low)  # fit-mf: without the magnitude limit
    fit = (f"{c.fit[0]:g} .. {c.fit[1]:g}" if c.fit
           else ("bounds" if searched == bounds else searched))
    meaning = c.meaning if c.evaluated else f"{c.meaning} [not evaluated]"
    stage = c.stage or "–"
    used = ", ".join((users or {}).get(c.name, [])) or "–"
    return [f"``{c.name}``", ", ".join(c.versions), _cell(c.unit.replace("**2", "²") or "1"),
            dflt, bounds, fit if c.section.endswith("COEFFICIENTS") else "–", _cell(meaning),
            stage, _cell(used)]


def _table(title: str, entries: list, users: dict[str, list[str]]) -> list[str]:
    out = [title, "~" * len(title), "", ".. list-table::", "   :header-rows: 1",
           "   :widths: 10 10 7 8 12 10 25 6 12", "",
           "   * - Name", "     - MF", "     - Unit", "     - Default", "     - Bounds",
           "     - Fit range", "     - Meaning", "     - Fit stage", "     - Used by"]
    for c in entries:
        cells = _row(c, users)
        out.append(f"   * - {cells[0]}")
        out.extend(f"     - {x}" for x in cells[1:])
    return out + [""]


def mf_coefficients_page() -> str:
    """The reST page: an introduction and one table per section."""
    from frictionlaws.tyre.mf.coefficients import rows
    from frictionlaws.tyre.mf.declarations import (
        COEFFICIENT_SECTIONS,
        SECTIONS,
        STRUCTURE_SECTIONS,
    )

    every = rows()
    lines = [":orphan:", "", ".. _mf-coefficients:", "",
             "Magic Formula coefficients", "==========================", "",
             "Every coefficient, scaling factor and file-level entry of a Magic Formula "
             "property file (MF 5.2 / PAC2002, 6.1, 6.2) that frictionlaws knows, generated "
             "from :mod:`frictionlaws.tyre.mf.declarations`. **Unit**: SI, as a ``.tir`` with "
             "SI ``[UNITS]`` states it (coefficients of the camber angle are per radian). "
             "**Default**: the value the evaluator takes when the file lacks the entry "
             "(*required*: the file is refused without it; *none*: the outputs that need it "
             "are refused). **Bounds**: the physically possible values (every coefficient and "
             "scaling factor within ±1e6; radius, width, nominal load, pressures, vertical "
             "stiffness and reference speed within what real tyres have, from a bicycle's to "
             "a mining truck's); a file outside them is refused with its section, name and "
             "line. **Fit range**: what "
             "``frictionlaws tyre fit-mf`` searches (*bounds*: the bounds); a file value "
             "outside it is noted when read. **Fit stage**: the stage of "
             "``tyre fit-mf`` that fits it (pure-slip ``Fx0``/``Fy0``, combined-slip "
             "``Fx``/``Fy``, ``Mz0``, ``Mz``). **Used by**: the steady-state outputs that read "
             "it, found by evaluating each output of the packaged examples. "
             "``frictionlaws tyre mf FILE --coefficients`` lists a file's values beside the "
             "same declarations.", ""]
    users = _users()
    for sec in COEFFICIENT_SECTIONS:
        lines += _table(_TITLES[sec], [c for c in every if c.section == sec], users)
    rest = [s for s in SECTIONS if s not in COEFFICIENT_SECTIONS]
    lines += _table("File-level entries", [c for c in every if c.section in rest], users)
    lines.append("The structure entries are read by name from any of the sections "
                 + ", ".join(f"``{s}``" for s in STRUCTURE_SECTIONS) + "; the ranges and "
                 "pressures from their own sections. Entries with a unit are converted to SI "
                 "with the file's ``[UNITS]``.")
    return "\n".join(lines) + "\n"


def write_mf_coefficients(path: Path) -> int:
    """Write the page to ``path`` (only when it changed); return the number of entries."""
    from frictionlaws.tyre.mf.declarations import DECLARED

    text = mf_coefficients_page()
    path.parent.mkdir(parents=True, exist_ok=True)
    if not (path.exists() and path.read_text(encoding="utf-8") == text):
        path.write_text(text, encoding="utf-8")
    return len(DECLARED)
