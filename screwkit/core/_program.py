"""Frame programs: a topology's wrench and twist systems as a flat list of ops, run over a batch (private).

The series-parallel recursion of paper 002 (Eqs. 1–3: a chain's twist system is the sum of its
members'; parallel branches' constraint systems add up; each system is the reciprocal of the other)
is recorded once per topology and set of requested frames (:func:`frame_program`) as ops on slots:
spans, reciprocals and closed forms (:mod:`screwkit.core._closed_forms`). :func:`run_program` runs
a program over a batch of scaled joint screws: one compiled call on the numba path
(:func:`screwkit.core._program_numba.run_program`), op by op with the batched kernels of
:mod:`screwkit.core.frames` on the numpy path (the same operations: bit for bit).
:class:`Evaluation` caches the frames of one batch, and runs the loop closure of a graph that does
not reduce (:meth:`Evaluation.network`).

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> from screwkit.graphs.topology import topology
>>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[[0, 0, 1.0, 0, 0, 0]]], True)])
>>> top = topology(table.base, table.platform, table.specs)
>>> rows, orders = run_program(frame_program(top, (("wrenches", top.root),)), table.screws, 1e-9,
...                            (("wrenches", top.root),))
>>> orders
array([[5]])
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..graphs.topology import Node, Topology, network_layout
from . import _closed_forms as CF
from . import frames as F
from ._kernel_constants import (
    COMPANION,
    CONTRACT,
    EXTEND,
    JOINT_ROWS,
    PARALLELOGRAM,
    RECIPROCAL,
    ROD,
    SLOT_ROWS,
    SPAN,
)

__all__ = [
    "Evaluation",
    "Frame",
    "Program",
    "ProgramBuilder",
    "Request",
    "frame_program",
    "run_program",
    "stacked",
]

Array = np.ndarray
Frame = tuple[Array, Array]


#: What a frame program computes: ``("twists", node)``, ``("wrenches", node)`` of a tree node,
#: ``("sum", nodes)``, the sum of the twist systems of tree nodes (a limb with its actuator locked),
#: or ``("passive", nodes)``, the reciprocal of that sum (the limb's passive wrenches).
Request = tuple[str, Any]


@dataclass(frozen=True, eq=False)
class Program:
    """A topology's frames as a flat list of operations, built once per topology and requests
    (:func:`frame_program`) and run over a batch by :func:`run_program` (one compiled call on the numba path,
    op by op with the batched kernels of :mod:`screwkit.core.frames` on the numpy path).

    Each op writes a new slot (its index): ``(code, slot, first, count)`` with ``code`` a span of
    ``sources[first : first + count]`` (rows ``(kind, a, b)``: joint screw rows ``a .. a + b`` or
    the first ``b`` rows of slot ``a``) or the reciprocal of slot ``first``
    (:func:`screwkit.core._program_numba.run_program`), or the reciprocal of the span of two spherical
    joints' rows in closed form (:func:`screwkit.core._closed_forms.rod`: the line through their centres,
    paper 002 §4.1's rod force; the issue's "closed-form reciprocal systems")."""

    ops: Array
    sources: Array
    slots: dict[Request, int]
    last_use: tuple[int, ...]


class ProgramBuilder:
    """Records the series-parallel recursion (paper 002 Eqs. 1–3: a chain's twist system is the
    sum of its members'; parallel branches' constraint systems add up, and each system is the
    reciprocal of the other) as ops, each frame computed once."""

    def __init__(self, top: Topology):
        self.top = top
        self.ops: list[tuple[int, int, int, int]] = []
        self.sources: list[tuple[int, int, int]] = []
        self.slots: dict[Request, int] = {}
        self._bounds: dict[int, int] = {}

    def _op(self, code: int, first: int, count: int) -> int:
        self.ops.append((code, len(self.ops), first, count))
        return len(self.ops) - 1

    def _span(self, parts: list[tuple[int, int, int]]) -> int:
        first = len(self.sources)
        self.sources.extend(parts)
        return self._op(SPAN, first, len(parts))

    def bound(self, index: int) -> int:
        """A static upper bound on a node's twist order (zero rows beyond it are dropped).

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        int
        """
        if index not in self._bounds:
            node = self.top.nodes[index]
            if node.kind == "joint":
                assert node.joint is not None
                value = self.top.specs[node.joint].dof
            elif node.kind == "series":
                value = sum(self.bound(c) for c in node.children)
            else:
                value = min(self.bound(c) for c in node.children)
            self._bounds[index] = min(value, 6)
        return self._bounds[index]

    def generators(self, index: int) -> list[tuple[int, int, int]]:
        """What a node adds to a sum of twist systems: a joint's screws, else its frame's rows.

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        list of tuple of int
            Sources ``(kind, a, b)``.
        """
        node = self.top.nodes[index]
        if node.kind == "joint":
            assert node.joint is not None
            return [(JOINT_ROWS, self.top.columns[node.joint], self.top.specs[node.joint].dof)]
        return [(SLOT_ROWS, self.twists(index), self.bound(index))]

    def _chain_sum(self, members: tuple[int, ...]) -> int:
        """The twists of members in series: their span, or :data:`EXTEND` (the closed form) for one
        1-dof joint and one other node."""
        if self._joint_and_node(members):
            return self._sourced(EXTEND, [g for c in members for g in self.generators(c)])
        return self._span([g for c in members for g in self.generators(c)])

    def _contract(self, members: tuple[int, ...]) -> int:
        """The wrenches of one 1-dof joint and one other node in series (reciprocal to their twists'
        sum): :data:`CONTRACT`, the node's wrenches less those not reciprocal to the joint's screw.
        Where the node's twists are not the reciprocal of its wrenches (a series node, a
        parallelogram), their slot is a third source: the fallback then spans the rows an
        :data:`EXTEND` of the same members spans, so the twists and wrenches of a chain are decided
        alike even within the threshold band."""
        parts = [
            self.generators(c)[0] if self.top.nodes[c].kind == "joint" else (SLOT_ROWS, self.wrenches(c), 6)
            for c in members
        ]
        (node,) = [c for c in members if self.top.nodes[c].kind != "joint"]
        if ("twists", node) in self.slots or self.top.nodes[node].kind != "parallel":  # else a reciprocal
            twists = self.twists(node)
            if self.ops[twists][0] != RECIPROCAL:
                parts.append((SLOT_ROWS, twists, self.bound(node)))
        return self._sourced(CONTRACT, parts)

    def _joint_and_node(self, members: tuple[int, ...]) -> bool:
        """Exactly two members: a joint of one screw and a node that is not a joint."""
        nodes = [self.top.nodes[c] for c in members]
        joints = [n for n in nodes if n.kind == "joint"]
        return (
            len(nodes) == 2
            and len(joints) == 1
            and joints[0].joint is not None
            and self.top.specs[joints[0].joint].dof == 1
        )

    def _sourced(self, code: int, parts: list[tuple[int, int, int]]) -> int:
        first = len(self.sources)
        self.sources.extend(parts)
        return self._op(code, first, len(parts))

    def twists(self, index: int) -> int:
        """The slot of a tree node's twist frame (recorded on first use).

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        int
        """
        key = ("twists", index)
        if key not in self.slots:
            node = self.top.nodes[index]
            if node.kind == "parallel":
                wrenches = self.wrenches(index)  # a parallelogram's twists come with its wrenches
                if key not in self.slots:
                    self.slots[key] = self._op(RECIPROCAL, wrenches, 0)
            elif node.kind == "joint":
                self.slots[key] = self._span(self.generators(index))
            elif (leg := self._limb_leg(index)) is not None:  # the limb's locked twists and its screw
                parts = [self.generators(leg[0])[0], (SLOT_ROWS, self.request(("sum", leg[1])), 6)]
                self.slots[key] = self._sourced(EXTEND, parts)
            else:
                self.slots[key] = self._chain_sum(node.children)
        return self.slots[key]

    def wrenches(self, index: int) -> int:
        """The slot of a tree node's wrench frame (recorded on first use).

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        int
        """
        key = ("wrenches", index)
        if key not in self.slots:
            node = self.top.nodes[index]
            if node.kind == "parallel" and len(node.children) == 2 and all(
                self._is_rod(self.top.nodes[c]) for c in node.children
            ):  # two rods: a parallelogram's wrenches and twists in closed form where it is one
                rods = [(SLOT_ROWS, self.wrenches(c), 6) for c in node.children]
                self.slots[key] = self._sourced(PARALLELOGRAM, rods)
                self.slots[("twists", index)] = self._op(COMPANION, self.slots[key], 0)
            elif node.kind == "parallel":
                self.slots[key] = self._span([(SLOT_ROWS, self.wrenches(c), 6) for c in node.children])
            elif self._is_rod(node):  # closed form: the line through the two centres
                self.slots[key] = self._sourced(ROD, [g for c in node.children for g in self.generators(c)])
            elif node.kind == "series" and self._joint_and_node(node.children):
                self.slots[key] = self._contract(node.children)
            elif (leg := self._limb_leg(index)) is not None:  # the limb's passive wrenches, less one
                passive, locked = self.request(("passive", leg[1])), self.request(("sum", leg[1]))
                parts = [self.generators(leg[0])[0], (SLOT_ROWS, passive, 6), (SLOT_ROWS, locked, 6)]
                self.slots[key] = self._sourced(CONTRACT, parts)  # (the fallback spans the sum, as EXTEND)
            else:
                self.slots[key] = self._op(RECIPROCAL, self.twists(index), 0)
        return self.slots[key]

    def _limb_leg(self, index: int) -> tuple[int, tuple[int, ...]] | None:
        """``(actuated joint's node, siblings)`` of a limb whose leg this series node of six or more
        freedoms is, made of that 1-dof joint and the siblings (a UPS leg), else None: its twists are
        then the EXTEND of the limb's locked twists, its wrenches the CONTRACT of the limb's passive
        wrenches (paper 002 Eq. 1 with Eq. 3), frames the limb needs anyway (no span of all its screws)."""
        node = self.top.nodes[index]
        if node.kind == "series" and len(node.children) >= 3 and sum(map(self.bound, node.children)) >= 6:
            for plan in self.top.limbs:
                rest = [c for c in node.children if c not in plan.siblings]
                if len(rest) == 1 == len(node.children) - len(plan.siblings) and plan.index == (
                    self.top.nodes[rest[0]].joint
                ) and self.top.specs[plan.index].dof == 1:
                    return rest[0], plan.siblings
        return None

    def _is_rod(self, node: Node) -> bool:
        """A chain of exactly two spherical joints (a rod with a ball at each end)."""
        kinds = [self.top.nodes[c] for c in node.children]
        return node.kind == "series" and len(kinds) == 2 and all(
            child.kind == "joint"
            and child.joint is not None
            and self.top.specs[child.joint].type == "S"
            and self.top.specs[child.joint].dof == 3
            for child in kinds
        )

    def request(self, request: Request) -> int:
        """The slot computing a request (:data:`Request`), recorded on first use.

        Parameters
        ----------
        request : Request

        Returns
        -------
        int
        """
        kind, what = request
        if kind == "passive":  # the reciprocal of a sum: a limb's passive wrenches
            if request not in self.slots:
                if self._joint_and_node(what):
                    self.slots[request] = self._contract(what)
                else:
                    self.slots[request] = self._op(RECIPROCAL, self.request(("sum", what)), 0)
            return self.slots[request]
        if kind == "sum":
            if request not in self.slots:
                self.slots[request] = self._chain_sum(what)
            return self.slots[request]
        return self.twists(what) if kind == "twists" else self.wrenches(what)


@functools.lru_cache(maxsize=256)
def frame_program(top: Topology, requests: tuple[Request, ...]) -> Program:
    """The ops computing ``requests`` (cached per topology object and requests).

    Parameters
    ----------
    top : Topology
    requests : tuple of Request

    Returns
    -------
    Program
    """
    builder = ProgramBuilder(top)
    for request in requests:
        builder.request(request)
    last_use = list(range(len(builder.ops)))
    for index, (code, _, first, count) in enumerate(builder.ops):
        sources = builder.sources[first : first + count]
        read = [first] if code == RECIPROCAL else [a for kind, a, _ in sources if kind == SLOT_ROWS]
        for slot in read:
            last_use[slot] = index
    return Program(
        np.array(builder.ops, dtype=np.int64).reshape(-1, 4),
        np.array(builder.sources, dtype=np.int64).reshape(-1, 3),
        {request: builder.slots[request] for request in requests},
        tuple(last_use),
    )


def run_program(program: Program, scaled: Array, rtol: float, requests: tuple[Request, ...]) -> Frame:
    """The requested frames of a program over the batch of ``scaled`` ``(..., rows, 6)``, on an
    axis of their own: rows ``(..., len(requests), 6, 6)``, orders ``(..., len(requests))``.

    Parameters
    ----------
    program : Program
    scaled : numpy.ndarray, shape (..., rows, 6)
        The unit scaled joint screws.
    rtol : float
        The rule's relative threshold.
    requests : tuple of Request
        Those of the program, in the order wanted.

    Returns
    -------
    rows : numpy.ndarray, shape (..., len(requests), 6, 6)
    orders : numpy.ndarray of int, shape (..., len(requests))
    """
    batch = scaled.shape[:-2]
    wanted = [program.slots[r] for r in requests]
    kernels = F.compiled_twin("_program_numba", math.prod(batch))
    if kernels is not None:
        if 0 in batch:
            return F.empty((*batch, len(requests)))
        flat = np.ascontiguousarray(scaled.reshape(-1, *scaled.shape[-2:]), dtype=float)
        rows, orders = kernels.run_program(
            flat, float(rtol), program.ops, program.sources, len(program.ops), np.array(wanted, np.int64)
        )
        return rows.reshape(*batch, len(wanted), 6, 6), orders.reshape(*batch, len(wanted))
    frames: dict[int, Frame] = {}
    keep = set(wanted)
    for index, (code, slot, first, count) in enumerate(program.ops.tolist()):
        sources = program.sources[first : first + count].tolist()
        if code == RECIPROCAL:
            frames[slot] = F.reciprocal(*frames[first])
        elif code == PARALLELOGRAM:
            frames[slot], frames[slot + 1] = _parallelogram([frames[a] for _, a, _ in sources], rtol)
        elif code == COMPANION:
            pass  # written by the op before it
        elif code in (EXTEND, CONTRACT):
            frames[slot] = _closed_form(code, sources, frames, scaled, rtol)
        else:
            parts = [
                scaled[..., a : a + b, :] if kind == JOINT_ROWS else frames[a][0][..., :b, :]
                for kind, a, b in sources
            ]
            if code == ROD:
                frames[slot] = CF.rod(np.concatenate(parts, axis=-2), rtol)
            else:
                frames[slot] = F.span(np.concatenate(parts, axis=-2), rtol) if parts else F.empty(batch)
        for done in [s for s in frames if program.last_use[s] <= index and s not in keep]:
            del frames[done]  # bounded memory over large batches
    return stacked([frames[s] for s in wanted])


def _parallelogram(rods: list[Frame], rtol: float) -> tuple[Frame, Frame]:
    """:data:`PARALLELOGRAM` over the batch (numpy path): the closed form
    (:func:`screwkit.core._closed_forms.parallelogram`), the span of the two rods' frames and its reciprocal
    where it does not apply; :func:`screwkit.core._program_numba.run_program`'s steps."""
    first, second = rods
    wrenches, wrench_order, twists, twist_order, decided = CF.parallelogram(first, second, rtol)
    if not decided.all():
        undecided = ~decided
        spanned = F.span(np.concatenate([rows[undecided] for rows, _ in rods], axis=-2), rtol)
        wrenches[undecided], wrench_order[undecided] = spanned
        twists[undecided], twist_order[undecided] = F.reciprocal(*spanned)
    return (wrenches, wrench_order), (twists, twist_order)


def _closed_form(
    code: int, sources: list[list[int]], frames: dict[int, Frame], scaled: Array, rtol: float
) -> Frame:
    """:data:`EXTEND` or :data:`CONTRACT` over the batch (numpy path): the closed form
    (:func:`screwkit.core._closed_forms.extend`, :func:`~screwkit.core._closed_forms.contract`), the
    rule's span (and reciprocals) where it does not decide; the steps of
    :func:`screwkit.core._program_numba.run_program`."""
    (joint,) = [a for kind, a, _ in sources[:2] if kind == JOINT_ROWS]
    (slot,) = [a for kind, a, _ in sources[:2] if kind == SLOT_ROWS]
    rows, order = frames[slot]
    closed = CF.extend if code == EXTEND else CF.contract
    out, out_order, decided = closed(rows, order, scaled[..., joint, :], rtol)
    if not decided.all():
        undecided = ~decided
        if code == CONTRACT and len(sources) == 3:  # the node's twist frame
            twists, bound = frames[sources[2][1]][0][undecided], sources[2][2]
        elif code == CONTRACT:  # the wrench frame's reciprocal
            twists, bound = F.reciprocal(rows[undecided], order[undecided])[0], 6
        else:
            twists, bound = rows[undecided], 6
        parts = [
            scaled[undecided][:, a : a + b] if kind == JOINT_ROWS else twists[:, : min(b, bound)]
            for kind, a, b in sources[:2]
        ]
        spanned = F.span(np.concatenate(parts, axis=-2), rtol)
        out[undecided], out_order[undecided] = F.reciprocal(*spanned) if code == CONTRACT else spanned
    return out, out_order


class Evaluation:
    """Cached frames of a topology over one batch of scaled, unit joint screws: the ``requests``
    given at creation run as one program (:func:`frame_program`); any other frame asked for later
    runs a program of its own."""

    def __init__(self, top: Topology, scaled: Array, rtol: float, requests: tuple[Request, ...] = ()):
        self.top, self.scaled, self.rtol = top, scaled, rtol
        self.batch = scaled.shape[:-2]
        self.columns = top.columns
        self._blocks: list[tuple[dict[Request, int], Frame]] = []
        if requests:
            self._compute(requests)

    def _compute(self, requests: tuple[Request, ...]) -> None:
        block = run_program(frame_program(self.top, requests), self.scaled, self.rtol, requests)
        self._blocks.append(({r: i for i, r in enumerate(requests)}, block))

    def _find(self, request: Request) -> tuple[int, Frame]:
        for positions, block in self._blocks:
            if request in positions:
                return positions[request], block
        self._compute((request,))
        return 0, self._blocks[-1][1]

    def frame(self, request: Request) -> Frame:
        """One requested frame over the batch (computed with the first requests, else on its own).

        Parameters
        ----------
        request : Request

        Returns
        -------
        tuple of numpy.ndarray
            ``(rows (..., 6, 6), order (...))``.
        """
        index, (rows, orders) = self._find(request)
        return rows[..., index, :, :], orders[..., index]

    def stacked(self, requests: list[Request]) -> Frame:
        """Frames on an axis of their own, ``(..., len(requests), 6, 6)``: a view when they were
        computed together, in this order.

        Parameters
        ----------
        requests : list of Request

        Returns
        -------
        tuple of numpy.ndarray
            ``(rows (..., len(requests), 6, 6), orders (..., len(requests)))``.
        """
        found = [self._find(r) for r in requests]
        first, block = found[0]
        if all(b is block and i == first + k for k, (i, b) in enumerate(found)):
            kept = slice(first, first + len(requests))
            return block[0][..., kept, :, :], block[1][..., kept]
        return stacked([(rows[..., i, :, :], orders[..., i]) for i, (rows, orders) in found])

    def joint_rows(self, index: int) -> Array:
        """A joint's scaled screw rows over the batch.

        Parameters
        ----------
        index : int
            The joint (its index in the topology's specs).

        Returns
        -------
        numpy.ndarray, shape (..., dof, 6)
        """
        start = self.columns[index]
        return self.scaled[..., start : start + self.top.specs[index].dof, :]

    def twists(self, index: int) -> Frame:
        """A tree node's twist frame over the batch.

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        tuple of numpy.ndarray
            ``(rows (..., 6, 6), order (...))``.
        """
        return self.frame(("twists", index))

    def wrenches(self, index: int) -> Frame:
        """A tree node's wrench frame over the batch.

        Parameters
        ----------
        index : int
            A tree node.

        Returns
        -------
        tuple of numpy.ndarray
            ``(rows (..., 6, 6), order (...))``.
        """
        return self.frame(("wrenches", index))

    def network(self, joints: tuple[int, ...], locked: int | None = None) -> Frame:
        """The platform's twist system of a sub-network by loop closure: ``rank[M; P] − rank M``
        decides the null space of the loop-closure matrix ``M``; ``P`` maps it to the platform.

        Parameters
        ----------
        joints : tuple of int
            The sub-network's joints.
        locked : int, optional
            A joint left out (an actuator locked).

        Returns
        -------
        tuple of numpy.ndarray
            The platform's twist frame ``(rows (..., 6, 6), order (...))``.
        """
        kept = tuple(j for j in joints if j != locked)
        loops, path = network_layout(self.top.base, self.top.platform, self.top.specs, kept)
        columns = [(j, r) for j in kept for r in range(self.top.specs[j].dof)]
        index = {c: k for k, c in enumerate(columns)}
        closure = np.zeros((*self.batch, 6 * len(loops), len(columns)))
        for row, loop in enumerate(loops):
            for joint, sign in loop:
                for r in range(self.top.specs[joint].dof):
                    closure[..., 6 * row : 6 * row + 6, index[(joint, r)]] += (
                        sign * self.joint_rows(joint)[..., r, :]
                    )
        platform = np.zeros((*self.batch, 6, len(columns)))
        for joint, sign in path:
            for r in range(self.top.specs[joint].dof):
                platform[..., :, index[(joint, r)]] += sign * self.joint_rows(joint)[..., r, :]
        if not columns or not path:
            return F.empty(self.batch)
        if closure.shape[-2]:
            _, values, vt = np.linalg.svd(closure)
            top_value = values[..., :1]
            rank = ((values > self.rtol * top_value) & (top_value > 0)).sum(axis=-1)
            keep = np.arange(len(columns)) >= rank[..., None]  # rows of vt spanning the null space
            rates = vt * keep[..., :, None]
        else:
            rates = np.broadcast_to(np.eye(len(columns)), (*self.batch, len(columns), len(columns)))
        twists = np.swapaxes(platform @ np.swapaxes(rates, -1, -2), -1, -2)  # (..., columns, 6)
        return F.span(twists, self.rtol)


def stacked(frames: list[Frame]) -> Frame:
    """Frames of the limbs on an axis of their own: rows ``(..., n, 6, 6)``, orders ``(..., n)``.

    Parameters
    ----------
    frames : list of tuple of numpy.ndarray

    Returns
    -------
    tuple of numpy.ndarray
    """
    return np.stack([rows for rows, _ in frames], axis=-3), np.stack([order for _, order in frames], axis=-1)

