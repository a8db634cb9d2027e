"""Implausible speeds, wheel speeds and radii, a standing wheel without the limit checks,
and the cosmetic findings of a hostile pass over the newest tyre features: each is said,
once, with what is wrong (the paths alike: ``test_tyre_mf_condition_corpus.py``).

Before: ``tyre mf MagicFormula61 --vx 1e6`` gave a loaded radius of 930 km and
``--omega 500`` at kappa 0.05 a loaded radius above the unloaded one, both with exit 0 and
no warning; vx = 0 exactly without the limit checks gave F_y -78 N where +-1e-9 m/s gave
4700 N, silently; the range warnings quoted the whole span of the inputs; transient_slip
said each warning three times; instKya was NaN without a word for several loads (the
worker-count message: ``tests/cli/test_cli_bound.py``).
"""

from __future__ import annotations

import json
import re
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.tyre import MagicFormula
from frictionlaws.tyre.mf.outputs import evaluate
from frictionlaws.tyre.mf.plausibility import (
    GROWTH_SHARE,
    SPEED_LIMIT,
    YAW_RATE_LIMIT,
    speed_bound,
)
from frictionlaws.tyre.mf.tir import format_tir, packaged_example, read_property_file
from frictionlaws.tyre.transient import transient_slip


def _said(f: Any, *args: Any, **kw: Any) -> tuple[Any, list[str]]:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = f(*args, **kw)
    return out, [str(w.message) for w in caught]


@pytest.fixture(scope="module")
def mf61() -> MagicFormula:
    return MagicFormula.from_file("MagicFormula61")


# ------------------------------------------------------------------ F1: speeds, radii

def test_the_speed_bound_is_the_files_growth_or_the_absolute_limit() -> None:
    m61, m52 = (MagicFormula.from_file(f"MagicFormula{v}") for v in ("61", "52"))
    s = m61.structure
    assert speed_bound(m61)[0] == pytest.approx(s["LONGVL"] * np.sqrt(GROWTH_SHARE / s["Q_V1"]))
    assert speed_bound(m61)[0] < SPEED_LIMIT
    assert speed_bound(m52) == (SPEED_LIMIT, "above the speed rating of every road tyre")


@pytest.mark.parametrize("file", ["MagicFormula52", "MagicFormula61", "MagicFormula62"])
def test_generated_speeds_and_wheel_speeds_are_plausible_or_warned(file: str) -> None:
    """Generated speeds (|vx| log-uniform 1e-3..1e6 m/s, either direction) and wheel speeds
    (the slip ratio's, or one drawn at random): a row whose outputs leave what a tyre does
    (a radius grown past the growth bound, a wheel speed beyond the speed bound, a wheel
    speed 0.1 in slip off the slip ratio's) is always warned of."""
    mf = MagicFormula.from_file(file)
    rng = np.random.default_rng(36)
    n = 300
    vx = rng.choice([-1, 1], n) * 10 ** rng.uniform(-3, 6, n)
    kappa = rng.uniform(-0.3, 0.3, n)
    bound = speed_bound(mf)[0]
    r0, q_re0 = mf.structure["UNLOADED_RADIUS"], mf.structure.get("Q_RE0", 1.0)
    for given in (None, rng.choice([-1, 1], n) * 10 ** rng.uniform(-1, 4, n)):
        res, said = _said(evaluate, mf, kappa, 0.0, mf.fnomin, vx=vx, omega=given)
        out = res.outputs
        text = " | ".join(said)
        fast = (np.abs(vx) > bound) | (np.abs(out["omega"]) * r0 > bound)
        assert ("an implausible" in text) == bool(fast.any())
        calm = ~fast
        # without a speed warning the radii are those a tyre has
        assert np.all(out["Re"][calm] <= r0 * (q_re0 + GROWTH_SHARE) + 1e-12)
        assert np.all(out["Rl"][calm] <= r0 * (q_re0 + GROWTH_SHARE) + 1e-12)
        if given is not None:
            off = np.abs(given * out["Re"] - (1 + kappa) * vx)
            far = off > 0.1 * np.maximum(np.abs(vx), mf.structure["VXLOW"])
            assert ("contradicts the slip ratio" in text) == bool(far.any())
            m = re.search(r"on (\d+) row\(s\): omega R_e", text)
            assert m is not None and int(m.group(1)) == int(far.sum())


