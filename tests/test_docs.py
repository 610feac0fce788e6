"""Every public function and class has a numpydoc docstring with an Examples section (run as a doctest)."""

import ast
import builtins
import importlib
import inspect
import pathlib
import pkgutil
import re

import pytest
from numpydoc.validate import validate

import screwkit

MODULES = sorted(
    info.name for info in pkgutil.walk_packages(screwkit.__path__, "screwkit.")
    if not info.name.rsplit(".", 1)[-1].startswith("_") and info.name != "screwkit.__main__"
)


def public_objects():
    for name in MODULES:
        module = importlib.import_module(name)
        for attribute in getattr(module, "__all__", []):
            value = getattr(module, attribute)
            if inspect.isfunction(value) or inspect.isclass(value):
                if value.__module__ == name:  # defined here, not re-exported
                    yield pytest.param(value, id=f"{name}.{attribute}")


@pytest.mark.parametrize("module_name", MODULES)
def test_module_has_a_docstring_and_all(module_name):
    module = importlib.import_module(module_name)
    assert module.__doc__ and module.__doc__.strip()
    if module_name not in ("screwkit.mechanisms", "screwkit.robots.families"):  # packages of modules / data
        assert hasattr(module, "__all__"), f"{module_name} has no __all__"


@pytest.mark.parametrize("obj", list(public_objects()))
def test_public_object_has_an_example(obj):
    doc = inspect.getdoc(obj) or ""
    documented = "Examples\n--------" in doc or (
        # dataclasses and exceptions documented by their module's or constructor's examples
        inspect.isclass(obj) and (issubclass(obj, Exception) or "Attributes\n----------" in doc)
    )
    assert doc and documented, f"{obj.__module__}.{obj.__qualname__} lacks a docstring with Examples"


def public_callables():
    """Every public function of a public module and every public method of its public classes."""
    for name in MODULES:
        module = importlib.import_module(name)
        for attribute in getattr(module, "__all__", []):
            value = getattr(module, attribute)
            if getattr(value, "__module__", None) != name:
                continue
            if inspect.isfunction(value):
                yield pytest.param(f"{name}.{attribute}", id=f"{name}.{attribute}")
            elif inspect.isclass(value) and not issubclass(value, Exception):
                for method, member in vars(value).items():
                    if method.startswith("_") or not (
                        inspect.isfunction(member) or isinstance(member, classmethod | staticmethod)
                    ):
                        continue
                    yield pytest.param(f"{name}.{attribute}.{method}", id=f"{name}.{attribute}.{method}")


#: numpydoc's validation codes this project holds every public callable to: every parameter
#: documented (PR01), no documented parameter that does not exist (PR02), a Returns section when
#: the callable returns a value (RT01), a Yields section for a generator (YD01).
REQUIRED = ("PR01", "PR02", "RT01", "YD01")


@pytest.mark.parametrize("qualname", list(public_callables()))
def test_public_callable_documents_parameters_and_returns(qualname):
    errors = [f"{code}: {message}" for code, message in validate(qualname)["errors"] if code in REQUIRED]
    assert errors == [], qualname


# --- cited paths: every `screwkit.a.b` in the docstrings and the docs names a module, or a name defined
# in one (read from the source, so modules of optional dependencies count too), and every file path
# cited exists. The subpackage split moved names; a citation of the old home must fail here.

_ROOT = pathlib.Path(__file__).resolve().parents[1]
_CITING = [
    *sorted((_ROOT / "screwkit").rglob("*.py")),
    _ROOT / "README.md",
    _ROOT / "CONTRIBUTING.md",
    *sorted((_ROOT / "docs").glob("*.md")),
]
_NOT_CODE = {"screwkit.mechanisms"}  # the catalog's data folder (a package of TOML files)


def _module_file(dotted):
    path = _ROOT.joinpath(*dotted.split("."))
    for candidate in (path.with_suffix(".py"), path / "__init__.py"):
        if candidate.is_file():
            return candidate
    return None


