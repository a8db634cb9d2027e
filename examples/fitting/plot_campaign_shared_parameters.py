r"""
A campaign at five temperatures: separate fits or a shared parameter
====================================================================

A compound is measured on the same counter-surface at five temperatures. Thirion's law,
:math:`1/\mu = a + b\,p`, has a level :math:`1/a` (the friction coefficient at low
pressure) and a saturation :math:`1/b` (the shear stress the real contact area saturates
at). Is the saturation a property of the contact that stays put while the level moves with
temperature? A *global* fit with ``b`` shared across the groups answers this, and the
comparison with separate fits says whether the data agree.

The data here are synthetic (the truth is known); the steps are those for measured data:
:func:`frictionlaws.fitting.campaign.fit_many` for the separate fits by group,
:func:`frictionlaws.fitting.shared.fit_shared` for the global fit.
"""

# %%
# A synthetic campaign
# --------------------
# 30 pressures per temperature, a level that rises with temperature, one saturation
# :math:`b = 3\times10^{-6}` 1/Pa, and a scatter of 0.02 in mu.
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

import frictionlaws as fl
from frictionlaws.fitting.campaign import fit_many
from frictionlaws.fitting.shared import fit_shared

law = fl.get_law("thirion")
rng = np.random.default_rng(11)
p = np.linspace(2e4, 1e6, 30)
frames = []
for i, T in enumerate((0, 10, 20, 30, 40)):
    mu = law(p=p, a=0.2 + 0.05 * i, b=3e-6) + 0.02 * rng.standard_normal(p.size)
    frames.append(pd.DataFrame({"mu": mu, "p [MPa]": p / 1e6, "T [degC]": T}))
data = pd.concat(frames, ignore_index=True)

# %%
# Separate fits, one per temperature
# ----------------------------------
# ``by="T"`` splits the data by temperature and fits each group on its own. The table has
# one row per group and parameter, with the unit of each value.
separate = fit_many("thirion", fl.load_dataset(data), by="T")
table = separate.to_frame()
print(table[["T [K]", "param", "value", "stderr", "unit", "r2"]].to_string(
    index=False, float_format="{:.5g}".format))

# %%
# One saturation for all temperatures
# -----------------------------------
# The global fit estimates one ``b`` from all 150 points and one ``a`` per temperature.
# The F-test compares it with the five separate fits (10 parameters against 6).
shared = fit_shared("thirion", data, by="T", shared=["b"])
print(shared.report())

# %%
# The estimates side by side
# --------------------------
# Left: each temperature's own ``b`` with its 95 % interval, and the shared value (band).
# Right: the data with the global fit. The separate estimates scatter around the shared
# one within their errors, which is what the F-test's p-value says in one number.
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(9, 3.8), layout="constrained")
b_rows = table[table["param"] == "b"]
T_c = b_rows["T [K]"].to_numpy() - 273.15
ax1.errorbar(T_c, b_rows["value"] * 1e6, yerr=1.96 * b_rows["stderr"] * 1e6, fmt="o",
             capsize=3, label="separate fits (95 % CI)")
sb = shared.shared_values()["b"]
ax1.axhspan((sb["value"] - 1.96 * sb["stderr"]) * 1e6, (sb["value"] + 1.96 * sb["stderr"]) * 1e6,
            color="C1", alpha=0.3, label="shared fit (95 % CI)")
ax1.axhline(3.0, color="k", lw=0.8, ls="--", label="truth")
ax1.set_xlabel("temperature T [°C]")
ax1.set_ylabel("b [1/MPa]")
ax1.legend(fontsize="small")
T_rows = data["T [degC]"].to_numpy() + 273.15
for g in shared.groups:
    T = g["key"]["T"]
    sel = np.isclose(T_rows, T)
    pts = ax2.plot(data["p [MPa]"][sel], data["mu"][sel], "o", ms=3)
    values = {k: e["value"] for k, e in g["params"].items()}
    ax2.plot(p / 1e6, law(p=p, **values), color=pts[0].get_color(),
             label=f"T = {T - 273.15:.0f} °C")
ax2.set_xlabel("contact pressure p [MPa]")
ax2.set_ylabel("friction coefficient mu [-]")
ax2.legend(fontsize="small")
plt.show()

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
