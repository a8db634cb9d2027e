"""Table and keyword exports read back with independent parsers.

Each written file is parsed here from scratch (no code from the writers),
interpolated as the solver does (linear in each variable, end values held:
scipy's RegularGridInterpolator on clamped queries, or np.interp for LS-DYNA
curves), and compared with the law at random off-grid points: the error must
stay within the maximum the file's own header states.
"""

from __future__ import annotations

import json
import re
import warnings

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from frictionlaws import get_law
from frictionlaws.base.errors import InputError
from frictionlaws.fe_export import export, parse_range, unit_system

# ------------------------------------------------------------------ parsers


def stated_error(text: str) -> float:
    """The maximum error the file's header states."""
    flat = re.sub(r"\n\W*", " ", text)
    m = re.search(r"max (?:interpolation|approximation) error \|mu_\w+ - mu_law\| = "
                  r"([0-9.eE+-]+)", flat)
    assert m, "no error statement in the header"
    return float(m.group(1))


def grid_from_rows(rows: np.ndarray, ncols: int):
    """Axes and mu array from rows of (vars..., mu) in any order."""
    axes = [np.unique(rows[:, i]) for i in range(ncols)]
    shape = tuple(len(a) for a in axes)
    mu = np.full(shape, np.nan)
    idx = tuple(np.searchsorted(a, rows[:, i]) for i, a in enumerate(axes))
    mu[idx] = rows[:, ncols]
    assert np.isfinite(mu).all(), "not a full tensor grid"
    return axes, mu


def solver_interp(axes, mu, query):
    """Multilinear, ends held (query clamped into the table)."""
    keep = [i for i, a in enumerate(axes) if len(a) > 1]
    vals = mu
    for i in reversed(range(len(axes))):
        if len(axes[i]) == 1:
            vals = np.take(vals, 0, axis=i)
    if not keep:
        return np.full(len(query[0]) if query else 1, float(vals))
    q = np.column_stack([np.clip(query[i], axes[i][0], axes[i][-1]) for i in keep])
    return RegularGridInterpolator([axes[i] for i in keep], vals, method="linear")(q)


def parse_csv(text):
    lines = [ln for ln in text.splitlines() if ln and not ln.startswith("#")]
    header = lines[0].split(",")
    names = [re.match(r"(\w+) \[(.*)\]", h).groups() for h in header]
    rows = np.array([[float(x) for x in ln.split(",")] for ln in lines[1:]])
    axes, mu = grid_from_rows(rows, len(header) - 1)
    return [n for n, _ in names[:-1]], dict(names), axes, mu


def parse_json(text):
    doc = json.loads(text)
    names = [a["name"] for a in doc["axes"]]
    axes = [np.array(a["values"]) for a in doc["axes"]]
    units = {a["name"]: a["unit"] for a in doc["axes"]}
    return names, units, axes, np.array(doc["mu"], dtype=float), doc


def parse_abaqus(text):
    """*FRICTION data lines -> (columns used, axes, mu), checking Abaqus' ordering rule."""
    lines = [ln.strip() for ln in text.splitlines() if ln.strip() and not ln.startswith("**")]
    start = next(i for i, ln in enumerate(lines) if ln.upper().startswith("*FRICTION"))
    m = re.search(r"DEPENDENCIES\s*=\s*(\d+)", lines[start].upper())
    deps = int(m.group(1)) if m else 0
    data = []
    for ln in lines[start + 1:]:
        if ln.startswith("*"):
            break
        data.append([float(x) for x in ln.split(",") if x.strip()])
    width = 4 + deps if deps else max(len(r) for r in data)
    rows = []
    buf: list[float] = []
    for r in data:
        buf += r
        if len(buf) >= width or not deps:
            rows.append(buf)
            buf = []
    arr = np.array(rows)
    ncols = arr.shape[1] - 1
    # reorder columns (mu first in Abaqus) to (vars..., mu)
    arr = np.column_stack([arr[:, 1:], arr[:, 0]])
    # ordering: first independent column fastest, ascending, same set in every block
    if ncols:
        first = arr[:, 0]
        n_first = len(np.unique(first))
        blocks = first.reshape(-1, n_first)
        assert np.all(np.diff(blocks, axis=1) > 0) or n_first == 1
        assert np.all(blocks == blocks[0])
        # rows sorted with the first column fastest, the last slowest, all ascending
        keys = tuple(arr[:, c] for c in range(ncols))
        assert np.array_equal(np.lexsort(keys), np.arange(len(arr)))
    axes, mu = grid_from_rows(arr, ncols)
    return deps, axes, mu


