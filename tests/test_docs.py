"""Every public function and class has a numpydoc docstring with an Examples section (run as a doctest)."""

import importlib
import inspect
import pkgutil

import pytest

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
