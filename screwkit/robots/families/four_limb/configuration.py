"""The four-limb family's configuration: every point and axis of the mechanism over a batch of poses.

:class:`FourLimbConfiguration` holds the limbs' points and directions (Eqs. 1-8 of paper 004) at the
poses and actuated angles that close them; the private helpers compute the base frames and the
platform points of Table 1 (corrected) that the inverse and forward kinematics
(:mod:`screwkit.robots.families.four_limb.kinematics`) and the joint table
(:mod:`screwkit.robots.families.four_limb.joints`) share.

Examples
--------
>>> config = load_mechanism("h4").configuration()
>>> type(config).__name__, config.batch_shape
('FourLimbConfiguration', ())
"""

from __future__ import annotations

import functools
from dataclasses import asdict, dataclass
from typing import Any, NamedTuple

import numpy as np

from ....exceptions import ScrewkitTypeError
from .parameters import FourLimbParameters

__all__ = [
    "ETA",
    "ODD_LIMB",
    "SGN_COS_ETA",
    "SGN_SIN_ETA",
    "BaseFrames",
    "FourLimbConfiguration",
    "base_frames",
]


#: η_i = (2i - 1)π/4 (Eq. 1), also the platform angles γ_i of the screw-pair platform (Table 3).
ETA = (2.0 * np.arange(1, 5) - 1.0) * np.pi / 4.0
#: sgn(cos η_i) and sgn(sin η_i) of Table 1.
SGN_COS_ETA = np.array([1.0, -1.0, -1.0, 1.0])
SGN_SIN_ETA = np.array([1.0, 1.0, -1.0, -1.0])
#: mod(i, 2) of Table 1 (limbs 1 and 3 carry the screw-pair offset).
ODD_LIMB = np.array([1.0, 0.0, 1.0, 0.0])


_K = np.array([0.0, 0.0, 1.0])


_ARRAY_FIELDS = (
    "pose", "theta", "a", "u", "b", "v", "c", "w", "h", "s", "platform_s",
    "elbow_corners", "platform_corners", "platform_joint_points", "platform_joint_axis",
)


@dataclass(frozen=True, slots=True, eq=False)
class FourLimbConfiguration:
    """Every point and axis of a four-limb SMG at one pose (or a batch of poses).

    All arrays are read-only; ``...`` is the batch shape of the pose. Limb ``i`` of paper 004 is
    index ``i - 1`` on the limb axis.

    Attributes
    ----------
    params : FourLimbParameters
    working_mode : tuple of 4 int
        Requested signs of ``h_i`` (Eq. 8).
    pose : (..., 4) ndarray
        ``χ = (x, y, z, φ)``.
    theta : (..., 4) ndarray
        Actuated angles ``θ_i`` in ``[-π, π)``.
    a, u : (..., 4, 3) ndarray
        Actuated joint points ``A_i`` (Eq. 1) and unit axes ``u_i = R_z(α_i) i``.
    b, v : (..., 4, 3) ndarray
        Elbow points ``B_i`` and unit arm directions ``v_i`` (Eq. 2).
    c, w : (..., 4, 3) ndarray
        Platform points ``C_i`` (Table 1) and unit parallelogram directions ``w_i = (c_i - b_i)/l``.
    h : (..., 4) ndarray
        ``h_i = b w_i·(u_i × v_i)`` (Eq. 8), the diagonal of ``B``.
    s : (..., 4, 3) ndarray
        ``s_i`` with ``∂c_i/∂φ = r s_i`` (Eq. 4; Table 1 corrected, see the module docstring).
    platform_s : (..., 3) ndarray
        The unit vector ``s`` of Tables 1-2: ``R_z(φ) j`` (Quattro, H4), ``-R_y(φ) k`` (V4, see the
        module docstring) or ``k`` (screw pair).
    elbow_corners, platform_corners : (..., 4, 2, 3) ndarray
        Sphere centres ``(m_i, n_i) = b_i ∓ (d/2) u_i`` and ``(p_i, q_i) = c_i ∓ (d/2) u_i``.
    subplatform_limbs : tuple of two pairs of int
        0-based limbs carried by sub-platforms I and II.
    platform_joint_points : (..., 2, 3) ndarray
        A point on the axis of the joint between sub-platform I (resp. II) and the end effector:
        ``P_I``, ``P_II`` for articulated platforms; the sub-platform centres on the screw axis for
        the screw pair.
    platform_joint_axis : (..., 3) ndarray
        Unit direction of both joints (``k``, ``j`` or ``k``).
    platform_joint_pitches : tuple of 2 float
        Pitch of each joint: 0 for a revolute joint, ``-h/(2π)`` for the helical joint of the
        screw-pair platform (sub-platform I).

    Examples
    --------
    >>> from screwkit.robots.families.four_limb.kinematics import inverse_kinematics
    >>> cfg = inverse_kinematics(FourLimbParameters(name="H4", platform_kind="articulated_z",
    ...     arm_length=375, rod_length=800, alpha=0, beta=np.pi / 2, platform_radius=80,
    ...     platform_offset=70, base_radius=275), [[0, 0, -700, 0], [100, 0, -800, 0.5]])
    >>> cfg.batch_shape, cfg.elbow_corners.shape, cfg.platform_joint_points.shape
    ((2,), (2, 4, 2, 3), (2, 2, 3))
    >>> cfg.theta.flags.writeable
    False
    """

    params: FourLimbParameters
    working_mode: tuple[int, int, int, int]
    pose: np.ndarray
    theta: np.ndarray
    a: np.ndarray
    u: np.ndarray
    b: np.ndarray
    v: np.ndarray
    c: np.ndarray
    w: np.ndarray
    h: np.ndarray
    s: np.ndarray
    platform_s: np.ndarray
    elbow_corners: np.ndarray
    platform_corners: np.ndarray
    subplatform_limbs: tuple[tuple[int, int], tuple[int, int]]
    platform_joint_points: np.ndarray
    platform_joint_axis: np.ndarray
    platform_joint_pitches: tuple[float, float]

    def __post_init__(self) -> None:
        for name in _ARRAY_FIELDS:
            array = np.array(getattr(self, name), dtype=float)
            array.flags.writeable = False
            object.__setattr__(self, name, array)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading (batch) shape of the pose."""
        return self.pose.shape[:-1]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (arrays become nested lists).

        Returns
        -------
        dict
            Plain lists and numbers.
        """
        out: dict[str, Any] = {
            "parameters": asdict(self.params),
            "working_mode": list(self.working_mode),
            "subplatform_limbs": [list(pair) for pair in self.subplatform_limbs],
            "platform_joint_pitches": list(self.platform_joint_pitches),
        }
        out |= {name: getattr(self, name).tolist() for name in _ARRAY_FIELDS}
        return out

    def __str__(self) -> str:
        return (
            f"FourLimbConfiguration({self.params.name}, {self.params.platform_kind}, "
            f"batch shape {self.batch_shape}, working mode {self.working_mode})"
        )


