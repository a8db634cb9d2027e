"""OpenRadioss export: ``/FRICTION`` with Ifric 1 or Ifric 4.

Radioss has no mu(p, v) tables, only fixed laws (OpenRadioss source):

* Ifric 1: ``mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2``
* Ifric 4: ``mu = C1 + (Fric - C1) exp(-C2 v)``

A law of either form (``quadratic-pv``, ``thesis-poly2``, ``coulomb``,
``exponential-decay`` with ``delta = 1``...) is written exactly.  Any other law
of p and v is *approximated*: Ifric 1 is fitted by linear least squares over
the user's box, and the maximum and rms approximation errors (checked on a
dense sample of the box) are written in the header and reported.  Radioss
floors mu at 1e-30.
"""

from __future__ import annotations

import numpy as np

from ..base.errors import InputError
from .exact import exp_decay_form, quadratic_pv_form
from .grid import Grid, GridError, breakpoints, tabulate
from .job import Job, Written, commented

__all__ = ["write_radioss", "ifric1", "fit_ifric1"]

_KEYS = ("C1", "C2", "C3", "C4", "C5", "C6", "Fric")


def ifric1(c: dict[str, float], P: np.ndarray | float,
           V: np.ndarray | float) -> np.ndarray | float:
    """Radioss Ifric 1 in model units."""
    return (c["Fric"] + c["C1"] * P + c["C2"] * V + c["C3"] * P * V + c["C4"] * P**2
            + c["C5"] * V**2)


def _f20(x: float) -> str:
    s = f"{float(x):.13g}"
    if "e" not in s and "." not in s:
        s += ".0"
    return s.rjust(20)


def _i10(i: int) -> str:
    return str(int(i)).rjust(10)


def fit_ifric1(job: Job, names: list[str]) -> tuple[dict[str, float], GridError, Grid]:
    """Least-squares Ifric 1 over the box; error checked on a dense sample."""
    specs = job.require_box(names, "radioss")
    fit_axes = [breakpoints(s.lo, s.hi, 41, s.kind) if not s.single else np.array([s.lo])
                for s in specs]
    mesh = np.meshgrid(*fit_axes, indexing="ij")
    x = {n: m.ravel() for n, m in zip(names, mesh, strict=True)}
    mu = np.broadcast_to(np.asarray(job.func(**x), float), (mesh[0].size,))
    if not np.isfinite(mu).all():
        raise InputError(f"radioss: law '{job.law.id}' is not finite somewhere in the box")
    P = np.asarray(job.units.to_model("p", x["p"]), float) if "p" in x else np.zeros_like(mu)
    V = np.asarray(job.units.to_model("v", x["v"]), float) if "v" in x else np.zeros_like(mu)
    sp = float(np.max(np.abs(P))) or 1.0
    sv = float(np.max(np.abs(V))) or 1.0
    cols = {"Fric": np.ones_like(mu), "C1": P / sp, "C2": V / sv, "C3": P * V / (sp * sv),
            "C4": (P / sp) ** 2, "C5": (V / sv) ** 2}
    use = ["Fric"] + (["C1", "C4"] if "p" in x and np.ptp(P) > 0 else []) + (
        ["C2", "C5"] if "v" in x and np.ptp(V) > 0 else []) + (
        ["C3"] if "p" in x and "v" in x and np.ptp(P) > 0 and np.ptp(V) > 0 else [])
    A = np.column_stack([cols[k] for k in use])
    coef, *_ = np.linalg.lstsq(A, mu, rcond=None)
    scale = {"Fric": 1.0, "C1": sp, "C2": sv, "C3": sp * sv, "C4": sp**2, "C5": sv**2}
    c = {k: 0.0 for k in ("Fric", "C1", "C2", "C3", "C4", "C5")}
    for k, val in zip(use, coef, strict=True):
        c[k] = float(val / scale[k])

    def approx(**kw: np.ndarray) -> np.ndarray:
        Pm = np.asarray(job.units.to_model("p", kw["p"]), float) if "p" in kw else 0.0
        Vm = np.asarray(job.units.to_model("v", kw["v"]), float) if "v" in kw else 0.0
        return np.asarray(ifric1(c, Pm, Vm), dtype=float)

    # the approximation error, on a denser sample than the fit's
    grid = Grid(tuple(names), tuple(breakpoints(s.lo, s.hi, 201, s.kind) if not s.single
                                    else np.array([s.lo]) for s in specs),
                tuple(s.kind for s in specs))

    def diff(**kw: np.ndarray) -> np.ndarray:
        return np.asarray(job.func(**kw), float) - approx(**kw)

    err = _approx_error(diff, grid)
    return c, err, grid


def _approx_error(diff, grid: Grid) -> GridError:
    """max/rms of |diff| on a dense tensor sample plus random points."""
    vals = tabulate(diff, grid.names, grid.points)
    a = np.abs(vals)
    k = np.unravel_index(int(np.argmax(a)), a.shape)
    where = {n: float(p[i]) for n, p, i in zip(grid.names, grid.points, k, strict=True)}
    best = float(a[k])
    rng = np.random.default_rng(7)
    q = []
    for pts, sp in zip(grid.points, grid.spacing, strict=True):
        lo, hi = float(pts[0]), float(pts[-1])
        q.append(np.exp(rng.uniform(np.log(lo), np.log(hi), 20000)) if sp == "log" and lo > 0
                 else rng.uniform(lo, hi, 20000))
    r = np.abs(np.broadcast_to(np.asarray(diff(**dict(zip(grid.names, q, strict=True))),
                                          float), (20000,)))
    if r.max() > best:
        j = int(np.argmax(r))
        best = float(r[j])
        where = {n: float(x[j]) for n, x in zip(grid.names, q, strict=True)}
    return GridError(best, where, float(np.sqrt(np.mean(a**2))), a.size + 20000, 0, 20000)


