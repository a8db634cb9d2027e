"""Diagnostic plots of processed records (matplotlib, Agg backend, imported on use)."""

from __future__ import annotations

import math
import re
import textwrap
from pathlib import Path
from typing import Any

import numpy as np

__all__ = ["plot_record", "plot_conditions", "plot_name"]


def _pyplot() -> Any:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_name(file: str) -> str:
    """PNG file name for a record (path separators and odd characters replaced)."""
    stem = re.sub(r"\.[A-Za-z0-9]+$", "", file.strip()) or "record"
    return re.sub(r"[^A-Za-z0-9._-]+", "_", stem).strip("_") + ".png"


def plot_record(directory: Path, result: Any, record: Any, signals: Any) -> Path:
    """Raw and filtered torque, friction coefficient and the window of one record.

    Parameters
    ----------
    directory : Path
        Output directory.
    result : RecordResult
        The record's result (title, window, status).
    record : Record
        The raw record.
    signals : _Signals or None
        Filtered signals (None when the record failed before filtering: only the
        raw torque is drawn).
    """
    plt = _pyplot()
    fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(9, 6), sharex=True)
    t = record.time
    step = max(1, t.size // 6000)  # keep the PNG light: at most ~6000 points per line
    ax1.plot(t[::step], record.torque[::step], lw=0.5, color="0.6", label="raw torque")
    if signals is not None:
        ax1.plot(t, signals.filtered, lw=1.0, color="C0",
                 label=f"filtered ({result.cutoff:.3g} Hz)")
        ax2.plot(t, signals.mu, lw=1.0, color="C1", label="mu (offsets subtracted)")
        if signals.segment is not None:
            a, b = signals.segment
            ax2.axvspan(t[a], t[b - 1], color="0.9", label="motors at speed")
        if signals.window is not None:
            w = signals.window
            ax2.axvspan(t[w.start], t[w.stop - 1], color="C2", alpha=0.25,
                        label=f"window ({result.window_source})")
            ax1.axvspan(t[w.start], t[w.stop - 1], color="C2", alpha=0.15)
        if math.isfinite(result.mu):
            ax2.axhline(result.mu, color="C3", lw=1.0, ls="--", label=f"mu = {result.mu:.4g}")
        lo, hi = np.nanpercentile(signals.mu, [0.5, 99.5])
        pad = 0.15 * (hi - lo if hi > lo else 1.0)
        ax2.set_ylim(lo - pad, hi + pad)
    ax1.set_ylabel("torque [N m]")
    ax2.set_ylabel("mu [-]")
    ax2.set_xlabel("time [s]")
    ax1.legend(loc="upper right", fontsize=8)
    ax2.legend(loc="upper right", fontsize=8)
    status = result.status if result.status == "used" else f"{result.status}: {result.reason}"
    title = textwrap.fill(f"{result.file} - {status}", 120)
    fig.suptitle(title if title.count("\n") < 3 else
                 "\n".join(title.splitlines()[:3]) + " ...", fontsize=8)
    fig.tight_layout()
    out = Path(directory) / plot_name(result.file)
    fig.savefig(out, dpi=80)
    plt.close(fig)
    return out


def plot_conditions(path: Path, campaign: Any) -> Path:
    """Mean mu against contact pressure per surface, with the 95 % intervals."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 4.5))
    conds = [c for c in campaign.conditions if c.written]
    surfaces = sorted({c.surface for c in conds})
    for k, surf in enumerate(surfaces):
        sel = [c for c in conds if c.surface == surf]
        p = np.array([c.p for c in sel]) / 1e6
        mu = np.array([c.mu for c in sel])
        lo = np.array([c.ci95[0] for c in sel])
        hi = np.array([c.ci95[1] for c in sel])
        # lists, not arrays: matplotlib < 3.10 converts a one-point array row to a
        # scalar with a NumPy deprecation warning
        ax.errorbar(p, mu, yerr=[(mu - lo).tolist(), (hi - mu).tolist()], fmt="o", ms=4,
                    capsize=3,
                    color=f"C{k % 10}", label=surf)
    ax.set_xlabel("contact pressure p [MPa]")
    ax.set_ylabel("mu [-] (mean, 95 % CI)")
    if surfaces:
        ax.legend(fontsize=8)
    ax.set_title(f"{len(conds)} conditions from {len(campaign.records)} records", fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    return Path(path)
