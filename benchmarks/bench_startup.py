"""Benchmark of the start-up of ``frictionlaws fit --law thirion thesis-steel`` and of
``frictionlaws --help``.

Baseline, measured in the same run: ``python -c "import lmfit"`` (target: the
whole fit command, start to finish, in <= 1.0x that time).  The two commands run as
subprocesses, alternately (the order swapped every round), so that the load of a shared
machine falls on both; printed are the best and median wall times of each, their ratios
and the median of the paired (same-round) ratios.  The fit runs in a temporary
directory with its output captured there, so no input is touched.

Then, from one more run of the fit command under ``python -X importtime``, which of
numpy, scipy.optimize, pandas, pint, sympy, matplotlib, lmfit and scipy.stats it loads
and their cumulative import time.

With ``--baseline REV`` (a commit of this repository, extracted with ``git archive``
into a temporary folder) or ``--tree DIR`` (another source tree) the fit and ``--help``
also run, in the same rounds, with that tree's ``frictionlaws`` package and with this
tree's, both launched the same way (``python -c``, the tree first on ``sys.path``, the
same interpreter and dependencies), so that the change is measured in the same run:
printed are each one's min and median wall and CPU seconds (the child's user + system
time, which the load of a shared machine moves less than wall time) and the median and
range of the paired ratios (this tree / the other).  The load average is printed before
and after the rounds.

Run: ``python benchmarks/bench_startup.py [--rounds N] [--baseline REV | --tree DIR]``
(default 7 rounds), e.g. ``--baseline 1d5a814 --rounds 20`` (the code before the
ground floor's rooms).
"""

from __future__ import annotations

import argparse
import io
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tarfile
import tempfile
import time
from pathlib import Path

#: The modules whose presence on the fit path is reported.
WATCHED = ("numpy", "scipy.optimize", "pandas", "pint", "sympy", "matplotlib", "lmfit",
           "scipy.stats")
FIT_ARGS = ("fit", "--law", "thirion", "thesis-steel")
HELP_ARGS = ("--help",)
TARGET = 1.0
#: This source tree (the one the benchmark belongs to).
REPO = Path(__file__).resolve().parents[1]

_REPORT_MODULES = (
    "import json, sys\n"
    "from frictionlaws.cli import main\n"
    "code = main(sys.argv[2:])\n"
    "with open(sys.argv[1], 'w') as fh:\n"
    "    json.dump({'code': code, 'modules': sorted(sys.modules)}, fh)\n"
)


def fit_command() -> list[str]:
    """The ``frictionlaws`` console script of this environment (else ``python -m``)."""
    script = Path(sys.executable).with_name("frictionlaws")
    if script.exists():
        return [str(script), *FIT_ARGS]
    found = shutil.which("frictionlaws")
    return [found, *FIT_ARGS] if found else [sys.executable, "-m", "frictionlaws", *FIT_ARGS]


def _child_cpu() -> float:
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def timed(cmd: list[str], cwd: Path, out: Path) -> tuple[float, float]:
    """Wall and CPU (user + system) seconds of one run of ``cmd`` (stdout and stderr to
    ``out``); it must succeed.  The runs are sequential, so the children's CPU time
    before and after is this run's."""
    with out.open("w") as fh:
        cpu0 = _child_cpu()
        t0 = time.perf_counter()
        proc = subprocess.run(cmd, cwd=cwd, stdout=fh, stderr=subprocess.STDOUT)
        elapsed = time.perf_counter() - t0
        cpu = _child_cpu() - cpu0
    if proc.returncode != 0:
        raise SystemExit(f"{' '.join(cmd)} failed (exit {proc.returncode}); see {out}")
    return elapsed, cpu


def wall(cmd: list[str], cwd: Path, out: Path) -> float:
    """Wall seconds of one run of ``cmd`` (stdout and stderr to ``out``); it must succeed."""
    return timed(cmd, cwd, out)[0]


def tree_command(tree: Path, args: tuple[str, ...] = FIT_ARGS) -> list[str]:
    """The command ``frictionlaws ARGS`` run with the package of the source tree ``tree``."""
    code = (f"import sys; sys.path.insert(0, {str(tree)!r}); import frictionlaws; "
            f"assert frictionlaws.__file__.startswith({str(tree)!r}), frictionlaws.__file__; "
            f"from frictionlaws.cli import main; sys.exit(main({list(args)!r}))")
    return [sys.executable, "-c", code]


def alternate(rounds: int, tmp: Path, commands: dict[str, list[str]],
              cpu: dict[str, list[float]] | None = None) -> dict[str, list[float]]:
    """Wall times of each command, one per round, the order rotated every round (and
    their CPU times into ``cpu``, when given)."""
    names = list(commands)
    for name in names:  # file caches, .pyc files
        wall(commands[name], tmp, tmp / f"warm-{name}.txt")
    times: dict[str, list[float]] = {name: [] for name in names}
    for i in range(rounds):
        for name in names[i % len(names):] + names[:i % len(names)]:
            elapsed, used = timed(commands[name], tmp, tmp / f"{name}.txt")
            times[name].append(elapsed)
            if cpu is not None:
                cpu.setdefault(name, []).append(used)
    return times


