"""Print pip constraints pinning each runtime dependency to its declared lower bound.

Each ``name>=X`` in ``[project].dependencies`` of pyproject.toml becomes ``name==X.*``
(the lowest release series the project claims to support); environment markers are kept.
CI installs the suite against these constraints on the oldest supported Python.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

import tomllib

REQ = re.compile(r"^\s*([A-Za-z0-9_.\-\[\]]+)\s*>=\s*([0-9][0-9A-Za-z.]*)\s*(;.*)?$")


def main() -> int:
    root = Path(__file__).resolve().parent.parent
    deps = tomllib.loads((root / "pyproject.toml").read_text())["project"]["dependencies"]
    for dep in deps:
        match = REQ.match(dep)
        if match is None:
            print(f"cannot read a lower bound from {dep!r}", file=sys.stderr)
            return 2
        name, version, marker = match.groups()
        name = name.split("[")[0]
        print(f"{name}=={version}.*{' ' + marker if marker else ''}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
