"""The limbs of a loop-closure mechanism as serial chains of screw exponentials, evaluated over
interval boxes (:mod:`screwkit.analysis.loop_closure_enclosure`): each limb's loop residual against the
platform's displacement at a pose, and its joint twists.

Every constant is enclosed from the twist graph's own numbers (its screws, the model's reference point
and characteristic length, the coordinates' point) by interval arithmetic, so the enclosures hold the
mechanism exactly as the graph gives it; a float that is exactly 0 in the graph is an exact zero
(None), which keeps a planar mechanism's out-of-plane components exact. Limbs with the same sequence
of factors are *grouped* and evaluated as one batch (the group's limbs one after another along the
batch axis, each with its own constants): one pass of interval operations for the six legs of a
Gough-Stewart platform.

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> m = sk.mechanism(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))]))
>>> [len(limb.factors) for limb in limbs_of(m)]
[1]
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from ..exceptions import ScrewkitValueError
from .interval_motions import (
    Constant,
    Matrix,
    Vector,
    adjoint,
    applied,
    compose,
    constant_of,
    exponential_constants,
    identity,
    lifted,
    rodrigues,
    screw_exponential,
    subtract,
    transposed_product,
)
from .intervals import Enclosure
from .limb_enclosures import _cross, _dot, _mul

__all__ = ["Factor", "Group", "Limb", "evaluate_group", "grouped", "limbs_of", "platform_constants"]

Array = np.ndarray


@dataclass(frozen=True)
class Factor:
    """One factor of a limb's product: the exponential of variable ``variable`` (``sign`` -1: of its
    negative, a joint traversed backwards) or the rotation offset of the spherical joints ``joints``
    (one per limb of a group; inverted when ``sign`` is -1) about ``centre``.

    Attributes
    ----------
    sign : float
    variable : int
        Index in the limb's variables (-1 for an offset).
    constants : dict
        Of :func:`~screwkit.analysis.interval_motions.exponential_constants`.
    screw : tuple
        The unit screw ``(ω; v)`` as constants.
    joints : tuple of str
        The spherical joints of an offset.
    centre : tuple
        Their centres (scaled) as constants.
    """

    sign: float
    variable: int = -1
    constants: Any = None
    screw: tuple[Constant, ...] = ()
    joints: tuple[str, ...] = ()
    centre: tuple[Constant, ...] = ()


@dataclass(frozen=True)
class Limb:
    """A serial chain from the base to the platform.

    Attributes
    ----------
    joints : tuple of str
    columns : tuple of int
        The model's joint variables, in chain order.
    factors : tuple of Factor
    actuated : int
        The actuated variable's index in ``columns``.
    """

    joints: tuple[str, ...]
    columns: tuple[int, ...]
    factors: tuple[Factor, ...]
    actuated: int


@dataclass(frozen=True)
class Group:
    """Limbs with the same sequence of factors, evaluated as one batch (limb after limb).

    Attributes
    ----------
    members : tuple of int
        Indices of the limbs.
    columns : numpy.ndarray, shape (g, d)
    factors : tuple of Factor
        Constants as arrays, one entry per member.
    actuated : int
    """

    members: tuple[int, ...]
    columns: Array
    factors: tuple[Factor, ...]
    actuated: int


def _one_box(value: float) -> Enclosure | None:
    return None if value == 0.0 else Enclosure(np.array([float(value)]), np.array([float(value)]))


def _refusal(reason: str) -> ScrewkitValueError:
    return ScrewkitValueError(reason)


def _chains(model: Any) -> list[list[tuple[str, bool]]]:
    """The limbs as ``(joint, traversed forward)`` from the base to the platform."""
    at: dict[Any, list[tuple[str, Any, bool]]] = {}
    for key, (u, v, _) in model.joints.items():
        at.setdefault(u, []).append((key, v, True))
        at.setdefault(v, []).append((key, u, False))
    chains = []
    for key, link, forward in sorted(at.get(model.base, []), key=lambda e: e[0]):
        chain, previous = [(key, forward)], key
        while link != model.platform:
            if link == model.base or len(at[link]) != 2:
                raise _refusal(f"link {link!r} is not inside one serial limb from the base to the platform")
            key, link, forward = next(e for e in at[link] if e[0] != previous)
            chain.append((key, forward))
            previous = key
        chains.append(chain)
    if sum(len(c) for c in chains) != len(model.joints):
        raise _refusal("some joints are not on a limb from the base to the platform")
    return chains


def limbs_of(mechanism: Any) -> list[Limb]:
    """The limbs of a loop-closure mechanism, their constants enclosed (module docstring).

    Parameters
    ----------
    mechanism : Mechanism
        Of the ``loop_closure`` family.

    Returns
    -------
    list of Limb

    Raises
    ------
    ScrewkitValueError
        When the graph is not a platform on serial limbs, or an actuated joint has several
        variables (the message is the reason alone).

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> m = sk.mechanism(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))]))
    >>> limbs_of(m)[0].factors[0].screw[3:]
    ((1.0, 1.0), None, None)
    """
    kinematics = mechanism.parameters
    model = kinematics.model
    raw = {
        key: np.asarray(joint.screws, dtype=float)
        for _, _, key, joint in kinematics.graph.edges(keys=True, data="joint")
    }
    actuated = {spec.name for spec in kinematics.reference.specs if spec.actuated}
    point = [_one_box(v) for v in model.point]
    inverse_length = Enclosure.constant(model.length, Enclosure(np.ones(1), np.ones(1))).reciprocal()
    limbs = []
    for chain in _chains(model):
        columns: list[int] = []
        factors: list[Factor] = []
        driven = []
        for key, forward in chain:
            _, _, indices = model.joints[key]
            joint_factors = []
            if model.types[key] == "S":
                centre = model.to_scaled_points(model.joint_points[key])
                joint_factors.append(
                    Factor(1.0, joints=(key,), centre=tuple(constant_of(_one_box(c)) for c in centre))
                )
            for k in range(len(indices)):
                w, v = _scaled_screw(raw[key][k], point, inverse_length)
                screw = tuple(constant_of(x) for x in (*w, *v))
                joint_factors.append(Factor(1.0, len(columns) + k, exponential_constants(w, v), screw))
            if key in actuated:
                if len(indices) != 1:
                    raise _refusal(f"actuated joint {key} has {len(indices)} variables")
                driven.append(len(columns))
            columns.extend(indices)
            if not forward:  # the inverse motion: the factors reversed, each inverted
                joint_factors = [replace(f, sign=-1.0) for f in reversed(joint_factors)]
            factors.extend(joint_factors)
        if len(driven) != 1:
            raise _refusal(f"the limb through {chain[0][0]} has {len(driven)} actuated joints, not one")
        limbs.append(Limb(tuple(k for k, _ in chain), tuple(columns), tuple(factors), driven[0]))
    return limbs


def _scaled_screw(raw: Array, point: Vector, inverse_length: Enclosure) -> tuple[Vector, Vector]:
    """The model's unit screw about its reference point in characteristic lengths
    (``screwkit.core.kinematic_model``), enclosed from the graph's screw."""
    s, s0 = [_one_box(v) for v in raw[:3]], [_one_box(v) for v in raw[3:]]
    if all(x is None for x in s):
        size = _dot(s0, s0)
        assert size is not None
        norm = size.sqrt().reciprocal()
        return [None] * 3, [_mul(x, norm) for x in s0]
    size = _dot(s, s)
    assert size is not None
    norm = size.sqrt().reciprocal()
    moment = subtract(s0, _cross(point, s))
    return [_mul(x, norm) for x in s], [_mul(_mul(m, inverse_length), norm) for m in moment]


