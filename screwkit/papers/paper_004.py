"""Paper 004's transmission indices of the four-limb robots: pressure angles, κ, ζ, LTI, Jacobians.

What is here, along the data flow:

* paper 004's pressure angles and indices of a four-limb configuration (:func:`motion_pressure_angles`,
  :func:`force_pressure_angle`, :func:`transmission_indices`, the Jacobians of Eq. 6), below;
* :func:`transmission`: the same ``κ`` (input), ``ζ`` (output) and LTI ``η`` for a batch of poses
  of a catalog mechanism (or ``mechanism.at(poses)``), inverse kinematics included, through one fused
  compiled kernel when numba is installed (:mod:`screwkit.papers._lti_numba`; the numpy path is the
  tested fallback, ``SCREWKIT_NUMBA=0`` forces it): the entry point for maps;
* handed on to the maps and the report by :mod:`screwkit.papers.paper_004_summary`.

Elsewhere: :mod:`screwkit.papers.paper_004_table4` (index extremes over a region, Table 4),
:mod:`screwkit.papers.paper_004_surfaces` (the actuation singularity surfaces of Figs. 14-16), and
the generic index of any mechanism (:mod:`screwkit.robots.transmission`).

Source: paper 004 (Wu, Bai, Caro, "A transmission quality index for a class of four-limb parallel
Schönflies motion generators", JMR 10(5), 2018) (docs/papers.md);
equation and table numbers are that paper's. Its functions here take a four-limb configuration
(:class:`screwkit.robots.families.four_limb.configuration.FourLimbConfiguration`, from the
family's inverse kinematics or :meth:`screwkit.robots.mechanism.Mechanism.configuration`) of any
batch shape ``...`` and returns arrays over that batch. The configuration's ``w_i`` (unit
parallelogram directions), ``h_i`` (Eq. 8), ``s_i`` (Eq. 4) and ``s`` (Tables 1-2) are the robot
model; what follows is paper 004's analysis of it.

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

Where paper 004 is wrong here
-----------------------------
Numbered as in :mod:`screwkit.robots.families.four_limb`, whose items 1-3 and 6 concern the model;
each is checked in ``tests/robots/test_families_four_limb.py``.

4. Table 2, Veloce, printed ``hφ/(2π) (w_13 × w_24)ᵀk``: it would make every pose with ``φ = 0``
   singular. Laplace expansion with the corrected ``s_i`` gives ``|A| = -h/(2π) (w_13 × w_24)ᵀk``.
   The Quattro/H4/V4 entry ``2r (w_14 × w_23)ᵀs`` (Eq. 12) is right, factor 2 and sign included.
5. Eq. (11) prints ``μ_i = cos⁻¹(w_iᵀ(u_i × v_i))``; in the paper's working mode (``h_i < 0``) that
   lies in (90°, 180°], yet Sec. 5.1 reports ``μ_i ∈ [0, 65°]``. The paper evidently uses the acute
   angle ``cos⁻¹|w_iᵀ(u_i × v_i)|``, which is what :func:`motion_pressure_angles` returns (``κ`` of
   Eq. 15 takes ``|cos μ_i|`` anyway). Eq. (13) likewise: as printed it gives σ = 180° at the
   spiral's ``φ = 0`` pose where Sec. 5.1 says σ = 0; :func:`force_pressure_angle` returns the
   acute angle.

7. Sec. 5.1 says the Quattro "encounters Type-2 singularity when ``|φ| = π/2`` at the end points" of
   the spiral (Eqs. 17-18). Only approximately: ``|A|`` changes sign at ``φ = -88.3°`` and at
   ``φ = +90°`` we find σ = 88.3° (ζ = 0.03).

Examples
--------
>>> quattro = load_mechanism("quattro")
>>> indices = transmission_indices(quattro.configuration([[0, 0, -800, 0], [0, 0, -800, 1.5]]))
>>> indices.eta.shape, bool(np.all((0 <= indices.eta) & (indices.eta <= 1)))
((2,), True)
"""

from __future__ import annotations

import math
import sys
from types import ModuleType
from typing import Any, NamedTuple, Protocol, runtime_checkable

import numpy as np

from ..algebra import backend as B
from ..algebra.compiled import COMPILED_MIN_BATCH, compiled_kernels
from ..exceptions import ScrewkitTypeError, ScrewkitValueError, UnreachablePoseError
from ..robots.posed import PosedMechanism
from ..robots.toml_fields import MAX_ANGLE_RADIANS, MAX_COORDINATE
from ..robots.transmission import Transmission

