"""Joints: each gives the unit twists of its child link relative to its parent, at one configuration.

A joint of a twist graph (docs/architecture.md §5) is a frozen :class:`Joint`: its type, the screws of its
twist system at the current configuration (rows ``(dof, 6)``, conventions in
:mod:`screwkit.algebra.screw`), whether it is actuated, whether it is *virtual* (a member of an equivalent
chain derived by :func:`screwkit.graphs.reduction.equivalent_twist_graph`, paper 002 Fig. 2b–3), and the
geometric data it was built from (kept for reports and for saving graphs).

===========  ======  =================================================================================
type         dof     twists (paper 002 §3; Hunt 1978)
===========  ======  =================================================================================
``R``        1       zero-pitch screw on the axis
``P``        1       infinite-pitch screw ``(0; d)``
``H``        1       screw of pitch h on the axis (h = lead / 2π)
``C``        2       the R and the P of one axis
``U``        2       two zero-pitch screws through the centre
``S``        3       three zero-pitch screws through the centre
``Pa``       1       planar parallelogram Π: the coupler translates along ``hinge × rod`` (paper 004 §2)
``virtual``  k       any screws (an equivalent chain's member); type ``"vR"``/``"vP"``/``"vH"`` by pitch
===========  ======  =================================================================================

Examples
--------
>>> hinge = revolute("A1", axis=[1, 0, 0], point=[0, 0, 0], actuated=True)
>>> hinge.dof, hinge.actuated
(1, True)
>>> spherical("S_m", center=[1, 2, 3]).screws.shape
(3, 6)
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..algebra.branch_values import float_lists, plain
from ..algebra.zero_tests import unit_directions, vanishes, zero_vectors
from ..exceptions import ScrewkitTypeError, ScrewkitValueError

__all__ = [
    "JOINT_FIELDS",
    "JOINT_TYPES",
    "PARALLEL_RTOL",
    "Joint",
    "cylindrical",
    "helical",
    "lead_to_pitch",
    "parallelogram",
    "prismatic",
    "revolute",
    "spherical",
    "universal",
    "virtual",
]

#: Joint types and their degrees of freedom (None: any, for virtual joints).
JOINT_TYPES: dict[str, int | None] = {
    "R": 1,
    "P": 1,
    "H": 1,
    "C": 2,
    "U": 2,
    "S": 3,
    "Pa": 1,
    "vR": 1,
    "vP": 1,
    "vH": 1,
}

Array = np.ndarray

#: Relative tolerance below which two axes count as parallel when a joint is built (a U joint
#: needs non-parallel axes, a parallelogram rods not parallel to its hinges): the sine of the angle.
PARALLEL_RTOL = 1e-12


#: The data each joint type is built from (its constructor's arguments), in file order: the fields
#: of a ``[[joints]]`` table of a snapshot file (read by :mod:`screwkit.robots.snapshot`, written by
#: :mod:`screwkit.interface.export`); kept in ``Joint.geometry`` by the constructors.
JOINT_FIELDS: dict[str, tuple[str, ...]] = {
    "R": ("axis", "point"),
    "P": ("direction",),
    "H": ("axis", "point", "pitch"),
    "C": ("axis", "point"),
    "U": ("first_axis", "second_axis", "center"),
    "S": ("center",),
    "Pa": ("hinge_axis", "rod_direction"),
}


@dataclass(frozen=True, slots=True, eq=False)
class Joint:
    """A joint at one configuration: the unit twists it allows (child relative to parent).

    Build joints with the module's constructors (:func:`revolute`, ...), which check their input.

    Parameters
    ----------
    name : str
        Unique within a twist graph (it is the edge key).
    type : str
        One of :data:`JOINT_TYPES`.
    screws : array_like, shape (dof, 6)
        Twists of the joint at the current configuration, in the graph's frame.
    actuated : bool
        True for an actuated (input) joint; only one-degree-of-freedom joints can be actuated.
    virtual : bool
        True for the members of an equivalent chain derived from a closed sub-loop.
    geometry : dict
        The data the joint was built from (axis, point, pitch, ...), plain floats.

    Examples
    --------
    >>> joint = prismatic("P1", direction=[0, 0, 2])
    >>> joint.screws
    array([[0., 0., 0., 0., 0., 1.]])
    >>> joint.screws[0, 0] = 1
    Traceback (most recent call last):
    ...
    ValueError: assignment destination is read-only
    """

    name: str
    type: str
    screws: Array
    actuated: bool = False
    virtual: bool = False
    geometry: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        if not isinstance(self.name, str) or not self.name:
            raise ScrewkitTypeError(f"Expected the joint `name` to be a non-empty string, got {self.name!r}.")
        if self.type not in JOINT_TYPES:
            raise ScrewkitValueError(
                f"Joint {self.name!r}: expected `type` to be one of {sorted(JOINT_TYPES)}, got {self.type!r}."
            )
        rows = B.as_array(self.screws, f"screws of joint {self.name!r}", (6,)).reshape(-1, 6)
        expected = JOINT_TYPES[self.type]
        if expected is not None and rows.shape[0] != expected:
            raise ScrewkitValueError(
                f"Joint {self.name!r} of type {self.type}: expected {expected} screw(s), got {rows.shape[0]}."
            )
        if np.any(zero_vectors(rows)):
            raise ScrewkitValueError(f"Joint {self.name!r}: expected non-zero screws, got a zero row.")
        if not isinstance(self.actuated, bool | np.bool_) or not isinstance(self.virtual, bool | np.bool_):
            flag, value = (
                ("actuated", self.actuated)
                if not isinstance(self.actuated, bool | np.bool_)
                else (
                    "virtual",
                    self.virtual,
                )
            )
            raise ScrewkitTypeError(
                f"Joint {self.name!r}: expected `{flag}` to be True or False, got {value!r}."
            )
        if bool(self.virtual) != self.type.startswith("v"):
            raise ScrewkitValueError(
                f"Joint {self.name!r}: expected `virtual` = True exactly for the virtual types vR, vP, "
                f"vH, got type {self.type!r} with virtual = {bool(self.virtual)}."
            )
        if self.actuated and self.virtual:
            raise ScrewkitValueError(
                f"Joint {self.name!r}: expected a virtual joint (a member of an equivalent chain, "
                "which no motor drives) not to be actuated, got actuated = True."
            )
        if self.actuated and rows.shape[0] != 1:
            raise ScrewkitValueError(
                f"Joint {self.name!r}: only one-degree-of-freedom joints can be actuated, "
                f"got a {self.type} joint with {rows.shape[0]}."
            )
        rows = rows.copy()
        rows.flags.writeable = False
        object.__setattr__(self, "screws", rows)
        object.__setattr__(self, "geometry", dict(self.geometry))

    @property
    def dof(self) -> int:
        """Degrees of freedom: the number of screws."""
        return int(self.screws.shape[0])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready description (used to save graphs with ``nx.node_link_data``).

        Returns
        -------
        dict
            ``name``, ``type``, ``actuated``, ``virtual``, ``screws`` (rows of floats, or of texts when
        symbolic) and ``geometry``.

        Examples
        --------
        >>> revolute("R1", [0, 0, 1], [1, 0, 0]).to_dict()["type"]
        'R'
        """
        return {
            "name": self.name,
            "type": self.type,
            "actuated": self.actuated,
            "virtual": self.virtual,
            "screws": [[plain(v) for v in row] for row in self.screws],
            "geometry": self.geometry,
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Joint:
        """Rebuild a joint from :meth:`to_dict` output (plain data only; nothing is evaluated).

        Parameters
        ----------
        data : dict
            The output of :meth:`to_dict` (e.g. read back from JSON).

        Returns
        -------
        Joint

        Raises
        ------
        ScrewkitTypeError
            For data that is not a dict, or flags that are not booleans.
        ScrewkitValueError
            For missing fields or screws that are not numbers (texts are not evaluated).

        Examples
        --------
        >>> joint = revolute("R1", [0, 0, 1], [1, 0, 0])
        >>> Joint.from_dict(joint.to_dict()).screws
        array([[ 0.,  0.,  1.,  0., -1.,  0.]])
        """
        if not isinstance(data, dict):
            raise ScrewkitTypeError(
                f"Expected `data` to be a dict of joint fields, got {type(data).__name__}."
            )
        missing = {"name", "type", "screws"} - set(data)
        if missing:
            raise ScrewkitValueError(
                f"Expected joint data with fields {sorted(missing)}, got {sorted(data)}."
            )
        try:  # numbers only: a text (a symbolic joint's, or "1") is not evaluated
            screws = B.as_array(data["screws"], "screws", (6,), symbolic=False)
        except (TypeError, ValueError) as err:
            raise ScrewkitValueError(
                f"Joint {data['name']!r}: expected numeric screws, got {data['screws']!r} "
                "(symbolic joints are not loaded: nothing is evaluated)."
            ) from err
        return cls(
            name=data["name"],
            type=data["type"],
            screws=screws,
            actuated=data.get("actuated", False),
            virtual=data.get("virtual", False),
            geometry=dict(data.get("geometry", {})),
        )

    def __str__(self) -> str:
        flags = " actuated" if self.actuated else ""
        flags += " virtual" if self.virtual else ""
        return f"{self.type} joint {self.name!r}{flags}"


def _unit_axis(axis: Any) -> Any:
    """A numeric axis scaled to unit length; a symbolic axis is kept as given, so that symbolic screws
    stay polynomial (:func:`screwkit.algebra.zero_tests.unit_directions`). A zero axis is refused."""
    return unit_directions(S.line(axis, [0, 0, 0])[:3])


def revolute(name: str, axis: Any, point: Any, *, actuated: bool = False) -> Joint:
    """A revolute joint R: the zero-pitch twist on its axis.

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    axis : array_like, shape (3,)
        The axis direction (non-zero).
    point : array_like, shape (3,)
        A point of the axis.
    actuated : bool, default False
        Whether the joint is actuated.

    Returns
    -------
    Joint

    Examples
    --------
    >>> revolute("R1", [0, 0, 2], [1, 0, 0]).screws  # unit twist: the axis is normalised
    array([[ 0.,  0.,  1.,  0., -1.,  0.]])
    """
    twist = S.revolute_twist(_unit_axis(axis), point)
    geometry = float_lists(axis=axis, point=point)
    return Joint(name, "R", twist.reshape(1, 6), actuated=actuated, geometry=geometry)


def prismatic(name: str, direction: Any, *, actuated: bool = False) -> Joint:
    """A prismatic joint P: the infinite-pitch twist ``(0; d/|d|)``.

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    direction : array_like, shape (3,)
        The sliding direction (non-zero).
    actuated : bool, default False
        Whether the joint is actuated.

    Returns
    -------
    Joint

    Examples
    --------
    >>> prismatic("P1", [3, 0, 4]).screws
    array([[0. , 0. , 0. , 0.6, 0. , 0.8]])
    """
    twist = S.normalize(S.prismatic_twist(direction))
    geometry = float_lists(direction=direction)
    return Joint(name, "P", twist.reshape(1, 6), actuated=actuated, geometry=geometry)


def helical(name: str, axis: Any, point: Any, pitch: Any, *, actuated: bool = False) -> Joint:
    """A helical (screw) joint H of pitch ``h`` (length per radian: lead / 2π).

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    axis : array_like, shape (3,)
        The axis direction (non-zero).
    point : array_like, shape (3,)
        A point of the axis.
    pitch : float or sympy.Expr
        Length per radian (:func:`lead_to_pitch`).
    actuated : bool, default False
        Whether the joint is actuated.

    Returns
    -------
    Joint

    Examples
    --------
    >>> helical("H1", [0, 0, 1], [0, 0, 0], lead_to_pitch(2 * math.pi)).screws
    array([[0., 0., 1., 0., 0., 1.]])
    """
    if not isinstance(pitch, str | bytes) and np.ndim(pitch) != 0:
        raise ScrewkitValueError(
            f"Expected `pitch` to be one number (the joint's pitch), got shape {np.shape(pitch)}."
        )
    twist = S.helical_twist(S.normalize(S.line(axis, [0, 0, 0]))[:3], point, pitch)
    geometry = float_lists(axis=axis, point=point, pitch=pitch)
    return Joint(name, "H", twist.reshape(1, 6), actuated=actuated, geometry=geometry)


def lead_to_pitch(lead: float) -> float:
    """Pitch (per radian) of a screw pair from its lead (per turn): ``h = lead / 2π``.

    Parameters
    ----------
    lead : float
        Length per turn.

    Returns
    -------
    float
        Length per radian.

    Examples
    --------
    >>> round(lead_to_pitch(20.0), 6)
    3.183099
    """
    return float(lead) / (2 * math.pi)


def cylindrical(name: str, axis: Any, point: Any) -> Joint:
    """A cylindrical joint C: rotation about and translation along one axis.

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    axis : array_like, shape (3,)
        The axis direction (non-zero).
    point : array_like, shape (3,)
        A point of the axis.

    Returns
    -------
    Joint

    Examples
    --------
    >>> cylindrical("C1", [0, 0, 1], [0, 0, 0]).dof
    2
    """
    unit = S.normalize(S.line(axis, [0, 0, 0]))[:3]
    rows = np.stack([S.revolute_twist(unit, point), S.prismatic_twist(unit)])
    geometry = float_lists(axis=axis, point=point)
    return Joint(name, "C", rows, geometry=geometry)


def universal(name: str, first_axis: Any, second_axis: Any, center: Any) -> Joint:
    """A universal joint U: two revolute axes through one centre (the first on the parent side).

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    first_axis, second_axis : array_like, shape (3,)
        The directions of the two revolute axes (not parallel; the first on the parent side).
    center : array_like, shape (3,)
        The point where the axes meet.

    Returns
    -------
    Joint

    Raises
    ------
    ScrewkitValueError
        If the two axes are parallel (a U joint needs two independent rotations).

    Examples
    --------
    >>> universal("U1", [1, 0, 0], [0, 1, 0], [0, 0, 1]).dof
    2
    """
    rows = np.stack(
        [S.revolute_twist(_unit_axis(first_axis), center), S.revolute_twist(_unit_axis(second_axis), center)]
    )
    first, second = rows[0, :3], rows[1, :3]
    if vanishes(B.cross(first, second), first, second, rtol=PARALLEL_RTOL):
        raise ScrewkitValueError(
            f"Universal joint {name!r}: expected two non-parallel axes, got parallel axes."
        )
    geometry = float_lists(first_axis=first_axis, second_axis=second_axis, center=center)
    return Joint(name, "U", rows, geometry=geometry)


def spherical(name: str, center: Any) -> Joint:
    """A spherical joint S: three rotations about axes through its centre.

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    center : array_like, shape (3,)
        The centre.

    Returns
    -------
    Joint

    Examples
    --------
    >>> spherical("S1", [0, 0, 0]).screws[:, :3]
    array([[1., 0., 0.],
           [0., 1., 0.],
           [0., 0., 1.]])
    """
    axes, centre = B.promote(np.eye(3), B.as_array(center, "center", (3,)))
    rows = np.stack([S.revolute_twist(a, centre) for a in axes])
    geometry = float_lists(center=center)
    return Joint(name, "S", rows, geometry=geometry)


def parallelogram(name: str, hinge_axis: Any, rod_direction: Any, *, actuated: bool = False) -> Joint:
    """A planar parallelogram Π with revolute hinges: the coupler translates along ``hinge × rod``.

    The four hinge axes are parallel to ``hinge_axis`` and the rods to ``rod_direction``; the
    coupler keeps its orientation and moves on a circle (a curvilinear translation, paper 004 §2),
    so its instantaneous twist is the pure translation ``(0; a × w)``.

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    hinge_axis : array_like, shape (3,)
        The direction of the hinges' axes.
    rod_direction : array_like, shape (3,)
        The direction of the rods (not parallel to the hinges).
    actuated : bool, default False
        Whether the joint is actuated.

    Returns
    -------
    Joint

    Raises
    ------
    ScrewkitValueError
        If the rods are parallel to the hinges (no parallelogram).

    Examples
    --------
    >>> parallelogram("Pi1", [1, 0, 0], [0, 0, -1]).screws + 0.0
    array([[0., 0., 0., 0., 1., 0.]])
    """
    a = B.as_array(hinge_axis, "hinge_axis", (3,))
    w = B.as_array(rod_direction, "rod_direction", (3,))
    a, w = B.promote(a, w)
    velocity = B.cross(a, w)
    if vanishes(velocity, a, w, rtol=PARALLEL_RTOL):
        raise ScrewkitValueError(
            f"Parallelogram {name!r}: expected rods not parallel to the hinge axes, got parallel ones."
        )
    twist = S.prismatic_twist(unit_directions(velocity))
    geometry = float_lists(hinge_axis=a, rod_direction=w)
    return Joint(name, "Pa", twist.reshape(1, 6), actuated=actuated, geometry=geometry)


def virtual(name: str, screw: Any) -> Joint:
    """A virtual one-degree-of-freedom joint carrying one screw, typed by its pitch (vR, vP, vH).

    Parameters
    ----------
    name : str
        The joint's name (unique in a graph).
    screw : array_like, shape (6,)
        The screw it carries (floats or sympy expressions).

    Returns
    -------
    Joint

    Examples
    --------
    >>> virtual("v1", [0, 0, 0, 0, 0, 1]).type
    'vP'
    """
    row = B.as_array(screw, "screw", (6,)).reshape(1, 6)
    kind = "vP" if S.is_infinite_pitch(row[0]) else ("vR" if S.is_zero_pitch(row[0]) else "vH")
    return Joint(name, kind, row, virtual=True)
