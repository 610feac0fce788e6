"""Planar 3-RRP parallel manipulator: the robot model (parameters, kinematics, joint table).

Source: paper 003 (S. Zarkandi, "A study of the instantaneous centers of rotation in
singularities of 3-DOF fully parallel planar manipulators"), file
``/work/shared/papers/003_37bb0c9b229f0566.txt``. Equation numbers below are that paper's. The
paper gives no dimensions; the model is general and :data:`EXAMPLE_PARAMETERS` are *our* choice
(see there).

The model
---------
Links carry the paper's labels (Fig. 1b): ``1`` base, ``2, 4, 6`` the first (actuated) link of limbs
1, 2, 3, ``3, 5, 7`` their second link, ``8`` the end effector (platform). Limb ``k`` (``k = 1, 2,
3``, first link ``i = 2k``, second link ``j = i + 1``) is

``base --R (actuated, at M_k = C_1i)--> link i --R (elbow A_k = C_ij)--> link j --P (b_k)--> 8``.

The prismatic joint keeps link ``j`` at the platform's orientation (Eq. 7b uses the platform's
``ω`` for link ``j``), so the elbow ``A_k`` slides on a *guide line fixed in the platform*: it
passes through the platform point ``P_k`` and has the direction ``b_k = R(φ) (cos β_k, sin β_k)``.

* pose ``(x, y, φ)``: position of the platform's reference point ``C`` and its orientation;
  twist ``t = (ω, ẋ, ẏ) = (φ̇, ẋ, ẏ)`` in the paper's order (Eq. 3, angular rate first: note
  the different order of the pose);
* joint angle ``θ_k``: the angle of ``M_k A_k`` from the base x axis, ``A_k = M_k + l_k u(θ_k)``;
* closure (our form of Eq. 1): ``f_k = n_k·(A_k - C) - n⁰_k·P_k = 0`` with ``n_k = E b_k``,
  ``E`` the 90° rotation of Eq. (6);
* inverse kinematics: line-circle intersection, ``A_k = Q_k + γ_k b_k``, ``Q_k = C + R(φ) P_k``,
  ``γ_k = -(Q_k - M_k)·b_k + σ_k sqrt(l_k² - h_k²)`` with ``h_k = (Q_k - M_k)·n_k``; the working
  mode ``σ = (σ_1, σ_2, σ_3)`` (each ``±1``) is the sign of ``J_kk``, since
  ``J_kk = σ_k sqrt(l_k² - h_k²)``;
* forward kinematics: with ``θ`` given, the three closure equations are linear in ``C``; they are
  consistent iff ``P cos φ + Q sin φ = S`` (the 2×2 minors of the normals do not depend on
  ``φ``), so there are at most two assembly modes, found in closed form.

Velocities, instant centres and the paper's Jacobians ``J``, ``K`` (Eqs. 4-11) and its singularity
classification (Sec. 4) are paper 003's analysis of this model: they live beside the tests that
check them (``tests/paper_003.py``); the joint table below is what screwkit analyses.

Where paper 003 is wrong about the model (its errata 1-5 on the analysis: ``tests/paper_003.py``)
----------------------------------------------------------------------------------------------
6. Sec. 4.2, second case (all ``b_i`` parallel): ``b_k`` turn together with the platform, so it
   never happens unless the guides are parallel in the platform, and then it happens at *every*
   pose. Such parameters are rejected (:class:`Planar3RRPParameters`).


The joint table
---------------
:func:`joints` embeds the mechanism in space (plane ``z = 0``): R joints are zero-pitch screws
along ``z`` through their centres, P joints infinite-pitch screws along ``(b_k, 0)``. Its wrench
systems (:mod:`screwkit.core.wrenches`) have a constraint system of order 3 (forces along ``z`` and
couples about horizontal axes, the planarity constraints) and, per limb, an actuation wrench that is
the planar force through the elbow ``A_k`` perpendicular to the guide: the Kennedy line ``L_k``.
The labels of :func:`screwkit.core.singularity.classify` then match paper 003's instant-centre
classification (``tests/paper_003.py``):
inverse (``J_kk = 0``) ↔ ``"serial"`` (that limb's twist system drops to order 2, so the platform
is locked in one direction rather than uncontrolled: ``lost_dof = 1``, the global system stays a
6-system); direct (``L_1, L_2, L_3`` concurrent) ↔ ``"actuation"``; combined ↔ both. The tests
(``tests/test_planar_catalog.py``) check this at poses found by root search.

Examples
--------
>>> import numpy as np
>>> from screwkit.robots.families.planar_3rrp import EXAMPLE_PARAMETERS, Planar3RRPConfiguration, joints
>>> from screwkit.core.singularity import classify_table
>>> config = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [[0.0, 0.0, 0.0], [0.05, -0.03, 0.1]])
>>> np.round(np.degrees(config.joint_angles[0]), 3)
array([ -3.557, 116.443, -123.557])
>>> classify_table(joints(config)).verdict.tolist()
['regular', 'regular']
"""

