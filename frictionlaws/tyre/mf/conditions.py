"""The operating conditions of one steady-state evaluation, checked and broadcast once.

The inputs are listed in :data:`~frictionlaws.tyre.mf.inputs.INPUTS`.  :class:`Conditions`
checks them once (finite, loads positive,
speeds above VXLOW, slip angles within +-90 deg), broadcasts them against each other,
warns where they leave the file's validity ranges and, with ``saturate=True`` or
``loads_above_fzmax="clamp"``, clamps them as MFeval's limit checks do, recording which
rows were clamped (:attr:`Conditions.clamped`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ...base.errors import InputError, broadcast_shape
from .parameters import MFParameters

__all__ = ["Conditions"]


class Conditions:
    """The broadcast, checked (and optionally saturated) inputs of one evaluation.

    Parameters
    ----------
    p : MFParameters
        The tyre.
    kappa, alpha, fz, gamma : array-like
        Slip ratio [-], slip angle [rad], vertical load [N], camber [rad].
    pressure : array-like or None
        Inflation pressure [Pa] (None: the tyre's).
    vx : array-like or None
        Forward speed [m/s] (None: the file's LONGVL).
    saturate : bool
        Clamp the inputs at the file's limits as MFeval does.

    Attributes
    ----------
    kappa, alpha, gamma, fz, vx : numpy.ndarray
        The inputs as evaluated, broadcast to :attr:`shape` (``fz`` clamped at FZMAX
        where the model clamps).
    kappa_in, fz_in : numpy.ndarray
        The slip ratio and load as given.
    fz_mz, fz_mx, fz_my : numpy.ndarray
        The loads the aligning, overturning and rolling moments take (MFeval's
        reductions below FZMIN with ``saturate``).
    dpi : float or numpy.ndarray
        The relative pressure increment.
    clamped : dict of str to numpy.ndarray
        Input name -> the rows (boolean, :attr:`shape`) where it was clamped; only the
        inputs clamped on some row.
    """

    def __init__(self, p: MFParameters, kappa: Any, alpha: Any, fz: Any, gamma: Any,
                 pressure: Any, vx: Any, saturate: bool) -> None:
        k = p.check("kappa", kappa)
        a = p.check("alpha", alpha)
        z = p.check("fz", fz, positive=True)
        g = p.check("gamma", gamma)
        pr = np.asarray(p.pressure if pressure is None else pressure, dtype=float) \
            if (pressure is not None or p.pressure is not None) else None
        v = p.check("vx", p.need("LONGVL") if vx is None else vx)
        vxlow = p.structure.get("VXLOW", 0.0)
        if not (v > vxlow).all():
            raise InputError(f"speeds at or below VXLOW = {vxlow:g} m/s (or backwards) are "
                             "not modelled here: the steady-state outputs need vx > VXLOW",
                             file=p.source)
        named = {"kappa": k, "alpha": a, "fz": z, "gamma": g, "vx": v}
        shape = broadcast_shape({**named, **({"pressure": pr} if pr is not None else {})},
                                p.source)
        self.shape = shape
        self.clamped: dict[str, np.ndarray] = {}
        self.kappa_in = np.broadcast_to(k, shape)
        self.fz_in = np.broadcast_to(z, shape)
        self.vx = np.broadcast_to(v, shape)
        clipped = self._limit(p, {"kappa": k, "alpha": a, "gamma": g, "pressure": pr},
                              saturate)
        self.kappa = np.broadcast_to(clipped["kappa"], shape)
        self.alpha = np.broadcast_to(clipped["alpha"], shape)
        if np.any(np.abs(self.alpha) >= np.pi / 2):
            raise InputError("slip angles must lie strictly between -90 and 90 degrees")
        self.gamma = np.broadcast_to(clipped["gamma"], shape)
        self.pressure = clipped["pressure"]
        self._loads(p, saturate)
        self.dpi = p.dpi(None if self.pressure is None else self.pressure)

    def _limit(self, p: MFParameters, given: dict[str, Any], saturate: bool
               ) -> dict[str, Any]:
        """Each input clipped to the file's range (``saturate``) or warned about."""
        clipped: dict[str, Any] = {}
        for name, x in given.items():
            if x is None:
                clipped[name] = None
            elif saturate and name in p.limits:
                clipped[name] = np.clip(x, *p.limits[name])
                self._record(name, np.asarray(clipped[name]) != x)
            else:
                p.warn_range(name, x)
                clipped[name] = x
        return clipped

    def _record(self, name: str, rows: Any) -> None:
        rows = np.broadcast_to(rows, self.shape)
        if rows.any():
            self.clamped[name] = rows.copy()

    def _loads(self, p: MFParameters, saturate: bool) -> None:
        """The loads of the forces and moments: clamped at FZMAX (``saturate`` or
        ``loads_above_fzmax="clamp"``), else warned about; MFeval's reductions below
        FZMIN with ``saturate``."""
        fzmin, fzmax = p.limits.get("fz", (0.0, np.inf))
        if saturate or p.loads_above_fzmax == "clamp":
            self.fz = np.minimum(self.fz_in, fzmax)
            self._record("fz", (self.fz_in > fzmax) | (saturate & (self.fz_in < fzmin)))
        else:
            p.warn_range("fz", self.fz_in)
            self.fz = self.fz_in
        self.fz_mz = np.maximum(self.fz, fzmin) if saturate else self.fz
        # MFeval's reduction of the load below FZMIN in M_x (squared) and M_y (linear)
        low = saturate & (self.fz_in < fzmin) if fzmin > 0 else np.zeros(self.shape, bool)
        ratio = np.where(low, self.fz_in / max(fzmin, 1e-300), 1.0)
        self.fz_mx = np.where(low, self.fz * ratio**2, self.fz)
        self.fz_my = np.where(low, self.fz_in * ratio, self.fz_in)
