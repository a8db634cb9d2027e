"""The README's commands: the set-up ones CI runs, and the first look, run in a fresh folder."""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

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


# ------------------------------------------------------------- the first look, run


def first_look_commands(text: str | None = None) -> list[str]:
    """The commands of the README's "A first look" block, continuation lines joined."""
    text = text if text is not None else (ROOT / "README.md").read_text()
    section = text.split("## A first look", 1)[1]
    block = re.search(r"```bash\n(.*?)```", section, re.S)
    assert block, "no bash block under 'A first look'"
    return [c.strip() for c in block.group(1).replace("\\\n", " ").splitlines() if c.strip()]


def needs_cluster(command: str) -> bool:
    """A command that needs a running Dask scheduler (marked so in the README)."""
    return "--scheduler" in command


def run_shell(command: str, folder: Path) -> subprocess.CompletedProcess[str]:
    """Run one README command with bash in ``folder``, the installed CLI first on PATH."""
    env = dict(os.environ, HOME=str(folder), MPLBACKEND="Agg",
               PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")
    return subprocess.run(["bash", "-c", command], cwd=folder, env=env, capture_output=True,
                          text=True, timeout=600)


def test_first_look_starts_with_the_example_files_and_marks_the_cluster_line():
    commands = first_look_commands()
    assert commands[0].startswith("frictionlaws examples .")
    cluster = [c for c in commands if needs_cluster(c)]
    assert len(cluster) == 1 and "needs a running Dask cluster" in cluster[0]


@pytest.mark.slow
def test_every_first_look_command_runs_in_a_fresh_folder(tmp_path):
    ran = []
    for command in first_look_commands():
        if needs_cluster(command):
            continue
        res = run_shell(command, tmp_path)
        assert res.returncode == 0, (command, res.stdout[-2000:], res.stderr[-2000:])
        ran.append(command)
    assert len(ran) >= 20
    completion = tmp_path / ".local/share/bash-completion/completions/frictionlaws"
    assert "frictionlaws" in completion.read_text()
    assert (tmp_path / "tyre.tir").stat().st_size > 0 and (tmp_path / "deck_steel.inp").exists()


@pytest.mark.slow
def test_the_python_block_runs_after_the_example_files(tmp_path):
    text = (ROOT / "README.md").read_text()
    code = re.search(r"```python\n(.*?)```", text, re.S)
    assert code
    assert run_shell("frictionlaws examples .", tmp_path).returncode == 0
    res = subprocess.run([sys.executable, "-c", code.group(1)], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600, env=dict(os.environ, MPLBACKEND="Agg"))
    assert res.returncode == 0, res.stderr[-3000:]
    assert "thirion" in res.stdout.lower()


def rst_blocks(path: Path, language: str) -> list[str]:
    """The ``.. code-block:: LANGUAGE`` bodies of an rst page, dedented."""
    import textwrap

    text = path.read_text()
    pattern = rf"\.\. code-block:: {language}\n\n((?:(?:   .*)?\n)+)"
    return [textwrap.dedent(b) for b in re.findall(pattern, text)]


@pytest.mark.slow
def test_getting_started_commands_run_in_a_fresh_folder(tmp_path):
    page = ROOT / "docs" / "getting-started.rst"
    commands = [c.strip() for b in rst_blocks(page, "bash") for c in b.splitlines() if c.strip()]
    assert commands[0].startswith("frictionlaws examples .")
    for command in commands:
        res = run_shell(command, tmp_path)
        assert res.returncode == 0, (command, res.stdout[-2000:], res.stderr[-2000:])
    (code,) = rst_blocks(page, "python")
    res = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True,
                         text=True, timeout=600, env=dict(os.environ, MPLBACKEND="Agg"))
    assert res.returncode == 0, res.stderr[-3000:]