from __future__ import annotations

import itertools
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...algebra import screw as S
from ...algebra.backend import DEFAULT_RTOL, as_array, checked_rtol
from ...exceptions import (
    CatalogError,
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    UnreachablePoseError,
)
from ...graphs.joints import JointTable
from ..two_limb import REACH_ULPS
from . import Family

__all__ = [
    "EXAMPLE_PARAMETERS",
    "FAMILY",
    "JOINT_PAIRS",
    "LINK_NAMES",
    "WORKING_MODES",
    "ForwardKinematicsSolutions",
    "Planar3RRPConfiguration",
    "Planar3RRPParameters",
    "forward_kinematics",
    "inverse_kinematics",
    "joints",
    "reach_margin",
    "twist_basis",
]

#: Link names by the paper's label (Fig. 1b): ``LINK_NAMES[label - 1]``.
LINK_NAMES = (
    "base",
    "limb1_link1",
    "limb1_link2",
    "limb2_link1",
    "limb2_link2",
    "limb3_link1",
    "limb3_link2",
    "platform",
)

#: The joints as pairs of paper labels, per limb from base to platform: actuated R, passive R, P.
JOINT_PAIRS = (
    ((1, 2), (2, 3), (3, 8)),
    ((1, 4), (4, 5), (5, 8)),
    ((1, 6), (6, 7), (7, 8)),
)

#: The eight working modes (signs of ``J_kk``), shape ``(8, 3)``; broadcast a pose against it.
WORKING_MODES = np.array(list(itertools.product((1.0, -1.0), repeat=3)))
WORKING_MODES.flags.writeable = False

_FIELDS = ("base_points", "link_lengths", "platform_points", "guide_angles")
#: Metadata keys a catalog entry passes along with the geometry (checked, not stored).
_METADATA = ("name", "length_unit")
_FIELD_SHAPES = {
    "base_points": (3, 2),
    "link_lengths": (3,),
    "platform_points": (3, 2),
    "guide_angles": (3,),
}


def _perp(v: np.ndarray) -> np.ndarray:
    """``E v`` of Eq. (6): rotate planar vectors ``(..., 2)`` by +90°."""
    return np.stack([-v[..., 1], v[..., 0]], axis=-1)


