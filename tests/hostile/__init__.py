"""The hostile-input harness: an in-process runner, the invariants, and input generators.

Every case runs ``frictionlaws.cli.main(argv)`` (or an API call) in this process
under a SIGALRM time guard and then checks the invariants every command owes a
user, whatever the input:

* the exit code is 0, 1 or 2, never 3 (an internal error) and never a hang;
* no ``Traceback`` and no library source path on stdout or stderr;
* on exit 2 exactly one stderr line that is not a ``warning:`` line, and it
  starts with ``error:``; no raw Python warning line (``...Warning: ...``);
* with ``--json`` and exit 0, stdout parses under a strict JSON parser (one that
  refuses ``NaN``/``Infinity``);
* no input file changed (hash before and after);
* nothing left behind after a failure (the directory listing is unchanged) and
  never a ``*.part`` file, even after a success.

The generators (``hypothesis`` strategies) build hostile CSV tables, Magic
Formula property files, parameter JSON files and rig TOML files; the tests in
``tests/test_hostile*.py`` combine them with hostile options.
"""

from __future__ import annotations

import contextlib
import hashlib
import io
import json
import math
import os
import re
import signal
import socket
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from hypothesis import HealthCheck, Phase, settings
from hypothesis import strategies as st

__all__ = [
    "hostile",
    "Outcome",
    "Hang",
    "time_limit",
    "run_cli",
    "Snapshot",
    "check_outcome",
    "check_api",
    "check_export_file",
    "strict_json",
    "stderr_lines",
    "csv_bytes",
    "tir_bytes",
    "params_bytes",
    "rig_bytes",
    "NASTY_NUMBERS",
    "MF52_TIR",
    "MF52_JSON",
    "RIG_TOML",
    "UNWRITABLE",
    "tcp_peer",
]

ROOT = Path(__file__).resolve().parents[2]
MF52_TIR = ROOT / "datasets" / "mf-examples" / "MagicFormula52_Parameters.converted.tir"
MF52_JSON = ROOT / "datasets" / "mf-examples" / "MagicFormula52_Parameters.json"
#: A path no process can create a file in, even as root.
UNWRITABLE = "/proc/frictionlaws-hostile/out.json"

#: Default time bound of one case [s] (a hang is a failure, not a slow test).
TIME_LIMIT = 20.0


def hostile(n: int) -> settings:
    """Harness settings: ``n`` derandomised examples, no deadline, no example database.

    Shrinking is off: a failing case is reported as generated, so a failure costs
    seconds, not the minutes shrinking can take (the CI budget is 60 s).

    Deeper runs: ``HOSTILE_SCALE=10`` multiplies the examples; ``HOSTILE_EXPLORE=1``
    draws fresh random cases and skips the pinned examples of known failures (use
    with ``--runxfail`` to see what else a test finds).
    """
    scale = int(os.environ.get("HOSTILE_SCALE", "1"))
    explore = os.environ.get("HOSTILE_EXPLORE") == "1"
    return settings(max_examples=n * max(scale, 1), deadline=None, derandomize=not explore,
                    database=None,
                    phases=[Phase.generate] if explore else [Phase.explicit, Phase.generate],
                    suppress_health_check=list(HealthCheck))


class Hang(BaseException):
    """Raised by the time guard (a BaseException so that ``except Exception`` cannot eat it)."""


@contextlib.contextmanager
def time_limit(seconds: float) -> Iterator[None]:
    """Raise :class:`Hang` in the main thread after ``seconds`` (SIGALRM)."""
    def _alarm(signum: int, frame: Any) -> None:
        raise Hang(f"no answer within {seconds:g} s")

    old = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


@dataclass
class Outcome:
    """What one CLI run produced."""

    argv: list[str]
    code: int | None
    out: str
    err: str
    seconds: float
    hung: bool = False

    def describe(self) -> str:
        return (f"argv={self.argv!r}\ncode={self.code} hung={self.hung} "
                f"({self.seconds:.2f} s)\nstdout={self.out[:600]!r}\nstderr={self.err[:1500]!r}")


def _stream() -> io.TextIOWrapper:
    return io.TextIOWrapper(io.BytesIO(), encoding="utf-8", errors="backslashreplace",
                            write_through=True)


def _text(stream: io.TextIOWrapper) -> str:
    stream.flush()
    raw = stream.buffer
    assert isinstance(raw, io.BytesIO)
    return raw.getvalue().decode("utf-8", errors="backslashreplace")


