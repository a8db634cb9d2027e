"""Rig-like tyre test data generated from a Magic Formula, for checking fits.

:func:`rig_data` measures a known tyre the way a flat-track rig does: at several loads,
pressures and cambers it sweeps the slip ratio and the slip angle up and down and runs a
combined-slip grid; the recorded slips jitter, the load drifts and every force and moment
carries noise.  :func:`moved_tyre` makes a tyre unlike a template by moving its
coefficients, :func:`random_tyre` one drawn at random (for held-out checks).
``tests/tyre/test_tyre_fit_mf_stages.py``, ``tests/tyre/test_tyre_fit_mf_held_out.py`` and
``benchmarks/bench_fit_mf.py`` fit :func:`~frictionlaws.tyre.mf.fit.fit_mf` to such data
and compare the result with the noise-free truth.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from .data.table import TyreData
from .mf.model import MagicFormula

__all__ = ["rig_data", "moved_tyre", "random_tyre", "truth_errors", "MOVED", "RANDOM_MOVED"]

#: Coefficients of the packaged MF 6.1 example moved (multiplied) to make another tyre:
#: peak, stiffness, shape, shifts, combined-slip and aligning coefficients, 5-50 %.
MOVED = {"PDX1": 0.92, "PKX1": 1.15, "PCX1": 1.05, "PEX1": 0.9, "PDY1": 1.06, "PKY1": 0.88,
         "PCY1": 0.95, "PEY1": 1.1, "PDY2": 1.1, "PKY2": 1.1, "PVY1": 1.5, "PHY1": 0.7,
         "RBX1": 1.2, "RBY1": 0.85, "RCX1": 1.05, "RCY1": 0.95, "RVY1": 0.8, "QBZ1": 1.1,
         "QDZ1": 0.9, "QCZ1": 1.05, "QDZ6": 1.3, "QEZ1": 0.9, "QHZ1": 1.2}


def moved_tyre(template: str = "MagicFormula61", factors: Mapping[str, float] = MOVED,
               set_to: Mapping[str, float] | None = None, *, fnomin: float | None = None,
               nominal_pressure: float | None = None) -> MagicFormula:
    """A tyre unlike ``template``: coefficients multiplied by ``factors``, others set.

    Parameters
    ----------
    template : str
        A property file or packaged example.
    factors : mapping
        Coefficient -> factor (default :data:`MOVED`).
    set_to : mapping, optional
        Coefficient -> value (default: a moment arm the example lacks, SSZ1 = 0.01,
        SSZ2 = 0.02).
    fnomin, nominal_pressure : float, optional
        Another nominal load [N] and nominal pressure [Pa] (default: the template's;
        for MF 5.2, which has no pressure, 2.6e5 Pa for the rig).

    Returns
    -------
    MagicFormula
        The moved tyre, with the template's limits and structure.
    """
    base = MagicFormula.from_file(template)
    c = dict(base.coefficients)
    for k, f in factors.items():
        c[k] = c.get(k, 0.0) * f
    c.update({"SSZ1": 0.01, "SSZ2": 0.02} if set_to is None else dict(set_to))
    p = nominal_pressure or base.nominal_pressure or 2.6e5
    return MagicFormula(c, fnomin=fnomin or base.fnomin, version=base.version, pressure=p,
                        nominal_pressure=p, limits=base.limits, structure=base.structure,
                        name=f"moved {base.name}")


#: Coefficients :func:`random_tyre` moves: those of :data:`MOVED` and the load dependence
#: of the peaks, stiffnesses, curvatures and shifts.
RANDOM_MOVED = tuple(MOVED) + ("PDX2", "PKX2", "PKX3", "PEX2", "PHX1", "PVX1", "PVX2", "PKY4",
                               "PEY2", "PHY2", "PVY2", "RBX2", "RBY2", "QBZ2", "QDZ2", "QDZ7")
#: The packaged examples :func:`random_tyre` starts from, in turn.
RANDOM_TEMPLATES = ("MagicFormula61", "MagicFormula62", "MagicFormula52")


def random_tyre(seed: int, *, spread: float = 0.2, fnomin: tuple[float, float] = (3e3, 9e3),
                pressure: tuple[float, float] = (1.8e5, 3.2e5)) -> MagicFormula:
    """A tyre drawn at random for held-out checks of a fit.

    The packaged example ``RANDOM_TEMPLATES[seed % 3]`` with each coefficient of
    :data:`RANDOM_MOVED` it has multiplied by a factor uniform in ``1 +- spread``, the moment
    arm's SSZ1 and SSZ2 uniform in -0.02..0.02, FNOMIN uniform in ``fnomin`` [N] and the
    nominal pressure uniform in ``pressure`` [Pa] (seeded: the same seed, the same tyre).
    """
    rng = np.random.default_rng(seed)
    template = RANDOM_TEMPLATES[seed % len(RANDOM_TEMPLATES)]
    have = MagicFormula.from_file(template).coefficients
    factors = {k: 1.0 + spread * float(rng.uniform(-1.0, 1.0)) for k in RANDOM_MOVED}
    factors = {k: f for k, f in factors.items() if k in have}
    set_to = {k: float(rng.uniform(-0.02, 0.02)) for k in ("SSZ1", "SSZ2")}
    return moved_tyre(template, factors, set_to,
                      fnomin=float(rng.uniform(*fnomin)),
                      nominal_pressure=float(rng.uniform(*pressure)))


def rig_data(truth: MagicFormula, *, n: int = 31, loads: Sequence[float] = (0.4, 0.7, 1.0,
             1.3, 1.6), pressures: Sequence[float] = (0.85, 1.1),
             cambers_deg: Sequence[float] = (-3.0, 0.0, 3.0), combined: bool = True,
             noise: float = 0.01, seed: int = 3, kappa_max: float = 0.25,
             alpha_max_deg: float = 12.0) -> TyreData:
    """Flat-track-like measurements of ``truth`` (SI, ISO axes).

    At every load (times FNOMIN), pressure (times the nominal pressure) and camber: a
    slip-ratio sweep -0.25..0.25 and a slip-angle sweep -12..12 deg, each up and down
    with ``n`` points, and (``combined``) slip-ratio sweeps -0.2..0.2 (15 points) at slip
    angles -8, -4, 4 and 8 deg (all scaled by ``kappa_max`` / 0.25 and ``alpha_max_deg``
    / 12).  The recorded slips jitter (normal, 0.002 in slip ratio;
    uniform 0.1-0.3 deg in slip angle on the slip-ratio sweeps, +-0.3 deg elsewhere), the
    load drifts (normal, 1 %; the recorded load is the one applied), and F_x, F_y, M_z
    carry normal noise of ``noise`` times each load's largest magnitude.

    Parameters
    ----------
    truth : MagicFormula
        The tyre measured (with its structure, for M_z).
    n : int
        Points per pure-slip sweep.
    loads, pressures : sequence of float
        Multiples of FNOMIN and of the nominal pressure.
    cambers_deg : sequence of float
        Cambers [deg].
    combined : bool
        Add the combined-slip grid.
    noise : float
        Noise share of each load's peak.
    seed : int
        Random seed.
    kappa_max, alpha_max_deg : float
        The largest slip ratio and slip angle [deg] swept (default 0.25 and 12).

    Returns
    -------
    TyreData
        With ``fx``, ``fy`` and ``mz`` on every row.
    """
    rng = np.random.default_rng(seed)
    blocks = []
    p_nom = truth.nominal_pressure or 2.6e5
    for fz in truth.fnomin * np.asarray(loads):
        for p in p_nom * np.asarray(pressures):
            for g in np.radians(cambers_deg):
                k = np.linspace(-kappa_max, kappa_max, n)
                a = np.radians(np.linspace(-alpha_max_deg, alpha_max_deg, n))
                for ks in (k, k[::-1]):
                    side = np.radians(rng.uniform(0.1, 0.3, n)) * rng.choice([-1, 1], n)
                    blocks.append((fz, ks + rng.normal(0, 0.002, n), side, g, p))
                for as_ in (a, a[::-1]):
                    blocks.append((fz, rng.normal(0, 0.002, n),
                                   as_ + np.radians(rng.uniform(-0.3, 0.3, n)), g, p))
                if combined:
                    kk = np.linspace(-0.8, 0.8, 15) * kappa_max
                    for deg in np.array([-8, -4, 4, 8]) * alpha_max_deg / 12:
                        blocks.append((fz, kk + rng.normal(0, 0.002, kk.size),
                                       np.radians(deg + rng.uniform(-0.3, 0.3, kk.size)),
                                       g, p))
    level, kappa, alpha, gamma, pressure = (
        np.concatenate([np.broadcast_to(b[i], b[1].shape) for b in blocks]) for i in range(5))
    fz = level * (1 + rng.normal(0, 0.01, level.size))
    out = truth.steady_state(kappa, alpha, fz, gamma, pressure=pressure)

    def noisy(v: np.ndarray) -> np.ndarray:
        v = v.copy()
        for lv in np.unique(level):
            m = level == lv
            v[m] += noise * np.abs(v[m]).max() * rng.standard_normal(int(m.sum()))
        return v

    return TyreData.from_arrays(fz=fz, kappa=kappa, alpha=alpha, gamma=gamma,
                                pressure=pressure, fx=noisy(out["Fx"]), fy=noisy(out["Fy"]),
                                mz=noisy(out["Mz"]), source="<synthetic rig data>")


def truth_errors(truth: MagicFormula, fitted: MagicFormula, *,
                 loads: Sequence[float] = (0.4, 0.7, 1.0, 1.3, 1.6),
                 pressures: Sequence[float] = (0.85, 1.1),
                 cambers_deg: Sequence[float] = (-3.0, 0.0, 3.0), kappa_max: float = 0.25,
                 alpha_max_deg: float = 12.0) -> dict[str, float]:
    """Largest errors of ``fitted`` against the noise-free ``truth``, as shares of the peak.

    At every load (times FNOMIN), pressure (times the nominal pressure) and camber of
    :func:`rig_data`: pure F_x0 on kappa -0.25..0.25 and F_y0 on alpha -12..12 deg, each
    as a share of that curve's peak; combined F_x and F_y on the grid kappa -0.2..0.2 at
    alpha -8, -4, 4, 8 deg, as shares of the pure curves' peaks; and M_z, pure and on the
    grid, as a share of the pure M_z curve's peak.  The slips scale with ``kappa_max`` /
    0.25 and ``alpha_max_deg`` / 12, as in :func:`rig_data`.

    Returns
    -------
    dict
        ``"Fx0"``, ``"Fy0"``, ``"Fx"``, ``"Fy"``, ``"Mz"`` -> the largest share [-].
    """
    k = np.linspace(-kappa_max, kappa_max, 101)
    a = np.radians(np.linspace(-alpha_max_deg, alpha_max_deg, 97))
    K, A = np.meshgrid(np.linspace(-0.8, 0.8, 21) * kappa_max,
                       np.radians(np.array([-8.0, -4.0, 4.0, 8.0]) * alpha_max_deg / 12))
    out: dict[str, float] = {}
    for fz in truth.fnomin * np.asarray(loads):
        for p in (truth.nominal_pressure or 2.6e5) * np.asarray(pressures):
            for g in np.radians(cambers_deg):
                pt, pf = (p if m.nominal_pressure else None  # none: no pressure terms
                          for m in (truth, fitted))
                tx, ty = truth.fx0(k, fz, g, pt), truth.fy0(a, fz, g, pt)
                t0, f0 = (m.steady_state(0.0, a, fz, g, pressure=q)
                          for m, q in ((truth, pt), (fitted, pf)))
                t, f = (m.steady_state(K, A, fz, g, pressure=q)
                        for m, q in ((truth, pt), (fitted, pf)))
                peak = np.abs(t0["Mz"]).max()
                errs = {"Fx0": np.abs(fitted.fx0(k, fz, g, pf) - tx).max() / np.abs(tx).max(),
                        "Fy0": np.abs(fitted.fy0(a, fz, g, pf) - ty).max() / np.abs(ty).max(),
                        "Fx": np.abs(f["Fx"] - t["Fx"]).max() / np.abs(tx).max(),
                        "Fy": np.abs(f["Fy"] - t["Fy"]).max() / np.abs(ty).max(),
                        "Mz": max(np.abs(f0["Mz"] - t0["Mz"]).max(),
                                  np.abs(f["Mz"] - t["Mz"]).max()) / peak}
                for name, e in errs.items():
                    out[name] = max(out.get(name, 0.0), float(e))
    return out