def _dot(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    return (a * b).sum(axis=-1)


def _unit(angle: np.ndarray) -> np.ndarray:
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def _readonly(array: np.ndarray) -> np.ndarray:
    array = np.array(array)
    array.flags.writeable = False
    return array


def _first_index(mask: np.ndarray) -> tuple[int, ...]:
    return tuple(int(i) for i in np.argwhere(mask)[0])


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False, slots=True)
class Planar3RRPParameters:
    """Geometry of a planar 3-RRP manipulator (paper 003, Fig. 1a).

    Parameters
    ----------
    base_points : array_like, shape (3, 2)
        Actuated joint centres ``M_k = C_1i`` in the base frame.
    link_lengths : array_like, shape (3,)
        Lengths ``l_k = |A_k - M_k|`` of the first links, > 0.
    platform_points : array_like, shape (3, 2)
        A point ``P_k`` of each guide line, in the platform frame (origin = reference point ``C``).
    guide_angles : array_like, shape (3,)
        Directions ``β_k`` of the guides in the platform frame, radians.

    Raises
    ------
    ScrewkitValueError
        If a field has the wrong shape or non-finite values, a link length is not positive, or the
        three guides are parallel (``|sin(β_k - β_1)| <= DEFAULT_RTOL`` for ``k = 2, 3``): such a
        manipulator translates freely along the guides at every pose (paper 003, Sec. 4.2).

    Examples
    --------
    >>> p = Planar3RRPParameters([[0, 0], [1, 0], [0, 1]], [0.5, 0.5, 0.5],
    ...     [[0, 0], [0.1, 0], [0, 0.1]], [0.0, 1.0, 2.0])
    >>> p.length_scale
    0.5
    """

    base_points: np.ndarray
    link_lengths: np.ndarray
    platform_points: np.ndarray
    guide_angles: np.ndarray

    def __post_init__(self) -> None:
        for name in _FIELDS:
            shape = _FIELD_SHAPES[name]
            value = as_array(getattr(self, name), name, shape)
            if value.shape != shape:
                raise ScrewkitValueError(
                    f"Expected `{name}` to have shape {shape}, got {value.shape}."
                )
            object.__setattr__(self, name, _readonly(value))
        if np.any(self.link_lengths <= 0):
            raise ScrewkitValueError(
                f"Expected `link_lengths` to be > 0, got {self.link_lengths.tolist()}."
            )
        spread = np.abs(np.sin(self.guide_angles[1:] - self.guide_angles[0]))
        if np.all(spread <= DEFAULT_RTOL):
            raise ScrewkitValueError(
                "Expected `guide_angles` not all parallel (mod π), got "
                f"{self.guide_angles.tolist()}: the platform would translate freely along the "
                "guides at every pose (paper 003, Sec. 4.2)."
            )

    @property
    def length_scale(self) -> float:
        """Characteristic length: the longest first link, ``max l_k`` (scales tolerances)."""
        return float(self.link_lengths.max())

    @classmethod
    def from_mapping(
        cls, mapping: Mapping[str, Any], *, source: str = "<mapping>"
    ) -> Planar3RRPParameters:
        """Build parameters from a mapping such as a parsed TOML table.

        Parameters
        ----------
        mapping : Mapping
            Exactly the fields ``base_points`` (3 pairs), ``link_lengths`` (3 numbers),
            ``platform_points`` (3 pairs), ``guide_angles`` (3 numbers, radians); optionally the
            metadata ``name`` and ``length_unit`` (non-empty strings, which
            :func:`screwkit.robots.catalog.load_mechanism` passes to every family; not stored here, the
            catalog's :class:`~screwkit.robots.catalog.Mechanism` keeps them).
        source : str
            Where the mapping comes from (a file name), quoted in error messages.

        Raises
        ------
        CatalogError
            If ``mapping`` is not a mapping, or a field is missing, unknown, not a (nested) list
            of real numbers, or of the wrong length, or a metadata field is not a non-empty string.
        ScrewkitValueError
            If a value is out of range (see the class); the message starts with ``source``.

        Examples
        --------
        >>> p = Planar3RRPParameters.from_mapping({"base_points": [[0, 0], [1, 0], [0, 1]],
        ...     "link_lengths": [0.5, 0.5, 0.5], "platform_points": [[0, 0], [0, 0], [0, 0]],
        ...     "guide_angles": [0, 1, 2]}, source="demo.toml")
        >>> p.link_lengths
        array([0.5, 0.5, 0.5])
        >>> Planar3RRPParameters.from_mapping({"link_lengths": [1, 1, 1]}, source="demo.toml")
        Traceback (most recent call last):
        ...
        screwkit.exceptions.CatalogError: demo.toml: missing field `base_points` ...
        """
        if not isinstance(mapping, Mapping):
            raise CatalogError(
                f"{source}: expected a mapping of the fields {list(_FIELDS)}, "
                f"got {type(mapping).__name__}."
            )
        for name in mapping:
            if name in _METADATA:
                if not isinstance(mapping[name], str) or not mapping[name].strip():
                    raise CatalogError(
                        f"{source}: field `{name}` must be a non-empty string, got {mapping[name]!r}."
                    )
            elif name not in _FIELDS:
                raise CatalogError(
                    f"{source}: unknown field `{name}`; expected only {list(_FIELDS)}."
                )
        values = {}
        for name in _FIELDS:
            if name not in mapping:
                raise CatalogError(
                    f"{source}: missing field `{name}` (expected shape {_FIELD_SHAPES[name]})."
                )
            values[name] = _catalog_field(mapping[name], name, _FIELD_SHAPES[name], source)
        try:
            return cls(**values)
        except ScrewkitValueError as err:
            raise ScrewkitValueError(f"{source}: {err}") from err


