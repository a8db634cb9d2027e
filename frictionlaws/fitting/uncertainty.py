"""Robust uncertainty glue: sandwich and bootstrap standard errors applied to a fit's
estimates, intervals cut at the parameters' bounds, the warnings they raise.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..law import Law
from .data import FitData, _condition_vars
from .diagnosis import RANK_TOL, _clip_interval, _derived
from .resampling import cannot_vary, withheld_message
from .result import ParamEstimate, _numpy_ns
from .robust import (
    NARROW_RATIO,
    Refit,
    bootstrap,
    condition_ids,
    derived_samples,
    intervals,
    rank,
    residual_structure,
    sandwich_cov,
)

__all__ = ["structure_record", "structure_warning"]


@dataclass
class _ErrorInputs:
    """What the robust error methods need from a finished fit."""

    law: Law
    fd: FitData
    x: dict[str, np.ndarray]
    y: np.ndarray
    w: np.ndarray | None
    vary: list[str]
    values: dict[str, float]
    bounds: dict[str, tuple[float, float]]
    jac: np.ndarray
    resid: np.ndarray
    non_id: list[str]
    tval: float

    @property
    def weighted_resid(self) -> np.ndarray:
        return self.resid * (self.w if self.w is not None else 1.0)


def _robust_errors(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                   derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                   warn_msgs: list[str], opts: dict[str, Any]) -> dict[str, Any]:
    """Replace the asymptotic errors by the requested method's; warn when they are too narrow.

    ``estimates``, ``derived``, ``corr`` and ``warn_msgs`` are updated in place; the
    returned record says which method was used (kept by :meth:`FitResult.to_dict`).
    """
    method = opts["method"]
    info: dict[str, Any] = {"method": method}
    asym = {k: estimates[k].stderr for k in inp.vary if k in estimates}
    structure = residual_structure(inp.weighted_resid, inp.fd.arrays, _condition_vars(inp.fd))
    if structure is not None:
        info["residual_structure"] = structure_record(structure)
    if not math.isfinite(inp.tval):  # as many parameters as rows: no method has errors
        if method != "asymptotic":
            warn_msgs.append(f"{method} standard errors need more rows than fitted "
                             "parameters: none are given")
            info["method"] = "asymptotic"
    elif method == "asymptotic" or not inp.vary or (inp.non_id and method == "sandwich"):
        if method != "asymptotic":
            warn_msgs.append(f"{method} standard errors need every fitted parameter to be "
                             "identifiable; the asymptotic ones (where available) are shown"
                             + ("; the bootstrap gives those of the identifiable ones"
                                if method == "sandwich" else ""))
            info["method"] = "asymptotic"
    elif method == "sandwich":
        if not _apply_sandwich(inp, estimates, derived, corr, warn_msgs):
            info["method"] = "asymptotic"
    else:
        info.update(_apply_bootstrap(inp, estimates, derived, corr, warn_msgs, opts))
    if info["method"] != "bootstrap" and structure is not None and structure.significant:
        warn_msgs.append(structure_warning(structure, info["method"]))
    _warn_if_narrow(info["method"], asym, estimates, warn_msgs)
    info["asymptotic_stderr"] = asym
    return info


def structure_record(structure: Any) -> dict[str, Any]:
    """What a result keeps of the residual structure found (:class:`~frictionlaws.
    uncertainty.Structure`)."""
    return {"variable": structure.variable, "test": structure.test,
            "statistic": structure.statistic, "p_value": structure.p_value,
            "n_tests": structure.n_tests}


def structure_warning(structure: Any, method: str) -> str:
    """The warning of significant residual structure under the ``method`` errors."""
    return (f"{structure.describe()}: the law misses a trend, so the {method} "
            "standard errors are likely too narrow; the bootstrap method (uncertainty "
            "'bootstrap'), which resamples whole conditions, gives honest ones")


def _warn_if_narrow(method: str, asym: Mapping[str, float | None],
                    estimates: Mapping[str, ParamEstimate], warn_msgs: list[str]) -> None:
    """Warn when a robust method's errors exceed the asymptotic ones by > NARROW_RATIO."""
    if method == "asymptotic":
        return
    ratios = {k: se / a for k, a in asym.items()
              if a and a > 0 and (se := estimates[k].stderr) is not None}
    wide = {k: r for k, r in ratios.items() if r > NARROW_RATIO}
    if wide:
        shown = ", ".join(f"{k} x{r:.2g}" for k, r in wide.items())
        warn_msgs.append(f"the {method} standard errors exceed the asymptotic ones by more "
                         f"than {NARROW_RATIO}x ({shown}): the asymptotic errors are too "
                         f"narrow for these data; the {method} values are reported")


