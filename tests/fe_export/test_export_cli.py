"""``frictionlaws export`` on the command line: outputs, parameter sources, errors."""

from __future__ import annotations

import json
import re

import pytest

from frictionlaws.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_abaqus_table_in_mm_n_s(tmp_path, capsys):
    out_file = tmp_path / "fric.inp"
    code, out, err = run(capsys, "export", "--law", "thesis-poly2", "--preset", "steel",
                         "--format", "abaqus", "--p", "0.03:0.25", "--v", "0:2770",
                         "--units", "mm-N-s", "--tol", "0.005", "-o", str(out_file))
    assert code == 0, err
    text = out_file.read_text()
    assert "*FRICTION" in text and "** units: mm-N-s (p MPa, v mm/s)" in text
    assert f"wrote {out_file}" in out and "max interpolation error" in out


@pytest.mark.parametrize("argv,message", [
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "csv", "--p", "0.1-0.5"],
     "expected MIN:MAX"),
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "nastran", "--p", "0:1"],
     "invalid choice: 'nastran'"),
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "abaqus"],
     "depends on p (contact pressure); give its range: --p MIN:MAX[:N]"),
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "abaqus-decay"],
     "cannot represent it exactly. Fit 'exponential-decay'"),
    (["--law", "savkoor", "--format", "csv", "--p", "0:1", "--v", "0:1"],
     "give the parameters"),
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "csv", "--p",
      "1furlong:2furlong"], "--p"),
    (["--law", "thirion", "--set", "a=1,b=1e-6", "--format", "csv", "--p", "0:1",
      "--spacing", "p=log"], "log spacing of p needs MIN > 0"),
    (["--law", "park", "--set", "n=0.1,mu_s=.5,mu_m=1.2,h10=.3,v_m=.01", "--format",
      "lsdyna", "--p", "1e4:1e5", "--v", "0.01:1"], "depends on T"),
    (["--law", "park", "--set", "n=0.1,mu_s=.5,mu_m=1.2,h10=.3,v_m=.01", "--format",
      "lsdyna", "--p", "0:1", "--v", "0:1"], "gives mu = nan at p = 0 Pa, v = 0 m/s"),
    (["--law", "nosuchlaw", "--set", "a=1", "--format", "csv"], "unknown law 'nosuchlaw'"),
])
def test_bad_input_exits_2_with_one_line(argv, message, tmp_path, capsys):
    code, out, err = run(capsys, "export", *argv, "-o", str(tmp_path / "x"))
    assert code == 2
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: ")
    assert message in lines[0]
    assert not (tmp_path / "x").exists()


def test_plain_params_json(tmp_path, capsys):
    pfile = tmp_path / "p.json"
    pfile.write_text(json.dumps({"law": "thirion", "params": {"a": 0.5, "b": 2e-6}}))
    code, out, err = run(capsys, "export", "--params", str(pfile), "--format", "json",
                         "--p", "0:1:11", "--units", "mm-N-s", "-o", str(tmp_path / "g.json"))
    assert code == 0, err
    doc = json.loads((tmp_path / "g.json").read_text())
    assert doc["law"] == "thirion" and doc["units"]["p"] == "MPa"
    assert doc["parameters"]["b"]["value"] == 2e-6
    assert doc["mu"][0] == pytest.approx(2.0)


def test_saved_fit_result_as_params(tmp_path, capsys):
    saved = tmp_path / "fit.json"
    code, out, err = run(capsys, "fit", "--law", "thesis-poly2", "thesis-steel",
                         "--save", str(saved))
    assert code == 0, err
    out_file = tmp_path / "f.rad"
    code, out, err = run(capsys, "export", "--params", str(saved), "--format", "radioss",
                         "--units", "mm-N-s", "-o", str(out_file))
    assert code == 0, err
    text = re.sub(r"\n#\s*", " ", out_file.read_text())
    assert "exact: Ifric 1" in text
    assert f"parameters from: file {saved}".replace(" ", "") in text.replace(" ", "")
    assert "standard error" in text
    # the saved law must match --law when both are given
    code, out, err = run(capsys, "export", "--law", "thirion", "--params", str(saved),
                         "--format", "radioss", "-o", str(out_file))
    assert code == 2 and "--law thirion does not match the law in the file" in err


def test_fit_then_export(tmp_path, capsys):
    out_file = tmp_path / "grid.csv"
    code, out, err = run(capsys, "export", "--law", "thesis-poly2", "--fit", "thesis-steel",
                         "--format", "csv", "--p", "0.03MPa:0.25MPa:5", "--v", "0:2.77:4",
                         "-o", str(out_file))
    assert code == 0, err
    text = out_file.read_text()
    assert "# parameters from: fit to thesis-steel (n = 19" in text
    assert "+/-" in text


