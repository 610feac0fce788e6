"""Loops of a twist graph and the loop-closure matrix (paper 002 §4; docs/architecture.md §5).

``nx.cycle_basis`` rejects multigraphs (parallel joints are loops too), so the loops are built
from a spanning tree from the base and reported as traversed edges ``(u, v, key, "forward" |
"reverse")`` (:data:`LoopEdge`). The loop-closure matrix stacks, for each fundamental loop, the
six equations ``Σ ±$_j q_j = 0``; the joint rates it allows (its null space), mapped to the
platform along the tree, are the platform's twists for any topology
(:func:`screwkit.graphs.reduction.platform_twist_system`).

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("B", "E", [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
...                            ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))])
>>> len(fundamental_loops(G)), loop_closure_matrix(G)[0].shape
(1, (6, 2))
"""

from __future__ import annotations

from collections import deque
from collections.abc import Iterable
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.branch_values import zeros
from ..algebra.ranks import screw_image_of_nullspace
from ..algebra.screwsystem import ScrewSystem
from .twistgraph import check_twist_graph

__all__ = ["LoopEdge", "fundamental_loops", "joint_screws_along", "loop_closure_matrix", "simple_paths"]

Array = np.ndarray
#: An edge as traversed in a loop or path: (u, v, key, "forward" | "reverse").
LoopEdge = tuple[Any, Any, str, str]


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

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    list of list of LoopEdge

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
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

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    edges : iterable of LoopEdge
        The traversed edges (a loop or a path).
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    numpy.ndarray, shape (n, 6)
        The screws, negated on edges traversed in reverse.

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
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

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.

    Returns
    -------
    matrix : numpy.ndarray, shape (6 · loops, joint freedoms)
    columns : list of (u, v, key, index)
        The joint freedom of each column (index: which screw of the joint).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
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
    matrix = zeros((6 * len(loops), len(columns)), symbolic=symbolic)
    for row, loop in enumerate(loops):
        for u, v, key, direction in loop:
            screws = _promoted(graph.edges[u, v, key][joint_key].screws, symbolic)
            sign = 1 if direction == "forward" else -1
            for i, screw in enumerate(screws):
                matrix[6 * row : 6 * row + 6, index[(u, v, key, i)]] += sign * screw
    return matrix, columns


def _promoted(screws: Array, symbolic: bool) -> Array:
    """Numeric screws as exact sympy numbers when the matrix is symbolic (no floats leak in)."""
    return B.promote(screws, zeros((0,), symbolic=True))[0] if symbolic else screws


def _loop_closure_twists(
    graph: nx.MultiDiGraph, joint_key: str, rtol: float, length_scale: float, locked: frozenset[str]
) -> ScrewSystem:
    matrix, columns = loop_closure_matrix(graph, joint_key=joint_key)
    free = [i for i, column in enumerate(columns) if column[2] not in locked]
    parent_edge = _spanning_tree(graph)
    path = _tree_path(parent_edge, graph.graph["base"], graph.graph["platform"])
    index = {c: i for i, c in enumerate(columns)}
    symbolic = B.is_symbolic(*(joint.screws for _, _, joint in graph.edges(data=joint_key)))
    path_matrix = zeros((6, len(columns)), symbolic=symbolic)
    for u, v, key, direction in path:
        screws = _promoted(graph.edges[u, v, key][joint_key].screws, symbolic)
        for i, screw in enumerate(screws):
            path_matrix[:, index[(u, v, key, i)]] += screw if direction == "forward" else -screw
    matrix, path_matrix = matrix[:, free], path_matrix[:, free]
    if not free:
        return ScrewSystem.zero(rtol=rtol, length_scale=length_scale)
    twists = screw_image_of_nullspace(path_matrix, matrix, rtol=rtol, length_scale=length_scale)
    return ScrewSystem.span(twists, rtol=rtol, length_scale=length_scale)


def simple_paths(graph: nx.MultiDiGraph, source: Any = None, target: Any = None) -> list[list[LoopEdge]]:
    """All simple paths between two links (default: base to platform), as traversed edges.

    These are the *limbs* of a parallel mechanism in the sense of paper 002 §4.3: each path from
    the base to the platform, through intermediate bodies such as a nacelle.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    source, target : hashable, optional
        The end links (default: the graph's base and platform).

    Returns
    -------
    list of list of LoopEdge
        Sorted by the joints' names.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
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
