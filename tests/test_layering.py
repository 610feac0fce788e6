"""The package's architecture as a test: imports run only downward along the data flow.

Every import in every module of ``screwkit`` is parsed (function-level ones included) and checked
against the layers of ``docs/architecture.md``: a module may import a module of its own layer
(without closing a cycle) or of a layer below it, never one above; and no private name (one
starting with ``_``, module or attribute, imported or read as ``module._name``) crosses a
subpackage.
"""

from __future__ import annotations

import ast
import pathlib

import networkx as nx
import pytest

PACKAGE = pathlib.Path(__file__).resolve().parents[1] / "screwkit"

#: The layers from the bottom up (docs/architecture.md). A module's layer is its subpackage; the
#: top-level modules are named.
LAYERS = (
    "version",
    "exceptions",
    "algebra",
    "graphs",
    "core",
    "gca",
    "robots",
    "testing",
    "analysis",
    "papers",
    "interface",
    "__init__",
    "__main__",
)


def _modules() -> dict[str, pathlib.Path]:
    found = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        name = ".".join(parts[:-1] if parts[-1] == "__init__" else parts)
        found[name] = path
    return found


MODULES = _modules()


def layer(module: str) -> str:
    """The layer of a module of the package (``screwkit.core.wrenches`` -> ``core``)."""
    parts = module.split(".")
    return "__init__" if len(parts) == 1 else parts[1]


def imports(module: str) -> list[tuple[str, str, int]]:
    """``(imported module, imported name or '', line)`` for every screwkit import of a module."""
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    found = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            found += [(a.name, "", node.lineno) for a in node.names if a.name.split(".")[0] == "screwkit"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")[: len(package.split(".")) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            if target.split(".")[0] != "screwkit":
                continue
            for alias in node.names:
                full = f"{target}.{alias.name}"
                if full in MODULES:  # a module imported by name
                    found.append((full, "", node.lineno))
                else:
                    found.append((target, alias.name, node.lineno))
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and "." in node.value \
                and node.value in MODULES:
            # a module named by a string (importlib.import_module, compiled_kernels): an import
            found.append((node.value, "", node.lineno))
    return found


def module_attributes(module: str) -> list[tuple[str, str, int]]:
    """``(module, attribute, line)`` for every ``alias.attribute`` read of a screwkit module
    imported under a name (``from ..algebra import projective as P`` ... ``P.LAPLACE``)."""
    aliases = {}
    tree = ast.parse(MODULES[module].read_text(encoding="utf-8"))
    path = MODULES[module]
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):  # import screwkit.algebra.backend as B
            aliases.update((a.asname, a.name) for a in node.names if a.asname and a.name in MODULES)
        elif isinstance(node, ast.ImportFrom):
            base = package.split(".")[: len(package.split(".")) - node.level + 1] if node.level else []
            target = ".".join(base + ([node.module] if node.module else [])) if node.level else node.module
            for alias in node.names:
                if f"{target}.{alias.name}" in MODULES:
                    aliases[alias.asname or alias.name] = f"{target}.{alias.name}"
    return [
        (aliases[node.value.id], node.attr, node.lineno)
        for node in ast.walk(tree)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in aliases
    ]


def test_every_layer_is_known():
    assert {layer(m) for m in MODULES} <= set(LAYERS)


def test_imports_run_downward():
    upward = []
    for module in MODULES:
        for target, _, line in imports(module):
            if target in MODULES and LAYERS.index(layer(target)) > LAYERS.index(layer(module)):
                upward.append(f"{module}:{line} imports {target}")
    assert upward == []


def test_no_import_cycle():
    graph = nx.DiGraph()
    graph.add_nodes_from(MODULES)
    for module in MODULES:
        for target, _, _ in imports(module):
            # a package's __init__ is imported by every import of its modules: count only the
            # modules, the package itself where it is imported by name
            if target in MODULES and target != module and not module.startswith(target + "."):
                graph.add_edge(module, target)
    assert [sorted(c) for c in nx.simple_cycles(graph)] == []


def test_no_private_name_crosses_a_subpackage():
    def subpackage(module: str) -> str:
        return module.rpartition(".")[0] if MODULES[module].name != "__init__.py" else module

    crossing = []
    for module in MODULES:
        reads = [(target, name, line) for target, name, line in module_attributes(module)]
        for target, name, line in imports(module) + reads:
            if target not in MODULES or subpackage(target) == subpackage(module):
                continue
            leaf = target.rpartition(".")[2]
            private = (name.startswith("_") and not name.startswith("__")) or (
                leaf.startswith("_") and not leaf.startswith("__")
            )
            if private:
                crossing.append(f"{module}:{line} imports {target}{':' + name if name else ''}")
    assert crossing == []


@pytest.mark.parametrize("module", sorted(MODULES))
def test_module_size(module):
    """Modules of one responsibility: at most 600 lines, unless the docstring says it is one
    algorithm that does not split (``One algorithm:`` in its first paragraph)."""
    text = MODULES[module].read_text(encoding="utf-8")
    lines = text.count("\n")
    doc = ast.get_docstring(ast.parse(text)) or ""
    assert lines <= 600 or "One algorithm:" in doc, f"{module}: {lines} lines"


def test_the_checks_see_string_imports_and_module_aliases(tmp_path, monkeypatch):
    """What the parser must not miss: a module named by a string (importlib.import_module) and a
    private attribute read through ``import screwkit.x.y as Y``."""
    probe = tmp_path / "probe.py"
    probe.write_text(
        "import importlib\nimport screwkit.core.frames as F\n\n\n"
        "def f():\n    F._hidden\n    return importlib.import_module('screwkit.interface.cli')\n",
        encoding="utf-8",
    )
    monkeypatch.setitem(MODULES, "screwkit.algebra.probe", probe)
    assert ("screwkit.interface.cli", "", 7) in imports("screwkit.algebra.probe")
    assert ("screwkit.core.frames", "_hidden", 6) in module_attributes("screwkit.algebra.probe")
