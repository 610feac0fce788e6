"""Labels at a pose: regular, constraint, actuation or serial (limb) singularity (numeric).

From a :class:`~screwkit.wrenches.WrenchAnalysis` (paper 002 §4–5; Zlatanov, Bonev & Gosselin
2002 for the constraint/actuation distinction):

* **constraint singularity**: the mechanism's constraint wrench system ``W^c`` falls below its
  nominal order ``6 − dof``; the platform gains ``6 − dof − order(W^c)`` freedoms even with every
  actuator locked (paper 002 §5.3, condition 1);
* **actuation singularity**: ``W^c`` is nominal but the global system ``W^c + W^a`` is below 6;
  with the actuators locked the platform keeps an uncontrolled twist (paper 002 §5.3, condition 2);
* **serial (limb) singularity**: an actuated joint's twist lies in the span of the other twists of
  its limb, so its actuation wrench is reciprocal to it: the actuator cannot move the platform
  (Gosselin & Angeles' inverse type).

The *uncontrolled twists* are the platform twists reciprocal to every constraint and actuation
wrench: the motions left with all actuators locked (empty at a regular pose).

Closeness measures (all in [0, 1], unit-free, computed about the mechanism's own reference point
and length (:func:`~screwkit.twistgraph.graph_frame`), so they follow rigid motions and changes of
unit; 0 at the singularity):

* ``constraint``: σ_c0 / σ_1 of orthonormal bases of the compound legs' constraint systems,
  stacked, with ``c0 = 6 − dof`` (about the reference point, moments over the length);
* ``actuation``: σ_6 / σ_1 of those bases stacked with the unit actuation wrenches;
* ``serial``: the smallest normalised reciprocal product of an actuation wrench with its actuated
  twist (:func:`~screwkit.wrenches.normalized_reciprocal_product`; for lines, mutual moment over the
  length, which can exceed 1 for limbs far from the reference point).

Examples
--------
>>> from screwkit.joints import prismatic
>>> from screwkit.twistgraph import twist_graph
>>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
>>> print(classify(G))
regular (dof 1): constraint order 5/5, global order 6/6
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import networkx as nx
import numpy as np

from . import _backend as B
from . import screw as S
from .screwsystem import ScrewSystem
from .wrenches import WrenchAnalysis, wrench_analysis

__all__ = ["SerialSingularity", "SingularityReport", "classify", "classify_analysis"]

Array = np.ndarray


@dataclass(frozen=True, eq=False)
class SerialSingularity:
    """A limb whose actuator cannot move the platform.

    Attributes
    ----------
    actuated_joint : str
    limb_wrenches : ScrewSystem
        The wrenches the limb now transmits with its actuator free (its constraint system): the
        platform directions this limb can no longer drive.
    transmission : float
    """

    actuated_joint: str
    limb_wrenches: ScrewSystem
    transmission: float


@dataclass(frozen=True, eq=False)
class SingularityReport:
    """The verdict at one pose. ``labels`` is empty at a regular pose.

    Attributes
    ----------
    labels : tuple of str
        Any of ``"constraint"``, ``"actuation"``, ``"serial"``.
    dof : int
        Nominal mobility.
    constraint_order, nominal_constraint_order : int
    global_order : int
    gained_dof : int
        Freedoms the platform gains from the loss of constraints (``nominal − order(W^c)``, ≥ 0).
    lost_dof : int
        Freedoms the platform lacks at this pose (``order(W^c) − nominal``, ≥ 0): a mechanism
        locked or overconstrained here; not a singularity label, but reported.
    uncontrolled_dof : int
        ``6 − order(W^c + W^a)``: the freedoms left with all actuators locked.
    uncontrolled_twists : numpy.ndarray, shape (uncontrolled_dof, 6)
        A readable basis of those twists (user frame).
    serial : tuple of SerialSingularity
    closeness : dict
        ``{"constraint": float, "actuation": float, "serial": float}`` (module docstring).
    analysis : WrenchAnalysis
    """

    labels: tuple[str, ...]
    dof: int
    constraint_order: int
    nominal_constraint_order: int
    global_order: int
    gained_dof: int
    lost_dof: int
    uncontrolled_dof: int
    uncontrolled_twists: Array
    serial: tuple[SerialSingularity, ...]
    closeness: dict[str, float]
    analysis: WrenchAnalysis = field(repr=False)

    @property
    def is_singular(self) -> bool:
        """True when any label applies."""
        return bool(self.labels)

    @property
    def verdict(self) -> str:
        """``"regular"`` or the labels joined, e.g. ``"constraint singularity"``."""
        if not self.labels:
            return "regular"
        return " + ".join(self.labels) + " singularity"

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready report.

        Examples
        --------
        >>> from screwkit.joints import prismatic
        >>> from screwkit.twistgraph import twist_graph
        >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> classify(G).to_dict()["verdict"]
        'regular'
        """
        return {
            "verdict": self.verdict,
            "labels": list(self.labels),
            "dof": self.dof,
            "constraint_order": self.constraint_order,
            "nominal_constraint_order": self.nominal_constraint_order,
            "global_order": self.global_order,
            "gained_dof": self.gained_dof,
            "lost_dof": self.lost_dof,
            "uncontrolled_dof": self.uncontrolled_dof,
            "uncontrolled_twists": [S.Screw(t).to_dict() for t in self.uncontrolled_twists],
            "serial": [
                {
                    "actuated_joint": s.actuated_joint,
                    "transmission": s.transmission,
                    "limb_wrenches": s.limb_wrenches.to_dict(),
                }
                for s in self.serial
            ],
            "closeness": dict(self.closeness),
        }

    def __str__(self) -> str:
        lines = [
            f"{self.verdict} (dof {self.dof}): constraint order {self.constraint_order}/"
            f"{self.nominal_constraint_order}, global order {self.global_order}/6"
        ]
        if self.gained_dof:
            lines.append(f"  the platform gains {self.gained_dof} DOF (constraints lost)")
        if self.lost_dof:
            lines.append(f"  the platform has {self.lost_dof} DOF fewer than nominal (locked)")
        if self.uncontrolled_dof:
            lines.append(f"  uncontrolled with actuators locked: {self.uncontrolled_dof} twist(s)")
            lines.extend(f"    {S.Screw(t)}" for t in self.uncontrolled_twists)
        for item in self.serial:
            lines.append(f"  serial singularity of the limb of {item.actuated_joint!r}")
        if self.labels:
            measures = ", ".join(f"{k} {v:.3g}" for k, v in self.closeness.items())
            lines.append(f"  closeness: {measures}")
        return "\n".join(lines)


