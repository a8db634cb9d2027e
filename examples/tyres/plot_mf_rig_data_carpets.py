"""
Rig data to a complete Magic Formula file: forces and aligning moment
======================================================================

A flat-track rig sweeps slip ratio and slip angle up and down at several loads, pressures
and cambers, runs a combined-slip grid, and records jittery slips, a drifting load and noisy
forces and moments. This example makes such data from a tyre unlike the packaged MF 6.1
template (:func:`frictionlaws.tyre.synthetic_rig.moved_tyre`: 23 coefficients moved by
5-50 %), fits every stage with :func:`frictionlaws.tyre.fit_mf` (pure slip, combined-slip
weights, the aligning moment), writes the ``.tir`` file, reads it back and draws carpet
plots of the fitted file against the data and the noise-free truth.
"""

# %%
# Rig-like data of a tyre nobody has
# ----------------------------------
# Three loads, two pressures, cambers -3, 0 and +3 degrees, up and down sweeps and a
# combined grid, with 1 % noise on F_x, F_y and M_z.
import tempfile
import warnings
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import MagicFormula, fit_mf
from frictionlaws.tyre.synthetic_rig import moved_tyre, rig_data

warnings.simplefilter("ignore", ExtrapolationWarning)
truth = moved_tyre()
data = rig_data(truth, n=21, loads=(0.5, 1.0, 1.5))
print(f"{data.fx.size} rows; loads {data.fz.min() / 1e3:.2f} to {data.fz.max() / 1e3:.2f} kN, "
      f"cambers {np.degrees(data.gamma).min():.0f} to {np.degrees(data.gamma).max():.0f} deg")

# %%
# Fit every stage and write the property file
# -------------------------------------------
# The report lists each stage, the coefficients the data cannot determine (held at the
# template's value, by name) and the standard errors.
result = fit_mf(data, fittyp=61)
tir = Path(tempfile.mkdtemp()) / "rig_tyre.tir"
result.write(tir)
fitted = MagicFormula.from_file(tir)
report = result.report().splitlines()
print("\n".join(report[:4] + ["  ..."] + [line for line in report
                                         if "determined" in line or "stage" in line]))

# %%
# Carpet plots: F_x, F_y and M_z against the data
# -----------------------------------------------
# Pure slip at the nominal pressure and zero camber, at each load: the data (points), the
# fitted file (lines) and the truth (dashed). The differences are stated below each panel.
fnom = truth.fnomin
p_nom = truth.nominal_pressure
kappa = np.linspace(-0.25, 0.25, 101)
alpha = np.radians(np.linspace(-12, 12, 101))
fig, axes = plt.subplots(1, 3, figsize=(12, 4), layout="constrained")
worst = {"Fx": 0.0, "Fy": 0.0, "Mz": 0.0}
for i, load in enumerate((0.5, 1.0, 1.5)):
    fz = load * fnom
    colour = f"C{i}"
    rows = (np.abs(data.fz / fz - 1) < 0.05) & (np.abs(data.gamma) < 1e-3) & (
        np.abs(data.pressure / p_nom - 0.85) < 0.01)
    pure_x = rows & (np.abs(data.alpha) < np.radians(0.5))
    pure_y = rows & (np.abs(data.kappa) < 0.005)
    at = (fz, 0.0, 0.85 * p_nom)
    curves = (
        ("Fx", kappa, data.kappa[pure_x], data.fx[pure_x],
         fitted.fx0(kappa, *at), truth.fx0(kappa, *at)),
        ("Fy", np.degrees(alpha), np.degrees(data.alpha[pure_y]), data.fy[pure_y],
         fitted.fy0(alpha, *at), truth.fy0(alpha, *at)),
        ("Mz", np.degrees(alpha), np.degrees(data.alpha[pure_y]), data.mz[pure_y],
         fitted.mz0(alpha, *at), truth.mz0(alpha, *at)),
    )
    for ax, (name, x, xd, yd, fit_y, true_y) in zip(axes, curves):
        ax.plot(xd, yd, ".", ms=3, color=colour, alpha=0.5)
        ax.plot(x, fit_y, "-", color=colour, label=f"{fz / 1e3:.1f} kN")
        ax.plot(x, true_y, "--", color="k", lw=0.8)
        worst[name] = max(worst[name], float(np.abs(fit_y - true_y).max()
                                             / np.abs(true_y).max()))
for ax, (name, xlabel, unit) in zip(axes, (("Fx", "slip ratio [-]", "N"),
                                           ("Fy", "slip angle [deg]", "N"),
                                           ("Mz", "slip angle [deg]", "N m"))):
    ax.set_xlabel(xlabel)
    ax.set_ylabel(f"{name} [{unit}]")
    ax.set_title(f"{name}: file within {100 * worst[name]:.2f} % of peak", fontsize="medium")
    ax.grid(alpha=0.3)
axes[0].legend(title="load (dashed: truth)", fontsize="small")
plt.show()
# sphinx_gallery_thumbnail_number = 1

# %%
# What the numbers say
# --------------------
# The fitted file reproduces the noise-free truth within the percentages in the panel titles
# (peak-normalised, pure slip, these loads); ``tests/tyre/test_tyre_fit_mf_stages.py`` holds the
# same comparison at every load, camber and pressure, combined slip included.
print({k: f"{100 * v:.2f} %" for k, v in worst.items()})
