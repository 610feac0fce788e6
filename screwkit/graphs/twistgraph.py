"""Twist graphs: links are nodes, joints are edges carrying screws (paper 002 §4; docs/architecture.md §5).

A twist graph is a plain :class:`networkx.MultiDiGraph`. Graph attributes ``base`` and
``platform`` name the fixed link and the end effector (and optionally ``dof``, the nominal mobility
of the platform). Each edge ``u → v`` is one joint, its key the joint's name and its attribute
``joint`` a :class:`~screwkit.graphs.joints.Joint` holding the twists of link ``v`` relative to link ``u``
(traversing it backwards negates them).

This module holds the schema: building a graph (:func:`twist_graph`, :func:`add_joint`), checking
it (:func:`check_twist_graph`), the reference frame it defines (:func:`graph_frame`,
:func:`graph_anchor`) and its plain-data round trip (:func:`to_data`, :func:`from_data`). Its loops
and loop-closure matrix are in :mod:`screwkit.graphs.loops`; its series-parallel reduction, the
platform's twist system and the equivalent twist graph in :mod:`screwkit.graphs.reduction`.

Examples
--------
>>> from screwkit.graphs.joints import revolute, prismatic
>>> G = twist_graph("ground", "slider", [
...     ("ground", "arm", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("arm", "slider", prismatic("P1", [1, 0, 0])),
... ])
>>> sorted(G.edges(keys=True))
[('arm', 'slider', 'P1'), ('ground', 'arm', 'R1')]
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.reference_frame import mechanism_frame
from ..exceptions import TwistGraphError
from .joints import Joint

__all__ = [
    "add_joint",
    "check_link_name",
    "check_twist_graph",
    "from_data",
    "graph_anchor",
    "graph_frame",
    "to_data",
    "twist_graph",
]

Array = np.ndarray


def check_link_name(value: Any, what: str) -> None:
    """Refuse a value that cannot name a link: a link name is any hashable value but None, a
    boolean (``True`` would be the link ``1``) or a float NaN (never equal to itself). Strings are
    the names files and reports use; integers and tuples work too.

    Parameters
    ----------
    value : object
        The candidate link name.
    what : str
        What it is, for the message (e.g. "the base link", "the parent of joint 'R'").

    Raises
    ------
    TwistGraphError
        Naming ``what``, the rule and the value given.

    Examples
    --------
    >>> check_link_name("ground", "the base link"), check_link_name(("leg", 1), "a link")
    (None, None)
    >>> check_link_name(["B"], "the base link")  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected the base link to be a hashable ..., got list ['B'].
    """
    try:
        hash(value)
        usable = not (
            value is None
            or isinstance(value, bool | np.bool_)
            or (isinstance(value, float | np.floating) and value != value)
        )
    except TypeError:  # unhashable: a list, a dict, an array
        usable = False
    if not usable:
        raise TwistGraphError(
            f"Expected {what} to be a hashable link name (a str, an int, a tuple) other than None, a "
            f"boolean or NaN, got {type(value).__name__} {value!r}."
        )


def twist_graph(
    base: Any,
    platform: Any,
    joints: Iterable[tuple[Any, Any, Joint]] = (),
    *,
    dof: int | None = None,
) -> nx.MultiDiGraph:
    """Build a twist graph from ``(parent, child, joint)`` triples and check it.

    Parameters
    ----------
    base, platform : hashable
        The fixed link and the end effector.
    joints : iterable of (parent, child, Joint)
    dof : int, optional
        Nominal degrees of freedom of the platform (for labels); by default the number of
        actuated joints (a non-redundantly actuated mechanism).

    Returns
    -------
    networkx.MultiDiGraph

    Raises
    ------
    TwistGraphError
        For a link that is not a link name (:func:`check_link_name`), ``joints`` that are not
        ``(parent, child, Joint)`` triples, or a graph that breaks the schema
        (:func:`check_twist_graph`).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))])
    >>> G.graph["base"], list(G.edges(keys=True))
    ('B', [('B', 'E', 'R')])
    """
    check_link_name(base, "the base link")
    check_link_name(platform, "the platform link")
    graph = nx.MultiDiGraph(base=base, platform=platform)
    if dof is not None:
        graph.graph["dof"] = dof
    if isinstance(joints, str | bytes) or not isinstance(joints, Iterable):
        raise TwistGraphError(
            "Expected `joints` to be an iterable of (parent, child, Joint) triples, got "
            f"{type(joints).__name__}."
        )
    for item in joints:
        if not (isinstance(item, tuple) and len(item) == 3):
            raise TwistGraphError(f"Expected joints as (parent, child, Joint) triples, got {item!r}.")
        add_joint(graph, *item)
    check_twist_graph(graph)
    return graph


def add_joint(graph: nx.MultiDiGraph, parent: Any, child: Any, joint: Joint) -> None:
    """Add a joint as the edge ``parent → child`` keyed by its name.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        The graph, changed in place.
    parent, child : hashable
        The links the joint connects (its twists are the child's relative to the parent).
    joint : Joint
        The joint.

    Raises
    ------
    TwistGraphError
        If the value is not a Joint, a link is not a link name (:func:`check_link_name`), or a
        joint of that name exists.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = nx.MultiDiGraph(base="B", platform="E")
    >>> add_joint(G, "B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))
    >>> G.number_of_edges()
    1
    """
    if not isinstance(joint, Joint):
        raise TwistGraphError(f"Edge {parent!r} → {child!r}: expected a Joint, got {type(joint).__name__}.")
    check_link_name(parent, f"the parent link of joint {joint.name!r}")
    check_link_name(child, f"the child link of joint {joint.name!r}")
    if any(key == joint.name for _, _, key in graph.edges(keys=True)):
        raise TwistGraphError(f"Duplicate joint name {joint.name!r}: joint names must be unique.")
    if parent == child:
        raise TwistGraphError(f"Joint {joint.name!r}: expected two different links, got {parent!r} twice.")
    graph.add_edge(parent, child, key=joint.name, joint=joint)


def check_twist_graph(graph: Any, *, joint_key: str = "joint") -> None:
    """Check the schema of a twist graph; raise a :class:`TwistGraphError` naming the problem.

    Checks: a MultiDiGraph; ``base`` and ``platform`` attributes naming distinct links of the
    graph; every edge carrying a :class:`Joint` under ``joint_key`` whose name is the edge key;
    unique joint names; no joint from a link to itself; all links connected to the base; a valid
    ``dof`` if given.

    Parameters
    ----------
    graph : object
        The candidate twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Examples
    --------
    >>> check_twist_graph(nx.MultiDiGraph())
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected graph attribute 'base' naming the fixed link, got none.
    """
    if not isinstance(graph, nx.MultiDiGraph):
        raise TwistGraphError(f"Expected a networkx.MultiDiGraph, got {type(graph).__name__}.")
    for role, meaning in (("base", "the fixed link"), ("platform", "the end effector")):
        if role not in graph.graph:
            raise TwistGraphError(f"Expected graph attribute {role!r} naming {meaning}, got none.")
        check_link_name(graph.graph[role], f"graph attribute {role!r}")
        if graph.graph[role] not in graph:
            raise TwistGraphError(
                f"Expected the {role} link {graph.graph[role]!r} to be a node of the graph, got no such node."
            )
    if graph.graph["base"] == graph.graph["platform"]:
        raise TwistGraphError(f"Expected base and platform to differ, got {graph.graph['base']!r} for both.")
    for node in graph:
        check_link_name(node, "every node of the graph")
    names: dict[str, tuple[Any, Any]] = {}
    for u, v, key, data in graph.edges(keys=True, data=True):
        joint = data.get(joint_key)
        if not isinstance(joint, Joint):
            raise TwistGraphError(
                f"Edge {u!r} → {v!r} (key {key!r}): expected attribute {joint_key!r} holding a Joint, "
                f"got {type(joint).__name__}."
            )
        if joint.name != key:
            raise TwistGraphError(
                f"Edge {u!r} → {v!r}: expected key {joint.name!r} (the joint's name), got {key!r}."
            )
        if key in names:
            raise TwistGraphError(f"Duplicate joint name {key!r} on edges {names[key]} and {(u, v)}.")
        if u == v:
            raise TwistGraphError(f"Joint {key!r}: expected two different links, got {u!r} twice.")
        names[key] = (u, v)
    unreached = set(graph) - nx.node_connected_component(
        graph.to_undirected(as_view=True), graph.graph["base"]
    )
    if unreached:
        raise TwistGraphError(
            f"Expected every link connected to the base {graph.graph['base']!r}, got unconnected links "
            f"{sorted(map(str, unreached))}."
        )
    dof = graph.graph.get("dof")
    if dof is not None and not B.is_dof(dof):
        raise TwistGraphError(f"Expected graph attribute 'dof' to be an integer in 0..6, got {dof!r}.")


def graph_frame(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> tuple[Array, float]:
    """A reference point and a characteristic length that move with the mechanism.

    The reference point is the point nearest (least squares) to all finite joint axes; the length
    is the root-mean-square distance of those axes from it (or 1 if it is 0). Both follow any
    rigid motion of the mechanism and any change of unit, so rank decisions and closeness
    measures made about them do not depend on where the user put the origin or which unit they
    used. With all axes parallel (a planar mechanism) the screws fix the point only across the
    axes; along them it is taken from :func:`graph_anchor`, or is the solution nearest the origin
    without one.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    reference_point : numpy.ndarray, shape (3,)
    length_scale : float

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "L", revolute("R1", [0, 0, 1], [100.0, 0, 0])),
    ...                            ("L", "E", revolute("R2", [0, 1, 0], [0, 0, 0]))])
    >>> point, length = graph_frame(G)
    >>> point.round(6) + 0.0, round(length, 6)
    (array([50.,  0.,  0.]), 50.0)
    """
    joints = sorted(graph.edges(keys=True, data=joint_key), key=lambda e: str(e[2]))  # the core's order
    rows = [joint.screws for _, _, _, joint in joints]
    stacked = np.concatenate(rows) if rows else np.zeros((0, 6))
    if B.is_symbolic(stacked):
        return np.zeros(3), 1.0
    anchor = graph_anchor(graph, joint_key=joint_key)
    point, length = mechanism_frame(stacked[None], None if anchor is None else anchor[None])  # as the core
    return point[0], float(length[0])


def graph_anchor(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> Array | None:
    """A point that moves with the mechanism: the graph's ``anchor`` attribute if set, else the
    mean of the joints' own points (their ``geometry``), else None.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    numpy.ndarray, shape (3,), or None

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> graph_anchor(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [2.0, 0, 0]))]))
    array([2., 0., 0.])
    """
    if graph.graph.get("anchor") is not None:
        return np.asarray(graph.graph["anchor"], dtype=float)
    anchors = [
        data[joint_key].geometry[key]
        for _, _, data in graph.edges(data=True)
        for key in ("point", "center")
        if key in data[joint_key].geometry
    ]
    return np.mean(np.asarray(anchors, dtype=float), axis=0) if anchors else None


def to_data(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> dict[str, Any]:
    """Plain, JSON-ready data of a twist graph (``nx.node_link_data`` with joints encoded).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    dict
        Node-link data (edges under ``"edges"``), JSON-ready.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))])
    >>> from_data(to_data(G)).edges["B", "E", "R"]["joint"].type
    'R'
    """
    copy = nx.MultiDiGraph(**graph.graph)
    copy.add_nodes_from(graph.nodes(data=True))
    for u, v, key, data in graph.edges(keys=True, data=True):
        copy.add_edge(u, v, key=key, **{**data, joint_key: data[joint_key].to_dict()})
    return nx.node_link_data(copy, edges="edges")


def from_data(data: dict[str, Any], *, joint_key: str = "joint") -> nx.MultiDiGraph:
    """Rebuild a twist graph saved with :func:`to_data` (plain data only; nothing is evaluated).

    Parameters
    ----------
    data : dict
        The output of :func:`to_data` (e.g. read back from JSON).
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    networkx.MultiDiGraph

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))])
    >>> import json
    >>> from_data(json.loads(json.dumps(to_data(G)))).graph["platform"]
    'E'
    """
    graph = nx.node_link_graph(data, directed=True, multigraph=True, edges="edges")
    for u, v, key in list(graph.edges(keys=True)):
        graph.edges[u, v, key][joint_key] = Joint.from_dict(graph.edges[u, v, key][joint_key])
    check_twist_graph(graph, joint_key=joint_key)
    return graph
