"""Package metadata: classifiers, extras that match use, a README that renders on the index."""

from __future__ import annotations

import re
import sys
from pathlib import Path

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

ROOT = Path(__file__).resolve().parents[1]


def project() -> dict:
    return tomllib.loads((ROOT / "pyproject.toml").read_text())["project"]


def test_classifiers_name_the_python_versions_status_and_typing():
    classifiers = set(project()["classifiers"])
    for minor in (10, 11, 12, 13):
        assert f"Programming Language :: Python :: 3.{minor}" in classifiers
    assert "Typing :: Typed" in classifiers
    assert any(c.startswith("Development Status :: ") for c in classifiers)
    assert (ROOT / "frictionlaws" / "py.typed").exists()


def test_extras_match_use():
    meta = project()
    names = {re.split(r"[<>=;\[ ]", d, maxsplit=1)[0] for d in meta["dependencies"]}
    assert "mpmath" not in names and "shtab" in names  # completion from a plain install
    extras = meta["optional-dependencies"]
    assert any(d.startswith("xarray") for d in extras["xarray"])
    assert any(d.startswith("mpmath") for d in extras["validate"])


def test_the_readme_has_no_link_that_breaks_on_the_package_index():
    text = (ROOT / "README.md").read_text()
    targets = re.findall(r"\]\(([^)]+)\)", text) + re.findall(r'(?:src|href)="([^"]+)"', text)
    assert all(t.startswith(("https://", "http://", "#")) for t in targets), targets
