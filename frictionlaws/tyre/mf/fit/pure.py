"""The pure-slip stages of a Magic Formula fit: F_x0 and F_y0 from the rows near pure slip.

Stage 1 fits one curve per load (one shape factor C for all), stage 2 regresses its
factors on the load to start the load coefficients (then fits the pressure and camber
terms with those held), stage 3 refines every coefficient the data span on all the rows
of the direction; see :mod:`frictionlaws.tyre.mf.fit.staged`.  Which coefficients are
fitted, and what each needs of the data, is declared with the coefficients (stages
``Fx0`` and ``Fy0`` of :mod:`frictionlaws.tyre.mf.declarations`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ....base.errors import FitError
from ....fitting.lsq import least_squares_solve
from ...data.table import TyreData
from ..coefficients import default as declared_default
from ..coefficients import fit_bounds, needs_met, stage_names
from ..declarations import VERSIONS
from ..equations import lateral, longitudinal, mf_curve
from ..parameters import MFParameters
from .peak import PEAK_MU, FittingModel, peak_penalty
from .rows import Direction, levels

__all__ = ["fit_direction", "direction_errors", "X_COEFFICIENTS", "Y_COEFFICIENTS",
           "STAGE1_SHAPES", "STAGE1_TIE", "STAGE1_NEAR"]

#: Coefficients fitted per version and direction (the declared stages ``Fx0``, ``Fy0``).
X_COEFFICIENTS = {v: stage_names("Fx0", v) for v in VERSIONS}
Y_COEFFICIENTS = {v: stage_names("Fy0", v) for v in VERSIONS}


def _linfit(x: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Intercept and slope of y on x (slope 0 with fewer than two distinct x)."""
    if np.ptp(x) <= 0 or x.size < 2:
        return float(np.mean(y)), 0.0
    slope, intercept = np.polyfit(x, y, 1)
    return float(intercept), float(slope)


def _curve_start(x: np.ndarray, y: np.ndarray) -> list[float]:
    """B, D, E, E_b, S_H, S_V to start one curve (C = 1.4): slope near 0 and peak."""
    ax = np.abs(x)
    small = ax <= max(np.quantile(ax, 0.15), np.sort(ax)[min(2, ax.size - 1)])
    K0 = np.polyfit(x[small], y[small], 1)[0] if np.ptp(x[small]) > 0 else 1.0
    D0 = float(np.max(np.abs(y)))
    return [K0 / (1.4 * D0), D0, 0.0, 0.0, 0.0, 0.0]


def _stage1(d: Direction) -> list[list[dict[str, float]]]:
    """Stage 1: one Magic Formula curve per load at the reference conditions (nominal
    pressure, smallest camber), all with one shape factor C (C does not depend on load).

    Each curve is ``D sin(C arctan(B x - E (B x - arctan(B x)))) + S_V`` with
    ``x = slip + S_H`` and ``E = E_a - E_b sgn(x)``.  Fitted from each shape factor of
    :data:`STAGE1_SHAPES`; returns the sets of curves, the lowest cost first, of the ends
    within :data:`STAGE1_TIE` of it (the data do not tell them apart here: the later
    stages choose), then the sets fitted with C held at each shape factor of
    :data:`STAGE1_SHAPES` that no free end came near.  Stage 1 sees the reference rows
    only, where each load's own curvature and shifts can trade against C and fit the
    noise with a C far from the tyre's; the later stages see every row and keep the best.
    """
    sets = [(d.x()[sel], d.force[sel], float(np.mean(d.fz[sel])))
            for sel in (d.reference & (d.load_labels == i) for i in range(d.loads.size))
            if sel.sum() >= 8]
    if not sets:
        raise FitError(f"stage 1: no load with 8 or more pure-slip F{d.name}0 points at the "
                       "reference pressure and camber")
    both = [(x > 0).sum() >= 3 and (x < 0).sum() >= 3 for x, _, _ in sets]
    c_lo, c_hi = fit_bounds()["PCX1" if d.name == "x" else "PCY1"]  # C = PCX1 at LCX = 1
    p0, lo, hi = [min(max(1.4, c_lo), c_hi)], [c_lo], [c_hi]
    for x, y, fz in sets:
        start = _curve_start(x, y)
        d_max = min(5 * start[1], PEAK_MU[1] * fz)  # a peak the data stop before: physical
        start[1] = min(start[1], 0.5 * d_max)
        p0 += start
        lo += [-np.inf, 1e-6 * start[1], -20.0, -20.0, -np.inf, -np.inf]
        hi += [np.inf, d_max, 1.0, 20.0, np.inf, np.inf]

    def resid(p: np.ndarray) -> np.ndarray:
        out = []
        for j, (x, y, _) in enumerate(sets):
            B, D, E, E_b, sh, sv = p[1 + 6 * j: 7 + 6 * j]
            out.append(mf_curve(x + sh, B, p[0], D, E, E_b if both[j] else 0.0, sv) - y)
        return np.concatenate(out)

    # from two shape factors: a curve whose peak is flat (C near 1) and a curve with a
    # peak; the shape and the curvature trade off, and one start can end in the other's
    # valley
    shapes = sorted({min(max(c0, c_lo), c_hi) for c0 in STAGE1_SHAPES}, reverse=True)
    ends = sorted((least_squares_solve(resid, _with_shape(p0, c0), bounds=(lo, hi),
                                       x_scale="jac") for c0 in shapes),
                  key=lambda res: res.cost)
    kept = [r for r in ends if r.cost <= (1 + STAGE1_TIE) * ends[0].cost]
    for c0 in shapes:  # C held: the start of a valley the free ends may have left
        if all(abs(r.x[0] - c0) > STAGE1_NEAR for r in kept):
            held = ([c0 - 1e-9, *lo[1:]], [c0 + 1e-9, *hi[1:]])
            kept.append(least_squares_solve(resid, _with_shape(p0, c0), bounds=held,
                                            x_scale="jac"))
    return [_curves(r.x, sets, both) for r in kept]


