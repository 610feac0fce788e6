"""Exceptions raised by screwkit.

A small hierarchy in the spirit of ``networkx.exception``: every error screwkit raises on purpose is a
:class:`ScrewkitError`; argument errors are also :class:`ValueError` or :class:`TypeError` so that
generic handlers keep working. A singularity is a *result*, never an exception.

Examples
--------
>>> from screwkit.exceptions import DegenerateGeometryError, ScrewkitError
>>> issubclass(DegenerateGeometryError, ScrewkitError) and issubclass(DegenerateGeometryError, ValueError)
True
"""

from __future__ import annotations

__all__ = [
    "CatalogError",
    "DegenerateGeometryError",
    "MissingDependencyError",
    "ScrewkitError",
    "ScrewkitIndexError",
    "ScrewkitTypeError",
    "ScrewkitValueError",
    "TwistGraphError",
    "UnreachablePoseError",
]


class ScrewkitError(Exception):
    """Base class of every error screwkit raises on purpose."""


class ScrewkitValueError(ScrewkitError, ValueError):
    """An argument has the right type but a wrong value, shape or content."""


class ScrewkitTypeError(ScrewkitError, TypeError):
    """An argument has the wrong type."""


class ScrewkitIndexError(ScrewkitError, IndexError):
    """An index is out of range (e.g. a pose of a batch), so that ``for`` loops stop at the end."""


class DegenerateGeometryError(ScrewkitValueError):
    """A geometric construction does not exist for the given input.

    For example the line through two coincident points, the meet of two parallel planes, or a
    screw axis asked of a zero screw.
    """


class TwistGraphError(ScrewkitValueError):
    """A twist graph violates the schema; the message names the link, joint or attribute."""


class UnreachablePoseError(ScrewkitValueError):
    """A pose lies outside a mechanism's workspace; the message names the limb that cannot reach it."""


class CatalogError(ScrewkitValueError):
    """A catalog or snapshot file is malformed; the message names the file and the field."""


class MissingDependencyError(ScrewkitError, ImportError):
    """An optional dependency is not installed; the message names the extra that installs it."""
