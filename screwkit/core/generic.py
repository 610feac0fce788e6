"""Generic analysis of a symbolic twist graph: a whole family of mechanisms at once.

A twist graph whose joint screws hold sympy symbols (joint positions, axes, angles) stands for a
family. :func:`generic_analysis` gives its *generic* answers, those that hold for all values of the
symbols outside a proper algebraic subset: every limb's twist and constraint systems, the compound
legs' systems, the platform's twist system, its mobility and motion type (e.g. ``3T1R``), the
actuation wrenches and the order of the global wrench system. It is what
:func:`screwkit.core.wrenches.wrench_analysis` and :func:`screwkit.core.singularity.classify` return for a
symbolic graph.

It walks the same structure as the numeric core (:func:`screwkit.graphs.topology.topology`; paper 002
Eqs. 1–2): along a chain the twist systems add up and the wrench systems intersect; across
parallel branches the roles swap. The screws are held as sparse integer polynomials paired with
their exact values at one random integer point of the symbols
(:class:`screwkit.algebra.symbolic.GenericRows`);
every order and every choice of generators is decided on those values (Schwartz–Zippel,
:mod:`screwkit.algebra.symbolic`), and the bases are built symbolically from the chosen generators:
intersections are solved on the few unknowns of the smaller system (``W_b ∩ T_others^⊥`` for a
chain, ``T_b ∩ W_others^⊥`` across branches) by Cramer's rule, so the expressions stay small. Only
the returned bases become sympy expressions.

There is **no pose verdict**: a generic analysis says what the family does at almost every
configuration. Where it is singular is a condition on the symbols (the superbracket,
:mod:`screwkit.gca`), not a label. A limb or a mechanism that is singular for *every* value of the
symbols (an architecture singularity) shows as a generic order below the nominal one.

Examples
--------
>>> import sympy
>>> from screwkit.graphs.joints import prismatic, revolute
>>> from screwkit.graphs.twistgraph import twist_graph
>>> a = sympy.Symbol("a")
>>> G = twist_graph("B", "E", [
...     ("B", "arm", revolute("A", [0, 0, 1], [0, 0, 0], actuated=True)),
...     ("arm", "E", revolute("R", [0, 0, 1], [a, 0, 0]))], dof=2)
>>> result = generic_analysis(G)
>>> result.mobility, result.motion_type, result.constraint_wrenches.order
(2, '1T1R', 4)
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra import screwvalue as S
from ..algebra import symbolic as Y
from ..algebra.motion_type import motion_type
from ..algebra.screwsystem import ScrewSystem
from ..algebra.symbolic_bases import reciprocal_within
from ..exceptions import ScrewkitTypeError, TwistGraphError
from ..graphs.jointtable import JointSpec
from ..graphs.topology import Topology, topology
from ..graphs.twistgraph import check_twist_graph
from .mobility import resolve_dof

__all__ = ["GenericAnalysis", "GenericLeg", "GenericLimb", "generic_analysis", "is_symbolic_graph"]

Array = np.ndarray


def is_symbolic_graph(graph: nx.MultiDiGraph, *, joint_key: str = "joint") -> bool:
    """True when some joint of a twist graph holds a sympy expression in its screws.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph.
    joint_key : str, default "joint"
        The edge attribute holding each joint.

    Returns
    -------
    bool

    Examples
    --------
    >>> import sympy
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [sympy.Symbol("a"), 0, 0]))])
    >>> is_symbolic_graph(G)
    True
    """
    return any(B.is_symbolic(getattr(joint, "screws", None)) for _, _, joint in graph.edges(data=joint_key))


@dataclass(frozen=True, eq=False)
class GenericLimb:
    """One actuated joint's limb, generically.

    Attributes
    ----------
    actuated_joint : str
    joints : tuple of str
    twist_system, constraint_wrenches, passive_wrenches : ScrewSystem
        As in :class:`screwkit.core.wrench_systems.Limb`, symbolic.
    actuated_twist : numpy.ndarray, shape (6,)
    actuation_wrench : numpy.ndarray, shape (6,), or None
        A passive wrench not reciprocal to the actuated twist (a line where the passive system's
        basis holds one); None when the limb is serially singular for every value of the symbols.
    """

    actuated_joint: str
    joints: tuple[str, ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem
    passive_wrenches: ScrewSystem
    actuated_twist: Array
    actuation_wrench: Array | None


@dataclass(frozen=True, eq=False)
class GenericLeg:
    """A compound leg (a branch of the series-parallel root), generically.

    Attributes
    ----------
    joints, actuated : tuple of str
    twist_system, constraint_wrenches : ScrewSystem
    """

    joints: tuple[str, ...]
    actuated: tuple[str, ...]
    twist_system: ScrewSystem
    constraint_wrenches: ScrewSystem

    @property
    def name(self) -> str:
        """``"leg through A1, A4"``, as :class:`screwkit.core.wrench_systems.CompoundLeg`."""
        return "leg through " + ", ".join(self.actuated or sorted(self.joints)[:2])


@dataclass(frozen=True, eq=False)
class GenericAnalysis:
    """The generic answers for a symbolic twist graph (module docstring).

    Attributes
    ----------
    topology : Topology
    dof : int
        The nominal mobility (as given, or the number of actuated joints).
    symbols : tuple of sympy.Symbol
        The family's parameters, sorted by name.
    platform_twists, constraint_wrenches : ScrewSystem
        Symbolic; ``constraint_wrenches`` is the platform's ``W^c = T^⊥``.
    compound_legs : tuple of GenericLeg
    limbs : tuple of GenericLimb
    global_order : int
        Generic order of ``W^c + W^a`` (6 when the family is generically controllable).
    exact : bool
        True when every decision was made in exact rational arithmetic (else 60-digit floats).
    """

    topology: Topology = field(repr=False)
    dof: int
    symbols: tuple[Any, ...]
    platform_twists: ScrewSystem = field(repr=False)
    constraint_wrenches: ScrewSystem = field(repr=False)
    compound_legs: tuple[GenericLeg, ...] = field(repr=False)
    limbs: tuple[GenericLimb, ...] = field(repr=False)
    global_order: int
    exact: bool = True

    generic = True  #: always True: answers for generic values of the symbols, no pose verdict

    @property
    def mobility(self) -> int:
        """The platform's generic number of freedoms (the order of its twist system)."""
        return self.platform_twists.order

    @property
    def motion_type(self) -> str:
        """The platform's motion type, e.g. ``"3T1R"`` (:func:`screwkit.algebra.motion_type.motion_type`)."""
        return str(motion_type(self.platform_twists))

    @property
    def constraint_order(self) -> int:
        """Generic order of ``W^c``."""
        return self.constraint_wrenches.order

    @property
    def verdict(self) -> str:
        """What holds generically: ``"generic: regular"`` or the architecture singularity seen for
        every value of the symbols. Never a pose verdict."""
        labels = []
        if self.constraint_order < 6 - self.dof:
            labels.append("constraint")
        elif self.global_order < 6:
            labels.append("actuation")
        if any(limb.actuation_wrench is None for limb in self.limbs):
            labels.append("serial")
        if not labels:
            return "generic: regular"
        return "generic: " + " + ".join(labels) + " singularity for every value of the symbols"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (expressions as strings).

        Returns
        -------
        dict
            ``generic`` (True), ``symbols``, ``mobility``, ``motion_type``, ``verdict``, the generic
            systems and orders, the compound legs and limbs; expressions as strings.

        Examples
        --------
        >>> import sympy
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, sympy.Symbol("c"), 0], actuated=True))])
        >>> generic_analysis(G).to_dict()["motion_type"]
        '1T'
        """
        return {
            "generic": True,
            "note": "generic answers for all values of the symbols outside a proper algebraic subset; "
            "no pose verdict",
            "symbols": [str(s) for s in self.symbols],
            "exact": self.exact,
            "dof": self.dof,
            "mobility": self.mobility,
            "motion_type": self.motion_type,
            "verdict": self.verdict,
            "platform_twists": self.platform_twists.to_dict(),
            "constraint_wrenches": self.constraint_wrenches.to_dict(),
            "global_order": self.global_order,
            "compound_legs": [
                {
                    "leg": leg.name,
                    "motion_type": motion_type(leg.twist_system),
                    "constraint_wrenches": leg.constraint_wrenches.to_dict(),
                }
                for leg in self.compound_legs
            ],
            "limbs": [
                {
                    "actuated_joint": limb.actuated_joint,
                    "motion_type": motion_type(limb.twist_system),
                    "constraint_wrenches": limb.constraint_wrenches.to_dict(),
                    "actuation_wrench": None
                    if limb.actuation_wrench is None
                    else S.Screw(limb.actuation_wrench).to_dict(),
                }
                for limb in self.limbs
            ],
        }

    def __str__(self) -> str:
        names = ", ".join(map(str, self.symbols))
        lines = [
            f"generic analysis over the symbols {names} (holds for all values outside a proper "
            "algebraic subset; no pose verdict)",
            f"  mobility {self.mobility} ({self.motion_type}), nominal dof {self.dof}; {self.verdict}",
            f"  platform twists: {self.platform_twists}",
            f"  constraint wrenches: {self.constraint_wrenches}",
        ]
        for leg in self.compound_legs:
            lines.append(
                f"  {leg.name}: {motion_type(leg.twist_system)}; constraints {leg.constraint_wrenches}"
            )
        for limb in self.limbs:
            lines.append(
                f"  limb of {limb.actuated_joint}: {motion_type(limb.twist_system)}; "
                f"constraints {limb.constraint_wrenches}"
            )
        lines.append(f"  global wrench system: order {self.global_order}/6")
        return "\n".join(lines)

    def __repr__(self) -> str:
        return f"GenericAnalysis(mobility={self.mobility}, motion_type={self.motion_type!r})"


def _specs_and_screws(graph: nx.MultiDiGraph, joint_key: str) -> tuple[tuple[JointSpec, ...], Array]:
    """The graph's joints sorted by name (as the numeric core), and their screws stacked exactly."""
    joints = sorted(graph.edges(keys=True, data=joint_key), key=lambda e: e[2])
    specs = tuple(
        JointSpec(key, joint.type, u, v, joint.dof, bool(joint.actuated)) for u, v, key, joint in joints
    )
    blocks = [
        B.as_array(joint.screws, f"screws of {key!r}", (6,), symbolic=True) for _, _, key, joint in joints
    ]
    screws = (
        np.concatenate([b.reshape(-1, 6) for b in blocks], axis=0) if blocks else np.zeros((0, 6), object)
    )
    return specs, screws


