"""The scaling guide's commands and Python blocks run as written, in a folder where
``frictionlaws examples .`` wrote the example files (the guide says so).

The commands that need a Dask cluster at an address of the reader's (``--scheduler
tcp://HOST:8786``, ``dask scheduler``, ``dask worker``) and the install line are left
out; the guide's ``LocalCluster`` block starts its own cluster and runs (slow).
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "scaling.rst"
#: Lines that need what a test machine has not: a cluster at the reader's address, pip.
NEEDS_MORE = ("--scheduler tcp://HOST", "dask scheduler", "dask worker", "pip install",
              "export DASK_")


def blocks(language: str) -> list[str]:
    """The guide's code blocks of ``language``, dedented, continuation lines joined."""
    text = GUIDE.read_text(encoding="utf-8")
    found = re.findall(rf"\.\. code-block:: {language}\n\n((?:   .*\n|\n)+)", text)
    return [re.sub(r"^   ", "", b, flags=re.M).replace("\\\n", " ").strip() for b in found]


def commands() -> list[str]:
    lines = [ln for b in blocks("bash") for ln in b.splitlines() if ln.strip()]
    return [ln for ln in lines if not any(m in ln for m in NEEDS_MORE)]


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    where = tmp_path_factory.mktemp("guide")
    run("frictionlaws examples .", where)
    return where


def run(command: str, where: Path) -> subprocess.CompletedProcess[str]:
    env = dict(os.environ, MPLBACKEND="Agg",
               PATH=f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}")
    res = subprocess.run(["bash", "-c", command], cwd=where, env=env, capture_output=True,
                         text=True, timeout=300)
    assert res.returncode == 0, (command, res.stdout[-2000:], res.stderr[-2000:])
    return res


def test_the_guide_has_the_commands_it_is_tested_on():
    assert len(commands()) >= 6 and len(blocks("python")) >= 3
    assert any("--jobs 2" in c for c in commands())


@pytest.mark.parametrize("command", commands())
def test_each_command_of_the_guide_runs_as_written(command, folder):
    run(command, folder)


def python_blocks(cluster: bool) -> list[str]:
    """The Python blocks that start a Dask cluster (``cluster``), or the others."""
    return [b for b in blocks("python") if ("LocalCluster" in b) == cluster]


def run_script(code: str, where: Path) -> subprocess.CompletedProcess[str]:
    """Run a Python block as a script file (as a reader saves it)."""
    script = where / "guide_block.py"
    script.write_text(code + "\n", encoding="utf-8")
    return run(f"{sys.executable} guide_block.py", where)


@pytest.mark.parametrize("code", python_blocks(cluster=False))
def test_each_python_block_of_the_guide_runs_as_written(code, folder):
    run_script(code, folder)


@pytest.mark.slow
@pytest.mark.parametrize("code", python_blocks(cluster=True))
def test_the_guide_local_cluster_block_runs_as_written(code, folder):
    pytest.importorskip("dask.distributed")
    res = run_script(code, folder)
    assert res.stdout.count("thirion: R^2 = ") == 4, res.stdout  # data/ holds 4 files
