"""Sphinx extension: the API reference, one page per public module, generated from ``__all__``.

A module is public when no part of its dotted name starts with ``_``. Its page shows the module's
docstring, a summary table of every name in its ``__all__``, and the full entry (autodoc) of every
function and class defined there and of every constant it lists. A function or class listed by a
module that re-exports it (``screwkit`` re-exports the main API) links to the entry in the module
that defines it; one defined in a module whose ``__all__`` does not list it is documented in full
at the first public module that lists it. ``tests/test_site.py`` checks the built site against
every ``__all__``, independently of this file.
"""

import importlib
import inspect
import pkgutil
import types
from pathlib import Path

from sphinx.pycode import ModuleAnalyzer

PACKAGE = "screwkit"
API_FOLDER = "api"
#: Re-exported full names and the names their entries are under (filled when the build starts).
ALIASES: dict[str, str] = {}


def public_modules(package=PACKAGE):
    """Every public module of ``package`` (itself first), sorted, imported."""
    root = importlib.import_module(package)
    names = [package] + sorted(
        info.name
        for info in pkgutil.walk_packages(root.__path__, f"{package}.")
        if not any(part.startswith("_") for part in info.name.split("."))
    )
    return {name: importlib.import_module(name) for name in names}


def _is_documentable(obj):
    """A function or class (documented once, where it is defined); anything else is a constant."""
    if isinstance(obj, types.GenericAlias | types.UnionType):  # type aliases: constants
        return False
    return inspect.isclass(obj) or inspect.isfunction(obj) or inspect.isbuiltin(obj)


def canonical_names(modules):
    """Map ``id(obj)`` of every listed function or class to the full name its entry is documented under."""
    homes = {}
    for module_name, module in modules.items():
        for name in module.__all__:
            obj = getattr(module, name)
            if not _is_documentable(obj) or id(obj) in homes:
                continue
            home = getattr(obj, "__module__", None)
            if home in modules and getattr(modules[home], name, None) is obj and name in modules[home].__all__:
                homes[id(obj)] = f"{home}.{name}"
            else:
                homes[id(obj)] = f"{module_name}.{name}"
    return homes


def _entry(full_name, obj):
    if inspect.isclass(obj):
        return f".. autoclass:: {full_name}\n   :members:\n"
    return f".. autofunction:: {full_name}\n"


def _constant(module_name, name, obj, comments):
    """A constant's entry: its value when short, and its ``#:`` comment (never its type's docstring)."""
    text = repr(obj)
    lines = [f".. py:data:: {name}", f"   :module: {module_name}"]
    if len(text) <= 80 and "\n" not in text:
        lines.append(f"   :value: {text}")
    comment = comments.get(("", name))
    lines += [""] + [f"   {line}" for line in (comment or ["(no description)"])] + [""]
    return "\n".join(lines)


def module_page(module_name, module, homes):
    """The reStructuredText of one module's API page."""
    title = f"``{module_name}``"
    lines = [title, "=" * len(title), "", f".. automodule:: {module_name}", ""]
    routines = [n for n in module.__all__ if _is_documentable(getattr(module, n))]
    constants = [n for n in module.__all__ if not _is_documentable(getattr(module, n))]
    if routines:
        # full names outside the module's context (autosummary reads ``screwkit.x`` under
        # ``screwkit`` as a cycle)
        lines += [".. rubric:: Functions and classes", "", ".. currentmodule:: None", ""]
        lines += [".. autosummary::", "   :nosignatures:", ""]
        lines += [f"   ~{homes[id(getattr(module, name))]}" for name in routines]
        lines += ["", f".. currentmodule:: {module_name}", ""]
    for name in routines:
        if homes[id(getattr(module, name))] == f"{module_name}.{name}":
            lines += [_entry(f"{module_name}.{name}", getattr(module, name)), ""]
    if constants:
        comments = ModuleAnalyzer.for_module(module_name).find_attr_docs()
        lines += [".. rubric:: Constants", ""]
        lines += [_constant(module_name, name, getattr(module, name), comments) for name in constants]
    return "\n".join(lines)


