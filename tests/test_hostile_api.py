"""Hostile-input harness over the main API calls.

Invariant: a call returns a sound result or raises ``InputError`` (``DomainError``)
or ``FitError`` with a one-line message; never another exception type, never a
hang, never a changed input, never a non-finite or negative friction coefficient
in a result.  Every case must pass.
"""

from __future__ import annotations

import contextlib
import math
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hostile import (
    MF52_TIR,
    Snapshot,
    check_api,
    check_export_file,
    csv_bytes,
    hostile,
    params_bytes,
    rig_bytes,
    tir_bytes,
)
from hypothesis import example, given
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base.errors import InputError

pytestmark = pytest.mark.hostile




def covers(area: str) -> pytest.MarkDecorator:
    """The area a case guards; every case must pass."""
    return pytest.mark.hostile


@contextlib.contextmanager
def workdir() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="hostile-api-"))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def _finite_mu(values: Any) -> None:
    arr = np.asarray(values, dtype=float)
    assert np.all(np.isfinite(arr)), f"non-finite mu returned: {arr}"
    assert np.all(arr >= 0), f"negative mu returned: {arr}"


@hostile(30)
@given(data=csv_bytes())
def test_load_dataset_hostile(data: bytes) -> None:
    with workdir() as tmp:
        src = tmp / "d.csv"
        src.write_bytes(data)
        snap = Snapshot.take([tmp], [src])
        ds = check_api(lambda: fl.load_dataset(src), snapshot=snap)
        if not isinstance(ds, Exception):
            frame = ds.frame if hasattr(ds, "frame") else None
            if frame is not None and "mu" in frame:
                _finite_mu(frame["mu"].to_numpy())


@hostile(25)
@given(data=csv_bytes(), law=st.sampled_from(["thirion", "coulomb", "quadratic-pv"]))
def test_fit_file_hostile(data: bytes, law: str) -> None:
    with workdir() as tmp:
        src = tmp / "d.csv"
        src.write_bytes(data)
        snap = Snapshot.take([tmp], [src])
        res = check_api(lambda: fl.fit(law, src), snapshot=snap)
        if not isinstance(res, Exception):
            for p in res.params.values():
                assert p.value is None or math.isfinite(p.value), res.params


ARRAY_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([-1.0, 0.0, 1e308, -1e-300]),
)


@covers("fit")
@hostile(25)
@example(mu=[0.0, -1.0], p=[0.0])  # negative mu and mismatched lengths accepted
@given(mu=st.lists(ARRAY_VALUES, min_size=0, max_size=6),
       p=st.lists(ARRAY_VALUES, min_size=0, max_size=6))
def test_fit_arrays_hostile(mu: list[float], p: list[float]) -> None:
    """fit() on arrays makes the checks the CSV loader makes."""
    res = check_api(lambda: fl.fit("thirion", {"mu": mu, "p": p}))
    if not isinstance(res, Exception):
        assert all(math.isfinite(x) and x >= 0 for x in mu), "bad mu accepted"
        assert all(math.isfinite(x) and x >= 0 for x in p), "bad p accepted"


VARIABLE_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([None, "0.1", -1.0, 0.0, 2.0, [0.1, -0.2], [], True]),
)


@covers("fit")  # laws evaluated outside their domain give negative mu
@hostile(60)
@example(law="thesis-poly2", p=0.0, v=7.0, s=0.0, T=0.0, F_N=0.0)  # mu = -2.3
@given(law=st.sampled_from(["thirion", "coulomb", "thesis-poly2", "savkoor", "pacejka",
                            "burckhardt", "park", "exponential-decay", "schallamach"]),
       p=VARIABLE_VALUES, v=VARIABLE_VALUES, s=VARIABLE_VALUES, T=VARIABLE_VALUES,
       F_N=VARIABLE_VALUES)
def test_law_call_hostile_variables(law: str, p: Any, v: Any, s: Any, T: Any, F_N: Any) -> None:
    the_law = fl.get_law(law)
    given_vars = {"p": p, "v": v, "s": s, "T": T, "F_N": F_N}
    kwargs = {k: given_vars[k] for k in the_law.variables}
    preset = next(iter(the_law.presets), None)
    res = check_api(lambda: the_law(preset=preset, **kwargs) if preset
                    else the_law(**kwargs, **{q.name: q.default for q in the_law.params}))
    if not isinstance(res, Exception):
        _finite_mu(res)


@hostile(30)
@given(values=st.dictionaries(st.sampled_from(["a", "b", "zz"]), ARRAY_VALUES, max_size=3))
def test_law_call_hostile_parameters(values: dict[str, float]) -> None:
    law = fl.get_law("thirion")
    res = check_api(lambda: law(p=0.1e6, **values))
    if not isinstance(res, Exception):
        _finite_mu(res)


@covers("fit")  # load_result: wrong types in the file give AttributeError/ValueError
@hostile(25)
@example(params=b'{"law": "thirion", "params": {"a": 1.0, "b": {"stderr": 1}}, '
         b'"settings": -3.9e16}', fmt="abaqus")  # AttributeError in load_result
