"""The numbers the Persson guide states outside its flash-temperature section, computed.

docs/user-guide/persson.rst states figures of the packaged compound, the surfaces and
the packaged DMA sweeps; each is computed here and looked up in the guide's text (the
flash temperature's figures: tests/persson/test_persson_published.py and
tests/persson/test_persson_flash.py).
"""

from __future__ import annotations

import csv
import math
from pathlib import Path

import numpy as np

from frictionlaws.io import datasets_dir
from frictionlaws.persson import SelfAffine, asphalt_like, theory, tread_compound
from frictionlaws.persson.published import V_GRID, peak

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "persson.rst"
TEXT = " ".join(GUIDE.read_text(encoding="utf-8").split())


def test_the_prony_series_of_the_compound():
    mat = tread_compound()
    assert f"A Prony series of {mat.E_i.size} terms, one per decade" in TEXT
    assert f"(rms relative misfit {mat.rms_rel:.1g})" in TEXT


def test_the_rms_slopes_and_the_friction_they_give(monkeypatch):
    road = asphalt_like(1e6)
    mu = theory.friction(tread_compound(), road, V_GRID, 293.15, 2e5)
    assert ("1.6 for the asphalt-like surface to :math:`q_1 = 10^6` 1/m, where the peak "
            ":math:`\\mu` is 1.6)") in TEXT
    assert f"{road.rms_slope():.2g}" == "1.6" and f"{peak(V_GRID, mu)[0]:.2g}" == "1.6"
    assert f"resolved to :math:`q_1 = 10^8` 1/m has {asphalt_like(1e8).rms_slope():.2g})" in TEXT
    steep = SelfAffine.from_rms(2 * math.pi / 0.01, 0.8, 0.1, 1e6)
    monkeypatch.setattr(theory, "check_roughness", lambda surface, q1: 0.0)  # what it would give
    mu = theory.friction(tread_compound(), steep, np.logspace(-3, 1, 41), 293.15, 2e5)
    assert f"slope {steep.rms_slope():.0f}, would give a maximum :math:`\\mu` of about 545" \
        in TEXT
    assert abs(peak(np.logspace(-3, 1, 41), mu)[0] - 545) < 2.5


def test_the_packaged_sweeps_storage_modulus_range():
    path = datasets_dir() / "dma-pyvisco" / "freq_user_raw.csv"
    with path.open(encoding="utf-8-sig", newline="") as fh:
        rows = list(csv.reader(fh))
    assert [c.strip() for c in rows[1][:2]] == ["Hz", "MPa"]
    stor = np.array([float(r[1]) for r in rows[2:] if r]) / 1e3           # GPa
    assert f"(storage modulus {stor.min():.2g} to {stor.max():.2g} GPa in the sweeps)" in TEXT
