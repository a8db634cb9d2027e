"""``frictionlaws tyre``: cornering, thesis, mf, reduce."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.cli import main

EXAMPLES = Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"


def run(capsys, *argv):
    code = main(["tyre", *argv])
    out, err = capsys.readouterr()
    return code, out, err


def test_cornering_with_set_prints_units(capsys):
    code, out, err = run(capsys, "cornering", "--law", "coulomb", "--set", "mu0=0.9")
    assert code == 0, err
    assert "CS [kN/deg]" in out and "load [kN]" in out and "SI units" in out
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    loads = [float(r[0]) for r in rows]
    assert loads == [2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5]
    cs = np.array([float(r[1]) for r in rows])
    assert cs[-1] / cs[0] == pytest.approx(3.25, rel=2e-3)
    assert "CS(6.5 kN) / CS(2 kN) = 3.250" in out


def test_cornering_preset_and_json(capsys):
    code, out, _ = run(capsys, "cornering", "--law", "coulomb", "--preset", "thesis-fe-1.0",
                       "--loads", "2,4", "--angles", "1,3", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["loads_kN"] == [2.0, 4.0] and d["angles_deg"] == [1.0, 3.0]
    assert d["params"] == {"mu0": 1.0}
    assert len(d["cornering_stiffness_kN_per_deg"]) == 2


def test_cornering_load_units_and_tyre_options(capsys):
    code, out, _ = run(capsys, "cornering", "--law", "coulomb", "--set", "mu0=0.9",
                       "--loads", "2000:4000:3", "--load-unit", "N", "--width", "120 mm",
                       "--half-length", "6 cm", "--c-py", "9 N/mm^2", "--speed", "20 km/h",
                       "--pressure-shape", "uniform", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["loads_kN"] == [2.0, 3.0, 4.0]
    t = d["tyre"]
    assert t["width"] == pytest.approx(0.12) and t["half_length_ref"] == pytest.approx(0.06)
    assert t["c_py"] == pytest.approx(9e6) and t["speed"] == pytest.approx(20 / 3.6)
    assert t["pressure"] == "uniform"


def test_cornering_fit_and_params_file(capsys, tmp_path):
    code, out, err = run(capsys, "cornering", "--law", "thirion", "--fit", "thesis-steel",
                         "--loads", "2,6.5")
    assert code == 0
    assert "law fitted to thesis-steel" in out and "1/Pa" in out
    assert "extrapolated" in err  # the patch pressures exceed the data's 0.25 MPa
    saved = tmp_path / "thirion.json"
    assert main(["fit", "--law", "thirion", "thesis-steel", "--save", str(saved)]) == 0
    capsys.readouterr()
    code, out2, _ = run(capsys, "cornering", "--params", str(saved), "--loads", "2,6.5")
    assert code == 0
    table = [line for line in out.splitlines() if line.strip()[:1].isdigit()]
    table2 = [line for line in out2.splitlines() if line.strip()[:1].isdigit()]
    assert table == table2
    code, _, err = run(capsys, "cornering", "--params", str(saved), "--law", "coulomb")
    assert code == 2 and "does not match" in err


@pytest.mark.parametrize("argv, message", [
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--loads", "6:2:3"], "MIN is above MAX"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--loads", "a,b"], "not a number"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--loads", "2:6.5:0.5"],
     "not START:STOP:STEP; a step of 0.5 is 2:6.5:10"),
    (["cornering", "--law", "coulomb", "--preset", "thesis-fe-1.0", "--params", "x.json"],
     "not allowed with argument"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--loads=-1,2"], "positive"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--load-unit", "m"], "force"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--width", "3 s"], "length"),
    (["cornering", "--law", "coulomb", "--set", "mu0=0.9", "--c-py", "5 N"], "N/m^2"),
    (["cornering", "--law", "schallamach", "--preset", "hertz"], "F_N"),
    (["cornering", "--law", "nope", "--set", "a=1"], "unknown law"),
    (["cornering", "--set", "mu0=0.9"], "--law is required"),
    (["cornering", "--law", "coulomb"], "give the parameters: --preset NAME"),
    (["mf", "missing.tir"], "not found"),
    (["reduce", "MagicFormula62", "--law", "thirion", "--load", "4"], "sliding law"),
])
def test_bad_input_exits_2_with_one_line(capsys, argv, message):
    code, out, err = run(capsys, *argv)
    assert code == 2
    assert message in err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_thesis_command(capsys):
    code, out, err = run(capsys, "thesis")
    assert code == 0
    assert "Table 6-2" in out and "kN/deg" in out
    ratio_line = next(line for line in out.splitlines() if line.strip().startswith("ratio"))
    values = [float(x) for x in ratio_line.replace("|", " ").split()[1:]]
    assert values[0] == pytest.approx(3.25, abs=0.01)   # coulomb 0.9
    assert values[2] < 0.85 * values[0]                 # thirion fitted to thesis-steel
    assert values[3] == pytest.approx(2.648, abs=1e-3)  # thesis mu 0.9
    assert values[5] == pytest.approx(1.891, abs=1e-3)  # thesis S120
    assert "fit thirion (thesis-steel)" in out
    assert "extrapolated" in err


def test_mf_command(capsys):
    code, out, _ = run(capsys, "mf", str(EXAMPLES / "MagicFormula62_Parameters.json"),
                       "--loads", "3,6.752")
    assert code == 0
    assert "Magic Formula 6.2" in out and "FNOMIN 6752 N" in out and "mu_x peak" in out
    assert "1.1632" in out  # PDX1 at the nominal load
    code, out, _ = run(capsys, "mf", "MagicFormula52", "--json")
    d = json.loads(out)
    assert d["version"] == "5.2" and d["fnomin_N"] == 9416.6
    assert len(d["mu_x_peak"]) == 3


def test_mf_command_shows_the_aligning_moment_and_trail(capsys):
    from frictionlaws.tyre import MagicFormula

    code, out, _ = run(capsys, "mf", "MagicFormula61", "--loads", "3,6.752")
    assert code == 0
    assert "trail [mm]" in out and "Mz0 peak [N m]" in out and "at [deg]" in out
    code, out, _ = run(capsys, "mf", "MagicFormula61", "--loads", "3,6.752", "--json")
    d = json.loads(out)
    mf = MagicFormula.from_file("MagicFormula61")
    ref = mf.steady_state(0.0, 0.0, np.array([3000.0, 6752.0]))
    np.testing.assert_allclose(d["trail_m"], ref["t"], rtol=1e-12)
    at = np.radians(d["Mz0_peak_alpha_deg"])
    np.testing.assert_allclose(d["Mz0_peak_N_m"], mf.mz0(at, np.array([3000.0, 6752.0])),
                               rtol=1e-12)
    # the peak: no slip angle on a finer grid gives a larger moment (within the grid step)
    fine = mf.mz0(np.radians(np.linspace(-20, 20, 4001))[:, None], np.array([3000.0, 6752.0]))
    assert np.all(np.abs(fine).max(axis=0) <= np.abs(d["Mz0_peak_N_m"]) * 1.001)
    assert f"{d['trail_m'][1] * 1000:.2f}" in run(capsys, "mf", "MagicFormula61", "--loads",
                                                  "3,6.752")[1]


def test_reduce_command(capsys, tmp_path):
    saved = tmp_path / "reduced.json"
    code, out, _ = run(capsys, "reduce", "MagicFormula62", "--law", "pacejka", "--load", "4",
                       "--save", str(saved))
    assert code == 0
    assert "reduced to law 'pacejka'" in out and "RMSE" in out and "(Magic Formula:" in out
    doc = json.loads(saved.read_text())
    assert doc["law"] == "pacejka" and doc["format"] == "frictionlaws-fit-result"
    code, out, _ = run(capsys, "reduce", str(EXAMPLES / "MagicFormula52_Parameters.json"),
                       "--law", "burckhardt", "--load", "5000", "--load-unit", "N", "--json")
    assert code == 0
    d = json.loads(out)
    assert d["load_N"] == 5000.0 and d["errors"]["rmse"] > 0


def test_cornering_refuses_fit_options_without_fit(capsys):
    from frictionlaws.cli import main

    assert main(["tyre", "cornering", "--law", "thirion", "--set", "a=0.2,b=3e-6",
                 "--fix", "a=0.2"]) == 2
    assert "--fix is not used without --fit" in capsys.readouterr().err


@pytest.mark.parametrize(("argv", "message"), [
    (["--load", "0"], "--load '0': loads must be positive"),
    (["--load", "4", "--load-unit", "m"], "--load-unit m: unit 'm' is a length"),
])
def test_reduce_load_errors_name_the_flag_typed(capsys, argv, message):
    from pathlib import Path

    from frictionlaws.cli import main

    tir = (Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"
           / "MagicFormula61_Parameters.converted.tir")
    assert main(["tyre", "reduce", str(tir), *argv]) == 2
    assert message in capsys.readouterr().err


@pytest.mark.slow
def test_fit_mf_reads_its_data_from_standard_input(capsys, tmp_path, monkeypatch):
    import io

    from test_tyre_fit_mf import synthetic, write_csv

    _, data, _ = synthetic("MagicFormula61", n_slip=15)
    csv = write_csv(tmp_path / "data.csv", data)
    from_file, from_stdin = tmp_path / "file.tir", tmp_path / "stdin.tir"
    assert main(["tyre", "fit-mf", str(csv), "--fittyp", "61", "-o", str(from_file)]) == 0
    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO(csv.read_bytes())))
    assert main(["tyre", "fit-mf", "-", "--fittyp", "61", "-o", str(from_stdin)]) == 0
    capsys.readouterr()
    coefficients = [ln for ln in from_file.read_text().splitlines() if "=" in ln
                    and not ln.startswith(("!", "$"))]
    assert coefficients == [ln for ln in from_stdin.read_text().splitlines() if "=" in ln
                            and not ln.startswith(("!", "$"))]
    first = from_stdin.read_text().splitlines()[0]
    assert "from <stdin>" in first and "frictionlaws-stdin-" not in first


def test_fit_mf_from_standard_input_that_fits_nothing_names_standard_input(
        capsys, tmp_path, monkeypatch):
    import io

    lines = ["Fz [N],kappa [-],alpha [deg],Fx [N],Fy [N]"]
    lines += [f"6752,{k},{a},{3000 * k / 0.1},{-400 * a}" for k in (0.05, 0.1)
              for a in (4.0, 8.0)]
    monkeypatch.setattr("sys.stdin", io.TextIOWrapper(io.BytesIO("\n".join(lines).encode())))
    target = tmp_path / "out.tir"
    code, _, err = run(capsys, "fit-mf", "-", "-o", str(target))
    assert code == 1 and "<stdin>: nothing could be fitted" in err
    assert "frictionlaws-stdin-" not in err and not target.exists()


@pytest.mark.parametrize("fittyp,template", [(62, "MagicFormula52"), (61, "MagicFormula52"),
                                             (5, "MagicFormula61"), (6, "MagicFormula62")])
def test_fit_mf_refuses_a_template_of_the_other_magic_formula_family(
        capsys, tmp_path, fittyp, template):
    target = tmp_path / "out.tir"
    assert main(["examples", str(tmp_path / "ex")]) == 0
    capsys.readouterr()
    code, _, err = run(capsys, "fit-mf", str(tmp_path / "ex" / "tyre_data.csv"), "--fittyp",
                       str(fittyp), "--template", template, "-o", str(target))
    assert code == 2 and "the template is Magic Formula" in err and len(err.splitlines()) == 1
    assert not target.exists()


@pytest.mark.parametrize("name,match", [("out.json", "suffix .tir"), ("out", "suffix .tir"),
                                        ("adir/", "ends with a slash")])
def test_fit_mf_writes_only_a_tir_file_name(capsys, tmp_path, name, match):
    assert main(["examples", str(tmp_path / "ex")]) == 0
    capsys.readouterr()
    before = sorted(p.name for p in tmp_path.iterdir())
    target = str(tmp_path / name) + ("/" if name.endswith("/") else "")
    code, _, err = run(capsys, "fit-mf", str(tmp_path / "ex" / "tyre_data.csv"), "-o", target)
    assert code == 2 and match in err
    assert sorted(p.name for p in tmp_path.iterdir()) == before


def test_thesis_refuses_a_law_given_twice(capsys):
    code, out, err = run(capsys, "thesis", "--laws", "thirion,thirion")
    assert code == 2 and "given twice" in err and "thirion" in err and not out


@pytest.mark.parametrize(("options", "named"), [
    (["--boot", "50"], "--boot is"), (["--seed", "3"], "--seed is"),
    (["--boot-jobs", "2", "--seed", "1"], "--boot-jobs, --seed are")])
def test_fit_mf_refuses_bootstrap_options_without_sweeps(capsys, tmp_path, options, named):
    target = tmp_path / "out.tir"
    code, out, err = run(capsys, "fit-mf", str(tmp_path / "absent.csv"), "-o", str(target),
                         *options)
    assert code == 2 and not out and len(err.splitlines()) == 1
    assert named in err and "--uncertainty sweeps only" in err
    assert not target.exists()


def test_mf_coefficients_refuses_loads(capsys):
    code, out, err = run(capsys, "mf", "MagicFormula61", "--coefficients", "--loads", "4")
    assert code == 2 and not out and "--loads is not used with --coefficients" in err
