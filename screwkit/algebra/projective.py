"""Projective geometry of P3: homogeneous points, planes and Plücker lines.

Conventions (``gca.md`` §1; screws: :mod:`screwkit.algebra.screw`)
------------------------------------------------------------------
* A point is ``(x, y, z, w)``, weight last: finite ``(r, 1)``, at infinity ``(d, 0)``. Any non-zero
  multiple is the same point.
* A plane is ``(n, δ)``: the points with ``n·x + δ w = 0``. The plane at infinity is ``(0, 0, 0, 1)``.
* The line through two points (their *join*) has Plücker coordinates, direction first,
  ``L(p, q) = (p_w q⃗ − q_w p⃗ ; p⃗ × q⃗)``. A finite point and an infinite point give ``(s; r × s)``,
  the zero-pitch screw of paper 002 §4.1; two infinite points give the line at infinity
  ``(0; u × v)``, a pure couple. So a line *is* a zero- or infinite-pitch screw.
* The bracket ``[pqrs]`` is the determinant of the 4×4 matrix whose rows are the four points; it
  vanishes iff they are coplanar, and ``[pqrs] = −L(p, q) ∘ L(r, s)`` (gca.md §1).
* Tolerance decisions (incidence tests: :mod:`screwkit.algebra.incidence`) scale the finite part of
  points and moments by ``length_scale`` and normalise every row before comparing with ``rtol`` (as
  for screws), so they do not depend on the unit.

Examples
--------
>>> a, b = finite_point([0, 0, 0]), finite_point([1, 0, 0])
>>> join(a, b)
array([1., 0., 0., 0., 0., 0.])
>>> float(bracket(a, b, finite_point([0, 1, 0]), finite_point([0, 0, 1])))
-1.0
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import DegenerateGeometryError, ScrewkitValueError
from . import backend as B
from .branch_values import ones_like, zeros_like
from .zero_tests import vanishes, zero_vectors

__all__ = [
    "bracket",
    "finite_point",
    "infinite_point",
    "join",
    "join_point_line",
    "line_points",
    "meet_line_plane",
    "meet_planes",
    "plane",
    "plane_through",
]

Array = np.ndarray


def finite_point(position: Any) -> Array:
    """The homogeneous point ``(r, 1)`` of a position ``r`` (shape ``(..., 3)``).

    Parameters
    ----------
    position : array_like, shape (..., 3)
        The positions.

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Examples
    --------
    >>> finite_point([1, 2, 3])
    array([1., 2., 3., 1.])
    """
    r = B.as_array(position, "position", (3,))
    return np.concatenate([r, ones_like(r[..., :1])], axis=-1)


def infinite_point(direction: Any) -> Array:
    """The point at infinity ``(d, 0)`` of a direction ``d`` (shape ``(..., 3)``, non-zero).

    Parameters
    ----------
    direction : array_like, shape (..., 3)
        The directions (non-zero).

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Raises
    ------
    DegenerateGeometryError
        If a direction is zero: ``(0, 0, 0, 0)`` is not a projective point.

    Examples
    --------
    >>> infinite_point([0, 0, 1])
    array([0., 0., 1., 0.])
    """
    d = B.as_array(direction, "direction", (3,))
    if np.any(zero_vectors(d)):
        raise DegenerateGeometryError(
            "Expected `direction` to be non-zero, got a zero vector: (0, 0, 0, 0) is not a point."
        )
    return np.concatenate([d, zeros_like(d[..., :1])], axis=-1)


def join(p: Any, q: Any, *, rtol: float = B.DEFAULT_RTOL) -> Array:
    """The line through two points, ``L(p, q) = (p_w q⃗ − q_w p⃗ ; p⃗ × q⃗)`` (gca.md §1).

    Parameters
    ----------
    p, q : array_like, shape (..., 4)
    rtol : float, default 1e-9
        The points coincide when ``|L(p, q)| <= rtol |p| |q|``.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    DegenerateGeometryError
        If the two points coincide (projectively), so no line is defined.

    Examples
    --------
    >>> join([1, 2, 3, 1], [0, 0, 1, 0])
    array([ 0.,  0.,  1.,  2., -1.,  0.])
    >>> join([1, 2, 3, 1], [2, 4, 6, 2])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.DegenerateGeometryError: Expected `p` and `q` to be distinct points, ...
    """
    pp, qq = B.as_arrays((4,), (p, "p"), (q, "q"))
    pp, qq = np.broadcast_arrays(pp, qq)
    result = join_unchecked(pp, qq)
    if np.any(vanishes(result, pp, qq, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `p` and `q` to be distinct points, got coincident points (no line through them)."
        )
    return result


def line_points(line: Any, *, rtol: float = B.DEFAULT_RTOL) -> tuple[Array, Array]:
    """Two points whose join is exactly ``line`` (a zero- or infinite-pitch screw).

    A finite line ``(s; m)`` gives its point nearest the origin and its point at infinity
    ``(s, 0)``; a line at infinity ``(0; m)`` gives two infinite points ``u, v`` with ``u × v = m``.

    Parameters
    ----------
    line : array_like, shape (6,)
        A line ``(s; m)`` (or a line at infinity ``(0; m)``).
    rtol : float, default 1e-9
        Relative tolerance of the pitch check.

    Returns
    -------
    p, q : numpy.ndarray, shape (4,)
        Two homogeneous points with ``join(p, q) = line``.

    Raises
    ------
    ScrewkitValueError
        If ``line`` is not a line (its pitch is neither zero nor infinite: ``s·m ≠ 0``).

    Examples
    --------
    >>> p, q = line_points([0, 0, 1, 2, -1, 0])
    >>> p + 0.0, q
    (array([1., 2., 0., 1.]), array([0., 0., 1., 0.]))
    """
    values = B.as_array(line, "line", (6,))
    if values.ndim != 1:
        raise ScrewkitValueError(f"Expected `line` to have shape (6,), got {values.shape}.")
    if B.is_symbolic(values):
        raise ScrewkitValueError("line_points is numeric; build symbolic lines from their points.")
    s, m = values[:3], values[3:]
    if not vanishes(B.dot(s, m, keepdims=True), s, m, rtol=rtol):
        raise ScrewkitValueError(
            f"Expected `line` to be a line (s·m = 0), got s·m = {s @ m:.6g}: a screw of "
            "non-zero pitch is not a line."
        )
    if np.linalg.norm(s) > 0:
        nearest = np.cross(s, m) / (s @ s)
        return np.append(nearest, 1.0), np.append(s, 0.0)
    if np.linalg.norm(m) == 0:
        raise DegenerateGeometryError("Expected a non-zero line, got the zero vector.")
    u = np.linalg.svd(m.reshape(1, 3))[2][1]  # a unit vector orthogonal to m
    # u × (m × u) = m (u·u) − u (u·m) = m, so the join of (u, 0) and (m × u, 0) is (0; m).
    return np.append(u, 0.0), np.append(np.cross(m, u), 0.0)


def join_point_line(point: Any, line: Any) -> Array:
    """The plane through a point and a line: ``(x⃗ × s − w m, x⃗·m)`` for ``x = (x⃗, w)``.

    It is the zero vector exactly when the point lies on the line.

    Parameters
    ----------
    point : array_like, shape (..., 4)
        Homogeneous points.
    line : array_like, shape (..., 6)
        Lines ``(s; m)``.

    Returns
    -------
    numpy.ndarray, shape (..., 4)
        The planes ``(n, δ)`` (zero where the point is on the line).

    Examples
    --------
    >>> join_point_line([0, 0, 0, 1], [1, 0, 0, 0, 0, 1])
    array([ 0.,  0., -1.,  0.])
    """
    x = B.as_array(point, "point", (4,))
    lv = B.as_array(line, "line", (6,))
    x, lv = B.promote(x, lv)
    s, m = lv[..., :3], lv[..., 3:]
    normal = B.cross(x[..., :3], s) - x[..., 3:] * m
    return np.concatenate([normal, B.dot(x[..., :3], m, keepdims=True)], axis=-1)


def plane(normal: Any, point: Any) -> Array:
    """The plane with normal ``n`` through the finite point ``r``: ``(n, −n·r)``.

    Parameters
    ----------
    normal : array_like, shape (..., 3)
        The normals.
    point : array_like, shape (..., 3)
        A point of each plane.

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Examples
    --------
    >>> plane([0, 0, 1], [5, 5, 2])
    array([ 0.,  0.,  1., -2.])
    """
    n = B.as_array(normal, "normal", (3,))
    r = B.as_array(point, "point", (3,))
    n, r = B.promote(n, r)
    if np.any(zero_vectors(n)):
        raise DegenerateGeometryError("Expected `normal` to be non-zero, got a zero vector.")
    return np.concatenate([n, -B.dot(n, r, keepdims=True)], axis=-1)


def _det3(a: Array, b: Array, c: Array) -> Array:
    return B.dot(a, B.cross(b, c))


def plane_through(p: Any, q: Any, r: Any, *, rtol: float = B.DEFAULT_RTOL) -> Array:
    """The plane ``π`` through three points with ``π·x = [p q r x]`` for every point ``x``.

    Parameters
    ----------
    p, q, r : array_like, shape (..., 4)
        Homogeneous points (not collinear).
    rtol : float, default 1e-9
        Relative tolerance of the collinearity check.

    Returns
    -------
    numpy.ndarray, shape (..., 4)

    Raises
    ------
    DegenerateGeometryError
        If the three points are collinear (or two coincide), so they span no plane.

    Examples
    --------
    >>> plane_through([0, 0, 0, 1], [1, 0, 0, 1], [0, 1, 0, 1]) + 0.0
    array([ 0.,  0., -1.,  0.])
    """
    pp, qq, rr = B.as_arrays((4,), (p, "p"), (q, "q"), (r, "r"))
    pp, qq, rr = np.broadcast_arrays(pp, qq, rr)
    columns = [[1, 2, 3], [0, 2, 3], [0, 1, 3], [0, 1, 2]]
    # Laplace expansion of det[p; q; r; x] along its last row: π_j = (−1)^(3+j) minor_j.
    coefficients = [
        (-1) ** (3 + j) * _det3(pp[..., cols], qq[..., cols], rr[..., cols])
        for j, cols in enumerate(columns)
    ]
    result = np.stack(coefficients, axis=-1)
    if np.any(vanishes(result, pp, qq, rr, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `p`, `q`, `r` to span a plane, got collinear (or coincident) points."
        )
    return result


def bracket(p: Any, q: Any, r: Any, s: Any) -> Any:
    """The bracket ``[pqrs]``: the determinant of the 4×4 matrix with rows p, q, r, s.

    Batched over leading axes; exact for sympy input (gca.md §1).

    Parameters
    ----------
    p, q, r, s : array_like, shape (..., 4)
        Homogeneous points (floats or sympy expressions).

    Returns
    -------
    float, numpy.ndarray of shape (...), or sympy.Expr

    Examples
    --------
    >>> float(bracket([1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, 1]))
    1.0
    """
    pts = B.as_arrays((4,), (p, "p"), (q, "q"), (r, "r"), (s, "s"))
    return bracket_unchecked(*np.broadcast_arrays(*pts))


#: Laplace expansion of a 4×4 determinant along its first two rows: (columns of rows 0-1, the
#: complementary columns of rows 2-3, sign (-1)^(i+j+1) with 0-based column indices i, j).
LAPLACE = (
    ((0, 1), (2, 3), 1),
    ((0, 2), (1, 3), -1),
    ((0, 3), (1, 2), 1),
    ((1, 2), (0, 3), 1),
    ((1, 3), (0, 2), -1),
    ((2, 3), (0, 1), 1),
)


def bracket_unchecked(p: Array, q: Array, r: Array, s: Array) -> Any:
    """:func:`bracket` on validated, promoted arrays ``(..., 4)`` (broadcast).

    The Laplace expansion along the first two rows (``+ - *`` only), so batches of float64 points and
    sympy-object points go through the same code.

    Examples
    --------
    >>> e = np.eye(4)
    >>> float(bracket_unchecked(e[1], e[0], e[2], e[3]))
    -1.0
    """
    total: Any = 0
    for (i, j), (k, m), sign in LAPLACE:
        upper = p[..., i] * q[..., j] - p[..., j] * q[..., i]
        lower = r[..., k] * s[..., m] - r[..., m] * s[..., k]
        total = total + sign * upper * lower
    return total


def join_unchecked(p: Array, q: Array) -> Array:
    """:func:`join` on validated, promoted arrays ``(..., 4)``, without the coincidence check.

    Coincident points give the zero line.

    Examples
    --------
    >>> join_unchecked(np.array([1.0, 2, 3, 1]), np.array([2.0, 4, 6, 2]))
    array([0., 0., 0., 0., 0., 0.])
    """
    direction = p[..., 3:] * q[..., :3] - q[..., 3:] * p[..., :3]
    return np.concatenate([direction, B.cross(p[..., :3], q[..., :3])], axis=-1)


def meet_line_plane(
    line: Any, plane_coords: Any, *, allow_infinite: bool = False, rtol: float = B.DEFAULT_RTOL
) -> Array:
    """The point where a line ``(s; m)`` meets a plane ``(n, δ)``: ``(n × m − δ s, n·s)``.

    Parameters
    ----------
    line : array_like, shape (..., 6)
    plane_coords : array_like, shape (..., 4)
    allow_infinite : bool, default False
        A line parallel to the plane meets it at infinity; by default that raises, since most
        constructions need a finite point (gca.md §7). Set True to get the point at infinity.
    rtol : float, default 1e-9

    Returns
    -------
    numpy.ndarray, shape (..., 4)
        The homogeneous meeting points.

    Raises
    ------
    DegenerateGeometryError
        If the line lies in the plane (no single meet point), or is parallel to it and
        ``allow_infinite`` is False.

    Examples
    --------
    >>> meet_line_plane([0, 0, 1, 0, 0, 0], [0, 0, 1, -2])
    array([0., 0., 2., 1.])
    """
    lv = B.as_array(line, "line", (6,))
    pl = B.as_array(plane_coords, "plane", (4,))
    lv, pl = B.promote(lv, pl)
    s, m, n, delta = lv[..., :3], lv[..., 3:], pl[..., :3], pl[..., 3:]
    point = np.concatenate([B.cross(n, m) - delta * s, B.dot(n, s, keepdims=True)], axis=-1)
    if np.any(vanishes(point, lv, pl, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `line` to cross `plane` at one point, got a line lying in the plane."
        )
    if not allow_infinite and np.any(vanishes(point[..., 3:], point, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `line` to cross `plane` at a finite point, got a line parallel to the plane "
            "(they meet at infinity; pass allow_infinite=True for that point)."
        )
    return point


def meet_planes(
    first: Any, second: Any, *, allow_infinite: bool = False, rtol: float = B.DEFAULT_RTOL
) -> Array:
    """The line common to two planes ``(n1, δ1)``, ``(n2, δ2)``: ``(n1 × n2 ; δ1 n2 − δ2 n1)``.

    Parameters
    ----------
    first, second : array_like, shape (..., 4)
        Planes ``(n, δ)``.
    allow_infinite : bool, default False
        Whether a line at infinity (parallel planes) is returned instead of refused.
    rtol : float, default 1e-9
        Relative tolerance of the degeneracy decisions.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    DegenerateGeometryError
        If the planes coincide, or are parallel and ``allow_infinite`` is False (parallel planes
        meet only in a line at infinity).

    Examples
    --------
    >>> meet_planes([1, 0, 0, 0], [0, 1, 0, 0])
    array([0., 0., 1., 0., 0., 0.])
    >>> meet_planes([0, 0, 1, 0], [0, 0, 1, -1])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.DegenerateGeometryError: Expected `first` and `second` to meet in a finite line, ...
    """
    a = B.as_array(first, "first", (4,))
    b = B.as_array(second, "second", (4,))
    a, b = B.promote(a, b)
    n1, d1, n2, d2 = a[..., :3], a[..., 3:], b[..., :3], b[..., 3:]
    result = np.concatenate([B.cross(n1, n2), d1 * n2 - d2 * n1], axis=-1)
    if np.any(vanishes(result, a, b, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `first` and `second` to be distinct planes, got the same plane twice."
        )
    if not allow_infinite and np.any(vanishes(result[..., :3], result, rtol=rtol)):
        raise DegenerateGeometryError(
            "Expected `first` and `second` to meet in a finite line, got parallel planes (they "
            "meet at infinity; pass allow_infinite=True for that line)."
        )
    return result
