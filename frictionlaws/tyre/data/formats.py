"""The tyre test formats, told apart by their content; several files read as one data set.

:data:`FORMATS` is the one list: a tidy CSV table (:mod:`~frictionlaws.tyre.data.table`), a
TYDEX file (:mod:`~frictionlaws.tyre.data.tydex`) and a raw rig run
(:mod:`~frictionlaws.tyre.data.raw_run`, turned into steady sweeps by
:func:`~frictionlaws.tyre.data.segments.prepare_run`).  :func:`detect_format` looks at the
start of a file: ``**HEADER`` opens a TYDEX file; a row of rig channel names (``FZ`` with
``SA``, ``SL``, ``FX``...) followed by a row of units opens a raw run; anything else is read
as a CSV table (whose reader says what it lacks).  Each format has its default axes
(:data:`DEFAULT_AXES`): CSV and TYDEX ISO-W, raw runs SAE, as the public programmes publish
them.

:func:`read_tyre_files` reads one or several files of any of these formats and joins them
(:func:`~frictionlaws.tyre.data.table.join`): one sweep type per TYDEX file, so a test is
several files.  The same file given twice is refused; so are files whose loads, pressures or
slip angles are of another order of magnitude than the others' (a unit wrong in one of
them: kN as N, bar as kPa, radians as degrees), naming both files and their units.
"""

from __future__ import annotations

import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...base.errors import InputError
from ...base.outputs import check_input_file
from ..mf.parameters import PLAUSIBLE_PRESSURE
from .raw_run import MIN_RIG_LOAD, load_raw_run, raw_layout
from .segments import prepare_run
from .table import TyreData, join, read_tyre_data
from .tydex import is_tydex, read_tydex

__all__ = ["FORMATS", "DEFAULT_AXES", "detect_format", "read_tyre_file", "read_tyre_files",
           "ReadFile", "MAX_FILES", "LOAD_RATIO", "PRESSURE_RATIO", "ANGLE_RATIO"]

#: Format -> what it is.
FORMATS = {"csv": "tidy CSV table (units in the headers)",
           "tydex": "TYDEX file (**HEADER ... **END, W axes)",
           "raw": "raw rig run (channel names and units rows, one row per sample)"}
#: Format -> the axes its data are in unless told otherwise.
DEFAULT_AXES = {"csv": "iso", "tydex": "iso", "raw": "sae"}
#: Most files read together.
MAX_FILES = 1000
#: Files whose median loads differ by this factor or more are refused (a unit wrong).
LOAD_RATIO = 10.0
#: The same for the median pressures.
PRESSURE_RATIO = 3.0
#: The same for the largest slip angles (of files that sweep it beyond 1 degree).
ANGLE_RATIO = 20.0
#: Bytes looked at to tell the format.
_HEAD_BYTES = 65536


@dataclass
class ReadFile:
    """One file read: its format, data and, for a raw run, the preparation."""

    path: str
    format: str
    data: TyreData
    prepared: object | None = None
    notes: list[str] = field(default_factory=list)


def detect_format(path: str | Path) -> str:
    """The format of a tyre test file (a key of :data:`FORMATS`), from its first lines.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    str
    """
    check_input_file(path, "tyre data file")
    try:
        with open(path, "rb") as fh:
            head = fh.read(_HEAD_BYTES)
    except OSError as exc:
        raise InputError(f"cannot read the tyre data file ({exc.strerror})",
                         file=str(path)) from None
    text = head.decode("utf-8", errors="replace").lstrip("\ufeff")
    lines = text.replace("\r\n", "\n").replace("\r", "\n").split("\n")[:-1] or [text]
    if is_tydex(lines):
        return "tydex"
    if raw_layout(lines) is not None:
        return "raw"
    return "csv"


def read_tyre_file(path: str | Path, *, sign_convention: str | None = None,
                   format: str | None = None, warmup: float = 0.0) -> ReadFile:
    """Read one tyre test file of any format (module documentation).

    Parameters
    ----------
    path : str or Path
    sign_convention : {"iso", "sae"}, optional
        The axes of the file (default: those of its format, :data:`DEFAULT_AXES`).
    format : str, optional
        A key of :data:`FORMATS` (default: :func:`detect_format`).
    warmup : float
        For a raw run: seconds dropped at its start as warm-up (beside the conditions the
        run returns to later).

    Returns
    -------
    ReadFile
    """
    kind = format or detect_format(path)
    if kind not in FORMATS:
        raise InputError(f"format {kind!r} is not known; expected one of "
                         + ", ".join(FORMATS))
    axes = sign_convention or DEFAULT_AXES[kind]
    if kind == "raw":
        prepared = prepare_run(load_raw_run(path, sign_convention=axes), warmup=warmup)
        return ReadFile(str(path), kind, prepared.data, prepared)
    reader = read_tydex if kind == "tydex" else read_tyre_data
    return ReadFile(str(path), kind, reader(path, sign_convention=axes))


