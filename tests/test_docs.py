"""Fast checks of the documentation sources and of the build-time generators.

The full build (``python -m sphinx -W --keep-going -b html docs docs/_build/html``) runs
in ``.ci/run``; these tests catch the common breakages in seconds: a law missing from
the catalogue, a gallery file without a title, a README command that drifted.
"""

from __future__ import annotations

import ast
import math
import re
import sys
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
EXAMPLES = ROOT / "examples"
sys.path.insert(0, str(DOCS / "_ext"))

import fl_docgen  # noqa: E402

import frictionlaws as fl  # noqa: E402
from frictionlaws.law import Law, Param  # noqa: E402
from frictionlaws.law.registry import REGISTRY  # noqa: E402

GALLERY = sorted(EXAMPLES.rglob("plot_*.py"))


# ------------------------------------------------------------------ catalogue


def test_catalogue_lists_every_registered_law(tmp_path):
    ids = fl_docgen.write_catalogue(tmp_path, plots=False)
    registered = [law.id for law in fl.list_laws()]
    assert ids == registered
    assert fl_docgen.check_catalogue(tmp_path) == []
    index = (tmp_path / "index.rst").read_text(encoding="utf-8")
    for law in fl.list_laws():
        page = (tmp_path / f"{fl_docgen._page_name(law.id)}.rst").read_text(encoding="utf-8")
        assert f":ref:`{law.id} <law-" in index
        assert f"``{law.id}``" in page
        assert ".. math::" in page and r"\mu = " in page
        for p in law.params:
            assert f"``{p.name}``" in page, (law.id, p.name)
        for s in law.settings:
            assert f"``{s.name}``" in page, (law.id, s.name)
        for preset in law.presets:
            assert f"``{preset}``" in page, (law.id, preset)
        assert "Evidence" in page and law.evidence.split()[0] in page
    assert f"**{len(registered)} laws**" in index


def test_catalogue_check_fails_when_a_law_is_missing(tmp_path):
    fl_docgen.write_catalogue(tmp_path, plots=False)
    victim = fl.list_laws()[1]
    (tmp_path / f"{fl_docgen._page_name(victim.id)}.rst").unlink()
    assert fl_docgen.check_catalogue(tmp_path) == [victim.id]


@pytest.mark.slow
def test_catalogue_picks_up_a_newly_registered_law(tmp_path):
    fl.list_laws()  # load the built-ins first
    law = Law(id="docs-test-linear", title="Docs test (linear in p)", family="sliding",
              variables=("p",), params=(Param("k", "1/Pa", 1e-6, (0.0, math.inf), "slope"),
                                        Param("mu0", "", 1.0, (0.0, math.inf), "offset")),
              formula=lambda m, p, k, mu0: mu0 - k * p, evidence="I",
              domain={"p": (1e4, 5e5)})
    fl_docgen.write_catalogue(tmp_path, plots=False)
    REGISTRY.register(law)
    try:
        # a catalogue written before the law existed lacks it: the build's check says so
        assert fl_docgen.check_catalogue(tmp_path) == [law.id]
        ids = fl_docgen.write_catalogue(tmp_path, plots=True)
        assert law.id in ids
        assert fl_docgen.check_catalogue(tmp_path) == []
        assert (tmp_path / "docs-test-linear.png").read_bytes()[:4] == b"\x89PNG"
    finally:
        REGISTRY.unregister(law.id)
    # once unregistered, a fresh write removes its stale page
    fl_docgen.write_catalogue(tmp_path, plots=False)
    assert not (tmp_path / "docs-test-linear.rst").exists()


def test_catalogue_fails_loudly_on_a_law_it_cannot_render(tmp_path):
    bad = Law(id="docs-test-broken", title="Broken", family="sliding", variables=("p",),
              params=(Param("a", "", 1.0),), formula=lambda m, p, a: m.no_such_function(p))
    with pytest.raises(RuntimeError, match="docs-test-broken"):
        fl_docgen.write_catalogue(tmp_path, laws=[bad], plots=False)