def _signature(limb: Limb) -> tuple[Any, ...]:
    return (
        limb.actuated,
        len(limb.columns),
        *tuple(
            (f.sign, f.variable, bool(f.joints), f.constants is not None and "v" in f.constants)
            for f in limb.factors
        ),
    )


def _merged(values: list[Any]) -> Any:
    """Per-member constants merged into arrays (None where every member's is an exact zero)."""
    first = values[0]
    if isinstance(first, dict):
        return {key: _merged([v[key] for v in values]) for key in first}
    if isinstance(first, list | tuple) and (not first or not isinstance(first[0], float)):
        return type(first)(_merged([v[i] for v in values]) for i in range(len(first)))
    if all(v is None for v in values):
        return None
    return (
        np.array([0.0 if v is None else v[0] for v in values]),
        np.array([0.0 if v is None else v[1] for v in values]),
    )


def grouped(limbs: list[Limb]) -> list[Group]:
    """The limbs grouped by their sequence of factors (module docstring).

    Parameters
    ----------
    limbs : list of Limb

    Returns
    -------
    list of Group

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> m = sk.mechanism(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))]))
    >>> grouped(limbs_of(m))[0].members
    (0,)
    """
    groups: dict[tuple[Any, ...], list[int]] = {}
    for i, limb in enumerate(limbs):
        groups.setdefault(_signature(limb), []).append(i)
    out = []
    for members in groups.values():
        chosen = [limbs[i] for i in members]
        factors = []
        for position, factor in enumerate(chosen[0].factors):
            parts = [limb.factors[position] for limb in chosen]
            factors.append(
                Factor(
                    factor.sign,
                    factor.variable,
                    None if factor.constants is None else _merged([p.constants for p in parts]),
                    _merged([list(p.screw) for p in parts]) if factor.screw else (),
                    tuple(j for p in parts for j in p.joints),
                    _merged([list(p.centre) for p in parts]) if factor.centre else (),
                )
            )
        out.append(
            Group(
                tuple(members),
                np.array([limb.columns for limb in chosen]),
                tuple(factors),
                chosen[0].actuated,
            )
        )
    return out


