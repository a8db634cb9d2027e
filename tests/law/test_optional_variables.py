"""Optional variables: Burckhardt's vehicle speed v drops out at c4 = 0 (declared once).

Slip-only (s, mu) data and preset evaluations need no v; fit, compare and export
derive this from the law's declaration; the variable's meaning is the law's own.
"""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from frictionlaws import fit, get_law
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.law import Law, Param

S = np.linspace(0.0, 1.0, 200_001)
# laws.md: Burckhardt derived peaks (slip, mu), computed there with v = 0
PEAKS = {"asphalt-dry": (0.170, 1.17), "asphalt-wet": (0.131, 0.80),
         "concrete-dry": (0.160, 1.09), "cobblestone-dry": (0.400, 1.00),
         "cobblestone-wet": (0.140, 0.38), "snow": (0.060, 0.19)}


@pytest.mark.parametrize("road", sorted(PEAKS))
def test_preset_peaks_hold_without_v(road):
    law = get_law("burckhardt")
    mu = law(s=S, preset=road)  # no v: the presets have c4 = 0
    i = int(np.argmax(mu))
    assert S[i] == pytest.approx(PEAKS[road][0], abs=0.01)
    assert mu[i] == pytest.approx(PEAKS[road][1], abs=0.01)
    np.testing.assert_array_equal(mu, law(s=S, v=25.0, preset=road))
    assert law.bind(preset=road)(S[::1000]) == pytest.approx(mu[::1000])


def test_v_is_required_as_soon_as_c4_acts():
    law = get_law("burckhardt")
    with pytest.raises(InputError, match=r"needs variable\(s\) v \(vehicle \(wheel-centre\) "
                       r"speed \[m/s\]\), optional only when c4 = 0 \(here c4 = 0.02\)"):
        law(s=0.2, preset="asphalt-dry", c4=0.02)
    assert law(s=0.2, v=10.0, preset="asphalt-dry", c4=0.02) == pytest.approx(
        law(s=0.2, preset="asphalt-dry") * np.exp(-0.2))
    assert law.required_variables() == ("s",)
    assert law.required_variables({"c4": 0.02}) == ("s", "v")
    assert law.neutral_fixes({"s"}) == {"c4": 0.0} and law.neutral_fixes({"s", "v"}) == {}


def test_labels_are_per_law():
    burck = get_law("burckhardt")
    assert burck.meaning("v") == "vehicle (wheel-centre) speed"
    from frictionlaws import list_laws

    sliding = [law for law in list_laws() if law.family == "sliding" and "v" in law.variables]
    assert sliding and all(law.meaning("v") == "sliding velocity (magnitude)" for law in sliding)
    summary = burck.summary()
    assert summary["variable_meanings"]["v"] == "vehicle (wheel-centre) speed"
    assert summary["optional_variables"] == {"v": {"parameter": "c4", "neutral": 0.0}}


def test_show_names_the_vehicle_speed(capsys):
    assert main(["show", "burckhardt"]) == 0
    out = capsys.readouterr().out
    line = next(x for x in out.splitlines() if x.startswith("variables:"))
    assert "v [m/s] (vehicle (wheel-centre) speed; optional when c4 = 0)" in line
    assert "sliding velocity" not in line


def test_declaration_is_checked():
    def f(m, s, v, a, b):
        return a * s + b * v

    params = (Param("a", "", 1.0), Param("b", "s/m", 0.0, (0.0, 1.0)))
    with pytest.raises(ValueError, match="unknown parameter 'c'"):
        Law("x", "x", "slip", ("s", "v"), params, f, optional_variables={"v": ("c", 0.0)})
    with pytest.raises(ValueError, match="outside its bounds"):
        Law("x", "x", "slip", ("s", "v"), params, f, optional_variables={"v": ("b", -1.0)})
    with pytest.raises(ValueError, match="is not a variable"):
        Law("x", "x", "slip", ("s", "v"), params, f, optional_variables={"p": ("b", 0.0)})
    ok = Law("x", "x", "slip", ("s", "v"), params, f, optional_variables={"v": ("b", 0.0)})
    assert ok(s=0.5, a=2.0, b=0.0) == 1.0


@pytest.fixture()
def slip_csv(tmp_path):
    law = get_law("burckhardt")
    s = np.linspace(0.01, 1.0, 40)
    mu = law(s=s, preset="asphalt-wet") + np.random.default_rng(1).normal(0, 0.003, s.size)
    path = tmp_path / "slip.csv"
    pd.DataFrame({"s": s, "mu": mu}).to_csv(path, index=False)
    return path


def test_fit_on_slip_only_data(slip_csv, capsys):
    res = fit("burckhardt", pd.read_csv(slip_csv))
    assert res.params["c4"].value == 0.0 and res.params["c4"].fixed
    for k, v in get_law("burckhardt").presets["asphalt-wet"].items():
        assert res.params[k].value == pytest.approx(v, rel=0.05)
    assert any("have no v (vehicle (wheel-centre) speed): c4 fixed at 0" in n
               for n in res.notes)
    assert res.predict(s=np.array([0.1, 0.2])).shape == (2,)
    code = main(["fit", "--law", "burckhardt", str(slip_csv)])
    out = capsys.readouterr().out
    assert code == 0 and "c4 fixed at 0" in out and "R^2" in out
    code = main(["fit", "--law", "burckhardt", str(slip_csv), "--fix", "c4=0.02"])
    err = capsys.readouterr().err
    assert code == 2 and "can only be fitted with c4 = 0" in err


def test_compare_on_slip_only_data(slip_csv, capsys):
    code = main(["compare", "--laws", "burckhardt,burckhardt-sqrt", str(slip_csv), "--json"])
    out = capsys.readouterr().out
    assert code == 0, out
    assert "burckhardt" in json.dumps(json.loads(out))


def test_export_without_v(tmp_path, capsys):
    out = tmp_path / "grid.csv"
    code = main(["export", "--law", "burckhardt", "--preset", "asphalt-dry", "--format",
                 "csv", "--s", "0:1", "-o", str(out)])
    assert code == 0, capsys.readouterr().err
    text = out.read_text()
    assert "v (vehicle (wheel-centre) speed) left out: it drops out of the law at c4 = 0" in \
        " ".join(line.lstrip("# ") for line in text.splitlines())
    table = pd.read_csv(out, comment="#")
    assert list(table.columns) == ["s [-]", "mu [-]"]
    law = get_law("burckhardt")
    np.testing.assert_allclose(table["mu [-]"].iloc[[0, -1]],
                               law(s=table["s [-]"].iloc[[0, -1]].to_numpy(),
                                   preset="asphalt-dry"), atol=1e-9)
    code = main(["export", "--law", "burckhardt", "--preset", "asphalt-dry", "--set",
                 "c4=0.02", "--format", "csv", "--s", "0:1", "-o", str(tmp_path / "b.csv")])
    err = capsys.readouterr().err
    assert code == 2 and "v (vehicle (wheel-centre) speed)" in err and "--v" in err
