"""Import cost: sympy loads only when symbolic work starts (docs/architecture.md §4).

``import screwkit`` (and every module but :mod:`screwkit.gca.conditions` and the modules it is built
on, whose vector forms subclass ``sympy.Function``) must not import sympy, nor must a numeric
analysis; the symbolic branch loads it on first use. Each check runs in a fresh interpreter, since this test session has imported sympy.
"""

import pkgutil
import subprocess
import sys

import pytest

import screwkit
import screwkit.robots.families as families

SYMBOLIC_MODULES = {  # sympy expressions all the way down
    "screwkit.gca.combined_brackets",
    "screwkit.gca.conditions",
    "screwkit.gca.condition_patterns",
    "screwkit.gca.exact_proofs",
    "screwkit.gca.vector_forms",
}
MODULES = sorted(
    info.name for info in pkgutil.walk_packages(screwkit.__path__, "screwkit.")
    if info.name not in SYMBOLIC_MODULES and info.name != "screwkit.__main__"
)


def _sympy_loaded_after(code: str) -> bool:
    probe = f"{code}\nimport sys\nprint('sympy' in sys.modules)"
    result = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True, timeout=120, check=True)
    return result.stdout.split()[-1] == "True"


def test_import_screwkit_does_not_import_sympy():
    assert not _sympy_loaded_after("import screwkit")


def test_no_module_imports_sympy():
    # one interpreter imports the modules in turn; the first to bring sympy in is named
    code = (
        f"import importlib, sys\nfor name in {MODULES!r}:\n    importlib.import_module(name)\n"
        "    if 'sympy' in sys.modules:\n        print(name)\n        break"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    assert result.stdout.strip() == "", f"importing {result.stdout.strip()} (or one of its imports) imports sympy"


def test_numeric_analysis_does_not_import_sympy():
    code = "from screwkit.interface.report import analyze\nanalyze('h4', superbracket=False)"
    assert not _sympy_loaded_after(code)


@pytest.mark.parametrize(
    "code",
    [
        "import screwkit.gca.conditions",
        "from screwkit.algebra.backend import to_sympy\nto_sympy(0.5)",
        "from screwkit.gca import Bracket\nBracket('abcd').to_sympy({c: [0, 0, 0, 1] for c in 'abcd'})",
    ],
)
def test_symbolic_work_imports_sympy(code):
    # the probe can tell: symbolic work does load sympy, on first use
    assert _sympy_loaded_after(code)


@pytest.mark.parametrize(("name", "family"), [("h4", "four_limb"), ("planar_3rrp", "planar_3rrp")])
def test_a_command_imports_only_the_family_it_analyses(name, family):
    # the registry makes a built-in family on first look-up; the map command's options read the
    # families' pose coordinates without importing them
    code = (
        "import sys\nfrom screwkit.interface.cli import main\n"
        f"main(['analyze', {name!r}, '--no-superbracket'])\n"
        "print(*sorted(m.split('.')[3] for m in sys.modules if m.startswith('screwkit.robots.families.')))"
    )
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True)
    loaded = set(result.stdout.splitlines()[-1].split())
    assert family in loaded
    shipped = {info.name for info in pkgutil.iter_modules(families.__path__) if not info.name.startswith("_")}
    assert family in shipped and loaded == {family}
