"""The search for the best optimum: deterministic and random starts, the scout subsample of
large data, the global stage, and the solver calls (:mod:`frictionlaws.fitting.lsq`).
"""

from __future__ import annotations

import inspect
import math
import warnings
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import numpy as np

from ..base.errors import InputError
from ..base.units import si_magnitude
from ..law import VARIABLES, Law, Setting
from .data import FitData, _check_data_for_law, _check_fix, _neutral_fixes, as_fit_data
from .derivatives import jacobian_function, model_jacobian
from .methods import fit_method

__all__ = ["ANALYTIC_FROM", "SCOUT_ROWS", "POLISH_TOL", "RANDOM_STARTS"]


#: Rows from which a fit's search uses the laws' analytic Jacobians (and MINPACK first).
#: Below, fits have few rows per parameter and are often ill-conditioned, so that the
#: search's path decides between near-equal minima: there the trust region with finite
#: differences chooses the minimum the results pinned by tests/test_pinned_*.py come from
#: (the thesis data have 19 rows, the synthetic pins 80); the best fit is then continued
#: to that minimum itself with the analytic Jacobian (:func:`.batch.polish`).
ANALYTIC_FROM = 100


#: Rows on which the starts after the first are refined on large data (4x this or more):
#: a start in the best fit's basin is recognised there at a fraction of a full solve.
SCOUT_ROWS = 1000


def _model_function(law: Law, extra: tuple[str, ...]) -> Any:
    """A function with an explicit signature for lmfit.Model."""
    settings = law.setting_values
    indep = law.variables or ("_shape",)
    names = list(indep) + list(law.param_names) + list(extra)

    def model(**kw: Any) -> Any:
        variables = {k: kw[k] for k in law.variables}
        shape = kw.get("_shape")
        values = {**settings, **{k: kw[k] for k in law.param_names}, **{k: kw[k] for k in extra}}
        out = law.evaluate(variables, values)
        if shape is not None:
            out = np.broadcast_to(out, np.shape(shape))
        return out

    model.__signature__ = inspect.Signature(  # type: ignore[attr-defined]
        [inspect.Parameter(n, inspect.Parameter.POSITIONAL_OR_KEYWORD) for n in names])
    model.__name__ = law.id.replace("-", "_").replace("+", "_")
    return model


def _starts(law: Law, guess: dict[str, float], names: list[str]) -> list[dict[str, float]]:
    """Deterministic starts: the data-driven guess, the defaults and the presets."""
    starts = [dict(guess)]
    if law.linear:
        return starts
    starts.append({**guess, **{k: law.param(k).default for k in names if k in law.param_names}})
    for preset in law.presets.values():
        starts.append({**guess, **{k: v for k, v in preset.items() if k in names}})
    # one start once: a preset equal to the defaults (pacejka's dry road) would otherwise
    # "reproduce" it without telling anything about the surface
    unique: list[dict[str, float]] = []
    for start in starts:
        if all(any(start[k] != seen[k] for k in names) for seen in unique):
            unique.append(start)
    return unique


def _random_starts(law: Law, guess: dict[str, float], names: list[str], n_random: int,
                   rng: np.random.Generator) -> list[dict[str, float]]:
    """Random perturbations of the guess (log-normal for positive parameters)."""
    starts = []
    for _ in range(n_random):
        s = dict(guess)
        for k in names:
            if k not in law.param_names:
                continue
            p = law.param(k)
            lo, _hi = p.bounds
            x = guess[k]
            if x > 0 and lo >= 0:
                x = x * math.exp(rng.normal(0.0, 1.0))
            else:
                x = x + rng.normal(0.0, 1.0) * max(abs(x), 0.1 * (abs(p.default) or 1.0))
            s[k] = x
        starts.append(s)
    return starts


def _clip(value: float, lo: float, hi: float) -> float:
    if not math.isfinite(value):
        return value
    span = hi - lo if math.isfinite(hi - lo) else 0.0
    eps = 1e-9 * span
    if math.isfinite(lo) and value <= lo:
        value = lo + eps if span else (lo + abs(lo) * 1e-9 + 1e-300 if lo >= 0 else lo)
    if math.isfinite(hi) and value >= hi:
        value = hi - eps if span else hi
    return value


