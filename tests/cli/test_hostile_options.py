"""Hostile option combinations and file situations, one named case each.

Every case checks the harness invariants (:func:`hostile.check_outcome`) plus
the exit code and the fragments the one-line message must contain.  Cases in
every case must pass (``area`` names the part of the library a case guards).
"""

from __future__ import annotations

import contextlib
import os
import resource
import shutil
import tempfile
import warnings
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from hostile import MF52_TIR, RIG_TOML, UNWRITABLE, Snapshot, check_outcome, run_cli, strict_json

pytestmark = pytest.mark.hostile

GOOD_CSV = "mu,p [MPa]\n0.62,0.03\n0.55,0.06\n0.5,0.09\n0.46,0.12\n0.43,0.15\n"
PARAMS = '{"law": "thirion", "params": {"a": 1.2, "b": 3.5e-6}}'


@dataclass
class Case:
    """A command line built in a scratch directory, and what it must give."""

    id: str
    argv: Callable[[Path], list[str]]
    codes: tuple[int, ...]
    fragments: tuple[str, ...] = ()
    area: str | None = None
    stdin: bytes = b""
    json_out: bool = False
    outputs: Callable[[Path], list[Path]] = field(default=lambda tmp: [])
    timeout: float = 10.0


def _fifo(tmp: Path, name: str) -> Path:
    path = tmp / name
    os.mkfifo(path)
    return path


def _write(tmp: Path, name: str, text: str) -> Path:
    path = tmp / name
    path.write_text(text, encoding="utf-8")
    return path


def _files(tmp: Path) -> None:
    (tmp / "data.csv").write_text(GOOD_CSV, encoding="utf-8")
    (tmp / "params.json").write_text(PARAMS, encoding="utf-8")
    (tmp / "adir").mkdir()
    shutil.copy(MF52_TIR, tmp / "tyre.tir")


def d(tmp: Path) -> str:
    return str(tmp / "data.csv")


FIT = ["fit", "--law", "thirion"]
EXPORT_P = ["--format", "csv", "--p", "0.01:0.5:5"]