def test_the_wheel_speed_the_slip_ratio_gives_is_never_a_contradiction(mf61) -> None:
    vx = np.array([-30.0, -1.0, -0.2, 0.0, 0.3, 1.0, 16.6, 60.0])
    kappa = np.array([0.1, -0.2, 0.05, 0.0, 0.3, -0.5, 0.12, -0.08])
    free, _ = _said(mf61.steady_state, kappa, 0.02, 5000.0, vx=vx)
    res, said = _said(mf61.steady_state, kappa, 0.02, 5000.0, vx=vx, omega=free["omega"])
    assert not [w for w in said if "contradicts" in w or "implausible" in w], said
    np.testing.assert_allclose(res["Rl"], free["Rl"], rtol=1e-12)


def test_the_findings_commands_warn_on_every_path(capsys) -> None:
    for argv, what in ((["--vx", "1e6", "--kappa", "0.05"], "an implausible speed"),
                       (["--omega", "500", "--kappa", "0.05"], "contradicts the slip ratio"),
                       (["--omega", "500", "--kappa", "0.05"], "an implausible wheel speed")):
        assert main(["tyre", "mf", "MagicFormula61", *argv]) == 0
        _, err = capsys.readouterr()
        assert what in err
        assert main(["tyre", "mf", "MagicFormula61", *argv, "--json"]) == 0
        doc = json.loads(capsys.readouterr()[0])
        assert [w for w in doc["warnings"] if what in w]


def test_a_deflection_to_the_centre_is_no_loaded_radius(tmp_path) -> None:
    pf = read_property_file(packaged_example("MagicFormula61"))
    pf.sections["VERTICAL"]["VERTICAL_STIFFNESS"] = 8000.0  # a soft hostile file
    pf.sections["VERTICAL"]["Q_FZ2"] = 0.0
    path = tmp_path / "soft.tir"
    path.write_text(format_tir(pf))
    mf, _ = _said(MagicFormula.from_file, path)
    out, said = _said(mf.steady_state, 0.0, 0.0, np.array([500.0, 6000.0]))
    assert out["Rl"][0] > 0 and np.isnan(out["Rl"][1])  # before: 0 m, silently
    assert [w for w in said if "1 row(s) deflect the tyre to its centre" in w]


def test_generated_turn_slips_are_plausible_or_warned() -> None:
    """Generated turn slips (|phit| log-uniform 1e-3..1e7 1/m, speeds 0..60 m/s either way,
    slip angles to 60 deg): warned of exactly where the wheel's yaw rate |phit vx| exceeds
    the bound, however small the path radius at a low speed (a wheel pivoting when parked).
    Before: phit 1e6 1/m at 16.6 m/s gave M_z 537 N m without a word."""
    mf = MagicFormula.from_file("MagicFormula61")
    rng = np.random.default_rng(36)
    n = 200
    phit = rng.choice([-1, 1], n) * 10 ** rng.uniform(-3, 7, n)
    vx = rng.choice([-1, 1], n) * np.where(rng.random(n) < 0.2, 0.0, rng.uniform(0, 60, n))
    alpha = np.radians(rng.uniform(-60, 60, n))
    rate = np.abs(phit * vx)
    fast = rate > YAW_RATE_LIMIT
    assert 0 < fast.sum() < n
    _, said = _said(evaluate, mf, 0.0, alpha, mf.fnomin, vx=vx, phit=phit, turn_slip=True)
    (turn,) = [w for w in said if "an implausible turn slip" in w]
    assert f"on {int(fast.sum())} row(s)" in turn
    calm = ~fast
    _, said = _said(evaluate, mf, 0.0, alpha[calm], mf.fnomin, vx=vx[calm], phit=phit[calm],
                    turn_slip=True)
    assert not [w for w in said if "turn slip" in w], said
    # parking: a path radius of 0.5 m at 0.5 m/s (1 rad/s), and a pivot at a standing wheel
    for vx_, phit_ in ((0.5, 2.0), (0.0, 1e6)):
        _, said = _said(evaluate, mf, 0.0, 0.0, mf.fnomin, vx=vx_, phit=phit_,
                        turn_slip=True, limit_checks=vx_ != 0.0)
        assert not [w for w in said if "implausible turn slip" in w], said