def read_tyre_files(paths: Sequence[str | Path], *, sign_convention: str | None = None,
                    warmup: float = 0.0) -> tuple[TyreData, list[ReadFile]]:
    """Read one or several tyre test files, of any formats, as one data set.

    Parameters
    ----------
    paths : sequence of str or Path
        The files (a file given twice is refused).
    sign_convention : {"iso", "sae"}, optional
        The axes of every file (default: each format's, :data:`DEFAULT_AXES`).
    warmup : float
        For raw runs: seconds dropped at the start as warm-up.

    Returns
    -------
    data : TyreData
        The rows of all files (SI, ISO-W); each row keeps its file (``extra["file"]``).
    files : list of ReadFile
        What each file was and gave.

    Raises
    ------
    InputError
        A file given twice, files of inconsistent units, or what a reader refuses.
    """
    if not paths:
        raise InputError("no tyre data file given")
    if len(paths) > MAX_FILES:
        raise InputError(f"{len(paths)} files, more than the limit of {MAX_FILES}")
    seen: dict[str, str] = {}
    for p in paths:
        key = os.path.realpath(p)
        if key in seen:
            raise InputError(f"the same file is given twice ('{seen[key]}' and '{p}'): its "
                             "rows would count twice", file=str(p))
        seen[key] = str(p)
    files = [read_tyre_file(p, sign_convention=sign_convention, warmup=warmup) for p in paths]
    if len(files) > 1:
        _check_consistent(files)
    data = join([f.data for f in files])
    if len(files) > 1:
        kinds = sorted({f.format for f in files})
        data.notes.insert(0, f"{len(files)} files read together ({', '.join(kinds)})")
    return data, files


def _check_consistent(files: list[ReadFile]) -> None:
    """Refuse files whose loads, pressures or slip angles are of another order than the
    others' (a unit wrong in one of them)."""
    def medians(values: list[np.ndarray]) -> list[float]:
        return [float(np.median(v[np.isfinite(v)])) if np.isfinite(v).any() else np.nan
                for v in values]

    checks = (("load", "fz", [f.data.fz for f in files], LOAD_RATIO, "kN as N?"),
              ("pressure", "pressure", [f.data.pressure for f in files], PRESSURE_RATIO,
               "bar as kPa, kPa as bar, psi as kPa?"),
              ("largest slip angle", "alpha",
               [np.array([np.max(np.abs(f.data.alpha))]) for f in files], ANGLE_RATIO,
               "radians as degrees?"))
    for what, column, values, ratio, hint in checks:
        m = medians(values)
        use = [i for i, v in enumerate(m) if np.isfinite(v) and v > 0
               and (column != "alpha" or v > np.radians(1.0))]
        if len(use) < 2:
            continue
        lo, hi = min(use, key=lambda i: m[i]), max(use, key=lambda i: m[i])
        if m[hi] >= ratio * m[lo]:
            # the file at fault: the one outside the range tyres run at, when only one is
            out_lo, out_hi = _outside(column, m[lo]), _outside(column, m[hi])
            bad, good = (lo, hi) if out_lo and not out_hi else (hi, lo)
            units = [files[i].data.units.get(column, "?") for i in (bad, good)]
            raise InputError(f"the {what} of '{files[bad].path}' ({m[bad]:.4g} in SI, unit "
                             f"'{units[0]}') is a factor {m[hi] / m[lo]:.3g} "
                             f"{'above' if bad == hi else 'below'} that of "
                             f"'{files[good].path}' ({m[good]:.4g}, unit '{units[1]}'): a "
                             f"unit is wrong in one of them ({hint})"
                             + ("; only this one's is outside the range tyres run at"
                                if out_lo != out_hi else ""), file=files[bad].path, column=column,
                             row=int(files[bad].data.rows[0]))


#: The range of a file's median load [N] and pressure [Pa] that tyres run at (a rig's
#: lightest load to an aircraft's; :data:`~frictionlaws.tyre.mf.parameters.PLAUSIBLE_PRESSURE`).
_PLAUSIBLE = {"fz": (MIN_RIG_LOAD, 1e6), "pressure": PLAUSIBLE_PRESSURE}


def _outside(column: str, median: float) -> bool:
    """True when a file's median ``column`` is outside the range tyres run at."""
    lo, hi = _PLAUSIBLE.get(column, (-np.inf, np.inf))
    return not lo <= median <= hi
