"""Singularity labels over many poses at once, vectorized over a leading batch axis.

:func:`screwkit.singularity.classify` analyses one pose with readable screw systems. For maps,
trajectories and scans, :func:`classify_poses` takes one twist graph as a *template* (its topology,
joint names and actuated flags) and the screws of every joint over a batch of poses, and makes the
same decisions with batched singular value decompositions; no Python loop runs over poses.

Orders come from ranks of the loop-closure equations without any null space of varying size: with
``M`` the loop-closure matrix and ``P`` the map from joint rates to the platform's twist along a
spanning tree, the platform's twist system has order ``rank[M; P] − rank M``. Locking the actuated
joints (dropping their columns) gives the twists left uncontrolled. A limb is serially singular when
locking its actuated joint does not lower its own twist order. Closeness measures are those of
:mod:`screwkit.singularity`, computed from bases of the *nominal* dimension (the largest order
seen over the batch), so they are continuous through singular poses. Like the single-pose path,
every decision is made about the frame of :func:`screwkit.twistgraph.axes_frame`.

Examples
--------
>>> import numpy as np
>>> from screwkit.joints import prismatic
>>> from screwkit.twistgraph import twist_graph
>>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
>>> screws = {"P": np.tile([0, 0, 0, 1.0, 0, 0], (3, 1, 1))}
>>> classify_poses(G, screws).labels()
[(), (), ()]
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import networkx as nx
import numpy as np

from . import _backend as B
from . import screw as S
from .exceptions import ScrewkitValueError, TwistGraphError
from .twistgraph import (
    axes_frame,
    check_twist_graph,
    fundamental_loops,
    series_parallel_tree,
    simple_paths,
)

__all__ = ["LoopClosureLayout", "PoseBatchReport", "checked_screws", "classify_poses", "normalized_columns"]

Array = np.ndarray
_SWAP = np.block([[np.zeros((3, 3)), np.eye(3)], [np.eye(3), np.zeros((3, 3))]])


@dataclass(frozen=True, eq=False)
class PoseBatchReport:
    """Orders, labels and closeness measures over a batch of poses (arrays of the batch shape).

    Attributes
    ----------
    dof : int
    constraint_order, global_order : numpy.ndarray of int
    serial : numpy.ndarray of bool, shape (..., n_actuated)
        True where the limb of that actuated joint is serially singular.
    actuated_joints : tuple of str
    closeness : dict of numpy.ndarray
        ``"constraint"``, ``"actuation"``, ``"serial"`` (see :mod:`screwkit.singularity`).
    """

    dof: int
    constraint_order: Array
    global_order: Array
    serial: Array
    actuated_joints: tuple[str, ...]
    closeness: dict[str, Array]

    @property
    def constraint(self) -> Array:
        """True where the constraint system is below its nominal order."""
        return self.constraint_order < 6 - self.dof

    @property
    def actuation(self) -> Array:
        """True where the constraint system is nominal but the global system is below 6."""
        return ~self.constraint & (self.global_order < 6)

    def labels(self) -> list[tuple[str, ...]]:
        """Per pose (flattened batch), the labels of :class:`~screwkit.singularity.SingularityReport`."""
        serial = np.asarray(self.serial.reshape(-1, self.serial.shape[-1]).any(axis=1))
        flags = zip(self.constraint.ravel(), self.actuation.ravel(), serial, strict=True)
        return [
            tuple(name for name, on in zip(("constraint", "actuation", "serial"), row, strict=True) if on)
            for row in flags
        ]


class LoopClosureLayout:
    """Column layout of a (sub)graph's loop-closure system, reused over a batch of poses.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        The template twist graph.
    edges : list of (u, v, key)
        The edges of the subgraph (e.g. one limb).
    base, platform : hashable
        The subgraph's terminal links.

    Examples
    --------
    >>> from screwkit.joints import revolute
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0], actuated=True))])
    >>> layout = LoopClosureLayout(G, list(G.edges(keys=True)), "B", "E")
    >>> closure, platform = layout.matrices({"R": np.zeros((2, 1, 6))}, frozenset())
    >>> closure.shape, platform.shape
    ((2, 0, 1), (2, 6, 1))
    """

    def __init__(self, graph: nx.MultiDiGraph, edges: list[tuple[Any, Any, str]], base: Any, platform: Any):
        sub = nx.MultiDiGraph(graph.edge_subgraph(edges))
        sub.graph.update(base=base, platform=platform)
        self.columns = [
            (key, i)
            for _, _, key, joint in sorted(sub.edges(keys=True, data="joint"), key=lambda e: str(e[2]))
            for i in range(joint.dof)
        ]
        self.loops = fundamental_loops(sub)
        path = next(p for p in simple_paths(sub) if p)
        self.path = path if path else []

    def matrices(self, screws: Mapping[str, Array], locked: frozenset[str]) -> tuple[Array, Array]:
        free = [(key, i) for key, i in self.columns if key not in locked]
        index = {c: k for k, c in enumerate(free)}
        batch = next(iter(screws.values())).shape[:-2]
        closure = np.zeros((*batch, 6 * len(self.loops), len(free)))
        for row, loop in enumerate(self.loops):
            for _, _, key, direction in loop:
                sign = 1.0 if direction == "forward" else -1.0
                for i in range(screws[key].shape[-2]):
                    if (key, i) in index:
                        closure[..., 6 * row : 6 * row + 6, index[(key, i)]] += sign * screws[key][..., i, :]
        platform = np.zeros((*batch, 6, len(free)))
        for _, _, key, direction in self.path:
            sign = 1.0 if direction == "forward" else -1.0
            for i in range(screws[key].shape[-2]):
                if (key, i) in index:
                    platform[..., :, index[(key, i)]] += sign * screws[key][..., i, :]
        return closure, platform


def _rank(matrix: Array, rtol: float) -> Array:
    if matrix.shape[-1] == 0 or matrix.shape[-2] == 0:
        return np.zeros(matrix.shape[:-2], dtype=int)
    values = np.linalg.svd(matrix, compute_uv=False)
    return ((values > rtol * values[..., :1]) & (values[..., :1] > 0)).sum(axis=-1)


def normalized_columns(closure: Array, platform: Array) -> tuple[Array, Array]:
    """Scale each joint-rate column of ``[M; P]`` to unit norm (the null space of M and the span of
    the platform's twists P·ker M do not change), batched over leading axes.

    Examples
    --------
    >>> closure, platform = normalized_columns(np.zeros((1, 0, 2)), np.array([[[3.0, 0], [4.0, 2]]]))
    >>> platform
    array([[[0.6, 0. ],
            [0.8, 1. ]]])
    """
    size = np.linalg.norm(np.concatenate([closure, platform], axis=-2), axis=-2, keepdims=True)
    size = np.where(size > 0, size, 1.0)
    return closure / size, platform / size


def _twist_order(closure: Array, platform: Array, rtol: float) -> Array:
    closure, platform = normalized_columns(closure, platform)
    return _rank(np.concatenate([closure, platform], axis=-2), rtol) - _rank(closure, rtol)


def _twist_basis(closure: Array, platform: Array, order: int) -> Array:
    """An orthonormal basis (rows ``(..., order, 6)``) of the platform twists of nominal order."""
    closure, platform = normalized_columns(closure, platform)
    columns = closure.shape[-1]
    if closure.shape[-2]:
        _, values, vt = np.linalg.svd(closure)
        nullity = columns - int(((values > 1e-12 * values[..., :1]).sum(axis=-1)).max())
        rates = vt[..., columns - nullity :, :]
    else:
        rates = np.broadcast_to(np.eye(columns), (*closure.shape[:-2], columns, columns))
    twists = platform @ np.swapaxes(rates, -1, -2)  # (..., 6, nullity)
    u = np.linalg.svd(twists)[0] if twists.shape[-1] else np.zeros((*twists.shape[:-1], 6))
    return np.swapaxes(u[..., :, :order], -1, -2)


def _reciprocal_basis(rows: Array, order: int) -> Array:
    """An orthonormal basis ``(..., 6 - order, 6)`` of the screws reciprocal to ``rows`` (nominal)."""
    if rows.shape[-2] == 0:
        return np.broadcast_to(np.eye(6), (*rows.shape[:-2], 6, 6))
    vt = np.linalg.svd(rows @ _SWAP)[2]
    return vt[..., order:, :]


def _sigma_ratio(rows: Array, index: int) -> Array:
    if index <= 0:
        return np.ones(rows.shape[:-2])
    if rows.shape[-2] < index:
        return np.zeros(rows.shape[:-2])
    size = np.linalg.norm(rows, axis=-1, keepdims=True)
    values = np.linalg.svd(rows / np.where(size > 0, size, 1.0), compute_uv=False)
    return np.where(
        values[..., 0] > 0, values[..., index - 1] / np.where(values[..., 0] > 0, values[..., 0], 1), 0.0
    )


def checked_screws(
    graph: nx.MultiDiGraph, screws: Mapping[str, Any]
) -> tuple[dict[str, Array], tuple[int, ...]]:
    """Validate batched joint screws against a template graph: ``{name: (..., dof, 6)}``, batch shape.

    Examples
    --------
    >>> from screwkit.joints import prismatic
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    >>> checked_screws(G, {"P": np.zeros((3, 1, 6))})[1]
    (3,)
    """
    names = {key: joint for _, _, key, joint in graph.edges(keys=True, data="joint")}
    missing, unknown = set(names) - set(screws), set(screws) - set(names)
    if missing or unknown:
        raise ScrewkitValueError(
            f"Expected `screws` for exactly the graph's joints, got missing {sorted(missing)} and unknown "
            f"{sorted(unknown)}."
        )
    arrays = {
        key: B.as_array(value, f"screws[{key!r}]", (names[key].dof, 6), symbolic=False)
        for key, value in sorted(screws.items())
    }
    shapes = [array.shape[:-2] for array in arrays.values()]
    batch = max(set(shapes), key=shapes.count)  # the odd one out is the one named
    for key, array in arrays.items():
        if array.shape[:-2] != batch or not batch:
            raise ScrewkitValueError(
                f"Expected `screws[{key!r}]` of shape {(*batch, names[key].dof, 6)} with a batch axis, "
                f"got {array.shape}."
            )
    return arrays, batch


def classify_poses(
    graph: nx.MultiDiGraph,
    screws: Mapping[str, Any],
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
) -> PoseBatchReport:
    """Label a batch of poses of one mechanism.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (any pose): its topology, names and actuated flags.
    screws : mapping of joint name to array_like, shape (..., dof_j, 6)
        The joints' screws over the batch (e.g.
        :func:`~screwkit.families.four_limb_graph.four_limb_joints`).
    dof : int, optional
        Nominal mobility; default: the graph's ``dof``, else the number of actuated joints.
    rtol : float, default 1e-9

    Returns
    -------
    PoseBatchReport

    Raises
    ------
    ScrewkitValueError
        If the screws do not match the graph's joints or their shapes disagree.

    Examples
    --------
    >>> import numpy as np
    >>> from screwkit.joints import revolute
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0], actuated=True))])
    >>> report = classify_poses(G, {"R": np.array([[[0, 0, 1, 0, 0, 0.0]], [[0, 0, 1, 1, 0, 0.0]]])})
    >>> report.constraint_order, report.global_order
    (array([5, 5]), array([6, 6]))
    """
    check_twist_graph(graph)
    arrays, batch = checked_screws(graph, screws)
    flat = {key: value.reshape(-1, *value.shape[-2:]) for key, value in arrays.items()}
    base, platform = graph.graph["base"], graph.graph["platform"]
    actuated = tuple(
        sorted(key for _, _, key, joint in graph.edges(keys=True, data="joint") if joint.actuated)
    )
    nominal_dof = dof if dof is not None else graph.graph.get("dof", len(actuated))
    if not B.is_dof(nominal_dof):
        raise TwistGraphError(f"Expected `dof` to be an integer in 0..6, got {nominal_dof!r}.")
    # the frame: centre on the reference point, moments over the length (as singularity.py)
    stacked = np.concatenate(list(flat.values()), axis=-2)
    centre, length = axes_frame(stacked)
    scaled = {}
    for key, value in flat.items():
        moved = S.transform(value, np.eye(3), -centre[:, None, :])
        moved[..., 3:] /= length[:, None, None]
        scaled[key] = moved
    all_edges = list(graph.edges(keys=True))
    whole = LoopClosureLayout(graph, all_edges, base, platform)
    closure, plat = whole.matrices(scaled, frozenset())
    constraint_order = 6 - _twist_order(closure, plat, rtol)
    closure_locked, plat_locked = whole.matrices(scaled, frozenset(actuated))
    global_order = 6 - _twist_order(closure_locked, plat_locked, rtol)
    # compound legs' constraint wrenches (nominal dimension) for the constraint closeness
    try:
        tree = series_parallel_tree(graph)
        legs = list(tree.children) if tree.kind == "parallel" else [tree]
        leg_edges = [[e for e in all_edges if e[2] in leg.joints] for leg in legs]
    except TwistGraphError:
        leg_edges = [all_edges]
    generators = []
    for edges in leg_edges:
        structure = LoopClosureLayout(graph, edges, base, platform)
        c, p = structure.matrices(scaled, frozenset())
        order = int(_twist_order(c, p, rtol).max())
        generators.append(_reciprocal_basis(_twist_basis(c, p, order), order))
    constraint_rows = np.concatenate(generators, axis=-2)
    # limbs: serial flags and actuation wrenches
    paths = simple_paths(graph)
    serial, wrenches, transmissions = [], [], []
    for name in actuated:
        edges = sorted({e[:3] for p in paths if any(x[2] == name for x in p) for e in p}, key=str)
        if not edges:
            raise TwistGraphError(f"Actuated joint {name!r} lies on no path from the base to the platform.")
        structure = LoopClosureLayout(graph, edges, base, platform)
        c, p = structure.matrices(scaled, frozenset())
        c_locked, p_locked = structure.matrices(scaled, frozenset({name}))
        free_order, locked_order = _twist_order(c, p, rtol), _twist_order(c_locked, p_locked, rtol)
        serial.append(free_order == locked_order)
        passive_order = int(locked_order.max())
        passive = _reciprocal_basis(_twist_basis(c_locked, p_locked, passive_order), passive_order)
        twist = scaled[name][..., 0, :]
        products = passive[..., :, :3] @ twist[..., 3:, None] + passive[..., :, 3:] @ twist[..., :3, None]
        wrench = (products * passive).sum(axis=-2)  # the passive wrench least reciprocal to the twist
        size = np.linalg.norm(wrench, axis=-1, keepdims=True)
        wrench = wrench / np.where(size > 0, size, 1.0)
        wrenches.append(wrench)
        magnitudes = [
            np.where(
                np.linalg.norm(x[..., :3], axis=-1) > rtol * np.linalg.norm(x[..., 3:], axis=-1),
                np.linalg.norm(x[..., :3], axis=-1),
                np.linalg.norm(x[..., 3:], axis=-1),
            )
            for x in (wrench, twist)
        ]
        product = np.abs(
            (wrench[..., :3] * twist[..., 3:]).sum(-1) + (wrench[..., 3:] * twist[..., :3]).sum(-1)
        )
        transmissions.append(
            np.where(
                magnitudes[0] * magnitudes[1] > 0,
                product / np.where(magnitudes[0] * magnitudes[1] > 0, magnitudes[0] * magnitudes[1], 1.0),
                0.0,
            )
        )
    all_rows = (
        np.concatenate([constraint_rows, np.stack(wrenches, axis=-2)], axis=-2)
        if wrenches
        else constraint_rows
    )
    closeness = {
        "constraint": _sigma_ratio(constraint_rows, 6 - nominal_dof).reshape(batch),
        "actuation": _sigma_ratio(all_rows, 6).reshape(batch),
        "serial": (
            np.min(np.stack(transmissions, axis=-1), axis=-1) if transmissions else np.ones(len(stacked))
        ).reshape(batch),
    }
    return PoseBatchReport(
        dof=nominal_dof,
        constraint_order=constraint_order.reshape(batch),
        global_order=global_order.reshape(batch),
        serial=(np.stack(serial, axis=-1) if serial else np.zeros((len(stacked), 0), dtype=bool)).reshape(
            *batch, len(actuated)
        ),
        actuated_joints=actuated,
        closeness=closeness,
    )
