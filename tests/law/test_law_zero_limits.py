"""A floor is no value of a law: at v = 0 and p = 0 a law gives its limit or refuses.

Every law with floors (Persson aside: its own tests) is evaluated with a floored
variable at 0 and just above 0 by a call, ``evaluate``, ``bind`` (the exporters' and
tyre models' path) and an export box: each gives the law's limit there (the value
far below the floor, where the formula itself is defined) or, where there is none, a
call raises :class:`~frictionlaws.base.errors.DomainError` and the unchecked paths give
NaN (which a scan or table then reports); none gives the value at the floor.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import DomainError
from frictionlaws.fe_export import export
from frictionlaws.validation.law_examples import EXAMPLES

FLOORED = sorted(law_id for law_id in EXAMPLES
                 if law_id != "persson" and fl.get_law(law_id).floors)


def _point(law, draw_fraction: float) -> dict[str, float]:
    ranges = EXAMPLES[law.id].battery.ranges
    out = {}
    for var in law.variables:
        lo, hi = ranges.get(var, law.typical_range(var))
        out[var] = lo + draw_fraction * (hi - lo)
    return out


def _value_or_refusal(call):
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return float(np.asarray(call(), float).ravel()[0])
    except DomainError as exc:
        return exc


@pytest.mark.parametrize("law_id", FLOORED)
@settings(max_examples=6, deadline=None)
@given(frac=st.floats(0.05, 0.95))
def test_a_floored_variable_at_zero_gives_the_limit_or_a_refusal(law_id, frac):
    law = fl.get_law(law_id)
    values = law.resolve(EXAMPLES[law_id].battery.params)
    for var, floor in law.floors.items():
        if var not in law.variables:
            continue
        point = {**_point(law, frac), var: 0.0}
        called = _value_or_refusal(lambda p=point: law(**p, **values))
        plain = _value_or_refusal(lambda p=point: law.evaluate(p, values))
        near = _value_or_refusal(lambda p=point, k=var, f=floor: law.evaluate(
            {**p, k: f * 1e-250}, values))
        bound = _value_or_refusal(lambda p=point: law.bind(values)(
            **{k: np.array([x]) for k, x in p.items()}))
        if isinstance(called, DomainError):
            assert "-> 0" in str(called) or "non-finite" in str(called), called
            if "-> 0" in str(called):  # no limit: NaN where nothing checks, never a number
                assert math.isnan(plain) and math.isnan(bound), (law_id, var, plain, bound)
            continue
        assert math.isfinite(called)
        assert plain == pytest.approx(called, rel=1e-12, abs=1e-15)
        assert bound == pytest.approx(called, rel=1e-12, abs=1e-15)
        if isinstance(near, float) and math.isfinite(near):  # the law's value close to 0
            assert called == pytest.approx(near, rel=1e-6, abs=1e-6), (law_id, var)


@pytest.mark.parametrize("law_id", FLOORED)
def test_below_a_floor_the_law_is_its_own_formula(law_id):
    law = fl.get_law(law_id)
    values = law.resolve(EXAMPLES[law_id].battery.params)
    for var, floor in law.floors.items():
        if var not in law.variables:
            continue
        point = {**_point(law, 0.5), var: floor * 1e-3}
        got = _value_or_refusal(lambda p=point: law(**p, **values))
        at_floor = _value_or_refusal(
            lambda p=point, k=var, f=floor: law.evaluate({**p, k: f}, values))
        raw = dict(law.prepare_variables(point))
        raw[var] = np.asarray(floor * 1e-3)
        with np.errstate(all="ignore"):
            formula = float(law.formula(fl.law.NUMPY, **raw, **values))
        if isinstance(got, DomainError):  # no value there, or a negative sliding mu
            assert not math.isfinite(formula) or formula < 0, (got, formula)
        else:
            assert got == pytest.approx(formula, rel=1e-12)
            if isinstance(at_floor, float) and not math.isclose(formula, at_floor,
                                                                rel_tol=1e-9):
                assert got != at_floor


def test_savkoor_at_zero_pressure_is_refused_and_at_zero_speed_is_mu_s():
    law = fl.get_law("savkoor")
    values = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": -0.2}
    with pytest.raises(DomainError, match="p -> 0"):
        law(p=0.0, v=0.01, **values)
    # the static limit mu_s (p/p_ref)^n, not the bell at the floor (0.357)
    assert law(p=1e5, v=0.0, **values) == pytest.approx(0.4, rel=1e-9)
    # n held at -0.2: where the data leave n free, an optimum may end at n = 0, where mu has
    # a limit at p = 0 (it did under numpy 1.24 / scipy 1.10)
    p, v = np.tile(np.linspace(1e5, 8e5, 4), 4), np.repeat(np.logspace(-4, 0, 4), 4)
    mu = law(p=p, v=v, **values) * (1 + 0.01 * np.sin(np.arange(16)))
    start = {k: x for k, x in values.items() if k != "n"}
    fitted = fl.fit("savkoor", {"mu": mu, "p": p, "v": v}, initial=start, fix={"n": -0.2})
    assert math.isnan(fitted.predict(p=0.0, v=0.1, warn=False))  # unchecked: NaN, no number
    with pytest.raises(DomainError, match="p -> 0"):
        fitted.bound(p=0.0, v=0.1, warn=False)


@pytest.mark.parametrize("box,match", [
    ({"p": (0.0, 5e5, 3), "v": (0.01, 1.0, 3)}, "p -> 0"),
    ({"p": (1e5, 5e5, 3), "v": (0.0, 1.0, 3)}, None),
])
def test_export_box_from_zero_holds_the_limit_or_is_refused(box, match, tmp_path):
    values = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": -0.2}
    out = tmp_path / "sav.csv"
    if match:
        with pytest.raises(DomainError, match=match):
            export("savkoor", values, "csv", box, path=out)
        assert not out.exists()
        return
    res = export("savkoor", values, "csv", box, path=out)
    rows = [ln.split(",") for ln in res.text.splitlines()
            if ln and not ln.startswith("#") and ln[0].isdigit()]
    at_zero = [float(r[2]) for r in rows if float(r[1]) == 0.0]
    law = fl.get_law("savkoor")
    expected = [law(p=float(r[0]), v=0.0, **values) for r in rows if float(r[1]) == 0.0]
    assert at_zero and np.allclose(at_zero, expected, rtol=1e-9)


def test_park_export_across_the_wlf_pole_is_refused(tmp_path, capsys):
    from frictionlaws.cli import main

    values = {"n": 0.2, "mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3}
    box = {"p": (1e5, 5e5, 3), "v": (0.01, 1.0, 3), "T": (150.0, 300.0, 4)}
    for fmt, name in (("csv", "park.csv"), ("abaqus-fric-coef", "park.f")):
        with pytest.raises(DomainError, match="WLF pole"):
            export("park", values, fmt, box, path=tmp_path / name)
        assert not (tmp_path / name).exists()
    code = main(["export", "--law", "park", "--set", "n=0.2,mu_s=0.4,mu_m=1.2,h10=0.35,"
                 "v_m=1e-3", "--format", "csv", "--p", "0.1MPa:0.5MPa:3", "--v", "0.01:1:3",
                 "--T", "150K:300K:4", "-o", str(tmp_path / "cli.csv")])
    err = capsys.readouterr().err
    assert code == 2 and "WLF pole" in err and len(err.strip().splitlines()) == 1
    assert not (tmp_path / "cli.csv").exists()


def test_user_subroutine_says_where_its_floors_depart_from_the_law():
    values = {"mu_s": 0.4, "mu_m": 1.2, "h10": 0.35, "v_m": 1e-3, "n": -0.2}
    res = export("savkoor", values, "abaqus-fric-coef", units="mm-N-s")
    floors = [w for w in res.warnings if "the routine floors" in w]
    assert any(w.startswith("the routine floors v") and "the law's limit is" in w
               for w in floors), floors
    assert any(w.startswith("the routine floors p") and "no limit there" in w
               for w in floors), floors
    plain = export("exponential-decay", None, "abaqus-fric-coef", preset="rubber-steel")
    assert not [w for w in plain.warnings if "the routine floors" in w]