@dataclass
class _GlobalStage:
    """Bounded differential evolution on transformed parameters (the global stage of a fit).

    Each parameter is searched on a finite box: two-sided bounds linearly (in log10
    when both are positive and far apart), positive one-sided ones in log10 over eight
    decades around the guess, others linearly over +/- 10 typical sizes.  Two-sided
    boxes reach 5 % beyond each bound and are clipped back, so a bound is reachable
    exactly (laws such as Wriggers' change form there).
    """

    law: Law
    held: dict[str, float]
    names: list[str]
    bounds: dict[str, tuple[float, float]]
    guess: dict[str, float]
    evaluate: Any
    y: np.ndarray
    w: np.ndarray | None
    seed: int

    def __post_init__(self) -> None:
        self.boxes = {k: self._box(k) for k in self.names}

    def wanted(self, best: Any, finals: list[float]) -> bool:
        """True when the local starts end worse than the mean of mu or at different minima."""
        if self.law.linear or best is None:
            return not self.law.linear
        fitted = np.asarray(best.best_fit, float)
        ss_tot = float(np.sum((self.y - self.y.mean()) ** 2))
        if ss_tot > 0 and float(np.sum((self.y - fitted) ** 2)) > ss_tot:
            return True
        # chi^2 differences below 1e-9 of the data's own sum of squares are round-off
        # (a law that fits exactly, e.g. constant mu), not different minima
        yw = self.y if self.w is None else self.y * self.w
        floor = 1e-6 * float(np.sum(yw ** 2))  # x the 1e-3 below: 1e-9 of it
        rel = (np.asarray(finals) - min(finals)) / max(min(finals), floor, 1e-300)
        return bool(np.mean(rel > 1e-3) > 0.5)  # most starts miss the best basin

    def _box(self, k: str) -> tuple[float, float, str]:
        lo, hi = self.bounds[k]
        ref = abs(self.guess.get(k, 0.0)) or abs(self._default(k)) or 1.0
        if math.isfinite(lo) and math.isfinite(hi):
            if lo > 0 and hi / lo > 1e3:
                span = math.log10(hi / lo)
                return math.log10(lo) - 0.05 * span, math.log10(hi) + 0.05 * span, "log"
            return lo - 0.05 * (hi - lo), hi + 0.05 * (hi - lo), "lin"
        if math.isfinite(lo) and lo >= 0:
            c = math.log10(max(ref, lo * 10, 1e-300))
            return c - 4.0, c + 4.0, "log"
        c = self.guess.get(k, 0.0)
        return c - 10 * ref, c + 10 * ref, "lin"

    def _default(self, k: str) -> float:
        return self.law.param(k).default if k in self.law.param_names else \
            self.law.setting(k).value

    def values(self, u: np.ndarray) -> dict[str, float]:
        """Parameter values for a point ``u`` of the search box."""
        out = {}
        for k, uk in zip(self.names, u):
            scale = self.boxes[k][2]
            lo, hi = self.bounds[k]
            out[k] = float(min(max(10.0 ** uk if scale == "log" else uk, lo), hi))
        return out

    def cost(self, u: np.ndarray) -> float:
        vals = {**self.held, **self.values(u)}
        with np.errstate(all="ignore"):
            try:  # a point the law refuses is no candidate (as in the local stage)
                model = np.broadcast_to(np.asarray(self.evaluate(vals), float), self.y.shape)
            except (ValueError, FloatingPointError, TypeError, ZeroDivisionError):
                return 1e300
        r = (model - self.y) * (self.w if self.w is not None else 1.0)
        c = float(np.sum(r * r))
        return c if math.isfinite(c) else 1e300

    def search(self) -> tuple[dict[str, float] | None, tuple[str, ...]]:
        """The best point found and the parameters it put exactly on a bound."""
        from scipy.optimize import differential_evolution

        box = [self.boxes[k][:2] for k in self.names]
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                sol = differential_evolution(self.cost, box, seed=self.seed, maxiter=200,
                                             popsize=10, tol=1e-5, polish=False)
        except (ValueError, FloatingPointError, np.linalg.LinAlgError):
            return None, ()
        if not math.isfinite(sol.fun) or sol.fun >= 1e300:
            return None, ()
        vals = {**self.guess, **self.values(sol.x)}
        pinned = tuple(k for k in self.names if vals[k] in self.bounds[k])
        return vals, pinned


@dataclass
class _Setup:
    """Everything a fit works with, once the data and options are checked."""

    law: Law
    fd: FitData
    notes: list[str]
    fix: dict[str, float]
    freed: tuple[str, ...]
    settings: dict[str, float]
    x: dict[str, np.ndarray]
    y: np.ndarray
    guess: dict[str, float]
    model_law: Law
    vary_names: list[str]
    bounds: dict[str, tuple[float, float]]

    @property
    def names(self) -> list[str]:
        """The parameters and freed settings, in the law's order."""
        return list(self.law.param_names) + list(self.freed)

    @property
    def w(self) -> np.ndarray | None:
        return self.fd.weights

    def unit(self, name: str) -> str:
        return self.law.setting(name).unit if name in self.freed else self.law.param(name).unit

    def typical(self, name: str) -> float:
        return (self.law.param(name).default if name in self.law.param_names
                else self.law.setting(name).value)


