"""
Processing a raw tribometer record
==================================

A pin-on-disc tribometer logs the torque on the disc shaft, not a friction coefficient. One
test record goes through phases: the pin is loaded with the motors off, the motor starts,
a start-up peak decays, the pin slides steadily, the motor stops. Between the raw reading
and a friction coefficient lie a filter, two offsets (a constant system error and an
internal torque that depends on disc speed), the lever arm of the pin track, the normal
load, and the choice of the steady window.

This example builds a synthetic record with a known coefficient, processes it with
:mod:`frictionlaws.tribometer`, and checks that the known value comes back. Then a small
campaign of repeated records becomes a dataset with confidence intervals, and a law is
fitted to it.
"""

# %%
# A synthetic record with a known coefficient
# -------------------------------------------
# The rig is the thesis' rig (40 mm track radius, 20 mm pin, 0.3 N m system error, 10 N m
# sensor). The record: a 3 kg dead weight, the disc at 331 rpm (5 km/h at the track
# radius), true mu = 1.30, with sensor noise, 50 Hz mains hum, a rig vibration at 37 Hz
# and a ripple once per revolution.
import matplotlib.pyplot as plt
import numpy as np

import frictionlaws as fl
from frictionlaws.tribometer import process_record, process_records
from frictionlaws.tribometer.process import manifest_from_rows
from frictionlaws.tribometer.signal import spectrum
from frictionlaws.tribometer.synthetic import (
    ConditionSpec,
    RecordSpec,
    campaign_records,
    generate_record,
    synthetic_rig,
)

rig = synthetic_rig()
MU_TRUE = 1.30
spec = RecordSpec(mu=MU_TRUE, load=3.0 * rig.g, disc_rpm=331.0)
record = generate_record(spec, rig, rng=7, source="steel_3kg_01.csv")
print(f"{len(record)} samples at {record.fs:g} Hz, {record.duration:.1f} s")

# %%
# Process it
# ----------
# The manifest row gives the load as a dead weight in kg (turned into newtons with the
# rig's g). ``process_record`` low-pass filters the torque (zero phase, cut-off chosen from
# the spectrum), subtracts the offsets, divides by the track radius and the load, finds the
# steady window and averages over it.
entries, notes = manifest_from_rows(
    [{"file": "steel_3kg_01.csv", "load [kg]": 3, "surface": "steel"}], rig)
result, signals = process_record(record, entries[0], rig, keep_signals=True)
print(f"status: {result.status}")
print(f"mu = {result.mu:.4f} (true {MU_TRUE}); error {100 * (result.mu / MU_TRUE - 1):+.2f} %")
print(f"window {result.window_start:.2f} .. {result.window_end:.2f} s ({result.window_source}); "
      f"cut-off {result.cutoff:.1f} Hz ({result.cutoff_source})")
print(f"p = {result.p / 1e6:.4f} MPa, v = {result.v:.3f} m/s, s = {result.s:.2f}")

# %%
# What happened to the signal
# ---------------------------
# Top: the raw reading and the filtered one, in N m, with the offsets still in. Bottom: the
# friction coefficient after the offsets are removed; the window the processing chose is
# shaded and the known coefficient is the dashed line.
t = signals.time
fig, (ax1, ax2) = plt.subplots(2, 1, figsize=(10, 6), sharex=True, layout="constrained")
ax1.plot(t, signals.raw, color="0.7", lw=0.5, label="raw reading")
ax1.plot(t, signals.filtered, color="C0", lw=1.2, label="filtered")
ax1.set_ylabel("torque [N m]")
ax1.legend(fontsize="small", loc="upper right")
ax2.plot(t, signals.mu, color="C0", lw=1.2, label="μ(t) after offsets")
ax2.axhline(MU_TRUE, color="k", ls="--", lw=1, label=f"true μ = {MU_TRUE}")
ax2.axvspan(result.window_start, result.window_end, color="C2", alpha=0.2,
            label=f"steady window: μ = {result.mu:.3f}")
ax2.set_ylim(-0.3, 2.2)
ax2.set_xlabel("time [s]")
ax2.set_ylabel("μ [–]")
ax2.legend(fontsize="small", loc="upper right")
for ax in (ax1, ax2):
    ax.grid(alpha=0.3)
plt.show()