class _GenericEvaluation:
    """Twist and wrench systems of a topology's nodes (independent rows,
    :class:`~screwkit.algebra.symbolic.GenericRows`)."""

    def __init__(self, top: Topology, screws: Y.GenericRows, point: Y.GenericPoint):
        self.top, self.screws, self.point = top, screws, point
        self._twists: dict[int, Y.GenericRows] = {}
        self._wrenches: dict[int, Y.GenericRows] = {}
        self._identity = screws.identity()
        self._none = screws.take([])

    def joint_rows(self, index: int) -> Y.GenericRows:
        start = self.top.columns[index]
        return self.screws.take(range(start, start + self.top.specs[index].dof))

    def stacked(self, parts: list[Y.GenericRows]) -> Y.GenericRows:
        return self._none.stack(*parts)

    def span(self, rows: Y.GenericRows) -> Y.GenericRows:
        return rows.take(rows.independent())

    def within(self, basis: Y.GenericRows, others: list[Y.GenericRows]) -> Y.GenericRows:
        return reciprocal_within(basis, self.stacked(others), self.point)

    def twists(self, index: int) -> Y.GenericRows:
        if index not in self._twists:
            node = self.top.nodes[index]
            if node.kind == "joint":
                assert node.joint is not None
                result = self.span(self.joint_rows(node.joint))
            elif node.kind == "series":
                result = self.span(self.stacked([self.twists(c) for c in node.children]))
            else:  # across branches: T_b ∩ (Σ W_others)^⊥ with b the smallest twist system
                smallest = min(node.children, key=lambda c: len(self.twists(c)))
                others = [self.wrenches(c) for c in node.children if c != smallest]
                result = self.within(self.twists(smallest), others)
            self._twists[index] = result
        return self._twists[index]

    def wrenches(self, index: int) -> Y.GenericRows:
        if index not in self._wrenches:
            node = self.top.nodes[index]
            if node.kind == "parallel":
                result = self.span(self.stacked([self.wrenches(c) for c in node.children]))
            elif node.kind == "joint":
                result = self.within(self._identity, [self.twists(index)])
            else:  # along a chain: W_b ∩ (Σ T_others)^⊥ with b the child of the largest twist system
                largest = max(node.children, key=lambda c: len(self.twists(c)))
                others = [self.twists(c) for c in node.children if c != largest]
                result = self.within(self.wrenches(largest), others)
            self._wrenches[index] = result
        return self._wrenches[index]

    def reciprocal_of_sum(self, nodes: tuple[int, ...], extra: list[Y.GenericRows]) -> Y.GenericRows:
        """``(Σ T_nodes + span(extra))^⊥`` as ``W_b ∩ (the rest)^⊥``."""
        if not nodes:
            return self.within(self._identity, extra)
        largest = max(nodes, key=lambda c: len(self.twists(c)))
        return self.within(self.wrenches(largest), [*(self.twists(c) for c in nodes if c != largest), *extra])


