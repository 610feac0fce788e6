"""The planar 3-RRP's configuration: the joint angles, elbows, sliders and guides of a batch of poses
in one working mode (:meth:`Planar3RRPConfiguration.from_pose`, the family's inverse kinematics).

Examples
--------
>>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
>>> Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [[0.0, 0.0, 0.0]]).batch_shape
(1,)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ....algebra.backend import DEFAULT_RTOL, as_array
from ....algebra.checks import checked_rtol
from ....exceptions import (
    ScrewkitTypeError,
    ScrewkitValueError,
)
from .kinematics import _guides, inverse_kinematics
from .parameters import Planar3RRPParameters, _dot, _first_index, _perp, _readonly, _unit

__all__ = ["Planar3RRPConfiguration"]


# --------------------------------------------------------------------------------------------------
# Configurations
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False, slots=True)
class Planar3RRPConfiguration:
    """A pose together with its actuated joint angles (one or a batch).

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.
    joint_angles : array_like, shape (..., 3)
        ``θ_k``; broadcast against ``pose``.
    closure_rtol : float, default 1e-9
        Each elbow ``A_k = M_k + l_k u(θ_k)`` must lie within ``closure_rtol * length_scale`` of its
        guide line.

    Attributes
    ----------
    base_points, elbow_points, guide_directions : numpy.ndarray, shape (..., 3, 2)
        ``M_k = C_1i``, ``A_k = C_ij`` and the unit guide directions ``b_k`` (base frame).
    platform_point : numpy.ndarray, shape (..., 2)
        The reference point ``C``.
    slider_positions : numpy.ndarray, shape (..., 3)
        ``γ_k`` with ``A_k = C + R(φ) P_k + γ_k b_k``.

    Raises
    ------
    ScrewkitValueError
        If an elbow is off its guide line (names the limb and batch index).

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [[0, 0, 0], [0.1, 0, 0.2]])
    >>> c.elbow_points.shape, c.slider_positions.shape
    ((2, 3, 2), (2, 3))
    """

    parameters: Planar3RRPParameters
    pose: np.ndarray
    joint_angles: np.ndarray
    closure_rtol: float = DEFAULT_RTOL
    base_points: np.ndarray = field(init=False)
    elbow_points: np.ndarray = field(init=False)
    guide_directions: np.ndarray = field(init=False)
    platform_point: np.ndarray = field(init=False)
    slider_positions: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        params = self.parameters
        if not isinstance(params, Planar3RRPParameters):
            raise ScrewkitTypeError(
                f"Expected `parameters` to be Planar3RRPParameters, got {type(params).__name__}."
            )
        rtol = checked_rtol(self.closure_rtol, "closure_rtol")
        pose = as_array(self.pose, "pose", (3,))
        theta = as_array(self.joint_angles, "joint_angles", (3,))
        shape = np.broadcast_shapes(pose.shape[:-1], theta.shape[:-1])
        pose = np.broadcast_to(pose, (*shape, 3))
        theta = np.broadcast_to(theta, (*shape, 3))
        q, b = _guides(params, pose)
        base = np.broadcast_to(params.base_points, (*shape, 3, 2))
        elbows = base + params.link_lengths[:, None] * _unit(theta)
        residual = np.abs(_dot(elbows - q, _perp(b)))
        off = residual > rtol * params.length_scale
        if np.any(off):
            index = _first_index(off)
            raise ScrewkitValueError(
                f"Expected the elbow of limb {index[-1] + 1} on its guide line, but it is "
                f"{residual[index]:.3g} away at batch index {index[:-1]} (more than closure_rtol "
                f"* length_scale = {rtol * params.length_scale:.3g}): `joint_angles` do not match "
                "`pose`."
            )
        for name, value in (
            ("pose", pose),
            ("joint_angles", theta),
            ("base_points", base),
            ("elbow_points", elbows),
            ("guide_directions", b),
            ("platform_point", pose[..., :2]),
            ("slider_positions", _dot(elbows - q, b)),
        ):
            object.__setattr__(self, name, _readonly(value))

    @classmethod
    def from_pose(
        cls,
        parameters: Planar3RRPParameters,
        pose: Any,
        working_mode: Any = (1, 1, 1),
        *,
        rtol: float = DEFAULT_RTOL,
    ) -> Planar3RRPConfiguration:
        """The configuration of ``pose`` in ``working_mode`` (see :func:`inverse_kinematics`).

        Parameters
        ----------
        parameters : Planar3RRPParameters
            The robot.
        pose : array_like, shape (..., 3)
            ``(x, y, φ)``, φ in radians.
        working_mode : sequence of 3 signs, optional
            The signs of ``J_kk`` (default ``(1, 1, 1)``).
        rtol : float, optional
            Relative tolerance of the reach test.

        Returns
        -------
        Planar3RRPConfiguration
            The configuration over the batch of poses.

        Examples
        --------
        >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
        >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0, 0, 0], (1, -1, 1))
        >>> c.joint_angles.shape
        (3,)
        """
        theta = inverse_kinematics(parameters, pose, working_mode, rtol=rtol)
        return cls(parameters, np.broadcast_to(as_array(pose, "pose", (3,)), theta.shape), theta)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading batch shape of the configuration."""
        return tuple(self.pose.shape[:-1])


def _check_config(config: Any) -> Planar3RRPConfiguration:
    if not isinstance(config, Planar3RRPConfiguration):
        raise ScrewkitTypeError(
            f"Expected `config` to be a Planar3RRPConfiguration, got {type(config).__name__}."
        )
    return config
