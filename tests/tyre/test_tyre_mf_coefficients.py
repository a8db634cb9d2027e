"""The declarations of the Magic Formula coefficients, and everything that reads them."""

from __future__ import annotations

import ast
import importlib
import inspect
import json
import math
import re
import warnings
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from frictionlaws.base.errors import ExtrapolationWarning, InputError
from frictionlaws.tyre import fit_mf
from frictionlaws.tyre.mf import coefficients as mf_coefficients
from frictionlaws.tyre.mf import declarations, outputs
from frictionlaws.tyre.mf.coefficients import default, fit_bounds
from frictionlaws.tyre.mf.declarations import DECLARED
from frictionlaws.tyre.mf.fit import pure, stages
from frictionlaws.tyre.mf.model import MagicFormula
from frictionlaws.tyre.mf.property_file import DIMENSIONAL, MF_KEYS
from frictionlaws.tyre.mf.tir import read_property_file, read_tir

#: The modules of the equations (what the evaluator reads is read from their code).
EQUATION_MODULES = [importlib.import_module(f"frictionlaws.tyre.mf.{m}") for m in (
    "parameters", "equations", "moments", "vertical", "conditions", "outputs", "model")]
EXAMPLES = Path(__file__).resolve().parents[2] / "datasets" / "mf-examples"
FILES = sorted(EXAMPLES.glob("MagicFormula*_Parameters.json"))
VERSIONS = ("5.2", "6.1", "6.2")


def _evaluator_reads() -> dict[str, set[object]]:
    """Name -> the literal defaults the evaluator's code passes with it (empty: none).

    Read from the code: ``c.PCX1`` (the checked view, ``p.c`` / ``self.c`` too) for
    coefficients, ``s.get("Q_RE0", 1.0)``, ``structure.get(...)``, ``p.need("LONGVL")``,
    ``s["LATERAL_STIFFNESS"]`` and ``"LATERAL_STIFFNESS" in s`` for the file's structure.
    """
    reads: dict[str, set[object]] = {}
    for module in EQUATION_MODULES:
        for node in ast.walk(ast.parse(inspect.getsource(module))):
            name, dflt = None, None
            if (isinstance(node, ast.Attribute) and re.fullmatch(r"[A-Z][A-Z0-9_]+", node.attr)
                    and ast.unparse(node.value) in ("c", "p.c", "self.c", "mf.c")):
                name = node.attr
            elif isinstance(node, ast.Call):
                f = node.func
                args = node.args
                if not (isinstance(f, ast.Attribute) and f.attr in ("need", "get")
                        and ast.unparse(f.value) in ("s", "p", "self", "mf", "p.structure",
                                                     "mf.structure", "self.structure")):
                    continue
                if args and isinstance(args[0], ast.Constant) and isinstance(args[0].value, str):
                    name = args[0].value
                    if len(args) > 1 and isinstance(args[1], ast.Constant):
                        dflt = args[1].value
            elif isinstance(node, ast.Subscript) and ast.unparse(node.value) == "s":
                if isinstance(node.slice, ast.Constant):
                    name = node.slice.value
            elif (isinstance(node, ast.Compare) and isinstance(node.ops[0], ast.In)
                  and isinstance(node.left, ast.Constant)
                  and ast.unparse(node.comparators[0]) in ("s", "mf.structure", "p.structure",
                                                           "self.structure")):
                name = node.left.value
            if isinstance(name, str) and re.fullmatch(r"[A-Z][A-Z0-9_]+", name):
                reads.setdefault(name, set()).update({dflt} if dflt is not None else set())
    return reads


def _fit_mf_names() -> dict[str, set[str]]:
    """Name -> the versions for which fit-mf fits it (pure, combined, M_z stages)."""
    names: dict[str, set[str]] = {}
    for v in VERSIONS:
        groups = (pure.X_COEFFICIENTS[v] + pure.Y_COEFFICIENTS[v]
                  + stages.combined_names("x", v) + stages.combined_names("y", v)
                  + sum(stages.mz_names(v), []))
        for k in groups:
            names.setdefault(k, set()).add(v)
    return names


# ---------------------------------------------------------------- completeness


