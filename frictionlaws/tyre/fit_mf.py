"""Fit the Magic Formula (forces and aligning moment) to tyre test data; write a property file.

:func:`fit_mf` fits the coefficient groups of MF 5.2, 6.1 or 6.2 to measured forces
and aligning moments (:class:`~frictionlaws.tyre.tyre_data.TyreData`) in stages: the
pure-slip forces F_x0, F_y0 as below, then the combined-slip weighting functions, the
forces refined together on every row, the aligning moment M_z0 and combined M_z
(:mod:`frictionlaws.tyre._fit_mf_stages`).  The pure-slip forces are fitted in three
steps:

1. **per-load curves**: at each load (at the nominal pressure and the smallest
   camber measured) a Magic Formula curve ``D sin(C arctan(B x - E (B x -
   arctan(B x)))) + S_V`` with ``x = slip + S_H`` is fitted alone;
2. **load dependence** (regressions of mu, K, E, S_H, S_V of the per-load curves
   on ``dfz``) gives the starting values of the load coefficients; the pressure
   and camber coefficients are then fitted with those held;
3. **global refinement** of every coefficient the data span, on all pure-slip
   points at once (:func:`scipy.optimize.least_squares`); standard errors from
   the Jacobian, ``SE = sqrt(diag(s^2 (J^T J)^-1))``.

Coefficients the data cannot determine (a pressure term with one pressure, a
camber term with one camber, a curvature in load with fewer than three loads,
an asymmetry with one sign of slip, or a direction of the Jacobian with no
information) are left at the template's value and named in the notes; a coefficient along a
direction the data do not inform whose template value would spoil the fit is held
at its fitted value instead (standard error infinite, named in the notes).  The
pure-slip steps start from the rows near pure slip (cross slip within
:data:`~frictionlaws.tyre._fit_mf_stages.ALPHA_PURE` = 1 deg or
:data:`~frictionlaws.tyre._fit_mf_stages.KAPPA_PURE` = 0.01, robust to rig jitter); the
later stages use every row with the combined-slip model at the slips recorded.  The
slip angle enters as tan(alpha), the library's default convention, and the file
written says so.  Data whose slips, angles or loads look like another unit than
declared are refused first (:mod:`frictionlaws.tyre._fit_mf_checks`).

The peak friction coefficient stays within a physical range during the fit, and
data that stop before the peak give a warning (the peak is extrapolated), not a
refusal; see :mod:`frictionlaws.tyre._fit_mf_peak`.
"""

from __future__ import annotations

import math
import time
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..base.errors import ExtrapolationWarning, FitError, InputError
from ..fitting.lsq import least_squares_solve
from . import _fit_mf_stages as stages_
from ._fit_mf_checks import check_plausible, repeated_rows
from ._fit_mf_peak import PEAK_MU, FittingModel, peak_message, peak_penalty, unreached_peaks
from ._fit_mf_rows import _Direction, _levels, _select
from ._mf_file import structure
from .magic_formula import EXAMPLES, MagicFormula, mf_curve, packaged_example
from .mf_coefficients import default as declared_default
from .mf_coefficients import fit_bounds
from .tir import PropertyFile, format_tir, read_property_file
from .tyre_data import TyreData

__all__ = ["MFFit", "fit_mf", "check_tir_path", "FITTYPS", "X_COEFFICIENTS", "Y_COEFFICIENTS",
           "UNCERTAINTIES"]

#: FITTYP -> Magic Formula version.
FITTYPS = {5: "5.2", 6: "5.2", 21: "5.2", 61: "6.1", 62: "6.2"}

_X = "PCX1 PDX1 PDX2 PDX3 PEX1 PEX2 PEX3 PEX4 PKX1 PKX2 PKX3 PHX1 PHX2 PVX1 PVX2".split()
_PPX = "PPX1 PPX2 PPX3 PPX4".split()
_Y52 = ("PCY1 PDY1 PDY2 PDY3 PEY1 PEY2 PEY3 PEY4 PKY1 PKY2 PKY3 PHY1 PHY2 PHY3 "
        "PVY1 PVY2 PVY3 PVY4").split()
