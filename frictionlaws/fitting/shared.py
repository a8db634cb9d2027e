"""Global fits across groups with shared parameters.

One law is fitted to several groups of a dataset at once (temperatures, compounds,
surfaces); the parameters named ``shared`` take one value for all groups, every other
free parameter one value per group.  Example: Thirion's saturation ``b`` shared across
five temperatures while the level ``a`` changes with temperature.

The global fit minimises the sum of every group's (weighted) squared residuals with a
bounded trust-region solver, started from the separate fits.  Standard errors come
from the Jacobian of the stacked residuals scaled by the residual variance (the same
asymptotic rule as a single fit).  The shared model is nested in the separate one, so
the two are compared with an F-test and with their AIC difference: a small p-value
says the groups do not share those parameters.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.display import group_label, parameter_table
from ..base.errors import FitError, InputError
from ..io import load_dataset
from ..law.registry import get_law
from . import fit
from .campaign import group_column, group_keys, group_subset, key_text, tidy_columns
from .diagnosis import _identifiability
from .lsq import least_squares_solve
from .robust import ZERO_SPREAD

__all__ = ["SharedFit", "fit_shared"]


@dataclass
class SharedFit:
    """The outcome of :func:`fit_shared`.

    Attributes
    ----------
    law : str
        Law id.
    by : tuple of str
        Grouping columns.
    shared : tuple of str
        Parameters with one value across groups.
    groups : list of dict
        Per group: ``key`` (column -> value), ``rows``, ``params`` (name -> value,
        stderr, unit, shared), ``rss``.
    comparison : dict
        ``rss_shared``, ``rss_separate``, ``k_shared``, ``k_separate``, ``n``,
        ``F``, ``p_value``, ``aic_shared``, ``aic_separate``, ``delta_aic``
        (shared minus separate; negative favours sharing) and a ``verdict``.
    dataset : str
        The name of the dataset fitted.
    """

    law: str
    by: tuple[str, ...]
    shared: tuple[str, ...]
    groups: list[dict[str, Any]]
    comparison: dict[str, Any]
    success: bool
    message: str
    warnings: list[str] = field(default_factory=list)
    dataset: str = ""

    def shared_values(self) -> dict[str, dict[str, Any]]:
        """The shared parameters: name -> value, stderr, unit."""
        first = self.groups[0]["params"]
        return {k: {f: first[k][f] for f in ("value", "stderr", "unit")} for k in self.shared}

    def to_dict(self) -> dict[str, Any]:
        """JSON-able form."""
        return {"law": self.law, "dataset": self.dataset, "by": list(self.by),
                "shared": list(self.shared),
                "groups": self.groups, "comparison": self.comparison,
                "success": self.success, "message": self.message,
                "warnings": list(self.warnings)}

    def to_frame(self) -> Any:
        """Tidy DataFrame: one row per (group, parameter), in SI.

        The columns are those of a campaign's tidy table
        (:func:`frictionlaws.fitting.campaign.tidy_columns`: ``dataset``, the grouping columns,
        ``law``, ``rows``, ``param``, ``value``, ``stderr``, ...) followed by
        ``shared``, so ``fit --by`` and ``fit --by --shared`` write one layout.
        Intervals and per-group metrics the shared fit does not give are empty.
        """
        import pandas as pd

        rows = []
        for g in self.groups:
            key = {group_column(c): v for c, v in g["key"].items()}
            for name, est in g["params"].items():
                rows.append({"dataset": self.dataset, **key, "law": self.law,
                             "rows": g["rows"], "param": name, "value": est["value"],
                             "stderr": est["stderr"], "unit": est["unit"] or "-",
                             "fixed": False, "converged": self.success, "n": g["rows"],
                             "warnings": len(self.warnings), "shared": est["shared"]})
        return pd.DataFrame(rows, columns=[*tidy_columns(self.by), "shared"])

    def report(self) -> str:
        """Plain-text report: the per-group parameter table (display units), the comparison."""
        lines = [f"{self.law}: shared {', '.join(self.shared)} across "
                 f"{len(self.groups)} groups of {', '.join(self.by)} (one global fit)"]
        lines.append(parameter_table(
            [{"label": group_label(g["key"]), "n": g["rows"], "params": g["params"]}
             for g in self.groups], shared=self.shared))
        c = self.comparison
        lines.append(f"shared vs separate: F = {c['F']:.4g}, p = {c['p_value']:.3g}, "
                     f"delta AIC = {c['delta_aic']:.3g} ({c['verdict']})")
        lines.extend(f"warning: {w}" for w in self.warnings)
        return "\n".join(lines)


@dataclass
class _Problem:
    """The stacked global least-squares problem."""

    law: Any
    names: list[str]          # free parameters of the law
    shared: list[str]
    data: list[dict[str, np.ndarray]]
    weights: list[np.ndarray]
    settings: dict[str, float]

    @property
    def own(self) -> list[str]:
        return [k for k in self.names if k not in self.shared]

    def unpack(self, theta: np.ndarray, g: int) -> dict[str, float]:
        s = len(self.shared)
        values = dict(zip(self.shared, theta[:s]))
        start = s + g * len(self.own)
        values.update(zip(self.own, theta[start:start + len(self.own)]))
        return {**self.settings, **values}

    def parts(self, theta: np.ndarray) -> list[np.ndarray]:
        """Each group's weighted residuals (model - data)."""
        out = []
        for g, (arrays, w) in enumerate(zip(self.data, self.weights)):
            xs = {k: arrays[k] for k in self.law.variables}
            with np.errstate(all="ignore"):
                pred = np.broadcast_to(self.law.evaluate(xs, self.unpack(theta, g)),
                                       arrays["mu"].shape)
            out.append(w * (pred - arrays["mu"]))
        return out

    def residual(self, theta: np.ndarray) -> np.ndarray:
        r = np.concatenate(self.parts(theta))
        return np.where(np.isfinite(r), r, 1e10)

    def bounds(self) -> tuple[np.ndarray, np.ndarray]:
        order = self.shared + self.own * len(self.data)
        lo = np.array([self.law.param(k).bounds[0] for k in order])
        hi = np.array([self.law.param(k).bounds[1] for k in order])
        return lo, hi


