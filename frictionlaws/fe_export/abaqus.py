"""Abaqus exports: the ``*FRICTION`` table, ``EXPONENTIAL DECAY``, and the user subroutines.

Table (``abaqus``): data lines ``mu, slip rate, contact pressure,
temperature, field 1, ...`` (eight values per line, continuation lines after
that); slip rate varies fastest, then pressure, then temperature, then the
field variables; ascending within each block; every block carries the same
slip-rate values.  Columns the law does not use are left out from the right;
one that must stay because a later column is used holds a single value ``0``
(mu does not depend on it).  Variables Abaqus does not pass to ``*FRICTION``
(normal load ``F_N``, slip ratio ``s``) become field variables
(``DEPENDENCIES=n``), in the order the law lists them.

``abaqus-decay``: ``*FRICTION, EXPONENTIAL DECAY`` with ``mu_s, mu_k, d_c``,
exact only when the law is of that form (see :mod:`.exact`); otherwise an
:class:`~frictionlaws.base.errors.InputError` suggests fitting ``exponential-decay``
with ``delta = 1`` first.
"""

from __future__ import annotations

import itertools

import numpy as np

from ..base.errors import Argument, InputError
from .exact import exp_decay_form
from .fortran import FIELD_VARIABLES, fortran_source, input_deck, routine_name
from .job import Job, Written, commented, model_axes, tabulated

__all__ = ["write_abaqus", "write_abaqus_decay", "write_abaqus_subroutine", "table_columns",
           "OUTSIDE_ABAQUS"]

OUTSIDE_ABAQUS = ("Abaqus interpolates linearly between the table rows and holds the end "
                  "values outside the table (no extrapolation)")
_ORDER = ("v", "p", "T")
_COLUMN = {"v": "slip rate", "p": "contact pressure", "T": "temperature"}


def _num(x: float) -> str:
    return f"{float(x):.12g}"


def table_columns(variables: tuple[str, ...]) -> tuple[list[str], list[str]]:
    """(independent columns in Abaqus order, field variables) for a law's variables."""
    fields = [v for v in variables if v in FIELD_VARIABLES]
    if fields:
        n_indep = 3
    else:
        used = [i for i, v in enumerate(_ORDER) if v in variables]
        n_indep = max(used) + 1 if used else 0
    return list(_ORDER[:n_indep]) + fields, fields


def write_abaqus(job: Job) -> Written:
    """``*FRICTION`` with mu tabulated against slip rate, pressure, temperature, fields."""
    cols, fields = table_columns(job.variables)
    axes_vars = [c for c in cols if c in job.variables]
    grid, err, how = job.make_grid(axes_vars, "abaqus")
    mu = tabulated(job, grid)
    model = dict(zip(grid.names, model_axes(job, grid), strict=True))
    col_vals = [model.get(c, np.array([0.0])) for c in cols]
    summary = [*job.box_lines(grid), *job.error_lines(err, how)]
    body = list(summary)
    colspec = ["mu"] + [
        (f"{_COLUMN[c]} ({c} [{job.units.label(c)}])" if c in _COLUMN else
         f"field {fields.index(c) + 1} ({c} [{job.units.label(c)}])")
        + ("" if c in job.variables else ": single value 0, mu does not depend on it")
        for c in cols]
    body.append("data lines: " + ", ".join(colspec))
    if cols:
        body.append("order: slip rate varies fastest, then pressure, then temperature"
                    + (", then the field variables" if fields else "")
                    + "; ascending; the same slip-rate values in every block")
    for i, f in enumerate(fields):
        body.append(f"field variable {i + 1} must carry {f} in the model's unit "
                    f"[{job.units.label(f)}] (define it with *FIELD, *INITIAL CONDITIONS, "
                    "TYPE=FIELD or USDFLD)")
    body.append("place the *FRICTION block under the *SURFACE INTERACTION it belongs to")
    head = job.header("Abaqus *FRICTION table", body, OUTSIDE_ABAQUS)
    lines = commented(head, "** ")
    lines.append("*FRICTION" + (f", DEPENDENCIES={len(fields)}" if fields else ""))
    for idx_rev in itertools.product(*[range(len(v)) for v in reversed(col_vals)]):
        idx = idx_rev[::-1]
        grid_idx = tuple(idx[cols.index(n)] for n in grid.names)
        vals = [float(mu[grid_idx])] + [float(cv[i]) for cv, i in zip(col_vals, idx,
                                                                      strict=True)]
        for k in range(0, len(vals), 8):
            lines.append(", ".join(_num(x) for x in vals[k:k + 8]))
    if float(np.min(mu)) < 0:
        job.warnings.append("the law gives negative mu inside the box")
    return Written("\n".join(lines) + "\n", rows=grid.rows, error=err, grid=grid,
                   summary=summary, details={"columns": cols, "fields": fields})


