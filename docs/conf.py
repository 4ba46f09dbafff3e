"""Sphinx configuration of the edmd2d documentation (see docs/README.md to build it)."""

from __future__ import annotations

import os
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "_ext"))

import edmd2d  # noqa: E402  (installed: python -m pip install -e ".[docs]")

project = "edmd2d"
author = "the edmd2d developers"
copyright = "edmd2d developers, MIT licence"
release = version = edmd2d.__version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "numpydoc",
    "myst_parser",
    "edmd2d_docs",  # docs/_ext: the runcode and example directives, API coverage check
]

source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
exclude_patterns = ["_build", "README.md", "Thumbs.db", ".DS_Store"]
templates_path: list[str] = []

# Every reference must resolve: a broken link inside the documentation fails the build.
nitpicky = True
# References to other packages cannot resolve here: the build runs without network
# access, so there is no intersphinx inventory of numpy, matplotlib, Python, ...
nitpick_ignore_regex = [
    (r"py:.*", r"(numpy|np|matplotlib|mpl|scipy|tqdm|gsd|os|pathlib|collections|typing|"
               r"dataclasses|argparse)(\..*)?"),
]

# The API reference: numpy-style docstrings through numpydoc, signatures without type
# hints (the docstrings state types, shapes and units).
autodoc_typehints = "none"
autodoc_member_order = "bysource"
autosummary_generate = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False

# Markdown pages: GitHub-style anchors for the links between sections.
myst_heading_anchors = 3
myst_enable_extensions = ["colon_fence"]

# The example gallery (docs/gallery/): EDMD2D_DOCS_GALLERY=quick (default), full or off.
edmd2d_examples_dir = "../examples"
# Links of the Markdown pages to files outside docs/ -> the page that covers each.
edmd2d_outside_links = {"benchmarks/README.md": "guide/performance.md"}

html_theme = "furo"
html_title = f"edmd2d {release}"
html_static_path = ["_static"]
html_css_files = ["edmd2d.css"]
html_show_sourcelink = False
html_copy_source = False

# The numba JIT cache stays where the package keeps it; matplotlib draws off-screen.
os.environ.setdefault("MPLBACKEND", "Agg")
