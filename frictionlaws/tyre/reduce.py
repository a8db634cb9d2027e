"""Reduce a full Magic Formula to a simple slip law (``pacejka``, ``burckhardt``...).

A property file describes the whole load-dependent tyre; an FE contact, a
controller or a quick vehicle model often wants a single mu(s) curve.
:func:`reduce_mf` samples ``mu = F_x0 / F_z`` from the Magic Formula at one
load over a range of slip ratios and fits a registered slip law to it with
:func:`frictionlaws.fitting.fit`, reporting the fit error and comparing the
peaks.

Slip laws use the braking slip ``s`` (0..1, positive) and a positive mu.  On
the braking side (default) ``kappa = -s`` and ``mu = -F_x0(-s) / F_z``; on the
driving side ``kappa = s`` and ``mu = F_x0(s) / F_z``.

At a fixed load the pure-slip Magic Formula *is* a ``pacejka`` curve: with
the factors of :meth:`MagicFormula.longitudinal`, braking gives
``B = B_x, C = C_x, D = mu_x, E = E_x(kappa_x < 0), S_h = -S_Hx,
S_v = -S_Vx / F_z`` (:func:`equivalent_pacejka`); the fit should recover them,
which tests the whole chain.  ``burckhardt`` has no such equivalent and the
fit error says how far it is from the tyre (its speed factor ``c4`` is fixed at
0: a steady-state pure-slip Magic Formula has no speed dependence).
"""

from __future__ import annotations

import json
import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..fitting import fit as run_fit
from ..law.registry import get_law
from .mf.model import MagicFormula
from .mf.notices import collected

__all__ = ["Reduction", "reduce_mf", "equivalent_pacejka", "mf_slip_curve", "MIN_POINTS"]

SIDES = ("braking", "driving")
#: The fewest slip points a reduction samples (a six-parameter law needs more than six).
MIN_POINTS = 10


def mf_slip_curve(mf: MagicFormula, fz: float, slip: Any, *, side: str = "braking",
                  gamma: float = 0.0, pressure: float | None = None) -> np.ndarray:
    """mu(s) = |F_x0| / F_z of ``mf`` at load ``fz`` [N] and braking/driving slip ``slip``."""
    if side not in SIDES:
        raise InputError(f"side must be one of {', '.join(SIDES)}, got {side!r}")
    s = np.asarray(slip, dtype=float)
    sign = -1.0 if side == "braking" else 1.0
    # per unit of the load evaluated: a load clamped at FZMAX is the force's load too
    return sign * np.asarray(mf.fx0(sign * s, fz, gamma, pressure)) / mf.evaluated_load(fz)


def equivalent_pacejka(mf: MagicFormula, fz: float, *, side: str = "braking",
                       gamma: float = 0.0, pressure: float | None = None) -> dict[str, float]:
    """The ``pacejka`` law parameters equal to ``mf``'s F_x0/F_z at load ``fz``.

    Exact for slips beyond the horizontal shift (where sgn(k_x) is constant).
    """
    if side not in SIDES:
        raise InputError(f"side must be one of {', '.join(SIDES)}, got {side!r}")
    k = mf.longitudinal(fz, gamma, pressure)
    sign = -1.0 if side == "braking" else 1.0
    return {"B": float(k.B), "C": float(k.C), "D": float(k.mu), "E": float(k.E(sign)),
            "S_h": float(sign * k.S_H),
            "S_v": float(sign * k.S_V / mf.evaluated_load(fz))}


