"""Figures of a prepared raw run: what was kept and dropped, and the steady sweeps.

:func:`plot_segments` draws the run against time (load, slip angle, slip ratio, camber and
pressure), the samples kept in one colour and those dropped in the colour of their reason;
:func:`plot_sweeps` the rows kept (lateral force and aligning moment against the slip angle,
longitudinal force against the slip ratio), by load, up and down sweeps apart.
:func:`write_plots` writes both as PNG files into a directory.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ...base.outputs import atomic_write
from ...io import output_dir
from .segments import REASONS, PreparedRun

__all__ = ["plot_segments", "plot_sweeps", "write_plots", "PLOT_FILES", "MAX_PLOTTED"]

#: The files :func:`write_plots` writes.
PLOT_FILES = ("segments.png", "sweeps.png")
#: Samples drawn per series at most (a long run is thinned evenly for the figure).
MAX_PLOTTED = 20_000
_COLOURS = {"kept": "C0", "lift": "0.6", "transition": "C1", "settling": "C8", "short": "C9",
            "warm-up": "C3", "dwell": "C7", "one-way": "C4", "thin bin": "C5"}


def _thin(n: int) -> slice:
    return slice(None, None, max(1, math.ceil(n / MAX_PLOTTED)))


def plot_segments(prepared: PreparedRun) -> Any:
    """The run against time, kept and dropped samples by reason (module documentation).

    Parameters
    ----------
    prepared : PreparedRun

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    q = prepared.run.quantities
    t = q["time"]
    panels = [("load [kN]", q["fz"] / 1e3), ("slip angle [deg]", np.degrees(q["alpha"])),
              ("slip ratio [-]", q["kappa"]), ("camber [deg]", np.degrees(q["gamma"]))]
    if np.isfinite(q["pressure"]).any():
        panels.append(("pressure [kPa]", q["pressure"] / 1e3))
    fig, axes = plt.subplots(len(panels), 1, figsize=(11, 1.9 * len(panels)), sharex=True,
                             layout="constrained")
    dropped = prepared.dropped()
    for ax, (label, values) in zip(axes, panels):
        for code, reason in enumerate(REASONS):
            if code and reason not in dropped:
                continue
            idx = np.flatnonzero(prepared.status == code)
            idx = idx[_thin(idx.size)]
            ax.plot(t[idx], values[idx], ".", ms=1.5, color=_COLOURS[reason],
                    label=reason if code else "kept")
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("time [s]")
    axes[0].legend(loc="upper right", ncol=5, fontsize="small", markerscale=6)
    kept = 100 * float(np.mean(prepared.status == 0))
    axes[0].set_title(f"{Path(prepared.run.source).name}: {kept:.1f} % of the samples kept; "
                      "dropped by reason in colour", fontsize="medium")
    return fig


def plot_sweeps(prepared: PreparedRun) -> Any:
    """The rows kept: Fy and Mz against the slip angle on slip-angle sweeps, Fx against the
    slip ratio on slip-ratio sweeps at zero slip angle, coloured by load; up and down
    sweeps with different markers.

    Parameters
    ----------
    prepared : PreparedRun

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    d = prepared.data
    kinds = {s.sweep: s for s in prepared.segments if s.kept}
    sweep = d.extra["sweep"].astype(int)
    lateral = np.array([kinds[s].kind == "lateral" for s in sweep])
    pure_x = np.array([kinds[s].kind == "longitudinal" and abs(kinds[s].alpha) < 0.01
                       for s in sweep])
    loads = prepared.levels["load"]
    level = (np.argmin(np.abs(d.fz[:, None] - loads[None, :]), axis=1) if loads.size
             else np.zeros(len(d), dtype=int))
    fig, axes = plt.subplots(1, 3, figsize=(13, 4), layout="constrained")
    series = ((axes[0], lateral, np.degrees(d.alpha), d.fy, "slip angle [deg]", "Fy [N]"),
              (axes[1], pure_x, d.kappa, d.fx, "slip ratio [-]", "Fx [N]"),
              (axes[2], lateral, np.degrees(d.alpha), d.mz, "slip angle [deg]", "Mz [N m]"))
    for ax, rows, x, y, xlabel, ylabel in series:
        for j in range(max(loads.size, 1)):
            for sign, marker in ((1.0, "^"), (-1.0, "v")):
                m = rows & (level == j) & (d.extra["direction"] == sign) & np.isfinite(y)
                label = (f"{loads[j] / 1e3:.3g} kN" if loads.size else None) if sign > 0 \
                    else None
                ax.plot(x[m], y[m], marker, ms=2.5, color=f"C{j % 10}", alpha=0.6,
                        label=label)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        ax.grid(alpha=0.3)
    axes[0].legend(title="load (^ up, v down)", fontsize="small")
    axes[1].set_title(f"{len(d)} rows from {len(kinds)} sweeps", fontsize="medium")
    return fig


def write_plots(prepared: PreparedRun, directory: str | Path) -> list[Path]:
    """Write :data:`PLOT_FILES` into ``directory`` (created; each file written atomically).

    Parameters
    ----------
    prepared : PreparedRun
    directory : str or Path

    Returns
    -------
    list of Path
    """
    import matplotlib.pyplot as plt


    out = output_dir(directory, "plot directory")
    written = []
    for name, draw in zip(PLOT_FILES, (plot_segments, plot_sweeps)):
        fig = draw(prepared)
        try:
            with atomic_write(out / name, "wb") as fh:
                fig.savefig(fh, format="png", dpi=110)
        finally:
            plt.close(fig)
        written.append(out / name)
    return written
