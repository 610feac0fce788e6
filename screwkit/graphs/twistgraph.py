"""Twist graphs: links are nodes, joints are edges carrying screws (paper 002 §4; design.md §5).

A twist graph is a plain :class:`networkx.MultiDiGraph`. Graph attributes ``base`` and
``platform`` name the fixed link and the end effector (and optionally ``dof``, the nominal mobility
of the platform). Each edge ``u → v`` is one joint, its key the joint's name and its attribute
``joint`` a :class:`~screwkit.graphs.joints.Joint` holding the twists of link ``v`` relative to link ``u``
(traversing it backwards negates them).

The platform's twist system is computed two ways that agree wherever both apply:

* **reduction** (paper 002 Eqs. 1–2): the sum of twist systems along serial chains and their
  intersection across parallel chains, on a series-parallel graph. It also yields the
  *equivalent twist graph* in which each closed sub-loop not touching the base (such as a 4S
  parallelogram, paper 002 Fig. 2) is replaced by a virtual serial chain spanning the same twist
  system (paper 002 Fig. 3);
* **loop closure**: the joint rates allowed by the loop-closure equations (the null space of the
  loop-closure matrix), mapped to the platform along a spanning tree. It works for any topology.

Examples
--------
>>> from screwkit.graphs.joints import revolute, prismatic
>>> G = twist_graph("ground", "slider", [
...     ("ground", "arm", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("arm", "slider", prismatic("P1", [1, 0, 0])),
... ])
>>> platform_twist_system(G).order, platform_twist_system(G, method="reduction").order
(2, 2)
"""

from __future__ import annotations

import itertools
from collections import deque
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Literal

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.screwsystem import ScrewSystem
from ..core._frames import compiled_kernels, sum_in_order, unit_scaled
from ..exceptions import TwistGraphError
from .joints import Joint, virtual

__all__ = [
    "LoopEdge",
    "SeriesParallelNode",
    "add_joint",
    "check_twist_graph",
    "equivalent_twist_graph",
    "from_data",
    "fundamental_loops",
    "graph_anchor",
    "graph_frame",
    "joint_screws_along",
    "loop_closure_matrix",
    "mechanism_frame",
    "platform_twist_system",
    "scaled_frame",
    "series_parallel_tree",
    "simple_paths",
    "to_data",
    "twist_graph",
]

Array = np.ndarray
#: An edge as traversed in a loop or path: (u, v, key, "forward" | "reverse").
LoopEdge = tuple[Any, Any, str, str]


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

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))])
    >>> G.graph["base"], list(G.edges(keys=True))
    ('B', [('B', 'E', 'R')])
    """
    graph = nx.MultiDiGraph(base=base, platform=platform)
    if dof is not None:
        graph.graph["dof"] = dof
    for item in joints:
        if not (isinstance(item, tuple) and len(item) == 3):
            raise TwistGraphError(f"Expected joints as (parent, child, Joint) triples, got {item!r}.")
        add_joint(graph, *item)
    check_twist_graph(graph)
    return graph


def add_joint(graph: nx.MultiDiGraph, parent: Any, child: Any, joint: Joint) -> None:
    """Add a joint as the edge ``parent → child`` keyed by its name.

    Raises
    ------
    TwistGraphError
        If the value is not a Joint, or a joint of that name exists.

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
        if graph.graph[role] not in graph:
            raise TwistGraphError(
                f"Expected the {role} link {graph.graph[role]!r} to be a node of the graph, got no such node."
            )
    if graph.graph["base"] == graph.graph["platform"]:
        raise TwistGraphError(f"Expected base and platform to differ, got {graph.graph['base']!r} for both.")
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


