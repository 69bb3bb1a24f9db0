"""Sphinx configuration of the axiscal site (``make docs``; warnings fail the build)."""

from __future__ import annotations

import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

import _generate  # noqa: E402  (docs/_generate.py: the CLI and file-format pages)

import axiscal  # noqa: E402

_generate.generate()

project = "axiscal"
author = "axiscal developers"
copyright = "2026, axiscal developers"
release = version = axiscal.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
    "numpydoc",
    "myst_parser",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
exclude_patterns = ["_build", "gallery/README.txt", "auto_examples/*.ipynb",
                    "auto_examples/*.py", "auto_examples/*.zip", "auto_examples/*.md5",
                    "auto_examples/*.codeobj.json", "**.ipynb_checkpoints"]
root_doc = "index"
smartquotes = False     # option names (--data) must stay two hyphens, not an en dash

# The API reference: numpydoc renders the docstrings' Parameters/Returns/Notes sections.
autodoc_member_order = "bysource"
autodoc_typehints = "none"          # numpydoc's type lines carry the units
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
numpydoc_xref_param_type = False

# The existing Markdown pages (standards, limits, Renishaw, EPICS) through MyST. standards.md
# goes from its title (H1) to H3 sections on purpose (they hang under the table); that is the
# only warning silenced ("Non-consecutive header level increase"), every other one fails.
myst_heading_anchors = 3
suppress_warnings = ["myst.header"]

sphinx_gallery_conf = {
    "examples_dirs": "gallery",
    "gallery_dirs": "auto_examples",
    "filename_pattern": r"plot_",
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "image_scrapers": ("matplotlib",),
    "matplotlib_animations": False,
    "reset_modules": ("matplotlib",),
    "abort_on_example_error": True,
    "only_warn_on_example_error": False,
    "show_memory": False,
}

html_theme = "pydata_sphinx_theme"
html_title = f"axiscal {release}"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
}
html_static_path: list[str] = []
html_show_sourcelink = False