__all__ = [
    "INDEX_NAMES",
    "FourLimbGeometry",
    "FourLimbJacobians",
    "backend",
    "det_A_closed_form",
    "force_pressure_angle",
    "four_limb_jacobians",
    "motion_pressure_angles",
    "transmission",
    "transmission_indices",
]


@runtime_checkable
class FourLimbGeometry(Protocol):
    """What the functions of this module read from a four-limb configuration.

    :class:`screwkit.robots.families.four_limb.configuration.FourLimbConfiguration` has these
    attributes (arrays over the batch ``...``; limb ``i`` of paper 004 at index ``i - 1``).

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


def four_limb_jacobians(config: FourLimbGeometry) -> FourLimbJacobians:
    """Forward Jacobian ``A`` (rows ``e_i = [w_iᵀ, r w_iᵀs_i]``) and ``B = diag(h_i)``, Eqs. (6)-(8).

    Columns of ``A`` are ordered ``(x, y, z, φ)``; the last column has the unit of length.

    Parameters
    ----------
    config : FourLimbGeometry
        A four-limb configuration (batch ``...``).

    Returns
    -------
    FourLimbJacobians

    Examples
    --------
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

    Parameters
    ----------
    config : FourLimbGeometry
        A four-limb configuration (batch ``...``).

    Returns
    -------
    (...,) ndarray
        In units of length (like ``np.linalg.det`` of ``A``).

    Examples
    --------
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

    Parameters
    ----------
    config : FourLimbGeometry
        A four-limb configuration (batch ``...``).

    Returns
    -------
    (..., 4) ndarray, radians

    Examples
    --------
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

    Parameters
    ----------
    config : FourLimbGeometry
        A four-limb configuration (batch ``...``).

    Returns
    -------
    (...,) ndarray, radians

    Examples
    --------
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


def transmission_indices(config: FourLimbGeometry) -> Transmission:
    """``κ = min_i |cos μ_i|``, ``ζ = |cos σ|`` (Eq. 15) and the LTI ``η = min(κ, ζ)`` (Eq. 16).

    Each lies in ``[0, 1]``; larger is better, 0 is a singularity.

    Parameters
    ----------
    config : FourLimbGeometry
        A four-limb configuration (batch ``...``).

    Returns
    -------
    Transmission
        ``input`` (κ), ``output`` (ζ), ``lti`` (η), each of the batch shape.

    Examples
    --------
    >>> cfg = load_mechanism("h4").configuration([[0, 0, -700, 0], [0, 0, -700, 1.0]])
    >>> ti = transmission_indices(cfg)
    >>> ti.eta.shape, bool(np.all(ti.eta == np.minimum(ti.kappa, ti.zeta)))
    ((2,), True)
    """
    _require_configuration(config)
    kappa = np.min(np.cos(motion_pressure_angles(config)), axis=-1)
    zeta = np.cos(force_pressure_angle(config))
    return Transmission(kappa, zeta, np.minimum(kappa, zeta))


#: The index names :func:`~screwkit.papers.paper_004_table4.index_extremes` accepts: paper 004's
#: ``lti`` (η, Eq. 16), ``input`` (κ) and ``output`` (ζ) of Eq. (15).
INDEX_NAMES = ("lti", "input", "output")

_UNREACHABLE = ("raise", "nan")


def _numba_kernels(poses: int) -> ModuleType | None:
    """The fused kernel module for a call over ``poses`` poses, or None for the numpy path
    (:func:`screwkit.core.frames.compiled_kernels`: the same rule as the rank kernels)."""
    return compiled_kernels("screwkit.papers._lti_numba", poses)


def backend() -> str:
    """``"numba"`` or ``"numpy"``: how :func:`transmission` computes batches of
    :data:`screwkit.algebra.compiled.COMPILED_MIN_BATCH` poses or more in this process.

    Returns
    -------
    str

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


def _plain_poses(mechanism: Any, poses: Any) -> np.ndarray | None:
    """``poses`` itself when it is a float64 array ``(..., n)`` whose coordinates are all finite and
    within the catalog's bounds, decided once over the batch from its extremes (a map's grid: no
    copy, no second pass); else None, and the caller runs the checks that name what is wrong."""
    names = mechanism.pose_names
    if not (isinstance(poses, np.ndarray) and poses.dtype == np.float64 and poses.ndim >= 1
            and poses.shape[-1] == len(names) and poses.size):
        return None
    low, high = float(poses.min()), float(poses.max())  # NaN or inf: not finite
    if not (math.isfinite(low) and math.isfinite(high) and max(-low, high) <= MAX_COORDINATE):
        return None
    for name in mechanism.angle_names:
        column = poses[..., names.index(name)]
        if max(-float(column.min()), float(column.max())) > MAX_ANGLE_RADIANS:
            return None
    return poses


def _transmission_numpy(mechanism: Any, poses: np.ndarray, mode: tuple[int, ...]) -> tuple[np.ndarray, ...]:
    """κ, ζ, reachable over a flat batch ``(n, 4)``: the family's IK, then :func:`transmission_indices`."""
    ok = mechanism.reachable(poses)
    kappa, zeta = np.zeros(len(poses)), np.zeros(len(poses))
    if ok.any():
        config: Any = mechanism.at(poses[ok], working_mode=mode).configuration
        result = transmission_indices(config)
        kappa[ok], zeta[ok] = result.kappa, result.zeta
    return kappa, zeta, ok


