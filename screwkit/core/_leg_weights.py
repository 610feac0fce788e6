"""Legs weighed by how independent their inner branches are: the constraint closeness near a leg's
own loss of order (private).

A leg with parallel branches on its series spine (:func:`spanned_spines`:
the Veloce's and the H4's sub-platforms, each held by two limbs) has the wrench system the sum of
its branches' (paper 002 Eq. 2), cut down by the joints in series after it (Eq. 1). Its frame is
orthonormal, so it keeps unit rows up to the very pose where the branches' systems become
dependent and the leg loses order: the constraint closeness, ``σ_c0 / σ_1`` of the legs' frames
stacked, then reads 1 beside a constraint singularity. :func:`weighted_legs` gives each direction of
such a leg's system a weight in ``(0, 1]``: 1 while the branches' span keeps every singular value
above :data:`TAPER` of its largest, else falling linearly with the smallest one the direction needs.
Far from any such loss the weighted frame spans the same system with orthonormal rows, so the
closeness is unchanged there; near it the closeness falls continuously to 0 where the loss drops the
mechanism's constraint order (and not where other legs still hold what the leg lost).

Examples
--------
>>> rows = np.zeros((1, 6, 6)); rows[0, 0, 3] = 1.0                # a leg holding one couple about x
>>> slides = np.zeros((2, 6, 6)); slides[:, :2, 3:5] = np.eye(2)  # its two branches: couples x, y
>>> weighted = weighted_rows(rows, [(slides, np.array(2))])
>>> bool(np.allclose(weighted, rows))                              # independent branches: unchanged
True
"""

from __future__ import annotations

import functools
from collections.abc import Sequence

import numpy as np

from ..graphs.topology import Topology
from ._program import Evaluation, ProgramBuilder

__all__ = ["TAPER", "spanned_spines", "weighted_legs", "weighted_rows"]

Array = np.ndarray

#: Below this fraction of its largest singular value, a singular value of a leg's branches' span
#: weighs the directions that need it (linearly: 0 where the span loses that direction).
TAPER = 0.1


def _span_weights(branches: Array, order: Array) -> tuple[Array, Array]:
    """The span of stacked branch rows ``(..., q, 6)``: its right singular vectors ``(..., 6, 6)``
    and their weights ``min(1, σ_i / (TAPER σ_1))`` ``(..., 6)``, 0 beyond ``order``."""
    _, values, vectors = np.linalg.svd(branches, full_matrices=False)
    largest = values[..., :1]
    weights = np.clip(np.divide(values, TAPER * largest, out=np.zeros_like(values), where=largest > 0), 0, 1)
    weights = np.where(np.arange(values.shape[-1]) < np.asarray(order)[..., None], weights, 0.0)
    return vectors, weights


def weighted_rows(rows: Array, spans: Sequence[tuple[Array, Array]]) -> Array:
    """A leg's orthonormal wrench rows ``(..., 6, 6)`` (zero rows beyond its order) weighed by the
    spans its system lies in (``spans``: each the stacked branch rows ``(..., q, 6)`` and the span's
    order ``(...)``).

    A leg direction ``p`` has coordinates ``x_j = p V_jᵀ / w_j`` in span ``j``'s weighted basis
    (singular vectors ``V_j``, weights ``w_j``); with ``C = [C_1 … C_J] / √J`` stacking those
    coordinates for the leg's rows ``Q``, the weighted rows are ``(C Cᵀ)^(−1/2) Q``: the same system,
    each direction shrunk by the norm of the coordinates it needs (exactly ``Q`` when every weight is
    1, for then ``C Cᵀ = I``).

    The leg's rows must lie in each span's first ``order`` directions (a series chain's wrench
    system lies in each of its members': :func:`spanned_spines`); the weights of the directions beyond
    it are 0 and what a row has along them is left out.

    Parameters
    ----------
    rows : numpy.ndarray, shape (..., 6, 6)
    spans : sequence of (numpy.ndarray, numpy.ndarray)

    Returns
    -------
    numpy.ndarray, shape (..., 6, 6)

    Examples
    --------
    Two couples' span about to lose a direction (at angle 0.01) weighs the leg's couple that needs it:

    >>> rows = np.zeros((6, 6)); rows[0, 4] = 1.0                   # the leg: a couple about y
    >>> branches = np.zeros((2, 6)); branches[0, 3] = 1.0             # couples about x and
    >>> branches[1, 3:5] = np.cos(0.01), np.sin(0.01)                  # nearly about x
    >>> float(np.linalg.norm(weighted_rows(rows, [(branches, np.array(2))])[0])) < 0.1
    True
    """
    coordinates = []
    for branches, order in spans:
        vectors, weights = _span_weights(branches, order)
        inverse = np.divide(1.0, weights, out=np.zeros_like(weights), where=weights > 0)
        coordinates.append(np.einsum("...ij,...kj->...ik", rows, vectors) * inverse[..., None, :])
    stacked = np.concatenate(coordinates, axis=-1) / np.sqrt(len(coordinates))
    gram = np.einsum("...ik,...jk->...ij", stacked, stacked)
    values, vectors = np.linalg.eigh(gram)
    scale = np.divide(1.0, np.sqrt(np.maximum(values, 0.0)), out=np.zeros_like(values), where=values > 1e-300)
    root = np.einsum("...ik,...k,...jk->...ij", vectors, scale, vectors)
    return np.einsum("...ij,...jk->...ik", root, rows)


