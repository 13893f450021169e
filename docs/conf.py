"""Sphinx configuration of the strapdown-analysis documentation site.

Build (from the repository root, after ``pip install '.[docs]'``)::

    sphinx-build -W -b html docs docs/_build/html

* The API reference is generated from the installed packages
  ``strapdown.analysis`` and ``strapdown.derivations`` (``_ext/api_pages.py``):
  every module is found by walking the packages and every public name (a
  module's ``__all__``, or its public definitions) is documented, so a new
  module appears without editing anything.
* The user guide, the task pages and the gallery are sphinx-gallery scripts
  under ``examples/``; every one is executed at build time, so the numbers and
  figures they show are the package's own.  A failing script fails the build.
* Mathematics is rendered by MathJax served from ``_static`` (sphinx-mathjax-offline):
  no network is needed to build or to read the site.  There is no intersphinx:
  the inventories of numpy, scipy and python-control would have to be fetched.
"""

from __future__ import annotations

import os
import sys
import warnings
from pathlib import Path

import strapdown.analysis

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))

# Figures are drawn without a display, and the package's progress bars stay off
# (stderr is the build log, not a terminal).
os.environ.setdefault("MPLBACKEND", "Agg")

project = "strapdown-analysis"
author = "strapdown-analysis contributors"
copyright = "strapdown-analysis contributors"
release = strapdown.analysis.__version__
version = release

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "sphinx-mathjax-offline",
    "numpydoc_cached",  # numpydoc, its docstring template compiled once per build (_ext/numpydoc_cached.py)
    "myst_parser",
    "sphinx_gallery.gen_gallery",
    "api_pages",  # one API page per module, generated from the installed packages (_ext/api_pages.py)
    "repository_links",  # a link to a repository file outside docs/ shows its path (_ext/repository_links.py)
    "cli_lexer",  # ``cli`` blocks: command lines whose hyphens are not operators (_ext/cli_lexer.py)
]

templates_path = ["_templates"]
exclude_patterns = ["_build", "examples", "Thumbs.db", ".DS_Store"]
source_suffix = {".rst": "restructuredtext", ".md": "markdown"}
root_doc = "index"
nitpicky = False
# Objects (functions, classes) are not entries of the page tables of contents:
# with several hundred of them the navigation of every page would carry them all.
toc_object_entries = False

# --------------------------------------------------------------------------- API reference
api_packages = ("strapdown.analysis", "strapdown.derivations")
api_intro = """
Every module of the two installed packages, generated from their docstrings at each build.
Conventions (quaternion order, frames, rotation vectors, dual numbers, the sign of errors,
steps, units) are stated once, in :mod:`strapdown.analysis`.
"""
autosummary_generate = False  # the pages come from _ext/api_pages.py
autodoc_typehints = "none"  # the numpydoc Parameters section states types and units
autodoc_member_order = "bysource"
numpydoc_show_class_members = False  # members are documented by autoclass below the class
numpydoc_class_members_toctree = False
numpydoc_attributes_as_param_list = True

# --------------------------------------------------------------------------- pages that run
sphinx_gallery_conf = {
    "examples_dirs": ["examples/concepts", "examples/tasks", "examples/gallery"],
    "gallery_dirs": ["concepts", "tasks", "gallery"],
    "filename_pattern": r".*",  # execute every script, not only plot_*.py
    "within_subsection_order": "FileNameSortKey",  # pages keep the order of their numbered file names
    # the gallery's sections in the order of the report
    "subsection_order": ["examples/gallery/coning", "examples/gallery/stability", "examples/gallery/azimuth", "examples/gallery/alignment", "examples/gallery/navigation"],
    "abort_on_example_error": False,  # run them all, then fail the build listing every failure
    "only_warn_on_example_error": False,
    "download_all_examples": False,
    "remove_config_comments": True,
    "doc_module": ("strapdown",),
    "reference_url": {"strapdown": None},  # names in the code link to this site's API reference
    "show_memory": False,
    "show_signature": False,
    "min_reported_time": 1,
    "write_computation_times": False,  # its page would load jQuery from a CDN
    "capture_repr": (),  # output is what the scripts print, not the repr of a last expression
    "image_scrapers": ("matplotlib",),
    "thumbnail_size": (320, 224),
}
# Executed scripts share this process; numba and matplotlib warnings that are not
# about the package would otherwise fail the -W build.
warnings.filterwarnings("ignore", message="Matplotlib is currently using agg", category=UserWarning)

# --------------------------------------------------------------------------- HTML
html_theme = "furo"
html_title = f"strapdown-analysis {release}"
html_static_path = ["_static"]
html_css_files = ["blocks.css"]  # code and output blocks wrap at the page width (_static/blocks.css)
html_show_sourcelink = False
html_theme_options = {
    "navigation_with_keys": True,
}
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence"]
myst_heading_anchors = 3