def parse_lsdyna(text):
    """Card 2, *DEFINE_TABLE values and the curves that follow them."""
    lines = [ln for ln in text.splitlines() if not ln.startswith("$")]
    out = {"table": None, "values": [], "curves": []}
    i = 0
    while i < len(lines):
        ln = lines[i]
        if ln.startswith("*CONTACT"):
            card2 = lines[i + 2]
            out["card2"] = [float(card2[k:k + 10]) for k in range(0, 80, 10)]
            i += 4
            continue
        if ln.startswith("*DEFINE_TABLE"):
            out["table"] = int(lines[i + 1][:10])
            i += 2
            while not lines[i].startswith("*"):
                out["values"].append(float(lines[i][:20]))
                i += 1
            continue
        if ln.startswith("*DEFINE_CURVE"):
            lcid = int(lines[i + 1][:10])
            i += 2
            pts = []
            while not lines[i].startswith("*"):
                pts.append((float(lines[i][:20]), float(lines[i][20:40])))
                i += 1
            out["curves"].append((lcid, np.array(pts)))
            continue
        i += 1
    return out


def lsdyna_interp(parsed, p, v):
    """Table lookup as LS-DYNA: each curve linear in v (clamped), then linear in p."""
    vals = np.array(parsed["values"])
    per_curve = np.array([np.interp(v, c[:, 0], c[:, 1]) for _, c in parsed["curves"]])
    return np.array([np.interp(p[k], vals, per_curve[:, k]) for k in range(len(p))])


def parse_ansys(text):
    rows = []
    current: dict[str, float] = {}
    order: list[str] = []
    for ln in text.splitlines():
        if ln.startswith("!") or not ln.strip():
            continue
        parts = [s.strip() for s in ln.split(",")]
        if parts[0] == "TB":
            assert parts[1] == "FRIC" and parts[-1] == "ISO"
        elif parts[0] == "TBFIELD":
            current[parts[1]] = float(parts[2])
            if parts[1] not in order:
                order.append(parts[1])
        elif parts[0] == "TBDATA":
            assert parts[1] == "1"
            rows.append([current[f] for f in order] + [float(parts[2])])
    arr = np.array(rows)
    axes, mu = grid_from_rows(arr, len(order))
    return order, axes, mu


def parse_radioss(text):
    lines = [ln for ln in text.splitlines() if not ln.startswith("#")]
    i = next(k for k, ln in enumerate(lines) if ln.startswith("/FRICTION/"))
    ifric = int(lines[i + 2][:10])
    c = [float(lines[i + 3][k:k + 20]) for k in range(0, 100, 20)]
    c6, fric = float(lines[i + 4][:20]), float(lines[i + 4][20:40])
    return ifric, dict(zip(("C1", "C2", "C3", "C4", "C5"), c, strict=True)) | {
        "C6": c6, "Fric": fric}


def radioss_mu(ifric, c, P, V):
    if ifric == 1:
        return (c["Fric"] + c["C1"] * P + c["C2"] * V + c["C3"] * P * V + c["C4"] * P**2
                + c["C5"] * V**2)
    if ifric == 4:
        return c["C1"] + (c["Fric"] - c["C1"]) * np.exp(-c["C2"] * V)
    raise AssertionError(ifric)


# ------------------------------------------------------------------ cases

