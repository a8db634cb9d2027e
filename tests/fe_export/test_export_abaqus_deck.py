"""Abaqus user-subroutine exports state the input-deck lines they need, and a deck built
from those instructions is complete (keywords, parameters and order as the manual has them;
see shared reference fe-formats.md: FRIC_COEF in Abaqus/Standard, VFRIC_COEF for general
contact only, VFRIC for contact pairs)."""

from __future__ import annotations

import re

import pytest

from frictionlaws import get_law, list_laws
from frictionlaws.base.errors import InputError
from frictionlaws.cli import main
from frictionlaws.fe_export import export
from frictionlaws.fe_export.fortran import input_deck, interaction_name

FORMATS = ("abaqus-fric-coef", "abaqus-vfric-coef", "abaqus-vfric")
USER = {"abaqus-fric-coef": "COEFFICIENT", "abaqus-vfric-coef": "COEFFICIENT",
        "abaqus-vfric": None}
EXPLICIT = {"abaqus-fric-coef": False, "abaqus-vfric-coef": True, "abaqus-vfric": True}
KEYWORD = re.compile(r"^\*[A-Z][A-Z ]*(, [A-Z][A-Z ]*(=[A-Za-z0-9_.+-]+)?)*$")


def _values(law):
    return law.resolve(preset=next(iter(law.presets))) if law.presets else law.resolve(
        law.defaults)


def instructions_from_header(text: str) -> list[str]:
    """The deck lines the exported file's header comment states, in order."""
    lines = text.splitlines()
    start = next(i for i, ln in enumerate(lines) if "in this order" in ln)
    out = []
    for ln in lines[start + 1:]:
        if not ln.startswith("C   "):
            break
        out.append(ln[4:])
    return out


def build_deck(instructions: list[str]) -> list[str]:
    """A minimal deck: surfaces, the instructions (placeholders filled), a step if none."""
    fill = {"<slave surface>": "SLAVE", "<master surface>": "MASTER", "<time period>": "1.0"}
    body = []
    for line in instructions:
        for k, v in fill.items():
            line = line.replace(k, v)
        body.append(line)
    deck = ["*HEADING", "frictionlaws deck check", "*SURFACE, NAME=SLAVE",
            "SLAVE_ELSET, S1", "*SURFACE, NAME=MASTER", "MASTER_ELSET, S2", *body]
    if "*STEP" not in body:
        deck += ["*STEP", "*STATIC", "*END STEP"]
    return deck


def _params(line: str) -> dict[str, str | None]:
    out: dict[str, str | None] = {}
    for part in line.split(",")[1:]:
        key, _, value = part.strip().partition("=")
        out[key] = value or None
    return out


