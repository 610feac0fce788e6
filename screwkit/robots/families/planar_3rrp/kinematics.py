"""The planar 3-RRP's position kinematics: the inverse kinematics of every working mode, the reach
margin, and the forward kinematics (every assembly), vectorised over poses.

Examples
--------
>>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
>>> inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0]).shape
(3,)
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import numpy as np

from ....algebra.backend import DEFAULT_RTOL, as_array
from ....algebra.checks import checked_rtol
from ....exceptions import (
    DegenerateGeometryError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from ...two_limb import REACH_ULPS
from .parameters import Planar3RRPParameters, _dot, _first_index, _perp, _readonly, _unit

__all__ = [
    "WORKING_MODES",
    "ForwardKinematicsSolutions",
    "forward_kinematics",
    "inverse_kinematics",
    "reach_margin",
]


#: The eight working modes (signs of ``J_kk``), shape ``(8, 3)``; broadcast a pose against it.
WORKING_MODES = np.array(list(itertools.product((1.0, -1.0), repeat=3)))
WORKING_MODES.flags.writeable = False


# --------------------------------------------------------------------------------------------------
# Position kinematics
# --------------------------------------------------------------------------------------------------


def _guides(parameters: Planar3RRPParameters, pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Guide points ``Q_k = C + R(φ) P_k`` and directions ``b_k``, each ``(..., 3, 2)``."""
    phi = pose[..., 2:3]
    c, s = np.cos(phi), np.sin(phi)
    px, py = parameters.platform_points[:, 0], parameters.platform_points[:, 1]
    q = pose[..., None, :2] + np.stack([c * px - s * py, s * px + c * py], axis=-1)
    return q, _unit(phi + parameters.guide_angles)


def _working_mode(value: Any) -> np.ndarray:
    mode = as_array(value, "working_mode", (3,))
    if not np.all(np.abs(mode) == 1):
        raise ScrewkitValueError(
            "Expected `working_mode` entries to be +1 or -1 (sign of J_kk per limb), "
            f"got {mode.tolist()}."
        )
    return mode


def reach_margin(parameters: Planar3RRPParameters, pose: Any) -> np.ndarray:
    """Normalised reach ``(l_k² - h_k²) / l_k²`` of each limb at the given poses.

    ``h_k`` is the distance from ``M_k`` to the guide line of limb ``k``. The margin is positive
    where limb ``k`` reaches its guide at two elbow points, zero on the boundary, negative outside.
    Where it is reachable it equals ``(J_kk / l_k)²`` (Eq. 11a), so its zeros are the inverse
    (type-1) singularities, Eq. (12); it continues ``det J`` analytically past the boundary.

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> round(float(reach_margin(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])[0]), 6)  # 1 - 0.75²/0.9²
    0.305556
    """
    pose = as_array(pose, "pose", (3,))
    q, b = _guides(parameters, pose)
    h = _dot(q - parameters.base_points, _perp(b))
    lengths = parameters.link_lengths
    return (lengths**2 - h**2) / lengths**2


def inverse_kinematics(
    parameters: Planar3RRPParameters,
    pose: Any,
    working_mode: Any = (1, 1, 1),
    *,
    rtol: float = DEFAULT_RTOL,
) -> np.ndarray:
    """Actuated joint angles ``θ`` of the given poses in the given working modes.

    Limb ``k`` meets its guide line where the circle of radius ``l_k`` about ``M_k`` cuts it:
    ``γ_k = -(Q_k - M_k)·b_k + σ_k sqrt(l_k² - h_k²)``, ``A_k = Q_k + γ_k b_k`` (module docstring).

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.
    working_mode : array_like, shape (..., 3)
        Sign ``σ_k = ±1`` of ``J_kk`` per limb; broadcast against ``pose``. All eight branches:
        ``inverse_kinematics(p, pose[..., None, :], WORKING_MODES)``.
    rtol : float, default 1e-9
        A limb with ``reach_margin >= -rtol`` is on the boundary (both branches coincide).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        ``θ_k`` in ``(-π, π]``.

    Raises
    ------
    UnreachablePoseError
        If a limb cannot reach its guide line; the message names the limb and the batch index.
    ScrewkitValueError
        If ``working_mode`` has an entry other than ±1.

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> theta = inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> np.round(np.degrees(theta), 3)  # 30° - atan(sqrt(0.2475) / 0.75), then +120°, +240°
    array([ -3.557, 116.443, -123.557])
    >>> inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0], WORKING_MODES).shape
    (8, 3)
    """
    pose = as_array(pose, "pose", (3,))
    mode = _working_mode(working_mode)
    rtol = checked_rtol(rtol)
    margin = reach_margin(parameters, pose)
    outside = margin < -rtol
    if np.any(outside):
        index = _first_index(outside)
        limb = index[-1]
        raise UnreachablePoseError(
            f"Limb {limb + 1} cannot reach pose {pose[index[:-1]].tolist()} (batch index "
            f"{index[:-1]}): the distance from M{limb + 1} to its guide line exceeds the link "
            f"length {parameters.link_lengths[limb]:g} (reach margin {margin[index]:.3g} < 0)."
        )
    q, b = _guides(parameters, pose)
    d = q - parameters.base_points
    lengths = parameters.link_lengths
    # a limb within rounding of its reach is put at its reach exactly (1 - h²/l² has condition ~2)
    margin = np.where(margin <= 2.0 * REACH_ULPS * np.finfo(float).eps, 0.0, margin)
    gamma = -_dot(d, b) + mode * lengths * np.sqrt(margin)
    elbow_offset = d + gamma[..., None] * b
    return np.arctan2(elbow_offset[..., 1], elbow_offset[..., 0])


