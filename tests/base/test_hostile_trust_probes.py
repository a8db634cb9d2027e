"""The second round of security probes, as a hostile user tried them: each a case here.

Numbers that went past the one number parser and reached a written ``.tir`` or a solver
deck with exit 0 (non-ASCII digits, ``_`` separators in property files, options read
with ``float()``/``int()``), names that collided (``process --plots``, a synthetic
campaign's records; ``export --by`` checked only after fitting), and an error of the csv
module that escaped the record reader as exit 3.  Every one now exits 2 with one line
and writes nothing.  (The scheduler probes are in ``tests/parallel``, the bootstrap that
cannot vary in ``tests/fitting``.)
"""

from __future__ import annotations

from pathlib import Path

import pytest
from hostile import RIG_TOML, Snapshot, check_outcome, run_cli

pytestmark = pytest.mark.hostile

ROOT = Path(__file__).resolve().parents[2]
MF61 = ROOT / "datasets" / "mf-examples" / "MagicFormula61_Parameters.converted.tir"
DECK = ["export", "--law", "exponential-decay", "--preset", "rubber-steel", "--v", "0.1:2"]


def _refused(argv: list[str], tmp_path: Path, *, inputs: tuple[Path, ...] = (),
             says: str = "") -> str:
    snap = Snapshot.take([tmp_path], inputs=inputs)
    res = run_cli(argv)
    check_outcome(res, snapshot=snap, codes=[2])
    assert says in res.err, res.describe()
    return res.err


