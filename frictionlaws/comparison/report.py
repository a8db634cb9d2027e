"""The comparison as a console table, Markdown, self-contained HTML and PNG figures.

Figures (matplotlib with the Agg backend, imported only here):

* ``fits_<x>_by_<g>.png``: the data with every fitted law, mu against one
  variable with one panel per level of the other (mu vs p per velocity, mu vs
  v per pressure); each curve spans the range of the rows its law was fitted
  on, and a law is not drawn in a panel all of whose rows it had to drop;
* ``residuals.png``: for every law, residuals against each variable and the
  fitted value, and the normal Q-Q plot, a red band where a test finds structure
  (the p-values are in the residual-tests table of ``report.md`` and ``report.html``);
* ``extrapolation_holdout.png``: each law fitted below the holdout threshold,
  with the held-out points it is scored on;
* ``extrapolation_box.png``: each fully fitted law over the extended box, with
  the measured range, the physical limits and the points where the
  plausibility scan flagged it;
* ``metrics.png``: fit RMSE, cross-validated RMSE and extrapolation RMSE per law
  (the values are in the ranking table).

Figures cost little to draw (issue 15): few axes with fixed layouts, one artist for
many repeated marks, unhinted text, no mathtext; ``benchmarks/bench_report.py`` times
them.

``report.html`` embeds every PNG as base64 and needs nothing else; ``report.md``
links the PNG files next to it; ``comparison.json`` is :meth:`Comparison.to_json`.
"""

from __future__ import annotations

import base64
import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from ..errors import InputError
from ..law import VARIABLES
from ..parallel import local_workers, starmap_local
from ..sanitize import html_text, markdown_text
from ..units import to_display
from .extrapolation import Split, evaluate_on, fmt_value
from .residuals import ALPHA

if TYPE_CHECKING:  # pragma: no cover
    from .results import Comparison, LawComparison

__all__ = ["format_table", "write_report", "make_figures", "Figure"]

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


# ------------------------------------------------------------------ helpers


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
    """SI -> display unit (MPa, degC), by :func:`~frictionlaws.units.to_display`."""
    return to_display(x, var)


def _label(var: str) -> str:
    if var == "mu":
        return "friction coefficient mu [-]"
    info = VARIABLES[var]
    return f"{info.meaning.split(' (')[0]} {var} [{info.display_unit or '-'}]"


def _ranges_text(cmp: Comparison) -> str:
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


# -------------------------------------------------------------------- table


def _common(cmp: Comparison) -> bool:
    return cmp.settings.get("ranking_metric") == "cv_rmse_common"


def _columns(cmp: Comparison) -> list[str]:
    cols = ["rank", "law", "k", "n", "R^2", "adj.R^2", "RMSE", "CV RMSE"]
    if _common(cmp):
        cols.append("CV common")
    return cols + ["extrap.RMSE", "AICc", "grp", "weight", "identifiable", "plausible", "resid.",
                   "rank basis"]


def _rows(cmp: Comparison) -> list[list[str]]:
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


def _header_lines(cmp: Comparison) -> list[str]:
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


def _table_footer(cmp: Comparison) -> list[str]:
    """The legend lines under the ranked table."""
    out = []
    if _common(cmp):
        out.append(f"CV common: CV RMSE over the {cmp.settings['common_rows']} rows every law "
                   "could use (the ranking criterion, as the laws were fitted to different rows)")
    if any(not r.cv.complete for r in cmp.results):
        out.append("* cross-validation incomplete (a fold could not be fitted; see notes)")
    out += _legend(cmp)
    return out


def _legend(cmp: Comparison) -> list[str]:
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


def _table_sections(cmp: Comparison) -> list[str]:
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


def format_table(cmp: Comparison) -> str:
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


# ------------------------------------------------------------------ figures


@dataclass
class Figure:
    """One PNG figure of the report."""

    name: str
    title: str
    caption: str
    png: bytes


def _styles(cmp: Comparison) -> dict[str, dict[str, Any]]:
    import matplotlib

    maps: Any = matplotlib.colormaps  # ListedColormaps: they have .colors
    colours = [*maps["tab10"].colors, *maps["Dark2"].colors]
    dashes = ["-", "--", "-.", ":"]
    out = {}
    # tab10 solid, then Dark2 dashed, so neighbouring colours differ in style too
    for i, r in enumerate(cmp.results):
        style = 0 if i < 10 else 1 + (i - 10) // 8
        out[r.law.id] = {"color": colours[i % len(colours)],
                         "linestyle": dashes[style % len(dashes)]}
    return out


def _law_handles(cmp: Comparison, styles: dict[str, dict[str, Any]],
                 suffix: dict[str, str] | None = None) -> list[Any]:
    from matplotlib.lines import Line2D

    suffix = suffix or {}
    return [Line2D([], [], lw=2, **styles[r.law.id],
                   label=f"{r.rank}. {r.law.id}{suffix.get(r.law.id, '')}")
            for r in cmp.results]


