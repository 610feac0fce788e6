"""Machinery shared by the families, written for the two-limb Schönflies-motion generators (McGill SMG
and Peppermill).

:mod:`screwkit.robots.families.mcgill_smg` and :mod:`screwkit.robots.families.peppermill` build on it
(the reach tolerance serves every family). It lives beside the families package, not in it, since
every module of that package is a family. It holds the robot-model plumbing only (families hold the
model; paper-specific analyses live in the stage modules or beside the tests that check them):

* parameter validation (``from_mapping`` of a TOML table, range checks in ``__post_init__``) and
  working-mode checks;
* :func:`joint_row`, one physical one-freedom joint (R, H or P) over a batch of poses as a row of
  :meth:`screwkit.graphs.jointtable.JointTable.from_rows`;
* :class:`ForwardSolutions`, every assembly mode of a forward-kinematics problem.

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> row = joint_row("base", "nut", "spin", "H", [0, 0, 0], [0, 0, 1], pitch=0.5)
>>> JointTable.from_rows("base", "nut", [row]).screws
array([[0. , 0. , 1. , 0. , 0. , 0.5]])
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import MISSING, dataclass, fields
from typing import Any, TypeVar

import numpy as np

from ..algebra import screw as S
from ..exceptions import CatalogError, ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "JOINT_KINDS",
    "REACH_ULPS",
    "ForwardSolutions",
    "at_reach",
    "check_parameters",
    "checked_mode",
    "describe_indices",
    "frozen",
    "joint_row",
    "parameters_from_mapping",
    "within_reach",
    "wrap_angle",
]

#: Joint kinds a :func:`joint_row` may have: revolute, helical, prismatic.
JOINT_KINDS = ("R", "H", "P")

_P = TypeVar("_P")
#: Metadata a catalog passes with the parameters (checked, not stored).
_METADATA = ("name", "length_unit")


def frozen(value: Any, dtype: Any = float) -> np.ndarray:
    """Return a read-only copy of ``value`` as an array of ``dtype``.

    Parameters
    ----------
    value : array_like
        The values.
    dtype : data-type, optional
        The array's type (default float).

    Returns
    -------
    numpy.ndarray
        A read-only copy.

    Examples
    --------
    >>> frozen([1, 2]).flags.writeable
    False
    """
    array = np.array(value, dtype=dtype, copy=True)
    array.setflags(write=False)
    return array


#: Rounding units within which a limb counts as at its reach (stretched or folded). Near its reach a
#: limb angle ``θ = arccos(c)`` is ill-conditioned: a rounding error ``δ`` of ``c`` moves ``θ`` by
#: ``sqrt(2 δ)`` (``~2e-8`` for ``δ = eps``), so an inverse kinematics that returns ``θ ~ 1e-8`` at a
#: stretched limb is as accurate as the pose allows, yet far above the rank tolerance 1e-9: the limb's
#: serial singularity would read "regular". Where ``1 - |c|`` is within this many rounding units of
#: ``c``'s computation, the limb is put at its reach exactly; its loop closes to the same rounding
#: (the closure error of the snapped angle is ``O(δ)``, quadratic in the angle change). README,
#: "Tolerance policy".
REACH_ULPS = 8.0


def at_reach(cosine: np.ndarray, condition: np.ndarray) -> np.ndarray:
    """A limb angle's cosine clipped to [-1, 1], and put at ±1 exactly where it lies within
    :data:`REACH_ULPS` rounding units of ±1 (``condition``: the sum of the absolute values of the terms
    of its numerator over its denominator, the relative size of its rounding error).

    Parameters
    ----------
    cosine : numpy.ndarray
        The computed cosines.
    condition : numpy.ndarray
        The relative size of their rounding error (broadcast against ``cosine``).

    Returns
    -------
    numpy.ndarray
        Cosines in ``[-1, 1]``, exactly ``±1`` at a limb's reach.

    Examples
    --------
    >>> at_reach(np.array([1.0 - 4e-16, 0.5, -1.0 + 1e-15, 1.0 + 1e-14]), np.ones(4))
    array([ 1. ,  0.5, -1. ,  1. ])
    >>> bool(at_reach(np.array([1.0 - 1e-12]), np.ones(1))[0] < 1.0)  # a bent limb keeps its angle
    True
    """
    clipped = np.clip(cosine, -1.0, 1.0)
    near = 1.0 - np.abs(clipped) <= REACH_ULPS * np.finfo(float).eps * np.abs(condition)
    return np.where(near, np.sign(clipped), clipped)


def within_reach(cosine: np.ndarray, condition: np.ndarray) -> np.ndarray:
    """Where a limb angle's cosine is a cosine to rounding: ``|c| <= 1``, or beyond by at most the
    :data:`REACH_ULPS` rounding units that :func:`at_reach` puts back at ``±1`` (a limb stretched
    exactly to its reach, whose ``c`` rounded to ``1 + 2e-16``, is at its reach, not out of it).

    Parameters
    ----------
    cosine : numpy.ndarray
        The computed cosines.
    condition : numpy.ndarray
        The relative size of their rounding error (broadcast against ``cosine``).

    Returns
    -------
    numpy.ndarray of bool
        True where the limb reaches (to rounding).

    Examples
    --------
    >>> within_reach(np.array([1.0 + 4e-16, -1.0 - 1e-15, 1.0 + 1e-12, 0.5]), np.ones(4))
    array([ True,  True, False,  True])
    """
    return np.abs(cosine) - 1.0 <= REACH_ULPS * np.finfo(float).eps * np.abs(condition)


def wrap_angle(angle: np.ndarray) -> np.ndarray:
    """Wrap angles into ``[-π, π)``.

    Parameters
    ----------
    angle : numpy.ndarray
        Angles in radians.

    Returns
    -------
    numpy.ndarray
        The same angles in ``[-π, π)``.

    Examples
    --------
    >>> wrap_angle(np.array([3 * np.pi / 2, -np.pi]))
    array([-1.57079633, -3.14159265])
    """
    return (np.asarray(angle) + np.pi) % (2.0 * np.pi) - np.pi


def describe_indices(mask: np.ndarray, limit: int = 5) -> str:
    """List (up to ``limit``) batch indices where ``mask`` is True, for error messages.

    Parameters
    ----------
    mask : numpy.ndarray of bool
        Over a batch.
    limit : int, optional
        How many indices to list (default 5).

    Returns
    -------
    str
        The first indices, and how many more there are.

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


