"""Generic configurations of any twist graph: move the mechanism along its own mobility, close its loops.

A twist graph holds one configuration of a mechanism (its joint screws there). Structural facts
(which points of a wrench diagram coincide, which brackets vanish) must be decided at *generic*
configurations of the same mechanism, never at the analysed one, which may be singular
(gca.md §6). This module makes such configurations from the graph alone, so snapshots, graphs
built in Python and catalog robots are treated alike:

1. every joint gets variables, one per screw (a Π parallelogram one: its hinge angle), zero at the
   given configuration; a spanning tree from the base places each link by the product of
   exponentials of the joint screws along its tree path (Brockett's formula, Murray, Li & Sastry,
   *A Mathematical Introduction to Robotic Manipulation*, 1994, §3.2, Eq. 3.22, spatial form);
2. each joint off the tree closes one loop: the displacement around it must be the identity;
3. a random step in the null space of the loop-closure matrix (the joint rates the loops allow,
   docs/architecture.md §5: the platform's own twist system and the legs' internal motions), then Newton's
   method (Gauss–Newton with the pseudo-inverse, the minimum-norm correction) on the loop-closure
   equations brings every loop back together; a few such steps move the mechanism well away from
   where it started;
4. the joints' screws are carried to the new configuration by the adjoint of the displacement of
   the joint's parent link (a U's second axis also by its first rotation).

All configurations of a batch are moved together (arrays with a leading batch axis), and the
result is a :class:`~screwkit.graphs.jointtable.JointTable` over the batch: the analysis core takes it as is.

The work is done about the mechanism's reference point and in units of its characteristic length
(:func:`~screwkit.graphs.twistgraph.graph_frame`), so the configurations reached do not depend on where
the user put the origin or which length unit they used.

A Π joint's rod length is not in the graph (only its hinge axis and rod direction are): it is
taken as the mechanism's characteristic length. The coupler still translates on a circle with the
right hinge axis, so every incidence the structure implies is kept.

Examples
--------
>>> from screwkit.graphs.joints import revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> fourbar = twist_graph("ground", "coupler", [
...     ("ground", "crank", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("crank", "coupler", revolute("B", [0, 0, 1], [1, 0, 0])),
...     ("ground", "rocker", revolute("D", [0, 0, 1], [3, 0, 0])),
...     ("rocker", "coupler", revolute("C", [0, 0, 1], [3, 2, 0]))], dof=1)
>>> table = generic_configurations(fourbar, np.random.default_rng(0), 4)
>>> table.batch_shape
(4,)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from ..exceptions import ScrewkitValueError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import graph_frame

__all__ = ["generic_configurations"]

Array = np.ndarray

#: Size of one random step (radians, or characteristic lengths), before the loops are closed again.
STEP = 0.25
#: Random steps taken from the given configuration.
STEPS = 3
#: Newton iterations per step, and the loop-closure residual (in characteristic lengths) accepted.
NEWTON_ITERATIONS = 30
CLOSURE_TOL = 1e-11


@dataclass(frozen=True)
class _Column:
    """One joint variable: the joint's screw ``row`` (scaled frame) on edge ``parent → child``."""

    joint: str
    parent: Any
    child: Any
    row: Array
    index: int  # the screw's index within its joint
    hinge: Array | None = None  # a Π joint: (hinge axis, rod direction) in the scaled frame
    rod: Array | None = None


def _hat(w: Array) -> Array:
    """Cross-product matrices of ``(..., 3)`` vectors."""
    zero = np.zeros(w.shape[:-1])
    return np.stack(
        [
            np.stack([zero, -w[..., 2], w[..., 1]], -1),
            np.stack([w[..., 2], zero, -w[..., 0]], -1),
            np.stack([-w[..., 1], w[..., 0], zero], -1),
        ],
        -2,
    )


def _rotation(axis: Array, angle: Array) -> Array:
    """Rodrigues' formula for a unit ``axis (3,)`` and angles ``(B,)`` → ``(B, 3, 3)``."""
    k = _hat(axis)
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1 - c) * (k @ k)


