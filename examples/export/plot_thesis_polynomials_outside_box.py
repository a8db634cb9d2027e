"""
The thesis polynomials outside their measured box
=================================================

The thesis summarised its tribometer campaign with two polynomial correlations in contact
pressure P [MPa] and disc velocity V [m/s] (its Eqs. 5-1 and 5-2, coefficients in Tables
5-1 and 5-2). Inside the box where they were measured, 0.03 to 0.25 MPa and 0 to 2.77 m/s,
they describe the data well (R² of 80 to 90 %). A polynomial carries no physics, though:
just outside the box it turns, and a little further it gives friction coefficients no
rubber ever had. This example shows where.
"""

# %%
# The published coefficients are presets
# ---------------------------------------
# ``thesis-poly2`` and ``thesis-poly3`` take the library's SI pressure and convert it to MPa
# inside the formula, so the presets are the published numbers. Their declared domain is
# the measured box, and it is strict: ``law(...)`` refuses a point outside it (and any
# negative mu). To look at what the polynomials do outside, ``law.evaluate`` gives the
# formula's bare numbers.
import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl

poly2 = fl.get_law("thesis-poly2")
poly3 = fl.get_law("thesis-poly3")
print("domain:", {k: v for k, v in poly2.domain.items()})
try:
    poly2(p=0.5e6, v=1.38, preset="steel")
except fl.InputError as exc:
    print("refused:", exc)


def bare(law, preset, **variables):
    """The formula's numbers, without the domain checks of law(...)."""
    return law.evaluate(variables, law.resolve(preset=preset))


for law in (poly2, poly3):
    for preset in law.presets:
        inside = law(p=0.1e6, v=1.38, preset=preset)
        outside = bare(law, preset, p=0.5e6, v=1.38)
        print(f"{law.id:<13} {preset:<10} mu(0.1 MPa) = {inside:6.2f}   "
              f"mu(0.5 MPa) = {outside:8.2f}")

# %%
# Along the pressure and the velocity
# -----------------------------------
# Each law with its ``steel`` preset, beside the 19 measured steel-disc points. The grey
# band is the measured box; the Thirion law fitted to the same points is drawn for contrast:
# it has two parameters and a physical reason to level off.
data = fl.load_dataset("thesis-steel").frame
thirion = fl.fit("thirion", "thesis-steel")
p = np.linspace(0.0, 0.6e6, 300)
v = np.linspace(0.0, 10.0, 300)
lo_p, hi_p = poly2.domain["p"]
lo_v, hi_v = poly2.domain["v"]

fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 5.2), layout="constrained")
for law, color in ((poly2, "C0"), (poly3, "C1")):
    ax1.plot(p / 1e6, bare(law, "steel", p=p, v=np.full_like(p, 1.38)), color=color,
             lw=2, label=f"{law.id} (steel), v = 1.38 m/s")
    ax2.plot(v, bare(law, "steel", p=np.full_like(v, 0.1e6), v=v), color=color, lw=2,
             label=f"{law.id} (steel), p = 0.1 MPa")
ax1.plot(p / 1e6, thirion.predict(p=np.maximum(p, 1.0), warn=False), color="k", lw=1.5,
         ls="--", label="thirion fitted to the points")
ax1.plot(data["p"] / 1e6, data["mu"], "o", color="0.3", ms=4, label="thesis-steel data")
ax1.axvspan(lo_p / 1e6, hi_p / 1e6, color="0.9", zorder=0, label="measured box")
ax2.axvspan(lo_v, hi_v, color="0.9", zorder=0, label="measured box")
ax1.set_xlabel("contact pressure p [MPa]")
ax2.set_xlabel("velocity v [m/s]")
for ax in (ax1, ax2):
    ax.set_ylabel("μ [–]")
    ax.set_ylim(-2, 8)
    ax.axhline(0, color="k", lw=0.5)
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", loc="upper left")
plt.show()

# %%
# The whole plane
# ---------------
# The quadratic law over a pressure-velocity plane four times larger than the box in each
# direction. Contours at μ = 0 and μ = 5 mark where it stops being a friction coefficient;
# the rectangle is the measured box.
P, V = np.meshgrid(np.linspace(0.0, 1.0e6, 200), np.linspace(0.0, 11.0, 200))
MU = bare(poly2, "steel", p=P, v=V)
fig, ax = plt.subplots(figsize=(7, 4.8), layout="constrained")
mesh = ax.pcolormesh(P / 1e6, V, np.clip(MU, -5, 40), cmap="magma", shading="auto")
fig.colorbar(mesh, ax=ax, label="μ (clipped to -5..40)")
contours = ax.contour(P / 1e6, V, MU, levels=[0.0, 5.0], colors=["c", "w"], linewidths=1.5)
ax.clabel(contours, fmt={0.0: "μ = 0", 5.0: "μ = 5"}, fontsize=8)
ax.add_patch(plt.Rectangle((lo_p / 1e6, lo_v), (hi_p - lo_p) / 1e6, hi_v - lo_v, fill=False,
                           ec="lime", lw=2))
ax.set_xlabel("contact pressure p [MPa]")
ax.set_ylabel("velocity v [m/s]")
ax.set_title("thesis-poly2, preset 'steel'")
plt.show()

# %%
# How the library guards the edge
# -------------------------------
# The law knows its domain and counts the points outside it; a fitted result warns when it
# is evaluated outside the data it was fitted to.
print(poly2.outside_domain({"p": np.array([0.1e6, 0.5e6, 1.0e6]), "v": np.array([1.0, 5.0, 1.0])}))
refit = fl.fit("thesis-poly2", "thesis-steel")
print(refit.extrapolation({"p": np.array([0.5e6]), "v": np.array([1.38])}))

# The gallery thumbnail: figure 2 of this example.
# sphinx_gallery_thumbnail_number = 2
