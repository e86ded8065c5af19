"""Sphinx configuration of the dustygas documentation (``python -m sphinx -W -b html docs docs/_build/html``)."""

import sys
from pathlib import Path

HERE = Path(__file__).parent
sys.path.insert(0, str(HERE / "_ext"))
sys.path.insert(0, str(HERE.parent / "src"))

from dustygas import __version__  # noqa: E402

project = "dustygas"
author = "dustygas developers"
copyright = "dustygas developers"
version = release = __version__

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.napoleon",
    "sphinx.ext.mathjax",
    "dustygas_docs",
]
napoleon_numpy_docstring = True
napoleon_google_docstring = False
napoleon_use_rtype = False
autodoc_member_order = "bysource"
autodoc_typehints = "description"
autodoc_default_options = {"members": True, "undoc-members": False, "show-inheritance": False}
suppress_warnings = ["ref.python"]  # ambiguous short cross-references inside numpy docstrings
nitpicky = False
exclude_patterns = ["_build", "tutorials/*.py", "generated/schema.rst", "generated/figures.rst"]
html_theme = "alabaster"
html_title = f"dustygas {__version__}"
html_static_path = []
templates_path = []