def test_every_name_the_evaluator_reads_is_declared_with_the_default_it_uses():
    reads = _evaluator_reads()
    assert {"PCX1", "PKY4", "QSX14", "RVY6", "LONGVL", "Q_RE0", "LATERAL_STIFFNESS",
            "PTY2"} <= set(reads)  # the scanner sees every kind of read
    assert sorted(set(reads) - set(DECLARED)) == []
    for name, literals in reads.items():
        c = DECLARED[name]
        assert c.evaluated, f"{name} is read by the evaluator but declared not evaluated"
        for value in literals:  # a default written in the code is the declared one
            assert c.default is not None and float(value) == c.default, (name, value)


def test_every_name_fit_mf_fits_is_declared_in_its_section_and_versions():
    for name, versions in _fit_mf_names().items():
        c = DECLARED[name]
        assert c.evaluated and set(versions) <= set(c.versions), (name, versions, c.versions)
        assert stages.section_of(name) == c.section, name
        assert c.stage is not None and set(c.needs) <= set(declarations.NEEDS), name
    for c in DECLARED.values():  # what a coefficient needs matters only if it is fitted
        assert c.stage is not None or not c.needs, c.name
    # the stages hold an undetermined coefficient at the template's value or 0: declared 0
    pure_names = set(pure.X_COEFFICIENTS["6.1"] + pure.Y_COEFFICIENTS["6.1"])
    for name in set(_fit_mf_names()) - pure_names:
        assert default(name) == 0.0, name


def test_the_reader_knows_exactly_the_declared_names():
    assert MF_KEYS == mf_coefficients.section_keys()
    assert sum(len(v) for v in MF_KEYS.values()) > 180


def test_every_declared_name_is_in_an_example_file_or_optional():
    seen: dict[str, set[str]] = {}
    for f in FILES:
        mf = MagicFormula.from_file(f)
        for entries in read_property_file(f).sections.values():
            for key in entries:
                seen.setdefault(key, set()).add(mf.version)
    for c in DECLARED.values():
        if c.required:  # in every example of its versions
            assert set(c.versions) <= seen.get(c.name, set()), c.name
        elif c.name not in seen:  # documented as optional: what its absence means
            assert c.default is not None or c.section in declarations.RANGE_SECTIONS, c.name
    assert {"LFZ0", "LMUV", "Q_A1", "IP"} <= set(DECLARED) - set(seen)


def test_declarations_are_whole_and_consistent():
    angles = {"", "rad", "1/rad", "1/rad**2"}
    for c in DECLARED.values():  # every dimension is converted by the reader
        assert c.unit in angles or c.unit in TO_MM_KN, (c.name, c.unit)
        assert ((c.section, c.name) in DIMENSIONAL) == (c.unit in TO_MM_KN), c.name
    assert set(DIMENSIONAL) <= {(c.section, c.name) for c in DECLARED.values()}
    from frictionlaws.base.units import unit_registry

    ureg = unit_registry()
    for c in DECLARED.values():
        assert c.meaning and c.section in declarations.SECTIONS and c.versions, c.name
        assert set(c.versions) <= set(VERSIONS), c.name
        ureg.Unit(c.unit)  # pint reads it
        if c.default is not None:
            assert c.allows(c.default), c.name
        if c.fit is not None:  # the fit searches only possible values
            assert c.allows(c.fit[0]) and c.allows(c.fit[1]), c.name
        if c.alias_of is not None:
            assert DECLARED[c.alias_of].default == c.default, c.name
        elif c.section == "SCALING_COEFFICIENTS":
            assert c.default == 1.0 and not c.allows(-0.1), c.name
        elif c.section in declarations.COEFFICIENT_SECTIONS and c.name != "PKY4":
            assert c.default == (None if c.required else 0.0), c.name
    assert default("PKY4") == 2.0 and DECLARED["FNOMIN"].required
    assert not DECLARED["FNOMIN"].allows(0.0) and not DECLARED["PCX1"].allows(0.0)
    assert not DECLARED["ALPMAX"].allows(2.0) and DECLARED["ALPMAX"].allows(1.5)


# --------------------------------------------------------------------- reading


@pytest.mark.parametrize("path", FILES + sorted(EXAMPLES.glob("*.converted.tir")),
                         ids=lambda p: p.name)
def test_the_example_files_pass_the_bounds(path: Path) -> None:
    pf = read_property_file(path)
    assert pf.check_bounds() == []  # nothing impossible, nothing even unusual
    for sec, entries in pf.sections.items():
        for key, value in entries.items():
            if key in DECLARED and not isinstance(value, str):
                assert DECLARED[key].allows(pf.si(sec, key)), key


