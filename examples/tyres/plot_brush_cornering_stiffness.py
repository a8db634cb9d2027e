"""
Brush-model cornering stiffness against load
============================================

Chapter 6 of the source thesis ran a finite-element tyre at loads of 2 to 6.5 kN with a
constant friction coefficient (0.9 and 1.0) and with pressure-dependent friction from its
tribometer tests. With constant friction the cornering stiffness kept rising with load
(2.65 times from 2 to 6.5 kN at mu = 0.9); with the measured friction it rose less (1.89
times on sandpaper 120) and levelled off.

Here the same experiment is repeated with a steady-state brush tyre whose bristles obey a
friction law: ``coulomb`` at 0.9 and 1.0 against the Thirion law fitted to the thesis'
steel-disc data. The brush tyre is not the FE model, so the numbers differ; the question is
whether the qualitative difference comes back.
"""

# %%
# Run the comparison
# ------------------
# :func:`frictionlaws.tyre.thesis.thesis_comparison` fits the law to ``thesis-steel``,
# builds one :class:`~frictionlaws.tyre.brush.BrushModel` per friction description and
# computes the cornering stiffness (least-squares slope of F_y over 1, 2 and 3 degrees)
# at the thesis' ten loads.
import matplotlib.pyplot as plt
import numpy as np

from frictionlaws.tyre.brush import BrushModel
from frictionlaws.tyre.thesis import TABLE_6_2, thesis_comparison

comparison = thesis_comparison(laws=("thirion",))
labels = list(comparison.results)
print("brush model, cornering stiffness [kN/deg]")
print(f"{'F_z [kN]':>9}" + "".join(f"{label:>24}" for label in labels))
for i, load in enumerate(comparison.loads_kN):
    print(f"{load:>9.3g}" + "".join(f"{comparison.results[label].cs_kN_per_deg[i]:>24.3f}"
                                    for label in labels))
print()
print("thesis FE model, Table 6-2 [kN/deg]")
columns = list(TABLE_6_2["columns"])
print(f"{'F_z [kN]':>9}" + "".join(f"{c:>9}" for c in columns))
for i, load in enumerate(TABLE_6_2["loads_kN"]):
    print(f"{load:>9.3g}" + "".join(f"{TABLE_6_2['columns'][c][i]:>9.3f}" for c in columns))

# %%
# Cornering stiffness and its growth with load
# --------------------------------------------
# Left: the stiffness itself, brush model (solid) and thesis FE (dashed). Right: each
# curve divided by its value at 2 kN, which removes the difference in tyre stiffness and
# shows only how the stiffness grows with load.
loads = comparison.loads_kN
table_loads = np.asarray(TABLE_6_2["loads_kN"])
fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 5.0), layout="constrained")
colors = {"coulomb 0.9": "C0", "coulomb 1.0": "C1"}
for label, result in comparison.results.items():
    color = colors.get(label, "C3")
    cs = result.cs_kN_per_deg
    ax1.plot(loads, cs, "-o", ms=4, color=color, label=f"brush: {label}")
    ax2.plot(loads, cs / cs[0], "-o", ms=4, color=color, label=f"brush: {label}")
for column, color in (("mu 0.9", "C0"), ("mu 1.0", "C1"), ("steel", "C3"), ("S120", "C2")):
    cs = np.asarray(TABLE_6_2["columns"][column])
    ax1.plot(table_loads, cs, "--s", ms=3, color=color, alpha=0.7, label=f"thesis FE: {column}")
    ax2.plot(table_loads, cs / cs[0], "--s", ms=3, color=color, alpha=0.7,
             label=f"thesis FE: {column}")
ax2.plot(loads, loads / loads[0], ":", color="0.4", label="proportional to load")
ax1.set_ylabel("cornering stiffness [kN/deg]")
ax2.set_ylabel("CS / CS(2 kN) [–]")
for ax in (ax1, ax2):
    ax.set_xlabel("vertical load F_z [kN]")
    ax.grid(alpha=0.3)
fig.legend(*ax2.get_legend_handles_labels(), loc="outside lower center", ncol=4,
           fontsize="small")
plt.show()

# %%
# The ratios CS(6.5 kN) / CS(2 kN)
# --------------------------------
ours = comparison.ratios()
theirs = comparison.thesis_ratios()
for label, ratio in ours.items():
    print(f"brush  {label:<24} {ratio:.2f}")
for label, ratio in theirs.items():
    print(f"FE     {label:<24} {ratio:.2f}")

# %%
# Why: the sliding zone
# ---------------------
# With constant friction both the elastic force of the bristles and the friction limit
# grow in proportion to the load, so the share of the patch that slides does not change.
# With Thirion's law the friction coefficient falls as the mean pressure rises with load,
# so at the same slip angle a larger part of the patch slides. The plots show the lateral
# line load along the patch at 2 degrees, at the lightest and heaviest load; the shaded
# parts slide.
fit = comparison.fits["thirion (thesis-steel)"]
models = {"coulomb 0.9": BrushModel("coulomb", {"mu0": 0.9}), "thirion": BrushModel(fit)}
fig, axes = plt.subplots(1, 2, figsize=(11, 3.6), sharey=True, layout="constrained")
for ax, (label, model) in zip(axes, models.items()):
    for fz, color in ((2000.0, "C0"), (6500.0, "C3")):
        state = model.patch_state(np.radians(2.0), fz, direction="y")
        x_mm = state["s"] * 1e3
        ax.plot(x_mm, state["line_load"] / 1e3, color=color, lw=2, label=f"F_z = {fz / 1e3:g} kN")
        ax.plot(x_mm, state["adhesion_line_load"] / 1e3, color=color, lw=0.8, ls=":")
        ax.fill_between(x_mm, 0, state["line_load"] / 1e3, where=state["sliding"],
                        color=color, alpha=0.15)
        share = np.mean(state["sliding"])
        print(f"{label:<12} F_z = {fz / 1e3:>3g} kN: {100 * share:4.0f} % of the patch slides")
    ax.set_title(label)
    ax.set_xlabel("distance from the leading edge [mm]")
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small")
axes[0].set_ylabel("lateral line load [kN/m]")
plt.show()

# %%
# The fitted law is used outside its data
# ---------------------------------------
# The heaviest loads press parts of the patch harder than the 0.25 MPa the tribometer
# reached; the model says how much of the load is carried by extrapolated friction:
for label, result in comparison.results.items():
    for message in result.warnings:
        print(f"{label}: {message}")

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
