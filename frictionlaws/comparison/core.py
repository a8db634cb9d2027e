"""Compare friction laws on one dataset: :func:`compare` and :class:`Comparison`.

For every law that can be fitted to the data, :func:`compare` reports

* the fit itself (:func:`frictionlaws.fitting.fit`): k, R^2, adjusted R^2,
  RMSE, MAE, max |residual|, AIC, AICc, BIC, identifiability warnings;
* **Akaike weights** from AICc (Burnham and Anderson recommend AICc whenever
  n/k < 40, which tribometer datasets always are; AIC is used when AICc is
  undefined, n <= k + 1).  AIC compares likelihoods of the *same* rows, so
  weights are computed only among laws fitted to identical rows: a law that
  dropped rows (v = 0 in a log-velocity law) forms its own group, and the
  report says so;
* the **k-fold cross-validated RMSE** (:mod:`.cv`, seeded, reproducible);
* the **extrapolation RMSE** on the upper part of the pressure and velocity
  ranges held out, and a **plausibility scan** over an extended box
  (:mod:`.extrapolation`);
* **residual structure** tests (:mod:`.residuals`).

Ranking: by cross-validated RMSE, the error on rows a law has not seen, which
neither rewards extra parameters the way R^2 does nor needs the likelihood
assumptions of AIC.  When the laws were fitted to different rows (a
log-velocity law cannot use the v = 0 rows), their CV RMSEs over their own rows
are not comparable: the ranking then uses ``cv_rmse_common``, the CV RMSE over
the rows *every* fitted law could use (each law's out-of-fold predictions of
those rows; laws fitted to more rows trained on them too, which is their
advantage).  Both numbers are reported.  Laws with parameters the data cannot
determine (named by the fitter) come after the identifiable ones, whatever
their CV RMSE: their parameters mean nothing, and their CV scores depend on
where the optimiser happened to stop.  Laws whose cross-validation is
incomplete (a fold could not be fitted) come after the complete ones, and laws
without a CV RMSE come last; ties go to the law with fewer parameters, then to
the id.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..errors import DomainError, FitError, InputError
from ..fitting import FitData, FitResult, as_fit_data, fit
from ..jsonio import dumps as _dumps
from ..law import VARIABLES, Law
from ..registry import get_law, list_laws
from .cv import CVResult, cross_validate, error_text, kfold_assignment
from .extrapolation import (
    MU_LIMITS,
    TREND_ALPHA,
    TREND_REL,
    TREND_TOL,
    Design,
    HoldoutResult,
    Plausibility,
    Split,
    Trend,
    data_trends,
    design_of,
    extended_box,
    fmt_value,
    holdout_splits,
    parse_holdout,
    scan_plausibility,
    score_holdout,
)
from .residuals import ResidualAnalysis, analyse_residuals

__all__ = ["compare", "Comparison", "LawComparison", "usable_rows", "COMPARISON_FORMAT"]

COMPARISON_FORMAT = "frictionlaws-comparison"
COMPARISON_VERSION = 1
RANKING = ("cross-validated RMSE (ascending), over the rows common to all fitted laws when "
           "they were fitted to different rows; laws with parameters the data cannot determine "
           "after identifiable ones, laws with incomplete cross-validation after complete ones, "
           "laws without a CV RMSE last; ties: fewer parameters, then id")


def usable_rows(law: Law, data: FitData) -> np.ndarray:
    """Rows where ``law`` is defined: the rule of ``fit(on_invalid="drop")``.

    A row is unusable when a variable the law floors (it takes its log or a
    negative power) is at or below its floor (``|v|`` for the velocity).
    """
    ok = np.ones(data.n, dtype=bool)
    for var, floor in law.floors.items():
        if var in data.arrays:
            x = data.arrays[var]
            ok &= (np.abs(x) if var == "v" else x) > floor
    return ok


@dataclass
class LawComparison:
    """Everything :func:`compare` found out about one fitted law."""

    law: Law
    fit: FitResult
    rows: np.ndarray
    notes: list[str]
    cv: CVResult
    holdouts: list[HoldoutResult]
    extrapolation_rmse: float
    plausibility: Plausibility
    residuals: ResidualAnalysis
    akaike_weight: float | None = None
    weight_basis: str = "aicc"
    aic_group: int = 0
    aic_group_size: int = 1
    rank: int = 0
    cv_rmse_common: float = math.nan
    extra_notes: list[str] = field(default_factory=list)

    @property
    def id(self) -> str:
        return self.law.id

    @property
    def metrics(self) -> dict[str, Any]:
        return self.fit.metrics

    @property
    def plausible(self) -> bool:
        return self.plausibility.plausible

    @property
    def n_dropped(self) -> int:
        return int(self.rows.size - self.rows.sum())

    def to_dict(self) -> dict[str, Any]:
        m = self.fit.metrics
        return {
            "rank": self.rank,
            "id": self.law.id,
            "title": self.law.title,
            "status": "fitted",
            "k": m["k"], "n": m["n"], "n_dropped": self.n_dropped,
            "r2": m["r2"], "adj_r2": m["adj_r2"], "rmse": m["rmse"], "mae": m["mae"],
            "max_abs_residual": m["max_abs_residual"],
            "aic": m["aic"], "aicc": m["aicc"], "bic": m["bic"],
            "akaike_weight": self.akaike_weight,
            "akaike_weight_basis": self.weight_basis,
            "aic_group": self.aic_group, "aic_group_size": self.aic_group_size,
            "cv_rmse": self.cv.rmse,
            "cv_rmse_common": self.cv_rmse_common,
            "cv": self.cv.to_dict(),
            "extrapolation_rmse": self.extrapolation_rmse,
            "extrapolation": [h.to_dict() for h in self.holdouts],
            "plausible": self.plausible,
            "plausibility_reasons": self.plausibility.reasons,
            "plausibility": self.plausibility.to_dict(),
            "converged": self.fit.success,
            "warnings": list(self.fit.warnings),
            "non_identifiable": list(self.fit.non_identifiable),
            "residual_tests": self.residuals.to_dict(),
            "residual_structure": list(self.residuals.structure),
            "notes": list(self.notes) + list(self.extra_notes),
            "params": {k: p.to_dict() for k, p in self.fit.params.items()},
            "settings": dict(self.fit.settings),
        }


@dataclass
class Comparison:
    """The result of :func:`compare`: ranked laws, skipped and failed laws, settings.

    ``results`` is in rank order (best first).  :meth:`table` is the console
    table, :meth:`to_dict`/:meth:`to_json` the machine-readable form,
    :meth:`write_report` the HTML/Markdown/PNG report.
    """

    data: FitData
    results: list[LawComparison]
    skipped: list[dict[str, str]]
    failed: list[dict[str, str]]
    design: Design
    trends: dict[str, Trend]
    box: dict[str, tuple[float, float]]
    splits: list[Split]
    folds: np.ndarray
    settings: dict[str, Any]
    notes: list[str] = field(default_factory=list)

    def __getitem__(self, law_id: str) -> LawComparison:
        key = get_law(law_id).id
        for r in self.results:
            if r.law.id == key:
                return r
        raise KeyError(law_id)

    @property
    def ranking(self) -> list[str]:
        """Law ids, best first."""
        return [r.law.id for r in self.results]

    @property
    def best(self) -> LawComparison | None:
        return self.results[0] if self.results else None

    def dataset_info(self) -> dict[str, Any]:
        """Name, source, rows and the ranges of the variables (SI and display units)."""
        variables = {}
        for k, x in self.data.arrays.items():
            if k not in VARIABLES:
                continue
            v = VARIABLES[k]
            variables[k] = {"unit": v.unit or "-", "meaning": v.meaning,
                            "min": float(np.min(x)), "max": float(np.max(x)),
                            "distinct": int(np.unique(x).size),
                            "range_display": f"{fmt_value(k, float(np.min(x)))} .. "
                                             f"{fmt_value(k, float(np.max(x)))}"}
        mu = self.data.arrays["mu"]
        return {"name": self.data.name, "source": self.data.source, "n": self.data.n,
                "mu": {"unit": "-", "min": float(np.min(mu)), "max": float(np.max(mu))},
                "variables": variables, "weighted": self.data.weights is not None,
                "notes": list(self.data.notes), "design": self.design.to_dict(),
                "trends": {k: t.to_dict() for k, t in self.trends.items()}}

    def to_dict(self) -> dict[str, Any]:
        """A JSON-able dict: dataset, units, settings, ranked laws, skipped, failed."""
        units = {"mu": "-", **{k: (v.unit or "-") for k, v in VARIABLES.items()}}
        units.update({m: "-" for m in ("r2", "adj_r2", "rmse", "mae", "max_abs_residual",
                                        "cv_rmse", "extrapolation_rmse", "akaike_weight")})
        units.update({m: "- (log-likelihood based, compare within a group)"
                      for m in ("aic", "aicc", "bic")})
        return {
            "format": COMPARISON_FORMAT,
            "version": COMPARISON_VERSION,
            "dataset": self.dataset_info(),
            "units": units,
            "settings": self.settings,
            "ranking": self.ranking,
            "laws": [r.to_dict() for r in self.results],
            "skipped": list(self.skipped),
            "failed": list(self.failed),
            "notes": list(self.notes),
        }

    def to_json(self, indent: int = 2) -> str:
        """JSON text of :meth:`to_dict` (non-finite numbers become null)."""
        return _dumps(self.to_dict(), indent=indent)

    def to_frame(self) -> Any:
        """One row per ranked law: rank, metrics, CV and extrapolation RMSE, flags."""
        import pandas as pd

        cols = ("rank", "id", "k", "n", "r2", "rmse", "aic", "bic", "cv_rmse",
                "extrapolation_rmse", "akaike_weight", "plausible", "converged")
        rows = [{c: r.to_dict()[c] for c in cols} for r in self.results]
        frame = pd.DataFrame(rows, columns=list(cols)).rename(columns={"id": "law"})
        frame.attrs["units"] = "mu, rmse, cv_rmse, extrapolation_rmse: - (dimensionless)"
        return frame

    def _repr_html_(self) -> str:
        from ..interop import table_html

        rows = self.to_frame().to_dict("records")
        return table_html(rows, caption=f"laws compared on {self.data.name} "
                                        f"({self.data.n} rows), best first")

    def table(self) -> str:
        """The ranked console table with the flags, skipped and failed laws."""
        from .report import format_table

        return format_table(self)

    def __str__(self) -> str:
        return self.table()

    def write_report(self, directory: str | Path) -> dict[str, Path]:
        """Write ``report.html``, ``report.md``, ``comparison.json`` and the PNG figures.

        Returns a dict name -> path of what was written.
        """
        from .report import write_report

        return write_report(self, directory)


# ----------------------------------------------------------------- compare


def default_family(fd: FitData) -> str:
    """The family a dataset calls for: ``"slip"`` for tyre-like slip data.

    Slip laws need the slip ratio s of a rolling wheel, 0 <= s <= 1, varying
    from row to row.  Pin-on-disc records carry s too (a fixed pin gives
    s = 1, a counter-rotating pin 1 < s <= 2): that is sliding data.
    """
    if "s" not in fd.variables:
        return "sliding"
    s = fd.arrays["s"]
    rolling = bool(np.all((s >= 0) & (s <= 1)) and np.unique(s).size > 1)
    return "slip" if rolling and "p" not in fd.variables else "sliding"


def _select_laws(laws: Any, family: str | None, fd: FitData
                 ) -> tuple[list[Law], list[dict[str, str]], str]:
    if laws is not None and family is not None:
        raise InputError("give either laws or a family, not both")
    if laws is not None:
        if isinstance(laws, (str, Law)):
            laws = [laws] if isinstance(laws, Law) else [s for s in laws.split(",") if s.strip()]
        chosen = []
        for name in laws:
            law = get_law(name.strip() if isinstance(name, str) else name)
            if law in chosen:  # a name given twice is an error (an alias counts as its law)
                raise InputError(f"law '{law.id}' is given twice", option="laws")
            chosen.append(law)
        if not chosen:
            raise InputError("no law given")
        what = "the laws asked for"
    else:
        if family is None:
            family = default_family(fd)
        chosen = list_laws(family)
        what = f"the {family} laws"
    ok, skipped = [], []
    for law in chosen:
        try:
            law.require_variables(fd.variables, f"data '{fd.name}'")
        except DomainError as exc:
            skipped.append({"id": law.id, "title": law.title, "reason": str(exc)})
            continue
        ok.append(law)
    return ok, skipped, what


def _progress(total: int, enabled: bool | None) -> Any:
    from tqdm import tqdm

    disable = (not sys.stderr.isatty()) if enabled is None else not enabled
    return tqdm(total=total, desc="compare", unit="fit", disable=disable, leave=False,
                file=sys.stderr)


def _akaike(results: list[LawComparison]) -> None:
    groups: dict[bytes, list[LawComparison]] = {}
    for r in results:
        groups.setdefault(np.packbits(r.rows).tobytes(), []).append(r)
    ordered = sorted(groups.values(), key=lambda g: (-int(g[0].rows.sum()), g[0].law.id))
    for gi, members in enumerate(ordered, start=1):
        aicc = np.array([m.fit.metrics["aicc"] for m in members], float)
        basis = "aicc"
        if not np.all(np.isfinite(aicc)):
            aicc = np.array([m.fit.metrics["aic"] for m in members], float)
            basis = "aic"
        finite = np.isfinite(aicc)
        w = np.full(aicc.size, np.nan)
        if finite.any():
            d = aicc[finite] - aicc[finite].min()
            e = np.exp(-0.5 * d)
            w[finite] = e / e.sum()
        for m, wi in zip(members, w):
            m.akaike_weight = float(wi) if np.isfinite(wi) else None
            m.weight_basis = basis
            m.aic_group = gi
            m.aic_group_size = len(members)


def _rank_key(r: LawComparison) -> tuple[Any, ...]:
    cv = r.cv_rmse_common
    bad = not math.isfinite(cv)
    return (bad, bool(r.fit.non_identifiable), not r.cv.complete, math.inf if bad else cv,
            r.fit.metrics["k"], r.law.id)


def compare(
    laws: str | Law | Iterable[str | Law] | None = None,
    data: Any = None,
    *,
    family: str | None = None,
    folds: int = 5,
    holdout: float | str | Mapping[str, float] | None = 0.3,
    seed: int = 0,
    starts: int | None = None,
    weights: Any = "auto",
    mu_limits: Sequence[float] = MU_LIMITS,
    mapping: Mapping[str, str] | None = None,
    units: Mapping[str, str] | None = None,
    area: Any = None,
    progress: bool | None = None,
) -> Comparison:
    """Fit and compare several laws on one dataset.

    Parameters
    ----------
    laws : str, Law or iterable, optional
        Law ids/aliases (a comma-separated string is accepted) or laws.  None
        takes every law of ``family``.  Laws the data cannot feed (a law
        needing T on data without temperature) are listed in
        :attr:`Comparison.skipped` with the reason, never silently left out.
    data : str, path, Dataset, DataFrame, mapping or FitData
        Anything :func:`frictionlaws.fitting.as_fit_data` accepts (a packaged
        dataset name such as ``"thesis-steel"``, a CSV path, SI arrays).
    family : {"sliding", "slip"}, optional
        The family to take when ``laws`` is None; by default
        :func:`default_family`: ``"slip"`` for rolling-wheel slip data (s
        varying within 0..1, no contact pressure), else ``"sliding"``.
    folds : int
        Number of cross-validation folds (at most the number of rows; more is
        reduced to leave-one-out with a note).
    holdout : float, str or mapping, optional
        Fraction of the upper range held out for the extrapolation test: a
        number applies to p and v; ``"p=0.3,v=0.2"`` or ``{"p": 0.3}`` per
        variable; None or 0 for none.
    seed : int
        Seed of the folds and of the fits' random starts: the same seed gives
        identical results.
    starts : int, optional
        Random starts per non-linear fit (default: the fitter's own rule).
    weights : {"auto"}, None or array
        As in :func:`~frictionlaws.fitting.fit`.  CV and extrapolation errors
        are unweighted.
    mu_limits : (float, float)
        Physical limits of mu in the plausibility scan (default 0 and 5).
    mapping : mapping or str, optional
        Canonical column -> the user's column, for reading a user's file, as in
        :func:`~frictionlaws.io.load_dataset`.
    units : mapping or str, optional
        Units of columns whose header has none, as in
        :func:`~frictionlaws.io.load_dataset`.
    area : str or float, optional
        Nominal contact area (``"314.16 mm^2"`` or a float in m^2) to derive
        the pressure from the normal load, as in
        :func:`~frictionlaws.io.load_dataset`.
    progress : bool, optional
        Show a tqdm progress bar; by default only when stderr is a terminal.

    Returns
    -------
    Comparison
        The fitted laws in rank order (best first, by cross-validated RMSE),
        each with its fit, cross-validation, extrapolation (hold-out) errors,
        plausibility scan, residual tests and Akaike weight; the laws skipped
        (with the reason) and those whose fit failed (with the error); the
        settings and notes.

    Raises
    ------
    InputError
        Bad data or options, unknown law names, or no law that can be fitted.
    FitError
        When every candidate law failed to fit.
    """
    if data is None:
        raise InputError("no data given to compare the laws on")
    fd = as_fit_data(data, mapping=mapping, units=units, area=area, weights=weights)
    if fd.n < 3:
        raise InputError(f"data '{fd.name}' has {fd.n} rows; a comparison needs at least 3")
    if isinstance(folds, bool) or not isinstance(folds, (int, np.integer)):
        raise InputError(f"folds must be a whole number, not {folds!r}", option="folds")
    if folds < 2:
        raise InputError(f"folds must be at least 2, not {folds}", option="folds")
    from ..fitting import _check_options

    _check_options("least_squares", starts, seed, "error")  # the fit's rule for starts, seed
    lims = tuple(float(x) for x in mu_limits)
    if len(lims) != 2 or not lims[0] < lims[1] or not np.isfinite(lims).all():
        raise InputError(f"the plausible range of mu must be finite with low < high, got {lims}",
                         option="mu_limits")
    notes: list[str] = []
    if folds > fd.n:
        notes.append(f"{folds} folds asked for but the data have {fd.n} rows: "
                     f"leave-one-out ({fd.n} folds) used")
        folds = fd.n
    fractions = parse_holdout(holdout)
    candidates, skipped, what = _select_laws(laws, family, fd)
    if not candidates:
        reasons = "; ".join(s["reason"] for s in skipped)
        raise InputError(f"none of {what} can be fitted to data '{fd.name}': {reasons}")

    design = design_of(fd)
    trends = data_trends(fd, design)
    box = extended_box(fd, design)
    splits = holdout_splits(fd, fractions, design)
    active = [s for s in splits if s.usable]
    assign = kfold_assignment(fd.n, folds, seed)
    fit_kw: dict[str, Any] = {"seed": seed, "starts": starts}

    results: list[LawComparison] = []
    failed: list[dict[str, str]] = []
    bar = _progress(len(candidates) * (1 + folds + len(active)), progress)
    try:
        for law in candidates:
            bar.set_postfix_str(law.id)
            rows = usable_rows(law, fd)
            try:
                res = fit(law, fd, on_invalid="drop", **fit_kw)
            except Exception as exc:  # noqa: BLE001 - any law may fail; list it, go on
                failed.append({"id": law.id, "title": law.title, "error": error_text(exc)})
                bar.update(1 + folds + len(active))
                continue
            bar.update(1)
            if res.metrics["n"] != int(rows.sum()):  # pragma: no cover - internal check
                raise RuntimeError(f"row bookkeeping mismatch for law '{law.id}'")
            law_notes = [n for n in res.notes if n not in fd.notes]
            cv = cross_validate(law, fd, rows, assign, fit_kwargs=fit_kw,
                                step=lambda: bar.update(1))
            holds = []
            for split in active:
                holds.append(score_holdout(law, fd, rows, split, fit_kwargs=fit_kw))
                bar.update(1)
            errs = [h for h in holds if h.error is None]
            n_err = sum(h.n_test for h in errs)
            extra = []
            if errs and n_err:
                sq = sum(h.rmse**2 * h.n_test for h in errs)
                ex_rmse = math.sqrt(sq / n_err) if math.isfinite(sq) else math.inf
            else:
                ex_rmse = math.nan
            for h in holds:
                if h.error is not None:
                    extra.append(f"extrapolation test along {h.variable}: {h.error}")
            for f in cv.failed:
                extra.append(f"cross-validation fold {f['fold']} ({f['n_train']} training "
                             f"rows): {f['error']}")
            plaus = scan_plausibility(law, res.values, fd, design, box, trends, limits=lims)
            sub = fd.subset(rows)
            resid = analyse_residuals(
                res.residual, res.best_fit,
                {k: sub.arrays[k] for k in design.varying},
                describe=lambda k: "the fitted value" if k == "fitted" else k)
            results.append(LawComparison(law, res, rows, law_notes, cv, holds, ex_rmse, plaus,
                                         resid, extra_notes=extra))
    finally:
        bar.close()

    if not results:
        raise FitError(f"none of {what} could be fitted to data '{fd.name}': "
                       + "; ".join(f"{f['id']}: {f['error']}" for f in failed))
    _akaike(results)
    common = np.logical_and.reduce([r.rows for r in results])
    same_rows = all(np.array_equal(r.rows, results[0].rows) for r in results)
    if not same_rows and common.sum() < 3:
        notes.append(f"the laws were fitted to different rows and share only "
                     f"{int(common.sum())}: the ranking uses each law's CV RMSE over its own "
                     "rows, which are not strictly comparable")
        same_rows = True
    elif not same_rows:
        notes.append(f"the laws were fitted to different rows: the ranking uses the CV RMSE over "
                     f"the {int(common.sum())} rows all of them could use (cv_rmse_common)")
    for r in results:
        if same_rows:
            r.cv_rmse_common = r.cv.rmse
        else:
            pred = r.cv.predictions[common] if r.cv.predictions is not None else np.array([])
            ok = np.isfinite(pred)
            err = fd.arrays["mu"][common][ok] - pred[ok]
            r.cv_rmse_common = float(np.sqrt(np.mean(err**2))) if err.size else math.nan
    results.sort(key=_rank_key)
    for i, r in enumerate(results, start=1):
        r.rank = i
    groups = {r.aic_group for r in results}
    if len(groups) > 1:
        notes.append("the laws were fitted to different rows (some dropped rows where they "
                     "are singular): AIC, AICc, BIC and Akaike weights compare only laws of "
                     "the same group (column 'grp')")
    settings = {
        "laws": what,
        "folds": folds,
        "seed": seed,
        "starts": starts,
        "holdout": fractions,
        "holdout_rule": "rows with x > x_min + (1 - fraction)(x_max - x_min) are held out; "
                        "the law is fitted on the others and scored on them",
        "splits": [s.to_dict() for s in splits],
        "extended_box": {k: {"low": lo, "high": hi, "unit": VARIABLES[k].unit or "-",
                             "display": f"{fmt_value(k, lo)} .. {fmt_value(k, hi)}"}
                         for k, (lo, hi) in box.items()},
        "extended_box_rule": "0.5 x lowest .. 3 x highest measured value (s capped at 1; "
                             "T: 20 K below .. 20 K above); derived variables follow their "
                             "driver",
        "mu_limits": list(lims),
        "trend_tolerance": {"absolute": TREND_TOL, "relative": TREND_REL},
        "trend_rule": "beyond each end of the measured range of a variable, mu must not move "
                      "against the trend the data show toward that end by more than the "
                      "tolerance (relative to mu where the reversal starts)",
        "trend_alpha": TREND_ALPHA,
        "ranking": RANKING,
        "ranking_metric": "cv_rmse" if same_rows else "cv_rmse_common",
        "common_rows": int(common.sum()),
        "akaike_weights": "from AICc (AIC when AICc is undefined), among laws fitted to "
                          "identical rows only",
        "residual_tests": "Wald-Wolfowitz runs test (exact, one-sided: too few runs) and "
                          "Kendall tau, per variable and vs the fitted value; Shapiro-Wilk; "
                          "5 % level each, uncorrected",
        "weights": "dataset" if fd.weights is not None else "none",
    }
    return Comparison(fd, results, skipped, failed, design, trends, box, splits, assign,
                      settings, notes)

