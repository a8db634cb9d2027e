"""Every output of the Magic Formula's table reaches every path: the API, the CLI's text and
``--json``, and xarray; every input of the table is an option of the CLI; every condition
an evaluation warns of (an input beyond the file's range, a clamped load, ``saturate``)
reaches every path with the rows it clamped.

The outputs and inputs are enumerated from the library's own tables
(:data:`~frictionlaws.tyre.mf.outputs.OUTPUTS`, :data:`~frictionlaws.tyre.mf.inputs.INPUTS`),
the paths from :data:`PATHS`: a new output or input is tested without a line added here.
"""

from __future__ import annotations

import json
import re
import warnings
from collections.abc import Callable
from typing import Any

import numpy as np
import pytest

from frictionlaws.cli import main
from frictionlaws.tyre.mf.inputs import INPUTS
from frictionlaws.tyre.mf.model import MagicFormula
from frictionlaws.tyre.mf.outputs import OUTPUTS

xr = pytest.importorskip("xarray")

EXAMPLES = ("MagicFormula52", "MagicFormula61", "MagicFormula62")
#: The conditions every path evaluates: SI values, and the CLI's text of them.
KAPPA, ALPHA_DEG, LOADS_KN, GAMMA_DEG = (0.0, 0.05), (0.0, 4.0), (3.0, 6.0), (2.0,)


def _cli(capsys: pytest.CaptureFixture[str], name: str, *extra: str) -> tuple[str, str]:
    code = main(["tyre", "mf", name, "--kappa", ",".join(map(str, KAPPA)),
                 "--alpha", ",".join(map(str, ALPHA_DEG)), "--loads",
                 ",".join(map(str, LOADS_KN)), "--gamma", ",".join(map(str, GAMMA_DEG)),
                 *extra])
    out, err = capsys.readouterr()
    assert code == 0, err
    return out, err


def _grid() -> dict[str, np.ndarray]:
    """The rows the CLI evaluates: every combination, in the order of the table's inputs
    but for the slip angle, which varies fastest (a sweep per combination: instKya)."""
    k, z, g, a = np.meshgrid(KAPPA, np.array(LOADS_KN) * 1e3, np.radians(GAMMA_DEG),
                             np.radians(ALPHA_DEG), indexing="ij")
    return {"kappa": k.ravel(), "alpha": a.ravel(), "fz": z.ravel(), "gamma": g.ravel()}


def _api(mf: MagicFormula, capsys: Any) -> dict[str, np.ndarray]:
    g = _grid()
    return mf.steady_state(g["kappa"], g["alpha"], g["fz"], g["gamma"])


def _cli_json(mf: MagicFormula, capsys: Any) -> dict[str, np.ndarray]:
    out, _ = _cli(capsys, mf.source.removeprefix("packaged:"), "--json")
    doc = json.loads(out)
    for name, spec in doc["outputs"].items():
        assert spec["unit"] == OUTPUTS[name].unit and spec["meaning"] == OUTPUTS[name].meaning
    return {name: np.array([np.nan if r[name] is None else r[name] for r in doc["rows"]])
            for name in doc["outputs"]}


def _cli_text(mf: MagicFormula, capsys: Any) -> dict[str, np.ndarray]:
    out, _ = _cli(capsys, mf.source.removeprefix("packaged:"))
    lines = [line for line in out.splitlines()
             if line and not line.startswith(("note:", mf.name))]
    head = re.findall(r"(\S+) \[([^\]]*)\]", lines[0])  # "name [unit]" per column
    rows = [line.split() for line in lines[1:]]
    found = {}
    for i, (label, unit) in enumerate(head):
        if label in OUTPUTS:
            assert unit == OUTPUTS[label].unit, label
            found[label] = np.array([float(r[i]) for r in rows])
    return found


def _xarray(mf: MagicFormula, capsys: Any) -> dict[str, np.ndarray]:
    g = _grid()
    row = xr.DataArray(np.arange(g["kappa"].size), dims="row")
    ds = mf.steady_state(*(xr.DataArray(g[k], dims="row", coords={"row": row})
                           for k in ("kappa", "alpha", "fz", "gamma")))
    out = {}
    for name in ds.data_vars:
        if name == "clamped":
            continue
        assert ds[name].attrs["units"] == OUTPUTS[name].unit
        assert ds[name].attrs["long_name"] == OUTPUTS[name].meaning
        assert ds[name].dims == ("row",)
        out[name] = ds[name].values
    return out


#: The paths an output reaches, each giving output name -> values per row.
PATHS: dict[str, Callable[[MagicFormula, Any], dict[str, np.ndarray]]] = {
    "api": _api, "cli-json": _cli_json, "cli-text": _cli_text, "xarray": _xarray}


@pytest.fixture(scope="module")
def evaluated() -> dict[str, MagicFormula]:
    return {name: MagicFormula.from_file(name) for name in EXAMPLES}


@pytest.mark.parametrize("path", PATHS)
@pytest.mark.parametrize("example", EXAMPLES)
def test_every_output_reaches_every_path(example: str, path: str, evaluated: Any,
                                         capsys: pytest.CaptureFixture[str]) -> None:
    mf = evaluated[example]
    api = _api(mf, capsys)
    got = PATHS[path](mf, capsys)
    expected = [name for name in OUTPUTS if name in api]  # the file gives these
    assert list(got) == expected
    assert set(OUTPUTS) - set(api) <= ({"Cx", "Cy"} if example.endswith("52") else set())
    for name in expected:
        rtol = 1e-5 if path == "cli-text" else 0.0  # the text prints six digits
        np.testing.assert_allclose(got[name], api[name], rtol=rtol, atol=0.0,
                                   equal_nan=True, err_msg=f"{name} via {path}")


