"""Flash temperature: the rubber's heating by its own friction, scale by scale.

After B. N. J. Persson, Rubber friction: role of the flash temperature, J. Phys.:
Condens. Matter 18 (2006) 7789-7823.  The energy dissipated in the rubber heats it;
because the modulus depends so strongly on temperature, the rubber at the length
scale 2 pi/q is taken at its own temperature ``T_q`` and the friction integral
uses ``E(omega, T_q)``.  The friction and the temperatures are solved together
(:func:`frictionlaws.persson.friction` with ``flash=Flash(...)``).

**The volume closure** (``closure="volume"``, the default).  The friction power
per unit nominal area, ``mu p v``, is split over the scales as the friction
integrand: the band of wavenumbers at q' dissipates ``p v dmu(q')``.  As in the
2006 paper's picture, that heat is made in the contact regions seen at q' (the
fraction ``P(q')`` of the nominal area) and in the rubber's volume, down to a depth
of order ``1/q'`` (here exactly ``1/q'``, a choice), at the rate per unit volume

    Qdot(q') = heat_fraction p v dmu(q') q' / P(q'),

for the contact time ``t(q') = d(q')/v`` that a point of the rubber spends in a
region of diameter ``d(q') = pi/q'`` (half a wavelength; a choice).  Diffusion
removes the heat of that layer at the one rate ``D q'^2`` (``D = kappa / (rho c)``;
a choice: one mode, not the heat equation's spectrum), so its
temperature after a time s is ``Qdot (1 - exp(-D q'^2 s)) / (rho c D q'^2)``.
Its mean over the contact time (``contact_temperature="mean"``, the default, a
choice) or its value at the end of it (``"exit"``) is the rise the scale q'
contributes:

    dT(q') = heat_fraction pi p dmu(q') h(x) / (P(q') rho c),  x = pi D q'/v,
    h_exit(x) = (1 - exp(-x)) / x,   h_mean(x) = (x - 1 + exp(-x)) / x^2.

At low speed (``x >> 1``, diffusion wins) ``dT -> heat_fraction p v dmu/(P kappa
q')``: it grows as v and scales as 1/kappa.  At high speed (``x << 1``, no time
to diffuse) ``dT -> heat_fraction pi p dmu/(P rho c)`` times 1 (exit) or 1/2
(mean): it levels off and scales as 1/(rho c).  The rubber at the scale q lies in
the contact regions of every coarser scale, so (Persson 2006)

    T_q = T + int_{q0}^{q} dT(q') (over ln q', the bands' rises as a density).

**Background heating** (``sliding_distance`` L > 0, off by default; the paper
discusses the cumulative heating, the form here is a choice): all the heat that
flows into the rubber, the mean flux ``heat_fraction mu p v``, raises the
temperature of a half-space over the sliding time L/v by
``2 heat_fraction mu p sqrt(L v / (pi kappa rho c))`` (constant flux on a
half-space, Carslaw and Jaeger); it is added to every ``T_q``.

**The surface-flux closure** (``closure="surface-flux"``, the closure shipped
before): the heat of each scale is a flux through the surface of a sliding disc
of radius ``a_q = pi/(2 q)`` whose maximum temperature follows the interpolation
of Tian and Kennedy (J. Tribol. 116 (1994) 167-174),
``dT = j a/kappa * 2/sqrt(pi (1.273 + Pe))``, ``Pe = v a/(2 D)``, and heat made
at finer scales also heats the coarser regions.  For the same dissipation its
rise is at least the volume closure's at every scale (each coarser band's term
is larger, for both ``contact_temperature`` choices, and it adds the finer
bands; the tests check the sums across speeds, temperatures and pressures): an
upper bound, not the default.

With no heat (``heat_fraction = 0``) every closure is the isothermal theory,
exactly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..base.errors import InputError

__all__ = ["Flash", "TREAD_THERMAL", "CLOSURES", "CONTACT_TEMPERATURES", "temperature_rise",
           "background_rise"]

#: The ways the heat of each scale becomes a temperature (see the module docstring).
CLOSURES = ("volume", "surface-flux")

#: Which temperature of a contact's heating time the volume closure takes.
CONTACT_TEMPERATURES = ("mean", "exit")

#: Plausible ranges: a polymer's conductivity [W/(m K)] and a solid's volumetric heat
#: capacity [J/(m^3 K)], and the longest sliding distance for background heating [m].
_CONDUCTIVITY = (0.01, 10.0)
_HEAT_CAPACITY = (1e5, 1e7)
_DISTANCE_MAX = 1000.0


def _number(name: str, x: Any, unit: str) -> float:
    if isinstance(x, bool) or not isinstance(x, (int, float, np.integer, np.floating)):
        raise InputError(f"flash temperature: {name} = {x!r} must be a number in {unit} "
                         f"(got {type(x).__name__})")
    if not math.isfinite(float(x)):
        raise InputError(f"flash temperature: {name} = {x!r} must be finite [{unit}]")
    return float(x)


def _check_thermal(kappa: float, rho_c: float) -> None:
    lo, hi = _CONDUCTIVITY
    if not lo <= kappa <= hi:
        hint = (" (a value 1000 times too large is likely in mW/(m K))" if kappa > hi else "")
        raise InputError(f"flash temperature: conductivity = {kappa:g} W/(m K) is outside "
                         f"{lo:g} .. {hi:g} W/(m K), the range of polymers (rubber about "
                         f"0.1 .. 0.5){hint}")
    lo, hi = _HEAT_CAPACITY
    if not lo <= rho_c <= hi:
        hint = ("; it looks like a specific heat capacity c in J/(kg K): give rho c, the "
                "density times c (1200 kg/m^3 x 1500 J/(kg K) = 1.8e6 J/(m^3 K))"
                if 100.0 <= rho_c < lo else "")
        raise InputError(f"flash temperature: heat_capacity = {rho_c:g} J/(m^3 K) is outside "
                         f"{lo:g} .. {hi:g} J/(m^3 K), the volumetric heat capacities of "
                         f"solids (rubber about 1.8e6){hint}")


@dataclass(frozen=True)
class Flash:
    """Thermal properties and settings of the flash temperature.

    Attributes
    ----------
    conductivity : float
        Thermal conductivity kappa [W/(m K)] of the rubber, 0.01 .. 10.
    heat_capacity : float
        Volumetric heat capacity rho c [J/(m^3 K)] (density times specific
        heat), 1e5 .. 1e7.
    heat_fraction : float
        Fraction of the friction power that flows into the rubber (0..1; the
        rest into the counter-surface).  0 is the isothermal theory, exactly.
    closure : str
        ``"volume"`` (default, Persson 2006: heat made in the volume down to the
        depth 1/q) or ``"surface-flux"`` (a flux through sliding discs; an
        upper bound).  See :mod:`frictionlaws.persson.flash`.
    contact_temperature : str
        For the volume closure: ``"mean"`` (default) the mean temperature over
        the contact time, ``"exit"`` the temperature at its end.
    sliding_distance : float
        Sliding distance L [m] over which the background (cumulative) heating
        builds up, 0 .. 1000; 0 (default) is none: the rubber away from the
        contacts stays at the nominal temperature.
    tol : float
        Convergence of the temperatures [K].
    max_iter : int
        Iterations allowed before the solution is refused.

    Raises
    ------
    InputError
        A value that is not a finite number, outside its range (naming the
        likely unit mistake), or an unknown closure.
    """

    conductivity: float = 0.25
    heat_capacity: float = 1.8e6
    heat_fraction: float = 1.0
    closure: str = "volume"
    contact_temperature: str = "mean"
    sliding_distance: float = 0.0
    tol: float = 1e-4
    max_iter: int = 400

    def __post_init__(self) -> None:
        kappa = _number("conductivity", self.conductivity, "W/(m K)")
        rho_c = _number("heat_capacity", self.heat_capacity, "J/(m^3 K)")
        _check_thermal(kappa, rho_c)
        hf = _number("heat_fraction", self.heat_fraction, "-")
        if not 0.0 <= hf <= 1.0:
            raise InputError(f"flash temperature: heat_fraction = {hf:g} must be in 0..1 (a "
                             "fraction, not a percentage)")
        for name, value, choices in (("closure", self.closure, CLOSURES),
                                     ("contact_temperature", self.contact_temperature,
                                      CONTACT_TEMPERATURES)):
            if not isinstance(value, str) or value not in choices:
                raise InputError(f"flash temperature: {name} = {value!r} must be one of "
                                 + ", ".join(repr(c) for c in choices))
        L = _number("sliding_distance", self.sliding_distance, "m")
        if not 0.0 <= L <= _DISTANCE_MAX:
            raise InputError(f"flash temperature: sliding_distance = {L:g} m must be in "
                             f"0 .. {_DISTANCE_MAX:g} m (0: no background heating)")
        tol = _number("tol", self.tol, "K")
        if not tol > 0:
            raise InputError(f"flash temperature: tol = {tol:g} K must be > 0")
        n = self.max_iter
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)) or n < 1:
            raise InputError(f"flash temperature: max_iter = {n!r} must be a whole number of "
                             "iterations, at least 1")

    @property
    def diffusivity(self) -> float:
        """Thermal diffusivity D = kappa / (rho c) [m^2/s]."""
        return self.conductivity / self.heat_capacity


#: Representative thermal properties of a filled tread rubber (chosen values of the
#: usual order: kappa about 0.2-0.3 W/(m K), rho c about 1.5-2e6 J/(m^3 K)), all the
#: friction heat into the rubber, the volume closure, no background heating.
TREAD_THERMAL = Flash()


def _h(x: np.ndarray, how: str) -> np.ndarray:
    """The share of the heat a layer keeps: h_exit or h_mean of x = D q^2 t (series near 0)."""
    x = np.asarray(x, dtype=float)
    small = x < 1e-4
    xs, x0 = np.where(small, 1.0, x), np.where(small, x, 0.0)
    exit_ = -np.expm1(-xs) / xs
    if how == "exit":
        return np.where(small, 1.0 - x0 / 2 + x0 * x0 / 6, exit_)
    # (x - 1 + exp(-x)) / x^2 written as (1 - h_exit) / x: no overflow at large x
    return np.where(small, 0.5 - x0 / 6 + x0 * x0 / 24, (1.0 - exit_) / xs)


def temperature_rise(flash: Flash, q: np.ndarray, weights: np.ndarray, cum: np.ndarray,
                     dmu: np.ndarray, P: np.ndarray, v: np.ndarray, p: np.ndarray
                     ) -> np.ndarray:
    """``T_q - T`` [K] made by a given dissipation, without the background heating.

    Parameters
    ----------
    flash : Flash
        The settings.
    q, weights, cum : numpy.ndarray
        The quadrature wavenumbers [1/m], their weights in ln q and the cumulative
        integration matrix (:func:`frictionlaws.persson.theory.q_nodes`).
    dmu, P : numpy.ndarray
        The friction integrand times the weights and the contact ratio at the
        nodes (points x nodes).
    v, p : numpy.ndarray
        Sliding velocity [m/s] (> 0) and nominal pressure [Pa] per point.

    Returns
    -------
    numpy.ndarray
        The rise at each point and node (points x nodes).
    """
    Pc = np.maximum(P, 1e-300)
    vv = np.maximum(v, 1e-300)[:, None]
    if flash.closure == "surface-flux":
        a = np.pi / (2.0 * q)
        phi = 2.0 / np.sqrt(np.pi * (1.273 + vv * a[None, :] / (2.0 * flash.diffusivity)))
        K = a[None, :] * phi / Pc
        finer = np.cumsum(dmu[:, ::-1], axis=1)[:, ::-1]        # sum over q' >= q
        coarser = np.cumsum(dmu * K, axis=1) - dmu * K           # sum over q' < q of dmu K
        c = flash.heat_fraction * p * v / flash.conductivity
        return c[:, None] * (K * finer + coarser)
    x = np.pi * flash.diffusivity * q[None, :] / vv
    band = (flash.heat_fraction * np.pi / flash.heat_capacity) * p[:, None] * dmu \
        * _h(x, flash.contact_temperature) / Pc
    # the bands' rises as a density in ln q', integrated from q0 to each q
    return (band / weights[None, :]) @ cum.T


def background_rise(flash: Flash, mu: np.ndarray, v: np.ndarray, p: np.ndarray) -> np.ndarray:
    """Background (cumulative) heating [K] per point: constant flux on a half-space.

    ``2 heat_fraction mu p sqrt(L v / (pi kappa rho c))`` after the sliding
    distance L = ``flash.sliding_distance`` (0 when L = 0).
    """
    if flash.sliding_distance == 0.0:
        return np.zeros(np.shape(mu))
    return 2.0 * flash.heat_fraction * mu * p * np.sqrt(
        flash.sliding_distance * v / (np.pi * flash.conductivity * flash.heat_capacity))