def _catalog_field(value: Any, name: str, shape: tuple[int, ...], source: str) -> np.ndarray:
    """Check that a catalog value is a nested list of real numbers of the given shape."""

    def fail(got: str) -> CatalogError:
        what = "a list of 3 numbers" if len(shape) == 1 else "a list of 3 [x, y] pairs"
        return CatalogError(f"{source}: field `{name}` must be {what}, got {got}.")

    def check(item: Any, depth: int) -> None:
        if depth == len(shape):
            if isinstance(item, bool) or not isinstance(item, int | float):
                raise fail(f"{type(item).__name__} {item!r} inside {value!r}")
            return
        if not isinstance(item, list | tuple) or len(item) != shape[depth]:
            raise fail(repr(item))
        for sub in item:
            check(sub, depth + 1)

    check(value, 0)
    return np.array(value, dtype=float)


#: Example dimensions (our choice; paper 003 gives none): base joints on a circle of radius 1 at
#: 210°, 330°, 90°; first links 0.9; guides tangent to a circle of radius 0.25 of the platform, the
#: guide of limb ``k`` through ``0.25 u(α_k)`` with direction ``β_k = α_k + 90°``. At the home pose
#: ``(0, 0, 0)`` every limb has ``J_kk = ±sqrt(0.9² - 0.75²) ≈ ±0.4975``.
EXAMPLE_PARAMETERS = Planar3RRPParameters(
    base_points=_unit(np.radians([210.0, 330.0, 90.0])),
    link_lengths=np.full(3, 0.9),
    platform_points=0.25 * _unit(np.radians([210.0, 330.0, 90.0])),
    guide_angles=np.radians([300.0, 60.0, 180.0]),
)


# --------------------------------------------------------------------------------------------------
# Position kinematics
# --------------------------------------------------------------------------------------------------


def _guides(parameters: Planar3RRPParameters, pose: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Guide points ``Q_k = C + R(φ) P_k`` and directions ``b_k``, each ``(..., 3, 2)``."""
    phi = pose[..., 2:3]
    c, s = np.cos(phi), np.sin(phi)
    px, py = parameters.platform_points[:, 0], parameters.platform_points[:, 1]
    q = pose[..., None, :2] + np.stack([c * px - s * py, s * px + c * py], axis=-1)
    return q, _unit(phi + parameters.guide_angles)


def _working_mode(value: Any) -> np.ndarray:
    mode = as_array(value, "working_mode", (3,))
    if not np.all(np.abs(mode) == 1):
        raise ScrewkitValueError(
            "Expected `working_mode` entries to be +1 or -1 (sign of J_kk per limb), "
            f"got {mode.tolist()}."
        )
    return mode


def reach_margin(parameters: Planar3RRPParameters, pose: Any) -> np.ndarray:
    """Normalised reach ``(l_k² - h_k²) / l_k²`` of each limb at the given poses.

    ``h_k`` is the distance from ``M_k`` to the guide line of limb ``k``. The margin is positive
    where limb ``k`` reaches its guide at two elbow points, zero on the boundary, negative outside.
    Where it is reachable it equals ``(J_kk / l_k)²`` (Eq. 11a), so its zeros are the inverse
    (type-1) singularities, Eq. (12); it continues ``det J`` analytically past the boundary.

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.

    Returns
    -------
    numpy.ndarray, shape (..., 3)

    Examples
    --------
    >>> round(float(reach_margin(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])[0]), 6)  # 1 - 0.75²/0.9²
    0.305556
    """
    pose = as_array(pose, "pose", (3,))
    q, b = _guides(parameters, pose)
    h = _dot(q - parameters.base_points, _perp(b))
    lengths = parameters.link_lengths
    return (lengths**2 - h**2) / lengths**2


def inverse_kinematics(
    parameters: Planar3RRPParameters,
    pose: Any,
    working_mode: Any = (1, 1, 1),
    *,
    rtol: float = DEFAULT_RTOL,
) -> np.ndarray:
    """Actuated joint angles ``θ`` of the given poses in the given working modes.

    Limb ``k`` meets its guide line where the circle of radius ``l_k`` about ``M_k`` cuts it:
    ``γ_k = -(Q_k - M_k)·b_k + σ_k sqrt(l_k² - h_k²)``, ``A_k = Q_k + γ_k b_k`` (module docstring).

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.
    working_mode : array_like, shape (..., 3)
        Sign ``σ_k = ±1`` of ``J_kk`` per limb; broadcast against ``pose``. All eight branches:
        ``inverse_kinematics(p, pose[..., None, :], WORKING_MODES)``.
    rtol : float, default 1e-9
        A limb with ``reach_margin >= -rtol`` is on the boundary (both branches coincide).

    Returns
    -------
    numpy.ndarray, shape (..., 3)
        ``θ_k`` in ``(-π, π]``.

    Raises
    ------
    UnreachablePoseError
        If a limb cannot reach its guide line; the message names the limb and the batch index.
    ScrewkitValueError
        If ``working_mode`` has an entry other than ±1.

    Examples
    --------
    >>> theta = inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> np.round(np.degrees(theta), 3)  # 30° - atan(sqrt(0.2475) / 0.75), then +120°, +240°
    array([ -3.557, 116.443, -123.557])
    >>> inverse_kinematics(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0], WORKING_MODES).shape
    (8, 3)
    """
    pose = as_array(pose, "pose", (3,))
    mode = _working_mode(working_mode)
    rtol = checked_rtol(rtol)
    margin = reach_margin(parameters, pose)
    outside = margin < -rtol
    if np.any(outside):
        index = _first_index(outside)
        limb = index[-1]
        raise UnreachablePoseError(
            f"Limb {limb + 1} cannot reach pose {pose[index[:-1]].tolist()} (batch index "
            f"{index[:-1]}): the distance from M{limb + 1} to its guide line exceeds the link "
            f"length {parameters.link_lengths[limb]:g} (reach margin {margin[index]:.3g} < 0)."
        )
    q, b = _guides(parameters, pose)
    d = q - parameters.base_points
    lengths = parameters.link_lengths
    # a limb within rounding of its reach is put at its reach exactly (1 - h²/l² has condition ~2)
    margin = np.where(margin <= 2.0 * REACH_ULPS * np.finfo(float).eps, 0.0, margin)
    gamma = -_dot(d, b) + mode * lengths * np.sqrt(margin)
    elbow_offset = d + gamma[..., None] * b
    return np.arctan2(elbow_offset[..., 1], elbow_offset[..., 0])


@dataclass(frozen=True, eq=False, slots=True)
class ForwardKinematicsSolutions:
    """The (at most two) assembly modes of given actuated joint angles.

    Attributes
    ----------
    poses : numpy.ndarray, shape (..., 2, 3)
        ``(x, y, φ)`` of each solution, ``φ`` in ``[-π, π)``; zeros where ``valid`` is False.
    valid : numpy.ndarray of bool, shape (..., 2)
        Whether each solution exists. At a direct singularity the two coincide.
    """

    poses: np.ndarray
    valid: np.ndarray

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary.

        Examples
        --------
        >>> fk = forward_kinematics(EXAMPLE_PARAMETERS, [0.1, 2.2, -2.0])
        >>> sorted(fk.to_dict())
        ['poses', 'valid']
        """
        return {"poses": self.poses.tolist(), "valid": self.valid.tolist()}

    def __str__(self) -> str:
        return (
            f"ForwardKinematicsSolutions: {int(self.valid.sum())} valid of "
            f"{self.valid.size} (batch shape {self.valid.shape[:-1]})"
        )