def _new_figure(width: float, height: float) -> Any:
    """A matplotlib figure on its own Agg canvas (no pyplot, no global figure registry)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure as MplFigure

    fig = MplFigure(figsize=(width, height))
    FigureCanvasAgg(fig)
    return fig


def _grid(fig: Any, nrows: int, ncols: int, *, legend_in: float = 0.0, top_in: float = 0.5,
          left_in: float = 0.65,
          bottom_in: float = 0.5, hspace: float = 0.45, wspace: float = 0.25,
          sharey: bool = False) -> np.ndarray:
    """A fixed grid of axes leaving ``legend_in`` inches on the right for a legend.

    A fixed layout costs nothing at draw time (a constrained layout measures every
    text of the figure, twice).  Linear axes get at most :data:`TICKS` intervals.
    """
    w, h = fig.get_size_inches()
    axes = fig.subplots(nrows, ncols, squeeze=False, sharey=sharey)
    for ax in axes.ravel():
        ax.locator_params(nbins=TICKS)
    fig.subplots_adjust(left=left_in / w, right=1.0 - (legend_in + 0.15) / w,
                        bottom=bottom_in / h, top=1.0 - top_in / h, hspace=hspace,
                        wspace=wspace)
    return axes


def _legend_width(handles: Sequence[Any]) -> float:
    """Inches a figure legend of ``handles`` needs (8-point text, the longest line)."""
    longest = max((len(line) for h in handles for line in str(h.get_label()).split("\n")),
                  default=10)
    return 0.7 + 0.062 * longest


def _png(fig: Any) -> bytes:
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=DPI, pil_kwargs={"compress_level": PNG_COMPRESSION})
    return buf.getvalue()


def _levels(values: np.ndarray) -> tuple[list[tuple[float, np.ndarray, str]], str]:
    """Panels for a grouping variable: (representative value, row mask, label), note."""
    uniq, counts = np.unique(values, return_counts=True)
    if uniq.size <= MAX_PANELS:
        return [(float(u), values == u, "") for u in uniq], ""
    if uniq.size > BIN_ABOVE:
        edges = np.quantile(values, [0.25, 0.5, 0.75])
        bins = np.searchsorted(edges, values, side="right")
        out = []
        for b in np.unique(bins):
            m = bins == b
            out.append((float(np.median(values[m])), m, "bin"))
        return out, "continuous values grouped into quartile bins (curves at the bin median)"
    order = sorted(range(uniq.size), key=lambda i: (-counts[i], uniq[i]))[:MAX_PANELS]
    chosen = sorted(order, key=lambda i: uniq[i])
    return ([(float(uniq[i]), values == uniq[i], "") for i in chosen],
            f"{MAX_PANELS} of {uniq.size} levels shown (those with the most rows)")


def _mode_level(cmp: Comparison, rows: np.ndarray, others: list[str]) -> dict[str, float]:
    """The most common combination of ``others`` among ``rows`` (median if continuous)."""
    if not others:
        return {}
    arr = np.column_stack([cmp.data.arrays[k][rows] for k in others])
    uniq, counts = np.unique(arr, axis=0, return_counts=True)
    if counts.max() == 1 and uniq.shape[0] > SCATTERED:
        return {k: float(np.median(cmp.data.arrays[k][rows])) for k in others}
    best = uniq[int(np.argmax(counts))]
    return {k: float(v) for k, v in zip(others, best)}


def _at_text(level: dict[str, float]) -> str:
    return ", ".join(f"{k} = {fmt_value(k, v)}" for k, v in level.items())


def _ylim_data(mu: np.ndarray, pad: float = 0.15) -> tuple[float, float]:
    lo, hi = float(np.min(mu)), float(np.max(mu))
    span = max(hi - lo, 0.1 * max(abs(hi), 1e-3))
    return max(0.0, lo - pad * span) if lo >= 0 else lo - pad * span, hi + pad * span


def _panel_title(cmp: Comparison, g: str, level: float, mask: np.ndarray, kind: str) -> str:
    if kind == "bin":
        gm = cmp.data.arrays[g][mask]
        title = f"{g} {fmt_value(g, float(gm.min()))} .. {fmt_value(g, float(gm.max()))}"
    else:
        title = f"{g} = {fmt_value(g, level)}"
    nr = int(mask.sum())
    return f"{title} ({nr} row{'s' if nr != 1 else ''})"


def _fits_panel(cmp: Comparison, ax: Any, x: str, fixed: dict[str, float], mask: np.ndarray,
                styles: dict[str, Any]) -> None:
    """One panel of a fits figure: the rows of ``mask`` and every law at ``fixed``."""
    d = cmp.data
    xs = d.arrays[x]
    ax.plot(_disp(x, xs[mask]), d.arrays["mu"][mask], "o", color="black", ms=5, zorder=5)
    for r in cmp.results:
        if not (r.rows & mask).any():
            continue
        lo, hi = r.fit.data["ranges"].get(x, (float(xs.min()), float(xs.max())))
        grid = np.linspace(lo, hi, 120) if hi > lo else np.array([lo])
        pts = {x: grid, **{k: np.full(grid.size, v) for k, v in fixed.items()}}
        yv = evaluate_on(r.law, r.fit.values, cmp.design, pts)
        ax.plot(_disp(x, grid), yv, lw=1.4, **styles[r.law.id])
    ax.grid(alpha=0.3)


def _fits_figure(cmp: Comparison, x: str, g: str | None, styles: dict[str, Any]
                 ) -> Figure:
    from matplotlib.lines import Line2D

    d = cmp.data
    if g is None:
        panels, note = [(math.nan, np.ones(d.n, bool), "")], ""
    else:
        panels, note = _levels(d.arrays[g])
    others = [k for k in cmp.design.varying if k not in (x, g)]
    ncols = min(4, len(panels))
    nrows = math.ceil(len(panels) / ncols)
    fig = _new_figure(3.2 * ncols + 2.8, 2.7 * nrows + 1.0)
    axes = _grid(fig, nrows, ncols, legend_in=2.6, top_in=0.7, bottom_in=0.6, sharey=True)
    for ax in axes.ravel()[len(panels):]:
        ax.set_visible(False)
    for (level, mask, kind), ax in zip(panels, axes.ravel()):
        fixed = {g: level} if g is not None else {}
        fixed.update({k: float(np.median(d.arrays[k][mask])) for k in others})
        _fits_panel(cmp, ax, x, fixed, mask, styles)
        if g is not None:
            ax.set_title(_panel_title(cmp, g, level, mask, kind), fontsize=9)
    for ax in axes[-1]:
        ax.set_xlabel(_label(x))
    for ax in axes[:, 0]:
        ax.set_ylabel(_label("mu"))
    axes[0, 0].set_ylim(*_ylim_data(d.arrays["mu"]))
    handles = [Line2D([], [], marker="o", ls="", color="black", label="measured")]
    handles += _law_handles(cmp, styles)
    fig.legend(handles=handles, loc="upper right", fontsize=8, title="law (rank)")
    what = f"mu against {x}" + (f" for each level of {g}" if g else "")
    fig.suptitle(f"{cmp.data.name}: {what}", fontsize=11)
    caption = (f"The data with every fitted law: {what}. Each curve spans the {x} range of "
               "the rows its law was fitted on; a law that dropped all rows of a panel "
               "(e.g. v = 0 for a log-velocity law) is not drawn there.")
    if others:
        caption += f" Other variables at the panel's median ({', '.join(others)})."
    if note:
        caption += f" {note}."
    name = f"fits_{x}" + (f"_by_{g}" if g else "")
    return Figure(name, what, caption, _png(fig))


#: Vertical distance between the strips of two laws in the residuals figure, in
#: standardised residuals (residual / the law's RMSE).
STRIP = 9.0
#: Colour of the band behind a residual strip whose test finds structure.
FLAG_COLOUR = "#fbd5d5"


def _test_p(r: LawComparison, column: str) -> dict[str, float | None]:
    """The p-values of one law's residual tests in one column ("qq": Shapiro-Wilk)."""
    if column == "qq":
        return {"Shapiro-Wilk": r.residuals.shapiro_p}
    t = r.residuals.tests.get(column, {})
    return {"runs": (t.get("runs") or {}).get("p_value"), "Kendall": t.get("kendall_p")}


