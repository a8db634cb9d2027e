"""Synthetic campaigns: recovery of the known mu and coverage of the 95 % intervals."""

from __future__ import annotations

import numpy as np
import pytest

from frictionlaws.tribometer import process_records
from frictionlaws.tribometer.rig import RPM
from frictionlaws.tribometer.synthetic import (
    THESIS_GROUPS,
    ConditionSpec,
    RecordSpec,
    campaign_records,
    generate_record,
    internal_torque_truth,
    synthetic_rig,
    thesis_conditions,
)

#: Short, 500 Hz records keep the many-condition tests fast.
FAST = {"duration": 12.0, "fs": 500.0, "t_second": 0.5}
SPEEDS = [(331.0, 0.0), (331.0, -120.0), (0.0, 331.0), (663.0, -120.0), (331.0, 500.0)]


def random_conditions(seed: int, n: int, repeat_sd: float) -> list[ConditionSpec]:
    """Conditions over the thesis' range: speeds, loads 1..8 kg, 3..7 repeats, some abrasive."""
    rng = np.random.default_rng(seed)
    out = []
    for i in range(n):
        disc, pin = SPEEDS[rng.integers(len(SPEEDS))]
        load = float(rng.choice([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0]))
        mu_max = min(3.5, 15.0 / load)  # keep the start-up peak inside the 10 N m sensor
        mode = "initial" if rng.random() < 0.2 else "steady"
        out.append(ConditionSpec(f"c{i:03d}", "steel", load, float(rng.uniform(0.6, mu_max)),
                                 int(rng.integers(3, 8)), disc, pin, mode, repeat_sd))
    return out


def test_generator_phases_and_offsets():
    rig = synthetic_rig()
    spec = RecordSpec(mu=1.5, load=29.4, disc_rpm=331.0, pin_rpm=-120.0, noise=0.0, hum=0.0,
                      vibration=0.0, ripple=0.0, speed_noise=0.0)
    rec = generate_record(spec, rig, 0)
    t = rec.time
    offset = rig.system_error + rig.internal_torque(rec.disc_speed)
    friction = rec.torque - offset
    assert np.allclose(friction[t < spec.t_start], 0.0)  # loading: offsets only
    full = spec.t_start + spec.t_second + spec.ramp
    assert friction[np.searchsorted(t, full)] == pytest.approx(1.5 * 29.4 * 0.04 * 1.4)  # peak
    steady = (t > full + 8) & (t < spec.t_stop - spec.t_second - spec.ramp)
    np.testing.assert_allclose(friction[steady], 1.5 * 29.4 * 0.04, rtol=1e-3)
    assert np.allclose(friction[t > spec.t_stop + spec.ramp], 0.0)  # motors off
    pre = (t > spec.t_start + spec.ramp) & (t < spec.t_start + spec.t_second)
    np.testing.assert_allclose(friction[pre], 0.2 * 1.5 * 29.4 * 0.04)  # disc alone
    np.testing.assert_allclose(rec.disc_speed[steady], 331 * RPM)
    np.testing.assert_allclose(rec.pin_speed[steady], -120 * RPM)
    # disturbances: hum and vibration appear in the spectrum where they were put
    noisy = generate_record(RecordSpec(mu=1.5, load=29.4, hum=0.05, vibration=0.08,
                                       vib_freq=31.0), rig, 1)
    f = np.fft.rfftfreq(noisy.torque.size, 1 / noisy.fs)
    amp = np.abs(np.fft.rfft(noisy.torque - noisy.torque.mean()))
    for freq in (50.0, 31.0):
        band = np.abs(f - freq) < 0.5
        assert amp[band].max() > 20 * np.median(amp[(f > 60) & (f < 400)])