@dataclass
class Reduction:
    """A slip law fitted to a Magic Formula curve at one load.

    Attributes
    ----------
    fit : FitResult
        The fit (parameters with standard errors, metrics, warnings).
    slip, mu_mf, mu_law : numpy.ndarray
        The sampled slips, the Magic Formula's mu and the fitted law's mu.
    errors : dict
        ``rmse``, ``max_abs`` (largest |mu_law - mu_mf|), ``r2`` and the peak
        values of both curves.
    expected : dict or None
        The exact ``pacejka`` equivalent (:func:`equivalent_pacejka`) when the
        law is ``pacejka``.
    """

    law: str
    mf_name: str
    fz: float
    side: str
    fit: Any
    slip: np.ndarray
    mu_mf: np.ndarray
    mu_law: np.ndarray
    errors: dict[str, float]
    expected: dict[str, float] | None = None
    notes: list[str] = field(default_factory=list)
    #: The load the Magic Formula evaluated [N] (FZMAX when ``fz`` was clamped).
    fz_evaluated: float = math.nan
    #: What the Magic Formula's evaluation warned of (outside the file's ranges, clamped).
    warnings: list[str] = field(default_factory=list)

    @property
    def clamped(self) -> bool:
        """True when the load was clamped (evaluated at the file's FZMAX)."""
        return bool(self.fz_evaluated != self.fz)

    @property
    def params(self) -> dict[str, float]:
        """Fitted parameter values."""
        return self.fit.param_values

    def to_dict(self) -> dict[str, Any]:
        """JSON-able summary (the fit is included in its save format)."""
        return {"law": self.law, "magic_formula": self.mf_name, "load_N": self.fz,
                "load_evaluated_N": self.fz_evaluated, "clamped": self.clamped,
                "side": self.side, "slip_range": [float(self.slip[0]), float(self.slip[-1])],
                "n_points": int(self.slip.size), "params": self.params,
                "errors": dict(self.errors), "expected_pacejka": self.expected,
                "notes": list(self.notes), "warnings": list(self.warnings),
                "fit": json.loads(self.fit.to_json())}

    def report(self) -> str:
        """Plain-text report with units."""
        e = self.errors
        at = (f" (clamped: evaluated at FZMAX = {self.fz_evaluated:g} N)" if self.clamped
              else "")
        lines = [f"{self.mf_name}: F_x0/F_z at F_z = {self.fz:g} N{at} ({self.side} side, "
                 f"s = {self.slip[0]:g}..{self.slip[-1]:g}, {self.slip.size} points) reduced "
                 f"to law '{self.law}'"]
        for name, p in self.fit.params.items():
            tail = "fixed" if p.fixed else (f"+/- {p.stderr:.3g}" if p.stderr is not None
                                            else "no std. error")
            exp = ""
            if self.expected and name in self.expected:
                exp = f"   (Magic Formula: {self.expected[name]:.6g})"
            lines.append(f"  {name:<4} = {p.value:.6g} {tail}{exp}")
        lines.append(f"fit error: RMSE {e['rmse']:.3g}, max |error| {e['max_abs']:.3g} "
                     f"(in mu, -), R^2 {e['r2']:.6f}")
        lines.append(f"peak: Magic Formula mu {e['mu_peak_mf']:.4f} at s = {e['s_peak_mf']:.4f}; "
                     f"law mu {e['mu_peak_law']:.4f} at s = {e['s_peak_law']:.4f}")
        lines.extend(f"note: {n}" for n in self.notes)
        lines.extend(f"warning: {w}" for w in (*self.warnings, *self.fit.warnings))
        return "\n".join(lines)