def _flagged(p: float | None) -> bool:
    """True when a p-value finds structure at the report's level (:data:`ALPHA`)."""
    return p is not None and math.isfinite(p) and p < ALPHA


def _strip(cmp: Comparison, r: LawComparison, column: str
           ) -> tuple[np.ndarray, np.ndarray, bool]:
    """x, standardised y, and whether a test flags it, of one law's strip in one panel."""
    scale = r.metrics["rmse"] if r.metrics["rmse"] > 0 else 1.0
    flagged = any(_flagged(p) for p in _test_p(r, column).values())
    if column == "qq":
        osm, osr = r.residuals.normal_quantiles
        return osm, osr / scale, flagged
    if column == "fitted":
        xv = r.fit.best_fit
    else:
        xv = _disp(column, cmp.data.arrays[column][r.rows])
    resid = np.asarray(r.fit.residual, float)
    return np.asarray(xv, float), resid / scale, flagged


def _strip_lines(ax: Any, offsets: np.ndarray, flagged: list[bool]) -> None:
    """The zero line of every strip and a band behind the flagged ones, as two artists.

    One polyline (broken by NaN) and one collection cost a fraction of a line or a
    patch per strip; both span the panel's width (x in axes coordinates).
    """
    from matplotlib.collections import PolyCollection
    from matplotlib.lines import Line2D

    trans = ax.get_yaxis_transform()
    half = 0.48 * STRIP  # a thin white gap between neighbouring bands
    bands = [[(0, off - half), (1, off - half), (1, off + half), (0, off + half)]
             for off, f in zip(offsets, flagged) if f]
    if bands:
        ax.add_collection(PolyCollection(bands, facecolors=FLAG_COLOUR, edgecolors="none",
                                         transform=trans, zorder=0), autolim=False)
    ax.add_line(Line2D(np.tile([0.0, 1.0, np.nan], offsets.size), np.repeat(offsets, 3),
                       color="grey", lw=0.6, transform=trans, zorder=1))


def _residuals_figure(cmp: Comparison, styles: dict[str, Any]) -> Figure:
    cols = list(cmp.design.varying) + ["fitted", "qq"]
    n = len(cmp.results)
    fig = _new_figure(3.3 * len(cols) + 1.8, 0.6 * n + 1.7)
    axes = _grid(fig, 1, len(cols), left_in=1.7, top_in=0.75, bottom_in=0.6, wspace=0.08)[0]
    offsets = -STRIP * np.arange(n)
    for ax, c in zip(axes, cols):
        # the same strips in every panel, named on the first: the others need no y ticks
        # (a shared axis would make and draw them, hidden, in every panel)
        ax.set_ylim(offsets[-1] - 0.5 * STRIP, 0.5 * STRIP)
        ax.set_yticks([] if c != cols[0] else offsets)
        flagged = []
        for r, off in zip(cmp.results, offsets):
            xv, yv, flag = _strip(cmp, r, c)
            ax.plot(xv, yv + off, "o", ms=3, color=styles[r.law.id]["color"], zorder=2)
            flagged.append(flag)
        _strip_lines(ax, offsets, flagged)
        ax.set_xlabel("normal quantile [-]" if c == "qq" else
                      "fitted mu [-]" if c == "fitted" else _label(c), fontsize=8)
        ax.set_title("normal Q-Q (Shapiro-Wilk)" if c == "qq" else
                     f"vs {'the fitted value' if c == 'fitted' else c} (runs, Kendall)",
                     fontsize=9)
        ax.grid(axis="x", alpha=0.3)
        ax.tick_params(labelsize=7)
    axes[0].set_yticks(offsets, [f"{r.rank}. {r.law.id}" for r in cmp.results], fontsize=7)
    fig.suptitle(f"{cmp.data.name}: residuals (data - fit) of each law, in rank order, "
                 "divided by the law's RMSE; red band: a test finds structure (p < "
                 f"{ALPHA:g})", fontsize=11)
    caption = ("Residuals of each fitted law (one strip per law, in rank order, each divided "
               "by that law's RMSE so that every strip has the same scale; the grey line is "
               "zero) against each variable and against the fitted value, and the normal Q-Q "
               f"plot. A strip on a red band: in that panel the one-sided runs test (residual "
               f"signs cluster along the variable, a systematic misfit) or the Kendall trend "
               f"test, or in the Q-Q panel the Shapiro-Wilk test, has p < {ALPHA:g}. Every "
               "p-value is in the table of residual tests.")
    return Figure("residuals", "residuals", caption, _png(fig))


def _holdout_panel(cmp: Comparison, ax: Any, split: Split, styles: dict[str, Any]) -> None:
    """One split's panel: training and held-out rows, every law fitted below the threshold."""
    d = cmp.data
    mu = d.arrays["mu"]
    x = split.variable
    xs = d.arrays[x]
    test = split.test if split.test is not None else np.zeros(d.n, bool)
    thr = float(split.threshold) if split.threshold is not None else float(xs.max())
    level = _mode_level(cmp, test, [k for k in cmp.design.varying if k != x])
    match = np.ones(d.n, bool)
    for k, v in level.items():
        match &= np.isclose(d.arrays[k], v, rtol=1e-9, atol=0)
    lo, hi = float(xs.min()), float(xs.max())
    ax.axvspan(_disp(x, thr), _disp(x, hi + 0.04 * (hi - lo)), color="tab:red", alpha=0.08)
    ax.plot(_disp(x, xs[~match]), mu[~match], "o", color="0.75", ms=4, zorder=3)
    tr, te = match & ~test, match & test
    ax.plot(_disp(x, xs[tr]), mu[tr], "o", color="black", ms=5, zorder=5)
    ax.plot(_disp(x, xs[te]), mu[te], "s", mfc="none", mec="tab:red", mew=2, ms=9, zorder=6)
    grid = np.linspace(lo, hi, 250)
    for r in cmp.results:
        h = next((h for h in r.holdouts if h.variable == x), None)
        if h is None or h.fit is None or not r.rows.any():
            continue
        pts = {x: grid, **{k: np.full(grid.size, v) for k, v in level.items()}}
        yv = evaluate_on(r.law, h.fit.values, cmp.design, pts)
        ax.plot(_disp(x, grid), yv, lw=1.4, **styles[r.law.id])
    ax.set_ylim(*_ylim_data(mu, 0.3))
    ax.set_xlim(_disp(x, lo - 0.04 * (hi - lo)), _disp(x, hi + 0.04 * (hi - lo)))
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label("mu"))
    at = f" at {_at_text(level)}" if level else ""
    ax.set_title(f"fitted on {x} <= {fmt_value(x, thr)}, scored above"
                 f"\n({int(test.sum())} held-out rows; curves{at})", fontsize=9)
    ax.grid(alpha=0.3)


