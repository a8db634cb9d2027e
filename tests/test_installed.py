"""The README's test command tests the installed package, not the source tree."""

from __future__ import annotations

import json
from importlib import metadata
from pathlib import Path

import frictionlaws

ROOT = Path(__file__).resolve().parents[1]


def _editable() -> bool:
    try:
        text = metadata.distribution("frictionlaws").read_text("direct_url.json")
    except metadata.PackageNotFoundError:
        return False
    return bool(text) and bool(json.loads(text).get("dir_info", {}).get("editable"))


def test_frictionlaws_is_imported_from_its_installation():
    dist = metadata.distribution("frictionlaws")
    assert dist.version == frictionlaws.__version__
    where = Path(frictionlaws.__file__).resolve()
    if _editable():
        assert where.is_relative_to(ROOT)  # a developer's `pip install -e`
    else:
        assert not where.is_relative_to(ROOT), (
            f"tests imported the source tree ({where}), not the installed package")
        files = {str(f) for f in dist.files or ()}
        assert "frictionlaws/__init__.py" in files


def test_packaged_data_come_with_the_installation():
    from frictionlaws.io import datasets_dir

    assert (Path(str(datasets_dir())) / "thesis-steel.csv").is_file()
    if not _editable():
        assert not Path(str(datasets_dir())).resolve().is_relative_to(ROOT)
