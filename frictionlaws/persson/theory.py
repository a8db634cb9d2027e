"""Persson's theory of rubber friction: the viscoelastic friction coefficient.

Sources: B. N. J. Persson, Theory of rubber friction and contact mechanics,
J. Chem. Phys. 115 (2001) 3840-3861; B. N. J. Persson,
O. Albohr, U. Tartaglino, A. I. Volokitin, E. Tosatti, On the nature of surface
roughness with application to contact mechanics, sealing, rubber friction and
adhesion, J. Phys.: Condens. Matter 17 (2005) R1-R62; the refinements of
B. N. J. Persson, J. Phys.: Condens. Matter 18 (2006) 7789 (the correction S(q)
and the flash temperature, :mod:`.flash`) are options.

.. code-block:: text

    mu = 1/2 int_q0^q1 dq q^3 C(q) P(q) int_0^2pi dphi cos(phi)
         Im E(q v cos(phi), T) / ((1 - nu^2) sigma0)
    P(q) = erf(1 / (2 sqrt(G(q))))
    G(q) = 1/8 int_q0^q dq' q'^3 C(q') int_0^2pi dphi |E(q' v cos(phi), T) / ((1 - nu^2) sigma0)|^2

with sigma0 = p the nominal pressure.

Quadrature (the fast path).  Both q integrals run over ln q on Gauss-Legendre
panels (``order`` nodes per panel, ``panels_per_decade``); the cumulative
integral G at the nodes uses each panel's spectral integration matrix
(integral of the Lagrange interpolant), so G and mu have the same high order.
Both angular integrals are functions of omega0 = q v a_T alone, tabulated once
per material at 16 points per decade of omega0 and interpolated by a cubic
spline of their log in ln omega0.  The loss term is analytic for a Prony
series: for one term with a = omega0 tau and c = cos(phi),
``int_0^2pi c Im[i a c/(1 + i a c)] dphi = 2 pi a / (sqrt(1 + a^2) (1 + sqrt(1 + a^2)))``;
the |E|^2 term is integrated by composite Gauss-Legendre in pi/2 - phi on
panels refined geometrically towards phi = pi/2.
"""

from __future__ import annotations

import functools
import math
import warnings
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy.special import erf

from ..base.errors import DomainError, ExtrapolationWarning, InputError
from .flash import Flash, background_rise, temperature_rise
from .material import Material
from .surface import check_roughness

__all__ = ["friction", "flash_temperature", "T_CEILING", "contact_ratio", "check_conditions",
           "loss_angular", "loss_tabulated", "modulus_sq_angular", "q_nodes"]


def loss_angular(material: Material, omega0: Any) -> np.ndarray:
    """``int_0^2pi cos(phi) Im E(omega0 cos phi) dphi`` [Pa] (analytic, Prony series)."""
    w = np.asarray(omega0, dtype=float)
    out = np.zeros(w.shape)
    for Ei, ti in zip(material.E_i, material.tau):
        a = w * ti
        r = np.sqrt(1.0 + a * a)
        out += Ei * a / (r * (1.0 + r))
    return 2.0 * math.pi * out


def _angular_nodes() -> tuple[np.ndarray, np.ndarray]:
    """Nodes psi = pi/2 - phi and weights on [0, pi/2], refined towards psi = 0."""
    x, w = np.polynomial.legendre.leggauss(10)
    edges = np.concatenate([[0.0], (math.pi / 2) * 10.0 ** np.linspace(-14, 0, 29)])
    psi, wt = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        psi.append(a + (b - a) * (x + 1) / 2)
        wt.append(w * (b - a) / 2)
    return np.concatenate(psi), np.concatenate(wt)


def _modsq_direct(material: Material, omega0: np.ndarray) -> np.ndarray:
    psi, wt = _angular_nodes()
    out = np.empty(omega0.size)
    for k in range(0, omega0.size, 64):
        w = omega0[k:k + 64, None] * np.sin(psi)[None, :]
        E = material.modulus(w)
        out[k:k + 64] = 4.0 * (np.abs(E) ** 2) @ wt
    return out


def _log_grid(material: Material) -> np.ndarray:
    """ln omega0 from 1e-6/tau_max to 1e8/tau_min, 16 points per decade."""
    lo = math.log(1e-6 / float(np.max(material.tau)))
    hi = math.log(1e8 / float(np.min(material.tau)))
    return np.linspace(lo, hi, int((hi - lo) / math.log(10) * 16) + 1)