def index_page(modules):
    """The API reference's front page: the top-level names, then every module by subpackage."""
    top = modules[PACKAGE]
    homes = canonical_names(modules)
    lines = [
        "API reference",
        "=============",
        "",
        "Every public name of every public module (a module is public when no part of its name starts",
        "with ``_``; its public names are its ``__all__``). ``import screwkit as sk`` gives the main",
        "API below; the modules are listed bottom-up, in the order of the data flow",
        "(:doc:`/architecture`).",
        "",
        ".. rubric:: The top-level namespace ``screwkit``",
        "",
        ".. autosummary::",
        "   :nosignatures:",
        "",
    ]
    lines += [
        f"   ~{homes[id(getattr(top, n))] if _is_documentable(getattr(top, n)) else f'{PACKAGE}.{n}'}"
        for n in top.__all__
    ]
    groups: dict[str, list[str]] = {}
    for name in modules:
        group = ".".join(name.split(".")[:2])
        groups.setdefault(group, []).append(name)
    for group, names in groups.items():
        lines += ["", f".. rubric:: ``{group}``", "", ".. toctree::", "   :maxdepth: 1", ""]
        lines += [f"   {name}" for name in names]
    return "\n".join(lines) + "\n"


def write_pages(app):
    """Write ``api/*.rst`` into the source folder, leaving unchanged files untouched (incremental builds)."""
    folder = Path(app.srcdir) / API_FOLDER
    folder.mkdir(exist_ok=True)
    modules = public_modules()
    homes = canonical_names(modules)
    pages = {"index": index_page(modules)}
    pages.update({name: module_page(name, module, homes) for name, module in modules.items()})
    for stale in folder.glob("*.rst"):
        if stale.stem not in pages:
            stale.unlink()
    ALIASES.update(aliases(modules))
    for stem, text in pages.items():
        path = folder / f"{stem}.rst"
        if not path.exists() or path.read_text() != text:
            path.write_text(text)


def aliases(modules):
    """Map every re-exported full name (``screwkit.classify``) to the name its entry is under."""
    homes = canonical_names(modules)
    return {
        f"{module_name}.{name}": homes[id(getattr(module, name))]
        for module_name, module in modules.items()
        for name in module.__all__
        if _is_documentable(getattr(module, name)) and homes[id(getattr(module, name))] != f"{module_name}.{name}"
    }


def _resolve_alias(app, env, node, contnode):
    """Resolve ``screwkit.classify`` (or ``screwkit.Mechanism.at``) to the entry of the re-exported object."""
    if node.get("refdomain") != "py":
        return None
    target = node.get("reftarget", "")
    parts = target.split(".")
    for cut in range(len(parts), 1, -1):
        head = ".".join(parts[:cut])
        if head in ALIASES:
            domain = env.get_domain("py")
            new_target = ALIASES[head] + target[len(head) :]
            return domain.resolve_xref(env, node["refdoc"], app.builder, node["reftype"], new_target, node, contnode)
    return None


def _is_checked(node):
    """Whether a reference that did not resolve fails the build: every reference of a hand-written
    page (``docs/**.md``), and, in docstrings, a reference to a function, class, module or constant
    written as a full public path (``screwkit.x.y``, no part starting with ``_``). A docstring's
    short name (resolved relative to its module when it can be), an attribute (numpydoc lists them
    in a table, not as entries), a private helper or another package's name is left as plain text."""
    if (node.source or "").endswith(".md"):
        return True
    parts = node.get("reftarget", "").lstrip("~.").split(".")
    public = parts[0] == PACKAGE and len(parts) > 1 and not any(p.startswith("_") for p in parts)
    return public and node.get("reftype") != "attr"


def _warn_missing_reference(app, domain, node):
    if domain.name == "py" and not _is_checked(node):
        return True  # handled: no warning
    return None


def setup(app):
    app.connect("builder-inited", write_pages)
    app.connect("missing-reference", _resolve_alias)
    app.connect("warn-missing-reference", _warn_missing_reference)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
