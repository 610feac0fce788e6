"""The wrench analysis of one twist graph at its pose, numeric or symbolic: the entry point.

:func:`wrench_analysis` takes a twist graph (:mod:`screwkit.graphs.twistgraph`): a graph of numbers
is one pose of the batched core (:func:`screwkit.core.wrench_systems.analyze_table`) with its
mobility settled (:func:`screwkit.core.mobility.settled_dof`); a graph whose screws hold sympy
symbols (a family) gets its generic answers (:func:`screwkit.core.generic.generic_analysis`). Its
two return types are documented there, in its Returns section: one entry point serves every twist
graph, as the CLI and the catalog hand it graphs of either kind. Two companions check what the
analysis must not depend on: :func:`translated_graph` moves a graph rigidly, and
:func:`normalized_reciprocal_product` is the unit-free reciprocal product the transmissions use.

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("ground", "slider", [
...     ("ground", "slider", prismatic("P1", [1, 0, 0], actuated=True))])
>>> analysis = wrench_analysis(G, dof=1)
>>> analysis.constraint_wrenches.order, analysis.global_wrenches.order
(5, 6)
"""

from __future__ import annotations

from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..algebra.checks import checked_length_scale, checked_rtol
from ..exceptions import DegenerateGeometryError
from ..graphs.joints import Joint
from ..graphs.jointtable import JointTable
from .generic import GenericAnalysis, generic_analysis, is_symbolic_graph
from .mobility import settled_dof
from .wrench_systems import WrenchAnalysis, analyze_table

__all__ = ["normalized_reciprocal_product", "translated_graph", "wrench_analysis"]

Array = np.ndarray


def translated_graph(graph: nx.MultiDiGraph, offset: Any, *, joint_key: str = "joint") -> nx.MultiDiGraph:
    """A copy of a twist graph with every joint moved by a translation (screws via the adjoint).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    offset : array_like, shape (3,)
        The translation.
    joint_key : str, default "joint"
        The edge attribute holding each joint.

    Returns
    -------
    networkx.MultiDiGraph
        A new graph: every joint's screws, its geometry's points and the graph's anchor moved.

    Raises
    ------
    ScrewkitValueError
        If ``offset`` is not three numbers.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> translated_graph(G, [-1, 0, 0]).edges["B", "E", "R"]["joint"].screws + 0.0
    array([[0., 0., 1., 0., 0., 0.]])
    """
    shift = B.as_array(offset, "offset", (3,))
    moved = nx.MultiDiGraph(**graph.graph)
    moved.add_nodes_from(graph.nodes(data=True))
    if moved.graph.get("anchor") is not None:
        moved.graph["anchor"] = (np.asarray(moved.graph["anchor"], dtype=float) + shift).tolist()
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


def _magnitude(rows: Array, length_scale: Any, rtol: float) -> Array:
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

    Parameters
    ----------
    first, second : array_like, shape (..., 6)
        Screws (broadcast against each other).
    length_scale : float
        The characteristic length ``L``.
    rtol : float, default 1e-9
        A screw is a couple (or translation) where its direction is at most ``rtol`` of its moment
        over ``L``.

    Returns
    -------
    float or numpy.ndarray
        Of the broadcast batch shape.

    Raises
    ------
    DegenerateGeometryError
        If a screw is zero.

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



def wrench_analysis(
    graph: nx.MultiDiGraph,
    *,
    dof: int | None = None,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> WrenchAnalysis | GenericAnalysis:
    """Constraint, actuation and global wrench systems of a twist graph at its configuration.

    The graph is a batch of one pose through :func:`~screwkit.core.wrench_systems.analyze_table`.
    A graph whose screws hold sympy symbols (a family) gets its generic answers instead
    (:func:`screwkit.core.generic.generic_analysis`).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (physical or equivalent).
    dof : int, optional
        Nominal mobility; default: the graph's ``dof`` attribute, else derived. Either way it must
        be the mechanism's mobility at generic configurations, with at most that many actuators
        (:func:`screwkit.core.mobility.resolve_dof`; checked by :func:`screwkit.core.mobility.settled_dof`, at
        no cost when the pose is regular with one actuator per freedom).
    joint_key : str
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (checked, and unused, for a symbolic graph: its
        generic decisions are exact).
    length_scale : float, optional
        The characteristic length of the rank decisions
        (:func:`~screwkit.core.wrench_systems.analyze_table`; checked, and unused, for a symbolic
        graph).

    Returns
    -------
    WrenchAnalysis or GenericAnalysis
        Of one pose (shape ``()``); a GenericAnalysis for a symbolic graph.

    Raises
    ------
    TwistGraphError
        If an actuated joint lies on no base-to-platform path, an invalid ``dof``, a ``dof`` other
        than the mobility, or more actuators than the mobility (both numbers named).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, spherical
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [
    ...     ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("arm", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> analysis = wrench_analysis(G)  # one actuator, mobility 2 (planar 2R): dof 2, under-actuated
    >>> limb = analysis.limbs[0]
    >>> analysis.dof, limb.passive_wrenches.order, S.is_zero_pitch(limb.actuation_wrench)
    (2, 5, True)
    """
    rtol = checked_rtol(rtol)
    length_scale = checked_length_scale(length_scale, allow_none=True)
    if isinstance(graph, nx.MultiDiGraph) and is_symbolic_graph(graph, joint_key=joint_key):
        return generic_analysis(graph, dof=dof, joint_key=joint_key)  # a family: generic answers
    table = JointTable.from_graph(graph, joint_key=joint_key)
    one = JointTable(
        table.base,
        table.platform,
        table.specs,
        table.screws[None],
        table.dof,
        None if table.anchor is None else table.anchor[None],
        table.mobility,
        table.free,
    )
    stated = dof if dof is not None else table.dof
    analysis = analyze_table(one, dof=stated, rtol=rtol, length_scale=length_scale)[0]
    given = None if stated is None else analysis.dof
    nominal = settled_dof(graph, given, analysis, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
    if nominal != analysis.dof:  # derived: the mechanism's mobility, not the number of actuators
        analysis = analyze_table(one, dof=nominal, rtol=rtol, length_scale=length_scale)[0]
    object.__setattr__(analysis, "graph", graph)  # the caller's own graph object (cached view)
    return analysis
