"""The output guard's input rule: a file read in this process is never replaced.

Rules checked here (stated in :mod:`frictionlaws.base.outputs`):

* every loader (datasets, manifests, records, rigs, params JSON, property files) goes
  through ``check_input_file``, which registers the file as an input of the process;
* no later write of the process (export, ``FitResult.save``, an atomic write, a
  directory of outputs) replaces a registered file, whatever name reaches it:
  ``./x``, ``a/../x``, an absolute path, a symbolic link or a hard link;
* an export or save of a fit refuses the fitted data file even when this process
  never read it (a result loaded from JSON, or the law bound to it);
* a path that is none of these is written as asked (as ``open`` does).
"""

from __future__ import annotations

import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import frictionlaws as fl
from frictionlaws.base import outputs
from frictionlaws.base.errors import InputError

DATA = "mu,p [MPa],v [m/s]\n1.2,0.05,1\n1.1,0.1,1\n1.0,0.15,2\n0.95,0.2,2\n0.9,0.25,3\n"
BOX = {"p": (1e4, 1e6, 5)}


@pytest.fixture(autouse=True)
def fresh_registry(monkeypatch: pytest.MonkeyPatch) -> None:
    """Each test starts with no file registered (the registry is per process)."""
    monkeypatch.setattr(outputs, "_PROTECTED", set())
    monkeypatch.setattr(outputs, "_PROTECTED_IDS", {})
    monkeypatch.setattr(outputs, "_WRITTEN", set())


def _data(folder: Path, name: str = "data.csv") -> Path:
    p = folder / name
    p.write_text(DATA, encoding="utf-8")
    return p


def test_every_loader_registers_the_file_it_reads(tmp_path: Path) -> None:
    from hostile import MF52_TIR, RIG_TOML

    from frictionlaws.io import read_table
    from frictionlaws.tribometer.records import read_record
    from frictionlaws.tribometer.rig import load_rig
    from frictionlaws.tyre import MagicFormula

    data = _data(tmp_path)
    manifest = tmp_path / "manifest.csv"
    manifest.write_text("file,load [kg],surface\nr.csv,3,steel\n", encoding="utf-8")
    record = tmp_path / "r.csv"
    rows = "".join(f"{i / 100:.2f},0.1,100\n" for i in range(200))
    record.write_text("time [s],torque [N m],disc_speed [rpm]\n" + rows, encoding="utf-8")
    rig = tmp_path / "rig.toml"
    rig.write_text(RIG_TOML, encoding="utf-8")
    params = tmp_path / "params.json"
    params.write_text('{"law": "thirion", "params": {"a": 1.0, "b": 1e-6}}', encoding="utf-8")
    tir = tmp_path / "tyre.tir"
    tir.write_bytes(MF52_TIR.read_bytes())
    loaders = [(data, fl.load_dataset), (manifest, read_table), (record, read_record),
               (rig, load_rig), (params, fl.load_result), (tir, MagicFormula.from_file)]
    for path, load in loaders:
        assert not outputs.is_protected(path)
        load(path)
        assert outputs.is_protected(path), path.name


def test_a_fitted_data_file_is_never_replaced_by_a_later_export(tmp_path: Path) -> None:
    data = _data(tmp_path)
    res = fl.fit("thirion", data)
    before = data.read_bytes()
    for call in (lambda: fl.export(None, res, "csv", box=BOX, path=data),
                 lambda: fl.export("thirion", {"a": 1, "b": 1e-6}, "csv", box=BOX,
                                   path=data),
                 lambda: res.save(data)):
        with pytest.raises(InputError, match="input"):
            call()
    assert data.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["data.csv"]  # nothing left behind