def fit_shared(law: Any, data: Any, by: str | Sequence[str], shared: Sequence[str], *,
               fix: Mapping[str, float] | None = None, weights: Any = "auto",
               load_options: Mapping[str, Any] | None = None) -> SharedFit:
    """Fit ``law`` to every group of ``data`` with the ``shared`` parameters in common.

    Parameters
    ----------
    law : str or Law
        The law.
    data : name, path, Dataset or DataFrame
        Read with :func:`frictionlaws.io.load_dataset`.
    by : str or sequence of str
        Grouping columns (at least two groups).
    shared : sequence of str
        Free parameters of the law with one value across groups.
    fix : mapping, optional
        Parameters held fixed in every group.
    weights : {"auto"} or None
        As in :func:`frictionlaws.fit`.

    Returns
    -------
    SharedFit
    """
    law = get_law(law)
    ds = load_dataset(data, **dict(load_options or {}))
    columns = (by,) if isinstance(by, str) else tuple(by)
    groups = group_keys(ds, columns)
    if len(groups) < 2:
        raise InputError(f"a shared fit needs two or more groups of {', '.join(columns)} "
                         f"(found {len(groups)})", file=str(ds.source))
    fixed = dict(fix or {})
    shared = list(dict.fromkeys(shared))
    _check_shared(law, shared, fixed)
    separate = [fit(law, group_subset(ds, key, mask), fix=fixed, weights=weights)
                for key, mask in groups]
    problem = _build_problem(law, ds, groups, shared, fixed)
    out = _solve(problem, columns, groups, separate)
    out.dataset = str(ds.name)
    return out


def _check_shared(law: Any, shared: list[str], fixed: Mapping[str, float]) -> None:
    if not shared:
        raise InputError(f"name the parameters of law '{law.id}' to share "
                         f"(parameters: {', '.join(law.param_names)})")
    for k in shared:
        law.param(k)  # InputError naming the parameters when unknown
        if k in fixed:
            raise InputError(f"parameter '{k}' is both fixed and shared")
    if set(shared) >= set(law.param_names) - set(fixed):
        raise InputError("every free parameter is shared: that is one pooled fit, not a "
                         "shared one")


def _build_problem(law: Any, ds: Any, groups: list[tuple[dict[str, Any], np.ndarray]],
                   shared: list[str], fixed: Mapping[str, float]) -> _Problem:
    names = [k for k in law.param_names if k not in fixed]
    data, weights = [], []
    for _, mask in groups:
        sub = ds.subset(mask)
        data.append(sub.arrays())
        w = sub.weights()
        weights.append(np.ones(len(sub)) if w is None else np.asarray(w, float))
    settings = {**law.setting_values, **{k: v for k, v in fixed.items()}}
    return _Problem(law, names, shared, data, weights, settings)


def _start(problem: _Problem, separate: list[Any]) -> np.ndarray:
    shared = [float(np.median([r.params[k].value for r in separate])) for k in problem.shared]
    own = [r.params[k].value for r in separate for k in problem.own]
    return np.array(shared + own, dtype=float)


def _solve(problem: _Problem, by: tuple[str, ...],
           groups: list[tuple[dict[str, Any], np.ndarray]], separate: list[Any]) -> SharedFit:
    lo, hi = problem.bounds()
    x0 = np.clip(_start(problem, separate), lo, hi)
    sol = least_squares_solve(problem.residual, x0, bounds=(lo, hi), x_scale="jac",
                        max_nfev=2000 * x0.size)
    if not np.all(np.isfinite(sol.x)):
        raise FitError(f"the shared fit of '{problem.law.id}' did not converge: {sol.message}")
    n = sum(d["mu"].size for d in problem.data)
    rss = float(np.sum(sol.fun**2))
    stderr, warns = _stderr(sol.jac, rss, n, _labels(problem, groups), sol.x)
    out_groups = _group_records(problem, groups, sol.x, stderr)
    comparison = _compare(rss, sol.x.size, separate, n)
    return SharedFit(problem.law.id, by, tuple(problem.shared), out_groups, comparison,
                     bool(sol.success), str(sol.message), warns)