def _names(body):
    """The names a module or class body defines: functions, classes, assignments and imports."""
    found = {}
    for node in body:
        if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
            found[node.name] = node
        elif isinstance(node, ast.Assign):
            found.update((t.id, node) for t in node.targets if isinstance(t, ast.Name))
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name):
            found[node.target.id] = node
        elif isinstance(node, ast.Import | ast.ImportFrom):
            found.update(((a.asname or a.name).split(".")[0], node) for a in node.names)
        elif isinstance(node, ast.If | ast.Try):
            found.update(_names(node.body))
            found.update(_names(getattr(node, "orelse", [])))
    return found


def _imported(dotted):
    """The object at ``dotted`` once imported (names made at import: the package's lazy names,
    dataclass fields), or None."""
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        try:
            value = importlib.import_module(".".join(parts[:i]))
        except ImportError:
            continue
        for name in parts[i:]:
            fields = getattr(value, "__dataclass_fields__", {})
            value = fields[name] if name in fields else getattr(value, name, None)
            if value is None:
                return None
        return value
    return None


def _resolves(dotted):
    if _imported(dotted) is not None:
        return True
    parts = dotted.split(".")
    for i in range(len(parts), 0, -1):
        module = ".".join(parts[:i])
        if module in _NOT_CODE:
            return True
        source = _module_file(module)
        if source is None:
            continue
        body = ast.parse(source.read_text(encoding="utf-8")).body
        for name in parts[i:]:
            node = _names(body).get(name)
            if node is None:
                return False
            body = node.body if isinstance(node, ast.ClassDef) else []
        return True
    return False


def _citations():
    for source in _CITING:
        for number, line in enumerate(source.read_text(encoding="utf-8").splitlines(), 1):
            where = f"{source.relative_to(_ROOT)}:{number}"
            for match in re.finditer(r"\bscrewkit(?:\.[A-Za-z_]\w*)+", line):
                yield where, match.group(0), "name"
            for match in re.finditer(r"(?<![\w/])(?:screwkit|tests|bench|docs)/[\w/]+\.(?:py|md)\b", line):
                yield where, match.group(0), "file"


def test_cited_modules_names_and_files_exist():
    missing = [
        f"{where}: {cited}"
        for where, cited, kind in _citations()
        if not (_resolves(cited) if kind == "name" else (_ROOT / cited).exists())
        and cited != "screwkit/robots/families/planar_3rpr.py"  # CONTRIBUTING's example, written by the reader
    ]
    assert not missing, "stale citations:\n" + "\n".join(missing)


_OUTSIDE = ("numpy", "np.", "sympy", "networkx", "nx.", "matplotlib", "dask", "math", "numba", "scipy",
            "tomllib", "json", "pathlib", "dataclasses", "typing", "collections", "importlib", "fractions")


def test_short_roles_name_something_in_their_module():
    """A role without a module (:func:`name`) is looked up in the module that writes it: after the
    split, a sibling's name there must be written in full (:func:`~screwkit.x.y.name`)."""
    unresolved = []
    for source in sorted((_ROOT / "screwkit").rglob("*.py")):
        text = source.read_text(encoding="utf-8")
        defined = set(dir(builtins))
        for node in ast.walk(ast.parse(text)):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                defined.add(node.name)
            elif isinstance(node, ast.alias):
                defined.add((node.asname or node.name).split(".")[0])
            elif isinstance(node, ast.Name | ast.Attribute) and isinstance(node.ctx, ast.Store):
                defined.add(node.id if isinstance(node, ast.Name) else node.attr)
        for match in re.finditer(r":(?:func|class|meth|data|attr|mod):`~?([\w.]+)`", text):
            target = match.group(1)
            if target.startswith(("screwkit", *_OUTSIDE)) or target.split(".")[0] in defined:
                continue
            line = text[: match.start()].count("\n") + 1
            unresolved.append(f"{source.relative_to(_ROOT)}:{line}: {match.group(0)}")
    assert not unresolved, "roles naming nothing in their module:\n" + "\n".join(unresolved)
