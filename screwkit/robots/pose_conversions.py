"""The poses a mechanism takes and gives besides its coordinates: rigid displacements of the platform
as coordinates (:func:`displacement_coordinates`), and the poses the forward kinematics reaches
(:func:`forward_posed`), both through a mechanism's loop-closure kinematics
(:mod:`screwkit.robots.graph_kinematics`).

Examples
--------
>>> lift = np.eye(4); lift[2, 3] = -10
>>> displacement_coordinates(kinematics_of(load_mechanism("h4")), lift[None]).round(9).tolist()
[[0.0, 0.0, -760.0, 0.0]]
"""

from __future__ import annotations

from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra.rigid_motions import rotation_log
from ..exceptions import ScrewkitValueError
from .graph_kinematics import GraphKinematics, kinematics_of

__all__ = ["displacement_coordinates", "displacements_as_coordinates", "forward_posed"]

Array = np.ndarray


def displacement_coordinates(kinematics: GraphKinematics, displacements: Array) -> Array:
    """Coordinates ``(m, n)`` of rigid displacements ``(m, 4, 4)`` of the measured link relative to the
    reference configuration, rotating about its point.

    Parameters
    ----------
    kinematics : GraphKinematics
    displacements : numpy.ndarray, shape (m, 4, 4)

    Returns
    -------
    numpy.ndarray, shape (m, n)

    Raises
    ------
    ScrewkitValueError
        If a matrix is not a rigid motion, or moves the link in a direction its motion does not have.

    Examples
    --------
    >>> h4 = kinematics_of(load_mechanism("h4"))
    >>> lift = np.eye(4); lift[2, 3] = -10
    >>> displacement_coordinates(h4, lift[None]).round(9).tolist()
    [[0.0, 0.0, -760.0, 0.0]]
    """
    rotation, translation = displacements[:, :3, :3], displacements[:, :3, 3]
    orthonormal = np.abs(rotation @ np.swapaxes(rotation, -1, -2) - np.eye(3)).max(axis=(-1, -2)) < 1e-9
    proper = np.linalg.det(rotation) > 0
    bottom = np.all(np.abs(displacements[:, 3] - [0, 0, 0, 1]) < 1e-12, axis=-1)
    if not np.all(orthonormal & proper & bottom):
        bad = int(np.flatnonzero(~(orthonormal & proper & bottom))[0])
        raise ScrewkitValueError(
            f"Expected `poses` of shape (..., 4, 4) to be rigid motions (a rotation, a translation and the "
            f"last row 0 0 0 1), got {displacements[bad].round(6).tolist()} at index {bad}."
        )
    coordinates = kinematics.coordinates
    position = coordinates.point + translation
    vector = rotation_log(rotation)
    translation_mask = np.array([k == "translation" for k in coordinates.kinds])
    values = np.where(
        translation_mask, position @ coordinates.directions.T, vector @ coordinates.directions.T
    )
    values = values + np.where(translation_mask, 0.0, kinematics.angle_offsets)
    if kinematics.complete:  # the directions left out must not move
        task = kinematics.task
        count = len(coordinates.names)
        extra = task.directions[count:]
        moved = np.where(task.translation[count:], (position - coordinates.point) @ extra.T, vector @ extra.T)
        size = np.max(np.abs(moved), axis=1, initial=0.0)
        limit = 1e-9 * np.maximum(1.0, np.where(task.translation[count:], kinematics.model.length, 1.0)).max(
            initial=1.0
        )
        if np.any(size > limit):
            bad = int(np.argmax(size))
            raise ScrewkitValueError(
                "Expected `poses` (4×4 displacements) the mechanism's motion makes "
                f"({', '.join(coordinates.names)}), got one at index {bad} that also moves "
                f"{size[bad]:.3g} along a direction the motion does not have."
            )
    return values


def displacements_as_coordinates(mechanism: Any, poses: Any, argument: str = "poses") -> Any:
    """Poses as coordinates: ``(..., 4, 4)`` rigid displacements of the platform relative to the
    reference configuration (rotating about the platform point) converted; a 2-D ``(4, 4)`` array
    is four poses of a four-coordinate robot, one displacement otherwise. Anything else is returned
    as it is.

    Parameters
    ----------
    mechanism : Mechanism
    poses : array_like or None
    argument : str, optional
        The argument's name, for the error messages.

    Returns
    -------
    numpy.ndarray or the input
        Coordinates ``(..., n)`` for displacements, else ``poses`` itself.

    Raises
    ------
    ScrewkitTypeError
        If a displacement holds something other than real numbers.
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
        shape = np.shape(poses)
    except ValueError:  # ragged: the callee names it
        return poses
    displacement = shape[-2:] == (4, 4) and (len(shape) > 2 or len(mechanism.pose_names) != 4)
    if not displacement:
        return poses
    array = B.as_array(poses, argument, (4, 4), symbolic=False).astype(float)
    flat = array.reshape(-1, 4, 4)
    return displacement_coordinates(kinematics_of(mechanism), flat).reshape(*array.shape[:-2], -1)


def forward_posed(robot: Any, values: Any, *, rtol: float | None, length_scale: float | None) -> Any:
    """What :meth:`screwkit.robots.mechanism.Mechanism.forward` returns: the mechanism at the platform
    poses its actuated-joint displacements give (unreached ones NaN, with their reasons).

    Parameters
    ----------
    robot : Mechanism
    values : array_like, shape (..., k)
        Displacements of the actuated joints from the reference configuration.
    rtol, length_scale : float or None
        As in :meth:`~screwkit.robots.mechanism.Mechanism.at`.

    Returns
    -------
    PosedMechanism

    Raises
    ------
    ScrewkitValueError
        If ``values`` does not have one finite value per actuated joint.

    Examples
    --------
    >>> forward_posed(load_mechanism("h4"), np.zeros(4), rtol=None, length_scale=None).poses.round(9).tolist()
    [[0.0, 0.0, -750.0, 0.0]]
    """
    from .posed import PosedMechanism

    kinematics = kinematics_of(robot)
    count = len(kinematics.actuated)
    array = B.as_array(values, "values", (count,), symbolic=False).astype(float)
    if not np.all(np.isfinite(array)):
        raise ScrewkitValueError(
            f"Expected finite `values` (one per actuated joint {kinematics.actuated}), got NaN or infinity."
        )
    array = array[None] if array.ndim == 1 else array  # one set of values: a batch of one, as at()
    shape = array.shape[:-1]
    poses, closed = kinematics.forward(array.reshape(-1, count))
    reasons = {
        tuple(int(j) for j in np.unravel_index(i, shape)): str(closed.reasons[i])
        for i in np.flatnonzero(~closed.reached)
    }
    return PosedMechanism.create(
        robot, poses.reshape(*shape, -1), rtol=rtol, length_scale=length_scale, failures=reasons
    )
