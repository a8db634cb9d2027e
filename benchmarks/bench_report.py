"""Time of ``Comparison.write_report`` on the packaged thesis-steel data (< 2.5 s wall).

The comparison is computed once (every sliding law, or five with ``--quick``); then the
report is written ``--rounds`` times into fresh temporary directories, serially, and
with the figures drawn by ``--jobs`` processes.  Printed from this one run:

* the first report of the process (it loads fonts and caches text metrics) and the median
  and best of the following ones, wall and CPU seconds;
* the CPU seconds of each figure (best of the rounds);
* the serial / ``jobs`` wall ratio;
* with ``--against REF``: the report of the git revision ``REF`` (e.g. ``main``; a module
  or, since it became one, a package), loaded beside the current one and timed
  alternately with it on the same comparison, and the median of the paired wall and CPU
  ratios (current / REF).

Wall times on a shared machine are noisy; CPU seconds and paired ratios are steadier.

Run: ``python benchmarks/bench_report.py [--quick] [--rounds 5] [--jobs 2] [--against main]``.
"""

from __future__ import annotations

import argparse
import importlib
import importlib.util
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from types import ModuleType
from typing import Any

from frictionlaws.comparison import compare, report
from frictionlaws.comparison.report import figures as report_figures
from frictionlaws.fitting import as_fit_data
from frictionlaws.law.registry import list_laws

QUICK = ["coulomb", "thirion", "thesis-poly2", "thesis-poly3", "savkoor"]
ROOT = Path(__file__).resolve().parent.parent


def _report_sources(ref: str) -> dict[str, str]:
    """The report's files at git revision ``ref``: ``report.py`` (a module, as before the
    report became a package) or the ``report/`` package's modules; path -> source."""
    def git(*args: str) -> str:
        return subprocess.run(["git", *args], cwd=ROOT, check=True, capture_output=True,
                              text=True).stdout

    try:
        listed = git("ls-tree", "-r", "--name-only", ref, "frictionlaws/comparison/").split()
        paths = [p for p in listed if p == "frictionlaws/comparison/report.py"
                 or (p.startswith("frictionlaws/comparison/report/") and p.endswith(".py"))]
        if not paths:
            sys.exit(f"bench_report: no report module at {ref!r}")
        return {p: git("show", f"{ref}:{p}") for p in paths}
    except (OSError, subprocess.CalledProcessError) as exc:
        sys.exit(f"bench_report: cannot read the report at {ref!r} with git: {exc}")


#: Modules that moved into rooms (old dotted name -> new one, under ``frictionlaws.``): a
#: revision from before the move imports them by their old names.
MOVED_MODULES = {
    "errors": "base.errors", "numbers": "base.numbers", "units": "base.units",
    "limits": "base.limits", "sanitize": "base.sanitize", "outputs": "base.outputs",
    "jsonio": "base.jsonio", "display": "base.display", "_lazy": "base.lazy",
    "_lsq": "fitting.lsq", "derivatives": "fitting.derivatives", "uncertainty": "fitting.robust",
    "shared": "fitting.shared", "campaign": "fitting.campaign", "interop": "fitting.views",
    "temperature": "viscoelastic.temperature", "mastercurve": "viscoelastic.mastercurve",
    "registry": "law.registry", "bound": "law.bound", "_network": "parallel._network",
    "law_examples": "validation.law_examples", "plotting": "comparison.plotting",
}


def alias_moved_modules() -> list[str]:
    """Make each moved module importable under its old name too (for an older revision's
    report); returns the names added to ``sys.modules``, for the caller to remove."""
    added = []
    for old, new in MOVED_MODULES.items():
        name = f"frictionlaws.{old}"
        if name not in sys.modules and importlib.util.find_spec(name) is None:
            sys.modules[name] = importlib.import_module(f"frictionlaws.{new}")
            added.append(name)
    return added


