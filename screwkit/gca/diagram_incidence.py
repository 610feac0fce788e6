"""Incidence arithmetic of a wrench diagram's points over a batch (the arithmetic the recipes of
:mod:`screwkit.gca.diagram_points` use): where a line meets a joint axis, a joint's centre, points
of a couple line, directions with a fixed sign.

Examples
--------
>>> x_axis = np.array([1.0, 0, 0, 0, 0, 0])  # meets the z axis through (2, 0, 0) there
>>> meet_points(x_axis, np.array([0, 0, 1.0, 0, -2.0, 0]), np.array(1.0)) + 0.0
array([2., 0., 0., 1.])
"""

from __future__ import annotations

import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..exceptions import DegenerateGeometryError
from .diagram import INCIDENCE_RTOL

__all__ = ["joint_centre", "meet_points"]

Array = np.ndarray


def _finite(points: Array) -> Array:
    return np.concatenate([points, np.ones((*points.shape[:-1], 1))], axis=-1)


def _infinite(directions: Array) -> Array:
    return np.concatenate([directions, np.zeros((*directions.shape[:-1], 1))], axis=-1)


def _units(v: Array) -> Array:
    with np.errstate(invalid="ignore", divide="ignore"):
        return v / np.linalg.norm(v, axis=-1, keepdims=True)


def _canonical_directions(v: Array) -> Array:
    """Unit directions ``(..., 3)`` with a fixed sign (first clearly non-zero component positive)."""
    u = _units(v)
    k = np.argmax(np.abs(u) > 1e-9, axis=-1)[..., None]
    return np.where(np.take_along_axis(u, k, axis=-1) < 0, -u, u)


def _free(moment: Array) -> tuple[Array, Array]:
    """Two unit directions ``(..., 3)`` normal to ``moment`` and to each other (the coordinate axis
    least aligned with it first): points of the couple line ``(0; moment)`` with no structural
    meaning."""
    m = _units(moment)
    axis = np.eye(3)[np.argmin(np.nan_to_num(np.abs(m), nan=0.0), axis=-1)]
    first = _units(B.cross(m, axis))
    return first, B.cross(m, first)


def _finite_axes(screws: Array) -> tuple[Array, Array]:
    """:func:`screwkit.algebra.screw.axis` over a batch ``(..., 6)``, NaN where the pitch is infinite
    (``s = 0``) or the screw is missing (NaN)."""
    bad = ~np.isfinite(screws).all(axis=-1) | np.all(screws[..., :3] == 0, axis=-1)
    safe = np.where(bad[..., None], np.array([0.0, 0.0, 1.0, 0.0, 0.0, 0.0]), screws)
    point, direction = S.axis(safe)
    return np.where(bad[..., None], np.nan, point), np.where(bad[..., None], np.nan, direction)


def _axis_lines(screws: Array) -> tuple[Array, Array]:
    """The axes ``(s; r × s)`` of screws ``(..., 6)`` and their points ``r`` nearest the origin."""
    nearest, _ = _finite_axes(screws)
    return np.concatenate([screws[..., :3], B.cross(nearest, screws[..., :3])], axis=-1), nearest


def _meet_plane_through_axis(line: Array, axis: Array, origin: Array) -> tuple[Array, Array]:
    """Where lines ``(..., 6)`` meet the planes that contain the axes ``(..., 6)`` (through their
    points ``origin``) and are normal to the planes of line and axis: ``(n × m − δ s, n·s)``
    (:func:`screwkit.algebra.projective.meet_line_plane`), and where the line lies in that plane instead."""
    normal = B.cross(B.cross(line[..., :3], axis[..., :3]), axis[..., :3])
    plane = np.concatenate([normal, -np.einsum("...i,...i", normal, origin)[..., None]], axis=-1)
    s, m, delta = line[..., :3], line[..., 3:], plane[..., 3:]
    point = np.concatenate(
        [B.cross(normal, m) - delta * s, np.einsum("...i,...i", normal, s)[..., None]], axis=-1
    )
    size = np.linalg.norm(line, axis=-1) * np.linalg.norm(plane, axis=-1)
    with np.errstate(invalid="ignore"):
        in_plane = np.all(normal == 0, axis=-1) | (np.linalg.norm(point, axis=-1) <= B.DEFAULT_RTOL * size)
    return point, in_plane


