"""How does a law behave outside the data it was fitted to?

Two checks answer that.

**Holdout of the upper range** (:func:`holdout_splits`, :func:`score_holdout`).
For each variable that varies over at least three distinct values (pressure
and velocity by default), the rows in the upper ``fraction`` of its measured
*range* (``x > x_min + (1 - fraction) (x_max - x_min)``) are held out; the law
is fitted on the remaining rows and scored on the held-out ones.  This is what
an engineer does when a tyre's contact pressure exceeds the tribometer's.

**Plausibility scan over an extended box** (:func:`extended_box`,
:func:`scan_plausibility`).  The fully fitted law is evaluated on a grid over
a box wider than the data: half the lowest to three times the highest measured
value of ``p``, ``v`` and ``F_N``; ``s`` likewise but capped at 1; ``T`` from
20 K below to 20 K above the measured range (halving a temperature in kelvin
means nothing).  ``v = 0`` is evaluated as the law defines it (singular laws
at their floor ``V_MIN``, as the FE exporters do).  A law is flagged as
implausible, with a reason naming where, when

* mu is not finite somewhere in the box (it blows up),
* mu leaves the physical limits, by default ``0 <= mu <= 5``: a friction
  coefficient is not negative, and 5 is well above the highest rubber-on-steel
  values measured (about 3.7 in the source thesis), so a law exceeding it is
  extrapolating, not describing rubber,
* beyond an end of the measured range of a variable, mu moves against the
  trend the data show toward that end, by more than 5 % of its value where
  the reversal starts and at least 0.02 (:data:`TREND_REL`,
  :data:`TREND_TOL`: below the scatter of repeated tribometer tests, so a law
  that merely levels off is not flagged).  Inside the measured range the data
  themselves judge the law (residual tests), so only the extensions are
  checked.

The trend the data show is established by a **stratified Kendall test**
(:func:`data_trend`, the "seasonal" Mann-Kendall test of Hirsch, Slack and
Smith, 1982): the rows are grouped by the values of the other variables (more
than eight distinct values are binned into quartiles), Kendall's S statistic
of mu against the variable is summed over the groups together with its
tie-corrected variance, and the trend counts as shown when the two-sided
p-value is below 0.05.  Without a clear trend no sign is imposed.  Toward each
end of the range the half of the data nearest that end decides when its own
trend is significant (the nearest quarter, third or half of the measured
values: a peaked curve may rise at one end and fall at the other).  Comparing
within groups matters: in the thesis data the 2.77 m/s row was measured only
at the lowest pressure, so pooling all rows would mix the pressure effect into
the velocity trend.

Variables that are a linear function of another in the data (``F_N = A p``
with a fixed pin) are not independent: they follow their driver (``p``) in the
box, are not held out separately and get no trend test of their own.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.errors import DomainError, InputError
from ..base.numbers import parse_number
from ..base.units import display_unit, to_display
from ..fitting import FitData, FitResult
from ..law import VARIABLES, Law
from .cv import error_text, refit, undetermined_rows

__all__ = ["MU_LIMITS", "TREND_TOL", "TREND_REL", "TREND_ALPHA", "Design", "design_of", "Trend",
           "data_trend", "data_trends", "extended_box", "Split", "holdout_splits",
           "HoldoutResult", "score_holdout", "Plausibility", "scan_plausibility",
           "fmt_value", "parse_holdout", "evaluate_on", "DEFAULT_HOLDOUT"]

#: Physical limits of the friction coefficient used by the plausibility scan.
MU_LIMITS = (0.0, 5.0)
#: Change of mu against the data's trend that counts as a reversal: more than
#: TREND_REL of mu where the reversal starts, and at least TREND_TOL.
TREND_TOL = 0.02
TREND_REL = 0.05
#: Significance level of the stratified Kendall test for the data's trend.
TREND_ALPHA = 0.05
#: Correlation above which one variable is taken as a linear function of another.
COLLINEAR_R = 0.999
#: Default holdout: the upper 30 % of the pressure and velocity ranges.
DEFAULT_HOLDOUT = {"p": 0.3, "v": 0.3}
#: Grid points in the plausibility box (all dimensions together, roughly).
GRID_POINTS = 60_000


def fmt_value(var: str, x: float) -> str:
    """``x`` (SI) in the variable's display unit, with the unit."""
    if var == "mu":
        return f"{x:.3g}"
    unit = display_unit(var)
    value = float(to_display(x, var))
    return f"{value:.4g} {unit}" if unit else f"{value:.4g}"


# ---------------------------------------------------------------- design


@dataclass
class Design:
    """Which variables of a dataset vary, and which follow another one.

    ``varying``: independent variables with at least two distinct values;
    ``derived``: variable -> (driver, intercept, slope) for variables that are
    a linear function of an earlier one; ``constant``: variable -> its single
    value.
    """

    varying: list[str]
    derived: dict[str, tuple[str, float, float]]
    constant: dict[str, float]

    def complete(self, values: Mapping[str, Any]) -> dict[str, Any]:
        """Add derived variables computed from their drivers (and the constants)."""
        out = dict(values)
        for k, c in self.constant.items():
            out.setdefault(k, c)
        for k, (drv, a, b) in self.derived.items():
            if k not in out and drv in out:
                out[k] = a + b * np.asarray(out[drv], float)
        return out

    def to_dict(self) -> dict[str, Any]:
        return {"varying": list(self.varying),
                "derived": {k: {"follows": d, "intercept": a, "slope": b}
                            for k, (d, a, b) in self.derived.items()},
                "constant": dict(self.constant)}