def run_cli(argv: Iterable[str], *, stdin: bytes = b"", timeout: float = TIME_LIMIT) -> Outcome:
    """Run ``frictionlaws.cli.main(argv)`` in-process with captured streams and a time bound."""
    from frictionlaws.cli import main

    args = [str(a) for a in argv]
    out, err = _stream(), _stream()
    fake_in = io.TextIOWrapper(io.BytesIO(stdin), encoding="utf-8")
    saved = sys.stdout, sys.stderr, sys.stdin
    sys.stdout, sys.stderr, sys.stdin = out, err, fake_in
    t0 = time.perf_counter()
    code: int | None = None
    hung = False
    try:
        with time_limit(timeout):
            code = main(args)
    except Hang:
        hung = True
    except SystemExit as exc:  # main must return, never exit
        code = -1 if exc.code is None else 1000 + int(exc.code) if isinstance(exc.code, int) else -1
    finally:
        sys.stdout, sys.stderr, sys.stdin = saved
    res = Outcome(args, code, _text(out), _text(err), time.perf_counter() - t0, hung)
    _log(res)
    return res


def _log(res: Outcome) -> None:
    """With HOSTILE_LOG=FILE, append one line per case (for measuring what the harness hits)."""
    path = os.environ.get("HOSTILE_LOG")
    if path:
        first = (stderr_lines(res.err) or [""])[0][:160]
        with open(path, "a", encoding="utf-8") as fh:
            fh.write(f"{' '.join(res.argv[:2])}\t{res.code}\t{res.seconds:.3f}\t{first}\n")


# ------------------------------------------------------------------- invariants


def stderr_lines(err: str) -> list[str]:
    """Stderr lines as a terminal would show them (progress-bar ``\\r`` rewrites dropped)."""
    lines = []
    for raw in err.split("\n"):
        shown = raw.split("\r")[-1].strip()
        if shown:
            lines.append(shown)
    return lines


def _refuse_constant(name: str) -> Any:
    raise ValueError(f"non-standard JSON constant {name}")


def strict_json(text: str) -> Any:
    """Parse ``text`` as JSON refusing ``NaN``/``Infinity`` (a strict parser)."""
    return json.loads(text, parse_constant=_refuse_constant)