def _exp(row: Array, angle: Array) -> Array:
    """Displacements ``(B, 4, 4)`` of the unit screw ``row = (ω; v)`` by ``angle (B,)`` (Murray, Li
    & Sastry 1994, Eq. 2.36: ``p = (I − R)(ω × v) + ω ωᵀ v θ``; ``(I, v θ)`` for ``ω = 0``)."""
    g = np.tile(np.eye(4), (len(angle), 1, 1))
    w, v = row[:3], row[3:]
    size = np.linalg.norm(w)
    if size < 1e-12:
        g[:, :3, 3] = angle[:, None] * v
        return g
    w, v = w / size, v / size  # a rotation screw: θ in radians about its unit axis
    rot = _rotation(w, angle)
    g[:, :3, :3] = rot
    g[:, :3, 3] = (np.eye(3) - rot) @ np.cross(w, v) + np.outer(angle, w * (w @ v))
    return g


def _parallelogram(column: _Column, angle: Array) -> Array:
    """The coupler's circular translation ``R(a, φ) w − w`` (rod length 1, the scaled unit)."""
    g = np.tile(np.eye(4), (len(angle), 1, 1))
    assert column.hinge is not None and column.rod is not None
    g[:, :3, 3] = _rotation(column.hinge, angle) @ column.rod - column.rod
    return g


def _adjoint(g: Array, rows: Array) -> Array:
    """``Ad(g)`` applied to screws ``(B, 6)``: ``(R s; R s0 + p × R s)``."""
    s = np.einsum("bij,bj->bi", g[:, :3, :3], rows[:, :3])
    s0 = np.einsum("bij,bj->bi", g[:, :3, :3], rows[:, 3:]) + np.cross(g[:, :3, 3], s)
    return np.concatenate([s, s0], axis=-1)