Spines = Sequence[tuple[int, Sequence[tuple[int, Sequence[int]]]]]


def weighted_legs(core: Evaluation, legs: Array, spines: Spines) -> Array:
    """The legs' stacked frames ``(..., L, 6, 6)`` with the legs of ``spines``
    (:func:`spanned_spines`) weighed (:func:`weighted_rows`).

    Parameters
    ----------
    core : Evaluation
        The batch's frames (the spans' branches and orders are read from it).
    legs : numpy.ndarray, shape (..., L, 6, 6)
    spines : sequence

    Returns
    -------
    numpy.ndarray, shape (..., L, 6, 6)
        A new array.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointSpec
    >>> from screwkit.graphs.topology import topology
    >>> top = topology("B", "E", (JointSpec("R1", "R", "B", "E", 1, True),))
    >>> legs = np.eye(6)[None, None]
    >>> bool((weighted_legs(Evaluation(top, np.zeros((1, 1, 6)), 1e-9), legs, ()) == legs).all())
    True
    """
    out = np.array(legs, dtype=float)
    for position, nodes in spines:
        spans = [
            (
                np.concatenate([core.frame(("wrenches", c))[0] for c in children], axis=-2),
                core.frame(("wrenches", node))[1],
            )
            for node, children in nodes
        ]
        out[..., position, :, :] = weighted_rows(out[..., position, :, :], spans)
    return out


@functools.lru_cache(maxsize=256)
def spanned_spines(top: Topology) -> tuple[tuple[int, tuple[tuple[int, tuple[int, ...]], ...]], ...]:
    """Per leg, the parallel nodes on its series spine whose wrench frame is the span of their
    branches' (paper 002 Eq. 2; parallelograms, which have a closed form, left out):
    ``((leg position, ((node, branches), ...)), ...)`` for the legs that have any.

    A series chain's wrench system is the intersection of its members' (Eq. 1), so the leg's lies
    in each such node's (what :func:`weighted_rows` needs).

    Parameters
    ----------
    top : Topology
        A series-parallel tree (none for a network).

    Returns
    -------
    tuple

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointSpec
    >>> from screwkit.graphs.topology import topology
    >>> spanned_spines(topology("B", "E", (JointSpec("R1", "R", "B", "E", 1, True),)))
    ()
    """
    if top.network or top.root is None:
        return ()
    builder = ProgramBuilder(top)
    found = []
    for position, leg in enumerate(top.legs):
        nodes: list[tuple[int, tuple[int, ...]]] = []
        stack = [leg] if leg != top.root else []
        while stack:
            index = stack.pop()
            node = top.nodes[index]
            if node.kind == "series":
                stack.extend(c for c in node.children if top.nodes[c].kind != "joint")
            elif node.kind == "parallel" and not (
                len(node.children) == 2 and all(builder._is_rod(top.nodes[c]) for c in node.children)
            ):
                nodes.append((index, tuple(node.children)))
        if nodes:
            found.append((position, tuple(sorted(nodes))))
    return tuple(found)