@dataclass(frozen=True, eq=False, slots=True)
class ForwardKinematicsSolutions:
    """The (at most two) assembly modes of given actuated joint angles.

    Attributes
    ----------
    poses : numpy.ndarray, shape (..., 2, 3)
        ``(x, y, φ)`` of each solution, ``φ`` in ``[-π, π)``; zeros where ``valid`` is False.
    valid : numpy.ndarray of bool, shape (..., 2)
        Whether each solution exists. At a direct singularity the two coincide.
    """

    poses: np.ndarray
    valid: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary.

        Returns
        -------
        dict
            Plain lists and numbers.

        Examples
        --------
        >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
        >>> fk = forward_kinematics(EXAMPLE_PARAMETERS, [0.1, 2.2, -2.0])
        >>> sorted(fk.to_dict())
        ['poses', 'valid']
        """
        return {"poses": self.poses.tolist(), "valid": self.valid.tolist()}

    def __str__(self) -> str:
        return (
            f"ForwardKinematicsSolutions: {int(self.valid.sum())} valid of "
            f"{self.valid.size} (batch shape {self.valid.shape[:-1]})"
        )


def forward_kinematics(
    parameters: Planar3RRPParameters, joint_angles: Any, *, rtol: float = DEFAULT_RTOL
) -> ForwardKinematicsSolutions:
    """All platform poses of given actuated joint angles, in closed form.

    With the elbows ``A_k`` fixed by ``θ``, the closures ``n_k(φ)·C = n_k(φ)·A_k - c_k`` (module
    docstring) are three linear equations in ``C``. Expanding ``det[n_k, n_k·A_k - c_k]`` along its
    last column, the cofactors ``n_k × n_l`` do not depend on ``φ``, so consistency reads
    ``P cos φ + Q sin φ = S`` with ``P = Σ s_k n⁰_k·A_k``, ``Q = Σ s_k (E n⁰_k)·A_k``,
    ``S = Σ s_k n⁰_k·P_k``, ``s_k = n⁰_{k+1} × n⁰_{k+2}``: at most two roots ``φ``, then ``C`` by
    least squares. These are all the solutions.

    Parameters
    ----------
    parameters : Planar3RRPParameters
    joint_angles : array_like, shape (..., 3)
    rtol : float, default 1e-9
        ``|S| <= (1 + rtol) sqrt(P² + Q²)`` counts as solvable; ``P, Q, S`` all below
        ``rtol * length_scale`` is a self-motion.

    Returns
    -------
    ForwardKinematicsSolutions

    Raises
    ------
    DegenerateGeometryError
        If the joint angles admit a continuum of poses (the platform turns about the common point of
        concurrent guides with coincident elbows).

    Examples
    --------
    >>> from screwkit.robots.families.planar_3rrp.parameters import EXAMPLE_PARAMETERS
    >>> theta = inverse_kinematics(EXAMPLE_PARAMETERS, [0.05, -0.02, 0.1])
    >>> fk = forward_kinematics(EXAMPLE_PARAMETERS, theta)
    >>> fk.valid
    array([ True,  True])
    >>> bool(np.any(np.all(np.isclose(fk.poses, [0.05, -0.02, 0.1]), axis=-1)))
    True
    """
    theta = as_array(joint_angles, "joint_angles", (3,))
    rtol = checked_rtol(rtol)
    elbows = parameters.base_points + parameters.link_lengths[:, None] * _unit(theta)
    normals0 = _perp(_unit(parameters.guide_angles))
    offsets = _dot(normals0, parameters.platform_points)
    shifted1, shifted2 = np.roll(normals0, -1, axis=0), np.roll(normals0, -2, axis=0)
    cofactors = shifted1[:, 0] * shifted2[:, 1] - shifted1[:, 1] * shifted2[:, 0]
    p_coef = _dot(_dot(normals0, elbows), cofactors)
    q_coef = _dot(_dot(_perp(normals0), elbows), cofactors)
    s_coef = float(_dot(cofactors, offsets))
    radius = np.hypot(p_coef, q_coef)
    scale = rtol * parameters.length_scale
    continuum = (radius <= scale) & (abs(s_coef) <= scale)
    if np.any(continuum):
        index = _first_index(continuum)
        raise DegenerateGeometryError(
            f"`joint_angles` {theta[index].tolist()} (batch index {index}) admit a continuum of "
            "platform poses: the consistency condition P cos φ + Q sin φ = S vanishes identically "
            "(the platform turns about the common point of its guides)."
        )
    safe = np.where(radius > 0, radius, 1.0)
    valid_one = (radius > 0) & (abs(s_coef) <= (1.0 + rtol) * radius)
    half_width = np.arccos(np.clip(s_coef / safe, -1.0, 1.0))
    phi = np.arctan2(q_coef, p_coef)[..., None] + np.stack([half_width, -half_width], axis=-1)
    phi = np.mod(phi + np.pi, 2.0 * np.pi) - np.pi
    normals = _perp(_unit(phi[..., None] + parameters.guide_angles))  # (..., 2, 3, 2)
    rhs = _dot(normals, elbows[..., None, :, :]) - offsets
    gram = np.einsum("...ka,...kb->...ab", normals, normals)
    centre = np.linalg.solve(gram, np.einsum("...ka,...k->...a", normals, rhs)[..., None])[..., 0]
    valid = np.broadcast_to(valid_one[..., None], phi.shape)
    poses = np.where(valid[..., None], np.concatenate([centre, phi[..., None]], axis=-1), 0.0)
    return ForwardKinematicsSolutions(poses=_readonly(poses), valid=_readonly(valid))
