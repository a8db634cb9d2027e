"""A generated hostile corpus over the newest Magic Formula features: every condition on
every property file through every path says the same, or is refused alike.

The conditions are the values and options a new user tries (an input beyond the file's
range in slip, angle, camber, load, pressure and speed; a load clamped at FZMAX or reduced
below FZMIN; ``saturate``; an option the file's version cannot apply; a speed the model
does not cover; a turn slip within reason and one no wheel turns at), singly and in
pairs; the files are the packaged MF 5.2, 6.1 and 6.2 and an MF 5.2 without its load
range (no FZMAX, no FZMIN).  Each case runs through the API
(:func:`~frictionlaws.tyre.mf.outputs.evaluate`, with the Python warnings it raises),
xarray (the dataset's ``warnings`` attribute), ``tyre mf --json`` (its ``warnings`` list
and per-row ``clamped`` flags) and the text of ``tyre mf`` (its ``warning:`` lines and
``clamped`` column), and the load conditions also through the summary (``tyre mf`` without
conditions) on the API, JSON and text paths.  Every path gives the same warnings (the text
shortens long ones as every command does) and the same rows clamped, or every path refuses:
the API with :class:`~frictionlaws.base.errors.InputError`, the command line with exit 2
and one ``error:`` line (beside the ``warning:`` lines of what ran before, as every command
prints them).  Neither a traceback nor exit 0 with a warning lost.

Before, the JSON of ``tyre mf`` lost an option the file cannot apply (the text warned of it
on stderr; the JSON had it in its notes only, with an empty ``warnings`` list); a turn slip
of 1e6 1/m at 16.6 m/s (a yaw rate of 1.7e7 rad/s) gave M_z 537 N m with no word.
"""

from __future__ import annotations

import itertools
import json
import warnings
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.cli._messages import short_warning
from frictionlaws.tyre.mf.model import MagicFormula
from frictionlaws.tyre.mf.outputs import evaluate
from frictionlaws.tyre.mf.plausibility import YAW_RATE_LIMIT, speed_bound
from frictionlaws.tyre.mf.tir import format_tir, packaged_example, read_property_file
from frictionlaws.tyre.mf.turn_slip import check_turn_slip

#: A corpus (hundreds of evaluations): run with the slow tests, on the newest set only.
pytestmark = pytest.mark.slow

xr = pytest.importorskip("xarray")


@dataclass(frozen=True)
class Condition:
    """One thing a user tries: the CLI's options and the API's inputs (SI) and model
    options for the same."""

    cli: tuple[str, ...]
    inputs: dict[str, float] = field(default_factory=dict)
    model: dict[str, str] = field(default_factory=dict)
    saturate: bool = False
    options: dict[str, Any] = field(default_factory=dict)  # of the evaluation


#: The conditions tried, singly and in pairs (the CLI's units: deg, kN, kPa, m/s).
SINGLE: dict[str, Condition] = {
    "kappa-beyond": Condition(("--kappa", "1.6"), {"kappa": 1.6}),
    "alpha-beyond": Condition(("--alpha", "88"), {"alpha": np.radians(88.0)}),
    "gamma-beyond": Condition(("--gamma", "20"), {"gamma": np.radians(20.0)}),
    "load-low": Condition(("--loads", "0.05"), {"fz": 50.0}),
    "load-high": Condition(("--loads", "30"), {"fz": 30000.0}),
    "pressure-beyond": Condition(("--pressure", "600"), {"pressure": 6e5}),
    "pressure-within": Condition(("--pressure", "250"), {"pressure": 2.5e5}),
    "speed-high": Condition(("--vx", "90"), {"vx": 90.0}),
    "speed-backwards": Condition(("--vx", "-5"), {"vx": -5.0}),
    "speed-low": Condition(("--vx", "0.5"), {"vx": 0.5}),
    "clamp": Condition(("--loads-above-fzmax", "clamp"), model={"loads_above_fzmax": "clamp"}),
    "degressive": Condition(("--friction-scaling", "degressive"),
                            model={"friction_scaling": "degressive"}),
    "published": Condition(("--equations", "published"), model={"equations": "published"}),
    "saturate": Condition(("--saturate",), saturate=True),
    "speed-implausible": Condition(("--vx", "1000"), {"vx": 1000.0}),
    "omega-contradicts": Condition(("--omega", "500"), {"omega": 500.0}),
    "standing-no-checks": Condition(("--vx", "0", "--no-limit-checks"), {"vx": 0.0},
                                    options={"limit_checks": False}),
    # a path radius of 5 m (parking), and of 1 um at speed (a yaw rate of 1.7e7 rad/s)
    "turn-slip-within": Condition(("--phit", "0.2", "--turn-slip"), {"phit": 0.2},
                                  options={"turn_slip": True}),
    "turn-slip-implausible": Condition(("--phit", "1e6", "--turn-slip"), {"phit": 1e6},
                                       options={"turn_slip": True}),
}
#: Pairs that ask one thing each (an input given twice is not a pair).
PAIRS = {f"{a}+{b}": (a, b) for a, b in itertools.combinations(SINGLE, 2)
         if not set(SINGLE[a].inputs) & set(SINGLE[b].inputs)
         and not (SINGLE[a].cli[0] == SINGLE[b].cli[0])}
