"""Raw rig runs: read (names and units rows, SAE axes), cut into steady sweeps, refused when
they cannot be used; ``tyre prepare``."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.tyre.data import (
    detect_format,
    load_raw_run,
    prepare_run,
    read_tydex,
    read_tyre_data,
    read_tyre_files,
    write_tydex,
)
from frictionlaws.tyre.data import raw_run as raw_module
from frictionlaws.tyre.data.segments import REASONS
from frictionlaws.tyre.data.synthetic import PHASES, RawRunSpec, sweep_data, synthetic_raw_run
from frictionlaws.tyre.magic_formula import MagicFormula

TRUTH = MagicFormula.from_file("MagicFormula61")
SPEC = RawRunSpec(loads=(0.5, 1.2), cambers_deg=(0.0, 3.0), pressures=(0.9, 1.1), rate=50.0,
                  combined_deg=(-5.0, 5.0), cycles=1, warmup_s=20.0)


TINY = RawRunSpec(loads=(0.6, 1.2), cambers_deg=(0.0,), pressures=(1.0,), rate=50.0,
                  combined_deg=(5.0,), cycles=1, warmup_s=10.0)


@pytest.fixture(scope="module")
def run():
    return synthetic_raw_run(TRUTH, SPEC)


@pytest.fixture(scope="module")
def tiny():
    """A short run (two loads) for the edits of hostile cases."""
    return synthetic_raw_run(TRUTH, TINY)


@pytest.fixture(scope="module")
def raw(run, tmp_path_factory) -> Path:
    return run.write(tmp_path_factory.mktemp("raw") / "run.dat")


@pytest.fixture(scope="module")
def prepared(raw):
    return prepare_run(load_raw_run(raw))


def _phase(name: str) -> int:
    return PHASES.index(name)


def test_the_sweeps_are_kept_and_the_rest_dropped_by_reason(run, prepared) -> None:
    kept = prepared.status == 0
    phase = run.phase
    sweeps = np.isin(phase, [_phase("lateral"), _phase("longitudinal")])
    assert not np.any(kept & np.isin(phase, [_phase("lift"), _phase("warm-up")]))
    assert np.sum(kept & ~sweeps) <= 0.01 * kept.sum()
    assert np.sum(kept & sweeps) >= 0.85 * sweeps.sum()
    warm = phase == _phase("warm-up")
    assert np.mean(prepared.status[warm] == REASONS.index("warm-up")) > 0.9
    lifted = (phase == _phase("lift")) & (run.channels["FZ"] > -50)
    assert np.all(prepared.status[lifted] == REASONS.index("lift"))
    dropped = prepared.dropped()
    assert {"lift", "warm-up", "transition", "settling"} <= set(dropped)
    assert sum(n for n, _ in dropped.values()) + kept.sum() == len(run)


def test_the_levels_lags_and_offsets_are_found(prepared) -> None:
    np.testing.assert_allclose(prepared.levels["load"], np.array(SPEC.loads) * TRUTH.fnomin,
                               rtol=0.01)
    np.testing.assert_allclose(np.degrees(prepared.levels["camber"]), SPEC.cambers_deg,
                               atol=0.05)
    np.testing.assert_allclose(prepared.levels["pressure"],
                               np.array(SPEC.pressures) * TRUTH.nominal_pressure, rtol=0.005)
    kinds = [s.kind for s in prepared.segments if s.kept]
    assert kinds.count("lateral") == 8 and kinds.count("longitudinal") == 24
    lags = np.array([tau for _, tau in prepared.lags])
    assert np.all(np.abs(lags / SPEC.lag - 1) < 0.2)
    t = prepared.offsets["time"] / (len(prepared.run) / SPEC.rate)
    start, end = np.array(SPEC.offsets)
    for j, k in enumerate(("fx", "fy", "mz")):
        truth = start[j] + (end[j] - start[j]) * t
        scale = 0.03 * SPEC.noise * 1e4 if k != "mz" else 0.5
        assert np.all(np.abs(prepared.offsets[k] - truth) < max(scale, 0.2 * abs(start[j])))


def _follow_the_truth(d, spec: RawRunSpec) -> None:
    """The rows' forces and moment within 1 % RMS of the noise-free truth's peak."""
    out = TRUTH.steady_state(d.kappa, d.alpha, d.fz, d.gamma, pressure=d.pressure,
                             vx=spec.speed_kph / 3.6)
    for k, name in (("fx", "Fx"), ("fy", "Fy"), ("mz", "Mz")):
        r = getattr(d, k) - out[name]
        assert np.sqrt(np.mean(r ** 2)) < 0.01 * np.abs(out[name]).max(), k


def test_the_rows_follow_the_noise_free_truth(prepared) -> None:
    d = prepared.data
    _follow_the_truth(d, SPEC)
    up, down = d.extra["direction"] > 0, d.extra["direction"] < 0
    assert 0.4 < up.mean() < 0.6 and up.sum() + down.sum() == len(d)
    assert np.all(d.extra["samples"] >= 3) and set(d.extra) >= {"sweep", "time"}
    assert any("kappa is SL" in n for n in d.notes)
    assert any("lag behind the slip" in n for n in d.notes)


@pytest.mark.parametrize("delimiter", [",", " "])
def test_every_delimiter_gives_the_same_rows(run, prepared, tmp_path: Path,
                                             delimiter: str) -> None:
    path = run.write(tmp_path / "run.txt", delimiter=delimiter)
    assert detect_format(path) == "raw"
    other = prepare_run(load_raw_run(path))
    for k in ("fz", "kappa", "alpha", "fx", "fy", "mz"):
        np.testing.assert_array_equal(getattr(other.data, k), getattr(prepared.data, k))


def _edited(run, path: Path, drop: tuple[str, ...] = (), scale: dict | None = None,
            units: dict | None = None, negate: tuple[str, ...] = ()) -> Path:
    names = [n for n in run.channels if n not in drop]
    cols = [run.channels[n] * (scale or {}).get(n, 1.0) * (-1 if n in negate else 1)
            for n in names]
    u = {**run.units, **(units or {})}
    lines = ["a title line", "\t".join(names), "\t".join(u[n] for n in names)]
    lines += ["\t".join(f"{v:.6g}" for v in row) for row in np.column_stack(cols)]
    path.write_text("\n".join(lines) + "\n")
    return path


def test_kappa_is_chosen_by_meaning(tiny, tmp_path: Path) -> None:
    sl = load_raw_run(_edited(tiny, tmp_path / "sl.txt"))
    computed = load_raw_run(_edited(tiny, tmp_path / "no_sl.txt", drop=("SL",)))
    assert any("kappa computed as omega R_e / V - 1" in n for n in computed.notes)
    diff = computed.quantities["kappa"] - sl.quantities["kappa"]
    assert abs(np.median(diff)) < 5e-4 and np.std(diff) < 5e-3  # the road speed's noise
    loaded = load_raw_run(_edited(tiny, tmp_path / "sr.txt", drop=("SL", "N")))
    assert any("kappa is SR, the rig's slip ratio on the loaded radius" in n
               for n in loaded.notes)
    free = np.median(loaded.quantities["kappa"][tiny.phase == _phase("lateral")])
    assert free < -0.01  # SR is offset by RL / RE - 1 at free rolling


def test_a_run_without_camber_or_with_one_load_says_so(tmp_path: Path) -> None:
    spec = RawRunSpec(loads=(1.0,), cambers_deg=(0.0,), pressures=(1.0,), rate=50.0,
                      combined_deg=(), cycles=1, warmup_s=10.0)
    one = synthetic_raw_run(TRUTH, spec)
    p = prepare_run(load_raw_run(_edited(one, tmp_path / "one.txt", drop=("IA", "P"))))
    notes = " / ".join(p.notes)
    assert "no camber (IA) channel: camber = 0" in notes
    assert "no pressure (P) channel: not measured" in notes
    assert "one load level only: a fit cannot determine the load dependence" in notes
    assert np.all(p.data.gamma == 0) and np.all(np.isnan(p.data.pressure))


@pytest.mark.parametrize("change,match", [
    (dict(units={"SA": "rad"}), "slip angle beyond 90 degrees .*'rad'.*degrees under a "
                                "radian unit"),
    (dict(units={"IA": "rad"}, scale={"IA": 20.0}), "camber beyond 30 degrees"),
    (dict(scale={"SA": math.pi / 180}), "radians under a degree header|slip angle"),
    (dict(units={"FZ": "kN"}), "below 2 % of the load"),
    (dict(units={"SL": "%"}), "fractions under a percent unit"),
    (dict(scale={"SL": 100.0}), "percent given as fractions"),
    (dict(units={"MZ": "N-m"}, scale={"MZ": 1000.0}), "N mm under N m"),
    (dict(units={"FZ": ""}), "FZ has no unit"),
    (dict(units={"P": "MPa"}), "inflation pressure of 2.*e\\+05 kPa.*'MPa'"),  # kPa as MPa
    (dict(units={"P": "Pa"}), "inflation pressure of 0.2.* kPa.*'Pa'"),
    (dict(units={"P": "bar"}), "inflation pressure of 2.*e\\+04 kPa.*'bar'"),
    (dict(scale={"P": 0.01}), "inflation pressure of 2.* kPa"),  # bar numbers under kPa
    (dict(units={"FX": "m"}), "force"),
    (dict(drop=("ET",)), "no ET channel"),
    (dict(drop=("SA",)), "no SA channel .*needs FZ, ET, SA, FX, FY"),
    (dict(drop=("FX",)), "no FX channel"),
    (dict(drop=("FY",)), "no FY channel"),
    (dict(units={"ET": "ms"}), "sampling rate of 5e\\+04 Hz .*'ms'"),
    (dict(units={"ET": "min"}), "sampling rate of 0.8333 Hz .*'min'"),
    (dict(drop=("FZ",)), "no row of channel names"),
])
def test_units_that_cannot_be_right_are_refused(tiny, tmp_path: Path, change, match) -> None:
    path = _edited(tiny, tmp_path / "bad.txt", **change)
    with pytest.raises(InputError, match=match) as exc:
        prepare_run(load_raw_run(path))
    assert exc.value.file == str(path)


@pytest.mark.parametrize("scale, unit", [(0.01, "kPa"), (1000.0, "kPa")])
def test_a_pressure_in_another_unit_is_refused_naming_channel_row_and_unit(
        tiny, tmp_path: Path, scale: float, unit: str) -> None:
    """bar numbers (or Pa) under a kPa unit: the one pressure check of the project names
    the channel, the first loaded sample's line and the unit that looks off."""
    path = _edited(tiny, tmp_path / "p.txt", scale={"P": scale})
    with pytest.raises(InputError, match=f"the unit '{unit}' looks off by a factor") as exc:
        load_raw_run(path)
    loaded = np.flatnonzero(-tiny.channels["FZ"] > 0.1 * np.percentile(-tiny.channels["FZ"], 95))
    assert exc.value.column == "P" and exc.value.row == int(loaded[0]) + 4  # title, 2 rows