class _Kinematics:
    """The product-of-exponentials model of a twist graph about its scaled frame (module docstring)."""

    def __init__(self, graph: nx.MultiDiGraph, joint_key: str):
        self.point, self.length = graph_frame(graph, joint_key=joint_key)
        self.base = graph.graph["base"]
        self.columns: list[_Column] = []
        self.joints: dict[str, tuple[Any, Any, list[int]]] = {}
        for u, v, key, joint in sorted(graph.edges(keys=True, data=joint_key), key=lambda e: str(e[2])):
            indices = []
            for k, row in enumerate(np.asarray(joint.screws, dtype=float)):
                hinge = rod = None
                if joint.type == "Pa" and {"hinge_axis", "rod_direction"} <= set(joint.geometry):
                    hinge = _unit(np.asarray(joint.geometry["hinge_axis"], dtype=float))
                    rod = np.asarray(joint.geometry["rod_direction"], dtype=float)
                    rod = _unit(rod - hinge * (hinge @ rod))
                indices.append(len(self.columns))
                self.columns.append(_Column(key, u, v, self._scaled(row), k, hinge, rod))
            self.joints[key] = (u, v, indices)
        tree = nx.bfs_tree(nx.Graph(graph.to_undirected()), self.base)
        self.order = list(nx.topological_sort(tree))  # links, base first
        chosen: dict[Any, tuple[str, bool]] = {}  # link → (tree joint reaching it, traversed forward)
        for parent, child in tree.edges():
            key = next(k for u, v, k in graph.edges(keys=True) if {u, v} == {parent, child})
            u, _, _ = self.joints[key]
            chosen[child] = (key, u == parent)
        self.tree = chosen
        tree_joints = {key for key, _ in chosen.values()}
        self.closing = [key for key in self.joints if key not in tree_joints]

    def _scaled(self, row: Array) -> Array:
        s, s0 = row[:3], row[3:]
        moment = (s0 - np.cross(self.point, s)) / self.length
        # a couple when its direction is negligible against the moment about the reference point in
        # characteristic lengths: the test is then free of the length unit and of where the origin
        # is (against the raw row, a hinge 1e15 lengths from the origin read as a slider)
        if np.linalg.norm(s) < 1e-12 * np.linalg.norm(moment):
            return np.concatenate([np.zeros(3), s0 / np.linalg.norm(s0)])
        return np.concatenate([s, moment]) / np.linalg.norm(s)

    def _unscaled(self, rows: Array) -> Array:
        s, s0 = rows[..., :3], rows[..., 3:]
        finite = np.linalg.norm(s, axis=-1, keepdims=True) > 1e-12
        return np.concatenate([s, np.where(finite, s0 * self.length + np.cross(self.point, s), s0)], axis=-1)

    def _joint_motion(self, key: str, theta: Array) -> tuple[Array, list[Array]]:
        """The joint's displacement in the reference (spatial) frame and, per screw, the displacement
        before it (what carries that screw to the current configuration, left of the parent's)."""
        g = np.tile(np.eye(4), (theta.shape[0], 1, 1))
        before = []
        for index in self.joints[key][2]:
            column = self.columns[index]
            before.append(g)
            step = (
                _parallelogram(column, theta[:, index])
                if column.hinge is not None
                else _exp(column.row, theta[:, index])
            )
            g = g @ step
        return g, before

    def state(self, theta: Array) -> tuple[dict[Any, Array], Array]:
        """Link displacements (from the tree) and the current screws ``(B, columns, 6)``."""
        links = {self.base: np.tile(np.eye(4), (theta.shape[0], 1, 1))}
        motions = {key: self._joint_motion(key, theta) for key in self.joints}
        for link in self.order[1:]:
            key, forward = self.tree[link]
            u, v, _ = self.joints[key]
            g = motions[key][0]
            links[link] = links[u] @ g if forward else links[v] @ np.linalg.inv(g)
        current = np.empty((theta.shape[0], len(self.columns), 6))
        for key, (u, _, indices) in self.joints.items():
            for index, before in zip(indices, motions[key][1], strict=True):
                column = self.columns[index]
                carry = links[u] @ before
                if column.hinge is not None:  # the Π's twist turns with its rods
                    assert column.rod is not None
                    direction = np.cross(column.hinge, _rotation(column.hinge, theta[:, index]) @ column.rod)
                    row = np.concatenate([np.zeros_like(direction), direction], axis=-1)
                    current[:, index] = _adjoint(carry, row)
                else:
                    current[:, index] = _adjoint(carry, np.broadcast_to(column.row, (theta.shape[0], 6)))
        self._motions = motions
        return links, current

    def residual_and_jacobian(self, theta: Array) -> tuple[Array, Array, Array]:
        """Loop-closure residuals ``(B, 6 L)``, their Jacobian ``(B, 6 L, columns)``, current screws."""
        links, current = self.state(theta)
        residuals, blocks = [], []
        paths = {link: self._path(link) for link in links}
        for key in self.closing:
            u, v, indices = self.joints[key]
            closed = links[u] @ self._motions[key][0] @ np.linalg.inv(links[v])
            rot = closed[:, :3, :3]
            omega = 0.5 * np.stack(
                [rot[:, 2, 1] - rot[:, 1, 2], rot[:, 0, 2] - rot[:, 2, 0], rot[:, 1, 0] - rot[:, 0, 1]], -1
            )
            residuals.append(np.concatenate([omega, closed[:, :3, 3]], axis=-1))
            block = np.zeros((theta.shape[0], 6, len(self.columns)))
            for index, sign in [*paths[u], *((i, -s) for i, s in paths[v])]:
                block[:, :, index] += sign * current[:, index]
            for index in indices:
                block[:, :, index] += current[:, index]
            blocks.append(block)
        if not residuals:
            return np.zeros((theta.shape[0], 0)), np.zeros((theta.shape[0], 0, len(self.columns))), current
        return np.concatenate(residuals, axis=1), np.concatenate(blocks, axis=1), current

    def _path(self, link: Any) -> list[tuple[int, float]]:
        """The tree joints' columns from the base to ``link``, with the sign of traversal."""
        out: list[tuple[int, float]] = []
        while link != self.base:
            key, forward = self.tree[link]
            u, v, indices = self.joints[key]
            out += [(index, 1.0 if forward else -1.0) for index in indices]
            link = u if forward else v
        return out


def _unit(v: Array) -> Array:
    return v / np.linalg.norm(v)


def _null_space(jacobian: Array, rtol: float = 1e-9) -> Array:
    """Orthonormal null-space bases ``(columns, k)`` of one matrix."""
    if jacobian.shape[0] == 0:
        return np.eye(jacobian.shape[1])
    _, sigma, vt = np.linalg.svd(jacobian)
    rank = int(np.sum(sigma > rtol * max(sigma[0], 1.0)))
    return vt[rank:].T


