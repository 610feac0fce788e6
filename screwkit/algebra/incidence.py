"""Incidence tests of P3 with tolerances: points at infinity, coplanar, collinear, meeting lines.

Each test is a zero decision on the objects of :mod:`screwkit.algebra.projective` (conventions
there): the finite part of points and the moments of lines are divided by ``length_scale`` and
every row normalised before the comparison with ``rtol``, so the answers do not depend on the
unit. Numeric input only (a symbolic incidence is a condition: the bracket or product itself).

Examples
--------
>>> from screwkit.algebra.projective import finite_point, join
>>> o, x, y = finite_point([0, 0, 0]), finite_point([1, 0, 0]), finite_point([0, 1, 0])
>>> bool(are_collinear(o, x, finite_point([2, 0, 0]))), bool(lines_intersect(join(o, x), join(o, y)))
(True, True)
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import DegenerateGeometryError, ScrewkitTypeError
from . import backend as B
from .checks import checked_length_scale
from .projective import join_point_line
from .ranks import unit_rows
from .zero_tests import _binary_exponents, zero_vectors

__all__ = ["are_collinear", "are_coplanar", "is_at_infinity", "lines_intersect", "point_on_line"]

Array = np.ndarray


def is_at_infinity(points: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> Any:
    """True where a point lies in the plane at infinity (``|w|`` negligible after scaling).

    Parameters
    ----------
    points : array_like, shape (..., 4)
        Homogeneous points (numeric).
    rtol : float, default 1e-9
        Relative tolerance of the zero decision (numeric input only).
    length_scale : float, default 1.0
        The characteristic length that makes the coordinates dimensionless.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> is_at_infinity([[1, 0, 0, 0], [1, 0, 0, 1]])
    array([ True, False])
    """
    unit = _unit_points(_numeric(points, "points", "is_at_infinity", (4,)), length_scale)
    result = np.abs(unit[..., 3]) <= rtol
    return bool(result) if np.ndim(result) == 0 else result


def _numeric(value: Any, name: str, test: str, shape: tuple[int, ...]) -> Array:
    """``value`` as an array if it holds numbers; a symbolic one is refused, naming the exact route."""
    value = B.as_array(value, name, shape)
    if B.is_symbolic(value):
        raise ScrewkitTypeError(
            f"Expected `{name}` to hold numbers ({test} decides with a tolerance; for symbolic "
            "coordinates test the exact bracket, join_point_line or plane_through for zero), got symbols."
        )
    return value


def _unit_points(p: Array, length_scale: float) -> Array:
    checked_length_scale(length_scale)
    scaled = np.ldexp(p, -_binary_exponents(p))  # exact; no square overflows below
    scaled[..., :3] /= length_scale
    scaled = np.ldexp(scaled, -_binary_exponents(scaled))
    size = np.linalg.norm(scaled, axis=-1, keepdims=True)
    if np.any(size == 0):
        raise DegenerateGeometryError("Expected non-zero points, got (0, 0, 0, 0).")
    return scaled / size


def are_coplanar(
    p: Any, q: Any, r: Any, s: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0
) -> Any:
    """True where four points lie in one plane: ``|[pqrs]| <= rtol`` on unit-scaled points.

    Parameters
    ----------
    p, q, r, s : array_like, shape (..., 4)
        Homogeneous points (numeric).
    rtol : float, default 1e-9
        Relative tolerance of the zero decision (numeric input only).
    length_scale : float, default 1.0
        The characteristic length that makes the coordinates dimensionless.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> are_coplanar([0, 0, 0, 1], [1, 0, 0, 1], [0, 1, 0, 1], [5, 5, 0, 1])
    True
    """
    named = zip((p, q, r, s), "pqrs", strict=True)
    pts = [_unit_points(_numeric(x, name, "are_coplanar", (4,)), length_scale) for x, name in named]
    result = np.abs(np.linalg.det(np.stack(np.broadcast_arrays(*pts), axis=-2))) <= rtol
    return bool(result) if np.ndim(result) == 0 else result


def are_collinear(
    p: Any, q: Any, r: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0
) -> Any:
    """True where three points lie on one line (the 3×4 matrix of unit-scaled points has rank < 3).

    Parameters
    ----------
    p, q, r : array_like, shape (..., 4)
        Homogeneous points (numeric).
    rtol : float, default 1e-9
        Relative tolerance of the zero decision (numeric input only).
    length_scale : float, default 1.0
        The characteristic length that makes the coordinates dimensionless.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> are_collinear([0, 0, 0, 1], [1, 1, 1, 1], [1, 1, 1, 0])
    True
    """
    named = zip((p, q, r), "pqr", strict=True)
    pts = [_unit_points(_numeric(x, name, "are_collinear", (4,)), length_scale) for x, name in named]
    values = np.linalg.svd(np.stack(np.broadcast_arrays(*pts), axis=-2), compute_uv=False)
    result = values[..., 2] <= rtol * values[..., 0]
    return bool(result) if np.ndim(result) == 0 else result


def lines_intersect(
    first: Any, second: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0
) -> Any:
    """True where two lines meet (parallel lines meet at infinity and count): ``L1 ∘ L2 = 0``.

    Equivalent to the coplanarity of the two lines (paper 002, §3).

    Parameters
    ----------
    first, second : array_like, shape (..., 6)
        Lines ``(s; m)`` (numeric).
    rtol : float, default 1e-9
        Relative tolerance of the zero decision (numeric input only).
    length_scale : float, default 1.0
        The characteristic length that makes the coordinates dimensionless.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> lines_intersect([1, 0, 0, 0, 0, 0], [0, 1, 0, 0, 0, 0])
    True
    >>> lines_intersect([1, 0, 0, 0, 0, 0], [0, 1, 0, -1, 0, 0])
    False
    """
    a = _numeric(first, "first", "lines_intersect", (6,))
    b = _numeric(second, "second", "lines_intersect", (6,))
    length = checked_length_scale(length_scale)
    for name, values in (("first", a), ("second", b)):
        if np.any(zero_vectors(values)):
            raise DegenerateGeometryError(f"Expected `{name}` to be a non-zero line, got zeros.")
    scaled_a, scaled_b = unit_rows(a, length), unit_rows(b, length)
    product = B.dot(scaled_a[..., :3], scaled_b[..., 3:]) + B.dot(
        scaled_a[..., 3:], scaled_b[..., :3]
    )
    result = np.abs(product) <= rtol
    return bool(result) if np.ndim(result) == 0 else result


def point_on_line(
    point: Any, line: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0
) -> Any:
    """True where a point lies on a line: their joining plane (:func:`join_point_line`) vanishes.

    Parameters
    ----------
    point : array_like, shape (..., 4)
        Homogeneous points (numeric).
    line : array_like, shape (..., 6)
        Lines ``(s; m)``.
    rtol : float, default 1e-9
        Relative tolerance of the zero decision (numeric input only).
    length_scale : float, default 1.0
        The characteristic length that makes the coordinates dimensionless.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> point_on_line([3, 0, 0, 1], [1, 0, 0, 0, 0, 0]), point_on_line([0, 1, 0, 1], [1, 0, 0, 0, 0, 0])
    (True, False)
    """
    x = _unit_points(_numeric(point, "point", "point_on_line", (4,)), length_scale)
    lv = _numeric(line, "line", "point_on_line", (6,))
    if np.any(zero_vectors(lv)):
        raise DegenerateGeometryError("Expected `line` to be a non-zero line, got zeros.")
    unit_lines = unit_rows(lv, checked_length_scale(length_scale))
    result = np.linalg.norm(join_point_line(x, unit_lines), axis=-1) <= rtol
    return bool(result) if np.ndim(result) == 0 else result
