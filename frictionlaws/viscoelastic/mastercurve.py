"""Master curves by time-temperature superposition, and WLF fitted to them.

Curves measured at several temperatures (friction against sliding velocity, or
a modulus against frequency) are shifted horizontally, in log10 of the
velocity or frequency, until they superpose on the curve at the reference
temperature.  The shift of each curve is log10 a_T (reduced variable
``a_T x``; positive below the reference temperature).  A WLF equation is then
fitted to the shifts, with standard errors.

How the shifts are found
------------------------
Neighbouring curves are shifted pairwise and the shifts chained outwards from
the reference curve.  Each curve is represented on log-log axes by a smooth
fit (a polynomial of degree 3 in log x by default, continued as a straight
line, i.e. a power law, for at most ``max_extrapolation`` decades beyond its
ends).  The shift d between two neighbours minimises the mean squared
difference of log y between each curve's points and the other curve's smooth
fit, over the points that fall in the (slightly extended) overlap; the
minimum is located on a fine grid and refined with a bounded scalar search.
The standard error of each pair shift comes from the curvature of that
mismatch at its minimum; along the chain the variances add.

Several properties measured at the same points (storage and loss modulus)
may be superposed together: pass ``y`` with one column per property.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..base.units import to_si
from ..fitting.lsq import lmfit_fit
from ..io import datasets_dir
from ..law import NUMPY
from .temperature import wlf_formula

__all__ = [
    "Curve",
    "WLFFit",
    "MasterCurve",
    "build_master_curve",
    "pair_shift",
    "fit_wlf",
    "load_dma_example",
    "load_dma_upstream_shifts",
]


@dataclass
class Curve:
    """One isothermal curve: ``y`` against ``x`` at temperature ``T`` [K].

    ``x`` is sorted ascending and positive; ``y`` is positive, shape (n,) or
    (n, k) for k properties measured at the same points.
    """

    T: float
    x: np.ndarray
    y: np.ndarray
    label: str = ""

    @property
    def u(self) -> np.ndarray:
        """log10 x."""
        return np.log10(self.x)

    @property
    def logy(self) -> np.ndarray:
        """log10 y as a 2-D array (n, k)."""
        y = np.log10(self.y)
        return y[:, None] if y.ndim == 1 else y


class _Smooth:
    """Polynomial in log x (per column of log y), continued linearly outside its range."""

    def __init__(self, u: np.ndarray, ly: np.ndarray, degree: int) -> None:
        deg = int(max(1, min(degree, u.size - 2)))
        self.lo, self.hi = float(u.min()), float(u.max())
        self.coef = [np.polyfit(u, ly[:, j], deg) for j in range(ly.shape[1])]
        self.dcoef = [np.polyder(c) if c.size > 1 else np.zeros(1) for c in self.coef]

    def __call__(self, u: np.ndarray) -> np.ndarray:
        uc = np.clip(u, self.lo, self.hi)
        cols = []
        for c, dc in zip(self.coef, self.dcoef):
            val = np.polyval(c, uc)
            val = val + np.where(u < self.lo, (u - self.lo) * np.polyval(dc, self.lo), 0.0)
            val = val + np.where(u > self.hi, (u - self.hi) * np.polyval(dc, self.hi), 0.0)
            cols.append(val)
        return np.column_stack(cols)


def _mismatch(a: Curve, sa: _Smooth, b: Curve, sb: _Smooth, d: float, ext: float,
              min_points: int) -> tuple[float, int]:
    """Mean squared log-y mismatch with b shifted by +d decades, and the point count."""
    ub = b.u + d
    mb = (ub >= sa.lo - ext) & (ub <= sa.hi + ext)
    ua = a.u - d
    ma = (ua >= sb.lo - ext) & (ua <= sb.hi + ext)
    n = int(mb.sum() + ma.sum())
    if n < min_points:
        return math.inf, n
    r = np.concatenate([(b.logy[mb] - sa(ub[mb])).ravel(), (a.logy[ma] - sb(ua[ma])).ravel()])
    return float(np.mean(r**2)), n


def pair_shift(a: Curve, b: Curve, *, degree: int = 3, max_extrapolation: float = 0.5,
               monotonic: bool = True, step: float = 0.02, min_points: int = 4
               ) -> tuple[float, float, float, int]:
    """Shift (decades of x) that superposes curve ``b`` on curve ``a``.

    Parameters
    ----------
    a, b : Curve
        The placed curve and the curve to shift.
    degree : int
        Degree of the smooth fit of log y against log x of each curve.
    max_extrapolation : float
        How far (decades) beyond a curve's ends its fit may be continued as a
        power law to compare with the other curve's points.
    monotonic : bool
        Enforce the physical direction: a warmer curve moves to lower reduced
        x (d <= 0), a colder one to higher (d >= 0).
    step : float
        Grid step of the initial scan [decades].
    min_points : int
        Minimum number of compared points for a candidate shift.

    Returns
    -------
    (d, stderr, rms, n)
        The shift of ``b`` relative to ``a``, its standard error, the rms
        mismatch of log10 y at the optimum and the number of compared points.

    Raises
    ------
    InputError
        When no shift gives an overlap of at least ``min_points`` points.
    """
    from scipy.optimize import minimize_scalar

    sa = _Smooth(a.u, a.logy, degree)
    sb = _Smooth(b.u, b.logy, degree)
    ext = float(max_extrapolation)
    lo = sa.lo - ext - sb.hi
    hi = sa.hi + ext - sb.lo
    if monotonic and b.T != a.T:
        if b.T > a.T:
            hi = min(hi, 0.0)
        else:
            lo = max(lo, 0.0)
    grid = np.arange(lo, hi + step / 2, step) if hi > lo else np.array([lo])
    vals = np.array([_mismatch(a, sa, b, sb, d, ext, min_points)[0] for d in grid])
    if not np.any(np.isfinite(vals)):
        raise InputError(
            f"the curves at {a.T:.2f} K and {b.T:.2f} K do not overlap (fewer than {min_points} "
            f"points even with {ext:g} decades of power-law extrapolation): measure an "
            "intermediate temperature or allow more extrapolation (max_extrapolation=...)")
    i = int(np.nanargmin(vals))
    a_lo, a_hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]

    def f(d: float) -> float:
        return _mismatch(a, sa, b, sb, d, ext, min_points)[0]

    d = float(grid[i])
    if a_hi > a_lo:
        res = minimize_scalar(f, bounds=(a_lo, a_hi), method="bounded",
                              options={"xatol": 1e-6})
        if np.isfinite(res.fun) and res.fun <= vals[i]:
            d = float(res.x)
    j, n = _mismatch(a, sa, b, sb, d, ext, min_points)
    # standard error from the curvature of SSE(d) = n J(d) at the minimum
    h = max(step, 1e-3)
    jp, jm = f(d + h), f(d - h)
    se = math.nan
    if np.isfinite(jp) and np.isfinite(jm) and n > 1:
        curv = n * (jp - 2 * j + jm) / h**2
        s2 = n * j / (n - 1)
        if curv > 0:
            se = math.sqrt(2.0 * s2 / curv)
    return d, se, math.sqrt(j), n


@dataclass
class WLFFit:
    """WLF constants fitted to shift factors.

    Attributes
    ----------
    C1, C2 : float
        Fitted constants (C2 in K).
    T_ref : float
        Reference temperature [K] (held fixed: log10 a_T(T_ref) = 0).
    C1_stderr, C2_stderr : float or None
        Standard errors (None when the fit could not estimate them).
    correlation : float or None
        Correlation of C1 and C2.
    rms : float
        rms residual of log10 a_T [decades].
    n : int
        Number of shift factors fitted.
    """

    C1: float
    C2: float
    T_ref: float
    C1_stderr: float | None
    C2_stderr: float | None
    correlation: float | None
    rms: float
    n: int
    messages: list[str] = field(default_factory=list)

    def log_aT(self, T: Any) -> Any:
        """log10 a_T of the fitted WLF equation at ``T`` [K] (NaN at or below the pole)."""
        T = np.asarray(T, dtype=float)
        out = np.where(T > self.T_ref - self.C2,
                       wlf_formula(NUMPY, T, self.C1, self.C2, self.T_ref), np.nan)
        return float(out) if out.ndim == 0 else out

    def to_dict(self) -> dict[str, Any]:
        """JSON-able summary with units."""
        return {"C1": self.C1, "C1_stderr": self.C1_stderr, "C2": self.C2,
                "C2_stderr": self.C2_stderr, "C2_unit": "K", "T_ref": self.T_ref,
                "T_ref_unit": "K", "correlation": self.correlation, "rms_decades": self.rms,
                "n": self.n, "messages": list(self.messages)}


def fit_wlf(T: Any, log_aT: Any, T_ref: float, *, stderr: Any = None) -> WLFFit:
    """Fit ``log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref)`` to shift factors with lmfit.

    Parameters
    ----------
    T : array-like
        Temperatures [K].
    log_aT : array-like
        Shift factors (log10), 0 at ``T_ref``.
    T_ref : float
        Reference temperature [K], held fixed.
    stderr : array-like, optional
        Standard errors of the shifts; used as weights when all are finite and
        positive (points at T_ref, with zero error, are left out).

    Returns
    -------
    WLFFit

    Notes
    -----
    Shifts chained from a reference curve are correlated (each one carries the
    errors of those between it and the reference); the standard errors of C1
    and C2 treat them as independent and are therefore approximate.
    """
    import lmfit

    T = np.asarray(T, float)
    y = np.asarray(log_aT, float)
    keep = np.abs(T - T_ref) > 1e-9
    T, y = T[keep], y[keep]
    w = None
    if stderr is not None:
        se = np.asarray(stderr, float)[keep]
        if np.all(np.isfinite(se)) and np.all(se > 0):
            w = 1.0 / se
    if T.size < 2:
        raise InputError("a WLF fit needs shift factors at two or more temperatures "
                         "besides the reference")
    dT = T - T_ref
    C1, C2 = _wlf_start(dT, y)

    def model(dT: np.ndarray, C1: float, C2: float) -> np.ndarray:
        return -C1 * dT / (C2 + dT)

    params = lmfit.Parameters()
    params.add("C1", value=C1, min=1e-3, max=1e3)
    params.add("C2", value=C2, min=float(-dT.min()) + 1e-6, max=1e5)
    res = lmfit_fit(lmfit.Model(model, independent_vars=["dT"]), y, params, dT=dT, weights=w)
    c1, c2 = res.params["C1"], res.params["C2"]
    corr = None
    if res.covar is not None:
        cv = np.asarray(res.covar)
        if cv[0, 0] > 0 and cv[1, 1] > 0:
            corr = float(cv[0, 1] / math.sqrt(cv[0, 0] * cv[1, 1]))
    rms = float(np.sqrt(np.mean((res.best_fit - y) ** 2)))
    msgs = _wlf_fit_messages(c1, c2, rms)
    return WLFFit(
        C1=float(c1.value), C2=float(c2.value), T_ref=float(T_ref),
        C1_stderr=None if c1.stderr is None else float(c1.stderr),
        C2_stderr=None if c2.stderr is None else float(c2.stderr),
        correlation=corr, rms=rms, n=int(T.size),
        messages=msgs)


def _wlf_start(dT: np.ndarray, y: np.ndarray) -> tuple[float, float]:
    """Starting C1, C2 [K] from the linearised form ``-dT / y = C2/C1 + dT/C1``.

    The universal constants (17.44, 51.6 K) when the line does not give positive
    values; C2 is kept clear of the pole at the lowest temperature.
    """
    ok = np.abs(y) > 0.05
    C1, C2 = 17.44, 51.6
    if np.count_nonzero(ok) >= 2:
        slope, icpt = np.polyfit(dT[ok], -dT[ok] / y[ok], 1)
        if slope > 0 and icpt / slope > 0:
            C1, C2 = 1.0 / slope, icpt / slope
    return C1, max(C2, float(-dT.min()) + 1.0)


def _wlf_fit_messages(c1: Any, c2: Any, rms: float) -> list[str]:
    """Warnings about a WLF fit: no standard errors, a constant at its bound, a poor fit."""
    msgs = []
    if c1.stderr is None or c2.stderr is None:
        msgs.append("the WLF fit could not estimate standard errors")
    for p in (c1, c2):
        tol = 1e-6 * max(abs(p.value), 1.0)
        if abs(p.value - p.min) < tol or abs(p.value - p.max) < tol:
            msgs.append(f"{p.name} = {p.value:g} is at its bound: the shifts do not follow WLF "
                        "over this temperature range")
    if rms > 0.2:
        msgs.append(f"the shifts deviate from the fitted WLF equation by {rms:.2f} decades rms: "
                    "WLF describes them poorly over this temperature range")
    return msgs


@dataclass
class MasterCurve:
    """The result of :func:`build_master_curve`.

    Attributes
    ----------
    curves : list of Curve
        The isothermal curves, by increasing temperature.
    T_ref : float
        Reference temperature [K]: the temperature of the reference curve.
    log_aT : numpy.ndarray
        log10 a_T of each curve (0 for the reference).
    stderr : numpy.ndarray
        Standard error of each shift (accumulated along the chain).
    pair_rms : numpy.ndarray
        rms mismatch of log10 y between each curve and its neighbour towards
        the reference (NaN for the reference).
    pair_points : numpy.ndarray
        Number of points compared for each pair shift.
    wlf : WLFFit or None
        WLF fitted to the shifts.
    x_name, y_names : str, list of str
        Names of the variables (for tables).
    messages : list of str
        Notes (reference chosen, extrapolation, WLF fit problems).
    """

    curves: list[Curve]
    T_ref: float
    log_aT: np.ndarray
    stderr: np.ndarray
    pair_rms: np.ndarray
    pair_points: np.ndarray
    wlf: WLFFit | None
    x_name: str = "x"
    y_names: list[str] = field(default_factory=lambda: ["y"])
    messages: list[str] = field(default_factory=list)

    @property
    def temperatures(self) -> np.ndarray:
        """Temperature of each curve [K]."""
        return np.array([c.T for c in self.curves])

    @property
    def reference_index(self) -> int:
        """Index of the reference curve."""
        return int(np.argmin(np.abs(self.temperatures - self.T_ref)))

    def points(self) -> dict[str, np.ndarray]:
        """The master-curve points, sorted by reduced x.

        Returns
        -------
        dict
            ``x_reduced`` (a_T x), ``log_x_reduced``, one entry per y name,
            ``T`` [K], ``x`` (as measured) and ``curve`` (index).
        """
        xs, ys, Ts, x0, idx = [], [], [], [], []
        for i, (c, s) in enumerate(zip(self.curves, self.log_aT)):
            xs.append(c.x * 10.0**s)
            ys.append(c.y if c.y.ndim == 2 else c.y[:, None])
            Ts.append(np.full(c.x.size, c.T))
            x0.append(c.x)
            idx.append(np.full(c.x.size, i))
        xr = np.concatenate(xs)
        order = np.argsort(xr, kind="stable")
        y = np.concatenate(ys)[order]
        out = {"x_reduced": xr[order], "log_x_reduced": np.log10(xr[order])}
        for j, name in enumerate(self.y_names):
            out[name] = y[:, j]
        out["T"] = np.concatenate(Ts)[order]
        out["x"] = np.concatenate(x0)[order]
        out["curve"] = np.concatenate(idx)[order]
        return out

    def to_frame(self) -> Any:
        """The master-curve points as a pandas DataFrame (units in the column names)."""
        import pandas as pd

        pts = self.points()
        df = pd.DataFrame(pts)
        return df.rename(columns={"x_reduced": f"{self.x_name}_reduced",
                                  "T": "T [K]", "x": self.x_name})

    def shift_table(self) -> list[dict[str, Any]]:
        """One row per curve: T [K], log10 a_T, its standard error, pair rms, WLF value."""
        rows = []
        for i, c in enumerate(self.curves):
            rows.append({
                "T [K]": c.T, "T [degC]": c.T - 273.15, "log_aT": float(self.log_aT[i]),
                "stderr": float(self.stderr[i]), "pair_rms": float(self.pair_rms[i]),
                "points": int(self.pair_points[i]),
                "log_aT_wlf": (float(self.wlf.log_aT(c.T)) if self.wlf is not None else None),
            })
        return rows

    def summary(self) -> dict[str, Any]:
        """JSON-able summary."""
        return {"T_ref": self.T_ref, "T_ref_unit": "K", "shifts": self.shift_table(),
                "wlf": None if self.wlf is None else self.wlf.to_dict(),
                "messages": list(self.messages)}


def _group(x: np.ndarray, y: np.ndarray, T: np.ndarray, groups: Any, T_tol: float
           ) -> list[Curve]:
    if groups is None:
        order = np.argsort(T, kind="stable")
        breaks = np.flatnonzero(np.diff(T[order]) > T_tol) + 1
        parts = np.split(order, breaks)
        labels = [f"T={T[p].mean() - 273.15:.1f} degC" for p in parts]
    else:
        g = np.asarray(groups)
        if g.shape[0] != x.shape[0]:
            raise InputError(f"groups has {g.shape[0]} values but x has {x.shape[0]}")
        keys = list(dict.fromkeys(g.tolist()))
        parts = [np.flatnonzero(g == k) for k in keys]
        labels = [str(k) for k in keys]
    curves = []
    for p, lab in zip(parts, labels):
        Tg = T[p]
        if np.ptp(Tg) > 2 * T_tol:
            raise InputError(f"curve '{lab}' spans {np.ptp(Tg):.2f} K of temperature; a curve "
                             "must be (nearly) isothermal")
        o = p[np.argsort(x[p], kind="stable")]
        curves.append(Curve(float(np.mean(Tg)), x[o], y[o], lab))
    curves.sort(key=lambda c: c.T)
    return curves


def build_master_curve(
    x: Any,
    y: Any,
    T: Any,
    *,
    groups: Any = None,
    T_ref: float | None = None,
    degree: int = 3,
    max_extrapolation: float = 0.5,
    monotonic: bool = True,
    T_tol: float = 2.0,
    fit: bool = True,
    x_name: str = "x",
    y_names: Sequence[str] | None = None,
) -> MasterCurve:
    """Shift isothermal curves onto a master curve and fit WLF to the shifts.

    Parameters
    ----------
    x : array-like
        Sliding velocity [m/s] or frequency [Hz] (any positive variable whose
        log is shifted), one value per point.
    y : array-like
        The property (friction coefficient, modulus...), positive; shape (n,)
        or (n, k) for k properties sharing the shifts.
    T : array-like
        Temperature of each point [K].
    groups : array-like, optional
        Curve label of each point; by default points are grouped by
        temperature (a new curve where sorted temperatures jump by more than
        ``T_tol``).
    T_ref : float, optional
        Reference temperature [K]; the curve nearest to it is the reference
        (default: the middle curve).
    degree : int
        Degree of each curve's smooth fit in log-log.
    max_extrapolation : float
        Decades a curve's fit may be continued beyond its ends.
    monotonic : bool
        Enforce that colder curves move to higher reduced x.
    T_tol : float
        Grouping tolerance [K].
    fit : bool
        Fit WLF to the shifts.
    x_name : str
        Name of ``x`` in tables.
    y_names : sequence of str, optional
        Name of each property in ``y`` (one per column).

    Returns
    -------
    MasterCurve
        The curves by increasing temperature, the reference temperature [K],
        each curve's shift log10 a_T with its standard error and pair mismatch,
        the WLF fit to the shifts (None when ``fit`` is false or the WLF fit
        failed) and messages about the reference, extrapolation and WLF fit.

    Raises
    ------
    InputError
        Non-positive or non-finite values, fewer than two curves, curves
        with fewer than three points, or neighbours that cannot be overlapped.
    """
    x, y, T = _checked_points(x, y, T)
    curves = _group(x, y, T, groups, T_tol)
    if len(curves) < 2 or min(c.x.size for c in curves) < 3:
        small = [c.label for c in curves if c.x.size < 3]
        raise InputError(f"curves {small} have fewer than 3 points" if small else
                         "a master curve needs curves at two or more temperatures "
                         f"(found {len(curves)})")
    names = _y_names(y, y_names)
    temps = np.array([c.T for c in curves])
    messages: list[str] = []
    ref = _reference_curve(temps, T_ref, T_tol, messages)
    shift, se, rms, pts = _chain_shifts(curves, ref, degree=degree,
                                        max_extrapolation=max_extrapolation,
                                        monotonic=monotonic)
    wlf = _wlf_or_message(temps, shift, float(temps[ref]), se, messages) if fit else None
    return MasterCurve(curves, float(temps[ref]), shift, se, rms, pts, wlf, x_name, names,
                       messages)


def _reference_curve(temps: np.ndarray, T_ref: float | None, T_tol: float,
                     messages: list[str]) -> int:
    """Index of the reference curve: nearest to ``T_ref`` [K], else the middle one."""
    if T_ref is None:
        return len(temps) // 2
    ref = int(np.argmin(np.abs(temps - T_ref)))
    if abs(temps[ref] - T_ref) > T_tol:
        messages.append(f"no curve at T_ref = {T_ref:.2f} K: the shifts are referred to the "
                        f"nearest curve, at {temps[ref]:.2f} K")
    return ref


def _wlf_or_message(temps: np.ndarray, shift: np.ndarray, T_ref: float, se: np.ndarray,
                    messages: list[str]) -> WLFFit | None:
    """Fit WLF to the shifts; a failure becomes a message, not an error."""
    try:
        wlf = fit_wlf(temps, shift, T_ref, stderr=se)
    except (InputError, ValueError) as exc:
        messages.append(f"WLF fit failed: {exc}")
        return None
    messages.extend(wlf.messages)
    return wlf


def _y_names(y: np.ndarray, y_names: Sequence[str] | None) -> list[str]:
    k = 1 if y.ndim == 1 else y.shape[1]
    names = list(y_names) if y_names is not None else (["y"] if k == 1 else
                                                        [f"y{j}" for j in range(k)])
    if len(names) != k:
        raise InputError(f"{len(names)} y_names for {k} y columns")
    return names


def _checked_points(x: Any, y: Any, T: Any) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """x, y, T as float arrays: one value per point, finite, x and y positive, T in K."""
    x = np.asarray(x, dtype=float).ravel()
    y = np.asarray(y, dtype=float)
    T = np.asarray(T, dtype=float).ravel()
    if y.shape[0] != x.size or T.size != x.size:
        raise InputError(f"x, y and T must have one value per point (got {x.size}, "
                         f"{y.shape[0]}, {T.size})")
    for name, arr in (("x", x), ("y", y), ("T", T)):
        bad = ~np.isfinite(arr)
        if bad.any():
            rows = np.flatnonzero(bad.reshape(arr.shape[0], -1).any(axis=1))
            raise InputError(f"{name} has non-finite values at points {rows[:5].tolist()}")
    for name, arr in (("x", x), ("y", y)):
        bad = arr <= 0
        if bad.any():
            rows = np.flatnonzero(bad.reshape(arr.shape[0], -1).any(axis=1))
            raise InputError(f"{name} must be positive (its log is used); non-positive at "
                             f"points {rows[:5].tolist()}")
    if np.any(T <= 0):
        raise InputError("T must be an absolute temperature in K (> 0)")
    return x, y, T


def _chain_shifts(curves: list[Curve], ref: int, *, degree: int, max_extrapolation: float,
                  monotonic: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Shift each curve onto its neighbour towards the reference, accumulating the shifts.

    Returns log10 shifts, their standard errors (variances of the chained pair shifts
    add), the pair rms mismatch and the number of overlapping points of each pair.
    """
    n = len(curves)
    shift = np.zeros(n)
    var = np.zeros(n)
    rms = np.full(n, np.nan)
    pts = np.zeros(n, dtype=int)
    for i in list(range(ref + 1, n)) + list(range(ref - 1, -1, -1)):
        j = i - 1 if i > ref else i + 1
        d, se, r, m = pair_shift(curves[j], curves[i], degree=degree,
                                 max_extrapolation=max_extrapolation, monotonic=monotonic)
        shift[i] = shift[j] + d
        var[i] = var[j] + (se**2 if np.isfinite(se) else np.nan)
        rms[i], pts[i] = r, m
    return shift, np.sqrt(var), rms, pts