def check_deck(deck: list[str], fmt: str, routine: str) -> None:
    """Raise AssertionError unless ``deck`` makes Abaqus call the routine of ``fmt``."""
    assert not any("<" in ln or ">" in ln for ln in deck), "unfilled placeholder"
    keywords = [(i, ln) for i, ln in enumerate(deck) if ln.startswith("*")
                and not ln.startswith("**")]
    for _, ln in keywords:
        assert KEYWORD.match(ln), f"not keyword syntax: {ln!r}"
    names = [ln.split(",")[0] for _, ln in keywords]
    assert "*SURFACE INTERACTION" in names and "*FRICTION" in names
    k_si = names.index("*SURFACE INTERACTION")
    # *FRICTION is a suboption of the interaction: the very next keyword
    assert names[k_si + 1] == "*FRICTION", names
    si_line, fr_line = keywords[k_si][1], keywords[k_si + 1][1]
    interaction = _params(si_line).get("NAME")
    assert interaction, "the surface interaction has no NAME"
    fr = _params(fr_line)
    assert "USER" in fr, "*FRICTION without USER: Abaqus would not call the routine"
    assert fr["USER"] == USER[fmt], (fr_line, fmt)
    assert fr.get("PROPERTIES") == "0"
    assert ("DEPVAR" in fr) == (fmt == "abaqus-vfric")
    # PROPERTIES=0: no data lines after *FRICTION
    i_fr = keywords[k_si + 1][0]
    assert deck[i_fr + 1].startswith("*")
    # the interaction is assigned to the contact, and in the right place
    step = names.index("*STEP")
    end = names.index("*END STEP")
    assert k_si < step, "*SURFACE INTERACTION is model data"
    if fmt == "abaqus-vfric-coef":
        c = names.index("*CONTACT")  # VFRIC_COEF: general contact only
        assert names[c + 1:c + 3] == ["*CONTACT INCLUSIONS", "*CONTACT PROPERTY ASSIGNMENT"]
        i_cpa = keywords[c + 2][0]
        assert [x.strip() for x in deck[i_cpa + 1].split(",")][2] == interaction
        assert "*CONTACT PAIR" not in names
    else:  # FRIC_COEF here and VFRIC: a contact pair naming the interaction
        c = names.index("*CONTACT PAIR")
        assert _params(keywords[c][1]).get("INTERACTION") == interaction
        assert deck[keywords[c][0] + 1] == "SLAVE, MASTER"
    if EXPLICIT[fmt]:
        assert names[step + 1] == "*DYNAMIC" and "EXPLICIT" in _params(keywords[step + 1][1])
        assert step < c < end, "Abaqus/Explicit contact is step data"
    else:
        assert c < step
    assert routine


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("law_id", ["thirion", "pacejka", "exponential-decay"])
def test_deck_from_the_exports_own_instructions_is_complete(fmt, law_id):
    law = get_law(law_id)
    res = export(law, _values(law), fmt)
    stated = instructions_from_header(res.text)
    assert stated == res.details["input_deck"] == input_deck(law, fmt)[0]
    header = " ".join(" ".join(ln[2:] for ln in res.text.splitlines()
                               if ln.startswith("C ")).split())
    assert "without *FRICTION, USER=... it silently uses other friction" in header
    check_deck(build_deck(stated), fmt, res.details["routine"])
    # PROPERTIES=0 and DEPVAR=0 are right: the routine never reads props or statev
    code = [ln.lower() for ln in res.text.splitlines() if not ln.startswith("C")]
    assert sum("props(" in ln for ln in code) == 1  # its declaration only
    assert sum("statev(" in ln for ln in code) == (1 if fmt == "abaqus-vfric" else 0)
    assert f"NAME={interaction_name(law)}" in stated[0]


@pytest.mark.parametrize("fmt", FORMATS)
def test_the_check_can_fail(fmt):
    law = get_law("thirion")
    good = build_deck(input_deck(law, fmt)[0])
    check_deck(good, fmt, "x")
    no_user = [ln.replace(", USER=COEFFICIENT", "").replace(", USER,", ",") for ln in good]
    swapped = list(good)
    i = next(i for i, ln in enumerate(good) if ln.startswith("*FRICTION"))
    swapped[i - 1], swapped[i] = swapped[i], swapped[i - 1]
    renamed = [ln.replace("INTERACTION=FRL_", "INTERACTION=OTHER_") for ln in good]
    renamed = [ln.replace(" ,  , FRL_", " ,  , OTHER_") for ln in renamed]
    with_data = good[:i + 1] + ["0.3"] + good[i + 1:]
    other = "abaqus-vfric" if fmt != "abaqus-vfric" else "abaqus-vfric-coef"
    for bad in (no_user, swapped, renamed, with_data):
        with pytest.raises(AssertionError):
            check_deck(bad, fmt, "x")
    with pytest.raises(AssertionError):
        check_deck(good, other, "x")


def test_notes_name_temperature_and_field_variables():
    t_law = next((lw for lw in list_laws() if "T" in lw.variables), None)
    if t_law is not None:
        _, notes = input_deck(t_law, "abaqus-fric-coef")
        assert any("TYPE=TEMPERATURE" in n for n in notes)
    _, notes = input_deck(get_law("pacejka"), "abaqus-vfric-coef")
    assert any("field variable 1 = s" in n and "VARIABLE=1" in n for n in notes)
    _, notes = input_deck(get_law("thirion"), "abaqus-fric-coef")
    assert any("general contact" in n for n in notes)
    with pytest.raises(InputError, match="unknown Fortran format"):
        input_deck(get_law("thirion"), "abaqus")


@pytest.mark.parametrize("fmt", FORMATS)
def test_cli_prints_the_deck_lines(fmt, tmp_path, capsys):
    out = tmp_path / "routine.f"
    code = main(["export", "--law", "thirion", "--set", "a=0.3,b=3e-6", "--format", fmt,
                 "-o", str(out)])
    printed = capsys.readouterr().out
    assert code == 0
    lines = [ln.strip() for ln in printed.splitlines()]
    deck = input_deck(get_law("thirion"), fmt)[0]
    # every deck line is printed, in order
    pos = [lines.index(d.strip()) for d in deck]
    assert pos == sorted(pos)
    assert any("*FRICTION, USER" in ln for ln in lines)
