"""Tribometer processing: rig file, records, signal processing, statistics, campaigns, CLI."""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy import stats

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.io import load_dataset
from frictionlaws.tribometer import (
    grubbs,
    load_rig,
    process_campaign,
    process_records,
    read_record,
    student_interval,
    write_record,
)
from frictionlaws.tribometer.process import ManifestEntry, process_record
from frictionlaws.tribometer.records import Record
from frictionlaws.tribometer.rig import RPM
from frictionlaws.tribometer.signal import (
    NoWindow,
    auto_cutoff,
    find_window,
    lowpass,
    speed_segment,
)
from frictionlaws.tribometer.synthetic import (
    ConditionSpec,
    RecordSpec,
    campaign_records,
    generate_record,
    make_campaign,
    synthetic_rig,
)

RIG_TOML = """
track_radius = "40 mm"
pin_diameter = "20 mm"
system_error = "0.3 N*m"
g = "9.8 m/s^2"
torque_range = "10 N*m"

[internal_torque]
disc_speed_rpm = [0, 331, 663]
torque_Nm = [0.1, 0.05, 0.12]

[filter]
cutoff = "auto"
"""

#: Short records keep the tests fast (the benchmark runs the full-size campaign).
SHORT = {"duration": 15.0, "t_second": 1.0}


def write(tmp_path: Path, name: str, text: str) -> Path:
    p = tmp_path / name
    p.write_text(text, encoding="utf-8")
    return p


# --------------------------------------------------------------------------- rig
def test_rig_toml_with_units(tmp_path):
    rig = load_rig(write(tmp_path, "rig.toml", RIG_TOML))
    assert rig.track_radius == pytest.approx(0.040)
    assert rig.contact_area == pytest.approx(314.159e-6, rel=1e-5)
    assert rig.system_error == pytest.approx(0.3)
    assert rig.g == pytest.approx(9.8)
    assert rig.torque_range == pytest.approx(10.0)
    assert rig.filter.cutoff is None
    # internal torque interpolated at |disc speed| (rad/s), end values held
    assert rig.internal_torque(331 * RPM) == pytest.approx(0.05)
    assert rig.internal_torque(-497 * RPM) == pytest.approx(0.085)
    assert rig.internal_torque(1000 * RPM) == pytest.approx(0.12)


def test_rig_other_units_and_roundtrip(tmp_path):
    text = ('track_radius = "4 cm"\ncontact_area = "3.1416 cm^2"\nsystem_error = "300 N*mm"\n'
            'g = "9.81 m/s^2"\n[filter]\ncutoff = "20 Hz"\n[window]\nsettle = "500 ms"\n'
            'level_tolerance = 0.02\n[outliers]\nrule = "none"\n[grouping]\n'
            'speed_step = "1 rad/s"\n')
    rig = load_rig(write(tmp_path, "rig.toml", text))
    assert rig.track_radius == pytest.approx(0.04)
    assert rig.contact_area == pytest.approx(3.1416e-4)
    assert rig.system_error == pytest.approx(0.3)
    assert rig.filter.cutoff == pytest.approx(20.0)
    assert rig.window.settle == pytest.approx(0.5)
    assert rig.window.level_tolerance == pytest.approx(0.02)
    assert rig.outliers.rule == "none"
    assert rig.group_speed_step == pytest.approx(1.0)
    again = load_rig(write(tmp_path, "again.toml", rig.to_toml()))
    for name in ("track_radius", "contact_area", "system_error", "g", "group_speed_step"):
        assert getattr(again, name) == pytest.approx(getattr(rig, name))
    assert again.filter == rig.filter and again.window == rig.window
    synth = synthetic_rig()
    back = load_rig(write(tmp_path, "synth.toml", synth.to_toml()))
    np.testing.assert_allclose(back.internal_torque_table, synth.internal_torque_table)
    np.testing.assert_allclose(back.internal_speed, synth.internal_speed)


