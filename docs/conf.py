"""Sphinx configuration of the frictionlaws documentation.

Build (warnings are errors, the gallery is executed)::

    python -m sphinx -W --keep-going -b html docs docs/_build/html

The law catalogue, the CLI reference and the API reference are generated from
the installed package at build time by ``docs/_ext/fl_docgen.py``.
"""

from __future__ import annotations

import importlib.util
import os
import sys
import warnings
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

from fl_docgen import GALLERY_SECTIONS  # noqa: E402
from sphinx_gallery.sorting import ExplicitOrder  # noqa: E402

import frictionlaws  # noqa: E402  (the installed package is what gets documented)

project = "frictionlaws"
author = "frictionlaws developers"
copyright = "frictionlaws developers, BSD-3-Clause"
version = release = frictionlaws.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
    "fl_docgen",
]

exclude_patterns = ["_build", "Thumbs.db", ".DS_Store", "**.ipynb_checkpoints",
                    "auto_examples/*.ipynb", "auto_examples/*.py", "auto_examples/*.zip"]
root_doc = "index"
language = "en"
default_role = "py:obj"
pygments_style = "sphinx"

# -- autodoc / numpydoc ------------------------------------------------------
autodoc_default_options = {"member-order": "bysource"}
autodoc_typehints = "none"  # numpydoc "Parameters" sections carry the types
autodoc_inherit_docstrings = True
autosummary_generate = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True
numpydoc_xref_param_type = False

# -- math: MathJax 3 served with the site, so it reads offline.  The docs extra installs
# sphinx-mathjax-offline (a MathJax 3 copy on PyPI), which copies MathJax into _static;
# FRICTIONLAWS_MATHJAX=/path/to/tex-chtml.js points at another local copy; without
# either, MathJax comes from its CDN.
_local_mathjax = os.environ.get("FRICTIONLAWS_MATHJAX")
if _local_mathjax:
    mathjax_path = Path(_local_mathjax).resolve().as_uri()
elif importlib.util.find_spec("sphinx-mathjax-offline") is not None:
    extensions.append("sphinx-mathjax-offline")

# -- sphinx-gallery ------------------------------------------------------------
sphinx_gallery_conf = {
    "examples_dirs": ["../examples"],
    "gallery_dirs": ["auto_examples"],
    "filename_pattern": r"/plot_",
    "ignore_pattern": r"__init__\.py|/_",
    # sections (sub-folders of examples/) in reading order, the start-here one first
    "subsection_order": ExplicitOrder([f"../examples/{name}" for name in GALLERY_SECTIONS]),
    "within_subsection_order": "fl_docgen.GalleryOrder",
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "plot_gallery": "True",
    "image_scrapers": ("matplotlib",),
    "reset_modules": ("matplotlib",),
    "remove_config_comments": True,
    "download_all_examples": False,
    "show_memory": False,
    "show_signature": False,
    "capture_repr": ("_repr_html_", "__repr__"),
    "min_reported_time": 1,
    "matplotlib_animations": False,
    "reference_url": {},
    "backreferences_dir": None,
    "doc_module": (),
    "inspect_global_variables": False,
    "parallel": 2,  # the examples run two at a time (CI has two cores)
}
# Examples show the library's own warnings (extrapolation, identifiability) in
# their output; third-party deprecation chatter is not part of the story.
warnings.filterwarnings("ignore", category=DeprecationWarning, module="matplotlib")

# -- HTML ------------------------------------------------------------------------
html_theme = "pydata_sphinx_theme"
html_title = f"frictionlaws {release}"
html_static_path = ["_static"]
html_css_files = ["frictionlaws.css"]
html_show_sourcelink = False
html_last_updated_fmt = None
html_theme_options = {
    "navbar_align": "left",
    "show_toc_level": 2,
    "navigation_depth": 3,
    "collapse_navigation": True,
    "show_nav_level": 1,
    # wide tables (catalogue index, CLI reference) get the full width
    # pages not named here get the theme's default (the page's table of contents)
    "secondary_sidebar_items": {"generated/catalogue/index": [],
                                "generated/api/index": [], "index": [], "api": [],
                                "auto_examples/**": [], "changelog": []},
    "footer_start": ["copyright"],
    "footer_end": ["sphinx-version"],
    "navbar_end": ["theme-switcher"],
    "header_links_before_dropdown": 7,
    "use_edit_page_button": False,
    "pygments_light_style": "tango",
    "pygments_dark_style": "monokai",
}
html_context = {"default_mode": "light"}
# the gallery, its examples and the API overview use the full width (multi-panel figures,
# long code lines)
html_sidebars = {"index": [], "getting-started": [], "generated/cli": [], "api": [],
                 "auto_examples/**": []}