class _Platform(NamedTuple):
    c: np.ndarray  # (..., 4, 3)
    dc_dphi: np.ndarray  # (..., 4, 3), = r s_i
    platform_s: np.ndarray  # (..., 3)
    joint_points: np.ndarray  # (..., 2, 3)
    joint_axis: np.ndarray  # (..., 3)


class BaseFrames(NamedTuple):
    """The fixed points and frames of the four limbs (arrays ``(4, 3)``, read-only).

    Attributes
    ----------
    a, u, j_rot, k_rot : numpy.ndarray
        The points ``A_i`` and the vectors ``F_i i`` (the actuated axes), ``F_i j``, ``F_i k``.
    """

    a: np.ndarray  # (4, 3) actuated joint points A_i
    u: np.ndarray  # (4, 3) F_i i, the actuated axes
    j_rot: np.ndarray  # (4, 3) F_i j = R_z(α_i) j (R_y leaves j fixed)
    k_rot: np.ndarray  # (4, 3) F_i k = R_z(α_i) R_y(ε_i) k (k when ε = 0)


def base_frames(params: FourLimbParameters) -> BaseFrames:
    """``a_i`` (Eq. 1 or explicit) and the limb frames ``F_i = R_z(α_i) R_y(ε_i)`` (item 6); read
    only, computed once per parameter set (every chunk of a batch asks).

    Parameters
    ----------
    params : FourLimbParameters
        The robot.

    Returns
    -------
    BaseFrames
        ``a`` (the points ``A_i``), ``u`` (``F_i i``, the actuated axes), ``j_rot`` (``F_i j``) and
        ``k_rot`` (``F_i k``), each ``(4, 3)``.

    Examples
    --------
    >>> frames = base_frames(load_mechanism("h4").parameters)
    >>> frames.u.shape, bool(np.allclose(np.linalg.norm(frames.u, axis=-1), 1.0))
    ((4, 3), True)
    """
    try:
        return _cached_base(params)
    except TypeError:  # unhashable parameters: computed afresh
        return _base_of(params)


@functools.lru_cache(maxsize=64)
def _cached_base(params: FourLimbParameters) -> BaseFrames:
    return _base_of(params)


def _base_of(params: FourLimbParameters) -> BaseFrames:
    if params.base_points is not None:
        a = np.array(params.base_points, dtype=float)
    else:
        assert params.base_radius is not None  # guaranteed by validation
        a = params.base_radius * np.stack([np.cos(ETA), np.sin(ETA), np.zeros(4)], axis=-1)
    alphas, tilts = params.limb_alphas, params.limb_inclinations
    ca, sa, ce, se = np.cos(alphas), np.sin(alphas), np.cos(tilts), np.sin(tilts)
    u = np.stack([ca * ce, sa * ce, -se], axis=-1)
    j_rot = np.stack([-sa, ca, np.zeros(4)], axis=-1)
    k_rot = np.stack([ca * se, sa * se, ce], axis=-1)
    for array in (a, u, j_rot, k_rot):
        array.flags.writeable = False
    return BaseFrames(a, u, j_rot, k_rot)