def _digest(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


@dataclass
class Snapshot:
    """The files under some directories (with hashes), taken before a run."""

    roots: list[Path]
    inputs: list[Path] = field(default_factory=list)
    files: dict[str, str] = field(default_factory=dict)
    input_hashes: dict[str, str] = field(default_factory=dict)

    @classmethod
    def take(cls, roots: Iterable[Path], inputs: Iterable[Path] = ()) -> Snapshot:
        snap = cls([Path(r) for r in roots], [Path(p) for p in inputs])
        snap.files = snap._listing()
        snap.input_hashes = {str(p): _digest(p) for p in snap.inputs if p.is_file()}
        return snap

    def _listing(self) -> dict[str, str]:
        out = {}
        for root in self.roots:
            for dirpath, dirnames, filenames in os.walk(root):
                for name in dirnames + filenames:
                    p = Path(dirpath) / name
                    if p.is_file() and not p.is_symlink():
                        out[str(p)] = _digest(p)
                    else:
                        out[str(p)] = "dir" if p.is_dir() else "other"
        return out

    def check(self, *, failed: bool, allowed: Iterable[Path] = ()) -> list[str]:
        """Problems: changed inputs, ``*.part`` files, anything new or changed after a failure."""
        problems = []
        for name, digest in self.input_hashes.items():
            if not Path(name).is_file() or _digest(Path(name)) != digest:
                problems.append(f"input changed: {name}")
        now = self._listing()
        parts = [n for n in now if n.endswith(".part") or ".part" in Path(n).name]
        problems.extend(f"left behind: {n}" for n in parts)
        changed = {n for n in now if self.files.get(n) != now[n]}
        gone = set(self.files) - set(now)
        if failed:
            problems.extend(f"after a failure, changed or new: {n}" for n in sorted(changed))
            problems.extend(f"after a failure, removed: {n}" for n in sorted(gone))
        else:
            ok = {str(Path(a)) for a in allowed}
            parents = {str(parent) for a in allowed for parent in Path(a).parents}
            for n in sorted(changed):
                inside = any(n.startswith(d + os.sep) for d in ok)
                if n not in ok and not inside and not (now[n] == "dir" and n in parents):
                    problems.append(f"unexpected file written: {n}")
        return problems


_RAW_WARNING = re.compile(r"(^|\s)\w*(Warning|Error):|:\d+: \w*Warning")


def check_outcome(res: Outcome, *, snapshot: Snapshot | None = None, json_out: bool = False,
                  allowed: Iterable[Path] = (), codes: Iterable[int] = (0, 1, 2)) -> None:
    """Assert the harness invariants on one run (the message shows the whole case)."""
    problems = []
    if res.hung:
        problems.append("hung (no answer within the time bound)")
    elif res.code not in set(codes):
        problems.append(f"exit code {res.code} (expected one of {sorted(set(codes))})")
    for name, text in (("stdout", res.out), ("stderr", res.err)):
        if "Traceback" in text:
            problems.append(f"a traceback on {name}")
        if "site-packages" in text or "dist-packages" in text:
            problems.append(f"a library path on {name}")
    lines = stderr_lines(res.err)
    others = [ln for ln in lines if not ln.startswith("warning:")]
    if res.code == 2:
        if len(others) != 1 or not others[0].startswith("error: "):
            problems.append(f"exit 2 needs exactly one 'error:' line on stderr, got {others!r}")
    raw = [ln for ln in lines if not ln.startswith(("warning:", "error:"))
           and _RAW_WARNING.search(ln)]
    if raw:
        problems.append(f"raw Python warnings or errors on stderr: {raw[:3]!r}")
    if json_out and res.code == 0:
        try:
            strict_json(res.out)
        except ValueError as exc:
            problems.append(f"stdout is not strict JSON ({exc})")
    if snapshot is not None:
        problems.extend(snapshot.check(failed=res.code != 0, allowed=allowed))
    assert not problems, "; ".join(problems) + "\n" + res.describe()


def check_api(call: Callable[[], Any], *, snapshot: Snapshot | None = None,
              timeout: float = TIME_LIMIT, allowed: Iterable[Path] = ()) -> Any:
    """Run an API call: it returns, or raises InputError/FitError; nothing else, no hang."""
    from frictionlaws.base.errors import FitError, InputError

    result: Any = None
    failed = False
    _log(Outcome(["api", getattr(call, "__name__", "call")], 0, "", "", 0.0))
    try:
        with time_limit(timeout):
            result = call()
    except Hang as exc:
        raise AssertionError(f"API call hung: {exc}") from None
    except (InputError, FitError) as exc:
        failed = True
        text = str(exc)
        assert text and "\n" not in text.strip(), f"message not one line: {text!r}"
        result = exc
    if snapshot is not None:
        problems = snapshot.check(failed=failed, allowed=allowed)
        assert not problems, problems
    return result


def check_export_file(path: Path, fmt: str) -> None:
    """A written grid is sound: every number finite, every mu >= 0, JSON strict."""
    if fmt == "json":
        strict_json(path.read_text(encoding="utf-8"))
        return
    if fmt != "csv":
        return
    rows = [ln for ln in path.read_text(encoding="utf-8").splitlines()
            if ln and not ln.startswith("#")][1:]
    assert rows, f"no rows in {path}"
    for line in rows:
        cells = [float(c) for c in line.split(",")]
        assert all(math.isfinite(c) for c in cells), f"non-finite number in {path}: {line}"
        assert cells[-1] >= 0, f"negative mu in {path}: {line}"


# ------------------------------------------------------------------- generators

#: Number spellings a strict reader must refuse or read correctly.
NASTY_NUMBERS = [
    "1_000", "\uff11\uff12\uff13", "\u0663", "1e999", "-1e999", "1e-400", "nan", "NaN", "inf",
    "-Infinity", "1,5", "1.000,5", "1.5.2", "0x10", " 3 ", "", "-", ".", "+.5", "1e", "e5",
    "12abc", "\u22121", "\u00bd", "True", "-0", "5e307", "-3", "-1e-3", "1E+02", "0.3 ",
    "\t0.2", "'0.1'", "\"0.4\"", "1 000", "1\u00a0000", "\u0661.\u0665",
]

HEADERS = [
    "mu", "p [MPa]", "v [m/s]", "T [degC]", "s", "F_N [N]", "p", "mu [-]", "p [Mpa]",
    "v [furlong]", "\u03bc", "mu ", "", "x", "T [C]", "v [mm/s]", "load [kg]", "p [bar]",
    "mu_std", "n", "FC", "CP", "\"mu\"", "mu\x00", "F_N [kN]",
]

_GOOD_ROW = st.tuples(st.floats(0.05, 2.0), st.floats(0.01, 0.5), st.floats(0.0, 2.0))


def _cell() -> st.SearchStrategy[str]:
    return st.one_of(
        st.sampled_from(NASTY_NUMBERS),
        st.floats(allow_nan=True, allow_infinity=True).map(repr),
        st.floats(-1e6, 1e6).map(lambda x: f"{x:.6g}"),
        st.integers(-10**30, 10**30).map(str),
        st.text(max_size=6),
    )


@st.composite
def _table(draw: Any, spoil: bool = True, good: bool = True) -> str:
    delim = draw(st.sampled_from([",", ";", "\t"] + ([] if good else ["|", " "])))
    comma = delim != "," and draw(st.booleans())  # decimal commas in ';'/tab files
    if good:
        header = ["mu", "p [MPa]", "v [m/s]"]
        rows = [[f"{a:.4g}", f"{b:.4g}", f"{c:.4g}"]
                for a, b, c in draw(st.lists(_GOOD_ROW, min_size=3, max_size=10))]
        if comma:
            rows = [[c.replace(".", ",") for c in r] for r in rows]
        for _ in range(draw(st.integers(1, 3)) if spoil else 0):  # spoil a few cells
            i = draw(st.integers(0, len(rows) - 1))
            rows[i][draw(st.integers(0, 2))] = draw(_cell())
    else:
        header = draw(st.lists(st.sampled_from(HEADERS), min_size=1, max_size=5))
        rows = draw(st.lists(st.lists(_cell(), min_size=len(header), max_size=len(header)),
                             max_size=8))
    lines = [delim.join(header)] + [delim.join(r) for r in rows]
    return "\n".join(lines) + draw(st.sampled_from(["\n", "", "\r\n", "\n\n\n"]))


def _big_then_nul(text_rows: int) -> bytes:
    rows = ["mu,p [MPa]"] + [f"{0.5 + 0.001 * (i % 50):.4f},{0.02 + 0.001 * (i % 90):.4f}"
                             for i in range(text_rows)]
    body = "\n".join(rows).encode()
    return body + b"\n0.5,\x000.1\n0.6,0.2\n"


_SPECIAL_CSV = [
    b"",
    b"mu,p [MPa]\n",
    b"mu,p [MPa],v [m/s]\n\"0.5\n0.6\",0.1,1\n0.7,0.2,2\n0.8,0.3,3\n",
    b"mu;p [MPa];v [m/s]\n1.000,5;0,1;1\n0,8;0.2;2,0\n0,7;1.000;3\n",
    b"mu,mu,p [MPa]\n0.5,0.6,0.1\n0.6,0.7,0.2\n0.7,0.8,0.3\n",
    b"mu,p [MPa]\n1e308,1e308\n1e308,1e308\n1e308,1e308\n",
    b"mu,p [MPa]\n-0.5,-0.1\n-0.6,-0.2\n-0.7,-0.3\n",
    b"mu,p [GPa]\n0.5,1e300\n0.6,2e300\n0.7,3e300\n",
    b"mu,p [MPa]\n0.5,0.1\n0.5,0.2\n0.5,0.3\n0.5,0.4\n",
    b"mu,p [MPa]\n0.5,0.1\n",
    b"\xef\xbb\xbfmu,p [MPa]\n0.5,0.1\n0.6,0.2\n0.7,0.3\n",
    "mu,p [MPa]\n0.5,0.1\n0.6,0.2\n0.7,0.3\n".encode("utf-16"),
    "mu,p [MPa]\n\uff10.5,0.1\n0.6,0.2\n0.7,0.3\n".encode(),
    b"mu,p [MPa]\n1_0,0.1\n0.6,0.2\n0.7,0.3\n",
    _big_then_nul(900),
]


@st.composite
def csv_bytes(draw: Any) -> bytes:
    """A CSV file: valid, spoiled in a few cells, random, random bytes, or a known trap."""
    kind = draw(st.sampled_from(["good", "good", "good", "spoiled", "spoiled", "spoiled",
                                 "random", "bytes", "special", "special"]))
    if kind == "bytes":
        return draw(st.binary(max_size=400))
    if kind == "special":
        return draw(st.sampled_from(_SPECIAL_CSV))
    text = draw(_table(spoil=kind == "spoiled", good=kind != "random"))
    enc = draw(st.sampled_from(["utf-8", "utf-8", "utf-8-sig", "utf-16", "latin-1", "cp1252"]))
    return text.encode(enc, errors="replace")


def _tir_lines() -> list[str]:
    return MF52_TIR.read_text(encoding="utf-8").splitlines()


_KEY_LINE = re.compile(r"^([A-Z_0-9]+)(\s*=\s*)(\S+)(.*)$")


@st.composite
def tir_bytes(draw: Any) -> bytes:
    """A Magic Formula .tir file with 1..3 hostile mutations."""
    lines = _tir_lines()
    keyed = [i for i, ln in enumerate(lines) if _KEY_LINE.match(ln)]
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.sampled_from(keyed))
        m = _KEY_LINE.match(lines[i])
        if m is None:  # already mutated beyond recognition
            continue
        key, eq, value, rest = m.groups()
        how = draw(st.sampled_from(["comma", "misspell", "text", "delete", "nasty", "dup",
                                    "fittyp", "pressure", "fnomin", "lower"]))
        if how == "comma" and "." in value:
            lines[i] = f"{key}{eq}{value.replace('.', ',')}{rest}"
        elif how == "misspell":
            lines[i] = f"{key[:-1]}_{key[-1]}{eq}{value}{rest}"
        elif how == "text":
            lines[i] = f"{key}{eq}abc{rest}"
        elif how == "delete":
            lines[i] = "$ deleted"
        elif how == "nasty":
            lines[i] = f"{key}{eq}{draw(st.sampled_from(NASTY_NUMBERS))}{rest}"
        elif how == "dup":
            lines.insert(i + 1, f"{key}{eq}7.5")
        elif how == "fittyp":
            lines = [re.sub(r"^FITTYP(\s*=\s*)\S+", r"FITTYP\g<1>" +
                            draw(st.sampled_from(["99", "5", "'x'", "62", "-1"])), ln)
                     for ln in lines]
        elif how == "pressure":
            lines.insert(i, f"INFLPRES{eq}{draw(st.sampled_from(['-2e5', '0', '1e999', 'x']))}")
        elif how == "fnomin":
            lines = [re.sub(r"^FNOMIN(\s*=\s*)\S+", r"FNOMIN\g<1>" +
                            draw(st.sampled_from(["0", "-4000", "1e999", "9,4"])), ln)
                     for ln in lines]
        elif how == "lower":
            lines[i] = lines[i].lower()
    text = "\n".join(lines) + "\n"
    tail = draw(st.sampled_from(["none", "none", "truncate", "utf16", "nul", "bytes"]))
    if tail == "truncate":
        text = text[: draw(st.integers(0, len(text)))]
    if tail == "utf16":
        return text.encode("utf-16")
    data = text.encode("utf-8")
    if tail == "nul":
        cut = draw(st.integers(0, len(data)))
        data = data[:cut] + b"\x00" + data[cut:]
    if tail == "bytes":
        data = draw(st.binary(max_size=200)) + data[:300]
    return data


