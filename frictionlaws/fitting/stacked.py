"""One law fitted to many datasets at once, with the numbers and warnings of one fit each.

:func:`fit_stacked` stacks the datasets (or groups) of equally many rows that hold the
same columns into ``(B, n)`` arrays and fits them together: the same starts as
:func:`~frictionlaws.fitting.fit` (the law's guess, then its defaults and presets in
the order of their sum of squares; one start for a law linear in its parameters), the
same bounds, and the solver every small fit ends with
(:func:`~frictionlaws.fitting.batch.solve`, which stops at the optimum itself, not at
a point that depends on the path to it).  The diagnosis of :func:`fit` then runs for
the whole stack at once: the identifiability of the Jacobian (one batched SVD), the
covariance, standard errors and intervals, the goodness of fit, the derived
quantities, the residual structure (:func:`~frictionlaws.fitting.robust.
residual_structures`) and the warnings they raise, written by the same functions.

A member is handed back (None) for :func:`fit` to fit alone whenever its fit needs
more than that: the two best starts do not end at the same optimum (several minima:
random starts, the global stage), the solve does not converge, the optimum lies at a
bound, a parameter is not determined (or a threshold is within rounding of deciding
it), the fit is no better than the mean of mu, mu or a variable takes one value,
a standard error comes out as zero, the law's domain or admissibility is left, rows
are invalid for the law, there are as many parameters as rows, or the law has no
analytic Jacobian.  So the results are those of one :func:`fit` per dataset, to the
precision both reach the optimum with (``tests/fitting/test_fitting_batch.py``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..law import VARIABLES, Law
from .batch import POLISH_ROWS, Problems, solve
from .data import FitData, _condition_vars, invalid_rows
from .derivatives import jacobian_function
from .diagnosis import (
    RANK_TOL,
    WEAK_TOL,
    _clip_interval,
    _directions,
    derived_columns,
    metric_table,
    weak_warning,
)
from .lsq import fit_statistics, scaled_covariance
from .methods import DEFAULT_METHOD
from .robust import STRUCTURE_ALPHA, ZERO_SPREAD, Structure, residual_structures
from .search import RANDOM_STARTS, _clip, _random_starts, _starts
from .uncertainty import structure_record, structure_warning

__all__ = ["fit_stacked", "stack_fits", "StackedFits", "stackable", "STACKED_OPTIONS",
           "notes_text"]

#: The options of :func:`fit` a stacked fit takes, and the values it takes them with;
#: with any other option or value every member is fitted alone.
STACKED_OPTIONS: dict[str, tuple[Any, ...] | None] = {
    "weights": ("auto", None), "seed": None, "on_invalid": ("error", "drop"),
    "global_stage": ("auto", "off"), "method": (DEFAULT_METHOD,),
    "uncertainty": ("asymptotic",), "lean": (False,), "starts": (None,),
    "n_boot": None, "n_jobs": None, "interval": None,
}
#: Relative margin around a threshold (identifiability, bounds, significance) within
#: which a member is fitted alone, so that rounding cannot decide it differently.
_MARGIN = 1e-6
#: Relative margin of the bound rule (:func:`~frictionlaws.fitting.diagnosis.
#: _warn_at_bound` warns within 1e-6).
_BOUND_MARGIN = 1e-5


def stackable(options: Mapping[str, Any]) -> bool:
    """True when :func:`fit` with ``options`` can be made by :func:`fit_stacked`.

    Parameters
    ----------
    options : mapping
        Keyword options of :func:`~frictionlaws.fitting.fit`.

    Returns
    -------
    bool
    """
    for key, value in options.items():
        if key not in STACKED_OPTIONS:
            return False
        allowed = STACKED_OPTIONS[key]
        if allowed is not None and not any(value is a or (isinstance(value, str) and value == a)
                                           for a in allowed):
            return False
    return True


def fit_stacked(law: Law, data: Sequence[FitData], seed: int = 0
                ) -> list[dict[str, Any] | None]:
    """Fit ``law`` to every member of ``data``; each result as a campaign keeps it.

    Parameters
    ----------
    law : Law
        The law (fitted with its declared bounds and settings).
    data : sequence of FitData
        The members, with their weights (``None``: unweighted).
    seed : int
        The seed of :func:`fit`'s random starts.

    Returns
    -------
    list
        Per member, the parts of :meth:`FitResult.to_dict` a campaign record keeps
        (``params``, ``metrics``, ``success``, ``warnings``, ``non_identifiable``,
        ``notes``, ``derived``, ``uncertainty``; JSON-able), or None: fit it with
        :func:`fit`.
    """
    fits = stack_fits(law, data, seed)
    return [fits.result(i) for i in range(len(data))]


def stack_fits(law: Law, data: Sequence[FitData], seed: int = 0) -> StackedFits:
    """:func:`fit_stacked`, its results kept in columns (:class:`StackedFits`)."""
    fits = StackedFits.empty(law, len(data))
    jac_func = jacobian_function(law)
    if jac_func is None:
        return fits
    buckets: dict[tuple[Any, ...], list[int]] = {}
    for i, fd in enumerate(data):
        if _eligible(law, fd):
            key = (fd.n, tuple(sorted(fd.arrays)), fd.weights is not None)
            buckets.setdefault(key, []).append(i)
    for members in buckets.values():
        stack = _Stack.of(law, [data[i] for i in members], jac_func, seed)
        try:
            stack.fit(fits, np.array(members))
        except (ValueError, TypeError, ArithmeticError, np.linalg.LinAlgError):
            continue  # a formula that does not take stacked arrays: one fit each
    fits = fits.compressed()
    fits.notes = {int(r): list(fd.notes) for r, fd in zip(fits.row, data) if r >= 0 and fd.notes}
    return fits


def _eligible(law: Law, fd: FitData) -> bool:
    """Whether a member's fit is made as :func:`fit` makes it without the one-fit path."""
    k = len(law.params)
    if not k < fd.n < POLISH_ROWS or law.neutral_fixes(fd.variables):
        return False
    if any(v not in fd.arrays for v in law.required_variables()):
        return False
    bad, _ = invalid_rows(law, fd.arrays, fd.n)
    return not bad.any()


