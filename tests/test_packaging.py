"""Packaging: a plain (non-editable) ``pip install`` ships the catalog of the top-level ``mechanisms/``.

The catalog's TOML files live outside the ``screwkit/`` folder and are installed as package data of
``screwkit.mechanisms`` through a setuptools ``package-dir`` mapping; an editable install (which runs the
rest of the suite) resolves that mapping with its own import hook, so only a real install checks it.
The install runs offline: a fresh virtual environment sees this interpreter's site-packages (numpy,
sympy, networkx, setuptools, wheel) through a ``.pth`` line, and pip builds with
``--no-build-isolation --no-deps --no-index``. (``venv --system-site-packages`` would not do: from inside a
virtual environment it exposes the base interpreter's packages, not this environment's.)
"""

import importlib.util
import shutil
import site
import subprocess
import sys
import venv
from pathlib import Path

import pytest

from screwkit.robots.catalog import list_mechanisms

REPO = Path(__file__).resolve().parents[1]
CATALOG = sorted(p.stem for p in (REPO / "mechanisms").glob("*.toml"))


def _run(args, cwd):
    return subprocess.run(args, cwd=cwd, capture_output=True, text=True, timeout=120, check=True).stdout


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """A copy of the source installed non-editably into a fresh virtual environment: (python, bin, source)."""
    if importlib.util.find_spec("venv") is None or importlib.util.find_spec("pip") is None:
        pytest.skip("the packaging check needs the venv module and pip in this interpreter")
    tmp = tmp_path_factory.mktemp("packaging")
    source = tmp / "source"  # a copy, so the build leaves no build/ or egg-info in the repository
    ignore = shutil.ignore_patterns("__pycache__", "*.egg-info")
    for name in ("screwkit", "mechanisms"):
        shutil.copytree(REPO / name, source / name, ignore=ignore)
    for name in ("pyproject.toml", "README.md"):
        shutil.copy2(REPO / name, source / name)
    env = tmp / "venv"
    venv.EnvBuilder(with_pip=False).create(env)
    bindir = env / ("Scripts" if sys.platform == "win32" else "bin")
    python = bindir / Path(sys.executable).name
    purelib = Path(_run([python, "-c", "import sysconfig; print(sysconfig.get_path('purelib'))"], tmp).strip())
    parents = [*site.getsitepackages(), *([site.getusersitepackages()] if site.ENABLE_USER_SITE else [])]
    (purelib / "_screwkit_test_parent.pth").write_text("\n".join(parents) + "\n")
    _run(
        [python, "-m", "pip", "install", "--quiet", "--no-deps", "--no-build-isolation", "--no-index",
         "--ignore-installed", "--disable-pip-version-check", str(source)],
        tmp,
    )
    return python, bindir, source


def test_the_catalog_is_the_mechanisms_folder():
    # every catalog file is an entry, whatever their number (adding a robot is adding its file)
    assert CATALOG and list_mechanisms() == CATALOG


def test_installed_cli_lists_the_whole_catalog(installed, tmp_path):
    python, bindir, _ = installed
    where = _run([python, "-c", "import screwkit; print(screwkit.__file__)"], tmp_path)
    assert Path(where.strip()).is_relative_to(bindir.parent)  # the installed copy, not this checkout
    listed = [line.split()[0] for line in _run([bindir / "screwkit", "list"], tmp_path).splitlines()]
    assert listed == CATALOG


def test_source_tree_shadowing_the_install_still_finds_the_catalog(installed):
    # ``python -m pytest`` from the repository root imports screwkit from the source tree, whose
    # screwkit/ folder has no mechanisms/; the installed package data must still be found.
    python, _, source = installed
    code = "import screwkit, screwkit.robots.catalog as c; print(screwkit.__file__); print(*c.list_mechanisms())"
    where, names = _run([python, "-c", code], source).splitlines()
    assert Path(where) == source / "screwkit" / "__init__.py"
    assert names.split() == CATALOG