def mechanism_frame(screws: Array, anchor: Array | None = None) -> tuple[Array, Array]:
    """The batched kernel of :func:`graph_frame`: screws ``(..., n, 6)`` → points ``(..., 3)``,
    lengths ``(...)``.

    The point is the least-squares point nearest to the finite axes (screws of infinite pitch are
    ignored). Directions along which the axes do not fix it (all axes parallel: a planar
    mechanism; eigenvalues of the normal matrix below :data:`UNDETERMINED_RTOL` of the largest)
    take the ``anchor`` ``(..., 3)``'s coordinate when one is given (a point that moves with the
    mechanism), else the solution nearest the origin. The length is the root-mean-square distance
    of the axes from the point; when every axis passes through it (a spherical mechanism) that is
    round-off, and below ``1e-12`` of the coordinates' own size it is replaced by that size (the
    farthest foot of an axis from the origin, or 1 when it is 0), a length that still follows the
    unit; moments about the common point are then zero whatever the length. With no finite axis,
    the point is the origin and the length 1.

    Examples
    --------
    >>> rows = np.array([[0, 0, 1, 0, -100.0, 0], [0, 1, 0, 0, 0, 0]])
    >>> point, length = mechanism_frame(np.stack([rows, rows]))
    >>> point.round(6) + 0.0, length
    (array([[50.,  0.,  0.],
           [50.,  0.,  0.]]), array([50., 50.]))
    >>> planar = np.array([[0, 0, 1, 0, 0, 0], [0, 0, 1, 1, 0, 0.0]])
    >>> mechanism_frame(planar, np.array([0, 0, 5.0]))[0].round(6) + 0.0
    array([0. , 0.5, 5. ])
    """
    point, length, _ = scaled_frame(screws, anchor, scale=False)
    return point, length


def scaled_frame(
    screws: Array, anchor: Array | None = None, *, scale: bool = True
) -> tuple[Array, Array, Array | None]:
    """:func:`mechanism_frame` and the screws in its scaled coordinates, unit rows
    (:func:`screwkit.core._frames.unit_scaled`; None unless ``scale``): ``(point, length, scaled)``. On
    the numba path one compiled pass (:func:`screwkit.core._frames_numba.mechanism_frame`) where the
    normal matrix is solved directly, the numpy path's operations in its order (the same bits);
    the other poses as the numpy path.

    Examples
    --------
    >>> rows = np.array([[0, 0, 1, 0, -100.0, 0], [0, 1, 0, 0, 0, 0]])
    >>> point, length, scaled = scaled_frame(rows)                    # about (50, 0, 0), per 50
    >>> point.round(6) + 0.0, float(length), scaled.round(6) + 0.0
    (array([50.,  0.,  0.]), 50.0, array([[ 0.      ,  0.      ,  0.707107,  0.      , -0.707107,  0.      ],
           [ 0.      ,  0.707107,  0.      ,  0.      ,  0.      , -0.707107]]))
    """
    batch = screws.shape[:-2]
    flat = np.ascontiguousarray(np.reshape(screws, (-1, *screws.shape[-2:])), dtype=float)
    anchors = None
    if anchor is not None:
        anchors = np.broadcast_to(np.asarray(anchor, dtype=float), (*batch, 3)).reshape(-1, 3)
    kernels = compiled_kernels("screwkit.core._frames_numba", len(flat))  # the same sums, in the same order
    if kernels is None:
        point, length = _frame_numpy(flat, anchors)
        scaled = unit_scaled(flat, point, length) if scale else None
    else:
        point, length, direct, scaled = kernels.mechanism_frame(flat, scale)
        rest = ~direct
        if rest.any():  # the eigendecomposition's poses
            point[rest], length[rest] = _frame_numpy(flat[rest], None if anchors is None else anchors[rest])
            if scale:
                scaled[rest] = kernels.unit_scaled(flat[rest], point[rest], length[rest])
        scaled = scaled if scale else None
    return (
        point.reshape(*batch, 3),
        length.reshape(batch),
        None if scaled is None else scaled.reshape(screws.shape),
    )


def _frame_numpy(flat: Array, anchor: Array | None) -> tuple[Array, Array]:
    """:func:`mechanism_frame` of screws ``(n, k, 6)`` with numpy (the compiled pass's twin)."""
    count, normal, rhs, farthest = _frame_sums_numpy(flat)
    point = _least_squares_point(normal, rhs, anchor)
    length = np.sqrt(_frame_spread_numpy(flat, point) / np.maximum(count, 1))
    reach = np.sqrt(point[:, 0] * point[:, 0] + point[:, 1] * point[:, 1] + point[:, 2] * point[:, 2])
    size = np.maximum(farthest, reach)
    round_off = length <= 1e-12 * size
    fallback = np.where(size > 0, size, 1.0)
    length = np.where(round_off | (length == 0), fallback, length)
    return point, length