CASES = {
    "poly2": ("thesis-poly2", None, "steel", {"p": "0.03:0.25", "v": "0:2770"}, "mm-N-s",
              2e-3),
    "expdecay-d1.5": ("exponential-decay", {"mu_s": 1.1, "mu_d": 0.55, "v_c": 0.2,
                                            "delta": 1.5}, None, {"v": "0:3"}, "SI", None),
    "savkoor": ("savkoor", {"mu_s": 0.5, "mu_m": 1.2, "h10": 0.4, "v_m": 0.01, "n": -0.1},
                None, {"p": "10kPa:1MPa", "v": "0.1:10000:40"}, "mm-N-s", 5e-3),
    "park-T": ("park", {"n": 0.11, "mu_s": 0.5, "mu_m": 1.2, "h10": 0.3, "v_m": 0.01}, None,
               {"p": "0.02:1:6", "v": "1:3000:25", "T": "0:50:6"}, "mm-N-s,T=degC", None),
    "pacejka-s": ("pacejka", None, "dry", {"s": "0:1"}, "SI", 1e-3),
    "schallamach-FN": ("schallamach", None, "hertz", {"F_N": "1:100"}, "SI", 2e-3),
}

TABLE_SUPPORT = {
    "csv": set(CASES),
    "json": set(CASES),
    "abaqus": set(CASES),
    "ansys": {"poly2", "expdecay-d1.5", "savkoor", "park-T"},
    "lsdyna": {"poly2", "expdecay-d1.5", "savkoor"},
}
PARAMS = [(fmt, case) for fmt, cases in TABLE_SUPPORT.items() for case in sorted(cases)]


def run_case(fmt, case, tmp_path):
    law_id, values, preset, box, units, tol = CASES[case]
    system = unit_system(units)
    specs = {k: parse_range(k, v, system) for k, v in box.items()}
    path = tmp_path / f"out.{fmt}"
    if fmt == "radioss":  # an approximation stated by its error; a missed tol is refused
        tol = None        # (test_radioss_approximation_that_misses_the_tolerance_is_refused)
    res = export(law_id, values, fmt, specs, preset=preset, units=units, tol=tol, path=path)
    text = path.read_text()
    assert text == res.text
    law = get_law(law_id)
    vals = law.resolve(values, preset)
    return law, vals, specs, system, text, res


def random_points(specs, n=3000, seed=5):
    rng = np.random.default_rng(seed)
    out = {}
    for k, s in specs.items():
        if s.kind == "log":
            out[k] = np.exp(rng.uniform(np.log(s.lo), np.log(s.hi), n))
        else:
            out[k] = rng.uniform(s.lo, s.hi, n)
    return out


def law_mu(law, vals, pts):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return np.asarray(law.evaluate(pts, vals), float)


@pytest.mark.parametrize("fmt,case", PARAMS, ids=[f"{f}-{c}" for f, c in PARAMS])
def test_table_read_back_within_stated_error(fmt, case, tmp_path):
    law, vals, specs, system, text, res = run_case(fmt, case, tmp_path)
    stated = stated_error(text) if fmt != "json" else json.loads(text)["interpolation"][
        "max_abs_error"]
    assert stated == pytest.approx(res.max_error, rel=1e-2, abs=1e-12)
    tol = CASES[case][5]
    if tol is not None:
        assert stated <= tol
    pts = random_points(specs)
    exact = law_mu(law, vals, pts)
    model = {k: np.asarray(system.to_model(k, x), float) for k, x in pts.items()}
    if fmt in ("csv", "json"):
        if fmt == "csv":
            names, units, axes, mu = parse_csv(text)
        else:
            names, units, axes, mu, doc = parse_json(text)
            assert doc["units"]["system"] == system.name
        for n in names:
            assert units[n] == system.label(n) or units[n] == system.unit(n)
        approx = solver_interp(axes, mu, [model[n] for n in names])
    elif fmt == "abaqus":
        deps, axes, mu = parse_abaqus(text)
        order = ["v", "p", "T"]
        fields = [v for v in law.variables if v in ("F_N", "s")]
        assert deps == len(fields)
        cols = (order if fields else order[:max([order.index(v) + 1 for v in law.variables
                                                 if v in order] or [0])]) + fields
        assert len(axes) == len(cols)
        q = [model[c] if c in model else np.zeros(len(exact)) for c in cols]
        approx = solver_interp(axes, mu, q)
    elif fmt == "ansys":
        order, axes, mu = parse_ansys(text)
        key = {"TEMP": "T", "NPRES": "p", "SLRV": "v"}
        approx = solver_interp(axes, mu, [model[key[o]] for o in order])
    else:
        parsed = parse_lsdyna(text)
        assert parsed["card2"][0] == 2.0 and int(parsed["card2"][1]) == parsed["table"]
        assert [c[0] for c in parsed["curves"]] == [parsed["table"] + 1 + i for i in range(
            len(parsed["values"]))]
        n = len(exact)
        approx = lsdyna_interp(parsed, model.get("p", np.zeros(n)), model.get("v", np.zeros(n)))
        # guard points: extrapolating the end segments linearly also holds the end values
        for _, c in parsed["curves"]:
            assert c[-1, 1] == c[-2, 1]
            if c[0, 0] > 0:
                assert c[0, 1] == c[1, 1]
    err = np.abs(approx - exact)
    assert err.max() <= stated * 1.02 + 1e-9, (err.max(), stated)
    if tol is not None:
        assert err.max() <= tol


