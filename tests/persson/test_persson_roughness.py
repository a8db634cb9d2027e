"""Plausibility of the roughness given to Persson's theory (its rms slope).

The theory takes small slopes on a linear-elastic rubber and its viscoelastic
friction grows about as the rms slope of the band q0..q1: a surface much steeper
than a road (an rms height of 0.1 m under a roll-off of 1 cm gives mu of about
540) is refused with the reason, one steeper than roads are is warned.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

import frictionlaws as fl
from frictionlaws.base.errors import FitError, InputError
from frictionlaws.persson import (
    RoughnessWarning,
    SelfAffine,
    TabulatedPSD,
    asphalt_like,
    check_roughness,
    contact_ratio,
    friction,
    tread_compound,
)
from frictionlaws.persson.surface import SLOPE_MAX, SLOPE_WARN

LAW = fl.get_law("persson")


@settings(max_examples=30, deadline=None)
@given(H=st.floats(0.05, 0.95), decades=st.floats(0.5, 5.0), h=st.floats(1e-6, 1e-3))
def test_rms_slope_is_the_integral_of_q3_C(H, decades, h):
    s = SelfAffine.from_rms(628.0, H, h, 628.0 * 10**decades)
    ref = math.sqrt(2 * math.pi * quad(lambda lq: math.exp(4 * lq) * float(s.C(math.exp(lq))),
                                       math.log(s.q0), math.log(s.q1), limit=200)[0])
    assert s.rms_slope() == pytest.approx(ref, rel=1e-6)


def test_a_tabulated_spectrum_has_the_same_slope():
    s = asphalt_like(1e6)
    q = np.logspace(math.log10(s.q0), 6, 2001)
    tab = TabulatedPSD(q, s.C(q))
    assert tab.rms_slope() == pytest.approx(s.rms_slope(), rel=1e-5)
    # the table's nodes up to q1 (the last one short of it by at most one step)
    assert tab.rms_slope(1e5) == pytest.approx(s.rms_slope(1e5), rel=1e-3)


def test_the_packaged_road_is_neither_warned_nor_refused():
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert check_roughness(asphalt_like(1e6), 1e6) == pytest.approx(1.603, abs=1e-3)
        LAW(p=2e5, v=0.01, T=293.15, preset="tread-on-asphalt")


@pytest.mark.parametrize("h_rms", [0.1, 0.01, 3e-3])
def test_a_surface_far_steeper_than_a_road_is_refused_with_the_reason(h_rms):
    slope = asphalt_like(1e6).rms_slope() * h_rms / 0.3e-3
    assert slope > SLOPE_MAX
    surf = SelfAffine.from_rms(2 * math.pi / 0.01, 0.8, h_rms, 1e6)
    with pytest.raises(InputError, match=rf"rms slope is {slope:.3g} .*rms height "
                                         rf"{h_rms:.3g} m.*above 10 it is refused"):
        friction(tread_compound(), surf, 0.01, 293.15, 2e5)
    with pytest.raises(InputError, match="rms slope"):
        contact_ratio(tread_compound(), surf, 0.01, 293.15, 2e5, [1e4, 1e6])
    # the law: an rms height above 1 cm is outside the setting's bounds, a smaller one
    # too steep on this band is refused by the theory
    match = "outside its bounds" if h_rms > 0.01 else rf"rms slope is {slope:.3g} "
    with pytest.raises(InputError, match=match):
        LAW(p=2e5, v=0.01, T=293.15, h_rms=h_rms, preset="tread-on-asphalt")


def test_a_steep_band_is_warned():
    surf = asphalt_like(1e8)                      # the road resolved to 63 nm
    assert SLOPE_WARN < surf.rms_slope() < SLOPE_MAX
    with pytest.warns(RoughnessWarning, match=r"rms slope is 4\.12 .*doubtful"):
        mu = friction(tread_compound(), surf, 0.01, 293.15, 2e5)
    assert np.isfinite(mu)


def test_fits_and_the_command_line_refuse_it(tmp_path, capsys):
    from frictionlaws.cli import main

    d = {"p": np.full(4, 2e5), "v": np.logspace(-4, -1, 4), "T": np.full(4, 293.15),
         "mu": np.linspace(1.0, 1.3, 4)}
    # every q1 of the fit's box (1e4..1e8 1/m) is too steep with 8 mm: no start is taken
    with pytest.raises(FitError, match=r"rms slope is \d+.*rms height 0.008 m"):
        fl.fit("persson", d, fix={"h_rms": 8e-3})
    path = tmp_path / "d.csv"
    path.write_text("p [MPa],v [m/s],T [degC],mu\n"
                    + "".join(f"0.2,{v},20,{m}\n" for v, m in zip(d["v"], d["mu"])),
                    encoding="utf-8")
    assert main(["fit", "--law", "persson", "--fix", "h_rms=0.1", str(path)]) == 2
    err = capsys.readouterr().err
    assert "h_rms = 0.1 m is outside its bounds" in err and err.count("\n") == 1


@pytest.mark.parametrize("q1", [10.0, 628.0, float("nan")])
def test_a_q1_not_above_q0_is_refused_naming_both(q1: float) -> None:
    from frictionlaws.persson import asphalt_like, check_roughness

    surface = asphalt_like()
    assert q1 != q1 or q1 <= surface.q0
    with pytest.raises(InputError, match=r"q1 = .* 1/m is not above the surface's roll-off "
                                         r"q0 = 628\.3 1/m: expected q1 > q0"):
        check_roughness(surface, q1)
    assert check_roughness(surface, 1e6) > 0