_Y6 = ("PCY1 PDY1 PDY2 PDY3 PEY1 PEY2 PEY3 PEY4 PEY5 PKY1 PKY2 PKY3 PKY4 PKY5 PKY6 PKY7 "
       "PHY1 PHY2 PVY1 PVY2 PVY3 PVY4 PPY1 PPY2 PPY3 PPY4 PPY5").split()
#: Coefficients fitted per version and direction.
X_COEFFICIENTS = {"5.2": _X, "6.1": _X + _PPX, "6.2": _X + _PPX}
Y_COEFFICIENTS = {"5.2": _Y52, "6.1": _Y6, "6.2": _Y6}

# What each coefficient needs in the data (beyond one load).
_NEEDS: dict[str, tuple[str, ...]] = {
    **{k: ("pressure",) for k in "PPX1 PPX3 PPY1 PPY2 PPY3".split()},
    # quadratic in the pressure: with two pressures they trade off against PKX1, PDX1, PDY1
    **{k: ("pressure3",) for k in "PPX2 PPX4 PPY4".split()},
    "PPY5": ("pressure", "camber"),
    **{k: ("camber",) for k in "PDX3 PDY3 PEY4 PEY5 PKY3 PKY5 PKY6 PHY3 PVY3".split()},
    **{k: ("camber", "loads2") for k in "PKY7 PVY4".split()},
    **{k: ("loads2",) for k in "PDX2 PEX2 PKX2 PHX2 PVX2 PDY2 PEY2 PKY2 PHY2 PVY2".split()},
    **{k: ("loads3",) for k in "PEX3 PKX3 PKY4".split()},
    "PEX4": ("both_signs",), "PEY3": ("both_signs",),
}