def _tir_with(changes: dict[str, str]) -> str:
    text = (EXAMPLES / "MagicFormula61_Parameters.converted.tir").read_text()
    return "\n".join(f"{ln.split('=')[0].strip()} = {changes[ln.split('=')[0].strip()]}"
                     if ln.split("=")[0].strip() in changes else ln
                     for ln in text.splitlines()) + "\n"


@pytest.mark.parametrize("key,value,section,message", [
    ("FNOMIN", "-6752", "VERTICAL", r"FNOMIN = -6752 is impossible: expected 10 <= value"),
    ("FNOMIN", "6.752", "VERTICAL", r"FNOMIN = 6\.752 is impossible: expected 10 <= value <= "
                                    r"2e\+06 N .*; check \[UNITS\]"),
    ("FNOMIN", "3e6", "VERTICAL", r"FNOMIN = 3e\+06 is impossible"),
    ("UNLOADED_RADIUS", "394.3", "DIMENSION", r"UNLOADED_RADIUS = 394\.3 is impossible: "
                                              r"expected 0\.05 <= value <= 3 m .*\[UNITS\]"),
    ("WIDTH", "255", "DIMENSION", r"WIDTH = 255 is impossible"),
    ("INFLPRES", "2.6", "OPERATING_CONDITIONS", r"INFLPRES = 2\.6 is impossible: expected "
                                                r"1e\+04 <= value <= 5e\+06 Pa"),
    ("NOMPRES", "2.6e8", "OPERATING_CONDITIONS", r"NOMPRES = 2\.6e\+08 is impossible"),
    ("PRESMAX", "4", "INFLATION_PRESSURE_RANGE", r"PRESMAX = 4 is impossible"),
    ("VERTICAL_STIFFNESS", "314.9", "VERTICAL", r"VERTICAL_STIFFNESS = 314\.9 is impossible"),
    ("LONGVL", "1000", "MODEL", r"LONGVL = 1000 is impossible: expected 0\.01 <= value <= 200"),
    ("PKX1", "1e12", "LONGITUDINAL_COEFFICIENTS", r"PKX1 = 1e\+12 is impossible: expected "
                                                  r"0 < value <= 1e\+06"),
    ("PKX1", "1e300", "LONGITUDINAL_COEFFICIENTS", r"PKX1 = 1e\+300 is impossible"),
    ("PDX2", "-2e6", "LONGITUDINAL_COEFFICIENTS", r"PDX2 = -2e\+06 is impossible: expected "
                                                  r"-1e\+06 <= value <= 1e\+06"),
    ("LKX", "5e6", "SCALING_COEFFICIENTS", r"LKX = 5e\+06 is impossible"),
    ("FNOMIN", "0", "VERTICAL", r"FNOMIN = 0 is impossible"),
    ("PCX1", "nan", "LONGITUDINAL_COEFFICIENTS", r"PCX1 = nan is not a number a property file"),
    ("ALPMAX", "15", "SLIP_ANGLE_RANGE", r"ALPMAX = 15 is impossible: expected -1\.571 <= "
                                         r"value <= 1\.571 rad .*; degrees where the file's "
                                         "angles are radians\\?"),
    ("CAMMIN", "-30", "INCLINATION_ANGLE_RANGE", r"CAMMIN = -30 is impossible"),
    ("PCX1", "-1.5", "LONGITUDINAL_COEFFICIENTS",
     r"PCX1 = -1\.5 is impossible: expected 0 < value"),
    ("LKY", "-1", "SCALING_COEFFICIENTS", r"LKY = -1 is impossible: expected 0 <= value"),
    ("PKY2", "0", "LATERAL_COEFFICIENTS", r"PKY2 = 0 is impossible"),
    ("PDY1", "1e6", "LATERAL_COEFFICIENTS", r"PDY1 = 1e\+06 is impossible"),
    ("VERTICAL_STIFFNESS", "-3e5", "VERTICAL", r"VERTICAL_STIFFNESS = -300000 is impossible"),
    ("NOMPRES", "0", "OPERATING_CONDITIONS", r"NOMPRES = 0 is impossible"),
])
def test_a_hostile_tir_is_refused_naming_file_section_and_name(
        tmp_path: Path, key: str, value: str, section: str, message: str) -> None:
    from frictionlaws.cli import main

    path = tmp_path / "hostile.tir"
    path.write_text(_tir_with({key: value}))
    with pytest.raises(InputError) as err:
        MagicFormula.from_file(path)
    text = str(err.value)
    assert "hostile.tir" in text and re.search(r"row \d+", text), text
    assert f"[{section}] " in text and re.search(message, text), text
    assert main(["tyre", "mf", str(path)]) == 2