def test_headers_state_law_params_units_box_error_and_outside(tmp_path):
    for fmt in ("csv", "abaqus", "ansys", "lsdyna"):
        law, vals, specs, system, text, res = run_case(fmt, "poly2", tmp_path)
        flat = re.sub(r"\n\W*", " ", text)
        assert "law: thesis-poly2" in flat
        for p in law.params:
            assert re.search(rf"\b{p.name} = {vals[p.name]!r} \[", flat)
        assert "units: mm-N-s (p MPa, v mm/s)" in flat
        assert "box: " in flat and "0.03 MPa .. 0.25 MPa" in flat
        assert re.search(r"max interpolation error \|mu_file - mu_law\| = \S+ at [pv] = ", flat)
        assert "outside the box:" in flat


def test_units_convert_the_numbers(tmp_path):
    common = dict(preset="steel", tol=None)
    box = {"p": (0.03e6, 0.25e6, 3), "v": (0.0, 2.0, 3)}
    si = export("thesis-poly2", None, "csv", box, units="SI", **common).text
    mm = export("thesis-poly2", None, "csv", box, units="mm-N-s", **common).text
    _, u_si, ax_si, mu_si = parse_csv(si)
    _, u_mm, ax_mm, mu_mm = parse_csv(mm)
    assert u_si["p"] == "Pa" and u_mm["p"] == "MPa" and u_mm["v"] == "mm/s"
    assert np.allclose(ax_mm[0] * 1e6, ax_si[0]) and np.allclose(ax_mm[1] / 1e3, ax_si[1])
    assert np.allclose(mu_si, mu_mm)


def test_temperature_offset_units(tmp_path):
    law, vals, specs, system, text, res = run_case("csv", "park-T", tmp_path)
    names, units, axes, mu = parse_csv(text)
    assert units["T"] == "degC"
    assert axes[names.index("T")][0] == pytest.approx(0.0)
    assert axes[names.index("T")][-1] == pytest.approx(50.0)


def test_abaqus_columns_for_a_pressure_only_law_and_constant():
    text = export("thirion", {"a": 0.5, "b": 2e-6}, "abaqus", {"p": (0, 1e6, 5)}).text
    deps, axes, mu = parse_abaqus(text)
    assert deps == 0 and len(axes) == 2 and axes[0].tolist() == [0.0]  # single slip rate 0
    assert np.allclose(mu[0], 1 / (0.5 + 2e-6 * axes[1]))
    text = export("coulomb", {"mu0": 0.7}, "abaqus").text
    data = [ln for ln in text.splitlines() if ln and not ln.startswith("*")]
    assert data == ["0.7"]


# ---------------------------------------------------------- exact formats