@pytest.fixture(scope="module")
def tyre_csv(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Pure slip-ratio sweeps of the packaged MF 6.1 tyre at two loads."""
    import numpy as np

    from frictionlaws.tyre import MagicFormula

    mf = MagicFormula.from_file("MagicFormula61")
    kappa = np.linspace(-0.2, 0.2, 15)
    rows = [f"{fz:.1f},{k:.4f},{fx:.2f}\n" for fz in (3000.0, 6000.0)
            for k, fx in zip(kappa, mf.fx0(kappa, np.full(kappa.size, fz)))]
    path = tmp_path_factory.mktemp("tyre") / "tyre.csv"
    path.write_text("Fz [N],kappa [-],Fx [N]\n" + "".join(rows), encoding="utf-8")
    return path


def _tir(tmp_path: Path, old: str, new: str, extra: str = "") -> Path:
    text = MF61.read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "hostile.tir"
    path.write_text(text.replace(old, new, 1) + extra, encoding="utf-8")
    return path


@pytest.mark.parametrize("value", ["\u0666\u0667\u0665\u0662", "6_752", "\uff16\uff17\uff15\uff12",
                                   "nan", "inf", "6752\u0662"])
def test_a_tir_value_past_the_parser_reaches_no_written_file(tmp_path: Path, tyre_csv: Path,
                                                            value: str) -> None:
    tir = _tir(tmp_path, "FNOMIN                     = 6752",
               f"FNOMIN                     = {value}")
    err = _refused(["tyre", "fit-mf", str(tyre_csv), "--template", str(tir), "-o",
                    str(tmp_path / "out.tir")], tmp_path, inputs=(tir,), says="FNOMIN")
    assert "row 58" in err
    _refused(["tyre", "mf", str(tir)], tmp_path, inputs=(tir,), says="FNOMIN")


@pytest.mark.parametrize("row", ["1.0 nan", "1_0 0.4", "\u0661.0 0.4", "1e999 0.4"])
def test_a_tir_table_row_past_the_parser_is_refused(tmp_path: Path, row: str) -> None:
    tir = _tir(tmp_path, "x", "x", extra=f"[SHAPE]\n{{radial width}}\n 1.0 0.0\n {row}\n")
    _refused(["tyre", "mf", str(tir)], tmp_path, inputs=(tir,), says="table row")


def test_a_quoted_fittyp_in_other_digits_is_no_version(tmp_path: Path) -> None:
    tir = _tir(tmp_path, "FITTYP                     = 61",
               "FITTYP                     = '\u0666\u0661'")
    _refused(["tyre", "mf", str(tir)], tmp_path, inputs=(tir,), says="FITTYP")


@pytest.mark.parametrize(("argv", "says"), [
    ([*DECK, "--format", "lsdyna", "--lsdyna-contact", "1_0,2"], "--lsdyna-contact"),
    ([*DECK, "--format", "lsdyna", "--lsdyna-contact", "\u0661,\u0662"], "--lsdyna-contact"),
    ([*DECK, "--format", "abaqus", "--tol", "1_0e-3"], "--tol"),
    ([*DECK, "--format", "abaqus", "--tol", "\u0660.\u0660\u0661"], "--tol"),
    ([*DECK, "--format", "abaqus", "--tol", "nan"], "--tol"),
    ([*DECK, "--format", "csv", "--v", "0.1:2:\u0665"], "--v"),
])
def test_a_number_past_the_parser_reaches_no_solver_deck(tmp_path: Path, argv: list[str],
                                                        says: str) -> None:
    _refused([*argv, "-o", str(tmp_path / "deck.out")], tmp_path, says=says)


@pytest.mark.parametrize(("argv", "says"), [
    (["tyre", "reduce", str(MF61), "--law", "pacejka", "--load", "4kN", "--slip-max",
      "\u0660.\u0665"], "--slip-max"),
    (["tyre", "reduce", str(MF61), "--law", "pacejka", "--load", "4kN", "--slip-max", "inf"],
     "--slip-max"),
    (["fit", "--law", "thirion", "thesis-steel", "--by", "p", "--jobs", "1_0"], "--jobs"),
    (["fit", "--law", "thirion", "thesis-steel", "--by", "p", "--jobs", "\u0662"], "--jobs"),
    (["compare", "thesis-steel", "--laws", "thirion,coulomb", "--holdout", "p=\u0660.\u0663"],
     "--holdout"),
    (["compare", "thesis-steel", "--laws", "thirion,coulomb", "--holdout", "0_3"],
     "--holdout"),
])
def test_a_numeric_option_past_the_parser_is_refused(tmp_path: Path, argv: list[str],
                                                     says: str) -> None:
    _refused(argv, tmp_path, says=says)


def test_fit_mf_fittyp_in_other_digits_is_refused(tmp_path: Path, tyre_csv: Path) -> None:
    _refused(["tyre", "fit-mf", str(tyre_csv), "--fittyp", "\u0666\u0661", "-o",
              str(tmp_path / "x.tir")], tmp_path, says="--fittyp")


# ------------------------------------------------------------------- names that collide


def test_records_whose_plots_share_a_name_are_refused_before_any_work(tmp_path: Path) -> None:
    rig = tmp_path / "rig.toml"
    rig.write_text(RIG_TOML, encoding="utf-8")
    (tmp_path / "records").mkdir()
    for name in ("records/a b.csv", "records/a_b.csv", "conditions.csv"):
        (tmp_path / name).write_text("time [s],torque [N m],disc_speed [rpm]\n0,0.1,100\n",
                                     encoding="utf-8")
    manifest = tmp_path / "m.csv"
    head = "file,load [kg],surface,condition,mode\n"
    argv = ["process", str(manifest), "--rig", str(rig), "-o", str(tmp_path / "out.csv"),
            "--plots", str(tmp_path / "plots"), "--jobs", "1"]
    manifest.write_text(head + "records/a b.csv,3,steel,c,steady\n"
                        "records/a_b.csv,3,steel,c,steady\n", encoding="utf-8")
    err = _refused(argv, tmp_path, inputs=(manifest,), says="records_a_b.png")
    assert "row 2" in err and "row 3" in err
    # a record whose plot would replace the summary plot
    manifest.write_text(head + "records/a b.csv,3,steel,c,steady\n"
                        "conditions.csv,3,steel,c,steady\n", encoding="utf-8")
    _refused(argv, tmp_path, inputs=(manifest,), says="the summary plot")


def test_a_synthetic_campaign_refuses_records_that_share_a_name(tmp_path: Path) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.tribometer.synthetic import ConditionSpec, make_campaign

    with pytest.raises(InputError, match="a_b_01.csv"):
        make_campaign(tmp_path / "c", [ConditionSpec("a b", "steel", 3.0, 1.1, repeats=2),
                                       ConditionSpec("a_b", "steel", 5.0, 1.1, repeats=2)])
    assert not (tmp_path / "c").exists()


def test_export_by_refuses_groups_that_share_a_file_name_before_fitting(
        tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import frictionlaws.fitting.campaign as campaign

    def no_fit(*args: object, **kwargs: object) -> None:
        raise AssertionError("fitted before the names were checked")

    monkeypatch.setattr(campaign, "fit_groups", no_fit)
    data = tmp_path / "d.csv"
    data.write_text("surface,p [MPa],mu\n" + "".join(
        f"{s},{p},{0.6 - p}\n" for s in ("A/B", "a b") for p in (0.05, 0.1, 0.2, 0.3)),
        encoding="utf-8")
    _refused(["export", "--law", "thirion", "--fit", str(data), "--by", "surface", "--format",
              "abaqus", "--p", "0.01MPa:0.5MPa", "-o", str(tmp_path / "deck.inp")], tmp_path,
             inputs=(data,), says="deck_a-b.inp")


# ------------------------------------------------------------------- errors that escaped


def test_a_record_header_beyond_the_csv_field_limit_is_an_input_error(tmp_path: Path) -> None:
    from frictionlaws.base.errors import InputError
    from frictionlaws.tribometer.records import read_record

    rec = tmp_path / "long.csv"
    rec.write_text("time [s],torque [N m],disc_speed [rpm],note" + "x" * 140_000 + "\n"
                   + "".join(f"{i / 100:.2f},0.1,100,1\n" for i in range(50)), encoding="utf-8")
    with pytest.raises(InputError, match="header line cannot be read") as err:
        read_record(rec)
    assert str(rec) in str(err.value) and "row 1" in str(err.value)
