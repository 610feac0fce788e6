"""The structure of a mechanism, analysed once: series-parallel tree, compound legs and limbs.

Everything here depends on the joints' names, types and connections only, never on their
screws, so a mechanism's structure is analysed once (and cached, :func:`topology`) and every pose
of a batch reuses it (docs/architecture.md §1a).

* The **series-parallel tree** (paper 002 Eqs. 1–2; Duffin, *J. Math. Anal. Appl.* 10, 1965):
  links other than base and platform attached by a single joint are dropped (they cannot change
  the platform's motion); joints between the same two links form a parallel node; a link with
  exactly two joints joins them in series. Each step is linear in the graph's size, so reduction
  is polynomial. A graph that does not reduce (a bridge, e.g. a Wheatstone topology) is analysed
  by loop closure instead (:attr:`Topology.network`).
* The **compound legs** are the root's branches (paper 002's ``L_I``, ``L_II``).
* A **limb** is an actuated joint with every base-to-platform path through it (paper 002 §4.3).
  In the tree: the path from the root to the joint's leaf, where a parallel node on that path
  keeps only the branch holding the joint and a series node keeps all its children. So the
  limb's twist system with the actuator locked is the sum of the *siblings* met on the way
  (:attr:`LimbPlan.siblings`), and with it free the sum of those and the actuated twist.

Examples
--------
>>> from screwkit.graphs.jointtable import JointSpec
>>> specs = [JointSpec("A", "R", "B", "arm", 1, True), JointSpec("P", "P", "arm", "E", 1, False)]
>>> top = topology("B", "E", tuple(specs))
>>> top.nodes[top.root].kind, top.limbs[0].joints
('series', ('A', 'P'))
"""

from __future__ import annotations

import functools
import itertools
from collections.abc import Hashable
from dataclasses import dataclass, replace
from typing import Any, Literal

import networkx as nx

from ..exceptions import TwistGraphError
from .jointtable import JointSpec

__all__ = ["LimbPlan", "Node", "Topology", "network_layout", "topology"]

#: Refuse loop-closure networks with more simple base-to-platform paths than this (limbs of a
#: non-series-parallel graph are unions of such paths).
MAX_NETWORK_PATHS = 10_000


@dataclass(frozen=True, eq=False)
class Node:
    """A node of the series-parallel tree.

    Attributes
    ----------
    kind : {"joint", "series", "parallel"}
    ends : (link, link)
        Its two terminal links in chain order (from the base side).
    children : tuple of int
        Indices into :attr:`Topology.nodes` (series: in chain order).
    joints : tuple of str
        The joints below it.
    joint : int or None
        For a joint node, its index in the joint table.
    links : tuple
        For a series node, the links along the chain.
    """

    kind: Literal["joint", "series", "parallel"]
    ends: tuple[Any, Any]
    children: tuple[int, ...] = ()
    joints: tuple[str, ...] = ()
    joint: int | None = None
    links: tuple[Any, ...] = ()


@dataclass(frozen=True, eq=False)
class LimbPlan:
    """One actuated joint's limb.

    Attributes
    ----------
    actuated_joint : str
    index : int
        The actuated joint's index in the joint table.
    sign : int
        +1 if the joint's edge points from the base side to the platform side along the limb,
        −1 otherwise (the actuated twist is the platform-ward one).
    siblings : tuple of int
        Tree nodes whose twist systems add up to the limb's with the actuator locked.
    joints : tuple of str
        Every joint of the limb, the actuated one included.
    network_edges : tuple of int
        For a network (non-series-parallel) topology: the joint indices of the limb's subgraph.
    path : tuple of int
        Tree nodes from the root down to the actuated joint's leaf (empty for a network).
    partners : tuple of int
        Indices into :attr:`Topology.limbs` of the actuated joints in *another branch of a parallel
        node* on :attr:`path` (the H4's ``A4`` for ``A1``: both arms carry the nacelle ``b_I``).
        The limb's own wrench ignores their motions; a compound leg with partners is analysed as a
        whole where that wrench fails (:func:`screwkit.core.wrench_systems.analyze_table`).
    """

    actuated_joint: str
    index: int
    sign: int
    siblings: tuple[int, ...]
    joints: tuple[str, ...]
    network_edges: tuple[int, ...] = ()
    path: tuple[int, ...] = ()
    partners: tuple[int, ...] = ()