def _table(material: Material, key: str) -> Any:
    """Cubic spline of ln F against ln omega0 for F = |E|^2 or loss angular integral."""
    cache = material._cache
    if key not in cache:
        from scipy.interpolate import CubicSpline

        lw = _log_grid(material)
        w = np.exp(lw)
        F = _modsq_direct(material, w) if key == "modsq" else loss_angular(material, w)
        cache[key] = (CubicSpline(lw, np.log(F)), float(lw[0]), float(lw[-1]))
    return cache[key]


def modulus_sq_angular(material: Material, omega0: Any) -> np.ndarray:
    """``int_0^2pi |E(omega0 cos phi)|^2 dphi`` [Pa^2] (tabulated, spline in ln omega0).

    Constant beyond the table (the rubbery and glassy limits).
    """
    spline, lo, hi = _table(material, "modsq")
    lw = np.log(np.maximum(np.asarray(omega0, dtype=float), 1e-300))
    return np.exp(spline(np.clip(lw, lo, hi)))


def loss_tabulated(material: Material, omega0: Any) -> np.ndarray:
    """:func:`loss_angular` from a spline in ln omega0 (the fast path).

    Beyond the table it continues with the exact asymptotes, proportional to
    omega0 below and to 1/omega0 above.
    """
    spline, lo, hi = _table(material, "loss")
    lw = np.log(np.maximum(np.asarray(omega0, dtype=float), 1e-300))
    c = np.clip(lw, lo, hi)
    return np.exp(spline(c) + np.where(lw < lo, lw - lo, 0.0) - np.where(lw > hi, lw - hi, 0.0))