def _damped_linear(jacobian: Array, residual: Array) -> Array:
    """``(J Jᵀ + λ I)⁻¹ r`` per configuration: ``Jᵀ`` of it is the minimum-norm Gauss–Newton step
    (Levenberg's damping ``λ`` tiny, so that the dependent loop equations of an overconstrained
    mechanism, whose rows repeat, leave the system solvable)."""
    gram = jacobian @ np.swapaxes(jacobian, -1, -2)
    damping = 1e-12 * (np.trace(gram, axis1=-2, axis2=-1)[:, None, None] + 1.0)
    return np.linalg.solve(gram + damping * np.eye(gram.shape[-1]), residual[..., None])[..., 0]


def _damped_solve(jacobian: Array, vectors: Array) -> Array:
    """The multipliers projecting ``vectors`` onto the null space of ``J``: ``(J Jᵀ + λ I)⁻¹ J z``."""
    return _damped_linear(jacobian, np.einsum("bij,bj->bi", jacobian, vectors))


def generic_configurations(
    graph: nx.MultiDiGraph, rng: np.random.Generator, count: int, *, joint_key: str = "joint"
) -> JointTable:
    """``count`` random configurations of the graph's mechanism, reached by moving it (module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph at one (any, even singular) configuration.
    rng : numpy.random.Generator
    count : int
        Configurations wanted; those whose loops Newton's method could not close are dropped.
    joint_key : str

    Returns
    -------
    JointTable
        Batch shape ``(k,)`` with ``k <= count``, the graph's joints (same names, types, actuation).

    Raises
    ------
    ScrewkitValueError
        If the mechanism cannot move (its loops admit no joint motion), or no loop could be closed.

    Examples
    --------
    >>> graph = load_mechanism("planar_3rrp").twist_graph()
    >>> table = generic_configurations(graph, np.random.default_rng(0), 3)
    >>> table.batch_shape, bool(np.allclose(table.screws[0], table.screws[1]))
    ((3,), False)
    """
    model = _Kinematics(graph, joint_key)
    n = len(model.columns)
    theta = np.zeros((count, n))
    _, jacobian, _ = model.residual_and_jacobian(theta[:1])
    null = _null_space(jacobian[0])
    if null.shape[1] == 0:
        raise ScrewkitValueError(
            "Expected a mechanism that can move (to reach generic configurations), got one whose loops "
            "admit no joint motion."
        )
    ok = np.ones(count, dtype=bool)
    for _ in range(STEPS):
        _, jacobian, _ = model.residual_and_jacobian(theta)
        direction = rng.standard_normal((count, n))
        direction = direction - np.einsum("bji,bj->bi", jacobian, _damped_solve(jacobian, direction))
        theta = theta + STEP * direction / np.max(np.abs(direction), axis=1, keepdims=True)
        for _ in range(NEWTON_ITERATIONS):
            residual, jacobian, _ = model.residual_and_jacobian(theta)
            if residual.shape[1] == 0 or np.max(np.abs(residual)) < CLOSURE_TOL:
                break
            theta = theta - np.einsum("bji,bj->bi", jacobian, _damped_linear(jacobian, residual))
        residual, _, _ = model.residual_and_jacobian(theta)
        ok &= (np.max(np.abs(residual), axis=1) if residual.shape[1] else np.zeros(count)) < 1e-9
    if not np.any(ok):
        raise ScrewkitValueError("Expected loops that close again after a small motion, got none in "
                                 f"{count} tries (Newton's method did not converge).")
    _, _, current = model.residual_and_jacobian(theta[ok])
    rows = model._unscaled(current)
    specs = JointTable.from_graph(graph, joint_key=joint_key)
    order = {spec.name: spec for spec in specs.specs}
    table_rows = [
        (u, v, key, order[key].type, rows[:, indices], order[key].actuated)
        for key, (u, v, indices) in model.joints.items()
    ]
    anchor = None
    if specs.anchor is not None:  # it moves with the platform
        links, _ = model.state(theta[ok])
        g = links[graph.graph["platform"]]
        local = (np.asarray(specs.anchor) - model.point) / model.length
        anchor = (np.einsum("bij,j->bi", g[:, :3, :3], local) + g[:, :3, 3]) * model.length + model.point
    return JointTable.from_rows(specs.base, specs.platform, table_rows, dof=specs.dof, anchor=anchor)