@dataclass(frozen=True, eq=False)
class Topology:
    """The analysed structure of a mechanism (see the module docstring).

    Attributes
    ----------
    base, platform : hashable
    specs : tuple of JointSpec
        The joint table's joints, in table order.
    nodes : tuple of Node
        The series-parallel tree in post-order (children first); empty for a network.
    root : int or None
        Index of the root node; None when the graph is not series-parallel.
    legs : tuple of int
        The compound legs (the root's branches, or the root itself).
    limbs : tuple of LimbPlan
        One per actuated joint, sorted by name.
    network : bool
        True when the graph does not reduce and is analysed by loop closure
        (:func:`network_layout`).
    irreducible : tuple
        For a network, the links left when the reduction stops; empty otherwise.
    """

    base: Any
    platform: Any
    specs: tuple[JointSpec, ...]
    nodes: tuple[Node, ...]
    root: int | None
    legs: tuple[int, ...]
    limbs: tuple[LimbPlan, ...]
    network: bool = False
    irreducible: tuple[Any, ...] = ()

    @property
    def actuated(self) -> tuple[str, ...]:
        """The actuated joints, sorted (the limbs' order)."""
        return tuple(limb.actuated_joint for limb in self.limbs)

    @functools.cached_property  # read for every joint by the core, once per batch
    def columns(self) -> tuple[int, ...]:
        """The first screw row of each joint in the table's stacked screws."""
        return tuple(itertools.accumulate((s.dof for s in self.specs[:-1]), initial=0))


@functools.lru_cache(maxsize=64)
def topology(base: Hashable, platform: Hashable, specs: tuple[JointSpec, ...]) -> Topology:
    """Analyse the structure of a mechanism (cached on its joints' names, types and links).

    Parameters
    ----------
    base, platform : hashable
    specs : tuple of JointSpec

    Returns
    -------
    Topology

    Raises
    ------
    TwistGraphError
        If an actuated joint lies on no base-to-platform path, or a non-series-parallel graph has
        more than :data:`MAX_NETWORK_PATHS` simple base-to-platform paths.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointSpec
    >>> specs = (JointSpec("R1", "R", "B", "E", 1, True), JointSpec("R2", "R", "B", "E", 1, False))
    >>> top = topology("B", "E", specs)
    >>> [n.kind for n in top.nodes], top.limbs[0].siblings
    (['joint', 'joint', 'parallel'], ())
    """
    nodes: list[Node] = []
    work = nx.MultiGraph()
    work.add_nodes_from([base, platform])
    for index, spec in enumerate(specs):
        nodes.append(Node("joint", (spec.parent, spec.child), joints=(spec.name,), joint=index))
        work.add_edge(spec.parent, spec.child, node=len(nodes) - 1)
    orientation: dict[int, tuple[Any, Any]] = {i: n.ends for i, n in enumerate(nodes)}

    def add(node: Node) -> int:
        nodes.append(node)
        orientation[len(nodes) - 1] = node.ends
        return len(nodes) - 1

    changed = True
    while changed:
        changed = False
        for link in list(work.nodes):
            if link not in (base, platform) and work.degree(link) <= 1:
                work.remove_node(link)
                changed = True
        for a, b in sorted({tuple(sorted((u, v), key=str)) for u, v in work.edges()}, key=str):
            if work.number_of_edges(a, b) > 1:
                members = [d["node"] for d in work.get_edge_data(a, b).values()]
                flat = [
                    c for m in members for c in (nodes[m].children if nodes[m].kind == "parallel" else (m,))
                ]
                joints = tuple(itertools.chain.from_iterable(nodes[m].joints for m in flat))
                merged = add(Node("parallel", (a, b), tuple(flat), joints))
                work.remove_edges_from([(a, b)] * work.number_of_edges(a, b))
                work.add_edge(a, b, node=merged)
                changed = True
        for link in sorted(work.nodes, key=str):
            if link in (base, platform) or work.degree(link) != 2:
                continue
            (_, a, first), (_, b, second) = work.edges(link, data="node")
            chain = [*_chain(nodes, orientation, first, a), *_chain(nodes, orientation, second, link)]
            joints = tuple(itertools.chain.from_iterable(nodes[c].joints for c in chain))
            merged = add(Node("series", (a, b), tuple(chain), joints, links=_series_links(nodes, chain, a)))
            work.remove_node(link)
            work.add_edge(a, b, node=merged)
            changed = True
            break
    names = [s.name for s in specs]
    actuated = sorted((s.name, i) for i, s in enumerate(specs) if s.actuated)
    if set(work.nodes) != {base, platform} or work.number_of_edges() != 1:
        return _network(base, platform, specs, actuated, tuple(work.nodes))
    ((_, _, root),) = work.edges(data="node")
    kept = _reachable(nodes, root)
    order = [i for i in range(len(nodes)) if i in kept]  # post-order: children were added first
    renumber = {old: new for new, old in enumerate(order)}
    tree = tuple(
        Node(
            n.kind,
            _from_base(orientation[i], n.ends),
            tuple(renumber[c] for c in n.children),
            n.joints,
            n.joint,
            n.links,
        )
        for i, n in ((i, nodes[i]) for i in order)
    )
    root_index = renumber[root]
    legs = tree[root_index].children if tree[root_index].kind == "parallel" else (root_index,)
    limbs = []
    for name, index in actuated:
        leaf = next((i for i, n in enumerate(tree) if n.joint == index), None)
        if leaf is None:
            raise TwistGraphError(f"Actuated joint {name!r} lies on no path from the base to the platform.")
        siblings, joints, path = _limb_siblings(tree, root_index, leaf)
        sign = _leaf_sign(tree, root_index, leaf, base, specs[index])
        limb_joints = tuple(sorted({name, *joints}, key=names.index))
        limbs.append(LimbPlan(name, index, sign, siblings, limb_joints, (), path))
    return Topology(base, platform, specs, tree, root_index, tuple(legs), _with_partners(tree, limbs))


