"""Sphinx configuration of the foilbearing documentation site (``make docs``).

Sphinx reads the Markdown pages through MyST, the numpydoc docstrings through numpydoc and
autodoc/autosummary, and runs the tutorials and the gallery (``docs/tutorials/*.py``,
``docs/gallery/*.py``) with sphinx-gallery at every build, so that they cannot rot.
"""

from __future__ import annotations

import os
import re
import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
ROOT = DOCS.parent
sys.path.insert(0, str(ROOT / "src"))
sys.path.insert(0, str(DOCS))  # figure_scraper
# The gallery's scripts run in this process: no display, and no progress bars.
os.environ.setdefault("MPLBACKEND", "Agg")
os.environ.setdefault("FOILBEARING_COMPILE_NOTICE", "0")

project = "foilbearing"
author = "the foilbearing developers"
copyright = "the foilbearing developers, BSD-3-Clause"
release = "0.1.0"

extensions = [
    "myst_parser",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "sphinx_gallery.gen_gallery",
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "**/README.md", "tutorials/*.py", "gallery/*.py", "figure_scraper.py"]

# MyST: anchors for headings down to level 4 (the pages link to their sections by them),
# $...$ maths, and the GitHub-style tables the pages use.
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
suppress_warnings = ["myst.header"]

# numpydoc: the docstrings' sections, no class-member tables of their own (autosummary lists them).
numpydoc_show_class_members = False
numpydoc_validation_checks: set[str] = set()
numpydoc_xref_param_type = False
autosummary_generate = True
autodoc_default_options = {"members": True, "undoc-members": False}
autodoc_typehints = "none"
# ROSS (the `ross` extra) takes most of a minute to import on a loaded machine; the
# reference needs only the names of what foilbearing.rotor imports from it.
autodoc_mock_imports = ["ross", "ccp"]

sphinx_gallery_conf = {
    "examples_dirs": ["tutorials", "gallery"],
    "gallery_dirs": ["generated/tutorials", "generated/gallery"],
    "filename_pattern": r"/plot_",  # run these; the others are shown, not run
    "download_all_examples": False,
    "remove_config_comments": True,
    "within_subsection_order": "FileNameSortKey",
    "matplotlib_animations": False,
    "show_memory": False,
    "image_scrapers": ("figure_scraper.result_figures", "matplotlib"),
    "abort_on_example_error": True,
    # No page that loads scripts from a CDN (the timing tables), no link off the site.
    "write_computation_times": False,
    "show_signature": False,
}


def _escape_bars(text: str) -> str:
    """``|`` as reStructuredText reads it, a literal bar, outside inline literals: the
    docstrings write |x| for a magnitude, which docutils would take for a substitution."""
    parts = text.split("``")
    for i in range(0, len(parts), 2):  # the even parts are outside ``...``
        parts[i] = re.sub(r"(?<!\\)\|", r"\\|", parts[i])
    return "``".join(parts)


def _magnitudes(app, what, name, obj, options, lines: list[str]) -> None:
    for i, line in enumerate(lines):
        if not line.lstrip().startswith(("|", "+-", "+=")):
            lines[i] = _escape_bars(line)


def setup(app) -> None:
    app.connect("autodoc-process-docstring", _magnitudes, priority=400)


html_theme = "pydata_sphinx_theme"
html_title = "foilbearing"
html_theme_options = {
    "navigation_with_keys": False,
    "show_toc_level": 2,
    "secondary_sidebar_items": ["page-toc"],
    "footer_start": ["copyright"],
    "footer_end": [],
}
html_context = {"default_mode": "light"}
html_static_path: list[str] = []
html_show_sourcelink = False
html_copy_source = False