def test_camber_settings_in_radians_under_a_degree_unit_are_refused(run, tmp_path: Path
                                                                    ) -> None:
    """IA of 0 and 3 deg written in radians under 'deg': the levels read as hundredths of a
    degree (which the preparation would merge into one), their camber thrust 57 times a
    tyre's (the run in degrees passes: the ``raw`` fixture)."""
    with pytest.raises(InputError, match="whole degrees 0, 3 .*look like radians") as exc:
        load_raw_run(_edited(run, tmp_path / "rad.txt", scale={"IA": math.pi / 180}))
    assert exc.value.column == "IA" and exc.value.row is not None


def test_the_axes_declared_must_be_the_axes_of_the_file(tiny, tmp_path: Path,
                                                        capsys) -> None:
    sae = _edited(tiny, tmp_path / "sae.txt")
    with pytest.raises(InputError, match="sign_convention='sae'") as exc:
        load_raw_run(sae, sign_convention="iso")
    assert exc.value.column == "FZ" and exc.value.row > 3
    iso = _edited(tiny, tmp_path / "iso.txt", negate=("FZ", "FY", "MZ", "SA"))
    with pytest.raises(InputError, match="sign_convention='iso'"):
        load_raw_run(iso)
    flipped = _edited(tiny, tmp_path / "fy_flipped.txt", negate=("FY",))
    assert main(["tyre", "prepare", str(flipped), "-o", str(tmp_path / "f.csv")]) == 2
    assert "Fy has the sign of the slip angle" in capsys.readouterr().err
    assert not (tmp_path / "f.csv").exists()


