"""Sphinx configuration of screwkit's documentation site.

Build: ``python -m sphinx -W --keep-going -n -b html docs docs/_build/html`` (the ``docs`` extra).
The API reference (``api/``) is generated at each build from every public module's ``__all__``
(``_ext/api_pages.py``); the notebook gallery (``gallery/``) from ``notebooks/*.ipynb``
(``_ext/gallery.py``): executed copies given by ``SCREWKIT_EXECUTED_NOTEBOOKS`` (the test suite's
own runs) are rendered as they are, else the notebooks are executed during the build.
"""

import sys
from pathlib import Path

DOCS = Path(__file__).resolve().parent
sys.path.insert(0, str(DOCS / "_ext"))
sys.path.insert(0, str(DOCS.parent))  # this checkout's screwkit, whatever is installed

import screwkit  # noqa: E402
from gallery import prepare  # noqa: E402

project = "screwkit"
author = "The screwkit developers"
copyright = "2025-2026, the screwkit developers"  # noqa: A001 (Sphinx's name)
release = screwkit.__version__
version = ".".join(release.split(".")[:2])

extensions = [
    "sphinx.ext.autodoc",
    "sphinx.ext.autosummary",
    "sphinx.ext.mathjax",
    "numpydoc",
    "myst_nb",
    "api_pages",
]

exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints", "README.md"]
source_suffix = {".rst": "restructuredtext", ".md": "myst-nb", ".ipynb": "myst-nb"}
root_doc = "index"

# the API: numpydoc sections, no type-hint cross references (the types are in the Parameters
# sections; the signatures' annotations would need intersphinx, which needs the network)
autodoc_typehints = "none"
autodoc_member_order = "bysource"
autosummary_generate = False
numpydoc_show_class_members = False
numpydoc_class_members_toctree = False
numpydoc_xref_param_type = False
# numpydoc's References sections list sources that the text need not mark with [1]
suppress_warnings = ["ref.citation"]
nitpicky = True  # every link into the API must resolve (the build runs with -W); see api_pages.py

# MyST: $...$ maths, definition lists, ::: fences; headings get anchors for links into pages
myst_enable_extensions = ["dollarmath", "colon_fence", "deflist"]
myst_heading_anchors = 3
nb_execution_mode = prepare(DOCS)  # "off" when the tests' executed copies are given
nb_execution_timeout = 180
nb_execution_raise_on_error = True
nb_merge_streams = True

html_theme = "furo"
html_title = f"screwkit {release}"
html_static_path: list[str] = []