def _setup(law: Law, data: Any, fix: Mapping[str, float] | None, free: Iterable[str],
           initial: Mapping[str, float] | None, weights: Any, on_invalid: str,
           load: Mapping[str, Any]) -> _Setup:
    """Check the data, fixes, freed settings and initial values; build the start guess."""
    fd = as_fit_data(data, weights=weights, **load)
    fd, notes = _check_data_for_law(law, fd, on_invalid)
    notes = list(fd.notes) + notes
    setting_names = [s.name for s in law.settings]
    freed = _freed_settings(law, free, setting_names)
    fixed = _check_fix(law, dict(fix or {}), setting_names)
    fixed.update(_neutral_fixes(law, fd, fixed, notes))
    settings = {k: float(fixed.get(k, v)) for k, v in law.setting_values.items()
                if k not in freed}
    y = fd.arrays["mu"]
    x = {k: fd.arrays[k] if k in fd.arrays else np.zeros_like(y) for k in law.variables}
    guess = _start_guess(law, fd, x, freed, initial)
    vary_names = [k for k in list(law.param_names) + list(freed) if k not in fixed]
    if not vary_names:
        raise InputError(f"every parameter of law '{law.id}' is fixed: nothing to fit")
    bounds = {p.name: p.bounds for p in law.params}
    bounds.update({k: law.setting(k).bounds for k in freed})
    return _Setup(law, fd, notes, fixed, freed, settings, x, y, guess,
                  _model_law(law, settings, freed), vary_names, bounds)


def _freed_settings(law: Law, free: Iterable[str], setting_names: list[str]
                    ) -> tuple[str, ...]:
    """The settings to fit as parameters; an unknown name is refused."""
    free = list(dict.fromkeys(free))
    for k in free:
        if k not in setting_names and k not in law.param_names:
            raise InputError(f"law '{law.id}' has no setting '{k}' to free "
                             f"(settings: {', '.join(setting_names) or 'none'})")
    return tuple(k for k in free if k in setting_names)


def _start_guess(law: Law, fd: FitData, x: Mapping[str, np.ndarray], freed: tuple[str, ...],
                 initial: Mapping[str, float] | None) -> dict[str, float]:
    """The law's data-driven guess, the freed settings' values, then ``initial``."""
    if initial:  # pint Quantities in SI (or refused), as everywhere in the API
        initial = {k: si_magnitude(v, law.value_unit(k), f"initial '{k}'")
                   for k, v in initial.items()}
    y = fd.arrays["mu"]
    guess_data = {**x, "mu": y, **{k: v for k, v in fd.arrays.items() if k in VARIABLES}}
    guess = law.initial_guess(guess_data)
    for k in freed:
        guess[k] = float(initial.get(k, law.setting(k).value) if initial
                         else law.setting(k).value)
    if initial:
        unknown = set(initial) - set(guess)
        if unknown:
            raise InputError(f"unknown initial value(s) {sorted(unknown)} for law '{law.id}'")
        if any(isinstance(v, (bool, str)) or v is None for v in initial.values()):
            raise InputError(f"initial values must be numbers, got {dict(initial)!r}",
                             option="initial")
        given = {k: float(v) for k, v in initial.items()}
        try:  # the one parameter-value check: finite, within the declared bounds
            law.check_values(given, admissible=False)
        except InputError as exc:
            raise InputError(exc.bare_message, option="initial") from None
        guess.update(given)
    return guess


def _model_law(law: Law, settings: Mapping[str, float], freed: tuple[str, ...]) -> Law:
    """The law with settings fixed to non-default values (they flow through its closure)."""
    if settings == {k: v for k, v in law.setting_values.items() if k not in freed}:
        return law

    return replace(law, settings=tuple(
        Setting(s.name, settings.get(s.name, s.value), s.unit, s.meaning, s.bounds)
        for s in law.settings))


