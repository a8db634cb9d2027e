"""Every reader of files frictionlaws has, in one list: what it reads, in which format,
and a valid example of its input.

A reader takes the path of a file a user gives and returns what the library works with,
or raises :class:`~frictionlaws.base.errors.InputError` naming the file and the place (row,
column, key) of what it refuses.  The list is what the hostile-input harness walks
(``tests/base/test_hostile_boundary_walk.py``): every reader here gets every hostile
class of input (numbers past the one number parser, malformed bytes, encodings, limits,
line separators), so a new reader is covered by adding its line.

Readers are named by their public import path and resolved only when used, so this
module imports nothing heavy.
"""

from __future__ import annotations

import importlib
import math
import os
import shutil
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

__all__ = ["Reader", "READERS", "FORMATS", "reader"]

#: File formats of the readers, and what each format itself allows of the spellings the
#: one number parser refuses (TOML's own number grammar has ``1_000``, ``inf`` and ``nan``;
#: CSV tables read ``nan`` as a missing cell).
FORMATS: dict[str, frozenset[str]] = {
    "csv": frozenset({"missing"}),
    "tir": frozenset(),
    "json": frozenset(),
    "toml": frozenset({"underscore"}),
    "tydex": frozenset(),
    "raw": frozenset(),
}


@dataclass(frozen=True)
class Reader:
    """One reader of files: its function, its file format and a valid example.

    Attributes
    ----------
    name : str
        What it reads (``"dataset"``).
    function : str
        ``"module:function"`` of the public reader, called with the path first.
    format : str
        A key of :data:`FORMATS`.
    example : str
        How a valid input is made: ``"examples:NAME"`` (a file of
        :func:`frictionlaws.example_files.write_example_files`), ``"packaged:PATH"`` (a
        packaged file under :func:`frictionlaws.io.datasets_dir`) or ``"make:NAME"`` (a
        function of this module that writes one).
    arguments : mapping
        Further arguments of the call: a value, or ``"make:NAME"`` for one made here.
    per_row : bool
        The reader refuses a bad row by marking it (the result's first item is a list of
        entries with an ``error``, reported and not used) rather than refusing the file.
    """

    name: str
    function: str
    format: str
    example: str
    arguments: Mapping[str, Any] = field(default_factory=dict)
    per_row: bool = False

    def refusals(self, result: Any) -> list[str]:
        """The rows a successful read refused, with the reason (see ``per_row``)."""
        if not self.per_row:
            return []
        return [str(e.error) for e in result[0] if getattr(e, "error", None)]

    def resolve(self) -> Callable[..., Any]:
        """The reader's function."""
        module, _, name = self.function.partition(":")
        return getattr(importlib.import_module(module), name)

    def read(self, path: str | os.PathLike[str]) -> Any:
        """Read ``path`` with this reader (its further arguments supplied)."""
        kwargs = {k: _made(v) for k, v in self.arguments.items()}
        return self.resolve()(path, **kwargs)

    def write_example(self, directory: str | os.PathLike[str]) -> Path:
        """Write a valid input of this reader into ``directory`` (with what it refers to,
        e.g. a manifest's records) and return its path."""
        kind, _, what = self.example.partition(":")
        root = Path(directory)
        if kind == "examples":
            from ..example_files import write_example_files

            if not (root / "EXAMPLES.txt").exists():
                write_example_files(root)
            return root / what
        if kind == "packaged":
            from .packaged import datasets_dir

            target = root / Path(what).name
            shutil.copyfile(Path(os.fspath(datasets_dir())) / what, target)
            return target
        return _MAKERS[what](root)


def _params_example(root: Path) -> Path:
    path = root / "params.json"
    path.write_text('{"law": "thirion", "params": {"a": 0.25, "b": 3.5e-06}}\n',
                    encoding="utf-8")
    return path


def _profile_example(root: Path) -> Path:
    """A surface profile: a position and a height column, 256 points (a rough sine sum)."""
    rows = [f"{0.01 * i:.4f},{math.sin(0.7 * i) + 0.3 * math.sin(2.3 * i + 1):.5f}"
            for i in range(256)]
    path = root / "profile.csv"
    path.write_text("x [mm],h [um]\n" + "\n".join(rows) + "\n", encoding="utf-8")
    return path


def _tydex_example(root: Path) -> Path:
    """Lateral sweeps of the packaged MF 6.1 example at two loads, as a TYDEX file."""
    from ..tyre.data import write_tydex
    from ..tyre.data.synthetic import sweep_data
    from ..tyre.magic_formula import MagicFormula

    data = sweep_data(MagicFormula.from_file("MagicFormula61"), "lateral", loads=(0.5, 1.0),
                      cambers_deg=(0.0,), pressures=(1.0,), n=7)
    return write_tydex(data, root / "lateral.tdx")


def _raw_run_example(root: Path) -> Path:
    """A short raw rig run of the packaged MF 6.1 example (tab separated, SAE axes)."""
    from ..tyre.data.synthetic import RawRunSpec, synthetic_raw_run
    from ..tyre.magic_formula import MagicFormula

    spec = RawRunSpec(loads=(1.0,), cambers_deg=(0.0,), pressures=(1.0,), rate=20.0,
                      combined_deg=(), cycles=1, warmup_s=5.0)
    run = synthetic_raw_run(MagicFormula.from_file("MagicFormula61"), spec)
    path = root / "run.dat"
    path.write_text(run.text(title="a raw rig run (synthetic)"), encoding="utf-8")
    return path


def _rig() -> Any:
    from ..tribometer.synthetic import synthetic_rig

    return synthetic_rig()


_MAKERS: dict[str, Callable[..., Any]] = {"params": _params_example,
                                          "profile": _profile_example, "rig": _rig,
                                          "tydex": _tydex_example, "raw": _raw_run_example}


def _made(value: Any) -> Any:
    if isinstance(value, str) and value.startswith("make:"):
        return _MAKERS[value[5:]]()
    return value


#: Every reader of files (the hostile-input harness walks this list).
READERS: tuple[Reader, ...] = (
    Reader("dataset", "frictionlaws.io:load_dataset", "csv", "examples:campaign.csv"),
    Reader("tyre data", "frictionlaws.tyre:read_tyre_data", "csv", "examples:tyre_data.csv"),
    Reader("record", "frictionlaws.tribometer.records:read_record", "csv",
           "examples:records/steel_2_kg_01.csv"),
    Reader("manifest", "frictionlaws.tribometer.process.manifest:read_manifest", "csv",
           "examples:manifest.csv", {"rig": "make:rig"}, per_row=True),
    Reader("rig", "frictionlaws.tribometer.rig:load_rig", "toml", "examples:rig.toml"),
    Reader("property file", "frictionlaws.tyre:read_property_file", "tir",
           "packaged:mf-examples/MagicFormula61_Parameters.converted.tir"),
    Reader("JSON property file", "frictionlaws.tyre:read_property_file", "json",
           "packaged:mf-examples/MagicFormula52_Parameters.json"),
    Reader("fit result", "frictionlaws.fitting.result:load_result", "json", "make:params"),
    Reader("surface profile", "frictionlaws.persson.surface:psd_from_profile_csv", "csv",
           "make:profile"),
    Reader("TYDEX file", "frictionlaws.tyre.data:read_tydex", "tydex", "make:tydex"),
    Reader("raw rig run", "frictionlaws.tyre.data:load_raw_run", "raw", "make:raw"),
)


def reader(name: str) -> Reader:
    """The reader named ``name`` in :data:`READERS`."""
    for r in READERS:
        if r.name == name:
            return r
    raise KeyError(name)