FILES = ("MagicFormula52", "MagicFormula61", "MagicFormula62", "no-load-range")
#: Where a condition's input is not given: the file's nominal state, one row.
NOMINAL = {"kappa": 0.05, "alpha": 0.02, "gamma": 0.0, "pressure": None, "vx": None,
           "omega": None, "phit": 0.0}


def _combined(names: tuple[str, ...]) -> Condition:
    parts = [SINGLE[n] for n in names]
    return Condition(tuple(a for c in parts for a in c.cli),
                     {k: v for c in parts for k, v in c.inputs.items()},
                     {k: v for c in parts for k, v in c.model.items()},
                     any(c.saturate for c in parts),
                     {k: v for c in parts for k, v in c.options.items()})


CASES = {**{n: (n,) for n in SINGLE}, **PAIRS}


@pytest.fixture(scope="module")
def files(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    pf = read_property_file(packaged_example("MagicFormula52"))
    del pf.sections["VERTICAL_FORCE_RANGE"]  # no FZMIN, no FZMAX
    path = tmp_path_factory.mktemp("corpus") / "no_load_range.tir"
    path.write_text(format_tir(pf))
    return {"MagicFormula52": "MagicFormula52", "MagicFormula61": "MagicFormula61",
            "MagicFormula62": "MagicFormula62", "no-load-range": str(path)}


@dataclass
class Said:
    """What one path said: the warnings (None: refused) and the inputs clamped per row."""

    warnings: list[str] | None
    clamped: list[list[str]] = field(default_factory=list)


def _api(file: str, c: Condition) -> Said:
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            mf = MagicFormula.from_file(file, **c.model)
            fz = c.inputs.get("fz", mf.fnomin)
            kw = {**NOMINAL, **{k: v for k, v in c.inputs.items() if k != "fz"}}
            res = evaluate(mf, kw["kappa"], kw["alpha"], fz, kw["gamma"], kw["pressure"],
                           kw["vx"], c.saturate, omega=kw["omega"], phit=kw["phit"],
                           **c.options)
        except InputError:
            return Said(None)
    raised = list(dict.fromkeys(str(w.message) for w in caught))
    assert raised == res.warnings  # what the result holds is what Python was told
    return Said(res.warnings, [r["clamped"] for r in res.to_dict()["rows"]])


def _xarray(file: str, c: Condition) -> Said:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            mf = MagicFormula.from_file(file, **c.model)
            fz = c.inputs.get("fz", mf.fnomin)
            kw = {**NOMINAL, **{k: v for k, v in c.inputs.items() if k != "fz"}}
            ds = mf.steady_state(xr.DataArray([kw["kappa"]], dims="row"), kw["alpha"], fz,
                                 kw["gamma"], kw["pressure"], kw["vx"], c.saturate,
                                 omega=kw["omega"], phit=kw["phit"], **c.options)
        except InputError:
            return Said(None)
    rows = [sorted(ds.attrs["clamped"]) if flag else [] for flag in ds["clamped"].values]
    return Said(list(ds.attrs["warnings"]), rows)


def _cli(capsys: pytest.CaptureFixture[str], file: str, argv: tuple[str, ...],
         json_out: bool) -> tuple[int, str, str]:
    steady = ["--kappa", str(NOMINAL["kappa"]), "--alpha", str(np.degrees(NOMINAL["alpha"]))]
    given = set(argv)
    extra = [a for i in range(0, len(steady), 2) if steady[i] not in given
             for a in steady[i:i + 2]]
    code = main(["tyre", "mf", file, *argv, *extra, *(["--json"] if json_out else [])])
    out, err = capsys.readouterr()
    assert code in (0, 2), (code, err)
    assert "Traceback" not in err
    if code == 2:
        said = [line for line in err.splitlines() if not line.startswith("warning: ")]
        assert len(said) == 1 and said[0].startswith("error: ") and out == "", err
    return code, out, err


def _cli_json(capsys: Any, file: str, c: Condition) -> Said:
    code, out, _ = _cli(capsys, file, c.cli, True)
    if code == 2:
        return Said(None)
    doc = json.loads(out)
    return Said(doc["warnings"], [r["clamped"] for r in doc["rows"]])


def _cli_text(capsys: Any, file: str, c: Condition) -> Said:
    code, out, err = _cli(capsys, file, c.cli, False)
    if code == 2:
        return Said(None)
    rows = [line.split()[-1] for line in out.splitlines() if line[:1] in " 0123456789-"]
    said = [line.removeprefix("warning: ") for line in err.splitlines()]
    assert all(line.startswith("warning: ") for line in err.splitlines()), err
    return Said(said, [[] if r == "-" else r.split(",") for r in rows])


def _short(said: Said) -> Said:
    """As the command line prints it."""
    return Said(None if said.warnings is None else [short_warning(w) for w in said.warnings],
                said.clamped)


#: The plausibility conditions (speed, wheel speed, a standing wheel without the limit
#: checks): their pairs are tried on one file (the rule is the same for every file).
PLAUSIBILITY = {"speed-implausible", "omega-contradicts", "standing-no-checks",
                "turn-slip-within", "turn-slip-implausible"}


@pytest.mark.parametrize(("case", "file"), [
    (case, file) for case in CASES for file in FILES
    if case in SINGLE or (file != "MagicFormula62"  # 6.2's ranges are 6.1's
                          and (file == "MagicFormula61" or not PLAUSIBILITY & set(CASES[case])))])
def test_a_condition_is_said_alike_on_every_path_or_refused_alike(
        case: str, file: str, files: dict[str, str],
        capsys: pytest.CaptureFixture[str]) -> None:
    c = _combined(CASES[case])
    path = files[file]
    api = _api(path, c)
    said = {"xarray": _xarray(path, c), "cli-json": _cli_json(capsys, path, c)}
    for name, other in said.items():
        assert other == api, (name, other, api)
    assert _cli_text(capsys, path, c) == _short(api)
    _expected(path, c, api)


def _has_turn_slip(mf: MagicFormula) -> bool:
    try:
        check_turn_slip(mf)
    except InputError:
        return False
    return True


def _expected(path: str, c: Condition, api: Said) -> None:
    """The corpus is not vacuous: what the file's ranges and version call for is said."""
    checks = c.options.get("limit_checks", True)
    turn_slip = c.options.get("turn_slip", False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mf = MagicFormula.from_file(path)
    if api.warnings is None:  # saturate needs the limit checks, turn slip its
        # coefficients; the rest is evaluated
        assert c.saturate and not checks or turn_slip and not _has_turn_slip(mf)
        return
    said = " | ".join(api.warnings)
    vxlow = mf.structure.get("VXLOW", 0.0)
    vx = c.inputs.get("vx", mf.need("LONGVL"))
    low_speed = abs(vx) <= vxlow
    assert ("VXLOW" in said) == low_speed, said
    assert ("an implausible speed" in said) == (abs(vx) > speed_bound(mf)[0]), said
    assert ("the wheel speed given contradicts" in said) == ("omega" in c.inputs), said
    assert ("at a standing wheel" in said) == (vx == 0 and not checks), said
    yaw_rate = abs(c.inputs.get("phit", 0.0) * vx)
    assert ("an implausible turn slip" in said) == (yaw_rate > YAW_RATE_LIMIT), said
    for name, value in c.inputs.items():
        if low_speed and name in ("kappa", "alpha"):
            continue  # taken towards 0 with the speed: the range is checked after that
        lim = mf.limits.get(name)
        if lim is not None and not lim[0] <= value <= lim[1]:
            assert name in said, (name, said)
    if "pressure" in c.inputs and mf.nominal_pressure is None:
        assert "the pressure given is not used" in said
    if c.model.get("friction_scaling") == "degressive" and not mf.version.startswith("6"):
        assert "friction_scaling = 'degressive' is not applied" in said
    if c.model.get("loads_above_fzmax") == "clamp" and "fz" not in mf.limits:
        assert "loads_above_fzmax = 'clamp' is not applied" in said
    fz, (fzmin, fzmax) = c.inputs.get("fz", mf.fnomin), mf.limits.get("fz", (0.0, np.inf))
    load_clamped = (fz > fzmax and (c.saturate or c.model.get("loads_above_fzmax") == "clamp")
                    or (c.saturate or not checks) and fz < fzmin)  # M_x, M_y reduced
    assert ("fz" in api.clamped[0]) == load_clamped, (api.clamped, said)


# ------------------------------------------------------- the summary of a property file

#: Conditions of the summary (``tyre mf FILE`` without conditions): loads and options.
SUMMARY = {n: CASES[n] for n in CASES
           if all(not SINGLE[s].inputs or set(SINGLE[s].inputs) == {"fz"} for s in CASES[n])
           and "saturate" not in CASES[n]}


@pytest.mark.parametrize("file", FILES)
@pytest.mark.parametrize("case", SUMMARY)
def test_the_summary_says_a_condition_alike_on_every_path(
        case: str, file: str, files: dict[str, str],
        capsys: pytest.CaptureFixture[str]) -> None:
    c = _combined(SUMMARY[case])
    path = files[file]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mf = MagicFormula.from_file(path, **c.model)
        loads = [c.inputs["fz"]] if "fz" in c.inputs else None
        summary = mf.summary(loads)
    assert list(dict.fromkeys(str(w.message) for w in caught)) == summary["warnings"]
    argv = ["tyre", "mf", path, *c.cli]
    assert main([*argv, "--json"]) == 0
    out, err = capsys.readouterr()
    doc = json.loads(out)
    assert doc["warnings"] == summary["warnings"] and doc["clamped"] == summary["clamped"]
    assert doc["loads_evaluated_N"] == summary["loads_evaluated_N"]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert [line.removeprefix("warning: ") for line in err.splitlines()] == [
        short_warning(w) for w in summary["warnings"]]
    assert ("*: clamped" in out) == any(summary["clamped"])


def test_the_corpus_is_generated_over_every_condition_and_file() -> None:
    assert len(CASES) > 50 and len(SUMMARY) >= 6
    assert {s for pair in PAIRS.values() for s in pair} == set(SINGLE)
    assert Path(__file__).name.startswith("test_tyre_")


# ------------------------------------------------------------- the reduction to a slip law

#: The summary's single conditions (loads and options): ``tyre reduce`` takes the same.
REDUCE = [n for n in SUMMARY if "+" not in n]


@pytest.mark.parametrize("file", ["MagicFormula52", "no-load-range"])  # each fit costs
@pytest.mark.parametrize("case", REDUCE)
def test_the_reduction_says_a_condition_alike_on_every_path(
        case: str, file: str, files: dict[str, str],
        capsys: pytest.CaptureFixture[str]) -> None:
    from frictionlaws.tyre.reduce import reduce_mf

    c = SINGLE[case]
    path = files[file]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mf = MagicFormula.from_file(path, **c.model)
        red = reduce_mf(mf, "pacejka", fz=c.inputs.get("fz", mf.fnomin), n=21)
    assert list(dict.fromkeys(str(w.message) for w in caught)) == red.warnings
    argv = ["tyre", "reduce", path, "--load", str(c.inputs.get("fz", mf.fnomin) / 1e3),
            "--points", "21", *([] if c.cli[0] == "--loads" else c.cli)]
    assert main([*argv, "--json"]) == 0
    out, _ = capsys.readouterr()
    doc = json.loads(out)
    assert doc["warnings"] == red.warnings and doc["clamped"] == red.clamped
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert [line.removeprefix("warning: ") for line in err.splitlines()] == [
        short_warning(w) for w in red.warnings]
    assert not [w for w in red.warnings if short_warning(w) in out]  # said once: on stderr