def write_abaqus_decay(job: Job) -> Written:
    """``*FRICTION, EXPONENTIAL DECAY``: exact for laws of that form, else a refusal."""
    law = job.law
    form, why = exp_decay_form(law, job.values)
    if form is None:
        raise InputError(
            [f"abaqus-decay: {why}, so *FRICTION, EXPONENTIAL DECAY cannot represent it "
             "exactly. Fit 'exponential-decay' with delta held at 1 first (",
             Argument("fix", "delta=1"), ") and export that fit, or export a table with ",
             Argument("format", "abaqus")])
    scale, _ = job.units.affine("v")
    d_c = form.d_c * scale
    notes = []
    job.check_levels({"mu_s": form.mu_s, "mu_k": form.mu_k})
    if form.mu_s == form.mu_k:
        d_c = 1.0
        notes.append("mu is constant (mu_s = mu_k): d_c has no effect and is written as 1")
    body = [
        *job.box_lines(),
        "exact: mu = mu_k + (mu_s - mu_k) exp(-d_c * slip rate) is the law itself "
        "(checked numerically)",
        f"mu_s = {form.mu_s!r}, mu_k = {form.mu_k!r}, d_c = {d_c!r} "
        f"[1/({job.units.label('v')})] (= 1/v_c)",
        *notes,
        "place the *FRICTION block under the *SURFACE INTERACTION it belongs to",
    ]
    head = job.header("Abaqus *FRICTION, EXPONENTIAL DECAY", body,
                      "the same formula holds at every slip rate (no table, no box)")
    lines = commented(head, "** ")
    lines += ["*FRICTION, EXPONENTIAL DECAY", f"{form.mu_s!r}, {form.mu_k!r}, {d_c!r}"]
    return Written("\n".join(lines) + "\n", exact=True, summary=body[-3:],
                   details={"mu_s": form.mu_s, "mu_k": form.mu_k, "d_c": d_c})


def write_abaqus_subroutine(job: Job) -> Written:
    """A Fortran user subroutine of Abaqus that evaluates the law itself: ``FRIC_COEF``,
    ``VFRIC_COEF`` or ``VFRIC`` by the job's format, with the input-deck lines it needs."""
    fmt = job.fmt
    law = job.law
    fields = [v for v in law.variables if v in FIELD_VARIABLES]
    u = job.units
    names = {"abaqus-fric-coef": "FRIC_COEF (Abaqus/Standard)",
             "abaqus-vfric-coef": "VFRIC_COEF (Abaqus/Explicit, general contact)",
             "abaqus-vfric": "VFRIC (Abaqus/Explicit, contact pairs)"}
    body = [f"routine: {names[fmt]}, calling {routine_name(law)} (the law, SI, "
            "implicit none)"]
    if fmt == "abaqus-fric-coef":
        body += [
            "interface of Abaqus 2017 and later: fCoef(nBlock,2), fCoefDeriv(nBlock,20,2), "
            "slipData(nBlock,6) with the slip-rate magnitude in slipData(k,1); check it "
            "against your release (older releases pass fCoef(nBlock), "
            "fCoefDeriv(nBlock,3), slipRate(nBlock), as VFRIC_COEF does)",
            "out: fCoef(k,1) = mu; fCoefDeriv(k,1..3,1) = d mu/d slip rate "
            f"[1/({u.label('v')})], d mu/d pressure [1/{u.label('p')}], d mu/d "
            f"temperature [1/{u.label('T')}], slots 4..20 0; isotropic friction: "
            "fCoef(k,2) and fCoefDeriv(k,:,2) are left alone, as the manual asks",
        ]
    elif fmt == "abaqus-vfric-coef":
        body += [
            "out: fCoef(k) = mu; fCoefDeriv(k,1..3) = d mu/d slip rate "
            f"[1/({u.label('v')})], d mu/d pressure [1/{u.label('p')}], d mu/d "
            f"temperature [1/{u.label('T')}]",
        ]
    else:
        body += [
            "out: fTangential(1,k) = -min(mu * |fNormal|, fStickForce) (opposing slip), "
            "other directions 0",
            "in: slip rate = |dSlipFric(:,k)| / dTimPrev; p = |fNormal(k)| / "
            "areaSlv(jConSlvid(k)); T = tempSlv(k)"
            + ("; F_N = |fNormal(k)|, the nodal normal force, which is not a "
               "tribometer's normal load: check the law's meaning" if "F_N" in
               law.variables else ""),
        ]
    fld = [v for v in fields if not (fmt == "abaqus-vfric" and v == "F_N")]
    for i, v in enumerate(fld):
        src = (f"preDefSlv(k,{i + 1})" if fmt == "abaqus-vfric"
               else f"fieldAvg(k,{i + 1})")
        body.append(f"field variable {i + 1} = {v} ({law.meaning(v)}) "
                    f"[{u.label(v)}], read from {src}; the analysis stops if it is "
                    "missing")
    if "T" in law.variables:
        body.append("the law needs the temperature: the analysis stops if none is "
                    "defined")
    body += [
        "inputs are converted from the model's units to SI, the law is evaluated in SI "
        "with its floors, and the derivatives are scaled back to the model's units",
        "every local is declared (the include's implicit typing would make names "
        "starting i..n INTEGER); in Abaqus/Explicit the real arguments take the "
        "include's precision",
        "use: abaqus job=<job> user=<this file>",
    ]
    deck, deck_notes = input_deck(law, fmt)
    instructions = [
        "input deck: Abaqus calls this routine only when the surface interaction says "
        "so; without *FRICTION, USER=... it silently uses other friction. Keyword lines, "
        "in this order (<...>: yours):", *(f"  {line}" for line in deck),
        *(f"deck: {note}" for note in deck_notes)]
    body += instructions
    if job.specs:
        job.domain_warnings()
        body += job.box_lines()
    head = job.header(f"Abaqus user subroutine {names[fmt]}", body,
                      "the subroutine evaluates the law itself at any input (check the "
                      "law's domain)")
    text = fortran_source(law, job.values, fmt, job.units, head)
    return Written(text, exact=True, summary=body[:1] + instructions,
                   details={"routine": routine_name(law), "input_deck": deck,
                            "input_deck_notes": deck_notes})