def _lines(raw: Path) -> list[str]:
    return raw.read_text().splitlines()


@pytest.mark.parametrize("edit,match", [
    (lambda ls: ls[:-1] + [ls[-1].rsplit("\t", 3)[0]], "cells on this row"),
    (lambda ls: ls[:50] + [ls[50].replace("\t", "\t\uff11", 1)] + ls[51:], "not a number"),
    (lambda ls: ls[:50] + [ls[50].replace("\t", "\t1_0", 1)] + ls[51:], "not a number"),
    (lambda ls: ls[:50] + [ls[50].replace("\t", "\tnan", 1)] + ls[51:], "not a number"),
    (lambda ls: ls[:50] + [ls[50].replace("\t", "\t", 1).replace("\t", "\t\t", 1)] + ls[51:],
     "cells on this row"),
    (lambda ls: ls[:1] + [ls[1].replace("ET", "FZ")] + ls[2:], "named twice"),
])
def test_broken_rows_are_refused_naming_the_line(tiny, tmp_path: Path, edit, match) -> None:
    path = tmp_path / "broken.txt"
    path.write_text("\n".join(edit(_lines(tiny.write(tmp_path / "tiny.txt")))) + "\n")
    with pytest.raises(InputError, match=match) as exc:
        load_raw_run(path)
    assert exc.value.file == str(path) and exc.value.row is not None