def test_an_implausible_turn_slip_is_said_on_every_path(capsys) -> None:
    argv = ["tyre", "mf", "MagicFormula61", "--phit", "1e6", "--turn-slip", "--outputs", "Mz"]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert "warning: MagicFormula61_Parameters: an implausible turn slip on 1 row(s)" in err
    assert main([*argv, "--json"]) == 0
    doc = json.loads(capsys.readouterr()[0])
    assert [w for w in doc["warnings"] if "yaw rate |phit vx| up to 1.66e+07 rad/s" in w]


# --------------------------------------------------- F3: a standing wheel, no limit checks

@pytest.mark.parametrize("turn_slip", [False, True])
def test_a_standing_wheel_without_the_limit_checks_is_warned_of(turn_slip: bool) -> None:
    variant = Path(__file__).parent / "data" / "mfeval" / "MF61_turnslip_variant.tir"
    mf = MagicFormula.from_file(str(variant) if turn_slip else "MagicFormula61")
    vx = np.array([-1e-9, 0.0, 1e-9])
    kw = {"turn_slip": turn_slip, "phit": 0.1 if turn_slip else 0.0}
    out, said = _said(mf.steady_state, 0.0, np.radians(3.0), 6000.0, np.radians(2.0),
                      vx=vx, limit_checks=False, **kw)
    standing = [w for w in said if "at a standing wheel" in w]
    assert len(standing) == 1 and "1 row(s)" in standing[0]
    assert abs(out["Fy"][1] - out["Fy"][2]) > 1000  # the jump the warning names
    # with the limit checks the slips go to 0 with the speed: no jump, no such warning
    out, said = _said(mf.steady_state, 0.0, np.radians(3.0), 6000.0, np.radians(2.0),
                      vx=vx, **kw)
    assert not [w for w in said if "at a standing wheel" in w]
    assert np.ptp(out["Fy"]) < 1e-3 * abs(mf.fnomin)


# ------------------------------------------------------------------ cosmetic findings

def test_a_range_warning_says_what_lies_outside_and_how_many(mf61) -> None:
    rng = np.random.default_rng(7)
    lo, hi = mf61.limits["kappa"]
    for _ in range(20):
        kappa = rng.uniform(-2.5, 2.5, int(rng.integers(1, 40)))
        below, above = kappa[kappa < lo], kappa[kappa > hi]
        _, said = _said(mf61.fx0, kappa, mf61.fnomin)
        ranged = [w for w in said if "kappa of" in w]
        if not below.size and not above.size:
            assert not ranged
            continue
        (text,) = ranged
        assert f"kappa of {below.size + above.size} of {kappa.size} value(s)" in text
        if below.size:
            assert f"{below.size} below it, down to {below.min():g}" in text
        if above.size:
            assert f"{above.size} above it, up to {above.max():g}" in text


def test_transient_slip_says_each_warning_once(mf61) -> None:
    t = np.linspace(0.0, 1.0, 21)
    res, said = _said(transient_slip, mf61, t, 0.5, 4000.0, kappa=0.2, alpha=0.1)
    assert len(said) == len(set(said)) and said == res.warnings
    assert len([w for w in said if "VXLOW" in w]) == 1


