"""Paper 003's own analysis of the planar 3-RRP: velocities, instant centres, its Jacobians and its
singularity classification, beside the tests that check them.

Source: paper 003 (S. Zarkandi, "A study of the instantaneous centers of rotation in singularities of
3-DOF fully parallel planar manipulators") (docs/papers.md);
equation numbers are that paper's. The robot model (parameters, kinematics, joint table) is
:mod:`screwkit.robots.families.planar_3rrp`; screwkit analyses its joint table with the wrench systems,
and the tests compare the two (``tests/robots/test_planar_catalog.py``, ``tests/facts_planar.py``,
``tests/papers/test_paper_jacobians.py``). These functions are computed without screw systems, from the
paper's formulas, so that the comparison is independent.

Velocities, Eqs. (4)-(11): ``J θ̇ + K t = 0`` with ``J = diag(b_kᵀ(C_ij - C_1i))`` (Eq. 11a) and rows
``K_k = [b_kᵀ(C - C_ij), b_kᵀE]`` (Eq. 11b). We keep the paper's letters: *its* ``J`` multiplies the
actuator rates and *its* ``K`` the twist, so ``det J = 0`` is the inverse (type-1, serial) and
``det K = 0`` the direct (type-2, parallel) singularity; some texts, and our task brief, swap the
letters. Both matrices equal the partial derivatives of ``f`` (Eq. 3), and the tests check them
against finite differences.

Instant centres
---------------
Planar points are homogeneous ``(x, y, w)``: finite ``(p, 1)``, at infinity ``(d, 0)`` (the
direction ``d`` of the pencil of parallel lines through it). The centre of links ``q, r`` whose
relative twist is ``(ω, v_O)`` (angular rate, velocity of the point at the origin) is
``(E v_O, ω)`` (Eq. 5 solved for the point of zero relative velocity). Joint centres do not
depend on the motion: ``C_1i = (M_k, 1)``, ``C_ij = (A_k, 1)``, ``C_j8 = (E b_k, 0)``. In these
coordinates

* ``J_kk = det[C_1i; C_ij; C_j8]``: limb ``k`` is inverse-singular iff its three joint centres are
  collinear (Eq. 12: first link ⟂ guide);
* ``det K = -det[L_1; L_2; L_3]`` with the Kennedy lines ``L_k = C_ij × C_j8`` (through the elbow,
  perpendicular to the guide; the paper's ``t_i``): direct-singular iff they are concurrent (at
  ``D``, then ``C_18 = D`` with the actuators locked) or parallel (impossible here, Sec. 4.2).

Where paper 003 is garbled or wrong (each is checked in ``tests/robots/test_families_planar_3rrp.py``; item 6,
about the model, is in :mod:`screwkit.robots.families.planar_3rrp`)
-------------------------------------------------------------------------------------------------------
1. Eqs. (7a), (11a): the OCR prints ``C_li``; it is ``C_1i`` (the actuated joint on link 1, Eq. 12).
2. Eq. (3): ``t ≡ X`` lost its dot, ``t = Ẋ`` with ``X = (φ, C)``; finite differences of the IK
   confirm Eq. (10) for ``t = (φ̇, ẋ, ẏ)``.
3. Eq. (17): with ``d = CD`` (Eq. 14) and ``t_i`` from ``C_ij`` to ``D`` (Fig. 3), ``C - C_ij =
   t_i - d``, not ``d + t_i``. The conclusion (Eq. 18) survives because ``b_iᵀ t_i = 0`` (Eq. 15)
   leaves ``b_iᵀ(C - C_ij) = -b_iᵀ d`` for every ``i``; the test measures both sides.
4. Eq. (13): "since the three vectors ``b_i`` are coplanar" is not the reason; it needs ``b_2``,
   ``b_4`` not parallel (``α_1, α_2`` exist then).
5. Sec. 4.3, "while none of the rows of ``K`` vanishes": ``|b_kᵀE| = 1``, so no row of ``K`` can
   vanish; the condition is void for this manipulator.

The claims of Secs. 4.1-4.2 survive a rank computation (tests): at an inverse singularity of limb
``k``, driving only actuator ``k`` leaves the platform at rest and ``C_i8 = C_1i``; at a direct
singularity the null twist of ``K`` is a rotation about the concurrency point ``D = C_18``.

Examples
--------
>>> config = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
>>> J, K = jacobians(config)
>>> np.round(np.diag(J), 4)
array([0.4975, 0.4975, 0.4975])
>>> str(classify(config).kind)
'regular'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from screwkit.algebra.backend import DEFAULT_RTOL, as_array
from screwkit.algebra.checks import checked_rtol
from screwkit.exceptions import DegenerateGeometryError, ScrewkitValueError
from screwkit.robots.families.planar_3rrp.configuration import Planar3RRPConfiguration, _check_config
from screwkit.robots.families.planar_3rrp.joints import JOINT_PAIRS
from screwkit.robots.families.planar_3rrp.parameters import (
    EXAMPLE_PARAMETERS,  # noqa: F401 (the doctests use it)
    _dot,
    _first_index,
    _perp,
    _readonly,
)

__all__ = [
    "SingularityClassification",
    "classify",
    "complete_velocity",
    "instant_center",
    "instant_centers",
    "jacobians",
    "link_twists",
]


# --------------------------------------------------------------------------------------------------
# Jacobians, Eqs. (4)-(11)
# --------------------------------------------------------------------------------------------------


def _joint_centers(config: Planar3RRPConfiguration) -> np.ndarray:
    """Homogeneous joint centres ``(..., limb, joint, 3)``: ``(M, 1)``, ``(A, 1)``, ``(E b, 0)``."""
    ones = np.ones((*config.batch_shape, 3, 1))
    return np.stack(
        [
            np.concatenate([config.base_points, ones], axis=-1),
            np.concatenate([config.elbow_points, ones], axis=-1),
            np.concatenate([_perp(config.guide_directions), 0.0 * ones], axis=-1),
        ],
        axis=-2,
    )


def jacobians(
    config: Planar3RRPConfiguration,
    *,
    method: Literal["instant_centers", "velocity_loop"] = "instant_centers",
) -> tuple[np.ndarray, np.ndarray]:
    """The Jacobians of Eq. (10), ``J θ̇ + K t = 0``, with ``t = (ω, ẋ, ẏ)``.

    Parameters
    ----------
    config : Planar3RRPConfiguration
    method : {"instant_centers", "velocity_loop"}
        ``"instant_centers"``: Eq. (11) as printed, from the joint centres ``C_1i``, ``C_ij`` and
        ``C_j8 = (E b_i, 0)`` (so ``b_i = -E`` times its first two coordinates).
        ``"velocity_loop"``: the loop ``θ̇_k $_1 + ψ̇_k $_2 + γ̇_k $_3 = t_O`` of each limb (planar
        twists ``(ω, v_O)`` about the base origin, the sum behind Eq. 4), with the passive rates
        eliminated by ``w_k = $_2 × $_3``, which annihilates both passive twists; then
        ``J_kk = w_k·$_1`` and ``K_k = -w_kᵀ T(C)``, ``T`` mapping ``(ω, Ċ)`` to ``(ω, v_O)``.

    Returns
    -------
    J : numpy.ndarray, shape (..., 3, 3)
        Diagonal, ``J_kk = b_kᵀ(C_ij - C_1i)`` (Eq. 11a).
    K : numpy.ndarray, shape (..., 3, 3)
        Rows ``[b_kᵀ(C - C_ij), b_kᵀE]`` (Eq. 11b).

    Raises
    ------
    ScrewkitValueError
        If ``method`` is unknown.

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.05, 0.0, 0.1])
    >>> J1, K1 = jacobians(c)
    >>> J2, K2 = jacobians(c, method="velocity_loop")
    >>> bool(np.allclose(J1, J2) and np.allclose(K1, K2))
    True
    """
    config = _check_config(config)
    centre = config.platform_point[..., None, :]
    if method == "instant_centers":
        centers = _joint_centers(config)
        c1i = centers[..., 0, :2] / centers[..., 0, 2:]
        cij = centers[..., 1, :2] / centers[..., 1, 2:]
        b = -_perp(centers[..., 2, :2])
        diagonal = _dot(b, cij - c1i)  # Eq. (11a)
        k_matrix = np.concatenate(  # Eq. (11b); b^T E = (b_y, -b_x)
            [_dot(b, centre - cij)[..., None], -_perp(b)], axis=-1
        )
    elif method == "velocity_loop":
        ones = np.ones((*config.batch_shape, 3))
        base, elbow, b = config.base_points, config.elbow_points, config.guide_directions
        actuated = np.stack([ones, base[..., 1], -base[..., 0]], axis=-1)
        passive_r = np.stack([ones, elbow[..., 1], -elbow[..., 0]], axis=-1)
        passive_p = np.stack([0.0 * ones, b[..., 0], b[..., 1]], axis=-1)
        reciprocal = np.cross(passive_r, passive_p)
        diagonal = _dot(reciprocal, actuated)
        x, y = config.platform_point[..., 0], config.platform_point[..., 1]
        zeros, unit = np.zeros_like(x), np.ones_like(x)
        to_origin = np.stack(
            [
                np.stack([unit, zeros, zeros], -1),
                np.stack([y, unit, zeros], -1),
                np.stack([-x, zeros, unit], -1),
            ],
            axis=-2,
        )
        k_matrix = -reciprocal @ to_origin
    else:
        raise ScrewkitValueError(
            f"Expected `method` to be 'instant_centers' or 'velocity_loop', got {method!r}."
        )
    j_matrix = diagonal[..., None] * np.eye(3)
    return j_matrix, k_matrix


# --------------------------------------------------------------------------------------------------
# Velocities and instant centres, Eqs. (5), (7)
# --------------------------------------------------------------------------------------------------


def _scaled_k(config: Planar3RRPConfiguration, k_matrix: np.ndarray) -> np.ndarray:
    """``K`` with moments about the elbows' centroid ``G`` divided by ``length_scale``.

    Moving the reference point adds multiples of columns 2, 3 to column 1 and scaling a column keeps
    the rank, so this matrix is singular exactly when ``K`` is; its singular values do not depend on
    the base frame, the platform frame or the length unit.
    """
    b = config.guide_directions
    elbows = config.elbow_points
    centroid = elbows.mean(axis=-2, keepdims=True)
    moments = _dot(b, centroid - elbows) / config.parameters.length_scale
    return np.concatenate([moments[..., None], k_matrix[..., 1:]], axis=-1)


def _k_spectrum(
    config: Planar3RRPConfiguration, k_matrix: np.ndarray, rtol: float
) -> tuple[np.ndarray, np.ndarray]:
    """Singular values of :func:`_scaled_k` and the rank they give with tolerance ``rtol``."""
    values = np.linalg.svd(_scaled_k(config, k_matrix), compute_uv=False)
    return values, (values > rtol * values[..., :1]).sum(axis=-1)


def complete_velocity(
    config: Planar3RRPConfiguration,
    *,
    joint_rates: Any = None,
    twist: Any = None,
    rtol: float = DEFAULT_RTOL,
) -> tuple[np.ndarray, np.ndarray]:
    """Actuator rates and platform twist satisfying Eq. (10), from either (or check both).

    Parameters
    ----------
    config : Planar3RRPConfiguration
    joint_rates : array_like, shape (..., 3), optional
        ``θ̇``; with ``twist`` absent, ``t = -K⁻¹ J θ̇``.
    twist : array_like, shape (..., 3), optional
        ``t = (ω, ẋ, ẏ)``; with ``joint_rates`` absent, ``θ̇_k = -K_k t / J_kk``.
    rtol : float, default 1e-9
        Rank tolerance (as in :func:`classify`) and, with both given, the allowed residual of limb
        ``k`` relative to ``l_k |θ̇_k| + |C - A_k| |ω| + |Ċ|``.

    Returns
    -------
    joint_rates, twist : numpy.ndarray, shape (..., 3)

    Raises
    ------
    ScrewkitValueError
        If neither is given, or both are given and violate Eq. (10) (names the limb).
    DegenerateGeometryError
        If the given half does not determine the other: ``joint_rates`` at a direct singularity,
        ``twist`` at an inverse singularity (names the limb).

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> rates, t = complete_velocity(c, twist=[1.0, 0.0, 0.0])
    >>> np.allclose(complete_velocity(c, joint_rates=rates)[1], [1.0, 0.0, 0.0])
    True
    """
    config = _check_config(config)
    rtol = checked_rtol(rtol)
    j_matrix, k_matrix = jacobians(config)
    diagonal = np.diagonal(j_matrix, axis1=-2, axis2=-1)
    if joint_rates is None and twist is None:
        raise ScrewkitValueError("Expected `joint_rates` or `twist` (or both), got neither.")
    if twist is None:
        rates = as_array(joint_rates, "joint_rates", (3,))
        rank_deficient = _k_spectrum(config, k_matrix, rtol)[1] < 3
        if np.any(rank_deficient):
            index = _first_index(rank_deficient)
            raise DegenerateGeometryError(
                f"`joint_rates` do not determine the twist at batch index {index}: the "
                "configuration is a direct (type-2) singularity, det K = 0 (Eq. 11b); pass `twist`."
            )
        rhs = -(diagonal * rates)
        shape = np.broadcast_shapes(k_matrix.shape[:-2], rhs.shape[:-1])
        solved = np.linalg.solve(
            np.broadcast_to(k_matrix, (*shape, 3, 3)), np.broadcast_to(rhs, (*shape, 3))[..., None]
        )
        return np.broadcast_to(rates, (*shape, 3)).copy(), solved[..., 0]
    t = as_array(twist, "twist", (3,))
    drive = np.einsum("...kc,...c->...k", k_matrix, t)
    if joint_rates is None:
        cosines = np.abs(diagonal) / config.parameters.link_lengths
        stuck = np.broadcast_to(cosines <= rtol, drive.shape)
        if np.any(stuck):
            index = _first_index(stuck)
            raise DegenerateGeometryError(
                f"The twist does not determine the rate of actuator {index[-1] + 1} at batch index "
                f"{index[:-1]}: limb {index[-1] + 1} is at an inverse (type-1) singularity, "
                "J_kk = 0 (Eq. 12); pass `joint_rates`."
            )
        safe = np.where(cosines > rtol, diagonal, 1.0)
        return -drive / safe, np.broadcast_to(t, drive.shape).copy()
    rates = as_array(joint_rates, "joint_rates", (3,))
    residual = np.abs(diagonal * rates + drive)
    offsets = np.linalg.norm(config.platform_point[..., None, :] - config.elbow_points, axis=-1)
    size = (
        config.parameters.link_lengths * np.abs(rates)
        + offsets * np.abs(t[..., :1])
        + np.linalg.norm(t[..., 1:], axis=-1, keepdims=True)
    )
    violated = residual > rtol * size
    if np.any(violated):
        index = _first_index(violated)
        raise ScrewkitValueError(
            f"Expected `joint_rates` and `twist` to satisfy J θ̇ + K t = 0 (Eq. 10), but limb "
            f"{index[-1] + 1} at batch index {index[:-1]} leaves a residual {residual[index]:.3g}."
        )
    shape = residual.shape
    return np.broadcast_to(rates, shape).copy(), np.broadcast_to(t, shape).copy()


def link_twists(config: Planar3RRPConfiguration, joint_rates: Any, twist: Any) -> np.ndarray:
    """Planar twists ``(ω, v_Ox, v_Oy)`` of the eight links relative to the base.

    ``v_O`` is the velocity of the link point at the base origin. Link ``i`` turns about ``M_k`` at
    ``θ̇_k``; link ``j`` turns at the platform's ``ω`` and moves its elbow point at
    ``θ̇_k E(A_k - M_k)`` (Eq. 7a); the platform moves at ``t`` (Eq. 3). Pass a consistent pair
    (see :func:`complete_velocity`); this function does not check Eq. (10).

    Parameters
    ----------
    config : Planar3RRPConfiguration
    joint_rates, twist : array_like, shape (..., 3)

    Returns
    -------
    numpy.ndarray, shape (..., 8, 3)
        Row ``label - 1`` for the paper's link ``label`` (:data:`LINK_NAMES`).

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> link_twists(c, [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]).shape
    (8, 3)
    """
    config = _check_config(config)
    rates = as_array(joint_rates, "joint_rates", (3,))
    t = as_array(twist, "twist", (3,))
    shape = np.broadcast_shapes(config.batch_shape, rates.shape[:-1], t.shape[:-1])
    rates = np.broadcast_to(rates, (*shape, 3))
    t = np.broadcast_to(t, (*shape, 3))
    omega = t[..., :1]
    base, elbow = config.base_points, config.elbow_points
    first = rates[..., None] * np.concatenate(
        [np.ones((*config.batch_shape, 3, 1)), -_perp(base)], axis=-1
    )
    elbow_velocity = rates[..., None] * _perp(elbow - base)
    second = np.concatenate(
        [
            np.broadcast_to(omega[..., None], (*shape, 3, 1)),
            elbow_velocity - omega[..., None] * _perp(elbow),
        ],
        axis=-1,
    )
    platform = np.concatenate([omega, t[..., 1:] - omega * _perp(config.platform_point)], axis=-1)
    out = np.zeros((*shape, 8, 3))
    out[..., 1:7:2, :] = first
    out[..., 2:7:2, :] = second
    out[..., 7, :] = platform
    return out


def instant_centers(
    config: Planar3RRPConfiguration,
    *,
    joint_rates: Any = None,
    twist: Any = None,
    rtol: float = DEFAULT_RTOL,
) -> np.ndarray:
    """All 28 instant centres of the eight links for a motion, as homogeneous points.

    The centre of links ``q, r`` is ``(E v, ω)`` for their relative twist ``(ω, v)``
    (:func:`link_twists`, Eq. 5): finite when they turn relative to each other, at infinity in the
    direction ``E v`` (perpendicular to the velocity) when they translate. Joint centres
    (:data:`JOINT_PAIRS`) are taken from the joints, ``(M_k, 1)``, ``(A_k, 1)``, ``(E b_k, 0)``,
    whatever the motion. Any three centres ``C_qr, C_rs, C_qs`` are collinear (Aronhold-Kennedy,
    Sec. 2.1). Centres of non-adjacent links depend on the motion, fixed by ``joint_rates`` and/or
    ``twist`` through :func:`complete_velocity`; the paper's "lock all actuators but ``k``" is
    ``joint_rates = e_k``.

    Parameters
    ----------
    config : Planar3RRPConfiguration
    joint_rates, twist : array_like, shape (..., 3), optional
        See :func:`complete_velocity`.
    rtol : float, default 1e-9

    Returns
    -------
    numpy.ndarray, shape (..., 8, 8, 3)
        ``[..., q - 1, r - 1, :]`` is ``C_qr`` (up to a non-zero factor; ``C_rq = -C_qr``). The
        zero vector means the two links do not move relative to each other (every point is a
        centre): the diagonal, and e.g. two links both at rest.

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> centers = instant_centers(c, twist=[1.0, 0.0, 0.0])
    >>> centers[0, 7]  # the platform turns about C = origin relative to the base
    array([0., 0., 1.])
    """
    rates, t = complete_velocity(config, joint_rates=joint_rates, twist=twist, rtol=rtol)
    twists = link_twists(config, rates, t)
    relative = twists[..., None, :, :] - twists[..., :, None, :]  # [q, r]: r relative to q
    centers = np.concatenate([_perp(relative[..., 1:]), relative[..., :1]], axis=-1)
    joint_centers = np.broadcast_to(_joint_centers(config), (*centers.shape[:-3], 3, 3, 3))
    for limb, pairs in enumerate(JOINT_PAIRS):
        for joint, (q, r) in enumerate(pairs):
            centers[..., q - 1, r - 1, :] = joint_centers[..., limb, joint, :]
            centers[..., r - 1, q - 1, :] = -joint_centers[..., limb, joint, :]
    return centers


def instant_center(
    config: Planar3RRPConfiguration,
    pair: tuple[int, int],
    *,
    joint_rates: Any = None,
    twist: Any = None,
    rtol: float = DEFAULT_RTOL,
) -> np.ndarray:
    """The instant centre ``C_qr`` of one pair of links (paper labels 1..8).

    For a joint pair (:data:`JOINT_PAIRS`) no motion is needed; otherwise give ``joint_rates``
    and/or ``twist`` as in :func:`instant_centers`.

    Parameters
    ----------
    config : Planar3RRPConfiguration
    pair : (int, int)
        Two distinct labels ``q, r`` in 1..8.
    joint_rates, twist : array_like, shape (..., 3), optional
    rtol : float, default 1e-9

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        Homogeneous ``(x, y, w)``, as in :func:`instant_centers`.

    Raises
    ------
    ScrewkitValueError
        If ``pair`` is not two distinct labels in 1..8, or it is not a joint pair and no motion
        is given.

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> instant_center(c, (1, 2))  # C_12 = M_1
    array([-0.8660254, -0.5      ,  1.       ])
    """
    config = _check_config(config)
    if (
        not isinstance(pair, tuple | list)
        or len(pair) != 2
        or any(isinstance(v, bool) or not isinstance(v, int | np.integer) for v in pair)
        or not all(1 <= v <= 8 for v in pair)
        or pair[0] == pair[1]
    ):
        raise ScrewkitValueError(
            f"Expected `pair` to be two distinct link labels in 1..8, got {pair!r}."
        )
    q, r = int(pair[0]), int(pair[1])
    for limb, pairs in enumerate(JOINT_PAIRS):
        for joint, joint_pair in enumerate(pairs):
            if {q, r} == set(joint_pair):
                sign = 1.0 if (q, r) == joint_pair else -1.0
                return sign * _joint_centers(config)[..., limb, joint, :]
    if joint_rates is None and twist is None:
        raise ScrewkitValueError(
            f"The instant centre C_{q}{r} of non-adjacent links depends on the motion; pass "
            "`joint_rates` or `twist`."
        )
    centers = instant_centers(config, joint_rates=joint_rates, twist=twist, rtol=rtol)
    return centers[..., q - 1, r - 1, :]


# --------------------------------------------------------------------------------------------------
# Singularities, Sec. 4
# --------------------------------------------------------------------------------------------------

_KINDS = np.array([["regular", "direct"], ["inverse", "combined"]])


@dataclass(frozen=True, eq=False, slots=True)
class SingularityClassification:
    """Singularity type of each configuration (paper 003, Sec. 4).

    Attributes
    ----------
    kind : numpy.ndarray of str, shape (...)
        ``"regular"``, ``"inverse"`` (type 1: ``J`` rank-deficient, ``K`` not, Sec. 4.1),
        ``"direct"`` (type 2, Sec. 4.2) or ``"combined"`` (type 3, Sec. 4.3).
    inverse_closeness : numpy.ndarray, shape (...)
        ``min_k |J_kk| / l_k``, the smallest ``|cos|`` of the angle between a first link and its
        guide, in ``[0, 1]``; 0 at an inverse singularity.
    direct_closeness : numpy.ndarray, shape (...)
        ``σ_min / σ_max`` of ``K`` with its moments taken about the elbows' centroid and divided
        by ``length_scale`` (same rank as ``K``), in ``[0, 1]``; 0 at a direct singularity.
    rank_j, rank_k : numpy.ndarray of int, shape (...)
        Ranks with tolerance ``rtol`` (``|J_kk| / l_k > rtol``, ``σ > rtol σ_max``).
    singular_limbs : numpy.ndarray of bool, shape (..., 3)
        Limbs with ``|J_kk| / l_k <= rtol`` (Eq. 12).
    rtol : float

    Both closeness values are invariant under rigid motions of the base frame and changes of the
    length unit (ratios of lengths and cosines).
    """

    kind: np.ndarray
    inverse_closeness: np.ndarray
    direct_closeness: np.ndarray
    rank_j: np.ndarray
    rank_k: np.ndarray
    singular_limbs: np.ndarray
    rtol: float

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary.

        Examples
        --------
        >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
        >>> classify(c).to_dict()["kind"]
        'regular'
        """
        return {
            "kind": self.kind.tolist(),
            "inverse_closeness": self.inverse_closeness.tolist(),
            "direct_closeness": self.direct_closeness.tolist(),
            "rank_j": self.rank_j.tolist(),
            "rank_k": self.rank_k.tolist(),
            "singular_limbs": self.singular_limbs.tolist(),
            "rtol": self.rtol,
        }

    def __str__(self) -> str:
        if self.kind.ndim == 0:
            return (
                f"{self.kind}: rank J = {self.rank_j}, rank K = {self.rank_k}, inverse closeness "
                f"{self.inverse_closeness:.3g}, direct closeness {self.direct_closeness:.3g}"
            )
        names, numbers = np.unique(self.kind, return_counts=True)
        counts = {str(k): int(n) for k, n in zip(names, numbers, strict=True)}
        return f"SingularityClassification over {self.kind.shape}: {counts}"