CASES = [
    # ---- repeated options merge; a name given twice is an error naming it
    Case("map-units-repeated-merge",
         lambda t: [*FIT, "thesis-steel-original", "--map", "mu=FC", "--map", "p=CP,v=DV",
                    "--units", "p=MPa", "--units", "v=m/s", "--json"], (0,), json_out=True),
    Case("units-name-twice", lambda t: [*FIT, d(t), "--units", "p=MPa", "--units", "p=kPa"],
         (2,), ("--units", "'p' is given twice")),
    Case("fix-name-twice-one-occurrence", lambda t: [*FIT, d(t), "--fix", "a=1,a=2"],
         (2,), ("--fix", "'a' is given twice")),
    Case("map-name-twice", lambda t: [*FIT, d(t), "--map", "mu=mu", "--map", "mu=x"],
         (2,), ("--map", "'mu' is given twice")),
    Case("free-name-twice", lambda t: [*FIT, d(t), "--free", "E_v", "--free", "E_v"],
         (2,), ("--free", "'E_v' is given twice")),
    Case("set-name-twice", lambda t: ["export", "--law", "thirion", "--set", "a=1",
                                      "--set", "a=2", *EXPORT_P, "-o", str(t / "o.csv")],
         (2,), ("--set", "'a'")),
    # ---- integers
    Case("seed-negative", lambda t: [*FIT, d(t), "--seed", "-1"], (2,),
         ("--seed", "from 0 to")),
    Case("seed-too-large", lambda t: [*FIT, d(t), "--seed", str(2**32)], (2,), ("--seed",)),
    Case("starts-negative", lambda t: [*FIT, d(t), "--starts", "-2"], (2,), ("--starts",)),
    Case("starts-unbounded", lambda t: [*FIT, d(t), "--starts", "1000000"], (2,),
         ("--starts", "0 to 1000")),
    Case("folds-zero", lambda t: ["compare", d(t), "--laws", "thirion", "--folds", "0"], (2,),
         ("--folds",), area="compare"),
    Case("folds-fraction", lambda t: ["compare", d(t), "--laws", "thirion", "--folds", "2.7"],
         (2,), ("--folds",)),
    Case("jobs-negative", lambda t: ["process", d(t), "--rig", "r.toml", "-o",
                                     str(t / "o.csv"), "--jobs", "-2"], (2,), ("--jobs",),
         area="tribo"),
    Case("max-rows-zero", lambda t: ["export", "--law", "thirion", "--set", "a=1,b=3e-6",
                                     *EXPORT_P, "--max-rows", "0", "-o", str(t / "o.csv")],
         (2,), ("--max-rows",), area="export"),
    Case("points-unbounded", lambda t: ["tyre", "reduce", str(t / "tyre.tir"), "--load", "4",
                                        "--points", "1000000000"], (2,), ("--points",),
         area="mf", timeout=3.0),
    Case("points-zero", lambda t: ["tyre", "reduce", str(t / "tyre.tir"), "--load", "4",
                                   "--points", "0"], (2,), ("--points",), area="mf"),
    # ---- validate
    Case("validate-case-empty", lambda t: ["validate", "--case", ""], (2,), ("--case",)),
    Case("validate-case-blank-list", lambda t: ["validate", "--case", " , "], (2,),
         ("--case",)),
    Case("validate-case-twice", lambda t: ["validate", "--list", "--case", "thesis-*",
                                           "--case", "thesis-*"], (2,), ("given twice",)),
    Case("validate-list-json", lambda t: ["validate", "--list", "--json"], (0,),
         json_out=True),
    Case("validate-run-json", lambda t: ["validate", "--case", "wlf-constant-sets",
                                         "--case", "thesis-rig-*", "--json"], (0, 1),
         json_out=True),
    Case("validate-unknown-case", lambda t: ["validate", "--case", "nope"], (2,),
         ("unknown validation case 'nope'",)),
    # ---- options that do not apply
    Case("export-fit-options-without-fit",
         lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P, "--fix", "a=1",
                    "-o", str(t / "o.csv")], (2,), ("--fix",), area="export"),
    Case("export-range-of-unused-variable",
         lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P,
                    "--T", "20degC:80degC:3", "-o", str(t / "o.csv")], (2,), ("--T",),
         area="export"),
    Case("datasets-map-without-name", lambda t: ["datasets", "--map", "mu=FC"], (2,),
         ("--map",)),
    # ---- outputs
    Case("fit-save-is-input", lambda t: [*FIT, d(t), "--save", d(t)], (2,),
         ("data.csv",), area="fit"),
    Case("fit-save-directory", lambda t: [*FIT, d(t), "--save", str(t / "adir")], (2,),
         ("adir",)),
    Case("fit-save-missing-dir", lambda t: [*FIT, d(t), "--save", str(t / "no" / "r.json")],
         (2,), ("r.json",)),
    Case("fit-save-unwritable", lambda t: [*FIT, d(t), "--save", UNWRITABLE], (2,),
         ("out.json",)),
    Case("export-output-is-params",
         lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P, "-o",
                    str(t / "params.json")], (2,), ("params.json",), area="export"),
    Case("export-output-directory",
         lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P, "-o",
                    str(t / "adir")], (2,), ("adir",)),
    Case("export-output-missing-dir",
         lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P, "-o",
                    str(t / "no" / "o.csv")], (2,), ("o.csv",)),
    Case("export-ok", lambda t: ["export", "--params", str(t / "params.json"), *EXPORT_P,
                                 "-o", str(t / "o.csv")], (0,),
         outputs=lambda t: [t / "o.csv"]),
    Case("reduce-save-is-input", lambda t: ["tyre", "reduce", str(t / "tyre.tir"), "--load",
                                            "4", "--points", "41", "--save",
                                            str(t / "tyre.tir")], (2,), ("tyre.tir",),
         area="mf"),
    Case("compare-report-is-a-file", lambda t: ["compare", d(t), "--laws", "thirion",
                                                "--folds", "2", "--report", d(t)], (2,),
         ("data.csv",)),
    Case("export-fit-warnings-are-warning-lines",
         lambda t: ["export", "--law", "thirion", "--fit", str(_write(t, "flat.csv",
                    "mu,p [MPa]\n0.5,0.1\n0.6,0.1\n0.55,0.1\n")), "--format",
                    "abaqus-decay", "-o", str(t / "o.inp")], (2,),
         ("cannot determine a, b",), area="export"),
    Case("fit-huge-mu", lambda t: ["fit", str(_write(t, "huge.csv", "mu,p [MPa]\n5e307,0.1\n"
                                                          "1.5,0.2\n1.9,0.3\n")),
                                   "--law", "coulomb"], (2,), ("huge.csv",), area="input"),
    Case("single-option-twice", lambda t: [*FIT, d(t), "--law", "coulomb"], (2,),
         ("--law", "given twice", "'thirion' and 'coulomb'")),
    Case("single-option-twice-same-value", lambda t: [*FIT, d(t), "--law", "thirion"], (0,)),
    Case("process-output-directory",
         lambda t: ["process", str(_write(t, "m.csv", "file,load [kg],surface\nr.csv,3,steel\n")),
                    "--rig", str(_write(t, "rig.toml", RIG_TOML)), "-o", str(t / "adir"),
                    "--jobs", "1"], (2,), ("no dataset written",), area="tribo", timeout=40.0),
    # ---- special input files
    Case("fit-fifo", lambda t: [*FIT, str(_fifo(t, "pipe.csv"))], (2,), ("pipe.csv",),
         timeout=3.0),
    Case("datasets-fifo", lambda t: ["datasets", str(_fifo(t, "pipe.csv"))], (2,),
         ("pipe.csv",), area="input", timeout=3.0),
    Case("mf-fifo", lambda t: ["tyre", "mf", str(_fifo(t, "pipe.tir"))], (2,), ("pipe.tir",),
         timeout=3.0),
    Case("export-params-fifo", lambda t: ["export", "--params", str(_fifo(t, "p.json")),
                                          *EXPORT_P, "-o", str(t / "o.csv")], (2,),
         ("p.json",), timeout=3.0),
    Case("fit-directory-as-data", lambda t: [*FIT, str(t / "adir")], (2,), ("adir",)),
    Case("params-malformed-json", lambda t: ["export", "--params", d(t), *EXPORT_P, "-o",
                                             str(t / "o.csv")], (2,), ("data.csv",)),
    # ---- stdin
    Case("fit-stdin", lambda t: [*FIT, "-", "--json"], (0,), stdin=GOOD_CSV.encode(),
         json_out=True),
    Case("fit-stdin-empty", lambda t: [*FIT, "-"], (2,), ("<stdin>",)),
    # ---- global flags and parsing
    Case("unknown-option", lambda t: [*FIT, d(t), "--bogus"], (2,), ("--bogus",)),
    Case("abbreviated-global-after-command", lambda t: ["export", "--params",
                                                        str(t / "params.json"), "--format",
                                                        "csv", "--p", "0.01:0.5:3", "-o",
                                                        str(t / "o.csv"), "--v", "0:1:3"],
         (0, 2), outputs=lambda t: [t / "o.csv"]),
    Case("quiet-and-verbose", lambda t: ["--quiet", "--verbose", "laws"], (2,),
         ("not allowed with",)),
    Case("progress-bad-choice", lambda t: ["compare", d(t), "--progress", "maybe"], (2,),
         ("--progress",)),
]