def forward_kinematics(
    parameters: Planar3RRPParameters, joint_angles: Any, *, rtol: float = DEFAULT_RTOL
) -> ForwardKinematicsSolutions:
    """All platform poses of given actuated joint angles, in closed form.

    With the elbows ``A_k`` fixed by ``θ``, the closures ``n_k(φ)·C = n_k(φ)·A_k - c_k`` (module
    docstring) are three linear equations in ``C``. Expanding ``det[n_k, n_k·A_k - c_k]`` along its
    last column, the cofactors ``n_k × n_l`` do not depend on ``φ``, so consistency reads
    ``P cos φ + Q sin φ = S`` with ``P = Σ s_k n⁰_k·A_k``, ``Q = Σ s_k (E n⁰_k)·A_k``,
    ``S = Σ s_k n⁰_k·P_k``, ``s_k = n⁰_{k+1} × n⁰_{k+2}``: at most two roots ``φ``, then ``C`` by
    least squares. These are all the solutions.

    Parameters
    ----------
    parameters : Planar3RRPParameters
    joint_angles : array_like, shape (..., 3)
    rtol : float, default 1e-9
        ``|S| <= (1 + rtol) sqrt(P² + Q²)`` counts as solvable; ``P, Q, S`` all below
        ``rtol * length_scale`` is a self-motion.

    Returns
    -------
    ForwardKinematicsSolutions

    Raises
    ------
    DegenerateGeometryError
        If the joint angles admit a continuum of poses (the platform turns about the common point of
        concurrent guides with coincident elbows).

    Examples
    --------
    >>> theta = inverse_kinematics(EXAMPLE_PARAMETERS, [0.05, -0.02, 0.1])
    >>> fk = forward_kinematics(EXAMPLE_PARAMETERS, theta)
    >>> fk.valid
    array([ True,  True])
    >>> bool(np.any(np.all(np.isclose(fk.poses, [0.05, -0.02, 0.1]), axis=-1)))
    True
    """
    theta = as_array(joint_angles, "joint_angles", (3,))
    rtol = checked_rtol(rtol)
    elbows = parameters.base_points + parameters.link_lengths[:, None] * _unit(theta)
    normals0 = _perp(_unit(parameters.guide_angles))
    offsets = _dot(normals0, parameters.platform_points)
    shifted1, shifted2 = np.roll(normals0, -1, axis=0), np.roll(normals0, -2, axis=0)
    cofactors = shifted1[:, 0] * shifted2[:, 1] - shifted1[:, 1] * shifted2[:, 0]
    p_coef = _dot(_dot(normals0, elbows), cofactors)
    q_coef = _dot(_dot(_perp(normals0), elbows), cofactors)
    s_coef = float(_dot(cofactors, offsets))
    radius = np.hypot(p_coef, q_coef)
    scale = rtol * parameters.length_scale
    continuum = (radius <= scale) & (abs(s_coef) <= scale)
    if np.any(continuum):
        index = _first_index(continuum)
        raise DegenerateGeometryError(
            f"`joint_angles` {theta[index].tolist()} (batch index {index}) admit a continuum of "
            "platform poses: the consistency condition P cos φ + Q sin φ = S vanishes identically "
            "(the platform turns about the common point of its guides)."
        )
    safe = np.where(radius > 0, radius, 1.0)
    valid_one = (radius > 0) & (abs(s_coef) <= (1.0 + rtol) * radius)
    half_width = np.arccos(np.clip(s_coef / safe, -1.0, 1.0))
    phi = np.arctan2(q_coef, p_coef)[..., None] + np.stack([half_width, -half_width], axis=-1)
    phi = np.mod(phi + np.pi, 2.0 * np.pi) - np.pi
    normals = _perp(_unit(phi[..., None] + parameters.guide_angles))  # (..., 2, 3, 2)
    rhs = _dot(normals, elbows[..., None, :, :]) - offsets
    gram = np.einsum("...ka,...kb->...ab", normals, normals)
    centre = np.linalg.solve(gram, np.einsum("...ka,...k->...a", normals, rhs)[..., None])[..., 0]
    valid = np.broadcast_to(valid_one[..., None], phi.shape)
    poses = np.where(valid[..., None], np.concatenate([centre, phi[..., None]], axis=-1), 0.0)
    return ForwardKinematicsSolutions(poses=_readonly(poses), valid=_readonly(valid))


