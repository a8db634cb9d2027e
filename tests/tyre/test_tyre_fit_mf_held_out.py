"""fit-mf on rig-like data of tyres drawn at random, none of them used to develop the fit.

Each tyre is a packaged example (MF 6.1, 6.2, 5.2) with its coefficients moved at random,
another nominal load and pressure (:func:`~frictionlaws.tyre.synthetic_rig.random_tyre`),
measured by :func:`~frictionlaws.tyre.synthetic_rig.rig_data` (5 loads, 2 pressures,
3 cambers, jitter, load drift, 1 % noise) and fitted as its own version from that
version's default template.  The seeds were drawn once for this test, not tuned.
"""

from __future__ import annotations

import math
import runpy
import warnings
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning
from frictionlaws.tyre import MagicFormula, fit_mf
from frictionlaws.tyre.mf.fit import FITTYPS
from frictionlaws.tyre.mf.fit.pure import X_COEFFICIENTS, Y_COEFFICIENTS
from frictionlaws.tyre.mf.fit.stages import ALPHA_PURE, KAPPA_PURE, level_scale
from frictionlaws.tyre.synthetic_rig import random_tyre, rig_data, truth_errors

#: Magic Formula version -> the FITTYP the tyre is fitted as.
FITTYP_OF = {version: fittyp for fittyp, version in FITTYPS.items() if fittyp in (6, 61, 62)}
#: The largest error allowed against the noise-free truth, as a share of the peak: pure
#: F_x0 and F_y0, combined F_x and F_y, M_z (pure and combined).
SHARES = {"Fx0": 0.005, "Fy0": 0.005, "Fx": 0.01, "Fy": 0.01, "Mz": 0.02}
#: Seeds of :func:`random_tyre` (seed % 3 picks the example: 1001 -> MF 5.2,
#: 1002 -> MF 6.1, 1003 -> MF 6.2) and of the rig's noise.
SEEDS = (1001, 1002, 1003)
#: Figures of :data:`SHARES` a tyre's noise does not let any fit meet: allowed over their
#: share only while the error at the worst point is within :data:`NOISE_SD` standard
#: deviations of the fit's own prediction there (:func:`_worst_in_sd`).  Seed 1001:
#: F_y0 ends 0.565 % off at 12 deg (the sweep's end), 1.6 FNOMIN, camber -3 deg, 2.7 SD
#: of the prediction (SD 0.21 % of peak there).  That is the noise, not a bias of the fit:
#: refitted to 12 other noise draws (``python benchmarks/bench_fit_mf.py --seeds 1001
#: --draws 12``) F_y0 ends 0.33 % on average (SD 0.09 %; 0.19-0.50 %, 1 of 12 over 0.5 %)
#: and the largest mean error over the grid is 0.09 % of peak, within two of its standard
#: errors; the fit ends at the weighted least-squares optimum of its rows (a refit from the
#: truth's values ends at the same point), its weights are the rig's noise (each load's
#: largest force, within 2 %), no F_y0 coefficient is held at the template, and the later
#: stages lower the F_y0 error (0.68 % after the pure-slip stages).  Seed 1005 (MF 6.1; not
#: run here, for CI time) misses the same way: 0.57 % at 0.4 FNOMIN, the lower pressure,
#: camber 3 deg, -1.75 deg; 12 other draws 0.43 % on average (SD 0.11 %, 2 of 12 over
#: 0.5 %); its one held F_y0 coefficient, PPY4 (a third pressure would set it), cannot
#: matter at two pressures (held, the model still meets the truth within 1e-13 of peak).
NOISE_LIMITED = {1001: ("Fy0",)}
#: How far (in standard deviations of the fitted curve) a noise-limited figure may be.
NOISE_SD = 3.0