@contextlib.contextmanager
def scratch() -> Iterator[Path]:
    tmp = Path(tempfile.mkdtemp(prefix="hostile-opt-"))
    try:
        _files(tmp)
        yield tmp
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


@contextlib.contextmanager
def memory_cap(extra_bytes: int = 3 * 2**30) -> Iterator[None]:
    """Cap the address space a little above today's use: a runaway allocation fails fast."""
    soft, hard = resource.getrlimit(resource.RLIMIT_AS)
    with open("/proc/self/statm") as fh:
        pages = int(fh.read().split()[0])
    cap = pages * resource.getpagesize() + extra_bytes
    if hard != resource.RLIM_INFINITY:
        cap = min(cap, hard)
    resource.setrlimit(resource.RLIMIT_AS, (cap, hard))
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, (soft, hard))


def _param(case: Case) -> object:
    return pytest.param(case, id=case.id)


@pytest.mark.parametrize("case", [_param(c) for c in CASES])
def test_hostile_option_case(case: Case) -> None:
    with scratch() as tmp:
        argv = case.argv(tmp)
        inputs = [p for p in tmp.iterdir() if p.is_file() and not p.is_fifo()]
        snap = Snapshot.take([tmp], inputs)
        with memory_cap():
            res = run_cli(argv, stdin=case.stdin, timeout=case.timeout)
        check_outcome(res, snapshot=snap, json_out=case.json_out, codes=case.codes,
                      allowed=case.outputs(tmp))
        for frag in case.fragments:
            assert frag in res.err, f"{frag!r} not in {res.err!r}"