def test_abaqus_decay_is_exact_and_in_model_units():
    vals = {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.5, "delta": 1.0}
    text = export("exponential-decay", vals, "abaqus-decay", units="mm-N-s").text
    lines = [ln for ln in text.splitlines() if not ln.startswith("**")]
    assert lines[0] == "*FRICTION, EXPONENTIAL DECAY"
    mu_s, mu_k, d_c = (float(x) for x in lines[1].split(","))
    v_mm = np.linspace(0, 5000, 200)
    law = get_law("exponential-decay")
    ref = law(v=v_mm / 1000, **vals)
    assert np.allclose(mu_k + (mu_s - mu_k) * np.exp(-d_c * v_mm), ref, rtol=1e-14)
    assert d_c == pytest.approx(1 / 500.0)


def test_abaqus_decay_coulomb_is_degenerate_decay():
    text = export("coulomb", {"mu0": 0.9}, "abaqus-decay").text
    assert text.rstrip().splitlines()[-1].startswith("0.9, 0.9, ")


@pytest.mark.parametrize("law_id,values", [
    ("exponential-decay", {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.5, "delta": 1.3}),
    ("thirion", {"a": 0.5, "b": 1e-6}),
    ("quadratic-pv", {"c0": 1, "c1": 0, "c2": 0.1, "c3": 0, "c4": 0, "c5": 0}),
])
def test_abaqus_decay_refuses_other_laws(law_id, values):
    with pytest.raises(InputError, match="fit 'exponential-decay'|Fit 'exponential-decay'"):
        export(law_id, values, "abaqus-decay")


def test_lsdyna_fs_fd_dc_exact():
    vals = {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.25, "delta": 1.0}
    res = export("exponential-decay", vals, "lsdyna", units="mm-N-s",
                 options={"lsdyna_ssid": 7, "lsdyna_msid": 9})
    parsed = parse_lsdyna(res.text)
    fs, fd, dc = parsed["card2"][:3]
    assert (fs, fd) == (1.2, 0.8) and dc == pytest.approx(1 / 250.0)
    assert parsed["table"] is None and res.exact and res.max_error == 0.0
    card1 = [ln for ln in res.text.splitlines() if not ln.startswith("$")][2]
    assert int(card1[:10]) == 7 and int(card1[10:20]) == 9


def test_lsdyna_refuses_temperature_and_slip_laws():
    with pytest.raises(InputError, match="pressure and sliding velocity only"):
        export("pacejka", None, "lsdyna", {"s": (0, 1)}, preset="dry")


def test_radioss_ifric1_exact_for_quadratic_pv_and_poly2():
    c = {"c0": 1.2, "c1": -1.5e-6, "c2": 0.08, "c3": 2e-7, "c4": 8e-13, "c5": -0.015}
    for law_id, vals, units in (("quadratic-pv", c, "SI"), ("thesis-poly2", None, "mm-N-s")):
        res = export(law_id, vals, "radioss", preset=None if vals else "steel", units=units)
        ifric, coef = parse_radioss(res.text)
        assert ifric == 1 and res.exact
        law = get_law(law_id)
        v_ = law.resolve(vals, None if vals else "steel")
        rng = np.random.default_rng(2)
        p, v = rng.uniform(0, 1e6, 100), rng.uniform(0, 3, 100)
        system = unit_system(units)
        got = radioss_mu(1, coef, system.to_model("p", p), system.to_model("v", v))
        assert np.allclose(got, law.evaluate({"p": p, "v": v}, v_), rtol=1e-10, atol=1e-12)


def test_radioss_ifric4_exact_for_exponential_decay():
    vals = {"mu_s": 1.2, "mu_d": 0.8, "v_c": 0.5, "delta": 1.0}
    res = export("exponential-decay", vals, "radioss", units="mm-N-s")
    ifric, coef = parse_radioss(res.text)
    assert ifric == 4
    v_mm = np.linspace(0, 3000, 50)
    assert np.allclose(radioss_mu(4, coef, 0, v_mm),
                       get_law("exponential-decay")(v=v_mm / 1e3, **vals), rtol=1e-13)


