"""Screws: the conventions, and the kernels over ``(..., 6)`` arrays.

The immutable value class :class:`~screwkit.algebra.screwvalue.Screw` wraps one screw for people.

Conventions (the one place they are written; every module links here)
----------------------------------------------------------------------
* **Direction first.** A screw is ``(s; s0)`` with shape ``(..., 6)``. The line through point ``r``
  with direction ``s`` is ``(s; r × s)``; the screw of pitch ``h`` on it is ``(s; r × s + h s)``.
  Twists ``(ω; v_O)`` and wrenches ``(f; m_O)`` share this order, so one type serves both: "twist"
  and "wrench" are roles, not types. This is the convention of the source papers, e.g.
  τ = (s, r × s) in Amine et al. 2010 (paper 002), §4.1.
* **Reciprocal product** ``a ∘ b = a[:3]·b[3:] + a[3:]·b[:3]``; twist ∘ wrench is virtual power
  (paper 002, §3: two screws are reciprocal when it vanishes).
* **Pitch** ``h = s·s0 / s·s``; a screw with ``s = 0`` has infinite pitch (``math.inf``, or
  ``sympy.oo`` symbolically). Zero pitch: a pure rotation / pure force on a line; infinite pitch: a
  pure translation / pure couple, a line at infinity in P3 (paper 002, §3).
* **Rigid motion** of a screw by rotation ``R`` and translation ``t`` (the adjoint):
  ``(R s; R s0 + t × R s)``.
* **Units.** Lengths are in the user's unit; angles in radians. Every zero decision takes a
  relative tolerance ``rtol`` and a characteristic length ``length_scale`` that makes the moment
  half dimensionless (:mod:`screwkit.algebra.ranks`), so answers do not depend on the unit.
* **Numeric or symbolic.** Every kernel accepts floats or sympy expressions (docs/architecture.md §4); the
  branch is decided by the inputs, and mixed inputs are promoted to exact sympy numbers.

Examples
--------
>>> from screwkit.algebra.screw import force, revolute_twist, reciprocal_product
>>> rotation_about_z = revolute_twist([0, 0, 1], [1, 0, 0])
>>> rotation_about_z
array([ 0.,  0.,  1.,  0., -1.,  0.])
>>> float(reciprocal_product(rotation_about_z, force([0, 1, 0], [0, 0, 0])))
-1.0
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import DegenerateGeometryError, ScrewkitValueError
from . import backend as B
from .branch_values import zeros_like
from .checks import check_rotation
from .ranks import direction_scaled, unit_screws
from .zero_tests import norm, ratio, vanishes, where_zero, zero_vectors

__all__ = [
    "axis",
    "couple",
    "direction",
    "force",
    "from_plucker",
    "helical_twist",
    "is_infinite_pitch",
    "is_zero_pitch",
    "line",
    "magnitude",
    "moment",
    "normalize",
    "pitch",
    "prismatic_twist",
    "reciprocal_product",
    "revolute_twist",
    "transform",
]

Array = np.ndarray


def _nonzero_direction(direction: Array, name: str) -> None:
    zero = np.atleast_1d(zero_vectors(direction.reshape(-1, 3))).tolist()
    if any(zero):
        raise DegenerateGeometryError(
            f"Expected `{name}` to be a non-zero direction, got a zero vector "
            f"(at batch index {zero.index(True)})."
        )


def line(direction: Any, point: Any) -> Array:
    """Plücker coordinates ``(s; r × s)`` of the line through ``point`` along ``direction``.

    The direction is not normalised: the line's coordinates scale with it, as the papers' screws do.

    Parameters
    ----------
    direction : array_like, shape (..., 3)
        Non-zero direction ``s``.
    point : array_like, shape (..., 3)
        Any point ``r`` of the line.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    DegenerateGeometryError
        If a direction is zero.

    Examples
    --------
    >>> line([0, 0, 1], [1, 2, 0])
    array([ 0.,  0.,  1.,  2., -1.,  0.])
    """
    s, r = B.as_arrays((3,), (direction, "direction"), (point, "point"))
    _nonzero_direction(s, "direction")
    s, r = np.broadcast_arrays(s, r)
    return np.concatenate([s, B.cross(r, s)], axis=-1)


def revolute_twist(axis: Any, point: Any) -> Array:
    """Unit-rate twist of a revolute joint: the zero-pitch screw on the joint axis.

    Parameters
    ----------
    axis : array_like, shape (..., 3)
        Direction of the joint axis (its length is the angular rate).
    point : array_like, shape (..., 3)
        A point of the axis.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> revolute_twist([1, 0, 0], [0, 0, 5])
    array([1., 0., 0., 0., 5., 0.])
    """
    return line(axis, point)


def helical_twist(axis: Any, point: Any, pitch: Any) -> Array:
    """Twist of a helical (screw) joint of pitch ``h``: ``(s; r × s + h s)``.

    Parameters
    ----------
    axis : array_like, shape (..., 3)
    point : array_like, shape (..., 3)
    pitch : float or array_like, shape (...)
        Translation per radian, in the unit of length (lead / 2π).

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> helical_twist([0, 0, 1], [0, 0, 0], 0.5)
    array([0. , 0. , 1. , 0. , 0. , 0.5])
    """
    base = line(axis, point)
    (h,) = B.promote(B.as_array(pitch, "pitch", (), symbolic=B.is_symbolic(base)))
    base, h = B.promote(base, h)
    try:
        batch = np.broadcast_shapes(base.shape[:-1], np.shape(h))
    except ValueError as err:
        raise ScrewkitValueError(
            f"Expected `pitch` of a shape broadcastable to the axes' batch {base.shape[:-1]}, "
            f"got {np.shape(h)}."
        ) from err
    base = np.broadcast_to(base, (*batch, 6))
    s = base[..., :3]
    return np.concatenate([s, base[..., 3:] + np.broadcast_to(np.asarray(h), batch)[..., None] * s], axis=-1)


def prismatic_twist(direction: Any) -> Array:
    """Unit-rate twist of a prismatic joint: the infinite-pitch screw ``(0; d)``.

    Parameters
    ----------
    direction : array_like, shape (..., 3)
        The sliding direction (non-zero; normalised).

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> prismatic_twist([0, 1, 0])
    array([0., 0., 0., 0., 1., 0.])
    """
    (d,) = B.as_arrays((3,), (direction, "direction"))
    _nonzero_direction(d, "direction")
    return np.concatenate([zeros_like(d), d], axis=-1)


def force(direction: Any, point: Any) -> Array:
    """A pure force on the line through ``point`` along ``direction``: a zero-pitch wrench.

    Same coordinates as :func:`line` (paper 002 §4.1: τ0 = (s, r × s)).

    Parameters
    ----------
    direction : array_like, shape (..., 3)
        The force's direction (non-zero).
    point : array_like, shape (..., 3)
        A point of its line.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> force([1, 0, 0], [0, 1, 0])
    array([ 1.,  0.,  0.,  0.,  0., -1.])
    """
    return line(direction, point)


def couple(moment_vector: Any) -> Array:
    """A pure couple ``(0; m)``: an infinite-pitch wrench (a line at infinity).

    Parameters
    ----------
    moment_vector : array_like, shape (..., 3)
        The couple's moment (the translation's direction for a twist).

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> couple([0, 0, 2])
    array([0., 0., 0., 0., 0., 2.])
    """
    return prismatic_twist(moment_vector)


def from_plucker(direction: Any, moment_vector: Any) -> Array:
    """Assemble ``(s; s0)`` from its two halves (no condition imposed; any screw).

    Parameters
    ----------
    direction : array_like, shape (..., 3)
        The half ``s``.
    moment_vector : array_like, shape (..., 3)
        The half ``s0``.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Examples
    --------
    >>> from_plucker([0, 0, 1], [1, 0, 0])
    array([0., 0., 1., 1., 0., 0.])
    """
    s, s0 = B.as_arrays((3,), (direction, "direction"), (moment_vector, "moment"))
    s, s0 = np.broadcast_arrays(s, s0)
    return np.concatenate([s, s0], axis=-1)


def _screws(screws: Any, name: str = "screws") -> Array:
    return B.as_array(screws, name, (6,))


def direction(screws: Any) -> Array:
    """The direction half ``s`` of screws ``(..., 6)``.

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> direction([1, 2, 3, 4, 5, 6])
    array([1., 2., 3.])
    """
    return _screws(screws)[..., :3]


def moment(screws: Any) -> Array:
    """The moment half ``s0`` of screws ``(..., 6)``.

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> moment([1, 2, 3, 4, 5, 6])
    array([4., 5., 6.])
    """
    return _screws(screws)[..., 3:]


def reciprocal_product(a: Any, b: Any) -> Any:
    """Reciprocal (virtual-power) product ``a ∘ b = s_a·s0_b + s0_a·s_b``, batched.

    Paper 002, §3. Symmetric and invariant under rigid motions.

    Parameters
    ----------
    a, b : array_like, shape (..., 6)

    Returns
    -------
    float, numpy.ndarray of shape (...), or sympy expression

    Raises
    ------
    ScrewkitValueError
        If a numeric product overflows the float range (screws of size 1e200 each).

    Examples
    --------
    >>> float(reciprocal_product([0, 0, 1, 0, 0, 0], [1, 0, 0, 0, 0, 1]))
    1.0
    """
    a_arr, b_arr = B.promote(_screws(a, "a"), _screws(b, "b"))
    if a_arr.dtype == object:
        return B.dot(a_arr[..., :3], b_arr[..., 3:]) + B.dot(a_arr[..., 3:], b_arr[..., :3])
    with np.errstate(over="ignore", invalid="ignore"):  # refused below
        product = B.dot(a_arr[..., :3], b_arr[..., 3:]) + B.dot(a_arr[..., 3:], b_arr[..., :3])
    if not np.all(np.isfinite(product)):
        raise ScrewkitValueError(
            "Expected screws `a` and `b` whose reciprocal product is a float, got a product that "
            "overflows the float range (|a| |b| beyond 1e308): scale the screws first."
        )
    return product


def pitch(screws: Any) -> Any:
    """Pitch ``h = s·s0 / s·s``; ``inf`` (``sympy.oo``) where ``s = 0``.

    Exact: a direction counts as zero only when all its components are exactly zero. Use
    :func:`is_infinite_pitch` for a tolerance-based decision.

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    float, numpy.ndarray of shape (...), or sympy.Expr

    Raises
    ------
    DegenerateGeometryError
        For the zero screw, whose pitch is undefined.

    Examples
    --------
    >>> float(pitch(helical_twist([0, 0, 2], [1, 1, 0], 0.25)))
    0.25
    >>> pitch([0, 0, 0, 1, 0, 0])
    inf
    """
    arr = _screws(screws)
    if np.any(zero_vectors(arr)):
        raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
    s, s0 = direction_scaled(arr[..., :3], arr[..., 3:])  # s·s0 / s·s is unchanged by a common factor
    return ratio(B.dot(s, s0), B.dot(s, s))


def magnitude(screws: Any) -> Any:
    """Magnitude: ``|s|``, or ``|s0|`` for infinite-pitch screws (exact zero test on ``s``).

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    float, numpy.ndarray of shape (...), or sympy.Expr

    Examples
    --------
    >>> float(magnitude([0, 0, 2, 1, 0, 0]))
    2.0
    >>> float(magnitude([0, 0, 0, 3, 4, 0]))
    5.0
    """
    arr = _screws(screws)
    ns = norm(arr[..., :3])
    return where_zero(ns, norm(arr[..., 3:]), ns)


def normalize(screws: Any) -> Array:
    """Scale screws to unit magnitude (see :func:`magnitude`).

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    DegenerateGeometryError
        For the zero screw.

    Examples
    --------
    >>> normalize([0, 0, 2, 2, 0, 0])
    array([0., 0., 1., 1., 0., 0.])
    """
    arr = _screws(screws)
    size = np.asarray(magnitude(arr))[..., None]
    if np.any(zero_vectors(size)):  # also a screw whose norm underflows (|s| = 1e-200)
        raise DegenerateGeometryError("Expected non-zero screws, got the zero screw.")
    return B.simplify(arr / size)


def axis(screws: Any) -> tuple[Array, Array]:
    """The axis of screws with finite pitch: its point nearest the origin and its unit direction.

    For ``(s; s0)`` with ``s ≠ 0`` the nearest point is ``s × s0 / s·s`` (independent of pitch).

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.

    Returns
    -------
    point : numpy.ndarray, shape (..., 3)
    unit_direction : numpy.ndarray, shape (..., 3)

    Raises
    ------
    DegenerateGeometryError
        For a screw of infinite pitch (``s = 0``): its axis is a line at infinity, which has no
        finite point; use :func:`moment` for its direction.

    Examples
    --------
    >>> point, unit = axis(line([0, 0, 3], [1, 2, 5]))
    >>> point + 0.0, unit
    (array([1., 2., 0.]), array([0., 0., 1.]))
    """
    arr = _screws(screws)
    if np.any(zero_vectors(arr[..., :3])):
        raise DegenerateGeometryError(
            "Expected screws of finite pitch, got s = 0 (a line at infinity has no finite point)."
        )
    s, s0 = direction_scaled(arr[..., :3], arr[..., 3:])  # s × s0 / s·s is unchanged by a common factor
    ss = np.asarray(B.dot(s, s))[..., None]
    return B.simplify(B.cross(s, s0) / ss), B.simplify(s / B.sqrt(ss))


def is_zero_pitch(screws: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0) -> Any:
    """True where a screw is a line (zero pitch, finite): a pure rotation or a pure force.

    After dividing the moment by ``length_scale`` and normalising, the screw is a line when
    ``|s| > rtol`` and ``|s·s0| <= rtol |s|``. Symbolic screws are decided generically: ``s`` not
    identically zero and ``s·s0`` identically zero (no tolerance;
    :func:`screwkit.algebra.zero_tests.vanishes`).

    Parameters
    ----------
    screws : array_like, shape (..., 6)
    rtol : float, default 1e-9
    length_scale : float, default 1.0
        A characteristic length in the screws' unit (e.g. the mechanism's size).

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> is_zero_pitch(line([1, 0, 0], [0, 3, 0]))
    True
    >>> is_zero_pitch(helical_twist([1, 0, 0], [0, 3, 0], 0.1))
    False
    """
    unit = unit_screws(_screws(screws), length_scale)
    s, s0 = unit[..., :3], unit[..., 3:]
    result = ~vanishes(s, rtol=rtol) & vanishes(B.dot(s, s0, keepdims=True), s, rtol=rtol)
    return bool(result) if np.ndim(result) == 0 else result


def is_infinite_pitch(
    screws: Any, *, rtol: float = B.DEFAULT_RTOL, length_scale: float = 1.0
) -> Any:
    """True where a screw is a pure translation / pure couple: ``|s| <= rtol`` after scaling
    (symbolic: ``s`` identically zero).

    Parameters as in :func:`is_zero_pitch`.

    Parameters
    ----------
    screws : array_like, shape (..., 6)
        Floats or sympy expressions.
    rtol : float, default 1e-9
        Relative tolerance of the decision (symbolic screws are decided identically).
    length_scale : float, default 1.0
        The characteristic length dividing the moment half.

    Returns
    -------
    bool or numpy.ndarray of bool, shape (...)

    Examples
    --------
    >>> is_infinite_pitch(couple([0, 0, 1]))
    True
    >>> is_infinite_pitch(line([0, 0, 1], [0, 0, 0]))
    False
    """
    result = vanishes(unit_screws(_screws(screws), length_scale)[..., :3], rtol=rtol)
    return bool(result) if np.ndim(result) == 0 else result


def transform(screws: Any, rotation: Any, translation: Any) -> Array:
    """Apply a rigid motion (the adjoint map): ``(R s; R s0 + t × R s)``, batched.

    Parameters
    ----------
    screws : array_like, shape (..., 6)
    rotation : array_like, shape (..., 3, 3)
        A proper rotation matrix (checked for numeric input).
    translation : array_like, shape (..., 3)

    Returns
    -------
    numpy.ndarray, shape (..., 6)

    Raises
    ------
    ScrewkitValueError
        If ``rotation`` is not orthonormal with determinant +1.

    Examples
    --------
    >>> quarter_turn = [[0, -1, 0], [1, 0, 0], [0, 0, 1]]
    >>> transform(line([1, 0, 0], [0, 0, 0]), quarter_turn, [0, 0, 1])
    array([ 0.,  1.,  0., -1.,  0.,  0.])
    """
    arr = _screws(screws)
    rot = B.as_array(rotation, "rotation", (3, 3))
    t = B.as_array(translation, "translation", (3,))
    arr, rot, t = B.promote(arr, rot, t)
    check_rotation(rot)
    s = np.einsum("...ij,...j->...i", rot, arr[..., :3])
    s0 = np.einsum("...ij,...j->...i", rot, arr[..., 3:])
    return np.concatenate([s, s0 + B.cross(np.broadcast_to(t, s.shape), s)], axis=-1)
