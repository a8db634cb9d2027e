"""Benchmark of the brush model's local-sliding-speed mode (``sliding_speed="local"``).

Baseline, measured in the same run: the node-by-node march as it was before the rework
(a log-grid scan for the slowest sliding speed, then 45 bisection steps per sliding
node), kept here as :func:`march_local_bisection` and run on the same patch, slips and
law.  The model (``BrushModel._march_local``) solves all nodes of all slips together:
Newton sweeps over the patch with vectorised tip-speed Newton steps, then a check that
each sliding state is the one the node-by-node march picks; its own node-by-node march
(scan + regula falsi), which decides when the sweeps do not settle, is timed as well.
Printed: CPU milliseconds per load of each, the ratios, the target (<= 5 ms
per load) and the largest relative difference of the forces against the baseline.
``tests/tyre/test_tyre_brush_march.py`` checks the agreement.

Run: ``python benchmarks/bench_brush.py [--loads N] [--repeat R]``.
"""

from __future__ import annotations

import argparse
import math
import time
from typing import Any

import numpy as np

from frictionlaws.base.errors import DomainError
from frictionlaws.tyre.brush import BrushModel

#: A law whose friction rises with the sliding speed (a unique local steady state).
LAW = {"mu_s": 0.6, "mu_d": 1.0, "v_c": 0.05, "delta": 1.0}
#: The earlier march's constants.
BISECTION_STEPS = 45
SCAN = np.geomspace(1e-9, 1.0, 60)
#: The target for the model's march [ms per load].
TARGET_MS = 5.0


def march_local_bisection(model: BrushModel, p: np.ndarray, d: np.ndarray, vr: np.ndarray,
                          ds: float, c: float) -> tuple[np.ndarray, Any]:
    """The local-speed march of :class:`BrushModel` before the bisection-free rework (the baseline).

    Parameters
    ----------
    model : BrushModel
        The model (its law and tyre).
    p : numpy.ndarray
        Pressure at the patch nodes [Pa].
    d : numpy.ndarray
        Adhesion deflection increment per node of each slip [m].
    vr : numpy.ndarray
        Rolling speed of each slip [m/s].
    ds : float
        Node spacing [m].
    c : float
        Tread stiffness [N/m^2].

    Returns
    -------
    q : numpy.ndarray
        Bristle deflections [m], shape (slips, nodes).
    vs_range : tuple of float or None
        Lowest and highest sliding speed [m/s].
    """
    limit = model._limit
    l_static = limit(p, 0.0, c)
    q = np.zeros((d.size, p.size))
    qn = np.zeros(d.size)
    vs_min, vs_max = math.inf, -math.inf
    for k in range(1, p.size):
        qa = qn + d
        stick = qa <= l_static[k]
        if not stick.all():
            slide = ~stick
            qs, vrs = qa[slide], vr[slide]
            pk = p[k]
            x = SCAN[None, :]
            lim = limit(pk, (vrs * qs / ds)[:, None] * x, c, check=False)
            below = (qs[:, None] * (1.0 - x)) <= lim
            first = np.argmax(below, axis=1)
            if not below[np.arange(qs.size), first].all():
                raise DomainError("no steady sliding speed")
            lo = np.where(first > 0, SCAN[np.maximum(first - 1, 0)], 0.0)
            hi = SCAN[first]
            for _ in range(BISECTION_STEPS):
                mid = 0.5 * (lo + hi)
                lim = limit(pk, vrs * qs * mid / ds, c, check=False)
                ok = qs * (1.0 - mid) <= lim
                hi = np.where(ok, mid, hi)
                lo = np.where(ok, lo, mid)
            qslide = qs * (1.0 - hi)
            vs = vrs * (qs - qslide) / ds
            with np.errstate(all="ignore"):
                model._check_mu(np.asarray(model.mu(pk, vs), float), pk, vs)
            qa = qa.copy()
            qa[slide] = qslide
            vs_min = min(vs_min, float(vs.min()))
            vs_max = max(vs_max, float(vs.max()))
        qn = qa
        q[:, k] = qn
    return q, ((vs_min, vs_max) if vs_min <= vs_max else None)


def forces(q: np.ndarray, c: float, ds: float) -> np.ndarray:
    """Force of each slip from its deflections (trapezoid rule) [N]."""
    return c * (np.sum(q, axis=1) - 0.5 * (q[:, 0] + q[:, -1])) * ds


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loads", type=int, default=5, help="loads from 2 to 6.5 kN")
    ap.add_argument("--repeat", type=int, default=3, help="best of this many runs")
    args = ap.parse_args()
    model = BrushModel("exponential-decay", LAW, sliding_speed="local")
    c = model.tyre.c_py
    sigma = np.tan(np.radians([1.0, 2.0, 3.0, 0.0057, 0.0115]))  # cornering's five slips
    vr = np.full(sigma.size, model.tyre.speed)
    best = {"baseline": math.inf, "nodes": math.inf, "model": math.inf}
    worst = 0.0
    for _ in range(args.repeat):
        spent = dict.fromkeys(best, 0.0)
        for fz in np.linspace(2000.0, 6500.0, args.loads):
            s, p = model.tyre.patch(float(fz))
            ds = float(s[1] - s[0])
            d = sigma * ds
            t0 = time.process_time()
            q_old, _ = march_local_bisection(model, p, d, vr, ds, c)
            t1 = time.process_time()
            model._march_local_nodes(p, d, vr, ds, c, model._limit(p, 0.0, c))
            t2 = time.process_time()
            q_new, _ = model._march_local(p, d, vr, ds, c)
            t3 = time.process_time()
            spent["baseline"] += t1 - t0
            spent["nodes"] += t2 - t1
            spent["model"] += t3 - t2
            f_old, f_new = forces(q_old, c, ds), forces(q_new, c, ds)
            worst = max(worst, float(np.max(np.abs(f_new - f_old) / np.abs(f_old))))
        best = {k: min(best[k], spent[k]) for k in best}
    ms = {k: 1000.0 * t / args.loads for k, t in best.items()}
    print(f"brush local mode, exponential-decay {LAW}, {sigma.size} slips, "
          f"{model.tyre.nodes} nodes, {args.loads} loads, best of {args.repeat} (CPU time)")
    print(f"baseline (scan + 45 bisection steps per node):  {ms['baseline']:8.2f} ms per load")
    print(f"node-by-node fallback (scan + Illinois):        {ms['nodes']:8.2f} ms per load"
          f"  speed-up {ms['baseline'] / ms['nodes']:5.1f}x")
    print(f"model march (Newton sweeps over all nodes):     {ms['model']:8.2f} ms per load"
          f"  speed-up {ms['baseline'] / ms['model']:5.1f}x")
    verdict = "met" if ms["model"] <= TARGET_MS else "NOT met"
    print(f"target <= {TARGET_MS:g} ms per load: {verdict}")
    print(f"largest relative difference of the forces (model vs baseline): {worst:.2e}")


if __name__ == "__main__":
    main()