_VALUES = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0, -5, 1e308, "0.5", "abc", None, True, [1, 2], {"value": "x"},
                     {"value": float("nan")}, {"value": -1.0}, {"stderr": 1}]),
)


def _good_values(law_id: str) -> dict[str, float]:
    from frictionlaws.law.registry import get_law

    law = get_law(law_id)
    if law.presets:
        return dict(next(iter(law.presets.values())))
    return {p.name: p.default for p in law.params}


@st.composite
def params_bytes(draw: Any, laws: tuple[str, ...] = ("thirion", "coulomb", "thesis-poly2",
                                                     "exponential-decay")) -> bytes:
    """A parameter JSON file (``{'law': ..., 'params': {...}}``), valid or spoiled."""
    kind = draw(st.sampled_from(["good", "good", "spoiled", "spoiled", "not-object", "text"]))
    if kind == "text":
        return draw(st.sampled_from([b"", b"{", b"{'law': 'thirion'}", b"\xff\xfe{\x00}",
                                     b"null", b"[]", "{\"law\": \"thirion\"}".encode("utf-16"),
                                     b"{\"law\": \"thirion\", \"params\": {\"a\": NaN}}"]))
    if kind == "not-object":
        doc: Any = draw(st.sampled_from([[1, 2], 3, "thirion", None, True]))
        return json.dumps(doc).encode()
    law = draw(st.sampled_from(laws))
    params: dict[str, Any] = dict(_good_values(law))
    doc = {"law": law, "params": params}
    if kind == "spoiled":
        for _ in range(draw(st.integers(1, 2))):
            how = draw(st.sampled_from(["value", "drop", "extra", "law", "top", "remove"]))
            name = draw(st.sampled_from(sorted(params) or ["a"]))
            if how == "value":
                params[name] = draw(_VALUES)
            elif how == "drop":
                params.pop(name, None)
            elif how == "extra":
                params[draw(st.sampled_from(["zz", "mu", "a_"]))] = 1.0
            elif how == "law":
                doc["law"] = draw(st.sampled_from(["nope", "", 7, None, "pacejka"]))
            elif how == "top":
                doc[draw(st.sampled_from(["format", "version", "settings"]))] = draw(_VALUES)
            else:
                doc.pop(draw(st.sampled_from(["law", "params"])), None)
    return json.dumps(doc, allow_nan=True).encode("utf-8")