def test_at_least_forty_option_cases() -> None:
    assert len(CASES) >= 40


# ------------------------------------------------------- main(): output hygiene


def _patched_run(monkeypatch: pytest.MonkeyPatch, run: Callable[..., int]) -> None:
    from frictionlaws.cli import cmd_laws

    monkeypatch.setattr(cmd_laws, "run", run)


def test_warnings_are_collected_into_one_line_each(monkeypatch: pytest.MonkeyPatch) -> None:
    import numpy as np

    def run(args: object) -> int:
        for _ in range(5):
            warnings.warn("the same thing\nover two lines", RuntimeWarning, stacklevel=1)
        np.log(np.zeros(3))  # numpy's own divide-by-zero RuntimeWarning
        warnings.warn("/usr/lib/python3/site-packages/scipy/x.py:12: ugly", UserWarning,
                      stacklevel=1)
        print("result")
        return 0

    _patched_run(monkeypatch, run)
    res = run_cli(["laws"])
    check_outcome(res, codes=(0,))
    lines = res.err.splitlines()
    assert lines[0] == "warning: the same thing over two lines (5 times)"
    assert any("divide by zero" in ln for ln in lines)
    assert all(ln.startswith("warning: ") for ln in lines) and len(lines) == 3
    assert "site-packages" not in res.err
    assert res.out == "result\n"
    quiet = run_cli(["--quiet", "laws"])
    assert quiet.err == "" and quiet.code == 0
    cornering = ["tyre", "cornering", "--law", "thesis-poly2", "--preset", "steel"]
    assert "warning: law 'thesis-poly2' is extrapolated" in run_cli(cornering).err
    quiet = run_cli(["--quiet", *cornering])
    assert quiet.code == 0 and quiet.err == "" and "cornering" in quiet.out.lower()
    verbose = run_cli(["--verbose", "laws"])
    assert "RuntimeWarning from" in verbose.err and "site-packages" not in verbose.err


def test_debug_shows_the_traceback_of_an_internal_error(
        monkeypatch: pytest.MonkeyPatch) -> None:
    def run(args: object) -> int:
        raise RuntimeError("a bug")

    _patched_run(monkeypatch, run)
    plain = run_cli(["laws"])
    assert plain.code == 3 and plain.err.count("\n") == 1
    assert "RuntimeError: a bug" in plain.err and "Traceback" not in plain.err
    debug = run_cli(["--debug", "laws"])
    assert debug.code == 3
    assert "Traceback (most recent call last)" in debug.err and "a bug" in debug.err


@pytest.mark.parametrize(("exc", "fragment"), [
    (PermissionError(13, "Permission denied", "/x/out.json"), "file '/x/out.json'"),
    (IsADirectoryError(21, "Is a directory", "/x/d"), "file '/x/d': is a directory"),
    (OSError(28, "No space left on device"), "No space left on device"),
])
def test_os_errors_on_user_files_exit_2(monkeypatch: pytest.MonkeyPatch, exc: OSError,
                                        fragment: str) -> None:
    def run(args: object) -> int:
        raise exc

    _patched_run(monkeypatch, run)
    res = run_cli(["laws"])
    check_outcome(res, codes=(2,))
    assert fragment in res.err


