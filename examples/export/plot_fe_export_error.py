"""
An FE export and its interpolation error
========================================

Most finite-element codes take a pressure- or velocity-dependent friction coefficient as a
table: Abaqus ``*FRICTION`` data lines, an LS-DYNA ``*DEFINE_TABLE``, Ansys ``TB,FRIC`` with
``TBFIELD``. Between the rows the solver interpolates linearly and beyond the last row it
holds the end value. A table is therefore an approximation of the law, and how good it is
depends on where the rows are. :func:`frictionlaws.fe_export.export` measures that error the
way the solver interpolates, writes it into the file's header, and can place the rows until
it is below a tolerance.
"""

# %%
# A fitted law, written for Abaqus
# --------------------------------
# Thirion's law fitted to the thesis' steel data, written as an Abaqus ``*FRICTION`` table in
# the mm-N-s system (pressure in MPa) with six evenly spaced rows from 0.01 to 0.5 MPa. The
# header records the law, the fitted parameters with their standard errors, the units, the
# box, and the largest interpolation error with where it occurs.
import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl
from frictionlaws.fe_export import export
from frictionlaws.fe_export.grid import AxisSpec, interpolate, uniform_grid_for_tol

fit = fl.fit("thirion", "thesis-steel")
coarse = export(None, fit, "abaqus", {"p": ("0.01 MPa", "0.5 MPa", 6)}, units="mm-N-s",
                spacing={"p": "lin"})
print(coarse.text)

# %%
# Read the table back and interpolate it as the solver does
# ---------------------------------------------------------
# An independent check: parse the data lines of the written file (mu, slip rate, pressure in
# MPa), interpolate linearly with the ends held (``numpy.interp`` does exactly that) and
# compare with the law on a fine grid, a little wider than the box.
text_lines = coarse.text.splitlines()
start = text_lines.index("*FRICTION") + 1
data_lines = [line for line in text_lines[start:] if line.strip() and not line.startswith("*")]
table = np.array([[float(x) for x in line.split(",")] for line in data_lines])
mu_rows, p_rows = table[:, 0], table[:, 2] * 1e6  # MPa -> Pa

p = np.linspace(0.005e6, 0.55e6, 2000)
mu_law = fit.predict(p=p, warn=False)
mu_file = np.interp(p, p_rows, mu_rows)
inside = (p >= p_rows[0]) & (p <= p_rows[-1])
err = np.abs(mu_file - mu_law)
print(f"largest error inside the box: {err[inside].max():.3f} at p = "
      f"{p[inside][np.argmax(err[inside])] / 1e6:.4f} MPa")
print(f"the exporter reported:        {coarse.max_error:.3f} at p = "
      f"{coarse.error_at['p']:.4f} MPa")

fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(8, 5.6), sharex=True, layout="constrained")
ax1.plot(p / 1e6, mu_law, color="k", lw=1.5, label="thirion (fitted)")
ax1.plot(p / 1e6, mu_file, color="C3", lw=1.5, label="Abaqus table, 6 rows (as interpolated)")
ax1.plot(p_rows / 1e6, mu_rows, "o", color="C3")
ax1.set_ylabel("μ [–]")
ax1.legend(fontsize="small")
ax2.plot(p / 1e6, err, color="C3")
ax2.set_ylabel("|μ_table − μ_law|")
ax2.set_xlabel("contact pressure p [MPa]")
for ax in (ax1, ax2):
    ax.axvspan(p[0] / 1e6, p_rows[0] / 1e6, color="0.9", zorder=0)
    ax.axvspan(p_rows[-1] / 1e6, p[-1] / 1e6, color="0.9", zorder=0)
    ax.grid(alpha=0.3)
plt.show()

# %%
# Where the rows go matters more than how many
# --------------------------------------------
# Thirion's law is steep at low pressure. Rows evenly spaced in p waste most of the table
# where μ hardly changes; rows spaced evenly in log p follow the curvature. The error falls
# with the square of the number of rows in both cases, but from very different levels.
counts = [3, 5, 9, 17, 33, 65]
box = {"p": ("0.01 MPa", "0.5 MPa")}
errors = {"lin": [], "log": []}
for n in counts:
    for spacing in errors:
        res = export(None, fit, "csv", {"p": (*box["p"], n)}, spacing={"p": spacing})
        errors[spacing].append(res.max_error)