def test_stdout_output_and_fortran_without_box(tmp_path, capsys):
    code, out, err = run(capsys, "export", "--law", "exponential-decay", "--preset",
                         "rubber-steel", "--format", "abaqus-vfric-coef", "--units", "mm-N-s",
                         "-o", "-")
    assert code == 0, err
    assert "subroutine vfric_coef" in out and "wrote (not written)" in err


def test_temperature_in_degc(tmp_path, capsys):
    out_file = tmp_path / "park.inp"
    code, out, err = run(capsys, "export", "--law", "park", "--set",
                         "n=0.11,mu_s=0.5,mu_m=1.2,h10=0.3,v_m=0.01", "--format", "abaqus",
                         "--p", "0.02:1:4", "--v", "1:3000:6", "--T", "0:50:3",
                         "--units", "mm-N-s,T=degC", "-o", str(out_file))
    assert code == 0, err
    text = out_file.read_text()
    assert "T degC" in text
    rows = [ln for ln in text.splitlines() if ln and not ln.startswith("*")]
    temps = sorted({float(r.split(",")[3]) for r in rows})
    assert temps == pytest.approx([0.0, 25.0, 50.0])


def test_help_documents_range_syntax(capsys):
    code, out, err = run(capsys, "export", "--help")
    assert code == 0
    assert "MIN:MAX:N" in out and "10kPa:0.5MPa:20" in out and "mm-N-s" in out


def test_export_json_summary_is_strict_and_names_the_error(tmp_path, capsys):
    out = tmp_path / "deck.inp"
    code = main(["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "abaqus",
                 "--p", "0.01:0.5:5", "-o", str(out), "--json"])
    assert code == 0
    doc = json.loads(capsys.readouterr().out, parse_constant=lambda c: pytest.fail(c))
    assert doc["path"] == str(out) and doc["format"] == "abaqus" and doc["rows"] == 5
    assert 0 < doc["max_error"] < 0.05 and doc["units"]
    assert "\n*FRICTION" in out.read_text()
    assert main(["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "abaqus",
                 "--p", "0.01:0.5:5", "-o", "-", "--json"]) == 2
    assert "give -o FILE" in capsys.readouterr().err


def _two_surfaces(path, rows_s120=8):
    import numpy as np

    rng = np.random.default_rng(1)
    lines = ["mu,p [MPa],surface"]
    for surface, a, n in (("steel", 0.3, 8), ("S 120", 0.2, rows_s120)):
        for p in np.linspace(0.03, 0.25, n):
            mu = 1 / (a + 3e-6 * p * 1e6) + 0.01 * rng.standard_normal()
            lines.append(f"{mu:.5f},{p:.4f},{surface}")
    path.write_text("\n".join(lines) + "\n")


def test_export_fit_by_group_writes_one_deck_per_group(tmp_path, capsys):
    data = tmp_path / "two.csv"
    _two_surfaces(data)
    out = tmp_path / "deck.inp"
    argv = ["export", "--law", "thirion", "--fit", str(data), "--format", "abaqus",
            "--p", "30000:250000:6", "-o", str(out)]
    assert main(argv) == 2  # pooled over two surfaces: refused, naming --by
    assert "--by surface" in capsys.readouterr().err
    assert main([*argv, "--by", "surface", "--json"]) == 0
    docs = json.loads(capsys.readouterr().out)
    assert [d["path"] for d in docs] == [str(tmp_path / "deck_steel.inp"),
                                         str(tmp_path / "deck_S-120.inp")]
    steel, s120 = ((tmp_path / n).read_text() for n in ("deck_steel.inp", "deck_S-120.inp"))
    assert "surface=steel" in steel and "surface=S 120" in s120
    first = [ln for ln in steel.splitlines() if ln and ln[0].isdigit()][0]
    other = [ln for ln in s120.splitlines() if ln and ln[0].isdigit()][0]
    assert first != other  # two fits, two tables
    assert not out.exists()


def test_export_fit_by_group_writes_nothing_when_a_group_fails(tmp_path, capsys):
    data = tmp_path / "two.csv"
    _two_surfaces(data, rows_s120=1)
    code = main(["export", "--law", "thirion", "--fit", str(data), "--by", "surface",
                 "--format", "abaqus", "--p", "30000:250000:6", "-o", str(tmp_path / "d.inp")])
    assert code in (1, 2)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["two.csv"]


