"""The McGill Schönflies-motion generator: two RΠΠR limbs on a bar-shaped moving plate.

Source: paper 001 (Angeles, Caro, Khan, Morozov, "Kinetostatic design of an innovative
Schönflies-motion generator", Proc. IMechE C 220(7), 2006), file
``/work/shared/papers/001_92cd67fab518f4bc.txt``. Equation, table and figure numbers refer to it.

The model
---------
Frame: origin midway between the feet ``O_I0``, ``O_II0`` of the two pan axes, ``k`` up, as in
Eqs. (1)-(2). Leg ``J`` has the sign ``s(J) = +1, -1`` for ``J = I, II`` (Eq. 13) and

* ``O_J0 = -s(J) (l0/2) j`` on the vertical pan axis (actuated angle ``θ_J1``);
* ``e(θ) = (-sin θ, cos θ, 0)``, the horizontal direction of the leg's vertical plane, and
  ``f_J = e(θ_J1) × k = (cos θ_J1, sin θ_J1, 0)``, the normal of that plane;
* ``O_J1 = O_J0 + s(J) l1 e(θ_J1)``: the horizontal offset ``a_J1``;
* ``O_J2 = O_J1 + l2 (cos θ_J2 e + sin θ_J2 k)``: the proximal parallelogram (actuated tilt
  ``θ_J2`` about ``f_J``);
* ``O_J3 = O_J2 + l3 (cos θ_J23 e + sin θ_J23 k)``, ``θ_J23 = θ_J2 + θ_J3``: the distal
  parallelogram (passive ``θ_J3``);
* ``O_J4 = O_J3 + b4 k`` on the vertical wrist axis (passive ``θ_J4``, ``φ = θ_J1 + θ_J4``,
  Eqs. 1d, 2d) and ``P = O_J4 + s(J) R e(φ) + b5 k``.

This reproduces Eqs. (1a)-(2d) term by term (``tests/test_families_mcgill_smg.py`` checks it). The
moving plate is the bar ``O_I4 O_II4`` of length ``2R`` with ``P`` at its middle.

Our choices where the paper is silent (Table 1 and Sec. 6 give only ``R = 200 mm``,
``l2 = 600 mm``, ``l3 = √2 R``):

* ``a4 = 0`` (``O_J4`` straight above or below ``O_J3``) and ``a5 = R``. A parallelogram keeps the
  orientation of its input link, so any horizontal offset along ``e(θ_J1)`` after the pan joint
  commutes with the parallelograms and is absorbed in ``l1``; only ``b4 + b5`` enters Eqs. (1)-(2).
* ``l0``, ``l1``, ``b4``, ``b5`` are parameters without published values.
* The parallelograms' short sides are vertical, of lengths ``proximal_width`` and
  ``distal_width``: corners ``O_J1, O_J1 + w k, O_J2 + w k, O_J2`` (proximal) and
  ``O_J2, O_J2 + w k, O_J3 + w k, O_J3`` (distal), revolute axes along ``f_J``. They do not enter
  the kinematics or ``A``, ``B``; they matter for the twist graph of the physical mechanism (a
  parallelogram whose long links are vertical is flat: all four axes in one plane).

Working modes. The inverse kinematics of each leg has two pan branches and two elbow branches. A
working mode is ``(pan_I, elbow_I, pan_II, elbow_II)``, signs with ``pan_J = sgn κ_J``, where the
horizontal projection of ``O_J3 - O_J0`` is ``κ_J e(θ_J1)`` (``κ_J = s(J) l1 + l2 cos θ_J2 +
l3 cos θ_J23``), and ``elbow_J = sgn sin θ_J3``. Beware Eq. (2)'s convention: leg II's tilt is
measured from ``+e(θ_II1)`` while its offset points along ``-e(θ_II1)``, so the posture that is the
mirror image of leg I (both offsets toward the other leg) has ``pan = (+1, -1)`` and *opposite*
elbow signs. :data:`DEFAULT_MODE` ``(1, 1, -1, -1)`` is that mirror-symmetric posture with both
elbows away from the other leg. Mode ``(1, 1, -1, 1)`` makes the two legs translates of each other,
which is a parallel singularity (Eq. 24) whenever ``P`` lies midway between the pan axes with
``φ = 0``.

Where paper 001 is garbled or wrong
-----------------------------------
Table 1 puts the origin of ``F`` at ``O_I0`` (so does the ``+ l0 j`` of Eq. 3b) while Eqs. (1)-(2)
put it midway; we follow Eqs. (1)-(2). Paper 001's Jacobians ``A``, ``B`` (Eqs. 16-19), the factors
of their singularities and what the paper gets wrong about them (the printed block shapes of
Eq. 17a, Figs. 7a-7b, Eq. 22) are a paper analysis, not the robot model: they live in
``tests/paper_001.py`` beside the tests that check them. The mechanism's own Jacobians and labels
come from the analysis core (:meth:`screwkit.robots.catalog.Mechanism.at`).

Examples
--------
>>> import numpy as np
>>> from screwkit.robots.families.mcgill_smg import McGillParameters, inverse_kinematics, joints
>>> from screwkit.core.singularity import classify_table
>>> smg = McGillParameters(l0=600.0, l1=100.0, l2=600.0, l3=200.0 * np.sqrt(2), radius=200.0,
...     b4=-50.0, b5=-50.0, proximal_width=80.0, distal_width=60.0)
>>> config = inverse_kinematics(smg, [[0.0, 0.0, -600.0, 0.0]])
>>> config.joint_angles[0, :, 0]  # pan angles: O_I3 and O_II3 lie on the y axis
array([0., 0.])
>>> classify_table(joints(config)).verdict.tolist()
['regular']
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from ...algebra.backend import as_array
from ...core.jacobians import schoenflies_basis
from ...exceptions import DegenerateGeometryError, ScrewkitValueError, UnreachablePoseError
from ...graphs.joints import JointTable
from ..two_limb import (
    ForwardSolutions,
    at_reach,
    check_parameters,
    checked_mode,
    describe_indices,
    frozen,
    joint_row,
    parameters_from_mapping,
    wrap_angle,
)
from . import Family

__all__ = [
    "DEFAULT_MODE",
    "FAMILY",
    "LEGS",
    "WORKING_MODES",
    "McGillConfiguration",
    "McGillParameters",
    "forward_kinematics",
    "inverse_kinematics",
    "joints",
    "leg_pose",
    "twist_basis",
]

#: Leg names, in the order of every leg axis of this module.
LEGS = ("I", "II")
#: The 16 working modes ``(pan_I, elbow_I, pan_II, elbow_II)`` (module docstring).
WORKING_MODES: tuple[tuple[int, ...], ...] = tuple(itertools.product((1, -1), repeat=4))
#: Mirror-symmetric legs, elbows away from each other (module docstring).
DEFAULT_MODE = (1, 1, -1, -1)

_SIGN = np.array([1.0, -1.0])  # s(J), Eq. (13)
_K = np.array([0.0, 0.0, 1.0])
#: Relative slack on the reach of a leg (|cos θ_J3| <= 1 + slack): poses built on the boundary
#: (a fully extended leg) must not be refused for a rounding error.
_REACH_SLACK = 1e-12


@dataclass(frozen=True, slots=True)
class McGillParameters:
    """Dimensions of a McGill SMG (Table 1 of paper 001; lengths in one unit of your choice).

    Parameters
    ----------
    l0 : float
        Distance between the two pan axes (Table 1), >= 0. Not given by the paper.
    l1 : float
        ``‖a_J1‖``, horizontal offset of the tilt axis from the pan axis (Eqs. 1-2), >= 0.
        Not given by the paper.
    l2, l3 : float
        Lengths of the proximal and distal parallelograms, > 0. Sec. 6: ``l2 = 600 mm``,
        ``l3 = √2 R = 282.843 mm``.
    radius : float
        ``R`` of Table 1, half the length of the moving bar, > 0. Sec. 6: 200 mm.
    b4, b5 : float
        Vertical projections of ``a_J4 = O_J3→O_J4`` and ``a_J5 = O_J4→P`` (Table 1), signed.
        Not given by the paper; only ``b4 + b5`` enters the kinematics.
    proximal_width, distal_width : float
        Short (vertical) sides of the two parallelograms, > 0. Our choice; only the joint axes of
        :func:`joints` depend on them.

    Examples
    --------
    >>> p = McGillParameters.from_mapping({"l0": 600, "l1": 100, "l2": 600, "l3": 282.843,
    ...     "radius": 200, "b4": -50, "b5": -50, "proximal_width": 80, "distal_width": 60})
    >>> p.l2, p.radius
    (600.0, 200.0)
    >>> McGillParameters(600, 100, 600, 282.843, -200, 0, 0, 80, 60)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected parameter `radius` of ... > 0, got -200.
    """

    l0: float
    l1: float
    l2: float
    l3: float
    radius: float
    b4: float
    b5: float
    proximal_width: float
    distal_width: float

    def __post_init__(self) -> None:
        check_parameters(
            self,
            positive=("l2", "l3", "radius", "proximal_width", "distal_width"),
            nonnegative=("l0", "l1"),
            real=("b4", "b5"),
        )

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> McGillParameters:
        """Build parameters from a mapping (e.g. a TOML table), naming ``source`` in every error.

        Raises
        ------
        CatalogError
            Unknown, missing or non-numeric fields.
        ScrewkitValueError
            Values out of range.

        Examples
        --------
        >>> McGillParameters.from_mapping({"l0": 600}, source="mcgill.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: mcgill.toml: missing field(s) ['l1', 'l2', ...
        """
        return parameters_from_mapping(cls, mapping, source)

    def scaled(self, factor: float) -> McGillParameters:
        """The same robot in another unit of length (every length times ``factor`` > 0).

        Examples
        --------
        >>> McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60).scaled(1e-3).l2
        0.6
        """
        if not (isinstance(factor, int | float) and factor > 0):
            raise ScrewkitValueError(f"Expected `factor` to be a number > 0, got {factor!r}.")
        return McGillParameters(
            *(getattr(self, name) * factor for name in self.__dataclass_fields__)
        )


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
        """JSON-ready dictionary of the pose, the mode and the joint angles."""
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


# --------------------------------------------------------------------------------------------------
# Inverse and forward kinematics
# --------------------------------------------------------------------------------------------------


def inverse_kinematics(
    params: McGillParameters, pose: Any, mode: Any = DEFAULT_MODE
) -> McGillConfiguration:
    """Joint angles of both legs for poses ``(x, y, z, φ)``: Eqs. (1)-(2) solved per leg.

    For leg ``J``: ``O_J3 = P - s(J) R e(φ) - (b4 + b5) k``; the pan angle makes ``O_J3 - O_J0`` lie
    along ``pan_J e(θ_J1)`` (so ``κ_J = pan_J |O_J3 - O_J0|_horizontal``); the tilt and distal
    angles solve the planar two-link problem ``(κ_J - s(J) l1, z - b4 - b5) = l2 (cos θ_J2,
    sin θ_J2) + l3 (cos θ_J23, sin θ_J23)`` with ``sgn sin θ_J3 = elbow_J``; ``θ_J4 = φ - θ_J1``.
    On the pan axis (``κ_J = 0``, a serial singularity) the pan angle is indeterminate: the value
    returned (``atan2`` of signed zeros) is one of infinitely many solutions.

    Parameters
    ----------
    params : McGillParameters
    pose : (..., 4) array_like
        ``(x, y, z, φ)``; lengths in the unit of ``params``, ``φ`` in radians.
    mode : tuple of 4 int, default :data:`DEFAULT_MODE`
        ``(pan_I, elbow_I, pan_II, elbow_II)``, each +1 or -1.

    Returns
    -------
    McGillConfiguration

    Raises
    ------
    UnreachablePoseError
        A leg cannot reach its wrist point ``O_J3`` (the message names the leg and the poses).
    ScrewkitValueError
        Malformed ``pose`` or ``mode``.

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> config = inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0], mode=(1, 1, -1, -1))
    >>> bool(np.allclose(leg_pose(p, "II", config.joint_angles[1]), config.pose))
    True
    >>> inverse_kinematics(p, [0.0, 0.0, -1400.0, 0.0])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Leg I cannot reach the pose: ...
    """
    pose = as_array(pose, "pose", (4,))
    signs = np.array(checked_mode(mode, "mode", 4), dtype=float)
    pan, elbow = signs[0::2], signs[1::2]
    x, y, z, phi = np.moveaxis(pose, -1, 0)
    centre = np.stack([x, y, np.zeros_like(x)], axis=-1)[..., None, :]
    target = centre - (_SIGN * params.radius)[:, None] * _e(phi)[..., None, :]
    offset = target - _pan_points(params)
    kappa = pan * np.hypot(offset[..., 0], offset[..., 1])
    theta1 = np.arctan2(-pan * offset[..., 0], pan * offset[..., 1])
    u = kappa - _SIGN * params.l1
    w = np.broadcast_to((z - params.b4 - params.b5)[..., None], u.shape)
    l2, l3 = params.l2, params.l3
    cos3 = (u**2 + w**2 - l2**2 - l3**2) / (2.0 * l2 * l3)
    for index, leg in enumerate(LEGS):
        bad = np.abs(cos3[..., index]) > 1.0 + _REACH_SLACK
        if np.any(bad):
            distance = np.hypot(u[..., index], w[..., index])[bad]
            raise UnreachablePoseError(
                f"Leg {leg} cannot reach the pose: at {describe_indices(bad)} the distance from "
                f"O_{leg}1 to O_{leg}3 is {distance[:3].round(6).tolist()}, expected within "
                f"[|l2 - l3|, l2 + l3] = [{abs(l2 - l3):.6g}, {l2 + l3:.6g}]."
            )
    cos3 = at_reach(cos3, (u**2 + w**2 + l2**2 + l3**2) / (2.0 * l2 * l3))  # a stretched leg exactly
    sin3 = elbow * np.sqrt(1.0 - cos3**2)
    theta3 = np.arctan2(sin3, cos3)
    theta2 = np.arctan2(w, u) - np.arctan2(l3 * sin3, l2 + l3 * cos3)
    theta4 = phi[..., None] - theta1
    angles = wrap_angle(np.stack([theta1, theta2, theta3, theta4], axis=-1))
    return _configuration(params, tuple(int(s) for s in signs), pose, angles)


@functools.cache
def _tan_half_basis() -> np.ndarray:
    """``T[k + 4, j]``: coefficient of ``t^j`` in ``(1 + i t)^(4 + k) (1 - i t)^(4 - k)`` (built on
    first use: importing ``numpy.polynomial`` is not a cost of loading the catalog's families)."""
    basis = np.zeros((9, 9), dtype=complex)
    for k in range(-4, 5):
        product = np.polynomial.polynomial.polymul(
            np.polynomial.polynomial.polypow([1.0, 1.0j], 4 + k),
            np.polynomial.polynomial.polypow([1.0, -1.0j], 4 - k),
        )
        basis[k + 4, : product.size] = product
    return basis


_SAMPLES = 16  # > 2 * 4: exact Fourier coefficients of a degree-4 trigonometric polynomial
#: Candidates closer than this (sum of angle differences, rad) are one assembly.
_SAME_ASSEMBLY = 1e-6
_NEWTON_STEPS = 12
_MAX_ASSEMBLIES = 8  # Bézout bound of the system in (cos, sin) of both distal angles


def _wrists(elbow: np.ndarray, h: np.ndarray, l3: float, psi: np.ndarray) -> np.ndarray:
    """``O_J3`` for distal angles ``ψ_J`` of shape (..., m, 2): shape (..., m, 2, 3)."""
    radial = np.cos(psi)[..., None] * h[..., None, :, :] + np.sin(psi)[..., None] * _K
    return np.asarray(elbow[..., None, :, :] + l3 * radial)


def _eliminant_roots(
    elbow: np.ndarray, h: np.ndarray, l3: float, radius: float
) -> tuple[np.ndarray, np.ndarray]:
    """Roots ``ψ_I`` (..., 8) of the eliminant ``F`` and a mask of the real ones."""
    gap = elbow[..., 0, :] - elbow[..., 1, :]
    horizontal = gap * np.array([1.0, 1.0, 0.0])
    shift = gap[..., 2:3] / l3  # sin ψ_II = sin ψ_I + shift
    grid = 2.0 * np.pi * np.arange(_SAMPLES) / _SAMPLES
    chord = horizontal[..., None, :] + l3 * np.cos(grid)[:, None] * h[..., None, 0, :]
    sin_two = np.sin(grid) + shift
    m = np.sum(chord**2, axis=-1) + l3**2 * (1.0 - sin_two**2) - 4.0 * radius**2
    n = 2.0 * l3 * np.sum(chord * h[..., None, 1, :], axis=-1)
    samples = m**2 - (1.0 - sin_two**2) * n**2  # F(ψ_I) on the grid, (..., 16)
    scale = (np.sum(horizontal**2, axis=-1) + 2.0 * l3**2 + 4.0 * radius**2) ** 2
    degenerate = np.abs(samples).max(axis=-1) <= 1e-12 * scale
    if np.any(degenerate):
        raise DegenerateGeometryError(
            f"The actuated angles at {describe_indices(degenerate)} admit a continuum of "
            "assemblies (the eliminant F(ψ_I) vanishes identically): expected isolated assemblies."
        )
    coefficients = np.fft.fft(samples, axis=-1)[..., np.arange(-4, 5) % _SAMPLES] / _SAMPLES
    psi0 = grid[np.argmax(np.abs(samples), axis=-1)] - np.pi
    shifted = coefficients * np.exp(1j * np.arange(-4, 5) * psi0[..., None])
    poly = np.real(shifted @ _tan_half_basis())  # ascending powers of t, leading term F(ψ0 + π) != 0
    companion = np.zeros((*poly.shape[:-1], 8, 8))
    companion[..., 0, :] = -poly[..., 7::-1] / poly[..., 8:9]
    companion[..., np.arange(1, 8), np.arange(7)] = 1.0
    roots = np.linalg.eigvals(companion)
    real = np.abs(roots.imag) <= 1e-6 * (1.0 + np.abs(roots))
    return psi0[..., None] + 2.0 * np.arctan(roots.real), real


def _polish(
    elbow: np.ndarray, h: np.ndarray, l3: float, radius: float, psi: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Newton's method on the unsquared equations; returns ``ψ`` and the relative residual."""
    for _ in range(_NEWTON_STEPS):
        bar = np.diff(_wrists(elbow, h, l3, psi), axis=-2)[..., 0, :]  # O_II3 - O_I3
        e_height, e_length = bar[..., 2], bar[..., 0] ** 2 + bar[..., 1] ** 2 - 4.0 * radius**2
        along = np.sum(bar[..., None, :] * h[..., None, :, :], axis=-1)  # (..., m, 2)
        slope = l3 * np.sin(psi) * along  # ∂|bar|²/∂ψ_J = 2 s(J) l3 sin ψ_J (bar · h_J)
        j11, j12 = -l3 * np.cos(psi[..., 0]), l3 * np.cos(psi[..., 1])
        j21, j22 = 2.0 * slope[..., 0], -2.0 * slope[..., 1]
        det = j11 * j22 - j12 * j21
        usable = np.abs(det) > 1e-14 * (l3 * radius) ** 2
        safe = np.where(usable, det, 1.0)
        step = np.stack([j22 * e_height - j12 * e_length, j11 * e_length - j21 * e_height], -1)
        psi = psi - np.where(usable[..., None], step / safe[..., None], 0.0)
    bar = np.diff(_wrists(elbow, h, l3, psi), axis=-2)[..., 0, :]
    residual = np.maximum(
        np.abs(bar[..., 2]) / l3,
        np.abs(bar[..., 0] ** 2 + bar[..., 1] ** 2 - 4.0 * radius**2) / radius**2,
    )
    return psi, residual


def _distinct(
    psi: np.ndarray, valid: np.ndarray, residual: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """One slot per assembly, best candidate kept, valid slots first, at most 8 slots."""
    rank = np.argsort(np.where(valid, residual, np.inf), axis=-1, kind="stable")
    psi = np.take_along_axis(psi, rank[..., None], axis=-2)
    valid = np.take_along_axis(valid, rank, axis=-1)
    apart = np.abs(wrap_angle(psi[..., :, None, :] - psi[..., None, :, :])).sum(axis=-1)
    earlier = np.tril(np.ones((psi.shape[-2],) * 2, dtype=bool), k=-1)
    valid = valid & ~np.any((apart < _SAME_ASSEMBLY) & earlier & valid[..., None, :], axis=-1)
    keep = np.argsort(~valid, axis=-1, kind="stable")[..., :_MAX_ASSEMBLIES]
    return np.take_along_axis(psi, keep[..., None], axis=-2), np.take_along_axis(valid, keep, -1)


def forward_kinematics(
    params: McGillParameters, actuated: Any, *, rtol: float = 1e-8
) -> ForwardSolutions:
    """All assemblies of the moving plate for given actuated angles (paper 001 gives none).

    The actuated angles fix ``O_J2`` and the leg planes; ``O_J3`` lies on the circle of radius
    ``l3`` about ``O_J2`` in the plane of leg ``J``, at angle ``ψ_J = θ_J23``. The plate needs
    equal heights, ``l3 sin ψ_II = l3 sin ψ_I + z_I2 - z_II2``, and ``|O_I3 - O_II3| = 2R``
    horizontally: ``G = M(ψ_I) - cos ψ_II N(ψ_I) = 0``. Eliminating ``cos ψ_II`` gives
    ``F(ψ_I) = M² - (1 - sin² ψ_II) N² = 0``, a trigonometric polynomial of degree 4. Its Fourier
    coefficients come from 16 samples; the substitution ``ψ_I = ψ_0 + 2 arctan t`` with ``ψ_0 + π``
    at the largest sample turns it into a degree-8 polynomial in ``t`` with a well-scaled leading
    coefficient (``F(ψ_0 + π)``), solved by companion-matrix eigenvalues (batched). Real roots
    with both signs of ``cos ψ_II`` are polished by Newton's method on the unsquared equations and
    kept if the relative residual is at most ``rtol``; hence at most 8 assemblies (Bézout).

    Parameters
    ----------
    params : McGillParameters
    actuated : (..., 4) array_like
        ``(θ_I1, θ_I2, θ_II1, θ_II2)`` in radians.
    rtol : float, default 1e-8
        Largest accepted residual, relative: ``|Δz| / l3`` and ``| |O_I3 O_II3|² - 4R² | / R²``.

    Returns
    -------
    ForwardSolutions
        ``poses (..., 8, 4)``, ``passive (..., 8, 4) = (θ_I3, θ_I4, θ_II3, θ_II4)`` and the working
        mode of each assembly; unused slots are invalid.

    Raises
    ------
    DegenerateGeometryError
        ``F`` vanishes identically (all 16 samples at most ``1e-12`` times the scale of ``F``): the
        actuated angles admit a continuum of assemblies (e.g. parallel leg planes, elbows at equal
        height, offset by ``2R`` normal to the planes).

    Notes
    -----
    Two further thresholds are numerical-method internals: a root ``t`` counts as real when
    ``|Im t| <= 1e-6 (1 + |t|)`` (Newton then polishes it), and two polished candidates closer than
    ``1e-6`` rad (sum over both distal angles) are one assembly, so two genuinely distinct
    assemblies that close are reported once (they are then next to a parallel singularity).

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> config = inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0])
    >>> solutions = forward_kinematics(p, config.actuated)
    >>> distance = np.abs(solutions.poses[solutions.valid] - config.pose).max(axis=-1)
    >>> bool(distance.min() < 1e-9)
    True
    """
    actuated = as_array(actuated, "actuated", (4,))
    theta1, theta2 = actuated[..., 0::2], actuated[..., 1::2]
    h = _e(theta1)
    _, elbow, _, _ = _chain(params, theta1, theta2, theta2)
    l3, radius = params.l3, params.radius
    psi_one, real = _eliminant_roots(elbow, h, l3, radius)
    # Both signs of cos ψ_II for every root ψ_I, then Newton's method.
    psi_one, real = np.repeat(psi_one, 2, axis=-1), np.repeat(real, 2, axis=-1)
    shift = (elbow[..., 0, 2:3] - elbow[..., 1, 2:3]) / l3
    sin_two = np.clip(np.sin(psi_one) + shift, -1.0, 1.0)
    psi_two = np.arctan2(sin_two, np.tile([1.0, -1.0], 8) * np.sqrt(1.0 - sin_two**2))
    psi, residual = _polish(elbow, h, l3, radius, np.stack([psi_one, psi_two], axis=-1))
    psi, valid = _distinct(psi, real & (residual <= rtol), residual)
    wrist = _wrists(elbow, h, l3, psi)
    direction = (wrist[..., 1, :] - wrist[..., 0, :]) / (2.0 * radius)
    phi = np.arctan2(-direction[..., 0], direction[..., 1])
    middle = 0.5 * (wrist[..., 0, :] + wrist[..., 1, :])
    poses = np.stack(
        [middle[..., 0], middle[..., 1], middle[..., 2] + params.b4 + params.b5, phi], axis=-1
    )
    t1, t2 = theta1[..., None, :], theta2[..., None, :]
    passive = wrap_angle(np.stack([psi - t2, phi[..., None] - t1], axis=-1))
    kappa = _SIGN * params.l1 + params.l2 * np.cos(t2) + l3 * np.cos(psi)
    modes = np.stack([np.sign(kappa), np.sign(np.sin(passive[..., 0]))], axis=-1)
    return ForwardSolutions(
        poses=poses,
        passive=passive.reshape(*passive.shape[:-2], 4),
        working_modes=modes.reshape(*modes.shape[:-2], 4).astype(int),
        valid=valid,
    )


# --------------------------------------------------------------------------------------------------
# The family protocol: joints and twist basis (screwkit.robots.families)
# --------------------------------------------------------------------------------------------------


def joints(config: McGillConfiguration) -> JointTable:
    """The 20 physical joints of the McGill SMG over the batch of ``config`` (design.md §1a, §5).

    Each leg is the R-Π-Π-R chain of paper 001 (Sec. 3) with each Π joint modelled by its four
    revolute joints; nothing is reduced, so each leg keeps two closed loops, which
    :func:`screwkit.graphs.twistgraph.equivalent_twist_graph` reduces to virtual translations. Per leg
    ``J``: ``J.pan`` (``base`` → ``J.carrier``, axis ``k`` through ``O_J0``, actuated), the
    proximal parallelogram ``J.proximal.a`` (``J.carrier`` → ``J.proximal_a`` at ``O_J1``,
    actuated tilt), ``J.proximal.b`` (``J.carrier`` → ``J.proximal_b`` at ``O_J1 + w k``),
    ``J.proximal.c`` (``J.proximal_a`` → ``J.elbow`` at ``O_J2``), ``J.proximal.d``
    (``J.proximal_b`` → ``J.elbow`` at ``O_J2 + w k``), all along ``f_J``; the distal parallelogram
    ``J.distal.a``-``d`` likewise from ``J.elbow`` to ``J.wrist`` (corners ``O_J2``,
    ``O_J2 + w k``, ``O_J3``, ``O_J3 + w k``); and ``J.wrist`` (``J.wrist`` → ``platform``, axis
    ``k`` through ``O_J4``). Links: ``base``, per leg ``J.carrier``, ``J.proximal_a``,
    ``J.proximal_b``, ``J.elbow``, ``J.distal_a``, ``J.distal_b``, ``J.wrist``, and ``platform``
    (16); five independent loops; ``dof = 4``.

    Unlike the Π joint of Eqs. (6)-(19), which always translates, a physical parallelogram whose
    long links lie along its short sides (here: vertical long links, see the module docstring) is
    *flat*: its four axes are coplanar and the twist graph lets its coupler turn too. Alone, in
    one leg, that changes no label (the other leg still supplies both horizontal couples); with
    both distal links vertical and parallel leg planes (Fig. 8a) the twist graph reports a
    constraint singularity (the plate gains a rotation about ``f_J``) where ``A`` is
    rank-deficient; with short sides tilted from the vertical it reports an actuation singularity
    (``tests/test_two_limb_catalog.py``).

    Parameters
    ----------
    config : McGillConfiguration

    Returns
    -------
    JointTable
        Screws ``(..., 20, 6)`` over the batch of ``config``; ``table.graph(index)`` is the twist
        graph of one pose.

    Examples
    --------
    >>> from screwkit.graphs.twistgraph import platform_twist_system
    >>> p = McGillParameters(1000, 450, 600, 282.843, 200, -50, -50, 80, 60)
    >>> table = joints(inverse_kinematics(p, [[0.0, 0.0, -800.0, 0.0], [10.0, 0.0, -800.0, 0.1]]))
    >>> table.batch_shape, [s.name for s in table.specs if s.actuated]
    ((2,), ['I.pan', 'I.proximal.a', 'II.pan', 'II.proximal.a'])
    >>> G = table.graph(0)
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"]
    (16, 20, 4)
    >>> platform_twist_system(G).order, platform_twist_system(G, method="reduction").order
    (4, 4)
    """
    rows = []
    for index, leg in enumerate(LEGS):
        k = config.pan_axis[..., index, :]
        f = config.tilt_axis[..., index, :]
        rows.append(joint_row("base", f"{leg}.carrier", f"{leg}.pan", "R",
                              config.pan_point[..., index, :], k, actuated=True))
        for part, start, end, width, first, last in (
            ("proximal", config.shoulder, config.elbow, config.params.proximal_width,
             f"{leg}.carrier", f"{leg}.elbow"),
            ("distal", config.elbow, config.wrist, config.params.distal_width,
             f"{leg}.elbow", f"{leg}.wrist"),
        ):
            lower, upper = start[..., index, :], end[..., index, :]
            corners = (
                ("a", first, f"{leg}.{part}_a", lower),
                ("b", first, f"{leg}.{part}_b", lower + width * k),
                ("c", f"{leg}.{part}_a", last, upper),
                ("d", f"{leg}.{part}_b", last, upper + width * k),
            )
            for tag, parent, child, point in corners:
                rows.append(joint_row(parent, child, f"{leg}.{part}.{tag}", "R", point, f,
                                      actuated=(part, tag) == ("proximal", "a")))
        rows.append(joint_row(f"{leg}.wrist", "platform", f"{leg}.wrist", "R",
                              config.wrist_joint[..., index, :], k))
    return JointTable.from_rows("base", "platform", rows, dof=4, mobility=4)


def twist_basis(config: McGillConfiguration) -> np.ndarray:
    """The moving plate's nominal twists over the batch: a Schoenflies basis (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1``, ``ż = 1`` and ``φ̇ = 1`` with the pose ``(x, y, z, φ)``: the three
    translations and the rotation about the vertical axis ``k`` (the wrist axes' direction) through
    the operation point ``P`` (:func:`screwkit.core.jacobians.schoenflies_basis`). They are the columns
    of ``A`` in :func:`screwkit.core.jacobians.jacobians_from_wrenches`; paper 001's twist is
    ``t = (φ̇, ṗ/L)`` (Eq. 17b), the same motion in other coordinates.

    Parameters
    ----------
    config : McGillConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Examples
    --------
    >>> p = McGillParameters(1000, 450, 600, 282.843, 200, -50, -50, 80, 60)
    >>> twist_basis(inverse_kinematics(p, [10.0, 0.0, -800.0, 0.0]))[3]  # about k through P
    array([  0.,   0.,   1.,   0., -10.,   0.])
    """
    return schoenflies_basis(config.platform_point, config.pan_axis[..., 0, :])


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[McGillParameters, McGillConfiguration] = Family(
    name="mcgill_smg",
    parameters=McGillParameters.from_mapping,
    inverse_kinematics=inverse_kinematics,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "z", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(
        ("l0", "l1", "l2", "l3", "radius", "b4", "b5", "proximal_width", "distal_width"), "length"
    ),
)