def test_every_input_is_an_option_of_the_cli() -> None:
    from frictionlaws.cli import build_parser

    flags = {s for a in _mf_parser(build_parser())._actions for s in a.option_strings}
    for name in INPUTS:
        assert ("--loads" if name == "fz" else f"--{name.replace('_', '-')}") in flags, name


def _mf_parser(parser: Any) -> Any:
    """The parser of ``frictionlaws tyre mf``."""
    for action in parser._actions:
        if getattr(action, "choices", None) and "tyre" in action.choices:
            tyre = action.choices["tyre"]
            for sub in tyre._actions:
                if getattr(sub, "choices", None) and "mf" in sub.choices:
                    return sub.choices["mf"]
    raise AssertionError("no tyre mf parser")


# --------------------------------------------------- conditions reach every path alike

#: Conditions an evaluation warns of, each with the CLI's options, the API's arguments and
#: what its warning and rows say: an input beyond the file's range, a load clamped at
#: FZMAX, inputs clamped by ``saturate``.
CONDITIONS: dict[str, dict[str, Any]] = {
    "extrapolated": {"cli": ["--kappa", "0.05,1.5"], "api": {"kappa": [0.05, 1.5]},
                     "model": {}, "saturate": False, "warning": "kappa of 1 of 2",
                     "clamped": {}},
    "clamped": {"cli": ["--loads", "4,25", "--loads-above-fzmax", "clamp"],
                "api": {"fz": [4000.0, 25000.0]}, "model": {"loads_above_fzmax": "clamp"},
                "saturate": False, "warning": "evaluated at FZMAX (clamped",
                "clamped": {"fz": [False, True]}},
    "saturated": {"cli": ["--kappa", "0.05,1.5", "--saturate"], "api": {"kappa": [0.05, 1.5]},
                  "model": {}, "saturate": True, "warning": "(clamped, saturate=True)",
                  "clamped": {"kappa": [False, True]}},
}


def _condition_api(c: dict[str, Any], capsys: Any) -> tuple[list[str], list[list[str]]]:
    from frictionlaws.tyre.mf.outputs import evaluate

    mf = MagicFormula.from_file("MagicFormula61", **c["model"])
    kw = {"kappa": 0.05, "alpha": 0.0, "fz": 4000.0, **{k: np.array(v) for k, v in
                                                          c["api"].items()}}
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        res = evaluate(mf, kw["kappa"], kw["alpha"], kw["fz"], saturate=c["saturate"])
    rows = res.to_dict()["rows"]
    assert [str(w.message) for w in caught] == res.warnings  # once each, as held
    return res.warnings, [r["clamped"] for r in rows]


def _condition_cli_json(c: dict[str, Any], capsys: Any) -> tuple[list[str], list[list[str]]]:
    code = main(["tyre", "mf", "MagicFormula61", *_with_defaults(c["cli"]), "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    doc = json.loads(out)
    return doc["warnings"], [r["clamped"] for r in doc["rows"]]


def _condition_cli_text(c: dict[str, Any], capsys: Any) -> tuple[list[str], list[list[str]]]:
    code = main(["tyre", "mf", "MagicFormula61", *_with_defaults(c["cli"])])
    out, err = capsys.readouterr()
    assert code == 0, err
    lines = [line for line in out.splitlines() if line[:1] == " " or line[:1].isdigit()]
    rows = [[] if line.split()[-1] == "-" else line.split()[-1].split(",")
            for line in lines]
    return [line.removeprefix("warning: ") for line in err.splitlines()], rows


def _condition_xarray(c: dict[str, Any], capsys: Any) -> tuple[list[str], list[list[str]]]:
    mf = MagicFormula.from_file("MagicFormula61", **c["model"])
    kw: dict[str, Any] = {"kappa": 0.05, "alpha": 0.0, "fz": 4000.0}
    kw.update({k: xr.DataArray(v, dims="row") for k, v in c["api"].items()})
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        ds = mf.steady_state(kw["kappa"], kw["alpha"], kw["fz"], saturate=c["saturate"])
    flags = ds["clamped"].values.tolist()
    return list(ds.attrs["warnings"]), [sorted(ds.attrs["clamped"]) if f else [] for f in flags]


def _with_defaults(argv: list[str]) -> list[str]:
    """The CLI's options of a condition, with the inputs the API takes by default."""
    extra = [] if "--kappa" in argv else ["--kappa", "0.05"]
    return argv + extra + ([] if "--loads" in argv else ["--loads", "4"])


#: The paths a condition reaches, each giving (the warnings, the inputs clamped per row).
CONDITION_PATHS: dict[str, Callable[[dict[str, Any], Any],
                                    tuple[list[str], list[list[str]]]]] = {
    "api": _condition_api, "cli-json": _condition_cli_json, "cli-text": _condition_cli_text,
    "xarray": _condition_xarray}


@pytest.mark.parametrize("path", CONDITION_PATHS)
@pytest.mark.parametrize("condition", CONDITIONS)
def test_every_condition_reaches_every_path_alike(condition: str, path: str,
                                                  capsys: pytest.CaptureFixture[str]) -> None:
    c = CONDITIONS[condition]
    said, clamped = CONDITION_PATHS[path](c, capsys)
    assert [w for w in said if c["warning"] in w], (path, said)
    expected = [[k for k, rows in c["clamped"].items() if rows[i]] for i in range(2)]
    assert clamped == expected, (path, clamped)
