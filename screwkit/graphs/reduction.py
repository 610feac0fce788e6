"""Series-parallel reduction of a twist graph: the platform's twist system and the equivalent graph.

The platform's twist system is computed two ways that agree wherever both apply:

* **reduction** (paper 002 Eqs. 1–2): the sum of twist systems along serial chains and their
  intersection across parallel chains, on a series-parallel graph (:func:`series_parallel_tree`).
  It also yields the *equivalent twist graph* in which each closed sub-loop not touching the base
  (such as a 4S parallelogram, paper 002 Fig. 2) is replaced by a virtual serial chain spanning the
  same twist system (paper 002 Fig. 3; :func:`equivalent_twist_graph`);
* **loop closure**: the joint rates allowed by the loop-closure equations (the null space of the
  loop-closure matrix, :mod:`screwkit.graphs.loops`), mapped to the platform along a spanning
  tree. It works for any topology.

Examples
--------
>>> from screwkit.graphs.joints import revolute, prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("ground", "slider", [
...     ("ground", "arm", revolute("R1", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("arm", "slider", prismatic("P1", [1, 0, 0])),
... ])
>>> platform_twist_system(G).order, platform_twist_system(G, method="reduction").order
(2, 2)
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any, Literal

import networkx as nx

from ..algebra import backend as B
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import TwistGraphError
from .joints import virtual
from .loops import _loop_closure_twists
from .twistgraph import check_twist_graph, graph_frame

__all__ = ["SeriesParallelNode", "equivalent_twist_graph", "platform_twist_system", "series_parallel_tree"]


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
        """The same node seen from its other end (its children too).

        Returns
        -------
        SeriesParallelNode
        """
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

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding the joints.
    rtol : float, default 1e-9
        Relative tolerance of the twist systems' rank decisions.
    length_scale : float, optional
        Their characteristic length (default: :func:`~screwkit.graphs.twistgraph.graph_frame`'s).

    Returns
    -------
    SeriesParallelNode
        The root, oriented from the base to the platform.

    Raises
    ------
    TwistGraphError
        If the graph is not series-parallel between base and platform (use the loop-closure method).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
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

    Returns
    -------
    ScrewSystem

    Examples
    --------
    >>> from screwkit.graphs.joints import spherical
    >>> from screwkit.graphs.twistgraph import twist_graph
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
    >>> from screwkit.graphs.twistgraph import twist_graph
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
