"""Display units of result views: MPa by default, SI one argument away, one dimensionless."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.display import (
    DIMENSIONLESS,
    display_param_unit,
    group_label,
    parameter_table,
)
from frictionlaws.base.errors import InputError


@pytest.fixture(scope="module")
def thirion():
    return fl.fit("thirion", "thesis-steel")


def test_the_frame_shows_b_in_one_over_mpa_and_si_on_request(thirion) -> None:
    shown, si = thirion.to_frame(), thirion.to_frame(units="si")
    assert shown.loc["b", "unit"] == "1/MPa" and si.loc["b", "unit"] == "1/Pa"
    assert shown.loc["a", "unit"] == si.loc["a", "unit"] == DIMENSIONLESS
    for col in ("value", "stderr", "ci95_low", "ci95_high"):
        assert shown.loc["b", col] == pytest.approx(si.loc["b", col] * 1e6, rel=1e-12)
        assert shown.loc["a", col] == si.loc["a", col]
    assert 3.0 < shown.loc["b", "value"] < 7.0  # ~4.7 1/MPa, not 4.7e-06
    with pytest.raises(InputError, match="'display' or 'si'"):
        thirion.to_frame(units="MPa")


def test_the_plot_has_pressure_in_mpa(thirion) -> None:
    import matplotlib.pyplot as plt

    fig = thirion.plot()
    assert fig.axes[1].get_xlabel() == "p [MPa]"
    lo, hi = fig.axes[0].get_xlim()
    assert 0.0 < lo and hi < 0.3
    plt.close(fig)
    fig = thirion.plot(units="si")
    assert fig.axes[1].get_xlabel() == "p [Pa]" and fig.axes[0].get_xlim()[1] > 2e5
    plt.close(fig)


def test_the_html_shows_display_units(thirion) -> None:
    text = thirion._repr_html_()
    assert "1/MPa" in text and "1/Pa<" not in text


def test_covar_is_the_covariance_of_the_fitted_parameters(thirion) -> None:
    cov = thirion.covar
    assert thirion.var_names == ["a", "b"] and cov.shape == (2, 2)
    np.testing.assert_allclose(np.sqrt(np.diag(cov)),
                               [thirion.params["a"].stderr, thirion.params["b"].stderr],
                               rtol=1e-12)
    np.testing.assert_allclose(cov, cov.T, rtol=1e-12)
    r = cov[0, 1] / math.sqrt(cov[0, 0] * cov[1, 1])
    assert r == pytest.approx(thirion.correlation["a"]["b"], rel=1e-9)
    assert np.all(np.linalg.eigvalsh(cov) > 0)


def test_covar_leaves_fixed_parameters_out_and_marks_undetermined_ones() -> None:
    res = fl.fit("denny", "thesis-steel", free=["E_v"])
    assert res.var_names == [k for k, e in res.params.items() if not e.fixed]
    undetermined = [i for i, k in enumerate(res.var_names) if k in res.non_identifiable]
    assert undetermined and all(np.isnan(res.covar[i, i]) for i in undetermined)
    fixed = fl.fit("thirion", "thesis-steel", fix={"a": 0.15})
    assert fixed.var_names == ["b"] and fixed.covar.shape == (1, 1)


@pytest.mark.parametrize("unit,shown,factor", [
    ("1/Pa", "1/MPa", 1e6), ("Pa", "MPa", 1e-6), ("1/Pa^2", "1/MPa^2", 1e12),
    ("m/(s*Pa)", "m/(s*MPa)", 1e6), ("s/m", "s/m", 1.0), ("", DIMENSIONLESS, 1.0),
    ("MPa^-1", "MPa^-1", 1.0)])
def test_parameter_units_show_pressures_in_mpa(unit: str, shown: str, factor: float) -> None:
    got, f = display_param_unit(unit)
    assert got == shown and f == pytest.approx(factor, rel=1e-12)


def test_every_law_parameter_has_a_display_unit() -> None:
    for law in fl.list_laws():
        for p in law.params:
            shown, factor = display_param_unit(p.unit)
            assert shown and math.isfinite(factor) and factor > 0, (law.id, p.name)
            assert "Pa" not in shown.replace("MPa", ""), (law.id, p.name, shown)


@given(st.floats(-50, 300, allow_nan=False), st.text(min_size=1, max_size=20))
def test_group_labels_show_temperatures_in_degc(t_degc: float, surface: str) -> None:
    label = group_label({"T": t_degc + 273.15, "surface": surface})
    assert label.startswith(f"T={t_degc + 273.15 - 273.15:.6g} degC, surface=")


def test_the_group_table_lists_every_parameter_with_its_error() -> None:
    rows = [{"label": "T=20 degC", "n": 14, "r2": 0.99, "rmse": 0.05,
             "params": {"a": {"value": 0.25, "stderr": 0.0061, "unit": ""},
                        "b": {"value": 3.0e-6, "stderr": 5.2e-8, "unit": "1/Pa"}}},
            {"label": "T=40 degC", "n": 14, "error": "did not converge"}]
    text = parameter_table(rows, shared=["b"])
    head, first, second = text.splitlines()
    assert "b [1/MPa] (shared)" in head and "a [-]" in head and "R^2" in head
    assert "0.25 +/- 0.0061" in first and "3 +/- 0.052" in first
    assert "error: did not converge" in second
    assert "e-0" not in text


@pytest.fixture(scope="module")
def temps(tmp_path_factory: pytest.TempPathFactory):
    from frictionlaws.example_files import write_example_files

    root = tmp_path_factory.mktemp("examples")
    write_example_files(root)
    return root / "temps.csv"


def test_fit_by_prints_each_groups_parameters_in_the_datas_units(temps, capsys) -> None:
    from frictionlaws.cli import main

    assert main(["fit", "--law", "thirion", str(temps), "--by", "T"]) == 0
    out = capsys.readouterr().out
    assert "K" not in out.replace("RMSE", "")
    lines = [line for line in out.splitlines() if line.startswith("T=")]
    assert [line.split()[0] for line in lines] == ["T=20", "T=40", "T=60"]
    assert all("degC" in line and line.count("+/-") == 2 for line in lines)
    assert "b [1/MPa]" in out


def test_by_and_shared_write_one_table_layout(temps, tmp_path, capsys) -> None:
    import pandas as pd

    from frictionlaws.cli import main

    by, shared = tmp_path / "by.csv", tmp_path / "shared.csv"
    assert main(["fit", "--law", "thirion", str(temps), "--by", "T", "--out", str(by)]) == 0
    assert main(["fit", "--law", "thirion", str(temps), "--by", "T", "--shared", "b",
                 "--out", str(shared)]) == 0
    out = capsys.readouterr().out
    assert "b [1/MPa] (shared)" in out and "+/- 0.0" in out and "e-08" not in out
    a, b = pd.read_csv(by, comment=None), pd.read_csv(shared)
    assert list(b.columns) == [*a.columns, "shared"]
    assert set(b.loc[b["shared"], "param"]) == {"b"}
    assert b["dataset"].eq("temps").all() and b["T [K]"].round(2).tolist()[0] == 293.15


def test_the_report_adds_the_values_with_pressure_in_mpa(thirion) -> None:
    text = thirion.report()
    (line,) = [x for x in text.splitlines() if x.startswith("with p in MPa: ")]
    b = thirion.params["b"]
    assert f"b = {b.value * 1e6:.6g} +/- {b.stderr * 1e6:.6g} 1/MPa" in line
    assert "tau_sat = " in line and line.endswith(" MPa")
    assert "with p in MPa" not in fl.fit("coulomb", "thesis-steel").report()


_BASE = st.sampled_from(["Pa", "m", "s", "N"])
_POWERED = st.builds(lambda u, p: f"{u}^{p}" if p != 1 else u, _BASE,
                     st.sampled_from([-3, -2, -1, 1, 2, 3]))


@st.composite
def _units(draw) -> str:
    parts = draw(st.lists(_POWERED, min_size=1, max_size=4))
    ops = draw(st.lists(st.sampled_from(["*", "/"]), min_size=len(parts) - 1,
                        max_size=len(parts) - 1))
    text = parts[0]
    for op, part in zip(ops, parts[1:]):
        text += op + (f"({part})" if draw(st.booleans()) else part)
    return text


@given(_units())
def test_the_display_factor_agrees_with_pint(unit: str) -> None:
    from frictionlaws.base.units import unit_registry

    shown, factor = display_param_unit(unit)
    if "Pa" not in unit:
        assert factor == 1.0 and shown == unit
        return
    ureg = unit_registry()
    expected = ureg.Quantity(1.0, unit.replace("^", "**")).to(shown.replace("^", "**")).magnitude
    assert factor == pytest.approx(expected, rel=1e-9)


@pytest.mark.parametrize("unit", ["Pa^", "(Pa", "Pa)", "Pa$", "1/Pa/", "Pa^m", "Pa**"])
def test_a_unit_the_parser_cannot_read_is_refused(unit: str) -> None:
    with pytest.raises(InputError, match="cannot read the unit"):
        display_param_unit(unit)


def test_a_dataset_renders_as_html_in_display_units() -> None:
    text = fl.load_dataset("thesis-steel")._repr_html_()
    assert text.startswith("<h4>dataset <code>thesis-steel</code>: 19 rows</h4>")
    assert "<th>p [MPa]</th>" in text and "0.03119 .. 0.2496" in text
    assert text.count("<tr>") >= 5 + 5  # a row per column, the first five data rows


@given(st.text(min_size=1, max_size=30).filter(lambda s: s.strip() and "," not in s
                                               and "\n" not in s and "\r" not in s
                                               and '"' not in s))
def test_dataset_html_escapes_what_the_file_holds(surface: str) -> None:
    import html

    import pandas as pd

    frame = pd.DataFrame({"mu": [0.5, 0.6, 0.7], "p [MPa]": [0.1, 0.2, 0.3],
                          "surface": [surface, "<b>x</b>", surface]})
    ds = fl.Dataset.from_frame(frame, name="<i>n</i>")
    text = ds._repr_html_()
    assert "<b>x</b>" not in text and "<i>n</i>" not in text
    assert html.escape(str(ds.column("surface")[0])) in text or "..." in text
