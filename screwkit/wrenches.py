"""Constraint and actuation wrench systems of a parallel mechanism (paper 002 §4.2–4.3).

For a twist graph at one configuration:

* each **limb**, i.e. each actuated joint with the union of the simple base-to-platform paths
  through it (compound legs through a nacelle included), has a twist system (the sum of its
  joints' twists, paper 002 Eq. 1) and a constraint wrench system (its reciprocal);
* the **actuation wrench** of an actuated joint is reciprocal to every twist of its limb except the
  actuated joint's, and not reciprocal to that one (paper 002 §4.3); it is defined up to the limb's
  constraint wrenches, and chosen as a line where one exists;
* each **compound leg** (a branch of the series-parallel decomposition between base and platform,
  such as the H4's ``L_I = l12 − R_I``) has its own twist and constraint systems; their
  constraint systems add up to the mechanism's (paper 002 Eqs. 2–3);
* the **global wrench system** is the sum of the mechanism's constraint wrenches and all
  actuation wrenches (paper 002 Eq. 4); it is a 6-system at a regular pose.

All ranks are decided about the reference point and length of
:func:`screwkit.twistgraph.graph_frame`, so they follow rigid motions and changes of unit; results
are reported in the user's frame.

Examples
--------
>>> from screwkit.joints import prismatic, revolute
>>> from screwkit.twistgraph import twist_graph
>>> G = twist_graph("ground", "slider", [
...     ("ground", "slider", prismatic("P1", [1, 0, 0], actuated=True))])
>>> analysis = wrench_analysis(G, dof=1)
>>> analysis.constraint_wrenches.order, analysis.global_wrenches.order
(5, 6)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from . import _backend as B
from . import screw as S
from .exceptions import DegenerateGeometryError, TwistGraphError
from .joints import Joint
from .screwsystem import ScrewSystem
from .twistgraph import (
    LoopEdge,
    SeriesParallelNode,
    check_twist_graph,
    graph_frame,
    joint_screws_along,
    platform_twist_system,
    series_parallel_tree,
    simple_paths,
)

__all__ = [
    "CompoundLeg",
    "Limb",
    "WrenchAnalysis",
    "normalized_reciprocal_product",
    "translated_graph",
    "wrench_analysis",
]

Array = np.ndarray


def translated_graph(graph: nx.MultiDiGraph, offset: Any, *, joint_key: str = "joint") -> nx.MultiDiGraph:
    """A copy of a twist graph with every joint moved by a translation (screws via the adjoint).

    Examples
    --------
    >>> from screwkit.joints import revolute
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> translated_graph(G, [-1, 0, 0]).edges["B", "E", "R"]["joint"].screws + 0.0
    array([[0., 0., 1., 0., 0., 0.]])
    """
    shift = B.as_array(offset, "offset", (3,))
    moved = nx.MultiDiGraph(**graph.graph)
    moved.add_nodes_from(graph.nodes(data=True))
    for u, v, key, data in graph.edges(keys=True, data=True):
        joint: Joint = data[joint_key]
        screws = S.transform(joint.screws, np.eye(3), shift)
        geometry = {
            key: (np.asarray(value) + shift).tolist() if key in ("point", "center") else value
            for key, value in joint.geometry.items()
        }
        copy = Joint(joint.name, joint.type, screws, joint.actuated, joint.virtual, geometry)
        moved.add_edge(u, v, key=key, **{**data, joint_key: copy})
    return moved


def _magnitude(rows: Array, length_scale: float, rtol: float) -> Array:
    directions = np.linalg.norm(rows[..., :3], axis=-1)
    moments = np.linalg.norm(rows[..., 3:], axis=-1) / length_scale
    return np.where(directions > rtol * moments, directions, moments)


def normalized_reciprocal_product(
    first: Any, second: Any, *, length_scale: float, rtol: float = B.DEFAULT_RTOL
) -> Any:
    """``|a ∘ b| / (N(a) N(b) L)``: a unit-free reciprocal product, invariant under rigid motions.

    ``N`` is ``|s|`` for a screw of finite pitch and ``|s0| / L`` for a couple or translation, and
    ``L`` the characteristic length. For two lines it is ``d·sin θ / L`` (their mutual moment over
    ``L``); for a line and a couple, or a force and a translation, the cosine of their angle.
    Zero exactly when the screws are reciprocal.

    Examples
    --------
    >>> force = S.line([1, 0, 0], [0, 0, 2.0])
    >>> rotation = S.line([0, 1, 0], [0, 0, 0])
    >>> float(normalized_reciprocal_product(force, rotation, length_scale=4.0))
    0.5
    """
    a = B.as_array(first, "first", (6,))
    b = B.as_array(second, "second", (6,))
    for name, rows in (("first", a), ("second", b)):
        if np.any(np.all(rows == 0, axis=-1)):
            raise DegenerateGeometryError(f"Expected `{name}` to hold non-zero screws, got the zero screw.")
    product = np.abs(B.dot(a[..., :3], b[..., 3:]) + B.dot(a[..., 3:], b[..., :3]))
    return product / (_magnitude(a, length_scale, rtol) * _magnitude(b, length_scale, rtol) * length_scale)


@dataclass(frozen=True, eq=False)
class Limb:
    """One actuated joint with its limb (every base-to-platform path through it).

    Attributes
    ----------
    actuated_joint : str
    joints : tuple of str
        The joints of the limb, the actuated one included.
    paths : tuple of tuple of LoopEdge
    twist_system : ScrewSystem
        Sum of the twists of the limb's joints (paper 002 Eq. 1).
    constraint_wrenches : ScrewSystem
        Its reciprocal: the wrenches the limb transmits with the actuator free.
    passive_wrenches : ScrewSystem
        Reciprocal to every twist of the limb but the actuated one's (with the actuator locked).
    actuation_wrench : numpy.ndarray, shape (6,), or None
        An element of ``passive_wrenches`` not reciprocal to the actuated twist (a line where one
        exists), None at a serial singularity of this limb.
    actuated_twist : numpy.ndarray, shape (6,)
    transmission : float
        :func:`normalized_reciprocal_product` of the actuation wrench and the actuated twist (0 at
        a serial singularity: the actuator cannot move the platform).
    """

    actuated_joint: str
    joints: tuple[str, ...]
    paths: tuple[tuple[LoopEdge, ...], ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem
    passive_wrenches: ScrewSystem
    actuation_wrench: Array | None
    actuated_twist: Array
    transmission: float


@dataclass(frozen=True, eq=False)
class CompoundLeg:
    """A branch between base and platform in the series-parallel decomposition (e.g. H4 ``L_I``).

    Attributes
    ----------
    joints : tuple of str
    twist_system : ScrewSystem
    constraint_wrenches : ScrewSystem
    actuated : tuple of str
        Its actuated joints, sorted.
    """

    joints: tuple[str, ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem
    actuated: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """``"leg through A1, A4"`` (its actuated joints), or its first joints if it has none."""
        return "leg through " + ", ".join(self.actuated or sorted(self.joints)[:2])


@dataclass(frozen=True, eq=False)
class WrenchAnalysis:
    """Wrench systems of a mechanism at one configuration (see the module docstring).

    Every screw system here is expressed in the user's frame.

    Attributes
    ----------
    graph : networkx.MultiDiGraph
        The analysed twist graph.
    reference_point, length_scale : numpy.ndarray (3,), float
        From :func:`~screwkit.twistgraph.graph_frame`.
    rtol : float
    dof : int
        The nominal mobility of the platform.
    platform_twists : ScrewSystem
    constraint_wrenches : ScrewSystem
        The mechanism's constraint wrench system ``W^c = T^⊥`` (paper 002 Eq. 3).
    compound_legs : tuple of CompoundLeg
        Empty when the graph is not series-parallel.
    limbs : tuple of Limb
        One per actuated joint.
    global_wrenches : ScrewSystem
        ``W^c + W^a`` (paper 002 Eq. 4).
    tree : SeriesParallelNode or None
        The series-parallel decomposition, about the reference point (None if the graph is not
        series-parallel).
    """

    graph: nx.MultiDiGraph
    reference_point: Array
    length_scale: float
    rtol: float
    dof: int
    platform_twists: ScrewSystem
    constraint_wrenches: ScrewSystem
    compound_legs: tuple[CompoundLeg, ...]
    limbs: tuple[Limb, ...]
    global_wrenches: ScrewSystem
    tree: SeriesParallelNode | None = None

    @property
    def actuation_wrenches(self) -> Array:
        """The actuation wrenches that exist, rows ``(k, 6)`` in limb order."""
        rows = [limb.actuation_wrench for limb in self.limbs if limb.actuation_wrench is not None]
        return np.array(rows).reshape(len(rows), 6)

    def constraint_generators(self) -> Array:
        """The compound legs' constraint wrenches stacked (the mechanism's generators), ``(k, 6)``.

        Falls back to a basis of :attr:`constraint_wrenches` when the graph is not
        series-parallel.
        """
        if not self.compound_legs:
            return np.asarray(self.constraint_wrenches.basis, dtype=float)
        rows = [leg.constraint_wrenches.readable_basis() for leg in self.compound_legs]
        return np.concatenate(rows).reshape(-1, 6)


def _system(rows: Array, rtol: float, length_scale: float) -> ScrewSystem:
    return ScrewSystem.span(
        np.asarray(rows, dtype=float).reshape(-1, 6), rtol=rtol, length_scale=length_scale
    )


def _user_frame(system: ScrewSystem, reference: Array) -> ScrewSystem:
    """The same system after the translation back to the user's frame (ranks were decided about
    the reference point; a rigid motion keeps independence, so they are not decided again)."""
    if system.order == 0:
        return system
    moved = S.transform(system.basis, np.eye(3), reference)
    return ScrewSystem.from_independent(moved, rtol=system.rtol, length_scale=system.length_scale)


def _choose_actuation_wrench(
    passive: ScrewSystem, constraint: ScrewSystem, actuated_twist: Array, length_scale: float, rtol: float
) -> tuple[Array | None, float]:
    """The actuation wrench: the passive wrench least reciprocal to the actuated twist, made canonical.

    It is defined up to the limb's constraint wrenches. The representative is the component
    orthogonal to them (in coordinates about the reference point with moments over the length, a
    metric rigid motions keep, so the choice follows the mechanism); when that is not a line, the
    nearest line obtained by adding one constraint wrench, if any.
    """
    if passive.order == 0:
        return None, 0.0
    candidates = passive.readable_basis()
    scores = normalized_reciprocal_product(candidates, actuated_twist, length_scale=length_scale, rtol=rtol)
    best = int(np.argmax(scores))
    if scores[best] <= rtol:
        return None, float(scores[best])
    wrench = _orthogonal_to(candidates[best], constraint.basis, length_scale)
    if constraint.order and not S.is_zero_pitch(wrench, rtol=LINE_RTOL, length_scale=length_scale):
        wrench = _nearest_line(wrench, constraint.basis, length_scale)
    score = normalized_reciprocal_product(wrench, actuated_twist, length_scale=length_scale, rtol=rtol)
    return wrench, float(score)


#: Relative tolerance deciding that a chosen actuation wrench is a line (zero pitch).
LINE_RTOL = 1e-6


def _scaled(rows: Array, length_scale: float) -> Array:
    out = np.array(rows, dtype=float)
    out[..., 3:] /= length_scale
    return out


def _orthogonal_to(wrench: Array, others: Array, length_scale: float) -> Array:
    if others.shape[0] == 0:
        return wrench
    basis = np.linalg.qr(_scaled(others, length_scale).T)[0]
    scaled = _scaled(wrench, length_scale)
    scaled = scaled - basis @ (basis.T @ scaled)
    scaled[3:] *= length_scale
    return scaled


def _nearest_line(wrench: Array, others: Array, length_scale: float) -> Array:
    """``wrench + α c`` of zero pitch with the smallest ``|α c|`` over single constraint wrenches c."""
    best, best_size = wrench, np.inf
    for other in others:
        # pitch numerator (s + α s_c)·(m + α m_c) = a α² + b α + c0
        a = other[:3] @ other[3:]
        b = wrench[:3] @ other[3:] + other[:3] @ wrench[3:]
        c0 = wrench[:3] @ wrench[3:]
        roots = np.roots([a, b, c0]) if abs(a) > 0 or abs(b) > 0 else np.array([])
        for alpha in roots[np.isreal(roots)].real:
            size = abs(alpha) * np.linalg.norm(_scaled(other, length_scale))
            if size < best_size:
                best, best_size = wrench + alpha * other, size
    return best


def _compound_legs(tree: SeriesParallelNode) -> list[SeriesParallelNode]:
    return list(tree.children) if tree.kind == "parallel" else [tree]


def wrench_analysis(
    graph: nx.MultiDiGraph,
    *,
    dof: int | None = None,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
) -> WrenchAnalysis:
    """Constraint, actuation and global wrench systems of a twist graph at its configuration.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (physical or equivalent).
    dof : int, optional
        Nominal mobility; default: the graph's ``dof`` attribute, else the number of actuated
        joints.
    joint_key : str
    rtol : float, default 1e-9
        Relative tolerance of every rank decision.

    Returns
    -------
    WrenchAnalysis

    Raises
    ------
    TwistGraphError
        If the graph has no actuated joint on a base-to-platform path, or an invalid ``dof``.

    Examples
    --------
    >>> from screwkit.joints import revolute, spherical
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [
    ...     ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("arm", "E", revolute("R", [0, 0, 1], [1, 0, 0]))], dof=1)
    >>> limb = wrench_analysis(G).limbs[0]
    >>> limb.passive_wrenches.order, S.is_zero_pitch(limb.actuation_wrench)
    (5, True)
    """
    check_twist_graph(graph, joint_key=joint_key)
    reference, length = graph_frame(graph, joint_key=joint_key)
    centred = translated_graph(graph, -reference, joint_key=joint_key)
    actuated = sorted(key for _, _, key, j in centred.edges(keys=True, data=joint_key) if j.actuated)
    nominal = dof if dof is not None else graph.graph.get("dof", len(actuated))
    if not B.is_dof(nominal):
        raise TwistGraphError(f"Expected `dof` to be an integer in 0..6, got {nominal!r}.")
    platform = platform_twist_system(centred, joint_key=joint_key, rtol=rtol, length_scale=length)
    constraints = platform.reciprocal()
    try:
        tree = series_parallel_tree(centred, joint_key=joint_key, rtol=rtol, length_scale=length)
        legs = [
            CompoundLeg(
                node.joints,
                node.system,
                node.system.reciprocal(),
                tuple(sorted(j for j in actuated if j in node.joints)),
            )
            for node in _compound_legs(tree)
        ]
    except TwistGraphError:
        tree, legs = None, []
    paths = simple_paths(centred)
    limbs = []
    for name in actuated:
        through = [p for p in paths if any(edge[2] == name for edge in p)]
        if not through:
            raise TwistGraphError(f"Actuated joint {name!r} lies on no path from the base to the platform.")
        edges = {edge[:3]: edge for path in through for edge in path}
        limb_graph = centred.edge_subgraph(edges)
        actuated_edge = next(e for key, e in edges.items() if key[2] == name)
        actuated_twist = joint_screws_along(centred, [actuated_edge], joint_key=joint_key)[0]
        limb_twists = platform_twist_system(limb_graph, joint_key=joint_key, rtol=rtol, length_scale=length)
        passive = platform_twist_system(
            limb_graph, joint_key=joint_key, rtol=rtol, length_scale=length, locked=[name]
        ).reciprocal()
        wrench, transmission = _choose_actuation_wrench(
            passive, limb_twists.reciprocal(), actuated_twist, length, rtol
        )
        limbs.append(
            Limb(
                actuated_joint=name,
                joints=tuple(key[2] for key in edges),
                paths=tuple(tuple(p) for p in through),
                twist_system=limb_twists,
                constraint_wrenches=limb_twists.reciprocal(),
                passive_wrenches=passive,
                actuation_wrench=wrench,
                actuated_twist=actuated_twist,
                transmission=transmission,
            )
        )
    actuation_rows = [limb.actuation_wrench for limb in limbs if limb.actuation_wrench is not None]
    global_system = _system(np.vstack([constraints.basis.reshape(-1, 6), *actuation_rows]), rtol, length)
    back = reference  # back to the user's frame: translate by +reference

    def shift(row: Array | None) -> Array | None:
        return None if row is None else S.transform(row, np.eye(3), back)

    return WrenchAnalysis(
        graph=graph,
        reference_point=reference,
        length_scale=length,
        rtol=rtol,
        dof=nominal,
        platform_twists=_user_frame(platform, back),
        constraint_wrenches=_user_frame(constraints, back),
        compound_legs=tuple(
            CompoundLeg(
                leg.joints, _user_frame(leg.twist_system, back), _user_frame(leg.constraint_wrenches, back)
            )
            for leg in legs
        ),
        limbs=tuple(
            Limb(
                limb.actuated_joint,
                limb.joints,
                limb.paths,
                _user_frame(limb.twist_system, back),
                _user_frame(limb.constraint_wrenches, back),
                _user_frame(limb.passive_wrenches, back),
                shift(limb.actuation_wrench),
                S.transform(limb.actuated_twist, np.eye(3), back),
                limb.transmission,
            )
            for limb in limbs
        ),
        global_wrenches=_user_frame(global_system, back),
        tree=tree,
    )