@given(params=params_bytes(), fmt=st.sampled_from(["csv", "json", "abaqus", "lsdyna",
                                                    "ansys", "radioss", "abaqus-fric-coef"]))
def test_export_from_hostile_params(params: bytes, fmt: str) -> None:
    with workdir() as tmp:
        src = tmp / "params.json"
        src.write_bytes(params)
        out = tmp / "deck.txt"
        snap = Snapshot.take([tmp], [src])

        def call() -> Any:
            result = fl.load_result(src)
            box = {v: ((0.01e6, 0.5e6, 4) if v == "p" else (0.0, 2.0, 3))
                   for v in result.law.variables}
            return fl.export(None, result, fmt, box, path=out)

        res = check_api(call, snapshot=snap, allowed=[out])
        if not isinstance(res, Exception):
            check_export_file(out, fmt)


@covers("mf")  # a negative or NaN inflation pressure is accepted
@hostile(25)
@example(data=MF52_TIR.read_bytes(), pressure=-2e5)
@given(data=tir_bytes(), pressure=st.sampled_from([None, -2e5, 0.0, float("nan"), 2.2e5]))
def test_magic_formula_from_hostile_file(data: bytes, pressure: float | None) -> None:
    with workdir() as tmp:
        src = tmp / "t.tir"
        src.write_bytes(data)
        snap = Snapshot.take([tmp], [src])
        res = check_api(lambda: fl.MagicFormula.from_file(src, pressure=pressure),
                        snapshot=snap)
        if not isinstance(res, Exception):
            assert pressure is None or (math.isfinite(pressure) and pressure > 0), \
                f"pressure {pressure} accepted"
            summary = res.summary(np.array([0.5, 1.0]) * res.fnomin)
            for key in ("mu_x_peak", "mu_y_peak"):
                _finite_mu(summary[key])


@hostile(25)
@given(data=rig_bytes())
def test_load_rig_hostile(data: bytes) -> None:
    with workdir() as tmp:
        src = tmp / "rig.toml"
        src.write_bytes(data)
        snap = Snapshot.take([tmp], [src])
        rig = check_api(lambda: fl.load_rig(src), snapshot=snap)
        if not isinstance(rig, Exception):
            for name in ("track_radius", "contact_area", "g"):
                x = getattr(rig, name)
                assert math.isfinite(x) and x > 0, f"{name} = {x} accepted"


@covers("fit")
@hostile(20)
@example(params=b'{"law": "coulomb", "params": {"mu0": "abc"}}')  # ValueError
@given(params=params_bytes())
def test_load_result_hostile(params: bytes) -> None:
    with workdir() as tmp:
        src = tmp / "r.json"
        src.write_bytes(params)
        res = check_api(lambda: fl.load_result(src))
        if not isinstance(res, Exception):
            for p in res.params.values():
                assert math.isfinite(p.value), f"{p.name} = {p.value} accepted"


# ---------------------------------------------------- nonsense keyword arguments

NONSENSE = [
    ("fit-method", lambda: fl.fit("thirion", "thesis-steel", method="nonsense"), "fit"),
    ("fit-starts-fraction", lambda: fl.fit("thirion", "thesis-steel", starts=2.5), "fit"),
    ("fit-seed-negative", lambda: fl.fit("thirion", "thesis-steel", seed=-1), "fit"),
    ("fit-weights-bogus", lambda: fl.fit("thirion", "thesis-steel", weights="bogus"), None),
    ("compare-folds-fraction",
     lambda: fl.compare(["thirion"], "thesis-steel", folds=2.7), "compare"),
    ("export-tol-bool",
     lambda: fl.export("thirion", {"a": 1.2, "b": 3e-6}, "csv", {"p": (1e4, 5e5)}, tol=True),
     "export"),
    ("export-format-unknown",
     lambda: fl.export("thirion", {"a": 1.2, "b": 3e-6}, "bogus", {"p": (1e4, 5e5, 3)}), None),
    ("export-negative-a",
     lambda: fl.export("thirion", {"a": -5, "b": 3e-6}, "csv", {"p": (1e4, 5e5, 3)}), None),
    ("law-negative-p", lambda: fl.get_law("thirion")(p=-1.0, a=1.2, b=3e-6), None),
    ("law-none-p", lambda: fl.get_law("thirion")(p=None, a=1.2, b=3e-6), None),
    ("mf-negative-pressure",
     lambda: fl.MagicFormula.from_file("MagicFormula52", pressure=-2e5), "mf"),
    ("get-law-number", lambda: fl.get_law(7), None),
    ("load-dataset-number", lambda: fl.load_dataset(7), None),
]


def _nonsense(case: tuple[str, Any, str | None]) -> Any:
    name, call, area = case
    marks = [covers(area)] if area else []
    return pytest.param(call, id=name, marks=marks)


@pytest.mark.parametrize("call", [_nonsense(c) for c in NONSENSE])
def test_nonsense_arguments_raise_input_error(call: Any) -> None:
    with pytest.raises(InputError) as info:
        call()
    assert "\n" not in str(info.value).strip()