def _curves(x: np.ndarray, sets: list[tuple[np.ndarray, np.ndarray, float]],
            both: list[bool]) -> list[dict[str, float]]:
    """The per-load curves of stage 1 from its parameters ``x``."""
    C = float(x[0])
    out = []
    for j, (_, _, fz) in enumerate(sets):
        B, D, E, E_b, sh, sv = (float(v) for v in x[1 + 6 * j: 7 + 6 * j])
        out.append({"load": fz, "mu": D / fz, "K": B * C * D, "C": C, "E": E,
                    "E_b": E_b if both[j] else 0.0, "S_H": sh, "S_V": sv, "B": B})
    return out


#: The shape factors C stage 1 starts from.
STAGE1_SHAPES = (1.4, 1.0)
#: Stage-1 ends within this share of the lowest cost are each carried through the later
#: pure-slip stages, which keep the better.
STAGE1_TIE = 0.03
#: A shape factor of :data:`STAGE1_SHAPES` no free stage-1 end came this near is carried
#: through the later stages too, from curves fitted with C held at it.
STAGE1_NEAR = 0.05


def _with_shape(p0: list[float], c0: float) -> np.ndarray:
    """Stage 1's start with the shape factor ``c0`` (within the declared fit range of C):
    each curve's B rescaled so that its slope at zero, B C D, stays."""
    p = np.array(p0, dtype=float)
    p[1::6] *= p[0] / c0
    p[0] = c0
    return p


def _ky_start(curves: list[dict[str, float]], fz0: float, six: bool) -> dict[str, float]:
    """PKY1, PKY2 (and PKY4 for MF 6.x) from the per-load cornering stiffnesses."""
    fz = np.array([c["load"] for c in curves])
    K = np.array([c["K"] for c in curves])
    free4 = six and fz.size >= 3

    def model(p: np.ndarray) -> np.ndarray:
        k1, k2 = p[0], p[1]
        k4 = p[2] if free4 else 2.0
        return k1 * fz0 * np.sin(k4 * np.arctan(fz / (k2 * fz0)))

    k2_0 = 2.0 * float(fz.max()) / fz0
    p0 = [float(K[np.argmax(np.abs(K))]) / fz0 * 1.2, k2_0] + ([2.0] if free4 else [])
    bounds = fit_bounds()
    lo = [-np.inf, bounds["PKY2"][0]] + ([bounds["PKY4"][0]] if free4 else [])
    hi = [np.inf, bounds["PKY2"][1]] + ([bounds["PKY4"][1]] if free4 else [])
    if fz.size >= 2:
        p = least_squares_solve(lambda q: (model(q) - K) / np.abs(K).max(), p0,
                          bounds=(lo, hi)).x
    else:
        p = np.array(p0)
        p[0] = K[0] / (fz0 * math.sin(2.0 * math.atan(fz[0] / (p[1] * fz0))))
    out = {"PKY1": float(p[0]), "PKY2": float(p[1])}
    if six:
        out["PKY4"] = float(p[2]) if free4 else 2.0
    return out