def transmission(
    mechanism_or_posed: Any,
    poses: Any = None,
    *,
    working_mode: Any = None,
    unreachable: str = "raise",
) -> Transmission:
    """Paper 004's ``κ`` (input), ``ζ`` (output) and LTI ``η`` (Eqs. 15-16) over a batch of poses.

    The batched entry point for maps (workspace grids, trajectories): inverse kinematics (Eq. 3) and
    the indices in one pass. With numba (the ``fast`` extra) one fused compiled loop
    (:mod:`screwkit.papers._lti_numba`) for batches of :data:`screwkit.algebra.compiled.COMPILED_MIN_BATCH`
    poses or more (or once it is loaded), else the numpy path
    (:func:`screwkit.robots.families.four_limb.kinematics.inverse_kinematics` then
    :func:`transmission_indices`; a single pose never loads numba);
    ``SCREWKIT_NUMBA=0`` forces numpy. The two agree to round-off (``tests/papers/test_paper_004.py``).

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
    Transmission
        ``input`` (κ), ``output`` (ζ), ``lti`` (η), each of the batch shape.

    Raises
    ------
    ScrewkitValueError
        Not a four-limb mechanism, malformed poses, or an unknown ``unreachable``.
    UnreachablePoseError
        With ``unreachable="raise"``, if a pose is out of reach.

    Examples
    --------
    >>> quattro = load_mechanism("quattro")
    >>> result = transmission(quattro, [[0, 0, -800, 0], [0, 0, -2000, 0]], unreachable="nan")
    >>> result.lti.round(3).tolist(), result.reachable.tolist()
    ([0.982, nan], [True, False])
    >>> float(transmission(quattro.at([0, 0, -800, 0.5])).lti[0]) < 1
    True
    """
    from ..robots.families.four_limb.kinematics import checked_working_mode

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
    chi = _plain_poses(mechanism, chosen)
    if chi is None:  # the checks one by one, each naming what is wrong
        mechanism.check_pose_range(chosen)
        chi = B.as_array(chosen, "poses", (4,), symbolic=False)  # a new float64 array, checked finite
    batch = chi.shape[:-1]
    flat = np.ascontiguousarray(chi.reshape(-1, 4))
    kernels = _numba_kernels(len(flat))
    if kernels is None:
        kappa, zeta, ok = _transmission_numpy(mechanism, flat, mode)
    else:
        kappa, zeta, ok = kernels.transmission(flat, *_kernel_arguments(params, mode))
        if unreachable == "raise" and not ok.all():  # before refusing, the reference decides: at the
            # reach band's edge (a leg stretched exactly) the two roundings may differ by an ulp (with
            # "nan" such a pose stays masked, never given a wrong value, and maps keep their speed)
            again = np.flatnonzero(~ok)
            kappa[again], zeta[again], ok[again] = _transmission_numpy(mechanism, flat[again], mode)
    eta = np.minimum(kappa, zeta)
    if not ok.all():
        if unreachable == "raise":
            mechanism.configuration(chi, working_mode=mode)  # raises the family's message
            raise UnreachablePoseError("A pose is out of reach.")  # pragma: no cover - unreachable
        missing = ~ok
        for values in (kappa, zeta, eta):
            np.copyto(values, np.nan, where=missing)
    return Transmission(kappa.reshape(batch), zeta.reshape(batch), eta.reshape(batch))


def _is_four_limb(parameters: Any) -> bool:
    """True for the parameters of a four-limb mechanism
    (:class:`~screwkit.robots.families.four_limb.parameters.FourLimbParameters`); the family's
    module is not imported to tell (no such parameters exist before it is)."""
    module = sys.modules.get("screwkit.robots.families.four_limb.parameters")
    return module is not None and isinstance(parameters, module.FourLimbParameters)
