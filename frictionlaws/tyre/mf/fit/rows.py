"""The pure-slip rows of tyre test data for one direction of a Magic Formula fit: which rows
count as pure slip (within :data:`~frictionlaws.tyre.mf.fit.stages.ALPHA_PURE` or
:data:`~frictionlaws.tyre.mf.fit.stages.KAPPA_PURE` of the other slip), their load levels and
the reference subset (nominal pressure, smallest camber).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ...data.table import TyreData
from .stages import ALPHA_PURE, KAPPA_PURE, level_scale

__all__ = ["Direction", "levels", "select_direction"]


def levels(values: np.ndarray, tol: float) -> tuple[np.ndarray, np.ndarray]:
    """Cluster ``values`` into levels (gaps > ``tol``): (level means, label of each value)."""
    order = np.argsort(values)
    sorted_v = values[order]
    breaks = np.flatnonzero(np.diff(sorted_v) > tol) + 1
    labels_sorted = np.zeros(values.size, dtype=int)
    for b in breaks:
        labels_sorted[b:] += 1
    labels = np.empty_like(labels_sorted)
    labels[order] = labels_sorted
    means = np.array([values[labels == i].mean() for i in range(len(breaks) + 1)])
    return means, labels


@dataclass
class Direction:
    """The pure-slip points of one direction ("x": F_x0 on kappa, "y": F_y0 on alpha)."""

    name: str
    slip: np.ndarray
    fz: np.ndarray
    gamma: np.ndarray
    dpi: np.ndarray
    force: np.ndarray
    load_labels: np.ndarray
    loads: np.ndarray
    reference: np.ndarray  # the rows at nominal pressure and smallest camber
    scale: np.ndarray  # each residual is divided by it (largest |force| at its load level)

    def x(self) -> np.ndarray:
        """The slip variable of the curve: kappa, or tan(alpha)."""
        return self.slip if self.name == "x" else np.tan(self.slip)


def select_direction(data: TyreData, name: str, p_nom: float | None) -> Direction | None:
    """The pure-slip rows of one direction, with their load levels and reference subset."""
    if name == "x":
        keep = np.isfinite(data.fx) & (np.abs(data.alpha) <= ALPHA_PURE)
        slip, force = data.kappa[keep], data.fx[keep]
    else:
        keep = np.isfinite(data.fy) & (np.abs(data.kappa) <= KAPPA_PURE)
        slip, force = data.alpha[keep], data.fy[keep]
    if keep.sum() == 0:
        return None
    fz, gamma, p = data.fz[keep], data.gamma[keep], data.pressure[keep]
    dpi = np.zeros(fz.size) if p_nom is None else np.where(np.isfinite(p),
                                                           (p - p_nom) / p_nom, 0.0)
    loads, labels = levels(fz, 0.03 * float(np.median(fz)))
    ref = np.ones(fz.size, dtype=bool)
    if np.isfinite(p).any() and p_nom is not None:
        p_lv, p_lab = levels(np.where(np.isfinite(p), p, p_nom), 0.02 * p_nom)
        ref &= p_lab == int(np.argmin(np.abs(p_lv - p_nom)))
    g_lv, g_lab = levels(gamma, math.radians(0.2))
    ref &= g_lab == int(np.argmin(np.abs(g_lv)))
    return Direction(name, slip, fz, gamma, dpi, force, labels, loads, ref,
                      level_scale(fz, force))