def test_a_huge_run_is_refused_by_its_sample_count(raw, monkeypatch) -> None:
    monkeypatch.setattr(raw_module, "MAX_SAMPLES", 1000)
    with pytest.raises(InputError, match="more than the limit of 1000"):
        load_raw_run(raw)


def test_a_name_with_a_line_break_is_not_used_and_writes_no_line(tiny, tmp_path: Path,
                                                                 capsys) -> None:
    lines = _lines(tiny.write(tmp_path / "tiny.txt"))
    lines[1] = lines[1].replace("RST", "R\u2028ST")
    path = tmp_path / "odd.txt"
    path.write_text("\n".join(lines) + "\n")
    assert "R\u2028ST" in load_raw_run(path).unused
    out = tmp_path / "odd.csv"
    assert main(["tyre", "prepare", str(path), "-o", str(out)]) == 0
    assert "\u2028" not in out.read_text()
    capsys.readouterr()


def test_a_run_cut_short_is_refused_for_what_it_lacks(tiny, tmp_path: Path) -> None:
    """Runs cut after any number of samples (drawn once): before the tyre is loaded the
    refusal says so; later, what is missing (no sweep); never a unit or the axes, which
    the samples kept do not bring into question."""
    lines = _lines(tiny.write(tmp_path / "tiny.txt"))
    fz = np.abs(tiny.channels["FZ"])
    first_loaded = int(np.argmax(fz >= raw_module.MIN_RIG_LOAD))
    cuts = sorted({1, 2, first_loaded, first_loaded + 1, first_loaded + 40,
                   *np.random.default_rng(37).integers(3, fz.size, 12).tolist()})
    for n in cuts:
        path = tmp_path / f"cut{n}.txt"
        path.write_text("\n".join(lines[:3 + n]) + "\n")
        try:
            prepare_run(load_raw_run(path))
        except InputError as exc:
            text = str(exc)
            assert "sign_convention" not in text and "unit" not in text, (n, text)
            if n <= first_loaded:
                assert "no sample carries a load of 100 N" in text, (n, text)
            assert exc.file == str(path)


