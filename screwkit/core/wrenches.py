"""Constraint and actuation wrench systems of a parallel mechanism: the one batched core.

For a mechanism's joint table over a batch of configurations (a single twist graph is a batch of
one, :func:`wrench_analysis`), with the structure analysed once (:mod:`screwkit.graphs.topology`):

* the **platform's twist system** by series-parallel reduction (paper 002 Eqs. 1–2: the sum of
  twist systems along a chain; across parallel branches their constraint systems add up, the
  dual of the intersection), or by loop closure when the graph does not reduce;
* each **limb** (an actuated joint with every base-to-platform path through it, paper 002
  §4.3): its twist system with the actuator locked (the *passive* wrenches are its reciprocal),
  with it free (the limb's constraint wrenches are its reciprocal), and its **actuation wrench**:
  the passive wrench most reciprocal-productive with the actuated twist. In the scaled metric
  (:mod:`screwkit.core._frames`) that is ``SWAP·t⊥`` with ``t⊥`` the actuated twist's component
  orthogonal to the locked twist system, defined up to the limb's constraint wrenches and made a
  line where adding one of them can (the representative drawn in diagrams). The actuator
  cannot move the platform (a *serial singularity* of the limb) when ``t⊥`` vanishes. Where
  actuators share a link (the H4's nacelle) and a limb's own wrench fails, its compound leg is
  analysed as a whole (:func:`_compound_legs`);
* each **compound leg** (a branch of the root of the series-parallel tree, such as the H4's
  ``L_I = l12 − R_I``) has its own constraint system; they add up to the mechanism's
  ``W^c`` (paper 002 Eq. 3);
* the **global wrench system** ``W^c + W^a`` (paper 002 Eq. 4): a 6-system at a regular pose.

Every decision is one rank rule (:mod:`screwkit.core._frames`), made about the reference point and
length of :func:`screwkit.algebra.reference_frame.mechanism_frame` so that it follows rigid motions and
changes of unit; results are reported in the user's frame.

Examples
--------
>>> from screwkit.graphs.joints import prismatic, revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("ground", "slider", [
...     ("ground", "slider", prismatic("P1", [1, 0, 0], actuated=True))])
>>> analysis = wrench_analysis(G, dof=1)
>>> analysis.constraint_wrenches.order, analysis.global_wrenches.order
(5, 6)
"""

from __future__ import annotations

import functools
import itertools
import math
from collections.abc import Callable
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any, NamedTuple

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra import screw as S
from ..algebra.checks import MIN_LENGTH_SCALE, checked_length_scale, checked_rtol
from ..algebra.compiled import compiled_kernels
from ..algebra.reference_frame import scaled_frame, unit_scaled
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import (
    DegenerateGeometryError,
    ScrewkitTypeError,
    ScrewkitValueError,
    TwistGraphError,
)
from ..graphs.joints import Joint
from ..graphs.jointtable import JointTable
from ..graphs.reduction import SeriesParallelNode
from ..graphs.topology import Node, Topology, network_layout, topology
from . import _frames as F

if TYPE_CHECKING:
    from .generic import GenericAnalysis

__all__ = [
    "CompoundLeg",
    "Limb",
    "WrenchAnalysis",
    "analyze_table",
    "checked_rtol",
    "normalized_reciprocal_product",
    "translated_graph",
    "wrench_analysis",
]

Array = np.ndarray
Frame = tuple[Array, Array]

#: Relative tolerance deciding that a chosen actuation wrench is a line (zero pitch).
LINE_RTOL = 1e-6

#: A limb with partners whose own actuation wrench (unit, scaled) lies this close to its compound
#: leg's constraint system has its leg analysed as a whole (:func:`_compound_legs`).
COMPOUND_RTOL = 1e-6

#: A compound leg's actuation wrench (unit, scaled) is drawn as a line only if the constraint
#: wrench that makes it one is at most this large: where none of moderate size exists (the H4's
#: ``W_1`` at ``n1·z = 0``, whose pitch no multiple of ``C_n1`` changes), the root found is
#: round-off divided by round-off, and the "line" would be the constraint couple itself.
COMPOUND_LINE_REACH = 1e3


def translated_graph(graph: nx.MultiDiGraph, offset: Any, *, joint_key: str = "joint") -> nx.MultiDiGraph:
    """A copy of a twist graph with every joint moved by a translation (screws via the adjoint).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> translated_graph(G, [-1, 0, 0]).edges["B", "E", "R"]["joint"].screws + 0.0
    array([[0., 0., 1., 0., 0., 0.]])
    """
    shift = B.as_array(offset, "offset", (3,))
    moved = nx.MultiDiGraph(**graph.graph)
    moved.add_nodes_from(graph.nodes(data=True))
    if moved.graph.get("anchor") is not None:
        moved.graph["anchor"] = (np.asarray(moved.graph["anchor"], dtype=float) + shift).tolist()
    for u, v, key, data in graph.edges(keys=True, data=True):
        joint: Joint = data[joint_key]
        screws = S.transform(joint.screws, np.eye(3), shift)
        geometry = {
            key: (np.asarray(value) + shift).tolist() if key in ("point", "center") else value
            for key, value in joint.geometry.items()
        }
        copy = Joint(joint.name, joint.type, screws, joint.actuated, joint.virtual, geometry)
        moved.add_edge(u, v, key=key, **{**data, joint_key: copy})
    return moved


def _magnitude(rows: Array, length_scale: Any, rtol: float) -> Array:
    directions = np.linalg.norm(rows[..., :3], axis=-1)
    moments = np.linalg.norm(rows[..., 3:], axis=-1) / length_scale
    return np.where(directions > rtol * moments, directions, moments)


def normalized_reciprocal_product(
    first: Any, second: Any, *, length_scale: float, rtol: float = B.DEFAULT_RTOL
) -> Any:
    """``|a ∘ b| / (N(a) N(b) L)``: a unit-free reciprocal product, invariant under rigid motions.

    ``N`` is ``|s|`` for a screw of finite pitch and ``|s0| / L`` for a couple or translation, and
    ``L`` the characteristic length. For two lines it is ``d·sin θ / L`` (their mutual moment over
    ``L``); for a line and a couple, or a force and a translation, the cosine of their angle.
    Zero exactly when the screws are reciprocal.

    Examples
    --------
    >>> force = S.line([1, 0, 0], [0, 0, 2.0])
    >>> rotation = S.line([0, 1, 0], [0, 0, 0])
    >>> float(normalized_reciprocal_product(force, rotation, length_scale=4.0))
    0.5
    """
    a = B.as_array(first, "first", (6,))
    b = B.as_array(second, "second", (6,))
    for name, rows in (("first", a), ("second", b)):
        if np.any(np.all(rows == 0, axis=-1)):
            raise DegenerateGeometryError(f"Expected `{name}` to hold non-zero screws, got the zero screw.")
    product = np.abs(B.dot(a[..., :3], b[..., 3:]) + B.dot(a[..., 3:], b[..., :3]))
    return product / (_magnitude(a, length_scale, rtol) * _magnitude(b, length_scale, rtol) * length_scale)


