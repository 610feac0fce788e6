"""Transmission indices of four-limb Schönflies-motion generators, and the Jacobians they rest on.

Source: paper 004 (Wu, Bai, Caro, "A transmission quality index for a class of four-limb parallel
Schönflies motion generators", JMR 10(5), 2018), file ``/work/shared/papers/004_60e52c5ada55e36d.txt``;
equation and table numbers are that paper's. Every function takes a four-limb configuration
(:class:`screwkit.families.four_limb.FourLimbConfiguration`, from the family's inverse kinematics or
:meth:`screwkit.catalog.Mechanism.configuration`) of any batch shape ``...`` and returns arrays over
that batch. The configuration's ``w_i`` (unit parallelogram directions), ``h_i`` (Eq. 8), ``s_i``
(Eq. 4) and ``s`` (Tables 1-2) are the robot model; what follows is paper 004's analysis of it.

The indices
-----------
========================================  ===================================  =========  =============
quantity                                  definition                           range      singular at
========================================  ===================================  =========  =============
motion pressure angle ``μ_i`` (Eq. 11)    ``cos⁻¹|w_iᵀ(u_i × v_i)|``           [0, π/2]   π/2 (type 1)
force pressure angle ``σ`` (Eq. 13)       ``cos⁻¹(|(w_I × w_II)ᵀs| / ‖·‖)``    [0, π/2]   π/2 (type 2)
motion index ``κ`` (Eq. 15)               ``min_i |cos μ_i|``                  [0, 1]     0
force index ``ζ`` (Eq. 15)                ``|cos σ|``                          [0, 1]     0
local transmission index ``η`` (Eq. 16)   ``min(κ, ζ)``                        [0, 1]     0
========================================  ===================================  =========  =============

Larger indices are better; Sec. 5.2 calls the transmission quality good where ``η > 0.7``. The
pairing ``w_I × w_II`` is over the limbs of one sub-platform: ``w_14 × w_23`` for the articulated
platforms (Quattro, H4, V4), ``w_13 × w_24`` (and ``s = k``) for the screw pair (Veloce, Ragnar).

The Jacobians
-------------
:func:`four_limb_jacobians` gives ``A χ̇ = B θ̇`` of Eq. (6): rows ``e_i = [w_iᵀ, r w_iᵀs_i]`` of the
forward Jacobian ``A`` (Eq. 8) and ``B = diag(h_i)`` (Eq. 7b); :func:`det_A_closed_form` is ``|A|``
of Table 2 / Eq. (12). They are the paper's own quantities; screwkit's general Jacobians come from
the wrench systems (:func:`screwkit.jacobians.jacobians_from_wrenches`), and the tests check that the
two agree up to row scaling.

Where paper 004 is wrong here (numbered as in :mod:`screwkit.families.four_limb`, whose items 1-3
and 6 concern the model; each is checked in ``tests/test_families_four_limb.py``)
----------------------------------------------------------------------------------------------------
4. Table 2, Veloce, printed ``hφ/(2π) (w_13 × w_24)ᵀk``: it would make every pose with ``φ = 0``
   singular. Laplace expansion with the corrected ``s_i`` gives ``|A| = -h/(2π) (w_13 × w_24)ᵀk``.
   The Quattro/H4/V4 entry ``2r (w_14 × w_23)ᵀs`` (Eq. 12) is right, factor 2 and sign included.
5. Eq. (11) prints ``μ_i = cos⁻¹(w_iᵀ(u_i × v_i))``; in the paper's working mode (``h_i < 0``) that
   lies in (90°, 180°], yet Sec. 5.1 reports ``μ_i ∈ [0, 65°]``. The paper evidently uses the acute
   angle ``cos⁻¹|w_iᵀ(u_i × v_i)|``, which is what :func:`motion_pressure_angles` returns (``κ`` of
   Eq. 15 takes ``|cos μ_i|`` anyway). Eq. (13) likewise: as printed it gives σ = 180° at the
   spiral's ``φ = 0`` pose where Sec. 5.1 says σ = 0; :func:`force_pressure_angle` returns the
   acute angle.
7. Sec. 5.1 says the Quattro "encounters Type-2 singularity when |φ| = π/2 at the end points" of
   the spiral (Eqs. 17-18). Only approximately: ``|A|`` changes sign at ``φ = -88.3°`` and at
   ``φ = +90°`` we find σ = 88.3° (ζ = 0.03).

Examples
--------
>>> from screwkit.catalog import load_mechanism
>>> quattro = load_mechanism("quattro")
>>> indices = transmission_indices(quattro.configuration([[0, 0, -800, 0], [0, 0, -800, 1.5]]))
>>> indices.eta.shape, bool(np.all((0 <= indices.eta) & (indices.eta <= 1)))
((2,), True)
"""