@pytest.mark.parametrize("law", fl.list_laws(), ids=lambda law: law.id)
def test_docs_formula_is_the_law(law):
    """The tidied formula the catalogue prints is the same function as the law."""
    import sympy

    tidy = fl_docgen.symbolic_for_docs(law)
    tidy = tidy.replace(lambda e: type(e).__name__ == "log10",
                        lambda e: sympy.log(e.args[0], 10))
    rng = np.random.default_rng(1)
    syms = law.symbols()
    for _ in range(3):
        values = {}
        for name in law.variables:
            lo, hi = law.typical_range(name)
            lo = max(lo, 1e-3 if name == "s" else lo)
            values[name] = float(rng.uniform(lo if lo > 0 else 1e-3, hi))
        params = law.resolve(law.presets[next(iter(law.presets))] if law.presets else
                             law.defaults)
        subs = {syms[k]: v for k, v in {**values, **params}.items() if k in syms}
        a = complex(law.symbolic().evalf(subs=subs))
        b = complex(tidy.evalf(subs=subs))
        assert abs(a - b) <= 1e-9 * max(1.0, abs(a)), (law.id, a, b)
    assert "log(10)" not in fl_docgen.law_latex(law)


def test_law_latex_examples():
    assert fl_docgen.law_latex(fl.get_law("thirion")) == r"\mu = \frac{1}{a + b p}"
    savkoor = fl_docgen.law_latex(fl.get_law("savkoor"))
    assert r"\log_{10}" in savkoor and r"\ln" not in savkoor
    nack = fl_docgen.law_latex(fl.get_law("nackenhorst"))
    assert r"\ln" in nack and r"\log_{10}" not in nack


@pytest.mark.parametrize("law_id", ["coulomb", "thesis-poly2", "pacejka", "savkoor"])
def test_law_figure_draws_every_preset(law_id):
    import matplotlib.pyplot as plt

    law = fl.get_law(law_id)
    fig = fl_docgen.law_figure(law)
    try:
        lines = [line for ax in fig.axes for line in ax.get_lines()
                 if np.asarray(line.get_ydata()).size > 1]
        assert lines
        for line in lines:
            assert np.all(np.isfinite(np.asarray(line.get_ydata(), float)))
        text = " ".join(t.get_text() for ax in fig.axes if ax.get_legend()
                        for t in ax.get_legend().get_texts())
        titles = " ".join(ax.get_title() for ax in fig.axes)
        for preset in list(law.presets)[:3]:
            assert preset in text or preset in titles
    finally:
        plt.close(fig)


def test_escape_reST_inline_markup():
    assert fl_docgen.escape("*FRICTION, mu*p |v| a_b `x`") == (
        r"\*FRICTION, mu\*p \|v\| a\_b \`x\`")


def test_escape_bars_in_docstrings():
    lines = ["the magnitude |v| and ``|v|``", ":math:`|v|`", ".. math::", "",
             "   |v| = 1", "back |x|", "| a line block"]
    fl_docgen.escape_bars(lines)
    assert lines == [r"the magnitude \|v\| and ``|v|``", ":math:`|v|`", ".. math::", "",
                     "   |v| = 1", r"back \|x\|", "| a line block"]


# ------------------------------------------------------------ CLI and API


def _all_commands(parser, prefix=()):
    for name, sub in fl_docgen._subparsers(parser).items():
        yield (*prefix, name)
        yield from _all_commands(sub, (*prefix, name))


def test_cli_reference_documents_every_command(tmp_path):
    from frictionlaws.cli import COMMANDS, build_parser

    commands = fl_docgen.write_cli_reference(tmp_path / "cli.rst")
    assert sorted(commands) == sorted(COMMANDS)
    text = (tmp_path / "cli.rst").read_text(encoding="utf-8")
    every = list(_all_commands(build_parser()))
    assert len(every) >= len(COMMANDS)
    for path in every:
        assert f".. _cli-{'-'.join(path)}:" in text, path
        assert f"usage: frictionlaws {' '.join(path)}" in text, path


def test_api_reference_covers_public_modules(tmp_path):
    modules = fl_docgen.write_api_reference(tmp_path)
    for core in ("frictionlaws.law", "frictionlaws.law.registry", "frictionlaws.fitting",
                 "frictionlaws.io", "frictionlaws.base.units", "frictionlaws.base.errors"):
        assert core in modules
    assert not [m for m in modules if "._" in m or ".cmd_" in m]
    index = (tmp_path / "index.rst").read_text(encoding="utf-8")
    for name in fl._API:
        assert f"``fl.{name}``" in index
    for module in modules:
        assert (tmp_path / f"{module}.rst").exists()


def _rooms_table() -> str:
    page = (DOCS / "user-guide" / "adding-a-law.rst").read_text(encoding="utf-8")
    return page[page.index(".. _package-rooms:"):page.index("Where to touch for")]


