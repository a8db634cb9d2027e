"""What :func:`~frictionlaws.comparison.compare` found, as plain data: the
:class:`ComparisonRecord` and, per law, :class:`LawComparison`.

The fits, cross-validation, hold-outs, plausibility and residual tests of every law and
the settings, with their JSON form and table (:meth:`ComparisonRecord.to_frame`).
Computing them is :mod:`frictionlaws.comparison.core`'s work, formatting them
:mod:`frictionlaws.comparison.report`'s, which reads this record;
:class:`~frictionlaws.comparison.results.Comparison` is the record with its views (the
console table, the report, the plot, Jupyter's HTML).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..base.jsonio import dumps as _dumps
from ..fitting import FitData, FitResult
from ..law import VARIABLES, Law
from ..law.registry import get_law
from .cv import CVResult
from .extrapolation import Design, HoldoutResult, Plausibility, Split, Trend, fmt_value
from .residuals import ResidualAnalysis

__all__ = ["ComparisonRecord", "LawComparison", "COMPARISON_FORMAT", "COMPARISON_VERSION",
           "FRAME_COLUMNS", "mark_undetermined"]

COMPARISON_FORMAT = "frictionlaws-comparison"
COMPARISON_VERSION = 1


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
    #: ``"scored"``, ``"undetermined"``, ``"implausible"`` or ``"none"``
    #: (:func:`~frictionlaws.comparison.core._extrapolation_score`).
    extrapolation_status: str = "scored"
    #: True when ``cv_rmse_common`` is undetermined (a prediction of a common row is).
    common_undetermined: bool = False
    #: Why the law ranks where it does (its ranking score, or why it has none).
    rank_basis: str = ""

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
    def undetermined_scores(self) -> list[str]:
        """The scores that are undetermined (null, n/d): ``cv_rmse``, ``cv_rmse_common``,
        ``extrapolation_rmse``; each is one whose held-out predictions depend on parameters
        the refit's rows cannot determine."""
        out = [] if self.cv.determined else ["cv_rmse"]
        if self.common_undetermined:
            out.append("cv_rmse_common")
        if self.extrapolation_status == "undetermined":
            out.append("extrapolation_rmse")
        return out

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
            "undetermined_scores": self.undetermined_scores,
            "rank_basis": self.rank_basis,
            "cv": self.cv.to_dict(),
            "extrapolation_rmse": self.extrapolation_rmse,
            "extrapolation_status": self.extrapolation_status,
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


#: The columns of :meth:`Comparison.to_frame` (and of a campaign's comparison table).
FRAME_COLUMNS = ("rank", "id", "k", "n", "r2", "rmse", "aic", "bic", "cv_rmse",
                 "cv_rmse_common", "extrapolation_rmse", "extrapolation_status",
                 "akaike_weight", "aic_group", "identifiable", "plausible", "converged",
                 "undetermined", "rank_basis")
#: The scores a frame row may name as undetermined.
SCORES = ("cv_rmse", "cv_rmse_common", "extrapolation_rmse")


def mark_undetermined(frame: Any) -> Any:
    """A copy of a comparison frame for display or CSV: each undetermined score "n/d".

    Parameters
    ----------
    frame : pandas.DataFrame
        :meth:`Comparison.to_frame` (or a campaign table made of them): the rows name
        their undetermined scores in the ``undetermined`` column.

    Returns
    -------
    pandas.DataFrame
        The same table, the score cells the ``undetermined`` column names replaced by
        ``"n/d"`` (those columns become text); the frame itself is unchanged.
    """
    if "undetermined" not in frame.columns:
        return frame
    out = frame.copy()
    names = out["undetermined"].fillna("").astype(str)
    for col in SCORES:
        if col in out.columns:
            hit = names.str.split(", ").apply(lambda xs, c=col: c in xs)
            if hit.any():
                out[col] = out[col].astype(object)
                out.loc[hit, col] = "n/d"
    return out


@dataclass
class ComparisonRecord:
    """What :func:`compare` found: ranked laws, skipped and failed laws, settings.

    ``results`` is in rank order (best first); :meth:`to_dict`/:meth:`to_json` are the
    machine-readable form.  Built as a
    :class:`~frictionlaws.comparison.results.Comparison`, which adds the views.
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
        """Name, source, rows and the ranges of the variables (SI and display units).

        ``n`` is the rows compared; ``n_data`` the rows of the data (more when a large
        dataset was subsampled, see :data:`~frictionlaws.comparison.core.MAX_ROWS`).
        """
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
        n_data = self.settings.get("rows", {}).get("data", self.data.n)
        return {"name": self.data.name, "source": self.data.source, "n": self.data.n,
                "n_data": n_data,
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
        """One row per ranked law: rank, metrics, CV and extrapolation RMSE, flags.

        A score that is undetermined (see :mod:`frictionlaws.comparison.cv`) is NaN and
        named in the ``undetermined`` column; ``rank_basis`` says why each law ranks
        where it does; ``aic_group`` is the group of laws fitted to the same rows within
        which ``akaike_weight`` compares them.
        """
        import pandas as pd

        rows = []
        for r in self.results:
            d = r.to_dict()
            row = {c: d[c] for c in FRAME_COLUMNS if c in d}
            row["identifiable"] = not r.fit.non_identifiable
            row["undetermined"] = ", ".join(r.undetermined_scores)
            rows.append(row)
        frame = pd.DataFrame(rows, columns=list(FRAME_COLUMNS)).rename(columns={"id": "law"})
        frame.attrs["units"] = ("mu, rmse, cv_rmse, cv_rmse_common, extrapolation_rmse: - "
                                "(dimensionless)")
        return frame