def test_a_saved_fit_refuses_its_data_file_even_when_this_process_never_read_it(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    data = _data(tmp_path)
    saved = tmp_path / "fit.json"
    fl.fit("thirion", data).save(saved)
    for name in ("_PROTECTED", "_PROTECTED_IDS", "_WRITTEN"):  # a new session
        monkeypatch.setattr(outputs, name, type(getattr(outputs, name))())
    res = fl.load_result(saved)
    assert not outputs.is_protected(data)
    before = data.read_bytes()
    for obj in (res, res.bound):
        with pytest.raises(InputError, match="also an input"):
            fl.export(None, obj, "csv", box=BOX, path=data)
    with pytest.raises(InputError, match="input"):  # nor the params file it came from
        fl.export(None, res, "csv", box=BOX, path=saved)
    assert data.read_bytes() == before


def test_a_path_that_is_not_an_input_is_written_as_asked(tmp_path: Path) -> None:
    other = tmp_path / "table.csv"
    other.write_text("an old table\n", encoding="utf-8")
    out = fl.export("thirion", {"a": 1, "b": 1e-6}, "csv", box=BOX, path=other)
    assert out.path == str(other) and "an old table" not in other.read_text(encoding="utf-8")
    new = tmp_path / "new.csv"
    fl.export("thirion", {"a": 1, "b": 1e-6}, "csv", box=BOX, path=new)
    assert new.is_file()


def test_a_file_this_process_wrote_may_be_read_and_written_again(tmp_path: Path) -> None:
    path = tmp_path / "rt.csv"
    for factor in (1.0, 0.5):  # write, read back, write again: the process's own file
        ds = fl.load_dataset({"mu": [0.9 * factor, 0.8 * factor], "p": [1e5, 2e5]})
        back = fl.load_dataset(ds.to_csv(path))
        assert back.frame["mu"].iloc[0] == pytest.approx(0.9 * factor)
    res = fl.fit("thirion", _data(tmp_path))
    with pytest.raises(InputError, match="also an input"):  # but never a call's own input
        res.save(tmp_path / "data.csv")


def test_the_cli_refuses_a_file_read_earlier_in_the_same_process(tmp_path: Path) -> None:
    from hostile import run_cli

    data = _data(tmp_path)
    assert run_cli(["fit", "--law", "thirion", str(data), "--json"]).code == 0
    before = data.read_bytes()
    res = run_cli(["export", "--law", "thirion", "--set", "a=1", "--set", "b=1e-6",
                   "--format", "csv", "--p", "0.01:1:5", "-o", str(data)])
    assert res.code == 2 and "input" in res.err, res.err
    assert data.read_bytes() == before


_NAMES = st.sampled_from(["plain", "dot", "dotdot", "absolute", "symlink", "hardlink",
                          "linked-dir"])


def _alias(root: Path, target: Path, how: str) -> Path:
    """Another name of ``target`` (relative names are relative to ``root``, the cwd)."""
    rel = target.relative_to(root)
    if how == "plain":
        return rel
    if how == "dot":
        return Path(".") / rel
    if how == "dotdot":
        (root / "sub").mkdir(exist_ok=True)
        return Path("sub") / ".." / rel
    if how == "absolute":
        return target
    if how == "symlink":
        link = root / "link.csv"
        link.symlink_to(target)
        return link
    if how == "hardlink":
        link = root / "hard.csv"
        os.link(target, link)
        return link
    (root / "dirlink").symlink_to(target.parent, target_is_directory=True)
    return Path("dirlink") / target.name


@settings(max_examples=30, deadline=None, derandomize=True, database=None,
          suppress_health_check=list(HealthCheck))
@given(stem=st.text(st.characters(min_codepoint=0x21, max_codepoint=0x2FF,
                                  blacklist_characters="/\\:*?\"<>|"),
                    min_size=1, max_size=12).filter(lambda s: s not in (".", "..")),
       read_as=_NAMES, write_as=_NAMES, how=st.sampled_from(["export", "atomic", "dir"]))
def test_a_read_file_is_never_replaced_whatever_name_reaches_it(
        stem: str, read_as: str, write_as: str, how: str) -> None:
    outputs._PROTECTED.clear()
    outputs._PROTECTED_IDS.clear()
    outputs._WRITTEN.clear()
    cwd = os.getcwd()
    with tempfile.TemporaryDirectory() as tmp:
        root = Path(tmp).resolve()
        (root / "d").mkdir()
        data = _data(root / "d", f"{stem}.csv")
        before = data.read_bytes()
        os.chdir(root)
        try:
            fl.load_dataset(_alias(root, data, read_as))
            for extra in ("link.csv", "hard.csv", "dirlink", "sub"):
                p = root / extra
                if p.is_symlink() or p.is_file():
                    p.unlink()
            target = _alias(root, data, write_as)
            with pytest.raises(InputError):
                if how == "export":
                    fl.export("thirion", {"a": 1, "b": 1e-6}, "csv", box=BOX, path=target)
                elif how == "atomic":
                    outputs.write_text_atomic(target, "replaced\n")
                else:  # a directory of outputs holding a file of that name
                    with outputs.atomic_dir(Path(target).parent) as d:
                        (d / Path(target).name).write_text("replaced\n", encoding="utf-8")
        finally:
            os.chdir(cwd)
        assert data.read_bytes() == before
        assert not [p for p in root.rglob("*.part")]


def test_a_reused_inode_of_a_deleted_input_protects_nothing(tmp_path: Path) -> None:
    """An input read, then deleted: a new file that gets its inode is not that input."""
    gone = tmp_path / "gone.csv"
    gone.write_text("mu\n0.5\n", encoding="utf-8")
    outputs.protect_input(gone)
    new = tmp_path / "new.csv"
    new.write_text("mu\n0.6\n", encoding="utf-8")
    st, old = new.stat(), gone.stat()
    gone.unlink()
    # what the file system does when it hands the deleted file's inode to a new file
    outputs._PROTECTED_IDS[(st.st_dev, st.st_ino)] = (old.st_mtime_ns - 1, old.st_size)
    assert not outputs.is_protected(new)
    assert outputs.is_protected(gone)  # the name read stays protected


def test_a_hard_link_to_an_input_is_protected(tmp_path: Path) -> None:
    src = tmp_path / "in.csv"
    src.write_text("mu\n0.5\n", encoding="utf-8")
    outputs.protect_input(src)
    link = tmp_path / "link.csv"
    os.link(src, link)
    assert outputs.is_protected(link)