def test_a_hostile_json_file_and_units_are_judged_in_si(tmp_path: Path) -> None:
    doc = json.loads(FILES[1].read_text())
    doc["VERTICAL"]["FNOMIN"] = -1.0
    (tmp_path / "neg.json").write_text(json.dumps(doc))
    with pytest.raises(InputError, match=r"neg\.json.*\[VERTICAL\] FNOMIN = -1 is impossible"):
        MagicFormula.from_file(tmp_path / "neg.json")
    # FNOMIN in kN is judged in newtons (and passes); a NaN in JSON is not even read
    in_kn = {"FORCE": "'kN'", "FNOMIN": "6.752", "VERTICAL_STIFFNESS": "314.93",
             "INFLPRES": "260", "NOMPRES": "260", "PRESMIN": "200", "PRESMAX": "400"}
    mf = MagicFormula.from_property_file(read_tir(_tir_with(in_kn), source="kn.tir"))
    assert mf.fnomin == pytest.approx(6752.0)
    with pytest.raises(InputError, match=r"\[VERTICAL\] FNOMIN = -6\.752 \(-6752 SI\) is "
                                         "impossible"):
        MagicFormula.from_property_file(read_tir(_tir_with({**in_kn, "FNOMIN": "-6.752"}),
                                                 source="x"))
    with pytest.raises(InputError, match="NaN is not a JSON number"):
        read_property_file(_write(tmp_path / "nan.json",
                                  FILES[1].read_text().replace('"PCX1": 1.5482',
                                                               '"PCX1": NaN')))


def _write(path: Path, text: str) -> Path:
    path.write_text(text)
    return path


def test_a_coefficient_built_in_code_is_checked_as_one_read_from_a_file() -> None:
    mf = MagicFormula.from_file(FILES[1])
    with pytest.raises(InputError, match=r"\[LONGITUDINAL_COEFFICIENTS\] PCX1 = 0 is "
                                         "impossible"):
        MagicFormula({**mf.coefficients, "PCX1": 0.0}, fnomin=mf.fnomin, version="6.1")
    with pytest.raises(InputError, match=r"\[VERTICAL\] FNOMIN = -1 is impossible"):
        MagicFormula(mf.coefficients, fnomin=-1.0, version="6.1")
    with pytest.raises(InputError, match="coefficient PDX2 is not finite"):
        MagicFormula({**mf.coefficients, "PDX2": math.nan}, fnomin=mf.fnomin)


def test_unusual_values_are_noted_and_unknown_names_kept_with_a_note(tmp_path: Path) -> None:
    text = _tir_with({"PCX1": "3.5"}).replace("[LATERAL_COEFFICIENTS]",
                                               "[LATERAL_COEFFICIENTS]\nPXY99 = 1.5")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        mf = MagicFormula.from_property_file(read_tir(text, source="odd.tir"))
    assert any("PCX1 = 3.5 lies outside 0.3 .. 3" in n for n in mf.notes), mf.notes
    assert any("unknown keys kept" in n and "PXY99" in n for n in mf.notes), mf.notes
    assert mf.coefficients["PXY99"] == 1.5


def test_absent_coefficients_take_their_declared_default() -> None:
    mf = MagicFormula.from_file(FILES[1])
    kept = {k: v for k, v in mf.coefficients.items() if k not in ("PKY4", "LKY", "QSX5")}
    bare = MagicFormula(kept, fnomin=mf.fnomin, version="6.1", structure=mf.structure)
    full = MagicFormula({**kept, "PKY4": default("PKY4"), "LKY": default("LKY"),
                         "QSX5": default("QSX5")}, fnomin=mf.fnomin, version="6.1",
                        structure=mf.structure)
    alpha = np.radians([-6.0, 2.0, 9.0])
    assert np.array_equal(bare.fy0(alpha, 5000.0), full.fy0(alpha, 5000.0))
    assert np.array_equal(bare.steady_state(0.02, alpha, 5000.0)["Mx"],
                          full.steady_state(0.02, alpha, 5000.0)["Mx"])


