"""The thesis' cornering comparison: constant mu against a law fitted to thesis-steel."""

from __future__ import annotations

import json
import warnings

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import TABLE_6_2, thesis_comparison, thesis_ratios


@pytest.fixture(scope="module")
def comparison():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        return thesis_comparison(laws=("thirion", "denny"))


def test_table_6_2_as_published():
    cols = TABLE_6_2["columns"]
    assert TABLE_6_2["loads_kN"] == (2.0, 2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 5.5, 6.0, 6.5)
    assert set(cols) == {"mu 0.9", "mu 1.0", "S120", "S400", "steel"}
    assert all(len(v) == 10 for v in cols.values())
    assert cols["mu 0.9"][0] == 0.463 and cols["S120"][-1] == 1.562
    r = thesis_ratios()
    assert r["mu 0.9"] == pytest.approx(2.65, abs=0.005)
    assert r["S120"] == pytest.approx(1.89, abs=0.005)
    assert "Table 6-2" in TABLE_6_2["source"]


def test_constant_mu_rises_linearly_with_load(comparison):
    loads = comparison.loads_kN
    for label in ("coulomb 0.9", "coulomb 1.0"):
        cs = comparison.results[label].cs_kN_per_deg
        # proportional to load: ratio = load ratio 6.5/2 = 3.25, straight line through 0
        assert comparison.ratios()[label] == pytest.approx(3.25, rel=2e-3)
        slope = np.sum(cs * loads) / np.sum(loads * loads)
        assert np.allclose(cs, slope * loads, rtol=2e-3)
    # more friction, more cornering stiffness at every load (as in the thesis)
    assert np.all(comparison.results["coulomb 1.0"].cs > comparison.results["coulomb 0.9"].cs)


def test_fitted_law_rises_clearly_less(comparison):
    const = comparison.ratios()["coulomb 0.9"]
    fitted = comparison.ratios()["thirion (thesis-steel)"]
    # the qualitative result of the thesis: x2.65 (mu 0.9) against x1.89 (S120) in the FE
    # model; the brush model gives x3.25 against about x2.6 with Thirion fitted to steel
    assert fitted < 0.85 * const
    assert 2.3 < fitted < 2.9
    cs = comparison.results["thirion (thesis-steel)"].cs_kN_per_deg
    assert np.all(np.diff(cs) > 0)          # still rising...
    assert np.all(np.diff(cs, 2) < 0)       # ...but levelling off: concave in load
    # high friction at low contact pressure: stiffer than mu 0.9 at the lightest load
    assert cs[0] > comparison.results["coulomb 0.9"].cs_kN_per_deg[0]
    # Denny with its fixed E_v is Thirion in disguise: same curve
    assert np.allclose(cs, comparison.results["denny (thesis-steel)"].cs_kN_per_deg,
                       rtol=1e-4)
    # the origin slope does not see friction at all
    assert np.allclose(comparison.results["thirion (thesis-steel)"].cs_origin,
                       comparison.results["coulomb 0.9"].cs_origin, rtol=1e-12)


def test_fits_and_extrapolation_reported(comparison):
    fit = comparison.fits["thirion (thesis-steel)"]
    assert fit.law.id == "thirion" and fit.success
    assert fit.params["a"].value > 0 and fit.params["b"].value > 0
    warns = comparison.results["thirion (thesis-steel)"].warnings
    # the patch pressures at high load exceed the 0.25 MPa the data reach: said so
    assert any("6.5 kN" in w and "fitted data range" in w for w in warns)
    assert comparison.results["coulomb 0.9"].warnings == []


def test_report_and_json(comparison):
    text = comparison.table()
    assert "kN/deg" in text and "Table 6-2" in text
    assert "3.250" in text and "2.648" in text and "1.891" in text
    d = json.loads(json.dumps(comparison.to_dict()))
    assert d["unit"] == "kN/deg"
    assert d["thesis_table_6_2"]["ratios"]["S120"] == pytest.approx(1.891, abs=1e-3)
    assert set(d["brush"]) == {"coulomb 0.9", "coulomb 1.0", "thirion (thesis-steel)",
                               "denny (thesis-steel)"}
    print()
    print(comparison.table())


def test_undetermined_fit_is_named_in_table_json_and_cli(capsys):
    from frictionlaws.cli import main

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        comp = thesis_comparison(laws=["exponential-decay"], loads_kN=[2.0, 6.5])
    fit = next(iter(comp.fits.values()))
    assert fit.non_identifiable
    table = comp.table()
    assert "cannot determine" in table and fit.non_identifiable[0] in table
    entry = next(iter(comp.to_dict()["fits"].values()))
    assert entry["undetermined"] == list(fit.non_identifiable) and entry["warnings"]
    assert main(["tyre", "thesis", "--laws", "exponential-decay"]) == 0
    out, err = capsys.readouterr()
    assert f"{fit.non_identifiable[0]} = " in out and "(undetermined)" in out
    assert "cannot determine" in err and "[exponential-decay (thesis-steel)]" in err