def test_radioss_fits_ifric1_and_states_the_error(tmp_path):
    law, vals, specs, system, text, res = run_case("radioss", "savkoor", tmp_path)
    assert not res.exact and res.details["approximate"]
    assert "APPROXIMATION" in text
    stated = stated_error(text)
    assert stated == pytest.approx(res.max_error, rel=1e-2)
    ifric, coef = parse_radioss(text)
    assert ifric == 1
    pts = random_points(specs, 5000, seed=9)
    got = radioss_mu(1, coef, system.to_model("p", pts["p"]), system.to_model("v", pts["v"]))
    err = np.abs(got - law_mu(law, vals, pts))
    assert err.max() <= stated * 1.02 + 1e-12
    assert err.max() > 0.5 * stated  # the statement is not a loose bound
    assert "rms" in text


def test_radioss_refuses_laws_of_other_variables():
    with pytest.raises(InputError, match="pressure and velocity only"):
        export("schallamach", None, "radioss", {"F_N": (1, 10)}, preset="hertz")


def test_ansys_refuses_slip_laws():
    with pytest.raises(InputError, match="NPRES"):
        export("pacejka", None, "ansys", {"s": (0, 1)}, preset="dry")


# ------------------------------------------------------------------ errors


def test_bad_input_errors():
    with pytest.raises(InputError, match="unknown export format 'nastran'"):
        export("coulomb", {"mu0": 1}, "nastran")
    with pytest.raises(InputError, match=r"depends on p .*box\['p'\]='MIN:MAX"):
        export("thirion", {"a": 1, "b": 1e-6}, "csv")
    with pytest.raises(InputError, match="expected MIN:MAX"):
        parse_range("p", "0.1-0.5", "SI")
    with pytest.raises(InputError, match="must not be negative"):
        parse_range("v", "-1:1", "SI")
    with pytest.raises(InputError, match="is a velocity, expected a pressure"):
        parse_range("p", "1m/s:2m/s", "SI")
    with pytest.raises(InputError, match="unknown unit system"):
        export("coulomb", {"mu0": 1}, "csv", units="imperial")
    with pytest.raises(InputError, match="tolerance"):
        export("thirion", {"a": 1, "b": 1e-6}, "csv", {"p": (0, 1e6)}, tol=-1)
    with pytest.raises(InputError, match="no preset 'nope'"):
        export("coulomb", None, "csv", preset="nope")


def test_ranges_with_units_and_bare_numbers_in_the_system():
    s = parse_range("p", "0.01:0.5:20", "mm-N-s")
    assert (s.lo, s.hi, s.n) == (pytest.approx(1e4), pytest.approx(5e5), 20)
    s = parse_range("p", "10kPa:0.5MPa", "SI")
    assert (s.lo, s.hi, s.n) == (pytest.approx(1e4), pytest.approx(5e5), None)
    s = parse_range("T", "20degC:80degC:4", "SI")
    assert s.lo == pytest.approx(293.15) and s.hi == pytest.approx(353.15)


def test_box_outside_a_strict_domain_is_refused_and_a_soft_one_warns():
    # the thesis polynomials must not be extrapolated: refused, nothing written
    with pytest.raises(InputError, match="must not be extrapolated"):
        export("thesis-poly2", None, "csv", {"p": (0.01e6, 0.5e6, 5), "v": (0, 2, 3)},
               preset="steel")
    # park's temperature domain (T_ref +/- 50 K) marks extrapolation: a warning
    law = get_law("park")
    lo, hi = law.domain["T"]
    res = export("park", law.defaults, "csv",
                 {"p": (1e5, 2e5, 3), "v": (0.01, 0.1, 3), "T": (lo, hi + 20.0, 3)})
    assert any("leaves the law's domain" in w for w in res.warnings)
    assert "WARNING: the box of T" in res.text


def test_public_api_name_is_the_function_after_the_package_is_imported():
    import frictionlaws
    import frictionlaws.fe_export.grid  # noqa: F401 - the package has its own name
    from frictionlaws.fe_export import export

    assert frictionlaws.export is export
    res = frictionlaws.export("coulomb", {"mu0": 0.5}, "csv")
    assert res.text.rstrip().endswith("0.5") and res.rows == 1
