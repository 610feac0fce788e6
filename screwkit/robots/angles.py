"""The one angle convention of the Python API: pose angles in radians unless ``angles="deg"``.

Every pose-taking function (:meth:`~screwkit.robots.mechanism.Mechanism.at`, ``configuration``,
``joints``, ``twist_graph``, ``twist_basis``, ``jacobians``, ``wrench_diagram``, the maps, loci,
paths and sweeps of :mod:`screwkit.analysis`, and :func:`screwkit.analyze`) takes
``angles="rad"`` (the default) or ``angles="deg"`` and converts the angle coordinates of its poses
here, with :func:`poses_in_radians`. Files and the command line state degrees (``--pose`` and the
catalog's ``default_pose``) and are converted on reading.

An angle beyond one turn given in radians is most likely meant in degrees (``phi = 45`` read as
45 rad, 2578°, is a legal but improbable pose): :func:`poses_in_radians` warns
(:class:`AngleUnitWarning`) and names ``angles="deg"``.

Examples
--------
>>> names = ("x", "y", "z", "phi")
>>> poses_in_radians([[0, 0, -750, 90]], names, ("phi",), angles="deg").round(4).tolist()
[[0.0, 0.0, -750.0, 1.5708]]
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .toml_fields import MAX_ANGLE_RADIANS

__all__ = ["ANGLE_UNITS", "AngleUnitWarning", "angle_factor", "pose_scale", "pose_text", "poses_in_radians"]

Array = np.ndarray

#: The accepted values of every ``angles`` keyword; the first is the default.
ANGLE_UNITS = ("rad", "deg")


class AngleUnitWarning(UserWarning):
    """A pose angle given in radians is larger than one turn: probably meant in degrees."""


def angle_factor(angles: Any) -> float:
    """Radians per unit of ``angles``: 1 for ``"rad"``, π/180 for ``"deg"``.

    Parameters
    ----------
    angles : {"rad", "deg"}
        The unit the caller's angles are in.

    Returns
    -------
    float

    Raises
    ------
    ScrewkitValueError
        For any other value, naming ``angles``.

    Examples
    --------
    >>> angle_factor("deg") * 180 == math.pi
    True
    >>> angle_factor("degrees")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `angles` to be 'deg' or 'rad', got 'degrees'.
    """
    if not isinstance(angles, str) or angles not in ANGLE_UNITS:
        raise ScrewkitValueError(f"Expected `angles` to be 'deg' or 'rad', got {angles!r}.")
    return 1.0 if angles == "rad" else math.pi / 180.0


def pose_scale(pose_names: Sequence[str], angle_names: Sequence[str], angles: Any = "rad") -> Array:
    """Per pose coordinate, the factor from the caller's unit to the API's: ``radians = value × scale``
    for the angles (:func:`angle_factor`), 1 for the lengths.

    Parameters
    ----------
    pose_names, angle_names : sequence of str
        The pose coordinates in order and those among them that are angles.
    angles : {"rad", "deg"}, default "rad"
        The unit of the caller's angle coordinates.

    Returns
    -------
    numpy.ndarray, shape (n,)

    Raises
    ------
    ScrewkitValueError
        If ``angles`` is neither ``"rad"`` nor ``"deg"``.

    Examples
    --------
    >>> pose_scale(("x", "y", "z", "phi"), ("phi",), "deg").round(5).tolist()
    [1.0, 1.0, 1.0, 0.01745]
    """
    factor = angle_factor(angles)
    return np.array([factor if name in angle_names else 1.0 for name in pose_names])


def pose_text(
    pose: Any, pose_names: Sequence[str], angle_names: Sequence[str], length_unit: str, angles: str = "deg"
) -> str:
    """One pose (API units: radians) in words, every coordinate with its unit: angles shown in
    ``angles`` (degrees by default, as files and the command line take them).

    Parameters
    ----------
    pose : array_like, shape (n,)
        In the length unit and radians.
    pose_names, angle_names : sequence of str
        The coordinates in order and those among them that are angles.
    length_unit : str
        The unit of the other coordinates ("" for none).
    angles : {"rad", "deg"}, default "deg"
        The unit to show the angles in.

    Returns
    -------
    str

    Raises
    ------
    ScrewkitValueError
        If ``angles`` is neither ``"rad"`` nor ``"deg"``.

    Examples
    --------
    >>> pose_text([0, 0, -750, math.pi / 4], ("x", "y", "z", "phi"), ("phi",), "mm")
    'x = 0 mm, y = 0 mm, z = -750 mm, phi = 45 deg'
    """
    shown = np.asarray(pose, dtype=float).reshape(-1) / pose_scale(pose_names, angle_names, angles) + 0.0
    length = f" {length_unit}" if length_unit else ""
    return ", ".join(
        f"{name} = {value:.4g} {angles}" if name in angle_names else f"{name} = {value:.6g}{length}"
        for name, value in zip(pose_names, shown, strict=True)
    )


def poses_in_radians(
    poses: Any,
    pose_names: Sequence[str],
    angle_names: Sequence[str],
    angles: Any = "rad",
    *,
    argument: str = "poses",
) -> Any:
    """Poses ``(..., n)`` with their angle coordinates converted to radians.

    ``None`` (the default pose) and anything that is not a numeric ``(..., n)`` array with
    ``n = len(pose_names)`` are passed through unchanged, for the callee to check and name.

    Parameters
    ----------
    poses : array_like, shape (..., n), or None
        Pose coordinates; lengths are left as they are.
    pose_names, angle_names : sequence of str
        The pose coordinates in order and those among them that are angles
        (:attr:`~screwkit.robots.mechanism.Mechanism.pose_names`, ``angle_names``).
    angles : {"rad", "deg"}, default "rad"
        The unit the angle coordinates of ``poses`` are in.
    argument : str, optional
        The argument's name, for the warning.

    Returns
    -------
    numpy.ndarray or the input
        A float copy in radians when ``angles="deg"``; the input itself when ``angles="rad"``.

    Raises
    ------
    ScrewkitValueError
        If ``angles`` is neither ``"rad"`` nor ``"deg"``.

    Warns
    -----
    AngleUnitWarning
        When ``angles="rad"`` and an angle exceeds one turn (2π) in magnitude (but not the bound
        beyond which the callee refuses it).

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as caught:
    ...     warnings.simplefilter("always")
    ...     _ = poses_in_radians([0, 0, -750, 45], ("x", "y", "z", "phi"), ("phi",))
    >>> print(caught[0].message)  # doctest: +ELLIPSIS
    The angle `phi` of `poses` is 45 rad (2578 deg), more than a turn: ... pass angles='deg' ...
    """
    scale = pose_scale(pose_names, angle_names, angles)
    if poses is None or isinstance(poses, str) or not angle_names:
        return poses
    try:
        array = np.asarray(poses, dtype=float)
    except (TypeError, ValueError):  # not numeric: the callee names it
        return poses
    if array.ndim == 0 or array.shape[-1] != len(pose_names):
        return poses
    indices = [list(pose_names).index(name) for name in angle_names]
    if angles == "rad":
        with np.errstate(invalid="ignore"):
            sizes = np.abs(array[..., indices]).reshape(-1, len(indices))
        for column, name in enumerate(angle_names):
            largest = np.nanmax(sizes[:, column], initial=0.0)
            if 2 * math.pi < largest <= MAX_ANGLE_RADIANS:  # beyond: refused, by the callee's range check
                warnings.warn(
                    f"The angle `{name}` of `{argument}` is {largest:.4g} rad "
                    f"({math.degrees(largest):.4g} deg), more than a turn: the Python API reads angles "
                    "in radians; pass angles='deg' for degrees.",
                    AngleUnitWarning,
                    stacklevel=3,
                )
        return poses
    return array * scale