def test_lfz0_is_read_as_lfzo_and_two_different_spellings_are_refused() -> None:
    mf = MagicFormula.from_file(FILES[1])
    base = {k: v for k, v in mf.coefficients.items() if k != "LFZO"}
    spelt = MagicFormula({**base, "LFZ0": 0.9}, fnomin=mf.fnomin, version="6.1")
    assert spelt.fz0 == pytest.approx(0.9 * mf.fnomin)
    assert any("LFZ0 read as LFZO" in n for n in spelt.notes)
    with pytest.raises(InputError, match="two spellings"):
        MagicFormula({**base, "LFZ0": 0.9, "LFZO": 1.0}, fnomin=mf.fnomin)


# ----------------------------------------------------------------------- fit-mf


@pytest.mark.slow
def test_fit_mf_takes_its_bounds_from_the_declarations(monkeypatch) -> None:
    """fit-mf's bounds are the declared ones; narrowing a declaration narrows the fit."""
    bounds = fit_bounds()
    assert bounds["PCX1"] == DECLARED["PCX1"].fit == (0.3, 3.0)
    assert bounds["PKY4"] == (1.0, 4.0) and bounds["PEY1"] == (-50.0, 1.0)
    lo, hi = bounds["PDX1"]
    assert 0.0 < lo < 1e-6 and hi == DECLARED["PDX1"].bounds[1]  # open at 0
    from frictionlaws.tyre.synthetic_rig import moved_tyre, rig_data

    truth = moved_tyre("MagicFormula61")
    data = rig_data(truth, n=15, loads=(0.7, 1.0, 1.3), pressures=(1.0,), cambers_deg=(0.0,),
                    combined=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        free = fit_mf(data, fittyp=61)
        assert free.values["PCX1"] > 1.5  # the moved tyre's C_x is about 1.63
        narrow = replace(DECLARED["PCX1"], fit=(0.3, 1.2))
        monkeypatch.setitem(DECLARED, "PCX1", narrow)  # every stage reads the declarations
        held = fit_mf(data, fittyp=61)
    assert 0.3 <= held.values["PCX1"] <= 1.2 + 1e-12
    assert held.errors["x"]["rmse"] > free.errors["x"]["rmse"]


# ------------------------------------------------------------------- docs, CLI


def test_the_documentation_table_is_generated_from_every_declaration(tmp_path: Path) -> None:
    import sys

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "docs" / "_ext"))
    import fl_mf_coefficients

    n = fl_mf_coefficients.write_mf_coefficients(tmp_path / "mf.rst")
    page = (tmp_path / "mf.rst").read_text(encoding="utf-8")
    assert n == len(DECLARED) and page == fl_mf_coefficients.mf_coefficients_page()
    rows = re.findall(r"^   \* - ``([A-Z0-9_]+)``\n((?:     - .*\n){8})", page, re.M)
    assert sorted(name for name, _ in rows) == sorted(DECLARED)  # one row each, 9 cells
    cells = {name: [c[len("     - "):] for c in body.splitlines()] for name, body in rows}
    assert cells["PCX1"][2:5] == ["required", "0 .. 1e+06 (not the low end)", "0.3 .. 3"]
    assert cells["PDX2"][3:5] == ["-1e+06 .. 1e+06", "–"]  # fit-mf: no bound declared
    assert cells["FNOMIN"][3] == "10 .. 2e+06"
    assert cells["PKY4"][0] == "6.1, 6.2" and cells["PKY4"][2] == "2"
    assert cells["FNOMIN"][1] == "N" and cells["ALPMAX"][3] == "-1.571 .. 1.571"
    assert "turn slip" in cells["PDXP1"][5] and cells["LFZ0"][2] == "read as LFZO"
    assert "MF 5.2 fixes it at 2" in cells["PKY4"][5] and "MFeval" in cells["PKY4"][5]
    assert cells["PKY4"][6] == "Fy0" and cells["SSZ1"][6] == "Mz" and cells["LMX"][6] == "–"
    assert cells["QSX1"][7] == "Mx" and "Mz" in cells["QBZ1"][7] and "Fx" not in cells["QBZ1"][7]
    assert "Fx" in cells["PDXP1"][7] and "Fy" not in cells["PDXP1"][7]  # zeta_1: F_x
    assert "Mz" in cells["QDRP1"][7] and cells["QDRP2"][7] == "–"  # MFeval reads no QDRP2