def platform_constants(model: Any, coordinates: Any) -> dict[str, Any]:
    """What :func:`evaluate_group` needs of the coordinates: each one's axis and kind, the model's
    reference point and length, the coordinates' point (scaled), as constants.

    Parameters
    ----------
    model : KinematicModel
    coordinates : TaskCoordinates
        Along the base axes.

    Returns
    -------
    dict

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> m = sk.mechanism(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))]))
    >>> platform_constants(m.parameters.model, m.parameters.coordinates)["axes"]
    [0]
    """
    directions = np.asarray(coordinates.directions, dtype=float)
    local = model.to_scaled_points(coordinates.point)
    return {
        "axes": [int(np.argmax(row)) for row in directions],
        "translation": [k == "translation" for k in coordinates.kinds],
        "point": [constant_of(_one_box(v)) for v in model.point],
        "length": model.length,
        "local": [constant_of(_one_box(v)) for v in local],
    }


def _platform(constants: dict[str, Any], pose: list[Enclosure]) -> tuple[Matrix, Vector]:
    """The platform's displacement at poses (scaled frame): the rotation ``exp([r]×)`` of the rotation
    coordinates, the point at its coordinates (the others held at the reference); constants fixed."""
    batch = len(pose[0].lo)
    position: Vector = [lifted(c, batch) for c in constants["local"]]
    turn: Vector = [None, None, None]
    scale = lifted((constants["length"], constants["length"]), batch)
    assert scale is not None
    inverse_length = scale.reciprocal()
    for value, axis, translation in zip(pose, constants["axes"], constants["translation"], strict=True):
        if translation:
            origin = lifted(constants["point"][axis], batch)
            position[axis] = (value if origin is None else value - origin) * inverse_length
        else:
            turn[axis] = value
    rotation = rodrigues(turn) if any(t is not None for t in turn) else identity(inverse_length)
    local = [lifted(c, batch) for c in constants["local"]]
    return rotation, subtract(position, applied(rotation, local))


def _negated(v: Vector) -> Vector:
    return [None if x is None else -x for x in v]