@dataclass
class _Stack:
    """Members of equal size and columns, their problems and what the diagnosis needs."""

    law: Law
    data: list[FitData]
    prob: Problems
    seed: int = 0

    @classmethod
    def of(cls, law: Law, data: list[FitData], jac_func: Any, seed: int = 0) -> _Stack:
        y = np.stack([fd.arrays["mu"] for fd in data])
        x = {k: np.stack([fd.arrays[k] for fd in data]) for k in law.variables}
        w = None if data[0].weights is None else np.stack(
            [np.asarray(fd.weights, float) for fd in data])
        names = list(law.param_names)
        prob = Problems(law, names, dict(law.setting_values), law.prepare_variables(x), y, w,
                        np.array([law.param(k).bounds[0] for k in names], float),
                        np.array([law.param(k).bounds[1] for k in names], float), jac_func)
        return cls(law, data, prob, seed)

    @property
    def names(self) -> list[str]:
        return self.prob.names

    def fit(self, fits: StackedFits, members: np.ndarray) -> None:
        """Solve from the starts of :func:`fit`, diagnose the members that agree and put
        those kept into ``fits`` (the stack's members are ``members`` there)."""
        theta, ok = self._solve()
        rows = np.flatnonzero(ok)
        if rows.size:
            _Diagnosis(self, rows, theta[rows]).put(fits, members[rows])

    def _solve(self) -> tuple[np.ndarray, np.ndarray]:
        """Each member's optimum and whether the search of :func:`fit` ends there: every
        start solved must end at the same point."""
        starts, ok = self._starts()
        size, count = len(self.data), starts.shape[1]
        every = self.prob.take(np.repeat(np.arange(size), count))
        sol = solve(every, starts.reshape(-1, len(self.names)))
        theta = sol.theta.reshape(size, count, -1)
        cost = sol.cost.reshape(size, count)
        ok &= np.all(sol.converged.reshape(size, count), axis=1)
        with np.errstate(invalid="ignore"):
            ok &= np.ptp(cost, axis=1) <= 1e-9 * np.max(cost, axis=1) + 1e-300
            ok &= np.all(np.ptp(theta, axis=1) <= 1e-7 * np.max(np.abs(theta), axis=1)
                         + 1e-300, axis=1)
        return theta[:, 0], ok

    def _starts(self) -> tuple[np.ndarray, np.ndarray]:
        """``(B, S, k)`` starts, and which members have them.

        A law linear in its parameters: one start (its optimum is unique).  A law of one
        or two parameters: the two best scored of :func:`fit`'s starts (its guess, then
        its defaults and presets), which :func:`fit` stops after when they agree.  A law
        of more: all of them and the random starts :func:`fit` takes when they do not
        agree (a surface of several parameters may have several minima).
        """
        law, names, lo, hi = self.law, self.names, self.prob.lo, self.prob.hi
        clip = np.vectorize(_clip, otypes=[float])
        size = len(self.data)
        if law.linear:
            first = clip(np.array([law.param(k).default for k in names]), lo, hi)
            return np.tile(first, (size, 1, 1)), np.ones(size, bool)
        found = [self._candidates(fd) for fd in self.data]
        ok = np.array([len(c) >= 2 for c in found])
        width = max(len(c) for c in found)
        starts = clip(np.array([c + [c[0]] * (width - len(c)) for c in found], float), lo, hi)
        if len(names) > 2:
            return starts, ok
        scores = np.stack([_sum_of_squares(self.prob, starts[:, s]) for s in range(width)],
                          axis=1)
        scores[:, 1:][np.array([[j >= len(c) - 1 for j in range(width - 1)]
                                for c in found])] = np.inf
        order = np.argsort(scores, axis=1, kind="stable")[:, :2]
        return np.take_along_axis(starts, order[:, :, None], axis=1), ok

    def _candidates(self, fd: FitData) -> list[list[float]]:
        """The starts of :func:`fit` for one member (with its random ones for a law of more
        than two parameters)."""
        law, names = self.law, self.names
        guess_data = {**{k: fd.arrays[k] for k in law.variables}, "mu": fd.arrays["mu"],
                      **{k: v for k, v in fd.arrays.items() if k in VARIABLES}}
        guess = law.initial_guess(guess_data)
        found = _starts(law, guess, names)
        if len(names) > 2 and len(found) >= 2:
            found += _random_starts(law, guess, names, RANDOM_STARTS,
                                    np.random.default_rng(self.seed))
        return [[s[k] for k in names] for s in found]