def test_cli_lists_a_files_coefficients_beside_their_declarations(tmp_path: Path,
                                                                  capsys) -> None:
    from frictionlaws.cli import main

    doc = json.loads(FILES[1].read_text())
    del doc["LATERAL_COEFFICIENTS"]["PKY4"]
    doc["LATERAL_COEFFICIENTS"]["PXY99"] = 1.5
    (tmp_path / "t.json").write_text(json.dumps(doc))
    assert main(["tyre", "mf", str(tmp_path / "t.json"), "--coefficients"]) == 0
    out = capsys.readouterr().out
    assert re.search(r"^\[LATERAL_COEFFICIENTS\]$", out, re.M)
    assert re.search(r"^  PKY4 +2\* 1 +curvature of K_y against load", out, re.M)
    assert re.search(r"^  PCX1 +1\.5482  1 +shape factor C_x", out, re.M)
    assert re.search(r"^  FNOMIN +6752  N +nominal", out, re.M)
    assert re.search(r"^  PXY99 +1\.5 .*unknown: kept, not used", out, re.M)
    assert "PTX1" not in out  # MF 5.2 only
    assert re.search(r"^  PDXP1 +0\.4  1 +turn slip: reduction of the F_x peak", out, re.M)
    assert main(["tyre", "mf", str(tmp_path / "t.json"), "--coefficients", "--json"]) == 0
    rows = {r["name"]: r for r in json.loads(capsys.readouterr().out)["coefficients"]}
    assert rows["PKY4"]["value"] == 2.0 and rows["PKY4"]["given"] is False
    assert rows["RBY4"]["unit"] == "1/rad**2" and rows["PXY99"]["section"] == ""


#: From each declared SI unit to millimetres, kilonewtons and seconds (written by hand,
#: not from the reader's table): the factor a value is multiplied by in such a file.
TO_MM_KN = {"N": 1e-3, "m": 1e3, "N/m": 1e-6, "1/m": 1e-3, "1/m**2": 1e-6, "N/rad": 1e-3,
            "m/s": 1e3, "Pa": 1e-9, "N*s/m": 1e-6, "kg": 1.0}


def test_a_file_in_millimetres_and_kilonewtons_gives_the_si_files_outputs(
        tmp_path: Path) -> None:
    """Every dimensional entry is converted with the file's [UNITS]: the MF 6.2 example
    written in mm and kN (its camber-deflection and camber-force terms Q_CAM1, Q_CAM2,
    Q_FYS1..3 included) evaluates to the same moments and radii as in SI."""
    from frictionlaws.tyre.tir import write_tir

    pf = read_property_file(EXAMPLES / "MagicFormula62_Parameters.json")
    scaled = 0
    for entries in pf.sections.values():
        for key, value in entries.items():
            unit = DECLARED[key].unit if key in DECLARED else ""
            if unit in TO_MM_KN and not isinstance(value, str):
                entries[key] = value * TO_MM_KN[unit]
                scaled += 1
    assert {"Q_CAM1", "Q_FYS1"} <= {k for e in pf.sections.values() for k in e}
    pf.sections["UNITS"] = {**pf.sections.get("UNITS", {}), "LENGTH": "mm", "FORCE": "kN"}
    path = write_tir(pf, tmp_path / "mm.tir")
    si = MagicFormula.from_file(EXAMPLES / "MagicFormula62_Parameters.json")
    mm = MagicFormula.from_file(path)
    args = (np.array([0.0, 0.05, -0.1]), np.array([0.0, 0.05, 0.1]),
            np.array([3000.0, 5000.0, 7000.0]), np.array([0.0, 0.05, -0.05]))
    a, b = outputs.steady_state(si, *args), outputs.steady_state(mm, *args)
    for name in ("Fx", "Fy", "Mz", "Mx", "My", "Rl", "rho", "Re", "a", "b"):
        if name in a:
            np.testing.assert_allclose(b[name], a[name], rtol=1e-9, atol=1e-12, err_msg=name)
    assert scaled >= 20