@dataclass
class MFFit:
    """The result of :func:`fit_mf`.

    Attributes
    ----------
    version : str
        Magic Formula version fitted (``"5.2"``, ``"6.1"``, ``"6.2"``).
    property_file : PropertyFile
        The template with the fitted coefficients, FITTYP, conditions and ranges.
    values, stderr : dict
        Fitted coefficient -> value and standard error.
    undetermined : list of str
        Coefficients the data cannot determine (left at the template value).
    errors : dict
        Per quantity: ``"x"``, ``"y"`` (pure-slip rows, F_x0 and F_y0 stages),
        ``"x_all"``, ``"y_all"`` (every row, combined model) and ``"mz"`` (every M_z
        row): ``rmse``, ``max_abs``, ``peak`` (largest measured magnitude) [N or N m]
        and ``n`` points.
    stages : dict
        Per direction, the per-load curves of stage 1 (load, mu, K, C, E, S_H, S_V).
    warnings : list of str
        What the data leave open (a peak they do not reach); also issued as
        :class:`~frictionlaws.base.errors.ExtrapolationWarning` and written as notes.
    """

    version: str
    property_file: PropertyFile
    model: MagicFormula
    values: dict[str, float]
    stderr: dict[str, float]
    undetermined: list[str]
    errors: dict[str, dict[str, float]]
    stages: dict[str, list[dict[str, float]]]
    data: TyreData
    seconds: float
    notes: list[str] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    #: How the standard errors were made (:data:`UNCERTAINTIES`, with the details).
    uncertainty: str = ""
    #: The asymptotic standard errors (equal to ``stderr`` unless bootstrapped).
    stderr_asymptotic: dict[str, float] = field(default_factory=dict)

    def tir_text(self) -> str:
        """The ``.tir`` text of the fitted property file."""
        fitted = ", ".join(_LABELS[k] for k in self.errors) or "nothing"
        from .. import __version__

        header = [f"FITTED by frictionlaws {__version__} fit_mf from {self.data.source} "
                  f"({len(self.data)} rows), Magic Formula {self.version}: {fitted}; "
                  "other coefficients and sections from the template.",
                  "Slip angle convention: alpha* = tan(alpha) in the lateral slip "
                  "(MFeval useMode 2x); camber as sin(gamma) in the force terms.",
                  "Friction scaling: LMU' = LMU (A_mu = 1, as MFeval 4.0).",
                  f"Standard errors: {self.uncertainty or UNCERTAINTIES['asymptotic']}."]
        header += [f"warning: {w}" for w in self.warnings]
        header += [f"note: {n}" for n in self.notes]
        return format_tir(self.property_file, header=header)

    def write(self, path: str | Path) -> Path:
        """Write the ``.tir`` file atomically (checked as an output first)."""
        from ..base.outputs import atomic_write, check_outputs

        check_tir_path(path)
        check_outputs([path], inputs=[self.data.source])
        with atomic_write(path) as fh:
            fh.write(self.tir_text())
        return Path(path)

    def report(self) -> str:
        """Plain-text report: coefficients with standard errors, errors, notes."""
        lines = [f"Magic Formula {self.version} fit to {self.data.source} "
                 f"({len(self.data)} rows, {self.seconds:.1f} s)",
                 f"standard errors: {self.uncertainty or UNCERTAINTIES['asymptotic']}"]
        for name, v in self.values.items():
            se = self.stderr.get(name, math.nan)
            lines.append(f"  {name:<5} = {v:< 12.6g} +/- {se:.3g}")
        for d, e in self.errors.items():
            u = "N m" if d == "mz" else "N"
            lines.append(f"{_LABELS[d]}: {int(e['n'])} points, RMSE {e['rmse']:.4g} {u}, max "
                         f"|error| {e['max_abs']:.4g} {u}, peak {e['peak']:.4g} {u}")
        lines.extend(f"warning: {w}" for w in self.warnings)
        lines.extend(f"note: {n}" for n in self.notes)
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """JSON-able summary."""
        return {"version": self.version, "source": self.data.source, "rows": len(self.data),
                "coefficients": {k: {"value": v, "stderr": self.stderr.get(k)}
                                 for k, v in self.values.items()},
                "uncertainty": self.uncertainty or UNCERTAINTIES["asymptotic"],
                "undetermined": list(self.undetermined), "errors": self.errors,
                "stages": self.stages, "seconds": self.seconds, "notes": list(self.notes),
                "warnings": list(self.warnings)}

    def plot(self, path: str | Path) -> Path:
        """Save a figure of data and fit per load (nominal pressure, smallest camber)."""
        from ._fit_mf_plot import plot_fit

        return plot_fit(self, path)


def check_tir_path(path: str | Path) -> None:
    """Refuse a property file name whose suffix is not ``.tir`` (the text written is
    ADAMS ``.tir``; a ``.json`` name would hold it under the wrong format)."""
    if Path(path).suffix.lower() != ".tir":
        raise InputError("the property file written is ADAMS .tir text: give the file the "
                         "suffix .tir", file=str(path))


#: How the standard errors are made (``uncertainty=`` of :func:`fit_mf`).
UNCERTAINTIES = {
    "asymptotic": "asymptotic (Gauss-Newton, s^2 (J^T J)^-1 of each stage; assumes "
                  "independent residuals, too small when a sweep's residuals share an "
                  "offset)",
    "sweeps": "sweep bootstrap"}

#: What each entry of :attr:`MFFit.errors` describes.
_LABELS = {"x": "Fx0 (rows near pure slip)", "y": "Fy0 (rows near pure slip)",
           "x_all": "Fx (every row, combined slip)", "y_all": "Fy (every row, combined slip)",
           "mz": "Mz (every row, combined slip)"}

# ------------------------------------------------------------------ helpers


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