def extract(rev: str, into: Path) -> Path:
    """This repository's tree at commit ``rev`` (``git archive``), extracted into ``into``."""
    proc = subprocess.run(["git", "-C", str(REPO), "archive", "--format=tar", rev],
                          capture_output=True)
    if proc.returncode != 0:
        raise SystemExit(f"git archive {rev} failed: {proc.stderr.decode(errors='replace')}")
    with tarfile.open(fileobj=io.BytesIO(proc.stdout)) as tar:
        if hasattr(tarfile, "data_filter"):  # Python >= 3.10.12: no path leaves ``into``
            tar.extractall(into, filter="data")
        else:
            tar.extractall(into)  # noqa: S202 - our own repository's commit
    return into


def load() -> str:
    """The load average over 1, 5 and 15 minutes."""
    return " ".join(f"{x:.2f}" for x in os.getloadavg())


def imports(tmp: Path) -> dict[str, float | None]:
    """Watched module -> cumulative import seconds on the fit path (None: not loaded)."""
    import json

    record = tmp / "modules.json"
    proc = subprocess.run([sys.executable, "-X", "importtime", "-c", _REPORT_MODULES,
                           str(record), *FIT_ARGS], cwd=tmp, capture_output=True, text=True)
    if proc.returncode not in (0, 1):
        raise SystemExit(f"the fit command failed under -X importtime:\n{proc.stderr[-2000:]}")
    loaded = set(json.loads(record.read_text())["modules"])
    cumulative: dict[str, float] = {}
    for line in proc.stderr.splitlines():
        m = re.match(r"import time:\s+\d+ \|\s+(\d+) \|\s*(\S+)", line)
        if m:
            name, us = m.group(2), int(m.group(1))
            cumulative[name] = max(cumulative.get(name, 0.0), us * 1e-6)
    return {name: cumulative.get(name, 0.0) if name in loaded else None for name in WATCHED}


def _print_trees(times: dict[str, dict[str, list[float]]], tree: str) -> None:
    """This tree against ``tree``, per command and per clock (wall, CPU): min, median,
    and the median and range of the paired ratios."""
    print(f"this tree ({REPO}) against {tree}, both run as python -c:")
    for name in ("help", "fit"):
        label = " ".join(("frictionlaws", *(HELP_ARGS if name == "help" else FIT_ARGS)))
        print(f"  {label}")
        for clock, runs in times.items():
            this, other = runs[f"this {name}"], runs[f"tree {name}"]
            paired = [t / o for t, o in zip(this, other, strict=True)]
            print(f"    {clock:<4} this tree : min {min(this):.3f} s   "
                  f"median {statistics.median(this):.3f} s")
            print(f"    {clock:<4} other tree: min {min(other):.3f} s   "
                  f"median {statistics.median(other):.3f} s")
            print(f"    {clock:<4} this / other: median of paired "
                  f"{statistics.median(paired):.3f}x (range {min(paired):.3f}.."
                  f"{max(paired):.3f})")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=7, help="timed runs of each command")
    other = ap.add_mutually_exclusive_group()
    other.add_argument("--tree", type=Path,
                       help="also time --help and the fit with this source tree's package")
    other.add_argument("--baseline", metavar="REV",
                       help="as --tree, with this repository's tree at commit REV")
    args = ap.parse_args()
    commands = {"fit": fit_command(), "lmfit": [sys.executable, "-c", "import lmfit"]}
    cpu: dict[str, list[float]] = {}
    with tempfile.TemporaryDirectory() as name:
        tmp = Path(name)
        tree = (extract(args.baseline, Path(tempfile.mkdtemp(dir=tmp)))
                if args.baseline else args.tree.resolve() if args.tree else None)
        if tree is not None:
            for cmd, argv in (("fit", FIT_ARGS), ("help", HELP_ARGS)):
                commands[f"this {cmd}"] = tree_command(REPO, argv)
                commands[f"tree {cmd}"] = tree_command(tree, argv)
        print(f"load average before: {load()}")
        times = alternate(args.rounds, tmp, commands, cpu)
        print(f"load average after : {load()}")
        loaded = imports(tmp)
    fits, bases = times["fit"], times["lmfit"]
    paired = [f / b for f, b in zip(fits, bases, strict=True)]
    print(f"frictionlaws {' '.join(FIT_ARGS)}  vs  python -c 'import lmfit'  "
          f"({args.rounds} alternate rounds, wall seconds)")
    print(f"  fit command : best {min(fits):.3f} s   median {statistics.median(fits):.3f} s")
    print(f"  import lmfit: best {min(bases):.3f} s   median {statistics.median(bases):.3f} s")
    print(f"  ratio fit / import lmfit: best/best {min(fits) / min(bases):.2f}x   "
          f"median/median {statistics.median(fits) / statistics.median(bases):.2f}x   "
          f"median of paired {statistics.median(paired):.2f}x "
          f"(range {min(paired):.2f}..{max(paired):.2f})")
    verdict = "met" if statistics.median(paired) <= TARGET else "NOT met"
    print(f"  target: <= {TARGET:.1f}x  -> {verdict} (median of paired ratios)")
    if tree is not None:
        _print_trees({"wall": times, "cpu": cpu},
                     f"commit {args.baseline}" if args.baseline else str(tree))
    print("modules loaded by the fit command (cumulative import time, -X importtime):")
    for mod, secs in loaded.items():
        state = "not loaded" if secs is None else f"loaded ({secs * 1e3:.0f} ms)"
        print(f"  {mod:<15} {state}")


if __name__ == "__main__":
    main()