def _with_partners(tree: tuple[Node, ...], limbs: list[LimbPlan]) -> tuple[LimbPlan, ...]:
    """Each limb with the actuated joints in other branches of the parallel nodes on its path
    below the root (the root's branches are the compound legs, which do not share a link)."""
    result = []
    for plan in limbs:
        beside = [
            set(tree[node].joints) - set(tree[child].joints)
            for node, child in itertools.pairwise(plan.path[1:])
            if tree[node].kind == "parallel"
        ]
        partners = tuple(k for k, other in enumerate(limbs) if any(other.actuated_joint in b for b in beside))
        result.append(replace(plan, partners=partners))
    return tuple(result)


def _chain(nodes: list[Node], orientation: dict[int, tuple[Any, Any]], index: int, start: Any) -> list[int]:
    """A node's series members seen from ``start`` (a series node contributes its children)."""
    node = nodes[index]
    members = list(node.children) if node.kind == "series" else [index]
    forward = orientation[index][0] == start
    if node.kind == "series" and not forward:
        members.reverse()
    return members


def _series_links(nodes: list[Node], chain: list[int], start: Any) -> tuple[Any, ...]:
    links = [start]
    for member in chain:
        a, b = nodes[member].ends
        links.append(b if a == links[-1] else a)
    return tuple(links)


def _reachable(nodes: list[Node], root: int) -> set[int]:
    seen, stack = set(), [root]
    while stack:
        i = stack.pop()
        seen.add(i)
        stack.extend(nodes[i].children)
    return seen


def _from_base(stored: tuple[Any, Any], ends: tuple[Any, Any]) -> tuple[Any, Any]:
    return ends if ends == stored else stored


def _limb_siblings(
    tree: tuple[Node, ...], root: int, leaf: int
) -> tuple[tuple[int, ...], tuple[str, ...], tuple[int, ...]]:
    """Siblings met at series nodes on the way from the root to the leaf, their joints, and the
    path (root first)."""
    parent = {c: i for i, n in enumerate(tree) for c in n.children}
    path = [leaf]
    while path[-1] != root:
        path.append(parent[path[-1]])
    siblings: list[int] = []
    for child, node_index in itertools.pairwise(path):
        node = tree[node_index]
        if node.kind == "series":
            siblings.extend(c for c in node.children if c != child)
    joints = tuple(itertools.chain.from_iterable(tree[s].joints for s in siblings))
    return tuple(sorted(siblings)), joints, tuple(reversed(path))


def _leaf_sign(tree: tuple[Node, ...], root: int, leaf: int, base: Any, spec: JointSpec) -> int:
    """+1 when the actuated joint's edge points away from the base along its limb's chain."""
    walk = _walk_links(tree, root, base)
    position = {link: k for k, link in enumerate(walk)}
    if spec.parent in position and spec.child in position:
        return 1 if position[spec.parent] < position[spec.child] else -1
    return 1