def design_of(data: FitData) -> Design:
    """The :class:`Design` of ``data`` (variables in :data:`VARIABLES` order)."""
    varying: list[str] = []
    derived: dict[str, tuple[str, float, float]] = {}
    constant: dict[str, float] = {}
    for var in VARIABLES:
        if var not in data.arrays:
            continue
        x = data.arrays[var]
        if np.unique(x).size < 2:
            constant[var] = float(x[0])
            continue
        for drv in varying:
            d = data.arrays[drv]
            r = np.corrcoef(d, x)[0, 1]
            if np.isfinite(r) and abs(r) >= COLLINEAR_R:
                b, a = np.polyfit(d, x, 1)
                derived[var] = (drv, float(a), float(b))
                break
        else:
            varying.append(var)
    return Design(varying, derived, constant)


# ----------------------------------------------------------------- trends


@dataclass
class Trend:
    """The monotone trend of mu along one variable, as the data show it.

    ``sign`` is the trend over all the data (+1 rising, -1 falling, 0 no
    clear trend); ``ends`` holds, for ``"low"`` and ``"high"``, the sign the
    plausibility scan expects beyond that end of the measured range and
    where it comes from (see :func:`data_trend`).
    """

    variable: str
    sign: int
    s: float
    var_s: float
    p_value: float | None
    strata: int
    pairs: int
    sen_slope: float | None
    ends: dict[str, dict[str, Any]] = field(default_factory=dict)

    @property
    def word(self) -> str:
        return _WORD[self.sign]

    def describe(self) -> str:
        if self.p_value is None:
            return f"no trend test along {self.variable} (no pairs of rows differing only in it)"
        what = (f"mu {'rises' if self.sign > 0 else 'falls'} with {self.variable}"
                if self.sign else f"no clear trend of mu with {self.variable}")
        text = (f"{what} (stratified Kendall S = {self.s:+.0f} over {self.strata} groups, "
                f"p = {self.p_value:.2g})")
        local = [f"toward the {'lowest' if k == 'low' else 'highest'} {self.variable}: "
                 f"{_WORD[e['sign']]} ({e['basis']})"
                 for k, e in self.ends.items() if e["sign"] != self.sign]
        return text + ("; " + "; ".join(local) if local else "")

    def to_dict(self) -> dict[str, Any]:
        return {"variable": self.variable, "sign": self.sign, "trend": self.word,
                "kendall_s": self.s, "var_s": self.var_s, "p_value": self.p_value,
                "strata": self.strata, "pairs": self.pairs, "sen_slope": self.sen_slope,
                "sen_slope_unit": f"1/{VARIABLES[self.variable].unit}"
                if VARIABLES[self.variable].unit else "-",
                "ends": self.ends, "description": self.describe()}


_WORD = {1: "rising", -1: "falling", 0: "no clear trend"}


def _ties(x: np.ndarray) -> np.ndarray:
    _, counts = np.unique(x, return_counts=True)
    return counts[counts > 1].astype(float)


def _kendall_s_var(x: np.ndarray, y: np.ndarray) -> tuple[float, float, int]:
    """Kendall's S of ``y`` against ``x`` and its variance with ties in both."""
    n = x.size
    if n < 2:
        return 0.0, 0.0, 0
    iu = np.triu_indices(n, 1)
    dx = np.sign(x[iu[1]] - x[iu[0]])
    dy = np.sign(y[iu[1]] - y[iu[0]])
    s = float(np.sum(dx * dy))
    t, u = _ties(x), _ties(y)
    var = (n * (n - 1) * (2 * n + 5) - np.sum(t * (t - 1) * (2 * t + 5))
           - np.sum(u * (u - 1) * (2 * u + 5))) / 18.0
    var += np.sum(t * (t - 1)) * np.sum(u * (u - 1)) / (2.0 * n * (n - 1))
    if n > 2:
        var += (np.sum(t * (t - 1) * (t - 2)) * np.sum(u * (u - 1) * (u - 2))
                / (9.0 * n * (n - 1) * (n - 2)))
    return s, float(var), int(np.count_nonzero(dx))


def _strata_keys(data: FitData, columns: list[str], binned: bool) -> np.ndarray:
    """One integer group label per row from the values of ``columns``.

    With ``binned``, columns with more than eight distinct values are cut into
    quartile bins (for scattered, non-gridded data).
    """
    if not columns:
        return np.zeros(data.n, dtype=int)
    parts = []
    for c in columns:
        x = data.arrays[c]
        if binned and np.unique(x).size > 8:
            edges = np.quantile(x, [0.25, 0.5, 0.75])
            parts.append(np.searchsorted(edges, x, side="right"))
        else:
            parts.append(np.unique(x, return_inverse=True)[1].ravel())
    return np.unique(np.column_stack(parts), axis=0, return_inverse=True)[1].ravel()


