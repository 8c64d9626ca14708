"""Sphinx configuration: build with `sphinx-build -W -b html docs docs/_build/html` after
`pip install ".[docs]"` (see the README, "Documentation")."""

from __future__ import annotations

import os
from pathlib import Path

import lambda_bezier

ROOT = Path(__file__).resolve().parent.parent
# The tutorials are the notebooks of notebooks/ (symlinked into docs/tutorials/), executed by
# myst-nb at build time. Their PNGs go to the build tree, not into notebooks/figures/, and
# matplotlib draws inline in the kernel.
os.environ.setdefault("LAMBDA_BEZIER_FIGURES", str(ROOT / "docs" / "_build" / "notebook_figures"))
os.environ.pop("MPLBACKEND", None)
project = "lambda-bezier"
author = "the lambda-bezier authors"
copyright = "the lambda-bezier authors"
release = version = lambda_bezier.__version__

extensions = [
    "myst_nb",
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "sphinx.ext.viewcode",
]

# conf.py is Python too: without this myst-nb would run it as a notebook
exclude_patterns = ["_build", "jupyter_execute", "**/.ipynb_checkpoints", "conf.py"]
templates_path = ["_templates"]
default_role = "code"  # the docstrings quote names in single backticks
# derive/published/README.md (included) shows a schematic TOML table with "[ ... ]" in it
suppress_warnings = ["misc.highlighting_failure"]

# MyST: $...$ and $$...$$ math, ::: fences, and definition lists in the guide pages
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "deflist"]
myst_heading_anchors = 3

# myst-nb reads the jupytext percent scripts directly and runs them at build time
nb_custom_formats = {".py": ["jupytext.reads", {"fmt": "py:percent"}]}
nb_execution_mode = "force"
# A cell's timeout also bounds a known nbclient stall (jupyter/nbclient#312): when a cell
# exchanges widget messages, the execute reply is sometimes picked up only when the wait for it
# times out, and the build then goes on as if nothing happened. Seen here on about one build in
# three, always in interactive_lambda.py, which therefore sets its own 30 s timeout in its
# header (its cells take about 2 s); the others get 120 s (their longest cell takes about 10 s
# on a loaded 2-core machine).
nb_execution_timeout = 120
nb_execution_raise_on_error = True
nb_execution_show_tb = True
nb_merge_streams = True

# autodoc: numpydoc-style sections through Napoleon, members of every public class
autosummary_generate = True
autosummary_imported_members = True
# the class template (_templates/autosummary/class.rst) is one autoclass; these fill it in
autodoc_default_options = {
    "members": True,
    "inherited-members": True,
    "show-inheritance": True,
    "exclude-members": "__init__",
}
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_typehints_description_target = "documented"  # types only where a docstring says more
autodoc_typehints_format = "short"
autodoc_preserve_defaults = True
napoleon_google_docstring = False
napoleon_numpy_docstring = True
napoleon_use_rtype = False

html_theme = "pydata_sphinx_theme"
html_title = f"lambda-bezier {release}"
html_theme_options = {"navigation_with_keys": False, "show_toc_level": 2}
