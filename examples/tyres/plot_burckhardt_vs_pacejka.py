"""
Burckhardt road presets against Pacejka presets
===============================================

Two slip laws are used for tyre-road friction in vehicle dynamics: Burckhardt's
exponential form, with published coefficients for a range of road surfaces, and Pacejka's
Magic Formula, here in its normalised longitudinal form with the generic dry, wet, snow and
ice coefficients. Both give the friction coefficient as a function of the braking slip
ratio s. This example puts the presets side by side, compares their peaks, and converts one
into the other by fitting.
"""

# %%
# Four surfaces, two laws
# -----------------------
# The Burckhardt presets are evaluated at v = 0 (their velocity factor ``exp(-c4 v)`` is 1
# there; the presets leave ``c4`` at 0). Dots mark each curve's peak.
import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl

pacejka = fl.get_law("pacejka")
burckhardt = fl.get_law("burckhardt")
s = np.linspace(0.0, 1.0, 400)
pairs = [("dry", "asphalt-dry"), ("wet", "asphalt-wet"), ("snow", "snow"), ("ice", "ice")]

fig, axes = plt.subplots(2, 2, figsize=(10, 7), sharex=True, layout="constrained")
for ax, (pj, bk) in zip(axes.flat, pairs):
    for law, preset, color in ((pacejka, pj, "C0"), (burckhardt, bk, "C3")):
        values = law.resolve(preset=preset)
        variables = {"s": s, "v": np.zeros_like(s)}
        mu = law.evaluate({k: variables[k] for k in law.variables}, values)
        peak = law.derived_values(values)
        ax.plot(s, mu, color=color, lw=2, label=f"{law.id} '{preset}'")
        ax.plot(peak["s_peak"], peak["mu_peak"], "o", color=color)
    ax.set_title(pj)
    ax.set_ylim(bottom=0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", loc="lower right")
for ax in axes[1]:
    ax.set_xlabel("slip ratio s [–]")
for ax in axes[:, 0]:
    ax.set_ylabel("μ [–]")
plt.show()

# %%
# Peaks and locked-wheel friction
# -------------------------------
# The derived quantities are computed from each law's declaration (the peak of Burckhardt's
# law has a closed form; Pacejka's is found numerically on s = 0..1).
print(f"{'surface':<8}{'law':<12}{'preset':<13}{'s_peak':>8}{'mu_peak':>9}{'mu(s=1)':>9}")
for pj, bk in pairs:
    for law, preset in ((pacejka, pj), (burckhardt, bk)):
        values = law.resolve(preset=preset)
        d = law.derived_values(values)
        locked = law.evaluate({k: np.float64(1.0 if k == "s" else 0.0) for k in law.variables},
                              values)
        print(f"{pj:<8}{law.id:<12}{preset:<13}{d['s_peak']:>8.3f}{d['mu_peak']:>9.3f}"
              f"{locked:>9.3f}")

# %%
# All Burckhardt roads
# --------------------
# Burckhardt's set is wider than Pacejka's four: cobblestones reach their peak only at
# 40 % slip, ice has no peak at all (its coefficient c3 is 0, so μ rises to 0.05 and stays).
fig, ax = plt.subplots(figsize=(7.5, 4), layout="constrained")
for preset in burckhardt.presets:
    ax.plot(s, burckhardt(s=s, v=np.zeros_like(s), preset=preset), lw=2, label=preset)
ax.set_xlabel("slip ratio s [–]")
ax.set_ylabel("μ [–]")
ax.grid(alpha=0.3)
ax.legend(fontsize="small", loc="center left", bbox_to_anchor=(1.01, 0.5))
plt.show()

# %%
# Converting by fitting
# ---------------------
# A Magic Formula for a road that only has Burckhardt coefficients: sample the Burckhardt
# curve and fit Pacejka's law to it. The fit takes a plain mapping of SI arrays.
# ``S_h`` and ``S_v`` (shifts) are held at zero.
s_fit = np.linspace(0.0, 1.0, 51)
samples = {"s": s_fit, "mu": burckhardt(s=s_fit, v=np.zeros_like(s_fit),
                                        preset="cobblestone-dry")}
converted = fl.fit("pacejka", samples, fix={"S_h": 0.0, "S_v": 0.0})
print(converted.report())

fig, ax = plt.subplots(figsize=(6.5, 3.8), layout="constrained")
ax.plot(samples["s"], samples["mu"], "o", ms=4, color="C3",
        label="burckhardt 'cobblestone-dry' (samples)")
ax.plot(s, converted.predict(s=s), color="C0", lw=2,
        label=f"pacejka fitted (RMSE {converted.metrics['rmse']:.3f})")
ax.set_xlabel("slip ratio s [–]")
ax.set_ylabel("μ [–]")
ax.grid(alpha=0.3)
ax.legend(fontsize="small")
plt.show()

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