def _platform(params: FourLimbParameters, pose: np.ndarray) -> _Platform:
    """Points ``c_i`` of Table 1 (corrected) and their derivative with respect to ``φ``."""
    p = pose[..., None, :3]
    phi = pose[..., 3]
    cos, sin, zero = np.cos(phi), np.sin(phi), np.zeros_like(phi)
    r = params.platform_radius
    j_vec = np.array([0.0, 1.0, 0.0])
    if params.platform_kind == "screw_pair":
        assert params.lead is not None
        radial = np.stack([np.cos(ETA), np.sin(ETA), np.zeros(4)], axis=-1)
        rise = params.lead / (2.0 * np.pi)
        c = r * radial + (ODD_LIMB[:, None] * rise * phi[..., None, None]) * _K + p
        dc_dphi = np.broadcast_to(ODD_LIMB[:, None] * rise * _K, c.shape)
        axis = np.broadcast_to(_K, (*pose.shape[:-1], 3))
        centre = pose[..., :3]
        joint_points = np.stack([centre + (rise * phi)[..., None] * _K, centre], axis=-2)
        return _Platform(c, dc_dphi, axis, joint_points, axis)
    assert params.platform_offset is not None
    offsets = (SGN_SIN_ETA * params.platform_offset)[:, None] * j_vec
    if params.platform_kind == "articulated_z":
        bar = np.stack([cos, sin, zero], axis=-1)  # R_z(φ) i
        s = np.stack([-sin, cos, zero], axis=-1)  # ∂(R_z(φ) i)/∂φ = R_z(φ) j
        axis = np.broadcast_to(_K, s.shape)
    else:  # articulated_y, Table 1 corrected (module docstring, item 3)
        bar = np.stack([cos, zero, -sin], axis=-1)  # R_y(φ) i
        s = np.stack([-sin, zero, -cos], axis=-1)  # ∂(R_y(φ) i)/∂φ = -R_y(φ) k
        axis = np.broadcast_to(j_vec, s.shape)
    c = SGN_COS_ETA[:, None] * r * bar[..., None, :] + offsets + p
    dc_dphi = SGN_COS_ETA[:, None] * r * s[..., None, :]
    joint_points = pose[..., None, :3] + np.array([1.0, -1.0])[:, None] * r * bar[..., None, :]
    return _Platform(c, dc_dphi, s, joint_points, axis)


def _require(value: Any, cls: type, name: str) -> None:
    if not isinstance(value, cls):
        raise ScrewkitTypeError(
            f"Expected `{name}` to be a {cls.__name__}, got {type(value).__name__}."
        )


def _assemble(
    params: FourLimbParameters,
    pose: np.ndarray,
    theta: np.ndarray,
    working_mode: tuple[int, int, int, int],
    platform: _Platform,
    base: BaseFrames,
) -> FourLimbConfiguration:
    """Build the configuration from a pose and the actuated angles that close it (``base``:
    :func:`base_frames` of ``params``, computed once by the caller)."""
    a, u, j_rot, k_rot = base
    batch = pose.shape[:-1]
    cos, sin = np.cos(theta)[..., None], np.sin(theta)[..., None]
    v = cos * j_rot + sin * k_rot  # F_i R_x(θ_i) j (Eq. 2)
    u_cross_v = -sin * j_rot + cos * k_rot  # F_i R_x(θ_i) k
    b = a + params.arm_length * v
    w = (platform.c - b) / params.rod_length
    h = params.arm_length * np.sum(w * u_cross_v, axis=-1)  # Eq. (8)
    assert params.parallelogram_width is not None  # set by FourLimbParameters.__post_init__
    half = 0.5 * params.parallelogram_width * np.stack([-u, u], axis=-2)  # (4, 2, 3)
    return FourLimbConfiguration(
        params=params,
        working_mode=working_mode,
        pose=pose,
        theta=theta,
        a=np.broadcast_to(a, (*batch, 4, 3)),
        u=np.broadcast_to(u, (*batch, 4, 3)),
        b=b,
        v=v,
        c=platform.c,
        w=w,
        h=h,
        s=platform.dc_dphi / params.platform_radius,
        platform_s=platform.platform_s,
        elbow_corners=b[..., None, :] + half,
        platform_corners=platform.c[..., None, :] + half,
        subplatform_limbs=params.subplatform_limbs,
        platform_joint_points=platform.joint_points,
        platform_joint_axis=platform.joint_axis,
        platform_joint_pitches=(
            (-params.lead / (2.0 * np.pi), 0.0) if params.lead is not None else (0.0, 0.0)
        ),
    )