def test_inst_kya_is_given_per_load_or_its_nan_is_explained(mf61, capsys) -> None:
    assert main(["tyre", "mf", "MagicFormula61", "--loads", "3,6", "--alpha", "-5:5:3",
                 "--outputs", "Fy,instKya", "--json"]) == 0
    rows = json.loads(capsys.readouterr()[0])["rows"]
    assert len(rows) == 6 and all(np.isfinite(r["instKya"]) for r in rows)
    for load in (3000.0, 6000.0):  # each load's sweep: MFeval's forward difference
        fy = [r["Fy"] for r in rows if r["fz"] == load]
        alpha = [r["alpha"] for r in rows if r["fz"] == load]
        ky = [r["instKya"] for r in rows if r["fz"] == load]
        assert ky[0] == pytest.approx((fy[1] - fy[0]) / (alpha[1] - alpha[0]), rel=1e-12)
        assert ky[2] == ky[1]
    # the loads alternating along the last axis: NaN, and said why
    res, said = _said(evaluate, mf61, 0.0, np.radians([-5.0, -5.0, 5.0, 5.0]),
                      np.array([3000.0, 6000.0, 3000.0, 6000.0]), names=["instKya"])
    assert np.isnan(res.outputs["instKya"]).all()
    assert [w for w in res.warnings if "instKya is NaN on 4 of 4 row(s)" in w]
    # one point, or one slip angle at several loads, asked for by name: said too
    for alpha, fz in ((0.05, 4000.0), (0.05, np.array([3000.0, 6000.0]))):
        res, said = _said(evaluate, mf61, 0.0, alpha, fz, names=["instKya"])
        assert np.isnan(res.outputs["instKya"]).all()
        assert [w for w in said if "instKya is NaN on" in w], (alpha, fz)
    # asked for with every output (rows of measured data): NaN by design, not warned of
    _, said = _said(evaluate, mf61, 0.0, np.radians([-5.0, -5.0, 5.0, 5.0]),
                    np.array([3000.0, 6000.0, 3000.0, 6000.0]))
    assert not [w for w in said if "instKya" in w]


# ------------------------------------------------------------ command-line findings

def test_a_wheel_speed_given_is_one_column(capsys) -> None:
    """Before: the text of ``--omega`` printed the omega column twice (input and output)."""
    assert main(["tyre", "mf", "MagicFormula61", "--kappa", "0.05", "--omega", "45",
                 "--outputs", "Fx,omega,Re"]) == 0
    head = capsys.readouterr()[0].splitlines()[2]
    assert head.split().count("omega") == 1 and head.split()[-1] == "clamped"


@pytest.mark.parametrize(("option", "given", "item"), [
    ("--kappa", "0,,0.1", 2), ("--kappa", ",0.1", 1), ("--alpha", "0.1, ", 2),
    ("--outputs", "Fx,,Fy", 2)])
def test_a_list_with_an_empty_item_says_so(capsys, option: str, given: str,
                                           item: int) -> None:
    """Before: ``--kappa 0,,0.1`` was told of an 'empty bound' of a range, and
    ``--outputs Fx,,Fy`` dropped the empty item silently."""
    assert main(["tyre", "mf", "MagicFormula61", f"{option}={given}", "--kappa", "0"]
                if option == "--outputs" else
                ["tyre", "mf", "MagicFormula61", f"{option}={given}"]) == 2
    err = capsys.readouterr()[1]
    assert f"item {item} of the list is empty" in err and "bound" not in err


@pytest.mark.parametrize("json_out", [False, True])
def test_what_was_warned_before_a_refusal_is_said_before_its_error(capsys,
                                                                   json_out: bool) -> None:
    """Before: ``--vx 1e200`` warned of an implausible speed, then refused a moment past
    floating point; the command line said the refusal only (the warnings were collected
    inside the evaluation and lost with its exception)."""
    argv = ["tyre", "mf", "MagicFormula61", "--vx", "1e200", *(["--json"] if json_out else [])]
    assert main(argv) == 2
    out, err = capsys.readouterr()
    lines = err.splitlines()
    assert out == "" and lines[-1].startswith("error: My is not finite")
    assert [w for w in lines[:-1] if w.startswith("warning: ") and "implausible speed" in w]
    assert all(w.startswith("warning: ") for w in lines[:-1])
    mf = MagicFormula.from_file("MagicFormula61")
    with pytest.warns(UserWarning, match="an implausible speed"), \
            pytest.raises(InputError, match="My is not finite"):
        evaluate(mf, 0.0, 0.0, mf.fnomin, vx=1e200)


