"""Whole-command time of ``frictionlaws fit`` against ``python -c "import lmfit"`` (issue 15).

Runs ``python -m frictionlaws fit --law thirion thesis-steel`` and ``python -c "import
lmfit"`` alternately as subprocesses in the same run and prints the median of each and
their ratio.  Target: at most 1.0x (a fit, its data loading and its report cost no more
than importing lmfit).  ``show thirion`` and ``laws`` are timed too, for reference.

Run: ``python benchmarks/bench_startup.py [--rounds 9]``.
"""

from __future__ import annotations

import argparse
import statistics
import subprocess
import sys
import time

COMMANDS = {
    "python -c 'import lmfit'": [sys.executable, "-c", "import lmfit"],
    "frictionlaws fit --law thirion thesis-steel": [
        sys.executable, "-m", "frictionlaws", "fit", "--law", "thirion", "thesis-steel"],
    "frictionlaws show thirion": [sys.executable, "-m", "frictionlaws", "show", "thirion"],
    "frictionlaws laws": [sys.executable, "-m", "frictionlaws", "laws"],
}


def once(cmd: list[str]) -> float:
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return time.perf_counter() - t0


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rounds", type=int, default=9)
    args = ap.parse_args()
    for cmd in COMMANDS.values():  # warm the file cache
        once(cmd)
    times: dict[str, list[float]] = {k: [] for k in COMMANDS}
    for _ in range(args.rounds):
        for name, cmd in COMMANDS.items():
            times[name].append(once(cmd))
    base = statistics.median(times["python -c 'import lmfit'"])
    print(f"{'command':<46} {'median [ms]':>11} {'ratio':>6}")
    for name, ts in times.items():
        med = statistics.median(ts)
        print(f"{name:<46} {med * 1e3:11.0f} {med / base:6.2f}")
    fit = statistics.median(times["frictionlaws fit --law thirion thesis-steel"])
    print(f"fit / import lmfit: {fit / base:.2f}x (target <= 1.0x)")


if __name__ == "__main__":
    main()
