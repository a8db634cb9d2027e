r"""
Friction predicted from the rubber and the road: Persson's theory
=================================================================

The laws of the registry describe friction once it has been measured. Persson's theory
predicts the viscoelastic part of it from two things that can be measured without a
tribometer: the rubber's complex modulus :math:`E(\omega, T)` and the road's roughness power
spectrum :math:`C(q)`,

.. math::

    \mu = \frac{1}{2}\int_{q_0}^{q_1} q^3 C(q) P(q) \int_0^{2\pi} \cos\phi\,
          \frac{\operatorname{Im} E(q v \cos\phi, T)}{(1-\nu^2)\,\sigma_0}\,d\phi\,dq,
    \qquad P(q) = \operatorname{erf}\frac{1}{2\sqrt{G(q)}}

(Persson, J. Chem. Phys. 115 (2001) 3840; Persson et al., J. Phys.: Condens. Matter 17
(2005) R1). This example goes from DMA sweeps to a friction table for an FE code:
master curve, Prony series, :math:`\mu(v, T)` on an asphalt-like surface, a Savkoor law
fitted to it, and an Abaqus table.
"""

# %%
# DMA sweeps -> master curve -> Prony series
# ------------------------------------------
# The packaged DMA sweeps (21 temperatures, 0.1..100 Hz) are shifted into a master curve at
# the sweep nearest 20 °C; a Prony series with non-negative terms, one per decade, is fitted
# to storage and loss modulus together (``scipy.optimize.nnls``).
import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl
from frictionlaws.persson import asphalt_like, friction, material_from_master_curve
from frictionlaws.viscoelastic.mastercurve import build_master_curve, load_dma_example

d = load_dma_example()
mc = build_master_curve(d["f"], np.column_stack([d["E_stor"], d["E_loss"]]), d["T"],
                        groups=d["set"], T_ref=293.15, y_names=["E_stor", "E_loss"],
                        x_name="f", fit=False)
mat = material_from_master_curve(mc)
pts = mc.points()
w = np.logspace(-19, 4, 300)
E = mat.modulus(2 * np.pi * w)
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
ax.loglog(pts["x_reduced"], pts["E_stor"], ".", ms=3, color="C0", label="E' (shifted sweeps)")
ax.loglog(pts["x_reduced"], pts["E_loss"], ".", ms=3, color="C1", label="E'' (shifted sweeps)")
ax.loglog(w, E.real, color="C0", label=f"Prony series, {mat.E_i.size} terms")
ax.loglog(w, E.imag, color="C1")
ax.set_xlabel(f"reduced frequency a_T f [Hz] (T_ref = {mc.T_ref - 273.15:.1f} °C)")
ax.set_ylabel("modulus [Pa]")
ax.set_title(f"master curve and Prony fit (rms relative misfit {mat.rms_rel:.3f})")
ax.legend(fontsize=8)

# %%
# Persson's mu(v, T) on an asphalt-like surface
# ---------------------------------------------
# A self-affine surface with roll-off at 1 cm (q0 = 628 1/m), Hurst exponent 0.8 and rms
# height 0.3 mm, cut off at q1 = 1e6 1/m; nominal pressure 0.2 MPa. 100 velocities take
# a few milliseconds. Warming the rubber moves the curve to higher speed by the measured
# shift factor a_T.
surf = asphalt_like(1e6)
v = np.logspace(-8, 2, 100)
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for T in (273.15, 293.15, 323.15):
    ax.semilogx(v, friction(mat, surf, v, T, 2e5), label=f"T = {T - 273.15:.0f} °C")
ax.set_xlabel("sliding velocity v [m/s]")
ax.set_ylabel("viscoelastic friction coefficient [-]")
ax.set_title("Persson: packaged DMA polymer on an asphalt-like surface, p = 0.2 MPa")
ax.legend()

# %%
# The registry law and an empirical law fitted to it
# --------------------------------------------------
# The registry law ``persson`` is the same theory for the packaged tread compound
# (``datasets/tread-compound``, see :doc:`/user-guide/persson`); its free parameters are q1
# and an additive mu_a. A Savkoor bell, fitted to the Persson curve at 20 °C over the
# velocities of a tyre, shows how far an empirical law can stand in for the theory.
law = fl.get_law("persson")
vv = np.logspace(-6, 1, 60)
p = np.full(vv.size, 2e5)
mu_p = law(p=p, v=vv, T=np.full(vv.size, 293.15), preset="tread-on-asphalt")
sav = fl.fit("savkoor", {"p": p, "v": vv, "mu": mu_p}, fix={"n": 0.0})
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
ax.semilogx(vv, mu_p, "o", ms=3, label="Persson (law 'persson', tread compound)")
ax.semilogx(vv, sav.law.evaluate({"p": p, "v": vv}, sav.values), label=(
    f"Savkoor fitted: RMSE {sav.metrics['rmse']:.4f}"))
ax.set_xlabel("sliding velocity v [m/s]")
ax.set_ylabel("friction coefficient [-]")
ax.legend()
print(sav.report())

# %%
# An FE table
# -----------
# Persson's law has no closed form, so there is no Fortran user subroutine; the table
# formats work like for any law. Here an Abaqus ``*FRICTION`` table in v and T at
# 0.2 MPa, with its interpolation error stated in the header.
import tempfile  # noqa: E402
from pathlib import Path  # noqa: E402

from frictionlaws.cli import main  # noqa: E402

out = Path(tempfile.mkdtemp()) / "persson.inp"
main(["export", "--law", "persson", "--preset", "tread-on-asphalt", "--format", "abaqus",
      "--p", "0.2MPa:0.2MPa:1", "--v", "1e-4:1:13", "--T", "0degC:40degC:5", "-o", str(out)])
print("\n".join(out.read_text().splitlines()[:8]))

# The gallery thumbnail: figure 2 of this example.
# sphinx_gallery_thumbnail_number = 2
