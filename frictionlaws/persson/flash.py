"""Flash temperature: the rubber's heating by its own friction, scale by scale.

After B. N. J. Persson, Rubber friction: role of the flash temperature, J. Phys.:
Condens. Matter 18 (2006) 7789-7823: the energy dissipated in the rubber heats
it; because the modulus depends so strongly on temperature, the rubber at the
length scale 2 pi/q is taken at its own temperature ``T_q`` and the friction
integral uses ``E(omega, T_q)``.  The heat diffuses in the rubber, so small hot
spots cool fast and large ones slowly.

The closure used here (a simplified, stated form of that treatment, not its
kernel): the friction power per unit nominal area, ``mu p v``, is split over the
scales as the friction integrand ``dmu(q)``; a fraction ``heat_fraction`` of it
flows into the rubber.  The contact regions seen at scale q cover the fraction
P(q) of the nominal area and have the radius ``a_q = pi/(2 q)`` (half a
wavelength across).  Heat made at finer scales (q' >= q) flows through the
scale-q regions; heat made at coarser scales (q' < q) heats the larger regions
those lie in.  A region of radius a under the mean flux density j reaches

    dT = j a / kappa * 2 / sqrt(pi (1.273 + Pe)),  Pe = v a / (2 D),

the interpolation of Tian and Kennedy (J. Tribol. 116 (1994) 167-174) for the
maximum temperature of a circular heat source sliding on a half-space, exact at
rest (``j a/kappa``) and fast (``2 j sqrt(t/(pi kappa rho c))`` for the contact
time t = 2a/v).  So

    T_q = T + heat_fraction * p v / kappa * sum_q' dmu(q') K(min(q, q')),
    K(q) = a_q phi(Pe_q) / P(q),

solved with mu itself by damped fixed-point iteration.  With no heat
(``heat_fraction = 0``) or a conductivity without bound it is the isothermal
theory.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from ..base.errors import InputError

__all__ = ["Flash", "TREAD_THERMAL"]


@dataclass(frozen=True)
class Flash:
    """Thermal properties of the rubber for the flash temperature.

    Attributes
    ----------
    conductivity : float
        Thermal conductivity kappa [W/(m K)].
    heat_capacity : float
        Volumetric heat capacity rho c [J/(m^3 K)].
    heat_fraction : float
        Fraction of the friction power that flows into the rubber (0..1; the
        rest into the counter-surface).  0 is the isothermal theory.
    tol : float
        Convergence of the temperatures [K].
    max_iter : int
        Iterations allowed before the solution is refused.
    """

    conductivity: float = 0.25
    heat_capacity: float = 1.8e6
    heat_fraction: float = 1.0
    tol: float = 1e-4
    max_iter: int = 400

    def __post_init__(self) -> None:
        for name in ("conductivity", "heat_capacity"):
            x = getattr(self, name)
            if not (isinstance(x, (int, float)) and x > 0 and not math.isnan(x)):
                raise InputError(f"flash temperature: {name} = {x!r} must be > 0")
        if not 0.0 <= self.heat_fraction <= 1.0:
            raise InputError(f"flash temperature: heat_fraction = {self.heat_fraction!r} "
                             "must be in 0..1")
        if not (self.tol > 0 and self.max_iter >= 1):
            raise InputError("flash temperature: tol must be > 0 and max_iter >= 1")

    @property
    def diffusivity(self) -> float:
        """Thermal diffusivity D = kappa / (rho c) [m^2/s]."""
        return self.conductivity / self.heat_capacity


#: Representative thermal properties of a filled tread rubber (chosen values of the
#: usual order: kappa about 0.2-0.3 W/(m K), rho c about 1.5-2e6 J/(m^3 K)), all the
#: friction heat into the rubber.
TREAD_THERMAL = Flash()
