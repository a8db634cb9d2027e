"""The report's figures: fits, residual strips, hold-outs, the extended box and the metrics,
drawn cheaply (few axes, fixed layouts) in one process or several (:func:`make_figures`).
"""

from __future__ import annotations

import io
import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from ...parallel import local_workers, starmap_local
from ..extrapolation import Split, evaluate_on, fmt_value
from ..residuals import ALPHA

if TYPE_CHECKING:  # pragma: no cover
    from ..record import ComparisonRecord, LawComparison

from .text import (
    BIN_ABOVE,
    DPI,
    MAX_PANELS,
    PNG_COMPRESSION,
    RC,
    SCATTERED,
    TICKS,
    UNDETERMINED,
    _common,
    _disp,
    _label,
    _score,
)

__all__ = ["Figure", "STRIP", "FLAG_COLOUR", "make_figures"]


@dataclass
class Figure:
    """One PNG figure of the report."""

    name: str
    title: str
    caption: str
    png: bytes


def _styles(cmp: ComparisonRecord) -> dict[str, dict[str, Any]]:
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


def _law_handles(cmp: ComparisonRecord, styles: dict[str, dict[str, Any]],
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


def _mode_level(cmp: ComparisonRecord, rows: np.ndarray, others: list[str]) -> dict[str, float]:
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


def _panel_title(cmp: ComparisonRecord, g: str, level: float, mask: np.ndarray, kind: str) -> str:
    if kind == "bin":
        gm = cmp.data.arrays[g][mask]
        title = f"{g} {fmt_value(g, float(gm.min()))} .. {fmt_value(g, float(gm.max()))}"
    else:
        title = f"{g} = {fmt_value(g, level)}"
    nr = int(mask.sum())
    return f"{title} ({nr} row{'s' if nr != 1 else ''})"


def _fits_panel(cmp: ComparisonRecord, ax: Any, x: str, fixed: dict[str, float], mask: np.ndarray,
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


def _fits_figure(cmp: ComparisonRecord, x: str, g: str | None, styles: dict[str, Any]
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


def _strip(cmp: ComparisonRecord, r: LawComparison, column: str
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


def _residuals_figure(cmp: ComparisonRecord, styles: dict[str, Any]) -> Figure:
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


def _holdout_panel(cmp: ComparisonRecord, ax: Any, split: Split, styles: dict[str, Any]) -> None:
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


def _holdout_figure(cmp: ComparisonRecord, styles: dict[str, Any]) -> Figure | None:
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


def _box_mode(cmp: ComparisonRecord, x: str) -> dict[str, float]:
    """The level of the other variables at which the panel of ``x`` is drawn."""
    others = [k for k in cmp.box if k != x and k in cmp.design.varying]
    return _mode_level(cmp, np.ones(cmp.data.n, bool), others)


def _box_panel(cmp: ComparisonRecord, ax: Any, x: str, styles: dict[str, Any]) -> None:
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


def _box_figure(cmp: ComparisonRecord, styles: dict[str, Any]) -> Figure:
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


def _metrics_figure(cmp: ComparisonRecord, styles: dict[str, Any]) -> Figure:
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


def _figure_plan(cmp: ComparisonRecord) -> list[tuple[Any, tuple[Any, ...]]]:
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


def _draw(cmp: ComparisonRecord, index: int) -> Figure | None:
    """Draw figure ``index`` of the report's plan."""
    import matplotlib

    draw, args = _figure_plan(cmp)[index]
    with matplotlib.rc_context(RC):  # type: ignore[arg-type]
        return draw(cmp, *args, _styles(cmp)) if args else draw(cmp, _styles(cmp))


def _draw_share(cmp: ComparisonRecord, indices: Sequence[int]) -> list[Figure | None]:
    """Draw several figures of the plan in a worker process (module-level for joblib)."""
    return [_draw(cmp, i) for i in indices]


def make_figures(cmp: ComparisonRecord, jobs: int = 1) -> list[Figure]:
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

