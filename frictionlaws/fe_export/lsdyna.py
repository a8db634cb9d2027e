"""LS-DYNA keyword export: the FS/FD/DC card, or a friction table.

``*CONTACT_...`` card 2 is ``FS FD DC VC VDC PENCHK BT DT`` (eight
10-character fields) and its law ``mu = FD + (FS - FD) exp(-DC |v_rel|)`` is
exactly ``exponential-decay`` with ``delta = 1`` (``DC = 1/v_c``).  For any
other law, ``FS = 2`` makes ``FD`` the id of a ``*DEFINE_TABLE``: one VALUE
per pressure level, each followed by a ``*DEFINE_CURVE`` of mu against the
sliding velocity.  That the table values are pressures is the usual reading of
the manual, not verified here; the file says so.

Each curve and the table get flat guard points (at 0 when the range starts
above 0, and just beyond the upper end), so mu is held at its end values
outside the box whether LS-DYNA clamps or extrapolates the last segment.
"""

from __future__ import annotations

import numpy as np

from ..base.errors import InputError
from .exact import ExpDecay, exp_decay_form
from .grid import Grid
from .job import Job, Written, commented, tabulated

__all__ = ["write_lsdyna", "field10", "field20"]


def _field(x: float, width: int) -> str:
    """The most precise representation of ``x`` that fits ``width`` columns."""
    x = float(x)
    if x == 0:
        return "0.0".rjust(width)
    for digits in range(min(16, width - 1), 0, -1):
        s = f"{x:.{digits}g}"
        if "e" in s:  # 3.0e-08 -> 3.0e-8: one more digit fits
            mant, exp = s.split("e")
            s = f"{mant}e{int(exp)}"
        elif "." not in s:
            s += ".0"
        if len(s) <= width:
            return s.rjust(width)
    raise InputError(f"cannot write {x!r} in {width} columns")


def field10(x: float) -> str:
    """A number in a 10-column LS-DYNA field."""
    return _field(x, 10)


def field20(x: float) -> str:
    """A number in a 20-column LS-DYNA field."""
    return _field(x, 20)


def _int10(i: int) -> str:
    return str(int(i)).rjust(10)


def _contact_cards(job: Job, fs: float, fd: float, dc: float) -> list[str]:
    opt = job.options  # checked, with the defaults of fe_export.formats
    ssid, msid = opt["lsdyna_ssid"], opt["lsdyna_msid"]
    sstyp, mstyp = opt["lsdyna_sstyp"], opt["lsdyna_mstyp"]
    return [
        "*CONTACT_AUTOMATIC_SURFACE_TO_SURFACE",
        "$#    SSID      MSID     SSTYP     MSTYP    SBOXID    MBOXID       SPR       MPR",
        "".join(_int10(i) for i in (ssid, msid, sstyp, mstyp, 0, 0, 0, 0)),
        "$#      FS        FD        DC        VC       VDC    PENCHK        BT        DT",
        "".join([field10(fs), field10(fd), field10(dc), field10(0.0), field10(0.0),
                 _int10(0), field10(0.0), field10(1e20)]),
        "$#     SFS       SFM       SST       MST      SFST      SFMT       FSF       VSF",
        "".join(field10(x) for x in (1.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0)),
    ]


def _contact_note(job: Job) -> str:
    opt = job.options
    return (f"contact card 1 uses SSID={opt['lsdyna_ssid']}, MSID={opt['lsdyna_msid']} "
            f"(SSTYP/MSTYP={opt['lsdyna_sstyp']}/{opt['lsdyna_mstyp']}): set them to your "
            "surfaces "
            "(API options lsdyna_ssid, lsdyna_msid, lsdyna_sstyp, lsdyna_mstyp); only card 2 "
            "carries the friction law")


def _guarded(x: np.ndarray) -> np.ndarray:
    """Abscissas with flat guard points: 0 below a positive start, and just past the end."""
    lo, hi = float(x[0]), float(x[-1])
    span = hi - lo if hi > lo else max(abs(hi), 1.0)
    out = list(x)
    if lo > 0:
        out.insert(0, 0.0)
    out.append(hi + 1e-3 * span)
    return np.asarray(out, dtype=float)


def _guard_values(mu: np.ndarray, x: np.ndarray, axis: int) -> np.ndarray:
    """Extend ``mu`` along ``axis`` with the end values for the guard points."""
    parts = []
    if float(x[0]) > 0:
        parts.append(np.take(mu, [0], axis=axis))
    parts.append(mu)
    parts.append(np.take(mu, [-1], axis=axis))
    return np.concatenate(parts, axis=axis)


def write_lsdyna(job: Job) -> Written:
    """FS/FD/DC when exact, else ``FS = 2`` with ``*DEFINE_TABLE`` / ``*DEFINE_CURVE``."""
    law = job.law
    bad = [v for v in job.variables if v not in ("p", "v")]
    form, _ = exp_decay_form(law, job.values)
    if form is not None:
        return _write_exact(job, form)
    if bad:
        raise InputError(
            f"lsdyna: law '{law.id}' depends on {', '.join(bad)}; LS-DYNA friction tables "
            "(FS = 2) give mu against pressure and sliding velocity only. Use an Abaqus "
            "format, or a law of p and v")
    return _write_table(job)