# ------------------------------------------------------------------ packaged DMA data


def _dma_path(name: str) -> Any:
    return datasets_dir() / "dma-pyvisco" / name


def _read_two_header_csv(name: str) -> tuple[list[str], list[str], np.ndarray]:
    text = _dma_path(name).read_text(encoding="utf-8-sig")
    lines = [ln for ln in text.splitlines() if ln.strip()]
    names = [s.strip() for s in lines[0].split(",")]
    units = [s.strip() for s in lines[1].split(",")]
    try:
        data = np.array([[float(v) for v in ln.split(",")] for ln in lines[2:]])
    except ValueError as exc:
        raise InputError(f"non-numeric value ({exc})", file=f"dma-pyvisco/{name}") from None
    return names, units, data


def _unit(u: str) -> str:
    # the upstream files write 'C' for degrees Celsius (pint reads 'C' as the coulomb)
    return "degC" if u == "C" else u


def load_dma_example() -> dict[str, np.ndarray]:
    """The packaged DMA frequency sweeps (NREL pyvisco example, BSD-3-Clause).

    Returns
    -------
    dict of numpy.ndarray
        ``f`` [Hz], ``E_stor`` and ``E_loss`` [Pa], ``T`` [K], ``set`` (sweep
        number): 21 temperatures from -50 to 100 degC, 10 frequencies each.
    """
    names, units, data = _read_two_header_csv("freq_user_raw.csv")
    kinds = {"f": "frequency", "E_stor": "p", "E_loss": "p", "T": "T"}
    out: dict[str, np.ndarray] = {}
    for j, (nm, un) in enumerate(zip(names, units)):
        if nm in kinds:
            out[nm] = to_si(data[:, j], _unit(un), kinds[nm], column=nm,
                            file="dma-pyvisco/freq_user_raw.csv")
        elif nm == "Set":
            out["set"] = data[:, j].astype(int)
    return out


def load_dma_upstream_shifts() -> dict[str, np.ndarray]:
    """The shift factors shipped beside the DMA sweeps: ``T`` [K] and ``log_aT``."""
    names, units, data = _read_two_header_csv("freq_user_master__shift_factors.csv")
    iT, ia = names.index("T"), names.index("log_aT")
    return {"T": to_si(data[:, iT], _unit(units[iT]), "T",
                       file="dma-pyvisco/freq_user_master__shift_factors.csv"),
            "log_aT": data[:, ia]}