@dataclass
class _Search:
    """The multi-start search: runs local lmfit fits and keeps the best."""

    setup: _Setup
    method: str
    best: Any = None
    best_pinned: tuple[str, ...] = ()
    errors: list[str] = field(default_factory=list)
    finals: list[float] = field(default_factory=list)
    model: Any = None

    def __post_init__(self) -> None:
        s = self.setup
        self.max_nfev = 300 * (len(s.vary_names) + 1)
        if fit_method(self.method).lmfit_model:
            import lmfit

            indep = s.law.variables or ("_shape",)
            self.model = lmfit.Model(_model_function(s.model_law, s.freed),
                                     independent_vars=list(indep), nan_policy="raise")
        self.kwargs = {k: s.x[k] for k in s.law.variables}
        if not s.law.variables:
            self.kwargs["_shape"] = s.y
        self.prepared = s.model_law.prepare_variables(s.x)
        self.held = {k: v for k, v in s.model_law.setting_values.items() if k not in s.names}
        self.jac_func = None
        if s.y.size >= ANALYTIC_FROM:
            self.jac_func = jacobian_function(s.law)

    def jacobian(self, values: Mapping[str, float], names: list[str]) -> np.ndarray | None:
        """The analytic Jacobian of the model by ``names`` at ``values`` (None: none)."""
        if self.jac_func is None:
            return None

        return model_jacobian(self.jac_func, self.prepared, {**self.held, **values}, names,
                              self.setup.y.size)

    def score(self, start: Mapping[str, float]) -> float:
        """chi^2 at a start (infinite when the model is not finite there)."""
        s = self.setup
        with np.errstate(all="ignore"):
            try:
                r = s.y - np.asarray(self.evaluate(self.start_values(start)), float)
            except (ValueError, FloatingPointError, TypeError, ZeroDivisionError):
                return math.inf
        if s.w is not None:
            r = r * s.w
        c = float(np.sum(r * r))
        return c if math.isfinite(c) else math.inf

    def start_values(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()
                     ) -> dict[str, float]:
        """Every parameter's start: fixed, held at a bound (pinned), or inside its bounds."""
        s = self.setup
        out = {}
        for k in s.names:
            if k in s.fix:
                out[k] = float(s.fix[k])
            elif k in pinned:  # held exactly at the bound the global stage found
                out[k] = float(start[k])
            else:
                out[k] = _clip(float(start[k]), *s.bounds[k])
        return out

    def params(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()) -> Any:
        """lmfit parameters from ``start``: fixed, pinned at a bound, or varied."""
        import lmfit

        s = self.setup
        params = lmfit.Parameters()
        for k, value in self.start_values(start, pinned).items():
            if k in s.fix or k in pinned:
                params.add(k, value=value, vary=False)
            else:
                params.add(k, value=value, min=s.bounds[k][0], max=s.bounds[k][1])
        return params

    def _local(self, start: Mapping[str, float], pinned: tuple[str, ...], tol: float = 1e-8
               ) -> Any:
        """One local solve, by the fit method's entry
        (:data:`~frictionlaws.fitting.methods.FIT_METHODS`)."""
        return fit_method(self.method).solve(self, start, pinned, tol)

    def evaluate(self, values: Mapping[str, float]) -> Any:
        """The model (the law with the fit's settings) at ``values`` on the data."""
        return self.setup.model_law.evaluate_prepared(self.prepared, {**self.held, **values},
                                                      self.setup.y.size)

    def solve_from(self, start: Mapping[str, float], pinned: tuple[str, ...] = (),
                   tol: float = 1e-8) -> Any:
        """One local fit from ``start`` (None when it fails; the error is kept)."""
        try:
            with warnings.catch_warnings(), np.errstate(all="ignore"):
                warnings.simplefilter("ignore")
                res = self._local(start, pinned, tol)
        except (ValueError, FloatingPointError, np.linalg.LinAlgError, TypeError) as exc:
            self.errors.append(str(exc))
            return None
        return res if np.isfinite(res.chisqr) else None

    def run(self, start: Mapping[str, float], pinned: tuple[str, ...] = ()) -> None:
        """One local fit from ``start``; kept when it beats the best so far."""
        res = self.solve_from(start, pinned)
        if res is None:
            return
        self.finals.append(float(res.chisqr))
        if self.best is None or res.chisqr < self.best.chisqr * (1 - 1e-10):
            self.best, self.best_pinned = res, pinned


#: Random starts tried when the deterministic ones disagree (or all fail).
RANDOM_STARTS = 6


#: Tolerances of the polish of a lean fit (:func:`_polish`).
POLISH_TOL = 1e-13


