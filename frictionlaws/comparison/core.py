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

Large data: a comparison makes ``1 + folds + hold-outs`` fits per law (96 for
the sliding family with the defaults), each with random starts, and the trend
test compares every pair of rows.  On data with more than ``max_rows`` rows
(default :data:`MAX_ROWS`) every part of the comparison (full fits, folds,
hold-outs, trends, residual tests) uses the same seeded random subsample of
``max_rows`` rows, and the notes and settings say so.  Measured on this
project's machine, the full fits alone of the sliding laws take about a minute
on 20,000 rows, so subsampling only the refits would not bound the run; the
ranking on a few thousand rows is what the extra rows would give, and the
chosen law can then be fitted to every row with :func:`frictionlaws.fitting.fit`.
Data with at most ``max_rows`` rows are compared as they are.

Ranking: by cross-validated RMSE, the error on rows a law has not seen, which
neither rewards extra parameters the way R^2 does nor needs the likelihood
assumptions of AIC.  When the laws were fitted to different rows (a
log-velocity law cannot use the v = 0 rows), their CV RMSEs over their own rows
are not comparable: the ranking then uses ``cv_rmse_common``, the CV RMSE over
the rows *every* fitted law could use (each law's out-of-fold predictions of
those rows; laws fitted to more rows trained on them too, which is their
advantage).  Both numbers are reported.  Laws with parameters the data cannot
determine (named by the fitter) come after the identifiable ones, whatever
their CV RMSE: their parameters mean nothing.  Laws whose cross-validation is
incomplete (a fold could not be fitted) come after the complete ones; ties go to
the law with fewer parameters, then to the id.