# %%
# Why that cut-off
# ----------------
# The power spectrum of the raw reading shows the ripple once per disc revolution (5.5 Hz
# at 331 rpm), the rig vibration and the mains hum standing above the noise floor; the
# automatic cut-off sits below all three. What passes is the slow evolution of friction
# (the start-up peak, the steady level) that the window average needs.
freq, power = spectrum(record.torque, record.fs)
fig, ax = plt.subplots(figsize=(8, 3.4), layout="constrained")
ax.semilogy(freq, power, color="C0", lw=0.8)
ax.axvline(result.cutoff, color="C3", ls="--", label=f"cut-off {result.cutoff:.1f} Hz")
ripple_hz = 331.0 / 60.0
for f0, name in ((ripple_hz, "once per revolution"), (spec.vib_freq, "rig vibration"),
                 (spec.hum_freq, "mains hum")):
    ax.annotate(name, (f0, power[np.argmin(abs(freq - f0))]), xytext=(5, 10),
                textcoords="offset points", fontsize=8)
ax.set_xlim(0, 120)
ax.set_xlabel("frequency [Hz]")
ax.set_ylabel("power spectral density")
ax.legend(fontsize="small")
ax.grid(alpha=0.3)
plt.show()

# %%
# From repeated records to a dataset
# ----------------------------------
# Five loads, four repeats each, with 2 % scatter from repeat to repeat. The true
# coefficient follows Thirion's law with a = 0.15 and b = 4.7e-6 1/Pa (close to the thesis'
# steel data). ``process_records`` processes the records in memory, averages each
# condition, gives the standard deviation and the 95 % Student-t interval, and drops
# outliers: a record far from its condition's median in units of the record-to-record
# scatter pooled over the campaign (the summary prints the rule used).
A_TRUE, B_TRUE = 0.15, 4.7e-6
truth_mu = {kg: 1.0 / (A_TRUE + B_TRUE * kg * rig.g / rig.contact_area)
            for kg in (1.0, 2.0, 3.0, 5.0, 8.0)}
conditions = [ConditionSpec(f"steel {kg:g} kg", "steel", kg, mu, repeats=4,
                            disc_rpm=331.0) for kg, mu in truth_mu.items()]
records, manifest, truth = campaign_records(conditions, rig, seed=3,
                                            record_kwargs={"duration": 16.0})
campaign = process_records(records, manifest, rig)
print(campaign.summary())
table = campaign.dataset_frame()
print(table[["condition", "mu", "mu_std", "mu_ci95_low", "mu_ci95_high", "n", "p [MPa]"]]
      .to_string(index=False, float_format=lambda x: f"{x:.4g}"))

# %%
# ... and a law fitted to it
# --------------------------
# The dataset carries each condition's standard deviation and repeat count, so the fit
# weights the conditions by them. The true parameters should lie inside the fitted 95 %
# intervals.
dataset = campaign.dataset()
thirion = fl.fit("thirion", dataset)
print(thirion.report())
for name, true in (("a", A_TRUE), ("b", B_TRUE)):
    est = thirion.params[name]
    inside = est.ci95[0] <= true <= est.ci95[1]
    print(f"{name}: true {true:.4g}, fitted {est.value:.4g} "
          f"[{est.ci95[0]:.4g}, {est.ci95[1]:.4g}] -> {'inside' if inside else 'OUTSIDE'}")

p = np.linspace(0.02e6, 0.27e6, 200)
fig, ax = plt.subplots(figsize=(7, 4), layout="constrained")
ax.errorbar(table["p [MPa]"], table["mu"],
            yerr=[table["mu"] - table["mu_ci95_low"], table["mu_ci95_high"] - table["mu"]],
            fmt="o", color="C0", capsize=3, label="conditions (mean, 95 % interval)")
ax.plot([kg * rig.g / rig.contact_area / 1e6 for kg in truth_mu], list(truth_mu.values()),
        "x", color="k", ms=8, label="true μ of the conditions")
ax.plot(p / 1e6, thirion.predict(p=p, warn=False), color="C3", label="thirion fit")
ax.set_xlabel("contact pressure p [MPa]")
ax.set_ylabel("μ [–]")
ax.grid(alpha=0.3)
ax.legend(fontsize="small")
plt.show()

# The gallery thumbnail: figure 1 of this example.
# sphinx_gallery_thumbnail_number = 1