@pytest.mark.parametrize("order", ["twice", "shuffled", "block again", "reversed",
                                   "joined"])
def test_samples_out_of_time_order_are_refused_naming_the_row(tiny, tmp_path: Path,
                                                              order: str) -> None:
    lines = _lines(tiny.write(tmp_path / "tiny.txt"))
    head, rows = lines[:3], lines[3:]
    rng = np.random.default_rng(41)
    edited = {"twice": [r for r in rows for _ in (0, 1)],
              "shuffled": [rows[i] for i in rng.permutation(len(rows))],
              "block again": rows[:2000] + rows[1500:],
              "reversed": rows[::-1],
              "joined": rows + rows}[order]
    path = tmp_path / "bad.txt"
    path.write_text("\n".join(head + edited) + "\n")
    with pytest.raises(InputError, match="the time does not advance here") as exc:
        load_raw_run(path)
    assert exc.value.column == "ET" and exc.value.row is not None and exc.value.row > 3


def test_a_gap_in_the_time_is_noted(tiny, tmp_path: Path) -> None:
    lines = _lines(tiny.write(tmp_path / "tiny.txt"))
    path = tmp_path / "gap.txt"
    path.write_text("\n".join(lines[:1003] + lines[1503:]) + "\n")  # 10 s at 50 Hz
    notes = " / ".join(load_raw_run(path).notes)
    assert "1 gap(s) in the time (ET), the first of 10 s after line 1003" in notes


def test_a_run_without_sweeps_is_refused(tiny, tmp_path: Path) -> None:
    still = _edited(tiny, tmp_path / "still.txt", scale={"SA": 0.0, "SL": 0.0})
    with pytest.raises(InputError, match="no sweep was found"):
        prepare_run(load_raw_run(still))


@pytest.mark.parametrize("channel, value, slip, forces", [
    ("SA", 0.0, "slip angle", "Fy (FY) and Mz (MZ)"),
    ("SA", 0.7, "slip angle", "Fy (FY) and Mz (MZ)"),
    ("SL", 0.0, "slip ratio", "Fx (FX)")])