def meet_points(line: Array, screw: Array, length_scale: Array) -> Array:
    """Where finite lines meet joint axes, NaN where they are skew, parallel or meet at infinity.

    The line meets the plane that contains the axis and is normal to the plane of both; they meet
    when ``L ∘ A = 0`` after scaling moments by ``length_scale``
    (:func:`screwkit.algebra.incidence.lines_intersect`).

    Parameters
    ----------
    line : numpy.ndarray, shape (..., 6)
        Finite lines ``(s; r × s)``.
    screw : numpy.ndarray, shape (..., 6)
        Joint screws of finite pitch; their axes are used.
    length_scale : numpy.ndarray, shape (...)
        The mechanism's characteristic length (the incidence test is unit-free).

    Returns
    -------
    numpy.ndarray, shape (..., 4)
        The meeting points, weight 1; rows of NaN where there is none.

    Examples
    --------
    >>> x_axis = np.array([1.0, 0, 0, 0, 0, 0])  # the x axis, and the z axis through (2, 0, 0)
    >>> meet_points(x_axis, np.array([0, 0, 1.0, 0, -2.0, 0]), np.array(1.0)) + 0.0
    array([2., 0., 0., 1.])
    """
    length = np.asarray(length_scale, dtype=float)[..., None]
    return _meet(line, _scaled_axes(screw, length), length)


def _scaled_axes(screw: Array, length: Array) -> tuple[Array, Array, Array, Array]:
    """What :func:`meet_points` reads of joint axes (once per joint over a batch): the axes with
    their moments divided by ``length`` ``(..., 1)``, those rows unit, the unit directions, and the
    axes' points nearest the origin divided by ``length``."""
    axis, origin = _axis_lines(screw)
    divided = np.concatenate([axis[..., :3], axis[..., 3:] / length], axis=-1)
    return divided, _units(divided), _units(axis[..., :3]), origin / length


def _meet(line: Array, axes: tuple[Array, Array, Array, Array], length: Array) -> Array:
    """:func:`meet_points` of lines and :func:`_scaled_axes`."""
    axis, b, direction, origin = axes
    # the meet in lengths divided by length_scale: the test of a line lying in the plane compares
    # the point with a product of two moments, not invariant under a change of unit otherwise (a
    # 1 m mechanism written in picometres lost every meet point)
    divided = np.concatenate([line[..., :3], line[..., 3:] / length], axis=-1)
    a = _units(divided)
    product = np.einsum("...i,...i", a[..., :3], b[..., 3:]) + np.einsum("...i,...i", a[..., 3:], b[..., :3])
    cross = B.cross(_units(line[..., :3]), direction)
    parallel = np.linalg.norm(cross, axis=-1) < INCIDENCE_RTOL
    point, in_plane = _meet_plane_through_axis(divided, axis, origin)
    with np.errstate(invalid="ignore"):
        skew = ~(np.abs(product) <= INCIDENCE_RTOL)
        missing = skew | parallel | in_plane | ~(np.abs(point[..., 3]) >= 1e-12)
    with np.errstate(invalid="ignore", divide="ignore"):
        meet = point / point[..., 3:]
    meet = np.concatenate([meet[..., :3] * length, meet[..., 3:]], axis=-1)
    return np.where(missing[..., None], np.nan, meet)


def _joint_centres(screws: Array) -> Array:
    """The common point ``(..., 3)`` of joints' first two axes ``(..., k, 6)`` (a spherical or
    universal joint's centre), NaN where they are parallel (no single point).

    The point of the first axis nearest the second, in closed form: with ``p`` the first axis's
    point nearest the origin (``s_1 × m_1 / |s_1|²``) and ``n = s_1 × s_2``, ``p + t s_1`` where
    ``t = ((m_2 − p × s_2)·n) / |n|²`` (the moment ``m_2 = q × s_2 + h s_2`` of the second about
    ``p``, along the common normal; the pitch term drops out).
    """
    s1, m1, s2, m2 = screws[..., 0, :3], screws[..., 0, 3:], screws[..., 1, :3], screws[..., 1, 3:]
    normal = B.cross(s1, s2)
    size = np.einsum("...i,...i", normal, normal)
    first, second = np.einsum("...i,...i", s1, s1), np.einsum("...i,...i", s2, s2)
    with np.errstate(invalid="ignore", divide="ignore"):
        nearest = B.cross(s1, m1) / first[..., None]
        along = np.einsum("...i,...i", m2 - B.cross(nearest, s2), normal) / size
        parallel = ~(size > B.DEFAULT_RTOL**2 * first * second)
    return np.where(parallel[..., None], np.nan, nearest + along[..., None] * s1)


def joint_centre(screws: Array) -> Array:
    """The centre of one spherical or universal joint: the common point of its first two axes.

    Parameters
    ----------
    screws : array_like, shape (k, 6)
        The joint's screws (``k >= 2``).

    Returns
    -------
    numpy.ndarray, shape (3,)

    Raises
    ------
    DegenerateGeometryError
        Where its first two axes are parallel (no single point).

    Examples
    --------
    >>> joint_centre([[1.0, 0, 0, 0, 3.0, 0], [0, 1.0, 0, -3.0, 0, 0]])  # axes x, y through (0, 0, 3)
    array([0., 0., 3.])
    """
    centre = _joint_centres(np.asarray(screws, dtype=float)[None])[0]
    if not np.isfinite(centre).all():
        raise DegenerateGeometryError(
            "Expected the joint's first two axes to meet at one point, got parallel axes."
        )
    return centre