# --------------------------------------------------------------------------------------------------
# Configurations
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False, slots=True)
class Planar3RRPConfiguration:
    """A pose together with its actuated joint angles (one or a batch).

    Parameters
    ----------
    parameters : Planar3RRPParameters
    pose : array_like, shape (..., 3)
        ``(x, y, φ)``.
    joint_angles : array_like, shape (..., 3)
        ``θ_k``; broadcast against ``pose``.
    closure_rtol : float, default 1e-9
        Each elbow ``A_k = M_k + l_k u(θ_k)`` must lie within ``closure_rtol * length_scale`` of its
        guide line.

    Attributes
    ----------
    base_points, elbow_points, guide_directions : numpy.ndarray, shape (..., 3, 2)
        ``M_k = C_1i``, ``A_k = C_ij`` and the unit guide directions ``b_k`` (base frame).
    platform_point : numpy.ndarray, shape (..., 2)
        The reference point ``C``.
    slider_positions : numpy.ndarray, shape (..., 3)
        ``γ_k`` with ``A_k = C + R(φ) P_k + γ_k b_k``.

    Raises
    ------
    ScrewkitValueError
        If an elbow is off its guide line (names the limb and batch index).

    Examples
    --------
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [[0, 0, 0], [0.1, 0, 0.2]])
    >>> c.elbow_points.shape, c.slider_positions.shape
    ((2, 3, 2), (2, 3))
    """

    parameters: Planar3RRPParameters
    pose: np.ndarray
    joint_angles: np.ndarray
    closure_rtol: float = DEFAULT_RTOL
    base_points: np.ndarray = field(init=False)
    elbow_points: np.ndarray = field(init=False)
    guide_directions: np.ndarray = field(init=False)
    platform_point: np.ndarray = field(init=False)
    slider_positions: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        params = self.parameters
        if not isinstance(params, Planar3RRPParameters):
            raise ScrewkitTypeError(
                f"Expected `parameters` to be Planar3RRPParameters, got {type(params).__name__}."
            )
        rtol = checked_rtol(self.closure_rtol, "closure_rtol")
        pose = as_array(self.pose, "pose", (3,))
        theta = as_array(self.joint_angles, "joint_angles", (3,))
        shape = np.broadcast_shapes(pose.shape[:-1], theta.shape[:-1])
        pose = np.broadcast_to(pose, (*shape, 3))
        theta = np.broadcast_to(theta, (*shape, 3))
        q, b = _guides(params, pose)
        base = np.broadcast_to(params.base_points, (*shape, 3, 2))
        elbows = base + params.link_lengths[:, None] * _unit(theta)
        residual = np.abs(_dot(elbows - q, _perp(b)))
        off = residual > rtol * params.length_scale
        if np.any(off):
            index = _first_index(off)
            raise ScrewkitValueError(
                f"Expected the elbow of limb {index[-1] + 1} on its guide line, but it is "
                f"{residual[index]:.3g} away at batch index {index[:-1]} (more than closure_rtol "
                f"* length_scale = {rtol * params.length_scale:.3g}): `joint_angles` do not match "
                "`pose`."
            )
        for name, value in (
            ("pose", pose),
            ("joint_angles", theta),
            ("base_points", base),
            ("elbow_points", elbows),
            ("guide_directions", b),
            ("platform_point", pose[..., :2]),
            ("slider_positions", _dot(elbows - q, b)),
        ):
            object.__setattr__(self, name, _readonly(value))

    @classmethod
    def from_pose(
        cls,
        parameters: Planar3RRPParameters,
        pose: Any,
        working_mode: Any = (1, 1, 1),
        *,
        rtol: float = DEFAULT_RTOL,
    ) -> Planar3RRPConfiguration:
        """The configuration of ``pose`` in ``working_mode`` (see :func:`inverse_kinematics`).

        Examples
        --------
        >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0, 0, 0], (1, -1, 1))
        >>> c.joint_angles.shape
        (3,)
        """
        theta = inverse_kinematics(parameters, pose, working_mode, rtol=rtol)
        return cls(parameters, np.broadcast_to(as_array(pose, "pose", (3,)), theta.shape), theta)

    @property
    def batch_shape(self) -> tuple[int, ...]:
        """Leading batch shape of the configuration."""
        return tuple(self.pose.shape[:-1])