def reduce_mf(mf: MagicFormula | str, law: str = "pacejka", *, fz: float,
              side: str = "braking", slip_max: float = 1.0, n: int = 201,
              gamma: float = 0.0, pressure: float | None = None,
              fix: Mapping[str, float] | None = None, seed: int = 0) -> Reduction:
    """Fit a slip law to the Magic Formula's mu(s) = |F_x0|/F_z at load ``fz``.

    Parameters
    ----------
    mf : MagicFormula or str
        The tyre, or a property file path / packaged example name.
    law : str
        A slip law (``pacejka``, ``burckhardt``, ``burckhardt-sqrt``,
        ``kiencke-daiss``, ``germann``).
    fz : float
        Vertical load [N].
    side : {"braking", "driving"}
        Which half of the curve.
    slip_max : float
        Largest slip ratio sampled (0 < slip_max <= 1).
    n : int
        Number of slip points (uniform from 0 to ``slip_max``).
    gamma, pressure : float
        Camber [rad] and inflation pressure [Pa] passed to the Magic Formula.
    fix : mapping, optional
        Parameters held fixed (``burckhardt`` always fixes ``c4 = 0``).
    seed : int
        Seed of the fitter's random starts.

    Returns
    -------
    Reduction
        The fitted law with its parameters and standard errors, the sampled
        curves, the fit error in mu (RMSE, largest error, R^2), both peaks, the
        exact ``pacejka`` equivalent when the law is ``pacejka``, the load evaluated (FZMAX
        when clamped), the warnings of the Magic Formula's evaluation (outside the file's
        ranges, clamped; also issued) and notes (fixed parameters).

    Raises
    ------
    InputError
        For a law that is not a slip law or needs other variables, a bad load,
        slip range, point count or side, or an unreadable property file.
    """
    mf = _as_mf(mf)
    the_law = _slip_law(law)
    fz = _check_request(n, slip_max, fz)
    slip = np.linspace(0.0, slip_max, n)
    with collected(mf.not_applied) as warned:  # of the Magic Formula's evaluation
        mu_mf = mf_slip_curve(mf, fz, slip, side=side, gamma=gamma, pressure=pressure)
        expected = (equivalent_pacejka(mf, fz, side=side, gamma=gamma, pressure=pressure)
                    if the_law.id == "pacejka" else None)
    notes: list[str] = []
    data: dict[str, Any] = {"mu": mu_mf, "s": slip}
    fix = dict(fix or {})
    if "v" in the_law.variables:
        data["v"] = np.zeros_like(slip)
        if "c4" in the_law.param_names and "c4" not in fix:
            fix["c4"] = 0.0
            notes.append("c4 fixed at 0: the steady-state pure-slip Magic Formula has no "
                         "speed dependence (v = 0 in the data)")
    result = run_fit(the_law, data, fix=fix, weights=None, seed=seed)
    if "v" in the_law.variables:
        result.warnings = [w for w in result.warnings
                           if not w.startswith("the data have a single value of v")]
    mu_law = np.asarray(result.law.evaluate(
        {k: v for k, v in data.items() if k != "mu"}, result.values), dtype=float)
    return Reduction(law=the_law.id, mf_name=mf.name or mf.source, fz=fz, side=side,
                     fit=result, slip=slip, mu_mf=mu_mf, mu_law=mu_law,
                     errors=_fit_errors(slip, mu_mf, mu_law), expected=expected, notes=notes,
                     fz_evaluated=float(mf.evaluated_load(fz)), warnings=warned)


def _as_mf(mf: MagicFormula | str) -> MagicFormula:
    """The tyre itself, or read from a property file path / packaged example name."""
    if isinstance(mf, str):
        return MagicFormula.from_file(mf)
    if not isinstance(mf, MagicFormula):
        raise InputError("mf must be a MagicFormula or a property file path")
    return mf


def _slip_law(law: str) -> Any:
    """The registered law ``law``, refused unless it is a slip law of ``s`` (and ``v``)."""
    the_law = get_law(law)
    if the_law.family != "slip":
        raise InputError(f"law '{the_law.id}' is a {the_law.family} law; a Magic Formula "
                         "curve is mu against the slip ratio: use a slip law (pacejka, "
                         "burckhardt, burckhardt-sqrt, kiencke-daiss, germann)")
    extra = [v for v in the_law.variables if v not in ("s", "v")]
    if extra:
        raise InputError(f"law '{the_law.id}' needs {', '.join(extra)}, which a pure-slip "
                         "Magic Formula curve does not provide")
    return the_law


def _check_request(n: Any, slip_max: Any, fz: Any) -> float:
    """Check the sampling (``n`` points up to ``slip_max``) and return the load as a float."""
    if not (isinstance(n, int) and n >= MIN_POINTS):
        raise InputError(f"n must be an integer >= {MIN_POINTS}, got {n!r}")
    if not (0 < slip_max <= 1):
        raise InputError(f"slip_max must lie in (0, 1], got {slip_max!r}")
    load = float(fz)
    if not (math.isfinite(load) and load > 0):
        raise InputError(f"fz must be a positive load [N], got {fz!r}")
    return load


def _fit_errors(slip: np.ndarray, mu_mf: np.ndarray, mu_law: np.ndarray) -> dict[str, float]:
    """RMSE, largest error and R^2 of the law against the Magic Formula, and both peaks."""
    resid = mu_law - mu_mf
    i_mf, i_law = int(np.argmax(mu_mf)), int(np.argmax(mu_law))
    ss_tot = float(np.sum((mu_mf - mu_mf.mean()) ** 2))
    return {"rmse": float(np.sqrt(np.mean(resid**2))),
            "max_abs": float(np.max(np.abs(resid))),
            "r2": 1.0 - float(np.sum(resid**2)) / ss_tot if ss_tot > 0 else float("nan"),
            "mu_peak_mf": float(mu_mf[i_mf]), "s_peak_mf": float(slip[i_mf]),
            "mu_peak_law": float(mu_law[i_law]), "s_peak_law": float(slip[i_law])}