def test_input_error_option_is_rendered_as_the_flag(monkeypatch: pytest.MonkeyPatch) -> None:
    from frictionlaws.base.errors import InputError

    err = InputError("no such column 'PRESSURE'", file="d.csv", option="mapping")
    assert str(err) == "argument 'mapping', file 'd.csv': no such column 'PRESSURE'"

    def run(args: object) -> int:
        raise err

    _patched_run(monkeypatch, run)
    res = run_cli(["laws"])
    assert res.err == "error: --map, file 'd.csv': no such column 'PRESSURE'\n"


def test_json_stdout_is_made_strict(monkeypatch: pytest.MonkeyPatch) -> None:
    import json

    from frictionlaws.cli import cmd_laws

    def run(args: object) -> int:
        print(json.dumps({"r2": float("nan"), "x": [float("inf"), 1.5]}))
        return 0

    monkeypatch.setattr(cmd_laws, "run", run)
    res = run_cli(["laws", "--json"])
    check_outcome(res, codes=(0,), json_out=True)
    assert strict_json(res.out) == {"r2": None, "x": [None, 1.5]}


def test_laws_show_json_is_strict() -> None:
    for argv in (["laws", "--json"], ["show", "thirion", "--json"], ["show", "park", "--json"]):
        res = run_cli(argv)
        check_outcome(res, codes=(0,), json_out=True)
        assert strict_json(res.out)


def test_show_does_not_call_summary(monkeypatch: pytest.MonkeyPatch) -> None:
    """Issue 13: the text form of ``show`` does not build the unused summary."""
    from frictionlaws.law import Law

    def boom(self: object) -> None:
        raise AssertionError("summary() called")

    monkeypatch.setattr(Law, "summary", boom)
    res = run_cli(["show", "thirion"])
    assert res.code == 0, res.err


def test_print_completion_bash() -> None:
    pytest.importorskip("shtab")
    res = run_cli(["--print-completion", "bash"])
    assert res.code == 0
    assert "compgen" in res.out or "complete" in res.out
    for word in ("fit", "export", "--progress"):
        assert word in res.out


@pytest.mark.parametrize("argv", [
    ["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "abaqus",
     "--p", "0.01:0.5", "--units", "mm-N-s,p=MPa,p=kPa"],
    ["compare", "thesis-steel", "--laws", "thirion,denny", "--holdout", "p=0.3,p=0.2"],
])
def test_a_name_given_twice_inside_one_option_value_is_refused(tmp_path, capsys, argv):
    """Not only repeated flags: VAR=... lists inside one value keep each name once."""
    from frictionlaws.cli import main

    if argv[0] == "export":
        argv = [*argv, "-o", str(tmp_path / "deck.inp")]
    assert main(argv) == 2
    assert "twice" in capsys.readouterr().err


@pytest.mark.parametrize(("argv", "reason"), [
    (["export", "--law", "thirion", "--set", "a=0.2,b=3e-6", "--format", "csv",
      "--p", "-0.5MPa:0.01MPa"], "must not be negative"),
    (["tyre", "cornering", "--law", "coulomb", "--set", "mu0=0.9", "--angles", "-1,1"],
     "slip angles must be in (0, 90)"),
])
def test_values_starting_with_a_minus_reach_the_check_that_explains_them(tmp_path, capsys,
                                                                        argv, reason):
    """argparse would say 'expected one argument'; the real reason is given instead."""
    from frictionlaws.cli import main

    if argv[0] == "export":
        argv = [*argv, "-o", str(tmp_path / "t.csv")]
    assert main(argv) == 2
    assert reason in capsys.readouterr().err


@pytest.mark.parametrize("argv", [
    ["fit", "--law", "thirion", "thesis-steel", "--jobs", "2"],
    ["fit", "--law", "thirion", "thesis-steel", "--scheduler", "tcp://127.0.0.1:1"],
    # one comparison spreads its fits over --jobs, but a cluster is for campaigns
    ["compare", "thesis-steel", "--laws", "thirion,coulomb", "--scheduler", "tcp://127.0.0.1:1"],
    ["tyre", "thesis", "--laws", ""],
])
def test_options_that_cannot_apply_are_refused(capsys, argv):
    from frictionlaws.cli import main

    assert main(argv) == 2
    assert capsys.readouterr().err.startswith("error: ")