def _stage2_start(d: Direction, curves: list[dict[str, float]], fz0: float,
                  version: str) -> dict[str, float]:
    """Starting values of the load coefficients from the per-load curves (regressions)."""
    fz = np.array([c["load"] for c in curves])
    dfz = (fz - fz0) / fz0
    col = {k: np.array([c[k] for c in curves]) for k in ("mu", "K", "C", "E", "S_H", "S_V")}
    e = np.minimum(col["E"], 0.95)
    if d.name == "x":
        names: tuple[str, ...] = ("PDX1 PDX2", "PKX1 PKX2", "PEX1 PEX2", "PHX1 PHX2",
                                  "PVX1 PVX2")
        ys: tuple[np.ndarray, ...] = (col["mu"], col["K"] / fz, e, col["S_H"], col["S_V"] / fz)
        out = {"PCX1": float(np.mean(col["C"]))}
    else:
        names = ("PDY1 PDY2", "PEY1 PEY2", "PHY1 PHY2", "PVY1 PVY2")
        ys = (col["mu"], e, col["S_H"], col["S_V"] / fz)
        out = {"PCY1": float(np.mean(col["C"]))}
        out.update(_ky_start(curves, fz0, version != "5.2"))
    for pair, y in zip(names, ys):
        a, b = _linfit(dfz, y)
        n1, n2 = pair.split()
        out[n1], out[n2] = a, b
    # the asymmetry of E: E = E0 (1 - P sgn(x)), so P = E_b / E0 at each load
    e0 = np.array([c["E"] for c in curves])
    e_b = np.array([c["E_b"] for c in curves])
    ok = np.abs(e0) > 1e-3
    if ok.any():
        out["PEX4" if d.name == "x" else "PEY3"] = float(np.median(e_b[ok] / e0[ok]))
    return out


def _spans(d: Direction, data: TyreData) -> set[str]:
    """What the data of one direction span: loads2/3, pressure(3), camber, both_signs."""
    have: set[str] = set()
    if d.loads.size >= 2:
        have.add("loads2")
    if d.loads.size >= 3:
        have.add("loads3")
    n_p = levels(d.dpi, 0.02)[0].size
    if n_p >= 2:
        have.add("pressure")
    if n_p >= 3:
        have.add("pressure3")
    if levels(d.gamma, math.radians(0.2))[0].size >= 2:
        have.add("camber")
    if (d.slip > 0).sum() >= 3 and (d.slip < 0).sum() >= 3:
        have.add("both_signs")
    return have