def _holdout_figure(cmp: Comparison, styles: dict[str, Any]) -> Figure | None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    splits = [s for s in cmp.splits if s.usable]
    if not splits:
        return None
    handles = [Line2D([], [], marker="o", ls="", color="black", label="training rows"),
               Line2D([], [], marker="s", ls="", mfc="none", mec="tab:red", mew=2, ms=8,
                      label="held-out rows"),
               Line2D([], [], marker="o", ls="", color="0.75", label="rows at other levels"),
               Patch(color="tab:red", alpha=0.15, label="held-out range")]
    handles += _law_handles(cmp, styles, {r.law.id: f" ({_score(r, 'extrapolation_rmse', '.3f')})"
                                          for r in cmp.results})
    legend_in = _legend_width(handles)
    fig = _new_figure(4.6 * len(splits) + legend_in + 0.9, 4.6)
    axes = _grid(fig, 1, len(splits), legend_in=legend_in, top_in=0.95, bottom_in=0.6,
                 wspace=0.3)
    for split, ax in zip(splits, axes[0]):
        _holdout_panel(cmp, ax, split, styles)
    fig.legend(handles=handles, loc="upper right", fontsize=8,
               title="law (extrapolation RMSE)")
    fig.suptitle(f"{cmp.data.name}: extrapolation to the held-out upper range", fontsize=11)
    caption = ("Extrapolation test: each law is fitted on the rows below the threshold only "
               "and predicts the held-out rows above it (red squares); the legend gives the "
               "RMSE of mu (-) on the held-out rows of every split, pooled.")
    return Figure("extrapolation_holdout", "extrapolation to held-out rows", caption,
                  _png(fig))


def _box_marks(ax: Any, r: LawComparison, x: str, lev: dict[str, float], colour: Any,
               limits: tuple[float, float]) -> None:
    """Mark where a law's plausibility flags happen in the panel of ``x``."""
    lo_lim, hi_lim = limits
    for f in r.plausibility.flags:
        if f.kind == "trend" and f.variable == x and f.mu:
            ax.plot([_disp(x, f.at[x]), _disp(x, f.to[x])], list(f.mu), "X",
                    color=colour, mec="black", ms=9, zorder=7)
        elif f.kind in ("above-limit", "below-limit") and x in f.at and f.mu:
            if all(math.isclose(f.at.get(k, v), v, rel_tol=1e-6) for k, v in lev.items()):
                yv_clip = min(max(f.mu[0], lo_lim - 0.9), hi_lim + 1.4)
                ax.plot(_disp(x, f.at[x]), yv_clip, "^" if f.kind == "above-limit" else "v",
                        color=colour, mec="black", ms=9, zorder=7)


def _box_level(r: LawComparison, x: str, level: dict[str, float],
               drawn_at: dict[str, list[str]]) -> dict[str, float]:
    """Where a law is drawn in the panel of ``x``: where its trend turns, if it does."""
    flag = next((f for f in r.plausibility.flags if f.kind == "trend" and f.variable == x),
                None)
    lev = dict(level)
    if flag is not None:
        lev.update({k: v for k, v in flag.at.items() if k != x and k in lev})
        moved = {k: v for k, v in lev.items() if v != level[k]}
        if moved:
            drawn_at.setdefault(r.law.id, []).append(f"{x} panel at {_at_text(moved)}")
    return lev


def _box_mode(cmp: Comparison, x: str) -> dict[str, float]:
    """The level of the other variables at which the panel of ``x`` is drawn."""
    others = [k for k in cmp.box if k != x and k in cmp.design.varying]
    return _mode_level(cmp, np.ones(cmp.data.n, bool), others)


def _box_panel(cmp: Comparison, ax: Any, x: str, styles: dict[str, Any]) -> None:
    """One variable's panel of the plausibility figure."""
    d = cmp.data
    limits = (float(cmp.settings["mu_limits"][0]), float(cmp.settings["mu_limits"][1]))
    blo, bhi = cmp.box[x]
    xs = d.arrays[x]
    level = _box_mode(cmp, x)
    ax.axvspan(_disp(x, float(xs.min())), _disp(x, float(xs.max())), color="0.85",
               alpha=0.6, zorder=0)
    for lim in limits:
        ax.axhline(lim, color="tab:red", lw=1, ls="--", zorder=1)
    grid = np.unique(np.concatenate([np.linspace(blo, bhi, 250),
                                     np.geomspace(max(blo, bhi * 1e-4), bhi, 120)]))
    ax.plot(_disp(x, xs), d.arrays["mu"], "o", color="black", ms=4, zorder=6)
    for r in cmp.results:
        lev = _box_level(r, x, level, {})
        pts = {x: grid, **{k: np.full(grid.size, v) for k, v in lev.items()}}
        yv = evaluate_on(r.law, r.fit.values, cmp.design, pts)
        ax.plot(_disp(x, grid), yv, lw=2.2 if not r.plausible else 1.2, **styles[r.law.id],
                zorder=4)
        _box_marks(ax, r, x, lev, styles[r.law.id]["color"], limits)
    ax.set_xlim(_disp(x, blo), _disp(x, bhi))
    ax.set_ylim(limits[0] - 1.0, limits[1] + 1.5)
    ax.set_xlabel(_label(x))
    ax.set_ylabel(_label("mu"))
    at = f" at {_at_text(level)}" if level else ""
    ax.set_title(f"fully fitted laws over the extended {x} range{at}\n"
                 "(a law whose trend turns is drawn where it turns: see legend)", fontsize=9)
    ax.grid(alpha=0.3)


