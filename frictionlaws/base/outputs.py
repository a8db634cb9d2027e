"""The output guard: output paths are checked before any work, and writes are atomic.

Rules (the same for every command and API call that writes files):

* an output may not be one of the inputs (same path or same file through a link),
  nor appear twice among the outputs;
* an output file may not be an existing directory or a special file (FIFO, device);
  its directory must exist and be writable; an output directory may be created;
* an input must be a regular file (a FIFO would block forever);
* every file is written to a temporary file in the same directory and renamed into
  place when complete, so a failure leaves neither a partial file nor a changed one;
  a directory of outputs is built in a temporary directory and moved in at the end.

Library functions call :func:`check_outputs` at their start with what they will
read and write; failures raise :class:`~frictionlaws.base.errors.InputError`.

Which files count as inputs (the files no write may replace):

* the inputs a call names (its data, manifest, records, rig, params or property file),
  given to :func:`check_outputs`;
* every file read in this process: the one table reader and the loaders (datasets,
  manifests, records, rigs, params JSON, property files) open their file through
  :func:`check_input_file`, which registers it with :func:`protect_input`.  So
  ``fit("data.csv")`` then ``export(..., path="data.csv")`` in the same session (API
  or CLI) is refused, whichever call wrote last.  A file is recognised through any
  name (relative, ``./x``, ``a/../x``, a symbolic link) and through a hard link;
* the files the values of a fit came from: exporting or saving a fit result (or a law
  bound to a fit) refuses the fitted data file even when this process never read it.

A file this process wrote itself (through this module) and read back later is its own
product, not a user's input: it may be written again (a script that writes, reads and
rewrites ``rt.csv`` works), unless the writing call names it as one of its inputs.

A path the caller names explicitly that is none of these is written as asked, an
existing file there replaced (atomically), as :func:`open` and ``pandas.to_csv`` do:
the library cannot know that a file it never read is precious.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import stat
import tempfile
from collections.abc import Iterable, Iterator
from pathlib import Path
from typing import IO, Any

from .errors import InputError

__all__ = [
    "check_figure_path",
    "check_input_file",
    "check_outputs",
    "check_unique_names",
    "protect_input",
    "is_protected",
    "atomic_write",
    "write_text_atomic",
    "write_bytes_atomic",
    "atomic_dir",
    "check_dir_move",
    "STDOUT",
]

#: The name that means standard output rather than a file.
STDOUT = "-"

PathLike = str | os.PathLike[str]


def _key(path: Path) -> str:
    return os.path.normcase(os.path.realpath(path))


def check_input_file(path: PathLike, what: str = "input file") -> Path:
    """Refuse an input that is missing, a directory or a special file (FIFO, device).

    A file that passes is registered as read (:func:`protect_input`): no later
    write of this process replaces it.
    """
    p = Path(path)
    _refuse_nul(p, what)
    try:
        st = p.stat()
    except FileNotFoundError:
        raise InputError(f"{what} not found", file=str(p)) from None
    except OSError as exc:
        raise InputError(f"cannot read the {what} ({exc.strerror})", file=str(p)) from None
    if stat.S_ISDIR(st.st_mode):
        raise InputError(f"the {what} is a directory, expected a file", file=str(p))
    if not stat.S_ISREG(st.st_mode):
        raise InputError(f"the {what} is not a regular file (a FIFO or device?); "
                         "give a file on disk", file=str(p))
    if not os.access(p, os.R_OK):
        raise InputError(f"the {what} is not readable", file=str(p))
    _register(p, st)
    return p


def _refuse_nul(path: Path, what: str) -> None:
    """A name holding a NUL character names no file (the system refuses it)."""
    if "\x00" in str(path):
        raise InputError(f"the {what} name holds a NUL character; no file has such a name",
                         file=str(path).replace("\x00", "\\0"))


def _same_file(a: Path, b: Path) -> bool:
    if _key(a) == _key(b):
        return True
    try:
        return os.path.samefile(a, b)
    except OSError:
        return False


def _check_file_target(out: Path, what: str) -> None:
    if out.exists() or out.is_symlink():
        try:
            st = out.stat()
        except OSError as exc:
            raise InputError(f"cannot use the {what} ({exc.strerror})", file=str(out)) from None
        if stat.S_ISDIR(st.st_mode):
            raise InputError(f"the {what} is a directory; give a file name", file=str(out))
        if not stat.S_ISREG(st.st_mode):
            raise InputError(f"the {what} is not a regular file (a FIFO or device?)",
                             file=str(out))
    parent = out.parent if str(out.parent) else Path(".")
    if not parent.is_dir():
        raise InputError(f"the directory of the {what} does not exist", file=str(out))
    if not os.access(parent, os.W_OK | os.X_OK):
        raise InputError(f"the directory of the {what} is not writable", file=str(out))


def _refuse_file_over_dir(out: Path, files: Iterable[Path]) -> None:
    """Refuse an output directory that is, or lies inside, an output file of the same call.

    One of the two would fail only after the other was written.
    """
    key = _key(out)
    for f in files:
        fk = _key(f)
        if key == fk or key.startswith(fk.rstrip(os.sep) + os.sep):
            raise InputError(f"the output directory would be inside the output file '{f}' "
                             "(or be it); give them different names", file=str(out))


def _check_dir_target(out: Path, what: str) -> None:
    if out.exists():
        if not out.is_dir():
            raise InputError(f"the {what} exists and is not a directory", file=str(out))
        if not os.access(out, os.W_OK | os.X_OK):
            raise InputError(f"the {what} is not writable", file=str(out))
        return
    base = out.parent
    while not base.exists() and base != base.parent:
        base = base.parent
    if not base.is_dir() or not os.access(base, os.W_OK | os.X_OK):
        raise InputError(f"cannot create the {what}: '{base}' is not a writable directory",
                         file=str(out))


def check_outputs(files: Iterable[PathLike | None] = (), *,
                  dirs: Iterable[PathLike | None] = (),
                  inputs: Iterable[PathLike | None] = (),
                  what: str = "output file") -> None:
    """Check output paths before any work starts.

    Parameters
    ----------
    files : iterable of path or None
        Output files (``None`` and ``"-"``, standard output, are skipped).
    dirs : iterable of path or None
        Output directories (created later if missing).
    inputs : iterable of path or None
        Files that will be read; none of them may be written.  For an
        output directory, an input inside it is allowed (files written there
        are checked again when written, see :func:`atomic_write`).

    Raises
    ------
    InputError
        Naming the output and what is wrong.
    """
    ins = [Path(p) for p in inputs if p is not None and str(p) != STDOUT]
    seen: dict[str, Path] = {}
    for raw in files:
        if raw is None or str(raw) == STDOUT:
            continue
        if str(raw).endswith(("/", os.sep)):  # Path() would drop the slash: a file 'dir'
            raise InputError(f"the {what} names a directory (it ends with a slash); give a "
                             "file name", file=str(raw))
        out = Path(raw)
        _refuse_nul(out, what)
        for src in ins:
            if _same_file(out, src):
                raise InputError(f"the {what} is also an input; it would be overwritten "
                                 "(give another name)", file=str(out))
        _refuse_protected(out, what)
        if _key(out) in seen:
            raise InputError(f"the same {what} is named twice", file=str(out))
        seen[_key(out)] = out
        _check_file_target(out, what)
    for raw in dirs:
        if raw is None:
            continue
        out = Path(raw)
        _refuse_nul(out, "output directory")
        for src in ins:
            if _same_file(out, src):
                raise InputError("the output directory is also an input", file=str(out))
        _refuse_file_over_dir(out, seen.values())
        _check_dir_target(out, "output directory")
    for src in ins:
        protect_input(src)


def check_unique_names(named: Iterable[tuple[str, str]], *, what: str,
                       file: str | None = None) -> None:
    """Refuse outputs of one call whose file names coincide, before any work.

    A command or call that derives a file name per input (a group, a record, a
    manifest) would otherwise let a later file silently replace an earlier one.  Names
    that differ only in case coincide too (one file on macOS and Windows).

    Parameters
    ----------
    named : iterable of (str, str)
        (what the output is made from, for the message; the file name it gets).
    what : str
        What the outputs are (``"plots"``), for the message.
    file : str, optional
        The input that names them (a manifest, a dataset), for the message.

    Raises
    ------
    InputError
        Naming both sources and the name they share.
    """
    seen: dict[str, str] = {}
    for label, name in named:
        key = os.path.normcase(str(name)).casefold()
        if key in seen:
            raise InputError(f"two {what} would be written as '{name}' ({seen[key]} and "
                             f"{label}; names may not differ only in case): rename one, "
                             "nothing was written", file=file)
        seen[key] = label


#: Inputs read or named in this process (real paths): never replaced.
_PROTECTED: set[str] = set()
#: The same files as (device, inode) -> (mtime in ns, size) when read: a hard link to one
#: is refused too, while the inode still holds that content (a deleted file's inode is
#: handed to new files, whose time and size differ).
_PROTECTED_IDS: dict[tuple[int, int], tuple[int, int]] = {}
#: Files written by this module in this process (real paths): not registered when read.
_WRITTEN: set[str] = set()


def _register(path: Path, st: os.stat_result | None) -> None:
    key = _key(path)
    if key in _WRITTEN:  # this process's own output, read back
        return
    _PROTECTED.add(key)
    if st is not None:
        _PROTECTED_IDS[(st.st_dev, st.st_ino)] = (st.st_mtime_ns, st.st_size)


def protect_input(path: PathLike) -> None:
    """Register ``path`` as an input of this process: no later write replaces it.

    Called for every file the library reads (through :func:`check_input_file`) and
    for the inputs given to :func:`check_outputs`.  Cheap: one ``stat``.  A file this
    process wrote (:func:`atomic_write`, :func:`atomic_dir`) is not registered.

    Parameters
    ----------
    path : path-like
        The file read (a missing file is registered by name).
    """
    p = Path(path)
    try:
        st: os.stat_result | None = p.stat()
    except OSError:
        st = None
    _register(p, st)


def is_protected(path: PathLike) -> bool:
    """True when ``path`` names a file registered by :func:`protect_input` (any name or link).

    Parameters
    ----------
    path : path-like
        The path to test.

    Returns
    -------
    bool
    """
    p = Path(path)
    if _key(p) in _PROTECTED:
        return True
    if not _PROTECTED_IDS:
        return False
    try:
        st = p.stat()
    except OSError:
        return False
    return _PROTECTED_IDS.get((st.st_dev, st.st_ino)) == (st.st_mtime_ns, st.st_size)


def _refuse_protected(path: Path, what: str = "output file") -> None:
    if is_protected(path):
        raise InputError(f"refusing to overwrite an input: the {what} was read in this "
                         "session (give another name)", file=str(path))


@contextlib.contextmanager
def atomic_write(path: PathLike, mode: str = "w", *, encoding: str | None = "utf-8",
                 newline: str | None = None) -> Iterator[IO[Any]]:
    """Open a temporary file beside ``path``; rename it onto ``path`` when the block succeeds.

    On any exception the temporary file is removed and ``path`` is untouched.
    """
    target = Path(path)
    _refuse_protected(target)
    _check_file_target(target, "output file")
    binary = "b" in mode
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part",
                               dir=str(target.parent) or ".")
    try:
        with os.fdopen(fd, mode, encoding=None if binary else encoding,
                       newline=None if binary else newline) as fh:
            yield fh
        with contextlib.suppress(OSError):
            os.chmod(tmp, _mode_for(target))
        os.replace(tmp, target)
        _WRITTEN.add(_key(target))
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _mode_for(target: Path) -> int:
    """The permissions of a file written over ``target``: those of the file it replaces
    (a private 0600 file stays private), else the default of a new file (0666 - umask)."""
    try:
        return stat.S_IMODE(target.stat().st_mode)
    except OSError:
        return 0o666 & ~_umask()


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_text_atomic(path: PathLike, text: str, *, encoding: str = "utf-8") -> Path:
    """Write ``text`` to ``path`` atomically; return the path."""
    with atomic_write(path, "w", encoding=encoding, newline="") as fh:
        fh.write(text)
    return Path(path)


def write_bytes_atomic(path: PathLike, data: bytes) -> Path:
    """Write ``data`` to ``path`` atomically; return the path."""
    with atomic_write(path, "wb") as fh:
        fh.write(data)
    return Path(path)


def check_dir_move(tmp: PathLike, target: PathLike) -> None:
    """Raise now what moving the files built in ``tmp`` into ``target`` would raise.

    A command that writes other files besides a directory of outputs calls this before
    writing them, so that a directory that cannot be moved in fails before anything is
    written (no partial output).

    Parameters
    ----------
    tmp : path-like
        The temporary directory :func:`atomic_dir` yielded.
    target : path-like
        The output directory.

    Raises
    ------
    InputError
        When a file would replace an input of this session, or a file or directory
        stands where the other is needed.
    """
    tmp, target = Path(tmp), Path(target)
    if target.exists() and not target.is_dir():
        raise InputError("the output directory exists and is not a directory", file=str(target))
    for item in sorted(tmp.rglob("*")):
        dest = target / item.relative_to(tmp)
        if item.is_file():
            _refuse_protected(dest)
            if dest.is_dir():
                raise InputError("an output file would replace a directory", file=str(dest))
        elif dest.exists() and not dest.is_dir():
            raise InputError("an output directory would replace a file", file=str(dest))


@contextlib.contextmanager
def atomic_dir(path: PathLike) -> Iterator[Path]:
    """Build a directory of outputs in a temporary directory, then move it into place.

    Yields the temporary directory to write into.  On success every file is moved
    into ``path`` (created with its parents if needed; files already there with other
    names are kept); on failure nothing in ``path`` changes and no directory is created.
    """
    target = Path(path)
    _check_dir_target(target, "output directory")
    base = target.parent if str(target.parent) else Path(".")
    while not base.exists() and base != base.parent:  # missing parents: made at the end only
        base = base.parent
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.", suffix=".part", dir=str(base)))
    try:
        yield tmp
        check_dir_move(tmp, target)
        target.mkdir(parents=True, exist_ok=True)
        for item in sorted(tmp.rglob("*")):
            dest = target / item.relative_to(tmp)
            if item.is_dir():
                dest.mkdir(parents=True, exist_ok=True)
            else:
                with contextlib.suppress(OSError):
                    os.chmod(item, _mode_for(dest))
                os.replace(item, dest)
                _WRITTEN.add(_key(dest))
    finally:
        shutil.rmtree(tmp, ignore_errors=True)


def check_figure_path(path: str | Path) -> str:
    """The figure format of ``path`` (its suffix), refused when matplotlib cannot write it.

    Called before any work, so that a figure that cannot be drawn leaves no other
    output behind.

    Parameters
    ----------
    path : str or Path
        The figure file; no suffix means PNG.

    Returns
    -------
    str
        The format (``"png"``, ``"pdf"``, ``"svg"``...).

    Raises
    ------
    InputError
        When matplotlib has no writer for the suffix (naming those it has).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fmt = Path(path).suffix.lstrip(".").lower() or "png"
    known = FigureCanvasAgg(Figure()).get_supported_filetypes()
    if fmt not in known:
        raise InputError(f"a figure cannot be written as '.{fmt}'; use one of "
                         f"{', '.join('.' + k for k in sorted(known))}", file=str(path))
    return fmt
