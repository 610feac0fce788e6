"""Paper 001's own analysis of the McGill SMG: its Jacobians ``A``, ``B`` and their singularities.

Source: paper 001 (Angeles, Caro, Khan, Morozov, "Kinetostatic design of an innovative
Schönflies-motion generator", Proc. IMechE C 220(7), 2006) (docs/papers.md). The robot model (parameters, inverse and forward
kinematics, joints, twist basis) is :mod:`screwkit.robots.families.mcgill_smg`; this module holds what
only serves to check the paper (``tests/robots/test_families_mcgill_smg.py``,
``tests/robots/test_two_limb_catalog.py``, ``tests/papers/test_paper_jacobians.py``, ``tests/facts_two_limb.py``):
Eqs. (16)-(19), the singularity factors of Eqs. (20)-(24), the Gosselin-Angeles type from them
(:func:`screwkit.core.jacobian_matrices.classify_jacobians`) and a root search for parallel singularities.

Where paper 001 is garbled or wrong (each item is demonstrated in the tests)
---------------------------------------------------------------------------
1. Eq. (17a) prints ``A_J ∈ R^{3×2}`` and ``B_J ∈ R^{2×4}``. ``A_J = [½ s(J) Φ_J (k × (σ_I - σ_II)),
   Φ_J]`` is 3×4 and ``B_J = [v_J, Δ_J f_J]`` is 3×2, as Eq. (19) (``A, B ∈ R^{6×4}``, zero blocks
   ``O_32``) requires.
2. Sec. 4.2 says the null spaces of ``Φ_I``, ``Φ_II`` are "spanned by vectors ``Φ_I`` and ``Φ_II``":
   they are spanned by ``φ_I``, ``φ_II`` (lower case, Eq. 17b).
3. Eqs. (20a)-(21b) and Figs. 7(a), 7(b). From Eq. (10), ``v_J = (ρ_J1 × k) × φ_J``; since
   ``ρ_J1 × k = (κ_J/L) f_J`` and ``f_J · ρ_J3 = 0``, ``v_J = -(κ_J/L) ρ_J3``. Hence ``v_J = 0``
   (Eq. 20a) if and only if ``κ_J = 0``: the point ``O_J3`` lies on the pan axis. The paper's
   "(20a) iff (21a) and (21b)" tacitly assumes ``ρ_J1 ∦ k``; each of ``ρ_J3 ∥ ρ_J1`` (Fig. 7a,
   ``O_J0, O_J2, O_J3`` aligned) and ``ρ_J3 ∥ k`` (Fig. 7b, distal link vertical) *alone* leaves
   ``B`` of full rank, and ``κ_J = 0`` is singular whatever the inclination of the distal link.
4. Eq. (20b): ``Δ_J = -(l2 l3 / L²) sin θ_J3`` vanishes for a fully extended leg (Fig. 7c) and also
   for a folded one (``θ_J3 = π``), which the paper omits.
5. Eqs. (22)-(24). ``A t = 0`` means ``σ̇_J ∥ φ_J`` for both legs with ``σ̇_I - σ̇_II =
   φ̇ k × (σ_I - σ_II)`` (Eq. 12), so ``A`` is rank-deficient if and only if
   ``det[φ_I, φ_II, k × (σ_I - σ_II)] = 0`` (:func:`singularity_factors`, ``parallel``).
   ``φ_I ∥ φ_II`` (Eq. 22) is sufficient, not necessary: e.g. two vertical distal links make
   ``A`` singular for *any* pan angles (``φ_I``, ``φ_II`` and ``k × (σ_I - σ_II)`` are all
   horizontal), and generic singular poses have ``φ_I ∦ φ_II``. Eq. (24) with parallel leg planes
   is singular at *any* common inclination of the distal links, not only "both vertical or
   horizontal"; two horizontal distal links are singular for any leg planes (``φ_J ∥ k``).

Examples
--------
>>> import numpy as np
>>> from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
>>> from screwkit.robots.families.mcgill_smg.parameters import McGillParameters
>>> smg = McGillParameters(l0=600.0, l1=100.0, l2=600.0, l3=200.0 * np.sqrt(2), radius=200.0,
...     b4=-50.0, b5=-50.0, proximal_width=80.0, distal_width=60.0)
>>> classify(inverse_kinematics(smg, [0.0, 0.0, -600.0, 0.0])).types.tolist()
'regular'
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np

from screwkit.algebra.backend import DEFAULT_RTOL
from screwkit.algebra.checks import checked_length_scale
from screwkit.core.jacobian_matrices import Jacobians, classify_jacobians
from screwkit.robots.families.mcgill_smg.configuration import McGillConfiguration
from screwkit.robots.families.mcgill_smg.kinematics import inverse_kinematics
from screwkit.robots.families.mcgill_smg.parameters import DEFAULT_MODE, McGillParameters
from screwkit.robots.two_limb import checked_mode, frozen

from .two_limb_papers import bisect_segment

__all__ = [
    "McGillSingularityFactors",
    "classify",
    "jacobians",
    "locate_direct_singularity",
    "singularity_factors",
]

_SIGN = np.array([1.0, -1.0])  # s(J), Eq. (13)


def _length(config: McGillConfiguration, length_scale: float | None) -> float:
    if length_scale is None:
        return config.params.radius
    return checked_length_scale(length_scale)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return np.asarray(np.sum(a * b, axis=-1))


class _Vectors(NamedTuple):
    k: np.ndarray  # (..., 2, 3) pan axes
    f: np.ndarray  # (..., 2, 3) f_J
    rho1: np.ndarray  # (..., 2, 3) ρ_J1 = r_J1 / L, r_J1 = a_J1 + a_J2 + a_J3 (Eqs. 6, 8a)
    rho2: np.ndarray  # ρ_J2, r_J2 = a_J2 + a_J3
    phi: np.ndarray  # φ_J = f_J × ρ_J3, r_J3 = a_J3 (Eq. 17b)
    w: np.ndarray  # (..., 3) ½ k × (σ_I - σ_II) (Eq. 12)


def _vectors(config: McGillConfiguration, length_scale: float | None) -> _Vectors:
    scale = _length(config, length_scale)
    k, f = config.pan_axis, config.tilt_axis
    rho3 = (config.wrist - config.elbow) / scale
    sigma_gap = (config.wrist[..., 0, :] - config.wrist[..., 1, :]) / scale
    return _Vectors(
        k=k,
        f=f,
        rho1=(config.wrist - config.pan_point) / scale,
        rho2=(config.wrist - config.shoulder) / scale,
        phi=np.cross(f, rho3),
        w=0.5 * np.cross(k[..., 0, :], sigma_gap),
    )


def jacobians(config: McGillConfiguration, *, length_scale: float | None = None) -> Jacobians:
    """Forward and inverse Jacobians ``A``, ``B`` of Eqs. (16)-(19): ``A t = B θ̇``.

    ``t = (φ̇, ṗ/L)`` (Eq. 17b, ``σ = p/L``, Eq. 14), ``θ̇ = (θ̇_I1, θ̇_I2, θ̇_II1, θ̇_II2)``
    (Eq. 19), ``A = [A_I; A_II]`` with ``A_J = [½ s(J) Φ_J (k × (σ_I - σ_II)), Φ_J]`` (3×4, not the
    printed 3×2) and ``B = diag(B_I, B_II)`` with ``B_J = [v_J, Δ_J f_J]`` (3×2, not the printed
    2×4); ``v_J``, ``Δ_J`` from Eqs. (10)-(11). Computed from the joint axes of ``config``, so they
    follow any rigid motion applied to it.

    Parameters
    ----------
    config : McGillConfiguration
    length_scale : float, optional
        The characteristic length ``L`` of Eq. (8), "as yet to be determined" in the paper. Default:
        ``R``, which makes ``‖½ k × (σ_I - σ_II)‖ = 1``.

    Returns
    -------
    Jacobians
        ``A`` and ``B``, each of shape (..., 6, 4), dimensionless.

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> jac = jacobians(inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0]))
    >>> jac.A.shape, jac.B.shape, int(np.linalg.matrix_rank(jac.A))
    ((6, 4), (6, 4), 4)
    """
    vec = _vectors(config, length_scale)
    phi = vec.phi
    v = _dot(phi, vec.rho1)[..., None] * vec.k - _dot(phi, vec.k)[..., None] * vec.rho1  # Eq. (10)
    delta = _dot(phi, vec.rho2)  # Eq. (11)
    rotation = _SIGN[:, None] * np.cross(phi, vec.w[..., None, :])  # ½ s(J) Φ_J (k × (σ_I - σ_II))
    phi_matrix = np.swapaxes(np.cross(phi[..., None, :], np.eye(3)), -1, -2)  # Φ_J x = φ_J × x
    a_legs = np.concatenate([rotation[..., None], phi_matrix], axis=-1)  # (..., 2, 3, 4)
    batch = config.batch_shape
    a = a_legs.reshape(*batch, 6, 4)
    b_legs = np.stack([v, delta[..., None] * vec.f], axis=-1)  # (..., 2, 3, 2)
    b = np.zeros((*batch, 6, 4))
    b[..., :3, :2] = b_legs[..., 0, :, :]
    b[..., 3:, 2:] = b_legs[..., 1, :, :]
    return Jacobians(a, b)


@dataclass(frozen=True, slots=True, eq=False)
class McGillSingularityFactors:
    """Scalar factors whose zeros are the singularities (module docstring, items 3-5).

    Attributes
    ----------
    reach : (..., 2) ndarray
        ``κ_J / L``: signed horizontal distance from the pan axis to ``O_J3``. ``v_J = -(κ_J/L)
        ρ_J3``; zero: serial singularity (``O_J3`` on the pan axis).
    delta : (..., 2) ndarray
        ``Δ_J = [f_J, ρ_J3, ρ_J2] = -(l2 l3 / L²) sin θ_J3`` (Eq. 11); zero: serial singularity
        (leg extended or folded).
    parallel : (...) ndarray
        ``det[φ_I, φ_II, ½ k × (σ_I - σ_II)]``; zero if and only if ``A`` is rank-deficient.

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> factors = singularity_factors(inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0]))
    >>> factors.reach.round(6)
    array([ 0.5, -0.5])
    """

    reach: np.ndarray
    delta: np.ndarray
    parallel: np.ndarray

    def __post_init__(self) -> None:
        for name in ("reach", "delta", "parallel"):
            object.__setattr__(self, name, frozen(getattr(self, name)))


def singularity_factors(
    config: McGillConfiguration, *, length_scale: float | None = None
) -> McGillSingularityFactors:
    """The factors of :class:`McGillSingularityFactors` (``L`` as in :func:`jacobians`).

    Parameters
    ----------
    config : McGillConfiguration
    length_scale : float, optional
        ``L`` (default ``R``).

    Returns
    -------
    McGillSingularityFactors

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> singularity_factors(inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0])).delta.shape
    (2,)
    """
    vec = _vectors(config, length_scale)
    reach = _dot(vec.rho1, np.cross(vec.k, vec.f))  # k × f_J = e(θ_J1)
    delta = _dot(vec.phi, vec.rho2)  # Eq. (11)
    parallel = np.linalg.det(np.stack([vec.phi[..., 0, :], vec.phi[..., 1, :], vec.w], axis=-2))
    return McGillSingularityFactors(reach, delta, parallel)


def classify(
    config: McGillConfiguration,
    *,
    rtol: float = DEFAULT_RTOL,
    length_scale: float | None = None,
) -> Jacobians:
    """Gosselin-Angeles type of each configuration: serial (``B``), parallel (``A``), combined.

    The closeness of each matrix is ``σ_min/σ_max`` of the dimensionless ``A`` or ``B`` of
    :func:`jacobians` (:func:`screwkit.core.jacobian_matrices.classify_jacobians`): it does not depend on the
    unit of length or on a rigid motion of the base frame. ``B``'s closeness does not depend on ``L``
    either (all its entries scale as ``1/L²``); ``A``'s does (its first column carries ``R/L``).

    Parameters
    ----------
    config : McGillConfiguration
    rtol : float, default 1e-9
        Closeness at or below which a matrix counts as rank-deficient.
    length_scale : float, optional
        ``L`` (default ``R``).

    Returns
    -------
    Jacobians
        Labels ``"inverse"`` (serial, ``B`` rank-deficient), ``"direct"`` (parallel, ``A``),
        ``"combined"`` or ``"regular"``.

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> # mode (1, 1, -1, 1): the legs are translates of each other, Eq. (24) holds
    >>> c = classify(inverse_kinematics(p, [0.0, 0.0, -600.0, 0.0], mode=(1, 1, -1, 1)))
    >>> c.types.tolist()
    'direct'
    """
    jac = jacobians(config, length_scale=length_scale)
    return classify_jacobians(jac.A, jac.B, rtol=rtol)


def locate_direct_singularity(
    params: McGillParameters,
    start: Any,
    end: Any,
    *,
    mode: Any = DEFAULT_MODE,
    length_scale: float | None = None,
) -> np.ndarray:
    """Pose where the straight path ``start → end`` crosses a parallel singularity (bisection).

    Bisection on :attr:`McGillSingularityFactors.parallel` along the segment, in one working mode.
    (Within a working mode ``κ_J`` and ``Δ_J`` keep their signs, so serial singularities are only
    met on the boundary between modes, never crossed.)

    Parameters
    ----------
    params : McGillParameters
    start, end : (..., 4) array_like
        Poses with opposite signs of the parallel factor.
    mode, length_scale
        As in :func:`inverse_kinematics` and :func:`jacobians`.

    Returns
    -------
    (..., 4) ndarray

    Examples
    --------
    >>> p = McGillParameters(600, 100, 600, 282.843, 200, -50, -50, 80, 60)
    >>> pose = locate_direct_singularity(p, [0, 0, -600, 0.2], [0, 0, -600, 1.2])
    >>> classify(inverse_kinematics(p, pose)).types.tolist()
    'direct'
    """
    checked = checked_mode(mode, "mode", 4)

    def factor(pose: np.ndarray) -> np.ndarray:
        config = inverse_kinematics(params, pose, checked)
        return singularity_factors(config, length_scale=length_scale).parallel

    return bisect_segment(factor, start, end)