def generic_analysis(
    graph: nx.MultiDiGraph, *, dof: int | None = None, joint_key: str = "joint"
) -> GenericAnalysis:
    """The generic wrench analysis of a symbolic twist graph (see the module docstring).

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph whose screws may hold sympy expressions (numbers are made exact).
    dof : int, optional
        Nominal mobility; default: the graph's ``dof``, else the generic mobility, which a stated
        ``dof`` must equal (:func:`screwkit.core.mobility.resolve_dof`).
    joint_key : str

    Returns
    -------
    GenericAnalysis

    Raises
    ------
    ScrewkitTypeError
        If the graph does not reduce to series and parallel parts (loop closure over symbols is
        not implemented: substitute values and use the numeric core).
    TwistGraphError
        For a malformed graph or an invalid ``dof``.

    Examples
    --------
    >>> import sympy
    >>> from screwkit.graphs.joints import spherical
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> x = sympy.Symbol("x")
    >>> G = twist_graph("B", "E", [("B", "rod", spherical("S1", [0, 0, 0])),
    ...                            ("rod", "E", spherical("S2", [x, 0, 1]))])
    >>> generic_analysis(G, dof=5).constraint_wrenches.basis.tolist()  # the force along the rod
    [[x, 0, 1, 0, 0, 0]]
    """
    check_twist_graph(graph, joint_key=joint_key)
    specs, screws = _specs_and_screws(graph, joint_key)
    top = topology(graph.graph["base"], graph.graph["platform"], specs)
    if top.network:
        raise ScrewkitTypeError(
            "Expected a twist graph that reduces to series and parallel parts for a generic (symbolic) "
            "analysis, got one that needs loop closure; substitute values for the symbols and use the "
            "numeric core."
        )
    stated = dof if dof is not None else graph.graph.get("dof")
    if stated is not None and not B.is_dof(stated):
        raise TwistGraphError(f"Expected `dof` to be an integer in 0..6, got {stated!r}.")
    point = Y.generic_point(screws)
    rows = Y.GenericRows.from_exprs(screws, point)
    with rows.precision():
        return _analysis(top, stated, screws, _GenericEvaluation(top, rows, point))