def _axes_numpy(screws: Array) -> tuple[Array, list[Array], list[Array]]:
    """Of screws ``(n, k, 6)``: which axes are finite ``(n, k)``, their unit directions (zero for
    infinite pitch) and their feet ``d × m / |d|²`` (each axis's point nearest the origin), component
    by component (``(n, k)`` arrays: no ``(n, k, 3, 3)`` temporaries)."""
    d = [screws[..., i] for i in range(3)]
    m = [screws[..., 3 + i] for i in range(3)]
    sizes = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    finite = sizes > 0
    inverse = 1.0 / np.where(finite, sizes, 1.0)
    scale = np.sqrt(inverse) * finite
    units = [x * scale for x in d]
    feet = [(d[1] * m[2] - d[2] * m[1]) * inverse, (d[2] * m[0] - d[0] * m[2]) * inverse,
            (d[0] * m[1] - d[1] * m[0]) * inverse]
    return finite, units, feet


def _frame_sums_numpy(screws: Array) -> tuple[Array, Array, Array, Array]:
    """The sums of :func:`screwkit.core._frames_numba.mechanism_frame` with numpy, operation for
    operation: the projectors ``P_k = I − u_k u_kᵀ`` of the finite axes never formed, their sum and
    ``Σ P_k f_k`` summed over the axes left to right (:func:`screwkit.core._frames.sum_in_order`)."""
    finite, units, feet = _axes_numpy(screws)
    along = units[0] * feet[0] + units[1] * feet[1] + units[2] * feet[2]
    pairs = ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2))
    terms = [units[i] * units[j] for i, j in pairs]
    totals = sum_in_order(np.stack(terms + [(feet[i] - units[i] * along) * finite for i in range(3)]))
    count = finite.sum(axis=-1)
    normal = np.empty((len(screws), 3, 3))
    for (i, j), total in zip(pairs, totals, strict=False):
        normal[:, i, j] = normal[:, j, i] = (count if i == j else 0.0) - total
    farthest = np.sqrt(feet[0] * feet[0] + feet[1] * feet[1] + feet[2] * feet[2]).max(axis=-1, initial=0.0)
    return count, normal, np.stack(list(totals[6:]), axis=-1), farthest


def _frame_spread_numpy(screws: Array, point: Array) -> Array:
    """The spread of :func:`screwkit.core._frames_numba.mechanism_frame` with numpy, operation for
    operation."""
    finite, units, feet = _axes_numpy(screws)
    away = [point[:, None, i] - feet[i] for i in range(3)]
    along = units[0] * away[0] + units[1] * away[1] + units[2] * away[2]
    away = [(away[i] - units[i] * along) * finite for i in range(3)]
    return sum_in_order(away[0] * away[0] + away[1] * away[1] + away[2] * away[2])