def _check_config(config: Any) -> Planar3RRPConfiguration:
    if not isinstance(config, Planar3RRPConfiguration):
        raise ScrewkitTypeError(
            f"Expected `config` to be a Planar3RRPConfiguration, got {type(config).__name__}."
        )
    return config


# --------------------------------------------------------------------------------------------------
# The joint table and the nominal twists (the family protocol, screwkit.robots.families)
# --------------------------------------------------------------------------------------------------

_AXIS_Z = np.array([0.0, 0.0, 1.0])


def _in_space(planar: np.ndarray) -> np.ndarray:
    """Planar points or directions ``(..., 2)`` in the plane ``z = 0`` of space, ``(..., 3)``."""
    return np.concatenate([planar, np.zeros((*planar.shape[:-1], 1))], axis=-1)


def joints(config: Planar3RRPConfiguration) -> JointTable:
    """The joints of the physical mechanism over the batch (design.md §1a, §5).

    Links are :data:`LINK_NAMES`; per limb ``k`` (:data:`JOINT_PAIRS`, base to platform) the joints
    are ``limb{k}_R1`` (actuated revolute, axis ``z`` through ``M_k``: the screw ``(z; M_k × z)``),
    ``limb{k}_R2`` (revolute, axis ``z`` through the elbow ``A_k``) and ``limb{k}_P`` (prismatic
    along the guide, the infinite-pitch screw ``(0; b_k)``). The mechanism lies in the plane
    ``z = 0``; its nominal mobility is ``dof = 3`` (planar motions). The table's ``anchor`` is the
    mean of the six revolute centres, a point of that plane that moves with the mechanism (it fixes
    the reference point along ``z``, where the parallel axes do not;
    :func:`screwkit.graphs.twistgraph.graph_frame`).

    Parameters
    ----------
    config : Planar3RRPConfiguration
        Any batch shape ``...``.

    Returns
    -------
    JointTable
        Base ``"base"``, platform ``"platform"``, nine joints (three loops), ``dof = 3``; screws
        ``(..., 9, 6)``.

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`Planar3RRPConfiguration`.

    Examples
    --------
    >>> from screwkit.core.singularity import classify
    >>> c = Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.0, 0.0, 0.0])
    >>> table = joints(c)
    >>> [(spec.name, spec.type, spec.actuated) for spec in table.specs[:3]]
    [('limb1_R1', 'R', True), ('limb1_R2', 'R', False), ('limb1_P', 'P', False)]
    >>> table.joint_screws("limb1_R1")  # axis z through M_1
    array([[ 0.       ,  0.       ,  1.       , -0.5      ,  0.8660254,  0.       ]])
    >>> G = table.graph()
    >>> G.number_of_nodes(), G.number_of_edges(), G.graph["dof"], classify(G).labels
    (8, 9, 3, ())
    """
    config = _check_config(config)
    base, elbow = _in_space(config.base_points), _in_space(config.elbow_points)
    screws = {
        "R1": S.revolute_twist(_AXIS_Z, base),
        "R2": S.revolute_twist(_AXIS_Z, elbow),
        "P": S.prismatic_twist(_in_space(config.guide_directions)),
    }
    rows = [
        (LINK_NAMES[parent - 1], LINK_NAMES[child - 1], f"limb{k + 1}_{label}", label[0],
         screws[label][..., k, None, :], label == "R1")
        for k, pairs in enumerate(JOINT_PAIRS)
        for label, (parent, child) in zip(("R1", "R2", "P"), pairs, strict=True)
    ]
    anchor = np.concatenate([base, elbow], axis=-2).mean(axis=-2)
    return JointTable.from_rows(LINK_NAMES[0], LINK_NAMES[-1], rows, dof=3, anchor=anchor, mobility=3)


