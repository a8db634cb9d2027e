"""Figure of a Magic Formula fit: data and fitted curve per load (see
:class:`~frictionlaws.tyre.mf.fit.result.MFFit`)."""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from ....base.outputs import atomic_write, check_figure_path, check_outputs
from .rows import select_direction

__all__ = ["plot_fit"]


def plot_fit(result: Any, path: str | Path) -> Path:
    """Draw F_x0(kappa) and F_y0(alpha) per load at the reference conditions; save to ``path``.

    The reference conditions are the nominal pressure and the smallest camber
    measured (those of stage 1).  Written atomically; the format follows the suffix.
    """
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    fmt = check_figure_path(path)
    check_outputs([path], inputs=[result.data.source], what="figure")
    p_nom = result.model.nominal_pressure if result.version != "5.2" else None
    dirs = [d for d in (select_direction(result.data, n, p_nom) for n in ("x", "y"))
            if d is not None]
    fig, axes = plt.subplots(1, len(dirs), figsize=(6 * len(dirs), 4.5), squeeze=False,
                             layout="constrained")
    for ax, d in zip(axes[0], dirs):
        _panel(ax, d, result.model)
    with atomic_write(path, "wb") as fh:
        fig.savefig(fh, format=fmt)
    plt.close(fig)
    return Path(path)


def _panel(ax: Any, d: Any, model: Any) -> None:
    """One direction: measured points and the fitted curve at each load."""
    for i in range(d.loads.size):
        sel = d.reference & (d.load_labels == i)
        if not sel.any():
            continue
        fz = float(np.mean(d.fz[sel]))
        g = float(np.mean(d.gamma[sel]))
        dpi = float(np.mean(d.dpi[sel]))
        p = None if model.nominal_pressure is None else model.nominal_pressure * (1 + dpi)
        s = np.linspace(d.slip[sel].min(), d.slip[sel].max(), 200)
        scale = 1.0 if d.name == "x" else 180 / math.pi
        color = f"C{i % 10}"
        ax.plot(d.slip[sel] * scale, d.force[sel] / 1000, ".", color=color, ms=3)
        f = model.fx0(s, fz, g, p) if d.name == "x" else model.fy0(s, fz, g, p)
        ax.plot(s * scale, np.asarray(f) / 1000, "-", color=color, label=f"{fz / 1000:.3g} kN")
    ax.set_xlabel("kappa [-]" if d.name == "x" else "alpha [deg]")
    ax.set_ylabel(f"F{d.name}0 [kN]")
    ax.set_title(f"F{d.name}0: data (dots) and fit, per load")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", title="Fz")