#: Parts of the measured values (nearest an end) whose trend is tried for that end.
END_FRACTIONS = (0.25, 1 / 3, 0.5)
#: Fewest within-group pairs for the exact grouping; below it, quartile bins are used.
MIN_PAIRS = 5


def _kendall(data: FitData, var: str, design: Design, rows: np.ndarray,
             continuity: bool) -> tuple[float, float, float | None, int, int, float | None]:
    """Stratified Kendall S, its variance, p-value, strata, pairs and Sen slope on ``rows``."""
    from scipy import stats

    others = [k for k in design.varying if k != var]
    x, y = data.arrays[var], data.arrays["mu"]

    def collect(keys: np.ndarray) -> tuple[float, float, int, int, list[np.ndarray]]:
        s_tot, v_tot, pairs, strata = 0.0, 0.0, 0, 0
        slopes = []
        for g in np.unique(keys[rows]):
            m = rows & (keys == g)
            if np.unique(x[m]).size < 2:
                continue
            s, v, npair = _kendall_s_var(x[m], y[m])
            s_tot, v_tot, pairs, strata = s_tot + s, v_tot + v, pairs + npair, strata + 1
            xi, yi = x[m], y[m]
            iu = np.triu_indices(xi.size, 1)
            dx = xi[iu[1]] - xi[iu[0]]
            ok = dx != 0
            slopes.append((yi[iu[1]] - yi[iu[0]])[ok] / dx[ok])
        return s_tot, v_tot, pairs, strata, slopes

    s_tot, v_tot, pairs, strata, slopes = collect(_strata_keys(data, others, binned=False))
    if pairs < MIN_PAIRS and others:
        s_tot, v_tot, pairs, strata, slopes = collect(_strata_keys(data, others, binned=True))
    if v_tot <= 0:
        return s_tot, v_tot, None, strata, pairs, None
    cc = (1.0 if s_tot > 0 else -1.0 if s_tot < 0 else 0.0) if continuity else 0.0
    z = (s_tot - cc) / math.sqrt(v_tot)
    p = float(2.0 * stats.norm.sf(abs(z)))
    sen = float(np.median(np.concatenate(slopes))) if slopes else None
    return s_tot, v_tot, p, strata, pairs, sen


def data_trend(data: FitData, var: str, design: Design, *,
               continuity: bool = True) -> Trend:
    """Stratified Kendall test of the trend of mu along ``var`` (module docstring).

    Rows are grouped by the exact values of the other varying variables (a
    gridded experiment); when that leaves fewer than :data:`MIN_PAIRS` pairs
    of rows to compare (scattered data), variables with more than eight
    distinct values are binned into quartiles instead.

    The sign expected beyond each end of the measured range (``Trend.ends``)
    is the trend of the rows nearest that end (the nearest quarter, third or
    half of the measured values, the first that is significant on its own: a
    peaked curve rises at its low end and falls at its high end); otherwise
    the overall trend, unless the rows near that end point the other way (then
    no sign is imposed there).
    """
    every = np.ones(data.n, dtype=bool)
    s_tot, v_tot, p, strata, pairs, sen = _kendall(data, var, design, every, continuity)
    if p is None:
        return Trend(var, 0, s_tot, v_tot, None, strata, pairs, None,
                     {k: {"sign": 0, "p_value": None, "basis": "no pairs to compare"}
                      for k in ("low", "high")})
    sign = int(np.sign(s_tot)) if p < TREND_ALPHA else 0
    x = data.arrays[var]
    levels = np.unique(x)
    n_lev = levels.size
    ends: dict[str, dict[str, Any]] = {}
    for end in ("low", "high"):
        chosen = last = None
        seen: set[int] = set()
        for frac in END_FRACTIONS:
            k = max(2, math.ceil(frac * n_lev))
            if k in seen or k >= n_lev:
                continue
            seen.add(k)
            near = x <= levels[k - 1] if end == "low" else x >= levels[n_lev - k]
            ls, _, lp, _, _, _ = _kendall(data, var, design, near, continuity)
            name = (f"the {'lowest' if end == 'low' else 'highest'} {k} of the {n_lev} "
                    f"measured {var} values")
            last = (ls, lp, name)
            if lp is not None and lp < TREND_ALPHA and ls != 0:
                chosen = {"sign": int(np.sign(ls)), "p_value": lp,
                          "basis": f"stratified Kendall p = {lp:.2g} over {name}"}
                break
        if chosen is not None:
            ends[end] = chosen
        elif sign != 0 and (last is None or last[1] is None or np.sign(last[0]) in (0, sign)):
            ends[end] = {"sign": sign, "p_value": p,
                         "basis": f"stratified Kendall p = {p:.2g} over all the data"}
        else:
            ends[end] = {"sign": 0, "p_value": None if last is None else last[1],
                         "basis": "no clear trend" + (f" ({last[2]} point the other way)"
                                                       if sign and last else "")}
    return Trend(var, sign, s_tot, v_tot, p, strata, pairs, sen, ends)


def data_trends(data: FitData, design: Design) -> dict[str, Trend]:
    """:func:`data_trend` for every independent varying variable."""
    return {v: data_trend(data, v, design) for v in design.varying}


