"""The OpenSees export read back without the writer's code: the ``frictionModel`` line's
numbers put into OpenSees' own formula (``mu = muFast - (muFast - muSlow)
exp(-transRate |v|)``, velocities in the model's units) against the law; the file read as
Tcl reads it (a comment ending in an odd run of backslashes continues onto the next line),
by a reader here and, where ``tclsh`` is installed, by Tcl itself."""

from __future__ import annotations

import re
import shlex
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from frictionlaws import get_law
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.fe_export import export
from frictionlaws.fe_export.opensees import tcl_comment

DECAY = {"mu_s": 0.9, "mu_d": 0.5, "v_c": 0.02, "delta": 1.0}
#: Metres per second in one velocity unit of each system (from the docs' table of units).
V_SCALE = {"SI": 1.0, "mm-N-s": 1e-3, "mm-kg-ms": 1.0}
GUIDE = Path(__file__).resolve().parents[2] / "docs" / "user-guide" / "export.rst"


def tcl_commands(text: str) -> list[list[str]]:
    """The commands of a Tcl script of plain words, as Tcl splits it: ``#`` comments
    (continued by an odd run of backslashes at a line's end) and blank lines left out."""
    commands, in_comment = [], False
    for line in text.split("\n"):
        continued = (len(line) - len(line.rstrip("\\"))) % 2 == 1
        if in_comment or line.lstrip().startswith("#"):
            in_comment = continued
        elif line.strip():
            assert not continued, line
            commands.append(line.split())
    return commands


def model(text: str) -> tuple[str, int, list[float]]:
    """The one ``frictionModel`` command: its type, tag and numbers."""
    (cmd,) = tcl_commands(text)
    assert cmd[0] == "frictionModel"
    return cmd[1], int(cmd[2]), [float(x) for x in cmd[3:]]


@pytest.mark.parametrize("units", list(V_SCALE))
def test_the_friction_model_is_the_law_in_the_models_velocity_unit(units: str) -> None:
    res = export("exponential-decay", DECAY, "opensees", units=units)
    kind, tag, (mu_slow, mu_fast, rate) = model(res.text)
    assert (kind, tag, res.exact, res.max_error) == ("VelDependent", 1, True, 0.0)
    v_model = np.concatenate([[0.0], np.geomspace(1e-6, 1e3, 200)]) / V_SCALE[units]
    opensees = mu_fast - (mu_fast - mu_slow) * np.exp(-rate * np.abs(v_model))
    law = get_law("exponential-decay").evaluate({"v": v_model * V_SCALE[units]}, DECAY)
    np.testing.assert_allclose(opensees, law, rtol=1e-13, atol=1e-15)


def test_a_constant_mu_is_a_coulomb_model_with_the_tag_given() -> None:
    res = export("coulomb", {"mu0": 0.35}, "opensees", options={"opensees_tag": 12})
    assert model(res.text) == ("Coulomb", 12, [0.35])


@pytest.mark.parametrize(("law", "values", "why"), [
    ("exponential-decay", {**DECAY, "delta": 2.0}, "delta = 2"),
    ("thirion", {"a": 0.3, "b": 3e-6}, "depends on p"),
    ("exponential-decay", {**DECAY, "mu_d": 0.0}, "positive friction coefficients"),
])
def test_a_law_opensees_cannot_take_exactly_is_refused(law, values, why) -> None:
    with pytest.raises(InputError, match=why):
        export(law, values, "opensees")


def test_the_cli_refuses_it_and_writes_nothing(tmp_path, capsys) -> None:
    out = tmp_path / "friction.tcl"
    assert main(["export", "--law", "exponential-decay", "--set",
                 "mu_s=0.9,mu_d=0.5,v_c=0.02,delta=2", "--format", "opensees",
                 "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "--fix delta=1" in err
    assert not out.exists()


@settings(max_examples=60, deadline=None)
@given(source=st.text(alphabet=st.sampled_from("\\{}[]$;\"# \nx\r\x0b\u2028é"),
                      max_size=60))
def test_no_source_text_adds_or_hides_a_command(source: str) -> None:
    """Text from a file or a user (here the source, also written in the header) can
    neither swallow the command into a comment (a trailing backslash) nor add one."""
    res = export("exponential-decay", DECAY, "opensees", source=source)
    assert model(res.text)[:2] == ("VelDependent", 1)


@given(text=st.text(alphabet=st.sampled_from("\\{}[]$; x"), max_size=30))
def test_a_comment_line_never_continues_onto_the_command(text: str) -> None:
    """Whatever a header line ends with, the command after it stays a command."""
    line = tcl_comment("# " + text)
    assert tcl_commands(f"{line}\nfrictionModel Coulomb 1 0.5\n") == [
        ["frictionModel", "Coulomb", "1", "0.5"]]
    assert "{" not in line and "}" not in line


TRICKY_SOURCE = "C:\\fits\\run{1}\\ [exec rm] $x ;\\"


@pytest.mark.skipif(shutil.which("tclsh") is None, reason="tclsh is not installed")
def test_tcl_itself_reads_one_command(tmp_path) -> None:
    """Tcl reads the file, and a hostile line right above the command, as we do."""
    text = export("exponential-decay", DECAY, "opensees", units="mm-N-s", source=TRICKY_SOURCE,
                  options={"opensees_tag": 7}).text
    assert text.count(TRICKY_SOURCE[:10]) == 1
    lines = text.splitlines()
    decks = {"file": text, "hostile last": "\n".join(
        [*lines[:-1], tcl_comment("# " + TRICKY_SOURCE), lines[-1]]) + "\n"}
    for name, deck_text in decks.items():
        deck = tmp_path / f"{name.replace(' ', '_')}.tcl"
        deck.write_text(deck_text)
        script = ("proc frictionModel {args} {puts \"CALL $args\"}\n"
                  f"source {{{deck}}}\n")
        proc = subprocess.run(["tclsh"], input=script, capture_output=True, text=True,
                              timeout=30)
        assert proc.returncode == 0, (name, proc.stderr)
        assert proc.stdout.splitlines() == ["CALL VelDependent 7 0.9 0.5 0.05"], name


def test_the_guides_command_runs_as_written(tmp_path, monkeypatch, capsys) -> None:
    section = GUIDE.read_text(encoding="utf-8").split(".. _adding-an-export-format:")[1]
    m = re.search(r"^   (frictionlaws export --law .*?)(?<!\\)\n", section, re.M | re.S)
    assert m, "the guide shows no export command"
    argv = shlex.split(m.group(1).replace("\\\n", " "))
    monkeypatch.chdir(tmp_path)
    assert main(argv[1:]) == 0
    out = tmp_path / argv[argv.index("-o") + 1]
    assert model(out.read_text()) == ("VelDependent", 7, [0.9, 0.5, 0.05])
    assert "transRate = 0.05 [1/(mm/s)]" in capsys.readouterr().out
