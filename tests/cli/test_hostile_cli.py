"""Hostile-input harness over every command (see ``tests/hostile/__init__.py``).

Each test draws hostile files and options with hypothesis (derandomised, so a CI
run is reproducible) and checks the invariants of :func:`hostile.check_outcome`.
Every case must pass; ``covers(area)`` names the area a case guards (see ``AREAS``).
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest
from hostile import (
    MF52_JSON,
    NASTY_NUMBERS,
    RIG_TOML,
    UNWRITABLE,
    Snapshot,
    check_export_file,
    check_outcome,
    csv_bytes,
    hostile,
    params_bytes,
    rig_bytes,
    run_cli,
    strict_json,
    tir_bytes,
)
from hypothesis import example, given
from hypothesis import strategies as st

from frictionlaws.fe_export.formats import FORMATS as EXPORT_FORMATS

pytestmark = pytest.mark.hostile




#: The areas of the library the cases guard.
AREAS = {
    "input": "input layer (one table reader, number policy)",
    "fit": "fit command/API",
    "export": "export",
    "mf": "Magic Formula property files",
    "tribo": "process / rig files",
    "compare": "compare",
}


def covers(area: str) -> pytest.MarkDecorator:
    """The area a case guards; every case must pass."""
    return pytest.mark.hostile


@contextlib.contextmanager
def workdir() -> Iterator[Path]:
    path = Path(tempfile.mkdtemp(prefix="hostile-"))
    try:
        yield path
    finally:
        shutil.rmtree(path, ignore_errors=True)


def _target(tmp: Path, kind: str, inputs: list[Path]) -> Path:
    """An output path of a given kind: fresh, an input, a directory, in a missing dir..."""
    if kind == "fresh":
        return tmp / "out.json"
    if kind == "input":
        return inputs[0]
    if kind == "dir":
        (tmp / "adir").mkdir(exist_ok=True)
        return tmp / "adir"
    if kind == "missing-dir":
        return tmp / "missing" / "out.json"
    return Path(UNWRITABLE)


TARGETS = st.sampled_from(["fresh", "fresh", "input", "dir", "missing-dir", "unwritable"])

FIX_VALUES = ["a=-5", "a=0", "a=nan", "a=1e999", "a=1_0", "b=", "=1", "a=1,a=2", "zz=1",
              "a=\uff11", "a=0.2", "b=3", "mu0=0.5", ","]
MAP_VALUES = ["mu=FC", "mu=mu", "p=p", "mu", "x=y", "mu=mu,mu=mu", "", "p=mu", "f_n=F_N"]
UNIT_VALUES = ["p=MPa", "p=Mpa", "v=furlong", "p=kPa,p=MPa", "T=degC", "mu=rad", "s=deg",
               "p=", "v=m/s", "T=delta_degC"]
AREA_VALUES = ["314 mm^2", "314", "-3 mm^2", "0 mm^2", "big", "1e999 m^2", "3 mm"]


@st.composite
def fit_options(draw: st.DrawFn) -> list[str]:
    opts: list[str] = []
    for _ in range(draw(st.integers(0, 3))):
        which = draw(st.sampled_from(["fix", "map", "units", "area", "starts", "seed",
                                      "weights", "drop", "free"]))
        if which == "fix":
            opts += ["--fix", draw(st.sampled_from(FIX_VALUES))]
        elif which == "map":
            opts += ["--map", draw(st.sampled_from(MAP_VALUES))]
        elif which == "units":
            opts += ["--units", draw(st.sampled_from(UNIT_VALUES))]
        elif which == "area":
            opts += ["--area", draw(st.sampled_from(AREA_VALUES))]
        elif which == "starts":
            opts += ["--starts", draw(st.sampled_from(["-1", "0", "2", "1e3", "1001", "x"]))]
        elif which == "seed":
            opts += ["--seed", draw(st.sampled_from(["-1", "0", "4294967296", "1.5", "7"]))]
        elif which == "weights":
            opts += ["--weights", draw(st.sampled_from(["none", "auto", "bogus"]))]
        elif which == "drop":
            opts += ["--drop-invalid"]
        else:
            opts += ["--free", draw(st.sampled_from(["E_v", "", "zz", "E_v,E_v"]))]
    return opts


FIT_LAWS = st.sampled_from(["thirion", "coulomb", "quadratic-pv", "exponential-decay",
                            "schallamach", "pacejka", "nope"])


# ------------------------------------------------------------------------------ fit


@covers("input")  # mu = 5e307 is accepted; lmfit overflows: exit 3
@hostile(60)
@example(data=b"mu,p [MPa]\n5e307,0.1\n1.5,0.2\n1.9,0.3\n", law="coulomb", opts=[],
         json_out=True, save=None)
@given(data=csv_bytes(), law=FIT_LAWS, opts=fit_options(), json_out=st.booleans(),
       save=st.one_of(st.none(), TARGETS))
def test_fit_hostile_csv(data: bytes, law: str, opts: list[str], json_out: bool,
                         save: str | None) -> None:
    with workdir() as tmp:
        src = tmp / "data.csv"
        src.write_bytes(data)
        argv = ["fit", str(src), "--law", law, *opts]
        allowed = []
        if save is not None:
            out = _target(tmp, save, [src])
            argv += ["--save", str(out)]
            allowed.append(out)
        if json_out:
            argv.append("--json")
        snap = Snapshot.take([tmp], [src])
        res = run_cli(argv)
        check_outcome(res, snapshot=snap, json_out=json_out, allowed=allowed)
        if res.code == 0 and json_out:
            doc = strict_json(res.out)
            values = [p["value"] for p in doc["params"].values()]
            assert all(isinstance(v, float | int) for v in values), f"missing value: {doc}"


@hostile(12)
@given(data=csv_bytes(), json_out=st.booleans())
def test_fit_reads_hostile_stdin(data: bytes, json_out: bool) -> None:
    """``-`` as DATA: the same invariants through standard input."""
    argv = ["fit", "-", "--law", "thirion"] + (["--json"] if json_out else [])
    with workdir() as tmp:
        snap = Snapshot.take([tmp])
        check_outcome(run_cli(argv, stdin=data), snapshot=snap, json_out=json_out)


# ------------------------------------------------------------------------ datasets


@hostile(40)
@given(data=csv_bytes(), opts=st.lists(st.one_of(
    st.sampled_from(MAP_VALUES).map(lambda v: ["--map", v]),
    st.sampled_from(UNIT_VALUES).map(lambda v: ["--units", v]),
    st.sampled_from(AREA_VALUES).map(lambda v: ["--area", v])), max_size=3).map(
        lambda groups: [x for g in groups for x in g]),
    json_out=st.booleans())
def test_datasets_hostile_csv(data: bytes, opts: list[str], json_out: bool) -> None:
    with workdir() as tmp:
        src = tmp / "data.csv"
        src.write_bytes(data)
        argv = ["datasets", str(src), *opts] + (["--json"] if json_out else [])
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv), snapshot=snap, json_out=json_out)


# ------------------------------------------------------------------------- compare


@pytest.mark.slow
@hostile(15)
@given(data=csv_bytes(), folds=st.sampled_from(["2", "2", "2", "0", "-1", "2.7", "1000"]),
       holdout=st.sampled_from(["0.3", "0.3", "0", "1.5", "p=0.3,p=0.2", "nan", "x=0.1"]),
       json_out=st.booleans(), report=st.one_of(st.none(), TARGETS))
def test_compare_hostile_csv(data: bytes, folds: str, holdout: str, json_out: bool,
                             report: str | None) -> None:
    with workdir() as tmp:
        src = tmp / "data.csv"
        src.write_bytes(data)
        argv = ["compare", str(src), "--laws", "thirion,coulomb", "--folds", folds,
                "--holdout", holdout, "--progress", "off"]
        allowed = []
        if report is not None:
            out = _target(tmp, report, [src])
            if report == "fresh":
                out = tmp / "report"
            argv += ["--report", str(out)]
            allowed.append(out)
        if json_out:
            argv.append("--json")
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv, timeout=40), snapshot=snap, json_out=json_out,
                      allowed=allowed)


# ---------------------------------------------------------------------------- tyre


LOADS = st.sampled_from(["2:6:5", "2:6.5:0.5", "4", "2,3,4", "-1:2:3", "0", "1e999",
                         "2:1:3", "2:6:1000000", "3kN:5kN:3", "x", "", "nan", "2:6"])


@hostile(40)
@given(data=tir_bytes(), loads=st.one_of(st.none(), LOADS), json_out=st.booleans(),
       as_json=st.booleans())
def test_tyre_mf_hostile_property_file(data: bytes, loads: str | None, json_out: bool,
                                       as_json: bool) -> None:
    with workdir() as tmp:
        src = tmp / "tyre.tir"
        if as_json:  # a hostile JSON property file built from the packaged example
            src = tmp / "tyre.json"
            data = _mutate_json(MF52_JSON.read_bytes(), data)
        src.write_bytes(data)
        argv = ["tyre", "mf", str(src)] + (["--loads", loads] if loads is not None else [])
        argv += ["--json"] if json_out else []
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv), snapshot=snap, json_out=json_out)


def _mutate_json(base: bytes, noise: bytes) -> bytes:
    """A JSON property file spoiled deterministically by ``noise`` (a drawn .tir)."""
    text = base.decode("utf-8")
    k = len(noise) % 5
    if k == 0:
        return text.replace("9416.6", "\"9,4\"").encode()
    if k == 1:
        return text.replace("\"FITTYP\": 6", "\"FITTYP\": 99").encode()
    if k == 2:
        return text.replace("\"PCX1\"", "\"PCX_1\"").encode()
    if k == 3:
        return text[: len(noise) % len(text)].encode()
    return text.replace("\"PDX1\": ", "\"PDX1\": NaN, \"x\": ").encode()


@hostile(15)
@given(data=tir_bytes(), load=st.sampled_from(["4", "-4", "0", "1e999", "4,5", "4kN", "x"]),
       points=st.sampled_from(["51", "0", "-3", "5000", "2"]),  # huge: see test_hostile_options
       save=st.one_of(st.none(), TARGETS), json_out=st.booleans())
def test_tyre_reduce_hostile(data: bytes, load: str, points: str, save: str | None,
                             json_out: bool) -> None:
    with workdir() as tmp:
        src = tmp / "tyre.tir"
        src.write_bytes(data)
        argv = ["tyre", "reduce", str(src), "--load", load, "--points", points]
        allowed = []
        if save is not None:
            out = _target(tmp, save, [src])
            argv += ["--save", str(out)]
            allowed.append(out)
        argv += ["--json"] if json_out else []
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv), snapshot=snap, json_out=json_out, allowed=allowed)


def _tyre_csv(spoil: str, cell: str) -> bytes:
    """A small flat-track CSV (2 loads, pure slip) from the MF 5.2 example, maybe spoiled."""
    import math

    import numpy as np

    from frictionlaws.tyre import MagicFormula

    mf = MagicFormula.from_file(MF52_JSON)
    header = "Fz [kN],kappa [-],alpha [deg],Fx [N],Fy [N]"
    rows = []
    for fz in (4.0, 8.0):
        for s in np.linspace(-0.2, 0.2, 11):
            rows.append(f"{fz},{s:.3f},0,{mf.fx0(s, fz * 1e3):.2f},")
            a = math.radians(s * 60)
            rows.append(f"{fz},0,{s * 60:.2f},,{mf.fy0(a, fz * 1e3):.2f}")
    if spoil == "cell":
        rows[3] = rows[3].replace(rows[3].split(",")[0], cell, 1)
    elif spoil == "no-angle-unit":
        header = header.replace("alpha [deg]", "alpha")
    elif spoil == "angle-unit":
        header = header.replace("alpha [deg]", f"alpha [{cell}]")
    elif spoil == "negative-load":
        rows = [r.replace("8.0,", "-8.0,", 1) for r in rows]
    elif spoil == "drop-fz":
        header, rows = header.split(",", 1)[1], [r.split(",", 1)[1] for r in rows]
    return ("\n".join([header, *rows]) + "\n").encode()


@covers("mf")
@hostile(12)
@given(spoil=st.sampled_from(["none", "cell", "no-angle-unit", "angle-unit", "negative-load",
                              "drop-fz", "bytes"]),
       cell=st.sampled_from(NASTY_NUMBERS), raw=st.binary(max_size=200),
       template=st.one_of(st.none(), tir_bytes()), out=TARGETS,
       sign=st.sampled_from(["iso", "sae", "xyz"]), json_out=st.booleans())
def test_tyre_fit_mf_hostile(spoil: str, cell: str, raw: bytes, template: bytes | None,
                             out: str, sign: str, json_out: bool) -> None:
    with workdir() as tmp:
        src = tmp / "flat.csv"
        src.write_bytes(raw if spoil == "bytes" else _tyre_csv(spoil, cell))
        inputs = [src]
        argv = ["tyre", "fit-mf", str(src), "--fittyp", "6", "--sign-convention", sign]
        if template is not None:
            tpl = tmp / "template.tir"
            tpl.write_bytes(template)
            inputs.append(tpl)
            argv += ["--template", str(tpl)]
        target = _target(tmp, out, inputs)
        if out in ("fresh", "missing-dir"):  # a property file is written as .tir
            target = target.with_suffix(".tir")
        argv += ["-o", str(target)] + (["--json"] if json_out else [])
        snap = Snapshot.take([tmp], inputs)
        check_outcome(run_cli(argv, timeout=60), snapshot=snap, json_out=json_out,
                      allowed=[target])


@covers("fit")
@hostile(20)
@example(params=b'{"law": "thesis-poly2", "params": {"a0": {"value": "x"}, "a1": -59.2, '
         b'"a2": 220.0, "a3": 1.05, "a4": -0.303}}', loads=None, angles="1,2,3", width=None,
         json_out=False)  # load_result: ValueError, exit 3
@given(params=params_bytes(), loads=st.one_of(st.none(), LOADS),
       angles=st.sampled_from(["1,2,3", "0", "-1,2", "x", "90", "1e999", ""]),
       width=st.one_of(st.none(), st.sampled_from(["150 mm", "-1 mm", "150 km", "0 mm", "x"])),
       json_out=st.booleans())
def test_tyre_cornering_hostile(params: bytes, loads: str | None, angles: str,
                                width: str | None, json_out: bool) -> None:
    with workdir() as tmp:
        src = tmp / "params.json"
        src.write_bytes(params)
        argv = ["tyre", "cornering", "--params", str(src), "--angles", angles]
        argv += ["--loads", loads] if loads is not None else []
        argv += ["--width", width] if width is not None else []
        argv += ["--json"] if json_out else []
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv), snapshot=snap, json_out=json_out)


@hostile(10)
@given(data=csv_bytes(), laws=st.sampled_from(["thirion", "thirion,denny", "nope", "",
                                               "coulomb", "pacejka", "thirion,thirion"]),
       json_out=st.booleans())
def test_tyre_thesis_hostile_data(data: bytes, laws: str, json_out: bool) -> None:
    with workdir() as tmp:
        src = tmp / "data.csv"
        src.write_bytes(data)
        argv = ["tyre", "thesis", "--data", str(src), "--laws", laws]
        argv += ["--json"] if json_out else []
        snap = Snapshot.take([tmp], [src])
        check_outcome(run_cli(argv), snapshot=snap, json_out=json_out)


# -------------------------------------------------------------------------- export


FORMATS = st.sampled_from([*EXPORT_FORMATS, "bogus"])  # the one list of formats, and a wrong name
RANGES = st.one_of(
    st.sampled_from(["0.01:0.5:5", "0.01:0.5", "10kPa:0.5MPa:4", "1e4:5e5:3", "0:2:3"]),
    st.sampled_from(["-1:2:3", "0:0:3", "0.5:0.01:3", "0.01:0.5:0", "0.01:0.5:1000000000",
                     "1e999:2:3", "0.01MPa:0.5m/s:3", "a:b", "0.01:0.5:2.5", "", "nan:1:3",
                     "1_0:2:3", "-5kPa:1MPa:3", "0.01:0.5:5:7"]))


@covers("fit")  # load_result: a non-numeric value gives ValueError, exit 3
@hostile(40)
@example(params=b'{"law": "thirion", "params": {"a": "abc", "b": 3e-6}}', fmt="csv",
         p="0.01:0.5:5", v=None, out="fresh", max_rows=None)
@given(params=params_bytes(), fmt=FORMATS, p=RANGES, v=st.one_of(st.none(), RANGES),
       out=TARGETS, max_rows=st.sampled_from([None, "0", "-1", "10", "x"]))
def test_export_hostile_params_file(params: bytes, fmt: str, p: str, v: str | None, out: str,
                                    max_rows: str | None) -> None:
    with workdir() as tmp:
        src = tmp / "params.json"
        src.write_bytes(params)
        target = _target(tmp, out, [src])
        if out == "fresh":
            target = tmp / "deck.txt"
        argv = ["export", "--params", str(src), "--format", fmt, "--p", p, "-o", str(target)]
        argv += ["--v", v] if v is not None else []
        argv += ["--max-rows", max_rows] if max_rows is not None else []
        snap = Snapshot.take([tmp], [src])
        res = run_cli(argv)
        check_outcome(res, snapshot=snap, allowed=[target])
        if res.code == 0:
            check_export_file(target, fmt)


@covers("export")  # 'fit warning:' lines before the error (not 'warning:'): one line per problem
@hostile(20)
@example(data=b"mu,p [MPa]\n0.5,0.1\n0.6,0.1\n0.55,0.1\n", opts=[], fmt="abaqus-decay",
         p="0.01:0.5:5")
@given(data=csv_bytes(), opts=fit_options(), fmt=FORMATS, p=RANGES)
def test_export_fit_hostile_data(data: bytes, opts: list[str], fmt: str, p: str) -> None:
    with workdir() as tmp:
        src = tmp / "data.csv"
        src.write_bytes(data)
        target = tmp / "deck.txt"
        argv = ["export", "--law", "thirion", "--fit", str(src), "--format", fmt, "--p", p,
                "-o", str(target), *[o.replace("--units", "--data-units") for o in opts]]
        snap = Snapshot.take([tmp], [src])
        res = run_cli(argv)
        check_outcome(res, snapshot=snap, allowed=[target])
        if res.code == 0:
            check_export_file(target, fmt)


# ------------------------------------------------------------------------- process


@contextlib.contextmanager
def campaign() -> Iterator[Path]:
    """A small synthetic campaign (rig.toml, manifest.csv, records/) in a fresh directory."""
    from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign, synthetic_rig

    with workdir() as tmp:
        conds = [ConditionSpec(f"c{i}", "steel", 2.0 + i, 1.0, 2, 331.0, 0.0)
                 for i in range(2)]
        make_campaign(tmp, conds, rig=synthetic_rig(), seed=4,
                      record_kwargs={"duration": 12.0, "t_second": 1.0, "fs": 250.0})
        yield tmp


@covers("tribo")  # -o DIR: the per-record table is written beside it, then the run fails
@hostile(15)
@example(rig=RIG_TOML.encode(), jobs="1", out="dir")
@given(rig=rig_bytes(), jobs=st.sampled_from(["1", "0", "-1", "x"]),
       out=st.sampled_from(["fresh", "fresh", "input", "dir", "missing-dir"]))
def test_process_hostile_rig(rig: bytes, jobs: str, out: str) -> None:
    with campaign() as tmp:
        rig_file = tmp / "rig.toml"
        rig_file.write_bytes(rig)
        manifest = tmp / "manifest.csv"
        target = _target(tmp, out, [manifest])
        if out == "fresh":
            target = tmp / "dataset.csv"
        argv = ["process", str(manifest), "--rig", str(rig_file), "-o", str(target),
                "--jobs", jobs]
        snap = Snapshot.take([tmp], [rig_file, manifest, *sorted((tmp / "records").iterdir())])
        check_outcome(run_cli(argv, timeout=40), snapshot=snap,
                      allowed=[target, tmp / "dataset_records.csv"])


@covers("tribo")
@hostile(15)
@example(data=b"mu;p [MPa];v [m/s]\n1.000,5;0,1;1\n0,8;0.2;2,0\n0,7;1.000;3\n",
         keep_header=True)  # the per-record table is written, then the run fails
@given(data=csv_bytes(), keep_header=st.booleans())
def test_process_hostile_manifest(data: bytes, keep_header: bool) -> None:
    with campaign() as tmp:
        manifest = tmp / "manifest.csv"
        if keep_header:  # the real header, hostile rows
            head = manifest.read_bytes().splitlines()[0]
            data = head + b"\n" + b"\n".join(data.splitlines()[1:])
        manifest.write_bytes(data)
        target = tmp / "dataset.csv"
        argv = ["process", str(manifest), "--rig", str(tmp / "rig.toml"), "-o", str(target),
                "--jobs", "1"]
        snap = Snapshot.take([tmp], [manifest, tmp / "rig.toml"])
        check_outcome(run_cli(argv, timeout=40), snapshot=snap,
                      allowed=[target, tmp / "dataset_records.csv"])


# ------------------------------------------------------- laws, show, validate, soup


NAMES = st.one_of(st.sampled_from(["thirion", "THIRION", "dorsch", "", " ", "thirion+wlf",
                                   "park+wlf", "nope", "thirion,coulomb", "*", "reference-*",
                                   "\x00", "../etc/passwd", "-", "--json"]),
                  st.text(max_size=12))


@hostile(25)
@given(name=NAMES, json_out=st.booleans(), which=st.sampled_from(["show", "validate", "laws"]))
def test_laws_show_validate_hostile_names(name: str, json_out: bool, which: str) -> None:
    if which == "show":
        argv = ["show", name]
    elif which == "laws":
        argv = ["laws", "--family", name]
    else:  # --list: never run the (slow) suite itself here
        argv = ["validate", "--list", "--case", name]
    argv += ["--json"] if json_out else []
    check_outcome(run_cli(argv), json_out=json_out)


SOUP = ["--json", "--json", "--map", "mu=mu", "--units", "p=MPa", "--fix", "a=1", "--seed",
        "-1", "--starts", "3", "--progress", "on", "--quiet", "--bogus", "-", "--", "--law",
        "thirion", "--law", "coulomb", "thesis-steel", "--folds", "2", "--help-me", "-o",
        "--format", "csv", "--p", "0.01:0.5:3", "=", "--area", "--debug", "--save"]


@hostile(60)
@given(command=st.sampled_from(["laws", "show", "fit", "compare", "datasets", "export",
                                "process", "validate", "tyre", "tyre mf", "tyre reduce",
                                "tyre cornering", "tyre thesis", "tyre fit-mf"]),
       words=st.lists(st.sampled_from(SOUP), max_size=6))
def test_option_soup(command: str, words: list[str]) -> None:
    """Random option soups: usage errors are one line and exit 2; nothing crashes."""
    if command in ("tyre thesis", "validate", "compare") and "--help-me" not in words:
        words = [*words, "--help-me"]  # keep to parsing: those commands are slow when valid
    argv = [*command.split(), *words]
    with workdir() as tmp:
        cwd = os.getcwd()
        os.chdir(tmp)  # any file a soup manages to write lands here
        try:
            snap = Snapshot.take([tmp])
            check_outcome(run_cli(argv), snapshot=snap, json_out="--json" in words,
                          allowed=[tmp])
        finally:
            os.chdir(cwd)


def _number_case(number: str, where: str) -> object:
    marks = []
    if number in ("-0", "1e-400") and where == "fix":  # a = 0 passes the bounds, then 1/a
        marks.append(covers("fit"))
    return pytest.param(number, where, id=f"{where}-{number!r}", marks=marks)


@pytest.mark.parametrize(("number", "where"), [_number_case(n, w) for n in NASTY_NUMBERS
                                               for w in ("fix", "set")])
def test_nasty_numbers_in_options(number: str, where: str) -> None:
    """Every number spelling in --fix and --set is a clear exit 2, or a valid value."""
    if where == "fix":
        argv = ["fit", "thesis-steel", "--law", "thirion", "--fix", f"a={number}"]
    else:
        argv = ["tyre", "cornering", "--law", "coulomb", "--set", f"mu0={number}",
                "--loads", "3"]
    check_outcome(run_cli(argv))
