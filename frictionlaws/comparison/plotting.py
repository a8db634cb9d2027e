"""Figures of fits and comparisons: a grid of fitted laws, and a comparison's errors.

* :func:`plot_fit_grid`: one panel per fitted law, the measured points coloured by a
  second variable (e.g. the sliding velocity) and each law drawn at the levels it was
  fitted on; rows a law could not use are open circles.
* :func:`plot_comparison` (also :meth:`Comparison.plot
  <frictionlaws.comparison.results.Comparison.plot>`): the in-sample, cross-validated and
  extrapolation RMSE of every law of a comparison, in rank order, laws the plausibility
  scan flags hatched.

Axes are in display units (p in MPa, T in degC, see :mod:`frictionlaws.base.display`).
matplotlib is imported inside the functions.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np

from ..base.display import unit_text
from ..base.errors import InputError
from ..base.units import QUANTITIES, display_unit, to_display

__all__ = ["plot_fit_grid", "plot_comparison"]


def _axis_label(name: str) -> str:
    return f"{name} [{unit_text(display_unit(name)) if name in QUANTITIES else '-'}]"


def _shown(values: Any, name: str) -> np.ndarray:
    arr = np.asarray(values, dtype=float)
    return to_display(arr, name) if name in QUANTITIES else arr


def _level_curve(result: Any, arrays: Mapping[str, np.ndarray], x: str, grid: np.ndarray,
                 by: str | None, level: float | None) -> np.ndarray | None:
    """The law along ``grid`` at one level of ``by`` (None when it is outside the fit)."""
    if by is not None and level is not None and result.extrapolation({by: np.array([level])}):
        return None
    order = np.argsort(arrays[x], kind="stable")
    variables: dict[str, np.ndarray] = {}
    for name in result.law.variables:
        if name == x:
            variables[name] = grid
        elif name == by and level is not None:
            variables[name] = np.full_like(grid, level)
        else:  # another variable follows x as it does in the data (F_N with p)
            variables[name] = np.interp(grid, arrays[x][order], arrays[name][order])
    mu = result.law.evaluate(variables or {x: grid}, result.values)
    return np.broadcast_to(np.asarray(mu, dtype=float), grid.shape)


def _panel(ax: Any, result: Any, arrays: Mapping[str, np.ndarray], x: str, by: str | None,
           colors: Mapping[float, Any]) -> None:
    grid = np.linspace(arrays[x].min(), arrays[x].max(), 120)
    levels = list(colors) if by is not None else [None]
    for level in levels:
        rows = (arrays[by] == level) if by is not None else np.ones(arrays["mu"].size, bool)
        color = colors.get(level, "C0") if level is not None else "C0"
        curve = _level_curve(result, arrays, x, grid, by, level)
        ax.plot(_shown(arrays[x][rows], x), arrays["mu"][rows], "o", ms=4, color=color,
                mfc=color if curve is not None else "none")
        if curve is not None:
            ax.plot(_shown(grid, x), curve, color=color, lw=1.5)
    m = result.metrics
    flag = " (!)" if result.non_identifiable else ""
    ax.set_title(f"{result.law.id}{flag}\nR² = {m['r2']:.3f}, n = {m['n']}", fontsize=9,
                 color="C3" if result.non_identifiable else "k")
    ax.grid(alpha=0.3)


def plot_fit_grid(results: Mapping[str, Any], data: Any, *, x: str = "p",
                  by: str | None = "v", ncol: int = 4) -> Any:
    """One panel per fitted law: data, and each law at the levels of ``by`` it was fitted on.

    Parameters
    ----------
    results : mapping of str to FitResult
        The fits, by name (their panels in this order).
    data : Dataset or mapping of arrays
        The measured data (SI), with ``mu``, ``x`` and ``by``.
    x : str
        The variable on the horizontal axis.
    by : str or None
        The variable whose levels colour the points and curves (None: one colour).
    ncol : int
        Panels per row.

    Returns
    -------
    matplotlib.figure.Figure
        A red title with ``(!)`` marks a fit with parameters the data cannot determine;
        an open circle a row at a level the law was not fitted on (no curve there).
    """
    import matplotlib.pyplot as plt

    arrays = data.arrays() if hasattr(data, "arrays") else data
    arrays = {k: np.asarray(v) for k, v in arrays.items()}
    if not results:
        raise InputError("no fits to plot")
    for need in ("mu", x, *([by] if by else [])):
        if need not in arrays:
            raise InputError(f"the data have no column '{need}' to plot")
    levels: Any = np.unique(arrays[by]) if by else []
    colors = dict(zip(levels, plt.get_cmap("viridis")(np.linspace(0, 0.8, len(levels)))))
    ncol = max(1, min(ncol, len(results)))
    nrow = math.ceil(len(results) / ncol)
    fig, axes = plt.subplots(nrow, ncol, figsize=(3.3 * ncol, 2.9 * nrow), sharex=True,
                             sharey=True, layout="constrained", squeeze=False)
    for ax, result in zip(axes.flat, results.values()):
        _panel(ax, result, arrays, x, by, colors)
    for ax in axes.flat[len(results):]:
        ax.set_visible(False)
    for col in range(ncol):
        shown = [ax for ax in axes[:, col] if ax.get_visible()]
        if shown:
            shown[-1].xaxis.set_tick_params(labelbottom=True)
            shown[-1].set_xlabel(_axis_label(x))
    for ax in axes[:, 0]:
        ax.set_ylabel("μ [-]")
    if by:
        unit = _axis_label(by).split("[", 1)[1].rstrip("]")
        handles = [plt.Line2D([], [], color=colors[v], marker="o",
                              label=f"{by} = {float(_shown([v], by)[0]):g} {unit}")
                   for v in levels]
        handles.append(plt.Line2D([], [], color="0.3", marker="o", mfc="none", ls="none",
                                  label="row not used by the law"))
        fig.legend(handles=handles, loc="outside lower center", ncol=len(handles))
    return fig


def plot_comparison(comparison: Any, *, ax: Any = None, log: bool = True) -> Any:
    """The fit, cross-validated and extrapolation RMSE of each law of a comparison.

    Parameters
    ----------
    comparison : Comparison
        From :func:`frictionlaws.comparison.compare`.
    ax : matplotlib Axes, optional
        Where to draw; a new figure otherwise.
    log : bool
        A logarithmic RMSE axis (default).

    Returns
    -------
    matplotlib.figure.Figure
        Bars in rank order, labelled with the law and its number of parameters;
        hatched bars mark laws the plausibility scan flags.
    """
    import matplotlib.pyplot as plt

    results = list(comparison.results)
    if not results:
        raise InputError("the comparison has no fitted law to plot")
    bars = {"RMSE (fit)": [r.metrics["rmse"] for r in results],
            "CV RMSE": [r.cv.rmse for r in results],
            "extrapolation RMSE": [r.extrapolation_rmse for r in results]}
    if ax is None:
        _, ax = plt.subplots(figsize=(max(6.0, 1.6 * len(results)), 4.2), layout="constrained")
    x = np.arange(len(results))
    width = 0.27
    for i, (name, values) in enumerate(bars.items()):
        drawn = ax.bar(x + (i - 1) * width, np.asarray(values, float), width, label=name,
                       color=f"C{i}")
        for bar, r in zip(drawn, results):
            if not r.plausible:
                bar.set_hatch("//")
                bar.set_edgecolor("k")
    ax.set_xticks(x, [f"{r.law.id}\n(k = {r.metrics['k']})" for r in results])
    if log:
        ax.set_yscale("log")
    ax.set_ylabel("RMSE in μ [-]")
    ax.grid(alpha=0.3, axis="y")
    handles, labels = ax.get_legend_handles_labels()
    if any(not r.plausible for r in results):
        handles.append(plt.Rectangle((0, 0), 1, 1, facecolor="w", edgecolor="k", hatch="//"))
        labels.append("flagged implausible outside the data")
    ax.legend(handles, labels, fontsize="small")
    return ax.figure
