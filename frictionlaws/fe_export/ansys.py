"""Ansys Mechanical APDL export: ``TB,FRIC`` with ``TBFIELD`` and ``TBDATA``.

Nested form, outermost field first: ``TBFIELD,TEMP,T`` (when the law uses
temperature), ``TBFIELD,NPRES,p`` (normal pressure; the field name is NPRES,
not PRES), ``TBFIELD,SLRV,v`` (sliding velocity), then ``TBDATA,1,mu``.
Values ascend; Ansys interpolates linearly between them.  Older manuals allow
at most two fields combined: the file says so when it uses three.
"""

from __future__ import annotations

import itertools

from ..base.errors import InputError
from .job import Job, Written, commented, model_axes, tabulated

__all__ = ["write_ansys", "OUTSIDE_ANSYS"]

OUTSIDE_ANSYS = ("Ansys interpolates linearly between the field values and uses the end "
                 "values outside them (as commonly documented; not verified here)")
_FIELD = {"T": "TEMP", "p": "NPRES", "v": "SLRV"}
_ORDER = ("T", "p", "v")  # outermost first


def _num(x: float) -> str:
    return f"{float(x):.12g}"


def write_ansys(job: Job) -> Written:
    """``TB,FRIC,MAT,,,ISO`` with nested ``TBFIELD`` blocks and ``TBDATA,1,mu``."""
    law = job.law
    bad = [v for v in job.variables if v not in _FIELD]
    if bad:
        raise InputError(
            f"ansys: law '{law.id}' depends on {', '.join(bad)}; TB,FRIC fields are "
            "NPRES (pressure), SLRV (sliding velocity) and TEMP only")
    names = [v for v in _ORDER if v in job.variables]
    grid, err, how = job.make_grid(names, "ansys")
    mu = tabulated(job, grid)
    axes = model_axes(job, grid)
    mat = job.options["ansys_mat"]
    summary = [*job.box_lines(grid), *job.error_lines(err, how)]
    body = [*summary,
            "fields: " + (", ".join(f"{_FIELD[n]} = {n} [{job.units.label(n)}]"
                                    for n in grid.names) or "none (constant mu)")
            + "; TBDATA constant 1 is mu",
            f"material id {mat} (API option ansys_mat)"]
    if len(grid.names) == 3:
        body.append("three fields combined: older Ansys releases allow at most two; check "
                    "your release")
    head = job.header("Ansys TB,FRIC with TBFIELD", body, OUTSIDE_ANSYS)
    lines = commented(head, "! ")
    lines.append(f"TB,FRIC,{mat},,,ISO")
    prev: tuple[int, ...] | None = None
    for idx in itertools.product(*[range(len(a)) for a in axes]):
        for k, (n, a) in enumerate(zip(grid.names, axes, strict=True)):
            if prev is None or idx[:k + 1] != prev[:k + 1]:
                lines.append(f"TBFIELD,{_FIELD[n]},{_num(a[idx[k]])}")
        lines.append(f"TBDATA,1,{_num(mu[idx])}")
        prev = idx
    return Written("\n".join(lines) + "\n", rows=grid.rows, error=err, grid=grid,
                   summary=summary, details={"material": mat})