def _card(job: Job, ifric: int, c: dict[str, float], title: str) -> list[str]:
    fid = job.options["radioss_id"]
    full = {k: c.get(k, 0.0) for k in _KEYS}
    return [
        f"/FRICTION/{fid}",
        title[:100],
        "#    Ifric    Ifiltr               Xfreq     Iform",
        _i10(ifric) + _i10(0) + _f20(0.0) + _i10(0),
        "#                 C1                  C2                  C3                  C4"
        "                  C5",
        "".join(_f20(full[k]) for k in ("C1", "C2", "C3", "C4", "C5")),
        "#                 C6                Fric                VISF",
        _f20(full["C6"]) + _f20(full["Fric"]) + _f20(1.0),
    ]


def write_radioss(job: Job) -> Written:
    """Ifric 1 or 4 exactly when the law allows, else Ifric 1 fitted over the box."""
    law = job.law
    bad = [v for v in job.variables if v not in ("p", "v")]
    if bad:
        raise InputError(
            f"radioss: law '{law.id}' depends on {', '.join(bad)}; Radioss friction laws "
            "(Ifric 1, 2, 4) depend on pressure and velocity only")
    units = f"p [{job.units.label('p')}], v [{job.units.label('v')}]"
    note_ref = ("reference it from the contact interface (/INTER/TYPE7, 24 or 25, field "
                "fric_ID); Radioss floors mu at 1e-30; p is the normal force over the main "
                "segment area")
    quad, _ = quadratic_pv_form(law, job.values, job.units)
    if quad is not None:
        body = [*job.box_lines(),
                "exact: Ifric 1, mu = Fric + C1 p + C2 v + C3 p v + C4 p^2 + C5 v^2 is the "
                f"law itself ({units})", note_ref]
        head = job.header("OpenRadioss /FRICTION, Ifric 1 (exact)", body,
                          "the same formula holds everywhere (no table)")
        lines = commented(head, "# ") + _card(job, 1, quad, f"frictionlaws {law.id} (exact)")
        return Written("\n".join(lines) + "\n", exact=True, summary=body[-2:-1],
                       details={"ifric": 1, "coefficients": quad})
    form, _ = exp_decay_form(law, job.values)
    if form is not None:
        scale, _ = job.units.affine("v")
        job.check_levels({"Fric = mu_s": form.mu_s, "C1 = mu_k": form.mu_k})
        c = {"C1": form.mu_k, "Fric": form.mu_s, "C2": form.d_c * scale}
        body = [*job.box_lines(),
                "exact: Ifric 4, mu = C1 + (Fric - C1) exp(-C2 v) is the law itself "
                f"(C1 = mu_k, Fric = mu_s, C2 = 1/v_c [1/({job.units.label('v')})])",
                note_ref]
        head = job.header("OpenRadioss /FRICTION, Ifric 4 (exact)", body,
                          "the same formula holds everywhere (no table)")
        lines = commented(head, "# ") + _card(job, 4, c, f"frictionlaws {law.id} (exact)")
        return Written("\n".join(lines) + "\n", exact=True, summary=body[-2:-1],
                       details={"ifric": 4, "coefficients": c})
    names: list[str] = [v for v in ("p", "v") if v in job.variables]
    c, err, grid = fit_ifric1(job, names)
    if job.tol is not None and err.max_abs > job.tol:
        raise InputError(
            f"radioss: the best Ifric 1 quadratic for law '{law.id}' is off by up to "
            f"{err.max_abs:.3g} in mu over the box, more than the tolerance {job.tol:g}; "
            "nothing was written (narrow the box, or use a table format: lsdyna, abaqus, "
            "ansys)")
    where = ", ".join(f"{k} = {job.model(k, v)}" for k, v in err.where.items())
    summary = [
        *job.box_lines(grid)[:1],
        f"APPROXIMATION: law '{law.id}' is not of a Radioss form; Ifric 1 was fitted by "
        "least squares over the box",
        f"max approximation error |mu_radioss - mu_law| = {err.max_abs:.3g} at {where}; "
        f"rms {err.rms:.3g} (checked on {err.n_checked} points of the box)",
    ]
    body = [*summary, f"coefficients in {units}", note_ref]
    head = job.header("OpenRadioss /FRICTION, Ifric 1 fitted to the law (approximation)",
                      body, "the fitted quadratic extrapolates and may be far from the law: "
                      "keep the model's pressures and velocities inside the box")
    lines = commented(head, "# ") + _card(job, 1, c, f"frictionlaws {law.id} (Ifric 1 fit)")
    return Written("\n".join(lines) + "\n", error=err, summary=summary[1:],
                   details={"ifric": 1, "coefficients": c, "approximate": True})