def test_a_dead_slip_channel_is_warned_of_on_every_path(tiny, tmp_path: Path, capsys,
                                                        channel: str, value: float,
                                                        slip: str, forces: str) -> None:
    """A slip channel that does not sweep (dead, or stuck at a value) leaves its forces
    without a slip to follow: they are not used, and every path says so, naming the
    channel and the lines of the rows (the API's warnings, the text, --json, the file)."""
    dead = _edited(tiny, tmp_path / "dead.txt", scale={channel: 0.0})
    lines = dead.read_text().splitlines()
    col = lines[1].split("\t").index(channel)
    rows = [line.split("\t") for line in lines[3:]]
    for r in rows:
        r[col] = f"{value:g}"
    dead.write_text("\n".join(lines[:3] + ["\t".join(r) for r in rows]) + "\n")
    said = f"the {slip} channel {channel} stays within "
    with pytest.warns(UserWarning, match=said):
        p = prepare_run(load_raw_run(dead))
    verb = "is" if channel == "SL" else "are"
    assert len(p.warnings) == 1 and said in p.warnings[0]
    assert f"{forces} {verb} not used" in p.warnings[0]
    lo, hi = int(p.data.rows.min()), int(p.data.rows.max())
    assert f"lines {lo}-{hi} of the run" in p.warnings[0]
    assert all(not np.isfinite(getattr(p.data, f)).any()
               for f in (("fx",) if channel == "SL" else ("fy", "mz")))
    out = tmp_path / "sweeps.csv"
    assert main(["tyre", "prepare", str(dead), "-o", str(out)]) == 0
    text, err = capsys.readouterr()
    assert said in err and said not in text  # said once: on stderr, as every warning
    assert f"# warning: {p.warnings[0]}" in out.read_text()
    assert main(["tyre", "prepare", str(dead), "-o", str(tmp_path / "s.tdx"), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["warnings"] == p.warnings


def test_prepare_writes_what_fit_mf_reads(raw, prepared, tmp_path: Path, capsys) -> None:
    out = tmp_path / "sweeps.csv"
    code = main(["tyre", "prepare", str(raw), "-o", str(out), "--plots",
                 str(tmp_path / "plots")])
    text = capsys.readouterr().out
    assert code == 0 and "dropped warm-up" in text and "written:" in text
    assert sorted(p.name for p in (tmp_path / "plots").iterdir()) == ["segments.png",
                                                                      "sweeps.png"]
    back = read_tyre_data(out)
    for k in ("fz", "kappa", "alpha", "gamma", "pressure", "fx", "fy", "mz"):
        np.testing.assert_allclose(getattr(back, k), getattr(prepared.data, k), rtol=1e-12)
    assert np.array_equal(back.extra["sweep"], prepared.data.extra["sweep"])
    assert out.read_text().startswith("# steady sweeps prepared by frictionlaws tyre prepare")
    rows = [line.split(",") for line in out.read_text().splitlines() if line[:1] != "#"]
    whole = [rows[0].index(k) for k in ("sweep", "direction", "samples")]
    assert all(r[j].lstrip("-").isdigit() for r in rows[1:] for j in whole)  # integers
    tdx = tmp_path / "sweeps.tdx"
    assert main(["tyre", "prepare", str(raw), "-o", str(tdx), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["rows"] == len(prepared.data) and "warm-up" in summary["dropped"]
    np.testing.assert_allclose(read_tydex(tdx).fy, prepared.data.fy, rtol=1e-12)


@pytest.mark.parametrize("argv,match", [
    (["-o", "out.txt"], "suffix"),
    (["-o", "out.csv", "--warm-up", "10"], "has no unit"),
    (["-o", "out.csv", "--warm-up", "-5 s"], "0 s or more"),
    (["-o", "out.csv", "--sign-convention", "iso"], "--sign-convention sae"),
])
def test_prepare_refuses_with_one_line_and_writes_nothing(raw, tmp_path: Path, capsys, argv,
                                                          match, monkeypatch) -> None:
    monkeypatch.chdir(tmp_path)
    code = main(["tyre", "prepare", str(raw), *argv])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1 and match in err, err
    assert not any(tmp_path.iterdir())


def test_prepare_reads_standard_input(raw, tmp_path: Path, capsys, monkeypatch) -> None:
    import io
    import sys

    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(raw.read_bytes())))
    out = tmp_path / "s.csv"
    assert main(["tyre", "prepare", "-", "-o", str(out)]) == 0
    assert "raw run <stdin>" in capsys.readouterr().out
    assert "prepare from <stdin>" in out.read_text()


def test_prepare_reports_what_the_checks_warn_of_on_every_path(tiny, tmp_path: Path,
                                                               capsys, monkeypatch) -> None:
    """Forces in daN under 'N' (both: their peaks agree, at an icy road's 0.1): warned of,
    naming each column, in --json, the written file and on stderr, the file named as the
    user gave it (standard input: <stdin>)."""
    import io
    import sys

    dan = _edited(tiny, tmp_path / "dan.txt", scale={"FX": 0.1, "FY": 0.1, "MZ": 0.1})
    monkeypatch.setattr(sys, "stdin", io.TextIOWrapper(io.BytesIO(dan.read_bytes())))
    out = tmp_path / "s.csv"
    assert main(["tyre", "prepare", "-", "-o", str(out), "--json"]) == 0
    text, err = capsys.readouterr()
    said = json.loads(text)["warnings"]
    assert [w.split(", row")[0] for w in said] == ["file '<stdin>', column 'Fx'",
                                                    "file '<stdin>', column 'Fy'"]
    assert all("looks like daN under an [N] header" in w for w in said)
    assert all(f"# warning: {w}" in out.read_text() for w in said)
    assert err.count("warning: file '<stdin>'") == 2 and "frictionlaws-stdin" not in err


def test_the_formats_are_told_apart_and_read_together(raw, tmp_path: Path) -> None:
    lat = write_tydex(sweep_data(TRUTH, "lateral", loads=(0.5, 1.2), n=9),
                      tmp_path / "lat.tdx")
    csv = tmp_path / "t.csv"
    csv.write_text("Fz [N],alpha [deg],Fy [N]\n4000,1,-800\n4000,2,-1500\n")
    assert [detect_format(p) for p in (raw, lat, csv)] == ["raw", "tydex", "csv"]
    data, files = read_tyre_files([raw, lat])
    assert [f.format for f in files] == ["raw", "tydex"]
    assert data.notes[0] == "2 files read together (raw, tydex)"
    assert np.unique(data.extra["file"]).tolist() == [0, 1]


@pytest.mark.slow
def test_a_raw_run_fitted_reproduces_the_noise_free_truth(tmp_path: Path) -> None:
    """From a raw run of a tyre unlike the template (its imperfections all on) to a property
    file within 1 % of the peak for Fx0, Fy0, 2 % combined and 3 % for Mz."""
    import warnings

    from frictionlaws.base.errors import ExtrapolationWarning
    from frictionlaws.tyre import fit_mf
    from frictionlaws.tyre.synthetic_rig import moved_tyre, truth_errors

    truth = moved_tyre()
    spec = RawRunSpec(loads=(0.4, 1.0, 1.6), cambers_deg=(-3.0, 0.0, 3.0),
                      pressures=(0.85, 1.1), rate=50.0, cycles=1)
    path = synthetic_raw_run(truth, spec).write(tmp_path / "held.dat")
    data, _ = read_tyre_files([path])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        fitted = fit_mf(data)
        e = truth_errors(truth, fitted.model, loads=spec.loads, pressures=spec.pressures,
                         cambers_deg=spec.cambers_deg)  # at +-12 deg, beyond the blocks' means
    assert e["Fx0"] < 0.01 and e["Fy0"] < 0.01, e
    assert e["Fx"] < 0.02 and e["Fy"] < 0.02, e
    assert e["Mz"] < 0.03, e


BAD_TOKENS = ["1_000", "\uff11\uff12", "nan", "inf", "1e999", "1,5", "0x10", "--1", "", "1.2.3",
              "\u0661\u0662"]


@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow,
                                                                  HealthCheck.function_scoped_fixture])
