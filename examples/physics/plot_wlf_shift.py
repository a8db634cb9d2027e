r"""
A WLF temperature shift of a velocity law
=========================================

Rubber friction is viscoelastic: warming the rubber does what sliding it more slowly does.
The Williams-Landel-Ferry (WLF) equation gives the factor by which a temperature change
rescales the velocity,

.. math::

    \log_{10} a_T = -\frac{C_1 (T - T_\mathrm{ref})}{C_2 + T - T_\mathrm{ref}},

and a law measured at the reference temperature holds at another temperature when it is
evaluated at the reduced velocity :math:`a_T(T)\,v`.
:func:`frictionlaws.viscoelastic.temperature.with_wlf` turns any velocity-dependent law into
such a temperature-aware law. Here it is applied to the Savkoor law, a bell in log velocity.
"""

# %%
# The shift factor and its two published constant sets
# ----------------------------------------------------
# Grosch's constants (C1 = 8.86, C2 = 101.6 K) are referred to T_g + 50 K, the "universal"
# ones (17.44, 51.6 K) to T_g. For a tread compound with T_g = -50 °C they are nearly the
# same curve, offset by a constant (the value of log10 a_T at the other reference). WLF holds
# roughly from T_g to T_g + 100 K (shaded); below T_ref - C2 it has a pole.
import warnings

import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl
from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.viscoelastic.temperature import WLF_PRESETS, with_wlf, wlf_log_aT

T_G = 273.15 - 50.0
T = np.linspace(T_G - 20.0, T_G + 140.0, 400)
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for (name, preset), style in zip(WLF_PRESETS.items(), ("-", "--")):
    T_ref = preset.T_ref(T_G)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)  # the band shows the window
        shift = wlf_log_aT(T[T > T_ref - preset.C2 + 5], preset=name, T_g=T_G)
    # refer both curves to T_g + 50 K so they can be compared
    offset = wlf_log_aT(T_G + 50.0, preset=name, T_g=T_G, warn=False)
    ax.plot(T[T > T_ref - preset.C2 + 5] - 273.15, shift - offset, lw=2.5, ls=style,
            label=f"{name}: C1 = {preset.C1}, C2 = {preset.C2} K, T_ref = T_g + "
                  f"{preset.offset:g} K")
ax.axvspan(T_G - 273.15, T_G + 100.0 - 273.15, color="0.92", zorder=0,
           label="validity window T_g .. T_g + 100 K")
ax.axhline(0, color="k", lw=0.5)
ax.set_xlabel("temperature T [°C]")
ax.set_ylabel("log10 a_T, referred to T_g + 50 K")
ax.set_ylim(-8, 12)
ax.grid(alpha=0.3)
ax.legend(fontsize="x-small")
plt.show()

# %%
# A temperature-aware Savkoor law
# -------------------------------
# The base law's parameters describe the rubber at the reference temperature (here 0 °C,
# Grosch's T_g + 50 K): a friction peak of 1.2 at 1 mm/s. The new law has the extra
# variable ``T`` and the WLF constants as settings.
savkoor = fl.get_law("savkoor")
base = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": 0.0}
hot = with_wlf(savkoor, preset="grosch", T_g=T_G)
print(f"{hot.id}: {hot.title}")
print("variables:", hot.variables)
print("settings:", {s.name: f"{s.value:g} {s.unit}".strip() for s in hot.settings})
print("domain of T [K]:", hot.domain["T"])

v = np.geomspace(1e-7, 10.0, 300)
temps_c = [-40.0, -20.0, 0.0, 20.0, 40.0]
fig, ax = plt.subplots(figsize=(8, 4.2), layout="constrained")
colors = plt.get_cmap("plasma")(np.linspace(0, 0.85, len(temps_c)))
for temp, color in zip(temps_c, colors):
    mu = hot(v=v, T=np.full_like(v, temp + 273.15), p=np.full_like(v, 1e5), **base)
    ax.semilogx(v, mu, color=color, lw=2, label=f"T = {temp:g} °C")
ax.set_xlabel("sliding velocity v [m/s]")
ax.set_ylabel("μ [–]")
ax.set_title("savkoor+wlf: the peak moves to higher speed as the rubber warms")
ax.grid(alpha=0.3)
ax.legend(fontsize="small", loc="center left", bbox_to_anchor=(1.01, 0.5))
plt.show()

# %%
# Where the peak sits
# -------------------
# With ``a_T`` the peak velocity at temperature T is ``v_m / a_T(T)``: near T_ref each
# 20 K of warming moves it by one to two decades, and much more towards T_g.
for temp in temps_c:
    shift = wlf_log_aT(temp + 273.15, preset="grosch", T_g=T_G)
    print(f"T = {temp:>5g} °C   log10 a_T = {shift:+6.2f}   peak at v = "
          f"{base['v_m'] / 10**shift:.3g} m/s")

# %%
# Outside the window the law says so
# ----------------------------------
# T_g + 100 K is 50 °C here; asking for 90 °C gives an ``ExtrapolationWarning``, and a
# temperature below the pole raises an error.
with warnings.catch_warnings(record=True) as caught:
    warnings.simplefilter("always")
    hot(v=0.01, T=90.0 + 273.15, p=1e5, **base)
for w in caught:
    print(f"{w.category.__name__}: {w.message}")
try:
    hot(v=0.01, T=-110.0 + 273.15, p=1e5, **base)
except fl.InputError as exc:
    print(f"{type(exc).__name__}: {exc}")

# The gallery thumbnail: figure 2 of this example.
# sphinx_gallery_thumbnail_number = 2