def test_real_tyres_lie_within_the_bounds_and_fit_mf_searches_inside_them() -> None:
    """A truck tyre (35 kN, 800 kPa, R0 0.55 m) and a bicycle tyre (400 N, 6 bar) are
    allowed; every fit range lies inside the bounds (with the magnitude limit), and the
    magnitude limit does not bound fit-mf's search where no fit range is declared."""
    from frictionlaws.tyre.mf.declarations import LARGEST_COEFFICIENT

    truck = {"FNOMIN": 35e3, "NOMPRES": 8e5, "INFLPRES": 8.5e5, "UNLOADED_RADIUS": 0.55,
             "WIDTH": 0.315, "VERTICAL_STIFFNESS": 1.2e6, "LONGVL": 16.7, "PRESMAX": 9e5}
    bicycle = {"FNOMIN": 400.0, "NOMPRES": 6e5, "UNLOADED_RADIUS": 0.34, "WIDTH": 0.025,
               "VERTICAL_STIFFNESS": 1.5e5}
    for tyre in (truck, bicycle):
        for name, value in tyre.items():
            assert DECLARED[name].allows(value), (name, value)
    for c in DECLARED.values():
        if c.fit is not None:
            low, high = c.limits()
            assert low <= c.fit[0] < c.fit[1] <= high, c.name
    for name, (lo, _) in fit_bounds().items():
        assert DECLARED[name].limits()[0] <= lo, name
    assert "PDX2" not in fit_bounds()
    assert DECLARED["PDX2"].allows(LARGEST_COEFFICIENT)
    assert not DECLARED["PDX2"].allows(-1.01 * LARGEST_COEFFICIENT)


@pytest.mark.parametrize("quoted", ["'61'", '"61"'])
def test_a_quoted_fittyp_is_the_same_version(tmp_path: Path, quoted: str) -> None:
    plain = MagicFormula.from_property_file(read_tir(_tir_with({}), source="plain.tir"))
    tir = MagicFormula.from_property_file(read_tir(_tir_with({"FITTYP": quoted}),
                                                   source="q.tir"))
    doc = json.loads(FILES[1].read_text())
    doc["MODEL"]["FITTYP"] = "61"
    js = MagicFormula.from_file(_write(tmp_path / "q.json", json.dumps(doc)))
    assert plain.version == tir.version == js.version == "6.1"
    assert tir.fy(0.05, 0.0, 4000.0) == plain.fy(0.05, 0.0, 4000.0)
    with pytest.raises(InputError, match="FITTYP = 6x: not a Magic Formula version"):
        MagicFormula.from_property_file(read_tir(_tir_with({"FITTYP": "'6x'"}), source="x"))


def test_json_null_is_an_absent_entry(tmp_path: Path) -> None:
    """null takes the declared default (what the NaN refusal advises); a required
    coefficient given as null is missing, by section and name."""
    doc = json.loads(FILES[1].read_text())
    doc["LONGITUDINAL_COEFFICIENTS"]["PDX3"] = None
    mf = MagicFormula.from_file(_write(tmp_path / "opt.json", json.dumps(doc)))
    assert "PDX3" not in mf.coefficients
    assert mf.fx(0.1, 0.0, 4000.0, gamma=0.05) != MagicFormula.from_file(FILES[1]).fx(
        0.1, 0.0, 4000.0, gamma=0.05)
    doc["LONGITUDINAL_COEFFICIENTS"]["PDX1"] = None
    with pytest.raises(InputError, match=r"req\.json.*\[LONGITUDINAL_COEFFICIENTS\] PDX1 is "
                                         "missing"):
        MagicFormula.from_file(_write(tmp_path / "req.json", json.dumps(doc)))
    doc["LONGITUDINAL_COEFFICIENTS"]["PDX1"] = [1.0]
    with pytest.raises(InputError, match="PDX1: expected a number, a string or null"):
        MagicFormula.from_file(_write(tmp_path / "list.json", json.dumps(doc)))


def test_a_positive_pky1_is_read_with_a_note_on_the_sign_of_the_lateral_force(
        tmp_path: Path) -> None:
    iso = MagicFormula.from_file(FILES[1])
    assert iso.coefficients["PKY1"] < 0 and not any("PKY1" in n for n in iso.notes)
    doc = json.loads(FILES[1].read_text())
    doc["LATERAL_COEFFICIENTS"]["PKY1"] = 22.0
    mf = MagicFormula.from_file(_write(tmp_path / "pos.json", json.dumps(doc)))
    sign_notes = [n for n in mf.notes if "PKY1 = 22" in n]
    assert len(sign_notes) == 1 and "ISO convention" in sign_notes[0]
    assert "sign of the slip angle" in sign_notes[0]
    assert mf.fy(0.0, 0.05, 4000.0) > 0 > iso.fy(0.0, 0.05, 4000.0)
    coefficients = {**iso.coefficients, "PKY1": 22.0}
    direct = MagicFormula(coefficients, fnomin=iso.fnomin, version=iso.version)
    assert any("PKY1 = 22" in n for n in direct.notes)