def _labels(problem: _Problem, groups: list[tuple[dict[str, Any], np.ndarray]]) -> list[str]:
    """A name per entry of the stacked parameter vector: ``b`` shared, ``a[steel]`` own."""
    return problem.shared + [f"{k}[{key_text(key)}]" for key, _ in groups for k in problem.own]


def _stderr(jac: np.ndarray, rss: float, n: int, labels: list[str], theta: np.ndarray
            ) -> tuple[np.ndarray, list[str]]:
    """Asymptotic standard errors of the stacked parameters (NaN where withheld).

    The rules of :func:`frictionlaws.fit` hold: no errors without more rows than
    parameters, none for parameters the data cannot determine (rank-deficient
    Jacobian; a pseudo-inverse would give them a number), none that come out as zero
    to rounding.
    """
    k = jac.shape[1]
    dof = n - k
    if dof <= 0:
        return np.full(k, np.nan), [f"{n} points for {k} parameters: no standard errors"]
    non_id = set(_identifiability(np.asarray(jac, float), labels)[0])
    keep = [j for j, lab in enumerate(labels) if lab not in non_id]
    se = np.full(k, np.nan)
    warns = ([f"the data cannot determine {', '.join(x for x in labels if x in non_id)} "
              "(Jacobian rank deficient): their standard errors are withheld"]
             if non_id else [])
    if keep:
        sub = jac[:, keep]
        try:
            cov = np.linalg.inv(sub.T @ sub) * (rss / dof)
        except np.linalg.LinAlgError:
            return se, [*warns, "singular Jacobian: no standard errors"]
        se[keep] = np.sqrt(np.maximum(np.diag(cov), 0.0))
    zero = [lab for j, lab in enumerate(labels) if se[j] <= ZERO_SPREAD * abs(theta[j])]
    if zero:
        se[[labels.index(z) for z in zero]] = np.nan
        warns.append(f"the standard error of {', '.join(zero)} comes out as 0 to rounding "
                     "(the residuals do not spread): undetermined and withheld, not zero")
    return se, warns


def _se(x: float) -> float | None:
    return float(x) if np.isfinite(x) else None


def _group_records(problem: _Problem, groups: list[tuple[dict[str, Any], np.ndarray]],
                   theta: np.ndarray, stderr: np.ndarray) -> list[dict[str, Any]]:
    s, m = len(problem.shared), len(problem.own)
    parts = problem.parts(theta)
    records = []
    for g, (key, mask) in enumerate(groups):
        values = problem.unpack(theta, g)
        params = {}
        for i, k in enumerate(problem.shared):
            params[k] = {"value": float(values[k]), "stderr": _se(stderr[i]),
                         "unit": problem.law.param(k).unit, "shared": True}
        for j, k in enumerate(problem.own):
            params[k] = {"value": float(values[k]), "stderr": _se(stderr[s + g * m + j]),
                         "unit": problem.law.param(k).unit, "shared": False}
        records.append({"key": key, "rows": int(mask.sum()), "params": params,
                        "rss": float(np.sum(parts[g] ** 2))})
    return records


def _compare(rss_shared: float, k_shared: int, separate: list[Any], n: int) -> dict[str, Any]:
    from scipy.stats import f as f_dist

    rss_sep = float(sum(_rss(r) for r in separate))
    k_sep = int(sum(sum(1 for e in r.params.values() if not e.fixed) for r in separate))
    df1, df2 = k_sep - k_shared, n - k_sep
    if df1 <= 0 or df2 <= 0 or rss_sep <= 0:
        F, p = math.nan, math.nan
    else:
        F = max((rss_shared - rss_sep) / df1, 0.0) / (rss_sep / df2)
        p = float(f_dist.sf(F, df1, df2))
    aic_sh = n * math.log(max(rss_shared, 1e-300) / n) + 2 * k_shared
    aic_sep = n * math.log(max(rss_sep, 1e-300) / n) + 2 * k_sep
    verdict = ("sharing is supported (p >= 0.05)" if not p < 0.05
               else "the groups differ in the shared parameters (p < 0.05)")
    return {"rss_shared": rss_shared, "rss_separate": rss_sep, "k_shared": k_shared,
            "k_separate": k_sep, "n": n, "F": F, "p_value": p, "aic_shared": aic_sh,
            "aic_separate": aic_sep, "delta_aic": aic_sh - aic_sep, "verdict": verdict}


def _rss(result: Any) -> float:
    resid = getattr(result, "residual", None)
    if resid is not None:
        return float(np.sum(np.asarray(resid, float) ** 2))
    return float(result.metrics.get("chi2", math.nan))