def evaluate_group(
    group: Group,
    a: Array,
    b: Array,
    lo: Array,
    hi: Array,
    platform: dict[str, Any],
    turns: dict[str, Array],
    *,
    gradient: bool = False,
    pose_gradient: bool = False,
    twists: bool = False,
    rows: tuple[Array, int] | None = None,
) -> tuple[Vector, Enclosure, list[Vector]]:
    """A group's loop residuals (6 each, exact zeros None), the traces of ``R_k R(u)ᵀ`` and, with
    ``twists``, the joint twists, over joint boxes ``[a, b]`` and pose boxes ``[lo, hi]`` (rows: the
    group's members one after another, ``g B`` rows), with gradients in the joint variables when
    ``gradient``.

    Parameters
    ----------
    group : Group
    a, b : numpy.ndarray, shape (g B, d)
    lo, hi : numpy.ndarray, shape (g B, n)
    platform : dict
        :func:`platform_constants`.
    turns : dict
        Spherical joint name → its offset's rotation vector ``(B, 3)``.
    gradient, pose_gradient, twists : bool
        Gradients in the joint variables (and, with ``pose_gradient``, then in the pose
        coordinates); the twists.
    rows : tuple (numpy.ndarray of int, int), optional
        The rows of the ``g B`` stacked ones that ``a, b, lo, hi`` are, and ``B`` (default all).

    Returns
    -------
    residual : list of 6 Enclosure or None
    trace : Enclosure
    twists : list of lists of 6 Enclosure or None
        One per variable (empty without ``twists``).

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> m = sk.mechanism(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))]))
    >>> group = grouped(limbs_of(m))[0]
    >>> constants = platform_constants(m.parameters.model, m.parameters.coordinates)
    >>> pose = m.parameters.task.unscaled(np.array([[0.5]])) + 0.0      # x at half a char. length
    >>> half = np.array([[0.5]])
    >>> residual, _, _ = evaluate_group(group, half, half, pose, pose, constants, {})
    >>> float(abs(residual[3].lo[0])) < 1e-12
    True
    """
    d, n = a.shape[1], lo.shape[1]
    dims = None if not gradient else d + n if pose_gradient else d
    size = len(group.members)
    batch = np.repeat(np.arange(size), len(a) // size) if rows is None else rows[0] // rows[1]  # members
    if dims is None:
        theta = [Enclosure(a[:, j], b[:, j]) for j in range(d)]
        pose = [Enclosure(lo[:, i], hi[:, i]) for i in range(n)]
    elif pose_gradient:
        joint = Enclosure.variables(np.hstack([a, lo]), np.hstack([b, hi]))
        theta, pose = joint[:d], joint[d:]
    else:
        theta = Enclosure.variables(a, b)
        pose = [Enclosure(lo[:, i], hi[:, i], fixed=True) for i in range(n)]
    g: tuple[Matrix, Vector] | None = None
    out: list[Vector] = [[] for _ in range(a.shape[1])]
    for factor in group.factors:
        if factor.joints:
            r = np.concatenate([turns[joint] for joint in factor.joints])
            r = r if rows is None else r[rows[0]]
            turn = rodrigues([Enclosure(r[:, i], r[:, i]) for i in range(3)])
            rotation = [[lifted(x, batch) for x in row] for row in turn]
            centre = [lifted(c, batch) for c in factor.centre]
            shift = subtract(centre, applied(rotation, centre))
            if factor.sign < 0:
                rotation = [[rotation[j][i] for j in range(3)] for i in range(3)]
                shift = _negated(applied(rotation, shift))
            g = compose(g, (rotation, shift))
            continue
        value = theta[factor.variable] if factor.sign > 0 else -theta[factor.variable]
        if twists:
            w = [lifted(c, batch) for c in factor.screw[:3]]
            v = [lifted(c, batch) for c in factor.screw[3:]]
            twist = adjoint(g, w, v)
            out[factor.variable] = twist if factor.sign > 0 else _negated(twist)
        g = compose(g, screw_exponential(factor.constants, value, batch))
    assert g is not None
    if pose_gradient:
        rotation_p, position_p = _platform(platform, pose)
    else:  # constant in the joint variables: values, then a zero gradient
        rotation_p, position_p = _platform(platform, [Enclosure(p.lo, p.hi) for p in pose])
        rotation_p = [[lifted(x, len(a)) for x in row] for row in rotation_p]
        position_p = [lifted(x, len(a)) for x in position_p]
    m = transposed_product(g[0], rotation_p)
    skew = subtract([m[2][1], m[0][2], m[1][0]], [m[1][2], m[2][0], m[0][1]])
    trace = m[0][0] + m[1][1] + m[2][2]  # type: ignore[operator]
    return [*skew, *subtract(g[1], position_p)], trace, (out if twists else [])