@given(row=st.integers(3, 299), channel=st.sampled_from(["ET", "SA", "IA", "P", "FX", "FY",
                                                         "FZ", "MZ", "SL", "TSTC"]),
       token=st.sampled_from(BAD_TOKENS))
def test_any_bad_number_in_a_used_channel_is_refused_with_its_line(tiny, tmp_path: Path, row,
                                                                   channel, token) -> None:
    lines = tiny.text().splitlines()[:300]
    names = lines[1].split("\t")
    cells = lines[row].split("\t")
    cells[names.index(channel)] = token
    lines[row] = "\t".join(cells)
    path = tmp_path / "bad.dat"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(InputError) as exc:
        load_raw_run(path)
    assert exc.value.file == str(path) and exc.value.row == row + 1
    assert exc.value.column == channel


@pytest.mark.parametrize("change", [dict(first_sign=1.0), dict(dwell_s=2.0),
                                    dict(first_sign=1.0, dwell_s=1.0, rate=100.0)])
def test_other_rig_designs_are_cut_alike(change) -> None:
    """Sweeps that start upwards, or hold at their turns, or a faster rate: every sweep is
    found, the holds at the turns dropped as dwells without cutting a sweep in two."""
    import dataclasses
    import tempfile

    spec = dataclasses.replace(TINY, **change)
    with tempfile.TemporaryDirectory() as tmp:
        p = prepare_run(load_raw_run(synthetic_raw_run(TRUTH, spec).write(Path(tmp) / "r.dat")))
    assert [s.kind for s in p.segments if s.kept] == ["lateral", "longitudinal",
                                                      "longitudinal"] * 2
    _follow_the_truth(p.data, spec)
    if change.get("dwell_s"):
        assert p.dropped()["dwell"][1] > 4 * 2 * change["dwell_s"]
