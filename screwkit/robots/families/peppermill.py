"""The Peppermill: a CRRHHRRC two-limb Schönflies-motion generator.

Source: paper 000 (Harada & Angeles, "Kinematics and singularity analysis of a CRRHHRRC parallel
Schönflies motion generator", CSME Trans. 38(2), 2014) (docs/papers.md). Equation and figure numbers refer
to it.

The model
---------
Base frame: origin ``O`` midway between ``O_1`` and ``O_2`` on the common normal (the z axis) of the
two drive axes. Limb ``i = 1, 2``:

* a C joint along ``a_i`` through ``O_i = o_i`` (``a_1 = i``, ``a_2 = j``, Eq. 3; ``o_1 = -b0 k``,
  ``o_2 = b0 k``, Eq. 9), both freedoms actuated: slide ``d_i`` and turn ``θ_i``;
* the proximal link ``A_i B_i = r_i u_i``, ``u_i = cos θ_i x_i + sin θ_i y_i`` (Eqs. 4-5), with
  ``x_1 = j``, ``y_1 = k``, ``x_2 = k``, ``y_2 = i`` (read off Eqs. 29-30; ``x_i × y_i = a_i``);
* a passive R joint at ``B_i`` (angle ``λ_i``, axis ``∥ a_i``) and the distal link ``B_i P_i =
  l_i v_i``, ``v_i = cos(θ_i + λ_i) x_i + sin(θ_i + λ_i) y_i`` (Eqs. 6-7);
* a passive R joint at ``P_i`` (axis ``∥ a_i``) into the nut of an H joint on the plate's axis
  ``k`` through ``C``: ``P_i = C + (p_i/2π) φ k`` (Eq. 11), ``p_i`` the H pair's lead.

Loop closure (Eq. 14): ``d_i a_i + r_i u_i + l_i v_i = -o_i + c + (p_i/2π) φ k``. The plate angle
``φ`` is not periodic: ``φ + 2π`` moves the nuts along the axis.

The nut of limb ``i`` only turns about ``a_i`` relative to the base, and its H axis must stay along
``k``, so the R joint at ``P_i`` turns by ``-(θ_i + λ_i)``. The plate turns by ``φ`` relative to the
nut and, by Eq. (11), moves by ``-(p_i/2π) φ`` along ``k`` relative to it: in the screw convention
``(s; r × s + h s)`` of docs/architecture.md §3 the H joint ``nut → platform`` has pitch ``h_i = -p_i/(2π)``.

Dimensions are not given by paper 000; ``r_i``, ``l_i``, ``b0``, ``p_i`` are parameters (the paper
chose ``p_2 = -p_1``, Sec. 4.3).

Modes. Eq. (25) has two roots per limb; a *working mode* is ``(sgn sin λ_1, sgn sin λ_2)``, the
signs of the diagonal entries ``v_i · u_θi = sin λ_i`` of ``B`` (first-kind singularities separate
them). The forward problem has four *assembly modes* ``(sgn v_1z, sgn v_2z)``, the signs of the
factors of ``det A`` (second-kind singularities separate them), in the order of
:data:`ASSEMBLY_MODES`.

Where paper 000 is garbled or wrong (each item is demonstrated in the tests)
----------------------------------------------------------------------------
1. Eq. (3): the third expression ``O_1A_1 = d_2 j`` should read ``O_2A_2 = d_2 j``.
2. Eq. (13) prints ``-b0 k`` for both limbs; it is ``-o_i``: ``+b0 k`` for limb 1 (as Eqs. 17,
   29, 34a and 35 use) and ``-b0 k`` for limb 2.
3. Eqs. (32)-(33) give one assembly mode: the principal ``arcsin`` and ``arccos`` force
   ``v_2z = cos(θ_2 + λ_2) >= 0`` and ``v_1z = sin(θ_1 + λ_1) >= 0``. :func:`forward_kinematics`
   returns all four (``π - arcsin``, ``-arccos``).
4. Fig. 1's caption reads "CRRHRRRC".

Paper 000's Jacobians ``A``, ``B`` (Eqs. 44-48), the factors of ``det A`` and ``det B`` and what
the paper gets wrong about them (Eqs. 45 and 46, the swapped ``u_i``/``v_i`` of Sec. 4.2, the
missing third-kind condition of Sec. 4.4) are a paper analysis, not the robot model: they live in
``tests/paper_000.py`` beside the tests that check them. The mechanism's own Jacobians and labels
come from the analysis core (:meth:`screwkit.robots.mechanism.Mechanism.at`).

Examples
--------
>>> from screwkit.robots.families.peppermill import PeppermillParameters, inverse_kinematics, joints
>>> from screwkit.core.singularity import classify_table
>>> mill = PeppermillParameters(r1=250.0, r2=250.0, l1=400.0, l2=400.0, b0=50.0, p1=40.0, p2=-40.0)
>>> config = inverse_kinematics(mill, [[30.0, -20.0, -450.0, 0.5]])
>>> config.actuated[0, :2]  # Eq. (19): d_1 = x, d_2 = y
array([ 30., -20.])
>>> classify_table(joints(config)).verdict.tolist()
['regular']
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from ...algebra.backend import as_array
from ...core.jacobians import schoenflies_basis
from ...exceptions import DegenerateGeometryError, ScrewkitValueError, UnreachablePoseError
from ...graphs.jointtable import JointTable
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
from . import Family, WorkingModes

__all__ = [
    "ASSEMBLY_MODES",
    "DEFAULT_MODE",
    "FAMILY",
    "WORKING_MODES",
    "PeppermillConfiguration",
    "PeppermillParameters",
    "forward_kinematics",
    "inverse_kinematics",
    "joints",
    "twist_basis",
]

#: ``(sgn sin λ_1, sgn sin λ_2)`` of the four inverse-kinematics branches.
WORKING_MODES = ((1, 1), (1, -1), (-1, 1), (-1, -1))
#: ``(sgn v_1z, sgn v_2z)`` of the four forward-kinematics slots, in this order.
ASSEMBLY_MODES = ((1, 1), (1, -1), (-1, 1), (-1, -1))
DEFAULT_MODE = (1, 1)

_A = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])  # a_1 = i, a_2 = j (Eq. 3)
_X = np.array([[0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])  # x_1 = j, x_2 = k (Eqs. 29-30)
_Y = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0]])  # y_1 = k, y_2 = i
_K = np.array([0.0, 0.0, 1.0])
_REACH_SLACK = 1e-12  # relative slack on |cos| <= 1 for poses built on a workspace boundary


@dataclass(frozen=True, slots=True)
class PeppermillParameters:
    """Dimensions of a Peppermill (Sec. 2 of paper 000; lengths in one unit of your choice).

    Paper 000 gives no values; ``p2 = -p1`` is its stated choice (Sec. 4.3).

    Parameters
    ----------
    r1, r2 : float
        Proximal link lengths ``r_i`` (Eq. 4), > 0.
    l1, l2 : float
        Distal link lengths ``l_i`` (Eq. 6), > 0.
    b0 : float
        Distance from ``O`` to each drive axis along z (Eq. 9), >= 0.
    p1, p2 : float
        Leads (length per turn) of the two H pairs (Eq. 11), signed; ``p1 = p2`` is an
        architecture singularity (Sec. 4.3).

    Examples
    --------
    >>> p = PeppermillParameters.from_mapping(
    ...     {"r1": 250, "r2": 250, "l1": 400, "l2": 400, "b0": 50, "p1": 40, "p2": -40})
    >>> p.p2
    -40.0
    >>> PeppermillParameters(250, 250, 0, 400, 50, 40, -40)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected parameter `l1` of ... > 0, got 0.
    """

    r1: float
    r2: float
    l1: float
    l2: float
    b0: float
    p1: float
    p2: float

    def __post_init__(self) -> None:
        check_parameters(
            self, positive=("r1", "r2", "l1", "l2"), nonnegative=("b0",), real=("p1", "p2")
        )

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> PeppermillParameters:
        """Build parameters from a mapping (e.g. a TOML table), naming ``source`` in every error.

        Parameters
        ----------
        mapping : mapping
            The ``[parameters]`` values (and the metadata ``name``, ``length_unit``).
        source : str, optional
            Where the mapping comes from, named in every error.

        Returns
        -------
        PeppermillParameters
            The validated parameters.

        Raises
        ------
        CatalogError
            Unknown, missing or non-numeric fields.
        ScrewkitValueError
            Values out of range.

        Examples
        --------
        >>> PeppermillParameters.from_mapping({"r1": 1.0}, source="peppermill.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: peppermill.toml: missing field(s) ['r2', 'l1', ...
        """
        return parameters_from_mapping(cls, mapping, source)

    def scaled(self, factor: float) -> PeppermillParameters:
        """The same robot in another unit of length (every length and lead times ``factor`` > 0).

        Parameters
        ----------
        factor : float
            The ratio of the new unit of length to the old (> 0).

        Returns
        -------
        PeppermillParameters
            The scaled parameters.

        Examples
        --------
        >>> PeppermillParameters(250, 250, 400, 400, 50, 40, -40).scaled(1e-3).p1
        0.04
        """
        if not (isinstance(factor, int | float) and factor > 0):
            raise ScrewkitValueError(f"Expected `factor` to be a number > 0, got {factor!r}.")
        return PeppermillParameters(*(getattr(self, f.name) * factor for f in fields(self)))

    @property
    def lengths(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """``(r_i, l_i, p_i/2π)`` per limb, each of shape (2,)."""
        return (
            np.array([self.r1, self.r2]),
            np.array([self.l1, self.l2]),
            np.array([self.p1, self.p2]) / (2.0 * np.pi),
        )


def _drive_points(params: PeppermillParameters) -> np.ndarray:
    """``o_i`` (Eq. 9), shape (2, 3)."""
    return np.outer([-params.b0, params.b0], _K)


# --------------------------------------------------------------------------------------------------
# Configuration
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class PeppermillConfiguration:
    """Every joint of a Peppermill at one pose or a batch of poses (read-only arrays).

    Limb axes (length 2) are limbs 1 and 2.

    Attributes
    ----------
    params : PeppermillParameters
    mode : tuple of 2 int
        The working mode ``(sgn sin λ_1, sgn sin λ_2)``.
    pose : (..., 4) ndarray
        ``(x, y, z, φ)``; ``φ`` is not wrapped.
    actuated : (..., 4) ndarray
        ``(d_1, d_2, θ_1, θ_2)``, angles in ``[-π, π)``.
    passive : (..., 2) ndarray
        ``(λ_1, λ_2)`` in ``[-π, π)``.
    drive_point, drive_axis : (..., 2, 3) ndarray
        ``O_i`` and ``a_i``: the C joints (``a_i`` also directs the other R joints of limb i).
    slider_point, elbow, wrist : (..., 2, 3) ndarray
        ``A_i``, ``B_i``, ``P_i``.
    u, u_theta, v : (..., 2, 3) ndarray
        ``u_i`` (Eq. 5), ``u_θi`` (Eq. 38), ``v_i`` (Eq. 7).
    platform_point, platform_axis : (..., 3) ndarray
        ``C`` and ``k``: the axis of both H joints.

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> config = inverse_kinematics(p, [[30.0, -20.0, -450.0, 0.5], [0.0, 0.0, -450.0, 0.0]])
    >>> config.batch_shape, config.wrist.shape
    ((2,), (2, 2, 3))
    """

    params: PeppermillParameters
    mode: tuple[int, ...]
    pose: np.ndarray
    actuated: np.ndarray
    passive: np.ndarray
    drive_point: np.ndarray
    drive_axis: np.ndarray
    slider_point: np.ndarray
    elbow: np.ndarray
    wrist: np.ndarray
    u: np.ndarray
    u_theta: np.ndarray
    v: np.ndarray
    platform_point: np.ndarray
    platform_axis: np.ndarray

    def __post_init__(self) -> None:
        for name in (
            "pose", "actuated", "passive", "drive_point", "drive_axis", "slider_point", "elbow",
            "wrist", "u", "u_theta", "v", "platform_point", "platform_axis",
        ):
            object.__setattr__(self, name, frozen(getattr(self, name)))

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Shape of the batch of poses."""
        return tuple(self.pose.shape[:-1])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary of the pose, the mode and the joint values.

        Returns
        -------
        dict
            Plain lists and numbers.
        """
        return {
            "mode": list(self.mode),
            "pose": self.pose.tolist(),
            "actuated": self.actuated.tolist(),
            "passive": self.passive.tolist(),
        }

    def __str__(self) -> str:
        return (
            f"PeppermillConfiguration(mode={self.mode}, batch_shape={self.batch_shape}, "
            f"pose={np.round(self.pose, 6).tolist()})"
        )


def _configuration(
    params: PeppermillParameters,
    mode: tuple[int, ...],
    pose: np.ndarray,
    actuated: np.ndarray,
    passive: np.ndarray,
) -> PeppermillConfiguration:
    """Every point and axis from the pose and the joint values (Eqs. 3-11)."""
    radius, length, _ = params.lengths
    d, theta = actuated[..., :2], actuated[..., 2:]
    absolute = theta + passive
    u = np.cos(theta)[..., None] * _X + np.sin(theta)[..., None] * _Y  # Eq. (5)
    u_theta = -np.sin(theta)[..., None] * _X + np.cos(theta)[..., None] * _Y  # Eq. (38)
    v = np.cos(absolute)[..., None] * _X + np.sin(absolute)[..., None] * _Y  # Eq. (7)
    drive_point = np.broadcast_to(_drive_points(params), u.shape)
    slider = drive_point + d[..., None] * _A  # Eq. (3)
    elbow = slider + radius[:, None] * u  # Eq. (4)
    centre = pose[..., :3]
    return PeppermillConfiguration(
        params=params,
        mode=mode,
        pose=pose,
        actuated=actuated,
        passive=passive,
        drive_point=drive_point,
        drive_axis=np.broadcast_to(_A, u.shape),
        slider_point=slider,
        elbow=elbow,
        wrist=elbow + length[:, None] * v,  # Eq. (6)
        u=u,
        u_theta=u_theta,
        v=v,
        platform_point=centre,
        platform_axis=np.broadcast_to(_K, centre.shape),
    )


# --------------------------------------------------------------------------------------------------
# Inverse and forward kinematics
# --------------------------------------------------------------------------------------------------


def inverse_kinematics(
    params: PeppermillParameters, pose: Any, mode: Any = DEFAULT_MODE
) -> PeppermillConfiguration:
    """Actuated and passive joint values for poses ``(x, y, z, φ)``: Eqs. (19)-(27).

    ``d_1 = x``, ``d_2 = y`` (Eq. 19); ``q_i = p_i - d_i a_i`` (Eq. 20); ``θ_i`` solves
    ``e_1 sin θ_i + e_2 cos θ_i + e_3 = 0`` with ``e_1 = q_i·y_i``, ``e_2 = q_i·x_i``,
    ``e_3 = -(q_i·q_i + r_i² - l_i²)/(2 r_i)`` (Eqs. 24, 26). We write its two roots as
    ``θ_i = atan2(e_1, e_2) - mode_i arccos(-e_3/‖q_i‖)``, equivalent to the half-angle formula of
    Eq. (25) without its division by ``e_3 - e_2``; this sign makes ``sgn sin λ_i = mode_i``.
    Then ``v_i = (q_i - r_i u_i)/l_i`` (Eq. 27) and ``λ_i`` is the angle of ``v_i`` minus ``θ_i``.

    Parameters
    ----------
    params : PeppermillParameters
    pose : (..., 4) array_like
        ``(x, y, z, φ)``; ``φ`` in radians, not periodic (it moves the nuts).
    mode : tuple of 2 int, default ``(1, 1)``
        ``(sgn sin λ_1, sgn sin λ_2)``.

    Returns
    -------
    PeppermillConfiguration

    Raises
    ------
    UnreachablePoseError
        ``‖q_i‖`` lies outside ``[|r_i - l_i|, r_i + l_i]`` (the message names the limb); a relative
        slack of 1e-12 admits poses built exactly on that boundary.

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> config = inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5], mode=(1, -1))
    >>> np.sign(np.sin(config.passive))
    array([ 1., -1.])
    >>> inverse_kinematics(p, [30.0, -20.0, -1450.0, 0.5])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Limb 1 cannot reach the pose: ...
    """
    pose = as_array(pose, "pose", (4,))
    signs = np.array(checked_mode(mode, "mode", 2), dtype=float)
    radius, length, leads = params.lengths
    d = pose[..., :2]  # Eq. (19)
    wrist = pose[..., None, :3] + (leads * pose[..., 3:4])[..., None] * _K  # Eqs. (11), (13)
    q = wrist - _drive_points(params) - d[..., None] * _A  # Eq. (20)
    e1 = np.sum(q * _Y, axis=-1)  # Eq. (26)
    e2 = np.sum(q * _X, axis=-1)
    distance = np.linalg.norm(q, axis=-1)
    e3 = -(distance**2 + radius**2 - length**2) / (2.0 * radius)
    low, high = np.abs(radius - length), radius + length
    for index in range(2):
        far = distance[..., index] > high[index] * (1 + _REACH_SLACK)
        near = distance[..., index] < low[index] * (1 - _REACH_SLACK)
        bad = far | near
        if np.any(bad):
            raise UnreachablePoseError(
                f"Limb {index + 1} cannot reach the pose: at {describe_indices(bad)} "
                f"‖q_{index + 1}‖ (Eq. 20) is {distance[..., index][bad][:3].round(6).tolist()}, "
                f"expected within [|r - l|, r + l] = [{low[index]:.6g}, {high[index]:.6g}]."
            )
    safe = np.where(distance > 0, distance, 1.0)
    cosine = at_reach(-e3 / safe, (distance**2 + radius**2 + length**2) / (2.0 * radius * safe))
    theta = np.arctan2(e1, e2) - signs * np.arccos(cosine)  # Eq. (25), see the docstring
    u = np.cos(theta)[..., None] * _X + np.sin(theta)[..., None] * _Y
    v = (q - radius[:, None] * u) / length[:, None]  # Eq. (27)
    lam = np.arctan2(np.sum(v * _Y, axis=-1), np.sum(v * _X, axis=-1)) - theta
    actuated = np.concatenate([d, wrap_angle(theta)], axis=-1)
    return _configuration(
        params, tuple(int(s) for s in signs), pose, actuated, wrap_angle(lam)
    )


def forward_kinematics(params: PeppermillParameters, actuated: Any) -> ForwardSolutions:
    """The four assemblies for given actuated values: Eqs. (28)-(35), all branches.

    ``x = d_1``, ``y = d_2`` (Eq. 28); ``sin(θ_2 + λ_2) = (d_1 - r_2 sin θ_2)/l_2`` (Eq. 31) and
    ``cos(θ_1 + λ_1) = (d_2 - r_1 cos θ_1)/l_1`` (Eq. 33) with ``v_2z = cos(θ_2 + λ_2)`` and
    ``v_1z = sin(θ_1 + λ_1)`` of either sign (Eqs. 32-33 keep only ``+``); then the linear system
    of Eq. (35) gives ``z`` and ``φ``.

    Parameters
    ----------
    params : PeppermillParameters
    actuated : (..., 4) array_like
        ``(d_1, d_2, θ_1, θ_2)``.

    Returns
    -------
    ForwardSolutions
        ``poses (..., 4, 4)`` in the slot order of :data:`ASSEMBLY_MODES`, ``passive (..., 4, 2) =
        (λ_1, λ_2)`` and the working mode ``(sgn sin λ_1, sgn sin λ_2)`` of each; a slot is invalid
        when a distal link cannot close its limb.

    Raises
    ------
    DegenerateGeometryError
        ``p1 = p2``: the matrix of Eq. (35) is singular (architecture singularity, Sec. 4.3).

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> config = inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5])
    >>> solutions = forward_kinematics(p, config.actuated)
    >>> solutions.poses[3].data.round(9)  # both distal links descend to the plate: slot (-1, -1)
    array([  30. ,  -20. , -450. ,    0.5])
    """
    actuated = as_array(actuated, "actuated", (4,))
    if params.p1 == params.p2:
        raise DegenerateGeometryError(
            f"Expected distinct leads p1 and p2 (Eq. 35), got p1 = p2 = {params.p1}: the "
            "coefficient matrix is singular (architecture singularity, Sec. 4.3)."
        )
    radius, length, leads = params.lengths
    d1, d2, theta1, theta2 = np.moveaxis(actuated, -1, 0)
    sin_two = (d1 - radius[1] * np.sin(theta2)) / length[1]  # Eq. (31)
    cos_one = (d2 - radius[0] * np.cos(theta1)) / length[0]  # Eq. (33)
    closes = (np.abs(sin_two) <= 1 + _REACH_SLACK) & (np.abs(cos_one) <= 1 + _REACH_SLACK)
    sin_two, cos_one = np.clip(sin_two, -1, 1), np.clip(cos_one, -1, 1)
    signs = np.array(ASSEMBLY_MODES, dtype=float)  # (4, 2)
    v1z = signs[:, 0] * np.sqrt(1 - cos_one**2)[..., None]  # sin(θ_1 + λ_1)
    v2z = signs[:, 1] * np.sqrt(1 - sin_two**2)[..., None]  # cos(θ_2 + λ_2)
    rhs1 = radius[0] * np.sin(theta1)[..., None] + length[0] * v1z - params.b0  # Eq. (35)
    rhs2 = radius[1] * np.cos(theta2)[..., None] + length[1] * v2z + params.b0
    phi = (rhs2 - rhs1) / (leads[1] - leads[0])
    z = rhs1 - leads[0] * phi
    shape = phi.shape
    poses = np.stack([np.broadcast_to(d1[..., None], shape), np.broadcast_to(d2[..., None], shape),
                      z, phi], axis=-1)
    lam1 = np.arctan2(v1z, cos_one[..., None]) - theta1[..., None]
    lam2 = np.arctan2(sin_two[..., None], v2z) - theta2[..., None]
    passive = wrap_angle(np.stack([lam1, lam2], axis=-1))
    return ForwardSolutions(
        poses=poses,
        passive=passive,
        working_modes=np.sign(np.sin(passive)).astype(int),
        valid=np.broadcast_to(closes[..., None], shape),
    )


# --------------------------------------------------------------------------------------------------
# The family protocol: joints and twist basis (screwkit.robots.families)
# --------------------------------------------------------------------------------------------------


def joints(config: PeppermillConfiguration) -> JointTable:
    """The joints of the single loop C-R-R-H-H-R-R-C over the batch of ``config`` (docs/architecture.md §5).

    Per limb ``i``: ``i.slide`` (P, ``base`` → ``i.slider``, along ``a_i``, actuated ``d_i``) and
    ``i.turn`` (R, ``i.slider`` → ``i.proximal``, axis ``a_i`` through ``O_i``, actuated ``θ_i``),
    together the C joint; ``i.elbow`` (R, ``i.proximal`` → ``i.distal`` at ``B_i``) and ``i.wrist``
    (R, ``i.distal`` → ``i.nut`` at ``P_i``), both along ``a_i``; ``i.screw`` (H, ``i.nut`` →
    ``platform``, axis ``k`` through ``C``, pitch ``-p_i/2π``, both H joints on the plate's axis).
    Links: ``base``, per limb ``i.slider``, ``i.proximal``, ``i.distal``, ``i.nut``, and
    ``platform`` (10); one loop; ``dof = 4``.

    The C joint has two actuated freedoms, which one :class:`screwkit.graphs.joints.Joint` cannot carry
    (only one-freedom joints are actuated). Paper 000's Appendix A drives ``(d_i, θ_i)`` by two
    motors through a constant invertible matrix (Eq. A.5), so actuating the slide and the turn
    is equivalent to actuating the motors: each C joint is an actuated P followed by an actuated
    R on the same axis, through the massless link ``i.slider``.

    Parameters
    ----------
    config : PeppermillConfiguration

    Returns
    -------
    JointTable
        Screws ``(..., 10, 6)`` over the batch of ``config``; ``table.graph(index)`` is the twist
        graph of one pose.

    Examples
    --------
    >>> from screwkit.graphs.loops import fundamental_loops
    >>> from screwkit.graphs.reduction import platform_twist_system
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> table = joints(inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5]))
    >>> [spec.type for spec in table.specs]
    ['P', 'R', 'R', 'R', 'H', 'P', 'R', 'R', 'R', 'H']
    >>> G = table.graph()
    >>> G.number_of_nodes(), G.number_of_edges(), len(fundamental_loops(G)), G.graph["dof"]
    (10, 10, 1, 4)
    >>> platform_twist_system(G).order, platform_twist_system(G, method="reduction").order
    (4, 4)
    """
    _, _, leads = config.params.lengths
    rows = []
    for index, limb in enumerate(("1", "2")):
        axis, origin = config.drive_axis[..., index, :], config.drive_point[..., index, :]
        rows += [
            joint_row("base", f"{limb}.slider", f"{limb}.slide", "P", origin, axis, actuated=True),
            joint_row(f"{limb}.slider", f"{limb}.proximal", f"{limb}.turn", "R", origin, axis,
                      actuated=True),
            joint_row(f"{limb}.proximal", f"{limb}.distal", f"{limb}.elbow", "R",
                      config.elbow[..., index, :], axis),
            joint_row(f"{limb}.distal", f"{limb}.nut", f"{limb}.wrist", "R",
                      config.wrist[..., index, :], axis),
            joint_row(f"{limb}.nut", "platform", f"{limb}.screw", "H", config.platform_point,
                      config.platform_axis, pitch=-float(leads[index])),
        ]
    return JointTable.from_rows("base", "platform", rows, dof=4, mobility=4)


def twist_basis(config: PeppermillConfiguration) -> np.ndarray:
    """The plate's nominal twists over the batch: a Schoenflies basis (user frame).

    Rows, for ``δx``, ``δy``, ``δz`` and ``δφ`` of Eq. (44): the three translations and the
    rotation about the plate's axis ``k`` (the axis of both H joints) through ``C``
    (:func:`screwkit.core.jacobians.schoenflies_basis`). They are the columns of ``A`` in
    :func:`screwkit.core.jacobians.jacobians_from_wrenches`, in the order of the columns of paper 000's
    ``A`` (Eq. 47).

    Parameters
    ----------
    config : PeppermillConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 4, 6)

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> twist_basis(inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5]))[3]  # about k through C
    array([  0.,   0.,   1., -20., -30.,   0.])
    """
    return schoenflies_basis(config.platform_point, config.platform_axis)

#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[PeppermillParameters, PeppermillConfiguration] = Family(
    "peppermill", PeppermillParameters.from_mapping, inverse_kinematics, joints, twist_basis,
    pose_names=("x", "y", "z", "phi"), angle_names=("phi",),
    parameter_kinds=dict.fromkeys(("r1", "r2", "l1", "l2", "b0", "p1", "p2"), "length"),
    actuated_values=lambda config: config.actuated[..., [0, 2, 1, 3]],  # the table's 1.slide, 1.turn, ...
    working_modes=WorkingModes("mode", DEFAULT_MODE, "sgn sin λ_i per limb (λ_i, Eq. 27)",
                               of=lambda config: np.sign(np.sin(config.passive)).astype(int)),
)
