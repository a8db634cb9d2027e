"""The README's two set-up commands are the ones CI runs and they name real things."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def bash_blocks():
    text = (ROOT / "README.md").read_text()
    return [b.strip() for b in re.findall(r"```bash\n(.*?)```", text, re.S)]


def test_readme_opens_with_the_two_commands():
    blocks = bash_blocks()
    assert blocks[0] == "pip install . && frictionlaws fit --law thirion thesis-steel"
    assert blocks[1] == 'pip install ".[test]" && python -m pytest -n auto'


def test_ci_runs_the_readme_test_command_verbatim():
    ci = (ROOT / ".ci" / "run").read_text()
    assert bash_blocks()[1] in ci.splitlines()


def test_main_command_names_a_registered_law_and_a_packaged_dataset():
    from frictionlaws import get_law
    from frictionlaws.io import list_datasets

    assert get_law("thirion").id == "thirion"
    assert "thesis-steel" in {d["name"] for d in list_datasets()}