def test_generator_initial_mode_decays_and_saturation_clips():
    rig = synthetic_rig()
    spec = RecordSpec(mu=1.0, load=29.4, mode="initial", noise=0.0, hum=0.0, vibration=0.0,
                      ripple=0.0)
    rec = generate_record(spec, rig, 0)
    friction = rec.torque - rig.system_error - rig.internal_torque(rec.disc_speed)
    late = rec.time > spec.t_stop - 1.0
    assert friction[late].max() < 0.8 * 29.4 * 0.04  # debris: the reading decays
    sat = generate_record(RecordSpec(mu=40.0, load=29.4), rig, 0)
    assert sat.torque.max() == pytest.approx(rig.torque_range)


def test_thesis_campaign_has_the_thesis_record_counts():
    conds = thesis_conditions(seed=3)
    assert sum(c.repeats for c in conds) == 843
    for label, surface, count, _, _, mode, _ in THESIS_GROUPS:
        group = [c for c in conds if c.name.startswith(label + " ")]
        assert sum(c.repeats for c in group) == count, label
        lo, hi = (2, 3) if mode == "initial" else (3, 7)
        assert all(lo <= c.repeats <= hi and c.surface == surface for c in group)


def test_recovery_within_2_percent_per_condition():
    """Across the thesis' test types, each condition's mean is within 2 % of the true mu."""
    rig = synthetic_rig()
    conds = random_conditions(seed=5, n=40, repeat_sd=0.01)
    records, rows, truth = campaign_records(conds, rig, seed=5, record_kwargs=FAST)
    camp = process_records(records, rows, rig)
    assert not camp.unusable, [r.reason for r in camp.unusable]
    true_mu = truth.condition_mu()
    errors = np.array([c.mu / true_mu[c.condition] - 1 for c in camp.conditions])
    assert len(errors) == 40
    assert np.abs(errors).max() < 0.02
    rec_mu = truth.record_mu()
    rec_err = np.array([r.mu / rec_mu[r.file] - 1 for r in camp.records if r.usable])
    assert np.abs(rec_err).max() < 0.01  # each record's own value, tighter still
    assert abs(rec_err.mean()) < 0.002  # no systematic bias from the window or offsets


@pytest.mark.slow
def test_confidence_intervals_cover_the_true_mu_at_the_stated_rate():
    """200 conditions with 3 % repeat-to-repeat scatter: the 95 % intervals cover ~95 %."""
    rig = synthetic_rig()
    conds = random_conditions(seed=2024, n=200, repeat_sd=0.03)
    records, rows, truth = campaign_records(conds, rig, seed=2024, record_kwargs=FAST)
    camp = process_records(records, rows, rig)
    assert not camp.unusable, [r.reason for r in camp.unusable][:5]
    true_mu = truth.condition_mu()
    written = [c for c in camp.conditions if c.written]
    assert len(written) == 200
    covered = np.array([c.ci95[0] <= true_mu[c.condition] <= c.ci95[1] for c in written])
    coverage = covered.mean()
    print(f"95 % CI coverage over {len(written)} conditions: {coverage:.3f}")
    assert 0.90 <= coverage <= 0.99
    # the intervals are honest in width too: |error| / half-width behaves like |t| / t_crit
    errors = np.array([c.mu / true_mu[c.condition] - 1 for c in written])
    assert abs(errors.mean()) < 3 * errors.std() / np.sqrt(errors.size)


def test_intervals_without_repeat_scatter_are_narrow_but_still_cover():
    """With no repeat scatter the record means agree closely; the interval shrinks with them."""
    rig = synthetic_rig()
    conds = [ConditionSpec(f"c{i}", "steel", 3.0, 1.5, 5, 331.0, 0.0, repeat_sd=0.0)
             for i in range(4)]
    records, rows, _ = campaign_records(conds, rig, seed=9, record_kwargs=FAST)
    camp = process_records(records, rows, rig)
    for c in camp.conditions:
        assert c.ci95[1] - c.ci95[0] < 0.01 * c.mu
        assert abs(c.mu / 1.5 - 1) < 0.003


def test_internal_torque_truth_shape():
    rpm = np.array([0.0, 150.0, 331.0, 663.0])
    tq = internal_torque_truth(rpm)
    assert tq[1] < tq[0] and tq[1] < tq[3]  # dips after start-up, rises near top speed
