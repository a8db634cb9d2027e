"""The stages of :func:`~frictionlaws.tyre.mf.fit.fit_mf` after the pure-slip forces.

With F_x0 and F_y0 fitted (:mod:`frictionlaws.tyre.mf.fit.pure`), the staged procedure goes on:

1. **combined-slip weighting functions** G_xa (RBX, RCX1, REX, RHX1) on every F_x row and
   G_yk with S_Vyk (RBY, RCY1, REY, RHY, RVY) on every F_y row, the pure-slip
   coefficients held;
2. **forces together**: the pure and combined coefficients of each direction refined at
   once on every row with the combined model, so that rows near pure slip (rig jitter)
   count with the slip they were measured at instead of being dropped.  Without
   combined-slip rows the weighting functions are the template's (another tyre's), so
   this stage fits the rows near pure slip only, and the rows away from it (F_y on a
   slip-ratio sweep, F_x on a slip-angle sweep), which would move the pure-slip shifts
   towards the template's weighting, are named in a note (:func:`together_rows`);
3. **aligning moment M_z0** (QBZ, QCZ1, QDZ, QEZ, QHZ, PPZ) on the rows near pure side slip
   with the forces held (first from three starts of the trail's B_t with the residual
   torque's width B_r held, :func:`_trail_start`; then with B_r free), then **combined
   M_z** (SSZ) with M_z0 refined together on every M_z row.

In every stage each residual is divided by the largest measured magnitude at its load
level (:func:`level_scale`), so that every load counts by its share of its own peak.

Which coefficients each stage fits, and what each needs of the data, is declared with the
coefficients (:mod:`frictionlaws.tyre.mf.declarations`: ``stage``, ``needs``).  Each stage
fits only the coefficients the data can determine: those whose variable the data do not
vary (camber, pressure, a second or third load, cross slip) keep the
template's value and are listed; so is a coefficient along a direction of the Jacobian
the data do not inform (smallest relative singular value below :data:`WEAK`) when the
template's value fits as well (cost within 1 %); otherwise it is held at its fitted value
with an infinite standard error.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ....base.errors import InputError
from ....fitting.lsq import least_squares_solve
from ..coefficients import ALL_NEEDS, direction_of, needs_met, section_of, stage_names
from ..equations import lateral, longitudinal, mf_curve, weight_x, weight_y
from ..outputs import aligning_moment
from .peak import FittingModel, peak_penalty

__all__ = ["CombinedData", "StageResult", "LaterStages", "fit_stage", "later_stages",
           "combined_names", "mz_names", "needs_met", "section_of", "group_of", "WEAK",
           "KAPPA_PURE", "ALPHA_PURE", "load_levels", "level_scale", "solve", "predict_fx",
           "predict_fy", "predict_mz", "MAX_ITERATIONS", "FTOL", "MIN_LEVEL_ROWS",
           "QBZ1_STARTS", "START_ROWS", "together_rows"]

#: Rows count as near pure slip within these cross slips (rig jitter is about 0.002 in
#: kappa and 0.1-0.3 deg in alpha): near-pure longitudinal rows have |alpha| <= 1 deg,
#: near-pure lateral rows |kappa| <= 0.01.  They start the pure-slip curves; the final
#: fits use every row with the combined model at the recorded slips.
ALPHA_PURE = math.radians(1.0)
KAPPA_PURE = 0.01
#: A direction of the column-normalised Jacobian with a relative singular value below
#: this is not informed by the data: its main coefficient is undetermined.
WEAK = 1e-5
#: Iterations (Jacobians) a stage's solver may take; a stage that stops at this limit is
#: named in the notes (its coefficients then rest where the solver stopped).
MAX_ITERATIONS = 60
#: Relative change of the cost below which a stage has converged: a change of the sum
#: of squares by 1e-7 of itself is far below one standard deviation of the noise for any
#: data set under a million rows, so further steps only wander along a flat valley.
FTOL = 1e-7
#: Cost factor within which the template's value of an uninformed coefficient is kept.
_DROP_COST = 1.01
#: A load level with fewer rows than this has its residual scale from its load
#: (:func:`level_scale`).
MIN_LEVEL_ROWS = 20

#: The width of the residual torque's peak (B_r).
_BR = ("QBZ9", "QBZ10")


def combined_names(direction: str, version: str) -> list[str]:
    """The combined-slip coefficients of ``direction`` ("x" or "y") for ``version``."""
    return stage_names("Fx" if direction == "x" else "Fy", version)


def mz_names(version: str) -> tuple[list[str], list[str]]:
    """(M_z0 coefficients, combined M_z coefficients) of ``version``."""
    return stage_names("Mz0", version), stage_names("Mz", version)


def group_of(name: str) -> str:
    """"x", "y" or "z" for a force or moment coefficient (its declared fit stage)."""
    return direction_of(name)


@dataclass
class CombinedData:
    """The rows of one fitted quantity with the model's inputs (SI, ISO axes)."""

    kappa: np.ndarray
    alpha: np.ndarray
    fz: np.ndarray
    gamma: np.ndarray
    dpi: np.ndarray
    pressure: np.ndarray
    target: np.ndarray
    #: Each row's residual is divided by this (:func:`level_scale`).
    scale: np.ndarray = field(default_factory=lambda: np.array([]))

    def __post_init__(self) -> None:
        if self.scale.size != self.target.size:
            self.scale = level_scale(self.fz, self.target)

    @classmethod
    def select(cls, data: Any, target: np.ndarray, keep: np.ndarray,
               p_nom: float | None) -> CombinedData:
        """The rows of ``data`` where ``keep`` (and ``target`` is finite)."""
        keep = keep & np.isfinite(target)
        p = data.pressure[keep]
        p = np.where(np.isfinite(p), p, p_nom if p_nom is not None else np.nan)
        dpi = (p - p_nom) / p_nom if p_nom is not None else np.zeros(p.size)
        return cls(data.kappa[keep], data.alpha[keep], data.fz[keep], data.gamma[keep],
                   dpi, p, target[keep])

    def thinned(self, most: int) -> CombinedData:
        """Every k-th row, k the smallest that leaves at most ``most`` rows (the row scales
        kept)."""
        return self.rows(slice(None, None, max(1, -(-self.target.size // most))))

    def rows(self, keep: np.ndarray | slice) -> CombinedData:
        """The rows ``keep`` (a mask, indices or a slice), with their row scales."""
        return CombinedData(*(getattr(self, f)[keep] for f in (
            "kappa", "alpha", "fz", "gamma", "dpi", "pressure", "target", "scale")))

    def spans(self) -> set[str]:
        """What these rows vary: loads2/3, camber (of both signs, of two magnitudes, two
        nonzero levels), pressure, both signs of slip, cross slip."""
        have: set[str] = set()
        n_loads = _count_levels(self.fz, 0.03 * float(np.median(self.fz)))
        have.update({"loads2"} if n_loads >= 2 else set())
        have.update({"loads3"} if n_loads >= 3 else set())
        tol = math.radians(0.2)
        if _count_levels(self.gamma, tol) >= 2:
            have.add("camber")
        if (self.gamma < -tol).sum() >= 3 and (self.gamma > tol).sum() >= 3:
            have.add("camber_signs")
        if _count_levels(np.abs(self.gamma[np.abs(self.gamma) > tol]), tol) >= 2:
            have.add("camber2")
        if _count_levels(self.gamma[np.abs(self.gamma) > tol], tol) >= 2:
            have.add("camber_sq")
        if _count_levels(self.dpi, 0.02) >= 2:
            have.add("pressure")
        if (self.alpha > 0).sum() >= 3 and (self.alpha < 0).sum() >= 3:
            have.add("both_signs")
        cross = (np.abs(self.alpha) > ALPHA_PURE) & (np.abs(self.kappa) > KAPPA_PURE)
        if cross.sum() >= 10:
            have.update({"combined_x", "combined_y", "combined_mz"})
        return have


def _count_levels(values: np.ndarray, tol: float) -> int:
    v = np.sort(values)
    return int(np.sum(np.diff(v) > tol)) + 1 if v.size else 0


def load_levels(fz: np.ndarray) -> np.ndarray:
    """The load level of each row: loads within 3 % of the median load of their
    neighbours (sorted) form one level; labels 0, 1, ... from the lightest."""
    if fz.size == 0:
        return np.zeros(0, dtype=int)
    order = np.argsort(fz)
    steps = np.diff(fz[order]) > 0.03 * float(np.median(fz))
    labels = np.empty(fz.size, dtype=int)
    labels[order] = np.concatenate([[0], np.cumsum(steps)])
    return labels


def level_scale(fz: np.ndarray, target: np.ndarray) -> np.ndarray:
    """The scale each row's residual is divided by: the largest ``|target|`` measured at
    its load level.

    A rig's noise and a fit's tolerance are both shares of the curve's peak, which grows
    with the load; unweighted, the heavy loads would dominate and the light ones be
    fitted to a larger share of their peak.  A level with fewer than
    :data:`MIN_LEVEL_ROWS` rows (loads that are not held at levels) takes the largest
    ``|target|`` of all rows in proportion to its load instead.  Scales are at least
    1e-3 of the largest ``|target|`` (never zero).
    """
    mag = np.abs(target)
    top = float(np.max(mag)) if mag.size else 1.0
    top = top if top > 0 else 1.0
    scale = top * fz / float(np.max(fz)) if fz.size else np.zeros(0)
    labels = load_levels(fz)
    for lv in np.unique(labels):
        m = labels == lv
        if m.sum() >= MIN_LEVEL_ROWS:
            scale[m] = np.max(mag[m])
    return np.maximum(scale, 1e-3 * top)


def predict_fx(mf: FittingModel, d: CombinedData) -> np.ndarray:
    """F_x = G_xa F_x0 at the rows of ``d`` (slip angle as tan(alpha))."""
    lon = longitudinal(mf, d.fz, d.gamma, d.dpi)
    fx0 = mf_curve(d.kappa + lon.S_H, lon.B, lon.C, lon.D, lon.E_a, lon.E_b, lon.S_V)
    return np.asarray(weight_x(mf, d.kappa, np.tan(d.alpha), d.fz, d.gamma) * fx0)


def predict_fy(mf: FittingModel, d: CombinedData) -> np.ndarray:
    """F_y = G_yk F_y0 + S_Vyk at the rows of ``d``."""
    lat = lateral(mf, d.fz, d.gamma, d.dpi)
    a = np.tan(d.alpha)
    fy0 = mf_curve(a + lat.S_H, lat.B, lat.C, lat.D, lat.E_a, lat.E_b, lat.S_V)
    G, S_V = weight_y(mf, d.kappa, a, d.fz, d.gamma, lat.mu)
    return np.asarray(G * fy0 + S_V)


def predict_mz(mf: FittingModel, d: CombinedData) -> np.ndarray:
    """M_z (combined, at the file's LONGVL) at the rows of ``d``."""
    p = d.pressure if mf.nominal_pressure is not None else None
    return aligning_moment(mf, d.kappa, d.alpha, d.fz, d.gamma, p)["Mz"]


@dataclass
class StageResult:
    """What one stage fitted: values, standard errors, undetermined and held names."""

    values: dict[str, float] = field(default_factory=dict)
    stderr: dict[str, float] = field(default_factory=dict)
    undetermined: list[str] = field(default_factory=list)
    held: list[str] = field(default_factory=list)
    rmse: float = math.nan
    n: int = 0
    #: Model evaluations of the last solve, and whether it met its tolerances.
    nfev: int = 0
    converged: bool = True


def fit_stage(mf: FittingModel, names: list[str], d: CombinedData,
              predict: Callable[[FittingModel, CombinedData], np.ndarray],
              template: dict[str, float], have: set[str], bounds: dict[str, tuple[float, float]]
              ) -> StageResult:
    """Fit ``names`` (those the data can determine) to ``d.target`` with ``predict``.

    Coefficients whose needs the data do not meet are set to the template's value and
    listed as undetermined; the others start at the model's current values.
    """
    out = StageResult(n=int(d.target.size))
    free = [k for k in names if needs_met(k, have)]
    for k in names:
        if k not in free:
            mf.coefficients[k] = template.get(k, 0.0)
            out.undetermined.append(k)
    if not free or d.target.size <= len(free):
        out.undetermined.extend(k for k in free if k not in out.undetermined)
        for k in free:
            mf.coefficients[k] = template.get(k, 0.0)
        return out
    r = solve(mf, free, d, predict, bounds)
    while True:
        se, weak = _stderr(r, len(free), d.target.size)
        if weak.size == 0 or len(free) <= 1:
            break
        worst = free.pop(int(np.argmax(np.abs(weak))))
        fitted = dict(mf.coefficients)
        mf.coefficients[worst] = template.get(worst, 0.0)
        refit = solve(mf, free, d, predict, bounds)
        if refit.cost <= _DROP_COST * r.cost + 1e-12 * float(np.sum((d.target / d.scale)**2)):
            out.undetermined.append(worst)
            r = refit
        else:
            mf.coefficients.clear()
            mf.coefficients.update(fitted)
            out.held.append(worst)
            out.stderr[worst] = math.inf
            r = solve(mf, free, d, predict, bounds)
    out.nfev, out.converged = int(r.nfev), bool(r.status > 0)
    out.values = {k: float(mf.coefficients[k]) for k in free + out.held}
    out.stderr.update({k: float(s) for k, s in zip(free, se)})
    res = predict(mf, d) - d.target
    out.rmse = float(np.sqrt(np.mean(res**2)))
    return out


def solve(mf: FittingModel, names: list[str], d: CombinedData,
           predict: Callable[[FittingModel, CombinedData], np.ndarray],
           bounds: dict[str, tuple[float, float]]) -> Any:
    """Bounded least squares over ``names`` from the model's current values."""
    lo = np.array([bounds.get(k, (-np.inf, np.inf))[0] for k in names])
    hi = np.array([bounds.get(k, (-np.inf, np.inf))[1] for k in names])

    def resid(p: np.ndarray) -> np.ndarray:
        for k, v in zip(names, p):
            mf.coefficients[k] = float(v)
        with np.errstate(all="ignore"):
            model = predict(mf, d)
        penalty: Any = (peak_penalty(mf.peak_mu, d.fz) if mf.peak_mu.size == d.fz.size
                        else np.array([]))
        res = np.concatenate([(model - d.target) / d.scale,
                              penalty / d.scale[:penalty.size]])
        return np.where(np.isfinite(res), res, 1e6 * (1 + np.abs(d.target).max()))

    p0 = np.array([mf.coefficients.get(k, 0.0) for k in names])
    with np.errstate(invalid="ignore"):
        p0 = np.clip(p0, np.where(np.isfinite(lo), lo + 1e-6 * (1 + np.abs(lo)), lo),
                     np.where(np.isfinite(hi), hi - 1e-6 * (1 + np.abs(hi)), hi))
    # Levenberg-Marquardt (MINPACK, QR-based: fast on tall Jacobians); the bounded
    # trust-region solver only when it ends outside the bounds of a shape coefficient
    r = least_squares_solve(resid, p0, x_scale="jac", method="lm", ftol=FTOL,
                      max_nfev=MAX_ITERATIONS * (len(names) + 1))
    if np.any(r.x < lo) or np.any(r.x > hi) or not np.isfinite(r.cost):
        r = least_squares_solve(resid, p0, bounds=(lo, hi), x_scale="jac", method="trf",
                          ftol=FTOL, max_nfev=MAX_ITERATIONS)
    resid(r.x)  # leave the model at the solution
    return r


def _stderr(r: Any, n_free: int, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Standard errors (Gauss-Newton) and the least informed direction, if any."""
    J = r.jac[:n]
    norms = np.linalg.norm(J, axis=0)
    norms[norms == 0] = 1.0
    # the singular values of J equal those of R in J = QR (small, square)
    _, s, vt = np.linalg.svd(np.linalg.qr(J / norms, mode="r"), full_matrices=False)
    s2 = 2.0 * r.cost / max(n - n_free, 1)
    with np.errstate(divide="ignore", invalid="ignore"):
        cov = (vt.T / s**2) @ vt / np.outer(norms, norms) * s2
        se = np.sqrt(np.diag(cov))
    weak = vt[-1] if s[-1] < WEAK * s[0] else np.array([])
    return se, weak


@dataclass
class LaterStages:
    """The result of :func:`later_stages`: merged over the stages."""

    values: dict[str, float] = field(default_factory=dict)
    stderr: dict[str, float] = field(default_factory=dict)
    undetermined: list[str] = field(default_factory=list)
    errors: dict[str, dict[str, float]] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def take(self, r: StageResult) -> None:
        for k in r.undetermined:
            self.values.pop(k, None)
            self.stderr.pop(k, None)
            if k not in self.undetermined:
                self.undetermined.append(k)
        self.values.update(r.values)
        self.stderr.update(r.stderr)
        if not r.converged:
            self.notes.append(f"a stage fitting {', '.join(r.values)} stopped at its limit of "
                              f"{MAX_ITERATIONS} iterations before meeting its tolerances: "
                              "these coefficients rest where the solver stopped (a flat "
                              "valley of the cost: more or wider data would settle them)")


def _errors(predict: Callable[[FittingModel, CombinedData], np.ndarray], mf: FittingModel,
            d: CombinedData) -> dict[str, float]:
    res = predict(mf, d) - d.target
    return {"n": float(d.target.size), "rmse": float(np.sqrt(np.mean(res**2))),
            "max_abs": float(np.max(np.abs(res))), "peak": float(np.max(np.abs(d.target)))}


def later_stages(mf: FittingModel, data: Any, version: str, template: dict[str, float],
                 p_nom: float | None, pure: dict[str, float], pure_se: dict[str, float],
                 bounds: dict[str, tuple[float, float]]) -> LaterStages:
    """Combined forces, the forces together, M_z0 and combined M_z (module notes).

    ``pure`` and ``pure_se`` are the pure-slip coefficients already fitted (with their
    standard errors; infinite for one held at its fitted value).
    """
    out = LaterStages(values=dict(pure), stderr=dict(pure_se))
    for name, target, predict in (("x", data.fx, predict_fx), ("y", data.fy, predict_fy)):
        d = CombinedData.select(data, target, np.ones(len(data), bool), p_nom)
        comb = combined_names(name, version)
        if not any(group_of(k) == name for k in pure):
            out.undetermined.extend(k for k in comb if k not in out.undetermined)
            if d.target.size:
                out.notes.append(f"F{name}: no pure-slip curve was fitted, so the combined-"
                                 f"slip rows cannot be used (the F{name} coefficients are "
                                 "the template's)")
            continue
        out.take(fit_stage(mf, comb, d, predict, template, d.spans(), bounds))
        rows = together_rows(d, name)
        out.notes.extend(_off_pure_note(name, d, rows))
        group = [k for k in out.values if group_of(k) == name and out.stderr.get(k) != math.inf]
        joint = fit_stage(mf, group, d.rows(rows), predict, template, set(ALL_NEEDS), bounds)
        out.take(joint)
        if ((np.abs(d.alpha) > ALPHA_PURE) & (np.abs(d.kappa) > KAPPA_PURE)).any():
            out.errors[f"{name}_all"] = _errors(predict, mf, d)
    _aligning_stages(mf, data, version, template, p_nom, bounds, out)
    return out


def together_rows(d: CombinedData, name: str) -> np.ndarray:
    """The rows of ``d`` on which the forces-together stage (and the sweep bootstrap's
    refit) fits the F``name`` coefficients: every row when the data have combined-slip
    rows, else only the rows near pure slip.

    The model of a row away from pure slip (F_y on a slip-ratio sweep, F_x on a slip-angle
    sweep) is the pure-slip curve times the weighting function; without combined-slip
    rows the weighting function is the template's, another tyre's, and fitted to it those
    rows move the pure-slip coefficients (the shifts most: an MF 5.2 tyre's pure sweeps
    with both forces on every row, fitted as MF 6.1, ended 1 % of peak off at zero slip
    instead of 0.3 %).
    """
    if f"combined_{name}" in d.spans():
        return np.ones(d.target.size, dtype=bool)
    return np.abs(d.alpha) <= ALPHA_PURE if name == "x" else np.abs(d.kappa) <= KAPPA_PURE


def _off_pure_note(name: str, d: CombinedData, rows: np.ndarray) -> list[str]:
    """The note on the rows of F``name`` that :func:`together_rows` leaves out (none when
    it leaves none)."""
    off = ~rows
    if not off.any():
        return []
    other, weight = (("|alpha| > 1 deg", "G_xa") if name == "x" else
                     ("|kappa| > 0.01", "G_yk and S_Vyk"))
    return [f"F{name}: {int(off.sum())} rows away from pure slip ({other}) are not fitted: "
            f"without combined-slip rows the weighting function ({weight}) is the "
            f"template's, and fitted to it those rows would move the pure-slip "
            "coefficients (the shifts most)"]


def _aligning_stages(mf: FittingModel, data: Any, version: str, template: dict[str, float],
                     p_nom: float | None, bounds: dict[str, tuple[float, float]],
                     out: LaterStages) -> None:
    """M_z0 on the rows near pure side slip, then M_z0 and SSZ together on every row."""
    if not np.isfinite(data.mz).any():
        out.notes.append("aligning-moment coefficients (Q*Z*, SSZ*): the template's (no Mz "
                         "column)")
        return
    mz0_names, s_names = mz_names(version)
    if not any(group_of(k) == "y" for k in out.values):
        raise InputError("the Mz column cannot be fitted: M_z rests on the lateral force, "
                         "and F_y0 was not fitted (no Fy rows near pure side slip); give "
                         "the Fy of those rows, or leave out the Mz column to fit the rest",
                         file=data.source, column="Mz")
    pure = CombinedData.select(data, data.mz, np.abs(data.kappa) <= KAPPA_PURE, p_nom)
    every = CombinedData.select(data, data.mz, np.ones(len(data), bool), p_nom)
    if pure.target.size:
        # the residual torque's width (B_r) last: a narrow peak the data barely sample
        # would otherwise take up the misfit of the trail and stay where it went
        _trail_start(mf, [k for k in mz0_names if k not in _BR], pure, template, bounds)
        out.take(fit_stage(mf, mz0_names, pure, predict_mz, template, pure.spans(), bounds))
    else:
        out.notes.append("no M_z rows near pure side slip: M_z0 is fitted on the combined "
                         "rows together with the SSZ terms")
    have = every.spans()
    group = [k for k in mz0_names if k in out.values and out.stderr.get(k) != math.inf]
    if not pure.target.size:
        group = [k for k in mz0_names if needs_met(k, have)]
    s_free = [k for k in s_names if needs_met(k, have)]
    for k in s_names:
        if k not in s_free:
            mf.coefficients[k] = template.get(k, 0.0)
            if k not in out.undetermined:
                out.undetermined.append(k)
    out.take(fit_stage(mf, group + s_free, every, predict_mz, template, set(ALL_NEEDS), bounds))
    out.errors["mz"] = _errors(predict_mz, mf, every)


#: Factors on the template's QBZ1 (the trail's stiffness factor B_t) the aligning moment
#: starts from; the trail's shape and B_t trade off, and one start can end in the wrong
#: valley (the best end is kept).
QBZ1_STARTS = (1.0, 0.6, 1.6)
#: Rows (every k-th) on which the starts are compared; the stage then runs on all.
START_ROWS = 1500


def _trail_start(mf: FittingModel, names: list[str], d: CombinedData,
                 template: dict[str, float], bounds: dict[str, tuple[float, float]]) -> None:
    """M_z0 with the residual torque's width held, from each start of :data:`QBZ1_STARTS`,
    on at most :data:`START_ROWS` of the rows; the model is left at the best end."""
    start = dict(mf.coefficients)
    d = d.thinned(START_ROWS)
    qbz1 = start.get("QBZ1", template.get("QBZ1", 0.0))
    best: tuple[float, dict[str, float]] | None = None
    for factor in QBZ1_STARTS:
        mf.coefficients.clear()
        mf.coefficients.update(start)
        mf.coefficients["QBZ1"] = qbz1 * factor
        r = fit_stage(mf, names, d, predict_mz, template, d.spans(), bounds)
        if math.isfinite(r.rmse) and (best is None or r.rmse < best[0]):
            best = (r.rmse, dict(mf.coefficients))
    mf.coefficients.clear()
    mf.coefficients.update(start if best is None else best[1])