def _stage1(d: _Direction) -> list[list[dict[str, float]]]:
    """Stage 1: one Magic Formula curve per load at the reference conditions (nominal
    pressure, smallest camber), all with one shape factor C (C does not depend on load).

    Each curve is ``D sin(C arctan(B x - E (B x - arctan(B x)))) + S_V`` with
    ``x = slip + S_H`` and ``E = E_a - E_b sgn(x)``.  Fitted from each shape factor of
    :data:`STAGE1_SHAPES`; returns the sets of curves, the lowest cost first, of the ends
    within :data:`STAGE1_TIE` of it (the data do not tell them apart here: the later
    stages choose).
    """
    sets = [(d.x()[sel], d.force[sel], float(np.mean(d.fz[sel])))
            for sel in (d.reference & (d.load_labels == i) for i in range(d.loads.size))
            if sel.sum() >= 8]
    if not sets:
        raise FitError(f"stage 1: no load with 8 or more pure-slip F{d.name}0 points at the "
                       "reference pressure and camber")
    both = [(x > 0).sum() >= 3 and (x < 0).sum() >= 3 for x, _, _ in sets]
    c_lo, c_hi = _BOUNDS["PCX1" if d.name == "x" else "PCY1"]  # C = PCX1 at LCX = 1
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
    return [_curves(r.x, sets, both) for r in ends
            if r.cost <= (1 + STAGE1_TIE) * ends[0].cost]


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
    lo = [-np.inf, _BOUNDS["PKY2"][0]] + ([_BOUNDS["PKY4"][0]] if free4 else [])
    hi = [np.inf, _BOUNDS["PKY2"][1]] + ([_BOUNDS["PKY4"][1]] if free4 else [])
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