def _box_figure(cmp: Comparison, styles: dict[str, Any]) -> Figure:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    lo_lim, hi_lim = cmp.settings["mu_limits"]
    vars_ = [k for k in cmp.design.varying if k in cmp.box] or list(cmp.box)[:1]
    drawn_at: dict[str, list[str]] = {}  # law -> the panels it is drawn off the mode in
    for r in cmp.results:
        for x in vars_:
            _box_level(r, x, _box_mode(cmp, x), drawn_at)
    handles = [Line2D([], [], marker="o", ls="", color="black", label="measured"),
               Patch(color="0.85", label="measured range"),
               Line2D([], [], color="tab:red", ls="--", label="physical limits of mu"),
               Line2D([], [], marker="X", ls="", color="0.5", mec="black", ms=8,
                      label="trend reversal (from, to)"),
               Line2D([], [], marker="^", ls="", color="0.5", mec="black", ms=8,
                      label="limit exceeded (worst point)")]
    suffix = {}
    for r in cmp.results:
        text = "" if r.plausible else " (IMPLAUSIBLE)"
        if r.law.id in drawn_at:
            text += "\n    " + "; ".join(drawn_at[r.law.id])
        suffix[r.law.id] = text
    handles += _law_handles(cmp, styles, suffix)
    legend_in = _legend_width(handles)
    fig = _new_figure(4.8 * max(1, len(vars_)) + legend_in + 0.9, 4.8)
    axes = _grid(fig, 1, max(1, len(vars_)), legend_in=legend_in, top_in=0.95,
                 bottom_in=0.6, wspace=0.3)
    for x, ax in zip(vars_, axes[0]):
        _box_panel(cmp, ax, x, styles)
    fig.legend(handles=handles, loc="upper right", fontsize=8, title="law (rank)")
    fig.suptitle(f"{cmp.data.name}: plausibility outside the measured range", fontsize=11)
    box = "; ".join(f"{k} {v['display']}" for k, v in cmp.settings["extended_box"].items())
    caption = (f"Each fully fitted law over the extended box ({box}); grey: the measured "
               f"range; dashed red: the physical limits {lo_lim:g} <= mu <= {hi_lim:g}. "
               "Implausible laws are drawn thick; X marks where a law's trend turns against "
               "the trend the data show (from the running extreme to the worst point); "
               "triangles mark the worst point outside the limits (clipped to the panel).")
    return Figure("extrapolation_box", "plausibility over the extended box", caption,
                  _png(fig))


def _log_axis(ax: Any, lo: float, hi: float) -> None:
    """A log x axis from ``lo`` to ``hi`` ticked and labelled at 1, 2, 5 x 10^k in plain numbers.

    Plain labels are drawn as text; the default 10^k labels go through mathtext, and the
    minor ticks the 1-2-5 ticks replace cost a tick each.
    """
    from matplotlib.ticker import FuncFormatter, LogLocator, NullLocator

    ax.set_xscale("log")
    ax.set_xlim(lo, hi)
    ax.xaxis.set_major_locator(LogLocator(subs=(1.0, 2.0, 5.0)))
    ax.xaxis.set_major_formatter(FuncFormatter(lambda x, _: f"{x:g}"))
    ax.xaxis.set_minor_locator(NullLocator())


def _metrics_figure(cmp: Comparison, styles: dict[str, Any]) -> Figure:
    res = cmp.results
    n = len(res)
    fig = _new_figure(10, 0.45 * n + 2.0)
    ax = _grid(fig, 1, 1, left_in=2.6, top_in=0.85, bottom_in=0.55)[0, 0]
    k = cmp.settings["folds"]
    series = [("fit RMSE", [r.metrics["rmse"] for r in res], "0.6", ""),
              (f"{k}-fold CV RMSE (own rows)", [r.cv.rmse for r in res], "tab:cyan", "cv_rmse")]
    if _common(cmp):
        series.append((f"{k}-fold CV RMSE, rows all laws share (ranking)",
                       [r.cv_rmse_common for r in res], "tab:blue", "cv_rmse_common"))
    series.append(("extrapolation RMSE", [r.extrapolation_rmse for r in res], "tab:orange",
                   "extrapolation_rmse"))
    hgt = 0.8 / len(series)
    y = np.arange(n)
    allv = [v for _, vals, _, _ in series for v in vals if v is not None and math.isfinite(v)
            and v > 0]
    vmin = min(allv) if allv else 1e-3
    vmax = max(allv) if allv else 1.0
    for j, (name, vals, colour, key) in enumerate(series):
        yy = y + (j - (len(series) - 1) / 2) * hgt
        good = [v if v is not None and math.isfinite(v) and v > 0 else np.nan for v in vals]
        ax.barh(yy, good, height=hgt, color=colour, label=name)
        for yi, v, r in zip(yy, vals, res):
            if v is None or not math.isfinite(v):
                text = _score(r, key).rstrip("*") if key else "n/a"
                ax.text(vmin * 0.55, yi, text, va="center", fontsize=7)
    _log_axis(ax, vmin * 0.5, vmax * 2.0)
    ax.set_yticks(y, [f"{r.rank}. {r.law.id}" + ("" if r.plausible else " (implausible)")
                      for r in res])
    for lab, r in zip(ax.get_yticklabels(), res):
        if not r.plausible:
            lab.set_color("tab:red")
    ax.invert_yaxis()
    ax.set_xlabel("RMSE of mu [-] (log scale)")
    ax.set_ylabel("law (rank by CV RMSE)")
    ax.grid(axis="x", alpha=0.3)
    ax.legend(loc="lower left", bbox_to_anchor=(0.0, 1.0), ncols=2, fontsize=8,
              frameon=False, borderaxespad=0.2)
    fig.suptitle(f"{cmp.data.name}: error on fitted rows, unseen rows and the held-out "
                 "upper range", fontsize=10)
    caption = ("Fit RMSE (on the rows fitted), cross-validated RMSE (on rows left out of "
               "each fit; the ranking criterion) and extrapolation RMSE (on the held-out "
               "upper range), per law in rank order, on a log scale; implausible laws in "
               f"red; n/a: not available; {UNDETERMINED}: undetermined (the refits' rows cannot "
               "determine the predictions). The values are in the ranking table.")
    return Figure("metrics", "metrics", caption, _png(fig))


