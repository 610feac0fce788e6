"""Label twist graphs and joint tables: regular, or which singularity (numeric; the entry points).

:func:`classify` labels one twist graph at its pose (or gives a family's generic answers, as
:func:`~screwkit.core.wrenches.wrench_analysis`); :func:`classify_table` and :func:`classify_poses`
label a batch, with the mechanism's mobility settled (:func:`screwkit.core.mobility.settled_dof`);
:func:`label_table` and :func:`classify_chunks` take the nominal mobility as given. Every pose goes
through the same kernels (:func:`screwkit.core.wrench_systems.analyze_table`: a single pose is a
batch of one), and the verdicts, their labels and closeness measures are
:class:`~screwkit.core.verdicts.SingularityReport`'s (:mod:`screwkit.core.verdicts`).

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
from dataclasses import replace
from typing import Any

import networkx as nx
import numpy as np

from ..algebra import backend as B
from ..exceptions import ScrewkitTypeError, ScrewkitValueError
from ..graphs.jointtable import JointTable
from ..graphs.twistgraph import check_twist_graph
from .generic import GenericAnalysis
from .mobility import settled_dof
from .verdicts import SingularityReport
from .wrench_systems import WrenchAnalysis, analyze_table
from .wrenches import wrench_analysis

__all__ = [
    "checked_screws",
    "classify",
    "classify_chunks",
    "classify_poses",
    "classify_table",
    "label_table",
]

Array = np.ndarray


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
        Relative tolerance of every rank decision (:mod:`screwkit.core.frames`).
    length_scale : float, optional
        The characteristic length of the rank decisions, in the screws' unit; default: derived
        from the screws (:func:`~screwkit.core.wrench_systems.analyze_table`).

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
        that many actuators (:func:`screwkit.core.mobility.settled_dof`; no extra cost when every pose is
        regular with one actuator per freedom).
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table` (default: derived per configuration).
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

    Parameters
    ----------
    table : JointTable
        With a batch axis.
    dof : int, optional
        The nominal mobility, taken as given (default: the table's, else the number of actuators).
    rtol : float, default 1e-9
    length_scale : float, optional
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.
    chunk : int, default 1024
        Configurations analysed at once.

    Returns
    -------
    SingularityReport
        Over the table's batch.

    Raises
    ------
    ScrewkitTypeError
        If ``table`` is not a JointTable.
    ScrewkitValueError
        If ``chunk`` is not a positive integer, or the table has no batch axis.

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
            table.free,
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

    Each chunk goes through :func:`~screwkit.core.wrench_systems.analyze_table` without its per-pose views,
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
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

    Returns
    -------
    SingularityReport
        Over ``shape``; its analysis keeps the arrays of the whole batch and ``table_source``.

    Raises
    ------
    ScrewkitValueError
        If the chunks hold other than ``prod(shape)`` configurations in all.

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


#: The per-pose array fields of a :class:`~screwkit.core.wrench_systems.WrenchAnalysis`.
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

    Parameters
    ----------
    graph : networkx.MultiDiGraph
        The template twist graph (its joints' names and numbers of screws).
    screws : mapping of joint name to array_like, shape (..., dof_j, 6)
        Every joint's screws over one batch shape.

    Returns
    -------
    arrays : dict of str to numpy.ndarray
        The screws as float arrays, by joint name (sorted).
    batch : tuple of int
        Their common batch shape.

    Raises
    ------
    ScrewkitTypeError
        If ``screws`` is not a mapping.
    ScrewkitValueError
        If the joints differ from the graph's, or a shape disagrees (the odd one named).

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
        As in :func:`~screwkit.core.wrench_systems.analyze_table`.

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