def _predict(mf: MFParameters, d: Direction, names: Sequence[str], p: np.ndarray
             ) -> np.ndarray:
    """The model force at the points of ``d`` with ``names`` set to ``p``."""
    for name, v in zip(names, p):
        mf.coefficients[name] = float(v)
    if d.name == "x":
        k = longitudinal(mf, d.fz, d.gamma, d.dpi)
        return mf_curve(d.slip + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
    k = lateral(mf, d.fz, d.gamma, d.dpi)
    return mf_curve(np.tan(d.slip) + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)


def _solve(mf: FittingModel, d: Direction, names: list[str], method: str = "lm") -> Any:
    """Least squares over ``names`` (starting at the model's current values).

    Levenberg-Marquardt (MINPACK) from the staged start; when it ends outside the
    bounds of a shape coefficient (C, PKY2, PKY4, E at nominal load), the bounded
    trust-region solver is run from the start and from the clipped solution, and the
    better end is kept (clipping a solution that ran along a flat direction can leave
    it far from the data).  The residuals are the
    force errors followed by the peak-friction penalty (zero while the peak
    friction is physical, :func:`~frictionlaws.tyre.mf.fit.peak.peak_penalty`), each
    divided by the largest measured force at its load level
    (:func:`~frictionlaws.tyre.mf.fit.stages.level_scale`).
    """
    bounds = fit_bounds()  # the declared search ranges
    lo = np.array([bounds.get(k, (-np.inf, np.inf))[0] for k in names])
    hi = np.array([bounds.get(k, (-np.inf, np.inf))[1] for k in names])

    def resid(p: np.ndarray) -> np.ndarray:
        force = _predict(mf, d, names, p) - d.force
        penalty = peak_penalty(mf.peak_mu, d.fz)
        return np.concatenate([force / d.scale, penalty / d.scale[:penalty.size]])

    def inside(p: np.ndarray) -> np.ndarray:
        with np.errstate(invalid="ignore"):
            return np.clip(p, np.where(np.isfinite(lo), lo + 1e-6 * (1 + np.abs(lo)), lo),
                           np.where(np.isfinite(hi), hi - 1e-6 * (1 + np.abs(hi)), hi))

    p0 = inside(np.array([mf.coefficients.get(k, 0.0) for k in names]))
    with np.errstate(all="ignore"):
        if method == "lm":
            r = least_squares_solve(resid, p0, method="lm", x_scale="jac",
                              max_nfev=200 * (len(names) + 1))
        else:
            r = least_squares_solve(resid, p0, bounds=(lo, hi), x_scale="jac", method="trf",
                              max_nfev=100 * (len(names) + 1))
        if np.any(r.x < lo) or np.any(r.x > hi) or not np.isfinite(r.cost):
            starts = [p0] + ([inside(r.x)] if np.isfinite(r.cost) else [])
            r = min((least_squares_solve(resid, x0, bounds=(lo, hi), x_scale="jac", method="trf",
                                   max_nfev=100 * (len(names) + 1)) for x0 in starts),
                    key=lambda res: res.cost)
    _predict(mf, d, names, r.x)  # leave the model at the solution
    return r


def _stderr(r: Any, n_free: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Standard errors and the smallest relative singular value's direction of J.

    ``n`` is the number of data points (the rows of J after them are the penalty's).
    """
    J = r.jac
    norms = np.linalg.norm(J, axis=0)
    norms[norms == 0] = 1.0
    _, s, vt = np.linalg.svd(J / norms, full_matrices=False)
    dof = max(n - n_free, 1)
    s2 = 2.0 * r.cost / dof
    with np.errstate(divide="ignore", invalid="ignore"):
        cov = (vt.T / s**2) @ vt / np.outer(norms, norms) * s2
        se = np.sqrt(np.diag(cov))
    weak = vt[-1] if s[-1] < 1e-6 * s[0] else np.array([])
    return se, weak


def fit_direction(mf: FittingModel, d: Direction, data: TyreData, version: str,
                   template: dict[str, float]) -> tuple[dict, dict, list[str], list[dict]]:
    """Stages 1-3 for one direction: (values, stderr, undetermined, stage-1 curves)."""
    group = X_COEFFICIENTS[version] if d.name == "x" else Y_COEFFICIENTS[version]
    have = _spans(d, data)
    free = [k for k in group if needs_met(k, have)]
    undetermined = [k for k in group if k not in free]
    for k in group:  # every coefficient starts at zero or its stage-2 value ...
        mf.coefficients[k] = 0.0
    for k in undetermined:  # ... except those the data cannot determine
        mf.coefficients[k] = _template_value(template, k)
    base = dict(mf.coefficients)
    best: _End | None = None
    for curves in _stage1(d):
        mf.coefficients.clear()
        mf.coefficients.update(base)
        kept = list(free)
        se, dropped, held = _stages23(mf, d, kept, curves, version, template)
        end = (_cost(mf, d), dict(mf.coefficients), kept, (se, dropped, held), curves)
        best = end if best is None or end[0] < best[0] else best
    assert best is not None  # _stage1 returns at least one set of curves
    _, coefficients, free, (se, dropped, held), curves = _template_restart(mf, d, best,
                                                                            template)
    mf.coefficients.clear()
    mf.coefficients.update(coefficients)
    undetermined.extend(dropped)
    values = {k: float(mf.coefficients[k]) for k in free + held}
    stderr = {k: float(s) for k, s in zip(free, se)}
    stderr.update({k: math.inf for k in held})
    return values, stderr, undetermined, curves


#: A stage-3 end: cost, coefficients, free names, (standard errors, dropped, held) and
#: the stage-1 curves it came from.
_End = tuple[float, dict[str, float], list[str], Any, list[dict]]
def _cost(mf: FittingModel, d: Direction) -> float:
    """The weighted sum of squares of the model at the rows of ``d``."""
    return float(np.sum(((_predict(mf, d, [], np.array([])) - d.force) / d.scale) ** 2))


def _template_restart(mf: FittingModel, d: Direction, best: _End,
                      template: dict[str, float]) -> _End:
    """Stage 3 once more, from the template's values of the coefficients ``best`` fitted;
    the lower cost is kept and the model left there.

    With the peak beyond the data (or a flat one) the per-load curves of stage 1 leave C
    free to trade against the peak and the curvature, and the coefficients' load and
    camber structure can then hold stage 3 in that valley; a start from another tyre
    (the template) can find the other."""
    cost, coefficients, free, (se, dropped, held), curves = best
    mf.coefficients.clear()
    mf.coefficients.update(coefficients)
    mf.coefficients.update({k: _template_value(template, k) for k in free})
    kept = list(free)
    with np.errstate(all="ignore"):
        se2, dropped2, held2 = _refine(mf, d, kept, template)
    if _cost(mf, d) < cost:
        return (_cost(mf, d), dict(mf.coefficients), kept,
                (se2, dropped + dropped2, held + held2), curves)
    mf.coefficients.clear()
    mf.coefficients.update(coefficients)
    return best


def _stages23(mf: FittingModel, d: Direction, free: list[str], curves: list[dict],
              version: str, template: dict[str, float]
              ) -> tuple[np.ndarray, list[str], list[str]]:
    """Stages 2 and 3 from the stage-1 ``curves`` (``free`` shortened in place): the
    standard errors, the coefficients dropped to the template and those held."""
    start = _stage2_start(d, curves, mf.fz0, version)
    mf.coefficients.update({k: v for k, v in start.items() if k in free})
    rest = [k for k in free if k not in start]
    if rest:  # stage 2b: pressure, camber and curvature terms with the load terms held
        _solve(mf, d, rest)
    return _refine(mf, d, free, template)


def _template_value(template: dict[str, float], name: str) -> float:
    return template[name] if name in template else declared_default(name)


#: A template value may replace an uninformed coefficient if the refit is no worse than
#: this factor on the cost (else the coefficient is held at its fitted value).
_DROP_COST = 1.01


def _refine(mf: FittingModel, d: Direction, free: list[str], template: dict[str, float]
            ) -> tuple[np.ndarray, list[str], list[str]]:
    """Stage 3: global refinement of ``free`` (shortened in place), dropping directions
    the data do not inform.

    A dropped coefficient goes back to the template's value when the refit is then no
    worse (cost within :data:`_DROP_COST`); otherwise the template's value does not
    suit these data and the coefficient is held where the fit left it.

    Returns the standard errors of ``free``, the coefficients set to the template's
    value and those held at their fitted value.
    """
    dropped: list[str] = []
    held: list[str] = []
    r = _solve(mf, d, free)
    while True:
        se, weak = _stderr(r, len(free), d.force.size)
        if weak.size == 0 or len(free) <= 1:
            return se, dropped, held
        worst = free[int(np.argmax(np.abs(weak)))]
        free.remove(worst)
        fitted = dict(mf.coefficients)
        mf.coefficients[worst] = _template_value(template, worst)
        refit = _solve(mf, d, free)
        if refit.cost <= _DROP_COST * r.cost + 1e-12 * float(np.sum((d.force / d.scale)**2)):
            dropped.append(worst)
            r = refit
        else:
            mf.coefficients.clear()
            mf.coefficients.update(fitted)
            held.append(worst)
            r = _solve(mf, d, free)



def direction_errors(mf: MFParameters, d: Direction) -> dict[str, float]:
    """RMSE, largest error, peak and count of the pure-slip rows of ``d`` [N]."""
    names: list[str] = []
    res = _predict(mf, d, names, np.array([])) - d.force
    return {"n": float(d.force.size), "rmse": float(np.sqrt(np.mean(res**2))),
            "max_abs": float(np.max(np.abs(res))), "peak": float(np.max(np.abs(d.force)))}
