"""
Transient side force: the relaxation length
===========================================

A tyre builds its side force while it rolls, not at the instant the slip angle changes:
the carcass has to deflect first. MF-Tyre's first-order transient model lags the slips
over the relaxation lengths (``sigmay`` for the slip angle, ``sigmax`` for the slip ratio)
and evaluates the steady-state Magic Formula at the lagged slips.
:func:`~frictionlaws.tyre.transient_slip` integrates it for time histories of speed, load,
slips and camber. This example steps the slip angle and then drives the tyre through
sinusoidal steering at rising frequency.
"""

# %%
# A step in slip angle
# --------------------
# At 20 m/s and 4 kN the packaged MF 6.1 tyre is stepped from 0 to 0.5 degree (two samples at
# t = 0 make the jump). Against the distance rolled, the side force rises as
# ``1 - exp(-s / sigma_y)``: 63 % of its new steady value after one relaxation length.
import matplotlib.pyplot as plt
import numpy as np

from frictionlaws.tyre import MagicFormula, transient_slip

mf = MagicFormula.from_file("MagicFormula61")
vx, fz = 20.0, 4000.0
t = np.concatenate([[0.0], np.linspace(0.0, 0.15, 301)])
alpha = np.where(np.arange(t.size) >= 1, np.radians(0.5), 0.0)
step = transient_slip(mf, t, vx, fz, alpha=alpha)
sigma = step.sigma_y[0]
share = (step.Fy - step.Fy[0]) / (step.Fy_steady[-1] - step.Fy[0])
at_sigma = np.interp(sigma, step.distance, share)
print(f"relaxation length sigma_y = {sigma * 1000:.0f} mm at {fz / 1000:g} kN; "
      f"after one sigma the side force has {at_sigma:.1%} of its change")

fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
ax.plot(step.distance / sigma, share, lw=2, label="side force, transient")
ax.plot(step.distance / sigma, -np.expm1(-step.distance / sigma), "k--", lw=1,
        label="1 - exp(-s / sigma_y)")
ax.axvline(1.0, color="0.6", lw=0.8)
ax.axhline(1 - np.exp(-1), color="0.6", lw=0.8)
ax.set_xlabel("distance rolled s / sigma_y [–]")
ax.set_ylabel("share of the steady change [–]")
ax.set_xlim(0, 5)
ax.grid(alpha=0.3)
ax.legend()
plt.show()

# %%
# Steering at rising frequency
# ----------------------------
# A sinusoidal slip angle of 2 degrees at 0.5 to 8 Hz: the lag is a first-order filter in
# the distance rolled, so the side force falls behind the slip angle more, and shrinks,
# the shorter the wavelength is against sigma_y (the tyre's bandwidth here is
# V / (2 pi sigma_y)).
fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharey=True, layout="constrained")
for ax, f in zip(axes.flat, (0.5, 2.0, 4.0, 8.0)):
    t = np.linspace(0.0, 3 / f, 600)
    alpha = np.radians(2.0) * np.sin(2 * np.pi * f * t)
    r = transient_slip(mf, t, vx, fz, alpha=alpha, initial=(0.0, 0.0))
    ax.plot(t * f, r.Fy_steady / 1000, color="0.5", lw=1, label="steady state")
    ax.plot(t * f, r.Fy / 1000, lw=2, label="transient")
    ax.set_title(f"{f:g} Hz: wavelength {vx / f:.1f} m")
    ax.grid(alpha=0.3)
for ax in axes[1]:
    ax.set_xlabel("periods [–]")
for ax in axes[:, 0]:
    ax.set_ylabel("F_y [kN]")
axes[0, 0].legend(fontsize="small")
plt.show()
print(f"bandwidth V / (2 pi sigma_y) = {vx / (2 * np.pi * sigma):.1f} Hz")

# The gallery thumbnail: figure 1 of this example (the step response).
# sphinx_gallery_thumbnail_number = 1