def twist_basis(config: Planar3RRPConfiguration) -> np.ndarray:
    """The platform's nominal (planar) twists over the batch, embedded in space (user frame).

    Rows, for ``ẋ = 1``, ``ẏ = 1`` and ``φ̇ = 1`` (the pose order ``(x, y, φ)``): the translations
    ``(0; i)``, ``(0; j)`` and the rotation ``(k; C × k)`` about the axis ``z`` through the platform
    point ``C = (x, y, 0)``. They are the columns of ``A`` in
    :func:`screwkit.core.jacobians.jacobians_from_wrenches`. Paper 003's twist ``t = (ω, ẋ, ẏ)`` (Eq. 3)
    lists the same rates with the angular rate first.

    Parameters
    ----------
    config : Planar3RRPConfiguration
        Any batch shape ``...``.

    Returns
    -------
    numpy.ndarray, shape (..., 3, 6)

    Raises
    ------
    ScrewkitTypeError
        If ``config`` is not a :class:`Planar3RRPConfiguration`.

    Examples
    --------
    >>> twist_basis(Planar3RRPConfiguration.from_pose(EXAMPLE_PARAMETERS, [0.05, -0.03, 0.1]))
    array([[ 0.  ,  0.  ,  0.  ,  1.  ,  0.  ,  0.  ],
           [ 0.  ,  0.  ,  0.  ,  0.  ,  1.  ,  0.  ],
           [ 0.  ,  0.  ,  1.  , -0.03, -0.05,  0.  ]])
    """
    config = _check_config(config)
    x, y = np.moveaxis(config.platform_point, -1, 0)
    rows = np.zeros((*x.shape, 3, 6))
    rows[..., 0, 3] = rows[..., 1, 4] = rows[..., 2, 2] = 1.0
    rows[..., 2, 3], rows[..., 2, 4] = y, -x  # C × k = (y, -x, 0)
    return rows


#: The family (:mod:`screwkit.robots.families`).
FAMILY: Family[Planar3RRPParameters, Planar3RRPConfiguration] = Family(
    name="planar_3rrp",
    parameters=Planar3RRPParameters.from_mapping,
    inverse_kinematics=Planar3RRPConfiguration.from_pose,
    joints=joints,
    twist_basis=twist_basis,
    pose_names=("x", "y", "phi"),
    angle_names=("phi",),
    parameter_kinds=dict.fromkeys(("base_points", "link_lengths", "platform_points"), "length")
    | {"guide_angles": "angle"},
)