# -------------------------------------------------------------------- box


def extended_box(data: FitData, design: Design) -> dict[str, tuple[float, float]]:
    """The extended box of the plausibility scan (SI; see the module docstring)."""
    box: dict[str, tuple[float, float]] = {}
    for var in [*design.varying, *design.constant]:
        x = data.arrays[var]
        lo, hi = float(np.min(x)), float(np.max(x))
        if var == "T":
            box[var] = (lo - 20.0, hi + 20.0)
        elif var == "s":
            box[var] = (0.5 * lo, min(1.0, 3.0 * hi) if hi > 0 else 1.0)
        else:
            box[var] = (0.5 * lo, 3.0 * hi) if hi > 0 else (0.5 * lo, 0.0)
    return box


def _axis(data: FitData, var: str, lo: float, hi: float, n: int) -> np.ndarray:
    """Grid of one variable: linear and geometric points, the measured values' ends."""
    if hi <= lo:
        return np.array([lo])
    x = data.arrays[var]
    pts = [np.linspace(lo, hi, n)]
    pos = x[x > 0]
    glo = lo if lo > 0 else (0.5 * float(pos.min()) if pos.size else hi * 1e-3)
    if var != "T" and 0 < glo < hi:
        pts.append(np.geomspace(glo, hi, n))
    pts.append(np.array([float(x.min()), float(x.max())]))
    return np.unique(np.concatenate(pts))


# ---------------------------------------------------------------- holdout


def _holdout_items(text: str) -> dict[str, Any]:
    """``"p=0.3,v=0.2"`` -> ``{"p": "0.3", "v": "0.2"}`` (each variable once)."""
    items: dict[str, Any] = {}
    for part in text.split(","):
        if not part.strip():
            continue
        if "=" not in part:
            raise InputError(f"expected FRACTION or VAR=FRACTION,..., "
                             f"got '{part.strip()}'", option="holdout")
        k, v = (s.strip() for s in part.split("=", 1))
        if k in items:
            raise InputError(f"'{k}' is given twice ({items[k]} and {v}); give each "
                             "variable once", option="holdout")
        items[k] = v
    return items


def _holdout_fraction(k: str, v: Any) -> float:
    """The checked fraction of variable ``k`` (0 means no holdout along it)."""
    if k not in VARIABLES:
        raise InputError(f"unknown variable '{k}' (known: {', '.join(VARIABLES)})",
                         option="holdout")

    try:  # text through the one number parser (no 0_3, no non-ASCII digits, no nan)
        f = parse_number(v) if isinstance(v, str) else float(v)
    except (TypeError, ValueError):
        raise InputError(f"'{k}={v}' is not a number", option="holdout") from None
    if not math.isfinite(f):
        raise InputError(f"'{k}={v}' is not a finite number", option="holdout")
    if f != 0 and not 0 < f < 1:
        raise InputError(f"the fraction for {k} must be between 0 and 1 "
                         f"(exclusive), not {f:g}", option="holdout")
    return f


def parse_holdout(spec: Any) -> dict[str, float]:
    """Holdout fractions from ``0.3``, ``"0.3"``, ``"p=0.3,v=0.2"``, a mapping, or None/0.

    A single fraction applies to pressure and velocity.

    Parameters
    ----------
    spec : float, str, mapping or None
        The holdout as given.

    Returns
    -------
    dict of str to float
        Variable -> fraction of its range held out (variables with 0 left out).
    """
    if spec is None:
        return {}
    if isinstance(spec, Mapping):
        items = {str(k): v for k, v in spec.items()}
    elif isinstance(spec, (int, float)):
        items = {k: spec for k in DEFAULT_HOLDOUT}
    else:
        text = str(spec).strip()
        if text.lower() in ("", "none", "0", "off"):
            return {}
        items = _holdout_items(text) if "=" in text else {k: text for k in DEFAULT_HOLDOUT}
    fractions = {k: _holdout_fraction(k, v) for k, v in items.items()}
    return {k: f for k, f in fractions.items() if f != 0}


@dataclass
class Split:
    """One holdout split: rows with ``variable > threshold`` are held out."""

    variable: str
    fraction: float
    threshold: float | None
    test: np.ndarray | None
    reason: str | None = None

    @property
    def usable(self) -> bool:
        return self.reason is None

    def describe(self) -> str:
        if self.reason or self.test is None or self.threshold is None:
            return f"{self.variable}: not held out ({self.reason})"
        n = int(self.test.sum())
        return (f"{self.variable} > {fmt_value(self.variable, self.threshold)} "
                f"(upper {self.fraction:.0%} of the range, {n} row{'s' if n != 1 else ''})")

    def to_dict(self) -> dict[str, Any]:
        return {"variable": self.variable, "fraction": self.fraction,
                "threshold": self.threshold,
                "threshold_unit": VARIABLES[self.variable].unit or "-",
                "n_test": None if self.test is None else int(self.test.sum()),
                "skipped": self.reason, "description": self.describe()}