@functools.lru_cache(maxsize=16)
def _panel(order: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes, weights and cumulative-integration matrix on [-1, 1]."""
    x, w = np.polynomial.legendre.leggauss(order)
    V = np.polynomial.legendre.legvander(x, order - 1)
    # integral from -1 to x_i of each Legendre polynomial P_k
    Vint = np.empty_like(V)
    for k in range(order):
        c = np.zeros(order)
        c[k] = 1.0
        ic = np.polynomial.legendre.legint(c, lbnd=-1.0)
        Vint[:, k] = np.polynomial.legendre.legval(x, ic)
    S = Vint @ np.linalg.inv(V)
    return x, w, S


def q_nodes(q0: float, q1: float, *, order: int = 10, panels_per_decade: float = 2.0,
            graded: int = 8) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """ln q nodes on [q0, q1], quadrature weights (in ln q) and the cumulative matrix.

    The first uniform panel is split geometrically (ratio 10, ``graded``
    times) towards q0: where G(q) grows fast P(q) behaves like
    ``1/sqrt(ln q - ln q0)`` next to q0, an endpoint singularity that uniform
    panels resolve slowly.
    """
    x, w, S = _panel(order)
    decades = math.log10(q1 / q0)
    k = max(1, int(math.ceil(decades * panels_per_decade - 1e-9)))
    uniform = np.linspace(math.log(q0), math.log(q1), k + 1)
    first = uniform[1] - uniform[0]
    fine = uniform[0] + first * 10.0 ** np.arange(-graded, 0, dtype=float)
    edges = np.concatenate([uniform[:1], fine, uniform[1:]])
    h = np.diff(edges) / 2
    nodes = (edges[:-1, None] + h[:, None] * (x[None, :] + 1)).ravel()
    weights = (h[:, None] * w[None, :]).ravel()
    npan = edges.size - 1
    n = npan * order
    cum = np.zeros((n, n))
    for j in range(npan):
        blk = slice(j * order, (j + 1) * order)
        cum[blk, : j * order] = weights[None, : j * order]
        cum[blk, blk] = S * h[j]
    return np.exp(nodes), weights, cum


def check_conditions(material: Material, v: Any, T: Any, p: Any) -> None:
    """Refuse sliding conditions the theory cannot take for this material.

    Every value finite; the pressure positive (the theory divides by it: at
    p = 0 there is no contact and no friction coefficient); the temperature
    inside the range the material's data cover
    (:meth:`~frictionlaws.persson.material.Material.temperature_range`), since
    the modulus elsewhere would be an extrapolation of its shift.

    Raises
    ------
    InputError
        A non-finite value.
    DomainError
        A pressure <= 0 or a temperature outside the material's data.
    """
    for name, unit, x in (("v", "m/s", v), ("T", "K", T), ("p", "Pa", p)):
        a = np.asarray(x, dtype=float)
        bad = ~np.isfinite(a)
        if bad.any():
            raise InputError(f"Persson: {name} has a non-finite value ({a[bad].flat[0]}) at "
                             f"index {_index(bad)} [{unit}]")
    pa = np.asarray(p, dtype=float)
    if pa.size and float(pa.min()) <= 0.0:
        bad = pa <= 0.0
        raise DomainError(f"Persson: p = {pa[bad].flat[0]:g} Pa at index {_index(bad)}: the "
                          "nominal pressure must be > 0 (the theory divides by it; without "
                          "contact there is no friction coefficient)")
    Ta = np.asarray(T, dtype=float)
    lo, hi = material.temperature_range()
    if Ta.size and (float(Ta.min()) < lo * (1 - 1e-12) or float(Ta.max()) > hi * (1 + 1e-12)):
        bad = (Ta < lo * (1 - 1e-12)) | (Ta > hi * (1 + 1e-12))
        first = float(Ta[bad].flat[0])
        hint = (f"; if it is in degC, {first:g} degC is {first + 273.15:g} K"
                if lo <= first + 273.15 <= hi else "")
        raise DomainError(f"Persson: T = {first:.6g} K at index {_index(bad)} is "
                          f"outside the temperatures the material's data cover, {lo:.6g} .. "
                          f"{hi:.6g} K ({lo - 273.15:.4g} .. {hi - 273.15:.4g} degC){hint}")


def _warn_outside_data(material: Material, q0: float, q1: float, v: np.ndarray, T: np.ndarray
                       ) -> None:
    """Warn where a condition excites only frequencies the material's data do not cover.

    The excitation runs from ``q0 v a_T`` to ``q1 v a_T`` (reduced to T_ref); when
    that band misses the measured ``omega_range`` altogether, mu comes from the
    Prony series' continuation alone (its rubbery or glassy limit).
    """
    if material.omega_range is None or v.size == 0:
        return
    lo, hi = material.omega_range
    w = v * 10.0 ** material.shift(T)
    out = (v > 0) & ((q1 * w < lo) | (q0 * w > hi))
    _warn_at(out, v, T, f"the sliding excites only frequencies outside the material's "
             f"measured master curve ({lo:.3g} .. {hi:.3g} rad/s at T_ref): mu there is the "
             "Prony series' continuation, an extrapolation")


def _warn_at(out: np.ndarray, v: np.ndarray, T: np.ndarray, what: str | Any) -> None:
    """One ExtrapolationWarning for the conditions ``out``, naming their count and the first.

    ``what`` says what happens there: text, or a function of the first one's index.
    """
    if not out.any():
        return
    k = int(np.flatnonzero(out)[0])
    text = what(k) if callable(what) else what
    warnings.warn(f"Persson: at {int(out.sum())} of {v.size} conditions (the first: v = "
                  f"{v[k]:.4g} m/s, T = {T[k]:.5g} K) {text}", ExtrapolationWarning,
                  stacklevel=5)


def _index(mask: np.ndarray) -> int | tuple[int, ...]:
    idx = tuple(int(i) for i in np.argwhere(np.atleast_1d(mask))[0])
    return idx[0] if len(idx) == 1 else idx


def _prepare(material: Material, v: Any, T: Any, p: Any
             ) -> tuple[tuple[int, ...], np.ndarray, np.ndarray, np.ndarray]:
    check_conditions(material, v, T, p)
    b = np.broadcast_arrays(np.asarray(v, float), np.asarray(T, float), np.asarray(p, float))
    shape = b[0].shape
    return shape, np.abs(b[0]).ravel(), b[1].ravel(), b[2].ravel()


def contact_ratio(material: Material, surface: Any, v: Any, T: Any, p: Any, q: Any) -> Any:
    """P(q) = A(q)/A0 at wavenumbers ``q`` [1/m] (last axis) for each v, T, p.

    G is integrated from q0 to each ``q`` itself (a Gauss-Legendre rule on
    [q0, q]), so P is the contact ratio at q, not at a quadrature node near it;
    ``P = 1`` for ``q <= q0``.
    """
    shape, vv, TT, pp = _prepare(material, v, T, p)
    q = np.asarray(q, dtype=float).ravel()
    if q.size and not np.all(np.isfinite(q)):
        raise InputError("Persson: contact_ratio needs finite wavenumbers q [1/m]")
    if q.size and q.max() > surface.q0:
        check_roughness(surface, float(q.max()))
    out = []
    for qi in q:
        if qi <= surface.q0:
            out.append(np.ones(vv.size))
            continue
        nodes, weights, _ = q_nodes(surface.q0, float(qi))
        out.append(_P(_G_total(material, surface, vv, TT, pp, nodes, weights)))
    return np.stack(out, axis=-1).reshape(shape + (q.size,))


def _omega0(material: Material, v: np.ndarray, T: np.ndarray, q: np.ndarray) -> np.ndarray:
    """omega0 = q v a_T for each point (rows) and node (columns); ``T`` per point or per node."""
    aT = 10.0 ** material.shift(T)
    if np.ndim(aT) == 2:
        return v[:, None] * aT * q[None, :]
    return (v * aT)[:, None] * q[None, :]


def _G(material: Material, surface: Any, v: np.ndarray, T: np.ndarray, p: np.ndarray,
       nodes: np.ndarray, cum: np.ndarray) -> np.ndarray:
    e = (1.0 - material.nu**2) * p
    F = modulus_sq_angular(material, _omega0(material, v, T, nodes))
    g = nodes**4 * surface.C(nodes) / 8.0 * F / (e * e)[:, None]
    # the last node of the cumulative matrix reaches only the last node, not q1:
    return g @ cum.T


def _G_total(material: Material, surface: Any, v: np.ndarray, T: np.ndarray, p: np.ndarray,
             nodes: np.ndarray, weights: np.ndarray) -> np.ndarray:
    """G at the upper end of the nodes' interval (the full quadrature, not the last node)."""
    e = (1.0 - material.nu**2) * p
    F = modulus_sq_angular(material, _omega0(material, v, T, nodes))
    return (nodes**4 * surface.C(nodes) / 8.0 * F / (e * e)[:, None]) @ weights


def _P(G: np.ndarray) -> np.ndarray:
    with np.errstate(divide="ignore"):
        return erf(1.0 / (2.0 * np.sqrt(np.maximum(G, 0.0))))


def friction(material: Material, surface: Any, v: Any, T: Any, p: Any, *,
             q1: float | None = None, order: int = 10, panels_per_decade: float = 2.0,
             gamma: float = 1.0, flash: Flash | None = None) -> Any:
    """The viscoelastic friction coefficient mu(v, T, p) of Persson's theory.

    Parameters
    ----------
    material : Material
        The rubber (Prony series, shift, Poisson ratio).
    surface : SelfAffine or TabulatedPSD
        The counter-surface spectrum C(q) [m^4] with its ``q0``.
    v, T, p : array-like
        Sliding velocity [m/s] (its magnitude; v = 0 gives the static limit
        mu = 0), temperature [K] inside the material's data, nominal pressure
        [Pa] > 0; broadcast together (:func:`check_conditions`).
    q1 : float, optional
        Short-wavelength cut-off [1/m] (default: the surface's ``q1``).
    order, panels_per_decade
        Gauss-Legendre nodes per panel and panels per decade of q.
    gamma : float
        The correction ``S(q) = gamma + (1 - gamma) P(q)^2`` of the integrand
        (Persson, J. Phys.: Condens. Matter 18 (2006) 7789, who suggests
        gamma of about 1/2): the elastic energy stored near the edges of the
        contact regions.  1 (the default) is the uncorrected theory of 2001.
    flash : Flash, optional
        Thermal properties for the flash temperature (:mod:`.flash`); None
        (the default) is the isothermal theory.

    Returns
    -------
    float or numpy.ndarray
        mu, of the broadcast shape (a float for scalar input).

    Raises
    ------
    DomainError
        Conditions outside the material's data, or a flash temperature that
        does not converge.
    """
    return _friction(material, surface, v, T, p, q1=q1, order=order,
                     panels_per_decade=panels_per_decade, gamma=gamma, flash=flash)[0]


def flash_temperature(material: Material, surface: Any, v: Any, T: Any, p: Any, *,
                      flash: Flash, q1: float | None = None, gamma: float = 1.0,
                      order: int = 10, panels_per_decade: float = 2.0
                      ) -> tuple[np.ndarray, np.ndarray]:
    """The temperatures T_q [K] the rubber has at each length scale while sliding.

    The same solution as :func:`friction` with ``flash`` (same arguments).

    Returns
    -------
    q, T_q : numpy.ndarray
        The quadrature wavenumbers [1/m] and the temperatures, one row per
        point of the broadcast v, T, p (flattened).
    """
    _, nodes, Tq = _friction(material, surface, v, T, p, q1=q1, order=order,
                             panels_per_decade=panels_per_decade, gamma=gamma, flash=flash)
    return nodes, Tq


def _check_gamma(gamma: float) -> None:
    if not (isinstance(gamma, (int, float)) and 0.0 <= gamma <= 1.0):
        raise InputError(f"Persson: gamma = {gamma!r} of S(q) = gamma + (1 - gamma) P^2 must "
                         "be in 0..1")


#: Most Gauss-Legendre nodes per panel and panels per decade of q a call may ask for.
_ORDER_MAX, _PANELS_MAX = 64, 64.0


def _check_quadrature(q0: float, q1: float, order: Any, panels_per_decade: Any) -> None:
    """Refuse a wavenumber range with no roughness in it, or a rule that is none."""
    if not (math.isfinite(q1) and q1 > q0):
        raise InputError(f"Persson: the cut-off q1 = {q1:g} 1/m must be finite and exceed the "
                         f"surface's q0 = {q0:g} 1/m (give q1, here or on the surface)")
    if isinstance(order, bool) or not isinstance(order, (int, np.integer)) or not (
            1 <= order <= _ORDER_MAX):
        raise InputError(f"Persson: order = {order!r} must be a whole number of nodes per "
                         f"panel, 1 to {_ORDER_MAX}")
    if not (isinstance(panels_per_decade, (int, float)) and 0.0 < panels_per_decade
            <= _PANELS_MAX):
        raise InputError(f"Persson: panels_per_decade = {panels_per_decade!r} must be in "
                         f"(0, {_PANELS_MAX:g}]")


def _friction(material: Material, surface: Any, v: Any, T: Any, p: Any, *, q1: float | None,
              order: int, panels_per_decade: float, gamma: float, flash: Flash | None
              ) -> tuple[Any, np.ndarray, np.ndarray]:
    """mu (as :func:`friction` returns it), the q nodes and T_q (points x nodes)."""
    if flash is not None and not isinstance(flash, Flash):
        raise InputError(f"Persson: flash must be a Flash (thermal properties) or None, got "
                         f"{type(flash).__name__}")
    _check_gamma(gamma)
    q1 = float(surface.q1 if q1 is None else q1)
    _check_quadrature(surface.q0, q1, order, panels_per_decade)
    check_roughness(surface, q1)
    shape, vv, TT, pp = _prepare(material, v, T, p)
    _warn_outside_data(material, surface.q0, q1, vv, TT)
    nodes, weights, cum = q_nodes(surface.q0, q1, order=order,
                                  panels_per_decade=panels_per_decade)
    grid = _Grid(nodes, weights, cum, nodes**4 * surface.C(nodes))
    mu = np.empty(vv.size)
    Tq = np.empty((vv.size, nodes.size))
    heated = flash is not None and flash.heat_fraction > 0
    for k in range(0, vv.size, _BLOCK):
        b = slice(k, k + _BLOCK)
        if heated:
            assert flash is not None
            dmu, Tq[b] = _flash_solve(material, surface, vv[b], TT[b], pp[b], grid, gamma,
                                      flash)
        else:
            dmu, _ = _integrand(material, surface, vv[b], TT[b], pp[b], grid, gamma)
            Tq[b] = TT[b][:, None]
        mu[b] = dmu.sum(axis=1)
    if heated:
        _check_hot(material, Tq, vv, TT, pp)
    # v = 0: no excitation, Im E(0) = 0, the exact limit (mu falls linearly in v towards it)
    mu[vv == 0.0] = 0.0
    return (float(mu[0]) if shape == () else mu.reshape(shape)), nodes, Tq


#: Highest rubber temperature [K] a friction coefficient is given for (300 degC: rubbers
#: degrade above about 200-300 degC, and the modulus there is no longer the measured one).
T_CEILING = 573.15


def _check_hot(material: Material, Tq: np.ndarray, v: np.ndarray, T: np.ndarray,
               p: np.ndarray) -> None:
    """Refuse rubber temperatures above :data:`T_CEILING`; warn above the material's data."""
    hottest = Tq.max(axis=1)
    over = hottest > T_CEILING
    if over.any():
        k = int(np.flatnonzero(over)[0])
        raise DomainError(f"Persson: at v = {v[k]:.4g} m/s, T = {T[k]:.5g} K, p = {p[k]:.4g} Pa "
                          f"the flash temperature reaches {hottest[k]:.4g} K, above "
                          f"{T_CEILING:g} K (300 degC), where rubber degrades; no friction "
                          "coefficient is given for these conditions")
    top = material.temperature_range()[1]
    _warn_at(hottest > top * (1 + 1e-12), v, T,
             lambda k: f"the flash temperature reaches {hottest[k]:.4g} K, above the "
             f"material's data (to {top:.5g} K): the modulus there is the shift's extrapolation")


@dataclass(frozen=True)
class _Grid:
    nodes: np.ndarray
    weights: np.ndarray
    cum: np.ndarray
    qC: np.ndarray


def _integrand(material: Material, surface: Any, v: np.ndarray, T: np.ndarray, p: np.ndarray,
               grid: _Grid, gamma: float) -> tuple[np.ndarray, np.ndarray]:
    """The friction integrand times the weights (points x nodes) and P(q) at the nodes.

    ``T`` is one temperature per point or one per point and node (T_q).
    """
    G = _G(material, surface, v, T, p, grid.nodes, grid.cum)
    P = _P(G)
    e = (1.0 - material.nu**2) * p
    A = loss_tabulated(material, _omega0(material, v, T, grid.nodes))
    S = P if gamma == 1.0 else P * (gamma + (1.0 - gamma) * P * P)
    return 0.5 * grid.qC * S * A / e[:, None] * grid.weights, P


def _flash_solve(material: Material, surface: Any, v: np.ndarray, T: np.ndarray, p: np.ndarray,
                 grid: _Grid, gamma: float, flash: Flash) -> tuple[np.ndarray, np.ndarray]:
    """Self-consistent T_q and the integrand with it (the closures of :mod:`.flash`).

    Damped fixed-point iteration, each point's step at most :data:`_DAMP_MAX` of
    the full one, halved whenever its change grows (a hot rubber on the glassy
    side heats itself further, and a fuller step overshoots there) and let grow
    slowly again while it shrinks.
    """
    Tq = np.repeat(T[:, None], grid.nodes.size, axis=1)
    omega = np.full(v.size, _DAMP_MAX)
    last = np.full(v.size, np.inf)
    live = np.arange(v.size)          # the points still iterating
    change = np.zeros(0)
    for _ in range(flash.max_iter):
        dmu, P = _integrand(material, surface, v[live], Tq[live], p[live], grid, gamma)
        rise = temperature_rise(flash, grid.nodes, grid.weights, grid.cum, dmu, P, v[live],
                                p[live])
        rise += background_rise(flash, dmu.sum(axis=1), v[live], p[live])[:, None]
        step = T[live, None] + rise - Tq[live]
        change = np.max(np.abs(step), axis=1)
        going = change >= flash.tol
        w = np.where(change > last[live], omega[live] / 2,
                     np.minimum(omega[live] * 1.05, _DAMP_MAX))
        omega[live] = np.maximum(w, _DAMP_MIN)
        last[live] = change
        # a converged point takes the full step: T_q is then the map's own value (below tol
        # from the fixed point), so a rise smaller than tol is kept, not rounded to 0
        Tq[live] += np.where(going, omega[live], 1.0)[:, None] * step
        live = live[going]
        if live.size == 0:
            return _integrand(material, surface, v, Tq, p, grid, gamma)[0], Tq
    raise DomainError(f"Persson: the flash temperature did not converge in {flash.max_iter} "
                      f"iterations (last change {float(change.max()):.3g} K); no friction "
                      "coefficient is given for these conditions")


#: Largest and smallest fraction of the fixed-point step taken (flash temperature).
_DAMP_MAX, _DAMP_MIN = 0.3, 1.0 / 128

#: Points evaluated together (bounds the memory of the (points x nodes) arrays).
_BLOCK = 1024