@pytest.mark.parametrize(("argv", "message"), [
    # a formula card the solver evaluates everywhere: checked on the box like a table
    (["--law", "quadratic-pv", "--set", "c0=0.5,c1=-1e-5,c2=0,c3=0,c4=0,c5=0",
      "--format", "radioss", "--p", "0:1MPa", "--v", "0:1"], "mu = -"),
    # a typed-in coefficient no rubber has
    (["--law", "coulomb", "--set", "mu0=1e6", "--format", "abaqus"], "in 0..10"),
    # a friction level of a formula card reached at high slip rates
    (["--law", "exponential-decay", "--set", "mu_s=1.4,mu_d=9000,v_c=2e4",
      "--format", "abaqus-decay"], "mu_k = 9000"),
])
def test_export_refuses_mu_no_deck_should_hold(tmp_path, capsys, argv, message):
    out = tmp_path / "deck.txt"
    assert main(["export", *argv, "-o", str(out)]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize("flag,value", [("--lsdyna-table-id", "-5"),
                                        ("--lsdyna-table-id", "99999999999"),
                                        ("--ansys-mat", "0"), ("--radioss-id", "-7")])
def test_solver_ids_outside_their_fields_are_refused(tmp_path, capsys, flag, value):
    out = tmp_path / "deck.k"
    code = main(["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "lsdyna",
                 "--p", "0.01MPa:0.5MPa:5", "-o", str(out), flag, value])
    assert code == 2 and not out.exists()
    assert "whole number from" in capsys.readouterr().err


@pytest.mark.parametrize("options,message", [({"ansys_mat": 1.5}, "whole number"),
                                             ({"bogus": 1}, "unknown export option"),
                                             ({"ansys_mat": "abc"}, "whole number"),
                                             ({"lsdyna_table_id": 5},
                                              "does not apply to format ansys")])
def test_api_export_options_are_checked(options, message):
    from frictionlaws.base.errors import InputError
    from frictionlaws.fe_export import export

    with pytest.raises(InputError, match=message):
        export("thirion", {"a": 0.3, "b": 3e-6}, "ansys", box={"p": (1e4, 5e5)},
               options=options)


def test_radioss_approximation_that_misses_the_tolerance_is_refused(tmp_path, capsys):
    out = tmp_path / "r.rad"
    argv = ["export", "--law", "thirion", "--set", "a=0.15,b=4e-6", "--format", "radioss",
            "--p", "0.01MPa:0.5MPa", "-o", str(out)]
    assert main([*argv, "--tol", "0.01"]) == 2
    assert "more than the tolerance 0.01" in capsys.readouterr().err and not out.exists()
    assert main(argv) == 0 and "APPROXIMATION" in out.read_text()


def test_a_range_the_law_does_not_use_is_refused_in_the_api_and_named_on_the_cli(tmp_path,
                                                                                  capsys):
    from frictionlaws.base.errors import InputError
    from frictionlaws.fe_export import export

    with pytest.raises(InputError, match="does not depend on v") as info:
        export("thirion", {"a": 0.3, "b": 3e-6}, "csv", box={"p": (1e4, 5e5), "v": (0, 1)})
    assert info.value.option == "box.v"
    assert main(["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "csv",
                 "--p", "0.01:0.5", "--v", "0:1", "-o", str(tmp_path / "x.csv")]) == 2
    assert capsys.readouterr().err.startswith("error: --v: law 'thirion' does not depend on v")


def test_a_fit_that_cannot_determine_its_parameters_exports_nothing(tmp_path, capsys):
    """One pressure: thirion's a and b trade off, so a deck over 0.01..0.5 MPa is arbitrary."""
    import frictionlaws as fl

    data = tmp_path / "one_p.csv"
    data.write_text("mu,p [MPa],v [m/s]\n1.10,0.03,0.5\n1.12,0.03,1.0\n1.09,0.03,1.5\n")
    deck = tmp_path / "f.inp"
    code = main(["export", "--law", "thirion", "--fit", str(data), "--format", "abaqus",
                 "--p", "0.01MPa:0.5MPa", "-o", str(deck)])
    err = [line for line in capsys.readouterr().err.splitlines() if line.startswith("error")]
    assert code == 2 and not deck.exists()
    assert len(err) == 1 and "cannot determine a, b" in err[0] and "--fix a=VALUE" in err[0]
    res = fl.fit("thirion", str(data))
    assert res.bound.undetermined == ("a", "b") and res.bound.to_dict()["undetermined"] == [
        "a", "b"]
    with pytest.raises(fl.InputError, match=r"cannot determine a, b.*fix='a=VALUE'"):
        fl.export(res.bound, format="csv", box={"p": (1e4, 5e5)})
    # holding b, the data determine a: the deck is written
    assert main(["export", "--law", "thirion", "--fit", str(data), "--fix", "b=2e-6",
                 "--format", "abaqus", "--p", "0.01MPa:0.5MPa", "-o", str(deck)]) == 0
    assert deck.exists()
