"""The brush model (:class:`BrushModel`): a friction law on a brush tyre's contact patch, the
local march of the bristles, and cornering sweeps.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from scipy.linalg.lapack import dtbtrs

from ...base.errors import DomainError, ExtrapolationWarning, InputError
from ...law import VARIABLES, Law
from ...law.bound import as_bound
from ...law.registry import get_law
from .result import CorneringResult
from .tyre import (
    BISECTION_STEPS,
    DEFAULT_ANGLES_DEG,
    LOCAL_VARIABLES,
    NEWTON_SWEEPS,
    ORIGIN_STEP,
    SLIDING_SPEEDS,
    SLIP_SCAN,
    SWEEP_TOL,
    TIP_STEPS,
    BrushTyre,
    positive_load,
)

__all__ = ["BrushModel"]


def _law_mu(bound: Callable[..., Any], names: tuple[str, ...]) -> Callable[..., Any]:
    """mu(p, v) of a bound law whatever its variables (none, p, v, or both)."""
    if names == ():
        mu0 = float(bound())

        def mu(p: Any, v: Any = 0.0) -> Any:
            return np.full(np.broadcast(p, v).shape, mu0)
    elif names == ("p",):
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(p)
    elif names == ("v",):
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(v) + 0.0 * p
    else:
        def mu(p: Any, v: Any = 0.0) -> Any:
            return bound(p=p, v=v)
    return mu


def _function_mu(func: Callable[..., Any]) -> Callable[..., Any]:
    """mu(p, v) of a user's function, given the speed's magnitude, as a float array."""
    def mu(p: Any, v: Any = 0.0) -> Any:
        return np.asarray(func(p, np.abs(v)), dtype=float) + 0.0 * p
    return mu


class BrushModel:
    """A brush tyre whose bristles obey a friction law mu(p, v).

    Parameters
    ----------
    law : str, Law, BoundLaw, FitResult or callable
        A registered law (id or :class:`~frictionlaws.law.Law`) with
        ``params``/``preset``; a :class:`~frictionlaws.law.bound.BoundLaw` or a fit
        result (its law and values; its fitted data range is used for
        extrapolation warnings); or a plain
        function ``mu(p, v)`` of pressure [Pa] and sliding speed [m/s].
    params : mapping, optional
        Parameter values of the law (SI).
    preset : str, optional
        A named preset of the law.
    tyre : BrushTyre, optional
        The tyre (default :class:`BrushTyre()`).
    sliding_speed : {"slip", "local"}
        Sliding speed given to a law that depends on v: ``"slip"`` (default)
        the speed of a fully sliding element, ``V tan(alpha)`` or
        ``V |kappa|``; ``"local"`` the bristle tip's own speed
        ``V_r (sigma - dq/ds)``, solved per node (see the module notes).

    Raises
    ------
    DomainError
        When the law needs a variable other than p and v (F_N, T, s).
    """

    def __init__(self, law: Any, params: Mapping[str, float] | None = None, *,
                 preset: str | None = None, tyre: BrushTyre | None = None,
                 sliding_speed: str = "slip") -> None:
        if sliding_speed not in SLIDING_SPEEDS:
            raise InputError(f"sliding_speed must be one of {', '.join(SLIDING_SPEEDS)}, "
                             f"got {sliding_speed!r}")
        self.sliding_speed = sliding_speed
        self.tyre = tyre if tyre is not None else BrushTyre()
        if not isinstance(self.tyre, BrushTyre):
            raise InputError("tyre must be a BrushTyre")
        self.law: Law | None = None
        self.fitted_ranges: dict[str, tuple[float, float]] = {}
        if isinstance(getattr(law, "law", None), Law):  # a BoundLaw or a fit result
            if params is not None or preset is not None:
                raise InputError("give either a bound law (or fit result) or params/preset, "
                                 "not both")
            bound = as_bound(law)
            self.fitted_ranges = dict(bound.fitted_ranges)
            params = bound.values
            law = bound.law
        if isinstance(law, (str, Law)):
            self._use_law(law, params, preset)
        elif callable(law):
            if params is not None or preset is not None:
                raise InputError("params/preset apply to a registered law, not to a function")
            self.values: dict[str, float] = {}
            self.uses_v = True
            self.label: str = getattr(law, "__name__", "function")
            self.mu = _function_mu(law)
        else:
            raise InputError(f"law must be a law name, a Law, a fit result or a function "
                             f"mu(p, v); got {type(law).__name__}")
        self._ranges = self._reference_ranges()

    def _use_law(self, law: str | Law, params: Mapping[str, float] | None,
                 preset: str | None) -> None:
        """Take a registered law of p and/or v, with its parameter values, as the limit."""
        self.law = get_law(law)
        extra = [v for v in self.law.variables if v not in LOCAL_VARIABLES]
        if extra or self.law.family != "sliding":
            what = ", ".join(f"{v} ({VARIABLES[v].meaning})" for v in extra)
            raise DomainError(
                f"law '{self.law.id}' cannot be the local friction limit of a brush "
                f"model: it needs {what or 'a slip ratio'}, while a bristle only has its "
                "contact pressure p and sliding speed v. Use a law of p and/or v "
                "(e.g. coulomb, thirion, savkoor, exponential-decay)")
        self.values = self.law.resolve(params, preset)
        adm = self.law.check_admissible(self.values)
        if adm:
            raise DomainError(f"law '{self.law.id}': parameters not admissible: {adm}")
        self.uses_v = "v" in self.law.variables
        self.label = self.law.id
        self.mu = _law_mu(self.law.bind(self.values), self.law.variables)

    # -------------------------------------------------------------- checks
    def _reference_ranges(self) -> dict[str, tuple[float, float, str]]:
        out: dict[str, tuple[float, float, str]] = {}
        if self.law is None:
            return out
        for var in self.law.variables:
            if var in self.fitted_ranges:
                lo, hi = self.fitted_ranges[var]
                out[var] = (lo, hi, "fitted data range")
            elif var in self.law.domain:
                lo, hi = self.law.domain[var]
                out[var] = (lo, hi, "valid domain of the law")
        return out

    def _limit(self, p: Any, v: Any, c: float, check: bool = True) -> np.ndarray:
        """Deflection limit mu p w / c [m]; raises on NaN or negative mu when ``check``."""
        with np.errstate(all="ignore"):
            mu = self._at_edges(np.asarray(self.mu(p, v), dtype=float), p, v)
        if check:
            self._check_mu(mu, p, v)
        return mu * self._limit_scale(p, c)

    def _at_edges(self, mu: np.ndarray, p: Any, v: Any) -> np.ndarray:
        """mu where the pressure is 0 (the patch's edges), for the limit mu p w / c.

        A law without a limit at p = 0 (mu growing as p -> 0) has no mu there, but
        the limit needs only mu p: where that goes to 0 (mu growing slower than 1/p,
        checked at p = 1e-100 and 1e-290 Pa) the limit is 0, and mu = 0 gives it;
        elsewhere mu stays NaN and is refused.
        """
        pb = np.broadcast_to(np.asarray(p, float), mu.shape)
        edge = (pb == 0) & ~np.isfinite(mu)
        if not edge.any():
            return mu
        vb = np.broadcast_to(np.asarray(v, float), mu.shape)[edge]
        with np.errstate(all="ignore"):
            q = [np.asarray(self.mu(e + 0.0 * vb, vb), float) * e for e in (1e-100, 1e-290)]
        vanishes = (np.isfinite(q[1]) & (np.abs(q[1]) <= 1e-12)
                    & (np.abs(q[1]) <= np.abs(q[0])))
        out = mu.copy()
        out[edge] = np.where(vanishes, 0.0, np.nan)
        return out

    def _limit_scale(self, p: Any, c: float) -> Any:
        """The deflection limit per unit mu, p w / c [m]."""
        return p * (self.tyre.width / c)

    def _check_mu(self, mu: np.ndarray, p: Any, v: Any) -> None:
        bad = ~np.isfinite(mu) | (mu < 0)
        if bad.any():
            i = np.unravel_index(int(np.flatnonzero(bad.ravel())[0]), bad.shape)
            pb = np.broadcast_to(np.asarray(p, float), mu.shape)[i]
            vb = np.broadcast_to(np.asarray(v, float), mu.shape)[i]
            raise DomainError(
                f"law '{self.label}' gives mu = {float(mu[i])!r} at p = {pb / 1e6:.4g} MPa, "
                f"v = {vb:.4g} m/s inside the contact patch: not usable as a friction limit "
                "there (check its parameters and valid domain)")

    def _pressure_share(self, p: np.ndarray) -> float:
        """Share of the load carried at pressures outside the law's fitted/valid range of p."""
        if "p" not in self._ranges:
            return 0.0
        lo, hi, _ = self._ranges["p"]
        outside = (p < lo * (1 - 1e-9)) | (p > hi * (1 + 1e-9))
        return float(np.sum(p[outside]) / np.sum(p)) if outside.any() else 0.0

    def _extrapolation(self, cases: list[tuple[float, np.ndarray, Any]]) -> list[str]:
        """Messages for loads whose patch leaves the law's range; ``cases`` = (fz, p, vs_range)."""
        msgs = []
        if "p" in self._ranges:
            lo, hi, what = self._ranges["p"]
            hits = [(fz, self._pressure_share(p), float(p.max())) for fz, p, _ in cases]
            hits = [h for h in hits if h[1] > 0.005]
            if hits:
                span = (f"{100 * hits[0][1]:.0f} % of the load at {hits[0][0] / 1000:g} kN"
                        if len(hits) == 1 else
                        f"{100 * hits[0][1]:.0f} % (at {hits[0][0] / 1000:g} kN) to "
                        f"{100 * hits[-1][1]:.0f} % (at {hits[-1][0] / 1000:g} kN) of the load")
                msgs.append(
                    f"law '{self.label}' is extrapolated: contact pressures outside the "
                    f"{what} of p ({lo / 1e6:.3g}..{hi / 1e6:.3g} MPa) carry {span}; "
                    f"patch pressures reach {max(h[2] for h in hits) / 1e6:.3g} MPa")
        if "v" in self._ranges:
            lo, hi, what = self._ranges["v"]
            out = [(fz, r) for fz, _, r in cases
                   if r is not None and (r[0] < lo * (1 - 1e-9) or r[1] > hi * (1 + 1e-9))]
            if out:
                vmin = min(r[0] for _, r in out)
                vmax = max(r[1] for _, r in out)
                msgs.append(
                    f"law '{self.label}' is extrapolated: sliding speeds {vmin:.3g}..{vmax:.3g} "
                    f"m/s leave the {what} of v ({lo:.3g}..{hi:.3g} m/s) at "
                    f"{', '.join(f'{fz / 1000:g}' for fz, _ in out)} kN")
        return msgs

    # --------------------------------------------------------------- core
    @staticmethod
    def _march(L: np.ndarray, d: np.ndarray) -> np.ndarray:
        """Deflections q_k = min(q_{k-1} + d, L_k), q_0 = 0, for every slip (closed form).

        With u_k = q_k - k d the recursion is u_k = min(u_{k-1}, L_k - k d), a
        cumulative minimum.  ``L`` is (nodes,) or (slips, nodes); ``d`` (slips,).
        """
        j = np.arange(L.shape[-1])
        M = np.broadcast_to(L, (d.size, L.shape[-1])) - j[None, :] * d[:, None]
        M[:, 0] = 0.0
        return j[None, :] * d[:, None] + np.minimum.accumulate(M, axis=1)

    def _solve(self, sigma: np.ndarray, fz: float, c: float, v_roll: Any,
               nodes: int | None = None, keep: bool = False) -> dict[str, Any]:
        """Forces for slip magnitudes ``sigma`` >= 0 (1-D) at load ``fz``."""
        s, p = self.tyre.patch(fz, nodes)
        ds = s[1] - s[0]
        n_nodes = s.size
        sigma = np.asarray(sigma, dtype=float)
        d = sigma * ds
        vr = np.broadcast_to(np.asarray(v_roll, float), sigma.shape)
        vs_range = None
        if not self.uses_v:
            q = self._march(self._limit(p, 0.0, c), d)
        elif self.sliding_speed == "slip":
            vs = vr * sigma  # sliding speed of a fully sliding element
            q = self._march(self._limit(p[None, :], vs[:, None], c), d)
            slides = np.any(q < np.arange(n_nodes)[None, :] * d[:, None] * (1 - 1e-9), axis=1)
            if slides.any():
                vs_range = (float(vs[slides].min()), float(vs[slides].max()))
        else:
            q, vs_range = self._march_local(p, d, vr, ds, c)
        force = c * (np.sum(q, axis=1) - 0.5 * (q[:, 0] + q[:, -1])) * ds
        out: dict[str, Any] = {"force": force, "p": p, "s": s, "vs_range": vs_range}
        if keep:
            out["q"] = q
        return out

    def _march_local(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float, c: float
                     ) -> tuple[np.ndarray, tuple[float, float] | None]:
        """March with the local tip sliding speed V_r (sigma - dq/ds).

        All nodes of all slips are solved together (:meth:`_march_local_sweeps`); when
        that does not settle on the march's own solution (no steady sliding state, a
        law with several, mu unusable) the node-by-node march
        (:meth:`_march_local_nodes`) decides, and raises its errors.
        """
        l_static = self._limit(p, 0.0, c)
        fast = self._march_local_sweeps(p, d, vr, ds, c, l_static)
        if fast is not None:
            return fast
        return self._march_local_nodes(p, d, vr, ds, c, l_static)

    def _march_local_sweeps(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float,
                            c: float, l_static: np.ndarray
                            ) -> tuple[np.ndarray, tuple[float, float] | None] | None:
        """The local-speed march as one Newton iteration over the whole patch, or None.

        Node k maps its adhesion trial ``a_k = q_{k-1} + d`` to ``q_k = F_k(a_k)``: ``a_k``
        where it sticks (``a_k <= L_static``), else ``a_k - v/rate`` with ``v`` the tip
        speed solving ``a_k - v/rate = limit(p_k, v)`` (``rate = V_r/ds``), and
        ``F_k' = beta/(1 + beta)``, ``beta = rate dlimit/dv`` (1 where it sticks).  Each
        sweep solves every node's equation at once (:meth:`_tip_speeds`, warm-started)
        and takes the Newton step of the chain ``q_k = F_k(q_{k-1} + d)``, a
        lower-bidiagonal system.  It starts from the march at the static limit.  Returns
        None when it does not converge or when :meth:`_local_state_ok` rejects the
        result, so that the node-by-node march decides.
        """
        n_slips, n = d.size, p.size - 1
        pk = np.tile(p[1:], n_slips)  # flat over (slip, node)
        ls = np.tile(l_static[1:], n_slips)
        rate = np.repeat(vr / ds, n)
        q = self._march(l_static, d)
        v = np.zeros(n_slips * n)
        band = np.zeros((2, n_slips * n))  # unit lower-bidiagonal, LAPACK band storage
        sub = band[1].reshape(n_slips, n)  # sub[:, k] couples node k + 1 to node k
        with np.errstate(all="ignore"):
            for _ in range(NEWTON_SWEEPS):
                a = (q[:, :-1] + d[:, None]).ravel()
                i = np.flatnonzero(a > ls)  # the sliding nodes
                if i.size == 0:
                    break  # every bristle sticks: the static march is exact
                v[i], dlim, settled = self._tip_speeds(pk[i], a[i], rate[i], c, v[i])
                f, slope = a.copy(), np.ones(a.size)
                f[i] = a[i] - v[i] / rate[i]
                slope[i] = dlim / (1.0 / rate[i] + dlim)
                sub[:, :-1] = -slope.reshape(n_slips, n)[:, 1:]
                step = dtbtrs(band, f - q[:, 1:].ravel(), uplo="L", diag="U")[0]
                q[:, 1:] += step.reshape(n_slips, n)
                if not np.all(np.isfinite(step)):
                    return None
                if settled and np.max(np.abs(step)) <= SWEEP_TOL * np.max(np.abs(q)):
                    break
            else:
                return None
            a = (q[:, :-1] + d[:, None]).ravel()
            i = np.flatnonzero(a > ls)
            speed = rate[i] * (a[i] - q[:, 1:].ravel()[i])
            if not self._local_state_ok(pk[i], a[i], speed, rate[i], c):
                return None
        return q, ((float(speed.min()), float(speed.max())) if speed.size else None)

    def _tip_speeds(self, pk: np.ndarray, a: np.ndarray, rate: np.ndarray, c: float,
                    v: np.ndarray) -> tuple[np.ndarray, np.ndarray, bool]:
        """Tip speeds v of sliding bristles: ``h(v) = a - v/rate - limit(pk, v) = 0``.

        Newton steps from the warm start ``v`` (forward-difference slope of the limit)
        inside the bracket ``[lo, hi]`` with ``h(lo) > 0 >= h(hi)`` that starts as
        ``[0, rate a]`` and shrinks with every evaluation (a step leaving it bisects
        it instead); at most :data:`TIP_STEPS`
        steps (the sweeps of :meth:`_march_local_sweeps` continue them).  Returns the
        speeds, the slopes ``dlimit/dv`` [s] and whether every ``|h| <= 1e-14 a``.
        """
        lo, hi = np.zeros_like(a), rate * a
        v = np.clip(v, lo, hi)
        dlim, settled = np.zeros_like(a), True
        scale = self._limit_scale(pk, c)  # limit = mu scale
        inv_rate, tol = 1.0 / rate, 1e-14 * a
        both = np.empty((2, a.size))
        for _ in range(TIP_STEPS):
            dv = 1e-7 * v + 1e-13
            both[0] = v
            np.add(v, dv, out=both[1])
            mu = np.broadcast_to(np.asarray(self.mu(pk, both), dtype=float), both.shape)
            lim = mu[0] * scale
            dlim = (mu[1] * scale - lim) / dv
            h = a - v / rate - lim  # as the sweep divides (q = 0 exactly where p = 0)
            pos = h > 0
            lo, hi = np.where(pos, v, lo), np.where(pos, hi, v)
            settled = bool(np.all(np.abs(h) <= tol))
            v_new = v + h / (inv_rate + dlim)
            v = np.where((v_new >= lo) & (v_new <= hi), v_new, 0.5 * (lo + hi))
            if settled:
                break
        return v, dlim, settled

    def _local_state_ok(self, pk: np.ndarray, a: np.ndarray, speed: np.ndarray,
                        rate: np.ndarray, c: float) -> bool:
        """Whether the sweeps' sliding states are those the node-by-node march picks.

        That march takes the first point of the log grid :data:`SLIP_SCAN` of
        ``x = (a - q)/a`` where the limit holds and the root between it and the point
        before; the state at ``x = speed/(rate a)`` must lie in that interval (it always
        does when the limit does not fall with speed: the root is then unique), and mu
        there must be usable.
        """
        if a.size == 0:
            return True
        lim = self._limit(pk[:, None], (rate * a)[:, None] * SLIP_SCAN[None, :], c, check=False)
        below = (a[:, None] * (1.0 - SLIP_SCAN[None, :])) <= lim
        first = np.argmax(below, axis=1)
        upper = SLIP_SCAN[first]
        lower = np.where(first > 0, SLIP_SCAN[np.maximum(first - 1, 0)], 0.0)
        x = speed / (rate * a)
        mu = np.asarray(self.mu(pk, speed), float)
        return bool(np.all(below[np.arange(a.size), first]) and np.all(x <= upper * (1 + 1e-9))
                    and np.all(x >= lower * (1 - 1e-9)) and np.all(np.isfinite(mu))
                    and np.all(mu >= 0))

    def _march_local_nodes(self, p: np.ndarray, d: np.ndarray, vr: np.ndarray, ds: float,
                           c: float, l_static: np.ndarray
                           ) -> tuple[np.ndarray, tuple[float, float] | None]:
        """The local-speed march node by node (a scan and regula falsi per node)."""
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
                x = self._slowest_slide(pk, qs, vrs, ds, c, l_static[k])
                qslide = qs * (1.0 - x)
                vs = vrs * (qs - qslide) / ds
                with np.errstate(all="ignore"):
                    self._check_mu(np.asarray(self.mu(pk, vs), float), pk, vs)
                qa = qa.copy()
                qa[slide] = qslide
                vs_min = min(vs_min, float(vs.min()))
                vs_max = max(vs_max, float(vs.max()))
            qn = qa
            q[:, k] = qn
        return q, ((vs_min, vs_max) if vs_min <= vs_max else None)

    def _slowest_slide(self, pk: float, qs: np.ndarray, vrs: np.ndarray, ds: float, c: float,
                       l_static: float) -> np.ndarray:
        """x = (q_a - q)/q_a of the slowest steady sliding state of each sliding bristle.

        The bristle at pressure ``pk`` with adhesion trial ``qs`` settles where its
        deflection meets the friction limit at its own tip speed:
        ``g(x) = qs (1 - x) - limit(pk, V_r qs x / ds) = 0``.  The root with the smallest
        sliding speed is bracketed by the first sign change of ``g`` on a log grid of x,
        then found by regula falsi with the Illinois modification (superlinear, and
        never leaving the bracket) to :data:`BISECTION_STEPS` halvings of the bracket;
        the returned x is the end of the final bracket where the limit holds.
        """
        x = SLIP_SCAN[None, :]
        lim = np.broadcast_to(self._limit(pk, (vrs * qs / ds)[:, None] * x, c, check=False),
                              (qs.size, SLIP_SCAN.size))
        below = (qs[:, None] * (1.0 - x)) <= lim
        first = np.argmax(below, axis=1)
        rows = np.arange(qs.size)
        if not below[rows, first].all():
            bad = int(np.flatnonzero(~below[rows, first])[0])
            raise DomainError(
                f"law '{self.label}': no steady sliding speed (tried up to "
                f"{vrs[bad] * qs[bad] / ds:.3g} m/s) holds a sliding bristle at "
                f"p = {pk / 1e6:.4g} MPa: the law falls with sliding speed there "
                "(velocity weakening) or turns negative, so the local-speed steady "
                "state does not exist; use sliding_speed='slip'")
        hi = SLIP_SCAN[first]
        g_hi = qs * (1.0 - hi) - lim[rows, first]
        prev = np.maximum(first - 1, 0)
        lo = np.where(first > 0, SLIP_SCAN[prev], 0.0)
        g_lo = np.where(first > 0, qs * (1.0 - lo) - lim[rows, prev], qs - l_static)
        return self._illinois(pk, qs, vrs, ds, c, (lo, hi, g_lo, g_hi))

    def _illinois(self, pk: float, qs: np.ndarray, vrs: np.ndarray, ds: float, c: float,
                  bracket: tuple[np.ndarray, ...]) -> np.ndarray:
        """Shrink brackets with g(lo) > 0 >= g(hi) around the root; return the hi ends."""
        lo, hi, g_lo, g_hi = bracket
        tol = (hi - lo) * 2.0**-BISECTION_STEPS
        side = np.zeros(qs.size)
        for _ in range(4 * BISECTION_STEPS):
            active = (hi - lo > tol) & (g_hi < 0)
            if not active.any():
                break
            with np.errstate(all="ignore"):
                x = hi - g_hi * (hi - lo) / (g_hi - g_lo)
            x = np.where((x > lo) & (x < hi), x, 0.5 * (lo + hi))
            g = qs * (1.0 - x) - self._limit(pk, vrs * qs * x / ds, c, check=False)
            ok = active & (g <= 0)
            up = active & ~(g <= 0)
            g_lo = np.where(ok & (side > 0), 0.5 * g_lo, g_lo)  # Illinois: the end that
            g_hi = np.where(up & (side < 0), 0.5 * g_hi, g_hi)  # stayed twice counts half
            hi, g_hi = np.where(ok, x, hi), np.where(ok, g, g_hi)
            lo, g_lo = np.where(up, x, lo), np.where(up, g, g_lo)
            side = np.where(ok, 1.0, np.where(up, -1.0, side))
        return hi

    def _full_sliding(self, fz: float, slide_speed: np.ndarray) -> np.ndarray:
        """Force of a fully sliding patch at sliding speeds ``slide_speed`` [N]."""
        s, p = self.tyre.patch(fz)
        ds = s[1] - s[0]
        lim = self._limit(p[None, :], np.asarray(slide_speed, float)[:, None], 1.0)
        return (np.sum(lim, axis=1) - 0.5 * (lim[:, 0] + lim[:, -1])) * ds

    def _emit(self, msgs: list[str]) -> None:
        if msgs:
            warnings.warn("; ".join(msgs), ExtrapolationWarning, stacklevel=3)

    def fy(self, alpha: Any, fz: float) -> Any:
        """Compute the lateral force F_y at slip angles and a vertical load.

        F_y has the sign of alpha.  Warns (ExtrapolationWarning) when the patch
        pressures or sliding speeds leave the law's fitted or valid range.

        Parameters
        ----------
        alpha : float or array-like
            Slip angles [rad], strictly between -pi/2 and pi/2.
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float or numpy.ndarray
            Lateral force F_y [N]: a float for a scalar ``alpha``, else an array
            of the shape of ``alpha``.

        Raises
        ------
        InputError
            For a bad load or slip angles that are not finite or not within
            (-90, 90) degrees.
        DomainError
            When the law gives no usable friction limit inside the patch.
        """
        fz = positive_load(fz)
        alpha = np.asarray(alpha, dtype=float)
        if not np.all(np.isfinite(alpha)) or np.any(np.abs(alpha) >= math.pi / 2):
            raise InputError("slip angles must be finite and strictly between -90 and 90 "
                             "degrees (given in radians)")
        flat = alpha.ravel()
        sigma = np.abs(np.tan(flat))
        res = self._solve(sigma, fz, self.tyre.c_py, self.tyre.speed)
        self._emit(self._extrapolation([(fz, res["p"], res["vs_range"])]))
        out = np.sign(flat) * res["force"]
        return float(out[0]) if alpha.ndim == 0 else out.reshape(alpha.shape)

    def fx(self, kappa: Any, fz: float) -> Any:
        """Compute the longitudinal force F_x at slip ratios and a vertical load.

        ``kappa = (Omega R_e - V)/V``: positive when driving, -1 for a locked
        wheel (full sliding at the road speed).  F_x has the sign of kappa.
        Warns (ExtrapolationWarning) when the patch pressures or sliding speeds
        leave the law's fitted or valid range.

        Parameters
        ----------
        kappa : float or array-like
            Longitudinal slip ratios [-], finite.
        fz : float
            Vertical load F_z [N], positive.

        Returns
        -------
        float or numpy.ndarray
            Longitudinal force F_x [N]: a float for a scalar ``kappa``, else an
            array of the shape of ``kappa``.

        Raises
        ------
        InputError
            For a bad load or slip ratios that are not finite.
        DomainError
            When the law gives no usable friction limit inside the patch.
        """
        fz = positive_load(fz)
        kappa = np.asarray(kappa, dtype=float)
        if not np.all(np.isfinite(kappa)):
            raise InputError("slip ratios must be finite")
        flat = kappa.ravel()
        out = np.zeros(flat.shape)
        rolling = flat > -1.0 + 1e-9
        cases: list[tuple[float, np.ndarray, Any]] = []
        if rolling.any():
            k = flat[rolling]
            sigma = np.abs(k / (1.0 + k))
            res = self._solve(sigma, fz, self.tyre.c_px, self.tyre.speed * (1.0 + k))
            out[rolling] = np.sign(k) * res["force"]
            cases.append((fz, res["p"], res["vs_range"]))
        if (~rolling).any():
            k = flat[~rolling]
            out[~rolling] = -self._full_sliding(fz, self.tyre.speed * np.abs(k))
            speeds = self.tyre.speed * np.abs(k)
            cases.append((fz, self.tyre.patch(fz)[1],
                          (float(speeds.min()), float(speeds.max())) if self.uses_v else None))
        msgs = self._extrapolation(cases)
        self._emit(msgs)
        return float(out[0]) if kappa.ndim == 0 else out.reshape(kappa.shape)

    def patch_state(self, slip: float, fz: float, direction: str = "y") -> dict[str, np.ndarray]:
        """Compute the profiles along the contact patch at one slip and load.

        Parameters
        ----------
        slip : float
            Slip angle alpha [rad] for ``direction="y"``, or slip ratio kappa
            [-] (> -1, a rolling wheel) for ``direction="x"``.
        fz : float
            Vertical load F_z [N], positive.
        direction : {"y", "x"}
            Lateral (side slip) or longitudinal slip.

        Returns
        -------
        dict of str to numpy.ndarray
            One value per patch node: ``"s"`` position from the leading edge [m],
            ``"p"`` contact pressure [Pa], ``"line_load"`` elastic line load
            carried by the bristles [N/m], ``"adhesion_line_load"`` the line load
            had every bristle adhered [N/m], and ``"sliding"`` (bool) the nodes
            where the bristle slides and carries its friction limit.

        Raises
        ------
        InputError
            For a bad load, ``kappa <= -1`` or an unknown ``direction``.
        """
        fz = positive_load(fz)
        if direction == "y":
            sigma, c, vr = abs(math.tan(slip)), self.tyre.c_py, self.tyre.speed
        elif direction == "x":
            if slip <= -1.0:
                raise InputError("patch_state needs a rolling wheel (kappa > -1)")
            sigma, c = abs(slip / (1.0 + slip)), self.tyre.c_px
            vr = self.tyre.speed * (1.0 + slip)
        else:
            raise InputError("direction must be 'x' or 'y'")
        res = self._solve(np.array([sigma]), fz, c, np.array([vr]), keep=True)
        q = res["q"][0]
        adhesion = np.arange(q.size) * sigma * (res["s"][1] - res["s"][0])
        return {"s": res["s"], "p": res["p"], "line_load": c * q,
                "adhesion_line_load": c * adhesion,
                "sliding": q < adhesion * (1 - 1e-9) - 1e-15}

    def cornering(self, loads: Sequence[float] | np.ndarray,
                  angles_deg: Sequence[float] = DEFAULT_ANGLES_DEG) -> CorneringResult:
        """Compute the cornering stiffness (secant over ``angles_deg`` and at the origin) by load.

        Parameters
        ----------
        loads : sequence of float
            Vertical loads [N].
        angles_deg : sequence of float
            Slip angles [deg] of the secant (the thesis used 1, 2, 3).

        Returns
        -------
        CorneringResult
            Per load: the least-squares cornering stiffness over the angles and
            the slope at the origin [N/rad], the lateral forces [N], the patch
            half-length [m] and mean and peak pressures [Pa], and extrapolation
            warnings.

        Raises
        ------
        InputError
            When no load is given, a load is not positive, or an angle is outside
            (0, 90) degrees.
        """
        loads = np.atleast_1d(np.asarray(loads, dtype=float))
        if loads.size == 0:
            raise InputError("no loads given")
        for fz in loads:
            positive_load(fz)
        angles = np.atleast_1d(np.asarray(angles_deg, dtype=float))
        if angles.size == 0 or np.any(~np.isfinite(angles)) or np.any(angles <= 0) or np.any(
                angles >= 90):
            raise InputError("slip angles must be in (0, 90) degrees")
        alpha = np.radians(angles)
        h = ORIGIN_STEP
        sig = np.concatenate([np.tan(alpha), [math.tan(h), math.tan(2 * h)]])
        fy = np.empty((loads.size, angles.size))
        cs0 = np.empty(loads.size)
        cases: list[tuple[float, np.ndarray, Any]] = []
        for i, fz in enumerate(loads):
            res = self._solve(sig, float(fz), self.tyre.c_py, self.tyre.speed)
            f = res["force"]
            fy[i] = f[:angles.size]
            static = self._limit(res["p"][1:-1], 0.0, self.tyre.c_py)
            if np.all(static > 0):
                # bristles adhere all along the patch as alpha -> 0: exactly 2 c a^2
                cs0[i] = 2 * self.tyre.c_py * self.tyre.half_length(float(fz)) ** 2
            else:
                # no static friction somewhere: numerical slope (Richardson)
                cs0[i] = 2 * f[-2] / h - f[-1] / (2 * h)
            cases.append((float(fz), res["p"], res["vs_range"]))
        msgs = self._extrapolation(cases)
        cs = fy @ alpha / float(alpha @ alpha)
        half = np.array([self.tyre.half_length(f) for f in loads])
        mean_p = loads / (2 * half * self.tyre.width)
        peak_p = np.array([self.tyre.patch(f)[1].max() for f in loads])
        result = CorneringResult(
            law=self.label, params=dict(self.values), tyre=self.tyre.describe(), loads=loads,
            angles_deg=angles, fy=fy, cs=cs, cs_origin=cs0, half_length=half,
            mean_pressure=mean_p, peak_pressure=peak_p, warnings=msgs)
        return result

    def __repr__(self) -> str:
        return f"<BrushModel law={self.label!r} params={self.values}>"

