"""The machinery of the validation suite: cases, checks, tolerances, the runner.

A :class:`Case` names its source (paper, manual, table), says what it checks,
and holds a function that computes the obtained values with the library's
public interface and compares them with reference values through a
:class:`CaseRun` recorder.  Every comparison becomes a :class:`Check` row with
the expected value, the obtained value, the tolerance and pass or fail;
quantities that are reported but deliberately not asserted (the R^2 of the
thesis polynomials on the 19 published rows, for instance) are rows with
``passed = None``.

A case passes when it ran to the end and every asserted check passed.  An
exception inside a case is a failure of that case (status ``error``), never of
the whole run.
"""

from __future__ import annotations

import fnmatch
import json
import math
import time
import traceback
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from .. import __version__
from ..base.errors import InputError

__all__ = ["Tol", "Check", "CaseRun", "Case", "CaseResult", "ValidationReport",
           "run_cases", "select_cases"]


@dataclass(frozen=True)
class Tol:
    """A tolerance: ``|obtained - expected| <= abs + rel * |expected|``.

    Parameters
    ----------
    abs : float
        Absolute part (in the unit of the quantity).
    rel : float
        Relative part.
    why : str
        Where the tolerance comes from (e.g. "half a unit of the last printed digit").
    """

    abs: float = 0.0
    rel: float = 0.0
    why: str = ""

    def limit(self, expected: float) -> float:
        """The allowed absolute deviation from ``expected``."""
        return self.abs + self.rel * abs(expected)

    def accepts(self, expected: float, obtained: float) -> bool:
        """True when ``obtained`` lies within the tolerance of ``expected`` (NaN never does)."""
        if not (math.isfinite(expected) and math.isfinite(obtained)):
            return expected == obtained
        return abs(obtained - expected) <= self.limit(expected)

    def describe(self) -> str:
        """``+/-0.0005``, ``rel 1e-09`` or ``+/-1e-12 + rel 1e-09``."""
        parts = []
        if self.abs:
            parts.append(f"+/-{self.abs:.3g}")
        if self.rel:
            parts.append(f"rel {self.rel:.3g}")
        return " + ".join(parts) if parts else "exact"


@dataclass
class Check:
    """One row of a case: a compared (or reported) quantity.

    ``passed`` is True or False for an asserted check and None for a quantity
    that is reported only.
    """

    name: str
    expected: Any
    obtained: Any
    tolerance: str
    passed: bool | None
    unit: str = ""
    note: str = ""

    def to_dict(self) -> dict[str, Any]:
        return {"name": self.name, "expected": _jsonable(self.expected),
                "obtained": _jsonable(self.obtained), "tolerance": self.tolerance,
                "passed": self.passed, "unit": self.unit, "note": self.note}


class CaseRun:
    """The recorder a case function writes its checks into."""

    def __init__(self) -> None:
        self.checks: list[Check] = []
        self.notes: list[str] = []

    def compare(self, name: str, expected: float, obtained: float, tol: Tol, *,
                unit: str = "", note: str = "") -> bool:
        """Assert ``obtained`` equals ``expected`` within ``tol``; return the outcome."""
        expected, obtained = float(expected), float(obtained)
        ok = tol.accepts(expected, obtained)
        self.checks.append(Check(name, expected, obtained, tol.describe(), ok, unit, note))
        return ok

    def at_most(self, name: str, obtained: float, limit: float, *, unit: str = "",
                note: str = "") -> bool:
        """Assert ``obtained <= limit`` (NaN fails)."""
        obtained = float(obtained)
        ok = bool(obtained <= limit)
        self.checks.append(Check(name, f"<= {_fmt(limit)}", obtained, "bound", ok, unit, note))
        return ok

    def at_least(self, name: str, obtained: float, limit: float, *, unit: str = "",
                 note: str = "") -> bool:
        """Assert ``obtained >= limit`` (NaN fails)."""
        obtained = float(obtained)
        ok = bool(obtained >= limit)
        self.checks.append(Check(name, f">= {_fmt(limit)}", obtained, "bound", ok, unit, note))
        return ok

    def require(self, name: str, ok: bool, expected: str, obtained: Any, *,
                note: str = "") -> bool:
        """Assert a qualitative condition described by ``expected``."""
        self.checks.append(Check(name, expected, obtained, "-", bool(ok), "", note))
        return bool(ok)

    def report(self, name: str, value: Any, *, unit: str = "", reference: Any = "",
               note: str = "") -> None:
        """Record a quantity that is reported, not asserted."""
        self.checks.append(Check(name, reference if reference != "" else "(reported)",
                                 value, "-", None, unit, note))

    def note(self, text: str) -> None:
        """Add a note printed under the case."""
        self.notes.append(text)


@dataclass(frozen=True)
class Case:
    """One validation case.

    Parameters
    ----------
    id : str
        Short name used by ``frictionlaws validate --case``.
    title : str
        One line saying what is validated.
    source : str
        The published source(s) of the reference numbers (paper, manual,
        table) or of the reference implementation.
    check : str
        What is compared, and how the tolerance was chosen.
    func : callable
        ``func(run: CaseRun) -> None``: computes and records the checks.
    note : str
        What the result means (printed with the case).
    """

    id: str
    title: str
    source: str
    check: str
    func: Callable[[CaseRun], None]
    note: str = ""

    def run(self) -> CaseResult:
        """Run the case; an exception makes it fail with status ``error``."""
        rec = CaseRun()
        t0 = time.perf_counter()
        error = None
        try:
            self.func(rec)
        except Exception as exc:  # noqa: BLE001 - a broken case must not stop the suite
            tb = traceback.extract_tb(exc.__traceback__)
            where = f" at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno}" if tb else ""
            error = f"{type(exc).__name__}: {exc}{where}"
        elapsed = time.perf_counter() - t0
        asserted = [c for c in rec.checks if c.passed is not None]
        if error is not None:
            status = "error"
        elif not asserted:
            status = "error"
            error = "the case recorded no asserted check"
        else:
            status = "pass" if all(c.passed for c in asserted) else "fail"
        return CaseResult(self.id, self.title, self.source, self.check, status, rec.checks,
                          rec.notes + ([self.note] if self.note else []), elapsed, error)


