"""Calibration helpers: system error from hanging weights, internal torque from no-contact runs."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.tribometer import (
    internal_torque_from_runs,
    load_rig,
    process_records,
    system_error_from_weights,
    write_record,
)
from frictionlaws.tribometer.records import Record
from frictionlaws.tribometer.rig import RPM
from frictionlaws.tribometer.synthetic import (
    ConditionSpec,
    campaign_records,
    hanging_weight_readings,
    internal_torque_truth,
    no_contact_run,
    synthetic_rig,
)

THESIS_MASSES = np.repeat([1.0, 2.0, 3.0, 4.0], 3)  # 1..4 kg, 3 repeats each


def test_system_error_recovered_with_an_interval_that_covers():
    covered = 0
    for seed in range(200):
        readings = hanging_weight_readings(THESIS_MASSES, system_error=0.3, noise=0.005,
                                           rng=seed)
        cal = system_error_from_weights(THESIS_MASSES, readings, radius="40 mm")
        assert cal.offset == pytest.approx(0.3, abs=0.01)
        covered += cal.ci95[0] <= 0.3 <= cal.ci95[1]
        assert not cal.warnings
    assert 0.90 <= covered / 200 <= 0.99
    assert cal.n == 12 and cal.slope == pytest.approx(1.0, abs=0.02)
    assert cal.to_toml() == f'system_error = "{cal.offset:.6g} N*m"'
    assert cal.apply(synthetic_rig()).system_error == cal.offset
    assert f"system error = {cal.offset:.4g} N m" in cal.report()


def test_system_error_units_and_gain_warning():
    grams = THESIS_MASSES * 1000
    readings = hanging_weight_readings(THESIS_MASSES, system_error=0.3, noise=0.001, rng=1)
    cal = system_error_from_weights(grams, readings * 100, radius=0.04, mass_unit="g",
                                    torque_unit="N*cm")
    assert cal.offset == pytest.approx(0.3, abs=0.005)
    skewed = hanging_weight_readings(THESIS_MASSES, system_error=0.3, noise=0.001, gain=1.08,
                                     rng=1)
    bad = system_error_from_weights(THESIS_MASSES, skewed, radius="40 mm")
    assert any("gain error" in w for w in bad.warnings)
    same = system_error_from_weights([2.0, 2.0, 2.0], [1.08, 1.085, 1.083], radius="40 mm")
    assert any("cannot be checked" in w for w in same.warnings)


@pytest.mark.parametrize("masses, readings, kwargs, match", [
    ([1, 2], [0.7], {}, "2 masses but 1 readings"),
    ([1], [0.7], {}, "at least 2"),
    ([1, -2], [0.7, 0.4], {}, "must be > 0"),
    ([1, np.nan], [0.7, 1.1], {}, "finite"),
    ([1, 2], [0.7, 1.1], {"mass_unit": "N"}, "not a mass unit"),
    ([1, 2], [0.7, 1.1], {"torque_unit": "N"}, "expected a torque"),
])
def test_system_error_bad_input(masses, readings, kwargs, match):
    with pytest.raises(InputError, match=match):
        system_error_from_weights(masses, readings, radius="40 mm", **kwargs)
    with pytest.raises(InputError, match="length"):
        system_error_from_weights([1, 2], [0.7, 1.1], radius="40 s")


def test_internal_torque_curve_from_four_runs(tmp_path):
    rig = synthetic_rig()
    runs = [no_contact_run(rig, rng=k) for k in range(4)]
    # one run goes through a CSV file, as a user would give it
    path = write_record(tmp_path / "run4.csv", runs[3])
    curve = internal_torque_from_runs(runs[:3] + [path], system_error=rig.system_error)
    assert curve.n_runs == 4
    assert np.all(np.diff(curve.speed_rpm) > 0)
    assert curve.runs.max() == 4
    truth = internal_torque_truth(curve.speed_rpm)
    assert np.max(np.abs(curve.torque - truth)) < 0.004
    assert curve(331.0) == pytest.approx(float(internal_torque_truth(331.0)), abs=0.003)
    # the table feeds a rig file and reads back
    text = 'track_radius = "40 mm"\npin_diameter = "20 mm"\nsystem_error = "0.3 N*m"\n' \
        + curve.to_toml()
    (tmp_path / "rig.toml").write_text(text)
    rig2 = load_rig(tmp_path / "rig.toml")
    assert rig2.internal_torque(331 * RPM) == pytest.approx(curve(331.0), rel=1e-5)
    assert curve.apply(rig).internal_torque(331 * RPM) == pytest.approx(curve(331.0))


def test_calibration_feeds_processing():
    """Offsets from the calibration helpers give the same mu as the true offsets."""
    true_rig = synthetic_rig()
    readings = hanging_weight_readings(THESIS_MASSES, system_error=0.3, noise=0.003, rng=4)
    cal = system_error_from_weights(THESIS_MASSES, readings, radius="40 mm")
    curve = internal_torque_from_runs([no_contact_run(true_rig, rng=k) for k in range(4)],
                                      system_error=cal.offset)
    calibrated = curve.apply(cal.apply(replace(true_rig, internal_speed=None,
                                               internal_torque_table=None)))
    conds = [ConditionSpec("steel 2 kg", "steel", 2.0, 1.9, 4, 663.0, -120.0, repeat_sd=0.01)]
    records, rows, _ = campaign_records(conds, true_rig, seed=3,
                                        record_kwargs={"duration": 15.0, "t_second": 1.0})
    ref = process_records(records, rows, true_rig).conditions[0].mu
    got = process_records(records, rows, calibrated).conditions[0].mu
    assert got == pytest.approx(ref, rel=0.005)
    # without the internal torque the offset error shows: mu too high
    raw = process_records(records, rows, replace(true_rig, internal_speed=None,
                                                 internal_torque_table=None))
    assert raw.conditions[0].mu > ref * 1.005


def test_internal_torque_bad_input():
    with pytest.raises(InputError, match="no no-contact runs"):
        internal_torque_from_runs([], system_error=0.3)
    short = Record(np.arange(10) / 1000, np.full(10, 0.4), np.full(10, 10.0))
    with pytest.raises(InputError, match="no speed bin"):
        internal_torque_from_runs([short], system_error=0.3)