def parameters_from_mapping(dataclass_type: type[_P], mapping: Any, source: str) -> _P:
    """Build a numeric parameters dataclass from a mapping, naming ``source`` in every error.

    Parameters
    ----------
    dataclass_type : type
        A dataclass whose fields are all real numbers.
    mapping : Mapping
        Field name to value, e.g. a table read with :mod:`tomllib`; optionally the metadata
        ``name`` and ``length_unit`` (non-empty strings), which
        :func:`screwkit.robots.catalog.load_mechanism` passes to every family (not stored here: the
        catalog's :class:`~screwkit.robots.mechanism.Mechanism` keeps them).
    source : str
        Where the mapping comes from (a file name), quoted in error messages.

    Returns
    -------
    object
        An instance of ``dataclass_type``.

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
    owner = dataclass_type.__name__
    if not isinstance(mapping, Mapping):
        raise CatalogError(
            f"{source}: expected a mapping of {owner} fields, got {type(mapping).__name__}."
        )
    names = [f.name for f in fields(dataclass_type)]  # type: ignore[arg-type]
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
    required = [f.name for f in fields(dataclass_type) if f.default is MISSING]  # type: ignore[arg-type]
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
        return dataclass_type(**mapping)
    except ScrewkitValueError as err:
        raise ScrewkitValueError(f"{source}: {err}") from err


def checked_mode(mode: Any, name: str, length: int) -> tuple[int, ...]:
    """Validate a working or assembly mode: a tuple of ``length`` signs, each +1 or -1.

    Parameters
    ----------
    mode : sequence of int
        The signs.
    name : str
        The argument's name, for the error message.
    length : int
        How many signs.

    Returns
    -------
    tuple of int
        The signs as Python ints.

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
# Joints and forward solutions
# --------------------------------------------------------------------------------------------------


def joint_row(
    parent: str,
    child: str,
    name: str,
    kind: str,
    point: Any,
    direction: Any,
    *,
    pitch: float = 0.0,
    actuated: bool = False,
) -> tuple[str, str, str, str, np.ndarray, bool]:
    """One physical one-freedom joint over a batch of poses, as a row of a joint table.

    Parameters
    ----------
    parent, child : str
        The links it joins; its screw is the unit twist of ``child`` relative to ``parent``.
    name : str
        Unique within the mechanism, e.g. ``"I.proximal.a"``.
    kind : {"R", "H", "P"}
        Revolute, helical or prismatic (a cylindrical joint is listed as its P and its R).
    point, direction : (..., 3) array_like
        A point of the axis (unused for P) and the axis's unit direction.
    pitch : float, default 0
        ``h`` in the convention ``(s; r × s + h s)`` of :mod:`screwkit.algebra.screw` (length per radian);
        0 unless ``kind == "H"``.
    actuated : bool, default False

    Returns
    -------
    tuple
        ``(parent, child, name, kind, screws (..., 1, 6), actuated)`` for
        :meth:`screwkit.graphs.jointtable.JointTable.from_rows`.

    Raises
    ------
    ScrewkitValueError
        Unknown ``kind``, or a pitch on a joint that is not helical.

    Examples
    --------
    >>> joint_row("a", "b", "slide", "P", [1, 2, 3], [0, 1, 0])[4]
    array([[0., 0., 0., 0., 1., 0.]])
    >>> joint_row("a", "b", "x", "C", [0, 0, 0], [0, 0, 1])
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `kind` of joint 'x' to be one of ('R', 'H', 'P'), ...
    """
    if kind not in JOINT_KINDS:
        raise ScrewkitValueError(
            f"Expected `kind` of joint {name!r} to be one of {JOINT_KINDS}, got {kind!r}."
        )
    if kind != "H" and pitch != 0:
        raise ScrewkitValueError(f"Expected `pitch` of {kind} joint {name!r} to be 0, got {pitch!r}.")
    if kind == "P":
        screw = S.prismatic_twist(direction)
    elif kind == "R":
        screw = S.revolute_twist(direction, point)
    else:
        screw = S.helical_twist(direction, point, pitch)
    return (parent, child, name, kind, np.asarray(screw)[..., None, :], actuated)


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


