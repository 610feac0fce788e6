"""Transmission indices: paper 004's for the four-limb robots, and one for any mechanism.

What is here, along the data flow:

* paper 004's pressure angles and indices of a four-limb configuration (:func:`motion_pressure_angles`,
  :func:`force_pressure_angle`, :func:`transmission_indices`, the Jacobians of Eq. 6), below;
* :func:`transmission`: the same ``κ`` (input), ``ζ`` (output) and LTI ``η`` for a batch of poses
  of a catalog mechanism (or ``mechanism.at(poses)``), inverse kinematics included, through one fused
  compiled kernel when numba is installed (:mod:`screwkit.papers._lti_numba`; the numpy path is the
  tested fallback, ``SCREWKIT_NUMBA=0`` forces it): the entry point for maps;
* :func:`index_extremes` over a :class:`Region` (grid and local refinement) and :func:`table_4`,
  paper 004's Table 4 regenerated with the paper's values beside ours (``screwkit table4``);
* :func:`actuation_singularity_surface`: the actuation singularity locus ``|A| = 0`` at one rotation
  as a triangulated surface (paper 004's Figs. 14-16; drawn by
  :func:`screwkit.interface.plot.plot_singularity_surfaces`);
* :func:`transmission_ratio` and :func:`wrench_transmission`: input and output transmission per
  actuated joint from the actuation wrenches and the platform twists (Wang, Wu & Liu 2010; range
  [0, 1]), for any family or twist graph; ``posed.wrench_transmission`` and the report use it.

Source: paper 004 (Wu, Bai, Caro, "A transmission quality index for a class of four-limb parallel
Schönflies motion generators", JMR 10(5), 2018), file ``/work/shared/papers/004_60e52c5ada55e36d.txt``;
equation and table numbers are that paper's. Its functions here take a four-limb configuration
(:class:`screwkit.robots.families.four_limb.configuration.FourLimbConfiguration`, from the family's
inverse kinematics or :meth:`screwkit.robots.mechanism.Mechanism.configuration`) of any batch shape
``...`` and returns arrays over that batch. The configuration's ``w_i`` (unit parallelogram
directions), ``h_i`` (Eq. 8), ``s_i`` (Eq. 4) and ``s`` (Tables 1-2) are the robot model; what
follows is paper 004's analysis of it.

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
the wrench systems (:func:`screwkit.core.jacobians.jacobians_from_wrenches`), and the tests check that the
two agree up to row scaling.

Where paper 004 is wrong here (numbered as in :mod:`screwkit.robots.families.four_limb`, whose items 1-3
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
>>> from screwkit.robots.catalog import load_mechanism
>>> quattro = load_mechanism("quattro")
>>> indices = transmission_indices(quattro.configuration([[0, 0, -800, 0], [0, 0, -800, 1.5]]))
>>> indices.eta.shape, bool(np.all((0 <= indices.eta) & (indices.eta <= 1)))
((2,), True)
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable
from dataclasses import dataclass
from types import ModuleType
from typing import Any, NamedTuple, Protocol, runtime_checkable

import numpy as np

from ..algebra import backend as B
from ..algebra.compiled import COMPILED_MIN_BATCH, compiled_kernels
from ..exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError

__all__ = [
    "INDEX_NAMES",
    "TABLE_4",
    "FourLimbGeometry",
    "FourLimbJacobians",
    "IndexExtremes",
    "Region",
    "SingularSurface",
    "Table4Row",
    "TransmissionIndices",
    "WrenchTransmission",
    "actuation_singularity_surface",
    "det_A_closed_form",
    "force_pressure_angle",
    "four_limb_jacobians",
    "index_extremes",
    "motion_pressure_angles",
    "table_4",
    "transmission",
    "transmission_indices",
    "transmission_ratio",
    "wrench_transmission",
]


@runtime_checkable
class FourLimbGeometry(Protocol):
    """What the functions of this module read from a four-limb configuration.

    :class:`screwkit.robots.families.four_limb.configuration.FourLimbConfiguration` has these attributes
    (arrays over the batch ``...``; limb ``i`` of paper 004 at index ``i - 1``).

    Attributes
    ----------
    params : FourLimbParameters
        ``platform_radius`` (``r``), ``arm_length`` (``b``), ``platform_kind``, ``lead`` (``h``).
    b : numpy.ndarray, shape (..., 4, 3)
        The elbows ``B_i`` (Eq. 2).
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
    b: np.ndarray
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

    Also readable as ``input`` (``κ``, the input or motion transmission), ``output`` (``ζ``, the
    output or force transmission) and ``lti`` (``η``).

    Attributes
    ----------
    kappa, zeta, eta : numpy.ndarray
        Each of the pose batch's shape, in [0, 1]; NaN only where :func:`transmission` was asked
        (``unreachable="nan"``) to mark a pose out of reach.
    """

    kappa: np.ndarray
    zeta: np.ndarray
    eta: np.ndarray

    @property
    def reachable(self) -> np.ndarray:
        """False where the pose was out of reach (the indices are NaN there, by request)."""
        return ~np.isnan(np.asarray(self.eta, dtype=float))

    @property
    def input(self) -> np.ndarray:
        """``κ = min_i |cos μ_i|`` (Eq. 15), the input (motion) transmission, in [0, 1]."""
        return self.kappa

    @property
    def output(self) -> np.ndarray:
        """``ζ = |cos σ|`` (Eq. 15), the output (force) transmission, in [0, 1]."""
        return self.zeta

    @property
    def lti(self) -> np.ndarray:
        """``η = min(κ, ζ)`` (Eq. 16), the local transmission index, in [0, 1]."""
        return self.eta

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready: ``input``, ``output``, ``lti`` (nested lists; NaN as None), ``reachable``."""

        def plain(values: np.ndarray) -> Any:
            array = np.asarray(values, dtype=float)
            return (None if math.isnan(array) else float(array)) if array.ndim == 0 else [
                plain(item) for item in array
            ]

        return {"input": plain(self.kappa), "output": plain(self.zeta), "lti": plain(self.eta),
                "reachable": self.reachable.tolist()}


def four_limb_jacobians(config: FourLimbGeometry) -> FourLimbJacobians:
    """Forward Jacobian ``A`` (rows ``e_i = [w_iᵀ, r w_iᵀs_i]``) and ``B = diag(h_i)``, Eqs. (6)-(8).

    Columns of ``A`` are ordered ``(x, y, z, φ)``; the last column has the unit of length.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
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
    >>> from screwkit.robots.catalog import load_mechanism
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
    >>> from screwkit.robots.catalog import load_mechanism
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
    >>> from screwkit.robots.catalog import load_mechanism
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
    >>> from screwkit.robots.catalog import load_mechanism
    >>> cfg = load_mechanism("h4").configuration([[0, 0, -700, 0], [0, 0, -700, 1.0]])
    >>> ti = transmission_indices(cfg)
    >>> ti.eta.shape, bool(np.all(ti.eta == np.minimum(ti.kappa, ti.zeta)))
    ((2,), True)
    """
    _require_configuration(config)
    kappa = np.min(np.cos(motion_pressure_angles(config)), axis=-1)
    zeta = np.cos(force_pressure_angle(config))
    return TransmissionIndices(kappa, zeta, np.minimum(kappa, zeta))


# --------------------------------------------------------------------------------------------------
# Paper 004's indices for a batch of poses of a catalog mechanism (fused kernel or numpy)
# --------------------------------------------------------------------------------------------------

#: The index names :func:`index_extremes` accepts: paper 004's ``lti`` (η, Eq. 16), ``input``
#: (κ) and ``output`` (ζ) of Eq. (15).
INDEX_NAMES = ("lti", "input", "output")

_UNREACHABLE = ("raise", "nan")


def _numba_kernels(poses: int) -> ModuleType | None:
    """The fused kernel module for a call over ``poses`` poses, or None for the numpy path
    (:func:`screwkit.algebra.compiled.compiled_kernels`: the same rule as the rank kernels)."""
    return compiled_kernels("screwkit.papers._lti_numba", poses)