def _constraint_systems(analysis: WrenchAnalysis) -> list[ScrewSystem]:
    """The compound legs' constraint systems, or the mechanism's when it is not series-parallel."""
    return [leg.constraint_wrenches for leg in analysis.compound_legs] or [analysis.constraint_wrenches]


def _orthonormal(rows: Array, analysis: WrenchAnalysis, *, each: bool = False) -> Array:
    """Rows about the reference point, moments over the length, then an orthonormal basis of their
    span (or, with ``each``, each row normalised): a metric rigid motions and changes of unit keep,
    so the measures below depend on the subspaces only, not on the bases chosen for them."""
    rows = np.asarray(rows, dtype=float).reshape(-1, 6)
    if rows.shape[0] == 0:
        return rows
    scaled = S.transform(rows, np.eye(3), -analysis.reference_point)
    scaled[:, 3:] /= analysis.length_scale
    if each:
        return scaled / np.linalg.norm(scaled, axis=1, keepdims=True)
    return np.linalg.qr(scaled.T)[0].T


def _ratio(rows: Array, index: int) -> float:
    """σ_index / σ_1 of rows already about the reference point and scaled (0 if fewer rows)."""
    if index <= 0:
        return 1.0
    if rows.shape[0] < index:
        return 0.0
    values = np.linalg.svd(rows, compute_uv=False)
    return float(values[index - 1] / values[0]) if values[0] > 0 else 0.0


def classify_analysis(analysis: WrenchAnalysis) -> SingularityReport:
    """Label a wrench analysis (see the module docstring).

    Examples
    --------
    >>> from screwkit.joints import prismatic
    >>> from screwkit.twistgraph import twist_graph
    >>> from screwkit.wrenches import wrench_analysis
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    >>> classify_analysis(wrench_analysis(G)).labels
    ()
    """
    nominal = 6 - analysis.dof
    order = analysis.constraint_wrenches.order
    global_order = analysis.global_wrenches.order
    labels = []
    if order < nominal:
        labels.append("constraint")
    elif global_order < 6:
        labels.append("actuation")
    serial = tuple(
        SerialSingularity(limb.actuated_joint, limb.constraint_wrenches, limb.transmission)
        for limb in analysis.limbs
        if limb.actuation_wrench is None
    )
    if serial:
        labels.append("serial")
    uncontrolled = analysis.global_wrenches.reciprocal()
    generators = np.vstack(
        [_orthonormal(system.basis, analysis) for system in _constraint_systems(analysis)]
    ).reshape(-1, 6)
    stacked = np.vstack([generators, _orthonormal(analysis.actuation_wrenches, analysis, each=True)])
    transmissions = [limb.transmission for limb in analysis.limbs]
    closeness = {
        "constraint": _ratio(generators, nominal),
        "actuation": _ratio(stacked, 6),
        "serial": float(min(transmissions)) if transmissions else 1.0,
    }
    return SingularityReport(
        labels=tuple(labels),
        dof=analysis.dof,
        constraint_order=order,
        nominal_constraint_order=nominal,
        global_order=global_order,
        gained_dof=max(nominal - order, 0),
        lost_dof=max(order - nominal, 0),
        uncontrolled_dof=6 - global_order,
        uncontrolled_twists=uncontrolled.readable_basis() if uncontrolled.order else np.zeros((0, 6)),
        serial=serial,
        closeness=closeness,
        analysis=analysis,
    )


def classify(
    graph: nx.MultiDiGraph, *, dof: int | None = None, joint_key: str = "joint", rtol: float = B.DEFAULT_RTOL
) -> SingularityReport:
    """Analyse a twist graph's wrench systems at its configuration and label the pose.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
    dof : int, optional
        Nominal mobility (see :func:`~screwkit.wrenches.wrench_analysis`).
    joint_key : str
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (singular values about the mechanism's reference
        point, moments over its length).

    Returns
    -------
    SingularityReport

    Examples
    --------
    >>> from screwkit.joints import revolute
    >>> from screwkit.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0], actuated=True)),
    ...                            ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))], dof=1)
    >>> report = classify(G)  # two parallel hinges on different axes lock the platform
    >>> report.labels, report.constraint_order, report.lost_dof
    ((), 6, 1)
    """
    return classify_analysis(wrench_analysis(graph, dof=dof, joint_key=joint_key, rtol=rtol))
