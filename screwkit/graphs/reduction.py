"""Series-parallel reduction of a twist graph: the platform's twist system and the equivalent graph.

The platform's twist system is computed two ways that agree wherever both apply:

* **reduction** (paper 002 Eqs. 1–2): the sum of twist systems along serial chains and their
  intersection across parallel chains, on a series-parallel graph (:func:`series_parallel_tree`:
  the series-parallel tree of :func:`screwkit.graphs.topology.topology`, the analysis core's, with
  each node's twist system). It also yields the *equivalent twist graph* in which each closed
  sub-loop not touching the base (such as a 4S parallelogram, paper 002 Fig. 2) is replaced by a
  virtual serial chain spanning the same twist system (paper 002 Fig. 3; :func:`equivalent_twist_graph`);
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
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace
from typing import Any, Literal

import networkx as nx

from ..algebra import backend as B
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import TwistGraphError
from .joints import virtual
from .jointtable import JointTable
from .loops import _loop_closure_twists
from .topology import Topology, topology
from .twistgraph import check_twist_graph, graph_frame

__all__ = ["SeriesParallelNode", "equivalent_twist_graph", "platform_twist_system", "series_parallel_tree"]


@dataclass(frozen=True, eq=False)
class SeriesParallelNode:
    """A node of a mechanism's series-parallel tree at a configuration, seen from the base.

    The tree is the analysis core's (:class:`~screwkit.graphs.topology.Node`, built once per
    mechanism by :func:`~screwkit.graphs.topology.topology`); :meth:`from_topology` gives each of
    its nodes a twist system and orients it from the base.

    Attributes
    ----------
    kind : {"joint", "series", "parallel"}
    ends : (link, link)
        The two terminal links, the base side first.
    system : ScrewSystem
        Twist system of ``ends[1]`` relative to ``ends[0]`` (sum in series, intersection in
        parallel: paper 002 Eqs. 1–2).
    children : tuple of SeriesParallelNode
        Series: in chain order from ``ends[0]``; parallel: the branches, each with the same ends.
    links : tuple
        For a series node, the links along the chain from ``ends[0]`` to ``ends[1]``.
    edge : (u, v, key) or None
        For a joint node, the graph edge.
    joints : tuple of str
        The joints below the node.
    """

    kind: Literal["joint", "series", "parallel"]
    ends: tuple[Any, Any]
    system: ScrewSystem
    children: tuple[SeriesParallelNode, ...] = ()
    links: tuple[Any, ...] = ()
    edge: tuple[Any, Any, str] | None = None
    joints: tuple[str, ...] = field(default=())

    @classmethod
    def from_topology(cls, top: Topology, systems: Sequence[ScrewSystem]) -> SeriesParallelNode:
        """The root of a topology's tree, each node with its twist system, oriented from the base.

        Parameters
        ----------
        top : Topology
            A series-parallel topology (``top.root`` is not None).
        systems : sequence of ScrewSystem
            The twist system of each node of ``top.nodes``, in their order.

        Returns
        -------
        SeriesParallelNode
            The root, from ``top.base`` to ``top.platform``.

        Examples
        --------
        >>> from screwkit.algebra.screw import revolute_twist
        >>> from screwkit.graphs.jointtable import JointSpec
        >>> from screwkit.graphs.topology import topology
        >>> top = topology("B", "E", (JointSpec("R", "R", "E", "B", 1),))  # an edge E -> B
        >>> hinge = ScrewSystem.span([revolute_twist([0, 0, 1], [0, 0, 0])])
        >>> root = SeriesParallelNode.from_topology(top, [hinge])
        >>> root.ends, root.edge, root.system.order
        (('B', 'E'), ('E', 'B', 'R'), 1)
        """

        def build(index: int, start: Any) -> SeriesParallelNode:
            node = top.nodes[index]
            forward = node.ends[0] == start
            children: list[SeriesParallelNode] = []
            current = start
            for child in node.children if forward or node.kind != "series" else node.children[::-1]:
                children.append(build(child, current))
                current = children[-1].ends[1] if node.kind == "series" else start
            edge = None
            if node.joint is not None:
                spec = top.specs[node.joint]
                edge = (spec.parent, spec.child, spec.name)
            ends = (start, node.ends[1] if forward else node.ends[0])
            links = node.links if forward else node.links[::-1]
            return cls(node.kind, ends, systems[index], tuple(children), links, edge, node.joints)

        if top.root is None:
            raise TwistGraphError("Expected a series-parallel topology, got a network (no tree).")
        return build(top.root, top.base)


def series_parallel_tree(
    graph: nx.MultiDiGraph,
    *,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> SeriesParallelNode:
    """The series-parallel tree of a twist graph, each node with its twist system.

    The tree is the analysis core's (:func:`~screwkit.graphs.topology.topology`: links other than
    base and platform attached by a single joint are dropped, joints between the same two links
    form a parallel node, a link with exactly two joints joins them in series); each joint node
    spans its joint's screws, a series node the sum of its children's twist systems and a
    parallel node their intersection (paper 002 Eqs. 1–2).

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
        The root, oriented from the base to the platform (:meth:`SeriesParallelNode.from_topology`).

    Raises
    ------
    TwistGraphError
        If the graph is not a twist graph, or not series-parallel between base and platform (use
        the loop-closure method).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "L", revolute("R", [0, 0, 1], [0, 0, 0])),
    ...                            ("L", "E", prismatic("P", [1, 0, 0]))])
    >>> tree = series_parallel_tree(G)
    >>> tree.kind, tree.system.order, tree.links
    ('series', 2, ('B', 'L', 'E'))
    >>> [(child.kind, child.edge) for child in tree.children]
    [('joint', ('B', 'L', 'R')), ('joint', ('L', 'E', 'P'))]
    """
    check_twist_graph(graph, joint_key=joint_key)
    scale = graph_frame(graph, joint_key=joint_key)[1] if length_scale is None else length_scale
    # sorted by name as the analysis core sorts them: the core's tree. Its structure only: no limbs,
    # so that an actuated joint off every base-to-platform path is dropped like any dangling joint
    table = JointTable.from_graph(graph, joint_key=joint_key)
    specs = tuple(sorted((replace(spec, actuated=False) for spec in table.specs), key=lambda spec: spec.name))
    top = topology(graph.graph["base"], graph.graph["platform"], specs)
    if top.network:
        raise TwistGraphError(
            "Expected a series-parallel twist graph between base and platform, got a topology that does "
            f"not reduce (links left: {sorted(map(str, top.irreducible))}); use method='loop_closure'."
        )
    systems: list[ScrewSystem] = []
    for node in top.nodes:  # post-order: children first
        if node.joint is not None:
            spec = top.specs[node.joint]
            screws = graph.edges[spec.parent, spec.child, spec.name][joint_key].screws
            systems.append(ScrewSystem.span(screws, rtol=rtol, length_scale=scale))
            continue
        system = systems[node.children[0]]
        for child in node.children[1:]:
            system = system + systems[child] if node.kind == "series" else system & systems[child]
        systems.append(system)
    return SeriesParallelNode.from_topology(top, systems)


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
        The graph's series-parallel tree when it is at hand, e.g. the analysis core's
        (:attr:`screwkit.core.wrench_systems.WrenchAnalysis.tree`: the same tree, its twist systems from the
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
