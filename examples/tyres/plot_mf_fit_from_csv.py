"""
From tyre test data to a Magic Formula property file
====================================================

A flat-track test gives forces against slip at several loads, pressures and cambers. This
example writes such a test as a tidy CSV file (here generated from the packaged MF 6.1
example with 1 % noise, so that the answer is known), fits the pure-slip Magic Formula to it
with :func:`frictionlaws.tyre.fit_mf`, writes the ``.tir`` file, reads it back with the
library's own reader and compares the fitted curves with the data and with the original
file.
"""

# %%
# The measurements: a tidy CSV file with units in the headers
# -----------------------------------------------------------
# 4 loads x 3 pressures x 3 cambers, a slip-ratio sweep at zero slip angle and a slip-angle
# sweep at zero slip ratio for each. Loads in kN, angles in degrees, pressure in kPa: the
# reader converts every column to SI.
import tempfile
import warnings
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import MagicFormula, fit_mf

warnings.simplefilter("ignore", ExtrapolationWarning)
truth = MagicFormula.from_file("MagicFormula61")
rng = np.random.default_rng(7)
kappa = np.linspace(-0.25, 0.25, 21)
alpha_deg = np.linspace(-12, 12, 21)
lines = ["Fz [kN],kappa [-],alpha [deg],gamma [deg],pressure [kPa],Fx [N],Fy [N]"]
for fz_kN in (3.0, 5.0, 7.0, 9.0):
    for p_kPa in (230.0, 260.0, 290.0):
        for gamma_deg in (-4.0, 0.0, 4.0):
            args = (fz_kN * 1e3, np.radians(gamma_deg), p_kPa * 1e3)
            fx = truth.fx0(kappa, *args)
            fy = truth.fy0(np.radians(alpha_deg), *args)
            fx += 0.01 * np.abs(fx).max() * rng.standard_normal(fx.size)
            fy += 0.01 * np.abs(fy).max() * rng.standard_normal(fy.size)
            for k, f in zip(kappa, fx):
                lines.append(f"{fz_kN},{k:.4f},0,{gamma_deg},{p_kPa},{f:.1f},")
            for a, f in zip(alpha_deg, fy):
                lines.append(f"{fz_kN},0,{a:.3f},{gamma_deg},{p_kPa},,{f:.1f}")
workdir = Path(tempfile.mkdtemp())
csv = workdir / "flat_track.csv"
csv.write_text("\n".join(lines) + "\n")
print(f"{len(lines) - 1} rows, e.g.:")
print("\n".join(lines[:3]))

# %%
# Fit and write the property file
# -------------------------------
# ``fit_mf`` fits the Fx0 and Fy0 coefficient groups in stages and reports each coefficient
# with its standard error. Coefficients the data cannot determine would keep the template's
# value and be listed in the notes. The ``.tir`` file is written atomically.
result = fit_mf(csv, fittyp=61)
print(result.report())
tir = result.write(workdir / "fitted.tir")
fitted = MagicFormula.from_file(tir)
print(f"read back: Magic Formula {fitted.version}, FNOMIN {fitted.fnomin:g} N")

# %%
# The fit against the data and the original file
# -----------------------------------------------
# Dots are the measured points at the nominal pressure and zero camber; lines the fitted file;
# dashes the file the data came from. The largest difference between fitted and original
# curves over the data range is printed as a share of the peak force.
fig, (ax_x, ax_y) = plt.subplots(1, 2, figsize=(11, 4.5), layout="constrained")
data = result.data
worst = 0.0
for i, fz in enumerate((3e3, 5e3, 7e3, 9e3)):
    color = f"C{i}"
    ref = (np.abs(data.fz - fz) < 1) & (data.gamma == 0) & (np.abs(data.pressure - 2.6e5) < 1)
    sx = ref & np.isfinite(data.fx)
    sy = ref & np.isfinite(data.fy)
    ax_x.plot(data.kappa[sx], data.fx[sx] / 1e3, ".", color=color)
    ax_y.plot(np.degrees(data.alpha[sy]), data.fy[sy] / 1e3, ".", color=color)
    k = np.linspace(-0.25, 0.25, 200)
    a = np.radians(np.linspace(-12, 12, 200))
    ax_x.plot(k, fitted.fx0(k, fz) / 1e3, color=color, label=f"{fz / 1e3:g} kN")
    ax_x.plot(k, truth.fx0(k, fz) / 1e3, "--", color=color, lw=0.8)
    ax_y.plot(np.degrees(a), fitted.fy0(a, fz) / 1e3, color=color, label=f"{fz / 1e3:g} kN")
    ax_y.plot(np.degrees(a), truth.fy0(a, fz) / 1e3, "--", color=color, lw=0.8)
    for f_fit, f_true in ((fitted.fx0(k, fz), truth.fx0(k, fz)),
                          (fitted.fy0(a, fz), truth.fy0(a, fz))):
        worst = max(worst, np.abs(f_fit - f_true).max() / np.abs(f_true).max())
ax_x.set(xlabel="slip ratio kappa [-]", ylabel="Fx0 [kN]", title="longitudinal")
ax_y.set(xlabel="slip angle alpha [deg]", ylabel="Fy0 [kN]", title="lateral")
for ax in (ax_x, ax_y):
    ax.grid(alpha=0.3)
    ax.legend(title="Fz", fontsize="small")
print(f"largest fitted-vs-original difference: {100 * worst:.2f} % of the peak force")
plt.show()

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