def _set_errors(inp: _ErrorInputs, estimates: dict[str, ParamEstimate], se: np.ndarray,
                ci: np.ndarray) -> list[str]:
    """Store the method's standard errors and intervals of the fitted parameters.

    A parameter the method cannot give an error for (not finite, or zero) has its
    error withheld rather than left at another method's; its name is returned.
    """
    withheld = []
    for j, k in enumerate(inp.vary):
        if k in inp.non_id:  # withheld whatever the method
            continue
        if math.isfinite(se[j]) and se[j] > 0 and np.all(np.isfinite(ci[j])):
            estimates[k] = replace(estimates[k], stderr=float(se[j]),
                                   ci95=(float(ci[j, 0]), float(ci[j, 1])))
        else:
            estimates[k] = replace(estimates[k], stderr=None, ci95=None)
            withheld.append(k)
    return withheld


def _set_corr(names: list[str], cov: np.ndarray, corr: dict[str, dict[str, float]]) -> None:
    sd = np.sqrt(np.clip(np.diag(cov), 0, None))
    with np.errstate(all="ignore"):
        cm = cov / np.outer(sd, sd)
    corr.clear()
    for i, a in enumerate(names):
        corr[a] = {b: float(cm[i, j]) for j, b in enumerate(names)}


def _apply_sandwich(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                    derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                    warn_msgs: list[str]) -> bool:
    """HC3 sandwich errors for the parameters and (delta method) the derived quantities.

    False (the asymptotic errors stay) when the sandwich cannot be computed.
    """
    cov = sandwich_cov(inp.jac, inp.weighted_resid)
    if cov is None:
        warn_msgs.append("the sandwich covariance could not be computed (singular Jacobian); "
                         "the asymptotic standard errors are shown")
        return False
    se = np.sqrt(np.clip(np.diag(cov), 0, None))
    theta = np.array([inp.values[k] for k in inp.vary])
    ci = np.array([_clip_interval(k, (t - inp.tval * e, t + inp.tval * e), inp.bounds[k],
                                  warn_msgs) if math.isfinite(e) and e > 0 else (math.nan,) * 2
                   for k, t, e in zip(inp.vary, theta, se)]).reshape(-1, 2)
    withheld = _set_errors(inp, estimates, se, ci)
    if withheld:
        warn_msgs.append(f"the sandwich covariance gives no standard error for "
                         f"{', '.join(withheld)} (zero or not finite: the residuals do not "
                         "tell it); it is withheld")
    _set_corr(inp.vary, cov, corr)
    derived.update(_derived(inp.law, inp.values, inp.vary, cov, inp.non_id))
    return True


