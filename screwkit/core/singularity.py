"""Labels over poses: regular, constraint, actuation or serial (limb) singularity (numeric).

From a :class:`~screwkit.core.wrenches.WrenchAnalysis` (paper 002 §4–5; Zlatanov, Bonev & Gosselin
2002 for the constraint/actuation distinction):

* **constraint singularity**: the mechanism's constraint wrench system ``W^c`` falls below its
  nominal order ``6 − dof``; the platform gains ``6 − dof − order(W^c)`` freedoms even with every
  actuator locked (paper 002 §5.3, condition 1);
* **actuation singularity**: ``W^c`` is nominal but the global system ``W^c + W^a`` is below 6;
  with the actuators locked the platform keeps an uncontrolled twist (paper 002 §5.3, condition 2);
* **serial (limb) singularity**: an actuated joint's twist lies in the span of the other twists of
  its limb, so its actuation wrench is reciprocal to it: the actuator cannot move the platform
  (Gosselin & Angeles' inverse type). In a compound leg whose actuators share a link, decided on
  the leg as a whole where the limb's own wrench fails: the actuator moves with the platform fixed
  (:func:`screwkit.core.wrenches.analyze_table`).

The *uncontrolled twists* are the platform twists reciprocal to every constraint and actuation
wrench: the motions left with all actuators locked (empty at a regular pose).

One pose and many go through the same kernels (:func:`screwkit.core.wrenches.analyze_table`):
:func:`classify` is a batch of one, :func:`classify_poses` and :func:`classify_table` a batch.

Closeness measures (all in [0, 1], unit-free, computed about the mechanism's own reference point
and length (:func:`~screwkit.algebra.reference_frame.mechanism_frame`), so they follow rigid motions and
changes of unit; 0 at the singularity; computed when first asked,
:attr:`~screwkit.core.wrenches.WrenchAnalysis.closeness`: the labels do not need them):

* ``constraint``: σ_c0 / σ_1 of orthonormal bases of the compound legs' constraint systems,
  stacked, with ``c0 = 6 − dof`` (about the reference point, moments over the length);
* ``actuation``: σ_6 / σ_1 of those bases stacked with the unit actuation wrenches (the wrench of
  a limb whose actuator shares a link with others, less its part in its compound leg's constraint
  system: otherwise the H4 near a vertical parallelogram plane would look near-singular,
  :func:`screwkit.core.wrenches.analyze_table`);
* ``serial``: the smallest normalised reciprocal product of an actuation wrench with its actuated
  twist (:func:`~screwkit.core.wrenches.normalized_reciprocal_product`; for lines, mutual moment over the
  length, which can exceed 1 for limbs far from the reference point).

Examples
--------
>>> from screwkit.graphs.joints import prismatic
>>> from screwkit.graphs.twistgraph import twist_graph
>>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
>>> print(classify(G))  # doctest: +ELLIPSIS
regular (dof 1): constraint order 5/5, global order 6/6
  closeness (0 at a singularity): constraint 1, actuation ...
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..algebra import screwvalue as S
from ..algebra.screwsystem import ScrewSystem
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import check_twist_graph
from .wrenches import WrenchAnalysis, analyze_table, wrench_analysis

if TYPE_CHECKING:
    from .generic import GenericAnalysis

__all__ = [
    "LABELS",
    "SerialSingularity",
    "SingularityReport",
    "checked_screws",
    "classify",
    "classify_analysis",
    "classify_chunks",
    "classify_poses",
    "classify_table",
    "label_table",
]

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
        """``6 − order(W^c + W^a)``: the freedoms left with all actuators locked."""
        return _same_kind(6 - np.asarray(self.global_order))

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
        """True where the constraint system is nominal but the global system is below 6."""
        return _same_kind(~np.asarray(self.constraint) & (np.asarray(self.global_order) < 6))

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
        actuation = ~constraint & (np.asarray(self.global_order) < 6)
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
    def uncontrolled_twists(self) -> Array:
        """A readable basis ``(uncontrolled_dof, 6)`` of the twists left with the actuators locked
        (user frame; one pose)."""
        self._require_single("uncontrolled_twists")
        system = self.analysis.uncontrolled_twists
        return system.readable_basis() if system.order else np.zeros((0, 6))

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

        Examples
        --------
        >>> from screwkit.graphs.joints import prismatic
        >>> from screwkit.graphs.twistgraph import twist_graph
        >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
        >>> classify(G).to_dict()["verdict"]
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
            "gained_dof": int(self.gained_dof),
            "lost_dof": int(self.lost_dof),
            "uncontrolled_dof": int(self.uncontrolled_dof),
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
        if self.single:
            return f"SingularityReport({self.verdict!r})"
        return f"SingularityReport(shape={self.shape})"

    def __str__(self) -> str:
        if not self.single:
            codes = np.asarray(self.codes).ravel()
            counts = ", ".join(f"{_verdict(c)} {int((codes == c).sum())}" for c in np.unique(codes))
            return f"{codes.size} poses (dof {self.dof}): {counts}"
        lines = [
            f"{self.verdict} (dof {self.dof}): constraint order {self.constraint_order}/"
            f"{self.nominal_constraint_order}, global order {self.global_order}/6"
        ]
        if self.gained_dof:
            lines.append(f"  the platform gains {self.gained_dof} DOF (constraints lost)")
            extra = 6 - int(self.gained_dof) - int(self.global_order)
            if extra > 0 and self.actuation_assessed:
                # the label follows Zlatanov-Bonev-Gosselin (actuation needs a nominal W^c); say what
                # the actuation wrenches lose on top of the constraint singularity
                lines.append(
                    f"  the actuation wrenches lose {extra} more order(s) here: {extra} freedom(s) "
                    "uncontrolled with the actuators locked beyond those the constraints give up"
                )
        if not self.actuation_assessed:
            lines.append("  no actuated joint: mobility analysis only, actuation not assessed")
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

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    >>> classify_analysis(wrench_analysis(G)).labels
    ()
    """
    if not isinstance(analysis, WrenchAnalysis):
        raise ScrewkitTypeError(f"Expected `analysis` to be a WrenchAnalysis, got {type(analysis).__name__}.")
    return SingularityReport(analysis)