Scores are properties of the law and the data, the same under every supported
numpy and scipy: every refit is polished to its optimum
(:func:`frictionlaws.fitting.fit` with ``lean=True``), and a score whose held-out
predictions depend on parameters the refit's rows cannot determine
(:func:`.cv.undetermined_rows`) is *undetermined*: NaN here, null in JSON, "n/d" in
tables, named in the notes.  An undetermined ranking score ranks nothing: such laws
(and those without a CV RMSE) come after every scored law, by fewer parameters then
id.  A hold-out prediction outside the plausible range of mu (``mu_limits``) makes
the extrapolation RMSE "implausible" instead of entering it.  Each law's
``rank_basis`` says which of these rules placed it.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import DomainError, FitError, InputError
from ..fitting import DEFAULT_METHOD, FitData, as_fit_data, check_fit_options, fit, invalid_rows
from ..law import VARIABLES, Law
from ..law.registry import get_law, list_laws
from ..parallel import local_workers, starmap_local
from .cv import CVResult, combine_folds, error_text, kfold_assignment, score_fold
from .extrapolation import (
    MU_LIMITS,
    TREND_ALPHA,
    TREND_REL,
    TREND_TOL,
    Design,
    HoldoutResult,
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
from .residuals import analyse_residuals
from .results import COMPARISON_FORMAT, Comparison, LawComparison

__all__ = ["compare", "Comparison", "LawComparison", "usable_rows", "COMPARISON_FORMAT",
           "default_family", "MAX_ROWS", "subsample"]

#: Most rows a comparison works on; larger data are subsampled (module docstring).
MAX_ROWS = 2000

RANKING = ("cross-validated RMSE (ascending), over the rows common to all fitted laws when "
           "they were fitted to different rows; laws with parameters the data cannot determine "
           "after identifiable ones, laws with incomplete cross-validation after complete ones; "
           "laws without a determined CV RMSE (undetermined: n/d, or none) after every scored "
           "law, by fewer parameters then id; ties: fewer parameters, then id")


def usable_rows(law: Law, data: FitData) -> np.ndarray:
    """Rows where ``law`` is defined: the rule of ``fit(on_invalid="drop")``
    (:func:`frictionlaws.fitting.invalid_rows`: a floored variable at its floor, a
    variable outside a strict domain).
    """
    return ~invalid_rows(law, data.arrays, data.n)[0]


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
    """Scored laws first (identifiable, then complete CV, then by score); unscored laws
    after them by fewer parameters then id, whatever their other numbers."""
    cv = r.cv_rmse_common
    if not math.isfinite(cv):
        return (True, False, False, 0.0, r.fit.metrics["k"], r.law.id)
    return (False, bool(r.fit.non_identifiable), not r.cv.complete, cv,
            r.fit.metrics["k"], r.law.id)


def _rank_basis(r: LawComparison, label: str, rows: np.ndarray, assign: np.ndarray) -> str:
    """Why ``r`` ranks where it does: its ranking score, or why it has none (short)."""
    cv = r.cv_rmse_common
    if math.isfinite(cv):
        parts = [f"{label} {cv:.6g}"]
        if r.fit.non_identifiable:
            parts.insert(0, "not identifiable")
        if not r.cv.complete:
            parts.insert(0, "CV incomplete")
        return "; ".join(parts)
    und = r.cv.undetermined_mask
    if und is not None and np.any(und & rows):
        folds = ", ".join(str(int(f) + 1) for f in np.unique(assign[und & rows]))
        return f"unscored: {label} n/d (fold {folds})"
    return f"unscored: no {label}"


def _check_options(fd: FitData, folds: Any, mu_limits: Sequence[float], jobs: Any
                   ) -> tuple[int, tuple[float, float], list[str]]:
    """Checked folds, limits of mu and the notes they call for (folds beyond the rows)."""
    if fd.n < 3:
        raise InputError(f"data '{fd.name}' has {fd.n} rows; a comparison needs at least 3")
    if isinstance(folds, bool) or not isinstance(folds, (int, np.integer)):
        raise InputError(f"folds must be a whole number, not {folds!r}", option="folds")
    if folds < 2:
        raise InputError(f"folds must be at least 2, not {folds}", option="folds")
    if isinstance(jobs, bool) or not isinstance(jobs, (int, np.integer)) or not (
            jobs >= 1 or jobs == -1):
        raise InputError(f"jobs must be a whole number >= 1, or -1 for one per core, not "
                         f"{jobs!r}", option="jobs")
    lims = tuple(float(x) for x in mu_limits)
    if len(lims) != 2 or not lims[0] < lims[1] or not np.isfinite(lims).all():
        raise InputError(f"the plausible range of mu must be finite with low < high, got {lims}",
                         option="mu_limits")
    notes: list[str] = []
    if folds > fd.n:
        notes.append(f"{folds} folds asked for but the data have {fd.n} rows: "
                     f"leave-one-out ({fd.n} folds) used")
        folds = fd.n
    return int(folds), (lims[0], lims[1]), notes


def subsample(fd: FitData, max_rows: int | None, seed: int) -> tuple[FitData, str | None]:
    """At most ``max_rows`` rows of ``fd``, drawn at random (seeded), in their order.

    Parameters
    ----------
    fd : FitData
        The data.
    max_rows : int or None
        Most rows kept; None keeps every row.
    seed : int
        Seed of :func:`numpy.random.default_rng` (same seed, same rows).

    Returns
    -------
    FitData, str or None
        The rows kept (``fd`` itself when it has at most ``max_rows`` rows) and
        the note saying what was done (None when nothing was).
    """
    if max_rows is None or fd.n <= max_rows:
        return fd, None
    keep = np.zeros(fd.n, dtype=bool)
    keep[np.random.default_rng(seed).choice(fd.n, size=max_rows, replace=False)] = True
    note = (f"the data have {fd.n} rows: every fit, fold, hold-out and test of this "
            f"comparison uses a random subsample of {max_rows} of them (seed {seed}); "
            "fit the chosen law to every row on its own")
    return fd.subset(keep), note


def _check_named_holdout(spec: Any, fractions: Mapping[str, float], fd: FitData) -> None:
    """Refuse a holdout that names a variable the data do not have (``T=0.3``).

    A bare fraction holds out pressure and velocity where the data have them; a
    variable named on purpose that cannot be held out is a mistake to report.
    """
    if not (isinstance(spec, Mapping) or (isinstance(spec, str) and "=" in spec)):
        return
    missing = [k for k in fractions if k not in fd.arrays]
    if missing:
        have = [k for k in VARIABLES if k in fd.arrays and k != "mu"]
        raise InputError(f"data '{fd.name}' have no {', '.join(missing)} to hold out; "
                         f"their variables are {', '.join(have) or 'none'}", option="holdout")


def _check_max_rows(max_rows: Any) -> int | None:
    if max_rows is None:
        return None
    if isinstance(max_rows, bool) or not isinstance(max_rows, (int, np.integer)) \
            or max_rows < 3:
        raise InputError(f"max_rows must be a whole number >= 3 (or None for every row), "
                         f"not {max_rows!r}", option="max_rows")
    return int(max_rows)


@dataclass
class _Setup:
    """What every law of one comparison shares: the data, its design, folds and splits."""

    fd: FitData
    design: Design
    trends: dict[str, Trend]
    box: dict[str, tuple[float, float]]
    splits: list[Split]
    assign: np.ndarray
    fit_kw: dict[str, Any]
    limits: tuple[float, float]

    @property
    def active(self) -> list[Split]:
        return [s for s in self.splits if s.usable]

    @property
    def folds(self) -> int:
        return int(self.assign.max()) + 1

    @property
    def tasks_per_law(self) -> int:
        return 1 + self.folds + len(self.active)


def _task(law: Law, setup: _Setup, kind: str, index: int) -> Any:
    """One fit of a comparison: the full fit, a cross-validation fold or a hold-out.

    Module-level and self-contained so that joblib can run it in another process.
    Returns a FitResult (or the error text) for the full fit, a FoldOutcome or a
    HoldoutResult.
    """
    fd = setup.fd
    rows = usable_rows(law, fd)
    if kind == "fold":
        return score_fold(law, fd, rows, setup.assign, index, fit_kwargs=setup.fit_kw)
    if kind == "holdout":
        return score_holdout(law, fd, rows, setup.active[index], fit_kwargs=setup.fit_kw,
                             limits=setup.limits)
    try:
        return fit(law, fd, on_invalid="drop", **setup.fit_kw)
    except Exception as exc:  # noqa: BLE001 - any law may fail; list it, go on
        return error_text(exc)


def _run_tasks(laws: list[Law], setup: _Setup, jobs: int, bar: Any) -> list[list[Any]]:
    """Every fit of every law (``jobs`` processes), grouped per law in task order."""
    tasks = [(law, "full", 0) for law in laws]
    tasks += [(law, "fold", f) for law in laws for f in range(setup.folds)]
    tasks += [(law, "holdout", i) for law in laws for i in range(len(setup.active))]
    workers = local_workers(jobs, len(tasks))
    outputs = starmap_local(_task, ((law, setup, kind, i) for law, kind, i in tasks), workers)
    per_law: dict[str, list[Any]] = {law.id: [] for law in laws}
    for (law, _kind, _i), out in zip(tasks, outputs):
        bar.set_postfix_str(law.id)
        per_law[law.id].append(out)
        bar.update(1)
    return [per_law[law.id] for law in laws]


def _extrapolation_score(holds: list[HoldoutResult]) -> tuple[float, str]:
    """The law's extrapolation RMSE and its status.

    The RMSE pools the held-out rows of every split that could be scored (a split
    whose fit failed is left out, as its note says).  It is undetermined (NaN,
    ``"undetermined"``) when a split's predictions depend on parameters its training
    rows cannot determine, and withheld (NaN, ``"implausible"``) when a split predicts
    mu outside the plausible range: neither belongs in an average.  ``"none"``: no
    split could be scored.
    """
    if any(h.status == "undetermined" for h in holds):
        return math.nan, "undetermined"
    if any(h.status == "implausible" for h in holds):
        return math.nan, "implausible"
    errs = [h for h in holds if h.status == "scored"]
    n_err = sum(h.n_test for h in errs)
    if not errs or not n_err:
        return math.nan, "none"
    sq = sum(h.rmse**2 * h.n_test for h in errs)
    return (math.sqrt(sq / n_err) if math.isfinite(sq) else math.inf), "scored"


def _undetermined_notes(cv: CVResult, holds: list[HoldoutResult]) -> list[str]:
    """Notes on the refits whose held-out predictions the training rows cannot determine.

    Such a refit predicts those rows from an arbitrary point of a flat valley of chi^2
    (another start, solver or library version stops elsewhere, with other predictions),
    so the score they enter is undetermined: reported as n/d and not used to rank.
    Implausible hold-out predictions are named too.
    """
    refits = [(f"cross-validation fold {u['fold']}", u["n_train"], u["n_test"], u["params"],
               u.get("n_undetermined", 0), "the CV RMSE") for u in cv.undetermined]
    refits += [(f"extrapolation test along {h.variable}", h.n_train, h.n_test,
                h.fit.non_identifiable, h.n_undetermined, "the extrapolation RMSE")
               for h in holds if h.fit is not None]
    notes = []
    for what, n_train, n_test, names, n_und, score in refits:
        if n_und:
            notes.append(f"{what}: its {n_train} training rows cannot determine "
                         f"{', '.join(names)}, on which the predictions of {n_und} of its "
                         f"{n_test} held-out row{'' if n_test == 1 else 's'} depend: they "
                         "come from an arbitrary point of a flat valley of chi^2, so "
                         f"{score} is undetermined (n/d) and not used to rank")
    notes += [f"extrapolation test along {h.variable}: the law fitted below the threshold "
              f"{h.implausible}; reported as implausible, not folded into the extrapolation "
              "RMSE" for h in holds if h.implausible and not h.n_undetermined]
    return notes


def _assemble(law: Law, setup: _Setup, outputs: list[Any]) -> LawComparison | dict[str, str]:
    """One law's comparison from its fits (full, folds, hold-outs), or its failure."""
    fd = setup.fd
    res = outputs[0]
    if isinstance(res, str):
        return {"id": law.id, "title": law.title, "error": res}
    rows = usable_rows(law, fd)
    if res.metrics["n"] != int(rows.sum()):  # pragma: no cover - internal check
        raise RuntimeError(f"row bookkeeping mismatch for law '{law.id}'")
    cv = combine_folds(fd, outputs[1:1 + setup.folds], int(setup.fit_kw["seed"]))
    holds: list[HoldoutResult] = outputs[1 + setup.folds:]
    extra = [f"extrapolation test along {h.variable}: {h.error}" for h in holds
             if h.error is not None]
    extra += [f"cross-validation fold {f['fold']} ({f['n_train']} training rows): "
              f"{f['error']}" for f in cv.failed]
    extra += _undetermined_notes(cv, holds)
    plaus = scan_plausibility(law, res.values, fd, setup.design, setup.box, setup.trends,
                              limits=setup.limits)
    sub = fd.subset(rows)
    resid = analyse_residuals(
        res.residual, res.best_fit, {k: sub.arrays[k] for k in setup.design.varying},
        describe=lambda k: "the fitted value" if k == "fitted" else k)
    law_notes = [n for n in res.notes if n not in fd.notes]
    ex_rmse, ex_status = _extrapolation_score(holds)
    return LawComparison(law, res, rows, law_notes, cv, holds, ex_rmse, plaus,
                         resid, extra_notes=extra, extrapolation_status=ex_status)


def _rank(results: list[LawComparison], fd: FitData, notes: list[str], assign: np.ndarray
          ) -> tuple[bool, int]:
    """Akaike weights, the common-rows CV RMSE and the ranks (in place); notes on rows.

    Returns whether the ranking used each law's own CV RMSE, and the common rows.
    """
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
            r.common_undetermined = not r.cv.determined
        elif not r.cv.determined_on(common):
            r.cv_rmse_common = math.nan
            r.common_undetermined = True
        else:
            pred = r.cv.predictions[common] if r.cv.predictions is not None else np.array([])
            ok = np.isfinite(pred)
            err = fd.arrays["mu"][common][ok] - pred[ok]
            r.cv_rmse_common = float(np.sqrt(np.mean(err**2))) if err.size else math.nan
        r.rank_basis = _rank_basis(r, "CV RMSE" if same_rows else "CV common",
                                   r.rows if same_rows else common, assign)
    results.sort(key=_rank_key)
    for i, r in enumerate(results, start=1):
        r.rank = i
    if len({r.aic_group for r in results}) > 1:
        notes.append("the laws were fitted to different rows (some dropped rows where they "
                     "are singular): AIC, AICc, BIC and Akaike weights compare only laws of "
                     "the same group (column 'grp')")
    return same_rows, int(common.sum())


def _settings(setup: _Setup, what: str, starts: int | None, fractions: dict[str, float],
              same_rows: bool, common: int, rows: dict[str, Any]) -> dict[str, Any]:
    """The settings block of a comparison (what was done, and by which rules)."""
    box = setup.box
    return {
        "laws": what,
        "folds": setup.folds,
        "seed": setup.fit_kw["seed"],
        "starts": starts,
        "holdout": fractions,
        "holdout_rule": "rows with x > x_min + (1 - fraction)(x_max - x_min) are held out; "
                        "the law is fitted on the others and scored on them",
        "splits": [s.to_dict() for s in setup.splits],
        "extended_box": {k: {"low": lo, "high": hi, "unit": VARIABLES[k].unit or "-",
                             "display": f"{fmt_value(k, lo)} .. {fmt_value(k, hi)}"}
                         for k, (lo, hi) in box.items()},
        "extended_box_rule": "0.5 x lowest .. 3 x highest measured value (s capped at 1; "
                             "T: 20 K below .. 20 K above); derived variables follow their "
                             "driver",
        "mu_limits": list(setup.limits),
        "trend_tolerance": {"absolute": TREND_TOL, "relative": TREND_REL},
        "trend_rule": "beyond each end of the measured range of a variable, mu must not move "
                      "against the trend the data show toward that end by more than the "
                      "tolerance (relative to mu where the reversal starts)",
        "trend_alpha": TREND_ALPHA,
        "ranking": RANKING,
        "ranking_metric": "cv_rmse" if same_rows else "cv_rmse_common",
        "common_rows": common,
        "akaike_weights": "from AICc (AIC when AICc is undefined), among laws fitted to "
                          "identical rows only",
        "residual_tests": "Wald-Wolfowitz runs test (exact, one-sided: too few runs) and "
                          "Kendall tau, per variable and vs the fitted value; Shapiro-Wilk; "
                          "5 % level each, uncorrected",
        "weights": "dataset" if setup.fd.weights is not None else "none",
        "rows": rows,
        "rows_rule": "data with more than max_rows rows are compared on a seeded random "
                     "subsample of max_rows rows (every fit, fold, hold-out and test)",
    }


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
    jobs: int = 1,
    max_rows: int | None = MAX_ROWS,
) -> Comparison:
    """Fit and compare several laws on one dataset.

    Parameters
    ----------
    laws : str, Law or iterable, optional
        Law ids/aliases (a comma-separated string is accepted) or laws.  None takes every
        law of ``family``.  Laws the data cannot feed (a law needing T on data without
        temperature) are listed in :attr:`Comparison.skipped` with the reason.
    data : str, path, Dataset, DataFrame, mapping or FitData
        Anything :func:`frictionlaws.fitting.as_fit_data` accepts (a packaged dataset name
        such as ``"thesis-steel"``, a CSV path, SI arrays).
    family : {"sliding", "slip"}, optional
        The family to take when ``laws`` is None; by default :func:`default_family`:
        ``"slip"`` for rolling-wheel slip data (s varying within 0..1, no contact
        pressure), else ``"sliding"``.
    folds : int
        Number of cross-validation folds (more than the rows: leave-one-out, with a note).
    holdout : float, str or mapping, optional
        Fraction of the upper range held out for the extrapolation test: a number applies
        to p and v; ``"p=0.3,v=0.2"`` or ``{"p": 0.3}`` per variable; None or 0 for none.
    seed : int
        Seed of the folds and of the fits' random starts (same seed, same results).
    starts : int, optional
        Random starts per non-linear fit (default: the fitter's own rule).
    weights : {"auto"}, None or array
        As in :func:`~frictionlaws.fitting.fit`.  CV and extrapolation errors are
        unweighted.
    mu_limits : (float, float)
        The plausible range of mu (default 0 and 5): the limits of the plausibility scan,
        and of hold-out predictions that can enter the extrapolation RMSE.
    mapping, units, area : optional
        Column mapping, units of columns whose header has none, and the nominal contact
        area (``"314.16 mm^2"`` or m^2) for reading a user's file, as in
        :func:`~frictionlaws.io.load_dataset`.
    progress : bool, optional
        Show a tqdm progress bar; by default only when stderr is a terminal.
    jobs : int
        Processes (joblib) sharing the fits (all independent); -1: one per core.  The
        results do not depend on it.
    max_rows : int or None
        Larger data are compared on a seeded random subsample of that many rows, with a
        note (module docstring); None compares every row, however long it takes.

    Returns
    -------
    Comparison
        The fitted laws in rank order, each with its fit, cross-validation, hold-out
        errors, plausibility scan, residual tests and Akaike weight; the laws skipped or
        failed (with the reason); the settings and notes.

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
    return _compare(fd, laws, family, folds, holdout, seed, starts, mu_limits, progress,
                    jobs, max_rows)


def _compare(fd: FitData, laws: Any, family: str | None, folds: Any, holdout: Any, seed: int,
             starts: int | None, mu_limits: Sequence[float], progress: bool | None,
             jobs: Any, max_rows: Any = MAX_ROWS) -> Comparison:
    """:func:`compare` on data already read."""
    check_fit_options(DEFAULT_METHOD, starts, seed, "error")  # the fit's rule for both
    limit = _check_max_rows(max_rows)
    n_data = fd.n
    fd, sub_note = subsample(fd, limit, seed)
    folds, lims, notes = _check_options(fd, folds, mu_limits, jobs)
    if sub_note:
        notes.insert(0, sub_note)
    fractions = parse_holdout(holdout)
    _check_named_holdout(holdout, fractions, fd)
    candidates, skipped, what = _select_laws(laws, family, fd)
    if not candidates:
        reasons = "; ".join(s["reason"] for s in skipped)
        raise InputError(f"none of {what} can be fitted to data '{fd.name}': {reasons}")
    design = design_of(fd)
    setup = _Setup(fd, design, data_trends(fd, design), extended_box(fd, design),
                   holdout_splits(fd, fractions, design), kfold_assignment(fd.n, folds, seed),
                   {"seed": seed, "starts": starts}, lims)
    bar = _progress(len(candidates) * setup.tasks_per_law, progress)
    try:
        outputs = _run_tasks(candidates, setup, int(jobs), bar)
    finally:
        bar.close()
    results: list[LawComparison] = []
    failed: list[dict[str, str]] = []
    for law, out in zip(candidates, outputs):
        one = _assemble(law, setup, out)
        (failed if isinstance(one, dict) else results).append(one)  # type: ignore[arg-type]
    if not results:
        raise FitError(f"none of {what} could be fitted to data '{fd.name}': "
                       + "; ".join(f"{f['id']}: {f['error']}" for f in failed))
    same_rows, common = _rank(results, fd, notes, setup.assign)
    settings = _settings(setup, what, starts, fractions, same_rows, common,
                         {"data": n_data, "used": fd.n, "max_rows": limit})
    return Comparison(fd, results, skipped, failed, design, setup.trends, setup.box,
                      setup.splits, setup.assign, settings, notes)