def _figure_plan(cmp: Comparison) -> list[tuple[Any, tuple[Any, ...]]]:
    """(drawing function, its extra arguments) of every figure of the report, in order."""
    var = cmp.design.varying
    plan: list[tuple[Any, tuple[Any, ...]]] = []
    if len(var) >= 2:
        plan += [(_fits_figure, (var[0], var[1])), (_fits_figure, (var[1], var[0]))]
    elif len(var) == 1:
        plan.append((_fits_figure, (var[0], None)))
    plan += [(_residuals_figure, ()), (_holdout_figure, ())]
    if cmp.box:
        plan.append((_box_figure, ()))
    plan.append((_metrics_figure, ()))
    return plan


def _draw(cmp: Comparison, index: int) -> Figure | None:
    """Draw figure ``index`` of the report's plan."""
    import matplotlib

    draw, args = _figure_plan(cmp)[index]
    with matplotlib.rc_context(RC):  # type: ignore[arg-type]
        return draw(cmp, *args, _styles(cmp)) if args else draw(cmp, _styles(cmp))


def _draw_share(cmp: Comparison, indices: Sequence[int]) -> list[Figure | None]:
    """Draw several figures of the plan in a worker process (module-level for joblib)."""
    return [_draw(cmp, i) for i in indices]


def make_figures(cmp: Comparison, jobs: int = 1) -> list[Figure]:
    """Render every figure of the report.

    Each figure is drawn on its own Agg canvas (pyplot and the user's backend are
    left alone), with a fixed layout, at :data:`DPI`.

    Parameters
    ----------
    cmp : Comparison
        The comparison to draw.
    jobs : int
        Processes drawing the figures (-1: one per core); 1 draws them here, one after
        another.  With more, each of ``jobs`` joblib workers draws one share of the
        figures, sent the comparison once.  A worker that has not drawn yet first
        imports the plotting code (a few tenths of a second), so two processes gain
        little on one report.

    Returns
    -------
    list of Figure
        The PNG figures in report order, the same with any ``jobs``.
    """
    count = len(_figure_plan(cmp))
    drawers = local_workers(jobs, count)
    if drawers == 1:
        return [f for f in (_draw(cmp, i) for i in range(count)) if f is not None]
    shares = [list(range(w, count, drawers)) for w in range(drawers)]
    drawn = list(starmap_local(_draw_share, ((cmp, share) for share in shares), drawers))
    figs: list[Figure | None] = [None] * count
    for share, figures in zip(shares, drawn):
        for i, f in zip(share, figures):
            figs[i] = f
    return [f for f in figs if f is not None]


# ------------------------------------------------------------- md and html


def _metric_table(cmp: Comparison) -> tuple[list[str], list[list[str]]]:
    head = ["rank", "law", "title", "k", "n", "R²", "adj. R²", "RMSE", "MAE", "max |res|",
            "AIC", "AICc", "BIC", "group", "Akaike w. (in group)", "CV RMSE",
            "CV RMSE (common rows)", "extrap. RMSE", "identifiable", "plausible", "residuals",
            "rank basis"]
    rows = []
    for r in cmp.results:
        m = r.metrics
        rows.append([str(r.rank), r.law.id, r.law.title, str(m["k"]), str(m["n"]),
                     _num(m["r2"], ".4f"), _num(m["adj_r2"], ".4f"), _num(m["rmse"], ".4f"),
                     _num(m["mae"], ".4f"), _num(m["max_abs_residual"], ".4f"),
                     _num(m["aic"], ".2f"), _num(m["aicc"], ".2f"), _num(m["bic"], ".2f"),
                     str(r.aic_group), _num(r.akaike_weight, ".3f"),
                     _score(r, "cv_rmse").replace("*", " *"),
                     _score(r, "cv_rmse_common").replace("*", " *"),
                     _score(r, "extrapolation_rmse"),
                     "NO" if r.fit.non_identifiable else "yes", _yes(r),
                     "structure" if r.residuals.structured else "ok", r.rank_basis])
    return head, rows


def _sections(cmp: Comparison) -> list[tuple[str, list[Any]]]:
    """(heading, items) for the prose parts; an item is a str or (str, sub-items)."""
    out: list[tuple[str, list[Any]]] = []
    plaus: list[Any] = []
    for r in cmp.results:
        if r.plausible:
            plaus.append(f"{r.law.id}: plausible (mu {_num(r.plausibility.mu_min)} .. "
                         f"{_num(r.plausibility.mu_max)} over the box)")
        else:
            plaus.append((f"{r.law.id}: IMPLAUSIBLE", list(r.plausibility.reasons)))
    out.append(("Plausibility outside the measured range", plaus))
    out.append(("Trends the data show", [t.describe() for t in cmp.trends.values()]))
    ex = []
    for r in cmp.results:
        parts = [f"{h.variable}: {h.error}" if h.error is not None else
                 f"{h.variable}: RMSE {UNDETERMINED} ({h.n_undetermined} of {h.n_test} "
                 f"held-out predictions undetermined; fitted on {h.n_train})"
                 if h.n_undetermined else
                 f"{h.variable}: implausible: {h.implausible} (fitted on {h.n_train})"
                 if h.implausible else
                 f"{h.variable}: RMSE {_num(h.rmse, '.4f')} on {h.n_test} held-out rows "
                 f"(fitted on {h.n_train})" for h in r.holdouts]
        ex.append(f"{r.law.id}: " + ("; ".join(parts) or "no holdout"))
    out.append(("Extrapolation to the held-out upper range", ex))
    cv = []
    for r in cmp.results:
        failed = {x["fold"] for x in r.cv.failed}
        und = {x["fold"] for x in r.cv.undetermined if x.get("n_undetermined")}
        folds = ", ".join(_num(f, ".3f") if f is not None else "failed" if i + 1 in failed
                          else UNDETERMINED if i + 1 in und else "no rows"
                          for i, f in enumerate(r.cv.fold_rmse))
        cv.append(f"{r.law.id}: CV RMSE {_score(r, 'cv_rmse').rstrip('*')} over "
                  f"{r.cv.n_scored} rows; "
                  f"per fold {folds}" + ("" if r.cv.complete else
                                         f"; {len(r.cv.failed)} fold(s) failed"))
    out.append(("Cross-validation", cv))
    struct: list[Any] = [(r.law.id, list(r.residuals.structure)) for r in cmp.results
                         if r.residuals.structure]
    out.append(("Residual structure (each test at the 5 % level)",
                struct or ["no law shows residual structure at the 5 % level"]))
    warn: list[Any] = [(r.law.id, list(r.fit.warnings)) for r in cmp.results if r.fit.warnings]
    out.append(("Fit warnings (identifiability, bounds)", warn or ["none"]))
    notes: list[Any] = list(cmp.data.notes) + list(cmp.notes)
    notes += [(r.law.id, r.notes + r.extra_notes) for r in cmp.results
              if r.notes or r.extra_notes]
    out.append(("Notes (dropped rows, failed folds)", notes or ["none"]))
    out.append(("Skipped laws (cannot be fitted to these data)",
                [f"{s['id']}: {s['reason']}" for s in cmp.skipped] or ["none"]))
    out.append(("Laws that failed to fit",
                [f"{f['id']}: {f['error']}" for f in cmp.failed] or ["none"]))
    return out


