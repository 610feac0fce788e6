"""Constraint and actuation wrench systems of a parallel mechanism: the one batched core.

For a mechanism's joint table over a batch of configurations (a single twist graph is a batch of
one, :func:`screwkit.core.wrenches.wrench_analysis`), with the structure analysed once
(:mod:`screwkit.graphs.topology`):

* the **platform's twist system** by series-parallel reduction (paper 002 Eqs. 1–2: the sum of
  twist systems along a chain; across parallel branches their constraint systems add up, the
  dual of the intersection), or by loop closure when the graph does not reduce;
* each **limb** (an actuated joint with every base-to-platform path through it, paper 002
  §4.3): its twist system with the actuator locked (the *passive* wrenches are its reciprocal),
  with it free (the limb's constraint wrenches are its reciprocal), and its **actuation wrench**:
  the passive wrench most reciprocal-productive with the actuated twist. In the scaled metric
  (:mod:`screwkit.core.frames`) that is ``SWAP·t⊥`` with ``t⊥`` the actuated twist's component
  orthogonal to the locked twist system, defined up to the limb's constraint wrenches and made a
  line where adding one of them can (the representative drawn in diagrams). The actuator
  cannot move the platform (a *serial singularity* of the limb) when ``t⊥`` vanishes. Where
  actuators share a link (the H4's nacelle) and a limb's own wrench fails, its compound leg is
  analysed as a whole (:func:`screwkit.core._compound_legs.compound_legs`);
* each **compound leg** (a branch of the root of the series-parallel tree, such as the H4's
  ``L_I = l12 − R_I``) has its own constraint system; they add up to the mechanism's
  ``W^c`` (paper 002 Eq. 3);
* the **global wrench system** ``W^c + W^a`` (paper 002 Eq. 4): a 6-system at a regular pose.

Every decision is one rank rule (:mod:`screwkit.core.frames`), made about the reference point and
length of :func:`screwkit.algebra.reference_frame.mechanism_frame` so that it follows rigid motions and
changes of unit; results are reported in the user's frame. The pass itself is
:mod:`screwkit.core._wrench_pass`; this module holds its result, :class:`WrenchAnalysis`, with the
per-pose views :class:`Limb` and :class:`CompoundLeg`.

Examples
--------
>>> from screwkit.graphs.jointtable import JointTable
>>> slider = ("ground", "slider", "P1", "P", [[[0, 0, 0, 1.0, 0, 0]]], True)
>>> analysis = analyze_table(JointTable.from_rows("ground", "slider", [slider]), dof=1)[0]
>>> analysis.constraint_wrenches.order, analysis.global_wrenches.order
(5, 6)
"""

from __future__ import annotations

import functools
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field, replace
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra.checks import checked_rtol
from ..algebra.reference_frame import unit_scaled
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import ScrewkitTypeError
from ..graphs.jointtable import JointTable
from ..graphs.reduction import SeriesParallelNode
from ..graphs.topology import Topology
from . import _closing as CK
from . import frames as F
from ._program import Evaluation, Frame
from ._wrench_pass import scalar, wrench_pass

__all__ = ["CompoundLeg", "Limb", "WrenchAnalysis", "analyze_table"]