def _worst_in_sd(truth: MagicFormula, fitted: MagicFormula, data: object, res: object,
                 name: str) -> float:
    """The error of the pure curve ``name`` ("Fx0" or "Fy0") at its worst point on the
    grid of :func:`truth_errors`, in standard deviations of the fitted curve there: the
    covariance ``s^2 (J^T J)^-1`` of the coefficients the fit determined, from the rows
    near pure slip weighted as the fit weights them (each load's largest force)."""
    x = name == "Fx0"
    names = [k for k in (X_COEFFICIENTS if x else Y_COEFFICIENTS)[fitted.version]
             if math.isfinite(res.stderr.get(k, math.inf))]  # type: ignore[attr-defined]
    rows = (np.abs(data.alpha) <= ALPHA_PURE if x  # type: ignore[attr-defined]
            else np.abs(data.kappa) <= KAPPA_PURE)  # type: ignore[attr-defined]
    measured = (data.fx if x else data.fy)  # type: ignore[attr-defined]
    scale = level_scale(data.fz, measured)[rows]  # type: ignore[attr-defined]
    slip_rows = (data.kappa if x else data.alpha)[rows]  # type: ignore[attr-defined]
    at = (data.fz[rows], data.gamma[rows], data.pressure[rows])  # type: ignore[attr-defined]
    base = dict(fitted.coefficients)
    p0 = np.array([base[k] for k in names])

    def curve(values: np.ndarray, slip: np.ndarray, fz: object, g: object, p: object
              ) -> np.ndarray:
        fitted.coefficients.update(zip(names, values))
        p = p if fitted.nominal_pressure else None  # MF 5.2: no pressure terms
        out = (fitted.fx0 if x else fitted.fy0)(slip, fz, g, p)
        fitted.coefficients.update(base)
        return np.asarray(out)

    def jacobian(*point: object) -> np.ndarray:
        f0 = curve(p0, *point)  # type: ignore[arg-type]
        steps = 1e-6 * np.maximum(1.0, np.abs(p0))
        return np.array([(curve(p0 + h * e, *point) - f0) / h  # type: ignore[arg-type]
                         for h, e in zip(steps, np.eye(p0.size))]).T

    J = jacobian(slip_rows, *at) / scale[:, None]
    r = (curve(p0, slip_rows, *at) - measured[rows]) / scale
    cov = np.linalg.pinv(J.T @ J) * float(r @ r) / (r.size - p0.size)
    grid = (np.linspace(-0.25, 0.25, 101) if x else np.radians(np.linspace(-12, 12, 97)))
    worst = (0.0, 0.0)
    for fz in truth.fnomin * np.array([0.4, 0.7, 1.0, 1.3, 1.6]):
        for p in (truth.nominal_pressure or 2.6e5) * np.array([0.85, 1.1]):
            for g in np.radians([-3.0, 0.0, 3.0]):
                true = np.asarray((truth.fx0 if x else truth.fy0)(
                    grid, fz, g, p if truth.nominal_pressure else None))
                err = np.abs(curve(p0, grid, fz, g, p) - true)
                i = int(np.argmax(err))
                if err[i] / np.abs(true).max() > worst[0]:
                    G = jacobian(grid[i:i + 1], fz, g, p)[0]
                    worst = (err[i] / np.abs(true).max(), err[i] / math.sqrt(G @ cov @ G))
    return worst[1]


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
    over = {k: worst[k] for k, share in SHARES.items() if worst[k] > share}
    assert set(over) <= set(NOISE_LIMITED.get(seed, ())), worst
    for name in over:  # a miss the data's noise explains, and no more
        assert _worst_in_sd(truth, fitted, data, res, name) <= NOISE_SD, (name, worst)
        off = MagicFormula.from_file(tmp_path / "fitted.tir")  # a curve 2 % off is not
        peak = "PDX1" if name == "Fx0" else "PDY1"
        off.coefficients[peak] *= 1.02
        assert _worst_in_sd(truth, off, data, res, name) > NOISE_SD, name


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


def test_the_benchmarks_noise_draws_measure_a_pure_curves_error_with_its_sign() -> None:
    # the evidence NOISE_LIMITED cites comes from benchmarks/bench_fit_mf.py --draws
    bench = Path(__file__).resolve().parents[2] / "benchmarks" / "bench_fit_mf.py"
    if not bench.exists():
        pytest.skip("needs the repository's benchmarks/")
    pure_errors = runpy.run_path(str(bench), run_name="bench_fit_mf_under_test")["pure_errors"]
    truth = random_tyre(1001)
    assert not pure_errors(truth, truth, "Fy0").any()
    more = MagicFormula(dict(truth.coefficients, PDY1=1.02 * truth.coefficients["PDY1"]),
                        fnomin=truth.fnomin, version=truth.version, structure=truth.structure)
    e = pure_errors(truth, more, "Fy0")
    assert e.shape == (30, 97)  # 5 loads x 2 pressures x 3 cambers, the slip grid
    end = e[:, [0, -1]]  # at +-12 deg, near the peak: 2 % more, of the force's sign
    assert np.all(np.abs(end) > 0.01) and np.all(np.abs(end) < 0.03)
    assert np.all(np.sign(end[:, 0]) == -np.sign(end[:, 1]))
    assert pure_errors(truth, truth, "Fx0").shape == (30, 101)