def _method(cmp: Comparison) -> list[str]:
    s = cmp.settings
    box = "; ".join(f"{k} {v['display']}" for k, v in s["extended_box"].items())
    hold = "; ".join(sp.describe() for sp in cmp.splits) or "none"
    return [
        f"Ranking: {s['ranking']}.",
        f"Cross-validation: {s['folds']} folds, rows shuffled with seed {s['seed']}; the same "
        "folds for every law; each fold refitted from the law's own data-driven start.",
        f"Extrapolation: {s['holdout_rule']}. Splits: {hold}.",
        f"Plausibility box: {box} ({s['extended_box_rule']}); physical limits "
        f"{s['mu_limits'][0]:g} <= mu <= {s['mu_limits'][1]:g}; {s['trend_rule']} "
        f"({s['trend_tolerance']['relative']:.0%} of mu, at least "
        f"{s['trend_tolerance']['absolute']:g}).",
        f"Akaike weights: {s['akaike_weights']}.",
        f"Residual tests: {s['residual_tests']}.",
        "RMSE, MAE, CV RMSE and extrapolation RMSE are in units of mu (dimensionless, -).",
    ]


RESIDUAL_TESTS_NOTE = (
    "One-sided Wald-Wolfowitz runs test on the signs of the residuals put in order of each "
    "variable and of the fitted value (small p: residuals of one sign cluster, a systematic "
    "misfit), Kendall's tau test of a monotone trend, and the Shapiro-Wilk test of "
    f"normal-looking residuals; each at the {ALPHA * 100:g} % level on its own. Marked: p < "
    f"{ALPHA:g} (a red band in the residuals figure). n/a: the test does not apply (a "
    "constant variable, or residuals all of one sign).")


def _residual_table(cmp: Comparison) -> tuple[list[str], list[list[tuple[str, bool]]]]:
    """Every residual test's p-value per law: header, rows of (text, below ALPHA)."""
    cols = [*cmp.design.varying, "fitted"]
    head = ["law"]
    for c in cols:
        name = "fitted mu" if c == "fitted" else c
        head += [f"runs p ({name})", f"Kendall p ({name})"]
    head.append("Shapiro-Wilk p")
    rows = []
    for r in cmp.results:
        ps = [p for c in cols for p in _test_p(r, c).values()] + [r.residuals.shapiro_p]
        rows.append([(f"{r.rank}. {r.law.id}", False)]
                    + [(_num(p, ".2g"), _flagged(p)) for p in ps])
    return head, rows


def _md_residual_tests(cmp: Comparison) -> list[str]:
    """The table of residual-test p-values in Markdown, the flagged ones in bold."""
    head, rows = _residual_table(cmp)
    lines = ["## Residual tests (p-values)", "", RESIDUAL_TESTS_NOTE, "",
             "| " + " | ".join(head) + " |", "|" + "|".join("---" for _ in head) + "|"]
    return lines + ["| " + " | ".join(f"**{markdown_text(t)}**" if bad else markdown_text(t)
                                      for t, bad in row) + " |" for row in rows]


def to_markdown(cmp: Comparison, figures: Sequence[Figure]) -> str:
    """The report as Markdown, linking the PNG files."""
    d = cmp.data
    esc = markdown_text  # every text from data, files or laws: one line, HTML escaped

    lines = [f"# Comparison of friction laws on {esc(d.name)}", "",
             f"Data: {esc(d.name)} ({esc(d.source)}), {d.n} rows; {esc(_ranges_text(cmp))}.",
             ""]
    lines += [f"- {esc(m)}" for m in _method(cmp)] + [""]
    head, rows = _metric_table(cmp)
    lines += ["## Ranking", "", "| " + " | ".join(esc(h) for h in head) + " |",
              "|" + "|".join("---" for _ in head) + "|"]
    lines += ["| " + " | ".join(esc(c) for c in r) + " |" for r in rows]
    lines += ["", "`*` cross-validation incomplete. Groups: laws fitted to the same rows; "
              "AIC-based numbers compare within a group only.", ""]
    lines += [f"- {esc(t)}" for t in _legend(cmp)] + [""]
    for heading, items in _sections(cmp):
        lines += [f"## {heading}", ""]
        for item in items:
            if isinstance(item, tuple):
                lines.append(f"- {esc(item[0])}")
                lines += [f"    - {esc(sub)}" for sub in item[1]]
            else:
                lines.append(f"- {esc(item)}")
        lines.append("")
    lines += _md_residual_tests(cmp) + ["", "## Figures", ""]
    for f in figures:
        lines += [f"### {esc(f.title)}", "", f"![{esc(f.title)}]({esc(f.name)}.png)", "",
                  esc(f.caption), ""]
    return "\n".join(lines)


_CSS = """
body{font-family:system-ui,-apple-system,Segoe UI,Helvetica,Arial,sans-serif;margin:2em;
color:#222;max-width:1400px}
table{border-collapse:collapse;font-size:13px;margin:1em 0}
th,td{border:1px solid #ccc;padding:3px 5px;text-align:right}
td.l,th.l{text-align:left}
td.law{min-width:13em;max-width:19em}
span.title{font-size:11px;color:#555}
tr.bad td{background:#fff0f0}
th{background:#f3f3f3}
.bad-word{color:#b00;font-weight:bold}
figure{margin:1.5em 0}
figure img{max-width:100%;border:1px solid #ddd}
figcaption{font-size:13px;color:#444;max-width:1100px}
li{margin:0.2em 0}
"""


