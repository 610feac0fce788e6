"""The McGill SMG's configuration: the points of both legs over a batch of poses (Eqs. 1-2 of
paper 001), and the forward chain of one leg (:func:`leg_pose`).

Examples
--------
>>> config = load_mechanism("mcgill_smg").configuration()
>>> type(config).__name__, config.joint_angles.shape
('McGillConfiguration', (2, 4))
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ....algebra.backend import as_array
from ....exceptions import ScrewkitValueError
from ...two_limb import (
    frozen,
)
from .parameters import LEGS, McGillParameters

__all__ = ["McGillConfiguration", "leg_pose"]


_SIGN = np.array([1.0, -1.0])  # s(J), Eq. (13)
_K = np.array([0.0, 0.0, 1.0])


# --------------------------------------------------------------------------------------------------
# Geometry of a leg
# --------------------------------------------------------------------------------------------------


def _e(angle: np.ndarray) -> np.ndarray:
    """``e(θ) = (-sin θ, cos θ, 0)``, the horizontal direction of Eqs. (1a)-(2b)."""
    return np.stack([-np.sin(angle), np.cos(angle), np.zeros_like(angle)], axis=-1)


def _pan_points(params: McGillParameters) -> np.ndarray:
    """``O_J0`` of both legs, shape (2, 3)."""
    return np.outer(-_SIGN * params.l0 / 2.0, [0.0, 1.0, 0.0])


def _leg_index(leg: Any) -> int:
    if leg not in LEGS:
        raise ScrewkitValueError(f"Expected `leg` to be one of {LEGS}, got {leg!r}.")
    return LEGS.index(leg)


def _chain(
    params: McGillParameters, theta1: np.ndarray, theta2: np.ndarray, theta23: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Points ``O_J1``, ``O_J2``, ``O_J3`` and ``e(θ_J1)`` of both legs, shape (..., 2, 3)."""
    h = _e(theta1)
    shoulder = _pan_points(params) + (_SIGN * params.l1)[:, None] * h
    elbow = shoulder + params.l2 * (np.cos(theta2)[..., None] * h + np.sin(theta2)[..., None] * _K)
    wrist = elbow + params.l3 * (np.cos(theta23)[..., None] * h + np.sin(theta23)[..., None] * _K)
    return shoulder, elbow, wrist, h


def leg_pose(params: McGillParameters, leg: str, joint_angles: Any) -> np.ndarray:
    """Pose of the moving plate from the four joint angles of one leg: Eqs. (1) and (2).

    Parameters
    ----------
    params : McGillParameters
    leg : {"I", "II"}
    joint_angles : (..., 4) array_like
        ``(θ_J1, θ_J2, θ_J3, θ_J4)`` in radians.

    Returns
    -------
    (..., 4) ndarray
        ``(x, y, z, φ)`` with ``φ = θ_J1 + θ_J4`` (not wrapped).

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 300, 200, -50, -50, 80, 60)
    >>> leg_pose(p, "I", [0.0, 0.0, 0.0, 0.0])  # Eq. (1): y = -l0/2 + l1 + l2 + l3 + R
    array([   0.,  900., -100.,    0.])
    """
    index = _leg_index(leg)
    angles = as_array(joint_angles, "joint_angles", (4,))
    t1, t2, t3, t4 = np.moveaxis(angles, -1, 0)
    sign = _SIGN[index]
    kappa = sign * params.l1 + params.l2 * np.cos(t2) + params.l3 * np.cos(t2 + t3)
    phi = t1 + t4
    centre = _pan_points(params)[index] + kappa[..., None] * _e(t1) + sign * params.radius * _e(phi)
    z = params.l2 * np.sin(t2) + params.l3 * np.sin(t2 + t3) + params.b4 + params.b5
    return np.stack([centre[..., 0], centre[..., 1], z, phi], axis=-1)