def _least_squares_point(normal: Array, rhs: Array, anchor: Array | None) -> Array:
    """``N⁻¹ rhs`` for the symmetric positive semi-definite ``normal (..., 3, 3)``, with the
    directions of its eigenvalues below :data:`UNDETERMINED_RTOL` of the largest taken from
    ``anchor`` (or 0). Where ``4 det N / (tr N)³ > 1e-6`` every eigenvalue is above ``1e-6`` of
    the largest (``λ_min ≥ 4 det / tr²`` as the other two multiply to at most ``(tr/2)²``, and
    ``λ_max ≤ tr``), so the adjugate solves it directly; the other poses go through the
    eigendecomposition. A pose's answer depends on its own data only."""
    batch = normal.shape[:-2]
    flat, b = normal.reshape(-1, 3, 3), rhs.reshape(-1, 3)
    n00, n01, n02 = flat[:, 0, 0], flat[:, 0, 1], flat[:, 0, 2]
    n11, n12, n22 = flat[:, 1, 1], flat[:, 1, 2], flat[:, 2, 2]
    a00, a01, a02 = n11 * n22 - n12 * n12, n02 * n12 - n01 * n22, n01 * n12 - n02 * n11
    a11, a12, a22 = n00 * n22 - n02 * n02, n01 * n02 - n00 * n12, n00 * n11 - n01 * n01
    det = n00 * a00 + n01 * a01 + n02 * a02
    trace = n00 + n11 + n22
    direct = (trace > 0) & (4.0 * det > 1e-6 * (trace * trace * trace))
    safe = np.where(direct, det, 1.0)
    point = np.stack(
        [
            (a00 * b[:, 0] + a01 * b[:, 1] + a02 * b[:, 2]) / safe,
            (a01 * b[:, 0] + a11 * b[:, 1] + a12 * b[:, 2]) / safe,
            (a02 * b[:, 0] + a12 * b[:, 1] + a22 * b[:, 2]) / safe,
        ],
        axis=-1,
    )
    rest = ~direct
    if rest.any():
        values, vectors = np.linalg.eigh(flat[rest])
        determined = values > UNDETERMINED_RTOL * values[..., -1:]
        inverse = np.where(determined, 1.0 / np.where(determined, values, 1.0), 0.0)
        coordinates = np.einsum("...ji,...j->...i", vectors, b[rest]) * inverse  # in the eigenbasis
        if anchor is not None:
            anchors = np.broadcast_to(np.asarray(anchor, dtype=float), (*batch, 3)).reshape(-1, 3)[rest]
            coordinates = np.where(determined, coordinates, np.einsum("...ji,...j->...i", vectors, anchors))
        point[rest] = np.einsum("...ij,...j->...i", vectors, coordinates)
    return point.reshape(*batch, 3)


#: Directions in which the joint axes fix the reference point too weakly to be used (eigenvalues of
#: the least-squares normal matrix below this fraction of the largest: axes within about 1e-5 rad
#: of all parallel) take the anchor's coordinate (:func:`mechanism_frame`).
UNDETERMINED_RTOL = 1e-10


# loops and loop closure ---------------------------------------------------------------------------
def _spanning_tree(graph: nx.MultiDiGraph) -> dict[Any, LoopEdge | None]:
    """BFS tree from the base: for each link, the edge that reaches it from its parent."""
    base = graph.graph["base"]
    parent_edge: dict[Any, LoopEdge | None] = {base: None}
    queue = deque([base])
    while queue:
        node = queue.popleft()
        incident = [(node, v, k, "forward") for _, v, k in graph.out_edges(node, keys=True)]
        incident += [(u, node, k, "reverse") for u, _, k in graph.in_edges(node, keys=True)]
        for u, v, key, direction in sorted(incident, key=lambda e: str(e[2])):
            other = v if direction == "forward" else u
            if other not in parent_edge:
                parent_edge[other] = (u, v, key, direction)
                queue.append(other)
    return parent_edge


def _tree_path(parent_edge: dict[Any, LoopEdge | None], start: Any, stop: Any) -> list[LoopEdge]:
    """Edges traversed from ``start`` to ``stop`` along the tree."""

    def ancestors(node: Any) -> list[Any]:
        chain = [node]
        while parent_edge[chain[-1]] is not None:
            edge = parent_edge[chain[-1]]
            assert edge is not None
            chain.append(edge[0] if edge[3] == "forward" else edge[1])
        return chain

    up_start, up_stop = ancestors(start), ancestors(stop)
    common = next(n for n in up_start if n in set(up_stop))
    path: list[LoopEdge] = []
    for node in up_start[: up_start.index(common)]:  # climbing: traverse tree edges backwards
        u, v, key, direction = parent_edge[node]  # type: ignore[misc]
        path.append((u, v, key, "reverse" if direction == "forward" else "forward"))
    descent = []
    for node in up_stop[: up_stop.index(common)]:
        descent.append(parent_edge[node])
    path.extend(e for e in reversed(descent) if e is not None)
    return path


