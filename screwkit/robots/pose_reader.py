"""The one reader of pose arguments: what a mechanism (a catalog robot or a graph over its motion,
:class:`~screwkit.robots.mechanism.Mechanism`) accepts as poses, and the bounds on their sizes.

:func:`read_poses` is what every pose-taking method reads its argument with (``at``, after
converting 4×4 displacements, ``configuration``, ``joints``, ``twist_graph``, ...), and
:func:`pose_array` its core (``reachable``, and the maps and paths of :mod:`screwkit.analysis`): real
numbers only (a string, a boolean or None inside a pose is refused, not converted), finite, one per
pose coordinate, each error naming the argument (``pose`` or ``poses``, ``start``, ...), what was
expected and what was got.

Examples
--------
>>> read_poses(load_mechanism("h4"), [0, 0, -750, 30], angles="deg").round(4).tolist()
[0.0, 0.0, -750.0, 0.5236]
>>> read_poses(load_mechanism("h4"), ["30", 0, -750, 0], argument="pose")  # doctest: +ELLIPSIS
Traceback (most recent call last):
...
screwkit.exceptions.ScrewkitTypeError: Expected `pose` to be an array of real numbers, got strings: ['30', ...
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitValueError
from .angles import poses_in_radians
from .toml_fields import MAX_ANGLE_DEGREES, MAX_ANGLE_RADIANS, MAX_COORDINATE

__all__ = ["check_pose_range", "pose_array", "read_poses"]

Array = np.ndarray


def pose_array(mechanism: Any, poses: Any, argument: str = "poses", *, one: bool = False) -> Array:
    """Poses ``(..., n)`` as a new float array: real numbers only, finite, one per pose coordinate.

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like, shape (..., n)
    argument : str, optional
        The argument's name, for the error messages.
    one : bool, optional
        Accept one pose ``(n,)`` only.

    Returns
    -------
    numpy.ndarray, shape (..., n)

    Raises
    ------
    ScrewkitTypeError
        If a value is not a real number (a string, a boolean, None, a ragged nesting).
    ScrewkitValueError
        If the last axis is not the pose coordinates, a value is NaN or infinite, or with ``one`` the
        array is not one pose.

    Examples
    --------
    >>> pose_array(load_mechanism("h4"), [True, 0, -750, 0], "pose")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitTypeError: Expected `pose` to be an array of real numbers, got bool True ...
    """
    names = mechanism.pose_names
    array = B.as_array(poses, argument, (), symbolic=False).astype(float)
    if one and array.shape != (len(names),):
        raise ScrewkitValueError(
            f"Expected `{argument}` to have shape ({len(names)},), got {array.shape} (one pose of "
            f"coordinates {', '.join(names)})."
        )
    if array.ndim == 0 or array.shape[-1] != len(names):
        raise ScrewkitValueError(
            f"Expected `{argument}` to have shape (..., {len(names)}), got {array.shape} (coordinates "
            f"{', '.join(names)})."
        )
    return array


def read_poses(mechanism: Any, poses: Any, argument: str = "poses", *, angles: str = "rad") -> Array | None:
    """A pose argument read: :func:`pose_array`, the angle coordinates to radians
    (:func:`~screwkit.robots.angles.poses_in_radians`), the sizes bounded (:func:`check_pose_range`).

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like, shape (..., n), or None
        None (the default pose) is returned as it is.
    argument : str, optional
        The argument's name, for the error messages.
    angles : {"rad", "deg"}, default "rad"
        The unit of the angle coordinates.

    Returns
    -------
    numpy.ndarray, shape (..., n), or None
        In the mechanism's length unit and radians.

    Raises
    ------
    ScrewkitTypeError, ScrewkitValueError
        As :func:`pose_array`, :func:`check_pose_range`, or for a bad ``angles``.

    Examples
    --------
    >>> read_poses(load_mechanism("h4"), [[0, 0, -750, 0], [0, 0, np.nan, 0]])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `poses` to hold finite numbers, got NaN or ...
    """
    names, angle_names = mechanism.pose_names, mechanism.angle_names
    if poses is None:
        poses_in_radians(None, names, angle_names, angles)  # checks `angles`
        return None
    array = pose_array(mechanism, poses, argument)
    array = np.asarray(poses_in_radians(array, names, angle_names, angles, argument=argument), dtype=float)
    check_pose_range(mechanism, array, argument)
    return array


def check_pose_range(mechanism: Any, poses: Any, argument: str = "poses") -> None:
    """Refuse pose coordinates beyond :data:`~screwkit.robots.toml_fields.MAX_COORDINATE` and angles
    beyond :data:`~screwkit.robots.toml_fields.MAX_ANGLE_RADIANS` (the radian form of the degrees
    rule, :data:`~screwkit.robots.toml_fields.MAX_ANGLE_DEGREES`).

    Shapes, types and NaN are left to the callee, which names them; this check only bounds sizes.

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like or None
        Poses ``(..., n)`` in the file's length unit and radians (None: the default pose).
    argument : str, optional
        The argument's name, for the error message.

    Raises
    ------
    ScrewkitValueError
        Naming the argument, the angle coordinate, the bound and the value.

    Examples
    --------
    >>> check_pose_range(load_mechanism("h4"), [0, 0, -750, 1e5])  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected the angle `phi` of `poses` to be at most 17453.3 ...
    """
    if poses is None or isinstance(poses, str):
        return
    with np.errstate(all="ignore"):
        try:
            values = np.abs(np.asarray(poses, dtype=float))
        except (TypeError, ValueError):  # not numeric: the callee names it
            return
    size = np.nanmax(values, initial=0.0)
    if np.isfinite(size) and size > MAX_COORDINATE:
        raise ScrewkitValueError(
            f"Expected pose coordinates up to {MAX_COORDINATE:g} in size ({mechanism.length_unit}, "
            f"radians), got {size:g}."
        )
    names = mechanism.pose_names
    if values.ndim == 0 or values.shape[-1] != len(names):
        return
    for name in mechanism.angle_names:
        angle = np.nanmax(values[..., names.index(name)], initial=0.0)
        if np.isfinite(angle) and angle > MAX_ANGLE_RADIANS:
            raise ScrewkitValueError(
                f"Expected the angle `{name}` of `{argument}` to be at most {MAX_ANGLE_RADIANS:g} rad "
                f"({MAX_ANGLE_DEGREES:g} degrees) in magnitude (beyond it a double no longer holds the "
                f"angle to the analysis's precision), got {angle:g} rad."
            )