def test_a_pressure_no_tyre_runs_at_is_refused_before_any_warning(capsys) -> None:
    """With the warnings before a refusal said, the pressure's range warning ('...
    extrapolation') came before its refusal: the pressure is now checked first."""
    assert main(["tyre", "mf", "MagicFormula61", "--pressure", "2.6", "--kappa", "0"]) == 2
    assert capsys.readouterr()[1].count("\n") == 1


def test_a_loaded_radius_past_floating_point_is_refused(mf61) -> None:
    """Before: a slip ratio of 1e300 printed R_l inf with exit 0 (null in JSON)."""
    with pytest.raises(InputError, match="Rl is not finite"), warnings.catch_warnings():
        warnings.simplefilter("ignore")
        evaluate(mf61, 1e300, 0.0, mf61.fnomin)


# ------------------------------------------------------- findings of the hostile pass

def test_a_camber_share_of_one_or_more_is_refused_with_its_coefficients(tmp_path) -> None:
    """Before: PECP1 = 1 (the model divides by 1 - eps_gamma) refused turn slip at phit = 0
    as 'F_y is not finite ... past floating point'; a PECP2 that takes eps_gamma past 1 at
    a high load gave a spin shift of the other sign without a word."""
    pf = read_property_file(packaged_example("MagicFormula61"))
    for pecp1, pecp2, fz in ((1.0, 0.0, 6752.0), (0.75, 0.12, 4 * 6752.0)):
        pf.sections["TURNSLIP_COEFFICIENTS"].update(PECP1=pecp1, PECP2=pecp2)
        path = tmp_path / "share.tir"
        path.write_text(format_tir(pf))
        mf, _ = _said(MagicFormula.from_file, path)
        with pytest.raises(InputError, match=r"eps_gamma = PECP1 \(1 \+ PECP2 dfz\)"), \
                warnings.catch_warnings():
            warnings.simplefilter("ignore")
            evaluate(mf, 0.0, 0.0, fz, np.radians(2.0), turn_slip=True)
    _, said = _said(evaluate, mf, 0.0, 0.0, 6752.0, turn_slip=True, phit=0.2)  # below 1
    assert not [w for w in said if "eps_gamma" in w]


def test_transient_slip_says_an_implausible_turn_slip_once(mf61) -> None:
    t = np.linspace(0.0, 0.5, 21)
    res, said = _said(transient_slip, mf61, t, 16.6, 5000.0, alpha=0.05, phit=1e6,
                      turn_slip=True)
    assert len([w for w in said if "an implausible turn slip" in w]) == 1, said
    assert len([w for w in res.warnings if "an implausible turn slip" in w]) == 1


def test_reduce_refuses_too_few_points_by_its_option(capsys) -> None:
    """Before: ``--points 3`` passed the option's bound (3) and met the library's (10):
    'n must be an integer >= 10', an argument the command line does not have."""
    assert main(["tyre", "reduce", "MagicFormula61", "--load", "4", "--points", "5"]) == 2
    err = capsys.readouterr()[1]
    assert "--points" in err and "n must" not in err


def test_no_deflection_at_a_load_near_zero_names_the_load(mf61) -> None:
    """Before: a load of 1e-297 N was told its free radius had grown past the load's."""
    out, said = _said(evaluate, mf61, 0.1, 0.0, 1e-297)
    assert np.isnan(out.outputs["Cz"][()])
    assert [w for w in said if "no deflection (a load too small" in w], said
