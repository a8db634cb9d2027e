"""The command line through ``main(argv)``: laws, show, fit."""

from __future__ import annotations

import json

import pytest

from frictionlaws import list_laws
from frictionlaws.cli import main


def run(capsys, *argv):
    code = main(list(argv))
    out, err = capsys.readouterr()
    return code, out, err


def test_help_and_version(capsys):
    code, out, _ = run(capsys, "--help")
    assert code == 0 and "fit" in out and "show" in out
    code, out, _ = run(capsys, "--version")
    assert code == 0 and "frictionlaws" in out


def test_no_command_and_unknown_command(capsys):
    code, _, _ = run(capsys)
    assert code == 2
    code, _, err = run(capsys, "frobnicate")
    assert code == 2 and len(err.strip().splitlines()) == 1 and "Traceback" not in err


def test_laws_lists_every_law(capsys):
    code, out, _ = run(capsys, "laws")
    assert code == 0
    for law in list_laws():
        assert law.id in out
    code, out, _ = run(capsys, "laws", "--json")
    ids = {d["id"] for d in json.loads(out)}
    assert ids == {law.id for law in list_laws()}
    code, out, _ = run(capsys, "laws", "--family", "slip", "--json")
    assert all(d["family"] == "slip" for d in json.loads(out))


@pytest.mark.parametrize("law_id", [law.id for law in list_laws()])
def test_show_prints_every_part_of_the_declaration(capsys, law_id):
    code, out, _ = run(capsys, "show", law_id)
    assert code == 0
    for part in ("formula: mu = ", "parameters:", "settings:", "presets:", "domain:",
                 "references:", "evidence:"):
        assert part in out, (law_id, part)
    code, out, _ = run(capsys, "show", law_id, "--json")
    doc = json.loads(out)
    assert doc["id"] == law_id and doc["latex"].startswith(r"\mu")


def test_show_unknown_law_is_exit_2(capsys):
    code, _, err = run(capsys, "show", "thirio")
    assert code == 2 and "unknown law 'thirio'" in err and "thirion" in err


def test_fit_thirion_on_thesis_steel(capsys):
    code, out, _ = run(capsys, "fit", "--law", "thirion", "thesis-steel")
    assert code == 0
    lines = out.splitlines()
    a = next(x for x in lines if x.startswith("a "))
    b = next(x for x in lines if x.startswith("b "))
    assert len(a.split()) >= 4 and b.rstrip().endswith("1/Pa")
    assert "R^2 = " in out and "std. error" in out


def test_fit_json_has_the_documented_keys(capsys, tmp_path):
    save = tmp_path / "fit.json"
    code, out, _ = run(capsys, "fit", "--law", "thirion", "thesis-steel", "--json",
                       "--save", str(save))
    assert code == 0
    doc = json.loads(out)
    for key in ("law", "params", "metrics", "warnings"):
        assert key in doc
    for name in ("a", "b"):
        assert set(doc["params"][name]) >= {"value", "stderr", "unit"}
        assert doc["params"][name]["stderr"] > 0
    assert set(doc["metrics"]) >= {"r2", "rmse", "aic", "bic", "n"}
    assert doc["metrics"]["n"] == 19
    assert json.loads(save.read_text())["law"] == "thirion"


def test_fit_with_the_thesis_column_names(capsys):
    code, out, err = run(capsys, "fit", "--law", "thirion", "thesis-steel-original",
                         "--map", "mu=FC,p=CP,v=DV", "--units", "p=MPa,v=m/s", "--json")
    assert code == 0, err
    ref_code, ref_out, _ = run(capsys, "fit", "--law", "thirion", "thesis-steel", "--json")
    a, b = json.loads(out), json.loads(ref_out)
    assert a["params"]["b"]["value"] == pytest.approx(b["params"]["b"]["value"], rel=1e-9)


def test_fit_denny_free_E_v_names_parameters(capsys):
    code, out, _ = run(capsys, "fit", "--law", "denny", "thesis-steel", "--free", "E_v")
    assert code == 0
    assert "cannot determine b, E_v" in out


def test_fit_fix_option(capsys):
    code, out, _ = run(capsys, "fit", "--law", "schallamach", "thesis-steel", "--fix",
                       "n=0.3333", "--json")
    assert code == 0
    assert json.loads(out)["params"]["n"]["fixed"] is True


@pytest.mark.parametrize("argv,needle", [
    (["fit", "--law", "thirion", "thesis-steel", "--fix", "a"], "NAME=VALUE"),
    (["fit", "--law", "thirion", "thesis-steel", "--fix", "a=x"], "not a number"),
    (["fit", "--law", "thirion", "thesis-steel", "--free", "E_v"], "no setting 'E_v'"),
    (["fit", "thesis-steel"], "--law"),
])
def test_fit_usage_errors_are_one_line_exit_2(capsys, argv, needle):
    code, _, err = run(capsys, *argv)
    assert code == 2
    assert len(err.strip().splitlines()) == 1 and needle in err and "Traceback" not in err