def holdout_splits(data: FitData, fractions: Mapping[str, float],
                   design: Design) -> list[Split]:
    """The holdout splits for ``fractions`` (variable -> fraction of the range)."""
    out = []
    for var, f in fractions.items():
        if var not in data.arrays:
            out.append(Split(var, f, None, None, f"the data have no {var}"))
            continue
        if var in design.derived:
            drv = design.derived[var][0]
            out.append(Split(var, f, None, None, f"{var} follows {drv} in these data; the "
                                                 f"{drv} holdout covers it"))
            continue
        x = data.arrays[var]
        levels = np.unique(x)
        if levels.size < 3:
            out.append(Split(var, f, None, None, f"{var} takes only {levels.size} distinct "
                                                 "value(s); at least 3 are needed to fit "
                                                 "below and score above"))
            continue
        lo, hi = float(levels[0]), float(levels[-1])
        thr = lo + (1.0 - f) * (hi - lo)
        test = x > thr * (1 + 1e-12) + 1e-300
        train_levels = np.unique(x[~test])
        if not test.any():
            out.append(Split(var, f, thr, None, f"no rows above {fmt_value(var, thr)}"))
        elif train_levels.size < 2:
            out.append(Split(var, f, thr, None, f"fewer than 2 distinct values of {var} "
                                                f"below {fmt_value(var, thr)}"))
        else:
            out.append(Split(var, f, thr, test))
    return out


@dataclass
class HoldoutResult:
    """A law fitted below a split's threshold and scored above it.

    ``rmse`` is NaN when there is no score: the fit failed (``error``), a held-out
    prediction depends on parameters the rows below the threshold cannot determine
    (``n_undetermined`` rows; :func:`~frictionlaws.comparison.cv.undetermined_rows`),
    or a held-out prediction lies outside the plausible range of mu (``implausible``
    says where): a friction coefficient below 0 or above the comparison's upper limit is
    a failure of the extrapolation, not an error to average with the others.
    """

    variable: str
    n_train: int
    n_test: int
    rmse: float
    max_abs: float
    fit: FitResult | None = None
    predictions: np.ndarray | None = None
    test: np.ndarray | None = None
    error: str | None = None
    n_undetermined: int = 0
    implausible: str | None = None

    @property
    def status(self) -> str:
        """``"scored"``, ``"error"``, ``"undetermined"`` or ``"implausible"``."""
        if self.error is not None:
            return "error"
        if self.n_undetermined:
            return "undetermined"
        return "implausible" if self.implausible else "scored"

    def to_dict(self) -> dict[str, Any]:
        return {"variable": self.variable, "n_train": self.n_train, "n_test": self.n_test,
                "rmse": self.rmse, "max_abs_error": self.max_abs, "error": self.error,
                "status": self.status, "n_undetermined": self.n_undetermined,
                "implausible": self.implausible,
                "params": None if self.fit is None else self.fit.param_values,
                "undetermined": [] if self.fit is None else list(self.fit.non_identifiable)}


def _implausible(law: Law, data: FitData, test: np.ndarray, pred: np.ndarray,
                 limits: tuple[float, float]) -> str | None:
    """Where the held-out predictions leave ``limits`` (the worst one), or None."""
    bad = (pred < limits[0]) | (pred > limits[1])
    if not bad.any():
        return None
    dev = np.where(pred < limits[0], limits[0] - pred, pred - limits[1])
    i = int(np.argmax(np.where(bad, dev, -np.inf)))
    row = int(np.flatnonzero(test)[i])
    at = ", ".join(f"{k} = {fmt_value(k, float(data.arrays[k][row]))}"
                   for k in law.variables if k in data.arrays)
    return (f"predicts mu outside the plausible range {limits[0]:g} .. {limits[1]:g} at "
            f"{int(bad.sum())} of {pred.size} held-out rows (mu = {pred[i]:.3g} at {at})")


def score_holdout(law: Law, data: FitData, usable: np.ndarray, split: Split, *,
                  fit_kwargs: Mapping[str, Any] | None = None,
                  limits: tuple[float, float] = MU_LIMITS) -> HoldoutResult:
    """Fit ``law`` on the usable rows below the split and score the usable rows above.

    The score is withheld (see :class:`HoldoutResult`) when a held-out prediction is
    undetermined or outside ``limits``, the plausible range of mu.
    """
    if split.test is None:
        raise InputError(f"the holdout along {split.variable} is not usable: {split.reason}")
    test = usable & split.test
    train = usable & ~split.test
    n_tr, n_te = int(train.sum()), int(test.sum())
    if n_te == 0:
        return HoldoutResult(split.variable, n_tr, 0, math.nan, math.nan, test=test,
                             error="no held-out rows this law can be evaluated on")
    try:
        res = refit(law, data.subset(train), fit_kwargs)
    except Exception as exc:  # noqa: BLE001 - a law may fail in any way; report it
        return HoldoutResult(split.variable, n_tr, n_te, math.nan, math.nan, test=test,
                             error=error_text(exc))
    xs = {k: data.arrays[k][test] for k in law.variables if k in data.arrays}
    with np.errstate(all="ignore"):
        pred = np.array(np.broadcast_to(np.asarray(law.evaluate(xs, res.values), float),
                                        (n_te,)))
    err = data.arrays["mu"][test] - pred
    if not np.all(np.isfinite(err)):
        return HoldoutResult(split.variable, n_tr, n_te, math.inf, math.inf, res, pred, test,
                             "the law fitted below the threshold predicts non-finite mu "
                             "above it")
    und = int(undetermined_rows(law, res, data.subset(train), xs, n_te).sum())
    odd = _implausible(law, data, test, pred, limits)
    if und or odd:
        return HoldoutResult(split.variable, n_tr, n_te, math.nan, math.nan, res, pred, test,
                             n_undetermined=und, implausible=odd)
    return HoldoutResult(split.variable, n_tr, n_te, float(np.sqrt(np.mean(err**2))),
                         float(np.max(np.abs(err))), res, pred, test)


