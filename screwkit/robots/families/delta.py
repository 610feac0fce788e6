"""Clavel's Delta robot: three legs, each an actuated revolute joint, an arm and a parallelogram of
two rods with spherical joints (``R–(4S)``), to a platform that translates (3T).

Sources: R. Clavel, "Device for the movement and positioning of an element in space", US Patent
4,976,582 (1990), the mechanism; R. L. Williams II, "The Delta Parallel Robot: Kinematics Solutions"
(Ohio University, 2015), the closed-form inverse kinematics solved below in our notation (a leg's
elbow on the circle of its arm meets the sphere of radius ``l`` about its platform point). The
catalog's robot (``mechanisms/delta.toml``) takes its dimensions from Williams' example robot.

The model
---------
Leg ``i = 1, 2, 3`` lies at the angle ``γ_i = 2π(i - 1)/3`` about ``k``: ``r_i = (cos γ_i, sin γ_i,
0)``, the actuated axis ``u_i = k × r_i`` through ``A_i = R r_i``; the arm ``v_i = cos θ_i r_i -
sin θ_i k`` (the rotation of ``r_i`` by ``θ_i`` about ``u_i``), the elbow ``B_i = A_i + b v_i``; the
platform point ``C_i = p + r r_i``; the rods ``|C_i - B_i| = l``. With ``d_i = C_i - A_i``,
``P_i = d_i·r_i``, ``Q_i = -d_i·k``, ``K_i = (|d_i|² + b² - l²)/(2b)``, the closure
``d_i·v_i = K_i`` reads ``ρ_i cos(θ_i - ψ_i) = K_i`` (``ρ_i = hypot(P_i, Q_i)``,
``ψ_i = atan2(Q_i, P_i)``), so ``θ_i = ψ_i - σ_i δ_i`` with ``δ_i = cos⁻¹(K_i/ρ_i)``. With
``w_i = (C_i - B_i)/l``, ``h_i = b w_i·(u_i × v_i) = (b ρ_i / l) sin(σ_i δ_i)``: the working mode
``σ_i`` is the sign of ``h_i``, as in the four-limb family (paper 004, Eq. 8), and ``σ_i = +1`` has the
elbows out (``B_i`` farther from the axis ``k`` than ``A_i``; ``tests/test_testing.py``). The
parallelogram's short sides are parallel to ``u_i``, of width ``parallelogram_width``.

Examples
--------
>>> delta = FAMILY.parameters({"base_radius": 163.68, "platform_radius": 43.88, "arm_length": 524.0,
...     "rod_length": 1244.0, "parallelogram_width": 131.0})
>>> config = FAMILY.inverse_kinematics(delta, [0.0, 0.0, -1000.0])
>>> np.round(np.degrees(config.theta), 2).tolist()
[-7.35, -7.35, -7.35]
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ...algebra.backend import as_array
from ...exceptions import CatalogError, ScrewkitTypeError, UnreachablePoseError
from ...graphs.jointtable import JointTable
from . import Family, WorkingModes
from .four_limb.joints import parallelogram_legs

__all__ = [
    "DEFAULT_MODE",
    "FAMILY",
    "DeltaConfiguration",
    "DeltaParameters",
    "inverse_kinematics",
    "joints",
    "reachable",
    "twist_basis",
]

_GAMMA = 2 * np.pi * np.arange(3) / 3
#: The legs' radial directions r_i (legs at 0°, 120°, 240° about z), rows (3, 3).
RADIAL_DIRECTIONS = np.stack([np.cos(_GAMMA), np.sin(_GAMMA), np.zeros(3)], axis=-1)
#: The actuated axes u_i = k × r_i, rows (3, 3).
ACTUATED_AXES = np.stack([-np.sin(_GAMMA), np.cos(_GAMMA), np.zeros(3)], axis=-1)
_K = np.array([0.0, 0.0, 1.0])
#: The elbows-out mode (module docstring).
DEFAULT_MODE = (1, 1, 1)


@dataclass(frozen=True)
class DeltaParameters:
    """A Delta robot's dimensions (one length unit).

    Attributes
    ----------
    base_radius, platform_radius : float
        ``R`` (centre to the actuated axes) and ``r`` (platform centre to a leg's platform point).
    arm_length, rod_length : float
        ``b`` and ``l``.
    parallelogram_width : float
        The rods' spacing along ``u_i`` (no part in the kinematics).

    Examples
    --------
    >>> DeltaParameters.from_mapping({"base_radius": 1, "platform_radius": 0.2, "arm_length": 1,
    ...     "rod_length": 2, "parallelogram_width": 0.1}).rod_length
    2.0
    """

    base_radius: float
    platform_radius: float
    arm_length: float
    rod_length: float
    parallelogram_width: float

    @classmethod
    def from_mapping(cls, mapping: Any, *, source: str = "<mapping>") -> DeltaParameters:
        """The parameters from a catalog mapping, each a positive number (``platform_radius`` >= 0).

        Parameters
        ----------
        mapping : mapping
            The catalog's ``[parameters]`` values.
        source : str, optional
            Named in errors.

        Returns
        -------
        DeltaParameters

        Raises
        ------
        CatalogError
            Naming the field, what was expected and what was got.

        Examples
        --------
        >>> DeltaParameters.from_mapping({"base_radius": -1})
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: <mapping>: field `base_radius`: expected a positive number, got -1.
        """
        values = {}
        for name in ("base_radius", "platform_radius", "arm_length", "rod_length", "parallelogram_width"):
            if name not in mapping:
                raise CatalogError(f"{source}: field `{name}`: missing.")
            value = mapping[name]
            low_ok = value >= 0 if name == "platform_radius" else value > 0
            if (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not np.isfinite(value)
                or not low_ok
            ):
                raise CatalogError(f"{source}: field `{name}`: expected a positive number, got {value!r}.")
            values[name] = float(value)
        return cls(**values)


@dataclass(frozen=True)
class DeltaConfiguration:
    """A Delta robot over a batch of poses (module docstring's notation).

    Attributes
    ----------
    params : DeltaParameters
    pose : numpy.ndarray, shape (..., 3)
    theta, h : numpy.ndarray, shape (..., 3)
    a, u, b, c : numpy.ndarray, shape (..., 3, 3)
        ``A_i``, ``u_i``, ``B_i``, ``C_i``.

    Examples
    --------
    >>> config = inverse_kinematics(DeltaParameters(163.68, 43.88, 524, 1244, 131), [[0, 0, -1000]])
    >>> config.b.shape
    (1, 3, 3)
    """

    params: DeltaParameters
    pose: np.ndarray
    theta: np.ndarray
    h: np.ndarray
    a: np.ndarray
    u: np.ndarray
    b: np.ndarray
    c: np.ndarray


def _closure(params: DeltaParameters, pose: np.ndarray) -> tuple[np.ndarray, ...]:
    """``ρ_i``, ``ψ_i``, ``K_i`` and ``C_i`` of the module docstring."""
    c = pose[..., None, :] + params.platform_radius * RADIAL_DIRECTIONS
    d = c - params.base_radius * RADIAL_DIRECTIONS
    p_term, q_term = np.sum(d * RADIAL_DIRECTIONS, axis=-1), -d[..., 2]
    k_term = (np.sum(d * d, axis=-1) + params.arm_length**2 - params.rod_length**2) / (2 * params.arm_length)
    return np.hypot(p_term, q_term), np.arctan2(q_term, p_term), k_term, c


def reachable(params: DeltaParameters, poses: Any) -> np.ndarray:
    """Which poses ``(..., 3)`` every leg reaches (``|K_i| <= ρ_i``), ``(...,)`` bool.

    Parameters
    ----------
    params : DeltaParameters
    poses : array_like, shape (..., 3)

    Returns
    -------
    numpy.ndarray of bool

    Examples
    --------
    >>> reachable(DeltaParameters(163.68, 43.88, 524, 1244, 131), [[0, 0, -1000], [0, 0, -3000]]).tolist()
    [True, False]
    """
    rho, _, k_term, _ = _closure(params, as_array(poses, "poses", (3,)))
    return np.all(np.abs(k_term) <= rho, axis=-1)


def inverse_kinematics(params: DeltaParameters, poses: Any, mode: Any = DEFAULT_MODE) -> DeltaConfiguration:
    """The arm angles ``θ_i = ψ_i - σ_i δ_i`` (module docstring) over a batch of poses ``(x, y, z)``.

    Parameters
    ----------
    params : DeltaParameters
    poses : array_like, shape (..., 3)
    mode : tuple of 3 int, optional
        ``σ_i`` (+1 elbows out, the default).

    Returns
    -------
    DeltaConfiguration

    Raises
    ------
    UnreachablePoseError
        Naming the leg and the first poses it cannot reach.
    ScrewkitTypeError
        If ``mode`` is not three signs.

    Examples
    --------
    >>> inverse_kinematics(DeltaParameters(163.68, 43.88, 524, 1244, 131), [0, 0, -3000])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.UnreachablePoseError: Expected every leg to reach the poses: leg 1 cannot reach ...
    """
    signs = tuple(mode) if isinstance(mode, tuple | list) else ()
    if len(signs) != 3 or not all(s in (-1, 1) for s in signs):
        raise ScrewkitTypeError(f"Expected `mode` to be 3 signs (+1 or -1, σ_i), got {mode!r}.")
    pose = as_array(poses, "poses", (3,))
    rho, psi, k_term, c = _closure(params, pose)
    bad = np.abs(k_term) > rho
    if np.any(bad):
        leg = int(np.argmax(np.any(bad.reshape(-1, 3), axis=0)))
        where = np.argwhere(bad[..., leg])[:3].tolist()
        raise UnreachablePoseError(
            f"Expected every leg to reach the poses: leg {leg + 1} cannot reach the poses at batch indices "
            f"{where} (its rods of length {params.rod_length:g} cannot meet the elbow's circle)."
        )
    delta = np.arccos(np.clip(k_term / rho, -1.0, 1.0))
    theta = psi - np.array(signs, dtype=float) * delta
    v = np.cos(theta)[..., None] * RADIAL_DIRECTIONS - np.sin(theta)[..., None] * _K
    a = np.broadcast_to(params.base_radius * RADIAL_DIRECTIONS, c.shape)
    b = a + params.arm_length * v
    w = (c - b) / params.rod_length
    # u_i × v_i
    elbow_velocity = -np.cos(theta)[..., None] * _K - np.sin(theta)[..., None] * RADIAL_DIRECTIONS
    h = params.arm_length * np.sum(w * elbow_velocity, axis=-1)
    return DeltaConfiguration(params, pose, theta, h, a, np.broadcast_to(ACTUATED_AXES, c.shape), b, c)


def joints(config: DeltaConfiguration) -> JointTable:
    """The joint table: three ``R–(4S)`` legs to the ``platform``, dof 3
    (:func:`~screwkit.robots.families.four_limb.joints.parallelogram_legs`).

    Parameters
    ----------
    config : DeltaConfiguration

    Returns
    -------
    JointTable

    Examples
    --------
    >>> table = joints(inverse_kinematics(DeltaParameters(163.68, 43.88, 524, 1244, 131), [0, 0, -1000]))
    >>> len(table.specs), table.dof
    (15, 3)
    """
    half = 0.5 * config.params.parallelogram_width * config.u[..., None, :] * np.array([-1.0, 1.0])[:, None]
    screws, specs = parallelogram_legs(
        config.pose.shape[:-1],
        config.a,
        config.u,
        config.b[..., None, :] + half,
        config.c[..., None, :] + half,
        ["platform"] * 3,
        [],
    )
    return JointTable("base", "platform", tuple(specs), screws, dof=3, mobility=3)


def twist_basis(config: DeltaConfiguration) -> np.ndarray:
    """The platform's nominal twists: the translations along ``x``, ``y``, ``z``, ``(..., 3, 6)``.

    Parameters
    ----------
    config : DeltaConfiguration

    Returns
    -------
    numpy.ndarray, shape (..., 3, 6)

    Examples
    --------
    >>> twist_basis(inverse_kinematics(DeltaParameters(163.68, 43.88, 524, 1244, 131), [0, 0, -1000]))[2]
    array([0., 0., 0., 0., 0., 1.])
    """
    return np.broadcast_to(np.eye(6)[3:], (*config.pose.shape[:-1], 3, 6))


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[DeltaParameters, DeltaConfiguration] = Family(
    "delta",
    DeltaParameters.from_mapping,
    inverse_kinematics,
    joints,
    twist_basis,
    pose_names=("x", "y", "z"),
    angle_names=(),
    parameter_kinds=dict.fromkeys(
        ("base_radius", "platform_radius", "arm_length", "rod_length", "parallelogram_width"), "length"
    ),
    reachable=reachable,
    application_points=lambda config: config.b,
    actuated_values=lambda config: config.theta,
    working_modes=WorkingModes(
        "mode",
        DEFAULT_MODE,
        "σ_i, the sign of h_i = b w_i·(u_i × v_i) per leg; +1 has the elbows out",
        of=lambda config: np.sign(config.h).astype(int),
    ),
    map_axes=("x", "y"),
)