from __future__ import annotations

from typing import Any, NamedTuple, Protocol, runtime_checkable

import numpy as np

from .exceptions import ScrewkitTypeError

__all__ = [
    "FourLimbGeometry",
    "FourLimbJacobians",
    "TransmissionIndices",
    "det_A_closed_form",
    "force_pressure_angle",
    "four_limb_jacobians",
    "motion_pressure_angles",
    "transmission_indices",
]


@runtime_checkable
class FourLimbGeometry(Protocol):
    """What the functions of this module read from a four-limb configuration.

    :class:`screwkit.families.four_limb.FourLimbConfiguration` has these attributes (arrays over the
    batch ``...``; limb ``i`` of paper 004 at index ``i - 1``).

    Attributes
    ----------
    params : FourLimbParameters
        ``platform_radius`` (``r``), ``arm_length`` (``b``), ``platform_kind``, ``lead`` (``h``).
    w, s : numpy.ndarray, shape (..., 4, 3)
        Unit parallelogram directions ``w_i`` and ``s_i`` of Eq. (4).
    h : numpy.ndarray, shape (..., 4)
        ``h_i = b w_i·(u_i × v_i)`` (Eq. 8).
    platform_s : numpy.ndarray, shape (..., 3)
        The unit vector ``s`` of Tables 1-2.
    subplatform_limbs : tuple of two pairs of int
        0-based limbs carried by sub-platforms I and II.
    """

    params: Any
    w: np.ndarray
    s: np.ndarray
    h: np.ndarray
    platform_s: np.ndarray
    subplatform_limbs: tuple[tuple[int, int], tuple[int, int]]


def _require_configuration(config: Any) -> None:
    if not isinstance(config, FourLimbGeometry):
        raise ScrewkitTypeError(
            f"Expected `config` to be a FourLimbConfiguration, got {type(config).__name__}."
        )


class FourLimbJacobians(NamedTuple):
    """Forward and inverse Jacobians of Eq. (6), ``A χ̇ = B θ̇``, each (..., 4, 4).

    Attributes
    ----------
    A : numpy.ndarray, shape (..., 4, 4)
        Rows ``e_i = [w_i, r w_i·s_i]`` (Eq. 8).
    B : numpy.ndarray, shape (..., 4, 4)
        ``diag(h_i)`` (Eq. 7b).
    """

    A: np.ndarray
    B: np.ndarray


class TransmissionIndices(NamedTuple):
    """Motion index ``κ``, force index ``ζ`` (Eq. 15) and LTI ``η = min(κ, ζ)`` (Eq. 16).

    Attributes
    ----------
    kappa, zeta, eta : numpy.ndarray
        Each of the pose batch's shape, in [0, 1].
    """

    kappa: np.ndarray
    zeta: np.ndarray
    eta: np.ndarray


def four_limb_jacobians(config: FourLimbGeometry) -> FourLimbJacobians:
    """Forward Jacobian ``A`` (rows ``e_i = [w_iᵀ, r w_iᵀs_i]``) and ``B = diag(h_i)``, Eqs. (6)-(8).

    Columns of ``A`` are ordered ``(x, y, z, φ)``; the last column has the unit of length.

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([0, 0, -700, 0])
    >>> A, B = four_limb_jacobians(cfg)
    >>> A.shape, bool(np.allclose(np.diag(B), cfg.h))
    ((4, 4), True)
    """
    _require_configuration(config)
    rotation_column = config.params.platform_radius * np.sum(config.w * config.s, axis=-1)
    forward = np.concatenate([config.w, rotation_column[..., None]], axis=-1)
    inverse = config.h[..., None] * np.eye(4)
    return FourLimbJacobians(forward, inverse)


def _paired_normals(config: FourLimbGeometry) -> np.ndarray:
    """``w_I × w_II`` with ``w_I = w_i × w_j`` over the limbs of sub-platform I (Eq. 12, Table 2)."""
    (i1, i2), (j1, j2) = config.subplatform_limbs
    w = config.w
    return np.cross(np.cross(w[..., i1, :], w[..., i2, :]), np.cross(w[..., j1, :], w[..., j2, :]))