def backend() -> str:
    """``"numba"`` or ``"numpy"``: how :func:`transmission` computes batches of
    :data:`screwkit.algebra.compiled.COMPILED_MIN_BATCH` poses or more in this process.

    Examples
    --------
    >>> backend() in {"numba", "numpy"}
    True
    """
    return "numpy" if _numba_kernels(COMPILED_MIN_BATCH) is None else "numba"


def _four_limb_parameters(mechanism: Any) -> Any:
    if isinstance(mechanism, str):  # a catalog name, as sk.analyze takes: say how to get the mechanism
        raise ScrewkitTypeError(
            f"Expected `mechanism` to be a catalog Mechanism, got the string {mechanism!r}; load it "
            f"first: sk.load_mechanism({mechanism!r})."
        )
    params = getattr(mechanism, "parameters", None)
    if not _is_four_limb(params):
        raise ScrewkitValueError(
            "Paper 004's transmission indices (kappa, zeta, LTI) are defined for the four-limb family "
            f"(Quattro, H4, V4, Veloce, Ragnar), got "
            f"{getattr(mechanism, 'name', type(mechanism).__name__)!r} "
            f"of family {getattr(mechanism, 'family', None)!r}; use wrench_transmission(posed.jacobians) "
            "(posed.wrench_transmission) for any mechanism."
        )
    return params


def _kernel_arguments(params: Any, mode: tuple[int, ...]) -> tuple[Any, ...]:
    """The packed geometry of :func:`screwkit.papers._lti_numba.transmission`, in units of ``l``.

    Per limb (sub-platform I's limbs first, then II's: ``ζ`` pairs them in that order) ``c_i - a_i``
    minus the position, as a constant plus multiples of ``cos φ``, ``sin φ`` and ``φ`` (Table 1 as
    corrected in :mod:`screwkit.robots.families.four_limb`); then ``F_i j``, ``F_i k`` and ``m_i``.
    """
    from ..robots.families.four_limb import configuration as FL

    base = FL.base_frames(params)
    rod = float(params.rod_length)
    constant, along_cos, along_sin, along_phi = (np.zeros((4, 3)) for _ in range(4))
    cosine_s, sine_s, fixed_s = np.zeros(3), np.zeros(3), np.zeros(3)
    if params.platform_kind == "screw_pair":  # c_i = r R_z(γ_i) i + mod(i, 2) h φ/(2π) k + p
        radial = np.stack([np.cos(FL.ETA), np.sin(FL.ETA), np.zeros(4)], axis=-1)
        constant[:] = params.platform_radius * radial
        along_phi[:, 2] = FL.ODD_LIMB * params.lead / (2.0 * np.pi)
        fixed_s[2] = 1.0  # s = k
    else:  # c_i = sgn(cos η_i) r e(φ) + sgn(sin η_i) c j + p
        constant[:, 1] = FL.SGN_SIN_ETA * params.platform_offset
        radius = (FL.SGN_COS_ETA * params.platform_radius)[:, None]
        if params.platform_kind == "articulated_z":  # e = R_z(φ) i, s = R_z(φ) j
            along_cos[:], along_sin[:] = radius * [1.0, 0.0, 0.0], radius * [0.0, 1.0, 0.0]
            cosine_s[1], sine_s[0] = 1.0, -1.0
        else:  # e = R_y(φ) i, s = -R_y(φ) k (four_limb item 3)
            along_cos[:], along_sin[:] = radius * [1.0, 0.0, 0.0], radius * [0.0, 0.0, -1.0]
            cosine_s[2], sine_s[0] = -1.0, -1.0
    order = [limb for pair in params.subplatform_limbs for limb in pair]
    rows = np.concatenate(
        [(constant - base.a) / rod, along_cos / rod, along_sin / rod, along_phi / rod, base.j_rot, base.k_rot,
         np.array(mode, dtype=float)[:, None]],
        axis=1,
    )[order]
    limbs = tuple(tuple(float(v) for v in row) for row in rows)
    platform = tuple(float(v) for v in np.concatenate([cosine_s, sine_s, fixed_s]))
    arm = float(params.arm_length) / rod
    return limbs, platform, arm, arm * arm - 1.0, 1.0 / rod


def _transmission_numpy(params: Any, poses: np.ndarray, mode: tuple[int, ...]) -> tuple[np.ndarray, ...]:
    """κ, ζ, reachable over a flat batch ``(n, 4)``: the family's IK, then :func:`transmission_indices`."""
    from ..robots.families.four_limb.kinematics import inverse_kinematics, reachable

    ok = reachable(params, poses)
    kappa, zeta = np.zeros(len(poses)), np.zeros(len(poses))
    if ok.any():
        config: Any = inverse_kinematics(params, poses[ok], working_mode=mode)
        result = transmission_indices(config)
        kappa[ok], zeta[ok] = result.kappa, result.zeta
    return kappa, zeta, ok


def transmission(
    mechanism_or_posed: Any,
    poses: Any = None,
    *,
    working_mode: Any = None,
    unreachable: str = "raise",
) -> TransmissionIndices:
    """Paper 004's ``κ`` (input), ``ζ`` (output) and LTI ``η`` (Eqs. 15-16) over a batch of poses.

    The batched entry point for maps (workspace grids, trajectories): inverse kinematics (Eq. 3) and
    the indices in one pass. With numba (the ``fast`` extra) one fused compiled loop
    (:mod:`screwkit.papers._lti_numba`) for batches of :data:`screwkit.algebra.compiled.COMPILED_MIN_BATCH`
    poses or more (or once it is loaded), else the numpy path
    (:func:`screwkit.robots.families.four_limb.kinematics.inverse_kinematics` then
    :func:`transmission_indices`; a single pose never loads numba);
    ``SCREWKIT_NUMBA=0`` forces numpy. The two agree to round-off (``tests/test_indices.py``).

    Parameters
    ----------
    mechanism_or_posed : Mechanism or PosedMechanism
        A four-limb catalog mechanism (``load_mechanism("quattro")``), or ``mechanism.at(poses)``
        (then ``poses`` must be None and its working mode is used).
    poses : array_like, shape (..., 4), optional
        ``(x, y, z, φ)`` in the mechanism's length unit and radians; default its default pose.
    working_mode : sequence of 4 int, optional
        Signs of ``h_i`` (Eq. 8); default the paper's ``(-1, -1, -1, -1)``.
    unreachable : {"raise", "nan"}
        ``"raise"``: an :class:`~screwkit.exceptions.UnreachablePoseError` naming the poses and
        limbs. ``"nan"``: the indices are NaN there (the result's ``reachable`` says where).

    Returns
    -------
    TransmissionIndices
        ``input`` (κ), ``output`` (ζ), ``lti`` (η), each of the batch shape.

    Raises
    ------
    ScrewkitValueError
        Not a four-limb mechanism, malformed poses, or an unknown ``unreachable``.
    UnreachablePoseError
        With ``unreachable="raise"``, if a pose is out of reach.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> quattro = load_mechanism("quattro")
    >>> result = transmission(quattro, [[0, 0, -800, 0], [0, 0, -2000, 0]], unreachable="nan")
    >>> result.lti.round(3).tolist(), result.reachable.tolist()
    ([0.982, nan], [True, False])
    >>> float(transmission(quattro.at([0, 0, -800, 0.5])).lti[0]) < 1
    True
    """
    from ..robots.families.four_limb.kinematics import checked_working_mode, inverse_kinematics
    from ..robots.posed import PosedMechanism

    if isinstance(mechanism_or_posed, PosedMechanism):
        if poses is not None:
            raise ScrewkitValueError(
                "Expected `poses` to be None when `mechanism_or_posed` is a PosedMechanism (it has its "
                f"poses), got {type(poses).__name__}."
            )
        mechanism, poses = mechanism_or_posed.mechanism, mechanism_or_posed.poses
        if working_mode is None:
            working_mode = mechanism_or_posed.options.get("working_mode")
    else:
        mechanism = mechanism_or_posed
    params = _four_limb_parameters(mechanism)
    if unreachable not in _UNREACHABLE:
        raise ScrewkitValueError(f"Expected `unreachable` to be one of {_UNREACHABLE}, got {unreachable!r}.")
    mode = checked_working_mode((-1, -1, -1, -1) if working_mode is None else working_mode)
    chosen = mechanism.default_pose if poses is None else poses
    mechanism.check_pose_range(chosen)
    chi = B.as_array(chosen, "poses", (4,), symbolic=False)  # a new float64 array, checked finite
    batch = chi.shape[:-1]
    flat = np.ascontiguousarray(chi.reshape(-1, 4))
    kernels = _numba_kernels(len(flat))
    if kernels is None:
        kappa, zeta, ok = _transmission_numpy(params, flat, mode)
    else:
        kappa, zeta, ok = kernels.transmission(flat, *_kernel_arguments(params, mode))
        if unreachable == "raise" and not ok.all():  # before refusing, the reference decides: at the
            # reach band's edge (a leg stretched exactly) the two roundings may differ by an ulp (with
            # "nan" such a pose stays masked, never given a wrong value, and maps keep their speed)
            again = np.flatnonzero(~ok)
            kappa[again], zeta[again], ok[again] = _transmission_numpy(params, flat[again], mode)
    eta = np.minimum(kappa, zeta)
    if not ok.all():
        if unreachable == "raise":
            inverse_kinematics(params, chi, working_mode=mode)  # raises the family's message
            raise UnreachablePoseError("A pose is out of reach.")  # pragma: no cover - unreachable
        missing = ~ok
        kappa[missing] = zeta[missing] = eta[missing] = np.nan
    return TransmissionIndices(kappa.reshape(batch), zeta.reshape(batch), eta.reshape(batch))