@pytest.mark.parametrize("text, match", [
    ('track_radius = "40 mm"\n', "pin_diameter"),
    ('track_radius = 40\npin_diameter = "20 mm"\n', "has no unit"),
    ('track_radius = "40 kg"\npin_diameter = "20 mm"\n', "expected a length"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\ncontact_area = "314 mm^2"\n',
     "not both"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\ntrack_raduis = "1 m"\n',
     "unknown key 'track_raduis'"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\ng = "9.8 m/s"\n', "expected an acceleration"),
    ('track_radius = "-40 mm"\npin_diameter = "20 mm"\n', "must be > 0"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\n[internal_torque]\n'
     'disc_speed_rpm = [0, 100]\ntorque_Nm = [0.1]\n', "same length"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\n[filter]\ncutoff = "20 s"\n',
     "expected a frequency"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\n[outliers]\nrule = "chauvenet"\n',
     "grubbs"),
    ('track_radius = "40 mm"\npin_diameter = "20 mm"\n[grouping]\nspeed_step = "10 Hz"\n',
     "ambiguous"),
    ('track_radius = "40 mm\n', "not valid TOML"),
])
def test_rig_errors_are_clear(tmp_path, text, match):
    path = write(tmp_path, "rig.toml", text)
    with pytest.raises(InputError, match=match) as err:
        load_rig(path)
    assert err.value.file == str(path)


def test_rig_missing_file(tmp_path):
    with pytest.raises(InputError, match="rig file not found"):
        load_rig(tmp_path / "nope.toml")


# --------------------------------------------------------------------------- records
def test_record_units_in_headers_convert_to_si(tmp_path):
    p = write(tmp_path, "r.csv", "# logger export\ntime [ms],torque [N*cm],disc_speed [rad/s],"
              "pin_speed [turn/min]\n0,100,2,-60\n1,150,2,-60\n2,120,2,-60\n3,110,2,-60\n")
    rec = read_record(p)
    np.testing.assert_allclose(rec.time, [0, 0.001, 0.002, 0.003])
    np.testing.assert_allclose(rec.torque, [1.0, 1.5, 1.2, 1.1])
    np.testing.assert_allclose(rec.disc_speed, 2.0)
    np.testing.assert_allclose(rec.pin_speed, -2 * np.pi)
    assert rec.fs == pytest.approx(1000.0)
    assert rec.units["torque"] == "N*cm"


@pytest.mark.parametrize("text, match, column, row", [
    ("time [s],torque [N m]\n0,1\n", "missing column disc_speed", None, None),
    ("time [s],force [N],disc_speed [rpm]\n0,1,2\n", "missing column torque", None, None),
    ("time [s],torque,disc_speed [rpm]\n0,1,2\n", "has no unit", "torque", None),
    ("time [s],torque [N],disc_speed [rpm]\n0,1,2\n", "expected a torque", "torque [N]", None),
    ("time [s],torque [N m],disc_speed [Hz]\n0,1,2\n", "ambiguous", "disc_speed [Hz]", None),
    ("time [s],torque [N m],disc_speed [blorps]\n0,1,2\n", "unknown unit", None, None),
    ("time [s],torque [N m],disc_speed [rpm]\n0,1,2\n0.001,,2\n0.002,1,2\n",
     "missing or non-numeric", "torque [N m]", 3),
    ("# c\ntime [s],torque [N m],disc_speed [rpm]\n0,1,2\n0.001,nan,2\n0.002,1,2\n",
     "missing or non-numeric", "torque [N m]", 4),
    ("time [s],torque [N m],disc_speed [rpm]\n0,1,2\n0.001,x1,2\n0.002,1,2\n",
     "non-numeric value 'x1'", "torque [N m]", 3),
    ("time [s],torque [N m],disc_speed [rpm]\n0,1,2\n0.002,1,2\n0.001,1,2\n",
     "not strictly increasing", "time [s]", 4),
    ("time [s],torque [N m],disc_speed [rpm]\n0,1,2\n0.001,1,2\n0.002,1,2\n0.01,1,2\n"
     "0.011,1,2\n", "irregular sampling", "time [s]", 5),
    ("time [s],torque [N m],disc_speed [rpm]\n", "no data rows", None, None),
    ("", "empty", None, None),
])
def test_bad_records_are_reported_with_file_column_row(tmp_path, text, match, column, row):
    p = write(tmp_path, "bad.csv", text)
    with pytest.raises(InputError, match=match) as err:
        read_record(p)
    assert err.value.file == str(p)
    if column is not None:
        assert err.value.column == column
    if row is not None:
        assert err.value.row == row


def test_write_record_roundtrip(tmp_path):
    rig = synthetic_rig()
    rec = generate_record(RecordSpec(mu=1.2, load=29.4, disc_rpm=331, pin_rpm=-120,
                                     duration=3.0), rig, 1)
    path = write_record(tmp_path / "r.csv", rec, torque_unit="N*cm", speed_unit="rad/s")
    assert path.read_text().splitlines()[0] == \
        "time [s],torque [N*cm],disc_speed [rad/s],pin_speed [rad/s]"
    back = read_record(path)
    np.testing.assert_allclose(back.time, rec.time, atol=1e-9)
    np.testing.assert_allclose(back.torque, rec.torque, atol=1e-5 * 100)
    np.testing.assert_allclose(back.disc_speed, rec.disc_speed, atol=0.01)
    np.testing.assert_allclose(back.pin_speed, rec.pin_speed, atol=0.01)


# --------------------------------------------------------------------------- signal
def test_lowpass_keeps_levels_and_removes_hum():
    fs = 1000.0
    t = np.arange(20000) / fs
    level = np.where((t > 5) & (t < 15), 2.0, 0.5)
    x = level + 0.2 * np.sin(2 * np.pi * 50 * t) + 0.1 * np.sin(2 * np.pi * 37 * t)
    y = lowpass(x, fs, 10.0)
    inner = (t > 7) & (t < 13)
    assert np.max(np.abs(y[inner] - 2.0)) < 2e-3  # hum and vibration gone, level kept
    assert np.mean(y[inner]) == pytest.approx(2.0, abs=1e-4)
    # zero phase: the step stays where it is
    assert abs(t[np.argmax(y > 1.25)] - 5.0) < 0.01
    with pytest.raises(InputError, match="Nyquist"):
        lowpass(x, fs, 600.0)


@given(c=st.floats(-100, 100), cutoff=st.floats(1.0, 200.0))
@settings(max_examples=30, deadline=None)
def test_lowpass_passes_constants(c, cutoff):
    y = lowpass(np.full(2000, c), 1000.0, cutoff)
    np.testing.assert_allclose(y, c, atol=1e-9 * max(1.0, abs(c)))


def test_auto_cutoff_stays_below_disturbances():
    rig = synthetic_rig()
    rec = generate_record(RecordSpec(mu=1.5, load=29.4, disc_rpm=331, vib_freq=23.0,
                                     hum_freq=50.0), rig, 3)
    info = auto_cutoff(rec.torque, rec.fs, rig.filter)
    assert any(abs(f - 23.0) < 1.0 for f in info.disturbances)
    assert any(abs(f - 50.0) < 1.0 for f in info.disturbances)
    assert rig.filter.auto_min <= info.cutoff <= 0.7 * 23.5
    # the filtered signal at that cut-off carries almost none of the 23 Hz vibration
    y = lowpass(rec.torque, rec.fs, info.cutoff)
    f = np.fft.rfftfreq(y.size, 1 / rec.fs)
    band = (f > 22) & (f < 24)
    assert np.abs(np.fft.rfft(y))[band].max() < 0.02 * np.abs(np.fft.rfft(rec.torque))[band].max()


def test_speed_segment_fixed_disc_and_two_motors():
    rig = synthetic_rig()
    spec = RecordSpec(mu=1.5, load=29.4, disc_rpm=0.0, pin_rpm=331.0, t_start=4, t_stop=26)
    rec = generate_record(spec, rig, 1)
    a, b, _ = speed_segment([rec.disc_speed, rec.pin()], 0.05)
    assert 4.0 < rec.time[a] < 4.6 and 25.4 < rec.time[b - 1] < 26.0
    spec = replace(spec, disc_rpm=331.0, pin_rpm=-120.0)
    rec = generate_record(spec, rig, 1)
    a, b, _ = speed_segment([rec.disc_speed, rec.pin()], 0.05)
    # both motors at speed: the pin starts 2 s after the disc and stops 2 s before it
    assert 6.0 < rec.time[a] < 6.6 and 23.4 < rec.time[b - 1] < 24.0
    with pytest.raises(NoWindow, match="no sliding"):
        speed_segment([np.zeros(100), np.zeros(100)], 0.05)


def test_find_window_after_peak_and_before_stop():
    fs = 1000.0
    t = np.arange(30000) / fs
    mu = np.where((t > 5) & (t < 25), 1.0 + 0.5 * np.exp(-np.maximum(t - 5, 0) / 0.8), 0.0)
    win = find_window(mu, fs, (5000, 25000), synthetic_rig().window)
    assert 8.5 < t[win.start] < 9.5  # peak decayed to 1 % (~8 s) + 0.5 s settle
    assert t[win.stop - 1] == pytest.approx(24.5, abs=0.01)  # end_margin before the stop
    assert np.mean(mu[win.slice()]) == pytest.approx(1.0, rel=2e-3)
    with pytest.raises(NoWindow, match="no steady window"):
        find_window(mu, fs, (5000, 7000), synthetic_rig().window)
    with pytest.raises(NoWindow, match="no friction"):
        find_window(-mu, fs, (5000, 25000), synthetic_rig().window)
    init = find_window(mu, fs, (5000, 25000), synthetic_rig().window, mode="initial")
    assert t[init.start] == pytest.approx(6.0) and t[init.stop] == pytest.approx(9.0)
    assert any("drifts" in n for n in init.notes)  # the peak is not over after 1 s


# --------------------------------------------------------------------------- statistics
def test_student_interval_matches_the_t_formula():
    x = np.array([1.2, 1.25, 1.18, 1.22, 1.3])
    mean, sd, lo, hi = student_interval(x)
    half = stats.t.ppf(0.975, 4) * x.std(ddof=1) / np.sqrt(5)
    assert mean == pytest.approx(x.mean())
    assert sd == pytest.approx(x.std(ddof=1))
    assert (lo, hi) == pytest.approx((x.mean() - half, x.mean() + half))
    m1, s1, l1, h1 = student_interval([1.0])
    assert m1 == 1.0 and math.isnan(s1) and math.isnan(l1) and math.isnan(h1)


def test_grubbs_critical_value_and_detection():
    # published two-sided critical value for n = 10, alpha = 0.05 is 2.290
    _, _, g_crit = grubbs(np.arange(10.0), alpha=0.05)
    assert g_crit == pytest.approx(2.290, abs=2e-3)
    x = np.array([1.00, 1.02, 0.99, 1.01, 0.98, 1.40])
    idx, g, g_crit = grubbs(x, alpha=0.01)
    assert idx == 5 and g > g_crit
    idx, g, _ = grubbs(x[:5], alpha=0.01)
    assert idx is None
    assert grubbs([1.0, 2.0])[0] is None  # fewer than 3 values: no test


@given(st.lists(st.floats(0.1, 10.0), min_size=3, max_size=8),
       st.floats(0.5, 5.0), st.floats(-5.0, 5.0))
@settings(max_examples=40, deadline=None)
def test_grubbs_is_affine_invariant(values, scale, shift):
    x = np.asarray(values)
    if np.std(x) < 1e-6:
        return
    a = grubbs(x, 0.05)
    b = grubbs(scale * x + shift, 0.05)
    assert a[0] == b[0]
    assert a[1] == pytest.approx(b[1], rel=1e-6, abs=1e-9)


def test_grubbs_rarely_drops_good_records():
    rng = np.random.default_rng(0)
    drops = sum(grubbs(rng.normal(1.0, 0.03, 5), 0.01)[0] is not None for _ in range(1500))
    assert drops / 1500 < 0.025  # alpha = 0.01 by construction


# --------------------------------------------------------------------------- campaigns
CONDS = [
    ConditionSpec("steel 2 kg 5 km/h", "steel", 2.0, 1.9, 4, 331.0, -120.0, repeat_sd=0.01),
    ConditionSpec("steel 5 kg fixed pin", "steel", 5.0, 1.2, 3, 331.0, 0.0, repeat_sd=0.01),
    ConditionSpec("S120 3 kg", "sandpaper 120", 3.0, 0.9, 3, 663.0, -120.0, "initial",
                  repeat_sd=0.01),
    ConditionSpec("same direction 4 kg", "steel", 4.0, 1.3, 3, 331.0, 500.0, repeat_sd=0.01),
    ConditionSpec("fixed disc 1 kg", "steel", 1.0, 3.0, 3, 0.0, 331.0, repeat_sd=0.01),
]


def test_campaign_recovers_mu_within_2_percent():
    rig = synthetic_rig()
    records, rows, truth = campaign_records(CONDS, rig, seed=11, record_kwargs=SHORT)
    camp = process_records(records, rows, rig)
    assert len(camp.used) == len(records) and not camp.unusable
    true_c = truth.condition_mu()
    for c in camp.conditions:
        assert c.written and c.n == next(s.repeats for s in CONDS if s.name == c.condition)
        assert abs(c.mu / true_c[c.condition] - 1) < 0.02, c.condition
        assert c.ci95[0] < c.mu < c.ci95[1]
    # each record's own coefficient is recovered much more tightly
    true_r = truth.record_mu()
    for r in camp.records:
        assert abs(r.mu / true_r[r.file] - 1) < 0.005, r.file
    # v, s, p from the speeds, load and area
    by = {c.condition: c for c in camp.conditions}
    c = by["steel 2 kg 5 km/h"]
    w = (331 + 120) * RPM
    assert c.v == pytest.approx(0.040 * w, rel=2e-3)
    assert c.s == pytest.approx(451 / 331, rel=2e-3)  # counter-rotating: 1 < s <= 2
    assert c.p == pytest.approx(2 * 9.8 / (np.pi * 0.01**2))
    assert c.F_N == pytest.approx(19.6)
    assert by["steel 5 kg fixed pin"].s == pytest.approx(1.0)
    assert by["fixed disc 1 kg"].s == pytest.approx(1.0)
    assert by["same direction 4 kg"].s == pytest.approx(169 / 500, rel=3e-3)
    assert by["same direction 4 kg"].v == pytest.approx(0.04 * 169 * RPM, rel=3e-3)


def test_unusable_records_are_reported_and_the_rest_processed(tmp_path):
    rig = synthetic_rig()
    conds = [ConditionSpec("steel 3 kg", "steel", 3.0, 1.5, 4, 331.0, 0.0, repeat_sd=0.01)]
    truth = make_campaign(tmp_path, conds, rig=rig, seed=5, record_kwargs=SHORT)
    rec_dir = tmp_path / "records"
    good = rec_dir / "steel_3_kg_01.csv"
    lines = good.read_text().splitlines()
    # NaN in the torque, too short, wrong columns, saturation, no sliding, not in contact
    nan_lines = list(lines)
    nan_lines[5001] = nan_lines[5001].split(",")[0] + ",,331.0"
    (rec_dir / "nan.csv").write_text("\n".join(nan_lines) + "\n")
    (rec_dir / "short.csv").write_text("\n".join(lines[:2001]) + "\n")
    (rec_dir / "columns.csv").write_text("\n".join(
        ["time [s],force [N],disc_speed [rpm]"] + lines[1:]) + "\n")
    sat = generate_record(RecordSpec(mu=30.0, load=3 * 9.8, duration=15.0, t_start=2.0,
                                     t_stop=13.0), rig, 1)
    write_record(rec_dir / "saturated.csv", sat)
    still = Record(sat.time, np.full(sat.time.size, 0.35), np.zeros(sat.time.size))
    write_record(rec_dir / "still.csv", still)
    lifted = generate_record(RecordSpec(mu=0.0, load=3 * 9.8, duration=15.0, t_start=2.0,
                                        t_stop=13.0), rig, 2)
    write_record(rec_dir / "lifted.csv", lifted)
    extra = ["records/nan.csv", "records/short.csv", "records/columns.csv",
             "records/saturated.csv", "records/still.csv", "records/lifted.csv",
             "records/missing.csv"]
    with truth.manifest.open("a") as fh:
        for f in extra:
            fh.write(f"{f},3,steel,steel 3 kg,steady\n")
        fh.write("records/steel_3_kg_02.csv,3,steel,steel 3 kg,steady\n")  # listed twice
        fh.write("records/bad_load.csv,heavy,steel,steel 3 kg,steady\n")
        fh.write("records/odd_load.csv,1_000,steel,steel 3 kg,steady\n")  # one number parser
        fh.write("records/bad_mode.csv,3,steel,steel 3 kg,sideways\n")
    camp = process_campaign(truth.manifest, rig, jobs=1, progress=False)
    reasons = {r.file: r.reason for r in camp.unusable}
    assert set(reasons) == set(extra) | {"records/steel_3_kg_02.csv", "records/bad_load.csv",
                                         "records/bad_mode.csv", "records/odd_load.csv"}
    assert "missing or non-numeric" in reasons["records/nan.csv"]
    assert "row 5002" in reasons["records/nan.csv"]
    assert "too short" in reasons["records/short.csv"]
    assert "missing column torque" in reasons["records/columns.csv"]
    assert "saturation" in reasons["records/saturated.csv"]
    assert "no sliding" in reasons["records/still.csv"]
    assert "no friction" in reasons["records/lifted.csv"]
    assert "not found" in reasons["records/missing.csv"]
    assert "listed twice" in reasons["records/steel_3_kg_02.csv"]
    assert "'heavy' is not a number" in reasons["records/bad_load.csv"]
    assert "'1_000' is not a number" in reasons["records/odd_load.csv"]
    assert "sideways" in reasons["records/bad_mode.csv"]
    # the good records are processed: 4 used (the repeated row is the one refused)
    (cond,) = camp.conditions
    assert cond.n == 4 and abs(cond.mu / 1.5 - 1) < 0.02
    assert len(cond.unusable) == 11
    text = camp.summary()
    assert "11 unusable" in text and "records/short.csv: " in text
    table = camp.records_frame()
    assert (table["status"] == "unusable").sum() == 11
    assert table.loc[table["status"] == "unusable", "reason"].str.len().min() > 10


def test_outlier_is_dropped_and_reported():
    rig = synthetic_rig()
    conds = [ConditionSpec("steel 3 kg", "steel", 3.0, 1.5, 6, 331.0, 0.0, repeat_sd=0.01)]
    records, rows, _ = campaign_records(conds, rig, seed=2, record_kwargs=SHORT)
    bad = generate_record(RecordSpec(mu=2.1, load=3 * 9.8, duration=15.0, t_start=2.0,
                                     t_stop=13.0), rig, 9, source="odd.csv")
    records.append(bad)
    rows.append({**rows[0], "file": "odd.csv"})
    camp = process_records(records, rows, rig)
    (cond,) = camp.conditions
    assert cond.n == 6 and [f for f, _ in cond.outliers] == ["odd.csv"]
    assert abs(cond.mu / 1.5 - 1) < 0.02
    (odd,) = camp.outliers
    assert odd.file == "odd.csv" and "Grubbs" in odd.reason and odd.grubbs_g > 2
    assert "outliers dropped:" in camp.summary()
    # with the rule off, the record stays and drags the mean
    off = process_records(records, rows, replace(rig, outliers=replace(rig.outliers,
                                                                       rule="none")))
    assert off.conditions[0].n == 7 and off.conditions[0].mu > cond.mu


def test_grouping_without_condition_column_and_window_override():
    rig = synthetic_rig()
    conds = [ConditionSpec("a", "steel", 2.0, 1.9, 3, 331.0, -120.0, repeat_sd=0.01),
             ConditionSpec("b", "steel", 2.0, 1.7, 3, 663.0, -120.0, repeat_sd=0.01),
             ConditionSpec("c", "glass", 2.0, 2.2, 2, 331.0, -120.0, repeat_sd=0.01)]
    records, rows, _ = campaign_records(conds, rig, seed=4, record_kwargs=SHORT)
    for r in rows:
        del r["condition"]
    rows[0]["window_start [s]"] = 8.0
    rows[0]["window_end [s]"] = 11.0
    rows[1]["window_start [ms]"] = ""  # an empty cell keeps the automatic window
    with pytest.raises(InputError, match="two columns give 'window_start'"):
        process_records(records, rows, rig)
    del rows[1]["window_start [ms]"]
    camp = process_records(records, rows, rig)
    names = sorted(c.condition for c in camp.conditions)
    assert len(names) == 3
    assert any("disc 331 rpm, pin -120 rpm" in n and n.startswith("steel") for n in names)
    assert any("disc 663 rpm" in n for n in names)
    assert any(n.startswith("glass") for n in names)
    first = camp.records[0]
    assert first.window_source == "manifest"
    assert first.window_start == pytest.approx(8.0) and first.window_end == pytest.approx(11.0)
    assert camp.records[1].window_source == "auto"


def test_direction_column_for_logged_magnitudes():
    rig = synthetic_rig()
    rec = generate_record(RecordSpec(mu=1.4, load=19.6, disc_rpm=331, pin_rpm=-120,
                                     duration=15.0, t_start=2.0, t_stop=13.0, t_second=1.0),
                          rig, 4)
    mag = Record(rec.time, rec.torque, np.abs(rec.disc_speed), np.abs(rec.pin_speed))
    base = ManifestEntry(row=2, file="r.csv", path="", load=19.6, load_text="2 kg",
                         surface="steel")
    signed = process_record(mag, base, rig)
    counter = process_record(mag, replace(base, direction="counter"), rig)
    assert signed.v == pytest.approx(0.04 * 211 * RPM, rel=3e-3)  # read as same direction
    assert counter.v == pytest.approx(0.04 * 451 * RPM, rel=3e-3)
    assert counter.mu == pytest.approx(signed.mu)


def test_min_repeats_and_conditions_not_written():
    rig = synthetic_rig()
    conds = [ConditionSpec("pair", "steel", 2.0, 1.9, 2, 331.0, 0.0),
             ConditionSpec("single", "steel", 3.0, 1.6, 1, 331.0, 0.0)]
    records, rows, _ = campaign_records(conds, rig, seed=1, record_kwargs=SHORT)
    camp = process_records(records, rows, rig)
    frame = camp.dataset_frame()
    assert list(frame["condition"]) == ["pair"]
    assert "single: 1 usable record(s), fewer than min_repeats = 2" in camp.summary()


def test_processed_dataset_is_ready_for_fit():
    from frictionlaws import fit, get_law

    rig = synthetic_rig()
    thirion = get_law("thirion")  # mu = 1 / (a + b p)
    conds = []
    for m in (1, 2, 3, 4, 6, 8):
        mu = float(thirion(p=m * 9.8 / rig.contact_area, a=0.3, b=3e-6))
        conds.append(ConditionSpec(f"steel {m:g} kg", "steel", m, mu, 3, 331.0, 0.0,
                                   repeat_sd=0.01))
    records, rows, _ = campaign_records(conds, rig, seed=8, record_kwargs=SHORT)
    ds = process_records(records, rows, rig).dataset()
    assert {"mu", "p", "v", "s", "F_N", "mu_std", "n"} <= set(ds.frame.columns)
    assert ds.weights() is not None
    result = fit("thirion", ds)
    assert result.params["a"].value == pytest.approx(0.3, rel=0.05)
    assert result.params["b"].value == pytest.approx(3e-6, rel=0.05)


# --------------------------------------------------------------------------- CLI
@pytest.mark.slow
def test_cli_process_writes_dataset_records_and_plots(tmp_path, capsys):
    rig = synthetic_rig()
    conds = [ConditionSpec("steel 2 kg", "steel", 2.0, 1.9, 3, 331.0, -120.0),
             ConditionSpec("S400 3 kg", "sandpaper 400", 3.0, 1.0, 2, 331.0, -120.0,
                           "initial")]
    truth = make_campaign(tmp_path / "camp", conds, rig=rig, seed=3, record_kwargs=SHORT)
    short = truth.directory / "records" / "short.csv"
    short.write_text("\n".join(
        (truth.directory / "records" / "steel_2_kg_01.csv").read_text().splitlines()[:6001]))
    with truth.manifest.open("a") as fh:
        fh.write("records/gone.csv,2,steel,steel 2 kg,steady\n")
        fh.write("records/short.csv,2,steel,steel 2 kg,steady\n")
    out = tmp_path / "dataset.csv"
    code = main(["process", str(truth.manifest), "--rig", str(truth.rig_file), "-o", str(out),
                 "--plots", str(tmp_path / "plots"), "--jobs", "1"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    assert "7 records: 5 used, 0 dropped as outliers, 2 unusable" in captured.out
    assert "records/gone.csv: " in captured.out and "not found" in captured.out
    assert captured.err == ""  # no progress bar when stderr is not a terminal
    header = [line for line in out.read_text().splitlines() if not line.startswith("#")][0]
    for col in ("mu", "mu_std", "n", "p [MPa]", "v [m/s]", "s", "F_N [N]", "surface",
                "mu_ci95_low", "mu_ci95_high"):
        assert col in header.split(",")
    ds = load_dataset(out)
    assert len(ds) == 2 and set(ds.frame["surface"]) == {"steel", "sandpaper 400"}
    assert ds.frame["p"].iloc[0] == pytest.approx(2 * 9.8 / (np.pi * 1e-4))
    records = pd.read_csv(tmp_path / "dataset_records.csv", comment="#")
    assert len(records) == 7 and (records["status"] == "used").sum() == 5
    pngs = sorted(p.name for p in (tmp_path / "plots").iterdir())
    # 5 used records, the unusable but readable one, and the summary (no file: no plot)
    assert "conditions.png" in pngs and "records_short.png" in pngs and len(pngs) == 7


def test_cli_process_bad_input_exit_2(tmp_path, capsys):
    rig = write(tmp_path, "rig.toml", RIG_TOML)
    manifest = write(tmp_path, "m.csv", "file,load,surface\nr.csv,3,steel\n")
    code = main(["process", str(manifest), "--rig", str(rig), "-o", str(tmp_path / "o.csv")])
    err = capsys.readouterr().err
    assert code == 2 and "load column has no unit" in err and "Traceback" not in err
    manifest = write(tmp_path, "m.csv", "file,load [kg]\nr.csv,3\n")
    assert main(["process", str(manifest), "--rig", str(rig), "-o",
                 str(tmp_path / "o.csv")]) == 2
    assert "no 'surface' column" in capsys.readouterr().err
    manifest = write(tmp_path, "m.csv", "file,load [kg],surface\nr.csv,3,steel\n")
    code = main(["process", str(manifest), "--rig", str(rig), "-o", str(tmp_path / "o.csv")])
    captured = capsys.readouterr()
    assert code == 2 and "no dataset written" in captured.err
    assert "r.csv: file" in captured.out and "record file not found" in captured.out
    assert main(["process", str(manifest), "--rig", str(tmp_path / "none.toml"), "-o",
                 str(tmp_path / "o.csv")]) == 2


@pytest.mark.slow
def test_parallel_and_serial_give_the_same_results(tmp_path):
    rig = synthetic_rig()
    conds = [ConditionSpec(f"c{i}", "steel", 1.0 + i, 2.0 - 0.2 * i, 3, 331.0, 0.0)
             for i in range(3)]
    truth = make_campaign(tmp_path, conds, rig=rig, seed=6,
                          record_kwargs={"duration": 10.0, "fs": 500.0, "peak_tau": 0.3})
    one = process_campaign(truth.manifest, rig, jobs=1, progress=False)
    two = process_campaign(truth.manifest, rig, jobs=2, progress=False)
    assert [r.mu for r in one.records] == [r.mu for r in two.records]
    assert [c.mu for c in one.conditions] == [c.mu for c in two.conditions]


def test_constant_speed_columns_window_from_torque_alone():
    """A logger that writes the speed set-points: the torque alone finds the window."""
    rig = synthetic_rig()
    rec = generate_record(RecordSpec(mu=1.6, load=29.4, disc_rpm=331.0, duration=20.0,
                                     t_start=3.0, t_stop=17.0), rig, 2)
    flat = Record(rec.time, rec.torque, np.full(rec.time.size, 331 * RPM))
    entry = ManifestEntry(row=2, file="flat.csv", path="", load=29.4, load_text="3 kg",
                          surface="steel")
    res = process_record(flat, entry, rig)
    assert res.status == "used", res.reason
    assert 5.0 < res.window_start < 7.5 and 15.5 < res.window_end < 17.0
    assert res.mu == pytest.approx(1.6, rel=0.005)
    assert any("from the torque alone" in n for n in res.notes)


def test_manifest_window_with_one_end_and_table_extrapolation_note():
    rig = synthetic_rig(internal_speed=np.array([0.0, 400.0]) * RPM,
                        internal_torque_table=np.array([0.11, 0.065]))
    rec = generate_record(RecordSpec(mu=1.4, load=19.6, disc_rpm=663, duration=15.0,
                                     t_start=2.0, t_stop=13.0), rig, 4)
    base = ManifestEntry(row=3, file="r.csv", path="", load=19.6, load_text="2 kg",
                         surface="steel", window_end=10.0)
    res = process_record(rec, base, rig)
    assert res.status == "used" and res.window_source == "manifest end"
    assert res.window_end == pytest.approx(10.0) and 3.0 < res.window_start < 8.0
    assert any("outside the internal-torque table" in n for n in res.notes)
    late = process_record(rec, replace(base, window_end=None, window_start=14.9), rig)
    assert late.status == "unusable" and "fewer than 2 samples" in late.reason
    outside = process_record(rec, replace(base, window_end=99.0), rig)
    assert "outside the record" in outside.reason
    still = Record(rec.time, rec.torque, np.zeros(rec.time.size))
    auto_fails = process_record(still, base, rig)
    assert auto_fails.status == "unusable" and "no sliding" in auto_fails.reason


def test_lowpass_equals_scipy_sosfiltfilt():
    from scipy import signal

    rng = np.random.default_rng(3)
    x = np.cumsum(rng.standard_normal(5000))
    for cutoff in (2.0, 17.5, 120.0):
        sos = signal.butter(4, cutoff, fs=1000.0, output="sos")
        np.testing.assert_allclose(lowpass(x, 1000.0, cutoff), signal.sosfiltfilt(sos, x),
                                   rtol=1e-10, atol=1e-10)
        stacked = lowpass(np.vstack([x, 2 * x]), 1000.0, cutoff)
        np.testing.assert_allclose(stacked[1], 2 * signal.sosfiltfilt(sos, x), atol=1e-9)


def test_record_with_a_repeated_header_is_refused(tmp_path):
    path = tmp_path / "dup.csv"
    path.write_text("time [s],torque [N m],torque [N m],disc_speed [rpm]\n"
                    + "0.1,2,3,4\n" * 10)
    with pytest.raises(InputError, match="duplicate column") as info:
        read_record(path)
    assert info.value.column == "torque [N m]"


def test_process_and_fit_refuse_output_names_they_cannot_honour(tmp_path, capsys):
    assert main(["process", str(tmp_path / "m.csv"), "--rig", str(tmp_path / "r.toml"),
                 "-o", str(tmp_path / "x.json")]) == 2
    assert "give a .csv name" in capsys.readouterr().err
    assert main(["fit", "--law", "thirion", "thesis-steel", "--save", "-"]) == 2
    assert "--save needs a file name" in capsys.readouterr().err


def test_a_condition_label_over_two_surfaces_is_not_averaged(tmp_path):
    """Records of steel and glass under one label: reported, never written as one row."""
    import shutil

    rig = synthetic_rig()
    conds = [ConditionSpec("steel 2 kg", "steel", 2.0, 1.9, 3, 331.0, -120.0),
             ConditionSpec("S400 3 kg", "sandpaper 400", 3.0, 1.0, 3, 331.0, -120.0)]
    truth = make_campaign(tmp_path / "camp", conds, rig=rig, seed=5, record_kwargs=SHORT)
    records = truth.directory / "records"
    shutil.copy(records / "steel_2_kg_01.csv", records / "glass.csv")
    with truth.manifest.open("a") as fh:
        fh.write("records/glass.csv,2,glass,steel 2 kg,steady\n")
    camp = process_campaign(truth.manifest, rig, jobs=1, progress=False)
    by = {c.condition: c for c in camp.conditions}
    assert not by["steel 2 kg"].written and by["S400 3 kg"].written
    assert any("surfaces (glass, steel)" in n for n in by["steel 2 kg"].notes)
    assert set(camp.dataset_frame()["condition"]) == {"S400 3 kg"}