def _analysis(top: Topology, stated: Any, screws: Array, core: _GenericEvaluation) -> GenericAnalysis:
    """The generic answers from the node systems (in the point's arithmetic context)."""
    assert top.root is not None
    platform = core.twists(top.root)
    # the nominal dof is the generic mobility, the actuators no more (screwkit.core.mobility.resolve_dof)
    nominal = resolve_dof(None if stated is None else int(stated), len(platform), top.actuated)
    constraint = core.wrenches(top.root)
    legs = tuple(
        GenericLeg(
            top.nodes[i].joints,
            tuple(sorted(j for j in top.nodes[i].joints if j in set(top.actuated))),
            _system(core.twists(i)),
            _system(core.wrenches(i)),
        )
        for i in top.legs
    )
    limbs, wrenches = [], []
    for plan in top.limbs:
        actuated = core.joint_rows(plan.index).take([0]).scaled(int(plan.sign))
        locked = core.span(core.stacked([core.twists(n) for n in plan.siblings]))
        passive = core.reciprocal_of_sum(plan.siblings, [])
        wrench = _actuation_wrench(passive, actuated)
        if wrench is not None:
            wrenches.append(wrench)
        limbs.append(
            GenericLimb(
                plan.actuated_joint,
                plan.joints,
                _system(core.span(locked.stack(actuated))),
                _system(core.reciprocal_of_sum(plan.siblings, [actuated])),
                _system(passive),
                plan.sign * screws[top.columns[plan.index]],
                None if wrench is None else wrench.exprs()[0],
            )
        )
    global_order = len(core.span(constraint.stack(*wrenches)))
    return GenericAnalysis(
        topology=top,
        dof=int(nominal),
        symbols=tuple(sorted(core.point.symbols, key=str)),
        platform_twists=_system(platform),
        constraint_wrenches=_system(constraint),
        compound_legs=legs,
        limbs=tuple(limbs),
        global_order=global_order,
        exact=core.screws.exact,
    )


def _system(rows: Y.GenericRows) -> ScrewSystem:
    return ScrewSystem.from_independent(rows.exprs())


def _actuation_wrench(passive: Y.GenericRows, actuated: Y.GenericRows) -> Y.GenericRows | None:
    """The first passive row not reciprocal to the actuated twist, lines first (decided on the
    values at the generic point by :func:`screwkit.algebra.symbolic.is_zero`, relative to the products of
    the rows' sizes: the reciprocal product ``w·t0 + w0·t`` of
    :func:`screwkit.algebra.screw.reciprocal_product`, and a line's ``w·w0 = 0``)."""
    twist = actuated.values[0]

    def size(row: list[Any]) -> Any:
        return max(abs(v) for v in row)

    def product(a: list[Any], b: list[Any]) -> Any:  # a·b0 + a0·b
        return sum(a[j] * b[j + 3] + a[j + 3] * b[j] for j in range(3))

    rows = passive.values
    productive = [i for i, r in enumerate(rows) if not Y.is_zero(product(r, twist), size(r) * size(twist))]
    lines = [i for i in productive if Y.is_zero(product(rows[i], rows[i]), size(rows[i]) ** 2)]
    for i in itertools.chain(lines, productive):
        return passive.take([i])
    return None