def classify(
    graph: nx.MultiDiGraph,
    *,
    dof: int | None = None,
    joint_key: str = "joint",
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> SingularityReport | GenericAnalysis:
    """Analyse a twist graph's wrench systems at its configuration and label the pose.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
    dof : int, optional
        Nominal mobility: the mechanism's mobility at generic configurations, derived when omitted;
        any other value is refused (:func:`~screwkit.core.wrenches.wrench_analysis`).
    joint_key : str
    rtol : float, default 1e-9
        Relative tolerance of every rank decision (:mod:`screwkit.core._frames`).
    length_scale : float, optional
        The characteristic length of the rank decisions, in the screws' unit; default: derived
        from the screws (:func:`~screwkit.core.wrenches.analyze_table`).

    Returns
    -------
    SingularityReport or GenericAnalysis
        Of one pose; for a graph whose screws hold sympy symbols, the family's generic answers
        (:func:`screwkit.core.generic.generic_analysis`: mobility, motion type, generic orders; no pose
        verdict).

    Examples
    --------
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> hinge = revolute("R", [0, 0, 1], [0, 0, 0], actuated=True)
    >>> report = classify(twist_graph("B", "E", [("B", "E", hinge)]))
    >>> report.labels, report.dof, report.constraint_order
    ((), 1, 5)
    >>> locked = twist_graph("B", "E", [("B", "E", hinge), ("B", "E", revolute("R2", [0, 0, 1], [1, 0, 0]))])
    >>> classify(locked, dof=1)  # two parallel hinges on different axes: a structure  # doctest: +ELLIPSIS
    Traceback (most recent call last):
    ...
    screwkit.exceptions.TwistGraphError: Expected `dof` to equal the mechanism's mobility, 0 (...), ...
    """
    analysis = wrench_analysis(graph, dof=dof, joint_key=joint_key, rtol=rtol, length_scale=length_scale)
    if not isinstance(analysis, WrenchAnalysis):
        return analysis  # a symbolic graph: generic answers, no pose verdict
    return SingularityReport(analysis)


def classify_table(
    table: JointTable,
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    chunk: int = 1024,
) -> SingularityReport:
    """Label every configuration of a joint table, in chunks of the batch (bounded memory).

    Parameters
    ----------
    table : JointTable
    dof : int, optional
        Nominal mobility; default: the table's ``dof``, else derived. It must be the mechanism's
        mobility at generic configurations (reached from the first configuration), with at most
        that many actuators (:func:`screwkit.core.motion.settled_dof`; no extra cost when every pose is
        regular with one actuator per freedom).
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrenches.analyze_table` (default: derived per configuration).
    chunk : int, default 1024
        Configurations analysed at once.

    Returns
    -------
    SingularityReport

    Raises
    ------
    TwistGraphError
        A ``dof`` other than the mobility, or more actuators than it (both numbers named).

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointTable
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]] * 5, True)])
    >>> classify_table(table, chunk=2).verdict.tolist()
    ['regular', 'regular', 'regular', 'regular', 'regular']
    """
    from .motion import settled_dof

    report = label_table(table, dof=dof, rtol=rtol, length_scale=length_scale, chunk=chunk)
    stated = dof if dof is not None else table.dof
    if table.screws.size == 0:
        return report
    first = table.graph((0,) * len(table.batch_shape))
    nominal = settled_dof(
        first, None if stated is None else report.dof, report.analysis, rtol=rtol, length_scale=length_scale
    )
    if nominal == report.dof:
        return report
    return label_table(table, dof=nominal, rtol=rtol, length_scale=length_scale, chunk=chunk)


def label_table(
    table: JointTable,
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
    chunk: int = 1024,
) -> SingularityReport:
    """:func:`classify_table` with ``dof`` taken as given (default: the table's, else the number of
    actuators), unchecked: for tables whose ``dof`` is known, a catalog family's.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointTable
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]] * 3, True)])
    >>> label_table(table, chunk=2).dof
    1
    """
    if not isinstance(table, JointTable):
        raise ScrewkitTypeError(f"Expected `table` to be a JointTable, got {type(table).__name__}.")
    if isinstance(chunk, bool) or not isinstance(chunk, int | np.integer) or chunk < 1:
        raise ScrewkitValueError(f"Expected `chunk` to be a positive integer, got {chunk!r}.")
    shape = table.batch_shape
    if not shape:
        raise ScrewkitValueError("Expected a table with a batch axis, got one configuration; use classify().")
    flat = table.screws.reshape(-1, *table.screws.shape[-2:])
    anchor = None if table.anchor is None else table.anchor.reshape(-1, 3)
    pieces = (
        JointTable(
            table.base,
            table.platform,
            table.specs,
            flat[start : start + chunk],
            table.dof,
            None if anchor is None else anchor[start : start + chunk],
            table.mobility,
        )
        for start in range(0, max(len(flat), 1), chunk)
    )
    return classify_chunks(pieces, table, shape, dof=dof, rtol=rtol, length_scale=length_scale)


def classify_chunks(
    tables: Iterable[JointTable],
    table_source: JointTable | Callable[[], JointTable],
    shape: tuple[int, ...],
    *,
    dof: int | None = None,
    rtol: float = B.DEFAULT_RTOL,
    length_scale: float | None = None,
) -> SingularityReport:
    """Label a flattened batch given chunk by chunk (the tables in order, one batch axis each).

    Each chunk goes through :func:`~screwkit.core.wrenches.analyze_table` without its per-pose views,
    and its results are copied into arrays allocated for the whole batch once the first chunk
    gives their shapes, so no chunk outlives its turn and the results are never concatenated.

    Parameters
    ----------
    tables : iterable of JointTable
        The chunks, with ``prod(shape)`` configurations in all.
    table_source : JointTable or callable
        The whole batch's table, or a function returning it (asked only by per-pose views).
    shape : tuple of int
        The batch shape of the result.
    dof : int, optional
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrenches.analyze_table`.

    Examples
    --------
    >>> from screwkit.graphs.jointtable import JointTable
    >>> table = JointTable.from_rows("B", "E", [("B", "E", "P", "P", [[[0, 0, 0, 1.0, 0, 0]]] * 4, True)])
    >>> classify_chunks([table[:3], table[3:]], table, (2, 2)).global_order
    array([[6, 6],
           [6, 6]])
    """
    total = int(np.prod(shape))
    out: dict[str, Any] = {}
    filled, first = 0, None
    for piece in tables:
        part = analyze_table(piece, dof=dof, rtol=rtol, length_scale=length_scale, views=False)
        arrays = _batch_arrays(part)
        if first is None:  # the template of the result: the first chunk's fields less its arrays and table
            blank: dict[str, Any] = {
                **dict.fromkeys(_BATCH_FIELDS),
                "frames": dict.fromkeys(part.frames),
                "closeness_factors": dict.fromkeys(part.closeness_factors),
            }
            first = replace(part, table_source=table_source, **blank)
            out = {key: np.empty((total, *value.shape[1:]), value.dtype) for key, value in arrays.items()}
            del out["branch_rows"]  # stored only once a chunk's differ from its actuation rows
        if "branch_rows" not in out and arrays["branch_rows"] is not arrays["actuation_rows"]:
            out["branch_rows"] = out["actuation_rows"].copy()  # the chunks before: the same rows
        for key, value in arrays.items():
            if key in out:
                out[key][filled : filled + len(value)] = value
        filled += len(part)
        del piece, part, arrays  # not alive while the next chunk is computed
    if first is None or filled != total:
        raise ScrewkitValueError(f"Expected chunks of {total} configurations in all, got {filled}.")
    out.setdefault("branch_rows", out["actuation_rows"])  # every chunk's the same: one array
    whole = {key: value.reshape(*shape, *value.shape[1:]) for key, value in out.items()}
    return SingularityReport(
        replace(
            first,
            table_source=table_source,
            **{key: whole[key] for key in _BATCH_FIELDS},
            frames={key: (whole[f"frame:{key}"], whole[f"order:{key}"]) for key in first.frames},
            closeness_factors={key: whole[f"closeness:{key}"] for key in first.closeness_factors},
        )
    )


#: The per-pose array fields of a :class:`~screwkit.core.wrenches.WrenchAnalysis`.
_BATCH_FIELDS = (
    "reference_point",
    "length_scale",
    "platform_order",
    "constraint_order",
    "global_order",
    "serial",
    "transmissions",
    "actuation_rows",
    "actuated_twists",
    "branch_rows",
)


def _batch_arrays(analysis: WrenchAnalysis) -> dict[str, Array]:
    """Every per-pose array of a batch analysis, by a flat name."""
    arrays = {key: np.asarray(getattr(analysis, key)) for key in _BATCH_FIELDS}
    for key, (rows, order) in analysis.frames.items():
        arrays[f"frame:{key}"], arrays[f"order:{key}"] = rows, np.asarray(order)
    arrays.update({f"closeness:{key}": value for key, value in analysis.closeness_factors.items()})
    return arrays


def checked_screws(
    graph: nx.MultiDiGraph, screws: Mapping[str, Any]
) -> tuple[dict[str, Array], tuple[int, ...]]:
    """Validate batched joint screws against a template graph: ``{name: (..., dof, 6)}``, batch shape.

    Examples
    --------
    >>> from screwkit.graphs.joints import prismatic
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", prismatic("P", [1, 0, 0], actuated=True))])
    >>> checked_screws(G, {"P": np.zeros((3, 1, 6))})[1]
    (3,)
    """
    names = {key: joint for _, _, key, joint in graph.edges(keys=True, data="joint")}
    if not isinstance(screws, Mapping):
        raise ScrewkitTypeError(
            f"Expected `screws` to map joint names to arrays, got {type(screws).__name__}."
        )
    missing, unknown = set(names) - set(screws), set(screws) - set(names)
    if missing or unknown:
        raise ScrewkitValueError(
            f"Expected `screws` for exactly the graph's joints, got missing {sorted(missing)} and unknown "
            f"{sorted(unknown, key=str)}."
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
    length_scale: float | None = None,
) -> SingularityReport:
    """Label a batch of poses of one mechanism given as a template graph and batched screws.

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        A twist graph of the mechanism (any pose): its topology, names and actuated flags.
    screws : mapping of joint name to array_like, shape (..., dof_j, 6)
        The joints' screws over the batch.
    dof : int, optional
        Nominal mobility; default: the graph's ``dof``, else derived; checked as in
        :func:`classify_table`.
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrenches.analyze_table`.

    Returns
    -------
    SingularityReport
        Over the batch (:func:`classify_table`).

    Raises
    ------
    ScrewkitValueError
        If the screws do not match the graph's joints or their shapes disagree.

    Examples
    --------
    >>> import numpy as np
    >>> from screwkit.graphs.joints import revolute
    >>> from screwkit.graphs.twistgraph import twist_graph
    >>> G = twist_graph("B", "E", [("B", "E", revolute("R", [0, 0, 1], [0, 0, 0], actuated=True))])
    >>> report = classify_poses(G, {"R": np.array([[[0, 0, 1, 0, 0, 0.0]], [[0, 0, 1, 1, 0, 0.0]]])})
    >>> report.constraint_order, report.global_order
    (array([5, 5]), array([6, 6]))
    """
    check_twist_graph(graph)
    arrays, batch = checked_screws(graph, screws)
    template = JointTable.from_graph(graph)
    stacked = np.concatenate([arrays[spec.name] for spec in template.specs], axis=-2)
    anchor = None if template.anchor is None else np.broadcast_to(template.anchor, (*batch, 3))
    table = JointTable(
        template.base, template.platform, template.specs, stacked, template.dof, anchor, template.mobility
    )
    return classify_table(table, dof=dof, rtol=rtol, length_scale=length_scale)