# --------------------------------------------------------------------------------------------------
# Configuration
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class McGillConfiguration:
    """Every joint of a McGill SMG at one pose or a batch of poses (read-only arrays).

    Leg axes (length 2) follow :data:`LEGS`.

    Attributes
    ----------
    params : McGillParameters
    mode : tuple of 4 int
        The working mode ``(pan_I, elbow_I, pan_II, elbow_II)``.
    pose : (..., 4) ndarray
        ``(x, y, z, φ)``.
    joint_angles : (..., 2, 4) ndarray
        ``(θ_J1, θ_J2, θ_J3, θ_J4)`` per leg (Eqs. 1-2), wrapped to ``[-π, π)``.
    pan_point, shoulder, elbow, wrist, wrist_joint : (..., 2, 3) ndarray
        ``O_J0`` (on the pan axis), ``O_J1``, ``O_J2``, ``O_J3``, ``O_J4``.
    pan_axis : (..., 2, 3) ndarray
        ``k``: the pan axes and the wrist axes (vertical).
    tilt_axis : (..., 2, 3) ndarray
        ``f_J``: the axes of the eight revolute joints of each leg's parallelograms.
    platform_point : (..., 3) ndarray
        The operation point ``P``.

    Examples
    --------
    >>> from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> config = inverse_kinematics(p, [[0.0, 0.0, -600.0, 0.0], [10.0, 0.0, -600.0, 0.1]])
    >>> config.batch_shape, config.wrist.shape
    ((2,), (2, 2, 3))
    """

    params: McGillParameters
    mode: tuple[int, ...]
    pose: np.ndarray
    joint_angles: np.ndarray
    pan_point: np.ndarray
    shoulder: np.ndarray
    elbow: np.ndarray
    wrist: np.ndarray
    wrist_joint: np.ndarray
    pan_axis: np.ndarray
    tilt_axis: np.ndarray
    platform_point: np.ndarray

    def __post_init__(self) -> None:
        for name in (
            "pose", "joint_angles", "pan_point", "shoulder", "elbow", "wrist", "wrist_joint",
            "pan_axis", "tilt_axis", "platform_point",
        ):
            object.__setattr__(self, name, frozen(getattr(self, name)))

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Shape of the batch of poses."""
        return tuple(self.pose.shape[:-1])

    @property
    def actuated(self) -> np.ndarray:
        """``(θ_I1, θ_I2, θ_II1, θ_II2)``, shape (..., 4): the vector ``θ`` of Eq. (19)."""
        return np.asarray(self.joint_angles[..., :2].reshape(*self.batch_shape, 4))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary of the pose, the mode and the joint angles.

        Returns
        -------
        dict
            Plain lists and numbers.
        """
        return {
            "mode": list(self.mode),
            "pose": self.pose.tolist(),
            "joint_angles": self.joint_angles.tolist(),
        }

    def __str__(self) -> str:
        return (
            f"McGillConfiguration(mode={self.mode}, batch_shape={self.batch_shape}, "
            f"pose={np.round(self.pose, 6).tolist()})"
        )


def _configuration(
    params: McGillParameters, mode: tuple[int, ...], pose: np.ndarray, joint_angles: np.ndarray
) -> McGillConfiguration:
    t1, t2, t3, _ = np.moveaxis(joint_angles, -1, 0)
    shoulder, elbow, wrist, h = _chain(params, t1, t2, t2 + t3)
    pan_point = np.broadcast_to(_pan_points(params), wrist.shape)
    vertical = np.broadcast_to(_K, wrist.shape)
    platform_point = np.stack([pose[..., 0], pose[..., 1], pose[..., 2]], axis=-1)
    return McGillConfiguration(
        params=params,
        mode=mode,
        pose=pose,
        joint_angles=joint_angles,
        pan_point=pan_point,
        shoulder=shoulder,
        elbow=elbow,
        wrist=wrist,
        wrist_joint=wrist + params.b4 * _K,
        pan_axis=vertical,
        tilt_axis=np.cross(h, _K),
        platform_point=platform_point,
    )
