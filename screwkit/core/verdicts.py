"""Labels over poses: regular, constraint, actuation or serial (limb) singularity (numeric).

From a :class:`~screwkit.core.wrench_systems.WrenchAnalysis` (paper 002 §4–5; Zlatanov, Bonev & Gosselin
2002 for the constraint/actuation distinction):

* **constraint singularity**: the mechanism's constraint wrench system ``W^c`` falls below its
  nominal order ``6 − dof``; the platform gains ``6 − dof − order(W^c)`` freedoms even with every
  actuator locked (paper 002 §5.3, condition 1);
* **actuation singularity**: ``W^c`` is nominal but the global system ``W^c + W^a`` is below 6
  (below ``6 − free`` for a task that leaves ``free`` freedoms undriven: 3 for a point task, whose
  rotations about the point stay free, :mod:`screwkit.robots.point_task`; a redundantly actuated
  mechanism with all its actuation wrenches, :mod:`screwkit.core.redundancy`);
  with the actuators locked the platform keeps an uncontrolled twist (paper 002 §5.3, condition 2);
* **serial (limb) singularity**: an actuated joint's twist lies in the span of the other twists of
  its limb, so its actuation wrench is reciprocal to it: the actuator cannot move the platform
  (Gosselin & Angeles' inverse type). In a compound leg whose actuators share a link, decided on
  the leg as a whole where the limb's own wrench fails: the actuator moves with the platform fixed
  (:func:`screwkit.core.wrench_systems.analyze_table`).

The *uncontrolled twists* are the platform twists reciprocal to every constraint and actuation
wrench: the motions left with all actuators locked (empty at a regular pose).

One pose and many go through the same kernels (:func:`screwkit.core.wrench_systems.analyze_table`):
:func:`~screwkit.core.singularity.classify` is a batch of one,
:func:`~screwkit.core.singularity.classify_poses` and :func:`~screwkit.core.singularity.classify_table` a
batch.

Closeness measures (all in [0, 1], unit-free, computed about the mechanism's own reference point
and length (:func:`~screwkit.algebra.reference_frame.mechanism_frame`), so they follow rigid motions and
changes of unit; 0 at the singularity; computed when first asked,
:attr:`~screwkit.core.wrench_systems.WrenchAnalysis.closeness`: the labels do not need them):

* ``constraint``: σ_c0 / σ_1 of orthonormal bases of the compound legs' constraint systems,
  stacked, with ``c0 = 6 − dof`` (about the reference point, moments over the length); a leg
  with parallel branches on its spine (the Veloce's and the H4's sub-platforms, the McGill SMG's
  parallelograms) weighed by how independent its branches' systems are
  (:mod:`screwkit.core._leg_weights`: unchanged while their span is well conditioned, falling to 0
  where the leg loses order; an orthonormal basis alone keeps unit rows up to that pose);
* ``actuation``: σ_6 / σ_1 of those bases stacked with the unit actuation wrenches (the wrench of
  a limb whose actuator shares a link with others, less its part in its compound leg's constraint
  system: otherwise the H4 near a vertical parallelogram plane would look near-singular,
  :func:`screwkit.core.wrench_systems.analyze_table`);
* ``serial``: the smallest normalised reciprocal product of an actuation wrench with its actuated
  twist (:func:`~screwkit.core.wrenches.normalized_reciprocal_product`; for lines, mutual moment over the
  length, which can exceed 1 for limbs far from the reference point).

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
>>> from screwkit.core.wrenches import wrench_analysis
>>> print(classify_analysis(wrench_analysis(G)))  # doctest: +ELLIPSIS
regular (dof 1): constraint order 5/5, global order 6/6
  closeness (0 at a singularity): constraint 1, actuation ...
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from ..algebra import screwvalue as S
from ..algebra.display import ScrewArray, html_section, html_table, number_text
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import ScrewkitTypeError
from .finite_mobility import MobilityReading, mobility_reading
from .wrench_systems import WrenchAnalysis

__all__ = ["LABELS", "SerialSingularity", "SingularityReport", "classify_analysis"]

Array = np.ndarray

#: The labels, and their bit in :attr:`SingularityReport.codes`: constraint 1, actuation 2, serial 4.
LABELS = ("constraint", "actuation", "serial")


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
    """The verdicts over a batch of poses (shape ``()`` for one pose), from a wrench analysis.

    Index it (``report[3]``) for one pose. ``labels`` is empty at a regular pose.

    Attributes
    ----------
    analysis : WrenchAnalysis
    """

    analysis: WrenchAnalysis = field(repr=False)

    # --- arrays over the batch -------------------------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """The batch shape."""
        return self.analysis.shape

    @property
    def single(self) -> bool:
        """True for one pose."""
        return self.analysis.single

    def __len__(self) -> int:
        return len(self.analysis)

    def __getitem__(self, index: Any) -> SingularityReport:
        return SingularityReport(self.analysis[index])

    @property
    def dof(self) -> int:
        """Nominal mobility."""
        return self.analysis.dof

    @cached_property
    def mobility(self) -> MobilityReading:
        """The instantaneous and finite mobility at this pose (one pose), at the analysis's ``rtol``
        and length scale (:func:`~screwkit.core.finite_mobility.mobility_reading`).

        Examples
        --------
        >>> from screwkit.core.singularity import classify
        >>> from screwkit.graphs.joints import revolute
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> flat = twist_graph("ground", "link", [  # sides 1, 2, 3: a triangle in line, rigid
        ...     ("ground", "link", revolute("A", [0, 0, 1], [0, 0, 0])),
        ...     ("link", "other", revolute("B", [0, 0, 1], [1, 0, 0])),
        ...     ("other", "ground", revolute("C", [0, 0, 1], [3, 0, 0]))])
        >>> reading = classify(flat, dof=0).mobility
        >>> reading.instantaneous, reading.finite
        (1, 0)
        """
        return mobility_reading(self.analysis.graph, rtol=self.analysis.rtol,
                                length_scale=float(self.analysis.length_scale))

    @property
    def nominal_constraint_order(self) -> int:
        """``6 − dof``."""
        return 6 - self.analysis.dof

    @property
    def constraint_order(self) -> Any:
        """Order of ``W^c`` (int, or an array over the batch)."""
        return self.analysis.constraint_order

    @property
    def global_order(self) -> Any:
        """Order of ``W^c + W^a``."""
        return self.analysis.global_order

    @property
    def nominal_global_order(self) -> int:
        """``6 − free``: 6, or 3 for a point task (its free rotations about the point are not driven;
        :attr:`JointTable.free <screwkit.graphs.jointtable.JointTable.free>`)."""
        return 6 - self.analysis.free

    @property
    def gained_dof(self) -> Any:
        """Freedoms the platform gains from the loss of constraints (``nominal − order(W^c)``, ≥ 0)."""
        return _same_kind(np.maximum(self.nominal_constraint_order - np.asarray(self.constraint_order), 0))

    @property
    def lost_dof(self) -> Any:
        """Freedoms the platform lacks here (``order(W^c) − nominal``, ≥ 0): a mechanism locked or
        overconstrained here; not a singularity label, but reported."""
        return _same_kind(np.maximum(np.asarray(self.constraint_order) - self.nominal_constraint_order, 0))

    @property
    def uncontrolled_dof(self) -> Any:
        """``6 − free − order(W^c + W^a)``: the freedoms left with all actuators locked (beyond a point
        task's free rotations)."""
        return _same_kind(self.nominal_global_order - np.asarray(self.global_order))

    @property
    def redundancy(self) -> Any:
        """The degree of actuation redundancy per pose: the actuated joints minus the freedoms they
        drive, ``n − (order(W^c + W^a) − order(W^c))`` (:mod:`screwkit.core.redundancy`): ``n − dof``
        at a regular pose, more at a singular one; 0 for a non-redundant mechanism at a regular pose.

        Examples
        --------
        >>> from screwkit.core.wrenches import wrench_analysis
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> pair = [prismatic(f"P{i}", [1, 0, 0], actuated=True) for i in (1, 2)]  # two on one slide
        >>> slide = twist_graph("B", "E", [("B", "E", joint) for joint in pair])
        >>> classify_analysis(wrench_analysis(slide)).redundancy
        1
        """
        driven = np.asarray(self.global_order) - np.asarray(self.constraint_order)
        return _same_kind(len(self.actuated_joints) - driven)

    @property
    def serial_flags(self) -> Array:
        """``(..., n_actuated)``: True where that limb is serially singular (joint order:
        :attr:`actuated_joints`)."""
        return self.analysis.serial

    @property
    def actuated_joints(self) -> tuple[str, ...]:
        """The actuated joints, sorted (the limbs' order)."""
        return self.analysis.topology.actuated

    @property
    def closeness(self) -> dict[str, Any]:
        """``{"constraint", "actuation", "serial"}`` (module docstring): floats or arrays."""
        return self.analysis.closeness

    @property
    def constraint(self) -> Any:
        """True where the constraint system is below its nominal order."""
        return _same_kind(np.asarray(self.constraint_order) < self.nominal_constraint_order)

    @property
    def actuation(self) -> Any:
        """True where the constraint system is nominal but the global system is below its nominal order."""
        below = np.asarray(self.global_order) < self.nominal_global_order
        return _same_kind(~np.asarray(self.constraint) & below)

    @property
    def actuation_assessed(self) -> bool:
        """False for a mechanism with no actuated joint: it is analysed for its mobility only (its
        legs' constraint systems, the platform's freedoms, constraint singularities); the actuation
        and serial labels are not assessed."""
        return bool(self.actuated_joints)

    @property
    def codes(self) -> Array:
        """An integer per pose: bit 1 constraint, 2 actuation, 4 serial (0 regular).

        A platform with fewer freedoms than nominal (``lost_dof > 0``, e.g. a stretched limb at the
        boundary of its workspace) is a serial singularity, Gosselin & Angeles' type 1 (the output
        loses a direction of motion), whether or not one limb's actuator is found idle."""
        constraint = np.asarray(self.constraint_order) < self.nominal_constraint_order
        if not self.actuation_assessed:
            return constraint * 1
        actuation = ~constraint & (np.asarray(self.global_order) < self.nominal_global_order)
        lost = np.asarray(self.constraint_order) > self.nominal_constraint_order
        serial = np.asarray(self.analysis.serial).any(axis=-1) | lost
        return constraint * 1 + actuation * 2 + serial * 4

    @property
    def labels(self) -> Any:
        """A tuple of labels for one pose; over a batch, an object array of such tuples."""
        codes = np.asarray(self.codes)
        tuples = [tuple(name for bit, name in enumerate(LABELS) if code >> bit & 1) for code in codes.ravel()]
        if self.single:
            return tuples[0]
        out = np.empty(len(tuples), dtype=object)
        out[:] = tuples
        return out.reshape(codes.shape)

    @property
    def is_singular(self) -> Any:
        """True where any label applies."""
        return _same_kind(np.asarray(self.codes) > 0)

    @property
    def verdict(self) -> Any:
        """``"regular"`` or the labels joined, e.g. ``"constraint singularity"`` (an array of such
        strings over a batch)."""
        names = [_verdict(code) for code in range(8)]
        if self.single:
            return names[int(self.codes)]
        return np.asarray(names, dtype=object)[np.asarray(self.codes)]

    # --- one pose --------------------------------------------------------------------------------
    def _require_single(self, what: str) -> None:
        if not self.single:
            raise ScrewkitTypeError(
                f"Expected one pose for `{what}`, got a batch of shape {self.shape}; index the report first."
            )

    @property
    def uncontrolled_twists(self) -> ScrewArray:
        """A readable basis ``(6 − order(W^c + W^a), 6)`` of the twists left with the actuators locked
        (user frame; one pose; for a point task its free rotations about the point too): an array
        that prints its rows as screws, rounding noise as 0."""
        self._require_single("uncontrolled_twists")
        system = self.analysis.uncontrolled_twists
        return ScrewArray(system.readable_basis() if system.order else np.zeros((0, 6)))

    @property
    def serial(self) -> tuple[SerialSingularity, ...]:
        """The serially singular limbs (one pose)."""
        self._require_single("serial")
        return tuple(
            SerialSingularity(limb.actuated_joint, limb.constraint_wrenches, limb.transmission)
            for limb in self.analysis.limbs
            if limb.actuation_wrench is None
        )

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready report of one pose.

        Returns
        -------
        dict
            ``verdict``, ``labels``, ``dof``, the orders and freedoms gained, lost and uncontrolled,
            the degree of actuation redundancy,
            the serial limbs and the closeness measures (JSON-ready).

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> from screwkit.core.wrenches import wrench_analysis
        >>> classify_analysis(wrench_analysis(G)).to_dict()["verdict"]
        'regular'
        """
        self._require_single("to_dict")
        return {
            "verdict": self.verdict,
            "labels": list(self.labels),
            "dof": self.dof,
            "actuation_assessed": self.actuation_assessed,
            "constraint_order": int(self.constraint_order),
            "nominal_constraint_order": self.nominal_constraint_order,
            "global_order": int(self.global_order),
            "nominal_global_order": self.nominal_global_order,
            "gained_dof": int(self.gained_dof),
            "lost_dof": int(self.lost_dof),
            "uncontrolled_dof": int(self.uncontrolled_dof),
            "redundancy": int(self.redundancy),
            "uncontrolled_twists": [S.Screw(t).to_dict() for t in self.uncontrolled_twists],
            "serial": [
                {
                    "actuated_joint": s.actuated_joint,
                    "transmission": s.transmission,
                    "limb_wrenches": s.limb_wrenches.to_dict(),
                }
                for s in self.serial
            ],
            "closeness": {k: float(v) for k, v in self.closeness.items()},
            "rtol": self.analysis.rtol,
            "length_scale": float(self.analysis.length_scale),
        }

    def __repr__(self) -> str:
        """One line: the verdict, the nominal mobility and the two orders against their nominal values
        (over a batch: its shape and the count of each verdict).

        Returns
        -------
        str

        Examples
        --------
        >>> from screwkit.robots.catalog import load_mechanism
        >>> load_mechanism("h4").at().singularities
        SingularityReport(shape=(1,): regular 1)
        >>> _[0]
        SingularityReport('regular', dof=4, constraint 2/2, global 6/6)
        """
        if not self.single:
            return f"SingularityReport(shape={self.shape}: {self._tally()})"
        return (
            f"SingularityReport({self.verdict!r}, dof={self.dof}, constraint {self.constraint_order}/"
            f"{self.nominal_constraint_order}, global {self.global_order}/{self.nominal_global_order})"
        )

    def _dof_text(self) -> str:
        free = self.analysis.free
        if not free:
            return f"dof {self.dof}"
        return f"dof {self.dof}: the task point's {self.dof - free} and {free} free rotations about it"

    def _tally(self) -> str:
        codes = np.asarray(self.codes).ravel()
        return ", ".join(f"{_verdict(c)} {int((codes == c).sum())}" for c in np.unique(codes))

    def _repr_html_(self) -> str:
        """Jupyter: the verdict, the orders, the uncontrolled twists and the closeness measures as
        tables (over a batch: the count of each verdict).

        Returns
        -------
        str
            HTML.

        Examples
        --------
        >>> from screwkit.robots.catalog import load_mechanism
        >>> load_mechanism("h4").at()[0].singularity._repr_html_()[:30]
        '<h4>singularity: regular</h4><'
        """
        if not self.single:
            codes = np.asarray(self.codes).ravel()
            rows = [(_verdict(c), int((codes == c).sum())) for c in np.unique(codes)]
            table = html_table(["verdict", "poses"], rows)
            return html_section(f"singularities over {codes.size} poses", table)
        orders = [
            ("nominal mobility (dof)", self.dof),
            ("constraint order", f"{self.constraint_order} / {self.nominal_constraint_order}"),
            ("global order", f"{self.global_order} / {self.nominal_global_order}"),
            (
                "freedoms gained / lost / uncontrolled",
                f"{self.gained_dof} / {self.lost_dof} / {self.uncontrolled_dof}",
            ),
        ]
        out = [html_table(["", ""], orders)]
        if len(self.uncontrolled_twists):
            twists = [(i + 1, str(S.Screw(t))) for i, t in enumerate(self.uncontrolled_twists)]
            table = html_table(["", "twist"], twists)
            out.append(html_section("uncontrolled twists (actuators locked)", table, level=5))
        out.extend(f"<p>serial singularity of the limb of {i.actuated_joint!r}</p>" for i in self.serial)
        measures = [(k, number_text(v, 3)) for k, v in self.closeness.items()]
        closeness = html_table(["measure", "value"], measures)
        out.append(html_section("closeness (0 at a singularity)", closeness, level=5))
        return html_section(f"singularity: {self.verdict}", "".join(out))

    def __str__(self) -> str:
        if not self.single:
            return f"{np.asarray(self.codes).size} poses ({self._dof_text()}): {self._tally()}"
        lines = [
            f"{self.verdict} ({self._dof_text()}): constraint order {self.constraint_order}/"
            f"{self.nominal_constraint_order}, global order {self.global_order}/{self.nominal_global_order}"
        ]
        if self.gained_dof:
            lines.append(f"  the platform gains {self.gained_dof} DOF (constraints lost)")
            extra = self.nominal_global_order - int(self.gained_dof) - int(self.global_order)
            if extra > 0 and self.actuation_assessed:
                # the label follows Zlatanov-Bonev-Gosselin (actuation needs a nominal W^c); say what
                # the actuation wrenches lose on top of the constraint singularity
                lines.append(
                    f"  the actuation wrenches lose {extra} more order(s) here: {extra} freedom(s) "
                    "uncontrolled with the actuators locked beyond those the constraints give up"
                )
        if not self.actuation_assessed:
            lines.append("  no actuated joint: mobility analysis only, actuation not assessed")
        elif len(self.actuated_joints) > self.dof:
            lines.append(
                f"  redundantly actuated: {len(self.actuated_joints)} actuated joints for {self.dof} "
                f"freedom(s); degree of redundancy {self.redundancy} here "
                f"({len(self.actuated_joints) - self.dof} at a regular pose)"
            )
        if self.lost_dof:
            lines.append(
                f"  the platform has {self.lost_dof} DOF fewer than nominal"
                + (
                    " (a serial singularity: a limb at its reach; or, if it holds at every configuration, "
                    "a nominal `dof` above the mechanism's mobility)"
                    if self.actuation_assessed
                    else ""
                )
            )
        if self.uncontrolled_dof and self.actuation_assessed:
            lines.append(f"  uncontrolled with actuators locked: {self.uncontrolled_dof} twist(s)")
            if not self.analysis.free:  # a point task's list holds its free rotations too
                lines.extend(f"    {S.Screw(t)}" for t in self.uncontrolled_twists)
        for item in self.serial:
            lines.append(f"  serial singularity of the limb of {item.actuated_joint!r}")
        measures = ", ".join(f"{k} {v:.3g}" for k, v in self.closeness.items())
        lines.append(f"  closeness (0 at a singularity): {measures}")
        return "\n".join(lines)


def _verdict(code: int) -> str:
    names = [name for bit, name in enumerate(LABELS) if code >> bit & 1]
    return " + ".join(names) + " singularity" if names else "regular"


def _same_kind(value: Array) -> Any:
    return value.item() if value.ndim == 0 else value


def classify_analysis(analysis: WrenchAnalysis) -> SingularityReport:
    """Label a wrench analysis (see the module docstring).

    Parameters
    ----------
    analysis : WrenchAnalysis
        Of one pose or a batch.

    Returns
    -------
    SingularityReport
        Of the analysis's shape.

    Raises
    ------
    ScrewkitTypeError
        If ``analysis`` is not a WrenchAnalysis.

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    >>> from screwkit.core.wrenches import wrench_analysis
    >>> classify_analysis(wrench_analysis(G)).labels
    ()
    """
    if not isinstance(analysis, WrenchAnalysis):
        raise ScrewkitTypeError(f"Expected `analysis` to be a WrenchAnalysis, got {type(analysis).__name__}.")
    return SingularityReport(analysis)
