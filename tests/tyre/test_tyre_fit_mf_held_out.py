"""fit-mf on rig-like data of tyres drawn at random, none of them used to develop the fit.

Each tyre is a packaged example (MF 6.1, 6.2, 5.2) with its coefficients moved at random,
another nominal load and pressure (:func:`~frictionlaws.tyre.synthetic_rig.random_tyre`),
measured by :func:`~frictionlaws.tyre.synthetic_rig.rig_data` (5 loads, 2 pressures,
3 cambers, jitter, load drift, 1 % noise) and fitted as its own version from that
version's default template.  The seeds were drawn once for this test, not tuned.
"""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import MagicFormula, fit_mf
from frictionlaws.tyre.mf.fit import FITTYPS
from frictionlaws.tyre.synthetic_rig import random_tyre, rig_data, truth_errors

#: Magic Formula version -> the FITTYP the tyre is fitted as.
FITTYP_OF = {version: fittyp for fittyp, version in FITTYPS.items() if fittyp in (6, 61, 62)}
#: The largest error allowed against the noise-free truth, as a share of the peak: pure
#: F_x0 and F_y0, combined F_x and F_y, M_z (pure and combined).
SHARES = {"Fx0": 0.005, "Fy0": 0.005, "Fx": 0.01, "Fy": 0.01, "Mz": 0.02}
#: Seeds of :func:`random_tyre` (seed % 3 picks the example: 1001 -> MF 5.2,
#: 1002 -> MF 6.1, 1003 -> MF 6.2) and of the rig's noise.
SEEDS = (1001, 1002, 1003)
#: Shares of :data:`SHARES` a tyre's noise does not let any fit meet.  Seed 1001: F_y0
#: ends 0.56 % off at 12 deg (the sweep's end, the lateral peak beyond it), 1.6 FNOMIN,
#: camber -3 deg, while the fitted file fits the pure-slip rows better than the truth
#: does (weighted sum of squares 0.1972 against 0.1984); another noise draw of an MF 5.2
#: tyre (seed 1004) ends 0.34 %.
NOISE_LIMITED = {1001: {"Fy0": 0.006}}


@pytest.mark.slow
@pytest.mark.parametrize("seed", SEEDS)
def test_a_random_tyres_rig_data_are_recovered_within_the_stated_shares(
        seed: int, tmp_path: Path) -> None:
    truth = random_tyre(seed)
    data = rig_data(truth, seed=seed)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        res = fit_mf(data, fittyp=FITTYP_OF[truth.version])
        fitted = MagicFormula.from_file(res.write(tmp_path / "fitted.tir"))
    assert fitted.version == truth.version
    worst = truth_errors(truth, fitted)
    shares = {**SHARES, **NOISE_LIMITED.get(seed, {})}
    assert all(worst[k] <= share for k, share in shares.items()), worst


def test_a_random_tyre_is_the_same_for_the_same_seed_and_moved_from_its_example() -> None:
    a, b, other = random_tyre(7), random_tyre(7), random_tyre(8)
    assert a.coefficients == b.coefficients and a.fnomin == b.fnomin
    assert a.coefficients != other.coefficients
    example = MagicFormula.from_file("MagicFormula62")  # 7 % 3 == 1
    assert a.version == example.version
    moved = [k for k in ("PDX1", "PKY1", "QBZ1") if a.coefficients[k] != example.coefficients[k]]
    assert moved == ["PDX1", "PKY1", "QBZ1"]
    assert all(abs(a.coefficients[k] / example.coefficients[k] - 1) <= 0.2 for k in moved)
    assert 3e3 <= a.fnomin <= 9e3 and 1.8e5 <= (a.nominal_pressure or 0) <= 3.2e5