def test_the_rooms_table_names_every_room_of_the_package():
    """The contributor page's map names every room (sub-package) and every loose module."""
    package = Path(fl.__file__).parent
    # _datasets/ is the top-level datasets/ folder as a wheel installs it (pyproject.toml),
    # data rather than a room of code.
    rooms = [f"``{p.name}/``" for p in package.iterdir()
             if p.is_dir() and (p / "__init__.py").is_file() and p.name != "_datasets"]
    loose = [f"``{p.name}``" for p in package.glob("*.py")
             if p.stem not in ("__init__", "__main__")]
    assert "``fitting/``" in rooms and "``base/``" in rooms
    table = _rooms_table()
    assert [r for r in rooms + loose if r not in table] == []


def test_the_rooms_table_names_every_room_of_the_law_package():
    """The contributor page's rooms table follows the law package's layout."""
    table = _rooms_table()
    row = table[table.index("``law/``"):table.index("``laws/``")]
    rooms = sorted(p.stem for p in Path(fl.law.__file__).parent.glob("*.py")
                   if p.stem != "__init__")
    assert "core" in rooms
    assert [r for r in rooms if f"``{r}``" not in row] == []


def test_shell_session_runs_the_first_fit():
    text = fl_docgen.shell_session(["fit", "--law", "thirion", "thesis-steel"])
    assert text.startswith("$ frictionlaws fit --law thirion thesis-steel\n")
    assert "1/Pa" in text and "R^2" in text


def test_shell_session_raises_on_failure():
    with pytest.raises(RuntimeError, match="exited with 2"):
        fl_docgen.shell_session(["fit", "--law", "no-such-law", "thesis-steel"])


# ------------------------------------------------------------------ gallery


def test_gallery_has_the_required_examples():
    names = {p.stem for p in GALLERY}
    required = {
        "plot_sliding_laws_thesis_steel",  # every sliding law fitted to thesis-steel
        "plot_thesis_polynomials_outside_box",
        "plot_burckhardt_vs_pacejka",
        "plot_wlf_shift",
        "plot_identifiability_nackenhorst",
        "plot_fe_export_error",
        "plot_tribometer_record",
        "plot_brush_cornering_stiffness",
    }
    assert required <= names, sorted(required - names)
    assert (EXAMPLES / "GALLERY_HEADER.rst").exists()


@pytest.mark.parametrize("path", GALLERY, ids=lambda p: p.name)
def test_gallery_file_has_title_docstring_and_cells(path):
    source = path.read_text(encoding="utf-8")
    tree = ast.parse(source)
    doc = ast.get_docstring(tree, clean=False)
    assert doc, f"{path.name}: no module docstring"
    lines = doc.strip("\n").splitlines()
    assert len(lines) >= 3, f"{path.name}: title, underline and a paragraph expected"
    title, underline = lines[0].strip(), lines[1].strip()
    assert title and re.fullmatch(r"=+", underline), f"{path.name}: RST title expected"
    assert len(underline) >= len(title), f"{path.name}: underline shorter than the title"
    assert "# %%" in source, f"{path.name}: no '# %%' cells"
    assert "plt.show()" in source or "savefig" not in source


# ------------------------------------------------------------------- pages


def test_getting_started_quotes_the_readme_commands(tmp_path):
    commands = fl_docgen.write_readme_commands(ROOT / "README.md", tmp_path)
    assert len(commands) == 2
    assert commands[0].startswith("pip install .") and "frictionlaws fit" in commands[0]
    assert "pytest" in commands[1]
    assert (tmp_path / "setup_2.txt").read_text(encoding="utf-8") == commands[1] + "\n"
    page = (DOCS / "getting-started.rst").read_text(encoding="utf-8")
    assert ".. literalinclude:: generated/shell/setup_1.txt" in page
    assert ".. literalinclude:: generated/shell/setup_2.txt" in page


