"""Paper 000's own analysis of the Peppermill: its Jacobians ``A``, ``B`` and their singularities.

Source: paper 000 (Harada & Angeles, "Kinematics and singularity analysis of a CRRHHRRC parallel
Schönflies motion generator", CSME Trans. 38(2), 2014) (docs/papers.md). The robot model (parameters, inverse and forward
kinematics, joints, twist basis) is :mod:`screwkit.robots.families.peppermill`; this module holds what only
serves to check the paper (``tests/robots/test_families_peppermill.py``, ``tests/robots/test_two_limb_catalog.py``,
``tests/papers/test_paper_jacobians.py``, ``tests/facts_two_limb.py``): Eqs. (44)-(48), the factors of
``det A`` and ``det B``, the Gosselin-Angeles type from them
(:func:`screwkit.core.jacobian_matrices.classify_jacobians`) and a root search for second-kind singularities.

Where paper 000 is garbled or wrong about its Jacobians (each item is demonstrated in the tests)
-----------------------------------------------------------------------------------------------
1. Eq. (45) prints ``u_θ2 = [u_θ2z, 0, u_θ2z]``; from Eq. (38) it is ``[u_θ2x, 0, u_θ2z] =
   [cos θ_2, 0, -sin θ_2]``.
2. Sec. 4.2 calls ``v_i`` the unit vector of the proximal link and ``u_i`` that of the distal one;
   Sec. 2 defines the opposite. ``v_i · u_θi = sin λ_i`` vanishes when the two links are aligned:
   extended (``λ_i = 0``) or folded (``λ_i = π``).
3. The vector ``δθ`` of Eq. (46) is ``(δd_1, δd_2, r_1 δθ_1, r_2 δθ_2)`` (Eq. 44), not
   ``(δd_1, δd_2, δθ_1, δθ_2)``; ``B`` of Eq. (47) multiplies the former.
4. Sec. 4.4 gives no condition for the third kind. From Eqs. (47)-(48) it is ``sin λ_j = 0`` and
   ``v_iz = 0`` (or ``p_1 = p_2``) for some ``i, j``: within one limb (aligned links lying
   horizontal) or across the limbs; both occur.

Examples
--------
>>> from screwkit.robots.families.peppermill import PeppermillParameters, inverse_kinematics
>>> mill = PeppermillParameters(r1=250.0, r2=250.0, l1=400.0, l2=400.0, b0=50.0, p1=40.0, p2=-40.0)
>>> classify(inverse_kinematics(mill, [30.0, -20.0, -450.0, 0.5])).types.tolist()
'regular'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from screwkit.algebra.backend import DEFAULT_RTOL
from screwkit.algebra.checks import checked_length_scale
from screwkit.core.jacobian_matrices import Jacobians, classify_jacobians
from screwkit.robots.families.peppermill import (
    DEFAULT_MODE,
    PeppermillConfiguration,
    PeppermillParameters,
    inverse_kinematics,
)
from screwkit.robots.two_limb import checked_mode, frozen

from .two_limb_papers import bisect_segment

__all__ = [
    "PeppermillSingularityFactors",
    "classify",
    "jacobians",
    "locate_direct_singularity",
    "singularity_factors",
]


def jacobians(config: PeppermillConfiguration) -> Jacobians:
    """Forward and inverse Jacobians of Eqs. (44)-(47): ``A δx = B δθ``.

    ``δx = (δx, δy, δz, δφ)`` and ``δθ = (δd_1, δd_2, r_1 δθ_1, r_2 δθ_2)`` (Eq. 44). The rows of
    ``A`` are ``[a_i^T, 0]`` and ``[v_i^T, (p_i/2π) v_i·k]``; ``B = diag(1, 1, v_1·u_θ1,
    v_2·u_θ2)``. Computed from the axes of ``config`` (Eq. 44 form), which in the base frame is
    Eq. (47) entry by entry.

    Returns
    -------
    Jacobians
        ``A`` and ``B``, each of shape (..., 4, 4); the last column of ``A`` has the unit of length.

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> jac = jacobians(inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5]))
    >>> jac.A[:2]
    array([[1., 0., 0., 0.],
           [0., 1., 0., 0.]])
    """
    _, _, leads = config.params.lengths
    k = config.platform_axis[..., None, :]
    v, a = config.v, config.drive_axis
    top = np.concatenate([a, np.zeros((*a.shape[:-1], 1))], axis=-1)
    bottom = np.concatenate([v, (leads * np.sum(v * k, axis=-1))[..., None]], axis=-1)
    a_matrix = np.concatenate([top, bottom], axis=-2)
    diagonal = np.concatenate(
        [np.ones((*config.batch_shape, 2)), np.sum(v * config.u_theta, axis=-1)], axis=-1
    )
    b_matrix = diagonal[..., None] * np.eye(4)
    return Jacobians(a_matrix, b_matrix)


@dataclass(frozen=True, slots=True, eq=False)
class PeppermillSingularityFactors:
    """The factors of ``det A`` and ``det B`` (Eqs. 47-48).

    Attributes
    ----------
    sin_lambda : (..., 2) ndarray
        ``v_i · u_θi = sin λ_i``; ``det B = sin λ_1 sin λ_2`` (first kind).
    v_z : (..., 2) ndarray
        ``v_iz``; ``det A = v_1z v_2z (p_2 - p_1)/2π`` (second kind, Eq. 48).
    lead_difference : float
        ``(p_2 - p_1)/2π``; zero: architecture singularity.

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> f = singularity_factors(inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5]))
    >>> round(float(f.lead_difference), 6), f.det_a.shape
    (-12.732395, ())
    """

    sin_lambda: np.ndarray
    v_z: np.ndarray
    lead_difference: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "sin_lambda", frozen(self.sin_lambda))
        object.__setattr__(self, "v_z", frozen(self.v_z))

    @property
    def det_a(self) -> np.ndarray:
        """``det A = v_1z v_2z (p_2 - p_1)/2π`` (Eq. 48), shape (...)."""
        return np.asarray(self.v_z[..., 0] * self.v_z[..., 1] * self.lead_difference)

    @property
    def det_b(self) -> np.ndarray:
        """``det B = sin λ_1 sin λ_2``, shape (...)."""
        return np.asarray(self.sin_lambda[..., 0] * self.sin_lambda[..., 1])


def singularity_factors(config: PeppermillConfiguration) -> PeppermillSingularityFactors:
    """The factors of :class:`PeppermillSingularityFactors` at ``config``.

    Parameters
    ----------
    config : PeppermillConfiguration

    Returns
    -------
    PeppermillSingularityFactors

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> singularity_factors(inverse_kinematics(p, [30.0, -20.0, -450.0, 0.5])).v_z.shape
    (2,)
    """
    _, _, leads = config.params.lengths
    return PeppermillSingularityFactors(
        sin_lambda=np.sum(config.v * config.u_theta, axis=-1),
        v_z=np.sum(config.v * config.platform_axis[..., None, :], axis=-1),
        lead_difference=float(leads[1] - leads[0]),
    )


def _length_scale(params: PeppermillParameters, length_scale: float | None) -> float:
    if length_scale is None:
        _, _, leads = params.lengths
        mean = float(np.abs(leads).mean())
        return mean if mean > 0 else 1.0
    return checked_length_scale(length_scale)


def classify(
    config: PeppermillConfiguration,
    *,
    rtol: float = DEFAULT_RTOL,
    length_scale: float | None = None,
) -> Jacobians:
    """Gosselin-Angeles type: first kind (``B``), second kind (``A``), third kind (both).

    ``B`` of Eq. (47) is dimensionless; ``A``'s last column (the ``δφ`` column) has the unit of
    length and is divided by ``length_scale`` before taking ``σ_min/σ_max``, which makes the
    closeness independent of the unit and of a rotation of the base frame. The default,
    ``(|p_1| + |p_2|)/(4π)`` (the mean lead per radian), turns that column into ``±v_iz`` when
    ``p_2 = -p_1``; when both leads vanish the column is zero and any scale gives closeness 0
    (1 is used).

    Parameters
    ----------
    config : PeppermillConfiguration
    rtol : float, default 1e-9
    length_scale : float, optional

    Returns
    -------
    Jacobians
        ``"inverse"`` (first kind), ``"direct"`` (second kind), ``"combined"`` (third kind) or
        ``"regular"``.

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> # q_1 = (0, y, b0 + z + p1 φ/2π) = (0, 390, -520) has length r1 + l1 = 650: limb 1 extended
    >>> classify(inverse_kinematics(p, [0.0, 390.0, -570.0, 0.0])).types.tolist()
    'inverse'
    """
    jac = jacobians(config)
    scale = np.array([1.0, 1.0, 1.0, 1.0 / _length_scale(config.params, length_scale)])
    return classify_jacobians(jac.A * scale, jac.B, rtol=rtol)


def locate_direct_singularity(
    params: PeppermillParameters, start: Any, end: Any, *, mode: Any = DEFAULT_MODE
) -> np.ndarray:
    """Pose where the straight path ``start → end`` crosses a second-kind singularity (bisection).

    Bisection on ``det A`` (Eq. 48) in one working mode; ``det A`` must change sign, i.e. one
    ``v_iz`` crosses zero. (Within a working mode ``sin λ_i`` keeps its sign: first-kind
    singularities bound the modes and are not crossed.)

    Parameters
    ----------
    params : PeppermillParameters
    start, end : (..., 4) array_like
        Poses at which ``det A`` has opposite signs.
    mode : tuple of 2 int, default ``(1, 1)``

    Returns
    -------
    (..., 4) ndarray

    Examples
    --------
    >>> p = PeppermillParameters(250, 250, 400, 400, 50, 40, -40)
    >>> # y only moves limb 1 (q_1 = (0, y, ...)); its distal link turns horizontal on the way
    >>> pose = locate_direct_singularity(p, [0.0, 150.0, -150.0, 0.0], [0.0, 300.0, -150.0, 0.0])
    >>> classify(inverse_kinematics(p, pose)).types.tolist()
    'direct'
    """
    checked = checked_mode(mode, "mode", 2)
    return bisect_segment(
        lambda pose: singularity_factors(inverse_kinematics(params, pose, checked)).det_a,
        start,
        end,
    )
