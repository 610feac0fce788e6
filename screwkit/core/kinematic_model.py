"""The product-of-exponentials model of a twist graph: where every link is, which screws its joints
carry there, and how far its loops are from closing, over a batch of joint values.

A twist graph holds one configuration of a mechanism (its joint screws there), the *reference*.
Every joint gets variables, one per screw (a Π parallelogram one: its hinge angle), zero at the
reference; a spanning tree from the base places each link by the product of exponentials of the
joint screws along its tree path (Brockett's formula in its spatial form: Murray, Li & Sastry, *A
Mathematical Introduction to Robotic Manipulation*, 1994, §3.2, Eq. 3.22; a link's displacement is
``g = Π exp(ŝᵢ θᵢ)`` with the screws ``sᵢ`` at the reference). Each joint off the tree closes one
loop: the displacement around it must be the identity (:meth:`KinematicModel.loop_residual`), and
the Jacobian of that residual is made of the joints' *current* screws (the reference screws carried
by the adjoint of the displacement before them; Murray, Li & Sastry Eq. 3.55), signed by the loop's
direction of travel (:meth:`KinematicModel.loop_jacobian`).

Two refinements make the model usable over a whole motion, not only near the reference:

* a spherical joint's three rotations are carried as a rotation *offset* (about its centre) times
  the product of exponentials of its three screws, and :meth:`KinematicModel.recentred` folds the
  angles into the offset, so three Euler-like angles never reach their gimbal lock (the S joint's
  screws span a Lie subalgebra, so offset × exponentials still covers every rotation about the
  centre);
* a Π joint (:func:`~screwkit.graphs.joints.parallelogram`) moves its coupler on a circle of the
  rods' length (the joint's ``rod_length`` when the graph has it, else the mechanism's characteristic
  length: the incidences the structure implies are kept either way, the finite motion is exact only
  with the length).

The work is done about the mechanism's reference point and in units of its characteristic length
(:func:`~screwkit.graphs.twistgraph.graph_frame`): the configurations reached do not depend on where
the user put the origin or which length unit they used. Everything is batched over a leading axis.

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> fourbar = twist_graph("ground", "coupler", [
...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
...     ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
...     ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0]))], dof=1)
>>> model = KinematicModel(fourbar)
>>> model.size, len(model.closing)
(4, 1)
>>> state = model.state(np.zeros((2, 4)))
>>> model.loop_residual(state).shape, float(abs(model.loop_residual(state)).max())
((2, 6), 0.0)
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np

from ..algebra.compiled import compiled_kernels
from ..algebra.rigid_motions import rotation_log
from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointSpec, JointTable
from ..graphs.twistgraph import graph_frame
from ._batched_poe import KERNELS, BatchedProduct, rigid_inverse
from ._joint_rows import joint_rows, unscaled_screws

__all__ = ["JointColumn", "KinematicModel", "KinematicState"]

Array = np.ndarray


@dataclass(frozen=True)
class JointColumn:
    """One joint variable: the joint's screw ``row`` (scaled frame) on the edge ``parent → child``.

    Attributes
    ----------
    joint : str
    parent, child : hashable
    row : numpy.ndarray, shape (6,)
        The unit screw at the reference, about the model's reference point in characteristic lengths.
    index : int
        The screw's index within its joint.
    hinge, rod : numpy.ndarray or None
        For a Π joint: the hinges' unit axis and the rod vector (scaled), else None.
    """

    joint: str
    parent: Any
    child: Any
    row: Array
    index: int
    hinge: Array | None = None
    rod: Array | None = None


@dataclass(frozen=True)
class KinematicState:
    """The model at a batch of joint values: link displacements and current screws (scaled frame).

    Attributes
    ----------
    theta : numpy.ndarray, shape (B, n)
        The joint values (radians; characteristic lengths for sliders).
    offsets : dict
        Spherical joint name → rotation offsets ``(B, 4, 4)`` (:meth:`KinematicModel.recentred`).
    links : dict
        Link → displacement ``(B, 4, 4)`` from the reference.
    current : numpy.ndarray, shape (B, n, 6)
        Every joint screw at these joint values.
    motions : dict
        Joint name → its relative displacement ``(B, 4, 4)``.
    stacked : tuple of numpy.ndarray or None
        The arrays ``links`` and ``motions`` view, ``(B, links, 4, 4)`` and ``(B, joints, 4, 4)``
        (the model's link and joint order), when the state was evaluated at once.
    """

    theta: Array
    offsets: dict[str, Array]
    links: dict[Any, Array]
    current: Array
    motions: dict[str, Array] = field(repr=False)
    stacked: tuple[Array, Array] | None = field(default=None, repr=False)


_ROOTS = object()  # the node joined to the base (and the pinned link) that the spanning forest grows from


def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v)



class KinematicModel:
    """The product-of-exponentials model of a twist graph about its scaled frame (module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A numeric twist graph at its reference configuration.
    joint_key : str, default "joint"
        The edge attribute holding the joints.
    pinned : hashable, optional
        A link placed from outside (:meth:`state`'s ``pinned``), like the base: the spanning forest
        then grows from both, and each loop stays within the limbs that it closes.

    Attributes
    ----------
    point : numpy.ndarray, shape (3,)
        The reference point of the scaled frame (graph units).
    length : float
        The characteristic length (graph units).
    columns : list of JointColumn
        One per joint variable, joints in name order.
    joints : dict
        Joint name → ``(parent, child, column indices)``.
    types : dict
        Joint name → joint type.
    joint_points : dict
        Joint name → its own point (graph frame), for joints built with one.
    closing : list of str
        The joints off the spanning tree, one loop each.
    incidence : numpy.ndarray, shape (loops, n)
        Each loop's signed columns (+1 along its direction of travel).
    paths : dict
        Link → ``(n,)`` signed columns of its tree path from the base (or the pinned link).
    roots : list
        The base, and the pinned link if any.
    blocks : list of tuple
        ``(equation rows, columns)`` of each part of the graph that the roots separate: the loop
        equations of :meth:`loop_jacobian` that involve only those joint variables.

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> arm = twist_graph("B", "E", [("B", "L", revolute("R", [0, 0, 1], [0, 0, 0])),
    ...                              ("L", "E", prismatic("P", [1, 0, 0]))])
    >>> KinematicModel(arm).paths["E"].tolist()
    [1.0, 1.0]
    """

    def __init__(self, graph: nx.MultiDiGraph, joint_key: str = "joint", *, pinned: Any = None):
        self.point, self.length = graph_frame(graph, joint_key=joint_key)
        self._source = (graph, joint_key)
        self._pinned_models: dict[Any, KinematicModel] = {}
        self.base = graph.graph["base"]
        self.roots = [self.base] if pinned is None else [self.base, pinned]
        self.platform = graph.graph["platform"]
        self.columns: list[JointColumn] = []
        self.joints: dict[str, tuple[Any, Any, list[int]]] = {}
        self.types: dict[str, str] = {}
        self.joint_points: dict[str, Array] = {}  # a joint's own point (its geometry), when it has one
        for u, v, key, joint in sorted(graph.edges(keys=True, data=joint_key), key=lambda e: str(e[2])):
            indices = []
            for k, row in enumerate(np.asarray(joint.screws, dtype=float)):
                hinge = rod = None
                if joint.type == "Pa" and {"hinge_axis", "rod_direction"} <= set(joint.geometry):
                    hinge = _unit(np.asarray(joint.geometry["hinge_axis"], dtype=float))
                    rod = np.asarray(joint.geometry["rod_direction"], dtype=float)
                    length = float(joint.geometry.get("rod_length", self.length))
                    rod = _unit(rod - hinge * (hinge @ rod)) * (length / self.length)
                indices.append(len(self.columns))
                self.columns.append(JointColumn(key, u, v, self._scaled(row), k, hinge, rod))
            self.joints[key] = (u, v, indices)
            self.types[key] = joint.type
            for name in ("point", "center"):
                if name in joint.geometry:
                    self.joint_points[key] = np.asarray(joint.geometry[name], dtype=float)
        undirected = nx.Graph(graph.to_undirected())
        undirected.add_edges_from((_ROOTS, root) for root in self.roots)
        tree = nx.bfs_tree(undirected, _ROOTS)
        tree.remove_node(_ROOTS)
        self.order = list(nx.topological_sort(tree))  # links, each after its tree parent
        chosen: dict[Any, tuple[str, bool]] = {}  # link → (tree joint reaching it, traversed forward)
        for parent, child in tree.edges():
            key = next(k for u, v, k in graph.edges(keys=True) if {u, v} == {parent, child})
            chosen[child] = (key, self.joints[key][0] == parent)
        self.tree = chosen
        tree_joints = {key for key, _ in chosen.values()}
        self.closing = [key for key in self.joints if key not in tree_joints]
        self.paths = {link: self._path(link) for link in self.order}
        rows = []
        for key in self.closing:
            u, v, indices = self.joints[key]
            signs = self.paths.get(u, np.zeros(self.size)) - self.paths.get(v, np.zeros(self.size))
            signs[indices] += 1.0
            rows.append(signs)
        self.incidence = np.array(rows).reshape(len(rows), self.size)
        self._product = BatchedProduct(self.columns, self.joints, self.order, self.tree, self.roots)
        links, joints = self._product.link_index, self._product.joint_index
        self._loops = np.array(  # (u, v, joint) of each loop, for the compiled residual
            [[links[self.joints[key][0]], links[self.joints[key][1]], joints[key]] for key in self.closing],
            dtype=np.int64,
        ).reshape(-1, 3)
        self.blocks = self._blocks()

    def _blocks(self) -> list[tuple[Array, Array]]:
        parts = nx.Graph()
        for key, (u, v, _) in self.joints.items():
            parts.add_node(("joint", key))
            ends = [("link", link) for link in (u, v) if link not in self.roots]
            parts.add_edges_from((("joint", key), end) for end in ends)
        blocks = []
        for part in nx.connected_components(parts):
            keys = {name for kind, name in part if kind == "joint"}
            loops = [i for i, key in enumerate(self.closing) if key in keys]
            if loops:
                rows = np.array([6 * i + k for i in loops for k in range(6)])
                blocks.append((rows, np.array(sorted(c for key in keys for c in self.joints[key][2]))))
        return blocks

    def pinned_model(self, link: Any) -> KinematicModel:
        """The same mechanism with ``link`` placed from outside (the parameter ``pinned``), built once.

        Parameters
        ----------
        link : hashable
            A link of the graph other than the base.

        Returns
        -------
        KinematicModel
            Its columns, joints and scaled frame are this model's.

        Raises
        ------
        ScrewkitValueError
            If ``link`` is the base or not a link of the graph.

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> arm = twist_graph("B", "E", [("B", "L", revolute("R1", [0, 0, 1], [0, 0, 0])),
        ...                              ("L", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))])
        >>> pinned = KinematicModel(arm).pinned_model("E")
        >>> pinned.closing, [rows.size for rows, _ in pinned.blocks]  # the arm closes on its end link
        (['R2'], [6])
        """
        if link == self.base or link not in self.paths:
            raise ScrewkitValueError(
                f"Expected a link of the graph other than the base for link, got {link!r}."
            )
        if link not in self._pinned_models:
            graph, joint_key = self._source
            self._pinned_models[link] = KinematicModel(graph, joint_key, pinned=link)
        return self._pinned_models[link]

    @property
    def size(self) -> int:
        """The number of joint variables ``n``."""
        return len(self.columns)

    def _path(self, link: Any) -> Array:
        """The tree joints' columns from the base to ``link``, signed by the direction of travel."""
        signs = np.zeros(self.size)
        while link not in self.roots:
            key, forward = self.tree[link]
            u, v, indices = self.joints[key]
            signs[indices] = 1.0 if forward else -1.0
            link = u if forward else v
        return signs

    def _scaled(self, row: Array) -> Array:
        s, s0 = row[:3], row[3:]
        moment = (s0 - np.cross(self.point, s)) / self.length
        # a couple when its direction is negligible against the moment about the reference point in
        # characteristic lengths: the test is then free of the length unit and of where the origin
        # is (against the raw row, a hinge 1e15 lengths from the origin read as a slider)
        if np.linalg.norm(s) < 1e-12 * np.linalg.norm(moment):
            return np.concatenate([np.zeros(3), s0 / np.linalg.norm(s0)])
        return np.concatenate([s, moment]) / np.linalg.norm(s)

    def unscaled(self, rows: Array) -> Array:
        """Screws ``(..., 6)`` of the scaled frame back in the graph's frame and unit.

        Parameters
        ----------
        rows : numpy.ndarray, shape (..., 6)

        Returns
        -------
        numpy.ndarray, shape (..., 6)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [5, 0, 0]))]))
        >>> model.unscaled(model.columns[0].row) + 0.0
        array([ 0.,  0.,  1.,  0., -5.,  0.])
        """
        return unscaled_screws(rows, self.length, self.point)

    def to_scaled_points(self, points: Array) -> Array:
        """Points ``(..., 3)`` of the graph's frame in the scaled frame.

        Parameters
        ----------
        points : array_like, shape (..., 3)

        Returns
        -------
        numpy.ndarray, shape (..., 3)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [5, 0, 0]))]))
        >>> bool(np.allclose(model.to_scaled_points(model.point), 0.0))
        True
        """
        return (np.asarray(points, dtype=float) - self.point) / self.length

    def displacement(self, state: KinematicState, link: Any) -> Array:
        """A link's displacement from the reference in the graph's frame and unit: ``(B, 4, 4)``.

        Parameters
        ----------
        state : KinematicState
        link : hashable

        Returns
        -------
        numpy.ndarray, shape (B, 4, 4)
            ``x ↦ R x + p`` in the graph's frame.

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0]))]))
        >>> moved = model.displacement(model.state(np.array([[0.5]])), "E")
        >>> bool(np.isclose(moved[0, 0, 3], 0.5 * model.length))
        True
        """
        g = state.links[link].copy()
        rotation = g[:, :3, :3]
        g[:, :3, 3] = self.point - rotation @ self.point + self.length * g[:, :3, 3]
        return g

    def state(
        self, theta: Array, offsets: dict[str, Array] | None = None, pinned: Array | None = None
    ) -> KinematicState:
        """Link displacements (from the tree) and the current screws at joint values ``theta``.

        Parameters
        ----------
        theta : numpy.ndarray, shape (B, n)
        offsets : dict, optional
            Spherical joint name → rotation offsets ``(B, 4, 4)`` (default: none).
        pinned : numpy.ndarray, shape (B, 4, 4), optional
            The pinned link's displacements (scaled frame), for a model built with one.

        Returns
        -------
        KinematicState

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))]))
        >>> state = model.state(np.array([[np.pi]]))
        >>> model.displacement(state, "E")[0, :3, 3].round(12) + 0.0  # the origin turns about x = 1
        array([2., 0., 0.])
        """
        offsets = dict(offsets or {})
        links, motions, current = self._product.evaluate(theta, offsets, pinned)
        return KinematicState(
            theta,
            offsets,
            {link: links[:, i] for link, i in self._product.link_index.items()},
            current,
            {key: motions[:, j] for key, j in self._product.joint_index.items()},
            (links, motions),
        )

    def loop_residual(self, state: KinematicState) -> Array:
        """How far each loop is from closing: ``(B, 6 L)``, rotation vector then translation (scaled).

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, 6 L)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> model.loop_residual(model.state(np.zeros((1, 1)))).shape  # no loop
        (1, 0)
        """
        if not self.closing:
            return np.zeros((state.theta.shape[0], 0))
        kernels = compiled_kernels(KERNELS, state.theta.shape[0])
        if kernels is not None and state.stacked is not None:
            return kernels.loop_residual(*state.stacked, self._loops)
        ends = [self.joints[key][:2] for key in self.closing]
        before = np.stack([state.links[u] for u, _ in ends], axis=1)
        motion = np.stack([state.motions[key] for key in self.closing], axis=1)
        after = np.stack([state.links[v] for _, v in ends], axis=1)
        closed = before @ motion @ rigid_inverse(after)
        residual = np.concatenate([rotation_log(closed[..., :3, :3]), closed[..., :3, 3]], axis=-1)
        return residual.reshape(state.theta.shape[0], -1)

    def loop_jacobian(self, state: KinematicState) -> Array:
        """The Jacobian of :meth:`loop_residual` in the joint variables: ``(B, 6 L, n)``.

        Parameters
        ----------
        state : KinematicState

        Returns
        -------
        numpy.ndarray, shape (B, 6 L, n)
            Each loop's current screws, signed by the loop's direction of travel.

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> loop = twist_graph("B", "E", [("B", "E", revolute("R1", [0, 0, 1], [0, 0, 0])),
        ...                               ("B", "E", revolute("R2", [0, 0, 1], [0, 0, 0]))])
        >>> model = KinematicModel(loop)
        >>> model.loop_jacobian(model.state(np.zeros((1, 2))))[0, 2].tolist()  # −R1 + R2 about z
        [-1.0, 1.0]
        """
        count = state.theta.shape[0]
        blocks = np.einsum("lc,bck->blkc", self.incidence, state.current)
        return blocks.reshape(count, 6 * len(self.closing), self.size)

    def link_jacobian(self, state: KinematicState, link: Any) -> Array:
        """The twist of a link (spatial, scaled) per unit rate of each joint variable: ``(B, 6, n)``.

        Parameters
        ----------
        state : KinematicState
        link : hashable
            A link of the graph.

        Returns
        -------
        numpy.ndarray, shape (B, 6, n)

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0]))]))
        >>> model.link_jacobian(model.state(np.zeros((1, 1))), "E")[0, :, 0].tolist()
        [0.0, 0.0, 1.0, 0.0, 0.0, 0.0]
        """
        return np.einsum("c,bck->bkc", self.paths[link], state.current)

    def recentred(self, theta: Array, offsets: dict[str, Array]) -> tuple[Array, dict[str, Array]]:
        """Joint values and offsets with every spherical joint's angles folded into its offset.

        Parameters
        ----------
        theta : numpy.ndarray, shape (B, n)
        offsets : dict
            Spherical joint name → rotation offsets ``(B, 4, 4)`` (those not given: none).

        Returns
        -------
        theta : numpy.ndarray, shape (B, n)
            The same values, spherical joints' set to 0.
        offsets : dict
            Spherical joint name → its whole rotation about its centre ``(B, 4, 4)``.

        Examples
        --------
        >>> from screwkit.graphs.joints import spherical
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> model = KinematicModel(twist_graph("B", "E", [("B", "E", spherical("S", [0, 0, 0]))], dof=3))
        >>> theta, offsets = model.recentred(np.array([[0.1, 0.2, 0.3]]), {})
        >>> theta.tolist(), offsets["S"].shape
        ([[0.0, 0.0, 0.0]], (1, 4, 4))
        """
        motions, _ = self._product.joint_motions(theta, offsets, screws=False)
        theta = theta.copy()
        offsets = dict(offsets)
        for key, kind in self.types.items():
            if kind == "S":
                offsets[key] = motions[:, self._product.joint_index[key]]
                theta[:, self.joints[key][2]] = 0.0
        return theta, offsets

    def joint_table(
        self, state: KinematicState, reference: JointTable, shape: tuple[int, ...] | None = None
    ) -> JointTable:
        """The joint table at a state: the reference table's joints with their current screws.

        Parameters
        ----------
        state : KinematicState
        reference : JointTable
            The graph's table (:meth:`~screwkit.graphs.jointtable.JointTable.from_graph`): names, types,
            actuation, dof and anchor (which moves with the platform).
        shape : tuple of int, optional
            The table's batch shape (of size ``B``; default ``(B,)``).

        Returns
        -------
        JointTable

        Raises
        ------
        ScrewkitValueError
            If ``reference`` is not this graph's table.

        Examples
        --------
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> graph = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
        >>> model = KinematicModel(graph)
        >>> model.joint_table(model.state(np.zeros((3, 1))), JointTable.from_graph(graph)).batch_shape
        (3,)
        """
        shape = (state.theta.shape[0],) if shape is None else tuple(shape)
        balls = [indices for key, (_, _, indices) in self.joints.items() if self.types[key] == "S"]
        rows = joint_rows(  # a new array, the table's: a ball's axes orthonormal, as a catalog's
            state.current.reshape(*shape, self.size, 6),
            self.length,
            self.point,
            np.array(balls, dtype=np.int64).reshape(-1, 3),
        )
        specs = {spec.name: spec for spec in reference.specs}
        if set(specs) != set(self.joints):
            raise ScrewkitValueError(
                f"Expected the joint table of the model's graph, got joints {sorted(specs)[:5]} ..."
            )
        ordered = tuple(  # the columns run joint by joint in this order (the model's)
            JointSpec(key, specs[key].type, u, v, len(indices), specs[key].actuated)
            for key, (u, v, indices) in self.joints.items()
        )
        anchor = None
        if reference.anchor is not None:  # it moves with the platform
            g = state.links[self.platform]
            local = self.to_scaled_points(np.asarray(reference.anchor))
            anchor = (np.einsum("bij,j->bi", g[:, :3, :3], local) + g[:, :3, 3]) * self.length + self.point
            anchor = anchor.reshape(*shape, 3)
        rows.flags.writeable = False  # (a read-only array that owns its data: the table keeps it)
        return JointTable(
            reference.base, reference.platform, ordered, rows, reference.dof, anchor, reference.mobility
        )
