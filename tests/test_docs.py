"""Every public function and class has a numpydoc docstring with an Examples section (run as a doctest)."""

import importlib
import inspect
import pkgutil

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