def classify(
    config: Planar3RRPConfiguration, *, rtol: float = DEFAULT_RTOL
) -> SingularityClassification:
    """Classify configurations as regular, inverse, direct or combined singularities (Sec. 4).

    In instant centres (module docstring): limb ``k`` is inverse-singular when ``C_1i``, ``C_ij``,
    ``C_j8`` are collinear (first link ⟂ guide, Eq. 12); driving actuator ``k`` alone then leaves
    the platform at rest and ``C_i8 = C_1i``. The configuration is direct-singular when the three
    lines ``C_ij C_j8`` (through the elbows, ⟂ the guides) are concurrent: with the actuators
    locked the platform can turn about that point, ``C_18``. Combined: both at once.

    Parameters
    ----------
    config : Planar3RRPConfiguration
    rtol : float, default 1e-9
        Rank tolerance on the closeness measures (see :class:`SingularityClassification`).

    Returns
    -------
    SingularityClassification

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> print(classify(c))
    regular: rank J = 3, rank K = 3, inverse closeness 0.553, direct closeness ...
    """
    config = _check_config(config)
    rtol = checked_rtol(rtol)
    j_matrix, k_matrix = jacobians(config)
    cosines = np.abs(np.diagonal(j_matrix, axis1=-2, axis2=-1)) / config.parameters.link_lengths
    singular_limbs = cosines <= rtol
    values, rank_k = _k_spectrum(config, k_matrix, rtol)
    rank_j = 3 - singular_limbs.sum(axis=-1)
    kind = _KINDS[(rank_j < 3).astype(int), (rank_k < 3).astype(int)]
    return SingularityClassification(
        kind=_readonly(kind),
        inverse_closeness=_readonly(cosines.min(axis=-1)),
        direct_closeness=_readonly(values[..., -1] / values[..., 0]),
        rank_j=_readonly(rank_j),
        rank_k=_readonly(rank_k),
        singular_limbs=_readonly(singular_limbs),
        rtol=rtol,
    )