# --------------------------------------------------------------------------------------------------
# Per-pose views (built from the batched arrays of one pose; no decision is made again)
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class Limb:
    """One actuated joint with its limb (every base-to-platform path through it), at one pose.

    Attributes
    ----------
    actuated_joint : str
    joints : tuple of str
        The joints of the limb, the actuated one included.
    edges : tuple of (u, v, key)
        The limb's edges in the twist graph.
    twist_system : ScrewSystem
        Sum of the twists of the limb's joints (paper 002 Eq. 1).
    constraint_wrenches : ScrewSystem
        Its reciprocal: the wrenches the limb transmits with the actuator free.
    passive_wrenches : ScrewSystem
        Reciprocal to every twist of the limb but the actuated one's (with the actuator locked).
    actuation_wrench : numpy.ndarray, shape (6,), or None
        An element of ``passive_wrenches`` not reciprocal to the actuated twist (a line where one
        exists), None at a serial singularity of this limb. Where the limb's compound leg is
        analysed as a whole, the leg's wrench that loads this actuator alone (it may then lie
        outside ``passive_wrenches`` and have a pitch; :func:`_compound_legs`).
    actuated_twist : numpy.ndarray, shape (6,)
    transmission : float
        :func:`normalized_reciprocal_product` of the actuation wrench and the actuated twist (0 at
        a serial singularity: the actuator cannot move the platform).
    """

    actuated_joint: str
    joints: tuple[str, ...]
    edges: tuple[tuple[Any, Any, str], ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem
    passive_wrenches: ScrewSystem
    actuation_wrench: Array | None
    actuated_twist: Array
    transmission: float


@dataclass(frozen=True, eq=False)
class CompoundLeg:
    """A branch between base and platform in the series-parallel decomposition (e.g. H4 ``L_I``).

    Attributes
    ----------
    joints : tuple of str
    twist_system : ScrewSystem
    constraint_wrenches : ScrewSystem
    actuated : tuple of str
        Its actuated joints, sorted.
    """

    joints: tuple[str, ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem
    actuated: tuple[str, ...] = ()

    @property
    def name(self) -> str:
        """``"leg through A1, A4"`` (its actuated joints), or its first joints if it has none."""
        return "leg through " + ", ".join(self.actuated or sorted(self.joints)[:2])


# --------------------------------------------------------------------------------------------------
# The batched result
# --------------------------------------------------------------------------------------------------


@dataclass(frozen=True, eq=False)
class WrenchAnalysis:
    """Wrench systems of a mechanism over a batch of configurations (see the module docstring).

    Arrays have the leading batch shape :attr:`shape` (``()`` for one pose). Index it like an
    array (``analysis[3]``) for one pose; the per-pose views (:attr:`platform_twists`,
    :attr:`limbs`, :attr:`graph`, ...) need a single pose.

    Attributes
    ----------
    table_source : JointTable or callable
        The analysed joint table, or a function returning it (a batch analysed chunk by chunk
        keeps no table; :attr:`table` asks for it when a per-pose view needs it).
    topology : Topology
    rtol : float
    dof : int
        The nominal mobility of the platform.
    reference_point : numpy.ndarray, shape (..., 3)
    length_scale : numpy.ndarray or float, shape (...)
        From :func:`~screwkit.algebra.reference_frame.mechanism_frame`.
    platform_order, constraint_order, global_order : numpy.ndarray of int, shape (...)
    serial : numpy.ndarray of bool, shape (..., n_actuated)
        True where the limb's actuator cannot move the platform.
    transmissions : numpy.ndarray, shape (..., n_actuated)
    actuation_rows : numpy.ndarray, shape (..., n_actuated, 6)
        The actuation wrenches, user frame, each a unit force or unit couple (zero where serial).
    actuated_twists : numpy.ndarray, shape (..., n_actuated, 6)
    branch_rows : numpy.ndarray, shape (..., n_actuated, 6)
        The part of each actuation wrench carried by its actuated joint's own branch, scaled as
        :attr:`actuation_rows`: ``B_jj = branch_j ∘ $_j`` (:mod:`screwkit.core.jacobians`). Equal to
        the actuation wrench except in a compound leg analysed as a whole (:func:`analyze_table`);
        where no leg is, the very array :attr:`actuation_rows`.
    closeness_factors : dict of str to numpy.ndarray, shape (..., 21)
        ``"constraint"``, ``"actuation"``: triangular factors (:func:`screwkit.core._frames.triangular`,
        :func:`~screwkit.core._frames.packed`) with the singular values of the matrices the closeness
        measures are defined on (:attr:`closeness`).
    """

    table_source: JointTable | Callable[[], JointTable] = field(repr=False)
    topology: Topology = field(repr=False)
    rtol: float
    dof: int
    reference_point: Array = field(repr=False)
    length_scale: Any = field(repr=False)
    platform_order: Array
    constraint_order: Array
    global_order: Array
    serial: Array
    transmissions: Array = field(repr=False)
    actuation_rows: Array = field(repr=False)
    actuated_twists: Array = field(repr=False)
    branch_rows: Array = field(repr=False)
    frames: dict[str, Frame] = field(repr=False)
    closeness_factors: dict[str, Array] = field(repr=False)

    @functools.cached_property
    def closeness(self) -> dict[str, Any]:
        """The closeness measures (:mod:`screwkit.core.singularity`), computed on first use: the
        labels need only orders and serial flags, so a batch pays for the two 6×6 SVDs per pose
        only when its closeness is asked. ``constraint`` is ``σ_(6 − dof) / σ_1`` and ``actuation``
        ``σ_6 / σ_1`` of :attr:`closeness_factors` (six rows with the singular values of the stacked
        legs' constraint wrenches, and of those stacked with the actuation wrenches apart from
        their legs; :func:`analyze_table`), ``serial`` the smallest transmission."""
        factors, transmissions = self.closeness_factors, self.transmissions
        values = {
            "constraint": _singular_ratios(factors["constraint"], 6 - self.dof),
            "actuation": _singular_ratios(factors["actuation"], 6),
            "serial": np.min(transmissions, axis=-1) if transmissions.shape[-1] else np.ones(self.shape),
        }
        return {k: _scalar(v) for k, v in values.items()}

    # --- batch behaviour -------------------------------------------------------------------------
    @functools.cached_property
    def table(self) -> JointTable:
        """The analysed joint table (computed on first use when the analysis kept none)."""
        source = self.table_source
        return source if isinstance(source, JointTable) else source()

    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape (``()`` for one pose)."""
        return tuple(np.shape(self.platform_order))

    @property
    def single(self) -> bool:
        """True for one pose."""
        return self.shape == ()

    def __len__(self) -> int:
        if self.single:
            raise TypeError("a WrenchAnalysis of one pose has no length")
        return self.shape[0]

    def __getitem__(self, index: Any) -> WrenchAnalysis:
        def pick(value: Any) -> Any:
            return value[index]

        source = self.table_source
        return replace(
            self,
            table_source=source[index]
            if isinstance(source, JointTable)
            else functools.partial(_indexed_table, self, index),
            reference_point=pick(self.reference_point),
            length_scale=_scalar(pick(np.asarray(self.length_scale))),
            platform_order=_scalar(pick(self.platform_order)),
            constraint_order=_scalar(pick(self.constraint_order)),
            global_order=_scalar(pick(self.global_order)),
            serial=pick(self.serial),
            transmissions=pick(self.transmissions),
            actuation_rows=pick(self.actuation_rows),
            actuated_twists=pick(self.actuated_twists),
            branch_rows=pick(self.branch_rows),
            frames={k: (rows[index], _scalar(order[index])) for k, (rows, order) in self.frames.items()},
            closeness_factors={k: v[index] for k, v in self.closeness_factors.items()},
        )

    def __repr__(self) -> str:
        return f"WrenchAnalysis(shape={self.shape}, dof={self.dof}, actuated={self.topology.actuated})"

    # --- per-pose views --------------------------------------------------------------------------
    def _require_single(self, what: str) -> None:
        if not self.single:
            raise ScrewkitTypeError(
                f"Expected one pose for `{what}`, got a batch of shape {self.shape}; "
                "index the analysis first."
            )

    def _system(self, key: str) -> ScrewSystem:
        self._require_single(key)
        if key not in self.frames:
            self._add_views()
        rows, order = self.frames[key]
        user = F.from_scaled(rows[: int(order)], self.reference_point, np.asarray(self.length_scale))
        return ScrewSystem.from_independent(user, rtol=self.rtol, length_scale=float(self.length_scale))

    def _add_views(self) -> None:
        """The per-pose frames a batch analysed without views did not keep (classify_table): this
        pose again, as a batch of one through the same kernels (the same arithmetic, same answers)."""
        one = analyze_table(self.table[None], dof=self.dof, rtol=self.rtol, length_scale=self.length_scale)
        self.frames.update({key: (rows[0], order[0]) for key, (rows, order) in one.frames.items()})

    @functools.cached_property
    def graph(self) -> nx.MultiDiGraph:
        """The analysed twist graph (one pose)."""
        self._require_single("graph")
        return self.table.graph()

    @property
    def platform_twists(self) -> ScrewSystem:
        """The platform's twist system (one pose)."""
        return self._system("platform")

    @property
    def constraint_wrenches(self) -> ScrewSystem:
        """The mechanism's constraint wrench system ``W^c = T^⊥`` (paper 002 Eq. 3; one pose)."""
        return self._system("constraint")

    @property
    def global_wrenches(self) -> ScrewSystem:
        """``W^c + W^a`` (paper 002 Eq. 4; one pose)."""
        return self._system("global")

    @property
    def uncontrolled_twists(self) -> ScrewSystem:
        """The platform twists left with every actuator locked: reciprocal to ``W^c + W^a``."""
        return self._system("uncontrolled")

    @property
    def compound_legs(self) -> tuple[CompoundLeg, ...]:
        """The compound legs (empty when the graph is not series-parallel; one pose)."""
        self._require_single("compound_legs")
        if self.topology.network:
            return ()
        actuated = set(self.topology.actuated)
        return tuple(
            CompoundLeg(
                node.joints,
                self._system(f"leg{k}:T"),
                self._system(f"leg{k}:W"),
                tuple(sorted(j for j in node.joints if j in actuated)),
            )
            for k, node in enumerate(self.topology.nodes[i] for i in self.topology.legs)
        )

    @property
    def limbs(self) -> tuple[Limb, ...]:
        """One :class:`Limb` per actuated joint, sorted by name (one pose)."""
        self._require_single("limbs")
        edges = {spec.name: (spec.parent, spec.child, spec.name) for spec in self.table.specs}
        result = []
        for k, plan in enumerate(self.topology.limbs):
            wrench = None if self.serial[k] else np.array(self.actuation_rows[k])
            result.append(
                Limb(
                    actuated_joint=plan.actuated_joint,
                    joints=plan.joints,
                    edges=tuple(edges[name] for name in plan.joints),
                    twist_system=self._system(f"limb{k}:T"),
                    constraint_wrenches=self._system(f"limb{k}:W"),
                    passive_wrenches=self._system(f"limb{k}:passive"),
                    actuation_wrench=wrench,
                    actuated_twist=np.array(self.actuated_twists[k]),
                    transmission=float(self.transmissions[k]),
                )
            )
        return tuple(result)

    @property
    def actuation_wrenches(self) -> Array:
        """The actuation wrenches that exist, rows ``(k, 6)`` in limb order (one pose)."""
        self._require_single("actuation_wrenches")
        rows = [row for row, serial in zip(self.actuation_rows, self.serial, strict=True) if not serial]
        return np.array(rows).reshape(len(rows), 6)

    def constraint_generators(self) -> Array:
        """The compound legs' constraint wrenches stacked (the mechanism's generators), ``(k, 6)``.

        Falls back to a basis of :attr:`constraint_wrenches` when the graph is not
        series-parallel.
        """
        legs = self.compound_legs
        if not legs:
            return np.asarray(self.constraint_wrenches.basis, dtype=float)
        rows = [leg.constraint_wrenches.readable_basis() for leg in legs]
        return np.concatenate(rows).reshape(-1, 6)

    @functools.cached_property
    def tree(self) -> SeriesParallelNode | None:
        """The series-parallel decomposition with each node's twist system (None for a network).

        Computed for this pose through the same kernels (a batch of one).
        """
        self._require_single("tree")
        if self.topology.network:
            return None
        if "node0" in self.frames:  # kept by analyze_table(views=True)
            frames = [self.frames[f"node{i}"] for i in range(len(self.topology.nodes))]
        else:
            scaled = unit_scaled(self.table.screws[None], self.reference_point[None], _lengths(self))
            requests = tuple(("twists", i) for i in range(len(self.topology.nodes)))
            core = _Evaluation(self.topology, scaled, self.rtol, requests)
            frames = [(rows[0], order[0]) for rows, order in map(core.frame, requests)]
        nodes: list[SeriesParallelNode] = []
        for (rows, order), node in zip(frames, self.topology.nodes, strict=True):
            user = F.from_scaled(rows[: int(order)], self.reference_point, np.asarray(self.length_scale))
            system = ScrewSystem.from_independent(user, rtol=self.rtol, length_scale=float(self.length_scale))
            children = tuple(nodes[c] for c in node.children)
            edge = None
            if node.joint is not None:
                spec = self.table.specs[node.joint]
                edge = (spec.parent, spec.child, spec.name)
            nodes.append(
                SeriesParallelNode(node.kind, node.ends, system, children, node.links, edge, node.joints)
            )
        return nodes[self.topology.root] if self.topology.root is not None else None


#: Poses whose closeness SVDs run at once (:func:`_singular_ratios`): bounded memory over any batch.
CLOSENESS_CHUNK = 4096


def _singular_ratios(packed: Array, index: int) -> Array:
    """:func:`screwkit.core._frames.singular_ratio` of :func:`~screwkit.core._frames.packed` triangles
    ``(..., 21)``, :data:`CLOSENESS_CHUNK` poses at a time (each pose's SVD on its own: the same
    values whatever the chunk)."""
    flat = packed.reshape(-1, packed.shape[-1])
    out = np.empty(len(flat))
    for start in range(0, len(flat), CLOSENESS_CHUNK):
        out[start : start + CLOSENESS_CHUNK] = F.singular_ratio(
            F.unpacked(flat[start : start + CLOSENESS_CHUNK]), index
        )
    return out.reshape(packed.shape[:-1])


def _indexed_table(analysis: WrenchAnalysis, index: Any) -> JointTable:
    """``analysis.table[index]`` (the table source of an indexed analysis that kept no table)."""
    return analysis.table[index]


def _scalar(value: Any) -> Any:
    array = np.asarray(value)
    return array.item() if array.ndim == 0 else value


def _lengths(analysis: WrenchAnalysis) -> Array:
    return np.asarray(analysis.length_scale, dtype=float)[None]


# --------------------------------------------------------------------------------------------------
# The kernels
# --------------------------------------------------------------------------------------------------


#: What a frame program computes: ``("twists", node)``, ``("wrenches", node)`` of a tree node,
#: ``("sum", nodes)``, the sum of the twist systems of tree nodes (a limb with its actuator locked),
#: or ``("passive", nodes)``, the reciprocal of that sum (the limb's passive wrenches).
Request = tuple[str, Any]


@dataclass(frozen=True, eq=False)
class _Program:
    """A topology's frames as a flat list of operations, built once per topology and requests
    (:func:`_program`) and run over a batch by :func:`_run` (one compiled call on the numba path,
    op by op with the batched kernels of :mod:`screwkit.core._frames` on the numpy path).

    Each op writes a new slot (its index): ``(code, slot, first, count)`` with ``code`` a span of
    ``sources[first : first + count]`` (rows ``(kind, a, b)``: joint screw rows ``a .. a + b`` or
    the first ``b`` rows of slot ``a``) or the reciprocal of slot ``first``
    (:func:`screwkit.core._frames_numba.run_program`), or the reciprocal of the span of two spherical
    joints' rows in closed form (:func:`screwkit.core._frames.rod`: the line through their centres,
    paper 002 §4.1's rod force; the issue's "closed-form reciprocal systems")."""

    ops: Array
    sources: Array
    slots: dict[Request, int]
    last_use: tuple[int, ...]


#: The op codes and source kinds of a :class:`_Program` (those of the compiled interpreter).
SPAN, RECIPROCAL, ROD, EXTEND, CONTRACT, PARALLELOGRAM, COMPANION = 0, 1, 2, 3, 4, 5, 6
JOINT_ROWS, SLOT_ROWS = 0, 1


class _ProgramBuilder:
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
        """A static upper bound on a node's twist order (zero rows beyond it are dropped)."""
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
        """What a node adds to a sum of twist systems: a joint's screws, else its frame's rows."""
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
        key = ("twists", index)
        if key not in self.slots:
            node = self.top.nodes[index]
            if node.kind == "parallel":
                wrenches = self.wrenches(index)  # a parallelogram's twists come with its wrenches
                if key not in self.slots:
                    self.slots[key] = self._op(RECIPROCAL, wrenches, 0)
            elif node.kind == "joint":
                self.slots[key] = self._span(self.generators(index))
            else:
                self.slots[key] = self._chain_sum(node.children)
        return self.slots[key]

    def wrenches(self, index: int) -> int:
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
            else:
                self.slots[key] = self._op(RECIPROCAL, self.twists(index), 0)
        return self.slots[key]

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
def _program(top: Topology, requests: tuple[Request, ...]) -> _Program:
    """The ops computing ``requests`` (cached per topology object and requests)."""
    builder = _ProgramBuilder(top)
    for request in requests:
        builder.request(request)
    last_use = list(range(len(builder.ops)))
    for index, (code, _, first, count) in enumerate(builder.ops):
        sources = builder.sources[first : first + count]
        read = [first] if code == RECIPROCAL else [a for kind, a, _ in sources if kind == SLOT_ROWS]
        for slot in read:
            last_use[slot] = index
    return _Program(
        np.array(builder.ops, dtype=np.int64).reshape(-1, 4),
        np.array(builder.sources, dtype=np.int64).reshape(-1, 3),
        {request: builder.slots[request] for request in requests},
        tuple(last_use),
    )


def _run(program: _Program, scaled: Array, rtol: float, requests: tuple[Request, ...]) -> Frame:
    """The requested frames of a program over the batch of ``scaled`` ``(..., rows, 6)``, on an
    axis of their own: rows ``(..., len(requests), 6, 6)``, orders ``(..., len(requests))``."""
    batch = scaled.shape[:-2]
    wanted = [program.slots[r] for r in requests]
    kernels = compiled_kernels("screwkit.core._frames_numba", math.prod(batch))
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
                frames[slot] = F.rod(np.concatenate(parts, axis=-2), rtol)
            else:
                frames[slot] = F.span(np.concatenate(parts, axis=-2), rtol) if parts else F.empty(batch)
        for done in [s for s in frames if program.last_use[s] <= index and s not in keep]:
            del frames[done]  # bounded memory over large batches
    return _stacked([frames[s] for s in wanted])


def _parallelogram(rods: list[Frame], rtol: float) -> tuple[Frame, Frame]:
    """:data:`PARALLELOGRAM` over the batch (numpy path): the closed form
    (:func:`screwkit.core._frames.parallelogram`), the span of the two rods' frames and its reciprocal
    where it does not apply; :func:`screwkit.core._frames_numba.run_program`'s steps."""
    first, second = rods
    wrenches, wrench_order, twists, twist_order, decided = F.parallelogram(first, second, rtol)
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
    (:func:`screwkit.core._frames.extend`, :func:`~screwkit.core._frames.contract`), the rule's span (and
    reciprocals) where it does not decide; :func:`screwkit.core._frames_numba.run_program`'s steps."""
    (joint,) = [a for kind, a, _ in sources[:2] if kind == JOINT_ROWS]
    (slot,) = [a for kind, a, _ in sources[:2] if kind == SLOT_ROWS]
    rows, order = frames[slot]
    closed = F.extend if code == EXTEND else F.contract
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


class _Evaluation:
    """Cached frames of a topology over one batch of scaled, unit joint screws: the ``requests``
    given at creation run as one program (:func:`_program`); any other frame asked for later
    runs a program of its own."""

    def __init__(self, top: Topology, scaled: Array, rtol: float, requests: tuple[Request, ...] = ()):
        self.top, self.scaled, self.rtol = top, scaled, rtol
        self.batch = scaled.shape[:-2]
        self.columns = top.columns
        self._blocks: list[tuple[dict[Request, int], Frame]] = []
        if requests:
            self._compute(requests)

    def _compute(self, requests: tuple[Request, ...]) -> None:
        block = _run(_program(self.top, requests), self.scaled, self.rtol, requests)
        self._blocks.append(({r: i for i, r in enumerate(requests)}, block))

    def _find(self, request: Request) -> tuple[int, Frame]:
        for positions, block in self._blocks:
            if request in positions:
                return positions[request], block
        self._compute((request,))
        return 0, self._blocks[-1][1]

    def frame(self, request: Request) -> Frame:
        index, (rows, orders) = self._find(request)
        return rows[..., index, :, :], orders[..., index]

    def stacked(self, requests: list[Request]) -> Frame:
        """Frames on an axis of their own, ``(..., len(requests), 6, 6)``: a view when they were
        computed together, in this order."""
        found = [self._find(r) for r in requests]
        first, block = found[0]
        if all(b is block and i == first + k for k, (i, b) in enumerate(found)):
            kept = slice(first, first + len(requests))
            return block[0][..., kept, :, :], block[1][..., kept]
        return _stacked([(rows[..., i, :, :], orders[..., i]) for i, (rows, orders) in found])

    def joint_rows(self, index: int) -> Array:
        start = self.columns[index]
        return self.scaled[..., start : start + self.top.specs[index].dof, :]

    def twists(self, index: int) -> Frame:
        return self.frame(("twists", index))

    def wrenches(self, index: int) -> Frame:
        return self.frame(("wrenches", index))

    def network(self, joints: tuple[int, ...], locked: int | None = None) -> Frame:
        """The platform's twist system of a sub-network by loop closure: ``rank[M; P] − rank M``
        decides the null space of the loop-closure matrix ``M``; ``P`` maps it to the platform."""
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


def _nearest_lines(wrench: Array, constraints_at: Callable[[Array], Array], order: Array) -> Array:
    """``wrench + c`` of zero pitch with ``c`` the smallest constraint wrench found that makes it a
    line, where the wrench is not already one (batched; rows orthonormal, scaled). The constraint
    system has ``order`` rows; ``constraints_at(where)`` gives its rows ``(m, 6, 6)`` at a boolean
    mask of the batch (asked only where a wrench is searched).

    The pitch numerator of ``w + C α`` is the quadratic ``αᵀQα + bᵀα + p0`` (``Q`` the symmetric
    part of ``C_s C_mᵀ``). Along a direction ``u`` it is a quadratic in one variable; the
    directions tried are the frame's rows, the gradient ``b`` (steepest descent) and the
    eigenvectors of ``Q``, and the root of smallest ``|α|`` wins. Only the wrenches that are not
    lines and have constraint wrenches to add are searched (each on its own: a pose's answer does
    not depend on the others).
    """
    searched = F.not_lines(wrench, LINE_RTOL) & (np.asarray(order) > 0)
    best = wrench.copy()
    if searched.any():
        best[searched] = _line_search(wrench[searched], constraints_at(searched), np.asarray(order)[searched])
    return best


def _line_search(wrench: Array, constraints: Array, order: Array) -> Array:
    """:func:`_nearest_lines` over wrenches ``(n, 6)`` that are not lines, constraints ``(n, k, 6)``."""
    s, m = wrench[..., :3], wrench[..., 3:]
    pitch = np.einsum("...i,...i->...", s, m)
    mask = np.arange(constraints.shape[-2]) < order[..., None]
    rows = constraints * mask[..., None]
    gradient = np.einsum("...i,...ki->...k", s, rows[..., 3:]) + np.einsum(
        "...ki,...i->...k", rows[..., :3], m
    )
    q = np.einsum("...ki,...li->...kl", rows[..., :3], rows[..., 3:])
    _, vectors = np.linalg.eigh((q + np.swapaxes(q, -1, -2)) / 2)
    directions = np.concatenate(
        [
            np.broadcast_to(np.eye(rows.shape[-2]), vectors.shape),
            gradient[..., None, :],
            np.swapaxes(vectors, -1, -2),
        ],
        axis=-2,
    )  # (..., d, k): every direction tried, on an axis of their own
    u = directions * mask[..., None, :]
    norm_u = np.linalg.norm(u, axis=-1)
    c = np.einsum("...dk,...ki->...di", u / np.where(norm_u > 0, norm_u, 1.0)[..., None], rows)
    usable = norm_u > 0
    a = np.einsum("...i,...i->...", c[..., :3], c[..., 3:])
    b = np.einsum("...i,...di->...d", s, c[..., 3:]) + np.einsum("...di,...i->...d", c[..., :3], m)
    p0 = pitch[..., None]
    disc = b * b - 4 * a * p0
    # the stable pair of roots (Numerical Recipes §5.6): q = -(b + sgn(b) √disc) / 2, α = q/a, p/q
    q = -(b + np.where(b < 0, -1.0, 1.0) * np.sqrt(np.where(disc >= 0, disc, 0.0))) / 2
    real = usable & (disc >= 0)
    with np.errstate(over="ignore"):  # a root past the float range is no candidate (inf)
        roots = np.stack(
            [
                np.where(np.abs(a) > 0, q / np.where(np.abs(a) > 0, a, 1.0), np.inf),
                np.where(np.abs(q) > 0, p0 / np.where(np.abs(q) > 0, q, 1.0), np.inf),
            ],
            axis=-1,
        ).reshape(*q.shape[:-1], -1)  # (..., 2d): direction by direction, both roots of each
    sizes = np.where(np.repeat(real, 2, axis=-1) & np.isfinite(roots), np.abs(roots), np.inf)
    pick = np.argmin(sizes, axis=-1)[..., None]  # the smallest |α|, the first of equals
    alpha = np.take_along_axis(roots, pick, -1)[..., 0]
    found = np.isfinite(np.take_along_axis(sizes, pick, -1)[..., 0])
    chosen = np.take_along_axis(c, (pick // 2)[..., None], -2)[..., 0, :]
    return np.where(
        found[..., None], wrench + np.where(found, alpha, 0.0)[..., None] * chosen, wrench
    )


def _canonical(table: JointTable) -> JointTable:
    """The table with its joints sorted by name: every route to the same mechanism (a family's
    table, a graph's, a graph rebuilt from a table) then runs the same arithmetic in the same order,
    bit for bit; its screws C-contiguous, so that a pose's sums run in one order whatever the batch
    it is in (a strided reduction adds in another)."""
    order = sorted(range(len(table.specs)), key=lambda k: table.specs[k].name)
    if order == list(range(len(order))) and table.screws.flags.c_contiguous:
        return table
    starts = list(itertools.accumulate((spec.dof for spec in table.specs), initial=0))
    rows = [r for k in order for r in range(starts[k], starts[k + 1])]
    specs = tuple(table.specs[k] for k in order)
    screws = np.ascontiguousarray(table.screws[..., rows, :])
    return JointTable(table.base, table.platform, specs, screws, table.dof, table.anchor, table.mobility)


def _checked_dof(dof: Any, table: JointTable, top: Topology) -> int:
    nominal = dof if dof is not None else (table.dof if table.dof is not None else len(top.limbs))
    if not B.is_dof(nominal):
        raise TwistGraphError(f"Expected `dof` to be an integer in 0..6, got {nominal!r}.")
    return int(nominal)


def _checked_lengths(value: Any, batch: tuple[int, ...]) -> Array | None:
    """A given characteristic length as an array of the batch shape (None: derive it).

    Examples
    --------
    >>> _checked_lengths(2, (3,))
    array([2., 2., 2.])
    >>> _checked_lengths([1.0, -1.0], (2,))  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.ScrewkitValueError: Expected `length_scale` to be positive finite numbers in ...
    """
    if value is None or np.ndim(value) == 0:
        checked = checked_length_scale(value, allow_none=True)
        return None if checked is None else np.full(batch, checked)
    try:
        lengths = np.array(np.broadcast_to(np.asarray(value, dtype=float), batch))
    except (TypeError, ValueError) as err:
        got = repr(value) if isinstance(value, str) else f"shape {np.shape(value)}"
        raise ScrewkitValueError(
            f"Expected `length_scale` to be a positive number or an array of the batch shape {batch}, "
            f"got {got}."
        ) from err
    smallest = MIN_LENGTH_SCALE
    if not np.all(np.isfinite(lengths) & (lengths >= smallest) & (lengths * smallest <= 1)):
        raise ScrewkitValueError(
            f"Expected `length_scale` to be positive finite numbers in [{smallest:g}, {1 / smallest:g}], "
            f"got {lengths}."
        )
    return lengths


def analyze_table(
    table: JointTable,
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    views: bool = True,
) -> WrenchAnalysis:
    """The wrench systems of a mechanism over a batch of configurations (the one core).

    Parameters
    ----------
    table : JointTable
        The joints and their screws over the batch (e.g. a family's ``joints(config)``).
    dof : int, optional
        Nominal mobility; default: the table's ``dof``, else the number of actuated joints.
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (:mod:`screwkit.core._frames`).
    length_scale : float or array_like of the batch shape, optional
        The characteristic length moments are divided by before every rank decision, in the
        screws' length unit; default: :func:`~screwkit.algebra.reference_frame.mechanism_frame`'s, derived
        from the screws (so that it follows a change of unit). Given, it must scale with the
        unit for the answers to stay unit-invariant. The reference point is the frame's either way.
        An analysis's own ``length_scale`` given back reproduces it bit for bit.
    views : bool, default True
        Keep the frames that the per-pose views need (every limb's and leg's systems, the
        constraint, global and uncontrolled systems); False keeps only orders, verdict inputs,
        actuation wrenches and the frames the Jacobians need (the platform's twists, each limb's
        passive wrenches): less memory for large batches, the other views recomputed for the one
        pose that asks.

    Returns
    -------
    WrenchAnalysis

    Raises
    ------
    TwistGraphError
        If an actuated joint lies on no base-to-platform path, or ``dof`` is invalid.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointTable
    >>> line = [0, 0, 1.0, 0, 0, 0]
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[line]] * 3, True)])
    >>> analyze_table(table).constraint_order
    array([5, 5, 5])
    """
    if not isinstance(table, JointTable):
        raise ScrewkitTypeError(f"Expected `table` to be a JointTable, got {type(table).__name__}.")
    rtol = checked_rtol(rtol)
    table = _canonical(table)
    top = topology(table.base, table.platform, table.specs)
    nominal = _checked_dof(dof, table, top)
    batch = table.batch_shape
    screws = table.screws
    given_length = _checked_lengths(length_scale, batch)
    if given_length is None:  # the frame's own length, with the scaled screws in the same pass
        centre, length, scaled = scaled_frame(screws, table.anchor)
        assert scaled is not None
    else:  # the reference point as derived, the given length
        centre, _, _ = scaled_frame(screws, table.anchor, scale=False)
        length = given_length
        scaled = unit_scaled(screws, centre, length)
    requests: tuple[Request, ...] = ()
    if not top.network:  # every frame the analysis needs, in one program
        assert top.root is not None
        requests = (
            ("twists", top.root),
            ("wrenches", top.root),  # the constraint system (paper 002 Eq. 3), spanned by the legs'
            *((("twists", i) for i in top.legs) if views else ()),
            *(("wrenches", i) for i in top.legs),
            *(("sum", tuple(plan.siblings)) for plan in top.limbs),
            *(("passive", tuple(plan.siblings)) for plan in top.limbs),
            *((("twists", i) for i in range(len(top.nodes))) if views else ()),
        )
        requests = tuple(dict.fromkeys(requests))
    core = _Evaluation(top, scaled, rtol, requests)
    frames: dict[str, Frame] = {}
    leg_block: Array | None = None
    if top.network:
        platform = core.network(tuple(range(len(top.specs))))
        leg_wrenches = [F.reciprocal(*platform)]
        leg_twists = [platform]
    else:
        assert top.root is not None
        platform = core.twists(top.root)
        leg_twists = [core.twists(i) for i in top.legs] if views else []
        leg_wrenches = [core.wrenches(i) for i in top.legs]
        leg_block = core.stacked([("wrenches", i) for i in top.legs])[0]  # a view of the program's block
    constraint = F.reciprocal(*platform) if top.network or top.root is None else core.wrenches(top.root)
    legs = leg_block if leg_block is not None else np.stack([w[0] for w in leg_wrenches], axis=-3)
    n = len(top.limbs)
    free: tuple[Array | None, Array]
    if n and top.network:  # each limb's sub-network by loop closure
        lockeds, frees, perpendiculars, serials, twists = [], [], [], [], []
        for plan in top.limbs:
            twist = plan.sign * core.joint_rows(plan.index)[..., 0, :]
            lockeds.append(core.network(plan.network_edges, locked=plan.index))
            frees.append(core.network(plan.network_edges))
            perpendiculars.append(F.residual(twist[..., None, :], lockeds[-1][0])[..., 0, :])
            serials.append(frees[-1][1] == lockeds[-1][1])
            twists.append(twist)
        serial = np.stack(serials, axis=-1)
        actuated = np.stack(twists, axis=-2)
        perpendicular = np.stack(perpendiculars, axis=-2)
        locked, free = _stacked(lockeds), _stacked(frees)
        passive = F.reciprocal(*locked)
        direction = F.actuation_directions(passive[0], perpendicular)
    elif n:  # the limbs on an axis of their own (..., n, ...), their locked systems from the program
        locked = core.stacked([("sum", tuple(plan.siblings)) for plan in top.limbs])
        passive = core.stacked([("passive", tuple(plan.siblings)) for plan in top.limbs])
        actuated = _actuated(top, scaled)
        coupled = _coupled(top)
        serial, order, direction, wrench, transmissions, leg_residuals, not_line = F.limb_wrenches(
            locked[0], locked[1], passive[0], actuated, legs, np.array(coupled, dtype=np.int64),
            np.array([_leg_of(top, k) for k in coupled], dtype=np.int64), rtol, LINE_RTOL,
        )  # in one pass; the free rows only for the views, else where a line is searched
        free_rows = F.limb_systems(locked[0], locked[1], passive[0], actuated, rtol)[2] if views else None
        free = (free_rows, order)
        del free_rows  # held by `free` alone, freed with it
    if n:
        # the limbs' constraint systems (reciprocal to `free`): kept for the views, else computed only
        # where an actuation wrench is searched for a line (_nearest_lines; at a few poses, if any)
        limb_constraint: Frame | None = None
        if views:
            assert free[0] is not None
            limb_constraint = F.reciprocal(free[0], free[1])

        def limb_constraints_at(where: Array) -> Array:
            if limb_constraint is not None:
                return limb_constraint[0][where]
            if free[0] is not None:
                return F.reciprocal(free[0][where], free[1][where])[0]
            at = (locked[0][where], locked[1][where], passive[0][where], actuated[where])
            rows = F.limb_systems(*at, rtol)[2]
            assert rows is not None
            return F.reciprocal(rows, free[1][where])[0]

        if top.network:
            lines = _nearest_lines(direction, limb_constraints_at, 6 - free[1])
            wrench, transmissions = F.transmissions(lines, actuated, rtol)
            residuals = _leg_residuals(top, wrench, legs)
        else:  # where a direction is no line: the line found (_nearest_lines), its wrench again
            residuals = leg_residuals if coupled else None
            searched = not_line & (6 - free[1] > 0)
            if searched.any():
                lines = direction.copy()
                lines[searched] = _line_search(
                    direction[searched], limb_constraints_at(searched), (6 - free[1])[searched]
                )
                again = searched.any(axis=-1)
                wrench[again], transmissions[again] = F.transmissions(lines[again], actuated[again], rtol)
                if residuals is not None:
                    residuals[again] = _leg_residuals(top, wrench[again], legs[again])
        branch, locked_legs = wrench, None
        compound = _compound_legs(
            top, scaled, rtol, leg_wrenches, actuated, (wrench, serial, transmissions), residuals
        )
        if compound is not None:
            serial, wrench, branch, transmissions, locked_legs = compound
        wrench_rows = np.where(serial[..., None], 0.0, wrench)
        if compound is not None:  # the replaced limbs' wrenches measured again
            residuals = _leg_residuals(top, wrench_rows, legs)
        elif residuals is not None:  # a serial limb's row is zero, and so is its residual (exactly)
            residuals = np.where(serial[..., _coupled(top), None], 0.0, residuals)
        for k in range(n):
            frames[f"limb{k}:passive"] = _limb(passive, k)  # the Jacobians' rows at serial singularities
            if views:
                assert free[0] is not None and limb_constraint is not None
                frames[f"limb{k}:T"] = _limb((free[0], free[1]), k)
                frames[f"limb{k}:W"] = _limb(limb_constraint, k)
        del free, limb_constraint  # (..., n, 6, 6) each: not alive while the closeness inputs are built
    else:
        serial, transmissions = np.zeros((*batch, 0), dtype=bool), np.zeros((*batch, 0))
        wrench_rows = branch = np.zeros((*batch, 0, 6))
        locked_legs, residuals = None, None
    # the global frame; the legs' stacked constraint wrenches as six rows with their singular
    # values (F.triangular: two 6×6 SVDs instead of (6 legs + n) × 6 ones), their singular values on
    # demand (WrenchAnalysis.closeness); the actuation rows in the user's frame
    apart = _apart_from_legs(top, wrench_rows, residuals)
    global_rows, global_order, constraint_factor, actuation_factor, actuation_rows = F.closing(
        constraint[0], wrench_rows, legs, apart, serial, centre, length, rtol
    )
    global_frame = (global_rows, global_order)
    closeness_factors = {"constraint": constraint_factor, "actuation": actuation_factor}
    if locked_legs is not None:  # where a compound leg was analysed as a whole
        locked_legs.add_to(global_frame, constraint, wrench_rows, rtol)
    frames["platform"] = platform  # the Jacobians' nominal twists are checked against it
    if views:  # else recomputed for the one pose that asks (WrenchAnalysis._add_views)
        frames.update(constraint=constraint, uncontrolled=F.reciprocal(*global_frame))
        frames["global"] = global_frame
    if views and not top.network:  # every node's twists, for the per-pose series-parallel tree
        for index in range(len(top.nodes)):
            frames[f"node{index}"] = core.twists(index)
    if views:
        for k, (twist_frame, wrench_frame) in enumerate(zip(leg_twists, leg_wrenches, strict=True)):
            frames[f"leg{k}:T"] = twist_frame
            frames[f"leg{k}:W"] = wrench_frame
    if locked_legs is None:  # every branch row is its actuation wrench: the same array (read only)
        user_branches = actuation_rows
    else:
        size = F.unit_size(F.from_scaled(wrench_rows, centre, length), length)
        user_branches = np.where(serial[..., None], 0.0, F.from_scaled(branch, centre, length) / size)
    return WrenchAnalysis(
        table_source=table,
        topology=top,
        rtol=rtol,
        dof=nominal,
        reference_point=centre,
        length_scale=_scalar(length),
        platform_order=_scalar(platform[1]),
        constraint_order=_scalar(constraint[1]),
        global_order=_scalar(global_frame[1]),
        serial=serial,
        transmissions=transmissions,
        actuation_rows=actuation_rows,
        branch_rows=user_branches,
        actuated_twists=_actuated(top, screws),
        frames=frames,
        closeness_factors=closeness_factors,
    )


def _actuated(top: Topology, screws: Array) -> Array:
    """Each limb's actuated joint's screw with the limb's sign ``(..., n, 6)`` (one gather)."""
    columns = [top.columns[plan.index] for plan in top.limbs]
    signs = np.array([float(plan.sign) for plan in top.limbs])
    return screws[..., columns, :] * signs[:, None]


class _LockedLegs(NamedTuple):
    """Where compound legs were analysed as a whole (:func:`_compound_legs`), each such leg's
    ``W_locked`` there: rows ``(m, 6 q, 6)``, orthonormal, zero beyond each leg's order."""

    where: Array
    rows: Array

    def add_to(self, global_frame: Frame, constraint: Frame, rows: Array, rtol: float) -> None:
        """The global system ``W^c + Σ_L W_L,locked`` at those poses (in place; one rank rule)."""
        where = self.where
        frame = F.span(np.concatenate([constraint[0][where], rows[where], self.rows], axis=-2), rtol)
        global_frame[0][where], global_frame[1][where] = frame


def _coupled(top: Topology) -> list[int]:
    """The limbs with partners in a compound leg (none in a network)."""
    return [] if top.network else [k for k, plan in enumerate(top.limbs) if plan.partners]


def _leg_residuals(top: Topology, rows: Array, legs: Array) -> Array | None:
    """Wrench rows ``(..., n, 6)`` of the limbs with partners (:func:`_coupled`) less their part in
    their compound leg's constraint system (``legs (..., L, 6, 6)``, the legs' wrench frames),
    ``(..., m, 6)`` (not renormalised; None without such limbs): what :func:`_compound_legs` and
    :func:`_apart_from_legs` measure."""
    coupled = _coupled(top)
    if not coupled:
        return None
    return F.residuals_against(rows[..., coupled, :], legs, np.array([_leg_of(top, k) for k in coupled]))


def _apart_from_legs(top: Topology, rows: Array, residuals: Array | None) -> Array:
    """Unit scaled wrench rows ``(..., n, 6)`` with each limb that has partners less its part in its
    compound leg's constraint system (``residuals``, :func:`_leg_residuals` of ``rows``;
    renormalised): the actuation closeness's rows. A limb's own wrench may lie close to that system
    where the leg as a whole transmits well (the H4 near ``n1·z = 0``, :func:`_compound_legs`),
    which would fake a near-singularity."""
    if residuals is None:
        return rows
    out = rows.copy()
    out[..., _coupled(top), :] = F.unit_rows(residuals)
    return out


def _leg_of(top: Topology, k: int) -> int:
    """The index in :attr:`Topology.legs` of limb ``k``'s compound leg."""
    return next(i for i, leg in enumerate(top.legs) if leg in top.limbs[k].path)


def _compound_legs(
    top: Topology,
    scaled: Array,
    rtol: float,
    leg_wrenches: list[Frame],
    actuated: Array,
    limbs: tuple[Array, Array, Array],
    residuals: Array | None,
) -> tuple[Array, Array, Array, Array, _LockedLegs] | None:
    """Compound legs whose actuators share a link, analysed as a whole where a limb's own
    actuation wrench fails: ``serial, wrench, branch, transmissions`` over the batch and the
    quotients (None where no limb's wrench fails). ``limbs``: the limbs' own ``wrench, serial,
    transmissions`` (scaled); ``residuals``: :func:`_leg_residuals` of their wrenches.

    **Why.** A limb with *partners* (:attr:`screwkit.graphs.topology.LimbPlan.partners`; the H4's
    ``A1`` and ``A4`` both carry the nacelle ``b_I``, which joins the end effector by ``R_I``) gets
    its actuation wrench from its own chain (``A1``, parallelogram 1, ``R_I``): the wrench reciprocal
    to that chain's passive joints, paper 002's force along the rods through the point where it
    meets ``R_I``'s axis (§4.3). Where parallelogram 1's plane contains the vertical (``n1·z = 0``)
    that line goes to infinity and becomes the couple ``C_n1``, which is also leg I's constraint
    wrench (paper 002 Eq. 3): the chain alone then says "serial" (``A1``'s twist in the span of
    its chain's passive twists) and the global system loses a rank ("actuation"). Yet the pose
    is regular: paper 004 Eq. (12) gives ``|A| = −47.9`` and paper 002 Eq. (7) ``47.9`` at
    ``(300, 300, −473.80 mm, 30°)`` (tests/test_workspace.py). With the end effector fixed and
    ``A4`` locked, ``b_I`` cannot turn about ``R_I`` (parallelogram 4's couple ``C_n4`` has
    ``n4·z ≠ 0``), so ``A1`` cannot move; with all four arms locked leg I transmits three
    independent wrenches (``C_n1``, ``F_w1 − (m1/n4z) C_n4``, ``F_w4 − (m4/n4z) C_n4``), leg II
    three. What fails is only the chain's assumption that its wrench does no work on the motion
    of the partner ``A4``.

    **The leg as a whole.** For a compound leg ``L`` with ``n_L`` actuators, ``W_free`` is its
    constraint system and ``W_locked`` the reciprocal of its twist system with its actuators
    locked. A wrench ``W`` of ``W_locked`` reaches the base through the leg's branches: split at
    each parallel node into the branches' locked wrench systems (least squares; unique when they
    are independent), the part reaching actuator ``j`` loads it with ``τ_j(W) = branch_j ∘ $_j``,
    and every motion of the leg has ``W ∘ t = Σ_j τ_j(W) θ̇_j`` (virtual work). So:

    * the leg is **serial** (an actuator moves with the platform fixed) iff ``τ`` loses rank on
      ``W_locked / W_free`` (``τ`` vanishes on ``W_free``; that quotient has order
      ``ord W_locked − ord W_free ≤ n_L``); actuator ``k`` is among the serial ones iff no
      wrench of ``W_locked`` loads ``k`` without loading the others: with ``τ`` evaluated on the
      orthonormal rows ``L_i`` of ``W_locked``, ``c_k``, the part of ``k``'s column orthogonal to
      the other actuators' columns, is ``≤ rtol`` (the rule of the limb's ``t⊥``; its
      transmission is then that of ``Σ_i c_k,i L_i``, ``~|c_k|``, continuous up to the
      singularity);
    * otherwise ``W_k = Σ_i c_k,i L_i`` loads ``k`` alone (``τ_k(W_k) = |c_k|²``), so ``B`` of the
      leg stays diagonal, ``B_kk = τ_k(W_k)`` (the branch row, :mod:`screwkit.core.jacobians`); drawn
      as a line where adding a constraint wrench can make it one (:func:`_nearest_lines`; at
      ``n1·z = 0`` it cannot: the H4's ``W_1`` has a pitch there);
    * the global system is ``W^c + Σ_L W_L,locked`` (each such leg's ``W_locked`` added; one rank
      rule).

    Evidence (tests/test_compound_legs.py): at the H4 pose above the core now says regular; its
    ``det A`` equals paper 004's Eq. (12), its ``B`` paper 004's ``diag(−h_i)`` (Eq. 8), ``B⁻¹A``
    the finite differences of the inverse kinematics, and the six locked-leg wrenches written out
    by hand have rank 6; where both of ``b_I``'s parallelograms are vertical the nacelle spins about
    ``R_I`` with the end effector and ``A4`` fixed, turning ``A1``: a serial singularity of ``A1``
    that paper 004's model, whose sub-platforms do not turn, cannot see (its ``h_1 ≠ 0`` there).

    Generically a limb's own wrench lies in ``W_locked``, outside ``W_free``, and loads no
    partner, so it is kept: the leg is analysed as a whole only at the poses where a limb with
    partners is serial by its chain or its wrench lies within :data:`COMPOUND_RTOL` of ``W_free``,
    and only its failing limbs are replaced.
    """
    coupled = _coupled(top)
    if residuals is None:
        return None
    wrench, serial, transmissions = limbs
    failing = np.zeros(serial.shape, dtype=bool)
    failing[..., coupled] = serial[..., coupled] | (np.linalg.norm(residuals, axis=-1) <= COMPOUND_RTOL)
    where = np.asarray(failing.any(axis=-1))
    if not where.any():
        return None
    locked_scaled = scaled[where].copy()
    for plan in top.limbs:
        start = top.columns[plan.index]
        locked_scaled[:, start : start + top.specs[plan.index].dof, :] = 0.0
    locked = _Evaluation(top, locked_scaled, rtol)
    twists = actuated[where]
    fixed_serial, fixed_wrench = serial[where], wrench[where]
    fixed_branch, fixed_transmissions = fixed_wrench.copy(), transmissions[where]
    lockeds = []
    for leg in sorted({_leg_of(top, k) for k in coupled}):
        members = [k for k in range(len(top.limbs)) if _leg_of(top, k) == leg]
        free = (leg_wrenches[leg][0][where], leg_wrenches[leg][1][where])
        leg_locked = locked.wrenches(top.legs[leg])[0]  # (m, 6, 6), zero beyond its order
        lockeds.append(leg_locked)
        paths = {k: _leg_path(top, k, leg) for k in members}
        loads = np.stack(  # τ_j(L_i) over the rows L_i of W_locked, (m, 6, n_L)
            [
                np.einsum(
                    "...is,...s->...i",
                    _branch_part(top, locked, paths[j], leg_locked, rtol),
                    F.swapped(twists[:, j]),
                )
                for j in members
            ],
            axis=-1,
        )
        for position, k in enumerate(members):
            replace_k = failing[where][:, k]
            if not replace_k.any():
                continue
            others = np.swapaxes(np.delete(loads, position, axis=-1), -1, -2)  # (m, n_L - 1, 6)
            alone = F.residual(loads[:, None, :, position], F.span(others, rtol)[0])[:, 0, :]
            size = np.linalg.norm(alone, axis=-1)
            is_serial = size <= rtol
            direction = F.unit_rows(np.einsum("...i,...is->...s", alone, leg_locked))
            # a line only if the constraint added stays small
            line = _nearest_lines(direction, free[0].__getitem__, free[1])
            near = np.linalg.norm(line - direction, axis=-1) <= COMPOUND_LINE_REACH
            chosen = F.unit_rows(np.where(near[:, None], line, direction))
            part = _branch_part(top, locked, paths[k], chosen[:, None, :], rtol)[:, 0, :]
            product = np.abs(np.einsum("...s,...s->...", part, F.swapped(twists[:, k])))
            new = replace_k & ~is_serial  # a serial actuator keeps its limb's (unused) wrench
            fixed_serial[:, k] = np.where(replace_k, is_serial, fixed_serial[:, k])
            fixed_wrench[:, k] = np.where(new[:, None], chosen, fixed_wrench[:, k])
            fixed_branch[:, k] = np.where(new[:, None], part, fixed_branch[:, k])
            transmission = np.where(  # serial: of the unit c_k·L, whose load is |c_k| (continuous)
                is_serial,
                F.transmission_index(direction, twists[:, k], size, rtol),
                F.transmission_index(chosen, twists[:, k], product, rtol),
            )
            fixed_transmissions[:, k] = np.where(replace_k, transmission, fixed_transmissions[:, k])
    serial, wrench, transmissions = serial.copy(), wrench.copy(), transmissions.copy()
    branch = wrench.copy()
    serial[where], wrench[where], branch[where], transmissions[where] = (
        fixed_serial,
        fixed_wrench,
        fixed_branch,
        fixed_transmissions,
    )
    return serial, wrench, branch, transmissions, _LockedLegs(where, np.concatenate(lockeds, axis=-2))


def _leg_path(top: Topology, k: int, leg: int) -> tuple[int, ...]:
    """Limb ``k``'s path from its compound leg's node down to its actuated joint."""
    path = top.limbs[k].path
    return path[path.index(top.legs[leg]) :]


def _branch_part(
    top: Topology, locked: _Evaluation, path: tuple[int, ...], wrenches: Array, rtol: float
) -> Array:
    """The part of wrenches ``(m, k, 6)`` of a leg's locked system that reaches the end of
    ``path``: split at each parallel node into its branches' locked wrench systems (minimum-norm
    least squares), the path's branch kept."""
    for node_index, child in itertools.pairwise(path):
        node = top.nodes[node_index]
        if node.kind != "parallel":
            continue
        blocks = np.concatenate([locked.wrenches(c)[0] for c in node.children], axis=-2)  # (m, 6p, 6)
        coefficients = np.einsum("...ks,...sr->...kr", wrenches, np.linalg.pinv(blocks, rcond=rtol))
        at = 6 * node.children.index(child)
        wrenches = np.einsum(
            "...kr,...rs->...ks", coefficients[..., at : at + 6], blocks[..., at : at + 6, :]
        )
    return wrenches


def _stacked(frames: list[Frame]) -> Frame:
    """Frames of the limbs on an axis of their own: rows ``(..., n, 6, 6)``, orders ``(..., n)``."""
    return np.stack([rows for rows, _ in frames], axis=-3), np.stack([order for _, order in frames], axis=-1)


def _limb(frame: Frame, k: int) -> Frame:
    """Limb ``k``'s frame from :func:`_stacked` frames."""
    return frame[0][..., k, :, :], frame[1][..., k]


def wrench_analysis(
    graph: nx.MultiDiGraph,
    *,
    dof: int | None = None,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> WrenchAnalysis | GenericAnalysis:
    """Constraint, actuation and global wrench systems of a twist graph at its configuration.

    The graph is a batch of one pose through :func:`analyze_table`. A graph whose screws hold
    sympy symbols (a family) gets its generic answers instead
    (:func:`screwkit.core.generic.generic_analysis`).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph (physical or equivalent).
    dof : int, optional
        Nominal mobility; default: the graph's ``dof`` attribute, else derived. Either way it must
        be the mechanism's mobility at generic configurations, with at most that many actuators
        (:func:`screwkit.core.motion.resolve_dof`; checked by :func:`screwkit.core.motion.settled_dof`, at
        no cost when the pose is regular with one actuator per freedom).
    joint_key : str
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (checked, and unused, for a symbolic graph: its
        generic decisions are exact).
    length_scale : float, optional
        The characteristic length of the rank decisions (:func:`analyze_table`; checked, and
        unused, for a symbolic graph).

    Returns
    -------
    WrenchAnalysis or GenericAnalysis
        Of one pose (shape ``()``); a GenericAnalysis for a symbolic graph.

    Raises
    ------
    TwistGraphError
        If an actuated joint lies on no base-to-platform path, an invalid ``dof``, a ``dof`` other
        than the mobility, or more actuators than the mobility (both numbers named).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute, spherical
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [
    ...     ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...     ("arm", "E", revolute("R", [0, 0, 1], [1, 0, 0]))])
    >>> analysis = wrench_analysis(G)  # one actuator, mobility 2 (planar 2R): dof 2, under-actuated
    >>> limb = analysis.limbs[0]
    >>> analysis.dof, limb.passive_wrenches.order, S.is_zero_pitch(limb.actuation_wrench)
    (2, 5, True)
    """
    from .generic import generic_analysis, is_symbolic_graph

    rtol = checked_rtol(rtol)
    length_scale = checked_length_scale(length_scale, allow_none=True)
    if isinstance(graph, nx.MultiDiGraph) and is_symbolic_graph(graph, joint_key=joint_key):
        return generic_analysis(graph, dof=dof, joint_key=joint_key)  # a family: generic answers
    from .motion import settled_dof

    table = JointTable.from_graph(graph, joint_key=joint_key)
    one = JointTable(
        table.base,
        table.platform,
        table.specs,
        table.screws[None],
        table.dof,
        None if table.anchor is None else table.anchor[None],
        table.mobility,
    )
    stated = dof if dof is not None else table.dof
    analysis = analyze_table(one, dof=stated, rtol=rtol, length_scale=length_scale)[0]
    given = None if stated is None else analysis.dof
    nominal = settled_dof(graph, given, analysis, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
    if nominal != analysis.dof:  # derived: the mechanism's mobility, not the number of actuators
        analysis = analyze_table(one, dof=nominal, rtol=rtol, length_scale=length_scale)[0]
    object.__setattr__(analysis, "graph", graph)  # the caller's own graph object (cached view)
    return analysis