def test_fit_temperature_aware_law_with_wlf_constants_freed(capsys, tmp_path):
    """``<law>+wlf`` by name, with C1 and C2 fitted from data at four temperatures (degC)."""
    import numpy as np

    from frictionlaws import get_law

    law = get_law("savkoor+wlf")
    rng = np.random.default_rng(0)
    n = 240
    v = np.exp(rng.uniform(np.log(1e-5), 0.0, n))
    T = rng.choice([273.15, 293.15, 313.15, 333.15], n)
    true = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": 0.0, "C1": 9.5, "C2": 110.0}
    mu = law(p=1e5, v=v, T=T, **true) + 0.01 * rng.standard_normal(n)
    path = tmp_path / "wlf.csv"
    lines = ["mu,p [MPa],v [m/s],T [degC]"]
    lines += [f"{m:.17g},0.1,{vv:.17g},{t - 273.15:.17g}" for m, vv, t in zip(mu, v, T)]
    path.write_text("\n".join(lines) + "\n")
    code, out, err = run(capsys, "fit", "--law", "savkoor+wlf", str(path), "--free", "C1,C2",
                         "--fix", "n=0", "--json")
    assert code == 0, err
    params = json.loads(out)["params"]
    for name in ("C1", "C2"):
        est = params[name]
        assert abs(est["value"] - true[name]) <= 3 * est["stderr"], (name, est)
    assert params["C2"]["unit"] == "K"


# ----------------------------------------------------- global flags, suggestions, warnings


@pytest.mark.parametrize("flag", ["-q", "--quiet", "-v", "--verbose", "--debug"])
def test_global_flags_are_accepted_after_the_command(flag, capsys):
    from frictionlaws.cli import main

    assert main(["fit", "--law", "thirion", "thesis-steel", "--json", flag]) == 0
    assert '"law"' in capsys.readouterr().out


def test_quiet_after_a_nested_command_drops_its_warnings(tmp_path, capsys):
    from frictionlaws.cli import main

    params = tmp_path / "t.json"
    assert main(["fit", "--law", "thirion", "thesis-steel", "--save", str(params)]) == 0
    capsys.readouterr()
    argv = ["tyre", "cornering", "--law", "thirion", "--params", str(params), "--loads",
            "2:6.5:3"]
    assert main(argv) == 0 and "warning:" in capsys.readouterr().err
    assert main([*argv, "-q"]) == 0 and "warning:" not in capsys.readouterr().err


def test_a_global_flag_as_an_options_value_stays_its_value():
    from frictionlaws.cli import _hoist_global_flags, build_parser

    parser = build_parser()
    argv = ["fit", "--law", "thirion", "x.csv", "--map", "-v", "-q"]
    assert _hoist_global_flags(parser, argv) == ["-q", *argv[:-1]]
    assert _hoist_global_flags(parser, ["fit", "--", "-q"]) == ["fit", "--", "-q"]


@pytest.mark.parametrize("argv,hint", [
    (["fitt"], "did you mean 'fit'?"),
    (["fit", "--law", "thirion", "thesis-steel", "--fixx", "a=1"], "did you mean '--fix'?"),
    (["fit", "--law", "thirion", "thesis-steel", "--uncertainty", "bootstrp"],
     "did you mean 'bootstrap'?"),
    (["fit", "--law", "thirio", "thesis-steel"], "did you mean thirion?"),
    (["export", "--law", "thirion", "--formta", "abaqus"], "did you mean '--format'"),
])
def test_a_misspelt_name_gets_a_suggestion(argv, hint, capsys):
    from frictionlaws.cli import main

    assert main(argv) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and hint in err


def test_long_warnings_are_cut_unless_verbose():
    from frictionlaws.cli import WARNING_WIDTH, _short

    text = "law x is extrapolated: " + "; ".join(f"clause {i} of the details" for i in range(30))
    short = _short(text)
    assert len(short) <= WARNING_WIDTH + 20 and short.endswith("(-v: in full)")
    assert text.startswith(short.rsplit(" ...", 1)[0])
    assert _short("short") == "short"


def test_export_prints_each_warning_once(tmp_path, capsys):
    from frictionlaws.cli import main

    out = tmp_path / "f.inp"
    assert main(["export", "--law", "thirion", "--fit", "thesis-steel", "--format", "abaqus",
                 "--p", "0.01MPa:0.5MPa", "-o", str(out)]) == 0
    text = capsys.readouterr()
    both = text.out + text.err
    assert both.count("residuals ordered by v") == 1
    assert "WARNING" not in both and "warning: fit: residuals" in text.out


def test_the_fit_reports_warnings_short_and_in_full_with_verbose(capsys):
    from frictionlaws.cli import WARNING_WIDTH, main

    assert main(["fit", "--law", "thirion", "thesis-steel"]) == 0
    short = [x for x in capsys.readouterr().out.splitlines() if x.startswith("warning: ")]
    assert main(["fit", "--law", "thirion", "thesis-steel", "-v"]) == 0
    full = [x for x in capsys.readouterr().out.splitlines() if x.startswith("warning: ")]
    assert len(short) == len(full) >= 1
    assert any(len(x) > WARNING_WIDTH + 20 for x in full)
    assert all(len(x) <= WARNING_WIDTH + 30 for x in short)
    assert "too narrow ... (-v: in full)" in short[-1] and "bootstrap" in full[-1]