def _apply_bootstrap(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                     derived: dict[str, dict[str, Any]], corr: dict[str, dict[str, float]],
                     warn_msgs: list[str], opts: dict[str, Any]) -> dict[str, Any]:
    """Condition-resampling bootstrap errors and intervals, parameters and derived alike."""
    lower = np.array([inp.bounds[k][0] for k in inp.vary], float)
    upper = np.array([inp.bounds[k][1] for k in inp.vary], float)
    full_rank = rank(inp.jac, RANK_TOL)
    refit = Refit(inp.law, dict(inp.values), list(inp.vary), lower, upper, inp.x, inp.y, inp.w,
                  RANK_TOL, full_rank)
    groups = condition_ids(inp.fd.arrays, _condition_vars(inp.fd), inp.fd.conditions)
    n_cond = int(np.unique(groups).size)
    if n_cond <= full_rank or cannot_vary([n_cond], unit="test condition"):
        return _bootstrap_refused(inp, estimates, derived, warn_msgs, opts, n_cond)
    theta = np.array([inp.values[k] for k in inp.vary])
    boot = bootstrap(refit, theta, groups, n_boot=opts["n_boot"], seed=opts["seed"],
                     n_jobs=opts["n_jobs"], jackknife=opts["interval"] == "bca")
    se, ci, used = intervals(boot.samples, theta, boot.jackknife, kind=opts["interval"])
    withheld = _set_errors(inp, estimates, se, ci)
    if withheld:
        warn_msgs.append(withheld_message("the bootstrap", withheld))
    ok = np.all(np.isfinite(boot.samples), axis=1)
    if ok.sum() > len(inp.vary) and not inp.non_id:
        _set_corr(inp.vary, np.cov(boot.samples[ok].T).reshape(len(inp.vary), -1), corr)
    if inp.law.derived and not inp.non_id:
        funcs = {d.name: (lambda vals, d=d: d.value(vals, _numpy_ns()))
                 for d in inp.law.derived}
        hat = np.array([derived[k]["value"] for k in funcs], float)
        dse, dci, _ = intervals(derived_samples(funcs, inp.values, inp.vary, boot.samples),
                                hat, derived_samples(funcs, inp.values, inp.vary,
                                                     boot.jackknife), kind=opts["interval"])
        for j, k in enumerate(funcs):
            finite = math.isfinite(dse[j]) and bool(np.all(np.isfinite(dci[j])))
            derived[k] = {**derived[k], "stderr": float(dse[j]) if finite else None,
                          "ci95": [float(dci[j, 0]), float(dci[j, 1])] if finite else None}
    if boot.failed > 0.1 * opts["n_boot"]:
        warn_msgs.append(f"{boot.failed} of {opts['n_boot']} bootstrap refits failed or "
                         "could not determine every parameter (resamples of too few "
                         "distinct conditions); the bootstrap errors rest on the others")
    if boot.n_groups < 8:
        warn_msgs.append(f"the bootstrap resamples only {boot.n_groups} conditions: its "
                         "errors and intervals are coarse")
    return {"n_boot": opts["n_boot"], "seed": opts["seed"], "interval": used,
            "conditions": boot.n_groups, "failed": boot.failed}


def _bootstrap_refused(inp: _ErrorInputs, estimates: dict[str, ParamEstimate],
                       derived: dict[str, dict[str, Any]], warn_msgs: list[str],
                       opts: dict[str, Any], n_cond: int) -> dict[str, Any]:
    """No bootstrap with no more conditions than parameters: every error withheld.

    Each resample of so few conditions either cannot determine the parameters or
    repeats the full fit, so its spread would read as an error of zero.
    """
    for k in inp.vary:
        estimates[k] = replace(estimates[k], stderr=None, ci95=None)
    for k in derived:
        derived[k] = {**derived[k], "stderr": None, "ci95": None}
    reason = cannot_vary([n_cond], unit="test condition")
    why = (f"it cannot vary ({reason})" if reason else
           f"it needs more test conditions than the parameters they determine ({n_cond} "
           f"conditions, {len(inp.vary)} parameters)")
    warn_msgs.append(f"the bootstrap gives no standard errors: {why}; they are undetermined "
                     "and withheld, not zero (the asymptotic ones are kept in "
                     "uncertainty.asymptotic_stderr)")
    return {"n_boot": opts["n_boot"], "seed": opts["seed"], "interval": None,
            "conditions": n_cond, "failed": None}

