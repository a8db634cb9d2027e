"""The comparison as text: number and score formatting, the ranking table with its legend
and rule (:func:`format_table`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ...base.units import to_display
from ...law import VARIABLES
from ..extrapolation import fmt_value

if TYPE_CHECKING:  # pragma: no cover
    from ..record import ComparisonRecord, LawComparison



__all__ = ["MAX_PANELS", "BIN_ABOVE", "SCATTERED", "DPI", "RC", "TICKS", "PNG_COMPRESSION",
           "UNDETERMINED", "RANK_RULE", "format_table"]


#: Most panels in one fits figure (levels with the most rows are shown): every panel
#: costs a set of axes to lay out and draw, and a reader compares a few at a glance.
MAX_PANELS = 4


#: A grouping variable with more distinct values than this is binned into quartiles.
BIN_ABOVE = 24


#: Rows whose other variables take more distinct combinations than this, each once, are
#: drawn at the median of those variables rather than at their most common combination.
SCATTERED = 8


#: Resolution of the PNG figures (dots per inch): the report is read on a screen.
DPI = 80


#: matplotlib settings of every figure.  A fixed title height (``axes.titley``) spares
#: matplotlib measuring every tick label of the figure to lift each title above the top
#: ticks: these axes have none there, and the PNG is the same.  Text without FreeType
#: hinting lays out and renders in about half the time (it dominates these figures) and
#: stays legible at :data:`DPI`, a little softer.
RC: dict[str, Any] = {"font.size": 9, "axes.titlesize": 9, "axes.titley": 1.0,
                      "text.hinting": "none"}


#: Intervals between the ticks of a linear axis at most (matplotlib's own choice on these
#: panel sizes is 6 to 9): every tick is two lines and two texts to make and draw, and
#: the ticks were a third of the report's drawing time.
TICKS = 5


#: zlib level of the PNG files: 3 compresses as tightly as the default 6 on these
#: flat-coloured figures, in about two thirds of the time.
PNG_COMPRESSION = 3


def _num(x: Any, fmt: str = ".3g") -> str:
    if x is None:
        return "n/a"
    try:
        xf = float(x)
    except (TypeError, ValueError):
        return str(x)
    if math.isnan(xf):
        return "n/a"
    if math.isinf(xf):
        return "inf" if xf > 0 else "-inf"
    return format(xf, fmt)


def _disp(var: str, x: Any) -> Any:
    """SI -> display unit (MPa, degC), by :func:`~frictionlaws.base.units.to_display`."""
    return to_display(x, var)


def _label(var: str) -> str:
    if var == "mu":
        return "friction coefficient mu [-]"
    info = VARIABLES[var]
    return f"{info.meaning.split(' (')[0]} {var} [{info.display_unit or '-'}]"


def _ranges_text(cmp: ComparisonRecord) -> str:
    parts = []
    for k, x in cmp.data.arrays.items():
        if k in VARIABLES:
            parts.append(f"{k} {fmt_value(k, float(np.min(x)))} .. "
                         f"{fmt_value(k, float(np.max(x)))}")
    return "; ".join(parts)


def _yes(r: LawComparison) -> str:
    return "yes" if r.plausible else "NO"


#: Table text of a score the refits' rows cannot determine (null in JSON).
UNDETERMINED = "n/d"


def _score(r: LawComparison, key: str, fmt: str = ".4f") -> str:
    """A CV or extrapolation score of ``r`` as table text: the number, "n/d" when it is
    undetermined, "implausible" for an extrapolation outside the plausible mu."""
    if key in r.undetermined_scores:
        return UNDETERMINED
    if key == "extrapolation_rmse":
        if r.extrapolation_status == "implausible":
            return "implausible"
        return _num(r.extrapolation_rmse, fmt)
    value = r.cv.rmse if key == "cv_rmse" else r.cv_rmse_common
    return _num(value, fmt) + ("" if r.cv.complete else "*")


def _common(cmp: ComparisonRecord) -> bool:
    return cmp.settings.get("ranking_metric") == "cv_rmse_common"


def _columns(cmp: ComparisonRecord) -> list[str]:
    cols = ["rank", "law", "k", "n", "R^2", "adj.R^2", "RMSE", "CV RMSE"]
    if _common(cmp):
        cols.append("CV common")
    return cols + ["extrap.RMSE", "AICc", "grp", "weight", "identifiable", "plausible", "resid.",
                   "rank basis"]


def _rows(cmp: ComparisonRecord) -> list[list[str]]:
    out = []
    for r in cmp.results:
        m = r.metrics
        row = [str(r.rank), r.law.id, str(m["k"]), str(m["n"]), _num(m["r2"], ".3f"),
               _num(m["adj_r2"], ".3f"), _num(m["rmse"], ".4f"), _score(r, "cv_rmse")]
        if _common(cmp):
            row.append(_score(r, "cv_rmse_common"))
        row += [_score(r, "extrapolation_rmse"), _num(m["aicc"], ".1f"),
                str(r.aic_group), _num(r.akaike_weight, ".3f"),
                "NO" if r.fit.non_identifiable else "yes", _yes(r),
                "structure" if r.residuals.structured else "ok", r.rank_basis]
        out.append(row)
    return out


def _header_lines(cmp: ComparisonRecord) -> list[str]:
    d = cmp.data
    s = cmp.settings
    hold = ", ".join(sp.describe() for sp in cmp.splits) or "none"
    return [
        f"Comparison of {len(cmp.results)} laws on '{d.name}' ({d.n} rows; {_ranges_text(cmp)})",
        f"ranked by {s['folds']}-fold cross-validated RMSE (seed {s['seed']}"
        + (", over the rows all laws share" if _common(cmp) else "")
        + "); RMSE, CV RMSE and extrapolation RMSE are in units of mu (-)",
        f"extrapolation holdout: {hold}",
        "plausibility box: " + "; ".join(f"{k} {v['display']}"
                                         for k, v in s["extended_box"].items())
        + f"; physical limits {s['mu_limits'][0]:g} <= mu <= {s['mu_limits'][1]:g}",
    ]


def _section(title: str, lines: Sequence[str]) -> list[str]:
    """A titled block of the console table, or nothing when there is nothing to say."""
    return ["", title, *lines] if lines else []


def _table_footer(cmp: ComparisonRecord) -> list[str]:
    """The legend lines under the ranked table."""
    out = []
    if _common(cmp):
        out.append(f"CV common: CV RMSE over the {cmp.settings['common_rows']} rows every law "
                   "could use (the ranking criterion, as the laws were fitted to different rows)")
    if any(not r.cv.complete for r in cmp.results):
        out.append("* cross-validation incomplete (a fold could not be fitted; see notes)")
    out += _legend(cmp)
    return out


def _legend(cmp: ComparisonRecord) -> list[str]:
    """What the n/d, weight and rank-basis entries mean (every table format)."""
    out = []
    if any(r.undetermined_scores for r in cmp.results):
        out.append(f"{UNDETERMINED}: undetermined: a refit's rows cannot determine "
                   "parameters its held-out predictions depend on (see notes); not used "
                   "to rank")
    if any(r.extrapolation_status == "implausible" for r in cmp.results):
        out.append("implausible: a hold-out prediction lies outside the plausible range "
                   f"{cmp.settings['mu_limits'][0]:g} <= mu <= "
                   f"{cmp.settings['mu_limits'][1]:g} (not averaged into an RMSE)")
    sizes = {r.aic_group: r.aic_group_size for r in cmp.results}
    out.append(f"grp: laws fitted to the same rows ({len(sizes)} group"
               f"{'' if len(sizes) == 1 else 's'}); weight: Akaike weight over the laws of "
               "the same grp only (AIC compares likelihoods of the same rows), so weights of "
               "different groups are not comparable, and a law alone in its group has "
               "weight 1 trivially")
    out.append("rank basis: why the law ranks where it does; " + RANK_RULE)
    return out


#: The ranking rule in words, under every ranked table.
RANK_RULE = ("laws with a determined ranking CV RMSE first (identifiable before not "
             "identifiable, complete cross-validation before incomplete, then by that CV "
             "RMSE), then the unscored ones (n/d: the fold named cannot determine its "
             "predictions; or no CV RMSE) by fewer parameters, then id")


def _table_sections(cmp: ComparisonRecord) -> list[str]:
    """The flags, trends, warnings, notes, skipped and failed laws under the table."""
    res = cmp.results
    out = _section("NOT IDENTIFIABLE from these data (ranked after the identifiable laws "
                   "with a score):",
                   [f"  {r.law.id}: cannot determine {', '.join(r.fit.non_identifiable)}"
                    for r in res if r.fit.non_identifiable])
    out += _section("IMPLAUSIBLE outside the measured range (extended box):",
                    [f"  {r.law.id}: {reason}" for r in res if not r.plausible
                     for reason in r.plausibility.reasons])
    trends = [t.describe() for t in cmp.trends.values()]
    if trends:
        out += ["", "trends the data show: " + "; ".join(trends)]
    out += _section("residual structure (each test at the 5 % level):",
                    [f"  {r.law.id}: {s}" for r in res for s in r.residuals.structure])
    out += _section("fit warnings (identifiability, bounds):",
                    [f"  {r.law.id}: {w}" for r in res for w in r.fit.warnings])
    notes = [f"  {r.law.id}: {n}" for r in res for n in r.notes + r.extra_notes]
    if notes or cmp.notes or cmp.data.notes:
        out += ["", "notes:", *[f"  {n}" for n in cmp.data.notes + cmp.notes], *notes]
    out += _section("skipped (cannot be fitted to these data):",
                    [f"  {s['id']}: {s['reason']}" for s in cmp.skipped])
    out += _section("failed to fit:", [f"  {f['id']}: {f['error']}" for f in cmp.failed])
    return out


def format_table(cmp: ComparisonRecord) -> str:
    """Format the ranked table with flags, notes, skipped and failed laws (plain text).

    Parameters
    ----------
    cmp : Comparison
        The comparison.

    Returns
    -------
    str
        The console table.
    """
    rows = _rows(cmp)
    columns = _columns(cmp)
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h)
              for i, h in enumerate(columns)]
    left = {1, len(columns) - 1}

    def line(cells: Sequence[str]) -> str:
        return "  ".join(c.ljust(w) if i in left else c.rjust(w)
                         for i, (c, w) in enumerate(zip(cells, widths))).rstrip()

    out = _header_lines(cmp) + ["", line(columns)]
    out += [line(r) for r in rows]
    return "\n".join(out + _table_footer(cmp) + _table_sections(cmp))