def _mf52_with_6x_terms(tmp_path: Path) -> Path:
    text = (EXAMPLES / "MagicFormula52_Parameters.converted.tir").read_text()
    text = text.replace("[LATERAL_COEFFICIENTS]\n",
                        "[LATERAL_COEFFICIENTS]\nPKY6 = -0.9\nPPY1 = 0.5\n", 1)
    text = text.replace("[LONGITUDINAL_COEFFICIENTS]\n",
                        "[LONGITUDINAL_COEFFICIENTS]\nPPX1 = -0.5\n", 1)
    return _write(tmp_path / "mf52x.tir", text)


def test_a_pressure_without_a_nominal_pressure_is_never_silently_ignored(
        tmp_path: Path) -> None:
    """The MF 5.2 example has no nominal pressure: pressure= warns (it cannot change the
    outputs), its pressure terms and its 6.x-only PKY6 are noted and listed as not used."""
    from frictionlaws.tyre.mf.outputs import steady_state

    path = _mf52_with_6x_terms(tmp_path)
    mf = MagicFormula.from_file(path)
    assert mf.nominal_pressure is None
    assert any(n.startswith("PKY6: MF 6.x terms not used by the MF 5.2") for n in mf.notes)
    assert any(n.startswith("PPX1, PPY1: pressure terms not used") for n in mf.notes)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        plain = mf.fx(0.1, 0.0, 4000.0)  # no pressure given: nothing to warn of
    for call in (lambda: mf.fx(0.1, 0.0, 4000.0, pressure=1e3),
                 lambda: mf.fy(0.0, 0.05, 4000.0, pressure=5e6),
                 lambda: steady_state(mf, 0.1, 0.0, 4000.0, pressure=2e5),
                 lambda: MagicFormula.from_file(path, pressure=2e5)):
        with pytest.warns(UserWarning, match="no nominal pressure .* the pressure given is "
                                             "not used"):
            call()
    with pytest.warns(UserWarning):
        assert mf.fx(0.1, 0.0, 4000.0, pressure=1e3) == plain
    rows = {r["name"]: r for r in mf_coefficients.listing(mf.version, mf.coefficients, {})}
    assert str(rows["PKY6"]["meaning"]).startswith("not used by MF 5.2")
    assert not str(rows["PPX1"]["meaning"]).startswith("not used")  # read with a nominal p
    with_nominal = MagicFormula(mf.coefficients, fnomin=mf.fnomin, version="5.2",
                                pressure=2.2e5, nominal_pressure=2e5)
    assert with_nominal.fx(0.1, 0.0, 4000.0) != plain  # PPX1 is read by MF 5.2 then
    assert not any("pressure terms not used" in n for n in with_nominal.notes)


def test_a_peak_friction_that_is_none_blames_the_input_outside_the_files_range() -> None:
    """A load beyond FZMAX, a camber in degrees, a pressure outside the file's range: each
    refusal names that input, not the others."""
    from frictionlaws.cli import main
    from frictionlaws.tyre.mf.outputs import steady_state

    mf = MagicFormula.from_file("MagicFormula61")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ExtrapolationWarning)
        with pytest.raises(InputError, match=r"the load F_z = 100000 N lies outside the "
                                             r"file's FZMIN\.\.FZMAX") as err:
            mf.fx(0.1, 0.0, 1e5)
        assert "inflation pressure against" not in str(err.value)
        with pytest.raises(InputError, match=r"camber 3 rad \(171\.9 deg\) lies outside .*"
                                             "degrees passed as radians") as err:
            steady_state(mf, 0.0, 0.05, 4000.0, gamma=3.0)
        assert "PD\\*" not in str(err.value) and "pressure" not in str(err.value).split(";")[1]
        with pytest.raises(InputError, match="check the inflation pressure against the "
                                             "file's range"):
            mf.fx(0.1, 0.0, 4000.0, pressure=1.2e6)
    assert main(["tyre", "mf", "MagicFormula61", "--loads", "100"]) == 2
