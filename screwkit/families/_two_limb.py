"""Machinery shared by the two-limb Schönflies-motion generators (McGill SMG and Peppermill).

Private module: :mod:`screwkit.families.mcgill_smg` and :mod:`screwkit.families.peppermill`
re-export what users need. It holds

* parameter validation (``from_mapping`` of a TOML table, range checks in ``__post_init__``);
* :class:`JointAxis`, one physical joint of a configuration (axis point, unit direction, pitch in
  the screw convention of :mod:`screwkit.screw`, the two links it joins) with its unit twist;
* :class:`ForwardSolutions`, every assembly mode of a forward-kinematics problem;
* :class:`Jacobians` and :class:`Classification`: the Gosselin-Angeles types from ``A t = B θ̇``;
* :func:`joint_twist_graph`, the twist graph of the physical mechanism built from those joints,
  and :func:`gosselin_angeles_label`, which names a twist-graph verdict in the papers' terms;
* :func:`bisect_segment`, the root search used to locate singularities along a path;
* :func:`pick_and_place_cycle`, the SCARA test cycle of papers 001 (Sec. 6) and 000 (Sec. 1).

Closeness to a singularity
--------------------------
Both papers write the velocity relation ``A t = B θ̇`` with dimensionless (or unit-normalised)
matrices. :func:`classify_jacobians` measures the closeness of each matrix to rank deficiency by its
*inverse condition number* ``σ_min / σ_max`` (smallest over largest singular value):

* it lies in ``[0, 1]`` and is 0 exactly when the matrix loses rank (Gosselin and Angeles 1990:
  ``det B = 0`` inverse/serial, ``det A = 0`` direct/parallel, both: combined);
* it does not change with the unit of length, provided the characteristic length that makes the
  matrix dimensionless is given in the same unit (each family documents its choice);
* it does not change under a rigid motion of the base frame, which multiplies ``A`` and ``B`` by
  orthogonal matrices.

Examples
--------
>>> import numpy as np
>>> from screwkit.families._two_limb import classify_jacobians
>>> c = classify_jacobians(np.eye(4), np.diag([1.0, 1.0, 0.0, 1.0]), rtol=1e-9)
>>> str(c.label)
'inverse'
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from dataclasses import MISSING, dataclass, fields
from typing import Any, TypeVar

import networkx as nx
import numpy as np

from .. import joints as J
from .. import screw as S
from .._backend import DEFAULT_RTOL, as_array
from ..exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError
from ..twistgraph import twist_graph

__all__ = [
    "JOINT_KINDS",
    "LABELS",
    "Classification",
    "ForwardSolutions",
    "Jacobians",
    "JointAxis",
    "bisect_segment",
    "check_parameters",
    "checked_mode",
    "classify_jacobians",
    "describe_indices",
    "frozen",
    "gosselin_angeles_label",
    "joint_twist_graph",
    "parameters_from_mapping",
    "pick_and_place_cycle",
    "wrap_angle",
]

#: Joint kinds a :class:`JointAxis` may have: revolute, helical, prismatic.
JOINT_KINDS = ("R", "H", "P")
#: Labels returned by :attr:`Classification.label` (Gosselin and Angeles 1990).
LABELS = ("regular", "inverse", "direct", "combined")

_P = TypeVar("_P")
#: Metadata a catalog passes with the parameters (checked, not stored).
_METADATA = ("name", "length_unit")


def frozen(value: Any, dtype: Any = float) -> np.ndarray:
    """Return a read-only copy of ``value`` as an array of ``dtype``.

    Examples
    --------
    >>> frozen([1, 2]).flags.writeable
    False
    """
    array = np.array(value, dtype=dtype, copy=True)
    array.setflags(write=False)
    return array


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    """Wrap angles into ``[-π, π)``.

    Examples
    --------
    >>> wrap_angle(np.array([3 * np.pi / 2, -np.pi]))
    array([-1.57079633, -3.14159265])
    """
    return (np.asarray(angle) + np.pi) % (2.0 * np.pi) - np.pi


def describe_indices(mask: np.ndarray, limit: int = 5) -> str:
    """List (up to ``limit``) batch indices where ``mask`` is True, for error messages.

    Examples
    --------
    >>> describe_indices(np.array([False, True, True]))
    'batch index (1,), (2,)'
    >>> describe_indices(np.array(True))
    'the pose'
    """
    if mask.ndim == 0:
        return "the pose"
    where = [tuple(int(i) for i in idx) for idx in np.argwhere(mask)]
    shown = ", ".join(str(w) for w in where[:limit])
    more = f" and {len(where) - limit} more" if len(where) > limit else ""
    return f"batch index {shown}{more}"


# --------------------------------------------------------------------------------------------------
# Parameters
# --------------------------------------------------------------------------------------------------


def _is_real(value: Any) -> bool:
    return isinstance(value, int | float | np.integer | np.floating) and not isinstance(
        value, bool | np.bool_
    )


def check_parameters(
    instance: Any,
    *,
    positive: tuple[str, ...] = (),
    nonnegative: tuple[str, ...] = (),
    real: tuple[str, ...] = (),
) -> None:
    """Validate the numeric fields of a frozen parameters dataclass and store them as floats.

    Parameters
    ----------
    instance : dataclass instance
        Called from its ``__post_init__``.
    positive, nonnegative, real : tuple of str
        Field names that must be > 0, >= 0, or merely finite.

    Raises
    ------
    ScrewkitTypeError
        A field is not a real number (booleans are refused).
    ScrewkitValueError
        A field is not finite or out of range.

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Link:
    ...     length: float
    ...     def __post_init__(self):
    ...         check_parameters(self, positive=("length",))
    >>> Link(2).length
    2.0
    >>> Link(-1.0)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected parameter `length` of Link to be > 0, got -1.0.
    """
    owner = type(instance).__name__
    for name in (*positive, *nonnegative, *real):
        value = getattr(instance, name)
        if not _is_real(value):
            raise ScrewkitTypeError(
                f"Expected parameter `{name}` of {owner} to be a real number, got "
                f"{type(value).__name__} {value!r}."
            )
        number = float(value)
        if not math.isfinite(number):
            raise ScrewkitValueError(
                f"Expected parameter `{name}` of {owner} to be finite, got {value!r}."
            )
        if name in positive and number <= 0:
            raise ScrewkitValueError(
                f"Expected parameter `{name}` of {owner} to be > 0, got {value!r}."
            )
        if name in nonnegative and number < 0:
            raise ScrewkitValueError(
                f"Expected parameter `{name}` of {owner} to be >= 0, got {value!r}."
            )
        object.__setattr__(instance, name, number)


def parameters_from_mapping(cls: type[_P], mapping: Any, source: str) -> _P:
    """Build a numeric parameters dataclass from a mapping, naming ``source`` in every error.

    Parameters
    ----------
    cls : type
        A dataclass whose fields are all real numbers.
    mapping : Mapping
        Field name to value, e.g. a table read with :mod:`tomllib`; optionally the metadata
        ``name`` and ``length_unit`` (non-empty strings), which
        :func:`screwkit.catalog.load_mechanism` passes to every family (not stored here: the
        catalog's :class:`~screwkit.catalog.Mechanism` keeps them).
    source : str
        Where the mapping comes from (a file name), quoted in error messages.

    Raises
    ------
    CatalogError
        ``mapping`` is not a mapping, or has unknown, missing or non-numeric fields.
    ScrewkitValueError
        A value is out of range (the dataclass's own message, prefixed with ``source``).

    Examples
    --------
    >>> from dataclasses import dataclass
    >>> @dataclass(frozen=True)
    ... class Link:
    ...     length: float
    >>> parameters_from_mapping(Link, {"length": "2"}, "robot.toml")
    Traceback (most recent call last):
    ...
    screwkit.exceptions.CatalogError: robot.toml: expected field `length` of Link to be a real ...
    >>> parameters_from_mapping(Link, {"length": 2.0, "name": "arm", "length_unit": "m"}, "r.toml")
    Link(length=2.0)
    """
    owner = cls.__name__
    if not isinstance(mapping, Mapping):
        raise CatalogError(
            f"{source}: expected a mapping of {owner} fields, got {type(mapping).__name__}."
        )
    names = [f.name for f in fields(cls)]  # type: ignore[arg-type]
    for key in _METADATA:
        if key in mapping and (not isinstance(mapping[key], str) or not mapping[key].strip()):
            raise CatalogError(
                f"{source}: expected metadata field `{key}` to be a non-empty string, got "
                f"{mapping[key]!r}."
            )
    mapping = {key: value for key, value in mapping.items() if key not in _METADATA}
    unknown = sorted(str(key) for key in mapping if key not in names)
    if unknown:
        raise CatalogError(
            f"{source}: unknown field(s) {unknown} for {owner}; expected fields {sorted(names)}."
        )
    required = [f.name for f in fields(cls) if f.default is MISSING]  # type: ignore[arg-type]
    missing = [name for name in required if name not in mapping]
    if missing:
        raise CatalogError(f"{source}: missing field(s) {missing} for {owner}.")
    for key, value in mapping.items():
        if not _is_real(value):
            raise CatalogError(
                f"{source}: expected field `{key}` of {owner} to be a real number, got "
                f"{type(value).__name__} {value!r}."
            )
    try:
        return cls(**mapping)
    except ScrewkitValueError as err:
        raise ScrewkitValueError(f"{source}: {err}") from err


def checked_mode(mode: Any, name: str, length: int) -> tuple[int, ...]:
    """Validate a working or assembly mode: a tuple of ``length`` signs, each +1 or -1.

    Examples
    --------
    >>> checked_mode([1, -1], "mode", 2)
    (1, -1)
    >>> checked_mode((1, 0), "mode", 2)
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `mode` to be a sequence of 2 signs ... (1, 0).
    """
    try:
        signs = tuple(mode)
    except TypeError:
        signs = None
    if (
        signs is None
        or len(signs) != length
        or not all(_is_real(s) and s in (1, -1) for s in signs)
    ):
        shown = signs if signs is not None else mode
        raise ScrewkitValueError(
            f"Expected `{name}` to be a sequence of {length} signs (+1 or -1), got {shown!r}."
        )
    return tuple(int(s) for s in signs)


# --------------------------------------------------------------------------------------------------
# Joints, forward solutions, Jacobians, classification
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, slots=True, eq=False)
class JointAxis:
    """One physical one-degree-of-freedom joint of a configuration, batched over poses.

    Attributes
    ----------
    name : str
        Unique within the mechanism, e.g. ``"I.proximal.a"``.
    kind : {"R", "H", "P"}
        Revolute, helical or prismatic (a cylindrical joint is listed as its P and its R).
    parent, child : str
        The links it joins; its screw is the unit twist of ``child`` relative to ``parent``.
    point : (..., 3) ndarray
        A point of the axis.
    direction : (..., 3) ndarray
        Unit direction of the axis.
    pitch : float
        Pitch ``h`` in the convention ``(s; r × s + h s)`` of :mod:`screwkit.screw` (length per
        radian); 0 unless ``kind == "H"``.
    actuated : bool
        Whether a motor drives it.

    Examples
    --------
    >>> joint = JointAxis("spin", "H", "base", "nut", [0, 0, 0], [0, 0, 1], pitch=0.5)
    >>> joint.screw()
    array([0. , 0. , 1. , 0. , 0. , 0.5])
    """

    name: str
    kind: str
    parent: str
    child: str
    point: np.ndarray
    direction: np.ndarray
    pitch: float = 0.0
    actuated: bool = False

    def __post_init__(self) -> None:
        if self.kind not in JOINT_KINDS:
            raise ScrewkitValueError(
                f"Expected `kind` of joint {self.name!r} to be one of {JOINT_KINDS}, "
                f"got {self.kind!r}."
            )
        if self.kind != "H" and self.pitch != 0:
            raise ScrewkitValueError(
                f"Expected `pitch` of {self.kind} joint {self.name!r} to be 0, got {self.pitch!r}."
            )
        point = as_array(self.point, f"point of joint {self.name!r}", (3,))
        direction = as_array(self.direction, f"direction of joint {self.name!r}", (3,))
        length = np.linalg.norm(direction, axis=-1)
        if not np.allclose(length, 1.0, rtol=0.0, atol=1e-9):
            raise ScrewkitValueError(
                f"Expected `direction` of joint {self.name!r} to be a unit vector, got norms "
                f"between {float(length.min()):.6g} and {float(length.max()):.6g}."
            )
        object.__setattr__(self, "point", frozen(point))
        object.__setattr__(self, "direction", frozen(direction))
        object.__setattr__(self, "pitch", float(self.pitch))

    def screw(self) -> np.ndarray:
        """Unit twist of the joint, shape ``(..., 6)`` (from :mod:`screwkit.screw` kernels)."""
        if self.kind == "P":
            return S.prismatic_twist(self.direction)
        return S.helical_twist(self.direction, self.point, self.pitch)


@dataclass(frozen=True, slots=True, eq=False)
class ForwardSolutions:
    """Every assembly of a parallel robot for given actuated joint values.

    Slots that hold no real assembly have ``valid`` False and are *masked* in ``poses`` and
    ``passive`` (numpy masked arrays, filled with 0): no NaN is ever returned. Select the real
    assemblies with ``poses[valid]`` (or ``poses.compressed()``).

    Attributes
    ----------
    poses : (..., m, 4) numpy.ma.MaskedArray
        ``(x, y, z, φ)`` of each assembly.
    passive : (..., m, k) numpy.ma.MaskedArray
        Passive joint values of each assembly (the family documents their order).
    working_modes : (..., m, n) ndarray of int
        Signs labelling the inverse-kinematics branch each assembly lies on (0 on a singularity
        or an invalid slot).
    valid : (..., m) ndarray of bool

    Examples
    --------
    >>> sol = ForwardSolutions(np.zeros((2, 4)), np.zeros((2, 1)), np.ones((2, 1)), [True, False])
    >>> sol.count
    array(1)
    """

    poses: np.ndarray
    passive: np.ndarray
    working_modes: np.ndarray
    valid: np.ndarray

    def __post_init__(self) -> None:
        valid = np.asarray(self.valid, dtype=bool)
        object.__setattr__(self, "valid", frozen(valid, bool))
        for name in ("poses", "passive"):
            array = np.array(getattr(self, name), dtype=float)
            mask = np.broadcast_to(~valid[..., None], array.shape)
            array = np.where(mask | ~np.isfinite(array), 0.0, array)
            masked = np.ma.MaskedArray(frozen(array), mask=mask.copy())
            object.__setattr__(self, name, masked)
        modes = np.where(valid[..., None], np.asarray(self.working_modes), 0)
        object.__setattr__(self, "working_modes", frozen(modes, np.int8))

    @property
    def count(self) -> np.ndarray:
        """Number of valid assemblies, shape ``(...)``."""
        return np.asarray(self.valid.sum(axis=-1))


@dataclass(frozen=True, slots=True, eq=False)
class Jacobians:
    """The forward Jacobian ``A`` and the inverse Jacobian ``B`` of ``A t = B θ̇``.

    Attributes
    ----------
    A, B : ndarray
        Read-only, batched over leading axes; shapes as each family documents.

    Examples
    --------
    >>> Jacobians(np.eye(2), np.eye(2)).A.flags.writeable
    False
    """

    A: np.ndarray
    B: np.ndarray

    def __post_init__(self) -> None:
        object.__setattr__(self, "A", frozen(self.A))
        object.__setattr__(self, "B", frozen(self.B))


def _closeness(matrix: np.ndarray) -> np.ndarray:
    values = np.linalg.svd(matrix, compute_uv=False)
    largest = values[..., 0]
    return np.asarray(np.where(largest > 0, values[..., -1] / np.where(largest > 0, largest, 1), 0))


@dataclass(frozen=True, slots=True, eq=False)
class Classification:
    """Gosselin-Angeles type of one or many configurations.

    Attributes
    ----------
    inverse_closeness, direct_closeness : (...) ndarray
        ``σ_min/σ_max`` of ``B`` and of ``A`` (see the module docstring), in ``[0, 1]``.
    rtol : float
        A matrix counts as singular when its closeness is at most ``rtol``.

    Examples
    --------
    >>> c = Classification(np.array([0.5, 0.0]), np.array([0.0, 0.0]), 1e-9)
    >>> c.label.tolist()
    ['direct', 'combined']
    """

    inverse_closeness: np.ndarray
    direct_closeness: np.ndarray
    rtol: float

    def __post_init__(self) -> None:
        object.__setattr__(self, "inverse_closeness", frozen(self.inverse_closeness))
        object.__setattr__(self, "direct_closeness", frozen(self.direct_closeness))

    @property
    def inverse(self) -> np.ndarray:
        """True where ``B`` is rank-deficient (inverse-kinematic, serial, first kind)."""
        return np.asarray(self.inverse_closeness <= self.rtol)

    @property
    def direct(self) -> np.ndarray:
        """True where ``A`` is rank-deficient (direct-kinematic, parallel, second-kind)."""
        return np.asarray(self.direct_closeness <= self.rtol)

    @property
    def label(self) -> np.ndarray:
        """One of :data:`LABELS` per configuration (``"combined"``: both; third kind)."""
        index = self.inverse.astype(int) + 2 * self.direct.astype(int)
        return np.asarray(np.array(LABELS)[index], dtype=f"<U{max(map(len, LABELS))}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {
            "label": self.label.tolist(),
            "inverse_closeness": self.inverse_closeness.tolist(),
            "direct_closeness": self.direct_closeness.tolist(),
            "rtol": self.rtol,
        }

    def __str__(self) -> str:
        return (
            f"Classification(label={self.label.tolist()}, "
            f"inverse_closeness={np.round(self.inverse_closeness, 6).tolist()}, "
            f"direct_closeness={np.round(self.direct_closeness, 6).tolist()})"
        )


def classify_jacobians(
    A: np.ndarray, B: np.ndarray, *, rtol: float = DEFAULT_RTOL
) -> Classification:
    """Classify from the (dimensionless) Jacobians ``A`` and ``B`` of ``A t = B θ̇``.

    Parameters
    ----------
    A, B : (..., m, n) ndarray
    rtol : float, default 1e-9
        Threshold on ``σ_min/σ_max``; must lie in ``[0, 1)``.

    Returns
    -------
    Classification

    Examples
    --------
    >>> classify_jacobians(np.eye(3), np.eye(3)).label.tolist()
    'regular'
    """
    if not (_is_real(rtol) and 0 <= float(rtol) < 1):
        raise ScrewkitValueError(f"Expected `rtol` to be a number in [0, 1), got {rtol!r}.")
    return Classification(_closeness(B), _closeness(A), float(rtol))


# --------------------------------------------------------------------------------------------------
# Twist graphs of the physical mechanisms
# --------------------------------------------------------------------------------------------------


def _checked_index(index: Any, batch: tuple[int, ...]) -> tuple[int, ...]:
    picked = (index,) if isinstance(index, int | np.integer) else index
    try:
        picked = tuple(int(i) for i in picked)
    except (TypeError, ValueError):
        picked = None
    if (
        picked is None
        or len(picked) != len(batch)
        or any(not 0 <= i < n for i, n in zip(picked, batch, strict=True))
    ):
        raise ScrewkitValueError(
            f"Expected `index` to pick one pose of the batch of shape {batch}, got {index!r}."
        )
    return picked


def joint_twist_graph(
    joints: Sequence[JointAxis],
    index: Any = (),
    *,
    base: str = "base",
    platform: str = "platform",
    dof: int = 4,
) -> nx.MultiDiGraph:
    """The twist graph of a physical mechanism from its joints, at one pose of a batch.

    Each :class:`JointAxis` becomes one edge ``parent → child`` keyed by its name, carrying a
    :class:`screwkit.joints.Joint` built by :func:`~screwkit.joints.revolute`,
    :func:`~screwkit.joints.prismatic` or :func:`~screwkit.joints.helical` (same axis, point,
    pitch and ``actuated`` flag). Nothing is reduced: closed sub-loops (parallelograms) stay loops,
    for :func:`screwkit.twistgraph.equivalent_twist_graph` to find.

    Parameters
    ----------
    joints : sequence of JointAxis
        E.g. ``config.joints`` of a McGill SMG or Peppermill configuration.
    index : tuple of int or int, default ()
        Which pose of the batch (empty for a single pose).
    base, platform : str
        Names of the fixed link and of the end effector.
    dof : int, default 4
        Nominal mobility of the platform (a Schönflies motion: 3T1R).

    Returns
    -------
    networkx.MultiDiGraph

    Raises
    ------
    ScrewkitValueError
        ``index`` does not pick one pose of the joints' batch.

    Examples
    --------
    >>> spin = JointAxis("spin", "R", "base", "arm", [0, 0, 0], [0, 0, 1], actuated=True)
    >>> slide = JointAxis("slide", "P", "arm", "platform", [[0, 0, 0], [1, 0, 0]], [1, 0, 0])
    >>> G = joint_twist_graph([spin, slide], (1,), dof=2)
    >>> sorted(G.edges(keys=True)), G.graph["dof"]
    ([('arm', 'platform', 'slide'), ('base', 'arm', 'spin')], 2)
    >>> joint_twist_graph([spin, slide], (2,))
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `index` to pick one pose of the batch of ...
    """
    batch = np.broadcast_shapes(*(j.point.shape[:-1] for j in joints),
                                *(j.direction.shape[:-1] for j in joints))
    picked = _checked_index(index, tuple(batch))
    triples = []
    for joint in joints:
        point = np.broadcast_to(joint.point, (*batch, 3))[picked]
        direction = np.broadcast_to(joint.direction, (*batch, 3))[picked]
        if joint.kind == "P":
            built = J.prismatic(joint.name, direction, actuated=joint.actuated)
        elif joint.kind == "R":
            built = J.revolute(joint.name, direction, point, actuated=joint.actuated)
        else:
            built = J.helical(joint.name, direction, point, joint.pitch, actuated=joint.actuated)
        triples.append((joint.parent, joint.child, built))
    return twist_graph(base, platform, triples, dof=dof)


def gosselin_angeles_label(report: Any) -> str:
    """Name a twist-graph verdict (:func:`screwkit.singularity.classify`) in the papers' terms.

    A *serial* (limb) singularity, where an actuator cannot move the platform, is the inverse
    (first-kind) singularity of ``B``; a *constraint* or *actuation* singularity, where the
    platform moves with every actuator locked, is the direct (second-kind) singularity of ``A``;
    both at once is the combined (third-kind) one.

    Parameters
    ----------
    report : SingularityReport
        Anything with a ``labels`` tuple drawn from ``"constraint"``, ``"actuation"``,
        ``"serial"``.

    Returns
    -------
    str
        One of :data:`LABELS`.

    Examples
    --------
    >>> from types import SimpleNamespace
    >>> gosselin_angeles_label(SimpleNamespace(labels=("actuation", "serial")))
    'combined'
    """
    labels = tuple(report.labels)
    unknown = sorted(set(labels) - {"constraint", "actuation", "serial"})
    if unknown:
        raise ScrewkitValueError(
            f"Expected labels among 'constraint', 'actuation', 'serial', got {unknown}."
        )
    direct = "constraint" in labels or "actuation" in labels
    return LABELS[int("serial" in labels) + 2 * int(direct)]


# --------------------------------------------------------------------------------------------------
# Paths
# --------------------------------------------------------------------------------------------------


def bisect_segment(
    function: Callable[[np.ndarray], np.ndarray],
    start: Any,
    end: Any,
    *,
    iterations: int = 60,
) -> np.ndarray:
    """Locate a sign change of a scalar function on the straight segment from ``start`` to ``end``.

    Bisection on the segment parameter ``t ∈ [0, 1]``, vectorised over leading batch axes;
    60 halvings bring ``t`` to ``2**-60``, below the resolution of a float.

    Parameters
    ----------
    function : callable
        Maps points ``(..., n)`` to values ``(...)`` (e.g. a singularity factor of the pose).
    start, end : (..., n) array_like
        Segment ends; ``function`` must have opposite signs (or a zero) at them.
    iterations : int, default 60

    Returns
    -------
    (..., n) ndarray
        The point of the segment where ``function`` changes sign.

    Raises
    ------
    ScrewkitValueError
        ``function`` has the same strict sign at both ends of some segment.

    Examples
    --------
    >>> bisect_segment(lambda p: p[..., 0] ** 2 - 2.0, [0.0, 5.0], [2.0, 5.0])
    array([1.41421356, 5.        ])
    """
    a = as_array(start, "start", (None,))
    b = as_array(end, "end", (None,))
    a, b = np.broadcast_arrays(a, b)
    fa = np.asarray(function(a))
    fb = np.asarray(function(b))
    same = np.sign(fa) * np.sign(fb) > 0
    if np.any(same):
        raise ScrewkitValueError(
            "Expected `function` to change sign between `start` and `end`, got the same sign at "
            f"both ends at {describe_indices(same)} (values {fa[same][:3]} and {fb[same][:3]})."
        )
    lo = np.zeros(fa.shape)
    hi = np.ones(fa.shape)
    sign_lo = np.sign(fa)
    for _ in range(iterations):
        mid = 0.5 * (lo + hi)
        value = np.asarray(function(a + mid[..., None] * (b - a)))
        move_lo = np.sign(value) == sign_lo
        lo = np.where(move_lo, mid, lo)
        hi = np.where(move_lo, hi, mid)
    t = np.where(fa == 0, 0.0, np.where(fb == 0, 1.0, 0.5 * (lo + hi)))
    return np.asarray(a + t[..., None] * (b - a))


def pick_and_place_cycle(
    start: Any,
    heading: float = 0.0,
    *,
    rise: float = 25.0,
    span: float = 300.0,
    turn: float = -np.pi,
    samples_per_segment: int = 1,
) -> np.ndarray:
    """The SCARA pick-and-place test cycle as a polyline of poses ``(x, y, z, φ)``.

    Paper 001 (Angeles et al. 2006), Sec. 6: "25-mm vertical displacement up, 300-mm horizontal
    displacement with a concomitant 180° turn, 25-mm vertical displacement down", then back with
    the reversed turn; paper 000 (Harada & Angeles 2014), Sec. 1, describes the same cycle and says
    the turn is clockwise on the way out. Neither paper (Fig. 10 of paper 001 is lost in the OCR)
    gives the start pose, the direction of the horizontal segment or a motion law, so ``start`` and
    ``heading`` are the caller's, and the polyline carries no timing. Lengths are in millimetres
    by default; pass ``rise`` and ``span`` in your unit otherwise.

    Parameters
    ----------
    start : (4,) array_like
        The home pose ``(x, y, z, φ)``.
    heading : float, default 0
        Direction of the horizontal segment, angle from the x axis about z (radians).
    rise, span : float, default 25 and 300
        Vertical and horizontal displacements.
    turn : float, default -π
        Rotation during the outbound horizontal segment (negative: clockwise seen from +z).
    samples_per_segment : int, default 1
        Number of equal steps on each of the six segments.

    Returns
    -------
    (6 * samples_per_segment + 1, 4) ndarray
        Starts and ends at ``start``.

    Examples
    --------
    >>> pick_and_place_cycle([0.0, 0.0, -400.0, 0.0]).round(3)
    array([[   0.   ,    0.   , -400.   ,    0.   ],
           [   0.   ,    0.   , -375.   ,    0.   ],
           [ 300.   ,    0.   , -375.   ,   -3.142],
           [ 300.   ,    0.   , -400.   ,   -3.142],
           [ 300.   ,    0.   , -375.   ,   -3.142],
           [   0.   ,    0.   , -375.   ,    0.   ],
           [   0.   ,    0.   , -400.   ,    0.   ]])
    """
    home = as_array(start, "start", (4,))
    if home.shape != (4,):
        raise ScrewkitValueError(f"Expected `start` to have shape (4,), got {home.shape}.")
    if not (isinstance(samples_per_segment, int | np.integer) and samples_per_segment >= 1):
        raise ScrewkitValueError(
            f"Expected `samples_per_segment` to be an integer >= 1, got {samples_per_segment!r}."
        )
    heading, rise, span, turn = (
        float(as_array(v, n)) for v, n in ((heading, "heading"), (rise, "rise"),
                                          (span, "span"), (turn, "turn"))
    )
    up = np.array([0.0, 0.0, rise, 0.0])
    across = np.array([span * np.cos(heading), span * np.sin(heading), 0.0, turn])
    corners = np.cumsum([home, up, across, -up, up, -across, -up], axis=0)
    steps = np.linspace(0.0, 1.0, samples_per_segment + 1)[:-1]
    path = corners[:-1, None, :] + steps[None, :, None] * np.diff(corners, axis=0)[:, None, :]
    return np.concatenate([path.reshape(-1, 4), corners[-1:]], axis=0)