# ----------------------------------------------------------- plausibility


@dataclass
class Flag:
    """One reason a law is implausible, with where it happens (SI)."""

    kind: str
    message: str
    variable: str | None = None
    at: dict[str, float] = field(default_factory=dict)
    to: dict[str, float] = field(default_factory=dict)
    mu: tuple[float, float] | None = None

    def to_dict(self) -> dict[str, Any]:
        return {"kind": self.kind, "message": self.message, "variable": self.variable,
                "at": self.at, "to": self.to, "mu": list(self.mu) if self.mu else None}


@dataclass
class Plausibility:
    """The plausibility scan of one fitted law over the extended box."""

    plausible: bool
    flags: list[Flag]
    mu_min: float
    mu_max: float
    n_points: int

    @property
    def reasons(self) -> list[str]:
        return [f.message for f in self.flags]

    def to_dict(self) -> dict[str, Any]:
        return {"plausible": self.plausible, "reasons": self.reasons,
                "flags": [f.to_dict() for f in self.flags], "mu_min": self.mu_min,
                "mu_max": self.mu_max, "grid_points": self.n_points}


def _where(law: Law, point: Mapping[str, float], design: Design) -> str:
    """``p = 0.5 MPa, v = 2 m/s`` for the variables of ``point`` that ``law`` depends on."""
    parts = []
    for k, x in point.items():
        if not _uses(law, k, design):
            continue
        s = fmt_value(k, x)
        if k == "v" and x <= law.floors.get("v", -1.0):
            s += f" [evaluated at the floor {law.floors['v']:g} m/s: singular at 0]"
        parts.append(f"{k} = {s}")
    return ", ".join(parts) or "every point (the law is a constant)"


def _uses(law: Law, var: str, design: Design) -> bool:
    """Does ``law`` depend on grid variable ``var`` (directly or through a derived one)?"""
    if var in law.variables:
        return True
    return any(d == var and k in law.variables for k, (d, _, _) in design.derived.items())


def _names(vars_: Sequence[str]) -> str:
    return " and ".join(vars_)


@dataclass
class _Scan:
    """A law evaluated over the grid of the extended box, and where the grid leaves the data."""

    law: Law
    design: Design
    dims: list[str]
    axes: list[np.ndarray]
    mu: np.ndarray
    ranges: dict[str, tuple[float, float]]
    used: list[str]
    outside: dict[str, np.ndarray]
    n_out: np.ndarray

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(a.size for a in self.axes)

    def point(self, idx: tuple[int, ...]) -> dict[str, float]:
        return {d: float(self.axes[i][idx[i]]) for i, d in enumerate(self.dims)}

    def extrapolated(self, idx: tuple[int, ...]) -> list[str]:
        return [d for d in self.used
                if bool(np.ravel(self.outside[d])[idx[self.dims.index(d)]])]

    def index(self, flat: int) -> tuple[int, ...]:
        """Grid index of a flat position (``()`` on a grid without dimensions)."""
        if not self.shape:
            return ()
        return tuple(int(i) for i in np.unravel_index(flat, self.mu.shape))

    def where(self, idx: tuple[int, ...]) -> str:
        return _where(self.law, self.point(idx) if self.shape else {}, self.design)


def _region_text(names: list[str]) -> str:
    if not names:
        return "inside the measured range"
    return f"with {_names(names)} outside the measured range"


def _evaluate_box(law: Law, values: Mapping[str, float], data: FitData, design: Design,
                  box: Mapping[str, tuple[float, float]]) -> _Scan:
    """Evaluate the law over the box's grid and mark the grid points outside the data."""
    dims = list(box)
    n_per = max(9, min(201, int(round(GRID_POINTS ** (1.0 / max(1, len(dims)))))))
    axes = [_axis(data, d, *box[d], n_per) for d in dims]
    grids = np.meshgrid(*axes, indexing="ij") if axes else []
    variables = design.complete(dict(zip(dims, grids)))
    shape = tuple(a.size for a in axes)
    with np.errstate(all="ignore"):
        mu = np.asarray(law.evaluate({k: variables[k] for k in law.variables
                                      if k in variables}, values), float)
    mu = np.broadcast_to(mu, shape).copy() if shape else np.atleast_1d(mu)
    ranges = {k: (float(np.min(data.arrays[k])), float(np.max(data.arrays[k]))) for k in dims}
    used = [d for d in dims if _uses(law, d, design)]
    outside = {}
    for i, d in enumerate(dims):
        lo, hi = ranges[d]
        o = (axes[i] < lo - 1e-12 * abs(lo)) | (axes[i] > hi + 1e-12 * abs(hi))
        outside[d] = o.reshape([-1 if j == i else 1 for j in range(len(dims))])
    n_out = np.zeros(shape, dtype=int)
    for d in used:
        n_out = n_out + outside[d]
    return _Scan(law, design, dims, axes, mu, ranges, used, outside, n_out)