Array = np.ndarray


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
        outside ``passive_wrenches`` and have a pitch; :func:`screwkit.core._compound_legs.compound_legs`).
    actuated_twist : numpy.ndarray, shape (6,)
    transmission : float
        :func:`~screwkit.core.wrenches.normalized_reciprocal_product` of the actuation wrench and the
        actuated twist (0 at
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
    free : int
        Platform freedoms no actuator is meant to drive (:attr:`JointTable.free
        <screwkit.graphs.jointtable.JointTable.free>`: 3 for a point task); the global system's
        nominal order is ``6 − free``.
    closeness_factors : dict of str to numpy.ndarray, shape (..., 21)
        ``"constraint"``, ``"actuation"``: triangular factors (:func:`screwkit.core._closing.triangular`,
        :func:`~screwkit.core._closing.packed`) with the singular values of the matrices the closeness
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
    free: int = 0

    @functools.cached_property
    def closeness(self) -> dict[str, Any]:
        """The closeness measures (:mod:`screwkit.core.singularity`), computed on first use: the
        labels need only orders and serial flags, so a batch pays for the two 6×6 SVDs per pose
        only when its closeness is asked. ``constraint`` is ``σ_(6 − dof) / σ_1`` and ``actuation``
        ``σ_(6 − free) / σ_1`` (:attr:`free`) of :attr:`closeness_factors` (six rows with the
        singular values of the stacked legs' constraint wrenches, and of those stacked with the
        actuation wrenches apart from their legs; :func:`analyze_table`), ``serial`` the smallest
        transmission."""
        factors, transmissions = self.closeness_factors, self.transmissions
        values = {
            "constraint": _singular_ratios(factors["constraint"], 6 - self.dof),
            "actuation": _singular_ratios(factors["actuation"], 6 - self.free),
            "serial": np.min(transmissions, axis=-1) if transmissions.shape[-1] else np.ones(self.shape),
        }
        return {k: scalar(v) for k, v in values.items()}

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
            length_scale=scalar(pick(np.asarray(self.length_scale))),
            platform_order=scalar(pick(self.platform_order)),
            constraint_order=scalar(pick(self.constraint_order)),
            global_order=scalar(pick(self.global_order)),
            serial=pick(self.serial),
            transmissions=pick(self.transmissions),
            actuation_rows=pick(self.actuation_rows),
            actuated_twists=pick(self.actuated_twists),
            branch_rows=pick(self.branch_rows),
            frames={k: (rows[index], scalar(order[index])) for k, (rows, order) in self.frames.items()},
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

        Returns
        -------
        numpy.ndarray, shape (k, 6)
            Each compound leg's constraint wrenches (readable basis), legs in order.
        """
        legs = self.compound_legs
        if not legs:
            return np.asarray(self.constraint_wrenches.basis, dtype=float)
        rows = [leg.constraint_wrenches.readable_basis() for leg in legs]
        return np.concatenate(rows).reshape(-1, 6)

    @functools.cached_property
    def tree(self) -> SeriesParallelNode | None:
        """The topology's series-parallel tree with each node's twist system, oriented from the base
        (:meth:`~screwkit.graphs.reduction.SeriesParallelNode.from_topology`; None for a network).

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
            core = Evaluation(self.topology, scaled, self.rtol, requests)
            frames = [(rows[0], order[0]) for rows, order in map(core.frame, requests)]
        systems = [
            ScrewSystem.from_independent(
                F.from_scaled(rows[: int(order)], self.reference_point, np.asarray(self.length_scale)),
                rtol=self.rtol,
                length_scale=float(self.length_scale),
            )
            for rows, order in frames
        ]
        return SeriesParallelNode.from_topology(self.topology, systems)


#: Poses whose closeness SVDs run at once (:func:`_singular_ratios`): bounded memory over any batch.
CLOSENESS_CHUNK = 4096


def _singular_ratios(packed: Array, index: int) -> Array:
    """:func:`screwkit.core._closing.singular_ratio` of :func:`~screwkit.core._closing.packed` triangles
    ``(..., 21)``, :data:`CLOSENESS_CHUNK` poses at a time (each pose's SVD on its own: the same
    values whatever the chunk)."""
    flat = packed.reshape(-1, packed.shape[-1])
    out = np.empty(len(flat))
    for start in range(0, len(flat), CLOSENESS_CHUNK):
        out[start : start + CLOSENESS_CHUNK] = CK.singular_ratio(
            CK.unpacked(flat[start : start + CLOSENESS_CHUNK]), index
        )
    return out.reshape(packed.shape[:-1])


def _indexed_table(analysis: WrenchAnalysis, index: Any) -> JointTable:
    """``analysis.table[index]`` (the table source of an indexed analysis that kept no table)."""
    return analysis.table[index]


def _lengths(analysis: WrenchAnalysis) -> Array:
    return np.asarray(analysis.length_scale, dtype=float)[None]


def analyze_table(
    table: JointTable,
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    views: bool = True,
    kept: Callable[[Topology], Iterable[str]] | None = None,
) -> WrenchAnalysis:
    """The wrench systems of a mechanism over a batch of configurations (the one core).

    Parameters
    ----------
    table : JointTable
        The joints and their screws over the batch (e.g. a family's ``joints(config)``).
    dof : int, optional
        Nominal mobility; default: the table's ``dof``, else the number of actuated joints.
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (:mod:`screwkit.core.frames`).
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
    kept : callable, optional
        With ``views=False``: ``kept(topology)`` (the :class:`~screwkit.graphs.topology.Topology` the
        pass runs on) names per-pose frames to keep besides, by their key in
        :attr:`WrenchAnalysis.frames`: ``"constraint"``, ``"leg{k}:W"``, ``"node{i}"`` (a
        series-parallel tree's node twists), each the same bits as with the views, at the cost of
        those frames only.

    Returns
    -------
    WrenchAnalysis

    Raises
    ------
    TwistGraphError
        If an actuated joint lies on no base-to-platform path, or ``dof`` is invalid.
    ScrewkitValueError
        If ``kept`` names a frame the topology does not have.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointTable
    >>> line = [0, 0, 1.0, 0, 0, 0]
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "R", "R", [[line]] * 3, True)])
    >>> analyze_table(table).constraint_order
    array([5, 5, 5])
    >>> sorted(analyze_table(table, views=False, kept=lambda top: ["constraint"]).frames)
    ['constraint', 'limb0:passive', 'platform']
    """
    if not isinstance(table, JointTable):
        raise ScrewkitTypeError(f"Expected `table` to be a JointTable, got {type(table).__name__}.")
    rtol = checked_rtol(rtol)
    if kept is not None and not callable(kept):
        raise ScrewkitTypeError(f"Expected `kept` to be callable, got {type(kept).__name__}.")
    fields = wrench_pass(table, dof=dof, rtol=rtol, length_scale=length_scale, views=views, kept=kept)
    return WrenchAnalysis(**fields)
