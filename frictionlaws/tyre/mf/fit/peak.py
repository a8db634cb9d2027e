"""The peak friction while a Magic Formula is fitted: kept physical, and said when unseen.

Two rules of :func:`frictionlaws.tyre.mf.fit.fit_mf`:

* **the peak friction stays physical during the fit.**  The peak coefficient
  ``mu = D / F_z`` at every measured condition is kept within :data:`PEAK_MU` by a
  penalty that is zero inside the range (so a fit that stays inside is unchanged,
  standard errors included) and grows with the excess outside it, in newtons
  (``excess * F_z`` times :data:`PENALTY_WEIGHT`).  While the solver searches, the
  model records the peak instead of refusing it (:class:`FittingModel`); the file
  written is read back by the ordinary, refusing model.
* **a peak the data do not reach is reported, not refused.**  When the fitted curve
  at a load still rises at the largest slip measured (on either side), the peak is
  extrapolated: the data determine the slope and the curvature, not the peak, and the
  standard errors of the peak coefficients (which assume the curve's shape holds beyond
  the data) understate their uncertainty.  :func:`unreached_peaks` finds those
  loads for a warning.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..equations import lateral, longitudinal, mf_curve
from ..model import MagicFormula

__all__ = ["PEAK_MU", "PENALTY_WEIGHT", "FittingModel", "peak_penalty", "unreached_peaks",
           "peak_message"]

#: Physical range of a tyre's peak friction coefficient [-]: from about 0.05 (a tyre on
#: wet ice) to about 4 (drag-racing slicks on a prepared track, the highest measured);
#: road and racing tyres on dry surfaces lie near 0.8..2.
PEAK_MU = (0.05, 4.0)
#: Penalty per unit of peak friction outside :data:`PEAK_MU`, as a multiple of F_z: an
#: excess of 0.01 costs as much as a 10 % misfit of the force at that point.
PENALTY_WEIGHT = 10.0
#: Points of the fitted curve per measured slip range when its peak is looked for.
_GRID = 201


class FittingModel(MagicFormula):
    """A Magic Formula that records its peak friction instead of refusing it.

    Used only while coefficients are searched: a trial step with an implausible peak
    then costs a penalty (:func:`peak_penalty`) instead of ending the fit.

    Parameters
    ----------
    *args, **kwargs
        As for :class:`~frictionlaws.tyre.mf.model.MagicFormula`.
    """

    def __init__(self, *args: Any, **kwargs: Any) -> None:
        super().__init__(*args, **kwargs)
        #: The peak friction of the last evaluation [-], one value per point.
        self.peak_mu: np.ndarray = np.array([])

    def check_peak(self, name: str, mu: Any, fz: Any, dpi: Any, gamma: Any = 0.0) -> None:
        """Record the peak friction ``mu`` (one value per point) instead of refusing it."""
        self.peak_mu = np.broadcast_to(np.asarray(mu, dtype=float), np.shape(fz)).copy()


def peak_penalty(mu: np.ndarray, fz: np.ndarray) -> np.ndarray:
    """Penalty residuals [N] of peak frictions outside :data:`PEAK_MU` (zero inside).

    Parameters
    ----------
    mu : numpy.ndarray
        Peak friction at each point [-] (``NaN`` counts as far outside).
    fz : numpy.ndarray
        Vertical load at each point [N].

    Returns
    -------
    numpy.ndarray
        ``PENALTY_WEIGHT * F_z * excess``, the excess being the distance of ``mu`` to
        the range.
    """
    lo, hi = PEAK_MU
    with np.errstate(invalid="ignore"):
        excess = np.maximum(mu - hi, 0.0) + np.maximum(lo - mu, 0.0)
    excess = np.where(np.isfinite(excess), excess, 1e3)
    return PENALTY_WEIGHT * np.abs(fz) * excess


def unreached_peaks(model: MagicFormula, direction: str, slip: np.ndarray, fz: np.ndarray,
                    gamma: np.ndarray, dpi: np.ndarray, labels: np.ndarray,
                    loads: np.ndarray) -> list[tuple[float, float]]:
    """Loads at which the fitted curve still rises at the largest slip measured.

    For each load level the fitted curve (at that load's mean camber and pressure) is
    evaluated from zero slip to the largest measured slip on each side; when its
    largest magnitude is at the end of that range, the peak lies beyond the data.

    Parameters
    ----------
    model : MagicFormula
        The fitted model.
    direction : {"x", "y"}
        Longitudinal (slip ratio) or lateral (slip angle [rad]).
    slip, fz, gamma, dpi : numpy.ndarray
        The measured points of that direction (reference conditions).
    labels : numpy.ndarray
        Load level of each point (index into ``loads``).
    loads : numpy.ndarray
        The load levels [N].

    Returns
    -------
    list of (float, float)
        ``(load [N], largest measured |slip|)`` of each load whose peak is not reached.
    """
    out = []
    for i, load in enumerate(loads):
        sel = labels == i
        if not sel.any():
            continue
        g, p = float(np.mean(gamma[sel])), float(np.mean(dpi[sel]))
        k = (longitudinal if direction == "x" else lateral)(model, np.array(load), g, p)
        edges = []
        for sign in (1.0, -1.0):
            side = sign * slip[sel]
            if not (side > 0).any():
                continue
            edge = float(side.max())
            s = sign * np.linspace(0.0, edge, _GRID)
            x = s if direction == "x" else np.tan(s)
            f = np.abs(mf_curve(x + k.S_H, k.B, k.C, k.D, k.E_a, k.E_b, 0.0))
            if int(np.argmax(f)) == f.size - 1:  # still rising at the last point measured
                edges.append(edge)
        if edges:
            out.append((float(load), max(edges)))
    return out


def peak_message(direction: str, unreached: Sequence[tuple[float, float]],
                 names: Sequence[str]) -> str:
    """The warning for loads whose peak the data do not reach.

    Parameters
    ----------
    direction : {"x", "y"}
        Longitudinal or lateral.
    unreached : sequence of (float, float)
        From :func:`unreached_peaks`.
    names : sequence of str
        The peak coefficients fitted (``PDX1``, ``PDY2``...), named in the message.

    Returns
    -------
    str
        One sentence: loads, largest slip, what is extrapolated and why.
    """
    loads = ", ".join(f"{load:g}" for load, _ in unreached)
    edge = max(s for _, s in unreached)
    slip = (f"|kappa| {edge:g}" if direction == "x"
            else f"|alpha| {math.degrees(edge):.3g} deg")
    coefs = f" ({', '.join(names)})" if names else ""
    return (f"F{direction}0: the data at F_z = {loads} N stop before the peak (largest "
            f"{slip}), so the peak friction mu_{direction}{coefs} is extrapolated, not "
            "determined by the data: it rests on the curve's shape beyond the data and its "
            "standard errors understate how uncertain it is (kept within "
            f"{PEAK_MU[0]:g}..{PEAK_MU[1]:g} during the fit); measure beyond the peak to "
            "determine it")
