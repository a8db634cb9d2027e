r"""
The flash temperature: a tread compound heated by its own friction
===================================================================

Persson's theory with the flash temperature of Persson (J. Phys.: Condens. Matter 18 (2006)
7789): the heat each length scale of the roughness makes is deposited in the rubber's volume,
down to the depth :math:`1/q` of that scale, diffuses during the time the rubber spends in a
contact, and heats the finer scales that lie in those contacts; the friction and the
temperatures :math:`T_q` are solved together (:mod:`frictionlaws.persson.flash` states the
equations, and the Persson guide which choices are the paper's and which are ours).

The rubber is the packaged tread compound (**constructed, not measured**:
``datasets/tread-compound/PROVENANCE.md``) on the asphalt-like surface with the cut-off
:math:`q_1 = 10^6` 1/m (preset ``tread-on-asphalt``) at 0.2 MPa, with the representative
thermal properties ``TREAD_THERMAL`` (conductivity 0.25 W/(m K), heat capacity
1.8 MJ/(m³ K), all the heat into the rubber).
"""

# %%
# mu(v) at 0, 20 and 40 °C, with and without the flash temperature
# -----------------------------------------------------------------
# Below its isothermal maximum the heated rubber behaves as if it slid more slowly, so the
# friction falls; the finest scales heat most, so the maximum is lower and broader. Above
# the maximum (the glassy side) heating softens the rubber back towards its transition and
# the friction is higher than isothermal. Where a temperature :math:`T_q` leaves the range
# of the compound's data (above 70 °C) its modulus is the WLF shift's extrapolation, and the
# library warns; those speeds are drawn dotted.
import warnings

import matplotlib.pyplot as plt
import numpy as np

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.persson import (
    TREAD_THERMAL,
    Flash,
    asphalt_like,
    flash_temperature,
    friction,
    tread_compound,
)
from frictionlaws.persson.published import peak

mat, surf, p = tread_compound(), asphalt_like(1e6), 2e5
v = np.logspace(-6, 2, 65)
top = mat.temperature_range()[1]
fig, ax = plt.subplots(figsize=(7.5, 4.2), layout="constrained")
for T, c in ((273.15, "C0"), (293.15, "C1"), (313.15, "C3")):
    iso = friction(mat, surf, v, T, p)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        hot = friction(mat, surf, v, T, p, flash=TREAD_THERMAL)
        _, Tq = flash_temperature(mat, surf, v, T, p, flash=TREAD_THERMAL)
    inside = Tq.max(axis=1) <= top
    (m0, v0), (m1, v1) = peak(v, iso), peak(v, hot)
    ax.semilogx(v, iso, color=c, lw=1, label=f"{T - 273.15:.0f} °C isothermal: max {m0:.2f} "
                f"at {v0:.3g} m/s")
    ax.semilogx(v[inside], hot[inside], "--", color=c, lw=2, label=f"{T - 273.15:.0f} °C "
                f"flash temperature: max {m1:.2f} at {v1:.3g} m/s")
    ax.semilogx(v[~inside], hot[~inside], ":", color=c, lw=2)
    print(f"T = {T - 273.15:3.0f} degC: maximum of mu {m0:.3f} at {v0:.3g} m/s isothermal, "
          f"{m1:.3f} at {v1:.3g} m/s with the flash temperature")
ax.set_xlabel("sliding velocity v [m/s]")
ax.set_ylabel("viscoelastic friction coefficient [-]")
ax.set_title("tread compound on asphalt-like road, 0.2 MPa")
ax.legend(fontsize=7, loc="upper left")

# %%
# The temperature rise at each scale, at 20 °C and 1 m/s
# ------------------------------------------------------
# The rise :math:`T_q - T` against the wavenumber: the coarse scales stay cold (their heat
# has time to spread), the finest are hottest, since they lie in the contacts of every
# coarser scale. The default takes each scale's mean temperature over the contact time;
# the temperature at its end heats more. The surface-flux closure (sliding discs heated
# through their surface, the closure shipped before; an upper bound for the same
# dissipation) heats even the coarsest scale, and its finest beyond the compound's data
# (its warning is silenced here; the text above says it).
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for flash, style, name in ((TREAD_THERMAL, "-", "volume, mean over the contact (default)"),
                           (Flash(contact_temperature="exit"), "--",
                            "volume, at the end of the contact"),
                           (Flash(closure="surface-flux"), ":", "surface flux (upper bound)")):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        q, Tq = flash_temperature(mat, surf, 1.0, 293.15, p, flash=flash)
    rise = Tq[0] - 293.15
    ax.semilogx(q, rise, style, color="C1", lw=2, label=f"{name}: {rise.max():.1f} K at most")
    print(f"{name}: rise {rise[0]:.2f} K at q = {q[0]:.3g} 1/m, {rise.max():.1f} K at most")
ax.set_xlabel("wavenumber q [1/m]")
ax.set_ylabel("temperature rise T_q - T [K]")
ax.set_title("20 °C, 1 m/s, 0.2 MPa")
ax.legend(fontsize=8)

# sphinx_gallery_thumbnail_number = 1