def _stage2_start(d: _Direction, curves: list[dict[str, float]], fz0: float,
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


def _spans(d: _Direction, data: TyreData) -> set[str]:
    """What the data of one direction span: loads2/3, pressure(3), camber, both_signs."""
    have: set[str] = set()
    if d.loads.size >= 2:
        have.add("loads2")
    if d.loads.size >= 3:
        have.add("loads3")
    n_p = _levels(d.dpi, 0.02)[0].size
    if n_p >= 2:
        have.add("pressure")
    if n_p >= 3:
        have.add("pressure3")
    if _levels(d.gamma, math.radians(0.2))[0].size >= 2:
        have.add("camber")
    if (d.slip > 0).sum() >= 3 and (d.slip < 0).sum() >= 3:
        have.add("both_signs")
    return have


def _needs_met(name: str, have: set[str]) -> bool:
    return all(n in have for n in _NEEDS.get(name, ()))


def _predict(mf: MagicFormula, d: _Direction, names: Sequence[str], p: np.ndarray
             ) -> np.ndarray:
    """The model force at the points of ``d`` with ``names`` set to ``p``."""
    for name, v in zip(names, p):
        mf.coefficients[name] = float(v)
    if d.name == "x":
        k = mf._long(d.fz, d.gamma, d.dpi)
        return mf_curve(d.slip + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)
    k = mf._lat(d.fz, d.gamma, d.dpi)
    return mf_curve(np.tan(d.slip) + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, k.S_V)


#: The search range of each coefficient, from its declaration (:mod:`.mf_coefficients`).
_BOUNDS = fit_bounds()


def _solve(mf: FittingModel, d: _Direction, names: list[str], method: str = "lm") -> Any:
    """Least squares over ``names`` (starting at the model's current values).

    Levenberg-Marquardt (MINPACK) from the staged start; when it ends outside the
    bounds of a shape coefficient (C, PKY2, PKY4, E at nominal load), the bounded
    trust-region solver is run from the start and from the clipped solution, and the
    better end is kept (clipping a solution that ran along a flat direction can leave
    it far from the data).  The residuals are the
    force errors followed by the peak-friction penalty (zero while the peak
    friction is physical, :func:`~frictionlaws.tyre._fit_mf_peak.peak_penalty`), each
    divided by the largest measured force at its load level
    (:func:`~frictionlaws.tyre._fit_mf_stages.level_scale`).
    """
    lo = np.array([_BOUNDS.get(k, (-np.inf, np.inf))[0] for k in names])
    hi = np.array([_BOUNDS.get(k, (-np.inf, np.inf))[1] for k in names])

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


def _fit_direction(mf: FittingModel, d: _Direction, data: TyreData, version: str,
                   template: dict[str, float]) -> tuple[dict, dict, list[str], list[dict]]:
    """Stages 1-3 for one direction: (values, stderr, undetermined, stage-1 curves)."""
    group = X_COEFFICIENTS[version] if d.name == "x" else Y_COEFFICIENTS[version]
    have = _spans(d, data)
    free = [k for k in group if _needs_met(k, have)]
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
def _cost(mf: FittingModel, d: _Direction) -> float:
    """The weighted sum of squares of the model at the rows of ``d``."""
    return float(np.sum(((_predict(mf, d, [], np.array([])) - d.force) / d.scale) ** 2))


def _template_restart(mf: FittingModel, d: _Direction, best: _End,
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


def _stages23(mf: FittingModel, d: _Direction, free: list[str], curves: list[dict],
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


def _refine(mf: FittingModel, d: _Direction, free: list[str], template: dict[str, float]
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


def _template(template: str | Path | PropertyFile | None, version: str) -> PropertyFile:
    if isinstance(template, PropertyFile):
        pf = template
    elif template is None:
        name = {"5.2": "magicformula52", "6.1": "magicformula61", "6.2": "magicformula62"}
        p = packaged_example(EXAMPLES[name[version]])
        if p is None:
            raise InputError("the packaged template property files are missing")
        pf = _packaged(p)
    else:
        path = Path(template)
        packaged = None if path.exists() else packaged_example(str(template))
        pf = _packaged(packaged) if packaged is not None else read_property_file(path)
    _check_template(pf, version)
    return pf


def _check_template(pf: PropertyFile, version: str) -> None:
    """Refuse a template of the other family (MF 5.2 against MF 6.x: it lacks the
    coefficients and sections of the version written, which would be written without
    them or as zeros claimed to be the template's values) or with an unloaded radius
    that is not positive (the moments would be zero and M_z data look wrong)."""
    from ._mf_file import version_of

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


def _packaged(path: Path) -> PropertyFile:
    """A packaged example, named by its file name (not where pip installed it)."""
    pf = read_property_file(path)
    pf.path = f"packaged:{path.name}"
    return pf


#: A template's FNOMIN or nominal pressure this factor or more outside the measured
#: range is replaced by the median measured value (:func:`_near_data`).
FAR_FROM_DATA = 2.0


def _near_data(name: str, value: float, measured: np.ndarray, unit: str,
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


def _nominal_pressure(pf: PropertyFile, data: TyreData, notes: list[str]) -> float | None:
    measured = data.pressure[np.isfinite(data.pressure)]
    for sec, key in (("OPERATING_CONDITIONS", "NOMPRES"), ("TIRE_CONDITIONS", "IP_NOM")):
        if pf.has(sec, key):
            p = pf.si(sec, key)
            return _near_data("NOMPRES", p, measured, "Pa", notes) if measured.size else p
    if measured.size:
        p = float(np.median(measured))
        notes.append(f"no nominal pressure in the template: the median measured pressure "
                     f"{p:g} Pa is taken as NOMPRES")
        return p
    return None


def _errors(mf: MagicFormula, d: _Direction) -> dict[str, float]:
    names: list[str] = []
    res = _predict(mf, d, names, np.array([])) - d.force
    return {"n": float(d.force.size), "rmse": float(np.sqrt(np.mean(res**2))),
            "max_abs": float(np.max(np.abs(res))), "peak": float(np.max(np.abs(d.force)))}


def _build_file(t: PropertyFile, fittyp: int, values: dict[str, float],
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
        pf.sections.setdefault(stages_.section_of(k), {})[k] = v
    f_force, f_p = pf.si_factor("force"), pf.si_factor("pressure")
    if fnomin is not None:
        pf.sections.setdefault("VERTICAL", {})["FNOMIN"] = fnomin / f_force
    if p_nom is not None and FITTYPS[fittyp] != "5.2":
        oc = pf.sections.setdefault("OPERATING_CONDITIONS", {})
        oc["NOMPRES"] = oc["INFLPRES"] = p_nom / f_p
    ranges = [("VERTICAL_FORCE_RANGE", "FZMIN", "FZMAX", data.fz / f_force),
              ("LONG_SLIP_RANGE", "KPUMIN", "KPUMAX", data.kappa),
              ("SLIP_ANGLE_RANGE", "ALPMIN", "ALPMAX", data.alpha),
              ("INCLINATION_ANGLE_RANGE", "CAMMIN", "CAMMAX", data.gamma)]
    measured = data.pressure[np.isfinite(data.pressure)]
    if measured.size and FITTYPS[fittyp] != "5.2":
        ranges.append(("INFLATION_PRESSURE_RANGE", "PRESMIN", "PRESMAX", measured / f_p))
    for sec, lo, hi, observed in ranges:
        entry = pf.sections.setdefault(sec, {})
        entry[lo], entry[hi] = float(np.min(observed)), float(np.max(observed))
    if p_nom is not None and measured.size and FITTYPS[fittyp] != "5.2":
        inside = float(np.clip(p_nom, measured.min(), measured.max()))
        if inside != p_nom:
            pf.sections["OPERATING_CONDITIONS"]["INFLPRES"] = inside / f_p
            notes.append(f"the nominal pressure {p_nom:g} Pa lies outside the measured "
                         f"{measured.min():g}..{measured.max():g} Pa: INFLPRES is set to "
                         f"{inside:g} Pa, NOMPRES stays")
    return pf


def _model_from_template(tpl: PropertyFile, data: TyreData, version: str, notes: list[str]
                         ) -> tuple[dict[str, float], float | None, float | None, FittingModel]:
    """The template's coefficients, the nominal pressure (of the file; of the fit: None for
    MF 5.2) and the model the stages fit,
    after the data's plausibility against the template (FNOMIN, pressure, radius)."""
    notes.append(f"template {tpl.path}: FNOMIN, the other sections and the undetermined "
                 "coefficients come from it")
    tpl_coeffs = tpl.coefficients("SCALING_COEFFICIENTS", "LONGITUDINAL_COEFFICIENTS",
                                  "LATERAL_COEFFICIENTS", "ALIGNING_COEFFICIENTS")
    fnomin = tpl.si("VERTICAL", "FNOMIN")
    p_nom = _nominal_pressure(tpl, data, notes)
    radius = (tpl.si("DIMENSION", "UNLOADED_RADIUS") if tpl.has("DIMENSION", "UNLOADED_RADIUS")
              else None)
    p_tpl = (tpl.si("OPERATING_CONDITIONS", "NOMPRES")
             if tpl.has("OPERATING_CONDITIONS", "NOMPRES") else None)
    check_plausible(data, fnomin, p_tpl, radius)
    fnomin = _near_data("FNOMIN", fnomin, data.fz, "N", notes)
    p_fit = p_nom if version != "5.2" else None
    mf = FittingModel(dict(tpl_coeffs), fnomin=fnomin, version=version, source=tpl.path,
                      pressure=p_fit, nominal_pressure=p_fit, structure=structure(tpl))
    if version == "5.2" and np.isfinite(data.pressure).any():
        notes.append("MF 5.2 has no pressure coefficients here: the pressure column is "
                     "not used")
    return dict(tpl_coeffs), p_nom, p_fit, mf


def fit_mf(data: TyreData | str | Path | Sequence[str | Path], *, fittyp: int = 61,
           template: str | Path | PropertyFile | None = None,
           sign_convention: str | None = None, uncertainty: str = "asymptotic",
           resamples: int = 100, seed: int = 0, jobs: int = 1,
           sweeps: Sequence[Any] | np.ndarray | None = None) -> MFFit:
    """Fit the Magic Formula to tyre test data, stage by stage (module docstring).

    Parameters
    ----------
    data : TyreData, str, Path or sequence of them
        The measurements, or files of any tyre test format (:mod:`frictionlaws.tyre.data`).
    fittyp : {5, 6, 21, 61, 62}
        FITTYP of the file written: 5, 6 or 21 for MF 5.2 / PAC2002, 61 for MF 6.1,
        62 for MF 6.2.
    template : path, PropertyFile or packaged example name, optional
        Property file providing FNOMIN, the nominal pressure, the other sections
        and the values of coefficients the data cannot determine (default: the
        packaged example of the version).
    sign_convention : {"iso", "sae"}, optional
        Axes of the files (default: each format's; SAE for raw rig runs).
    uncertainty : {"asymptotic", "sweeps"}
        How the standard errors are made.  ``"asymptotic"`` (the default, no extra
        cost): from the Jacobian of each stage, ``s^2 (J^T J)^-1``, which assumes
        independent residuals and is too small when a sweep's residuals share an
        offset.  ``"sweeps"``: the sweep bootstrap
        (:mod:`frictionlaws.tyre._fit_mf_bootstrap`), which resamples whole sweeps
        and refits the final stages from the point estimate; it costs about
        ``resamples`` times the final stages.
    resamples, seed, jobs : int
        For ``uncertainty="sweeps"``: resamples (default 100), their seed (default 0)
        and worker processes (default 1; :func:`frictionlaws.parallel.run_parallel`).
    sweeps : array-like, optional
        For ``uncertainty="sweeps"``: a sweep label per row; default: the data's own
        (``data.extra``), else from the row order (``_fit_mf_bootstrap.find_sweeps``).

    Returns
    -------
    MFFit

    Raises
    ------
    InputError
        Unknown FITTYP, unreadable data or template.
    FitError
        Too few pure-slip points.
    """
    t0 = time.perf_counter()
    boot = dict(resamples=resamples, seed=seed, jobs=jobs, sweeps=sweeps)
    data = _checked_inputs(data, fittyp, sign_convention, uncertainty, boot)
    version = FITTYPS[fittyp]
    tpl = _template(template, version)
    notes = list(data.notes)
    notes.extend(filter(None, [repeated_rows(data)]))
    tpl_coeffs, p_nom, p_fit, mf = _model_from_template(tpl, data, version, notes)
    values, stderr, undetermined, stages, errors, warns = _fit_directions(
        mf, data, version, tpl_coeffs, p_fit, notes)
    later = stages_.later_stages(mf, data, version, tpl_coeffs, p_fit, values, stderr,
                                 _BOUNDS)
    values, stderr = later.values, later.stderr
    undetermined = [k for k in undetermined if k not in values] + [
        k for k in later.undetermined if k not in undetermined]
    errors.update(later.errors)
    notes.extend(later.notes)
    if not values:
        raise FitError(f"{data.source}: nothing could be fitted (no coefficient is "
                       "determined by these rows); no file written")
    notes.extend(_undetermined_notes(undetermined, stderr))
    pf = _build_file(tpl, fittyp, values, p_nom, data, notes, mf.fnomin)
    asymptotic = dict(stderr)
    method = UNCERTAINTIES["asymptotic"]
    if uncertainty == "sweeps":
        stderr, method = _bootstrap(mf, data, values, stderr, p_fit, {**boot,
                                                                      "warnings_out": warns})
    fitted = _finish(pf, version, values, stderr, undetermined, errors, stages, data,
                     t0, notes)
    fitted.uncertainty, fitted.stderr_asymptotic = method, asymptotic
    fitted.warnings = warns
    for text in warns:
        warnings.warn(text, ExtrapolationWarning, stacklevel=2)
    return fitted


def _checked_inputs(data: TyreData | str | Path | Sequence[str | Path], fittyp: int,
                    sign_convention: str | None, uncertainty: str, boot: dict[str, Any]
                    ) -> TyreData:
    """The data (read when files), after the options are checked (before any fit)."""
    from .data.formats import read_tyre_files

    if uncertainty not in UNCERTAINTIES:
        raise InputError(f"uncertainty {uncertainty!r} is not known; expected one of "
                         f"{', '.join(UNCERTAINTIES)}")
    if fittyp not in FITTYPS:
        raise InputError(f"FITTYP {fittyp!r} is not fitted here; expected one of "
                         f"{', '.join(str(k) for k in FITTYPS)}")
    if not isinstance(data, TyreData):
        files = [data] if isinstance(data, (str, Path)) else list(data)
        data, _ = read_tyre_files(files, sign_convention=sign_convention)
    if boot["sweeps"] is None and "sweep" in data.extra:
        boot["sweeps"] = data.extra["sweep"]
    if uncertainty == "sweeps":
        from ._fit_mf_bootstrap import check_can_resample, check_options

        check_options(boot["resamples"], boot["jobs"], boot["sweeps"], len(data))
        check_can_resample(data, boot["sweeps"])  # resamples that cannot vary: refused
    return data


def _undetermined_notes(undetermined: list[str], stderr: dict[str, float]) -> list[str]:
    """The notes naming the coefficients left at the template and those held."""
    out = []
    if undetermined:
        out.append("not determined by the data, left at the template's value: "
                   + ", ".join(undetermined))
    held = [k for k, se in stderr.items() if se == math.inf]
    if held:
        out.append("not determined by the data, and the template's value does not suit "
                   "them: held at the fitted value (standard error infinite): "
                   + ", ".join(held))
    return out


def _bootstrap(mf: FittingModel, data: TyreData, values: dict[str, float],
               stderr: dict[str, float], p_fit: float | None, options: dict[str, Any]
               ) -> tuple[dict[str, float], str]:
    """The sweep bootstrap's standard errors of every coefficient with a finite one (the
    others keep theirs) and its description."""
    from ._fit_mf_bootstrap import sweep_bootstrap

    groups: dict[str, list[str]] = {}
    for k in values:
        if math.isfinite(stderr.get(k, math.inf)):
            groups.setdefault(stages_.group_of(k), []).append(k)
    boot, method = sweep_bootstrap(mf, data, groups, p_fit, _BOUNDS, **options)
    return {**stderr, **boot}, method


def _fit_directions(mf: FittingModel, data: TyreData, version: str,
                    template: dict[str, float], p_fit: float | None, notes: list[str]
                    ) -> tuple[dict[str, float], dict[str, float], list[str], dict, dict,
                               list[str]]:
    """Fit F_x0 then F_y0: values, standard errors, undetermined coefficients, stage-1
    curves, errors and warnings (peaks the data do not reach)."""
    values: dict[str, float] = {}
    stderr: dict[str, float] = {}
    undetermined: list[str] = []
    stages: dict[str, list[dict[str, float]]] = {}
    errors: dict[str, dict[str, float]] = {}
    warns: list[str] = []
    for name in ("x", "y"):
        d = _select(data, name, p_fit)
        if d is None:
            notes.append(f"no pure-slip F{name}0 points: the F{name}0 coefficients are the "
                         "template's")
            continue
        v, se, und, curves = _fit_direction(mf, d, data, version, template)
        values.update(v)
        stderr.update(se)
        undetermined.extend(und)
        stages[name] = curves
        errors[name] = _errors(mf, d)
        ref = d.reference
        unreached = unreached_peaks(mf, name, d.slip[ref], d.fz[ref], d.gamma[ref],
                                    d.dpi[ref], d.load_labels[ref], d.loads)
        if unreached:
            warns.append(peak_message(name, unreached, [k for k in v if k[:2] == "PD"]))
    return values, stderr, undetermined, stages, errors, warns


def _finish(pf: PropertyFile, version: str, values: dict[str, float],
            stderr: dict[str, float], undetermined: list[str], errors: dict, stages: dict,
            data: TyreData, t0: float, notes: list[str]) -> MFFit:
    """Check that the written text reads back as the fitted model; assemble the result."""
    from .tir import read_tir

    text = format_tir(pf)
    back = read_tir(text, source="<fitted .tir>")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        model = MagicFormula.from_property_file(back)
    if model.version != version:
        raise FitError(f"the written file reads back as MF {model.version}, not {version}")
    return MFFit(version=version, property_file=pf, model=model, values=values,
                 stderr=stderr, undetermined=undetermined, errors=errors, stages=stages,
                 data=data, seconds=time.perf_counter() - t0, notes=notes)