# --------------------------------------------------------------------------------------------------
# Regions and the extremes of an index over a region (Table 4)
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Region:
    """A region of platform positions ``(x, y, z)``: a bounding box and a membership test.

    Build one with :meth:`box`, :meth:`super_ellipsoid` or :meth:`cone_cylinder`.

    Attributes
    ----------
    name : str
    lower, upper : tuple of 3 float
        The bounding box.
    contains : callable
        ``points (..., 3) -> bool (...)``.
    """

    name: str
    lower: tuple[float, float, float]
    upper: tuple[float, float, float]
    contains: Callable[[np.ndarray], np.ndarray]

    @classmethod
    def box(cls, x: tuple[float, float], y: tuple[float, float], z: tuple[float, float]) -> Region:
        """The box ``x × y × z``.

        Examples
        --------
        >>> Region.box((0, 1), (0, 1), (0, 1)).contains(np.array([[0.5, 0.5, 2.0]])).tolist()
        [False]
        """
        lower, upper = (float(x[0]), float(y[0]), float(z[0])), (float(x[1]), float(y[1]), float(z[1]))

        def inside(points: np.ndarray) -> np.ndarray:
            return np.all((points >= np.array(lower) - 1e-9) & (points <= np.array(upper) + 1e-9), axis=-1)

        return cls(f"box {lower}..{upper}", lower, upper, inside)

    @classmethod
    def super_ellipsoid(
        cls, centre: tuple[float, float, float], semi_axes: tuple[float, float, float], exponent: float = 3.0
    ) -> Region:
        """``Σ |(x_k - c_k)/a_k|^e ≤ 1`` (paper 004, Eq. 19 with ``e = 3``).

        Examples
        --------
        >>> eq_19 = Region.super_ellipsoid((0, 0, -575), (505, 685, 365))
        >>> eq_19.contains(np.array([[0, 0, -575], [505, 0, -210]])).tolist()
        [True, False]
        """
        c, a = np.array(centre, dtype=float), np.array(semi_axes, dtype=float)

        def inside(points: np.ndarray) -> np.ndarray:
            return np.sum(np.abs((points - c) / a) ** exponent, axis=-1) <= 1.0 + 1e-9

        lower, upper = tuple((c - a).tolist()), tuple((c + a).tolist())
        return cls(f"super-ellipsoid |x/a|^{exponent:g} about {tuple(c.tolist())}, a = {tuple(a.tolist())}",
                   lower, upper, inside)

    @classmethod
    def cone_cylinder(cls, apex_z: float, radius: float, rim_z: float, top_z: float) -> Region:
        """About ``z``: a cone (apex ``(0, 0, apex_z)``, radius ``radius`` at ``rim_z``) below a
        cylinder of that radius up to ``top_z`` (the Table 4 workspace assumed for paper 004's
        missing Fig. 6: the cone of the spiral of Eq. 17, ``-975``, 650, ``-575``, ``-475`` mm).

        Examples
        --------
        >>> cone = Region.cone_cylinder(-975, 650, -575, -475)
        >>> cone.contains(np.array([[600, 0, -500], [600, 0, -900]])).tolist()
        [True, False]
        """

        def inside(points: np.ndarray) -> np.ndarray:
            z = points[..., 2]
            limit = np.where(z >= rim_z, radius, radius * (z - apex_z) / (rim_z - apex_z))
            within = np.hypot(points[..., 0], points[..., 1]) <= limit + 1e-9
            return within & (z >= apex_z - 1e-9) & (z <= top_z + 1e-9)

        return cls(f"cone-cylinder (apex z {apex_z:g}, radius {radius:g} from z {rim_z:g} to {top_z:g})",
                   (-radius, -radius, apex_z), (radius, radius, top_z), inside)

    def boundary(self, count: int = 16) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Points of the region's boundary on a latitude-longitude grid about the centre of its box,
        each where the ray from the centre leaves the region (bisection on :attr:`contains`; the
        region must be star-shaped about that centre, as the box, the super-ellipsoid and the
        cone-cylinder are): ``x, y, z`` of shape ``(count + 1, 2 count + 1)``, for a wireframe.

        Examples
        --------
        >>> x, y, z = Region.super_ellipsoid((0, 0, 0), (1, 2, 3), 2.0).boundary(8)
        >>> x.shape, bool(np.allclose(x**2 + (y / 2) ** 2 + (z / 3) ** 2, 1.0))
        ((9, 17), True)
        """
        centre = 0.5 * (np.array(self.lower) + np.array(self.upper))
        polar, azimuth = np.meshgrid(
            np.linspace(0.0, np.pi, count + 1), np.linspace(-np.pi, np.pi, 2 * count + 1), indexing="ij"
        )
        sine = np.sin(polar)
        directions = np.stack([sine * np.cos(azimuth), sine * np.sin(azimuth), np.cos(polar)], axis=-1)
        reach = float(np.linalg.norm(np.array(self.upper) - np.array(self.lower)))  # beyond the box
        points = _pulled_inside(self, centre, centre + reach * directions.reshape(-1, 3))
        x, y, z = points.reshape(*polar.shape, 3).transpose(2, 0, 1)
        return x, y, z


class IndexExtremes(NamedTuple):
    """The extremes of an index over a region at one rotation angle (:func:`index_extremes`).

    Attributes
    ----------
    minimum, maximum : float
    argmin, argmax : numpy.ndarray, shape (4,)
        The poses ``(x, y, z, φ)`` where they are reached.
    points : int
        Grid points inside the region or on its boundary.
    reachable_fraction : float
        The fraction of them the robot reaches (the others are skipped).
    grid_minimum, grid_maximum : float
        The extremes over the grid alone (before refinement).
    """

    minimum: float
    maximum: float
    argmin: np.ndarray
    argmax: np.ndarray
    points: int
    reachable_fraction: float
    grid_minimum: float
    grid_maximum: float


def _index_values(params: Any, index: str, poses: np.ndarray, mode: tuple[int, ...]) -> np.ndarray:
    kernels = _numba_kernels(len(poses))
    if kernels is None:
        kappa, zeta, ok = _transmission_numpy(params, poses, mode)
    else:
        kappa, zeta, ok = kernels.transmission(np.ascontiguousarray(poses), *_kernel_arguments(params, mode))
    values = {"lti": np.minimum(kappa, zeta), "input": kappa, "output": zeta}[index]
    return np.where(ok, values, np.nan)


def _pulled_inside(region: Region, fallback: np.ndarray, targets: np.ndarray) -> np.ndarray:
    """Each target outside the region moved along the segment from the region's centre (the centre
    of its box; ``fallback`` if that is outside) to the last point inside (bisection on the
    membership test), so the search can slide along a curved boundary of a star-shaped region."""
    centre = 0.5 * (np.array(region.lower) + np.array(region.upper))
    if not region.contains(centre[None])[0]:
        centre = fallback
    outside = ~region.contains(targets)
    if not outside.any():
        return targets
    low, high = np.zeros(int(outside.sum())), np.ones(int(outside.sum()))
    delta = targets[outside] - centre
    for _ in range(30):
        middle = 0.5 * (low + high)
        inside = region.contains(centre + middle[:, None] * delta)
        low, high = np.where(inside, middle, low), np.where(inside, high, middle)
    moved = targets.copy()
    moved[outside] = centre + low[:, None] * delta
    return moved


def _refined(
    params: Any, index: str, region: Region, start: np.ndarray, step: np.ndarray, sign: float,
    mode: tuple[int, ...], rounds: int,
) -> tuple[float, np.ndarray]:
    """Compass search from a grid point: the 26 neighbours (pulled back inside the region where they
    leave it), halving the step each round."""
    offsets = np.stack(np.meshgrid(*[np.array([-1.0, 0.0, 1.0])] * 3, indexing="ij"), axis=-1).reshape(-1, 3)
    best = start.copy()
    best_value = sign * float(_index_values(params, index, best[None], mode)[0])
    for _ in range(rounds):
        candidates = _pulled_inside(region, best[:3], best[:3] + offsets * step)
        poses = np.column_stack([candidates, np.full(len(candidates), best[3])])
        values = sign * _index_values(params, index, poses, mode)
        if np.any(np.isfinite(values)):
            pick = int(np.nanargmin(values))
            if values[pick] < best_value:
                best, best_value = poses[pick], float(values[pick])
                continue  # keep the step while the search moves
        step = step / 2.0
    return sign * best_value, best


#: The largest grid (points per axis, ``grid³`` poses) and number of refinement rounds a search over
#: a region takes (:func:`index_extremes`, :func:`table_4`, :func:`actuation_singularity_surface`):
#: 201³ ≈ 8·10⁶ poses and 200 rounds already take minutes; larger values are refused, not run out of
#: memory or time.
MAX_GRID = 201
MAX_REFINE = 200
#: The largest grid of :func:`actuation_singularity_surface`: its marching tetrahedra hold the whole
#: grid's cells at once (≈ 0.6 GB at 64, measured 2 GB at 100 and 16 GB at 201 on the Quattro).
MAX_SURFACE_GRID = 64


def _region_grid(
    mechanism: Any, region: Region | None, phi: Any, working_mode: Any, *, grid: Any, refine: Any = 0
) -> tuple[Region, tuple[int, int, int, int], list[np.ndarray]]:
    """The checked region (default: the mechanism's workspace box), working mode and grid axes of a
    search at one rotation ``phi`` (:func:`index_extremes`, :func:`actuation_singularity_surface`)."""
    from ..robots.families.four_limb.kinematics import checked_working_mode

    for name, value, least, most in (("grid", grid, 2, MAX_GRID), ("refine", refine, 0, MAX_REFINE)):
        if not isinstance(value, int | np.integer) or isinstance(value, bool) or not least <= value <= most:
            raise ScrewkitValueError(f"Expected `{name}` to be an integer in {least}..{most}, got {value!r}.")
    from ..robots.toml_fields import MAX_ANGLE_RADIANS

    numeric = isinstance(phi, int | float | np.integer | np.floating)
    if not numeric or not abs(float(phi)) <= MAX_ANGLE_RADIANS:
        raise ScrewkitValueError(
            f"Expected `phi` to be a finite number of at most {MAX_ANGLE_RADIANS:g} in magnitude (radians), "
            f"got {phi!r}."
        )
    if region is None:
        box = mechanism.workspace
        region = Region.box(box["x"], box["y"], box["z"])
    elif not isinstance(region, Region):
        raise ScrewkitTypeError(f"Expected `region` to be a Region, got {type(region).__name__}.")
    mode = checked_working_mode((-1, -1, -1, -1) if working_mode is None else working_mode)
    axes = [np.linspace(lo, hi, int(grid)) for lo, hi in zip(region.lower, region.upper, strict=True)]
    return region, mode, axes


def index_extremes(
    mechanism: Any,
    index: str = "lti",
    region: Region | None = None,
    *,
    phi: float = 0.0,
    grid: int = 41,
    refine: int = 12,
    working_mode: Any = None,
) -> IndexExtremes:
    """The minimum and maximum of a transmission index over a region at one rotation ``φ``.

    A ``grid``³ grid over the region's bounding box (its points outside the region moved onto the
    region's boundary; points out of reach skipped), then ``refine`` rounds of a compass search
    from the best grid points (the 26 neighbours, pulled back onto the region's boundary where they
    leave it; the step halves when no neighbour improves, and stays while the search moves).
    Paper 004 reports Table 4 ("the max-/minimum LTI within the operational workspace") without
    saying how it searched; :func:`table_4` compares.

    Parameters
    ----------
    mechanism : Mechanism
        A four-limb catalog mechanism.
    index : {"lti", "input", "output"}
        η (Eq. 16), κ or ζ (Eq. 15).
    region : Region, optional
        Default: the box of the mechanism's ``[workspace]``.
    phi : float
        Rotation of the platform, radians.
    grid : int
        Points per axis (at least 2).
    refine : int
        Rounds of local refinement (0: the grid's values).
    working_mode : sequence of 4 int, optional

    Returns
    -------
    IndexExtremes

    Raises
    ------
    ScrewkitValueError
        Unknown index, a bad grid or refine count, a non-finite ``phi``, or no reachable grid point.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> result = index_extremes(load_mechanism("quattro"), region=Region.cone_cylinder(-975, 650, -575, -475),
    ...                         grid=21, refine=0)
    >>> round(result.maximum, 3), result.points
    (1.0, 8921)
    """
    params = _four_limb_parameters(mechanism)
    if index not in INDEX_NAMES:
        raise ScrewkitValueError(f"Expected `index` to be one of {INDEX_NAMES}, got {index!r}.")
    region, mode, axes = _region_grid(mechanism, region, phi, working_mode, grid=grid, refine=refine)
    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    # the box's points outside the region, pulled onto its boundary: a boundary sampling as fine as
    # the grid (extremes often sit on the boundary, between the grid's points)
    points = np.unique(_pulled_inside(region, points[0], points).round(9), axis=0)
    poses = np.column_stack([points, np.full(len(points), float(phi))])
    values = _index_values(params, index, poses, mode)
    reached = np.isfinite(values)
    if not reached.any():
        raise ScrewkitValueError(
            f"No point of the {grid}^3 grid over {region.name} is reachable by {mechanism.name} at "
            f"phi = {math.degrees(phi):g} deg."
        )
    step = np.array([(hi - lo) / (grid - 1) for lo, hi in zip(region.lower, region.upper, strict=True)])
    low_at, high_at = int(np.nanargmin(values)), int(np.nanargmax(values))
    low, low_pose = _refined(params, index, region, poses[low_at], step / 2, 1.0, mode, refine)
    high, high_pose = _refined(params, index, region, poses[high_at], step / 2, -1.0, mode, refine)
    return IndexExtremes(low, high, low_pose, high_pose, len(points), float(reached.mean()),
                         float(values[low_at]), float(values[high_at]))


# --------------------------------------------------------------------------------------------------
# Paper 004's Table 4, regenerated
# --------------------------------------------------------------------------------------------------

#: The Table 4 workspace of the Quattro, H4, V4 and Veloce: paper 004's Fig. 6 is missing from the
#: text, so this is an assumption (the cone on which the spiral of Eq. 17 lies, capped by a
#: cylinder: the Quattro's 1300 mm x 500 mm envelope), the one the catalog's facts use.
TABLE_4_CONE = Region.cone_cylinder(-975.0, 650.0, -575.0, -475.0)
#: The Ragnar's super-ellipsoid, paper 004 Eq. (19).
TABLE_4_EQ_19 = Region.super_ellipsoid((0.0, 0.0, -575.0), (505.0, 685.0, 365.0), 3.0)

_CONE_NOTE = (
    "paper 004's workspace (Fig. 6) is missing from the text; over the assumed cone-cylinder the "
    "extreme differs, so the paper's workspace differs from it"
)
#: Why a minimum over a region that reaches beyond the robot's reach is not a converged number.
_BEYOND_REACH_NOTE = (
    "the assumed region reaches just beyond the robot's reach ({share:.3%} of the {grid}^3 grid is out "
    "of reach); near that boundary a limb is stretched and kappa -> 0 (a type-1 singularity), so the "
    "minimum over the region is 0 in the limit and our value only says how close the grid comes (a "
    "finer grid gives less); the paper's workspace (Fig. 6, missing) evidently stays inside the reach"
)
_RAGNAR_MIN_NOTE = (
    "part of Eq. (19) is out of reach with the printed b, l and A_i (e.g. (0, 0, -250): "
    "|C_1 - A_1| = 376 mm < l - b = 425 mm), so the paper's Ragnar dimensions differ; over the "
    "reachable part the minimum sits at the reach boundary (a type-1 singularity)"
)
_RAGNAR_MAX_NOTE = (
    "the axis inclination (45 deg) is inferred from this table's phi = 0 maximum (ragnar.toml); with "
    "it the phi = 360 deg maximum is not the paper's, so the real Ragnar differs in more than eps"
)


class Table4Row(NamedTuple):
    """One cell pair of paper 004's Table 4, the paper's values beside ours.

    Attributes
    ----------
    robot, mechanism : str
        The paper's row name and the catalog entry.
    phi_deg : float
    region : str
    paper_min, paper_max : float
    ours : IndexExtremes
    notes : dict of str to str
        ``"min"``/``"max"``: why ours differs from the paper's (only where it does).
    """

    robot: str
    mechanism: str
    phi_deg: float
    region: str
    paper_min: float
    paper_max: float
    ours: IndexExtremes
    notes: dict[str, str]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {
            "robot": self.robot, "mechanism": self.mechanism, "phi_deg": self.phi_deg, "region": self.region,
            "paper": {"min": self.paper_min, "max": self.paper_max},
            "ours": {"min": self.ours.minimum, "max": self.ours.maximum,
                     "argmin": self.ours.argmin.tolist(), "argmax": self.ours.argmax.tolist(),
                     "points": self.ours.points, "reachable_fraction": self.ours.reachable_fraction},
            "notes": self.notes,
        }


#: Table 4 of paper 004: (row, catalog entry, φ in degrees, region, η_min, η_max, why a min / max
#: may differ). Values as printed; the Veloce's φ = 360° column is for h = 20 mm (its catalog lead).
TABLE_4: tuple[tuple[str, str, float, str, float, float, str, str], ...] = (
    ("Quattro", "quattro", 0.0, "cone", 0.380, 1.0, _CONE_NOTE, _CONE_NOTE),
    ("Quattro", "quattro", 45.0, "cone", 0.173, 0.750, _CONE_NOTE, _CONE_NOTE),
    ("H4", "h4", 0.0, "cone", 0.031, 0.917, _CONE_NOTE, _CONE_NOTE),
    ("H4", "h4", 45.0, "cone", 0.0, 0.847, _CONE_NOTE, _CONE_NOTE),
    ("Veloce", "veloce", 0.0, "cone", 0.287, 1.0, _CONE_NOTE, _CONE_NOTE),
    ("Veloce", "veloce", 360.0, "cone", 0.268, 0.999, _CONE_NOTE, _CONE_NOTE),
    ("V4", "v4", 0.0, "cone", 0.008, 0.872, _CONE_NOTE, _CONE_NOTE),
    ("V4", "v4", 45.0, "cone", 0.0, 0.804, _CONE_NOTE, _CONE_NOTE),
    ("Ragnar", "ragnar", 0.0, "eq_19", 0.238, 0.892, _RAGNAR_MIN_NOTE, _RAGNAR_MAX_NOTE),
    ("Ragnar", "ragnar", 360.0, "eq_19", 0.175, 0.885, _RAGNAR_MIN_NOTE, _RAGNAR_MAX_NOTE),
)

#: Agreement with a Table 4 value: the paper prints 3 decimals; a 41³ grid moves the extremes by
#: up to about 1e-3 (tests/test_indices.py measures it).
TABLE_4_TOLERANCE = 0.002


def table_4(*, grid: int = 41, refine: int = 12, robots: Any = None) -> list[Table4Row]:
    """Paper 004's Table 4 regenerated: each (robot, φ) cell pair, the paper's and ours.

    Parameters
    ----------
    grid, refine : int
        As :func:`index_extremes`.
    robots : iterable of str, optional
        Catalog names to include (default all five).

    Returns
    -------
    list of Table4Row
        A note explains each value that differs from the paper's by more than
        :data:`TABLE_4_TOLERANCE`: the grid (when the paper's value lies between our grid value and
        our refined one), or the known cause (the missing workspace figure, the Ragnar's data).

    Examples
    --------
    >>> row = table_4(grid=21, refine=0, robots=["veloce"])[0]
    >>> row.robot, row.paper_max, round(row.ours.maximum, 2)
    ('Veloce', 1.0, 1.0)
    """
    from ..robots.catalog import load_mechanism

    wanted = None if robots is None else set(robots)
    regions = {"cone": TABLE_4_CONE, "eq_19": TABLE_4_EQ_19}
    rows = []
    for robot, name, phi_deg, region, low, high, low_note, high_note in TABLE_4:
        if wanted is not None and name not in wanted:
            continue
        mechanism = load_mechanism(name)
        ours = index_extremes(mechanism, "lti", regions[region], phi=math.radians(phi_deg), grid=grid,
                              refine=refine)
        notes = {}
        for key, paper, refined, on_grid, cause in (
            ("min", low, ours.minimum, ours.grid_minimum, low_note),
            ("max", high, ours.maximum, ours.grid_maximum, high_note),
        ):
            if abs(refined - paper) <= TABLE_4_TOLERANCE:
                continue
            if key == "min" and ours.reachable_fraction < 1 and cause == _CONE_NOTE:
                cause = _BEYOND_REACH_NOTE.format(share=1 - ours.reachable_fraction, grid=grid)
            low_end, high_end = min(refined, on_grid), max(refined, on_grid)
            between = low_end - TABLE_4_TOLERANCE <= paper <= high_end + TABLE_4_TOLERANCE
            notes[key] = (
                f"the extreme lies between grid points: our {grid}^3 grid gives {on_grid:.3f}, the refined "
                f"value is {refined:.3f}; the paper's {paper:.3f} lies between (a grid value: its grid is "
                "not given)" if between else cause
            )
        rows.append(Table4Row(robot, name, phi_deg, regions[region].name, low, high, ours, notes))
    return rows


# --------------------------------------------------------------------------------------------------
# Actuation singularity surfaces (paper 004, Sec. 5.3, Figs. 14-16)
# --------------------------------------------------------------------------------------------------


class SingularSurface(NamedTuple):
    """The actuation singularity locus of a four-limb robot in a region at one rotation ``φ``.

    Attributes
    ----------
    triangles : numpy.ndarray, shape (m, 3, 3)
        Vertices ``(x, y, z)`` on ``|A| = 0`` (Eq. 12, Table 2), in the robot's length unit.
    phi : float
        The rotation, radians.
    region : Region
        The region searched (the triangles whose centroids lie inside it are kept).
    robot : str
    """

    triangles: np.ndarray
    phi: float
    region: Region
    robot: str

    @property
    def area(self) -> float:
        """The surface's area (sum of its triangles'), in the robot's length unit squared."""
        edges = self.triangles[:, 1:] - self.triangles[:, :1]
        return float(0.5 * np.sum(np.linalg.norm(np.cross(edges[:, 0], edges[:, 1]), axis=-1)))


def actuation_singularity_surface(
    mechanism: Any,
    phi: float,
    region: Region | None = None,
    *,
    grid: int = 32,
    working_mode: Any = None,
) -> SingularSurface:
    """Paper 004's actuation singularity locus at a rotation ``φ`` as a surface (Sec. 5.3, Figs. 14-16).

    The paper draws the poses where ``ζ = |cos σ| ≤ ε`` (Eq. 15, ``ε = 0.001``) at a fixed ``φ``
    inside the operational workspace. Here: the zero set of ``|A|`` (Eq. 12 / Table 2,
    :func:`det_A_closed_form`), where ``ζ = 0`` (``|A| = 2r |w_I × w_II| cos σ`` for the articulated
    platforms, ``-h/(2π) |w_I × w_II| cos σ`` for the screw pair) or ``w_I × w_II = 0``. ``|A|``
    is sampled on a ``grid``³ grid over the region's box (the family's inverse kinematics; poses out
    of reach left out), its zero set triangulated by marching tetrahedra and every vertex moved onto
    it by bisection along its grid edge (:mod:`screwkit.analysis._isosurface`); the triangles whose centroid
    lies in the region are kept, so the surface's edge follows the region's boundary to within a
    grid cell. A thin sheet between two grid points of equal sign is missed: refine ``grid``.

    Parameters
    ----------
    mechanism : Mechanism
        A four-limb catalog mechanism.
    phi : float
        The rotation of the platform, radians.
    region : Region, optional
        Default: the box of the mechanism's ``[workspace]``.
    grid : int
        Grid points per axis (at least 2).
    working_mode : sequence of 4 int, optional
        Signs of ``h_i`` (Eq. 8); default the paper's ``(-1, -1, -1, -1)``.

    Returns
    -------
    SingularSurface

    Raises
    ------
    ScrewkitValueError
        Not a four-limb mechanism, a non-finite ``phi``, ``grid`` below 2.
    ScrewkitTypeError
        ``region`` is not a Region.

    Examples
    --------
    The Quattro has no actuation singularity in its (assumed) workspace at ``φ = 0`` (Table 4's
    ``η_min = 0.380``); at ``φ = 90°`` it has (Sec. 5.1, Fig. 14b):

    >>> from screwkit.robots.catalog import load_mechanism
    >>> quattro = load_mechanism("quattro")
    >>> len(actuation_singularity_surface(quattro, 0.0, TABLE_4_CONE, grid=12).triangles)
    0
    >>> actuation_singularity_surface(quattro, np.pi / 2, TABLE_4_CONE, grid=12).area > 0
    True
    """
    from ..robots.families.four_limb.kinematics import inverse_kinematics, reachable
    from ._isosurface import zero_surface

    params = _four_limb_parameters(mechanism)
    if isinstance(grid, int | np.integer) and not isinstance(grid, bool) and grid > MAX_SURFACE_GRID:
        raise ScrewkitValueError(
            f"Expected `grid` to be an integer in 2..{MAX_SURFACE_GRID} for a surface, got {grid!r}."
        )
    region, mode, axes = _region_grid(mechanism, region, phi, working_mode, grid=grid)
    angle = float(phi)

    def det_a(points: np.ndarray) -> np.ndarray:
        poses = np.column_stack([points, np.full(len(points), angle)])
        ok = reachable(params, poses)
        values = np.full(len(points), np.nan)
        if ok.any():
            config: Any = inverse_kinematics(params, poses[ok], working_mode=mode)
            values[ok] = det_A_closed_form(config)
        return values

    points = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, 3)
    triangles = zero_surface(axes, det_a(points).reshape((int(grid),) * 3), det_a)
    inside = region.contains(triangles.mean(axis=1)) if len(triangles) else np.zeros(0, dtype=bool)
    return SingularSurface(triangles[inside], angle, region, mechanism.name)


# --------------------------------------------------------------------------------------------------
# A transmission index for any mechanism, from the actuation wrenches and the platform twists
# --------------------------------------------------------------------------------------------------


def transmission_ratio(
    wrench: Any, twist: Any, *, point: Any = None, length_scale: float = 1.0, rtol: float = B.DEFAULT_RTOL
) -> np.ndarray:
    """``|W ∘ T| / max``: the virtual coefficient of a wrench and a twist over its largest value.

    Two bounds, both from the reciprocal product ``W ∘ T = f·(v(q) + h ω)`` of a wrench
    ``W = (f; q × f + h f)`` (pitch ``h``, through ``q``) and a twist ``T = (ω; v_0)`` whose point
    ``q`` moves at ``v(q) = v_0 + ω × q``:

    * ``point`` given (the point of application ``q``: on the wrench's axis, or off it by what the
      wrench is defined up to, e.g. a limb's constraint wrenches, which do no work on the twist):
      the maximum over the directions of a force of the same size at ``q``, ``|f| |v(q) + h ω|``, so
      the ratio is the cosine of the pressure angle between the force and the velocity of its point
      of application (Wang, Wu & Liu, Mech. Mach. Theory 45(10), 2010, paper 004's ref. [38]; with
      ``q = B_i`` it is paper 004's ``|cos μ_i|``, Eq. 11);
    * ``point=None``: the maximum over the angle ``θ`` of the two axes at fixed distance ``d`` and
      pitches, ``|f| |ω| √((h_W + h_T)² + d²)``, from ``$_1 ∘ $_2 = (h_1 + h_2) cos θ - d sin θ``
      for unit screws (Chen & Angeles, "Generalized transmission index and transmission quality for
      spatial linkages", Mech. Mach. Theory 42(9), 2007). It needs no point but is 1 for any force
      normal to a rotation axis (planar linkages) except through it: give points there.

    A pure couple ``m`` against a twist: ``|m·ω| / (|m| |ω|)``; a force against a translation
    ``v``: ``|f·v| / (|f| |v|)``; a couple against a translation cannot act (ratio 0). Range [0, 1],
    invariant under rigid motions and changes of the length unit; 0 where the wrench does no work.

    Parameters
    ----------
    wrench, twist : array_like, shape (..., 6)
        Conventions of :mod:`screwkit.algebra.screw`.
    point : array_like, shape (..., 3), optional
        The wrench's point of application.
    length_scale : float
        Used only to decide which screws are couples or translations (relative to ``rtol``).
    rtol : float

    Returns
    -------
    numpy.ndarray, shape (...)

    Examples
    --------
    A unit force through ``(1, 0, 0)`` against a unit rotation about ``z`` through the origin: along
    ``y`` it pushes its point straight along its velocity (1); along ``(0, 1, 1)/√2`` at 45 degrees
    to it; along ``x`` not at all.

    >>> from screwkit.algebra import screw as S
    >>> spin = S.revolute_twist([0, 0, 1], [0, 0, 0])
    >>> forces = [S.force(f, [1, 0, 0]) for f in ([0, 1, 0], [0, 1, 1], [1, 0, 0])]
    >>> [round(float(transmission_ratio(f, spin, point=[1, 0, 0])), 6) for f in forces]
    [1.0, 0.707107, 0.0]
    """
    w = B.as_array(wrench, "wrench", (6,), symbolic=False).astype(float)
    t = B.as_array(twist, "twist", (6,), symbolic=False).astype(float)
    w, t = np.broadcast_arrays(w, t)
    f, m, omega, v = w[..., :3], w[..., 3:], t[..., :3], t[..., 3:]
    product = np.abs(np.sum(f * v, axis=-1) + np.sum(m * omega, axis=-1))
    nf, nm = np.linalg.norm(f, axis=-1), np.linalg.norm(m, axis=-1)
    nw, nv = np.linalg.norm(omega, axis=-1), np.linalg.norm(v, axis=-1)
    finite_wrench = nf > rtol * nm / length_scale
    finite_twist = nw > rtol * nv / length_scale
    safe_f, safe_w = np.where(finite_wrench, nf, 1.0), np.where(finite_twist, nw, 1.0)
    wrench_pitch = np.sum(f * m, axis=-1) / safe_f**2
    if point is not None:
        q = B.as_array(point, "point", (3,), symbolic=False).astype(float)
        moving = v + np.cross(omega, q) + wrench_pitch[..., None] * omega
        force_bound = nf * np.linalg.norm(moving, axis=-1)
    else:
        pitch_sum = wrench_pitch + np.sum(omega * v, axis=-1) / safe_w**2
        offset = np.cross(omega, v) / safe_w[..., None] ** 2 - np.cross(f, m) / safe_f[..., None] ** 2
        normal = np.cross(f / safe_f[..., None], omega / safe_w[..., None])
        sine = np.linalg.norm(normal, axis=-1)
        skew = np.abs(np.sum(offset * normal, axis=-1)) / np.where(sine > 1e-12, sine, 1.0)
        parallel = np.linalg.norm(np.cross(offset, f / safe_f[..., None]), axis=-1)
        force_bound = nf * nw * np.hypot(pitch_sum, np.where(sine > 1e-12, skew, parallel))
    bound = np.select(
        [finite_wrench & finite_twist, finite_wrench, finite_twist],
        [force_bound, nf * nv, nm * nw],
        default=0.0,
    )
    ratio = np.divide(product, bound, out=np.zeros_like(product), where=bound > 0)
    return np.minimum(ratio, 1.0)


def _driven_link_points(
    jacobians: Any, wrenches: np.ndarray, *, output: bool = False
) -> tuple[np.ndarray, np.ndarray]:
    """Per limb, where the actuation wrench acts on the link the actuator drives (``output``: on the
    platform): the point of the wrench's line nearest (least squares) to the zero-pitch axes of that
    link's other joints in the limb (a spherical joint's three axes meet at its centre; a
    revolute's axis crosses the line), shape ``(..., n, 3)``, and whether one was found ``(..., n)``
    (no such axis, or all parallel to the line: the common-normal bound is used)."""
    analysis = jacobians.analysis
    table = analysis.table
    specs = {spec.name: spec for spec in table.specs}
    offsets = dict(zip(specs, np.cumsum([0] + [spec.dof for spec in table.specs[:-1]]).tolist(), strict=True))
    screws = np.asarray(table.screws, dtype=float)
    points = np.zeros((*wrenches.shape[:-1], 3))
    found = np.zeros(wrenches.shape[:-1], dtype=bool)
    for k, plan in enumerate(analysis.topology.limbs):
        actuated = specs[plan.actuated_joint]
        driven = actuated.parent if actuated.child == table.base else actuated.child
        if output:
            driven = table.platform
        rows = [
            offsets[name] + r
            for name in plan.joints
            if name != plan.actuated_joint and driven in (specs[name].parent, specs[name].child)
            for r in range(specs[name].dof)
        ]
        lines = screws[..., rows, :]  # (..., k, 6)
        s, s0 = lines[..., :3], lines[..., 3:]
        size = np.linalg.norm(s, axis=-1)
        pitch_part = np.abs(np.sum(s * s0, axis=-1))
        usable = (size > 0) & (pitch_part <= 1e-9 * size * np.linalg.norm(lines, axis=-1))
        safe = np.where(size > 0, size, 1.0)[..., None]
        unit, anchor = s / safe, np.cross(s, s0) / safe**2
        f, m = wrenches[..., k, :3], wrenches[..., k, 3:]
        nf = np.linalg.norm(f, axis=-1)[..., None]
        direction = f / np.where(nf > 0, nf, 1.0)
        foot = np.cross(f, m) / np.where(nf > 0, nf, 1.0) ** 2
        # x = foot + t d minimises sum_k |(x - r_k) x s_k|^2: t = sum d.M_k(r_k - foot) / sum d.M_k d
        along = np.sum(direction[..., None, :] * unit, axis=-1)  # d.s_k
        weight = np.where(usable, 1.0, 0.0)
        offset = anchor - foot[..., None, :]
        numerator = np.sum(weight * (np.sum(direction[..., None, :] * offset, axis=-1)
                                     - along * np.sum(unit * offset, axis=-1)), axis=-1)
        denominator = np.sum(weight * (1.0 - along**2), axis=-1)
        ok = (denominator > 1e-9) & (nf[..., 0] > 0)
        t = np.divide(numerator, denominator, out=np.zeros_like(numerator), where=ok)
        points[..., k, :] = foot + t[..., None] * direction
        found[..., k] = ok
    return points, found


class WrenchTransmission(NamedTuple):
    """Input and output transmission per actuated joint, and the LTI (:func:`wrench_transmission`).

    Attributes
    ----------
    input : numpy.ndarray, shape (..., n)
        ``ITI_j``: the actuation wrench ``w_j`` against the actuated joint's twist ``$_j``.
    output : numpy.ndarray, shape (..., n)
        ``OTI_j``: ``w_j`` against the platform twist ``$_Oj`` produced by actuator ``j`` alone.
    lti : numpy.ndarray, shape (...)
        ``min(min_j ITI_j, min_j OTI_j)``.
    actuated_joints : tuple of str
    """

    input: np.ndarray
    output: np.ndarray
    lti: np.ndarray
    actuated_joints: tuple[str, ...]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready."""
        return {"input": self.input.tolist(), "output": self.output.tolist(),
                "lti": np.asarray(self.lti).tolist(),
                "actuated_joints": list(self.actuated_joints)}


def wrench_transmission(
    jacobians: Any, *, input_points: Any = None, output_points: Any = None
) -> WrenchTransmission:
    """A transmission index for any mechanism, from its actuation wrenches and platform twists.

    In the style of Wang, Wu & Liu (2010, paper 004's ref. [38]): with the actuation wrench ``w_j``
    of limb ``j`` (:func:`screwkit.core.wrenches.wrench_analysis`), the twist ``$_j`` of its actuated
    joint, and the platform twist ``$_Oj`` that actuator ``j`` alone produces (the twist of the
    basis reciprocal to every other actuation wrench: the null vector of ``A`` without row ``j``),

    * input transmission ``ITI_j = |w_j ∘ $_j| / max`` and output ``OTI_j = |w_j ∘ $_Oj| / max``,
      each with a bound of :func:`transmission_ratio`: for the input at ``input_points[j]``, by
      default the point where ``w_j`` acts on the link the actuator drives (the point of its line
      nearest the zero-pitch axes of that link's other joints; the common-normal bound where there
      is none); for the output likewise at ``output_points[j]``, by default where ``w_j`` meets the
      axes of the limb's joints on the platform (the common-normal bound where there are none, e.g.
      a limb ending in a prismatic joint, or on a sub-platform: there a planar force against a
      rotation normal to it always scores 1 but at the singularity, a known weakness of that bound);
    * ``LTI = min(min_j ITI_j, min_j OTI_j)`` (Eq. 16 of paper 004 has the same form).

    All three lie in [0, 1] and do not change under rigid motions or a change of length unit. A
    serial singularity (``B_jj = 0``) gives ``ITI_j = 0``; an actuation singularity (``A`` loses
    rank) gives ``OTI_j = 0`` for the limbs involved.

    Relation to paper 004 (derived; ``tests/test_indices.py`` checks both). For a four-limb robot
    ``w_i`` is a force along the parallelogram (unit ``w_i``, through ``B_i``) and ``$_i`` the
    rotation about ``u_i`` through ``A_i`` (pitches 0). With the point of application ``B_i``
    (``posed.wrench_transmission`` passes it), ``v(B_i) = b u_i × v_i`` and
    ``ITI_i = |w_i·(u_i × v_i)| = |cos μ_i|`` (Eq. 11): ``min_i ITI_i`` *is* paper 004's ``κ``.
    Without a point, the common-normal bound gives ``ITI_i = |sin ∠(w_i, u_i)|``
    ``= √(κ_i² + (w_i·v_i)²) ≥ κ_i`` (``u_i``, ``v_i``, ``u_i × v_i`` orthonormal), equal to
    ``κ_i`` exactly where ``w_i ⟂ v_i``. Neither depends on the representative of ``w_i`` modulo
    the limb's constraint couple ``u_i × w_i`` (it does no work on ``$_i``, and adding it shifts the
    force's line along ``u_i``, which moves neither ``B_i`` nor the common normal). The output
    indices are not paper 004's ``ζ`` (the pressure angle between the two sub-platforms' planes,
    Eq. 13): ``OTI_j`` uses the actuation wrench as the core gives it (a unit force; for a limb with
    constraint wrenches ``$_Oj`` is reciprocal to them, the bound is not, so it depends on that
    representative).

    Parameters
    ----------
    jacobians : WrenchJacobians
        From :func:`screwkit.core.jacobians.jacobians_from_wrenches` or ``posed.jacobians``; ``A`` must
        be square (one actuator per degree of freedom of the basis).
    input_points, output_points : array_like, shape (..., n, 3), optional
        Points of application of the actuation wrenches on the actuated link and on the platform,
        in the order of ``jacobians.actuated_joints``.

    Returns
    -------
    WrenchTransmission

    Raises
    ------
    ScrewkitTypeError
        Not a WrenchJacobians.
    ScrewkitValueError
        ``A`` is not square, or points of the wrong shape.

    Examples
    --------
    The slider-crank of :func:`screwkit.core.jacobians.jacobians_from_wrenches` (crank 1, coupler 2)
    at ``θ = 60°``: the coupler pushes the crank pin nearly along the pin's velocity (input 0.997,
    at the pin) and the slider at ``asin(√3/4)`` to its path (output ``√13/4 = 0.901``).

    >>> import numpy as np
    >>> from screwkit.core.jacobians import jacobians_from_wrenches
    >>> from screwkit.graphs.joints import prismatic, revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> pin = [0.5, np.sqrt(3.0) / 2, 0.0]
    >>> slider = [0.5 + np.sqrt(4.0 - 0.75), 0.0, 0.0]
    >>> G = twist_graph("ground", "slider", [
    ...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("crank", "coupler", revolute("R1", [0, 0, 1], pin)),
    ...     ("coupler", "slider", revolute("R2", [0, 0, 1], slider)),
    ...     ("ground", "slider", prismatic("P", [1, 0, 0]))], dof=1)
    >>> jac = jacobians_from_wrenches(wrench_analysis(G), [[0, 0, 0, 1, 0, 0]])
    >>> result = wrench_transmission(jac, input_points=[pin])
    >>> result.input.round(6).tolist(), result.output.round(6).tolist(), round(float(result.lti), 6)
    ([0.997131], [0.901388], 0.901388)
    """
    from ..core.jacobians import WrenchJacobians

    if not isinstance(jacobians, WrenchJacobians):
        raise ScrewkitTypeError(
            f"Expected `jacobians` to be a WrenchJacobians, got {type(jacobians).__name__}."
        )
    forward = np.asarray(jacobians.A)
    n, dof = forward.shape[-2:]
    if n != dof:
        raise ScrewkitValueError(
            f"Expected a square A (one actuator per twist of the basis) for the output transmission, got "
            f"A of shape {(n, dof)}."
        )
    wrenches = np.asarray(jacobians.wrenches)
    # what the driven link receives: the wrench, or in a compound leg analysed as a whole its part
    # on the actuator's own branch (screwkit.core.wrenches.WrenchAnalysis.branch_rows)
    branches = np.asarray(jacobians.analysis.branch_rows, dtype=float)
    twists = np.asarray(jacobians.analysis.actuated_twists, dtype=float)
    basis = np.asarray(jacobians.twist_basis)
    points = [None if p is None else B.as_array(p, name, (None, 3), symbolic=False)
              for name, p in (("input_points", input_points), ("output_points", output_points))]
    for name, array in zip(("input_points", "output_points"), points, strict=True):
        if array is not None and array.shape[-2] != n:
            raise ScrewkitValueError(f"Expected `{name}` to have shape (..., {n}, 3), got {array.shape}.")
    if points[0] is None and n:
        found, located = _driven_link_points(jacobians, branches)
        iti = np.where(
            located,
            transmission_ratio(branches, twists, point=found),
            transmission_ratio(branches, twists),
        )
    else:
        iti = transmission_ratio(branches, twists, point=points[0]) if n else np.zeros(forward.shape[:-1])
    iti = np.where(np.asarray(jacobians.serial), 0.0, iti)
    if n == 0:
        return WrenchTransmission(iti, iti, np.ones(forward.shape[:-2]), jacobians.actuated_joints)
    others = np.stack([np.delete(forward, j, axis=-2) for j in range(n)], axis=-3)  # (..., n, n-1, dof)
    if n > 1:
        scale = np.linalg.norm(others, axis=-2, keepdims=True)  # column scaling: mixed units
        scale = np.where(scale > 0, scale, 1.0)
        coefficients = np.linalg.svd(others / scale)[2][..., -1, :] / scale[..., 0, :]
    else:
        coefficients = np.ones((*forward.shape[:-2], 1, 1))
    output_twists = np.einsum("...jk,...kc->...jc", coefficients, basis)
    if points[1] is None:
        found, located = _driven_link_points(jacobians, wrenches, output=True)
        oti = np.where(
            located,
            transmission_ratio(wrenches, output_twists, point=found),
            transmission_ratio(wrenches, output_twists),
        )
    else:
        oti = transmission_ratio(wrenches, output_twists, point=points[1])
    lti = np.minimum(iti.min(axis=-1), oti.min(axis=-1))
    return WrenchTransmission(iti, oti, lti, jacobians.actuated_joints)


# --------------------------------------------------------------------------------------------------
# For the report and PosedMechanism
# --------------------------------------------------------------------------------------------------


def application_points(configuration: Any) -> np.ndarray | None:
    """The actuation wrenches' points of application on the actuated links, where the family knows
    them: ``B_i`` (the elbows) for a four-limb configuration, in limb order; None otherwise.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> application_points(load_mechanism("h4").configuration()).shape
    (4, 3)
    """
    return np.asarray(configuration.b) if isinstance(configuration, FourLimbGeometry) else None


def transmission_summary(mechanism: Any, pose: Any, jacobians: Any) -> dict[str, Any]:
    """The transmission indices at one pose, for :func:`screwkit.interface.report.pose_report`.

    ``"wrench"``: :func:`wrench_transmission` (any mechanism with Jacobians; at the elbows for the
    four-limb family), ``"paper_004"``: :func:`transmission` (four-limb family only, else None),
    ``"note"``: what they are or why one is missing.

    Examples
    --------
    >>> from screwkit.robots.catalog import load_mechanism
    >>> h4 = load_mechanism("h4")
    >>> summary = transmission_summary(h4, h4.default_pose, h4.at()[0].jacobians)
    >>> round(min(summary["wrench"]["input"]), 9) == round(summary["paper_004"]["input"], 9)  # κ, derived
    True
    """
    summary: dict[str, Any] = {"wrench": None, "paper_004": None, "note": ""}
    notes = []
    if jacobians is None or jacobians.A.shape[-1] != jacobians.A.shape[-2]:
        notes.append("wrench-based index: needs square Jacobians at the pose")
    else:
        points = None
        if _is_four_limb(getattr(mechanism, "parameters", None)):
            points = application_points(mechanism.configuration(pose))
        summary["wrench"] = wrench_transmission(jacobians, input_points=points).to_dict()
        notes.append(
            "wrench-based: input ITI_j = |w_j o $_j| / max (at the elbow for the four-limb family), "
            "output OTI_j against the platform twist of actuator j alone, LTI = min "
            "(screwkit.analysis.indices.wrench_transmission)"
        )
    if _is_four_limb(getattr(mechanism, "parameters", None)):
        summary["paper_004"] = transmission(mechanism, pose).to_dict()
        notes.append("paper 004: kappa, zeta (Eq. 15), LTI eta (Eq. 16)")
    summary["note"] = "; ".join(notes)
    return summary


def _is_four_limb(parameters: Any) -> bool:
    """True for the parameters of a four-limb mechanism (:class:`FourLimbParameters`); the family's
    module is not imported to tell (no such parameters exist before it is)."""
    module = sys.modules.get("screwkit.robots.families.four_limb.parameters")
    return module is not None and isinstance(parameters, module.FourLimbParameters)