@dataclass
class CaseResult:
    """The outcome of one case."""

    id: str
    title: str
    source: str
    check: str
    status: str
    checks: list[Check]
    notes: list[str]
    seconds: float
    error: str | None = None

    @property
    def passed(self) -> bool:
        return self.status == "pass"

    def to_dict(self) -> dict[str, Any]:
        return {"id": self.id, "title": self.title, "source": self.source,
                "check": self.check, "status": self.status, "passed": self.passed,
                "seconds": round(self.seconds, 3), "error": self.error,
                "checks": [c.to_dict() for c in self.checks], "notes": list(self.notes)}

    def format(self) -> str:
        """The plain-text block ``frictionlaws validate`` prints for this case."""
        head = {"pass": "PASS", "fail": "FAIL", "error": "ERROR"}[self.status]
        lines = [f"{head}  {self.id}: {self.title}  ({self.seconds:.2f} s)",
                 f"      source: {self.source}",
                 f"      check:  {self.check}"]
        if self.checks:
            rows = [("quantity", "expected", "obtained", "tolerance", "result")]
            for c in self.checks:
                res = "report" if c.passed is None else ("pass" if c.passed else "FAIL")
                unit = f" {c.unit}" if c.unit else ""
                rows.append((c.name, _fmt(c.expected) + (unit if _is_num(c.expected) else ""),
                             _fmt(c.obtained) + (unit if _is_num(c.obtained) else ""),
                             c.tolerance, res))
            widths = [min(max(len(r[i]) for r in rows), cap)
                      for i, cap in enumerate((44, 22, 22, 24, 6))]
            for r in rows:
                cells = [r[i].ljust(widths[i]) for i in range(5)]
                lines.append("      " + "  ".join(cells).rstrip())
            for c in self.checks:
                if c.note:
                    lines.append(f"      * {c.name}: {c.note}")
        if self.error:
            lines.append(f"      error: {self.error}")
        for n in self.notes:
            lines.append(f"      note: {n}")
        return "\n".join(lines)


@dataclass
class ValidationReport:
    """The outcome of a validation run."""

    results: list[CaseResult] = field(default_factory=list)
    seconds: float = 0.0
    warnings: list[str] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return bool(self.results) and all(r.passed for r in self.results)

    @property
    def n_failed(self) -> int:
        return sum(not r.passed for r in self.results)

    def summary_line(self) -> str:
        n = len(self.results)
        return (f"validation: {n} case{'s' if n != 1 else ''}, {n - self.n_failed} passed, "
                f"{self.n_failed} failed ({self.seconds:.1f} s)")

    def to_dict(self) -> dict[str, Any]:
        return {"format": "frictionlaws-validation", "version": 1,
                "frictionlaws": __version__, "passed": self.passed,
                "n_cases": len(self.results), "n_failed": self.n_failed,
                "seconds": round(self.seconds, 3), "warnings": list(self.warnings),
                "cases": [r.to_dict() for r in self.results]}

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    def format(self) -> str:
        blocks = [r.format() for r in self.results]
        tail = [f"warning: {w}" for w in self.warnings] + [self.summary_line()]
        return "\n\n".join(blocks) + "\n\n" + "\n".join(tail)


def select_cases(cases: Sequence[Case], names: Iterable[str] | None) -> list[Case]:
    """The cases named by id or shell pattern (``reference-*``), in suite order.

    Raises
    ------
    InputError
        When a name matches no case (the message lists the case ids).
    """
    if not names:
        return list(cases)
    ids = [c.id for c in cases]
    chosen: set[str] = set()
    for name in names:
        hits = [i for i in ids if fnmatch.fnmatchcase(i, name.strip().lower())]
        if not hits:
            raise InputError(f"unknown validation case '{name}' (cases: {', '.join(ids)})")
        chosen.update(hits)
    return [c for c in cases if c.id in chosen]


def run_cases(cases: Sequence[Case], *, progress: Callable[[CaseResult], None] | None = None
              ) -> ValidationReport:
    """Run ``cases`` in order and collect a :class:`ValidationReport`."""
    t0 = time.perf_counter()
    report = ValidationReport()
    for case in cases:
        res = case.run()
        report.results.append(res)
        if progress is not None:
            progress(res)
    report.seconds = time.perf_counter() - t0
    return report


def _is_num(x: Any) -> bool:
    return isinstance(x, (int, float)) and not isinstance(x, bool)


def _fmt(x: Any) -> str:
    if isinstance(x, bool):
        return "yes" if x else "no"
    if _is_num(x):
        x = float(x)
        if x == 0:
            return "0"
        if not math.isfinite(x):
            return str(x)
        a = abs(x)
        if 1e-3 <= a < 1e5:
            return f"{x:.6g}"
        return f"{x:.4e}"
    return str(x)


def _jsonable(x: Any) -> Any:
    if _is_num(x):
        x = float(x)
        return x if math.isfinite(x) else str(x)
    return x