def _nonfinite_flag(sc: _Scan) -> list[Flag]:
    finite = np.isfinite(sc.mu)
    if finite.all():
        return []
    bad = ~finite
    fewest = int(sc.n_out[bad].min())
    idx = sc.index(int(np.flatnonzero((bad & (sc.n_out == fewest)).ravel())[0]))
    names = sc.extrapolated(idx) if sc.shape else []
    pt = sc.point(idx) if sc.shape else {}
    return [Flag("non-finite",
                 f"mu is not finite (blows up) at {int(bad.sum())} of {sc.mu.size} points "
                 f"of the extended box, {_region_text(names)} e.g. at {sc.where(idx)}", at=pt)]


def _limit_flag(sc: _Scan, kind: str, bad: np.ndarray, worst_fn: Any, text: str
                ) -> list[Flag]:
    """A limit of mu broken somewhere: where first (fewest variables extrapolated), worst."""
    if not bad.any():
        return []
    mu = sc.mu
    fewest = int(sc.n_out[bad].min())
    near = bad & (sc.n_out == fewest)
    i_near = sc.index(int(worst_fn(np.where(near, mu, np.nan))))
    names = sc.extrapolated(i_near) if sc.shape else []
    msg = (f"{text} at {int(bad.sum())} of {mu.size} points of the extended box; "
           f"{_region_text(names)} it reaches {mu[i_near]:.3g} at {sc.where(i_near)}")
    i_all = sc.index(int(worst_fn(np.where(bad, mu, np.nan))))
    if sc.shape and i_all != i_near and abs(mu[i_all] - mu[i_near]) > 1e-9 * abs(mu[i_near]):
        msg += (f" (extreme {mu[i_all]:.3g} at {sc.where(i_all)}, "
                f"{_region_text(sc.extrapolated(i_all))})")
    pt = sc.point(i_near) if sc.shape else {}
    return [Flag(kind, msg, at=pt, mu=(float(mu[i_near]), float(mu[i_near])))]


def _walk(sc: _Scan, var: str, end: str) -> np.ndarray:
    """Grid indices of ``var`` from the measured end outward (beyond x_max up, x_min down)."""
    xa = sc.axes[sc.dims.index(var)]
    lo_v, hi_v = sc.ranges[var]
    if end == "high":
        return np.flatnonzero(xa >= hi_v * (1 - 1e-12))
    return np.flatnonzero(xa <= lo_v * (1 + 1e-12) + 1e-300)[::-1]


def _worst_reversal(sc: _Scan, var: str, end: str, sign: int
                    ) -> tuple[int, int, int, np.ndarray, np.ndarray] | None:
    """The line (other variables fixed) where mu turns most against ``sign`` beyond ``end``.

    Returns (line, from, to, walk indices, mu along the walk of every line), or None.
    """
    ax = sc.dims.index(var)
    idx = _walk(sc, var, end)
    if idx.size < 2:
        return None
    m = np.moveaxis(np.where(np.isfinite(sc.mu), sc.mu, np.nan), ax, -1)
    lines = m.reshape(-1, m.shape[-1])[:, idx]
    line_out = np.moveaxis(sc.n_out - np.broadcast_to(sc.outside[var], sc.shape), ax, -1)
    line_out = line_out.reshape(-1, m.shape[-1])[:, 0]
    step = 1 if end == "high" else -1
    # along the walk mu should move by sign*step; count the movement against it
    run = (np.fmin if sign * step < 0 else np.fmax).accumulate(lines, axis=1)
    change = np.abs(lines - run)
    thr = np.maximum(TREND_TOL, TREND_REL * np.abs(run))
    change = np.where(np.isfinite(change) & (change > thr), change, -np.inf)
    worst_line = change.max(axis=1)
    cand = np.isfinite(worst_line)
    if not cand.any():
        return None
    fewest = int(line_out[cand].min())
    li = int(np.argmax(np.where(cand & (line_out == fewest), worst_line, -np.inf)))
    j = int(np.argmax(change[li]))
    seg = lines[li, : j + 1]
    i = int(np.nanargmin(seg)) if sign * step < 0 else int(np.nanargmax(seg))
    return li, i, j, idx, lines