fig, ax = plt.subplots(figsize=(6.5, 4), layout="constrained")
for spacing, values in errors.items():
    ax.loglog(counts, values, "o-", label=f"{spacing} spacing")
ax.loglog(counts, errors["lin"][0] * (np.array(counts) / counts[0]) ** -2.0, "k:",
          label="∝ rows⁻²")
ax.axhline(1e-3, color="C2", ls="--", label="tol = 0.001")
ax.set_xticks(counts, [str(n) for n in counts])
ax.minorticks_off()
ax.set_xlabel("table rows")
ax.set_ylabel("largest interpolation error in μ")
ax.grid(alpha=0.3, which="both")
ax.legend(fontsize="small")
plt.show()

# With a tolerance the exporter places the rows itself, refining where the error is largest.
# For the same guarantee (0.001 in μ everywhere in the box), compare with the smallest evenly
# spaced tables:
adaptive = export(None, fit, "abaqus", box, units="mm-N-s", tol=1e-3)
print(f"adaptive:            {adaptive.rows:>4} rows, largest error {adaptive.max_error:.5f}")
law_function = fit.law.bind(fit.values)
for spacing in ("lin", "log"):
    grid, error = uniform_grid_for_tol(law_function, [AxisSpec("p", 0.01e6, 0.5e6, None)],
                                       1e-3, spacing=spacing)
    print(f"evenly spaced ({spacing}): {grid.rows:>4} rows, largest error {error.max_abs:.5f}")

# %%
# Two variables: a velocity bell on an adaptive grid
# --------------------------------------------------
# A Savkoor law (a bell in log velocity times a pressure power) over 0.02 to 0.5 MPa and
# 0.01 mm/s to 10 m/s, with ``tol = 0.002``. The exporter chooses log spacing in velocity,
# refines until the error is below the tolerance everywhere, and reports the grid. The map
# shows the error of the solver's bilinear interpolation; the white marks along the axes
# are the breakpoints.
law = fl.get_law("savkoor")
values = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": -0.2}
bell = export(law, values, "abaqus",
              {"p": ("0.02 MPa", "0.5 MPa"), "v": ("1e-5 m/s", "10 m/s")},
              units="mm-N-s", tol=2e-3)
print(bell.report())

grid = bell.grid
table_values = law.evaluate(dict(zip(grid.names, np.meshgrid(*grid.points, indexing="ij"))),
                            law.resolve(values))
pp, vv = np.meshgrid(np.linspace(0.02e6, 0.5e6, 240), np.geomspace(1e-5, 10.0, 240))
query = [{"p": pp, "v": vv}[name].ravel() for name in grid.names]
mu_grid = interpolate(grid.points, table_values, query).reshape(pp.shape)
error_map = np.abs(mu_grid - law(p=pp, v=vv, **values))
fig, ax = plt.subplots(figsize=(8, 4.6), layout="constrained")
mesh = ax.pcolormesh(pp / 1e6, vv, error_map, cmap="viridis", shading="auto")
fig.colorbar(mesh, ax=ax, label="|μ_table − μ_law|")
# the breakpoints, as rug marks along the axes
ax.plot(np.full(grid.axis("v").size, 0.02), grid.axis("v"), "_", color="w", ms=8)
ax.plot(grid.axis("p") / 1e6, np.full(grid.axis("p").size, 1.2e-5), "|", color="w", ms=8)
ax.set_yscale("log")
ax.set_xlabel("contact pressure p [MPa]")
ax.set_ylabel("sliding velocity v [m/s]")
ax.set_title(f"{bell.rows} rows ({' x '.join(map(str, grid.shape))}); "
             f"largest error {bell.max_error:.4f}")
plt.show()

# %%
# A solver without tables
# -----------------------
# OpenRadioss has no μ(p, v) tables, only fixed forms. Exporting the bell to its quadratic
# Ifric 1 law means fitting that form over the box, and the file says how far the
# approximation strays: here far too much to be used, which is the point of stating it.
radioss = export(law, values, "radioss",
                 {"p": ("0.02 MPa", "0.5 MPa"), "v": ("1e-3 m/s", "1 m/s")}, units="mm-N-s")
print(radioss.report())

# The gallery thumbnail: figure 2 of this example.
# sphinx_gallery_thumbnail_number = 2
