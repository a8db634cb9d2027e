"""
Every sliding law fitted to the thesis steel data
=================================================

The packaged dataset ``thesis-steel`` holds the 19 friction coefficients the thesis
prints for a tread-rubber pin on a steel disc: eight pressures with the disc at rest,
ten at 1.38 m/s and one at 2.77 m/s. Here every registered sliding-velocity law is fitted
to it with the same call, and the fits are drawn side by side.

Two things to watch: laws with a logarithm or a negative power of the velocity cannot
use the eight rows at v = 0. By default the fitter stops and names such rows; here
``on_invalid="drop"`` asks it to fit the remaining 11 and say which rows it dropped. And a
law with more parameters than the data can support is flagged with the parameters it
cannot determine.
"""

# %%
# Load the data and fit every law
# -------------------------------
# The list of laws comes from the registry, so a new sliding law appears here without
# editing this example. Laws whose variables the data lack (the temperature-dependent
# Park law needs ``T``) are reported and skipped.
import warnings

import matplotlib.pyplot as plt

import frictionlaws as fl
from frictionlaws.base.errors import DomainError
from frictionlaws.comparison.plotting import plot_fit_grid

data = fl.load_dataset("thesis-steel")
print(data)

results = {}
for law in fl.list_laws("sliding"):
    try:
        law.require_variables(data.variables)
    except DomainError as exc:
        print(f"skipped {law.id}:\n    {exc}")
        continue
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the warnings are kept in result.warnings
        results[law.id] = fl.fit(law, data, on_invalid="drop")
print(f"fitted {len(results)} laws")

# %%
# One panel per law
# -----------------
# Each panel shows the measured points (coloured by disc velocity) and the fitted law at
# the velocities it was fitted on; open circles are rows a law could not use (v = 0 for the
# log-velocity laws), and no curve is drawn there. A red title marks a fit with parameters
# the data cannot determine. :func:`frictionlaws.comparison.plotting.plot_fit_grid` draws the grid.
fig = plot_fit_grid(results, data, x="p", by="v")
fig.axes[0].set_ylim(0, 4.5)
plt.show()

# %%
# The numbers
# -----------
# R² and RMSE are on the rows each law was fitted to; AICc compares laws fitted to the
# same rows only (the log-velocity laws saw 11 rows, the others 19).
print(f"{'law':<20}{'n':>4}{'k':>4}{'R²':>9}{'RMSE':>9}{'AICc':>9}  not identifiable")
for law_id, res in results.items():
    m = res.metrics
    print(f"{law_id:<20}{m['n']:>4}{m['k']:>4}{m['r2']:>9.3f}{m['rmse']:>9.3f}"
          f"{m['aicc']:>9.1f}  {', '.join(res.non_identifiable) or '-'}")

# %%
# What the comparison says
# ------------------------
# The pressure-saturation laws (Thirion, Denny) follow the fall of μ with pressure with
# two parameters. The polynomial and quadratic forms fit a little better in R² but
# spend more parameters and turn at the edges. With only three velocity levels (and one
# point at the highest) the velocity-dependent laws are not determined: the fitter
# names the parameters it cannot separate instead of printing meaningless errors.
# Wriggers' law has no static friction (μ = 0 at v = 0), so it cannot follow the eight rows
# measured with the disc at rest, hence its negative R². The full report of any fit says
# what it could and could not determine in words:
print(results["nackenhorst"].report())

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