RIG_TOML = """\
track_radius = "40 mm"
pin_diameter = "20 mm"
system_error = "0.3 N*m"
g = "9.8 m/s^2"
torque_range = "10 N*m"

[internal_torque]
disc_speed_rpm = [0, 331, 663]
torque_Nm = [0.1, 0.05, 0.12]

[filter]
cutoff = "auto"
"""

_RIG_VALUES = ["\"-40 mm\"", "\"40\"", "\"40 furlong\"", "\"nan mm\"", "\"1e999 mm\"", "40",
               "-1", "[1, 2]", "\"0 mm\"", "\"40 mm\" junk", "\"\"", "{ a = 1 }", "true",
               "\"4O mm\"", "\"40 mm\"\"", "0.04", "\"1_000 mm\""]


@st.composite
def rig_bytes(draw: Any) -> bytes:
    """A rig TOML file with 1..3 hostile edits."""
    lines = RIG_TOML.splitlines()
    for _ in range(draw(st.integers(1, 3))):
        i = draw(st.integers(0, len(lines) - 1))
        line = lines[i]
        how = draw(st.sampled_from(["value", "delete", "misspell", "array", "garbage"]))
        if "=" in line and how == "value":
            lines[i] = line.split("=")[0] + "= " + draw(st.sampled_from(_RIG_VALUES))
        elif how == "delete":
            lines[i] = ""
        elif how == "misspell" and "=" in line:
            lines[i] = "x" + line
        elif how == "array" and "[" in line and "=" in line:
            lines[i] = line.split("=")[0] + "= " + draw(st.sampled_from(
                ["[]", "[0, 331]", "[\"a\", 1, 2]", "[1e999, 2, 3]", "[-1, -2, -3]"]))
        elif how == "garbage":
            lines.insert(i, draw(st.sampled_from(["[[", "= 3", "a = ", "\x00", "[filter]"])))
    text = "\n".join(lines) + "\n"
    if draw(st.integers(0, 6)) == 0:
        return text.encode("utf-16")
    return text.encode("utf-8")


# ------------------------------------------------------------------------ peers


def tcp_peer(replies: list[bytes]) -> Iterator[str]:
    """A TCP peer on 127.0.0.1 that sends ``replies`` in turn on every connection, one
    after each message it reads (the first at once); with none it accepts and never
    says a word.  A generator: the address, then the peer is shut down."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(8)
    stop = threading.Event()
    held: list[socket.socket] = []

    def serve() -> None:
        server.settimeout(0.1)
        while not stop.is_set():
            try:
                conn, _ = server.accept()
            except OSError:
                continue
            held.append(conn)
            try:
                for reply in replies:
                    conn.sendall(reply)
                    conn.settimeout(2.0)
                    conn.recv(65536)
            except OSError:
                pass

    thread = threading.Thread(target=serve, daemon=True)
    thread.start()
    try:
        yield f"tcp://127.0.0.1:{server.getsockname()[1]}"
    finally:
        stop.set()
        thread.join(2)
        for conn in held:
            conn.close()
        server.close()
