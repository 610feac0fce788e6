"""The one reader of pose arguments: what a mechanism (a catalog robot or a graph over its motion,
:class:`~screwkit.robots.mechanism.Mechanism`) accepts as poses, and the bounds on their sizes.

Examples
--------
>>> check_pose_range(load_mechanism("h4"), [0, 0, -750, 0.5])
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .graph_kinematics import kinematics_of
from .pose_conversions import displacement_coordinates
from .toml_fields import MAX_ANGLE_DEGREES, MAX_ANGLE_RADIANS, MAX_COORDINATE

__all__ = ["check_pose_range", "displacements_as_coordinates"]


def displacements_as_coordinates(mechanism: Any, poses: Any) -> Any:
    """Poses as coordinates: ``(..., 4, 4)`` rigid displacements of the platform relative to the
    reference configuration (rotating about the platform point) converted; a 2-D ``(4, 4)`` array
    is four poses of a four-coordinate robot, one displacement otherwise. Anything else is returned
    as it is.

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like or None

    Returns
    -------
    numpy.ndarray or the input
        Coordinates ``(..., n)`` for displacements, else ``poses`` itself.

    Raises
    ------
    ScrewkitValueError
        If a displacement is not finite.

    Examples
    --------
    >>> shift = np.eye(4)[None].copy()
    >>> shift[0, 2, 3] = -50.0
    >>> displacements_as_coordinates(load_mechanism("h4"), shift).round(9).tolist()
    [[0.0, 0.0, -800.0, 0.0]]
    """
    if poses is None or isinstance(poses, str):
        return poses
    try:
        array = np.asarray(poses, dtype=float)
    except (TypeError, ValueError):
        return poses  # the callee names it
    displacement = array.shape[-2:] == (4, 4) and (array.ndim > 2 or len(mechanism.pose_names) != 4)
    if not displacement:
        return poses
    if not np.all(np.isfinite(array)):
        raise ScrewkitValueError("Expected finite `poses` (4×4 displacements), got NaN or infinity.")
    flat = array.reshape(-1, 4, 4)
    return displacement_coordinates(kinematics_of(mechanism), flat).reshape(*array.shape[:-2], -1)


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