def _polish(search: _Search) -> None:
    """Refine the best fit from its own end point with tight tolerances, steps scaled.

    The search's solves stop at lmfit's tolerances (1e-8), a few 1e-7 of chi^2 short of
    the optimum on badly scaled or flat problems (Wriggers' b ~ 1e5 with d ~ 1e-5), and
    where exactly depends on the solver's path, which differs between scipy versions.
    Continued to :data:`POLISH_TOL` with the steps scaled by the Jacobian, every path
    ends at the optimum itself (chi^2 the same to about 1e-10), so the refits of a
    comparison give the same scores under every supported numpy and scipy.
    """
    best = search.best
    if best is None or not fit_method(search.method).polished:
        return
    start = {k: float(best.params[k].value) for k in search.setup.names}
    res = search.solve_from(start, search.best_pinned, POLISH_TOL)
    if res is not None and res.chisqr <= best.chisqr:
        search.best = res


def _multistart(search: _Search, starts: int | None, seed: int) -> None:
    """The deterministic starts, then random ones when they disagree, all fail or are asked.

    The deterministic starts are scored by their chi^2 and refined best first, and the
    search stops as soon as one ends where an earlier one did (chi^2 within 1e-6): the
    surface then shows one basin for the starts that look best, and the others would
    cost a full solve each.
    """
    s = search.setup
    candidates = _starts(s.law, s.guess, s.vary_names)
    if len(candidates) > 1:
        scores = [search.score(c) for c in candidates]
        candidates = [candidates[i] for i in sorted(range(len(scores)), key=scores.__getitem__)]
    reproduced = scouted = False
    if s.y.size >= 4 * SCOUT_ROWS:
        reproduced, scouted = _scout(search, candidates), True
    else:
        for start in candidates:
            search.run(start)
            reproduced = _reproduced(search.finals)
            if reproduced:
                break
    # Random starts when the deterministic ones disagree (several minima) or all failed:
    # the surface is then multi-modal or hard, and more starts are worth their cost.
    finals = search.finals
    spread = (max(finals) - min(finals)) / max(min(finals), 1e-300) if finals else math.inf
    disagree = (spread > 1e-6 or scouted) and not reproduced
    forced = starts is not None and int(starts) > 0
    if not s.law.linear and (disagree or search.best is None or forced):
        rng = np.random.default_rng(seed)
        n_random = RANDOM_STARTS if starts is None else int(starts)
        for start in _random_starts(s.law, s.guess, s.vary_names, n_random, rng):
            search.run(start)


def _scout(search: _Search, candidates: list[dict[str, float]]) -> bool:
    """Refine ``candidates`` on :data:`SCOUT_ROWS` evenly spaced rows, then the best on all.

    The candidates (best scored first) are refined on the subsample until one ends
    where an earlier one did (chi^2 within 1e-6 there): the rows span the data evenly,
    so their basins are the full data's, at a fraction of the cost.  The best of them
    is then refined on every row, from next to its minimum.  Returns True when a
    candidate reproduced the best on the subsample.
    """
    s = search.setup
    rows = np.unique(np.linspace(0, s.y.size - 1, SCOUT_ROWS).round().astype(int))
    mask = np.zeros(s.y.size, bool)
    mask[rows] = True
    scout = _Search(replace(s, fd=s.fd.subset(mask), y=s.y[rows],
                            x={k: v[rows] for k, v in s.x.items()}), search.method)
    for start in candidates:
        scout.run(start)
        if _reproduced(scout.finals):
            break
    if scout.best is not None:
        search.run({k: scout.best.params[k].value for k in s.names})
    if search.best is None:  # nothing converged on the subsample: every row, first start
        search.run(candidates[0])
    return _reproduced(scout.finals)


def _reproduced(finals: list[float]) -> bool:
    """True when the latest local fit ended at the best chi^2 of the earlier ones."""
    if len(finals) < 2:
        return False
    best = min(finals[:-1])
    return abs(finals[-1] - best) <= 1e-6 * max(best, 1e-300)


def _global_stage(search: _Search, mode: str, seed: int) -> list[str]:
    """Differential evolution then a local polish, when asked or wanted; its notes."""
    s = search.setup
    held = {k: v for k, v in s.fix.items() if k in s.names}  # settings: in model_law
    stage = _GlobalStage(s.model_law, held, s.vary_names, s.bounds, s.guess,
                         search.evaluate, s.y, s.w, seed)
    if not (mode == "on" or (mode == "auto" and stage.wanted(search.best, search.finals))):
        return []
    start, pinned = stage.search()
    if start is None:
        return []
    search.run(start, pinned)
    if pinned:  # the bound may be a limit the polish should also leave
        search.run(start)
    return [f"global stage: differential evolution over {len(s.vary_names)} transformed "
            "parameters, then the local polish"
            + (f" (with {', '.join(pinned)} held at the bound it reached)"
               if pinned and search.best_pinned else "")]