def _write_exact(job: Job, form: ExpDecay) -> Written:
    """Contact card 2 with FS, FD, DC: the exponential decay written exactly."""
    scale, _ = job.units.affine("v")
    dc = form.d_c * scale
    job.check_levels({"FS = mu_s": form.mu_s, "FD = mu_k": form.mu_k})
    cards = _contact_cards(job, form.mu_s, form.mu_k, dc)
    written = [float(c) for c in (cards[4][0:10], cards[4][10:20], cards[4][20:30])]
    vv = np.linspace(0.0, 20.0 / dc, 2001) if dc > 0 else np.array([0.0, 1.0])
    ref = written[1] + (written[0] - written[1]) * np.exp(-written[2] * vv)
    exact_mu = form.mu_k + (form.mu_s - form.mu_k) * np.exp(-dc * vv)
    dev = float(np.max(np.abs(ref - exact_mu)))
    if dev > 1e-6:
        job.warnings.append(
            f"the 10-column fields of card 2 round FS, FD, DC enough to change mu by up to "
            f"{dev:.2g}: check the values, or export a table (the law itself is exact)")
    body = [
        *job.box_lines(),
        "exact: mu = FD + (FS - FD) exp(-DC |v_rel|) is the law itself (checked "
        "numerically)",
        f"FS = {form.mu_s!r}, FD = {form.mu_k!r}, DC = {dc!r} "
        f"[1/({job.units.label('v')})]; written in 10-column fields, which changes mu "
        f"by at most {dev:.2g}",
        _contact_note(job),
    ]
    head = job.header("LS-DYNA contact card 2 (FS, FD, DC)", body,
                      "the same formula holds at every sliding velocity (no table)")
    lines = ["*KEYWORD", *commented(head, "$ "), *cards, "*END"]
    return Written("\n".join(lines) + "\n", exact=True, summary=body[-3:-1],
                   details={"FS": form.mu_s, "FD": form.mu_k, "DC": dc,
                            "rounding": dev})


def _table_values(job: Job, grid: Grid) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Pressures, velocities (model units, with guard points) and mu[p, v] of the table."""
    mu = tabulated(job, grid)
    if "p" not in grid.names:
        mu = mu[None, ...] if mu.ndim else np.full((1, 1), float(mu))
    if "v" not in grid.names:
        mu = mu[..., None] if mu.ndim == 1 else mu.reshape(1, 1)
    p_si = grid.axis("p") if "p" in grid.names else np.array([0.0])
    v_si = grid.axis("v") if "v" in grid.names else np.array([0.0])
    p_m = np.asarray(job.units.to_model("p", p_si), float)
    v_m = np.asarray(job.units.to_model("v", v_si), float)
    if len(v_m) == 1 and v_m[0] == 0.0:
        v_m = np.array([0.0, 1.0])
        mu = np.repeat(mu, 2, axis=1)
    mu = _guard_values(mu, p_m, 0)
    mu = _guard_values(mu, v_m, 1)
    return _guarded(p_m), _guarded(v_m), mu


def _write_table(job: Job) -> Written:
    """``FS = 2``: a *DEFINE_TABLE of pressures, each with a *DEFINE_CURVE of mu(v)."""
    names = [v for v in ("p", "v") if v in job.variables]
    grid, err, how = job.make_grid(names, "lsdyna")
    p_g, v_g, mu = _table_values(job, grid)
    tbid = job.options["lsdyna_table_id"]
    summary = [*job.box_lines(grid), *job.error_lines(err, how)]
    body = [
        *summary,
        f"*DEFINE_TABLE {tbid}: the VALUEs are contact pressures "
        f"[{job.units.label('p')}] (the usual reading of FS = 2: verify with your "
        "LS-DYNA release); each VALUE is followed by its *DEFINE_CURVE of mu (ordinate) "
        f"against the relative sliding velocity [{job.units.label('v')}] (abscissa)",
        "FS = 2 (friction from the table FD) works with surface-to-surface contact types",
        "guard points with the end values were added (at 0 below a positive start and just "
        "past each upper end), so mu is held outside the box",
        "LS-DYNA may resample curves to LCINT equally spaced points (*CONTROL_SOLUTION, "
        f"default 100): set LCINT >= {len(v_g)} so the curves keep their resolution",
        _contact_note(job),
    ]
    head = job.header("LS-DYNA friction table (FS = 2, *DEFINE_TABLE)", body,
                      "mu is held at the end values (flat guard points)")
    lines = ["*KEYWORD", *commented(head, "$ "), *_contact_cards(job, 2.0, float(tbid), 0.0)]
    lines += _table_cards(job, tbid, p_g, v_g, mu)
    lines.append("*END")
    return Written("\n".join(lines) + "\n", rows=grid.rows, error=err, grid=grid,
                   summary=summary, details={"table_id": tbid})


def _table_cards(job: Job, tbid: int, p_g: np.ndarray, v_g: np.ndarray,
                 mu: np.ndarray) -> list[str]:
    """The *DEFINE_TABLE card and one *DEFINE_CURVE per pressure."""
    lines = ["*DEFINE_TABLE", "$#    TBID       SFA      OFFA",
             _int10(tbid) + field10(1.0) + field10(0.0),
             "$#             VALUE  (contact pressure)"]
    lines += [field20(p) for p in p_g]
    for i, p in enumerate(p_g):
        lines += ["*DEFINE_CURVE",
                  f"$ mu against sliding velocity at pressure {p:.10g} {job.units.label('p')}",
                  "$#    LCID      SIDR       SFA       SFO      OFFA      OFFO    DATTYP",
                  "".join([_int10(tbid + 1 + i), _int10(0), field10(1.0), field10(1.0),
                           field10(0.0), field10(0.0), _int10(0)]),
                  "$#                A1                  O1"]
        lines += [field20(v) + field20(m) for v, m in zip(v_g, mu[i], strict=True)]
    return lines