def test_readme_commands_are_required(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("# x\n\n## Set-up\n\n```bash\npip install .\n```\n\n## Next\n",
                      encoding="utf-8")
    with pytest.raises(RuntimeError, match="1 command blocks, expected 2"):
        fl_docgen.readme_commands(readme)


def test_every_page_is_reachable():
    """Hand-written pages are in a toctree (Sphinx would warn, this says which)."""
    texts = {p: p.read_text(encoding="utf-8") for p in DOCS.rglob("*.rst")
             if "_build" not in p.parts and "generated" not in p.parts
             and "auto_examples" not in p.parts and p.name != "sg_execution_times.rst"}
    for path in texts:
        rel = path.relative_to(DOCS).with_suffix("").as_posix()
        if rel == "index":
            continue
        name = Path(rel).name
        parent_index = (path.parent / "index.rst") if path.name != "index.rst" else (
            path.parent.parent / "index.rst")
        assert parent_index in texts, rel
        assert re.search(rf"^\s+{re.escape(name if path.name != 'index.rst' else rel)}\s*$",
                         texts[parent_index], re.M), f"{rel} is not in a toctree"


def test_conf_uses_the_agreed_extensions():
    conf = (DOCS / "conf.py").read_text(encoding="utf-8")
    for ext in ("sphinx.ext.autodoc", "sphinx.ext.autosummary", "sphinx.ext.mathjax",
                "numpydoc", "sphinx_gallery.gen_gallery", "fl_docgen"):
        assert f'"{ext}"' in conf
    assert "intersphinx" not in conf
    assert '"abort_on_example_error": True' in conf
    assert 'html_theme = "pydata_sphinx_theme"' in conf


@pytest.mark.parametrize("example", sorted(
    (Path(__file__).resolve().parents[1] / "examples").rglob("plot_*.py")), ids=lambda p: p.stem)
def test_every_gallery_example_chooses_its_thumbnail(example):
    """Each example names the figure that stands for it, and that figure exists."""
    text = example.read_text(encoding="utf-8")
    found = re.findall(r"^# sphinx_gallery_thumbnail_number = (\d+)$", text, re.MULTILINE)
    assert len(found) == 1, f"{example.name}: no (or several) thumbnail choices"
    figures = len(re.findall(r"plt\.subplots\(|plt\.figure\(|\.plot\(\)|plot_fit_grid\(", text))
    assert 1 <= int(found[0]) <= figures, f"{example.name}: {figures} figures"


def test_the_gallery_is_in_sections_in_reading_order():
    folders = {p.parent.name for p in GALLERY}
    assert set(fl_docgen.GALLERY_SECTIONS) == folders, folders
    assert all(p.parent.parent == EXAMPLES for p in GALLERY), "an example outside a section"
    for name in fl_docgen.GALLERY_SECTIONS:
        assert (EXAMPLES / name / "GALLERY_HEADER.rst").exists(), name
    assert fl_docgen.GALLERY_SECTIONS[0] == "fitting"
    assert "Start here" in (EXAMPLES / "fitting" / "GALLERY_HEADER.rst").read_text()
    order = fl_docgen.GalleryOrder("")
    fitting = sorted((p.name for p in (EXAMPLES / "fitting").glob("plot_*.py")), key=order)
    assert fitting[0] == "plot_sliding_laws_thesis_steel.py"
    assert fl_docgen.GALLERY_FIRST[0] == fitting[0]


def test_cli_reference_has_an_anchor_per_option(tmp_path):
    fl_docgen.write_cli_reference(tmp_path / "cli.rst")
    text = (tmp_path / "cli.rst").read_text(encoding="utf-8")
    fit = text.split(".. program:: frictionlaws fit\n", 1)[1].split(".. program::", 1)[0]
    for option in (".. option:: --law LAW", ".. option:: --drop-invalid", ".. option:: DATA",
                   ".. option:: --uncertainty UNCERTAINTY"):
        assert option in fit, option
    assert ".. program:: frictionlaws tyre cornering" in text
    assert "%(default)" not in text


def test_the_public_api_page_names_objects_that_exist():
    import importlib

    text = (DOCS / "api.rst").read_text(encoding="utf-8")
    names = re.findall(r"^   ~(frictionlaws\.[\w.]+)$", text, re.M)
    assert len(names) >= 40
    for dotted in names:
        module, _, attr = dotted.rpartition(".")
        assert hasattr(importlib.import_module(module), attr), dotted
    for core in ("frictionlaws.fitting.fit", "frictionlaws.io.load_dataset",
                 "frictionlaws.comparison.core.compare", "frictionlaws.fe_export.api.export"):
        assert core in names


def test_the_changelog_is_in_the_toctree():
    assert "   changelog" in (DOCS / "index.rst").read_text(encoding="utf-8")
    assert (DOCS / "changelog.rst").read_text(encoding="utf-8").count("\n---") >= 2
