"""The one CLI path from --preset/--set/--params/--fit to a BoundLaw, and the CLI's words."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from frictionlaws.cli import main

ROOT = Path(__file__).resolve().parents[2] / "frictionlaws"


def run(capsys: pytest.CaptureFixture[str], *argv: str) -> tuple[int, str, str]:
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


@pytest.fixture(scope="module")
def saved(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("fit") / "thirion.json"
    assert main(["fit", "--law", "thirion", "thesis-steel", "--save", str(path)]) == 0
    return path


def test_show_with_values_prints_the_bound_law(capsys, saved) -> None:
    code, out, _ = run(capsys, "show", "coulomb", "--set", "mu0=0.8")
    assert code == 0
    assert "bound values (from given values; SI):" in out and "mu0      = 0.8 -" in out
    code, out, _ = run(capsys, "show", "thirion", "--params", str(saved))
    assert code == 0
    assert f"bound values (from file {saved}; SI):" in out
    assert re.search(r"b\s+= 4\.7\d+e-06 1/Pa \+/- ", out)
    assert "derived at these values: mu_0 = " in out and "fitted on: p " in out
    code, out, _ = run(capsys, "show", "thirion")
    assert code == 0 and "bound values" not in out


def test_show_json_with_a_preset(capsys) -> None:
    from frictionlaws.law.registry import get_law

    preset = next(iter(get_law("exponential-decay").presets))
    code, out, _ = run(capsys, "show", "exponential-decay", "--preset", preset,
                       "--set", "mu_d=0.5", "--json")
    assert code == 0
    doc = json.loads(out)
    assert doc["bound"]["values"]["mu_d"]["value"] == 0.5
    assert doc["bound"]["source"]["text"] == f"preset '{preset}' with given values"


@pytest.mark.parametrize(("argv", "message"), [
    (["show", "thirion", "--params", "PARAMS", "--set", "a=1"],
     "--set cannot be combined with --params"),
    (["show", "coulomb", "--params", "PARAMS"], "--law coulomb does not match the law"),
    (["show", "thirion", "--set", "a=-1,b=1e-6"], "outside its bounds"),
    (["show", "thirion", "--preset", "nope"], "has no preset 'nope'"),
    (["export", "--format", "csv", "--p", "0:1", "-o", "OUT"], "--law is required"),
    (["export", "--law", "thirion", "--fit", "thesis-steel", "--set", "a=1", "--format",
      "csv", "--p", "0:1", "-o", "OUT"], "--set cannot be combined with --fit"),
    (["tyre", "cornering", "--law", "thirion", "--fit", "thesis-steel", "--set", "a=1"],
     "--set cannot be combined with --fit"),
    (["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9", "--map", "mu=FC"],
     "--map is not used without --fit"),
])
def test_law_source_errors_are_one_line(capsys, saved, tmp_path, argv, message) -> None:
    argv = [str(saved) if a == "PARAMS" else str(tmp_path / "o.csv") if a == "OUT" else a
            for a in argv]
    code, out, err = run(capsys, *argv)
    assert code == 2, err
    assert message in err and err.count("\n") == 1 and err.startswith("error: ")


def test_export_set_over_a_preset(capsys, tmp_path) -> None:
    from frictionlaws.law.registry import get_law

    preset = next(iter(get_law("exponential-decay").presets))
    out = tmp_path / "d.csv"
    code, _, err = run(capsys, "export", "--law", "exponential-decay", "--preset", preset,
                       "--set", "mu_d=0.5", "--format", "csv", "--v", "0:1:3", "-o", str(out))
    assert code == 0, err
    text = out.read_text()
    assert f"parameters from: preset '{preset}' with given values" in text
    assert "mu_d = 0.5 " in text


def test_tyre_loads_use_the_one_range_grammar(capsys) -> None:
    base = ["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9", "--json"]
    code, out, err = run(capsys, *base, "--loads", "2:6:5")
    assert code == 0 and json.loads(out)["loads_kN"] == [2.0, 3.0, 4.0, 5.0, 6.0]
    assert "warning" not in err
    code, out, err = run(capsys, *base, "--loads", "2kN:4kN:3")
    assert code == 0 and json.loads(out)["loads_kN"] == [2.0, 3.0, 4.0]
    # an integer third number that also reads as an old step: used as a count, flagged
    code, out, err = run(capsys, *base, "--loads", "2:6:2")
    assert code == 0 and json.loads(out)["loads_kN"] == [2.0, 6.0]
    assert "is MIN:MAX:N, 2 loads; for a step of 2 write 2:6:3" in err
    code, _, err = run(capsys, *base, "--loads", "2:6.5:0.5")
    assert code == 2 and "a step of 0.5 is 2:6.5:10" in err
    code, out, _ = run(capsys, "tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9")
    rows = [line.split() for line in out.splitlines() if line.strip()[:1].isdigit()]
    assert [float(r[0]) for r in rows] == [2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5]


def test_export_data_units_are_named_by_the_export_flag(capsys, tmp_path) -> None:
    data = tmp_path / "d.csv"
    data.write_text("mu,p\n0.5,0.1\n0.6,0.2\n0.55,0.3\n")
    code, _, err = run(capsys, "export", "--law", "thirion", "--fit", str(data), "--format",
                       "csv", "--p", "0.1:0.3", "--data-units", "p=MPa,v=m/s",
                       "-o", str(tmp_path / "o.csv"))
    assert code == 2
    assert "--data-units v=m/s: the file has no 'v' column" in err


def test_the_library_does_not_quote_cli_flags() -> None:
    """Messages outside frictionlaws/cli/ name arguments; flags are the CLI's words."""
    flag = re.compile(r"""f?["'][^"'\n]*?(?<![-\w])--(map|units|area|p|v|T|F_N|s|set|fix|"""
                      r"""preset|params|fit|loads|data-units)\b""")
    offenders = []
    files = [*sorted((ROOT / "io").glob("*.py")), ROOT / "base" / "errors.py",
             ROOT / "law" / "bound.py",
             ROOT / "fe_export" / "api.py"]
    assert len(files) > 4
    for path in files:
        for n, line in enumerate(path.read_text().splitlines(), 1):
            if flag.search(line):
                offenders.append(f"{path.relative_to(ROOT)}:{n}: {line.strip()}")
    assert not offenders, "\n".join(offenders)


@pytest.mark.parametrize("argv", [
    ["tyre", "fit-mf", "x.csv", "-o", "y.tir", "--boot-jobs", "0"],
    ["fit", "x.csv", "--law", "coulomb", "--jobs", "0"],
    ["process", "m.toml", "--jobs", "2000"]])
def test_a_worker_count_out_of_range_says_what_minus_one_means(argv, capsys) -> None:
    """Every worker-count option refuses alike, saying what -1 means (one parser)."""
    assert main(argv) == 2
    err = capsys.readouterr()[1]
    assert "expected a whole number from 1 to 1024, or -1 for one per core" in err