def load_revision(ref: str, where: Path) -> ModuleType:
    """The comparison report as it is at git revision ``ref``, as a module beside the current
    one (``frictionlaws.comparison._report_at_ref``, its relative imports resolving as the
    current report's, the modules moved since under their old names too:
    :func:`alias_moved_modules`); a package's modules are written to ``where`` and imported
    from there.
    """
    alias_moved_modules()
    name = "frictionlaws.comparison._report_at_ref"
    sources = _report_sources(ref)
    root = where / "_report_at_ref"
    if "frictionlaws/comparison/report.py" in sources:
        root.with_suffix(".py").write_text(sources["frictionlaws/comparison/report.py"])
        spec = importlib.util.spec_from_file_location(name, root.with_suffix(".py"))
    else:
        root.mkdir()
        for path, source in sources.items():
            (root / Path(path).name).write_text(source)
        spec = importlib.util.spec_from_file_location(
            name, root / "__init__.py", submodule_search_locations=[str(root)])
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module


def timed_report(module: Any, cmp: Any, jobs: int = 1) -> tuple[float, float]:
    """Wall and CPU seconds of one ``module.write_report`` into a fresh directory."""
    with tempfile.TemporaryDirectory() as tmp:
        w0, c0 = time.perf_counter(), time.process_time()
        module.write_report(cmp, Path(tmp) / "report", jobs)
        return time.perf_counter() - w0, time.process_time() - c0


def figure_seconds(cmp: Any, rounds: int) -> dict[str, float]:
    """Best CPU seconds of each figure of the current report over ``rounds`` drawings."""
    best: dict[str, float] = {}
    for _ in range(rounds):
        for index in range(len(report_figures._figure_plan(cmp))):
            c0 = time.process_time()
            fig = report_figures._draw(cmp, index)
            spent = time.process_time() - c0
            if fig is not None:
                best[fig.name] = min(best.get(fig.name, spent), spent)
    return best


def summary(label: str, runs: list[tuple[float, float]]) -> str:
    walls, cpus = [w for w, _ in runs], [c for _, c in runs]
    return (f"{label:34s} median {statistics.median(walls):6.2f} s wall "
            f"{statistics.median(cpus):6.2f} s cpu; best {min(walls):6.2f} s wall")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="five laws instead of all")
    ap.add_argument("--rounds", type=int, default=5, help="reports timed per variant")
    ap.add_argument("--jobs", type=int, default=2, help="processes of the parallel run")
    ap.add_argument("--against", metavar="REF", help="git revision whose report to time too")
    args = ap.parse_args()
    data = as_fit_data("thesis-steel")
    laws = QUICK if args.quick else [
        law.id for law in list_laws("sliding") if all(v in data.variables for v in law.variables)]
    cmp = compare(laws, data, progress=False)
    with tempfile.TemporaryDirectory() as where:
        old = load_revision(args.against, Path(where)) if args.against else None
        run(args, laws, cmp, old)


def run(args: argparse.Namespace, laws: list[str], cmp: Any, old: ModuleType | None) -> None:
    """Time the reports and print the figures (see the module's docstring)."""
    first = timed_report(report, cmp)
    now: list[tuple[float, float]] = []
    then: list[tuple[float, float]] = []
    for _ in range(args.rounds):  # alternately, so both see the same machine load
        now.append(timed_report(report, cmp))
        if old is not None:
            then.append(timed_report(old, cmp))
    par = [timed_report(report, cmp, args.jobs) for _ in range(args.rounds)]

    print(f"laws: {len(laws)}; figures: {len(report.make_figures(cmp))}")
    print(f"first report of the process:         {first[0]:6.2f} s wall {first[1]:6.2f} s cpu"
          "  (target < 2.5 s wall)")
    print(summary("report, serial:", now))
    speedup = statistics.median(w for w, _ in now) / statistics.median(w for w, _ in par)
    print(summary(f"report, figures with jobs={args.jobs}:", par)
          + f"; serial / jobs wall {speedup:5.2f}x")
    for name, sec in figure_seconds(cmp, args.rounds).items():
        print(f"  figure {name:28s} {sec:6.3f} s cpu")
    if old is not None:
        print(summary(f"report at {args.against}, serial:", then))
        wall = statistics.median(a[0] / b[0] for a, b in zip(now, then))
        cpu = statistics.median(a[1] / b[1] for a, b in zip(now, then))
        print(f"paired ratio now / {args.against}: {wall:5.2f}x wall, {cpu:5.2f}x cpu "
              f"(median of {len(now)} pairs)")


if __name__ == "__main__":
    main()