def det_A_closed_form(config: FourLimbGeometry) -> np.ndarray:
    """``|A|`` of Table 2 / Eq. (12) (paper 004), corrected for the Veloce platform.

    * articulated platforms: ``|A| = 2r (w_14 × w_23)ᵀ s`` (Eq. 12; verified, factor and sign);
    * screw pair: ``|A| = -h/(2π) (w_13 × w_24)ᵀ k`` (Table 2 prints ``hφ/(2π)(...)`` with no minus
      sign; Laplace expansion of ``A`` with ``r s_i = mod(i, 2) h/(2π) k`` gives this form).

    Returns
    -------
    (...,) ndarray
        In units of length (like ``np.linalg.det`` of ``A``).

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([30, 10, -700, 0.2])
    >>> bool(np.isclose(det_A_closed_form(cfg), np.linalg.det(four_limb_jacobians(cfg).A)))
    True
    """
    _require_configuration(config)
    normals = _paired_normals(config)
    params = config.params
    if params.platform_kind == "screw_pair":
        assert params.lead is not None
        return -params.lead / (2.0 * np.pi) * normals[..., 2]
    return 2.0 * params.platform_radius * np.sum(normals * config.platform_s, axis=-1)


def motion_pressure_angles(config: FourLimbGeometry) -> np.ndarray:
    """Pressure angles ``μ_i`` between ``u_i × v_i`` and ``w_i``, Eq. (11), as acute angles.

    ``μ_i = cos⁻¹|w_iᵀ(u_i × v_i)| = cos⁻¹(|h_i| / b)`` in ``[0, π/2]``; ``μ_i = π/2`` is a type-1
    (serial) singularity. Eq. (11) as printed has no absolute value, which in the paper's working
    mode ``h_i < 0`` would put ``μ_i`` above 90°, against the paper's own range [0, 65°] (Sec. 5.1).

    Returns
    -------
    (..., 4) ndarray, radians

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([0, 0, -700, 0])
    >>> bool(np.all((0 <= motion_pressure_angles(cfg)) & (motion_pressure_angles(cfg) <= np.pi / 2)))
    True
    """
    _require_configuration(config)
    return np.arccos(np.clip(np.abs(config.h) / config.params.arm_length, 0.0, 1.0))


def force_pressure_angle(config: FourLimbGeometry) -> np.ndarray:
    """Pressure angle ``σ`` among limbs, Eq. (13) (paper 004), as an acute angle.

    ``cos σ = |(w_I × w_II)ᵀ s| / ‖w_I × w_II‖`` with ``w_I × w_II = w_14 × w_23`` (articulated) or
    ``w_13 × w_24`` (screw pair, ``s = k``), the pairing of Table 2 ("by the same token" in Sec.
    4.1). ``σ = π/2`` is a type-2 singularity (``|A| = 0``); it is also returned where
    ``w_I × w_II = 0`` exactly, where ``|A| = 0`` and Eq. (13) is undefined.

    Returns
    -------
    (...,) ndarray, radians

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([0, 0, -700, 0])
    >>> float(np.degrees(force_pressure_angle(cfg))) < 90
    True
    """
    _require_configuration(config)
    normals = _paired_normals(config)
    length = np.linalg.norm(normals, axis=-1)
    projection = np.abs(np.sum(normals * config.platform_s, axis=-1))
    cosine = np.divide(projection, length, out=np.zeros_like(length), where=length > 0)
    return np.arccos(np.clip(cosine, 0.0, 1.0))


def transmission_indices(config: FourLimbGeometry) -> TransmissionIndices:
    """``κ = min_i |cos μ_i|``, ``ζ = |cos σ|`` (Eq. 15) and the LTI ``η = min(κ, ζ)`` (Eq. 16).

    Each lies in ``[0, 1]``; larger is better, 0 is a singularity.

    Examples
    --------
    >>> from screwkit.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([[0, 0, -700, 0], [0, 0, -700, 1.0]])
    >>> ti = transmission_indices(cfg)
    >>> ti.eta.shape, bool(np.all(ti.eta == np.minimum(ti.kappa, ti.zeta)))
    ((2,), True)
    """
    _require_configuration(config)
    kappa = np.min(np.cos(motion_pressure_angles(config)), axis=-1)
    zeta = np.cos(force_pressure_angle(config))
    return TransmissionIndices(kappa, zeta, np.minimum(kappa, zeta))