def _html_ranking(cmp: Comparison) -> list[str]:
    """The ranking table in HTML; each law's title under its id."""
    e = html_text
    head, rows = _metric_table(cmp)
    # the title goes under the law id (a separate column makes the table too wide)
    skip = head.index("title")
    parts = ["<table><tr>" + "".join(f"<th class='{'l' if h == 'law' else ''}'>{e(h)}</th>"
                                     for i, h in enumerate(head) if i != skip) + "</tr>"]
    for r, row in zip(cmp.results, rows):
        cells = []
        for i, c in enumerate(row):
            if i == skip:
                continue
            text, cls_td = e(c), ""
            if head[i] in ("plausible", "identifiable") and c == "NO":
                text = "<span class='bad-word'>NO</span>"
            if head[i] == "law":
                text = f"<b>{e(c)}</b><br><span class='title'>{e(row[skip])}</span>"
                cls_td = "l law"
            cells.append(f"<td class='{cls_td}'>{text}</td>")
        cls = "" if r.plausible else " class='bad'"
        parts.append(f"<tr{cls}>" + "".join(cells) + "</tr>")
    parts.append("</table>")
    return parts


def _html_sections(cmp: Comparison) -> list[str]:
    """The prose sections as HTML lists, IMPLAUSIBLE highlighted."""
    e = html_text

    def mark(text: str) -> str:
        return e(text).replace("IMPLAUSIBLE", "<span class='bad-word'>IMPLAUSIBLE</span>")

    parts = []
    for heading, items in _sections(cmp):
        parts.append(f"<h2>{e(heading)}</h2><ul>")
        for item in items:
            if isinstance(item, tuple):
                subs = "".join(f"<li>{mark(sub)}</li>" for sub in item[1])
                parts.append(f"<li><b>{mark(item[0])}</b><ul>{subs}</ul></li>")
            else:
                parts.append(f"<li>{mark(item)}</li>")
        parts.append("</ul>")
    return parts


def _html_residual_tests(cmp: Comparison) -> list[str]:
    """The table of residual-test p-values in HTML, the flagged ones marked."""
    e = html_text
    head, rows = _residual_table(cmp)
    parts = ["<h2>Residual tests (p-values)</h2>", f"<p>{e(RESIDUAL_TESTS_NOTE)}</p>",
             "<table><tr>" + "".join(f"<th class='{'l' if i == 0 else ''}'>{e(h)}</th>"
                                     for i, h in enumerate(head)) + "</tr>"]
    for row in rows:
        cells = [f"<td class='l'>{e(row[0][0])}</td>"]
        cells += [f"<td><span class='bad-word'>{e(t)}</span></td>" if bad else f"<td>{e(t)}</td>"
                  for t, bad in row[1:]]
        parts.append("<tr>" + "".join(cells) + "</tr>")
    parts.append("</table>")
    return parts


def to_html(cmp: Comparison, figures: Sequence[Figure]) -> str:
    """Write the report as one self-contained HTML page (figures embedded as base64 PNG).

    Parameters
    ----------
    cmp : Comparison
        The comparison.
    figures : sequence of Figure
        The figures to embed, in order.

    Returns
    -------
    str
        The HTML page.
    """
    e = html_text
    d = cmp.data
    parts = ["<!DOCTYPE html>", "<html lang='en'><head><meta charset='utf-8'>",
             f"<title>Comparison of friction laws on {e(d.name)}</title>",
             f"<style>{_CSS}</style></head><body>",
             f"<h1>Comparison of friction laws on {e(d.name)}</h1>",
             f"<p>Data: <b>{e(d.name)}</b> ({e(d.source)}), {d.n} rows; "
             f"{e(_ranges_text(cmp))}.</p>",
             "<ul>" + "".join(f"<li>{e(m)}</li>" for m in _method(cmp)) + "</ul>",
             "<h2>Ranking</h2>", *_html_ranking(cmp),
             "<p>* cross-validation incomplete. Group: laws fitted to the same rows; "
             "AIC, AICc, BIC and Akaike weights compare laws within a group only (a law "
             "alone in its group has weight 1 trivially).</p>",
             "<ul>" + "".join(f"<li>{e(t)}</li>" for t in _legend(cmp)) + "</ul>",
             *_html_sections(cmp), *_html_residual_tests(cmp), "<h2>Figures</h2>"]
    for f in figures:
        b64 = base64.b64encode(f.png).decode("ascii")
        parts.append(f"<figure id='{e(f.name)}'><h3>{e(f.title)}</h3>"
                     f"<img alt='{e(f.title)}' src='data:image/png;base64,{b64}'>"
                     f"<figcaption>{e(f.caption)}</figcaption></figure>")
    parts.append("</body></html>")
    return "\n".join(parts)


def write_report(cmp: Comparison, directory: str | Path, jobs: int = 1) -> dict[str, Path]:
    """Write the PNG figures, ``report.md``, ``report.html`` and ``comparison.json``.

    Parameters
    ----------
    cmp : Comparison
        The comparison.
    directory : str or Path
        Where to write (created if missing).
    jobs : int
        Processes drawing the figures (see :func:`make_figures`).

    Returns
    -------
    dict of str to Path
        Name -> path of each file written.

    Notes
    -----
    The files are written by the output guard (:func:`frictionlaws.outputs.atomic_dir`):
    all of them or none, and never over a file read in this process.
    """
    from ..outputs import atomic_dir

    if isinstance(jobs, bool) or not isinstance(jobs, int) or not (jobs >= 1 or jobs == -1):
        raise InputError(f"jobs must be a whole number >= 1, or -1 for one per core, not "
                         f"{jobs!r}", option="jobs")
    out = Path(directory)
    with atomic_dir(out) as tmp:  # checks the directory before the figures are drawn
        figures = make_figures(cmp, jobs)
        for f in figures:
            (tmp / f"{f.name}.png").write_bytes(f.png)
        (tmp / "report.md").write_text(to_markdown(cmp, figures) + "\n", encoding="utf-8")
        (tmp / "report.html").write_text(to_html(cmp, figures) + "\n", encoding="utf-8")
        (tmp / "comparison.json").write_text(cmp.to_json() + "\n", encoding="utf-8")
    written = {f.name: out / f"{f.name}.png" for f in figures}
    written.update({n: out / n for n in ("report.md", "report.html", "comparison.json")})
    return written