def _sum_of_squares(prob: Problems, theta: np.ndarray) -> np.ndarray:
    r = prob.residual(theta)
    c = np.einsum("bn,bn->b", r, r)
    return np.where(np.isfinite(c), c, np.inf)


class _Diagnosis:
    """The diagnosis of :func:`fit` for the accepted members of a stack, at once."""

    def __init__(self, stack: _Stack, rows: np.ndarray, theta: np.ndarray) -> None:
        self.stack, self.rows, self.theta = stack, rows, theta
        self.law, self.names = stack.law, stack.names
        self.data = [stack.data[i] for i in rows]
        prob = stack.prob.take(rows)
        self.y, self.n, self.k = prob.y, prob.y.shape[1], len(self.names)
        self.fitted = prob.model(theta).copy()
        self.resid = prob.residual(theta)
        stats = fit_statistics(np.einsum("bn,bn->b", self.resid, self.resid), self.n, self.k)
        self.chisqr, self.redchi, self.aic, self.bic = stats
        self.jac = prob.jacobian(theta)
        self.keep = np.isfinite(self.chisqr) & np.all(np.isfinite(self.jac), axis=(1, 2))
        self.jac[~self.keep] = 1.0  # not used: keeps the batched algebra finite
        self.cov = np.full((len(rows), self.k, self.k), np.nan)

    def _covariance(self) -> None:
        """``inv(J' J)`` times the reduced chi-square of the members kept (a singular one
        is dropped)."""
        idx = np.flatnonzero(self.keep)
        unit = scaled_covariance(self.jac[idx])
        if unit is None:  # some member is singular: one by one
            unit = np.full((idx.size, self.k, self.k), np.nan)
            for n, i in enumerate(idx):
                one = scaled_covariance(self.jac[i])
                if one is None:
                    self.keep[i] = False
                else:
                    unit[n] = one
        self.cov[idx] = unit * self.redchi[idx, None, None]

    def put(self, fits: StackedFits, members: np.ndarray) -> None:
        """Put the results of the members kept into ``fits`` (at ``members``)."""
        weak = self._identifiability()
        self._covariance()
        self._check_values()
        var = np.diagonal(self.cov, axis1=1, axis2=2)
        with np.errstate(invalid="ignore"):  # a negative variance: no error (fit says so)
            se = np.sqrt(np.where(var > 0, var, np.nan))
        self._check_errors(se)
        metrics = metric_table(self.y, self.fitted, self.k, self.aic, self.bic, self.chisqr,
                               self.redchi)
        self._check_fit(metrics)
        derived = self._derived()
        structures = self._structures()
        keep = np.flatnonzero(self.keep)
        at = members[keep]
        fits.row[at] = at
        fits.values[at], fits.errors[at] = self.theta[keep], se[keep]
        fits.low[at], fits.high[at], fits.cut[at] = self._intervals(se, keep)
        fits.weak[at] = weak[keep]
        fits.metrics[at] = np.column_stack([metrics[key] for key in _METRICS])[keep]
        fits.size[at] = self.n
        fits.weighted[at] = [self.data[i].weights is not None for i in keep]
        for d, (name, _, _) in enumerate(fits.derived_names):
            fits.derived[at, d] = np.column_stack(derived[name])[keep]
        for i, m in zip(keep, at):
            st = structures[i]
            if st is not None:
                fits.variable[m] = fits.variables.index(st.variable)
                fits.test[m] = _TESTS.index(st.test)
                fits.statistic[m], fits.p_value[m], fits.n_tests[m] = \
                    st.statistic, st.p_value, st.n_tests

    def _intervals(self, se: np.ndarray, keep: np.ndarray
                   ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The 95 % intervals of the members ``keep`` cut at the bounds (by
        :func:`~frictionlaws.fitting.diagnosis._clip_interval`), and where cut."""
        from scipy.special import stdtrit

        tval = float(stdtrit(self.n - self.k, 0.975))
        theta, err = self.theta[keep], se[keep]
        low, high = theta - tval * err, theta + tval * err
        lo = np.array([self.law.param(k).bounds[0] for k in self.names])
        hi = np.array([self.law.param(k).bounds[1] for k in self.names])
        cut = (low < lo) | (high > hi)
        return np.maximum(low, lo), np.minimum(high, hi), cut

    def _identifiability(self) -> np.ndarray:
        """The poorly determined parameters of each member (a mask); members with
        undetermined ones dropped."""
        norms = np.sqrt(np.einsum("bnk,bnk->bk", self.jac, self.jac))
        self.keep &= np.all(np.isfinite(norms) & (norms > 0), axis=1)
        unit = self.jac / np.where(norms > 0, norms, 1.0)[:, None, :]
        _, s, vt = np.linalg.svd(unit, full_matrices=False)
        rel = s / np.where(s[:, :1] > 0, s[:, :1], 1.0)
        near = (np.abs(rel - RANK_TOL) <= _MARGIN * RANK_TOL) | (
            np.abs(rel - WEAK_TOL) <= _MARGIN * WEAK_TOL)
        self.keep &= np.all(rel >= RANK_TOL * (1 + _MARGIN), axis=1) & ~np.any(near, axis=1)
        weak = np.zeros((len(self.rows), self.k), bool)
        for i in np.flatnonzero(self.keep & np.any(rel < WEAK_TOL, axis=1)):
            for j in np.flatnonzero(rel[i] < WEAK_TOL):
                comp = np.abs(vt[i, j])
                if np.any(np.abs(comp - 0.1 * comp.max()) <= _MARGIN * comp.max()):
                    self.keep[i] = False
            _, found = _directions(rel[i], vt[i], self.names, [])
            weak[i] = [k in found for k in self.names]
        return weak

    def _check_values(self) -> None:
        """Members at a bound, or whose law variable takes one value, are fitted alone."""
        law = self.law
        for j, k in enumerate(self.names):
            lo, hi = law.param(k).bounds
            v = self.theta[:, j]
            scale = np.maximum(np.abs(v), max(abs(law.param(k).default), 1e-300))
            for bound in (lo, hi):
                if math.isfinite(bound):
                    self.keep &= np.abs(v - bound) > _BOUND_MARGIN * np.maximum(scale,
                                                                                abs(bound))
        for var in law.variables:
            x = np.stack([fd.arrays[var] for fd in self.data])
            self.keep &= np.ptp(x, axis=1) > 0
        for var, (lo, hi) in law.domain.items():
            if var in self.data[0].arrays:
                x = np.stack([fd.arrays[var] for fd in self.data])
                x = np.abs(x) if var == "v" else x
                self.keep &= ~np.any((x < lo * (1 - 1e-9)) | (x > hi * (1 + 1e-9)), axis=1)
        if law.admissible is not None:
            for i in np.flatnonzero(self.keep):
                values = {**law.setting_values, **dict(zip(self.names, self.theta[i].tolist()))}
                self.keep[i] = law.check_admissible(values) is None

    def _check_errors(self, se: np.ndarray) -> None:
        """No member with an error that is not finite, or zero to rounding."""
        self.keep &= np.all(np.isfinite(se) & (se > ZERO_SPREAD * np.abs(self.theta)), axis=1)

    def _check_fit(self, metrics: Mapping[str, np.ndarray]) -> None:
        """Not worse than the mean of mu (for a non-linear law: better, else the global
        stage may run), mu not constant, no residual so near 0 that its sign is rounding."""
        self.keep &= ~metrics["flat"] & (metrics["r2"] > -1e-9 * (1 - _MARGIN))
        if not self.law.linear:
            self.keep &= metrics["r2"] > _MARGIN
        rms = np.sqrt(np.mean(self.resid**2, axis=1, keepdims=True))
        self.keep &= ~np.any(np.abs(self.resid) <= 1e-9 * rms, axis=1)
        size = np.sqrt(np.mean(self.y**2, axis=1))  # an exact fit: residuals of rounding
        self.keep &= rms[:, 0] > 1e-3 * size

    def _derived(self) -> dict[str, tuple[np.ndarray, np.ndarray]]:
        """The derived quantities; a member with one not finite or without an error is
        fitted alone."""
        if not self.law.derived:
            return {}
        values: dict[str, Any] = {k: np.full(len(self.rows), v)
                                  for k, v in self.law.setting_values.items()}
        values.update({k: self.theta[:, j] for j, k in enumerate(self.names)})
        out = derived_columns(self.law, values, self.names, self.cov)
        for value, se in out.values():
            self.keep &= np.isfinite(value) & np.isfinite(se) & (se > ZERO_SPREAD * np.abs(value))
        return out

    def _structures(self) -> list[Any]:
        """The residual structure of each member (its significance not within rounding
        of the level)."""
        names = _condition_vars(self.data[0])
        arrays = {v: np.stack([fd.arrays[v] for fd in self.data]) for v in names}
        found = residual_structures(self.resid, arrays, names)
        for i, st in enumerate(found):
            if st is not None and abs(st.p_value * st.n_tests - STRUCTURE_ALPHA) <= \
                    _MARGIN * STRUCTURE_ALPHA:
                self.keep[i] = False
        return found

#: The metrics kept in :attr:`StackedFits.metrics`, in its columns' order.
_METRICS = ("r2", "adj_r2", "rmse", "mae", "max_abs_residual", "aic", "aicc", "bic",
            "chisqr", "redchi")
#: The residual-structure tests, by their index in :attr:`StackedFits.test`.
_TESTS = ("runs", "lag1")


@dataclass
class StackedFits:
    """The results of a law's stacked fits, in columns (one row per member fitted).

    Numbers and flags only, so they are cheap to keep and to send between processes:
    the warnings are written when a result is (by the functions :func:`fit` writes them
    with).  :meth:`result` gives one member's result as :func:`fit_stacked` does,
    :meth:`tidy` its rows of a campaign's table.  ``row[i]`` is the row of member ``i``,
    -1 for one handed back.
    """

    law: str
    names: list[str]
    units: list[str]
    bounds: list[tuple[float, float]]
    derived_names: list[tuple[str, str, str]]
    variables: list[str]
    row: np.ndarray
    values: np.ndarray
    errors: np.ndarray
    low: np.ndarray
    high: np.ndarray
    cut: np.ndarray
    weak: np.ndarray
    metrics: np.ndarray
    size: np.ndarray
    weighted: np.ndarray
    derived: np.ndarray
    #: Residual structure: index into ``variables`` (-1: none), test, statistic, p, tests.
    variable: np.ndarray
    test: np.ndarray
    statistic: np.ndarray
    p_value: np.ndarray
    n_tests: np.ndarray
    #: The notes of the members' data (rows dropped, columns ignored, ...), by row; a
    #: row without notes is not listed.
    notes: dict[int, list[str]] = field(default_factory=dict)

    @classmethod
    def empty(cls, law: Law, count: int) -> StackedFits:
        """Room for ``count`` members, none fitted yet."""
        k, nd = len(law.params), len(law.derived)

        def nan() -> np.ndarray:
            return np.full((count, k), np.nan)

        return cls(law.id, list(law.param_names), [p.unit for p in law.params],
                   [p.bounds for p in law.params],
                   [(d.name, d.unit, d.meaning) for d in law.derived], list(VARIABLES),
                   np.full(count, -1), nan(), nan(), nan(), nan(),
                   np.zeros((count, k), bool), np.zeros((count, k), bool),
                   np.full((count, len(_METRICS)), np.nan), np.zeros(count, int),
                   np.zeros(count, bool), np.full((count, nd, 2), np.nan),
                   np.full(count, -1), np.zeros(count, int), np.full(count, np.nan),
                   np.full(count, np.nan), np.zeros(count, int))

    _ROWS = ("values", "errors", "low", "high", "cut", "weak", "metrics", "size", "weighted",
             "derived", "variable", "test", "statistic", "p_value", "n_tests")

    def compressed(self) -> StackedFits:
        """The same results with only the rows of the members fitted (``row`` points there)."""
        kept = self.row >= 0
        row = np.full(len(self.row), -1)
        row[kept] = np.arange(int(kept.sum()))
        return replace(self, row=row, **{a: getattr(self, a)[kept] for a in self._ROWS})

    def result(self, member: int) -> dict[str, Any] | None:
        """Member ``member``'s result (as :func:`_compact` keeps :meth:`FitResult.to_dict`),
        None when it was handed back."""
        r = int(self.row[member])
        return None if r < 0 else self.at(r)

    def structure(self, r: int) -> Any:
        """The residual structure of row ``r`` (a :class:`~frictionlaws.fitting.robust.
        Structure`), or None."""
        v = int(self.variable[r])
        return None if v < 0 else Structure(
            self.variables[v], _TESTS[int(self.test[r])], float(self.statistic[r]),
            float(self.p_value[r]), int(self.n_tests[r]))

    def warnings(self, r: int) -> list[str]:
        """The warnings of row ``r``, in :func:`fit`'s order and words."""
        from scipy.special import stdtrit

        warn = [weak_warning([k for k, w in zip(self.names, self.weak[r]) if w])] \
            if self.weak[r].any() else []
        if self.cut[r].any():
            tval = float(stdtrit(int(self.size[r]) - len(self.names), 0.975))
            for j in np.flatnonzero(self.cut[r]):
                value, err = self.values[r, j], self.errors[r, j]
                _clip_interval(self.names[j], (value - tval * err, value + tval * err),
                               self.bounds[j], warn)
        st = self.structure(r)
        if st is not None and st.significant:
            warn.append(structure_warning(st, "asymptotic"))
        return warn

    def at(self, r: int) -> dict[str, Any]:
        """The result in row ``r``."""
        values, errors = self.values[r].tolist(), self.errors[r].tolist()
        low, high = self.low[r].tolist(), self.high[r].tolist()
        params = {k: {"value": values[j], "stderr": errors[j], "ci95": [low[j], high[j]],
                      "unit": self.units[j], "fixed": False, "identifiable": True}
                  for j, k in enumerate(self.names)}
        metrics = {k: _number(v) for k, v in zip(_METRICS, self.metrics[r].tolist())}
        metrics.update(n=int(self.size[r]), k=len(self.names), weighted=bool(self.weighted[r]))
        uncertainty: dict[str, Any] = {"method": "asymptotic"}
        st = self.structure(r)
        if st is not None:
            uncertainty["residual_structure"] = structure_record(st)
        uncertainty["asymptotic_stderr"] = dict(zip(self.names, errors))
        derived = self.derived[r].tolist()
        return {"params": params, "metrics": metrics, "success": True,
                "warnings": self.warnings(r), "non_identifiable": [],
                "notes": list(self.notes.get(r, [])),
                "derived": {name: {"value": derived[d][0], "stderr": derived[d][1],
                                   "unit": unit, "meaning": meaning}
                            for d, (name, unit, meaning) in enumerate(self.derived_names)},
                "uncertainty": uncertainty}

    def warning_counts(self, rows: np.ndarray) -> np.ndarray:
        """How many warnings the results in ``rows`` have (without writing them)."""
        significant = (self.variable[rows] >= 0) & (
            self.p_value[rows] * self.n_tests[rows] < STRUCTURE_ALPHA)
        return (self.weak[rows].any(axis=1).astype(int) + self.cut[rows].sum(axis=1)
                + significant.astype(int))

    def tidy_columns(self, rows: np.ndarray) -> dict[str, np.ndarray]:
        """The table columns from ``param`` to ``error`` of the results in ``rows``: one
        entry per (result, parameter), results in the order given (numbers as arrays of
        numbers, finite: a stacked result has no empty cell; text and flags as objects)."""
        k, m = len(self.names), len(rows)

        def per_param(a: np.ndarray) -> np.ndarray:
            return a[rows].ravel()

        def per_result(a: np.ndarray) -> np.ndarray:
            return np.repeat(a, k)

        return {"param": np.tile(np.array(self.names, object), m),
                "value": per_param(self.values), "stderr": per_param(self.errors),
                "ci95_low": per_param(self.low), "ci95_high": per_param(self.high),
                "uncertainty": np.full(m * k, "asymptotic", object),
                "unit": np.tile(np.array([u or "-" for u in self.units], object), m),
                "fixed": np.full(m * k, False, object), "converged": np.full(m * k, True, object),
                "r2": per_result(self.metrics[rows, 0]), "rmse": per_result(self.metrics[rows, 2]),
                "aic": per_result(self.metrics[rows, 5]), "bic": per_result(self.metrics[rows, 7]),
                "n": per_result(self.size[rows]), "warnings": per_result(self.warning_counts(rows)),
                "notes": per_result(self._notes_cells(rows)),
                "error": np.full(m * k, None, object)}

    def _notes_cells(self, rows: np.ndarray) -> np.ndarray:
        """The notes cells of the results in ``rows`` (None for most: no notes)."""
        cells = np.full(len(rows), None, object)
        if self.notes:
            for i, r in enumerate(rows.tolist()):
                if r in self.notes:
                    cells[i] = notes_text(self.notes[r])
        return cells

    def tidy(self, r: int, base: tuple[Any, ...]) -> list[tuple[Any, ...]]:
        """The rows of the result in row ``r`` in a campaign's tidy table, after ``base``
        (dataset, group values, law, rows); the columns of
        :func:`~frictionlaws.fitting.campaign_results.tidy_columns`."""
        m = self.metrics[r].tolist()
        count = int(self.warning_counts(np.array([r]))[0])
        tail = (True, _number(m[0]), _number(m[2]), _number(m[5]), _number(m[7]),
                int(self.size[r]), count, notes_text(self.notes.get(r)), None)
        values, errors = self.values[r].tolist(), self.errors[r].tolist()
        low, high = self.low[r].tolist(), self.high[r].tolist()
        return [(*base, k, values[j], errors[j], low[j], high[j], "asymptotic",
                 self.units[j] or "-", False, *tail) for j, k in enumerate(self.names)]


def notes_text(notes: Sequence[str] | None) -> str | None:
    """A result's notes as one cell of a campaign's table (None: no notes).

    Parameters
    ----------
    notes : sequence of str or None
        The notes.

    Returns
    -------
    str or None
        The notes joined by ``' | '``.
    """
    return " | ".join(notes) if notes else None


def _number(x: float) -> float | None:
    return x if math.isfinite(x) else None