def _walk_links(tree: tuple[Node, ...], root: int, base: Any) -> list[Any]:
    """Links in the order a depth-first walk from the base meets them (for edge orientation)."""
    order: list[Any] = [base]

    def visit(index: int, start: Any) -> Any:
        node = tree[index]
        a, b = node.ends
        end = b if a == start else a
        if node.kind == "series":
            current = start
            members = node.children if a == start else tuple(reversed(node.children))
            for child in members:
                current = visit(child, current)
        elif node.kind == "parallel":
            for child in node.children:
                visit(child, start)
        if end not in order:
            order.append(end)
        return end

    visit(root, base)
    return order


@functools.lru_cache(maxsize=256)
def network_layout(
    base: Hashable, platform: Hashable, specs: tuple[JointSpec, ...], joints: tuple[int, ...]
) -> tuple[tuple[tuple[tuple[int, int], ...], ...], tuple[tuple[int, int], ...]]:
    """Fundamental loops and a base-to-platform path of the subgraph of some joints, as
    ``(joint index, ±1)`` steps (+1 along the joint's edge), from a spanning tree.

    Parameters
    ----------
    base, platform : hashable
        The fixed link and the end effector.
    specs : tuple of JointSpec
        The mechanism's joints, in table order.
    joints : tuple of int
        Indices into ``specs`` of the subgraph's joints.

    Returns
    -------
    loops : tuple of tuple of (int, int)
        One fundamental loop per joint outside the spanning tree, starting with that joint.
    path : tuple of (int, int)
        The tree path from the base to the platform (empty if they are not connected).

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointSpec
    >>> specs = (JointSpec("R1", "R", "B", "E", 1), JointSpec("R2", "R", "B", "E", 1))
    >>> network_layout("B", "E", specs, (0, 1))
    ((((1, 1), (0, -1)),), ((0, 1),))
    """
    graph = nx.MultiGraph()
    graph.add_nodes_from([base, platform])
    for index in joints:
        graph.add_edge(specs[index].parent, specs[index].child, key=index)
    in_tree = {k for _, _, k in nx.minimum_spanning_edges(graph, algorithm="prim", keys=True, data=False)}
    spanning = nx.MultiGraph()
    spanning.add_nodes_from(graph)
    spanning.add_edges_from((specs[k].parent, specs[k].child, k) for k in sorted(in_tree))

    def oriented_path(source: Any, target: Any) -> list[tuple[int, int]]:
        steps = []
        for u, v in itertools.pairwise(nx.shortest_path(spanning, source, target)):
            key = min(spanning.get_edge_data(u, v))
            steps.append((key, 1 if specs[key].parent == u else -1))
        return steps

    loops = tuple(
        ((index, 1), *oriented_path(specs[index].child, specs[index].parent))
        for index in joints
        if index not in in_tree
    )
    path = tuple(oriented_path(base, platform)) if nx.has_path(spanning, base, platform) else ()
    return loops, path


def _network(
    base: Any,
    platform: Any,
    specs: tuple[JointSpec, ...],
    actuated: list[tuple[str, int]],
    irreducible: tuple[Any, ...],
) -> Topology:
    """A graph that does not reduce: analysed by loop closure; limbs as unions of paths."""
    graph = nx.MultiGraph()
    for index, spec in enumerate(specs):
        graph.add_edge(spec.parent, spec.child, key=index)
    paths: list[dict[int, int]] = []  # joint index -> +1 / -1 as traversed from the base
    for count, edge_path in enumerate(nx.all_simple_edge_paths(graph, base, platform)):
        if count >= MAX_NETWORK_PATHS:
            raise TwistGraphError(
                f"Expected a mechanism with at most {MAX_NETWORK_PATHS} simple base-to-platform paths "
                "outside its series-parallel parts, got more; split the model or reduce it."
            )
        paths.append({k: 1 if specs[k].parent == u else -1 for u, _, k in edge_path})
    limbs = []
    for name, index in actuated:
        through = [p for p in paths if index in p]
        if not through:
            raise TwistGraphError(f"Actuated joint {name!r} lies on no path from the base to the platform.")
        edges = tuple(sorted(set().union(*through)))
        joints = tuple(specs[e].name for e in edges)
        limbs.append(LimbPlan(name, index, through[0][index], (), joints, edges))
    return Topology(base, platform, specs, (), None, (), tuple(limbs), True, irreducible)
