"""Every documented command that writes a Fortran file writes one gfortran compiles under its name.

The commands are read from README.md and docs/**/*.rst (shell blocks, continuation
lines joined), run through the CLI's ``main`` in a scratch directory, and the file
each writes is compiled by gfortran as its name says (a ``.f`` file as fixed form, a
``.f90`` one as free form) against Abaqus-like include files.  A Fortran export
under a free-form name is refused before any work.
"""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
from pathlib import Path

import pytest

from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.fe_export.fortran import FORTRAN_FORMATS

ROOT = Path(__file__).resolve().parents[2]
INCLUDE = ROOT / "tests" / "fe_export" / "fortran" / "include"
GFORTRAN = shutil.which("gfortran")


def _shell_lines(text: str) -> list[str]:
    """Shell command lines of Markdown ```bash blocks and reST code blocks, joined."""
    blocks = re.findall(r"```(?:bash|sh|console)?\n(.*?)```", text, re.S)
    blocks += [b for b in re.findall(
        r"\.\. code-block:: (?:bash|console|sh)\s*\n\n((?:[ \t]+.*\n|\n)+)", text)]
    lines: list[str] = []
    for block in blocks:
        joined = re.sub(r"\\\n\s*", " ", block)
        lines += [ln.strip().removeprefix("$ ") for ln in joined.splitlines()]
    return lines


def fortran_commands() -> list[tuple[str, list[str]]]:
    """(source file, argv) of every documented ``frictionlaws export`` to a Fortran format."""
    found = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").rglob("*.rst"))]:
        for line in _shell_lines(path.read_text(encoding="utf-8")):
            if not line.startswith("frictionlaws export"):
                continue
            argv = shlex.split(line, comments=True)[1:]
            fmt = argv[argv.index("--format") + 1] if "--format" in argv else None
            if fmt in FORTRAN_FORMATS:
                found.append((str(path.relative_to(ROOT)), argv))
    return found


COMMANDS = fortran_commands()


def test_the_docs_hold_fortran_export_commands():
    # the extraction must find the README's example at least (or this file tests nothing)
    assert any(src == "README.md" for src, _ in COMMANDS), COMMANDS


@pytest.mark.skipif(GFORTRAN is None, reason="gfortran not installed (apt-get install gfortran)")
@pytest.mark.parametrize("source,argv", COMMANDS,
                         ids=[f"{s}:{a[a.index('-o') + 1]}" for s, a in COMMANDS])
def test_documented_fortran_export_compiles_under_its_name(source, argv, tmp_path,
                                                           monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(argv) == 0, f"{source}: {shlex.join(argv)}"
    written = tmp_path / argv[argv.index("-o") + 1]
    out = subprocess.run([GFORTRAN, "-c", f"-I{INCLUDE}", written.name, "-o", "routine.o"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert out.returncode == 0, f"{source}: {written.name}:\n{out.stderr}"


@pytest.mark.parametrize("name", ["fric_coef.f90", "r.F95", "sub.f03", "x.f08"])
def test_fortran_export_under_a_free_form_name_is_refused(name, tmp_path, capsys):
    out = tmp_path / name
    code = main(["export", "--law", "exponential-decay", "--preset", "rubber-steel",
                 "--format", "abaqus-fric-coef", "-o", str(out)])
    err = capsys.readouterr().err
    assert code == 2 and "fixed-form" in err and ".for" in err, err
    assert not out.exists()
    from frictionlaws.fe_export import export

    with pytest.raises(InputError, match="fixed-form"):
        export("exponential-decay", preset="rubber-steel", format="abaqus-vfric", path=out)
    assert not out.exists()


@pytest.mark.skipif(GFORTRAN is None, reason="gfortran not installed (apt-get install gfortran)")
@pytest.mark.parametrize("name", ["fric.f", "fric.for"])
def test_fortran_export_under_a_fixed_form_name_compiles(name, tmp_path):
    from frictionlaws.fe_export import export

    export("exponential-decay", preset="rubber-steel", format="abaqus-fric-coef",
           path=tmp_path / name)
    out = subprocess.run([GFORTRAN, "-c", f"-I{INCLUDE}", name, "-o", "routine.o"],
                         capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert out.returncode == 0, out.stderr