def fundamental_loops(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> list[list[LoopEdge]]:
    """A basis of the graph's cycles, one loop per edge outside a spanning tree from the base.

    ``nx.cycle_basis`` does not accept multigraphs (parallel joints are loops too), so loops are
    built from a BFS spanning tree; each is a list of ``(u, v, key, "forward" | "reverse")`` that
    starts with its non-tree edge. There are ``E − V + 1`` of them for a connected graph.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
    ...                            ("B", "E", revolute("R2", [0, 0, 1], [0, 0, 0]))])
    >>> fundamental_loops(G)
    [[('B', 'E', 'R2', 'forward'), ('B', 'E', 'R1', 'reverse')]]
    """
    check_twist_graph(graph, joint_key=joint_key)
    parent_edge = _spanning_tree(graph)
    tree = {(e[0], e[1], e[2]) for e in parent_edge.values() if e is not None}
    loops = []
    for u, v, key in sorted(graph.edges(keys=True), key=lambda e: str(e[2])):
        if (u, v, key) in tree:
            continue
        loops.append([(u, v, key, "forward"), *_tree_path(parent_edge, v, u)])
    return loops


def _columns(graph: nx.MultiDiGraph, joint_key: str) -> list[tuple[Any, Any, str, int]]:
    return [
        (u, v, key, i)
        for u, v, key, data in sorted(graph.edges(keys=True, data=True), key=lambda e: str(e[2]))
        for i in range(data[joint_key].dof)
    ]


def joint_screws_along(
    graph: nx.MultiDiGraph, edges: Iterable[LoopEdge], *, joint_key: str = "joint"
) -> Array:
    """The signed screws of the joints along traversed edges, rows ``(n, 6)``.

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))])
    >>> joint_screws_along(G, [("B", "E", "P", "reverse")]) + 0.0
    array([[ 0.,  0.,  0., -1.,  0.,  0.]])
    """
    rows = []
    for u, v, key, direction in edges:
        screws = graph.edges[u, v, key][joint_key].screws
        rows.append(screws if direction == "forward" else -screws)
    return np.concatenate(rows) if rows else np.zeros((0, 6))


def loop_closure_matrix(
    graph: nx.MultiDiGraph, *, joint_key: str = "joint"
) -> tuple[Array, list[tuple[Any, Any, str, int]]]:
    """The loop-closure matrix: for each fundamental loop, the six equations ``Σ ±$_j q_j = 0``.

    Returns
    -------
    matrix : numpy.ndarray, shape (6 · loops, joint freedoms)
    columns : list of (u, v, key, index)
        The joint freedom of each column (index: which screw of the joint).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
    ...                            ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))])
    >>> matrix, columns = loop_closure_matrix(G)
    >>> matrix.shape, [c[2] for c in columns]
    ((6, 2), ['R1', 'R2'])
    """
    loops = fundamental_loops(graph, joint_key=joint_key)
    columns = _columns(graph, joint_key)
    index = {c: i for i, c in enumerate(columns)}
    symbolic = B.is_symbolic(*(graph.edges[u, v, k][joint_key].screws for u, v, k, _ in columns))
    matrix = B.zeros((6 * len(loops), len(columns)), symbolic=symbolic)
    for row, loop in enumerate(loops):
        for u, v, key, direction in loop:
            screws = _promoted(graph.edges[u, v, key][joint_key].screws, symbolic)
            sign = 1 if direction == "forward" else -1
            for i, screw in enumerate(screws):
                matrix[6 * row : 6 * row + 6, index[(u, v, key, i)]] += sign * screw
    return matrix, columns


def _promoted(screws: Array, symbolic: bool) -> Array:
    """Numeric screws as exact sympy numbers when the matrix is symbolic (no floats leak in)."""
    return B.promote(screws, B.zeros((0,), symbolic=True))[0] if symbolic else screws


def _loop_closure_twists(
    graph: nx.MultiDiGraph, joint_key: str, rtol: float, length_scale: float, locked: frozenset[str]
) -> ScrewSystem:
    matrix, columns = loop_closure_matrix(graph, joint_key=joint_key)
    free = [i for i, column in enumerate(columns) if column[2] not in locked]
    parent_edge = _spanning_tree(graph)
    path = _tree_path(parent_edge, graph.graph["base"], graph.graph["platform"])
    index = {c: i for i, c in enumerate(columns)}
    symbolic = B.is_symbolic(*(joint.screws for _, _, joint in graph.edges(data=joint_key)))
    path_matrix = B.zeros((6, len(columns)), symbolic=symbolic)
    for u, v, key, direction in path:
        screws = _promoted(graph.edges[u, v, key][joint_key].screws, symbolic)
        for i, screw in enumerate(screws):
            path_matrix[:, index[(u, v, key, i)]] += screw if direction == "forward" else -screw
    matrix, path_matrix = matrix[:, free], path_matrix[:, free]
    if not free:
        return ScrewSystem.zero(rtol=rtol, length_scale=length_scale)
    twists = B.screw_image_of_nullspace(path_matrix, matrix, rtol=rtol, length_scale=length_scale)
    return ScrewSystem.span(twists, rtol=rtol, length_scale=length_scale)


# series-parallel reduction -----------------------------------------------------------------------
@dataclass(frozen=True, eq=False)
class SeriesParallelNode:
    """A node of the series-parallel decomposition of a twist graph.

    Attributes
    ----------
    kind : {"joint", "series", "parallel"}
    ends : (link, link)
        The two terminal links, in chain order.
    system : ScrewSystem
        Twist system of ``ends[1]`` relative to ``ends[0]`` (sum in series, intersection in
        parallel: paper 002 Eqs. 1–2).
    children : tuple of SeriesParallelNode
    links : tuple
        For a series node, the links along the chain from ``ends[0]`` to ``ends[1]``.
    edge : (u, v, key) or None
        For a joint node, the graph edge.
    """

    kind: Literal["joint", "series", "parallel"]
    ends: tuple[Any, Any]
    system: ScrewSystem
    children: tuple[SeriesParallelNode, ...] = ()
    links: tuple[Any, ...] = ()
    edge: tuple[Any, Any, str] | None = None
    joints: tuple[str, ...] = field(default=())

    def reversed(self) -> SeriesParallelNode:
        """The same node seen from its other end (its children too)."""
        children = tuple(child.reversed() for child in self.children)
        return SeriesParallelNode(
            self.kind,
            (self.ends[1], self.ends[0]),
            self.system,
            tuple(reversed(children)) if self.kind == "series" else children,
            tuple(reversed(self.links)),
            self.edge,
            self.joints,
        )


def series_parallel_tree(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> SeriesParallelNode:
    """Reduce a twist graph to one base–platform node by series and parallel steps.

    Links other than base and platform attached by a single joint are dropped (they cannot
    change the platform's motion); a link with exactly two joints joins them in series; parallel
    joints between the same two links are intersected.

    Raises
    ------
    TwistGraphError
        If the graph is not series-parallel between base and platform (use the loop-closure method).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, prismatic
    >>> G = twist_graph("B", "E", [("B", "L", revolute("R", [0, 0, 1], [0, 0, 0])),
    ...                            ("L", "E", prismatic("P", [1, 0, 0]))])
    >>> tree = series_parallel_tree(G)
    >>> tree.kind, tree.system.order, tree.links
    ('series', 2, ('B', 'L', 'E'))
    """
    check_twist_graph(graph, joint_key=joint_key)
    base, platform = graph.graph["base"], graph.graph["platform"]
    scale = graph_frame(graph, joint_key=joint_key)[1] if length_scale is None else length_scale
    work = nx.MultiGraph()
    work.add_nodes_from(graph)
    for u, v, key, data in graph.edges(keys=True, data=True):
        joint = data[joint_key]
        system = ScrewSystem.span(joint.screws, rtol=rtol, length_scale=scale)
        node = SeriesParallelNode("joint", (u, v), system, edge=(u, v, key), joints=(key,))
        work.add_edge(u, v, node=node)
    changed = True
    while changed:
        changed = False
        for link in list(work.nodes):
            if link not in (base, platform) and work.degree(link) <= 1:
                work.remove_node(link)
                changed = True
        for a, b in {tuple(sorted((u, v), key=str)) for u, v in work.edges()}:
            if work.number_of_edges(a, b) > 1:
                members = [_oriented(d["node"], a) for d in work.get_edge_data(a, b).values()]
                # parallel composition is associative: one parallel node per pair of links, whose
                # children are the branches (not an earlier parallel node and a later branch)
                members = [c for m in members for c in (m.children if m.kind == "parallel" else (m,))]
                system = members[0].system
                for member in members[1:]:
                    system = system & member.system
                joints = tuple(itertools.chain.from_iterable(m.joints for m in members))
                merged = SeriesParallelNode("parallel", (a, b), system, tuple(members), joints=joints)
                work.remove_edges_from([(a, b)] * work.number_of_edges(a, b))
                work.add_edge(a, b, node=merged)
                changed = True
        for link in list(work.nodes):
            if link in (base, platform) or work.degree(link) != 2:
                continue
            (_, a, first), (_, b, second) = work.edges(link, data="node")
            left, right = _oriented(first, a), _oriented(second, link)
            chain = _flatten_series(left) + _flatten_series(right)
            links = (*_series_links(left), *_series_links(right)[1:])
            system = left.system + right.system
            joints = left.joints + right.joints
            work.remove_node(link)
            work.add_edge(
                a, b, node=SeriesParallelNode("series", (a, b), system, tuple(chain), links, joints=joints)
            )
            changed = True
            break
    if set(work.nodes) != {base, platform} or work.number_of_edges() != 1:
        raise TwistGraphError(
            "Expected a series-parallel twist graph between base and platform, got a topology that does "
            f"not reduce (links left: {sorted(map(str, work.nodes))}); use method='loop_closure'."
        )
    ((_, _, data),) = work.edges(data=True)
    return _oriented(data["node"], base)


def _oriented(node: SeriesParallelNode, start: Any) -> SeriesParallelNode:
    return node if node.ends[0] == start else node.reversed()


def _flatten_series(node: SeriesParallelNode) -> list[SeriesParallelNode]:
    return list(node.children) if node.kind == "series" else [node]


def _series_links(node: SeriesParallelNode) -> tuple[Any, ...]:
    return node.links if node.kind == "series" else node.ends


def platform_twist_system(
    graph: nx.MultiDiGraph,
    *,
    method: Literal["loop_closure", "reduction"] = "loop_closure",
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    locked: Iterable[str] = (),
) -> ScrewSystem:
    """The twist system of the platform relative to the base.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
    method : {"loop_closure", "reduction"}
        ``"loop_closure"`` (any topology) or ``"reduction"`` (series-parallel graphs, paper 002
        Eqs. 1–2). Both agree where both apply.
    joint_key : str
    rtol : float, default 1e-9
    length_scale : float, optional
        Defaults to the length of :func:`graph_frame`.
    locked : iterable of str
        Names of joints held fixed (loop-closure method only), e.g. an actuated joint.

    Examples
    --------
    >>> from screwkit.graphs.joints import spherical
    >>> G = twist_graph("B", "E", [("B", "rod", spherical("S1", [0, 0, 0])),
    ...                            ("rod", "E", spherical("S2", [0, 0, 1]))])
    >>> platform_twist_system(G).order  # the rod's spin about its axis is internal
    5
    """
    check_twist_graph(graph, joint_key=joint_key)
    scale = graph_frame(graph, joint_key=joint_key)[1] if length_scale is None else length_scale
    locked_names = frozenset(locked)
    unknown = locked_names - {key for _, _, key in graph.edges(keys=True)}
    if unknown:
        raise TwistGraphError(
            f"Expected `locked` to name joints of the graph, got unknown {sorted(unknown)}."
        )
    if method == "reduction":
        if locked_names:
            raise TwistGraphError("Expected no `locked` joints with method='reduction'; use 'loop_closure'.")
        return series_parallel_tree(graph, joint_key=joint_key, rtol=rtol, length_scale=scale).system
    if method == "loop_closure":
        return _loop_closure_twists(graph, joint_key, rtol, scale, locked_names)
    raise TwistGraphError(f"Expected method 'loop_closure' or 'reduction', got {method!r}.")


# the equivalent twist graph ----------------------------------------------------------------------
def equivalent_twist_graph(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    tree: SeriesParallelNode | None = None,
) -> nx.MultiDiGraph:
    """Replace each closed sub-loop by a virtual serial chain with the same twist system.

    A closed sub-loop is a parallel node of the series-parallel decomposition whose two end links
    are both different from the base (e.g. the 4S parallelogram of an H4 leg between its arm and
    its sub-platform, paper 002 Fig. 2). Its virtual chain has one virtual joint per screw of a
    readable basis of its twist system (couples/translations → ``vP``, lines → ``vR``), chained
    through virtual links named ``"<a>~<b>/1"``, ...; paper 002 Fig. 2b and Fig. 3. Parallel
    chains that start at the base (the limbs) are kept, so the result has the same limbs.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
    joint_key, rtol, length_scale
        As in :func:`series_parallel_tree`.
    tree : SeriesParallelNode, optional
        The graph's series-parallel decomposition when it is at hand, e.g. the analysis core's
        (:attr:`screwkit.core.wrench_systems.WrenchAnalysis.tree`, the same nodes and twist systems from the
        core's frames); default: :func:`series_parallel_tree` of ``graph``.

    Returns
    -------
    networkx.MultiDiGraph
        A new twist graph (graph attributes copied, ``equivalent=True``).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, spherical
    >>> m, n, p, q = [0, 0, 0], [1, 0, 0], [0, 0, -2], [1, 0, -2]
    >>> G = twist_graph("B", "E", [
    ...     ("B", "arm", revolute("A", [1, 0, 0], [0, 0, 0], actuated=True)),
    ...     ("arm", "rod1", spherical("Sm", m)), ("rod1", "E", spherical("Sp", p)),
    ...     ("arm", "rod2", spherical("Sn", n)), ("rod2", "E", spherical("Sq", q))])
    >>> sorted(j.type for _, _, j in equivalent_twist_graph(G).edges(data="joint"))
    ['R', 'vP', 'vP', 'vR', 'vR']
    """
    if tree is None:
        tree = series_parallel_tree(graph, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
    result = nx.MultiDiGraph(**graph.graph)
    result.graph["equivalent"] = True
    base = graph.graph["base"]
    counter = itertools.count(1)

    def expand(node: SeriesParallelNode) -> None:
        a, b = node.ends
        if node.kind == "joint":
            u, v, key = node.edge  # type: ignore[misc]
            result.add_edge(u, v, key=key, **{joint_key: graph.edges[u, v, key][joint_key]})
        elif node.kind == "series":
            for child in node.children:
                expand(child)
        elif base in (a, b) or node.system.order == 0:
            # limbs from the base are kept; so is a rigid sub-loop (no virtual chain can weld a to b)
            for child in node.children:
                expand(child)
        else:
            screws = node.system.readable_basis()
            links = [a, *[f"{a}~{b}/{i}" for i in range(1, len(screws))], b]
            for i, screw in enumerate(screws):
                name = f"v{next(counter)}[{a}~{b}]"
                joint = virtual(name, screw)
                result.add_edge(links[i], links[i + 1], key=name, **{joint_key: joint})

    expand(tree)
    return result


def simple_paths(graph: nx.MultiDiGraph, source: Any = None, target: Any = None) -> list[list[LoopEdge]]:
    """All simple paths between two links (default: base to platform), as traversed edges.

    These are the *limbs* of a parallel mechanism in the sense of paper 002 §4.3: each path from
    the base to the platform, through intermediate bodies such as a nacelle.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
    ...                            ("E", "B", revolute("R2", [0, 0, 1], [1, 0, 0]))])
    >>> simple_paths(G)
    [[('B', 'E', 'R1', 'forward')], [('E', 'B', 'R2', 'reverse')]]
    """
    source = graph.graph["base"] if source is None else source
    target = graph.graph["platform"] if target is None else target
    undirected = nx.MultiGraph()
    for u, v, key in graph.edges(keys=True):
        undirected.add_edge(u, v, key=key, stored=(u, v))
    paths = []
    for path in nx.all_simple_edge_paths(undirected, source, target):
        traversed: list[LoopEdge] = []
        current = source
        for u, v, key in path:
            stored = undirected.edges[u, v, key]["stored"]
            forward = stored[0] == current
            traversed.append((stored[0], stored[1], key, "forward" if forward else "reverse"))
            current = stored[1] if forward else stored[0]
        paths.append(traversed)
    return sorted(paths, key=lambda p: [str(e[2]) for e in p])


# saving and loading ------------------------------------------------------------------------------
def to_data(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> dict[str, Any]:
    """Plain, JSON-ready data of a twist graph (``nx.node_link_data`` with joints encoded).

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
