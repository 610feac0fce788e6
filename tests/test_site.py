"""The documentation site builds with warnings as errors and documents every public name.

The build is the documented command (``python -m sphinx -W --keep-going -n -b html docs OUT``):
``-W`` turns every warning into a failure and ``-n`` (nitpicky) makes every link into the API
that does not resolve a warning (``docs/_ext/api_pages.py`` says which docstring links are
checked). The notebooks are rendered from the copies ``tests/test_notebooks.py`` executed in this
session when all are there, else executed by the build. The check of the API reference reads the
built site's inventory (``objects.inv``) and pages, and takes the expected names from the modules'
``__all__`` directly, not from the page generator.
"""

import importlib
import os
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

pytest.importorskip("sphinx", reason="the docs extra is not installed")
pytest.importorskip("myst_nb", reason="the docs extra is not installed")
pytest.importorskip("numpydoc", reason="the docs extra is not installed")
pytest.importorskip("matplotlib", reason="the API pages import screwkit's plot modules")
from sphinx.util.inventory import InventoryFile

import screwkit

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = sorted(p.name for p in (ROOT / "notebooks").glob("*.ipynb"))


def _public_modules():
    names = ["screwkit"] + [
        info.name
        for info in pkgutil.walk_packages(screwkit.__path__, "screwkit.")
        if not any(part.startswith("_") for part in info.name.split("."))
    ]
    return {name: importlib.import_module(name) for name in names}


@pytest.fixture(scope="module")
def site(tmp_path_factory, executed_notebooks):
    out = tmp_path_factory.mktemp("docs_site")
    env = dict(os.environ, MPLBACKEND="Agg")
    if all((executed_notebooks / name).is_file() for name in NOTEBOOKS):
        env["SCREWKIT_EXECUTED_NOTEBOOKS"] = str(executed_notebooks)
    command = [sys.executable, "-m", "sphinx", "-W", "--keep-going", "-n", "-q", "-b", "html",
               "-d", str(out / "doctrees"), "docs", str(out / "html")]
    run = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=900)
    assert run.returncode == 0, f"the docs build failed:\n{run.stderr[-8000:]}"
    return out / "html"


def test_every_public_name_has_an_entry_linked_from_its_module_page(site):
    with open(site / "objects.inv", "rb") as stream:
        inventory = InventoryFile.load(stream, "", lambda base, uri: uri)
    documented = {
        name: item.uri for role, entries in inventory.items() if role.startswith("py:") for name, item in entries.items()
    }
    missing = []
    for module_name, module in _public_modules().items():
        assert module_name in documented, f"no page for module {module_name}"
        page = (site / "api" / f"{module_name}.html").read_text()
        for name in module.__all__:
            obj = getattr(module, name)
            home = getattr(obj, "__module__", None)
            candidates = [f"{module_name}.{name}"]
            if home and getattr(sys.modules.get(home), name, None) is obj:
                candidates.append(f"{home}.{name}")  # a re-export, documented where it is defined
            found = [c for c in candidates if c in documented]
            if not found or not any(f'id="{c}"' in page or f'#{c}"' in page for c in found):
                missing.append(f"{module_name}.{name}")
    assert not missing, f"public names without an API entry linked from their module's page: {missing}"


def test_every_docs_page_is_in_the_site(site):
    pages = [p.relative_to(ROOT / "docs").with_suffix(".html") for p in (ROOT / "docs").glob("**/*.md")]
    pages = [p for p in pages if not str(p).startswith(("_build", "api", "gallery"))]
    assert pages and all((site / p).is_file() for p in pages), [p for p in pages if not (site / p).is_file()]
    gallery = [(site / "gallery" / name).with_suffix(".html") for name in NOTEBOOKS]
    assert all(p.is_file() for p in gallery)
    # executed: the first notebook's figures and outputs are on its page
    assert 'class="cell_output' in gallery[0].read_text()