def _trend_flag(sc: _Scan, var: str, end: str, trend: Trend) -> list[Flag]:
    """A reversal of the data's trend beyond one end of ``var``'s measured range."""
    sign = trend.ends.get(end, {}).get("sign", 0)
    found = _worst_reversal(sc, var, end, sign) if sign else None
    if found is None:
        return []
    li, i, j, idx, lines = found
    xa = sc.axes[sc.dims.index(var)]
    others = [d for d in sc.dims if d != var]
    other_shape = tuple(sc.axes[sc.dims.index(d)].size for d in others)
    oidx = np.unravel_index(li, other_shape) if other_shape else ()
    at_o = {d: float(sc.axes[sc.dims.index(d)][oidx[k]]) for k, d in enumerate(others)}
    x_i, x_j = float(xa[idx[i]]), float(xa[idx[j]])
    mu_i, mu_j = float(lines[li, i]), float(lines[li, j])
    lo_v, hi_v = sc.ranges[var]
    walk = (f"as {var} increases beyond the highest measured {var} ({fmt_value(var, hi_v)})"
            if end == "high" else
            f"as {var} decreases below the lowest measured {var} ({fmt_value(var, lo_v)})")
    o_names = [d for d in others if d in sc.used
               and not sc.ranges[d][0] <= at_o[d] <= sc.ranges[d][1]]
    ctx = ""
    if any(_uses(sc.law, d, sc.design) for d in others):
        ctx = f"; at {_where(sc.law, at_o, sc.design)}" + (
            f", {_names(o_names)} also outside the measured range" if o_names else
            ", inside the measured range")
    verb = "rises" if mu_j > mu_i else "falls"
    return [Flag(
        "trend",
        f"mu {verb} by {abs(mu_j - mu_i):.3g} {walk}: "
        f"from {mu_i:.3g} at {var} = {fmt_value(var, x_i)} to {mu_j:.3g} at {var} = "
        f"{fmt_value(var, x_j)}{ctx}; the data show mu {_WORD[sign]} with {var} toward that "
        f"end ({trend.ends[end]['basis']})",
        variable=var, at={**at_o, var: x_i}, to={**at_o, var: x_j}, mu=(mu_i, mu_j))]


def scan_plausibility(law: Law, values: Mapping[str, float], data: FitData, design: Design,
                      box: Mapping[str, tuple[float, float]], trends: Mapping[str, Trend], *,
                      limits: tuple[float, float] = MU_LIMITS) -> Plausibility:
    """Scan the fitted law over ``box`` (module docstring); flag what is implausible.

    Where a limit is broken, the message gives the worst point among those
    with the fewest variables outside their measured range (inside the
    measured box if it happens there; else with only, say, ``p``
    extrapolated), and the worst point overall.  A trend reversal is likewise
    looked for first along lines whose other variables stay inside their
    measured ranges.

    Parameters
    ----------
    law : Law
        The law.
    values : mapping
        Its fitted parameters and settings (:attr:`FitResult.values`).
    data : FitData
        The data (for the measured ranges in messages and the grid ends).
    design : Design
        Which variables vary (:func:`design_of`).
    box : mapping
        Variable -> (low, high) in SI (:func:`extended_box`).
    trends : mapping
        Variable -> :class:`Trend` of the data (:func:`data_trends`).
    limits : tuple of float
        Physical limits (low, high) of mu.

    Returns
    -------
    Plausibility
        Whether the law is plausible, the flags with the reasons, and the range of
        mu over the box.
    """
    try:
        sc = _evaluate_box(law, values, data, design, box)
    except DomainError:  # a law that refuses to be evaluated outside its domain
        sc = _evaluate_box(law, values, data, design, _within_domain(law, box))
    mu = sc.mu
    finite = np.isfinite(mu)
    flags = _nonfinite_flag(sc)
    lo_lim, hi_lim = limits
    with np.errstate(invalid="ignore"):
        flags += _limit_flag(sc, "below-limit", finite & (mu < lo_lim), np.nanargmin,
                             f"mu < {lo_lim:g}")
        flags += _limit_flag(sc, "above-limit", finite & (mu > hi_lim), np.nanargmax,
                             f"mu > {hi_lim:g}")
    for var, trend in trends.items():
        if var in sc.dims and var in sc.used:
            for end in ("high", "low"):
                flags += _trend_flag(sc, var, end, trend)
    with np.errstate(all="ignore"):
        mu_min = float(np.nanmin(np.where(finite, mu, np.nan))) if finite.any() else math.nan
        mu_max = float(np.nanmax(np.where(finite, mu, np.nan))) if finite.any() else math.nan
    return Plausibility(not flags, flags, mu_min, mu_max, int(mu.size))


def _within_domain(law: Law, box: Mapping[str, tuple[float, float]]
                   ) -> dict[str, tuple[float, float]]:
    """The box cut to a strict domain, for a law that cannot be evaluated outside it.

    Persson's law has no modulus beyond its material's temperatures.  The data lie
    inside the domain (a fit refuses rows outside it), so the cut box still holds
    them; beyond the domain there is nothing to scan.  (Laws that can be evaluated
    there, such as the thesis polynomials, are scanned over the whole box.)
    """
    if not law.strict_domain:
        return dict(box)
    out = {}
    for var, (lo, hi) in box.items():
        d_lo, d_hi = law.domain.get(var, (-math.inf, math.inf))
        out[var] = (max(lo, d_lo), min(hi, d_hi))
    return out


def evaluate_on(law: Law, values: Mapping[str, float], design: Design,
                points: Mapping[str, Any]) -> np.ndarray:
    """Evaluate at ``points`` with derived variables filled in from their drivers."""
    full = design.complete(points)
    with np.errstate(all="ignore"):
        out = law.evaluate({k: full[k] for k in law.variables if k in full}, values)
    shape = np.broadcast_shapes(*[np.shape(v) for v in points.values()]) if points else ()
    return np.broadcast_to(np.asarray(out, float), shape)

